"""The ``aliasing tune`` subcommand: an engine's own shadow settings for a camera, a sun band and limits.

::

    aliasing tune --engine ENGINE[@RELEASE] --camera SPEC --sun ELEV[..ELEV][@AZ] \\
        [--receivers NEAR..FAR | --scene FILE] [--max-texels N] [--max-memory MIB] [--max-gap-px P] [--max-slope DEG] \\
        [--moving] [--objective auto|wrong|perspective] [--prefer wrong|blocky|memory] [--frames N] \\
        [--settings FILE] [--set KEY=VALUE]... [--keep KEY[,KEY...]]... [--patch | --write] [--format table|json]

The user's setup (``--settings``, ``--set`` and, where the command line has it, ``--project``) is
the start, "before"; ``--keep`` holds settings at their start values; the others the profile
declares tunable are searched from there: first for the lowest worst perspective error
(:func:`aliasing.tune.search.tune`), then, for the engines whose frames are predicted (three.js,
Babylon.js, PlayCanvas; Godot with ``rendering/renderer/rendering_method=gl_compatibility``), for the fewest wrong pixels (:mod:`aliasing.tune.pixels`: the objective;
the other engines keep the perspective one and the output says why in one line).  Every changed
setting is listed with its value before and after in the engine's units, with a line saying what it
fixes and costs, and every measure that got worse (:func:`aliasing.tune.report.worse`) on its own
line.  JSON: the ``check`` object of the tuned settings (feeding its ``settings`` back through
``aliasing check --settings`` gives the same numbers), plus ``objective`` (the worst perspective
error of the pick), ``objective_kind`` (``wrong`` or ``perspective``), ``objective_note``,
``wrong`` (before and after, the samples), ``pareto``, ``prefer``, ``why``, ``frames`` (with
``--frames``), ``binding``, ``feasible``, ``changed``, ``changes`` (``[{key, before, after,
unit}]``), ``worse``, ``keep``, ``held_gap`` (where the gap grew unasked: the search with the
start's gap as the limit, its objective and changes), ``snippet``, ``tradeoff``, ``limits``,
``measured`` and ``defaults`` (the ``check`` object of the start); with ``--patch`` and ``--format
json``, ``patch`` (file -> diff).  No NaN or inf: a number that does not exist is ``null`` with a
reason beside it.  ``--patch`` prints the changes as a unified diff of the project's own files,
``--write`` applies it (both need ``--project``).

Exit status: 0 tuned within the limits; 3 (:data:`INFEASIBLE`) the limits cannot all be met (the
closest settings are printed, ``binding`` names the limits, one line on stderr); 2 a malformed
option (one line naming its flag).
"""

from __future__ import annotations

import argparse
import dataclasses
import difflib
import json
import math
import re
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .. import _table as _tables
from .. import setups
from ..check import check
from ..frames import seen as _seen
from ..setups import files
from . import explain, pixels, proof, report, search
from .measure import measure as _measure

#: The exit status where the limits cannot all be met (the closest settings are still printed).
INFEASIBLE = 3

_FLAGS = {"receivers": "--receivers", "max_texels": "--max-texels", "max_gap_px": "--max-gap-px", "max_slope": "--max-slope",
          "scene": "--scene", "keep": "--keep", "max_memory": "--max-memory", "prefer": "--prefer"}


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


def _keep(values: list[str] | None) -> tuple[str, ...]:
    """``--keep KEY[,KEY...]`` (repeatable) as keys; each is checked against the profile's by :func:`aliasing.tune.tune`."""
    out = []
    for v in values or ():
        parts = [p.strip() for p in v.split(",")]
        if not all(parts):
            raise ValueError(f"--keep must be KEY[,KEY...] of the engine's own setting keys, got {v!r}")
        out += parts
    return tuple(out)


def _project(args: argparse.Namespace) -> list[Path]:
    """The project files of ``--project`` (one or a list), [] without it."""
    got = getattr(args, "project", None)
    if not got:
        return []
    return [Path(p) for p in ([got] if isinstance(got, (str, Path)) else got)]


