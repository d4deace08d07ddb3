"""Plain-text tables for the command line: one cell format and one right-aligned layout.

Every command that prints a table (``check``, ``tune``, ``shimmer``, ``bias``, ``engines``,
``render``, ``validate``) formats its cells and aligns its columns here, so that a number reads
the same in all of them.

Example
-------
>>> print(table([{"cascade": 0, "texel": 0.0581234, "acne": None}, {"cascade": 1, "texel": 0.119, "acne": 0.5}]), end="")
cascade    texel  acne
      0  0.05812     -
      1    0.119   0.5
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Iterable, Mapping, Sequence

#: A result without a finite bound (an overflow, a bias that cannot help), in words in place of ``inf``.
UNBOUNDED = "unbounded"


def cell(value: object, digits: int = 4) -> str:
    """One value as a table cell: ``-`` for None, a float to ``digits`` significant digits, anything else as ``str``.

    Parameters
    ----------
    value : object
        The value; None stands for "not applicable".
    digits : int
        Significant digits of a float, 1 to 17.

    Example
    -------
    >>> cell(None), cell(2.0 / 3.0), cell(2.0 / 3.0, digits=6), cell("sphere"), cell(3)
    ('-', '0.6667', '0.666667', 'sphere', '3')
    """
    if not isinstance(digits, int) or isinstance(digits, bool) or not 1 <= digits <= 17:
        raise ValueError(f"digits must be an integer from 1 to 17, got {digits!r}")
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def aligned(rows: Sequence[Sequence[str]]) -> str:
    """Rows of cells (the header first) as lines with right-aligned columns two spaces apart.

    Example
    -------
    >>> print(aligned([["a", "bb"], ["100", "2"]]), end="")
      a  bb
    100   2
    """
    if not rows or any(len(r) != len(rows[0]) for r in rows):
        raise ValueError("rows must be a non-empty list of rows of equal length")
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return "".join("  ".join(c.rjust(w) for c, w in zip(r, widths)) + "\n" for r in rows)


def table(rows: Sequence[Mapping[str, object]], keys: Iterable[str] | None = None, digits: int = 4) -> str:
    """Dict rows as an aligned table: the header is ``keys`` (default: the first row's keys), a missing key a ``-``.

    Example
    -------
    >>> print(table([{"x": 1.23456789, "y": None}], digits=3), end="")
       x  y
    1.23  -
    """
    if not rows:
        raise ValueError("rows must hold at least one row")
    keys = list(rows[0]) if keys is None else list(keys)
    return aligned([keys] + [[cell(r.get(k), digits) for k in keys] for r in rows])


def csv_text(rows: Sequence[Mapping[str, object]], keys: Iterable[str] | None = None) -> str:
    """Dict rows as CSV text: the header is ``keys`` (default: the first row's keys); None and a missing key are empty cells.

    Example
    -------
    >>> print(csv_text([{"x": 0.5, "y": None}, {"x": 2}]), end="")
    x,y
    0.5,
    2,
    """
    if not rows:
        raise ValueError("rows must hold at least one row")
    keys = list(rows[0]) if keys is None else list(keys)
    buf = io.StringIO()
    wr = csv.DictWriter(buf, fieldnames=keys, lineterminator="\n")
    wr.writeheader()
    wr.writerows({k: "" if r.get(k) is None else r[k] for k in keys} for r in rows)
    return buf.getvalue()


def labelled(rows: Sequence[Mapping[str, object]], headers: Mapping[str, str]) -> list[dict]:
    """Rows with each key renamed to its header (``gap_px`` → ``gap [px]``; a key without one kept) and
    each non-finite float as :data:`UNBOUNDED` (NaN as None): for a table or CSV that names units and
    never prints ``inf``.

    Example
    -------
    >>> labelled([{"gap_px": float("inf"), "cascade": 0}], {"gap_px": "gap [px]"})
    [{'gap [px]': 'unbounded', 'cascade': 0}]
    """
    if not isinstance(headers, Mapping):
        raise ValueError(f"headers must be a mapping of keys to headers, got {type(headers).__name__}")

    def shown(v: object) -> object:
        if isinstance(v, float) and not math.isfinite(v):
            return None if math.isnan(v) else UNBOUNDED if v > 0 else "-" + UNBOUNDED
        return v

    return [{headers.get(k, k): shown(v) for k, v in r.items()} for r in rows]
