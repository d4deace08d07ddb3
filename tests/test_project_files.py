"""The engines' own project files: read in the engine's names, units and conventions, and patched in place.

* each format's sample under tests/files (Babylon's and three.js's written by the pinned engines in node,
  PlayCanvas's read back by its own SceneParser, Godot's in its documented text format) reads to the
  settings, camera and sun the engine means: the orientation conventions pinned by known directions;
* ``aliasing check --project FILE`` reports exactly what the same setup typed as --set/--camera/--sun does;
* a patch changes only the changed keys' lines and reads back exactly; ``write`` is atomic;
* damaged and foreign files are refused in one line naming the file and the line or key (exit 2 on the
  command line), also for generated corruptions of the samples;
* where node and the pinned packages are installed, the engine-made samples are regenerated and equal the
  committed ones.
"""

from __future__ import annotations

import contextlib
import difflib
import io
import json
import math
import shutil
import sys
import warnings
from pathlib import Path

import pytest

from conftest import need

from aliasing.cli import main
from aliasing import setups
from aliasing.setups import files
from aliasing.setups.files import FileError

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

HERE = Path(__file__).resolve().parent / "files"
GODOT = [HERE / "project.godot", HERE / "main.tscn"]
BABYLON = HERE / "scene.babylon"
THREE = HERE / "scene.three.json"
PLAYCANVAS = HERE / "scene.playcanvas.json"
SAMPLES = {"godot": GODOT, "babylon": [BABYLON], "threejs": [THREE], "playcanvas": [PLAYCANVAS]}


def _cli(argv, capsys) -> tuple[int, str, str]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


# --- reading: the engines' conventions -------------------------------------------------------------------------------


def test_godot_reads_the_project_settings_the_light_and_camera_with_godots_defaults():
    f = files.read(GODOT)
    assert f.engine == "godot" and f.light == "Lights/Sun" and f.camera_name == "Camera3D"
    assert f.settings == {"rendering/lights_and_shadows/directional_shadow/size": 4096,
                          "rendering/lights_and_shadows/directional_shadow/soft_shadow_filter_quality": 3,
                          "directional_shadow_max_distance": 200.0, "shadow_normal_bias": 1.0}
    assert f.camera == {"fov": 75.0, "near": 0.05, "far": 4000.0}  # Camera3D's defaults: Godot does not write them
    assert f.where["shadow_normal_bias"] == "main.tscn line 17"
    assert any("size.mobile" in n for n in f.notes)  # a feature override is said, not taken


def test_godot_transform_is_the_basis_row_by_row_and_parents_compose():
    """Lights (yaw 30°) ∘ Sun (pitch −50°): the sun 50° up, behind and right of the camera (azimuth 150°).
    Read as columns, the z axis would point below the horizon."""
    el, az = files.read(GODOT).sun
    assert el == pytest.approx(50.0, abs=1e-5) and az == pytest.approx(150.0, abs=1e-5)


def test_godot_enum_keep_aspect_and_light_picking(tmp_path):
    scene = tmp_path / "two.tscn"
    scene.write_text('[gd_scene format=3]\n\n[node name="Main" type="Node3D"]\n\n'
                     '[node name="A" type="DirectionalLight3D" parent="."]\n'
                     'transform = Transform3D(1, 0, 0, 0, 0, 1, 0, -1, 0, 0, 0, 0)\ndirectional_shadow_mode = 0\n\n'
                     '[node name="B" type="DirectionalLight3D" parent="."]\ndirectional_shadow_mode = 1\n\n'
                     '[node name="Cam" type="Camera3D" parent="."]\nkeep_aspect = 0\nfov = 90.0\n')
    with pytest.raises(FileError, match=r"^two\.tscn: DirectionalLight3D: expected one DirectionalLight3D, or --light-node NAME to pick one of: 'A', 'B'"):
        files.read(scene)
    a = files.read(scene, light="A")
    assert a.settings == {"directional_shadow_mode": "SHADOW_ORTHOGONAL"} and a.sun == (90.0, 0.0)  # basis z = +y: straight down
    assert files.read(scene, light="B").settings == {"directional_shadow_mode": "SHADOW_PARALLEL_2_SPLITS"}
    assert a.camera == {"near": 0.05, "far": 4000.0, "horizontal_fov": 90.0}  # KEEP_WIDTH: horizontal
    fields, notes = files.merge_camera(a.camera, {"aspect": "2"})
    assert setups.parse_camera(fields).fov == pytest.approx(math.degrees(2 * math.atan(0.5))) and "horizontal 90°" in notes[0]
    with pytest.raises(FileError, match=r"two\.tscn: DirectionalLight3D 'C': expected one of: 'A', 'B'"):
        files.read(scene, light="C")


