"""One frame end to end: the engine draws it, the toolkit predicts it, both are measured alike.

Example
-------
>>> job = make_job(frame_scene("boxes", near=1.0, far=30.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2),
...                np.array([0.0, 1.0, 0.0]), {"cascades": 2}, 64)
>>> job["width"], job["height"], job["camera"]["fov"]
(128, 64, 50.0)
"""

from __future__ import annotations

import base64
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from . import compare
from .models import MODELS, Prediction, model_for
from .readback import Readback, decode
from .scenes import FrameScene, frame_scene, light_target  # noqa: F401 - frame_scene for the example, light_target re-exported

Array = NDArray[np.float64]


@dataclass(frozen=True)
class FrameResult:
    """An engine's frame against the toolkit's prediction: ``readback`` (:class:`Readback`),
    ``prediction``, the exact reference's lit pixels ``reference``, the filled ``settings``, and
    ``report`` (the JSON-ready ``engine``, ``release``, ``measured``, ``predicted``)."""

    readback: Readback
    prediction: Prediction
    reference: NDArray[np.bool_]
    settings: dict
    report: dict


def make_job(scene: FrameScene, sun: Array, settings: dict, height: int, path: list[dict] | None = None, maps: int | None = None) -> dict:
    """The page's job: the scene's triangles (base64 float32), the camera, the sun and the settings.

    ``height`` [px] in [16, 2160]; the width is round(aspect · height).  ``maps``: read the
    shadow maps back, at most this many texels per side (:mod:`aliasing.frames.maps`).
    """
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

    Example
    -------
    >>> refuse_unrendered("threejs", "CSM", "sideways:0.05:4", 256)
    >>> refuse_unrendered("playcanvas", None, "sideways:0.05:4", None)
    Traceback (most recent call last):
    ...
    ValueError: --path: the camera path is rendered for threejs and babylon only (not yet for playcanvas)
    """
    single = cls in ("DirectionalLight", "ShadowGenerator")
    if path is not None:
        if engine not in PATH_ENGINES:
            raise ValueError(f"--path: the camera path is rendered for {' and '.join(PATH_ENGINES)} only (not yet for {engine})")
        if single:
            raise ValueError(f"--path: the camera path is rendered for the cascaded classes only (a {cls}'s box does not follow the camera)")
    if maps is not None:
        _map_side(maps)
        if engine not in ("threejs", "babylon") or single:
            raise ValueError(f"--maps: the shadow maps are read back for three.js's CSM and Babylon.js's CascadedShadowGenerator "
                             f"only (not yet for {engine}{' ' + cls if cls else ''})")


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

    The sides are :func:`aliasing.engines.stable.evaluate` of the pipeline's ranges, fit and snap,
    except the tight fit, measured in the light frame rolled by the world's up
    (:func:`aliasing.frames.models.tight_sides`, ERRATA F5).
    """
    from ..engines import stable
    from .models import tight_sides

    near_i, far_i = np.asarray(pipeline.near_i, float), np.asarray(pipeline.far_i, float)
    res = float(pipeline.resolution)
    if pipeline.fit == "fixed":  # one box the user sets: its larger side
        return near_i, np.full(len(near_i), float(max(pipeline.box))), np.full(len(near_i), res)
    if pipeline.fit == "tight":
        sides = np.array([tight_sides(camera, np.array([a, b]), -sun, np.array([0.0, 1.0, 0.0]))[0] for a, b in zip(near_i, far_i)])
    else:
        box = stable.evaluate((near_i, far_i), camera.near, float(far_i[-1]), camera.fov, camera.direction_to_eye(sun)[None], aspect=camera.aspect,
                              fit=pipeline.fit, snap=pipeline.snap, resolution=res)
        sides = np.maximum(box.width_x[0], box.width_y[0])
    return near_i, sides, np.full(len(sides), res)


