"""The ``aliasing frames`` subcommand: an engine's own frame against the toolkit's prediction.

::

    aliasing frames --engine threejs|babylon|playcanvas|filament --scene boxes|city|FILE [--eye X,Y,Z --target X,Y,Z]
                    --camera near=N,far=F,fov=DEG,aspect=A,height=PX --sun ELEV[..ELEV][@AZ]
                    [--settings FILE] [--set KEY=VALUE]... [--path KIND:STEP[:FRAMES]] [--maps [SIDE]]
                    --out DIR [--format json|table]
    aliasing frames --install [--engine ENGINE]

writes ``DIR/engine.png`` (the engine's frame), ``DIR/predicted.png`` (the toolkit's shadow
factor), ``DIR/difference.png`` (red: the engine shadows what the toolkit lights; blue: the
reverse) and ``DIR/frames.json`` (``engine``, ``release``, ``measured``, ``predicted``; with
``--maps`` also ``maps``, and ``DIR/map<i>.npy``/``.png`` the engine's shadow maps, PlayCanvas's one
atlas as ``map0``), and
prints the JSON (or a table).  Nothing is downloaded unless ``--install`` is given: without the
engine's pinned package, Chromium or Playwright, one line says how to install it (exit 2).
A sun range ``LO..HI`` is drawn at its middle elevation (a frame has one sun).  ``--engine``,
``--settings``, ``--set``, ``--camera`` and ``--sun`` are :mod:`aliasing.setups`' (the engine's
own setting keys, checked and defaulted there); the frames render the pinned release only.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from ..raster.scenes.world import json_safe
from .install import PINS, MissingTool

def _png(path: Path, rgb: np.ndarray) -> None:
    import matplotlib.image

    matplotlib.image.imsave(path, np.clip(rgb, 0, 1))


def write_images(out: Path, result) -> None:
    """engine.png, predicted.png and difference.png of a :class:`aliasing.frames.readback.FrameResult` in ``out``.

    Parameters
    ----------
    out : Path
        An existing directory.
    result : FrameResult
        The frame (its ``readback.frame`` PNG bytes, ``readback.shadow`` and ``prediction.factor``
        [fraction of the sun's light]).

    Returns
    -------
    None

    Examples
    --------
    >>> import tempfile
    >>> from types import SimpleNamespace
    >>> from aliasing.frames.readback import Readback
    >>> rb = Readback("threejs", "187", np.array([[0.0, 1.0]]), np.zeros((1, 2), np.int64), np.zeros((1, 2, 3)), np.zeros((1, 2, 3)),
    ...               np.eye(4)[None], np.array([[16, 16]]), {}, b"png")
    >>> result = SimpleNamespace(readback=rb, prediction=SimpleNamespace(factor=np.array([[1.0, 1.0]])))   # the engine shadows one more pixel
    >>> with tempfile.TemporaryDirectory() as d:
    ...     write_images(Path(d), result)
    ...     import matplotlib.image
    ...     diff = matplotlib.image.imread(Path(d) / "difference.png")
    ...     names = sorted(p.name for p in Path(d).iterdir())
    >>> names, diff[0, 0, :3].round(1).tolist()                        # red: the engine shadows, the toolkit lights
    (['difference.png', 'engine.png', 'predicted.png'], [1.0, 0.1, 0.1])
    """
    if not Path(out).is_dir():
        raise ValueError(f"out must be an existing directory, got {str(out)!r}")
    out = Path(out)
    (out / "engine.png").write_bytes(result.readback.frame)
    drawn = result.readback.drawn
    pf = np.where(drawn, np.nan_to_num(result.prediction.factor), 0.0)
    grey = np.where(drawn, 0.25 + 0.7 * pf, 0.0)
    _png(out / "predicted.png", np.repeat(grey[..., None], 3, axis=-1))
    m = np.nan_to_num(result.readback.shadow, nan=1.0) < 0.5
    p = np.nan_to_num(result.prediction.factor, nan=1.0) < 0.5
    diff = np.where(drawn, 0.5, 0.0)[..., None] * np.ones(3)
    diff[drawn & m & ~p] = (1.0, 0.1, 0.1)
    diff[drawn & ~m & p] = (0.1, 0.3, 1.0)
    _png(out / "difference.png", diff)


def run(args: argparse.Namespace) -> dict:
    """Everything checked before the browser starts (the setup through :mod:`aliasing.setups`); the report of the frame.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``aliasing frames`` arguments (:func:`add_frames_parser`).

    Returns
    -------
    dict
        The JSON-ready report (also written to ``--out``/frames.json).

    Raises
    ------
    ValueError
        An argument out of range, naming it; a missing tool or a page error, in one line.

    Examples
    --------
    >>> parser = argparse.ArgumentParser(prog="aliasing"); _ = add_frames_parser(parser.add_subparsers())
    >>> run(parser.parse_args(["frames", "--engine", "unity-urp", "--scene", "boxes"]))   # refused before any browser starts
    Traceback (most recent call last):
    ...
    ValueError: --engine must be one of babylon, filament, godot, playcanvas, threejs (the engines drawn in a browser), got 'unity-urp'

    A frame itself needs Chromium and the installed engine, so it is not run here:

    >>> run(parser.parse_args(["frames", "--engine", "threejs", "--scene", "boxes", "--camera", "near=1,far=60,fov=50,aspect=1,height=64",
    ...                        "--sun", "35@30", "--out", "out"]))["measured"]["acne"]     # doctest: +SKIP
    0.0
    """
    from .. import setups
    from . import browser, run as frames_run, scenes
    from .models import from_setup

    engine = args.engine or (setups.project(args).engine if getattr(args, "project", None) else None)
    if not engine:
        raise ValueError(f"--engine (one of {', '.join(sorted(PINS))}) or --project FILE is required")
    name = engine.split("@")[0]
    if name not in PINS:
        raise ValueError(f"--engine must be one of {', '.join(sorted(PINS))} (the engines drawn in a browser), got {engine!r}")
    own = bool(getattr(args, "project", None))  # the project's camera and sun stand in for --camera and --sun
    if args.scene is None or (args.camera is None and not own) or (args.sun is None and not own) or args.out is None:
        raise ValueError("--scene, --camera, --sun and --out are required (--camera and --sun may come from --project; or --install)")
    setup = setups.from_args(args)
    frames_run.refuse_unrendered(setup.engine, setup.settings.get("class"), args.path, args.maps)
    if args.path is not None:
        frames_run.parse_path(args.path, scenes.frame_scene("boxes", near=1.0, far=2.0, fov=50.0, aspect=1.0, boxes=0, ground_cells=1).camera)
    if setup.release != PINS[name].release and PINS[name].release not in getattr(setup.profile, "releases", ()):
        raise ValueError(f"--engine {engine}: the frames render {name} {PINS[name].release} only (the pinned npm release), not {setup.release}")
    cam = setup.camera
    if not 16 <= cam.height <= 2160:
        raise ValueError(f"--camera height must be in [16, 2160] pixels for a frame, got {cam.height}")
    from_setup(setup)  # settings the frames do not render or model: refused before the browser starts
    fs = scenes.frame_scene(args.scene, near=cam.near, far=cam.far, fov=cam.fov, aspect=cam.aspect, eye=args.eye, target=args.target)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    try:
        with browser.Browser(timeout=args.timeout) as b:
            result = frames_run.frame_setup(b, setup, fs, path=args.path, maps=args.maps)
    except (MissingTool, browser.PageError) as e:
        raise ValueError(str(e)) from None
    write_images(out, result)
    if args.maps is not None:
        from .maps import decode_maps, write_maps

        result.report["maps"]["files"] = write_maps(out, decode_maps(result.readback.info))
    report = json_safe(result.report)
    (out / "frames.json").write_text(json.dumps(report, indent=1) + "\n")
    return report


def _run(args: argparse.Namespace) -> int:
    if args.install:
        from .install import install

        engines = [args.engine.split("@")[0]] if args.engine else sorted(PINS)
        for e in engines:
            if e not in PINS:
                raise ValueError(f"--engine must be one of {', '.join(sorted(PINS))}, got {e!r}")
        try:
            for e in engines:
                print(f"{e}: {install(e)}")
        except (MissingTool, RuntimeError) as err:
            raise ValueError(str(err)) from None
        return 0
    report = run(args)
    if args.format == "json":
        sys.stdout.write(json.dumps(report, indent=1) + "\n")
    else:
        m, p = report["measured"], report["predicted"]
        rows = [("shadow_agreement", m["shadow_agreement"], None)] + [(k, m[k], p[k]) for k in ("acne", "lost_shadow", "gap_px", "px_per_texel")]
        sys.stdout.write(f"{report['engine']} {report['release']}  measured  predicted\n")
        for k, a, b in rows:
            sys.stdout.write(f"{k}  {a}  {'-' if b is None else b}\n")
    return 0


def add_frames_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``frames`` subcommand to the ``aliasing`` command's subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The ``aliasing`` parser's subparsers.

    Returns
    -------
    argparse.ArgumentParser
        The ``frames`` parser.

    Examples
    --------
    >>> p = add_frames_parser(argparse.ArgumentParser(prog="aliasing").add_subparsers())
    >>> a = p.parse_args(["--engine", "threejs", "--maps"])
    >>> a.engine, a.maps, a.format, a.timeout                           # --maps alone: at most 1024 texels per side
    ('threejs', 1024, 'json', 120.0)
    """
    p = sub.add_parser(
        "frames",
        help="an engine's own frame (three.js, Babylon.js, PlayCanvas, Filament, Godot in headless Chromium) against the toolkit's prediction: shadow mask, acne, gap, texel footprint",
        description="Renders the scene with the engine itself (pinned npm release, system Chromium, WebGL 2 on SwiftShader), reads back its "
        "shadow factor, positions, normals and light matrices, and measures them against the toolkit's prediction for the same pixels.",
    )
    from ..setups import add_arguments

    add_arguments(p, sun=None)  # --engine, --settings, --set, --camera, --sun: the setups' vocabulary
    p.add_argument("--scene", help="boxes, city or a scene file (.glb, .gltf, .obj, .ply, .stl)")
    p.add_argument("--eye", metavar="X,Y,Z", help="camera position, world space (a scene file needs it; write --eye=-5,2,0 when X is negative)")
    p.add_argument("--target", metavar="X,Y,Z", help="point the camera looks at, world space")
    p.add_argument("--path", metavar="KIND:STEP[:FRAMES]", help="a camera path for shimmer (threejs, babylon, playcanvas, godot): sideways or forward, STEP world units per "
                   "frame, or turn, STEP degrees per frame about the world's up; FRAMES (default 30); the cascades follow it while the picture's camera stays "
                   "(godot: the picture moves with the camera and flips are counted at world points seen in consecutive frames), and flips_per_frame is added")
    p.add_argument("--maps", nargs="?", type=int, const=1024, metavar="SIDE",
                   help="read the shadow maps back (threejs, babylon; playcanvas: its one atlas, each cascade compared in its cell): every stride-th texel, "
                   "at most SIDE per side (default 1024); writes map<i>.npy and map<i>.png and adds maps (agreement with the toolkit's rasterizer) to the JSON")
    p.add_argument("--out", metavar="DIR", help="directory for engine.png, predicted.png, difference.png, frames.json")
    p.add_argument("--format", default="json", choices=["json", "table"], help="what is printed (default json)")
    p.add_argument("--timeout", type=float, default=120.0, help="seconds a page load or a frame may take (default 120)")
    p.add_argument("--install", action="store_true", help="install the engines' pinned npm packages (npm ci from the committed lockfiles) and exit")
    p.set_defaults(run=_run)
    return p
