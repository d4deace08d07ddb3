"""The engine schemes on a loaded scene: measured perspective error against the analytic bounds.

:mod:`aliasing.engines.validate` renders the probes, which face the bisector of eye and
light so that every bound is reached.  Here the scene is any
:class:`aliasing.raster.scenes.SceneSetup` (a glTF file, the procedural city of
:func:`aliasing.raster.scenes.procedural.city`, any triangle soup), rendered by the eye pass; the
measured pixels are those of :func:`aliasing.raster.validate.scene.validate_scene` (four
neighbours on the same planar face and map, inside [near, far], facing the light).

For a uniform (orthographic) map of side W the perspective error of a pixel at eye depth d
is m = W / (2 tanθ d) at unit resolutions (Lloyd et al. 2006, eq. 2), whatever the
surface's orientation (the projection factor is separate).  A camera of aspect ≠ 1
(width/height, its fov vertical): the cascades are fitted to the wide slices
(:func:`stable.evaluate` with the camera's ``aspect``), the eye pass and the measured error go
through the camera's :class:`~aliasing.View`, and θ stays the vertical half angle (square
pixels of unit vertical resolution); the result then carries ``aspect``.  VSM's clipmap takes
the camera's aspect (:class:`vsm.Clipmap`: the engine's LOD from tan θ_x and the image's
pixels across).  Three checks per map:

``ratio``
    max measured / the map's analytic maximum (at its first used depth u_k, or for VSM the
    clipmap's frustum supremum): ≤ 1 + :data:`TOLERANCE`, the bound holds on the scene;
``reach``
    max measured / the analytic value at the map's nearest measured pixel: within
    1 ± :data:`TOLERANCE` — the bound is reached where the scene has samples (a scene
    without receivers near u_k cannot reach M itself; ``ratio`` then stays below 1);
``pointwise``
    (min, max) over pixels of measured / W/(2 tanθ d): the texel size of the fit, the map
    selection and the depth model, pixel by pixel.

Example
-------
>>> from aliasing.raster import scenes
>>> from aliasing.raster.scenes import procedural
>>> st = scenes.setup(procedural.city(2000, seed=1, size=60.0), eye="-40,6,-35", target="0,0,0", near=0.5, far=90.0, light_dir="-1,0.8,0.3")
>>> r = cascades_on_scene(st, "log", k=3, fit="sphere", res=96)
>>> r["passed"], r["max_ratio"] <= 1 + TOLERANCE
(True, True)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .. import _validation as check
from .. import geometry
from ..raster.draw import check_resolution, frame_map
from ..raster.scenes import SceneSetup
from ..raster.validate.measure import pixel_errors
from ..raster.validate.scene import measurable_pixels
from ..view import View, tan_theta
from . import sdsm, stable, vsm

#: Relative tolerance of the finite differences (:data:`aliasing.raster.validate.scene.TOLERANCE`).
TOLERANCE = 1e-3


def _wide(out: dict, cam) -> dict:
    """A non-square camera's result carries ``aspect`` (as :func:`aliasing.raster.validate.validate_scene`)."""
    return out if cam.aspect == 1.0 else out | {"aspect": float(cam.aspect)}


