"""The toolkit's prediction of an engine's frame: its own rasterizer, the engine's rules.

For every pixel the engine drew, the toolkit predicts the shadow factor from

* the scene's triangles that the engine's rule lets cast (:func:`casting`: three.js draws the
  back faces of front-sided materials, ``shadowSide`` null; Babylon.js both sides by default);
* a depth map drawn by the toolkit's rasterizer (:func:`aliasing.raster.rasterize`) through
  each cascade's light matrix, at the cascade's map size;
* the engine's cascade selection, bias rule and filter (:func:`threejs_factor`, ...), written
  from the engine's shader source (the pinned package under ``node_modules``).

The light matrices used to draw the predicted maps are the engine's own (read back), so that
the shadow mask and the acne test the rasterizer, faces, bias and filter: the matrices
themselves are predicted separately (the texel footprint, :func:`px_per_texel`).

The reference (what is really lit) is exact: for each pixel, the surface nearest the light in
its texel of a map of *all* faces is compared as a plane at the pixel's own map position
(as :func:`aliasing.raster.draw.lookup.shadow_test` does), so it neither acnes nor peter-pans.

Examples
--------
>>> m = np.eye(4)
>>> tri = np.array([[[0.1, 0.1, 0.5], [0.9, 0.1, 0.5], [0.1, 0.9, 0.5]]])
>>> dm = light_depth_map(tri, m, 8)
>>> float(dm.depth[1, 1]), int(dm.triangle[1, 1])
(0.5, 0)
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from ..raster.draw import DepthMap
from .lightmaps.depth import KEPT, _draw, _mapped, _sampled, light_depth_map, sampled_depth_map, snap, to_map, to_map32  # noqa: F401 - re-exported
from .lightmaps.sampled import SampledMap, TexelArray, gathered, texels  # noqa: F401 - re-exported

Array = NDArray[np.float64]
SIDES = ("front", "back", "double")




def casting(triangles: ArrayLike, sun: ArrayLike, side: str) -> NDArray[np.bool_]:
    """Which triangles are drawn into the shadow map: ``side`` "front", "back" or "double" as seen from the sun.

    A triangle is front-facing to the sun when its right-handed normal (v1 − v0) × (v2 − v0)
    points towards the sun (``sun``: world direction towards it).

    Examples
    --------
    >>> tri = np.array([[[0, 0, 0], [0, 0, 1], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]]], float)   # facing up, down
    >>> casting(tri, [0.0, 1.0, 0.0], "back").tolist(), casting(tri, [0.0, 1.0, 0.0], "double").tolist()
    ([False, True], [True, True])
    """
    if np.shape(triangles)[1:] != (3, 3) or np.ndim(triangles) != 3:
        raise ValueError(f"triangles must have shape (T, 3, 3), got {np.shape(triangles)}")
    if np.shape(sun) != (3,):
        raise ValueError(f"sun must be a 3-vector, got shape {np.shape(sun)}")
    tri = check.finite(triangles, "triangles")
    s = check.finite(sun, "sun")
    side = check.choice(side, "side", SIDES)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    facing = n @ s
    return {"front": facing > 0, "back": facing < 0, "double": facing != 0}[side]



def reference_lit(triangles: Array, matrix: Array, resolution: int, points: Array, normals: Array, sun: Array) -> NDArray[np.bool_]:
    """Exactly lit points: facing the sun and not behind the plane of the surface nearest the light in their texel.

    All faces are drawn; the nearest surface is compared as a plane at the point's own (s, t).
    Points outside the map count as lit.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> reference_lit(roof, m, 4, pts, up, np.array([0.0, 1.0, 0.0])).tolist()
    [False, True]
    """
    if np.shape(points)[-1:] != (3,) or np.shape(normals) != np.shape(points):
        raise ValueError(f"points and normals must have one shape (..., 3), got {np.shape(points)} and {np.shape(normals)}")
    if np.shape(sun) != (3,):
        raise ValueError(f"sun must be a 3-vector, got shape {np.shape(sun)}")
    normals, sun = check.finite(normals, "normals"), check.finite(sun, "sun")
    dm = SampledMap(*_mapped(triangles, matrix, resolution))  # one texel per point: only those drawn (not kept: its table serves the next)
    c = to_map(matrix, points)
    r = dm.resolution
    inside = np.all((c[..., :2] >= 0) & (c[..., :2] < 1), axis=-1)
    col = np.clip(np.floor(np.nan_to_num(c[..., 0]) * r), 0, r - 1).astype(np.int64)
    row = np.clip(np.floor(np.nan_to_num(c[..., 1]) * r), 0, r - 1).astype(np.int64)
    tid = dm.at(row, col)[1]
    mt = dm.mapped if len(dm.mapped) == len(triangles) else to_map(matrix, triangles)  # (T, 3, 3) corners in map space
    a, b, cc = mt[:, 0], mt[:, 1], mt[:, 2]
    nrm = np.cross(b - a, cc - a)  # plane of each triangle in map space
    t = np.maximum(tid, 0)
    nz = nrm[t, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        plane_d = a[t, 2] - (nrm[t, 0] * (c[..., 0] - a[t, 0]) + nrm[t, 1] * (c[..., 1] - a[t, 1])) / nz
    eps = 1e-6
    lit = ~inside | (tid < 0) | ~np.isfinite(plane_d) | (c[..., 2] <= plane_d + eps)
    return lit & ((normals @ sun) > 0)


def _factor_inputs(maps, matrices, cascade, points, normals) -> None:
    """Refuse the factor functions' per-cascade and per-point arrays of mismatched shapes, naming them."""
    mats = check.finite(matrices, "matrices")
    if mats.ndim != 3 or mats.shape[1:] != (4, 4) or len(mats) != len(maps):
        raise ValueError(f"matrices must have shape (k, 4, 4) with one map each (k = {len(maps)}), got {mats.shape}")
    if np.shape(points)[-1:] != (3,) or np.shape(cascade) != np.shape(points)[:-1]:
        raise ValueError(f"points must have shape (..., 3) and cascade (...), got {np.shape(points)} and {np.shape(cascade)}")
    if normals is not None and np.shape(normals) != np.shape(points):
        raise ValueError(f"normals must have the shape of points {np.shape(points)}, got {np.shape(normals)}")


