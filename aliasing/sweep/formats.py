"""CSV text of whole columns at once: ``'%.10g'`` of float64 arrays, vectorized and exact.

The per-direction CSV of a large sweep is mostly numbers (about 25 per row with the per-map
lists), and CPython formats one float at a time (~0.25 µs each), several times the cost
of evaluating the schemes.  :func:`g10` gives the same bytes as ``'%.10g' % x`` for every
float64, built with integer arithmetic on whole arrays:

1. The decimal exponent e of |x| from ``log10``, corrected so that m = |x|·10^(9−e) lies
   in [10⁹, 10¹⁰) (10^k from a table of correctly rounded powers).
2. q = round(m), the 10 significant digits.  m carries at most ~2.3e-6 of rounding error
   (two roundings of a number below 10¹⁰), so it rounds like the exact |x|·10^(9−e) unless
   its fraction lies within :data:`AMBIGUOUS` of ½: those few values (about 2 in 10⁵),
   and the values outside [1e-290, 1e290], are formatted by Python itself.
3. The digits, trailing zeros stripped, in fixed notation for −4 ≤ e < 10 and otherwise in
   exponent notation (``d.ddde±XX``), as C's ``%g`` does; ``0``, ``-0``, ``inf``, ``-inf``,
   ``nan`` as Python writes them.

Every value fills a slot of three little-endian 64-bit words (:data:`SLOT` bytes): the
separator before it, its sign and "0.000" lead, the digits with the point among them and the
exponent, NUL bytes between the parts.  :func:`lines` puts a chunk's slots side by side in
one table of words and drops the NUL bytes in one pass, so a chunk of rows becomes text
without a Python step per number.

Example
-------
>>> import numpy as np
>>> g10(np.array([0.1, -2.5e-7, 1e16, 12345678905.0, float("inf")])).tolist()
['0.1', '-2.5e-07', '1e+16', '1.23456789e+10', 'inf']
>>> print(csv_lines("P,1000", [np.array([1.5, 2.0]), np.array([[0.25, 1e-5], [3.0, 4.0]]), np.array([1, 2])]), end="")
P,1000,1.5,0.25;1e-05,1
P,1000,2,3;4,2
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

__all__ = ["AMBIGUOUS", "BLOCK", "EXPONENTS", "SLOT", "cells", "csv_lines", "g10", "lines"]

#: How close to ½ the fraction of the scaled value may come before Python formats the number (see the module docstring).
AMBIGUOUS = 1e-5
#: Exponents (of 10) formatted here; the rest (subnormals, |x| > 1e290) go to Python.
EXPONENTS = 290
#: Values formatted per vectorized step (their ~40 temporaries stay in the CPU cache).
BLOCK = 16_384
#: Bytes of one value's slot: separator, sign and "0.000" lead (6), 10 digits and a point (11), "e±DDD" (5), a NUL.
SLOT = 24

_OFF = EXPONENTS + 12
_POW10 = np.array([float(f"1e{k}") for k in range(-_OFF, _OFF + 1)])  # correctly rounded 10**k, k = index − _OFF
_S8, _S56 = np.uint64(8), np.uint64(56)


def _words(texts: Sequence[bytes], shift: int = 0) -> NDArray[np.uint64]:
    """Each byte string (shifted up by ``shift`` bytes, cut to 8) as a little-endian word."""
    return np.array([int.from_bytes((b"\0" * shift + t).ljust(8, b"\0")[:8], "little") for t in texts], dtype="<u8")


def _layout(cls: int, nd: int) -> tuple[int, int]:
    """Digits shown and the digit the point follows (10: none) for exponent class ``cls`` and ``nd`` significant digits.

    Classes: 0 exponent notation, 1–4 fixed notation below 1 (e = −4 … −1: the point is in
    the lead "0.000"), 5–14 fixed notation with e = 0 … 9 (an integer part of e + 1 digits).
    """
    if cls == 0:
        return nd, 0 if nd > 1 else 10
    if cls < 5:
        return nd, 10
    e = cls - 5
    shown = max(nd, e + 1)  # an integer part keeps its zeros
    return shown, e if shown > e + 1 else 10


def _masks() -> dict[str, NDArray[np.uint64]]:
    """Row 11·class + nd: masks of the 10 digits (bytes 0–9 of two words, lo and hi).

    ``keep``: the digits staying in place; ``move``: the places of the digits moved up one
    byte (those after the point); ``point``: the point.  nd = 0 (zeros, infinities, NaN,
    whose text is all in the lead): nothing.
    """
    keep, move, point = [], [], []
    for cls in range(15):
        for nd in range(11):
            shown, p = _layout(cls, nd) if nd else (0, 10)
            keep.append(bytes(0xFF if j < shown and j <= p else 0 for j in range(16)))
            move.append(bytes(0xFF if p < 10 and p + 2 <= j <= shown else 0 for j in range(16)))
            point.append(b"\0" * (p + 1) + b"." if p < 10 else b"")
    out = {}
    for name, rows in (("keep", keep), ("move", move), ("point", point)):
        out[name + "_lo"] = _words([r[:8] for r in rows])
        out[name + "_hi"] = _words([r[8:16] for r in rows])
    return out


_FOUR = [f"{i:04d}".encode() for i in range(10_000)]
_A = _words([f"{i:02d}".encode() for i in range(100)])  # q = a·10⁸ + b·10⁴ + c: a's two digits in bytes 0–1 of lo,
_B = _words(_FOUR, 2)  # b's four in bytes 2–5,
_C_LO = _words([t[:2] for t in _FOUR], 6)  # c's first two in bytes 6–7,
_C_HI = _words([t[2:] for t in _FOUR])  # and its last two in bytes 0–1 of hi
_TRAILING = np.array([len(t) - len(t.rstrip(b"0")) for t in _FOUR], np.int8)
_MASK = _masks()
_CLASS = np.array([0] + [1, 2, 3, 4] + list(range(5, 15)) + [0], np.int64)  # class of clip(e, −5, 10) + 5
# the lead (≤ 6 bytes) in bytes 1–6 of a slot's first word, after the separator
_LEAD = _words([sign + (b"0." + b"0" * (4 - c) if 1 <= c <= 4 else b"") for sign in (b"", b"-") for c in range(15)]
               + [b"", b"0", b"-0", b"inf", b"-inf", b"nan"], 1)  # row 15·negative + class; row 30 + kind: what Python writes for these
_EXPONENT = _words([b"" if -4 <= k < 10 else f"e{k:+03d}".encode() for k in range(-_OFF, _OFF + 1)], 2)  # row k + _OFF, bytes 2–6 of the third word


def _slots(x: NDArray[np.float64]) -> NDArray[np.uint64]:
    """Each value's ``'%.10g'`` text in a slot of three words (N, 3), byte 0 (the separator) left NUL."""
    x = np.ascontiguousarray(x, dtype=np.float64).ravel()
    n = x.size
    ax = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # 0, inf, NaN and the extremes are not "fast": handled below
        lg = np.log10(ax)
        fast = np.abs(lg) <= EXPONENTS
        e = np.floor(np.where(fast, lg, 0.0)).astype(np.int64)
        m = ax * _POW10[_OFF + 9 - e]  # |x|·10^(9−e), two roundings: error < 2.3e-6
        off = np.flatnonzero(fast & ((m >= 1e10) | (m < 1e9)))  # log10 one off next to a power of 10: one correction suffices
        if off.size:
            e[off] += np.where(m[off] >= 1e10, 1, -1)
            m[off] = ax[off] * _POW10[_OFF + 9 - e[off]]
        r = np.rint(m)
        fast &= np.abs(m - r) <= 0.5 - AMBIGUOUS
    q = np.where(fast, r, 1e9).astype(np.int64)
    up = np.flatnonzero(q == 10_000_000_000)  # rounded up to the next power of 10
    q[up] = 1_000_000_000
    e[up] += 1
    a, rest = np.divmod(q, 100_000_000)
    b, c = np.divmod(rest, 10_000)
    lo = _A.take(a)  # the 10 ASCII digits: bytes 0–7 in lo, 8–9 in hi
    lo |= _B.take(b)
    lo |= _C_LO.take(c)
    hi = _C_HI.take(c)
    nd = np.where(c != 0, 10 - _TRAILING.take(c), np.where(b != 0, 6 - _TRAILING.take(b), 2 - _TRAILING.take(a)))
    cls = _CLASS.take(np.clip(e, -5, 10) + 5)
    mask = 11 * cls + nd
    lead = 15 * (x < 0) + cls
    special = np.flatnonzero(~fast)
    if special.size:  # 0, -0, ±inf, NaN: their text in the lead row, no digits; kind 0 (extremes, ambiguous rounding): Python's, below
        v = x[special]
        kind = np.select([v == 0, np.isinf(v), np.isnan(v)], [1, 3, 5], 0)
        kind += (kind > 0) & (kind < 5) & np.signbit(v)  # "-0", "-inf" (Python writes "nan" whatever its sign)
        lead[special] = 30 + kind
        mask[special] = 0
        e[special] = 0
    # digits after the point move up a byte (a shift of the two words by 8 bits), the point goes in between
    moved_hi = (hi << _S8) | (lo >> _S56)
    moved_hi &= _MASK["move_hi"].take(mask)
    hi &= _MASK["keep_hi"].take(mask)
    hi |= moved_hi
    hi |= _MASK["point_hi"].take(mask)
    moved_lo = lo << _S8
    moved_lo &= _MASK["move_lo"].take(mask)
    lo &= _MASK["keep_lo"].take(mask)
    lo |= moved_lo
    lo |= _MASK["point_lo"].take(mask)
    # the slot: [separator, lead (6), digits 0] [digits 1–8] [digits 9–10, exponent (5), NUL]
    out = np.empty((n, 3), "<u8")
    np.bitwise_or(_LEAD.take(lead), lo << _S56, out=out[:, 0])
    np.bitwise_or(lo >> _S8, hi << _S56, out=out[:, 1])
    np.bitwise_or(hi >> _S8, _EXPONENT.take(e + _OFF), out=out[:, 2])
    if special.size:
        for i, text in zip(special[kind == 0].tolist(), map("%.10g".__mod__, v[kind == 0].tolist())):
            out[i] = np.frombuffer(b"\0" + text.encode().ljust(SLOT - 1, b"\0"), "<u8")
    return out


