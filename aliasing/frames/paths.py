"""Frames along a camera path: the poses, the pixels that flip between frames, and the toolkit's
prediction of them per engine (:func:`shimmer`), and a replay of the engine's own per-pose
matrices through the toolkit's rasterizer (:func:`replay`, the diagnostic of ERRATA F7, F8, F11).

The engine's page draws each pose's maps with the cascades' camera at the pose and the picture's
camera in place, so every pixel keeps its world point (:func:`aliasing.frames.run.frame_setup`).
Godot fits its shadow to the camera it draws only: its picture moves with the camera, and its
flips are counted at the world points two consecutive poses both see (:func:`matched_flips`,
:func:`godot_shimmer`).

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

from .. import _validation as check
from ..view import tan_theta
from . import babylon_cascades
from .models import MODELS
from .readback import FrameResult
from .scenes import FrameScene, frame_scene  # noqa: F401 - frame_scene for the examples

Array = NDArray[np.float64]

PATHS = ("sideways", "forward", "turn")
#: the engines whose page holds the picture's camera in place while the cascades follow the path
PATH_ENGINES = ("threejs", "babylon", "playcanvas")
#: the engines whose picture moves with the camera along the path (flips counted at matched world points, :func:`matched_flips`)
MOVING_ENGINES = ("godot",)
#: :func:`matched_flips`'s visibility test: a point is seen again where the next pose's pixel holds a point this
#: fraction of its distance from that pose's eye away, on a surface turned the same way (normals within 8°)
MATCH_TOLERANCE, MATCH_COS = 0.02, float(np.cos(np.radians(8.0)))


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


def matched_flips(factors, positions, normals, keep, cameras: list, tolerance: float = MATCH_TOLERANCE) -> dict:
    """Flips per frame at matched world points, for frames whose camera moves (Godot's path).

    For consecutive frames k, k + 1, each kept pixel of frame k is reprojected through frame
    k + 1's camera; it is *matched* where it lands in the image on a kept pixel whose point lies
    within ``tolerance`` · (its distance from frame k + 1's eye) of it, with normals within 8°
    (a visibility test: the point is seen again, not hidden behind another surface).  A flip is a
    matched point whose factor crosses ½ between the two frames.

    Parameters
    ----------
    factors : array_like (F, H, W)
        The shadow factor per frame and pixel (rows top down); F ≥ 2.
    positions, normals : array_like (F, H, W, 3)
        Each pixel's world point [world units] and unit normal.
    keep : array_like of bool (F, H, W)
        The pixels counted (drawn, within the shadow's range).
    cameras : list of Camera
        Each frame's camera (:func:`pose_camera`), with the image's aspect.
    tolerance : float
        The visibility test's distance, as a fraction of the distance from the eye, in (0, 1).

    Returns
    -------
    dict
        ``flips_per_frame`` (the mean over the F − 1 pairs of flips / matched points; None where no pair
        matched a point) and ``matched`` (the mean fraction of frame k's kept pixels matched in k + 1).

    Examples
    --------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> cams = [pose_camera(look_at("0,1,0", "0,0,-4"), {"eye": [x, 1.0, 0.0], "target": [x, 0.0, -4.0]}) for x in (0.0, 0.0)]
    >>> pts = np.zeros((2, 2, 2, 3)); pts[...] = [0.0, 0.0, -4.0]          # every pixel sees the same point of the ground
    >>> up = np.zeros((2, 2, 2, 3)); up[..., 1] = 1.0
    >>> f = np.array([np.ones((2, 2)), np.zeros((2, 2))])                 # lit, then shadowed
    >>> matched_flips(f, pts, up, np.ones((2, 2, 2), bool), cams)["flips_per_frame"]
    1.0
    """
    f, pos, nrm = _reals(factors, "factors"), _reals(positions, "positions"), _reals(normals, "normals")
    keep = np.asarray(keep, bool) if _reals(keep, "keep").size else np.zeros(0, bool)
    if f.ndim != 3 or len(f) < 2 or pos.shape != f.shape + (3,) or nrm.shape != pos.shape or keep.shape != f.shape:
        raise ValueError(f"factors must be (F, H, W) with F >= 2, positions and normals (F, H, W, 3), keep (F, H, W); "
                         f"got {f.shape}, {pos.shape}, {nrm.shape}, {keep.shape}")
    if not isinstance(cameras, (list, tuple)) or len(cameras) != len(f) or not all(hasattr(c, "to_eye") for c in cameras):
        raise ValueError(f"cameras must be one camera per frame ({len(f)}), got {type(cameras).__name__}")
    tol = check.scalar(tolerance, "tolerance")
    if not 0 < tol < 1:
        raise ValueError(f"tolerance must be in (0, 1) [fraction of the distance from the eye], got {tolerance!r}")
    keep = keep & np.all(np.isfinite(pos), -1) & np.all(np.isfinite(nrm), -1) & np.isfinite(f)
    _, h, w = f.shape
    rates, matched = [], []
    for k in range(len(f) - 1):                       # one vectorized pass per pair of frames
        cam = cameras[k + 1]
        p, a = pos[k][keep[k]], f[k][keep[k]]
        e = cam.to_eye(p)
        t = float(tan_theta(cam.fov))
        with np.errstate(divide="ignore", invalid="ignore"):
            col = np.floor((e[:, 0] / (e[:, 2] * t * cam.aspect) + 1) / 2 * w)
            row = np.floor((1 - e[:, 1] / (e[:, 2] * t)) / 2 * h)
        inside = (e[:, 2] > 0) & (col >= 0) & (col < w) & (row >= 0) & (row < h)
        r, c = np.where(inside, row, 0).astype(np.int64), np.where(inside, col, 0).astype(np.int64)
        q = pos[k + 1][r, c]
        same = inside & keep[k + 1][r, c] & (np.linalg.norm(q - p, axis=-1) <= tol * np.linalg.norm(e, axis=-1)) \
            & (np.sum(nrm[k][keep[k]] * nrm[k + 1][r, c], -1) >= MATCH_COS)
        matched.append(float(np.mean(same)) if len(same) else 0.0)
        if same.any():
            rates.append(float(np.mean((a[same] < 0.5) != (f[k + 1][r, c][same] < 0.5))))
    return {"flips_per_frame": float(np.mean(rates)) if rates else None, "matched": float(np.mean(matched))}


def _reals(value, name: str) -> Array:
    """An array of real numbers, NaN allowed (what is not drawn), named in the refusal."""
    raw = np.asarray(value) if not isinstance(value, (str, bytes)) and value is not None else np.asarray([""])
    if raw.dtype.kind not in "biuf":
        raise ValueError(f"{name} must be an array of real numbers, got {type(value).__name__}")
    return raw.astype(float)


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
    if rb.engine in MOVING_ENGINES:
        return godot_shimmer(result, scene, sun, path)
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


def godot_shimmer(result: FrameResult, scene: FrameScene, sun: Array, path: list[dict], matrices: str = "model") -> dict:
    """Godot's flips along ``path``, measured and predicted, at matched world points (:func:`matched_flips`).

    Godot fits its directional shadow to the camera that draws the picture, so its page moves the
    camera itself along the path: each pose's read-back is its own (the factor Godot drew, the
    toolkit's eye pass through the pose's camera for the world points and normals, the split
    matrices Godot uploaded; :meth:`aliasing.frames.models.godot.Godot.readback`), and each pose's
    factor is predicted from it as for a single frame (:meth:`~aliasing.frames.models.godot.Godot.predict`
    through the toolkit's own matrices of the pose, ``matrices="model"``; ``"unsnapped"``: without
    Godot's 4r/R snap; ``"engine"``: through Godot's).  Returns ``measured`` and ``predicted``
    (flips per frame), ``matched`` (the fraction of each pose's pixels seen again in the next),
    ``resampling`` (the flips per frame of the exact shadows, no map at all, at the same points: the
    pixels' own motion, a matched point's neighbour lies up to half a pixel away),
    ``matrices_vs_engine`` (the largest relative difference of the poses' split matrices, the
    toolkit's snapped ones against Godot's) and ``view_vs_toolkit`` (the largest difference of a
    pose's camera view as Godot held it and the pose's).

    Examples
    --------
    The poses come from Godot's page, so the example's render is not run here; its bad input is:

    >>> godot_shimmer(None, None, [0.0, 1.0, 0.0], [])
    Traceback (most recent call last):
    ...
    ValueError: result must be Godot's FrameResult (frame_setup with a path)
    >>> godot_shimmer(r, fs, sun, parse_path("sideways:0.05:4", fs.camera))["measured"]   # doctest: +SKIP
    0.0088
    """
    from .models.godot import Godot
    from .readback import decode

    if not isinstance(result, FrameResult) or result.readback.engine != "godot":
        raise ValueError("result must be Godot's FrameResult (frame_setup with a path)")
    which = check.choice(matrices, "matrices", ("engine", "model", "unsnapped"))
    rb, s, model = result.readback, result.settings, Godot()
    frames = rb.info.get("path") or []
    if not isinstance(path, list) or len(path) < 2 or len(frames) != len(path):
        raise ValueError(f"path must be the {len(frames)} poses Godot's page rendered (parse_path), got {len(path) if isinstance(path, list) else path!r}")
    base = {k: rb.info[k] for k in ("engine", "revision", "width", "height", "light") if k in rb.info}
    cams, got, pred, lit, worst, view = [], [], [], [], 0.0, 0.0
    for pose, f in zip(path, frames):
        sc = replace(scene, camera=pose_camera(scene.camera, pose))
        rk = decode(model.readback({**base, **f, "frame": ""}, sc, sun))
        own = model.matrices(s, sc.camera, sun)
        worst = max(worst, float(np.max(np.abs(own - rk.matrices)) / np.max(np.abs(rk.matrices))))
        view = max(view, rk.info["checks"]["view_vs_toolkit"])
        p, ref = model.predict(s, sc, sun, rk, matrices=which)
        cams.append(sc.camera)
        got.append(rk)
        pred.append(p.factor)
        lit.append(ref.astype(float))
    pos, nrm = np.array([g.position for g in got]), np.array([g.normal for g in got])
    keep = np.array([g.drawn & (g.cascade >= 0) for g in got])
    measured = matched_flips(np.array([g.shadow for g in got]), pos, nrm, keep, cams)
    predicted = matched_flips(np.array(pred), pos, nrm, keep, cams)
    return {"measured": measured["flips_per_frame"], "predicted": predicted["flips_per_frame"], "matched": measured["matched"],
            "resampling": matched_flips(np.array(lit), pos, nrm, keep, cams)["flips_per_frame"],
            "matrices_vs_engine": worst, "view_vs_toolkit": view}


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
