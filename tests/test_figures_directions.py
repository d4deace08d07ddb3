"""Figures over light directions (Lloyd 2006 Fig. 7, Lloyd 2007 Figs. 29–30) show what the papers' text says.

Small resolutions / sample counts keep these fast; the scripts' defaults only refine the grids.
"""

from __future__ import annotations

import numpy as np
import pytest

from aliasing.figures import lloyd2006_fig7, lloyd2007_fig29, lloyd2007_fig30
from aliasing.warping import shaping_eta

TAN30 = np.tan(np.radians(30.0))


# --- Lloyd et al. 2006 Fig. 7: f/n = 1000, θ = 30° (Fig. 12's frustum) -------------------------


@pytest.fixture(scope="module")
def fig7():
    res = 21
    cols = lloyd2006_fig7.data(res)
    grids = {k: cols[k].reshape(res, res) for k in cols}
    return res, cols, grids


def test_fig7_columns_and_disc(fig7):
    res, cols, grids = fig7
    assert list(cols) == ["u", "v", "log10S_standard", "log10S_lispsm", "log10S_fpw"]
    outside = 1.0 - grids["u"] ** 2 - grids["v"] ** 2 < 0  # hemisphere_map's test
    for key in ("log10S_standard", "log10S_lispsm", "log10S_fpw"):
        assert np.isnan(grids[key][outside]).all() and np.isfinite(grids[key][~outside]).all()
    with pytest.raises(ValueError, match="odd"):
        lloyd2006_fig7.data(20)


def test_fig7_overhead_closed_forms(fig7):
    res, _, grids = fig7
    c = res // 2
    assert grids["u"][c, c] == 0 and grids["v"][c, c] == 0
    a = lloyd2006_fig7.FAR / lloyd2006_fig7.NEAR
    # Lloyd 2006 eq. 12 at n′ = n′_LiSPSM, and the uniform map n′ = ∞
    assert grids["log10S_lispsm"][c, c] == pytest.approx(np.log10((a - 1) / (2 * TAN30)), rel=1e-12)
    assert grids["log10S_standard"][c, c] == pytest.approx(np.log10(a * (a - 1) / (2 * TAN30)), rel=1e-12)


def test_fig7_what_the_text_says(fig7):
    res, _, grids = fig7
    c = res // 2
    std, lis = grids["log10S_standard"], grids["log10S_lispsm"]
    a = lloyd2006_fig7.FAR / lloyd2006_fig7.NEAR
    # without warping: high everywhere, between the overhead value and 2(f/n)² (Lloyd 2007 Table 3)
    assert np.nanmin(std) == pytest.approx(std[c, c], rel=1e-12)
    assert np.nanmax(std) <= np.log10(2 * a * a) + 1e-12
    # with warping: lowest overhead, highest towards behind (left) and in front (right)
    assert np.nanmin(lis) == pytest.approx(lis[c, c], rel=1e-12)
    behind, front = lis[c, 0], lis[c, -1]
    assert behind > lis[c, c] + 3 and front > lis[c, c] + 3
    # there the map reverts to n′ = ∞: both panels agree, S̄ = (f/n)² for a square far face
    assert behind == pytest.approx(std[c, 0], rel=1e-12) and front == pytest.approx(np.log10(a * a), rel=1e-12)
    # warping helps wherever the light is at least θ away from the view axis
    away = np.abs(grids["u"]) <= np.cos(np.radians(30.0))
    assert np.all(lis[away & np.isfinite(lis)] < std[away & np.isfinite(std)])


def test_fig7_face_partitioning_panel(fig7):
    # Lloyd 2006 §5.1: "face partitioning reduces the error for the problematic light/camera
    # configurations and leads to a more uniform error distribution over all light directions"
    res, _, grids = fig7
    c = res // 2
    fp, lis, std = grids["log10S_fpw"], grids["log10S_lispsm"], grids["log10S_standard"]
    a = lloyd2006_fig7.FAR / lloyd2006_fig7.NEAR
    assert fp[c, c] == pytest.approx(lis[c, c], rel=1e-12)  # overhead: the bottom face alone
    for edge in (fp[c, 0], fp[c, -1]):  # behind / in front: four faces and the near face
        assert edge == pytest.approx(np.log10(2 * (a - 1) + 1), rel=1e-12)
    assert np.nanmax(fp) < np.nanmax(lis) - 2 and np.nanmax(fp) < np.nanmin(std) - 2
    assert np.nanmax(fp) - np.nanmin(fp) < 1.0  # under a decade of spread (LiSPSM: > 3)


def test_fig7_symmetries(fig7):
    _, _, grids = fig7
    for key in ("log10S_standard", "log10S_lispsm", "log10S_fpw"):
        g = grids[key]
        # sideways mirror (x → −x) and l → −l with the frustum's up/down symmetry (behind ↔ front)
        np.testing.assert_allclose(g, g[::-1, :], rtol=1e-9)
        np.testing.assert_allclose(g, g[:, ::-1], rtol=1e-9)


