"""Lloyd et al. 2007 (LogPSM, UNC TR07-005) §3.4, eqs. 32–40: the 3D aliasing matrix M_a.

Derived with sympy from the projections themselves, in general 3D coordinates:

* eq. 32: the light image plane point p_l = p_l0 + u W_lx x̂_l + v W_ly ŷ_l;
* eq. 3 (point light) or eq. 25 (directional light): p_l projected onto the surface π;
* eq. 4: the surface point projected onto the eye image plane π_e;
* eqs. 33 and 5: the eye image coordinates i = x̂_e·(p_e − p_e0)/W_ex, j = ŷ_e·(p_e − p_e0)/W_ey;
* eq. 35: ∂i/∂s as the chain of the Jacobians of these maps (eqs. 36, 8, 9 or 26, 37, 38),
  eq. 34: M_a = diag(r_i, r_j) ∂i/∂s diag(1/r_s, 1/r_t), and the spacing matrices
  δ_l = ∂G/∂s (eq. 39) and δ_e = (∂i/∂u)⁻¹ (eq. 40).

Symbol map (paper → here → numeric API :mod:`aliasing.aliasing_matrix`):

==========================  =========================  ==================================
paper                       sympy                      numeric
==========================  =========================  ==================================
e, x̂_e, ŷ_e, ẑ_e              ``e``, ``x_e`` …           ``Camera(position, axes)``
l (point), l̂ (directional)   ``l``, ``l_hat``           ``Camera(position=…)``, ``direction=…``
n_e, n_l                    ``n_e``, ``n_l``           ``Camera.near``
W_ex, W_ey, W_lx, W_ly      same                       ``Camera.width``
π = (n̂ᵀ, −D), p on π        ``N``, ``p`` (D = n̂·p)      ``point``, ``normal``
∂G/∂s (eq. 38)              ``g11 … g22``              ``delta_l``
r_i, r_j, r_s, r_t          same                       ``res_image``, ``res_map``
==========================  =========================  ==================================

A camera looks along −ẑ; its image plane is π X = ẑ·(X − c) + n = 0 (π c = n, as in eq. 8).
The vectors are general symbols (no orthonormality is assumed): the chain rule holds for
any frames, and the numeric checks use orthonormal ones.
"""

from __future__ import annotations

import sympy as sp

from .registry import derivation
from . import lloyd2007 as L2

SOURCE = "Lloyd et al. 2007"


def _vec(name: str) -> sp.Matrix:
    return sp.Matrix(sp.symbols(f"{name}1:4", real=True))


def _dot(p: sp.Matrix, q: sp.Matrix) -> sp.Expr:
    return (p.T * q)[0]


X = _vec("X")
e, x_e, y_e, z_e = _vec("e"), _vec("xe"), _vec("ye"), _vec("ze")
l, x_l, y_l, z_l = _vec("l"), _vec("xl"), _vec("yl"), _vec("zl")
l_hat = _vec("lhat")  # towards the directional light
N, p, p_l0 = _vec("N"), _vec("p"), _vec("pl0")
n_e, n_l = sp.symbols("n_e n_l", positive=True)
W_ex, W_ey, W_lx, W_ly = sp.symbols("W_ex W_ey W_lx W_ly", positive=True)
r_i, r_j, r_s, r_t = sp.symbols("r_i r_j r_s r_t", positive=True)
u, v, s, t = sp.symbols("u v s t", real=True)
g11, g12, g21, g22 = sp.symbols("g11 g12 g21 g22", real=True)
D = sp.Symbol("D", real=True)

DELTA_L = sp.Matrix([[g11, g12], [g21, g22]])  # ∂G/∂s, eqs. (38)-(39)


# --- the maps themselves ---------------------------------------------------------------------
def light_plane_point() -> sp.Matrix:
    return p_l0 + u * W_lx * x_l + v * W_ly * y_l  # eq. (32)


def project_point_light(P: sp.Matrix, plane_N: sp.Matrix = N, plane_D: sp.Expr = D) -> sp.Matrix:
    """Eq. 3: P projected onto π = (n̂ᵀ, −D) along the line through the light l."""
    return P - (_dot(plane_N, P) - plane_D) / _dot(plane_N, P - l) * (P - l)  # eq. (3)


def project_directional(P: sp.Matrix, plane_N: sp.Matrix = N, plane_D: sp.Expr = D) -> sp.Matrix:
    """Eq. 25: P projected onto π along the direction l̂ (the L11 reading: ... (πP/πl̂) l̂)."""
    return P - (_dot(plane_N, P) - plane_D) / _dot(plane_N, l_hat) * l_hat  # eq. (25)


