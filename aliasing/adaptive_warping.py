"""A warping rule from the light's position in the eye's image ("pyramid" rule), and the grid study.

Beyond the papers (derivation and measurements in docs/warping_rule.md).
Lloyd et al. 2007's eq. 79 shapes η by γ alone.  The S-optimal η (scheme ``Sopt``) shows a
simpler structure: for a light whose direction (folded towards the view direction) lies
*outside* the view frustum's pyramid of directions, η_opt sits on a plateau near η = n/f
(n′ = n_γ√(f/n) in Lloyd 2007 eq. 120's light-plane units; η = 0, LiSPSM's n_γ(1 + √(f/n)),
is as good only at large f/n); *inside* the pyramid it falls towards −1 (uniform).  Whether the
light is inside is decided by its vanishing point in the eye's image,

    (u, w) = (l_x, l_y)/(l_z tanθ),   t = max(|u|, |w|)   (t < 1: inside the pyramid),

which depends on the azimuth of the light as well as on γ (t = tanγ·max(|sin φ|, |cos φ|)/tanθ).
The rule is η = clip(min(t, 2t²) − 1, −1, n/f): quadratic near the view axis (where Standard's
S̄ has its supremum at small f/n and falls only quadratically away from it), the plateau
η = n/f, i.e. n′ = n_γ√(f/n), outside; n′ from η by eq. 120, and a guard near the pyramid's
boundary: n′ ≥ c·W_ly·max(0, 1 − |t − 1|/τ), c = 0.1, τ = 0.3 (there the S-optimal centre of
projection sits about 0.1 W_ly before the near face, which η ≈ 0 cannot express at large f/n;
docs/warping_rule.md §5).  Continuous in the light direction, no per-direction optimisation:
a few divisions and two maxima per direction.  Its log+perspective counterpart (scheme
``pyramid-log``) also uses how diagonal the light's image position is, r = min(|u|, |w|)/t:
inside, η = min((1 − r)(min(t, 2t²) − 1) − r(1 − t)⁵, 3t² − 1); outside a ramp to LogSopt's
plateau η = 1 at t = 1.3, where the guard ends; the same guard (docs/warping_rule.md §6).

Both rules are registered ``bounded``: :func:`aliasing.schemes.evaluate` keeps their n′ for a
map only where its S̄ is at most the uniform map's and uses n′ = ∞ elsewhere, so that S̄ is
never above Standard's, per direction, for any frustum (docs/warping_rule.md §7).

What holds on the grid f/n ∈ 10…1e5, fov 20°…120° (docs/warping_rule.md): see
:func:`grid_study` and the reproduce target ``warping-rule-grid``.

Example
-------
>>> import numpy as np
>>> from aliasing.geometry import light_direction
>>> eta_pyramid(light_direction(np.array([90.0, 15.0, 0.0]), 0.0), 60.0).round(3)  # overhead, inside, along the view
array([ 0.   , -0.569, -1.   ])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from . import geometry, schemes, warping
from .warping import register
from .view import tan_theta

Array = NDArray[np.float64]
RULES = ("P", "LogP", "lispsm", "gmnpr", "glpr", "pyramid", "pyramid-log")
F_OVER_N = (10.0, 100.0, 1e3, 1e4, 1e5)
FOVS = (20.0, 50.0, 80.0, 120.0)


def image_position(light: ArrayLike, fov: ArrayLike) -> tuple[Array, Array]:
    """(u, w): the light's vanishing point in the eye's image, in units of tanθ (NDC).

    The light vector is folded towards the view direction first (l and −l give the same
    shadow-map error); a light perpendicular to the view has its vanishing point at infinity.

    Parameters
    ----------
    light : array_like
        Directions towards the light ``(N, 3)`` or ``(3,)``.
    fov : array_like
        Full field of view [deg], 0 < fov < 180.
    """
    lv = np.atleast_2d(geometry._unit(light))
    tan = tan_theta(fov)
    lz = np.abs(lv[:, 2])
    sign = np.where(lv[:, 2] < 0, -1.0, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(lz > 0, sign * lv[:, 0] / (lz * tan), np.copysign(np.inf, lv[:, 0]))
        w = np.where(lz > 0, sign * lv[:, 1] / (lz * tan), np.copysign(np.inf, lv[:, 1]))
    return u, w


AXIS_SLOPE = 2.0  # η + 1 = min(t, 2t²) inside: quadratic near the view axis (docs/warping_rule.md §5)
GUARD, GUARD_WIDTH = 0.1, 0.3  # c and τ of the boundary guard (docs/warping_rule.md §5)
LOG_DIAGONAL_POWER, LOG_AXIS_SLOPE = 5.0, 3.0  # pyramid-log's inside shape (docs/warping_rule.md §6)


def _eta_of_t(t: Array, top: ArrayLike) -> Array:
    """η = clip(min(t, 2t²) − 1, −1, top): the rule's one formula (t = inf gives top)."""
    with np.errstate(over="ignore", invalid="ignore"):
        inside = np.minimum(t, AXIS_SLOPE * t * t)
    return np.clip(inside - 1.0, -1.0, top)