# --- Lloyd et al. 2007 Fig. 29: n = 1, f = 1024, θ = 30° --------------------------------------


@pytest.fixture(scope="module")
def fig29():
    cols = lloyd2007_fig29.data(count=21, samples=11)
    return {g: {k: v[cols["gamma"] == g] for k, v in cols.items()} for g in lloyd2007_fig29.GAMMAS}


def test_fig29_overhead(fig29):
    c = fig29[90.0]
    a = lloyd2007_fig29.FAR / lloyd2007_fig29.NEAR
    eta = c["eta"]
    # "S_p is the same over η ∈ [0, 1] for γ = 90°" (caption), = Lloyd 2006 eq. 12
    np.testing.assert_allclose(c["S[P]"][eta >= 0], (a - 1) / (2 * TAN30), rtol=1e-10)
    # R and the variation of M̃ for F_p,s and F_lp,t minimal at η = 1; S_lp = ln(f/n)/(2 tanθ) (App. C)
    one, zero = eta == 1, eta == 0
    np.testing.assert_allclose(c["M_s(v_n1)[P]"][one], 1.0, rtol=1e-12)
    assert c["M_x[P]"][one] == pytest.approx(c["M_x[P]"].min())
    assert c["M_t(v_n1)[LogP]"][one] == pytest.approx(c["M_t(1)[LogP]"][one], rel=1e-10)
    assert c["S[LogP]"][one] == pytest.approx(np.log(a) / (2 * TAN30), rel=1e-10)
    # η = 0 (LiSPSM): M̃_p,t equal at both ends; the minimum over v lies inside
    assert c["M_t(v_n1)[P]"][zero] == pytest.approx(c["M_t(1)[P]"][zero], rel=1e-10)
    assert 0 < c["v_min[P]"][zero][0] < 1
    # eq. 120 in light-plane units: n′(1) = n_γ = W_ly/(f/n − 1) = n overhead
    assert c["n_prime"][one][0] == pytest.approx(1.0, rel=1e-12)


def test_fig29_shape_of_curves(fig29):
    for g, c in fig29.items():
        # F_lp,s = F_p,s
        np.testing.assert_array_equal(c["M_x[LogP]"], c["M_x[P]"])
        for label in ("P", "LogP"):
            # R is the larger of the v = v_n1 and v = 1 values, and the minimum lies below both
            np.testing.assert_allclose(c[f"M_x[{label}]"], np.maximum(c["M_s(v_n1)[P]"], c["M_s(1)[P]"]), rtol=1e-12)
            np.testing.assert_allclose(c[f"M_z[{label}]"], np.maximum(c[f"M_t(v_n1)[{label}]"], c[f"M_t(1)[{label}]"]), rtol=1e-12)
            assert np.all(c[f"M_t(v_min)[{label}]"] <= np.minimum(c[f"M_t(v_n1)[{label}]"], c[f"M_t(1)[{label}]"]) * (1 + 1e-12))
            # η = −1 is the uniform map
            assert c[f"S[{label}]"][0] == pytest.approx(c["S[Standard]"][0], rel=1e-12), g


def test_fig29_what_the_text_says(fig29):
    one = fig29[90.0]["eta"] == 1
    r_ps = {g: c["M_x[P]"][one][0] for g, c in fig29.items()}
    r_lpt = {g: c["M_z[LogP]"][one][0] for g, c in fig29.items()}
    # as γ decreases to θ, R_p,s rises significantly while R_lp,t remains practically the same
    assert r_ps[90.0] < r_ps[60.0] < r_ps[30.0] and r_ps[30.0] > 1000 * r_ps[90.0]
    assert r_lpt[30.0] < 2.5 * r_lpt[90.0]
    # light in front: minimal maximum error at η = −1 for all parameterizations
    c0 = fig29[0.0]
    assert np.argmin(c0["S[P]"]) == 0 and np.argmin(c0["S[LogP]"]) == 0
    assert np.all(c0["S[P]"][1:] > c0["S[Standard]"][1:]) and np.all(c0["S[LogP]"][1:] > c0["S[Standard]"][1:])
    # at γ = θ, P needs η ≈ 0
    c30 = fig29[30.0]
    assert c30["eta"][np.argmin(c30["S[P]"])] == pytest.approx(0.0, abs=1e-12)


# --- Lloyd et al. 2007 Fig. 30: n = 1, f = 1024, θ = 30° --------------------------------------


@pytest.fixture(scope="module")
def fig30():
    return lloyd2007_fig30.data(count=46, samples=11)  # γ in steps of 2°, θ = 30° on the grid


