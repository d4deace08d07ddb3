"""A predicted frame without a browser: the read-back an engine's page would return, synthesized.

For a :class:`aliasing.setups.Setup` (three.js, Babylon.js, PlayCanvas or Godot's Compatibility
renderer, the engines whose light matrices the toolkit predicts) and a :class:`~aliasing.frames.scenes.FrameScene`, the
toolkit makes, per pixel of the setup's image (its camera, ``height`` rows and
round(aspect · height) columns), what the engine's page reads back
(:class:`~aliasing.frames.readback.Readback`):

* the world position and normal from the toolkit's eye pass
  (:func:`aliasing.raster.draw.eye_pass`) over the triangles the engine's main pass draws (its
  face culling: :data:`VISIBLE`), each position the pixel centre's ray on the visible
  triangle's plane; a pixel is drawn where a triangle is visible within near … far;
* the light matrices from the model's own prediction (three.js: ``ThreeCSM.matrices``;
  Babylon.js: its float32 cascades, :func:`aliasing.frames.babylon_cascades.matrices`;
  PlayCanvas: ``PlayCanvas.light_matrices``; Godot: ``Godot.matrices``, its split-local matrices,
  which equal those Godot uploads to 1.2·10⁻⁷, docs/ERRATA.md F13; the single-map classes' ``matrices``);
* the cascade each pixel selects by the engine's rule (the model's ``select``; Godot's from its split
  offsets, ``Godot.select``);

then the predicted shadow factor and the exact reference exactly as
:func:`aliasing.frames.run.measure` takes them from a real read-back
(:func:`~aliasing.frames.run.predict_readback`, :func:`~aliasing.frames.run.pixel_masks`,
:func:`~aliasing.frames.run.shading`).

The eye pass draws square R × R images; a W × H image is drawn on R = max(W, H) by a shear of
eye space that puts the image's pixel centres on the square's first W columns and H rows
(:func:`aliasing.raster.draw.eye.image_pass`).

Examples
--------
>>> from aliasing import setups
>>> from aliasing.frames.scenes import frame_scene
>>> s = setups.build("threejs", {"cascades": 2, "shadowMapSize": 256}, "near=0.5,far=40,fov=50,aspect=16:9,height=36", "35@30")
>>> fs = frame_scene("boxes", near=0.5, far=40.0, fov=50.0, aspect=16 / 9, boxes=6, ground_cells=2)
>>> r = synthetic_frame(s, fs)
>>> r.readback.shadow.shape, sorted(r.report["predicted"])
((36, 64), ['acne', 'gap_px', 'lost_shadow', 'px_per_texel'])
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ... import _validation as check
from ...raster.draw.eye import image_pass
from ...setups.godot import SIZE, layout
from .. import babylon_cascades
from ...view import tan_theta
from ..models import from_setup, model_for
from ..readback import FrameResult, Readback
from ..run import frame_inputs, pixel_masks, predict_readback, shading
from ..scenes import FrameScene, sun_direction  # noqa: F401 - sun_direction for the examples

Array = NDArray[np.float64]

#: The engines whose light matrices the toolkit predicts (their frames can be synthesized).
ENGINES = ("threejs", "babylon", "playcanvas", "godot")

#: Which faces each engine's main pass draws, by its settings (the material's culling):
#: three.js ``material.side`` (WebGLRenderer's ``setMaterial``: FrontSide culls back faces);
#: Babylon.js ``backFaceCulling`` (``Material.backFaceCulling``, true: back faces culled);
#: PlayCanvas ``cull`` (``CULLFACE_BACK`` default); Godot: the page's ShaderMaterial is ``cull_back`` (``pages/godot/main.gd``
#: ``FACTOR_SHADER``; no Godot setting changes it) over the job's triangles rewound (a, c, b) for Godot's clockwise front
#: faces, so the faces drawn are the job's front faces.  "front": faces whose right-handed normal points towards the eye.
VISIBLE = {
    "threejs": lambda s: s.get("side", "front"),
    "babylon": lambda s: "front" if s.get("backFaceCulling", True) else "double",
    "playcanvas": lambda s: {"back": "front", "front": "back", "none": "double"}[s.get("cull", "back")],
    "godot": lambda s: "front",
}


def engine_settings(setup) -> tuple[object, dict]:
    """The model of ``setup``'s engine and its settings as the model takes them (:func:`aliasing.frames.models.from_setup`).

    Raises
    ------
    ValueError
        An engine whose frames are not synthesized (:data:`ENGINES`) or a setting the models do not model.

    Examples
    --------
    >>> from aliasing import setups
    >>> m, s = engine_settings(setups.build("playcanvas", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=144", "35"))
    >>> type(m).__name__, s["numCascades"]
    ('PlayCanvas', 1)
    """
    if not (hasattr(setup, "pipeline") and hasattr(setup, "profile")):
        raise ValueError(f"setup must be an aliasing.setups.Setup, got {type(setup).__name__}")
    if setup.engine not in ENGINES:
        raise ValueError(f"setup's engine must be one of {', '.join(ENGINES)} (the engines whose light matrices are predicted), got {setup.engine!r}")
    settings = from_setup(setup)
    model = model_for(setup.engine, settings)
    why = model.predicted(settings) if hasattr(model, "predicted") else None
    if why:
        raise ValueError(f"setup: {why}")
    return model, settings


def light_matrices(model, settings: dict, scene: FrameScene, sun: Array, aspect: float) -> Array:
    """Each cascade's predicted light matrix (world → (s, t, depth) in [0, 1]³), as the engine builds it (module docstring).

    ``aspect``: the image's width / height (Babylon.js fits its cascades at the canvas's aspect).

    Examples
    --------
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.scenes import frame_scene
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> m = MODELS["babylon"]; s = m.settings({"numCascades": 2})
    >>> light_matrices(m, s, fs, sun_direction(30.0, 0.0, fs.camera), 2.0).shape
    (2, 4, 4)
    """
    sun = check.direction(sun)
    if hasattr(model, "light_matrices"):  # PlayCanvas: its palette, from the casters' box too
        return model.light_matrices(settings, scene.camera, sun, scene.triangles)
    if hasattr(model, "matrices"):  # three.js's CSM, both single-map classes and Godot's splits (split-local, as Godot.predict takes them)
        return model.matrices(settings, scene.camera, sun)
    return babylon_cascades.matrices(settings, scene.camera, sun, scene.triangles, aspect=aspect)  # Babylon.js's float32 cascades


def _visible(triangles: Array, eye: Array, side: str) -> NDArray[np.bool_]:
    """The triangles a main pass drawing ``side`` faces keeps, seen from ``eye``."""
    n = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    towards = ((eye - triangles[:, 0]) * n).sum(-1)
    return {"front": towards > 0, "back": towards < 0, "double": towards != 0}[side]


def eye_geometry(scene: FrameScene, width: int, height: int, side: str = "front") -> tuple[Array, Array, NDArray[np.bool_]]:
    """Per pixel of a ``width`` × ``height`` image (rows top down): world position [world units], unit normal facing the eye, drawn.

    The scene's camera (its near, far, vertical fov; the pixels' aspect is width / height);
    ``side`` "front", "back" or "double": the faces drawn (seen from the eye).

    Examples
    --------
    >>> from aliasing.frames.scenes import frame_scene
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=0, ground_cells=2)
    >>> pos, nrm, drawn = eye_geometry(fs, 8, 4)
    >>> drawn.astype(int).tolist()                     # the ground (1 below the eye) in the lower half
    [[0, 0, 0, 0, 0, 0, 0, 0], [0, 0, 0, 0, 0, 0, 0, 0], [0, 1, 1, 1, 1, 1, 1, 0], [1, 1, 1, 1, 1, 1, 1, 1]]
    >>> t = tan_theta(50.0); y, x = -0.75 * t, -1.75 * t   # the bottom left pixel's ray (x, y, −1)
    >>> bool(np.allclose(pos[3, 0], [x / -y, -1.0, -1 / -y])), np.round(nrm[3, 0], 9).tolist()
    (True, [0.0, 1.0, 0.0])
    """
    w = check.whole(width, "width", 1, 4096, " [px]")
    h = check.whole(height, "height", 1, 4096, " [px]")
    side = check.choice(side, "side", ("front", "back", "double"))
    cam = scene.camera
    tri = scene.triangles[_visible(scene.triangles, cam.eye, side)]
    pos = np.full((h, w, 3), np.nan)
    nrm = np.full((h, w, 3), np.nan)
    if not len(tri):
        return pos, nrm, np.zeros((h, w), bool)
    p, n, triangle = image_pass(cam.to_eye(tri), float(cam.fov), w, h, near=cam.near)
    drawn = (triangle >= 0) & (p[..., 2] <= cam.far)
    world = p @ cam.rotation + cam.eye
    nw = n @ cam.rotation
    pos[drawn], nrm[drawn] = world[drawn], nw[drawn]
    return pos[::-1], nrm[::-1], drawn[::-1]  # the eye pass's rows are bottom up


def synthetic_readback(model, settings: dict, scene: FrameScene, sun: Array, geometry: tuple, engine: str) -> Readback:
    """The read-back of :func:`eye_geometry`'s ``geometry`` under ``sun``: the predicted matrices and cascades, shadow 1 where drawn.

    The ``shadow`` field holds no engine's factor: 1 where drawn (so that ``drawn`` reads it), NaN elsewhere.

    Examples
    --------
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.scenes import frame_scene
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> m = MODELS["threejs"]; s = m.settings({"cascades": 2, "shadowMapSize": 256})
    >>> rb = synthetic_readback(m, s, fs, sun_direction(30.0, 0.0, fs.camera), eye_geometry(fs, 16, 8), "threejs")
    >>> rb.matrices.shape, rb.cascade[-1].tolist()       # the bottom row: the ground nearest the eye, cascade 0
    ((2, 4, 4), [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0])
    """
    sun = check.direction(sun)
    pos, nrm, drawn = geometry
    h, w = drawn.shape
    cam = scene.camera
    mats = light_matrices(model, settings, scene, sun, w / h)
    depth = np.where(drawn, cam.to_eye(np.nan_to_num(pos))[..., 2], np.nan)
    if engine == "godot":  # Godot.select takes its split offsets (scene.glsl compares the view depth with them)
        cascade = model.select(settings, model.edges(settings, cam)[1:], depth)
        res, rows = layout(int(settings[SIZE]), len(mats))[:2]      # a split's texels across and along t (2 splits: R × R/2)
        sizes = np.tile([res, rows], (len(mats), 1))
    else:
        cascade = model.select(settings, cam, depth) if hasattr(model, "select") else np.where(drawn, 0, -1)
        res = int(settings.get("shadowMapSize", settings.get("mapSize", settings.get("shadowResolution", 0))))
        sizes = np.full((len(mats), 2), res, np.int64)
    return Readback(engine, "toolkit", np.where(drawn, 1.0, np.nan), np.asarray(cascade, np.int64), pos, nrm, mats,
                    np.asarray(sizes, np.int64), {}, b"")


def synthetic_frame(setup, scene: FrameScene, sun: Array | None = None) -> FrameResult:
    """The frame the engine of ``setup`` would draw of ``scene``, predicted without a browser (module docstring).

    Parameters
    ----------
    setup : aliasing.setups.Setup
        Engine threejs, babylon, playcanvas or godot (its ``rendering/renderer/rendering_method``
        gl_compatibility), its settings, the camera (its ``height`` [px] the image's rows) and the sun.
    scene : FrameScene
        Built with the setup's camera (:func:`aliasing.frames.scenes.frame_scene`).
    sun : array_like (3,), optional
        World direction towards the sun; default the middle of the setup's band.

    Returns
    -------
    FrameResult
        ``readback`` (synthesized; its ``shadow`` the predicted factor), ``prediction``,
        ``reference`` and ``report`` with ``predicted`` (``acne``, ``lost_shadow``, ``gap_px``,
        ``px_per_texel``) as :func:`aliasing.frames.run.measure` reports it.

    Raises
    ------
    ValueError
        Naming ``setup``, ``scene`` or ``sun``.

    Examples
    --------
    >>> from aliasing import setups
    >>> from aliasing.frames.scenes import frame_scene
    >>> s = setups.build("babylon", {"numCascades": 2, "mapSize": 512}, "near=0.5,far=40,fov=50,aspect=2,height=32", "35@30")
    >>> fs = frame_scene("boxes", near=0.5, far=40.0, fov=50.0, aspect=2.0, boxes=6, ground_cells=2)
    >>> r = synthetic_frame(s, fs)
    >>> 0 <= r.report["predicted"]["acne"] <= 1, r.readback.drawn.shape
    (True, (32, 64))
    """
    model, settings = engine_settings(setup)
    setup, scene, sun = frame_inputs(setup, scene, sun)
    cam = setup.camera
    geometry = eye_geometry(scene, cam.width, cam.height, VISIBLE[setup.engine](settings))
    return predict_synthetic(model, settings, scene, sun, geometry, setup.engine, setup.release)


def predict_synthetic(model, settings: dict, scene: FrameScene, sun: Array, geometry: tuple, engine: str, release: str = "") -> FrameResult:
    """:func:`synthetic_frame` on checked values and a drawn ``geometry`` (:func:`eye_geometry`), for many suns over one eye pass.

    Examples
    --------
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.scenes import frame_scene
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> m = MODELS["playcanvas"]; s = m.settings({"shadowResolution": 256})
    >>> r = predict_synthetic(m, s, fs, sun_direction(30.0, 0.0, fs.camera), eye_geometry(fs, 16, 8), "playcanvas")
    >>> r.prediction.factor.shape, r.report["predicted"]["lost_shadow"] is not None
    ((8, 16), True)
    """
    rb = synthetic_readback(model, settings, scene, sun, geometry, engine)
    pred, ref, _, _ = predict_readback(model, settings, scene, sun, rb)
    receivers, facing, ground = pixel_masks(scene, sun, rb, ref)
    from ..compare import px_per_texel

    h = rb.shadow.shape[0]
    predicted = {**shading(pred.factor, ref, receivers, facing, ground, rb.drawn),
                 "px_per_texel": px_per_texel(pred.starts, pred.sides, pred.resolution, scene.camera.fov, h)}
    rb = Readback(rb.engine, rb.release, pred.factor, rb.cascade, rb.position, rb.normal, rb.matrices, rb.sizes, rb.info, rb.frame)
    report = {"engine": engine, "release": release, "scene": scene.name, "predicted": predicted,
              "details": {"pixels": int(rb.drawn.sum()), "receivers": int(receivers.sum())}}
    return FrameResult(rb, pred, ref, settings, report)
