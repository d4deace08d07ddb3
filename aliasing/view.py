"""The eye's view frustum as one validated value: ``View(near, far, fov)``.

``near`` and ``far`` [world units] and the full field of view ``fov`` [deg] travel together
through every layer of the toolkit; a :class:`View` checks them once (0 < near < far < inf,
0 < fov < 180, no NaN) and holds what the formulas derive from them: θ = fov/2 [rad],
tan θ, cos θ, f/n and the frustum's four corner rays.  **This module is the one place where
the field of view is converted from degrees to radians.**

The three fields may be scalars or arrays that broadcast together (a family of frusta, as
:func:`aliasing.geometry.frustum_vertices` has always accepted); scalars are stored as
Python floats, arrays as read-only float arrays of the broadcast shape.  The public
functions that take ``(near, far, fov)`` also take a View in place of ``near``
(:func:`as_view` does the conversion at their edge).

Example
-------
>>> v = View(1.0, 100.0, 90.0)
>>> v.ratio, round(v.tan_theta, 12)
(100.0, 1.0)
>>> v.corner_rays.round(12).tolist()[2]   # right-top corner at unit eye depth
[1.0, 1.0, 1.0]
>>> v.slice_vertices(1.0, 2.0).shape
(8, 3)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check

Array = NDArray[np.float64]
# corner order: left-bottom, right-bottom, right-top, left-top (x right, y up)
CORNER_SIGNS = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


def _store(value: Array) -> float | Array:
    if value.ndim == 0:
        return float(value)
    value = np.array(value, dtype=float)
    value.setflags(write=False)
    return value


@dataclass(frozen=True, eq=False)
class View:
    """A square symmetric view frustum, validated once.

    Parameters
    ----------
    near, far : float or array_like
        Eye near and far distances [world units], 0 < near < far < inf.
    fov : float or array_like
        Full field of view [deg], 0 < fov < 180; θ = fov/2.

    Raises
    ------
    ValueError
        Naming ``near``, ``far`` or ``fov`` and its allowed range (also for NaN, non-numbers
        and shapes that do not broadcast).

    Example
    -------
    >>> View(1.0, 1000.0, 60.0).theta_deg
    30.0
    >>> View(2.0, 1.0, 60.0)
    Traceback (most recent call last):
    ...
    ValueError: far must be greater than near (far/near in (1, inf)), got near=2, far=1
    """

    near: Any
    far: Any
    fov: Any
    _theta: Any = field(init=False, repr=False)

    def __post_init__(self) -> None:
        n, f = check.frustum(self.near, self.far)
        a = check.fov(self.fov)
        n, f, a = check.broadcast(near=n, far=f, fov=a)  # a shape error names the three and their shapes
        theta = half_angle(a)
        for name, value in (("near", n), ("far", f), ("fov", a), ("_theta", theta)):
            object.__setattr__(self, name, _store(value))

    @property
    def shape(self) -> tuple[int, ...]:
        """Broadcast shape of the fields (``()`` for one frustum)."""
        return np.shape(self.near)

    @property
    def theta(self) -> float | Array:
        """Half field of view θ [rad]."""
        return self._theta

    @property
    def theta_deg(self) -> float | Array:
        """Half field of view θ [deg] (exactly fov/2)."""
        return self.fov / 2

    @property
    def tan_theta(self) -> float | Array:
        """tan θ [dimensionless]: the half-width of the image at unit eye depth."""
        return _store(np.tan(np.asarray(self._theta)))

    @property
    def cos_theta(self) -> float | Array:
        """cos θ [dimensionless]."""
        return _store(np.cos(np.asarray(self._theta)))

    @property
    def ratio(self) -> float | Array:
        """f/n [dimensionless], > 1."""
        return _store(np.asarray(self.far) / np.asarray(self.near))

    @property
    def corner_rays(self) -> Array:
        """The 4 corner rays at unit eye depth, ``shape + (4, 3)`` [world units per unit depth].

        Order: left-bottom, right-bottom, right-top, left-top; a vertex at eye depth d is
        ``d * ray`` (up to rounding: :meth:`slice_vertices` forms them as the toolkit always has).
        """
        t = np.asarray(self.tan_theta)[..., None]
        return np.stack([CORNER_SIGNS[:, 0] * t, CORNER_SIGNS[:, 1] * t, np.ones_like(t * CORNER_SIGNS[:, 0])], axis=-1)

    def slice_vertices(self, z0: ArrayLike | None = None, z1: ArrayLike | None = None) -> Array:
        """The 8 vertices of the frustum between eye depths z0 < z1 [world units].

        Defaults: the whole frustum (near, far).  Shape ``broadcast(z0, z1, fields) + (8, 3)``:
        the 4 corners at z0, then the 4 at z1, in :attr:`corner_rays` order.

        Example
        -------
        >>> View(1.0, 10.0, 90.0).slice_vertices()[[0, 6]].round(12).tolist()
        [[-1.0, -1.0, 1.0], [10.0, 10.0, 10.0]]
        """
        n = np.asarray(self.near if z0 is None else check.positive(z0, "z0"))
        f = np.asarray(self.far if z1 is None else check.positive(z1, "z1"))
        if (f <= n).any():
            raise ValueError("z1 must be greater than z0 (a slice of positive depth)")
        n, f, t = np.broadcast_arrays(n, f, np.asarray(self.tan_theta))
        depth = np.stack([n] * 4 + [f] * 4, axis=-1)  # (..., 8)
        sx = np.concatenate([CORNER_SIGNS[:, 0], CORNER_SIGNS[:, 0]])
        sy = np.concatenate([CORNER_SIGNS[:, 1], CORNER_SIGNS[:, 1]])
        half = depth * t[..., None]
        return np.stack([sx * half, sy * half, depth], axis=-1)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, View):
            return NotImplemented
        return all(np.array_equal(getattr(self, k), getattr(other, k)) for k in ("near", "far", "fov"))

    def __hash__(self) -> int:
        return hash(tuple(np.asarray(getattr(self, k)).tobytes() for k in ("near", "far", "fov")))


def half_angle(fov: ArrayLike, name: str = "fov") -> Array:
    """θ = fov/2 [rad] from the full field of view [deg], 0 < fov < 180 (validated).

    The one degrees → radians conversion of the field of view in the toolkit.

    Example
    -------
    >>> round(float(np.tan(half_angle(90.0))), 12)
    1.0
    """
    return np.radians(check.fov(fov, name)) / 2


def as_view(near: View | ArrayLike, far: ArrayLike | None = None, fov: ArrayLike | None = None) -> View:
    """A View from a View (returned as is) or from the three numbers.

    Example
    -------
    >>> as_view(1.0, 100.0, 60.0) == as_view(View(1.0, 100.0, 60.0))
    True
    """
    if isinstance(near, View):
        if far is not None or fov is not None:
            raise ValueError("pass either a View or near, far, fov, not both")
        return near
    if far is None or fov is None:
        raise ValueError("far and fov are required unless near is a View")
    return View(near, far, fov)


def split_view(near: View | ArrayLike | None, far: Any, fov: Any, rest: Any, defaults: tuple[Any, Any, Any, Any]) -> tuple[View, Any]:
    """Resolve ``(near, far, fov, <next argument>)`` where ``near`` may be a View.

    With a View in ``near`` the arguments after it move up one place, so that
    ``f(view, light)`` means ``f(near, far, fov, light)``.  ``None`` means "not given";
    ``defaults`` are (near, far, fov, next argument).

    Example
    -------
    >>> split_view(View(1.0, 10.0, 60.0), "overhead", None, None, (1.0, 1000.0, 60.0, "front"))[1]
    'overhead'
    >>> split_view(None, 10.0, None, None, (1.0, 1000.0, 60.0, "front"))
    (View(near=1.0, far=10.0, fov=60.0), 'front')
    """
    dn, df, da, dr = defaults
    if near is not None and far is None and not isinstance(near, View):
        raise ValueError(f"far is required beside near={near!r} (the default far goes with the default near), or a View in place of near")
    if isinstance(near, View):
        if fov is not None or (far is not None and rest is not None):
            raise ValueError("with a View, pass the arguments that follow it once (e.g. light), not far and fov")
        nxt = far if far is not None else rest
        nxt = dr if nxt is None else nxt
        if nxt is None:
            raise ValueError("the argument after the View (light) is required")
        return near, nxt
    given = {"near": dn if near is None else near, "far": df if far is None else far, "fov": da if fov is None else fov, "light": dr if rest is None else rest}
    missing = [k for k, v in given.items() if v is None]
    if missing:
        raise ValueError(f"{', '.join(missing)} required (or a View in place of near)")
    return View(given["near"], given["far"], given["fov"]), given["light"]
