"""Babylon.js 9.35's cascade matrices, predicted as ``CascadedShadowGenerator._computeMatrices`` builds them.

Each cascade (Lights/Shadows/cascadedShadowGenerator.pure.js, ``_computeFrustumInWorldSpace``,
``_computeCascadeFrustum``, ``_computeMatrices``; Babylon.js's left-handed world, which is the
job's world mirrored in z):

* the slice's 8 corners (the camera's near-to-far corner rays cut at the cascade's ends) and
  their centroid c;
* ``stabilizeCascades``: a cube of half side r = ⌈16 · (the corners' largest distance from c)⌉ / 16 about c; otherwise
  the corners' box in the frame ``Matrix.LookAtLH(c, c + d, Up)``;
* the shadow camera at c + d · min z, ``LookAtLH(camera, c, Up)``; its depth range [0, box depth]
  tightened to the casters' bounding box with depth clamp (z min = max(0, casters' min),
  z max = max(z min + 1, min(box depth, casters' max)));
* ``Matrix.OrthoOffCenterLH`` of the box's x and y and that depth range, and the world origin
  rounded to a whole texel of the map (the projection translated by the rounding offset).

The result is returned as the read-back's matrices are (:func:`aliasing.frames.readback.decode`):
world of the job → (s, t, depth) in [0, 1]³, column vectors.  The engine computes in float32
(ERRATA F6); this is float64.

Example
-------
>>> from aliasing.frames.scenes import frame_scene, sun_direction
>>> fs = frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=4, ground_cells=2)
>>> from aliasing.frames.models import MODELS
>>> m = matrices(MODELS["babylon"].settings({"stabilizeCascades": True}), fs.camera, sun_direction(35, 30, fs.camera), fs.triangles)
>>> m.shape
(4, 4, 4)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check

Array = NDArray[np.float64]
MIRROR = np.diag([1.0, 1.0, -1.0])
UP = np.array([0.0, 1.0, 0.0])


def look_at_lh(eye: Array, target: Array, up: Array = UP) -> Array:
    """``Matrix.LookAtLH`` as a 4×4 column-vector matrix (world → view; x ∝ up × z, z towards the target).

    Parameters
    ----------
    eye, target : array_like (3,)
        The viewer and the point it looks at [world units], finite, different.
    up : array_like (3,)
        The world up (x is ±x of the world when ``up`` is along the view).

    Returns
    -------
    ndarray (4, 4)
        World → view [world units] (column vectors).

    Examples
    --------
    >>> v = look_at_lh(np.array([0.0, 0.0, -5.0]), np.zeros(3))   # looking along +z from 5 units before the origin
    >>> (v @ [0.0, 0.0, 0.0, 1.0]).tolist()                        # the target lies 5 units ahead
    [0.0, 0.0, 5.0, 1.0]
    """
    eye, target, up = (check.finite(v, n) for v, n in ((eye, "eye"), (target, "target"), (up, "up")))
    if not np.linalg.norm(target - eye) > 0:
        raise ValueError("target must differ from eye")
    z = target - eye
    z = z / np.linalg.norm(z)
    x = np.cross(up, z)
    nx = np.linalg.norm(x)
    x = np.array([1.0, 0.0, 0.0]) if nx == 0 else x / nx
    y = np.cross(z, x)
    y /= np.linalg.norm(y)
    v = np.eye(4)
    v[:3, :3] = np.stack([x, y, z])
    v[:3, 3] = -v[:3, :3] @ eye
    return v


def ortho_off_center_lh(left: float, right: float, bottom: float, top: float, near: float, far: float) -> Array:
    """``Matrix.OrthoOffCenterLH`` (NDC z in [−1, 1]) as a 4×4 column-vector matrix.

    Parameters
    ----------
    left, right, bottom, top : float
        The box's sides in view x and y [world units], right ≠ left, top ≠ bottom.
    near, far : float
        Its depth range along view z [world units], far ≠ near.

    Returns
    -------
    ndarray (4, 4)
        View → NDC (column vectors).

    Examples
    --------
    >>> p = ortho_off_center_lh(-2.0, 2.0, -1.0, 1.0, 0.0, 10.0)
    >>> (p @ [2.0, -1.0, 10.0, 1.0]).tolist()                      # the box's corner on the far plane
    [1.0, -1.0, 1.0, 1.0]
    """
    if not (right != left and top != bottom and far != near) or not np.all(np.isfinite([left, right, bottom, top, near, far])):
        raise ValueError("left, right, bottom, top, near and far must be finite with right ≠ left, top ≠ bottom and far ≠ near")
    p = np.diag([2 / (right - left), 2 / (top - bottom), 2 / (far - near), 1.0])
    p[:3, 3] = [(left + right) / (left - right), (top + bottom) / (bottom - top), -(far + near) / (far - near)]
    return p


def _transform(m: Array, pts: Array) -> Array:
    h = pts @ m[:3, :3].T + m[:3, 3]
    return h / (pts @ m[3, :3] + m[3, 3])[..., None]


def matrices(settings: dict, camera, sun: Array, triangles: Array) -> Array:
    """Per cascade, the predicted world → [0, 1]³ matrix (k, 4, 4) of the job's world.

    Parameters
    ----------
    settings : dict
        Babylon.js's filled settings (:data:`aliasing.frames.models.MODELS` ``["babylon"]``).
    camera : aliasing.raster.scenes.camera.Camera
        The camera the cascades are fitted to.
    sun : array_like (3,)
        World direction towards the sun (the light shines along −sun).
    triangles : array_like (T, 3, 3)
        The shadow casters [world units] (their bounding box sets the depth range).

    Returns
    -------
    ndarray (k, 4, 4)
        Per cascade: world → (s, t, depth) in [0, 1]³ (column vectors), orthographic.

    Examples
    --------
    >>> from aliasing.raster.scenes.camera import look_at
    >>> cam = look_at("0,0,0", "0,0,-1", near=1.0, far=50.0, fov=50.0)
    >>> floor = np.array([[[-50.0, -1.0, 10.0], [50.0, -1.0, 10.0], [0.0, -1.0, -90.0]]])
    >>> m = matrices({"numCascades": 2, "stabilizeCascades": True}, cam, np.array([0.0, 0.8, -0.6]), floor)
    >>> m.shape, m[:, 3].tolist()                       # two cascades, orthographic (w = 1)
    ((2, 4, 4), [[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0]])
    >>> [round(1 / float(np.linalg.norm(c[0, :3])), 4) for c in m]   # map sides 2r [world units], r in whole 1/16ths
    [26.375, 74.125]
    """
    from .models import MODELS

    s = MODELS["babylon"].settings(settings)
    if not s["depthClamp"]:
        raise ValueError("depthClamp must be true (the depth range modelled)")
    from .. import _validation as check

    tri = check.finite(triangles, "triangles")
    if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri):
        raise ValueError(f"triangles must have shape (T, 3, 3), T >= 1, got {tri.shape}")
    sv = check.finite(sun, "sun")
    if sv.shape != (3,) or not np.linalg.norm(sv) > 0:
        raise ValueError(f"sun must be a non-zero 3-vector, got {sv.tolist()}")
    d = MIRROR @ (-sv)
    d = d / np.linalg.norm(d)
    if abs(d @ UP) == 1.0:
        d[2] = 1e-13
    lo, hi = (tri.reshape(-1, 3) @ MIRROR).min(0), (tri.reshape(-1, 3) @ MIRROR).max(0)
    box = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    edges = MODELS["babylon"].edges(s, camera)
    res = float(s["mapSize"])
    to_unit = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        corners = (camera.view.slice_vertices(a, b) @ camera.rotation + camera.eye) @ MIRROR
        c = corners.mean(0)
        if s["stabilizeCascades"]:
            r = np.ceil(np.max(np.linalg.norm(corners - c, axis=1)) * 16) / 16
            mn, mx = np.full(3, -r), np.full(3, r)
        else:
            lc = _transform(look_at_lh(c, c + d), corners)
            mn, mx = lc.min(0), lc.max(0)
        pos = c + d * mn[2]
        view = look_at_lh(pos, c)
        zmin, zmax = 0.0, float(mx[2] - mn[2])
        cz = _transform(view, box)[:, 2]
        if not cz.min() > zmax:
            zmax = min(zmax, float(cz.max()))
            zmin = max(zmin, float(cz.min()))
            zmax = max(zmin + 1.0, zmax)
        proj = ortho_off_center_lh(mn[0], mx[0], mn[1], mx[1], zmin, zmax)
        o = (proj @ view)[:2, 3] * res / 2  # the world origin in texels from the map's centre
        off = (np.floor(o + 0.5) - o) * 2 / res  # Math.round
        t = np.eye(4)
        t[:2, 3] = off
        full = t @ proj @ view
        out.append(to_unit @ full @ np.diag([1.0, 1.0, -1.0, 1.0]))
    return np.array(out)
