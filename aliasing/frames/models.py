"""Each engine's settings (its own keys and defaults) and the toolkit's model of its shadow pass.

A model turns the engine's settings into what the toolkit predicts: which faces cast, which
cascade each pixel samples, the bias and the filter (from the engine's shader source in the
pinned package), and the cascades' ends and map sides from the toolkit's presets
(:data:`aliasing.engines.stable.PRESETS`, :func:`aliasing.partitioning.split_distances`).

Example
-------
>>> sorted(MODELS)
['babylon', 'playcanvas', 'threejs']
>>> MODELS["threejs"].settings({"shadowBias": 0})["shadowBias"]   # CSM: `data.shadowBias || 0.000001`
1e-06
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .. import partitioning
from .. import _validation as check
from ..engines import stable
from ..setups import babylon as babylon_setup
from . import babylon_cascades, predict
from .predict import Prediction, reference, tight_sides
from .single import BabylonSingle, Filament, ThreeDirectional

Array = NDArray[np.float64]
__all__ = ["MODELS", "SINGLE", "Prediction", "reference", "tight_sides", "ThreeCSM", "ThreeDirectional", "BabylonCSM", "BabylonSingle",
           "PlayCanvas", "Filament", "model_for", "from_setup"]


@dataclass(frozen=True)
class ThreeCSM:
    """three.js r187, WebGLRenderer with the CSM addon (examples/jsm/csm/CSM.js, CSMShader.js).

    Settings (the engine's own keys): CSM's ``cascades``, ``maxFar``, ``mode``,
    ``shadowMapSize``, ``shadowBias``, ``lightIntensity``, ``lightNear``, ``lightFar``,
    ``lightMargin``, ``fade``; each cascade light's shadow ``normalBias`` and ``shadowRadius``
    (``light.shadow.radius``); the renderer's ``shadowMapType``; the material's ``side`` and
    ``shadowSide`` (null: the opposite of ``side``, WebGLShadowMap's ``shadowSide`` table).
    Distances are in world units, ``shadowMapSize`` in texels, ``shadowBias`` in normalized depth.

    Examples
    --------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> m, cam = ThreeCSM(), look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
    >>> s = m.settings({"cascades": 2, "mode": "logarithmic", "maxFar": 400.0})
    >>> m.cast_side(s), m.shadow_far(s, cam), m.edges(s, cam).tolist()   # back faces cast; ends 1 · 100^(i/2) [world units]
    ('back', 100.0, [1.0, 10.0, 100.0])
    >>> m.select(s, cam, np.array([2.0, 30.0, 200.0, np.nan])).tolist()  # the cascade of each eye depth, −1 none
    [0, 1, -1, -1]
    >>> from aliasing.frames.readback import Readback
    >>> from aliasing.frames.scenes import frame_scene, sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=1.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera)
    >>> pts = np.array([[[-2.0, -1.0, -4.25], [0.0, -1.0, -12.0]]])   # two ground pixels: in a box's shadow, lit
    >>> def rb(mats, info=None):                                      # what a page would read back there
    ...     return Readback("", "", np.ones((1, 2)), np.zeros((1, 2), np.int64), pts, np.array([[[0.0, 1.0, 0.0]] * 2]),
    ...                     mats, np.full((len(mats), 2), 256), info or {}, b"")
    >>> s = m.settings({"cascades": 2, "shadowMapSize": 256}); mats = m.matrices(s, fs.camera, sun)
    >>> pred, ref = m.predict(s, fs, sun, rb(mats))
    >>> pred.cascade.tolist(), (pred.factor < 0.5).tolist(), ref.tolist()
    ([[0, 1]], [[True, False]], [[False, True]])
    >>> bool(np.allclose(mats[:, 2, :3] @ sun, -1 / 1999))   # depth grows away from the sun: ½ · 2 / (lightFar − lightNear)
    True
    >>> [v.tolist() for v in m.measured_cascades(s, fs.camera, rb(np.diag([0.1, 0.1, 0.01, 1.0])[None], {"breaks": [1.0]}))]
    [[1.0], [10.0], [256.0]]
    """

    engine: str = "threejs"
    preset: str = "threejs"
    defaults: dict = field(default_factory=lambda: {
        "cascades": 3, "maxFar": 100000.0, "mode": "practical", "shadowMapSize": 2048, "shadowBias": 0.000001,
        "lightIntensity": 3.0, "lightNear": 1.0, "lightFar": 2000.0, "lightMargin": 200.0, "fade": False,
        "normalBias": 0.0, "shadowRadius": 1.0, "shadowMapType": "PCFShadowMap", "side": "front", "shadowSide": None})

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in, as the engine takes them (CSM's ``x || default`` included)."""
        given = dict(given or {})
        unknown = sorted(set(given) - set(self.defaults))
        if unknown:
            raise ValueError(f"unknown three.js setting {unknown[0]!r}; known: {', '.join(sorted(self.defaults))}")
        s = {**self.defaults, **given}
        for k in ("cascades", "maxFar", "shadowMapSize", "shadowBias", "lightIntensity", "lightNear", "lightFar", "lightMargin"):
            if not s[k]:  # CSM's constructor: `data.x || default` (0 becomes the default)
                s[k] = self.defaults[k]
        if s["mode"] not in ("practical", "uniform", "logarithmic"):
            raise ValueError(f"mode must be practical, uniform or logarithmic (custom splits are not modelled), got {s['mode']!r}")
        for k in ("side",):
            if s[k] not in predict.SIDES:
                raise ValueError(f"{k} must be one of {', '.join(predict.SIDES)}, got {s[k]!r}")
        if s["shadowSide"] is not None and s["shadowSide"] not in predict.SIDES:
            raise ValueError(f"shadowSide must be null or one of {', '.join(predict.SIDES)}, got {s['shadowSide']!r}")
        if s["shadowMapType"] not in ("PCFShadowMap", "BasicShadowMap"):
            raise ValueError(f"shadowMapType must be PCFShadowMap or BasicShadowMap (the filters modelled), got {s['shadowMapType']!r}")
        if bool(s["fade"]):
            raise ValueError("fade must be false (the blended cascades are not modelled)")
        k = int(s["cascades"])
        if not 1 <= k <= 8:
            raise ValueError(f"cascades must be a whole number in [1, 8], got {s['cascades']!r}")
        return s

    def cast_side(self, s: dict) -> str:
        """The faces drawn into the map: ``shadowSide``, or the opposite of ``side`` (front ↔ back, double stays)."""
        if s["shadowSide"] is not None:
            return s["shadowSide"]
        return {"front": "back", "back": "front", "double": "double"}[s["side"]]

    def shadow_far(self, s: dict, camera) -> float:
        """The last cascade's end [world units]: min(the camera's far, ``maxFar``)."""
        return float(min(camera.far, s["maxFar"]))

    def edges(self, s: dict, camera) -> Array:
        """The cascades' ends (near … shadow far) [world units]: the toolkit's threejs split for
        ``practical`` (λ = 0.5), and CSM's ``uniformSplit``/``logarithmicSplit`` for the other modes."""
        n, f, k = camera.near, self.shadow_far(s, camera), int(s["cascades"])
        if s["mode"] == "practical":
            return partitioning.split_distances(stable.PRESETS[self.preset].split, n, f, k)
        i = np.arange(k + 1) / k
        ends = n + (f - n) * i if s["mode"] == "uniform" else n * (f / n) ** i
        ends[0], ends[-1] = n, f
        return ends

    def select(self, s: dict, camera, depth: Array) -> NDArray[np.int64]:
        """The cascade each eye depth samples (CSMShader, fade off): linearDepth = z / (far − near)
        against the breaks (end / far); −1 beyond the last (no shadow)."""
        far = self.shadow_far(s, camera)
        breaks = self.edges(s, camera)[1:] / far
        ld = depth / (far - camera.near)
        idx = np.searchsorted(breaks, ld, side="right")
        return np.where(np.isfinite(ld) & (idx < len(breaks)), idx, -1).astype(np.int64)

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        """The predicted factor at the engine's pixels, and the exact reference's lit pixels."""
        cam = scene.camera
        depth = cam.to_eye(np.nan_to_num(rb.position))[..., 2]
        depth = np.where(rb.drawn, depth, np.nan)
        sel = self.select(s, cam, depth)
        res = int(s["shadowMapSize"])
        cast = scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))]
        maps = [predict.light_depth_map(cast, m, res) for m in rb.matrices]
        h, w = depth.shape
        fy, fx = np.mgrid[0:h, 0:w]
        gl_y = (h - 1 - fy) + 0.5
        pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
        factor = predict.threejs_factor(maps, rb.matrices, sel, pts, nrm, fx + 0.5, gl_y, bias=float(s["shadowBias"]),
                                        normal_bias=float(s["normalBias"]), radius=float(s["shadowRadius"]), map_type=s["shadowMapType"])
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)  # the exact reference, through each cascade's matrix at its own pixels
        edges = self.edges(s, cam)
        p = stable.PRESETS[self.preset]
        light_eye = cam.direction_to_eye(sun)[None]
        box = stable.evaluate(edges, cam.near, edges[-1], cam.fov, light_eye, aspect=cam.aspect, fit=p.fit, snap=p.snap, resolution=float(res))
        sides = np.maximum(box.width_x[0], box.width_y[0])
        return Prediction(factor, sel, edges[:-1], sides, np.full(len(sides), float(res))), ref

    def matrices(self, s: dict, camera, sun: Array) -> Array:
        """The toolkit's prediction of each cascade's shadow matrix (world → [0, 1]³), as CSM builds it.

        ``CSM.update``: the light frame is ``Matrix4.lookAt(origin, lightDirection, up)`` (z = −d,
        x ∝ up × z, y = z × x); the slice's corners in it give a box whose centre is floored to a
        texel of the square side (:func:`aliasing.engines.stable.diagonal`, unrounded) in x and y
        and put ``lightMargin`` beyond the box's top in z; the shadow camera sits there looking
        along d (the same frame), orthographic ±side/2, ``lightNear``…``lightFar``; the matrix is
        [½ bias] · projection · view (``LightShadow.updateMatrices``).
        """
        _sun(sun)
        from ..engines.stable import diagonal

        d = -np.asarray(sun, float) / np.linalg.norm(sun)
        z = -d
        x = np.cross([0.0, 1.0, 0.0], z)
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        basis = np.stack([x, y, z])  # rows: light-space axes in world
        edges = self.edges(s, camera)
        res = float(s["shadowMapSize"])
        near_l, far_l = float(s["lightNear"]), float(s["lightFar"])
        half = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
        out = []
        for a, b in zip(edges[:-1], edges[1:]):
            side = float(diagonal(a, b, camera.fov, camera.aspect))
            texel = side / res
            corners = camera.view.slice_vertices(a, b) @ camera.rotation + camera.eye  # world
            lc = corners @ basis.T
            lo, hi = lc.min(0), lc.max(0)
            centre = (lo + hi) / 2
            centre[2] = hi[2] + float(s["lightMargin"])
            centre[:2] = np.floor(centre[:2] / texel) * texel
            c_world = centre @ basis
            view = np.eye(4)
            view[:3, :3] = basis
            view[:3, 3] = -basis @ c_world
            proj = np.diag([2 / side, 2 / side, -2 / (far_l - near_l), 1.0])
            proj[2, 3] = -(far_l + near_l) / (far_l - near_l)
            out.append(half @ proj @ view)
        return np.array(out)

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """From the engine's objects: each cascade's first depth (its breaks × far), its map's larger texel side × R, and R."""
        far = self.shadow_far(s, camera)
        breaks = np.asarray(rb.info["breaks"], float)
        starts = np.concatenate([[camera.near], breaks[:-1] * far])
        sides = np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3])) for m in rb.matrices])
        return starts, sides, rb.sizes[:, 0].astype(float)


