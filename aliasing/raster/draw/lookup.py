"""The shadow tests: is a surface point lit through a depth map?

* :func:`shadow_test`, the toolkit's own: it compares a point with the sample its texel
  stores, treating receiver and occluder as locally planar, within a tolerance ``bias``
  [world units] (:data:`BIAS` by default), so a plane never shadows itself; the pictures
  (:mod:`aliasing.pictures`) shade with it;
* :func:`depth_test`, the engines': a plain depth compare with their biases, as real renderers
  do it.  Real engines compare the looked-up point's depth with the depth stored at the
  texel's centre, and fight the resulting self-shadowing (acne) with biases:

  * a constant depth bias along the light [world units];
  * a slope-scaled bias: a factor times the receiver's depth change per texel along the map's
    axes, max(|∂d/∂s|, |∂d/∂t|)/R (Direct3D ``SlopeScaledDepthBias``, OpenGL ``glPolygonOffset``);
  * a normal offset: the looked-up point moved along the receiver's normal [world units];
  * k×k percentage-closer filtering (PCF): taps one texel apart around the point, the lit
    fraction of their nearest-texel tests;
  * receiver-plane depth bias: each PCF tap compares the receiver plane's own depth at the
    tap's position (extrapolated along the plane), not the point's;

* :func:`texel_edges`: the light-plane vectors of one texel's sides at a point, for every map
  (uniform, perspective-warped, logarithmic).

Example
-------
>>> from aliasing.raster.draw import light_map, shadow_map
>>> lm = light_map(1.0, 20.0, 60.0, "overhead", "Standard")
>>> ground = np.array([[[-40, -1, 0.5], [40, -1, 0.5], [0, -1, 60]]], float)
>>> sm = shadow_map(ground, lm, 32)
>>> shadow_test(lm, sm, ground, [[0.0, -1.0, 10.0]], [[0.0, 1.0, 0.0]]).tolist()   # a plane never shadows itself
[True]
>>> float(depth_test(lm, sm, [[0.3, -1.0, 10.2]], [[0.0, 1.0, 0.0]], bias=1.0)[0])   # the engines' test, biased enough
1.0
"""


from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from .core import DepthMap
from .lightmap import LightMap
from .shadow import MapSampler

Array = NDArray[np.float64]

#: Default tolerance of the shadow test's depth comparisons [world units].
BIAS = 1e-3

# Whether :func:`shadow_test` through a gl :class:`MapSampler` compares on the device (the
# tests turn it off to get the host's comparisons of the same texels, their reference).
_ON_DEVICE = True


def _bias(value: float) -> float:
    return float(check.closed_range(value, "bias", 0.0, np.inf, " world units (depth-test tolerance)"))


