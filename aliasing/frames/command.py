"""The ``aliasing frames`` subcommand: an engine's own frame against the toolkit's prediction.

::

    aliasing frames --engine threejs --scene boxes|city|FILE [--eye X,Y,Z --target X,Y,Z]
                    --camera near=N,far=F,fov=DEG,aspect=A,height=PX --sun ELEV[..ELEV][@AZ]
                    [--settings FILE] [--set KEY=VALUE]... --out DIR [--format json|table]
    aliasing frames --install [--engine ENGINE]

writes ``DIR/engine.png`` (the engine's frame), ``DIR/predicted.png`` (the toolkit's shadow
factor), ``DIR/difference.png`` (red: the engine shadows what the toolkit lights; blue: the
reverse) and ``DIR/frames.json`` (``engine``, ``release``, ``measured``, ``predicted``), and
prints the JSON (or a table).  Nothing is downloaded unless ``--install`` is given: without the
engine's pinned package, Chromium or Playwright, one line says how to install it (exit 2).
A sun range ``LO..HI`` is drawn at its middle elevation (a frame has one sun).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

from ..raster.scenes.world import json_safe
from .install import PINS, MissingTool

CAMERA_KEYS = ("near", "far", "fov", "aspect", "height")


def parse_camera(spec: str) -> dict:
    """``near=N,far=F,fov=DEG,aspect=A,height=PX`` (aspect as ``16:9`` or a number) as a dict.

    Example
    -------
    >>> parse_camera("near=0.1,far=500,fov=50,aspect=16:9,height=288")["aspect"]
    1.7777777777777777
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError("--camera must be near=N,far=F,fov=DEG,aspect=A,height=PX")
    out: dict = {}
    for part in spec.split(","):
        key, eq, value = part.partition("=")
        key = key.strip()
        if not eq or key not in CAMERA_KEYS:
            raise ValueError(f"--camera: {part!r} is not one of {', '.join(k + '=' for k in CAMERA_KEYS)}")
        try:
            if key == "aspect" and ":" in value:
                a, b = value.split(":")
                v = float(a) / float(b)
            else:
                v = float(value)
        except (ValueError, ZeroDivisionError):
            raise ValueError(f"--camera: {key} must be a number, got {value!r}") from None
        if not math.isfinite(v) or v <= 0:
            raise ValueError(f"--camera: {key} must be a finite number > 0, got {value!r}")
        out[key] = v
    missing = [k for k in CAMERA_KEYS if k not in out]
    if missing:
        raise ValueError(f"--camera misses {', '.join(missing)} (near=N,far=F,fov=DEG,aspect=A,height=PX)")
    if not out["near"] < out["far"]:
        raise ValueError(f"--camera: near must be < far, got near={out['near']:g}, far={out['far']:g}")
    if not out["fov"] < 180:
        raise ValueError(f"--camera: fov must be in (0, 180) degrees, got {out['fov']:g}")
    if out["height"] != int(out["height"]) or not 16 <= out["height"] <= 2160:
        raise ValueError(f"--camera: height must be a whole number of pixels in [16, 2160], got {out['height']:g}")
    out["height"] = int(out["height"])
    return out


def parse_sun(spec: str) -> tuple[float, float]:
    """``ELEV[..ELEV][@AZ]`` [deg] as (elevation, azimuth); a range gives its middle.

    Example
    -------
    >>> parse_sun("20..40@15")
    (30.0, 15.0)
    """
    if not isinstance(spec, str) or not spec.strip():
        raise ValueError("--sun must be ELEV[..ELEV][@AZ] in degrees")
    elev, _, az = spec.partition("@")
    try:
        lo, _, hi = elev.partition("..")
        e0 = float(lo)
        e1 = float(hi) if hi else e0
        a = float(az) if az else 0.0
    except ValueError:
        raise ValueError(f"--sun must be ELEV[..ELEV][@AZ] in degrees, got {spec!r}") from None
    if not (all(math.isfinite(v) for v in (e0, e1, a)) and 0 < e0 <= e1 < 90):
        raise ValueError(f"--sun: elevations must satisfy 0 < LO <= HI < 90 degrees and the azimuth be finite, got {spec!r}")
    return (e0 + e1) / 2, a


