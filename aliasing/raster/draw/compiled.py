"""Optional compiled kernels of the eye pass (numba, the ``fast`` extra): the same buffers, bit for bit.

The numpy eye pass comes within 1.5× of the P and LogP depth maps but not of the Standard
map (target 1.5×; about 1.6–1.8× at 2048², figures in benchmarks/README.md): its
z-buffer expands the covered spans into (texel, triangle) arrays and merges them with
``np.minimum.at``, and the outputs take several passes over 232 MB.  Loops compiled with
numba replace those stages; the rest (near clipping, projection, triangle order and
culling) stays the numpy code:

* ``draw_rows`` — the covered span of every (triangle, row) (:func:`.coverage.row_spans`)
  and the z-test of its texels (minimum depth, ties to the highest triangle index, NaN
  sticks as with ``np.minimum``), skipping hidden pieces; then the culling blocks it lowered
  are refreshed (:mod:`.occlusion`);
* ``eye_outputs`` — triangle id, position and normal of every pixel in one pass.

:func:`merge` (on ``merge_spans``) is the compiled drop-in for
:func:`.occlusion.merge_visible` on given spans.  numba caches the compiled kernels on disk
(``cache=True``): about 2 s to compile once, well under a second to load afterwards.

Both evaluate the numpy path's expressions in the same order, without fast-math, with
numpy's floating-point error model (division by zero gives inf/NaN), so the results are
identical (tests/test_raster_eye.py compares them bit for bit).  Without numba
:func:`available` is False and asking for these kernels raises ValueError.

Example
-------
>>> isinstance(available(), bool)
True
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

try:  # optional: pip install ".[fast]"
    import numba
except ImportError:  # pragma: no cover - depends on the environment
    numba = None

#: The numba extra's install hint, for error messages.
INSTALL = "pip install \".[fast]\""


def available() -> bool:
    """True when numba (the optional ``fast`` extra) is installed.

    Example
    -------
    >>> isinstance(available(), bool)
    True
    """
    return numba is not None


def require() -> None:
    """Raise ValueError when numba is missing (asked for by ``backend="numba"``)."""
    if numba is None:
        raise ValueError(f"backend 'numba' needs numba, which is not installed ({INSTALL}); use backend='numpy'")


def _jit(fn: Callable) -> Callable:
    """Compile lazily with numpy's error model (x/0 → inf/NaN, no exception) and no fast-math."""
    if numba is None:
        return fn
    return numba.njit(cache=True, nogil=True, error_model="numpy", fastmath=False)(fn)