def run(args: argparse.Namespace) -> dict[str, Any]:
    """The result of the parsed options: the :class:`~aliasing.tune.Tuned`, its ``check`` reports, what got worse, the project found."""
    if args.receivers is not None and args.scene is not None:
        raise ValueError("--receivers and --scene both give the receivers: use one")
    paths = _project(args)
    if (args.patch or args.write) and not paths:
        raise ValueError(f"{'--patch' if args.patch else '--write'} needs --project FILE (the engine's own project file to change)")
    start = setups.from_args(args)
    found = files.read(paths, getattr(args, "light_node", None), getattr(args, "camera_node", None)) if paths else None
    try:
        tuned = search.tune(start, receivers=_receivers(args.receivers), scene=args.scene, max_texels=_texels(args.max_texels),
                            max_gap_px=args.max_gap_px, max_slope=args.max_slope, moving=args.moving, keep=_keep(args.keep))
    except ValueError as exc:
        raise _flag_error(exc) from None
    tuned, wrong = _wrong_pixels(args, start, tuned)
    light = found.light if found is not None and found.light else getattr(args, "light_node", None)
    out = {"tuned": tuned, "after": check(tuned.setup), "before": check(tuned.start), "worse": report.worse(tuned), "light": light,
           "found": found, "paths": paths, **wrong}
    if paths:
        node, camera = getattr(args, "light_node", None), getattr(args, "camera_node", None)  # as the user named them, for the readers
        out["placed"], out["unplaced"] = placed(paths, tuned.changed, found.where, node, camera)
        out["patches"] = patches(out["placed"], node, camera)
    return out


def _wrong_pixels(args: argparse.Namespace, start, tuned) -> tuple[Any, dict[str, Any]]:
    """The wrong-pixel search (:mod:`aliasing.tune.pixels`) from the start and the perspective pick, where the engine is predicted.

    Returns the Tuned of the pick (the perspective one where the objective stays perspective or no candidate meets the
    limits) and the result's ``objective_kind``, ``objective_note``, ``seen`` (:class:`~aliasing.tune.pixels.Seen` or None),
    ``why`` and ``infeasible`` (why no candidate met the limits, or None).
    """
    kind = getattr(args, "objective", "auto") or "auto"
    n = getattr(args, "frames", None)
    if n is not None and (isinstance(n, bool) or not 1 <= n <= 64):
        raise ValueError(f"--frames must be a whole number of candidates to render, 1 to 64, got {n!r}")
    mem = getattr(args, "max_memory", None)
    if mem is not None and not (math.isfinite(mem) and mem > 0):
        raise ValueError(f"--max-memory must be a number of MiB > 0, got {mem!r}")
    note = pixels.why_not(start)
    if n is not None and not (kind == "perspective" or note):
        from ..frames import MissingTool

        try:
            proof.ready(start.engine)
        except MissingTool as exc:
            raise ValueError(f"--frames renders in the engine and needs its tools: {exc} (install them all with `aliasing frames --install`)") from None
    if kind == "wrong" and note:
        raise ValueError(f"--objective wrong: {note}")
    out: dict[str, Any] = {"objective_kind": "perspective", "objective_note": note, "seen": None, "why": [], "infeasible": None}
    if getattr(args, "frames", None) is not None and (kind == "perspective" or note):
        raise ValueError("--frames renders the wrong-pixel search's candidates: it needs --objective wrong or auto and an engine whose "
                         f"frames are predicted ({', '.join(_seen.ENGINES)})" + (f"; here {note}" if note else ""))
    if kind == "perspective":
        out["objective_note"] = "the worst perspective error, as asked (--objective perspective)"
        return tuned, out
    if note:
        return tuned, out
    max_memory = getattr(args, "max_memory", None)
    scene = _frame_scene(args.scene, start)
    try:
        got = pixels.refine(start, tuned.setup, tuned.limits, scene=scene, keep=frozenset(tuned.keep), prefer=getattr(args, "prefer", "wrong"),
                            max_memory=max_memory, max_gap_given=args.max_gap_px is not None)
    except pixels.Infeasible as exc:
        out["infeasible"] = str(exc)
        binding = tuned.binding if not tuned.feasible else (("max_memory",) if max_memory is not None else tuned.binding)
        return dataclasses.replace(tuned, feasible=False, binding=tuple(binding)), out
    except ValueError as exc:
        raise _flag_error(exc) from None
    frames = _frames(args, start, got, scene)
    if frames is not None:
        chosen = frames["candidates"][frames["pick"]]["settings"]
        if chosen != dict(got.setup.settings):
            pick = setups.Setup(start.profile, dict(chosen), start.camera, start.sun)
            final = _seen.sample(start, scene, height=pixels.FINAL_HEIGHT, suns=pixels.FINAL_SUNS)
            got = dataclasses.replace(got, setup=pick, after=_seen.count(pick, final).total)
        out["frames"] = frames
    pick = got.setup
    m = _measure(pick, tuned.limits)
    picked = dataclasses.replace(tuned, setup=pick, objective=m.objective, measure=m, feasible=True, binding=(), tradeoff=(), held_gap=None,
                                 changed={k: v for k, v in pick.settings.items() if start.settings.get(k) != v})
    out.update({"objective_kind": "wrong", "seen": got, "why": explain.why(got, start, tuned.limits)})
    return picked, out


