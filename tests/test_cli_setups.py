"""One vocabulary on every command: --engine, --settings, --set, --camera, --sun on engines, splits, bias,
shimmer, render and validate, each with the engine's own pipeline; old flags unchanged; bad input one line."""

from __future__ import annotations

import csv
import io
import json
import warnings

import numpy as np
import pytest

from aliasing import setups
from aliasing.check import check
from aliasing.cli import main

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
ENGINE = ["--engine", "threejs", "--set", "cascades=4", "--camera", CAMERA, "--sun", "15..60"]


def _csv(capsys, argv):
    assert main(argv + ["--format", "csv"]) == 0
    return list(csv.DictReader(io.StringIO(capsys.readouterr().out)))


@pytest.fixture(scope="module")
def report():
    return check(setups.build("threejs", {"cascades": 4}, CAMERA, "15..60"))


def test_engines_uses_the_engines_own_cascades(capsys, report):
    rows = _csv(capsys, ["engines"] + ENGINE)
    assert [r["scheme"] for r in rows] == ["threejs@r187", "matched", "exact"]
    assert float(rows[0]["max_error"]) == pytest.approx(max(c["error_max"] for c in report.cascades), rel=1e-9)
    assert float(rows[0]["storage_texels"]) == 4 * 2048**2


def test_engines_old_flags_keep_their_numbers(capsys):
    old = _csv(capsys, ["engines", "--schemes", "csm:log:k=4,matched", "--light", "overhead"])
    assert old[0]["scheme"] == "csm:log:k=4" and float(old[0]["max_error"]) == pytest.approx(9.375, rel=1e-12)  # near 10, far 1e5, 1920 px wide


def test_splits_uses_the_engines_split(capsys, report):
    rows = _csv(capsys, ["splits"] + ENGINE)
    parts = [r for r in rows if r["partition"] != "all"]
    assert [float(r["near"]) for r in parts] == pytest.approx([c["near"] for c in report.cascades], rel=1e-9)
    assert [float(r["far"]) for r in parts] == pytest.approx([c["far"] for c in report.cascades], rel=1e-9)
    assert [float(r["res_s[equal]"]) for r in parts] == [2048.0] * 4  # the budget: 4 maps of 2048²


def test_bias_in_the_engines_units(capsys):
    front = ENGINE + ["--set", "material.shadowSide=FrontSide"]
    rows = _csv(capsys, ["bias"] + front)
    r = check(setups.build("threejs", {"cascades": 4, "material.shadowSide": "FrontSide"}, CAMERA, "15..60"))
    assert [float(row["needed_shadow.normalBias [world units]"]) for row in rows] == [c["needed"]["shadow.normalBias"] for c in r.cascades]
    assert [float(row["acne [fraction]"]) for row in rows] == [1.0] * 4


def test_bias_camera_and_sun_without_engine(capsys):
    via = _csv(capsys, ["bias", "--presets", "filament", "--camera", "near=0.1,far=50,fov=60,aspect=1,height=720", "--sun", "30"])
    old = _csv(capsys, ["bias", "--presets", "filament", "--near", "0.1", "--far", "50", "--fov", "60", "--image", "720", "--light", "gamma:30"])
    assert via == old  # a sun 30° up ahead is gamma 30 in eye space


def test_shimmer_stable_engine_does_not_flip(capsys):
    rows = _csv(capsys, ["shimmer", "--engine", "threejs", "--set", "cascades=2", "--set", "shadowMapSize=128", "--camera", "near=1,far=60,fov=50,aspect=16:9",
                         "--sun", "30@20", "--schemes", "csm:practical:k=2", "--motion", "translate:0,0,0.05", "--frames", "3", "--image-res", "24"])
    assert rows[0]["scheme"] == "threejs@r187" and float(rows[0]["flip_fraction"]) == 0.0
    assert float(rows[1]["flip_fraction"]) > 0.0  # the same split, fitted tightly, unsnapped


