"""The engines' shadow maps, read back and checked texel for texel against the toolkit's rasterizer.

WebGL 2 cannot ``readPixels`` a depth texture.  With ``job["maps"]`` the engine's page draws
each cascade's own depth texture (the one its shadow lookup samples: three.js's
``light.shadow.map.depthTexture``, Babylon.js's depth-stencil texture array of the
``CascadedShadowGenerator``, PlayCanvas's one ``DEPTH_COMPONENT32F`` atlas) through a small pass of ``texelFetch`` into an RGBA32F colour
target and reads that (``pages/common.mjs``, ``readDepthTexture``): the stored depth in
[0, 1] as float32, every ``stride``-th texel in s and t so that at most ``side`` texels per
side come back (a map of 2048² at ``side`` 1024: every second texel).

The toolkit draws the same maps with its own rasterizer (:func:`aliasing.raster.rasterize`)
through the engine's own light matrices, from the faces the engine casts, at the engine's
map size, and stores what the engine stores (:func:`stored_depth`): three.js the window depth;
Babylon.js, with its default depth clamp, the window depth of the casters moved by the normal
bias, plus 1.5 × ``bias``, clamped to [0, 1] (ERRATA F4); PlayCanvas the window depth through the
cascade's palette matrix plus the caster pass's polygon offset (ERRATA F9), each cascade compared
in its own cell of the atlas (:func:`measure_maps`).  The triangles are the float32 ones
the page drew.

The tolerance (:func:`tolerance`) is derived, not fitted: the float32 depth's rounding
(2⁻²⁴) plus SwiftShader's rasterization, which snaps every vertex to 1/2^4 of a texel
(:data:`SUBPIXEL_BITS`; ``SUBPIXEL_PRECISION_BITS`` in SwiftShader's src/Vulkan/VkConfig.hpp is
4 with ``SWIFTSHADER_LEGACY_PRECISION``, else 8, and the maps read back from Debian's Chromium
show 4: their differences reach over 70 % of the 1/32-texel bound): a corner moved by at most 1/32 texel
in s and t moves the depth at any inside point by at most (abs ∂d/∂i + abs ∂d/∂j)/32, with the
depth's derivatives per texel of the triangle drawn there.  Texels on a triangle's edge (a
different nearest triangle in the toolkit's 3 × 3 neighbourhood) are left out: there the
snapped edge decides which triangle covers the texel.

Examples
--------
>>> tri = np.array([[[0, 0, 0.0], [1, 0, 0.0], [0, 1, 1.0]]])   # map space: depth = t
>>> tol = tolerance(tri, np.zeros((4, 4), int))                  # a map of 4 texels: 1/4 of depth per texel in t
>>> bool(np.allclose(tol, 2 ** -24 + 0.25 / 32))
True
"""

from __future__ import annotations

import base64
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

from .. import _validation as check
from . import babylon_cascades, predict
from .lightmaps.depth import SUBPIXEL_BITS, snap

Array = NDArray[np.float64]
FLOAT32_DEPTH = 2.0**-24
MAX_SIDE = 1024


@dataclass(frozen=True)
class EngineMap:
    """One cascade's map as the engine stored it: ``depth`` (n, n) in [0, 1] (row j: t index
    j·stride, column i: s index i·stride; 1 where nothing was drawn), the map's ``size`` R
    [texels] and the ``stride`` of the texels read.

    Parameters
    ----------
    depth : ndarray (n, n)
        The stored depth read back [normalized window depth, 0 … 1], 1 where nothing was drawn.
    size : int
        The map's side R [texels].
    stride : int
        Every ``stride``-th texel was read in s and t [texels].

    Examples
    --------
    >>> m = EngineMap(np.ones((2, 2)), 4, 2)     # a 4 × 4 map, every second texel read back
    >>> m.depth.shape, m.size // m.stride
    ((2, 2), 2)
    """

    depth: Array
    size: int
    stride: int


