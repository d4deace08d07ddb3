"""Lloyd et al. 2007 App. A figures (Figs. 18–21, 25, 26) show what the paper's text says about them.

θ = 45°, n = 1, f = 1000 throughout: y0 = √2, y1 = 1000√2, ln(f/n)/sin 2θ = 6.9078.
Small grids keep these fast; the scripts' defaults only refine them.
"""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import logpsm
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.figures import lloyd2007_fig18, lloyd2007_fig19, lloyd2007_fig20, lloyd2007_fig21, lloyd2007_fig25, lloyd2007_fig26
from aliasing.reproduce import TARGETS

LOG_T = np.log(1000.0)  # ln(f/n)/sin 2θ at θ = 45°: eqs. 89, 103


def rows(cols, name):
    return np.array([cols[f"{name}[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS])


def test_fig18_linear_limit_and_dense_sampling_near_the_light():
    cols = lloyd2007_fig18.data(4001)
    v = cols["v"]
    y = A.Y0 + A.SPAN * v
    for kappa in lloyd2007_fig18.KAPPAS:
        d = rows(cols, f"delta_b[kappa={kappa:g}]")
        # σ = ∞: eq. 62 with cos φ = 1, linear; normalised it is δ_log,t with a = 0 (eq. 102)
        np.testing.assert_allclose(d[-1], A.W_E * y * A.COS_THETA / (A.SPAN * A.Y0), rtol=1e-13)
        rho = float(logpsm.critical_factors(A.NEAR, A.FAR, A.FOV)["bound_t_side"])
        np.testing.assert_allclose(rho * d[-1], logpsm.spacing("log_t", v, A.NEAR, A.FAR, A.FOV), rtol=1e-13)
        # a near light needs sparser samples everywhere except right under it
        assert np.all(d[:-1] >= d[-1] * (1 - 1e-13))
    d = rows(cols, "delta_b[kappa=0.5]")
    ly = 0.5 * A.SPAN
    for k, sigma in enumerate(A.SIGMAS[:-1]):
        lz = sigma * A.SPAN
        interior = np.flatnonzero((d[k][1:-1] < d[k][:-2]) & (d[k][1:-1] < d[k][2:])) + 1
        if ly**2 > 8 * lz**2:  # local minimum just before the light: 2d² + l_y d + l_z² = 0
            y_min = ly + (-ly + np.sqrt(ly**2 - 8 * lz**2)) / 4
            assert interior.size == 1 and abs(y[interior[0]] - y_min) <= y[1] - y[0]
        else:
            assert interior.size == 0  # σ ≥ 0.2 at κ = 0.5: monotone


def test_fig19_rounded_absolute_value_converging_to_uniform():
    cols = lloyd2007_fig19.data(401)
    v = cols["v"]
    y = A.W_E * A.FAR / A.NEAR * (v - 0.5)
    d = rows(cols, "delta_b_over_cos")
    for k, sigma in enumerate(A.SIGMAS):
        if np.isinf(sigma):
            np.testing.assert_array_equal(d[k], 1.0)  # "converges to uniform"
            continue
        lz = sigma * A.SPAN
        np.testing.assert_allclose(d[k], np.sqrt(y**2 + lz**2) / lz, rtol=1e-14)  # 1/cos φ_ly, eqs. 57–58
        assert d[k][200] == 1.0 and np.argmin(d[k]) == 200  # the rounded tip, under the light
        np.testing.assert_allclose(d[k], d[k][::-1], rtol=1e-14)
        assert abs(d[k][0] - abs(y[0]) / lz) <= lz / abs(y[0])  # |y − l_y|/l_z away from it


def test_fig20_is_the_end_face_spacing_extruded_and_scaled_by_y():
    n = 41
    cols = lloyd2007_fig20.data(n)
    u, v, d = (cols[k].reshape(n, n) for k in ("u", "v", "delta_b_s"))
    y = A.Y0 + A.SPAN * v
    lz = lloyd2007_fig20.SIGMA * A.SPAN
    end = logpsm.delta_bound_end(u[0], A.NEAR, A.FAR, A.FOV, ly=0.0, lz=lz, face="far")  # the far face is W_e f/n = x1(y1) − x0(y1) wide
    np.testing.assert_allclose(d * A.Y1 / y, np.broadcast_to(end, d.shape), rtol=1e-13)
    on = cols["on_face"].reshape(n, n) > 0
    assert on[:, n // 2].all() and not on[0, 0] and on[-1].all()  # the trapezoid of eq. 69
    assert np.all(np.argmin(d, axis=1) == n // 2)  # densest under the light


@pytest.fixture(scope="module")
def fig21():
    return lloyd2007_fig21.data(61)


def test_fig21_maximum_is_the_overhead_closed_form(fig21):
    expected = {"R_b_t_end_times_cos": 1.0, "R_b_s_side_times_cos": 1.0, "R_b_t_side": LOG_T}  # eqs. 87–89
    for name, value in expected.items():
        r = rows(fig21, name)
        np.testing.assert_allclose(r[-1], value, rtol=1e-12)
        assert np.all(r[:-1] < value * (1 + 1e-12))  # eq. 72: no light position does worse


def test_fig21_smaller_near_the_plane_and_falling_off_to_either_side(fig21):
    for name, _, _, (lo, hi), _ in lloyd2007_fig21.PANELS:
        r, kappa = rows(fig21, name), fig21[f"kappa[{name}]"]
        assert np.all(np.diff(r, axis=0) >= -1e-12)  # rises with σ at every position
        left, right = kappa < lo, kappa > hi
        assert np.all(np.diff(r[:-1, left], axis=1) > 0) and np.all(np.diff(r[:-1, right], axis=1) < 0)  # (σ = ∞ is flat)


def test_fig25_log_parameterization_vs_the_bound():
    cols = lloyd2007_fig25.data(31)
    kappa = cols["kappa"]
    opt, a0, bound, a_opt = rows(cols, "R_log_t_opt"), rows(cols, "R_log_t_a0"), rows(cols, "R_b_t"), rows(cols, "a_opt")
    np.testing.assert_allclose(opt[-1], LOG_T, rtol=1e-12)  # eq. 103 = eq. 89 overhead, a_opt = 0
    np.testing.assert_array_equal(a_opt[-1], 0.0)
    assert np.all(opt <= LOG_T * (1 + 1e-12)) and np.all(opt <= a0 * (1 + 1e-12))
    assert np.all(opt >= bound * (1 - 1e-12)) and np.max(opt / bound) < 5.0  # "on the same order as R_b,t"
    over = (kappa * A.SPAN >= A.Y0) & (kappa * A.SPAN <= A.Y1)
    np.testing.assert_allclose(a0[:, over], LOG_T, rtol=1e-9)  # a = 0: the maximum whenever over the face
    assert np.all(opt[0, over][1:] < 0.95 * LOG_T)  # ... which the optimal a lowers for a low light


def test_fig26_linear_form_optimal_a_is_zero_and_two_parabolas_approach_the_bound():
    cols = lloyd2007_fig26.data(21)
    S_lp, a_opt, S_two, S_b = rows(cols, "S_lp"), rows(cols, "a_opt"), rows(cols, "S_two_parabolas"), rows(cols, "S_b")
    np.testing.assert_array_equal(a_opt, 0.0)  # "It appears that the optimal parameter is always a = 0"
    s_max = np.sqrt(2) * LOG_T  # eq. 99 × eq. 103
    np.testing.assert_allclose(S_lp[-1], s_max, rtol=1e-12)
    assert np.all(S_lp <= s_max * (1 + 1e-12))
    assert np.all(S_two >= S_b * (1 - 1e-9)) and np.all(S_two <= 1.1 * S_b)  # "approaches that of δ_b,t^side"
    np.testing.assert_allclose(S_two[-1], S_b[-1], rtol=1e-9)
    assert np.max(S_lp / S_b) > 5  # while the linear form does not


def test_fig26_parabolic_fits_stay_below_the_bound():
    fit = lloyd2007_fig26.fits(401)
    R_lin, R_one, R_two, rho = fit["R"]
    assert R_lin > R_one > R_two > rho  # more freedom, lower critical resolution; ρ_b is the least
    assert R_lin == pytest.approx(LOG_T, rel=1e-9)  # the light is over the face
    for key in ("linear", "one_parabola", "two_parabolas"):
        assert np.all(fit[key] <= fit["bound"] * (1 + 1e-9)), key
        assert np.max(fit[key] / fit["bound"]) > 0.999, key  # and touches it where R is attained


def test_targets_registered_and_reruns_identical(tmp_path):
    for n in (18, 19, 20, 21, 25, 26):
        assert TARGETS[f"lloyd2007-fig{n}"].module == f"lloyd2007_fig{n}"
    first = lloyd2007_fig19.main(tmp_path / "a")
    second = lloyd2007_fig19.main(tmp_path / "b")
    assert [p.read_bytes() for p in first] == [p.read_bytes() for p in second]
