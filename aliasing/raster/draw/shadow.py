"""Shadow maps: eye-space triangles rasterized through a light map, logarithmically for LogP.

:func:`log_row_centres` gives the texel centres of the log map mapped back into the
perspective map's t (the inverse of eq. 84), and rasterizing there with the straight edge
equations of the perspective map is logarithmic rasterization (Lloyd 2007 §6.3): the
bounding box is found in warped space and each candidate centre is tested against the
triangle's straight edges.

Maps drawn where they are looked up
-----------------------------------
A shadow test of P points reads P texels of a map; an engine-sized map has millions.
:class:`MapSampler` holds a map's scene and light map and gives the depth and triangle of
just the texels asked (:meth:`MapSampler.at`), keeping those it has found for the next
question.  Its memory and work grow with the texels asked, not with the map's R²:

* ``backend="numpy"`` rasterizes only the rows that hold an asked texel, and along each
  (triangle, row) span only the asked texels (:func:`.core.zbuffer_at`): the same
  per-span formulas and tie rule as :func:`shadow_map`, so every value is the whole map's,
  bit for bit;
* ``backend="gl"`` draws the map on the device, over the box of the texels asked (grown
  and drawn again if later texels fall outside it), and keeps it there
  (:class:`.resident.DeviceMap`); a compute pass evaluates the asked texels' depths there,
  and only they come back (:func:`shadow_map`'s gl values: depth within
  ``gl.DEPTH_ERROR`` of the scene's depth range, visible triangles up to the hardware's
  snapping of edges).  Log+perspective maps have no matrix and are sampled by numpy.
  :func:`aliasing.raster.draw.shadow_test` through a gl sampler runs its comparisons there
  too (:meth:`MapSampler.device_test`): only one bit per point comes back.

:func:`aliasing.raster.draw.shadow_test` accepts a sampler where it accepts a
:class:`~aliasing.raster.draw.DepthMap`.

Example
-------
>>> from aliasing.raster.draw import light_map
>>> lm = light_map(1.0, 10.0, 60.0, "overhead", "LogP")
>>> m = shadow_map(np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float), lm, 16)
>>> m.resolution, bool(np.isfinite(m.depth).any())
(16, True)
>>> lm = light_map(1.0, 10.0, 60.0, "overhead", "P")
>>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
>>> ms = MapSampler(ground, lm, 2048)              # nothing drawn yet
>>> d, i = ms.at(np.array([1000, 5]), np.array([1024, 7]))
>>> full = shadow_map(ground, lm, 2048)
>>> bool((d == full.depth[[1000, 5], [1024, 7]]).all() and (i == full.triangle[[1000, 5], [1024, 7]]).all()), ms.texels
(True, 2)
"""

from __future__ import annotations

import weakref

import numpy as np
from numpy.typing import ArrayLike, NDArray

from typing import Sequence

from ... import _validation as check
from . import backends, gl
from . import resident
from .core import CHUNK, DepthMap, _triangles, check_chunk, check_resolution, clip_near, TexelStore, rasterize, texel_indices, weights_and_rows, zbuffer_at
from .facemaps import MapSet
from .lightmap import LightMap, light_map

Array = NDArray[np.float64]


def log_row_centres(lm: LightMap, resolution: int) -> Array:
    """Row centres of the log+perspective map, in the perspective map's t (for ``row_centres``).

    Example
    -------
    >>> lm = light_map(1.0, 100.0, 60.0, "overhead", "LogP")
    >>> c = log_row_centres(lm, 4)
    >>> bool((np.diff(c) > 0).all() and 0 < c[0] < c[-1] < 1)
    True
    """
    check.instance(lm, "lm", LightMap)
    res = check_resolution(resolution)
    return lm.perspective_t((np.arange(res) + 0.5) / res)