def _ign(x: Array, y: Array) -> Array:
    """three.js's interleaved gradient noise of gl_FragCoord (x, y), in float32 as the shader computes it."""
    f32 = np.float32
    d = x.astype(f32) * f32(0.06711056) + y.astype(f32) * f32(0.00583715)
    return np.mod(f32(52.9829189) * np.mod(d, f32(1.0)), f32(1.0)).astype(float)


def _hardware_pcf(depth: Array, s: Array, t: Array, ref: Array) -> Array:
    """A LINEAR sampler2DShadow lookup (LessEqual compare): the bilinear weights of the 4 nearest texels' results."""
    return _hardware_compare(depth, s, t, ref, strict=False)


def threejs_factor(maps: list[DepthMap], matrices: Array, cascade: NDArray[np.int64], points: Array, normals: Array,
                   frag_x: Array, frag_y: Array, *, bias: float, normal_bias: float, radius: float, map_type: str = "PCFShadowMap",
                   float32: bool = False) -> Array:
    """three.js r187's shadow factor (``getShadow`` of shadowmap_pars_fragment, PCFShadowMap or BasicShadowMap).

    The point moves by ``normal_bias`` along its world normal (shadowmap_vertex), its map depth
    gains ``bias`` (normalized depth), and PCF averages 5 taps of hardware 2×2 PCF on a Vogel
    disk of ``radius`` texels turned by the interleaved gradient noise of the pixel; outside
    [0, 1]² or beyond depth 1 the factor is 1.  ``cascade`` −1: no shadow (factor 1).
    ``float32``: the shadow coordinate as the shader computes it per point in float32
    (:func:`to_map32`; the GPU computes it per vertex and interpolates, with rounding of the same size).

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> maps = [light_depth_map(roof, m, 4)]
    >>> threejs_factor(maps, m[None], np.array([0, 0]), pts, up, np.array([0.5, 1.5]), np.array([0.5, 0.5]),
    ...                bias=0.0, normal_bias=0.0, radius=1.0).tolist()
    [0.0, 1.0]
    """
    if map_type not in ("PCFShadowMap", "BasicShadowMap"):
        raise ValueError(f"map_type must be PCFShadowMap or BasicShadowMap, got {map_type!r}")
    _factor_inputs(maps, matrices, cascade, points, normals)
    for v, n in ((bias, "bias"), (normal_bias, "normal_bias")):
        check.finite(check.scalar(v, n), n)
    if not check.finite(check.scalar(radius, "radius"), "radius") >= 0:
        raise ValueError(f"radius must be in [0, inf) texels, got {radius!r}")
    factor = np.ones(points.shape[:-1])
    for i, (dm, m) in enumerate(zip(maps, matrices)):
        sel = cascade == i
        if not sel.any():
            continue
        q = points[sel] + normal_bias * normals[sel]
        c = to_map32(m, q) if float32 else to_map(m, q)
        z = c[:, 2] + bias
        inside = (c[:, 0] >= 0) & (c[:, 0] <= 1) & (c[:, 1] >= 0) & (c[:, 1] <= 1) & (z <= 1)
        r = dm.resolution
        depth = texels(dm, lambda d, _: np.where(np.isfinite(d), d, 1.0))  # cleared to the far plane
        if map_type == "BasicShadowMap":
            col = np.clip(np.floor(c[:, 0] * r), 0, r - 1).astype(np.int64)
            row = np.clip(np.floor(c[:, 1] * r), 0, r - 1).astype(np.int64)
            f = (z <= depth[row, col]).astype(float)
        else:
            phi = _ign(frag_x[sel], frag_y[sel]) * 2 * np.pi
            f = np.zeros(len(z))
            for k in range(5):
                rr = np.sqrt((k + 0.5) / 5)
                th = k * 2.399963229728653 + phi
                f += _hardware_pcf(depth, c[:, 0] + rr * np.cos(th) * radius / r, c[:, 1] + rr * np.sin(th) * radius / r, z)
            f *= 0.2
        factor[sel] = np.where(inside, f, 1.0)
    return factor