def decode_maps(out: dict) -> list[EngineMap]:
    """The page's ``maps`` (base64 float32 per cascade) as :class:`EngineMap` s.

    Parameters
    ----------
    out : dict
        The page's answer; ``out["maps"]`` lists per cascade ``side`` [texels read per side],
        ``size`` [texels], ``stride`` [texels] and ``depth`` (base64 float32, side² values
        [normalized window depth]).

    Returns
    -------
    list of EngineMap
        One per cascade.

    Raises
    ------
    ValueError
        The page returned no maps, or a map whose buffer does not match its side.

    Examples
    --------
    >>> d = base64.b64encode(np.array([0.5, 1, 1, 0.25], np.float32).tobytes()).decode()
    >>> m = decode_maps({"maps": [{"side": 2, "size": 4, "stride": 2, "depth": d}]})[0]
    >>> m.depth.tolist(), m.size, m.stride
    ([[0.5, 1.0], [1.0, 0.25]], 4, 2)
    """
    maps = out.get("maps") if isinstance(out, dict) else None
    if not maps:
        raise ValueError("the page returned no shadow maps (job maps not set)")
    res = []
    for m in maps:
        n = int(m["side"])
        d = np.frombuffer(base64.b64decode(m["depth"]), np.float32).astype(float)
        if d.size != n * n:
            raise ValueError(f"a read-back map of {d.size} depths does not match its side {n}")
        res.append(EngineMap(d.reshape(n, n), int(m["size"]), int(m["stride"])))
    return res


def snapped_depth_map(triangles: Array, matrix: Array, size: int, subpixel_bits: int | None = SUBPIXEL_BITS):
    """:func:`aliasing.frames.lightmaps.depth.light_depth_map` with each corner's (s, t) rounded to 1/2^bits of
    a texel first, as a rasterizer with ``subpixel_bits`` of sub-texel precision places it (None: exact).

    Parameters
    ----------
    triangles : array_like (T, 3, 3)
        World triangles [world units].
    matrix : array_like (4, 4)
        World → (s, t, depth) in [0, 1]³ (column vectors).
    size : int
        The map's side [texels], >= 1.
    subpixel_bits : int or None
        Sub-texel precision [bits], in [0, 16]; None: exact corners.

    Returns
    -------
    aliasing.raster.draw.DepthMap
        The depth [normalized window depth] and nearest triangle per texel.

    Examples
    --------
    >>> tri = np.array([[[0.1, 0.1, 0.5], [0.9, 0.1, 0.5], [0.1, 0.9, 0.5]]])
    >>> float(snapped_depth_map(tri, np.eye(4), 8).depth[1, 1])
    0.5
    """
    if subpixel_bits is None:
        return predict.light_depth_map(triangles, matrix, size)
    if not (isinstance(subpixel_bits, (int, np.integer)) and 0 <= subpixel_bits <= 16):
        raise ValueError(f"subpixel_bits must be a whole number in [0, 16] or None, got {subpixel_bits!r}")
    from ..raster.draw import rasterize

    tri = np.asarray(triangles, float)
    if not len(tri):
        return predict.light_depth_map(tri.reshape(0, 3, 3), matrix, size)
    return rasterize(snap(predict.to_map(matrix, tri), int(size), int(subpixel_bits)), int(size))