def parse_settings(path: str | None, sets: list[str]) -> dict:
    """The engine's settings: a JSON object file, then each ``KEY=VALUE`` (VALUE read as JSON, else as text)."""
    s: dict = {}
    if path:
        try:
            s = json.loads(Path(path).read_text())
        except json.JSONDecodeError as e:
            raise ValueError(f"--settings {path}: not JSON ({e.msg} at line {e.lineno})") from None
        if not isinstance(s, dict):
            raise ValueError(f"--settings {path}: must hold a JSON object of the engine's settings")
    for item in sets:
        key, eq, value = item.partition("=")
        if not eq or not key.strip():
            raise ValueError(f"--set must be KEY=VALUE, got {item!r}")
        try:
            s[key.strip()] = json.loads(value)
        except json.JSONDecodeError:
            s[key.strip()] = value
    return s


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
    """Everything checked before the browser starts; the report of the frame."""
    from . import browser, run as frames_run, scenes

    if args.engine not in PINS:
        raise ValueError(f"--engine must be one of {', '.join(sorted(PINS))}, got {args.engine!r}")
    from .models import MODELS

    if args.scene is None or args.camera is None or args.sun is None or args.out is None:
        raise ValueError("--scene, --camera, --sun and --out are required (or --install)")
    cam = parse_camera(args.camera)
    elev, az = parse_sun(args.sun)
    settings = MODELS[args.engine].settings(parse_settings(args.settings, args.set))
    fs = scenes.frame_scene(args.scene, near=cam["near"], far=cam["far"], fov=cam["fov"], aspect=cam["aspect"], eye=args.eye, target=args.target)
    sun = scenes.sun_direction(elev, az, fs.camera)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    try:
        with browser.Browser(timeout=args.timeout) as b:
            result = frames_run.frame(b, args.engine, fs, sun, settings, height=cam["height"])
    except (MissingTool, browser.PageError) as e:
        raise ValueError(str(e)) from None
    write_images(out, result)
    report = json_safe(result.report)
    (out / "frames.json").write_text(json.dumps(report, indent=1) + "\n")
    return report


def _run(args: argparse.Namespace) -> int:
    if args.install:
        from .install import install

        engines = [args.engine] if args.engine else sorted(PINS)
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
        help="an engine's own frame (three.js, Babylon.js, PlayCanvas in headless Chromium) against the toolkit's prediction: shadow mask, acne, gap, texel footprint",
        description="Renders the scene with the engine itself (pinned npm release, system Chromium, WebGL 2 on SwiftShader), reads back its "
        "shadow factor, positions, normals and light matrices, and measures them against the toolkit's prediction for the same pixels.",
    )
    p.add_argument("--engine", help=f"engine: {', '.join(sorted(PINS))}")
    p.add_argument("--scene", help="boxes, city or a scene file (.glb, .gltf, .obj, .ply, .stl)")
    p.add_argument("--eye", metavar="X,Y,Z", help="camera position, world space (a scene file needs it; write --eye=-5,2,0 when X is negative)")
    p.add_argument("--target", metavar="X,Y,Z", help="point the camera looks at, world space")
    p.add_argument("--camera", metavar="SPEC", help="near=N,far=F,fov=DEG,aspect=A,height=PX (fov vertical; aspect 16:9 or a number)")
    p.add_argument("--sun", metavar="ELEV[..ELEV][@AZ]", help="degrees above the ground, azimuth from the view direction (a range: its middle)")
    p.add_argument("--settings", metavar="FILE", help="JSON object of the engine's settings in its own keys")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="one engine setting (VALUE as JSON, else text); repeatable")
    p.add_argument("--out", metavar="DIR", help="directory for engine.png, predicted.png, difference.png, frames.json")
    p.add_argument("--format", default="json", choices=["json", "table"], help="what is printed (default json)")
    p.add_argument("--timeout", type=float, default=120.0, help="seconds a page load or a frame may take (default 120)")
    p.add_argument("--install", action="store_true", help="install the engines' pinned npm packages (npm ci from the committed lockfiles) and exit")
    p.set_defaults(run=_run)
    return p
