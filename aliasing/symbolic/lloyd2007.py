"""Lloyd, Govindaraju, Quammen, Molnar, Manocha 2007 (LogPSM, UNC TR07-005), §3–5 and App. A.

*Logarithmic Perspective Shadow Maps*.  Derived with sympy from the definitions:

* §3.2, eqs. 2–19: the 2D aliasing error m of a point light, from the chain of projections
  (light image plane → surface → eye image plane), and of a directional light (eq. 25);
  the "intuitive" derivation from projected beam widths (eqs. 20–24) as a cross-check;
* §3.3, eqs. 27–31: the factorisation into spacing functions δ_l, δ_e, δ̃_e;
* §4.1, eqs. 41–43: the parameterization of a spacing function;
* §4.3–4.4, eqs. 48–69: the error-bound spacing δ_b, its minimum on the entry/exit faces,
  on end and side faces, with the closed-form integrals ζ of eqs. 66–68;
* §5 and App. A, eqs. 74–110 and 84: uniform, perspective, logarithmic and
  log+perspective parameterizations on a side face, their spacing functions and the
  closed-form critical resolution factors for the overhead directional light (eqs. 87–103).

Symbol map (paper → here → numeric API :mod:`aliasing.logpsm`):

=========================  ==============  =====================================
paper                      sympy symbol    numeric API
=========================  ==============  =====================================
θ (half field of view)     ``theta``       ``fov`` = 2θ in degrees
n_e, f_e                   ``n``, ``f``    ``near``, ``far``
W_e = 2 n_e tanθ           ``W_e``         (derived from near, fov)
y0, y1 (side face)         ``y0``, ``y1``  n_e/cosθ, f_e/cosθ
a (COP at y = −a)          ``a``           ``a``
b (second root, eq. 106)   ``b``           ``b`` (``inf`` = eq. 78)
l_x, l_y, l_z (light)      same            ``light=(lx, ly, lz)``, lz = inf overhead
=========================  ==============  =====================================

Side-face frame (Fig. 5): the origin is at the eye, y runs along the face's centre line,
the face spans y ∈ [y0, y1] and, at y, x ∈ [−W_e y/(2y0), W_e y/(2y0)].  :data:`PRINTED`
holds our reading of the printed equations; where they differ from the derivation see
docs/ERRATA.md (L9–L16).
"""

from __future__ import annotations

import sympy as sp

from .registry import Printed, derivation
from .rewrite import linear_solve, polynomial_roots

SOURCE = "Lloyd et al. 2007"

# --- symbols ---------------------------------------------------------------------------
theta = sp.Symbol("theta", positive=True)
n, f = sp.symbols("n f", positive=True)
W_e, W_l, n_e, n_l = sp.symbols("W_e W_l n_e n_l", positive=True)
d_e, d_l = sp.symbols("d_e d_l", positive=True)
r_j, r_t = sp.symbols("r_j r_t", positive=True)
dGdt = sp.Symbol("dG/dt", positive=True)
cphi_e, cphi_l, cpsi_e, cpsi_l = sp.symbols("cos_phi_e cos_phi_l cos_psi_e cos_psi_l", positive=True)
y, y0, y1, a, b = sp.symbols("y y0 y1 a b", positive=True)
u, v, t = sp.symbols("u v t", real=True)
x = sp.Symbol("x", real=True)
l_x, l_y = sp.symbols("l_x l_y", real=True)
l_z = sp.Symbol("l_z", positive=True)
mu = sp.Symbol("mu", positive=True)
c, ze_v, ze_l, zl_v = sp.symbols("c zeta_ev zeta_el zeta_lv", real=True)  # c, ẑe·v̂l, ẑe·(l−e), ẑl·v̂l

# 2D configuration of §3.2 in coordinates (surface point at the origin, surface along x)
E1, E2, L1, L2, X1, X2 = sp.symbols("E1 E2 L1 L2 X1 X2", real=True)
s_e, s_l, s_v = sp.symbols("s_e s_l s_v", real=True)


def _unit(s: sp.Expr) -> sp.Matrix:
    """Rational unit vector ((1 − s²), 2s)/(1 + s²): keeps every cosine rational."""
    return sp.Matrix([(1 - s**2) / (1 + s**2), 2 * s / (1 + s**2)])


def _perp(w: sp.Matrix) -> sp.Matrix:
    """w rotated by −90°: the image-plane axis ŷ of a plane with normal ẑ = w."""
    return sp.Matrix([w[1], -w[0]])


def _dot(p: sp.Matrix, q: sp.Matrix) -> sp.Expr:
    return (p.T * q)[0]


