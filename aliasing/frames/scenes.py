"""The scenes the engines draw: world triangles, wound for the engines, with a camera and a sun.

The world is the toolkit's loaded-scene world (right-handed, y up; :mod:`aliasing.raster.scenes`).
The built-in ``boxes`` scene (:func:`aliasing.raster.ground_and_boxes`, made in eye space) is
placed with the eye at the origin looking along −z (so that the toolkit's eye space is the
world with z negated); the ``city`` (:func:`aliasing.raster.scenes.procedural.city`) is
already in world space, seen by default from its street camera.  A file is read with
:func:`aliasing.raster.scenes.loading.load_scene` (glTF through trimesh) and keeps its winding.

The toolkit's own triangles carry no winding (its rasterizer draws both sides); engines cull by
it and cast shadows from one side, so the built-in scenes are wound outward first
(:func:`wind_outward`: every part of them is convex, or planar and facing up).

Examples
--------
>>> fs = frame_scene("boxes", near=1.0, far=40.0, fov=50.0, aspect=16 / 9, boxes=4, ground_cells=2)
>>> fs.triangles.shape, fs.ground
((56, 3, 3), 8)
>>> n = np.cross(fs.triangles[:, 1] - fs.triangles[:, 0], fs.triangles[:, 2] - fs.triangles[:, 0])
>>> bool((n[: fs.ground, 1] > 0).all())   # the ground faces up
True
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .. import _validation as check
from ..raster.scenes import ground_and_boxes
from ..raster.scenes.camera import Camera, look_at
from ..raster.scenes.loading import load_scene
from ..raster.scenes import procedural
from ..view import View

Array = NDArray[np.float64]
BUILTIN = ("boxes", "city")


@dataclass(frozen=True)
class FrameScene:
    """World triangles (T, 3, 3) [world units] wound outward where known, the number of leading
    ground triangles ``ground``, the world ``camera`` (:class:`aliasing.raster.scenes.camera.Camera`
    with the image aspect) and the scene's ``name``.

    Parameters
    ----------
    triangles : ndarray (T, 3, 3)
        World triangles [world units].
    ground : int
        The number of leading ground triangles.
    camera : aliasing.raster.scenes.camera.Camera
        The world camera (near, far [world units], fov [deg], aspect).
    name : str
        The scene's name.

    Examples
    --------
    >>> fs = FrameScene(np.zeros((1, 3, 3)), 0, look_at("0,0,0", "0,0,-1"), "empty")
    >>> fs.triangles.shape, fs.camera.fov
    ((1, 3, 3), 60.0)
    """

    triangles: Array
    ground: int
    camera: Camera
    name: str


def wind_outward(triangles: ArrayLike) -> Array:
    """The triangles re-wound so that their right-handed normals (v1 − v0) × (v2 − v0) point outward.

    Parts are the connected components of shared corners; a planar part faces +y (up, or
    its normal's sign is kept when it is vertical), any other part is taken as convex and
    faces away from the average of its corners.

    Parameters
    ----------
    triangles : array_like (T, 3, 3)
        World triangles [world units], T >= 1, finite.

    Returns
    -------
    ndarray (T, 3, 3)
        The same triangles, some with two corners swapped.

    Examples
    --------
    >>> t = np.array([[[0, 0, 0], [1, 0, 0], [0, 0, 1]]], float)   # facing −y
    >>> wind_outward(t)[0].tolist()
    [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
    """
    tri = check.triangles(triangles)
    t = len(tri)
    _, vid = np.unique(np.round(tri.reshape(-1, 3), 9), axis=0, return_inverse=True)
    vid = vid.reshape(t, 3)
    nv = int(vid.max()) + 1
    rows = np.repeat(np.arange(t), 3)
    graph = coo_matrix((np.ones(3 * t), (rows, t + vid.ravel())), shape=(t + nv, t + nv))
    _, label = connected_components(graph, directed=False)
    part = label[:t]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    nu = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    cent = tri.mean(axis=1)
    ids, inv, counts = np.unique(part, return_inverse=True, return_counts=True)
    mean = np.zeros((len(ids), 3))
    np.add.at(mean, inv, cent)
    mean /= counts[:, None]
    # planar parts: every triangle's plane passes through the part's average (within 1e-9 of its size)
    off = np.abs(((cent - mean[inv]) * nu).sum(-1))
    span = np.zeros(len(ids))
    np.maximum.at(span, inv, np.linalg.norm(tri - mean[inv][:, None], axis=-1).max(-1))
    planar_tri = off <= 1e-9 * np.maximum(span[inv], 1e-300)
    planar = np.ones(len(ids), bool)
    np.logical_and.at(planar, inv, planar_tri)
    away = ((cent - mean[inv]) * n).sum(-1)
    flip = np.where(planar[inv], np.where(np.abs(nu[:, 1]) > 1e-9, n[:, 1] < 0, False), away < 0)
    out = tri.copy()
    out[flip] = tri[flip][:, [0, 2, 1]]
    return out


def frame_scene(scene: str, *, near: float, far: float, fov: float, aspect: float, eye: ArrayLike | str | None = None,
                target: ArrayLike | str | None = None, boxes: int = 40, ground_cells: int = 8, city_triangles: int = 20_000,
                seed: int = 1) -> FrameScene:
    """The scene ``scene`` ("boxes", "city" or a file) in the world, with its camera.

    Parameters
    ----------
    scene : str
        ``"boxes"`` (ground and boxes over the view's depth range, eye 1 above the ground),
        ``"city"`` (a procedural city block, 200 a side) or a scene file (glTF/GLB, OBJ, PLY, STL).
    near, far : float
        The camera's near and far distances [world units], 0 < near < far.
    fov : float
        Vertical field of view [deg], in (0, 180).
    aspect : float
        Image width / height, > 0.
    eye, target : array_like or "X,Y,Z", optional
        Camera position and the point it looks at [world units]: required for a file; the
        built-in scenes have their own (boxes: the origin looking along −z; city: its street camera).
    boxes, ground_cells, city_triangles, seed : int
        Sizes of the built-in scenes (see :func:`aliasing.raster.ground_and_boxes` and
        :func:`aliasing.raster.scenes.procedural.city`) and their seed.

    Returns
    -------
    FrameScene
        The wound triangles, the ground count and the camera with the image aspect.

    Examples
    --------
    >>> fs = frame_scene("boxes", near=1.0, far=40.0, fov=50.0, aspect=2.0, boxes=3, ground_cells=2)
    >>> fs.name, fs.ground, fs.camera.aspect, fs.camera.eye.tolist()
    ('boxes', 8, 2.0, [0.0, 0.0, 0.0])
    """
    if not isinstance(scene, str) or not scene:
        raise ValueError(f"scene must be boxes, city or a scene file, got {scene!r}")
    view = View(check.scalar(near, "near"), check.scalar(far, "far"), check.scalar(fov, "fov"), aspect=check.scalar(aspect, "aspect"))
    if (eye is None) != (target is None):
        raise ValueError("give both eye and target (or neither for a built-in scene)")
    if scene == "boxes":
        sc = ground_and_boxes(view.near, view.far, view.fov, boxes=boxes, ground_cells=ground_cells, seed=seed)
        tri = sc.triangles * np.array([1.0, 1.0, -1.0])  # eye space (z ahead) -> world looking along -z
        ground = 2 * ground_cells**2
        cam = look_at("0,0,0", "0,0,-1") if eye is None else look_at(eye, target)
    elif scene == "city":
        size = 200.0
        tri = procedural.city(city_triangles, seed=seed, size=size)
        flat = np.all(tri[..., 1] == 0.0, axis=1)
        ground = int(len(flat) if flat.all() else np.argmin(flat))  # the leading grid on y = 0 (buildings' bottoms come later)
        cam = procedural.street_camera(size) if eye is None else look_at(eye, target)
    else:
        path = Path(scene)
        if not path.is_file():
            raise ValueError(f"scene must be boxes, city or an existing scene file, got {scene!r}")
        if eye is None:
            raise ValueError("a scene file needs a camera: --eye X,Y,Z --target X,Y,Z")
        try:
            ws = load_scene(path)
        except (ValueError, ImportError, OSError) as e:
            raise ValueError(f"scene {scene} could not be loaded: {str(e).splitlines()[0] if str(e) else type(e).__name__}") from None
        cam = look_at(eye, target)
        return FrameScene(np.asarray(ws.triangles, float), 0, _with(cam, view), path.name)
    return FrameScene(wind_outward(tri), ground, _with(cam, view), scene)


def _with(cam: Camera, view: View) -> Camera:
    return Camera(cam.eye, cam.rotation, float(view.near), float(view.far), float(view.fov), cam.name, float(view.aspect))


def sun_direction(elevation: float, azimuth: float, camera: Camera) -> Array:
    """World unit vector towards the sun: ``elevation`` [deg] above the ground, ``azimuth`` [deg]
    from the camera's horizontal view direction (towards the camera's right for positive angles).

    Parameters
    ----------
    elevation : float
        Above the ground [deg], in [−90, 90].
    azimuth : float
        From the camera's horizontal view direction [deg], finite.
    camera : aliasing.raster.scenes.camera.Camera
        The camera (not looking straight up or down).

    Returns
    -------
    ndarray (3,)
        World unit vector towards the sun.

    Examples
    --------
    >>> cam = look_at("0,0,0", "0,0,-1")
    >>> np.round(sun_direction(90.0, 0.0, cam), 12).tolist()
    [0.0, 1.0, 0.0]
    >>> np.round(sun_direction(0.0, 90.0, cam), 12).tolist()   # on the camera's right
    [1.0, 0.0, 0.0]
    """
    el = float(check.closed_range(check.scalar(elevation, "elevation"), "elevation", -90.0, 90.0, " degrees"))
    az = float(check.finite(check.scalar(azimuth, "azimuth"), "azimuth"))
    fwd = camera.rotation[2] * np.array([1.0, 0.0, 1.0])
    if np.linalg.norm(fwd) < 1e-9:
        raise ValueError("the camera looks straight up or down: the sun's azimuth from its view direction is undefined")
    fwd /= np.linalg.norm(fwd)
    right = np.cross(fwd, [0.0, 1.0, 0.0])
    e, a = np.radians(el), np.radians(az)
    return np.cos(e) * (np.cos(a) * fwd + np.sin(a) * right) + np.sin(e) * np.array([0.0, 1.0, 0.0])


def export(scene: FrameScene, path) -> str:
    """Write the scene's (wound) triangles and its camera (named ``frame``) as a GLB file (trimesh).

    Loading it back (``aliasing frames --scene FILE --eye ... --target ...``) gives the engines
    the same triangles (float32, as glTF stores them) with the same winding.

    Parameters
    ----------
    scene : FrameScene
        The scene.
    path : str or path
        The GLB file to write.

    Returns
    -------
    str
        The path written.

    Examples
    --------
    >>> import tempfile, pytest
    >>> _ = pytest.importorskip("trimesh")
    >>> fs = frame_scene("boxes", near=1.0, far=10.0, fov=50.0, aspect=1.0, boxes=1, ground_cells=1)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     back = load_scene(export(fs, Path(d) / "s.glb"))
    >>> back.triangles.shape == fs.triangles.shape
    True
    """
    if not isinstance(scene, FrameScene):
        raise ValueError(f"scene must be a FrameScene, got {type(scene).__name__}")
    return procedural.to_glb(scene.triangles, path, {"frame": scene.camera})


def light_target(camera) -> np.ndarray:
    """Where a single (non-cascaded) light looks: the point on the camera's view axis half way from near to far [world units].

    The engines' fixed shadow boxes (three.js's ``DirectionalLight``, Babylon.js's
    ``ShadowGenerator``) are placed at their light and look at its target; the frames put the
    target here and the light half the shadow camera's near + far from it towards the sun.

    Parameters
    ----------
    camera : aliasing.raster.scenes.camera.Camera
        The eye camera (near and far [world units]).

    Returns
    -------
    ndarray (3,)
        The target [world units].

    Examples
    --------
    >>> fs = frame_scene("boxes", near=1.0, far=9.0, fov=50.0, aspect=1.0, boxes=1, ground_cells=1)
    >>> light_target(fs.camera).round(6).tolist()   # the eye at the origin looking along -z
    [0.0, 0.0, -5.0]
    """
    return camera.eye + camera.rotation[2] * (camera.near + camera.far) / 2
