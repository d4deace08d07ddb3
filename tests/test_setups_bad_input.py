"""Bad input met by a new user, refused in one line naming the parameter: render's numeric flags, and the
setups functions fed the wrong types (the generated kinds are in tests/test_fuzz_api.py)."""

from __future__ import annotations

import argparse
import re

import pytest

from aliasing import setups
from aliasing.check import check
from aliasing.cli import main


@pytest.mark.parametrize("flag, message", [("--res=-1", "--res must be a whole number >= 1"), ("--res=0", "--res must be"),
                                           ("--res=70000", r"--res must be a whole number in \[1, 65536\]"),
                                           ("--every=0", "--every must be a whole number >= 1")])
def test_render_numeric_flags_exit_2_in_one_line(capsys, flag, message):
    assert main(["render", flag, "--format", "json"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("aliasing render: error: ")
    assert re.search(message, err), err


@pytest.mark.parametrize("call, name", [
    (lambda: setups.parse_camera({"aspect": None}), "camera aspect"),
    (lambda: setups.parse_camera(5), "camera"),
    (lambda: setups.parse_camera({1: 2}), "camera fields"),
    (lambda: setups.parse_set(5), "items"),
    (lambda: setups.parse_set([5]), "items"),
    (lambda: setups.parse_set("cascades=4"), "items"),
    (lambda: setups.parse_sun(None), "sun"),
    (lambda: setups.parse_sun([30]), "sun"),
    (lambda: setups.build(5), "engine"),
    (lambda: setups.build("threejs", [("cascades", 2)]), "settings"),
    (lambda: setups.build("threejs", camera=3.5), "camera"),
    (lambda: setups.build("threejs", sun=object()), "sun"),
    (lambda: setups.from_args({"engine": "threejs"}), "args"),
    (lambda: setups.resolve(None), "args"),
    (lambda: setups.Setup(setups.get("threejs"), {}, "near=1", setups.parse_sun(30)), "camera"),
    (lambda: check("threejs"), "setup"),
])
def test_wrong_types_are_a_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=rf"^{name}|\b{name}\b") as err:
        call()
    assert "\n" not in str(err.value)


def test_a_pipeline_that_cannot_be_built_names_the_settings(capsys):
    assert main(["check", "--engine", "bevy", "--set", "minimum_distance=0"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "minimum_distance" in err


def test_from_args_still_takes_a_namespace():
    ns = argparse.Namespace(engine="godot", settings=None, set_=["directional_shadow_mode=2"], camera="fov=75,near=0.05,far=4000", sun="30")
    s = setups.from_args(ns)
    assert s.settings["directional_shadow_mode"] == "SHADOW_PARALLEL_4_SPLITS" and s.camera.fov == 75.0
