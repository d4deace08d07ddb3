"""Loading engine exports (aliasing.raster.scenes.loading), the world-space camera, the procedural city."""

from __future__ import annotations

import json
import struct

import numpy as np
import pytest

from aliasing.raster.scenes import camera, loading, procedural

trimesh = pytest.importorskip("trimesh")
from scipy.spatial.transform import Rotation  # noqa: E402


@pytest.fixture(scope="module")
def city():
    return procedural.city(1500, seed=3, size=60.0)


def _mesh(tri):
    return trimesh.Trimesh(vertices=tri.reshape(-1, 3), faces=np.arange(3 * len(tri)).reshape(-1, 3), process=False)


@pytest.mark.parametrize("ext,kw", [(".glb", {}), (".ply", {"encoding": "binary"}), (".stl", {}), (".obj", {})])
def test_round_trip_formats(tmp_path, city, ext, kw):
    path = tmp_path / f"city{ext}"
    data = _mesh(city).export(file_type=ext[1:], **kw)
    path.write_bytes(data if isinstance(data, bytes) else data.encode())
    if ext == ".ply":
        assert b"binary_little_endian" in path.read_bytes()[:200]
    ws = loading.load_scene(path)
    assert ws.degenerate == 0 and ws.triangles.shape == city.shape
    # float32 in GLB, binary PLY and STL; OBJ text keeps at least 7 digits
    np.testing.assert_allclose(ws.triangles, city, rtol=0, atol=1e-5 * np.abs(city).max())