def _weighted_taps(stored: Array, s: Array, t: Array, ref: Array, weights, norm: float) -> Array:
    """Babylon.js's optimized PCF (``shadowsFragmentFunctions``): around the texel corner nearest (s, t), hardware-PCF
    (LINEAR, compare LESS) taps at offsets ``weights(f)`` → (w, o) per axis of the fractional position f, weighted
    w_a·w_b and divided by ``norm``."""
    r = stored.shape[0]
    u, v = s * r + 0.5, t * r + 0.5
    bu, bv = (np.floor(u) - 0.5) / r, (np.floor(v) - 0.5) / r
    (wx, ox), (wy, oy) = weights(u - np.floor(u)), weights(v - np.floor(v))
    out = np.zeros_like(ref)
    for a in range(len(wx)):
        for b in range(len(wy)):
            out += wx[a] * wy[b] * _hardware_compare(stored, bu + ox[a] / r, bv + oy[b] / r, ref, strict=True)
    return out / norm


def _pcf5_weights(f: Array) -> tuple:
    w = (4 - 3 * f, np.full_like(f, 7.0), 1 + 3 * f)
    return w, ((3 - 2 * f) / w[0] - 2, (3 + f) / w[1], f / w[2] + 2)


def _pcf3_weights(f: Array) -> tuple:
    w = (3 - 2 * f, 1 + 2 * f)
    return w, ((2 - f) / w[0] - 1, f / w[1] + 1)


def _babylon_pcf5(stored: Array, s: Array, t: Array, ref: Array) -> Array:
    """Babylon.js's computeShadowWithCSMPCF5 (high quality): 9 hardware-PCF taps with weights /144."""
    return _weighted_taps(stored, s, t, ref, _pcf5_weights, 144.0)


def _babylon_pcf3(stored: Array, s: Array, t: Array, ref: Array) -> Array:
    """Babylon.js's computeShadowWithCSMPCF3 (medium quality): 4 hardware-PCF taps with weights /16."""
    return _weighted_taps(stored, s, t, ref, _pcf3_weights, 16.0)


def _babylon_pcf1(stored: Array, s: Array, t: Array, ref: Array) -> Array:
    """Babylon.js's computeShadowWithCSMPCF1 (low quality): one hardware-PCF (LINEAR, compare LESS) lookup."""
    return _hardware_compare(stored, s, t, ref, strict=True)


BABYLON_PCF = {0: _babylon_pcf5, 1: _babylon_pcf3, 2: _babylon_pcf1}  # filteringQuality: high, medium, low (lightFragment 238–242)


