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


def test_log_perspective_t_map_eq78():
    # eq. 78 built from its parts (eqs. 75–76 perspective map, c0, c1, c2) equals the closed form
    y0, y1, a = 2.0, 50.0, 3.0
    y = np.linspace(y0, y1, 41)
    p2 = (y1 + a) / (y1 - y0)
    p3 = -p2 * (y0 + a)
    f_pt = (p2 * (y + a) + p3) / (y + a)  # eq. (75), t component
    c0 = -1 / np.log((y1 + a) / (y0 + a))
    c1, c2 = (y0 + a) / p3, -(y0 + a) * p2 / p3
    f_lpt = c0 * np.log(c1 * f_pt + c2)  # eq. (78)
    # c0 as printed is negative: ln(c1 F_p,t + c2) = ln((y0+a)/(y+a)) ≤ 0, so the map still rises 0 → 1
    np.testing.assert_allclose(pz.t_log_perspective(y, y0, y1, a), f_lpt, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(pz.t_log_perspective(y, y0, y1, np.inf), (y - y0) / (y1 - y0), rtol=1e-12)
    # spacing (dt/dy)⁻¹ = (y + a) ln((y1 + a)/(y0 + a)): the logperspective w_lz of aliasing.directional
    h = 1e-5
    inner = y[1:-1]
    dtdy = (pz.t_log_perspective(inner + h, y0, y1, a) - pz.t_log_perspective(inner - h, y0, y1, a)) / (2 * h)
    np.testing.assert_allclose(1 / dtdy, (inner + a) * np.log((y1 + a) / (y0 + a)), rtol=1e-7)


def test_warping_frustum_is_tight_for_every_direction():
    from aliasing import directional, geometry

    lf = directional.fit(geometry.frustum_vertices(1.0, 300.0, 70.0), geometry.sphere_directions(300))
    for npr in (np.full(lf.depth.shape, 5.0), lf.depth, np.full(lf.depth.shape, np.inf)):
        s, t = directional.warping_frustum(lf, npr).coordinates(lf.x, lf.y)
        np.testing.assert_allclose(s.min(axis=-1), 0.0, atol=1e-12)
        np.testing.assert_allclose(s.max(axis=-1), 1.0, atol=1e-12)
        np.testing.assert_allclose(t.min(axis=-1), 0.0, atol=1e-12)
        np.testing.assert_allclose(t.max(axis=-1), 1.0, atol=1e-12)
