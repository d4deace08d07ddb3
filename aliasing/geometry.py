"""View frusta, light directions, light space: the geometry every scheme stands on.

Eye space: the eye at the origin looking along +z (the view vector v), x to the right,
y up; a square image, so the frustum's half-angle θ = fov/2 applies to x and y alike.
Light directions are unit vectors **towards** the light, given by

* γ [deg], the angle between v and the light vector: 0° looking into the light
  ("front"), 90° perpendicular, 180° light behind the viewer ("behind");
* an azimuth [deg] around v, measured from up (+y) towards +x, so that γ = 90°,
  azimuth 0° is an overhead light.

Light space is Wimmer et al. 2004 §3.4: y_L points to the light, z_L is perpendicular to
it in the plane of v and the light, oriented like v, and x_L = y_L × z_L.  When the light is
parallel to v that plane is undefined (the paper does not say what to do; every warp
becomes uniform there): we take z_L = the eye's up vector (+y), which is perpendicular to
the light in that case.  It is the limit of the general rule as γ → 180° at azimuth 0°
(and its negative as γ → 0°); since the frustum is symmetric and the map uniform, no
error metric depends on the choice.

Example
-------
>>> import numpy as np
>>> light_direction(90.0, 0.0).round(12)  # overhead
array([0., 1., 0.])
>>> frustum_vertices(1.0, 10.0, 90.0).shape
(8, 3)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from .view import View, as_view

Array = NDArray[np.float64]
VIEW = np.array([0.0, 0.0, 1.0])
UP = np.array([0.0, 1.0, 0.0])


def frustum_vertices(near: ArrayLike | View, far: ArrayLike | None = None, fov: ArrayLike | None = None) -> Array:
    """The 8 corners of square view frusta, shape ``broadcast(near, far, fov).shape + (8, 3)``.

    Parameters
    ----------
    near, far : array_like
        Near and far distances [world units], 0 < near < far; or a
        :class:`aliasing.View` in ``near`` (and nothing else).
    fov : array_like
        Full field of view [deg], 0 < fov < 180.

    Returns
    -------
    ndarray
        Corners in eye space [world units]: the 4 near corners then the 4 far corners.
    """
    return as_view(near, far, fov).slice_vertices()


def light_direction(gamma: ArrayLike, azimuth: ArrayLike = 0.0) -> Array:
    """Unit vectors towards the light from γ and azimuth [deg]; shape ``(..., 3)``.

    Exact at multiples of 90° (overhead is exactly (0, 1, 0)).

    Example
    -------
    >>> light_direction([0.0, 180.0])
    array([[ 0.,  0.,  1.],
           [ 0.,  0., -1.]])
    """
    g = check.closed_range(gamma, "gamma", 0.0, 180.0, " degrees")
    a = check.finite(azimuth, "azimuth")
    g, a = check.broadcast(gamma=g, azimuth=a)
    sg, cg = sind(g), sind(90.0 - g)
    return np.stack([sg * sind(a), sg * sind(90.0 - a), cg], axis=-1)


def sind(x: ArrayLike) -> Array:
    """sin of an angle in degrees, exact at multiples of 90° (the argument is folded to [−90°, 90°])."""
    r = check.finite(x, "x")
    r = np.where(np.abs(r) > 180.0, np.remainder(r + 180.0, 360.0) - 180.0, r)  # reduce only when needed: keeps tiny angles exact
    r = np.where(r > 90.0, 180.0 - r, np.where(r < -90.0, -180.0 - r, r))
    return np.sin(np.radians(r))


def direction_angles(light: ArrayLike) -> tuple[Array, Array]:
    """(γ, azimuth) [deg] of light vectors ``(..., 3)`` (need not be normalised)."""
    lv = _unit(light)
    gamma = np.degrees(np.arctan2(np.hypot(lv[..., 0], lv[..., 1]), lv[..., 2]))  # accurate near 0° and 180°
    azimuth = np.degrees(np.arctan2(lv[..., 0], lv[..., 1]))
    return gamma, azimuth


def light_space(light: ArrayLike) -> Array:
    """Wimmer et al. 2004 §3.4 light-space bases, rows (x_L, y_L, z_L); shape ``(..., 3, 3)``.

    y_L is the light vector, z_L = normalise(v − (v·y_L) y_L); when the light is parallel to
    the view vector (|v × y_L| below 1e-12) z_L is the eye's up vector made perpendicular to
    y_L instead (see the module docstring).

    Example
    -------
    >>> light_space([0.0, 1.0, 0.0]).round(12)  # overhead: z_L is the view vector
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    y = _unit(light)
    # (y × v) × y = v − (v·y) y, but without the cancellation as y → ±v
    z = np.cross(np.cross(y, VIEW), y)
    norm = np.linalg.norm(z, axis=-1, keepdims=True)
    up = np.cross(np.cross(y, UP), y)
    degenerate = norm < 1e-300
    z = np.where(degenerate, up, z)
    z = z / np.linalg.norm(z, axis=-1, keepdims=True)
    x = np.cross(y, z)
    return np.stack([x, y, z], axis=-2)