def configuration_2d() -> dict[str, sp.Basic]:
    """A general 2D point-light configuration (Fig. 2) in coordinates.

    The surface point p is the origin and the surface π is the x-axis (normal n̂ = (0, 1));
    the eye sits at e = (E1, E2) looking along −ẑ_e, ẑ_e = unit(s_e), its image plane π_e
    at distance n_e; the light sits at l = (L1, L2) looking along −ẑ_l, ẑ_l = unit(s_l),
    image plane at distance n_l.  Returns the vectors and the substitution map from the
    paper's scalar symbols (d_e, d_l, cos φ, cos ψ) to coordinates.  Only ratios of cosines
    appear in eq. 19, so the norms |e − p|, |l − p| cancel and everything stays rational.
    """
    p = sp.zeros(2, 1)
    nh = sp.Matrix([0, 1])
    e, ze = sp.Matrix([E1, E2]), _unit(s_e)
    lpos, zl = sp.Matrix([L1, L2]), _unit(s_l)
    norm_e = sp.Symbol("|e-p|", positive=True)
    norm_l = sp.Symbol("|l-p|", positive=True)
    subs = {
        d_e: _dot(ze, e - p),
        d_l: -_dot(zl, p - lpos),
        cphi_e: _dot(ze, e - p) / norm_e,
        cpsi_e: _dot(nh, e - p) / norm_e,
        cphi_l: _dot(zl, lpos - p) / norm_l,
        cpsi_l: _dot(nh, lpos - p) / norm_l,
    }
    return {"p": p, "n": nh, "e": e, "z_e": ze, "y_e": _perp(ze), "l": lpos, "z_l": zl, "y_l": _perp(zl), "subs": subs}


def _eye_jacobian(g: dict) -> sp.Matrix:
    """∂p_e/∂p of eq. 4 at the surface point, by differentiating eq. 4 itself."""
    X = sp.Matrix([X1, X2])
    e, ze = g["e"], g["z_e"]
    pi_e = _dot(ze, X - e) + n_e  # π_e X, with π_e e = n_e
    p_e = X - pi_e / _dot(ze, e - X) * (e - X)  # eq. (4)
    return p_e.jacobian(X).subs({X1: 0, X2: 0})


def _dp_dv_point(g: dict) -> sp.Matrix:
    """dp/dv for the point light: eq. 3 differentiated at the light-plane point of p."""
    X = sp.Matrix([X1, X2])
    lpos, nh, p = g["l"], g["n"], g["p"]
    proj = X - _dot(nh, X - p) / _dot(nh, X - lpos) * (X - lpos)  # eq. (3)
    dl = g["subs"][d_l]
    p_l = lpos + (n_l / dl) * (p - lpos)  # the point of π_l on the ray l → p (eq. 2)
    return proj.jacobian(X).subs({X1: p_l[0], X2: p_l[1]}) * (W_l * g["y_l"])  # eq. (10)


@derivation("lloyd2007.m_point_2d", f"{SOURCE}, eqs. 2-19", "2D aliasing error m = (r_j/r_t) dj/dt of a point light, by the chain rule, in coordinates")
def m_point_2d() -> sp.Expr:
    """m = (r_j/r_t)·dj/dt = (r_j/r_t)·(∂j/∂p_e)(∂p_e/∂p)(∂p/∂p_l)(∂p_l/∂v)·dG/dt (eqs. 1, 6).

    Each Jacobian is obtained by differentiating the projections eqs. 3–5 themselves, in
    the coordinates of :func:`configuration_2d`.
    """
    g = configuration_2d()
    dj_dv = _dot(g["y_e"], _eye_jacobian(g) * _dp_dv_point(g)) / W_e  # eqs. (5), (7)
    return sp.cancel(sp.together(r_j / r_t * dj_dv * dGdt))


@derivation("lloyd2007.m_directional_2d", f"{SOURCE}, eqs. 19, 25", "2D aliasing error of a directional light (eq. 25), in coordinates")
def m_directional_2d() -> sp.Expr:
    """m for a directional light: light rays along v̂_l = −unit(s_v), p = p_l − (πp_l/πv̂_l)v̂_l.

    The light image plane has normal ẑ_l and the rays arrive from the side of n̂.
    """
    g = configuration_2d()
    X = sp.Matrix([X1, X2])
    vl = -_unit(s_v)
    proj = X - _dot(g["n"], X - g["p"]) / _dot(g["n"], vl) * vl  # eq. (25)
    dp_dv = proj.jacobian(X) * (W_l * g["y_l"])
    dj_dv = _dot(g["y_e"], _eye_jacobian(g) * dp_dv) / W_e
    return sp.cancel(sp.together(r_j / r_t * dj_dv * dGdt))


def directional_subs() -> dict:
    """cos φ_l and cos ψ_l of the directional light in coordinates (v̂_l = −unit(s_v))."""
    g = configuration_2d()
    toward = _unit(s_v)  # direction towards the light
    return {**g["subs"], cphi_l: _dot(g["z_l"], toward), cpsi_l: _dot(g["n"], toward)}


