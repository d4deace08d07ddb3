"""Drawing maps: the vectorized triangle rasterizer, depth maps, face maps, the eye pass.

One module per step; this package re-exports their public names:

* :mod:`.core`: map coordinates, validation, :class:`DepthMap`, near clipping and
  :func:`rasterize` (bounding boxes, chunking);
* :mod:`.coverage`: the exact covered span of each (triangle, row) and its depths;
* :mod:`.lightmap`: :class:`LightMap` (warped maps) and :func:`light_map`, :func:`light_maps`;
* :mod:`.facemaps`: face-partition maps (:func:`frame_map`, :func:`near_face_map`)
  and :func:`map_set`;
* :mod:`.shadow`: :func:`shadow_map`, :func:`shadow_maps` (every map of a set), the
  logarithmic rasterization (:func:`log_row_centres`) and :class:`MapSampler` (a map drawn
  only at the texels looked up);
* :mod:`.occlusion`: front-to-back occlusion culling with an order-independent merge (the
  same buffers as :func:`rasterize`), used by the eye pass;
* :mod:`.eye`: the eye pass (:func:`eye_pass`, :func:`project`);
* :mod:`.compiled`: the eye pass's optional numba kernels (``eye_pass(..., backend="numba")``);
* :mod:`.backends`: the table of drawing backends (numpy, the reference; numba; gl) and the
  one check of a ``backend=`` keyword: the seam where another backend stands beside numpy;
* :mod:`.gl`: depth maps and the eye pass drawn by OpenGL (moderngl, headless EGL; the
  optional ``gl`` extra), with the maps' 4×4 matrices;
* :mod:`.resident`: gl maps kept on the device, their texels fetched there;
* :mod:`.cascades`: a scheme's maps for any split method or engine preset, and the texel
  budget shared among them;
* :mod:`.lookup`: the shadow tests of surface points through a depth map: the toolkit's plane
  test, and the engines' depth compare (constant, slope-scaled and normal-offset bias, PCF,
  receiver-plane depth) with the local texel's sides.

Example
-------
>>> from aliasing.raster.scenes import ground_and_boxes
>>> sc = ground_and_boxes(near=1.0, far=50.0, boxes=5, seed=1)
>>> maps = map_set(1.0, 50.0, 60.0, "gamma:60", "ZP2+P")   # two z-partitions, a P map each
>>> [shadow_map(sc.triangles, lm, 32).resolution for lm in maps.maps]
[32, 32]
"""

from __future__ import annotations

from .core import CHUNK, MAX_RESOLUTION, DepthMap, _triangles, check_resolution, clip_near, rasterize, rasterize_at
from .eye import EyeBuffer, eye_pass, project
from .facemaps import MapSet, fixed_face_map, frame_map, map_set, near_face_map
from .lightmap import LightMap, _unit_vector, light_map, light_maps
from .shadow import MapSampler, log_row_centres, shadow_map, shadow_maps
from .cascades import CascadeSet, budget_shares, cascade_set
from .lookup import BIAS, shadow_test
from .lookup import depth_test, texel_edges

__all__ = [
    "BIAS", "CHUNK", "MapSampler", "CascadeSet", "MAX_RESOLUTION", "DepthMap", "budget_shares", "cascade_set", "shadow_test", "depth_test", "texel_edges", "EyeBuffer", "LightMap", "MapSet", "check_resolution", "clip_near", "eye_pass",
    "fixed_face_map", "frame_map", "light_map", "light_maps", "log_row_centres", "map_set", "near_face_map", "project", "rasterize", "rasterize_at", "shadow_map", "shadow_maps",
]
