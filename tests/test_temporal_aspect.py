"""Shimmer with a non-square camera (aspect = width/height, fov vertical): aspect 1 is the square
sequence bit for bit; at aspect 2 the fits are the engines' wide fits, and what the theory says
about shimmer still holds."""

from __future__ import annotations

import contextlib
import dataclasses
import io
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import View, cli
from aliasing.engines import stable
from aliasing.temporal import fits, measure, paths, points, predict
from test_temporal import AGREEMENT, assert_agreement  # the square test's cases and bound

BAD_ASPECTS = st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([math.nan, math.inf, -math.inf]))


def _fields(r: measure.Shimmer) -> dict:
    out = {f.name: getattr(r, f.name) for f in dataclasses.fields(r) if f.name not in ("seconds", "motion")}
    return {**out, "motion": dataclasses.astuple(r.motion)}


def _poses(w, motion, n):
    return paths.frames(paths.parse_motion(motion), w.camera.eye, w.camera.rotation, w.camera.fov, w.light, n)


@pytest.fixture(scope="module")
def wide():
    """The scene of tests/test_temporal.py's agreement tests, seen by a 2:1 camera."""
    w = points.world("boxes", boxes=150, seed=3, aspect=2.0)
    return w, points.sample(w, 96)


# ---------------------------------------------------------------- aspect 1: the square sequence, bit for bit

@pytest.mark.parametrize("spec, motion", [
    ("csm:log:k=3", "translate:0.037,0,0"),
    ("csm-stable:log:k=3:fit=sphere:snap=origin", "zoom:0.2"),
    ("csm-stable:godot", "rotate:yaw,0.3"),
    ("sdsm:k=3", "translate:0,0,0.1"),
    ("vsm:bias=0", "translate:0.05,0,0"),
])
def test_aspect_one_is_the_sequence_without_it(spec, motion):
    runs = []
    for kw in ({}, {"aspect": 1.0}):
        w = points.world("boxes", boxes=40, seed=1, **kw)
        pts = points.sample(w, 40)
        runs.append((w, pts, measure.shimmer(w, pts, spec, motion, 4, res=64, shifts=2)))
    (w0, p0, r0), (w1, p1, r1) = runs
    assert w0.triangles.tobytes() == w1.triangles.tobytes() and p0.position.tobytes() == p1.position.tobytes()
    a, b = _fields(r0), _fields(r1)
    for key in a:
        np.testing.assert_equal(a[key], b[key], err_msg=key)
    assert r0.row().keys() == r1.row().keys() and "aspect" not in r1.row()


@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_cli_aspect_one_is_byte_identical(monkeypatch, capsys, fmt):
    monkeypatch.setattr(measure.time, "perf_counter", lambda: 0.0)  # the seconds column: the only varying output
    argv = ["shimmer", "--schemes", "csm:log:k=3,csm-stable:log:k=3:fit=sphere:snap=origin,sdsm:k=2", "--motion", "translate:0.05,0,0", "--frames", "3",
            "--image-res", "32", "--shadow-res", "64", "--format", fmt]
    outs = []
    for extra in ([], ["--aspect", "1"], ["--aspect=1.0"]):
        assert cli.main(argv + extra) == 0
        outs.append(capsys.readouterr().out)
    assert outs[0] == outs[1] == outs[2] and "aspect" not in outs[0]


def test_cli_wide_rows_carry_the_aspect(capsys):
    argv = ["shimmer", "--schemes", "csm:log:k=3", "--motion", "translate:0.05,0,0", "--frames", "3", "--image-res", "32", "--shadow-res", "64", "--aspect", "2"]
    assert cli.main(argv + ["--format", "csv"]) == 0
    head, row = capsys.readouterr().out.splitlines()[:2]
    assert head.startswith("scheme,aspect,flip_fraction") and row.startswith("csm:log:k=3,2.0,")
    assert cli.main(argv) == 0
    assert capsys.readouterr().out.split()[:2] == ["scheme", "aspect"]


