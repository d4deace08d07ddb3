"""The readers of Unity URP's, Unreal's and Filament's own settings files (aliasing.setups.files).

* each sample under tests/files parses the way the engine's source says: a URP asset at
  UniversalRenderPipelineAsset.cs's defaults reads as the profile's defaults; the scene's light,
  additional data, camera and quaternions; Unreal's sections' strength and its ``+ - ! ~`` keys;
  Filament's two JSON shapes and its 35 mm focal length;
* the check of the setup built from a file equals the check of the same settings typed as
  ``--set`` values;
* patch, read back exact, touching only the changed lines; write atomic;
* damaged and foreign files (Hypothesis corruptions of the samples, empty, binary) are refused in
  one line, never a traceback, never a partial write.
"""

from __future__ import annotations

import difflib
import math
import shutil
from pathlib import Path

import pytest

from aliasing import setups
from aliasing.check import check
from aliasing.setups import files
from aliasing.setups.files import FileError
from aliasing.setups.files import unity_urp as urp_reader

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

HERE = Path(__file__).parent / "files"
SAMPLES = ("urp_defaults.asset", "urp_high.asset", "urp_scene.unity", "unreal_DefaultEngine.ini", "unreal_quirks.ini",
           "filament_settings.json", "filament_camera.json")


def _copy(tmp_path: Path, name: str) -> Path:
    return Path(shutil.copy(HERE / name, tmp_path / name))


# ---------------------------------------------------------------- Unity URP


def test_urp_asset_at_the_source_defaults_reads_as_the_profile_defaults():
    found = files.read(HERE / "urp_defaults.asset")
    defaults = setups.get("unity-urp").defaults()
    assert found.engine == "unity-urp"
    assert found.settings == {k: defaults[k] for k in urp_reader.ASSET}
    assert found.where["shadowDistance"] == "urp_defaults.asset line 48 (m_ShadowDistance)"
    assert found.camera is None and found.sun is None


def test_urp_cascade_split_reads_as_those_fractions_and_the_enums_as_names():
    found = files.read(HERE / "urp_high.asset")
    s = found.settings
    assert (s["cascade4Split.x"], s["cascade4Split.y"], s["cascade4Split.z"]) == (0.05, 0.15, 0.4)
    assert (s["shadowCascadeCount"], s["shadowDistance"], s["mainLightShadowmapResolution"]) == (4, 150.0, 4096)
    assert (s["supportsSoftShadows"], s["softShadowQuality"]) == (True, "High")  # m_SoftShadowQuality: 3
    assert any(n.startswith("m_ConservativeEnclosingSphere 1") for n in found.notes)


def test_urp_scene_light_camera_and_sun():
    found = files.read([HERE / "urp_high.asset", HERE / "urp_scene.unity"])
    s = found.settings
    assert (s["light.shadows"], s["light.shadowBias"], s["light.shadowNormalBias"]) == ("Soft", 0.1, 0.6)
    assert (s["light.usePipelineSettings"], s["light.softShadowQuality"]) == (False, "Low")
    assert found.camera == {"near": 0.3, "far": 1000.0, "fov": 60.0}
    assert (found.light, found.camera_name) == ("Directional Light", "Main Camera")
    # Unity's new-scene light (50°, −30°, 0°) seen from a camera yawed −30° too: 50° up, straight behind
    elevation, azimuth = found.sun
    assert elevation == 50.0 and abs(azimuth) == 180.0


def _scene(lights: list[tuple[str, str, str]]) -> str:
    """A scene of directional lights: (name, local rotation x,y,z,w, father transform id or 0)."""
    out = ["%YAML 1.1", "%TAG !u! tag:unity3d.com,2011:"]
    for i, (name, rot, father) in enumerate(lights, 1):
        out += [f"--- !u!1 &{i}00", "GameObject:", f"  m_Name: {name}",
                f"--- !u!4 &{i}01", "Transform:", f"  m_GameObject: {{fileID: {i}00}}", f"  m_LocalRotation: {{{rot}}}",
                f"  m_Father: {{fileID: {father}}}"]
        if name.startswith("Sun"):
            out += [f"--- !u!108 &{i}02", "Light:", f"  m_GameObject: {{fileID: {i}00}}", "  m_Type: 1", "  m_Shadows:", "    m_Type: 1",
                    "    m_Bias: 0.05", "    m_NormalBias: 0.4"]
    return "\n".join(out) + "\n"