def test_godot_refuses_a_parent_from_an_instanced_scene(tmp_path):
    scene = tmp_path / "inst.tscn"
    scene.write_text('[gd_scene format=3]\n[ext_resource type="PackedScene" path="res://rig.tscn" id="1"]\n'
                     '[node name="Main" type="Node3D"]\n[node name="Rig" parent="." instance=ExtResource("1")]\n'
                     '[node name="Sun" type="DirectionalLight3D" parent="Rig"]\n')
    with pytest.raises(FileError, match=r"inst\.tscn: line 4: .*not an instanced scene.*'Rig'"):
        files.read(scene)


def test_babylon_reads_the_serializers_generator_light_and_camera():
    f = files.read(BABYLON)
    assert f.engine == "babylon" and f.light == "sun" and f.camera_name == "camera"
    s = f.settings
    assert (s["class"], s["mapSize"], s["numCascades"], s["lambda"], s["shadowMaxZ"]) == ("CascadedShadowGenerator", 2048, 4, 0.7, 800)
    assert (s["filter"], s["filteringQuality"]) == ("FILTER_PCF", "QUALITY_HIGH")  # usePercentageCloserFiltering, filteringQuality 0
    assert f.camera == {"near": 0.5, "far": 800.0, "fov": math.degrees(0.8)}  # fov in radians, converted
    assert any("0.8 rad (vertical)" in n for n in f.notes)


def test_babylon_azimuth_in_its_left_handed_world(tmp_path):
    """direction (−1, −2, 1): towards the sun (1, 2, −1), i.e. up, behind a camera looking along +z and to its right
    (+x is right in Babylon's left-handed world): azimuth +135°; in a right-handed scene the same numbers are on the left."""
    el, az = files.read(BABYLON).sun
    assert el == pytest.approx(math.degrees(math.asin(2 / math.sqrt(6))), abs=1e-9) and az == pytest.approx(135.0, abs=1e-9)
    data = json.loads(BABYLON.read_text())
    data["useRightHandedSystem"] = True
    p = tmp_path / "rh.babylon"
    p.write_text(json.dumps(data))
    assert files.read(p).sun[1] == pytest.approx(-135.0, abs=1e-9)  # forward +z, right −x in a right-handed world: behind-left


def test_threejs_reads_the_lights_shadow_and_camera_from_its_world_matrices():
    f = files.read(THREE)
    assert f.engine == "threejs" and f.light == "Sun" and f.camera_name == "Camera"
    assert f.settings == {"class": "DirectionalLight", "shadow.bias": -0.0005, "shadow.normalBias": 0.02, "shadow.radius": 1,
                          "shadow.blurSamples": 8, "shadow.mapSize.width": 2048, "shadow.camera.left": -30, "shadow.camera.right": 30,
                          "shadow.camera.top": 30, "shadow.camera.bottom": -30, "shadow.camera.near": 0.5, "shadow.camera.far": 100}
    assert f.camera == {"near": 0.1, "far": 500.0, "fov": 50.0, "aspect": 16 / 9}
    el, az = f.sun  # the light at (10, 19, 10) in a rig lifted by 1: world (10, 20, 10) towards its target at the origin
    assert el == pytest.approx(math.degrees(math.asin(2 / math.sqrt(6))), abs=1e-9) and az == pytest.approx(135.0, abs=1e-9)


def test_playcanvas_reads_what_its_own_scene_parser_makes_of_the_file():
    engine = json.loads((HERE / "scene.playcanvas.parsed.json").read_text())  # PlayCanvas's SceneParser, in node
    f = files.read(PLAYCANVAS)
    names = {"shadowType": {4: "SHADOW_PCF5_32F"}, "vsmBlurMode": {1: "BLUR_GAUSSIAN"}}
    assert f.settings == {k: names[k][v] if k in names else v for k, v in engine["light"].items()}
    c = engine["camera"]
    assert f.camera == {"near": c["nearClip"], "far": c["farClip"], "fov": c["fov"]} and c["horizontalFov"] is False
    assert f.sun == pytest.approx(files.sun_from_directions(engine["towards_light"], engine["camera_forward"]), abs=1e-6)  # float32 there
    assert f.sun == pytest.approx((55.0, -45.0), abs=1e-9)  # the rig's yaw 45° and the light's pitch −35°: ahead-left


