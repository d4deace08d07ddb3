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

import inspect
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check


@dataclass(frozen=True)
class WarpingRule:
    """A registered warping-parameter rule."""

    name: str
    func: Callable[..., NDArray[np.float64]]
    source: str
    summary: str


WARPING_RULES: dict[str, WarpingRule] = {}


def register(name: str, source: str, summary: str) -> Callable:
    """Decorator adding a rule ``func(near, far, **options) -> n′`` to the registry."""

    def wrap(func: Callable[..., NDArray[np.float64]]) -> Callable[..., NDArray[np.float64]]:
        if name in WARPING_RULES:
            raise RuntimeError(f"warping rule {name!r} registered twice")
        WARPING_RULES[name] = WarpingRule(name, func, source, summary)
        return func

    return wrap


def warping_parameter(method: str, near: ArrayLike, far: ArrayLike, **options: ArrayLike) -> NDArray[np.float64]:
    """n′ [world units] chosen by the named rule; broadcasts over its array arguments.

    Parameters
    ----------
    method : str
        A name in :data:`WARPING_RULES` (case-insensitive): ``uniform``, ``psm``,
        ``lispsm``, ``eta``, ...
    near, far : array_like
        Eye near and far plane distances [world units], ``0 < near < far``.
    **options
        Rule-specific parameters (``eta`` for the η rule).

    Returns
    -------
    ndarray
        n′ [world units], ``near <= n′ <= inf``.

    Raises
    ------
    ValueError
        For an unknown method, an option the rule does not take, or a value out of range.
    """
    key = check.choice(method, "warping method", WARPING_RULES)
    rule = WARPING_RULES[key]
    accepted = set(inspect.signature(rule.func).parameters) - {"near", "far"}
    unknown = set(options) - accepted
    if unknown:
        raise ValueError(f"warping method {key!r} takes options {sorted(accepted) or 'none'}, not {sorted(unknown)}")
    return rule.func(near, far, **options)


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
    return n + np.sqrt(f * n)


def n_prime_from_eta(eta: ArrayLike, near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    """n′(η) [world units], Lloyd et al. 2006 eq. 11 (Appendix B).

    η = −1 gives n′ = ∞ (uniform), η = 0 LiSPSM's n + √(fn), η = 1 PSM's n′ = n; M_z is
    linear in η on each half.

    Parameters
    ----------
    eta : array_like
        Warping parameter η ∈ [−1, 1].
    near, far : array_like
        Eye near and far distances [world units], ``0 < near < far``.

    Example
    -------
    >>> n_prime_from_eta([-1.0, 0.0, 1.0], 1.0, 100.0)
    array([inf, 11.,  1.])
    """
    e = check.closed_range(eta, "eta", -1.0, 1.0)
    n, f = check.frustum(near, far)
    a = f / n
    ra = np.sqrt(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        lower = n * (ra + 1 - e * (a - 1)) / (e + 1)  # eq. (11), −1 ≤ η ≤ 0
        upper = n * (ra + 1) / (e * ra + 1)  # eq. (11), 0 < η ≤ 1
    return np.where(e <= 0, np.where(e == -1, np.inf, lower), upper)


def eta_from_n_prime(n_prime: ArrayLike, near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    """η(n′), the inverse of eq. 11: Lloyd et al. 2006 Appendix B.

    Example
    -------
    >>> eta_from_n_prime([np.inf, 11.0, 1.0], 1.0, 100.0)
    array([-1.,  0.,  1.])
    """
    n, f = check.frustum(near, far)
    npr = check.n_prime(n_prime, n)
    a = f / n
    ra = np.sqrt(a)
    q = npr / n
    with np.errstate(invalid="ignore", divide="ignore"):
        # App. B, n′ > n′_LiSPSM: η = (M_z(n′_L) − M_z(n′)) / (M_z(∞) − M_z(n′_L)), M_z ∝ n′/f′
        ratio = 1.0 / (1.0 + (a - 1) / q)  # n′/f′, tends to 1 as n′ → ∞
        lower = (1 / ra - ratio) / (1 - 1 / ra)
        # App. B, n ≤ n′ ≤ n′_L: η = (M_z(n′) − M_z(n′_L)) / (M_z(n) − M_z(n′_L)), M_z ∝ f′/(f n′)
        upper = ((q + a - 1) / (a * q) - 1 / ra) / (1 - 1 / ra)
    return np.where(q > ra + 1, lower, upper)


@register("uniform", "Williams 1978; Lloyd et al. 2006 §4.1 (n′ = ∞)", "no warping: an orthographic shadow map")
def _uniform(near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    n, f = check.frustum(near, far)
    return np.full(np.broadcast(n, f).shape, np.inf)


@register("psm", "Stamminger & Drettakis 2002; Lloyd et al. 2006 §4.1 (n′ = n)", "perspective shadow map: warp centred on the eye")
def _psm(near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    n, f = check.frustum(near, far)
    return np.broadcast_to(n, np.broadcast(n, f).shape).astype(float)


@register("lispsm", "Wimmer et al. 2004 §4.3; Lloyd et al. 2006 §4.1 (n′ = n + √(fn))", "light-space perspective shadow map, overhead light")
def _lispsm(near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    return n_prime_lispsm(near, far)


@register("eta", "Lloyd et al. 2006 eq. 11 and Appendix B", "n′ from the normalised warping parameter η ∈ [−1, 1]")
def _eta(near: ArrayLike, far: ArrayLike, eta: ArrayLike = 0.0) -> NDArray[np.float64]:
    return n_prime_from_eta(eta, near, far)