def _patch_json(glb: bytes, edit) -> bytes:
    length, _ = struct.unpack_from("<I4s", glb, 12)
    doc = json.loads(glb[20:20 + length])
    edit(doc)
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + glb[20 + length:]
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def test_gltf_node_rotation_scale_and_cameras(tmp_path):
    """A mesh node with translation, rotation and non-uniform scale (TRS, not a matrix), and two
    cameras: one at the root, one under a rotated and translated parent node."""
    box = trimesh.creation.box(extents=[1.0, 2.0, 3.0])
    glb = trimesh.Scene(box).export(file_type="glb")
    cam = camera.look_at([3.0, 4.0, 5.0], [0.0, 1.0, 0.0], near=0.1, far=50.0, fov=45.0)
    glb = procedural.add_cameras(glb, {"main": cam})
    q = Rotation.from_euler("xyz", [20, 35, -50], degrees=True)
    t, s = np.array([1.0, -2.0, 3.0]), np.array([2.0, 0.5, 1.5])
    parent_q = Rotation.from_euler("y", 90, degrees=True)

    def edit(doc):
        for node in doc["nodes"]:
            if "mesh" in node:
                node.pop("matrix", None)
                node.update(translation=t.tolist(), rotation=q.as_quat().tolist(), scale=s.tolist())
        doc["cameras"].append({"type": "perspective", "name": "child", "perspective": {"yfov": 1.0, "znear": 0.5, "zfar": 80.0}})
        doc["nodes"].append({"name": "child-node", "camera": len(doc["cameras"]) - 1, "translation": [0.0, 0.0, 2.0]})
        doc["nodes"].append({"name": "rig", "children": [len(doc["nodes"]) - 1], "translation": [10.0, 0.0, 0.0], "rotation": parent_q.as_quat().tolist()})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)

    path = tmp_path / "nodes.glb"
    path.write_bytes(_patch_json(glb, edit))
    ws = loading.load_scene(path)
    expected = q.apply(box.vertices[box.faces].reshape(-1, 3) * s).reshape(-1, 3, 3) + t
    np.testing.assert_allclose(ws.triangles, expected, atol=1e-5)
    assert {"main", "main-node", "child", "child-node"} <= set(ws.cameras)
    got = ws.camera("main")
    np.testing.assert_allclose(got.eye, cam.eye, atol=1e-12)
    np.testing.assert_allclose(got.rotation, cam.rotation, atol=1e-9)
    assert (got.near, got.far) == (0.1, 50.0) and got.fov == pytest.approx(45.0)
    child = ws.camera("child", far=30.0)
    # the child looks along its parent's −z turned 90° about y: world −x, from (10, 0, 0) + R·(0, 0, 2)
    np.testing.assert_allclose(child.eye, [12.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(child.rotation[2], [-1.0, 0.0, 0.0], atol=1e-12)
    assert child.far == 30.0 and child.fov == pytest.approx(np.degrees(1.0))
    with pytest.raises(ValueError, match="camera 'nope' is not in .*main"):
        ws.camera("nope")


def test_degenerate_skipped_and_bad_files(tmp_path):
    p = tmp_path / "d.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 2 2 3\n")
    ws = loading.load_scene(p)
    assert len(ws.triangles) == 1 and ws.degenerate == 2
    (tmp_path / "e.glb").write_bytes(b"")
    with pytest.raises(ValueError, match="is empty"):
        loading.load_scene(tmp_path / "e.glb")
    (tmp_path / "g.glb").write_bytes(b"not a gltf file at all")
    with pytest.raises(ValueError, match="cannot parse"):
        loading.load_scene(tmp_path / "g.glb")
    (tmp_path / "n.obj").write_text("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(ValueError, match="non-finite"):
        loading.load_scene(tmp_path / "n.obj")
    with pytest.raises(ValueError, match="must end in"):
        loading.load_scene(tmp_path / "x.fbx")


def test_without_trimesh(tmp_path, monkeypatch):
    monkeypatch.setattr(loading, "_trimesh", lambda: None)
    (tmp_path / "a.glb").write_bytes(b"glTF....")
    with pytest.raises(ValueError, match=r'needs trimesh: pip install "\.\[scenes\]"'):
        loading.load_scene(tmp_path / "a.glb")
    p = tmp_path / "q.obj"
    p.write_text("v 0 0 1\nv 1 0 1\nv 1 1 1\nf 1 2 3\n")
    assert loading.load_scene(p).triangles.shape == (1, 3, 3)


def test_camera_conversion():
    cam = camera.look_at("1,2,3", "1,2,13", up="0,5,0", near=0.5, far=20.0, fov=50.0)
    np.testing.assert_allclose(cam.rotation, [[-1, 0, 0], [0, 1, 0], [0, 0, 1]], atol=1e-15)  # looking along +z: right is −x
    p = np.random.default_rng(0).normal(size=(5, 3))
    e = cam.to_eye(p)
    np.testing.assert_allclose(np.linalg.norm(e - cam.to_eye(np.zeros(3)), axis=1), np.linalg.norm(p, axis=1))  # distances kept
    assert np.linalg.det(cam.rotation) == pytest.approx(-1.0)  # right-handed world → left-handed eye space
    with pytest.raises(ValueError, match="eye must differ from target"):
        camera.look_at("1,1,1", "1,1,1")
    with pytest.raises(ValueError, match="up must not be parallel"):
        camera.look_at("0,0,0", "0,3,0", up="0,1,0")
    with pytest.raises(ValueError, match="light direction must be a non-zero"):
        cam.direction_to_eye("0,0,0")
    with pytest.raises(ValueError, match="eye must be three"):
        camera.look_at("1,2", "0,0,0")


def test_procedural_city_seeded_and_glb(tmp_path):
    a, b = procedural.city(20_000, seed=5), procedural.city(20_000, seed=5)
    np.testing.assert_array_equal(a, b)
    assert abs(len(a) - 20_000) < 200 and not np.array_equal(a, procedural.city(20_000, seed=6))
    assert procedural.main(["--triangles", "2000", "--out", str(tmp_path / "c.glb")]) == 0
    ws = loading.load_scene(tmp_path / "c.glb")
    assert abs(len(ws.triangles) - 2000) < 50 and "street" in ws.cameras
    with pytest.raises(ValueError, match="triangles must be"):
        procedural.city(10)
