"""The minimal depth bias and normal offset of a planar receiver, and the lit gap a bias costs.

Derived in :mod:`aliasing.symbolic.bias` from one texel's geometry (the guide's "Depth bias"
page).  A planar receiver whose normal makes the angle θ with the direction to the light,
seen through a map whose texels are w world units wide there, with its depth increasing
fastest along the azimuth φ from the map's s axis, needs

* nearest lookup: a constant depth bias b = (w/2)·tan θ·(|cos φ| + |sin φ|), or a normal
  offset o = b·cos θ = (w/2)·sin θ·(|cos φ| + |sin φ|);
* k×k PCF: k times those;
* receiver-plane depth bias (any k): those of nearest lookup.

A constant depth bias b leaves a lit gap of b·cos α at the foot of a vertical caster on
horizontal ground lit at elevation α (peter-panning); a normal offset o shortens the shadow by
o/tan α at its far end (:func:`edge_shift`, any engine's whole rule).

Example
-------
>>> pb = plane_bias(0.1, 45.0)
>>> round(pb.depth, 6), round(pb.normal, 6)
(0.05, 0.035355)
>>> round(lit_gap(pb.depth, 45.0), 6)
0.035355
"""

from __future__ import annotations

import re
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from ..raster.draw.lookup import PCF_MAX, light_gradient, texel_edges
from ..raster.draw.lightmap import LightMap

Array = NDArray[np.float64]

#: The lookups: ``nearest``, ``pcf<k>`` (k×k percentage-closer filtering, k = 1 … 15) and
#: ``receiver-plane`` (PCF of any width with receiver-plane depth bias).
LOOKUPS = ("nearest", "pcf<k>", "receiver-plane")


class PlaneBias(NamedTuple):
    """Minimal biases that leave a planar receiver free of acne [world units]."""

    depth: float | Array  #: constant depth bias along the light
    normal: float | Array  #: normal offset


def kernel(lookup: str) -> tuple[int, bool]:
    """(k, receiver_plane) of a lookup name (:data:`LOOKUPS`); ValueError names ``lookup``.

    Example
    -------
    >>> kernel("nearest"), kernel("PCF3"), kernel("receiver-plane")
    ((1, False), (3, False), (1, True))
    """
    if not isinstance(lookup, str):
        raise ValueError(f"lookup must be a string, one of: {', '.join(LOOKUPS)}; got {check._repr(lookup)}")
    key = lookup.strip().lower()
    if key == "nearest":
        return 1, False
    if key in ("receiver-plane", "receiver_plane", "rpdb"):
        return 1, True
    m = re.fullmatch(r"pcf(\d{1,2})", key)
    if m and 1 <= int(m.group(1)) <= PCF_MAX:
        return int(m.group(1)), False
    raise ValueError(f"unknown lookup {lookup!r}; choose one of: nearest, pcf<k> (k = 1 … {PCF_MAX}), receiver-plane")


def _angle(value: ArrayLike, name: str, what: str) -> Array:
    arr = check.as_float_array(value, name)
    if not np.isfinite(arr).all() or ((arr < 0) | (arr >= 90)).any():
        raise ValueError(f"{name} must be in [0, 90) degrees ({what}), got {check._show(arr)}")
    return arr


def _receiver(texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike) -> tuple[Array, Array, Array]:
    """(w, θ [rad], φ [rad]) of a planar receiver, validated and broadcast: the texel width
    [world units] > 0, θ to the light in [0°, 90°), φ from the map's s axis."""
    w = check.as_float_array(texel, "texel")
    if not np.isfinite(w).all() or (w <= 0).any():
        raise ValueError(f"texel must be a finite texel width > 0 [world units], got {check._show(w)}")
    theta = np.radians(_angle(angle, "angle", "between the receiver's normal and the direction to the light"))
    phi = np.radians(check.finite(azimuth, "azimuth"))
    return np.broadcast_arrays(w, theta, phi)


def _out(arr: Array) -> float | Array:
    return float(arr) if arr.ndim == 0 else arr


