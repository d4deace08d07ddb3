"""The wrong-pixel measure: how much of what the user sees a setup's shadows get wrong, per cascade.

For a :class:`aliasing.setups.Setup` and a scene (default :func:`~aliasing.frames.seen.scene.reference_scene`), the
frame the engine would draw is predicted without a browser (:mod:`aliasing.frames.seen.synth`) for ``suns`` suns
evenly over the setup's elevation band (at its azimuth), on a small image of the setup's camera
(``height`` rows: a sample of the view; the fractions are of its area).  Each drawn pixel is
compared with the exact shadow (:func:`aliasing.frames.predict.reference`); shaded means a
predicted factor below ½.  Counted over every sun:

``pixels``
    The denominator: the drawn pixels facing the sun (cos > :data:`aliasing.frames.compare.MIN_COS`),
    the pixels whose light a shadow can change.
``acne``
    Lit pixels shaded by their own surface: exactly lit, shaded, and farther than the filter's
    reach (:func:`reach_px`) from every pixel the exact solution leaves dark (in shadow or facing
    away from the sun), so that no shadow edge explains them.
``false_shadow``
    Shadow beyond the exact one: exactly lit, shaded, within the filter's reach of an exactly dark
    pixel: shadows grown past their outline by the texels (blocky edges) and the filter.
``lost_shadow``
    Exactly shadowed pixels shaded lit: peter-panning at contacts, shadows shortened by normal
    offsets, thin casters missed, and everything beyond the last cascade.
``wrong``
    acne + false_shadow + lost_shadow: the three are disjoint, over the same ``pixels``.
``blocky``
    Its own axis, over the cascade's drawn pixels (any facing): the fraction whose map texel is
    larger than one pixel of the user's image (the camera's full height, not the sample's): the
    texel side (the cascade's map side over its texels) over the pixel's side at the pixel's eye
    depth d, 2 d tan(fov/2) / height, above 1.
``memory``
    Its own axis: the bytes of the cascade's maps (the pipeline's memory over its cascades).

Pixels beyond the last cascade (no shadow drawn) form the row ``cascade = "beyond"``; the
``total`` sums every row.  Fractions are in [0, 1]; None where a denominator is 0.

Examples
--------
>>> from aliasing import setups
>>> s = setups.build("playcanvas", {"numCascades": 2, "shadowResolution": 512}, "near=0.5,far=60,fov=50,aspect=16:9,height=1080", "30..50")
>>> w = wrong_pixels(s, height=36, suns=2)
>>> [c["cascade"] for c in w.cascades], sorted(w.total)
([0, 1, 'beyond'], ['acne', 'blocky', 'false_shadow', 'lost_shadow', 'pixels', 'wrong'])
"""

from __future__ import annotations

import math
import os
from concurrent import futures
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage

from ... import _validation as check
from ..compare import MIN_COS
from ..predict import GEOMETRY_KEY, geometry_digest
from ..run import at_pixel_aspect, predict_readback
from ...view import tan_theta
from ..scenes import FrameScene, frame_scene, sun_direction
from .scene import reference_scene
from .synth import VISIBLE, engine_settings, eye_geometry, synthetic_readback

Array = NDArray[np.float64]
#: Suns measured at once (threads: numpy's array work runs outside the interpreter's lock), at most the machine's cores.
WORKERS = max(1, min(4, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)))
#: What each number of :meth:`Wrong.to_dict` is in.
UNITS = {"pixels": "pixels (sample image, summed over the suns)", "acne": "fraction of pixels", "false_shadow": "fraction of pixels",
         "lost_shadow": "fraction of pixels", "wrong": "fraction of pixels", "blocky": "fraction of the cascade's drawn pixels",
         "memory": "bytes"}


@dataclass(frozen=True)
class Wrong:
    """What :func:`wrong_pixels` found: a row per cascade (and ``beyond``), the ``total`` and the ``sample`` measured.

    Examples
    --------
    >>> w = Wrong(({"cascade": 0, "pixels": 10, "acne": 0.1, "false_shadow": 0.0, "lost_shadow": None, "wrong": 0.1, "blocky": 0.5,
    ...            "memory": 4},), {"pixels": 10}, {"scene": "reference"})
    >>> sorted(w.to_dict())
    ['cascades', 'sample', 'total', 'units']
    """

    cascades: tuple
    total: dict
    sample: dict

    def to_dict(self) -> dict:
        """JSON-ready: ``cascades``, ``total``, ``sample`` and ``units`` (no NaN: None where undefined)."""
        return {"cascades": [dict(c) for c in self.cascades], "total": dict(self.total), "sample": dict(self.sample), "units": dict(UNITS)}