def _hardware_compare(depth: Array, s: Array, t: Array, ref: Array, *, strict: bool) -> Array:
    """A LINEAR shadow-sampler lookup: the bilinear weights of the 4 nearest texels' compares (LESS if strict, else LEQUAL), clamped
    to the edge; ``depth`` rows (t) × columns (s), square or not (Godot's 2 splits: 2048 × 4096)."""
    out = np.zeros_like(ref)
    for j, i, w in bilinear_texels(depth.shape, s, t):
        d = depth[j, i]
        out += w * ((ref < d) if strict else (ref <= d))
    return out


def bilinear_texels(shape: tuple, s: Array, t: Array) -> list:
    """The 4 texels (row, column, weight) a LINEAR lookup at (``s``, ``t``) reads of a ``shape`` (rows, columns) map, clamped
    to the edge (:func:`_hardware_compare`).

    Examples
    --------
    >>> [(j.tolist(), i.tolist(), w.tolist()) for j, i, w in bilinear_texels((4, 4), np.array([0.25]), np.array([0.5]))][:2]
    [([1], [0], [0.25]), ([2], [0], [0.25])]
    """
    rows, cols = shape
    u, v = s * cols - 0.5, t * rows - 0.5
    i0, j0 = np.floor(u), np.floor(v)
    fu, fv = u - i0, v - j0
    out = []
    for di, wu in ((0, 1 - fu), (1, fu)):
        for dj, wv in ((0, 1 - fv), (1, fv)):
            out.append((np.clip(j0 + dj, 0, rows - 1).astype(np.int64), np.clip(i0 + di, 0, cols - 1).astype(np.int64), wu * wv))
    return out


def babylon_factor(maps: list[DepthMap], matrices: Array, cascade: NDArray[np.int64], depth: Array, points: Array, *,
                   ends: Array, lengths: Array, blend_factor: float, bias: float, quality: int = 0) -> Array:
    """Babylon.js 9.35's CSM shadow factor (lightFragment with SHADOWCSM, PCF high quality, depth clamp on).

    The stored depth is the caster's window depth + 1.5 · ``bias`` clamped to [0, 1]
    (shadowMapVertexMetric adds bias·w to clip z, i.e. bias/2 in window depth, and
    shadowMapFragment adds ``bias`` again to the clamped depth); the receiver's depth is its
    window depth clamped to [0, 1 − 2⁻²⁴]; the lookup is that of ``quality`` (``filteringQuality``:
    0 :func:`_babylon_pcf5`, 1 :func:`_babylon_pcf3`, 2 :func:`_babylon_pcf1`); a pixel within
    the last ``1/blend_factor`` of its cascade's length mixes in the next cascade's factor.
    ``cascade`` −1: no shadow (beyond shadowMaxZ).

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> babylon_factor([light_depth_map(roof, m, 4)], m[None], np.array([0, 0]), np.array([5.0, 5.0]), pts,
    ...                ends=np.array([10.0]), lengths=np.array([10.0]), blend_factor=10.0, bias=0.0).tolist()
    [0.0, 1.0]
    """
    _factor_inputs(maps, matrices, cascade, points, None)
    if np.shape(depth) != np.shape(cascade):
        raise ValueError(f"depth must have the shape of cascade {np.shape(cascade)}, got {np.shape(depth)}")
    if np.ndim(ends) != 1 or np.ndim(lengths) != 1 or min(len(ends), len(lengths)) < len(maps) - 1:
        raise ValueError(f"ends and lengths must be 1-d with a value per cascade ({len(maps)}), got shapes {np.shape(ends)} and {np.shape(lengths)}")
    if not check.finite(check.scalar(blend_factor, "blend_factor"), "blend_factor") > 0:
        raise ValueError(f"blend_factor must be in (0, inf), got {blend_factor!r}")
    check.finite(check.scalar(bias, "bias"), "bias")

    def lookup(i: int, sel: NDArray[np.bool_]) -> Array:
        c = to_map(matrices[i], points[sel])
        stored = texels(maps[i], lambda d, _: np.clip(np.where(np.isfinite(d), d, 1.0) + 1.5 * bias, 0.0, 1.0))
        ref = np.clip(c[:, 2], 0.0, 0.99999994)
        return pcf(stored, c[:, 0], c[:, 1], ref)

    if quality not in BABYLON_PCF:
        raise ValueError(f"quality (filteringQuality) must be 0, 1 or 2 (high, medium, low), got {quality!r}")
    pcf = BABYLON_PCF[quality]
    factor = np.ones(points.shape[:-1])
    k = len(maps)
    for i in range(k):
        sel = cascade == i
        if not sel.any():
            continue
        f = lookup(i, sel)
        if i < k - 1:
            ratio = np.clip((ends[i] - depth[sel]) / lengths[i], 0, 1) * blend_factor
            blend = ratio < 1
            if blend.any():
                idx = np.flatnonzero(sel)[blend]
                sub = np.zeros_like(sel)
                sub.flat[idx] = True
                nxt = lookup(i + 1, sub)
                f[blend] = nxt + (f[blend] - nxt) * ratio[blend]  # mix(next, this, ratio)
        factor[sel] = f
    return factor


