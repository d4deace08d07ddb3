"""Light depth maps drawn only at the texels looked up: :class:`SampledMap`, :class:`TexelArray`, :func:`gathered`.

A frame of H × W pixels reads a few texels per pixel through each cascade's map, an engine's map
holds millions: a :class:`SampledMap` draws only the texels asked (through
:func:`aliasing.raster.draw.rasterize_at`: the same values as the whole map, bit for bit) and keeps
them (:class:`aliasing.raster.draw.core.TexelStore`).  A :class:`TexelArray` presents a map's
texels, through a function of their depth and triangle, as the (R, R) array the engines' factor
functions index; :func:`gathered` runs such a function so that every texel it reads is drawn in
one pass per map.

Examples
--------
>>> sm = SampledMap(np.array([[[0.0, 0, 0.25], [2, 0, 0.25], [0, 2, 0.25]]]), 2048)   # a roof over the map
>>> sm.at(np.array([5, 2000]), np.array([7, 10]))[0].tolist(), sm.texels
([0.25, 0.25], 2)
"""

from __future__ import annotations

import weakref

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...raster.draw import DepthMap
from ...raster.draw.core import CHUNK, TexelStore, _triangles, texel_indices, weights_and_rows, zbuffer_at

Array = NDArray[np.float64]


class SampledMap:
    """A light depth map drawn only at the texels looked up (:meth:`SampledMap.at`), those found kept: bit for bit the whole map's values.

    ``mapped`` (T, 3, 3): the triangles in map space (s, t, depth), as :func:`aliasing.raster.draw.rasterize` takes them;
    ``resolution``: texels per side.  Made by :func:`aliasing.frames.lightmaps.depth.sampled_depth_map`.

    A frame of H × W pixels reads a few texels per pixel through each map; an engine's map has
    millions.  The factor functions (:func:`threejs_factor`, :func:`babylon_factor`,
    :func:`playcanvas_factor`) take a sampled map where they take a :class:`DepthMap`; run them
    through :func:`gathered` to draw every texel they read in one pass per map.

    Attributes
    ----------
    resolution : int
        Texels per side [texels].
    texels : int
        Texels drawn so far.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> from aliasing.frames.lightmaps.depth import light_depth_map, sampled_depth_map
    >>> roof = [[[0, 0.25, 0], [1, 0.25, 0], [0, 0.25, 1]]]
    >>> sm = sampled_depth_map(roof, m, 4)
    >>> d, tri = sm.at(np.array([1, 1]), np.array([1, 3]))
    >>> d.tolist(), tri.tolist(), sm.texels                     # only the 2 texels asked are drawn
    ([0.25, inf], [0, -1], 2)
    >>> bool((d == light_depth_map(roof, m, 4).depth[[1, 1], [1, 3]]).all())
    True
    """

    def __init__(self, mapped: Array, resolution: int) -> None:
        self.mapped = mapped
        self.resolution = int(resolution)
        self._kept = TexelStore(size=self.resolution**2)  # a slot table: 4 bytes per texel
        weakref.finalize(self, self._kept.release)  # its table serves the next map once this one is gone
        self._asked: list | None = None  # while gathered's first run records the texels read
        self._prepared: tuple | None = None
        self._strict = False  # while gathered tries a run on the texels drawn before: a missing one stops it

    @property
    def texels(self) -> int:
        """The texels drawn so far.

        Examples
        --------
        >>> from aliasing.frames.lightmaps.depth import sampled_depth_map
        >>> sampled_depth_map([[[0, 0, 0], [1, 0, 0], [0, 0, 1]]], np.eye(4), 8).texels
        0
        """
        return len(self._kept)

    def sampled_maps(self) -> list:
        """This map, for :func:`gathered` (which collects the sampled maps behind what a computation reads).

        Examples
        --------
        >>> sm = SampledMap(np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]]), 8)
        >>> sm.sampled_maps() == [sm]
        True
        """
        return [self]

    @property
    def nbytes(self) -> int:
        """The bytes kept [bytes]: the slot table's 4 per texel of the map, and 24 per texel drawn.

        Examples
        --------
        >>> sm = SampledMap(np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]]), 8)
        >>> sm.draw([0, 1, 1]); sm.nbytes                 # 64 · 4 + 2 · (8 + 8 + 8)
        304
        """
        return self._kept.nbytes

    def at(self, row: ArrayLike, col: ArrayLike) -> tuple[Array, NDArray[np.int64]]:
        """Depth (``inf`` where empty) and visible triangle (−1 where empty) of texels (``row``, ``col``), whole numbers in [0, R) of one shape."""
        flat = texel_indices(row, col, self.resolution)
        if self._asked is not None:  # recording (gathered): the values are not used
            self._asked.append(flat.ravel())
            return np.zeros(flat.shape), np.full(flat.shape, -1, np.int64)
        if self._strict:
            if not self._kept.holds(flat):
                raise _Missing
        else:
            self.draw(flat)
        return self._kept.get(flat)

    def draw(self, flat: ArrayLike) -> None:
        """Draw the texels of flat indices row·R + column (those not drawn yet), in one pass.

        Examples
        --------
        >>> sm = SampledMap(np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]]), 8)
        >>> sm.draw([3, 3, 9]); sm.texels
        2
        """
        flat = np.asarray(flat, np.int64)
        if self._kept.holds(flat):
            return
        missing = self._kept.missing(flat)
        if self._prepared is None:  # rasterize_at's set-up, once
            self._prepared = (_triangles(self.mapped),) + weights_and_rows(_triangles(self.mapped), self.resolution, None, None)
        tri, inv_w, rows, uniform = self._prepared
        depth, ident, _, _ = zbuffer_at(tri, self.resolution, inv_w, rows, uniform, CHUNK, missing)
        self._kept.add(missing, depth, ident)