def reach_px(taps: int, texel: Array, pixel: Array) -> Array:
    """How far [px] a shadow edge can spread: (taps / 2 + 1) texels (the filter's half width and the texel the edge falls in), in pixels.

    Parameters
    ----------
    taps : int
        The filter's width [texels], >= 1.
    texel, pixel : array_like
        The map texel's side and the image pixel's side at the same points [world units], > 0.

    Examples
    --------
    >>> reach_px(3, np.array([0.1, 0.01]), np.array([0.05, 0.05])).tolist()    # 2.5 texels of 2 px, of 0.2 px
    [5.0, 0.5]
    """
    t = check.whole(taps, "taps", 1, 64, " [texels]")
    return (t / 2 + 1) * np.asarray(texel, float) / np.asarray(pixel, float)


def classify(factor: Array, ref: NDArray[np.bool_], drawn: NDArray[np.bool_], facing: NDArray[np.bool_], reach: Array) -> dict:
    """The per-pixel masks of the module docstring: ``acne``, ``false_shadow``, ``lost_shadow`` (disjoint, within ``facing``).

    ``ref``: exactly lit; ``reach`` [px] per pixel (:func:`reach_px`).

    Examples
    --------
    >>> ref = np.array([[False, True, True, True, True]]); every = np.ones((1, 5), bool)
    >>> m = classify(np.array([[1.0, 0.0, 1.0, 1.0, 0.0]]), ref, every, every, np.full((1, 5), 1.5))
    >>> {k: v.astype(int).tolist()[0] for k, v in m.items()}    # a lit gap, a grown edge, acne far from the shadow
    {'acne': [0, 0, 0, 0, 1], 'false_shadow': [0, 1, 0, 0, 0], 'lost_shadow': [1, 0, 0, 0, 0]}
    """
    shaded = np.nan_to_num(factor, nan=1.0) < 0.5
    dark = drawn & ~ref
    far = ndimage.distance_transform_edt(~dark) if dark.any() else np.full(ref.shape, np.inf)
    lit_shaded = facing & ref & shaded
    edge = far <= reach
    return {"acne": lit_shaded & ~edge, "false_shadow": lit_shaded & edge, "lost_shadow": facing & ~ref & ~shaded}


def _scene(setup, scene, eye, target) -> FrameScene:
    cam = setup.camera
    if scene is None:
        return reference_scene(cam.near, cam.far, cam.fov, cam.aspect)
    if isinstance(scene, FrameScene):
        return scene
    if isinstance(scene, str):
        return frame_scene(scene, near=cam.near, far=cam.far, fov=cam.fov, aspect=cam.aspect, eye=eye, target=target)
    raise ValueError(f"scene must be None (the reference scene), boxes, city, a scene file or a FrameScene, got {type(scene).__name__}")


def _fraction(num: int, den: int) -> float | None:
    return float(num / den) if den else None


@dataclass(frozen=True)
class Sample:
    """What :func:`wrong_pixels` measures on, for a camera, a scene and a sun band: kept between setups of the same camera.

    Built by :func:`sample`; :func:`count` measures a setup on it.  Holds the scene, the eye pass
    (:func:`~aliasing.frames.seen.synth.eye_geometry`) of the ``side`` faces the main pass draws,
    each sample pixel's eye depth, the side [world units] of one pixel of the sample and of the
    user's image there, the suns' elevations [deg] and azimuth [deg], and a digest of its pixels
    and scene (:func:`aliasing.frames.predict.geometry_digest`).

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("playcanvas", {}, "near=0.5,far=60,fov=50,aspect=2,height=720", "30..50")
    >>> sm = sample(s, height=32, suns=2)
    >>> sm.height, sm.width, sm.elevations, bool((sm.pixel_user < sm.pixel_small)[sm.geometry[2]].all())   # the user's pixel is the smaller
    (32, 64, (30.0, 50.0), True)
    """

    scene: FrameScene
    camera: object
    side: str
    geometry: tuple
    depth: Array
    pixel_small: Array
    pixel_user: Array
    elevations: tuple
    azimuth: float
    height: int
    width: int
    digest: bytes = b""


