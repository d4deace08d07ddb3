"""One frame end to end: the engine draws it, the toolkit predicts it, both are measured alike.

Examples
--------
>>> job = make_job(frame_scene("boxes", near=1.0, far=30.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2),
...                np.array([0.0, 1.0, 0.0]), {"cascades": 2}, 64)
>>> job["width"], job["height"], job["camera"]["fov"]
(128, 64, 50.0)
"""

from __future__ import annotations

import base64
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from . import compare
from .models import Prediction, model_for
from .paths import MOVING_ENGINES, PATH_ENGINES, flips, parse_path, pose_camera, replay, shimmer  # noqa: F401 - flips, pose_camera, replay re-exported
from .readback import FrameResult, Readback, decode
from .scenes import FrameScene, frame_scene, light_target  # noqa: F401 - frame_scene for the example, light_target re-exported

Array = NDArray[np.float64]


def make_job(scene: FrameScene, sun: Array, settings: dict, height: int, path: list[dict] | None = None, maps: int | None = None) -> dict:
    """The page's job: the scene's triangles (base64 float32), the camera, the sun and the settings.

    ``height`` [px] in [16, 2160]; the width is round(aspect · height).  ``maps``: read the
    shadow maps back, at most this many texels per side (:mod:`aliasing.frames.maps`).

    Examples
    --------
    >>> fs = frame_scene("boxes", near=1.0, far=30.0, fov=50.0, aspect=1.5, boxes=1, ground_cells=1)
    >>> job = make_job(fs, [0.0, 1.0, 0.0], {}, 100, maps=256)
    >>> job["width"], job["maps"], len(base64.b64decode(job["triangles"])) == fs.triangles.size * 4   # float32 triangles
    (150, {'side': 256}, True)
    """
    if not isinstance(scene, FrameScene):
        raise ValueError(f"scene must be a FrameScene (aliasing.frames.scenes.frame_scene), got {type(scene).__name__}")
    check.direction(sun)
    h = int(height)
    if h != height or not 16 <= h <= 2160:
        raise ValueError(f"height must be a whole number of pixels in [16, 2160], got {height!r}")
    cam = scene.camera
    w = int(round(cam.aspect * h))
    if not 16 <= w <= 4096:
        raise ValueError(f"the width round(aspect * height) must be in [16, 4096] px, got {w}")
    tri = np.ascontiguousarray(scene.triangles, np.float32)
    return {"width": w, "height": h, "triangles": base64.b64encode(tri.tobytes()).decode(),
            "camera": {"eye": cam.eye.tolist(), "target": (cam.eye + cam.rotation[2]).tolist(), "up": cam.rotation[1].tolist(),
                       "near": cam.near, "far": cam.far, "fov": cam.fov},
            "sun": [float(v) for v in sun], "settings": settings, "ground": scene.ground, "path": path,
            "maps": None if maps is None else {"side": _map_side(maps)}, "lightTarget": light_target(cam).tolist()}


def refuse_unrendered(engine: str, cls: str | None, path, maps) -> None:
    """Refuse, in one line, a camera ``path`` or a map read-back (``maps``) that the frames do not render for ``engine``'s ``cls``.

    Raises
    ------
    ValueError
        What is not rendered, naming ``--path`` or ``--maps``.

    Examples
    --------
    >>> refuse_unrendered("threejs", "CSM", "sideways:0.05:4", 256)
    >>> refuse_unrendered("playcanvas", None, "turn:0.5:4", 256)
    >>> refuse_unrendered("babylon", "ShadowGenerator", None, 256)
    Traceback (most recent call last):
    ...
    ValueError: --maps: the shadow maps are read back for three.js's CSM, Babylon.js's CascadedShadowGenerator and PlayCanvas's directional light only (not yet for babylon ShadowGenerator)
    """
    single = cls in ("DirectionalLight", "ShadowGenerator")
    if path is not None:
        if engine not in PATH_ENGINES + MOVING_ENGINES:
            raise ValueError(f"--path: the camera path is rendered for {', '.join(PATH_ENGINES + MOVING_ENGINES)} only (not for {engine})")
        if single:
            raise ValueError(f"--path: the camera path is rendered for the cascaded classes only (a {cls}'s box does not follow the camera)")
    if maps is not None:
        _map_side(maps)
        if engine not in PATH_ENGINES or single:
            raise ValueError(f"--maps: the shadow maps are read back for three.js's CSM, Babylon.js's CascadedShadowGenerator and "
                             f"PlayCanvas's directional light only (not yet for {engine}{' ' + cls if cls else ''})")