# ---------------------------------------------------------------- bad aspects: one clear line

@settings(max_examples=25, deadline=None)
@given(BAD_ASPECTS)
def test_bad_aspect_refused_naming_it(aspect):
    with pytest.raises(ValueError, match="^aspect") as info:
        points.world("boxes", boxes=2, aspect=aspect)
    assert "\n" not in str(info.value)


@settings(max_examples=25, deadline=None)
@given(st.one_of(BAD_ASPECTS.map(repr), st.sampled_from(["0", "-2", "nan", "inf", "-inf", "1e400", "-0"])))
def test_bad_aspect_on_the_command_line_one_line(text):
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        code = cli.main(["shimmer", "--schemes", "csm:log:k=2", "--motion", "translate:0.1,0,0", "--frames", "2", "--image-res", "16", "--shadow-res", "16", f"--aspect={text}"])
    assert code == 2 and out.getvalue() == "", text
    assert err.getvalue().count("\n") == 1 and "aspect" in err.getvalue() and "Traceback" not in err.getvalue(), (text, err.getvalue())


def test_vsm_takes_a_wide_camera(capsys):
    """At the same viewport width a 2:1 view has pixels twice as large (tan θ_x = 2 tan θ_y): B′ grows by
    one octave, so every level's distance bound comes twice as near the camera."""
    code = cli.main(["shimmer", "--schemes", "csm:log:k=2,vsm:bias=0", "--motion", "translate:0.1,0,0", "--frames", "2", "--image-res", "16", "--shadow-res", "16", "--aspect", "2"])
    out, err = capsys.readouterr()
    assert code == 0 and err == "" and "vsm:bias=0" in out
    lats = []
    for aspect in (1.0, 2.0):
        w = points.world("boxes", boxes=40, seed=1, aspect=aspect)
        pts = points.sample(w, 32)
        lats.append(fits.plan("vsm:bias=0", w, _poses(w, "translate:0.05,0,0", 3), 64, positions=pts.position, image_res=96))
    sq, wide = lats
    assert wide.aspect == 2.0 and sq.aspect == 1.0
    np.testing.assert_allclose(wide.hi[:, :-1], sq.hi[:, :-1] / 2, rtol=1e-12)  # B′ unclamped here: log2(0.5·tanθ_x·16384/96) > 0
    np.testing.assert_array_equal(wide.hi[:, -1], sq.hi[:, -1])  # the last level's radius is the engine's, whatever the view


def test_points_of_another_aspect_are_refused():
    w1, w2 = points.world("boxes", boxes=5), points.world("boxes", boxes=5, aspect=2.0)
    with pytest.raises(ValueError, match="aspect"):
        measure.shimmer(w2, points.sample(w1, 16), "csm:log:k=2", "translate:0.1,0,0", 2, res=32)


# ---------------------------------------------------------------- aspect 2: the wide view through every step

def test_wide_points_fill_the_wide_view_and_every_one_has_a_map(wide):
    w, pts = wide
    assert pts.aspect == 2.0
    eye = w.camera.to_eye(pts.position)
    t = w.camera.view.tan_theta
    assert np.all(np.abs(eye[:, 0]) <= 2 * t * eye[:, 2] * (1 + 1e-9)) and np.all(np.abs(eye[:, 1]) <= t * eye[:, 2] * (1 + 1e-9))
    assert np.mean(np.abs(eye[:, 0]) > t * eye[:, 2]) > 0.3  # about half the image lies beyond the square view
    lat = fits.plan("csm:log:k=4", w, _poses(w, "translate:0.037,0,0", 2), 128)
    part = fits.assign(lat, fits.eye_coordinates(pts.position, *_poses(w, "translate:0.037,0,0", 2)[:2]), np.full(2, w.camera.fov), w.camera.near, w.camera.far)
    assert lat.aspect == 2.0 and np.all(part[0] >= 0)  # frame 0 sees every point it sampled