def sample(setup, scene: FrameScene | str | None = None, *, eye=None, target=None, height: int = 144, suns: int = 3) -> Sample:
    """The :class:`Sample` of ``setup``'s camera, sun band and main-pass faces on ``scene`` (parameters: :func:`wrong_pixels`).

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 2, "shadowMapSize": 512}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", "30..50")
    >>> sm = sample(s, height=36, suns=2)
    >>> sm.geometry[2].shape, sm.elevations
    ((36, 64), (30.0, 50.0))
    """
    _, settings = engine_settings(setup)
    h = check.whole(height, "height", 16, 1080, " [px] (rows of the sample image)")
    n = check.whole(suns, "suns", 1, 16, " (suns over the elevation band)")
    fs = _scene(setup, scene, eye, target)
    from ...setups import Setup, spec

    cam = setup.camera
    small, fs = at_pixel_aspect(Setup(setup.profile, dict(setup.settings), spec.Camera(cam.near, cam.far, cam.fov, cam.aspect, h), setup.sun), fs)
    side = VISIBLE[setup.engine](settings)
    geometry = eye_geometry(fs, small.camera.width, h, side)
    drawn = geometry[2]
    if not drawn.any():
        raise ValueError(f"scene: nothing is drawn within near..far ({cam.near:g}..{cam.far:g}) by this camera")
    depth = np.where(drawn, fs.camera.to_eye(np.nan_to_num(geometry[0]))[..., 2], np.nan)
    tan = float(tan_theta(cam.fov))
    return Sample(fs, cam, side, geometry, depth, 2 * depth * tan / h, 2 * depth * tan / cam.height,
                  tuple(float(v) for v in setup.sun.elevations(n)), float(setup.sun.azimuth), h, int(small.camera.width),
                  geometry_digest(drawn, geometry[0], geometry[1], fs.triangles))


