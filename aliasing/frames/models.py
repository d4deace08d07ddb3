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
from ..engines import stable
from . import predict

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Prediction:
    """Per pixel: the predicted ``factor`` and ``cascade``; per cascade: ``starts`` [world units] and map ``sides`` [world units]."""

    factor: Array
    cascade: NDArray[np.int64]
    starts: Array
    sides: Array
    resolution: Array


def tight_sides(camera, edges: Array, along: Array, up: Array) -> Array:
    """Per cascade: the larger side [world units] of the slice corners' box in a light frame whose x axis is ``up`` × ``along``.

    The tight fit's box depends on the light frame's roll about the light direction, which an
    engine takes from a world up vector (Babylon.js: ``Matrix.LookAtLH(centre, centre + d, Vector3.Up())``),
    not from the camera: the extents are measured on x ∝ up × d and y ∝ d × x (signs do not
    change extents; the mirror into Babylon's left-handed world neither).
    """
    d = along / np.linalg.norm(along)
    x = np.cross(up, d)
    x /= np.linalg.norm(x)
    y = np.cross(d, x)
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        corners = camera.view.slice_vertices(a, b)  # eye space (8, 3)
        world = corners @ camera.rotation + camera.eye
        out.append(max(np.ptp(world @ x), np.ptp(world @ y)))
    return np.array(out)


@dataclass(frozen=True)
class ThreeCSM:
    """three.js r187, WebGLRenderer with the CSM addon (examples/jsm/csm/CSM.js, CSMShader.js).

    Settings (the engine's own keys): CSM's ``cascades``, ``maxFar``, ``mode``,
    ``shadowMapSize``, ``shadowBias``, ``lightIntensity``, ``lightNear``, ``lightFar``,
    ``lightMargin``, ``fade``; each cascade light's shadow ``normalBias`` and ``shadowRadius``
    (``light.shadow.radius``); the renderer's ``shadowMapType``; the material's ``side`` and
    ``shadowSide`` (null: the opposite of ``side``, WebGLShadowMap's ``shadowSide`` table).
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
class ThreeDirectional:
    """three.js r187, one ``DirectionalLight`` shadow (src/lights/DirectionalLightShadow.js, LightShadow.js).

    Settings (the page's keys for the light's own): ``class`` ("DirectionalLight"), the shadow
    camera's ``left``, ``right``, ``top``, ``bottom``, ``near``, ``far`` (an orthographic box
    [world units]), ``mapSize`` (square), ``bias``, ``normalBias``, ``radius``; the renderer's
    ``shadowMapType``; the material's ``side`` and ``shadowSide``.  The frames place the light's
    target at :func:`aliasing.frames.run.light_target` and the light (near + far)/2 from it
    towards the sun.  The factor is :func:`aliasing.frames.predict.threejs_factor` of the one
    map (``shadow.bias`` as CSM's ``shadowBias``: added to the normalized map depth).
    """

    engine: str = "threejs"
    defaults: dict = field(default_factory=lambda: {
        "class": "DirectionalLight", "left": -5.0, "right": 5.0, "top": 5.0, "bottom": -5.0, "near": 0.5, "far": 500.0, "mapSize": 512,
        "bias": 0.0, "normalBias": 0.0, "radius": 1.0, "shadowMapType": "PCFShadowMap", "side": "front", "shadowSide": None})

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in (``DirectionalLightShadow``'s camera, ``LightShadow``'s bias, radius and map size)."""
        given = dict(given or {})
        unknown = sorted(set(given) - set(self.defaults))
        if unknown:
            raise ValueError(f"unknown three.js DirectionalLight setting {unknown[0]!r}; known: {', '.join(sorted(self.defaults))}")
        s = {**self.defaults, **given}
        if s["class"] != "DirectionalLight":
            raise ValueError(f"class must be DirectionalLight, got {s['class']!r}")
        if not (s["right"] > s["left"] and s["top"] > s["bottom"] and s["far"] > s["near"] >= 0):
            raise ValueError("the shadow camera must have right > left, top > bottom and far > near >= 0")
        if int(s["mapSize"]) != s["mapSize"] or not 16 <= s["mapSize"] <= 8192:
            raise ValueError(f"mapSize must be a whole number of texels in [16, 8192], got {s['mapSize']!r}")
        if s["shadowMapType"] not in ("PCFShadowMap", "BasicShadowMap"):
            raise ValueError(f"shadowMapType must be PCFShadowMap or BasicShadowMap (the filters modelled), got {s['shadowMapType']!r}")
        if s["side"] not in predict.SIDES or (s["shadowSide"] is not None and s["shadowSide"] not in predict.SIDES):
            raise ValueError(f"side and shadowSide must be one of {', '.join(predict.SIDES)} (shadowSide also null)")
        return s

    cast_side = ThreeCSM.cast_side

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        """The predicted factor of the one map at the engine's pixels (cascade 0 for every drawn pixel), and the exact reference."""
        cam = scene.camera
        sel = np.where(rb.drawn, 0, -1).astype(np.int64)
        res = int(s["mapSize"])
        cast = scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))]
        maps = [predict.light_depth_map(cast, rb.matrices[0], res)]
        h, w = rb.shadow.shape
        fy, fx = np.mgrid[0:h, 0:w]
        pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
        factor = predict.threejs_factor(maps, rb.matrices[:1], sel, pts, nrm, fx + 0.5, (h - 1 - fy) + 0.5, bias=float(s["bias"]),
                                        normal_bias=float(s["normalBias"]), radius=float(s["radius"]), map_type=s["shadowMapType"])
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)
        side = max(s["right"] - s["left"], s["top"] - s["bottom"])
        return Prediction(factor, sel, np.array([cam.near]), np.array([float(side)]), np.array([float(res)])), ref

    def matrices(self, s: dict, camera, sun: Array) -> Array:
        """The shadow matrix (world → [0, 1]³) as ``LightShadow.updateMatrices`` builds it: the camera at the light,
        ``lookAt`` its target with up +y (``Matrix4.lookAt``'s nudge of z when up ∥ z), the orthographic box, [½ bias]."""
        from .run import light_target

        target = light_target(camera)
        sv = np.asarray(sun, float) / np.linalg.norm(sun)
        eye = target + sv * (s["near"] + s["far"]) / 2
        z = eye - target
        z /= np.linalg.norm(z)
        up = np.array([0.0, 1.0, 0.0])
        x = np.cross(up, z)
        if np.dot(x, x) == 0:  # Matrix4.lookAt: up parallel to z
            z = z + np.array([0.0, 0.0, 0.0001])
            z /= np.linalg.norm(z)
            x = np.cross(up, z)
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        basis = np.stack([x, y, z])
        view = np.eye(4)
        view[:3, :3] = basis
        view[:3, 3] = -basis @ eye
        l, r, t, b, n, f = (float(s[k]) for k in ("left", "right", "top", "bottom", "near", "far"))
        proj = np.array([[2 / (r - l), 0, 0, -(r + l) / (r - l)], [0, 2 / (t - b), 0, -(t + b) / (t - b)],
                         [0, 0, -2 / (f - n), -(f + n) / (f - n)], [0, 0, 0, 1.0]])
        half = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
        return (half @ proj @ view)[None]

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """The one map: the camera's near, the matrix's larger texel side × R, and R."""
        m = rb.matrices[0]
        side = max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3]))
        return np.array([camera.near]), np.array([side]), rb.sizes[:1, 0].astype(float)