def shadow_map(triangles: ArrayLike, lm: LightMap, resolution: int, *, chunk: int = CHUNK, backend: str = "numpy") -> DepthMap:
    """Depth map of eye-space triangles ``(T, 3, 3)`` through the light map ``lm``.

    Depth is the negated height along the light [world units] (smaller = nearer the light),
    exact for planar triangles (perspective-correct); log+perspective maps are rasterized
    logarithmically (module docstring).  For warped maps, triangles are first clipped at
    y = −n′/2 in the light plane (behind the map's near edge y = 0, in front of the warp's
    centre of projection y = −n′); ``triangle`` ids index the input triangles, the counts
    ``rasterized`` and ``degenerate`` the clipped ones.

    ``backend="gl"`` draws the map with OpenGL (:mod:`.gl`, the optional ``gl`` extra) through
    its 4×4 matrix (:meth:`LightMap.matrix`): the same depth (computed per texel centre from
    the visible triangle's plane in double precision, stored as float32: within
    ``gl.DEPTH_ERROR`` of the scene's depth range) and the same visible triangles up to
    the hardware's sub-texel snapping of edges; there ``rasterized`` counts the finite
    triangles sent and ``degenerate`` the non-finite ones, and a scene wholly behind the
    warp's centre of projection gives an empty map (numpy: a ``ValueError``).  The map stays
    on the device until ``depth`` or ``triangle`` is first read (:mod:`.resident`); a map
    bigger than the device allows is refused in one line before any work.
    Log+perspective maps have no matrix: they are rasterized by numpy whichever backend is
    asked.

    Example
    -------
    >>> lm = light_map(1.0, 10.0, 60.0, "overhead", "P")
    >>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    >>> m = shadow_map(ground, lm, 16)
    >>> float(np.unique(m.depth[np.isfinite(m.depth)])[0])   # the ground is 1 below the eye
    1.0
    """
    tri = _triangles(triangles)
    check.instance(lm, "lm", LightMap)
    res = check_resolution(resolution)
    chunk = check_chunk(chunk)
    if backends.check(backend, "shadow_map") == "gl" and not _logarithmic(lm):
        resident.check_size(res)  # before any work
        return _gl_maps(tri, [lm], [res])[0]
    return _numpy_map(tri, lm, res, chunk)


def _logarithmic(lm: LightMap) -> bool:
    return lm.parameterization == "logperspective" and np.isfinite(lm.n_prime)


def _gl_maps(tri: Array, maps: Sequence[LightMap], resolutions: Sequence[int]) -> list[DepthMap]:
    """Projective maps drawn on the device (:func:`.resident.draw_device_maps`, the triangles
    uploaded once), kept there until their arrays are asked for (:class:`_DeviceDepthMap`)."""
    drawn, skipped = resident.draw_device_maps(tri, [lm.matrix() for lm in maps], resolutions)
    return [_DeviceDepthMap(m, tri.shape[0] - skipped, skipped) for m in drawn]


class _DeviceDepthMap(DepthMap):
    """A gl :class:`DepthMap` whose ``depth`` and ``triangle`` stay on the device until one of
    them is read (:meth:`.resident.DeviceMap.read`, which frees the device map), or until the
    device needs the room (then they are read back first)."""

    def __init__(self, device: resident.DeviceMap, rasterized: int, degenerate: int) -> None:
        for name, value in (("_device", device), ("_arrays", None), ("resolution", device.resolution), ("rasterized", rasterized), ("degenerate", degenerate)):
            object.__setattr__(self, name, value)
        device.on_evict = weakref.WeakMethod(self._load)

    def _load(self) -> tuple[Array, NDArray[np.int64]]:
        if self._arrays is None:
            object.__setattr__(self, "_arrays", self._device.read())
            self._device.release()
        return self._arrays

    @property
    def depth(self) -> Array:  # type: ignore[override]
        return self._load()[0]

    @property
    def triangle(self) -> NDArray[np.int64]:  # type: ignore[override]
        return self._load()[1]


def _numpy_map(tri: Array, lm: LightMap, resolution: int, chunk: int) -> DepthMap:
    mapped, w, rows, src = map_triangles(tri, lm, resolution)
    m = rasterize(mapped, resolution, w=w, row_centres=rows, chunk=chunk)
    if src is None:
        return m
    ident = np.where(m.triangle >= 0, src[np.maximum(m.triangle, 0)], -1)
    return DepthMap(m.depth, ident, m.resolution, m.rasterized, m.degenerate)


def map_triangles(tri: Array, lm: LightMap, resolution: int) -> tuple[Array, Array, Array | None, NDArray[np.int64] | None]:
    """The numpy rasterizer's input for map ``lm``: (s, t, depth) triangles, their weights w,
    the row centres (log maps; None: uniform) and each triangle's source index (None: unclipped)."""
    x, y, h = lm.light_plane(tri)
    src = None
    if np.isfinite(lm.n_prime):
        # clip behind the warp's centre of projection (y = −n′); y < 0 is off the map anyway
        lp, src = clip_near(np.stack([x, h, y], axis=-1), -0.5 * lm.n_prime)
        if lp.shape[0] == 0:
            raise ValueError("triangles lie wholly behind the warping frustum's centre of projection: empty scene for this map")
        x, h, y = lp[..., 0], lp[..., 1], lp[..., 2]
    s, t, w = lm.map_plane(x, y)
    rows = log_row_centres(lm, resolution) if lm.parameterization == "logperspective" and np.isfinite(lm.n_prime) else None
    return np.stack([s, t, -h], axis=-1), w, rows, src



