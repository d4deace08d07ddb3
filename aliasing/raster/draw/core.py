"""Rasterizer setup: validation, the depth map value, near clipping and :func:`rasterize`.

Map coordinates
---------------
The conventions every backend reproduces (the rasterizer guide's "Map conventions"):

* A map of resolution R covers (s, t) ∈ [0, 1]²; texel (row j, column i) has its centre at
  s = (i + ½)/R and, by default, t = (j + ½)/R: row 0 is at the bottom, t ≈ 0 (show with
  ``origin="lower"``).
* A texel belongs to a triangle when its centre lies inside it; a centre exactly on an edge
  goes to one triangle only (the top-left rule, here with t up: an edge on the triangle's
  left side, or a horizontal edge at its bottom, owns the centres lying exactly on it), so a
  mesh without overlaps covers every texel at most once.
* Depth is interpolated from the vertices by barycentric weights, optionally
  perspective-correctly with per-vertex homogeneous weights ``w``: d = Σ bᵢdᵢ/wᵢ / Σ bᵢ/wᵢ,
  the depth of the triangle's plane at the texel centre.  Smaller is nearer: the z-buffer
  keeps the minimum, ties go to the highest triangle index; empty texels hold ``inf`` and
  triangle −1.  (Light maps store the negated height along the light, :mod:`.lightmap`.)

The covered spans and their depths are computed in :mod:`.coverage`.

Example
-------
>>> import numpy as np
>>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]])  # (s, t, depth)
>>> m = rasterize(tri, 8)
>>> int(np.isfinite(m.depth).sum()), m.degenerate   # s + t < 1; the 8 centres on s + t = 1 are not owned
(28, 0)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from . import occlusion
from .coverage import chunk_bounds, expand, merge_at, pair_spans, rasterize_rows

Array = NDArray[np.float64]

#: (16384² would need 4 GiB for these two arrays alone).
MAX_RESOLUTION = 8192
#: Default number of candidate (triangle, texel) pairs per vectorized chunk (≈ 100 MB of temporaries).
CHUNK = 1 << 20


@dataclass(frozen=True)
class DepthMap:
    """A rasterized depth map.

    Attributes
    ----------
    depth : ndarray, shape (R, R)
        Minimum interpolated depth per texel [caller's depth units]; ``inf`` where empty.
        ``depth[j, i]`` is the texel at s = (i + ½)/R and t = row centre j.
    triangle : ndarray of int64, shape (R, R)
        Index of the visible (nearest) triangle per texel, −1 where empty.
    resolution : int
        R, texels per side.
    rasterized : int
        Triangles rasterized (non-degenerate).
    degenerate : int
        Triangles skipped: zero area in map space, or a non-finite coordinate.
    """

    depth: Array
    triangle: NDArray[np.int64]
    resolution: int
    rasterized: int
    degenerate: int


def check_resolution(resolution: int, name: str = "resolution") -> int:
    """Validate a resolution: a whole number in [1, MAX_RESOLUTION]."""
    if isinstance(resolution, (bool, np.bool_)) or not isinstance(resolution, (int, np.integer)) and not (isinstance(resolution, (float, np.floating)) and np.isfinite(resolution) and float(resolution).is_integer()):
        raise ValueError(f"{name} must be a whole number in [1, {MAX_RESOLUTION}], got {check._repr(resolution)}")
    r = int(resolution)
    if r < 1 or r > MAX_RESOLUTION:
        raise ValueError(f"{name} must be in [1, {MAX_RESOLUTION}] (larger maps do not fit in memory), got {r}")
    return r


def check_chunk(chunk: int) -> int:
    """Validate a chunk size: a whole number >= 1."""
    return check.whole(chunk, "chunk", 1)


def _triangles(triangles: ArrayLike, name: str = "triangles") -> Array:
    try:
        raw = np.asarray(triangles)
    except (TypeError, ValueError):
        raw = None
    if raw is None or raw.dtype.kind not in "biuf":  # strings, complex, None, ragged, 10**400: refused by name
        raw = check.as_float_array(triangles, name)
    tri = raw.astype(float, copy=False)  # NaN or inf corners stay: degenerate triangles, skipped and counted
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise ValueError(f"{name} must have shape (T, 3, 3) (T triangles, 3 corners, 3 coordinates), got {tri.shape}")
    if tri.shape[0] == 0:
        raise ValueError(f"{name} is empty: need at least 1 triangle")
    return tri


def rasterize(triangles: ArrayLike, resolution: int, *, w: ArrayLike | None = None, row_centres: ArrayLike | None = None, chunk: int = CHUNK) -> DepthMap:
    """Rasterize triangles given per-corner (s, t, depth) into a z-buffer.

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Per triangle, per corner: map coordinates s, t [map units; the map is [0, 1]²] and a
        depth [any unit; smaller is nearer].  Parts outside the map are clipped.
    resolution : int
        R, texels per side, 1 ≤ R ≤ :data:`MAX_RESOLUTION`.
    w : array_like, shape (T, 3), optional
        Positive homogeneous weights for perspective-correct depth (see the module
        docstring); default: depth is affine in (s, t).
    row_centres : array_like, shape (R,), optional
        Increasing t of each row's texel centres (e.g. :func:`log_row_centres`); default
        (j + ½)/R.
    chunk : int
        Rows, or texels, per vectorized step (temporaries ≈ 250 bytes per row, 50 per texel).

    Returns
    -------
    DepthMap

    Raises
    ------
    ValueError
        Empty or malformed ``triangles``, resolution outside [1, MAX_RESOLUTION], bad ``w``
        or ``row_centres``.

    Example
    -------
    >>> import numpy as np
    >>> sq = np.array([[[0, 0, 1], [1, 0, 1], [1, 1, 1]], [[0, 0, 2], [1, 1, 2], [0, 1, 2]]], float)
    >>> m = rasterize(sq, 4)
    >>> (m.triangle >= 0).all(), sorted(np.unique(m.depth).tolist())   # diagonal texels to one triangle only
    (np.True_, [1.0, 2.0])
    """
    tri = _triangles(triangles)
    res = check_resolution(resolution)
    chunk = check_chunk(chunk)
    inv_w, rows, uniform_rows = weights_and_rows(tri, res, w, row_centres)
    return zbuffer(tri, res, inv_w, rows, uniform_rows, chunk)


def rasterize_at(triangles: ArrayLike, resolution: int, row: ArrayLike, col: ArrayLike, *, w: ArrayLike | None = None,
                 row_centres: ArrayLike | None = None, chunk: int = CHUNK) -> tuple[Array, NDArray[np.int64]]:
    """:func:`rasterize`'s depth and visible triangle at the texels (``row``, ``col``) only, bit for bit the whole map's.

    Only the rows holding an asked texel are set up and each span only at the asked texels
    (:func:`zbuffer_at`): the work grows with the texels asked, not with R².

    Parameters
    ----------
    triangles, resolution, w, row_centres, chunk
        As for :func:`rasterize`.
    row, col : array_like of int
        Texel indices, whole numbers in [0, R) of one shape [texels].

    Returns
    -------
    depth : ndarray
        The depth at each asked texel [the triangles' depth unit], ``inf`` where empty; the shape of ``row``.
    triangle : ndarray of int64
        The visible triangle's index, −1 where empty.

    Raises
    ------
    ValueError
        As :func:`rasterize`, and ``row``/``col`` not whole texel indices of one shape.

    Example
    -------
    >>> import numpy as np
    >>> sq = np.array([[[0, 0, 1], [1, 0, 1], [1, 1, 1]], [[0, 0, 2], [1, 1, 2], [0, 1, 2]]], float)
    >>> d, t = rasterize_at(sq, 4, [[0, 3], [3, 3]], [[3, 0], [3, 3]])     # below and above the diagonal, twice one texel
    >>> d.tolist(), t.tolist(), bool((d == rasterize(sq, 4).depth[[[0, 3], [3, 3]], [[3, 0], [3, 3]]]).all())
    ([[1.0, 2.0], [1.0, 1.0]], [[0, 1], [0, 0]], True)
    """
    tri = _triangles(triangles)
    res = check_resolution(resolution)
    chunk = check_chunk(chunk)
    flat = texel_indices(row, col, res)
    inv_w, rows, uniform_rows = weights_and_rows(tri, res, w, row_centres)
    asked, where = np.unique(flat, return_inverse=True)
    depth, ident, _, _ = zbuffer_at(tri, res, inv_w, rows, uniform_rows, chunk, asked)
    return depth[where].reshape(flat.shape), ident[where].reshape(flat.shape)


def texel_indices(row: ArrayLike, col: ArrayLike, res: int) -> NDArray[np.int64]:
    """Flat texel indices row·R + column of whole texel indices (``row``, ``col``) in [0, R) of one shape (refused by name otherwise)."""
    r, c = np.asarray(row), np.asarray(col)
    if r.shape != c.shape or r.dtype.kind not in "iu" or c.dtype.kind not in "iu" or (r.size and (min(r.min(), c.min()) < 0 or max(r.max(), c.max()) >= res)):
        raise ValueError(f"row and col must be whole texel indices in [0, {res - 1}] of one shape, got {r.dtype} {r.shape} and {c.dtype} {c.shape}")
    return r.astype(np.int64) * res + c.astype(np.int64)


#: Bytes of the tables released (:meth:`TexelStore.release`) kept for the next stores, at most [bytes].
TABLES_KEPT = 2**28
_TABLES: dict = {}


def _table(size: int, dtype=np.int32) -> NDArray:
    """A zeroed table of ``size`` entries of ``dtype``: a released one if kept, else a new one."""
    try:
        return _TABLES.get((np.dtype(dtype).str, size), []).pop()
    except IndexError:
        return np.zeros(size, dtype)


def _give_back(table: NDArray) -> None:
    """Keep a zeroed table for the next store (up to :data:`TABLES_KEPT` bytes in all)."""
    if sum(t.nbytes for v in _TABLES.values() for t in v) + table.nbytes <= TABLES_KEPT:
        _TABLES.setdefault((table.dtype.str, table.size), []).append(table)


class TexelStore:
    """The texels of one map found so far (depth and triangle by flat index row·R + column): which of those asked are missing, add, read.

    ``size``: the map's texels R²; given, the store keeps a table of 4 bytes per texel from
    flat index to slot, and a question costs one gather instead of a binary search (for maps
    that fit: R² up to 2³¹); None: sorted keys only, memory as the texels found.  A table is
    taken from the tables released before (:meth:`release`, up to :data:`TABLES_KEPT` bytes kept):
    a fresh one costs the system a page fault per 4 KiB the first time it is written.

    Example
    -------
    >>> import numpy as np
    >>> for kept in (TexelStore(), TexelStore(size=16)):
    ...     m = kept.missing(np.array([7, 3, 7])).tolist()
    ...     kept.add(np.array([3, 7]), np.array([0.5, np.inf]), np.array([2, -1]))
    ...     print(m, kept.missing(np.array([7, 9])).tolist(), [v.tolist() for v in kept.get(np.array([[7, 3]]))], len(kept),
    ...           kept.holds(np.array([3, 7])), kept.holds(np.array([3, 9])))
    [3, 7] [9] [[[inf, 0.5]], [[-1, 2]]] 2 True False
    [3, 7] [9] [[[inf, 0.5]], [[-1, 2]]] 2 True False
    """

    def __init__(self, size: int | None = None) -> None:
        self._flat = np.zeros(0, np.int64)
        self._depth = np.zeros(0)
        self._ident = np.zeros(0, np.int64)
        if size is not None and not (isinstance(size, (int, np.integer)) and 1 <= size <= 2**31):
            raise ValueError(f"size must be a whole number of texels in [1, 2**31] or None, got {size!r}")
        self._slot = None if size is None else _table(int(size))  # slot + 1, 0: missing
        self._mark: NDArray[np.bool_] | None = None  # missing's table (size entries), made when first needed

    def __len__(self) -> int:
        return int(self._flat.size)

    def release(self) -> None:
        """Give the slot table back for another store of the same size (cleared where written); the store is then empty."""
        if self._slot is not None:
            self._slot[self._flat] = 0
            _give_back(self._slot)
            self._slot = np.zeros(0, np.int32)  # released: this store holds nothing more
        if self._mark is not None:
            _give_back(self._mark)  # all False between questions
            self._mark = None
        self._flat, self._depth, self._ident = np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64)

    @property
    def nbytes(self) -> int:
        """The bytes held [bytes]."""
        return int(self._flat.nbytes + self._depth.nbytes + self._ident.nbytes + sum(t.nbytes for t in (self._slot, self._mark) if t is not None))

    def holds(self, flat: NDArray[np.int64]) -> bool:
        """Whether every asked flat index is held."""
        flat = np.asarray(flat)
        if not self._flat.size:
            return not flat.size
        if self._slot is not None:
            return bool(self._slot[flat].all())
        pos = np.minimum(np.searchsorted(self._flat, flat), self._flat.size - 1)
        return bool((self._flat[pos] == flat).all())

    def missing(self, flat: NDArray[np.int64]) -> NDArray[np.int64]:
        """The asked flat indices not held, sorted and unique."""
        flat = np.asarray(flat).ravel()
        if self._slot is None:
            if not self._flat.size:
                return np.unique(flat)
            pos = np.minimum(np.searchsorted(self._flat, flat), self._flat.size - 1)
            return np.unique(flat[self._flat[pos] != flat])
        new = flat[self._slot[flat] == 0] if self._flat.size else flat
        if new.size * 16 < self._slot.size:  # a few: sorted
            return _sorted_unique(new)
        if self._mark is None:  # many (a frame's texels, repeated by its neighbouring pixels): marked on a table and read back in order
            self._mark = _table(self._slot.size, bool)
        self._mark[new] = True
        out = np.flatnonzero(self._mark)
        self._mark[out] = False
        return out

    def add(self, flat: NDArray[np.int64], depth: Array, ident: NDArray[np.int64]) -> None:
        """Hold the values of flat indices not held yet (:meth:`missing`'s)."""
        if self._slot is not None:  # appended: the table says where
            self._slot[flat] = np.arange(self._flat.size + 1, self._flat.size + flat.size + 1, dtype=np.int32)
            self._flat, self._depth, self._ident = (np.concatenate(v) for v in ((self._flat, flat), (self._depth, depth), (self._ident, ident)))
            return
        keys = np.concatenate([self._flat, flat])
        order = np.argsort(keys, kind="stable")
        self._flat = keys[order]
        self._depth = np.concatenate([self._depth, depth])[order]
        self._ident = np.concatenate([self._ident, ident])[order]

    def get(self, flat: NDArray[np.int64]) -> tuple[Array, NDArray[np.int64]]:
        """The depth and triangle of held flat indices, in the shape of ``flat``."""
        at = self._slot[flat] - 1 if self._slot is not None else np.searchsorted(self._flat, flat)
        return self._depth[at], self._ident[at]


def weights_and_rows(tri: Array, res: int, w: ArrayLike | None, row_centres: ArrayLike | None) -> tuple[Array, Array, bool]:
    """:func:`rasterize`'s checks of ``w`` and ``row_centres``: (1/w, row centres, whether uniform)."""
    n_tri = tri.shape[0]
    if w is None:
        inv_w = np.ones((n_tri, 3))
    else:
        ww = check.as_float_array(w, "w")
        if ww.shape != (n_tri, 3):
            raise ValueError(f"w must have shape (T, 3) = ({n_tri}, 3), got {ww.shape}")
        if not ((ww > 0) & np.isfinite(ww)).all():
            raise ValueError("w must be in (0, inf) (homogeneous weights of points in front of the projection centre)")
        inv_w = 1.0 / ww
    if row_centres is None:
        rows = (np.arange(res) + 0.5) / res
        uniform_rows = True
    else:
        rows = check.as_float_array(row_centres, "row_centres")
        if rows.shape != (res,) or (np.diff(rows) <= 0).any():
            raise ValueError(f"row_centres must be {res} increasing values (one per row)")
        uniform_rows = False
    return inv_w, rows, uniform_rows


def zbuffer(tri: Array, res: int, inv_w: Array, rows: Array, uniform_rows: bool, chunk: int, *, front_to_back: bool = False, draw=None) -> DepthMap:
    """:func:`rasterize` on checked arguments (``inv_w`` = 1/w, ``rows`` the row centres).

    ``front_to_back``: rasterize the triangles nearest first and skip, block by block, the
    spans already hidden (:mod:`.occlusion`); the same buffers, for scenes with much overdraw.
    ``draw``: how that pass draws a group of triangles (default :func:`.occlusion.draw_visible`).
    """
    depth = np.full(res * res, np.inf)
    ident = np.full(res * res, -1, dtype=np.int64)
    sx, ty, row_coord, area2, good, idx, x0, x1, y0, y1 = _boxes(tri, res, inv_w, rows, uniform_rows)
    if idx.size:
        height = y1 - y0 + 1
        dep = tri[:, :, 2]
        if front_to_back:
            occlusion.rasterize_front_to_back(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident, draw)
        else:
            # groups of triangles with at most `chunk` rows in all (a tall triangle alone may exceed it)
            bounds = chunk_bounds(height, chunk)
            for a, b in zip(bounds[:-1], bounds[1:]):
                rasterize_rows(idx[a:b], x0[a:b], x1[a:b], y0[a:b], height[a:b], sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident)
    return DepthMap(depth.reshape(res, res), ident.reshape(res, res), res, int(good.sum()), int(tri.shape[0] - good.sum()))


def _sorted_unique(values: NDArray[np.int64], presorted: bool = False) -> NDArray[np.int64]:
    """The distinct values, sorted (a sort and a comparison of neighbours: faster than hashing for these sizes)."""
    v = values if presorted else np.sort(values)
    return v[np.concatenate([[True], v[1:] != v[:-1]])] if v.size else v


def zbuffer_at(tri: Array, res: int, inv_w: Array, rows: Array, uniform_rows: bool, chunk: int, texels: NDArray[np.int64]) -> tuple[Array, NDArray[np.int64], int, int]:
    """:func:`zbuffer` at the given texels only: (depth, triangle) of ``texels`` (sorted unique
    flat indices row·R + column), and the counts rasterized and degenerate.

    Only the (triangle, row) pairs of rows holding an asked texel are set up, and each row's
    span only at the asked texels (:func:`.coverage.merge_at`): memory and work grow with the
    texels asked (times their overdraw) and the triangles, not with R².  The values are the
    whole map's, bit for bit (the same per-pair formulas, the same tie rule).
    """
    depth = np.full(texels.size, np.inf)
    ident = np.full(texels.size, -1, dtype=np.int64)
    sx, ty, row_coord, area2, good, idx, x0, x1, y0, y1 = _boxes(tri, res, inv_w, rows, uniform_rows)
    need = _sorted_unique(texels // res, presorted=True)
    lo = np.searchsorted(need, y0, side="left")
    count = np.searchsorted(need, y1, side="right") - lo  # asked rows inside each triangle's box
    if idx.size and texels.size:
        dep = tri[:, :, 2]
        bounds = chunk_bounds(count, chunk)
        for a, b in zip(bounds[:-1], bounds[1:]):
            owner, k = expand(count[a:b])
            owner += a
            row = need[lo[owner] + k]
            hit = np.searchsorted(texels, row * res + x1[owner], side="right") > np.searchsorted(texels, row * res + x0[owner], side="left")
            owner, row = owner[hit], row[hit]  # pairs with an asked texel inside the triangle's column box
            sp = pair_spans(idx[owner], row, x0[owner], x1[owner], sx, ty, row_coord, dep, inv_w, area2, res)
            merge_at(sp, res, chunk, texels, depth, ident)
    return depth, ident, int(good.sum()), int(tri.shape[0] - good.sum())


def _boxes(tri: Array, res: int, inv_w: Array, rows: Array, uniform_rows: bool) -> tuple:
    """The drawn triangles and their texel boxes: (sx, ty, row coordinates, 2·area, good,
    indices, x0, x1, y0, y1), boxes of texel indices whose centres lie inside [lo, hi]."""
    # texel units for s (and t when rows are uniform): keeps edge functions well scaled
    sx = tri[:, :, 0] * res
    ty = tri[:, :, 1] * res if uniform_rows else tri[:, :, 1]
    row_coord = rows * res if uniform_rows else rows
    area2 = (sx[:, 1] - sx[:, 0]) * (ty[:, 2] - ty[:, 0]) - (sx[:, 2] - sx[:, 0]) * (ty[:, 1] - ty[:, 0])
    finite = np.isfinite(tri).all(axis=(1, 2)) & np.isfinite(inv_w).all(axis=1)
    good = finite & (area2 != 0) & np.isfinite(area2)
    good &= np.abs(area2) > 1e-12 * (np.ptp(sx, axis=1) * np.ptp(ty, axis=1) + 1e-300)
    idx = np.nonzero(good)[0]
    # bounding boxes in texel indices (centre inside [lo, hi])
    with np.errstate(invalid="ignore"):
        x0 = np.clip(np.ceil(sx[idx].min(axis=1) - 0.5), 0, res).astype(np.int64)
        x1 = np.clip(np.floor(sx[idx].max(axis=1) - 0.5), -1, res - 1).astype(np.int64)
    y0 = np.searchsorted(row_coord, ty[idx].min(axis=1), side="left").astype(np.int64)
    y1 = np.searchsorted(row_coord, ty[idx].max(axis=1), side="right").astype(np.int64) - 1
    keep = (x1 >= x0) & (y1 >= y0)
    return sx, ty, row_coord, area2, good, idx[keep], x0[keep], x1[keep], y0[keep], y1[keep]


def clip_near(tri: Array, z_clip: float) -> tuple[Array, NDArray[np.int64]]:
    """Clip triangles to z ≥ z_clip; returns the new triangles and their source indices."""
    behind = tri[:, :, 2] < z_clip
    nb = behind.sum(axis=1)
    keep = tri[nb == 0]
    src = [np.nonzero(nb == 0)[0]]
    out = [keep]
    for count in (1, 2):
        sel = np.nonzero(nb == count)[0]
        if sel.size == 0:
            continue
        t = tri[sel]
        b = behind[sel]
        # rotate corners so that the odd one out (behind if count == 1, in front if 2) is first
        odd = b if count == 1 else ~b
        first = np.argmax(odd, axis=1)
        order = (first[:, None] + np.arange(3)) % 3
        t = np.take_along_axis(t, order[:, :, None], axis=1)
        a, p1, p2 = t[:, 0], t[:, 1], t[:, 2]
        q1 = a + (p1 - a) * ((z_clip - a[:, 2]) / (p1[:, 2] - a[:, 2]))[:, None]
        q2 = a + (p2 - a) * ((z_clip - a[:, 2]) / (p2[:, 2] - a[:, 2]))[:, None]
        if count == 1:  # quad q1, p1, p2, q2
            out += [np.stack([q1, p1, p2], 1), np.stack([q1, p2, q2], 1)]
            src += [sel, sel]
        else:  # triangle a, q1, q2
            out.append(np.stack([a, q1, q2], 1))
            src.append(sel)
    return np.concatenate(out), np.concatenate(src)


