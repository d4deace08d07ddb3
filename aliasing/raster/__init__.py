"""Numpy rasterizer: the toolkit's independent witness for the analytic aliasing bounds.

* :mod:`.rasterize`: the rasterizer's public names, from one module per concern:
  :mod:`.core` (validation, clipping, the vectorized z-buffer :func:`rasterize` for (s, t,
  depth) triangles), :mod:`.coverage` (covered spans and depths), :mod:`.lightmap` (maps
  through the toolkit's parameterizations), :mod:`.facemaps` (face-partition maps, map
  sets; face-fixed FP, FPc, FPcs), :mod:`.shadow` (shadow maps; log+perspective by logarithmic rasterization) and
  :mod:`.eye` (the eye pass: visible position and normal per pixel, its z-buffer culled by
  :mod:`.occlusion`);
* :mod:`.scenes`: seeded procedural scenes (ground, boxes, probe planes) and an ASCII
  OBJ/PLY loader;
* :mod:`.measure`: perspective aliasing measured from sampled positions by finite
  differences, compared with :func:`aliasing.schemes.evaluate`;
* :mod:`.raycast`: a ray-casting reference for the shadow maps (one Embree ray per texel;
  optional, ``pip install ".[bench]"``).

Example
-------
>>> from aliasing import raster
>>> sc = raster.ground_and_boxes(near=1.0, far=50.0, boxes=5, seed=1)
>>> lm = raster.light_map(1.0, 50.0, 60.0, "gamma:60", "P")
>>> m = raster.shadow_map(sc.triangles, lm, 64)
>>> m.resolution, m.degenerate   # the boxes' 4 sides facing ±x are edge-on to this light: skipped
(64, 20)
"""

from .rasterize import (
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
)
from .scenes import Scene, ground_and_boxes, load_mesh, probes
from .measure import Measurement, measure

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
]
