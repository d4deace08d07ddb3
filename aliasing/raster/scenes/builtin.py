"""The built-in eye-space scenes: seeded ground and boxes, and the probes of the validation.

All coordinates are eye space [world units] (eye at the origin looking along +z, x right,
y up).  A :class:`Scene` is a triangle soup with a group per triangle: −1 for ordinary
geometry, k ≥ 0 for the triangles of probe k.

Probes (Lloyd 2006 §3.3, Fig. 2): small squares whose normal is half-way between the
direction to the eye and the direction to the light, so that cos φ_i = cos φ_l and the
projection aliasing factor cos φ_i / cos φ_l is 1; what remains is perspective aliasing.

Example
-------
>>> sc = ground_and_boxes(near=1.0, far=100.0, boxes=10, seed=0)
>>> sc.triangles.shape[1:], int((sc.group == -1).sum()) == len(sc.triangles)
((3, 3), True)
>>> pr = probes(1.0, 100.0, 60.0, "overhead", cells=4)
>>> pr.triangles.shape, pr.normals.shape
((32, 3, 3), (16, 3))
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ... import geometry
from ...view import View, view_args

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Scene:
    """A triangle soup.

    Attributes
    ----------
    triangles : ndarray (T, 3, 3)
        Corners in eye space [world units].
    group : ndarray of int64 (T,)
        −1 for ordinary geometry, k for the triangles of probe k.
    normals : ndarray (P, 3)
        Unit normal of each probe (empty for scenes without probes).
    """

    triangles: Array
    group: NDArray[np.int64]
    normals: Array = field(default_factory=lambda: np.zeros((0, 3)))

    def __post_init__(self) -> None:
        if self.triangles.ndim != 3 or self.triangles.shape[1:] != (3, 3) or self.triangles.shape[0] == 0:
            raise ValueError(f"scene must have at least 1 triangle of shape (3, 3), got triangles of shape {self.triangles.shape}")

    def __add__(self, other: "Scene") -> "Scene":
        shift = len(self.normals)
        g = np.where(other.group >= 0, other.group + shift, -1)
        return Scene(np.concatenate([self.triangles, other.triangles]), np.concatenate([self.group, g]), np.concatenate([self.normals, other.normals]))


# Largest counts of the generated scenes: they bound the triangle arrays (~2e6 triangles).
MAX_COUNT = {"boxes": 100_000, "ground_cells": 1024, "cells": 1024}


def _count(value: int, name: str, lo: int) -> int:
    return check.whole(value, name, lo, MAX_COUNT[name], " (scene size; bounds memory)")


def _seed(seed: int) -> int:
    return check.whole(seed, "seed", 0, what=" (random seed)")


def _box(centre: Array, half: Array) -> Array:
    """12 triangles of axis-aligned boxes: centre (B, 3), half sizes (B, 3) → (12B, 3, 3)."""
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    faces = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                      [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    pts = centre[:, None, :] + corners[None] * half[:, None, :]  # (B, 8, 3)
    return pts[:, faces].reshape(-1, 3, 3)


def ground_and_boxes(near: float | View | None = None, far: float | None = None, fov: float | None = None, *, boxes: int = 100, ground_cells: int = 20, height: float = 1.0, seed: int = 0) -> Scene:
    """A ground plane with boxes spread log-uniformly over the depth range [near, far].

    Parameters
    ----------
    near, far : float
        Depth range [world units], 0 < near < far (default 1, 1000); or a
        :class:`~aliasing.View` in ``near``.
    fov : float
        Full field of view [deg] (default 60); the ground spans the view's width at every depth.
    boxes : int
        Number of boxes (12 triangles each), ≥ 0.
    ground_cells : int
        The ground is a ground_cells × ground_cells grid (2 triangles per cell), cells
        spaced logarithmically in depth, ≥ 1.
    height : float
        Eye height above the ground [world units], > 0.
    seed : int
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    Scene
        ``2·ground_cells² + 12·boxes`` triangles.

    Example
    -------
    >>> ground_and_boxes(1.0, 50.0, boxes=3, ground_cells=2).triangles.shape
    (44, 3, 3)
    """
    view, _ = view_args(near, far, fov, (), (1.0, 1000.0, 60.0))
    n, f, tan, _ = _scalar_view(view)  # the width of the view: tan θ_x
    h = float(check.positive(check.scalar(height, "height"), "height"))
    nb = _count(boxes, "boxes", 0)
    gc = _count(ground_cells, "ground_cells", 1)
    rng = np.random.default_rng(_seed(seed))
    z = np.geomspace(0.5 * n, 1.05 * f, gc + 1)
    xs = np.linspace(-1.0, 1.0, gc + 1)
    zz, xx = np.meshgrid(z, xs, indexing="ij")
    half_width = 1.2 * tan * zz + h
    pts = np.stack([xx * half_width, np.full_like(zz, -h), zz], axis=-1)
    a, b, c, d = pts[:-1, :-1], pts[:-1, 1:], pts[1:, 1:], pts[1:, :-1]
    ground = np.concatenate([np.stack([a, b, c], -2).reshape(-1, 3, 3), np.stack([a, c, d], -2).reshape(-1, 3, 3)])
    parts = [ground]
    if nb:
        bz = n * (f / n) ** rng.uniform(0.02, 1.0, nb)
        bx = rng.uniform(-1.0, 1.0, nb) * tan * bz
        size = bz[:, None] * rng.uniform(0.01, 0.05, (nb, 3)) + 0.05 * h
        centre = np.stack([bx, -h + size[:, 1], bz], axis=-1)
        parts.append(_box(centre, size))
    tri = np.concatenate(parts)
    return Scene(tri, np.full(len(tri), -1, np.int64))


def _scalar_view(view: View) -> tuple[float, float, float, float]:
    """near, far, tan θ_x, tan θ_y of one frustum."""
    if view.shape != ():
        raise ValueError(f"near, far and fov must be scalars here, got shape {view.shape}")
    return view.near, view.far, view.tan_theta_x, view.tan_theta


def probes(near: float | View, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, *, cells: int = 32, fill: float = 0.6, seed: int = 0, splits: ArrayLike | None = None) -> Scene:
    """Probe squares, one per cell of a cells × cells grid over the image, inside the frustum.

    Probe k sits on the ray through its cell's centre, faces the bisector of the directions
    to the eye and to the light, and spans about ``fill`` of its cell in the image.  Depths
    are spread log-uniformly over [near, far] by a seeded permutation; the cells nearest each
    image corner hold probes at the ends of the depth range (or of each z-partition, with
    ``splits``): near, far (far twice without splits), then the next partition's near, far,
    and so on, since the analytic maxima lie at the frustum's vertices.  Each probe lies
    wholly in [near, far] and in one partition.

    Parameters
    ----------
    near, far : float
        Frustum depth range [world units]; or a :class:`~aliasing.View` in ``near``
        (``probes(view, light)``).
    fov : float
        Full field of view [deg].
    light : str or array_like
        One light direction (spec or vector towards the light).
    cells : int
        Grid size, ≥ 2.
    fill : float
        Probe size as a fraction of a cell, in (0, 1].
    seed : int
        Seed of the depth permutation.
    splits : array_like, optional
        Increasing split depths C_0 = near < … < C_k = far [world units] of z-partitioned
        maps (e.g. :func:`aliasing.schemes.z_partitions`); default (near, far).

    Example
    -------
    >>> sc = probes(1.0, 10.0, 60.0, "behind", cells=2)
    >>> bool(np.all((sc.triangles[..., 2] >= 1.0) & (sc.triangles[..., 2] <= 10.0)))
    True
    """
    view, (light,) = view_args(near, far, fov, (light,), (None, None, None, None), ("light",))
    n, f, tan_x, tan = _scalar_view(view)
    k = _count(cells, "cells", 2)
    fl = check.scalar(fill, "fill")
    if not 0 < fl <= 1:
        raise ValueError(f"fill must be in (0, 1], got {fl:g}")
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    lv = lv[0]
    c = (np.arange(k) + 0.5) / k
    u, v = np.meshgrid(c, c)  # row = v index
    ray = np.stack([(2 * u - 1) * tan_x, (2 * v - 1) * tan, np.ones_like(u)], axis=-1).reshape(-1, 3)
    to_eye = -ray / np.linalg.norm(ray, axis=-1, keepdims=True)
    nrm = to_eye + lv
    small = np.linalg.norm(nrm, axis=-1) < 1e-3  # light straight behind the probe: face the eye
    nrm[small] = to_eye[small]
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    # in-plane axes
    helper = np.where(np.abs(nrm[:, 1:2]) < 0.9, np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0]))
    e1 = np.cross(nrm, helper)
    e1 /= np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = np.cross(nrm, e1)
    # half size per unit depth: fill/2 of a cell's width (2 tan θ z / k) over the ray length
    half = fl / 2 * 2 * min(tan, tan_x) / k / np.linalg.norm(ray, axis=-1)  # the cell's narrower side
    dz = half * (np.abs(e1[:, 2]) + np.abs(e2[:, 2]))  # corner depth offset per unit depth
    edges = np.array([n, f]) if splits is None else check.finite(splits, "splits").ravel()
    if edges.size < 2 or np.any(np.diff(edges) <= 0) or not (np.isclose(edges[0], n) and np.isclose(edges[-1], f)):
        raise ValueError(f"splits must increase from near ({n:g}) to far ({f:g})")
    q = np.random.default_rng(_seed(seed)).permutation(k * k) / (k * k - 1)
    depth = n * (f / n) ** q
    part = np.clip(np.searchsorted(edges, depth, side="right") - 1, 0, edges.size - 2)
    # the cells nearest each image corner take the partitions' ends
    targets = [(i, end) for i in range(edges.size - 1) for end in (0, 1)]
    if edges.size == 2:
        targets.append((0, 1))
    targets = targets[: k * k // 4]
    for cu, cv in ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)):
        dist = np.hypot(u.ravel() - cu, v.ravel() - cv)
        order = np.argsort(dist, kind="stable")
        for cell, (i, end) in zip(order, targets):
            part[cell] = i
            depth[cell] = edges[i + end]
    # keep the whole probe inside its partition: corners at z_c(1 ± dz)
    lo = edges[part] / (1 - dz) * (1 + 1e-9)
    hi = edges[part + 1] / (1 + dz) * (1 - 1e-9)
    depth = np.minimum(np.maximum(depth, lo), np.maximum(hi, lo))
    centre = ray * depth[:, None]
    hs = (half * depth)[:, None]
    p = [centre + hs * (sa * e1 + sb * e2) for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    tri = np.concatenate([np.stack([p[0], p[1], p[2]], 1), np.stack([p[0], p[2], p[3]], 1)])
    group = np.concatenate([np.arange(k * k), np.arange(k * k)]).astype(np.int64)
    return Scene(tri, group, nrm)
