"""Load an engine's export (glTF/GLB, OBJ, PLY, STL) as world-space triangles, with its cameras.

Meshes are read by ``trimesh`` (optional: ``pip install ".[scenes]"``): every
geometry node of the scene graph is placed by its world transform (glTF node translation,
rotation, scale or matrix, composed down the hierarchy).  glTF cameras are read from the
file's own JSON (trimesh keeps only the first one): every perspective camera, by its name
and by its node's name, placed by its node's world transform.  Without trimesh, ASCII OBJ
and PLY files still load through :func:`load_mesh`, the plain reader at the end of this
module.

Triangles of zero area (collinear or repeated corners) are skipped and counted
(``WorldScene.degenerate``); a file that does not parse, holds no triangles or has
non-finite vertices raises ``ValueError`` in one line.

Example
-------
>>> import os, tempfile
>>> p = os.path.join(tempfile.mkdtemp(), "quad.obj")
>>> _ = open(p, "w").write("v 0 0 0\\nv 1 0 0\\nv 1 1 0\\nv 0 1 0\\nv 2 2 2\\nf 1 2 3 4\\nf 1 1 5\\n")
>>> ws = load_scene(p)
>>> ws.triangles.shape, ws.degenerate
((2, 3, 3), 1)
"""

from __future__ import annotations

import json
import os
import struct
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from .camera import Camera, from_matrix
from .builtin import Scene

Array = NDArray[np.float64]

#: File types read (through trimesh; .obj and ASCII .ply also without it).
FORMATS = (".glb", ".gltf", ".obj", ".ply", ".stl")
EXTRA = "pip install \".[scenes]\""


@dataclass(frozen=True)
class GltfCamera:
    """A glTF perspective camera: its node's world matrix (4×4), yfov [deg], znear, zfar (None if infinite)."""

    name: str
    matrix: Array
    yfov: float
    znear: float
    zfar: float | None


@dataclass(frozen=True)
class WorldScene:
    """World-space triangles (T, 3, 3) [world units], the skipped degenerate count, the file's glTF cameras."""

    triangles: Array
    degenerate: int = 0
    cameras: dict[str, GltfCamera] = field(default_factory=dict)
    source: str = ""

    def camera(self, name: str, *, near: float | None = None, far: float | None = None, fov: float | None = None) -> Camera:
        """The :class:`~aliasing.raster.scenes.camera.Camera` of glTF camera ``name``; near/far/fov override the file's.

        The glTF yfov (vertical, full) is the square image's fov; a camera without zfar
        (infinite) needs ``far``.
        """
        if name not in self.cameras:
            have = ", ".join(sorted(self.cameras)) or "none"
            raise ValueError(f"camera {name!r} is not in {self.source or 'the scene'} (glTF cameras: {have})")
        c = self.cameras[name]
        f = c.zfar if far is None else far
        if f is None:
            raise ValueError(f"camera {name!r} has no zfar (infinite projection): give --far")
        return from_matrix(c.matrix, near=c.znear if near is None else near, far=f, fov=c.yfov if fov is None else fov, name=name)

    def in_eye_space(self, cam: Camera) -> Scene:
        """The triangles in the eye space of ``cam``; ValueError if none reaches in front of it (z > near)."""
        tri = cam.to_eye(self.triangles)
        if not (tri[..., 2].max(axis=1) > cam.near).any():
            raise ValueError(f"no triangles in front of the camera {cam.name!r} (all at eye depth <= near = {cam.near:g})")
        return Scene(tri, np.full(len(tri), -1, np.int64))


def _trimesh():
    try:
        import trimesh
    except ImportError:
        return None
    return trimesh


