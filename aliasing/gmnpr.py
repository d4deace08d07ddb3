"""Zhang et al. 2007 (GMNPR): λ selections and the generalized aliasing error, vectorized.

Closed forms of *Theory to Practice: Generalized Minimum-Norm Perspective Shadow Maps*
(ICEC 2007), each checked in the tests against the sympy derivation of
:mod:`aliasing.symbolic.zhang2007`, which also maps the paper's symbols to these names.

In the package convention Zhang's θ (light–view angle) is ``gamma`` folded by symmetry,
θ = min(γ, 180° − γ) ∈ [0°, 90°], and Zhang's φ is half the field of view, φ = fov/2.
λ = P_n/(P_f − P_n) is dimensionless; the warping parameter in world units is
n′ = λ·D with D the light-space depth of the warping frustum
(:func:`light_space_depth`).  Regime 1 is θ ≥ φ (Fig. 4 left), regime 2 θ < φ (Fig. 4
right; the light is within the field of view of the view direction or its reverse).

Importing this module registers three warping rules in :mod:`aliasing.warping`:
``gmnpr``, ``glpr`` and ``lispsm-zhang``.  Their n′ is P's near-plane distance in light
space; off the overhead case it can be below ``near`` (GLPR's n′ = n sin(θ − φ)/cos φ).

All functions broadcast over their array arguments.  Angles are in degrees, lengths in
world units.

Example
-------
>>> from aliasing.gmnpr import lambda_gmnpr, lambda_lispsm
>>> round(float(lambda_gmnpr(1.0, 100.0, 60.0, 45.0)), 5), round(float(lambda_lispsm(1.0, 100.0, 60.0, 45.0)), 5)
(0.06625, 0.13985)
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from ._stable import sqrt_product
from .parameterizations import _depths
from .warping import register
from .view import View, theta_of

__all__ = [
    "generalized_error",
    "lambda_glpr",
    "lambda_gmnpr",
    "lambda_lispsm",
    "lambda_optimal",
    "light_space_depth",
]

Array = NDArray[np.float64]


class _Geometry(NamedTuple):
    """The Fig. 4 model for one (near, far, fov, gamma), broadcast."""

    n: Array
    f: Array
    regime1: Array  # θ ≥ φ
    beyond: Array  # θ > φ (strict)
    theta: Array  # Zhang's θ [rad], folded to [0, π/2]
    phi: Array  # Zhang's φ = fov/2 [rad]
    sin_t: Array
    cos_t: Array
    tan_p: Array
    z_min: Array  # light-space z of P's near plane, measured from the eye
    depth: Array  # D = P_f − P_n


def _geometry(near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike) -> _Geometry:
    n, f = check.frustum(near, far)
    fov_deg = np.asarray(fov.fov, dtype=float) if isinstance(fov, View) else check.fov(fov)  # a View: validated there
    g = check.closed_range(gamma, "gamma", 0.0, 180.0, " degrees")
    theta_deg = np.minimum(g, 180.0 - g)  # symmetry (§2): only 0 ≤ θ ≤ 90° matters
    regime1 = theta_deg >= fov_deg / 2  # compared in degrees, so θ = φ is exact
    theta, phi = np.radians(theta_deg), theta_of(fov if isinstance(fov, View) else fov_deg)
    sin_t, cos_t, tan_p, cos_p = np.sin(theta), np.cos(theta), np.tan(phi), np.cos(phi)
    # smallest corner z_L: (n, −n tanφ) in regime 1, (f, −f tanφ) in regime 2; x·sin(θ−φ)/cosφ
    z_min = np.where(regime1, n, f) * np.sin(theta - phi) / cos_p
    # D as sums of non-negative terms (no cancellation as f/n → 1 or θ → 90°)
    depth = np.where(regime1, (f - n) * sin_t + (f + n) * tan_p * cos_t, 2 * f * tan_p * cos_t)
    return _Geometry(n, f, regime1, theta_deg > fov_deg / 2, theta, phi, sin_t, cos_t, tan_p, z_min, depth)


@check.public
def light_space_depth(near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike = 90.0) -> Array:
    """Light-space depth D = P_f − P_n of the warping frustum fitted to the view frustum.

    Zhang et al. 2007, Fig. 4 and the denominators of eq. 9: P's near and far planes lie
    at the smallest and largest light-space z of the view frustum's corners.

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180 (Zhang's φ = fov/2).
    gamma : array_like, optional
        Angle between view direction and direction towards the light [deg], 0 ≤ γ ≤ 180
        (default 90, overhead); Zhang's θ = min(γ, 180 − γ).

    Returns
    -------
    ndarray
        D [world units]: (f − n) sinθ + (f + n) tanφ cosθ for θ ≥ φ, 2 f tanφ cosθ for
        θ < φ; f − n for an overhead light.

    Example
    -------
    >>> light_space_depth(1.0, 100.0, 60.0, [90.0, 30.0, 0.0]).round(4)
    array([ 99.    , 100.    , 115.4701])
    """
    return _geometry(near, far, fov, gamma).depth


@check.public
def lambda_optimal(near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike = 90.0) -> Array:
    """λ equating the error at the near and far plane, F(n) = F(f) (Zhang et al. 2007, eqs. 3–4).

    λ1(θ) for θ ≥ φ and λ2(θ) for θ < φ.  λ2 falls to 0 at tanθ0 = tanφ·f/(f + √(fn)) and
    is negative below θ0 (−1/2 at θ = 0): there the equalising frustum does not exist,
    which is why GMNPR replaces λ2 (:func:`lambda_gmnpr`).

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    gamma : array_like, optional
        Light–view angle γ [deg], 0 ≤ γ ≤ 180 (default 90, overhead).

    Returns
    -------
    ndarray
        λ [dimensionless]; n′ = λ·D where positive.

    Example
    -------
    >>> lambda_optimal(1.0, 100.0, 60.0, [90.0, 30.0, 0.0]).round(5)
    array([ 0.11111,  0.05   , -0.5    ])
    """
    g = _geometry(near, far, fov, gamma)
    root = sqrt_product(g.f, g.n)  # √(fn) without under- or overflow of f·n
    # λ1 of eq. 4 multiplied through by sinθ: (√(fn) sinθ + n sinθ(1 − tanφ/tanθ))/D
    lam1 = (root * g.sin_t + g.z_min) / g.depth  # eq. (4), λ1
    with np.errstate(divide="ignore", invalid="ignore"):
        lam2 = (g.f + root) / (2 * g.f) * np.tan(g.theta) / g.tan_p - 0.5  # eq. (4), λ2
    return np.where(g.regime1, lam1, lam2)


@check.public
def lambda_gmnpr(near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike = 90.0) -> Array:
    """λ_GMNPR (Zhang et al. 2007, eq. 8): eq. 4's λ1 for θ ≥ φ, λ2* of eq. 7 below.

    λ2*(θ) = (√(fn)/(2f))/tan(πθ/(4φ)) joins λ1 continuously at θ = φ (eq. 5) and grows
    to ∞ (a uniform map) as θ → 0 (eq. 6).  For θ < φ it no longer equalises F(n) and F(f).

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    gamma : array_like, optional
        Light–view angle γ [deg], 0 ≤ γ ≤ 180 (default 90, overhead).

    Returns
    -------
    ndarray
        λ [dimensionless], > 0; ``inf`` at γ = 0° and 180°.

    Example
    -------
    >>> lambda_gmnpr(1.0, 100.0, 60.0, [90.0, 30.0, 10.0]).round(5)
    array([0.11111, 0.05   , 0.1866 ])
    """
    g = _geometry(near, far, fov, gamma)
    root = sqrt_product(g.f, g.n)  # √(fn) without under- or overflow of f·n
    lam1 = (root * g.sin_t + g.z_min) / g.depth  # eq. (8) = eq. (4), λ1
    with np.errstate(divide="ignore"):
        lam2_star = root / (2 * g.f) / np.tan(np.pi * g.theta / (4 * g.phi))  # eq. (7): λ1(φ)/tan(πθ/(4φ))
    return np.where(g.regime1, lam1, lam2_star)


@check.public
def lambda_lispsm(near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike = 90.0) -> Array:
    """λ_LiSPSM = P_n/(P_f − P_n) with P_n = (n + √(fn))/sinθ (Zhang et al. 2007, eq. 9).

    Wimmer 2004 §4.4's n′_opt = n_opt/sin γ normalised by the model's depth D.  It equals
    λ_GMNPR only at θ = 90°; below, its warp is too weak and F(n) > F(f).

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    gamma : array_like, optional
        Light–view angle γ [deg], 0 ≤ γ ≤ 180 (default 90, overhead).

    Returns
    -------
    ndarray
        λ [dimensionless], > 0; ``inf`` at γ = 0° and 180°.

    Example
    -------
    >>> lambda_lispsm(1.0, 100.0, 60.0, [90.0, 30.0]).round(5)
    array([0.11111, 0.22   ])
    """
    g = _geometry(near, far, fov, gamma)
    with np.errstate(divide="ignore"):
        den = g.sin_t * g.depth
        num = g.n + sqrt_product(g.f, g.n)
        return np.where(np.isfinite(den) & (den >= np.finfo(float).tiny), num / den, num / g.depth / g.sin_t)  # eq. (9); sinθ·D underflows for tiny θ and D


@check.public
def lambda_glpr(near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike = 90.0) -> Array:
    """λ_GLPR: the λ with F(z) ∝ z (Zhang et al. 2007, §3, GLPR; no formula printed).

    F ∝ z iff ϕ(λ, θ) = 0 in eq. 2: λ = n(1 − tanφ/tanθ)/(f − n + (f + n) tanφ/tanθ),
    the centre of projection at the eye's light-space z.  It gives PSM (n′ = n) at
    θ = 90° and tends to 0 as θ → φ (the "over-strong warping" of §3–4).

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    gamma : array_like, optional
        Light–view angle γ [deg], 0 ≤ γ ≤ 180 (default 90, overhead).

    Returns
    -------
    ndarray
        λ [dimensionless] for θ > φ; **NaN where GLPR does not exist**, θ ≤ φ: there
        ϕ = 0 needs λ = (tanθ/tanφ − 1)/2 ≤ 0, which no warping frustum realises.

    Example
    -------
    >>> lambda_glpr(1.0, 100.0, 60.0, [90.0, 60.0, 30.0]).round(5)
    array([0.0101 , 0.00503,     nan])
    """
    g = _geometry(near, far, fov, gamma)
    lam = g.z_min / g.depth  # ϕ = 0: λD = z_L,min = n sin(θ − φ)/cosφ
    return np.where(g.beyond, lam, np.nan)  # λ ≤ 0 for θ ≤ φ: GLPR does not exist


@check.public
def generalized_error(lam: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike, z: ArrayLike) -> Array:
    """Generalized perspective aliasing error F(λ, θ, z) (Zhang et al. 2007, eq. 2).

    F = ψ(λ, θ)(z + ϕ(λ, θ))²/z = (1/tanφ)·dz/(z ds) for the point at eye depth z on the
    central view ray, with the warping frustum fitted to the view frustum (Fig. 4).  The
    screen is normalised to half-height 1, so for an overhead light F is twice Lloyd
    2006's m_z at unit resolutions.

    Parameters
    ----------
    lam : array_like
        λ = P_n/(P_f − P_n) [dimensionless], 0 < λ ≤ ∞ (∞: a uniform map).
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    gamma : array_like
        Light–view angle γ [deg], 0 ≤ γ ≤ 180.
    z : array_like
        Eye depth [world units], near ≤ z ≤ far.

    Returns
    -------
    ndarray
        F [dimensionless]; ``inf`` at γ = 0° and 180°, where the view ray runs along a
        single texel beam.

    Example
    -------
    >>> generalized_error(lambda_gmnpr(1, 100, 60, 60), 1, 100, 60, 60, [1.0, 10.0, 100.0]).round(3)
    array([18.186,  6.012, 18.186])
    """
    zz, n, f = _depths(z, near, far)
    lam_ = check.positive(lam, "lam", allow_inf=True)
    g = _geometry(n, f, fov, gamma)
    # q = z sinθ − z_L,min ≥ 0, the view-ray point's light-space distance from P's near plane,
    # written without cancellation in each regime
    q = np.where(g.regime1, (zz - g.n) * g.sin_t + g.n * g.tan_p * g.cos_t, zz * g.sin_t + g.f * np.sin(g.phi - g.theta) / np.cos(g.phi))
    # eq. (2): ψ(z + ϕ)²/z = z′²/(tanφ D sinθ z λ(λ+1)), z′ = λD + q; divided through by λ²
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        r = 1.0 / lam_  # r = 1/λ, 0 for a uniform map
        den = (1 + r) * g.tan_p * g.sin_t * zz
        err = (g.depth + q * r) ** 2 / ((1 + r) * g.tan_p * g.depth * g.sin_t * zz)  # eq. (2)
        # where D or its square overflow (far near 1e308) that is inf/inf: the same as (D + qr)(1 + qr/D)/den
        err = np.where(np.isnan(err), (g.depth + q * r) * (1 + q * r / g.depth) / den, err)
        # where r = 1/λ itself overflows those products (λ near 1e-308): eq. (2) undivided
        err = np.where(np.isnan(err), (lam_ * g.depth + q) ** 2 / (lam_ * (lam_ + 1) * g.tan_p * g.depth * g.sin_t * zz), err)
        # where (q/λ)² overflowed although F ~ 1/λ is finite (λ < 1e-154): eq. (2) in dimensionless factors,
        # F = (a/λ)·(a/(1 + λ))·(D/z)/(tanφ sinθ), a = z′/D = λ + q/D ∈ [λ, λ + 1]; elsewhere the form above, bit for bit
        a = lam_ + q / g.depth
        uniform = np.isinf(lam_)  # λ = ∞: both ratios are 1 (F = D/(tanφ sinθ z))
        per_step = np.where(uniform, 1.0, a / (1 + lam_)) * (g.depth / zz) / g.tan_p / g.sin_t  # F·λ/a
        growth = np.where(uniform, 1.0, a / lam_)  # ≥ 1; inf only for subnormal λ
        factored = np.where(np.isinf(growth), per_step * a / np.where(uniform, 1.0, lam_), per_step * growth)
        return np.where(np.isfinite(err) | np.isinf(g.depth), err, factored)  # where D overflows (far near 1e308) F stays inf


def _n_prime(lam: Array, near: ArrayLike, far: ArrayLike, fov: ArrayLike, gamma: ArrayLike, depth: ArrayLike | None) -> Array:
    """n′ = λ·D [world units]; ``inf`` (no warping) where λ is NaN or not positive."""
    d = light_space_depth(near, far, fov, gamma) if depth is None else check.positive(depth, "depth")
    with np.errstate(invalid="ignore"):
        usable = np.isfinite(lam) & (lam > 0)
        return np.where(usable, np.where(usable, lam, 1.0) * d, np.inf)


@register("gmnpr", "Zhang et al. 2007, eq. 8", "generalized minimum-norm PR: lambda_GMNPR times the light-space depth D")
def _gmnpr(near: ArrayLike, far: ArrayLike, *, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None) -> Array:
    """n′ = λ_GMNPR·D [world units]; ``fov`` [deg] defaults to the paper's 60°, ``depth`` to
    :func:`light_space_depth`.  ``inf`` at γ = 0° and 180° (uniform map)."""
    return _n_prime(lambda_gmnpr(near, far, fov, gamma), near, far, fov, gamma, depth)


@register("glpr", "Zhang et al. 2007, §3 (GLPR, F ~ z)", "generalized linear PR: F proportional to z; no warping (inf) where theta <= fov/2")
def _glpr(near: ArrayLike, far: ArrayLike, *, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None) -> Array:
    """n′ = λ_GLPR·D [world units]; where GLPR does not exist (θ ≤ φ, λ_GLPR = NaN) it
    returns ``inf``, a uniform map, rather than NaN.  ``fov`` defaults to 60°."""
    return _n_prime(lambda_glpr(near, far, fov, gamma), near, far, fov, gamma, depth)


@register("lispsm-zhang", "Zhang et al. 2007, eq. 9; Wimmer et al. 2004 §4.4", "LiSPSM's lambda in Zhang's model: (n + sqrt(fn))/sin(theta) normalised by D, times D")
def _lispsm_zhang(near: ArrayLike, far: ArrayLike, *, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None) -> Array:
    """n′ = λ_LiSPSM·D [world units]; with the default depth this is (n + √(fn))/sinθ.
    ``fov`` defaults to 60°; ``inf`` at γ = 0° and 180°."""
    return _n_prime(lambda_lispsm(near, far, fov, gamma), near, far, fov, gamma, depth)
