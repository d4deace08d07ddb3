"""Zhang et al. 2007 (GMNPR): derived against printed, numeric against symbolic, errata.

Symbolic tests compare the sympy derivations of :mod:`aliasing.symbolic.zhang2007` with
the printed equations (``PRINTED``); where the paper is wrong (errata Z1–Z3, see
docs/ERRATA.md) the test asserts that the printed form differs and that the corrected
form holds.  Numeric tests compare :mod:`aliasing.gmnpr` with 40-digit evaluations of
the derivations.  The paper prints no numbers: the reference values below are our own.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from aliasing import gmnpr  # noqa: F401  (registers the gmnpr, glpr, lispsm-zhang rules)
from aliasing import warping
from aliasing.figures import zhang2007_fig5, zhang2007_fig6
from aliasing.symbolic import equivalent, get
from aliasing.symbolic import lloyd2006 as L
from aliasing.symbolic import wimmer2004 as W
from aliasing.symbolic import zhang2007 as Z
from conftest import assert_close, exact

P = Z.PRINTED
n, f, z, lam, theta, phi = Z.n, Z.f, Z.z, Z.lam, Z.theta, Z.phi
RTOL = 1e-12


def branches(expr: sp.Piecewise) -> tuple[sp.Expr, sp.Expr]:
    """(regime 1, regime 2) expressions of a two-branch Piecewise."""
    (e1, _), (e2, _) = expr.args
    return e1, e2


# --- eq. 2 and the computational model ------------------------------------------------


def test_depth_is_the_denominator_of_eq9_and_overhead_f_minus_n():
    d1, d2 = branches(Z.depth())
    p1, p2 = branches(P["eq9"].expr)
    pn = P["P_n_lispsm"].expr
    assert sp.simplify(pn / p1 - d1) == 0 and sp.simplify(pn / p2 - d2) == 0
    assert sp.simplify(d1.subs(theta, sp.pi / 2) - (f - n)) == 0
    assert sp.simplify(d1.subs(theta, phi) - d2.subs(theta, phi)) == 0  # continuous at θ = φ


def test_eq2_F_equals_printed():
    assert equivalent(Z.generalized_error(), P["eq2"].expr)


def test_eq2_psi_and_varphi_equal_printed():
    assert equivalent(Z.psi(), P["eq2_psi"].expr)
    assert equivalent(Z.varphi(), P["eq2_varphi"].expr)


def test_eq2_overhead_is_twice_lloyd_m_z_and_wimmer_dp_ds_over_near_tan():
    # θ = π/2: D = f − n, n′ = λ(f − n); Zhang's screen has half-height 1
    F = branches(Z.generalized_error())[0].subs(theta, sp.pi / 2)
    F = F.subs(lam, L.n_p / (f - n))
    mz = L.m_z().subs({L.res_i: 1, L.res_t: 1, L.theta: phi, L.z: z, L.n: n, L.f: f})
    assert sp.simplify(F - 2 * mz) == 0
    dpds = W.dp_ds().subs({W.z: z, W.z_n: n, W.z_f: f, W.n: L.n_p})
    assert sp.simplify(F - dpds / (n * sp.tan(phi))) == 0


def test_cases_1_2_boundary_errors_equal_printed():
    derived, printed = Z.boundary_errors(), P["cases"].expr
    for d, p in zip(derived, printed):
        assert equivalent(d, p)
    # and they are F at z = n and z = f
    F1, F2 = branches(Z.generalized_error())
    for k, F in enumerate((F1, F2)):
        kn, mu, kf, nu = (e.args[k][0] for e in derived)
        assert sp.simplify(F.subs(z, n) - kn * (lam + mu) ** 2 / (lam * (lam + 1))) == 0
        assert sp.simplify(F.subs(z, f) - kf * (lam + nu) ** 2 / (lam * (lam + 1))) == 0


# --- eqs. 3-4: the optimal λ ------------------------------------------------------------


def test_eq4_lambda_optimal_equals_printed():
    assert equivalent(Z.lambda_optimal(), P["eq4"].expr)


def test_eq4_general_form_equals_printed_cases():
    assert equivalent(Z.lambda_optimal(), P["eq4_general"].expr)


def test_eq3_lambda_optimal_equalises_the_end_errors():
    # ϕ(λ_opt) = √(fn) in both regimes, hence F(n) = F(f)
    for vp, lo in zip(branches(Z.varphi()), branches(Z.lambda_optimal())):
        assert sp.simplify(vp.subs(lam, lo) - sp.sqrt(f * n)) == 0
    # and directly on F, at θ = 60° (regime 1) and 29° (regime 2, where λ2 > 0)
    for F, lo, th in zip(branches(Z.generalized_error()), branches(Z.lambda_optimal()), (sp.pi / 3, sp.pi * 29 / 180)):
        Fl = F.subs(lam, lo).subs({n: 1, f: 100, phi: sp.pi / 6, theta: th})
        assert sp.N(Fl.subs(z, 1) - Fl.subs(z, 100), 30) == pytest.approx(0, abs=1e-25)


def test_lambda_1_at_90_degrees_is_lispsm():
    l1 = sp.limit(branches(Z.lambda_optimal())[0], theta, sp.pi / 2)  # tan(π/2) itself is undefined
    assert sp.simplify(l1 * (f - n) - L.n_prime_lispsm().subs({L.n: n, L.f: f})) == 0


# --- eqs. 5-9 and GLPR ------------------------------------------------------------------


def test_eq7_eq8_lambda_gmnpr_equals_printed():
    assert equivalent(Z.lambda_gmnpr(), P["eq8"].expr)
    assert sp.simplify(branches(Z.lambda_gmnpr())[1] - P["eq7"].expr) == 0


def test_eq5_eq6_requirements_hold_for_lambda_2_star():
    l1, l2s = branches(Z.lambda_gmnpr())
    assert sp.simplify(l2s.subs(theta, phi) - l1.subs(theta, phi)) == 0  # eq. (5)
    assert sp.simplify(l1.subs(theta, phi) - P["eq5"].expr) == 0
    assert sp.simplify(P["eq5"].expr - sp.sqrt(f * n) / (2 * f)) == 0
    assert sp.limit(l2s, theta, 0, "+") is sp.oo  # eq. (6)


def test_eq9_lambda_lispsm_equals_printed():
    assert equivalent(Z.lambda_lispsm(), P["eq9"].expr)


def test_lispsm_equalises_only_at_90_degrees():
    # ϕ(λ_LiSPSM) − √(fn) = 0 at θ = π/2 and > 0 below (weaker warp, F(n) > F(f))
    vp1 = branches(Z.varphi())[0].subs(lam, branches(Z.lambda_lispsm())[0])
    assert sp.simplify(vp1.subs(theta, sp.pi / 2) - sp.sqrt(f * n)) == 0
    for deg in (80, 60, 45, 31):
        assert (vp1 - sp.sqrt(f * n)).subs({n: 1, f: 100, phi: sp.pi / 6, theta: sp.pi * deg / 180}).evalf() > 0


def test_glpr_makes_F_proportional_to_z_and_exists_only_above_phi():
    lg = Z.lambda_glpr()
    cond = lg.args[0][1]
    assert lg.args[1][0] is sp.nan and cond.subs({theta: 1, phi: 0.5}) is sp.true and cond.subs({theta: 0.5, phi: 0.5}) is sp.false
    F1 = branches(Z.generalized_error())[0].subs(lam, lg.args[0][0])
    assert sp.simplify(sp.diff(F1 / z, z)) == 0
    assert sp.simplify(sp.limit(lg.args[0][0], theta, sp.pi / 2) * (f - n) - n) == 0  # PSM overhead
    assert sp.simplify(lg.args[0][0].subs(theta, phi)) == 0  # over-strong warp as θ → φ


def test_registry_lookup():
    assert get("zhang2007.F").func is Z.generalized_error
    assert get("zhang2007.lambda_gmnpr").source.startswith("Zhang et al. 2007, eq")


# --- errata (docs/ERRATA.md, Z1-Z3) -------------------------------------------------------


def test_Z1_location_of_F_minimum_depends_on_lambda():
    derived, printed = Z.error_minimum(), P["minimum"].expr
    # printed: z = n(1 − tanφ/tanθ)/(f − n + (f+n)tanφ/tanθ), independent of λ ...
    assert lam not in printed.free_symbols
    assert not equivalent(branches(derived)[0], printed)
    # ... which is λ_GLPR (the λ with ϕ = 0), not a location
    assert sp.simplify(printed - Z.lambda_glpr().args[0][0]) == 0
    # derived: z = ϕ(λ, θ), a zero of dF/dz; overhead z = n′ − n (Lloyd 2006 §4.1, Wimmer 2004 §4.3)
    for F, zs in zip(branches(Z.generalized_error()), branches(derived)):
        assert sp.simplify(sp.diff(F, z).subs(z, zs)) == 0
    overhead = branches(derived)[0].subs(theta, sp.pi / 2).subs(lam, L.n_p / (f - n))
    assert sp.simplify(overhead - (L.n_p - n)) == 0
    # the printed location is not a stationary point
    F1 = branches(Z.generalized_error())[0]
    probe = {n: 1, f: 100, phi: sp.pi / 6, theta: sp.pi / 3, lam: sp.Rational(1, 10)}
    assert abs(sp.diff(F1, z).subs(z, printed).subs(probe).evalf()) > 1


def test_Z2_eq4_is_already_continuous_at_phi_only_the_slope_jumps():
    # §3 calls θ = φ a "singularity" and demands eq. 5 of λ2*; eq. 4's λ2 already satisfies it
    l1, l2 = branches(Z.lambda_optimal())
    assert sp.simplify(l1.subs(theta, phi) - l2.subs(theta, phi)) == 0
    slope1 = sp.diff(l1, theta).subs({n: 1, f: 100, phi: sp.pi / 6, theta: sp.pi / 6}).evalf()
    slope2 = sp.diff(l2, theta).subs({n: 1, f: 100, phi: sp.pi / 6, theta: sp.pi / 6}).evalf()
    # per radian; the notes' values 0.070 and 1.27, to half a unit in their last digit
    assert slope1 == pytest.approx(0.070, abs=5e-4) and slope2 == pytest.approx(1.27, abs=5e-3)
    # the real defect: λ2 = 0 at tanθ0 = tanφ f/(f + √(fn)) and negative below
    (tan0,) = sp.solve(l2.subs(sp.tan(theta), sp.Symbol("T", positive=True)), sp.Symbol("T", positive=True))
    assert sp.simplify(tan0 - sp.tan(phi) * f / (f + sp.sqrt(f * n))) == 0
    assert float(sp.deg(sp.atan(tan0.subs({n: 1, f: 100, phi: sp.pi / 6})))) == pytest.approx(27.69, abs=5e-3)  # the notes: 27.69°


def test_Z3_equal_end_errors_are_not_minimax_below_theta_1():
    lam_star, tan1 = Z.lambda_minimax_degenerate()
    assert sp.simplify(lam_star - (f * sp.tan(phi) / (2 * (f - n) * sp.tan(theta)) - sp.Rational(1, 2))) == 0
    a = sp.Symbol("a", positive=True)  # f = a²n lets sympy cancel the roots
    assert sp.simplify((tan1**2 - (f * sp.tan(phi)) ** 2 / ((f - n) * (f + sp.sqrt(f * n)))).subs(f, a**2 * n)) == 0
    theta1 = np.degrees(np.arctan(float(tan1.subs({n: 1, f: 100, phi: sp.pi / 6}))))
    assert theta1 == pytest.approx(28.9538, abs=1e-4)
    # printed claim (eq. 3): minimising max F needs F(n) = F(f).  At θ = 20° < θ1 (and
    # θ0) no λ > 0 equalises; at θ = 28.5° λ2 > 0 does, but both end errors still fall
    # as λ grows from λ2, so λ2 is not the minimiser; λ* is, with F(n) > F(f).
    lams = np.geomspace(1e-3, 1e2, 400001)
    for deg in (28.5, 20.0, 10.0):
        fn = gmnpr.generalized_error(lams, 1, 100, 60, deg, 1.0)
        ff = gmnpr.generalized_error(lams, 1, 100, 60, deg, 100.0)
        best = lams[np.argmin(np.maximum(fn, ff))]
        ls = float(lam_star.subs({n: 1, f: 100, phi: sp.pi / 6, theta: sp.rad(deg)}))
        assert best == pytest.approx(ls, rel=1e-4)  # grid step 1e-4 relative
        l2 = float(gmnpr.lambda_optimal(1, 100, 60, deg))
        assert l2 < ls
        if l2 > 0:
            h = 1e-6
            for zz in (1.0, 100.0):
                up = gmnpr.generalized_error(l2 * (1 + h), 1, 100, 60, deg, zz)
                assert up < gmnpr.generalized_error(l2, 1, 100, 60, deg, zz)
    # above θ1 eq. 4 is the minimiser
    fn = gmnpr.generalized_error(lams, 1, 100, 60, 29.5, 1.0)
    ff = gmnpr.generalized_error(lams, 1, 100, 60, 29.5, 100.0)
    assert lams[np.argmin(np.maximum(fn, ff))] == pytest.approx(float(gmnpr.lambda_optimal(1, 100, 60, 29.5)), rel=1e-4)


def test_minor_normalised_depth_range_lambda_to_2_lambda_is_half_of_s():
    # "[λ ≤ z ≤ 2λ] occupies … [0 ≤ s ≤ ~0.5]": z is the distance from P's centre (depth 1)
    s = Z.shadow_map_depth_normalised()
    assert sp.simplify(s.subs(Z.z_p, lam)) == 0
    assert sp.simplify(s.subs(Z.z_p, 2 * lam) - (lam + 1) / 2) == 0


# --- numeric (aliasing.gmnpr) against the derivations -------------------------------------


@pytest.fixture(scope="module")
def zgrid():
    """near (3) × f/n (4) × fov (4) × gamma (13), broadcastable; angles also in radians."""
    near = np.array([0.1, 1.0, 3.0]).reshape(-1, 1, 1, 1)
    far = near * np.array([1.0 + 1e-6, 1.5, 10.0, 1000.0]).reshape(1, -1, 1, 1)
    fov = np.array([10.0, 60.0, 120.0, 170.0]).reshape(1, 1, -1, 1)
    gamma = np.array([1.0, 10.0, 25.0, 29.9, 30.0, 30.1, 45.0, 60.0, 85.0, 90.0, 95.0, 150.0, 179.5]).reshape(1, 1, 1, -1)
    th = np.radians(np.minimum(gamma, 180.0 - gamma))
    ph = np.radians(fov) / 2
    return {"near": near, "far": far, "fov": fov, "gamma": gamma, "theta": th, "phi": ph}


def _sym(expr):
    return exact(expr, n, f, phi, theta)


@pytest.mark.parametrize(
    ("func", "derivation"),
    [
        (gmnpr.lambda_optimal, Z.lambda_optimal),
        (gmnpr.lambda_gmnpr, Z.lambda_gmnpr),
        (gmnpr.lambda_lispsm, Z.lambda_lispsm),
        (gmnpr.lambda_glpr, Z.lambda_glpr),
        (gmnpr.light_space_depth, Z.depth),
    ],
)
def test_lambdas_and_depth_match_symbolic(zgrid, func, derivation):
    g = zgrid
    got = func(g["near"], g["far"], g["fov"], g["gamma"])
    assert got.shape == (3, 4, 4, 13)
    expr = derivation()
    if func is gmnpr.lambda_glpr:  # NaN for θ ≤ φ; compare the defined branch
        (expr, cond), _ = expr.args
        defined = np.broadcast_to(g["theta"] > g["phi"], got.shape)
        assert np.isnan(got[~defined]).all()
        got = np.where(defined, got, 1.0)
        want = np.where(defined, _sym(expr)(g["near"], g["far"], g["phi"], np.where(defined, g["theta"], 1.0)), 1.0)
    else:
        want = _sym(expr)(g["near"], g["far"], g["phi"], g["theta"])
    assert_close(got, want, rtol=RTOL)


def test_generalized_error_matches_symbolic(zgrid):
    g = {k: v[..., None, None] for k, v in zgrid.items()}
    u = np.linspace(0.0, 1.0, 4).reshape(-1, 1)
    zz = g["near"] + u * (g["far"] - g["near"])
    lams = np.array([1e-3, 0.05, 0.3, 2.0, 50.0])
    got = gmnpr.generalized_error(lams, g["near"], g["far"], g["fov"], g["gamma"], zz)
    want = exact(Z.generalized_error(), lam, n, f, phi, theta, z)(lams, g["near"], g["far"], g["phi"], g["theta"], zz)
    assert got.shape == (3, 4, 4, 13, 4, 5)
    assert_close(got, want, rtol=RTOL)


def test_generalized_error_uniform_limit(zgrid):
    # λ = ∞ (no warping): F = D/(tanφ sinθ z), the λ → ∞ limit of eq. 2
    g = zgrid
    lim = [sp.limit(F, lam, sp.oo) for F in branches(Z.generalized_error())]
    want = exact(sp.Piecewise((lim[0], Z.REGIME_1), (lim[1], True)), n, f, phi, theta, z)(g["near"], g["far"], g["phi"], g["theta"], g["near"])
    assert_close(gmnpr.generalized_error(np.inf, g["near"], g["far"], g["fov"], g["gamma"], g["near"]), want, rtol=RTOL)


def test_generalized_error_against_direct_geometry():
    # independent check of the model: corners → light-space extent → glFrustum depth s(z)
    # along the central view ray, differentiated numerically (central difference, O(h²))
    rng = np.random.default_rng(7)
    k = 200
    near = rng.uniform(0.1, 5.0, k)
    far = near * rng.uniform(2.0, 500.0, k)
    fov = rng.uniform(5.0, 175.0, k)
    gamma = rng.uniform(0.5, 179.5, k)
    lam_ = rng.uniform(0.01, 3.0, k)
    zz = near + rng.uniform(0.05, 0.95, k) * (far - near)
    th = np.radians(np.minimum(gamma, 180 - gamma))
    tp = np.tan(np.radians(fov) / 2)
    corners = [d * np.sin(th) + s * d * tp * np.cos(th) for d in (near, far) for s in (-1, 1)]
    lo, hi = np.min(corners, axis=0), np.max(corners, axis=0)
    d = hi - lo
    p_n = lam_ * d

    def s_of(depth):
        zp = p_n + depth * np.sin(th) - lo
        return (p_n + d) / d * (1 - p_n / zp)

    h = 1e-5 * zz
    ds_dz = (s_of(zz + h) - s_of(zz - h)) / (2 * h)
    direct = 1 / (tp * zz * ds_dz)
    np.testing.assert_allclose(gmnpr.generalized_error(lam_, near, far, fov, gamma, zz), direct, rtol=1e-6)
    np.testing.assert_allclose(gmnpr.light_space_depth(near, far, fov, gamma), d, rtol=1e-12)


def test_F_maximum_over_z_is_at_the_ends_and_gmnpr_equalises_them():
    z_ = np.linspace(1.0, 100.0, 2001)[:, None]
    th = np.array([30.0, 40.0, 60.0, 75.0, 90.0, 120.0, 150.0])
    lg = gmnpr.lambda_gmnpr(1, 100, 60, th)
    F = gmnpr.generalized_error(lg, 1, 100, 60, th, z_)
    np.testing.assert_allclose(F.max(axis=0), np.maximum(F[0], F[-1]), rtol=1e-12)
    np.testing.assert_allclose(F[0], F[-1], rtol=1e-12)  # eq. (3)
    # shape independent of θ (ϕ ≡ √(fn)): F/F(n) is one curve, minimum at z = √(fn) = 10
    np.testing.assert_allclose(F / F[0], np.broadcast_to(F[:, :1] / F[0, 0], F.shape), rtol=1e-12)
    assert z_[np.argmin(F[:, 0]), 0] == pytest.approx(10.0, abs=0.05)


# Our own computed values (the paper prints none), n = 1, f = 100, φ = π/6 (fov 60°),
# F in Zhang's normalisation, as tabulated in the Zhang/Wimmer research notes §1.7
# (computed there with an independent numeric model).  Columns: θ [deg], λ eq. 4,
# λ_GMNPR, λ_LiSPSM, λ_GLPR, F_GMNPR(n), F_GMNPR(f), F_LiSPSM(n), F_LiSPSM(f), D.
# Each value is checked to half a unit in its last tabulated digit.  λ_GLPR is NaN for
# θ ≤ φ (the notes list its limit 0 at θ = φ).
REFERENCE = [
    ("90", ".11111", ".11111", ".11111", ".01010", "17.147", "17.147", "17.147", "17.147", "99.0"),
    ("60", ".08040", ".08040", ".11055", ".00503", "18.186", "18.186", "23.926", "13.820", "114.89"),
    ("45", ".06625", ".06625", ".13985", ".00269", "18.858", "18.858", "35.208", "10.209", "111.24"),
    ("30", ".05000", ".05000", ".22000", "nan", "19.960", "19.960", "65.339", "6.691", "100.0"),
    ("25", "-.05578", ".06516", ".24871", "nan", "168.98", "19.738", "168.13", "7.742", "104.65"),
    ("10", "-.33203", ".18660", ".55706", "nan", "1468.5", "24.149", "1073.1", "14.612", "113.72"),
]


def _check_tabulated(got, text: str) -> None:
    """``got`` equals the tabulated ``text`` to half a unit in its last digit (NaN to NaN)."""
    if text == "nan":
        assert np.isnan(got)
        return
    decimals = len(text.split(".")[1]) if "." in text else 0
    assert abs(float(got) - float(text)) <= 0.5 * 10.0**-decimals, (float(got), text)


@pytest.mark.parametrize("row", REFERENCE, ids=[f"theta={r[0]}" for r in REFERENCE])
def test_reference_values_own_computation(row):
    th = float(row[0])
    args = (1.0, 100.0, 60.0, th)
    lg, ll = gmnpr.lambda_gmnpr(*args), gmnpr.lambda_lispsm(*args)
    F_g = gmnpr.generalized_error(lg, 1, 100, 60, th, [1.0, 100.0])
    F_l = gmnpr.generalized_error(ll, 1, 100, 60, th, [1.0, 100.0])
    got = (gmnpr.lambda_optimal(*args), lg, ll, gmnpr.lambda_glpr(*args), *F_g, *F_l, gmnpr.light_space_depth(*args))
    for value, text in zip(got, row[1:]):
        _check_tabulated(value, text)


# --- limits ---------------------------------------------------------------------------------


def test_overhead_limits():
    n_, f_ = np.array([0.5, 1.0, 2.0]), np.array([10.0, 100.0, 1e4])
    D = gmnpr.light_space_depth(n_, f_, 60.0, 90.0)
    np.testing.assert_allclose(D, f_ - n_, rtol=1e-15)
    lispsm = n_ + np.sqrt(f_ * n_)
    np.testing.assert_allclose(gmnpr.lambda_lispsm(n_, f_, 60.0, 90.0) * D, lispsm, rtol=1e-14)
    np.testing.assert_allclose(gmnpr.lambda_gmnpr(n_, f_, 60.0, 90.0) * D, lispsm, rtol=1e-14)
    np.testing.assert_allclose(gmnpr.lambda_glpr(n_, f_, 60.0, 90.0) * D, n_, rtol=1e-14)  # PSM


@pytest.mark.parametrize("fov", [20.0, 60.0, 150.0])
def test_continuity_at_theta_equal_phi(fov):
    phi_deg, eps = fov / 2, 1e-7
    for func in (gmnpr.lambda_optimal, gmnpr.lambda_gmnpr, gmnpr.light_space_depth):
        below, at, above = func(1.0, 100.0, fov, [phi_deg - eps, phi_deg, phi_deg + eps])
        assert at == pytest.approx(below, rel=1e-6) and at == pytest.approx(above, rel=1e-6)
    lam_phi = np.sqrt(100.0) / 200.0  # λ1(φ) = √(fn)/(2f)
    assert float(gmnpr.lambda_gmnpr(1.0, 100.0, fov, phi_deg)) == pytest.approx(lam_phi, rel=1e-13)
    assert float(gmnpr.lambda_optimal(1.0, 100.0, fov, phi_deg)) == pytest.approx(lam_phi, rel=1e-13)
    # GLPR vanishes as θ → φ⁺ and does not exist at or below φ
    assert 0 < gmnpr.lambda_glpr(1.0, 100.0, fov, phi_deg + eps) < 1e-6
    assert np.isnan(gmnpr.lambda_glpr(1.0, 100.0, fov, phi_deg))


def test_symmetry_and_parallel_light():
    g = np.array([0.0, 20.0, 45.0, 80.0])
    for func in (gmnpr.lambda_optimal, gmnpr.lambda_gmnpr, gmnpr.lambda_lispsm, gmnpr.light_space_depth):
        np.testing.assert_array_equal(func(1.0, 100.0, 60.0, g), func(1.0, 100.0, 60.0, 180.0 - g))
    # γ = 0° or 180°: GMNPR and LiSPSM converge to a uniform map (eq. 6), F is infinite
    assert np.isinf(gmnpr.lambda_gmnpr(1.0, 100.0, 60.0, [0.0, 180.0])).all()
    assert np.isinf(gmnpr.lambda_lispsm(1.0, 100.0, 60.0, 0.0))
    assert float(gmnpr.lambda_optimal(1.0, 100.0, 60.0, 0.0)) == -0.5
    assert np.isinf(gmnpr.generalized_error([0.1, np.inf], 1.0, 100.0, 60.0, 0.0, 50.0)).all()


# --- shapes and validation --------------------------------------------------------------------


def test_scalar_and_nd_inputs():
    for func in (gmnpr.lambda_optimal, gmnpr.lambda_gmnpr, gmnpr.lambda_lispsm, gmnpr.lambda_glpr, gmnpr.light_space_depth):
        assert np.ndim(func(1.0, 100.0, 60.0, 45.0)) == 0
        out = func(np.array([1.0, 2.0]).reshape(2, 1, 1), np.array([10.0, 50.0, 100.0]).reshape(1, 3, 1), 60.0, np.array([5.0, 30.0, 60.0, 170.0]))
        assert out.shape == (2, 3, 4)
        assert out[1, 2, 2] == func(2.0, 100.0, 60.0, 60.0)
    F = gmnpr.generalized_error(np.array([0.1, 1.0]).reshape(2, 1), 1.0, 100.0, 60.0, np.array([10.0, 45.0, 90.0]), 5.0)
    assert F.shape == (2, 3) and F[1, 2] == gmnpr.generalized_error(1.0, 1.0, 100.0, 60.0, 90.0, 5.0)
    assert np.ndim(gmnpr.generalized_error(0.1, 1.0, 100.0, 60.0, 45.0, 5.0)) == 0


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"fov": 0.0}, "fov"),
        ({"fov": 180.0}, "fov"),
        ({"gamma": -1.0}, "gamma"),
        ({"gamma": 180.5}, "gamma"),
        ({"gamma": np.nan}, "gamma"),
        ({"near": 0.0}, "near"),
        ({"far": 1.0}, "far"),
        ({"far": 0.5}, "far"),
    ],
)
def test_bad_input_raises(kwargs, match):
    args = {"near": 1.0, "far": 100.0, "fov": 60.0, "gamma": 45.0} | kwargs
    for func in (gmnpr.lambda_optimal, gmnpr.lambda_gmnpr, gmnpr.lambda_lispsm, gmnpr.lambda_glpr, gmnpr.light_space_depth):
        with pytest.raises(ValueError, match=match):
            func(**args)
    with pytest.raises(ValueError, match=match):
        gmnpr.generalized_error(0.1, z=2.0, **args)
    with pytest.raises(ValueError, match=match):
        warping.warping_parameter("gmnpr", **args)


@pytest.mark.parametrize(("lam_", "z_", "match"), [(0.0, 2.0, "lam"), (-0.1, 2.0, "lam"), (np.nan, 2.0, "lam"), (0.1, 0.5, "z"), (0.1, 101.0, "z")])
def test_generalized_error_bad_lambda_or_depth(lam_, z_, match):
    with pytest.raises(ValueError, match=match):
        gmnpr.generalized_error(lam_, 1.0, 100.0, 60.0, 45.0, z_)


def test_range_messages_name_the_range():
    with pytest.raises(ValueError, match=r"gamma must be in \[0, 180\] degrees"):
        gmnpr.lambda_gmnpr(1.0, 100.0, 60.0, 200.0)
    with pytest.raises(ValueError, match=r"\(0, 180\) degrees"):
        gmnpr.lambda_gmnpr(1.0, 100.0, 200.0, 45.0)


# --- the registered warping rules ---------------------------------------------------------------


def test_rules_registered():
    for name in ("gmnpr", "glpr", "lispsm-zhang"):
        rule = warping.WARPING_RULES[name]
        assert rule.source.startswith("Zhang et al. 2007") and rule.summary


def test_rules_return_lambda_times_depth():
    g = np.array([0.0, 10.0, 30.0, 45.0, 90.0, 135.0, 180.0])
    D = gmnpr.light_space_depth(1, 100, 60, g)
    with np.errstate(invalid="ignore"):  # λ = ∞ at γ = 0°, 180°
        want = gmnpr.lambda_gmnpr(1, 100, 60, g) * D
    np.testing.assert_array_equal(warping.warping_parameter("gmnpr", 1, 100, fov=60, gamma=g), want)
    lis = warping.warping_parameter("lispsm-zhang", 1, 100, fov=60, gamma=g)
    with np.errstate(divide="ignore"):
        np.testing.assert_allclose(lis, 11.0 / np.sin(np.radians(np.minimum(g, 180 - g))), rtol=1e-14)  # (n + √(fn))/sinθ
    glpr = warping.warping_parameter("glpr", 1, 100, fov=60, gamma=g)
    finite = np.minimum(g, 180 - g) > 30
    np.testing.assert_allclose(glpr[finite], (gmnpr.lambda_glpr(1, 100, 60, g) * D)[finite], rtol=1e-15)
    assert np.isinf(glpr[~finite]).all()  # GLPR does not exist: no warping
    assert float(warping.warping_parameter("glpr", 1, 100, fov=60, gamma=90)) == pytest.approx(1.0, rel=1e-14)
    # with the model's own depth, Zhang's LiSPSM is the package's 1/sin γ LiSPSM rule
    np.testing.assert_allclose(lis, warping.warping_parameter("lispsm", 1, 100, gamma=g), rtol=1e-14)


def test_rules_defaults_depth_and_options():
    # defaults: fov 60°, γ = 90° (overhead): all three give LiSPSM or PSM
    assert float(warping.warping_parameter("gmnpr", 1, 100)) == pytest.approx(11.0, rel=1e-14)
    assert float(warping.warping_parameter("lispsm-zhang", 1, 100)) == pytest.approx(11.0, rel=1e-14)
    # depth overrides the model's D: n′ = λ·depth
    lg = gmnpr.lambda_gmnpr(1, 100, 60, 45)
    got = warping.warping_parameter("gmnpr", 1, 100, fov=60, gamma=45, depth=[50.0, 200.0])
    np.testing.assert_allclose(got, lg * np.array([50.0, 200.0]), rtol=1e-15)
    with pytest.raises(ValueError, match="depth"):
        warping.warping_parameter("gmnpr", 1, 100, gamma=45, depth=0.0)
    with pytest.raises(ValueError, match="eta"):
        warping.warping_parameter("gmnpr", 1, 100, eta=0.5)


# --- figures ---------------------------------------------------------------------------------------


def test_fig5_lambda_curves():
    c = zhang2007_fig5.data()
    th = c["theta_deg"]
    above = th >= 30.0
    np.testing.assert_array_equal(c["lambda_GMNPR"][above], c["lambda_eq4"][above])
    assert np.all(np.diff(c["lambda_eq4"]) > 0)  # eq. 4 falls monotonically as θ goes from 90° to 0
    assert c["lambda_eq4"][0] < 0 < c["lambda_eq4"][th == 30.0][0]  # the nose-dive through 0
    assert np.all(np.diff(c["lambda_GMNPR"][th <= 30.0]) < 0)  # λ2* grows towards θ = 0
    assert np.all(c["lambda_LiSPSM"][th < 90.0] > c["lambda_GMNPR"][th < 90.0])
    assert np.isnan(c["lambda_GLPR"][th <= 30.0]).all() and np.all(c["lambda_GLPR"][th > 30.0] > 0)


def test_fig6_distributions():
    c = zhang2007_fig6.data()
    for th in zhang2007_fig6.THETA_NONDEGENERATE:  # GMNPR: equal ends for all θ ≥ φ
        F = c[f"F_GMNPR[theta={th:g}]"]
        assert F[0] == pytest.approx(F[-1], rel=1e-12)
    near_lispsm = [c[f"F_LiSPSM[theta={th:g}]"][0] for th in zhang2007_fig6.THETA_NONDEGENERATE]
    assert np.all(np.diff(near_lispsm) > 0)  # θ decreasing: LiSPSM's near error increases
    for method in ("LiSPSM", "GMNPR"):  # degenerate range: errors grow as θ → 0
        near = [c[f"F_{method}[theta={th:g}]"][0] for th in zhang2007_fig6.THETA_DEGENERATE]
        assert np.all(np.diff(near) > 0)


def test_figure_scripts_write_png_and_csv(tmp_path):
    for module in (zhang2007_fig5, zhang2007_fig6):
        paths = module.main(tmp_path)
        assert [p.suffix for p in paths] == [".png", ".csv"] and all(p.stat().st_size > 0 for p in paths)
