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


@dataclass(frozen=True, eq=False, repr=False)
class View:
    """A symmetric view frustum, validated once.

    Parameters
    ----------
    near, far : float or array_like
        Eye near and far distances [world units], 0 < near < far < inf.
    fov : float or array_like
        VERTICAL full field of view [deg], 0 < fov < 180; θ = θ_y = fov/2 (the engines'
        convention).
    aspect : float or array_like
        Image width/height, 0 < aspect < inf (default 1, the square view of the papers):
        tan θ_x = aspect·tan θ_y.  The image has square pixels: R_y rows and aspect·R_y
        columns, and errors are per pixel of that image (unit resolution: R_y = 1).

    Raises
    ------
    ValueError
        Naming ``near``, ``far``, ``fov`` or ``aspect`` and its allowed range (also for NaN,
        non-numbers and shapes that do not broadcast).

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
    aspect: Any = 1.0
    _theta: Any = field(init=False, repr=False)

    def __post_init__(self) -> None:
        n, f = check.frustum(self.near, self.far)
        a = check.fov(self.fov)
        r = check_aspect(self.aspect)
        n, f, a, r = check.broadcast(near=n, far=f, fov=a, aspect=r)  # a shape error names them and their shapes
        theta = np.radians(a) / 2  # the conversion of half_angle, on the fov validated above
        for name, value in (("near", n), ("far", f), ("fov", a), ("aspect", r), ("_theta", theta)):
            object.__setattr__(self, name, _store(value))

    def __repr__(self) -> str:
        square = np.all(np.asarray(self.aspect) == 1.0)
        tail = "" if square else f", aspect={self.aspect!r}"
        return f"View(near={self.near!r}, far={self.far!r}, fov={self.fov!r}{tail})"

    @property
    def square(self) -> bool:
        """True when aspect = 1 everywhere (the papers' square frustum)."""
        return bool(np.all(np.asarray(self.aspect) == 1.0))

    def require_square(self, what: str) -> None:
        """Refuse a non-square view where only the square closed forms exist (ValueError naming aspect)."""
        if not self.square:
            raise ValueError(f"aspect must be 1 for {what} (a square view), got {check._show(np.asarray(self.aspect, float))}")

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
    def tan_theta_x(self) -> float | Array:
        """tan θ_x = aspect·tan θ [dimensionless]: the half-width of the image at unit eye depth (= tan θ at aspect 1)."""
        return _store(np.asarray(self.aspect) * np.asarray(self.tan_theta))

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
        tx = np.asarray(self.tan_theta_x)[..., None]  # the same numbers as t at aspect 1
        return np.stack([CORNER_SIGNS[:, 0] * tx, CORNER_SIGNS[:, 1] * t, np.ones_like(t * CORNER_SIGNS[:, 0])], axis=-1)

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
        n, f, t, tx = np.broadcast_arrays(n, f, np.asarray(self.tan_theta), np.asarray(self.tan_theta_x))
        depth = np.stack([n] * 4 + [f] * 4, axis=-1)  # (..., 8)
        sx = np.concatenate([CORNER_SIGNS[:, 0], CORNER_SIGNS[:, 0]])
        sy = np.concatenate([CORNER_SIGNS[:, 1], CORNER_SIGNS[:, 1]])
        half = depth * t[..., None]
        half_x = depth * tx[..., None]  # equal to half at aspect 1 (aspect·t = t exactly)
        return np.stack([sx * half_x, sy * half, depth], axis=-1)

    def between(self, z0: ArrayLike, z1: ArrayLike) -> "View":
        """The same view cut to the eye depths [z0, z1] (a partition's sub-frustum) [world units].

        Only the new depths are checked (0 < z0 < z1 < inf); the field of view and θ are
        carried over as they are, not validated or converted again.

        Example
        -------
        >>> v = View(1.0, 100.0, 60.0).between(10.0, 20.0)
        >>> v.near, v.far, v.fov, v.theta == View(1.0, 100.0, 60.0).theta
        (10.0, 20.0, 60.0, True)
        """
        n, f = check.frustum(z0, z1)
        n, f, a, r, th = check.broadcast(near=n, far=f, fov=np.asarray(self.fov), aspect=np.asarray(self.aspect), theta=np.asarray(self._theta))
        out = object.__new__(View)
        for name, value in (("near", n), ("far", f), ("fov", a), ("aspect", r), ("_theta", th)):
            object.__setattr__(out, name, _store(value))
        return out

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, View):
            return NotImplemented
        return all(np.array_equal(getattr(self, k), getattr(other, k)) for k in ("near", "far", "fov", "aspect"))

    def __hash__(self) -> int:
        return hash(tuple(np.asarray(getattr(self, k)).tobytes() for k in ("near", "far", "fov", "aspect")))


def check_aspect(value: ArrayLike, name: str = "aspect") -> Array:
    """Image width/height: require 0 < aspect < inf (ValueError naming ``aspect``).

    Example
    -------
    >>> check_aspect(0.0)
    Traceback (most recent call last):
    ...
    ValueError: aspect (image width/height) must be in (0, inf), got 0
    """
    arr = check.as_float_array(value, name)
    if not np.all(np.isfinite(arr) & (arr > 0)):
        raise ValueError(f"{name} (image width/height) must be in (0, inf), got {check._show(arr)}")
    return arr