@dataclass(frozen=True)
class BabylonCSM:
    """Babylon.js 9.35, CascadedShadowGenerator on a DirectionalLight (Lights/Shadows/cascadedShadowGenerator.pure.js).

    Settings (the engine's own keys): the generator's ``mapSize`` (its constructor's first
    argument), ``numCascades``, ``lambda``, ``bias``, ``normalBias``, ``darkness``,
    ``frustumEdgeFalloff``, ``stabilizeCascades``, ``cascadeBlendPercentage``, ``depthClamp``,
    ``autoCalcDepthBounds``, ``shadowMaxZ`` (null: the camera's far), ``filteringQuality``,
    ``usePercentageCloserFiltering``, ``forceBackFacesOnly``; the material's ``backFaceCulling``.
    Distances are in world units, ``mapSize`` in texels, ``bias`` in normalized depth.

    Examples
    --------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> m, cam = BabylonCSM(), look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
    >>> s = m.settings({"numCascades": 2, "shadowMaxZ": 80.0})
    >>> m.cast_side(s), m.shadow_far(s, cam), m.edges(s, cam).round(3).tolist()   # ends: (uniform + log) / 2 [world units]
    ('front', 80.0, [1.0, 24.722, 80.0])
    >>> m.select(s, cam, np.array([2.0, 30.0, 90.0])).tolist()
    [0, 1, -1]
    >>> from aliasing.frames.readback import Readback
    >>> from aliasing.frames.scenes import frame_scene, sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=1.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera)
    >>> pts = np.array([[[-2.0, -1.0, -4.25], [0.0, -1.0, -12.0]]])   # two ground pixels: in a box's shadow, lit
    >>> def rb(mats, info=None):                                      # what a page would read back there
    ...     return Readback("", "", np.ones((1, 2)), np.zeros((1, 2), np.int64), pts, np.array([[[0.0, 1.0, 0.0]] * 2]),
    ...                     mats, np.full((len(mats), 2), 256), info or {}, b"")
    >>> from aliasing.frames.babylon_cascades import matrices
    >>> s = m.settings({"numCascades": 2, "mapSize": 256})
    >>> pred, ref = m.predict(s, fs, sun, rb(matrices(s, fs.camera, sun, fs.triangles)))
    >>> pred.cascade.tolist(), (pred.factor < 0.5).tolist(), ref.tolist()
    ([[0, 1]], [[True, False]], [[False, True]])
    >>> [v.tolist() for v in m.measured_cascades(s, fs.camera, rb(np.diag([0.1, 0.1, 0.01, 1.0])[None], {"cascades": [{"viewZ": 20.0}]}))]
    [[1.0], [10.0], [256.0]]
    """

    engine: str = "babylon"
    #: the predicted footprint is the modelled engine's (its float32 matrices), not the setups' float64 fit
    footprint_from_matrices: bool = True
    defaults: dict = field(default_factory=lambda: {
        "mapSize": 1024, "numCascades": 4, "lambda": 0.5, "bias": 0.00005, "normalBias": 0.0, "darkness": 0.0, "frustumEdgeFalloff": 0.0,
        "stabilizeCascades": False, "cascadeBlendPercentage": 0.1, "depthClamp": True, "autoCalcDepthBounds": False, "shadowMaxZ": None,
        "filteringQuality": 0, "usePercentageCloserFiltering": True, "forceBackFacesOnly": False, "backFaceCulling": True})

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in (the generator's own defaults, read from its constructor)."""
        given = dict(given or {})
        unknown = sorted(set(given) - set(self.defaults))
        if unknown:
            raise ValueError(f"unknown Babylon.js setting {unknown[0]!r}; known: {', '.join(sorted(self.defaults))}")
        s = {**self.defaults, **given}
        checks = [("numCascades", 2 <= s["numCascades"] <= 4, "a whole number in [2, 4]"),
                  ("lambda", 0 <= s["lambda"] <= 1, "in [0, 1]"),
                  ("bias", s["bias"] >= 0, ">= 0"), ("normalBias", s["normalBias"] >= 0, ">= 0"),
                  ("darkness", s["darkness"] == 0, "0 (modelled)"), ("frustumEdgeFalloff", s["frustumEdgeFalloff"] == 0, "0 (modelled)"),
                  ("depthClamp", s["depthClamp"] is True, "true (the depth-clamped bias is modelled)"),
                  ("autoCalcDepthBounds", s["autoCalcDepthBounds"] is False, "false"),
                  ("filteringQuality", s["filteringQuality"] in (0, 1, 2), "0, 1 or 2 (high, medium, low: PCF5, PCF3, PCF1)"),
                  ("usePercentageCloserFiltering", s["usePercentageCloserFiltering"] is True, "true (modelled)"),
                  ("cascadeBlendPercentage", 0 <= s["cascadeBlendPercentage"] <= 1, "in [0, 1]"),
                  ("mapSize", s["mapSize"] in (256, 512, 1024, 2048, 4096), "a power of two in [256, 4096]")]
        for key, ok, what in checks:
            if not ok:
                raise ValueError(f"{key} must be {what}, got {s[key]!r}")
        return s

    def cast_side(self, s: dict) -> str:
        """The faces drawn into the map: the material's culling (front faces by default), or back faces only."""
        if s["forceBackFacesOnly"]:
            return "back"
        return "front" if s["backFaceCulling"] else "double"

    def shadow_far(self, s: dict, camera) -> float:
        """The last cascade's end [world units]: ``shadowMaxZ`` capped at the camera's far (null: the far)."""
        return float(camera.far if s["shadowMaxZ"] is None else min(s["shadowMaxZ"], camera.far))

    def edges(self, s: dict, camera) -> Array:
        """The cascades' eye depths [world units]: near, then each cascade's end (``_splitFrustum``, blending the
        logarithmic and the uniform split by ``lambda``, :func:`aliasing.setups.babylon.splits`)."""
        starts, ends = babylon_setup.splits({"numCascades": s["numCascades"], "lambda": s["lambda"], "minDistance": 0.0, "maxDistance": 1.0,
                                             "shadowMaxZ": s["shadowMaxZ"]}, camera.near, camera.far)
        return np.concatenate([starts[:1], ends])

    def select(self, s: dict, camera, depth: Array) -> NDArray[np.int64]:
        """lightFragment's loop: the first cascade whose end is at or beyond the eye depth; −1 beyond the last."""
        ends = self.edges(s, camera)[1:]
        idx = np.searchsorted(ends, depth, side="left")
        return np.where(np.isfinite(depth) & (idx < len(ends)), idx, -1).astype(np.int64)

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        """The predicted factor at the engine's pixels (:func:`aliasing.frames.predict.babylon_factor`), and the exact reference."""
        cam = scene.camera
        depth = np.where(rb.drawn, cam.to_eye(np.nan_to_num(rb.position))[..., 2], np.nan)
        sel = self.select(s, cam, depth)
        res = int(s["mapSize"])
        cast = predict.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))], sun, float(s["normalBias"]))
        maps = [predict.light_depth_map(cast, m, res) for m in rb.matrices]
        edges = self.edges(s, cam)
        pct = float(s["cascadeBlendPercentage"])
        pts = np.nan_to_num(rb.position)
        factor = predict.babylon_factor(maps, rb.matrices, sel, depth, pts, ends=edges[1:], lengths=np.diff(edges),
                                        blend_factor=10000.0 if pct == 0 else 1 / pct, bias=float(s["bias"]), quality=int(s["filteringQuality"]))
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)
        # the whole cascade matrices as the engine computes them, in its float32 (ERRATA F6), at the render's aspect
        mats = babylon_cascades.matrices(s, cam, sun, scene.triangles, aspect=rb.shadow.shape[1] / rb.shadow.shape[0])
        sides = babylon_cascades.map_sides(mats)
        return Prediction(factor, sel, edges[:-1], sides, np.full(len(sides), float(res)), mats), ref

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """From the engine's objects: each cascade's first depth (the previous one's view z), its map's larger side, and R."""
        ends = np.array([c["viewZ"] for c in rb.info["cascades"]], float)
        starts = np.concatenate([[camera.near], ends[:-1]])
        return starts, babylon_cascades.map_sides(rb.matrices), rb.sizes[:, 0].astype(float)


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
        from ..setups.playcanvas import splits

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
        atlas = predict.playcanvas_atlas(cast, rb.matrices, self.cells(s), res, float(s["shadowBias"]))
        pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
        factor = predict.playcanvas_factor(atlas, rb.matrices, sel, pts, nrm, normal_offset=float(s["normalOffsetBias"]),
                                           taps=self.FILTERS[int(s["shadowType"])])
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

        Example
        -------
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
        from .. import _validation as check

        sv = check.finite(sun, "sun")
        if sv.shape != (3,) or not np.linalg.norm(sv) > 0:
            raise ValueError(f"sun must be a non-zero 3-vector, got {sv.tolist()}")
        tri = check.finite(triangles, "triangles")
        if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri):
            raise ValueError(f"triangles must have shape (T, 3, 3), T >= 1, got {tri.shape}")
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