# --- the command line: --project is the same setup as typing it ------------------------------------------------------

TYPED = {
    "godot": ["--engine", "godot", "--set", "rendering/lights_and_shadows/directional_shadow/size=4096",
              "--set", "rendering/lights_and_shadows/directional_shadow/soft_shadow_filter_quality=3",
              "--set", "directional_shadow_mode=SHADOW_PARALLEL_4_SPLITS", "--set", "directional_shadow_split_1=0.1",
              "--set", "directional_shadow_split_2=0.2", "--set", "directional_shadow_split_3=0.5", "--set", "shadow_bias=0.1",
              "--set", "directional_shadow_max_distance=200", "--set", "shadow_normal_bias=1.0",
              "--camera", "fov=75,near=0.05,far=4000", "--sun", "49.999998929588@149.999999891584"],
    "babylon": ["--engine", "babylon", "--set", "mapSize=2048", "--set", "numCascades=4", "--set", "lambda=0.7", "--set", "shadowMaxZ=800",
                "--set", "filter=FILTER_PCF", "--camera", f"near=0.5,far=800,fov={math.degrees(0.8)!r}",
                "--sun", "54.735610317245@135"],
    "threejs": ["--engine", "threejs", "--set", "class=DirectionalLight", "--set", "shadow.bias=-0.0005", "--set", "shadow.normalBias=0.02",
                "--set", "shadow.mapSize.width=2048", "--set", "shadow.camera.left=-30", "--set", "shadow.camera.right=30",
                "--set", "shadow.camera.top=30", "--set", "shadow.camera.bottom=-30", "--set", "shadow.camera.near=0.5",
                "--set", "shadow.camera.far=100", "--camera", f"near=0.1,far=500,fov=50,aspect={16 / 9!r}",
                "--sun", "54.735610317245@135"],
    "playcanvas": ["--engine", "playcanvas", "--set", "castShadows=true", "--set", "numCascades=4", "--set", "cascadeDistribution=0.6",
                   "--set", "cascadeBlend=0.1", "--set", "shadowDistance=150", "--set", "shadowResolution=4096", "--set", "shadowBias=0.2",
                   "--set", "normalOffsetBias=0.05", "--set", "shadowType=SHADOW_PCF5_32F", "--set", "vsmBlurMode=BLUR_GAUSSIAN",
                   "--camera", "near=0.2,far=900,fov=55", "--sun", "55@-45"],
}


@pytest.mark.parametrize("engine", sorted(TYPED))
def test_check_of_the_project_is_the_check_of_the_same_setup_typed(engine, capsys):
    project = [a for p in SAMPLES[engine] for a in ("--project", str(p))]
    code, out, err = _cli(["check", *project, "--format", "json"], capsys)
    assert code == 0, err
    code2, typed, err2 = _cli(["check", *TYPED[engine], "--format", "json"], capsys)
    assert code2 == 0, err2
    a, b = json.loads(out), json.loads(typed)
    assert a == b


def test_babylon_fov_in_radians_is_the_exact_degrees(capsys):
    code, out, _ = _cli(["check", "--project", str(BABYLON), "--format", "json"], capsys)
    typed = ["check", "--engine", "babylon", "--set", "mapSize=2048", "--set", "numCascades=4", "--set", "lambda=0.7",
             "--set", "shadowMaxZ=800", "--set", "filter=FILTER_PCF", "--camera", "near=0.5,far=800,fov=45.836623610465864",
             "--sun", "54.735610317245@135", "--format", "json"]
    code2, out2, _ = _cli(typed, capsys)
    assert code == code2 == 0 and out == out2  # byte-equal: 0.8 rad is 45.836623610465864° (math.degrees(0.8))


