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
    (lambda: warping.warping_parameter("lisp", 1.0, 5.0), r"unknown warping method 'lisp'; choose one of: uniform, psm, lispsm, "),
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
