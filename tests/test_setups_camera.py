"""The camera in the engine's own terms: fov in radians refused unless written ``rad``, ``deg``/``rad``
suffixes, ``hfov``, ``aspect=WxH``, ``size=WxH``, the engines' names for near and far."""

from __future__ import annotations

import json
import math

import pytest

from aliasing import setups
from aliasing.cli import main
from aliasing.setups.files import vertical_fov as files_vertical_fov
from aliasing.setups.spec import CAMERA_ALIASES
from aliasing.view import vertical_fov

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

BABYLON = ["check", "--engine", "babylon", "--set", "class=CascadedShadowGenerator", "--set", "numCascades=4", "--set", "mapSize=2048",
           "--set", "lambda=0.7", "--format", "json"]


def test_babylon_fov_in_radians_equals_degrees(capsys):
    assert main(BABYLON + ["--camera", "near=0.5,far=800,fov=0.8rad,aspect=1920x1080"]) == 0
    rad = json.loads(capsys.readouterr().out)
    assert main(BABYLON + ["--camera", f"minZ=0.5,maxZ=800,fov={math.degrees(0.8)!r},aspect=16:9,height=1080"]) == 0
    deg = json.loads(capsys.readouterr().out)
    assert rad == deg
    assert rad["cascades"][0]["error_max"] == pytest.approx(116.9, rel=1e-3)


def test_bare_radians_exit_2_naming_degrees(capsys):
    assert main(BABYLON + ["--camera", "near=0.5,far=800,fov=0.8"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "45.84°" in err and "fov=45.84 (degrees) or fov=0.8rad" in err and "fov=0.8deg" in err


@pytest.mark.parametrize("text, fov", [("fov=50deg", 50.0), ("fov=50°", 50.0), ("fov=2deg", 2.0), ("fov=0.5RAD", math.degrees(0.5)),
                                       ("fov= 1e1 ", 10.0), ("fieldOfView=60", 60.0)])
def test_fov_units(text, fov):
    assert setups.parse_camera(text).fov == pytest.approx(fov, rel=1e-15)


@pytest.mark.parametrize("value", ["0.8", "3.14", "1", {"fov": 0.8}, {"hfov": 1.0}])
def test_radians_refused(value):
    spec = value if isinstance(value, dict) else f"fov={value}"
    with pytest.raises(ValueError, match=r"looks like radians .*°\): write .*rad"):
        setups.parse_camera(spec)


def test_hfov_is_the_horizontal_field_of_view():
    cam = setups.parse_camera("hfov=90,aspect=1920x1080")
    t_h = cam.aspect * math.tan(math.radians(cam.fov) / 2)  # the view's horizontal half-angle tangent
    assert t_h == pytest.approx(1.0, rel=1e-14)
    assert setups.parse_camera("hfov=1.2rad,aspect=2").fov == pytest.approx(vertical_fov(math.degrees(1.2), 2.0), rel=1e-15)
    assert files_vertical_fov is vertical_fov  # one home for the conversion
    with pytest.raises(ValueError, match="fov or hfov, not both"):
        setups.parse_camera("fov=50,hfov=60")


def test_aspect_and_size():
    assert setups.parse_camera("aspect=1920x1080").aspect == setups.parse_camera("aspect=16:9").aspect
    assert setups.parse_camera("aspect=1920×1080,height=720").height == 720  # aspect is the ratio only
    cam = setups.parse_camera("size=1280x720")
    assert (cam.width, cam.height) == (1280, 720)
    for bad in ("size=1280x720,height=10", "size=1280x720,aspect=1"):
        with pytest.raises(ValueError, match="not both"):
            setups.parse_camera(bad)


def test_engine_names_of_near_and_far():
    want = setups.parse_camera("near=0.5,far=800")
    for alias, name in CAMERA_ALIASES.items():
        if name in ("near", "far"):
            other = "far=800" if name == "near" else "near=0.5"
            assert setups.parse_camera(f"{alias}={0.5 if name == 'near' else 800},{other}") == want
    with pytest.raises(ValueError, match="given twice"):
        setups.parse_camera("minZ=1,near=2")


def test_spec_round_trips_a_narrow_fov():
    cam = setups.parse_camera("fov=2deg")
    assert "fov=2deg" in cam.spec() and setups.parse_camera(cam.spec()).fov == cam.fov


@settings(max_examples=200, deadline=None, derandomize=True)
@given(st.one_of(st.none(), st.integers(), st.floats(allow_nan=True), st.text(max_size=12), st.lists(st.integers(), max_size=2),
                 st.dictionaries(st.sampled_from(["near", "far", "fov", "hfov", "aspect", "height", "size", "minZ"]),
                                 st.one_of(st.none(), st.floats(allow_nan=True), st.text(max_size=8), st.booleans()), max_size=3)))
def test_garbage_is_refused_naming_the_camera(spec):
    try:
        cam = setups.parse_camera(spec)
    except ValueError as exc:
        assert str(exc).startswith(("camera", "unknown camera")) and "\n" not in str(exc)
    else:
        assert all(math.isfinite(v) for v in (cam.near, cam.far, cam.fov, cam.aspect)) and 0 < cam.fov < 180
