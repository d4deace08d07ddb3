"""Shimmer of a still world (aliasing.temporal): parsers, lattices, the measure against its prediction."""

from __future__ import annotations

import contextlib
import io
import json
import os
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import cli
from aliasing.temporal import fits, measure, paths, points, predict

FINITE = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)


# ---------------------------------------------------------------- parsers (generated input)

@settings(max_examples=60, deadline=None)
@given(st.tuples(FINITE, FINITE, FINITE).filter(lambda v: max(map(abs, v)) > 0))
def test_translate_roundtrip(step):
    m = paths.parse_motion("translate:" + ",".join(repr(v) for v in step))
    assert m.kind == "translate" and m.step.tolist() == list(step)


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(["rotate:yaw,", "rotate:pitch,", "zoom:", "sun:", "ROTATE:Yaw,"]), st.floats(-90, 90, allow_nan=False).filter(lambda v: v != 0))
def test_angle_motions_roundtrip(prefix, deg):
    m = paths.parse_motion(prefix + repr(deg))
    assert m.step.tolist() == [deg]


@settings(max_examples=80, deadline=None)
@given(st.text(max_size=30))
def test_any_text_is_a_motion_or_a_named_refusal(text):
    try:
        m = paths.parse_motion(text)
    except ValueError as exc:
        assert "motion" in str(exc)
    else:
        assert m.kind in paths.MOTIONS and np.isfinite(m.step).all()


@pytest.mark.parametrize("text, words", [
    ("shake:1", "unknown kind"), ("translate:1,2", "three numbers"), ("translate:nan,0,0", "finite"), ("translate:0,0,inf", "finite"),
    ("translate:0,0,0", "zero"), ("rotate:roll,1", "yaw|pitch"), ("rotate:yaw,0", "non-zero"), ("sun:1e9", "at most"), ("zoom", "needs"),
    ("zoom:x", "number"), ("sun:1,2", "one number"),
])
def test_bad_motions(text, words):
    with pytest.raises(ValueError, match=words):
        paths.parse_motion(text)


@settings(max_examples=60, deadline=None)
@given(st.one_of(st.integers(-10**12, 10**12), st.floats(allow_nan=True, allow_infinity=True), st.booleans()))
def test_frames_in_range_or_refused(n):
    ok = not isinstance(n, bool) and math.isfinite(n) and float(n).is_integer() and 2 <= n <= paths.MAX_FRAMES
    if ok:
        assert paths.check_frames(n) == int(n)
    else:
        with pytest.raises(ValueError, match="frames"):
            paths.check_frames(n)


def test_zoom_leaving_the_field_of_view_is_refused():
    with pytest.raises(ValueError, match="leaves"):
        paths.frames(paths.parse_motion("zoom:1"), [0, 0, 0], np.eye(3), 60.0, [0, 1, 0], 200)


def test_rotation_keeps_the_frame_orthonormal():
    _, rots, _, _ = paths.frames(paths.parse_motion("rotate:pitch,7"), [0, 0, 0], np.eye(3), 60.0, [0, 1, 0], 5)
    assert np.allclose(np.einsum("fij,fkj->fik", rots, rots), np.eye(3))
    assert np.isclose(rots[4, 2] @ np.array([0, 0, 1.0]), np.cos(np.deg2rad(28)))


def test_sizes_refused_before_work():
    with pytest.raises(ValueError, match="frames × points"):
        measure.check_size(paths.MAX_FRAMES, 1000)


# ---------------------------------------------------------------- lattices

@pytest.fixture(scope="module")
def scene():
    w = points.world("boxes", boxes=150, seed=3)
    return w, points.sample(w, 96)


def _poses(w, motion, n):
    return paths.frames(paths.parse_motion(motion), w.camera.eye, w.camera.rotation, w.camera.fov, w.light, n)


def test_snapped_lattice_is_world_fixed_and_tight_is_not(scene):
    w, _ = scene
    poses = _poses(w, "translate:0.037,0,0", 6)
    snapped = fits.plan("csm-stable:log:k=4:fit=sphere:snap=origin", w, poses, 128)
    assert np.all(snapped.tx == snapped.tx[0])  # the side does not move with the camera
    assert np.allclose(snapped.x0 / snapped.tx, np.round(snapped.x0 / snapped.tx), atol=1e-6)  # corners on whole texels
    shift, scale = predict.grid_motion(snapped)
    assert np.allclose(shift, np.round(shift), atol=1e-6) and np.allclose(scale, 0)
    tight = fits.plan("csm:log:k=4", w, poses, 128)
    shift, _ = predict.grid_motion(tight)
    assert np.abs(shift - np.round(shift)).max() > 0.01  # sub-texel phase shifts