@dataclass(frozen=True)
class BabylonCSM:
    """Babylon.js 9.35, CascadedShadowGenerator on a DirectionalLight (Lights/Shadows/cascadedShadowGenerator.pure.js).

    Settings (the engine's own keys): the generator's ``mapSize`` (its constructor's first
    argument), ``numCascades``, ``lambda``, ``bias``, ``normalBias``, ``darkness``,
    ``frustumEdgeFalloff``, ``stabilizeCascades``, ``cascadeBlendPercentage``, ``depthClamp``,
    ``autoCalcDepthBounds``, ``shadowMaxZ`` (null: the camera's far), ``filteringQuality``,
    ``usePercentageCloserFiltering``, ``forceBackFacesOnly``; the material's ``backFaceCulling``.
    """

    engine: str = "babylon"
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
                  ("lambda", s["lambda"] == 0.5, "0.5 (the split the toolkit's babylon preset models)"),
                  ("bias", s["bias"] >= 0, ">= 0"), ("normalBias", s["normalBias"] >= 0, ">= 0"),
                  ("darkness", s["darkness"] == 0, "0 (modelled)"), ("frustumEdgeFalloff", s["frustumEdgeFalloff"] == 0, "0 (modelled)"),
                  ("depthClamp", s["depthClamp"] is True, "true (the depth-clamped bias is modelled)"),
                  ("autoCalcDepthBounds", s["autoCalcDepthBounds"] is False, "false"),
                  ("filteringQuality", s["filteringQuality"] == 0, "0, high quality (PCF5, modelled)"),
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
        return float(camera.far if s["shadowMaxZ"] is None else min(s["shadowMaxZ"], camera.far))

    def edges(self, s: dict, camera) -> Array:
        return partitioning.split_distances("babylon", camera.near, self.shadow_far(s, camera), int(s["numCascades"]))

    def select(self, s: dict, camera, depth: Array) -> NDArray[np.int64]:
        """lightFragment's loop: the first cascade whose end is at or beyond the eye depth; −1 beyond the last."""
        ends = self.edges(s, camera)[1:]
        idx = np.searchsorted(ends, depth, side="left")
        return np.where(np.isfinite(depth) & (idx < len(ends)), idx, -1).astype(np.int64)

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        cam = scene.camera
        depth = np.where(rb.drawn, cam.to_eye(np.nan_to_num(rb.position))[..., 2], np.nan)
        sel = self.select(s, cam, depth)
        res = int(s["mapSize"])
        cast = predict.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))], sun, float(s["normalBias"]))
        maps = [predict.light_depth_map(cast, m, res) for m in rb.matrices]
        edges = self.edges(s, cam)
        pct = float(s["cascadeBlendPercentage"])
        pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
        factor = predict.babylon_factor(maps, rb.matrices, sel, depth, pts, ends=edges[1:], lengths=np.diff(edges),
                                        blend_factor=10000.0 if pct == 0 else 1 / pct, bias=float(s["bias"]))
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)
        if s["stabilizeCascades"]:
            p = stable.PRESETS["babylon"]
            box = stable.evaluate(edges, cam.near, edges[-1], cam.fov, cam.direction_to_eye(sun)[None], aspect=cam.aspect, fit=p.fit, snap=p.snap,
                                  resolution=float(res))
            sides = np.maximum(box.width_x[0], box.width_y[0])
        else:
            sides = tight_sides(cam, edges, -sun, np.array([0.0, 1.0, 0.0]))
        return Prediction(factor, sel, edges[:-1], sides, np.full(len(sides), float(res))), ref

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """From the engine's objects: each cascade's first depth (the previous one's view z), its map's larger side, and R."""
        ends = np.array([c["viewZ"] for c in rb.info["cascades"]], float)
        starts = np.concatenate([[camera.near], ends[:-1]])
        sides = np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3])) for m in rb.matrices])
        return starts, sides, rb.sizes[:, 0].astype(float)


