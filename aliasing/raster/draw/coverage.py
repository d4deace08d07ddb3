"""Coverage: the exact covered span of every (triangle, row) and the depths along it.

are expanded into (triangle, row) pairs with ``np.repeat``.  Along a row each edge function
is monotone (in rounded arithmetic too), so the covered texels form an interval: its ends
are estimated from the edges' intersections with the row's centre line and settled exactly
by the edge-function test (with the top-left rule) at the estimate ± 1 texel.  Depth is a
ratio of two affine functions of the column along a row; the spans are expanded into
(triangle, texel) pairs and merged into the z-buffer with ``np.minimum.at`` (the triangle
id map keeps the candidate equal to the running minimum).  Rows and texels are processed in
chunks of at most ``chunk``, so memory is bounded by the chunk size, not by the triangles'
size, and the work is the covered area plus a few tests per row.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]


def chunk_bounds(size: NDArray[np.int64], chunk: int) -> NDArray[np.int64]:
    """Cut indices into consecutive groups whose summed size is ≤ chunk (or of one element)."""
    cum = np.cumsum(size)
    n = size.size
    bounds = [0]
    while bounds[-1] < n:
        base = int(cum[bounds[-1] - 1]) if bounds[-1] else 0
        nxt = int(np.searchsorted(cum, base + chunk, side="right"))
        bounds.append(min(max(nxt, bounds[-1] + 1), n))
    return np.asarray(bounds)


def expand(counts: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """(owner, k) for k in range(counts[owner]), for every owner: the vectorized double loop."""
    owner = np.repeat(np.arange(counts.size), counts)
    first = np.cumsum(counts) - counts
    return owner, np.arange(owner.size) - first[owner]


def _edges(ax: Array, ay: Array, sgn: Array) -> list[tuple[Array, Array, Array, Array]]:
    """Per edge opposite corner e: origin (x, y) and counter-clockwise direction (ex, ey)."""
    out = []
    for e in range(3):
        i0, i1 = (e + 1) % 3, (e + 2) % 3
        out.append((ax[:, i0], ay[:, i0], (ax[:, i1] - ax[:, i0]) * sgn, (ay[:, i1] - ay[:, i0]) * sgn))
    return out


def _inside(edges, px: Array, py: Array) -> NDArray[np.bool_]:
    """The exact coverage predicate (edge functions with the top-left rule) at texel centres."""
    ok = np.ones(px.shape, dtype=bool)
    for ox, oy, ex, ey in edges:
        f = ex * (py - oy) - ey * (px - ox)  # > 0 on the inner side; monotone in px even rounded
        owns = (ey < 0) | ((ey == 0) & (ex > 0))
        ok &= (f > 0) | ((f == 0) & owns)
    return ok


class Spans(NamedTuple):
    """The non-empty covered spans of (triangle, row) pairs: texels col_lo … col_lo + width − 1
    of ``row`` belong to triangle ``t_id``; along the row d/w = n0 + n1·px and 1/w = m0 + m1·px
    (px the texel centre's column coordinate), so the depth is their ratio."""

    row: NDArray[np.int64]
    t_id: NDArray[np.int64]
    col_lo: NDArray[np.int64]
    width: NDArray[np.int64]
    n0: Array
    n1: Array
    m0: Array
    m1: Array

    def depth_at(self, span: NDArray[np.int64], px: Array) -> Array:
        """Interpolated depth of span ``span`` at column coordinate ``px`` (the one formula)."""
        return (self.n0[span] + self.n1[span] * px) / (self.m0[span] + self.m1[span] * px)


def rasterize_rows(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident) -> None:
    """Rasterize a group of triangles: their spans (:func:`row_spans`) merged into the z-buffer."""
    merge(row_spans(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res), res, chunk, depth, ident)


def row_spans(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res) -> Spans:
    """Exact covered span of every (triangle, row) and the depth along it.

    Each edge function is monotone along a row (also in rounded arithmetic), so the covered
    texels of a row are an interval; its ends are estimated from the edges' intersections
    with the row's centre line and settled by the exact predicate at the estimate ± 1.
    """
    owner, k = expand(height)
    return pair_spans(idx[owner], y0[owner] + k, x0[owner], x1[owner], sx, ty, row_coord, dep, inv_w, area2, res)


def pair_spans(t_id, row, bx0, bx1, sx, ty, row_coord, dep, inv_w, area2, res) -> Spans:
    """:func:`row_spans` of given (triangle ``t_id``, ``row``) pairs, ``bx0`` … ``bx1`` the
    triangle's column box.  Every value is computed per pair, so a pair's span and depths do
    not depend on which other pairs are computed with it."""
    y = row_coord[row]
    ax, ay = sx[t_id], ty[t_id]
    lo = np.full(row.size, np.inf)
    hi = np.full(row.size, -np.inf)
    for e in range(3):
        i0, i1 = e, (e + 1) % 3
        ya, yb = ay[:, i0], ay[:, i1]
        cross = (np.minimum(ya, yb) <= y) & (y <= np.maximum(ya, yb)) & (ya != yb)
        with np.errstate(divide="ignore", invalid="ignore"):
            xe = ax[:, i0] + (y - ya) * (ax[:, i1] - ax[:, i0]) / (yb - ya)
        lo = np.where(cross, np.minimum(lo, xe), lo)
        hi = np.where(cross, np.maximum(hi, xe), hi)
    has = np.isfinite(lo) & np.isfinite(hi)
    lo_e = np.clip(np.ceil(np.where(has, lo, 0.0) - 0.5), -2, res + 1).astype(np.int64)
    hi_e = np.clip(np.floor(np.where(has, hi, -1.0) - 0.5), -2, res + 1).astype(np.int64)
    sgn = np.sign(area2[t_id])
    edges = _edges(ax, ay, sgn)
    # the true ends are within one texel of the estimates (rounding only), so the smallest
    # and largest covered columns among estimate - 1 .. estimate + 1 (kept inside the bounding
    # box) are the exact ends; none covered means an empty row (e.g. on a horizontal edge
    # that this triangle does not own)
    col_lo = np.full(row.size, res + 5, dtype=np.int64)
    for d in (1, 0, -1):
        c = np.clip(lo_e + d, bx0, bx1)
        col_lo = np.where(_inside(edges, c + 0.5, y), c, col_lo)
    col_hi = np.full(row.size, -5, dtype=np.int64)
    for d in (-1, 0, 1):
        c = np.clip(hi_e + d, bx0, bx1)
        col_hi = np.where(_inside(edges, c + 0.5, y), c, col_hi)
    width = np.where(has, np.maximum(col_hi - col_lo + 1, 0), 0)
    # depth along the row: barycentrics are affine in px, so d/w and 1/w are (a + b px)
    denom = np.abs(area2[t_id])
    iw = inv_w[t_id]
    dw = dep[t_id] * iw
    n0 = np.zeros(row.size)
    n1 = np.zeros(row.size)
    m0 = np.zeros(row.size)
    m1 = np.zeros(row.size)
    for e, (ox, oy, ex, ey) in enumerate(edges):
        f0 = (ex * (y - oy) + ey * ox) / denom  # b_e at px = 0
        f1 = -ey / denom  # db_e/dpx
        n0 += f0 * dw[:, e]
        n1 += f1 * dw[:, e]
        m0 += f0 * iw[:, e]
        m1 += f1 * iw[:, e]
    live = width > 0
    row, t_id, col_lo, width = row[live], t_id[live], col_lo[live], width[live]
    n0, n1, m0, m1 = n0[live], n1[live], m0[live], m1[live]
    return Spans(row, t_id, col_lo, width, n0, n1, m0, m1)


def merge(sp: Spans, res: int, chunk: int, depth: Array, ident: NDArray[np.int64]) -> None:
    """Expand spans into texels, in chunks of at most ``chunk``, and merge them into the z-buffer.

    ``depth`` keeps the minimum; ``ident`` the triangle of the last texel drawn at that
    minimum: spans come in increasing triangle order, so ties go to the highest index.
    """
    bounds = chunk_bounds(sp.width, chunk)
    for a, b in zip(bounds[:-1], bounds[1:]):
        span, kk = expand(sp.width[a:b])
        span += a
        col = sp.col_lo[span] + kk
        z = sp.depth_at(span, col + 0.5)
        pix = sp.row[span] * res + col
        np.minimum.at(depth, pix, z)
        win = z <= depth[pix]
        ident[pix[win]] = sp.t_id[span[win]]


def merge_at(sp: Spans, res: int, chunk: int, texels: NDArray[np.int64], depth: Array, ident: NDArray[np.int64]) -> None:
    """:func:`aliasing.raster.draw.coverage.merge` into the given texels only: ``texels`` sorted unique flat indices
    (row·R + column), ``depth`` and ``ident`` their buffers (same length).

    Each span is cut to the asked texels inside it (two binary searches), so the work and the
    temporaries are the asked texels' overdraw, not the map's area.  The depths are the same
    formula at the same columns as :func:`merge`'s, and the merge keeps the minimum with ties
    to the last span (the highest triangle index): the asked texels get exactly the values
    of the whole map.
    """
    start = sp.row * res + sp.col_lo
    first = np.searchsorted(texels, start, side="left")
    count = np.searchsorted(texels, start + sp.width, side="left") - first
    bounds = chunk_bounds(count, chunk)
    for a, b in zip(bounds[:-1], bounds[1:]):
        span, kk = expand(count[a:b])
        span += a
        j = first[span] + kk
        col = texels[j] - sp.row[span] * res
        z = sp.depth_at(span, col + 0.5)
        np.minimum.at(depth, j, z)
        win = z <= depth[j]
        ident[j[win]] = sp.t_id[span[win]]