def gpu_depth_map(triangles: Array, view: Array, projection: Array, size: int, subpixel_bits: int = SUBPIXEL_BITS):
    """three.js's depth pass as a float32 GPU draws it, then the toolkit's rasterizer.

    three.js uploads the caster's ``modelViewMatrix`` (the shadow camera's ``matrixWorldInverse``
    times the mesh's ``matrixWorld``, float64 in JavaScript: ``view``) and the shadow camera's
    ``projectionMatrix`` as float32 uniforms (WebGLShadowMap.js 530), and the vertex shader computes
    ``projectionMatrix * ( modelViewMatrix * vec4( position, 1.0 ) )`` in float32 (project_vertex.glsl.js
    16–18; :func:`aliasing.frames.lightmaps.depth.to_map32`).  The viewport transform places each corner
    at ``round(X0·2^b + x·(R/2)·2^b)`` in 1/2^b texel (SwiftShader's VertexRoutine; ``b`` =
    ``subpixel_bits``, rounded to nearest, ties to even).  The corners are those of a light camera
    that moved by whole texels, but not its float32 translation: a corner within about 10⁻⁴ texel
    of a rounding boundary lands on a different 1/16 step from pose to pose (ERRATA F7).
    Triangles crossing the map's border are not clipped here (the GPU clips them in float32):
    texels on those triangles' clipped edges may differ.

    Parameters
    ----------
    triangles : array_like (T, 3, 3)
        World triangles [world units], taken as float32 (the page's vertex buffer).
    view, projection : array_like (4, 4)
        The uniforms (column vectors), float64: rounded to float32 here.
    size : int
        Texels per side R, in [1, 16384].
    subpixel_bits : int
        In [0, 16].

    Returns
    -------
    aliasing.raster.draw.DepthMap
        Depth as stored: the window depth (clip z + 1)/2 in float32.

    Examples
    --------
    >>> tri = np.array([[[-0.9, -0.9, 0.0], [0.9, -0.9, 0.0], [-0.9, 0.9, 0.0]]])   # clip space through identities
    >>> float(gpu_depth_map(tri, np.eye(4), np.eye(4), 8).depth[1, 1])
    0.5
    """
    tri = np.asarray(triangles, float)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not np.all(np.isfinite(tri)):
        raise ValueError(f"triangles must be finite with shape (T, 3, 3), got shape {tri.shape}")
    mats = []
    for name, m in (("view", view), ("projection", projection)):
        m = np.asarray(m, float)
        if m.shape != (4, 4) or not np.all(np.isfinite(m)):
            raise ValueError(f"{name} must be a finite 4×4 matrix, got shape {m.shape}")
        mats.append(m)
    if not (isinstance(size, (int, np.integer)) and 1 <= size <= 16384):
        raise ValueError(f"size must be a whole number of texels in [1, 16384], got {size!r}")
    if not (isinstance(subpixel_bits, (int, np.integer)) and 0 <= subpixel_bits <= 16):
        raise ValueError(f"subpixel_bits must be a whole number in [0, 16], got {subpixel_bits!r}")
    from ..raster.draw import rasterize

    if not len(tri):
        return predict.light_depth_map(tri.reshape(0, 3, 3), np.eye(4), size)
    clip = predict.to_map32(mats[1], predict.to_map32(mats[0], tri.reshape(-1, 3)))  # orthographic: w = 1 exactly
    half = np.float32(size * 2.0 ** (subpixel_bits - 1))  # X0·2^b = (R/2)·2^b = half
    scale = float(size) * 2.0**subpixel_bits
    clip = clip.astype(np.float32)  # float32 values already: exact
    st = [np.rint(half + clip[:, k] * half).astype(float) / scale for k in (0, 1)]  # float32 sums, then round to even
    z = (clip[:, 2] * np.float32(0.5) + np.float32(0.5)).astype(float)
    return rasterize(np.stack([st[0], st[1], z], -1).reshape(tri.shape), int(size))


