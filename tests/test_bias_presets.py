"""Engine bias presets per cascade, and the ``aliasing bias`` command.

* each preset's offsets, converted to one depth bias, equal the rasterizer's verdict: a
  plane lit through ``depth_test`` with the engine's own offsets (normal offset, offset
  across the light, constant and slope-scaled bias) shows acne exactly where
  ``equivalent_depth`` < ``plane_bias`` (checked at 0.9× and 1.1× of the break-even texel);
* a normal offset opens no lit gap at the foot of a vertical caster (the offsets cancel),
  a constant bias opens b·cos α (rasterizer);
* ``cascade_bias`` rows: margins and acne angles consistent with ``plane_bias``;
* the command: table/CSV/JSON, and generated bad input ends in exit 2 with one line.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from aliasing.bias import lit_gap, plane_bias, presets
from aliasing.bias.cascades import cascade_bias
from aliasing.cli import main
from aliasing.raster.draw import depth_test, light_map, shadow_map, texel_edges

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


def _plane(theta: float, res: int):
    """A plane at θ from the light, sloping along the map's t axis, in a uniform map; points on it."""
    lm = light_map(1.0, 20.0, 60.0, "gamma:60", "Standard")
    xl, up, zl = lm.basis
    th = np.radians(theta)
    nrm = np.cos(th) * up + np.sin(th) * zl
    p0 = np.array([0.0, -1.0, 8.0])
    a = np.cross(nrm, [0.3, 0.5, 0.7])
    a /= np.linalg.norm(a)
    b = np.cross(nrm, a)
    sm = shadow_map(np.array([[p0 + 400.0 * (np.cos(t) * a + np.sin(t) * b) for t in (0.0, 2.1, 4.2)]]), lm, res)
    s, t = np.random.default_rng(1).uniform(0.05, 0.95, (2, 20000))
    c0 = lm.plane_point(*lm.inverse(s, t))
    p = c0 + (((p0 - c0) @ nrm) / (nrm @ up))[:, None] * up
    return lm, sm, p, np.broadcast_to(nrm, p.shape)


def _engine_lookup(preset, lm, sm, p, n, w, theta):
    """The engine's own offsets applied in the rasterizer (not their depth equivalent)."""
    th = np.radians(theta)
    up = lm.basis[1]
    scale = {"one": 1.0, "sin": np.sin(th), "one-minus-cos": 1.0 - np.cos(th)}[preset.normal_scale]
    across = n - np.outer(n @ up, up)  # the normal's part across the light (length sin θ)
    q = p + preset.across_texels * w * across
    return depth_test(lm, sm, q, n, bias=preset.depth + preset.depth_texels * w, normal_offset=preset.normal_texels * w * scale,
                      slope=preset.slope, pcf=preset.pcf)  # slope: × the map's own depth change per texel


@pytest.mark.parametrize("name", ["bevy", "godot", "unity-urp", "unity-urp-soft"])
@pytest.mark.parametrize("theta", [35.0, 70.0])
def test_preset_equivalent_depth_predicts_the_rasterizer(name, theta):
    # the offsets without the rasterizer-state slope term (which alone clears Unity's 2x2 PCF: see the slope test)
    preset = dataclasses.replace(presets.get(name), slope=0.0)
    res = 128
    lm, sm, p, n = _plane(theta, res)
    _, e_t = texel_edges(lm, res, p[:1])
    w = float(e_t[0, 1])  # the slope runs along t (φ = 90°): the texel's t side is what matters
    need = plane_bias(w, theta, 90.0, f"pcf{preset.pcf}").depth
    th = np.radians(theta)
    fixed = preset.depth + preset.slope * w * np.tan(th)  # the slope term acts on the map's own texel w
    per_texel = presets.equivalent_depth(preset, 1.0, theta, 90.0) - preset.depth - preset.slope * np.tan(th)
    tested = 0
    for factor in (0.9, 1.1):
        ws = (factor * need - fixed) / per_texel  # the engine's texel size that makes its rule factor × the need
        if ws <= 0:
            continue  # the fixed part alone exceeds the target
        assert presets.equivalent_depth(preset, ws, theta, 90.0) - preset.slope * ws * np.tan(th) + preset.slope * w * np.tan(th) == pytest.approx(factor * need)
        acne = (_engine_lookup(preset, lm, sm, p, n, ws, theta) < 1).mean()
        assert (acne > 1e-3) if factor < 1 else (acne == 0.0), (name, theta, factor, acne)
        tested += 1
    assert tested == 2


def test_slope_scaled_preset_clears_pcf2_acne():
    # Filament's polygonOffsetSlope 2 (Unity's 2.5) alone covers 2x2 PCF at every azimuth (needed ≤ k = 2)
    for theta in (30.0, 75.0):
        lm, sm, p, n = _plane(theta, 128)
        assert (depth_test(lm, sm, p, n, slope=2.0 * 1.05, pcf=2) < 1).mean() == 0.0
        assert (depth_test(lm, sm, p, n, slope=1.0 * 0.9, pcf=2) < 1).mean() > 1e-3  # k/2 at φ = 90°: 0.9 of it fails


