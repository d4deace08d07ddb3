"""The 3D aliasing matrix M_a of Lloyd et al. 2007 §3.4 (eqs. 32–40), evaluated with numpy.

M_a maps a step in the shadow map (s, t), in texels, to the step it makes in the eye image
(i, j), in pixels: its columns are the two edges of a shadow-map texel projected through the
surface into the image.  It is the chain of eq. 35,

    ∂i/∂s = ∂i/∂p_e · ∂p_e/∂p · ∂p/∂p_l · ∂p_l/∂u · ∂u/∂s,

of the image-coordinate map (eq. 36), the eye projection (eq. 8), the light projection onto
the surface (eq. 9 for a point light, eq. 26 as corrected in erratum L11 for a directional
light), the light image plane (eq. 37) and the parameterization's spacing matrix
δ_l = ∂G/∂s (eqs. 38–39), scaled by the resolutions (eq. 34).  δ_e = (∂i/∂u)⁻¹ (eq. 40).
A scalar error is a metric h(M_a) (§3.4: a p-norm, the Frobenius norm or the
determinant), :func:`error_metric`.  The symbolic source is
:mod:`aliasing.symbolic.lloyd2007_matrix`.

§3.4's two candidate 3D perspective errors, h(X_l)/h(X_e) from the beams' cross-sections
(:func:`cross_sections`) and h(M_a) on the surface half-way between the eye and the light
(:func:`halfway_normal`, §3.3), are "not guaranteed to be equivalent".  What the tests show:
the half-way surface carries the light beam's cross-section isometrically onto the eye
beam's (it is the mirror between them), M_a = X_e⁻¹ P X_l with P orthogonal, so the two agree
exactly for h = |det| (and any surface gives |det M_a| = |det X_l|/|det X_e| · cos ψ_e/cos ψ_l,
eq. 29's factorisation), while for the 2-norm h(M_a) lies between h(X_l)/h(X_e) and
cond(X_e) times it.

Conventions: a :class:`Camera` (the eye, a point light or a directional light) looks along
−ẑ of its axes (rows x̂, ŷ, ẑ); its image plane lies ``near`` before its centre of
projection and its window is ``width`` = (W_x, W_y) wide.  All lengths are in world units,
every array broadcasts over leading axes: points ``(..., 3)``, axes ``(..., 3, 3)``,
matrices ``(..., 2, 2)``.

Example
-------
>>> import numpy as np
>>> eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 10.0], near=1.0, width=2.0)
>>> sun = Camera(axes=np.eye(3), direction=[0.0, 0.0, 1.0], width=20.0)
>>> aliasing_matrix([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], eye, sun)  # one texel → one pixel
array([[1., 0.],
       [0., 1.]])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check

__all__ = [
    "Camera",
    "aliasing_matrix",
    "camera_axes",
    "cross_sections",
    "error_metric",
    "halfway_normal",
    "spacing_eye",
    "spacing_light",
]

Array = NDArray[np.float64]
METRICS = ("1", "2", "inf", "fro", "det", "column")


def _vectors(value: ArrayLike, name: str, size: int = 3) -> Array:
    arr = check.finite(value, name)
    if arr.ndim == 0 or arr.shape[-1] != size:
        raise ValueError(f"{name} must have a last axis of length {size} (shape (..., {size})), got shape {arr.shape}")
    return arr


def _unit(value: ArrayLike, name: str) -> Array:
    arr = _vectors(value, name)
    if (np.abs(arr).max(axis=-1, initial=0.0) == 0).any():
        raise ValueError(f"{name} must be a non-zero vector")
    return check.unit_rows(arr)


def _dot(a: Array, b: Array) -> Array:
    return np.einsum("...k,...k->...", a, b)


def _outer(a: Array, b: Array) -> Array:
    return a[..., :, None] * b[..., None, :]


def _pair(value: ArrayLike, name: str) -> Array:
    """A positive scalar or pair (..., 2), returned with a last axis of 2."""
    arr = check.positive(value, name)
    return np.stack([arr, arr], axis=-1) if arr.ndim == 0 or arr.shape[-1] != 2 else arr


@dataclass(frozen=True)
class Camera:
    """An eye, a point light or a directional light (Lloyd et al. 2007 §3.2, eq. 32).

    Parameters
    ----------
    axes : array_like, shape (..., 3, 3)
        Rows x̂, ŷ, ẑ (orthonormal); the camera looks along −ẑ, x̂ and ŷ span its image plane.
    position : array_like, shape (..., 3), optional
        Centre of projection [world units] (the eye e or a point light l).
    direction : array_like, shape (..., 3), optional
        For a directional light instead of ``position``: the direction towards the light l̂
        (need not be unit length).
    near : array_like, optional
        Distance n from the centre of projection to the image plane [world units], > 0
        (irrelevant for a directional light).
    width : array_like, optional
        Window widths (W_x, W_y) on the image plane [world units], > 0; a scalar for both.

    Examples
    --------
    >>> Camera(axes=np.eye(3), position=[0.0, 0.0, 5.0]).directional
    False
    """

    axes: ArrayLike
    position: ArrayLike | None = None
    direction: ArrayLike | None = None
    near: ArrayLike = 1.0
    width: ArrayLike = 2.0

    def __post_init__(self) -> None:
        axes = check.as_float_array(self.axes, "axes")
        if axes.ndim < 2 or axes.shape[-2:] != (3, 3):
            raise ValueError(f"axes must have shape (..., 3, 3) (rows x, y, z), got shape {axes.shape}")
        if np.abs(axes @ np.swapaxes(axes, -1, -2) - np.eye(3)).max() > 1e-9:
            raise ValueError("axes must be orthonormal (rows x, y, z with axes @ axes.T = I to 1e-9)")
        if (self.position is None) == (self.direction is None):
            raise ValueError("give exactly one of position (eye or point light) and direction (directional light)")
        object.__setattr__(self, "axes", axes)
        if self.position is not None:
            object.__setattr__(self, "position", _vectors(self.position, "position"))
        else:
            object.__setattr__(self, "direction", _unit(self.direction, "direction"))
        object.__setattr__(self, "near", check.positive(self.near, "near"))
        object.__setattr__(self, "width", _pair(self.width, "width"))

    @property
    def directional(self) -> bool:
        """True for a directional light."""
        return self.direction is not None


@check.public
def camera_axes(view: ArrayLike, up: ArrayLike = (0.0, 1.0, 0.0)) -> Array:
    """Orthonormal camera axes (rows x̂, ŷ, ẑ) looking along ``view``, ẑ = −view/|view|.

    Parameters
    ----------
    view : array_like, shape (..., 3)
        Viewing direction (non-zero).
    up : array_like, shape (..., 3), optional
        Up vector, not parallel to ``view``; ŷ is its part perpendicular to ``view``.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> camera_axes([0.0, 0.0, -1.0])
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    z = -_unit(view, "view")
    x = np.cross(_unit(up, "up"), z)
    norm = np.linalg.norm(x, axis=-1, keepdims=True)
    if (norm <= 1e-12).any():
        raise ValueError("up must not be parallel to view")
    x = x / norm
    return np.stack(np.broadcast_arrays(x, np.cross(z, x), z), axis=-2) + 0.0  # + 0.0: no signed zeros


