"""The ``aliasing bias`` subcommand: minimal biases per cascade against the engines' presets.

Example
-------
>>> import argparse
>>> sub = argparse.ArgumentParser().add_subparsers()
>>> p = add_bias_parser(sub)
>>> args = p.parse_args(["--plane", "--texel", "0.1", "--angle", "45"])
>>> _run(args)
texel  angle  azimuth   lookup  depth    normal
  0.1     45        0  nearest   0.05  0.0353553
0
"""

from __future__ import annotations

import argparse
import sys

from .. import _table as _tables
from .. import _validation as check
from .. import setups
from ..sweep import format_rows
from ..view import check_aspect
from . import presets as _presets
from .cascades import cascade_bias
from .filtering import filter_rows
from .plane import plane_bias


def _table(rows: list[dict]) -> str:
    return _tables.table(rows, digits=6)


def _numbers(text: str, flag: str) -> list[float]:
    items = [t.strip() for t in str(text).split(",")]
    if not items or any(not t for t in items):
        raise ValueError(f"{flag} must be a comma-separated list of numbers, got {text!r}")
    out = []
    for t in items:
        try:
            out.append(float(t))
        except ValueError:
            raise ValueError(f"{flag} must be a comma-separated list of numbers, got {text!r}") from None
    return out


def _wide(rows: list[dict], aspect: float) -> list[dict]:
    """Rows of a non-square view carry ``aspect`` after ``preset``; at aspect 1 the rows are returned as they are."""
    if aspect == 1.0:
        return rows
    return [{"preset": r["preset"], "aspect": aspect} | {key: value for key, value in r.items() if key != "preset"} for r in rows]


def _run(args: argparse.Namespace) -> int:
    if args.list:
        for p in _presets.PRESETS.values():
            note = f" [not modelled: {p.partial}]" if p.partial else ""
            print(f"{p.name:15s} {p.engine}: {p.source}{note}")
        return 0
    setup, camera, sun = setups.resolve(args)
    if setup is not None:
        raise ValueError("bias --engine (or --project) runs through 'aliasing bias' of the aliasing command (aliasing.cli)")  # wired in aliasing.cli
    if camera is not None:  # --image is the image's rows: the camera's height
        args.near, args.far, args.fov, args.aspect, args.image = camera.near, camera.far, camera.fov, camera.aspect, camera.height
    if sun is not None:
        args.light = sun.light()  # one light: the band's lowest sun
    if args.plane:
        if args.filter:
            raise ValueError("--filter works per cascade, not with --plane")
        if args.aspect is not None:
            raise ValueError("--aspect is the view's width/height: it works per cascade, not with --plane (a receiver's texel is given by --texel)")
        if args.texel is None or args.angle is None:
            raise ValueError("--plane needs --texel and --angle")
        rows = []
        for w in _numbers(args.texel, "--texel"):
            for a in _numbers(args.angle, "--angle"):
                for az in _numbers(args.azimuth, "--azimuth"):
                    pb = plane_bias(w, a, az, args.lookup)
                    rows.append({"texel": w, "angle": a, "azimuth": az, "lookup": args.lookup, "depth": pb.depth, "normal": pb.normal})
    else:
        names = [t.strip() for t in str(args.presets).split(",")]
        chosen = [_presets.get(n).name for n in names]  # validate every name before any work
        aspect = 1.0 if args.aspect is None else float(check_aspect(check.scalar(args.aspect, "aspect")))
        params = {} if args.lam is None else {"lam": float(check.closed_range(args.lam, "--lambda", 0.0, 1.0))}
        if args.fraction is not None and not args.filter or args.radius is not None and not args.filter:
            raise ValueError("--fraction and --radius need --filter")
        fraction = 0.1 if args.fraction is None else float(check.closed_range(args.fraction, "--fraction", 0.0, 1.0))
        if not fraction > 0:
            raise ValueError(f"--fraction must be in (0, 1] (change of the blur width per pixel), got {fraction}")
        if args.radius is not None and not (args.radius > 0 and args.radius < float("inf")):
            raise ValueError(f"--radius must be a finite world width > 0, got {args.radius}")
        rows = []
        for name in chosen:
            got = cascade_bias(args.near, args.far, args.fov, args.light, name, scheme=args.scheme, splits=args.splits,
                               k=args.k, resolution=args.resolution, image=args.image, aspect=aspect, **params)
            rows.extend(_wide(filter_rows(got, args.fov, args.image, fraction, args.radius) if args.filter else got, aspect))
    sys.stdout.write(_table(rows) if args.format == "table" else format_rows(rows, args.format))
    return 0