def shadow_maps(triangles: ArrayLike, maps: MapSet | Sequence[LightMap], resolution: int | Sequence[int], *, chunk: int = CHUNK, backend: str = "numpy") -> list[DepthMap]:
    """Depth maps of eye-space triangles through every map of a set: :func:`shadow_map` per map.

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Eye-space triangles [world units].
    maps : MapSet or sequence of LightMap
        A scheme's maps (:func:`aliasing.raster.map_set`; cascades:
        ``cascade_set(...).maps``; face partitions), or a list of light maps.
    resolution : int or sequence of int
        Texels per side of every map, or of each map (e.g. :func:`aliasing.raster.draw.cascades.budget_shares`).
    chunk : int
        Rows, or texels, per vectorized step of the numpy rasterizer.
    backend : {"numpy", "gl"}
        ``"gl"`` uploads the triangles once and draws each projective map with its matrix
        (:func:`shadow_map`); log+perspective maps are drawn by numpy.

    Returns
    -------
    list of DepthMap
        One per map, in the set's order.

    Example
    -------
    >>> from aliasing import raster
    >>> ms = raster.map_set(1.0, 10.0, 60.0, "gamma:60", "ZP2+P")
    >>> ground = np.array([[[-20, -1, 0.5], [20, -1, 0.5], [0, -1, 30]]], float)
    >>> [m.resolution for m in shadow_maps(ground, ms, [16, 8])]
    [16, 8]
    """
    tri = _triangles(triangles)
    try:
        lms = list(maps.maps) if isinstance(maps, MapSet) else list(maps)
    except TypeError:
        raise ValueError(f"maps must be a MapSet or a list of LightMap, got {type(maps).__name__}") from None
    if not lms:
        raise ValueError("maps must hold at least one LightMap")
    for lm in lms:
        check.instance(lm, "maps", LightMap)
    if isinstance(resolution, (list, tuple, np.ndarray)):
        if len(resolution) != len(lms):
            raise ValueError(f"resolution must be one whole number or one per map ({len(lms)}), got {len(resolution)}")
        rs = [check_resolution(r) for r in resolution]
    else:
        rs = [check_resolution(resolution)] * len(lms)
    chunk = check_chunk(chunk)
    out: list[DepthMap | None] = [None] * len(lms)
    if backends.check(backend, "shadow_map") == "gl":
        todo = [i for i, lm in enumerate(lms) if not _logarithmic(lm)]
        for i in todo:
            resident.check_size(rs[i])  # every map before any work
        if todo:
            for i, m in zip(todo, _gl_maps(tri, [lms[i] for i in todo], [rs[i] for i in todo])):
                out[i] = m
    for i, lm in enumerate(lms):
        if out[i] is None:
            out[i] = _numpy_map(tri, lm, rs[i], chunk)
    return out


# ------------------------------------------------------------- maps drawn where they are looked up

#: Pairs, or texels, per vectorized step of the sampled rasterizer (temporaries ≈ 250 bytes
#: per (triangle, row) pair: about 65 MB).
SAMPLE_CHUNK = 1 << 18


