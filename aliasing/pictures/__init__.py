"""Pictures from the rasterizer: shadowed renders, projected texel grids, error maps and
distributions, of the built-in scene or a loaded one.

* :mod:`.images`: a scene seen and shadowed through a scheme's maps (:func:`render_view`)
  and the pictures drawn from it (:func:`shade`, :func:`grid_of`, :func:`error_of`), the
  error's distribution over light directions (:func:`error_cdf`);
* :mod:`.scenerender`: each scheme rendered and measured on the built-in or a loaded scene
  with any split method or engine preset, drawn as titled panels with their statistics;
* :mod:`.command`: the ``aliasing render`` command (every case through :mod:`.scenerender`).

Example
-------
>>> img = shadow_image(1.0, 20.0, 60.0, "gamma:60", "P", image_res=32, budget=64**2, seed=1)
>>> img.shape
(32, 32, 3)
"""

from __future__ import annotations

from ..raster.draw.lookup import BIAS, shadow_test
from ..raster.scenes.world import add_scene_arguments
from .images import (
    AMBIENT, BOX, GRID_COLOURS, GROUND, SKY, View, analytic_max_error, cdf, error_cdf, error_colours, error_field, error_image, error_of,
    grid_image, grid_of, map_resolution, measured_max_error, random_lights, render_view, shade, shadow_image, view,
)
from .command import add_render_parser

__all__ = [
    "AMBIENT", "BIAS", "BOX", "GRID_COLOURS", "GROUND", "SKY", "View", "add_render_parser", "add_scene_arguments", "analytic_max_error", "cdf",
    "error_cdf", "error_colours", "error_field", "error_image", "error_of", "grid_image", "grid_of", "map_resolution", "measured_max_error",
    "random_lights", "render_view", "shade", "shadow_image", "shadow_test", "view",
]