def _factors(point: ArrayLike, normal: ArrayLike, eye: Camera, light: Camera) -> list[Array]:
    """∂i/∂p_e, ∂p_e/∂p, ∂p/∂p_l, ∂p_l/∂u of eq. 35 at the surface point ``point``."""
    _cameras(eye, light)
    if eye.directional:
        raise ValueError("eye must have a position (a centre of projection), not a direction")
    p = _vectors(point, "point")
    nh = _unit(normal, "normal")
    I = np.eye(3)
    e, ze = eye.position, eye.axes[..., 2, :]
    d_e = _dot(ze, e - p)
    if (d_e <= 0).any():
        raise ValueError("point must lie in front of the eye (eye depth d_e = ẑ_e·(e − p) in (0, inf))")
    di_dpe = np.stack([eye.axes[..., 0, :] / eye.width[..., :1], eye.axes[..., 1, :] / eye.width[..., 1:]], axis=-2)  # eq. (36)
    pi_e_p, pi_e_ep, pi_e_e = eye.near - d_e, d_e, eye.near  # π_e p, π_e(e − p), π_e e
    dpe_dp = I + (pi_e_p / pi_e_ep)[..., None, None] * I - (pi_e_e / pi_e_ep**2)[..., None, None] * _outer(e - p, ze)  # eq. (8)
    if light.directional:
        lh = light.direction
        if (_dot(nh, lh) == 0).any():
            raise ValueError("direction must not be parallel to the surface (n̂·l̂ = 0 makes M_a unbounded)")
        dp_dpl = I - _outer(lh, nh) / _dot(nh, lh)[..., None, None]  # eq. (26), corrected (L11)
    else:
        l, zl = light.position, light.axes[..., 2, :]
        d_l = _dot(zl, l - p)
        if (d_l <= 0).any():
            raise ValueError("point must lie in front of the light (light depth d_l = ẑ_l·(l − p) in (0, inf))")
        if (_dot(nh, l - p) == 0).any():
            raise ValueError("position of the light must not lie in the surface plane (n̂·(l − p) = 0 makes M_a unbounded)")
        p_l = l + (light.near / d_l)[..., None] * (p - l)  # the light image plane point of p
        pi_pl, pi_pl_l, pi_l = _dot(nh, p_l - p), _dot(nh, p_l - l), _dot(nh, l - p)
        dp_dpl = I - (pi_pl / pi_pl_l)[..., None, None] * I + (pi_l / pi_pl_l**2)[..., None, None] * _outer(p_l - l, nh)  # eq. (9)
    dpl_du = np.stack([light.width[..., :1] * light.axes[..., 0, :], light.width[..., 1:] * light.axes[..., 1, :]], axis=-1)  # eq. (37)
    return [di_dpe, dpe_dp, dp_dpl, dpl_du]


