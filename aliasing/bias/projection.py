"""Projection aliasing: the full error m·cos ψ_e / cos ψ_l of a receiver of any orientation.

Perspective aliasing m (pixels per texel, px/texel, on a surface facing both eye and light) is only part
of the error: a surface whose normal makes ψ_e with the direction to the eye and ψ_l with the
direction to the light receives texels stretched by 1/cos ψ_l and seen foreshortened by
cos ψ_e (Lloyd et al. 2006 §3.3; Lloyd et al. 2007 eqs. 29–31, the cos ψ_e / cos ψ_l factor of
eq. 19, :func:`aliasing.logpsm.aliasing_error`).

* :func:`projection_factor`: cos ψ_e / cos ψ_l of surface points (eye at the origin);
* :func:`ground_factor`: the ground in closed form, h/(sin α·√(h² + d²)) for an eye h above
  it, a ground point d away horizontally and the light at elevation α;
* a wall *facing* the light has cos ψ_l = cos α; a wall *along* the light (its normal
  perpendicular to the light) has cos ψ_l = 0: the factor has no maximum there (grazing
  light), whatever the map.

Example
-------
>>> round(ground_factor(1.0, 10.0, 30.0), 6)   # h = 1, d = 10, light 30° up: 1/(0.5·√101)
0.199007
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check

Array = NDArray[np.float64]


@check.public
def projection_factor(points: ArrayLike, normals: ArrayLike, light: ArrayLike) -> Array:
    """cos ψ_e / cos ψ_l at eye-space surface points (the eye at the origin).

    Parameters
    ----------
    points, normals : array_like, shape (..., 3)
        Surface points [world units] and normals (any length; the side facing the eye is used).
    light : array_like, shape (3,)
        Direction towards the light (any length).

    Returns
    -------
    ndarray, shape (...)
        The factor; ``inf`` where the light grazes the surface (cos ψ_l = 0), NaN where the
        visible side faces away from the light (in its own shadow: no texel lands there).

    Example
    -------
    >>> projection_factor([[0.0, -1.0, 10.0]], [[0.0, 1.0, 0.0]], [0.0, 1.0, -1.0]).round(6).tolist()
    [0.14072]
    """
    p = check.finite(points, "points")
    n = check.finite(normals, "normals")
    if p.shape[-1:] != (3,) or n.shape != p.shape:
        raise ValueError(f"points and normals must have the same shape (..., 3), got {p.shape} and {n.shape}")
    lv = check.finite(light, "light")
    if lv.shape != (3,) or not np.abs(lv).max() > 0:
        raise ValueError(f"light must be a non-zero vector of shape (3,), got {check._repr(light)}")
    dist = np.linalg.norm(p, axis=-1, keepdims=True)
    length = np.linalg.norm(n, axis=-1, keepdims=True)
    if (dist == 0).any() or (length == 0).any():
        raise ValueError("points must differ from the eye (the origin) and normals must be non-zero")
    e = -p / dist
    n = n / length
    cos_e = (n * e).sum(-1)
    n = np.where((cos_e < 0)[..., None], -n, n)  # the side the eye sees
    cos_e = np.abs(cos_e)
    cos_l = n @ (lv / np.linalg.norm(lv))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(cos_l > 0, cos_e / cos_l, np.where(cos_l == 0, np.inf, np.nan))  # Lloyd 2006 §3.3


@check.public
def ground_factor(height: ArrayLike, distance: ArrayLike, elevation: ArrayLike) -> float | Array:
    """cos ψ_e / cos ψ_l on the ground: h/(sin α·√(h² + d²)).

    Parameters
    ----------
    height : array_like
        Eye height h above the ground [world units], > 0.
    distance : array_like
        Horizontal distance d of the ground point from the eye [world units], ≥ 0.
    elevation : array_like
        Light elevation α above the ground [deg], in (0, 90].
    """
    h = check.as_float_array(height, "height")
    d = check.as_float_array(distance, "distance")
    el = check.as_float_array(elevation, "elevation")
    if not np.isfinite(h).all() or (h <= 0).any():
        raise ValueError(f"height must be a finite eye height > 0 [world units], got {check._show(h)}")
    if not np.isfinite(d).all() or (d < 0).any():
        raise ValueError(f"distance must be a finite distance >= 0 [world units], got {check._show(d)}")
    if not np.isfinite(el).all() or ((el <= 0) | (el > 90)).any():
        raise ValueError(f"elevation must be in (0, 90] degrees, got {check._show(el)}")
    out = h / (np.sin(np.radians(el)) * np.hypot(h, d))
    return float(out) if out.ndim == 0 else out