def _frame_scene(scene: str | None, start) -> Any:
    """``--scene`` for the wrong pixels: None (the reference scene), boxes or city as named, a file seen from its first glTF camera."""
    if scene is None or scene in ("boxes", "city"):
        return scene
    from ..frames.scenes import frame_scene
    from ..raster.scenes import load_scene

    cam = start.camera
    try:
        ws = load_scene(scene)
    except (ValueError, ImportError, OSError) as exc:
        raise ValueError(f"--scene {scene} could not be loaded: {str(exc).splitlines()[0] if str(exc) else type(exc).__name__}") from None
    if not ws.cameras:
        raise ValueError(f"--scene {scene!r} has no glTF camera to see it from: give --receivers NEAR..FAR instead")
    c = ws.camera(sorted(ws.cameras)[0], near=cam.near, far=cam.far, fov=cam.fov)
    return frame_scene(str(scene), near=cam.near, far=cam.far, fov=cam.fov, aspect=cam.aspect, eye=c.eye, target=c.eye + c.rotation[2])


def _frames(args: argparse.Namespace, start, got, scene: Any = None) -> dict[str, Any] | None:
    """``--frames N``: the N best candidates rendered in the engine (:func:`aliasing.tune.proof.prove`); None without it."""
    n = getattr(args, "frames", None)
    if n is None:
        return None
    from ..frames import MissingTool

    try:
        return proof.prove(start, got.points, prefer=got.prefer, n=n, scene=scene, first=got.pareto[0] if got.pareto else None)
    except MissingTool as exc:
        raise ValueError(f"--frames renders in the engine and needs its tools: {exc} (install them all with `aliasing frames --install`)") from None


def placed(paths: list[Path], changes: Mapping[str, Any], where: Mapping[str, str], light: str | None = None,
           camera: str | None = None) -> tuple[dict[Path, dict[str, Any]], dict[str, Any]]:
    """The changed settings grouped by the project file that holds each, and those no file takes.

    A key is in the file that ``Found.where`` (:class:`aliasing.setups.files.Found`) names for it (``"main.tscn line 12"``: the
    file's name first).  A key no file holds goes to the first file whose reader's patch takes it (a reader refuses,
    with a ValueError, a key that does not belong in its file); a key no file takes (Unreal's light properties live in
    the level, not in ``DefaultEngine.ini``) is returned apart, for the engine's editor or the snippet.
    """
    by_name = {p.name: p for p in paths}
    out: dict[Path, dict[str, Any]] = {p: {} for p in paths}
    apart: dict[str, Any] = {}
    for key, value in changes.items():
        at = str(where.get(key, ""))
        home = next((p for name, p in by_name.items() if at == name or at.startswith(name + " ") or at.startswith(name + ":")), None)
        if home is None:
            for p in paths:
                try:
                    files.patch(p, {key: value}, light, camera)
                except ValueError:
                    continue
                home = p
                break
        if home is None:
            apart[key] = value
        else:
            out[home][key] = value
    return {p: c for p, c in out.items() if c}, apart