def test_urp_light_under_a_rotated_parent_and_several_lights(tmp_path):
    s45 = math.sin(math.radians(45.0) / 2)
    c45 = math.cos(math.radians(45.0) / 2)
    # a pivot pitched 45° holding a light with no rotation of its own: the light shines 45° down
    one = tmp_path / "pivot.unity"
    one.write_text(_scene([("Pivot", f"x: {s45!r}, y: 0, z: 0, w: {c45!r}", "0"), ("Sun", "x: 0, y: 0, z: 0, w: 1", "101")]))
    found = files.read(one)
    assert found.sun == (45.0, 180.0)  # no camera: from world +Z; the sun is behind
    assert found.settings["light.shadows"] == "Hard"
    two = tmp_path / "two.unity"
    two.write_text(_scene([("Sun A", "x: 0.5, y: 0, z: 0, w: 0.8660254", "0"), ("Sun B", "x: 0.2588190, y: 0, z: 0, w: 0.9659258", "0")]))
    with pytest.raises(FileError, match=r"two.unity: light: expected one light, or light= naming one of 'Sun A', 'Sun B', got 2 of them"):
        files.read(two)
    assert files.read(two, light="Sun B").sun[0] == pytest.approx(30.0, abs=1e-5)
    with pytest.raises(FileError, match="'Sun C'"):
        files.read(two, light="Sun C")
    # URP's main light (GetMainLightIndex): RenderSettings.sun, else the brightest directional light
    text = two.read_text()
    two.write_text(text + "--- !u!104 &3\nRenderSettings:\n  m_Sun: {fileID: 202}\n")
    assert files.read(two).light == "Sun B"
    two.write_text(text.replace("  m_Type: 1\n", "  m_Type: 1\n  m_Intensity: 2\n", 1).replace("  m_Type: 1\n  m_Shadows", "  m_Type: 1\n  m_Intensity: 1\n  m_Shadows"))
    found = files.read(two)
    assert found.light == "Sun A" and any("the brightest" in n for n in found.notes)


# ---------------------------------------------------------------- Unreal


def test_unreal_ini_sections_strength_and_notes():
    found = files.read(HERE / "unreal_DefaultEngine.ini")
    assert found.settings == {"r.Shadow.Virtual.Enable": 0, "r.Shadow.CSMDepthBias": 8.0, "r.Shadow.MaxCSMResolution": 4096,
                              "r.Shadow.CSMSlopeScaleDepthBias": 2.5, "r.Shadow.DistanceScale": 1.5,
                              "r.Shadow.ShadowMaxSlopeScaleDepthBias": 0.8}
    # [SystemSettings] (ECVF_SetBySystemSettingsIni) overrides [/Script/Engine.RendererSettings] (ProjectSetting)
    assert found.where["r.Shadow.Virtual.Enable"] == "unreal_DefaultEngine.ini line 21 [SystemSettings]"
    assert any(n.startswith("r.Shadow.CSM.MaxCascades (line 25") for n in found.notes)
    assert any("HORIZONTAL" in n for n in found.notes) and found.camera is None


def test_unreal_ini_quirks():
    found = files.read(HERE / "unreal_quirks.ini")
    # 1024, then +2048 added: the last wins; CSMDepthBias removed by '-'; DistanceScale cleared by '!';
    # 'False' is 0 (ConvertValueFromHumanFriendlyValue); a line without '=' is ignored, with a note
    assert found.settings == {"r.Shadow.MaxCSMResolution": 2048, "r.Shadow.Virtual.Enable": 0}
    assert any("has no '='" in n and "line 15" in n for n in found.notes)


# ---------------------------------------------------------------- Filament


