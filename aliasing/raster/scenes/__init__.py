"""Scenes: what the rasterizer draws, in the toolkit's eye space.

* :mod:`.builtin`: the seeded ground-and-boxes scene and the validation probes
  (:class:`Scene`: an eye-space triangle soup with a probe group per triangle);
* :mod:`.procedural`: a seeded procedural city (up to 10⁶ triangles) and its street cameras;
* :mod:`.loading`: the one mesh loader: glTF/GLB, OBJ, PLY and STL through trimesh (the
  ``scenes`` extra), with a plain ASCII OBJ/PLY reader as its fallback (:func:`load_mesh`);
* :mod:`.camera`: a world-space camera and the one world → eye conversion;
* :mod:`.world`: a loaded scene placed by its camera and light (:func:`setup`), and the
  command-line options that name it.

Example
-------
>>> sc = ground_and_boxes(near=1.0, far=50.0, boxes=5, seed=1)
>>> sc.triangles.shape[1:], len(probes(1.0, 50.0, 60.0, "overhead", cells=2).normals)
((3, 3), 4)
"""

from __future__ import annotations

from .builtin import Scene, ground_and_boxes, probes
from .camera import Camera, check_raster_frustum, from_matrix, look_at
from .loading import GltfCamera, WorldScene, load_mesh, load_scene
from .world import MIN_COS_LIGHT, SceneSetup, plane_ids, setup

__all__ = [
    "Camera", "GltfCamera", "MIN_COS_LIGHT", "Scene", "SceneSetup", "WorldScene", "check_raster_frustum", "from_matrix",
    "ground_and_boxes", "load_mesh", "load_scene", "look_at", "plane_ids", "probes", "setup",
]
