"""A world-space camera and THE conversion world → eye space (the only one in the toolkit).

The toolkit computes in eye space (:mod:`aliasing.geometry`): the eye at the origin looking
along +z, x to the right, y up.  Engines and files place a camera in a world: an eye point,
a target (or a view direction) and an up vector, or a glTF camera node (looking along its
local −z with its local +y up).  :class:`Camera` holds such a camera and maps world points
and directions into eye space:

    x_e = (p − eye)·right,  y_e = (p − eye)·up′,  z_e = (p − eye)·forward

with forward = (target − eye)/|target − eye|, right = forward × up/|…| and
up′ = right × forward (up made orthogonal to the view).  Eye space is left-handed when the
world is right-handed (glTF, most engines), so the map is a rotation composed with a mirror
(determinant −1): triangle winding flips, which nothing in the toolkit depends on (normals
are turned towards the eye).

Example
-------
>>> cam = look_at([10.0, 2.0, 5.0], [0.0, 2.0, 5.0], near=0.5, far=100.0, fov=60.0)
>>> cam.to_eye([[0.0, 2.0, 5.0], [10.0, 3.0, 5.0]]).tolist()   # the target is 10 ahead; 1 above the eye is up
[[0.0, 0.0, 10.0], [0.0, 1.0, 0.0]]
>>> cam.direction_to_eye([0.0, 1.0, 0.0]).tolist()   # a light straight above: overhead
[0.0, 1.0, 0.0]
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ...view import View

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Camera:
    """A perspective camera in world space.

    Attributes
    ----------
    eye : ndarray (3,)
        Eye position [world units].
    rotation : ndarray (3, 3)
        Rows right, up, forward (unit, orthogonal) in world coordinates.
    near, far : float
        Eye near and far (shadow) distances [world units], 0 < near < far.
    fov : float
        Full vertical field of view [deg].
    name : str
        A label (the glTF camera's name, or "look-at").
    aspect : float
        Image width/height (default 1: a square image).
    """

    eye: Array
    rotation: Array
    near: float
    far: float
    fov: float
    name: str = "look-at"
    aspect: float = 1.0

    @functools.cached_property
    def view(self) -> View:
        """The camera's frustum as a :class:`~aliasing.View` (built once per camera)."""
        return View(self.near, self.far, self.fov, self.aspect)

    def to_eye(self, points: ArrayLike) -> Array:
        """Eye-space coordinates ``(..., 3)`` of world points ``(..., 3)`` [world units]."""
        p = np.asarray(points, float)
        return (p - self.eye) @ self.rotation.T

    def direction_to_eye(self, direction: ArrayLike) -> Array:
        """Eye-space unit vector of a world direction (e.g. towards the light); ValueError if zero."""
        d = vector(direction, "light direction")
        return (d / np.linalg.norm(d)) @ self.rotation.T

    def with_range(self, near: float | None = None, far: float | None = None, fov: float | None = None) -> "Camera":
        """The same camera (aspect included) with another near, far or field of view (None keeps the value)."""
        n = self.near if near is None else near
        f = self.far if far is None else far
        n, f = (float(v) for v in check.frustum(n, f))
        fv = float(check.fov(self.fov if fov is None else fov))
        return Camera(self.eye, self.rotation, n, f, fv, self.name, self.aspect)


def vector(value: ArrayLike | str, name: str) -> Array:
    """A finite 3-vector from an array-like or a string ``"X,Y,Z"``; ValueError naming ``name``.

    Example
    -------
    >>> vector("1, 2,3", "eye").tolist()
    [1.0, 2.0, 3.0]
    """
    if isinstance(value, str):
        try:
            v = np.array([float(x) for x in value.split(",")])
        except ValueError:
            raise ValueError(f"{name} must be three numbers X,Y,Z, got {value!r}") from None
    else:
        v = np.asarray(value, float)
    if v.shape != (3,) or not np.isfinite(v).all():
        raise ValueError(f"{name} must be three finite numbers X,Y,Z, got {value!r}")
    if name == "light direction" and not np.linalg.norm(v) > 0:
        raise ValueError(f"light direction must be a non-zero vector towards the light, got {value!r}")
    return v


def frame(forward: ArrayLike, up: ArrayLike) -> Array:
    """Rows right, up′, forward of a view (unit, orthogonal); ValueError if up ∥ forward."""
    f = vector(forward, "view direction")
    u = vector(up, "up")
    if not np.linalg.norm(f) > 0:
        raise ValueError("eye must differ from target (zero-length view direction)")
    if not np.linalg.norm(u) > 0:
        raise ValueError("up must be a non-zero vector")
    f = f / np.linalg.norm(f)
    r = np.cross(f, u / np.linalg.norm(u))
    if np.linalg.norm(r) < 1e-9:
        raise ValueError(f"up must not be parallel to the view direction (eye → target), got up {np.asarray(u).tolist()}")
    r /= np.linalg.norm(r)
    return np.stack([r, np.cross(r, f), f])


def look_at(eye: ArrayLike | str, target: ArrayLike | str, up: ArrayLike | str = (0.0, 1.0, 0.0), *, near: float = 1.0, far: float = 100.0, fov: float = 60.0) -> Camera:
    """A camera at ``eye`` looking at ``target`` with ``up`` towards the image's top.

    Parameters
    ----------
    eye, target : array_like or str
        Points [world units] ("X,Y,Z" strings accepted); they must differ.
    up : array_like or str
        Not parallel to target − eye (default +y).
    near, far : float
        0 < near < far [world units].
    fov : float
        Full field of view [deg], in (0, 180).

    Example
    -------
    >>> look_at("0,0,0", "0,0,-1").rotation.tolist()   # glTF's default view: −z
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]
    """
    e, t = vector(eye, "eye"), vector(target, "target")
    if np.array_equal(e, t):
        raise ValueError(f"eye must differ from target, both are {e.tolist()}")
    rot = frame(t - e, up)
    n, f = (float(v) for v in check.frustum(near, far))
    return Camera(e, rot + 0.0, n, f, float(check.fov(fov)))


def from_matrix(matrix: ArrayLike, *, near: float, far: float, fov: float, name: str = "camera") -> Camera:
    """A camera from a glTF node's world matrix (4×4, column vectors): local −z ahead, +y up."""
    m = np.asarray(matrix, float)
    if m.shape != (4, 4) or not np.isfinite(m).all():
        raise ValueError(f"camera {name!r}: node matrix must be a finite 4×4 matrix")
    rot = frame(-m[:3, 2], m[:3, 1])
    n, f = (float(v) for v in check.frustum(near, far))
    return Camera(m[:3, 3].copy(), rot, n, f, float(check.fov(fov)), name)


MAX_F_OVER_N = 1e15
"""Largest depth ratio far/near the rasterizer measures: beyond ~1e17 the rows of a LogP map
(log-spaced in float64) stop increasing, and ~1e300 overflows to NaN."""
MIN_FOV = 1e-6
"""Smallest full field of view [deg] the rasterizer measures (at ~1e-300 the eye rays underflow)."""


def check_raster_frustum(near: float, far: float, fov: float) -> None:
    """Refuse a frustum outside the rasterizer's float64 range (ValueError naming the range).

    The analytic functions take any far/near > 1 and fov in (0, 180); the rasterizer measures
    in float64 and is checked here before anything is rasterized.

    Example
    -------
    >>> check_raster_frustum(1.0, 1e20, 60.0)
    Traceback (most recent call last):
    ...
    ValueError: far/near must be <= 1e+15 for the rasterizer (float64 rows and depths), got 1e+20
    """
    ratio = float(far) / float(near)
    if ratio > MAX_F_OVER_N:
        raise ValueError(f"far/near must be <= {MAX_F_OVER_N:g} for the rasterizer (float64 rows and depths), got {ratio:g}")
    if float(fov) < MIN_FOV:
        raise ValueError(f"fov must be >= {MIN_FOV:g} degrees for the rasterizer (float64 eye rays), got {float(fov):g}")
