"""Lloyd et al. 2007 (LogPSM) App. A: the critical resolution factors of a side or end face.

For the directional light straight above the face (where R and S are maximal over light
positions, §5.1): the closed forms of the maximum error factors R and the storage S of the
error-bound, uniform, perspective and logarithmic parameterizations (eqs. 87–103, eqs. 100–101
corrected).  They are re-exported by :mod:`aliasing.logpsm`, whose
:func:`aliasing.logpsm.critical_factor_side` checks them by sampling the spacing functions
(eq. 47); the factors for any light position are :mod:`aliasing.face_factors`.

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
from .view import theta_of

__all__ = ["critical_factors"]

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
    half = theta_of(fov)
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