def _delta(delta_l: ArrayLike | None, name: str = "delta_l") -> Array:
    if delta_l is None:
        return np.eye(2)
    arr = check.finite(delta_l, name)
    if arr.ndim < 2 or arr.shape[-2:] != (2, 2):
        raise ValueError(f"{name} must have shape (..., 2, 2), got shape {arr.shape}")
    return arr


def _cameras(eye: object, light: object) -> None:
    check.instance(eye, "eye", Camera)
    check.instance(light, "light", Camera)


def _chain(factors: list[Array]) -> Array:
    out = factors[0]
    for fac in factors[1:]:
        out = out @ fac
    return out


@check.public
def aliasing_matrix(
    point: ArrayLike,
    normal: ArrayLike,
    eye: Camera,
    light: Camera,
    *,
    delta_l: ArrayLike | None = None,
    res_image: ArrayLike = 1.0,
    res_map: ArrayLike = 1.0,
) -> Array:
    """3D aliasing matrix M_a = diag(r_i, r_j) ∂i/∂s diag(1/r_s, 1/r_t), Lloyd et al. 2007, eqs. 34–35.

    Parameters
    ----------
    point : array_like, shape (..., 3)
        Surface point p [world units], in front of the eye and of a point light.
    normal : array_like, shape (..., 3)
        Normal n̂ of the planar surface π through ``point`` (need not be unit length).
    eye : Camera
        The eye (with a ``position``).
    light : Camera
        A point light (``position``) or a directional light (``direction``).
    delta_l : array_like, shape (..., 2, 2), optional
        Spacing matrix δ_l = ∂G/∂s = (∂F/∂u)⁻¹ of the parameterization (eqs. 38–39);
        identity (a uniform shadow map over the light window) by default.
    res_image, res_map : array_like, optional
        (r_i, r_j) [pixels] and (r_s, r_t) [texels], > 0; scalars for both directions.

    Returns
    -------
    ndarray, shape (..., 2, 2)
        M_a [pixels per texel]: column k is the image step of one texel step in s (k = 0)
        or t (k = 1); row 0 is i, row 1 is j.

    Examples
    --------
    >>> eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 10.0])
    >>> lamp = Camera(axes=np.eye(3), position=[0.0, 0.0, 5.0], width=2.0)
    >>> aliasing_matrix([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], eye, lamp, res_map=512, res_image=512)
    array([[0.5, 0. ],
           [0. , 0.5]])
    """
    di_ds = _chain(_factors(point, normal, eye, light) + [_delta(delta_l)])  # eq. (35)
    r_img, r_map = _pair(res_image, "res_image"), _pair(res_map, "res_map")
    return r_img[..., :, None] * di_ds / r_map[..., None, :]  # eq. (34)


