"""Bad input: a ValueError that names the parameter and its allowed range."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import error, parameterizations, warping

CASES = [
    (lambda: error.storage_factor(10.0, 10.0, 60.0), r"far must be greater than near"),
    (lambda: error.storage_factor(10.0, 5.0, 60.0), r"far must be greater than near"),
    (lambda: error.storage_factor(0.0, 5.0, 60.0), r"near must be in \(0, inf\)"),
    (lambda: error.storage_factor(1.0, np.inf, 60.0), r"far must be finite, got inf"),
    (lambda: error.storage_factor(1.0, 5.0, 180.0), r"fov .* must be in \(0, 180\) degrees"),
    (lambda: error.storage_factor(1.0, 5.0, 0.0), r"fov .* must be in \(0, 180\) degrees"),
    (lambda: error.storage_factor(1.0, 5.0, [30.0, -1.0]), r"fov .*array with values in \[-1, 30\]"),
    (lambda: error.storage_factor(1.0, 5.0, 60.0, 0.5), r"n_prime must be in \[near, inf\]"),
    (lambda: error.m_x(0.5, 1.0, 5.0), r"z must lie in \[near, far\]"),
    (lambda: error.m_x(6.0, 1.0, 5.0), r"z must lie in \[near, far\]"),
    (lambda: error.m_x(2.0, 1.0, 5.0, res_s=0), r"res_s must be in \(0, inf\)"),
    (lambda: error.m_z(2.0, 1.0, 5.0, 60.0, res_image=-512), r"res_image must be in \(0, inf\)"),
    (lambda: error.m_z(2.0, 1.0, 5.0, 60.0, res_t=np.nan), r"res_t must not be NaN"),
    (lambda: error.resolution_for_budget(-1, 10, 10), r"budget must be in \(0, inf\)"),
    (lambda: error.m_x("deep", 1.0, 5.0), r"z must be a real number"),
    (lambda: warping.n_prime_from_eta(1.5, 1.0, 5.0), r"eta must be in \[-1, 1\]"),
    (lambda: warping.warping_parameter("lisp", 1.0, 5.0), r"unknown warping method 'lisp' \(did you mean 'lispsm' or 'lispsm-dz'\?\); choose one of: uniform, psm, lispsm, "),
    (lambda: warping.warping_parameter("psm", 1.0, 5.0, eta=0.3), r"takes options none, not \['eta'\]"),
    (lambda: parameterizations.t_logarithmic(0.9, 1.0, 5.0), r"z must lie in \[near, far\]"),
]


@pytest.mark.parametrize("call, message", CASES)
def test_bad_input_names_parameter_and_range(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_boundaries_are_accepted():
    # closed ends of the allowed ranges are valid input, not errors
    assert np.isfinite(error.m_x([1.0, 5.0], 1.0, 5.0, 1.0)).all()
    assert warping.n_prime_from_eta(-1.0, 1.0, 5.0) == np.inf


# Issue 19 item 4: every example the issue lists, and the classes of input behind them.
from aliasing import budgets, geometry, logpsm, partitioning, schemes  # noqa: E402

ISSUE_19 = [
    (lambda: geometry.sphere_directions(1j), ValueError, r"count must be a whole number >= 1, got 1j"),
    (lambda: geometry.sphere_directions(np.inf), ValueError, r"count must be a whole number >= 1, got inf"),
    (lambda: geometry.sphere_directions(10**11), ValueError, r"count must be a whole number in \[1, 10000000\]"),
    (lambda: geometry.lights("sphere:100000000000"), ValueError, r"N must be a whole number in \[1, 10000000\]"),
    (lambda: budgets.allocate("pow2", 180, 180, 180), ValueError, r"M_x and M_z must have the same shape \(\.\.\., K\)"),
    (lambda: budgets.allocate(1.5, [[1.0]], [[1.0]], 10), ValueError, r"allocation method must be a string"),
    (lambda: schemes.evaluate(None, 0.01, 10.5, 0.5, "overhead"), TypeError, r"scheme must be a str or Scheme, got NoneType"),
    (lambda: schemes.parse(None), TypeError, r"name \(scheme name\) must be a str"),
    (lambda: warping.shaping_eta(10**400, "nan"), ValueError, r"gamma is outside the float range"),
    (lambda: warping.shaping_eta(30.0, "nan"), ValueError, r"fov must be a real number"),
    (lambda: partitioning.split_distances("bgfx", 0.95, [[]]), ValueError, r"far must be a single number, got an array of shape \(1, 0\)"),
    (lambda: schemes.z_partitions([1.0, 2.0], 10.0, 3), ValueError, r"near must be a single number"),
    (lambda: schemes.z_partitions(1.0, 10.0, np.array([2, 3])), ValueError, r"k must be a whole number >= 1"),
    (lambda: budgets.max_error(0.0, 1.0, 1.0, 1.0), ValueError, r"M_x must be in \(0, inf\)"),
    (lambda: budgets.max_error(1.0, np.nan, 1.0, 1.0), ValueError, r"M_z must not be NaN"),
    (lambda: geometry.lights([np.inf, 0.0, 1.0]), ValueError, r"light must be finite, got inf"),
    (lambda: geometry.direction_angles([0.0, -np.inf, 1.0]), ValueError, r"light must be finite, got -inf"),
    (lambda: error.max_error_x(0.01, 1e308, 1e308), ValueError, r"far/near must be at most 1.8e308"),
    # inf is named as inf, not as NaN; complex numbers and strings by name
    (lambda: error.m_z(2.0, 1.0, 5.0, 60.0, res_t=np.inf), ValueError, r"res_t must be finite, got inf"),
    (lambda: error.m_x(2.0 + 1j, 1.0, 5.0), ValueError, r"z must be real, got a complex number"),
    (lambda: error.m_x(np.array([2.0, 3.0 + 0.5j]), 1.0, 5.0), ValueError, r"z must be real"),
    (lambda: error.m_x("2.0", 1.0, 5.0), ValueError, r"z must be a real number"),
    (lambda: error.storage_factor(1.0, 10**400, 60.0), ValueError, r"far is outside the float range"),
    # numpy's broadcast errors name the parameters and their shapes
    (lambda: error.storage_factor([1.0, 2.0], [10.0, 20.0, 30.0], 60.0), ValueError, r"shapes do not broadcast together: near \(2,\), far \(3,\)"),
    (lambda: error.m_x([2.0, 3.0], 1.0, 5.0, res_s=[1.0, 2.0, 3.0]), ValueError, r"shapes do not broadcast together: z \(2,\), res_s \(3,\)"),
    (lambda: warping.n_prime_from_eta([0.1, 0.2], 1.0, [5.0, 6.0, 7.0]), ValueError, r"shapes do not broadcast together: eta \(2,\), far \(3,\)"),
    (lambda: geometry.frustum_vertices([1.0, 2.0], 100.0, []), ValueError, r"shapes do not broadcast together: near \(2,\), far \(\), fov \(0,\)"),
    # other types where a number, a Camera or a dict belongs
    (lambda: logpsm.delta_bound_end(0.3, 1.0, 10.0, 60.0, directional=np.array([])), TypeError, r"directional must be True or False"),
    (lambda: error.storage_factor(1.0, 10.0, 1e-300), ValueError, r"fov \(full field of view\) must be at least 1e-06 degrees"),
]


@pytest.mark.parametrize("call, kind, message", ISSUE_19)
def test_issue_19_bad_input_is_named(call, kind, message):
    with pytest.raises(kind, match=message):
        call()


def test_overflowing_valid_input_gives_inf_not_nan():
    # issue 19: "a valid but overflowing input gives inf or a refusal, never NaN"
    assert error.max_error_x(1.0, 1e308, res_image=1e10) == np.inf  # 1e318 pixels per texel
    assert np.isfinite(error.max_error_x(1.0, 1e308, 1e308))  # f n'/(n (n' + f - n)) = 5e307
    factors = logpsm.critical_factors(1.0, 1e308, 60.0)
    assert not any(np.isnan(v).any() for v in factors.values())
    assert budgets.max_error(1e308, 1.0, 1e-10, 1.0) == np.inf
