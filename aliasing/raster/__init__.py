"""Numpy rasterizer: the toolkit's independent witness for the analytic aliasing bounds.

One package per concern, from the bottom up:

* :mod:`.scenes`: what is drawn: the built-in scenes and probes, the procedural city, the
  one mesh loader (trimesh, with a plain ASCII OBJ/PLY fallback), world cameras;
* :mod:`.draw`: drawing maps: the vectorized z-buffer, depth maps through every
  parameterization (logarithmic rasterization included), face-partitioned map sets,
  cascades, the eye pass, the shadow test, and the backends (numpy, the reference; numba);
* :mod:`.validate`: measuring and validating: perspective aliasing measured by finite
  differences against :func:`aliasing.schemes.evaluate`, validation grids, scene
  validation, and a ray-casting reference for the depth maps (optional,
  ``pip install ".[bench]"``).

The pictures drawn from it (shadowed renders, texel grids, error maps, bias margins) are
:mod:`aliasing.pictures`, a layer above: they also draw the bias margins of
:mod:`aliasing.bias`.

This package re-exports the documented names of the drawing, scenes and measuring
packages; import from those packages in new code.

Example
-------
>>> from aliasing import raster
>>> sc = raster.ground_and_boxes(near=1.0, far=50.0, boxes=5, seed=1)
>>> lm = raster.light_map(1.0, 50.0, 60.0, "gamma:60", "P")
>>> m = raster.shadow_map(sc.triangles, lm, 64)
>>> m.resolution, m.degenerate   # the boxes' 4 sides facing ±x are edge-on to this light: skipped
(64, 20)
"""

from .draw import (
    CHUNK,
    MAX_RESOLUTION,
    DepthMap,
    EyeBuffer,
    LightMap,
    MapSet,
    eye_pass,
    fixed_face_map,
    frame_map,
    light_map,
    light_maps,
    log_row_centres,
    map_set,
    near_face_map,
    project,
    rasterize,
    shadow_map,
    shadow_maps,
)
from .scenes import Scene, ground_and_boxes, load_mesh, probes
from .validate import Measurement, measure

__all__ = [
    "CHUNK",
    "MAX_RESOLUTION",
    "DepthMap",
    "EyeBuffer",
    "LightMap",
    "MapSet",
    "Measurement",
    "Scene",
    "eye_pass",
    "fixed_face_map",
    "frame_map",
    "ground_and_boxes",
    "light_map",
    "light_maps",
    "load_mesh",
    "log_row_centres",
    "map_set",
    "measure",
    "near_face_map",
    "probes",
    "project",
    "rasterize",
    "shadow_map",
    "shadow_maps",
]