def g10(x: NDArray[np.float64]) -> NDArray[np.str_]:
    """``'%.10g' % v`` for every element of ``x``, as an array of str (vectorized, exact).

    Parameters
    ----------
    x : ndarray of float64

    Returns
    -------
    ndarray of str, the shape of ``x``

    Example
    -------
    >>> g10(np.array([[1.0, 1e-4], [123456.78901234, -0.0]])).tolist()
    [['1', '0.0001'], ['123456.789', '-0']]
    """
    a = np.asarray(x)
    if a.dtype.kind not in "iuf":
        raise ValueError(f"x must be an array of real numbers, got dtype {a.dtype}")
    a = a.astype(np.float64)
    words = _slots(a)
    words[:, 0] |= np.uint64(ord("\n"))  # one value per line
    text = _text(words)
    return np.array(text.split("\n")[1:] if text else [], dtype=str).reshape(a.shape)


def _text(table: NDArray[np.uint64]) -> str:
    """The bytes of a table of words without their NUL bytes, as text."""
    flat = np.ascontiguousarray(table, dtype="<u8").view(np.uint8).ravel()
    return str(memoryview(np.compress(flat != 0, flat)), "ascii")  # a 1-D compress: ~5x faster than 2-D boolean indexing


def _columns(columns: Sequence[np.ndarray]) -> tuple[NDArray[np.float64], list[int]]:
    """The columns side by side as one (N, K) float array, checked, and each column's values per row."""
    cols = [np.asarray(c) for c in columns]
    n = len(cols[0]) if cols else 0
    for a in cols:
        if a.shape[:1] != (n,) or a.dtype.kind not in "iuf":
            raise ValueError(f"columns must be numbers of the same length, got {a.dtype} {a.shape[:1]} and {n}")
        if a.dtype.kind in "iu" and a.size and np.abs(a).max() >= 10**10:
            raise ValueError("integer columns must be below 10**10 in magnitude (where str and '%.10g' agree)")
    widths = [int(np.prod(a.shape[1:])) for a in cols]
    if not cols:
        return np.empty((0, 0)), widths
    return np.concatenate([a.reshape(n, w).astype(np.float64) for a, w in zip(cols, widths)], axis=1), widths


