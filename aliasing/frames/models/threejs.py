"""three.js r187's CSM addon: its settings and the toolkit's model of its shadow pass (:class:`ThreeCSM`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ... import partitioning
from ... import _validation as check
from ...engines import stable
from .. import predict
from ..lightmaps.depth import SUBPIXEL_BITS
from ..predict import Prediction, reference

Array = NDArray[np.float64]


def _sun(sun) -> None:
    """Refuse a sun that is not a finite non-zero 3-vector, naming it."""
    check.direction(sun)


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
        maps = [predict.sampled_depth_map(cast, m, res, SUBPIXEL_BITS) for m in rb.matrices]  # drawn where the pixels read them, corners as SwiftShader snaps them
        h, w = depth.shape
        fy, fx = np.mgrid[0:h, 0:w]
        gl_y = (h - 1 - fy) + 0.5
        pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
        factor = predict.gathered(lambda: predict.threejs_factor(
            maps, rb.matrices, sel, pts, nrm, fx + 0.5, gl_y, bias=float(s["shadowBias"]), normal_bias=float(s["normalBias"]),
            radius=float(s["shadowRadius"]), map_type=s["shadowMapType"]), maps)
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
        from ...engines.stable import diagonal

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
