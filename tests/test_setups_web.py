"""The profiles of the engines that ship on npm: three.js (r187, r184), Babylon.js 9.35, PlayCanvas 2.23.

What the engines' own code says is run in node by ``tests/test_engines_js.py`` (texels, depth
ranges, defaults, clamps); here, without node:

* settings round-trip (defaults, text values, JSON and TOML files) and the snippets carry them;
* bad values give one-line ValueErrors naming the key and what it takes; unknown keys a
  did-you-mean from that engine's keys; Hypothesis fuzz of every setting's value;
* the pipelines' splits are the split presets the node tests check against the engines;
* the bias rules: Babylon's bias factor per filter and depth clamp, the faces per setting, the
  terms that need the cascade's depth range;
* the bias presets ``threejs`` and ``babylon`` are views of the profiles.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from aliasing import partitioning, setups
from aliasing.bias import presets
from aliasing.engines import pipeline
from aliasing.setups import babylon, playcanvas, threejs

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

WEB = ["threejs@r187", "threejs@r184", "babylon", "playcanvas"]
CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
LIGHTS = np.array([[0.0, 1.0, 0.0], [0.3, 0.8, 0.2], [-0.6, 0.3, -0.74]])


@pytest.mark.parametrize("spec", WEB)
def test_defaults_round_trip(spec, tmp_path):
    p = setups.get(spec)
    d = p.defaults()
    assert p.resolve(d) == d and p.resolve({}) == d
    # every value as --set text is the same value
    text = {k: ("null" if v is None else str(v).lower() if isinstance(v, bool) else str(v)) for k, v in d.items()}
    assert p.resolve(text) == d
    # and through a JSON file and a TOML file (dotted keys as nested tables)
    (tmp_path / "s.json").write_text(json.dumps(d))
    assert p.resolve(setups.load_settings(tmp_path / "s.json")) == d
    lines = [f"{json.dumps(k)} = {json.dumps(v)}" for k, v in d.items() if v is not None]
    (tmp_path / "s.toml").write_text("\n".join(lines))
    assert p.resolve(setups.load_settings(tmp_path / "s.toml")) == {k: v for k, v in d.items()}
    s = setups.build(spec, {}, CAMERA)
    assert s.changed() == {} and s.pipeline.k >= 1


@pytest.mark.parametrize("spec, changes, shown", [
    ("threejs", {"cascades": 4, "shadowBias": -0.0005, "fade": True, "mode": "custom", "customSplitsLambda": 0.7},
     ["cascades: 4", "shadowBias: -0.0005", "csm.fade = true", "0.7"]),
    ("threejs", {"class": "DirectionalLight", "shadow.bias": -0.001, "material.shadowSide": "FrontSide"},
     ["light.shadow.bias = -0.001;", "material.shadowSide = THREE.FrontSide;"]),
    ("babylon", {"numCascades": 3, "lambda": 0.8, "stabilizeCascades": True, "shadowMaxZ": 120.0, "filter": "FILTER_PCSS"},
     ["gen.numCascades = 3;", "gen.lambda = 0.8;", "gen.stabilizeCascades = true;", "gen.shadowMaxZ = 120;", "FILTER_PCSS"]),
    ("babylon", {"class": "ShadowGenerator", "light.shadowFrustumSize": 80.0}, ["new BABYLON.ShadowGenerator(1024, light);",
                                                                                  "light.shadowFrustumSize = 80;"]),
    ("playcanvas", {"numCascades": 4, "shadowType": "SHADOW_PCF5_32F", "material.cull": "CULLFACE_FRONT"},
     ["numCascades: 4", "shadowType: pc.SHADOW_PCF5_32F", "material.cull = pc.CULLFACE_FRONT;"]),
])
def test_snippets_carry_the_settings(spec, changes, shown):
    s = setups.build(spec, changes, CAMERA)
    code = s.profile.snippet(s.settings)
    assert s.changed() == changes
    for piece in shown:
        assert piece in code, (piece, code)


@pytest.mark.parametrize("spec, key, value, message", [
    ("threejs", "cascades", -1, r"^cascades must be a whole number in \[0, 64\], got -1$"),
    ("threejs", "shadowMapSize", 2.5, r"^shadowMapSize must be a whole number in \[0, 16384\] \[texels\], got 2.5$"),
    ("threejs", "mode", "practcal", r"^mode must be one of .*'practical'.*did you mean 'practical'"),
    ("threejs", "fade", "yes", r"^fade must be true or false, got 'yes'$"),
    ("babylon", "cascadeBlendPercentage", 2, r"^cascadeBlendPercentage must be a number in \[0, 1\] \[fraction of a cascade\], got 2$"),
    ("babylon", "numCascades", "four", r"^numCascades must be a whole number, got 'four'$"),
    ("babylon", "filter", "PFC", r"^filter must be one of 'FILTER_NONE'.* or null .*got 'PFC'"),
    ("babylon", "shadowMaxZ", [1, 2], r"^shadowMaxZ must be a number \[world units\] or null \(the engine's derived default\), got \[1, 2\]$"),
    ("playcanvas", "shadowType", "SHADOW_PCF3_23F", r"^shadowType must be one of .*did you mean .*'SHADOW_PCF3_32F'"),
    ("playcanvas", "shadowDistance", math.inf, r"^shadowDistance must be a number >= 0 \[world units\], got inf$"),
])
def test_bad_values_name_the_key_and_range(spec, key, value, message):
    with pytest.raises(ValueError, match=message) as err:
        setups.build(spec, {key: value}, CAMERA)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("spec, key, hint", [("threejs", "shadowbias", "shadowBias"), ("babylon", "numCascade", "numCascades"),
                                             ("babylon", "lamda", "lambda"), ("playcanvas", "cascadeDistrib", "cascadeDistribution")])
def test_unknown_keys_get_a_did_you_mean(spec, key, hint):
    with pytest.raises(ValueError, match=f"unknown .* setting '{key}'.*did you mean '{hint}'") as err:
        setups.build(spec, {key: 1}, CAMERA)
    assert "\n" not in str(err.value)


def test_engine_level_inconsistencies_are_one_line_errors():
    cases = [
        ("threejs", {"class": "DirectionalLight", "shadow.camera.left": 5.0}, "shadow.camera must have right > left"),
        ("threejs", {"lightNear": 10.0, "lightFar": 5.0}, "lightFar must exceed lightNear"),
        ("threejs", {"maxFar": 0.05}, "maxFar must exceed the camera's near"),
        ("babylon", {"class": "ShadowGenerator"}, "light.shadowFrustumSize must be > 0"),
        ("babylon", {"minDistance": 0.5, "maxDistance": 0.5}, "minDistance .* must lie below maxDistance"),
        ("playcanvas", {"shadowDistance": 0.05}, "shadowDistance must exceed the camera's near"),
    ]
    for spec, changes, message in cases:
        with pytest.raises(ValueError, match=message) as err:
            setups.build(spec, changes, CAMERA)
        assert "\n" not in str(err.value)


def _values(setting):
    anything = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True),
                         st.text(max_size=12), st.lists(st.integers(), max_size=2))
    if setting.kind == "choice":
        return st.one_of(st.sampled_from(setting.accepts), anything)
    if setting.kind == "bool":
        return st.one_of(st.booleans(), st.sampled_from(["true", "false", "TRUE"]), anything)
    lo, hi = setting.accepts
    lo = -1e6 if lo is None else lo
    hi = 1e6 if hi is None else hi
    if setting.kind == "int":
        return st.one_of(st.integers(int(max(lo, -5)), int(min(hi, 5000))), anything)
    return st.one_of(st.floats(max(lo, -1e4), min(hi, 1e4)), anything)


@st.composite
def _case(draw):
    spec = draw(st.sampled_from(WEB))
    profile = setups.get(spec)
    chosen = draw(st.lists(st.sampled_from(profile.settings), min_size=1, max_size=4, unique_by=lambda s: s.key))
    return spec, {s.key: draw(_values(s)) for s in chosen}


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(_case())
def test_fuzzed_settings_build_a_pipeline_or_say_which_key(case):
    spec, changes = case
    try:
        s = setups.build(spec, changes, CAMERA)
    except ValueError as err:
        text = str(err)
        assert "\n" not in text and text
        keys = [st_.key for st_ in setups.get(spec).settings]
        assert any(k in text for k in keys) or "shadow.camera" in text or "cascades are empty" in text, text  # names a setting
        return
    p = s.pipeline
    assert all(0 < a < b for a, b in zip(p.near_i, p.far_i)) and p.resolution >= 1
    if p.k and p.fit != "fixed" or p.fit == "fixed":
        w = pipeline.texels(p, s.camera, LIGHTS)
        assert np.all(np.isfinite(w)) and np.all(w > 0)
        if p.fit != "fixed" or p.depth_range is not None:
            e = pipeline.extents(p, s.camera, LIGHTS)
            assert np.all(np.isfinite(e)) and np.all(e > 0)
            d = p.bias.depth(w[..., 0], 30.0, 0.0, extent=e)
            assert np.all(np.isfinite(d))


# ---------------------------------------------------------------------------------------------
# the splits are the presets the node tests run against the engines (tests/test_engines_js.py)

@pytest.mark.parametrize("near, far", [(0.1, 500.0), (1.0, 100.0), (0.5, 250.0)])
def test_threejs_splits_are_the_checked_presets(near, far):
    for release, preset in (("r187", "threejs-csm"), ("r184", "threejs-csm@r184")):
        for k in (1, 3, 5):
            p = setups.build(f"threejs@{release}", {"cascades": k}, f"near={near},far={far},fov=50").pipeline
            ends = partitioning.split_distances(preset, near, far, k)
            assert np.allclose(p.far_i, ends[1:], rtol=1e-13) and np.allclose(p.near_i, ends[:-1], rtol=1e-13)
            assert p.fit == "diagonal-unrounded" and p.snap == "bevy"


@pytest.mark.parametrize("near, far", [(0.1, 500.0), (1.0, 100.0), (0.5, 250.0)])
def test_babylon_splits_are_the_checked_preset(near, far):
    for k, want in ((None, 4), (2, 2), (3, 3), (1, 2), (9, 4)):
        p = setups.build("babylon", {} if k is None else {"numCascades": k}, f"near={near},far={far},fov=50").pipeline
        ends = partitioning.split_distances("babylon", near, far, want)
        assert np.allclose(p.far_i, ends[1:], rtol=1e-13) and np.allclose(p.near_i, ends[:-1], rtol=1e-13)
    # stabilizeCascades: the stable preset's fit and snap; otherwise the tight box
    stable = setups.build("babylon", {"stabilizeCascades": True}).pipeline
    assert (stable.fit, stable.snap, stable.stable) == ("centroid16", "origin", True)
    assert setups.build("babylon").pipeline.fit == "tight" and not setups.build("babylon").pipeline.stable


def test_babylon_shadow_max_z_and_min_max_distance():
    s = babylon.PROFILES[0].defaults()
    a, b = babylon.splits({**s, "shadowMaxZ": 100.0}, 1.0, 201.0)
    assert b[-1] == pytest.approx(100.0, rel=1e-14) and a[0] == 1.0
    a, b = babylon.splits({**s, "minDistance": 0.1, "maxDistance": 0.6, "lambda": 0.0}, 1.0, 201.0)
    assert a[0] == pytest.approx(21.0) and np.allclose(np.diff(np.r_[a[0], b]), 25.0)  # uniform over 21..121
    # the setter's clamp and reset
    assert np.array_equal(babylon.splits({**s, "minDistance": 0.7, "maxDistance": 0.3}, 1.0, 201.0)[1], babylon.splits(s, 1.0, 201.0)[1])


def test_playcanvas_splits_are_practical_and_float32():
    s = setups.build("playcanvas", {"numCascades": 4, "cascadeDistribution": 0.5}, "near=0.1,far=500,fov=50").pipeline
    ends = partitioning.split_distances("practical", 0.1, 40.0, 4, lam=0.5)[1:]
    assert np.array_equal(s.far_i, ends.astype(np.float32).astype(float))
    assert s.resolution == 512 and s.layout == "atlas 2x2 of 1024" and s.memory == 1024 * 1024 * 4
    one = setups.build("playcanvas").pipeline
    assert one.k == 1 and one.resolution == 1024 and one.far_i == (40.0,)


# ---------------------------------------------------------------------------------------------
# bias rules and faces

@pytest.mark.parametrize("changes, factor", [
    ({}, 1.5),
    ({"depthClamp": False}, 0.5),
    ({"filter": "FILTER_PCSS"}, 0.5),
    ({"filter": "FILTER_NONE"}, 1.0),
    ({"filter": "FILTER_EXPONENTIALSHADOWMAP"}, 1.0),  # CSM does not take it: FILTER_NONE
    ({"class": "ShadowGenerator", "light.shadowFrustumSize": 50.0}, 1.0),
    ({"class": "ShadowGenerator", "light.shadowFrustumSize": 50.0, "filter": "FILTER_PCF"}, 0.5),
])
def test_babylon_bias_factor(changes, factor):
    s = setups.build("babylon", changes, CAMERA)
    term = s.pipeline.bias.term("bias")
    assert babylon.bias_factor(s.settings) == factor
    if s.settings["class"] == "ShadowGenerator":  # over the light's shadowMinZ..shadowMaxZ (the camera's)
        assert term.kind == "depth" and term.scale == pytest.approx(factor * (500.0 - 0.1), rel=1e-15)
    else:
        assert term.kind == "depth_range" and term.scale == factor
        assert s.pipeline.min_extent == (1.0 if s.settings["depthClamp"] and babylon.filter_name(s.settings) != "FILTER_PCSS" else 0.0)


def test_depth_range_terms_need_the_extent():
    rule = setups.build("babylon").pipeline.bias
    assert rule.needs_extent and rule.resolution == 1024
    bare = setups.BiasRule(rule.terms, rule.faces)  # no resolution to fall back on
    with pytest.raises(ValueError, match="^extent is needed for the bias term 'bias'"):
        bare.depth(0.1, 30.0)
    # without an extent the rule takes the map's side w·mapSize (exact for stabilized cascades)
    assert rule.depth(0.1, 30.0) == rule.depth(0.1, 30.0, extent=0.1 * 1024) == pytest.approx(1.5 * 0.00005 * 102.4, rel=1e-14)
    assert rule.minimal("bias", 0.03, 0.1, 30.0) == pytest.approx(0.03 / (1.5 * 102.4), rel=1e-12)
    s = setups.build("babylon", {"stabilizeCascades": True}, CAMERA)
    w = pipeline.texels(s.pipeline, s.camera, LIGHTS)[..., 0]
    assert np.allclose(s.pipeline.bias.depth(w, 20.0), s.pipeline.bias.depth(w, 20.0, extent=pipeline.extents(s.pipeline, s.camera, LIGHTS)),
                       rtol=1e-13)
    # 1.5 × 0.00005 × 200 world units of range; normalBias 0
    assert rule.depth(0.1, 30.0, extent=200.0) == pytest.approx(0.015, rel=1e-14)
    assert rule.contact(0.1, extent=200.0) == pytest.approx(0.015, rel=1e-14)
    assert rule.minimal("bias", 0.03, 0.1, 30.0, extent=200.0) == pytest.approx(1e-4, rel=1e-12)
    # Babylon's normalBias: the caster moves inwards by v·sin θ: v·tan θ along the light
    nb = setups.build("babylon", {"normalBias": 0.02}).pipeline.bias
    assert nb.depth(0.1, 60.0, extent=200.0) - rule.depth(0.1, 60.0, extent=200.0) == pytest.approx(0.02 * math.tan(math.radians(60.0)))
    assert not setups.build("threejs").pipeline.bias.needs_extent


@pytest.mark.parametrize("changes, faces", [
    ({}, "back"),
    ({"material.side": "BackSide"}, "front"),
    ({"material.side": "DoubleSide"}, "both"),
    ({"material.shadowSide": "FrontSide"}, "front"),
    ({"renderer.shadowMap.type": "VSMShadowMap"}, "front"),  # VSM draws the material's own side
    ({"renderer.shadowMap.type": "VSMShadowMap", "material.side": "DoubleSide"}, "both"),
])
def test_threejs_faces(changes, faces):
    assert setups.build("threejs", changes).pipeline.bias.faces == faces


@pytest.mark.parametrize("changes, faces", [
    ({}, "front"), ({"forceBackFacesOnly": True}, "back"), ({"material.backFaceCulling": False}, "both"),
    ({"material.backFaceCulling": False, "forceBackFacesOnly": True}, "back"), ({"material.cullBackFaces": False}, "back"),
])
def test_babylon_faces(changes, faces):
    assert setups.build("babylon", changes).pipeline.bias.faces == faces


def test_playcanvas_rule():
    rule = setups.build("playcanvas").pipeline.bias
    assert rule.faces == "front" and setups.build("playcanvas", {"material.cull": "CULLFACE_NONE"}).pipeline.bias.faces == "both"
    w, ext = 0.05, 40.0
    # slope factor 10·0.05 per texel·tan θ, constant 10·0.05 steps of 2^-24 and the 0.0001 lift of the range
    want = 0.5 * w * math.tan(math.radians(45.0)) + 0.5 * 2.0**-24 * ext + 1e-4 * ext
    assert rule.depth(w, 45.0, 0.0, extent=ext) == pytest.approx(want, rel=1e-14)
    sixteen = [t for t in setups.build("playcanvas", {"shadowType": "SHADOW_PCF3_16F"}).pipeline.bias.terms if t.kind == "depth_range"]
    assert sixteen[0].key == "shadowBias" and sixteen[0].scale == pytest.approx(10.0 / 65535)
    # the needed shadowBias counts both of its terms (slope and constant); the 0.0001 lift stays
    need = rule.minimal("shadowBias", 0.2, w, 45.0, 0.0, extent=ext)
    per = 10 * w * math.tan(math.radians(45.0)) + 10 * 2.0**-24 * ext
    assert need == pytest.approx((0.2 - 1e-4 * ext) / per, rel=1e-12)
    # the component clamps shadowBias to [0, 1]: 3 is 1
    assert setups.build("playcanvas", {"shadowBias": 3.0}).pipeline.bias.term("shadowBias").value == 1.0


def test_threejs_fade_margin_and_bias():
    s = setups.build("threejs", {"fade": True, "maxFar": 200.0}, CAMERA)
    ends = np.asarray(s.pipeline.far_i)
    big = max(500.0, 200.0)  # F = max(camera.far, maxFar)
    assert np.allclose(s.pipeline.grow, 0.25 * (ends / (big - 0.1)) ** 2 * (big - 0.1), rtol=1e-14)
    plain = setups.build("threejs", {"maxFar": 200.0}, CAMERA)
    w, w0 = pipeline.texels(s.pipeline, s.camera, LIGHTS), pipeline.texels(plain.pipeline, plain.camera, LIGHTS)
    assert np.allclose((w - w0) * 2048, np.asarray(s.pipeline.grow)[None, :, None], rtol=1e-12)
    # shadowBias is normalized over lightFar − lightNear; its quirk: 0 reads as 1e-6
    rule = setups.build("threejs", {"shadowBias": 0}).pipeline.bias
    assert rule.term("shadowBias").value == 1e-6 and rule.depth(0.1, 0.0) == pytest.approx(-1e-6 * 1999.0)


def test_filters():
    assert setups.build("threejs").pipeline.filter.taps == 3
    assert setups.build("threejs", {"shadow.radius": 2.0}).pipeline.filter.taps == 5
    assert setups.build("threejs", {"renderer.shadowMap.type": "BasicShadowMap"}).pipeline.filter.kind == "hard"
    assert [setups.build("babylon", {"filteringQuality": q}).pipeline.filter.taps for q in babylon.QUALITIES] == [5, 3, 2]
    assert setups.build("babylon", {"filter": "FILTER_PCSS"}).pipeline.filter.kind == "pcss"
    assert [setups.build("playcanvas", {"shadowType": t}).pipeline.filter.taps for t in ("SHADOW_PCF1_32F", "SHADOW_PCF3_32F", "SHADOW_PCF5_16F")] == [2, 3, 5]
    assert setups.build("playcanvas", {"shadowType": "SHADOW_VSM_16F"}).pipeline.filter.kind == "vsm"


# ---------------------------------------------------------------------------------------------
# the bias presets are views of the profiles

def test_bias_presets_are_views_of_the_profiles():
    three = presets.PRESETS["threejs"]
    rule = setups.build("threejs", {"class": "DirectionalLight"}).pipeline.bias
    assert (three.depth, three.normal, three.pcf, three.faces) == (rule.depth(1.0, 0.0), 0.0, 3, "back")
    assert (three.depth_texels, three.normal_texels, three.across_texels, three.slope) == (0.0, 0.0, 0.0, 0.0)  # the numbers as before
    bab = presets.PRESETS["babylon"]
    assert bab.depth_map == pytest.approx(1.5 * 0.00005, rel=1e-15) and bab.normal_scale == "sin" and bab.pcf == 5 and bab.faces == "front"
    # with the map's side as its depth range (a stabilized cascade), the preset is the profile's rule
    s = setups.build("babylon", {"stabilizeCascades": True}, CAMERA)
    w = pipeline.texels(s.pipeline, s.camera, LIGHTS)[..., 0]
    e = pipeline.extents(s.pipeline, s.camera, LIGHTS)
    got = presets.equivalent_depth(bab, w, 40.0, 10.0, s.pipeline.resolution)
    assert np.allclose(got, s.pipeline.bias.depth(w, 40.0, 10.0, extent=e), rtol=1e-13)
    with pytest.raises(ValueError, match="resolution .* is needed for the babylon preset"):
        presets.equivalent_depth(bab, 0.1, 30.0)


def test_errata_numbers():
    """The numbers docs/ERRATA.md quotes in TJ2, BJ1 and PC1, at the precision printed there."""
    cam = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
    s = setups.build("threejs", {"fade": True}, cam)  # TJ2
    assert [round(g, 3) for g in s.pipeline.grow] == [0.018, 0.082, 0.625]
    sides = pipeline.texels(s.pipeline, s.camera, LIGHTS[:1])[0, :, 0] * s.pipeline.resolution
    assert [round(x) for x in sides] == [160, 345, 952]
    b = setups.build("babylon", {}, cam, sun="30")  # BJ1: the sun 30° up, ahead
    light = b.sun.direction(30.0)[None]
    ext = pipeline.extents(b.pipeline, b.camera, light)[0]
    w = pipeline.texels(b.pipeline, b.camera, light)[0]
    assert [round(x) for x in ext] == [69, 101, 157, 412]
    assert [round(1000 * x, 1) for x in b.pipeline.bias.depth(w[:, 0], 0.0, extent=ext)] == [5.2, 7.6, 11.8, 30.9]
    assert (round(w[:, 0].min(), 2), round(w[:, 0].max(), 2)) == (0.10, 0.81)
    t = setups.build("playcanvas").pipeline.bias.term("shadowBias")  # PC1: the default rasterizer bias
    assert t.value * t.scale == pytest.approx(0.5, rel=1e-15)


def test_errata_tj1_rows():
    """TJ1: the threejs rows (front faces casting) keep their numbers; only `partial` says the faces are not modelled."""
    from aliasing.bias.cascades import cascade_bias

    rows = cascade_bias(0.1, 100.0, 60.0, "gamma:45", "threejs", k=4, resolution=2048)
    assert [(r["margin"], r["acne_from"], r["partial"]) for r in rows] == [(0.0, 0.5, "yes")] * 4


def test_blend_bands():
    from aliasing.setups.profile import Pipeline  # noqa: F401  (the bands are (start, end) eye depths, as Pipeline.bands)

    s = setups.build("babylon", {}, CAMERA)
    bands = babylon.blend_bands(s.settings, 0.1, 500.0)
    p = s.pipeline
    assert len(bands) == p.k - 1
    for (start, end), a, b in zip(bands, p.near_i, p.far_i):
        assert end == b and (end - start) / (b - a) == pytest.approx(p.blend, rel=1e-12)
    assert babylon.blend_bands({**s.settings, "cascadeBlendPercentage": 0.0}, 0.1, 500.0) == ()
    pc = setups.build("playcanvas", {"numCascades": 3, "cascadeBlend": 0.2}, CAMERA)
    assert playcanvas.blend_bands(pc.settings, 0.1, 500.0) == tuple((0.8 * e, e) for e in pc.pipeline.far_i[:-1])
    th = setups.build("threejs", {"fade": True}, CAMERA).pipeline
    b = np.asarray(th.far_i[:-1]) / 500.0
    got = threejs.blend_bands(b, 0.1, 500.0)
    for (s0, e1), x in zip(got, b):  # centred on the break in linear depth z/(far − near), 0.25·b² wide
        assert (s0 + e1) / 2 == pytest.approx(x * 499.9, rel=1e-14) and e1 - s0 == pytest.approx(0.25 * x**2 * 499.9, rel=1e-12)


def test_babylon_shadow_generator_loses_half_a_half_float_step():
    # ERRATA F10: FILTER_NONE stores (z + 1)/2 + bias in a half-float target: the rule loses 2⁻¹² of the light's depth
    # range, no lit gap comes of it, and the bias that removes acne grows by exactly that much (in the engine's units)
    sg = {"class": "ShadowGenerator", "light.shadowFrustumSize": 60.0, "light.shadowMaxZ": 200.0}
    rule = setups.build("babylon", sg, CAMERA).pipeline.bias
    term = rule.term(babylon.HALF_FLOAT)
    assert term.kind == "depth" and not term.contact and term.value * term.scale == -(2.0**-12) * (200.0 - 0.1)
    exact = setups.BiasRule(tuple(t for t in rule.terms if t.key != babylon.HALF_FLOAT), rule.faces)
    w, th, need = 0.06, np.array([5.0, 30.0, 60.0]), np.array([0.001, 0.01, 0.1])
    gain = np.asarray(rule.minimal("bias", need, w, th)) - np.asarray(exact.minimal("bias", need, w, th))
    np.testing.assert_allclose(gain, 2.0**-12, rtol=1e-9)  # factor 1 (FILTER_NONE) over the same range
    assert rule.contact(w) == exact.contact(w)
    pcf = setups.build("babylon", {**sg, "filter": "FILTER_PCF"}, CAMERA).pipeline.bias  # a depth texture: no half float
    assert babylon.HALF_FLOAT not in {t.key for t in pcf.terms}
