"""Warping registry and the overhead parameterizations."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import parameterizations as pz
from aliasing import warping
from aliasing.symbolic import lloyd2006 as L
from conftest import assert_close, exact


def test_registry_rules():
    assert set(warping.WARPING_RULES) >= {"uniform", "psm", "lispsm", "eta"}
    for rule in warping.WARPING_RULES.values():
        assert rule.source and rule.summary
    n, f = np.array([1.0, 2.0]), np.array([100.0, 50.0])
    np.testing.assert_array_equal(warping.warping_parameter("uniform", n, f), [np.inf, np.inf])
    np.testing.assert_array_equal(warping.warping_parameter("PSM", n, f), n)
    np.testing.assert_allclose(warping.warping_parameter("lispsm", n, f), [11.0, 12.0])
    np.testing.assert_allclose(warping.warping_parameter("eta", 1.0, 100.0, eta=[-0.5, 0.5]), warping.n_prime_from_eta([-0.5, 0.5], 1.0, 100.0))


def test_registry_rejects_duplicates():
    with pytest.raises(RuntimeError):
        warping.register("psm", "x", "y")(lambda near, far: near)


def test_t_perspective_matches_symbolic_and_limits(grid):
    g = grid
    t_sym = exact(L.shadow_map_coordinates()[1].subs(L.z_p, L.n_p + L.z - L.n), L.z, L.n, L.f, L.n_p)
    got = pz.t_perspective(g["z"], g["near"], g["far"], g["n_prime"])
    assert_close(got, t_sym(g["z"], g["near"], g["far"], g["n_prime"]), atol=1e-15)
    z = np.linspace(2.0, 30.0, 9)
    np.testing.assert_allclose(pz.t_perspective(z, 2.0, 30.0, np.inf), (z - 2) / 28, rtol=1e-12)
    np.testing.assert_allclose(pz.t_perspective([2.0, 30.0], 2.0, 30.0, 2.0), [0.0, 1.0])


def test_spacing_is_inverse_derivative():
    # dz/dt against a central difference of t(z), step h: truncation error O(h²)
    z, h = np.linspace(1.5, 99.5, 99), 1e-4
    for npr in (1.0, 11.0, 300.0, np.inf):
        dt_dz = (pz.t_perspective(z + h, 1.0, 100.0, npr) - pz.t_perspective(z - h, 1.0, 100.0, npr)) / (2 * h)
        np.testing.assert_allclose(1 / dt_dz, pz.spacing_perspective(z, 1.0, 100.0, npr), rtol=1e-6)
    dt_dz = (pz.t_logarithmic(z + h, 1.0, 100.0) - pz.t_logarithmic(z - h, 1.0, 100.0)) / (2 * h)
    np.testing.assert_allclose(1 / dt_dz, pz.spacing_logarithmic(z, 1.0, 100.0), rtol=1e-6)