MODELS = {"threejs": ThreeCSM(), "babylon": BabylonCSM(), "playcanvas": PlayCanvas()}
#: the engines' single-map classes, by the ``class`` setting
SINGLE = {("threejs", "DirectionalLight"): ThreeDirectional(), ("babylon", "ShadowGenerator"): BabylonSingle()}


def _sun(sun) -> None:
    """Refuse a sun that is not a finite non-zero 3-vector, naming it."""
    sv = check.finite(sun, "sun")
    if sv.shape != (3,) or not np.linalg.norm(sv) > 0:
        raise ValueError(f"sun must be a finite non-zero 3-vector (world direction towards the sun), got shape {sv.shape}")


def model_for(engine: str, settings: dict):
    """The model of ``engine`` for these settings: its single-map class where ``settings["class"]`` names one, else its cascades'.

    Examples
    --------
    >>> type(model_for("threejs", {"class": "DirectionalLight"})).__name__, type(model_for("threejs", {})).__name__
    ('ThreeDirectional', 'ThreeCSM')
    """
    if engine == "filament":
        return FILAMENT
    if engine not in MODELS:
        raise ValueError(f"engine must be one of {', '.join(sorted(MODELS))}, got {engine!r}")
    return SINGLE.get((engine, (settings or {}).get("class")), MODELS[engine])