@_jit
def _draw_span(r, t, c0, c1, a0, a1, b0, b1, res, depth, ident, far, block, margin, dirty):  # pragma: no cover - compiled
    """Merge texels c0 … c1 of row r (depth (a0 + a1·px)/(b0 + b1·px)) into the z-buffer.

    A nearer depth takes the texel; an equal one keeps the higher triangle index; a NaN
    depth is stored (as ``np.minimum`` would) and then nothing changes that texel: the merge
    of :func:`.occlusion.merge_visible`, in any order.  As there, a piece within one block of
    ``block`` columns is skipped when its nearest end, less ``margin``, lies beyond the
    block's ``far`` (which may be stale: only ever too far, so the test stays safe); blocks
    whose depths dropped are flagged in ``dirty``.
    """
    nblk = far.shape[1]
    base = r * res
    for b in range(c0 // block, c1 // block + 1):
        lo, hi = max(c0, b * block), min(c1, b * block + block - 1)
        za = (a0 + a1 * (lo + 0.5)) / (b0 + b1 * (lo + 0.5))
        zb = (a0 + a1 * (hi + 0.5)) / (b0 + b1 * (hi + 0.5))
        zn = za if za < zb or za != za else zb  # np.minimum: NaN wins, and NaN never skips
        if zn - margin > far[r, b]:
            continue
        lowered = False
        for c in range(lo, hi + 1):
            px = c + 0.5
            z = (a0 + a1 * px) / (b0 + b1 * px)
            p = base + c
            d = depth[p]
            if z < d:
                depth[p] = z
                ident[p] = t
                lowered = True
            elif z == d:
                if t > ident[p]:
                    ident[p] = t
            elif z != z and d == d:
                depth[p] = z
                lowered = True
        if lowered:
            dirty[r * nblk + b] = True


@_jit
def _refresh(dirty, depth, far, res, block):  # pragma: no cover - compiled
    """Recompute ``far`` (farthest depth per row and block, NaN if any) at the flagged blocks."""
    nblk = far.shape[1]
    for k in range(dirty.size):
        if dirty[k]:
            r, b = k // nblk, k % nblk
            base = r * res
            m = -np.inf
            for c in range(b * block, min(b * block + block, res)):
                v = depth[base + c]
                if v > m or v != v:
                    m = v
                    if v != v:
                        break
            far[r, b] = m


@_jit
def merge_spans(row, t_id, col_lo, width, n0, n1, m0, m1, res, depth, ident, far, block, margin):  # pragma: no cover - compiled
    """Merge :class:`.coverage.Spans` (depth as :meth:`~.coverage.Spans.depth_at`) texel by texel (:func:`_draw_span`)."""
    dirty = np.zeros(far.size, np.bool_)
    for s in range(row.size):
        t = t_id[s]
        _draw_span(row[s], t, col_lo[s], col_lo[s] + width[s] - 1, n0[s], n1[s], m0[s], m1[s], res, depth, ident, far, block, margin[t], dirty)
    _refresh(dirty, depth, far, res, block)


@_jit
def _inside(ex0, ey0, ox0, oy0, ex1, ey1, ox1, oy1, ex2, ey2, ox2, oy2, px, py):  # pragma: no cover - compiled
    """:func:`.coverage._inside` at one point (edge functions with the top-left rule)."""
    ok = True
    for ox, oy, ex, ey in ((ox0, oy0, ex0, ey0), (ox1, oy1, ex1, ey1), (ox2, oy2, ex2, ey2)):
        f = ex * (py - oy) - ey * (px - ox)
        owns = (ey < 0) or (ey == 0 and ex > 0)
        ok = ok and ((f > 0) or (f == 0 and owns))
    return ok


@_jit
def draw_rows(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, depth, ident, far, block, margin):  # pragma: no cover - compiled
    """:func:`.coverage.row_spans` and ``merge_spans`` fused, one (triangle, row) at a time.

    The span ends and the depth coefficients are :func:`.coverage.row_spans`'s expressions,
    evaluated in the same order.
    """
    dirty = np.zeros(far.size, np.bool_)
    for q in range(idx.size):
        t = idx[q]
        ax0, ax1, ax2 = sx[t, 0], sx[t, 1], sx[t, 2]
        ay0, ay1, ay2 = ty[t, 0], ty[t, 1], ty[t, 2]
        sgn = np.sign(area2[t])
        # edges opposite corners 0, 1, 2 (coverage._edges)
        ox0, oy0, ex0, ey0 = ax1, ay1, (ax2 - ax1) * sgn, (ay2 - ay1) * sgn
        ox1, oy1, ex1, ey1 = ax2, ay2, (ax0 - ax2) * sgn, (ay0 - ay2) * sgn
        ox2, oy2, ex2, ey2 = ax0, ay0, (ax1 - ax0) * sgn, (ay1 - ay0) * sgn
        denom = abs(area2[t])
        iw0, iw1, iw2 = inv_w[t, 0], inv_w[t, 1], inv_w[t, 2]
        dw0, dw1, dw2 = dep[t, 0] * iw0, dep[t, 1] * iw1, dep[t, 2] * iw2
        bx0, bx1 = x0[q], x1[q]
        for r in range(y0[q], y0[q] + height[q]):
            y = row_coord[r]
            lo, hi = np.inf, -np.inf
            for xa, ya, xb, yb in ((ax0, ay0, ax1, ay1), (ax1, ay1, ax2, ay2), (ax2, ay2, ax0, ay0)):
                if min(ya, yb) <= y and y <= max(ya, yb) and ya != yb:
                    xe = xa + (y - ya) * (xb - xa) / (yb - ya)
                    lo = xe if xe < lo or xe != xe else lo
                    hi = xe if xe > hi or xe != xe else hi
            if not (math.isfinite(lo) and math.isfinite(hi)):
                continue
            lo_e = min(max(np.ceil(lo - 0.5), -2.0), res + 1.0)
            hi_e = min(max(np.floor(hi - 0.5), -2.0), res + 1.0)
            col_lo = res + 5
            for d in (1, 0, -1):
                c = min(max(np.int64(lo_e) + d, bx0), bx1)
                if _inside(ex0, ey0, ox0, oy0, ex1, ey1, ox1, oy1, ex2, ey2, ox2, oy2, c + 0.5, y):
                    col_lo = c
            col_hi = -5
            for d in (-1, 0, 1):
                c = min(max(np.int64(hi_e) + d, bx0), bx1)
                if _inside(ex0, ey0, ox0, oy0, ex1, ey1, ox1, oy1, ex2, ey2, ox2, oy2, c + 0.5, y):
                    col_hi = c
            if col_hi < col_lo:
                continue
            n0 = n1 = m0 = m1 = 0.0
            for ox, oy, ex, ey, dw, iw in ((ox0, oy0, ex0, ey0, dw0, iw0), (ox1, oy1, ex1, ey1, dw1, iw1), (ox2, oy2, ex2, ey2, dw2, iw2)):
                f0 = (ex * (y - oy) + ey * ox) / denom
                f1 = -ey / denom
                n0 += f0 * dw
                n1 += f1 * dw
                m0 += f0 * iw
                m1 += f1 * iw
            _draw_span(r, t, col_lo, col_hi, n0, n1, m0, m1, res, depth, ident, far, block, margin[t], dirty)
    _refresh(dirty, depth, far, res, block)


def draw(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident, far, scale) -> None:
    """:func:`.occlusion.draw_visible`'s signature on ``draw_rows`` (no chunks: no temporaries)."""
    from .occlusion import BLOCK, MARGIN

    c = np.ascontiguousarray
    draw_rows(idx, x0, x1, y0, height, c(sx), c(ty), c(row_coord), c(dep), c(inv_w), area2, res, depth, ident, far, BLOCK, MARGIN * scale)


def merge(sp, res: int, chunk: int, depth, ident, far, scale) -> None:
    """:func:`.occlusion.merge_visible`'s signature on ``merge_spans``: the compiled merge of given spans."""
    from .occlusion import BLOCK, MARGIN

    merge_spans(sp.row, sp.t_id, sp.col_lo, sp.width, sp.n0, sp.n1, sp.m0, sp.m1, res, depth, ident, far, BLOCK, MARGIN * scale)


@_jit
def eye_outputs(tri_id, src, X, Y, nrm, lam_num, ident, position, normal):  # pragma: no cover - compiled
    """Per pixel: source triangle id, exact position and eye-facing normal (one pass, in place).

    ``tri_id`` (R·R) is the clipped triangle per pixel (−1 empty), ``src`` its source index;
    ``nrm`` (T, 3) unit normals and ``lam_num`` (T,) n·a per source triangle.  As in
    :func:`.eye.eye_pass`: den = n_x X + n_y Y + n_z (in that order), λ = n·a / den,
    position = λ(X, Y, 1), normal = −n where den > 0; NaN where empty.
    """
    res = X.size
    nan = np.nan
    for j in range(res):
        y = Y[j]
        for i in range(res):
            p = j * res + i
            k = tri_id[p]
            if k < 0:
                ident[p] = -1
                for a in range(3):
                    position[p, a] = nan
                    normal[p, a] = nan
                continue
            t = src[k]
            ident[p] = t
            nx, ny, nz = nrm[t, 0], nrm[t, 1], nrm[t, 2]
            x = X[i]
            den = nx * x
            den += ny * y
            den += nz
            lam = lam_num[t] / den
            position[p, 0] = x * lam
            position[p, 1] = y * lam
            position[p, 2] = lam
            if den > 0:
                normal[p, 0], normal[p, 1], normal[p, 2] = -nx, -ny, -nz
            else:
                normal[p, 0], normal[p, 1], normal[p, 2] = nx, ny, nz