def sphere_directions(count: int) -> Array:
    """``count`` deterministic, near-uniform (equal solid angle) directions on the sphere.

    A Fibonacci lattice: point i at height 1 − (2i + 1)/count, golden-angle longitudes.
    """
    count = _count(count)
    i = np.arange(count)
    h = 1.0 - (2.0 * i + 1.0) / count
    lon = i * np.pi * (3.0 - np.sqrt(5.0))
    r = np.sqrt(1.0 - h * h)
    # the lattice's pole axis is the eye's up vector, so hemispheres split cleanly
    return np.stack([r * np.sin(lon), h, r * np.cos(lon)], axis=-1)


def hemisphere_directions(count: int) -> Array:
    """``count`` deterministic equal-solid-angle directions above the viewer (light · up ≥ 0)."""
    count = _count(count)
    i = np.arange(count)
    h = 1.0 - (i + 0.5) / count  # uniform in height ⇒ uniform in solid angle (Archimedes)
    lon = i * np.pi * (3.0 - np.sqrt(5.0))
    r = np.sqrt(1.0 - h * h)
    return np.stack([r * np.sin(lon), h, r * np.cos(lon)], axis=-1)


def hemisphere_map(resolution: int) -> tuple[Array, Array, Array]:
    """Directions over the upper hemisphere on a square grid, for plots like Lloyd 2006 Fig. 7.

    Orthographic view from above: overhead in the centre, behind the viewer on the left
    (u = −1), in front on the right (u = +1); v runs sideways (x).  Returns ``(u, v, light)``
    with ``light`` of shape ``(resolution, resolution, 3)``, NaN outside the unit disc.
    """
    res = _count(resolution, "resolution", MAX_MAP_RESOLUTION)
    c = np.linspace(-1.0, 1.0, res)
    u, v = np.meshgrid(c, c)
    h2 = 1.0 - u * u - v * v
    inside = h2 >= 0
    light = np.stack([v, np.sqrt(np.where(inside, h2, 0.0)), u], axis=-1)
    light[~inside] = np.nan
    return u, v, light


def _unit(light: ArrayLike) -> Array:
    lv = check.finite(light, "light")  # an infinite vector has no direction
    if lv.shape[-1:] != (3,):
        raise ValueError(f"light must have shape (..., 3), got {lv.shape}")
    with np.errstate(over="ignore", under="ignore"):
        norm = np.linalg.norm(lv, axis=-1, keepdims=True)
    if (norm == 0).any() and (np.abs(lv).max(axis=-1) == 0).any():
        raise ValueError("light must be a non-zero vector")
    extreme = ~np.isfinite(norm) | (norm < 1e-150)
    if extreme.any():  # |v| near 1e308 or 1e-320 overflows or loses digits: scale such vectors first
        scale = np.abs(lv).max(axis=-1, keepdims=True)
        lv = np.where(extreme, lv / np.where(extreme, scale, 1.0), lv)
        norm = np.where(extreme, np.linalg.norm(lv, axis=-1, keepdims=True), norm)
    return lv / norm  # plain v/|v| otherwise: the same bits as before the scaling was added