def test_sphere_fit_keeps_its_scale_under_rotation_and_zoom_rescales(scene):
    w, _ = scene
    rot = fits.plan("csm-stable:log:k=4:fit=sphere", w, _poses(w, "rotate:yaw,1", 4), 128)
    assert np.allclose(predict.grid_motion(rot)[1], 0, atol=1e-12)
    tight = fits.plan("csm:log:k=4", w, _poses(w, "rotate:yaw,1", 4), 128)
    assert np.abs(predict.grid_motion(tight)[1]).max() > 1e-4
    zoom = fits.plan("csm-stable:log:k=4:fit=sphere", w, _poses(w, "zoom:0.5", 4), 128)
    assert np.all(predict.grid_motion(zoom)[1] > 0)  # a wider view: larger texels


def test_limits_without_a_grid_are_refused(scene):
    w, _ = scene
    with pytest.raises(ValueError, match="without a texel grid"):
        fits.plan("matched", w, _poses(w, "sun:1", 2), 64)
    with pytest.raises(ValueError, match="scheme family"):
        fits.plan("pcf:log", w, _poses(w, "sun:1", 2), 64)


# ---------------------------------------------------------------- the measure and its prediction

def test_snapped_fit_under_sideways_translation_shows_no_shimmer_tight_does(scene):
    w, pts = scene
    snapped = measure.shimmer(w, pts, "csm-stable:log:k=4:fit=sphere:snap=origin", "translate:0.037,0,0", 12, res=128)
    seen = (snapped.part[1:] >= 0) & (snapped.part[:-1] >= 0)
    assert not np.any(seen & (snapped.part[1:] != snapped.part[:-1]))  # sideways: no point changes cascade
    assert seen.sum() > 1000
    assert snapped.flips.sum() == 0 and np.all(snapped.predicted == 0)
    tight = measure.shimmer(w, pts, "csm:log:k=4", "translate:0.037,0,0", 12, res=128)
    assert tight.flips.sum() > 50 and np.all(tight.predicted > 0)


def test_flips_from_cascade_changes_are_reported_apart(scene):
    w, pts = scene
    r = measure.shimmer(w, pts, "csm-stable:log:k=4:fit=sphere:snap=origin", "translate:0,0,0.4", 12, res=128)
    row = r.row()
    assert r.changed_flips.sum() > 0  # moving along the view carries points across cascade boundaries
    assert r.same_fraction.max() == 0 and row["map_change_share"] == 1.0  # the stable grid itself never flips a point


# Tolerance: the prediction and the measure agree within three bootstrap standard errors.  The
# error is that of the point sample (which points happen to lie near shadow edges decides both
# the measured flips and the edge densities the prediction uses; predict.agreement resamples
# the points); it is required to be below 0.2 so that the check can fail (a prediction off by
# a factor 1.6 or more fails it).
AGREEMENT = [
    ("csm:log:k=4", "translate:0.037,0,0"),
    ("csm:log:k=4", "rotate:yaw,0.2"),
    ("csm-stable:log:k=4:fit=tight:snap=origin", "rotate:pitch,0.15"),
    ("csm-stable:log:k=4:fit=sphere:snap=origin", "zoom:0.2"),
    ("sdsm:k=4", "translate:0,0,0.1"),
]


def assert_agreement(w, pts, spec, motion):
    r = measure.shimmer(w, pts, spec, motion, 16, res=128)
    assert r.flips.sum() > 100
    assert r.ratio_se < 0.2
    assert abs(r.ratio - 1) <= 3 * r.ratio_se, (r.ratio, r.ratio_se)


@pytest.mark.parametrize("spec, motion", AGREEMENT)
def test_measure_and_prediction_agree(scene, spec, motion):
    assert_agreement(*scene, spec, motion)


def test_prediction_scales_with_the_edge_density(scene):
    # the agreement test can fail: doubling the densities doubles the prediction
    w, pts = scene
    r = measure.shimmer(w, pts, "csm:log:k=4", "translate:0.037,0,0", 8, res=128)
    poses = _poses(w, "translate:0.037,0,0", 8)
    lat = fits.plan("csm:log:k=4", w, poses, 128)
    delta = predict.displacement(lat, r.part, predict.light_plane(pts.position, lat))
    grp = r.group
    small = predict.predicted(delta * 1e-3, grp, r.g)
    assert small.max() > 0 and np.allclose(predict.predicted(delta * 1e-3, grp, 2 * r.g), 2 * small, rtol=1e-3)


