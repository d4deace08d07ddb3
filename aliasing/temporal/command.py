"""The ``aliasing shimmer`` subcommand: shimmer of engine schemes along a camera or sun path.

::

    aliasing shimmer --schemes SPEC[,SPEC...] --motion MOTION --frames N
                     [--scene NAME|FILE] [--aspect A] [--format table|csv|json]

``SPEC`` is the engines command's scheme grammar (:mod:`aliasing.engines.compare`);
``MOTION`` is :func:`aliasing.temporal.paths.parse_motion`'s.  One row per scheme
(:meth:`aliasing.temporal.measure.Shimmer.row`).  ``--aspect`` is the camera's width/height
(``--fov`` vertical; the points are one per pixel of an R × R image whose pixels are
aspect : 1 wide); the rows gain an ``aspect`` column only when it is not 1.  Bad input (an
unknown motion or scheme, a non-finite step, too few or too many frames, an aspect that is
not in (0, inf)) is refused before any map is drawn, with
one line on stderr and exit status 2 (:func:`aliasing.cli.main`).
"""

from __future__ import annotations

import argparse
import dataclasses
import json

import numpy as np

from .. import _table as _tables
from .. import _validation as check
from .. import setups
from ..engines import compare, pipeline
from ..raster.draw import backends, check_resolution, resident
from ..raster.scenes.world import json_safe
from . import measure, paths, points

FIELDS = ("scheme", "flip_fraction", "flip_fraction_max", "flips_per_second", "same_map_fraction", "map_change_share", "predicted_same_map", "predicted_over_measured",
          "ratio_se", "predicted_fraction", "per_degree", "edge_shift_px", "maps_drawn", "frames", "points", "seconds")
TABLE = ("scheme", "flip_fraction", "flips_per_second", "same_map_fraction", "map_change_share", "predicted_same_map", "predicted_over_measured", "ratio_se", "per_degree", "edge_shift_px", "seconds")


def run(args: argparse.Namespace) -> list[dict]:
    """The rows of ``aliasing shimmer`` (everything checked before the first map is drawn)."""
    motion = paths.parse_motion(args.motion)
    frames = paths.check_frames(args.frames)
    image_res = check_resolution(args.image_res, "--image-res")
    shadow_res = check_resolution(args.shadow_res, "--shadow-res")
    measure.check_size(frames, image_res**2)  # at most one point per pixel
    fps = float(check.positive(args.fps, "--fps"))
    backend = backends.check(args.backend, "eye_pass")  # refused before any work
    gltf = args.camera if args.camera is not None and "=" not in args.camera else None  # a glTF camera's name, or a camera spec
    setup, camera, sun = setups.resolve(args)
    specs = [s.strip() for s in (args.schemes or "").split(",") if s.strip()]
    if setup is not None:  # the engine's own cascades (fit, snap, ranges) at its own map size
        specs = [pipeline.scheme_spec(setup.pipeline)] + specs
        shadow_res = check_resolution(setup.pipeline.resolution, "the engine's map size")
    if backends.pair(backend)[1] == "gl":
        resident.check_size(shadow_res, "--shadow-res")  # a map the device cannot hold: refused before any work
    if camera is not None:
        args.near, args.far, args.fov, args.aspect = camera.near, camera.far, camera.fov, camera.aspect
        if setup is not None:
            args.far = max(setup.pipeline.far_i)
    if not specs:
        raise ValueError("--schemes is empty: name at least one scheme (e.g. csm:log:k=4,csm-stable:log:k=4:fit=sphere:snap=origin) or give --engine")
    w = points.world(args.scene, light=args.light_dir, eye=args.eye, target=args.target, camera=gltf, near=args.near, far=args.far, fov=args.fov, aspect=args.aspect)
    if sun is not None:  # the sun over the camera's horizontal view direction, the world's y up
        w = dataclasses.replace(w, light=_sun_world(w.camera.rotation, sun))
    cam = w.camera
    for spec in specs:  # every spec read before any work
        ps = compare.parse_spec(spec, fov=cam.fov, near=cam.near, far=cam.far, image_res=image_res, shadow_res=shadow_res, unit=args.unit, aspect=cam.aspect)
        if ps.family in ("matched", "exact"):
            raise ValueError(f"scheme {spec!r}: {ps.family} is a limit without a texel grid; shimmer needs csm, csm-stable, sdsm or vsm")
    paths.frames(motion, cam.eye, cam.rotation, cam.fov, w.light, frames)  # a zoom leaving (0, 180) deg is refused here
    pts = points.sample(w, image_res, backend=backend)
    rows = [measure.shimmer(w, pts, spec, motion, frames, res=shadow_res, unit=args.unit, backend=backend).row(fps) for spec in specs]
    if setup is not None:
        rows[0]["scheme"] = setup.profile.name  # the engine's own cascades
    return rows