@derivation("lloyd2007.m_intuitive_2d", f"{SOURCE}, eqs. 20-24", "m = w'_l/w'_e from the widths of the beams projected on the surface")
def m_intuitive_2d() -> sp.Expr:
    """m = w′_l/w′_e: the lengths along the surface of one texel's and one pixel's beam.

    w′_l = |dp/dt|/r_t, with p the surface point hit by the light ray through p_l(v);
    w′_e = |dp/dj|/r_j, with p hit by the eye ray through the image point p_e(j).  Both
    move along the surface direction b̂ = (1, 0) (signed lengths).
    """
    g = configuration_2d()
    X = sp.Matrix([X1, X2])
    e, nh, p = g["e"], g["n"], g["p"]
    # eye ray through the image point X hits the surface at: X − (πX/π(X − e))(X − e)
    hit = X - _dot(nh, X - p) / _dot(nh, X - e) * (X - e)
    de = g["subs"][d_e]
    p_e = e + (n_e / de) * (p - e)  # image point of p
    dp_dj = hit.jacobian(X).subs({X1: p_e[0], X2: p_e[1]}) * (W_e * g["y_e"])
    w_e_proj = dp_dj[0] / r_j
    w_l_proj = _dp_dv_point(g)[0] * dGdt / r_t
    return sp.cancel(sp.together(w_l_proj / w_e_proj))


def projected_widths() -> tuple[sp.Expr, sp.Expr]:
    """(w′_e, w′_l) as signed lengths along the surface (for eqs. 23–24)."""
    g = configuration_2d()
    X = sp.Matrix([X1, X2])
    e, nh, p = g["e"], g["n"], g["p"]
    hit = X - _dot(nh, X - p) / _dot(nh, X - e) * (X - e)
    p_e = e + (n_e / g["subs"][d_e]) * (p - e)
    dp_dj = hit.jacobian(X).subs({X1: p_e[0], X2: p_e[1]}) * (W_e * g["y_e"])
    return sp.cancel(dp_dj[0] / r_j), sp.cancel(_dp_dv_point(g)[0] * dGdt / r_t)


@derivation("lloyd2007.delta_e", f"{SOURCE}, eqs. 27-30", "eye spacing delta_e = dv/dj of a point light, in coordinates")
def delta_e() -> sp.Expr:
    """δ_e = dv/dj = (dj/dv)⁻¹ (eq. 27's (Δv)_e = δ_e/r_j)."""
    return sp.cancel(dGdt * r_j / (r_t * m_point_2d()))


# --- §4.1: the parameterization of a spacing function (eqs. 41–43) ----------------------
nu = sp.Symbol("nu", positive=True)
delta = sp.Function("delta")


@derivation("lloyd2007.F_from_spacing", f"{SOURCE}, eqs. 41-43", "F(v) with (dF/dv)^-1 proportional to delta(v), F(0) = 0, F(1) = 1")
def F_from_spacing(spacing: sp.Expr | None = None, var: sp.Symbol = v, lo: sp.Expr = 0, hi: sp.Expr = 1) -> tuple[sp.Expr, sp.Expr]:
    """(F, ρ): F(v) = (1/ρ)∫_lo^v dν/δ(ν), ρ = ∫_lo^hi dν/δ(ν) (eqs. 42–43).

    With no ``spacing`` the result is in terms of an unspecified δ (an unevaluated integral).
    """
    d = delta(nu) if spacing is None else spacing.subs(var, nu)
    # an unspecified δ has no antiderivative to look for: the integrals stay unevaluated
    integral = sp.Integral if spacing is None else sp.integrate
    rho = integral(1 / d, (nu, lo, hi))
    F = integral(1 / d, (nu, lo, var)) / rho
    return F, rho


# --- §4.3: the minimum of B(μ) on the entry or exit face (eqs. 48–54) -------------------
def B_of_mu() -> sp.Expr:
    """B(μ) = c cosθ d_e(μ)/d_l(μ), eqs. 50–52 (ẑe·v̂l = ze_v, ẑe·(l − e) = ze_l, ẑl·v̂l = zl_v)."""
    de = -mu * ze_v - ze_l  # eq. (50)
    dl = -mu * zl_v  # eq. (51)
    return c * sp.cos(theta) * de / dl  # eq. (52)


@derivation("lloyd2007.dB_dmu", f"{SOURCE}, eq. 53", "derivative of the bound B(mu) along a light ray")
def dB_dmu() -> sp.Expr:
    """dB/dμ; its sign is that of ẑ_e·(l − e) because ẑ_l·v̂_l < 0, so B is monotone (eq. 54)."""
    return sp.factor(sp.diff(B_of_mu(), mu))


# --- §4.4: δ_b on end and side faces (eqs. 57–69) --------------------------------------
def cos_phi(coord: sp.Expr, l_c: sp.Expr) -> sp.Expr:
    """cos φ_l of a point light at height l_z over the face, along one face axis (eq. 57)."""
    return l_z / sp.sqrt((coord - l_c) ** 2 + l_z**2)


def delta_b_general(We, de_over_ne, Wl, cos_phil) -> sp.Expr:
    """Eq. 55 with the light image plane in the face (n_l/d_l = 1)."""
    return We * de_over_ne * sp.cos(theta) / (Wl * cos_phil)