@dataclass(frozen=True)
class BabylonSingle:
    """Babylon.js 9.35, one ShadowGenerator of a DirectionalLight with a fixed box (Lights/Shadows/shadowGenerator.js).

    Settings: ``class`` ("ShadowGenerator"), ``mapSize``, ``bias``, ``normalBias``,
    ``shadowFrustumSize`` (the light's square box side > 0 [world units]), ``shadowMinZ`` and
    ``shadowMaxZ`` (null: the camera's near and far), ``forceBackFacesOnly``; the material's
    ``backFaceCulling``.  FILTER_NONE (the class's default) is the filter modelled.  The frames
    place the light (minZ + maxZ)/2 from :func:`aliasing.frames.run.light_target` towards the sun.
    """

    engine: str = "babylon"
    defaults: dict = field(default_factory=lambda: {
        "class": "ShadowGenerator", "mapSize": 1024, "bias": 0.00005, "normalBias": 0.0, "shadowFrustumSize": 20.0, "shadowMinZ": None,
        "shadowMaxZ": None, "forceBackFacesOnly": False, "backFaceCulling": True})

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in (the generator's constructor; the box side has no engine default > 0)."""
        given = dict(given or {})
        unknown = sorted(set(given) - set(self.defaults))
        if unknown:
            raise ValueError(f"unknown Babylon.js ShadowGenerator setting {unknown[0]!r}; known: {', '.join(sorted(self.defaults))}")
        s = {**self.defaults, **given}
        if s["class"] != "ShadowGenerator":
            raise ValueError(f"class must be ShadowGenerator, got {s['class']!r}")
        if not s["shadowFrustumSize"] > 0:
            raise ValueError(f"shadowFrustumSize must be > 0 [world units] (a fixed box), got {s['shadowFrustumSize']!r}")
        if s["mapSize"] not in (256, 512, 1024, 2048, 4096):
            raise ValueError(f"mapSize must be a power of two in [256, 4096], got {s['mapSize']!r}")
        if not (s["bias"] >= 0 and s["normalBias"] >= 0):
            raise ValueError("bias and normalBias must be >= 0")
        return s

    cast_side = BabylonCSM.cast_side

    def depth_range(self, s: dict, camera) -> tuple[float, float]:
        """The light's depth near and far [world units]: shadowMinZ/shadowMaxZ, else the camera's."""
        lo = camera.near if s["shadowMinZ"] is None else float(s["shadowMinZ"])
        hi = camera.far if s["shadowMaxZ"] is None else float(s["shadowMaxZ"])
        if not hi > lo:
            raise ValueError(f"shadowMaxZ must exceed shadowMinZ ({lo:g}), got {hi:g}")
        return lo, hi

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        cam = scene.camera
        sel = np.where(rb.drawn, 0, -1).astype(np.int64)
        res = int(s["mapSize"])
        cast = predict.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))], sun, float(s["normalBias"]))
        dm = predict.light_depth_map(cast, rb.matrices[0], res)
        factor = predict.babylon_single_factor(dm, rb.matrices[0], np.nan_to_num(rb.position), bias=float(s["bias"]))
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)
        return Prediction(factor, sel, np.array([cam.near]), np.array([float(s["shadowFrustumSize"])]), np.array([float(res)])), ref

    def matrices(self, s: dict, camera, sun: Array) -> Array:
        """World → [0, 1]³ in the job's (right-handed) world: ``Matrix.LookAtLH(position, position + d, Up)`` and
        ``OrthoLH(size, size, minZ, maxZ)`` in Babylon's mirrored world (z ↦ −z), window depth (z + 1)/2."""
        from .run import light_target

        lo, hi = self.depth_range(s, camera)
        mirror = np.diag([1.0, 1.0, -1.0])
        sv = np.asarray(sun, float) / np.linalg.norm(sun)
        eye = mirror @ (light_target(camera) + sv * (lo + hi) / 2)
        d = mirror @ -sv
        if abs(abs(d[1]) - 1.0) == 0:  # ShadowGenerator: a light straight along Up gets z = 1e-13
            d = np.array([d[0], d[1], 1e-13])
        z = d / np.linalg.norm(d)
        x = np.cross([0.0, 1.0, 0.0], z)
        x /= np.linalg.norm(x)
        y = np.cross(z, x)
        view = np.eye(4)
        view[:3, :3] = np.stack([x, y, z]) @ mirror
        view[:3, 3] = -np.stack([x, y, z]) @ eye
        size = float(s["shadowFrustumSize"])
        proj = np.diag([2 / size, 2 / size, 2 / (hi - lo), 1.0])
        proj[2, 3] = -(hi + lo) / (hi - lo)
        half = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
        return (half @ proj @ view)[None]

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """The one map: the camera's near, the matrix's larger texel side × R, and R."""
        m = rb.matrices[0]
        return np.array([camera.near]), np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3]))]), rb.sizes[:1, 0].astype(float)


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
    rendered but not predicted.
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

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """Each cascade's first depth (the previous cascade's distance), its larger texel side × R (R the atlas's side) and R."""
        ends = np.array([c["distance"] for c in rb.info["cascades"]], float)
        starts = np.concatenate([[camera.near], ends[:-1]])
        sides = np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3])) for m in rb.matrices])
        return starts, sides, rb.sizes[:, 0].astype(float)


