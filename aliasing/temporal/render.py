"""Drawing the maps of a lattice and testing points through them, sharing maps across frames.

The world is still, so a map is fully named by its light frame and texel grid: a map
whose grid did not change since the last frame (a snapped stable fit under translation, a
VSM level) is reused, not drawn again.  Each map is drawn only from the triangles whose
light-plane box meets its window (the stored depth of a texel depends only on its centre,
so the culled map is the same map).

Example
-------
>>> from aliasing.temporal import paths, points, fits
>>> w = points.world("boxes", boxes=10)
>>> pts = points.sample(w, 32)
>>> poses = paths.frames(paths.parse_motion("translate:0.1,0,0"), w.camera.eye, w.camera.rotation, 60.0, w.light, 3)
>>> lat = fits.plan("csm-stable:log:k=3:snap=origin", w, poses, 64)
>>> part = fits.assign(lat, fits.eye_coordinates(pts.position, poses[0], poses[1]), poses[2], 1.0, 100.0)
>>> mc = MapCache(w.triangles)
>>> lit = mc.test(lat, 0, 0, pts.position[part[0] == 0], pts.normal[part[0] == 0])
>>> lit.dtype == bool, mc.drawn
(True, 1)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from ..raster.draw import BIAS, backends, check_resolution, frame_map, shadow_map, shadow_test
from ..raster.draw.shadow import MapSampler
from .fits import Lattices

Array = NDArray[np.float64]


class MapCache:
    """Depth maps keyed by (light frame, corner, texel sides, size), kept while in use.

    :meth:`test` draws (or reuses) map ``k`` of frame ``f`` of a :class:`Lattices` and
    returns the shadow test (:func:`aliasing.raster.draw.shadow_test`) of points through it;
    :meth:`next_frame` forgets the maps the finished frame did not use.  ``drawn`` counts
    the maps drawn, ``reused`` the tests that found their map.  ``backend`` draws the depth
    maps (:mod:`aliasing.raster.draw.backends`: numpy, the reference, or gl).
    """

    def __init__(self, triangles: Array, *, bias: float = BIAS, backend: str = "numpy") -> None:
        tri = check.as_float_array(triangles, "triangles")
        if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri):
            raise ValueError(f"triangles must have shape (T, 3, 3) with T >= 1 [world units], got {tri.shape}")
        self.triangles = tri
        self.bias = float(check.closed_range(bias, "bias", 0.0, np.inf, " world units"))
        self.backend = backends.pair(backend)[1]  # numba draws eye passes only: its maps are numpy's
        self.maps: dict[tuple, tuple] = {}
        self.used: set[tuple] = set()
        self.drawn = 0
        self.reused = 0
        self._frame_key: bytes | None = None
        self._boxes: tuple[Array, Array, Array, Array] | None = None

    def _light_boxes(self, basis: Array) -> tuple[Array, Array, Array, Array]:
        key = basis.tobytes()
        if key != self._frame_key:  # the light-plane boxes of all triangles, once per light frame
            px, py = self.triangles @ basis[0], self.triangles @ basis[2]
            self._boxes = (px.min(-1), px.max(-1), py.min(-1), py.max(-1))
            self._frame_key = key
        return self._boxes  # type: ignore[return-value]

    def window(self, basis: Array, x0: float, y0: float, tx: float, ty: float, n: int) -> tuple:
        """The (light map, depth map, triangles) of one window, the whole map drawn.

        :meth:`test` draws a window only at its points' texels; this draws all of it
        (:func:`aliasing.raster.shadow_map`, R² texels) and does not keep the depth map.

        ``basis`` (3, 3) the light frame (rows x̂, l̂, ŷ), (x0, y0) the corner and (tx, ty) the
        texel sides [world units], ``n`` texels per side.
        """
        basis = check.finite(basis, "basis")
        if basis.shape != (3, 3):
            raise ValueError(f"basis must have shape (3, 3), got {basis.shape}")
        x0, y0 = (float(check.scalar(v, name)) for v, name in ((x0, "x0"), (y0, "y0")))
        tx, ty = (float(check.positive(v, name)) for v, name in ((tx, "tx"), (ty, "ty")))
        n = check_resolution(n, "n")
        lm, sampler, sub = self._sampler(basis, x0, y0, tx, ty, n)
        return lm, shadow_map(sub, lm, n, backend=self.backend), sub

    def _sampler(self, basis: Array, x0: float, y0: float, tx: float, ty: float, n: int) -> tuple:
        """(light map, :class:`~aliasing.raster.draw.shadow.MapSampler`, triangles) of one window, made or reused."""
        key = (basis.tobytes(), float(x0), float(y0), float(tx), float(ty), int(n))
        self.used.add(key)
        if key in self.maps:
            self.reused += 1
            return self.maps[key]
        x1, y1 = x0 + n * tx, y0 + n * ty
        lx, hx, ly, hy = self._light_boxes(basis)
        keep = (hx >= x0) & (lx <= x1) & (hy >= y0) & (ly <= y1)
        sub = self.triangles[keep] if keep.any() else self.triangles[:1]
        lm = frame_map(basis[1], basis[2], y0, y1, np.inf, x0, x1, "uniform")
        self.maps[key] = (lm, MapSampler(sub, lm, int(n), backend=self.backend), sub)
        self.drawn += 1
        return self.maps[key]

    def test(self, lat: Lattices, f: int, k: int, positions: Array, normals: Array, *, dx: float = 0.0, dy: float = 0.0) -> NDArray[np.bool_]:
        """Lit (True) or shadowed, for points through map k of frame f (its grid moved by (dx, dy) [world units]).

        The map is drawn only at the points' texels (:class:`~aliasing.raster.draw.shadow.MapSampler`;
        numpy: only those texels are rasterized, gl: the map stays on the device and only
        the texels come back), so the memory grows with the points, not with the texels.
        """
        if not len(positions):
            return np.zeros(0, bool)
        basis = check.finite(lat.basis[f], "basis")
        lm, sampler, sub = self._sampler(basis, float(lat.x0[f, k] + dx), float(lat.y0[f, k] + dy), float(lat.tx[f, k]), float(lat.ty[f, k]), check_resolution(int(lat.n[f, k]), "n"))
        return shadow_test(lm, sampler, sub, positions, normals, bias=self.bias)

    def next_frame(self) -> None:
        """Forget the maps the last frame did not use (the memory stays at about one frame's maps)."""
        for key, (_, sampler, _) in self.maps.items():
            if key not in self.used:
                sampler.release()
        self.maps = {key: v for key, v in self.maps.items() if key in self.used}
        self.used = set()

    def release(self) -> None:
        """Forget every map (and free the gl backend's device maps)."""
        for _, sampler, _ in self.maps.values():
            sampler.release()
        self.maps, self.used = {}, set()