def side_face() -> dict[str, sp.Expr]:
    """Side-face frame: y0 = n/cosθ, y1 = f/cosθ, W_e = 2n tanθ; x(u), y(v) (eqs. 59–60)."""
    We = 2 * n * sp.tan(theta)
    Y0, Y1 = n / sp.cos(theta), f / sp.cos(theta)
    return {"W_e": We, "y0": Y0, "y1": Y1}


def x0_of(yy):
    return -W_e * yy / (2 * y0)  # eq. (60)


def x1_of(yy):
    return W_e * yy / (2 * y0)  # eq. (60)


y_of_v = (y1 - y0) * v + y0
x_of_u = (x1_of(y1) - x0_of(y1)) * u + x0_of(y1)


@derivation("lloyd2007.delta_b_end", f"{SOURCE}, eqs. 55, 57-58", "error-bound spacing delta_b,t on an end face (point light)")
def delta_b_end() -> sp.Expr:
    """End face at depth d_e: W_ly = W_e d_e/n_e, so δ_b = cosθ/cos φ_ly(v) (eq. 58)."""
    return sp.together(delta_b_general(W_e, d_e / n_e, W_e * d_e / n_e, cos_phi(y, l_y)))  # one fraction


@derivation("lloyd2007.delta_b_side_s", f"{SOURCE}, eqs. 55, 59-61", "error-bound spacing delta_b,s on a side face (point light)")
def delta_b_side_s() -> sp.Expr:
    """Side face, s: d_e/n_e = y/y0 (eq. 59), W_lx = x1(y1) − x0(y1) = W_e y1/y0."""
    return sp.together(delta_b_general(W_e, y / y0, x1_of(y1) - x0_of(y1), cos_phi(x, l_x)))


@derivation("lloyd2007.delta_b_side_t", f"{SOURCE}, eqs. 55, 59, 62", "error-bound spacing delta_b,t on a side face (point light)")
def delta_b_side_t() -> sp.Expr:
    """Side face, t: d_e/n_e = y/y0, W_ly = y1 − y0."""
    return sp.together(delta_b_general(W_e, y / y0, y1 - y0, cos_phi(y, l_y)))


def zeta_integrands() -> dict[str, tuple[sp.Expr, sp.Symbol]]:
    """1/δ_b per unit of the face coordinate (dv = dy/(y1 − y0), du = dx/(x1(y1) − x0(y1)))."""
    return {
        "end": (1 / (delta_b_end() * (y1 - y0)), y),
        "side_s": (1 / (delta_b_side_s() * (x1_of(y1) - x0_of(y1))), x),
        "side_t": (1 / (delta_b_side_t() * (y1 - y0)), y),
    }


@derivation("lloyd2007.u_range_side", f"{SOURCE}, eq. 69", "u0(v), u1(v): the part of the u domain covered by a side face")
def u_range_side() -> sp.Matrix:
    """Solve x(u) = x0(y(v)) and x(u) = x1(y(v)) for u (eq. 69)."""
    sol = linear_solve([x_of_u - x0_of(y)], [u]), linear_solve([x_of_u - x1_of(y)], [u])
    return sp.Matrix([sol[0][u], sol[1][u]])


def _overhead(expr: sp.Expr) -> sp.Expr:
    """The directional light straight above the face: l_z → ∞ (cos φ_l → 1)."""
    return sp.limit(expr, l_z, sp.oo)


@derivation("lloyd2007.R_bound", f"{SOURCE}, eqs. 87-89", "R_b = rho_b of the error-bound parameterizations, overhead directional light")
def R_bound() -> sp.Matrix:
    """ρ_b = ∫ 1/δ_b with cos φ_l = 1: R_b,t^end, max_v ρ_b,s^side(v), R_b,t^side (eqs. 87–89)."""
    ends = _overhead(delta_b_end())
    r_end = sp.integrate(1 / ends, (v, 0, 1))
    s_side = _overhead(delta_b_side_s())
    u0, u1 = u_range_side()
    rho_s = sp.factor(sp.integrate(1 / s_side, (u, u0, u1)))  # constant in v
    assert sp.diff(rho_s, y) == 0
    t_side = _overhead(delta_b_side_t()).subs(y, y_of_v)
    rho_t = sp.integrate(1 / t_side, (v, 0, 1))
    # ∫ dv/(y0 + (y1 − y0)v) is a difference of logs: combine it into one
    rho_t = sp.factor(sp.logcombine(sp.expand_log(rho_t, force=True), force=True))
    return sp.Matrix([sp.factor(r_end), rho_s, rho_t])


def to_frustum(expr: sp.Expr) -> sp.Expr:
    """Substitute the side-face frame: y0 = n/cosθ, y1 = f/cosθ, W_e = 2n tanθ."""
    sf = side_face()
    return sp.simplify(expr.subs({y0: sf["y0"], y1: sf["y1"], W_e: sf["W_e"]}))


