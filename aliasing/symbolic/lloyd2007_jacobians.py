"""Lloyd et al. 2007 §3, eqs. 8, 9 and 25–26: the projection Jacobians in general vector form, and
the directional light as the limit of a receding point light (§3.2).

Split from :mod:`aliasing.symbolic.lloyd2007` (whose 2D configuration they use); the 3D forms
are in :mod:`aliasing.symbolic.lloyd2007_matrix`.
"""

from __future__ import annotations

import sympy as sp

from .registry import derivation
from .lloyd2007 import L1, L2, SOURCE, W_e, X1, X2, _dot, _dp_dv_point, _eye_jacobian, _unit, configuration_2d, dGdt, n_l, r_j, r_t, s_l, s_v


def _plane_2d():
    """A general 2D line π = (n̂ᵀ, −D) and points X, e, l (symbols), for eqs. 8, 9, 25–26."""
    N1, N2, D = sp.symbols("N1 N2 D", real=True)
    Q1, Q2 = sp.symbols("Q1 Q2", real=True)  # e (eq. 8) or l (eq. 9)
    nh = sp.Matrix([N1, N2])
    X = sp.Matrix([X1, X2])
    Q = sp.Matrix([Q1, Q2])
    pi_pt = lambda p: _dot(nh, p) - D  # noqa: E731  π applied to a point
    pi_vec = lambda w: _dot(nh, w)  # noqa: E731  π applied to a vector
    return nh, X, Q, pi_pt, pi_vec


@derivation("lloyd2007.jacobian_eye", f"{SOURCE}, eq. 8", "d p_e / d p of the projection onto the eye image plane (eq. 4)")
def jacobian_eye() -> sp.Matrix:
    nh, X, e, pi_pt, pi_vec = _plane_2d()
    p_e = X - pi_pt(X) / pi_vec(e - X) * (e - X)  # eq. (4)
    return p_e.jacobian(X).applyfunc(sp.factor)  # rational entries: factor each


@derivation("lloyd2007.jacobian_light", f"{SOURCE}, eq. 9", "d p / d p_l of the projection from the light onto the surface (eq. 3)")
def jacobian_light() -> sp.Matrix:
    nh, X, lpos, pi_pt, pi_vec = _plane_2d()
    p = X - pi_pt(X) / pi_vec(X - lpos) * (X - lpos)  # eq. (3)
    return p.jacobian(X).applyfunc(sp.factor)


@derivation("lloyd2007.jacobian_directional", f"{SOURCE}, eqs. 25-26", "d p / d p_l of the directional projection p = p_l - (pi p_l / pi l) l")
def jacobian_directional() -> sp.Matrix:
    nh, X, ell, pi_pt, pi_vec = _plane_2d()
    p = X - pi_pt(X) / pi_vec(ell) * ell  # eq. (25)
    return p.jacobian(X).applyfunc(sp.factor)


def printed_jacobians() -> dict[str, sp.Matrix]:
    """Eqs. 8, 9 and 26 as printed, in the symbols of :func:`_plane_2d` (Q = e, l or l̂)."""
    nh, X, Q, pi_pt, pi_vec = _plane_2d()
    eye = sp.eye(2)
    eq8 = eye + pi_pt(X) / pi_vec(Q - X) * eye - pi_pt(Q) / pi_vec(Q - X) ** 2 * ((Q - X) * nh.T)
    eq9 = eye - pi_pt(X) / pi_vec(X - Q) * eye + pi_pt(Q) / pi_vec(X - Q) ** 2 * ((X - Q) * nh.T)
    eq26 = eye - eye / pi_vec(Q)  # "I − 1/(π l̂)", read literally
    eq26_corrected = eye - Q * nh.T / pi_vec(Q)
    return {"eq8": eq8, "eq9": eq9, "eq26": eq26, "eq26_corrected": eq26_corrected}


@derivation("lloyd2007.m_point_far_limit", f"{SOURCE}, §3.2 'Directional lights'", "limit of the point-light m as the light recedes along a direction, image plane fixed")
def m_point_far_limit() -> sp.Expr:
    """The point light at l = D·unit(s_v) with its image plane fixed in space (n_l = D ẑ_l·l̂ − k),
    D → ∞: the limit of :func:`aliasing.symbolic.lloyd2007.m_point_2d`, to be compared with
    :func:`aliasing.symbolic.lloyd2007.m_directional_2d`."""
    D = sp.Symbol("D", positive=True)
    k = sp.Symbol("k", real=True)
    toward = _unit(s_v)
    g = configuration_2d()
    # only dp/dv (eq. 10) depends on the light's position, and m is linear in it: take the
    # limit there.  Each component is rational in D with numerator and denominator of one
    # degree, so its limit is the ratio of their leading coefficients.
    dp_dv = _dp_dv_point(g).subs({L1: D * toward[0], L2: D * toward[1]}).subs(n_l, D * _dot(_unit(s_l), toward) - k)

    def at_infinity(q: sp.Expr) -> sp.Expr:
        num, den = (sp.Poly(part, D) for part in sp.fraction(sp.cancel(sp.together(q))))
        assert num.degree() <= den.degree()
        return num.LC() / den.LC() if num.degree() == den.degree() else sp.Integer(0)

    dj_dv = _dot(g["y_e"], _eye_jacobian(g) * dp_dv.applyfunc(at_infinity)) / W_e  # eqs. (5), (7)
    return sp.cancel(sp.together(r_j / r_t * dj_dv * dGdt))
