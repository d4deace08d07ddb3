"""A loaded scene placed in the toolkit's eye space: file, world camera and light, ready to draw.

:func:`setup` loads a file (:mod:`aliasing.raster.scenes.loading`), places the camera
(``eye``/``target``/``up`` or a glTF camera by name, :mod:`aliasing.raster.scenes.camera`) and
turns the world-space light direction into eye space: everything after it is the toolkit's
eye space.  Coplanar triangles count as one planar face (:func:`plane_ids`), so that central
differences run across a mesh's tessellation, not only inside single triangles.
:func:`add_scene_arguments` is how a scene and its cascades are named on the command line
(``aliasing render`` and ``aliasing validate --scene``).

Example
-------
>>> from aliasing.raster.scenes import procedural
>>> st = setup(procedural.city(1000, seed=1, size=50.0), eye="-40,2,-40", target="0,0,0", near=0.5, far=100.0, light_dir="1,2,0.5")
>>> st.camera.near, st.scene.triangles.shape[1:], bool(st.light @ [0.0, 1.0, 0.0] > 0)
(0.5, (3, 3), True)
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ... import geometry
from ...view import check_aspect
from .builtin import Scene
from .camera import Camera, check_raster_frustum, look_at, vector
from .loading import WorldScene, load_scene

Array = NDArray[np.float64]

#: Errors are measured where the surface faces the light by more than this cosine (n·l):
#: surfaces turned away are in their own shadow (nothing for the map to alias), and near
#: grazing light the map's Jacobian on the surface is singular (finite differences blow up).
MIN_COS_LIGHT = 0.1



@dataclass(frozen=True)
class SceneSetup:
    """An eye-space scene ready to render: ``scene``, per-triangle planar ``faces``, the
    ``camera`` (near, far, fov), ``light`` (eye-space unit vector towards the light), the
    loaded file's ``degenerate`` triangle count, ``source``, and ``ground``: the number of
    leading ground triangles, shaded in the ground's colour and the rest in the boxes'
    (the built-in scene; 0: a loaded scene, all in the ground's colour)."""

    scene: Scene
    faces: NDArray[np.int64]
    camera: Camera
    light: Array
    degenerate: int = 0
    source: str = ""
    ground: int = 0


def plane_ids(triangles: ArrayLike) -> NDArray[np.int64]:
    """An id per triangle, equal for coplanar triangles (normal and offset within 1e-6 relative).

    Example
    -------
    >>> quad = [[[0, 0, 0], [1, 0, 0], [1, 0, 1]], [[0, 0, 0], [1, 0, 1], [0, 0, 1]], [[0, 0, 0], [0, 1, 0], [0, 1, 1]]]
    >>> plane_ids(np.array(quad, float)).tolist()
    [0, 0, 1]
    """
    tri = np.asarray(triangles, float)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-300)
    # one sign per plane: the first clearly non-zero component positive
    lead = np.argmax(np.abs(n) > 1e-6, axis=-1)
    n *= np.sign(np.take_along_axis(n, lead[:, None], -1))
    d = (n * tri[:, 0]).sum(-1)
    scale = max(float(np.abs(tri).max()), 1e-300)
    key = np.column_stack([np.round(n * 1e6), np.round(d / scale * 1e6)])
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    rank = np.argsort(np.argsort(first))  # ids in order of first appearance
    return rank[inv.ravel()].astype(np.int64)


