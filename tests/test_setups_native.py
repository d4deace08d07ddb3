"""The engine profiles read from public source (Godot 4, Bevy, Unity URP 17, Filament, Unreal 5).

* every setting's default and range as the engine's source gives them; bad values are one-line
  ValueErrors naming the key and the range; unknown keys get a did-you-mean; Hypothesis feeds
  generated settings to every profile;
* each pipeline's splits equal the split presets at the defaults; Godot's atlas layout; the
  blend bands and overlaps;
* each bias rule on a plane, by hand from the engine's formula, against the bias presets'
  ``equivalent_depth`` (the presets are views of the profiles) and against ``plane_bias``;
* Godot's bias preset now carries its constant term (ERRATA GD1), and the guide's row.
"""

from __future__ import annotations

import dataclasses
import json
from re import escape as re_escape

import numpy as np
import pytest

from aliasing import partitioning, setups
from aliasing.bias import plane_bias, presets
from aliasing.engines import pipeline as engine_pipeline
from aliasing.engines import stable
from aliasing.setups import bevy, filament, godot, unity_urp, unreal

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

ENGINES = ("godot", "bevy", "unity-urp", "filament", "unreal")
CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"

# The defaults as the sources give them (module docstrings cite file and function).
DEFAULTS = {
    "godot": {"directional_shadow_mode": "SHADOW_PARALLEL_4_SPLITS", "directional_shadow_split_1": 0.1, "directional_shadow_split_2": 0.2,
              "directional_shadow_split_3": 0.5, "directional_shadow_blend_splits": False, "directional_shadow_fade_start": 0.8,
              "directional_shadow_max_distance": 100.0, "directional_shadow_pancake_size": 20.0, "shadow_bias": 0.1, "shadow_normal_bias": 2.0,
              "shadow_blur": 1.0, "shadow_reverse_cull_face": False, "light_angular_distance": 0.0,
              "rendering/lights_and_shadows/directional_shadow/size": 4096,
              "rendering/lights_and_shadows/directional_shadow/soft_shadow_filter_quality": 2,
              "rendering/lights_and_shadows/directional_shadow/16_bits": True, "rendering/renderer/rendering_method": "forward_plus"},
    "bevy": {"num_cascades": 4, "minimum_distance": 0.1, "maximum_distance": 150.0, "first_cascade_far_bound": 10.0, "overlap_proportion": 0.2,
             "shadow_depth_bias": 0.02, "shadow_normal_bias": 1.8, "DirectionalLightShadowMap.size": 2048, "ShadowFilteringMethod": "Gaussian"},
    "unity-urp": {"shadowDistance": 50.0, "shadowCascadeCount": 1, "cascade2Split": 0.25, "cascade3Split.x": 0.1, "cascade3Split.y": 0.3,
                  "cascade4Split.x": 0.067, "cascade4Split.y": 0.2, "cascade4Split.z": 0.467, "cascadeBorder": 0.2,
                  "mainLightShadowmapResolution": 2048, "shadowDepthBias": 1.0, "shadowNormalBias": 1.0, "supportsSoftShadows": False,
                  "softShadowQuality": "Medium", "light.shadows": "Soft", "light.usePipelineSettings": True, "light.shadowBias": 0.05,
                  "light.shadowNormalBias": 0.4, "light.softShadowQuality": "UsePipelineSettings"},
    "filament": {"mapSize": 1024, "shadowCascades": 1, "cascadeSplitPositions[0]": 0.125, "cascadeSplitPositions[1]": 0.25,
                 "cascadeSplitPositions[2]": 0.5, "constantBias": 0.001, "normalBias": 1.0, "shadowFar": 0.0, "shadowNearHint": 1.0,
                 "shadowFarHint": 100.0, "stable": False, "lispsm": True, "polygonOffsetConstant": 0.5, "polygonOffsetSlope": 2.0,
                 "screenSpaceContactShadows": False, "stepCount": 8, "maxShadowDistance": 0.3, "View.shadowType": "PCF"},
    "unreal": {"DynamicShadowDistanceMovableLight": 20000.0, "DynamicShadowCascades": 3, "CascadeDistributionExponent": 3.0,
               "CascadeTransitionFraction": 0.1, "ShadowDistanceFadeoutFraction": 0.1, "ShadowCascadeBiasDistribution": 1.0, "ShadowBias": 0.5,
               "ShadowSlopeBias": 0.5, "r.Shadow.MaxCSMResolution": 2048, "r.Shadow.CSMDepthBias": 10.0, "r.Shadow.CSMSlopeScaleDepthBias": 3.0,
               "r.Shadow.ShadowMaxSlopeScaleDepthBias": 1.0, "r.Shadow.DistanceScale": 1.0, "r.Shadow.Virtual.Enable": 0},
}