def test_filament_viewer_settings_both_shapes():
    old = files.read(HERE / "filament_settings.json")
    assert old.settings["mapSize"] == 2048 and old.settings["stable"] is True and old.settings["View.shadowType"] == "PCF"
    assert [old.settings[f"cascadeSplitPositions[{i}]"] for i in range(3)] == [0.1, 0.3, 0.5]
    assert old.camera["fov"] == pytest.approx(math.degrees(2 * math.atan(12.0 / 28.0)), rel=1e-12)  # 24 mm frame, 28 mm lens
    assert old.sun[0] == pytest.approx(45.0, abs=1e-9)  # (0.6, −1, −0.8): |y| = √(0.6² + 0.8²)
    new = files.read(HERE / "filament_camera.json")
    assert new.settings["shadowCascades"] == 4 and new.settings["View.shadowType"] == "VSM"
    assert new.camera["near"] == 0.2 and new.sun == (45.0, 0.0)  # the light comes from ahead of the camera


# ---------------------------------------------------------------- the same check as --set

TYPED = {
    "urp": ((HERE / "urp_high.asset", HERE / "urp_scene.unity"), "unity-urp",
            ["shadowDistance=150", "shadowCascadeCount=4", "cascade4Split.x=0.05", "cascade4Split.y=0.15", "cascade4Split.z=0.4",
             "mainLightShadowmapResolution=4096", "shadowDepthBias=0.5", "shadowNormalBias=0.3", "supportsSoftShadows=true",
             "softShadowQuality=High", "light.shadows=Soft", "light.shadowBias=0.1", "light.shadowNormalBias=0.6",
             "light.usePipelineSettings=false", "light.softShadowQuality=Low"], "near=0.3,far=1000,fov=60", "50@180"),
    "unreal": ((HERE / "unreal_DefaultEngine.ini",), "unreal",
               ["r.Shadow.Virtual.Enable=0", "r.Shadow.CSMDepthBias=8", "r.Shadow.MaxCSMResolution=4096", "r.Shadow.CSMSlopeScaleDepthBias=2.5",
                "r.Shadow.DistanceScale=1.5", "r.Shadow.ShadowMaxSlopeScaleDepthBias=0.8"], None, "15..60"),
    "filament": ((HERE / "filament_camera.json",), "filament",
                 ["mapSize=1024", "shadowCascades=4", "cascadeSplitPositions[0]=0.05", "cascadeSplitPositions[1]=0.15",
                  "cascadeSplitPositions[2]=0.4", "normalBias=2", "View.shadowType=VSM"],
                 f"near=0.2,far=400,fov={math.degrees(2 * math.atan(12 / 35))!r}", "45@0"),
}


@pytest.mark.parametrize("name", sorted(TYPED))
def test_check_from_the_file_equals_the_check_of_the_same_set_values(name):
    paths, engine, typed, camera, sun = TYPED[name]
    found = files.read(list(paths))
    sun_found = setups.Sun((found.sun[0], found.sun[0]), found.sun[1]) if found.sun else "15..60"
    from_file = setups.build(found.engine, found.settings, found.camera, sun_found)
    by_hand = setups.build(engine, setups.parse_set(typed), camera, sun)
    assert dict(from_file.settings) == dict(by_hand.settings)
    assert check(from_file).to_dict() == check(by_hand).to_dict()


# ---------------------------------------------------------------- patch and write

PATCHES = {
    "urp_high.asset": {"shadowDistance": 80.0, "cascade4Split.y": 0.2, "softShadowQuality": "Low", "supportsSoftShadows": False},
    "urp_scene.unity": {"light.shadowBias": 0.25, "light.shadows": "Hard", "light.softShadowQuality": "UsePipelineSettings"},
    "unreal_DefaultEngine.ini": {"r.Shadow.CSMDepthBias": 6.5, "r.Shadow.ShadowMaxSlopeScaleDepthBias": 0.5},
    "unreal_quirks.ini": {"r.Shadow.CSMDepthBias": 3.0, "r.Shadow.MaxCSMResolution": 8192},
    "filament_settings.json": {"mapSize": 4096, "cascadeSplitPositions[1]": 0.25, "stable": False},
    "filament_camera.json": {"shadowFarHint": 50.0, "constantBias": 0.0005},
}
# the lines each patch may touch (added lines count as touched at their place)
TOUCHED = {"urp_high.asset": 4, "urp_scene.unity": 3, "unreal_DefaultEngine.ini": 2, "unreal_quirks.ini": 2,
           "filament_settings.json": 3, "filament_camera.json": 1}


