"""Closed forms for today's engine schemes (issue 18), derived from their definitions.

None of these is printed by the engines' sources; each is derived here and the numeric
code in :mod:`aliasing.engines` is tested against it.

* ``engines.sphere_centre`` / ``engines.sphere_radius``: the minimal sphere through both
  corner rings of a square frustum slice [a, b] (t = tan θ): the centre on the axis
  equidistant from a near corner (√2·t·a off the axis, depth a) and a far corner.
* ``engines.vsm_m_axis``: the UE5 clipmap's error on the view axis.  Level
  L = floor(log2 d + B′), texel 2^(L+3)/16384, pixel footprint 2 t d/W,
  B′ = bias + log2(0.5·t·16384/W) (VirtualShadowMapClipmap.cpp).  Writing
  log2 d + B′ = L + φ, φ ∈ [0, 1): m = 2^(1 + bias − φ).
* ``engines.matched_texels``: mean texels per pixel of power-of-two resolution matching,
  ∫₀¹ 4^φ dφ = 3/ln 4, with m = 2^(−φ) and texels per pixel 1/m².

Example
-------
>>> import sympy as sp
>>> sp.simplify(vsm_m_axis())
2**(bias - phi + 1)
"""

from __future__ import annotations

import sympy as sp

from . import derivation

a, b, t = sp.symbols("a b t", positive=True)
z = sp.Symbol("z_c", real=True)
W, L, phi, bias = sp.symbols("W L phi bias", real=True)


@derivation("engines.sphere_centre", "issue 18 (derived)", "axis position z_c of the sphere through both corner rings of a frustum slice [a, b]")
def sphere_centre() -> sp.Expr:
    near_sq = (z - a) ** 2 + 2 * t**2 * a**2  # squared distance to a near corner
    far_sq = (z - b) ** 2 + 2 * t**2 * b**2
    (sol,) = sp.solve(sp.Eq(near_sq, far_sq), z)
    return sp.factor(sol)


@derivation("engines.sphere_radius", "issue 18 (derived)", "radius of that sphere (valid while z_c <= b; else sqrt(2) t b)")
def sphere_radius() -> sp.Expr:
    zc = sphere_centre()
    return sp.sqrt(sp.expand((b - zc) ** 2 + 2 * t**2 * b**2))


@derivation("engines.vsm_m_axis", "UE5 VirtualShadowMapClipmap.cpp + issue 18 (derived)", "VSM clipmap error on the view axis: 2^(1 + bias - phi)")
def vsm_m_axis() -> sp.Expr:
    b_prime = bias + sp.log(sp.Rational(1, 2) * t * 16384 / W, 2)
    d = 2 ** (L + phi - b_prime)  # log2 d + B′ = L + φ
    texel = 2 ** (L + 3) / 16384
    footprint = 2 * t * d / W
    return sp.powsimp(sp.expand_log(sp.simplify(texel / footprint), force=True), force=True)


@derivation("engines.matched_texels", "issue 18 (derived)", "mean texels per pixel of power-of-two resolution matching, 3/ln 4")
def matched_texels() -> sp.Expr:
    return sp.simplify(sp.integrate(4**phi, (phi, 0, 1)))