# --- §5: the four parameterizations on a side face (eqs. 74–78) -------------------------
p0 = (y1 + a) / (W_e * (y1 / y0))  # eq. (76)
p1 = sp.Rational(1, 2)
p2 = (y1 + a) / (y1 - y0)
p3 = -p2 * (y0 + a)


@derivation("lloyd2007.F_p", f"{SOURCE}, eqs. 75-76", "perspective parameterization (s, t) on a side face, as functions of (x, y)")
def F_p() -> sp.Matrix:
    """F_p = ((p0 x + p1 (y + a))/(y + a), (p2 (y + a) + p3)/(y + a)) (eq. 75, layout corrected)."""
    return sp.Matrix([(p0 * x + p1 * (y + a)) / (y + a), (p2 * (y + a) + p3) / (y + a)])


@derivation("lloyd2007.F_log", f"{SOURCE}, eq. 77", "logarithmic parameterization of a side face in t")
def F_log() -> sp.Expr:
    """t = ∫_{y0}^{y} dη/(η + a), normalised: δ linear in y (the y term of δ_b,t^side)."""
    eta_ = sp.Symbol("eta", positive=True)
    g = sp.integrate(1 / (eta_ + a), (eta_, y0, y))  # log(y + a) − log(y0 + a)
    combine = lambda q: sp.logcombine(sp.expand_log(q, force=True), force=True)  # noqa: E731
    return combine(g) / combine(g.subs(y, y1))


def spacing_of(F_expr: sp.Expr, coord: sp.Symbol, d_coord_d_param: sp.Expr) -> sp.Expr:
    """δ = (dF/dparam)⁻¹ with dparam = dcoord / d_coord_d_param."""
    return sp.factor(1 / (sp.diff(F_expr, coord) * d_coord_d_param))  # rational (in the logs too)


@derivation("lloyd2007.spacing_p", f"{SOURCE}, eqs. 96-97", "spacing functions delta_p,s and delta_p,t on a side face")
def spacing_p() -> sp.Matrix:
    """δ_p,s = (ds/du)⁻¹, δ_p,t = (dt/dv)⁻¹ with dx/du = x1(y1) − x0(y1), dy/dv = y1 − y0."""
    s_, t_ = F_p()
    return sp.Matrix([spacing_of(s_, x, x1_of(y1) - x0_of(y1)), sp.factor(spacing_of(t_, y, y1 - y0))])


@derivation("lloyd2007.spacing_log", f"{SOURCE}, eq. 102", "spacing function delta_log,t on a side face")
def spacing_log() -> sp.Expr:
    return spacing_of(F_log(), y, y1 - y0)


c0_s, c1_s, c2_s = sp.symbols("c0 c1 c2", real=True)


def F_lp_t_general() -> sp.Expr:
    """t = c0 log(c1 F_p,t + c2) with free constants (eq. 78)."""
    return c0_s * sp.log(c1_s * F_p()[1] + c2_s)


@derivation("lloyd2007.spacing_lp_general", f"{SOURCE}, eq. 104", "spacing of F_lp,t with free constants c0, c1, c2")
def spacing_lp_general() -> sp.Expr:
    return sp.factor(spacing_of(F_lp_t_general(), y, y1 - y0))


@derivation("lloyd2007.lp_roots", f"{SOURCE}, eq. 105", "the two roots in y of delta_lp,t")
def lp_roots() -> list[sp.Expr]:
    """Both roots of δ_lp,t's numerator in y (−a among them: y is a positive symbol, and a
    general solver would drop that negative root)."""
    def tidy(r: sp.Expr) -> sp.Expr:  # one fraction, its denominator's leading sign positive
        num, den = sp.fraction(sp.cancel(r))
        return (-num) / (-den) if den.could_extract_minus_sign() else num / den

    return sorted((tidy(r) for r in polynomial_roots(spacing_lp_general(), y)), key=sp.count_ops)


@derivation("lloyd2007.lp_constants", f"{SOURCE}, eqs. 107-108, 110", "c0, c1, c2 of F_lp,t with roots -a, -b, F(y0) = 0, F(y1) = 1")
def lp_constants() -> dict[sp.Symbol, sp.Expr]:
    """c1, c2 from λ1 = −b and c1 F_p,t(y0) + c2 = 1; then c0 from F_lp,t(y1) = 1."""
    lam1 = -(a + c1_s * p3 / (c1_s * p2 + c2_s))  # second root of eq. 104
    arg_y0 = (c1_s * F_p()[1] + c2_s).subs(y, y0)
    # λ1 = −b is linear in c1, c2 once multiplied by its denominator c1 p2 + c2 (≠ 0)
    s = linear_solve([sp.numer(sp.together(lam1 + b)), arg_y0 - 1], [c1_s, c2_s])
    c1v, c2v = sp.factor(s[c1_s]), sp.factor(s[c2_s])
    arg_y1 = sp.factor((c1v * F_p()[1] + c2v).subs(y, y1))
    return {c0_s: 1 / sp.log(arg_y1), c1_s: c1v, c2_s: c2v}