def _map_side(maps) -> int:
    m = int(maps) if isinstance(maps, (int, np.integer)) and not isinstance(maps, bool) else -1
    if not 16 <= m <= 4096:
        raise ValueError(f"maps (--maps SIDE) must be a whole number of texels per side in [16, 4096], got {maps!r}")
    return m


def _ground_pixels(scene: FrameScene, rb: Readback) -> NDArray[np.bool_]:
    if scene.ground == 0:
        return np.zeros(rb.shadow.shape, bool)
    y0 = float(scene.triangles[: scene.ground, :, 1].mean())
    scale = float(np.ptp(scene.triangles[..., 1])) or 1.0
    return rb.drawn & (np.abs(np.nan_to_num(rb.position[..., 1]) - y0) < 1e-4 * scale) & (np.nan_to_num(rb.normal[..., 1]) > 0.999)


def pipeline_footprint(pipeline, camera, sun: Array) -> tuple[Array, Array, Array]:
    """Per cascade from an :class:`aliasing.setups.Pipeline`: first depth, map side [world units], resolution.

    The sides are :func:`aliasing.engines.pipeline.result` of the pipeline whole (its ranges, fit, snap and size),
    except the tight fit, measured in the light frame rolled by the world's up
    (:func:`aliasing.frames.models.tight_sides`, ERRATA F5).

    Examples
    --------
    >>> from aliasing import setups
    >>> from aliasing.frames.scenes import sun_direction
    >>> su = setups.build("threejs", {"cascades": 2}, "near=1,far=20,fov=50,aspect=2,height=64", "20@30")
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=1, ground_cells=1)
    >>> starts, sides, res = pipeline_footprint(su.pipeline, fs.camera, sun_direction(20.0, 30.0, fs.camera))
    >>> starts.round(3).tolist(), bool((sides > 0).all()), res.tolist()
    ([1.0, 7.486], True, [2048.0, 2048.0])
    """
    check.direction(sun)
    from ..engines import pipeline as engine_pipeline
    from .models import tight_sides

    near_i, far_i = np.asarray(pipeline.near_i, float), np.asarray(pipeline.far_i, float)
    res = float(pipeline.resolution)
    if pipeline.fit == "fixed":  # one box the user sets: its larger side
        return near_i, np.full(len(near_i), float(max(pipeline.box))), np.full(len(near_i), res)
    if pipeline.fit == "tight":
        sides = np.array([tight_sides(camera, np.array([a, b]), -sun, np.array([0.0, 1.0, 0.0]))[0] for a, b in zip(near_i, far_i)])
    else:
        box = engine_pipeline.result(pipeline, camera, camera.direction_to_eye(sun)[None])  # the pipeline whole: its ranges, fit, snap, size
        sides = np.maximum(box.width_x[0], box.width_y[0])
    return near_i, sides, np.full(len(sides), res)


def predict_readback(model, settings: dict, scene: FrameScene, sun: Array, rb: Readback) -> tuple[Prediction, NDArray[np.bool_], bool, str | None]:
    """The model's predicted factor at a read-back's pixels and the exact reference's lit pixels.

    Shared by :func:`measure` (an engine's read-back) and :mod:`aliasing.frames.seen` (a
    read-back synthesized by the toolkit).  Returns ``(prediction, reference, predicts, why_not)``:
    where the model renders these settings but does not predict them (``why_not`` says why), the
    prediction is NaN and the reference is drawn through the read-back's first map size.

    Examples
    --------
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.scenes import sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera); m = MODELS["threejs"]; s = m.settings({"cascades": 2, "shadowMapSize": 256})
    >>> rb = Readback("threejs", "187", np.ones((1, 2)), np.array([[0, 1]]), np.array([[[-2.0, -1.0, -4.25], [0.0, -1.0, -12.0]]]),
    ...               np.array([[[0.0, 1.0, 0.0]] * 2]), m.matrices(s, fs.camera, sun), np.full((2, 2), 256), {}, b"")
    >>> pred, ref, predicts, why_not = predict_readback(m, s, fs, sun, rb)
    >>> (pred.factor < 0.5).tolist(), ref.tolist(), predicts, why_not    # in a box's shadow, lit
    ([[True, False]], [[False, True]], True, None)
    """
    why_not = model.predicted(settings) if hasattr(model, "predicted") else None
    predicts = getattr(model, "predicts", True) and why_not is None
    if predicts:
        pred, ref = model.predict(settings, scene, sun, rb)
    else:  # rendered and measured only: the exact reference, no predicted factor
        from .models import reference

        ref = reference(scene, sun, rb, int(rb.sizes[0, 0]))
        k = len(rb.matrices)
        pred = Prediction(np.full(rb.shadow.shape, np.nan), np.full(rb.shadow.shape, -1), np.full(k, np.nan), np.full(k, np.nan), np.full(k, np.nan))
    return pred, ref, predicts, why_not


