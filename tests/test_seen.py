"""What the user sees wrong, predicted without a browser (aliasing.frames.seen, check --seen).

* The synthesized read-back against the engines' own (three.js, Babylon.js, PlayCanvas in the
  system Chromium, one small frame each): the same pixels drawn and the same cascades, and the
  prediction's acne and lost shadow from the synthesized read-back within 0.01 of the prediction
  from the browser's read-back.
* The wrong-pixel measure on the reference scene, each engine at its defaults and at bias 0, with
  a large normal offset, and over map sizes: monotone where the engines' rules say so, and its
  acne + false shadow and lost shadow the frames' own acne and lost shadow of the same frame.
* Bad input refused by name (Hypothesis), the check's ``seen`` block and ``--seen`` flag, and
  ``import aliasing.check`` loading no browser.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from aliasing import setups  # noqa: E402
from aliasing.check import check  # noqa: E402
from aliasing.frames import scenes  # noqa: E402
from aliasing.frames.seen import reference_scene, synthetic_frame, wrong_pixels  # noqa: E402
from aliasing.frames.seen.synth import eye_geometry  # noqa: E402
from aliasing.frames.seen.wrong import reach_px  # noqa: E402
from aliasing.tune.pixels import significant  # noqa: E402
from conftest import need_frames  # noqa: E402

HEIGHT = 144
CAMERA = dict(near=0.5, far=60.0, fov=50.0, aspect=16 / 9)
CAMERA_SPEC = f"near=0.5,far=60,fov=50,aspect=16:9,height={HEIGHT}"
SUN = "35@30"
#: the synthesized read-back's prediction against the browser read-back's: acne and lost shadow [fraction]
AGREE = 0.01
#: the measure's cameras: the user's image 720 rows, sampled at 72
USER = "near=0.5,far=60,fov=50,aspect=16:9,height=720"
FAST = dict(height=72, suns=2)


# ----------------------------------------------------------------------------- against the engines' own read-back

@pytest.fixture(scope="module")
def chromium():
    need_frames("threejs", "three.js")
    from aliasing.frames import browser as fb

    with fb.Browser(timeout=120) as b:
        yield b


@pytest.mark.parametrize("engine, given", [("threejs", {"material.shadowSide": "FrontSide"}), ("babylon", {}),
                                           ("playcanvas", {"numCascades": 4, "shadowBias": 0.0})])
def test_synthetic_readback_predicts_what_the_browser_readback_does(chromium, engine, given):
    need_frames(engine, engine)
    from aliasing.frames.run import frame_setup

    fs = scenes.frame_scene("boxes", **CAMERA, boxes=30, ground_cells=8)
    s = setups.build(engine, given, CAMERA_SPEC, SUN)
    real = frame_setup(chromium, s, fs)
    syn = synthetic_frame(s, fs)
    rb, sy = real.readback, syn.readback
    assert rb.shadow.shape == sy.shadow.shape
    assert np.mean(rb.drawn == sy.drawn) >= 0.999
    both = rb.drawn & sy.drawn
    assert np.mean(rb.cascade[both] == sy.cascade[both]) >= 0.999
    depth = -fs.camera.to_eye(sy.position[both])[:, 2]
    assert np.percentile(np.linalg.norm(rb.position[both] - sy.position[both], axis=-1) / depth, 99) < 0.005  # the GPU's interpolation
    # the rest of the difference is the positions': with the browser's, the synthesized matrices and cascades predict what it does
    from dataclasses import replace

    from aliasing.frames.run import pixel_masks, predict_readback, shading
    from aliasing.frames.seen.synth import engine_settings

    model, settings = engine_settings(s)
    cam_fs = replace(fs, camera=replace(fs.camera, aspect=rb.shadow.shape[1] / rb.shadow.shape[0]))
    mixed = replace(sy, position=rb.position, normal=rb.normal, shadow=np.where(rb.drawn, 1.0, np.nan))
    sun = scenes.sun_direction(35.0, 30.0, fs.camera)
    pred, ref, _, _ = predict_readback(model, settings, cam_fs, sun, mixed)
    got = shading(pred.factor, ref, *pixel_masks(cam_fs, sun, mixed, ref), mixed.drawn)
    for key in ("acne", "lost_shadow"):
        assert abs(got[key] - real.report["predicted"][key]) <= 0.002, (key, got, real.report["predicted"])
    for key in ("acne", "lost_shadow"):
        assert abs(syn.report["predicted"][key] - real.report["predicted"][key]) <= AGREE, (key, syn.report["predicted"], real.report["predicted"])
        assert abs(syn.report["predicted"][key] - real.report["measured"][key]) <= 0.03, (key, syn.report["predicted"], real.report["measured"])


# ----------------------------------------------------------------------------- the measure on the reference scene

def _wrong(engine: str, given: dict, camera: str = USER, sun="30..50", **kw):
    return wrong_pixels(setups.build(engine, given, camera, sun), **{**FAST, **kw})


@pytest.mark.parametrize("engine, zero", [("babylon", {"bias": 0.0}), ("playcanvas", {"shadowBias": 0.0}),
                                          ("threejs", {"material.shadowSide": "FrontSide"})])
def test_bias_zero_acnes_more_than_the_defaults(engine, zero):
    """Each engine at its defaults (its own map sizes and cascades) and without its depth bias.  three.js's CSM
    takes shadowBias 0 as its default 1e-6 (``data.shadowBias || 0.000001``) and casts back faces: its
    'no bias' case is front faces casting at that bias."""
    base, bare = _wrong(engine, {}, suns=1), _wrong(engine, zero, suns=1)
    lit_shaded = [w.total["acne"] + w.total["false_shadow"] for w in (base, bare)]  # near a shadow's edge acne counts as false shadow
    assert lit_shaded[1] >= lit_shaded[0] and bare.total["acne"] >= base.total["acne"]
    if engine != "babylon":  # Babylon.js's default bias, 5e-5, shades within the noise of none on this sample (44.5 % against 45.3 %)
        assert significant(lit_shaded[0], lit_shaded[1], base.total["pixels"])
    for w in (base, bare):
        t = w.total
        assert math.isclose(t["wrong"], t["acne"] + t["false_shadow"] + t["lost_shadow"], rel_tol=1e-12)
        assert all(0 <= t[k] <= 1 for k in ("acne", "false_shadow", "lost_shadow", "wrong", "blocky"))
        assert sum(c["pixels"] for c in w.cascades) == t["pixels"] > 0


@pytest.mark.parametrize("engine, small, normal", [("babylon", {"mapSize": 512, "numCascades": 2}, {"normalBias": 2.0}),
                                                   ("playcanvas", {"shadowResolution": 512}, {"normalOffsetBias": 2.0}),
                                                   ("threejs", {"shadowMapSize": 512, "cascades": 2}, {"shadow.normalBias": 2.0})])
def test_a_large_normal_offset_loses_shadow(engine, small, normal):
    base, offset = _wrong(engine, small), _wrong(engine, {**small, **normal})
    assert offset.total["lost_shadow"] > base.total["lost_shadow"] + 0.005
    assert offset.total["acne"] <= base.total["acne"]


def test_threejs_shadow_bias_zero_is_its_default_and_a_negative_bias_removes_front_face_acne():
    front = {"material.shadowSide": "FrontSide", "shadowMapSize": 512, "cascades": 2}
    assert _wrong("threejs", {"shadowBias": 0.0, "cascades": 2, "shadowMapSize": 512}).total == _wrong("threejs", {"cascades": 2, "shadowMapSize": 512}).total
    assert _wrong("threejs", {**front, "shadowBias": -0.002}).total["acne"] < 0.5 * _wrong("threejs", front).total["acne"]


def test_blockiness_falls_as_the_map_grows():
    camera = "near=0.5,far=60,fov=50,aspect=16:9,height=120"  # a small image: its pixels are as large as the texels of these maps
    three = [_wrong("threejs", {"cascades": 2, "shadowMapSize": r}, camera).total["blocky"] for r in (256, 512, 1024)]
    assert three[0] > three[1] > three[2]
    pc = [_wrong("playcanvas", {"shadowResolution": r}, camera).total["blocky"] for r in (256, 512)]
    assert pc[0] > pc[1]


def test_acne_false_and_lost_are_the_frames_measures_of_the_same_frame():
    """One sun, the sample's height as the camera's: acne + false shadow counts the lit receivers shaded
    (the frames' acne), lost shadow the exactly shadowed pixels shaded lit (the frames' lost shadow)."""
    s = setups.build("playcanvas", {"numCascades": 2, "shadowBias": 0.0}, "near=0.5,far=60,fov=50,aspect=16:9,height=72", 40)
    w = wrong_pixels(s, height=72, suns=1)
    r = synthetic_frame(s, reference_scene(0.5, 60.0, 50.0, 16 / 9))
    rec, shadowed = r.report["details"]["receivers"], w.total["pixels"] - r.report["details"]["receivers"]
    t = w.total
    assert (t["acne"] + t["false_shadow"]) * t["pixels"] == pytest.approx(r.report["predicted"]["acne"] * rec, abs=1e-6)
    assert t["lost_shadow"] * t["pixels"] == pytest.approx(r.report["predicted"]["lost_shadow"] * shadowed, abs=1e-6)
    assert t["acne"] > 0 and t["false_shadow"] > 0


def test_pixels_beyond_the_shadow_distance_lose_their_shadow():
    """Beyond the shadow distance nothing is shaded: the ``beyond`` row's lost shadow is every exactly shadowed pixel there.

    (Its total need not exceed a longer distance's: one cascade stretched over 60 m loses more shadow near the eye, where
    most pixels are, than one over 8 m loses beyond it.)"""
    from aliasing.frames.compare import MIN_COS
    from aliasing.frames.scenes import sun_direction
    from aliasing.frames.seen import count, sample
    from aliasing.frames.seen.synth import engine_settings, predict_synthetic

    s = setups.build("playcanvas", {"shadowDistance": 8.0}, USER, 40)
    where = sample(s, height=72, suns=1)
    beyond = count(s, where).cascades[-1]
    assert beyond["cascade"] == "beyond" and beyond["acne"] == 0 and beyond["false_shadow"] == 0
    model, settings = engine_settings(s)
    sun = sun_direction(40.0, s.sun.azimuth, where.scene.camera)
    r = predict_synthetic(model, settings, where.scene, sun, where.geometry, "playcanvas")
    facing = where.geometry[2] & ((np.nan_to_num(where.geometry[1]) @ sun) > MIN_COS)
    there = facing & (r.prediction.cascade < 0)
    assert beyond["pixels"] == there.sum() > 0 and (r.prediction.factor[there] == 1).all()
    assert beyond["lost_shadow"] == (there & ~r.reference).sum() / there.sum() > 0


def test_the_reference_scene_is_deterministic_with_casters_near_and_far():
    a, b = reference_scene(0.1, 500.0, 50.0, 16 / 9), reference_scene(0.1, 500.0, 50.0, 16 / 9)
    assert np.array_equal(a.triangles, b.triangles)
    depth = -a.triangles[a.ground:, :, 2].mean(axis=1)
    size = np.ptp(a.triangles[a.ground:].reshape(-1, 12, 3, 3), axis=(1, 2)).max(axis=-1)
    assert depth.min() < 5 and depth.max() > 100 and size.max() > 20 * size.min()


def test_the_frames_guide_table_of_the_reference_scene():
    """docs/guide/frames.rst's table: the check's default camera, sun 15–60°, each engine's defaults and changes, at its printed digits."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "docs" / "guide" / "frames.rst").read_text(encoding="utf-8")
    table = text[text.index("   * - three.js, defaults (back faces cast)"):text.index("Every cascade is blocky there")]
    printed = [[c.strip()[2:] for c in row.strip().split("\n")[1:]] for row in table.split("   * - ")[1:]]
    rows = [("threejs", {}), ("threejs", {"material.shadowSide": "FrontSide"}),
            ("threejs", {"material.shadowSide": "FrontSide", "shadow.normalBias": 2.0}), ("babylon", {}), ("babylon", {"bias": 0.0}),
            ("babylon", {"normalBias": 2.0}), ("playcanvas", {}), ("playcanvas", {"shadowBias": 0.0}), ("playcanvas", {"normalOffsetBias": 2.0})]

    def fmt(v):
        return "0" if v == 0 else (f"{100 * v:.2f} %" if v < 0.01 else f"{100 * v:.1f} %")

    got = []
    for engine, given in rows:
        total = check(setups.build(engine, given, "near=0.1,far=500,fov=50,aspect=16:9,height=1080", "15..60"), wrong=True).seen["total"]
        assert total["blocky"] == 1.0  # "every cascade is blocky there"
        got.append([fmt(total[k]) for k in ("acne", "false_shadow", "lost_shadow", "wrong")])
    assert got == printed


