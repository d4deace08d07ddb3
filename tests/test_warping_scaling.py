"""Every warping rule is scale invariant: n′(s·n, s·f, depth = s·D) = s·n′(n, f, D), for near
across 1e-300..1e300 (fuzz residue: products such as f·n under- or overflowed, giving n′ = 0 or inf).

Profiles (tests/conftest.py): "ci" is derandomized; ALIASING_HYPOTHESIS=long runs many more examples.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

import aliasing  # noqa: E402,F401  (registers every rule)
from aliasing import warping  # noqa: E402

RULES = sorted(warping.WARPING_RULES)
TINY = 1e-290  # below this the expected n′ itself may be subnormal: only relative accuracy above it is asked for

# Rule options besides near and far; lengths (depth) are given relative to near and scaled with it.
OPTIONS = {
    "fov": st.floats(1.0, 170.0),
    "gamma": st.floats(0.0, 180.0),
    "azimuth": st.floats(-180.0, 180.0),
    "eta": st.floats(-1.0, 1.0),
    "focus": st.floats(0.01, 0.99),
    "line": st.floats(0.01, 0.99),
    "c_fraction": st.floats(0.1, 0.9),
    "depth": st.one_of(st.none(), st.floats(-3.0, 3.0).map(lambda x: 10.0**x)),  # relative to near
}


def _scale(x: float, k: int) -> float:
    """x·2^k, exact; inf where it exceeds a float (math.ldexp raises there)."""
    try:
        return math.ldexp(x, k)
    except OverflowError:
        return math.inf


def _case(rule: str):
    taken = sorted(warping._accepted(warping.WARPING_RULES[rule].func))
    return st.fixed_dictionaries({k: OPTIONS[k] for k in taken})


@pytest.mark.parametrize("rule", RULES)
def test_n_prime_scales_with_near_from_1e_300_to_1e300(rule):
    # near = m·2^k: scaling by 2^k is exact in floating point, so the unit-frame reference
    # (near = m ∈ [1, 2), far = m·f/n) has exactly the same f/n, and any difference is the
    # rule's own under- or overflow, not the conditioning of f − n as f/n → 1
    @settings(max_examples=max(150, settings.default.max_examples // 25))  # "long": 2,000 per rule
    @given(k=st.integers(-996, 996), m=st.floats(1.0, 2.0, exclude_max=True), log_gap=st.floats(-6.0, 12.0), options=_case(rule))
    def check(k, m, log_gap, options):
        far_unit = m * (1.0 + 10.0**log_gap)
        near, far = math.ldexp(m, k), _scale(far_unit, k)
        hypothesis.assume(math.isfinite(far))
        unit, scaled = dict(options), dict(options)
        if options.get("depth") is not None:
            unit["depth"] = m * options["depth"]
            scaled["depth"] = _scale(unit["depth"], k)
            hypothesis.assume(math.isfinite(scaled["depth"]) and scaled["depth"] > TINY)
        got = float(warping.warping_parameter(rule, near, far, **scaled))
        ref = float(warping.warping_parameter(rule, m, far_unit, **unit))
        if math.isinf(ref):  # no warping (uniform, light along the view, ...) or n′ beyond a float at scale m
            assert got == math.inf or (k < 0 and got >= _scale(sys.float_info.max, k) * (1 - 1e-12))
            return
        expected = _scale(ref, k)
        if math.isinf(expected):  # the answer exceeds a float: inf, or a finite n′ at the edge
            assert got >= 1e307
            return
        if expected > TINY:
            assert math.isfinite(got) and got > 0
            assert got == pytest.approx(expected, rel=1e-12, abs=0.0), (near, far, options)

    check()


@pytest.mark.parametrize(("rule", "options"), [
    ("lispsm", {}), ("lispsm-dz", {"depth": 1.7e-131}), ("psm", {"depth": 1e-140}), ("p", {"depth": 1e-140}),
    ("logp", {"depth": 1e-140}), ("eta", {"depth": 1e-140}), ("po", {"depth": 1e-140}), ("pyramid", {}),
    ("pyramid-log", {"gamma": 80.0}), ("gmnpr", {}), ("lispsm-zhang", {}), ("glpr", {}), ("tsm", {}),
])
def test_fuzz_residue_tiny_frustum_has_positive_n_prime(rule, options):
    # the fuzz suite's case near = 5.8e-264, far = 1.7e-131: f·n and D·n underflowed to 0
    near, far = 5.8e-264, 1.7e-131
    unit = {k: (v / near if k == "depth" else v) for k, v in options.items()}
    got = float(warping.warping_parameter(rule, near, far, **options))
    assert 0 < got < math.inf
    assert got == pytest.approx(near * float(warping.warping_parameter(rule, 1.0, far / near, **unit)), rel=1e-12, abs=0.0)


def test_lispsm_of_a_huge_frustum_is_finite():
    # n + √(fn) overflowed in f·n although n′ = n(1 + √(f/n)) is far inside float range
    assert float(warping.n_prime_lispsm(1e200, 1e250)) == pytest.approx(1e200 * (1 + 1e25), rel=1e-14, abs=0.0)
    np.testing.assert_allclose(warping.n_prime_lispsm(1.0, [100.0, 1e4]), [11.0, 101.0], rtol=1e-15)


@pytest.mark.parametrize("ratio", [1e3, 1e30, 1e132])
def test_error_branch_point_of_a_tiny_frustum(ratio):
    # aliasing.error's branch point n′_LiSPSM = n + √(fn) had the same underflow: S̄ and M_z are
    # dimensionless and n′ a length, so scaling near, far and n′ together must not change them
    near = 5.8e-264
    far = near * ratio
    for frac in (0.3, 0.9, 3.0):  # n′ between n and n′_LiSPSM, and beyond it
        npr_unit = 1 + frac * math.sqrt(far / near)
        for func in (aliasing.storage_factor, aliasing.max_error_z):
            got = float(func(near, far, 60.0, near * npr_unit))
            assert got == pytest.approx(float(func(1.0, far / near, 60.0, npr_unit)), rel=1e-12, abs=0.0), (func.__name__, frac)
