"""Schemes rendered and measured on a scene: your own (a loaded mesh, a world-space camera and
light) or the built-in ground and boxes (:func:`builtin`); the one path of ``aliasing render``.

The scene comes placed in eye space (:func:`aliasing.raster.scenes.setup`: file, world camera,
light; :func:`builtin`: the seeded scene in the conventions' eye space).  :func:`render` draws the scene through each scheme's maps (any split method or
engine preset, :mod:`aliasing.raster.draw.cascades`) sharing one texel budget and measures the
perspective aliasing error per pixel on lit surfaces within [near, far]
(:func:`aliasing.pictures.error_field`:
m = max(m_x, m_z)·R_image/R_map [image pixels per texel], the projection factor of the
surface left out as in the analytic model), with :func:`statistics`: its percentiles, the
fraction of pixels at ≤ 1 texel per pixel, and each map's analytic maximum
max(M_x, M_z)·R_image/R_map (Lloyd 2006 eqs. 7–10 at the map's resolution).

Coplanar triangles count as one planar face (:func:`aliasing.raster.scenes.plane_ids`), so
the error's central differences run across a mesh's tessellation, not only inside single
triangles.

Example
-------
>>> from aliasing.raster.scenes import procedural, setup
>>> tri = procedural.city(2000, seed=1, size=100.0)
>>> st = setup(tri, eye="-40,2,-40", target="0,0,0", near=0.5, far=100.0, light_dir="1,2,0.5")
>>> r = render(st, ["Standard", "LogP"], budget=128**2, image_res=48)
>>> [x.label for x in r], r[0].stats["max"] >= r[0].stats["p99"] >= r[0].stats["p50"] > 0
(['Standard', 'LogP'], True)
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _table as _tables
from .. import _validation as check
from .. import geometry
from .. import partitioning
from ..sweep import store
from ..raster.scenes.camera import Camera, check_raster_frustum
from ..raster.draw.cascades import CascadeSet, budget_shares, cascade_set
from .images import BIAS, View, error_field, render_view
from ..raster.scenes.world import MIN_COS_LIGHT, SceneSetup, json_safe, plane_ids, setup
from ..view import View as Frustum

Array = NDArray[np.float64]

PERCENTILES = (50, 90, 99)


@dataclass(frozen=True)
class SchemeRender:
    """One scheme on the scene: ``label``, its ``view``, ``cascades``, map ``resolutions``
    [texels per side], per-pixel ``error`` (R, R, row 0 at the bottom; NaN where not
    measured, beyond far or on surfaces not facing the light, :data:`MIN_COS_LIGHT`), ``stats``
    and ``measured`` (R, R): the pixels where the error is measured, on the scene within far
    and facing the light (the error is NaN there only at a face's border)."""

    label: str
    view: View
    cascades: CascadeSet
    resolutions: NDArray[np.int64]
    error: Array
    stats: dict = field(default_factory=dict)
    measured: NDArray[np.bool_] | None = None


def render(st: SceneSetup, schemes_: list[str], *, splits: str | None = None, k: int | None = None, allocation: str = "equal", budget: int = 1024**2,
           image_res: int = 512, bias: float = BIAS, backend: str = "numpy", **params: float) -> list[SchemeRender]:
    """Render and measure each scheme on the scene, all sharing ``budget`` texels.

    ``splits``, ``k``, ``params``: the partitions of every scheme (a split method or engine
    preset, :func:`aliasing.raster.draw.cascades.cascade_set`); ``allocation``: ``equal`` or
    ``error`` (:func:`aliasing.raster.draw.cascades.budget_shares`); ``backend``: how the eye
    pass and the maps are drawn (:func:`aliasing.pictures.images.render_view`).
    """
    if not schemes_:
        raise ValueError("schemes must name at least one scheme")
    cam = st.camera
    out = []
    for name in schemes_:
        cs = cascade_set(cam.view, st.light, name.strip(), splits=splits, k=k, **params)
        res = budget_shares(cs, budget, allocation)
        v = render_view(st.scene, cs.maps, res, image_res=image_res, bias=bias, ground=st.ground, faces=st.faces, backend=backend)
        if not (v.triangle >= 0).any():
            raise ValueError("no triangles in front of the camera: the image is empty")
        facing = np.nan_to_num(v.normal) @ st.light > MIN_COS_LIGHT  # lit side, not grazing the light
        measured = (v.triangle >= 0) & (v.position[..., 2] <= cam.far) & facing  # shadows end at far
        err = np.where(measured, error_field(v), np.nan)
        out.append(SchemeRender(cs.label, v, cs, res, err, statistics(err, cs, res, v, budget), measured))
    return out


def statistics(err: ArrayLike, cs: CascadeSet, resolutions: ArrayLike, v: View, budget: int) -> dict:
    """Percentiles (50/90/99), max and fraction ≤ 1 of the measured error [pixels per texel],
    with each map's depth range, side, budget share, pixel share and analytic maximum."""
    e = np.asarray(err, float)
    e = e[np.isfinite(e)]
    res = np.asarray(resolutions, float)
    image_res = v.position.shape[0]
    analytic = np.maximum(cs.M_x, cs.M_z) * image_res / res  # Lloyd 2006 eqs. (7)-(10) at resolution res
    hit = v.partition >= 0
    pix = np.array([(v.partition == i).sum() for i in range(len(res))], float) / max(int(hit.sum()), 1)
    out = {"scheme": cs.label, "maps": len(res), "pixels_measured": int(e.size)}
    for p in PERCENTILES:
        out[f"p{p}"] = float(np.percentile(e, p)) if e.size else float("nan")
    out["max"] = float(e.max()) if e.size else float("nan")
    out["frac_le_1"] = float((e <= 1.0).mean()) if e.size else float("nan")
    used = pix > 0
    out["analytic_max"] = float(analytic[used].max()) if used.any() else float("nan")
    out["cascades"] = [
        {"map": i, "near": float(cs.near_i[i]), "far": float(cs.far_i[i]), "side": int(res[i]), "budget_share": float(res[i] ** 2 / budget),
         "pixel_share": float(pix[i]), "analytic_max": float(analytic[i])}
        for i in range(len(res))
    ]
    return out


def table(renders: list[SchemeRender]) -> str:
    """The statistics as aligned text: one row per scheme, then one per cascade."""
    keys = ["scheme", "maps", "p50", "p90", "p99", "max", "frac_le_1", "analytic_max"]
    rows = [keys] + [[_cell(r.stats[k]) for k in keys] for r in renders]
    text = _tables.aligned(rows)
    text += "errors: measured perspective error [image pixels per texel] (p50/p90/p99/max over measured pixels); frac_le_1: share at <= 1\n"
    ck = ["scheme", "map", "near", "far", "side", "budget_share", "pixel_share", "analytic_max"]
    crow = [ck] + [[_cell(r.label)] + [_cell(c[k]) if k not in ("near", "far") or np.isfinite(c[k]) else "—" for k in ck[1:]] for r in renders for c in r.stats["cascades"]]
    text += "\n" + _tables.aligned(crow)
    if any(not np.isfinite(c["near"]) for r in renders for c in r.stats["cascades"]):
        text += "near, far: each map's eye-depth range; — for a face partition's map, which covers one face of the frustum, not a depth slice\n"
    return text


def _cell(v: object) -> str:
    return _tables.cell(v)


# ----------------------------------------------------------------------------- pictures and CLI


#: Resolution [dots per inch] :func:`run` saves the figure at; :func:`figure` sizes the panels for it.
DPI = 110
#: Smallest side of an image panel [inches] (small renders are enlarged to it).
PANEL_MIN = 3.2


def figure(renders: list[SchemeRender], what: str = "shadows", *, every: int = 16, vmax: float = 64.0, preset: str = "filament"):
    """Side-by-side panels of the schemes (``shadows``, ``grid``, ``error``, ``bias-margin``: an
    engine ``preset``'s bias over each pixel's minimal bias) or their per-pixel error
    distributions on one plot (``cdf``); returns the matplotlib Figure.

    Each panel is titled with its scheme and statistics and is at least the image's size at
    :data:`DPI` (no pixel of the render is lost when saved at that resolution); ``error`` has a
    colour bar, ``grid`` a legend of the maps.  A non-square view's R × R pixels are aspect : 1
    wide: its panels show round(aspect·R) × R square pixels, and its ``cdf`` is over the R × R
    pixels, each covering the same share of the image's area (the distribution over the area).
    """
    from .biasmargin import SPAN, margin_of
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Patch

    from .images import GRID_COLOURS, cdf, error_of, grid_of, shade

    kind = check.choice(what, "what", dict.fromkeys(("shadows", "grid", "error", "cdf", "bias-margin")))
    if kind == "cdf":
        fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
        for r in renders:
            xs, ys = cdf(r.error)
            ax.plot(xs, ys, label=f"{r.label} (max {r.stats['max']:.3g}, bound {r.stats['analytic_max']:.3g})")
        ax.axvline(1.0, color="0.5", lw=0.8, ls=":")
        ax.set(xscale="log", xlabel="measured perspective error [image pixels per texel]", ylabel="fraction of measured pixels", ylim=(0, 1.02))
        ax.legend(fontsize=7, loc="lower right")
        return fig
    n = len(renders)
    rows = renders[0].view.position.shape[0]
    side = max(rows / DPI * 1.04, PANEL_MIN)  # [inches]: the image's pixels and some room
    tall = side
    shown = float(renders[0].cascades.maps.view.aspect)
    if shown != 1.0:  # a non-square image (round(aspect·R) × R square pixels): the panel takes its shape, no pixel lost, none side under PANEL_MIN
        columns = max(1, round(shown * rows))
        scale = max(1.04 / DPI, PANEL_MIN / min(columns, rows))
        side, tall = columns * scale, rows * scale
    legend = 0.2 + 0.16 * np.ceil(max(len(r.resolutions) for r in renders) / 2) if kind == "grid" else 0.0
    width = n * (side + 0.15) + (1.1 if kind in ("error", "bias-margin") else 0.0)
    fig, axes = plt.subplots(1, n, figsize=(width, tall + 0.55 + legend), dpi=DPI, layout="constrained", squeeze=False)
    for ax, r in zip(axes[0], renders):
        if kind == "shadows":
            img = np.clip(shade(r.view)[::-1], 0, 1)
        elif kind == "grid":
            img = grid_of(r.view, every, wash=0.45)
        elif kind == "bias-margin":
            img = margin_of(r.view, preset)[0]
        else:
            img = error_of(r.view, vmax)[0]
            unmeasured = (r.view.triangle >= 0) & ~(r.measured if r.measured is not None else np.isfinite(r.error))
            img = np.where(unmeasured[::-1, :, None], 0.6 * img + 0.25, img)  # greyed: facing away from the light, or beyond far
        aspect = float(r.cascades.maps.view.aspect)
        if aspect != 1.0:  # the R x R pixels of a non-square view are aspect : 1 wide: shown as round(aspect·R) square pixels per row
            width = max(1, round(aspect * img.shape[1]))
            img = img[:, ((np.arange(width) + 0.5) * img.shape[1] / width).astype(int)]
        ax.imshow(img, interpolation="nearest")
        ax.set_xticks([]), ax.set_yticks([])
        s = r.stats
        ax.set_title(f"{r.label}\np99 {s['p99']:.3g}, max {s['max']:.3g} px/texel, ≤1: {100 * s['frac_le_1']:.0f}%", fontsize=8)
        if kind == "grid":
            cs = r.cascades
            handles = [Patch(color=GRID_COLOURS[i % len(GRID_COLOURS)], label=f"map {i}: {_range(cs, i)}, {r.resolutions[i]}²") for i in range(len(r.resolutions))]
            ax.legend(handles=handles, fontsize=6, loc="upper center", bbox_to_anchor=(0.5, -0.01), ncol=2, frameon=False)
    if kind == "error":
        sm = plt.cm.ScalarMappable(norm=LogNorm(1.0, vmax), cmap="jet")
        cb = fig.colorbar(sm, ax=axes[0].tolist(), shrink=0.8, label="perspective error [pixels per texel] (grey: not measured)")
        ticks = 2.0 ** np.arange(0, np.floor(np.log2(vmax)) + 1)  # 1, 2, 4, … : a labelled tick per doubling
        cb.set_ticks(ticks, labels=[f"{t:g}" for t in ticks])
        cb.minorticks_off()
    if kind == "bias-margin":
        sm = plt.cm.ScalarMappable(norm=LogNorm(2.0 ** -SPAN, 2.0 ** SPAN), cmap="RdBu")
        cb = fig.colorbar(sm, ax=axes[0].tolist(), shrink=0.8, label=f"{preset} bias / minimal bias\n(red: acne; blue: to spare, a lit gap at contacts)")
        ticks = 2.0 ** np.arange(-SPAN, SPAN + 1)
        cb.set_ticks(ticks, labels=[f"{t:g}" for t in ticks])
        cb.minorticks_off()
    return fig


def _range(cs: CascadeSet, i: int) -> str:
    if np.isnan(cs.near_i[i]):
        return "face map"
    return f"{cs.near_i[i]:.3g}–{cs.far_i[i]:.3g}"


def report(st: SceneSetup, renders: list[SchemeRender], *, budget: int, allocation: str, splits: str | None, light: str | None = None) -> dict:
    """JSON-ready numbers of a render: the view, the light (γ as typed in ``light``, a spec), and each scheme's statistics."""
    cam = st.camera
    return {
        "source": st.source, "triangles": int(len(st.scene.triangles)), "degenerate_skipped": st.degenerate,
        "camera": {"name": cam.name, "eye": cam.eye.tolist(), "forward": cam.rotation[2].tolist(), "up": cam.rotation[1].tolist(),
                   "near": cam.near, "far": cam.far, "fov": cam.fov} | ({} if cam.aspect == 1.0 else {"aspect": float(cam.aspect)}),
        "light_eye_space": st.light.tolist(), "gamma": float(geometry._typed_angles(light)[0][0]) if isinstance(light, str) else float(np.degrees(np.arccos(np.clip(st.light[2], -1, 1)))),
        "budget": int(budget), "allocation": allocation, "splits": splits, "image_res": int(renders[0].view.position.shape[0]),
        "schemes": [json_safe(r.stats) for r in renders],
    }


#: Ground cells per side of the built-in scene (its first 2·16² triangles are the ground).
GROUND_CELLS = 16


def builtin(near: float, far: float, fov: float, light: str | ArrayLike, *, seed: int = 1, aspect: float = 1.0) -> SceneSetup:
    """The built-in scene (:func:`~aliasing.raster.scenes.builtin.ground_and_boxes`, 40 boxes) in eye space as a
    :class:`SceneSetup`: the eye at the origin looking along +z, near/far [world units], ``fov`` [deg] (vertical),
    ``aspect`` (width/height), one light.

    Example
    -------
    >>> st = builtin(1.0, 50.0, 60.0, "gamma:60", seed=1)
    >>> st.ground, st.camera.far, len(st.scene.triangles) > st.ground
    (512, 50.0, True)
    """
    from ..raster.scenes.builtin import ground_and_boxes

    frustum = Frustum(near, far, fov, aspect)
    n, f, fv = float(frustum.near), float(frustum.far), float(frustum.fov)
    check_raster_frustum(n, f, fv)  # before the scene is built
    ls = geometry.lights(light)
    if ls.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {ls.shape[0]}")
    sc = ground_and_boxes(frustum, seed=seed, boxes=40, ground_cells=GROUND_CELLS)
    cam = Camera(np.zeros(3), np.eye(3), n, f, fv, "eye space", float(frustum.aspect))
    return SceneSetup(sc, plane_ids(sc.triangles), cam, ls[0], ground=2 * GROUND_CELLS**2)


def run(args) -> int:
    """``aliasing render``: the built-in scene or a loaded one, one scheme or several, any splits.

    Every picture is :func:`figure`'s (panels titled with the scheme and its statistics) and
    the statistics go to standard output (:func:`table`, or JSON with ``--format json``).
    """
    import json
    import sys
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fmt = check.choice(args.format, "format", dict.fromkeys(("text", "json")))
    out = None if args.out is None else Path(args.out)
    if out is not None and out.suffix.lower() != ".png":
        raise ValueError(f"--out must be a .png file, got {args.out!r}")
    if out is None and fmt != "json":
        raise ValueError("--out FILE.png is required (or --format json for the numbers alone)")
    if out is not None and out.parent.is_dir() and store.resolve_out(out, "--out") is None:  # refused before any work
        raise ValueError("--out must be a .png file, not standard output")
    light = None if args.light_dir is not None else args.light
    if args.scene is not None:
        st = setup(args.scene, eye=args.eye, target=args.target, up=args.up, camera=args.camera, near=args.near, far=args.far, fov=args.fov,
                   light_dir=args.light_dir, light=light, aspect=args.aspect)
    else:
        for flag, value in (("--eye", args.eye), ("--target", args.target), ("--camera", args.camera), ("--light-dir", args.light_dir)):
            if value is not None:
                raise ValueError(f"{flag} needs --scene FILE (the seeded scene is in eye space)")
        if args.far is None and args.near is None and not float(args.f_over_n) > 1:
            raise ValueError(f"--f-over-n must be > 1, got {args.f_over_n!r}")
        f = float(args.f_over_n) if args.far is None else float(args.far)
        st = builtin(1.0 if args.near is None else float(args.near), f, 60.0 if args.fov is None else float(args.fov), light, seed=args.seed, aspect=args.aspect)
    names = [s.strip() for s in args.scheme.split(",") if s.strip()]
    params = partitioning.split_params(args.lam, args.param)
    if args.splits is None and (args.k is not None or params):
        raise ValueError("-k, --lambda and --param need --splits NAME (see aliasing splits --list)")
    budget = int(args.res) ** 2
    renders = render(st, names, splits=args.splits, k=args.k, allocation=args.allocation, budget=budget, image_res=args.image_res, backend=args.backend, **params)
    if out is not None:
        fig = figure(renders, args.what, every=args.every, preset=getattr(args, "bias_preset", "filament"))
        try:  # the sweep's safe writer (store): atomic, symlinks followed, devices refused, one-line errors
            out.parent.mkdir(parents=True, exist_ok=True)
            target = store.resolve_out(out, "--out")
            if target is None:
                raise ValueError("--out must be a .png file, not standard output")
            with store.atomic_target(target) as tmp:
                fig.savefig(tmp, format="png", dpi=DPI, bbox_inches="tight", pad_inches=0.1, metadata={"Software": None})
        except OSError as exc:
            raise ValueError(f"--out {args.out!r} cannot be written: {exc.strerror}") from None
        finally:
            plt.close(fig)
    if fmt == "json":
        sys.stdout.write(json.dumps(report(st, renders, budget=budget, allocation=args.allocation, splits=args.splits, light=light), indent=1) + "\n")
    else:
        print(out)
        if st.degenerate:
            print(f"skipped {st.degenerate} degenerate triangles")
        sys.stdout.write(table(renders))
    return 0

