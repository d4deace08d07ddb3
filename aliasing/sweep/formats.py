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

Every value is laid out in a fixed-width row of bytes with NUL padding between its parts;
:func:`csv_lines` puts the columns of a chunk side by side and drops the padding in one
pass, so a chunk of rows becomes text without a Python step per number.

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

#: How close to ½ the fraction of the scaled value may come before Python formats the number (see the module docstring).
AMBIGUOUS = 1e-5
#: Exponents (of 10) formatted here; the rest (subnormals, |x| > 1e290) go to Python.
EXPONENTS = 290
#: Values formatted per vectorized step (their ~40 temporaries stay in the CPU cache).
BLOCK = 16_384
#: Bytes of one value's padded row: sign and "0.000" prefix, 10 digits with a point among them, "e±DDD".
WIDTH = 6 + 11 + 5

_OFF = EXPONENTS + 12
_POW10 = np.array([float(f"1e{k}") for k in range(-_OFF, _OFF + 1)])  # correctly rounded 10**k, k = index − _OFF
_MINUS = ord("-")


def _table(rows: Sequence[bytes], width: int) -> NDArray[np.void]:
    """Byte strings as one row each of a table of ``width``-byte records, NUL-padded (a gather takes whole rows)."""
    return np.array([r.ljust(width, b"\0") for r in rows], dtype=f"S{width}").view(f"V{width}")


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


def _masks() -> NDArray[np.void]:
    """Row 11·class + nd: three pairs of little-endian words masking the 10 digits (two words).

    The digits kept in place, the digits moved up one byte (those after the point), the point.
    """
    def words(b: bytes) -> list[int]:
        b = b.ljust(16, b"\0")
        return [int.from_bytes(b[:8], "little"), int.from_bytes(b[8:16], "little")]

    rows = []
    for cls in range(15):
        for nd in range(11):
            shown, p = _layout(cls, max(nd, 1))
            keep = bytes(0xFF if j < shown and j <= p else 0 for j in range(16))
            move = bytes(0xFF if p < 10 and p + 2 <= j <= shown else 0 for j in range(16))
            point = b"\0" * (p + 1) + b"." if p < 10 else b""
            rows.append(words(keep) + words(move) + words(point))
    return np.array(rows, dtype="<u8").view("V48").ravel()


_DIGITS4 = _table([f"{i:04d}".encode() for i in range(10_000)], 4)  # four ASCII digits
_TRAILING = np.array([len(s) - len(s.rstrip("0")) for s in (f"{i:04d}" for i in range(10_000))], np.int8)
_MASKS = _masks()
_CLASS = np.array([0] + [1, 2, 3, 4] + list(range(5, 15)) + [0], np.int64)  # class of clip(e, −5, 10) + 5
_LEAD = _table([sign + (b"0." + b"0" * (4 - c) if 1 <= c <= 4 else b"") for sign in (b"", b"-") for c in range(15)], 6)  # row 15·negative + class
_EXPONENT = _table([b"" if -4 <= k < 10 else f"e{k:+03d}".encode() for k in range(-_OFF, _OFF + 1)], 5)  # row k + _OFF
_SPECIAL = _table([b"", b"0", b"-0", b"inf", b"-inf", b"nan"], WIDTH)  # what Python writes for these


