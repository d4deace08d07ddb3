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
``--maps`` also ``maps``, and ``DIR/map<i>.npy``/``.png`` the engine's shadow maps), and
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
    """engine.png, predicted.png and difference.png of a :class:`aliasing.frames.run.FrameResult` in ``out``."""
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
    """Everything checked before the browser starts (the setup through :mod:`aliasing.setups`); the report of the frame."""
    from .. import setups
    from . import browser, run as frames_run, scenes
    from .models import from_setup

    if not args.engine:
        raise ValueError(f"--engine is required: one of {', '.join(sorted(PINS))}")
    name = args.engine.split("@")[0]
    if name not in PINS:
        raise ValueError(f"--engine must be one of {', '.join(sorted(PINS))} (the engines drawn in a browser), got {args.engine!r}")
    if args.scene is None or args.camera is None or args.sun is None or args.out is None:
        raise ValueError("--scene, --camera, --sun and --out are required (or --install)")
    setup = setups.from_args(args)
    frames_run.refuse_unrendered(setup.engine, setup.settings.get("class"), args.path, args.maps)
    if args.path is not None:
        frames_run.parse_path(args.path, scenes.frame_scene("boxes", near=1.0, far=2.0, fov=50.0, aspect=1.0, boxes=0, ground_cells=1).camera)
    if setup.release != PINS[name].release:
        raise ValueError(f"--engine {args.engine}: the frames render {name} {PINS[name].release} only (the pinned npm release), not {setup.release}")
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
        rows = [("shadow_agreement", m["shadow_agreement"], None)] + [(k, m[k], p[k]) for k in ("acne", "gap_px", "texels_per_pixel")]
        sys.stdout.write(f"{report['engine']} {report['release']}  measured  predicted\n")
        for k, a, b in rows:
            sys.stdout.write(f"{k}  {a}  {'-' if b is None else b}\n")
    return 0


def add_frames_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``frames`` subcommand to the ``aliasing`` command's subparsers ``sub``."""
    p = sub.add_parser(
        "frames",
        help="an engine's own frame (three.js, Babylon.js, PlayCanvas, Filament in headless Chromium) against the toolkit's prediction: shadow mask, acne, gap, texel footprint",
        description="Renders the scene with the engine itself (pinned npm release, system Chromium, WebGL 2 on SwiftShader), reads back its "
        "shadow factor, positions, normals and light matrices, and measures them against the toolkit's prediction for the same pixels.",
    )
    from ..setups import add_arguments

    add_arguments(p, sun=None)  # --engine, --settings, --set, --camera, --sun: the setups' vocabulary
    p.add_argument("--scene", help="boxes, city or a scene file (.glb, .gltf, .obj, .ply, .stl)")
    p.add_argument("--eye", metavar="X,Y,Z", help="camera position, world space (a scene file needs it; write --eye=-5,2,0 when X is negative)")
    p.add_argument("--target", metavar="X,Y,Z", help="point the camera looks at, world space")
    p.add_argument("--path", metavar="KIND:STEP[:FRAMES]", help="a camera path for shimmer (threejs, babylon): sideways or forward, STEP world units per "
                   "frame, or turn, STEP degrees per frame about the world's up; FRAMES (default 30); the cascades follow it while the picture's camera stays, and flips_per_frame is added")
    p.add_argument("--maps", nargs="?", type=int, const=1024, metavar="SIDE",
                   help="read the shadow maps back (threejs, babylon): every stride-th texel, at most SIDE per side (default 1024); "
                   "writes map<i>.npy and map<i>.png and adds maps (agreement with the toolkit's rasterizer) to the JSON")
    p.add_argument("--out", metavar="DIR", help="directory for engine.png, predicted.png, difference.png, frames.json")
    p.add_argument("--format", default="json", choices=["json", "table"], help="what is printed (default json)")
    p.add_argument("--timeout", type=float, default=120.0, help="seconds a page load or a frame may take (default 120)")
    p.add_argument("--install", action="store_true", help="install the engines' pinned npm packages (npm ci from the committed lockfiles) and exit")
    p.set_defaults(run=_run)
    return p
