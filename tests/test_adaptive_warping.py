"""The pyramid warping rule (issue 15 item 6, docs/warping_rule.md): what holds and what does not."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import adaptive_warping as A
from aliasing import geometry, schemes, warping


def test_registered_rule_equals_the_full_geometry_evaluation():
    lv = geometry.lights("hemisphere:300")
    via_schemes = schemes.evaluate("pyramid", 1.0, 1000.0, 50.0, lv).S  # the azimuth comes from warping.CONTEXT
    np.testing.assert_allclose(via_schemes, A.evaluate("pyramid", 1.0, 1000.0, 50.0, lv), rtol=1e-12)
    assert "pyramid" in warping.WARPING_RULES


def test_eta_is_minus_one_along_the_view_and_the_plateau_outside_the_pyramid():
    fov = 60.0
    gamma = np.array([0.0, 180.0, 90.0, 60.0, 31.0])
    eta = A.eta_pyramid(geometry.light_direction(gamma, 0.0), fov)
    np.testing.assert_allclose(eta, [-1.0, -1.0, 0.0, 0.0, 0.0], atol=1e-12)  # tan 31° > tan 30°: outside
    # inside along the diagonal the light reaches the pyramid's edge only at tanγ = √2 tanθ
    edge = np.degrees(np.arctan(np.sqrt(2) * np.tan(np.radians(30.0))))
    assert A.eta_pyramid(geometry.light_direction(edge - 1.0, 45.0), fov)[0] < 0
    assert A.eta_pyramid(geometry.light_direction(edge + 1e-6, 45.0), fov, 1.0)[0] == pytest.approx(0.0, abs=1e-6)


def test_continuous_over_directions():
    # η and S have no jumps: η steps are Lipschitz-small on a 0.02° grid, across γ and azimuth;
    # S's steepest step shrinks when the grid is refined (a jump would not)
    g = np.arange(0.01, 90.0, 0.02)
    for az in (0.0, 20.0, 45.0):
        lv = geometry.light_direction(g, az)
        eta = A.eta_pyramid(lv, 50.0)
        assert np.max(np.abs(np.diff(eta))) < 0.01
        s = A.evaluate("pyramid", 1.0, 1000.0, 50.0, lv)
        steps = np.abs(np.diff(np.log(s)))
        i = int(np.argmax(steps))  # the steepest place (the kink at t = 1): refine it tenfold
        fine = A.evaluate("pyramid", 1.0, 1000.0, 50.0, geometry.light_direction(np.linspace(g[i], g[i + 1], 11), az))
        assert np.max(np.abs(np.diff(np.log(fine)))) < 0.2 * steps[i]  # a jump would not shrink
        assert steps[i] < 0.1  # per 0.02°; Sopt's own steepest step here is 0.035–0.042
    a = np.arange(0.0, 90.0, 0.02)
    eta = A.eta_pyramid(geometry.light_direction(25.0, a), 50.0)
    assert np.max(np.abs(np.diff(eta))) < 0.01


def test_goals_hold_from_f_over_n_100_up():
    # docs/warping_rule.md: f/n ≥ 100: max ≤ Standard's and mean within 10 % of Sopt's
    lv = geometry.lights("hemisphere:600")
    for fn, fov in ((100.0, 50.0), (1000.0, 80.0), (1e5, 50.0)):
        s = A.evaluate("pyramid", 1.0, fn, fov, lv)
        assert s.max() <= schemes.evaluate("Standard", 1.0, fn, fov, lv).S.max() * (1 + 1e-9)
        assert s.mean() <= 1.1 * schemes.evaluate("Sopt", 1.0, fn, fov, lv).S.mean()


def test_the_guard_is_what_holds_the_maximum_at_large_depth_ranges():
    # without the guard (η alone), lights just outside the pyramid (t ≈ 1.01) over-warp at
    # f/n = 1e5: η_opt ≈ −0.1 there, i.e. n′ ≈ 0.1 W_ly, which η = 0 cannot express
    from aliasing import directional

    lv = geometry.lights("hemisphere:2000")
    n_i, f_i = np.array([1.0]), np.array([1e5])
    lf = directional.fit(geometry.frustum_vertices(n_i, f_i, 50.0), lv)
    eta = A.eta_pyramid(lv, 50.0)[:, None]
    mx, mz = directional.vertex_errors(lf, 50.0, warping.n_prime_from_eta(eta, n_i, f_i, lf.depth))
    unguarded = (mx.max(-1) * mz.max(-1))[:, 0]
    standard = schemes.evaluate("Standard", 1.0, 1e5, 50.0, lv).S.max()
    assert unguarded.max() > 2 * standard
    u, w = A.image_position(lv, 50.0)
    assert 1.0 <= np.maximum(np.abs(u), np.abs(w))[np.argmax(unguarded)] < 1.05
    assert A.evaluate("pyramid", 1.0, 1e5, 50.0, lv).max() <= standard


def test_small_depth_range_exceeds_standard_slightly():
    # the documented shortfall: at f/n = 10, fov ≥ 50°, the maximum is 0.2–0.4 % above Standard's
    lv = geometry.lights("hemisphere:2000")
    ratio = A.evaluate("pyramid", 1.0, 10.0, 80.0, lv).max() / schemes.evaluate("Standard", 1.0, 10.0, 80.0, lv).S.max()
    assert 1.0 < ratio < 1.005


def test_grid_study_shapes_and_reference():
    r = A.grid_study(rules=("P", "pyramid-log"), f_over_n=(100.0,), fovs=(50.0,), light="hemisphere:200")
    assert r["max_ratio"].shape == (2, 1, 1)
    assert r["mean_ratio"][0, 0, 0] >= 1.0 - 1e-9  # nothing beats the S-optimal warp on average
    assert r["mean_ratio"][1, 0, 0] >= 1.0 - 1e-9


def test_validation():
    with pytest.raises(ValueError, match="eta_outside"):
        A.eta_pyramid([0.0, 1.0, 0.0], 60.0, eta_outside=2.0)
    with pytest.raises(ValueError, match="fov"):
        A.image_position([0.0, 1.0, 0.0], 190.0)
    with pytest.raises(ValueError, match="light"):
        A.image_position([0.0, 0.0, 0.0], 60.0)