@pytest.mark.parametrize("fit", ["tight", "sphere", "diagonal", "centroid"])
def test_wide_fits_are_the_engines_fits_at_that_aspect(wide, fit):
    """Each frame's map sides equal aliasing.engines.stable.evaluate's at aspect 2, and are wider than at aspect 1."""
    w, _ = wide
    poses = _poses(w, "rotate:yaw,2", 3)
    res = 128
    lat = fits.plan(f"csm-stable:log:k=4:fit={fit}", w, poses, res)
    square = points.World(w.triangles, dataclasses.replace(w.camera, aspect=1.0), w.light, w.name)
    lat1 = fits.plan(f"csm-stable:log:k=4:fit={fit}", square, poses, res)
    cam = w.camera
    # the tight box is taken in the world-fixed light frame, the engines' in each frame's eye light frame: the same
    # frame only where the camera has not turned (frame 0); the other fits' sides do not depend on the frame
    for f in ([0] if fit == "tight" else range(3)):
        light_e = poses[1][f] @ poses[3][f]
        r = stable.evaluate("log", cam.near, cam.far, cam.fov, light_e[None], k=4, fit=fit, aspect=2.0, resolution=res)
        np.testing.assert_allclose(lat.tx[f] * res, r.width_x[0], rtol=1e-9)
        np.testing.assert_allclose(lat.ty[f] * res, r.width_y[0], rtol=1e-9)
    assert np.all(lat.tx > lat1.tx)
    if fit == "sphere":
        (a, b), _ = stable.cascade_ranges("log", cam.near, cam.far, 4)
        np.testing.assert_allclose(lat.tx[0] * res, 2 * stable.sphere_radius(a, b, cam.fov, 2.0), rtol=1e-12)


@pytest.mark.parametrize("fov", [30.0, 60.0])
def test_wide_sphere_centre_is_equidistant_from_the_wide_corners(fov):
    """The sphere fit's centre on the view axis is as far from the wide slice's near corners as from its far ones, or at b
    where the far ring alone decides (at 60° and aspect 2 for every slice: c² = tan²θ_x + tan²θ_y > 1)."""
    w = points.world("boxes", boxes=5, fov=fov, aspect=2.0)
    cam = w.camera
    (a, b), _ = stable.cascade_ranges("log", cam.near, cam.far, 4)
    lat = fits.plan("csm-stable:log:k=4:fit=sphere", w, _poses(w, "translate:0.01,0,0", 2), 128)
    B = lat.basis[0]
    centre = np.stack([lat.x0[0] + lat.tx[0] * 64, lat.y0[0] + lat.ty[0] * 64], -1)  # the unsnapped map's centre (K, 2)
    axis = np.array([cam.rotation[2] @ B[0], cam.rotation[2] @ B[2]])
    zc = ((centre - np.array([cam.eye @ B[0], cam.eye @ B[2]])) @ axis) / (axis @ axis)  # its depth on the view axis
    corners = View(a, b, cam.fov, 2.0).slice_vertices()  # (K, 8, 3) eye space, the wide slice
    d = np.linalg.norm(corners - np.stack([np.zeros_like(zc), np.zeros_like(zc), zc], -1)[:, None], axis=-1)
    inner = zc < b * (1 - 1e-9)
    assert inner.all() if fov == 30.0 else not inner.any()
    np.testing.assert_allclose(d[inner, 0], d[inner, 4], rtol=1e-9)  # equidistant where the centre lies inside the slice
    np.testing.assert_allclose(zc[~inner], b[~inner], rtol=1e-9)
    np.testing.assert_allclose(d.max(-1), stable.sphere_radius(a, b, cam.fov, 2.0), rtol=1e-9)


# ---------------------------------------------------------------- aspect 2: what the theory predicts