def patches(by_file: Mapping[Path, Mapping[str, Any]], light: str | None = None, camera: str | None = None) -> dict[Path, str]:
    """Per project file with a changed key (:func:`placed`), the unified diff (``difflib.unified_diff``) of its patched text
    (:func:`aliasing.setups.files.patch`)."""
    out = {}
    for path, mine in by_file.items():
        old = path.read_text(encoding="utf-8-sig")
        new = files.patch(path, mine, light, camera)
        out[path] = "".join(difflib.unified_diff(old.splitlines(keepends=True), new.splitlines(keepends=True),
                                                 fromfile=f"a/{path.as_posix()}", tofile=f"b/{path.as_posix()}"))
    return out


def write(by_file: Mapping[Path, Mapping[str, Any]], light: str | None = None, camera: str | None = None) -> list[Path]:
    """Apply the changes to each project file that holds one (:func:`placed`), each atomically
    (:func:`aliasing.setups.files.write`), and none unless every file's patch reads back as written first."""
    for path, mine in by_file.items():  # every file's patch read back before any file is replaced
        new = files.patch(path, mine, light, camera)
        back = files.reader(files.detect(path, new)).read([(path, new)], light, camera).settings
        wrong = {k: v for k, v in mine.items() if back.get(k) != v}
        if wrong:
            raise ValueError(f"{path.name}: the patch does not read back as written ({wrong}); no file was changed")
    return [files.write(path, mine, light, camera) for path, mine in by_file.items()]


def _before_reason(tuned) -> str | None:
    """Why the start has no worst error: its shadows end before the receivers begin."""
    if math.isfinite(tuned.before.objective):
        return None
    end = float(max(tuned.start.pipeline.far_i))
    return (f"the start's shadows end at {end:.4g} world units, before the receivers begin ({tuned.limits.receivers[0]:.4g}): "
            "no cascade draws a shadow there")


def to_dict(result: dict[str, Any]) -> dict[str, Any]:
    """The JSON object (module docstring)."""
    tuned = result["tuned"]
    lim = tuned.limits
    out = result["after"].to_dict()
    held = tuned.held_gap
    out.update({
        "objective": _finite(tuned.objective),
        "binding": list(tuned.binding),
        "feasible": tuned.feasible,
        "changed": dict(tuned.changed),
        "changes": tuned.changes,
        "worse": result["worse"],
        "keep": list(tuned.keep),
        "held_gap": None if held is None else {"max_gap_px": held.limits.max_gap_px, "objective": _finite(held.objective),
                                               "changes": held.changes, "feasible": held.feasible},
        "snippet": tuned.snippet(result.get("light")),
        "language": tuned.setup.profile.language,
        "tradeoff": [{k: (v if math.isfinite(v) else None) for k, v in p.items()} for p in tuned.tradeoff],
        "limits": {"receivers": list(lim.receivers), "max_texels": lim.max_texels,
                   "max_gap_px": lim.max_gap_px if math.isfinite(lim.max_gap_px) else None, "max_slope": lim.max_slope, "moving": lim.moving},
        "measured": {"texels": tuned.measure.texels, "gap_px": _finite(max(tuned.measure.gap_px, default=0.0)),
                     "objective_before": _finite(tuned.before.objective), "objective_before_reason": _before_reason(tuned)},
        "defaults": result["before"].to_dict(),
    })
    out.update(_wrong_dict(result))
    if "patches" in result:
        out["patch"] = {str(p): d for p, d in result["patches"].items()}
        out["unplaced"] = dict(result["unplaced"])
    return out


