"""A still world and a fixed set of points on its visible surfaces.

:class:`World` is world-space triangles with a camera and a light; :func:`world` builds
one from a built-in scene (:data:`SCENES`: ``boxes``, the ground and boxes of
:func:`aliasing.raster.scenes.ground_and_boxes`; ``city``, :func:`aliasing.raster.scenes.procedural.city`
with its street camera) or a file (:func:`aliasing.raster.scenes.load_scene`).
:func:`sample` takes the points the camera sees in frame 0 (the eye pass, one point per
pixel of an R × R image) that face the light: they stay put while the camera or the sun
moves.  The camera's ``aspect`` (width/height; its ``fov`` is vertical) is set once, in
:func:`world`, and travels in its :class:`~aliasing.View`: a wide view's R × R pixels are
aspect : 1 wide (:func:`aliasing.raster.draw.eye_pass`).  Points turned away from the light (n·l ≤ :data:`aliasing.raster.scenes.world.MIN_COS_LIGHT`)
are in their own shadow whatever the map, so they are left out.

Example
-------
>>> w = world("boxes", boxes=20)
>>> pts = sample(w, 32)
>>> pts.position.shape[1], bool(pts.count > 100)
(3, True)
"""

from __future__ import annotations

import os
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from ..raster.draw import check_resolution, eye_pass
from ..raster.scenes import Camera, ground_and_boxes, load_scene, look_at, plane_ids, procedural
from ..raster.scenes.camera import vector
from ..raster.scenes.world import MIN_COS_LIGHT
from ..view import View, check_aspect

Array = NDArray[np.float64]

#: Built-in scenes: name → (what it is).
SCENES = {
    "boxes": "a ground plane with boxes over [1, 100] (aliasing.raster.scenes.ground_and_boxes), camera at the origin looking along +z",
    "city": "the procedural city block (120 units wide, 20000 triangles) seen from its street camera",
}
#: World-space direction towards the light when none is given.
DEFAULT_LIGHT = (-1.0, 2.0, 0.6)


@dataclass(frozen=True)
class World:
    """World-space ``triangles`` (T, 3, 3), the frame-0 ``camera``, the unit ``light``
    (world direction towards the light) and a ``name``."""

    triangles: Array
    camera: Camera
    light: Array
    name: str


@dataclass(frozen=True)
class Points:
    """Fixed world points: ``position`` (P, 3), unit ``normal`` (P, 3) facing the frame-0
    eye, ``pixel`` (P, 2) their (row, column) in the frame-0 image of ``resolution``
    pixels per side, ``plane`` (P,) the planar face they lie on; ``aspect`` the image's
    width/height (its pixels are aspect : 1 wide)."""

    position: Array
    normal: Array
    pixel: NDArray[np.int64]
    plane: NDArray[np.int64]
    resolution: int
    aspect: float = 1.0

    @property
    def count(self) -> int:
        return len(self.position)