def count(setup, where: Sample) -> Wrong:
    """The wrong-pixel measure of ``setup`` on a :class:`Sample` of its camera and sun band (module docstring).

    Raises
    ------
    ValueError
        ``where`` not a Sample, or one of another camera, sun band or main-pass faces than ``setup``'s.

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("playcanvas", {"numCascades": 2, "shadowResolution": 512}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", 40)
    >>> sm = sample(s, height=36, suns=1)
    >>> count(s, sm).total == wrong_pixels(s, height=36, suns=1).total    # the sample kept, the same numbers
    True
    """
    model, settings = engine_settings(setup)
    if not isinstance(where, Sample):
        raise ValueError(f"where must be a Sample (aliasing.frames.seen.sample(...)), got {type(where).__name__}")
    if (where.camera != setup.camera or where.side != VISIBLE[setup.engine](settings) or where.azimuth != float(setup.sun.azimuth)
            or not all(setup.sun.elevation[0] <= e <= setup.sun.elevation[1] for e in where.elevations)):
        raise ValueError("where: the sample is of another camera, sun band or main-pass faces than setup's: take sample(setup, ...) again")
    fs, geometry, drawn = where.scene, where.geometry, where.geometry[2]
    taps = max(1, int(setup.pipeline.filter.taps))

    def one_sun(e: float) -> NDArray[np.int64]:  # each sun draws its own maps: the suns share nothing but the memo
        sun = sun_direction(float(e), setup.sun.azimuth, fs.camera)
        rb = synthetic_readback(model, settings, fs, sun, geometry, setup.engine)
        if where.digest:  # the sample's pixels and scene, digested once
            rb.info[GEOMETRY_KEY] = where.digest
        pred, ref, _, _ = predict_readback(model, settings, fs, sun, rb)
        k = len(pred.sides)
        texel = np.append(pred.sides / pred.resolution, np.nan)[pred.cascade]  # −1 (no cascade) picks NaN
        facing = drawn & ((np.nan_to_num(geometry[1]) @ sun) > MIN_COS)
        masks = classify(pred.factor, ref, drawn, facing, np.nan_to_num(reach_px(taps, texel, where.pixel_small), nan=0.0))
        row = np.where(pred.cascade >= 0, pred.cascade, k)  # k: beyond the last cascade
        layers = [facing, masks["acne"], masks["false_shadow"], masks["lost_shadow"], drawn,
                  drawn & (np.nan_to_num(texel / where.pixel_user) > 1)]
        return np.stack([np.bincount(row[m], minlength=k + 1) for m in layers])

    workers = min(WORKERS, len(where.elevations))
    if workers > 1:
        with futures.ThreadPoolExecutor(workers) as pool:
            counts = sum(pool.map(one_sun, where.elevations))
    else:
        counts = sum(map(one_sun, where.elevations))
    k = counts.shape[1] - 1
    memory = int(setup.pipeline.memory)
    rows = []
    for i in range(k + 1):
        pix, acne, false, lost, shown, blocky = (int(v) for v in counts[:, i])
        rows.append({"cascade": i if i < k else "beyond", "pixels": pix, "acne": _fraction(acne, pix), "false_shadow": _fraction(false, pix),
                     "lost_shadow": _fraction(lost, pix), "wrong": _fraction(acne + false + lost, pix),
                     "blocky": _fraction(blocky, shown) if i < k else None, "memory": memory // k if i < k else 0})
    tot = counts.sum(axis=1)
    total = {"pixels": int(tot[0]), "acne": _fraction(tot[1], tot[0]), "false_shadow": _fraction(tot[2], tot[0]), "lost_shadow": _fraction(tot[3], tot[0]),
             "wrong": _fraction(tot[1] + tot[2] + tot[3], tot[0]), "blocky": _fraction(counts[5, :k].sum(), counts[4, :k].sum())}
    info = {"scene": fs.name, "elevations": list(where.elevations), "azimuth": where.azimuth, "width_px": where.width,
            "height_px": where.height, "image_height_px": int(setup.camera.height), "filter_taps": taps, "memory": memory}
    return Wrong(tuple(rows), total, info)


def wrong_pixels(setup, scene: FrameScene | str | None = None, *, eye=None, target=None, height: int = 144, suns: int = 3) -> Wrong:
    """The wrong-pixel measure of ``setup`` on ``scene`` (module docstring).

    Parameters
    ----------
    setup : aliasing.setups.Setup
        Engine threejs, babylon or playcanvas (:data:`aliasing.frames.seen.ENGINES`), its
        settings, camera and sun band.
    scene : FrameScene or str, optional
        None: :func:`~aliasing.frames.seen.scene.reference_scene`; ``"boxes"``, ``"city"`` or a scene file
        (:func:`aliasing.frames.scenes.frame_scene`, with ``eye`` and ``target`` for a file); or a
        FrameScene built with the setup's camera.
    eye, target : array_like or "X,Y,Z", optional
        The camera of a city or file scene [world units].
    height : int
        Rows of the sample image [px], 16 to 1080 (its width round(aspect · height)).
    suns : int
        Suns over the elevation band, 1 to 16 (one for a single sun).

    Returns
    -------
    Wrong

    Raises
    ------
    ValueError
        Naming ``setup``, ``scene``, ``height`` or ``suns``.

    Examples
    --------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 2, "shadowMapSize": 512}, "near=0.5,far=60,fov=50,aspect=16:9,height=720", 40)
    >>> w = wrong_pixels(s, height=36, suns=1)
    >>> math.isclose(w.total["wrong"], w.total["acne"] + w.total["false_shadow"] + w.total["lost_shadow"]), w.sample["elevations"]
    (True, [40.0])
    """
    return count(setup, sample(setup, scene, eye=eye, target=target, height=height, suns=suns))


def fractions(factor: Array, reference: NDArray[np.bool_], drawn: NDArray[np.bool_], normal: Array, sun: Array, texel: Array,
              pixel: Array, taps: int) -> dict:
    """Acne, false and lost shadow (and their sum, ``wrong``) of one frame's shadow ``factor``, as fractions of its sun-facing pixels.

    The same counts as :func:`count` makes of a predicted frame, for any frame: an engine's read-back
    (:func:`aliasing.frames.run.frame_setup`) or its prediction.  ``texel`` and ``pixel`` [world units] per
    pixel (NaN where no cascade); ``sun`` the world direction towards the sun; ``pixels`` the count.

    Examples
    --------
    >>> ref = np.array([[False, True, True, True, True]]); every = np.ones((1, 5), bool); up = np.tile([0.0, 1.0, 0.0], (1, 5, 1))
    >>> f = fractions(np.array([[1.0, 0.0, 1.0, 1.0, 0.0]]), ref, every, up, np.array([0.0, 1.0, 0.0]), np.ones((1, 5)), np.ones((1, 5)), 1)
    >>> f["pixels"], f["acne"], f["false_shadow"], f["lost_shadow"]
    (5, 0.2, 0.2, 0.2)
    """
    sun = check.direction(sun)
    shape = np.shape(drawn)
    if not all(np.shape(a) == shape for a in (factor, reference, texel, pixel)) or np.shape(normal) != (*shape, 3):
        raise ValueError(f"factor, reference, drawn, texel and pixel must have one shape (H, W) and normal (H, W, 3), got "
                         f"{[np.shape(a) for a in (factor, reference, drawn, texel, pixel, normal)]}")
    facing = drawn & ((np.nan_to_num(normal) @ sun) > MIN_COS)
    masks = classify(factor, reference, drawn, facing, np.nan_to_num(reach_px(taps, texel, pixel), nan=0.0))
    n = int(facing.sum())
    out = {"pixels": n, **{k: _fraction(int(m.sum()), n) for k, m in masks.items()}}
    out["wrong"] = _fraction(int(sum(int(m.sum()) for m in masks.values())), n)
    return out