class _Missing(Exception):
    """A texel read in :func:`gathered`'s first try was not drawn yet."""


class TexelArray:
    """An (R, R) array of a map's texels made where indexed: ``values(depth, triangle)`` at the texels of ``array[row, col]``.

    ``rows``: only the map's first rows, an (rows, R) array (Godot's 2 splits: each split a
    4096 × 2048 half of its atlas, drawn on the first rows of a 4096² raster); None: all R.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])
    >>> from aliasing.frames.lightmaps.depth import sampled_depth_map
    >>> stored = TexelArray(sampled_depth_map([[[0, 0.25, 0], [1, 0.25, 0], [0, 0.25, 1]]], m, 4), lambda d, tri: np.where(tri >= 0, d, 1.0))
    >>> stored.shape, stored[np.array([1, 1]), np.array([1, 3])].tolist()
    ((4, 4), [0.25, 1.0])
    >>> TexelArray(stored.source, stored.values, rows=2).shape
    (2, 4)
    """

    ndim = 2

    def __init__(self, source, values, rows: int | None = None) -> None:
        self.source = source
        self.values = values
        r = source.resolution
        if rows is not None and not (isinstance(rows, (int, np.integer)) and 1 <= rows <= r):
            raise ValueError(f"rows must be a whole number of texel rows in [1, {r}] or None, got {rows!r}")
        self.shape = (r if rows is None else int(rows), r)

    def sampled_maps(self) -> list:
        """The sampled maps behind the array (its source's), for :func:`gathered`.

        Examples
        --------
        >>> sm = SampledMap(np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]]), 8)
        >>> TexelArray(sm, lambda d, tri: d).sampled_maps() == [sm]
        True
        """
        return _sampled_maps(self.source)

    def __getitem__(self, key) -> Array:
        row, col = np.broadcast_arrays(*key)
        return self.values(*self.source.at(row, col))


def texels(dm, values) -> Array | TexelArray:
    """``values(depth, triangle)`` of a whole :class:`DepthMap`, or the :class:`TexelArray` of a :class:`SampledMap`.

    Examples
    --------
    >>> from aliasing.frames.lightmaps.depth import light_depth_map
    >>> dm = light_depth_map([[[0, 0.25, 0], [1, 0.25, 0], [0, 0.25, 1]]], np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]]), 2)
    >>> texels(dm, lambda d, tri: np.where(tri >= 0, d, 1.0)).tolist()
    [[0.25, 1.0], [1.0, 1.0]]
    """
    if isinstance(dm, DepthMap):
        return values(dm.depth, dm.triangle)
    if not (hasattr(dm, "at") and hasattr(dm, "resolution") and hasattr(dm, "sampled_maps")):
        raise ValueError(f"dm must be a DepthMap or a SampledMap, got {type(dm).__name__}")
    return TexelArray(dm, values)


def _sampled_maps(a) -> list:
    """The :class:`SampledMap` objects behind ``a``: anything with ``sampled_maps()`` (a sampled map, a :class:`TexelArray`,
    PlayCanvas's sampled atlas); none for a whole map."""
    return list(a.sampled_maps()) if hasattr(a, "sampled_maps") else []


def gathered(compute, maps):
    """``compute()`` with the texels it reads of sampled ``maps`` drawn in one pass per map.

    ``compute`` runs once if every texel it reads was drawn before (a search that moves only the
    biases of the same maps), else twice: first recording the texels it reads (the values are then
    zeros: its lookups must not depend on them, as the factor functions' do not), then, with
    those texels drawn, for its result.  Maps that are not sampled are left as they are.

    Examples
    --------
    >>> sm = SampledMap(np.array([[[0.0, 0, 0.5], [1, 0, 0.5], [0, 1, 0.5]]]), 64)   # half the map at depth 0.5
    >>> stored = TexelArray(sm, lambda d, tri: np.where(tri >= 0, d, 1.0))
    >>> rows, cols = np.array([1, 60, 2]), np.array([1, 60, 2])
    >>> gathered(lambda: stored[rows, cols] + stored[rows + 1, cols], [sm]).tolist(), sm.texels   # 6 texels read, drawn in one pass
    ([1.0, 2.0, 1.0], 6)
    """
    lazy = [m for a in maps for m in _sampled_maps(a)]
    if not lazy:
        return compute()
    for m in lazy:
        m._strict = True
    try:
        return compute()
    except _Missing:
        pass
    finally:
        for m in lazy:
            m._strict = False
    for m in lazy:
        m._asked = []
    try:
        compute()
    finally:
        asked = [(m, m._asked) for m in lazy]
        for m in lazy:
            m._asked = None
    for m, flat in asked:
        if flat:
            m.draw(np.concatenate(flat))
    return compute()