class MapSampler:
    """A depth map of ``triangles`` through ``lm`` at ``resolution``, drawn where it is looked up.

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Eye-space (or world) triangles [world units], as for :func:`aliasing.raster.shadow_map`.
    lm : LightMap
        The map.
    resolution : int
        R, texels per side, in [1, :data:`aliasing.raster.draw.MAX_RESOLUTION`].
    backend : {"numpy", "gl"}
        numpy: only the asked texels are rasterized; gl: the map is drawn on the device once
        and the asked texels are fetched there (module docstring).
    chunk : int
        Pairs, or texels, per vectorized step of the numpy path.

    Attributes
    ----------
    texels : int
        Texels found so far (and kept).
    """

    def __init__(self, triangles: ArrayLike, lm: LightMap, resolution: int, *, backend: str = "numpy", chunk: int = SAMPLE_CHUNK) -> None:
        self.triangles = _triangles(triangles)
        check.instance(lm, "lm", LightMap)
        self.lm = lm
        self.resolution = check_resolution(resolution)
        self.chunk = check_chunk(chunk)
        name = backends.check(backend, "shadow_map")
        self.backend = "numpy" if name == "gl" and _logarithmic(lm) else name
        if self.backend == "gl":
            resident.check_size(self.resolution)
        self._kept = TexelStore()
        self._prepared: tuple | None = None
        self._device: resident.DeviceMap | None = None
        self._planes: tuple | None = None  # (the scene, its plane rows) of device_test

    @property
    def texels(self) -> int:
        return len(self._kept)

    def at(self, row: ArrayLike, col: ArrayLike) -> tuple[Array, NDArray[np.int64]]:
        """Depth [the map's depth units; ``inf`` where empty] and visible triangle (−1 where
        empty) of texels (``row``, ``col``), whole numbers in [0, R) of any one shape."""
        flat = texel_indices(row, col, self.resolution)
        missing = self._kept.missing(flat)
        if missing.size:
            self._kept.add(missing, *self._draw(missing))
        return self._kept.get(flat)

    def _drawn(self, texels: NDArray[np.int64]) -> resident.DeviceMap:
        """The device map (gl), drawn (again) over a box that holds ``texels`` if it does not."""
        if self._device is None or self._device.released or not self._device.covers(texels):
            box = _box(texels, self.resolution)
            if self._device is not None and not self._device.released:  # grow the drawn box to hold the new texels
                x, y, w, h = self._device.box
                box = _union(box, (x, y, w, h))
                self._device.release()
            self._device = resident.draw_device_map(self.triangles, self.lm.matrix(), self.resolution, box=box)
        return self._device

    def device_test(self, texels: NDArray[np.int64], points: Array, receiver: Array, triangles: Array, bias: float) -> NDArray[np.bool_]:
        """:func:`aliasing.raster.draw.shadow_test` of points in the map, run on the device (gl).

        ``texels`` (P,) the points' flat texel indices (row·R + column), ``points`` (P, 4) their
        positions [world units] and depths [the map's depth units], ``receiver`` (P,) the
        test's receiver term (+inf where unusable), ``triangles`` the test's scene (its planes
        are computed once per scene array and kept: change a scene in place and they are
        stale; pass a new array), ``bias`` [world units].  The map stays on the device
        and only one bit per point comes back (:meth:`.resident.DeviceMap.test`)."""
        if self.backend != "gl":
            raise ValueError(f"device_test needs a sampler drawn by the gl backend, this one is drawn by {self.backend}")
        flat = np.asarray(texels)
        if flat.ndim != 1 or flat.dtype.kind not in "iu" or (flat.size and (flat.min() < 0 or flat.max() >= self.resolution**2)):
            raise ValueError(f"texels must be whole flat texel indices in [0, {self.resolution**2 - 1}] of shape (P,), got {flat.dtype} {flat.shape}")
        tri = np.asarray(triangles, float)
        if tri.ndim != 3 or tri.shape[1:] != (3, 3) or len(tri) < len(self.triangles):
            raise ValueError(f"triangles must be the sampler's scene, shape (T, 3, 3) with T >= {len(self.triangles)}, got {tri.shape}")
        bias = float(check.closed_range(bias, "bias", 0.0, np.inf, " world units (depth-test tolerance)"))
        flat = flat.astype(np.int64)
        if not flat.size:
            return np.zeros(0, bool)
        device = self._drawn(flat)
        if self._planes is None or self._planes[0] is not triangles:  # the planes, computed once per scene array
            self._planes = (triangles, resident._plane_rows(tri[:len(self.triangles)], self.lm.basis[1]))
        return device.test(flat, points, receiver, self._planes[1], bias)

    def _draw(self, texels: NDArray[np.int64]) -> tuple[Array, NDArray[np.int64]]:
        if self.backend == "gl":
            return self._drawn(texels).fetch(texels)
        if self._prepared is None:
            mapped, w, rows, src = map_triangles(self.triangles, self.lm, self.resolution)
            inv_w, rows, uniform = weights_and_rows(mapped, self.resolution, w, rows)
            self._prepared = (mapped, inv_w, rows, uniform, src)
        mapped, inv_w, rows, uniform, src = self._prepared
        depth, ident, _, _ = zbuffer_at(mapped, self.resolution, inv_w, rows, uniform, self.chunk, texels)
        if src is not None:
            ident = np.where(ident >= 0, src[np.maximum(ident, 0)], -1)
        return depth, ident

    def release(self) -> None:
        """Free the device map (gl), if one was drawn; the texels found are kept."""
        if self._device is not None:
            self._device.release()
            self._device = None


def _box(texels: NDArray[np.int64], res: int) -> tuple[int, int, int, int]:
    """The smallest box (x, y, width, height) [texels] holding flat texel indices ``texels``."""
    row, col = texels // res, texels % res
    return int(col.min()), int(row.min()), int(col.max() - col.min() + 1), int(row.max() - row.min() + 1)


def _union(a: tuple[int, int, int, int], b: tuple[int, int, int, int]) -> tuple[int, int, int, int]:
    x, y = min(a[0], b[0]), min(a[1], b[1])
    return x, y, max(a[0] + a[2], b[0] + b[2]) - x, max(a[1] + a[3], b[1] + b[3]) - y