def _rows(x: NDArray[np.float64], out: NDArray[np.uint8]) -> None:
    """Write each value's ``'%.10g'`` text into ``out`` (``x.shape + (WIDTH,)``, any strides), NUL-padded between its parts."""
    x = np.ascontiguousarray(x, dtype=np.float64).ravel()
    n = x.size
    ax = np.abs(x)
    fast = (ax >= 10.0**-EXPONENTS) & (ax <= 10.0**EXPONENTS)  # also excludes 0, inf, NaN
    ax[~fast] = 1.0  # those are formatted below
    e = np.floor(np.log10(ax)).astype(np.int64)
    m = ax * _POW10[_OFF + 9 - e]  # |x|·10^(9−e), two roundings: error < 2.3e-6
    off = np.flatnonzero(fast & ((m >= 1e10) | (m < 1e9)))  # log10 one off next to a power of 10
    if off.size:
        e[off] += np.where(m[off] >= 1e10, 1, -1)
        m[off] = ax[off] * _POW10[_OFF + 9 - e[off]]
    r = np.rint(m)
    fast &= (r >= 1e9) & (r <= 1e10) & (np.abs(m - r) <= 0.5 - AMBIGUOUS)
    q = np.where(fast, r, 1e9).astype(np.int64)
    up = np.flatnonzero(q == 10_000_000_000)  # rounded up to the next power of 10
    q[up] = 1_000_000_000
    e[up] += 1
    a, rest = np.divmod(q, 100_000_000)
    b, c = np.divmod(rest, 10_000)
    d = np.zeros((n, 4), "V4")  # the 10 digits "ab" "bbbb" "cccc" from byte 2 on, as little-endian words from byte 0
    d[:, 0], d[:, 1], d[:, 2] = _DIGITS4.take(a), _DIGITS4.take(b), _DIGITS4.take(c)
    d = d.view(np.uint8)
    d[:, :14] = d[:, 2:].copy()
    d = d.view("<u8")
    nd = np.where(c != 0, 10 - _TRAILING.take(c), np.where(b != 0, 6 - _TRAILING.take(b), 2 - _TRAILING.take(a)))
    cls = _CLASS.take(np.clip(e, -5, 10) + 5)
    masks = _MASKS.take(11 * cls + nd).view("<u8").reshape(n, 6)
    moved = d << np.uint64(8)  # the digits after the point move up a byte, the point goes in between
    moved[:, 1] |= d[:, 0] >> np.uint64(56)
    moved &= masks[:, 2:4]
    d &= masks[:, :2]
    d |= moved
    d |= masks[:, 4:]
    shape = out.shape[:-1]
    out[..., :6] = _LEAD.take(15 * (x < 0) + cls).view(np.uint8).reshape(shape + (6,))
    out[..., 6:17] = d.view(np.uint8)[:, :11].reshape(shape + (11,))
    out[..., 17:] = _EXPONENT.take(e + _OFF).view(np.uint8).reshape(shape + (5,))
    special = np.flatnonzero(~fast)
    if special.size:  # 0, -0, ±inf, NaN from a table; extreme exponents and the rare ambiguous rounding: Python's own text
        v = x[special]
        kind = np.select([v == 0, np.isinf(v), np.isnan(v)], [1, 3, 5], 0)
        kind += (kind > 0) & (kind < 5) & np.signbit(v)  # "-0", "-inf" (Python writes "nan" whatever its sign)
        at = np.unravel_index(special, shape)
        out[at] = _SPECIAL.take(kind).view(np.uint8).reshape(-1, WIDTH)
        for i, text in zip(special[kind == 0].tolist(), map("%.10g".__mod__, v[kind == 0].tolist())):
            row = out[np.unravel_index(i, shape)]
            row[:] = 0
            row[: len(text)] = np.frombuffer(text.encode(), np.uint8)


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
    a = np.asarray(x, dtype=np.float64)
    rows = np.zeros((a.size, WIDTH + 1), np.uint8)
    _rows(a, rows[:, :WIDTH])
    rows[:, WIDTH] = ord("\n")
    flat = rows.ravel()
    return np.array(np.compress(flat != 0, flat).tobytes().decode("ascii").split("\n")[:-1], dtype=str).reshape(a.shape)


def csv_lines(head: str, columns: Sequence[np.ndarray]) -> str:
    """CSV lines ``head,c1,c2,…`` of N rows: float columns as ``'%.10g'``, (N, k) columns as k values joined with ``;``.

    Parameters
    ----------
    head : str
        The cells shared by every row, already CSV-quoted, without a trailing comma (may be empty).
    columns : sequence of ndarray
        Each (N,) or (N, k): floats are written as ``'%.10g' % v``, integers (of fewer than
        11 digits) as ``str(v)`` — which is the same text.

    Returns
    -------
    str
        N lines, each ending in ``\\n``.
    """
    prefix = head.encode()
    if b"\0" in prefix:
        raise ValueError("head must not contain NUL characters")
    cols = [np.asarray(c) for c in columns]
    n = len(cols[0]) if cols else 0
    for a in cols:
        if a.shape[:1] != (n,) or a.dtype.kind not in "iuf":
            raise ValueError(f"columns must be numbers of the same length, got {a.dtype} {a.shape[:1]} and {n}")
        if a.dtype.kind in "iu" and a.size and np.abs(a).max() >= 10**10:
            raise ValueError("integer columns must be below 10**10 in magnitude (where str and '%.10g' agree)")
    values = np.concatenate([a.reshape(n, -1).astype(np.float64) for a in cols], axis=1) if cols else np.empty((0, 0))
    k = values.shape[1]
    sep = np.concatenate([[ord(",") if c or prefix else 0] + [ord(";")] * (a.reshape(n, -1).shape[1] - 1) for c, a in enumerate(cols)]).astype(np.uint8)
    table = np.empty((n, len(prefix) + k * (1 + WIDTH) + 1), np.uint8)
    table[:, : len(prefix)] = np.frombuffer(prefix, np.uint8)
    cells = table[:, len(prefix) : -1].reshape(n, k, 1 + WIDTH)
    cells[:, :, 0] = sep
    step = max(1, BLOCK // max(k, 1))
    for start in range(0, n, step):  # blocks whose temporaries stay in cache: ~3x faster than one pass over the chunk
        _rows(values[start : start + step], cells[start : start + step, :, 1:])
    table[:, -1] = ord("\n")
    flat = table.ravel()
    return np.compress(flat != 0, flat).tobytes().decode("ascii")  # 1-D compress: ~5x faster than 2-D boolean indexing