def _eta_log_of(t: Array, r: Array) -> Array:
    """pyramid-log's η from t and r = min(|u|, |w|)/max(|u|, |w|) (0 in the view's vertical plane, 1 on the diagonal).

    Inside: a blend, by r, of the perspective shape min(t, 2t²) − 1 and the diagonal's
    −(1 − t)⁵, capped by 3t² − 1 near the view axis; outside: a ramp to η = 1 at t = 1 + τ
    (τ = 0.3, where the guard ends).
    Both inside terms tend to −1 as t → 0 and to 0 as t → 1, so η is continuous.
    """
    with np.errstate(over="ignore", invalid="ignore"):
        tc = np.minimum(t, 1.0)
        blend = (1.0 - r) * (np.minimum(tc, AXIS_SLOPE * tc * tc) - 1.0) - r * (1.0 - tc) ** LOG_DIAGONAL_POWER
        inside = np.minimum(blend, LOG_AXIS_SLOPE * tc * tc - 1.0)
        return np.where(t < 1.0, inside, np.clip((t - 1.0) / GUARD_WIDTH, 0.0, 1.0))  # plateau where the guard ends


def _t_and_r(a: Array, b: Array) -> tuple[Array, Array]:
    """t = max(a, b) and r = min(a, b)/max(a, b) (0 where t is 0 or infinite) of |u|, |w|."""
    t = np.maximum(a, b)
    ok = np.isfinite(t) & (t > 0)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(ok, np.minimum(a, b) / np.where(ok, t, 1.0), 0.0)
    return t, r


def eta_pyramid_log(light: ArrayLike, fov: ArrayLike) -> Array:
    """η of pyramid-log (log+perspective), from the light's image position (docs/warping_rule.md §6).

    Parameters
    ----------
    light : array_like
        Directions towards the light ``(N, 3)``.
    fov : array_like
        Full field of view [deg].

    Example
    -------
    >>> from aliasing.geometry import light_direction
    >>> eta_pyramid_log(light_direction([20.0, 20.0, 32.0], [0.0, 45.0, 0.0]), 60.0).round(3)  # vertical plane, diagonal, outside
    array([-0.37 , -0.404,  0.274])
    """
    u, w = image_position(light, fov)
    return _eta_log_of(*_t_and_r(np.abs(u), np.abs(w)))


def eta_pyramid(light: ArrayLike, fov: ArrayLike, eta_outside: float = 0.0) -> Array:
    """η of the pyramid rule: clip(min(t, 2t²) − 1, −1, η_out), t = max(|u|, |w|).

    Parameters
    ----------
    light : array_like
        Directions towards the light ``(N, 3)``.
    fov : array_like
        Full field of view [deg].
    eta_outside : float
        The plateau η for lights outside the view pyramid, in [0, 1]: n/f for perspective
        (n′ = n_γ√(f/n), the S-optimal plateau); larger values ramp to it over 1 ≤ t ≤ 1 + η_out.

    Example
    -------
    >>> from aliasing.geometry import light_direction
    >>> eta_pyramid(light_direction([0.0, 10.0, 25.0, 90.0], 0.0), 60.0, 0.001).round(4)
    array([-1.    , -0.8135, -0.1923,  0.001 ])
    """
    top = float(check.closed_range(eta_outside, "eta_outside", 0.0, 1.0))
    u, w = image_position(light, fov)
    return _eta_of_t(np.maximum(np.abs(u), np.abs(w)), top)


