"""The ``aliasing tune`` subcommand: an engine's own shadow settings for a camera, a sun band and limits.

::

    aliasing tune --engine ENGINE[@RELEASE] --camera SPEC --sun ELEV[..ELEV][@AZ] \\
        [--receivers NEAR..FAR | --scene FILE] [--max-texels N] [--max-gap-px P] [--max-slope DEG] \\
        [--moving] [--settings FILE] [--set KEY=VALUE]... [--format table|json]

The settings given with ``--settings`` and ``--set`` are fixed; the others the profile declares
tunable are searched.  JSON: the ``check`` object of the tuned settings (feeding its
``settings`` back through ``aliasing check --settings`` gives the same numbers), plus
``objective``, ``binding``, ``feasible``, ``changed``, ``snippet``, ``tradeoff``, ``limits`` and
``defaults`` (the ``check`` object of the settings before tuning).  Limits that cannot all be
met are exit status 0 with ``binding``; a malformed limit is one line naming its flag, exit 2.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
from typing import Any

from .. import _table as _tables
from .. import setups
from ..check import check
from . import search

_FLAGS = {"receivers": "--receivers", "max_texels": "--max-texels", "max_gap_px": "--max-gap-px", "max_slope": "--max-slope",
          "scene": "--scene"}


def _flag_error(exc: ValueError) -> ValueError:
    """The error with the parameter's name replaced by its flag."""
    text = str(exc)
    for name, flag in _FLAGS.items():
        if text.startswith(name):
            return ValueError(flag + text[len(name):])
    return exc


def _receivers(text: str | None) -> tuple[float, float] | None:
    if text is None:
        return None
    m = re.fullmatch(r"\s*([^.\s][^\s]*?)\s*\.\.\s*([^\s]+)\s*", text)
    try:
        if not m:
            raise ValueError
        near, far = float(m.group(1)), float(m.group(2))
    except ValueError:
        raise ValueError(f"--receivers must be NEAR..FAR eye depths [world units], e.g. 1..200, got {text!r}") from None
    return near, far


def _texels(text: str | None) -> int | None:
    """``N`` or ``KxR`` (K maps of R² texels)."""
    if text is None:
        return None
    m = re.fullmatch(r"\s*(\d+)\s*[x×]\s*(\d+)\s*", text)
    if m:
        value = int(m.group(1)) * int(m.group(2)) ** 2
    else:
        try:
            number = float(text)
        except ValueError:
            number = math.nan
        if not (math.isfinite(number) and number >= 1 and number.is_integer()):
            raise ValueError(f"--max-texels must be a whole number of texels >= 1 or K x R (K maps of R² texels, e.g. 4x2048), got {text!r}")
        value = int(number)
    if value < 1:
        raise ValueError(f"--max-texels must be at least 1 texel, got {text!r}")
    return value


def run(args: argparse.Namespace) -> dict[str, Any]:
    """The result of the parsed options: the :class:`~aliasing.tune.Tuned` and its ``check`` reports."""
    start = setups.from_args(args)
    fixed: dict[str, Any] = {}
    if args.settings:
        fixed.update(setups.load_settings(args.settings))
    fixed.update(setups.parse_set(args.set_))
    if args.receivers is not None and args.scene is not None:
        raise ValueError("--receivers and --scene both give the receivers: use one")
    try:
        tuned = search.tune(start, receivers=_receivers(args.receivers), scene=args.scene, max_texels=_texels(args.max_texels),
                            max_gap_px=args.max_gap_px, max_slope=args.max_slope, moving=args.moving, fixed=tuple(fixed))
    except ValueError as exc:
        raise _flag_error(exc) from None
    return {"tuned": tuned, "after": check(tuned.setup), "before": check(tuned.start)}


def to_dict(result: dict[str, Any]) -> dict[str, Any]:
    """The JSON object (module docstring)."""
    tuned = result["tuned"]
    lim = tuned.limits
    out = result["after"].to_dict()
    out.update({
        "objective": tuned.objective,
        "binding": list(tuned.binding),
        "feasible": tuned.feasible,
        "changed": dict(tuned.changed),
        "snippet": tuned.snippet(),
        "language": tuned.setup.profile.language,
        "tradeoff": [{k: (v if math.isfinite(v) else None) for k, v in p.items()} for p in tuned.tradeoff],
        "limits": {"receivers": list(lim.receivers), "max_texels": lim.max_texels,
                   "max_gap_px": lim.max_gap_px if math.isfinite(lim.max_gap_px) else None, "max_slope": lim.max_slope, "moving": lim.moving},
        "measured": {"texels": tuned.measure.texels, "gap_px": _finite(max(tuned.measure.gap_px, default=0.0)),
                     "objective_before": tuned.before.objective},
        "defaults": result["before"].to_dict(),
    })
    return out


