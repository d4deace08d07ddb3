"""Wimmer, Scherzer, Purgathofer 2004: LiSPSM error analysis, derived with sympy.

*Light Space Perspective Shadow Maps*, EGSR 2004, §4.1–4.4.

Symbol map (paper → here → numeric API):

==========================================  =================  =======================
paper                                       sympy symbol       numeric API
==========================================  =================  =======================
z_n, z_f (eye near, far)                    ``z_n``, ``z_f``   ``near``, ``far``
n (projection reference point to P's near)  ``n``              ``n_prime`` (Lloyd n′)
f = n + z_f − z_n (to P's far plane)        ``f``              (derived)
z′ (depth seen from the reference point)    ``z_p``            (derived)
γ (angle between light and view vectors)    ``gamma``          ``gamma`` in degrees
==========================================  =================  =======================

Wimmer's s is the shadow-map coordinate along the view-depth axis, which Lloyd 2006
calls t (Lloyd swaps s and t); Wimmer's dp/ds is therefore Lloyd's m_z up to the
constant 2·tanθ·z_n (see :func:`dp_ds` and the tests).  The viewport is on the near
plane with height 1 and resolutions are 1.
"""

from __future__ import annotations

import sympy as sp

from .registry import Printed, derivation
from .rewrite import linear_solve, polynomial_roots

z, z_n, z_f, n = sp.symbols("z z_n z_f n", positive=True)
z_p = sp.Symbol("z'", positive=True)
gamma = sp.Symbol("gamma", positive=True)

SOURCE = "Wimmer et al. 2004"


def _on_domain(expr: sp.Expr) -> sp.Expr:
    """Rewrite on the physical domain z_f > z_n, n > 0 for sign tests."""
    gap = sp.Symbol("gap", positive=True)
    return sp.factor(sp.together(expr.subs(z_f, z_n + gap)))  # a sign test needs factors only


def _depth_map(far: sp.Expr) -> sp.Expr:
    """Projective s(z′) = α + β/z′ with s(n) = 0 and s(far) = 1 (glFrustum depth)."""
    al, be = sp.symbols("alpha beta")
    s = al + be / z_p
    return s.subs(linear_solve([s.subs(z_p, n), s.subs(z_p, far) - 1], [al, be]))


@derivation("wimmer2004.s", f"{SOURCE}, eq. 2", "shadow-map depth coordinate s(z') of the perspective frustum P")
def s_of_z_prime() -> sp.Expr:
    """s(z′) of P mapping its near plane (z′ = n) to 0 and far plane (z′ = f) to 1 (eq. 2)."""
    return sp.together(_depth_map(n + z_f - z_n))  # rational: one common denominator


@derivation("wimmer2004.dp_ds", f"{SOURCE}, eq. 3", "perspective aliasing dp/ds along the view depth, light perpendicular")
def dp_ds() -> sp.Expr:
    """dp/ds = (z_n/z)·dz/ds (eq. 1 without projection aliasing) with z′ = z − z_n + n (eq. 3)."""
    ds_dz = sp.diff(s_of_z_prime().subs(z_p, z - z_n + n), z)
    return sp.factor(z_n / z / ds_dz)


@derivation("wimmer2004.dp_ds_uniform", f"{SOURCE}, §4.3", "eq. 3 with n -> infinity (uniform shadow map)")
def dp_ds_uniform() -> sp.Expr:
    """The uniform limit n → ∞ of eq. 3."""
    return sp.factor(sp.limit(dp_ds(), n, sp.oo))


@derivation("wimmer2004.dp_ds_psm", f"{SOURCE}, §4.3", "eq. 3 with n = z_n (perspective shadow map)")
def dp_ds_psm() -> sp.Expr:
    """The PSM case n = z_n of eq. 3: linear in z."""
    return sp.factor(dp_ds().subs(n, z_n))


