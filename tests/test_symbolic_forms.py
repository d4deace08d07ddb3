"""The derivations whose printed form changed when general ``simplify`` gave way to targeted
rewrites (together, factor, cancel, linear and polynomial solves, sinθ = tanθ·cosθ) are still
the same functions: each is evaluated at random rational points and compared with the numeric
module that implements it independently (or with the property that defines it).
"""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import pytest
import sympy as sp

from aliasing import error, gmnpr, logpsm, warping
from aliasing.symbolic import display
from aliasing.symbolic import lloyd2006 as L6
from aliasing.symbolic import lloyd2007 as L7
from aliasing.symbolic import lloyd2007_matrix as LM
from aliasing.symbolic import zhang2007 as Z

RNG = random.Random(20261126)


def _q(lo: float, hi: float) -> sp.Rational:
    """A random rational in [lo, hi] (denominator up to 97)."""
    frac = Fraction(RNG.uniform(lo, hi)).limit_denominator(97)
    return sp.Rational(frac.numerator, frac.denominator)


def _value(expr: sp.Expr, subs: dict) -> float:
    return float(sp.N(expr.subs(subs), 30))


def test_eta_of_n_prime_equals_the_numeric_inverse_of_eq_11():
    eta_upper, eta_lower = (e for e, _ in L6.eta_of_n_prime().args)
    for _ in range(8):
        n, ratio = _q(0.5, 3.0), _q(1.5, 400.0)
        f = n * ratio
        n_l = n + sp.sqrt(f * n)
        for npr, branch in ((n_l * _q(1.05, 30.0), eta_upper), (n + (n_l - n) * _q(0.0, 0.95), eta_lower)):
            expected = float(warping.eta_from_n_prime(float(npr), float(n), float(f)))
            assert _value(branch, {L6.n: n, L6.f: f, L6.n_p: npr}) == pytest.approx(expected, rel=1e-10, abs=1e-12)


def test_critical_resolutions_equal_the_numeric_ones():
    rs, rt = L6.critical_resolutions()
    for _ in range(8):
        n, f, fov, ri = _q(0.5, 3.0), None, _q(10.0, 150.0), _q(100.0, 4000.0)
        f = n * _q(1.5, 400.0)
        npr = n * _q(1.0, 60.0)
        subs = {L6.n: n, L6.f: f, L6.n_p: npr, L6.theta: sp.pi * fov / 360, L6.res_i: ri}
        num_s, num_t = error.critical_resolution(float(n), float(f), float(fov), float(npr), res_image=float(ri))
        assert _value(rs, subs) == pytest.approx(float(num_s), rel=1e-10)
        assert _value(rt.subs(subs), {}) == pytest.approx(float(num_t), rel=1e-10)


def _zhang_point(regime: int) -> tuple[dict, tuple[float, float, float, float]]:
    """Symbol values and (near, far, fov, gamma) of a random frustum in a regime (θ ≥ φ or θ < φ)."""
    n, f = _q(0.5, 3.0), None
    f = n * _q(2.0, 300.0)
    fov = _q(20.0, 140.0)
    half = fov / 2
    gamma = half + (90 - half) * _q(0.05, 0.95) if regime == 1 else half * _q(0.1, 0.9)
    subs = {Z.n: n, Z.f: f, Z.phi: sp.pi * half / 180, Z.theta: sp.pi * gamma / 180}
    return subs, (float(n), float(f), float(fov), float(gamma))


@pytest.mark.parametrize("regime", [1, 2])
def test_zhang_F_psi_varphi_and_boundary_errors_equal_the_numeric_F(regime):
    F = Z.generalized_error().args[regime - 1][0]
    psi, varphi = Z.psi().args[regime - 1][0], Z.varphi().args[regime - 1][0]
    minimum = Z.error_minimum().args[regime - 1][0]
    k_n, mu, k_f, nu = (e.args[regime - 1][0] for e in Z.boundary_errors())
    for _ in range(5):
        subs, (n, f, fov, gamma) = _zhang_point(regime)
        lam, z = _q(0.05, 3.0), subs[Z.n] + (subs[Z.f] - subs[Z.n]) * _q(0.0, 1.0)
        at = {**subs, Z.lam: lam, Z.z: z}
        numeric = float(gmnpr.generalized_error(float(lam), n, f, fov, gamma, float(z)))
        assert _value(F, at) == pytest.approx(numeric, rel=1e-9)
        assert _value(psi * (Z.z + varphi) ** 2 / Z.z, at) == pytest.approx(numeric, rel=1e-9)
        assert _value(minimum - varphi, at) == pytest.approx(0.0, abs=1e-9 * max(1.0, abs(_value(varphi, at))))
        g = lambda mu_, k_: k_ * (Z.lam + mu_) ** 2 / (Z.lam * (Z.lam + 1))  # noqa: E731
        assert _value(g(mu, k_n), at) == pytest.approx(float(gmnpr.generalized_error(float(lam), n, f, fov, gamma, n)), rel=1e-9)
        assert _value(g(nu, k_f), at) == pytest.approx(float(gmnpr.generalized_error(float(lam), n, f, fov, gamma, f)), rel=1e-9)