def _count(columns: Sequence[np.ndarray]) -> int:
    """Values per row of the columns: each (N,) column gives 1, each (N, k) column k."""
    return sum(int(np.prod(np.shape(c)[1:])) for c in columns)


def _fill(columns: Sequence[np.ndarray], out: NDArray[np.uint64]) -> None:
    """Write the slots of ``columns`` into ``out`` (N, K, 3): each value after its separator (``,`` or ``;``)."""
    values, widths = _columns(columns)
    n, k = values.shape
    seps = np.array([s for w in widths for s in [ord(",")] + [ord(";")] * (w - 1) if w], "<u8")
    step = max(1, BLOCK // max(k, 1))
    for start in range(0, n, step):  # blocks whose temporaries stay in cache: ~3x faster than one pass over the chunk
        slots = _slots(values[start : start + step]).reshape(-1, k, 3)
        slots[:, :, 0] |= seps
        out[start : start + step] = slots


def cells(columns: Sequence[np.ndarray]) -> NDArray[np.uint64]:
    """The CSV cells of N rows as slots of words, shape (N, K, 3): a separator, then the value's text, NUL-padded.

    Each column is (N,) or (N, k): floats are written as ``'%.10g' % v``, integers (of fewer
    than 11 digits) as ``str(v)``, which is the same text.  A column's first value follows
    ``,``, the others ``;``.  For cells shared by several :func:`lines` calls.
    """
    out = np.empty((len(columns[0]) if columns else 0, _count(columns), 3), "<u8")
    _fill(columns, out)
    return out


def lines(head: str, blocks: Sequence[NDArray[np.uint64] | Sequence[np.ndarray]]) -> str:
    """CSV lines: ``head``, then the blocks side by side, NUL padding dropped.

    Parameters
    ----------
    head : str
        The cells shared by every row, already CSV-quoted, without a trailing comma (may be
        empty: then each line starts with the first block's first value).
    blocks : sequence
        Each either cells made by :func:`cells` (N, K, 3), or a list of columns, formatted in
        place (see :func:`cells`).

    Returns
    -------
    str
        N lines, each ending in ``\\n``.
    """
    prefix = head.encode()
    if b"\0" in prefix:
        raise ValueError("head must not contain NUL characters")
    ready = [isinstance(b, np.ndarray) and b.dtype == np.dtype("<u8") and b.ndim == 3 and b.shape[2] == 3 for b in blocks]
    counts = [b.shape[1] if r else _count(b) for b, r in zip(blocks, ready)]
    rows = {b.shape[0] if r else len(b[0]) for b, r in zip(blocks, ready) if r or len(b)}
    if len(rows) > 1:
        raise ValueError(f"blocks must have the same number of rows, got {sorted(rows)}")
    n = rows.pop() if rows else 0
    head_words = np.frombuffer(prefix.ljust(-(-len(prefix) // 8) * 8, b"\0"), "<u8")
    table = np.empty((n, head_words.size + 3 * sum(counts) + 1), "<u8")  # head, slots, the line end
    table[:, : head_words.size] = head_words
    at = head_words.size
    for block, is_ready, k in zip(blocks, ready, counts):
        view = table[:, at : at + 3 * k].reshape(n, k, 3)
        if is_ready:
            view[...] = block
        else:
            _fill(block, view)
        at += 3 * k
    if not prefix and at > 0:
        table[:, 0] &= ~np.uint64(0xFF)  # no separator before the first value
    table[:, -1] = ord("\n")
    return _text(table)


def csv_lines(head: str, columns: Sequence[np.ndarray]) -> str:
    """CSV lines ``head,c1,c2,…`` of N rows (the columns of :func:`cells` through :func:`lines`).

    Example
    -------
    >>> print(csv_lines("", [np.array([0.5, -0.0]), np.array([[1, 2], [3, 40]])]), end="")
    0.5,1;2
    -0,3;40
    """
    return lines(head, [columns])