def _wrong_dict(result: dict[str, Any]) -> dict[str, Any]:
    """The JSON of the objective: ``objective_kind``, ``objective_note``, ``wrong`` (before, after, samples), ``pareto``, ``prefer``, ``why``."""
    got = result.get("seen")
    out: dict[str, Any] = {"objective_kind": result.get("objective_kind", "perspective"), "objective_note": result.get("objective_note"),
                           "infeasible_reason": result.get("infeasible"), "why": [dict(w) for w in result.get("why", [])]}
    if got is None:
        out.update({"wrong": None, "pareto": [], "prefer": None})
        return out
    start = result["tuned"].start.settings
    out.update({"wrong": {"before": _clean(got.before), "after": _clean(got.after), "sample": dict(got.sample), "final": dict(got.final),
                          "evaluations": got.evaluations, "seconds": round(got.seconds, 3), "units": "fractions of the sun-facing pixels"},
                "pareto": [p.to_dict(start) for p in got.pareto], "prefer": got.prefer})
    if result.get("frames") is not None:
        out["frames"] = result["frames"]
    return out


def _clean(d: Mapping[str, Any]) -> dict[str, Any]:
    return {k: (v if not isinstance(v, float) or math.isfinite(v) else None) for k, v in d.items()}


def _pct(v: float | None) -> str:
    return "n/a (no sun-facing pixel)" if v is None else f"{100 * v:.3g} %"


def _wrong_text(result: dict[str, Any]) -> list[str]:
    """The objective's lines: what it is, wrong pixels before and after, the why lines and the Pareto front."""
    got = result.get("seen")
    if got is None:
        lines = ["objective: worst perspective error (" + (result.get("objective_note") or "the papers' measure") + ")"]
        if result.get("infeasible"):
            lines.append(f"wrong-pixel search: {result['infeasible']}")
        return lines
    smp, fin = got.sample, got.final
    b, a = got.before, got.after
    lines = [f"objective: wrong pixels (acne + false shadow + lost shadow, of the sun-facing pixels) predicted on the {smp['scene']} scene, "
             f"searched at {smp['height_px']} rows and {smp['suns']} suns, measured at {fin['height_px']} rows and {fin['suns']} suns "
             f"({got.evaluations} candidates, {got.seconds:.1f} s)",
             f"wrong pixels: {_pct(b['wrong'])} -> {_pct(a['wrong'])} (acne {_pct(b['acne'])} -> {_pct(a['acne'])}, false shadow "
             f"{_pct(b['false_shadow'])} -> {_pct(a['false_shadow'])}, lost shadow {_pct(b['lost_shadow'])} -> {_pct(a['lost_shadow'])})"]
    if result.get("why"):
        lines.append("why each change (the pick with that setting alone at your value -> the pick, on the search's sample):")
        lines += ["  " + w["line"] for w in result["why"]]
    fr = result.get("frames")
    if fr:
        lines.append(f"rendered in the engine ({len(fr['candidates'])} candidates, {fr['height_px']} rows, {fr['suns']} suns, "
                     f"{fr['seconds']:.1f} s; measured / predicted wrong pixels; the pick marked *):")
        for i, c in enumerate(fr["candidates"]):
            ch = ", ".join(f"{k}={v}" for k, v in c["search"]["changed"].items()) or "(your settings)"
            lines.append(f"  {'*' if i == fr['pick'] else ' '} {_pct(c['measured']['wrong'])} / {_pct(c['predicted']['wrong'])}  {ch}")
    lines.append(f"Pareto front (wrong pixels, worst px/texel, memory; picked by --prefer {got.prefer}: the first row):")
    start = result["tuned"].start.settings
    rows = [["wrong", "acne", "false shadow", "lost shadow", "px/texel", "memory [MiB]", "changes"]]
    for p in got.pareto[:12]:
        d = p.to_dict(start)
        rows.append([_pct(p.wrong), _pct(p.acne), _pct(p.false_shadow), _pct(p.lost_shadow), _tables.cell(d["px_per_texel"]),
                     f"{p.memory:.4g}", ", ".join(f"{k}={v}" for k, v in d["changed"].items()) or "(your settings)"])
    lines += ["  " + ln for ln in _tables.aligned(rows).splitlines()]
    if len(got.pareto) > 12:
        lines.append(f"  ... {len(got.pareto) - 12} more in --format json")
    return lines


def _finite(v: float) -> float | None:
    v = float(v)
    return v if math.isfinite(v) else None


