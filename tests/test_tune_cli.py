"""``aliasing tune``: the JSON contract, the round trip through ``aliasing check --settings``, bad input."""

from __future__ import annotations

import json

import pytest

from aliasing.cli import main

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
# the perspective objective (the papers' measure) is what these tests pin; the wrong-pixel objective has tests/test_tune_pixels.py
BASE = ["tune", "--objective", "perspective", "--engine", "threejs", "--camera", CAMERA, "--sun", "15..60", "--set", "cascades=4",
        "--set", "shadowMapSize=2048", "--keep", "cascades,shadowMapSize"]


def _json(capsys, argv, code=0):
    assert main(argv + ["--format", "json"]) == code
    out = capsys.readouterr()
    return json.loads(out.out), out.err


def test_json_contract_and_round_trip(capsys, tmp_path):
    got, err = _json(capsys, BASE + ["--set", "material.shadowSide=FrontSide", "--receivers", "1..200", "--max-slope", "5"])
    assert err == ""
    for key in ("engine", "release", "settings", "cascades", "verdicts", "objective", "binding", "defaults"):
        assert key in got
    assert got["engine"] == "threejs" and got["binding"] == [] and got["feasible"] is True
    assert got["settings"]["cascades"] == 4 and got["settings"]["maxFar"] == 200.0  # fixed kept; shadows end at the receivers
    assert got["defaults"]["settings"]["mode"] == "practical" and got["settings"]["mode"] == "custom"
    assert got["objective"] < got["measured"]["objective_before"] / 10
    assert "customSplitsCallback" in got["snippet"] and "normalBias" in got["snippet"]
    # feeding the settings back through check gives every number of the check object
    path = tmp_path / "tuned.json"
    path.write_text(json.dumps(got["settings"]))
    assert main(["check", "--engine", "threejs", "--settings", str(path), "--camera", CAMERA, "--sun", "15..60", "--format", "json"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert {k: got[k] for k in again} == again
    assert all(c["acne"] == 0.0 for c in again["cascades"])


def test_unmeetable_limits_exit_3_with_binding(capsys):
    """Limits that cannot all be met: exit status 3 (not 0, not 2), the closest settings still printed with 'binding'."""
    from aliasing.tune.command import INFEASIBLE

    got, err = _json(capsys, BASE + ["--set", "material.shadowSide=FrontSide", "--set", "shadow.normalBias=0", "--receivers", "2..500",
                                     "--max-gap-px", "1"], code=INFEASIBLE)
    assert got["feasible"] is False and set(got["binding"]) == {"max_gap_px", "max_slope"}
    assert err.count("\n") == 1 and "--max-gap-px" in err
    assert len(got["tradeoff"]) == 10 and got["tradeoff"][0]["gap_px"] <= 1.0 < got["tradeoff"][-1]["gap_px"]


def test_table(capsys):
    assert main(BASE) == 0
    out = capsys.readouterr().out
    assert "677.2 -> 9.045 px/texel" in out and "mode: 'practical' → 'logarithmic'" in out and "csm.mode = 'logarithmic';" in out


@pytest.mark.parametrize("extra, words", [
    (["--receivers", "5..1"], "--receivers"),
    (["--receivers", "near"], "--receivers"),
    (["--receivers", "600..700"], "--receivers"),
    (["--max-gap-px", "-1"], "--max-gap-px"),
    (["--max-gap-px", "x"], "--max-gap-px"),
    (["--max-slope", "95"], "--max-slope"),
    (["--max-texels", "0"], "--max-texels"),
    (["--max-texels", "4y2048"], "--max-texels"),
    (["--set", "customSplitsLambda=2"], "customSplitsLambda must be a number in [0, 1]"),
    (["--set", "cascade=3"], "did you mean 'cascades'"),
    (["--receivers", "1..2", "--scene", "a.glb"], "--receivers and --scene"),
])
def test_bad_input_is_one_line(capsys, extra, words):
    try:
        status = main(BASE + extra)
    except SystemExit as exc:  # argparse's own usage errors
        status = exc.code
    assert status == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


def test_max_texels_as_maps_of_a_size(capsys):
    got, _ = _json(capsys, ["tune", "--objective", "perspective", "--engine", "threejs", "--camera", CAMERA, "--sun", "15..60", "--max-texels", "2x1024"])
    assert got["limits"]["max_texels"] == 2 * 1024 ** 2
    assert sum(c["memory"] for c in got["cascades"]) <= 4 * 2 * 1024 ** 2


def test_explorer_shows_the_tuned_settings():
    """The explorer's data is tune's, and follows the limits; a bad gap entry keeps the last good state."""
    pytest.importorskip("ipywidgets")
    from aliasing import explore, setups
    from aliasing.tune import tune

    e = explore.tune(receivers_near=1.0, receivers_far=200.0, max_slope=10.0)
    assert e.error is None and e.png().startswith(b"\x89PNG")
    start = setups.build("threejs", {"cascades": 4, "shadowMapSize": 2048, "material.shadowSide": "FrontSide"}, CAMERA, "15..60")
    t = tune(start, receivers=(1.0, 200.0), max_slope=10.0, max_texels=4 * 2048**2, keep=("cascades", "shadowMapSize"))
    assert e.data["changed"] == t.changed and e.data["objective"] == t.objective
    assert e.set_state({"max_slope": 0.0}) and e.data["changed"]["shadow.normalBias"] < t.changed["shadow.normalBias"]
    assert not e.set_state({"max_gap_px": "-1"}) and "max_gap_px" in e.error and e.data["changed"]["shadow.normalBias"] < 0.2778


hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_GARBAGE = st.sampled_from(["nan", "inf", "-inf", "1e400", "", "-0", "0", "1", "2.5", "x", "1..", "..2", "3..1", "0.5..50", "1e-300..1",
                            "4x", "2x1024", "1e9", "-5", "89.99", "90", "ü"])
_FLAGS = st.lists(st.tuples(st.sampled_from(["--receivers", "--max-texels", "--max-gap-px", "--max-slope", "--set", "--keep"]),
                            _GARBAGE | st.sampled_from(["mode", "cascades,mode", "mode,,x", "shadow.normalBias"])),
                  min_size=1, max_size=3)


@settings(max_examples=12, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(flags=_FLAGS, moving=st.booleans())
def test_fuzz_limits_exit_zero_or_one_line(flags, moving, capsys):
    argv = ["tune", "--objective", "perspective", "--engine", "threejs", "--sun", "15..60", "--set", "cascades=2", "--set", "shadowMapSize=512", "--set", "mode=uniform"]
    for flag, value in flags:
        argv += [flag, f"shadow.normalBias={value}" if flag == "--set" else value]
    argv += ["--moving"] if moving else []
    capsys.readouterr()  # what an earlier example left
    try:
        status = main(argv + ["--format", "json"])
    except SystemExit as exc:
        status = exc.code
    out = capsys.readouterr()
    assert status in (0, 2) and "Traceback" not in out.err
    if status == 2:
        assert out.err.count("\n") == 1
    else:
        got = json.loads(out.out, parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
        assert got["feasible"] or got["binding"]  # an unmet limit is named
        assert (out.err == "") == got["feasible"]  # one line on stderr says which


def test_scene_without_a_camera_is_one_line(capsys, tmp_path):
    obj = tmp_path / "ground.obj"
    obj.write_text("v -10 0 -10\nv 10 0 -10\nv 0 0 10\nf 1 2 3\n")
    assert main(BASE + ["--scene", str(obj)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--scene" in err and "no glTF camera" in err and "receivers NEAR..FAR" in err
