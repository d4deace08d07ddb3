"""A loaded scene's camera with an aspect: ``aliasing validate --scene --aspect`` and ``aliasing render --scene --aspect``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import View, cli
from aliasing.raster import scenes
from aliasing.raster.draw.cascades import cascade_set
from aliasing.pictures import scenerender
from aliasing.raster.scenes import camera, procedural
from aliasing.raster.validate import scene as scene_validate

trimesh = pytest.importorskip("trimesh")

SCENE = ("--camera", "view", "--light-dir=-1,0.8,0.3")


@pytest.fixture(scope="module")
def glb(tmp_path_factory):
    path = tmp_path_factory.mktemp("ascene") / "city.glb"
    cam = camera.look_at([-40.0, 6.0, -35.0], [0.0, 0.0, 0.0], near=0.5, far=90.0, fov=60.0)
    procedural.to_glb(procedural.city(2000, seed=2, size=60.0), path, {"view": cam})
    return path


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# ----------------------------------------------------------------------------- aspect 1: the square camera, byte for byte


@pytest.mark.parametrize("fmt", ["json", "text"])
def test_validate_scene_aspect_one_is_byte_identical(glb, capsys, fmt):
    base = ("validate", "--scheme", "ZP3+LogP", "--scene", str(glb), *SCENE, "--res", "64", "--format", fmt)
    code, plain, err = run(capsys, *base)
    assert code == 0 and err == ""
    code, one, _ = run(capsys, *base, "--aspect", "1")
    assert code == 0 and one == plain and "aspect" not in plain


@pytest.mark.parametrize("where", ["scene", "builtin"])
def test_render_aspect_one_is_byte_identical(glb, tmp_path, capsys, where):
    base = ("render", "--scheme", "Standard,ZP2+LogP", "--res", "128", "--image-res", "48", "--what", "error", "--format", "json")
    base += ("--scene", str(glb), *SCENE) if where == "scene" else ("--f-over-n", "50")
    plain, one = tmp_path / "plain.png", tmp_path / "one.png"
    code, out_plain, err = run(capsys, *base, "--out", str(plain))
    assert code == 0 and err == ""
    code, out_one, _ = run(capsys, *base, "--aspect", "1", "--out", str(one))
    assert code == 0 and out_one == out_plain and "aspect" not in out_plain
    assert one.read_bytes() == plain.read_bytes()


# ----------------------------------------------------------------------------- aspect 2: a wider camera


def test_setup_gives_the_camera_the_aspect_and_the_eye_pass_widens():
    """A far wall ahead fills the image: the pixel columns of the measured eye pass span
    x/z = (2c − 1)·aspect·tan θ_y, the rows (2c − 1)·tan θ_y (written out here)."""
    wall = np.array([[[-1e4, -1e4, 500.0], [1e4, -1e4, 500.0], [0.0, 1e4, 500.0]]])
    res = 16
    c = (np.arange(res) + 0.5) / res
    t = math.tan(math.radians(30.0))
    for aspect in (1.0, 2.0, 0.5):
        stp = scenes.setup(wall, eye="0,0,0", target="0,0,1", near=1.0, far=1000.0, fov=60.0, light="overhead", aspect=aspect)
        assert stp.camera.aspect == aspect and stp.camera.view == View(1.0, 1000.0, 60.0, aspect)
        eb, pos, _, _ = scene_validate.measurable_pixels(stp, res, lambda pos, hit: np.zeros(hit.shape, np.int64))
        x_over_z = eb.position[0, :, 0] / eb.position[0, :, 2]
        np.testing.assert_allclose(np.abs(x_over_z), np.abs((2 * c - 1) * aspect * t), rtol=1e-12)
        np.testing.assert_allclose(eb.position[:, 0, 1] / eb.position[:, 0, 2], (2 * c - 1) * t, rtol=1e-12)


def test_wider_camera_sees_more_of_the_city(glb):
    square = scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3")
    wide = scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3", aspect=2.0)
    t = math.tan(math.radians(30.0))
    seen = []
    for stp in (square, wide):
        eb, _, _, _ = scene_validate.measurable_pixels(stp, 96, lambda pos, hit: np.zeros(hit.shape, np.int64))
        hit = eb.triangle >= 0
        side = np.abs(eb.position[..., 0] / eb.position[..., 2])
        seen.append((len(np.unique(eb.triangle[hit])), float(np.nanmax(side)), set(np.unique(eb.triangle[hit & (side > t)]).tolist())))
    (count_sq, ext_sq, out_sq), (count_wide, ext_wide, out_wide) = seen
    assert ext_sq <= t < ext_wide and not out_sq  # the city reaches beyond the square view's sides
    assert count_wide > count_sq and len(out_wide) > 10  # triangles seen only by the wider camera


def test_validate_scene_at_aspect_two_uses_the_wide_bounds(glb):
    wide = scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3", aspect=2.0)
    r = scene_validate.validate_scene(wide, "ZP3+LogP", res=128)
    cs = cascade_set(View(0.5, 90.0, 60.0, 2.0), wide.light, "ZP3+LogP")
    assert r["aspect"] == 2.0 and r["M_x"] == cs.M_x.tolist() and r["M_z"] == cs.M_z.tolist()
    square = scene_validate.validate_scene(scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3"), "ZP3+LogP", res=128)
    assert all(w > s for w, s in zip(r["M_x"], square["M_x"]))  # the light's view of a wider frustum
    assert r["passed"] and r["max_ratio"] <= 1 + r["tolerance"] and sum(r["pixels"]) > 500


def test_loaded_scene_renders_as_the_builtin_scene_at_aspect_two():
    """The built-in scene (the one-case path of render --aspect) loaded as world triangles with a camera at
    the origin looking along +z: eye space mirrors x (written out here), so the world copy has x negated."""
    builtin = scenerender.builtin(1.0, 40.0, 60.0, "gamma:60@azimuth:30", aspect=2.0)
    world = builtin.scene.triangles * [-1.0, 1.0, 1.0]
    loaded = scenes.setup(world, eye="0,0,0", target="0,0,1", near=1.0, far=40.0, fov=60.0, light="gamma:60@azimuth:30", aspect=2.0)
    np.testing.assert_array_equal(loaded.scene.triangles, builtin.scene.triangles)
    assert loaded.camera.view == builtin.camera.view
    a, b = (scenerender.render(s, ["ZP2+LogP"], budget=128**2, image_res=48)[0] for s in (loaded, builtin))
    for name in ("triangle", "partition", "lit"):
        np.testing.assert_array_equal(getattr(a.view, name), getattr(b.view, name), err_msg=name)
    np.testing.assert_array_equal(a.error, b.error)
    assert a.stats == b.stats and a.stats["max"] <= a.stats["analytic_max"]


def test_render_cli_scene_at_aspect_two(glb, tmp_path, capsys):
    out = tmp_path / "wide.png"
    code, text, err = run(capsys, "render", "--scheme", "ZP2+LogP", "--scene", str(glb), *SCENE, "--res", "128", "--image-res", "48",
                          "--aspect", "2", "--format", "json", "--out", str(out))
    assert code == 0 and err == ""
    r = json.loads(text)
    assert r["camera"]["aspect"] == 2.0 and r["image_res"] == 48
    from matplotlib.image import imread

    img = imread(out)
    assert img.shape[1] > 1.7 * img.shape[0]  # one wide panel: 96 x 48 square pixels and its title


# ----------------------------------------------------------------------------- bad input


@settings(max_examples=25, deadline=None)
@given(st.one_of(st.floats(max_value=0.0), st.just(float("nan")), st.just(float("inf")), st.just(-float("inf"))))
def test_setup_refuses_a_bad_aspect_naming_it(aspect):
    with pytest.raises(ValueError, match="^aspect"):
        scenes.setup(np.array([[[0.0, 0.0, 5.0], [1.0, 0.0, 5.0], [0.0, 1.0, 5.0]]]), eye="0,0,0", target="0,0,1", aspect=aspect)


@pytest.mark.parametrize("command", ["validate", "render"])
@pytest.mark.parametrize("extra, message", [(("--aspect", "0"), "aspect (image width/height) must be in (0, inf)"),
                                            (("--aspect", "2", "--scheme", "FPc+P"), "aspect must be 1 for face partitions")])
def test_scene_cli_bad_aspect_one_line(glb, tmp_path, capsys, command, extra, message):
    argv = [command, "--scene", str(glb), *SCENE, "--res", "64", *extra]
    if command == "render":
        argv += ["--image-res", "32", "--out", str(tmp_path / "x.png")]
    if "--scheme" not in extra:
        argv += ["--scheme", "P"]
    code, out, err = run(capsys, *argv)
    assert code == 2 and err.count("\n") == 1 and message in err, err
    assert not (tmp_path / "x.png").exists()


def test_camera_with_range_keeps_the_aspect():
    cam = scenes.setup(np.array([[[0.0, 0.0, 5.0], [1.0, 0.0, 5.0], [0.0, 1.0, 5.0]]]), eye="0,0,0", target="0,0,1", aspect=16 / 9).camera
    assert cam.with_range(far=50.0).aspect == 16 / 9


# ----------------------------------------------------------------------------- render --what cdf at aspect != 1


def test_cdf_of_a_wide_image_is_over_its_area(glb, tmp_path, capsys):
    """Every one of the R × R pixels of a wide view covers the same share of the image (aspect : 1 wide),
    so their distribution is the distribution over the image: the same as over the picture's
    2R × R square pixels at aspect 2 (each column shown twice)."""
    from aliasing.pictures.images import cdf

    wide = scenes.setup(str(glb), camera="view", light_dir="-1,0.8,0.3", aspect=2.0)
    r = scenerender.render(wide, ["ZP2+LogP"], budget=128**2, image_res=48)[0]
    xs, ys = cdf(r.error)
    shown_x, shown_y = cdf(np.repeat(r.error, 2, axis=1))
    assert xs.size > 100 and shown_x.size == 2 * xs.size
    np.testing.assert_array_equal(shown_x[1::2], xs)
    np.testing.assert_array_equal(shown_y[1::2], ys)
    fig = scenerender.figure([r], "cdf")
    np.testing.assert_array_equal(fig.axes[0].lines[0].get_xdata(), xs)  # the plotted curve is that distribution
    out = tmp_path / "cdf.png"
    code, text, err = run(capsys, "render", "--scheme", "Standard,ZP2+LogP", "--scene", str(glb), *SCENE, "--res", "128", "--image-res", "48",
                          "--aspect", "2", "--what", "cdf", "--format", "json", "--out", str(out))
    assert code == 0 and err == "" and out.stat().st_size > 0
    got = json.loads(text)["schemes"][1]
    assert got["p50"] == pytest.approx(float(np.percentile(xs, 50)), rel=1e-12) and got["max"] == xs[-1]


def test_engine_schemes_on_a_scene_take_a_wide_camera():
    """aliasing.engines.scene fits the cascades to the wide camera (its aspect, as the eye pass); VSM's
    clipmap takes it too (its LOD from tan θ_x and the image's pixels across)."""
    from aliasing.engines import scene as engine_scene

    world = procedural.city(1000, seed=1, size=40.0)
    wide = scenes.setup(world, eye="-30,6,-25", target="0,0,0", near=0.5, far=60.0, light_dir="-1,0.8,0.3", aspect=2.0)
    for call in (lambda: engine_scene.cascades_on_scene(wide, "log", k=2, res=64), lambda: engine_scene.sdsm_on_scene(wide, res=64)):
        got = call()
        assert got["aspect"] == 2.0 and got["passed"] and sum(got["pixels"]) > 0
    got = engine_scene.vsm_on_scene(wide, res=64)
    assert got["aspect"] == 2.0 and got["passed"] and sum(got["pixels"]) > 0


def test_to_glb_writes_the_camera_aspect(tmp_path):
    import dataclasses
    import struct

    cam = camera.look_at([-40.0, 6.0, -35.0], [0.0, 0.0, 0.0], near=0.5, far=90.0, fov=60.0)
    path = tmp_path / "wide.glb"
    procedural.to_glb(procedural.city(1000, seed=1, size=40.0), path, {"square": cam, "wide": dataclasses.replace(cam, aspect=16 / 9)})
    glb = path.read_bytes()
    length = struct.unpack_from("<I", glb, 12)[0]
    doc = json.loads(glb[20:20 + length])
    assert {c["name"]: c["perspective"]["aspectRatio"] for c in doc["cameras"]} == {"square": 1.0, "wide": 16 / 9}