@derivation("lloyd2007.F_lp_t", f"{SOURCE}, eqs. 78, 106-110", "log+perspective parameterization in t with roots -a and -b")
def F_lp_t() -> sp.Expr:
    """F_lp,t = c0 log(c1 F_p,t + c2) = c0 log((y0+a)(y+b)/((y0+b)(y+a)))."""
    k = lp_constants()
    arg = sp.factor(sp.cancel((c1_s * F_p()[1] + c2_s).subs(k)))
    return k[c0_s] * sp.log(arg)


@derivation("lloyd2007.spacing_lp", f"{SOURCE}, eq. 109", "normalised spacing delta_lp,t with roots -a, -b")
def spacing_lp() -> sp.Expr:
    k = lp_constants()
    return sp.factor(sp.cancel(spacing_lp_general().subs({c1_s: k[c1_s], c2_s: k[c2_s]})))


@derivation("lloyd2007.lp_constants_b_inf", f"{SOURCE}, eq. 78", "c0, c1, c2 of F_lp,t as b -> infinity")
def lp_constants_b_inf() -> dict[sp.Symbol, sp.Expr]:
    return {key: sp.factor(sp.limit(val, b, sp.oo)) for key, val in lp_constants().items()}


@derivation("lloyd2007.F_lp_inverse", f"{SOURCE}, eq. 84", "inverse of F_lp,t: v(t) and the perspective coordinate p(t)")
def F_lp_inverse() -> sp.Matrix:
    """Solve t = F_lp,t for v (light-plane coordinate) and for p = F_p,t (shader coordinate)."""
    pp = sp.Symbol("p", real=True)
    k = lp_constants()
    # w.r.t. p: t = c0 log(c1 p + c2)
    # t = c0 log(c1 p + c2)  ⇔  c1 p + c2 = exp(t/c0): linear in p
    p_of_t = linear_solve([c1_s * pp + c2_s - sp.exp(t / c0_s)], [pp])[pp]
    # w.r.t. v: y(v) from t = c0 log(arg(y)), arg(y) = exp(t/c0)
    Ex = sp.Symbol("E", positive=True)
    arg = sp.factor(sp.cancel((c1_s * F_p()[1] + c2_s).subs(k)))
    (y_of_E,) = polynomial_roots(arg - Ex, y)  # arg is a Möbius map of y: one root
    # c0 = 1/log(A) with A = arg(y1), so exp(t/c0) = A**t
    (log_a,) = (1 / k[c0_s]).atoms(sp.log)
    v_of_t = sp.factor((y_of_E - y0) / (y1 - y0)).subs(Ex, log_a.args[0] ** t)
    return sp.Matrix([v_of_t, p_of_t])


# --- App. A: closed-form critical resolution factors, overhead directional light -------
def ratio_bound(spacing: sp.Expr, which: str) -> sp.Expr:
    """δ_l/δ_b for the overhead directional light (cos φ_l = 1), as a function of y."""
    bound = {"s": _overhead(delta_b_side_s()), "t": _overhead(delta_b_side_t()), "end": _overhead(delta_b_end())}[which]
    return sp.factor(spacing / bound)


def _decreasing_in_y(expr: sp.Expr) -> bool:
    """d expr/dy < 0 on a side face (y1 = y0 + gap, cosθ > 0), read from its factors."""
    gap, C = sp.symbols("gap C", positive=True)
    return bool(sp.factor(sp.diff(expr, y).subs({y1: y0 + gap, sp.cos(theta): C})).is_negative)


@derivation("lloyd2007.R_uniform", f"{SOURCE}, eqs. 90-95", "critical resolution factors of the uniform parameterization, overhead light")
def R_uniform() -> sp.Matrix:
    """δ_un = 1: R = max 1/δ_b; on side faces 1/δ_b decreases in y, so the max is at y = y0."""
    end = ratio_bound(sp.Integer(1), "end")
    rs, rt = ratio_bound(sp.Integer(1), "s"), ratio_bound(sp.Integer(1), "t")
    assert _decreasing_in_y(rs) and _decreasing_in_y(rt)
    return sp.Matrix([end, rs.subs(y, y0), rt.subs(y, y0)])


@derivation("lloyd2007.a_lispsm_side", f"{SOURCE}, App. A (text before eq. 99)", "a equating the end values of delta_p,t/delta_b,t: the LiSPSM parameter")
def a_lispsm_side() -> sp.Expr:
    r = ratio_bound(spacing_p()[1], "t")  # (y+a)²/y: convex, maximum at an end
    roots = polynomial_roots(r.subs(y, y0) - r.subs(y, y1), a)
    (root,) = [q for q in roots if q.is_positive]
    return root


