"""Zhang, Sun et al. 2007: generalized minimum-norm perspective shadow maps (GMNPR).

*Theory to Practice: Generalized Minimum-Norm Perspective Shadow Maps*, ICEC 2007
(LNCS 4740), §2–3: the generalized aliasing error F(λ, θ, z) (eq. 2) of the computational
model of Fig. 4, the L∞-optimal λ (eqs. 3–4), λ_GMNPR (eqs. 5–8), λ_LiSPSM (eq. 9) and
GLPR's λ (F ∝ z, no formula printed).

Symbol map (paper → here → numeric API, :mod:`aliasing.gmnpr`):

==========================================  =====================  ==================================
paper                                       sympy symbol           numeric API
==========================================  =====================  ==================================
θ (angle between light and view direction)  ``theta``              ``gamma`` [deg], folded by symmetry:
                                                                   θ = min(γ, 180° − γ) ∈ [0°, 90°]
φ (half field of view)                      ``phi``                ``fov`` = 2φ [deg]
n, f (eye near, far)                        ``n``, ``f``           ``near``, ``far``
z (eye depth of a point on the view ray)    ``z``                  ``z``
λ = P_n/(P_f − P_n)                         ``lam``                ``lam``; n′ = λ·D [world units]
P_f − P_n (light-space depth of P)          ``D``                  :func:`aliasing.gmnpr.light_space_depth`
ψ(λ, θ), ϕ(λ, θ) of eq. 2                   ``psi``, ``varphi``    (inside ``generalized_error``)
==========================================  =====================  ==================================

λ is dimensionless: P's near-plane distance P_n measured in units of P's own depth
D = P_f − P_n ("P with a normalized depth range", text after eq. 8).  In world units the
warping parameter is n′ = P_n = λ·D, which is Lloyd 2006's n′ and Wimmer 2004's n.

The computational model (Fig. 4; the paper omits the derivation and refers to its [20]),
reconstructed here so that it gives eq. 2 exactly:

* a 2-D model in the light-space yz plane (Wimmer 2004 §3.4: y towards the light, z ⊥ y
  in the plane of the view and light directions); the eye is at the origin, its view
  axis makes the angle θ with the light direction and the frustum's half-angle φ lies in
  the same plane.  A point at eye depth d and lateral offset u has light-space
  z_L = d·sinθ + u·cosθ;
* the warping frustum P is fitted to the view frustum V (B = V): its near and far planes
  lie at the smallest and largest z_L of V's corners, and its centre of projection lies
  P_n = λ·D before the near plane;
* s is P's projective depth (glFrustum-type: 0 on P's near plane, 1 on its far plane);
* F is evaluated for a point on the central view ray at eye depth z (z_L = z·sinθ), with
  dz the length of view ray inside one texel beam, so dz = dz_L/sinθ.

Every function derives its result from these definitions; :data:`PRINTED` holds the
equations as printed (our reading of the text extraction), for comparison.  Where they
differ, and where the paper's argument fails, see docs/ERRATA.md (Z1–Z3).
"""

from __future__ import annotations

from functools import cache

import sympy as sp

from .registry import Printed, derivation
from .rewrite import linear_solve, polynomial_roots
from . import wimmer2004 as W

z, n, f = sp.symbols("z n f", positive=True)
theta, phi = sp.symbols("theta phi", positive=True)
lam = sp.Symbol("lambda", positive=True)
z_p = sp.Symbol("z'", positive=True)  # distance from P's centre of projection along light-space z
v = sp.Symbol("varphi", real=True)  # stands for ϕ(λ, θ) while solving eq. 3

SOURCE = "Zhang et al. 2007"

REGIME_1 = theta >= phi
"""θ ∈ [φ, π/2]: P's near plane touches V's near plane (Fig. 4, left)."""

# probe points inside each regime, used only to pick a root or check a sign
_PROBE = {1: {n: 1, f: 100, phi: sp.pi / 6, theta: sp.pi / 3}, 2: {n: 1, f: 100, phi: sp.pi / 6, theta: sp.pi / 9}}


def _piecewise(first: sp.Expr, second: sp.Expr) -> sp.Piecewise:
    """Regime 1 (θ ≥ φ) first, regime 2 (θ < φ) second, as eq. 2 writes them."""
    return sp.Piecewise((first, REGIME_1), (second, True))


