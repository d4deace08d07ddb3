"""aliasing._stable: products without under- or overflow, bit-identical to the plain formulas in the normal range.

Issue 12 requires every number to stay what it was; the warping rules' fix for extreme frusta
(issue 19's fuzz residue) must therefore change nothing where the plain product was a normal
float.  Generated inputs check both halves of that promise.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from aliasing._stable import product_ratio, sqrt_product

positive = st.floats(min_value=5e-324, max_value=1.7e308, allow_nan=False, allow_infinity=False)


@given(positive, positive)
def test_sqrt_product_is_the_plain_form_where_the_product_is_normal(a, b):
    p = a * b
    got = float(sqrt_product(a, b))
    if math.isfinite(p) and p >= 2.2250738585072014e-308:
        assert got == float(np.sqrt(p))  # exactly
    else:  # the plain form under- or overflowed: √a·√b, within two roundings of the true value
        assert math.isfinite(got) and got > 0
        assert got == float(np.sqrt(a) * np.sqrt(b))


@given(positive, positive, positive)
def test_product_ratio_is_the_plain_form_where_the_product_is_normal(a, b, c):
    p = a * b
    with np.errstate(over="ignore", under="ignore"):
        got = float(product_ratio(a, b, c))
        if math.isfinite(p) and p >= 2.2250738585072014e-308:
            assert got == float(np.float64(p) / c)  # exactly
        else:
            assert got == float(np.float64(a) * (np.float64(b) / c))


def test_zero_factors_and_arrays():
    assert float(sqrt_product(0.0, 5.0)) == 0.0 and float(product_ratio(0.0, 1e-300, 1e-300)) == 0.0
    got = sqrt_product(np.array([1e-200, 4.0]), np.array([1e-200, 9.0]))
    assert got.shape == (2,) and got[0] == 1e-200 and got[1] == 6.0