def test_the_users_values_go_over_the_projects():
    from aliasing import setups
    from aliasing.cli import build_parser

    args = build_parser().parse_args(["check", "--project", str(BABYLON), "--set", "lambda=0.2", "--camera", "far=300", "--sun", "30@10"])
    with pytest.warns(setups.ProjectNote, match=r"camera\.fov 0\.8 rad \(vertical\) = 45\.8366"):
        s = setups.from_args(args)
    assert s.settings["lambda"] == 0.2 and s.settings["mapSize"] == 2048  # --set over the file, the file over the defaults
    assert (s.camera.near, s.camera.far, s.camera.fov) == (0.5, 300.0, math.degrees(0.8))  # --camera's field over the file's
    assert (s.sun.elevation, s.sun.azimuth) == ((30.0, 30.0), 10.0)  # a typed --sun over the file's light
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = setups.from_args(build_parser().parse_args(["check", "--project", str(BABYLON)]))
    assert s.sun.elevation == (54.735610317245, 54.735610317245) and s.sun.azimuth == 135.0  # the file's over --sun's default


@pytest.mark.parametrize("argv, message", [
    (["--project", str(BABYLON), "--engine", "threejs"], "names another engine than the --project files (babylon)"),
    (["--set", "cascades=2"], "--engine NAME[@RELEASE]"),
    (["--engine", "babylon", "--light-node", "sun"], "--light-node picks a node of --project FILE"),
    (["--project", str(BABYLON), "--light-node", "moon"], "scene.babylon: light 'moon': expected one of: 'sun'"),
    (["--project", str(HERE / "missing.tscn")], "cannot be read"),
    (["--project", str(HERE / "project.godot"), "--project", str(BABYLON)], "project files must be one engine's"),
    (["--project", str(THREE), "--camera-node", "Cam"], "scene.three.json: PerspectiveCamera 'Cam': expected one of: 'Camera'"),
])
def test_refusals_are_one_line(argv, message, capsys):
    code, _, err = _cli(["check", *argv], capsys)
    assert code == 2 and err.count("\n") == 1 and message in err, err


# --- patching ---------------------------------------------------------------------------------------------------------

PATCHES = {
    "main.tscn": ({"shadow_bias": 0.07250000000000001, "directional_shadow_mode": "SHADOW_PARALLEL_2_SPLITS", "shadow_normal_bias": 1.5}, 3),
    "project.godot": ({"rendering/lights_and_shadows/directional_shadow/size": 8192,
                       "rendering/lights_and_shadows/directional_shadow/16_bits": False}, 2),
    "scene.babylon": ({"lambda": 0.1 + 0.2, "mapSize": 4096, "filteringQuality": "QUALITY_LOW", "numCascades": 3}, 4),
    "scene.three.json": ({"shadow.bias": -1.25e-05, "shadow.mapSize.width": 4096}, 3),
    "scene.playcanvas.json": ({"shadowBias": 0.123456789012345, "shadowType": "SHADOW_VSM_16F", "numCascades": 2}, 3),
}


@pytest.mark.parametrize("name", sorted(PATCHES))
def test_a_patch_reads_back_exactly_and_changes_only_those_lines(name, tmp_path):
    changes, lines = PATCHES[name]
    p = tmp_path / name
    shutil.copy(HERE / name, p)
    before = p.read_text()
    files.write(p, changes)
    after = p.read_text()
    back = files.read([p] if name != "main.tscn" else [p])
    assert {k: back.settings[k] for k in changes} == changes  # exactly: floats round-trip
    diff = [line for line in difflib.unified_diff(before.splitlines(), after.splitlines(), lineterm="", n=0)
            if line[:1] in "+-" and not line.startswith(("+++", "---"))]
    assert sum(1 for line in diff if line.startswith("+")) == lines, diff
    assert all(line.startswith("+") or line.startswith("-") for line in diff)
    untouched = {k: v for k, v in files.read([p]).settings.items() if k not in changes}
    original = {k: v for k, v in files.read([HERE / name]).settings.items() if k not in changes}
    assert untouched == original