@derivation("wimmer2004.dp_ds_minimum", f"{SOURCE}, §4.3", "location of the only positive extremum of eq. 3, a minimum")
def dp_ds_minimum() -> sp.Expr:
    """The stationary point of eq. 3 in z > 0 (for n > z_n): z = n − z_n, a minimum."""
    d = sp.Symbol("d", positive=True)
    e = dp_ds()
    (zs,) = [r for r in polynomial_roots(sp.diff(e, z), z) if _on_domain(r.subs(n, z_n + d)).is_positive]
    assert _on_domain(sp.diff(e, z, 2).subs(z, zs).subs(n, z_n + d)).is_positive
    return zs


@derivation("wimmer2004.n_opt", f"{SOURCE}, §4.3", "n equating dp/ds at z_n and z_f")
def n_opt() -> sp.Expr:
    """n_opt: the maxima of eq. 3 lie at z_n and z_f; make them equal (L∞-optimal)."""
    e = dp_ds()
    # the difference's numerator is a quadratic in n (its denominator is positive)
    roots = polynomial_roots(e.subs(z, z_n) - e.subs(z, z_f), n)
    (root,) = [r for r in roots if _on_domain(r).is_positive]
    return root


@derivation("wimmer2004.n_opt_general", f"{SOURCE}, §4.4", "n_opt for tilt angle gamma, with z' = (z - z_n)/sin(gamma) + n")
def n_opt_general() -> sp.Expr:
    """n′_opt for a tilt γ: redo the equal-maxima argument with z′ = (z − z_n)/sin γ + n."""
    far = n + (z_f - z_n) / sp.sin(gamma)
    ds_dz = sp.diff(_depth_map(far).subs(z_p, (z - z_n) / sp.sin(gamma) + n), z)
    e = sp.factor(z_n / z / ds_dz)
    # sin γ as a positive symbol keeps the equation a polynomial (a quadratic in n)
    sg = sp.Symbol("sin_gamma", positive=True)
    ends = (e.subs(z, z_n) - e.subs(z, z_f)).subs(sp.sin(gamma), sg)
    roots = polynomial_roots(ends, n)
    probe = {z_n: 1, z_f: 100, sg: sp.sin(sp.pi / 3)}  # pick the positive root
    (root,) = [r for r in roots if r.subs(probe).evalf() > 0]
    return sp.factor(root).subs(sg, sp.sin(gamma))


def _printed() -> dict[str, Printed]:
    f = n + z_f - z_n
    return {
        "eq2": Printed("eq. (2)", sp.Rational(1, 2) + (f + n) / (2 * (f - n)) + f * n / (z_p * (f - n)), "s = 1/2 + (f+n)/(2(f−n)) + fn/(z′(f−n))"),
        "ds_dz": Printed("§4.3", f * n / ((z - z_n + n) ** 2 * (f - n)), "ds/dz = fn/((z − z_n + n)²(f − n))"),
        "eq3": Printed("eq. (3)", (z - z_n + n) ** 2 / z * z_n * (z_f - z_n) / (n * (n + z_f - z_n)), ""),
        "uniform": Printed("§4.3", (z_f - z_n) * z_n / z, "n → ∞ gives (z_f − z_n) z_n / z"),
        "psm": Printed("§4.3", z * (z_f - z_n) / z_f, "n = z_n gives z (z_f − z_n)/z_f"),
        "minimum": Printed("§4.3", n - z_n, "a minimum at location n − z_n"),
        "n_opt": Printed("§4.3", z_n + sp.sqrt(z_f * z_n), "n_opt = z_n + √(z_f z_n)"),
        "n_opt_general": Printed("§4.4", (z_n + sp.sqrt(z_f * z_n)) / sp.sin(gamma), "n′_opt = n_opt / sin γ"),
        "gamma_original": Printed("§4.4", sp.pi, "“For γ = π, on the other hand, the original formula results.”"),
    }


PRINTED = _printed()