@derivation("lloyd2007.R_perspective", f"{SOURCE}, eqs. 98-101", "min_a R_p,s, min_a R_p,t and min_a S_p on a side face, overhead light")
def R_perspective() -> sp.Matrix:
    """R_p,s(a) = value at y0 (δ_p,s/δ_b,s ∝ (y+a)/y decreases), minimal at a = 0;
    R_p,t(a) = max of the two end values, minimal where they are equal (a = √(y0 y1));
    S_p(a) = R_p,s R_p,t is constant for 0 ≤ a ≤ √(y0 y1) (where the far end binds t)."""
    rs = ratio_bound(spacing_p()[0], "s")
    rt = ratio_bound(spacing_p()[1], "t")
    rs_a = rs.subs(y, y0)
    gap = sp.Symbol("g", positive=True)
    assert sp.factor(sp.diff(rs_a, a).subs({y1: y0 + gap, sp.cos(theta): sp.Symbol("C", positive=True)})).is_positive  # grows with a: min at a = 0
    aL = a_lispsm_side()
    R_s_min = sp.factor(rs_a.subs(a, 0))
    R_t_min = sp.factor(rt.subs(y, y0).subs(a, aL))
    S_far = sp.factor(rs_a * rt.subs(y, y1))  # a ≤ a_L: far end binds R_t
    assert sp.diff(S_far, a) == 0
    return sp.Matrix([R_s_min, R_t_min, S_far])


@derivation("lloyd2007.R_log", f"{SOURCE}, eq. 103", "min_a R_log,t on a side face, overhead light")
def R_log() -> sp.Expr:
    """δ_log/δ_b,t ∝ (y + a)/y decreases in y: value at y0, which grows with a: a_opt = 0."""
    r0 = ratio_bound(spacing_log(), "t").subs(y, y0)
    return sp.factor(r0.subs(a, 0))


