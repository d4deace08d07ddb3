"""Units on every number of ``check`` (table, CSV, JSON, and ``bias --engine``), the one name of the aliasing
error, and no ``inf``/``nan`` for any setting at huge finite values (refused beyond the engine's limit, or
reported in words)."""

from __future__ import annotations

import csv
import io
import json
import math
import re

import pytest

from aliasing import setups
from aliasing.check import ERROR_NAME, ERROR_UNIT, check, header, units
from aliasing.check.units import UNITLESS
from aliasing.cli import main

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

CAMERA = "near=0.5,far=800,fov=45,aspect=16:9,height=1080"
HEADER = re.compile(r"^(?P<key>\S+) \[(?P<unit>[^\]]+)\]$")


def _headers(text: str) -> list[str]:
    return next(csv.reader(io.StringIO(text)))


@pytest.mark.parametrize("engine", list(setups.ENGINES))
def test_every_header_has_a_unit_or_is_unitless_by_declaration(capsys, engine):
    r = check(setups.build(engine, {}, CAMERA, "15..60"))
    heads = _headers(r.to_csv())
    world = setups.get(engine).length_unit
    for h in heads:
        m = HEADER.match(h)
        assert m or h in UNITLESS, h
    assert f"texel_s [{world}]" in heads and f"error_max [{ERROR_UNIT}]" in heads and "memory [MiB]" in heads and "gap [px]" in heads
    for key in r.cascades[0]["needed"]:
        assert f"needed_{key} [{setups.get(engine).setting(key).unit or 'unitless'}]" in heads
    first = r.text().splitlines()[1].split()  # the table's header line: the same headers
    assert " ".join(first) == " ".join(heads)
    assert [float(row["memory [MiB]"]) for row in csv.DictReader(io.StringIO(r.to_csv()))] == [c["memory"] / 2**20 for c in r.cascades]


@pytest.mark.parametrize("engine", ["threejs", "unreal", "godot"])
def test_json_units_cover_every_field(capsys, engine):
    assert main(["check", "--engine", engine, "--camera", CAMERA, "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    u = out["units"]
    for c in out["cascades"]:
        assert set(c) <= set(u)
        assert set(c["needed"]) == set(u["needed"])
    assert u["error_max"] == ERROR_UNIT and u["memory"] == "bytes" and u["near"] == setups.get(engine).length_unit
    assert all(u[k] == "" for k in UNITLESS) and all(v for k, v in u.items() if k not in UNITLESS and isinstance(v, str))
    assert main(["bias", "--engine", engine, "--camera", CAMERA, "--format", "json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out["rows"][0]) == set(out["units"])


def test_one_name_for_the_error(capsys):
    r = check(setups.build("babylon", {"mapSize": 2048, "lambda": 0.7}, "near=0.5,far=800,fov=0.8rad", "15..60"))
    line = next(v for v in r.verdicts if v.startswith(ERROR_NAME))
    assert f"[{ERROR_UNIT}]" in line and "pixels per texel" in line and "texels per pixel" not in r.text()
    with pytest.raises(SystemExit):
        main(["check", "--help"])
    assert "texels per pixel" not in capsys.readouterr().out


def test_header_and_units_refuse_garbage():
    assert header("shimmer_px", "px/frame") == "shimmer [px/frame]"
    for bad in (None, 3, "x"):
        with pytest.raises(ValueError, match="setup must be"):
            units(bad)
    with pytest.raises(ValueError, match="key and unit"):
        header(1, "px")


NUMERIC = [(p, s) for e in setups.ENGINES for p in setups.profiles(e)[:1] for s in p.settings if s.kind in ("float", "int")]
HUGE = [1.7e308, -1.7e308, 1e300, -1e300, 3.4028234663852886e38, -3.4028234663852886e38, 1e38, 1e30, -1e30]


@settings(max_examples=80, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(NUMERIC), st.one_of(st.sampled_from(HUGE), st.floats(allow_nan=False, allow_infinity=False, min_value=1e15),
                                           st.floats(allow_nan=False, allow_infinity=False, max_value=-1e15)),
       st.booleans())
def test_huge_settings_never_print_inf_or_nan(pair, value, at_limit):
    profile, setting = pair
    lo, hi = setting.accepts
    if at_limit and (hi if value > 0 else lo) is not None:  # the engine's own bound, where it has one
        value = hi if value > 0 else lo
    try:
        s = setups.build(profile, {setting.key: value}, CAMERA, "15..60")
        r = check(s)
    except ValueError as exc:  # beyond what the engine accepts (its range, or its 32-bit float): one line naming the key
        assert setting.key in str(exc) and "\n" not in str(exc)
        return
    text, js = r.text() + r.to_csv(), r.to_json()
    assert not re.search(r"\b(inf|nan)\b", text, re.IGNORECASE), (setting.key, value)
    json.loads(js, parse_constant=lambda c: pytest.fail(f"{c} in the JSON of {setting.key}={value}"))


@pytest.mark.parametrize("engine, key", [("bevy", "shadow_depth_bias"), ("filament", "normalBias"), ("unreal", "r.Shadow.CSMSlopeScaleDepthBias")])
def test_overflowing_biases_are_refused_at_the_engines_float(capsys, engine, key):
    assert main(["check", "--engine", engine, "--set", f"{key}=1.7e308"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and key in err and "32-bit float" in err
    assert main(["check", "--engine", engine, "--set", f"{key}=3.4e38", "--format", "csv"]) == 0
    assert not re.search(r"\binf\b", capsys.readouterr().out)
