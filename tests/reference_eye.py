"""The eye pass before issue 12, kept as the bit-identity reference (not part of the package).

Used by tests/test_raster_eye.py and, imported by path, by benchmarks/raster.py: one copy.
"""

from __future__ import annotations

import numpy as np

from aliasing import raster
from aliasing.raster.draw import clip_near, project


def reference_eye_pass(triangles, fov: float, res: int, near: float = 1e-3):
    """(position, normal, triangle id) of the plain eye pass: z-buffer in triangle order, masked positions."""
    tri = np.asarray(triangles, float)
    clipped, src = clip_near(tri, near)
    u, v, z = project(clipped, fov)
    dm = raster.rasterize(np.stack([u, v, -1.0 / z], axis=-1), res)
    ident = np.where(dm.triangle >= 0, src[np.maximum(dm.triangle, 0)], -1)
    t = np.tan(np.radians(fov) / 2)
    c = (np.arange(res) + 0.5) / res
    ray = np.stack(np.broadcast_arrays(((2 * c[None, :] - 1) * t), ((2 * c[:, None] - 1) * t), np.ones((res, 1))), axis=-1)
    a, b, cc = tri[:, 0], tri[:, 1], tri[:, 2]
    nrm = np.cross(b - a, cc - a)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    hit = ident >= 0
    n_px, a_px, r_px = nrm[ident[hit]], a[ident[hit]], ray[hit]
    lam = (n_px * a_px).sum(-1) / (n_px * r_px).sum(-1)
    position = np.full((res, res, 3), np.nan)
    normal = np.full((res, res, 3), np.nan)
    position[hit] = r_px * lam[:, None]
    normal[hit] = np.where(((n_px * r_px).sum(-1) > 0)[:, None], -n_px, n_px)
    return position, normal, ident