@pytest.mark.parametrize("engine", ENGINES)
def test_defaults_as_the_sources_give_them(engine):
    profile = setups.get(engine)
    assert profile.defaults() == DEFAULTS[engine]
    assert profile.engine == engine and profile.language and profile.source
    for s in profile.settings:
        assert s.coerce(s.default) == s.default  # every default is accepted as is
        assert s.source or s.key.startswith(("light.", "View.")), s.key


def _outside(s):
    lo, hi = s.accepts
    out = []
    if lo is not None:
        out.append(lo - (1 if s.kind == "int" else max(1e-6, abs(lo) * 1e-6)))
    if hi is not None:
        out.append(hi + (1 if s.kind == "int" else max(1e-6, abs(hi) * 1e-6)))
    return out


@pytest.mark.parametrize("engine", ENGINES)
def test_every_range_ends_accepted_and_beyond_refused_in_one_line(engine):
    profile = setups.get(engine)
    for s in profile.settings:
        if s.kind in ("float", "int"):
            for end in s.accepts:
                if end is not None:
                    assert profile.resolve({s.key: end})[s.key] == end
            for bad in _outside(s):
                with pytest.raises(ValueError) as err:
                    profile.resolve({s.key: bad})
                msg = str(err.value)
                assert msg.startswith(s.key) and "\n" not in msg and s.allowed() in msg
        elif s.kind == "choice":
            with pytest.raises(ValueError, match=rf"^{re_escape(s.key)} must be one of"):
                profile.resolve({s.key: "nonsense"})
        for bad in (None, [1], "x" if s.kind != "choice" else 1.5):
            with pytest.raises(ValueError, match=f"^{re_escape(s.key)} must be"):
                profile.resolve({s.key: bad})


@pytest.mark.parametrize("engine, typo, key", [("godot", "shadow_bais", "shadow_bias"), ("bevy", "shadow_normal_bais", "shadow_normal_bias"),
                                               ("unity-urp", "shadowCascadeCont", "shadowCascadeCount"), ("filament", "constantBais", "constantBias"),
                                               ("unreal", "r.Shadow.CSMDepthBais", "r.Shadow.CSMDepthBias")])
def test_unknown_keys_get_a_did_you_mean(engine, typo, key):
    with pytest.raises(ValueError, match=f"did you mean '{re_escape(key)}'"):
        setups.build(engine, {typo: 1}, CAMERA)




def test_releases_resolve_and_unknown_ones_are_named():
    assert setups.get("godot@4.4").name == "godot@4" and setups.get("unity-urp@17").release == "17"
    assert setups.get("unreal@5.4").release == "5" and setups.get("bevy").release == "0.17" and setups.get("filament").engine == "filament"
    with pytest.raises(ValueError, match="unknown Godot DirectionalLight3D release '3.5'"):
        setups.get("godot@3.5")


_VALUES = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
                    st.text(max_size=12), st.lists(st.integers(), max_size=2))


