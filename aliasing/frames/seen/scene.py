"""The reference scene of the wrong-pixel measure: boxes and walls on a ground, near and far.

Without a user's scene, :func:`aliasing.frames.seen.wrong_pixels` measures the setup's camera on
:func:`reference_scene`: the built-in boxes scene of :func:`aliasing.frames.scenes.frame_scene`
(a ground 1 below the eye under the whole view, :data:`BOXES` boxes spread log-uniformly over
near … far, each a few hundredths of its depth across: small casters near, large ones far;
seed :data:`SEED`) and :data:`WALLS` walls standing on the ground across the view at depths
log-spaced from max(4 near, far / 100) to far / 2, alternately left and right of the view's
axis, each as long as a quarter of the view's width there, a twentieth of its depth high and a
hundredth thick (long thin casters whose shadows fall on
the ground and on the boxes).  Deterministic; 944 triangles.

Examples
--------
>>> from aliasing.raster.scenes.camera import look_at
>>> fs = reference_scene(0.1, 500.0, 50.0, 16 / 9)
>>> fs.name, fs.ground, fs.triangles.shape
('reference', 128, (944, 3, 3))
"""

from __future__ import annotations

import numpy as np

from ... import _validation as check
from ...raster.scenes.builtin import _box
from ..scenes import FrameScene, frame_scene, wind_outward
from ...view import tan_theta

#: Boxes in the reference scene: enough shadow edges in view that the wrong pixels a setting makes number
#: hundreds, not tens (with 24 a search's ranking of settings did not carry over to another arrangement).
BOXES = 64
#: Walls in the reference scene.
WALLS = 4
#: Ground cells per side.
GROUND_CELLS = 8
#: The scene's seed.
SEED = 7


def reference_scene(near: float, far: float, fov: float, aspect: float) -> FrameScene:
    """The reference scene (module docstring) for a camera at the origin looking along −z, 1 above the ground.

    Parameters
    ----------
    near, far : float
        The camera's near and far distances [world units], 0 < near < far.
    fov : float
        Vertical field of view [deg], in (0, 180).
    aspect : float
        Image width / height, > 0.

    Returns
    -------
    FrameScene
        Named ``reference``; its ground first (the first ``ground`` triangles).

    Examples
    --------
    >>> fs = reference_scene(0.5, 60.0, 50.0, 2.0)
    >>> walls = fs.triangles[-12 * WALLS:]
    >>> bool(np.all(walls[..., 1] >= -1.0)), float(walls[..., 1].min())   # standing on the ground
    (True, -1.0)
    """
    fs = frame_scene("boxes", near=near, far=far, fov=fov, aspect=aspect, boxes=BOXES, ground_cells=GROUND_CELLS, seed=SEED)
    n, f = float(check.scalar(near, "near")), float(check.scalar(far, "far"))
    tan_x = float(tan_theta(fov)) * float(aspect)
    depth = np.geomspace(min(max(4.0 * n, 0.01 * f), 0.25 * f), 0.5 * f, WALLS)
    side = np.where(np.arange(WALLS) % 2 == 0, -1.0, 1.0)  # alternately left and right of the view's axis
    half = np.stack([0.125 * tan_x * depth, 0.025 * depth + 0.05, 0.005 * depth + 0.02], axis=-1)
    centre = np.stack([side * 0.3 * tan_x * depth, -1.0 + half[:, 1], -depth], axis=-1)
    walls = wind_outward(_box(centre, half))
    return FrameScene(np.concatenate([fs.triangles, walls]), fs.ground, fs.camera, "reference")
