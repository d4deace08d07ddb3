"""Shadow-map parameterizations along the view depth for an overhead light.

Each map sends eye depth z ∈ [near, far] [world units] to the shadow-map coordinate
t ∈ [0, 1] (Lloyd et al. 2006 names the depth-aligned axis t; Wimmer et al. 2004 calls
it s).  The spacing dz/dt [world units per unit t] sets the light-beam width
w_lz = (1/res_t)·dz/dt (Lloyd 2006 eq. 4).

Example
-------
>>> import numpy as np
>>> t_perspective(np.array([1.0, 100.0]), 1.0, 100.0, n_prime=11.0)
array([0., 1.])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check

__all__ = [
    "spacing_logarithmic",
    "spacing_perspective",
    "t_log_perspective",
    "t_logarithmic",
    "t_perspective",
]


def _depths(z: ArrayLike, near: ArrayLike, far: ArrayLike):
    n, f = check.frustum(near, far)
    zz = check.as_float_array(z, "z")
    if ((zz < n) | (zz > f)).any():
        raise ValueError(f"z must lie in [near, far], got {check._show(zz)}")
    return zz, n, f


def _ratio(n_prime: Array, u: ArrayLike, v: ArrayLike) -> Array:
    """(n′ + u)/(n′ + v), with its limit 1 at n′ = ∞."""
    n_prime, u, v = np.broadcast_arrays(n_prime, np.asarray(u, float), np.asarray(v, float))
    finite = np.isfinite(n_prime)
    with np.errstate(invalid="ignore", over="ignore"):
        r = (n_prime + u) / (n_prime + v)
        big = finite & ~np.isfinite(n_prime + v)
        if big.any():  # sums beyond 1.8e308: divide by the largest term first (elsewhere bit for bit as before)
            s = np.maximum(np.abs(n_prime), np.maximum(np.abs(u), np.abs(v)))
            with np.errstate(under="ignore", divide="ignore"):
                r = np.where(big, (n_prime / s + u / s) / (n_prime / s + v / s), r)
    return np.where(finite, r, 1.0)


@check.public
def t_perspective(z: ArrayLike, near: ArrayLike, far: ArrayLike, n_prime: ArrayLike) -> NDArray[np.float64]:
    """t(z) of a perspective warping frustum, Lloyd et al. 2006 eq. 6 (sign corrected).

    t = f′(z′ − n′)/(z′(f′ − n′)) with z′ = n′ + z − n and f′ = n′ + f − n; it tends to the
    uniform map (z − n)/(f − n) as n′ → ∞.  The printed eq. 6 has the wrong sign on its
    1/z′ term for positive z′ (docs/ERRATA.md, E2).

    Parameters
    ----------
    z : array_like
        Eye depth [world units], near ≤ z ≤ far.
    near, far : array_like
        Eye near and far distances [world units].
    n_prime : array_like
        Warping parameter n′ ≥ near [world units]; ``inf`` for the uniform map.
    """
    zz, n, f = _depths(z, near, far)
    npr = check.n_prime(n_prime, n)
    with np.errstate(invalid="ignore"):
        fp_over_zp = (npr + f - n) / (npr + zz - n)  # f′/z′, → 1 as n′ → ∞
    fp_over_zp = np.where(np.isinf(npr), 1.0, fp_over_zp)
    return (zz - n) / (f - n) * fp_over_zp  # eq. (6): f′(z′ − n′)/(z′(f′ − n′))


@check.public
def t_logarithmic(z: ArrayLike, near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    """t(z) = ln(z/n)/ln(f/n), the optimal map for an overhead light (Lloyd 2006 App. C).

    Example
    -------
    >>> float(t_logarithmic(10.0, 1.0, 100.0))
    0.5
    """
    zz, n, f = _depths(z, near, far)
    return np.log1p((zz - n) / n) / np.log1p((f - n) / n)  # App. C (log1p: accurate as f/n → 1)


@check.public
def spacing_perspective(z: ArrayLike, near: ArrayLike, far: ArrayLike, n_prime: ArrayLike) -> NDArray[np.float64]:
    """dz/dt of :func:`t_perspective` [world units]: (f − n)·z′²/(f′n′), → f − n as n′ → ∞."""
    zz, n, f = _depths(z, near, far)
    npr = check.n_prime(n_prime, n)
    zp_over_np = 1.0 + (zz - n) / npr  # z′/n′
    zp_over_fp = _ratio(npr, zz - n, f - n)  # z′/f′
    return (f - n) * zp_over_np * zp_over_fp


@check.public
def spacing_logarithmic(z: ArrayLike, near: ArrayLike, far: ArrayLike) -> NDArray[np.float64]:
    """dz/dt of :func:`t_logarithmic` [world units]: z·ln(f/n)."""
    zz, n, f = _depths(z, near, far)
    return zz * np.log1p((f - n) / n)


@check.public
def t_log_perspective(y: ArrayLike, y0: ArrayLike, y1: ArrayLike, a: ArrayLike) -> NDArray[np.float64]:
    """LogPSM's t-mapping F_lp,t on a face or frustum spanning y ∈ [y0, y1] (Lloyd 2007 eqs. 77–78).

    F_lp,t = c0 ln(c1 F_p,t + c2) with F_p,t the perspective map whose centre of projection
    sits at y = −a (eqs. 75–76); the constants make it equal to the logarithmic map of the
    shifted coordinate, t = ln((y + a)/(y0 + a)) / ln((y1 + a)/(y0 + a)) (eq. 77).  ``a`` is
    the free parameter: a = 0 puts the centre at the eye, a → ∞ gives the uniform map.

    Parameters
    ----------
    y : array_like
        Coordinate along the map's t direction [world units], y0 ≤ y ≤ y1.
    y0, y1 : array_like
        The extent [world units], y1 > y0 and y0 + a > 0.
    a : array_like
        Offset of the centre of projection [world units], ≥ 0 (``inf`` allowed).

    Example
    -------
    >>> t_log_perspective([1.0, 10.0, 100.0], 1.0, 100.0, 0.0)
    array([0. , 0.5, 1. ])
    """
    yy = check.as_float_array(y, "y")
    lo, hi = check.as_float_array(y0, "y0"), check.as_float_array(y1, "y1")
    if (hi <= lo).any():
        raise ValueError("y1 must be greater than y0")
    if ((yy < lo) | (yy > hi)).any():
        raise ValueError(f"y must lie in [y0, y1], got {check._show(yy)}")
    shift = check.as_float_array(a, "a")
    if (shift < 0).any() or (lo + shift <= 0).any():
        raise ValueError("a must be >= 0 with y0 + a > 0")
    with np.errstate(invalid="ignore"):
        # eq. (77)/(78): c0 ln(c1 F_p,t + c2) = ln((y + a)/(y0 + a)) / ln((y1 + a)/(y0 + a))
        t = np.log1p((yy - lo) / (lo + shift)) / np.log1p((hi - lo) / (lo + shift))
    return np.where(np.isinf(shift), (yy - lo) / (hi - lo), t)
