"""Perspective aliasing error for an overhead directional light, vectorized.

Closed forms from Lloyd et al. 2006 §4.1–4.2 and Appendix C, and Wimmer et al. 2004
eq. 3.  Each is checked in the tests against the lambdified sympy derivation of
:mod:`aliasing.symbolic.lloyd2006` / :mod:`aliasing.symbolic.wimmer2004`.

All functions broadcast over their array arguments.  Lengths (z, near, far, n′) are in
world units, ``fov`` is the full field of view in degrees (θ = fov/2 in the papers),
resolutions are in texels or pixels per side.  ``n_prime = inf`` is a uniform
(orthographic) shadow map, ``n_prime = near`` a PSM.

Example
-------
>>> from aliasing.error import max_error_x, max_error_z, storage_factor
>>> float(max_error_x(near=1.0, far=100.0, n_prime=11.0))
10.0
>>> float(max_error_z(near=1.0, far=100.0, fov=90.0, n_prime=11.0))
4.95
>>> float(storage_factor(near=1.0, far=100.0, fov=90.0, n_prime=11.0))
49.5
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from ._stable import sqrt_product
from .view import View, split_view, tan_theta
from .parameterizations import _depths, _ratio

__all__ = [
    "critical_resolution",
    "dp_ds",
    "m_x",
    "m_z",
    "max_error_x",
    "max_error_z",
    "resolution_for_budget",
    "storage_factor",
    "storage_factor_optimal",
]

Array = NDArray[np.float64]


def _half_tan(fov: ArrayLike) -> Array:
    """tan θ for the full field of view ``fov`` [deg]."""
    return tan_theta(fov)


def _unpack(near: ArrayLike | View, far: ArrayLike | None, fov: ArrayLike | None, n_prime: ArrayLike | None) -> tuple[ArrayLike, ArrayLike, ArrayLike, ArrayLike]:
    """(near, far, fov, n′) from the numbers or from a :class:`aliasing.View` in ``near``
    (then ``f(view, n_prime)``: the arguments after it move up one place)."""
    view, npr = split_view(near, far, fov, n_prime, (None, None, None, np.inf))
    if not isinstance(near, View):
        # against the near given: the View broadcasts near to far's shape, which may be empty
        check.n_prime(npr, check.positive(near, "near"))
    view.require_square("the closed forms of Lloyd et al. 2006 (eqs. 3-4, 7-10: a square frustum; use aliasing.schemes.evaluate)")
    return view.near, view.far, view.fov, npr


def _frustum_warp(near: ArrayLike, far: ArrayLike, n_prime: ArrayLike) -> tuple[Array, Array, Array]:
    n, f = check.frustum(near, far)
    return n, f, check.n_prime(n_prime, n)


@check.public
def m_x(z: ArrayLike, near: ArrayLike, far: ArrayLike, n_prime: ArrayLike = np.inf, *, res_image: ArrayLike = 1.0, res_s: ArrayLike = 1.0) -> Array:
    """Perspective aliasing error across the view, m_x = w_lx/w_i (Lloyd et al. 2006 eq. 7).

    Parameters
    ----------
    z : array_like
        Eye depth [world units], near ≤ z ≤ far.
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    n_prime : array_like, optional
        Warping parameter n′ [world units], near ≤ n′ ≤ ∞ (default ∞, uniform map).
    res_image, res_s : array_like, optional
        Image resolution [pixels] and shadow-map resolution along s [texels].

    Returns
    -------
    ndarray
        m_x [dimensionless]; > 1 means a shadow texel is wider than a pixel.

    Example
    -------
    >>> m_x([1.0, 20.0], near=1.0, far=20.0)  # uniform map: f/z
    array([20.,  1.])
    """
    zz, n, f = _depths(z, near, far)
    n, f, npr = _frustum_warp(n, f, n_prime)
    ri = check.positive(res_image, "res_image")
    rs = check.positive(res_s, "res_s")
    return ri / rs * f / zz * _ratio(npr, zz - n, f - n)  # eq. (7): f z′/(z f′)


@check.public
def m_z(z: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, n_prime: ArrayLike = np.inf, *, res_image: ArrayLike = 1.0, res_t: ArrayLike = 1.0) -> Array:
    """Perspective aliasing error along the view depth, m_z = w_lz/w_i (Lloyd et al. 2006 eq. 8).

    Parameters
    ----------
    z : array_like
        Eye depth [world units], near ≤ z ≤ far.
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    n_prime : array_like, optional
        Warping parameter n′ [world units], near ≤ n′ ≤ ∞ (default ∞, uniform map).
    res_image, res_t : array_like, optional
        Image resolution [pixels] and shadow-map resolution along t [texels].

    Returns
    -------
    ndarray
        m_z [dimensionless].

    Example
    -------
    >>> m_z([1.0, 100.0], near=1.0, far=100.0, fov=90.0, n_prime=11.0)  # equal at both ends
    array([4.95, 4.95])
    """
    zz, n, f = _depths(z, near, far)
    n, f, npr = _frustum_warp(n, f, n_prime)
    ri = check.positive(res_image, "res_image")
    rt = check.positive(res_t, "res_t")
    zp_over_np = 1.0 + (zz - n) / npr  # z′/n′
    return ri / rt * (f - n) / (2 * _half_tan(fov)) * zp_over_np * _ratio(npr, zz - n, f - n) / zz  # eq. (8)


@check.public
def max_error_x(near: ArrayLike, far: ArrayLike, n_prime: ArrayLike = np.inf, *, res_image: ArrayLike = 1.0, res_s: ArrayLike = 1.0) -> Array:
    """M_x = max over z of m_x, at z = near (Lloyd et al. 2006 eq. 9, corrected: docs/ERRATA.md E3).

    M_x = (res_i/res_s)·f n′/(n (n′ + f − n)); f/n for a uniform map, 1 for a PSM.

    Example
    -------
    >>> max_error_x(1.0, 100.0, [np.inf, 1.0])
    array([100.,   1.])
    """
    n, f, npr = _frustum_warp(near, far, n_prime)
    ri = check.positive(res_image, "res_image")
    rs = check.positive(res_s, "res_s")
    return ri / rs * f / n * _ratio(npr, 0.0, f - n)  # eq. (9) corrected: f n′/(n f′)


@check.public
def max_error_z(near: ArrayLike | View, far: ArrayLike | None = None, fov: ArrayLike | None = None, n_prime: ArrayLike | None = None, *, res_image: ArrayLike = 1.0, res_t: ArrayLike = 1.0) -> Array:
    """M_z = max over z of m_z (Lloyd et al. 2006 eq. 10, corrected: docs/ERRATA.md E3).

    At the far plane for n′ ≤ n′_LiSPSM = n + √(fn), (res_i/res_t)(f − n)/(2 tanθ)·f′/(f n′);
    at the near plane above, (res_i/res_t)(f − n)/(2 tanθ)·n′/(n f′).

    Example
    -------
    >>> max_error_z(1.0, 100.0, 90.0, [np.inf, 11.0, 1.0])
    array([49.5 ,  4.95, 49.5 ])
    """
    near, far, fov, n_prime = _unpack(near, far, fov, n_prime)
    n, f, npr = _frustum_warp(near, far, n_prime)
    ri = check.positive(res_image, "res_image")
    rt = check.positive(res_t, "res_t")
    scale = ri / rt * (f - n) / (2 * _half_tan(fov))
    n_l = n + sqrt_product(f, n)  # √(fn), n′_LiSPSM (the branch point), without under- or overflow of f·n
    with np.errstate(divide="ignore"):
        far_plane = (1.0 + (f - n) / npr) / f  # f′/(f n′)
    near_plane = _ratio(npr, 0.0, f - n) / n  # n′/(n f′)
    return scale * np.where(npr <= n_l, far_plane, near_plane)  # eq. (10) corrected


@check.public
def storage_factor(near: ArrayLike | View, far: ArrayLike | None = None, fov: ArrayLike | None = None, n_prime: ArrayLike | None = None) -> Array:
    """Storage factor S̄ = M_x·M_z at unit resolutions (Lloyd et al. 2006 eq. 12).

    The critical-resolution shadow map needs S̄·res_i² texels.  S̄ is minimal,
    (f/n − 1)/(2 tanθ), for every n′ ≤ n + √(fn).  ``near`` may be a
    :class:`aliasing.View`, followed by ``n_prime``; n′ defaults to ∞ (uniform).

    Example
    -------
    >>> storage_factor(1.0, 100.0, 90.0, [1.0, 11.0, np.inf])
    array([  49.5,   49.5, 4950. ])
    >>> float(storage_factor(View(1.0, 100.0, 90.0), 11.0))
    49.5
    """
    near, far, fov, n_prime = _unpack(near, far, fov, n_prime)
    n, f, npr = _frustum_warp(near, far, n_prime)
    base = (f - n) / n / (2 * _half_tan(fov))  # (f/n − 1), without cancellation as f/n → 1
    n_l = n + sqrt_product(f, n)  # √(fn), n′_LiSPSM (the branch point), without under- or overflow of f·n
    np_over_fp = _ratio(npr, 0.0, f - n)
    return base * np.where(npr <= n_l, 1.0, np_over_fp**2 * f / n)  # eq. (12)


@check.public
def storage_factor_optimal(near: ArrayLike | View, far: ArrayLike | None = None, fov: ArrayLike | None = None) -> Array:
    """S̄ of the logarithmic parameterization, ln(f/n)/(2 tanθ) (Lloyd et al. 2006 App. C).

    Example
    -------
    >>> round(float(storage_factor_optimal(1.0, 100.0, 90.0)), 6)
    2.302585
    """
    if isinstance(near, View) and (far is not None or fov is not None):
        raise ValueError("pass either a View or near, far, fov, not both")
    near, far, fov, _ = _unpack(near, far, fov, None)
    n, f = check.frustum(near, far)
    return np.log1p((f - n) / n) / (2 * _half_tan(fov))  # App. C; log1p keeps f/n → 1 accurate


@check.public
def critical_resolution(near: ArrayLike | View, far: ArrayLike | None = None, fov: ArrayLike | None = None, n_prime: ArrayLike | None = None, *, res_image: ArrayLike = 1.0) -> tuple[Array, Array]:
    """Critical resolutions (res*_s, res*_t) [texels] at which M_x = M_z = 1 (Lloyd 2006 §4.2).

    Their product is the critical storage S* = res_i²·S̄ (eq. 12).

    Example
    -------
    >>> rs, rt = critical_resolution(1.0, 100.0, 90.0, 11.0, res_image=1024)
    >>> float(rs), float(rt)
    (10240.0, 5068.8)
    """
    near, far, fov, n_prime = _unpack(near, far, fov, n_prime)
    rs = max_error_x(near, far, n_prime, res_image=res_image)
    rt = max_error_z(near, far, fov, n_prime, res_image=res_image)
    return rs, rt


@check.public
def resolution_for_budget(budget: ArrayLike, res_s_critical: ArrayLike, res_t_critical: ArrayLike) -> tuple[Array, Array]:
    """Split a texel budget S0 between s and t (Lloyd et al. 2006 eqs. 13–14).

    res_s·res_t = S0 and res_s/res_t = res*_s/res*_t, so that the error is divided equally:
    the resulting M_x = M_z = √(res*_s·res*_t / S0).

    Parameters
    ----------
    budget : array_like
        Texel budget S0 [texels], > 0.
    res_s_critical, res_t_critical : array_like
        Critical resolutions [texels], > 0 (e.g. from :func:`critical_resolution`).

    Returns
    -------
    res_s, res_t : ndarray
        Shadow-map resolutions [texels] (real-valued; round as your hardware needs).

    Example
    -------
    >>> rs, rt = resolution_for_budget(2048 * 2048, 10240.0, 5068.8)
    >>> round(float(rs)), round(float(rt)), round(float(rs * rt))
    (2911, 1441, 4194304)
    """
    s0 = check.positive(budget, "budget")
    rs_c = check.positive(res_s_critical, "res_s_critical")
    rt_c = check.positive(res_t_critical, "res_t_critical")
    return np.sqrt(s0 * rs_c / rt_c), np.sqrt(s0 * rt_c / rs_c)  # eqs. (13), (14)


@check.public
def dp_ds(z: ArrayLike, near: ArrayLike, far: ArrayLike, n_prime: ArrayLike = np.inf) -> Array:
    """Wimmer et al. 2004 eq. 3: perspective aliasing dp/ds along the view depth.

    dp/ds = (z − z_n + n)²/z · z_n(z_f − z_n)/(n (n + z_f − z_n)), with Wimmer's n the
    warping parameter (our ``n_prime``), z_n = ``near``, z_f = ``far``; a viewport of
    height 1 on the near plane, unit resolutions.  Equals 2·tanθ·near·m_z.

    Example
    -------
    >>> dp_ds([1.0, 100.0], 1.0, 100.0, [np.inf, 1.0])  # uniform at z_n, PSM at z_f
    array([99., 99.])
    """
    zz, n, f = _depths(z, near, far)
    n, f, npr = _frustum_warp(n, f, n_prime)
    zp_over_np = 1.0 + (zz - n) / npr
    return n * (f - n) * zp_over_np * _ratio(npr, zz - n, f - n) / zz  # eq. (3)
