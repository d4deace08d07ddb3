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

from ... import _validation as check
from .core import CHUNK, DepthMap, _triangles, check_resolution, clip_near, rasterize
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


def shadow_map(triangles: ArrayLike, lm: LightMap, resolution: int, *, chunk: int = CHUNK) -> DepthMap:
    """Depth map of eye-space triangles ``(T, 3, 3)`` through the light map ``lm``.

    Depth is the negated height along the light [world units] (smaller = nearer the light),
    exact for planar triangles (perspective-correct); log+perspective maps are rasterized
    logarithmically (module docstring).  For warped maps, triangles are first clipped at
    y = −n′/2 in the light plane (behind the map's near edge y = 0, in front of the warp's
    centre of projection y = −n′); ``triangle`` ids index the input triangles, the counts
    ``rasterized`` and ``degenerate`` the clipped ones.

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