def test_godot_inserts_a_default_property_in_the_lights_section_and_a_missing_rendering_section(tmp_path):
    p = tmp_path / "main.tscn"
    shutil.copy(HERE / "main.tscn", p)
    files.write(p, {"directional_shadow_split_1": 0.15})
    lines = p.read_text().splitlines()
    assert lines[lines.index("directional_shadow_max_distance = 200.0") + 1] == "directional_shadow_split_1 = 0.15"
    q = tmp_path / "project.godot"
    q.write_text("config_version=5\n\n[application]\n\nconfig/name=\"x\"\n")
    files.write(q, {"rendering/lights_and_shadows/directional_shadow/size": 2048})
    assert q.read_text().endswith("[rendering]\n\nlights_and_shadows/directional_shadow/size=2048\n")
    assert files.read(q).settings == {"rendering/lights_and_shadows/directional_shadow/size": 2048}


def test_write_leaves_the_file_unchanged_when_the_patch_does_not_read_back(tmp_path, monkeypatch):
    p = tmp_path / "scene.babylon"
    shutil.copy(BABYLON, p)
    before = p.read_bytes()
    reader = files.reader("babylon")
    real = reader.read

    def wrong(items, light, camera):
        f = real(items, light, camera)
        return files.Found(f.engine, {**f.settings, "lambda": 0.5}, f.camera, f.sun, f.light, f.camera_name, f.where, f.notes)

    monkeypatch.setattr(reader, "read", wrong)
    with pytest.raises(ValueError, match="does not read back as written"):
        files.write(p, {"lambda": 0.9})
    assert p.read_bytes() == before and sorted(x.name for x in tmp_path.iterdir()) == ["scene.babylon"]  # no temporary left


def test_a_key_the_file_does_not_keep_is_refused(tmp_path):
    p = tmp_path / "project.godot"
    shutil.copy(HERE / "project.godot", p)
    with pytest.raises(ValueError, match="shadow_bias is a light property, kept in the scene"):
        files.write(p, {"shadow_bias": 0.2})
    assert p.read_text() == (HERE / "project.godot").read_text()


# --- damaged and foreign files ----------------------------------------------------------------------------------------


@pytest.mark.parametrize("name, text, where", [
    ("scene.babylon", BABYLON.read_text()[:500], r"scene\.babylon: line \d+ column \d+: expected valid JSON"),
    ("main.tscn", "[gd_scene format=3]\n[node name=\"Sun\" type=\"DirectionalLight3D\"]\nshadow_bias 0.1\n",
     r"main\.tscn: line 3: expected a property line"),
    ("main.tscn", "[gd_scene format=3]\n[node name=\"Sun\" type=\"DirectionalLight3D\"]\ntransform = Transform3D(1, 0, 0)\n",
     r"main\.tscn: line 3 transform: expected Transform3D\( 12 numbers"),
    ("main.tscn", "[gd_scene format=3]\n[node name=\"Sun\" type=\"DirectionalLight3D\"]\nshadow_bias = \"x\"\n",
     r"main\.tscn: line 3 shadow_bias: expected a number"),
    ("package.json", '{"name": "x", "version": "1.0.0"}', r"package\.json: the whole file: expected one of"),
    ("scene.babylon", '{"cameras": [], "lights": [], "shadowGenerators": []}', r"scene\.babylon: shadowGenerators: expected a shadow generator"),
    ("empty.tscn", "", r"empty\.tscn: line 1: expected a Godot text file"),
    ("scene.babylon", "", r"scene\.babylon: line 1: expected JSON text, got an empty file"),
    ("scene.babylon", '{"cameras": [], "lights": [{"id": "l", "type": 1, "direction": [0, 0, 0]}], '
                      '"shadowGenerators": [{"lightId": "l", "mapSize": 1024}]}', r"lights\[0\]\.direction: expected a non-zero direction"),
    ("scene.babylon", '{"cameras": [], "lights": [], "shadowGenerators": [{"lightId": "l", "bias": NaN}]}', r"NaN: expected a finite number"),
])
def test_damaged_and_foreign_files_are_refused_naming_the_file_and_place(name, text, where, tmp_path):
    p = tmp_path / name
    p.write_text(text)
    with pytest.raises(ValueError, match=where):
        files.read(p)


def test_a_binary_file_is_refused(tmp_path, capsys):
    p = tmp_path / "scene.babylon"
    p.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe")
    with pytest.raises(FileError, match=r"scene\.babylon: byte \d+: expected UTF-8 text"):
        files.read(p)
    code, _, err = _cli(["check", "--project", str(p)], capsys)
    assert code == 2 and err.count("\n") == 1 and "scene.babylon" in err