def project_eye(P: sp.Matrix) -> sp.Matrix:
    """Eq. 4: P projected onto π_e (π_e X = ẑ_e·(X − e) + n_e) along the line to the eye."""
    pi_e = lambda Q: _dot(z_e, Q - e) + n_e  # noqa: E731  (a point)
    return P - pi_e(P) / _dot(z_e, e - P) * (e - P)  # eq. (4)


def image_coordinates(P_e: sp.Matrix) -> sp.Matrix:
    """Eqs. 33 and 5 (the eye window origin p_e0 is taken at e; it only shifts i)."""
    return sp.Matrix([_dot(x_e, P_e - e) / W_ex, _dot(y_e, P_e - e) / W_ey])  # eqs. (33), (5)


def pipeline(light: str = "point") -> sp.Matrix:
    """i(u, v): light image plane → surface π → eye image plane → image coordinates."""
    proj = {"point": project_point_light, "directional": project_directional}[light]
    return image_coordinates(project_eye(proj(light_plane_point())))


# --- the Jacobians of eq. 35, each by differentiating its map ----------------------------------
@derivation("lloyd2007.jacobian_eye_3d", f"{SOURCE}, eqs. 4, 8 (3D)", "d p_e / d p of eq. 4 in 3D")
def jacobian_eye_3d() -> sp.Matrix:
    return project_eye(X).jacobian(X)


@derivation("lloyd2007.jacobian_light_3d", f"{SOURCE}, eqs. 3, 9 (3D)", "d p / d p_l of eq. 3 in 3D")
def jacobian_light_3d() -> sp.Matrix:
    return project_point_light(X).jacobian(X)


@derivation("lloyd2007.jacobian_directional_3d", f"{SOURCE}, eqs. 25-26 (3D)", "d p / d p_l of eq. 25 in 3D")
def jacobian_directional_3d() -> sp.Matrix:
    return project_directional(X).jacobian(X).applyfunc(sp.cancel)  # rational entries


def printed_jacobians_3d() -> dict[str, sp.Matrix]:
    """Eqs. 8, 9 and 26 (corrected, L11) as printed, read with 3×3 identities and π = (Nᵀ, −D)."""
    eye = sp.eye(3)
    pi_e_pt = lambda Q: _dot(z_e, Q - e) + n_e  # noqa: E731
    pi_pt = lambda Q: _dot(N, Q) - D  # noqa: E731
    eq8 = eye + pi_e_pt(X) / _dot(z_e, e - X) * eye - pi_e_pt(e) / _dot(z_e, e - X) ** 2 * ((e - X) * z_e.T)
    eq9 = eye - pi_pt(X) / _dot(N, X - l) * eye + pi_pt(l) / _dot(N, X - l) ** 2 * ((X - l) * N.T)
    eq26 = eye - l_hat * N.T / _dot(N, l_hat)
    return {"eq8": eq8, "eq9": eq9, "eq26": eq26}


def di_dpe() -> sp.Matrix:
    """Eq. 36, from differentiating eqs. 33 and 5."""
    return image_coordinates(X).jacobian(X)


def dpl_du() -> sp.Matrix:
    """Eq. 37, from differentiating eq. 32."""
    return light_plane_point().jacobian(sp.Matrix([u, v]))


def light_plane_point_of(P: sp.Matrix) -> sp.Matrix:
    """The point of the light image plane (ẑ_l·(X − l) = −n_l) on the ray from l through P."""
    d_l = _dot(z_l, l - P)
    return l + n_l / d_l * (P - l)


def chain_factors(light: str = "point", point: sp.Matrix = p, normal: sp.Matrix = N, p_light: sp.Matrix | None = None) -> list[sp.Matrix]:
    """The five factors of eq. 35 at the surface point ``point`` of π = (n̂ᵀ, −n̂·point).

    ``p_light`` is the light image plane point of ``point`` (by default the one on the plane
    ẑ_l·(X − l) = −n_l, :func:`light_plane_point_of`).
    """
    subs_plane = {D: _dot(normal, point), **dict(zip(N, normal))}
    at_p = dict(zip(X, point))
    dpe_dp = jacobian_eye_3d().xreplace(at_p)  # eq. (8)
    if light == "point":
        at_pl = dict(zip(X, light_plane_point_of(point) if p_light is None else p_light))
        dp_dpl = jacobian_light_3d().xreplace(at_pl).xreplace(subs_plane)  # eq. (9)
    else:
        dp_dpl = jacobian_directional_3d().xreplace(subs_plane)  # eq. (26), corrected
    return [di_dpe(), dpe_dp, dp_dpl, dpl_du(), DELTA_L]  # eqs. (36), (8), (9)/(26), (37), (38)


def _product(factors: list[sp.Matrix]) -> sp.Matrix:
    out = factors[0]
    for fac in factors[1:]:
        out = out * fac
    return out