# --- printed forms ----------------------------------------------------------------------
def _printed() -> dict[str, Printed]:
    cos, tan, log = sp.cos(theta), sp.tan(theta), sp.log
    Lz2 = sp.sqrt(l_y**2 + l_z**2)
    return {
        "eq19": Printed("eq. (19)", r_j / r_t * dGdt * W_l / W_e * n_e / n_l * d_l / d_e * cphi_l / cphi_e * cpsi_e / cpsi_l, ""),
        "eq19_dir": Printed("eq. (19), directional (n_l/d_l → 1)", r_j / r_t * dGdt * W_l / W_e * n_e / d_e * cphi_l / cphi_e * cpsi_e / cpsi_l, ""),
        "eq23": Printed("eq. (23)", W_e * d_e * cphi_e / (r_j * n_e * cpsi_e), "w′_e = W_e d_e cosφ_e/(r_j n_e cosψ_e)"),
        "eq24": Printed("eq. (24)", W_l * dGdt / r_t * d_l * cphi_l / (n_l * cpsi_l), "w′_l = (W_l/r_t)(dG/dt) d_l cosφ_l/(n_l cosψ_l)"),
        "eq30": Printed("eq. (30)", W_e * n_l * d_e * cphi_e / (W_l * n_e * d_l * cphi_l), "δ̃_e"),
        "eq29": Printed("eq. (29)", W_e * n_l * d_e * cphi_e / (W_l * n_e * d_l * cphi_l) * cpsi_l / cpsi_e, "δ_e = δ̃_e cosψ_l/cosψ_e"),
        "eq31_widths": Printed("eq. (31)", sp.Symbol("w_e") / sp.Symbol("w_l"), "m̃ = r_j δ̃_l/(r_t δ̃_e) = w_e/w_l (δ̃_l read as δ_l)"),
        "eq53": Printed("eq. (53)", c * cos * ze_l * zl_v / (mu * zl_v) ** 2, "dB/dμ = (c cosθ) ẑe·(l−e)(ẑl·v̂l)/(μ ẑl·v̂l)²"),
        "eq57": Printed("eq. (57)", l_z / sp.sqrt((y - l_y) ** 2 + l_z**2), ""),
        "eq58": Printed("eq. (58)", cos * sp.sqrt((y - l_y) ** 2 + l_z**2) / l_z, "δ_b,t^end = cosθ/cosφ_ly"),
        "eq61": Printed("eq. (61)", y / y1 * cos * sp.sqrt((x - l_x) ** 2 + l_z**2) / l_z, "δ_b,s^side = (y/y1) cosθ/cosφ_lx"),
        "eq62": Printed("eq. (62)", W_e * y / ((y1 - y0) * y0) * cos * sp.sqrt((y - l_y) ** 2 + l_z**2) / l_z, ""),
        "eq66": Printed("eq. (66)", 1 / ((y1 - y0) * cos) * l_z * sp.asinh((y - l_y) / l_z), "C_b,t^end = 1/((y1−y0)cosθ)"),
        "eq67": Printed("eq. (67)", 1 / ((x1_of(y1) - x0_of(y1)) * cos) * l_z / y * sp.asinh((x - l_x) / l_z), "C_b,s^side = 1/((x1(y1)−x0(y1))cosθ)"),
        "eq68": Printed(
            "eq. (68)",
            -y0 / (W_e * cos) * l_z / Lz2 * log(2 / y * ((l_y * (l_y - y) + l_z**2) / (l_z * Lz2) + sp.sqrt((y - l_y) ** 2 + l_z**2) / l_z)),
            "C_b,t^side = y0/(W_e cosθ)",
        ),
        "C_end_2": Printed("eq. (66) constant, 2nd form", n_e / (W_e * d_e * cos), ""),
        "C_s_2": Printed("eq. (67) constant, 2nd form", n / (W_e * f * cos), ""),
        "C_t_2": Printed("eq. (68) constant, 2nd form", n / (W_e * cos**2), ""),
        "eq69": Printed("eq. (69)", sp.Matrix([(y1 - y) / (2 * y1), (y1 + y) / (2 * y1)]), ""),
        "eq77": Printed("eq. (77)", log((y + a) / (y0 + a)) / log((y1 + a) / (y0 + a)), ""),
        "eq78": Printed("eq. (78)", sp.Matrix([-1 / log((y1 + a) / (y0 + a)), -(y1 - y0) / (y1 + a), 1]), "c0, c1, c2 (c1 = (y0+a)/p3, c2 = −(y0+a)p2/p3)"),
        "eq78_c12_first": Printed("eq. (78), first forms", sp.Matrix([(y0 + a) / p3, -(y0 + a) * p2 / p3]), ""),
        "eq84": Printed("eq. (84)", 1 / (c1_s * (y1 - y0)) * sp.exp(t / c0_s) - (c1_s * y0 + c2_s) / (c1_s * (y1 - y0)), "v = d0 e^{d1 t} + d2"),
        "eq87": Printed("eq. (87)", 1 / cos, ""),
        "eq88": Printed("eq. (88)", 1 / cos, ""),
        "eq89": Printed("eq. (89)", sp.Matrix([y0 * log(y1 / y0) / (W_e * cos), log(f / n) / (2 * tan * cos**2), log(f / n) / sp.sin(2 * theta)]), "three forms"),
        "eq93": Printed("eq. (93)", 1 / cos, ""),
        "eq94": Printed("eq. (94)", sp.Matrix([y1 / (y0 * cos), f / (n * cos)]), ""),
        "eq95": Printed("eq. (95)", sp.Matrix([(y1 - y0) / (W_e * cos), (f - n) / (2 * n * tan * cos**2), (f / n - 1) / sp.sin(2 * theta)]), ""),
        "eq96": Printed("eq. (96)", sp.Matrix([(y + a) / (p0 * (x1_of(y1) - x0_of(y1))), (y + a) / (y1 + a)]), ""),
        "eq97": Printed("eq. (97)", sp.Matrix([-((y + a) ** 2) / (p2 * (y1 - y0)), (y + a) ** 2 / ((y0 + a) * (y1 + a))]), ""),
        "eq99": Printed("eq. (99)", 1 / cos, ""),
        "eq100": Printed(
            "eq. (100)",
            sp.Matrix([y0 * (y1 - y0) / (W_e * sp.sqrt(y0 * y1) * cos), (f - n) / (2 * tan * cos**3 * sp.sqrt(n * f)), (f / n - 1) / (sp.sin(2 * theta) * sp.sqrt(f / n) * cos)]),
            "three forms",
        ),
        "eq101": Printed("eq. (101)", sp.Matrix([(y1 - y0) / (W_e * cos**2), (f - n) / (2 * n * tan * cos**2), (f / n - 1) / sp.sin(2 * theta)]), "three forms"),
        "eq102": Printed("eq. (102)", log((y1 + a) / (y0 + a)) * (y + a) / (y1 - y0), ""),
        "eq103": Printed("eq. (103)", sp.Matrix([y0 * log(y1 / y0) / (W_e * cos), log(f / n) / sp.sin(2 * theta)]), ""),
        "eq104": Printed("eq. (104)", (y + a) * ((y + a) * (c1_s * p2 + c2_s) + c1_s * p3) / (c0_s * c1_s * p3 * (y1 - y0)), ""),
        "eq105": Printed("eq. (105)", sp.Matrix([-a, -(a + c1_s * p3 / (c1_s * p2 + c2_s))]), ""),
        "eq107": Printed("eq. (107)", -(y0 + a) * (a - b) / ((y0 + b) * p3), ""),
        "eq108": Printed("eq. (108)", (y0 + a) * (a * p2 - b * p2 + p3) / ((y0 + b) * p3), ""),
        "eq109": Printed("eq. (109)", -(y + a) * (y + b) / (c0_s * (a - b) * (y1 - y0)), ""),
        "eq110": Printed("eq. (110)", 1 / log((y0 + a) * (y1 + b) / ((y0 + b) * (y1 + a))), ""),
    }


PRINTED = _printed()