def test_a_setting_out_of_the_engines_range_names_where_it_is(tmp_path, capsys):
    p = tmp_path / "scene.babylon"
    p.write_text(BABYLON.read_text().replace('"mapSize": 2048', '"mapSize": -5'))
    code, _, err = _cli(["check", "--project", str(p)], capsys)
    assert code == 2 and "scene.babylon shadowGenerators[0].mapSize: mapSize must be a whole number in [1, 16384]" in err, err


def _corrupt(text: str, data) -> str:
    kind = data.draw(st.sampled_from(["truncate", "replace", "insert", "delete"]))
    i = data.draw(st.integers(0, max(0, len(text) - 1)))
    if kind == "truncate":
        return text[:i]
    j = data.draw(st.integers(i, min(len(text), i + 12)))
    junk = data.draw(st.text(alphabet=st.sampled_from(list('{}[]()",:=\n -.0123456789eNaInfxtrue') + ["\x00", "é"]), max_size=6))
    return text[:i] + (junk if kind != "delete" else "") + text[(j if kind != "insert" else i):]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(name=st.sampled_from(sorted(PATCHES)), data=st.data())
def test_corrupted_samples_are_read_or_refused_and_never_half_patched(name, data, tmp_path):
    text = _corrupt((HERE / name).read_text(), data)
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    try:
        files.read([p])
    except ValueError as exc:
        assert "\n" not in str(exc).strip() and str(exc).startswith((name, "project", "light", "camera")), str(exc)
    changes = dict(list(PATCHES[name][0].items())[:1])
    try:
        files.write(p, changes)
    except ValueError:
        assert p.read_text(encoding="utf-8") == text  # refused: untouched
    else:
        back = files.read([p]).settings
        assert {k: back[k] for k in changes} == changes


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
@given(name=st.sampled_from(["scene.babylon", "main.tscn", "scene.three.json", "scene.playcanvas.json"]), data=st.data())
def test_check_on_a_corrupted_project_is_a_report_or_one_line(name, data, tmp_path_factory):
    p = tmp_path_factory.mktemp("c") / name
    p.write_text(_corrupt((HERE / name).read_text(), data), encoding="utf-8")
    out_err = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        err = io.StringIO()
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = main(["check", "--project", str(p), "--samples", "2", "--format", "json"])
        out_err.append(err.getvalue())
    assert code in (0, 2)
    if code == 2:
        assert out_err[0].count("\n") == 1 and "Traceback" not in out_err[0], out_err[0]


# --- the engine-made samples are the engines' own ---------------------------------------------------------------------


def test_the_engine_made_samples_regenerate_byte_for_byte():
    from aliasing.frames import install

    if shutil.which("node") is None:
        need("node", "Debian: apt-get install nodejs npm")
    for engine in ("babylon", "threejs", "playcanvas"):
        try:
            install.package_root(engine)
        except install.MissingTool as e:
            need(f"the pinned {engine} package", str(e))
    sys.path.insert(0, str(HERE / "make"))
    try:
        import make
    finally:
        sys.path.pop(0)
    for name, text in make.outputs().items():
        assert (HERE / name).read_text(encoding="utf-8") == text, f"{name} differs from what the pinned engine writes now"


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=st.sampled_from(sorted(PATCHES)), value=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=8),
       st.none(), st.booleans(), st.integers(-10**30, 10**30), st.lists(st.integers(), max_size=2)))
def test_a_patch_with_a_bad_value_is_refused_by_key_and_touches_nothing(name, value, tmp_path_factory):
    p = tmp_path_factory.mktemp("v") / name
    p.write_bytes((HERE / name).read_bytes())
    key = next(iter(PATCHES[name][0]))
    try:
        files.write(p, {key: value})
    except ValueError as exc:
        assert str(exc).startswith(f"changes[{key!r}]: "), str(exc)
        assert p.read_bytes() == (HERE / name).read_bytes()
    else:
        back = files.read([p]).settings[key]
        assert back == files.reader(files.detect(p)).PROFILE.setting(key).coerce(value)


