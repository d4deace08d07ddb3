"""Optional compiled kernels of the eye pass (numba, the ``fast`` extra): the same buffers, bit for bit.

numpy cannot bring the eye pass within 1.5× a depth map (issue 12 item 5; figures in
benchmarks/README.md): its z-buffer expands every covered span into (texel, triangle)
arrays and merges them with ``np.minimum.at``, and the outputs take several passes over
232 MB.  Two loops compiled with numba replace those stages; the rest (near clipping,
projection, spans, triangle culling) stays the numpy code:

* :func:`merge_spans` — the z-test of every texel of the spans, in place (minimum depth,
  ties to the highest triangle index, NaN sticks as with ``np.minimum``), then the culling
  blocks it lowered are refreshed (:mod:`.occlusion`);
* :func:`eye_outputs` — triangle id, position and normal of every pixel in one pass.

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

from typing import Callable

import numpy as np

try:  # optional: pip install 'aliasing[fast]'
    import numba
except ImportError:  # pragma: no cover - depends on the environment
    numba = None

#: The numba extra's install hint, for error messages.
INSTALL = "pip install 'aliasing[fast]'"


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
def merge_spans(row, t_id, col_lo, width, n0, n1, m0, m1, res, depth, ident, far, block, margin):  # pragma: no cover - compiled
    """Merge spans into the z-buffer texel by texel; refresh ``far`` (R × blocks) where depths dropped.

    The depth of a texel is (n0 + n1·px)/(m0 + m1·px), px = column + ½, as
    :meth:`.coverage.Spans.depth_at`.  A nearer depth takes the texel; an equal one keeps the
    higher triangle index; a NaN depth is stored (as ``np.minimum`` would) and then nothing
    changes that texel: the merge of :func:`.occlusion.merge_visible`, in any order.  As
    there, a piece of a span within one block of ``block`` columns is skipped when its
    nearest end, less ``margin`` (per triangle), lies beyond the block's ``far``.
    """
    nblk = far.shape[1]
    dirty = np.zeros(far.shape[0] * nblk, np.bool_)
    for s in range(row.size):
        base = row[s] * res
        t = t_id[s]
        a0, a1, b0, b1 = n0[s], n1[s], m0[s], m1[s]
        c0, c1 = col_lo[s], col_lo[s] + width[s] - 1
        fr = far[row[s]]
        for b in range(c0 // block, c1 // block + 1):
            lo, hi = max(c0, b * block), min(c1, b * block + block - 1)
            # the piece test of merge_visible (far may be stale: only ever too far, so safe)
            za = (a0 + a1 * (lo + 0.5)) / (b0 + b1 * (lo + 0.5))
            zb = (a0 + a1 * (hi + 0.5)) / (b0 + b1 * (hi + 0.5))
            zn = za if za < zb or za != za else zb  # np.minimum: NaN wins, and NaN never skips
            if zn - margin[t] > fr[b]:
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
                dirty[row[s] * nblk + b] = True
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


def merge(sp, res: int, chunk: int, depth, ident, far, scale) -> None:
    """:func:`.occlusion.merge_visible`'s signature on :func:`merge_spans` (no chunks or margins needed)."""
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