def pixel_masks(scene: FrameScene, sun: Array, rb: Readback, ref: NDArray[np.bool_]) -> tuple[NDArray[np.bool_], NDArray[np.bool_], NDArray[np.bool_]]:
    """The pixels the measures count (:mod:`aliasing.frames.compare`): ``(receivers, facing, ground)``.

    ``facing``: drawn and turned towards the sun (cos > :data:`~aliasing.frames.compare.MIN_COS`);
    ``receivers``: those lit in the exact reference ``ref``; ``ground``: the scene's ground pixels.

    Examples
    --------
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> rb = Readback("", "", np.ones((1, 2)), np.zeros((1, 2), np.int64), np.array([[[0.0, -1.0, -4.0], [0.0, -1.0, -9.0]]]),
    ...               np.array([[[0.0, 1.0, 0.0]] * 2]), np.eye(4)[None], np.full((1, 2), 16), {}, b"")
    >>> [m.tolist() for m in pixel_masks(fs, np.array([0.0, 1.0, 0.0]), rb, np.array([[True, False]]))]
    [[[True, False]], [[True, True]], [[True, True]]]
    """
    sunward = (np.nan_to_num(rb.normal) @ sun) > compare.MIN_COS
    return ref & sunward, rb.drawn & sunward, _ground_pixels(scene, rb)


def shading(factor: Array, ref: NDArray[np.bool_], receivers: NDArray[np.bool_], facing: NDArray[np.bool_], ground: NDArray[np.bool_],
            drawn: NDArray[np.bool_]) -> dict:
    """``acne``, ``lost_shadow`` [fractions] and ``gap_px`` [px] of a shadow ``factor`` on the pixels of :func:`pixel_masks`.

    Examples
    --------
    >>> ref = np.array([[True, False]]); every = np.ones((1, 2), bool)
    >>> shading(np.array([[0.0, 1.0]]), ref, ref, every, ~every, every)   # the lit pixel shaded, the shadowed one lit
    {'acne': 1.0, 'lost_shadow': 1.0, 'gap_px': None}
    """
    return {"acne": compare.acne(factor, receivers), "lost_shadow": compare.lost_shadow(factor, ref, facing),
            "gap_px": compare.gap(factor, ref, ground, drawn)}


