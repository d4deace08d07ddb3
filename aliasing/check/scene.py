"""A scene's own receivers for :func:`aliasing.check.check`: what the camera sees, pixel by pixel.

The scene (``"boxes"``: the seeded ground and boxes of
:func:`aliasing.raster.scenes.ground_and_boxes` over the camera's depth range, eye 1 above the
ground; ``"city"``: the procedural city of :func:`aliasing.raster.scenes.procedural.city`, 400
world units across, seen from its street camera unless ``eye`` and ``target`` are given; a file
path: glTF/GLB, OBJ, PLY, STL, with ``eye`` and ``target``; or world-space triangles (T, 3, 3))
is drawn by the eye pass (:func:`aliasing.raster.draw.eye_pass`) at ``pixels`` × ``pixels``
with the setup's camera (its near, far, vertical fov and aspect: the pixels span the frustum).
Each visible pixel inside [near, far] is a receiver: its eye depth picks the cascade (the
first whose range holds it), its face normal gives θ against each sun and the direction φ of
its steepest depth change in the light map's axes (s = up × l, t = l × s).  The suns are the
setup's band and azimuth about the world's up (+y) from the camera's horizontal view
direction, so a camera looking down sees them at the same elevations above the ground.

A pixel counts as a receiver under a sun when its face turns towards it (θ ≤
``aliasing.check.MAX_ANGLE``); whether another object shadows it is not tested: the
counts are of the pixels facing the sun.

Example
-------
>>> from aliasing import setups
>>> s = setups.build("babylon", {}, "near=0.5,far=100,fov=60,aspect=16:9,height=720", "20..40")
>>> seen = scene_pixels(s, "boxes", None, None, 32)
>>> seen.position.shape[1], seen.source
(3, 'boxes')
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check_
from ..raster.draw.eye import eye_pass
from ..raster.scenes import ground_and_boxes
from ..raster.scenes import setup as scene_setup
from ..raster.scenes.procedural import city, street_camera
from ..setups import Setup

Array = NDArray[np.float64]

#: World size of the built-in city [world units] and its triangle count (a light one: the check's eye pass is small).
CITY_SIZE = 400.0
CITY_TRIANGLES = 20_000
#: Receivers whose normal is within this angle of the world's up are "ground", within it of horizontal "walls" [deg].
CLASS_ANGLE = 10.0


@dataclass(frozen=True)
class Seen:
    """The visible receivers: eye-space ``position`` and unit ``normal`` (P, 3), the eye-space world
    ``up`` and view ``forward`` (horizontal), and the scene's ``source`` name."""

    position: Array
    normal: Array
    up: Array
    forward: Array
    source: str

    def light(self, elevations: ArrayLike, azimuth: float) -> Array:
        """Eye-space unit vectors towards each sun, (E, 3): elevation above the ground, azimuth from the horizontal view."""
        e = np.radians(np.asarray(elevations, float))[:, None]
        a = math.radians(azimuth)
        right = np.cross(self.up, self.forward)
        out = np.cos(e) * math.sin(a) * right + np.sin(e) * self.up + np.cos(e) * math.cos(a) * self.forward
        return out / np.linalg.norm(out, axis=-1, keepdims=True)

    def angles(self, lv: Array) -> tuple[Array, Array]:
        """θ (the normal against each sun) and φ (the receiver's steepest depth change from the map's s axis) [deg], (E, P)."""
        l = lv / np.linalg.norm(lv, axis=-1, keepdims=True)
        cos = np.clip(self.normal @ l.T, -1.0, 1.0).T  # (E, P)
        theta = np.degrees(np.arccos(cos))
        s = np.cross(self.up, l)
        sn = np.linalg.norm(s, axis=-1, keepdims=True)
        s = np.where(sn > 1e-12, s / np.where(sn > 1e-12, sn, 1.0), np.array([1.0, 0.0, 0.0]))
        t = np.cross(l, s)
        phi = np.degrees(np.arctan2(t @ self.normal.T, s @ self.normal.T))  # the normal's projection across the light
        return theta, np.where(np.isfinite(phi), phi, 90.0)

    def cascades(self, near_i: Array, far_i: Array) -> NDArray[np.bool_]:
        """(K, P): whether each pixel is drawn from cascade k (the first whose eye-depth range holds its depth)."""
        z = self.position[:, 2]
        inside = (z[None, :] >= np.asarray(near_i)[:, None]) & (z[None, :] < np.asarray(far_i)[:, None])
        first = np.argmax(inside, axis=0)
        return inside & (np.arange(len(near_i))[:, None] == first[None, :])

    def kinds(self) -> dict[str, NDArray[np.bool_]]:
        """Which receivers are ground (normal near up), walls (normal near horizontal) and other slopes, (P,) each."""
        c = self.normal @ self.up
        lim = math.sin(math.radians(CLASS_ANGLE))
        ground = c >= math.cos(math.radians(CLASS_ANGLE))
        walls = np.abs(c) <= lim
        return {"ground": ground, "walls": walls, "other slopes": ~ground & ~walls}

    def verdict(self, k: int, short: NDArray[np.bool_], elev: Array, fixes: str, acne: float) -> str:
        """Which receivers acne in cascade k and how many pixels, at the worst sun."""
        counts = short.sum(axis=-1)
        e = int(np.argmax(counts))
        parts = [f"{name} {int((short[e] & mask).sum())} px" for name, mask in self.kinds().items() if (short[e] & mask).any()]
        suns = elev[counts > 0]
        when = f"{suns.min():g}–{suns.max():g}° suns" if suns.size > 1 else f"{suns[0]:g}° sun"
        return (f"cascade {k} acnes on {int(counts[e])} px of the {self.source} scene at {elev[e]:g}° sun ({', '.join(parts)}; "
                f"acne at {when}; {acne:.0%} of its receiver pixels over the band): {fixes}")