def half_angle(fov: ArrayLike, name: str = "fov") -> Array:
    """θ = fov/2 [rad] from the full field of view [deg], 0 < fov < 180 (validated).

    The one degrees → radians conversion of the field of view in the toolkit.

    Example
    -------
    >>> round(float(np.tan(half_angle(90.0))), 12)
    1.0
    """
    return np.radians(check.fov(fov, name)) / 2


def vertical_fov(hfov: ArrayLike, aspect: ArrayLike, name: str = "hfov") -> float | Array:
    """The vertical full field of view [deg] of a horizontal one ``hfov`` [deg] at ``aspect`` (width/height).

    tan(fov/2) = tan(hfov/2) / aspect: how Unreal, PlayCanvas's ``horizontalFov``, Babylon's
    ``FOVMODE_HORIZONTAL_FIXED`` and Godot's ``KEEP_WIDTH`` cameras are turned into the toolkit's
    vertical convention.

    Example
    -------
    >>> round(float(vertical_fov(90.0, 16 / 9)), 4)
    58.7155
    """
    a = check_aspect(aspect)
    return _store(np.degrees(2.0 * np.arctan(np.tan(half_angle(hfov, name)) / a)))


def theta_of(fov: View | ArrayLike, name: str = "fov") -> float | Array:
    """θ [rad] of a View (as it is, not validated again) or of a full field of view [deg] (validated).

    For the closed forms of the square frustum: a View with aspect ≠ 1 is refused.

    Example
    -------
    >>> theta_of(View(1.0, 2.0, 90.0)) == float(theta_of(90.0))
    True
    """
    if isinstance(fov, View):
        fov.require_square("a closed form of the square frustum (θ alone)")
        return fov.theta
    return half_angle(fov, name)


def tan_theta(fov: View | ArrayLike, name: str = "fov") -> float | Array:
    """tan θ of a View (as it is) or of a full field of view [deg] (validated): np.tan(half_angle(fov)).

    For the closed forms of the square frustum: a View with aspect ≠ 1 is refused.

    Example
    -------
    >>> round(float(tan_theta(90.0)), 12), round(tan_theta(View(1.0, 2.0, 90.0)), 12)
    (1.0, 1.0)
    """
    if isinstance(fov, View):
        fov.require_square("a closed form of the square frustum (tan θ alone)")
        return fov.tan_theta
    return np.tan(half_angle(fov, name))


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


def view_args(near: View | ArrayLike | None, far: Any, fov: Any, rest: tuple[Any, ...], defaults: tuple[Any, ...], names: tuple[str, ...] = ("light", "scheme")) -> tuple[View, tuple[Any, ...]]:
    """Resolve ``(near, far, fov, *rest)`` where ``near`` may be a View, for any number of following arguments.

    With a View in ``near``, what was given in the places of ``far`` and ``fov`` moves to the
    first two of ``rest`` (``f(view, light, scheme)`` means ``f(near, far, fov, light,
    scheme)``); arguments given by name stay where they are.  ``None`` means "not given";
    ``defaults`` are ``(near, far, fov, *rest)`` (None: required; ``names`` name the following
    arguments in the error).  Loose numbers are validated
    here, once, into the View.

    Example
    -------
    >>> v = View(1.0, 10.0, 60.0)
    >>> view_args(v, "overhead", "P", (None, None), (None, None, None, None, "Standard"))[1]
    ('overhead', 'P')
    >>> view_args(v, "overhead", None, (None, None), (None, None, None, None, "Standard"))[1]
    ('overhead', 'Standard')
    >>> view_args(v, None, None, ("front", "LogP"), (None, None, None, None, "Standard"))[1]   # by name
    ('front', 'LogP')
    >>> view_args(1.0, 10.0, 60.0, ("front", None), (None, None, None, None, "Standard"))
    (View(near=1.0, far=10.0, fov=60.0), ('front', 'Standard'))
    """
    tail = defaults[3:]
    if len(tail) != len(rest):
        raise ValueError("defaults must give near, far, fov and one default per following argument")
    if isinstance(near, View):
        # the arguments after the View, in order: those given by position form a leading
        # run of the places far, fov, rest...; any later one was given by name in its own place
        seq = [far, fov, *rest]
        m = next((i for i, v in enumerate(seq) if v is None), len(seq))
        out = [None] * len(rest)
        for j, value in enumerate(seq):
            if value is None:
                continue
            i = j if j < m else j - 2
            if i >= len(out) or out[i] is not None:
                raise ValueError("with a View, pass the arguments that follow it (e.g. light) once each, not far and fov")
            out[i] = value
        view = near
    else:
        given = {"near": defaults[0] if near is None else near, "far": defaults[1] if far is None else far, "fov": defaults[2] if fov is None else fov}
        missing = [k for k, v in given.items() if v is None]
        if missing:
            raise ValueError(f"{', '.join(missing)} required (or a View in place of near)")
        view = View(given["near"], given["far"], given["fov"])
        out = list(rest)
    resolved = tuple(d if v is None else v for v, d in zip(out, tail))
    missing = [names[i] if i < len(names) else f"argument {i + 4}" for i, v in enumerate(resolved) if v is None]
    if missing:
        raise ValueError(f"{', '.join(missing)} required")
    return view, resolved


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