def measure(engine: str, scene: FrameScene, sun: Array, settings: dict, out: dict, pipeline=None) -> FrameResult:
    """Decode the page's answer ``out`` for ``scene`` and ``sun``, predict it and measure both.

    With an :class:`aliasing.setups.Pipeline` the predicted texel footprint is the pipeline's
    (its ranges, fit and snap), and the details say how far its cascade ranges are from the model's.

    Examples
    --------
    >>> import base64
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.scenes import sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera); m = MODELS["threejs"]; s = m.settings({"cascades": 2, "shadowMapSize": 256})
    >>> b64 = lambda a: base64.b64encode(np.asarray(a, np.float32).tobytes()).decode()
    >>> out = {"engine": "threejs", "revision": "187", "width": 2, "height": 1, "frame": "data:image/png;base64,",   # a page's answer, by hand:
    ...        "shadow": b64([[[0, 0, 0, 0], [1, 1, 0.3, 0]]]),                     # per pixel factor, cascade, n·l
    ...        "position": b64([[[-2.0, -1.0, -4.25, 1.0], [0.0, -1.0, -12.0, 1.0]]]), # two ground pixels, drawn (w = 1)
    ...        "normal": b64([[[0, 1, 0, 0]] * 2]), "breaks": (m.edges(s, fs.camera)[1:] / 20.0).tolist(),
    ...        "cascades": [{"matrix": c.T.ravel().tolist(), "size": [256, 256]} for c in m.matrices(s, fs.camera, sun)]}
    >>> rep = measure("threejs", fs, sun, s, out).report
    >>> rep["measured"]["acne"], rep["predicted"]["acne"], rep["details"]["matrices_vs_engine"]
    (0.0, 0.0, 0.0)
    >>> np.round(rep["measured"]["px_per_texel"], 6).tolist() == np.round(rep["predicted"]["px_per_texel"], 6).tolist()
    True
    """
    if not isinstance(scene, FrameScene):
        raise ValueError(f"scene must be a FrameScene (aliasing.frames.scenes.frame_scene), got {type(scene).__name__}")
    check.direction(sun)
    model = model_for(engine, settings)
    if hasattr(model, "readback"):  # a page that returns colours only (Filament): the model makes the read-back
        out = model.readback(out, scene, sun)
    rb = decode(out)
    pred, ref, predicts, why_not = predict_readback(model, settings, scene, sun, rb)
    receivers, facing, ground = pixel_masks(scene, sun, rb, ref)
    m_starts, m_sides, m_res = model.measured_cascades(settings, scene.camera, rb)
    h = rb.shadow.shape[0]
    measured = {
        "shadow_agreement": compare.agreement(rb.shadow, pred.factor, rb.drawn) if predicts else None,
        **shading(rb.shadow, ref, receivers, facing, ground, rb.drawn),
        "px_per_texel": compare.px_per_texel(m_starts, m_sides, m_res, scene.camera.fov, h),
    }
    starts, sides, res = pred.starts, pred.sides, pred.resolution
    extra_pipe = {}
    if pipeline is not None and predicts:
        starts, sides, res = pipeline_footprint(pipeline, scene.camera, sun)
        extra_pipe = {"pipeline_fit": pipeline.fit, "pipeline_starts_vs_model": float(np.max(np.abs(starts / pred.starts - 1))) if len(starts) == len(pred.starts) else None}
        if getattr(model, "footprint_from_matrices", False):  # Babylon.js: its float32 matrices modelled; the setups' fit is float64
            extra_pipe["pipeline_px_per_texel"] = compare.px_per_texel(starts, sides, res, scene.camera.fov, h)
            starts, sides, res = pred.starts, pred.sides, pred.resolution
    predicted = {
        **shading(pred.factor, ref, receivers, facing, ground, rb.drawn),
        "px_per_texel": compare.px_per_texel(starts, sides, res, scene.camera.fov, h),
    } if predicts else {"acne": None, "lost_shadow": None, "gap_px": None, "px_per_texel": None}
    drawn = rb.drawn
    if predicts and (pred.matrices is not None or hasattr(model, "matrices")):  # the whole light matrices, predicted from the fit, snap and light frame
        pm = pred.matrices if pred.matrices is not None else model.matrices(settings, scene.camera, sun)
        if pm.shape == rb.matrices.shape:
            extra_pipe["matrices_vs_engine"] = float(np.max(np.abs(pm - rb.matrices)) / np.max(np.abs(rb.matrices)))
    if predicts and hasattr(model, "light_matrices"):  # PlayCanvas: the palette, from the fit, snap and the casters' box
        pm = model.light_matrices(settings, scene.camera, sun, scene.triangles)
        if pm.shape == rb.matrices.shape:
            extra_pipe["matrices_vs_engine"] = float(np.max(np.abs(pm - rb.matrices)) / np.max(np.abs(rb.matrices)))
            extra_pipe["grid_vs_engine"] = float(np.max(np.abs(pm - rb.matrices)[:, :2]) / np.max(np.abs(rb.matrices)))
    extra = {"pixels": int(drawn.sum()), "receivers": int(receivers.sum()),
             "cascade_agreement": float(np.mean(rb.cascade[drawn] == pred.cascade[drawn])) if drawn.any() and predicts else None,
             "renderer": rb.info.get("renderer"), "engine_ms": rb.info.get("ms"), **extra_pipe, **rb.info.get("checks", {})}
    if why_not:
        extra["not_predicted"] = why_not
        extra["agreement_vs_exact"] = compare.agreement(rb.shadow, np.where(ref, 1.0, 0.0), rb.drawn)  # the engine's mask against the exact shadows
    report = {"engine": engine, "release": rb.release, "scene": scene.name, "measured": measured, "predicted": predicted, "details": extra}
    return FrameResult(rb, pred, ref, settings, report)


