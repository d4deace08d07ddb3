"""Lloyd et al. 2007 (LogPSM) App. A: the critical resolution factors of a side or end face.

For the directional light straight above the face (where R and S are maximal over light
positions, §5.1): the closed forms of the maximum error factors R and the storage S of the
error-bound, uniform, perspective and logarithmic parameterizations (eqs. 87–103, eqs. 100–101
corrected), and R = max_v δ_l/δ_b by sampling the spacing functions of
:mod:`aliasing.logpsm` (eq. 47), which checks them.  Both are re-exported by
:mod:`aliasing.logpsm`; the factors for any light position are :mod:`aliasing.face_factors`.

Conventions (see :mod:`aliasing`): angles in degrees, ``fov`` is the full field of view
(θ = fov/2); ``near``, ``far`` are the eye distances n_e, f_e.

Example
-------
>>> factors = critical_factors(1.0, 1000.0, 60.0)
>>> round(float(factors["log_t_side"]), 4)  # ln(f/n)/sin 2θ, eq. 103
7.9764
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from .view import half_angle

__all__ = ["critical_factor_side", "critical_factors"]

Array = NDArray[np.float64]


# --- App. A: closed-form critical resolution factors (overhead directional light) --------
@check.public
def critical_factors(near: ArrayLike, far: ArrayLike, fov: ArrayLike) -> dict[str, Array]:
    """Closed-form critical resolution factors R and storage S, Lloyd et al. 2007, eqs. 87–103.

    For the directional light straight above the face (where R and S are maximal over
    light positions, §5.1), with cosθ included:

    ==================  =========================================  ========
    key                 value                                      eq.
    ==================  =========================================  ========
    bound_t_end         1/cosθ                                     87
    bound_s_side        1/cosθ                                     88
    bound_t_side        ln(f/n)/sin 2θ                             89
    uniform_t_end       1/cosθ                                     93
    uniform_s_side      f/(n cosθ)                                 94
    uniform_t_side      (f/n − 1)/sin 2θ                           95
    perspective_s_side  1/cosθ (a = 0)                             99
    perspective_t_side  (f/n − 1)/(sin 2θ √(f/n)) (a = √(y0 y1))   100 (corr.)
    perspective_S_side  (f/n − 1)/(sin 2θ cosθ) (0 ≤ a ≤ √(y0y1))  101 (corr.)
    log_t_side          ln(f/n)/sin 2θ (a = 0)                     103
    ==================  =========================================  ========

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [degrees], in (0, 180).

    Returns
    -------
    dict of str to ndarray
        Dimensionless factors (texels per pixel, per direction; S per area).

    Examples
    --------
    >>> round(float(critical_factors(1.0, 100.0, 90.0)["uniform_t_side"]), 6)
    99.0
    """
    n, f = check.frustum(near, far)
    half = half_angle(fov)
    ct, s2 = np.cos(half), np.sin(2 * half)
    r = f / n
    return {
        "bound_t_end": 1 / ct + 0 * r,  # eq. (87)
        "bound_s_side": 1 / ct + 0 * r,  # eq. (88)
        "bound_t_side": np.log(r) / s2,  # eq. (89)
        "uniform_t_end": 1 / ct + 0 * r,  # eq. (93)
        "uniform_s_side": r / ct,  # eq. (94)
        "uniform_t_side": (r - 1) / s2,  # eq. (95)
        "perspective_s_side": 1 / ct + 0 * r,  # eq. (99)
        "perspective_t_side": (r - 1) / (s2 * np.sqrt(r)),  # eq. (100), corrected (cos²θ, not cos³θ)
        "perspective_S_side": (r - 1) / (s2 * ct),  # eq. (101), corrected (cos²θ in the first form)
        "log_t_side": np.log(r) / s2,  # eq. (103)
    }


@check.public
def critical_factor_side(kind: str, direction: str, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, a: ArrayLike = 0.0, b: ArrayLike = np.inf, samples: int = 2001) -> Array:
    """R = max_v δ_l/δ_b on a side face for the overhead light, by sampling (Lloyd 2007 eq. 47).

    ``direction`` is ``"s"`` (δ_b,s; maximum over v, with u irrelevant) or ``"t"``.  The
    ratio is monotone or convex for every parameterization here, so its maximum lies at
    v = 0 or v = 1 and the samples only confirm it.  Parameters as in :func:`aliasing.logpsm.spacing`.

    Returns
    -------
    ndarray
        R, dimensionless.

    Examples
    --------
    >>> round(float(critical_factor_side("uniform", "t", 1.0, 100.0, 90.0)), 6)
    99.0
    """
    from .logpsm import delta_bound_side_s, delta_bound_side_t, spacing  # not at the top: logpsm imports this module to re-export it

    key = check.choice(direction, "direction", ["s", "t"])
    samples = check.whole(samples, "samples", 2, 100_000)  # bounded: one float per sample and frustum
    vv = np.linspace(0.0, 1.0, samples).reshape((-1,) + (1,) * len(np.broadcast(np.asarray(near), np.asarray(far), np.asarray(fov), np.asarray(a), np.asarray(b)).shape))
    if key == "s":
        spacing_kind = {"uniform": "uniform", "perspective": "perspective_s", "logp": "perspective_s"}[check.choice(kind, "kind", ["uniform", "perspective", "logp"])]
        ratio = spacing(spacing_kind, vv, near, far, fov, a=a) / delta_bound_side_s(0.5, vv, near, far, fov)  # eqs. (47), (71)
    else:
        spacing_kind = {"uniform": "uniform", "perspective": "perspective_t", "log": "log_t", "logp": "logp_t"}[check.choice(kind, "kind", ["uniform", "perspective", "log", "logp"])]
        ratio = spacing(spacing_kind, vv, near, far, fov, a=a, b=b) / delta_bound_side_t(vv, near, far, fov)  # eq. (47)
    return ratio.max(axis=0)