def test_wide_snapped_fit_under_sideways_translation_shows_no_shimmer_tight_does(wide):
    """Snapping moves the grid by whole texels and the side does not depend on the view direction, at any aspect."""
    w, pts = wide
    snapped = measure.shimmer(w, pts, "csm-stable:log:k=4:fit=sphere:snap=origin", "translate:0.037,0,0", 12, res=128)
    seen = (snapped.part[1:] >= 0) & (snapped.part[:-1] >= 0)
    assert seen.sum() > 1000 and not np.any(seen & (snapped.part[1:] != snapped.part[:-1]))
    assert snapped.flips.sum() == 0 and np.all(snapped.predicted == 0)
    shift, scale = snapped.shift, snapped.scale
    assert np.allclose(shift, np.round(shift), atol=1e-6) and np.allclose(scale, 0)
    tight = measure.shimmer(w, pts, "csm:log:k=4", "translate:0.037,0,0", 12, res=128)
    assert tight.flips.sum() > 50 and np.all(tight.predicted > 0)


def test_wide_tight_fit_moves_its_grid_by_the_step_over_its_wider_texel(wide):
    """Under sideways translation a tight fit's box follows the camera: its corner moves by the step's light-plane
    projection, a phase shift of step/t texels, t the (wider) texel of the wide slice."""
    w, _ = wide
    step = 0.037
    poses = _poses(w, f"translate:{step},0,0", 4)
    lat = fits.plan("csm:log:k=4", w, poses, 128)
    shift, scale = predict.grid_motion(lat)
    move = poses[0][1] - poses[0][0]
    expect = np.stack([(move @ lat.basis[0, 0]) / lat.tx[:-1], (move @ lat.basis[0, 2]) / lat.ty[:-1]], -1)  # (F − 1, K, 2)
    np.testing.assert_allclose(shift, expect, rtol=1e-6, atol=1e-9)
    assert np.allclose(scale, 0, atol=1e-12)
    square = points.World(w.triangles, dataclasses.replace(w.camera, aspect=1.0), w.light, w.name)
    shift1, _ = predict.grid_motion(fits.plan("csm:log:k=4", square, poses, 128))
    assert np.all(np.abs(shift[..., 0]) < np.abs(shift1[..., 0]))  # the same step is a smaller phase of a wider texel


# The bound of tests/test_temporal.py's agreement test, unchanged: the prediction and the measure
# agree within three bootstrap standard errors, the error below 0.2 (so that the check can fail).
@pytest.mark.parametrize("spec, motion", AGREEMENT)
def test_wide_measure_and_prediction_agree(wide, spec, motion):
    assert_agreement(*wide, spec, motion)


# ---------------------------------------------------------------- the edge length on aspect : 1 pixels

@pytest.mark.parametrize("aspect", [0.5, 1.0, 2.0, 3.0])
def test_edge_length_of_a_disc_in_pixel_heights(aspect):
    """Cauchy–Crofton on pixels aspect : 1 wide: a disc of radius ρ pixel heights has perimeter 2πρ (within 3 %)."""
    r, rho = 240, 50.0
    rows, cols = np.mgrid[0:r, 0:r]
    pix = np.stack([rows.ravel(), cols.ravel()], -1)
    pts = points.Points(np.zeros((r * r, 3)), np.zeros((r * r, 3)), pix, np.zeros(r * r, np.int64), r, aspect)
    lit = (aspect * (pix[:, 1] - r / 2)) ** 2 + (pix[:, 0] - r / 2) ** 2 < rho**2
    assert measure.edge_length(pts, lit, np.ones(r * r, bool)) == pytest.approx(2 * np.pi * rho, rel=0.03)


def test_a_handful_of_flips_gives_an_unbounded_error_without_a_warning(recwarn):
    """Few flips (here 1 at aspect 2): a bootstrap replicate may draw none of them, so the ratio's error is unbounded (inf, shown "-")."""
    w = points.world("boxes", boxes=60, seed=2, aspect=2.0)
    r = measure.shimmer(w, points.sample(w, 48), "csm-stable:log:k=4:fit=tight:snap=origin", "rotate:pitch,0.15", 5, res=64, shifts=3)
    assert r.flips.sum() == 1 and r.ratio_se == np.inf and r.row()["ratio_se"] is None
    assert not [x for x in recwarn if issubclass(x.category, RuntimeWarning)]