def measure(engine: str, scene: FrameScene, sun: Array, settings: dict, out: dict, pipeline=None) -> FrameResult:
    """Decode the page's answer ``out`` for ``scene`` and ``sun``, predict it and measure both.

    With an :class:`aliasing.setups.Pipeline` the predicted texel footprint is the pipeline's
    (its ranges, fit and snap), and the details say how far its cascade ranges are from the model's.
    """
    model = model_for(engine, settings)
    rb = decode(out)
    why_not = model.predicted(settings) if hasattr(model, "predicted") else None
    predicts = getattr(model, "predicts", True) and why_not is None
    if predicts:
        pred, ref = model.predict(settings, scene, sun, rb)
    else:  # rendered and measured only: the exact reference, no predicted factor
        from .models import reference

        ref = reference(scene, sun, rb, int(rb.sizes[0, 0]))
        k = len(rb.matrices)
        pred = Prediction(np.full(rb.shadow.shape, np.nan), np.full(rb.shadow.shape, -1), np.full(k, np.nan), np.full(k, np.nan), np.full(k, np.nan))
    receivers = ref & ((np.nan_to_num(rb.normal) @ sun) > compare.MIN_COS)
    ground = _ground_pixels(scene, rb)
    m_starts, m_sides, m_res = model.measured_cascades(settings, scene.camera, rb)
    h = rb.shadow.shape[0]
    measured = {
        "shadow_agreement": compare.agreement(rb.shadow, pred.factor, rb.drawn) if predicts else None,
        "acne": compare.acne(rb.shadow, receivers),
        "gap_px": compare.gap(rb.shadow, ref, ground, rb.drawn),
        "texels_per_pixel": compare.texels_per_pixel(m_starts, m_sides, m_res, scene.camera.fov, h),
    }
    starts, sides, res = pred.starts, pred.sides, pred.resolution
    extra_pipe = {}
    if pipeline is not None and predicts:
        starts, sides, res = pipeline_footprint(pipeline, scene.camera, sun)
        extra_pipe = {"pipeline_fit": pipeline.fit, "pipeline_starts_vs_model": float(np.max(np.abs(starts / pred.starts - 1))) if len(starts) == len(pred.starts) else None}
    predicted = {
        "acne": compare.acne(pred.factor, receivers),
        "gap_px": compare.gap(pred.factor, ref, ground, rb.drawn),
        "texels_per_pixel": compare.texels_per_pixel(starts, sides, res, scene.camera.fov, h),
    } if predicts else {"acne": None, "gap_px": None, "texels_per_pixel": None}
    drawn = rb.drawn
    if predicts and hasattr(model, "matrices"):  # the whole light matrices, predicted from the fit, snap and light frame
        pm = model.matrices(settings, scene.camera, sun)
        if pm.shape == rb.matrices.shape:
            extra_pipe["matrices_vs_engine"] = float(np.max(np.abs(pm - rb.matrices)) / np.max(np.abs(rb.matrices)))
    extra = {"pixels": int(drawn.sum()), "receivers": int(receivers.sum()),
             "cascade_agreement": float(np.mean(rb.cascade[drawn] == pred.cascade[drawn])) if drawn.any() and predicts else None,
             "renderer": rb.info.get("renderer"), "engine_ms": rb.info.get("ms"), **extra_pipe}
    if why_not:
        extra["not_predicted"] = why_not
    report = {"engine": engine, "release": rb.release, "scene": scene.name, "measured": measured, "predicted": predicted, "details": extra}
    return FrameResult(rb, pred, ref, settings, report)


