"""Per cascade of a setup: the minimal biases, an engine preset's bias, its acne and its peter-panning.

For each map of a cascade setup (:func:`aliasing.raster.draw.cascades.cascade_set`: a split method or an
engine's split preset, any warp) the texel at the middle of the cascade on the view axis
(:func:`aliasing.raster.draw.lookup.texel_edges`: its sides w_s, w_t; warped maps vary across
the map) gives

* the minimal depth bias and normal offset of the ground (``need_depth``, ``need_normal``:
  :func:`aliasing.bias.map_bias`) for the preset's filter;
* the preset's bias on the ground as one depth bias (``preset_depth``:
  :func:`aliasing.bias.presets.equivalent_depth`, with the engine's texel size taken as the
  map's larger side) and their ratio ``margin`` (< 1: the ground shows acne);
* ``acne_from``: the smallest angle θ between a receiver's normal and the light at which the
  preset's bias is too small for some azimuth (NaN: none below 89°);
* ``gap`` and ``gap_px``: the lit gap at the foot of a vertical caster on the ground
  (:func:`aliasing.bias.lit_gap` of the bias along the light), in world units and in pixels
  of an ``image``-pixel view at the cascade's middle depth;
* ``pcf_px``: the filter's footprint, k texels, in those pixels, and ``step``: the texel's growth
  from this cascade to the next at their boundary (the visible seam of the filter's width), both
  from :mod:`aliasing.bias.filtering` (its blend band: ``aliasing bias --filter``);
* ``partial``: "yes" where part of the engine's rule is not modelled (the preset's ``partial``).

Example
-------
>>> rows = cascade_bias(1.0, 100.0, 60.0, "gamma:60", "filament", k=3, resolution=1024)
>>> [r["cascade"] for r in rows], all(r["margin"] > 1 for r in rows)
([0, 1, 2], True)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .. import _validation as check
from ..raster.draw import cascade_set
from ..raster.draw.lookup import light_gradient, texel_edges
from ..view import View
from . import presets as _presets
from .filtering import pcf_footprint, seam_step
from .plane import lit_gap, map_bias

#: Receiver angles θ [deg] and azimuths φ [deg] searched for ``acne_from``.
ANGLES = np.arange(0.0, 89.5, 0.5)
AZIMUTHS = np.arange(0.0, 91.0, 5.0)


def cascade_bias(near: float, far: float, fov: float, light: str | ArrayLike, preset: str = "filament", *, scheme: str = "Standard",
                 splits: str = "practical", k: int | None = 4, resolution: int = 2048, image: int = 1080, aspect: float = 1.0,
                 **params: float) -> list[dict]:
    """Rows, one per cascade, of the minimal biases against ``preset`` (module docstring).

    Parameters
    ----------
    near, far : float
        Eye near and shadow far distances [world units].
    fov : float
        Full (vertical) field of view [deg].
    light : str or array_like
        One light direction (spec or eye-space vector towards the light), above the ground
        (eye-space y is up).
    preset : str
        A bias preset of :data:`aliasing.bias.presets.PRESETS`.
    scheme : str
        Warp inside each cascade (Standard, P, LogP, a warping rule).
    splits : str
        A split method or engine split preset (:data:`aliasing.partitioning.SPLIT_METHODS`).
    k : int or None
        Cascades (None: the split preset's own).
    resolution : int
        Texels per side of each cascade's map.
    image : int
        Pixels across the view, top to bottom (for ``gap_px`` and ``pcf_px``; the image's rows,
        square pixels: aspect·image columns).
    aspect : float
        Image width/height, 0 < aspect < inf (:class:`aliasing.View`; default 1, the square
        view): each cascade's map is fitted to its slice of the wider (or taller) frustum.
    **params
        The split method's parameters (``lam`` for practical, default 0.5).
    """
    p = _presets.get(preset)
    res = check.whole(resolution, "resolution", 2, 1 << 15, " (texels per side)")
    img = check.whole(image, "image", 1, 1 << 16, " (pixels across the view)")
    if splits == "practical" and "lam" not in params:
        params["lam"] = 0.5
    cs = cascade_set(View(near, far, fov, aspect), light, scheme, splits=splits, k=k, **params)  # validated once
    up = np.array([0.0, 1.0, 0.0])
    lookup = f"pcf{p.pcf}"
    half = float(cs.maps.view.tan_theta)  # the view of the cascades, validated once
    rows, texels = [], []
    for i, lm in enumerate(cs.maps.maps):
        lo, hi = float(cs.near_i[i]), float(cs.far_i[i])
        mid = np.array([[0.0, 0.0, 0.5 * (lo + hi)]])
        e_s, e_t = texel_edges(lm, res, mid)
        w_s, w_t = float(np.hypot(*e_s[0])), float(np.hypot(*e_t[0]))
        w = max(w_s, w_t)
        texels.append((w, lm, lo, hi))
        grad, cos = light_gradient(lm, up[None])
        if not cos[0] > np.cos(np.radians(89.9)):
            raise ValueError("light must be above the ground (its elevation over the y = 0 plane > 0.1°)")
        theta = float(np.degrees(np.arccos(min(1.0, cos[0]))))
        g = grad[0]
        phi = float(np.degrees(np.arctan2(g @ (e_t[0] / w_t), g @ (e_s[0] / w_s)))) if np.hypot(*g) > 0 else 0.0
        need = map_bias(lm, res, mid, up[None], lookup)
        have = _presets.equivalent_depth(p, w, theta, phi, res)
        # worst azimuth per angle, with the map's own texel sides
        th, ph = np.meshgrid(np.radians(ANGLES), np.radians(AZIMUTHS), indexing="ij")
        needed = 0.5 * p.pcf * np.tan(th) * (np.abs(np.cos(ph)) * w_s + np.abs(np.sin(ph)) * w_t)
        offered = _presets.equivalent_depth(p, w, np.degrees(th), np.degrees(ph), res)
        short = (offered < needed).any(axis=1)
        pix = 2.0 * float(mid[0, 2]) * half / img
        gap = float(lit_gap(_presets.contact_depth(p, w, res), 90.0 - theta))
        rows.append({
            "preset": p.name, "cascade": i, "near": lo, "far": hi, "texel_s": w_s, "texel_t": w_t,
            "ground_angle": theta, "need_depth": float(need.depth[0]), "need_normal": float(need.normal[0]),
            "preset_depth": float(have), "margin": float(have) / float(need.depth[0]) if need.depth[0] > 0 else float("inf"),
            "acne_from": float(ANGLES[short.argmax()]) if short.any() else float("nan"),
            "gap": gap, "gap_px": float(gap / pix), "pcf_px": float(pcf_footprint(p.pcf, w, pix)), "step": float("nan"),
            "partial": "yes" if p.partial else "no",
        })
    for i in range(len(rows) - 1):  # texel growth across the boundary at far_i, both maps evaluated there
        at = np.array([[0.0, 0.0, rows[i]["far"]]])
        here = max(np.hypot(*v[0]) for v in texel_edges(texels[i][1], res, at))
        there = max(np.hypot(*v[0]) for v in texel_edges(texels[i + 1][1], res, at))
        rows[i]["step"] = float(seam_step(here, there))
    return rows