@check.public
def spacing_eye(point: ArrayLike, normal: ArrayLike, eye: Camera, light: Camera) -> Array:
    """Eye spacing matrix δ_e = (∂i/∂u)⁻¹, Lloyd et al. 2007, eq. 40.

    Parameters as in :func:`aliasing_matrix`.  M_a = diag(r_i, r_j) δ_e⁻¹ δ_l diag(1/r_s, 1/r_t),
    the 3D form of eq. 27.

    Returns
    -------
    ndarray, shape (..., 2, 2)
        ∂u/∂i, light-window units per image unit.

    Examples
    --------
    >>> eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 10.0])
    >>> sun = Camera(axes=np.eye(3), direction=[0.0, 0.0, 1.0], width=40.0)
    >>> spacing_eye([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], eye, sun)
    array([[0.5, 0. ],
           [0. , 0.5]])
    """
    chain = _chain(_factors(point, normal, eye, light))
    try:
        return np.linalg.inv(chain)  # eq. (40)
    except np.linalg.LinAlgError:
        raise ValueError("point and normal give a singular ∂i/∂s (the surface is seen edge-on, or the point is beyond float precision)") from None


@check.public
def spacing_light(dF_du: ArrayLike) -> Array:
    """Light spacing matrix δ_l = ∂G/∂s = (∂F/∂u)⁻¹, Lloyd et al. 2007, eq. 39.

    Parameters
    ----------
    dF_du : array_like, shape (..., 2, 2)
        Jacobian of the parameterization s = F(u), invertible.

    Returns
    -------
    ndarray, shape (..., 2, 2)

    Examples
    --------
    >>> spacing_light([[2.0, 0.0], [0.0, 4.0]])
    array([[0.5 , 0.  ],
           [0.  , 0.25]])
    """
    jac = _delta(dF_du, "dF_du")
    if (np.linalg.det(jac) == 0).any():
        raise ValueError("dF_du must be invertible (det ≠ 0)")
    return np.linalg.inv(jac)  # eq. (39)


@check.public
def error_metric(M: ArrayLike, metric: str | int | float = "2") -> Array:
    """Scalar aliasing error h(M) of a 2×2 matrix (Lloyd et al. 2007 §3.4).

    Parameters
    ----------
    M : array_like, shape (..., 2, 2)
        An aliasing matrix (or a beam cross-section, :func:`cross_sections`).
    metric : {"1", "2", "inf", "fro", "det", "column"}
        The induced p-norms for p = 1, 2, ∞ (1 and 2 and ``np.inf`` are accepted too), the
        Frobenius norm, |det M| (the projected texel's area [pixels²]) or the largest
        Euclidean column norm (the longest projected texel edge [pixels]).

    Returns
    -------
    ndarray
        h ≥ 0, shape (...).

    Examples
    --------
    >>> M = [[3.0, 0.0], [4.0, 1.0]]
    >>> [round(float(error_metric(M, metric=k)), 4) for k in ("1", "2", "inf", "fro", "det", "column")]
    [7.0, 5.0645, 5.0, 5.099, 3.0, 5.0]
    """
    key = check.choice(str(metric), "metric", METRICS)
    arr = _delta(M, "M")
    if key == "det":
        return np.abs(np.linalg.det(arr))
    if key == "column":
        return np.sqrt((arr**2).sum(axis=-2)).max(axis=-1)
    order = {"1": 1, "2": 2, "inf": np.inf, "fro": "fro"}[key]
    return np.linalg.norm(arr, ord=order, axis=(-2, -1))


