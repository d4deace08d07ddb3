"""Warping-parameter rules: n′ for the perspective warping frustum, in one registry.

A rule maps a view frustum (and, for later rules, a light direction) to the distance
n′ [world units] from the warping frustum's centre of projection to the eye's near
plane.  ``n′ = near`` is PSM, ``n′ = inf`` a uniform (orthographic) shadow map.
Adding a scheme is adding one :func:`register` entry; :func:`warping_parameter` is the
single dispatcher.

Example
-------
>>> from aliasing.warping import warping_parameter
>>> float(warping_parameter("lispsm", near=1.0, far=100.0))
11.0
>>> float(warping_parameter("eta", near=1.0, far=100.0, eta=1.0))
1.0
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from ._stable import product_ratio, sqrt_product
from .view import View


@dataclass(frozen=True)
class WarpingRule:
    """A registered warping-parameter rule."""

    name: str
    func: Callable[..., NDArray[np.float64]]
    source: str
    summary: str
    bounded: bool = False
    """Promises S̄ never above Standard's: :func:`aliasing.schemes.evaluate` keeps the rule's
    n′ only for the maps and directions where its S̄ is at most the uniform map's, and uses
    n′ = ∞ (the uniform map) elsewhere."""


WARPING_RULES: dict[str, WarpingRule] = {}


def register(name: str, source: str, summary: str, bounded: bool = False) -> Callable:
    """Decorator adding a rule ``func(near, far, **options) -> n′`` to the registry.

    ``bounded``: the rule promises S̄ never above Standard's (:attr:`WarpingRule.bounded`).
    """

    def wrap(func: Callable[..., NDArray[np.float64]]) -> Callable[..., NDArray[np.float64]]:
        if name in WARPING_RULES:
            raise RuntimeError(f"warping rule {name!r} registered twice")
        WARPING_RULES[name] = WarpingRule(name, func, source, summary, bounded)
        return func

    return wrap


CONTEXT = ("fov", "gamma", "depth", "azimuth")
"""Geometry a rule may take besides near and far: the full field of view [deg], the angle
γ between view direction and direction to the light [deg], the light-space depth D
[world units] of the body the warping frustum is fitted to (f − n for an overhead light),
and the light's azimuth around the view direction [deg] (:func:`aliasing.geometry.direction_angles`),
for rules that use the direction's full geometry rather than γ alone."""


@check.public  # broadcast errors name the parameters
def warping_parameter(method: str, near: ArrayLike, far: ArrayLike, **options: ArrayLike) -> NDArray[np.float64]:
    """n′ [world units] chosen by the named rule; broadcasts over its array arguments.

    Parameters
    ----------
    method : str
        A name in :data:`WARPING_RULES` (case-insensitive), e.g. ``uniform``, ``psm``,
        ``lispsm``, ``eta``.
    near, far : array_like
        Eye near and far plane distances [world units], ``0 < near < far``.
    **options
        The geometry of :data:`CONTEXT` (``fov``, ``gamma``, ``depth``, ``azimuth``), passed on only to
        rules that use it, and rule-specific parameters (``eta`` for the η rule), which
        are an error for rules that do not take them.

    Returns
    -------
    ndarray
        n′ [world units], the distance from the centre of projection to the warping
        frustum's near plane; ``inf`` for no warping.

    Raises
    ------
    ValueError
        For an unknown method, an option the rule does not take, or a value out of range.
    """
    key = check.choice(method, "warping method", WARPING_RULES)
    rule = WARPING_RULES[key]
    accepted = _accepted(rule.func)
    unknown = set(options) - accepted - set(CONTEXT)
    if unknown:
        own = sorted(accepted - set(CONTEXT))
        raise ValueError(f"warping method {key!r} takes options {own or 'none'}, not {sorted(unknown)}")
    return rule.func(near, far, **{k: v for k, v in options.items() if k in accepted})


@functools.lru_cache(maxsize=None)
def _accepted(func: Callable) -> frozenset[str]:
    """The options a rule takes besides near and far (its signature, read once)."""
    return frozenset(inspect.signature(func).parameters) - {"near", "far"}