def test_turning_sun_has_a_rate_per_degree_and_no_grid_prediction(scene):
    w, pts = scene
    r = measure.shimmer(w, pts, "csm-stable:log:k=4:fit=sphere:snap=origin", "sun:0.25", 6, res=128)
    row = r.row()
    assert row["flip_fraction"] > 0 and row["per_degree"] == pytest.approx(row["flip_fraction"] / 0.25)
    assert row["predicted_fraction"] is None and np.isnan(r.predicted).all()


def test_vsm_pages_are_world_fixed_maps_are_reused(scene):
    w, pts = scene
    short = measure.shimmer(w, pts, "vsm:bias=0", "translate:0.05,0,0", 3, res=128, shifts=2)
    long = measure.shimmer(w, pts, "vsm:bias=0", "translate:0.05,0,0", 9, res=128, shifts=2)
    assert long.drawn == short.drawn  # one window per level for the whole sequence
    assert long.same_fraction.max() == 0  # texels never move: only level changes can flip


# ---------------------------------------------------------------- command line

def test_cli_json(capsys):
    code = cli.main(["shimmer", "--schemes", "csm:log:k=3,csm-stable:log:k=3:fit=sphere:snap=origin", "--motion", "translate:0.05,0,0", "--frames", "4",
                     "--image-res", "48", "--shadow-res", "64", "--format", "json"])
    rows = json.loads(capsys.readouterr().out)
    assert code == 0 and [r["scheme"] for r in rows] == ["csm:log:k=3", "csm-stable:log:k=3:fit=sphere:snap=origin"]
    assert rows[1]["flip_fraction"] == 0.0 and rows[0]["flip_fraction"] >= 0.0


def test_cli_backend_gl_flips_as_numpy(capsys):
    """--backend gl draws the same maps as numpy (to edge texels: the flips agree within a point or two)."""
    from aliasing.raster.draw import gl

    if not gl.available() and os.environ.get("CI") != "true":
        pytest.skip(f"the gl backend cannot draw here: {gl._setup()[1]}")
    argv = ["shimmer", "--schemes", "csm:log:k=3,csm-stable:log:k=3:fit=sphere:snap=origin", "--motion", "translate:0.05,0,0", "--frames", "6",
            "--image-res", "48", "--shadow-res", "128", "--format", "json"]
    rows = {}
    for backend in ("numpy", "gl"):
        assert cli.main(argv + ["--backend", backend]) == 0
        rows[backend] = json.loads(capsys.readouterr().out)
    points = 48 * 48
    for a, b in zip(rows["numpy"], rows["gl"]):
        assert abs(a["flip_fraction"] - b["flip_fraction"]) * points <= 2, (a, b)
    assert rows["gl"][1]["flip_fraction"] == 0.0


@pytest.mark.parametrize("args, words", [
    (["--motion", "wobble:1"], "unknown kind"),
    (["--motion", "translate:nan,0,0"], "finite"),
    (["--frames", "0"], "frames"),
    (["--frames", "1e9"], "frames"),
    (["--frames", "90000"], "frames × points"),
    (["--schemes", "csm:nosuch"], "split method"),
    (["--schemes", "warp:log"], "scheme family"),
    (["--scene", "/nonexistent.glb"], "scene"),
    (["--backend", "vulkan"], "backend"),
])
def test_cli_bad_input_one_line_exit_2(capsys, args, words):
    base = {"--schemes": "csm:log:k=3", "--motion": "translate:0.05,0,0", "--frames": "3"}
    for key, value in zip(args[::2], args[1::2]):
        base[key] = value
    argv = ["shimmer"] + [x for kv in base.items() for x in kv] + ["--image-res", "32", "--shadow-res", "32"]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


# ---------------------------------------------------------------- fuzz: exit 0, or exit 2 with one line

