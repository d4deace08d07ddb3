"""Zhang et al. 2006 (PSSM) split schemes and its misprints (docs/ERRATA.md P1–P5)."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import partitioning as P


def test_pssm_eq3_as_printed():
    # Zhang 2006 eq. 3: C_i = min(n + (f − n)/γ^(m−i) + δ_bias, f); n = 1, f = 800, m = 3, γ = 2, δ = 10
    np.testing.assert_allclose(P.split_distances("pssm", 1.0, 800.0, 3, ratio=2.0, bias=10.0), [1.0, 210.75, 410.5, 800.0])


def test_P2_eqs_1_2_imply_a_growing_bias():
    # eqs. 1–2: L_1 = (f − n)/γ^(m−1) + δ, L_(i+1) = γ L_i  ⇒  C_i = n + (f − n)γ^(i−m) + γ^(i−1) δ
    n, f, m, g, d = 1.0, 800.0, 3, 2.0, 10.0
    L1 = (f - n) / g ** (m - 1) + d
    from_eqs_1_2 = np.minimum(n + L1 * g ** np.arange(m), f)
    eq3 = P.split_distances("pssm", n, f, m, ratio=g, bias=d)[1:]
    assert from_eqs_1_2[1] == pytest.approx(420.5) and eq3[1] == pytest.approx(410.5)  # they differ unless δ = 0
    np.testing.assert_allclose(P.split_distances("pssm", n, f, m, ratio=g)[1:], np.minimum(n + (f - n) / g ** (m - 1) * g ** np.arange(m), f))


def test_P3_eq4_transition_holds_for_its_rule_and_fails_for_eq3():
    # E1 of a uniform map on [n_i, f_i] at depth z is (f_i − n_i)/z; eq. 4 wants E1^i/E1^(i+1) = λ at every plane
    def jumps(c):
        lengths = np.diff(c)
        return lengths[:-1] / lengths[1:]  # E1^i(C_i)/E1^(i+1)(C_i)

    np.testing.assert_allclose(jumps(P.split_distances("pssm-transition", 1.0, 800.0, 4, resolution_ratio=2.0)), 2.0, rtol=1e-12)
    # eq. 3's planes give ratios 1/(γ − 1) at C_1 and 1/γ beyond: no γ > 1 makes them all equal 2
    for g in np.linspace(1.05, 8.0, 200):
        r = jumps(P.split_distances("pssm", 1.0, 800.0, 4, ratio=g))
        assert not np.allclose(r, 2.0, rtol=1e-3)
    # the log-map rule: ln a_i = λ ln a_(i+1)
    c = P.split_distances("pssm-transition-log", 1.0, 800.0, 4, resolution_ratio=2.0)
    la = np.log(c[1:] / c[:-1])
    np.testing.assert_allclose(la[:-1] / la[1:], 2.0, rtol=1e-12)


def test_transition_rules_tend_to_uniform_and_log():
    np.testing.assert_allclose(P.split_distances("pssm-transition", 1.0, 800.0, 3, resolution_ratio=1 + 1e-9), P.split_distances("uniform", 1.0, 800.0, 3), rtol=1e-6)
    np.testing.assert_allclose(P.split_distances("pssm-transition-log", 1.0, 800.0, 3, resolution_ratio=1 + 1e-9), P.split_distances("log", 1.0, 800.0, 3), rtol=1e-6)


def test_P4_storage_bound_needs_both_axes_halved():
    # §3.5: Σ 2^(k−i) × 2^(k−i) ≤ (1/3) 4^k; with only u halved (the text's own remark) the sum tends to 4^k / 2
    k = 10
    both = sum(4.0 ** (k - i) for i in range(1, 40))
    u_only = sum(2.0 ** (k - i) * 2.0 ** (k - 1) for i in range(1, 40))
    assert both == pytest.approx(4.0**k / 3) and u_only == pytest.approx(4.0**k / 2)
    assert 512**2 + 256**2 + 128**2 == pytest.approx(0.328 * 1024**2, rel=1e-3)  # PSSM(3) with k = 10


def test_P5_eq6_clip_depth():
    # D3D post-projection depth f/(f − n)(1 − n/z): 0 at z = n, 1 at z = f; the printed (n − 1/C_i) agrees only at n = 1
    n, f = 2.0, 800.0
    correct = lambda z: f / (f - n) * (1 - n / z)  # noqa: E731
    printed = lambda z: f / (f - n) * (n - 1 / z)  # noqa: E731
    assert correct(n) == pytest.approx(0.0) and correct(f) == pytest.approx(1.0)
    assert printed(n) != pytest.approx(0.0)
    assert printed(f) != pytest.approx(1.0)
    # with n = 1 (the paper's experiments) the printed form is the correct one
    at_n1 = lambda form, z: form(z).__float__()  # noqa: E731
    n = 1.0
    assert at_n1(lambda z: f / (f - n) * (n - 1 / z), 37.0) == pytest.approx(at_n1(lambda z: f / (f - n) * (1 - n / z), 37.0), rel=1e-15)


@pytest.mark.parametrize(
    "kwargs, message",
    [({"ratio": 1.0}, r"ratio must be in \(1, inf\)"), ({"bias": -1.0}, r"bias must be in \[0, inf\]"), ({"bias": 1e6}, "bias too large")],
)
def test_pssm_bad_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        P.split_distances("pssm", 1.0, 800.0, 3, **kwargs)