def shadow_test(lm: LightMap, sm: DepthMap, triangles: ArrayLike, points: ArrayLike, normals: ArrayLike, *, bias: float = BIAS) -> NDArray[np.bool_]:
    """Shadow-map test of surface points: True where lit (not occluded towards the light).

    A texel stores one sample of the surface nearest the light: its depth at the texel's
    centre and its triangle.  Treating the receiver and that occluder as locally planar, a
    point p is lit when any of these holds (each within ``bias``):

    1. p's depth is at most the stored depth (the plain test);
    2. the occluder's plane, met on p's own light ray, is not nearer the light than p
       (e.g. a box face beside the ground it stands on: the ground sampled at the texel
       centre lies below the face at p);
    3. the receiver's plane, met on the ray through the texel's centre (found with the
       map's inverse, :meth:`~aliasing.raster.LightMap.inverse`), is not farther than the
       stored depth (e.g. near a box's convex edge, or a planar receiver, which thus never
       shadows itself: no acne).

    No bias grows with the texel, so occluders of any height cast shadows that touch them
    (no "peter-panning").  What remains is the map's own sampling error: shadow outlines
    are the occluders' footprints on the texel grid, up to a texel out of place.

    Parameters
    ----------
    lm : LightMap
        The map the depth map was rendered through.
    sm : DepthMap or MapSampler
        :func:`aliasing.raster.shadow_map` of ``triangles`` through ``lm``, or a
        :class:`~aliasing.raster.draw.shadow.MapSampler` of them (drawn at the points'
        texels only: the same result).
    triangles : array_like, shape (T, 3, 3)
        The scene [world units], indexed by ``sm.triangle``.
    points, normals : array_like, shape (..., 3)
        Surface points [world units] and their surfaces' normals (any length or sign).
    bias : float
        Tolerance of the three depth comparisons [world units], ≥ 0.

    Returns
    -------
    ndarray of bool, shape (...)
        True where lit; points outside the map count as lit.

    Example
    -------
    >>> from aliasing.raster.draw import light_map, shadow_map
    >>> lm = light_map(1.0, 20.0, 60.0, "gamma:60", "Standard")
    >>> ground = np.array([[[-40, -1, 0.5], [40, -1, 0.5], [0, -1, 60]]], float)
    >>> roof = np.array([[[-1, 0, 4], [1, 0, 4], [0, 0, 6]]], float)   # 1 above the ground
    >>> scene = np.concatenate([ground, roof])
    >>> sm = shadow_map(scene, lm, 64)
    >>> p = np.array([[0.0, -1.0, 15.0], [0.0, 0.0, 5.0], [0.0, -1.0, 4.4]])   # open ground, roof, roof's shadow
    >>> shadow_test(lm, sm, scene, p, [[0, 1, 0]] * 3).tolist()
    [True, True, False]
    """
    tri = np.asarray(triangles, float)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise ValueError(f"triangles must have shape (T, 3, 3), got {tri.shape}")
    p = check.as_float_array(points, "points")
    nrm = check.as_float_array(normals, "normals")
    if p.shape[-1:] != (3,) or nrm.shape != p.shape:
        raise ValueError(f"points and normals must have the same shape (..., 3), got {p.shape} and {nrm.shape}")
    bias = _bias(bias)
    sampled = isinstance(sm, MapSampler)
    if not sampled and not isinstance(sm, DepthMap):
        raise TypeError(f"sm must be a DepthMap or MapSampler, got {type(sm).__name__}")
    if (sampled and len(sm.triangles) > len(tri)) or (not sampled and sm.triangle.size and int(sm.triangle.max()) >= len(tri)):
        raise ValueError("triangles must be the scene of sm (sm names a triangle beyond them)")
    rm = sm.resolution
    s, t, d, _ = lm.coordinates(p)
    inside = (s >= 0) & (s < 1) & (t >= 0) & (t < 1)
    col = np.clip(np.floor(np.nan_to_num(s) * rm), 0, rm - 1).astype(np.int64)
    row = np.clip(np.floor(np.nan_to_num(t) * rm), 0, rm - 1).astype(np.int64)
    if sampled and sm.backend == "gl" and _ON_DEVICE:  # the map stays on the device: the test runs there, one bit per point comes back
        return _device_test(lm, sm, tri, p, nrm, d, inside, row, col, bias)
    if sampled:  # only the texels of points inside the map are drawn (the others count as lit)
        stored, occ = np.full(inside.shape, np.inf), np.full(inside.shape, -1, np.int64)
        stored[inside], occ[inside] = sm.at(row[inside], col[inside])
    else:
        stored, occ = sm.depth[row, col], sm.triangle[row, col]
    up = lm.basis[1]  # towards the light; height along it is −depth
    lit = d <= stored + bias
    # 2. the occluder's plane on p's ray p + λ·up: λ > 0 is nearer the light than p
    a = tri[np.maximum(occ, 0)]
    n_o = np.cross(a[..., 1, :] - a[..., 0, :], a[..., 2, :] - a[..., 0, :])
    across = n_o @ up
    ok = (occ >= 0) & (np.abs(across) > 1e-9 * np.linalg.norm(n_o, axis=-1))
    lam = ((a[..., 0, :] - p) * n_o).sum(-1) / np.where(ok, across, 1.0)
    lit |= ok & (lam <= bias)
    # 3. the receiver's plane on the ray through the texel centre c0 + μ·up (c0 at height 0)
    ok, mu = _receiver(lm, rm, p, nrm, row, col)
    lit |= ok & (-mu <= stored + bias)
    return ~inside | lit


def _receiver(lm: LightMap, rm: int, p: Array, nrm: Array, row: NDArray[np.int64], col: NDArray[np.int64]) -> tuple[NDArray[np.bool_], Array]:
    """:func:`shadow_test`'s third comparison's terms: whether the receiver's plane meets the ray
    through the texel centre c0 + μ·up, and μ (c0 at height 0)."""
    xc, yc = lm.inverse((col + 0.5) / rm, (row + 0.5) / rm)
    c0 = lm.plane_point(xc, yc)
    along = nrm @ lm.basis[1]
    ok = np.abs(along) > 1e-9 * np.linalg.norm(nrm, axis=-1)
    mu = ((p - c0) * nrm).sum(-1) / np.where(ok, along, 1.0)
    return ok, mu