def _same(a: sp.Expr, b: sp.Expr) -> bool:
    """Trigonometric identity test used inside derivations.

    Sums of angles are expanded and tanφ written as sinφ/cosφ; what is left is rational in
    the sines and cosines, and ``cancel`` decides whether it vanishes.
    """
    diff = sp.expand_trig(a - b).subs(sp.tan(phi), sp.sin(phi) / sp.cos(phi))
    return sp.cancel(diff) == 0


def _tan_theta(expr: sp.Expr) -> sp.Expr:
    """``expr`` with sinθ = tanθ·cosθ, factored: the cosθ of sinθ and cosθ terms cancel.

    The errors of the Fig. 4 model are homogeneous in sinθ and cosθ, so this writes them
    in tanθ and tanφ (eq. 2's variables) without a general simplification.
    """
    return sp.factor(expr.subs(sp.sin(theta), sp.tan(theta) * sp.cos(theta)))


def view_frustum_light_space() -> dict[str, sp.Expr]:
    """Light-space z of the 2-D view frustum's four corners (Fig. 4).

    Corner (d, u) with depth d ∈ {n, f} and lateral offset u = ±d·tanφ has
    z_L = d·sinθ + u·cosθ.
    """
    zl = lambda d, side: d * sp.sin(theta) + side * d * sp.tan(phi) * sp.cos(theta)  # noqa: E731
    return {"near-": zl(n, -1), "near+": zl(n, 1), "far-": zl(f, -1), "far+": zl(f, 1)}


@cache  # sympy expressions are immutable; several derivations reuse these
def light_space_extent(regime: int) -> tuple[sp.Expr, sp.Expr]:
    """(z_L,min, z_L,max) of the view frustum, the near and far planes of P (B = V).

    The largest corner is always (f, +f tanφ): it exceeds (n, +n tanφ) by
    (f − n)(sinθ + tanφ cosθ) ≥ 0 and (f, −f tanφ) by 2f tanφ cosθ ≥ 0 for θ ∈ [0, π/2].
    The smallest is (n, −n tanφ) or (f, −f tanφ): their difference is
    (f − n)·sin(θ − φ)/cos φ, so the near corner binds for θ ≥ φ (regime 1, Fig. 4 left)
    and the far corner for θ ≤ φ (regime 2: both of P's planes pass through V's far-plane
    corners, Fig. 4 right).
    """
    c = view_frustum_light_space()
    assert _same(c["far+"] - c["near+"], (f - n) * (sp.sin(theta) + sp.tan(phi) * sp.cos(theta)))
    assert _same(c["far+"] - c["far-"], 2 * f * sp.tan(phi) * sp.cos(theta))
    assert _same(c["far-"] - c["near-"], (f - n) * sp.sin(theta - phi) / sp.cos(phi))
    return (c["near-"] if regime == 1 else c["far-"]), c["far+"]


@cache
def _depth(regime: int) -> sp.Expr:
    lo, hi = light_space_extent(regime)
    return sp.expand(hi - lo)  # a sum of the corners' terms: expand collects them


@derivation("zhang2007.depth", f"{SOURCE}, Fig. 4 and eq. 9", "light-space depth D = P_f - P_n of the warping frustum fitted to the view frustum")
def depth() -> sp.Piecewise:
    """D = P_f − P_n = z_L,max − z_L,min, the light-space depth of P (the denominators of eq. 9).

    Regime 1: D = (f − n) sinθ + (f + n) tanφ cosθ = sinθ·(f − n + (f + n) tanφ/tanθ);
    regime 2: D = 2 f tanφ cosθ.  Overhead (θ = π/2): D = f − n.
    """
    return _piecewise(sp.expand(_depth(1)), sp.factor(_depth(2)))


def _s_map(near: sp.Expr, far: sp.Expr) -> sp.Expr:
    """Projective depth s(z′) = α + β/z′ with s(near) = 0 and s(far) = 1 (glFrustum)."""
    al, be = sp.symbols("alpha beta")
    s = al + be / z_p
    return s.subs(linear_solve([s.subs(z_p, near), s.subs(z_p, far) - 1], [al, be]))


@cache
def _error(regime: int) -> sp.Expr:
    """F(λ, θ, z) of one regime from eq. 1: F = (1/tanφ)·dz/(z ds), on the central view ray."""
    z_min, _ = light_space_extent(regime)
    d = _depth(regime)
    p_n = lam * d  # λ = P_n/(P_f − P_n)
    s = _s_map(p_n, p_n + d)
    # the view-ray point at eye depth z has z_L = z sinθ, i.e. z′ = P_n + z sinθ − z_L,min
    ds_dz = sp.diff(s.subs(z_p, p_n + z * sp.sin(theta) - z_min), z)
    # rational in z, λ, sinθ, cosθ, tanφ: factor finds eq. 2's square; sinθ and cosθ are
    # kept apart (not tanθ) so that the overhead light θ = π/2 stays a plain substitution
    return sp.factor(1 / (sp.tan(phi) * z * ds_dz))