def test_normal_offset_opens_no_gap_but_a_depth_bias_does():
    el = 40.0
    a = np.radians(el)
    lm = light_map(1.0, 20.0, 60.0, [0.0, np.sin(a), np.cos(a)], "Standard")
    ground = [[[-60.0, -1.0, 0.5], [60.0, -1.0, 0.5], [0.0, -1.0, 80.0]]]
    wall = [[[-2, -1, 10], [2, -1, 10], [2, 2, 10]], [[-2, -1, 10], [2, 2, 10], [-2, 2, 10]]]
    res = 512
    sm = shadow_map(np.array(ground + wall, float), lm, res)
    gs = np.linspace(0.0, 0.6, 601)
    X, G = np.meshgrid(np.linspace(-1.5, 1.5, 11), gs, indexing="ij")
    p = np.stack([X, np.full_like(X, -1.0), 10.0 - G], -1)
    n = np.broadcast_to([0.0, 1.0, 0.0], p.shape)
    _, e_t = texel_edges(lm, res, [[0.0, -1.0, 10.0]])
    tol = 0.5 * np.hypot(*e_t[0]) * np.sin(a) + (gs[1] - gs[0])
    ground_need = plane_bias(np.hypot(*e_t[0]), 90.0 - el, 90.0).normal
    for offset in (2 * ground_need, 0.3):  # a normal offset, small or large, and no depth bias
        shadowed = depth_test(lm, sm, p, n, normal_offset=offset) < 1
        first = gs[np.argmax(shadowed, 1)]
        assert shadowed.any(1).all() and first.max() <= tol, (offset, first.max(), tol)
    shadowed = depth_test(lm, sm, p, n, bias=0.3) < 1
    assert np.abs(gs[np.argmax(shadowed, 1)] - lit_gap(0.3, el)).max() <= tol


def test_cascade_rows_are_consistent():
    rows = cascade_bias(0.5, 200.0, 60.0, "gamma:50", "bevy", k=3, resolution=1024)
    assert [r["cascade"] for r in rows] == [0, 1, 2]
    for r in rows:
        w = max(r["texel_s"], r["texel_t"])
        assert r["margin"] == pytest.approx(r["preset_depth"] / r["need_depth"])
        assert r["preset_depth"] == pytest.approx(presets.equivalent_depth("bevy", w, r["ground_angle"], 90.0), rel=0.05)
        assert r["gap"] == pytest.approx(lit_gap(0.02, 90.0 - r["ground_angle"]))
        if np.isfinite(r["acne_from"]):  # just below acne_from the preset suffices at every azimuth
            th = r["acne_from"] - 0.5
            need = 0.5 * 5 * np.tan(np.radians(th)) * (np.abs(np.cos(np.radians(presets_az := np.arange(0, 91, 5.0)))) * r["texel_s"] + np.abs(np.sin(np.radians(presets_az))) * r["texel_t"])
            assert (presets.equivalent_depth("bevy", w, th, presets_az) >= need).all()
    assert all(rows[i]["far"] == rows[i + 1]["near"] for i in range(2))
    assert np.isnan(rows[-1]["step"]) and all(r["step"] > 1 for r in rows[:-1])


@pytest.mark.parametrize("aspect", [0.5, 16 / 9])
def test_cascade_rows_of_a_non_square_view(aspect):
    """aspect (width/height, fov vertical): the splits stay, each map is fitted to the wider slice.
    A light ahead in the view's yz plane: the map's s axis is the view's width, so texel_s scales by
    the aspect and texel_t, the ground's minimal bias (its slope is along t) and the lit gap do not."""
    sq = cascade_bias(0.5, 200.0, 60.0, "gamma:50", "bevy", k=3, resolution=1024)
    np.testing.assert_equal(cascade_bias(0.5, 200.0, 60.0, "gamma:50", "bevy", k=3, resolution=1024, aspect=1.0), sq)
    wide = cascade_bias(0.5, 200.0, 60.0, "gamma:50", "bevy", k=3, resolution=1024, aspect=aspect)
    for w, r in zip(wide, sq):
        assert (w["near"], w["far"]) == (r["near"], r["far"])
        # texel_edges differences the map coordinates over h = 1e-6: rounding up to ~1e-16/1e-6 (measured 2e-11 at 16:9, 0 at 0.5)
        assert w["texel_s"] == pytest.approx(aspect * r["texel_s"], rel=1e-9) and w["texel_t"] == pytest.approx(r["texel_t"], rel=1e-12)
        assert w["need_depth"] == pytest.approx(r["need_depth"], rel=1e-12) and w["gap_px"] == pytest.approx(r["gap_px"], rel=1e-12)
        assert w["margin"] == pytest.approx(w["preset_depth"] / w["need_depth"])


