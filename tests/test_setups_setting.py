"""Enumerations as the engines spell them: the constants, their short forms, qualified names, the editor's
labels and the integers the engines' files store, each taken to the canonical spelling."""

from __future__ import annotations

import json

import pytest

from aliasing import setups
from aliasing.cli import main
from aliasing.setups.setting import _affixes as affixes

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
NAMED = [(p, s) for e in setups.ENGINES for p in setups.profiles(e) for s in p.settings if s.kind == "choice" or s.aliases]


def _settings_json(capsys, engine, items):
    argv = ["check", "--engine", engine, "--camera", CAMERA, "--sun", "30", "--format", "json"]
    for item in items:
        argv += ["--set", item]
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)["settings"]


@pytest.mark.parametrize("engine, key, spellings, canonical", [
    ("godot", "directional_shadow_mode", ["2", "SHADOW_PARALLEL_4_SPLITS", "PARALLEL_4_SPLITS", "DirectionalLight3D.SHADOW_PARALLEL_4_SPLITS",
                                          "parallel 4 splits"], "SHADOW_PARALLEL_4_SPLITS"),
    ("godot", "directional_shadow_mode", ["1", "SHADOW_PARALLEL_2_SPLITS"], "SHADOW_PARALLEL_2_SPLITS"),
    ("godot", "directional_shadow_mode", ["0", "orthogonal"], "SHADOW_ORTHOGONAL"),
    ("godot", "rendering/lights_and_shadows/directional_shadow/soft_shadow_filter_quality",
     ["2", "SOFT_LOW", "Soft Low", "Soft Low (Fast)", "RenderingServer.SHADOW_QUALITY_SOFT_LOW"], 2),
    ("babylon", "filteringQuality", ["0", "high", "QUALITY_HIGH", "ShadowGenerator.QUALITY_HIGH", "BABYLON.ShadowGenerator.QUALITY_HIGH"],
     "QUALITY_HIGH"),
    ("babylon", "filteringQuality", ["2", "low"], "QUALITY_LOW"),
    ("babylon", "filter", ["6", "PCF", "ShadowGenerator.FILTER_PCF"], "FILTER_PCF"),
    ("threejs", "renderer.shadowMap.type", ["1", "THREE.PCFShadowMap", "PCFShadowMap", "pcf"], "PCFShadowMap"),
    ("threejs", "renderer.shadowMap.type", ["3", "VSM"], "VSMShadowMap"),
    ("threejs", "material.shadowSide", ["0", "THREE.FrontSide", "FrontSide", "front"], "FrontSide"),
    ("threejs", "material.side", ["2", "THREE.DoubleSide"], "DoubleSide"),
    ("playcanvas", "shadowType", ["0", "SHADOW_PCF3", "pc.SHADOW_PCF3_32F", "PCF3_32F"], "SHADOW_PCF3_32F"),
    ("playcanvas", "shadowType", ["4", "SHADOW_PCF5"], "SHADOW_PCF5_32F"),
    ("playcanvas", "material.cull", ["1", "pc.CULLFACE_BACK", "back"], "CULLFACE_BACK"),
    ("playcanvas", "vsmBlurMode", ["0", "box"], "BLUR_BOX"),
    ("unity-urp", "softShadowQuality", ["3", "High", "SoftShadowQuality.High"], "High"),
    ("unity-urp", "light.shadows", ["1", "LightShadows.Hard"], "Hard"),
    ("filament", "View.shadowType", ["1", "VSM", "View::ShadowType::VSM", "ShadowType.VSM"], "VSM"),
])
def test_engine_spellings_reach_the_canonical(capsys, engine, key, spellings, canonical):
    for text in spellings:
        assert _settings_json(capsys, engine, [f"{key}={text}"])[key] == canonical, text
    setting = setups.get(engine).setting(key)
    numbers = [int(t) for t in spellings if t.isdigit()]
    for n in numbers:  # an integer from a JSON or TOML file, not only a text
        assert setting.coerce(n) == canonical


def test_godot_mode_2_is_the_same_setup():
    a = setups.build("godot", {"directional_shadow_mode": 2}, CAMERA)
    b = setups.build("godot", {"directional_shadow_mode": "SHADOW_PARALLEL_4_SPLITS"}, CAMERA)
    assert a.settings == b.settings and a.pipeline.near_i == b.pipeline.near_i


@pytest.mark.parametrize("profile, setting", NAMED, ids=[f"{p.name}-{s.key}" for p, s in NAMED])
def test_every_spelling_of_every_enum(profile, setting):
    for spelling, value in setting.names().items():
        assert setting.coerce(spelling) == value
        if isinstance(spelling, str):
            assert setting.coerce(spelling.upper()) == value
            assert setting.coerce(f"{profile.title.split()[0]}.{spelling}") == value
    for c in (setting.accepts if setting.kind == "choice" else ()):
        assert setting.coerce(c) == c and setting.coerce(f" {str(c).lower()} ") == c


@pytest.mark.parametrize("profile, setting", NAMED, ids=[f"{p.name}-{s.key}" for p, s in NAMED])
def test_typos_still_get_a_did_you_mean(profile, setting):
    if setting.kind != "choice":
        return
    first = str(setting.accepts[-1])
    typo = first[:-1] + ("x" if first[-1] != "x" else "y") + "q"
    with pytest.raises(ValueError, match=rf"^{setting.key} must be one of .*did you mean") as err:
        setting.coerce(typo)
    assert "\n" not in str(err.value)


def test_numbers_outside_the_table_are_refused():
    s = setups.get("babylon").setting("filteringQuality")
    for bad in (3, -1, "7", True, 0.5, None):
        with pytest.raises(ValueError, match=r"^filteringQuality must be one of 'QUALITY_HIGH'.*numbers 0, 1, 2"):
            s.coerce(bad)


def test_short_forms_need_a_word_edge():
    assert affixes(["SHADOW_PCF3_32F", "SHADOW_VSM_16F"]) == (7, 0)  # "F" is no word
    assert affixes(["FrontSide", "BackSide"]) == (0, 4)
    assert affixes(["Low", "Medium"]) == (0, 0)


def test_a_short_form_two_choices_share_is_left_out():
    s = setups.Setting("x", "A_ONE", "", "choice", ("A_ONE", "A_TWO"), aliases={"one": "A_TWO"})
    assert "one" not in s.names() and s.coerce("A_ONE") == "A_ONE"
    with pytest.raises(ValueError, match="names 'B'"):
        setups.Setting("x", "A", "", "choice", ("A",), aliases={0: "B"})


@settings(max_examples=150, deadline=None, derandomize=True)
@given(st.sampled_from(NAMED), st.one_of(st.text(max_size=20), st.integers(-5, 20), st.floats(), st.none(), st.booleans()))
def test_generated_spellings_give_a_value_or_one_line(pair, value):
    profile, setting = pair
    try:
        out = setting.coerce(value)
    except ValueError as exc:
        assert str(exc).startswith(setting.key) and "\n" not in str(exc)
    else:
        assert (out is None and setting.default is None) or (out in setting.accepts if setting.kind == "choice" else isinstance(out, int))