def text(result: dict[str, Any]) -> str:
    """The table: the changes, what got worse, the snippet, and check's rows before and after, side by side."""
    tuned = result["tuned"]
    s = tuned.setup
    lines = [f"{s.profile.title} {s.release}: camera {s.camera.spec()} ({s.camera.width}x{s.camera.height}), sun {s.sun.spec()}, "
             f"receivers {tuned.limits.receivers[0]:g}..{tuned.limits.receivers[1]:g}"]
    before = f"{tuned.before.objective:.4g}" if math.isfinite(tuned.before.objective) else f"none ({_before_reason(tuned)})"
    lines.append(f"worst perspective error: {before} -> {tuned.objective:.4g} px/texel"
                 + ("" if tuned.feasible else " (limits not all met)"))
    lines.append("binding: " + (", ".join(_FLAGS.get(b, "--" + b.replace("_", "-")) for b in tuned.binding) or "none"))
    lines += _wrong_text(result)
    if tuned.keep:
        lines.append("kept: " + ", ".join(tuned.keep))
    lines.append("changes (before → after, in the engine's units):" if tuned.changed else "changes: none (your settings are the best found within the limits)")
    lines += ["  " + ln for ln in report.changes_text(tuned)]
    lines += [w["line"] for w in result["worse"]]
    if tuned.held_gap is not None:
        h = tuned.held_gap
        lines.append(f"  with --max-gap-px {h.limits.max_gap_px:.4g} (the start's gap) the worst error would be {h.objective:.4g} px/texel"
                     + (f" ({len(h.changed)} changes)" if h.changed else " (your settings unchanged)"))
    rows = []
    before_rows, after_rows = result["before"].cascades, result["after"].cascades
    keys = ("near", "far", "error_max", "acne", "gap_px")
    head = ["cascade"] + [f"{k} before" for k in keys] + [f"{k} after" for k in keys]
    for i in range(max(len(before_rows), len(after_rows))):
        b = before_rows[i] if i < len(before_rows) else {}
        a = after_rows[i] if i < len(after_rows) else {}
        rows.append([str(i)] + [_tables.cell(b.get(k)) for k in keys] + [_tables.cell(a.get(k)) for k in keys])
    lines += _tables.aligned([head] + rows).splitlines()
    if tuned.tradeoff:
        lines.append("trade-off (the smallest gap that leaves no acne up to each angle to the light):")
        lines += [f"  {p['angle']:5.1f}° (slope {p['slope']:+.1f}°): {_tables.cell(p['gap_px'])} px" for p in tuned.tradeoff]
    snippet = tuned.snippet(result.get("light"))
    if snippet:
        lines.append(f"{s.profile.language or 'settings'}:")
        lines += ["  " + ln for ln in snippet.splitlines()]
    return "\n".join(lines) + "\n"


