"""A seeded procedural city block with trees (world space, y up), exportable to GLB with a camera.

For demos and benchmarks of real-size scenes: a ground grid, box buildings on a street grid
and trees (a box trunk and a cone crown) in between, about ``triangles`` triangles in all
(10³ … 10⁷), deterministic for a seed.  :func:`to_glb` writes any triangle soup as a
binary glTF file (through ``trimesh``, the ``scenes`` extra) with named perspective cameras
placed by their nodes' translation and rotation.

Command line (writes the file used in the README)::

    python -m aliasing.raster.scenes.procedural --triangles 100000 --seed 1 --out city.glb

Example
-------
>>> tri = city(triangles=5000, seed=1)
>>> tri.shape[1:], 4500 <= len(tri) <= 5500
((3, 3), True)
>>> bool(tri[..., 1].min() == 0.0)   # the ground is y = 0
True
"""

from __future__ import annotations

import argparse
import json
import os
import struct
import sys
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from .camera import Camera, look_at
from .builtin import _box
from ...view import theta_of

Array = NDArray[np.float64]

#: Crown segments of a tree at 10⁴ triangles (2·segments triangles, sides and base, plus 12
#: for the trunk); larger scenes get finer crowns (up to :data:`MAX_SEGMENTS`) rather than a
#: denser forest.
SEGMENTS = 8
MAX_SEGMENTS = 48
#: Most buildings (12 triangles each): a city block's few hundred, however large the scene.
MAX_BUILDINGS = 600


def _cones(base: Array, radius: Array, height: Array, segments: int = SEGMENTS) -> Array:
    """Cones with ``segments`` sides: base centre (N, 3), radius (N,), height (N,) → (2·segments·N, 3, 3)."""
    a = 2 * np.pi * np.arange(segments + 1) / segments
    ring = np.stack([np.cos(a), np.zeros_like(a), np.sin(a)], -1)  # (S+1, 3)
    rim = base[:, None, :] + radius[:, None, None] * ring[None]  # (N, S+1, 3)
    tip = base + np.stack([0 * height, height, 0 * height], -1)
    n = len(base)
    side = np.stack([rim[:, :-1], rim[:, 1:], np.broadcast_to(tip[:, None], (n, segments, 3))], 2)
    bottom = np.stack([rim[:, 1:], rim[:, :-1], np.broadcast_to(base[:, None], (n, segments, 3))], 2)
    return np.concatenate([side, bottom], 1).reshape(-1, 3, 3)


