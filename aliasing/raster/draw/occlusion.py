"""Occlusion culling for scenes with much overdraw (the eye pass): the same z-buffer, less work.

Triangles are rasterized nearest first (sorted by their corners' mean depth: a large triangle
reaching far back goes after the small ones in front of it), in groups
of at most :data:`GROUP`·R rows.  Before a group is rasterized, a triangle is skipped when its
nearest corner lies beyond the farthest depth stored in every tile (:data:`TILE` rows ×
:data:`BLOCK` columns) its bounding box touches; a triangle's depth is a weighted mean of its corners' (weights b/w ≥ 0), so none of
its texels could win.  Then, before its exact span is computed, a (triangle, row) is skipped
when the depths where the row's centre line enters and leaves the triangle both lie beyond the
farthest depth stored in the blocks around that segment (:func:`_live_rows`).  Before each
batch of at most :data:`BATCH` texels is generated, every covered span is cut at blocks of
:data:`BLOCK` columns, and a piece is skipped when its nearest depth lies beyond the
farthest depth already stored in its block: every texel of the piece would lose the depth
test.  Depth along a span is monotone (a ratio of affine functions with a positive
denominator), so a piece's nearest depth is at one of its ends.  All tests keep a
rounding margin of :data:`MARGIN` times the triangle's largest corner depth (interpolation
rounds relative to it), so no texel that could win is ever skipped.

The merge is order-independent, so the result does not depend on the drawing order: each
texel keeps the minimum depth and, among the triangles reaching it exactly, the highest
index, which is what :func:`aliasing.raster.draw.coverage.merge` gives when triangles are drawn in
index order (the plain :func:`aliasing.raster.draw`).

Example
-------
>>> import numpy as np
>>> from aliasing.raster.draw import core
>>> tri = np.array([[[0, 0, 2.0], [1, 0, 2.0], [0, 1, 2.0]], [[0, 0, 1.0], [1, 0, 1.0], [0, 1, 1.0]]])
>>> a = core.zbuffer(tri, 8, np.ones((2, 3)), (np.arange(8) + 0.5) / 8, True, 1 << 20, front_to_back=True)
>>> sorted(np.unique(a.triangle).tolist()), float(a.depth[0, 0])   # the far triangle is hidden
([-1, 1], 1.0)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .coverage import Spans, chunk_bounds, expand, row_spans

Array = NDArray[np.float64]

#: Columns per culling block (a power of 2): a piece is skipped when wholly behind its block's farthest depth.
BLOCK = 16
#: Rows per group of triangles, in units of R: the buffer is culled against between groups.
GROUP = 4
#: Tile side [texels] of the triangle test: a triangle is skipped when its box lies behind its tiles.
TILE = 16
#: Texels per merge step at most (and ``chunk``): the temporaries stay in cache, and ``far`` is
#: refreshed between steps, so later spans of a group are culled against earlier ones.
BATCH = 1 << 16
#: Blocks of a row segment tested by the row test at most (wider rows are drawn).
ROW_BLOCKS = 8
#: Rounding margin of the tests, relative to the triangle's depth scale (never skip a texel that could win).
MARGIN = 1e-9


def rasterize_front_to_back(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident, draw=None) -> None:
    """Rasterize triangles ``idx`` nearest first, skipping hidden ones and hidden pieces (module docstring).

    Groups of at most :data:`GROUP`·R rows (and ``chunk``): each is culled against the
    buffer the nearer groups left.  ``far`` (farthest stored depth per row and block of
    :data:`BLOCK` columns) starts at inf and is kept up to date only where texels were
    drawn: depths only decrease, so elsewhere it is at worst too far (safe).  ``draw``: how a group of triangles is
    drawn, :func:`draw_visible` by default (:func:`.compiled.draw` has its signature).
    """
    draw = draw_visible if draw is None else draw
    order = np.argsort(dep[idx].mean(axis=1), kind="stable")  # any order gives the same buffers; this one culls well
    idx, x0, x1, y0, height = idx[order], x0[order], x1[order], y0[order], height[order]
    scale = np.abs(dep).max(axis=1)  # per triangle: interpolated depths round relative to it
    near = dep[idx].min(axis=1) - MARGIN * scale[idx]  # a weighted mean of the corners' depths is never nearer
    y1 = y0 + height - 1
    cum = np.cumsum(height)
    # ``far`` may only ever be too far (then it culls less, never wrongly): zbuffer's buffers
    # start empty, so start at inf rather than reducing R² depths
    far = np.full((res, -(-res // BLOCK)), np.inf)
    a = 0
    while a < idx.size:
        b = max(int(np.searchsorted(cum, (cum[a - 1] if a else 0) + min(GROUP * res, chunk), side="right")), a + 1)
        sel = np.arange(a, b)
        if a:  # skip triangles whose bounding box lies wholly behind the stored depths
            sel = sel[_visible_boxes(near[a:b], x0[a:b], x1[a:b], y0[a:b], y1[a:b], res, far, chunk)]
        a = b
        if sel.size:
            draw(idx[sel], x0[sel], x1[sel], y0[sel], height[sel], sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident, far, scale)


def draw_visible(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident, far, scale) -> None:
    """Draw a group of triangles: their spans (:func:`.coverage.row_spans`) merged by :func:`merge_visible`.

    Rows wholly behind the stored depths (:func:`_live_rows`) are dropped first, so their
    exact spans are never computed.
    """
    t, row, x0, x1 = _live_rows(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, res, far, scale)
    sp = row_spans(t, x0, x1, row, np.ones_like(row), sx, ty, row_coord, dep, inv_w, area2, res)
    merge_visible(sp, res, chunk, depth, ident, far, scale)


def _live_rows(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, res: int, far: Array, scale: Array):
    """(triangle, row, x0, x1) of the rows of triangles ``idx`` that may hold a visible texel.

    With the corners sorted by t (top, middle, bottom), a row's centre line meets the
    triangle in a segment from the long edge (top–bottom) to the short edge it crosses
    (top–middle above the middle corner, middle–bottom from it on).  Depth along the segment
    is monotone, so no texel of the row is nearer than its ends' depths (perspective-correct
    interpolation along those edges).  A row is dropped when that bound, less the rounding
    margin, lies beyond the farthest stored depth of every block within two texels of the
    segment (the exact ends are within one texel of the estimate).
    """
    owner, k = expand(height)
    row = y0.take(owner) + k
    y = row_coord.take(row)
    order = np.argsort(ty[idx], axis=1, kind="stable")  # per triangle: corners top, middle, bottom
    cx, cy, cd, cw = (np.take_along_axis(a[idx], order, axis=1).ravel() for a in (sx, ty, dep, inv_w))
    first = owner * 3
    mid = first + 1
    upper = y < cy.take(mid)
    short = first + (~upper)  # the short edge's first corner: top above the middle corner, else middle
    ends = []
    with np.errstate(divide="ignore", invalid="ignore"):
        for a, b in ((first, first + 2), (short, short + 1)):
            ya, yb = cy.take(a), cy.take(b)
            f = (y - ya) / (yb - ya)  # in [0, 1] (rounding is monotone); 0/0 only on a horizontal bottom edge, at its row
            f[yb == ya] = 0.0
            xa, wa, wb = cx.take(a), (1.0 - f) * cw.take(a), f * cw.take(b)
            ends.append((xa + f * (cx.take(b) - xa), (wa * cd.take(a) + wb * cd.take(b)) / (wa + wb)))
    (xl, dl), (xs, ds) = ends
    near = np.minimum(dl, ds)
    bx0, bx1 = x0.take(owner), x1.take(owner)
    c0 = np.minimum(np.maximum(np.floor(np.minimum(xl, xs)) - 2, bx0), bx1).astype(np.int64) // BLOCK
    c1 = np.minimum(np.maximum(np.ceil(np.maximum(xl, xs)) + 2, bx0), bx1).astype(np.int64) // BLOCK
    # farthest stored depth over blocks c0 … c1 (rows wider than ROW_BLOCKS blocks are kept)
    last = np.minimum(c1 - c0, ROW_BLOCKS - 1)
    start = row * far.shape[1] + c0
    far_flat = far.reshape(-1)
    row_far = far_flat.take(start)
    for j in range(1, ROW_BLOCKS):
        np.maximum(row_far, far_flat.take(start + np.minimum(j, last)), out=row_far)
    row_far[c1 - c0 >= ROW_BLOCKS] = np.inf
    t = idx.take(owner)
    live = np.flatnonzero(~(near - MARGIN * scale.take(t) > row_far))
    return t.take(live), row.take(live), bx0.take(live), bx1.take(live)


def _block_far(depth: Array, res: int) -> Array:
    """Farthest stored depth per row and block of :data:`BLOCK` columns, (R, ⌈R/BLOCK⌉); inf if a texel is empty."""
    return np.maximum.reduceat(depth.reshape(res, res), np.arange(0, res, BLOCK), axis=1)


def _refresh(far_flat: Array, depth: Array, res: int, fb: NDArray[np.int64]) -> None:
    """Recompute the farthest depth of blocks ``fb`` (flat indices into ``far``; repeats allowed).

    A block is BLOCK consecutive texels of ``depth`` unless the last block of a row is partial
    (R not a multiple of :data:`BLOCK`), which repeats its row's last texel.
    """
    if res % BLOCK == 0:
        m = depth.reshape(-1, BLOCK).take(fb, axis=0).ravel()
    else:
        nb = -(-res // BLOCK)
        row, blk = np.divmod(fb, nb)
        m = depth.take(row[:, None] * res + np.minimum(blk[:, None] * BLOCK + np.arange(BLOCK), res - 1)).ravel()
    while m.size > fb.size:  # pairwise halving (BLOCK is a power of 2) in long 1-D loops: ~5× a reduction over a short axis
        m = np.maximum(m[0::2], m[1::2])
    far_flat[fb] = m


def _tile_far(far: Array) -> Array:
    """Farthest of ``far`` per :data:`TILE` rows (the last tile may be partial), (⌈rows/TILE⌉, blocks); a max over a reshape is ~5× reduceat's speed."""
    n = far.shape[0] - far.shape[0] % TILE
    tiles = far[:n].reshape(-1, TILE, far.shape[1]).max(axis=1)
    return np.vstack([tiles, far[n:].max(axis=0, keepdims=True)]) if n < far.shape[0] else tiles