@check.public
def plane_bias(texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike = 0.0, lookup: str = "nearest") -> PlaneBias:
    """Minimal constant depth bias and normal offset that leave a planar receiver free of acne.

    Derived from the texel's corners (:mod:`aliasing.symbolic.bias`): ``depth`` =
    (k/2)·w·tan θ·(|cos φ| + |sin φ|) and ``normal`` = depth·cos θ, with k the kernel width
    (1 for nearest and receiver-plane lookups).  Any smaller bias shadows part of the plane.

    Parameters
    ----------
    texel : array_like
        Width w of a texel at the receiver [world units], > 0.
    angle : array_like
        θ between the receiver's normal and the direction to the light [deg], in [0, 90).
    azimuth : array_like
        φ, the direction of the receiver's steepest depth change from the map's s axis [deg].
    lookup : str
        ``nearest``, ``pcf<k>`` or ``receiver-plane`` (:data:`LOOKUPS`).

    Returns
    -------
    PlaneBias
        ``depth`` and ``normal`` [world units], broadcast over the inputs.

    Example
    -------
    >>> plane_bias(0.2, 60.0, 45.0, "pcf3").depth.__round__(6)   # 3 · 0.1 · tan 60° · √2
    0.734847
    >>> plane_bias(0.2, 0.0).depth   # facing the light: no bias needed
    0.0
    """
    k, _ = kernel(lookup)
    w, theta, phi = _receiver(texel, angle, azimuth)
    spread = 0.5 * k * w * (np.abs(np.cos(phi)) + np.abs(np.sin(phi)))
    return PlaneBias(_out(spread * np.tan(theta)), _out(spread * np.sin(theta)))


@check.public
def slope_factor(azimuth: ArrayLike = 0.0, lookup: str = "nearest") -> float | Array:
    """Minimal slope-scaled bias factor on max(|∂d/∂s|, |∂d/∂t|) per texel (Direct3D's slope-scaled bias).

    (k/2)·(|cos φ| + |sin φ|)/max(|cos φ|, |sin φ|): k/2 for a slope along a map axis, k at 45°,
    whatever the tilt θ.

    Example
    -------
    >>> slope_factor(0.0), slope_factor(45.0), slope_factor(0.0, "pcf5")
    (0.5, 1.0, 2.5)
    """
    k, _ = kernel(lookup)
    phi = np.radians(check.finite(azimuth, "azimuth"))
    c, s = np.abs(np.cos(phi)), np.abs(np.sin(phi))
    return _out(np.round(0.5 * k * (c + s) / np.maximum(c, s), 15))


@check.public
def lit_gap(depth_bias: ArrayLike, elevation: ArrayLike, thickness: ArrayLike = 0.0) -> float | Array:
    """Lit gap [world units] at the foot of a vertical caster on horizontal ground: b·cos α (− D).

    A ground point at distance g behind the caster's foot sees the caster g/cos α nearer the
    light along its ray; a constant depth bias b keeps it lit while g/cos α ≤ b
    (:mod:`aliasing.symbolic.bias`, ``bias.lit_gap``).  The map stores the caster's surface
    nearest the light: through a caster of thickness D (a box's extent along the light's
    horizontal direction) the gap shrinks to max(0, b·cos α − D).  For casters taller than b·sin α.

    Parameters
    ----------
    depth_bias : array_like
        Constant depth bias b along the light [world units], ≥ 0.
    elevation : array_like
        α, the light's elevation above the ground [deg], in (0, 90]: the ground's normal makes
        90° − α ∈ [0, 90) with the direction to the light.
    thickness : array_like
        D, the caster's thickness along the light's horizontal direction [world units], ≥ 0
        (0: a wall or a fence).

    Example
    -------
    >>> lit_gap([0.1, 0.1], [30.0, 90.0]).round(6).tolist()
    [0.086603, 0.0]
    >>> round(lit_gap(0.1, 30.0, thickness=0.05), 6)
    0.036603
    """
    b = check.as_float_array(depth_bias, "depth_bias")
    if not np.isfinite(b).all() or (b < 0).any():
        raise ValueError(f"depth_bias must be a finite bias >= 0 [world units], got {check._show(b)}")
    el = check.as_float_array(elevation, "elevation")
    if not np.isfinite(el).all() or ((el <= 0) | (el > 90)).any():
        raise ValueError(f"elevation must be in (0, 90] degrees (the light above the ground), got {check._show(el)}")
    d = check.as_float_array(thickness, "thickness")
    if not np.isfinite(d).all() or (d < 0).any():
        raise ValueError(f"thickness must be a finite caster thickness >= 0 [world units], got {check._show(d)}")
    gap = np.where(el < 90, b * np.cos(np.radians(el)), 0.0)  # eq. bias.lit_gap
    return _out(np.maximum(gap - d, 0.0))