@pytest.mark.parametrize("name", sorted(PATCHES))
def test_patch_reads_back_exact_and_touches_only_the_changed_lines(name, tmp_path):
    path = _copy(tmp_path, name)
    before = path.read_text()
    after = files.patch(path, PATCHES[name])
    back = files.read(_write(tmp_path, name, after))
    for key, value in PATCHES[name].items():
        assert back.settings[key] == value and type(back.settings[key]) is type(value)
    changed = [ln for ln in difflib.ndiff(before.splitlines(), after.splitlines()) if ln[:1] in "-+"]
    assert 0 < len([ln for ln in changed if ln[0] == "+"]) <= TOUCHED[name]
    assert len([ln for ln in changed if ln[0] == "-"]) <= len([ln for ln in changed if ln[0] == "+"])
    untouched = {k: v for k, v in files.read(path).settings.items() if k not in PATCHES[name]}
    assert {k: back.settings[k] for k in untouched} == untouched


def _write(tmp_path: Path, name: str, text: str) -> Path:
    out = tmp_path / "out"
    out.mkdir(exist_ok=True)
    p = out / name
    p.write_text(text)
    return p


def test_unreal_absent_cvar_goes_into_the_last_system_settings_section(tmp_path):
    path = _copy(tmp_path, "unreal_quirks.ini")
    lines = files.patch(path, {"r.Shadow.CSMDepthBias": 3.0}).splitlines()
    assert lines[14:16] == ["r.Shadow.CSMSlopeScaleDepthBias 7", "r.Shadow.CSMDepthBias=3"]
    bare = tmp_path / "bare.ini"
    bare.write_text("[/Script/Engine.RendererSettings]\nr.ReflectionMethod=1\n")
    assert files.patch(bare, {"r.Shadow.MaxCSMResolution": 1024}).endswith("\n[SystemSettings]\nr.Shadow.MaxCSMResolution=1024\n")
    with pytest.raises(ValueError, match="ShadowBias is a property of the DirectionalLight"):
        files.patch(bare, {"ShadowBias": 1.0})


def test_filament_absent_key_is_inserted_keeping_the_rest(tmp_path):
    path = _copy(tmp_path, "filament_camera.json")
    text = files.patch(path, {"shadowFarHint": 50.0})
    assert text.replace(', "shadowFarHint": 50.0', "") == path.read_text()
    bare = tmp_path / "bare.json"
    bare.write_text('{"view": {"shadowType": "PCF"}}')
    assert files.patch(bare, {"cascadeSplitPositions[2]": 0.7}) == (
        '{"view": {"shadowType": "PCF"}, "lighting": {"shadowOptions": {"cascadeSplitPositions": [0.125, 0.25, 0.7]}}}')


def test_write_is_atomic_and_refuses_bad_values(tmp_path):
    path = _copy(tmp_path, "urp_high.asset")
    before = path.read_bytes()
    with pytest.raises(ValueError, match=r"shadowCascadeCount must be a whole number in \[1, 4\]"):
        files.write(path, {"shadowCascadeCount": 9})
    with pytest.raises(ValueError, match="unknown Unity URP main light setting 'shadowDistanse' \\(did you mean 'shadowDistance'"):
        files.write(path, {"shadowDistanse": 9.0})
    with pytest.raises(ValueError, match="has no one-line m_Shadows.m_Bias"):
        files.write(path, {"light.shadowBias": 0.2})  # the asset has no light
    assert path.read_bytes() == before
    files.write(path, {"shadowDistance": 75.5})
    assert files.read(path).settings["shadowDistance"] == 75.5
    assert sorted(p.name for p in tmp_path.iterdir()) == ["urp_high.asset"]  # no temporary file left


# ---------------------------------------------------------------- damaged and foreign files


