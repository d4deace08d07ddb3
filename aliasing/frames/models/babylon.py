"""Babylon.js 9.35's CascadedShadowGenerator: its settings and the toolkit's model (:class:`BabylonCSM`), and the tight fit's map sides (:func:`tight_sides`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ... import _validation as check
from ...setups import babylon as babylon_setup
from .. import babylon_cascades, predict
from ..lightmaps.depth import SUBPIXEL_BITS
from ..predict import Prediction, reference

Array = NDArray[np.float64]


def tight_sides(camera, edges: Array, along: Array, up: Array) -> Array:
    """Per cascade: the larger side [world units] of the slice corners' box in a light frame whose x axis is ``up`` × ``along``.

    The tight fit's box depends on the light frame's roll about the light direction, which an
    engine takes from a world up vector (Babylon.js: ``Matrix.LookAtLH(centre, centre + d, Vector3.Up())``),
    not from the camera: the extents are measured on x ∝ up × d and y ∝ d × x (signs do not
    change extents; the mirror into Babylon's left-handed world neither).

    Examples
    --------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> cam = look_at("0,0,0", "0,0,-1", fov=90.0)              # aspect 1
    >>> tight_sides(cam, np.array([1.0, 2.0]), np.array([0.0, -1.0, 0.0]), np.array([0.0, 0.0, 1.0])).tolist()   # from above: the far end's width
    [4.0]
    """
    edges = check.finite(edges, "edges")
    if edges.ndim != 1 or len(edges) < 2 or not np.all(np.diff(edges) > 0):
        raise ValueError(f"edges must be an increasing 1-d array of at least 2 depths [world units], got {edges.tolist()}")
    along, up = check.finite(along, "along"), check.finite(up, "up")
    if along.shape != (3,) or up.shape != (3,) or not np.linalg.norm(np.cross(up, along)) > 0:
        raise ValueError("along and up must be non-zero 3-vectors that are not parallel")
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
        cast = babylon_cascades.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))], sun, float(s["normalBias"]))
        maps = [predict.sampled_depth_map(cast, m, res, SUBPIXEL_BITS) for m in rb.matrices]  # drawn where the pixels read them, corners as SwiftShader snaps them
        edges = self.edges(s, cam)
        pct = float(s["cascadeBlendPercentage"])
        pts = np.nan_to_num(rb.position)
        factor = predict.gathered(lambda: predict.babylon_factor(
            maps, rb.matrices, sel, depth, pts, ends=edges[1:], lengths=np.diff(edges), blend_factor=10000.0 if pct == 0 else 1 / pct,
            bias=float(s["bias"]), quality=int(s["filteringQuality"])), maps)
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