def reference(scene, sun: Array, rb, resolution: int) -> NDArray[np.bool_]:
    """The exact reference's lit pixels, through the matrix of the cascade each pixel sampled (the last one where none)."""
    pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
    ref = np.ones(rb.shadow.shape, bool)
    for i, m in enumerate(rb.matrices):
        here = rb.drawn & ((rb.cascade == i) | ((rb.cascade < 0) & (i == len(rb.matrices) - 1)))
        if here.any():
            ref[here] = predict.reference_lit(scene.triangles, m, resolution, pts[here], nrm[here], sun)
    return ref & rb.drawn & ((nrm @ sun) > 0)


MODELS = {"threejs": ThreeCSM(), "babylon": BabylonCSM(), "playcanvas": PlayCanvas()}
#: the engines' single-map classes, by the ``class`` setting
SINGLE = {("threejs", "DirectionalLight"): ThreeDirectional(), ("babylon", "ShadowGenerator"): BabylonSingle()}


def model_for(engine: str, settings: dict):
    """The model of ``engine`` for these settings: its single-map class where ``settings["class"]`` names one, else its cascades'.

    Example
    -------
    >>> type(model_for("threejs", {"class": "DirectionalLight"})).__name__, type(model_for("threejs", {})).__name__
    ('ThreeDirectional', 'ThreeCSM')
    """
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
    """
    engine, s = setup.engine, dict(setup.settings)
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
