"""The engines' single-map classes: three.js's ``DirectionalLight`` and Babylon.js's ``ShadowGenerator`` with a fixed box;
and Filament's directional light, rendered and measured only (:class:`Filament`).

Each draws one shadow map through a box the user sets, placed by the frames at a light looking at
:func:`aliasing.frames.scenes.light_target`; the models have the cascaded models' methods
(:mod:`aliasing.frames.models`), and :func:`aliasing.frames.models.model_for` picks them by the
``class`` setting.

Examples
--------
>>> ThreeDirectional().settings({"left": -10, "right": 10})["top"]
5.0
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from ..raster.draw import DepthMap
from . import babylon_cascades, predict
from .predict import Prediction, reference, to_map

Array = NDArray[np.float64]


@dataclass(frozen=True)
class ThreeDirectional:
    """three.js r187, one ``DirectionalLight`` shadow (src/lights/DirectionalLightShadow.js, LightShadow.js).

    Settings (the page's keys for the light's own): ``class`` ("DirectionalLight"), the shadow
    camera's ``left``, ``right``, ``top``, ``bottom``, ``near``, ``far`` (an orthographic box
    [world units]), ``mapSize`` (square), ``bias``, ``normalBias``, ``radius``; the renderer's
    ``shadowMapType``; the material's ``side`` and ``shadowSide``.  The frames place the light's
    target at :func:`aliasing.frames.scenes.light_target` and the light (near + far)/2 from it
    towards the sun.  The factor is :func:`aliasing.frames.predict.threejs_factor` of the one
    map (``shadow.bias`` as CSM's ``shadowBias``: added to the normalized map depth).

    Parameters
    ----------
    engine : str
        "threejs".
    defaults : dict
        The light's defaults (box [world units], ``mapSize`` [texels], biases as the engine takes them).

    Examples
    --------
    >>> m = ThreeDirectional()
    >>> s = m.settings({"mapSize": 1024})
    >>> m.cast_side(s), s["right"] - s["left"]            # back faces cast; the box 10 wide [world units]
    ('back', 10.0)
    """

    engine: str = "threejs"
    defaults: dict = field(default_factory=lambda: {
        "class": "DirectionalLight", "left": -5.0, "right": 5.0, "top": 5.0, "bottom": -5.0, "near": 0.5, "far": 500.0, "mapSize": 512,
        "bias": 0.0, "normalBias": 0.0, "radius": 1.0, "shadowMapType": "PCFShadowMap", "side": "front", "shadowSide": None})

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in (``DirectionalLightShadow``'s camera, ``LightShadow``'s bias, radius and map size).

        Parameters
        ----------
        given : dict, optional
            Settings in the engine's own keys (units as the engine takes them).

        Returns
        -------
        dict
            Every setting.

        Raises
        ------
        ValueError
            An unknown key, or a value outside what is rendered and modelled (the key and its allowed values).

        Examples
        --------
        >>> ThreeDirectional().settings({"left": 5.0})
        Traceback (most recent call last):
        ...
        ValueError: the shadow camera must have right > left, top > bottom and far > near >= 0
        """
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

    def cast_side(self, s: dict) -> str:
        """The faces drawn into the map: ``shadowSide``, or the opposite of ``side`` (WebGLShadowMap's table, as for CSM).

        Parameters
        ----------
        s : dict
            The filled settings.

        Returns
        -------
        str
            "front", "back" or "double" (as seen from the sun).

        Examples
        --------
        >>> m = ThreeDirectional()
        >>> m.cast_side(m.settings({"side": "back"})), m.cast_side(m.settings({"shadowSide": "double"}))
        ('front', 'double')
        """
        if s["shadowSide"] is not None:
            return s["shadowSide"]
        return {"front": "back", "back": "front", "double": "double"}[s["side"]]

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        """The predicted factor of the one map at the engine's pixels (cascade 0 for every drawn pixel), and the exact reference.

        Parameters
        ----------
        s : dict
            The filled settings (:meth:`settings`).
        scene : FrameScene
            The scene drawn (:func:`aliasing.frames.scenes.frame_scene`).
        sun : array_like (3,)
            World unit direction towards the sun.
        rb : Readback
            The engine's pixels: positions [world units], normals, matrices, map sizes [texels].

        Returns
        -------
        Prediction
            Factor [fraction of the sun's light] and cascade per pixel; starts, sides [world units] and resolution [texels] per cascade.
        ndarray of bool (H, W)
            The exact reference's lit pixels.

        Examples
        --------
        >>> from aliasing.frames.readback import Readback
        >>> from aliasing.frames.scenes import frame_scene, sun_direction
        >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=1.0, boxes=2, ground_cells=2)
        >>> sun = sun_direction(20.0, 30.0, fs.camera)
        >>> pts = np.array([[[-2.0, -1.0, -4.25], [0.0, -1.0, -12.0]]])        # two ground pixels: in a box's shadow, lit
        >>> def rb(mats):                                                       # what a page would read back there
        ...     return Readback("", "", np.ones((1, 2)), np.zeros((1, 2), np.int64), pts, np.array([[[0.0, 1.0, 0.0]] * 2]),
        ...                     mats, np.full((len(mats), 2), 256), {}, b"")
        >>> m = ThreeDirectional(); s = m.settings({"left": -15, "right": 15, "top": 15, "bottom": -15, "mapSize": 256})
        >>> pred, ref = m.predict(s, fs, sun, rb(m.matrices(s, fs.camera, sun)))
        >>> pred.cascade.tolist(), (pred.factor < 0.5).tolist(), ref.tolist()
        ([[0, 0]], [[True, False]], [[False, True]])
        """
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
        ``lookAt`` its target with up +y (``Matrix4.lookAt``'s nudge of z when up ∥ z), the orthographic box, [½ bias].

            Parameters
            ----------
            s : dict
                The filled settings.
            camera : aliasing.raster.scenes.camera.Camera
                The eye camera (it places the light's target, :func:`aliasing.frames.scenes.light_target`).
            sun : array_like (3,)
                World direction towards the sun, non-zero.

            Returns
            -------
            ndarray (1, 4, 4)
                World → (s, t, depth) in [0, 1]³ (column vectors).

        Examples
        --------
        >>> from aliasing.raster.scenes.camera import look_at
        >>> cam = look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
        >>> m = ThreeDirectional().matrices(ThreeDirectional().settings(), cam, np.array([0.0, 1.0, 0.0]))   # the sun overhead
        >>> np.round(m[0] @ [0.0, 0.0, -50.5, 1.0], 6).tolist()    # the target: the box's centre, half way in depth
        [0.5, 0.5, 0.5, 1.0]
        """
        check.direction(sun)
        from .scenes import light_target

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
        """The one map: the camera's near, the matrix's larger texel side × R, and R.

        Parameters
        ----------
        s : dict
            The filled settings.
        camera : aliasing.raster.scenes.camera.Camera
            The eye camera.
        rb : Readback
            The engine's read-back (its matrices, map sizes and info).

        Returns
        -------
        starts, sides, resolution : ndarray (k,)
            First eye depth [world units], map side [world units], map side [texels].

        Examples
        --------
        >>> from aliasing.raster.scenes.camera import look_at
        >>> cam = look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
        >>> from aliasing.frames.readback import Readback
        >>> rb = Readback("", "", np.ones((1, 1)), np.zeros((1, 1), np.int64), np.zeros((1, 1, 3)), np.zeros((1, 1, 3)),
        ...               np.diag([0.1, 0.1, 0.01, 1.0])[None], np.array([[1024, 1024]]), {}, b"")   # a 10 × 10 box
        >>> [v.tolist() for v in ThreeDirectional().measured_cascades(ThreeDirectional().settings(), cam, rb)]
        [[1.0], [10.0], [1024.0]]
        """
        m = rb.matrices[0]
        side = max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3]))
        return np.array([camera.near]), np.array([side]), rb.sizes[:1, 0].astype(float)


@dataclass(frozen=True)
class BabylonSingle:
    """Babylon.js 9.35, one ShadowGenerator of a DirectionalLight with a fixed box (Lights/Shadows/shadowGenerator.js).

    Settings: ``class`` ("ShadowGenerator"), ``mapSize``, ``bias``, ``normalBias``,
    ``shadowFrustumSize`` (the light's square box side > 0 [world units]), ``shadowMinZ`` and
    ``shadowMaxZ`` (null: the camera's near and far), ``forceBackFacesOnly``; the material's
    ``backFaceCulling``.  FILTER_NONE (the class's default) is the filter modelled.  The frames
    place the light (minZ + maxZ)/2 from :func:`aliasing.frames.scenes.light_target` towards the sun.

    Parameters
    ----------
    engine : str
        "babylon".
    defaults : dict
        The generator's defaults (``mapSize`` [texels], ``shadowFrustumSize`` [world units], biases as the engine takes them).

    Examples
    --------
    >>> m = BabylonSingle()
    >>> s = m.settings({"shadowFrustumSize": 30.0})
    >>> m.cast_side(s), s["mapSize"]
    ('front', 1024)
    """

    engine: str = "babylon"
    defaults: dict = field(default_factory=lambda: {
        "class": "ShadowGenerator", "mapSize": 1024, "bias": 0.00005, "normalBias": 0.0, "shadowFrustumSize": 20.0, "shadowMinZ": None,
        "shadowMaxZ": None, "forceBackFacesOnly": False, "backFaceCulling": True})

    def settings(self, given: dict | None = None) -> dict:
        """Every setting, the defaults filled in (the generator's constructor; the box side has no engine default > 0).

        Parameters
        ----------
        given : dict, optional
            Settings in the engine's own keys (units as the engine takes them).

        Returns
        -------
        dict
            Every setting.

        Raises
        ------
        ValueError
            An unknown key, or a value outside what is rendered and modelled (the key and its allowed values).

        Examples
        --------
        >>> BabylonSingle().settings({"shadowFrustumSize": 0})
        Traceback (most recent call last):
        ...
        ValueError: shadowFrustumSize must be > 0 [world units] (a fixed box), got 0
        """
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

    def cast_side(self, s: dict) -> str:
        """The faces drawn into the map: the material's culling (front faces by default), or back faces only.

        Parameters
        ----------
        s : dict
            The filled settings.

        Returns
        -------
        str
            "front", "back" or "double" (as seen from the sun).

        Examples
        --------
        >>> BabylonSingle().cast_side(BabylonSingle().settings({"backFaceCulling": False}))
        'double'
        """
        if s["forceBackFacesOnly"]:
            return "back"
        return "front" if s["backFaceCulling"] else "double"

    def depth_range(self, s: dict, camera) -> tuple[float, float]:
        """The light's depth near and far [world units]: shadowMinZ/shadowMaxZ, else the camera's.

        Parameters
        ----------
        s : dict
            The filled settings.
        camera : aliasing.raster.scenes.camera.Camera
            The eye camera (its near and far [world units]).

        Returns
        -------
        tuple of float
            (near, far) [world units], far > near.

        Examples
        --------
        >>> from aliasing.raster.scenes.camera import look_at
        >>> cam = look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
        >>> BabylonSingle().depth_range(BabylonSingle().settings({"shadowMaxZ": 50.0}), cam)
        (1.0, 50.0)
        """
        lo = camera.near if s["shadowMinZ"] is None else float(s["shadowMinZ"])
        hi = camera.far if s["shadowMaxZ"] is None else float(s["shadowMaxZ"])
        if not hi > lo:
            raise ValueError(f"shadowMaxZ must exceed shadowMinZ ({lo:g}), got {hi:g}")
        return lo, hi

    def predict(self, s: dict, scene, sun: Array, rb) -> tuple[Prediction, NDArray[np.bool_]]:
        """The predicted factor of the one map (:func:`babylon_single_factor`), and the exact reference.

        Parameters
        ----------
        s : dict
            The filled settings (:meth:`settings`).
        scene : FrameScene
            The scene drawn (:func:`aliasing.frames.scenes.frame_scene`).
        sun : array_like (3,)
            World unit direction towards the sun.
        rb : Readback
            The engine's pixels: positions [world units], normals, matrices, map sizes [texels].

        Returns
        -------
        Prediction
            Factor [fraction of the sun's light] and cascade per pixel; starts, sides [world units] and resolution [texels] per cascade.
        ndarray of bool (H, W)
            The exact reference's lit pixels.

        Examples
        --------
        >>> from aliasing.frames.readback import Readback
        >>> from aliasing.frames.scenes import frame_scene, sun_direction
        >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=1.0, boxes=2, ground_cells=2)
        >>> sun = sun_direction(20.0, 30.0, fs.camera)
        >>> pts = np.array([[[-2.0, -1.0, -4.25], [0.0, -1.0, -12.0]]])        # two ground pixels: in a box's shadow, lit
        >>> def rb(mats):                                                       # what a page would read back there
        ...     return Readback("", "", np.ones((1, 2)), np.zeros((1, 2), np.int64), pts, np.array([[[0.0, 1.0, 0.0]] * 2]),
        ...                     mats, np.full((len(mats), 2), 256), {}, b"")
        >>> m = BabylonSingle(); s = m.settings({"shadowFrustumSize": 30.0, "mapSize": 256})
        >>> pred, ref = m.predict(s, fs, sun, rb(m.matrices(s, fs.camera, sun)))
        >>> pred.factor.tolist(), ref.tolist()
        ([[0.0, 1.0]], [[False, True]])
        """
        cam = scene.camera
        sel = np.where(rb.drawn, 0, -1).astype(np.int64)
        res = int(s["mapSize"])
        cast = babylon_cascades.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, self.cast_side(s))], sun, float(s["normalBias"]))
        dm = predict.light_depth_map(cast, rb.matrices[0], res)
        factor = babylon_single_factor(dm, rb.matrices[0], np.nan_to_num(rb.position), bias=float(s["bias"]))
        factor = np.where(rb.drawn, factor, np.nan)
        ref = reference(scene, sun, rb, res)
        return Prediction(factor, sel, np.array([cam.near]), np.array([float(s["shadowFrustumSize"])]), np.array([float(res)])), ref

    def matrices(self, s: dict, camera, sun: Array) -> Array:
        """World → [0, 1]³ in the job's (right-handed) world: ``Matrix.LookAtLH(position, position + d, Up)`` and
        ``OrthoLH(size, size, minZ, maxZ)`` in Babylon's mirrored world (z ↦ −z), window depth (z + 1)/2.

            Parameters
            ----------
            s : dict
                The filled settings.
            camera : aliasing.raster.scenes.camera.Camera
                The eye camera (it places the light's target, :func:`aliasing.frames.scenes.light_target`).
            sun : array_like (3,)
                World direction towards the sun, non-zero.

            Returns
            -------
            ndarray (1, 4, 4)
                World → (s, t, depth) in [0, 1]³ (column vectors).

        Examples
        --------
        >>> from aliasing.raster.scenes.camera import look_at
        >>> cam = look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
        >>> m = BabylonSingle().matrices(BabylonSingle().settings({"shadowFrustumSize": 20.0}), cam, np.array([0.0, 1.0, 0.0]))
        >>> np.round(m[0] @ [0.0, -1.0, -50.5, 1.0], 6).tolist()   # below the target: the box's centre in s, t
        [0.5, 0.5, 0.510101, 1.0]
        """
        check.direction(sun)
        from .scenes import light_target

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
        """The one map: the camera's near, the matrix's larger texel side × R, and R.

        Parameters
        ----------
        s : dict
            The filled settings.
        camera : aliasing.raster.scenes.camera.Camera
            The eye camera.
        rb : Readback
            The engine's read-back (its matrices, map sizes and info).

        Returns
        -------
        starts, sides, resolution : ndarray (k,)
            First eye depth [world units], map side [world units], map side [texels].

        Examples
        --------
        >>> from aliasing.raster.scenes.camera import look_at
        >>> cam = look_at("0,0,0", "0,0,-1", near=1.0, far=100.0, fov=50.0)
        >>> from aliasing.frames.readback import Readback
        >>> rb = Readback("", "", np.ones((1, 1)), np.zeros((1, 1), np.int64), np.zeros((1, 1, 3)), np.zeros((1, 1, 3)),
        ...               np.diag([0.1, 0.1, 0.01, 1.0])[None], np.array([[1024, 1024]]), {}, b"")   # a 10 × 10 box
        >>> [v.tolist() for v in BabylonSingle().measured_cascades(BabylonSingle().settings(), cam, rb)]
        [[1.0], [10.0], [1024.0]]
        """
        m = rb.matrices[0]
        return np.array([camera.near]), np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3]))]), rb.sizes[:1, 0].astype(float)


def babylon_single_factor(depth_map: DepthMap, matrix: Array, points: Array, *, bias: float, half: bool = True) -> Array:
    """Babylon.js 9.35's ShadowGenerator factor with FILTER_NONE (``computeShadow`` of shadowsFragmentFunctions).

    The map is a colour target holding the caster's window depth + ``bias``
    (shadowMapVertexMetric's ``vDepthMetricSM``, no depth texture, no depth clamp; cleared to 1),
    rounded to a half float when ``half`` (the generator takes a half-float target first where
    the device renders and filters them, shadowGenerator.js 659–668);
    the receiver's depth is its window depth clamped to [0, 1], compared with the nearest texel
    (NEAREST sampling): shadowed where it is greater; outside [0, 1]² the factor is 1.

    Examples
    --------
    >>> m = np.array([[1.0, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0.5], [0, 0, 0, 1]])    # s = x, t = z, depth = 0.5 − y
    >>> roof = np.array([[[0.0, 0.25, 0.0], [2.0, 0.25, 0.0], [0.0, 0.25, 2.0]]])     # covers the map at depth 0.25
    >>> pts = np.array([[0.5, 0.0, 0.5], [0.5, 0.3, 0.5]]); up = np.array([[0.0, 1.0, 0.0]] * 2)   # under it, above it
    >>> babylon_single_factor(predict.light_depth_map(roof, m, 4), m, pts, bias=0.0).tolist()
    [0.0, 1.0]
    """
    if not isinstance(depth_map, DepthMap):
        raise ValueError(f"depth_map must be a DepthMap (light_depth_map), got {type(depth_map).__name__}")
    check.finite(check.scalar(bias, "bias"), "bias")
    c = to_map(matrix, points)
    r = depth_map.resolution
    stored = np.where(np.isfinite(depth_map.depth), depth_map.depth + bias, 1.0)
    if half:
        stored = stored.astype(np.float32).astype(np.float16).astype(float)
    col = np.clip(np.floor(np.nan_to_num(c[..., 0]) * r), 0, r - 1).astype(np.int64)
    row = np.clip(np.floor(np.nan_to_num(c[..., 1]) * r), 0, r - 1).astype(np.int64)
    inside = np.all((c[..., :2] >= 0) & (c[..., :2] <= 1), axis=-1)
    lit = np.clip(c[..., 2], 0.0, 1.0) <= stored[row, col]
    return np.where(inside & ~lit, 0.0, 1.0)