@pytest.mark.parametrize("name, text, message", [
    ("broken.asset", "%YAML 1.1\n--- !u!114 &1\nMonoBehaviour:\n  m_ShadowCascadeCount: 2\n  m_ShadowDistance 80\n",
     "broken.asset: line 5: expected KEY: VALUE at this depth (Unity's YAML), got 'm_ShadowDistance 80'"),
    ("flow.asset", "%YAML 1.1\n--- !u!114 &1\nMonoBehaviour:\n  m_ShadowCascadeCount: 3\n  m_Cascade3Split: {x: 0.1, y: 0.3\n",
     "flow.asset: line 5: expected a flow mapping {KEY: VALUE, …} closed on its line"),
    ("count.asset", "%YAML 1.1\n--- !u!114 &1\nMonoBehaviour:\n  m_ShadowCascadeCount: four\n",
     "count.asset: line 4 / shadowCascadeCount: expected a whole number in [1, 4], got 'four'"),
    ("soft.asset", "%YAML 1.1\n--- !u!114 &1\nMonoBehaviour:\n  m_ShadowCascadeCount: 1\n  m_SoftShadowQuality: 0\n",
     "soft.asset: line 5 / softShadowQuality: expected one of 1 (Low), 2 (Medium), 3 (High), got '0'"),
    ("nan.unity", "%YAML 1.1\n--- !u!20 &1\nCamera:\n  near clip plane: nan\n",
     "nan.unity: line 4 / near clip plane: expected a finite number [m], got 'nan'"),
    ("bad.ini", "[SystemSettings]\nr.Shadow.CSMDepthBias=ten\n",
     "bad.ini: line 2 / r.Shadow.CSMDepthBias: expected a number in [-3.40282e+38, 3.40282e+38] (a 32-bit float), got 'ten'"),
    ("res.ini", "[ConsoleVariables]\nr.Shadow.MaxCSMResolution=2.5\n",
     "res.ini: line 2 / r.Shadow.MaxCSMResolution: expected a whole number in [4, 16384] [texels], got '2.5'"),
    ("none.ini", "; nothing\n", "none.ini: the whole file: expected an Unreal .ini with [Section] lines, got no section"),
    ("shape.json", '{"lighting": {"shadowOptions": [2048]}}',
     "shape.json: line 1 / lighting.shadowOptions: expected a JSON object, got [2048]"),
    ("split.json", '{"lighting": {"shadowOptions": {"cascadeSplitPositions": [0.1, "a", 0.5]}}}',
     "split.json: line 1 / lighting.shadowOptions.cascadeSplitPositions[1]: expected a number in [0, 1] [fraction of (far − near)], got 'a'"),
    ("syntax.json", '{"lighting": {"shadowOptions": {"mapSize": 2048,}}}',
     "syntax.json: line 1 column 49: expected JSON, got Expecting property name enclosed in double quotes"),
    ("inf.json", '{"view": {"shadowType": "PCF"}, "lighting": {"shadowOptions": {"normalBias": Infinity}}}',
     "inf.json: a number: expected a finite JSON number, got Infinity"),
    ("empty.ini", "", "empty.ini: the whole file: expected an Unreal .ini"),
    ("nul.ini", "[SystemSettings]\n\x00\x01", "nul.ini: line 2: expected an Unreal .ini"),
])
def test_damaged_files_are_refused_in_one_line(tmp_path, name, text, message):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(ValueError) as err:
        files.read(path)
    assert str(err.value).startswith(message) and "\n" not in str(err.value)


def test_binary_file_is_refused(tmp_path):
    path = tmp_path / "URP.asset"
    path.write_bytes(b"%YAML\x80\x81\xfe")
    with pytest.raises(FileError, match="URP.asset: byte 5: expected UTF-8 text"):
        files.read(path)


def _corrupt(text: str, data) -> str:
    lines = text.splitlines(keepends=True)
    i = data.draw(st.integers(0, max(len(lines) - 1, 0)))
    how = data.draw(st.sampled_from(["delete", "duplicate", "replace", "truncate", "insert", "flip", "indent"]))
    junk = data.draw(st.text(alphabet=st.sampled_from(list("{}[]:,=-+!;#\"' \t\nxyz019.eE%&*@\\\x00é")), max_size=12))
    if how == "delete":
        del lines[i]
    elif how == "duplicate":
        lines.insert(i, lines[i])
    elif how == "replace":
        lines[i] = junk + "\n"
    elif how == "truncate":
        return text[: data.draw(st.integers(0, len(text)))]
    elif how == "insert":
        k = data.draw(st.integers(0, len(lines[i])))
        lines[i] = lines[i][:k] + junk + lines[i][k:]
    elif how == "flip":
        k = data.draw(st.integers(0, max(len(lines[i]) - 1, 0)))
        lines[i] = lines[i][:k] + junk[:1] + lines[i][k + 1:]
    else:
        lines[i] = " " + lines[i]
    return "".join(lines)


