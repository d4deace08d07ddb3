"""What every engine model shares: the prediction's value, the tight box in a world-up light frame, the exact reference.

Example
-------
>>> p = Prediction(np.ones((1, 1)), np.zeros((1, 1), np.int64), np.array([0.5]), np.array([10.0]), np.array([1024.0]))
>>> float(p.sides[0] / p.resolution[0])
0.009765625
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from . import predict

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Prediction:
    """Per pixel: the predicted ``factor`` and ``cascade``; per cascade: ``starts`` [world units] and map ``sides`` [world units]."""

    factor: Array
    cascade: NDArray[np.int64]
    starts: Array
    sides: Array
    resolution: Array


def tight_sides(camera, edges: Array, along: Array, up: Array) -> Array:
    """Per cascade: the larger side [world units] of the slice corners' box in a light frame whose x axis is ``up`` × ``along``.

    The tight fit's box depends on the light frame's roll about the light direction, which an
    engine takes from a world up vector (Babylon.js: ``Matrix.LookAtLH(centre, centre + d, Vector3.Up())``),
    not from the camera: the extents are measured on x ∝ up × d and y ∝ d × x (signs do not
    change extents; the mirror into Babylon's left-handed world neither).
    """
    d = along / np.linalg.norm(along)
    x = np.cross(up, d)
    x /= np.linalg.norm(x)
    y = np.cross(d, x)
    out = []
    for a, b in zip(edges[:-1], edges[1:]):
        corners = camera.view.slice_vertices(a, b)  # eye space (8, 3)
        world = corners @ camera.rotation + camera.eye
        out.append(max(np.ptp(world @ x), np.ptp(world @ y)))
    return np.array(out)


def reference(scene, sun: Array, rb, resolution: int) -> NDArray[np.bool_]:
    """The exact reference's lit pixels, through the matrix of the cascade each pixel sampled (the last one where none)."""
    pts, nrm = np.nan_to_num(rb.position), np.nan_to_num(rb.normal)
    ref = np.ones(rb.shadow.shape, bool)
    for i, m in enumerate(rb.matrices):
        here = rb.drawn & ((rb.cascade == i) | ((rb.cascade < 0) & (i == len(rb.matrices) - 1)))
        if here.any():
            ref[here] = predict.reference_lit(scene.triangles, m, resolution, pts[here], nrm[here], sun)
    return ref & rb.drawn & ((nrm @ sun) > 0)
