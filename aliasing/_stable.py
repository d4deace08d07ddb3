"""Products that neither underflow nor overflow, bit-identical to the plain formulas elsewhere.

The warping rules take square roots and ratios of products of the frustum's distances
(√(f·n), D·n/(f − n)).  For frusta near 1e-300 or 1e300 those products leave the float64
range although the results are representable; rescaled forms (√f·√n, D·(n/(f − n))) avoid
that but round differently in the last bit.  Each helper here takes the plain form wherever
its product is a normal float, so every result in the normal range stays exactly what it
was, and the rescaled form only where the plain one under- or overflows.

Example
-------
>>> float(sqrt_product(4.0, 9.0)), float(sqrt_product(1e-300, 1e-300))
(6.0, 1e-300)
>>> float(product_ratio(1e-300, 1e-200, 1e-200))
1e-300
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

_TINY = np.finfo(np.float64).tiny


def _plain(p: NDArray[np.float64], a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Where the product p = a·b is trustworthy: a normal float, or an exact zero (a factor is 0)."""
    return (np.isfinite(p) & (np.abs(p) >= _TINY)) | (a == 0) | (b == 0)


def sqrt_product(a: ArrayLike, b: ArrayLike) -> NDArray[np.float64]:
    """√(a·b) for a, b ≥ 0: ``np.sqrt(a * b)`` where a·b is a normal float, else √a·√b."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    with np.errstate(over="ignore", under="ignore"):
        p = a * b
    return np.where(_plain(p, a, b), np.sqrt(p), np.sqrt(a) * np.sqrt(b))


def product_ratio(a: ArrayLike, b: ArrayLike, c: ArrayLike) -> NDArray[np.float64]:
    """a·b/c: ``a * b / c`` where a·b is a normal float, else a·(b/c)."""
    a, b, c = (np.asarray(v, dtype=float) for v in (a, b, c))
    with np.errstate(over="ignore", under="ignore"):
        p = a * b
        return np.where(_plain(p, a, b), p / c, a * (b / c))
