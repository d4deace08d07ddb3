"""The receivers of a scene: the eye depths of its visible surface, for :func:`aliasing.tune.tune`'s ``scene``."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import _validation as check
from ..setups import Setup


def scene_receivers(scene: Any, setup: Setup, samples: int = 6) -> tuple[float, float]:
    """The eye depths of a scene's visible surface, (nearest, farthest) [world units]: its receivers.

    Points on each triangle (a barycentric grid of ``samples`` steps per edge) inside the
    camera's frustum (near..far, the vertical fov and the aspect) are kept; their least and
    largest eye depths bound the receivers.

    Parameters
    ----------
    scene : str, Scene or array_like
        A scene file with a glTF camera (its first camera by name is used, with ``setup``'s near,
        far and fov), an eye-space :class:`aliasing.raster.scenes.Scene`, or eye-space triangles
        ``(T, 3, 3)`` (z the depth in front of the eye).
    setup : Setup
        The camera.
    samples : int
        Steps per triangle edge, 1 to 64.

    Example
    -------
    >>> from aliasing import setups
    >>> from aliasing.raster.scenes import ground_and_boxes
    >>> s = setups.build("threejs", camera="near=0.5,far=100,fov=60,aspect=1,height=1080")
    >>> near, far = scene_receivers(ground_and_boxes(1.0, 50.0, 60.0, boxes=5), s)
    >>> 0.5 <= near < 2.0 < 45.0 < far <= 53.0
    True
    """
    from ..raster.scenes import load_scene  # noqa: PLC0415  (the loaders' optional trimesh only when a file is given)

    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (setups.build(...)), got {type(setup).__name__}")
    samples = check.whole(samples, "samples", 1, 64)
    cam = setup.camera
    if isinstance(scene, (str, bytes)) or hasattr(scene, "__fspath__"):
        ws = load_scene(scene)
        if not ws.cameras:
            raise ValueError(f"scene {str(scene)!r} has no glTF camera to place the receivers: give receivers NEAR..FAR instead")
        scene = ws.in_eye_space(ws.camera(sorted(ws.cameras)[0], near=cam.near, far=cam.far, fov=cam.fov))
    tri = check.as_float_array(getattr(scene, "triangles", scene), "scene")
    if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri) or not np.isfinite(tri).all():
        raise ValueError(f"scene must be a scene file, a Scene or eye-space triangles of shape (T, 3, 3), got shape {tri.shape}")
    n = samples
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    keep = i + j <= n
    bary = np.stack([i[keep], j[keep], n - i[keep] - j[keep]], axis=-1) / n  # (P, 3)
    pts = np.einsum("pv,tvc->tpc", bary, tri).reshape(-1, 3)
    t = float(cam.view.tan_theta)
    z = pts[:, 2]
    seen = (z >= cam.near) & (z <= cam.far) & (np.abs(pts[:, 1]) <= z * t) & (np.abs(pts[:, 0]) <= z * t * cam.aspect)
    if not seen.any():
        raise ValueError("scene has no surface inside the camera's frustum: give receivers NEAR..FAR instead")
    near, far = float(z[seen].min()), float(z[seen].max())
    return (near, far) if far > near else (near, near * (1 + 1e-6))
