"""Perspective aliasing for a directional light in any direction, at the frustum vertices.

Lloyd et al. 2006 §4.4: the beam widths w_i, w_lx, w_lz are evaluated at the vertices of
the view frustum (they are maximal there: m_x ∝ (Y + n′)/d is linear-fractional and
m_z ∝ (Y + n′)²/d convex over the convex frustum), giving M_x, M_z and S̄ = M_x·M_z.
The shadow map is fitted in Wimmer et al. 2004's light space (§3.4): the frustum's
vertices are projected onto the light image plane, whose y axis (Wimmer's z_L) is the view
direction projected onto it; W_ly is the frustum's extent along that axis and the warping
frustum's centre of projection sits n′ before the nearest vertex, at the eye's x.  This
is also the model of Lloyd et al. 2007 App. B (eqs. 111–121) for lights in the frustum's
yz plane, extended to any direction as its §6.2 does ("evaluating δ_l/δ_b only at the
vertices").  Lloyd 2007's Table 3 omits the 1/cos²θ factor of δ_b; so does this model.

Parameterizations along y (the shadow map's t axis; s is across, always perspective or
uniform):

* ``uniform``: w_lx = W_lx (the x extent), w_lz = W_ly;
* ``perspective``: w_lx = (Y + n′)·ptp(X/(Y + n′)), w_lz = (Y + n′)²·W_ly/(n′(n′ + W_ly))
  (Lloyd 2006 eqs. 3–8; Lloyd 2007 eqs. 96–97 with a = n′);
* ``logperspective``: s as perspective, w_lz = (Y + n′)·ln((n′ + W_ly)/n′)
  (Lloyd 2007 eq. 78 / 102: dF_lp,t/dv has the spacing of F_log,t).

with Y the vertex's distance from the nearest one along y.  w_i = 2 tanθ·d at eye depth d
(Lloyd 2006 eq. 2, corrected).  At an overhead light these reduce to Lloyd 2006 eqs. 7–12
(tested).

Speed: :func:`light_frame` rotates the view's 4 corner rays into every direction's
light frame once; :func:`slice_fit` and :func:`slice_errors` fit and evaluate the maps of any
z-slices from those coordinates scaled by depth, ``(K, N)`` arrays with directions innermost,
giving the same numbers as :func:`fit` + :func:`vertex_errors` on the slices' vertices.

Example
-------
>>> import numpy as np
>>> from aliasing.geometry import frustum_vertices, light_direction
>>> v = frustum_vertices(1.0, 100.0, 90.0)
>>> mx, mz = max_errors(v, light_direction(90.0), 90.0, n_prime=11.0)
>>> float(mx[0, 0]), round(float(mz[0, 0]), 12)
(10.0, 4.95)
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from .geometry import VIEW, light_space
from .view import View, tan_theta

Array = NDArray[np.float64]
PARAMETERIZATIONS = ("uniform", "perspective", "logperspective")


@dataclass(frozen=True)
class LightFit:
    """Frustum vertices in light-image-plane coordinates, shape ``(N, K, V)``.

    ``x``: across, ``y``: along the projected view direction measured from the nearest
    vertex, ``depth``: W_ly = max y ``(N, K)``, ``eye_depth``: the vertices' eye depth d
    ``(K, V)``.
    """

    x: Array
    y: Array
    depth: Array
    eye_depth: Array


# Largest |coordinate| of a vertex: projections and their differences then stay below 1.8e308.
VERTEX_MAX = 1e150


@check.public
def fit(vertices: ArrayLike, light: ArrayLike) -> LightFit:
    """Project frusta ``(K, V, 3)`` (or ``(V, 3)``) for lights ``(N, 3)`` (or ``(3,)``).

    Returns coordinates of shape ``(N, K, V)``; the x origin is the eye's x.
    """
    verts = check.finite(vertices, "vertices")
    if verts.ndim not in (2, 3) or verts.shape[-1] != 3 or verts.shape[-2] == 0:
        raise ValueError(f"vertices must have shape (V, 3) or (K, V, 3) with V >= 1, got {verts.shape}")
    if (np.abs(verts) > VERTEX_MAX).any():
        raise ValueError(f"vertices must have coordinates in [-{VERTEX_MAX:g}, {VERTEX_MAX:g}] (their projections must stay finite)")
    if verts.ndim == 2:
        verts = verts[None]
    basis = light_space(np.atleast_2d(_lights(light)))  # (N, 3, 3)
    x = np.einsum("nj,kvj->nkv", basis[:, 0], verts)
    y = np.einsum("nj,kvj->nkv", basis[:, 2], verts)
    y = y - y.min(axis=-1, keepdims=True)
    return LightFit(x=x, y=y, depth=y.max(axis=-1), eye_depth=verts @ VIEW)


@dataclass(frozen=True)
class WarpingFrustum:
    """The perspective warping frustum P fitted to the vertices (Wimmer et al. 2004 §3.4–3.6).

    In light-image-plane coordinates (x across, y along the projected view direction from
    the nearest vertex): centre of projection at (0, −n′); near plane y = 0, far plane
    y = W_ly (distances n′ and n′ + W_ly from the centre); ``x_lo``, ``x_hi`` the extent of
    the vertices projected centrally onto the near plane.  All ``(N, K)``.
    """

    n_prime: Array
    depth: Array
    x_lo: Array
    x_hi: Array

    def coordinates(self, x: ArrayLike, y: ArrayLike) -> tuple[Array, Array]:
        """Shadow-map (s, t) ∈ [0, 1]² of light-plane points ``(N, K, M)`` (M points per map).

        s = (n′x/(y + n′) − x_lo)/(x_hi − x_lo), t = f′(z′ − n′)/(z′(f′ − n′)) with z′ = y + n′
        (Lloyd 2006 eqs. 5–6, corrected); for n′ = ∞ both are the uniform maps.
        """
        xx, yy = np.asarray(x, float), np.asarray(y, float)
        npr, d = self.n_prime[..., None], self.depth[..., None]
        with np.errstate(invalid="ignore"):
            zp_np = np.where(np.isinf(npr), 1.0, 1.0 + yy / npr)  # z′/n′
        s = (xx / zp_np - self.x_lo[..., None]) / (self.x_hi - self.x_lo)[..., None]
        t = yy / d / (zp_np * _ratio_to_far(npr, 0.0, d))  # eq. (6): (z′ − n′)/(f′ − n′) · f′/z′
        return s, t


@check.public
def warping_frustum(lf: LightFit, n_prime: ArrayLike = np.inf) -> WarpingFrustum:
    """Fit P (or, for n′ = ∞, the tight orthographic map) to the projected vertices.

    Example
    -------
    >>> from aliasing.geometry import frustum_vertices, light_direction
    >>> lf = fit(frustum_vertices(1.0, 100.0, 90.0), light_direction(90.0))
    >>> p = warping_frustum(lf, 11.0)
    >>> [float(c.min()) for c in p.coordinates(lf.x, lf.y)], [float(c.max()) for c in p.coordinates(lf.x, lf.y)]
    ([0.0, 0.0], [1.0, 1.0])
    """
    check.instance(lf, "lf", LightFit)
    npr = _n_prime(n_prime, lf)
    with np.errstate(invalid="ignore"):
        zp_np = np.where(np.isinf(npr)[..., None], 1.0, 1.0 + lf.y / npr[..., None])
    near_x = lf.x / zp_np
    return WarpingFrustum(n_prime=npr, depth=lf.depth, x_lo=near_x.min(axis=-1), x_hi=near_x.max(axis=-1))


def _ratio_to_far(n_prime: Array, y: Array, depth: Array) -> Array:
    """(n′ + Y)/(n′ + W_ly), with its limit 1 at n′ = ∞."""
    with np.errstate(invalid="ignore"):
        r = (n_prime + y) / (n_prime + depth)
    return np.where(np.isinf(n_prime), 1.0, r)


@check.public
def vertex_errors(lf: LightFit, fov: ArrayLike, n_prime: ArrayLike = np.inf, parameterization: str = "perspective") -> tuple[Array, Array]:
    """m_x, m_z [dimensionless] at every vertex, unit resolutions; shape ``(N, K, V)``.

    Parameters
    ----------
    lf : LightFit
        From :func:`fit`.
    fov : array_like or View
        Full field of view [deg] of the eye (or a :class:`aliasing.View`, whose fov is used).
    n_prime : array_like
        Warping parameter n′ [world units] broadcastable to ``(N, K)``; ``inf`` is a uniform
        map (for ``logperspective`` too, whose limit it is).
    parameterization : {"uniform", "perspective", "logperspective"}
    """
    kind = check.choice(parameterization, "parameterization", PARAMETERIZATIONS)
    check.instance(lf, "lf", LightFit)
    if (lf.eye_depth <= 0).any():
        raise ValueError("lf's vertices must lie in front of the eye (eye depth z > 0)")
    w_i = 2 * _tan_theta(fov) * lf.eye_depth  # eq. (2), corrected
    npr = _n_prime(n_prime, lf)
    with np.errstate(over="ignore"):
        if not np.isfinite(lf.depth / npr).all():  # z′/n′ would overflow, and inf·0 give NaN
            raise ValueError(f"n_prime is too small for the maps' depth W_ly: W_ly/n_prime exceeds 1.8e308, got n_prime={check._show(npr)}")
    npr = npr[..., None]
    if kind == "uniform":
        npr = np.full_like(npr, np.inf)
    y, depth = lf.y, lf.depth[..., None]
    with np.errstate(invalid="ignore"):
        zp_np = np.where(np.isinf(npr), 1.0, 1.0 + y / npr)  # z′/n′
    wf = warping_frustum(lf, npr[..., 0])
    w_lx = zp_np * (wf.x_hi - wf.x_lo)[..., None]  # eq. (3): z′·W_n/n′, W_n the near-plane width
    if kind == "logperspective":
        with np.errstate(invalid="ignore", divide="ignore"):
            log_term = np.where(np.isinf(npr), depth, npr * np.log1p(depth / npr))  # n′ ln(1 + W_ly/n′)
        w_lz = zp_np * log_term  # eq. (78): (Y + n′) ln((n′ + W_ly)/n′)
    else:
        w_lz = zp_np * _ratio_to_far(npr, y, depth) * depth  # eq. (4): z′² W_ly/(n′ f′)
    return w_lx / w_i, w_lz / w_i


@check.public
def max_errors(vertices: ArrayLike, light: ArrayLike, fov: ArrayLike, n_prime: ArrayLike = np.inf, parameterization: str = "perspective") -> tuple[Array, Array]:
    """M_x, M_z: the maxima of m_x, m_z over the vertices, shape ``(N, K)``.

    S̄ = M_x·M_z.  See the module docstring for the model and an example.
    """
    mx, mz = vertex_errors(fit(vertices, light), fov, n_prime, parameterization)
    return mx.max(axis=-1), mz.max(axis=-1)


def folded_gamma(light: ArrayLike) -> Array:
    """γ [deg] between view direction and light, folded to [0°, 90°] (l and −l alike)."""
    lv = np.atleast_2d(_lights(light))
    with np.errstate(over="ignore", under="ignore"):
        norm = np.linalg.norm(lv, axis=-1)
    odd = ~np.isfinite(norm) | (norm < 1e-150)
    if odd.any():  # |l| overflows or underflows: scale those vectors by their largest component
        lv = np.where(odd[:, None], lv / np.abs(lv).max(axis=-1, keepdims=True), lv)
        norm = np.linalg.norm(lv, axis=-1)
    cos = np.abs(lv @ VIEW) / norm
    return np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))


def _lights(light: ArrayLike) -> Array:
    """Light vectors ``(..., 3)``: finite, non-zero (one pass, at the public entry)."""
    lv = check.finite(light, "light")
    if lv.shape[-1:] != (3,):
        raise ValueError(f"light must have shape (3,) or (N, 3), got {lv.shape}")
    if lv.ndim > 2:
        raise ValueError(f"light must have shape (3,) or (N, 3), got {lv.shape}")
    if (np.abs(lv).max(axis=-1) == 0).any():
        raise ValueError("light must be a non-zero vector")
    return lv


def _n_prime(n_prime: ArrayLike, lf: LightFit) -> Array:
    """n′ broadcast to the maps ``(N, K)``, in (0, inf]."""
    npr = check.as_float_array(n_prime, "n_prime")
    try:
        npr = np.broadcast_to(npr, lf.depth.shape)
    except ValueError:
        raise ValueError(f"n_prime of shape {npr.shape} does not broadcast to the maps' shape {lf.depth.shape} (N, K)") from None
    if (npr <= 0).any():
        raise ValueError(f"n_prime must be in (0, inf] (inf is a uniform map), got {check._show(npr)}")
    return npr


def _tan_theta(fov: ArrayLike | View) -> Array | float:
    """tan θ_y: the eye beam w_i = 2 d tan θ_y of a pixel of unit vertical resolution (square pixels at any aspect)."""
    return fov.tan_theta if isinstance(fov, View) else tan_theta(fov)


# --- shared light frames: the rotation done once per (view, directions) -------------------------


@dataclass(frozen=True)
class LightFrame:
    """The view's 4 corner rays in each direction's light-image-plane frame, computed once.

    ``X``, ``Y``: coordinates ``(4, N)`` of the corner rays at unit eye depth across (x_L)
    and along the projected view direction (Wimmer's z_L); a vertex at eye depth d of
    corner c is at ``(d X[c], d Y[c])``, so every z-slice of the frustum — every map of every
    z-partition — is these coordinates scaled, with no rotation per map.
    ``x_min`` … ``y_max`` ``(N,)``: their extremes over the corners.
    """

    view: View
    X: Array
    Y: Array
    x_min: Array
    x_max: Array
    y_min: Array
    y_max: Array

    @property
    def size(self) -> int:
        """Number of directions N."""
        return self.X.shape[1]


def light_frame(view: View, light: ArrayLike) -> LightFrame:
    """Rotate the corner rays of one ``view`` into the light frames of ``light`` ``(N, 3)``.

    Example
    -------
    >>> fr = light_frame(View(1.0, 100.0, 90.0), [0.0, 1.0, 0.0])   # overhead
    >>> fr.Y[:, 0].tolist(), fr.X[:, 0].tolist()    # along the view: 1 at every corner
    ([1.0, 1.0, 1.0, 1.0], [-1.0, 1.0, 1.0, -1.0])
    """
    check.instance(view, "view", View)
    if view.shape != ():
        raise ValueError(f"a light frame needs one view (scalar near, far, fov), got fields of shape {view.shape}")
    basis = light_space(np.atleast_2d(check.as_float_array(light, "light")))  # (N, 3, 3)
    rays = view.corner_rays  # (4, 3); the third component is 1
    bx, bz = basis[:, 0].T.copy(), basis[:, 2].T.copy()  # (3, N): contiguous per component
    X = rays[:, 0, None] * bx[0] + rays[:, 1, None] * bx[1] + bx[2]  # (4, N), no einsum on a 3-long axis
    Y = rays[:, 0, None] * bz[0] + rays[:, 1, None] * bz[1] + bz[2]
    return LightFrame(view, X, Y, X.min(axis=0), X.max(axis=0), Y.min(axis=0), Y.max(axis=0))


@dataclass(frozen=True)
class SliceFit:
    """Maps fitted to the z-slices [near_i, far_i] of a :class:`LightFrame`, shape ``(K, N)``.

    Maps first, directions last, so that every inner loop runs over the N directions.
    ``y_lo``: the nearest vertex along y (the map's near plane); ``y_near``, ``y_far``: the
    largest y − y_lo among the slice's near and far corners; ``depth`` = W_ly.
    """

    frame: LightFrame
    near: Array  # (K, 1)
    far: Array  # (K, 1)
    y_lo: Array
    y_near: Array
    y_far: Array
    depth: Array

    @cached_property
    def vertices(self) -> tuple[Array, Array]:
        """x and y − y_lo of the 8 vertices, ``(8, K, N)`` each (the 4 near corners, then far).

        Computed once per slice fit and shared by every map fitted to it; reductions over
        the vertices run over contiguous ``(K, N)`` slabs.
        """
        fr, K = self.frame, self.near.shape[0]
        x, y = np.empty((8, K, fr.size)), np.empty((8, K, fr.size))
        for j, d in enumerate((self.near, self.far)):
            np.multiply(d[None], fr.X[:, None, :], out=x[4 * j : 4 * j + 4])
            np.multiply(d[None], fr.Y[:, None, :], out=y[4 * j : 4 * j + 4])
        y -= self.y_lo
        return x, y

    def light_fit(self) -> LightFit:
        """The per-vertex :class:`LightFit` ``(N, K, 8)`` of the same maps."""
        x, y = self.vertices
        n, f = self.near[:, 0], self.far[:, 0]
        eye = np.concatenate([np.repeat(n[:, None], 4, 1), np.repeat(f[:, None], 4, 1)], axis=1)
        return LightFit(x=np.transpose(x, (2, 1, 0)), y=np.transpose(y, (2, 1, 0)), depth=self.depth.T, eye_depth=eye)


def slice_fit(frame: LightFrame, near: ArrayLike, far: ArrayLike) -> SliceFit:
    """Fit one map per z-slice ``[near_i, far_i]`` ``(K,)`` for every direction of ``frame``.

    Extremes over a slice's 8 vertices come from the corner extremes scaled by the two
    depths (d > 0 keeps the order, rounding included), so this is ``(K, N)`` work only.

    Example
    -------
    >>> fr = light_frame(View(1.0, 100.0, 90.0), [0.0, 1.0, 0.0])
    >>> slice_fit(fr, [1.0, 10.0], [10.0, 100.0]).depth.tolist()   # (K, N): f_i − n_i overhead
    [[9.0], [90.0]]
    """
    check.instance(frame, "frame", LightFrame)
    n = check.positive(near, "near").reshape(-1, 1)
    f = check.positive(far, "far").reshape(-1, 1)
    if n.shape != f.shape or n.size == 0:
        raise ValueError(f"near and far must list the same number (>= 1) of slices, got {n.size} and {f.size}")
    if (f <= n).any():
        raise ValueError("far must be greater than near for every slice")
    ymin, ymax = frame.y_min[None], frame.y_max[None]
    lo = np.minimum(n * ymin, f * ymin)
    y_near, y_far = n * ymax - lo, f * ymax - lo
    return SliceFit(frame, n, f, lo, y_near, y_far, np.maximum(y_near, y_far))


def slice_errors(sf: SliceFit, n_prime: ArrayLike = np.inf, parameterization: str = "perspective") -> tuple[Array, Array]:
    """M_x, M_z ``(K, N)``: :func:`max_errors` of the slices' maps, without a vertex axis.

    Same model and same floating-point operations per vertex as :func:`vertex_errors`
    (Lloyd et al. 2006 §4.4 eqs. 2–4; Lloyd et al. 2007 eq. 78), but m_x and m_z grow
    with y at a fixed eye depth, so their maxima over a slice's 4 near (4 far) corners are
    at the corner of largest y; only the near-plane x extent of a warped map needs all
    8 vertices.  ``n_prime`` broadcasts to ``(K, N)``.

    Example
    -------
    >>> sf = slice_fit(light_frame(View(1.0, 100.0, 90.0), [0.0, 1.0, 0.0]), 1.0, 100.0)
    >>> [float(m[0, 0]) for m in slice_errors(sf, 11.0)]   # Lloyd 2006 eqs. 7-12 at n' = n + sqrt(fn)
    [10.0, 4.95]
    """
    kind = check.choice(parameterization, "parameterization", PARAMETERIZATIONS)
    check.instance(sf, "sf", SliceFit)
    fr = sf.frame
    npr = check.as_float_array(n_prime, "n_prime")
    try:
        npr = np.broadcast_to(npr, sf.depth.shape)
    except ValueError:
        raise ValueError(f"n_prime of shape {npr.shape} does not broadcast to the slices' shape {sf.depth.shape} (K, N)") from None
    if (npr <= 0).any() or np.isnan(npr).any():
        raise ValueError("n_prime must be in (0, inf]")
    n, f = sf.near, sf.far
    if kind == "uniform" or np.isinf(npr).all():
        npr = np.full(sf.depth.shape, np.inf)
        x_lo = np.minimum(n * fr.x_min, f * fr.x_min)
        x_hi = np.maximum(n * fr.x_max, f * fr.x_max)
    else:
        x, y = sf.vertices
        q = np.divide(y, npr, out=np.empty_like(y))
        q += 1.0  # z′/n′
        np.divide(x, q, out=q)  # x/(z′/n′): central projection onto the near plane
        x_lo, x_hi = q.min(axis=0), q.max(axis=0)
    width = x_hi - x_lo
    depth = sf.depth
    inf = np.isinf(npr)
    two_tan = 2 * fr.view.tan_theta
    if kind == "logperspective":
        with np.errstate(invalid="ignore", divide="ignore"):
            log_term = np.where(inf, depth, npr * np.log1p(depth / npr))  # n′ ln(1 + W_ly/n′)
    out_x, out_z = [], []
    for y, d in ((sf.y_near, n), (sf.y_far, f)):
        zp_np = 1.0 + y / npr  # z′/n′ (exactly 1 at n′ = ∞)
        w_i = two_tan * d  # eq. (2), corrected
        out_x.append(zp_np * width / w_i)  # eq. (3)
        if kind == "logperspective":
            out_z.append(zp_np * log_term / w_i)  # eq. (78)
        else:
            with np.errstate(invalid="ignore"):
                ratio = np.where(inf, 1.0, (npr + y) / (npr + depth))
            out_z.append(zp_np * ratio * depth / w_i)  # eq. (4)
    return np.maximum(*out_x), np.maximum(*out_z)