def di_ds(light: str = "point", point: sp.Matrix = p, normal: sp.Matrix = N, p_light: sp.Matrix | None = None) -> sp.Matrix:
    return _product(chain_factors(light, point, normal, p_light))  # eq. (35)


def M_a(light: str = "point", point: sp.Matrix = p, normal: sp.Matrix = N) -> sp.Matrix:
    return sp.diag(r_i, r_j) * di_ds(light, point, normal) * sp.diag(1 / r_s, 1 / r_t)  # eq. (34)


@derivation("lloyd2007.M_a", f"{SOURCE}, eqs. 32-38", "3D aliasing matrix M_a of a point light at a surface point p (chain of eq. 35)")
def aliasing_matrix() -> sp.Matrix:
    return M_a("point")


@derivation("lloyd2007.M_a_directional", f"{SOURCE}, eqs. 25-26, 32-38", "3D aliasing matrix M_a of a directional light at a surface point p")
def aliasing_matrix_directional() -> sp.Matrix:
    return M_a("directional")


@derivation("lloyd2007.delta_e_3d", f"{SOURCE}, eq. 40", "eye spacing matrix delta_e = (di/du)^-1 of a point light")
def delta_e_3d(light: str = "point", point: sp.Matrix = p, normal: sp.Matrix = N) -> sp.Matrix:
    (a11, a12), (a21, a22) = _product(chain_factors(light, point, normal)[:-1]).tolist()
    return sp.Matrix([[a22, -a12], [-a21, a11]]) / (a11 * a22 - a12 * a21)  # eq. (40): (∂i/∂u)⁻¹, no simplification


def direct_jacobian(light: str = "point") -> tuple[sp.Matrix, dict]:
    """∂i/∂s of the composite map s → u = G(s) → … → i, by sympy's own chain rule.

    Returns the 2×2 Jacobian in terms of u, v, g11 … g22 and the substitution taking
    Derivative(G_k(s, t), ·) to g_kl.
    """
    G1, G2 = sp.Function("G1")(s, t), sp.Function("G2")(s, t)
    comp = pipeline(light).xreplace({u: G1, v: G2})
    jac = comp.jacobian(sp.Matrix([s, t]))
    subs = {sp.Derivative(G1, s): g11, sp.Derivative(G1, t): g12, sp.Derivative(G2, s): g21, sp.Derivative(G2, t): g22}
    return jac.xreplace(subs).xreplace({G1: u, G2: v}), subs


# --- the 2D configuration of §3.2 embedded in the y–z plane --------------------------------------
def embedding_2d(light: str = "point") -> dict:
    """Substitutions putting :func:`lloyd2007.configuration_2d` in the plane x = 0.

    2D (X1, X2) ↦ 3D (0, X1, X2); x̂_e = x̂_l = (1, 0, 0) so that (x̂, ŷ, ẑ) is right-handed;
    the surface point is the origin, its normal (0, 0, 1).
    """
    g = L2.configuration_2d()
    up = lambda w: [0, w[0], w[1]]  # noqa: E731
    vals = {**dict(zip(e, up(g["e"]))), **dict(zip(z_e, up(g["z_e"]))), **dict(zip(y_e, up(g["y_e"]))), **dict(zip(x_e, [1, 0, 0]))}
    vals.update({**dict(zip(z_l, up(g["z_l"]))), **dict(zip(y_l, up(g["y_l"]))), **dict(zip(x_l, [1, 0, 0]))})
    if light == "point":
        vals.update(dict(zip(l, up(g["l"]))))
    else:
        vals.update(dict(zip(l_hat, up(L2._unit(L2.s_v)))))
    vals.update({W_ey: L2.W_e, W_ly: L2.W_l, n_e: L2.n_e, n_l: L2.n_l, r_j: L2.r_j, r_t: L2.r_t})
    return vals


@derivation("lloyd2007.M_a_in_plane", f"{SOURCE}, eqs. 19, 34", "M_a of a point light for the 2D configuration embedded in the y-z plane")
def M_a_in_plane(light: str = "point") -> sp.Matrix:
    """M_a at the origin, surface normal ẑ, everything in x = 0, δ_l = diag(g11, dG/dt).

    Its t–j element is the 2D m of eq. 19 (:func:`lloyd2007.m_point_2d`), its off-diagonal
    elements vanish.
    """
    origin, nz = sp.zeros(3, 1), sp.Matrix([0, 0, 1])
    M = M_a(light, origin, nz).xreplace({g12: 0, g21: 0, g22: L2.dGdt}).xreplace(embedding_2d(light))
    return M.applyfunc(lambda q: sp.factor(sp.cancel(sp.together(q))))