def _finite(v: float) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def text(result: dict[str, Any]) -> str:
    """The table: the changed settings, the snippet, and check's rows before and after, side by side."""
    tuned = result["tuned"]
    s = tuned.setup
    lines = [f"{s.profile.title} {s.release}: camera {s.camera.spec()} ({s.camera.width}x{s.camera.height}), sun {s.sun.spec()}, "
             f"receivers {tuned.limits.receivers[0]:g}..{tuned.limits.receivers[1]:g}"]
    lines.append(f"worst perspective error: {tuned.before.objective:.4g} -> {tuned.objective:.4g} px per texel"
                 + ("" if tuned.feasible else " (limits not all met)"))
    lines.append("binding: " + (", ".join(_FLAGS.get(b, "--" + b.replace("_", "-")) for b in tuned.binding) or "none"))
    lines.append("settings:" if tuned.changed else "settings: the start is already the best")
    lines += [f"  {k} = {v!r}  (was {tuned.start.settings[k]!r})" for k, v in tuned.changed.items()]
    rows = []
    before, after = result["before"].cascades, result["after"].cascades
    keys = ("near", "far", "error_max", "acne", "gap_px")
    head = ["cascade"] + [f"{k} before" for k in keys] + [f"{k} after" for k in keys]
    for i in range(max(len(before), len(after))):
        b = before[i] if i < len(before) else {}
        a = after[i] if i < len(after) else {}
        rows.append([str(i)] + [_tables.cell(b.get(k)) for k in keys] + [_tables.cell(a.get(k)) for k in keys])
    lines += _tables.aligned([head] + rows).splitlines()
    if tuned.tradeoff:
        lines.append("trade-off (the smallest gap that leaves no acne up to each angle to the light):")
        lines += [f"  {p['angle']:5.1f}° (slope {p['slope']:+.1f}°): {_tables.cell(p['gap_px'])} px" for p in tuned.tradeoff]
    lines.append(f"{s.profile.language or 'settings'}:")
    lines += ["  " + ln for ln in tuned.snippet().splitlines()]
    return "\n".join(lines) + "\n"


def _run(args: argparse.Namespace) -> int:
    result = run(args)
    tuned = result["tuned"]
    if not tuned.feasible:
        print(f"aliasing tune: {_verdict(tuned)}", file=sys.stderr)
    sys.stdout.write(json.dumps(to_dict(result), indent=1) + "\n" if args.format == "json" else text(result))
    return 0


def _verdict(tuned) -> str:
    """One line: which limits cannot all be met, and the closest."""
    names = ", ".join(_FLAGS.get(b, "--" + b.replace("_", "-")) for b in tuned.binding)
    m = tuned.measure
    parts = [f"cannot meet {names}"]
    if "max_gap_px" in tuned.binding:
        parts.append(f"the smallest gap with no acne up to {tuned.limits.max_slope:g}° slope is {max(m.gap_px):.3g} px")
    if "max_texels" in tuned.binding:
        parts.append(f"the fewest texels the engine allows here: {m.texels}")
    return "; ".join(parts) + " (closest settings below)"


def add_tune_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``tune`` subcommand to the ``aliasing`` command's subparsers ``sub``."""
    p = sub.add_parser(
        "tune",
        help="what to set: the engine's own shadow settings with the lowest worst error for a camera, a sun band and limits",
        description="Search the engine's own shadow settings (split mode and λ or fractions, cascade count, map size, biases, filter, "
        "stabilization) for the lowest worst-case perspective error over the receivers and the sun band, with no acne up to "
        "--max-slope, shadow edges moved within --max-gap-px, the texels within --max-texels and, with --moving, no shimmer. Settings "
        "given with --settings or --set are kept. Biases are set to the closed-form minimum, not searched.",
        epilog="Example: aliasing tune --engine threejs --set cascades=4 --set shadowMapSize=2048 "
        "--camera near=0.1,far=500,fov=50,aspect=16:9,height=1080 --sun 15..60 --receivers 1..200.  Where the limits cannot all "
        "be met the command still answers (exit 0): 'binding' names them and the trade-off between acne and gap is printed.",
    )
    setups.add_arguments(p, required=True)
    p.add_argument("--receivers", metavar="NEAR..FAR", help="eye depths of the receivers [world units] (default the camera's near..far)")
    p.add_argument("--scene", metavar="FILE", help="a scene (glTF/GLB with a camera, OBJ, PLY, STL) whose visible depths give the receivers")
    p.add_argument("--max-texels", metavar="N|KxR", help="texels of all maps together, a number or K x R (default: those of the given settings)")
    p.add_argument("--max-gap-px", type=float, metavar="P", help="the most a bias may move a shadow's edge on the ground [pixels]: the gap at a contact, the shortening by a normal offset (default: no limit)")
    p.add_argument("--max-slope", type=float, default=0.0, metavar="DEG",
                   help="the steepest receiver that must stay free of acne, degrees tilted from the ground away from the sun (default 0: the ground)")
    p.add_argument("--moving", action="store_true", help="the camera moves: the fit must be stabilized (no shimmer)")
    p.add_argument("--format", default="table", choices=["table", "json"], help="output format (default table)")
    p.set_defaults(run=_run)
    return p