def _device_test(lm: LightMap, sm: MapSampler, tri: Array, p: Array, nrm: Array, d: Array,
                 inside: NDArray[np.bool_], row: NDArray[np.int64], col: NDArray[np.int64], bias: float) -> NDArray[np.bool_]:
    """:func:`shadow_test` through a gl :class:`MapSampler`, its comparisons run on the device.

    The host finds the points' texels, depths and receiver terms (as the host test does, in
    float64); the device reads each texel's sample and compares (:meth:`MapSampler.device_test`:
    the same float64 operations, in the same order, none fused), and one bit per point comes
    back.  The result is the host test's on the same sampler, bit for bit on llvmpipe (checked
    in the tests)."""
    lit = np.ones(inside.shape, bool)
    if not inside.any():
        return lit
    ok, mu = _receiver(lm, sm.resolution, p, nrm, row, col)  # at every point, as the host test (the same arrays: the same doubles)
    points = np.concatenate([p[inside], d[inside][:, None]], axis=-1)
    lit[inside] = sm.device_test(row[inside] * sm.resolution + col[inside], points, np.where(ok, -mu, np.inf)[inside], tri, bias)
    return lit


# ------------------------------------------------------------- the engines' depth compare

#: Largest PCF kernel width [texels].
PCF_MAX = 15


def _points(points: ArrayLike, normals: ArrayLike) -> tuple[Array, Array]:
    p = check.as_float_array(points, "points")
    nrm = check.as_float_array(normals, "normals")
    if p.shape[-1:] != (3,) or nrm.shape != p.shape:
        raise ValueError(f"points and normals must have the same shape (..., 3), got {p.shape} and {nrm.shape}")
    if not (np.isfinite(p).all() and np.isfinite(nrm).all()):
        raise ValueError("points and normals must be finite")
    length = np.linalg.norm(nrm, axis=-1, keepdims=True)
    if (length == 0).any():
        raise ValueError("normals must be non-zero vectors")
    return p, nrm / length


def light_gradient(lm: LightMap, normals: Array) -> tuple[Array, Array]:
    """Gradient of light depth over the light plane, (∂d/∂x, ∂d/∂y), of planes with unit ``normals``, and cos θ.

    θ is the angle between the normal (turned towards the light) and the direction to the light.
    The plane's height along the light is h = −(n_x x + n_y y)/n_up + const, so the depth
    d = −h has gradient (n_x, n_y)/n_up.
    """
    up = lm.basis[1]
    along = normals @ up
    n = np.where((along < 0)[..., None], -normals, normals)
    cos = np.abs(along)
    with np.errstate(divide="ignore", invalid="ignore"):
        grad = np.stack([n @ lm.basis[0], n @ lm.basis[2]], axis=-1) / cos[..., None]
    return grad, cos


def texel_edges(lm: LightMap, resolution: int, points: ArrayLike) -> tuple[Array, Array]:
    """Light-plane vectors (x, y) [world units] of one texel's sides along s and along t, at ``points``.

    The map's Jacobian ∂(x, y)/∂(s, t) at the points' map coordinates (central differences
    of :meth:`~aliasing.raster.LightMap.inverse`), divided by the resolution: for a uniform
    map (w_s, 0) and (0, w_t); a perspective warp shears and scales them with depth; a
    logarithmic map's t side grows with distance from the map's near edge.

    Example
    -------
    >>> from aliasing.raster.draw import light_map
    >>> lm = light_map(1.0, 20.0, 60.0, "overhead", "Standard")
    >>> e_s, e_t = texel_edges(lm, 64, [[0.0, -1.0, 10.0]])
    >>> bool(np.isclose(e_s[0, 1], 0.0) and np.isclose(e_t[0, 0], 0.0) and e_s[0, 0] > 0)
    True
    """
    from .core import check_resolution

    res = check_resolution(resolution)
    p = check.as_float_array(points, "points")
    s, t, _, _ = lm.coordinates(p)
    h = 1e-6
    def at(ds: float, dt: float) -> Array:
        x, y = lm.inverse(s + ds, t + dt)
        return np.stack([x, y], axis=-1)
    e_s = (at(h, 0.0) - at(-h, 0.0)) / (2 * h * res)
    e_t = (at(0.0, h) - at(0.0, -h)) / (2 * h * res)
    return e_s, e_t


