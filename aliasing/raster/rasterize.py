"""Vectorized numpy triangle rasterizer: shadow (depth) maps and the eye pass.

Map coordinates
---------------
A map of resolution R covers (s, t) ∈ [0, 1]²; texel (row j, column i) has its centre at
s = (i + ½)/R and, by default, t = (j + ½)/R (row 0 is t ≈ 0: show with ``origin="lower"``).
A texel belongs to a triangle when its centre lies inside it; a centre exactly on an edge
goes to one triangle only (the top-left rule, here with t up: an edge on the triangle's
left side, or a horizontal edge at its bottom, owns the centres lying exactly on it), so a
mesh without overlaps covers every texel at most once.  Depth is interpolated from the vertices by barycentric weights, optionally
perspective-correctly with per-vertex homogeneous weights ``w``: d = Σ bᵢdᵢ/wᵢ / Σ bᵢ/wᵢ.

Algorithm (no loop per pixel or per triangle): the rows of every triangle's bounding box
are expanded into (triangle, row) pairs with ``np.repeat``.  Along a row each edge function
is monotone (in rounded arithmetic too), so the covered texels form an interval: its ends
are estimated from the edges' intersections with the row's centre line and settled exactly
by the edge-function test (with the top-left rule) at the estimate ± 1 texel.  Depth is a
ratio of two affine functions of the column along a row; the spans are expanded into
(triangle, texel) pairs and merged into the z-buffer with ``np.minimum.at`` (the triangle
id map keeps the candidate equal to the running minimum).  Rows and texels are processed in
chunks of at most ``chunk``, so memory is bounded by the chunk size, not by the triangles'
size, and the work is the covered area plus a few tests per row.

Warped maps
-----------
A perspective warp (the warping frustum P of :mod:`aliasing.directional`) is a projective
map of the light plane: straight lines stay straight, so a triangle of the light plane is
a triangle in (s, t) and rasterizing its mapped vertices is exact.  Light depth along the
light direction is affine over a planar triangle in light-plane (x, y); under the
projective map it becomes (affine in (s, t)) / (affine in (s, t)) with denominator
1/w, w = z′/n′ = 1 + y/n′: interpolating d/w and 1/w linearly and dividing (``w=``) gives
the exact light depth.  The log+perspective map (Lloyd 2007 eqs. 77–78, 84) bends edges:
:func:`log_row_centres` gives the texel centres of the log map mapped back into the
perspective map's t (the inverse of eq. 84), and rasterizing there with the straight edge
equations of the perspective map is logarithmic rasterization (Lloyd 2007 §6.3): the
bounding box is found in warped space and each candidate centre is tested against the
triangle's straight edges.

Example
-------
>>> import numpy as np
>>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]])  # (s, t, depth)
>>> m = rasterize(tri, 8)
>>> int(np.isfinite(m.depth).sum()), m.degenerate   # s + t < 1; the 8 centres on s + t = 1 are not owned
(28, 0)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from .. import directional, faces, geometry, schemes

Array = NDArray[np.float64]

#: Largest resolution accepted: an 8192² float64 depth map and its int64 id map take 1 GiB
#: (16384² would need 4 GiB for these two arrays alone).
MAX_RESOLUTION = 8192
#: Default number of candidate (triangle, texel) pairs per vectorized chunk (≈ 100 MB of temporaries).
CHUNK = 1 << 20


@dataclass(frozen=True)
class DepthMap:
    """A rasterized depth map.

    Attributes
    ----------
    depth : ndarray, shape (R, R)
        Minimum interpolated depth per texel [caller's depth units]; ``inf`` where empty.
        ``depth[j, i]`` is the texel at s = (i + ½)/R and t = row centre j.
    triangle : ndarray of int64, shape (R, R)
        Index of the visible (nearest) triangle per texel, −1 where empty.
    resolution : int
        R, texels per side.
    rasterized : int
        Triangles rasterized (non-degenerate).
    degenerate : int
        Triangles skipped: zero area in map space, or a non-finite coordinate.
    """

    depth: Array
    triangle: NDArray[np.int64]
    resolution: int
    rasterized: int
    degenerate: int


def check_resolution(resolution: int, name: str = "resolution") -> int:
    """Validate a resolution: a whole number in [1, MAX_RESOLUTION]."""
    if isinstance(resolution, bool) or not isinstance(resolution, (int, np.integer)) and not (isinstance(resolution, float) and resolution.is_integer()):
        raise ValueError(f"{name} must be a whole number in [1, {MAX_RESOLUTION}], got {resolution!r}")
    r = int(resolution)
    if r < 1 or r > MAX_RESOLUTION:
        raise ValueError(f"{name} must be in [1, {MAX_RESOLUTION}] (larger maps do not fit in memory), got {r}")
    return r


def _triangles(triangles: ArrayLike, name: str = "triangles") -> Array:
    tri = np.asarray(triangles, dtype=float) if not isinstance(triangles, np.ndarray) else triangles.astype(float, copy=False)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise ValueError(f"{name} must have shape (T, 3, 3) (T triangles, 3 corners, 3 coordinates), got {tri.shape}")
    if tri.shape[0] == 0:
        raise ValueError(f"{name} is empty: need at least 1 triangle")
    return tri


def rasterize(triangles: ArrayLike, resolution: int, *, w: ArrayLike | None = None, row_centres: ArrayLike | None = None, chunk: int = CHUNK) -> DepthMap:
    """Rasterize triangles given per-corner (s, t, depth) into a z-buffer.

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Per triangle, per corner: map coordinates s, t [map units; the map is [0, 1]²] and a
        depth [any unit; smaller is nearer].  Parts outside the map are clipped.
    resolution : int
        R, texels per side, 1 ≤ R ≤ :data:`MAX_RESOLUTION`.
    w : array_like, shape (T, 3), optional
        Positive homogeneous weights for perspective-correct depth (see the module
        docstring); default: depth is affine in (s, t).
    row_centres : array_like, shape (R,), optional
        Increasing t of each row's texel centres (e.g. :func:`log_row_centres`); default
        (j + ½)/R.
    chunk : int
        Rows, or texels, per vectorized step (temporaries ≈ 250 bytes per row, 50 per texel).

    Returns
    -------
    DepthMap

    Raises
    ------
    ValueError
        Empty or malformed ``triangles``, resolution outside [1, MAX_RESOLUTION], bad ``w``
        or ``row_centres``.

    Example
    -------
    >>> import numpy as np
    >>> sq = np.array([[[0, 0, 1], [1, 0, 1], [1, 1, 1]], [[0, 0, 2], [1, 1, 2], [0, 1, 2]]], float)
    >>> m = rasterize(sq, 4)
    >>> (m.triangle >= 0).all(), sorted(np.unique(m.depth).tolist())   # diagonal texels to one triangle only
    (np.True_, [1.0, 2.0])
    """
    tri = _triangles(triangles)
    res = check_resolution(resolution)
    if isinstance(chunk, bool) or int(chunk) < 1:
        raise ValueError(f"chunk must be a whole number >= 1, got {chunk!r}")
    chunk = int(chunk)
    n_tri = tri.shape[0]
    if w is None:
        inv_w = np.ones((n_tri, 3))
    else:
        ww = check.as_float_array(w, "w")
        if ww.shape != (n_tri, 3):
            raise ValueError(f"w must have shape (T, 3) = ({n_tri}, 3), got {ww.shape}")
        if not ((ww > 0) & np.isfinite(ww)).all():
            raise ValueError("w must be in (0, inf) (homogeneous weights of points in front of the projection centre)")
        inv_w = 1.0 / ww
    if row_centres is None:
        rows = (np.arange(res) + 0.5) / res
        uniform_rows = True
    else:
        rows = check.as_float_array(row_centres, "row_centres")
        if rows.shape != (res,) or (np.diff(rows) <= 0).any():
            raise ValueError(f"row_centres must be {res} increasing values (one per row)")
        uniform_rows = False

    # texel units for s (and t when rows are uniform): keeps edge functions well scaled
    sx = tri[:, :, 0] * res
    ty = tri[:, :, 1] * res if uniform_rows else tri[:, :, 1]
    row_coord = rows * res if uniform_rows else rows
    area2 = (sx[:, 1] - sx[:, 0]) * (ty[:, 2] - ty[:, 0]) - (sx[:, 2] - sx[:, 0]) * (ty[:, 1] - ty[:, 0])
    finite = np.isfinite(tri).all(axis=(1, 2)) & np.isfinite(inv_w).all(axis=1)
    good = finite & (area2 != 0) & np.isfinite(area2)
    good &= np.abs(area2) > 1e-12 * (np.ptp(sx, axis=1) * np.ptp(ty, axis=1) + 1e-300)
    degenerate = int(n_tri - good.sum())

    depth = np.full(res * res, np.inf)
    ident = np.full(res * res, -1, dtype=np.int64)
    idx = np.nonzero(good)[0]
    # bounding boxes in texel indices (centre inside [lo, hi])
    with np.errstate(invalid="ignore"):
        x0 = np.clip(np.ceil(sx[idx].min(axis=1) - 0.5), 0, res).astype(np.int64)
        x1 = np.clip(np.floor(sx[idx].max(axis=1) - 0.5), -1, res - 1).astype(np.int64)
    y0 = np.searchsorted(row_coord, ty[idx].min(axis=1), side="left").astype(np.int64)
    y1 = np.searchsorted(row_coord, ty[idx].max(axis=1), side="right").astype(np.int64) - 1
    keep = (x1 >= x0) & (y1 >= y0)
    idx, x0, x1, y0, y1 = idx[keep], x0[keep], x1[keep], y0[keep], y1[keep]
    if idx.size:
        height = y1 - y0 + 1
        dep = tri[:, :, 2]
        # groups of triangles with at most `chunk` rows in all (a tall triangle alone may exceed it)
        bounds = _chunk_bounds(height, chunk)
        for a, b in zip(bounds[:-1], bounds[1:]):
            _rasterize_rows(idx[a:b], x0[a:b], x1[a:b], y0[a:b], height[a:b], sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident)
    return DepthMap(depth.reshape(res, res), ident.reshape(res, res), res, int(good.sum()), degenerate)


def _chunk_bounds(size: NDArray[np.int64], chunk: int) -> NDArray[np.int64]:
    """Cut indices into consecutive groups whose summed size is ≤ chunk (or of one element)."""
    cum = np.cumsum(size)
    n = size.size
    bounds = [0]
    while bounds[-1] < n:
        base = int(cum[bounds[-1] - 1]) if bounds[-1] else 0
        nxt = int(np.searchsorted(cum, base + chunk, side="right"))
        bounds.append(min(max(nxt, bounds[-1] + 1), n))
    return np.asarray(bounds)


def _expand(counts: NDArray[np.int64]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """(owner, k) for k in range(counts[owner]), for every owner: the vectorized double loop."""
    owner = np.repeat(np.arange(counts.size), counts)
    first = np.cumsum(counts) - counts
    return owner, np.arange(owner.size) - first[owner]


def _edges(ax: Array, ay: Array, sgn: Array) -> list[tuple[Array, Array, Array, Array]]:
    """Per edge opposite corner e: origin (x, y) and counter-clockwise direction (ex, ey)."""
    out = []
    for e in range(3):
        i0, i1 = (e + 1) % 3, (e + 2) % 3
        out.append((ax[:, i0], ay[:, i0], (ax[:, i1] - ax[:, i0]) * sgn, (ay[:, i1] - ay[:, i0]) * sgn))
    return out


def _inside(edges, px: Array, py: Array) -> NDArray[np.bool_]:
    """The exact coverage predicate (edge functions with the top-left rule) at texel centres."""
    ok = np.ones(px.shape, dtype=bool)
    for ox, oy, ex, ey in edges:
        f = ex * (py - oy) - ey * (px - ox)  # > 0 on the inner side; monotone in px even rounded
        owns = (ey < 0) | ((ey == 0) & (ex > 0))
        ok &= (f > 0) | ((f == 0) & owns)
    return ok


def _rasterize_rows(idx, x0, x1, y0, height, sx, ty, row_coord, dep, inv_w, area2, res, chunk, depth, ident) -> None:
    """Exact covered span of every (triangle, row), then depth on the span's texels.

    Each edge function is monotone along a row (also in rounded arithmetic), so the covered
    texels of a row are an interval; its ends are estimated from the edges' intersections
    with the row's centre line and settled by the exact predicate at the estimate ± 1.
    """
    owner, k = _expand(height)
    row = y0[owner] + k
    y = row_coord[row]
    t_id = idx[owner]
    ax, ay = sx[t_id], ty[t_id]
    lo = np.full(row.size, np.inf)
    hi = np.full(row.size, -np.inf)
    for e in range(3):
        i0, i1 = e, (e + 1) % 3
        ya, yb = ay[:, i0], ay[:, i1]
        cross = (np.minimum(ya, yb) <= y) & (y <= np.maximum(ya, yb)) & (ya != yb)
        with np.errstate(divide="ignore", invalid="ignore"):
            xe = ax[:, i0] + (y - ya) * (ax[:, i1] - ax[:, i0]) / (yb - ya)
        lo = np.where(cross, np.minimum(lo, xe), lo)
        hi = np.where(cross, np.maximum(hi, xe), hi)
    has = np.isfinite(lo) & np.isfinite(hi)
    lo_e = np.clip(np.ceil(np.where(has, lo, 0.0) - 0.5), -2, res + 1).astype(np.int64)
    hi_e = np.clip(np.floor(np.where(has, hi, -1.0) - 0.5), -2, res + 1).astype(np.int64)
    sgn = np.sign(area2[t_id])
    edges = _edges(ax, ay, sgn)
    # the true ends are within one texel of the estimates (rounding only), so the smallest
    # and largest covered columns among estimate - 1 .. estimate + 1 (kept inside the bounding
    # box) are the exact ends; none covered means an empty row (e.g. on a horizontal edge
    # that this triangle does not own)
    bx0, bx1 = x0[owner], x1[owner]
    col_lo = np.full(row.size, res + 5, dtype=np.int64)
    for d in (1, 0, -1):
        c = np.clip(lo_e + d, bx0, bx1)
        col_lo = np.where(_inside(edges, c + 0.5, y), c, col_lo)
    col_hi = np.full(row.size, -5, dtype=np.int64)
    for d in (-1, 0, 1):
        c = np.clip(hi_e + d, bx0, bx1)
        col_hi = np.where(_inside(edges, c + 0.5, y), c, col_hi)
    width = np.where(has, np.maximum(col_hi - col_lo + 1, 0), 0)
    # depth along the row: barycentrics are affine in px, so d/w and 1/w are (a + b px)
    denom = np.abs(area2[t_id])
    iw = inv_w[t_id]
    dw = dep[t_id] * iw
    n0 = np.zeros(row.size)
    n1 = np.zeros(row.size)
    m0 = np.zeros(row.size)
    m1 = np.zeros(row.size)
    for e, (ox, oy, ex, ey) in enumerate(edges):
        f0 = (ex * (y - oy) + ey * ox) / denom  # b_e at px = 0
        f1 = -ey / denom  # db_e/dpx
        n0 += f0 * dw[:, e]
        n1 += f1 * dw[:, e]
        m0 += f0 * iw[:, e]
        m1 += f1 * iw[:, e]
    live = width > 0
    row, t_id, col_lo, width = row[live], t_id[live], col_lo[live], width[live]
    n0, n1, m0, m1 = n0[live], n1[live], m0[live], m1[live]
    bounds = _chunk_bounds(width, chunk)
    for a, b in zip(bounds[:-1], bounds[1:]):
        span, kk = _expand(width[a:b])
        span += a
        col = col_lo[span] + kk
        px = col + 0.5
        z = (n0[span] + n1[span] * px) / (m0[span] + m1[span] * px)
        pix = row[span] * res + col
        np.minimum.at(depth, pix, z)
        win = z <= depth[pix]
        ident[pix[win]] = t_id[span[win]]


# ----------------------------------------------------------------------------- light maps


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


def light_map(near: float, far: float, fov: float, light: str | ArrayLike, scheme: str | schemes.Scheme = "Standard", **options: ArrayLike) -> LightMap:
    """Fit the map of a single-map ``scheme`` (Standard, P, LogP, any rule) for one light.

    Parameters
    ----------
    near, far : float
        Eye near and far distances [world units].
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
    sch = schemes.parse(scheme) if isinstance(scheme, str) else scheme
    if sch.k != 1:
        raise ValueError(f"scheme must have a single map (no ZP<k> with k > 1; see light_maps), got {sch.name!r}")
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    res = schemes.evaluate(sch, near, far, fov, lv, **options)
    npr = float(res.n_prime[0, 0])
    verts = geometry.frustum_vertices(near, far, fov)
    basis = geometry.light_space(lv)[0]
    lf = directional.fit(verts, lv)
    wf = directional.warping_frustum(lf, npr if sch.parameterization != "uniform" else np.inf)
    y_off = float((verts @ basis[2]).min())
    param = sch.parameterization if sch.parameterization != "uniform" else "uniform"
    return LightMap(basis, y_off, wf, param, npr if param != "uniform" else float("inf"))


def light_maps(near: float, far: float, fov: float, light: str | ArrayLike, scheme: str = "Standard", **options: ArrayLike) -> tuple[list[LightMap], Array]:
    """The maps of a scheme with k z-partitions (``ZP<k>+…``; k = 1 otherwise) and the split depths.

    Partition i spans [C_i, C_{i+1}] (Lloyd 2006 eqs. 15–16, :func:`aliasing.schemes.z_partitions`)
    and gets its own map fitted to its sub-frustum, as :func:`aliasing.schemes.evaluate` does.

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
    sch = schemes.parse(scheme)
    n_i, f_i = schemes.z_partitions(near, far, sch.k)
    base = schemes.Scheme(name=sch.name, k=1, rule=sch.rule, parameterization=sch.parameterization)
    maps = [light_map(float(a), float(b), fov, light, base, **options) for a, b in zip(n_i, f_i)]
    return maps, np.append(n_i, f_i[-1])


def frame_map(light: ArrayLike, axis: ArrayLike, y0: float, y1: float, a: float, s_lo: float, s_hi: float, parameterization: str) -> LightMap:
    """The map of a warping frustum with an explicit light-plane frame (FPc side faces).

    Y is measured along ``axis`` (⟂ the light) from the origin's projection, X along
    l̂ × axis; the map spans Y ∈ [y0, y1] and its centre of projection is at Y = −a, so
    n′ = y0 + a.  s ∝ X/(Y + a) over [s_lo, s_hi] (X itself when uniform); t is the
    perspective warp of that frustum (Lloyd 2006 eq. 6) or, for ``logperspective``,
    ln((Y + a)/(y0 + a))/ln((y1 + a)/(y0 + a)) (Lloyd 2007 eqs. 77–78), or uniform.

    Parameters
    ----------
    light : array_like, shape (3,)
        Direction towards the light (any length > 0).
    axis : array_like, shape (3,)
        The frame's Y direction, non-zero and ⟂ ``light`` (made unit here).
    y0, y1 : float
        The map's near and far edges along Y [world units], y0 + a > 0, y1 > y0.
    a : float
        Offset of the centre of projection [world units], ≥ 0; ``inf`` for uniform.
    s_lo, s_hi : float
        Range of X/(Y + a) (of X if uniform) the map's s spans, s_lo < s_hi.
    parameterization : {"uniform", "perspective", "logperspective"}

    Returns
    -------
    LightMap

    Example
    -------
    >>> fr = faces.face_frames("fpc", "logperspective", 1.0, 100.0, 60.0, [0.0, 1.0, 0.0])
    >>> i = (0, 0, 0, 0)   # first direction, bottom face, whole face, depth range 0
    >>> lm = frame_map([0.0, 1.0, 0.0], fr.axis[i[:3]], fr.y0[i], fr.y1[i], fr.a[i], fr.s_lo[i], fr.s_hi[i], "logperspective")
    >>> s, t, _, _ = lm.coordinates(geometry.frustum_vertices(1.0, 100.0, 60.0)[[0, 1, 4, 5]])   # the bottom face's corners
    >>> np.round(s, 12).tolist(), np.round(t, 12).tolist()
    ([0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0])
    """
    kind = check.choice(parameterization, "parameterization", faces.FACE_PARAMETERIZATIONS)
    lv = _unit_vector(light, "light")
    ax = check.as_float_array(axis, "axis")
    if ax.shape != (3,) or not np.linalg.norm(ax) > 0 or abs(ax @ lv) > 1e-9 * np.linalg.norm(ax):
        raise ValueError(f"axis must be a non-zero vector (3,) perpendicular to light, got {ax!r}")
    ax = ax / np.linalg.norm(ax)
    lo, hi, lo_s, hi_s = (float(check.as_float_array(v, n)) for v, n in ((y0, "y0"), (y1, "y1"), (s_lo, "s_lo"), (s_hi, "s_hi")))
    off = float(check.as_float_array(a, "a"))
    if not np.isfinite(lo) or not hi > lo or not np.isfinite(hi):
        raise ValueError(f"y0 and y1 must be finite with y1 > y0 [world units], got {lo!r}, {hi!r}")
    if not lo_s < hi_s or not np.isfinite(hi_s - lo_s):
        raise ValueError(f"s_lo and s_hi must be finite with s_lo < s_hi, got {lo_s!r}, {hi_s!r}")
    if kind == "uniform":
        npr = np.inf
    else:
        if not (off >= 0 and np.isfinite(off)) or not lo + off > 0:
            raise ValueError(f"a must be in [0, inf) with y0 + a > 0 (centre of projection behind the map) [world units], got a = {off!r}, y0 = {lo!r}")
        npr = lo + off
    scale = 1.0 if kind == "uniform" else npr
    wf = directional.WarpingFrustum(n_prime=np.array([[npr]]), depth=np.array([[hi - lo]]), x_lo=np.array([[scale * lo_s]]), x_hi=np.array([[scale * hi_s]]))
    return LightMap(np.stack([np.cross(lv, ax), lv, ax]), lo, wf, kind, float(npr))


def near_face_map(near: float, fov: float, light: ArrayLike) -> LightMap:
    """The near face's uniform map (face-fixed, Lloyd 2007 §6.1.3), as a light-plane map.

    A point's (s, t) are those of the point where its light ray meets the near plane, in
    the near face's rectangle: an affine map of the light plane, with light-plane axes
    x_L ∝ l̂ × ŷ (⟂ the face's t-edges) and z_L ∝ x̂ × l̂ (⟂ its s-edges).  The light-beam
    widths along them, 2n tanθ·cos φ_lx and 2n tanθ·cos φ_ly per unit s and t, are the
    analytic model's (m = cos φ_l at the near face, eqs. 55, 58).

    Parameters
    ----------
    near : float
        Eye near distance [world units], > 0.
    fov : float
        Full field of view [deg].
    light : array_like, shape (3,)
        Direction towards the light; not parallel to the near plane (the face is then edge-on).

    Example
    -------
    >>> lm = near_face_map(1.0, 90.0, [0.3, 0.4, -0.8])
    >>> s, t, _, _ = lm.coordinates([[-1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [0.0, 0.0, 1.0]])
    >>> np.round(s, 12).tolist(), np.round(t, 12).tolist()
    ([0.0, 1.0, 0.5], [0.0, 1.0, 0.5])
    """
    n = float(check.positive(near, "near"))
    h = n * np.tan(np.radians(float(check.fov(fov))) / 2)
    lv = _unit_vector(light, "light")
    if abs(lv[2]) < 1e-9:
        raise ValueError(f"light must not be parallel to the near plane (the near face is then edge-on, no map), got {lv!r}")
    x_l = np.cross(lv, [0.0, 1.0, 0.0])
    z_l = np.cross([1.0, 0.0, 0.0], lv)
    x_l, z_l = x_l / np.linalg.norm(x_l), z_l / np.linalg.norm(z_l)
    x_l, z_l = x_l * np.sign(x_l[0]), z_l * np.sign(z_l[1])  # s grows with eye x, t with eye y
    corners = np.array([[-h, -h, n], [h, h, n]])
    x, y = corners @ x_l, corners @ z_l
    wf = directional.WarpingFrustum(n_prime=np.array([[np.inf]]), depth=np.array([[y[1] - y[0]]]), x_lo=np.array([[x[0]]]), x_hi=np.array([[x[1]]]))
    return LightMap(np.stack([x_l, lv, z_l]), float(y[0]), wf, "uniform", float("inf"))


def _unit_vector(value: ArrayLike, name: str) -> Array:
    v = check.as_float_array(value, name)
    if v.shape != (3,) or not np.isfinite(v).all() or not np.linalg.norm(v) > 0:
        raise ValueError(f"{name} must be a finite non-zero vector of shape (3,), got {value!r}")
    return v / np.linalg.norm(v)


@dataclass(frozen=True)
class MapSet:
    """The shadow maps of a scheme for one light, and which map shades which point.

    Attributes
    ----------
    maps : list of LightMap
        One per map the light needs (z-partitions in depth order; for face partitions the
        near face's map first if chosen, then the side faces' in :mod:`aliasing.faces`'
        slot order).
    slots : ndarray of int (len(maps),)
        Each map's column in :func:`aliasing.schemes.evaluate`'s ``M_x``, ``M_z``.
    edges : ndarray (k + 1,)
        Depth split points: z-partitions' C_0 … C_k, or a face's k depth ranges
        (eye depth of the face point a light ray meets) [world units].
    faces : str
        "" (z-partitions), "fpc" or "fpcs".
    near, far, fov : float
        The view frustum [world units, deg].
    light : ndarray (3,)
        Unit vector towards the light.
    frames : FaceFrames or None
        The side faces' frames (:func:`aliasing.faces.face_frames`, for this one light) of
        face partitions; None for z-partitions.
    """

    maps: list[LightMap]
    slots: NDArray[np.int_]
    edges: Array
    faces: str
    near: float
    far: float
    fov: float
    light: Array
    frames: faces.FaceFrames | None = None

    def assign(self, points: ArrayLike) -> NDArray[np.int_]:
        """Index into ``maps`` of the map shading each eye-space point ``(..., 3)`` in the frustum.

        z-partitions: the partition holding the point's eye depth.  Face partitions: the
        chosen face its light ray meets (:func:`aliasing.faces.partition_of`), for FPcs the
        half of that face, and the depth range of the point where the ray meets it.
        """
        p = check.as_float_array(points, "points")
        if p.shape[-1:] != (3,):
            raise ValueError(f"points must have shape (..., 3), got {p.shape}")
        k = self.edges.size - 1
        if not self.faces:
            return np.clip(np.searchsorted(self.edges, p[..., 2], side="right") - 1, 0, k - 1)
        face = faces.partition_of(p, self.near, self.far, self.fov, self.light)
        fr = self.frames
        if fr is None:
            raise ValueError(f"frames must be the face frames of the {self.faces} partitions (see map_set), got None")
        normal, *_ = faces.side_frames(self.fov)
        lv = self.light
        travel = -lv if lv[2] >= 0 else lv  # eq. (54), as in partition_of
        j = np.clip(face - 1, 0, 3)
        nj = normal[j]
        with np.errstate(divide="ignore", invalid="ignore"):
            hit = p - ((p * nj).sum(-1) / (nj @ travel))[..., None] * travel  # on the side face's plane
        rng = np.clip(np.searchsorted(self.edges, hit[..., 2], side="right") - 1, 0, k - 1)
        half = np.zeros(face.shape, int)
        if fr.used.shape[2] == 2:  # FPcs: the side of the split ray (half 0's second edge) holding the point
            split = fr.edges[0, j, 0, 1]  # (..., 3)
            first = fr.edges[0, j, 0, 0]
            side = np.cross(split, p) @ lv
            ref = np.cross(split, first) @ lv
            half = np.where(fr.used[0, j, 1] & (side * ref < 0), 1, 0)
        slot = np.where(face == 0, 0, 1 + (j * fr.used.shape[2] + half) * k + rng)
        lookup = np.full(1 + 4 * fr.used.shape[2] * k, -1)
        lookup[self.slots] = np.arange(len(self.maps))
        return lookup[slot]


def map_set(near: float, far: float, fov: float, light: str | ArrayLike, scheme: str = "Standard", **options: ArrayLike) -> MapSet:
    """The maps of any scheme for one light: single, z-partitioned or face-partitioned.

    ``ZP<k>+…`` and single-map schemes: :func:`light_maps`.  ``FPc+P|LogP|Standard`` and
    ``FPcs+…`` (options ``tau0``, ``tau1``; also with ``+ZP<k>``): the near face's uniform
    map (:func:`near_face_map`) if chosen and each used side-face slot's adjusted frame
    (:func:`aliasing.faces.face_frames`, through :func:`frame_map`) — the same frames
    :func:`aliasing.faces.face_errors` evaluates.  Face-fixed ``FP+…`` (a projective map
    in each side face's own plane) is not built: it raises ``ValueError``.

    Parameters
    ----------
    near, far, fov, light
        The view frustum (0 < near < far [world units], full field of view [deg]) and one
        light direction, as for :func:`light_map`.
    scheme : str
        Any scheme of :mod:`aliasing.schemes` except ``FP+…``.
    **options
        Warping-rule options, or ``tau0``, ``tau1`` for face partitions.

    Example
    -------
    >>> ms = map_set(1.0, 100.0, 60.0, "gamma:60@azimuth:30", "FPc+LogP")
    >>> len(ms.maps), ms.slots.tolist()
    (3, [0, 1, 3])
    >>> ms.assign([[0.0, -20.0, 50.0], [-25.0, 20.0, 50.0], [0.0, 0.0, 1.0]]).tolist()   # bottom, left, near
    [1, 2, 0]
    """
    sch = schemes.parse(scheme) if isinstance(scheme, str) else scheme
    n, f = (float(v) for v in check.frustum(near, far))
    fv = float(check.fov(fov))
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    if not sch.faces:
        maps, edges = light_maps(n, f, fv, lv, sch.name, **options)
        return MapSet(maps, np.arange(len(maps)), edges, "", n, f, fv, lv[0])
    if sch.faces == "fp":
        raise ValueError(f"scheme {sch.name!r}: face-fixed FP maps (projective in each face's plane) are not rasterized; use FPc or FPcs")
    unknown = set(options) - {"tau0", "tau1"}
    if unknown:
        raise ValueError(f"unknown options for {sch.name}: {', '.join(sorted(unknown))}; face partitions take tau0, tau1")
    fr = faces.face_frames(sch.faces, sch.parameterization, n, f, fv, lv, k=sch.k, **{key: float(v) for key, v in options.items()})
    maps, slots = [], []
    if faces.chosen_faces(lv, fv)[0, 0]:
        maps.append(near_face_map(n, fv, lv[0]))
        slots.append(0)
    halves, k = fr.used.shape[2], sch.k
    for j in range(4):  # ≤ 4 faces × 2 halves × k ranges
        for h in range(halves):
            if not fr.used[0, j, h]:
                continue
            for i in range(k):
                c = (0, j, h, i)
                maps.append(frame_map(lv[0], fr.axis[0, j, h], fr.y0[c], fr.y1[c], fr.a[c], fr.s_lo[c], fr.s_hi[c], sch.parameterization))
                slots.append(1 + (j * halves + h) * k + i)
    return MapSet(maps, np.asarray(slots), fr.depth, sch.faces, n, f, fv, lv[0], fr)


def log_row_centres(lm: LightMap, resolution: int) -> Array:
    """Row centres of the log+perspective map, in the perspective map's t (for ``row_centres``).

    Example
    -------
    >>> lm = light_map(1.0, 100.0, 60.0, "overhead", "LogP")
    >>> c = log_row_centres(lm, 4)
    >>> bool((np.diff(c) > 0).all() and 0 < c[0] < c[-1] < 1)
    True
    """
    res = check_resolution(resolution)
    return lm.perspective_t((np.arange(res) + 0.5) / res)


def shadow_map(triangles: ArrayLike, lm: LightMap, resolution: int, *, chunk: int = CHUNK) -> DepthMap:
    """Depth map of eye-space triangles ``(T, 3, 3)`` through the light map ``lm``.

    Depth is the negated height along the light [world units] (smaller = nearer the light),
    exact for planar triangles (perspective-correct); log+perspective maps are rasterized
    logarithmically (module docstring).  For warped maps, triangles are first clipped at
    y = −n′/2 in the light plane (behind the map's near edge y = 0, in front of the warp's
    centre of projection y = −n′); ``triangle`` ids index the input triangles, the counts
    ``rasterized`` and ``degenerate`` the clipped ones.

    Example
    -------
    >>> lm = light_map(1.0, 10.0, 60.0, "overhead", "P")
    >>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    >>> m = shadow_map(ground, lm, 16)
    >>> float(np.unique(m.depth[np.isfinite(m.depth)])[0])   # the ground is 1 below the eye
    1.0
    """
    tri = _triangles(triangles)
    x, y, h = lm.light_plane(tri)
    src = None
    if np.isfinite(lm.n_prime):
        # clip behind the warp's centre of projection (y = −n′); y < 0 is off the map anyway
        lp, src = _clip_near(np.stack([x, h, y], axis=-1), -0.5 * lm.n_prime)
        if lp.shape[0] == 0:
            raise ValueError("triangles lie wholly behind the warping frustum's centre of projection: empty scene for this map")
        x, h, y = lp[..., 0], lp[..., 1], lp[..., 2]
    s, t, w = lm.map_plane(x, y)
    rows = log_row_centres(lm, resolution) if lm.parameterization == "logperspective" and np.isfinite(lm.n_prime) else None
    m = rasterize(np.stack([s, t, -h], axis=-1), resolution, w=w, row_centres=rows, chunk=chunk)
    if src is None:
        return m
    ident = np.where(m.triangle >= 0, src[np.maximum(m.triangle, 0)], -1)
    return DepthMap(m.depth, ident, m.resolution, m.rasterized, m.degenerate)


# ----------------------------------------------------------------------------- eye pass


@dataclass(frozen=True)
class EyeBuffer:
    """What each image pixel sees.

    Attributes
    ----------
    position : ndarray (R, R, 3)
        Visible eye-space point [world units] (ray through the pixel centre ∩ the visible
        triangle's plane); NaN where nothing is visible.  Row j is v = (j + ½)/R (bottom up),
        column i is u = (i + ½)/R (left to right).
    normal : ndarray (R, R, 3)
        Unit face normal of the visible triangle, facing the eye; NaN where empty.
    triangle : ndarray of int64 (R, R)
        Visible triangle index, −1 where empty.
    resolution, fov
        R and the full field of view [deg].
    """

    position: Array
    normal: Array
    triangle: NDArray[np.int64]
    resolution: int
    fov: float


def project(points: ArrayLike, fov: float) -> tuple[Array, Array, Array]:
    """Image coordinates (u, v) ∈ [0, 1]² and depth z of eye-space points (square image).

    u = ½ + x/(2 z tanθ), v = ½ + y/(2 z tanθ), θ = fov/2.
    """
    p = np.asarray(points, float)
    t = np.tan(np.radians(float(check.fov(fov))) / 2)
    z = p[..., 2]
    return 0.5 + p[..., 0] / (2 * z * t), 0.5 + p[..., 1] / (2 * z * t), z


def _clip_near(tri: Array, z_clip: float) -> tuple[Array, NDArray[np.int64]]:
    """Clip triangles to z ≥ z_clip; returns the new triangles and their source indices."""
    behind = tri[:, :, 2] < z_clip
    nb = behind.sum(axis=1)
    keep = tri[nb == 0]
    src = [np.nonzero(nb == 0)[0]]
    out = [keep]
    for count in (1, 2):
        sel = np.nonzero(nb == count)[0]
        if sel.size == 0:
            continue
        t = tri[sel]
        b = behind[sel]
        # rotate corners so that the odd one out (behind if count == 1, in front if 2) is first
        odd = b if count == 1 else ~b
        first = np.argmax(odd, axis=1)
        order = (first[:, None] + np.arange(3)) % 3
        t = np.take_along_axis(t, order[:, :, None], axis=1)
        a, p1, p2 = t[:, 0], t[:, 1], t[:, 2]
        q1 = a + (p1 - a) * ((z_clip - a[:, 2]) / (p1[:, 2] - a[:, 2]))[:, None]
        q2 = a + (p2 - a) * ((z_clip - a[:, 2]) / (p2[:, 2] - a[:, 2]))[:, None]
        if count == 1:  # quad q1, p1, p2, q2
            out += [np.stack([q1, p1, p2], 1), np.stack([q1, p2, q2], 1)]
            src += [sel, sel]
        else:  # triangle a, q1, q2
            out.append(np.stack([a, q1, q2], 1))
            src.append(sel)
    return np.concatenate(out), np.concatenate(src)


def eye_pass(triangles: ArrayLike, fov: float, resolution: int, *, near: float = 1e-3, chunk: int = CHUNK) -> EyeBuffer:
    """Render eye-space triangles with the perspective camera of the conventions.

    The eye is at the origin looking along +z, x right, y up, square image of full field of
    view ``fov`` [deg]; triangles are clipped at z = ``near`` [world units].  Visibility is
    a z-buffer on 1/z (affine in the image for planar triangles); each visible pixel's
    position is recomputed exactly as the intersection of its pixel-centre ray with the
    triangle's plane.  A scene wholly behind the eye gives an empty buffer (all −1 / NaN).

    Example
    -------
    >>> wall = np.array([[[-9, -9, 5], [9, -9, 5], [0, 9, 5]]], float)
    >>> eb = eye_pass(wall, 60.0, 8)
    >>> np.allclose(eb.position[4, 4], [0.5 * 5 * np.tan(np.pi / 6) / 4, 0.5 * 5 * np.tan(np.pi / 6) / 4, 5.0])
    True
    """
    tri = _triangles(triangles)
    res = check_resolution(resolution)
    fv = float(check.fov(fov))
    zc = float(check.positive(near, "near"))
    clipped, src = _clip_near(tri, zc)
    if clipped.shape[0] == 0:
        empty = np.full((res, res, 3), np.nan)
        return EyeBuffer(empty, empty.copy(), np.full((res, res), -1, np.int64), res, fv)
    u, v, z = project(clipped, fv)
    # depth key: -1/z is affine in (u, v) over a plane and increases with z
    dm = rasterize(np.stack([u, v, -1.0 / z], axis=-1), res, chunk=chunk)
    ident = np.where(dm.triangle >= 0, src[np.maximum(dm.triangle, 0)], -1)
    # exact positions: ray through pixel centre ∩ plane of the source triangle
    t = np.tan(np.radians(fv) / 2)
    c = (np.arange(res) + 0.5) / res
    ray = np.stack(np.broadcast_arrays(((2 * c[None, :] - 1) * t), ((2 * c[:, None] - 1) * t), np.ones((res, 1))), axis=-1)
    a, b, cc = tri[:, 0], tri[:, 1], tri[:, 2]
    nrm = np.cross(b - a, cc - a)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    hit = ident >= 0
    n_px = nrm[ident[hit]]
    a_px = a[ident[hit]]
    r_px = ray[hit]
    lam = (n_px * a_px).sum(-1) / (n_px * r_px).sum(-1)
    position = np.full((res, res, 3), np.nan)
    normal = np.full((res, res, 3), np.nan)
    position[hit] = r_px * lam[:, None]
    facing = np.where(((n_px * r_px).sum(-1) > 0)[:, None], -n_px, n_px)
    normal[hit] = facing
    return EyeBuffer(position, normal, ident, res, fv)