@check.public
def edge_shift(rule, texel: ArrayLike, elevation: ArrayLike, extent: ArrayLike | None = None) -> float | NDArray[np.float64]:
    """How far an engine's whole bias rule moves a shadow's edge on horizontal ground [world units].

    The ground receiver makes θ = 90° − α with the direction to a light at elevation α.  The
    rule's whole depth bias there, b = ``rule.depth(w, θ, 90°)`` (every term: constant,
    slope-scaled and normal offsets, as world depth along the light), moves the shadow's edge
    by :func:`lit_gap` (b) = b·cos α: at the foot of a vertical caster for the depth terms
    (peter-panning), and at the shadow's far end for a normal offset o·g(θ), whose depth
    equivalent o·g(θ)/cos θ = o·g(θ)/sin α gives o·g(θ)/tan α: a receiver moved o along the
    ground's normal is tested o above the ground, where the caster below that height casts no
    shadow (three.js, PlayCanvas), and a caster offset (Babylon.js) lowers a box's top by
    o·sin θ = o cos α.  A normal offset cancels at the foot but not at the end.

    Parameters
    ----------
    rule : aliasing.setups.BiasRule
        The engine's bias rule (its :meth:`~aliasing.setups.BiasRule.depth`).
    texel : array_like
        The map's texel side w there [world units], > 0.
    elevation : array_like
        α, the light's elevation above the ground [deg], in (0, 90].
    extent : array_like, optional
        The map's depth range along the light [world units], for rules with range terms.

    Returns
    -------
    float or ndarray
        The shift [world units], ≥ 0 (a rule that lifts the receiver above the light's
        surface moves nothing).

    Examples
    --------
    >>> from aliasing.setups import BiasRule, BiasTerm
    >>> depth = BiasRule((BiasTerm("bias", 0.1, "depth"),))
    >>> normal = BiasRule((BiasTerm("normalBias", 0.1, "normal"),))
    >>> round(edge_shift(depth, 0.01, 45.0), 6), round(edge_shift(normal, 0.01, 45.0), 6)   # b cos α; o / tan α
    (0.070711, 0.1)
    """
    el = check.as_float_array(elevation, "elevation")
    if not np.isfinite(el).all() or ((el <= 0) | (el > 90)).any():
        raise ValueError(f"elevation must be in (0, 90] degrees (the light above the ground), got {check._show(el)}")
    b = np.asarray(rule.depth(texel, 90.0 - el, 90.0, extent), float)
    return lit_gap(np.maximum(np.nan_to_num(b, nan=0.0, posinf=np.finfo(float).max), 0.0), np.broadcast_to(el, b.shape))


@check.public
def map_bias(lm: LightMap, resolution: int, points: ArrayLike, normals: ArrayLike, lookup: str = "nearest") -> PlaneBias:
    """Minimal biases at surface points of a map of any parameterization, from its local texel.

    The texel at a point is the parallelogram of its sides e_s, e_t (:func:`aliasing.raster.draw.lookup.texel_edges`,
    first order in the texel); the receiver's depth gradient over the light plane g (from its
    normal) gives depth = (k/2)·(|g·e_s| + |g·e_t|), which is :func:`plane_bias` for square texels,
    and normal = depth·cos θ.

    Parameters
    ----------
    lm : LightMap
        The light's map (:func:`aliasing.raster.light_map`; Standard, P, LogP …).
    resolution : int
        Texels per side.
    points, normals : array_like, shape (..., 3)
        Surface points [world units] and their normals (any length or sign).
    lookup : str
        As in :func:`plane_bias`.

    Example
    -------
    >>> from aliasing.raster.draw import light_map
    >>> lm = light_map(1.0, 20.0, 60.0, "gamma:60", "Standard")
    >>> e_s, e_t = texel_edges(lm, 256, [[0.0, -1.0, 5.0]])
    >>> mb = map_bias(lm, 256, [[0.0, -1.0, 5.0]], [[0.0, 1.0, 0.0]])
    >>> w_t = float(e_t[0, 1])   # the texel's extent along t [world units]
    >>> bool(np.isclose(mb.depth[0], plane_bias(w_t, 30.0, 90.0).depth))   # the ground: 30° from the light, slope along t
    True
    """
    check.instance(lm, "lm", LightMap)
    k, _ = kernel(lookup)
    p = check.as_float_array(points, "points")
    nrm = check.as_float_array(normals, "normals")
    if p.shape[-1:] != (3,) or nrm.shape != p.shape:
        raise ValueError(f"points and normals must have the same shape (..., 3), got {p.shape} and {nrm.shape}")
    length = np.linalg.norm(nrm, axis=-1, keepdims=True)
    if not (np.isfinite(p).all() and np.isfinite(nrm).all()) or (length == 0).any():
        raise ValueError("points and normals must be finite, normals non-zero")
    grad, cos = light_gradient(lm, nrm / length)
    e_s, e_t = texel_edges(lm, resolution, p)
    depth = 0.5 * k * (np.abs((grad * e_s).sum(-1)) + np.abs((grad * e_t).sum(-1)))
    return PlaneBias(depth, depth * cos)
