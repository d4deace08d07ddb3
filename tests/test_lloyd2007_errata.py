"""Lloyd et al. 2007 misprints that the warping rules depend on (docs/ERRATA.md L1–L3, L7, L8)."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import geometry, schemes, warping


def printed_eq79(gamma, theta, a, eta_b, eta_c, c_fraction=0.4):
    """Eq. 79 exactly as printed: 0 below γ_a, and 'η_c for γ < γ_c' as the last case."""
    ga, gb, gc = a * theta, theta, theta + c_fraction * (90 - theta)
    if gamma < ga:
        return 0.0
    if gamma < gb:
        return -1 + (eta_b + 1) * (gamma - ga) / (gb - ga)
    if gamma < gc:
        return eta_b + (eta_c - eta_b) * np.sin(np.pi / 2 * (gamma - gb) / (gc - gb))
    return eta_c  # printed condition "γ < γ_c" cannot hold here; the case is γ > γ_c


def test_L1_printed_eq79_jumps_at_gamma_a_corrected_is_continuous():
    theta = 30.0
    ga = theta / 2
    below, above = printed_eq79(ga - 1e-9, theta, 0.5, -0.2, 1.0), printed_eq79(ga + 1e-9, theta, 0.5, -0.2, 1.0)
    assert below == 0.0 and above == pytest.approx(-1.0, abs=1e-6)  # a jump of 1 in η
    eta = warping.shaping_eta(np.array([ga - 1e-9, ga + 1e-9]), 2 * theta, "logp")
    assert np.ptp(eta) < 1e-6
    # and −1 is the η of n′ = ∞, "a continuous transition to n′ = ∞" (§6.1.1)
    assert warping.n_prime_from_eta(-1.0, 1.0, 100.0) == np.inf


@pytest.mark.parametrize("shaping", ["p", "logp"])
def test_L1_L2_corrected_eq79_is_continuous_and_monotone(shaping):
    gamma = np.linspace(0.0, 90.0, 90001)
    eta = warping.shaping_eta(gamma, 60.0, shaping)
    assert np.all(np.diff(eta) >= -1e-15)
    assert np.max(np.abs(np.diff(eta))) < 1e-4  # no jumps on a 0.001° grid
    assert eta[0] == -1.0 and eta[-1] == warping.SHAPING[shaping].eta_c


def test_L3_both_gamma_c_readings_are_selectable():
    # eq. 79: γ_c = θ + 0.4(90° − θ) = 54°; App. B text: θ + 0.3(90° − θ) = 48° (θ = 30°)
    near = warping.warping_parameter("logp", 1.0, 1000.0, fov=60.0, gamma=50.0, c_fraction=0.4)
    far = warping.warping_parameter("logp", 1.0, 1000.0, fov=60.0, gamma=50.0, c_fraction=0.3)
    assert far == pytest.approx(1.0)  # η = η_c = 1 past γ_c = 48°: n′ = n_γ = n
    assert near > far


def test_L7_printed_eq120_is_discontinuous_corrected_equals_eq11():
    alpha, n_gamma = 1000.0, 1.0
    printed_pos = lambda eta: n_gamma * np.sqrt(alpha + 1) / (eta * np.sqrt(alpha + 1))  # as printed, η ≥ 0
    printed_neg = lambda eta: n_gamma * (np.sqrt(alpha + 1) - eta * (alpha - 1)) / (eta + 1)
    assert printed_pos(1e-9) / printed_neg(-1e-9) > 1e6  # the printed branches do not meet at η = 0
    eta = np.linspace(-0.99, 1.0, 199)
    # corrected eq. 120 with W_ly = f − n is Lloyd 2006 eq. 11
    np.testing.assert_allclose(warping.n_prime_from_eta(eta, 1.0, alpha, depth=alpha - 1), warping.n_prime_from_eta(eta, 1.0, alpha), rtol=1e-14)
    left, right = warping.n_prime_from_eta(np.array([-1e-12, 1e-12]), 1.0, alpha, depth=1234.5)
    assert left == pytest.approx(right, rel=1e-9)


def test_L8_literal_po_does_not_reproduce_table3():
    # §6.1.1 prints n′ = (n_e + √(n_e f_e))/sin γ; with it the maximum over directions far exceeds
    # Table 3's 3.65e6 (printed in the "P" row, see L5); n_γ(1 + √(f/n))/sin γ reproduces it
    lv = geometry.hemisphere_directions(4000)
    literal = schemes.evaluate("lispsm", 1.0, 1000.0, 60.0, lv).S.max()
    table = schemes.evaluate("Po", 1.0, 1000.0, 60.0, lv).S.max()
    assert literal > 4.5e6 and table < 3.66e6
