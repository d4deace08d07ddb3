"""``aliasing render``: the command line of the pictures (seeded or loaded scenes)."""

from __future__ import annotations

import argparse
import math

from .. import _validation, partitioning, setups
from ..bias import presets as bias_presets
from ..raster.draw import backends
from ..view import check_aspect
from ..raster.scenes import world
from .scenerender import run


def _render(args: argparse.Namespace) -> int:
    """``aliasing render``: one path for every case (:func:`~aliasing.pictures.scenerender.run`),
    the built-in scene or a loaded one, one scheme or several: labelled panels and their statistics."""
    try:  # parsed once here (float() alone named no option)
        args.f_over_n = float(args.f_over_n)
    except ValueError:
        raise ValueError(f"--f-over-n must be a number, got {args.f_over_n!r}") from None
    if args.seed < 0:
        raise ValueError(f"--seed must be a whole number >= 0, got {args.seed}")
    _validation.whole(args.res, "--res", 1, 65536, " (the texel budget's side: RES² texels over all maps)")
    _validation.whole(args.every, "--every", 1, 65536, " [texels between grid lines]")
    backends.check(args.backend, "eye_pass")  # refused before any work, like the bias preset and the aspect
    _setup(args)
    if args.what == "bias-margin":
        bias_presets.get(args.bias_preset)
    args.aspect = float(check_aspect(args.aspect))
    return run(args)


def _setup(args: argparse.Namespace) -> None:
    """--engine, --camera (a spec), --sun onto render's own options: the engine's split, cascade count and texel
    budget (k maps of R² texels: RES = R·√k, rounded), the camera's near, far, fov, aspect and rows, the band's lowest sun."""
    setup, camera, sun = setups.resolve(args)
    if setup is not None:
        pl = setup.pipeline
        try:
            args.splits = partitioning.resolve_name({"logarithmic": "log"}.get(pl.split, pl.split))
        except ValueError:
            raise ValueError(f"--engine {setup.profile.name}: its split {pl.split!r} (with these settings) is not a split method of the toolkit") from None
        args.k, args.res = pl.k, int(round(pl.resolution * math.sqrt(pl.k)))
    if camera is not None:
        if "=" in (args.camera or ""):
            args.camera = None
        args.near, args.far, args.fov, args.aspect, args.image_res = camera.near, camera.far, camera.fov, camera.aspect, camera.height
        if setup is not None:
            args.far = max(setup.pipeline.far_i)
        args.f_over_n = args.far / args.near
    if sun is not None:
        args.light = sun.light()


#: What ``render --engine`` takes from the engine's pipeline (its --help and the docs say it).
RENDER_USES = ("render takes the engine's split (by its split name), its cascade count and its texel budget (k maps of R² texels: "
               "--res R·√k) and, with --camera, the last cascade's far; each cascade is then fitted tightly (the papers' fit), not "
               "with the engine's own fit, snap, bias or filter: aliasing check and aliasing engines --engine use those")


def add_render_parser(sub) -> argparse.ArgumentParser:
    """Add the ``render`` subcommand to an ``add_subparsers`` object (of :class:`aliasing.cli._Parser`)."""
    ren = sub.add_parser(
        "render",
        help="picture of a seeded or loaded scene: shadows, projected texel grid, per-pixel error, error distribution",
        description="Render a seeded ground-and-boxes scene (near 1, far = f/n, eye 1 above the ground), or your own scene "
        "(--scene FILE: glTF/GLB, OBJ, PLY, STL) seen by a world-space camera, with one directional light through each "
        "scheme's shadow maps sharing a texel budget of RES² texels; write a PNG (one panel per scheme, titled with its "
        "statistics) and print the statistics table.",
        epilog="schemes: Standard | P | LogP | <warping rule>, alone or after ZP<k>+; FPc|FPcs[+ZP<k>]+P|LogP|Standard; "
        "comma-separated for side-by-side panels; with --splits NAME a warp used in every cascade.  "
        "lights: overhead | behind | front | gamma:DEG[@azimuth:DEG] (eye space), or --light-dir X,Y,Z (world space, towards the light).",
    )
    ren.add_argument("--scheme", default="Standard", help="scheme(s), comma-separated (default Standard)")
    ren.add_argument("--f-over-n", default="100", help="seeded scene: depth ratio far/near (default 100)")
    ren.add_argument("--fov", type=float, default=None, help="FULL (vertical) field of view in degrees (default 60, or the glTF camera's)")
    ren.add_argument("--aspect", type=float, default=1.0, help="image width/height, > 0 (default 1; --fov is then the vertical field of view): the seeded scene's or the --scene camera's image, "
                     "IMAGE_RES rows, shown with square pixels; cdf: over the image's area (every pixel covers the same area)")
    ren.add_argument("--light", default="gamma:60@azimuth:30", help="one eye-space light direction (default gamma:60@azimuth:30)")
    ren.add_argument("--what", choices=["shadows", "grid", "error", "cdf", "bias-margin"], default="shadows",
                     help="picture (default shadows); bias-margin: an engine's bias over each pixel's minimal bias (red: acne, blue: to spare)")
    ren.add_argument("--bias-preset", default="filament", help="engine bias preset of --what bias-margin (default filament; see aliasing bias --list)")
    ren.add_argument("--out", help="output PNG file (required unless --format json)")
    ren.add_argument("--res", type=int, default=1024, help="texel budget as RES² texels over all maps (default 1024; NOT a map's side: "
                     "k maps of R² texels are RES = R·√k; --engine sets it so)")
    ren.add_argument("--image-res", type=int, default=512, help="the image's HEIGHT in pixels (rows; default 512; the width is aspect·rows)")
    ren.add_argument("--every", type=int, default=16, help="grid: texels between grid lines (default 16)")
    ren.add_argument("--seed", type=int, default=1, help="scene seed (default 1)")
    ren.add_argument("--backend", default="numpy", help="how the eye pass and the maps are drawn: numpy (default, the reference), numba (the eye pass; fast extra) or gl (OpenGL, gl extra)")
    scn, cas = ren.add_argument_group("your own scene"), ren.add_argument_group("cascades")
    world.add_scene_arguments(scn, cas, "for every scheme")
    setups.add_arguments(ren, sun=None, camera=False, uses=RENDER_USES)  # --engine: its split, k, texel budget; --camera SPEC, --sun: the view and light
    cas.add_argument("--allocation", choices=["equal", "error"], default="equal", help="texel budget per cascade: equal, or error-based (Lloyd 2007 eq. 83)")
    ren.add_argument("--format", default="text", help="statistics on stdout: text (table) or json (default text)")
    ren.set_defaults(run=_render)
    return ren