def polygon_offset(map_triangles: Array, resolution: int, factor: float, units: float, slope: str = "max") -> Array:
    """Per triangle: the rasterizer's polygon offset [window depth], as SwiftShader applies ``glPolygonOffset(factor, units)``.

    ``factor`` · m + ``units`` · r with m = max(|∂z/∂x|, |∂z/∂y|) of the triangle's plane in
    window pixels (``resolution`` texels per map side) and r = 2^(e − 23), e the exponent of its
    largest depth (a 32-bit float depth map; SwiftShader ``src/Pipeline/SetupRoutine.cpp``).
    ``slope`` "length" takes m = √((∂z/∂x)² + (∂z/∂y)²) instead, the OpenGL ES 3.0 definition
    (§3.6.5) that "max" approximates.  ``map_triangles`` (T, 3, 3): corners in map coordinates
    (s, t, depth) in [0, 1].

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5 + 3 / 8], [0.0, 1.0, 0.5 + 4 / 8]]])
    >>> float(polygon_offset(tri, 8, 1.0, 0.0)[0]), float(polygon_offset(tri, 8, 1.0, 0.0, "length")[0])   # ∂z/∂x = 3/64, ∂z/∂y = 4/64
    (0.0625, 0.078125)
    """
    t = check.finite(map_triangles, "map_triangles")
    if t.ndim != 3 or t.shape[1:] != (3, 3):
        raise ValueError(f"map_triangles must have shape (T, 3, 3), got {t.shape}")
    if int(resolution) != resolution or resolution < 1:
        raise ValueError(f"resolution must be a whole number of texels >= 1, got {resolution!r}")
    slope = check.choice(slope, "slope", ("max", "length"))
    scale = np.array([resolution, resolution, 1.0])
    n = np.cross((t[:, 1] - t[:, 0]) * scale, (t[:, 2] - t[:, 0]) * scale)
    with np.errstate(divide="ignore", invalid="ignore"):
        gx, gy = np.abs(n[:, 0]) / np.abs(n[:, 2]), np.abs(n[:, 1]) / np.abs(n[:, 2])
        m = np.maximum(gx, gy) if slope == "max" else np.hypot(gx, gy)
    m = np.where(np.isfinite(m), m, 0.0)
    zmax = np.clip(t[:, :, 2].max(axis=1), 2.0**-126, 1.0)
    r = 2.0 ** (np.floor(np.log2(zmax)) - 23)
    return factor * m + units * r