def test_threejs_editors_project_keeps_the_renderers_shadow_type_and_its_camera(tmp_path):
    """editor/js/Editor.js toJSON: {"metadata", "project": {"shadows", "shadowType", ...}, "camera", "scene", ...}."""
    scene = json.loads(THREE.read_text())
    camera = {"metadata": scene["metadata"], "object": {**scene["object"]["children"][0], "name": "Viewport", "fov": 40}}
    app = {"metadata": {}, "project": {"shadows": True, "shadowType": 2, "toneMapping": 0, "toneMappingExposure": 1},
           "camera": camera, "scene": scene, "scripts": {}, "history": {}}
    p = tmp_path / "app.json"
    p.write_text(json.dumps(app, indent="\t"))
    f = files.read(p)
    assert f.settings["renderer.shadowMap.type"] == "PCFSoftShadowMap" and f.where["renderer.shadowMap.type"] == "app.json project.shadowType"
    assert f.camera_name == "Viewport" and f.camera["fov"] == 40.0 and f.sun == files.read(THREE).sun  # the app's camera, not the scene's
    files.write(p, {"renderer.shadowMap.type": "VSMShadowMap", "shadow.bias": 0.001})
    assert json.loads(p.read_text())["project"]["shadowType"] == 3 and files.read(p).settings["shadow.bias"] == 0.001
    q = tmp_path / "scene.json"
    q.write_bytes(THREE.read_bytes())
    with pytest.raises(ValueError, match="renderer.shadowMap.type is the renderer's, not kept in scene.toJSON"):
        files.write(q, {"renderer.shadowMap.type": "VSMShadowMap"})


def test_godot_headers_with_groups_and_unique_ids(tmp_path):
    """Godot 4 writes groups=["a", "b"] (with a space) and unique_id=N in node headers."""
    p = tmp_path / "g.tscn"
    p.write_text('[gd_scene load_steps=2 format=3 uid="uid://x"]\n\n[node name="Main" type="Node3D" unique_id=1]\n\n'
                 '[node name="Sun" type="DirectionalLight3D" parent="." groups=["lights", "sun"] unique_id=2]\nshadow_bias = 0.3\n')
    assert files.read(p).settings == {"shadow_bias": 0.3}


def test_babylon_camera_forward_is_the_engines_own():
    """ArcRotateCamera (alpha, beta, radius, target) and FreeCamera (rotation: yaw y, pitch x) as Babylon serializes them,
    against the engine's getDirection(Vector3.Forward()) (float32 there)."""
    reader = files.reader("babylon")
    for case in json.loads((HERE / "babylon_cameras.json").read_text()):
        forward = reader._forward(Path("cameras.json"), "cameras[0]", case["camera"])
        assert forward.tolist() == pytest.approx(case["forward"], abs=1e-6), case["camera"]["type"]


@settings(max_examples=80, deadline=None)
@given(args=st.lists(st.one_of(st.none(), st.booleans(), st.floats(), st.text(max_size=6), st.integers(-10, 10),
                               st.lists(st.floats(), max_size=4), st.dictionaries(st.text(max_size=4), st.floats(), max_size=2)),
                     min_size=3, max_size=3),
       which=st.sampled_from(["sun_from_directions", "vertical_fov", "merge_camera", "detect", "read", "patch"]))
def test_the_public_helpers_refuse_garbage_by_name(args, which):
    fn = getattr(files, which)
    call = {"sun_from_directions": lambda: fn(*args), "vertical_fov": lambda: fn(args[0], args[1]),
            "merge_camera": lambda: fn(args[0], args[1]), "detect": lambda: fn(args[0], args[1]), "read": lambda: fn(args[0], args[1], args[2]),
            "patch": lambda: fn(args[0], args[1])}[which]
    try:
        out = call()
    except ValueError as exc:
        names = {"sun_from_directions": ("towards_sun", "camera_forward", "up"), "vertical_fov": ("hfov", "aspect"),
                 "merge_camera": ("found", "user", "camera"), "detect": ("text", "path", "project"),
                 "read": ("project", "light", "camera"), "patch": ("project", "changes")}[which]
        named_file = isinstance(exc, files.FileError) and which in ("detect", "read", "patch")  # names the file it read
        assert named_file or str(exc).startswith(names) or any(f" {n} " in str(exc) for n in names), str(exc)
    else:
        assert "nan" not in repr(out).lower()


