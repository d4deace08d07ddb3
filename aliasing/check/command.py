"""The ``aliasing check`` subcommand: the per-cascade report of an engine's setup.

::

    aliasing check --engine ENGINE[@RELEASE] [--settings FILE] [--set KEY=VALUE]... \\
        --camera near=N,far=F,fov=DEG,aspect=A,height=PX --sun ELEV[..ELEV][@AZ] \\
        [--receivers SLOPES] [--samples N] [--walk STEP] [--seen] [--format table|csv|json]

Bad input (an unknown engine, release or setting, a malformed settings file, a value the
engine does not accept, a camera or sun typo) is one line on stderr and exit status 2
(:func:`aliasing.cli.main`), as is a field of view without a unit that reads as radians (at or
below π: written ``fov=0.8rad`` or ``fov=45.84``).
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from .. import _table as _tables
from .. import setups
from . import ERROR_UNIT, ERROR_WORDS, MAX_ANGLE, check, header, units


def _slopes(text: str | None) -> list[float] | None:
    if text is None:
        return None
    out = []
    for part in filter(None, (p.strip() for p in text.split(","))):
        try:
            out.append(float(part))
        except ValueError:
            raise ValueError(f"--receivers must be slopes in degrees, comma-separated (0: the ground), got {text!r}") from None
    if not out:
        raise ValueError(f"--receivers must name at least one slope in [0, 90) degrees, got {text!r}")
    return out


def run(args: argparse.Namespace):
    """The :class:`aliasing.check.Report` of the parsed options."""
    setup = setups.from_args(args)
    return check(setup, receivers=_slopes(args.receivers), scene=args.scene, eye=args.eye, target=args.target, pixels=args.pixels,
                 walk=args.walk, samples=args.samples, wrong=bool(getattr(args, "seen", False)))


def _run(args: argparse.Namespace) -> int:
    report = run(args)
    text = {"json": report.to_json, "csv": report.to_csv}.get(args.format, report.text)()
    sys.stdout.write(text)
    return 0


BIAS_COLUMNS = ("cascade", "near", "far", "texel_s", "texel_t", "acne", "gap_px", "footprint_px", "seam_step")


def run_bias(args: argparse.Namespace) -> int:
    """``aliasing bias --engine ...``: the bias columns of the check (the engine's own fit, filter and bias rule,
    the needed settings in the engine's units), then the bias verdicts; units as :func:`aliasing.check.units`."""
    report = check(setups.from_args(args))
    u = units(report.setup)
    rows = [{k: r[k] for k in BIAS_COLUMNS} | {k: v for k, v in r.items() if k.startswith("needed_")} for r in report.to_rows()]
    verdicts = [v for v in report.verdicts if "acne" in v or "faces" in v or "detach" in v or "without bound" in v]
    if args.format == "json":
        clean = [{k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in r.items()} for r in rows]
        sys.stdout.write(json.dumps({"engine": report.setup.engine, "release": report.setup.release, "rows": clean,
                                     "units": {k: u[k] for k in rows[0]}, "verdicts": verdicts}, indent=1) + "\n")
        return 0
    shown = _tables.labelled(rows, {k: header(k, u[k]) for k in rows[0]})
    if args.format == "csv":
        sys.stdout.write(_tables.csv_text(shown))
        return 0
    sys.stdout.write(_tables.table(shown))
    sys.stdout.write("".join(f"- {v}\n" for v in verdicts))
    return 0


def add_check_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``check`` subcommand to the ``aliasing`` command's subparsers ``sub``."""
    p = sub.add_parser(
        "check",
        help="per cascade of an engine's own setup: texel, error, the bias settings it needs, acne, peter-panning, seams, shimmer, memory",
        description="What an engine's shadow settings do, per cascade, in the engine's own terms: each cascade's depth range and world "
        f"texel (the engine's own fit), the aliasing error ({ERROR_WORDS} [{ERROR_UNIT}]: how many of the camera's image pixels one "
        "texel spans) over the sun band, the bias "
        "settings that remove acne (in the engine's units), the acne and peter-panning at the given settings, the seam step, the "
        "filter footprint, shimmer under a walk and memory, with verdict lines naming the setting to change. Every column names its "
        "unit in brackets (lengths in the engine's world unit, needed_<key> in the setting's own unit); --format json adds 'units'.",
        epilog="Example: aliasing check --engine threejs --set cascades=4 --camera near=0.1,far=500,fov=50,aspect=16:9,height=1080 "
        "--sun 15..60.  'needed' is a lower bound (set at or above) for settings of positive scale and an upper bound (set at or "
        "below) for three.js's shadowBias and shadow.bias, which lift the receiver when negative.",
    )
    setups.add_arguments(p, required=True)
    p.add_argument("--receivers", metavar="SLOPES", help="slopes of the sampled planar receivers, tilted away from the sun, degrees in "
                   f"[0, 90), comma-separated (default 0: the ground); receivers more than {MAX_ANGLE:g}° from the light are left out")
    p.add_argument("--scene", metavar="boxes|city|FILE", help="the receivers of a scene instead of planar ones: boxes (seeded ground and "
                   "boxes around the camera), city (the procedural city, 400 units across, from its street camera unless --eye/--target), "
                   "or a file (glTF/GLB, OBJ, PLY, STL; needs --eye and --target); acne is then counted in the eye pass's pixels "
                   "facing the sun, per cascade, by receiver kind (ground, walls, other slopes)")
    p.add_argument("--eye", metavar="X,Y,Z", help="camera position for --scene city or FILE (world space; --eye=-5,2,0 when X is negative)")
    p.add_argument("--target", metavar="X,Y,Z", help="point the camera looks at, for --scene city or FILE (world space)")
    p.add_argument("--pixels", type=int, default=256, help="eye-pass pixels per side for --scene (default 256; they span the camera's frustum)")
    p.add_argument("--samples", type=int, default=7, help="sun elevations sampled over the --sun band (default 7)")
    p.add_argument("--walk", type=float, default=0.05, help="camera step per frame along the view [world units] for the shimmer "
                   "(default 0.05: 3 m/s at 60 fps)")
    p.add_argument("--seen", action=argparse.BooleanOptionalAction, default=False,
                   help="also predict what the user sees wrong per cascade (acne, false and lost shadow as fractions of the pixels facing "
                   "the sun, blocky texels, memory in bytes): the engine's frame of the reference scene (or --scene) drawn by the "
                   "toolkit with the engine's rules, no browser; threejs, babylon and playcanvas; a few seconds (default --no-seen); "
                   "in the table and JSON formats")
    p.add_argument("--format", default="table", choices=["table", "csv", "json"], help="output format (default table: the table, then the verdicts)")
    p.set_defaults(run=_run)
    return p