def city(triangles: int = 100_000, seed: int = 0, *, size: float = 400.0) -> Array:
    """World-space triangles (T, 3, 3) of a city block with trees on the ground y = 0.

    Parameters
    ----------
    triangles : int
        Approximate triangle count, in [10³, 10⁷] (within 1 %).
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    size : float
        Side of the square block centred at the origin [world units], > 0.

    Returns
    -------
    ndarray (T, 3, 3)
        Ground (a grid taking about a quarter of the triangles), buildings (boxes, up to
        :data:`MAX_BUILDINGS`, footprints up to a third of a lot, 3–60 high, on a 12 × 12 street grid of lots) and trees (a
        box trunk and a cone crown, 3–12 high; the crowns' segments grow with the count) [world units].
    """
    if isinstance(triangles, bool) or int(triangles) != triangles or not 1_000 <= triangles <= 10_000_000:
        raise ValueError(f"triangles must be a whole number in [1000, 10000000], got {triangles!r}")
    if not (np.isfinite(size) and size > 0):
        raise ValueError(f"size must be > 0 [world units], got {size!r}")
    rng = np.random.default_rng(seed)
    half = size / 2
    g = max(1, int(np.sqrt(0.125 * triangles)))  # ground cells per side: 2g² ≈ a quarter of the triangles
    xs = np.linspace(-half, half, g + 1)
    xx, zz = np.meshgrid(xs, xs, indexing="ij")
    pts = np.stack([xx, np.zeros_like(xx), zz], -1)
    a, b, c, d = pts[:-1, :-1], pts[1:, :-1], pts[1:, 1:], pts[:-1, 1:]
    ground = np.concatenate([np.stack([a, c, b], -2), np.stack([a, d, c], -2)]).reshape(-1, 3, 3)
    rest = int(triangles) - len(ground)
    n_build = min(int(0.3 * rest) // 12, MAX_BUILDINGS)
    seg = int(np.clip(round(SEGMENTS * np.sqrt(triangles / 10_000)), SEGMENTS, MAX_SEGMENTS))
    n_tree = (rest - 12 * n_build) // (12 + 2 * seg)
    # buildings on a 12 × 12 street grid of lots, several per lot, random footprints
    lot = size / 12
    cell = rng.integers(0, 12, (n_build, 2))
    centre_xz = -half + (cell + rng.uniform(0.15, 0.85, (n_build, 2))) * lot
    w = rng.uniform(2.0, 0.15 * lot + 2.0, (n_build, 2))
    h = rng.uniform(3.0, 60.0, n_build) * rng.uniform(0.2, 1.0, n_build)
    bc = np.stack([centre_xz[:, 0], h / 2, centre_xz[:, 1]], -1)
    buildings = _box(bc, np.stack([w[:, 0], h / 2, w[:, 1]], -1))
    # trees anywhere on the block
    txz = rng.uniform(-0.98 * half, 0.98 * half, (n_tree, 2))
    th = rng.uniform(3.0, 12.0, n_tree)
    trunk_h = 0.35 * th
    trunk = _box(np.stack([txz[:, 0], trunk_h / 2, txz[:, 1]], -1), np.stack([0.08 * th, trunk_h / 2, 0.08 * th], -1))
    crown = _cones(np.stack([txz[:, 0], trunk_h, txz[:, 1]], -1), 0.3 * th, 0.65 * th, seg)
    return np.concatenate([ground, buildings, trunk, crown])


def street_camera(size: float = 400.0) -> Camera:
    """The demo camera of :func:`city`: 20 up, outside a corner of the block, looking at its centre (near 0.5, far 1.5·size)."""
    return look_at([-0.55 * size, 20.0, -0.55 * size], [0.0, 0.0, 0.0], near=0.5, far=1.5 * size, fov=60.0)


def _quaternion(rot: Array) -> list[float]:
    from scipy.spatial.transform import Rotation

    return [float(q) for q in Rotation.from_matrix(rot).as_quat()]  # (x, y, z, w), glTF's order


def to_glb(triangles: Array, path: str | os.PathLike, cameras: dict[str, Camera] | None = None) -> str:
    """Write triangles (T, 3, 3) [world units] as a GLB file, with perspective cameras by name.

    A camera's node gets translation = eye and the rotation taking glTF's local frame
    (−z ahead, +y up) to the camera's; yfov = fov, znear = near, zfar = far.
    Needs trimesh (``pip install ".[scenes]"``).  Returns the path written.
    """
    try:
        import trimesh
    except ImportError:
        raise ValueError("writing GLB needs trimesh: pip install \".[scenes]\"") from None
    tri = np.asarray(triangles, float)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri):
        raise ValueError(f"triangles must have shape (T, 3, 3) with T >= 1, got {tri.shape}")
    mesh = trimesh.Trimesh(vertices=tri.reshape(-1, 3), faces=np.arange(3 * len(tri)).reshape(-1, 3), process=False)
    data = trimesh.Scene(mesh).export(file_type="glb")
    if cameras:
        data = add_cameras(data, cameras)
    name = os.fspath(path)
    with open(name, "wb") as fh:
        fh.write(data)
    return name


def add_cameras(glb: bytes, cameras: dict[str, Camera]) -> bytes:
    """The GLB ``glb`` with perspective cameras added as root nodes of its default scene."""
    length, kind = struct.unpack_from("<I4s", glb, 12)
    doc = json.loads(glb[20:20 + length].decode("utf-8"))
    rest = glb[20 + length:]
    scene = doc.setdefault("scenes", [{"nodes": []}])[doc.get("scene", 0)]
    for label, cam in cameras.items():
        doc.setdefault("cameras", []).append({"type": "perspective", "name": label, "perspective": {
            "yfov": float(2 * theta_of(cam.fov)), "znear": cam.near, "zfar": cam.far, "aspectRatio": float(cam.aspect)}})
        local = np.stack([cam.rotation[0], cam.rotation[1], -cam.rotation[2]], 1)  # columns: local x, y, z
        doc.setdefault("nodes", []).append({"name": f"{label}-node", "camera": len(doc["cameras"]) - 1,
                                             "translation": [float(v) for v in cam.eye], "rotation": _quaternion(local)})
        scene.setdefault("nodes", []).append(len(doc["nodes"]) - 1)
    text = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + rest
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m aliasing.raster.scenes.procedural``: write the city block as GLB with its "street" camera."""
    p = argparse.ArgumentParser(prog="python -m aliasing.raster.scenes.procedural", description="Write a seeded city block with trees as GLB.")
    p.add_argument("--triangles", type=int, default=100_000, help="approximate triangle count (default 100000)")
    p.add_argument("--seed", type=int, default=1, help="seed (default 1)")
    p.add_argument("--size", type=float, default=400.0, help="side of the block in world units (default 400)")
    p.add_argument("--out", required=True, help="output .glb file")
    args = p.parse_args(argv)
    try:
        if not args.out.lower().endswith(".glb"):
            raise ValueError(f"--out must be a .glb file, got {args.out!r}")
        tri = city(args.triangles, args.seed, size=args.size)
        to_glb(tri, args.out, {"street": street_camera(args.size)})
    except ValueError as exc:
        print(f"procedural: error: {exc}", file=sys.stderr)
        return 2
    print(f"{args.out}: {len(tri)} triangles, camera 'street'")
    return 0


if __name__ == "__main__":
    sys.exit(main())