def _beam(point: Array, cam: Camera) -> Array:
    """Unit vector from ``point`` towards the camera (or along l̂ for a directional light)."""
    return cam.direction + 0 * point if cam.directional else _unit(cam.position - point, "position - point")


def _basis(w: Array, hint: Array) -> Array:
    """Orthonormal basis (..., 3, 2) of the plane ⟂ w, its first vector along hint's part ⟂ w."""
    b1 = hint - _dot(hint, w)[..., None] * w
    b1 = b1 / np.linalg.norm(b1, axis=-1, keepdims=True)
    return np.stack(np.broadcast_arrays(b1, np.cross(w, b1)), axis=-1)


@check.public
def halfway_normal(point: ArrayLike, eye: Camera, light: Camera) -> Array:
    """Unit normal half-way between the eye direction v̂_e and the light direction −v̂_l (§3.3).

    On such a surface cos ψ_e = cos ψ_l: the projection factor of eq. 29 is 1.

    Parameters as in :func:`aliasing_matrix`.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 1.0])
    >>> sun = Camera(axes=np.eye(3), direction=[1.0, 0.0, 0.0])
    >>> halfway_normal([0.0, 0.0, 0.0], eye, sun).round(6)
    array([0.707107, 0.      , 0.707107])
    """
    _cameras(eye, light)
    p = _vectors(point, "point")
    if eye.directional:
        raise ValueError("eye must have a position (a centre of projection), not a direction")
    h = _unit(eye.position - p, "eye position - point") + _beam(p, light)
    return _unit(h, "halfway vector (the eye and the light are in opposite directions)")


@check.public
def cross_sections(point: ArrayLike, eye: Camera, light: Camera, *, delta_l: ArrayLike | None = None, res_image: ArrayLike = 1.0, res_map: ArrayLike = 1.0) -> tuple[Array, Array]:
    """Differential cross-sections X_l (one texel) and X_e (one pixel) of the beams at a point.

    Lloyd et al. 2007 §3.4 ("compute the differential cross sections X_e and X_l of the light
    and eye beam at a point and define perspective aliasing error as h(X_l)/h(X_e)").  X_l is
    ∂p/∂s · diag(1/r_s, 1/r_t) on the plane through ``point`` perpendicular to the light
    beam, X_e is ∂p/∂i · diag(1/r_i, 1/r_j) on the plane perpendicular to the eye beam; each
    is written in an orthonormal basis of its plane, so only metrics invariant under a
    rotation of that basis ("2", "fro", "det", "column") compare them meaningfully.
    Parameters as in :func:`aliasing_matrix`.

    Returns
    -------
    (X_l, X_e) : tuple of ndarray, shape (..., 2, 2)
        [world units per texel], [world units per pixel].

    Examples
    --------
    >>> eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 10.0])
    >>> sun = Camera(axes=np.eye(3), direction=[0.0, 0.0, 1.0], width=20.0)
    >>> X_l, X_e = cross_sections([0.0, 0.0, 0.0], eye, sun)
    >>> float(error_metric(X_l, "det")), float(error_metric(X_e, "det"))
    (400.0, 400.0)
    """
    _cameras(eye, light)
    p = _vectors(point, "point")
    w_l = _beam(p, light)
    di_dpe, dpe_dp, dp_dpl, dpl_du = _factors(p, w_l, eye, light)  # ∂p/∂p_l onto the plane ⟂ the light beam
    T_l = _basis(w_l, light.axes[..., 0, :])
    X_l = np.swapaxes(T_l, -1, -2) @ dp_dpl @ dpl_du @ _delta(delta_l) / _pair(res_map, "res_map")[..., None, :]
    w_e = _unit(eye.position - p, "eye position - point")
    X_e = np.linalg.inv(di_dpe @ dpe_dp @ _basis(w_e, eye.axes[..., 0, :])) / _pair(res_image, "res_image")[..., None, :]
    return X_l, X_e