def pyramid_t(gamma: ArrayLike, azimuth: ArrayLike, fov: ArrayLike) -> Array:
    """t = tanγ·max(|sin φ|, |cos φ|)/tanθ, γ folded to [0°, 90°] [deg in, dimensionless out]."""
    return pyramid_t_r(gamma, azimuth, fov)[0]


def pyramid_t_r(gamma: ArrayLike, azimuth: ArrayLike, fov: ArrayLike) -> tuple[Array, Array]:
    """(t, r): t as :func:`pyramid_t`, r = min(|sin φ|, |cos φ|)/max(|sin φ|, |cos φ|) [dimensionless]."""
    g = check.closed_range(gamma, "gamma", 0.0, 180.0, " degrees")
    g = np.minimum(g, 180.0 - g)
    phi = np.radians(check.as_float_array(azimuth, "azimuth"))
    tan = tan_theta(fov)
    with np.errstate(over="ignore"):
        scale = np.tan(np.radians(g)) / tan
        return _t_and_r(scale * np.abs(np.sin(phi)), scale * np.abs(np.cos(phi)))


def n_prime_pyramid(near: ArrayLike, far: ArrayLike, t: ArrayLike, depth: ArrayLike, eta_outside: ArrayLike | None = None, r: ArrayLike | None = None) -> Array:
    """n′ [world units] of the pyramid rules from t and the light-space depth W_ly [world units].

    η = clip(min(t, 2t²) − 1, −1, η_out) through eq. 120 (η_out = n/f by default, the
    perspective plateau n′ = n_γ√(f/n)); with ``r`` given, pyramid-log's η of t and r
    instead (:func:`eta_pyramid_log`); then n′ ≥ c·W_ly·max(0, 1 − |t − 1|/τ).

    Example
    -------
    >>> float(n_prime_pyramid(1.0, 1000.0, 1.0, 999.0))  # at the boundary the guard binds: 0.1 W_ly
    99.9
    >>> round(float(n_prime_pyramid(1.0, 100.0, 3.0, 99.0)), 6)  # outside: n_γ√(f/n) = 1·10
    10.0
    """
    n, f = check.frustum(near, far)
    top = n / f if eta_outside is None else check.closed_range(eta_outside, "eta_outside", 0.0, 1.0)
    tt = check.as_float_array(t, "t")
    d = check.positive(depth, "depth")
    eta = _eta_of_t(tt, top) if r is None else _eta_log_of(tt, check.as_float_array(r, "r"))
    npr = warping.n_prime_from_eta(eta, n, f, d)  # eq. (120), Lloyd et al. 2007
    guard = GUARD * d * np.clip(1.0 - np.abs(tt - 1.0) / GUARD_WIDTH, 0.0, 1.0)  # NaN-free: t = inf gives 0
    return np.maximum(npr, np.where(np.isfinite(tt), guard, 0.0))


@register("pyramid", "new (this toolkit, docs/warping_rule.md): η from the light's vanishing point in the eye image", "eta = clip(min(t, 2t^2) - 1, -1, n/f), t = max(|u|,|w|) of the light's image position / tan(theta), n' >= 0.1 W_ly near t = 1; perspective", bounded=True)
def _pyramid(near: ArrayLike, far: ArrayLike, *, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None, azimuth: ArrayLike = 0.0) -> Array:
    """n′ [world units] of the pyramid rule from γ and the light's azimuth [deg] (eq. 120's n_γ).

    t = tanγ·max(|sin φ|, |cos φ|)/tanθ with γ folded to [0°, 90°]; :func:`aliasing.schemes.evaluate`
    passes each direction's azimuth φ (``warping.CONTEXT``); alone, φ defaults to 0.
    """
    n, f = check.frustum(near, far)
    d = (f - n) if depth is None else depth
    return n_prime_pyramid(n, f, pyramid_t(gamma, azimuth, fov), d)


