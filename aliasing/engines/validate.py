"""VSM clipmap levels through the rasterizer: measured error against the analytic bound.

The probes of :func:`aliasing.raster.scenes.probes` are rendered by the eye pass
(:func:`aliasing.raster.draw.eye_pass`, W × W pixels); each pixel takes the clipmap level of its
visible point's distance to the camera (:func:`aliasing.engines.vsm.level`), and that
level's uniform map — a square of side 2^(l+3) cm (16384 texels) centred on the camera in
the light's image plane (:func:`aliasing.raster.draw.frame_map`) — gives its map coordinates.
The perspective error is then measured by central differences between neighbouring pixels
on the same probe and level (:func:`aliasing.raster.validate.measure.pixel_errors`, unit
resolutions) and scaled to 16384 texels and W pixels.  Its maximum over the pixels is
compared with :func:`aliasing.engines.vsm.frustum_max` (the corner rays' supremum
2^(1+b)·√(1 + 2tan²θ), or the first level's clamp near the eye).

What this witnesses: the level selection from rasterized positions (distance, not depth),
the texel size per level, and that the pixels reach the bound; the coordinates themselves
are those of :class:`aliasing.raster.draw.LightMap`.

Example
-------
>>> r = validate_vsm(100.0, 10000.0, 60.0, "gamma:60", resolution=64, cells=8)
>>> bool(r["ratio"] <= 1.0 + r["tolerance"])
True
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .. import _validation as check
from .. import geometry
from ..raster.draw import eye_pass, frame_map
from ..raster.scenes import probes
from ..raster.validate.measure import pixel_errors
from ..view import View
from . import vsm

TOLERANCE = 0.02  # finite differences across a probe: relative error of the central difference


def validate_vsm(near: float, far: float, fov: float, light: str | ArrayLike, *, bias: float = 0.0, resolution: int = 128, cells: int = 16, first: int = 6, last: int = 22, unit: str = "cm") -> dict[str, float]:
    """Measured max m of a VSM clipmap on probes vs :func:`vsm.frustum_max`.

    Parameters
    ----------
    near, far : float
        Depth range of the probes [scene units].
    fov : float
        Full field of view [deg].
    light : str or array_like
        One light direction.
    bias : float
        Resolution LOD bias [octaves].
    resolution : int
        Eye image width W [pixels] (also the clipmap's viewport width).
    cells : int
        Probe grid cells per side.

    Returns
    -------
    dict
        ``measured`` (max m over the pixels), ``bound``, ``ratio`` (measured/bound),
        ``tolerance``, ``pixels`` (measured pixels), ``levels`` (distinct levels seen).
    """
    n, f = (float(x) for x in check.frustum(near, far))
    c = vsm.Clipmap(fov, resolution, bias, first, last, unit)
    lv = geometry.lights(light)
    if len(lv) != 1:
        raise ValueError(f"light must be one direction, got {len(lv)}")
    sc = probes(n, f, fov, lv[0], cells=cells)
    eb = eye_pass(sc.triangles, fov, resolution)
    g = np.where(eb.triangle >= 0, sc.group[np.maximum(eb.triangle, 0)], -1)
    pos = np.where((g >= 0)[..., None], eb.position, 1.0)
    level = np.where(g >= 0, vsm.level(c, np.linalg.norm(pos, axis=-1)), np.nan)
    key = np.where(np.isnan(level), -1.0, g * 1000.0 + level)  # same probe and same level
    ok = (g >= 0) & ~np.isnan(level)
    for axis in (0, 1):
        for step in (1, -1):
            ok &= key == np.roll(key, step, axis)
    basis = geometry.light_space(lv)[0]
    measured, levels = 0.0, 0
    for L in np.unique(level[ok]):
        side = float(vsm.texel(c, L)) * vsm.VIRTUAL_RES  # 4·R_l = 2^(l+3) cm
        lm = frame_map(lv[0], basis[2], -side / 2, side / 2, np.inf, -side / 2, side / 2, "uniform")
        sel = ok & (level == L)
        m = pixel_errors(lm, pos, sel, resolution, fov)
        peak = np.nanmax(np.maximum(m["m_x"], m["m_z"])) * resolution / vsm.VIRTUAL_RES  # unit → W px, 16384 texels
        measured, levels = max(measured, float(peak)), levels + 1
    bound = vsm.frustum_max(c, n, f)
    return {"measured": measured, "bound": bound, "ratio": measured / bound, "tolerance": TOLERANCE, "pixels": int(ok.sum()), "levels": levels}


def validate_stable(split: str | ArrayLike, near: float, far: float, fov: float, light: str | ArrayLike, *, k: int | None = None, fit: str = "sphere", resolution: int = 128, cells: int = 16, **options) -> dict[str, object]:
    """Measured M_x, M_z of each cascade of a (stable) fit on probes vs :func:`stable.evaluate`.

    Each pixel on a probe uses the cascade whose split interval holds its eye depth; that
    cascade's uniform map has the fit's sides (:attr:`StableResult.width_x`, ``width_y``),
    centred on the slice's light-space box.  Returns per-map ``ratio_x``, ``ratio_z``
    (measured max / analytic M), ``inside`` (the fraction of the cascade's pixels whose map
    coordinates lie in [0, 1]²: 1 when the fit covers what it must) and ``tolerance``.

    Example
    -------
    >>> r = validate_stable("log", 1.0, 100.0, 60.0, "gamma:60", k=2, fit="sphere", resolution=64, cells=8)
    >>> bool(max(r["ratio_x"]) <= 1 + r["tolerance"])
    True
    """
    from . import stable

    n, f = (float(x) for x in check.frustum(near, far))
    lv = geometry.lights(light)
    if len(lv) != 1:
        raise ValueError(f"light must be one direction, got {len(lv)}")
    res = stable.evaluate(split, n, f, fov, lv, k=k, fit=fit, **options)
    u, v = res.used
    edges = np.append(u, v[-1])
    sc = probes(n, f, fov, lv[0], cells=cells, splits=edges)
    eb = eye_pass(sc.triangles, fov, resolution)
    g = np.where(eb.triangle >= 0, sc.group[np.maximum(eb.triangle, 0)], -1)
    pos = np.where((g >= 0)[..., None], eb.position, 1.0)
    cascade = np.clip(np.searchsorted(v, pos[..., 2], side="left"), 0, len(v) - 1)
    key = np.where(g >= 0, g * 100 + cascade, -1)
    ok = g >= 0
    for axis in (0, 1):
        for step in (1, -1):
            ok &= key == np.roll(key, step, axis)
    basis = geometry.light_space(lv)[0]
    frame = frame_map(lv[0], basis[2], 0.0, 1.0, np.inf, 0.0, 1.0, "uniform").basis  # its x, z axes
    a_fit, b_fit = res.fit_range
    rx, rz, inside = [], [], []
    for i in range(len(v)):
        wx, wy = float(res.width_x[0, i]), float(res.width_y[0, i])
        corners = geometry.frustum_vertices(a_fit[i], b_fit[i], fov)
        xc = 0.5 * (np.min(corners @ frame[0]) + np.max(corners @ frame[0]))  # centred on the slice's box
        yc = 0.5 * (np.min(corners @ frame[2]) + np.max(corners @ frame[2]))
        if fit == "far":  # Filament shadowFar: centred on the camera
            xc = yc = 0.0
        lm = frame_map(lv[0], basis[2], yc - wy / 2, yc + wy / 2, np.inf, xc - wx / 2, xc + wx / 2, "uniform")
        mine = (g >= 0) & (cascade == i)
        sel = ok & mine
        if not sel.any():
            rx, rz, inside = rx + [float("nan")], rz + [float("nan")], inside + [float("nan")]
            continue
        m = pixel_errors(lm, pos, sel, resolution, fov)
        rx.append(float(np.nanmax(m["m_x"]) / res.M_x[0, i]))
        rz.append(float(np.nanmax(m["m_z"]) / res.M_z[0, i]))
        s_all, t_all = m["s"][mine], m["t"][mine]
        eps = 1e-9
        inside.append(float(np.mean((s_all >= -eps) & (s_all <= 1 + eps) & (t_all >= -eps) & (t_all <= 1 + eps))))
    return {"ratio_x": rx, "ratio_z": rz, "inside": inside, "tolerance": TOLERANCE}


def eye_histogram(triangles: ArrayLike, near: float, far: float, fov: float | View, *, resolution: int = 128, bins: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """Depth histogram of a scene's visible pixels from the rasterizer's eye pass (SDSM's input).

    Log-spaced bins over [near, far] (the Intel sample's histogram uses a configurable power
    mapping; log spacing here); pixels outside [near, far] or empty are not counted.  ``fov``
    is the full (vertical) field of view [deg] or a camera's :class:`~aliasing.View`, whose
    aspect widens the eye pass (:func:`aliasing.raster.eye_pass`).

    Example
    -------
    >>> from aliasing.raster.scenes import ground_and_boxes
    >>> sc = ground_and_boxes(near=1.0, far=100.0, boxes=5, seed=1)
    >>> e, c = eye_histogram(sc.triangles, 1.0, 100.0, 60.0, resolution=32, bins=8)
    >>> len(e), int(c.sum()) > 0
    (9, True)
    """
    n, f = (float(x) for x in check.frustum(near, far))
    if isinstance(bins, bool) or int(bins) != bins or bins < 1:
        raise ValueError(f"bins must be a whole number >= 1, got {bins!r}")
    eb = eye_pass(triangles, fov, resolution)
    z = eb.position[..., 2][eb.triangle >= 0]
    edges = np.geomspace(n, f, int(bins) + 1)
    counts, _ = np.histogram(z[(z >= n) & (z <= f)], bins=edges)
    return edges, counts.astype(float)


def scene_pages(triangles: ArrayLike, clipmap: vsm.Clipmap, light: str | ArrayLike, *, resolution: int = 512) -> int:
    """VSM pages a scene marks: the distinct (level, page) of its visible pixels (eye pass).

    Each visible point takes its level from its camera distance and its page from its
    light-plane coordinates on a grid of 128·t_l (aligned at the camera; the engine snaps
    the level's origin to the grid, which shifts pages but not their number by more than the
    border).  ``resolution`` is the sampling image (R × R pixels over the clipmap's view, its
    ``aspect`` included; a page spans tens of pixels at the
    engine's width, so a few hundred pixels per side find every page); the levels use
    ``clipmap.width``.  Sampled at the engine's own width this is what its page marking
    marks: each pixel also marks the pages at floor(p ± δ·d) (``clipmap.dilation`` δ, d the
    engine's dither of one diagonal by the pixel's index bits 0 and 1, as
    ``VirtualShadowMapPageMarking.usf`` does per thread), and the coarse levels' 4 central
    pages are added (:func:`vsm.coarse_pages`, around the camera).

    Against :func:`vsm.ground_pages` (the ground's area in pages plus the 16 coarse pages) on
    a ground quad to 1 km, camera 170 cm up, fov 60, sampled at 512 pixels (measured): width
    512, bias −2: 562 marked vs 634 overhead (×0.89), 501 vs 479 at γ = 60°, azimuth 30°
    (×1.05); without dilation and coarse pages 532 vs 618 (×0.86) and 461 vs 463 (×0.995), so
    the engine's 0.05-page dilation adds 6–9 % marked pages here; bias −3: ×0.70–0.78, as
    pages near the horizon shrink below the pixel spacing and no pixel marks them (the first
    pass measured 640 vs 545, ×1.18, at width 1920, bias 0, sampled at 1920 pixels, without
    dilation or coarse pages).  The area estimate is therefore neither a bound nor exact for
    the engine's marking.

    Example
    -------
    >>> quad = np.array([[[-1e4, -170.0, 1.0], [1e4, -170.0, 1.0], [1e4, -170.0, 1e5]], [[-1e4, -170.0, 1.0], [1e4, -170.0, 1e5], [-1e4, -170.0, 1e5]]])
    >>> scene_pages(quad, vsm.Clipmap(60.0, 1920, 0.0), "overhead", resolution=64) > 0
    True
    """
    lv = geometry.lights(light)
    if len(lv) != 1:
        raise ValueError(f"light must be one direction, got {len(lv)}")
    eb = eye_pass(triangles, View(1.0, 2.0, clipmap.fov, clipmap.aspect), resolution)  # the clipmap's angles (near and far do not clip)
    hit = eb.triangle >= 0
    col = np.broadcast_to(np.arange(hit.shape[1]), hit.shape)[hit]  # the thread index's low bits: the pixel column
    pos = eb.position[hit]
    level = vsm.level(clipmap, np.linalg.norm(pos, axis=-1))
    keep = ~np.isnan(level)
    pos, level, col = pos[keep], level[keep], col[keep]
    page = vsm.PAGE * vsm.texel(clipmap, level)
    basis = geometry.light_space(lv)[0]
    u, v = pos @ basis[0] / page, pos @ basis[2] / page  # page units
    marks = [np.stack([level, np.floor(u), np.floor(v)], axis=-1)]
    if clipmap.dilation > 0:  # PageDilationDither = (bit 0 ? 1 : −1, bit 1 ? 1 : −1)
        du, dv = clipmap.dilation * np.where(col & 1, 1.0, -1.0), clipmap.dilation * np.where(col & 2, 1.0, -1.0)
        marks += [np.stack([level, np.floor(u + s * du), np.floor(v + s * dv)], axis=-1) for s in (1.0, -1.0)]
    if clipmap.coarse is not None:  # MarkCoarsePages: floor/ceil(0 − ½) = pages −1 and 0 around the origin
        lo, hi = max(clipmap.coarse[0], clipmap.first), min(clipmap.coarse[1], clipmap.last)
        marks += [np.array([[L, x, y] for L in range(lo, hi + 1) for x in (-1, 0) for y in (-1, 0)], float).reshape(-1, 3)]
    return len(np.unique(np.concatenate(marks), axis=0))
