"""gmnpr.generalized_error for tiny λ (fuzz residue): F ~ 1/λ is finite down to λ ~ 1e-308, but
the former evaluation squared q/λ and returned inf below λ ≈ 1e-154.

References: a 40-digit evaluation of the sympy derivation of eq. 2 (Zhang et al. 2007), and the
former implementation, kept here verbatim, wherever it was finite.
"""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import gmnpr
from aliasing.gmnpr import _depths, _geometry
from aliasing.symbolic import zhang2007 as Z
from conftest import assert_close, exact

NEAR = np.array([1e-3, 1.0, 7.0]).reshape(-1, 1, 1, 1, 1)
FAR = NEAR * np.array([1.0 + 1e-6, 2.0, 100.0, 1e5]).reshape(1, -1, 1, 1, 1)
FOV = np.array([10.0, 60.0, 170.0]).reshape(1, 1, -1, 1, 1)
GAMMA = np.array([0.5, 20.0, 30.0, 45.0, 89.0, 90.0, 150.0]).reshape(1, 1, 1, -1, 1)
U = np.array([0.0, 0.3, 1.0]).reshape(1, 1, 1, 1, -1)  # the point's position between near and far


def _former(lam, near, far, fov, gamma, z):
    """generalized_error as it was before the rewrite (eq. 2 divided through by λ², r = 1/λ)."""
    zz, n, f = _depths(z, near, far)
    r = 1.0 / np.asarray(lam, float)
    g = _geometry(n, f, fov, gamma)
    q = np.where(g.regime1, (zz - g.n) * g.sin_t + g.n * g.tan_p * g.cos_t, zz * g.sin_t + g.f * np.sin(g.phi - g.theta) / np.cos(g.phi))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return (g.depth + q * r) ** 2 / ((1 + r) * g.tan_p * g.depth * g.sin_t * zz)


def test_same_values_as_before_where_they_were_finite():
    z = NEAR + U * (FAR - NEAR)
    lams = np.array([1e-150, 1e-40, 1e-6, 0.01, 0.3, 1.0, 40.0, 1e8, 1e150, np.inf]).reshape(-1, 1, 1, 1, 1, 1)
    new = gmnpr.generalized_error(lams, NEAR, FAR, FOV, GAMMA, z)
    with np.errstate(invalid="ignore"):
        old = _former(lams, NEAR, FAR, FOV, GAMMA, z)
    fine = np.isfinite(old)
    assert fine[1:].all()  # only λ = 1e-150 overflowed before (F ≈ 1e150 once q/λ > 1e154 is squared)
    np.testing.assert_array_equal(new[fine], old[fine])  # bit for bit: the former form is kept wherever it was finite


@pytest.mark.parametrize("lam", [1e-155, 1e-200, 1e-250, 1e-300, 1e-307])
def test_tiny_lambda_against_40_digit_eq2(lam):
    near, far = NEAR[..., 0], FAR[..., 0]  # one point per frustum: the middle of the view ray
    z = 0.5 * (near + far)
    theta = np.radians(np.minimum(GAMMA[..., 0], 180.0 - GAMMA[..., 0]))
    got = gmnpr.generalized_error(lam, near, far, FOV[..., 0], GAMMA[..., 0], z)
    with np.errstate(over="ignore"):
        want = exact(Z.generalized_error(), Z.lam, Z.n, Z.f, Z.phi, Z.theta, Z.z)(lam, near, far, np.radians(FOV[..., 0]) / 2, theta, z)
    finite = np.isfinite(want)  # F beyond 1.8e308 (λ = 1e-307 with a large f/n) is inf in both
    assert finite.mean() > 0.8
    assert np.isinf(got[~finite]).all()
    assert_close(got[finite], want[finite], rtol=1e-12)


def test_tiny_lambda_follows_the_1_over_lambda_asymptote():
    # λ·F → (q/D)²·D/(tanφ sinθ z) as λ → 0, with a relative correction O(λ D/q)
    z = NEAR + U * (FAR - NEAR)
    args = (NEAR, FAR, FOV, GAMMA, z)
    ref = 1e-200 * gmnpr.generalized_error(1e-200, *args)
    for lam in (1e-160, 1e-250, 1e-300):
        scaled = lam * gmnpr.generalized_error(lam, *args)
        assert np.isfinite(scaled).all()
        assert_close(scaled, ref, rtol=1e-13)