@cache
def _psi_varphi(regime: int) -> tuple[sp.Expr, sp.Expr]:
    """ψ and ϕ of F = ψ(z + ϕ)²/z, read off the derived F.

    ψ = lim F/z (z → ∞); F·z/ψ must then be the perfect square z² + 2ϕz + ϕ².
    """
    F = _error(regime)
    # F is rational in z with a numerator one degree above its denominator: lim F/z is
    # the ratio of their leading coefficients
    num, den = (sp.Poly(part, z) for part in sp.fraction(sp.together(F)))
    assert num.degree() == den.degree() + 1
    psi = sp.factor(num.LC() / den.LC())
    quad = sp.Poly(sp.cancel(F * z / psi), z)
    a2, a1, a0 = quad.all_coeffs()
    assert sp.cancel(a2 - 1) == 0 and sp.cancel(a1**2 - 4 * a0) == 0  # a perfect square: eq. 2's form
    return psi, sp.expand(_tan_theta(a1 / 2))  # ϕ in tanφ/tanθ, as eq. 2 writes it


@derivation("zhang2007.F", f"{SOURCE}, eq. 2", "generalized perspective aliasing error F(lambda, theta, z) of the Fig. 4 model")
def generalized_error() -> sp.Piecewise:
    """F(λ, θ, z) (eq. 2), derived from the Fig. 4 model in both regimes."""
    return _piecewise(_error(1), _error(2))


@derivation("zhang2007.psi", f"{SOURCE}, eq. 2", "psi(lambda, theta) of F = psi (z + varphi)^2 / z")
def psi() -> sp.Piecewise:
    """ψ(λ, θ) of eq. 2, from the derived F."""
    return _piecewise(_psi_varphi(1)[0], _psi_varphi(2)[0])


@derivation("zhang2007.varphi", f"{SOURCE}, eq. 2", "varphi(lambda, theta) of F = psi (z + varphi)^2 / z")
def varphi() -> sp.Piecewise:
    """ϕ(λ, θ) of eq. 2, from the derived F.

    Geometrically −ϕ·sinθ is the light-space z of P's centre of projection: ϕ is how far
    behind the eye, in eye depth along the view ray, the centre sits.
    """
    return _piecewise(_psi_varphi(1)[1], _psi_varphi(2)[1])


@derivation("zhang2007.F_minimum", f"{SOURCE}, §3 (text before eq. 3)", "the only positive stationary point of F in z (a minimum), z = varphi")
def error_minimum() -> sp.Piecewise:
    """Location of F's positive extremum in z for given λ, θ: z = ϕ(λ, θ) (for ϕ > 0).

    dF/dz = ψ(z + ϕ)(z − ϕ)/z², so the stationary points are z = ±ϕ; z = −ϕ is F's zero
    (the view ray through the centre of projection), z = ϕ is a minimum:
    d²F/dz² = 2ψϕ²/z³ > 0.
    """
    out = []
    for regime in (1, 2):
        ps, ph = _psi_varphi(regime)
        F = ps * (z + v) ** 2 / z
        # ψ > 0 does not depend on z: the stationary points are the roots of d/dz (z + ϕ)²/z
        roots = polynomial_roots(sp.diff((z + v) ** 2 / z, z), z)
        assert set(roots) == {v, -v}
        assert sp.cancel(sp.diff(F, z, 2).subs(z, v) - 2 * ps / v) == 0  # > 0 for ϕ > 0
        out.append(ph)
    return _piecewise(*out)