def _run(args: argparse.Namespace) -> int:
    result = run(args)
    tuned = result["tuned"]
    if not tuned.feasible:
        print(f"aliasing tune: {result['infeasible'] if result.get('infeasible') else _verdict(tuned)} (exit status {INFEASIBLE})", file=sys.stderr)
    if args.write:
        done = write(result["placed"], getattr(args, "light_node", None), getattr(args, "camera_node", None))
        print(f"aliasing tune: wrote {', '.join(str(p) for p in done) or 'nothing (no setting changed)'}", file=sys.stderr)
    if result.get("unplaced"):
        print("aliasing tune: not in your project files (set them in the engine, as the snippet does): "
              + ", ".join(f"{k} = {v}" for k, v in result["unplaced"].items()), file=sys.stderr)
    if args.patch and args.format != "json":
        sys.stdout.write("".join(result["patches"].values()))
        return 0 if tuned.feasible else INFEASIBLE
    sys.stdout.write(json.dumps(to_dict(result), indent=1, allow_nan=False) + "\n" if args.format == "json" else text(result))
    return 0 if tuned.feasible else INFEASIBLE


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
        help="what to set: the engine's own shadow settings with the fewest wrong pixels for a camera, a sun band and limits",
        description="Search the engine's own shadow settings (split mode and λ or fractions, cascade count, map size, where shadows "
        "end, biases, filter, which faces cast, stabilization, blend band) for the fewest pixels the user sees wrong (acne, false "
        "and lost shadow in the frame the engine would draw, predicted on the reference scene or --scene; three.js, Babylon.js, "
        "PlayCanvas) or, for the other engines, the lowest worst-case perspective error over the receivers and the sun band with no "
        "acne up to --max-slope and shadow edges moved within --max-gap-px; the texels within --max-texels and, with --moving, no "
        "shimmer. Your settings (--settings, --set) are the start: the search begins there, --keep holds some at their values, every "
        "change is listed before and after in the engine's units with what it fixes and costs, and every measure that gets worse is "
        "named. The Pareto front of wrong pixels, px/texel and memory is printed; --prefer picks from it.",
        epilog="Example: aliasing tune --engine threejs --set cascades=4 --set shadowMapSize=2048 "
        "--camera near=0.1,far=500,fov=50,aspect=16:9,height=1080 --sun 15..60 --receivers 1..200.  Exit status: 0 tuned within "
        f"the limits; {INFEASIBLE} the limits cannot all be met (the closest settings are still printed: 'binding' names the "
        "limits and the trade-off between acne and gap is printed); 2 a malformed option (one line on stderr).",
    )
    setups.add_arguments(p, required=True)
    p.add_argument("--receivers", metavar="NEAR..FAR", help="eye depths of the receivers [world units] (default the camera's near..far)")
    p.add_argument("--scene", metavar="FILE", help="a scene (glTF/GLB with a camera) whose visible depths give the receivers and, for the "
                   "wrong-pixel objective, on which the frames are predicted, seen from its first camera (default: the reference scene)")
    p.add_argument("--max-texels", metavar="N|KxR", help="texels of all maps together, a number or K x R (default: those of the given settings)")
    p.add_argument("--max-gap-px", type=float, metavar="P", help="the most a bias may move a shadow's edge on the ground [pixels]: the gap at a contact, the shortening by a normal offset (default: no limit)")
    p.add_argument("--max-slope", type=float, default=0.0, metavar="DEG",
                   help="the steepest receiver that must stay free of acne, degrees tilted from the ground away from the sun (default 0: the ground)")
    p.add_argument("--moving", action="store_true", help="the camera moves: the fit must be stabilized (no shimmer)")
    p.add_argument("--objective", default="auto", choices=["auto", "wrong", "perspective"],
                   help="what is minimised: wrong, the pixels the predicted frame gets wrong (acne, false and lost shadow) on the "
                   "reference scene or --scene (threejs, babylon, playcanvas; godot with rendering/renderer/rendering_method=gl_compatibility); perspective, the worst perspective error; auto "
                   "(default): wrong where the engine's frames are predicted, else perspective (the output says which and why)")
    p.add_argument("--prefer", default="wrong", choices=list(pixels.PREFER),
                   help="the pick from the Pareto front of wrong pixels, px/texel and memory: wrong (default: fewest wrong "
                   "pixels within the noise of their counts, then the fewest of your settings changed, then px/texel and memory), "
                   "blocky (fewest px/texel first) or memory (least memory first)")
    p.add_argument("--max-memory", type=float, metavar="MIB", help="the most memory of all shadow maps together [MiB] (wrong-pixel search)")
    p.add_argument("--frames", type=int, metavar="N", help="render the pick and the next N - 1 candidates in the engine itself (headless "
                   "Chromium) on the same scene; a candidate that measures significantly fewer wrong pixels replaces the pick (needs "
                   "'aliasing frames --install'); JSON holds measured beside predicted")
    p.add_argument("--keep", action="append", metavar="KEY[,KEY...]",
                   help="settings held at your values, in the engine's own keys (repeatable; default: every tunable setting may change)")
    out = p.add_mutually_exclusive_group()
    out.add_argument("--patch", action="store_true", help="print the changes as a unified diff of your project files (needs --project)")
    out.add_argument("--write", action="store_true", help="write the changes into your project files, atomically (needs --project)")
    p.add_argument("--format", default="table", choices=["table", "json"], help="output format (default table)")
    p.set_defaults(run=_run)
    return p
