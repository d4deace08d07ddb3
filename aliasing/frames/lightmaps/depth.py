"""The light depth maps of the frames' models: world triangles through a light matrix, whole or drawn where read.

:func:`to_map` (and :func:`to_map32`, as a float32 shader computes it) takes world points through
a 4×4 light matrix to map coordinates (s, t, depth); :func:`light_depth_map` draws the whole map
with the toolkit's rasterizer, :func:`sampled_depth_map` only the texels looked up
(:class:`aliasing.frames.lightmaps.sampled.SampledMap`).  Within
:func:`aliasing.frames.seen.remember`'s block both keep what they drew (:data:`KEPT`).

Examples
--------
>>> m = np.eye(4)
>>> tri = np.array([[[0.1, 0.1, 0.5], [0.9, 0.1, 0.5], [0.1, 0.9, 0.5]]])
>>> dm = light_depth_map(tri, m, 8)
>>> float(dm.depth[1, 1]), int(dm.triangle[1, 1]), float(sampled_depth_map(tri, m, 8).at(np.array([1]), np.array([1]))[0][0])
(0.5, 0, 0.5)
"""

from __future__ import annotations

import hashlib

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ...raster.draw import DepthMap, rasterize
from .sampled import SampledMap

Array = NDArray[np.float64]
#: The sub-texel precision [bits] with which SwiftShader, the renderer of the engines' frames here, places a
#: triangle's corners (``SUBPIXEL_PRECISION_BITS`` in its src/Vulkan/VkConfig.hpp: 4 with
#: ``SWIFTSHADER_LEGACY_PRECISION``; the maps read back from Debian's Chromium show 4, ERRATA F14).
SUBPIXEL_BITS = 4


def _matrix(m: ArrayLike) -> Array:
    mm = check.finite(m, "matrix")
    if mm.shape != (4, 4):
        raise ValueError(f"matrix must be 4x4, got shape {mm.shape}")
    return mm


def to_map(matrix: ArrayLike, points: ArrayLike) -> Array:
    """Map coordinates (s, t, depth) of world points ``(..., 3)`` through a 4×4 light matrix (column vectors).

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])   # s = x, t = z, depth = 0.5 − y
    >>> to_map(m, [[0.25, 0.1, 0.75], [1.0, 0.0, 0.0]]).tolist()
    [[0.25, 0.75, 0.4], [1.0, 0.0, 0.5]]
    """
    if np.shape(points)[-1:] != (3,):
        raise ValueError(f"points must have shape (..., 3), got {np.shape(points)}")
    check.finite(points, "points")
    m = _matrix(matrix)
    p = np.asarray(points, float)
    h = p @ m[:3, :3].T + m[:3, 3]
    w = p @ m[3, :3] + m[3, 3]
    return h / w[..., None]


def to_map32(matrix: ArrayLike, points: ArrayLike) -> Array:
    """:func:`to_map` as a float32 shader computes ``matrix * vec4( point, 1.0 )``: the matrix and the
    points rounded to float32, then per row the first column's product and each further column's
    product added in order, every step rounded to float32 (SwiftShader's ``OpMatrixTimesVector``).
    The last row is not used: w = 1, an orthographic matrix (the lights' here).

    Examples
    --------
    >>> float(to_map32(np.eye(4), [[0.1, 0.2, 0.3]])[0, 0]) == float(np.float32(0.1))
    True
    """
    m = _matrix(matrix).astype(np.float32)
    p = np.asarray(points, float)
    if p.shape[-1:] != (3,):
        raise ValueError(f"points must have shape (..., 3), got {p.shape}")
    q = p.reshape(-1, 3).astype(np.float32)
    out = np.empty(q.shape, np.float32)
    for i in range(3):
        v = m[i, 0] * q[:, 0]
        for j in (1, 2):
            v = v + m[i, j] * q[:, j]
        out[:, i] = v + m[i, 3]  # times w = 1
    return out.astype(float).reshape(p.shape)


