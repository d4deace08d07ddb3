"""Closed forms for today's engine schemes, derived from their definitions.

None of these is printed by the engines' sources; each is derived here and the numeric
code in :mod:`aliasing.engines` is tested against it.

* ``engines.sphere_centre`` / ``engines.sphere_radius``: the minimal sphere through both
  corner rings of a square frustum slice [a, b] (t = tan θ): the centre on the axis
  equidistant from a near corner (√2·t·a off the axis, depth a) and a far corner.
* ``engines.centroid_radius``: the sphere Filament's ``stable`` mode, Babylon.js'
  ``stabilizeCascades`` and Godot 4 fit: centred on the 8 corners' average (on the axis at
  (a + b)/2), radius the largest corner distance, a far corner's:
  r² = ((b − a)/2)² + 2t²b².
* ``engines.far_corner_distance``: a far corner of [near, f] lies at f·√(1 + 2t²) from the
  camera, beyond Filament's ``shadowFar`` sphere {camera, f} for every t > 0.
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

from .registry import derivation
from .rewrite import polynomial_roots

a, b, t = sp.symbols("a b t", positive=True)
z = sp.Symbol("z_c", real=True)
W, L, phi, bias = sp.symbols("W L phi bias", real=True)


@derivation("engines.sphere_centre", "derived here", "axis position z_c of the sphere through both corner rings of a frustum slice [a, b]")
def sphere_centre() -> sp.Expr:
    near_sq = (z - a) ** 2 + 2 * t**2 * a**2  # squared distance to a near corner
    far_sq = (z - b) ** 2 + 2 * t**2 * b**2
    (sol,) = polynomial_roots(near_sq - far_sq, z)  # the z_c² terms cancel: linear
    return sp.factor(sol)


@derivation("engines.sphere_radius", "derived here", "radius of that sphere (valid while z_c <= b; else sqrt(2) t b)")
def sphere_radius() -> sp.Expr:
    zc = sphere_centre()
    return sp.sqrt(sp.expand((b - zc) ** 2 + 2 * t**2 * b**2))


@derivation("engines.vsm_m_axis", "UE5 VirtualShadowMapClipmap.cpp + derived here", "VSM clipmap error on the view axis: 2^(1 + bias - phi)")
def vsm_m_axis() -> sp.Expr:
    b_prime = bias + sp.log(sp.Rational(1, 2) * t * 16384 / W, 2)
    d = 2 ** (L + phi - b_prime)  # log2 d + B′ = L + φ
    texel = 2 ** (L + 3) / 16384
    footprint = 2 * t * d / W
    return sp.powsimp(sp.expand_log(sp.simplify(texel / footprint), force=True), force=True)


@derivation("engines.matched_texels", "derived here", "mean texels per pixel of power-of-two resolution matching, 3/ln 4")
def matched_texels() -> sp.Expr:
    return sp.factor(sp.expand_log(sp.integrate(4**phi, (phi, 0, 1)), force=True))  # 3/ln 4 = 3/(2 ln 2)


@derivation("engines.centroid_radius", "Filament ShadowMap.cpp computeBoundingSphere, Babylon.js _computeCascadeFrustum, Godot 4 + derived here", "radius of the sphere around the 8 corners' average of a frustum slice [a, b]")
def centroid_radius() -> sp.Expr:
    corners = [(sx * t * d, sy * t * d, d) for d in (a, b) for sx in (-1, 1) for sy in (-1, 1)]
    centre = [sp.Rational(1, 8) * sum(c[i] for c in corners) for i in range(3)]  # (0, 0, (a + b)/2)
    dist_sq = [sp.expand(sum((c[i] - centre[i]) ** 2 for i in range(3))) for c in corners]
    far_sq = dist_sq[-1]  # near corners: far_sq − near_sq = 2t²(b² − a²) ≥ 0 for b > a (tested)
    return sp.sqrt(sp.factor(far_sq))


@derivation("engines.far_corner_distance", "Filament ShadowMap.cpp computeFocusParams (shadowFar > 0) + derived here", "distance from the camera to a far corner of the view frustum at depth f")
def far_corner_distance() -> sp.Expr:
    f = sp.Symbol("f", positive=True)
    return sp.sqrt(sp.factor((t * f) ** 2 + (t * f) ** 2 + f**2))
