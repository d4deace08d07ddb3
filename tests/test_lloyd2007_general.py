"""Lloyd et al. 2007 §3–5 and App. A: derived against printed, numeric against symbolic.

Each test names the equation.  Where the printed form is wrong (docs/ERRATA.md,
L9–L16) the test asserts that it differs and that the
corrected form holds.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy import optimize

from aliasing import logpsm
from aliasing.symbolic import equivalent
from aliasing.symbolic import lloyd2007 as L
from aliasing.symbolic import lloyd2007_jacobians as J

from conftest import assert_close, exact

P = L.PRINTED
y, y0, y1, a, b, theta, n, f, W_e = L.y, L.y0, L.y1, L.a, L.b, L.theta, L.n, L.f, L.W_e
c0, c1, c2 = L.c0_s, L.c1_s, L.c2_s
def _same(d, p):
    return sp.simplify(sp.expand_log(sp.sympify(d) - sp.sympify(p), force=True)) == 0


# --- §3.2: the general 2D aliasing error -------------------------------------------------


def test_eq19_point_light_chain_rule_equals_printed():
    g = L.configuration_2d()
    assert sp.cancel(sp.together(L.m_point_2d() / P["eq19"].expr.subs(g["subs"]))) == 1


def test_eq19_directional_light_equals_printed_limit():
    assert sp.cancel(sp.together(L.m_directional_2d() / P["eq19_dir"].expr.subs(L.directional_subs()))) == 1


def test_eqs20_24_intuitive_derivation_agrees_with_eq19():
    g = L.configuration_2d()
    assert sp.cancel(L.m_intuitive_2d() - L.m_point_2d()) == 0
    w_e, w_l = L.projected_widths()
    assert sp.cancel(sp.together(w_e / P["eq23"].expr.subs(g["subs"]))) == 1
    assert sp.cancel(sp.together(w_l / P["eq24"].expr.subs(g["subs"]))) == 1


def test_eq19_numeric_equals_symbolic():
    rng = np.random.default_rng(7)
    k = 25
    vals = dict(dG=rng.uniform(0.1, 3, k), Wl=rng.uniform(0.5, 4, k), We=rng.uniform(0.5, 4, k), ne=rng.uniform(0.1, 2, k), de=rng.uniform(1, 50, k),
                nl=rng.uniform(0.1, 2, k), dl=rng.uniform(1, 50, k), phl=rng.uniform(0, 80, k), phe=rng.uniform(0, 80, k), pse=rng.uniform(0, 80, k), psl=rng.uniform(0, 80, k))
    expr = P["eq19"].expr.subs({L.r_j: 1, L.r_t: 1})
    syms = [L.dGdt, L.W_l, L.W_e, L.n_e, L.d_e, L.n_l, L.d_l, L.cphi_l, L.cphi_e, L.cpsi_e, L.cpsi_l]
    cosd = lambda q: np.cos(np.radians(q))  # noqa: E731
    ref = exact(expr, *syms)(vals["dG"], vals["Wl"], vals["We"], vals["ne"], vals["de"], vals["nl"], vals["dl"], cosd(vals["phl"]), cosd(vals["phe"]), cosd(vals["pse"]), cosd(vals["psl"]))
    got = logpsm.aliasing_error(vals["dG"], vals["Wl"], vals["We"], vals["ne"], vals["de"], vals["phl"], vals["phe"], vals["pse"], vals["psl"], n_l=vals["nl"], d_l=vals["dl"])
    assert_close(got, ref)


# --- §3.3: factorisation (eqs. 27–31) ---------------------------------------------------


def test_eqs27_30_delta_e_factorises_into_perspective_and_projection_factors():
    g = L.configuration_2d()
    # eq. 27: m = (Δv)_l/(Δv)_e = (δ_l/r_t)/(δ_e/r_j), δ_l = dG/dt (eq. 28)
    assert sp.cancel(L.r_j * L.dGdt / (L.r_t * L.delta_e()) - L.m_point_2d()) == 0
    # eqs. 29–30: δ_e = δ̃_e cosψ_l/cosψ_e
    assert sp.cancel(sp.together(L.delta_e() / P["eq29"].expr.subs(g["subs"]))) == 1


def test_L9_eq31_perspective_error_is_w_l_over_w_e_not_w_e_over_w_l():
    g = L.configuration_2d()
    m_tilde = (L.r_j * L.dGdt / (L.r_t * P["eq30"].expr)).subs(g["subs"])
    w_e_proj, w_l_proj = L.projected_widths()
    # beam widths: the projected widths times cosψ (eqs. 22–23 and their light analogue)
    w_e = w_e_proj * g["subs"][L.cpsi_e]
    w_l = w_l_proj * g["subs"][L.cpsi_l]
    assert sp.cancel(sp.together(m_tilde / (w_l / w_e))) == 1  # corrected
    assert sp.cancel(sp.together(m_tilde / (w_e / w_l))) != 1  # printed
    # and m̃ is m with the projection factor removed: m̃ = m cosψ_l/cosψ_e
    assert sp.cancel(sp.together(m_tilde / (L.m_point_2d() * g["subs"][L.cpsi_l] / g["subs"][L.cpsi_e]))) == 1


def test_perspective_factor_numeric_equals_eq30():
    ref = exact(P["eq30"].expr, L.W_l, L.W_e, L.n_e, L.d_e, L.n_l, L.d_l, L.cphi_e, L.cphi_l)
    Wl, We, ne, de, nl, dl, pe, pl = 2.0, 1.5, 0.3, np.linspace(1, 40, 9), 0.7, np.linspace(3, 5, 9), 20.0, np.linspace(0, 70, 9)
    got = logpsm.perspective_factor(Wl, We, ne, de, pl, pe, n_l=nl, d_l=dl)
    assert_close(got, ref(Wl, We, ne, de, nl, dl, np.cos(np.radians(pe)), np.cos(np.radians(pl))))


# --- §4.1: parameterization from a spacing function (eqs. 41–43) -------------------------


def test_eqs41_43_F_from_spacing_inverts_and_normalises():
    F, rho = L.F_from_spacing()
    assert F.subs(L.v, 0).doit() == 0
    assert sp.simplify(F.subs(L.v, 1) - 1) == 0
    assert sp.simplify(1 / sp.diff(F, L.v) - rho * L.delta(L.v)) == 0  # (dF/dv)⁻¹ = ρδ
    # a concrete spacing: δ = 1 + v gives F = log(1 + v)/log 2 and ρ = log 2
    F2, rho2 = L.F_from_spacing(1 + L.v)
    assert _same(F2, sp.log(1 + L.v) / sp.log(2)) and _same(rho2, sp.log(2))
    # eq. 47: with δ_l = (dF_b/dv)⁻¹ = ρ_b δ_b, δ_l/δ_b = ρ_b everywhere: R = ρ_b
    assert sp.simplify((1 / sp.diff(F, L.v)) / L.delta(L.v) - rho) == 0


# --- §4.3: B(μ) along a light ray (eqs. 50–54) ------------------------------------------


def test_L10_eq53_sign():
    derived = L.dB_dmu()
    assert sp.simplify(derived + P["eq53"].expr) == 0  # printed is the negative
    assert sp.simplify(derived - P["eq53"].expr) != 0
    # eq. 54 follows the derived sign: with ẑ_l·v̂_l < 0, dB/dμ has the sign of ẑ_e·(l − e)
    pos = {L.c: 1, theta: sp.pi / 6, L.zl_v: -sp.Rational(1, 2), L.mu: 3}
    assert derived.subs({**pos, L.ze_l: 1}) > 0  # B increases: minimum at μ0 (eq. 54, first case)
    assert derived.subs({**pos, L.ze_l: -1}) < 0  # minimum at μ1
    assert P["eq53"].expr.subs({**pos, L.ze_l: 1}) < 0  # printed would put it at μ1


def test_eq54_minimum_at_entry_face_for_light_behind_viewer_numeric():
    # eye at the origin looking along −z, light behind it at z = 10 shining along −z
    mu = np.linspace(10.5, 30.0, 200)  # inside the frustum: eye depth d_e = μ − 10 ∈ [0.5, 20]
    B = (mu - 10.0) / mu  # d_e/d_l, eqs. 50–52 with ẑe·v̂l = −1, ẑe·(l − e) = 10, ẑl·v̂l = −1
    assert np.argmin(B) == 0  # μ0: ẑ_e·(l − e) = 10 > 0


# --- §4.4: δ_b on end and side faces (eqs. 57–69) ---------------------------------------


def test_eqs57_62_delta_b_equal_printed():
    assert _same(L.delta_b_end(), P["eq58"].expr)
    assert _same(L.delta_b_side_s(), P["eq61"].expr)
    assert _same(L.delta_b_side_t(), P["eq62"].expr)
    assert _same(L.cos_phi(y, L.l_y), P["eq57"].expr)


def test_eq66_zeta_end_is_antiderivative():
    integrand, var = L.zeta_integrands()["end"]
    assert sp.simplify(sp.diff(P["eq66"].expr, var) - integrand) == 0
    # second form of the constant: y1 − y0 = W_e d_e/n_e on an end face
    assert _same(P["C_end_2"].expr, (1 / ((y1 - y0) * sp.cos(theta))).subs(y1, y0 + W_e * L.d_e / L.n_e))


def test_L12_eq67_constant_misses_y1():
    integrand, var = L.zeta_integrands()["side_s"]
    printed = P["eq67"].expr
    ratio = sp.simplify(integrand / sp.diff(printed, var))
    assert ratio == y1  # the printed ζ is the antiderivative divided by y1
    corrected = printed * y1  # C_b,s = y0/(W_e cosθ)
    assert sp.simplify(sp.diff(corrected, var) - integrand) == 0
    # hence printed ρ_b,s = ζ|u0..u1 → 1/(y1 cosθ) overhead, not eq. 88's 1/cosθ
    u0, u1 = L.u_range_side()
    xs = lambda uu: L.x_of_u.subs(L.u, uu)  # noqa: E731
    rho_printed = sp.limit((printed.subs(L.x, xs(u1)) - printed.subs(L.x, xs(u0))).subs(L.l_x, 0), L.l_z, sp.oo)
    assert sp.simplify(rho_printed - 1 / (y1 * sp.cos(theta))) == 0
    assert sp.simplify(rho_printed * y1 - P["eq88"].expr) == 0
    # the second printed form n/(W_e f cosθ) equals the first (both miss y1): y0/y1 = n/f
    sf = L.side_face()
    assert sp.simplify((1 / ((L.x1_of(y1) - L.x0_of(y1)) * sp.cos(theta))).subs({y0: sf["y0"], y1: sf["y1"]}) - P["C_s_2"].expr) == 0


def test_eq68_zeta_side_t_is_antiderivative():
    integrand, var = L.zeta_integrands()["side_t"]
    d = sp.diff(P["eq68"].expr, var) - integrand
    # exact check at random rational points (the sqrt terms defeat a blind simplify)
    rng = np.random.default_rng(3)
    for _ in range(6):
        pt = {y0: sp.Rational(int(rng.integers(1, 9)), 3), y: sp.Rational(int(rng.integers(10, 90)), 7), L.l_y: sp.Rational(int(rng.integers(-50, 50)), 11),
              L.l_z: sp.Rational(int(rng.integers(1, 40)), 13), y1: 40, W_e: sp.Rational(3, 2), theta: sp.pi / 5}
        assert abs(sp.N(d.subs(pt), 50)) < 1e-40
    sf = L.side_face()
    assert sp.simplify((y0 / (W_e * sp.cos(theta))).subs(y0, sf["y0"]) - P["C_t_2"].expr.subs(W_e, W_e)) == 0


def test_eq69_u_range_equals_printed():
    assert L.u_range_side() == P["eq69"].expr or all(sp.simplify(d - p) == 0 for d, p in zip(L.u_range_side(), P["eq69"].expr))


def test_eqs87_89_R_bound_equal_printed():
    r_end, r_s, r_t = L.R_bound()
    assert _same(r_end, P["eq87"].expr) and _same(r_s, P["eq88"].expr)
    for form in P["eq89"].expr:
        target = form if form.has(y0) else form
        assert _same(L.to_frustum(r_t), L.to_frustum(target))


# --- §5: parameterizations and spacings (eqs. 74–110, 84) ---------------------------------


def test_eqs75_76_F_p_maps_face_to_unit_square():
    s, tt = L.F_p()
    assert sp.simplify(tt.subs(y, y0)) == 0 and sp.simplify(tt.subs(y, y1) - 1) == 0
    assert sp.simplify(s.subs({y: y1, L.x: L.x0_of(y1)})) == 0
    assert sp.simplify(s.subs({y: y1, L.x: L.x1_of(y1)}) - 1) == 0


def test_eq77_log_equals_printed():
    assert _same(L.F_log(), P["eq77"].expr)


def test_eq96_spacing_p_s_equals_printed():
    ds = L.spacing_p()[0]
    assert _same(ds, P["eq96"].expr[0]) and _same(ds, P["eq96"].expr[1])


def test_L13_eq97_first_form_has_p2_for_p3():
    dt = L.spacing_p()[1]
    assert _same(dt, P["eq97"].expr[1])  # second form right
    assert not _same(dt, P["eq97"].expr[0])  # first form wrong
    assert _same(dt, -((y + a) ** 2) / (L.p3 * (y1 - y0)))  # with p3


def test_eq102_spacing_log_equals_printed():
    assert _same(L.spacing_log(), P["eq102"].expr)


def test_L14_eq104_and_eq109_sign():
    assert _same(L.spacing_lp_general(), -P["eq104"].expr)
    assert not _same(L.spacing_lp_general(), P["eq104"].expr)
    assert _same(L.spacing_lp(), -P["eq109"].expr)
    # the derived δ is positive on the face; the printed one negative (a = 0, b = 2y1 and b = y0/2)
    k = L.lp_constants()
    for bval in (2 * y1, y0 / 2):
        pt = {y0: 1, y1: 10, y: 3, a: 0, b: bval}
        d = L.spacing_lp().subs(c0, k[c0]).subs(pt).subs(pt)
        assert sp.N(d) > 0 and sp.N(P["eq109"].expr.subs(c0, k[c0]).subs(pt).subs(pt)) < 0


def test_eq105_roots_equal_printed():
    roots = [r for r in sp.solve(sp.numer(sp.together(L.spacing_lp_general())), y)]
    assert any(sp.simplify(r - P["eq105"].expr[1]) == 0 for r in roots)
    assert sp.simplify(L.spacing_lp_general().subs(y, -a)) == 0


def test_eqs107_108_110_constants_equal_printed():
    k = L.lp_constants()
    assert sp.simplify(k[c1] - P["eq107"].expr) == 0
    assert sp.simplify(k[c2] - P["eq108"].expr) == 0 and k[c2] == 1
    assert _same(k[c0], P["eq110"].expr)
    F = L.F_lp_t()
    assert sp.simplify(F.subs(y, y0)) == 0 and sp.simplify(F.subs(y, y1) - 1) == 0


def test_eq78_constants_are_the_b_to_infinity_limit():
    k = L.lp_constants_b_inf()
    c0p, c1p, c2p = P["eq78"].expr
    assert _same(k[c0], c0p) and sp.simplify(k[c1] - c1p) == 0 and k[c2] == c2p
    first = P["eq78_c12_first"].expr
    assert sp.simplify(first[0] - c1p) == 0 and sp.simplify(first[1] - c2p) == 0
    # and F_lp,t → F_log, δ_lp,t → δ_log,t
    Flp = c0 * sp.log(c1 * L.F_p()[1] + c2)
    assert _same(Flp.subs({c0: c0p, c1: c1p, c2: c2p}), L.F_log())
    lim = sp.limit(L.spacing_lp().subs(c0, L.lp_constants()[c0]), b, sp.oo)
    assert _same(lim, L.spacing_log())


def test_L15_eq84_is_not_the_inverse_of_eq78():
    k = L.lp_constants_b_inf()
    v_of_t, p_of_t = L.F_lp_inverse()
    v_inf = sp.limit(v_of_t, b, sp.oo)
    # derived inverse: F_lp,t(y(v(t))) = t
    Fv = L.F_log().subs(y, L.y_of_v.subs(L.v, v_inf))
    assert sp.simplify(sp.expand_log(Fv, force=True) - L.t) == 0
    printed = P["eq84"].expr.subs(k)
    assert sp.simplify(printed - v_inf) != 0
    assert sp.simplify(printed.subs(L.t, 0) + y0 / (y1 - y0)) == 0  # v(0) = −y0/(y1 − y0), not 0
    # printed equals the inverse of t = c0 log(c1 y(v) + c2), i.e. with y(v) in place of F_p,t ...
    vv = sp.solve(sp.Eq(c0 * sp.log(c1 * L.y_of_v + c2), L.t), L.v)[0]
    assert sp.simplify(vv - P["eq84"].expr) == 0
    # ... which is the inverse w.r.t. the perspective coordinate p only when y0 = 0, y1 = 1
    assert sp.simplify(P["eq84"].expr.subs({y0: 0, y1: 1}) - p_of_t) == 0


# --- App. A: closed forms (eqs. 87–103) -----------------------------------------------------


def test_eqs93_95_uniform_equal_printed():
    r_end, r_s, r_t = L.R_uniform()
    assert _same(r_end, P["eq93"].expr)
    for form in P["eq94"].expr:
        assert _same(L.to_frustum(r_s), L.to_frustum(form))
    for form in P["eq95"].expr:
        assert _same(L.to_frustum(r_t), L.to_frustum(form))


def test_eq99_and_lispsm_parameter():
    assert _same(L.R_perspective()[0], P["eq99"].expr)
    assert sp.simplify(L.a_lispsm_side() - sp.sqrt(y0 * y1)) == 0


def test_L16_eq100_eq101_later_forms_off_by_cos_theta():
    _, r_t, s_min = L.R_perspective()
    e100, e101 = P["eq100"].expr, P["eq101"].expr
    assert _same(L.to_frustum(r_t), L.to_frustum(e100[0]))  # first form right
    assert _same(L.to_frustum(s_min), L.to_frustum(e101[0]))
    corr100 = (f / n - 1) / (sp.sin(2 * theta) * sp.sqrt(f / n))
    corr101 = (f / n - 1) / (sp.sin(2 * theta) * sp.cos(theta))
    assert _same(L.to_frustum(r_t), corr100) and _same(L.to_frustum(s_min), corr101)
    for wrong in (e100[1], e100[2]):
        assert sp.simplify(wrong / corr100 - 1 / sp.cos(theta)) == 0  # one cosθ too many
    for wrong in (e101[1], e101[2]):
        assert sp.simplify(wrong / corr101 - sp.cos(theta)) == 0  # one cosθ too few


def test_eq103_log_equals_printed():
    for form in P["eq103"].expr:
        assert _same(L.to_frustum(L.R_log()), L.to_frustum(form))


# --- numeric == symbolic ----------------------------------------------------------------------

NEAR = np.array([0.1, 1.0, 3.0]).reshape(-1, 1, 1, 1)
RATIO = np.array([1.5, 10.0, 1000.0]).reshape(1, -1, 1, 1)
FOV = np.array([10.0, 60.0, 120.0]).reshape(1, 1, -1, 1)
V = np.linspace(0.0, 1.0, 5).reshape(1, 1, 1, -1)


def _frame(expr):
    sf = L.side_face()
    return expr.subs({y0: sf["y0"], y1: sf["y1"], W_e: sf["W_e"]})


def _with_v(expr):
    return _frame(expr.subs(y, L.y_of_v))


def test_delta_bound_numeric_equals_symbolic():
    far = NEAR * RATIO
    th = np.radians(FOV) / 2
    ly, lz = 0.7, 2.5
    ref_t = exact(_with_v(L.delta_b_side_t()), n, f, theta, L.v, L.l_y, L.l_z)
    assert_close(logpsm.delta_bound_side_t(V, NEAR, far, FOV, ly=ly, lz=lz), ref_t(NEAR, far, th, V, ly, lz))
    ref_s = exact(_frame(L.delta_b_side_s().subs({y: L.y_of_v, L.x: L.x_of_u})), n, f, theta, L.u, L.v, L.l_x, L.l_z)
    assert_close(logpsm.delta_bound_side_s(0.3, V, NEAR, far, FOV, lx=-0.4, lz=lz), ref_s(NEAR, far, th, 0.3, V, -0.4, lz))
    # end face (far): y(v) = W_e f/n (v − 1/2)
    end = L.delta_b_end().subs(y, L.W_e * f / n * (L.v - sp.Rational(1, 2))).subs(W_e, L.side_face()["W_e"])
    assert_close(logpsm.delta_bound_end(V, NEAR, far, FOV, ly=ly, lz=lz), exact(end, n, f, theta, L.v, L.l_y, L.l_z)(NEAR, far, th, V, ly, lz))


@pytest.mark.parametrize("kind", ["perspective_t", "log_t", "logp_t", "perspective_s"])
def test_spacing_numeric_equals_symbolic(kind):
    far = NEAR * RATIO
    th = np.radians(FOV) / 2
    aval = 0.37
    if kind == "perspective_s":
        expr = L.spacing_p()[0]
    elif kind == "perspective_t":
        expr = L.spacing_p()[1]
    elif kind == "log_t":
        expr = L.spacing_log()
    else:
        expr = L.spacing_lp().subs(c0, L.lp_constants()[c0])
    bval = 2.9
    ref = exact(_with_v(expr), n, f, theta, L.v, a, b)(NEAR, far, th, V, aval, bval)
    assert_close(logpsm.spacing(kind, V, NEAR, far, FOV, a=aval, b=bval), ref)


def test_parameterizations_and_inverse_numeric_equal_symbolic():
    far = NEAR * RATIO
    th = np.radians(FOV) / 2
    aval, bval = 0.37, 2.9
    ref = exact(_with_v(L.F_lp_t()), n, f, theta, L.v, a, b)(NEAR, far, th, V, aval, bval)
    assert_close(logpsm.parameterization("logp_t", V, NEAR, far, FOV, a=aval, b=bval), ref, atol=1e-15)
    ref_log = exact(_with_v(L.F_log()), n, f, theta, L.v, a)(NEAR, far, th, V, aval)
    assert_close(logpsm.parameterization("logp_t", V, NEAR, far, FOV, a=aval), ref_log, atol=1e-15)
    assert_close(logpsm.parameterization("log_t", V, NEAR, far, FOV, a=aval), ref_log, atol=1e-15)
    ref_p = exact(_with_v(L.F_p()[1]), n, f, theta, L.v, a)(NEAR, far, th, V, aval)
    assert_close(logpsm.parameterization("perspective_t", V, NEAR, far, FOV, a=aval), ref_p, atol=1e-15)
    tt = np.linspace(0, 1, 5).reshape(1, 1, 1, -1)
    v_of_t = L.F_lp_inverse()[0]
    ref_inv = exact(_frame(v_of_t), n, f, theta, L.t, a, b)(NEAR, far, th, tt, aval, bval)
    assert_close(logpsm.logp_inverse(tt, NEAR, far, FOV, a=aval, b=bval), ref_inv, rtol=1e-12, atol=1e-13)
    # round trip, both forms
    for bb in (bval, np.inf):
        t_of_v = logpsm.parameterization("logp_t", V, NEAR, far, FOV, a=aval, b=bb)
        assert_close(logpsm.logp_inverse(t_of_v, NEAR, far, FOV, a=aval, b=bb), V + 0 * t_of_v, rtol=1e-9, atol=1e-9)


def test_zeta_bound_numeric_is_antiderivative_of_inverse_delta_b():
    from scipy import integrate

    near, far, fov, lx, ly, lz = 1.0, 50.0, 70.0, 0.3, 12.0, 4.0
    y0_, y1_, We_, _ = logpsm.side_face(near, far, fov)
    for kind, inv in (
        ("end", lambda q: 1 / logpsm.delta_bound_end(q, near, far, fov, ly=ly, lz=lz)),
        ("side_t", lambda q: 1 / logpsm.delta_bound_side_t(q, near, far, fov, ly=ly, lz=lz)),
        ("side_s", lambda q: 1 / logpsm.delta_bound_side_s(q, 0.4, near, far, fov, lx=lx, lz=lz)),
    ):
        zeta = lambda q: logpsm.zeta_bound(kind, q, near, far, fov, lx=lx, ly=ly, lz=lz, v=0.4)  # noqa: E731
        num, _ = integrate.quad(lambda q: float(inv(q)), 0.1, 0.9, epsabs=0, epsrel=1e-13, limit=200)
        assert float(zeta(0.9) - zeta(0.1)) == pytest.approx(num, rel=1e-10)


# --- closed forms vs numeric maximisation; Table 2 orders -----------------------------------


@pytest.mark.parametrize("ratio", [2.0, 30.0, 1000.0])
@pytest.mark.parametrize("fov", [20.0, 60.0, 100.0])
def test_closed_form_factors_match_numeric_maximisation(ratio, fov):
    near, far = 1.0, ratio
    cf = logpsm.critical_factors(near, far, fov)
    y0_, y1_, _, _ = logpsm.side_face(near, far, fov)

    def worst(kind_spacing, bound, aval):
        res = optimize.minimize_scalar(lambda q: -float(logpsm.spacing(kind_spacing, q, near, far, fov, a=aval) / bound(q)), bounds=(0, 1), method="bounded", options={"xatol": 1e-12})
        return max(-res.fun, *(float(logpsm.spacing(kind_spacing, e, near, far, fov, a=aval) / bound(e)) for e in (0.0, 1.0)))

    bt = lambda q: logpsm.delta_bound_side_t(q, near, far, fov)  # noqa: E731
    bs = lambda q: logpsm.delta_bound_side_s(0.5, q, near, far, fov)  # noqa: E731
    assert worst("uniform", bt, 0.0) == pytest.approx(float(cf["uniform_t_side"]), rel=1e-10)
    assert worst("uniform", bs, 0.0) == pytest.approx(float(cf["uniform_s_side"]), rel=1e-10)
    assert worst("log_t", bt, 0.0) == pytest.approx(float(cf["log_t_side"]), rel=1e-10)
    assert worst("perspective_s", bs, 0.0) == pytest.approx(float(cf["perspective_s_side"]), rel=1e-10)
    # perspective in t: minimise over a the maximum over v
    best_t = optimize.minimize_scalar(lambda la: worst("perspective_t", bt, np.exp(la)), bounds=(np.log(y0_) - 8, np.log(y1_) + 3), method="bounded", options={"xatol": 1e-10})
    assert best_t.fun == pytest.approx(float(cf["perspective_t_side"]), rel=1e-7)
    assert np.exp(best_t.x) == pytest.approx(np.sqrt(y0_ * y1_), rel=1e-3)
    # S_p = R_s R_t with a common a: minimal and constant on [0, √(y0 y1)]
    S = lambda aval: worst("perspective_s", bs, aval) * worst("perspective_t", bt, aval)  # noqa: E731
    for aval in (0.0, 0.5 * np.sqrt(y0_ * y1_), np.sqrt(y0_ * y1_)):
        assert S(aval) == pytest.approx(float(cf["perspective_S_side"]), rel=1e-9)
    assert S(3 * np.sqrt(y0_ * y1_)) > float(cf["perspective_S_side"])
    # log: a = 0 is optimal
    assert worst("log_t", bt, 0.5) > worst("log_t", bt, 0.0)
    # error bound: R_b = ρ_b (numeric quadrature of 1/δ_b), eqs. 87–89
    from scipy import integrate

    rho_t, _ = integrate.quad(lambda q: 1 / float(bt(q)), 0, 1, epsrel=1e-13)
    assert rho_t == pytest.approx(float(cf["bound_t_side"]), rel=1e-10)
    assert critical_numeric("logp", "t", near, far, fov) == pytest.approx(float(cf["log_t_side"]), rel=1e-12)


def critical_numeric(kind, direction, near, far, fov):
    return float(logpsm.critical_factor_side(kind, direction, near, far, fov))


def test_table2_orders_by_fitting_growth_over_f_over_n():
    r = np.logspace(3, 7, 9)
    cf = logpsm.critical_factors(1.0, r, 60.0)

    def slope(vals, x):
        return np.polyfit(np.log(x), np.log(vals), 1)[0]

    # power laws: uniform R_s, R_t ~ (f/n)¹, S ~ (f/n)²; perspective R_t ~ √, S ~ (f/n)¹; bound/perspective R_s ~ 1
    assert slope(cf["uniform_s_side"], r) == pytest.approx(1.0, abs=1e-3)
    assert slope(cf["uniform_t_side"], r) == pytest.approx(1.0, abs=1e-3)
    assert slope(cf["uniform_s_side"] * cf["uniform_t_side"], r) == pytest.approx(2.0, abs=1e-3)
    assert slope(cf["perspective_t_side"], r) == pytest.approx(0.5, abs=1e-3)
    assert slope(cf["perspective_S_side"], r) == pytest.approx(1.0, abs=1e-3)
    assert np.ptp(cf["perspective_s_side"]) == 0 and np.ptp(cf["bound_s_side"]) == 0 and np.ptp(cf["bound_t_end"]) == 0
    # logarithmic: linear in log(f/n) (slope 1 against log r, zero intercept), bound and log alike
    for key in ("bound_t_side", "log_t_side"):
        k, c = np.polyfit(np.log(r), cf[key], 1)
        assert c == pytest.approx(0.0, abs=1e-9) and k == pytest.approx(1 / np.sin(np.radians(60.0)), rel=1e-12)
    # S^side of bound/log: R_s O(1) × R_t O(log)
    S_log = cf["perspective_s_side"] * cf["log_t_side"]
    assert np.polyfit(np.log(r), S_log, 1)[1] == pytest.approx(0.0, abs=1e-9)
    # and the numeric maxima show the same growth
    num = np.array([critical_numeric("perspective", "t", 1.0, rr, 60.0) for rr in r])  # a = 0: R_t ~ f/n
    assert slope(num, r) == pytest.approx(1.0, abs=1e-3)
    # vectorised over f/n, the sampled maxima equal the closed forms where the max is at an end
    assert_close(logpsm.critical_factor_side("uniform", "t", 1.0, r, 60.0), cf["uniform_t_side"])
    assert_close(logpsm.critical_factor_side("logp", "t", 1.0, r, 60.0), cf["log_t_side"])
    assert_close(logpsm.critical_factor_side("perspective", "s", 1.0, r, 60.0), cf["perspective_s_side"])
    assert_close(logpsm.critical_factor_side("perspective", "t", 1.0, r, 60.0, a=np.sqrt(r) / np.cos(np.radians(30.0))), cf["perspective_t_side"])


def test_closed_forms_numeric_equal_symbolic():
    far = NEAR * RATIO
    th = np.radians(FOV) / 2
    cf = logpsm.critical_factors(NEAR, far, FOV)
    r_end, r_s, r_t = L.R_bound()
    u_end, u_s, u_t = L.R_uniform()
    p_s, p_t, p_S = L.R_perspective()
    for key, expr in (("bound_t_end", r_end), ("bound_s_side", r_s), ("bound_t_side", r_t), ("uniform_t_end", u_end), ("uniform_s_side", u_s),
                      ("uniform_t_side", u_t), ("perspective_s_side", p_s), ("perspective_t_side", p_t), ("perspective_S_side", p_S), ("log_t_side", L.R_log())):
        assert_close(cf[key], exact(L.to_frustum(expr), n, f, theta)(NEAR, far, th))


# --- validation -----------------------------------------------------------------------------


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: logpsm.spacing("log_t", 1.5, 1.0, 10.0, 60.0), "v must be in [0, 1]"),
        (lambda: logpsm.spacing("log_t", 0.5, 1.0, 10.0, 200.0), "fov"),
        (lambda: logpsm.spacing("log_t", 0.5, 10.0, 1.0, 60.0), "far must be greater than near"),
        (lambda: logpsm.spacing("nope", 0.5, 1.0, 10.0, 60.0), "unknown kind"),
        (lambda: logpsm.spacing("logp_t", 0.5, 1.0, 10.0, 60.0, a=1.0, b=1.0), "b must differ from a"),
        (lambda: logpsm.parameterization("perspective_t", 0.5, 1.0, 10.0, 60.0, a=-1.0), "a must be in [0, inf]"),
        (lambda: logpsm.delta_bound_side_t(0.5, 1.0, 10.0, 60.0, lz=-1.0), "lz must be in (0, inf]"),
        (lambda: logpsm.aliasing_error(1, 1, 1, 1, 1, 95.0, 0, 0, 0), "phi_l must be in [0, 90)"),
        (lambda: logpsm.zeta_bound("end", 0.5, 1.0, 10.0, 60.0, lz=np.inf), "lz must be finite, got inf"),
    ],
)
def test_validation_names_parameter_and_range(call, word):
    with pytest.raises(ValueError, match=None) as err:
        call()
    assert word in str(err.value)


# --- eqs. 8, 9, 26: projection Jacobians ----------------------------------------------------


def test_eqs8_9_jacobians_equal_printed():
    pj = J.printed_jacobians()
    assert sp.simplify(J.jacobian_eye() - pj["eq8"]) == sp.zeros(2, 2)
    assert sp.simplify(J.jacobian_light() - pj["eq9"]) == sp.zeros(2, 2)


def test_L11_eq26_directional_jacobian_lost_its_outer_product():
    pj = J.printed_jacobians()
    assert sp.simplify(J.jacobian_directional() - pj["eq26_corrected"]) == sp.zeros(2, 2)
    assert sp.simplify(J.jacobian_directional() - pj["eq26"]) != sp.zeros(2, 2)
    # the corrected Jacobian sends the light direction to 0 (points along a ray share p)
    nh, X, ell, _, _ = J._plane_2d()
    assert sp.simplify(J.jacobian_directional() * ell) == sp.zeros(2, 1)
    assert sp.simplify(pj["eq26"] * ell) != sp.zeros(2, 1)


def test_eqs63_65_72_rho_bound_is_largest_for_the_overhead_light():
    # App. A / §5.1: R_b is maximal for the directional light straight above the face (eqs. 72–73),
    # where it takes the closed forms of eqs. 87–89.
    near, far, fov = 1.0, 1000.0, 90.0
    cf = logpsm.critical_factors(near, far, fov)
    y0_, y1_, _, _ = logpsm.side_face(near, far, fov)
    ly = np.linspace(-2 * y1_, 3 * y1_, 41).reshape(-1, 1)
    lz = np.array([0.1, 0.5, 1.0, 10.0, 1e3]).reshape(1, -1) * (y1_ - y0_)
    r_t = logpsm.rho_bound("side_t", near, far, fov, ly=ly, lz=lz)
    assert np.all(r_t <= cf["bound_t_side"] * (1 + 1e-12)) and np.all(r_t > 0)
    r_end = logpsm.rho_bound("end", near, far, fov, ly=ly, lz=lz)
    assert np.all(r_end <= cf["bound_t_end"] * (1 + 1e-12))
    vv = np.linspace(0, 1, 11).reshape(-1, 1, 1)
    r_s = logpsm.rho_bound("side_s", near, far, fov, lx=ly / 10, lz=lz, v=vv).max(axis=0)
    assert np.all(r_s <= cf["bound_s_side"] * (1 + 1e-12))
    # and the overhead limit reproduces the closed forms
    big = 1e7 * (y1_ - y0_)
    assert float(logpsm.rho_bound("side_t", near, far, fov, ly=0.0, lz=big)) == pytest.approx(float(cf["bound_t_side"]), rel=1e-6)
    assert float(logpsm.rho_bound("end", near, far, fov, lz=big)) == pytest.approx(float(cf["bound_t_end"]), rel=1e-9)
    assert float(logpsm.rho_bound("side_s", near, far, fov, lz=big, v=0.3)) == pytest.approx(float(cf["bound_s_side"]), rel=1e-9)


def test_eq19_point_light_tends_to_directional_light():
    # §3.2: as the light recedes (image plane fixed), n_l/d_l → 1 and the point-light m becomes eq. 25's
    assert sp.cancel(sp.together(J.m_point_far_limit() / L.m_directional_2d())) == 1


def test_log_maps_at_a_infinite_are_the_uniform_limit_without_warnings():
    """a = inf (with b = inf) is the uniform limit of eqs. 77, 78 and 84: v for the maps, t for the inverse, and no
    inf − inf on the way (the API fuzz found logp_inverse(0.5, 1, 100, 60, a=[inf, 0, 1]) warning, and the maps NaN)."""
    import warnings

    from aliasing import logpsm

    v = np.linspace(0.0, 1.0, 5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for kind in ("log_t", "logp_t", "perspective_t"):
            np.testing.assert_array_equal(logpsm.parameterization(kind, v, 1.0, 50.0, 60.0, a=np.inf), v)
        np.testing.assert_array_equal(logpsm.logp_inverse(v, 1.0, 50.0, 60.0, a=np.inf), v)
        out = logpsm.logp_inverse(0.5, 1.0, 100.0, 60.0, a=[np.inf, 0.0, 1.0])
    assert np.isfinite(out).all() and out[0] == 0.5
    t = logpsm.parameterization("logp_t", 0.3, 1.0, 50.0, 60.0, a=[0.0, 1.0])  # finite a: the inverse undoes the map
    np.testing.assert_allclose(logpsm.logp_inverse(t, 1.0, 50.0, 60.0, a=[0.0, 1.0]), 0.3, rtol=1e-12)