CHANGE = {"urp": ("urp_high.asset", {"shadowDistance": 60.0}), "scene": ("urp_scene.unity", {"light.shadowBias": 0.3}),
          "unreal": ("unreal_DefaultEngine.ini", {"r.Shadow.CSMDepthBias": 5.0}), "quirks": ("unreal_quirks.ini", {"r.Shadow.CSMDepthBias": 5.0}),
          "filament": ("filament_settings.json", {"normalBias": 2.5})}


@pytest.mark.parametrize("case", sorted(CHANGE))
@settings(max_examples=100, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(data=st.data())
def test_corrupted_samples_are_read_or_refused_in_one_line_and_never_half_written(case, data, tmp_path):
    name, change = CHANGE[case]
    text = _corrupt((HERE / name).read_text(), data)
    path = tmp_path / name
    path.write_text(text, newline="")
    before = path.read_bytes()
    try:
        found = files.read(path)
    except ValueError as err:  # FileError, or the dispatcher's "no known format"
        assert "\n" not in str(err) and str(err)
        found = None
    if found is not None:
        assert found.engine == {"urp": "unity-urp", "scene": "unity-urp", "filament": "filament"}.get(case, "unreal")
        if found.sun is not None:
            assert all(math.isfinite(v) for v in found.sun)
    try:
        files.write(path, change)
    except ValueError as err:
        assert "\n" not in str(err)
        assert path.read_bytes() == before  # nothing written
    else:
        assert files.read(path).settings[next(iter(change))] == next(iter(change.values()))
    assert sorted(p.name for p in tmp_path.iterdir()) == [name]


@pytest.mark.parametrize("name", SAMPLES)
def test_every_sample_is_detected_as_its_engine(name):
    engine = {"urp": "unity-urp", "unreal": "unreal", "filament": "filament"}[name.split("_")[0]]
    assert files.detect(HERE / name) == engine


READERS = ("unity_urp", "unreal", "filament")
GARBAGE = st.one_of(st.none(), st.integers(), st.floats(allow_nan=True), st.text(max_size=8), st.lists(st.integers(), max_size=3),
                    st.dictionaries(st.text(max_size=4), st.integers(), max_size=2), st.binary(max_size=4))


@pytest.mark.parametrize("module", READERS)
@settings(max_examples=40, deadline=None, derandomize=True)
@given(files_=GARBAGE, light=GARBAGE, camera=GARBAGE, changes=GARBAGE)
def test_reader_functions_refuse_garbage_naming_the_parameter(module, files_, light, camera, changes):
    import importlib

    mod = importlib.import_module(f"aliasing.setups.files.{module}")
    with pytest.raises(ValueError, match="files|light|camera"):
        mod.read(files_, light, camera)
    sample = {"unity_urp": "urp_high.asset", "unreal": "unreal_DefaultEngine.ini", "filament": "filament_settings.json"}[module]
    path = HERE / sample
    text = path.read_text()
    found = mod.read([(path, text)], None, None)
    with pytest.raises(ValueError, match=r"changes|setting|must be"):
        mod.patch(path, text, changes if not isinstance(changes, dict) or changes else {"": 1}, found)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(value=GARBAGE)
def test_write_refuses_a_garbage_value_naming_the_key(value, tmp_path_factory):
    path = _copy(tmp_path_factory.mktemp("w"), "filament_settings.json")
    before = path.read_bytes()
    try:
        files.write(path, {"mapSize": value})
    except ValueError as err:
        assert str(err).startswith("mapSize must be")
        assert path.read_bytes() == before
    else:
        assert files.read(path).settings["mapSize"] == value
