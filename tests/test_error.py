"""Numeric error metrics against the lambdified symbolic derivations, limits and shapes."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from aliasing import error, warping
from aliasing.symbolic import lloyd2006 as L
from aliasing.symbolic import wimmer2004 as W
from conftest import assert_close, exact

RTOL = 1e-12


def _lambdify(expr, *symbols):
    return exact(expr.subs(sp.tan(L.theta), sp.Symbol("T")), *symbols)


def _tan(fov):
    return np.tan(np.radians(fov) / 2)


@pytest.fixture(scope="module")
def sym():
    T = sp.Symbol("T")
    args = (L.z, L.n, L.f, L.n_p, T, L.res_i, L.res_s, L.res_t)
    return {
        "m_x": _lambdify(L.m_x(), *args),
        "m_z": _lambdify(L.m_z(), *args),
        "M_x": _lambdify(L.max_error_x(), *args),
        "M_z": _lambdify(L.max_error_z(), *args),
        "S": _lambdify(L.storage_factor(), *args),
        "S_opt": _lambdify(L.storage_factor_optimal(), *args),
        "dp_ds": exact(W.dp_ds(), W.z, W.z_n, W.z_f, W.n),
    }


def test_m_x_m_z_match_symbolic(grid, sym):
    g = grid
    args = (g["z"], g["near"], g["far"], g["n_prime"], _tan(g["fov"]), 512.0, 1024.0, 768.0)
    assert_close(error.m_x(g["z"], g["near"], g["far"], g["n_prime"], res_image=512, res_s=1024), sym["m_x"](*args))
    assert_close(error.m_z(g["z"], g["near"], g["far"], g["fov"], g["n_prime"], res_image=512, res_t=768), sym["m_z"](*args))


def test_maxima_and_storage_match_symbolic(grid, sym):
    g = grid
    args = (1.0, g["near"], g["far"], g["n_prime"], _tan(g["fov"]), 1.0, 1.0, 1.0)
    assert_close(error.max_error_x(g["near"], g["far"], g["n_prime"]), sym["M_x"](*args))
    assert_close(error.max_error_z(g["near"], g["far"], g["fov"], g["n_prime"]), sym["M_z"](*args))
    assert_close(error.storage_factor(g["near"], g["far"], g["fov"], g["n_prime"]), sym["S"](*args))
    assert_close(error.storage_factor_optimal(g["near"], g["far"], g["fov"]), sym["S_opt"](*args))


def test_maxima_are_the_maxima_over_z(grid):
    g = grid
    u = np.linspace(0, 1, 201).reshape(-1, 1, 1, 1, 1, 1)
    z = g["near"] + u * (g["far"] - g["near"])
    mx = error.m_x(z, g["near"], g["far"], g["n_prime"]).max(axis=0)
    mz = error.m_z(z, g["near"], g["far"], g["fov"], g["n_prime"]).max(axis=0)
    assert_close(mx, error.max_error_x(g["near"], g["far"], g["n_prime"]))
    assert_close(mz, error.max_error_z(g["near"], g["far"], g["fov"], g["n_prime"]))


def test_dp_ds_matches_symbolic_and_lloyd_m_z(grid, sym):
    g = grid
    got = error.dp_ds(g["z"], g["near"], g["far"], g["n_prime"])
    assert_close(got, sym["dp_ds"](g["z"], g["near"], g["far"], g["n_prime"]))
    mz = error.m_z(g["z"], g["near"], g["far"], g["fov"], g["n_prime"])
    assert_close(got, 2 * _tan(g["fov"]) * g["near"] * mz)


# --- limits and degenerate geometry ----------------------------------------------------


def test_uniform_limit_is_continuous():
    # n′ = inf must equal the limit of large finite n′ (no nan/inf arithmetic)
    z = np.linspace(1.0, 50.0, 7)
    big = 1e13
    for fn, extra in ((error.m_x, ()), (error.m_z, (75.0,)), (error.dp_ds, ())):
        np.testing.assert_allclose(fn(z, 1.0, 50.0, *extra, np.inf), fn(z, 1.0, 50.0, *extra, big), rtol=1e-10)
    np.testing.assert_allclose(error.storage_factor(1.0, 50.0, 75.0, np.inf), error.storage_factor(1.0, 50.0, 75.0, big), rtol=1e-10)
    # closed forms of the uniform map: M_x = f/n, M_z = (f/n − 1)/(2 tanθ), S = (f/n)(f/n − 1)/(2 tanθ)
    assert error.max_error_x(2.0, 100.0) == pytest.approx(50.0, rel=RTOL)
    assert error.max_error_z(2.0, 100.0, 90.0) == pytest.approx(49.0 / (2 * _tan(90.0)), rel=RTOL)
    assert error.storage_factor(2.0, 100.0, 90.0) == pytest.approx(50 * 49 / 2 / _tan(90.0), rel=RTOL)


def test_psm_limit():
    # n′ = n: m_x ≡ res_i/res_s (the warping frustum is the view frustum), m_z ∝ z
    z = np.linspace(1.0, 20.0, 9)
    np.testing.assert_allclose(error.m_x(z, 1.0, 20.0, 1.0), 1.0, rtol=RTOL)
    mz = error.m_z(z, 1.0, 20.0, 60.0, 1.0)
    np.testing.assert_allclose(mz / z, mz[0] / z[0], rtol=RTOL)


@pytest.mark.parametrize("eta, expected", [(-1.0, np.inf), (0.0, 11.0), (1.0, 1.0)])
def test_eta_endpoints(eta, expected):
    assert warping.n_prime_from_eta(eta, 1.0, 100.0) == pytest.approx(expected, rel=RTOL)
    assert warping.eta_from_n_prime(expected, 1.0, 100.0) == pytest.approx(eta, abs=1e-15)


def test_eta_round_trip_and_monotonic():
    eta = np.linspace(-1, 1, 101)
    npr = warping.n_prime_from_eta(eta, 2.0, 3000.0)
    assert np.all(np.diff(npr) < 0)
    np.testing.assert_allclose(warping.eta_from_n_prime(npr, 2.0, 3000.0), eta, atol=1e-12)


def test_storage_flat_for_eta_nonnegative_and_equal_to_eq12_minimum():
    eta = np.linspace(0, 1, 11)
    s = error.storage_factor(1.0, 100.0, 60.0, warping.n_prime_from_eta(eta, 1.0, 100.0))
    np.testing.assert_allclose(s, 99 / (2 * _tan(60.0)), rtol=RTOL)


def test_lispsm_gives_equal_near_and_far_m_z_and_balances_x():
    n, f = 1.0, 400.0
    npr = warping.n_prime_lispsm(n, f)
    ends = error.m_z(np.array([n, f]), n, f, 60.0, npr)
    assert ends[0] == pytest.approx(ends[1], rel=RTOL)


def test_depth_ratio_to_one():
    # f/n → 1: the frustum is a slab; no aliasing in x, S and M_z vanish linearly in f/n − 1
    n = 1.0
    for eps in (1e-3, 1e-9):
        f = n * (1 + eps)
        for npr in (n, warping.n_prime_lispsm(n, f), np.inf):
            assert error.max_error_x(n, f, npr) == pytest.approx(1.0, rel=2 * eps)
            assert error.storage_factor(n, f, 90.0, npr) == pytest.approx(eps / 2, rel=2 * eps)
    assert error.storage_factor_optimal(n, 1 + 1e-9, 90.0) == pytest.approx(0.5e-9, rel=1e-6)


def test_optimal_is_below_warped_storage(grid):
    g = grid
    assert np.all(error.storage_factor_optimal(g["near"], g["far"], g["fov"]) <= error.storage_factor(g["near"], g["far"], g["fov"], g["n_prime"]) * (1 + 1e-12))


# --- resolutions -----------------------------------------------------------------------


def test_critical_resolution_zeroes_the_error():
    rs, rt = error.critical_resolution(1.0, 100.0, 60.0, 11.0, res_image=800)
    assert error.max_error_x(1.0, 100.0, 11.0, res_image=800, res_s=rs) == pytest.approx(1.0, rel=RTOL)
    assert error.max_error_z(1.0, 100.0, 60.0, 11.0, res_image=800, res_t=rt) == pytest.approx(1.0, rel=RTOL)
    assert rs * rt == pytest.approx(800**2 * error.storage_factor(1.0, 100.0, 60.0, 11.0), rel=RTOL)


def test_budget_split_balances_error():
    rs_c, rt_c = error.critical_resolution(1.0, 1000.0, 60.0, np.array([1.0, 32.6, np.inf]), res_image=1024)
    budget = 4096.0**2
    rs, rt = error.resolution_for_budget(budget, rs_c, rt_c)
    np.testing.assert_allclose(rs * rt, budget, rtol=RTOL)
    np.testing.assert_allclose(rs_c / rs, rt_c / rt, rtol=RTOL)  # M_x = M_z
    np.testing.assert_allclose(rs_c / rs, np.sqrt(rs_c * rt_c / budget), rtol=RTOL)


# --- shapes ----------------------------------------------------------------------------


def test_scalar_in_scalar_out():
    out = error.m_z(3.0, 1.0, 10.0, 60.0, 2.0)
    assert np.ndim(out) == 0 and isinstance(float(out), float)


def test_broadcasting_nd():
    z = np.linspace(1, 10, 4).reshape(4, 1, 1)
    npr = np.array([1.0, 5.0, np.inf]).reshape(1, 3, 1)
    fov = np.array([30.0, 60.0]).reshape(1, 1, 2)
    assert error.m_z(z, 1.0, 10.0, fov, npr).shape == (4, 3, 2)
    assert error.storage_factor([1.0, 2.0], [[10.0], [20.0], [40.0]], 60.0).shape == (3, 2)
    assert error.m_x([[1.0, 2.0]], 1.0, 10.0).shape == (1, 2)