def add_bias_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``bias`` subcommand to the ``aliasing`` command's subparsers ``sub``.

    ValueErrors (bad input) are printed by ``aliasing.cli.main`` as one line, exit 2.
    """
    p = sub.add_parser(
        "bias",
        help="minimal depth bias and normal offset per cascade against the engines' bias presets",
        description="Per cascade: the texel, the ground's minimal depth bias and normal offset, a preset's bias as one depth "
        "bias and its margin (below 1: acne), the receiver angle from which the preset shows acne, the lit gap at a contact "
        "(peter-panning) in world units and pixels, the filter's footprint in pixels and the texel step to the next cascade. "
        "With --plane: the minimal biases of planar receivers.",
        epilog="presets: " + ", ".join(_presets.PRESETS) + " (see --list); lookups: nearest, pcf<k>, receiver-plane.",
    )
    p.add_argument("--list", action="store_true", help="list the bias presets with the engine files they were read from, and exit")
    p.add_argument("--presets", default=",".join(_presets.PRESETS), help="comma list of bias presets (default all)")
    p.add_argument("--near", type=float, default=0.1, help="near distance (default 0.1)")
    p.add_argument("--far", type=float, default=100.0, help="shadow distance (default 100)")
    p.add_argument("--fov", type=float, default=60.0, help="FULL (vertical) field of view in degrees (default 60)")
    p.add_argument("--aspect", type=float, help="image width/height, > 0 (default 1: square; --fov is then the vertical field of view): "
                   "each cascade's map is fitted to its slice of the wider view; rows carry it when not 1 (not with --plane)")
    p.add_argument("--light", default="gamma:45", help="one light direction above the ground (default gamma:45: 45° elevation ahead)")
    p.add_argument("--scheme", default="Standard", help="warp inside each cascade: Standard, P, LogP or a warping rule (default Standard)")
    p.add_argument("--splits", default="practical", help="split method or engine split preset (default practical, λ = 0.5)")
    p.add_argument("-k", type=int, default=4, help="number of cascades (default 4)")
    p.add_argument("--lambda", dest="lam", type=float, help="λ of practical-style splits (default 0.5)")
    p.add_argument("--resolution", type=int, default=2048, help="texels per side of each cascade (default 2048)")
    p.add_argument("--image", type=int, default=1080, help="the image's HEIGHT in pixels (rows, top to bottom; default 1080; square pixels)")
    p.add_argument("--plane", action="store_true", help="minimal biases of planar receivers instead (with --texel, --angle)")
    p.add_argument("--texel", help="texel widths in world units, comma list (with --plane)")
    p.add_argument("--angle", help="angles between the receiver's normal and the light in degrees, comma list (with --plane)")
    p.add_argument("--azimuth", default="0", help="azimuths of the receiver's slope from the map's s axis in degrees, comma list (default 0)")
    p.add_argument("--lookup", default="nearest", help="nearest, pcf<k> or receiver-plane (default nearest; with --plane)")
    p.add_argument("--filter", action="store_true", help="per cascade, the filter instead: its kernel in world units and pixels, "
                   "texels of a world-constant kernel, the texel step at the boundary, the blend band that hides it, "
                   "the bias of plain PCF and of receiver-plane PCF")
    p.add_argument("--fraction", type=float, help="with --filter: largest change of the blur width per pixel in the blend band, "
                   "a fraction of the narrower width (default 0.1)")
    p.add_argument("--radius", type=float, help="with --filter: width of the world-constant kernel in world units "
                   "(default the first cascade's k texels)")
    p.add_argument("--format", default="table", choices=["table", "csv", "json"], help="output format (default table)")
    setups.add_arguments(p, sun=None)  # --engine: the engine's own fit, filter and bias rule, in its units (aliasing check's bias columns)
    p.set_defaults(run=_run)
    return p