def load_scene(path: str | os.PathLike) -> WorldScene:
    """Triangles (world space, node transforms applied) and cameras of a mesh or scene file.

    Parameters
    ----------
    path : str or path-like
        ``.glb``, ``.gltf``, ``.obj``, ``.ply`` (ASCII or binary) or ``.stl``.

    Raises
    ------
    ValueError
        Unknown extension, missing/empty/unparsable file, no triangles, non-finite
        vertices, or a binary format without trimesh (naming the extra to install).
    """
    name = os.fspath(path)
    ext = os.path.splitext(name)[1].lower()
    if ext not in FORMATS:
        raise ValueError(f"scene file must end in {', '.join(FORMATS)}, got {name!r}")
    if not os.path.exists(name):
        raise ValueError(f"scene file {name!r} does not exist")
    if not os.path.isfile(name):  # a folder, FIFO or device (a FIFO would block the read)
        raise ValueError(f"scene file {name!r} is not a regular file")
    if os.path.getsize(name) == 0:
        raise ValueError(f"scene file {name!r} is empty")
    tm = _trimesh()
    if tm is None:
        if ext in (".obj", ".ply"):
            try:
                return _clean(load_mesh(name).triangles, name, {})
            except ValueError as exc:
                raise ValueError(f"{exc} (binary PLY, glTF/GLB and STL need trimesh: {EXTRA})") from None
        raise ValueError(f"loading {ext} files needs trimesh: {EXTRA}")
    try:
        sc = tm.load(name, force="scene", process=False)
        parts = []
        for node in sc.graph.nodes_geometry:
            matrix, geom = sc.graph[node]
            g = sc.geometry[geom]
            faces = getattr(g, "faces", None)
            if faces is None or len(faces) == 0:
                continue
            v = np.asarray(g.vertices, float) @ matrix[:3, :3].T + matrix[:3, 3]
            parts.append(v[np.asarray(faces)])
    except Exception as exc:  # trimesh raises many types for a malformed file
        msg = " ".join(str(exc).split()) or type(exc).__name__
        raise ValueError(f"cannot parse scene file {name!r}: {msg[:200]}") from None
    if not parts:
        raise ValueError(f"scene file {name!r} has no triangles")
    cams = gltf_cameras(name) if ext in (".glb", ".gltf") else {}
    return _clean(np.concatenate(parts), name, cams)


def _clean(tri: Array, name: str, cams: dict[str, GltfCamera]) -> WorldScene:
    if not np.isfinite(tri).all():
        raise ValueError(f"scene file {name!r} has non-finite (NaN or infinite) vertex coordinates")
    area2 = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=-1)
    scale = np.abs(tri).max() or 1.0
    ok = area2 > 1e-12 * scale * scale
    if not ok.any():
        raise ValueError(f"scene file {name!r} has no triangles of non-zero area ({len(tri)} degenerate)")
    return WorldScene(tri[ok], int((~ok).sum()), cams, name)


def gltf_json(path: str | os.PathLike) -> dict:
    """The JSON document of a ``.gltf`` file or of a ``.glb`` file's first chunk."""
    name = os.fspath(path)
    with open(name, "rb") as fh:
        data = fh.read()
    try:
        if data[:4] == b"glTF":
            length, kind = struct.unpack_from("<I4s", data, 12)
            if kind != b"JSON":
                raise ValueError("first GLB chunk is not JSON")
            return json.loads(data[20:20 + length].decode("utf-8"))
        return json.loads(data.decode("utf-8"))
    except (ValueError, struct.error, UnicodeDecodeError) as exc:
        raise ValueError(f"cannot parse glTF file {name!r}: {exc}") from None


def _node_matrix(node: dict) -> Array:
    if "matrix" in node:
        return np.asarray(node["matrix"], float).reshape(4, 4).T  # glTF stores column-major
    t = np.asarray(node.get("translation", [0, 0, 0]), float)
    x, y, z, w = np.asarray(node.get("rotation", [0, 0, 0, 1]), float)  # unit quaternion (x, y, z, w)
    s = np.asarray(node.get("scale", [1, 1, 1]), float)
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3] = r * s  # T · R · S
    m[:3, 3] = t
    return m


def gltf_cameras(path: str | os.PathLike) -> dict[str, GltfCamera]:
    """The perspective cameras of a glTF/GLB file, keyed by camera name and by node name.

    Each is placed by the world matrix of its node (the product of the matrices from the
    scene's root down).  Orthographic cameras are left out.
    """
    doc = gltf_json(path)
    nodes, cams = doc.get("nodes", []), doc.get("cameras", [])
    scenes = doc.get("scenes", [])
    roots = scenes[doc.get("scene", 0)].get("nodes", []) if scenes else range(len(nodes))
    out: dict[str, GltfCamera] = {}
    stack = [(int(i), np.eye(4)) for i in roots]
    seen = set()
    while stack:
        i, parent = stack.pop()
        if i in seen or not 0 <= i < len(nodes):
            continue
        seen.add(i)
        node = nodes[i]
        world = parent @ _node_matrix(node)
        stack += [(int(c), world) for c in node.get("children", [])]
        if "camera" not in node or not 0 <= node["camera"] < len(cams):
            continue
        cam = cams[node["camera"]]
        per = cam.get("perspective")
        if cam.get("type") != "perspective" or per is None:
            continue
        label = cam.get("name") or node.get("name") or f"camera{node['camera']}"
        gc = GltfCamera(label, world, float(np.degrees(per["yfov"])), float(per["znear"]), None if per.get("zfar") is None else float(per["zfar"]))
        for key in {label, node.get("name")} - {None}:
            out.setdefault(key, gc)
    return out


# ---------------------------------------------------------------- the ASCII fallback (no trimesh)


