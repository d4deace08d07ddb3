"""An engine's pipeline (:class:`aliasing.setups.Pipeline`) through the toolkit's fits: texels and errors.

The engine's own cascades (their eye-depth ranges, fit and snap) are evaluated by
:func:`aliasing.engines.stable.evaluate`; a fixed world box (three.js's single
DirectionalLight) has the same texel everywhere and covers what it covers.

Example
-------
>>> from aliasing import setups
>>> s = setups.build("threejs", camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080", sun=30)
>>> w = texels(s.pipeline, s.camera, s.sun.direction()[None])
>>> w.shape, bool(w[0, 0, 0] == w[0, 0, 1])      # (directions, cascades, [s, t]); square boxes
((1, 3, 2), True)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import geometry
from ..setups import Camera, Pipeline
from ..view import View
from . import stable

Array = NDArray[np.float64]


def _lights(light: str | ArrayLike) -> Array:
    return geometry.lights(light)


def result(pipeline: Pipeline, camera: Camera, light: str | ArrayLike, ranges: tuple[ArrayLike, ArrayLike] | None = None) -> stable.StableResult:
    """:func:`aliasing.engines.stable.evaluate` of the pipeline's cascades (not for ``fit="fixed"``): the pipeline and
    the camera reach it whole (ranges, fit, snap, map size; near, fov, aspect).

    ``ranges``: other cascade ranges ``(near_i, far_i)`` [world units] with the pipeline's fit, snap and size (a
    split the pipeline might have had: :mod:`aliasing.tune.theory`).

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080", sun=30)
    >>> r = result(s.pipeline, s.camera, s.sun.direction()[None], ranges=([0.1, 50.0], [50.0, 500.0]))
    >>> r.M_x.shape                                   # (directions, cascades)
    (1, 2)
    """
    if pipeline.fit == "fixed":
        raise ValueError("a fixed shadow box has no cascade fit: use texels()")
    a, b = (np.asarray(pipeline.near_i), np.asarray(pipeline.far_i)) if ranges is None else (np.asarray(x, float) for x in ranges)
    return stable.evaluate((a, b), camera.near, float(b.max()), camera.fov, _lights(light), aspect=camera.aspect,
                           fit=pipeline.fit, snap=pipeline.snap, resolution=float(pipeline.resolution))


def texels(pipeline: Pipeline, camera: Camera, light: str | ArrayLike) -> Array:
    """World texel sides [s, t] of each cascade's map per light direction [world units], shape ``(N, K, 2)``.

    A map with ``rows`` (Godot's two splits: halves of a square atlas) has its t texel over ``rows``.

    Parameters
    ----------
    pipeline : Pipeline
        What the engine builds (``setup.pipeline`` of a :class:`aliasing.setups.spec.Setup`).
    camera : Camera
        The camera it was built for.
    light : str or array_like
        Light spec or eye-space vectors towards the light ``(N, 3)``.
    """
    lv = _lights(light)
    if pipeline.fit == "fixed":
        w, h = pipeline.box
        out = np.empty((len(lv), 1, 2))
        out[..., 0], out[..., 1] = w / pipeline.resolution, h / (pipeline.rows or pipeline.resolution)
        return out
    r = result(pipeline, camera, lv)
    sides = np.stack([r.width_x, r.width_y], axis=-1)
    if pipeline.grow:  # three.js CSM fade: a margin added to the side after the fit
        sides = sides + np.asarray(pipeline.grow)[None, :, None]
    return np.stack([sides[..., 0] / pipeline.resolution, sides[..., 1] / (pipeline.rows or pipeline.resolution)], axis=-1)


def extents(pipeline: Pipeline, camera: Camera, light: str | ArrayLike) -> Array:
    """Each cascade's map depth range along the light per light direction [world units], shape ``(N, K)``.

    What a ``depth_range`` bias term scales with (:class:`aliasing.setups.BiasTerm`):
    the engine's fixed light near..far where it has one (``pipeline.depth_range``: three.js),
    else the fitted box's extent along the light: the spread of the cascade's 8 corners along
    the light for the tight fit (Babylon.js's light-space box), the box side for the sphere
    and diagonal fits (a cube around the sphere).  Engines that shrink the range to the
    shadow casters' bounds (Babylon.js, PlayCanvas) use less in a scene that does not fill the
    box: then the range here is an upper bound.

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("babylon", {"stabilizeCascades": True}, camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080")
    >>> l = s.sun.direction()[None]
    >>> bool(np.allclose(extents(s.pipeline, s.camera, l), texels(s.pipeline, s.camera, l)[..., 0] * s.pipeline.resolution))
    True
    """
    lv = _lights(light)
    k = pipeline.k
    if pipeline.depth_range is not None:
        near, far = pipeline.depth_range
        return np.full((len(lv), k), float(far) - float(near))
    if pipeline.fit == "fixed":
        raise ValueError("a fixed shadow box needs depth_range (its light near and far)")
    if pipeline.fit == "tight":
        a, b = np.asarray(pipeline.near_i), np.asarray(pipeline.far_i)
        corners = geometry.frustum_vertices(View(a, b, camera.fov, camera.aspect))  # (K, 8, 3) eye space
        along = np.einsum("kcj,nj->nkc", corners, lv / np.linalg.norm(lv, axis=-1, keepdims=True))
        return np.maximum(np.ptp(along, axis=-1), pipeline.min_extent)
    return np.maximum(texels(pipeline, camera, lv)[..., 0] * pipeline.resolution, pipeline.min_extent)


def scheme_spec(pipeline: Pipeline) -> str:
    """The pipeline's cascades as a scheme of the engines grammar (:mod:`aliasing.engines.compare`):
    ``csm-stable:ranges=A..B/...:fit=FIT:snap=SNAP`` (``csm:ranges=...`` for the tight, unsnapped fit),
    for ``aliasing engines`` and ``aliasing shimmer`` with ``--engine``.

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 2, "mode": "uniform"}, "near=1,far=101,fov=50")
    >>> scheme_spec(s.pipeline)
    'csm-stable:ranges=1.0..51.0/51.0..101.0:fit=diagonal-unrounded:snap=bevy'
    """
    if pipeline.fit == "fixed":
        raise ValueError("a fixed shadow box (one DirectionalLight) has no cascades to compare or to move: use aliasing check")
    ranges = "/".join(f"{a!r}..{b!r}" for a, b in zip(pipeline.near_i, pipeline.far_i))
    if pipeline.fit == "tight" and pipeline.snap == "none":
        return f"csm:ranges={ranges}"
    return f"csm-stable:ranges={ranges}:fit={pipeline.fit}:snap={pipeline.snap}"