def _sun_world(rotation: object, sun: setups.Sun) -> np.ndarray:
    """The sun's world direction (its lowest elevation): azimuth from the camera's horizontal view direction, y up."""
    forward = np.asarray(rotation, float)[2] * np.array([1.0, 0.0, 1.0])  # eye z in world, levelled
    if np.linalg.norm(forward) < 1e-9:
        raise ValueError("--sun needs a camera that does not look straight up or down (its azimuth is from the view direction)")
    forward /= np.linalg.norm(forward)
    up = np.array([0.0, 1.0, 0.0])
    right = np.cross(up, forward)
    e, a = np.radians(sun.elevation[0]), np.radians(sun.azimuth)
    return np.cos(e) * np.sin(a) * right + np.sin(e) * up + np.cos(e) * np.cos(a) * forward


def format_rows(rows: list[dict], fmt: str) -> str:
    """Rows as ``table``, ``csv`` or ``json`` text (an ``aspect`` column after ``scheme`` when a row has one)."""
    if fmt == "json":
        return json.dumps(json_safe(rows), indent=1) + "\n"
    wide = any("aspect" in r for r in rows)
    fields, table = ((f[:1] + ("aspect",) + f[1:]) if wide else f for f in (FIELDS, TABLE))
    if fmt == "csv":
        return _tables.csv_text(rows, fields)
    return _tables.table(rows, table)


def _run(args: argparse.Namespace) -> int:
    print(format_rows(run(args), args.format), end="")
    return 0


def add_shimmer_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``shimmer`` subcommand to the ``aliasing`` command's subparsers ``sub``."""
    p = sub.add_parser(
        "shimmer",
        help="shadow shimmer of a still world under a moving camera or a turning sun, measured and predicted, per scheme",
        description="Fixed points on the surfaces the first frame sees are shadow-tested through every frame's maps; the shimmer is the "
        "fraction of points whose lit/shadowed state flips between consecutive frames (an artefact: the world is still).  Flips of points "
        "that change cascade or clipmap level are reported apart; the prediction is the grid motion times the density of shadow edges.",
        epilog="motions: " + "; ".join(f"{k}:{e.args} ({e.help})" for k, e in paths.MOTIONS.items())
        + ".  schemes: the engines grammar (aliasing engines --list): csm:SPLIT[:k=N] | csm-stable:SPLIT|PRESET[:fit=..][:snap=..] | sdsm[:k=N] | vsm:PRESET | vsm:bias=B.",
    )
    p.add_argument("--schemes", help="comma list of scheme specs, e.g. csm:log:k=4,csm-stable:log:k=4:fit=sphere:snap=origin (required without --engine)")
    p.add_argument("--motion", required=True, help="translate:DX,DY,DZ | rotate:yaw|pitch,DEG | zoom:DEG | sun:DEG (per frame)")
    p.add_argument("--frames", required=True, type=float, help=f"frames of the sequence, 2 to {paths.MAX_FRAMES}")
    p.add_argument("--scene", default="boxes", help=f"a built-in scene ({', '.join(points.SCENES)}; default boxes) or a scene file (.glb, .gltf, .obj, .ply, .stl)")
    p.add_argument("--eye", metavar="X,Y,Z", help="camera position, world space (a scene file needs it or --camera; write --eye=-5,2,0 when X is negative)")
    p.add_argument("--target", metavar="X,Y,Z", help="point the camera looks at, world space")
    p.add_argument("--camera", metavar="NAME|SPEC", help=f"a glTF camera of the file, or the camera spec {setups.CAMERA_SPEC} (near, far, "
                   "vertical fov, aspect; its height is not used: the points are --image-res per side)")
    p.add_argument("--near", type=float, help="near distance [scene units]")
    p.add_argument("--far", type=float, help="far (shadow) distance [scene units]")
    p.add_argument("--fov", type=float, help="VERTICAL full field of view in degrees of the first frame")
    p.add_argument("--aspect", type=float, default=1.0, help="the camera's image width/height, > 0 (default 1: square; --fov is the vertical field of view; 16:9 is 1.7778)")
    p.add_argument("--light-dir", metavar="X,Y,Z", help=f"world direction towards the light (default {','.join(f'{v:g}' for v in points.DEFAULT_LIGHT)}; write --light-dir=-1,2,0 when X is negative)")
    p.add_argument("--image-res", type=int, default=128, help="points: one per pixel of this R x R first-frame image (default 128; its pixels are aspect : 1 wide); also VSM's viewport WIDTH")
    p.add_argument("--shadow-res", type=int, default=256, help="texels per side of each cascade's map (default 256; with --engine the engine's own, for every row)")
    p.add_argument("--fps", type=float, default=60.0, help="frame rate for flips per second (default 60)")
    p.add_argument("--unit", default="m", help="scene length unit for VSM's constants: m (default), cm, mm, in, ft")
    p.add_argument("--backend", default="numpy", help="how the eye pass and the depth maps are drawn: numpy (default, the reference), numba (the eye pass; fast extra) or gl (OpenGL, gl extra)")
    p.add_argument("--format", default="table", choices=["table", "csv", "json"], help="output format (default table)")
    setups.add_arguments(p, sun=None, camera=False)  # --engine: the engine's cascades as the first scheme; --sun replaces --light-dir
    p.set_defaults(run=_run)
    return p
