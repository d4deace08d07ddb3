"""Lloyd et al. 2007 (LogPSM) §3–5 and App. A, evaluated with numpy.

The general 2D aliasing error (eq. 19) and its perspective factor (eq. 30); the
error-bound spacing δ_b on end and side faces (eqs. 57–62) with the closed-form integrals
ζ_b (eqs. 66–68, eq. 67 corrected); the uniform, perspective, logarithmic and
log+perspective parameterizations of a side face (eqs. 74–78, 104–110), their spacing
functions (eqs. 96–97, 102, 109, signs corrected) and inverse (eq. 84, corrected).  The
closed-form critical resolution factors of App. A (eqs. 87–103) are in
:mod:`aliasing.logpsm_critical` and re-exported here.  The symbolic sources are in
:mod:`aliasing.symbolic.lloyd2007`.

Conventions (see :mod:`aliasing`): angles in degrees, ``fov`` is the full field of view
(θ = fov/2); ``near``, ``far`` are the eye distances n_e, f_e.  Side-face frame (Lloyd 2007
Fig. 5): origin at the eye, y along the face's centre line, y0 = near/cosθ,
y1 = far/cosθ, W_e = 2·near·tanθ; v ∈ [0, 1] maps to y = y0 + (y1 − y0)v and u ∈ [0, 1] to
x = W_x(u − 1/2) with W_x = W_e·y1/y0.  A point light is given in the face's frame
(``lx``, ``ly``, ``lz``, lz the height above the face); ``lz = inf`` is the directional light
straight above the face (cos φ_l = 1).

Example
-------
>>> import numpy as np
>>> factors = critical_factors(1.0, 1000.0, 60.0)  # re-exported from aliasing.logpsm_critical
>>> round(float(factors["log_t_side"]), 4)  # ln(f/n)/sin 2θ, eq. 103
7.9764
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from .logpsm_critical import critical_factors  # App. A's closed forms, re-exported: old imports keep working
from .view import theta_of

__all__ = [
    "aliasing_error",
    "critical_factor_side",
    "critical_factors",
    "delta_bound_end",
    "delta_bound_side_s",
    "delta_bound_side_t",
    "logp_inverse",
    "parameterization",
    "perspective_factor",
    "rho_bound",
    "side_face",
    "spacing",
    "zeta_bound",
]

Array = NDArray[np.float64]


# --- §3: the general aliasing error -----------------------------------------------------
@check.public
def aliasing_error(
    dG_dt: ArrayLike,
    W_l: ArrayLike,
    W_e: ArrayLike,
    n_e: ArrayLike,
    d_e: ArrayLike,
    phi_l: ArrayLike,
    phi_e: ArrayLike,
    psi_e: ArrayLike,
    psi_l: ArrayLike,
    *,
    n_l: ArrayLike = 1.0,
    d_l: ArrayLike = 1.0,
    res_image: ArrayLike = 1.0,
    res_t: ArrayLike = 1.0,
) -> Array:
    """2D aliasing error m of a point or directional light, Lloyd et al. 2007, eq. 19.

    m = (r_j/r_t)(dG/dt)(W_l/W_e)(n_e/n_l)(d_l/d_e)(cosφ_l/cosφ_e)(cosψ_e/cosψ_l).
    For a directional light leave ``n_l = d_l = 1`` (n_l/d_l → 1, §3.2).

    Parameters
    ----------
    dG_dt : array_like
        Spacing δ_l = dv/dt of the parameterization (dimensionless, > 0).
    W_l, W_e : array_like
        Widths of the light and eye image-plane windows [world units], > 0.
    n_e, d_e : array_like
        Eye image-plane distance and eye depth of the point [world units], > 0.
    phi_l, phi_e : array_like
        Angles between the light/eye beam and its image-plane normal [degrees], in [0, 90).
    psi_e, psi_l : array_like
        Angles between the eye/light beam and the surface normal [degrees], in [0, 90).
    n_l, d_l : array_like, optional
        Light image-plane distance and light depth of the point [world units], > 0.
    res_image, res_t : array_like, optional
        Image resolution r_j and shadow-map resolution r_t [pixels, texels], > 0.

    Returns
    -------
    ndarray
        m, dimensionless (texel width over pixel width on the surface).

    Examples
    --------
    >>> float(aliasing_error(1.0, 2.0, 2.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0))
    1.0
    """
    args = [check.positive(q, name) for q, name in ((dG_dt, "dG_dt"), (W_l, "W_l"), (W_e, "W_e"), (n_e, "n_e"), (d_e, "d_e"), (n_l, "n_l"), (d_l, "d_l"), (res_image, "res_image"), (res_t, "res_t"))]
    g, wl, we, ne, de, nl, dl, rj, rt = args
    cos = {}
    for q, name in ((phi_l, "phi_l"), (phi_e, "phi_e"), (psi_e, "psi_e"), (psi_l, "psi_l")):
        ang = check.as_float_array(q, name)
        if ((ang < 0) | (ang >= 90)).any():
            raise ValueError(f"{name} must be in [0, 90) degrees, got {check._show(ang)}")
        cos[name] = np.cos(np.radians(ang))
    return rj / rt * g * wl / we * ne / nl * dl / de * cos["phi_l"] / cos["phi_e"] * cos["psi_e"] / cos["psi_l"]  # eq. (19)


@check.public
def perspective_factor(W_l: ArrayLike, W_e: ArrayLike, n_e: ArrayLike, d_e: ArrayLike, phi_l: ArrayLike, phi_e: ArrayLike, *, n_l: ArrayLike = 1.0, d_l: ArrayLike = 1.0) -> Array:
    """Perspective factor δ̃_e = W_e n_l d_e cosφ_e/(W_l n_e d_l cosφ_l), Lloyd et al. 2007, eq. 30.

    Parameters as in :func:`aliasing_error` (lengths in world units, angles in degrees).

    Returns
    -------
    ndarray
        δ̃_e, dimensionless; m̃ = (r_j/r_t) δ_l/δ̃_e (eq. 31).

    Examples
    --------
    >>> float(perspective_factor(2.0, 2.0, 1.0, 3.0, 0.0, 0.0))
    3.0
    """
    ones = aliasing_error(1.0, W_l, W_e, n_e, d_e, phi_l, phi_e, 0.0, 0.0, n_l=n_l, d_l=d_l)
    return 1.0 / ones  # eq. (30): with cosψ = 1 and dG/dt = 1, eq. 19 is 1/δ̃_e


# --- faces ------------------------------------------------------------------------------
@check.public
def side_face(near: ArrayLike, far: ArrayLike, fov: ArrayLike) -> tuple[Array, Array, Array, Array]:
    """(y0, y1, W_e, cosθ) of a side face: y0 = n/cosθ, y1 = f/cosθ, W_e = 2n tanθ (§4.4).

    Parameters
    ----------
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [degrees], in (0, 180).

    Returns
    -------
    tuple of ndarray
        y0, y1, W_e [world units] and cosθ.

    Examples
    --------
    >>> [round(float(q), 4) for q in side_face(1.0, 2.0, 90.0)]
    [1.4142, 2.8284, 2.0, 0.7071]
    """
    n, f = check.frustum(near, far)
    half = theta_of(fov)
    ct = np.cos(half)
    return n / ct, f / ct, 2 * n * np.tan(half), ct


def _unit_coordinate(value: ArrayLike, name: str) -> Array:
    return check.closed_range(value, name, 0.0, 1.0)


def _cos_phi(coord: Array, l_c: ArrayLike, l_z: ArrayLike, directional: bool = False) -> Array:
    """cos φ_l = l_z/√((c − l_c)² + l_z²) (eq. 57); 1 for l_z = inf.

    For a directional light (l_c, l_z) is the direction towards it, projected on the plane
    of the face's normal and the coordinate axis: cos φ_l = l_z/√(l_c² + l_z²), constant.
    """
    if check.flag(directional, "directional"):
        lz = check.positive(l_z, "lz")
        lc = check.as_float_array(l_c, "lx/ly (light coordinate)")
        if np.isinf(lc).any():
            raise ValueError("lx/ly: the direction of a directional light must be finite")
        return lz / np.sqrt(lc * lc + lz * lz) + 0.0 * coord  # eq. (57), parallel rays
    lz = check.positive(l_z, "lz", allow_inf=True)
    lc = check.as_float_array(l_c, "lx/ly (light coordinate)")
    with np.errstate(invalid="ignore", divide="ignore"):
        q = np.where(np.isinf(lz), 0.0, (coord - lc) / np.where(np.isinf(lz), 1.0, lz))
    return 1.0 / np.sqrt(q * q + 1.0)  # eq. (57)


@check.public
def delta_bound_end(v: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, ly: ArrayLike = 0.0, lz: ArrayLike = np.inf, face: str = "far", directional: bool = False) -> Array:
    """Error-bound spacing δ_b,t on an end face, Lloyd et al. 2007, eq. 58.

    δ_b,t^end(v) = cosθ/cos φ_ly(v), with y(v) = W_e d_e/n_e (v − 1/2) across the face.

    Parameters
    ----------
    v : array_like
        Face coordinate in [0, 1].
    near, far : array_like
        Eye near and far distances [world units], 0 < near < far.
    fov : array_like
        Full field of view [degrees], in (0, 180).
    ly, lz : array_like, optional
        Light position over the face [world units]; ``lz = inf`` is an overhead directional light.
    face : {"near", "far"}
        Which end face (sets d_e).
    directional : bool, optional
        If True, (``ly``, ``lz``) is the direction towards a directional light (lz > 0) and
        cos φ_l is constant over the face.

    Returns
    -------
    ndarray
        δ_b,t^end, dimensionless.

    Examples
    --------
    >>> round(float(delta_bound_end(0.5, 1.0, 10.0, 60.0)), 6)  # cos 30°
    0.866025
    """
    vv = _unit_coordinate(v, "v")
    _, _, We, ct = side_face(near, far, fov)
    n, f = check.frustum(near, far)
    de = {"near": n, "far": f}[check.choice(face, "face", ["near", "far"])]
    yy = We * de / n * (vv - 0.5)
    return ct / _cos_phi(yy, ly, lz, directional)  # eq. (58)


@check.public
def delta_bound_side_s(u: ArrayLike, v: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, lx: ArrayLike = 0.0, lz: ArrayLike = np.inf, directional: bool = False) -> Array:
    """Error-bound spacing δ_b,s on a side face, Lloyd et al. 2007, eq. 61.

    δ_b,s^side(u, v) = (y(v)/y1) cosθ/cos φ_lx(u).  Parameters as in
    :func:`delta_bound_end` (``u`` in [0, 1] across the face's bounding width W_e y1/y0).

    Returns
    -------
    ndarray
        δ_b,s^side, dimensionless.

    Examples
    --------
    >>> round(float(delta_bound_side_s(0.5, 0.0, 1.0, 10.0, 60.0)), 6)  # cosθ · n/f
    0.086603
    """
    uu, vv = _unit_coordinate(u, "u"), _unit_coordinate(v, "v")
    y0, y1, We, ct = side_face(near, far, fov)
    yy = y0 + (y1 - y0) * vv
    xx = We * y1 / y0 * (uu - 0.5)
    return yy / y1 * ct / _cos_phi(xx, lx, lz, directional)  # eq. (61)


@check.public
def delta_bound_side_t(v: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, ly: ArrayLike = 0.0, lz: ArrayLike = np.inf, directional: bool = False) -> Array:
    """Error-bound spacing δ_b,t on a side face, Lloyd et al. 2007, eq. 62.

    δ_b,t^side(v) = W_e y(v)/((y1 − y0) y0) · cosθ/cos φ_ly(v).  Parameters as in
    :func:`delta_bound_end`; ``ly`` is measured along the face from the eye.

    Returns
    -------
    ndarray
        δ_b,t^side, dimensionless.

    Examples
    --------
    >>> round(float(delta_bound_side_t(0.0, 1.0, 2.0, 90.0)), 6)  # W_e cos²θ/(f − n)
    1.0
    """
    vv = _unit_coordinate(v, "v")
    y0, y1, We, ct = side_face(near, far, fov)
    yy = y0 + (y1 - y0) * vv
    return We * yy / ((y1 - y0) * y0) * ct / _cos_phi(yy, ly, lz, directional)  # eq. (62)


@check.public
def zeta_bound(kind: str, coord: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, lx: ArrayLike = 0.0, ly: ArrayLike = 0.0, lz: ArrayLike = 1.0, v: ArrayLike = 0.0, face: str = "far") -> Array:
    """Antiderivative ζ_b of 1/δ_b in the face coordinate, Lloyd et al. 2007, eqs. 66–68.

    ``kind`` is ``"end"`` (eq. 66, coordinate v), ``"side_s"`` (eq. 67, coordinate u at
    the given ``v``; the constant corrected to y0/(W_e cosθ), see erratum L12) or ``"side_t"``
    (eq. 68, coordinate v).  ρ_b = ζ_b(1) − ζ_b(0) (eqs. 63, 65) and
    ρ_b,s(v) = ζ_b,s(u1(v)) − ζ_b,s(u0(v)) (eqs. 64, 69).  A point light (finite ``lz``) only.

    Parameters
    ----------
    kind : {"end", "side_s", "side_t"}
    coord : array_like
        u or v in [0, 1].
    near, far, fov : array_like
        Frustum [world units, degrees].
    lx, ly, lz : array_like, optional
        Light position in the face frame [world units], 0 < lz < inf.
    v : array_like, optional
        The row v of ``side_s``.
    face : {"near", "far"}
        End face of ``end``.

    Returns
    -------
    ndarray
        ζ_b (dimensionless), up to an additive constant.

    Examples
    --------
    >>> z = lambda c: zeta_bound("end", c, 1.0, 10.0, 60.0, lz=1e9)
    >>> round(float(z(1.0) - z(0.0)), 6)  # R_b,t^end = 1/cosθ as lz → ∞ (eq. 87)
    1.154701
    """
    key = check.choice(kind, "kind", ["end", "side_s", "side_t"])
    cc = _unit_coordinate(coord, "coord")
    y0, y1, We, ct = side_face(near, far, fov)
    n, f = check.frustum(near, far)
    lz_ = check.positive(lz, "lz")
    lx_, ly_ = check.as_float_array(lx, "lx"), check.as_float_array(ly, "ly")
    if (lz_ > _BIG).any():
        raise ValueError(f"lz must be at most {_BIG:g} here (its square overflows beyond), got {check._show(lz_)}")
    if (np.abs(lx_) > _BIG).any() or (np.abs(ly_) > _BIG).any():
        raise ValueError(f"lx and ly must be within [-{_BIG:g}, {_BIG:g}] (a light farther away is lz = inf), got lx={check._show(lx_)}, ly={check._show(ly_)}")
    if key == "end":
        de = {"near": n, "far": f}[check.choice(face, "face", ["near", "far"])]
        width = We * de / n
        yy = width * (cc - 0.5)
        return lz_ * np.arcsinh((yy - ly_) / lz_) / (width * ct)  # eq. (66)
    if key == "side_s":
        yy = y0 + (y1 - y0) * _unit_coordinate(v, "v")
        xx = We * y1 / y0 * (cc - 0.5)
        return y0 / (We * ct) * lz_ / yy * np.arcsinh((xx - lx_) / lz_)  # eq. (67), C_b,s = y0/(W_e cosθ)
    if (lz_ < 1e-150 * y0).any():  # lz² underflows below this and eq. (68) becomes 0/0
        raise ValueError(f"lz must be at least 1e-150·near for the side face (lower is the face's plane), got {check._show(lz_)}")
    yy = y0 + (y1 - y0) * cc
    L = np.sqrt(ly_**2 + lz_**2)
    inv_cos = np.sqrt((yy - ly_) ** 2 + lz_**2) / lz_
    first = (ly_ * (ly_ - yy) + lz_**2) / (lz_ * L)
    # first + inv_cos cancels when the light is low and y is beyond it; (inv_cos² − first²) = y²/L², so
    # there first + inv_cos = y²/(L² (inv_cos − first)) (the same value, without the cancellation)
    arg = np.where(first < 0, 2 * yy / (L**2 * np.maximum(inv_cos - first, np.finfo(float).tiny)), 2 / yy * np.maximum(first + inv_cos, 0.0))
    return -y0 / (We * ct) * lz_ / L * np.log(arg)  # eq. (68)


@check.public
def rho_bound(kind: str, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, lx: ArrayLike = 0.0, ly: ArrayLike = 0.0, lz: ArrayLike = 1.0, v: ArrayLike = 0.0, face: str = "far") -> Array:
    """Normalising constant ρ_b = R_b of the error-bound parameterization, Lloyd et al. 2007, eqs. 63–65.

    ``end``: ζ_b,t^end(1) − ζ_b,t^end(0); ``side_t``: ζ_b,t^side(1) − ζ_b,t^side(0);
    ``side_s``: ρ_b,s^side(v) = ζ_b,s(u1(v)) − ζ_b,s(u0(v)) with u0,1 = (y1 ∓ y(v))/(2y1) (eq. 69).
    R_b = ρ_b (App. A); R_b,s = max_v ρ_b,s(v).  Parameters as in :func:`zeta_bound`.

    Returns
    -------
    ndarray
        ρ_b, dimensionless.

    Examples
    --------
    >>> round(float(rho_bound("side_s", 1.0, 10.0, 60.0, lz=1e9, v=0.5)), 6)  # → 1/cosθ (eq. 88)
    1.154701
    """
    key = check.choice(kind, "kind", ["end", "side_s", "side_t"])
    opts = dict(lx=lx, ly=ly, lz=lz, face=face)
    if key != "side_s":
        return zeta_bound(key, 1.0, near, far, fov, **opts) - zeta_bound(key, 0.0, near, far, fov, **opts)  # eqs. (63), (65)
    y0, y1, _, _ = side_face(near, far, fov)
    vv = _unit_coordinate(v, "v")
    yy = y0 + (y1 - y0) * vv
    u0, u1 = (y1 - yy) / (2 * y1), (y1 + yy) / (2 * y1)  # eq. (69)
    return zeta_bound(key, u1, near, far, fov, v=vv, **opts) - zeta_bound(key, u0, near, far, fov, v=vv, **opts)  # eq. (64)


# --- §5: parameterizations of a side face -------------------------------------------------
def _ab(a: ArrayLike, b: ArrayLike, y0: Array, y1: Array) -> tuple[Array, Array]:
    """a ≥ 0; b real or ±inf with its root −b of eq. 106 off the face (−b ∉ [y0, y1]) and b ≠ a."""
    aa = check.closed_range(a, "a", 0.0, np.inf)
    bb = check.as_float_array(b, "b")
    if ((-bb >= y0) & (-bb <= y1)).any():
        raise ValueError(f"b must be > −y0 or < −y1 (the root −b of δ_lp,t, eq. 106, must lie off the face [y0, y1]), got b={check._show(bb)}")
    with np.errstate(invalid="ignore"):  # a = b = inf (the uniform limit): inf − inf is NaN, not "equal"
        same = np.abs(bb - aa) <= 1e-9 * (aa + y0)
    if same.any():  # eq. 110 is 0/0 at b = a, and all rounding near it
        raise ValueError(f"b must differ from a by more than 1e-9·(a + y0) (b = a makes eq. 110's logarithm 0); use b = inf for eq. 78; got a={check._show(aa)}, b={check._show(bb)}")
    # beyond 1e150 the products (y + a)(y + b) of eq. 110 overflow to inf/inf
    if (np.isinf(aa) & np.isfinite(bb)).any() or (np.isfinite(bb) & (np.abs(bb) > _BIG)).any() or (np.isfinite(aa) & (aa > _BIG)).any():
        raise ValueError(f"a and b must each be inf or within [-{_BIG:g}, {_BIG:g}], and a = inf needs b = inf; got a={check._show(aa)}, b={check._show(bb)}")
    return aa, bb


_BIG = 1e150  # largest finite a, b, lx, ly for which the closed forms stay inside float64


def _log_ratio(dx: Array, x0: Array) -> Array:
    """ln((x0 + dx)/x0) for x0 > 0, dx ≥ 0: log1p(dx/x0), exact also as the ratio → 1 (a ≫ y: the
    map tends to uniform); where dx/x0 overflows (near → 0), ln(x0 + dx) − ln x0, which loses nothing there."""
    with np.errstate(over="ignore", invalid="ignore"):  # x0 = inf (a = inf): step 0; the other branch's inf − inf is not taken
        step = dx / x0
        big = np.log(x0 + dx) - np.log(x0)
    return np.where(np.isinf(step), big, np.log1p(np.where(np.isinf(step), 0.0, step)))


def _log_map(dy: Array, span: Array, y0a: Array, vv: Array) -> Array:
    """ln((y0+a+dy)/(y0+a)) / ln((y0+a+span)/(y0+a)) (eqs. 77, 78), and its limit v, the uniform map, at a = inf."""
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = _log_ratio(dy, y0a) / _log_ratio(span, y0a)
    return np.where(np.isinf(y0a), vv, ratio)


@check.public
def parameterization(kind: str, v: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, a: ArrayLike = 0.0, b: ArrayLike = np.inf, u: ArrayLike = 0.5) -> Array:
    """A side-face parameterization in s or t, Lloyd et al. 2007, eqs. 74–78, 106–110.

    Parameters
    ----------
    kind : {"uniform", "perspective_s", "perspective_t", "log_t", "logp_t"}
        F_un (eq. 74, t = v), F_p,s and F_p,t (eqs. 75–76), F_log (eq. 77) and F_lp,t
        (eq. 78; with finite ``b`` the two-root form of eqs. 106–110).
    v : array_like
        Face coordinate in [0, 1].
    near, far, fov : array_like
        Frustum [world units, degrees].
    a : array_like, optional
        Centre of projection at y = −a [world units], ≥ 0 (``inf`` is uniform).
    b : array_like, optional
        Second root −b of δ_lp,t (eq. 106) [world units], ≠ a, with −b off the face (b > −y0:
        a convex parabola, or b < −y1: a concave one); ``±inf`` gives eq. 78.
    u : array_like, optional
        Face coordinate in [0, 1] for ``perspective_s``.

    Returns
    -------
    ndarray
        s or t in [0, 1].

    Examples
    --------
    >>> parameterization("logp_t", np.array([0.0, 1.0]), 1.0, 100.0, 60.0)
    array([0., 1.])
    """
    key = check.choice(kind, "kind", ["uniform", "perspective_s", "perspective_t", "log_t", "logp_t"])
    vv = _unit_coordinate(v, "v")
    y0, y1, We, _ = side_face(near, far, fov)
    aa, bb = _ab(a, b, y0, y1)
    yy = y0 + (y1 - y0) * vv
    if key == "uniform":
        return vv + 0.0 * yy  # eq. (74)
    if key == "perspective_s":
        xx = We * y1 / y0 * (_unit_coordinate(u, "u") - 0.5)
        with np.errstate(invalid="ignore"):
            p0 = (y1 + aa) / (We * y1 / y0)  # eq. (76)
            s = p0 * xx / (yy + aa) + 0.5  # eq. (75)
        return np.where(np.isinf(aa), xx * y0 / (We * y1) + 0.5, s)
    if key == "perspective_t":
        with np.errstate(invalid="ignore"):
            t = (y1 + aa) * (yy - y0) / ((y1 - y0) * (yy + aa))  # eqs. (75)-(76): p2 + p3/(y + a)
        return np.where(np.isinf(aa), vv, t)
    if key == "log_t":
        return _log_map(yy - y0, y1 - y0, y0 + aa, vv)  # eq. (77)
    # logp_t: c0 log((y0+a)(y+b)/((y0+b)(y+a))), eqs. (106)-(110); b = inf gives eq. (78)
    with np.errstate(invalid="ignore", divide="ignore"):
        finite = np.log((y0 + aa) * (yy + bb) / ((y0 + bb) * (yy + aa))) / np.log((y0 + aa) * (y1 + bb) / ((y0 + bb) * (y1 + aa)))  # eq. (110)
    return np.where(np.isinf(bb), _log_map(yy - y0, y1 - y0, y0 + aa, vv), finite)


@check.public
def spacing(kind: str, v: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, a: ArrayLike = 0.0, b: ArrayLike = np.inf) -> Array:
    """Normalised spacing δ = (dF/dv)⁻¹ of a side-face parameterization, Lloyd et al. 2007.

    ``uniform`` (eq. 90), ``perspective_s`` (eq. 96), ``perspective_t`` (eq. 97, second
    form), ``log_t`` (eq. 102), ``logp_t`` (eq. 109 with the sign corrected, erratum L14;
    ``b = inf`` gives δ_log,t).  ``perspective_s`` is δ in u, constant across the face.
    Parameters as in :func:`parameterization`.

    Returns
    -------
    ndarray
        δ, dimensionless.

    Examples
    --------
    >>> round(float(spacing("perspective_t", 0.0, 1.0, 100.0, 60.0)), 6)  # y0/y1 at a = 0
    0.01
    """
    key = check.choice(kind, "kind", ["uniform", "perspective_s", "perspective_t", "log_t", "logp_t"])
    vv = _unit_coordinate(v, "v")
    y0, y1, _, _ = side_face(near, far, fov)
    aa, bb = _ab(a, b, y0, y1)
    yy = y0 + (y1 - y0) * vv
    if key == "uniform":
        return np.ones_like(yy)  # eq. (90)
    with np.errstate(invalid="ignore", divide="ignore"):
        if key == "perspective_s":
            return np.where(np.isinf(aa), 1.0, (yy + aa) / (y1 + aa))  # eq. (96)
        if key == "perspective_t":
            return np.where(np.isinf(aa), 1.0, (yy + aa) ** 2 / ((y0 + aa) * (y1 + aa)))  # eq. (97)
        lin = np.log((y1 + aa) / (y0 + aa)) * (yy + aa) / (y1 - y0)  # eq. (102)
        if key == "log_t":
            return lin
        c0 = 1 / np.log((y0 + aa) * (y1 + bb) / ((y0 + bb) * (y1 + aa)))  # eq. (110)
        finite = (yy + aa) * (yy + bb) / (c0 * (aa - bb) * (y1 - y0))  # eq. (109), sign corrected
    return np.where(np.isinf(bb), lin, finite)


@check.public
def logp_inverse(t: ArrayLike, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, a: ArrayLike = 0.0, b: ArrayLike = np.inf) -> Array:
    """Inverse of F_lp,t: v(t), Lloyd et al. 2007, eq. 84 (corrected, erratum L15).

    With E = exp(t/c0) = (y0+a)(y+b)/((y0+b)(y+a)):
    y = (a(y0+b)E − b(y0+a))/((y0+a) − (y0+b)E), and for b = inf y + a = (y0+a)e^{−t/c0};
    v = (y − y0)/(y1 − y0).  Parameters as in :func:`parameterization`, ``t`` in [0, 1].

    Returns
    -------
    ndarray
        v in [0, 1].

    Examples
    --------
    >>> round(float(logp_inverse(parameterization("logp_t", 0.3, 1.0, 50.0, 60.0), 1.0, 50.0, 60.0)), 12)
    0.3
    """
    tt = _unit_coordinate(t, "t")
    y0, y1, _, _ = side_face(near, far, fov)
    aa, bb = _ab(a, b, y0, y1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        c0_inf = -1 / np.log((y1 + aa) / (y0 + aa))  # eq. (78)
        y_inf = (y0 + aa) * np.exp(-tt / c0_inf) - aa  # eq. (84), corrected
        c0 = 1 / np.log((y0 + aa) * (y1 + bb) / ((y0 + bb) * (y1 + aa)))  # eq. (110)
        E = np.exp(tt / c0)
        y_fin = (aa * (y0 + bb) * E - bb * (y0 + aa)) / ((y0 + aa) - (y0 + bb) * E)
    yy = np.where(np.isinf(bb), y_inf, y_fin)
    return np.where(np.isinf(aa), tt, (yy - y0) / (y1 - y0))  # a = inf: the uniform limit, v = t (as parameterization has it)


@check.public
def critical_factor_side(kind: str, direction: str, near: ArrayLike, far: ArrayLike, fov: ArrayLike, *, a: ArrayLike = 0.0, b: ArrayLike = np.inf, samples: int = 2001) -> Array:
    """R = max_v δ_l/δ_b on a side face for the overhead light, by sampling (Lloyd 2007 eq. 47).

    ``direction`` is ``"s"`` (δ_b,s; maximum over v, with u irrelevant) or ``"t"``.  The
    ratio is monotone or convex for every parameterization here, so its maximum lies at
    v = 0 or v = 1 and the samples only confirm it.  Parameters as in :func:`spacing`;
    it checks the closed forms of :func:`critical_factors` (App. A).

    Returns
    -------
    ndarray
        R, dimensionless.

    Examples
    --------
    >>> round(float(critical_factor_side("uniform", "t", 1.0, 100.0, 90.0)), 6)
    99.0
    """
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