@pytest.mark.parametrize("engine", ENGINES)
@settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_fuzzed_settings_build_or_fail_in_one_line(engine, data):
    profile = setups.get(engine)
    keys = [s.key for s in profile.settings]
    chosen = data.draw(st.dictionaries(st.sampled_from(keys + ["nope", "shadow"]), st.one_of(_VALUES, st.sampled_from(
        [s.default for s in profile.settings] + [c for s in profile.settings if s.kind == "choice" for c in s.accepts])), max_size=4))
    try:
        setup = setups.build(profile, chosen, CAMERA)
    except ValueError as err:
        assert "\n" not in str(err) and str(err)
        return
    p = setup.pipeline
    assert all(0 < a < b for a, b in zip(p.near_i, p.far_i)) and p.resolution >= 1 and p.memory > 0
    assert p.bias.faces in ("front", "back", "both")
    w = engine_pipeline.texels(p, setup.camera, setup.sun.direction()[None])
    assert np.all(np.isfinite(w)) and np.all(w > 0)
    assert isinstance(profile.snippet(setup.settings), str)


@pytest.mark.parametrize("engine", ENGINES)
@settings(max_examples=30, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(near=st.floats(1e-3, 50.0), ratio=st.floats(1.0 + 1e-6, 1e5), fov=st.floats(1.0, 170.0), aspect=st.floats(0.1, 10.0))
def test_any_camera_builds_or_fails_in_one_line(engine, near, ratio, fov, aspect):
    """Degenerate cameras included (far/near → 1, narrow and wide fields of view)."""
    camera = setups.Camera(near, near * ratio, fov, aspect, 1080)
    try:
        setup = setups.build(engine, {}, camera)
    except ValueError as err:
        assert "\n" not in str(err)
        return
    p = setup.pipeline
    assert all(0 < a < b for a, b in zip(p.near_i, p.far_i)) and min(p.near_i) >= camera.near * (1 - 1e-12)
    w = engine_pipeline.texels(p, camera, setup.sun.direction()[None])
    assert np.all(np.isfinite(w)) and np.all(w > 0)


# --- splits, fits and layouts ----------------------------------------------------------------


def test_splits_equal_the_split_presets_at_the_defaults():
    cam = setups.parse_camera(CAMERA)
    g = setups.build("godot", camera=cam).pipeline
    np.testing.assert_array_equal(g.near_i + (g.far_i[-1],), partitioning.split_distances("godot", 0.1, 100.0, 4))
    b = setups.build("bevy", camera=cam).pipeline
    lo, hi = partitioning.partitions("bevy", 0.1, 150.0, 4)
    np.testing.assert_array_equal(b.near_i, lo) and np.testing.assert_array_equal(b.far_i, hi)
    u = setups.build("unity-urp", {"shadowCascadeCount": 4}, cam).pipeline
    np.testing.assert_array_equal(u.near_i + (u.far_i[-1],), partitioning.split_distances("unity-urp", 0.1, 50.0, 4))
    assert setups.build("unity-urp", camera=cam).pipeline.near_i == (0.1,)  # URP's asset default: one cascade
    f = setups.build("filament", {"shadowCascades": 4}, cam).pipeline
    np.testing.assert_array_equal(f.near_i + (f.far_i[-1],), partitioning.split_distances("filament", 0.1, 500.0, 4))
    ue = setups.build("unreal", camera="near=10,far=100000,fov=60,aspect=16:9,height=1080").pipeline
    lo, hi = partitioning.partitions("unreal", 10.0, 20000.0, 3)
    np.testing.assert_array_equal(ue.near_i, lo) and np.testing.assert_array_equal(ue.far_i, hi)
    assert (g.split, b.split, u.split, f.split, ue.split) == ("godot", "bevy", "unity-urp", "filament", "unreal")


def test_the_engines_own_split_settings_reach_the_split_presets():
    s = setups.build("godot", {"directional_shadow_split_1": 0.05, "directional_shadow_max_distance": 0.0}, CAMERA).pipeline
    assert s.far_i[0] == pytest.approx(0.1 + 0.05 * 499.9) and s.far_i[-1] == 500.0  # max distance 0: the camera's far
    u = setups.build("unity-urp", {"shadowCascadeCount": 3, "cascade3Split.x": 0.2, "cascade3Split.y": 0.6}, CAMERA).pipeline
    assert u.far_i[:2] == pytest.approx((0.1 + 0.2 * 49.9, 0.1 + 0.6 * 49.9))
    with pytest.raises(ValueError, match=r"^directional_shadow_split_1, directional_shadow_split_2, directional_shadow_split_3 must increase"):
        setups.build("godot", {"directional_shadow_split_2": 0.05}, CAMERA)


def test_godot_atlas_layout():
    cam = setups.parse_camera(CAMERA)
    up = np.array([[0.0, 1.0, 0.0]])
    four = setups.build("godot", camera=cam).pipeline
    assert (four.resolution, four.rows, four.memory) == (2048, 0, 4096 * 4096 * 2)  # quadrants of one 16-bit atlas
    assert "2x2" in four.layout
    two = setups.build("godot", {"directional_shadow_mode": "SHADOW_PARALLEL_2_SPLITS"}, cam).pipeline
    assert (two.resolution, two.rows, two.memory, two.k) == (4096, 2048, 4096 * 4096 * 2, 2)
    w = engine_pipeline.texels(two, cam, up)
    np.testing.assert_allclose(w[..., 1], 2 * w[..., 0], rtol=1e-15)  # halves: the t texel is twice the s texel
    one = setups.build("godot", {"directional_shadow_mode": "SHADOW_ORTHOGONAL", godot.BITS: False}, cam).pipeline
    assert (one.resolution, one.rows, one.k, one.memory) == (4096, 0, 1, 4096 * 4096 * 4)
    # the split's texel is Godot's shadow_texel_size = 2r/R, r the corners' sphere radius × R/(R − 2)
    r = stable.centroid_radius(four.near_i[0], four.far_i[0], cam.fov, cam.aspect) * 2048 / 2046
    assert engine_pipeline.texels(four, cam, up)[0, 0, 0] == pytest.approx(2 * r / 2048, rel=1e-12)
    assert godot.layout(4096, 4)[:2] == (2048, 2048) and unity_urp.layout(2048, 4)[:3] == (1024, 2048, 2048)


def test_blend_bands_and_overlaps():
    g = setups.build("godot", {"directional_shadow_blend_splits": True}, CAMERA).pipeline
    ends = partitioning.split_distances("godot", 0.1, 100.0, 4)
    assert g.near_i == (ends[0], ends[0], ends[1], ends[2])  # split i >= 1 fitted from the start of split i - 1
    assert g.bands == tuple((0.9 * e, e) for e in ends[1:-1])  # smoothstep(0.9·split, split, depth)
    assert setups.build("godot", CAMERA and {}, CAMERA).pipeline.bands == ()
    b = setups.build("bevy", camera=CAMERA).pipeline
    ends = partitioning.split_distances("bevy", 0.1, 150.0, 4)
    assert b.bands == tuple((0.8 * e, e) for e in ends[1:-1])
    u = setups.build("unreal", camera="near=10,far=100000,fov=60,aspect=16:9,height=1080").pipeline
    ends = partitioning.split_distances("unreal", 10.0, 20000.0, 3)
    np.testing.assert_allclose(u.bands, [(e, e + 0.1 * (e - s)) for s, e in zip(ends[:-2], ends[1:-1])], rtol=1e-14)


def test_bevy_renders_at_most_four_cascades_and_starts_at_minimum_distance():
    p = setups.build("bevy", {"num_cascades": 6}, CAMERA).pipeline
    ends = partitioning.split_distances("bevy", 0.1, 150.0, 6)
    assert p.k == 4 and p.far_i[-1] == ends[4]  # MAX_CASCADES_PER_LIGHT: shadows end at the 4th bound
    q = setups.build("bevy", {"minimum_distance": 2.0}, CAMERA).pipeline
    assert q.near_i[0] == 2.0
    with pytest.raises(ValueError, match=r"^first_cascade_far_bound must be in \(minimum_distance, maximum_distance\)"):
        setups.build("bevy", {"first_cascade_far_bound": 200.0}, CAMERA)


def test_fits_and_stability():
    assert (godot.FIT, godot.SNAP) == (stable.PRESETS["godot"].fit, stable.PRESETS["godot"].snap)
    assert (bevy.FIT, bevy.SNAP) == (stable.PRESETS["bevy"].fit, stable.PRESETS["bevy"].snap)
    f = setups.build("filament", {"stable": True}, CAMERA).pipeline
    assert (f.fit, f.snap, f.stable) == (stable.PRESETS["filament"].fit, stable.PRESETS["filament"].snap, True)
    far = setups.build("filament", {"stable": True, "shadowFar": 80.0}, CAMERA).pipeline
    assert (far.fit, far.far_i[-1]) == ("far", 80.0)
    assert setups.build("filament", camera=CAMERA).pipeline.fit == "tight"
    u = setups.build("unity-urp", camera=CAMERA).pipeline
    assert (u.fit, u.stable) == ("sphere", False) and any("assumption" in n for n in u.notes)


def test_unreal_refuses_virtual_shadow_maps_in_one_line():
    with pytest.raises(ValueError, match=r"^r\.Shadow\.Virtual\.Enable=1 selects virtual shadow maps") as err:
        setups.build("unreal", {"r.Shadow.Virtual.Enable": 1}, CAMERA)
    assert "\n" not in str(err.value)


# --- bias rules on a plane ---------------------------------------------------------------------

W = np.array([0.003, 0.02, 0.3])[:, None, None]
TH = np.array([0.0, 10.0, 35.0, 60.0, 80.0])[None, :, None]
PH = np.array([0.0, 30.0, 90.0])[None, None, :]


def _by_hand(engine, w, th, ph):
    t, p = np.radians(th), np.radians(ph)
    steep = np.maximum(np.abs(np.cos(p)), np.abs(np.sin(p)))
    if engine == "godot":  # shadow_bias/100·(2r + pancake)·blur·q along the light, 2r = w·2048; normal 2 texels across it
        return 0.1 / 100 * (w * 2048 + 20.0) * 1.0 * 2.0 + 2.0 * w * np.sin(t) * np.tan(t)
    if engine == "bevy":
        return 0.02 + 1.8 * w / np.cos(t)
    if engine == "unity-urp":  # caster: 1 texel along the light, (1 − cos θ) texel along −n; slope-scaled 2.5
        return w + w * (1 - np.cos(t)) / np.cos(t) + 2.5 * w * np.tan(t) * steep
    if engine == "filament":
        return 0.001 + w * np.sin(t) / np.cos(t) + 2.0 * w * np.tan(t) * steep
    # unreal: CSMDepthBias·ShadowBias·W/Res·(1 + CSMSlopeScale·ShadowSlopeBias·min(tan θ, 1)), W/Res = w/2
    return 10.0 * 0.5 * (w / 2) * (1 + 3.0 * 0.5 * np.minimum(np.tan(t), 1.0))


def _default_rule(engine):
    d = setups.get(engine).defaults()
    return {"godot": lambda: godot.rule(d, 2048), "bevy": lambda: bevy.rule(d), "unity-urp": lambda: unity_urp.rule(d),
            "filament": lambda: filament.rule(d), "unreal": lambda: unreal.rule(d)}[engine]()


@pytest.mark.parametrize("engine", ENGINES)
def test_bias_rules_by_hand(engine):
    rule = _default_rule(engine)
    got = rule.depth(W, TH, PH)
    np.testing.assert_allclose(got, np.broadcast_to(_by_hand(engine, W, TH, PH), got.shape), rtol=1e-13)
    built = setups.build(engine, camera=CAMERA).pipeline.bias
    if engine != "godot":  # Godot's rule depends on the split's texture size (2048 at the defaults: the same)
        assert built == rule
    assert built.faces == "front"


@pytest.mark.parametrize("engine, preset", [("godot", "godot"), ("bevy", "bevy"), ("unity-urp", "unity-urp"), ("filament", "filament")])
def test_bias_presets_are_views_of_the_profiles(engine, preset):
    np.testing.assert_allclose(presets.equivalent_depth(preset, W, TH, PH), _default_rule(engine).depth(W, TH, PH), rtol=1e-12)
    soft = unity_urp.rule({**setups.get("unity-urp").defaults(), "supportsSoftShadows": True})
    np.testing.assert_allclose(presets.equivalent_depth("unity-urp-soft", W, TH, PH), soft.depth(W, TH, PH), rtol=1e-12)
    assert presets.get(preset).pcf == setups.build(engine, {"supportsSoftShadows": False} if engine == "unity-urp" else {}, CAMERA).pipeline.filter.taps


def test_godot_bias_preset_is_the_profile_at_2048():
    p = presets.get("godot")
    assert (p.depth, p.depth_texels, p.across_texels, p.pcf) == (pytest.approx(0.04, rel=1e-14), pytest.approx(4.096, rel=1e-14), 2.0, 5)
    assert presets.contact_depth("godot", 0.01) == pytest.approx(0.04 + 0.04096)
    # at another atlas size the profile carries the size: R = 1024 halves the texel part
    r = godot.rule(setups.get("godot").defaults(), 1024)
    assert r.depth(0.01, 0.0) == pytest.approx(0.1 / 100 * (0.01 * 1024 + 20) * 2)


@pytest.mark.parametrize("engine, key", [("bevy", "shadow_normal_bias"), ("godot", "shadow_bias"), ("unity-urp", "shadowDepthBias"),
                                         ("filament", "normalBias"), ("unreal", "ShadowBias")])
def test_minimal_setting_meets_plane_bias(engine, key):
    """The value of one setting that just covers the plane's need (aliasing.bias.plane) gives exactly that need."""
    rule = _default_rule(engine)
    w, th, ph = 0.02, 50.0, 30.0
    need = plane_bias(w, th, ph, "pcf5").depth
    v = rule.minimal(key, need, w, th, ph)
    tuned = dataclasses.replace(rule, terms=tuple(dataclasses.replace(t, value=v) if t.key == key else t for t in rule.terms))
    assert tuned.depth(w, th, ph) == pytest.approx(need, rel=1e-12)


def test_unreal_bias_is_constant_in_texels_and_its_slope_clamps():
    r = _default_rule("unreal")
    assert r.depth(0.04, 0.0) / 0.04 == pytest.approx(2.5) and r.depth(1.0, 0.0) == pytest.approx(2.5)  # CSMDepthBias/2 × ShadowBias texels
    assert r.depth(0.04, 70.0) == pytest.approx(r.depth(0.04, 85.0))  # tan θ clamped at 1
    assert r.contact(0.04) == pytest.approx(0.1)
    with pytest.raises(ValueError, match="ShadowCascadeBiasDistribution 0.5: only 1"):
        setups.build("unreal", {"ShadowCascadeBiasDistribution": 0.5}, CAMERA)


def test_faces_follow_the_engine_setting():
    assert setups.build("godot", {"shadow_reverse_cull_face": True}, CAMERA).pipeline.bias.faces == "back"


def test_unity_per_light_biases_and_soft_kernels():
    own = setups.build("unity-urp", {"light.usePipelineSettings": False}, CAMERA).pipeline.bias
    assert [t.key for t in own.terms][:2] == ["light.shadowBias", "light.shadowNormalBias"] and own.depth(1.0, 0.0) == pytest.approx(0.05)
    for quality, k, taps in (("Low", 1.5, 3), ("Medium", 2.5, 5), ("High", 3.5, 7)):
        p = setups.build("unity-urp", {"supportsSoftShadows": True, "softShadowQuality": quality}, CAMERA).pipeline
        assert p.bias.depth(1.0, 0.0) == pytest.approx(k) and p.filter.taps == taps
    hard_light = setups.build("unity-urp", {"supportsSoftShadows": True, "light.shadows": "Hard"}, CAMERA).pipeline
    assert hard_light.bias.depth(1.0, 0.0) == pytest.approx(1.0) and hard_light.filter.taps == 2


def test_godot_guide_row(capsys):
    """docs/guide/bias.rst: Godot's row (margin, acne, lit gap, PCF footprint), at the guide's precision."""
    from aliasing.cli import main

    assert main(["bias", "--light", "gamma:45", "--presets", "godot", "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    ends = lambda key, nd=1: (round(rows[0][key], nd), round(rows[-1][key], nd))  # noqa: E731
    assert ends("margin") == (4.6, 2.9) and ends("acne_from") == (81.5, 74.5)
    assert ends("gap_px") == (7.1, 2.4)
    pcf = [r["pcf_px"] for r in rows]
    assert (round(min(pcf), 1), round(max(pcf), 1)) == (3.4, 5.2)


# --- snippets -----------------------------------------------------------------------------------


@pytest.mark.parametrize("engine, key, value, text", [
    ("godot", "shadow_normal_bias", 3.5, "light.shadow_normal_bias = 3.5"),
    ("godot", godot.QUALITY, 4, "SHADOW_QUALITY_SOFT_HIGH"),
    ("bevy", "overlap_proportion", 0.3, "overlap_proportion: 0.3,"),
    ("bevy", "ShadowFilteringMethod", "Temporal", "ShadowFilteringMethod::Temporal"),
    ("unity-urp", "cascade4Split.y", 0.25, "new Vector3(0.067f, 0.25f, 0.467f)"),
    ("filament", "normalBias", 1.5, "options.normalBias = 1.5f;"),
    ("filament", "mapSize", 2048, "options.mapSize = 2048;"),
    ("unreal", "r.Shadow.CSMDepthBias", 4.0, "r.Shadow.CSMDepthBias=4"),
])
def test_snippets_carry_the_settings(engine, key, value, text):
    profile = setups.get(engine)
    code = profile.snippet(profile.resolve({key: value}))
    assert text in code
    assert profile.language in ("gdscript", "rust", "csharp", "cpp", "ini")


def test_guide_table():
    """docs/guide/engines.rst, 'Engine profiles read from source': its table at the printed precision."""
    web = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
    rows = {"godot": (4, 100.0, 32, (7.9, 4.5), (10.9, 7.5), 1), "bevy": (4, 150.0, 64, (3.8, 1.9), (5.6, 3.7), 1),
            "unity-urp": (1, 50.0, 8, (1.0, 1.0), (6.3, 6.3), 1), "filament": (1, 500.0, 4, (0.0012, 0.0012), (5.2, 5.2), None),
            "unreal": (3, 20000.0, 48, (2.5, 2.5), (6.25, 6.25), 2)}
    for engine, (k, end, mib, facing, tilted, nd) in rows.items():
        s = setups.build(engine, camera="near=10,far=100000,fov=50,aspect=16:9,height=1080" if engine == "unreal" else web, sun=30)
        p = s.pipeline
        w = engine_pipeline.texels(p, s.camera, s.sun.direction()[None])[0, :, 0]
        per = lambda th: (float(p.bias.depth(w[0], th) / w[0]), float(p.bias.depth(w[-1], th) / w[-1]))  # noqa: E731
        got0, got60 = per(0.0), per(60.0)
        if nd is None:
            assert tuple(float(f"{v:.2g}") for v in got0) == facing
        else:
            assert tuple(round(v, nd) for v in got0) == facing
        assert tuple(round(v, 2 if engine == "unreal" else 1) for v in got60) == tilted
        assert (p.k, p.far_i[-1], p.memory / 2**20) == (k, end, mib)