def test_render_takes_camera_and_sun(capsys):
    assert main(["render", "--engine", "threejs", "--set", "cascades=2", "--set", "shadowMapSize=64", "--camera", "near=1,far=40,fov=50,aspect=16:9,height=48",
                 "--sun", "40", "--format", "json", "--res", "9"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["camera"]["fov"] == 50.0 and out["camera"]["aspect"] == pytest.approx(16 / 9) and out["image_res"] == 48
    assert out["splits"] == "threejs-csm" and out["budget"] == round(64 * np.sqrt(2)) ** 2
    assert out["gamma"] == pytest.approx(40.0)


def test_validate_takes_camera_and_sun(capsys):
    code = main(["validate", "--scheme", "Standard", "--camera", "near=1,far=20,fov=50,aspect=1,height=100", "--sun", "60", "--res", "64",
                 "--probes", "4", "--format", "json"])
    out = json.loads(capsys.readouterr().out)
    assert code in (0, 1) and out["f_over_n"] == 20.0 and out["fov"] == 50.0 and out["image_res"] == 100 and out["gamma"] == pytest.approx(60.0)


@pytest.mark.parametrize("command", ["engines", "splits", "bias", "render", "validate", "shimmer"])
def test_set_needs_engine_and_radians_warn(capsys, command):
    extra = {"render": [], "validate": ["--scheme", "P"], "shimmer": ["--motion", "translate:0,0,1", "--frames", "2", "--schemes", "csm:log:k=2"]}.get(command, [])
    assert main([command, "--set", "cascades=4"] + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--set needs --engine" in err
    assert main([command, "--engine", "threejs", "--set", "cascads=4"] + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "did you mean 'cascades'" in err


def test_radians_refused_on_another_command(capsys):
    assert main(["engines", "--camera", "near=1,far=100,fov=0.8727", "--schemes", "csm:log:k=2", "--format", "csv"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("aliasing engines: error: camera fov 0.8727 looks like radians (50.00°)")
    assert main(["engines", "--camera", "near=1,far=100,fov=0.8727rad", "--schemes", "csm:log:k=2", "--format", "csv"]) == 0


@settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(st.sampled_from(["engines", "splits", "bias"]), st.one_of(st.none(), st.sampled_from(["threejs", "threejs@r184", "three", "godot@9", ""])),
       st.lists(st.sampled_from(["cascades=2", "mode=uniform", "maxFar=20", "shadowMapSize=0", "x=1", "class=DirectionalLight", "shadowBias=-2"]), max_size=2),
       st.one_of(st.sampled_from(["near=1,far=100", "fov=0.5", "aspect=4:3,height=10", "near=5,far=1", "height=-1"]), st.text(max_size=6)),
       st.one_of(st.none(), st.sampled_from(["30", "10..80@45", "0", "x"]), st.text(max_size=4)))
def test_fuzz_vocabulary(capsys, command, engine, sets, camera, sun):
    argv = [command, "--camera", camera, "--format", "csv"] + (["--engine", engine] if engine is not None else []) + (["--sun", sun] if sun is not None else [])
    argv += ["--light", "overhead"] if command == "engines" and sun is None else []
    for item in sets:
        argv += ["--set", item]
    if command == "engines":
        argv += ["--schemes", "csm:log:k=2"] if engine is None else []
    if command == "splits" and engine is None:
        argv += ["-k", "2"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code
    _, err = capsys.readouterr()
    assert code in (0, 2)
    if code == 2:
        assert err.count("\n") == 1 and "Traceback" not in err


def test_ranges_scheme_is_the_split_it_names():
    from aliasing.engines.compare import compare

    a, b = compare(["csm:ranges=1..10/10..100", "csm:log:k=2"], near=1.0, far=100.0, lights="gamma:40")
    assert {k: v for k, v in a.items() if k != "scheme"} == {k: v for k, v in b.items() if k != "scheme"}
    for bad in ("csm:ranges=10..1", "csm:ranges=1..x", "csm-stable:ranges=:fit=sphere"):
        with pytest.raises(ValueError, match="ranges must be NEAR..FAR"):
            compare([bad], near=1.0, far=100.0, lights="overhead")