def test_horizontal_fields_of_view_become_vertical_at_the_final_aspect(tmp_path, recwarn):
    from aliasing import setups
    from aliasing.cli import build_parser

    data = json.loads(BABYLON.read_text())
    data["cameras"][0]["fovMode"] = 1  # FOVMODE_HORIZONTAL_FIXED
    p = tmp_path / "h.babylon"
    p.write_text(json.dumps(data))
    assert files.read(p).camera == {"near": 0.5, "far": 800.0, "horizontal_fov": math.degrees(0.8)}
    s = setups.from_args(build_parser().parse_args(["check", "--project", str(p), "--camera", "aspect=2"]))
    assert s.camera.fov == pytest.approx(math.degrees(2 * math.atan(math.tan(0.4) / 2)), rel=1e-12)
    scene = json.loads(PLAYCANVAS.read_text())
    scene["entities"]["camera"]["components"]["camera"]["horizontalFov"] = True
    q = tmp_path / "pc.json"
    q.write_text(json.dumps(scene))
    s = setups.from_args(build_parser().parse_args(["check", "--project", str(q)]))  # the toolkit's 16:9
    assert s.camera.fov == pytest.approx(math.degrees(2 * math.atan(math.tan(math.radians(27.5)) * 9 / 16)), rel=1e-12)
    assert any("horizontal 55° at aspect 1.77778" in str(w.message) for w in recwarn.list)


def test_a_json_patch_inserts_a_key_the_file_leaves_at_the_default(tmp_path):
    p = tmp_path / "scene.json"
    p.write_bytes(PLAYCANVAS.read_bytes())
    files.write(p, {"shadowSamples": 32})
    lines = p.read_text().splitlines()
    at = lines.index('          "shadowSamples": 32,')
    assert lines[at - 1] == '        "light": {' and lines[at + 1] == '          "enabled": true,'  # first in its object, its indentation
    assert files.read(p).settings["shadowSamples"] == 32


def test_the_current_camera_is_taken_and_orthographic_cameras_are_refused(tmp_path):
    p = tmp_path / "cams.tscn"
    p.write_text('[gd_scene format=3]\n[node name="Main" type="Node3D"]\n[node name="A" type="Camera3D" parent="."]\nfov = 40.0\n'
                 '[node name="B" type="Camera3D" parent="."]\ncurrent = true\nfov = 60.0\n'
                 '[node name="C" type="Camera3D" parent="."]\nprojection = 1\n')
    f = files.read(p)
    assert f.camera_name == "B" and f.camera["fov"] == 60.0  # Camera3D.current: the one Godot renders with
    assert files.read(p, camera="A").camera["fov"] == 40.0
    with pytest.raises(FileError, match=r"cams\.tscn: line 9 projection: expected 0 \(PROJECTION_PERSPECTIVE\)"):
        files.read(p, camera="C")
    data = json.loads(BABYLON.read_text())
    data["cameras"][0]["mode"] = 1
    q = tmp_path / "o.babylon"
    q.write_text(json.dumps(data))
    with pytest.raises(FileError, match=r"o\.babylon: cameras\[0\]\.mode: expected 0 \(PERSPECTIVE_CAMERA\)"):
        files.read(q)
    scene = json.loads(PLAYCANVAS.read_text())
    scene["entities"]["camera"]["components"]["camera"]["projection"] = 1
    r = tmp_path / "o.json"
    r.write_text(json.dumps(scene))
    with pytest.raises(FileError, match=r"o\.json: entities\.camera\.components\.camera\.projection: expected 0"):
        files.read(r)


def test_babylon_filter_flags_round_trip_and_filter_none_is_refused_with_the_reason(tmp_path):
    p = tmp_path / "scene.babylon"
    p.write_bytes(BABYLON.read_bytes())
    files.write(p, {"filter": "FILTER_PCSS"})
    data = json.loads(p.read_text())["shadowGenerators"][0]
    assert data["useContactHardeningShadow"] is True and data["usePercentageCloserFiltering"] is False
    assert files.read(p).settings["filter"] == "FILTER_PCSS"
    files.write(p, {"filter": None})  # no flag: the class's default
    assert "filter" not in files.read(p).settings
    before = p.read_bytes()
    with pytest.raises(ValueError, match="cannot keep filter FILTER_NONE: ShadowGenerator.Parse leaves the class's default"):
        files.write(p, {"filter": "FILTER_NONE"})
    assert p.read_bytes() == before