# Most directions a spec or count may ask for: (N, 3) float64 is 240 MB at 10^7.
MAX_DIRECTIONS = 10**7
# Largest hemisphere_map grid side (three (res, res) arrays and a (res, res, 3) one).
MAX_MAP_RESOLUTION = 8192


def _count(value: int, name: str = "count", hi: int = MAX_DIRECTIONS) -> int:
    return check.whole(value, name, 1, hi)


LIGHT_SPEC = "overhead | behind | front | gamma:DEG[@azimuth:DEG] | sphere:N | hemisphere:N"


def _typed_angles(spec: str | ArrayLike) -> tuple[Array, Array]:
    """(γ, azimuth) [deg] of the directions of :func:`lights`, as the spec gives them (for outputs that echo them).

    For ``gamma:DEG[@azimuth:DEG]`` and the named lights these are the numbers as typed
    (``gamma:30`` gives 30, not the 29.999999999999996 that the unit vector's angle
    computes to); for sampled directions and vectors they are :func:`direction_angles`.

    Example
    -------
    >>> _typed_angles("gamma:30@azimuth:45")
    (array([30.]), array([45.]))
    >>> [float(g) for g in direction_angles(lights("gamma:30"))[0]]
    [29.999999999999996]
    """
    lv = lights(spec)  # validates the spec (and its ranges) first
    if isinstance(spec, str):
        text = spec.strip().lower()
        named = {"overhead": (90.0, 0.0), "behind": (180.0, 0.0), "front": (0.0, 0.0)}
        if text in named:
            return np.array([named[text][0]]), np.array([named[text][1]])
        kind, _, rest = text.partition(":")
        if kind == "gamma":
            gamma_text, _, az_text = rest.partition("@")
            return np.array([float(gamma_text)]), np.array([float(az_text.partition(":")[2]) if az_text else 0.0])
    return direction_angles(lv)


def lights(spec: str | ArrayLike) -> Array:
    """Light directions ``(N, 3)`` from a spec string (or pass vectors through).

    ``overhead`` (γ = 90°), ``behind`` (γ = 180°), ``front`` (γ = 0°), ``gamma:DEG`` with an
    optional ``@azimuth:DEG``, ``sphere:N`` and ``hemisphere:N`` (deterministic equal
    solid-angle samples; the hemisphere is above the viewer).

    Example
    -------
    >>> lights("gamma:45@azimuth:90").round(6)
    array([[0.707107, 0.      , 0.707107]])
    >>> lights("hemisphere:100").shape
    (100, 3)
    """
    if not isinstance(spec, str):
        return np.atleast_2d(_unit(spec))
    text = spec.strip().lower()
    named = {"overhead": (90.0, 0.0), "behind": (180.0, 0.0), "front": (0.0, 0.0)}
    try:
        if text in named:
            return light_direction(*named[text])[None]
        kind, _, rest = text.partition(":")
        if kind in ("sphere", "hemisphere") and rest:
            count = _count(int(rest), "N")
            return sphere_directions(count) if kind == "sphere" else hemisphere_directions(count)
        if kind == "gamma" and rest:
            gamma_text, _, az_text = rest.partition("@")
            azimuth = 0.0
            if az_text:
                key, _, value = az_text.partition(":")
                if key != "azimuth" or not value:
                    raise ValueError
                azimuth = float(value)
            return light_direction(float(gamma_text), azimuth)[None]
    except ValueError as exc:
        if "must" in str(exc):  # a range error from the checks: keep its message
            raise ValueError(f"light {spec!r}: {exc}") from None
    raise ValueError(f"malformed light {spec!r}; expected {LIGHT_SPEC}")
