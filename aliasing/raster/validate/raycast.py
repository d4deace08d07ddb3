"""Ray-casting reference for the rasterizer's shadow maps (optional: Intel Embree via embreex).

:func:`raycast_shadow_map` computes the same depth map as
:func:`aliasing.raster.shadow_map` by another method: one ray per texel, cast along the light
direction through the texel's centre mapped back to the light plane by the inverse of the
map's parameterization (:meth:`~aliasing.raster.LightMap.texel_centres`: uniform,
perspective, log+perspective), and intersected with the scene by Embree's BVH.  Where the
two agree, the rasterizer's coverage rule, its depth interpolation (perspective-correct for
warped maps) and its logarithmic rasterization are right; they may differ only for texel
centres within rounding of a triangle edge.  :func:`agreement` measures that.

Embree computes in single precision (float32): depths carry an absolute error of about
1e-7 times the scene's extent, which is what the tolerance of :func:`agreement` allows for.

embreex is an optional dependency (``pip install ".[bench]"``); without it,
:func:`available` is False and :func:`raycast_shadow_map` raises ValueError.

Example
-------
>>> from aliasing.raster.draw import light_map, shadow_map
>>> from aliasing.raster.scenes import ground_and_boxes
>>> sc = ground_and_boxes(1.0, 50.0, boxes=5, seed=1)
>>> lm = light_map(1.0, 50.0, 60.0, "gamma:60", "LogP")
>>> a, b = shadow_map(sc.triangles, lm, 64), raycast_shadow_map(sc.triangles, lm, 64)
>>> bool(agreement(a, b, sc.triangles) > 0.99)
True
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..draw.core import CHUNK, DepthMap, _triangles, check_resolution
from ..draw.lightmap import LightMap

#: Depth tolerance of :func:`agreement` as a fraction of the scene's extent: about 8 float32
#: ulps (Embree's results differ from the rasterizer's by ≲ 1.3e-7 of the extent).
DEPTH_TOLERANCE = 1e-6


def available() -> bool:
    """True when embreex (the optional ``bench`` extra) is installed.

    Example
    -------
    >>> isinstance(available(), bool)
    True
    """
    try:
        _embree()
    except ValueError:
        return False
    return True


def _embree():
    try:
        from embreex import rtcore_scene
        from embreex.mesh_construction import TriangleMesh
    except ImportError:
        raise ValueError("the ray-casting reference needs embreex, the optional extra: pip install \".[bench]\"") from None
    return rtcore_scene, TriangleMesh


def raycast_shadow_map(triangles: ArrayLike, lm: LightMap, resolution: int, *, chunk: int = CHUNK) -> DepthMap:
    """Depth map of eye-space triangles through ``lm`` by ray casting, one ray per texel.

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Triangle corners in eye space [world units].
    lm : LightMap
        The light's map (:func:`aliasing.raster.light_map`).
    resolution : int
        R, texels per side, 1 ≤ R ≤ :data:`aliasing.raster.MAX_RESOLUTION`.
    chunk : int
        Rays per call into Embree (≥ 1); bounds the temporaries (≈ 60 bytes per ray).

    Returns
    -------
    DepthMap
        ``depth[j, i]``: negated height along the light [world units] of the first surface
        hit by the ray through texel (j, i), ``inf`` for a miss (as
        :func:`aliasing.raster.shadow_map`); ``triangle``: the input index of that
        triangle, −1 for a miss; ``rasterized``: triangles given to Embree;
        ``degenerate``: triangles dropped for a non-finite coordinate (Embree itself never
        hits zero-area ones).

    Raises
    ------
    ValueError
        embreex not installed, malformed ``triangles``, resolution outside
        [1, MAX_RESOLUTION], chunk < 1.

    Example
    -------
    >>> from aliasing.raster.draw import light_map
    >>> lm = light_map(1.0, 10.0, 60.0, "overhead", "P")
    >>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    >>> m = raycast_shadow_map(ground, lm, 16)
    >>> float(np.unique(m.depth[np.isfinite(m.depth)]).round(5)[0])   # the ground is 1 below the eye
    1.0
    """
    tri = _triangles(triangles)
    res = check_resolution(resolution)
    if isinstance(chunk, bool) or not isinstance(chunk, (int, np.integer)) or chunk < 1:
        raise ValueError(f"chunk must be a whole number >= 1 (rays per Embree call), got {chunk!r}")
    if not isinstance(lm, LightMap):
        raise ValueError(f"lm must be a LightMap (see aliasing.raster.light_map), got {type(lm).__name__}")
    rtcore_scene, TriangleMesh = _embree()
    finite = np.isfinite(tri).all(axis=(1, 2))
    keep = np.nonzero(finite)[0]
    pts = tri[keep]
    # work in light coordinates (x, height, y) centred on the scene: float32 keeps its
    # precision relative to the scene's extent, not to the distance from the eye
    x, y, h = lm.light_plane(pts)
    local = np.stack([x, h, y], axis=-1)
    centre = 0.5 * (local.reshape(-1, 3).min(axis=0) + local.reshape(-1, 3).max(axis=0)) if keep.size else np.zeros(3)
    top = float(local[..., 1].max() - centre[1]) + 1.0 if keep.size else 1.0  # ray origins above every triangle
    depth = np.full(res * res, np.inf)
    ident = np.full(res * res, -1, dtype=np.int64)
    if keep.size:
        try:
            scene = rtcore_scene.EmbreeScene(robust=True)
        except TypeError:  # embreex builds without the robust flag
            scene = rtcore_scene.EmbreeScene()
        TriangleMesh(scene, np.ascontiguousarray(local - centre, dtype=np.float32))
        cx, cy = lm.texel_centres(res)
        cx, cy = cx.ravel() - centre[0], cy.ravel() - centre[2]
        down = np.array([[0.0, -1.0, 0.0]], np.float32)
        for a in range(0, res * res, int(chunk)):
            b = min(a + int(chunk), res * res)
            org = np.empty((b - a, 3), np.float32)
            org[:, 0], org[:, 1], org[:, 2] = cx[a:b], top, cy[a:b]
            hit = scene.run(org, np.repeat(down, b - a, axis=0), output=1)
            prim = hit["primID"].astype(np.int64)
            ok = prim >= 0
            # height = centre + top − tfar; depth is its negation
            depth[a:b] = np.where(ok, hit["tfar"].astype(float) - top - centre[1], np.inf)
            ident[a:b] = np.where(ok, keep[np.maximum(prim, 0)], -1)
    return DepthMap(depth.reshape(res, res), ident.reshape(res, res), res, int(keep.size), int(tri.shape[0] - keep.size))


def agreement(a: DepthMap, b: DepthMap, triangles: ArrayLike, *, tolerance: float = DEPTH_TOLERANCE) -> float:
    """Fraction of texels whose depths agree: both empty, or both finite within tolerance.

    Parameters
    ----------
    a, b : DepthMap
        Two depth maps of the same scene and resolution.
    triangles : array_like, shape (T, 3, 3)
        The scene [world units]; its extent (largest side of its bounding box) scales the
        tolerance.
    tolerance : float
        Allowed depth difference as a fraction of the scene's extent, ≥ 0.

    Example
    -------
    >>> m = DepthMap(np.array([[1.0, np.inf], [2.0, 2.5]]), np.array([[0, -1], [0, 0]]), 2, 1, 0)
    >>> agreement(m, m, [[[0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    1.0
    """
    if a.depth.shape != b.depth.shape:
        raise ValueError(f"a and b must have the same resolution, got {a.depth.shape} and {b.depth.shape}")
    if not tolerance >= 0:
        raise ValueError(f"tolerance must be >= 0 (a fraction of the scene's extent), got {tolerance!r}")
    tri = _triangles(triangles)
    pts = tri.reshape(-1, 3)[np.isfinite(tri.reshape(-1, 3)).all(axis=1)]
    extent = float(np.ptp(pts, axis=0).max()) if pts.size else 1.0
    both_empty = np.isinf(a.depth) & np.isinf(b.depth)
    with np.errstate(invalid="ignore"):
        close = np.abs(a.depth - b.depth) <= tolerance * extent
    return float((both_empty | close).mean())
