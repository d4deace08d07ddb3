"""PlayCanvas 2.23.3's cascaded directional light: its settings and the toolkit's model (:class:`PlayCanvas`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ...engines import stable
from .. import predict
from ..lightmaps.depth import SUBPIXEL_BITS
from ..predict import Prediction, reference

Array = NDArray[np.float64]


def _light_rotation(sun: Array) -> Array:
    """The page's light rotation (3 × 3, columns: the light's x, y, z in the world): +y turned onto the unit
    ``sun`` about y × sun (``Quat.setFromAxisAngle``); about x by 0° or 180° when the sun is along ±y."""
    y = np.array([0.0, 1.0, 0.0])
    axis = np.cross(y, sun)
    n = np.linalg.norm(axis)
    if n < 1e-9:
        return np.eye(3) if sun[1] > 0 else np.diag([1.0, -1.0, -1.0])
    k = axis / n
    ang = np.arccos(np.clip(y @ sun, -1.0, 1.0))
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(ang) * kx + (1 - np.cos(ang)) * kx @ kx  # Rodrigues


@dataclass(frozen=True)
class PlayCanvas:
    """PlayCanvas 2.23.3, a directional light with (cascaded) shadows (npm ``playcanvas``, ``build/playcanvas/src``).

    Settings (the light component's own keys): ``shadowBias``, ``normalOffsetBias``,
    ``shadowResolution``, ``numCascades``, ``cascadeDistribution``, ``cascadeBlend``,
    ``shadowDistance``, ``shadowType``, ``shadowIntensity``; the material's ``cull``.

    The model, from the engine's source (files under ``scene/``):

    * splits: ``generateSplitDistances`` (``renderer/shadow-renderer-directional.js`` 182–191),
      practical with λ = ``cascadeDistribution`` from near to min(far, ``shadowDistance``),
      stored in a Float32Array (the toolkit's :func:`aliasing.setups.playcanvas.splits`);
    * fit: the sphere around the slice corners' average, the map side its diameter
      (``cull``, lines 84–116; the pipeline's ``centroid`` fit); one map of ``shadowResolution``,
      a 2×2 atlas of half-size cells when there are more cascades (``light.js`` 46–51);
    * faces: the material's ``cull`` in the caster pass too (CULLFACE_BACK: front faces cast);
    * bias: the caster pass's polygon offset, factor and units both 10·``shadowBias``
      (``light.js`` ``_updateShadowBias`` 746–755, the component's −0.01·shadowBias);
      the receiver's depth ``saturate(z) − 0.0001`` and its point moved by
      ``normalOffsetBias`` along the world normal (``lightFunctionShadow``, the PCF path
      ``SHADOW_SAMPLE_SOURCE_ZBUFFER``); :func:`aliasing.frames.predict.playcanvas_factor`;
    * filter: PCF1/3/5 hardware comparisons (LESS) over the whole atlas (``shadowPCF1/3/5``);
    * cascade: the number of ends ≤ the eye depth, at most k − 1; none beyond the last end
      (``shadowCascades`` ``getShadowCascadeIndex``, ``getShadow``'s early return).

    The polygon offset's slope term is the rasterizer's: SwiftShader takes
    m = max(|∂z/∂x|, |∂z/∂y|) in window units and r = 2^(e − 23) for the 32-bit float depth
    map, e the exponent of the triangle's largest depth (SwiftShader ``src/Pipeline/SetupRoutine.cpp``).
    ``cascadeBlend`` (a dither of ``fract(sin(...))``) and the VSM, PCSS and 16-bit types are
    rendered but not predicted.  Distances are in world units, ``shadowResolution`` in texels.

    Examples
    --------
    >>> from aliasing.frames.models import MODELS, ThreeCSM
    >>> from aliasing.raster.scenes.camera import look_at
    >>> m, cam = PlayCanvas(), look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
    >>> s = m.settings({"numCascades": 2, "cull": "none"})
    >>> m.cast_side(s), m.edges(s, cam).round(3).tolist(), m.cells(s).tolist()   # ends (uniform + log) / 2 up to shadowDistance 40
    ('double', [1.0, 13.412, 40.0], [[0.0, 0.0, 0.5, 0.5], [0.0, 0.5, 0.5, 0.5]])
    >>> m.select(s, cam, np.array([2.0, 20.0, 41.0])).tolist(), m.predicted(s)
    ([0, 1, -1], None)
    >>> from aliasing.frames.readback import Readback
    >>> from aliasing.frames.scenes import frame_scene, sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=1.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera)
    >>> pts = np.array([[[-2.0, -1.0, -4.25], [0.0, -1.0, -12.0]]])   # two ground pixels: in a box's shadow, lit
    >>> def rb(mats, info=None):                                      # what a page would read back there
    ...     return Readback("", "", np.ones((1, 2)), np.zeros((1, 2), np.int64), pts, np.array([[[0.0, 1.0, 0.0]] * 2]),
    ...                     mats, np.full((len(mats), 2), 256), info or {}, b"")
    >>> mats = ThreeCSM().matrices(ThreeCSM().settings({"cascades": 1}), fs.camera, sun)   # any world → [0, 1]³ box
    >>> pred, ref = m.predict(m.settings({"shadowResolution": 256}), fs, sun, rb(mats))
    >>> (pred.factor < 0.5).tolist(), ref.tolist()
    ([[True, False]], [[False, True]])
    >>> [v.tolist() for v in m.measured_cascades(s, fs.camera, rb(np.diag([0.1, 0.1, 0.01, 1.0])[None], {"cascades": [{"distance": 40.0}]}))]
    [[1.0], [10.0], [256.0]]
    """

    engine: str = "playcanvas"
    defaults: dict = field(default_factory=lambda: {
        "shadowBias": 0.05, "normalOffsetBias": 0.0, "shadowResolution": 1024, "numCascades": 1, "cascadeDistribution": 0.5,
        "cascadeBlend": 0.0, "shadowDistance": 40.0, "shadowType": 0, "shadowIntensity": 1.0, "cull": "back"})
    #: shadowType numbers predicted (scene/constants.js): PCF3_32F, PCF5_32F, PCF1_32F and their filter sizes
    FILTERS = {0: 3, 4: 5, 5: 1}

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in (the light's and the component's own defaults)."""
        given = dict(given or {})
        unknown = sorted(set(given) - set(self.defaults))
        if unknown:
            raise ValueError(f"unknown PlayCanvas setting {unknown[0]!r}; known: {', '.join(sorted(self.defaults))}")
        s = {**self.defaults, **given}
        if s["numCascades"] not in (1, 2, 3, 4):
            raise ValueError(f"numCascades must be 1, 2, 3 or 4, got {s['numCascades']!r}")
        if s["cull"] not in ("back", "front", "none"):
            raise ValueError(f"cull must be back, front or none, got {s['cull']!r}")
        if s["shadowResolution"] not in (256, 512, 1024, 2048, 4096):
            raise ValueError(f"shadowResolution must be a power of two in [256, 4096], got {s['shadowResolution']!r}")
        return s

    def predicted(self, s: dict) -> str | None:
        """Why a setting's frame is rendered but not predicted (None when it is predicted)."""
        if s["shadowType"] not in self.FILTERS:
            return "shadowType must be SHADOW_PCF1_32F, SHADOW_PCF3_32F or SHADOW_PCF5_32F for a prediction (VSM, PCSS and 16-bit maps are not modelled)"
        if s["cascadeBlend"] != 0:
            return "cascadeBlend must be 0 for a prediction (the blend is a per-pixel dither of fract(sin(...)), not modelled)"
        if s["shadowIntensity"] != 1:
            return "shadowIntensity must be 1 for a prediction"
        return None

    def cast_side(self, s: dict) -> str:
        """The faces drawn into the map: the material's cull mode, as in the main pass (back culled: front faces cast)."""
        return {"back": "front", "front": "back", "none": "double"}[s["cull"]]

    def edges(self, s: dict, camera) -> Array:
        """The cascades' ends, near first [world units], float32 as the engine stores them."""
        from ...setups.playcanvas import splits

        a, b = splits({"numCascades": s["numCascades"], "cascadeDistribution": s["cascadeDistribution"], "shadowDistance": s["shadowDistance"]},
                      camera.near, camera.far)
        return np.concatenate([[a[0]], b])

    def select(self, s: dict, camera, depth: Array) -> NDArray[np.int64]:
        """``getShadowCascadeIndex``: the number of ends ≤ the eye depth, at most k − 1; −1 beyond the last end."""
        ends = self.edges(s, camera)[1:]
        idx = np.minimum(np.searchsorted(ends, depth, side="right"), len(ends) - 1)
        return np.where(np.isfinite(depth) & (depth <= ends[-1]), idx, -1).astype(np.int64)

    def cells(self, s: dict) -> Array:
        """Each cascade's atlas cell (x, y, w, h) in [0, 1] (``light.js`` ``directionalCascades``)."""
        k = int(s["numCascades"])
        if k == 1:
            return np.array([[0.0, 0.0, 1.0, 1.0]])
        return np.array([[0.0, 0.0, 0.5, 0.5], [0.0, 0.5, 0.5, 0.5], [0.5, 0.0, 0.5, 0.5], [0.5, 0.5, 0.5, 0.5]])[:k]

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        """The predicted factor at the engine's pixels (:func:`aliasing.frames.predict.playcanvas_factor`), and the exact reference."""
        why = self.predicted(s)
        if why:
            raise ValueError(why)
        cam = scene.camera
        depth = np.where(rb.drawn, cam.to_eye(np.nan_to_num(rb.position))[..., 2], np.nan)
        sel = self.select(s, cam, depth)
        res = int(s["shadowResolution"])
        cast = scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))]
        atlas = predict.playcanvas_atlas(cast, rb.matrices, self.cells(s), res, float(s["shadowBias"]), subpixel_bits=SUBPIXEL_BITS,
                                         sampled=True)  # drawn where read, corners as SwiftShader snaps them
        pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
        factor = predict.gathered(lambda: predict.playcanvas_factor(atlas, rb.matrices, sel, pts, nrm, normal_offset=float(s["normalOffsetBias"]),
                                                                    taps=self.FILTERS[int(s["shadowType"])]), [atlas])
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)
        edges = self.edges(s, cam)
        k = len(edges) - 1
        per = res if k == 1 else res // 2
        sides = np.array([2 * float(stable.centroid_radius(a, b, cam.fov, cam.aspect)) for a, b in zip(edges[:-1], edges[1:])])
        return Prediction(factor, sel, edges[:-1], sides, np.full(k, float(per))), ref

    def light_matrices(self, s: dict, camera, sun: Array, triangles: Array, float32_depth: bool = True, snap: bool = True) -> Array:
        """The toolkit's prediction of each cascade's palette matrix (world → the atlas's (s, t, depth) in [0, 1]³),
        as ``ShadowRendererDirectional.cull`` and ``ShadowRenderer.dispatchUniforms`` build it (float64).

        Per cascade (``renderer/shadow-renderer-directional.js``): the light's rotation turned −90° about
        its x (69–83: the shadow camera looks along −``sun``, its up the light's −z, its right the
        light's x); the slice corners' centroid c and radius r, the largest corner distance (84–100);
        the centre snapped up to a multiple of 4r/R along up and right (104–111: ``sizeRatio`` =
        R/(4r), ``Math.ceil``), which is one texel of a half-size atlas cell (two of a whole map);
        orthographic ±r (116); the depth from the casters' bounding box (``meshInstance.aabb``,
        ``triangles`` [world units]) seen along the light, the camera 0.1 before its nearest corner
        and far 0.2 beyond its depth (174–177, near 0.01); then the cell's viewport (``Mat4.setViewport``,
        ``shadow-renderer.js`` 261–266).  The light entity turns +y onto ``sun`` about y × sun (the page's rotation).

        The depth range is measured with the shadow camera first put 10⁶ behind the centre
        (``translateLocal(0, 0, 1e6)``, line 113) in a float32 world matrix (``Mat4``), inverted into
        float32: the casters' nearest depth, and so the camera's final place along the light, is off by
        that rounding (up to about 2⁻⁴ world units; ERRATA F11).  ``float32_depth`` (default) repeats
        that arithmetic; False places the camera exactly 0.1 before the box.  Neither changes s or t.
        ``snap`` False leaves the centre where the slice puts it (what the maps would do unsnapped).

        Examples
        --------
        >>> from aliasing.frames.models import MODELS
        >>> from aliasing.frames.scenes import frame_scene, sun_direction
        >>> fs = frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=4, ground_cells=2)
        >>> pc = MODELS["playcanvas"]
        >>> s = pc.settings({"numCascades": 2})
        >>> m = pc.light_matrices(s, fs.camera, sun_direction(35, 30, fs.camera), fs.triangles)
        >>> a, b = pc.edges(s, fs.camera)[1:3]                                   # cascade 1's slice
        >>> st = m[1] @ [*(fs.camera.view.slice_vertices(a, b) @ fs.camera.rotation + fs.camera.eye).mean(0), 1.0]
        >>> m.shape, bool(0 <= st[0] <= 0.5 <= st[1] <= 1)                     # its centre: in its cell, the atlas's upper left quarter
        ((2, 4, 4), True)
        """
        from ... import _validation as check

        sv = check.direction(sun)
        tri = check.triangles(triangles)
        rot = _light_rotation(sv / np.linalg.norm(sv))
        right, up, back = rot[:, 0], -rot[:, 2], rot[:, 1]  # the shadow camera's x, y and z (it looks along −z = −sun)
        res = float(s["shadowResolution"])
        pts = tri.reshape(-1, 3)
        lo, hi = pts.min(0), pts.max(0)
        corners_box = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
        box = corners_box @ back
        depth = float(box.max() - box.min())
        near, far = 0.01, depth + 0.2
        edges = self.edges(s, camera)
        out = []
        for (a, b), (x0, y0, w, h) in zip(zip(edges[:-1], edges[1:]), self.cells(s)):
            corners = camera.view.slice_vertices(a, b) @ camera.rotation + camera.eye
            c = corners.mean(0)
            r = float(np.max(np.linalg.norm(corners - c, axis=1)))
            ratio = 0.25 * res / r
            basis = np.stack([right, up, back])
            snapped = up * (np.ceil(c @ up * ratio) / ratio) + right * (np.ceil(c @ right * ratio) / ratio) if snap else up * (c @ up) + right * (c @ right)
            nearest = box.max()
            if float32_depth:  # the camera 1e6 behind the centre, its world matrix and inverse in float32
                far_cam = np.eye(4)
                far_cam[:3, :3] = basis.T
                far_cam[:3, 3] = snapped + back * (c @ back) + 1e6 * back
                inv = np.linalg.inv(far_cam.astype(np.float32).astype(float)).astype(np.float32).astype(float)
                nearest = float(np.max(corners_box @ inv[2, :3] + inv[2, 3])) + (far_cam[:3, 3] @ back)
            pos = snapped + back * (nearest + 0.1)
            view = np.eye(4)
            view[:3, :3] = basis
            view[:3, 3] = -basis @ pos
            proj = np.diag([1 / r, 1 / r, -2 / (far - near), 1.0])
            proj[2, 3] = -(far + near) / (far - near)
            vp = np.diag([w / 2, h / 2, 0.5, 1.0])
            vp[:3, 3] = [x0 + w / 2, y0 + h / 2, 0.5]
            out.append(vp @ proj @ view)
        return np.array(out)

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """Each cascade's first depth (the previous cascade's distance), its larger texel side × R (R the atlas's side) and R."""
        ends = np.array([c["distance"] for c in rb.info["cascades"]], float)
        starts = np.concatenate([[camera.near], ends[:-1]])
        sides = np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3])) for m in rb.matrices])
        return starts, sides, rb.sizes[:, 0].astype(float)
