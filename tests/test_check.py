"""``aliasing check`` and :func:`aliasing.check.check`: the JSON contract, the needed settings fed back,
verdicts naming settings, bad input as one line, a field of view in radians refused, and fuzzing."""

from __future__ import annotations

import json
import math
import warnings

import numpy as np
import pytest

from aliasing import setups
from aliasing.check import Report, check
from aliasing.cli import main
from aliasing.engines import pipeline as engine_pipeline

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
BASE = ["check", "--engine", "threejs", "--set", "cascades=4", "--set", "shadowMapSize=2048", "--camera", CAMERA, "--sun", "15..60"]


def _json(capsys, argv):
    assert main(argv + ["--format", "json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_contract(capsys):
    out = _json(capsys, BASE)
    assert set(out) == {"engine", "release", "settings", "cascades", "units", "verdicts"}
    assert (out["engine"], out["release"]) == ("threejs", "r187")
    profile = setups.get("threejs")
    assert list(out["settings"]) == [s.key for s in profile.settings]  # every key, as three.js spells it
    assert out["settings"]["cascades"] == 4 and out["settings"]["shadowBias"] == 1e-6
    assert len(out["cascades"]) == 4
    for c in out["cascades"]:
        assert {"near", "far", "texel", "error_max", "needed", "acne", "gap_px"} <= set(c)
        assert len(c["texel"]) == 2 and set(c["needed"]) == {"shadowBias", "shadow.normalBias"}
        assert 0.0 <= c["acne"] <= 1.0 and c["gap_px"] >= 0
    assert all(isinstance(v, str) for v in out["verdicts"]) and out["verdicts"]


def test_texel_is_the_engines_fit_over_the_map_size():
    s = setups.build("threejs", {"cascades": 4, "shadowMapSize": 1024}, CAMERA, "15..60")
    r = check(s)
    lv = s.sun.direction(s.sun.elevations(7))
    want = engine_pipeline.texels(s.pipeline, s.camera, lv).max(axis=0)
    got = np.array([c["texel"] for c in r.cascades])
    assert np.array_equal(got, want)
    res = engine_pipeline.result(s.pipeline, s.camera, lv)  # texel = width / resolution
    assert np.allclose(got[:, 0], res.width_x.max(axis=0) / 1024, rtol=1e-12)
    assert [c["near"] for c in r.cascades] == list(s.pipeline.near_i)


def test_error_is_texel_over_pixel_at_the_near_end():
    s = setups.build("threejs", {"cascades": 4}, CAMERA, 30)
    r = check(s)
    t = math.tan(math.radians(25.0))
    for c in r.cascades:
        pixel = 2 * c["near"] * t / 1080
        assert c["error_max"] == pytest.approx(max(c["texel"]) / pixel, rel=1e-12)


@pytest.mark.parametrize("key", ["shadowBias", "shadow.normalBias"])
def test_needed_values_fed_back_remove_the_acne(capsys, key):
    front = BASE + ["--set", "material.shadowSide=FrontSide"]
    out = _json(capsys, front)
    assert all(c["acne"] > 0 for c in out["cascades"])  # front faces cast: the defaults acne
    sign = -1 if key == "shadowBias" else 1
    for i, c in enumerate(out["cascades"]):
        v = c["needed"][key]
        fixed = _json(capsys, front + ["--set", f"{key}={v!r}"])
        assert fixed["cascades"][i]["acne"] == 0.0
        worse = _json(capsys, front + ["--set", f"{key}={v - sign * 0.02 * abs(v)!r}"])  # 2 % short of the need
        assert worse["cascades"][i]["acne"] > 0.0
    # the largest texel needs the most
    values = [sign * c["needed"][key] for c in out["cascades"]]
    assert values == sorted(values)


def test_back_faces_do_not_acne_and_the_verdict_says_so():
    r = check(setups.build("threejs", {"cascades": 4}, CAMERA, "15..60"))
    assert all(c["acne"] == 0.0 for c in r.cascades)
    assert any("back faces" in v for v in r.verdicts)


def test_verdicts_name_the_setting_and_its_value():
    s = setups.build("threejs", {"cascades": 4, "material.shadowSide": "FrontSide"}, CAMERA, "15..60")
    r = check(s)
    acne = [v for v in r.verdicts if "acnes" in v]
    assert len(acne) == 4
    for v, c in zip(acne, r.cascades):
        assert "shadowBias ≤ " in v and "shadow.normalBias ≥ " in v
        shown = float(v.split("shadow.normalBias ≥ ")[1].split()[0])
        assert shown >= c["needed"]["shadow.normalBias"]  # rounded on the safe side
        assert check(s.with_settings(**{"shadow.normalBias": shown})).cascades[c["cascade"]]["acne"] == 0.0


def test_peter_panning_grows_with_the_depth_bias():
    s = setups.build("threejs", {"cascades": 4, "material.shadowSide": "FrontSide"}, CAMERA, "15..60")
    a = check(s.with_settings(shadowBias=-0.0005)).cascades
    b = check(s.with_settings(shadowBias=-0.001)).cascades
    assert all(y["gap_px"] == pytest.approx(2 * x["gap_px"] + 0.0, rel=0.01) for x, y in zip(a, b))  # 1e-6·1999 m less
    assert all(c["gap_px"] == 0.0 for c in check(s).cascades)  # 1e-6 lowers the receiver: no gap


def test_stable_pipeline_does_not_shimmer_and_a_fixed_box_is_one_cascade():
    r = check(setups.build("threejs", {"cascades": 4}, CAMERA, "15..60"))
    assert all(c["shimmer_px"] == 0.0 for c in r.cascades)
    assert r.cascades[-1]["seam_step"] is None and all(c["seam_step"] > 1 for c in r.cascades[:-1])
    fixed = check(setups.build("threejs", {"class": "DirectionalLight"}, CAMERA, "30"))
    assert len(fixed.cascades) == 1 and fixed.cascades[0]["texel"] == [10 / 512, 10 / 512]


def test_rows_and_text():
    r = check(setups.build("threejs", {"cascades": 4}, CAMERA, "15..60"))
    rows = r.to_rows()
    assert [row["cascade"] for row in rows] == [0, 1, 2, 3]
    assert "needed_shadowBias" in rows[0] and rows[0]["texel_s"] == r.cascades[0]["texel"][0]
    assert "cascade" in r.text() and r.to_csv().count("\n") == 5


def test_bad_parameters():
    s = setups.build("threejs", camera=CAMERA)
    for kwargs, name in (({"receivers": [95.0]}, "receivers"), ({"walk": -1.0}, "walk"), ({"samples": 0}, "samples"),
                         ({"walk": np.ones(2)}, "walk"), ({"scene": 42, "eye": "0,1,0", "target": "0,1,1"}, "scene"),
                         ({"scene": "boxes", "pixels": 8}, "pixels")):
        with pytest.raises(ValueError, match=name):
            check(s, **kwargs)
    with pytest.raises(ValueError, match="setup"):
        check("threejs")


@pytest.mark.parametrize("argv, words", [
    (["--set", "shadowBas=0.1"], "did you mean 'shadowBias'"),
    (["--set", "shadowBias=2"], "shadowBias must be a number in [-1, 1]"),
    (["--set", "cascades=two"], "cascades must be a whole number"),
    (["--set", "mode=fast"], "mode must be one of"),
    (["--sun", "15...60"], "sun"),
    (["--sun", "95"], "sun elevation must be in (0, 90]"),
    (["--camera", "near=0.1,farr=500"], "did you mean 'far'"),
    (["--camera", "near=0.1,far=500,fov=abc"], "camera fov must be a number"),
    (["--engine", "three"], "engine"),
    (["--engine", "threejs@r99"], "release"),
])
def test_bad_input_is_one_line(capsys, argv, words):
    assert main(BASE + argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("aliasing check: error: ") and words in err


@pytest.mark.parametrize("suffix, text, words", [
    (".json", "{\"shadowBias\": ", "not valid JSON"),
    (".toml", "shadowBias = = 1", "not valid TOML"),
    (".json", "{\"shadowbias\": 0.001}", "did you mean 'shadowBias'"),
    (".json", "{\"fade\": 1}", "fade must be true or false"),
    (".toml", "lightMargin = -5", "lightMargin must be a number >= 0"),
    (".json", "[1, 2]", "must hold a table of settings"),
])
def test_bad_settings_files(tmp_path, capsys, suffix, text, words):
    f = tmp_path / f"s{suffix}"
    f.write_text(text)
    assert main(BASE + ["--settings", str(f)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err


def test_settings_file_nested_toml(tmp_path, capsys):
    f = tmp_path / "s.toml"
    f.write_text("cascades = 2\n[shadow]\nnormalBias = 0.5\n")
    out = _json(capsys, ["check", "--engine", "threejs", "--settings", str(f), "--set", "cascades=3", "--camera", CAMERA])
    assert out["settings"]["cascades"] == 3 and out["settings"]["shadow.normalBias"] == 0.5  # --set over the file


def test_radians_refused_in_one_line(capsys):
    assert main(["check", "--engine", "threejs", "--camera", "fov=0.8727", "--format", "csv"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("aliasing check: error: camera fov 0.8727 looks like radians (50.00°)")
    assert "fov=50.00 (degrees) or fov=0.8727rad" in err and "fov=0.8727deg" in err


FIELDS = ["cascades=4", "cascades=0", "cascades=-1", "shadowBias=-0.001", "shadowBias=nan", "shadow.normalBias=0.3", "mode=uniform",
          "mode=custom", "customSplitsLambda=0.9", "maxFar=50", "maxFar=0.05", "class=DirectionalLight", "material.shadowSide=FrontSide",
          "shadow.camera.left=5", "renderer.shadowMap.type=BasicShadowMap", "shadow.radius=20", "x=1", "=", "fade=true", "lightFar=1e308"]
CAMERAS = [CAMERA, "fov=0.8", "near=1,far=1.0000001", "aspect=0:1", "height=0", "height=1.5", "aspect=21:9,height=2160", "fov=179.9",
           "far=1e300", "near=-1", ",,", "fov"]
SUNS = ["15..60", "90", "0", "1..1@180", "60..15", "30@nan", "a", "45@-30", "89.99..90"]


@settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(st.lists(st.one_of(st.sampled_from(FIELDS), st.text(max_size=8)), max_size=3), st.one_of(st.sampled_from(CAMERAS), st.text(max_size=10)),
       st.one_of(st.sampled_from(SUNS), st.text(max_size=6)), st.sampled_from(["table", "csv", "json"]))
def test_fuzz_cli(capsys, sets, camera, sun, fmt):
    argv = ["check", "--engine", "threejs", "--camera", camera, "--sun", sun, "--format", fmt]
    for item in sets:
        argv += ["--set", item]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse: an option-like value ("--x")
            code = exc.code
    out, err = capsys.readouterr()
    assert code in (0, 2)
    if code == 2:
        assert err.count("\n") == 1 and "Traceback" not in err
    elif fmt == "json":
        data = json.loads(out)
        assert all(math.isfinite(c["error_max"]) for c in data["cascades"])


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.one_of(st.none(), st.floats(allow_nan=True), st.lists(st.floats(-10, 100), max_size=3)), st.one_of(st.floats(), st.integers(-2, 3)),
       st.one_of(st.integers(-1, 20), st.floats()))
def test_fuzz_api(receivers, walk, samples):
    s = setups.build("threejs", {"cascades": 2}, CAMERA, "20..50")
    try:
        r = check(s, receivers=receivers, walk=walk, samples=samples)
    except ValueError:
        return
    assert isinstance(r, Report) and all(0.0 <= c["acne"] <= 1.0 for c in r.cascades)
    json.dumps(r.to_dict(), allow_nan=False)


def test_readme_states_what_check_says():
    """The README's first screen: its verdict line and the figure's numbers are what check computes."""
    from pathlib import Path

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text()
    s = setups.build("threejs", {"cascades": 4, "shadowMapSize": 2048, "material.shadowSide": "FrontSide"}, CAMERA, "15..60")
    r = check(s)
    line = next(v for v in r.verdicts if v.startswith("cascade 3 acnes"))
    assert f"- {line}\n" in readme
    assert "`shadow.normalBias` ≥ 0.68" in readme and line.endswith("shadow.normalBias ≥ 0.68")
    common = min(c["needed"]["shadowBias"] for c in r.cascades)
    gap = check(s.with_settings(shadowBias=common)).cascades[0]["gap_px"]
    assert f"{gap:.0f}-pixel gap" in readme and round(gap) == 92


def test_guide_page_states_what_the_commands_compute():
    """docs/guide/engines-check.rst: every number it states, recomputed."""
    from pathlib import Path

    page = (Path(__file__).resolve().parents[1] / "docs" / "guide" / "engines-check.rst").read_text()
    flat = " ".join(page.split())
    base = {"cascades": 4, "shadowMapSize": 2048}
    r = check(setups.build("threejs", base, CAMERA, "15..60"))
    cm = ", ".join(f"{max(c['texel']) * 100:.1f} cm" for c in r.cascades[:3]) + f" and {max(r.cascades[3]['texel']) * 100:.1f} cm"
    assert cm in flat
    errs = [f"{c['error_max']:.3g}" for c in r.cascades]
    assert f"{errs[0]}, {errs[1]}, {errs[2]} and {errs[3]}" in flat and errs == ["677", "2.2", "1.82", "2.48"]
    front = check(setups.build("threejs", base | {"material.shadowSide": "FrontSide"}, CAMERA, "15..60"))
    nb = [c["needed"]["shadow.normalBias"] for c in front.cascades]
    assert [f"{v:.2g}" for v in nb] == ["0.085", "0.17", "0.29", "0.67"]  # the page gives them rounded up (safe side)
    assert "(0.086, 0.18, 0.3 and 0.68 m;" in flat and all(float(x) >= v for x, v in zip(("0.086", "0.18", "0.3", "0.68"), nb))
    sb = min(c["needed"]["shadowBias"] for c in front.cascades)
    assert "at or below −0.0014" in flat and -0.0014 <= sb < -0.0013
    cost = [c["stable_cost"] for c in r.cascades]
    assert all(f"{c:.4g}" == "1.147" for c in cost) and "1.147 in every cascade" in flat
    assert np.allclose(cost, math.sqrt(1 + (9 / 16) ** 2), rtol=1e-12)
    log = check(setups.build("threejs", base | {"mode": "logarithmic"}, CAMERA, "15..60"))
    assert all(f"{c['error_max']:.3g}" == "9.05" for c in log.cascades) and "same ``error_max``, 9.05" in page


def test_engine_fit_against_the_bias_preset():
    """docs/ERRATA.md G3: the tight fit of `bias --presets threejs` against three.js's own box, and the face rule."""
    from aliasing.bias.cascades import cascade_bias

    rows = cascade_bias(0.1, 500.0, 50.0, "gamma:30", "threejs", splits="threejs-csm", k=4, resolution=2048, image=1080, aspect=16 / 9)
    r = check(setups.build("threejs", {"cascades": 4}, CAMERA, "30"))
    ratio_t = [c["texel"][1] / a["texel_t"] for a, c in zip(rows, r.cascades)]
    ratio_s = [c["texel"][0] / a["texel_s"] for a, c in zip(rows, r.cascades)]
    assert [a["near"] for a in rows] == pytest.approx([c["near"] for c in r.cascades], rel=1e-12)
    assert 2.1 <= min(ratio_t) and max(ratio_t) <= 2.25
    assert ratio_s == pytest.approx([math.sqrt(1 + (9 / 16) ** 2)] * 4, rel=1e-9)
    assert all(a["margin"] == 0.0 for a in rows) and all(c["acne"] == 0.0 for c in r.cascades)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.text(max_size=30), st.text(max_size=14), st.text(max_size=40))
def test_fuzz_specs(camera, sun, settings_text):
    """The camera and sun specs and a settings file's text: a value or a ValueError, nothing else."""
    import tempfile
    from pathlib import Path

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for parse, text in ((setups.parse_camera, camera), (setups.parse_sun, sun)):
            try:
                parse(text)
            except ValueError:
                pass
    with tempfile.TemporaryDirectory() as d:
        for suffix in (".json", ".toml"):
            f = Path(d) / f"s{suffix}"
            f.write_text(settings_text, encoding="utf-8")
            try:
                values = setups.load_settings(f)
                setups.build("threejs", values)
            except ValueError:
                pass