# ----------------------------------------------------------------------------- bad input, check and the command line

BAD = settings(max_examples=15, deadline=None, suppress_health_check=list(HealthCheck))
SETUP = setups.build("playcanvas", {"shadowResolution": 256}, "near=0.5,far=60,fov=50,aspect=16:9,height=72", 40)
bad_count = st.one_of(st.integers(-10**6, 0), st.floats(allow_nan=True, allow_infinity=True).filter(lambda v: not float(v).is_integer()),
                      st.sampled_from(["3", None, True, 1e400, [3]]))


@BAD
@given(value=bad_count, name=st.sampled_from(["height", "suns"]))
def test_wrong_pixels_refuses_bad_sizes_by_name(value, name):
    with pytest.raises(ValueError, match=name):
        wrong_pixels(SETUP, **{name: value})


@BAD
@given(value=st.one_of(st.integers(), st.text(max_size=5), st.none(), st.lists(st.floats(), max_size=3)))
def test_bad_setup_and_scene_are_refused_by_name(value):
    with pytest.raises(ValueError, match="setup"):
        wrong_pixels(value)
    if value is not None:
        with pytest.raises(ValueError, match="scene"):
            wrong_pixels(SETUP, scene=value if not isinstance(value, str) else value + "!nofile")


@BAD
@given(width=st.one_of(st.integers(-5, 0), st.integers(4097, 10**6)), side=st.sampled_from(["up", "", "fronts"]))
def test_eye_geometry_and_reach_refuse_by_name(width, side):
    fs = scenes.frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=1, ground_cells=1)
    with pytest.raises(ValueError, match="width"):
        eye_geometry(fs, width, 8)
    with pytest.raises(ValueError, match="side"):
        eye_geometry(fs, 16, 8, side)
    with pytest.raises(ValueError, match="taps"):
        reach_px(width, np.ones(2), np.ones(2))