def light_depth_map(triangles: ArrayLike, matrix: ArrayLike, resolution: int, subpixel_bits: int | None = None) -> DepthMap:
    """The toolkit's depth map (smaller depth = nearer the light) of world triangles through a light matrix.

    Parameters
    ----------
    triangles : array_like (T, 3, 3)
        World triangles [world units].
    matrix : array_like (4, 4)
        World → (s, t, depth) in [0, 1]³ (an orthographic light: w = 1).
    resolution : int
        Texels per side [texels], in [1, 16384].
    subpixel_bits : int, optional
        Each corner's (s, t) first rounded to 1/2^bits of a texel (:func:`snap`), as the frames'
        renderer places it (:data:`SUBPIXEL_BITS`); None: exact corners.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> dm = light_depth_map([[[0, 0.25, 0], [1, 0.25, 0], [0, 0.25, 1]]], m, 4)      # half the map (s + t < 1), at depth 0.25
    >>> dm.depth[1].tolist(), dm.triangle[1].tolist()                                # row t = 3/8: centres s = 1/8, 3/8 inside
    ([0.25, 0.25, inf, inf], [0, 0, -1, -1])
    >>> light_depth_map([[[0, 0.25, 0], [1, 0.25, 0], [0, 0.25, 1]]], m, 4, subpixel_bits=-1)
    Traceback (most recent call last):
    ...
    ValueError: subpixel_bits must be a whole number in [0, 16] or None, got -1
    """
    mapped, r = _mapped(triangles, matrix, resolution)
    return _draw(mapped if subpixel_bits is None else snap(mapped, r, subpixel_bits), r)


def _mapped(triangles: ArrayLike, matrix: ArrayLike, resolution: int) -> tuple[Array, int]:
    """Checked world triangles through ``matrix`` (one far outside the map where none is given) and the checked size."""
    check.whole(resolution, "resolution", 1, 16384, " [texels]")
    tri = check.triangles(triangles, empty=True)
    if not len(tri):
        tri = np.full((1, 3, 3), 10.0)  # nothing casts: one triangle far outside the map
    return to_map(matrix, tri), int(resolution)


def _keep(kind: str, mapped: Array, r: int, make):
    """``make(mapped, r)``, kept by ``kind`` and a digest of the map-space triangles within :func:`aliasing.frames.seen.remember`'s block."""
    kept = KEPT["maps"]
    if kept is None:
        return make(mapped, r)
    key = (kind, hashlib.blake2b(np.ascontiguousarray(mapped, np.float64).tobytes(), digest_size=16).digest(), r)
    try:
        return kept[key]
    except KeyError:  # not made yet (or dropped)
        kept[key] = made = make(mapped, r)
        return made


def _draw(mapped: Array, r: int) -> DepthMap:
    """:func:`rasterize` of map-space triangles, kept within :func:`aliasing.frames.seen.remember`'s block."""
    return _keep("whole", mapped, r, rasterize)


#: The maps kept within :func:`aliasing.frames.seen.remember`'s block (None outside it), by the mapped triangles and the size.
KEPT: dict = {"maps": None}


def sampled_depth_map(triangles: ArrayLike, matrix: ArrayLike, resolution: int, subpixel_bits: int | None = None) -> SampledMap:
    """:func:`light_depth_map` (the same parameters), drawn only at the texels looked up (:class:`SampledMap`).

    ``subpixel_bits``: each corner's (s, t) first rounded to 1/2^bits of a texel (:func:`snap`), as the
    frames' renderer places it (:data:`SUBPIXEL_BITS`); None: exact corners.

    Kept within :func:`aliasing.frames.seen.remember`'s block, as the whole maps are.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])
    >>> sampled_depth_map([[[0, 0.25, 0], [1, 0.25, 0], [0, 0.25, 1]]], m, 4).at(np.array([0]), np.array([0]))[0].tolist()
    [0.25]
    """
    mapped, r = _mapped(triangles, matrix, resolution)
    return _sampled(mapped if subpixel_bits is None else snap(mapped, r, subpixel_bits), r)


def snap(mapped: Array, resolution: int, subpixel_bits: int) -> Array:
    """Map-space triangles with each corner's (s, t) rounded to 1/2^``subpixel_bits`` of a texel of a ``resolution`` map.

    A rasterizer with that sub-texel precision places the corners there before it decides which
    texel centres a triangle covers: SwiftShader, which draws the engines' frames here, with 4 bits
    (:data:`SUBPIXEL_BITS`).  The depth is left as it is.

    Examples
    --------
    >>> snap(np.array([[[0.1, 0.2, 0.5], [0.9, 0.1, 0.5], [0.1, 0.9, 0.5]]]), 8, 4)[0, 0].tolist()   # 0.8 and 1.6 texels: 13/16, 26/16
    [0.1015625, 0.203125, 0.5]
    """
    if not (isinstance(subpixel_bits, (int, np.integer)) and 0 <= subpixel_bits <= 16):
        raise ValueError(f"subpixel_bits must be a whole number in [0, 16] or None, got {subpixel_bits!r}")
    out = np.array(mapped, float)
    q = float(resolution) * 2.0**subpixel_bits
    out[..., :2] = np.floor(out[..., :2] * q + 0.5) / q
    return out


def _sampled(mapped: Array, r: int) -> SampledMap:
    """A :class:`SampledMap` of map-space triangles, kept within :func:`aliasing.frames.seen.remember`'s block."""
    return _keep("sampled", mapped, r, SampledMap)
