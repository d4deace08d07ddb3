"""``aliasing bias --aspect``: the cascades' biases of a non-square view (``--fov`` vertical, aspect = width/height)."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from aliasing.bias import presets
from aliasing.bias.cascades import cascade_bias
from aliasing.bias.filtering import filter_rows
from aliasing.cli import main
from aliasing.sweep import format_rows

BASE = ("bias", "--presets", "bevy,filament", "--near", "0.5", "--far", "200", "--light", "gamma:50", "-k", "3", "--resolution", "1024")
PATHS = {  # every path of the command that builds cascades
    "presets": (),
    "split-preset": ("--splits", "babylon", "--lambda", "0.7"),
    "warp": ("--scheme", "LogP", "--splits", "log"),
    "filter": ("--filter", "--fraction", "0.2"),
}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("path", list(PATHS))
@pytest.mark.parametrize("fmt", ["table", "csv", "json"])
def test_aspect_one_is_byte_identical_to_no_aspect(capsys, path, fmt):
    code, plain, err = run(capsys, *BASE, *PATHS[path], "--format", fmt)
    assert code == 0 and err == "" and "aspect" not in plain
    for one in ("1", "1.0"):
        code, same, err = run(capsys, *BASE, *PATHS[path], "--format", fmt, "--aspect", one)
        assert code == 0 and err == "" and same == plain


@pytest.mark.parametrize("path", list(PATHS))
def test_wide_rows_carry_aspect_and_equal_cascade_bias(capsys, path):
    code, out, err = run(capsys, *BASE, *PATHS[path], "--aspect", "2", "--format", "json")
    assert code == 0 and err == ""
    rows = json.loads(out)
    assert len(rows) == 6 and all(r["aspect"] == 2.0 and list(r)[:2] == ["preset", "aspect"] for r in rows)
    extra = dict(zip(PATHS[path][::2], PATHS[path][1::2]))
    kw = dict(scheme=extra.get("--scheme", "Standard"), splits=extra.get("--splits", "practical"), k=3, resolution=1024)
    if "--lambda" in extra:
        kw["lam"] = float(extra["--lambda"])
    want = []
    for name in ("bevy", "filament"):
        got = cascade_bias(0.5, 200.0, 60.0, "gamma:50", name, aspect=2.0, **kw)
        want += filter_rows(got, 60.0, 1080, 0.2) if "--filter" in extra else got
    assert out == format_rows([{"preset": w["preset"], "aspect": 2.0} | {key: v for key, v in w.items() if key != "preset"} for w in want], "json")
    code, text, _ = run(capsys, *BASE, *PATHS[path], "--aspect", "2", "--format", "csv")
    table = list(csv.DictReader(io.StringIO(text)))
    assert code == 0 and len(table) == 6 and {r["aspect"] for r in table} == {"2"}
    code, text, _ = run(capsys, *BASE, *PATHS[path], "--aspect", "2")
    assert code == 0 and text.splitlines()[0].split()[:3] == ["preset", "aspect", "cascade"]


def test_the_texel_across_the_view_doubles_and_the_preset_follows_the_larger_side(capsys):
    """A light ahead (in the view's yz plane): the map's s axis is the view's width.  At aspect 2
    texel_s doubles, texel_t and the splits stay; the ground's minimal bias (its slope is along t)
    stays, the preset's bias is taken at the larger texel side, so it and the margin grow."""
    _, out, _ = run(capsys, *BASE, "--format", "json")
    square = json.loads(out)
    _, out, _ = run(capsys, *BASE, "--aspect", "2", "--format", "json")
    wide = json.loads(out)
    for w, s in zip(wide, square):
        assert (w["near"], w["far"]) == (s["near"], s["far"])
        # texel_edges differences the map coordinates over h = 1e-6 (rounding ~1e-16/1e-6, as in test_bias_presets)
        assert w["texel_s"] == pytest.approx(2.0 * s["texel_s"], rel=1e-9) and w["texel_t"] == pytest.approx(s["texel_t"], rel=1e-12)
        assert w["texel_s"] > w["texel_t"]
        assert w["need_depth"] == pytest.approx(s["need_depth"], rel=1e-12)
        p = presets.get(w["preset"])
        # the light ahead: the ground's slope is along t (azimuth 90°), the preset's texel the larger side, texel_s
        assert w["preset_depth"] == pytest.approx(float(presets.equivalent_depth(p, w["texel_s"], w["ground_angle"], 90.0)), rel=1e-12)
        assert w["preset_depth"] > s["preset_depth"] and w["margin"] > s["margin"]
    # the preset's depth as cascade_bias computes it, at the larger side
    direct = cascade_bias(0.5, 200.0, 60.0, "gamma:50", "bevy", k=3, resolution=1024, aspect=2.0)
    np.testing.assert_array_equal([r["preset_depth"] for r in direct], [r["preset_depth"] for r in wide[:3]])


def test_aspect_with_plane_is_refused_in_one_line(capsys):
    for value in ("1", "2"):
        code, out, err = run(capsys, "bias", "--plane", "--texel", "0.1", "--angle", "45", "--aspect", value)
        assert code == 2 and out == "" and err.count("\n") == 1 and "--aspect" in err and "--plane" in err


def test_square_only_warp_is_refused_naming_aspect(capsys):
    code, out, err = run(capsys, *BASE, "--scheme", "lispsm-zhang", "--aspect", "2")
    assert code == 2 and out == "" and err.count("\n") == 1 and "aspect must be 1" in err
    code, _, _ = run(capsys, *BASE, "--scheme", "lispsm-zhang", "--aspect", "1")
    assert code == 0


def test_help_offers_aspect(capsys):
    with pytest.raises(SystemExit):
        main(["bias", "--help"])
    assert "--aspect" in capsys.readouterr().out


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.one_of(st.floats(max_value=0.0, allow_nan=False), st.sampled_from([float("nan"), float("inf"), float("-inf")])))
def test_bad_aspect_is_one_line_naming_aspect(capsys, aspect):
    for extra in ((), ("--filter",)):
        code, out, err = run(capsys, *BASE, *extra, f"--aspect={aspect!r}")
        assert code == 2 and out == "" and err.count("\n") == 1 and "aspect" in err and "Traceback" not in err, (aspect, err)


@pytest.mark.parametrize("value", ["x", "", "1,2"])
def test_unparsable_aspect_is_a_usage_error(capsys, value):
    with pytest.raises(SystemExit) as info:
        main([*BASE, "--aspect", value])
    assert info.value.code == 2 and "--aspect" in capsys.readouterr().err
