"""Rendering and measuring schemes on your own scene (aliasing.pictures.scenerender, cascades, render CLI)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from aliasing import cli, partitioning
from aliasing import pictures
from aliasing.raster import map_set
from aliasing.raster import scenes
from aliasing.raster.scenes import camera, procedural
from aliasing.raster.draw import cascades
from aliasing.raster.validate import scene as scene_validate
from aliasing.pictures import scenerender
from aliasing.raster.scenes import Scene

trimesh = pytest.importorskip("trimesh")

LIGHT_WORLD = np.array([0.3, 1.0, 0.2])


@pytest.fixture(scope="module")
def world():
    return procedural.city(2000, seed=2, size=60.0)


@pytest.fixture(scope="module")
def glb(tmp_path_factory, world):
    path = tmp_path_factory.mktemp("scene") / "city.glb"
    cam = camera.look_at([-40.0, 6.0, -35.0], [0.0, 0.0, 0.0], near=0.5, far=90.0, fov=60.0)
    procedural.to_glb(world, path, {"view": cam})
    return path


def test_world_render_equals_eye_space_render(world):
    """Eye at (40, 3, 5) looking along world −x, up +y: eye space is x_e = 5 − z, y_e = y − 3, z_e = 40 − x
    (written out here, not through the camera module); the light turns the same way."""
    st = scenes.setup(world, eye="40,3,5", target="0,3,5", near=0.5, far=90.0, fov=60.0, light_dir=LIGHT_WORLD)
    by_hand = np.stack([5.0 - world[..., 2], world[..., 1] - 3.0, 40.0 - world[..., 0]], axis=-1)
    light_eye = np.array([-LIGHT_WORLD[2], LIGHT_WORLD[1], -LIGHT_WORLD[0]])
    np.testing.assert_array_equal(st.scene.triangles, by_hand)
    np.testing.assert_allclose(st.light, light_eye / np.linalg.norm(light_eye), atol=1e-15)
    for scheme in ("ZP2+P", "LogP"):
        got = scenerender.render(st, [scheme], budget=96**2, image_res=64)[0].view
        want = pictures.view(0.5, 90.0, 60.0, light_eye, scheme, image_res=64, budget=96**2, scene=Scene(by_hand, np.full(len(by_hand), -1)))
        assert (got.triangle >= 0).sum() > 1000
        for name in ("triangle", "partition", "lit"):
            np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)
        np.testing.assert_allclose(np.nan_to_num(got.s), np.nan_to_num(want.s), atol=1e-12)
        np.testing.assert_allclose(np.nan_to_num(got.t), np.nan_to_num(want.t), atol=1e-12)
        np.testing.assert_array_equal(pictures.shade(got), pictures.shade(want))


def test_preset_cascades_match_aliasing_splits(glb, capsys):
    """three.js CSM and Unreal (overlapping cascades) in the render: split positions as `aliasing splits` prints them."""
    st = scenes.setup(str(glb), camera="view")
    for preset in ("threejs-csm", "unreal"):
        assert cli.main(["splits", "--method", preset, "--near", "0.5", "--far", "90", "--format", "json"]) == 0
        rows = [r for r in json.loads(capsys.readouterr().out) if r["partition"] != "all"]
        r = scenerender.render(st, ["P"], splits=preset, budget=128**2, image_res=48)[0]
        cas = r.stats["cascades"]
        assert [c["near"] for c in cas] == [row["near"] for row in rows]
        assert [c["far"] for c in cas] == [row["far"] for row in rows]
        edges = partitioning.split_distances(preset, 0.5, 90.0)
        np.testing.assert_array_equal(r.cascades.maps.edges, edges)
        # every pixel is shaded by the cascade holding its eye depth
        hit = r.view.partition >= 0
        depth = r.view.position[hit][:, 2]
        np.testing.assert_array_equal(r.view.partition[hit], np.clip(np.searchsorted(edges, depth, side="right") - 1, 0, len(edges) - 2))
        assert len(set(r.view.partition[hit].tolist())) >= 2


def test_budget_shares_and_measured_within_bound(glb):
    st = scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3")
    budget = 256**2
    rs = scenerender.render(st, ["Standard", "ZP3+P", "FPc+LogP"], budget=budget, image_res=64)
    rs += scenerender.render(st, ["LogP"], splits="practical", k=3, lam=0.7, allocation="error", budget=budget, image_res=64)
    for r in rs:
        s = r.stats
        assert s["pixels_measured"] > 500 and 0 <= s["frac_le_1"] <= 1
        assert s["p50"] <= s["p90"] <= s["p99"] <= s["max"]
        # the measured perspective error stays within the analytic maximum of its maps (Lloyd 2006 eqs. 7-10)
        assert s["max"] <= s["analytic_max"] * (1 + scene_validate.TOLERANCE), r.label  # finite differences: 1e-3 (as measure states)
        assert sum(c["side"] ** 2 for c in s["cascades"]) <= budget
    err = rs[-1]
    sides = np.array([c["side"] for c in err.stats["cascades"]], float)
    sigma = err.cascades.M_x * err.cascades.M_z / (err.cascades.M_x * err.cascades.M_z).sum()
    np.testing.assert_array_equal(sides, np.floor(np.sqrt(sigma * budget)))  # Lloyd 2007 eq. 83, square maps
    assert [c["side"] for c in rs[1].stats["cascades"]] == [147] * 3  # equal: ⌊√(256²/3)⌋


def test_cascade_set_without_splits_is_map_set():
    cs = cascades.cascade_set(1.0, 100.0, 60.0, "gamma:60@azimuth:30", "ZP3+LogP")
    ms = map_set(1.0, 100.0, 60.0, "gamma:60@azimuth:30", "ZP3+LogP")
    np.testing.assert_array_equal(cs.maps.edges, ms.edges)
    with pytest.raises(ValueError, match="single-map warp"):
        cascades.cascade_set(1.0, 100.0, 60.0, "overhead", "ZP3+P", splits="log", k=3)
    with pytest.raises(ValueError, match="split method"):
        cascades.cascade_set(1.0, 100.0, 60.0, "overhead", "P", splits="nope")


def _render(args, capsys):
    code = cli.main(["render", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_render_cli_scene(glb, tmp_path, capsys):
    base = ["--scene", str(glb), "--camera", "view", "--light-dir=-1,0.8,0.3", "--res", "96", "--image-res", "40"]
    for what in ("shadows", "grid", "error", "cdf"):
        png = tmp_path / f"{what}.png"
        code, out, err = _render([*base, "--scheme", "Standard,ZP2+P,LogP", "--what", what, "--out", str(png)], capsys)
        assert code == 0, err
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and "ZP2+P" in out and "frac_le_1" in out
    code, out, err = _render([*base, "--scheme", "P", "--splits", "unity-urp", "--allocation", "error", "--format", "json"], capsys)
    assert code == 0, err
    rep = json.loads(out)
    assert rep["splits"] == "unity-urp" and rep["schemes"][0]["scheme"] == "unity-urp+P" and len(rep["schemes"][0]["cascades"]) == 4
    assert rep["camera"]["name"] == "view" and rep["degenerate_skipped"] == 0
    # eye/target: the same camera as the file's
    code, out2, _ = _render(["--scene", str(glb), "--eye=-40,6,-35", "--target", "0,0,0", "--near", "0.5", "--far", "90",
                             "--light-dir=-1,0.8,0.3", "--res", "96", "--image-res", "40", "--scheme", "P", "--splits", "unity-urp",
                             "--allocation", "error", "--format", "json"], capsys)
    rep2 = json.loads(out2)
    assert code == 0 and rep2["schemes"][0]["p99"] == pytest.approx(rep["schemes"][0]["p99"], rel=1e-6)


@pytest.mark.parametrize("args,message", [
    (["--camera", "nope"], "camera 'nope' is not in"),
    (["--eye", "1,2,3", "--target", "1,2,3"], "eye must differ from target"),
    (["--eye", "0,5,0", "--target", "0,0,0"], "up must not be parallel"),
    (["--eye=-40,6,-35", "--target=-80,6,-70"], "no triangles in front of the camera"),
    (["--camera", "view", "--light-dir", "0,0,0"], "light direction must be a non-zero"),
    (["--camera", "view", "--splits", "nope"], "split method"),
    (["--camera", "view", "--lambda", "0.5"], "need --splits"),
])
def test_render_cli_bad_input_one_line(glb, tmp_path, capsys, args, message):
    code, _, err = _render(["--scene", str(glb), *args, "--out", str(tmp_path / "x.png"), "--image-res", "16", "--res", "32"], capsys)
    assert code == 2 and err.count("\n") == 1 and message in err, err


def test_render_cli_bad_files(tmp_path, capsys):
    (tmp_path / "empty.glb").write_bytes(b"")
    (tmp_path / "junk.glb").write_bytes(b"glTF\x02\x00\x00\x00junk")
    (tmp_path / "nan.obj").write_text("v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    for name, message in (("empty.glb", "is empty"), ("junk.glb", "cannot parse"), ("nan.obj", "non-finite")):
        code, _, err = _render(["--scene", str(tmp_path / name), "--eye", "0,0,5", "--target", "0,0,0", "--out", str(tmp_path / "x.png")], capsys)
        assert code == 2 and err.count("\n") == 1 and message in err, err


def test_degenerate_counted_in_report(tmp_path, capsys):
    p = tmp_path / "d.obj"
    p.write_text("v -50 0 -50\nv 50 0 -50\nv 50 0 50\nv -50 0 50\nv 0 0 0\nf 1 2 3\nf 1 3 4\nf 1 1 5\n")
    code, out, err = _render(["--scene", str(p), "--eye", "0,2,-10", "--target", "0,0,10", "--image-res", "24", "--res", "32", "--out", str(tmp_path / "d.png")], capsys)
    assert code == 0, err
    assert "skipped 1 degenerate triangles" in out


def test_readme_scene_commands(tmp_path, monkeypatch, capsys):
    """The README's "Your own scene" commands run as written, in one folder (the GLB first)."""
    import re
    import shlex
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    section = readme.split("### Your own scene", 1)[1].split("\n## ", 1)[0]
    lines = [ln.strip() for block in re.findall(r"```bash\n(.*?)```", section, flags=re.S) for ln in block.splitlines() if ln.strip()]
    assert lines[0].startswith("python -m aliasing.raster.scenes.procedural") and len(lines) >= 4
    monkeypatch.chdir(tmp_path)
    for line in lines:
        argv = shlex.split(line)
        if argv[0] == "python":
            assert procedural.main(argv[3:]) == 0, line
        else:
            assert argv[0] == "aliasing" and cli.main(argv[1:]) == 0, line
    capsys.readouterr()
    assert (tmp_path / "city.glb").exists() and (tmp_path / "shadows.png").exists() and (tmp_path / "grid.png").exists()