@settings(max_examples=8, deadline=None, suppress_health_check=list(HealthCheck))
@given(engine=st.sampled_from(["threejs", "babylon", "playcanvas"]), low=st.floats(1.0, 90.0), span=st.floats(0.0, 60.0),
       azimuth=st.floats(-360.0, 360.0), near=st.floats(0.05, 2.0), ratio=st.floats(5.0, 5000.0))
def test_any_valid_sun_band_and_camera_give_fractions_and_strict_json(engine, low, span, azimuth, near, ratio):
    small = {"threejs": {"shadowMapSize": 256, "cascades": 2}, "babylon": {"mapSize": 256, "numCascades": 2},
             "playcanvas": {"shadowResolution": 256}}[engine]
    far = max(near * ratio, 5.0)  # the ground, 1 below the eye, enters the view at a depth of 1 / tan 25° = 2.1
    s = setups.build(engine, small, f"near={near!r},far={far!r},fov=50,aspect=16:9,height=480", f"{low!r}..{min(90.0, low + span)!r}@{azimuth!r}")
    w = wrong_pixels(s, height=24, suns=2)
    json.dumps(w.to_dict(), allow_nan=False)
    t = w.total
    assert all(t[k] is None or 0 <= t[k] <= 1 for k in ("acne", "false_shadow", "lost_shadow", "wrong", "blocky"))
    if t["pixels"] == 0:  # a sun too low for any surface to face it (cos <= 0.05): nothing to count
        assert t["acne"] is t["wrong"] is None
    else:
        assert math.isclose(t["wrong"], t["acne"] + t["false_shadow"] + t["lost_shadow"], rel_tol=1e-12, abs_tol=1e-15)


