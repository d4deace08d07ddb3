"""Lloyd et al. 2006: derived expressions against the printed equations.

Each test names the equation.  Where the printed form is wrong (docs/ERRATA.md) the test
asserts that it differs, shows why, and checks the corrected form.
"""

from __future__ import annotations

import sympy as sp

from aliasing.symbolic import equivalent
from aliasing.symbolic import lloyd2006 as L

P = L.PRINTED
z, n, f, n_p, theta, x = L.z, L.n, L.f, L.n_p, L.theta, L.x
fp = n_p + f - n
zp = n_p + z - n


def test_eq7_m_x_equals_printed():
    assert equivalent(L.m_x(), P["eq7"].expr)


def test_eq8_m_z_equals_printed():
    assert equivalent(L.m_z(), P["eq8"].expr)


def test_m_z_minimum_at_n_prime_minus_n():
    # §4.1: "For z, the maximum error is at z = n for n′ > n′_LSPSM and at z = f below":
    # the only stationary point in z > 0 is a minimum at z = n′ − n.
    assert sp.simplify(L.m_z_minimum() - (n_p - n)) == 0


def test_n_prime_lispsm_equals_printed():
    assert equivalent(L.n_prime_lispsm(), P["n_lispsm"].expr)


def test_eq11_eta_map_equals_printed():
    assert equivalent(L.n_prime_of_eta(), P["eq11"].expr)


def test_appendix_b_m_z_is_linear_in_eta():
    # App. B defines η by interpolating M_z linearly; M_z(n′(η)) must be affine in η on each half.
    a, eta = L.a, L.eta
    mz = L.max_error_z().subs({L.res_i: 1, L.res_t: 1, f: a * n})
    for (npr_eta, _), (mz_branch, _) in zip(L.n_prime_of_eta().args, reversed(mz.args)):
        curve = sp.simplify(mz_branch.subs(n_p, npr_eta))
        assert sp.simplify(sp.diff(curve, eta, 2)) == 0


def test_eq12_storage_factor_equals_printed():
    assert equivalent(L.storage_factor(), P["eq12"].expr)


def test_eq13_14_budget_split_equals_printed():
    assert equivalent(L.budget_resolutions()[0], P["eq13"].expr[0])
    assert equivalent(L.budget_resolutions()[1], P["eq13"].expr[1])


def test_critical_storage_is_res_i_squared_times_storage_factor():
    # eq. 12: S* = res*_s res*_t = res_i² S̄, branch by branch
    rs, rt = L.critical_resolutions()
    for (rt_b, _), (s_b, _) in zip(rt.args, L.storage_factor().args):
        assert sp.simplify(rs * rt_b - L.res_i**2 * s_b) == 0


def test_appendix_c_log_map_and_optimal_storage_equal_printed():
    assert equivalent(L.log_parameterization(), P["appC_t"].expr)
    assert equivalent(L.storage_factor_optimal(), P["appC_S"].expr)


def test_appendix_a_projective_spacing_is_quadratic_in_z():
    spacing = L.projective_spacing()
    al, be, ga, de = sp.symbols("alpha beta gamma delta")
    c0 = de / ga
    assert sp.simplify(spacing / (z + c0) ** 2 - ga**2 / (al * de - be * ga)) == 0


# --- errata (docs/ERRATA.md) ---------------------------------------------------------


def test_E1_eq5_printed_s_does_not_map_frustum_to_unit_interval():
    # printed: s = x/(z′ tanθ′) + 1/2 with tanθ′ = (f′/f) tanθ; at the far corner
    # x = f tanθ, z′ = f′ it must give 1 but does not; the derived s does.
    printed = P["eq5"].expr.subs({L.z_p: fp, x: f * sp.tan(theta)})
    assert sp.simplify(printed - 1) != 0
    derived_s = L.shadow_map_coordinates()[0]
    assert sp.simplify(derived_s.subs({L.z_p: fp, x: f * sp.tan(theta)}) - 1) == 0
    assert sp.simplify(derived_s.subs({L.z_p: fp, x: -f * sp.tan(theta)})) == 0
    # ...and the derived s reproduces the printed eq. 7, the literal eq. 5 does not
    w_i = L.image_beam_width()
    m_x_literal = sp.simplify(1 / (L.res_s * sp.diff(P["eq5"].expr, x)) / w_i).subs(L.z_p, zp)
    assert not equivalent(m_x_literal, P["eq7"].expr)


def test_E2_eq6_sign_of_inverse_depth_term():
    # printed t(z′) at z′ = n′ is 2f′/(f′ − n′), not 0: the 1/z′ term needs a minus sign
    t_printed = P["eq6"].expr
    assert sp.simplify(t_printed.subs(L.z_p, n_p) - 2 * fp / (fp - n_p)) == 0
    t_derived = L.shadow_map_coordinates()[1]
    assert sp.simplify(t_derived.subs(L.z_p, n_p)) == 0
    assert sp.simplify(t_derived.subs(L.z_p, fp) - 1) == 0
    corrected = (fp + n_p) / (2 * (fp - n_p)) - fp * n_p / (L.z_p * (fp - n_p)) + sp.Rational(1, 2)
    assert equivalent(t_derived, corrected)
    # only the sign differs: |dt/dz′| is the same, so eqs. 7–8 are unaffected
    assert sp.simplify(sp.diff(t_printed, L.z_p) + sp.diff(t_derived, L.z_p)) == 0


def test_E3_eqs_9_10_follow_the_dimensionless_eq2_not_eqs_7_8():
    # printed eq. 9/10 differ from the maxima of printed eqs. 7/8 ...
    assert not equivalent(L.max_error_x(), P["eq9"].expr)
    assert not equivalent(L.max_error_z(), P["eq10"].expr)
    # ... agree at n = 1 (the paper's figures all use n = 1) ...
    assert equivalent(L.max_error_x().subs(n, 1), P["eq9"].expr.subs(n, 1))
    for (d, _), (p, _) in zip(L.max_error_z().args, P["eq10"].expr.args):
        assert sp.simplify((d - p).subs(n, 1)) == 0
    # ... and are exactly what the printed (dimensionless) eq. 2 produces.
    scale = sp.simplify(L.image_beam_width() / P["eq2"].expr)
    assert scale == n  # printed w_i = correct w_i / n
    assert equivalent(L.max_error_x() * scale, P["eq9"].expr)
    for (d, _), (p, _) in zip(L.max_error_z().args, P["eq10"].expr.args):
        assert sp.simplify(d * scale - p) == 0
    # the corrected forms are scale invariant (n, f, n′ → λn, λf, λn′), as M must be
    lam = sp.Symbol("lambda", positive=True)
    grow = {n: lam * n, f: lam * f, n_p: lam * n_p}
    assert sp.simplify(L.max_error_x().subs(grow, simultaneous=True) - L.max_error_x()) == 0
    assert sp.simplify(P["eq9"].expr.subs(grow, simultaneous=True) - P["eq9"].expr) != 0


def test_E3_storage_factor_is_consistent_only_with_corrected_maxima():
    # eq. 12 (correct as printed) = M_x M_z of the corrected eqs. 9–10, not of the printed ones
    unit = {L.res_i: 1, L.res_s: 1, L.res_t: 1}
    printed_product = (P["eq9"].expr * P["eq10"].expr.args[0][0]).subs(unit)
    assert sp.simplify(printed_product - P["eq12"].expr.args[0][0]) != 0
    assert equivalent(L.storage_factor(), P["eq12"].expr)
