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

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from .geometry import VIEW, light_space

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


def fit(vertices: ArrayLike, light: ArrayLike) -> LightFit:
    """Project frusta ``(K, V, 3)`` (or ``(V, 3)``) for lights ``(N, 3)`` (or ``(3,)``).

    Returns coordinates of shape ``(N, K, V)``; the x origin is the eye's x.
    """
    verts = check.as_float_array(vertices, "vertices")
    if verts.ndim == 2:
        verts = verts[None]
    basis = light_space(np.atleast_2d(check.as_float_array(light, "light")))  # (N, 3, 3)
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
    npr = np.broadcast_to(check.as_float_array(n_prime, "n_prime"), lf.depth.shape)
    with np.errstate(invalid="ignore"):
        zp_np = np.where(np.isinf(npr)[..., None], 1.0, 1.0 + lf.y / npr[..., None])
    near_x = lf.x / zp_np
    return WarpingFrustum(n_prime=npr, depth=lf.depth, x_lo=near_x.min(axis=-1), x_hi=near_x.max(axis=-1))


def _ratio_to_far(n_prime: Array, y: Array, depth: Array) -> Array:
    """(n′ + Y)/(n′ + W_ly), with its limit 1 at n′ = ∞."""
    with np.errstate(invalid="ignore"):
        r = (n_prime + y) / (n_prime + depth)
    return np.where(np.isinf(n_prime), 1.0, r)


def vertex_errors(lf: LightFit, fov: ArrayLike, n_prime: ArrayLike = np.inf, parameterization: str = "perspective") -> tuple[Array, Array]:
    """m_x, m_z [dimensionless] at every vertex, unit resolutions; shape ``(N, K, V)``.

    Parameters
    ----------
    lf : LightFit
        From :func:`fit`.
    fov : array_like
        Full field of view [deg] of the eye.
    n_prime : array_like
        Warping parameter n′ [world units] broadcastable to ``(N, K)``; ``inf`` is a uniform
        map (for ``logperspective`` too, whose limit it is).
    parameterization : {"uniform", "perspective", "logperspective"}
    """
    kind = check.choice(parameterization, "parameterization", PARAMETERIZATIONS)
    w_i = 2 * np.tan(np.radians(check.fov(fov)) / 2) * lf.eye_depth  # eq. (2), corrected
    npr = np.broadcast_to(check.as_float_array(n_prime, "n_prime"), lf.depth.shape)[..., None]
    if (npr <= 0).any():
        raise ValueError("n_prime must be in (0, inf]")
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


def max_errors(vertices: ArrayLike, light: ArrayLike, fov: ArrayLike, n_prime: ArrayLike = np.inf, parameterization: str = "perspective") -> tuple[Array, Array]:
    """M_x, M_z: the maxima of m_x, m_z over the vertices, shape ``(N, K)``.

    S̄ = M_x·M_z.  See the module docstring for the model and an example.
    """
    mx, mz = vertex_errors(fit(vertices, light), fov, n_prime, parameterization)
    return mx.max(axis=-1), mz.max(axis=-1)


def folded_gamma(light: ArrayLike) -> Array:
    """γ [deg] between view direction and light, folded to [0°, 90°] (l and −l alike)."""
    lv = np.atleast_2d(check.as_float_array(light, "light"))
    cos = np.abs(lv @ VIEW) / np.linalg.norm(lv, axis=-1)
    return np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))