@settings(max_examples=20, deadline=None)
@given(st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([float("nan"), float("inf"), float("-inf")])))
def test_cascade_bias_refuses_a_bad_aspect_naming_it(aspect):
    with pytest.raises(ValueError, match="^aspect") as info:
        cascade_bias(0.5, 200.0, 60.0, "gamma:50", "bevy", k=2, resolution=256, aspect=aspect)
    assert "\n" not in str(info.value)


def test_unknown_preset_names_preset():
    with pytest.raises(ValueError, match="preset"):
        presets.get("unreal")
    with pytest.raises(ValueError, match="preset"):
        cascade_bias(1.0, 100.0, 60.0, "gamma:45", "nope")


def test_command_formats(capsys):
    assert main(["bias", "--presets", "filament", "-k", "2", "--resolution", "256", "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["cascade"] for r in rows] == [0, 1] and rows[0]["preset"] == "filament"
    assert main(["bias", "--plane", "--texel", "0.2", "--angle", "60", "--azimuth", "45", "--lookup", "pcf3", "--format", "csv"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "texel,angle,azimuth,lookup,depth,normal"
    assert float(out[1].split(",")[4]) == pytest.approx(plane_bias(0.2, 60.0, 45.0, "pcf3").depth)
    assert main(["bias", "--list"]) == 0
    assert "bevyengine/bevy" in capsys.readouterr().out


VOCAB = ["--presets", "--near", "--far", "--fov", "--aspect", "--light", "--scheme", "--splits", "-k", "--lambda", "--resolution", "--image",
         "--texel", "--angle", "--azimuth", "--lookup", "--format"]
VALUES = ["0", "-1", "1", "0.5", "45", "90", "nan", "inf", "1e400", "", "x", "filament", "bevy,nope", "gamma:45", "overhead", "gamma:0",
          "Standard", "P", "practical", "log", "pcf3", "pcf99", "receiver-plane", "csv", "json", "table", "32", "1,2", ",,"]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])  # readouterr() each call
@given(args=st.lists(st.tuples(st.sampled_from(VOCAB), st.sampled_from(VALUES)), max_size=4), plane=st.booleans())
def test_bad_command_lines_are_one_line(args, plane, capsysbinary):
    argv = ["bias"] + (["--plane"] if plane else []) + [x for pair in args for x in pair]
    if not plane and not any(a == "--resolution" for a, _ in args):
        argv += ["--resolution", "64", "-k", "2"]  # keep valid runs cheap (a later -k wins)
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse usage errors
        code = exc.code
    out = capsysbinary.readouterr()
    assert code in (0, 2), (argv, code)
    if code == 2:
        assert len(out.err.decode().strip().splitlines()) == 1, (argv, out.err)
        assert b"Traceback" not in out.err


def test_render_bias_margin(tmp_path, capsys):
    out = tmp_path / "m.png"
    assert main(["render", "--what", "bias-margin", "--bias-preset", "bevy", "--image-res", "32", "--res", "128", "--out", str(out)]) == 0
    assert out.stat().st_size > 0
    assert main(["render", "--what", "bias-margin", "--bias-preset", "unreal", "--image-res", "32", "--res", "128", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "preset" in err[0]
    assert "did you mean 'unity-urp'" in (main(["render", "--what", "bias-margin", "--bias-preset", "unity", "--out", str(out)]) == 2 and capsys.readouterr().err)
    # one rendering path: cascades of a split method and several schemes get the picture too, labelled
    out.unlink()
    assert main(["render", "--what", "bias-margin", "--scheme", "Standard,P", "--splits", "practical", "-k", "2", "--image-res", "32", "--res", "128", "--out", str(out)]) == 0
    assert out.stat().st_size > 0 and "practical+P" in capsys.readouterr().out


def test_figures_registered_and_their_claims():
    import sys
    from pathlib import Path

    from aliasing.reproduce import TARGETS

    assert TARGETS["bias-threshold"].module == "bias_threshold" and TARGETS["bias-presets"].module == "bias_presets"
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from figures import bias_threshold

    cols = bias_threshold.data()
    f = cols["factor"]
    for key, v in cols.items():
        if key == "factor":
            continue
        assert (v[f >= 1.05] == 0).all(), key  # the docstring: zero from 1.025–1.05 at the latest
        assert v[np.isclose(f, 0.9)][0] > 0.004, key  # acne at 0.9 in every case
    assert (cols["Standard_nearest"][f >= 1.0] == 0).all() and (cols["Standard_pcf3"][f >= 1.0] == 0).all()


def test_bias_explorer_equals_the_api():
    pytest.importorskip("ipywidgets")
    from aliasing import explore

    e = explore.bias(preset="bevy", elevation=20.0, k=4)
    assert e.error is None and e.png().startswith(b"\x89PNG")
    rows = cascade_bias(0.1, 100.0, 60.0, "gamma:20", "bevy", k=4, resolution=2048, image=1080, lam=0.5)
    assert [r["margin"] for r in e.data["rows"]] == [r["margin"] for r in rows]
    assert e.set_state({"preset": "filament"}) and e.data["preset"] == "filament"