@register("pyramid-log", "new (this toolkit, docs/warping_rule.md): the pyramid rule for the log+perspective map", "inside: blend by r = min/max(|u|,|w|) of min(t, 2t^2) - 1 and -(1 - t)^5, capped by 3t^2 - 1; outside: ramp to eta = 1 at t = 1.3; guard as pyramid; the scheme 'pyramid-log' uses it with the log+perspective parameterization", bounded=True)
def _pyramid_log(near: ArrayLike, far: ArrayLike, *, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None, azimuth: ArrayLike = 0.0) -> Array:
    """n′ [world units] of pyramid-log: η of :func:`eta_pyramid_log` through eq. 120 and the same guard."""
    n, f = check.frustum(near, far)
    d = (f - n) if depth is None else depth
    t, r = pyramid_t_r(gamma, azimuth, fov)
    return n_prime_pyramid(n, f, t, d, r=r)


def evaluate(rule: str, near: float, far: float, fov: float, light: ArrayLike) -> Array:
    """S̄ per direction of a rule of :data:`RULES` (through :func:`aliasing.schemes.evaluate`)."""
    return schemes.evaluate(rule, near, far, fov, geometry.lights(light)).S


def near_axis_directions(step: float = 1.0) -> Array:
    """Dense directions near the view axis (γ 1e-4°, 0.02°…10°, every ``step`` degrees of azimuth).

    At small f/n Standard's maximum is the limit towards the view axis along the pyramid's
    diagonal (the light frame turns with the azimuth there; 200 at f/n = 10), which
    equal-area samples miss (199.37 with 20,000); :func:`grid_study` takes maxima over these
    directions too.  γ = 1e-4° stands for that limit.

    Example
    -------
    >>> near_axis_directions(90.0).shape
    (344, 3)
    """
    g, az = np.meshgrid(np.r_[1e-4, 0.02:1.0:0.02, 1.0:10.0:0.25], np.arange(0.0, 360.0, float(check.positive(step, "step"))))
    return geometry.light_direction(g.ravel(), az.ravel())


def grid_study(rules=RULES, f_over_n=F_OVER_N, fovs=FOVS, light: str | ArrayLike = "hemisphere:2000") -> dict[str, Array]:
    """max_dir S / max_dir S_Standard and mean_dir S / mean_dir S_opt on a grid, per rule.

    The reference optimum is ``Sopt`` for perspective rules and ``LogSopt`` for the log ones
    (LogP, pyramid-log).  Returns ``{"max_ratio": (R, F, V), "mean_ratio": (R, F, V)}`` with
    R rules, F values of f/n, V fields of view, and the axes.  Near = 1.  Maxima are taken
    over ``light`` and :func:`near_axis_directions`; means over ``light`` only.
    """
    lv = geometry.lights(light)
    both = np.vstack([lv, near_axis_directions()])  # maxima: the samples and the view axis' neighbourhood
    fn_arr, fov_arr = np.asarray(f_over_n, float), np.asarray(fovs, float)
    mx = np.empty((len(rules), fn_arr.size, fov_arr.size))
    mean = np.empty_like(mx)
    for j, fn in enumerate(fn_arr):  # loops over the grid only; each evaluation is vectorised over directions
        for k, fov in enumerate(fov_arr):
            std = schemes.evaluate("Standard", 1.0, fn, fov, both).S.max()
            opt = {p: schemes.evaluate(p, 1.0, fn, fov, lv).S.mean() for p in ("Sopt", "LogSopt")}
            for i, s in enumerate(schemes.evaluate(list(rules), 1.0, fn, fov, both)):
                mx[i, j, k] = s.S.max() / std
                mean[i, j, k] = s.S[: len(lv)].mean() / opt["LogSopt" if rules[i] in ("LogP", "pyramid-log") else "Sopt"]
    return {"max_ratio": mx, "mean_ratio": mean, "rules": np.array(rules), "f_over_n": fn_arr, "fov": fov_arr}
