"""An engine preset's bias on a rendered scene: acne and peter-panning pixels per cascade, and the per-pixel margin.

The reference is the rasterizer's own shadow test (:func:`aliasing.raster.draw.lookup.shadow_test`:
it compares planes, so it neither acnes nor peter-pans); the preset's is the engines'
depth compare (:func:`aliasing.raster.draw.lookup.depth_test`) with the preset's offsets,
each scaled by the cascade's texel size (the larger side of the map's texel, median over the
cascade's pixels).  A pixel is

* acne: the preset's filtered result darker by more than 0.05 than the same filter with each
  pixel's own minimal bias (:func:`aliasing.bias.map_bias`, × 1.05: acne-free on planes, so
  what remains of the filter is the soft edge of real shadows);
* peter-panning: shadowed in the reference, and the preset's result above one half (a
  filter's soft edge straddles the true shadow boundary and counts as neither).

:func:`bias_margin` is the per-pixel ratio of the preset's bias (as one depth bias,
:func:`aliasing.bias.presets.equivalent_depth`) to the pixel's minimal bias
(:func:`aliasing.bias.map_bias` for the preset's filter): below 1 the surface shows acne,
far above 1 its contacts peter-pan.

Example
-------
>>> from aliasing.pictures import view
>>> v = view(1.0, 30.0, 60.0, "gamma:50@azimuth:20", image_res=48, budget=3 * 128**2, boxes=10)
>>> rows = scene_bias(v, "threejs")
>>> rows[0]["acne_px"] > 0   # three.js' default bias is zero
True
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..raster.draw import MapSampler, depth_test, texel_edges
from ..raster.draw.lookup import light_gradient
from . import presets as _presets
from .plane import map_bias

Array = NDArray[np.float64]


def _offsets(p: _presets.BiasPreset, n: Array, up: Array, w: float, res: int | None = None) -> dict:
    cos = np.abs(n @ up)
    scale = {"one": np.ones_like(cos), "sin": np.sqrt(np.clip(1.0 - cos**2, 0.0, 1.0)), "one-minus-cos": 1.0 - cos}[p.normal_scale]
    return {"bias": p.depth + p.depth_texels * w + _presets._map_side(p, w, res), "normal_offset": (p.normal + p.normal_texels * w) * scale,
            "slope": p.slope, "pcf": p.pcf}


_VIEW_FIELDS = ("scene", "maps", "map_res", "map_resolutions", "partition", "triangle", "position", "normal", "lit", "light")


def _view(v: object) -> None:
    """A rendered view (:class:`aliasing.pictures.View`, a higher layer: checked by its fields)."""
    missing = [f for f in _VIEW_FIELDS if not hasattr(v, f)]
    if missing:
        raise ValueError(f"v must be a rendered view (aliasing.pictures.View), missing {', '.join(missing)}")


def _cascades(v):
    """(index, map, resolution, selected pixels, points, outward normals, cascade texel) per cascade with pixels.

    The eye pass's normals face the eye: the outward normals of the visible side.
    """
    res = v.map_resolutions if v.map_resolutions is not None else np.full(len(v.maps), v.map_res)
    for i, lm in enumerate(v.maps):
        sel = (v.partition == i) & (v.triangle >= 0)
        if not sel.any():
            continue
        p, n = v.position[sel], v.normal[sel]
        e_s, e_t = texel_edges(lm, int(res[i]), p)
        w = float(np.median(np.maximum(np.hypot(*e_s.T), np.hypot(*e_t.T))))
        yield i, lm, int(res[i]), sel, p, n, w


def scene_bias(v, preset: str) -> list[dict]:
    """Acne and peter-panning pixels of ``preset`` per cascade of a rendered view (module docstring).

    Parameters
    ----------
    v : View
        A view rendered with the reference test (:func:`aliasing.pictures.view` or
        :func:`~aliasing.pictures.images.render_view`).
    preset : str
        A bias preset of :data:`aliasing.bias.presets.PRESETS`.

    Returns
    -------
    list of dict
        Per cascade: ``pixels``, ``texel`` [world units], ``acne_px`` and ``acne`` (fraction of
        the cascade's pixels), ``peter_px`` and ``peter`` (fraction of its shadowed pixels).
    """
    _view(v)
    p = _presets.get(preset)
    rows = []
    for i, lm, res, sel, pts, n, w in _cascades(v):
        sm = MapSampler(v.scene.triangles, lm, res)  # drawn at the taps' texels only (the whole map's values)
        up = lm.basis[1]
        q = pts + p.across_texels * w * (n - np.outer(n @ up, up))
        frac = depth_test(lm, sm, q, n, **_offsets(p, n, up, w, res))
        ideal = depth_test(lm, sm, pts, n, bias=1.05 * map_bias(lm, res, pts, n, f"pcf{p.pcf}").depth, pcf=p.pcf)
        ref = v.lit[sel]
        acne, peter = frac < ideal - 0.05, ~ref & (frac > 0.5)
        rows.append({"preset": p.name, "cascade": i, "pixels": int(sel.sum()), "texel": w,
                     "acne_px": int(acne.sum()), "acne": float(acne.sum() / acne.size),
                     "peter_px": int(peter.sum()), "peter": float(peter.sum() / max((~ref).sum(), 1))})
    return rows


def bias_margin(v, preset: str) -> Array:
    """Per pixel: the preset's bias over the minimal bias, (R, R); NaN off the scene and on faces turned from the light.

    Example
    -------
    >>> from aliasing.pictures import view
    >>> v = view(1.0, 30.0, 60.0, "gamma:50@azimuth:20", image_res=32, budget=128**2, boxes=5)
    >>> m = bias_margin(v, "unity-urp")
    >>> m.shape, bool(np.nanmin(m) > 1)   # URP's slope-scaled 2.5 alone covers its 2x2 filter
    ((32, 32), True)
    """
    _view(v)
    p = _presets.get(preset)
    out = np.full(v.triangle.shape, np.nan)
    light = np.asarray(v.light, float)
    for i, lm, res, sel, pts, n, w in _cascades(v):
        facing = (n @ light) > 1e-6  # towards the light
        need = map_bias(lm, res, pts, n, f"pcf{p.pcf}").depth
        grad, cos = light_gradient(lm, n)
        e_s, e_t = texel_edges(lm, res, pts)
        phi = np.degrees(np.arctan2((grad * e_t).sum(-1) / np.hypot(*e_t.T), (grad * e_s).sum(-1) / np.hypot(*e_s.T)))
        theta = np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))
        ok = facing & (theta < 89.9)
        have = np.full(len(pts), np.nan)
        have[ok] = _presets.equivalent_depth(p, w, theta[ok], np.nan_to_num(phi[ok]), res)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(ok, have / need, np.nan)
        out[sel] = ratio
    return out
