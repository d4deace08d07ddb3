"""``aliasing validate --grid --aspect``: validation grids of a non-square view (one aspect for every case)."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import aliasing.raster.validate as V
from aliasing import cli

GRID = ("validate", "--grid", "--scheme", "Standard,ZP2+P", "--f-over-n", "10,100", "--light", "gamma:60,gamma:150", "--res", "96", "--probes", "6", "--reach", "0.8")
GRID_ARGS = dict(schemes="Standard,ZP2+P", f_over_n="10,100", fov=60, lights="gamma:60,gamma:150", res=96, probes=6, reach=0.8)


def run(capsys, *argv):
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("fmt", ["csv", "json", "text"])
def test_aspect_one_is_byte_identical_to_no_aspect(capsys, fmt):
    code, plain, err = run(capsys, *GRID, "--format", fmt)
    assert code == 0 and err == ""
    code, one, _ = run(capsys, *GRID, "--format", fmt, "--aspect", "1")
    assert code == 0 and one == plain
    assert "aspect" not in plain


def test_aspect_one_grid_has_the_same_parameters_digest_and_command():
    g, g1 = V.plan(**GRID_ARGS), V.plan(**GRID_ARGS, aspect=1.0)
    assert g == g1 and g1.parameters() == g.parameters() and "aspect" not in g.parameters()
    assert g1.digest("csv") == g.digest("csv") and g1.command() == g.command() and g1.describe() == g.describe()
    assert dict(g1.chunk(3).arguments) == dict(g.chunk(3).arguments)


def test_wide_grid_rows_carry_aspect_and_equal_single_validations(capsys):
    code, out, err = run(capsys, *GRID, "--aspect", "2", "--format", "json")
    assert code == 0 and err == ""
    rows = json.loads(out)
    assert len(rows) == 8 and all(r["aspect"] == 2.0 for r in rows)
    # the same numbers as the one-case path, row by row (scheme outer, f/n, light inner)
    for r in (rows[0], rows[7]):
        one = V.validate(r["scheme"], r["f_over_n"], 60, r["light"], res=96, probes=6, reach=0.8, aspect=2.0)
        assert r == json.loads(json.dumps(one))
    # and not the square numbers: the wider frustum changes every bound
    square = V.validate_rows(**GRID_ARGS)
    assert all(w["M_x"] != s["M_x"] for w, s in zip(rows, square))
    assert all(w["within_bound"] for w in rows)
    code, text, _ = run(capsys, *GRID, "--aspect", "2", "--format", "csv")
    table = list(csv.DictReader(io.StringIO(text)))
    assert code == 0 and {r["aspect"] for r in table} == {"2"}
    code, text, _ = run(capsys, *GRID, "--aspect", "2", "--format", "text")
    assert code == 0 and text.splitlines()[0].split()[:4] == ["scheme", "f_over_n", "fov", "aspect"]


def test_wide_grid_parameters_command_and_dry_run(capsys):
    g, wide = V.plan(**GRID_ARGS), V.plan(**GRID_ARGS, aspect=16 / 9)
    assert wide.parameters()["aspect"] == 16 / 9 and wide.digest("csv") != g.digest("csv")  # a resume of the square grid is refused
    assert dict(wide.chunk(0).arguments)["aspect"] == 16 / 9
    argv = wide.command().split()
    assert argv[argv.index("--aspect") + 1] == repr(16 / 9)
    code, out, _ = run(capsys, *GRID, "--aspect", "2", "--dry-run")
    assert code == 0 and out.splitlines()[0].endswith("(res 96, 6x6 probes, aspect 2)")


@pytest.mark.parametrize("scheme", ["FPc+P", "FP+LogP", "FPcs+ZP2+P", "gmnpr", "pyramid", "ZP2+lispsm-zhang"])
def test_square_only_schemes_refused_as_in_single_validation(capsys, scheme):
    with pytest.raises(ValueError, match=r"aspect must be 1") as grid_info:
        V.plan(f"P,{scheme}", 10, 60, "gamma:60", res=96, probes=6, aspect=2.0)
    with pytest.raises(ValueError, match=r"aspect must be 1") as one_info:
        V.validate(scheme, 10, 60, "gamma:60", res=96, probes=6, aspect=2.0)
    assert str(grid_info.value) == str(one_info.value) and str(one_info.value).startswith("scheme ")
    code, out, err = run(capsys, "validate", "--grid", "--scheme", f"P,{scheme}", "--f-over-n", "10", "--aspect", "2", "--res", "96", "--probes", "6")
    assert code == 2 and out == "" and err.count("\n") == 1 and "aspect must be 1" in err
    V.plan(scheme, 10, 60, "gamma:60", res=96, probes=6)  # the same scheme at aspect 1 plans


@settings(max_examples=25, deadline=None)
@given(st.one_of(st.floats(max_value=0.0), st.just(float("nan")), st.just(float("inf")), st.just(-float("inf"))))
def test_bad_aspect_refused_naming_it(aspect):
    with pytest.raises(ValueError, match="^aspect"):
        V.plan(**GRID_ARGS, aspect=aspect)


def test_bad_aspect_on_the_command_line_one_line(capsys):
    for value in ("0", "-2", "nan", "inf"):
        code, out, err = run(capsys, *GRID, f"--aspect={value}")
        assert code == 2 and out == "" and err.count("\n") == 1 and "aspect" in err, (value, err)


def test_wide_grid_xarray_keeps_aspect_as_an_attribute():
    pytest.importorskip("xarray")
    t = V.validate_sweep("P", 10, 60, "gamma:60,gamma:150", res=96, probes=6, reach=0.8, aspect=2.0)
    ds = t.to_xarray()
    assert ds.attrs["aspect"] == 2.0 and "aspect" not in ds.data_vars
    np.testing.assert_array_equal(ds["M_x"].values.ravel(), [r["M_x"] for r in t.rows()])
