"""``aliasing render``: the command line of the pictures (seeded or loaded scenes)."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np


from ... import _validation as check
from ...sweep import store
from ..scenes import world
from ..scenes.camera import check_raster_frustum
from .images import error_image, grid_image, shadow_image
from .scenerender import run
from ...view import View, check_aspect


def _render(args: argparse.Namespace) -> int:
    try:  # parsed once here, for both paths below (float() alone named no option)
        args.f_over_n = float(args.f_over_n)
    except ValueError:
        raise ValueError(f"--f-over-n must be a number, got {args.f_over_n!r}") from None
    if args.seed < 0:
        raise ValueError(f"--seed must be a whole number >= 0, got {args.seed}")
    aspect = float(check_aspect(args.aspect))
    if args.scene is not None or "," in args.scheme or args.splits is not None or args.what == "cdf" or args.format != "text" \
            or any(v is not None for v in (args.eye, args.target, args.camera, args.light_dir, args.k, args.lam, args.near, args.far)) or args.param:
        if aspect != 1.0:
            raise ValueError("--aspect applies to one scheme's picture of the seeded scene (no --scene, --splits, cdf, several schemes or --format json)")
        return run(args)
    if args.out is None:
        raise ValueError("--out FILE.png is required")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f_over_n = float(args.f_over_n)
    if not f_over_n > 1:
        raise ValueError(f"--f-over-n must be > 1, got {args.f_over_n!r}")
    out = Path(args.out)
    if out.suffix.lower() != ".png":
        raise ValueError(f"--out must be a .png file, got {args.out!r}")
    if out.exists() and out.is_dir():
        raise ValueError(f"--out must be a file, but {args.out!r} is a folder")
    kw = dict(image_res=args.image_res, budget=args.res**2, seed=args.seed)
    frustum = View(1.0, f_over_n, 60.0 if args.fov is None else args.fov, aspect)
    check_raster_frustum(frustum.near, frustum.far, frustum.fov)
    if args.what == "shadows":
        img = shadow_image(frustum, args.light, args.scheme, **kw)
    elif args.what == "grid":
        img = grid_image(frustum, args.light, args.scheme, every=args.every, **kw)
    else:
        img, _ = error_image(frustum, args.light, args.scheme, **kw)
    if aspect != 1.0:  # the R x R pixels are aspect : 1 wide: shown as round(aspect·R) square pixels per row
        width = max(1, round(aspect * img.shape[1]))
        img = img[:, ((np.arange(width) + 0.5) * img.shape[1] / width).astype(int)]
    # the sweep's safe writer (store): atomic, symlinks followed, devices refused, one-line errors
    try:
        out.parent.mkdir(parents=True, exist_ok=True)
        target = store.resolve_out(out, "--out")
        if target is None:
            raise ValueError("--out must be a .png file, not standard output")
        with store.atomic_target(target) as tmp:
            plt.imsave(tmp, img, format="png", metadata={"Software": None})
    except OSError as exc:
        raise ValueError(f"--out {args.out!r} cannot be written: {exc.strerror}") from None
    print(out)
    return 0


def add_render_parser(sub) -> argparse.ArgumentParser:
    """Add the ``render`` subcommand to an ``add_subparsers`` object (of :class:`aliasing.cli._Parser`)."""
    ren = sub.add_parser(
        "render",
        help="picture of a seeded or loaded scene: shadows, projected texel grid, per-pixel error, error distribution",
        description="Render a seeded ground-and-boxes scene (near 1, far = f/n, eye 1 above the ground), or your own scene "
        "(--scene FILE: glTF/GLB, OBJ, PLY, STL) seen by a world-space camera, with one directional light through each "
        "scheme's shadow maps sharing a texel budget of RES² texels; write a PNG (schemes side by side) and a statistics table.",
        epilog="schemes: Standard | P | LogP | <warping rule>, alone or after ZP<k>+; FPc|FPcs[+ZP<k>]+P|LogP|Standard; "
        "comma-separated for side-by-side panels; with --splits NAME a warp used in every cascade.  "
        "lights: overhead | behind | front | gamma:DEG[@azimuth:DEG] (eye space), or --light-dir X,Y,Z (world space, towards the light).",
    )
    ren.add_argument("--scheme", default="Standard", help="scheme(s), comma-separated (default Standard)")
    ren.add_argument("--f-over-n", default="100", help="seeded scene: depth ratio far/near (default 100)")
    ren.add_argument("--fov", type=float, default=None, help="FULL (vertical) field of view in degrees (default 60, or the glTF camera's)")
    ren.add_argument("--aspect", type=float, default=1.0, help="image width/height, > 0 (default 1): one scheme's picture of the seeded scene, IMAGE_RES rows")
    ren.add_argument("--light", default="gamma:60@azimuth:30", help="one eye-space light direction (default gamma:60@azimuth:30)")
    ren.add_argument("--what", choices=["shadows", "grid", "error", "cdf"], default="shadows", help="picture (default shadows)")
    ren.add_argument("--out", help="output PNG file (required unless --format json)")
    ren.add_argument("--res", type=int, default=1024, help="texel budget as RES² texels over all maps (default 1024)")
    ren.add_argument("--image-res", type=int, default=512, help="image resolution in pixels per side (default 512)")
    ren.add_argument("--every", type=int, default=16, help="grid: texels between grid lines (default 16)")
    ren.add_argument("--seed", type=int, default=1, help="scene seed (default 1)")
    scn, cas = ren.add_argument_group("your own scene"), ren.add_argument_group("cascades")
    world.add_scene_arguments(scn, cas, "for every scheme")
    cas.add_argument("--allocation", choices=["equal", "error"], default="equal", help="texel budget per cascade: equal, or error-based (Lloyd 2007 eq. 83)")
    ren.add_argument("--format", default="text", help="statistics on stdout: text (table) or json (default text)")
    ren.set_defaults(run=_render)
    return ren