def frame_setup(browser, setup, scene: FrameScene, sun: Array | None = None, path: str | None = None, maps: int | None = None) -> FrameResult:
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
        From :func:`aliasing.setups.build` (engine threejs, babylon or playcanvas at the pinned release).
    scene : FrameScene
        From :func:`aliasing.frames.scenes.frame_scene` with the setup's camera.
    sun : array_like (3,), optional
        World direction towards the sun.
    path : str, optional
        ``KIND:STEP[:FRAMES]`` (:func:`parse_path`): adds ``flips_per_frame``.
    maps : int, optional
        Read the shadow maps back (three.js, Babylon.js), every stride-th texel so that at most
        ``maps`` texels per side come back, and add ``report["maps"]``: the engine's maps
        against the toolkit's rasterizer (:func:`aliasing.frames.maps.measure_maps`).

    Example
    -------
    >>> from aliasing import setups
    >>> from aliasing.frames.browser import Browser
    >>> s = setups.build("threejs", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=144", "35@30")
    >>> fs = frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9)
    >>> with Browser() as b:                                  # doctest: +SKIP
    ...     r = frame_setup(b, s, fs)
    >>> r.report["measured"]["acne"] < 0.01                   # doctest: +SKIP
    True
    """
    if not (hasattr(setup, "pipeline") and hasattr(setup, "profile")):
        raise ValueError(f"setup must be an aliasing.setups.Setup, got {type(setup).__name__}")
    if not isinstance(scene, FrameScene):
        raise ValueError(f"scene must be a FrameScene (aliasing.frames.scenes.frame_scene), got {type(scene).__name__}")
    from ..raster.scenes.camera import Camera
    from ..setups import Setup, spec
    from .models import from_setup
    from .scenes import sun_direction

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
    if sun is None:
        lo, hi = setup.sun.elevation
        sun = sun_direction((lo + hi) / 2, setup.sun.azimuth, scene.camera)
    settings = from_setup(setup)
    sv = np.asarray(sun, float) / np.linalg.norm(sun)
    poses = None
    if path is not None:
        refuse_unrendered(setup.engine, settings.get("class"), path, None)
        poses = parse_path(path, scene.camera)
    refuse_unrendered(setup.engine, settings.get("class"), None, maps)
    out = browser.render(setup.engine, make_job(scene, sv, settings, cam.height, poses, maps))
    result = measure(setup.engine, scene, sv, settings, out, pipeline=setup.pipeline)
    if maps is not None:
        from . import maps as frame_maps

        got = frame_maps.decode_maps(out)
        mats = np.array([np.asarray(m["matrix"], float).reshape(4, 4).T for m in out["maps"]]) if "matrix" in out["maps"][0] else result.readback.matrices
        result.report["maps"] = frame_maps.measure_maps(setup.engine, settings, scene.triangles, sv, mats, got)
    if poses is not None:
        sh = shimmer(result, scene, sv, poses)
        result.report["measured"]["flips_per_frame"] = sh["measured"]
        result.report["predicted"]["flips_per_frame"] = sh["predicted"]
        result.report["details"]["path"] = path
        result.report["details"]["path_matrices_vs_engine"] = sh["matrices_vs_engine"]
    result.report["details"]["engine_revision"] = result.report["release"]
    result.report["release"] = setup.release
    return result


PATHS = ("sideways", "forward", "turn")
PATH_ENGINES = ("threejs", "babylon")


def parse_path(spec: str, camera) -> list[dict]:
    """Camera poses of ``KIND:STEP[:FRAMES]``: KIND ``sideways`` (along the camera's right) or
    ``forward`` (along its view), STEP [world units per frame, finite, non-zero], or ``turn``
    (the view turned about the world's up, y, through the eye; STEP [degrees per frame, at most 10 in size]);
    FRAMES in [3, 120] (default 30); the first pose is the camera itself.

    Example
    -------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> [p["eye"] for p in parse_path("sideways:0.5:3", look_at("0,0,0", "0,0,-1"))]
    [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0]]
    """
    parts = str(spec).split(":")
    if len(parts) not in (2, 3) or parts[0] not in PATHS:
        raise ValueError(f"--path must be KIND:STEP[:FRAMES] with KIND one of {', '.join(PATHS)}, got {spec!r}")
    try:
        step = float(parts[1])
        n = int(parts[2]) if len(parts) == 3 else 30
    except ValueError:
        raise ValueError(f"--path STEP must be a number and FRAMES a whole number, got {spec!r}") from None
    if not np.isfinite(step) or step == 0:
        raise ValueError(f"--path STEP must be finite and non-zero [world units per frame], got {parts[1]!r}")
    if not 3 <= n <= 120:
        raise ValueError(f"--path FRAMES must be in [3, 120], got {n}")
    if parts[0] == "turn":
        if abs(step) > 10:
            raise ValueError(f"--path turn STEP must be at most 10 degrees per frame in size, got {parts[1]!r}")
        out = []
        for i in range(n):
            a = np.radians(i * step)
            rot = np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])
            out.append({"eye": camera.eye.tolist(), "target": (camera.eye + rot @ camera.rotation[2]).tolist()})
        return out
    axis = camera.rotation[0] if parts[0] == "sideways" else camera.rotation[2]
    return [{"eye": (camera.eye + i * step * axis).tolist(), "target": (camera.eye + i * step * axis + camera.rotation[2]).tolist()} for i in range(n)]


def pose_camera(camera, pose: dict):
    """``camera`` moved to a pose of :func:`parse_path` (its eye, looking at its target, with the camera's own up)."""
    from ..raster.scenes.camera import frame

    eye = np.asarray(pose["eye"], float)
    return replace(camera, eye=eye, rotation=frame(np.asarray(pose["target"], float) - eye, camera.rotation[1]) + 0.0)


def flips(masks: NDArray[np.bool_], keep: NDArray[np.bool_]) -> float:
    """Mean over consecutive frames of the fraction of ``keep`` pixels whose mask changed.

    ``masks``: (F, H, W) shadowed or not per frame; ``keep``: (H, W) the pixels counted. NaN for
    fewer than two frames or no pixel kept.

    Example
    -------
    >>> m = np.array([[[True, False]], [[True, True]], [[False, True]]])   # 3 frames of 1 × 2 pixels
    >>> flips(m, np.ones((1, 2), bool))                                    # one of two pixels flips per frame
    0.5
    """
    masks, keep = np.asarray(masks, bool), np.asarray(keep, bool)
    if masks.ndim != 3 or masks.shape[1:] != keep.shape:
        raise ValueError(f"masks must be (F, H, W) with keep (H, W), got {masks.shape} and {keep.shape}")
    m = masks[:, keep]
    return float(np.mean(m[1:] != m[:-1])) if m.shape[1] and len(m) > 1 else float("nan")


def shimmer(result: FrameResult, scene: FrameScene, sun: Array, path: list[dict]) -> dict:
    """``flips_per_frame`` of the engine along ``path`` (its read-back ``path``) and as the toolkit
    predicts it (three.js: each pose's predicted matrices, the toolkit's maps and three.js's filter at
    the same pixels); details: the largest relative difference of the pose matrices."""
    from . import predict

    rb, s = result.readback, result.settings
    frames = rb.info.get("path") or []
    if len(frames) != len(path):
        raise ValueError("the page returned no camera path")
    h, w = rb.shadow.shape
    measured = np.array([np.frombuffer(__import__("base64").b64decode(f["shadow"]), np.float32).reshape(h, w)[::-1] for f in frames])
    keep = rb.drawn & (rb.cascade >= 0)
    out = {"measured": flips(measured < 0.5, keep), "predicted": None, "matrices_vs_engine": None}
    if rb.engine == "babylon":
        return {**out, **_babylon_shimmer(result, scene, sun, path, frames, keep)}
    model = MODELS[rb.engine] if rb.engine in MODELS else None
    if model is None or not hasattr(model, "matrices"):
        return out
    res = int(s["shadowMapSize"])
    cast = scene.triangles[predict.casting(scene.triangles, sun, model.cast_side(s))]
    fy, fx = np.mgrid[0:h, 0:w]
    pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
    masks, worst = [], 0.0
    for pose, f in zip(path, frames):
        cam = pose_camera(scene.camera, pose)
        mats = model.matrices(s, cam, sun)
        eng = np.array([np.asarray(m, float).reshape(4, 4).T for m in f["matrices"]])
        worst = max(worst, float(np.max(np.abs(mats - eng)) / np.max(np.abs(eng))))
        maps = [predict.light_depth_map(cast, m, res) for m in mats]
        fac = predict.threejs_factor(maps, mats, result.prediction.cascade, pts, nrm, fx + 0.5, (h - 1 - fy) + 0.5, bias=float(s["shadowBias"]),
                                     normal_bias=float(s["normalBias"]), radius=float(s["shadowRadius"]), map_type=s["shadowMapType"])
        masks.append(fac < 0.5)
    out["predicted"] = flips(np.array(masks), keep)
    out["matrices_vs_engine"] = worst
    return out


def _babylon_shimmer(result: FrameResult, scene: FrameScene, sun: Array, path: list[dict], frames: list[dict], keep) -> dict:
    """Babylon.js's predicted flips: each pose's predicted matrices (:mod:`aliasing.frames.babylon_cascades`),
    the toolkit's maps and Babylon.js's factor at the same pixels (the picture's cascades and depths)."""
    from . import babylon_cascades, predict

    rb, s = result.readback, result.settings
    model = MODELS["babylon"]
    cam0 = scene.camera
    h, w = rb.shadow.shape
    depth = np.where(rb.drawn, cam0.to_eye(np.nan_to_num(rb.position))[..., 2], np.nan)
    edges = model.edges(s, cam0)
    pct = float(s["cascadeBlendPercentage"])
    res = int(s["mapSize"])
    cast = predict.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, model.cast_side(s))], sun, float(s["normalBias"]))
    pts = np.nan_to_num(rb.position)
    to_unit = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
    masks, worst = [], 0.0
    for pose, f in zip(path, frames):
        cam = pose_camera(cam0, pose)
        mats = babylon_cascades.matrices(s, cam, sun, scene.triangles)
        eng = np.array([to_unit @ np.asarray(m, float).reshape(4, 4).T for m in f["matrices"]])
        worst = max(worst, float(np.max(np.abs(mats - eng)) / np.max(np.abs(eng))))
        maps = [predict.light_depth_map(cast, m, res) for m in mats]
        fac = predict.babylon_factor(maps, mats, result.prediction.cascade, depth, pts, ends=edges[1:], lengths=np.diff(edges),
                                     blend_factor=10000.0 if pct == 0 else 1 / pct, bias=float(s["bias"]))
        masks.append(fac < 0.5)
    return {"predicted": flips(np.array(masks), keep), "matrices_vs_engine": worst}