@pytest.mark.parametrize("regime", [1, 2])
@pytest.mark.parametrize("which", ["lambda_optimal", "lambda_lispsm", "lambda_glpr", "lambda_gmnpr"])
def test_zhang_lambdas_equal_the_numeric_ones(regime, which):
    derived = getattr(Z, which)()
    for _ in range(5):
        subs, (n, f, fov, gamma) = _zhang_point(regime)
        numeric = float(getattr(gmnpr, which)(n, f, fov, gamma))
        value = derived.subs(subs)
        if np.isnan(numeric):  # GLPR does not exist for θ ≤ φ (NaN by contract)
            assert value is sp.nan
            continue
        assert float(sp.N(value, 30)) == pytest.approx(numeric, rel=1e-9)


def test_zhang_minimax_degenerate_lambda_star_minimises_F_at_near_and_tan_theta_1_is_where_lambda_2_meets_it():
    lam_star, tan1 = Z.lambda_minimax_degenerate()
    lam2 = Z.lambda_optimal().args[1][0]
    for _ in range(5):
        subs, (n, f, fov, gamma) = _zhang_point(2)
        ls = _value(lam_star, subs)
        if ls <= 0:
            continue
        near_err = lambda lam: float(gmnpr.generalized_error(lam, n, f, fov, gamma, n))  # noqa: E731
        assert near_err(ls) <= min(near_err(ls * 0.99), near_err(ls * 1.01))
        t1 = _value(tan1, subs)
        at1 = {**subs, sp.tan(Z.theta): t1}
        assert _value(lam2.subs(sp.tan(Z.theta), t1), subs) == pytest.approx(_value(lam_star.subs(sp.tan(Z.theta), t1), at1), rel=1e-9)


def test_lloyd2007_log_forms_equal_the_numeric_side_face_maps():
    theta_half = lambda fov: sp.pi * fov / 360  # noqa: E731
    for _ in range(6):
        n, fov = _q(0.5, 2.0), _q(20.0, 120.0)
        f, a, v = n * _q(2.0, 200.0), _q(0.0, 5.0), _q(0.0, 1.0)
        th = theta_half(fov)
        frame = {L7.y0: n / sp.cos(th), L7.y1: f / sp.cos(th), L7.W_e: 2 * n * sp.tan(th), L7.a: a}
        y_v = frame[L7.y0] + (frame[L7.y1] - frame[L7.y0]) * v
        at = {**frame, L7.y: y_v}
        args = (float(v), float(n), float(f), float(fov))
        assert _value(L7.F_log(), at) == pytest.approx(float(logpsm.parameterization("log_t", *args, a=float(a))), rel=1e-9)
        assert _value(L7.spacing_log(), at) == pytest.approx(float(logpsm.spacing("log_t", *args, a=float(a))), rel=1e-9)
        b = a + _q(1.0, 50.0)
        assert _value(L7.F_lp_t(), {**at, L7.b: b}) == pytest.approx(float(logpsm.parameterization("logp_t", *args, a=float(a), b=float(b))), rel=1e-9)
        # the inverse: v(t) of F_lp,t at t = F_lp,t(v) gives v back
        k = L7.lp_constants()
        t_val = _value(L7.F_lp_t(), {**at, L7.b: b})
        v_back = L7.F_lp_inverse()[0].subs({**frame, L7.b: b, L7.t: sp.Float(t_val, 30)})
        assert float(sp.N(v_back, 30)) == pytest.approx(float(v), abs=1e-9)
        assert _value(k[L7.c2_s], {}) == 1


def test_lp_roots_are_both_roots_of_the_spacing_numerator():
    roots = L7.lp_roots()
    assert len(roots) == 2 and -L7.a in roots  # eq. 105: −a and −(a + c1 p3/(c1 p2 + c2))
    num = sp.numer(sp.together(L7.spacing_lp_general()))
    for _ in range(4):
        vals = {L7.a: _q(0.1, 3.0), L7.y0: _q(1.0, 2.0), L7.y1: _q(3.0, 50.0), L7.c1_s: _q(0.1, 2.0), L7.c2_s: _q(0.1, 2.0), L7.c0_s: _q(0.1, 2.0)}
        for r in roots:
            assert _value(num.subs(L7.y, r), vals) == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("func", [LM.delta_e_3d, LM.aliasing_matrix, LM.aliasing_matrix_directional])
def test_large_results_are_shown_with_named_subexpressions_that_substitute_back(func):
    expr = func()
    text = display(expr)
    assert "\nwhere\n" in text and len(text) < 20_000  # the full expression is 55-300 kB written out
    defs, (reduced,) = sp.cse(expr, symbols=sp.numbered_symbols("w", start=1), order="none")
    assert display(expr).startswith(sp.sstr(reduced))
    # evaluate the named form line by line, as a reader would, and the full expression at once
    # a point of its own for each expression, in a fixed symbol order (a set's order follows the hash seed), drawn
    # as full floats: rationals of denominator ≤ 97 repeat among 44 symbols and can land on a 0/0 (NaN on both sides)
    rng = random.Random(f"{func.__name__}:20261127")
    for _ in range(5):
        values = {s: sp.Float(rng.uniform(-2.0, 2.0), 30) for s in sorted(expr.free_symbols, key=str)}
        want = expr.xreplace(values)
        if all(sp.Float(w, 30).is_finite for w in want):  # a regular point
            break
    assert all(sp.Float(w, 30).is_finite for w in want), "no regular point in five draws"
    for name, value in defs:
        values[name] = value.xreplace(values)
    for got, w in zip(reduced.xreplace(values), want):
        assert complex(got) == pytest.approx(complex(w), rel=1e-12, abs=1e-12)