def scene_pixels(setup: Setup, scene: object, eye: ArrayLike | str | None, target: ArrayLike | str | None, pixels: int) -> Seen:
    """The visible receivers of ``scene`` under the setup's camera (module docstring).

    Raises
    ------
    ValueError
        An unknown scene, a file scene without ``eye`` and ``target``, ``pixels`` outside
        [16, 1024], or a view in which no receiver lies inside [near, far].
    """
    res = check_.whole(pixels, "pixels", 16, 1024, " (eye-pass pixels per side)")
    cam = setup.camera
    if isinstance(scene, str) and scene == "boxes":
        if eye is not None or target is not None:
            raise ValueError("the boxes scene is built around the camera (eye 1 above the ground, looking along the ground): "
                             "eye and target are for the city or a file")
        tri, source = ground_and_boxes(cam.view).triangles, "boxes"
        eye, target = "0,0,0", "0,0,1"
    elif isinstance(scene, str) and scene == "city":
        tri, source = city(CITY_TRIANGLES, seed=0, size=CITY_SIZE), "city"
        if eye is None and target is None:
            street = street_camera(CITY_SIZE)
            eye, target = street.eye, street.eye + street.rotation[2]
    elif isinstance(scene, (str, os.PathLike)):
        tri, source = scene, os.path.basename(os.fspath(scene))
    elif isinstance(scene, (list, tuple, np.ndarray)):
        tri, source = scene, "given"
    else:
        raise ValueError(f"scene must be 'boxes', 'city', a scene file's path or world-space triangles (T, 3, 3), got {type(scene).__name__}")
    if eye is None or target is None:
        raise ValueError("scene needs a camera: eye and target (--eye X,Y,Z --target X,Y,Z) for a scene file or triangles")
    st = scene_setup(tri, eye=eye, target=target, near=cam.near, far=cam.far, fov=cam.fov, aspect=cam.aspect)
    buf = eye_pass(st.scene.triangles, st.camera.view, res, near=cam.near)
    pos, nrm = buf.position.reshape(-1, 3), buf.normal.reshape(-1, 3)
    keep = np.isfinite(pos).all(axis=-1) & (pos[:, 2] >= cam.near) & (pos[:, 2] <= cam.far)
    if not keep.any():
        raise ValueError(f"scene: nothing visible within near..far ({cam.near:g}..{cam.far:g}) from this eye and target")
    up = st.camera.direction_to_eye(np.array([0.0, 1.0, 0.0]))
    fwd = np.array([0.0, 0.0, 1.0]) - up[2] * up
    if np.linalg.norm(fwd) < 1e-9:
        raise ValueError("scene: the camera looks straight up or down: the sun's azimuth from the view direction is undefined")
    return Seen(pos[keep], nrm[keep], up, fwd / np.linalg.norm(fwd), source)
