"""A warping rule from the light's position in the eye's image ("pyramid" rule), and the grid study.

Beyond the papers (issue 15 item 6; derivation and measurements in docs/warping_rule.md).
Lloyd et al. 2007's eq. 79 shapes η by γ alone.  The S-optimal η (scheme ``Sopt``) shows a
simpler structure: for a light whose direction (folded towards the view direction) lies
*outside* the view frustum's pyramid of directions, η_opt sits on the plateau η = 0 (n′ =
n_γ(1 + √(f/n)), LiSPSM's parameter in light-plane units, Lloyd 2007 eq. 120) — App. A's "largest
a on the equivalent range"; *inside* the pyramid it falls towards −1 (uniform).  Whether the
light is inside is decided by its vanishing point in the eye's image,

    (u, w) = (l_x, l_y)/(l_z tanθ),   t = max(|u|, |w|)   (t < 1: inside the pyramid),

which depends on the azimuth of the light as well as on γ (t = tanγ·max(|sin φ|, |cos φ|)/tanθ).
The rule is η = clip(t − 1, −1, 0), n′ from η by eq. 120, and a guard near the pyramid's
boundary: n′ ≥ c·W_ly·max(0, 1 − |t − 1|/τ), c = 0.1, τ = 0.3 (there the S-optimal centre of
projection sits about 0.1 W_ly before the near face, which η ≈ 0 cannot express at large f/n;
docs/warping_rule.md §5).  Continuous in the light direction, no per-direction optimisation:
a few divisions and two maxima per direction.  Its log+perspective counterpart uses
η = clip(t − 1, −1, 1) (a ramp to LogSopt's plateau η = 1, reached at t = 2) and the same guard.

What holds on the grid f/n ∈ 10…1e5, fov 20°…120° (docs/warping_rule.md): see
:func:`grid_study` and the reproduce target ``warping-rule-grid``.

Example
-------
>>> import numpy as np
>>> from aliasing.geometry import light_direction
>>> eta_pyramid(light_direction(np.array([90.0, 15.0, 0.0]), 0.0), 60.0).round(3)  # overhead, inside, along the view
array([ 0.   , -0.536, -1.   ])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from . import directional, geometry, schemes, warping
from .warping import register

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
    tan = np.tan(np.radians(check.fov(fov)) / 2)
    lz = np.abs(lv[:, 2])
    sign = np.where(lv[:, 2] < 0, -1.0, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.where(lz > 0, sign * lv[:, 0] / (lz * tan), np.copysign(np.inf, lv[:, 0]))
        w = np.where(lz > 0, sign * lv[:, 1] / (lz * tan), np.copysign(np.inf, lv[:, 1]))
    return u, w


def eta_pyramid(light: ArrayLike, fov: ArrayLike, eta_outside: float = 0.0) -> Array:
    """η of the pyramid rule: clip(t − 1, −1, η_out), t = max(|u|, |w|).

    Parameters
    ----------
    light : array_like
        Directions towards the light ``(N, 3)``.
    fov : array_like
        Full field of view [deg].
    eta_outside : float
        The plateau η for lights far outside the view pyramid: 0 for perspective (the
        S-optimal plateau's largest n′), 1 for log+perspective (reached at t = 2); in [0, 1].
    """
    top = float(check.closed_range(eta_outside, "eta_outside", 0.0, 1.0))
    u, w = image_position(light, fov)
    t = np.maximum(np.abs(u), np.abs(w))
    return np.clip(t - 1.0, -1.0, top)


GUARD, GUARD_WIDTH = 0.1, 0.3  # c and τ of the boundary guard (docs/warping_rule.md §5)


def pyramid_t(gamma: ArrayLike, azimuth: ArrayLike, fov: ArrayLike) -> Array:
    """t = tanγ·max(|sin φ|, |cos φ|)/tanθ, γ folded to [0°, 90°] [deg in, dimensionless out]."""
    g = check.closed_range(gamma, "gamma", 0.0, 180.0, " degrees")
    g = np.minimum(g, 180.0 - g)
    phi = np.radians(check.as_float_array(azimuth, "azimuth"))
    tan = np.tan(np.radians(check.fov(fov)) / 2)
    with np.errstate(over="ignore"):
        return np.tan(np.radians(g)) * np.maximum(np.abs(np.sin(phi)), np.abs(np.cos(phi))) / tan


def n_prime_pyramid(near: ArrayLike, far: ArrayLike, t: ArrayLike, depth: ArrayLike, eta_outside: float = 0.0) -> Array:
    """n′ [world units] of the pyramid rule from t and the light-space depth W_ly [world units].

    η = clip(t − 1, −1, η_out) through eq. 120, then n′ ≥ c·W_ly·max(0, 1 − |t − 1|/τ).

    Example
    -------
    >>> float(n_prime_pyramid(1.0, 1000.0, 1.0, 999.0))  # at the boundary the guard binds: 0.1 W_ly
    99.9
    """
    top = float(check.closed_range(eta_outside, "eta_outside", 0.0, 1.0))
    tt = check.as_float_array(t, "t")
    d = check.positive(depth, "depth")
    npr = warping.n_prime_from_eta(np.clip(tt - 1.0, -1.0, top), near, far, d)
    guard = GUARD * d * np.clip(1.0 - np.abs(tt - 1.0) / GUARD_WIDTH, 0.0, 1.0)  # NaN-free: t = inf gives 0
    return np.maximum(npr, np.where(np.isfinite(tt), guard, 0.0))


@register("pyramid", "new (this toolkit, docs/warping_rule.md): η from the light's vanishing point in the eye image", "eta = clip(t - 1, -1, 0), t = max(|u|,|w|) of the light's image position / tan(theta), n' >= 0.1 W_ly near t = 1; needs azimuth (default 0)")
def _pyramid(near: ArrayLike, far: ArrayLike, *, fov: ArrayLike = 60.0, gamma: ArrayLike = 90.0, depth: ArrayLike | None = None, azimuth: ArrayLike = 0.0) -> Array:
    """n′ [world units] of the pyramid rule from γ and the light's azimuth [deg] (eq. 120's n_γ).

    t = tanγ·max(|sin φ|, |cos φ|)/tanθ with γ folded to [0°, 90°]; ``azimuth`` φ defaults to 0
    (the view's vertical plane) because :func:`aliasing.schemes.evaluate` passes only γ and the
    depth; pass ``azimuth=`` per direction for the full rule (as :func:`grid_study` does).
    """
    n, f = check.frustum(near, far)
    d = (f - n) if depth is None else depth
    return n_prime_pyramid(n, f, pyramid_t(gamma, azimuth, fov), d)


def evaluate(rule: str, near: float, far: float, fov: float, light: ArrayLike) -> Array:
    """S̄ per direction of a rule of :data:`RULES` with the light's full geometry (azimuth too)."""
    lv = geometry.lights(light)
    if rule not in ("pyramid", "pyramid-log"):
        return schemes.evaluate(rule, near, far, fov, lv).S
    n_i, f_i = np.array([float(near)]), np.array([float(far)])
    lf = directional.fit(geometry.frustum_vertices(n_i, f_i, fov), lv)
    u, w = image_position(lv, fov)
    t = np.maximum(np.abs(u), np.abs(w))[:, None]
    npr = n_prime_pyramid(n_i, f_i, t, lf.depth, 1.0 if rule == "pyramid-log" else 0.0)
    mx, mz = directional.vertex_errors(lf, fov, npr, "logperspective" if rule == "pyramid-log" else "perspective")
    return (mx.max(-1) * mz.max(-1)).sum(-1)


def grid_study(rules=RULES, f_over_n=F_OVER_N, fovs=FOVS, light: str | ArrayLike = "hemisphere:2000") -> dict[str, Array]:
    """max_dir S / max_dir S_Standard and mean_dir S / mean_dir S_opt on a grid, per rule.

    The reference optimum is ``Sopt`` for perspective rules and ``LogSopt`` for the log ones
    (LogP, pyramid-log).  Returns ``{"max_ratio": (R, F, V), "mean_ratio": (R, F, V)}`` with
    R rules, F values of f/n, V fields of view, and the axes.  Near = 1.
    """
    lv = geometry.lights(light)
    fn_arr, fov_arr = np.asarray(f_over_n, float), np.asarray(fovs, float)
    mx = np.empty((len(rules), fn_arr.size, fov_arr.size))
    mean = np.empty_like(mx)
    for j, fn in enumerate(fn_arr):  # loops over the grid only; each evaluation is vectorised over directions
        for k, fov in enumerate(fov_arr):
            std = schemes.evaluate("Standard", 1.0, fn, fov, lv).S.max()
            opt = {p: schemes.evaluate(p, 1.0, fn, fov, lv).S.mean() for p in ("Sopt", "LogSopt")}
            for i, rule in enumerate(rules):
                s = evaluate(rule, 1.0, fn, fov, lv)
                mx[i, j, k] = s.max() / std
                mean[i, j, k] = s.mean() / opt["LogSopt" if rule in ("LogP", "pyramid-log") else "Sopt"]
    return {"max_ratio": mx, "mean_ratio": mean, "rules": np.array(rules), "f_over_n": fn_arr, "fov": fov_arr}