def stored_depth(engine: str, settings: dict, triangles: Array, sun: Array, matrix: Array, size: int) -> tuple[Array, NDArray[np.int64], Array]:
    """The toolkit's map of what ``engine`` stores: depth (R, R) (1 where empty), the nearest
    triangle per texel (−1 empty) and the map-space triangles drawn (for :func:`tolerance`).

    ``settings`` are the engine's filled settings (:data:`aliasing.frames.models.MODELS`).

    Parameters
    ----------
    engine : str
        "threejs" or "babylon".
    settings : dict
        The engine's filled settings.
    triangles : array_like (T, 3, 3)
        World triangles [world units] (rounded to float32, as the page drew them).
    sun : array_like (3,)
        World direction towards the sun.
    matrix : array_like (4, 4)
        World → (s, t, depth) in [0, 1]³ (column vectors).
    size : int
        The map's side R [texels], in [1, 16384].

    Returns
    -------
    depth : ndarray (R, R)
        Stored depth [normalized window depth], 1 where empty.
    triangle : ndarray of int (R, R)
        The nearest caster per texel, −1 where empty.
    map_triangles : ndarray (C, 3, 3)
        The casters drawn, in map space (s, t, depth).

    Examples
    --------
    >>> from aliasing.frames.models import MODELS
    >>> floor = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]])   # faces down: a back face casts in three.js
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> depth, tid, mt = stored_depth("threejs", MODELS["threejs"].settings(), floor, [0.0, 1.0, 0.0], m, 4)
    >>> depth[0].tolist(), tid[0].tolist()
    ([0.5, 0.5, 0.5, 1.0], [0, 0, 0, -1])
    """
    check.whole(size, "size", 1, 16384, " [texels]")
    from .models import MODELS

    if engine not in ("threejs", "babylon", "playcanvas"):
        raise ValueError(f"engine must be threejs, babylon or playcanvas for the shadow maps, got {engine!r}")
    model = MODELS[engine]
    tri = np.asarray(triangles, np.float32).astype(float)  # what the page drew
    cast = tri[predict.casting(tri, sun, model.cast_side(settings))]
    if engine == "babylon":
        cast = babylon_cascades.offset_casters(cast, sun, float(settings["normalBias"]))
    dm = predict.light_depth_map(cast, matrix, size)
    depth = np.where(np.isfinite(dm.depth), dm.depth, 1.0)
    if engine == "babylon":  # shadowMapFragment with depth clamp: + bias twice over (ERRATA F4), clamped
        depth = np.clip(depth + 1.5 * float(settings["bias"]), 0.0, 1.0)
    mt = predict.to_map(matrix, cast) if len(cast) else np.zeros((0, 3, 3))
    if engine == "playcanvas" and len(cast):  # the caster pass's polygon offset (ERRATA F9), in the depth buffer's [0, 1]
        off = 10.0 * min(max(float(settings["shadowBias"]), 0.0), 1.0)
        if off:
            depth = np.where(dm.triangle >= 0, np.clip(depth + predict.polygon_offset(mt, size, off, off)[np.maximum(dm.triangle, 0)], 0.0, 1.0), 1.0)
    return depth, dm.triangle, mt


def tolerance(map_triangles: Array, triangle: NDArray[np.int64]) -> Array:
    """Per texel: 2⁻²⁴ + (abs ∂d/∂i + abs ∂d/∂j) / 2^(SUBPIXEL_BITS + 1) of the triangle drawn there
    (``map_triangles``: (T, 3, 3) in map space; ``triangle``: (R, R) indices, −1 empty; the
    derivatives are per texel of the R-texel map).

    Parameters
    ----------
    map_triangles : array_like (T, 3, 3)
        Triangles in map space (s, t, depth) [fraction of the map, normalized window depth].
    triangle : array_like of int (R, R)
        The triangle drawn per texel (an index into ``map_triangles``), −1 where empty.

    Returns
    -------
    ndarray (R, R)
        The tolerance per texel [normalized window depth].

    Examples
    --------
    >>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]])   # a flat caster: float32 alone
    >>> float(tolerance(tri, np.zeros((4, 4), np.int64))[0, 0]) == 2.0**-24
    True
    """
    triangle = np.asarray(triangle)
    if triangle.ndim != 2 or triangle.shape[0] != triangle.shape[1]:
        raise ValueError(f"triangle must be a square (R, R) array of indices, got shape {triangle.shape}")
    mt = check.as_float_array(map_triangles, "map_triangles")
    if len(mt) and (mt.ndim != 3 or mt.shape[1:] != (3, 3)):
        raise ValueError(f"map_triangles must have shape (T, 3, 3), got {mt.shape}")
    if triangle.size and int(triangle.max()) >= len(mt):
        raise ValueError(f"triangle must hold indices in [-1, {len(mt) - 1}] (into map_triangles), got {int(triangle.max())}")
    r = triangle.shape[0]
    t = np.asarray(map_triangles, float)
    if len(t):
        n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        with np.errstate(divide="ignore", invalid="ignore"):
            g = (np.abs(n[:, 0]) + np.abs(n[:, 1])) / np.abs(n[:, 2]) / r
        g = np.where(np.isfinite(g), g, np.inf)
        slope = np.where(triangle >= 0, g[np.maximum(triangle, 0)], 0.0)
    else:
        slope = np.zeros(triangle.shape)
    return FLOAT32_DEPTH + slope / 2.0 ** (SUBPIXEL_BITS + 1)