def _visible_boxes(near: Array, x0, x1, y0, y1, res: int, far: Array, chunk: int) -> NDArray[np.bool_]:
    """False for a bounding box whose every tile's farthest stored depth is nearer than ``near``.

    Only the tile rows the boxes touch are reduced; tiles are expanded per box in groups of
    at most ``chunk`` tiles (bounded memory).
    """
    top = int(y0.min()) // TILE
    tiles_far = _tile_far(far[top * TILE:(int(y1.max()) // TILE + 1) * TILE])
    tx0, tx1, ty0, ty1 = x0 // BLOCK, x1 // BLOCK, y0 // TILE - top, y1 // TILE - top
    nx = tx1 - tx0 + 1
    count = nx * (ty1 - ty0 + 1)
    box_far = np.empty(near.size)
    bounds = chunk_bounds(count, chunk).tolist()
    for a, b in zip(bounds[:-1], bounds[1:]):
        box, k = expand(count[a:b])
        box += a
        ny, nxb = np.divmod(k, nx.take(box))
        tiles = tiles_far.reshape(-1).take((ty0.take(box) + ny) * tiles_far.shape[1] + tx0.take(box) + nxb)
        box_far[a:b] = np.maximum.reduceat(tiles, np.cumsum(count[a:b]) - count[a:b])
    return ~(near > box_far)


def merge_visible(sp: Spans, res: int, chunk: int, depth: Array, ident: NDArray[np.int64], far: Array, scale: Array) -> None:
    """Merge spans into the z-buffer (min depth, then highest triangle index), skipping hidden pieces.

    ``far``: per block, the farthest stored depth (:func:`_block_far`) or farther (never
    nearer: a stale block only culls less); C-contiguous, refreshed here where texels are
    drawn.  ``scale``: each triangle's largest absolute corner depth (for the rounding margin).
    Spans go in steps of at most ``min(chunk, BATCH)`` texels (:data:`BATCH`).
    """
    nb = far.shape[1]
    far_flat = far.reshape(-1)  # a view: far is C-contiguous
    col_hi = sp.col_lo + sp.width - 1
    b_lo = sp.col_lo // BLOCK
    pieces = col_hi // BLOCK - b_lo + 1
    margin = MARGIN * scale[sp.t_id]
    first = sp.row * nb + b_lo  # far_flat index of each span's first block
    bounds = chunk_bounds(sp.width, min(chunk, BATCH)).tolist()
    for a, b in zip(bounds[:-1], bounds[1:]):
        span, k = expand(pieces[a:b])
        span += a
        blk = b_lo.take(span) + k
        c0 = np.maximum(sp.col_lo.take(span), blk * BLOCK)
        c1 = np.minimum(col_hi.take(span), blk * BLOCK + (BLOCK - 1))
        n0, n1, m0, m1 = sp.n0.take(span), sp.n1.take(span), sp.m0.take(span), sp.m1.take(span)
        p0, p1 = c0 + 0.5, c1 + 0.5
        near = np.minimum((n0 + n1 * p0) / (m0 + m1 * p0), (n0 + n1 * p1) / (m0 + m1 * p1))  # Spans.depth_at at both ends
        fb = first.take(span) + k
        live = np.flatnonzero(~(near - margin.take(span) > far_flat.take(fb)))
        # texels of the live pieces: per-piece values repeated per texel (np.repeat beats a
        # gather by owner at these sizes: the step's arrays stay in cache)
        sl = span.take(live)
        c0, w, fb = c0.take(live), c1.take(live) - c0.take(live) + 1, fb.take(live)
        start = np.cumsum(w)
        start -= w
        c0 -= start  # a texel's column: c0 − start + its index in the step
        n = int(start[-1] + w[-1]) if w.size else 0
        px = np.arange(n, dtype=np.float64)
        px += np.repeat(c0 + 0.5, w)  # column + ½, exact (integers and halves)
        pix = np.arange(n)
        pix += np.repeat(sp.row.take(sl) * res + c0, w)
        num = np.repeat(n1.take(live), w)
        num *= px
        num += np.repeat(n0.take(live), w)
        den = np.repeat(m1.take(live), w)
        den *= px
        den += np.repeat(m0.take(live), w)
        z = np.divide(num, den, out=num)  # (n0 + n1 px) / (m0 + m1 px): Spans.depth_at
        before = depth.take(pix)
        np.minimum.at(depth, pix, z)
        after = depth.take(pix)
        ident[pix[after < before]] = -1  # a nearer triangle arrived: forget the old ties
        win = z == after
        np.maximum.at(ident, pix[win], np.repeat(sp.t_id.take(sl), w)[win])
        _refresh(far_flat, depth, res, fb)
