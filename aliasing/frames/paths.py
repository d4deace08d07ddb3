"""Frames along a camera path: the poses, the pixels that flip between frames, and the toolkit's
prediction of them per engine (:func:`shimmer`), and a replay of the engine's own per-pose
matrices through the toolkit's rasterizer (:func:`replay`, the diagnostic of ERRATA F7, F8, F11).

The engine's page draws each pose's maps with the cascades' camera at the pose and the picture's
camera in place, so every pixel keeps its world point (:func:`aliasing.frames.run.frame_setup`).

Examples
--------
>>> from aliasing.frames.scenes import frame_scene
>>> cam = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=1, ground_cells=1).camera
>>> [p["eye"][0] for p in parse_path("sideways:0.25:3", cam)]   # the eye moves 0.25 to the right per frame
[0.0, 0.25, 0.5]
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from . import babylon_cascades
from .models import MODELS
from .readback import FrameResult
from .scenes import FrameScene, frame_scene  # noqa: F401 - frame_scene for the examples

Array = NDArray[np.float64]

PATHS = ("sideways", "forward", "turn")
PATH_ENGINES = ("threejs", "babylon", "playcanvas")


def parse_path(spec: str, camera) -> list[dict]:
    """Camera poses of ``KIND:STEP[:FRAMES]``: KIND ``sideways`` (along the camera's right) or
    ``forward`` (along its view), STEP [world units per frame, finite, non-zero], or ``turn``
    (the view turned about the world's up, y, through the eye; STEP [degrees per frame, at most 10 in size]);
    FRAMES in [3, 120] (default 30); the first pose is the camera itself.

    Examples
    --------
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
    """``camera`` moved to a pose of :func:`parse_path` (its eye, looking at its target, with the camera's own up).

    Examples
    --------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> c = pose_camera(look_at("0,0,0", "0,0,-1"), {"eye": [1.0, 2.0, 0.0], "target": [1.0, 2.0, 5.0]})
    >>> c.eye.tolist(), np.round(c.rotation[2], 12).tolist()          # now looking along +z
    ([1.0, 2.0, 0.0], [0.0, 0.0, 1.0])
    """
    if not isinstance(pose, dict) or "eye" not in pose or "target" not in pose:
        raise ValueError(f"pose must be a dict with eye and target (parse_path), got {pose!r}")
    e, t = np.asarray(pose["eye"], float), np.asarray(pose["target"], float)
    if e.shape != (3,) or t.shape != (3,) or not np.all(np.isfinite(e) & np.isfinite(t)) or not np.linalg.norm(t - e) > 0:
        raise ValueError(f"pose eye and target must be finite 3-vectors [world units] that differ, got {pose!r}")
    from ..raster.scenes.camera import frame

    eye = np.asarray(pose["eye"], float)
    return replace(camera, eye=eye, rotation=frame(np.asarray(pose["target"], float) - eye, camera.rotation[1]) + 0.0)


def flips(masks: NDArray[np.bool_], keep: NDArray[np.bool_]) -> float:
    """Mean over consecutive frames of the fraction of ``keep`` pixels whose mask changed.

    ``masks``: (F, H, W) shadowed or not per frame; ``keep``: (H, W) the pixels counted. NaN for
    fewer than two frames or no pixel kept.

    Examples
    --------
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
    the same pixels; Babylon.js and PlayCanvas alike with their own); details: the largest relative
    difference of the pose matrices.

    Examples
    --------
    >>> import base64
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.run import measure
    >>> from aliasing.frames.scenes import sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera); m = MODELS["threejs"]; s = m.settings({"cascades": 2, "shadowMapSize": 256})
    >>> b64 = lambda a: base64.b64encode(np.asarray(a, np.float32).tobytes()).decode()
    >>> out = {"engine": "threejs", "revision": "187", "width": 2, "height": 1, "frame": "data:image/png;base64,",   # a page's answer, by hand:
    ...        "shadow": b64([[[0, 0, 0, 0], [1, 1, 0.3, 0]]]),                     # per pixel factor, cascade, n·l
    ...        "position": b64([[[-2.0, -1.0, -4.25, 1.0], [0.0, -1.0, -12.0, 1.0]]]), # two ground pixels, drawn (w = 1)
    ...        "normal": b64([[[0, 1, 0, 0]] * 2]), "breaks": (m.edges(s, fs.camera)[1:] / 20.0).tolist(),
    ...        "cascades": [{"matrix": c.T.ravel().tolist(), "size": [256, 256]} for c in m.matrices(s, fs.camera, sun)]}
    >>> path = parse_path("sideways:0.05:3", fs.camera)                          # and its camera path: the same two pixels
    >>> out["path"] = [{"shadow": b64([[0, 1]]), "matrices": [c.T.ravel().tolist() for c in m.matrices(s, pose_camera(fs.camera, p), sun)]}
    ...                for p in path]
    >>> r = measure("threejs", fs, sun, s, out)
    >>> shimmer(r, fs, sun, path)
    {'measured': 0.0, 'predicted': 0.0, 'matrices_vs_engine': 0.0}
    """
    if not isinstance(result, FrameResult):
        raise ValueError(f"result must be a FrameResult (measure, frame_setup), got {type(result).__name__}")
    if not isinstance(path, list) or len(path) < 2:
        raise ValueError(f"path must be a list of at least 2 poses (parse_path), got {type(path).__name__}")
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
    if rb.engine == "playcanvas":
        return {**out, **_playcanvas_shimmer(result, scene, sun, path, frames, keep)}
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
    cast = babylon_cascades.offset_casters(scene.triangles[predict.casting(scene.triangles, sun, model.cast_side(s))], sun, float(s["normalBias"]))
    pts = np.nan_to_num(rb.position)
    to_unit = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
    masks, worst = [], 0.0
    for pose, f in zip(path, frames):
        cam = pose_camera(cam0, pose)
        mats = babylon_cascades.matrices(s, cam, sun, scene.triangles, aspect=w / h, float32=False)  # the grid's motion: float64 (ERRATA F8)
        eng = np.array([to_unit @ np.asarray(m, float).reshape(4, 4).T for m in f["matrices"]])
        worst = max(worst, float(np.max(np.abs(mats - eng)) / np.max(np.abs(eng))))
        maps = [predict.light_depth_map(cast, m, res) for m in mats]
        fac = predict.babylon_factor(maps, mats, result.prediction.cascade, depth, pts, ends=edges[1:], lengths=np.diff(edges),
                                     blend_factor=10000.0 if pct == 0 else 1 / pct, bias=float(s["bias"]), quality=int(s["filteringQuality"]))
        masks.append(fac < 0.5)
    return {"predicted": flips(np.array(masks), keep), "matrices_vs_engine": worst}


def _playcanvas_shimmer(result: FrameResult, scene: FrameScene, sun: Array, path: list[dict], frames: list[dict], keep) -> dict:
    """PlayCanvas's predicted flips: each pose's predicted palette (:meth:`aliasing.frames.models.PlayCanvas.light_matrices`),
    the toolkit's atlas and PlayCanvas's factor at the same pixels (the picture's cascades); details:
    the largest relative difference of the pose matrices, whole and in their s and t rows."""
    from . import predict

    rb, s = result.readback, result.settings
    model = MODELS["playcanvas"]
    if model.predicted(s):
        return {"predicted": None, "matrices_vs_engine": None}
    cast = scene.triangles[predict.casting(scene.triangles, sun, model.cast_side(s))]
    pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
    masks, worst, grid = [], 0.0, 0.0
    for pose, f in zip(path, frames):
        mats = model.light_matrices(s, pose_camera(scene.camera, pose), sun, scene.triangles)
        eng = np.array([np.asarray(m, float).reshape(4, 4).T for m in f["matrices"]])
        worst = max(worst, float(np.max(np.abs(mats - eng)) / np.max(np.abs(eng))))
        grid = max(grid, float(np.max(np.abs(mats - eng)[:, :2]) / np.max(np.abs(eng))))
        masks.append(_playcanvas_factor(model, s, cast, mats, result.prediction.cascade, pts, nrm, None) < 0.5)
    return {"predicted": flips(np.array(masks), keep), "matrices_vs_engine": worst, "grid_vs_engine": grid}


def _playcanvas_factor(model, s: dict, cast: Array, mats: Array, cascade, pts: Array, nrm: Array, subpixel_bits: int | None) -> Array:
    from . import predict

    atlas = predict.playcanvas_atlas(cast, mats, model.cells(s), int(s["shadowResolution"]), float(s["shadowBias"]), subpixel_bits=subpixel_bits)
    return predict.playcanvas_factor(atlas, mats, cascade, pts, nrm, normal_offset=float(s["normalOffsetBias"]), taps=model.FILTERS[int(s["shadowType"])])


def replay(result: FrameResult, scene: FrameScene, sun: Array, path: list[dict], subpixel_bits: int | None = 4,
           float32_vertices: bool = False, float32_receivers: bool = False) -> dict:
    """An engine's path replayed by the toolkit through the *engine's* pose matrices (read back),
    with the casters' corners snapped to 1/2^``subpixel_bits`` texel (:func:`aliasing.frames.maps.snapped_depth_map`;
    SwiftShader: 4; None: exact): ``flips_per_frame`` and ``shared``, the fraction of the engine's
    flips (pixel and frame) that the replay also flips, and ``shared_pixels``, the fraction of the
    pixels the engine flips somewhere along the path that the replay flips too.  A diagnostic of
    where the engine's flips come from, when the toolkit's own prediction is 0 (ERRATA F7, F8, F11).
    ``float32_vertices`` (three.js): the corners as the GPU's float32 vertex shader places them from
    each pose's own uniforms (:func:`aliasing.frames.maps.gpu_depth_map`; ``subpixel_bits`` must then
    be a number); ``float32_receivers`` (three.js): each pixel's shadow coordinate in float32
    (``threejs_factor(float32=True)``).

    Examples
    --------
    >>> import base64
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.run import measure
    >>> from aliasing.frames.scenes import sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera); m = MODELS["threejs"]; s = m.settings({"cascades": 2, "shadowMapSize": 256})
    >>> b64 = lambda a: base64.b64encode(np.asarray(a, np.float32).tobytes()).decode()
    >>> out = {"engine": "threejs", "revision": "187", "width": 2, "height": 1, "frame": "data:image/png;base64,",   # a page's answer, by hand:
    ...        "shadow": b64([[[0, 0, 0, 0], [1, 1, 0.3, 0]]]),                     # per pixel factor, cascade, n·l
    ...        "position": b64([[[-2.0, -1.0, -4.25, 1.0], [0.0, -1.0, -12.0, 1.0]]]), # two ground pixels, drawn (w = 1)
    ...        "normal": b64([[[0, 1, 0, 0]] * 2]), "breaks": (m.edges(s, fs.camera)[1:] / 20.0).tolist(),
    ...        "cascades": [{"matrix": c.T.ravel().tolist(), "size": [256, 256]} for c in m.matrices(s, fs.camera, sun)]}
    >>> path = parse_path("sideways:0.05:3", fs.camera)                          # and its camera path: the same two pixels
    >>> out["path"] = [{"shadow": b64([[0, 1]]), "matrices": [c.T.ravel().tolist() for c in m.matrices(s, pose_camera(fs.camera, p), sun)]}
    ...                for p in path]
    >>> r = measure("threejs", fs, sun, s, out)
    >>> replay(r, fs, sun, path)
    {'flips_per_frame': 0.0, 'shared': None, 'shared_pixels': None}
    """
    if not isinstance(result, FrameResult):
        raise ValueError(f"result must be a FrameResult (measure, frame_setup), got {type(result).__name__}")
    if subpixel_bits is not None and not (isinstance(subpixel_bits, (int, np.integer)) and 0 <= subpixel_bits <= 16):
        raise ValueError(f"subpixel_bits must be a whole number in [0, 16] or None, got {subpixel_bits!r}")
    if float32_vertices and (result.readback.engine != "threejs" or subpixel_bits is None):
        raise ValueError("float32_vertices is modelled for three.js's depth pass only, with subpixel_bits a number")
    if float32_receivers and result.readback.engine != "threejs":
        raise ValueError("float32_receivers is modelled for three.js's shadow lookup only")
    from . import maps as frame_maps, predict

    rb, s = result.readback, result.settings
    if rb.engine not in PATH_ENGINES:
        raise ValueError(f"replay is for {', '.join(PATH_ENGINES)} frames, got {rb.engine!r}")
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
    if rb.engine == "playcanvas":
        if model.predicted(s):
            raise ValueError(f"replay needs predicted PlayCanvas settings: {model.predicted(s)}")
        masks = np.array([_playcanvas_factor(model, s, cast, np.array([np.asarray(m, float).reshape(4, 4).T for m in f["matrices"]]),
                                             result.prediction.cascade, pts, nrm, subpixel_bits) < 0.5 for f in frames])
        fe, fp = np.diff(engine[:, keep], axis=0), np.diff(masks[:, keep], axis=0)
        return {"flips_per_frame": flips(masks, keep), "shared": float((fe & fp).sum() / fe.sum()) if fe.any() else None}
    if rb.engine == "babylon":
        cast = babylon_cascades.offset_casters(cast, sun, float(s["normalBias"]))
        depth = np.where(rb.drawn, scene.camera.to_eye(pts)[..., 2], np.nan)
        edges = model.edges(s, scene.camera)
        pct = float(s["cascadeBlendPercentage"])
        res = int(s["mapSize"])

        def factor(maps, mats):
            return predict.babylon_factor(maps, mats, result.prediction.cascade, depth, pts, ends=edges[1:], lengths=np.diff(edges),
                                          blend_factor=10000.0 if pct == 0 else 1 / pct, bias=float(s["bias"]), quality=int(s["filteringQuality"]))
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