def at_pixel_aspect(setup, scene: FrameScene):
    """The setup and the scene with the image's pixel aspect round(aspect · height) / height, and checked to share one camera.

    The engines project with the canvas's width/height: where that is not the setup's aspect,
    the setup and the scene's camera take it.

    Raises
    ------
    ValueError
        ``scene`` not built with the setup's camera (near, far, fov, aspect).

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=100", "35@30")
    >>> s2, fs = at_pixel_aspect(s, frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=1, ground_cells=1))
    >>> s2.camera.aspect, fs.camera.aspect       # 178 x 100 pixels
    (1.78, 1.78)
    """
    from ..raster.scenes.camera import Camera
    from ..setups import Setup, spec

    cam = setup.camera
    pixel_aspect = round(cam.aspect * cam.height) / cam.height
    if pixel_aspect != cam.aspect:
        # the engines project with the canvas's width/height: the setup and the scene take that aspect
        setup = Setup(setup.profile, dict(setup.settings), spec.Camera(cam.near, cam.far, cam.fov, pixel_aspect, cam.height), setup.sun)
        c = scene.camera
        scene = replace(scene, camera=Camera(c.eye, c.rotation, c.near, c.far, c.fov, c.name, pixel_aspect))
        cam = setup.camera
    if abs(scene.camera.near - cam.near) > 0 or abs(scene.camera.far - cam.far) > 0 or abs(scene.camera.fov - cam.fov) > 0 \
            or abs(scene.camera.aspect - cam.aspect) > 1e-9:
        raise ValueError("scene must be built with the setup's camera (near, far, fov, aspect)")
    return setup, scene


def frame_inputs(setup, scene: FrameScene, sun: Array | None = None):
    """A frame's checked setup and scene (:func:`at_pixel_aspect`) and its unit sun: the middle of the setup's band unless ``sun`` is given.

    Raises
    ------
    ValueError
        Naming ``setup``, ``scene`` or ``sun``.

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {}, "near=0.5,far=60,fov=50,aspect=2,height=100", "20..40")
    >>> _, fs, sun = frame_inputs(s, frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=2.0, boxes=1, ground_cells=1))
    >>> round(float(np.degrees(np.arcsin(sun[1]))), 9)       # 30° above the ground
    30.0
    """
    from .scenes import sun_direction

    if not (hasattr(setup, "pipeline") and hasattr(setup, "profile")):
        raise ValueError(f"setup must be an aliasing.setups.Setup, got {type(setup).__name__}")
    if not isinstance(scene, FrameScene):
        raise ValueError(f"scene must be a FrameScene (aliasing.frames.scenes.frame_scene), got {type(scene).__name__}")
    setup, scene = at_pixel_aspect(setup, scene)
    if sun is None:
        lo, hi = setup.sun.elevation
        sun = sun_direction((lo + hi) / 2, setup.sun.azimuth, scene.camera)
    sv = check.direction(sun)
    return setup, scene, np.asarray(sv, float) / np.linalg.norm(sv)