def playcanvas_atlas(triangles: Array, matrices: Array, cells: Array, resolution: int, shadow_bias: float, slope: str = "max",
                     subpixel_bits: int | None = None, sampled: bool = False) -> Array | TexelArray:
    """PlayCanvas's shadow atlas: each cascade's casters drawn through its palette matrix into its cell, with the polygon offset.

    ``matrices`` (k, 4, 4) map world points to the atlas's (s, t, depth) (the engine's
    ``_shadowMatrixPalette``, its viewport included); ``cells`` (k, 4) each cascade's viewport
    (x, y, w, h) in [0, 1] (the scissor); the stored depth is the window depth plus
    :func:`polygon_offset` with factor and units 10 · clamp(``shadow_bias``, 0, 1)
    (``light.js`` ``_updateShadowBias``: −1000 × the light's −0.01 · shadowBias).
    Empty texels hold the clear depth 1; ``slope``: :func:`polygon_offset`'s.  ``subpixel_bits``: each
    corner's (s, t) first rounded to 1/2^bits of a texel, as a rasterizer with that sub-texel precision
    places it (SwiftShader: 4; None: exact).  Returns the (R, R) depth array; ``sampled``: a :class:`TexelArray`
    of it whose cascades' maps are drawn only where read (:class:`SampledMap`, :func:`gathered`), the same values.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> playcanvas_atlas(roof, m[None], [[0.0, 0.0, 1.0, 1.0]], 4, 0.0)[2].tolist()     # no bias: the window depth
    [0.25, 0.25, 0.25, 0.25]
    >>> float(playcanvas_atlas(roof, m[None], [[0.0, 0.0, 1.0, 1.0]], 4, 0.05)[2, 2] - 0.25) == 0.5 * 2.0**-25   # a flat caster: units · r
    True
    >>> playcanvas_atlas(roof, m[None], [[0.0, 0.0, 1.0, 1.0]], 4, 0.0, sampled=True)[np.array([2, 2]), np.array([0, 3])].tolist()
    [0.25, 0.25]
    """
    r = int(resolution)
    cells = check.finite(cells, "cells")
    mats = check.finite(matrices, "matrices")
    if cells.ndim != 2 or cells.shape[1] != 4 or mats.shape != (len(cells), 4, 4):
        raise ValueError(f"cells must be (k, 4) and matrices (k, 4, 4) for the same k, got {cells.shape} and {mats.shape}")
    if r != resolution or r < 1:
        raise ValueError(f"resolution must be a whole number of texels >= 1, got {resolution!r}")
    if not np.isfinite(shadow_bias):
        raise ValueError(f"shadow_bias must be finite, got {shadow_bias!r}")
    off = 10.0 * min(max(shadow_bias, 0.0), 1.0)
    if subpixel_bits is not None and not (isinstance(subpixel_bits, (int, np.integer)) and 0 <= subpixel_bits <= 16):
        raise ValueError(f"subpixel_bits must be a whole number in [0, 16] or None, got {subpixel_bits!r}")
    parts = []
    for m, cell in zip(mats, cells):
        if subpixel_bits is None or not len(triangles):
            dm = (sampled_depth_map if sampled else light_depth_map)(triangles, m, r)
            mt = to_map(m, triangles) if len(triangles) else None
        else:
            mt = snap(to_map(m, check.finite(triangles, "triangles")), r, subpixel_bits)
            dm = _sampled(mt, r) if sampled else _draw(mt, r)
        bias = polygon_offset(mt, r, off, off, slope) if off and len(triangles) else np.zeros(max(len(triangles), 1))
        parts.append((dm, bias, cell))
    if sampled:
        return TexelArray(_Atlas(parts, r), lambda d, _: d)
    out = np.ones((r, r))
    centre = (np.arange(r) + 0.5) / r
    for dm, bias, (x, y, w, h) in parts:
        d = _offset(dm.depth, dm.triangle, bias)
        cols = (centre >= x) & (centre < x + w)
        rows = (centre >= y) & (centre < y + h)
        cell = rows[:, None] & cols[None, :]
        out[cell] = d[cell]
    return out


def _offset(depth: Array, triangle: NDArray[np.int64], bias: Array) -> Array:
    """The atlas's stored depth: the window depth plus the polygon offset of the texel's triangle, 1 (cleared) where empty."""
    return np.where(triangle >= 0, depth + bias[np.maximum(triangle, 0)], 1.0)


class _Atlas:
    """:func:`playcanvas_atlas`'s texels from its cascades' sampled maps (``parts``: map, polygon offsets, cell), drawn where read."""

    def __init__(self, parts: list, resolution: int) -> None:
        self.parts = parts
        self.resolution = resolution
        centre = (np.arange(resolution) + 0.5) / resolution  # the texel centres, as the whole atlas's
        # per column and per row: a bit for each cell whose columns (rows) hold it
        self._cols = sum(((centre >= x) & (centre < x + w)).astype(np.int64) << i for i, (_, _, (x, _, w, _)) in enumerate(parts))
        self._rows = sum(((centre >= y) & (centre < y + h)).astype(np.int64) << i for i, (_, _, (_, y, _, h)) in enumerate(parts))

    def sampled_maps(self) -> list:
        """The cascades' sampled maps, for :func:`aliasing.frames.lightmaps.sampled.gathered`."""
        return [dm for dm, _, _ in self.parts if isinstance(dm, SampledMap)]

    def at(self, row: NDArray[np.int64], col: NDArray[np.int64]) -> tuple[Array, NDArray[np.int64]]:
        out = np.ones(row.shape)
        cells = self._cols[col] & self._rows[row]
        for i, (dm, bias, _) in enumerate(self.parts):
            cell = (cells >> i) == 1  # in cell i and in no later one (a later cell is drawn over it)
            if cell.any():
                out[cell] = _offset(*dm.at(row[cell], col[cell]), bias)
        return out, np.full(row.shape, -1, np.int64)