def test_a_view_that_draws_nothing_is_refused_by_name():
    with pytest.raises(ValueError, match="scene: nothing is drawn"):
        wrong_pixels(setups.build("playcanvas", {"shadowResolution": 256}, "near=0.25,far=1.25,fov=50,aspect=16:9,height=480", 30))


def test_engines_without_predicted_matrices_are_refused_or_reported():
    bevy = setups.build("bevy", {}, USER, 30)
    with pytest.raises(ValueError, match="engine must be one of threejs, babylon, playcanvas, godot"):
        wrong_pixels(bevy)
    assert "not_predicted" in check(bevy, wrong=True).to_dict()["seen"]
    with pytest.raises(ValueError, match="wrong"):
        check(bevy, wrong="yes")
    godot = setups.build("godot", {}, USER, 30)  # Forward+, Godot's desktop default: its Compatibility renderer is predicted
    with pytest.raises(ValueError, match="rendering/renderer/rendering_method must be gl_compatibility"):
        wrong_pixels(godot)
    assert check(godot, wrong=True).to_dict()["seen"]["not_predicted"].startswith("rendering/renderer/rendering_method")


def test_check_reports_the_measure_per_cascade_only_when_asked():
    s = setups.build("threejs", {"cascades": 2, "shadowMapSize": 512}, USER, 40)
    assert "seen" not in check(s).to_dict()
    r = check(s, wrong=True)
    seen = json.loads(r.to_json())["seen"]
    assert [c["cascade"] for c in seen["cascades"]] == [0, 1, "beyond"] and seen["units"]["memory"] == "bytes"
    assert seen["total"]["pixels"] > 0 and "what you see wrong, predicted" in r.text()


def test_cli_check_seen_json_and_table(capsys):
    from aliasing.cli import main

    args = ["check", "--engine", "playcanvas", "--set", "shadowResolution=512", "--camera", "near=0.5,far=60,fov=50,aspect=16:9,height=720", "--sun", "40"]
    assert main(args + ["--seen", "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(f"{c} in the JSON"))
    assert out["seen"]["total"]["wrong"] is not None
    assert main(args + ["--no-seen", "--format", "json"]) == 0
    assert "seen" not in json.loads(capsys.readouterr().out)
    assert main(args + ["--seen"]) == 0
    assert "[fraction of the pixels facing the sun]" in capsys.readouterr().out


def test_importing_check_loads_no_browser():
    code = "import sys, aliasing.check; print(any(m.startswith(('playwright', 'aliasing.frames.browser')) for m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
