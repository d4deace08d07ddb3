"""Lloyd et al. 2007 App. A Figs. 22–24 show what the paper's text says about them (or, where
not, what ERRATA L19 and L21 record).  θ = 45°, n = 1, f = 1000: y0 = √2, y1 = 1000√2."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.figures import lloyd2007_fig21, lloyd2007_fig22, lloyd2007_fig23, lloyd2007_fig24
from aliasing.reproduce import TARGETS

F_N = A.FAR / A.NEAR


def rows(cols, name):
    return np.array([cols[f"{name}[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS])


@pytest.fixture(scope="module")
def fig22():
    return lloyd2007_fig22.data(61)


def test_fig22_overhead_closed_forms_and_maximum(fig22):
    # eqs. 93–95 at σ = ∞ (cos θ factored out of the first two): 1, f/n, (f/n − 1)/sin 2θ
    for name, value in zip((p[0] for p in lloyd2007_fig22.PANELS), (1.0, F_N, F_N - 1)):
        r = rows(fig22, name)
        np.testing.assert_allclose(r[-1], value, rtol=1e-9)
        assert np.all(r <= value * (1 + 1e-9))  # eq. 72: no light position does worse


def test_fig22_end_face_maximal_over_the_face_side_face_only_over_its_near_edge(fig22):
    # "R_un reaches its maximum whenever the light position is over the face": end face yes ...
    name = "R_un_t_end_times_cos"
    kappa, r = fig22[f"kappa[{name}]"], rows(fig22, name)
    over = np.abs(kappa) <= lloyd2007_fig22.END_HALF
    np.testing.assert_allclose(r[:, over], 1.0, rtol=1e-9)
    assert np.all(r[:-1, ~over] < 1.0)
    # ... the side face's R_un,t only over the near edge y0 (ERRATA L19)
    name = "R_un_t_side"
    kappa, r = fig22[f"kappa[{name}]"], rows(fig22, name)
    mid = (kappa > 0.2) & (kappa < 0.8)
    assert np.all(r[:-1][:, mid] < 0.99 * (F_N - 1))  # every finite σ drops over the middle of the face
    assert np.all(r[:2][:, mid] < 0.75 * (F_N - 1))  # σ ≤ 0.2: by more than a quarter


def test_fig22_side_face_magnitudes_differ_from_fig21_by_the_y_term(fig22):
    # "on the side face, the magnitudes of the plots differ significantly … a factor of f_e/n_e"
    kappa = fig22["kappa[R_un_t_side]"]
    un, b = rows(fig22, "R_un_t_side"), lloyd2007_fig22.panel("R_b_t_side", kappa, kind="bound")
    assert un[-1, 0] / b[-1, 0] == pytest.approx((F_N - 1) / np.log(F_N), rel=1e-9)  # 999/6.908 = 144.6
    # "when the light is not directly over the face, the shapes of the graphs are nearly identical":
    # normalised by their overhead values, off the face the two differ by at most 30 % of each other
    off = (kappa < -0.3) | (kappa > 1.3)
    shape_un, shape_b = un[:-1, off] / un[-1, off], b[:-1, off] / b[-1, off]
    assert np.max(np.abs(shape_un / shape_b - 1)) < 0.30
    # end face: identical maxima (text after eq. 95) and, off the face, the same fall-off order
    k = fig22["kappa[R_un_t_end_times_cos]"]
    b_end = lloyd2007_fig22.panel("R_b_t_end_times_cos", k, kind="bound")
    assert b_end[-1].max() == pytest.approx(rows(fig22, "R_un_t_end_times_cos")[-1].max(), rel=1e-9)


@pytest.fixture(scope="module")
def fig23():
    return lloyd2007_fig23.data(13, samples=33)


def test_fig23_overhead_is_eqs_99_to_101_and_the_worst(fig23):
    s2t = np.sin(2 * np.radians(45.0))
    expected = {
        "R_p_s_side_times_cos": 1.0,  # eq. 99 (cos θ factored out)
        "R_p_t_side": (F_N - 1) / (s2t * np.sqrt(F_N)),  # eq. 100, corrected later form (L16): 31.59
        "S_p_side": (F_N - 1) / (s2t * A.COS_THETA),  # eq. 101, corrected later form (L16): 1412.8
    }
    for name, value in expected.items():
        r = rows(fig23, name)
        np.testing.assert_allclose(r[-1], value, rtol=1e-6)
        assert np.all(r <= value * (1 + 1e-6)), name
    # at σ = ∞ the optimal a of R_p,t is LiSPSM's √(y0 y1)
    np.testing.assert_allclose(rows(fig23, "a_opt[R_p_t_side]")[-1], np.sqrt(A.Y0 * A.Y1), rtol=1e-4)


def test_fig23_R_s_is_minimised_at_a_zero(fig23):
    # "R_p,s^side is minimized when a = 0, which leaves only the cos φ_lx/cos θ term"
    a = rows(fig23, "a_opt[R_p_s_side_times_cos]")
    assert np.all(a < 1e-6 * A.Y1)
    kappa = fig23["kappa[R_p_s_side_times_cos]"]
    from aliasing.face_factors import face_factors

    lz = A.heights()
    cos_lx = face_factors("uniform", A.NEAR, A.FAR, A.FOV, lx=kappa * A.SPAN, lz=lz, face="far")["R_s"] * A.COS_THETA
    np.testing.assert_allclose(rows(fig23, "R_p_s_side_times_cos"), cos_lx, rtol=1e-6)


def test_fig24_optimal_range_top_is_lispsm_overhead_and_shrinks_for_near_lights():
    # "For an overhead directional light this corresponds to the LiSPSM parameter" √(y0 y1)
    ly = np.array([-0.5, 0.25, 0.5, 1.5]) * A.SPAN
    top = lloyd2007_fig24.a_range_top(ly, np.inf)
    np.testing.assert_allclose(top, np.sqrt(A.Y0 * A.Y1), rtol=1e-6)
    # l_y = 0.5 y1: a flat range for σ = 1 (to 44.7), none beyond ~1 for σ ≤ 0.5 (ERRATA L21)
    lz = np.array([0.1, 0.2, 0.5, 1.0]) * A.SPAN
    top = lloyd2007_fig24.a_range_top(0.5 * A.Y1, lz)
    assert top[3] == pytest.approx(np.sqrt(A.Y0 * A.Y1), rel=1e-3)
    assert np.all(top[:3] < 1.0)
    s = lloyd2007_fig24.storage(np.array([0.0, 44.0]), 0.5 * A.Y1, lz[:, None])
    np.testing.assert_allclose(s[:, 1] / s[:, 0] - 1, [0.0568, 0.0451, 0.0019, 0.0], atol=5e-4)  # the figure docstring: 5.7 %, 4.5 %, 0.19 %


@pytest.mark.parametrize("n", [22, 23, 24])
def test_registered(n):
    assert f"lloyd2007-fig{n}" in TARGETS