def test_fig30_strategies(fig30):
    g, w = fig30["gamma"], fig30["W_ly"]
    a = lloyd2007_fig30.FAR / lloyd2007_fig30.NEAR
    n_gamma = w / (a - 1)
    # row 1: the γ = 90° optima
    np.testing.assert_array_equal(fig30["eta[fixed|P]"], 0.0)
    np.testing.assert_allclose(fig30["eta[fixed|LogP]"], 1.0, rtol=1e-12)
    # row 2: n′ of the optimum divided by sin γ (∞ at γ = 0)
    with np.errstate(divide="ignore"):
        s = np.sin(np.radians(g))
        np.testing.assert_allclose(fig30["n_prime[1/sin(gamma)|P]"], n_gamma * (1 + np.sqrt(a)) / s, rtol=1e-12)
        np.testing.assert_allclose(fig30["n_prime[1/sin(gamma)|LogP]"], n_gamma / s, rtol=1e-12)
    assert fig30["eta[1/sin(gamma)|P]"][0] == -1 and fig30["eta[1/sin(gamma)|LogP]"][0] == -1
    # row 4: eq. 79
    np.testing.assert_allclose(fig30["eta[eq. 79|P]"], shaping_eta(g, lloyd2007_fig30.FOV, "p"), atol=1e-10)
    np.testing.assert_allclose(fig30["eta[eq. 79|LogP]"], shaping_eta(g, lloyd2007_fig30.FOV, "logp"), atol=1e-10)


def test_fig30_s_optimal_is_lowest(fig30):
    for label in ("P", "LogP"):
        best = fig30[f"S[S-optimal|{label}]"]
        for strategy in lloyd2007_fig30.STRATEGIES:
            assert np.all(best <= fig30[f"S[{strategy}|{label}]"] * (1 + 1e-9)), (strategy, label)
        # "The optimal S_p and S_lp never rise above S_un"
        assert np.all(best <= fig30["S[Standard]"] * (1 + 1e-12))


def test_fig30_s_optimal_eta(fig30):
    g = fig30["gamma"]
    p, lp = fig30["eta[S-optimal|P]"], fig30["eta[S-optimal|LogP]"]
    above = (g > 30) & (g < 90)
    # for γ > θ the same as without shaping (γ = 90° is a tie for P: S_p is flat over η ∈ [0, 1])
    assert np.all(np.abs(p[above]) < 0.01)
    np.testing.assert_allclose(lp[above], 1.0, atol=1e-6)
    # below θ: near 0 just under θ, then falling to −1 at about θ/3 (P) and θ/2 (LogP)
    below = g < 30
    assert np.all(np.diff(p[below]) >= -1e-9) and np.all(np.diff(lp[below]) >= -1e-9)
    assert np.all(p[g <= 10] == -1) and np.all(lp[g <= 14] == -1)
    assert p[g == 28][0] > -0.1 and lp[g == 28][0] > -0.1
    assert lp[g == 30][0] > 0.5  # the jump from 1 happens at θ


def test_fig30_what_the_text_says(fig30):
    g, s_un = fig30["gamma"], fig30["S[Standard]"]
    low = g < 24
    for label in ("P", "LogP"):
        # row 1: very high error for γ < θ; row 2: 1/sin γ falls off too slowly
        assert np.all(fig30[f"S[fixed|{label}]"][low] > s_un[low])
        assert fig30[f"S[1/sin(gamma)|{label}]"].max() > 3 * s_un.max()
        # row 4: eq. 79 keeps the maximum at the standard map's level
        assert fig30[f"S[eq. 79|{label}]"].max() <= s_un.max() * (1 + 1e-12)
        assert np.all(fig30[f"S[eq. 79|{label}]"] <= s_un * 1.001)
        # overhead closed forms for the fixed optima
    a = lloyd2007_fig30.FAR / lloyd2007_fig30.NEAR
    assert fig30["S[fixed|P]"][-1] == pytest.approx((a - 1) / (2 * TAN30), rel=1e-10)
    assert fig30["S[fixed|LogP]"][-1] == pytest.approx(np.log(a) / (2 * TAN30), rel=1e-10)
    # "M̃_lp,s has even higher error because η_lp is further from −1 than η_p" (row 2, 0 < γ < θ)
    mid = (g > 0) & (g < 30)
    assert np.all(fig30["M_s(v_n1)[1/sin(gamma)|LogP]"][mid] > fig30["M_s(v_n1)[1/sin(gamma)|P]"][mid])


def test_E7_lispsm_storage_peaks_off_axis_not_behind_or_in_front():
    # Lloyd 2006 §4.4 on Fig. 7: with warping S̄ "is highest when the light comes from directly behind
    # or in front of the viewer".  With LiSPSM's n′ = (n + √(fn))/sin γ it peaks near γ ≈ 11° instead,
    # at over four times the value at γ = 0° or 180° (f/n = 1000, θ = 30°): ERRATA E7.
    import numpy as np

    from aliasing import geometry, schemes

    gamma = np.linspace(0.0, 180.0, 3601)
    s = schemes.evaluate("lispsm", 1.0, 1000.0, 60.0, geometry.light_direction(gamma, 0.0)).S
    peak = gamma[np.argmax(s)]
    assert 10.0 < min(peak, 180.0 - peak) < 12.5
    assert s.max() > 4 * max(s[0], s[-1])