def _playcanvas_pcf3(stored: Array, s: Array, t: Array, ref: Array) -> Array:
    """PlayCanvas's ``_getShadowPCF3x3``: 4 hardware-PCF (LINEAR, compare LESS) taps with weights /16."""
    r = stored.shape[0]
    u, v = s * r, t * r
    bu, bv = np.floor(u + 0.5), np.floor(v + 0.5)
    ss, tt = u + 0.5 - bu, v + 0.5 - bv
    bu, bv = (bu - 0.5) / r, (bv - 0.5) / r
    uw = (3 - 2 * ss, 1 + 2 * ss)
    uo = ((2 - ss) / uw[0] - 1, ss / uw[1] + 1)
    vw = (3 - 2 * tt, 1 + 2 * tt)
    vo = ((2 - tt) / vw[0] - 1, tt / vw[1] + 1)
    out = np.zeros_like(ref)
    for a in range(2):
        for b in range(2):
            out += uw[a] * vw[b] * _hardware_compare(stored, uo[a] / r + bu, vo[b] / r + bv, ref, strict=True)
    return out / 16.0


def playcanvas_factor(atlas: Array, matrices: Array, cascade: NDArray[np.int64], points: Array, normals: Array, *,
                      normal_offset: float, taps: int = 3) -> Array:
    """PlayCanvas 2.23.3's directional shadow factor (``getShadow`` with a PCF map, ``lightFunctionShadow``).

    The point moves by ``normal_offset`` along its world normal (``SHADOW_SAMPLE_NORMAL_OFFSET``
    with ``SHADOW_SAMPLE_SOURCE_ZBUFFER``: no n·l factor), its map depth is
    ``saturate(z) − 0.0001`` (``SHADOW_SAMPLE_ORTHO``), and ``taps`` 1, 3 or 5 picks
    ``getShadowPCF1x1`` (one hardware comparison), ``PCF3x3`` (4 taps /16) or ``PCF5x5`` (9 taps
    /144, Castaño's weights as Babylon.js's), all LESS comparisons of the whole atlas (a tap
    can read a neighbouring cell).  ``cascade`` −1: no shadow (factor 1).

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> atlas = playcanvas_atlas(roof, m[None], [[0.0, 0.0, 1.0, 1.0]], 4, 0.0)
    >>> playcanvas_factor(atlas, m[None], np.array([0, 0]), pts, up, normal_offset=0.0).tolist()
    [0.0, 1.0]
    """
    if taps not in (1, 3, 5):
        raise ValueError(f"taps must be 1, 3 or 5, got {taps!r}")
    shape = atlas.shape if isinstance(atlas, TexelArray) else np.shape(atlas)
    if len(shape) != 2 or shape[0] != shape[1]:
        raise ValueError(f"atlas must be a square (R, R) array, got shape {shape}")
    check.finite(matrices, "matrices")
    if np.shape(matrices)[1:] != (4, 4) or np.ndim(matrices) != 3:
        raise ValueError(f"matrices must have shape (k, 4, 4), got {np.shape(matrices)}")
    if np.shape(points)[-1:] != (3,) or np.shape(normals) != np.shape(points) or np.shape(cascade) != np.shape(points)[:-1]:
        raise ValueError(f"points and normals must be (..., 3) with cascade (...), got {np.shape(points)}, {np.shape(normals)} and {np.shape(cascade)}")
    check.finite(check.scalar(normal_offset, "normal_offset"), "normal_offset")
    factor = np.ones(points.shape[:-1])
    for i, m in enumerate(matrices):
        sel = cascade == i
        if not sel.any():
            continue
        q = points[sel] + normal_offset * normals[sel] if normal_offset else points[sel]
        c = to_map(m, q)
        z = np.clip(c[:, 2], 0.0, 1.0) - 0.0001
        if taps == 1:
            f = _hardware_compare(atlas, c[:, 0], c[:, 1], z, strict=True)
        elif taps == 3:
            f = _playcanvas_pcf3(atlas, c[:, 0], c[:, 1], z)
        elif taps == 5:
            f = np.clip(_babylon_pcf5(atlas, c[:, 0], c[:, 1], z), 0.0, 1.0)
        else:
            raise ValueError(f"taps must be 1, 3 or 5, got {taps!r}")
        factor[sel] = f
    return factor


