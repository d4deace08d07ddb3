"""Godot's Compatibility renderer in the wrong-pixel objective (aliasing.frames.seen, aliasing tune) and in ``tune --frames``.

* The synthesized frame: its shape, Godot's split-local matrices and split selection, and its prediction exactly
  ``Godot.predict(..., matrices="model")`` on the same pixels (the matrices Godot uploads equal the model's,
  docs/ERRATA.md F13).
* Godot's factor through maps drawn only where read (``split_maps(sampled=True)``) against whole maps, bit for bit:
  Hard, PCF_5 and PCF_13, 16-bit depth on and off, 2 and 4 splits, blended splits.
* ``pixels.why_not``: None with ``rendering_method=gl_compatibility``, a reason naming the setting for Forward+
  and for ``light_angular_distance``; the filter lever; a small ``pixels.refine`` that lowers the wrong pixels.
* In Godot's own frames (the official web build in the system Chromium; skipped with one line without it): the
  synthesized read-back predicts what the browser's does, and ``tune --frames 2`` reports measured beside predicted.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import setups
from aliasing.cli import main
from aliasing.frames import predict, scenes, seen
from aliasing.frames.models import Godot
from aliasing.frames.models.godot import PCF, godot_factor, split_maps
from aliasing.frames.run import frame_inputs, predict_readback
from aliasing.frames.scenes import sun_direction
from aliasing.frames.seen.synth import VISIBLE, engine_settings, eye_geometry, synthetic_frame, synthetic_readback
from aliasing.setups import godot as profile
from aliasing.tune import pixels
from aliasing.tune.measure import limits
from conftest import need_frames

CAMERA = "near=0.5,far=60,fov=50,aspect=16:9,height=720"
COMPAT = {profile.RENDERER: "gl_compatibility"}
FOUR, TWO = "SHADOW_PARALLEL_4_SPLITS", "SHADOW_PARALLEL_2_SPLITS"


def _setup(given: dict, camera: str = CAMERA, sun="30..50"):
    return setups.build("godot", {**COMPAT, **given}, camera, sun)


@pytest.mark.parametrize("mode, blend", [(FOUR, False), (TWO, True)])
def test_the_synthesized_frame_is_godots_prediction_through_the_models_matrices(mode, blend):
    s = _setup({"directional_shadow_mode": mode, "directional_shadow_blend_splits": blend, profile.SIZE: 1024},
               "near=0.5,far=60,fov=50,aspect=16:9,height=72", "35@30")
    fs = scenes.frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=12, ground_cells=2)
    r = synthetic_frame(s, fs)
    k = profile.SPLITS[mode]
    assert r.readback.shadow.shape == r.prediction.factor.shape == (72, 128)
    assert sorted(r.report["predicted"]) == ["acne", "gap_px", "lost_shadow", "px_per_texel"] and len(r.prediction.sides) == k
    g, st_ = engine_settings(s)
    assert isinstance(g, Godot) and VISIBLE["godot"](st_) == "front"
    setup, fs2, sun = frame_inputs(s, fs)
    rb = synthetic_readback(g, st_, fs2, sun, eye_geometry(fs2, setup.camera.width, setup.camera.height), "godot")
    assert np.array_equal(rb.matrices, g.matrices(st_, fs2.camera, sun))           # the split-local matrices Godot.predict draws through
    depth = np.where(rb.drawn, fs2.camera.to_eye(np.nan_to_num(rb.position))[..., 2], np.nan)
    assert np.array_equal(rb.cascade, g.select(st_, g.edges(st_, fs2.camera)[1:], depth))
    res, rows = profile.layout(1024, k)[:2]
    assert rb.sizes.tolist() == [[res, rows]] * k
    engine, ref_e = g.predict(st_, fs2, sun, rb)                                   # the read-back's matrices
    model, ref_m = g.predict(st_, fs2, sun, rb, matrices="model")
    assert np.array_equal(engine.factor, model.factor, equal_nan=True) and np.array_equal(ref_e, ref_m)
    pred, ref, predicts, why = predict_readback(g, st_, fs2, sun, rb)               # what synthetic_frame measures
    assert predicts and why is None and np.array_equal(pred.factor, model.factor, equal_nan=True)
    assert np.array_equal(r.prediction.factor, model.factor, equal_nan=True)
    drawn = rb.drawn
    assert drawn.any() and np.all((model.factor[drawn] >= 0) & (model.factor[drawn] <= 1))


def _frame(given: dict, elevation: float = 35.0, height: int = 72):
    s = _setup(given, sun=elevation)
    where = seen.sample(s, height=height, suns=1)
    g, st_ = engine_settings(s)
    fs = where.scene
    sun = sun_direction(elevation, 0.0, fs.camera)
    pos, nrm, drawn = where.geometry
    depth = np.where(drawn, fs.camera.to_eye(np.nan_to_num(pos))[..., 2], np.nan)
    return g, st_, fs, sun, np.nan_to_num(pos), np.nan_to_num(nrm), depth


@pytest.mark.parametrize("mode, quality, bits16, blend", [(FOUR, 0, True, False), (FOUR, 2, True, False), (FOUR, 4, True, False),
                                                          (FOUR, 2, False, False), (TWO, 2, True, False), (TWO, 5, False, False),
                                                          (TWO, 1, True, True), (FOUR, 3, True, True)])
def test_godots_factor_through_sampled_maps_is_the_whole_maps(mode, quality, bits16, blend):
    size = 2048
    g, s, fs, sun, pts, nrm, depth = _frame({"directional_shadow_mode": mode, profile.QUALITY: quality, profile.BITS: bits16,
                                             "directional_shadow_blend_splits": blend, profile.SIZE: size,
                                             "shadow_bias": 0.05, "shadow_normal_bias": 0.5})
    splits, mats = g.transforms(s, fs.camera, sun), g.matrices(s, fs.camera, sun)
    edges = g.edges(s, fs.camera)
    sel = g.select(s, edges[1:], depth)
    cast = fs.triangles[predict.casting(fs.triangles, sun, g.cast_side(s))]

    def factor(maps):
        return godot_factor(maps, mats, sel, depth, pts, nrm, sun, s, edges=edges, radii=[sp.radius for sp in splits])

    whole = factor(split_maps(cast, splits, mats, s, sampled=False))
    sampled = split_maps(cast, splits, mats, s)
    got = predict.gathered(lambda: factor(sampled), sampled)
    assert np.array_equal(got, whole)
    res = g.resolution(s)
    assert 0 < sum(m.texels for m in sampled) < len(splits) * res**2 / 10       # a tenth of the texels at most
    exact = factor(split_maps(cast, splits, mats, s, sampled=False, subpixel_bits=None))
    assert np.mean(exact != whole) < 0.05                                        # SwiftShader's 1/16-texel corners move a few pixels


def test_the_quality_table_is_the_measured_one_and_a_filter_lever_under_compatibility_only():
    assert PCF == profile.COMPAT_PCF == {0: 1, 1: 1, 2: 5, 3: 5, 4: 13, 5: 13}   # ERRATA F13: the engine's penumbra by quality
    lever = [t for t in profile.TUNABLE if t.key == profile.QUALITY]
    assert len(lever) == 1 and lever[0].role == "filter" and lever[0].values == (0, 2, 4)
    assert lever[0].active({profile.RENDERER: "gl_compatibility"}) and not lever[0].active({profile.RENDERER: "forward_plus"})


def test_why_not_is_none_for_the_compatibility_renderer_and_names_what_is_not_predicted():
    assert pixels.why_not(_setup({})) is None
    assert pixels.why_not(_setup({"directional_shadow_mode": "SHADOW_ORTHOGONAL"})) is None
    forward = pixels.why_not(setups.build("godot", {}, CAMERA, "30..50"))
    assert forward.startswith("the toolkit does not predict these settings per pixel: rendering/renderer/rendering_method must be "
                              "gl_compatibility") and "'forward_plus'" in forward
    assert "light_angular_distance must be 0" in pixels.why_not(_setup({"light_angular_distance": 2.0}))
    with pytest.raises(ValueError, match="rendering/renderer/rendering_method"):
        seen.wrong_pixels(setups.build("godot", {profile.RENDERER: "mobile"}, CAMERA, 40), height=16, suns=1)


def test_a_small_refine_lowers_godots_wrong_pixels():
    s = _setup({"shadow_bias": 0.0, "shadow_normal_bias": 0.0, profile.SIZE: 2048})       # acne on every lit face
    lim = limits(s)
    keep = frozenset(t.key for t in profile.TUNABLE if t.role != "bias")
    got = pixels.refine(s, s, lim, keep=keep, height=48, suns=1)
    assert got.before["acne"] > 0.3 and got.after["wrong"] < got.before["wrong"] / 5
    assert {k for k, v in got.setup.settings.items() if s.settings[k] != v} <= {"shadow_bias", "shadow_normal_bias"}


@pytest.mark.parametrize("bad, name", [({"sampled": "yes"}, "sampled"), ({"splits": []}, "splits")])
def test_split_maps_refuses_by_name(bad, name):
    g, s, fs, sun, *_ = _frame({}, height=16)
    args = {"splits": g.transforms(s, fs.camera, sun), "sampled": True}
    args.update(bad)
    with pytest.raises(ValueError, match=name):
        split_maps(fs.triangles, args["splits"], g.matrices(s, fs.camera, sun), s, sampled=args["sampled"])


def test_godot_factor_refuses_mismatched_shapes_by_name():
    g, s, fs, sun, pts, nrm, depth = _frame({}, height=16)
    splits, mats = g.transforms(s, fs.camera, sun), g.matrices(s, fs.camera, sun)
    maps = split_maps(fs.triangles, splits, mats, s)
    edges = g.edges(s, fs.camera)
    sel = g.select(s, edges[1:], depth)
    radii = [sp.radius for sp in splits]
    with pytest.raises(ValueError, match="matrices"):
        godot_factor(maps, mats[:2], sel, depth, pts, nrm, sun, s, edges=edges, radii=radii)
    with pytest.raises(ValueError, match="points and normals"):
        godot_factor(maps, mats, sel[:, 1:], depth, pts, nrm, sun, s, edges=edges, radii=radii)
    with pytest.raises(ValueError, match="edges"):
        godot_factor(maps, mats, sel, depth, pts, nrm, sun, s, edges=edges[:-1], radii=radii)


# ----------------------------------------------------------------------------- in Godot's own frames

def test_the_synthesized_readback_predicts_what_godots_readback_does():
    need_frames("godot", "Godot web runtime")
    from aliasing.frames import browser as fb
    from aliasing.frames.run import frame_setup

    spec = "near=0.5,far=60,fov=50,aspect=16:9,height=144"
    s = setups.build("godot@4.6", {**COMPAT, "shadow_bias": 0.0, "shadow_normal_bias": 0.0}, spec, "35@30")   # acne: a hard case
    fs = scenes.frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=30, ground_cells=2)
    with fb.Browser(timeout=120) as b:                       # one browser at a time (Playwright's sync API): closed before tune's
        real = frame_setup(b, s, fs)
    synth = synthetic_frame(s, fs)
    both = real.readback.drawn & synth.readback.drawn
    assert np.mean(real.readback.drawn != synth.readback.drawn) < 0.01              # the same pixels drawn (Godot clips at far)
    assert np.mean(real.readback.cascade[both] == synth.readback.cascade[both]) > 0.99   # Godot's shader's split is the model's
    for key in ("acne", "lost_shadow"):
        assert abs(real.report["predicted"][key] - synth.report["predicted"][key]) <= 0.01, key
        assert abs(real.report["measured"][key] - synth.report["predicted"][key]) <= 0.02, key


def test_tune_frames_2_renders_godots_candidates_and_reports_measured_beside_predicted(capsys, monkeypatch):
    need_frames("godot", "Godot web runtime")
    from aliasing.tune import proof

    monkeypatch.setattr(proof, "HEIGHT", 72)
    monkeypatch.setattr(proof, "SUNS", 1)
    keep = ",".join(t.key for t in profile.TUNABLE if t.role not in ("bias", "filter"))
    argv = ["tune", "--engine", "godot", "--set", f"{profile.RENDERER}=gl_compatibility", "--set", "shadow_normal_bias=0",
            "--camera", CAMERA, "--sun", "30..50", "--keep", keep, "--frames", "2", "--format", "json"]
    assert main(argv) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["objective_kind"] == "wrong" and got["objective_note"] is None
    fr = got["frames"]
    assert len(fr["candidates"]) == 2 and 0 <= fr["pick"] < 2 and fr["height_px"] == 72 and fr["suns"] == 1
    for c in fr["candidates"]:
        m, p = c["measured"], c["predicted"]
        assert m["pixels"] == p["pixels"] > 0 and 0 <= m["wrong"] <= 1 and 0 <= p["wrong"] <= 1
        assert abs(m["wrong"] - p["wrong"]) <= 0.02, (m, p)                       # Godot's frame, predicted
    assert got["settings"] == fr["candidates"][fr["pick"]]["settings"]


def test_frame_setup_refuses_a_bad_probe_by_name():
    from aliasing.frames.run import frame_setup

    fs = scenes.frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=1, ground_cells=1)
    with pytest.raises(ValueError, match="probe"):
        frame_setup(None, _setup({}, "near=0.5,far=60,fov=50,aspect=16:9,height=72", 35), fs, probe="no")


def test_the_memo_keeps_godots_maps_while_the_normal_bias_or_filter_moves_and_redraws_for_the_constant_bias():
    g, s, fs, sun, *_ = _frame({}, height=16)
    splits, mats = g.transforms(s, fs.camera, sun), g.matrices(s, fs.camera, sun)
    cast = fs.triangles[predict.casting(fs.triangles, sun, g.cast_side(s))]

    def maps(**given):
        return split_maps(cast, splits, mats, g.settings({**s, **given}))

    with seen.remember():
        first = maps()
        assert all(a is b for a, b in zip(first, maps(shadow_normal_bias=0.5, **{profile.QUALITY: 4})))
        assert not any(a is b for a, b in zip(first, maps(shadow_bias=0.3)))   # the depth pass moves every caster vertex
    assert not any(a is b for a, b in zip(first, maps()))                          # outside the block nothing is kept


@settings(max_examples=15, deadline=None)
@given(st.integers(8, 40), st.integers(8, 40))
def test_eye_buffers_any_image_size(w, h):
    """Godot's and Filament's read-back positions for any w × h: each seen pixel's position lies on its pixel-centre ray
    (the sheared pass where w − h is odd or negative), and where w − h is even and ≥ 0 the square grid's and the sheared
    pass's positions agree where both see a surface, their seen pixels differing only on the seen region's border (a
    pixel-centre ray through a triangle's edge: a tie the two rasterizations break apart)."""
    from aliasing.frames.models.filament import eye_buffers
    from aliasing.raster.draw.eye import image_pass
    from aliasing.view import tan_theta

    fs = scenes.frame_scene("boxes", near=0.5, far=30.0, fov=50.0, aspect=w / h, boxes=3, ground_cells=2)
    pos, nrm, hit = eye_buffers(fs, w, h)
    assert pos.shape == (h, w, 3) and hit.any()
    e = fs.camera.to_eye(pos[hit])
    t = float(tan_theta(50.0))
    rows, cols = np.nonzero(hit)
    assert np.allclose(e[:, 0] / e[:, 2], ((cols + 0.5) / w * 2 - 1) * t * w / h, atol=1e-9)
    assert np.allclose(e[:, 1] / e[:, 2], ((rows + 0.5) / h * 2 - 1) * t, atol=1e-9)
    if (w - h) % 2 == 0 and w >= h:
        from scipy import ndimage

        p, _, tri = image_pass(fs.camera.to_eye(fs.triangles), 50.0, w, h, near=0.5)
        both = hit & (tri >= 0)
        assert np.allclose(p[both] @ fs.camera.rotation + fs.camera.eye, pos[both], atol=1e-9)
        border = ndimage.binary_dilation(hit) & ~ndimage.binary_erosion(hit)
        assert not ((hit != (tri >= 0)) & ~border).any()