def depth_test(lm: LightMap, sm: DepthMap, points: ArrayLike, normals: ArrayLike, *, bias: ArrayLike = 0.0, slope: ArrayLike = 0.0,
               normal_offset: ArrayLike = 0.0, pcf: int = 1, receiver_plane: bool = False) -> Array:
    """A renderer's shadow test: the lit fraction of a k×k PCF lookup with depth bias, slope bias and normal offset.

    The point p is first moved by ``normal_offset`` along its unit normal as given (q = p + o·n;
    engines use the surface's outward normal, which faces the light on lit surfaces).  Each of the k×k taps at q + (i, j) texels of the map, i, j ∈
    {−(k−1)/2 … (k−1)/2}, reads the depth stored in the texel under it (the depth of the
    surface nearest the light on the ray through that texel's centre) and is lit when the
    reference depth is at most the stored depth plus the bias.  The reference depth is q's
    own, or with ``receiver_plane`` the depth at the tap of the plane through q with normal n.
    The bias is ``bias + slope·max(|∂d/∂s|, |∂d/∂t|)/R``: a constant [world units] plus a factor
    times the receiver's depth change per texel along the map's axes.

    Parameters
    ----------
    lm : LightMap
        The map the depth map was rendered through.
    sm : DepthMap or MapSampler
        :func:`aliasing.raster.shadow_map` of the scene through ``lm``, or a
        :class:`~aliasing.raster.draw.shadow.MapSampler` of it (drawn at the taps' texels
        only: the same result).
    points, normals : array_like, shape (..., 3)
        Surface points [world units] and their surfaces' outward normals (any length).
    bias : array_like
        Constant depth bias along the light [world units], ≥ 0, broadcast over the points.
    slope : array_like
        Slope-scaled bias factor [per texel of depth slope], ≥ 0.
    normal_offset : array_like
        Normal offset [world units], ≥ 0.
    pcf : int
        Kernel width k [texels], 1 (nearest) to :data:`PCF_MAX`.
    receiver_plane : bool
        Compare the receiver plane's depth at each tap (receiver-plane depth bias).

    Returns
    -------
    ndarray, shape (...)
        Fraction of the taps that are lit, in [0, 1]; taps outside the map or on empty texels are lit.

    Example
    -------
    >>> from aliasing.raster.draw import light_map, shadow_map
    >>> lm = light_map(1.0, 20.0, 60.0, "gamma:60", "Standard")
    >>> ground = np.array([[[-40, -1, 0.5], [40, -1, 0.5], [0, -1, 60]]], float)
    >>> sm = shadow_map(ground, lm, 32)
    >>> p = np.stack([np.linspace(-2, 2, 50), np.full(50, -1.0), np.linspace(5, 15, 50)], -1)
    >>> acne = depth_test(lm, sm, p, [[0, 1, 0]] * 50) < 1
    >>> bool(acne.any()), bool((depth_test(lm, sm, p, [[0, 1, 0]] * 50, receiver_plane=True, bias=1e-9) == 1).all())
    (True, False)
    """
    check.instance(lm, "lm", LightMap)
    check.instance(sm, "sm", (DepthMap, MapSampler))
    p, n = _points(points, normals)
    k = check.whole(pcf, "pcf", 1, PCF_MAX, " (kernel width [texels])")
    rp = check.flag(receiver_plane, "receiver_plane")
    shape = p.shape[:-1]
    b, sl, off = (np.broadcast_to(check.closed_range(v, name, 0.0, np.inf, unit), shape)
                  for v, name, unit in ((bias, "bias", " world units"), (slope, "slope", " (factor)"), (normal_offset, "normal_offset", " world units")))
    res = sm.resolution
    up = lm.basis[1]
    q = p + off[..., None] * n  # along the normal as given (outward: away from the surface's material)
    s, t, d, _ = lm.coordinates(q)
    grad, cos = light_gradient(lm, n)
    total = b.astype(float)
    if np.any(sl > 0):
        e_s, e_t = texel_edges(lm, res, q)
        per_texel = np.maximum(np.abs((grad * e_s).sum(-1)), np.abs((grad * e_t).sum(-1)))
        total = total + np.where(sl > 0, sl * np.nan_to_num(per_texel, nan=np.inf, posinf=np.inf), 0.0)
    offsets = (np.arange(k) - (k - 1) / 2.0) / res
    lit = np.zeros(shape)
    for di in offsets:  # k² taps, each vectorized over all points
        for dj in offsets:
            st, tt = s + di, t + dj
            inside = (st >= 0) & (st < 1) & (tt >= 0) & (tt < 1)
            col = np.clip(np.floor(np.nan_to_num(st) * res), 0, res - 1).astype(np.int64)
            row = np.clip(np.floor(np.nan_to_num(tt) * res), 0, res - 1).astype(np.int64)
            if isinstance(sm, MapSampler):  # drawn at the taps' texels only (taps outside the map are lit)
                stored = np.full(inside.shape, np.inf)
                stored[inside] = sm.at(row[inside], col[inside])[0]
            else:
                stored = sm.depth[row, col]
            if rp:
                x, y = lm.inverse(st, tt)
                c0 = lm.plane_point(x, y)
                with np.errstate(divide="ignore", invalid="ignore"):
                    ref = -((q - c0) * n).sum(-1) / (n @ up)
            else:
                ref = d
            lit += ~inside | ~np.isfinite(stored) | (ref <= stored + total)
    return lit / (k * k)