def frame_setup(browser, setup, scene: FrameScene, sun: Array | None = None, path: str | None = None, maps: int | None = None,
                probe: bool = True) -> FrameResult:
    """Render an :class:`aliasing.setups.Setup` (engine, settings, camera with image size, sun) on ``scene``.

    ``scene`` must have been built with the setup's camera (:func:`aliasing.frames.scenes.frame_scene`);
    the sun is the setup's (the middle of its band) unless ``sun`` (a world direction) is given.
    The engines project with the image's width/height: where round(aspect · height)/height is not
    the setup's aspect, the setup and the scene's camera take that pixel aspect.

    Parameters
    ----------
    browser : Browser
        An open :class:`aliasing.frames.browser.Browser`.
    setup : aliasing.setups.Setup
        From :func:`aliasing.setups.build` (an engine of :data:`aliasing.frames.PINS` at its pinned release).
        Godot draws a second frame, the split each pixel's shader chose (``pages/godot.mjs``).
    scene : FrameScene
        From :func:`aliasing.frames.scenes.frame_scene` with the setup's camera.
    sun : array_like (3,), optional
        World direction towards the sun.
    path : str, optional
        ``KIND:STEP[:FRAMES]`` (:func:`parse_path`): adds ``flips_per_frame`` (Godot: its camera itself moves,
        flips at matched world points, :func:`aliasing.frames.paths.godot_shimmer`).
    maps : int, optional
        Read the shadow maps back (three.js, Babylon.js; PlayCanvas's atlas), every stride-th texel so that at most
        ``maps`` texels per side come back, and add ``report["maps"]``: the engine's maps
        against the toolkit's rasterizer (:func:`aliasing.frames.maps.measure_maps`).
    probe : bool
        Godot: draw the second frame, the split each pixel's shader chose (default); False: the split
        Godot's own split offsets pick at each pixel's view depth (the same on 99.99 % of the pixels,
        docs/ERRATA.md F13), one frame per call (``tune --frames``).  Other engines draw one frame either way.

    Returns
    -------
    FrameResult
        The engine's frame against the prediction (:func:`measure`).

    Examples
    --------
    The engine draws in a browser, so the example is not run here:

    >>> from aliasing import setups
    >>> from aliasing.frames.browser import Browser
    >>> s = setups.build("threejs", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=144", "35@30")
    >>> fs = frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9)
    >>> with Browser() as b:                                  # doctest: +SKIP
    ...     r = frame_setup(b, s, fs)
    >>> r.report["measured"]["acne"] < 0.01                   # doctest: +SKIP
    True
    """
    from .models import from_setup

    if not isinstance(probe, (bool, np.bool_)):
        raise ValueError(f"probe must be True or False, got {probe!r}")
    setup, scene, sv = frame_inputs(setup, scene, sun)
    cam = setup.camera
    settings = from_setup(setup)
    poses = None
    if path is not None:
        refuse_unrendered(setup.engine, settings.get("class"), path, None)
        poses = parse_path(path, scene.camera)
    refuse_unrendered(setup.engine, settings.get("class"), None, maps)
    job = make_job(scene, sv, settings, cam.height, poses, maps)
    out = browser.render(setup.engine, job)
    if setup.engine == "godot" and probe:  # the split per pixel from Godot's own shader: a second frame that draws it
        splits = browser.render("godot", {**job, "probe": "splits", "path": None})
        out["splits_frame"], out["shaders_probed"] = splits["factor"], splits.get("shaders_probed")
    result = measure(setup.engine, scene, sv, settings, out, pipeline=setup.pipeline)
    if maps is not None:
        from . import maps as frame_maps

        got = frame_maps.decode_maps(out)
        if "matrices" in out["maps"][0]:  # one atlas, drawn with these palette matrices
            mats = np.array([np.asarray(m, float).reshape(4, 4).T for m in out["maps"][0]["matrices"]])
        elif "matrix" in out["maps"][0]:
            mats = np.array([np.asarray(m["matrix"], float).reshape(4, 4).T for m in out["maps"]])
        else:
            mats = result.readback.matrices
        result.report["maps"] = frame_maps.measure_maps(setup.engine, settings, scene.triangles, sv, mats, got)
    if poses is not None:
        sh = shimmer(result, scene, sv, poses)
        result.report["measured"]["flips_per_frame"] = sh["measured"]
        result.report["predicted"]["flips_per_frame"] = sh["predicted"]
        result.report["details"]["path"] = path
        result.report["details"]["path_matrices_vs_engine"] = sh["matrices_vs_engine"]
        if "matched" in sh:  # Godot: the picture moves with the camera, flips counted at matched world points
            for key in ("matched", "resampling", "view_vs_toolkit"):
                result.report["details"][f"path_{key}"] = sh[key]
        if "grid_vs_engine" in sh:
            result.report["details"]["path_grid_vs_engine"] = sh["grid_vs_engine"]
    result.report["details"]["engine_revision"] = result.report["release"]
    result.report["release"] = setup.release
    return result