def load_mesh(path: str | os.PathLike) -> Scene:
    """Triangles of an ASCII OBJ (``v``/``f`` lines; polygons fan-triangulated) or PLY file.

    Parameters
    ----------
    path : str or path-like
        ``.obj`` or ``.ply`` (``format ascii 1.0``, vertex x y z first, face lists).

    Raises
    ------
    ValueError
        Unknown extension, unreadable or unparsable content (with the line number), binary
        PLY, or no triangles.

    Example
    -------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp(); p = os.path.join(d, "quad.obj")
    >>> _ = open(p, "w").write("v 0 0 1\\nv 1 0 1\\nv 1 1 1\\nv 0 1 1\\nf 1 2 3 4\\n")
    >>> load_mesh(p).triangles.shape
    (2, 3, 3)
    """
    name = os.fspath(path)
    ext = os.path.splitext(name)[1].lower()
    if ext not in (".obj", ".ply"):
        raise ValueError(f"path must end in .obj or .ply, got {name!r}")
    try:
        with open(name, encoding="utf-8") as fh:
            lines = fh.read().splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"cannot read mesh file {name!r}: {exc}") from None
    verts, faces = (_parse_obj if ext == ".obj" else _parse_ply)(lines, name)
    if not faces:
        raise ValueError(f"mesh file {name!r} has no faces (empty scene)")
    v = np.asarray(verts, float)
    tris = []
    for lineno, f in faces:
        if len(f) < 3:
            raise ValueError(f"{name}:{lineno}: a face needs at least 3 vertices")
        for i in f:
            if not -len(v) <= i < len(v):
                raise ValueError(f"{name}:{lineno}: vertex index out of range [1, {len(v)}]")
        tris += [(f[0], f[j], f[j + 1]) for j in range(1, len(f) - 1)]
    tri = v[np.asarray(tris)]
    if not np.isfinite(tri).all():
        raise ValueError(f"mesh file {name!r} has non-finite vertex coordinates")
    return Scene(tri, np.full(len(tri), -1, np.int64))


def _parse_obj(lines: list[str], name: str) -> tuple[list[list[float]], list[tuple[int, list[int]]]]:
    verts: list[list[float]] = []
    faces: list[tuple[int, list[int]]] = []
    for no, raw in enumerate(lines, 1):
        parts = raw.split("#", 1)[0].split()
        if not parts:
            continue
        try:
            if parts[0] == "v":
                if len(parts) < 4:
                    raise ValueError
                verts.append([float(x) for x in parts[1:4]])
            elif parts[0] == "f":
                idx = [int(p.split("/")[0]) for p in parts[1:]]
                if any(i == 0 for i in idx):
                    raise ValueError
                faces.append((no, [i - 1 if i > 0 else len(verts) + i for i in idx]))
        except ValueError:
            raise ValueError(f"{name}:{no}: cannot parse OBJ line {raw.strip()!r}") from None
    return verts, faces


def _parse_ply(lines: list[str], name: str) -> tuple[list[list[float]], list[tuple[int, list[int]]]]:
    if not lines or lines[0].strip() != "ply":
        raise ValueError(f"{name}:1: not a PLY file (first line must be 'ply')")
    elements: list[tuple[str, int, list[str]]] = []
    fmt = None
    end = None
    for no, raw in enumerate(lines[1:], 2):
        parts = raw.split()
        if not parts or parts[0] in ("comment", "obj_info"):
            continue
        if parts[0] == "format":
            fmt = parts[1] if len(parts) > 1 else ""
        elif parts[0] == "element":
            try:
                elements.append((parts[1], int(parts[2]), []))
            except (IndexError, ValueError):
                raise ValueError(f"{name}:{no}: cannot parse PLY header line {raw.strip()!r}") from None
        elif parts[0] == "property" and elements:
            elements[-1][2].append(parts[-1])
        elif parts[0] == "end_header":
            end = no
            break
    if fmt != "ascii":
        raise ValueError(f"{name}: only 'format ascii 1.0' PLY files are supported, got format {fmt!r}")
    if end is None:
        raise ValueError(f"{name}: PLY header has no end_header")
    verts: list[list[float]] = []
    faces: list[tuple[int, list[int]]] = []
    row = end  # 0-based index of the next body line
    for el_name, count, props in elements:
        for _ in range(count):
            if row >= len(lines):
                raise ValueError(f"{name}: PLY body ends early (element {el_name!r} expects {count} lines)")
            parts = lines[row].split()
            row += 1
            try:
                if el_name == "vertex":
                    ix = [props.index(a) for a in ("x", "y", "z")]
                    verts.append([float(parts[i]) for i in ix])
                elif el_name == "face":
                    m = int(parts[0])
                    if len(parts) < m + 1:
                        raise ValueError
                    faces.append((row, [int(p) for p in parts[1:m + 1]]))
            except (ValueError, IndexError):
                raise ValueError(f"{name}:{row}: cannot parse PLY {el_name} line {lines[row - 1].strip()!r}") from None
    return verts, faces