def _pixels(st: SceneSetup, res: int, assign) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Measurable pixels of the scene (:func:`aliasing.raster.validate.scene.measurable_pixels`), also not before near."""
    eb, pos, part, ok = measurable_pixels(st, res, assign)
    return pos, part, ok & (part >= 0) & (pos[..., 2] >= st.camera.near)


def _summary(rows: list[dict], extra: dict) -> dict:
    out = {key: [row[key] for row in rows] for key in ("ratio_x", "ratio_z", "reach_x", "reach_z", "pointwise_min", "pointwise_max", "inside", "pixels")}
    live = [row for row in rows if row["pixels"]]
    if not live:
        raise ValueError("no measurable pixels: no lit planar surface within [near, far] covers 3 x 3 pixels; raise res or move the camera")
    worst = max(max(r["ratio_x"], r["ratio_z"]) for r in live)
    point = (min(r["pointwise_min"] for r in live), max(r["pointwise_max"] for r in live))
    reach = [x for r in live for x in (r["reach_x"], r["reach_z"])]
    out.update(extra)
    out.update(
        max_ratio=worst, tolerance=TOLERANCE,
        passed=bool(worst <= 1 + TOLERANCE and point[1] <= 1 + TOLERANCE and point[0] >= 1 - TOLERANCE and all(abs(x - 1) <= TOLERANCE for x in reach) and all(r["inside"] == 1.0 for r in live)),
    )
    return out


def cascades_on_scene(st: SceneSetup, split: str | ArrayLike | tuple, *, res: int = 128, k: int | None = None, fit: str = "tight", **options) -> dict:
    """Cascades of a (stable) fit or SDSM partitions on the scene vs :func:`stable.evaluate`.

    Parameters
    ----------
    st : SceneSetup
        The scene in eye space (:func:`aliasing.raster.scenes.setup`).
    split : str, array_like or tuple
        As :func:`aliasing.engines.stable.evaluate` (a split preset, distances, or SDSM's
        (near_i, far_i)); the camera's near and far are the range.
    res : int
        Eye-pass resolution [pixels per side].
    k, fit, **options
        Passed to :func:`stable.evaluate` (snap, resolution, scene, overlap, border,
        dilation, quantize).

    Returns
    -------
    dict
        Per map ``ratio_x``, ``ratio_z``, ``reach_x``, ``reach_z``, ``pointwise_min``,
        ``pointwise_max``, ``inside`` (fraction of the map's pixels inside [0, 1]²),
        ``pixels``; ``max_ratio``, ``tolerance``, ``passed``, ``near_i``, ``far_i``;
        ``aspect`` when the camera's is not 1 (the fits take it).
    """
    r = check_resolution(res, "res")
    if "aspect" in options:
        raise ValueError("aspect is the camera's: give it to the scene's setup (aliasing.raster.scenes.setup(..., aspect=...)), not again")
    cam = st.camera
    lv = st.light[None]
    fit_result = stable.evaluate(split, cam.near, cam.far, cam.fov, lv, k=k, fit=fit, aspect=cam.aspect, **options)
    u, v = fit_result.used
    a_fit, b_fit = fit_result.fit_range

    def assign(pos, hit):  # the map whose used range holds the depth (SDSM: none in the gaps)
        d = pos[..., 2]
        i = np.clip(np.searchsorted(v, d, side="left"), 0, len(v) - 1)
        return np.where(hit & (d >= u[i] * (1 - 1e-12)) & (d <= v[i] * (1 + 1e-12)), i, -1)

    pos, part, ok = _pixels(st, r, assign)
    basis = geometry.light_space(lv)[0]
    t = tan_theta(cam.fov)
    rows = []
    for i in range(len(v)):
        wx, wy = float(fit_result.width_x[0, i]), float(fit_result.width_y[0, i])
        corners = geometry.frustum_vertices(View(a_fit[i], b_fit[i], cam.fov, cam.aspect))  # the camera's slice, wide or square
        xc, yc = (0.5 * (np.min(corners @ basis[j]) + np.max(corners @ basis[j])) for j in (0, 2))  # centred on the slice's box
        if fit == "far":  # Filament's shadowFar sphere is centred on the camera
            xc = yc = 0.0
        lm = frame_map(st.light, basis[2], yc - wy / 2, yc + wy / 2, np.inf, xc - wx / 2, xc + wx / 2, "uniform")
        sel, mine = ok & (part == i), part == i
        if not sel.any():
            rows.append(dict(ratio_x=np.nan, ratio_z=np.nan, reach_x=np.nan, reach_z=np.nan, pointwise_min=np.nan, pointwise_max=np.nan, inside=np.nan, pixels=0))
            continue
        m = pixel_errors(lm, pos, sel, r, cam.view)
        d = pos[..., 2]
        px, pz = m["m_x"] / (wx / (2 * t * d)), m["m_z"] / (wy / (2 * t * d))  # eq. (2), uniform map
        d_min = d[sel].min()
        s_all, t_all = m["s"][mine], m["t"][mine]
        rows.append(dict(
            ratio_x=float(np.nanmax(m["m_x"]) / fit_result.M_x[0, i]), ratio_z=float(np.nanmax(m["m_z"]) / fit_result.M_z[0, i]),
            reach_x=float(np.nanmax(m["m_x"]) / (wx / (2 * t * d_min))), reach_z=float(np.nanmax(m["m_z"]) / (wy / (2 * t * d_min))),
            pointwise_min=float(min(np.nanmin(px), np.nanmin(pz))), pointwise_max=float(max(np.nanmax(px), np.nanmax(pz))),
            inside=float(np.mean((s_all >= -1e-9) & (s_all <= 1 + 1e-9) & (t_all >= -1e-9) & (t_all <= 1 + 1e-9))), pixels=int(sel.sum()),
        ))
    return _wide(_summary(rows, {"near_i": u.tolist(), "far_i": v.tolist()}), cam)


def sdsm_on_scene(st: SceneSetup, method: str = "adaptive", k: int = 4, *, res: int = 128, bins: int = 64, **options) -> dict:
    """SDSM partitions from the scene's own depth histogram (its eye pass), checked by :func:`cascades_on_scene`.

    ``method`` is ``"log"`` (log partitions of the measured [z_min, z_max]), ``"adaptive"``
    or ``"kmeans"`` (:mod:`aliasing.engines.sdsm`); ``options`` are the sample's
    ``border``, ``dilation``, ``quantize``.  Adds ``occupied`` (the measured [z_min, z_max]).

    Example
    -------
    >>> from aliasing.raster import scenes
    >>> from aliasing.raster.scenes import procedural
    >>> st = scenes.setup(procedural.city(2000, seed=1, size=60.0), eye="-40,6,-35", target="0,0,0", near=0.5, far=90.0, light_dir="-1,0.8,0.3")
    >>> sdsm_on_scene(st, "kmeans", 3, res=96)["passed"]
    True
    """
    from .validate import eye_histogram

    kind = check.choice(method, "method", ("log", "adaptive", "kmeans"))
    cam = st.camera
    edges, counts = eye_histogram(st.scene.triangles, cam.near, cam.far, cam.view, resolution=check_resolution(res, "res"), bins=bins)
    filled = np.nonzero(counts)[0]
    if not filled.size:
        raise ValueError("the histogram has no samples: nothing visible within [near, far]")
    z_min, z_max = float(edges[filled[0]]), float(edges[filled[-1] + 1])
    if kind == "log":
        e = sdsm.log_partitions(cam.near, cam.far, z_min, z_max, k)
        parts = (e[:-1], e[1:])
    else:
        parts = (sdsm.adaptive_log if kind == "adaptive" else sdsm.kmeans)(edges, counts, k)
    out = cascades_on_scene(st, parts, res=res, **options)
    out["occupied"] = [z_min, z_max]
    return out


def vsm_on_scene(st: SceneSetup, *, bias: float = 0.0, res: int = 128, first: int = 6, last: int = 22, unit: str = "m") -> dict:
    """A VSM clipmap on the scene: each pixel's level from its camera distance, measured vs analytic.

    The eye image has ``res`` rows; the clipmap's viewport width is the image's pixels
    across, W = round(aspect·res) (``res`` for a square camera), its aspect the camera's;
    the scene's unit is ``unit``.  Per level (as a map): ``ratio`` against
    :func:`vsm.frustum_max` (the clipmap's supremum over the frustum, per pixel of W/aspect
    rows), ``reach`` and ``pointwise`` against m = t_L·W/(2 tanθ_x d) = t_L·(W/aspect)/(2 tanθ_y d)
    (:func:`vsm.m_at`).  Adds ``levels`` (the levels seen) and ``bound``; ``aspect`` when the
    camera's is not 1.

    Example
    -------
    >>> from aliasing.raster import scenes
    >>> from aliasing.raster.scenes import procedural
    >>> st = scenes.setup(procedural.city(2000, seed=1, size=60.0), eye="-40,6,-35", target="0,0,0", near=0.5, far=90.0, light_dir="-1,0.8,0.3")
    >>> vsm_on_scene(st, bias=-1.0, res=96)["passed"]
    True
    """
    r = check_resolution(res, "res")
    cam = st.camera
    wide = float(cam.view.aspect)  # validated by the camera's View
    width = max(1, int(round(wide * r)))  # the image's pixels across (r for a square camera)
    c = vsm.Clipmap(cam.fov, width, bias, first, last, unit, aspect=wide)

    def assign(pos, hit):
        lv = vsm.level(c, np.linalg.norm(pos, axis=-1))
        return np.where(hit & ~np.isnan(lv), np.nan_to_num(lv, nan=-1.0), -1).astype(int)

    pos, level, ok = _pixels(st, r, assign)
    basis = geometry.light_space(st.light[None])[0]
    bound = vsm.frustum_max(c, cam.near, cam.far)
    t = tan_theta(cam.fov)
    rows, seen = [], []
    for L in np.unique(level[ok]):
        side = float(vsm.texel(c, L)) * vsm.VIRTUAL_RES  # 4·R_l, centred on the camera
        lm = frame_map(st.light, basis[2], -side / 2, side / 2, np.inf, -side / 2, side / 2, "uniform")
        sel, mine = ok & (level == L), level == L
        m = pixel_errors(lm, pos, sel, r, cam.view)  # per unit vertical resolution (2 d tanθ_y)
        scale = (width / wide) / vsm.VIRTUAL_RES  # unit resolutions → W/aspect rows (square pixels of W across), 16384 texels
        d = pos[..., 2]
        exact = side / (2 * t * d)  # = vsm.m_at / scale
        px, pz = m["m_x"] / exact, m["m_z"] / exact
        d_min = d[sel].min()
        s_all, t_all = m["s"][mine], m["t"][mine]
        rows.append(dict(
            ratio_x=float(np.nanmax(m["m_x"]) * scale / bound), ratio_z=float(np.nanmax(m["m_z"]) * scale / bound),
            reach_x=float(np.nanmax(m["m_x"]) / (side / (2 * t * d_min))), reach_z=float(np.nanmax(m["m_z"]) / (side / (2 * t * d_min))),
            pointwise_min=float(min(np.nanmin(px), np.nanmin(pz))), pointwise_max=float(max(np.nanmax(px), np.nanmax(pz))),
            inside=float(np.mean((s_all >= 0) & (s_all <= 1) & (t_all >= 0) & (t_all <= 1))), pixels=int(sel.sum()),
        ))
        seen.append(int(L))
    if not rows:
        raise ValueError("no measurable pixels: no lit planar surface within [near, far] covers 3 x 3 pixels; raise res or move the camera")
    return _wide(_summary(rows, {"levels": seen, "bound": bound}), cam)