def setup(scene: str | WorldScene | ArrayLike, *, eye: ArrayLike | str | None = None, target: ArrayLike | str | None = None, up: ArrayLike | str = (0.0, 1.0, 0.0),
          camera: str | None = None, near: float | None = None, far: float | None = None, fov: float | None = None,
          light_dir: ArrayLike | str | None = None, light: str | ArrayLike | None = None, aspect: float = 1.0) -> SceneSetup:
    """Load (if a path), place the camera, convert to eye space.

    Parameters
    ----------
    scene : str, WorldScene or array_like (T, 3, 3)
        A file (:func:`aliasing.raster.scenes.loading.load_scene`) or world-space triangles.
    eye, target, up : array_like or "X,Y,Z"
        A look-at camera [world units] (eye ≠ target, up not parallel to the view).
    camera : str, optional
        A glTF camera's name instead of eye/target (near, far, fov override its own).
    near, far : float, optional
        Eye near and far (shadow) distances [world units]; defaults 1 and 100 for a look-at camera.
    fov : float, optional
        Full field of view [deg]; default 60 (look-at) or the glTF camera's yfov.
    light_dir : array_like or "X,Y,Z", optional
        World-space direction towards the light (non-zero).
    light : str or array_like, optional
        Or an eye-space light (:data:`aliasing.geometry.LIGHT_SPEC`, one direction);
        default ``gamma:60@azimuth:30`` when neither is given.
    aspect : float
        The camera's image width/height, 0 < aspect < inf (default 1: square); ``fov`` is
        the vertical field of view.  The camera's :attr:`~Camera.view` carries it into the
        eye pass, the cascades and the measured error.  A glTF camera's own aspectRatio is
        not read: this value replaces it.
    """
    wide = float(check_aspect(check.scalar(aspect, "aspect")))  # checked once, where it enters
    if isinstance(scene, WorldScene):
        ws = scene
    elif isinstance(scene, str) or hasattr(scene, "__fspath__"):
        ws = load_scene(scene)
    else:
        tri = check.as_float_array(scene, "scene")
        if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri) or not np.isfinite(tri).all():
            raise ValueError(f"scene triangles must be finite with shape (T, 3, 3), T >= 1, got {tri.shape}")
        ws = WorldScene(tri)
    if camera is not None:
        if eye is not None or target is not None:
            raise ValueError("give either camera (a glTF camera name) or eye and target, not both")
        cam = ws.camera(camera, near=near, far=far, fov=fov)
    else:
        if eye is None or target is None:
            raise ValueError("a scene needs a camera: eye and target (--eye X,Y,Z --target X,Y,Z) or a glTF camera name (--camera NAME)")
        cam = look_at(eye, target, up, near=1.0 if near is None else near, far=100.0 if far is None else far, fov=60.0 if fov is None else fov)
    if light_dir is not None and light is not None:
        raise ValueError("give either light_dir (world space) or light (eye space), not both")
    if light_dir is not None:
        lv = cam.direction_to_eye(vector(light_dir, "light direction"))
    else:
        ls = geometry.lights("gamma:60@azimuth:30" if light is None else light)
        if ls.shape[0] != 1:
            raise ValueError(f"light must be a single direction, got {ls.shape[0]}")
        lv = ls[0]
    cam = replace(cam, aspect=wide)  # a glTF camera's aspectRatio is not read: this value replaces it
    sc = ws.in_eye_space(cam)
    check_raster_frustum(cam.near, cam.far, cam.fov)
    return SceneSetup(sc, plane_ids(sc.triangles), cam, lv, ws.degenerate, ws.source)


def add_scene_arguments(scene, cascades, splits_for: str) -> None:
    """The options of a loaded scene (file, world camera, light) and of its cascades, for ``render`` and ``validate``.

    ``scene`` and ``cascades`` are argument groups (or parsers); ``splits_for`` says which
    schemes ``--splits`` applies to.
    """
    scene.add_argument("--scene", metavar="FILE", help="scene file: .glb, .gltf, .obj, .ply, .stl (glTF/GLB, binary PLY and STL need the scenes extra)")
    scene.add_argument("--eye", metavar="X,Y,Z", help="camera position (world space; --eye=-5,2,0 when X is negative)")
    scene.add_argument("--target", metavar="X,Y,Z", help="point the camera looks at (world space)")
    scene.add_argument("--up", metavar="X,Y,Z", default="0,1,0", help="up vector (default 0,1,0)")
    scene.add_argument("--camera", metavar="NAME|SPEC", help="a glTF camera of the file, by camera or node name; or a camera spec "
                       "near=N,far=F,fov=DEG,aspect=A,height=PX (with or without a file: the view, its vertical fov and rows)")
    scene.add_argument("--near", type=float, help="near distance (default 1, or the glTF camera's znear)")
    scene.add_argument("--far", type=float, help="far (shadow) distance (default 100, or the glTF camera's zfar)")
    scene.add_argument("--light-dir", metavar="X,Y,Z", help="world-space direction towards the light, instead of --light (eye space); write --light-dir=-1,2,0 when X is negative")
    cascades.add_argument("--splits", metavar="NAME", help=f"split method or engine preset {splits_for} (see aliasing splits --list)")
    cascades.add_argument("--lambda", dest="lam", type=float, help="blend λ in [0, 1] of practical-style splits")
    cascades.add_argument("-k", type=int, help="number of cascades (default: the preset's own)")
    cascades.add_argument("--param", action="append", default=[], metavar="KEY=VALUE", help="other split parameters, as in aliasing splits")


def json_safe(value: object) -> object:
    """JSON has no NaN: write it as null."""
    if isinstance(value, dict):
        return {k: json_safe(v) for k, v in value.items()}
    if isinstance(value, list):
        return [json_safe(v) for v in value]
    if isinstance(value, float) and not np.isfinite(value):
        return None
    return value
