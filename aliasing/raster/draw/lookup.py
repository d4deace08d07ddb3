"""The shadow test: is a surface point lit through a depth map?

:func:`shadow_test` compares a point with the sample its texel stores, treating receiver and
occluder as locally planar, within a tolerance ``bias`` [world units] (:data:`BIAS` by
default).  The pictures (:mod:`aliasing.raster.pictures`) shade with it.

Example
-------
>>> from aliasing.raster.draw import light_map, shadow_map
>>> lm = light_map(1.0, 20.0, 60.0, "overhead", "Standard")
>>> ground = np.array([[[-40, -1, 0.5], [40, -1, 0.5], [0, -1, 60]]], float)
>>> sm = shadow_map(ground, lm, 32)
>>> shadow_test(lm, sm, ground, [[0.0, -1.0, 10.0]], [[0.0, 1.0, 0.0]]).tolist()   # a plane never shadows itself
[True]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from .core import DepthMap
from .lightmap import LightMap

#: Default tolerance of the shadow test's depth comparisons [world units].
BIAS = 1e-3


def _bias(value: float) -> float:
    return float(check.closed_range(value, "bias", 0.0, np.inf, " world units (depth-test tolerance)"))


def shadow_test(lm: LightMap, sm: DepthMap, triangles: ArrayLike, points: ArrayLike, normals: ArrayLike, *, bias: float = BIAS) -> NDArray[np.bool_]:
    """Shadow-map test of surface points: True where lit (not occluded towards the light).

    A texel stores one sample of the surface nearest the light: its depth at the texel's
    centre and its triangle.  Treating the receiver and that occluder as locally planar, a
    point p is lit when any of these holds (each within ``bias``):

    1. p's depth is at most the stored depth (the plain test);
    2. the occluder's plane, met on p's own light ray, is not nearer the light than p
       (e.g. a box face beside the ground it stands on: the ground sampled at the texel
       centre lies below the face at p);
    3. the receiver's plane, met on the ray through the texel's centre (found with the
       map's inverse, :meth:`~aliasing.raster.LightMap.inverse`), is not farther than the
       stored depth (e.g. near a box's convex edge, or a planar receiver, which thus never
       shadows itself: no acne).

    No bias grows with the texel, so occluders of any height cast shadows that touch them
    (no "peter-panning").  What remains is the map's own sampling error: shadow outlines
    are the occluders' footprints on the texel grid, up to a texel out of place.

    Parameters
    ----------
    lm : LightMap
        The map the depth map was rendered through.
    sm : DepthMap
        :func:`aliasing.raster.shadow_map` of ``triangles`` through ``lm``.
    triangles : array_like, shape (T, 3, 3)
        The scene [world units], indexed by ``sm.triangle``.
    points, normals : array_like, shape (..., 3)
        Surface points [world units] and their surfaces' normals (any length or sign).
    bias : float
        Tolerance of the three depth comparisons [world units], ≥ 0.

    Returns
    -------
    ndarray of bool, shape (...)
        True where lit; points outside the map count as lit.

    Example
    -------
    >>> from aliasing.raster.draw import light_map, shadow_map
    >>> lm = light_map(1.0, 20.0, 60.0, "gamma:60", "Standard")
    >>> ground = np.array([[[-40, -1, 0.5], [40, -1, 0.5], [0, -1, 60]]], float)
    >>> roof = np.array([[[-1, 0, 4], [1, 0, 4], [0, 0, 6]]], float)   # 1 above the ground
    >>> scene = np.concatenate([ground, roof])
    >>> sm = shadow_map(scene, lm, 64)
    >>> p = np.array([[0.0, -1.0, 15.0], [0.0, 0.0, 5.0], [0.0, -1.0, 4.4]])   # open ground, roof, roof's shadow
    >>> shadow_test(lm, sm, scene, p, [[0, 1, 0]] * 3).tolist()
    [True, True, False]
    """
    tri = np.asarray(triangles, float)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise ValueError(f"triangles must have shape (T, 3, 3), got {tri.shape}")
    p = check.as_float_array(points, "points")
    nrm = check.as_float_array(normals, "normals")
    if p.shape[-1:] != (3,) or nrm.shape != p.shape:
        raise ValueError(f"points and normals must have the same shape (..., 3), got {p.shape} and {nrm.shape}")
    bias = _bias(bias)
    if sm.triangle.size and int(sm.triangle.max()) >= len(tri):
        raise ValueError("triangles must be the scene of sm (sm names a triangle beyond them)")
    rm = sm.resolution
    s, t, d, _ = lm.coordinates(p)
    inside = (s >= 0) & (s < 1) & (t >= 0) & (t < 1)
    col = np.clip(np.floor(np.nan_to_num(s) * rm), 0, rm - 1).astype(np.int64)
    row = np.clip(np.floor(np.nan_to_num(t) * rm), 0, rm - 1).astype(np.int64)
    stored, occ = sm.depth[row, col], sm.triangle[row, col]
    up = lm.basis[1]  # towards the light; height along it is −depth
    lit = d <= stored + bias
    # 2. the occluder's plane on p's ray p + λ·up: λ > 0 is nearer the light than p
    a = tri[np.maximum(occ, 0)]
    n_o = np.cross(a[..., 1, :] - a[..., 0, :], a[..., 2, :] - a[..., 0, :])
    across = n_o @ up
    ok = (occ >= 0) & (np.abs(across) > 1e-9 * np.linalg.norm(n_o, axis=-1))
    lam = ((a[..., 0, :] - p) * n_o).sum(-1) / np.where(ok, across, 1.0)
    lit |= ok & (lam <= bias)
    # 3. the receiver's plane on the ray through the texel centre c0 + μ·up (c0 at height 0)
    xc, yc = lm.inverse((col + 0.5) / rm, (row + 0.5) / rm)
    c0 = lm.plane_point(xc, yc)
    along = nrm @ up
    ok = np.abs(along) > 1e-9 * np.linalg.norm(nrm, axis=-1)
    mu = ((p - c0) * nrm).sum(-1) / np.where(ok, along, 1.0)
    lit |= ok & (-mu <= stored + bias)
    return ~inside | lit