def replay(result: FrameResult, scene: FrameScene, sun: Array, path: list[dict], subpixel_bits: int | None = 4,
           float32_vertices: bool = False, float32_receivers: bool = False) -> dict:
    """An engine's path replayed by the toolkit through the *engine's* pose matrices (read back),
    with the casters' corners snapped to 1/2^``subpixel_bits`` texel (:func:`aliasing.frames.maps.snapped_depth_map`;
    SwiftShader: 4; None: exact): ``flips_per_frame`` and ``shared``, the fraction of the engine's
    flips (pixel and frame) that the replay also flips, and ``shared_pixels``, the fraction of the
    pixels the engine flips somewhere along the path that the replay flips too.  A diagnostic of
    where the engine's flips come from, when the toolkit's own prediction is 0 (ERRATA F7, F8).  ``float32_vertices``
    (three.js): the corners as the GPU's float32 vertex shader places them from each pose's own
    uniforms (:func:`aliasing.frames.maps.gpu_depth_map`; ``subpixel_bits`` must then be a number);
    ``float32_receivers`` (three.js): each pixel's shadow coordinate in float32 (``threejs_factor(float32=True)``).
    """
    if float32_vertices and (result.readback.engine != "threejs" or subpixel_bits is None):
        raise ValueError("float32_vertices is modelled for three.js's depth pass only, with subpixel_bits a number")
    if float32_receivers and result.readback.engine != "threejs":
        raise ValueError("float32_receivers is modelled for three.js's shadow lookup only")
    from . import maps as frame_maps, predict

    rb, s = result.readback, result.settings
    if rb.engine not in PATH_ENGINES:
        raise ValueError(f"replay is for {' and '.join(PATH_ENGINES)} frames, got {rb.engine!r}")
    frames = rb.info.get("path") or []
    if len(frames) != len(path):
        raise ValueError("the page returned no camera path")
    model = MODELS[rb.engine]
    h, w = rb.shadow.shape
    keep = rb.drawn & (rb.cascade >= 0)
    pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
    tri = np.asarray(scene.triangles, np.float32).astype(float)
    cast = tri[predict.casting(tri, sun, model.cast_side(s))]
    to_unit = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
    engine = np.array([np.frombuffer(__import__("base64").b64decode(f["shadow"]), np.float32).reshape(h, w)[::-1] for f in frames]) < 0.5
    if rb.engine == "babylon":
        cast = predict.offset_casters(cast, sun, float(s["normalBias"]))
        depth = np.where(rb.drawn, scene.camera.to_eye(pts)[..., 2], np.nan)
        edges = model.edges(s, scene.camera)
        pct = float(s["cascadeBlendPercentage"])
        res = int(s["mapSize"])

        def factor(maps, mats):
            return predict.babylon_factor(maps, mats, result.prediction.cascade, depth, pts, ends=edges[1:], lengths=np.diff(edges),
                                          blend_factor=10000.0 if pct == 0 else 1 / pct, bias=float(s["bias"]))
    else:
        fy, fx = np.mgrid[0:h, 0:w]
        res = int(s["shadowMapSize"])

        def factor(maps, mats):
            return predict.threejs_factor(maps, mats, result.prediction.cascade, pts, nrm, fx + 0.5, (h - 1 - fy) + 0.5, bias=float(s["shadowBias"]),
                                          normal_bias=float(s["normalBias"]), radius=float(s["shadowRadius"]), map_type=s["shadowMapType"],
                                          float32=float32_receivers)
    masks = []
    for f in frames:
        mats = np.array([(to_unit if rb.engine == "babylon" else np.eye(4)) @ np.asarray(m, float).reshape(4, 4).T for m in f["matrices"]])
        if float32_vertices:  # the depth pass's own uniforms of this pose
            if "views" not in f:
                raise ValueError("the page returned no depth-pass uniforms (views, projections) for the path")
            views, projs = ([np.asarray(m, float).reshape(4, 4).T for m in f[k]] for k in ("views", "projections"))
            maps = [frame_maps.gpu_depth_map(cast, v, p, res, subpixel_bits) for v, p in zip(views, projs)]
        else:
            maps = [frame_maps.snapped_depth_map(cast, m, res, subpixel_bits) for m in mats]
        masks.append(factor(maps, mats) < 0.5)
    masks = np.array(masks)
    fe, fp = np.diff(engine[:, keep], axis=0), np.diff(masks[:, keep], axis=0)
    pe, pp = fe.any(axis=0), fp.any(axis=0)  # the pixels that flip at all along the path
    return {"flips_per_frame": flips(masks, keep), "shared": float((fe & fp).sum() / fe.sum()) if fe.any() else None,
            "shared_pixels": float((pe & pp).sum() / pe.sum()) if pe.any() else None}