_WORDS = {
    "--schemes": ["csm:log:k=2", "csm-stable:log:k=2:fit=sphere:snap=origin", "csm-stable:godot", "sdsm:k=2", "vsm:bias=2", "matched", "csm:log:k=0", "csm:log:k=nan",
                  "csm-stable:log:fit=oval", "vsm", "", ",", "csm:log:k=2,,sdsm:k=2"],
    "--motion": ["translate:0.1,0,0", "rotate:yaw,1", "rotate:pitch,-1", "zoom:0.5", "zoom:-50", "sun:2", "sun:nan", "translate:inf,0,0", "translate:1e400,0,0", "rotate:roll,1", "zoom:", ""],
    "--frames": ["2", "3", "0", "1", "-1", "2.5", "nan", "inf", "1e400", "x", ""],
    "--scene": ["boxes", "city.glb", "", "boxes "],
    "--near": ["0.5", "1", "0", "-1", "nan", "1e400"], "--far": ["50", "100", "1", "nan", "inf"], "--fov": ["60", "0", "180", "nan", "1e400"],
    "--light-dir": ["-1,2,0.6", "0,1,0", "0,0,0", "nan,1,0", "1,2", "a,b,c"], "--eye": ["0,0,0", "1,2", "nan,0,0"], "--target": ["0,0,1", "0,0,0"],
    "--image-res": ["16", "24", "0", "-3", "x"], "--shadow-res": ["16", "32", "0", "99999"], "--fps": ["60", "0", "-1", "nan", "inf"],
    "--unit": ["m", "cm", "parsec"], "--format": ["table", "csv", "json", "xml"],
    "--aspect": ["1", "2", "0.5", "1.7778", "0", "-1", "nan", "inf", "1e400"],
}


@settings(max_examples=40, deadline=None)
@given(st.dictionaries(st.sampled_from(sorted(_WORDS)), st.integers(0, 99), max_size=7), st.text(max_size=8))
def test_shimmer_fuzz(picks, garbage):
    base = {"--schemes": "csm:log:k=2", "--motion": "translate:0.1,0,0", "--frames": "2", "--image-res": "16", "--shadow-res": "16"}
    for key, i in picks.items():
        words = _WORDS[key] + ([garbage] if key not in ("--image-res", "--shadow-res", "--frames") else [])
        base[key] = words[i % len(words)]
    argv = ["shimmer"] + [f"{k}={v}" for k, v in base.items()]
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = cli.main(argv)
        except SystemExit as exc:  # argparse: a non-number for a typed option
            code = exc.code
    text = err.getvalue()
    assert code in (0, 2), (argv, text)
    assert "Traceback" not in text
    if code == 2 and not text.startswith("usage:"):
        assert text.count("\n") == 1, (argv, text)


# ---------------------------------------------------------------- explorer

def test_explorer_plays_a_path():
    pytest.importorskip("ipywidgets")
    from aliasing import explore

    e = explore.shimmer(scheme="csm:log:k=3", frames=5, frame=3, image_res=48, shadow_res=128)
    assert e.error is None and e.controls["frame"].max == 4 and e.play.max == 4
    d = e.data
    assert d["frame"] == 3 and d["flip_fraction"].shape == (4,)
    _, pts, r, _ = __import__("aliasing.explore._shimmer", fromlist=["_sequence"])._sequence("boxes", "csm:log:k=3", "translate:0.05,0,0", 5, 48, 128)
    assert int(d["flipped"].sum()) == int(r.flips[2])  # the flips between frames 2 and 3
    assert e.set_state({"frame": 1}) and e.data["frame"] == 1
    assert not e.set_state({"motion": "wobble:1"}) and "unknown kind" in e.error


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-3, 3), st.floats(-3, 3)), min_size=1, max_size=20), st.lists(st.floats(0, 50), min_size=4, max_size=4))
def test_flip_probability_is_a_probability_growing_with_the_motion(deltas, rates):
    d = np.array(deltas)[None]
    g = np.array([rates])
    grp = np.zeros(d.shape[1], np.int64)
    p = predict.flip_probability(d, grp, g)
    assert np.all((p >= 0) & (p <= 0.5))
    assert np.all(predict.flip_probability(2 * d, grp, g) >= p - 1e-12)


@pytest.mark.parametrize("call, words", [
    (lambda: predict.flip_probability(np.zeros((1, 3, 3)), np.zeros(3, np.int64), np.ones((1, 2))), "delta"),
    (lambda: predict.flip_probability(np.zeros((1, 3, 2)), np.full(3, 5), np.ones((1, 2))), "group"),
    (lambda: predict.flip_probability(np.zeros((1, 3, 2)), np.zeros(3, np.int64), -np.ones((1, 2))), "g must"),
    (lambda: paths.rotation([0, 0, 0], 10.0), "axis"),
    (lambda: fits.eye_coordinates(np.zeros((4, 2)), np.zeros((1, 3)), np.eye(3)[None]), "positions"),
    (lambda: measure.check_size(0, 10), "frames"),
])
def test_public_functions_name_the_bad_parameter(call, words):
    with pytest.raises(ValueError, match=words):
        call()