_THREE_SIDE = {"FrontSide": "front", "BackSide": "back", "DoubleSide": "double"}
_FACES = {"front": "front", "back": "back", "both": "double"}
_PC_TYPES = {"SHADOW_PCF3_32F": 0, "SHADOW_VSM_16F": 2, "SHADOW_VSM_32F": 3, "SHADOW_PCF5_32F": 4, "SHADOW_PCF1_32F": 5, "SHADOW_PCSS_32F": 6,
             "SHADOW_PCF1_16F": 7, "SHADOW_PCF3_16F": 8, "SHADOW_PCF5_16F": 9}
_PC_CULL = {"CULLFACE_BACK": "back", "CULLFACE_FRONT": "front", "CULLFACE_NONE": "none"}


def from_setup(setup) -> dict:
    """The settings the engine's page and the model take, from an :class:`aliasing.setups.Setup`
    (every key in the engine's own spelling, defaults filled), checked against what is rendered
    and modelled here; the pipeline's faces that cast must be the model's.

    Raises
    ------
    ValueError
        A setting the frames do not render or model (its key and why), or a pipeline that
        disagrees with the model about the faces that cast.

    Examples
    --------
    >>> from aliasing import setups
    >>> s = from_setup(setups.build("threejs", {"cascades": 2}, "near=0.5,far=60,fov=50,aspect=16:9,height=144", "35@30"))
    >>> s["cascades"], s["shadowMapSize"], s["side"]
    (2, 2048, 'front')
    """
    if not (hasattr(setup, "settings") and hasattr(setup, "engine") and hasattr(setup, "pipeline")):
        raise ValueError(f"setup must be an aliasing.setups.Setup, got {type(setup).__name__}")
    engine, s = setup.engine, dict(setup.settings)
    if engine == "filament":
        return FILAMENT.from_setup(setup)
    if engine not in MODELS:
        raise ValueError(f"engine must be one of {', '.join(sorted(MODELS))}, got {engine!r}")
    if engine == "threejs" and s["class"] == "DirectionalLight":
        out = {"class": "DirectionalLight", "mapSize": s["shadow.mapSize.width"], "bias": s["shadow.bias"], "normalBias": s["shadow.normalBias"],
               "radius": s["shadow.radius"], "shadowMapType": s["renderer.shadowMap.type"], "side": _THREE_SIDE[s["material.side"]],
               "shadowSide": None if s["material.shadowSide"] == "null" else _THREE_SIDE[s["material.shadowSide"]],
               **{k: s[f"shadow.camera.{k}"] for k in ("left", "right", "top", "bottom", "near", "far")}}
        if out["shadowMapType"] == "PCFSoftShadowMap":  # WebGLShadowMap replaces it (lines 99-102)
            out["shadowMapType"] = "PCFShadowMap"
    elif engine == "threejs":
        if s["class"] != "CSM":
            raise ValueError(f"class must be CSM or DirectionalLight for the frames, got {s['class']!r}")
        if s["shadow.bias"] != 0:
            raise ValueError("shadow.bias is overwritten by CSM's shadowBias on every cascade light: set shadowBias")
        out = {k: s[k] for k in ("cascades", "maxFar", "mode", "shadowMapSize", "shadowBias", "lightNear", "lightFar", "lightMargin", "fade")}
        out.update(normalBias=s["shadow.normalBias"], shadowRadius=s["shadow.radius"], shadowMapType=s["renderer.shadowMap.type"],
                   side=_THREE_SIDE[s["material.side"]], shadowSide=None if s["material.shadowSide"] == "null" else _THREE_SIDE[s["material.shadowSide"]])
        if out["shadowMapType"] == "PCFSoftShadowMap":  # WebGLShadowMap replaces it (lines 99-102)
            out["shadowMapType"] = "PCFShadowMap"
    elif engine == "babylon" and s["class"] == "ShadowGenerator":
        if s["filter"] not in (None, "FILTER_NONE"):
            raise ValueError(f"filter must be null or FILTER_NONE for a ShadowGenerator's frames (modelled), got {s['filter']!r}")
        for key, want in (("darkness", 0.0), ("frustumEdgeFalloff", 0.0)):
            if s[key] != want:
                raise ValueError(f"{key} must be {want!r} for the frames (modelled), got {s[key]!r}")
        if s["material.backFaceCulling"] != s["material.cullBackFaces"] and not s["material.cullBackFaces"]:
            raise ValueError("material.cullBackFaces false (front faces culled) is not rendered by the frames")
        out = {"class": "ShadowGenerator", "mapSize": s["mapSize"], "bias": s["bias"], "normalBias": s["normalBias"],
               "shadowFrustumSize": s["light.shadowFrustumSize"], "shadowMinZ": s["light.shadowMinZ"], "shadowMaxZ": s["light.shadowMaxZ"],
               "forceBackFacesOnly": s["forceBackFacesOnly"], "backFaceCulling": s["material.backFaceCulling"]}
    elif engine == "babylon":
        if s["class"] != "CascadedShadowGenerator":
            raise ValueError(f"class must be CascadedShadowGenerator or ShadowGenerator for the frames, got {s['class']!r}")
        for key, want in (("filter", None), ("minDistance", 0.0), ("maxDistance", 1.0), ("light.shadowMinZ", None), ("light.shadowMaxZ", None),
                          ("light.shadowFrustumSize", 0.0)):
            if s[key] != want:
                raise ValueError(f"{key} must be {want!r} for the frames (modelled), got {s[key]!r}")
        out = {k: s[k] for k in ("mapSize", "numCascades", "lambda", "bias", "normalBias", "frustumEdgeFalloff", "stabilizeCascades",
                                 "cascadeBlendPercentage", "depthClamp", "autoCalcDepthBounds", "shadowMaxZ", "forceBackFacesOnly")}
        out["filteringQuality"] = {"QUALITY_HIGH": 0, "QUALITY_MEDIUM": 1, "QUALITY_LOW": 2}[s["filteringQuality"]]
        if s["material.backFaceCulling"] != s["material.cullBackFaces"] and not s["material.cullBackFaces"]:
            raise ValueError("material.cullBackFaces false (front faces culled) is not rendered by the frames")
        out["backFaceCulling"] = s["material.backFaceCulling"]
    else:
        out = {k: s[k] for k in ("shadowBias", "normalOffsetBias", "shadowResolution", "numCascades", "cascadeDistribution", "cascadeBlend",
                                 "shadowDistance")}
        out["shadowType"] = _PC_TYPES[s["shadowType"]]
        out["cull"] = _PC_CULL[s["material.cull"]]
    model = model_for(engine, out)
    full = model.settings(out)
    if getattr(model, "predicts", True):
        faces = _FACES[setup.pipeline.bias.faces]
        if faces != model.cast_side(full):
            raise ValueError(f"the setup's pipeline casts {setup.pipeline.bias.faces} faces, the frames' model {model.cast_side(full)}")
    return full


FILAMENT = Filament()