def world(scene: str = "boxes", *, light: object = None, eye: object = None, target: object = None, camera: str | None = None,
          near: float | None = None, far: float | None = None, fov: float | None = None, boxes: int = 100, seed: int = 0, aspect: float = 1.0) -> World:
    """A built-in scene by name (:data:`SCENES`) or a scene file, with its camera and light.

    Parameters
    ----------
    scene : str
        ``boxes``, ``city`` or a path (.glb, .gltf, .obj, .ply, .stl).
    light : "X,Y,Z" or array_like, optional
        World direction towards the light (default :data:`DEFAULT_LIGHT`).
    eye, target : "X,Y,Z" or array_like, optional
        A look-at camera [world units] (needed for a file without ``camera``).
    camera : str, optional
        A glTF camera's name.
    near, far, fov : float, optional
        Override the camera's near and far [world units] and VERTICAL full field of view [deg].
    boxes, seed : int
        The ``boxes`` scene's box count and seed.
    aspect : float
        The camera's image width/height, 0 < aspect < inf (default 1: square; ``fov`` is
        vertical), checked here, once, and carried by the camera into the eye pass, every
        frame's fits and the frustum tests.  The ``boxes`` ground spans the wider view.  A
        glTF camera's own aspectRatio is not read: this value replaces it.

    Example
    -------
    >>> world("boxes", boxes=5, aspect=2.0).camera.view.tan_theta_x / world("boxes", boxes=5).camera.view.tan_theta_x
    2.0
    """
    wide = float(check_aspect(check.scalar(aspect, "aspect")))  # checked once, where it enters
    lv = vector(DEFAULT_LIGHT if light is None else light, "light direction")
    lv = lv / np.linalg.norm(lv)
    key = scene.lower() if isinstance(scene, str) else ""
    if key == "boxes":
        n, f = (1.0 if near is None else near), (100.0 if far is None else far)
        fv = 60.0 if fov is None else fov
        tri = ground_and_boxes(View(n, f, fv, wide), boxes=boxes, seed=seed).triangles  # the ground spans the view's width
        cam = look_at(eye or (0.0, 0.0, 0.0), target or (0.0, 0.0, 1.0), near=n, far=f, fov=fv)
        return World(tri, _wide(cam, wide), lv, "boxes")
    if key == "city":
        tri = procedural.city(20_000, seed=1, size=120.0)
        cam = procedural.street_camera(120.0)
        if eye is not None or target is not None:
            cam = look_at(eye or cam.eye, target or (0.0, 0.0, 0.0), near=cam.near, far=cam.far, fov=cam.fov)
        return World(tri, _wide(cam.with_range(near, far, fov), wide), lv, "city")
    if not isinstance(scene, (str, os.PathLike)) or not os.path.exists(scene):
        raise ValueError(f"scene must be one of {', '.join(SCENES)} or an existing file, got {scene!r}")
    ws = load_scene(scene)
    if camera is not None:
        cam = ws.camera(camera, near=near, far=far, fov=fov)
    else:
        if eye is None or target is None:
            raise ValueError("a scene file needs a camera: eye and target (--eye X,Y,Z --target X,Y,Z) or a glTF camera name (--camera NAME)")
        cam = look_at(eye, target, near=1.0 if near is None else near, far=100.0 if far is None else far, fov=60.0 if fov is None else fov)
    return World(ws.triangles, _wide(cam, wide), lv, os.path.basename(str(scene)))


def _wide(cam: Camera, aspect: float) -> Camera:
    """The camera with the (checked) aspect."""
    return replace(cam, aspect=aspect)


def sample(w: World, resolution: int = 128, *, backend: str = "numpy") -> Points:
    """The points the frame-0 camera sees, one per pixel of an image of ``resolution`` × ``resolution`` pixels, facing the light.

    The image is the camera's view (:attr:`~aliasing.raster.scenes.Camera.view`): square
    pixels at aspect 1, pixels aspect : 1 wide otherwise.  ``backend`` draws the eye pass
    (:mod:`aliasing.raster.draw.backends`).  Raises ValueError when no visible point faces
    the light within [near, far].
    """
    r = check_resolution(resolution, "resolution")
    check.instance(w, "w", World)
    cam = w.camera
    eb = eye_pass(cam.to_eye(w.triangles), cam.view, r, near=cam.near, backend=backend)
    pos_e, nrm_e = eb.position.reshape(-1, 3), eb.normal.reshape(-1, 3)
    hit = eb.triangle.reshape(-1) >= 0
    pos = np.where(hit[:, None], np.nan_to_num(pos_e), 0.0) @ cam.rotation + cam.eye  # eye → world
    nrm = np.nan_to_num(nrm_e) @ cam.rotation
    ok = hit & (np.nan_to_num(pos_e[:, 2]) <= cam.far) & (nrm @ w.light > MIN_COS_LIGHT)
    if not ok.any():
        raise ValueError("no visible point faces the light within [near, far]: move the camera or the light")
    idx = np.nonzero(ok)[0]
    planes = plane_ids(w.triangles)[eb.triangle.reshape(-1)[idx]]
    return Points(pos[idx], nrm[idx], np.stack([idx // r, idx % r], -1).astype(np.int64), planes.astype(np.int64), r, float(cam.aspect))
