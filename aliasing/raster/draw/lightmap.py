"""Light maps: one directional light's map fitted to a view frustum, as the analysis builds it.

Warped maps
-----------
A perspective warp (the warping frustum P of :mod:`aliasing.directional`) is a projective
map of the light plane: straight lines stay straight, so a triangle of the light plane is
a triangle in (s, t) and rasterizing its mapped vertices is exact.  Light depth along the
light direction is affine over a planar triangle in light-plane (x, y); under the
projective map it becomes (affine in (s, t)) / (affine in (s, t)) with denominator
1/w, w = z′/n′ = 1 + y/n′: interpolating d/w and 1/w linearly and dividing (``w=``) gives
the exact light depth.  The log+perspective map (Lloyd 2007 eqs. 77–78, 84) bends edges:
The log+perspective map (Lloyd 2007 eqs. 77–78, 84) bends edges: it is rasterized
logarithmically by :func:`aliasing.raster.draw.shadow.shadow_map`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ... import directional, geometry, schemes
from ...view import View, view_args
from .core import check_resolution

Array = NDArray[np.float64]


@dataclass(frozen=True)
class LightMap:
    """The map of one directional light fitted to a view frustum, as the analysis builds it.

    World (eye-space) points → light-plane (x, y) of :func:`aliasing.directional.fit` →
    (s, t) of the warping frustum (:meth:`aliasing.directional.WarpingFrustum.coordinates`),
    or, for ``logperspective``, s of that frustum and t = ln(1 + y/n′)/ln(1 + W_ly/n′)
    (Lloyd 2007 eq. 77 with y0 = 0, a = n′).  Light depth is the distance along the light
    direction (larger = nearer the light), stored negated so that the z-buffer keeps the
    point nearest the light.

    The same class holds the maps of face partitions (:func:`map_set`): a side face's
    adjusted frame (:func:`frame_map`: x_L across, z_L along the face's bisector, the warp's
    centre of projection at Y = −a) and the near face's sheared uniform map
    (:func:`near_face_map`: x_L, z_L unit but not orthogonal).

    Attributes: ``basis`` (rows x_L, y_L, z_L; y_L towards the light), ``y_offset`` (z_L of
    the map's near edge: of the nearest frustum vertex for single maps), ``frustum`` (the fitted WarpingFrustum, shape (1, 1)), ``parameterization``,
    ``n_prime`` [world units].
    """

    basis: Array
    y_offset: float
    frustum: directional.WarpingFrustum
    parameterization: str
    n_prime: float

    def light_plane(self, points: ArrayLike) -> tuple[Array, Array, Array]:
        """(x, y, height) of eye-space points ``(..., 3)``: light-plane coordinates and height along the light."""
        p = np.asarray(points, float)
        return p @ self.basis[0], p @ self.basis[2] - self.y_offset, p @ self.basis[1]

    def plane_point(self, x: ArrayLike, y: ArrayLike) -> Array:
        """Eye-space points ``(..., 3)`` at height 0 with light-plane coordinates (x, y).

        The inverse of :meth:`light_plane` at zero height; the basis rows x_L, z_L need not
        be orthogonal (the near face's sheared map of :func:`near_face_map`).
        """
        xx, yy = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        rhs = np.stack([xx, np.zeros_like(xx), yy + self.y_offset], axis=-1)
        return rhs @ np.linalg.inv(self.basis).T

    def map_plane(self, x: ArrayLike, y: ArrayLike) -> tuple[Array, Array, Array]:
        """(s, t, w) of the perspective (or uniform) map at light-plane points; w = z′/n′ (1 if uniform)."""
        xx, yy = np.asarray(x, float), np.asarray(y, float)
        shape = np.broadcast_shapes(xx.shape, yy.shape)
        xx, yy = np.broadcast_to(xx, shape), np.broadcast_to(yy, shape)
        s, t = self.frustum.coordinates(xx.reshape(1, 1, -1), yy.reshape(1, 1, -1))
        w = np.ones(shape) if np.isinf(self.n_prime) else 1.0 + yy / self.n_prime
        return s.reshape(shape), t.reshape(shape), w

    def coordinates(self, points: ArrayLike) -> tuple[Array, Array, Array, Array]:
        """(s, t, depth, w) of eye-space points ``(..., 3)`` (in front of the warp's centre, y > −n′).

        ``depth`` is the negated height along the light [world units]; ``w`` the homogeneous
        weight z′/n′ (1 if uniform).
        """
        x, y, h = self.light_plane(points)
        with np.errstate(divide="ignore", invalid="ignore"):  # at the centre of projection (y = −n′): inf
            s, t, w = self.map_plane(x, y)
        if self.parameterization == "logperspective" and np.isfinite(self.n_prime):
            with np.errstate(invalid="ignore", divide="ignore"):  # behind the centre of projection: NaN
                t = np.log1p(y / self.n_prime) / np.log1p(float(self.frustum.depth[0, 0]) / self.n_prime)
        return s, t, -h, w

    def perspective_t(self, t_log: ArrayLike) -> Array:
        """t of the perspective map at the log map's t (inverse of eq. 84 composed with eq. 6).

        y = n′((1 + W/n′)^t_log − 1), then t_p = f′(z′ − n′)/(z′(f′ − n′)) with z′ = y + n′.
        """
        npr, depth = self.n_prime, float(self.frustum.depth[0, 0])
        tl = np.asarray(t_log, float)
        y = npr * np.expm1(tl * np.log1p(depth / npr))
        return (y / depth) * (npr + depth) / (npr + y)

    def inverse(self, s: ArrayLike, t: ArrayLike) -> tuple[Array, Array]:
        """Light-plane (x, y) [world units] of map coordinates (s, t): the inverse of :meth:`coordinates`.

        ``t`` is this map's own t (the log map's for ``logperspective``).  Uniform:
        x = x_lo + s·W_x, y = t·W_ly; perspective (inverse of Lloyd 2006 eqs. 5–6):
        y = n′W_ly·t/(n′ + W_ly(1 − t)); log+perspective (inverse of Lloyd 2007 eq. 77):
        y = n′((1 + W_ly/n′)^t − 1); then x = (x_lo + s·(x_hi − x_lo))·(1 + y/n′).

        Parameters
        ----------
        s, t : array_like
            Map coordinates [map units], broadcastable; values outside [0, 1] extrapolate.

        Example
        -------
        >>> lm = light_map(1.0, 100.0, 60.0, "gamma:60@azimuth:20", "LogP")
        >>> x, y = lm.inverse([0.25, 0.5], [0.1, 0.9])
        >>> s, t, _, _ = lm.coordinates(lm.plane_point(x, y))
        >>> np.allclose(s, [0.25, 0.5]) and np.allclose(t, [0.1, 0.9])
        True
        """
        ss, tt = np.broadcast_arrays(check.as_float_array(s, "s"), check.as_float_array(t, "t"))
        npr, depth = self.n_prime, float(self.frustum.depth[0, 0])
        if np.isinf(npr):
            y = tt * depth
        elif self.parameterization == "logperspective":
            y = npr * np.expm1(tt * np.log1p(depth / npr))
        else:
            y = tt * npr * depth / (npr + depth * (1.0 - tt))
        zp = 1.0 if np.isinf(npr) else 1.0 + y / npr
        x_lo, x_hi = float(self.frustum.x_lo[0, 0]), float(self.frustum.x_hi[0, 0])
        return (x_lo + ss * (x_hi - x_lo)) * zp, y

    def matrix(self) -> Array:
        """The 4×4 matrix H with H·(p, 1) = (s·w, t·w, depth, w) for eye-space points p.

        Every map but log+perspective is a projective function of the point: with
        x = x_L·p, y = z_L·p − y_offset and height h = y_L·p (:meth:`light_plane`), the
        homogeneous weight is w = 1 + y/n′ (1 if uniform), s·w = (x − x_lo·w)/(x_hi − x_lo)
        (Lloyd 2006 eq. 5) and t·w = y·(n′ + W_ly)/(W_ly·n′) (eq. 6; y/W_ly if uniform), all
        affine in p; the depth −h is affine in p and is not divided by w.  So
        s = H₀·p̃/H₃·p̃, t = H₁·p̃/H₃·p̃, depth = H₂·p̃ (p̃ = (p, 1)), as :meth:`coordinates`
        gives them; a hardware rasterizer draws the map with this matrix (the ``gl`` backend).

        Raises
        ------
        ValueError
            For a log+perspective map, whose t = ln(1 + y/n′)/ln(1 + W_ly/n′) is no
            projective function of the point.

        Example
        -------
        >>> lm = light_map(1.0, 100.0, 60.0, "gamma:50@azimuth:20", "P")
        >>> p = geometry.frustum_vertices(1.0, 100.0, 60.0)
        >>> h = np.c_[p, np.ones(len(p))] @ lm.matrix().T
        >>> s, t, d, w = lm.coordinates(p)
        >>> np.allclose(h[:, 0] / h[:, 3], s) and np.allclose(h[:, 1] / h[:, 3], t) and np.allclose(h[:, 2], d)
        True
        """
        if self.parameterization == "logperspective" and np.isfinite(self.n_prime):
            raise ValueError("lm must be a projective map (uniform or perspective): a log+perspective map has no 4×4 matrix")
        npr, depth = self.n_prime, float(self.frustum.depth[0, 0])
        x_lo, x_hi = float(self.frustum.x_lo[0, 0]), float(self.frustum.x_hi[0, 0])
        x_row = np.append(self.basis[0], 0.0)
        y_row = np.append(self.basis[2], -self.y_offset)
        if np.isinf(npr):
            w_row, t_row = np.array([0.0, 0.0, 0.0, 1.0]), y_row / depth
        else:
            w_row = y_row / npr + np.array([0.0, 0.0, 0.0, 1.0])  # w = 1 + y/n′
            t_row = y_row * ((npr + depth) / (depth * npr))  # eq. (6) times w
        s_row = (x_row - x_lo * w_row) / (x_hi - x_lo)  # eq. (5) times w
        return np.stack([s_row, t_row, -np.append(self.basis[1], 0.0), w_row])

    def texel_centres(self, resolution: int) -> tuple[Array, Array]:
        """Light-plane (x, y) [world units] of the centres of a resolution² map's texels, each (R, R).

        Entry [j, i] is the texel at s = (i + ½)/R, t = (j + ½)/R of this map's own t: the
        light rays that :func:`shadow_map` samples (for log+perspective maps, the rows of
        :func:`log_row_centres`).

        Example
        -------
        >>> lm = light_map(1.0, 100.0, 60.0, "overhead", "P")
        >>> x, y = lm.texel_centres(4)
        >>> x.shape, bool((np.diff(y[:, 0]) > 0).all())   # rows go away from the map's near edge
        ((4, 4), True)
        """
        res = check_resolution(resolution)
        c = (np.arange(res) + 0.5) / res
        return self.inverse(c[None, :], c[:, None])


@check.public
def light_map(near: float | View, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | schemes.Scheme | None = None, **options: ArrayLike) -> LightMap:
    """Fit the map of a single-map ``scheme`` (Standard, P, LogP, any rule) for one light.

    Parameters
    ----------
    near, far : float
        Eye near and far distances [world units].  Or a :class:`~aliasing.View` in ``near``:
        ``light_map(view, light, scheme)``.
    fov : float
        Full field of view [deg].
    light : str or array_like
        One light direction (spec or vector towards the light).
    scheme : str
        A scheme of :mod:`aliasing.schemes` with one map (no ``ZP<k>`` with k > 1).
    **options
        Passed to :func:`aliasing.schemes.evaluate` (warping-rule options).

    Example
    -------
    >>> lm = light_map(1.0, 100.0, 60.0, "overhead", "P")
    >>> s, t, d, w = lm.coordinates(geometry.frustum_vertices(1.0, 100.0, 60.0))
    >>> float(s.min()), float(t.min()), round(float(s.max()), 12), round(float(t.max()), 12)
    (0.0, 0.0, 1.0, 1.0)
    """
    view, (light, scheme) = view_args(near, far, fov, (light, scheme), (None, None, None, None, "Standard"))
    check.instance(scheme, "scheme", (str, schemes.Scheme))
    sch = schemes.parse(scheme) if isinstance(scheme, str) else scheme
    if sch.k != 1:
        raise ValueError(f"scheme must have a single map (no ZP<k> with k > 1; see light_maps), got {sch.name!r}")
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    if view.shape != ():
        raise ValueError(f"light_map takes one view: near, far and fov must be scalars, got shape {view.shape}")
    return _light_map(view, lv, sch, options)


def _light_map(view: View, lv: Array, sch: schemes.Scheme, options: dict) -> LightMap:
    """The map of one single-map scheme on a validated View, for one light ``lv`` (1, 3)."""
    res = schemes.evaluate(sch, view, lv, **options)
    npr = float(res.n_prime[0, 0])
    verts = geometry.frustum_vertices(view)
    if np.abs(verts).max() > directional.VERTEX_MAX:  # the light-space fit would overflow
        raise ValueError(f"far must keep the view frustum within |coordinate| <= {directional.VERTEX_MAX:g} [world units], got far={check._repr(view.far)}")
    basis = geometry.light_space(lv)[0]
    lf = directional.fit(verts, lv)
    wf = directional.warping_frustum(lf, npr if sch.parameterization != "uniform" else np.inf)
    y_off = float((verts @ basis[2]).min())
    param = sch.parameterization if sch.parameterization != "uniform" else "uniform"
    return LightMap(basis, y_off, wf, param, npr if param != "uniform" else float("inf"))


@check.public
def light_maps(near: float | View, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, **options: ArrayLike) -> tuple[list[LightMap], Array]:
    """The maps of a scheme with k z-partitions (``ZP<k>+…``; k = 1 otherwise) and the split depths.

    Partition i spans [C_i, C_{i+1}] (Lloyd 2006 eqs. 15–16, :func:`aliasing.schemes.z_partitions`)
    and gets its own map fitted to its sub-frustum, as :func:`aliasing.schemes.evaluate` does.
    The arguments are those of :func:`light_map` (a :class:`~aliasing.View` may stand for
    near, far, fov).

    Returns
    -------
    maps : list of LightMap
        One per partition.
    edges : ndarray (k + 1,)
        C_0 = near < … < C_k = far [world units].

    Example
    -------
    >>> maps, edges = light_maps(1.0, 1000.0, 60.0, "overhead", "ZP4+P")
    >>> len(maps), edges.round(3).tolist()
    (4, [1.0, 5.623, 31.623, 177.828, 1000.0])
    """
    view, (light, scheme) = view_args(near, far, fov, (light, scheme), (None, None, None, None, "Standard"))
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    if view.shape != ():
        raise ValueError(f"light_maps takes one view: near, far and fov must be scalars, got shape {view.shape}")
    return _light_maps(view, lv, schemes.parse(scheme), options)


def _light_maps(view: View, lv: Array, sch: schemes.Scheme, options: dict) -> tuple[list[LightMap], Array]:
    """:func:`light_maps` on a validated View, one light ``lv`` (1, 3) and a parsed scheme."""
    n_i, f_i = schemes.z_partitions(view.near, view.far, sch.k)
    base = schemes.Scheme(name=sch.name, k=1, rule=sch.rule, parameterization=sch.parameterization)
    maps = [_light_map(view.between(float(a), float(b)), lv, base, options) for a, b in zip(n_i, f_i)]
    return maps, np.append(n_i, f_i[-1])


def _unit_vector(value: ArrayLike, name: str) -> Array:
    v = check.as_float_array(value, name)
    if v.shape != (3,) or not np.isfinite(v).all() or not np.abs(v).max() > 0:
        raise ValueError(f"{name} must be a finite non-zero vector of shape (3,), got {check._repr(value)}")
    return check.unit_rows(v)  # plain v/|v| unless |v| over- or underflows

