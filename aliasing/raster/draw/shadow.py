"""Shadow maps: eye-space triangles rasterized through a light map, logarithmically for LogP.

:func:`log_row_centres` gives the texel centres of the log map mapped back into the
perspective map's t (the inverse of eq. 84), and rasterizing there with the straight edge
equations of the perspective map is logarithmic rasterization (Lloyd 2007 §6.3): the
bounding box is found in warped space and each candidate centre is tested against the
triangle's straight edges.

Example
-------
>>> from aliasing.raster.draw import light_map
>>> lm = light_map(1.0, 10.0, 60.0, "overhead", "LogP")
>>> m = shadow_map(np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float), lm, 16)
>>> m.resolution, bool(np.isfinite(m.depth).any())
(16, True)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from typing import Sequence

from ... import _validation as check
from . import backends, gl
from .core import CHUNK, DepthMap, _triangles, check_chunk, check_resolution, clip_near, rasterize
from .facemaps import MapSet
from .lightmap import LightMap, light_map

Array = NDArray[np.float64]


def log_row_centres(lm: LightMap, resolution: int) -> Array:
    """Row centres of the log+perspective map, in the perspective map's t (for ``row_centres``).

    Example
    -------
    >>> lm = light_map(1.0, 100.0, 60.0, "overhead", "LogP")
    >>> c = log_row_centres(lm, 4)
    >>> bool((np.diff(c) > 0).all() and 0 < c[0] < c[-1] < 1)
    True
    """
    check.instance(lm, "lm", LightMap)
    res = check_resolution(resolution)
    return lm.perspective_t((np.arange(res) + 0.5) / res)


def shadow_map(triangles: ArrayLike, lm: LightMap, resolution: int, *, chunk: int = CHUNK, backend: str = "numpy") -> DepthMap:
    """Depth map of eye-space triangles ``(T, 3, 3)`` through the light map ``lm``.

    Depth is the negated height along the light [world units] (smaller = nearer the light),
    exact for planar triangles (perspective-correct); log+perspective maps are rasterized
    logarithmically (module docstring).  For warped maps, triangles are first clipped at
    y = −n′/2 in the light plane (behind the map's near edge y = 0, in front of the warp's
    centre of projection y = −n′); ``triangle`` ids index the input triangles, the counts
    ``rasterized`` and ``degenerate`` the clipped ones.

    ``backend="gl"`` draws the map with OpenGL (:mod:`.gl`, the optional ``gl`` extra) through
    its 4×4 matrix (:meth:`LightMap.matrix`): the same depth (computed per texel centre from
    the visible triangle's plane in double precision, stored as float32: within
    ``gl.DEPTH_ERROR`` of the scene's depth range) and the same visible triangles up to
    the hardware's sub-texel snapping of edges; there ``rasterized`` counts the finite
    triangles sent and ``degenerate`` the non-finite ones, and a scene wholly behind the
    warp's centre of projection gives an empty map (numpy: a ``ValueError``).
    Log+perspective maps have no matrix: they are rasterized by numpy whichever backend is
    asked.

    Example
    -------
    >>> lm = light_map(1.0, 10.0, 60.0, "overhead", "P")
    >>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    >>> m = shadow_map(ground, lm, 16)
    >>> float(np.unique(m.depth[np.isfinite(m.depth)])[0])   # the ground is 1 below the eye
    1.0
    """
    tri = _triangles(triangles)
    check.instance(lm, "lm", LightMap)
    res = check_resolution(resolution)
    chunk = check_chunk(chunk)
    if backends.check(backend, "shadow_map") == "gl" and not _logarithmic(lm):
        return _gl_maps(tri, [lm], [res])[0]
    return _numpy_map(tri, lm, res, chunk)


def _logarithmic(lm: LightMap) -> bool:
    return lm.parameterization == "logperspective" and np.isfinite(lm.n_prime)


def _gl_maps(tri: Array, maps: Sequence[LightMap], resolutions: Sequence[int]) -> list[DepthMap]:
    """Projective maps drawn by :func:`.gl.draw_maps` (the triangles uploaded once)."""
    drawn, skipped = gl.draw_maps(tri, [lm.matrix() for lm in maps], resolutions)
    return [DepthMap(d, i, r, tri.shape[0] - skipped, skipped) for (d, i), r in zip(drawn, resolutions)]


def _numpy_map(tri: Array, lm: LightMap, resolution: int, chunk: int) -> DepthMap:
    x, y, h = lm.light_plane(tri)
    src = None
    if np.isfinite(lm.n_prime):
        # clip behind the warp's centre of projection (y = −n′); y < 0 is off the map anyway
        lp, src = clip_near(np.stack([x, h, y], axis=-1), -0.5 * lm.n_prime)
        if lp.shape[0] == 0:
            raise ValueError("triangles lie wholly behind the warping frustum's centre of projection: empty scene for this map")
        x, h, y = lp[..., 0], lp[..., 1], lp[..., 2]
    s, t, w = lm.map_plane(x, y)
    rows = log_row_centres(lm, resolution) if lm.parameterization == "logperspective" and np.isfinite(lm.n_prime) else None
    m = rasterize(np.stack([s, t, -h], axis=-1), resolution, w=w, row_centres=rows, chunk=chunk)
    if src is None:
        return m
    ident = np.where(m.triangle >= 0, src[np.maximum(m.triangle, 0)], -1)
    return DepthMap(m.depth, ident, m.resolution, m.rasterized, m.degenerate)



def shadow_maps(triangles: ArrayLike, maps: MapSet | Sequence[LightMap], resolution: int | Sequence[int], *, chunk: int = CHUNK, backend: str = "numpy") -> list[DepthMap]:
    """Depth maps of eye-space triangles through every map of a set: :func:`shadow_map` per map.

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Eye-space triangles [world units].
    maps : MapSet or sequence of LightMap
        A scheme's maps (:func:`aliasing.raster.map_set`; cascades:
        ``cascade_set(...).maps``; face partitions), or a list of light maps.
    resolution : int or sequence of int
        Texels per side of every map, or of each map (e.g. :func:`aliasing.raster.draw.cascades.budget_shares`).
    chunk : int
        Rows, or texels, per vectorized step of the numpy rasterizer.
    backend : {"numpy", "gl"}
        ``"gl"`` uploads the triangles once and draws each projective map with its matrix
        (:func:`shadow_map`); log+perspective maps are drawn by numpy.

    Returns
    -------
    list of DepthMap
        One per map, in the set's order.

    Example
    -------
    >>> from aliasing import raster
    >>> ms = raster.map_set(1.0, 10.0, 60.0, "gamma:60", "ZP2+P")
    >>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    >>> [m.resolution for m in shadow_maps(ground, ms, [16, 8])]
    [16, 8]
    """
    tri = _triangles(triangles)
    lms = list(maps.maps) if isinstance(maps, MapSet) else list(maps)
    if not lms:
        raise ValueError("maps must hold at least one LightMap")
    for lm in lms:
        check.instance(lm, "maps", LightMap)
    if isinstance(resolution, (list, tuple, np.ndarray)):
        if len(resolution) != len(lms):
            raise ValueError(f"resolution must be one whole number or one per map ({len(lms)}), got {len(resolution)}")
        rs = [check_resolution(r) for r in resolution]
    else:
        rs = [check_resolution(resolution)] * len(lms)
    chunk = check_chunk(chunk)
    out: list[DepthMap | None] = [None] * len(lms)
    if backends.check(backend, "shadow_map") == "gl":
        todo = [i for i, lm in enumerate(lms) if not _logarithmic(lm)]
        if todo:
            for i, m in zip(todo, _gl_maps(tri, [lms[i] for i in todo], [rs[i] for i in todo])):
                out[i] = m
    for i, lm in enumerate(lms):
        if out[i] is None:
            out[i] = _numpy_map(tri, lm, rs[i], chunk)
    return out