def _linear_in_lambda(expr: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    """(a, b) with expr = a·λ + b, asserting that expr is affine in λ."""
    a = sp.factor(sp.diff(expr, lam))
    assert sp.diff(a, lam) == 0
    return a, sp.factor(expr - a * lam)


@derivation("zhang2007.boundary_errors", f"{SOURCE}, §3 Cases 1-2", "F at z = n and z = f as K (lambda + mu)^2 / (lambda (lambda + 1)): [K_n, mu, K_f, nu]")
def boundary_errors() -> sp.Matrix:
    """F(λ, θ, n) = K_n(λ + μ)²/(λ(λ+1)) and F(λ, θ, f) = K_f(λ + ν)²/(λ(λ+1)) (§3 Cases 1–2).

    ϕ = aλ + b is affine in λ, so F(z) = ψ(z + b + aλ)²/z = ψa²(λ + (z + b)/a)²/z, and
    ψ·λ(λ + 1) does not depend on λ.
    """
    rows = []
    for regime in (1, 2):
        ps, ph = _psi_varphi(regime)
        a, b = _linear_in_lambda(ph)
        k = sp.factor(ps * lam * (lam + 1))
        assert sp.diff(k, lam) == 0
        # K in ψ's sinθ, cosθ (defined at θ = π/2); μ and ν in ϕ's tanθ
        rows.append([sp.factor(k * a**2 / n), _tan_theta((n + b) / a), sp.factor(k * a**2 / f), _tan_theta((f + b) / a)])
    return sp.Matrix([_piecewise(r1, r2) for r1, r2 in zip(*rows)])


def _varphi_optimal() -> sp.Expr:
    """ϕ with F(n) = F(f) (eq. 3): (n + ϕ)²/n = (f + ϕ)²/f ⇔ ϕ = ±√(fn); ψ > 0 cancels.

    The root +√(fn) is the one with the centre of projection behind the eye; with −√(fn)
    F would vanish at z = √(fn) inside [n, f] (the view ray would pass through the centre).
    """
    roots = polynomial_roots((n + v) ** 2 / n - (f + v) ** 2 / f, v)
    (root,) = [r for r in roots if r.subs({n: 1, f: 100}) > 0]
    return root


@derivation("zhang2007.lambda_optimal", f"{SOURCE}, eqs. 3-4", "lambda equating F(n) and F(f), both regimes (lambda_1, lambda_2)")
def lambda_optimal() -> sp.Piecewise:
    """λ(θ) minimising max F over [n, f]: F(n) = F(f) (eqs. 3–4).

    F = ψ(z + ϕ)²/z is convex in z > 0 (see :func:`error_minimum`), so its maximum over
    [n, f] is at an end, and the L∞ optimum equalises the two ends: ϕ(λ, θ) = √(fn).
    """
    target = _varphi_optimal()
    out = []
    for regime in (1, 2):
        a, b = _linear_in_lambda(_psi_varphi(regime)[1])  # ϕ = aλ + b
        out.append(sp.cancel((target - b) / a))
    return _piecewise(*out)


@derivation("zhang2007.lambda_gmnpr", f"{SOURCE}, eqs. 5-8", "lambda_GMNPR: lambda_1 for theta >= phi, lambda_1(phi)/tan(pi theta/(4 phi)) below")
def lambda_gmnpr() -> sp.Piecewise:
    """λ_GMNPR (eq. 8): eq. 4's λ1 on [φ, π/2], the paper's replacement λ2* on [0, φ].

    λ2*(θ) = λ1(φ)/tan(πθ/(4φ)) is the paper's choice (eq. 7) among functions with
    λ2*(φ) = λ1(φ) (eq. 5) and λ2* → ∞ as θ → 0 (eq. 6); λ1(φ) is derived here.
    """
    lam1 = lambda_optimal().args[0][0]
    lam1_phi = sp.factor(lam1.subs(theta, phi))
    lam2_star = lam1_phi / sp.tan(sp.pi * theta / (4 * phi))  # eq. (7): the paper's choice
    return _piecewise(lam1, lam2_star)


@derivation("zhang2007.lambda_lispsm", f"{SOURCE}, eq. 9", "LiSPSM's P_n = (n + sqrt(fn))/sin(theta) (Wimmer 2004 4.4) divided by D")
def lambda_lispsm() -> sp.Piecewise:
    """λ_LiSPSM = P_n/(P_f − P_n) with Wimmer 2004's P_n = n_opt/sinθ (eq. 9)."""
    p_n = W.n_opt_general().subs({W.z_n: n, W.z_f: f, W.gamma: theta})
    return _piecewise(sp.factor(p_n / _depth(1)), sp.factor(p_n / _depth(2)))


@derivation("zhang2007.lambda_glpr", f"{SOURCE}, §3 (GLPR, F ~ z)", "lambda with F proportional to z (varphi = 0); only for theta > phi")
def lambda_glpr() -> sp.Piecewise:
    """λ_GLPR: F(z) ∝ z for given λ, θ (§3, GLPR of the paper's [20]; no formula printed).

    F/z = ψ(1 + ϕ/z)² is constant in z iff ϕ = 0: the centre of projection at the eye's
    light-space z (PSM-like).  In regime 2 that λ is (tanθ/tanφ − 1)/2 ≤ 0, which no
    frustum realises (P_n ≤ 0), so GLPR exists only for θ > φ (NaN otherwise).
    """
    out = []
    for regime in (1, 2):
        _, ph = _psi_varphi(regime)
        # F/z = ψ(1 + ϕ/z)² with ψ > 0 free of z: constant in z iff d/dz ((z + ϕ)/z)² = 0
        numer = sp.numer(sp.together(sp.diff((z + ph) ** 2 / z**2, z)))
        coeffs = sp.Poly(sp.expand(numer), z).coeffs()
        # the leading coefficient (−2ϕ) is linear in λ; its root must zero every coefficient
        root = linear_solve([coeffs[0]], [lam])[lam]
        assert all(sp.cancel(cf.subs(lam, root)) == 0 for cf in coeffs)
        out.append(sp.factor(root))
    # regime 2: the root is (tanθ/tanφ − 1)/2, not positive for θ ≤ φ
    assert sp.cancel(out[1] - (sp.tan(theta) / sp.tan(phi) - 1) / 2) == 0
    return sp.Piecewise((out[0], theta > phi), (sp.nan, True))


@derivation(
    "zhang2007.lambda_minimax_degenerate",
    f"{SOURCE}, eq. 3 (our analysis, theta < phi)",
    "[lambda*, tan(theta_1)]: for theta < theta_1 the L-inf optimum is lambda* (F(n) > F(f)), not eq. 4's lambda_2",
)
def lambda_minimax_degenerate() -> sp.Matrix:
    """Where eq. 3 (equal end errors) stops being L∞-optimal, and the optimum there.

    Not in the paper.  In regime 2, ν = 1/2, so F(f) = K_f(1 + 1/(4λ(λ+1))) decreases in
    λ for every λ > 0, and F(n)/F(f) = (f/n)((λ + μ)/(λ + 1/2))² increases in λ (μ < 1/2):
    for λ ≥ λ2, max(F(n), F(f)) = F(n).  F(n) ∝ (λ + μ)²/(λ(λ+1)) has its minimum at
    λ* = μ/(1 − 2μ) = f tanφ/(2(f − n) tanθ) − 1/2.  Where λ2 < λ*, raising λ from λ2
    lowers both end errors, so λ2 is not the minimiser: the L∞-optimal λ over λ > 0 is
    λ2 on [θ1, φ] and λ* on (0, θ1], with λ2(θ1) = λ*(θ1).

    Returns the column [λ*, tan θ1].
    """
    k_n, mu, _, nu = (e.args[1][0] for e in boundary_errors())
    assert nu == sp.Rational(1, 2)
    g = (lam + mu) ** 2 / (lam * (lam + 1))
    # dg/dλ ∝ (λ + μ)·(λ(1 − 2μ) − μ): divide out λ + μ and solve the linear factor
    quotient, remainder = sp.div(sp.Poly(sp.numer(sp.together(sp.diff(g, lam))), lam), sp.Poly(lam + mu, lam))
    assert remainder.is_zero and quotient.degree() == 1
    c1, c0 = quotient.all_coeffs()
    lam_star = sp.factor(-c0 / c1)
    lam2 = lambda_optimal().args[1][0]
    tt, tp = sp.symbols("T P", positive=True)  # tan θ, tan φ (both positive here)
    # λ2 = λ* is, times tanθ, a quadratic in tanθ without a linear term: solve for tan²θ
    quad = sp.Poly(sp.numer(sp.together((lam2 - lam_star).subs({sp.tan(theta): tt, sp.tan(phi): tp}))), tt)
    a2, a1, a0 = quad.all_coeffs()
    assert a1 == 0
    tan_theta1 = sp.sqrt(sp.factor(-a0 / a2)).subs(tp, sp.tan(phi))
    assert tan_theta1.subs(_PROBE[2]).evalf() > 0
    return sp.Matrix([lam_star, tan_theta1])


def shadow_map_depth_normalised() -> sp.Expr:
    """s(z′) of P with normalised depth (P_f − P_n = 1, P_n = λ); z′ from the centre (§3)."""
    return sp.together(_s_map(lam, lam + 1))


def _printed() -> dict[str, Printed]:
    """The printed equations, read from the text extraction (see docs/ERRATA.md)."""
    tan_p, tan_t = sp.tan(phi), sp.tan(theta)
    t = tan_p / tan_t
    L = f - n + (f + n) * t  # "f − n + (f + n) tanφ/tanθ", recurring in eqs. 2, 4, 9
    psi1 = 1 / tan_p / (L * lam * (lam + 1))
    psi2 = 1 / tan_p / (2 * f * lam * (lam + 1)) * tan_t / tan_p
    vp1 = L * lam + n * t - n
    vp2 = f * (2 * lam + 1) * t - f
    mu1 = n / ((f - n) * tan_t / tan_p + f + n)
    nu1 = 1 - f / ((f - n) * tan_t / tan_p + f + n)
    mu2 = sp.Rational(1, 2) - (f - n) / (2 * f) * tan_t / tan_p
    nu2 = sp.Rational(1, 2)
    lam1 = (n + sp.sqrt(f * n) - n * t) / L
    lam2 = (f + sp.sqrt(f * n)) / (2 * f) * tan_t / tan_p - sp.Rational(1, 2)
    lam2_star = sp.sqrt(f * n) / (2 * f) / sp.tan(theta / (4 * phi) * sp.pi)
    r = sp.sqrt(f / n)
    pn_lispsm = (n + sp.sqrt(f * n)) / sp.sin(theta)
    pw = _piecewise
    return {
        "eq2": Printed("eq. (2)", pw(psi1 * (z + vp1) ** 2 / z, psi2 * (z + vp2) ** 2 / z), "F(λ, θ, z) = ψ(λ, θ)(z + ϕ(λ, θ))²/z"),
        "eq2_psi": Printed(
            "eq. (2)", pw(psi1, psi2), "ψ = (1/tanφ)·1/((f−n+(f+n)tanφ/tanθ) λ(λ+1)) on [φ, π/2]; (1/tanφ)·1/(2fλ(λ+1))·tanθ/tanφ on [0, φ]"
        ),
        "eq2_varphi": Printed("eq. (2)", pw(vp1, vp2), "ϕ = (f−n+(f+n)tanφ/tanθ)λ + n tanφ/tanθ − n on [φ, π/2]; f(2λ+1)tanφ/tanθ − f on [0, φ]"),
        "minimum": Printed("§3, before eq. (3)", n * (1 - t) / L, "F(z) has a single positive minimum at z = n(1 − tanφ/tanθ)(f − n + (f+n)tanφ/tanθ)⁻¹"),
        "cases": Printed(
            "§3, Cases 1-2",
            sp.Matrix([pw(L / (n * tan_p), 2 * f / (n * tan_t)), pw(mu1, mu2), pw(L / (f * tan_p), 2 / tan_t), pw(nu1, nu2)]),
            "[K_n, μ, K_f, ν] of F(n) = K_n(λ+μ)²/(λ(λ+1)), F(f) = K_f(λ+ν)²/(λ(λ+1))",
        ),
        "eq4": Printed("eq. (4)", pw(lam1, lam2), "λ1 = ((n+√(fn)) − n tanφ/tanθ)/(f−n+(f+n)tanφ/tanθ); λ2 = ((f+√(fn))/(2f))·tanθ/tanφ − 1/2"),
        "eq4_general": Printed("eq. (4)", pw((nu1 - mu1) / (r - 1) - mu1, (nu2 - mu2) / (r - 1) - mu2), "λ = (ν − μ)/(√(f/n) − 1) − μ with each case's μ, ν"),
        "eq5": Printed("eq. (5)", lam1.subs(theta, phi), "λ2*(φ) = λ1(φ): the value λ2* must take at θ = φ"),
        "eq7": Printed("eq. (7)", lam2_star, "λ2*(θ) = λ1(φ)/tan(θπ/(4φ)) = (√(fn)/(2f))/tan(θπ/(4φ))"),
        "eq8": Printed("eq. (8)", pw(lam1, lam2_star), "λ_GMNPR = λ1(θ) on [φ, π/2], λ2*(θ) on [0, φ]"),
        "P_n_lispsm": Printed("§3, after eq. (8)", pn_lispsm, "P_n = (n + √(fn))/sinθ"),
        "eq9": Printed(
            "eq. (9)",
            pw(pn_lispsm / ((n * t + f - n + f * t) * sp.sin(theta)), pn_lispsm / (2 * f * tan_p * sp.cos(theta))),
            "λ_LiSPSM = ((n+√(fn))/sinθ)·1/((n tanφ/tanθ + f − n + f tanφ/tanθ) sinθ) on [φ, π/2]; ((n+√(fn))/sinθ)·1/(2f tanφ cosθ) on [0, φ]",
        ),
    }


PRINTED = _printed()