@check.public  # broadcast errors name the parameters
def n_prime_lispsm(near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    """LiSPSM's n′ = n + √(fn) for an overhead light [world units].

    Wimmer et al. 2004 §4.3 (n_opt); Lloyd et al. 2006 §4.1.  It equates the near- and
    far-plane maxima of m_z (see ``aliasing derive lloyd2006.n_prime_lispsm``).

    Example
    -------
    >>> float(n_prime_lispsm(1.0, 100.0))
    11.0
    """
    n, f = check.frustum(near, far)
    return n + sqrt_product(f, n)  # √(fn); f·n under- or overflows for near below 1e-154 or above 1e154


def _n_gamma(near: NDArray[np.float64], far: NDArray[np.float64], depth: ArrayLike | None) -> NDArray[np.float64]:
    """Lloyd 2007 App. B's light-space "near" n_γ = W_ly/(f/n − 1): ``near`` when depth = f − n."""
    if depth is None:
        return near
    d = check.positive(depth, "depth")
    return product_ratio(d, near, far - near)  # W_ly/(α − 1), α = f/n; d·near under- or overflows for extreme frusta


@check.public  # broadcast errors name the parameters
def n_prime_from_eta(eta: ArrayLike, near: ArrayLike, far: ArrayLike, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    """n′(η) [world units], Lloyd et al. 2006 eq. 11 (App. B); Lloyd et al. 2007 eq. 120.

    η = −1 gives n′ = ∞ (uniform), η = 0 the LiSPSM-like n_γ(1 + √a), η = 1 the PSM-like
    n′ = n_γ, with a = f/n.  For an overhead light n_γ = n; for a light in general position
    Lloyd 2007 measures the warp in the light image plane, where the frustum's extent is
    ``depth`` = W_ly, and uses n_γ = W_ly/(a − 1) (so that [n_γ, n_γ + W_ly] has the same
    ratio a).  M_z is linear in η on each half.  Eq. 120 is misprinted (docs/ERRATA.md L7).

    Parameters
    ----------
    eta : array_like
        Warping parameter η ∈ [−1, 1].
    near, far : array_like
        Eye near and far distances [world units], ``0 < near < far``.
    depth : array_like, optional
        Light-space depth W_ly of the frustum [world units]; default ``far − near``.

    Example
    -------
    >>> n_prime_from_eta([-1.0, 0.0, 1.0], 1.0, 100.0)
    array([inf, 11.,  1.])
    """
    e = check.closed_range(eta, "eta", -1.0, 1.0)
    n, f = check.frustum(near, far)
    ng = _n_gamma(n, f, depth)
    a = f / n
    ra = np.sqrt(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        lower = ng * (ra + 1 - e * (a - 1)) / (e + 1)  # eq. (11), −1 ≤ η ≤ 0
        upper = ng * (ra + 1) / (e * ra + 1)  # eq. (11), 0 < η ≤ 1
    return np.where(e <= 0, np.where(e == -1, np.inf, lower), upper)


@check.public  # broadcast errors name the parameters
def eta_from_n_prime(n_prime: ArrayLike, near: ArrayLike, far: ArrayLike, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    """η(n′), the inverse of eq. 11 (Lloyd et al. 2006 App. B; Lloyd 2007 eq. 120).

    n′ below n_γ (warping stronger than PSM) has no η; it is an error.

    Example
    -------
    >>> eta_from_n_prime([np.inf, 11.0, 1.0], 1.0, 100.0)
    array([-1.,  0.,  1.])
    """
    n, f = check.frustum(near, far)
    ng = _n_gamma(n, f, depth)
    npr = check.as_float_array(n_prime, "n_prime")
    if (npr < ng * (1 - 1e-12)).any():
        raise ValueError("n_prime must be in [n_γ, inf] (n_γ = near for an overhead light; PSM is n_γ)")
    return eta_checked(npr, n, f, ng)


def eta_checked(npr: NDArray[np.float64], n: NDArray[np.float64], f: NDArray[np.float64], ng: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`eta_from_n_prime` on checked arrays: n′ ≥ n_γ, n_γ = W_ly/(f/n − 1) given (eq. 120 inverted).

    For the inner loops of :mod:`aliasing.schemes`, which validate once at their edge.
    """
    a = f / n
    ra = np.sqrt(a)
    q = npr / ng
    with np.errstate(invalid="ignore", divide="ignore"):
        # App. B, n′ > n′_LiSPSM: η = (M_z(n′_L) − M_z(n′)) / (M_z(∞) − M_z(n′_L)), M_z ∝ n′/f′
        ratio = 1.0 / (1.0 + (a - 1) / q)  # n′/f′, tends to 1 as n′ → ∞
        lower = (1 / ra - ratio) / (1 - 1 / ra)
        # App. B, n ≤ n′ ≤ n′_L: η = (M_z(n′) − M_z(n′_L)) / (M_z(n) − M_z(n′_L)), M_z ∝ f′/(f n′)
        upper = ((q + a - 1) / (a * q) - 1 / ra) / (1 - 1 / ra)
    return np.where(q > ra + 1, lower, upper)


@dataclass(frozen=True)
class Shaping:
    """Parameters of Lloyd et al. 2007's η shaping function (eq. 79), angles in units of θ.

    γ_a = ``a``·θ, γ_b = θ, γ_c = θ + ``c_fraction``·(90° − θ); η_b, η_c.  ``c_fraction`` is
    0.4 in eq. 79 and 0.3 in the App. B text: both are selectable (docs/ERRATA.md L3).
    """

    a: float
    eta_b: float
    eta_c: float
    c_fraction: float = 0.4


SHAPING = {
    "p": Shaping(a=1 / 3, eta_b=-0.2, eta_c=0.0),  # §6.1.1: γ_a = θ/3, η_c = 0 for P
    "logp": Shaping(a=1 / 2, eta_b=-0.2, eta_c=1.0),  # eq. 79: γ_a = θ/2, η_c = 1 for LogP
}


@check.public  # broadcast errors name the parameters
def shaping_eta(gamma: ArrayLike, fov: ArrayLike | View, shaping: Shaping | str = "p") -> NDArray[np.float64]:
    """η(γ), Lloyd et al. 2007 eq. 79 (corrected: docs/ERRATA.md L1–L3).

    −1 (uniform) up to γ_a, linear to η_b at γ_b = θ, a quarter sine to η_c at γ_c, then
    η_c; γ is folded to [0°, 90°] (the error is symmetric under reversing the light).

    Parameters
    ----------
    gamma : array_like
        Angle between view direction and light [deg], 0 ≤ γ ≤ 180.
    fov : array_like or View
        Full field of view [deg]; θ = fov/2 (a :class:`~aliasing.View`'s, as validated there).
    shaping : Shaping or {"p", "logp"}
        The parameter set.

    Example
    -------
    >>> shaping_eta([0.0, 20.0, 30.0, 90.0], 60.0, "logp").round(4)
    array([-1.    , -0.7333, -0.2   ,  1.    ])
    """
    sh = SHAPING[check.choice(shaping, "shaping", SHAPING)] if isinstance(shaping, str) else shaping
    check.instance(sh, "shaping", Shaping)
    g = check.closed_range(gamma, "gamma", 0.0, 180.0, " degrees")
    g = np.minimum(g, 180.0 - g)
    theta = fov.theta_deg if isinstance(fov, View) else check.fov(fov) / 2
    ga, gb, gc = sh.a * theta, theta, theta + sh.c_fraction * (90.0 - theta)
    rising = -1.0 + (sh.eta_b + 1.0) * (g - ga) / (gb - ga)  # eq. (79), γ_a ≤ γ ≤ γ_b
    easing = sh.eta_b + (sh.eta_c - sh.eta_b) * np.sin(np.pi / 2 * (g - gb) / (gc - gb))  # eq. (79), γ_b ≤ γ ≤ γ_c
    return np.select([g <= ga, g <= gb, g <= gc], [-1.0, rising, easing], sh.eta_c)


def _sin_gamma(gamma: ArrayLike) -> NDArray[np.float64]:
    return np.sin(np.radians(check.closed_range(gamma, "gamma", 0.0, 180.0, " degrees")))


def _over_sin(value: NDArray[np.float64], gamma: ArrayLike) -> NDArray[np.float64]:
    """value / sin γ, with ∞ (no warping) where the light is parallel to the view."""
    s = _sin_gamma(gamma)
    with np.errstate(divide="ignore"):
        return np.where(s > 1e-12, value / np.where(s > 1e-12, s, 1.0), np.inf)


@register("uniform", "Williams 1978; Lloyd et al. 2006 §4.1 (n′ = ∞)", "no warping: an orthographic shadow map")
def _uniform(near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    n, f = check.frustum(near, far)
    return np.full(np.broadcast(n, f).shape, np.inf)


@register("psm", "Stamminger & Drettakis 2002; Lloyd et al. 2006 §4.1 (n′ = n); Lloyd 2007 eq. 120 at η = 1", "PSM-like warp: n′ = n overhead, n_γ = W_ly/(f/n − 1) in general")
def _psm(near: ArrayLike, far: ArrayLike, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    n, f = check.frustum(near, far)
    ng = _n_gamma(n, f, depth)
    return np.broadcast_to(ng, np.broadcast(n, f, ng).shape).astype(float)


@register("lispsm", "Wimmer et al. 2004 §4.3–4.4 (n′ = (n + √(fn))/sin γ)", "LiSPSM: n_opt/sin γ with the eye's near and far; n + √(fn) overhead")
def _lispsm(near: ArrayLike, far: ArrayLike, gamma: ArrayLike = 90.0) -> NDArray[np.float64]:
    return _over_sin(n_prime_lispsm(near, far), gamma)


@register("lispsm-dz", "Wimmer et al. 2004 §4.4, last paragraph", "LiSPSM with z_f replaced by z_n + Δz, Δz = D sin γ (D: light-space depth)")
def _lispsm_dz(near: ArrayLike, far: ArrayLike, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    n, f = check.frustum(near, far)
    d = f - n if depth is None else check.positive(depth, "depth")
    dz = d * _sin_gamma(gamma)  # Δz = (f − n) sin γ in Wimmer's P-notation: f − n is P's depth
    return _over_sin(n + sqrt_product(n, n + dz), gamma)  # √(n(n + Δz)) without under- or overflow of the product


@register("po", "Lloyd et al. 2007 §6.1.1, in light-plane units (eq. 120's n_γ)", "LiSPSM's 1/sin γ rule as Lloyd 2007 Table 3 evaluates it: n_γ(1 + √(f/n))/sin γ")
def _po(near: ArrayLike, far: ArrayLike, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    n, f = check.frustum(near, far)
    return _over_sin(_n_gamma(n, f, depth) * (1 + np.sqrt(f / n)), gamma)


@register("eta", "Lloyd et al. 2006 eq. 11 and App. B; Lloyd et al. 2007 eq. 120", "n′ from the normalised warping parameter η ∈ [−1, 1]")
def _eta(near: ArrayLike, far: ArrayLike, eta: ArrayLike = 0.0, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    return n_prime_from_eta(eta, near, far, depth)


@register("p", "Lloyd et al. 2007 eq. 79 (γ_a = θ/3, η_b = −0.2, η_c = 0) and eq. 120", "perspective warp with Lloyd 2007's η shaping function")
def _p(near: ArrayLike, far: ArrayLike, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None, c_fraction: float = 0.4) -> NDArray[np.float64]:
    sh = Shaping(SHAPING["p"].a, SHAPING["p"].eta_b, SHAPING["p"].eta_c, c_fraction)
    return n_prime_from_eta(shaping_eta(gamma, fov, sh), near, far, depth)


@register("logp", "Lloyd et al. 2007 eq. 79 (γ_a = θ/2, η_b = −0.2, η_c = 1) and eq. 120", "warp of the log+perspective map with Lloyd 2007's η shaping function")
def _logp(near: ArrayLike, far: ArrayLike, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None, c_fraction: float = 0.4) -> NDArray[np.float64]:
    sh = Shaping(SHAPING["logp"].a, SHAPING["logp"].eta_b, SHAPING["logp"].eta_c, c_fraction)
    return n_prime_from_eta(shaping_eta(gamma, fov, sh), near, far, depth)


@register("tsm", "Lloyd et al. 2006 §4.1 (Martin & Tan 2004): focus point on the 80 % line", "trapezoidal shadow map: n′ putting the focus depth at t = 0.8")
def _tsm(near: ArrayLike, far: ArrayLike, depth: ArrayLike | None = None, focus: ArrayLike = 0.25, line: ArrayLike = 0.8) -> NDArray[np.float64]:
    return n_prime_tsm(near, far, focus=focus, line=line, depth=depth)


@check.public  # broadcast errors name the parameters
def n_prime_tsm(near: ArrayLike, far: ArrayLike, focus: ArrayLike = 0.25, line: ArrayLike = 0.8, depth: ArrayLike | None = None) -> NDArray[np.float64]:
    """TSM's n′: the focus point maps to the line ``line`` of the way up the map [world units].

    Solving t(z_F) = τ for the perspective map t = f′(z′ − n′)/(z′(f′ − n′)) (Lloyd 2006
    eq. 6, corrected) with z_F − n = κ·D gives n′ = (1 − τ)κ/(τ − κ)·D, D the light-space
    depth (f − n overhead).  Lloyd 2006 §4.1 calls the focus "user selected" and no paper
    here gives a default: ``focus`` κ = 0.25 is ours.  For κ ≥ τ even the uniform map
    puts the focus below the line, so n′ = ∞.

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units].
    focus : array_like
        Focus depth κ as a fraction of the depth range, 0 < κ < 1.
    line : array_like
        The line τ the focus maps to, 0 < τ < 1 (0.8 in TSM).
    depth : array_like, optional
        Light-space depth D [world units]; default far − near.

    Example
    -------
    >>> round(float(n_prime_tsm(1.0, 100.0, focus=(10.0 - 1.0) / 99.0)), 4)
    2.5385
    """
    n, f = check.frustum(near, far)
    d = f - n if depth is None else check.positive(depth, "depth")
    k = check.as_float_array(focus, "focus")
    if ((k <= 0) | (k >= 1)).any():
        raise ValueError(f"focus must be in (0, 1), got {check._show(k)}")
    tau = check.as_float_array(line, "line")
    if ((tau <= 0) | (tau >= 1)).any():
        raise ValueError(f"line must be in (0, 1), got {check._show(tau)}")
    with np.errstate(divide="ignore"):
        return np.where(k < tau, (1 - tau) * k / np.where(k < tau, tau - k, 1.0) * d, np.inf)