def compare(engine_map: EngineMap, depth: Array, triangle: NDArray[np.int64], tol: Array, region: NDArray[np.bool_] | None = None) -> dict:
    """One cascade: the engine's map against the toolkit's (full-size ``depth``, ``triangle``, ``tol``).

    ``region`` (R, R), optional: only the texels there count (a cascade's cell of an atlas).

    Returns ``size``, ``stride``, ``texels`` (read back), ``covered`` (drawn in either map),
    ``coverage_agreement`` (fraction of the read texels drawn in both or in neither),
    ``interior`` (covered texels away from triangle edges), ``agreement`` (fraction of those
    within the tolerance), ``max_difference`` (the largest absolute engine − toolkit difference there) and
    ``max_over_tolerance`` (the largest difference over its tolerance).

    Parameters
    ----------
    engine_map : EngineMap
        The engine's read-back map.
    depth : array_like (R, R)
        The toolkit's stored depth [normalized window depth], 1 where empty.
    triangle : array_like of int (R, R)
        The toolkit's nearest triangle per texel, −1 where empty.
    tol : array_like (R, R)
        The tolerance per texel [normalized window depth] (:func:`tolerance`).

    Returns
    -------
    dict
        As above (agreements [fraction of texels], differences [normalized window depth]).

    Examples
    --------
    >>> e = EngineMap(np.array([[0.5, 0.5], [0.5, 1.0]]), 2, 1)
    >>> c = compare(e, np.full((2, 2), 0.5), np.zeros((2, 2), int), np.full((2, 2), 1e-6))
    >>> c["coverage_agreement"], c["interior"], c["agreement"]      # the engine left one texel empty
    (0.75, 4, 0.75)
    """
    if not isinstance(engine_map, EngineMap):
        raise ValueError(f"engine_map must be an EngineMap, got {type(engine_map).__name__}")
    r = engine_map.size
    depth, triangle, tol = np.asarray(depth, float), np.asarray(triangle), np.asarray(tol, float)
    for name, a in (("depth", depth), ("triangle", triangle), ("tol", tol)):
        if a.shape != (r, r):
            raise ValueError(f"{name} must have the map's shape ({r}, {r}), got {a.shape}")
    s = engine_map.stride
    n = engine_map.depth.shape[0]
    if n != -(-r // s) and n != r // s:
        raise ValueError(f"the engine's map of side {n} is not every {s}th texel of {r}")
    p, tid, tt = depth[::s, ::s][:n, :n], triangle, tol[::s, ::s][:n, :n]
    interior_full = ndimage.maximum_filter(tid, 3, mode="nearest") == ndimage.minimum_filter(tid, 3, mode="nearest")
    interior_full &= tid >= 0
    inside = interior_full[::s, ::s][:n, :n]
    e = engine_map.depth
    if region is not None:
        region = np.asarray(region, bool)
        if region.shape != (r, r):
            raise ValueError(f"region must have the map's shape ({r}, {r}), got {region.shape}")
        sub = region[::s, ::s][:n, :n]
        p, tt, inside, e = p[sub], tt[sub], inside[sub], e[sub]
    covered = (e < 1) | (p < 1)
    keep = covered & inside
    diff = np.abs(e - p)
    return {"size": engine_map.size, "stride": s, "texels": int(e.size), "covered": int(covered.sum()),
            "coverage_agreement": float(np.mean((e < 1) == (p < 1))), "interior": int(keep.sum()),
            "agreement": float(np.mean(diff[keep] <= tt[keep])) if keep.any() else None,
            "max_difference": float(diff[keep].max()) if keep.any() else None,
            "max_over_tolerance": float(np.max(diff[keep] / tt[keep])) if keep.any() else None}


def measure_maps(engine: str, settings: dict, triangles: Array, sun: Array, matrices: Array, maps: list[EngineMap]) -> dict:
    """Every cascade's read-back map against the toolkit's: ``cascades`` (per cascade :func:`compare`
    and the light ``matrix`` used, world → [0, 1]³, column vectors), ``agreement`` (the smallest),
    ``max_difference`` (the largest), the ``tolerance`` rule.  PlayCanvas: ``maps`` is its one atlas,
    each cascade compared in its own cell.

    Parameters
    ----------
    engine : str
        "threejs", "babylon" or "playcanvas".
    settings : dict
        The engine's filled settings (:data:`aliasing.frames.models.MODELS`).
    triangles : array_like (T, 3, 3)
        World triangles [world units].
    sun : array_like (3,)
        World direction towards the sun.
    matrices : array_like (k, 4, 4)
        Per cascade: world → (s, t, depth) in [0, 1]³.
    maps : list of EngineMap
        The engine's read-back maps, one per matrix.

    Returns
    -------
    dict
        As above (agreement [fraction of interior texels], max_difference [normalized window depth]).

    Examples
    --------
    >>> from aliasing.frames.models import MODELS
    >>> floor = np.array([[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]])
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])   # s = x, t = z, depth = 0.5 − y
    >>> engine = EngineMap(np.array([[0.5] * 7 + [1.0]] * 8), 8, 1)                   # what the engine might store
    >>> r = measure_maps("threejs", MODELS["threejs"].settings(), floor, [0.0, 1.0, 0.0], [m], [engine])
    >>> r["cascades"][0]["interior"] > 0, r["agreement"], r["max_difference"]
    (True, 1.0, 0.0)
    """
    if not isinstance(maps, (list, tuple)) or not all(isinstance(m, EngineMap) for m in maps):
        raise ValueError("maps must be a list of EngineMap (decode_maps)")
    regions = [None] * len(maps)
    if engine == "playcanvas":  # one atlas: each cascade's cell of it ((x, y, w, h) in [0, 1], the scissor)
        from .models import MODELS

        if len(maps) != 1:
            raise ValueError(f"PlayCanvas draws one shadow atlas, got {len(maps)} maps")
        centre = (np.arange(maps[0].size) + 0.5) / maps[0].size
        cells = MODELS["playcanvas"].cells(settings)
        if len(cells) != len(matrices):
            raise ValueError(f"{len(cells)} atlas cells for {len(matrices)} light matrices")
        regions = [((centre >= y) & (centre < y + h))[:, None] & ((centre >= x) & (centre < x + w))[None, :] for x, y, w, h in cells]
        maps = maps * len(cells)
    if len(maps) != len(matrices):
        raise ValueError(f"{len(maps)} maps for {len(matrices)} light matrices")
    per = []
    for m, mat, region in zip(maps, matrices, regions):
        depth, tid, mt = stored_depth(engine, settings, triangles, sun, mat, m.size)
        per.append({**compare(m, depth, tid, tolerance(mt, tid), region), "matrix": np.asarray(mat, float).tolist()})
    ag = [c["agreement"] for c in per if c["agreement"] is not None]
    mx = [c["max_difference"] for c in per if c["max_difference"] is not None]
    return {"cascades": per, "agreement": min(ag) if ag else None, "max_difference": max(mx) if mx else None,
            "tolerance": f"2^-24 + (|dd/di| + |dd/dj|) / 2^{SUBPIXEL_BITS + 1} per texel (float32 depth, {SUBPIXEL_BITS} subpixel bits)"}


def write_maps(out: Path, maps: list[EngineMap], predicted: list[Array] | None = None) -> list[str]:
    """``map<i>.npy`` (the engine's read-back depths, float32) and ``map<i>.png`` (grey, drawn
    depths stretched to their range, white empty) per cascade in ``out``; the file names.

    Parameters
    ----------
    out : path
        An existing directory.
    maps : list of EngineMap
        The engine's read-back maps.
    predicted : list of ndarray, optional
        Not written (kept for the call's shape).

    Returns
    -------
    list of str
        The names written, two per cascade.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     write_maps(Path(d), [EngineMap(np.array([[0.25, 1.0], [0.5, 0.75]]), 2, 1)])
    ['map0.npy', 'map0.png']
    """
    if not Path(out).is_dir():
        raise ValueError(f"out must be an existing directory, got {str(out)!r}")
    out = Path(out)
    import matplotlib.image

    names = []
    for i, m in enumerate(maps):
        np.save(out / f"map{i}.npy", m.depth.astype(np.float32))
        d = m.depth
        drawn = d < 1
        lo, hi = (float(d[drawn].min()), float(d[drawn].max())) if drawn.any() else (0.0, 1.0)
        g = np.where(drawn, (d - lo) / max(hi - lo, 1e-12) * 0.9, 1.0)[::-1]  # t upward: row 0 at the image's bottom
        matplotlib.image.imsave(out / f"map{i}.png", np.repeat(g[..., None], 3, -1))
        names += [f"map{i}.npy", f"map{i}.png"]
    return names