# ----------------------------------------------------------------------------- what every engine model shares

@dataclass(frozen=True)
class Prediction:
    """Per pixel: the predicted ``factor`` and ``cascade``; per cascade: ``starts`` [world units] and map ``sides`` [world units].

    Examples
    --------
    >>> p = Prediction(np.ones((1, 1)), np.zeros((1, 1), np.int64), np.array([0.5]), np.array([10.0]), np.array([1024.0]))
    >>> float(p.sides[0] / p.resolution[0])   # the texel [world units]
    0.009765625
    """

    factor: Array
    cascade: NDArray[np.int64]
    starts: Array
    sides: Array
    resolution: Array
    matrices: Array | None = None  # per cascade, the predicted world → [0, 1]³ matrices, where the model predicts them whole


#: The read-back ``info`` key of a digest of its pixels (``drawn``, ``position``, ``normal``) and the scene's triangles, set by a
#: caller that measures the same pixels many times (:func:`aliasing.frames.seen.count`): :func:`reference` then keys its memo by
#: it instead of digesting those arrays again.
GEOMETRY_KEY = "geometry_digest"


def geometry_digest(drawn: Array, position: Array, normal: Array, triangles: Array) -> bytes:
    """The digest :func:`reference` takes for the pixels and scene under :data:`GEOMETRY_KEY`.

    Examples
    --------
    >>> a = np.zeros((1, 2, 3)); tri = np.zeros((1, 3, 3))
    >>> geometry_digest(np.ones((1, 2), bool), a, a, tri) == geometry_digest(np.ones((1, 2), bool), a, a, tri), len(geometry_digest(np.ones((1, 2), bool), a, a, tri))
    (True, 16)
    """
    digest = hashlib.blake2b(digest_size=16)
    for a in (drawn, position, normal, triangles):
        digest.update(np.ascontiguousarray(a).tobytes())
    return digest.digest()


def reference(scene, sun: Array, rb, resolution: int) -> NDArray[np.bool_]:
    """The exact reference's lit pixels, through the matrix of the cascade each pixel sampled (the last one where none).

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> from types import SimpleNamespace
    >>> from aliasing.frames.readback import Readback
    >>> rb = Readback("threejs", "187", np.ones((1, 2)), np.zeros((1, 2), np.int64), pts[None], up[None], m[None], np.full((1, 2), 4), {}, b"")
    >>> reference(SimpleNamespace(triangles=roof), np.array([0.0, 1.0, 0.0]), rb, 4).tolist()
    [[False, True]]
    """
    check.whole(resolution, "resolution", 1, 16384, " [texels]")
    kept, key = KEPT["maps"], None
    if kept is not None:  # a search that moves only biases or filters asks again for the same matrices, cascades and pixels
        digest = hashlib.blake2b(digest_size=16)
        geometry = rb.info.get(GEOMETRY_KEY) if isinstance(rb.info, dict) else None  # the pixels and scene, digested once by their owner
        for a in (rb.matrices, rb.cascade, sun) + (() if geometry else (rb.drawn, rb.position, rb.normal, scene.triangles)):
            digest.update(np.ascontiguousarray(a).tobytes())
        digest.update(geometry or b"")
        key = ("reference", digest.digest(), int(resolution))
        try:
            return kept[key].copy()
        except KeyError:  # not found yet (or dropped)
            pass
    pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
    ref = np.ones(rb.shadow.shape, bool)
    for i, m in enumerate(rb.matrices):
        here = rb.drawn & ((rb.cascade == i) | ((rb.cascade < 0) & (i == len(rb.matrices) - 1)))
        if here.any():
            ref[here] = reference_lit(scene.triangles, m, resolution, pts[here], nrm[here], sun)
    ref &= rb.drawn & ((nrm @ sun) > 0)
    if key is not None:
        kept[key] = ref.copy()
    return ref
