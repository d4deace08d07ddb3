"""Sweeps over non-square views: ``aspect`` (image width/height) as a grid axis like ``fov``.

A square sweep (no aspect, or the single value 1) writes what it wrote before views had an
aspect, byte for byte, with the same manifest and digest; any other aspect axis adds an
``aspect`` column after ``fov`` and has a digest of its own.  Rows at aspect ≠ 1 are
``schemes.evaluate`` of ``View(..., aspect)``; schemes of square views only are refused
before any work.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import aliasing
from aliasing import View, schemes
from aliasing import sweep as S
from conftest import Stop, interrupt_after, stop_after, sweep_cli, sweep_one_line_error

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

NAMES = "P,ZP3+LogP,eta"
ARGV = ["--schemes", NAMES, "--param", "eta=-1,0.5", "--f-over-n", "10,1000", "--fov", "30,90", "--light", "sphere:20,overhead,gamma:30@azimuth:45", "--block", "8"]
ARGS = dict(params={"eta": "-1,0.5"}, f_over_n=[10.0, 1000.0], fov=[30.0, 90.0], light="sphere:20,overhead,gamma:30@azimuth:45", block=8)


def _run(tmp_path, capsys, argv, name):
    out = tmp_path / name
    code, _, err = sweep_cli([*argv, "--out", str(out)], capsys)
    assert code == 0, err
    return out.read_bytes()


# ---- a square sweep is what it was ------------------------------------------------------------


@pytest.mark.parametrize("fmt", ["csv", "json", "parquet"])
@pytest.mark.parametrize("summary", [[], ["--summary"]])
def test_aspect_1_is_byte_identical_to_no_aspect(tmp_path, capsys, fmt, summary):
    if fmt == "parquet":
        pytest.importorskip("pyarrow")
    argv = [*ARGV, *summary, "--format", fmt]
    plain = _run(tmp_path, capsys, argv, f"plain.{fmt}")
    assert _run(tmp_path, capsys, [*argv, "--aspect", "1"], f"one.{fmt}") == plain
    assert _run(tmp_path, capsys, [*argv, "--aspect", "1:1:lin:1"], f"range.{fmt}") == plain
    if fmt != "parquet":
        assert b"aspect" not in plain


def test_square_grid_keeps_its_parameters_and_digest():
    """The manifest's hash of a square grid is computed from the parameters it had before the aspect
    axis (no ``aspect`` key, the old chunk numbering), so an interrupted square run resumes."""
    old = {
        "chunk_order": "f_over_n,fov,block,variant",
        "schemes": ["P", "ZP3+LogP", "eta", "eta"],
        "options": [{}, {}, {"eta": -1.0}, {"eta": 0.5}],
        "f_over_n": [10.0, 1000.0],
        "fov": [30.0, 90.0],
        "light": ["sphere:20", "overhead", "gamma:30@azimuth:45"],
        "directions": 22,
        "near": 1.0,
        "summary": False,
        "block": 8,
    }
    for aspect in ({}, {"aspect": 1}, {"aspect": [1.0]}, {"aspect": "1"}):
        g = S.plan(NAMES, **ARGS, **aspect)
        assert g.parameters() == old and list(g.parameters()) == list(old)
        assert g.digest("csv") == S.parameters_digest(old, "csv", np.ascontiguousarray(g.directions).tobytes())
        assert g.command() == S.plan(NAMES, **ARGS).command() and "--aspect" not in g.command()
        assert g.describe() == "grid: 4 schemes × 2 f/n × 2 fov × 22 directions = 352 evaluations in 48 chunks"
    wide = S.plan(NAMES, **ARGS, aspect=[1.0, 2.0])
    assert wide.digest("csv") != g.digest("csv") and S.plan(NAMES, **ARGS, aspect=2).digest("csv") not in (g.digest("csv"), wide.digest("csv"))
    assert wide.parameters()["aspect"] == [1.0, 2.0] and wide.parameters()["chunk_order"] == "f_over_n,fov,aspect,block,variant"
    assert "--aspect 1,2" in wide.command() and "× 2 aspect ×" in wide.describe()


def test_manifest_of_aspect_1_is_the_square_one_and_resumes(tmp_path, capsys, monkeypatch):
    whole = _run(tmp_path, capsys, ARGV, "whole.csv")
    manifests = []
    for name, extra in (("a", []), ("b", ["--aspect", "1"])):
        monkeypatch.setattr(S, "progress_bar", interrupt_after(5))
        code, _, err = sweep_cli([*ARGV, *extra, "--out", str(tmp_path / f"{name}.csv")], capsys)
        assert code == 130, err
        manifests.append((tmp_path / f"{name}.csv.parts" / "manifest.json").read_bytes())
    monkeypatch.undo()
    assert manifests[0] == manifests[1]
    # a square run interrupted without --aspect resumes with --aspect 1 (and the other way round)
    assert sweep_cli([*ARGV, "--aspect", "1", "--out", str(tmp_path / "a.csv"), "--resume"], capsys)[0] == 0
    assert sweep_cli([*ARGV, "--out", str(tmp_path / "b.csv"), "--resume"], capsys)[0] == 0
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes() == whole


def test_resume_never_mixes_aspects(tmp_path, capsys):
    out = tmp_path / "s.csv"
    with pytest.raises(Stop):
        S.execute(S.plan(NAMES, **ARGS), "csv", out, progress=stop_after(3))
    sweep_one_line_error([*ARGV, "--aspect", "2", "--out", str(out), "--resume"], capsys, "belongs to a different sweep")
    sweep_one_line_error([*ARGV, "--aspect", "1,2", "--out", str(out), "--resume"], capsys, "belongs to a different sweep")
    wide = tmp_path / "w.csv"
    with pytest.raises(Stop):
        S.execute(S.plan(NAMES, **ARGS, aspect=2), "csv", wide, progress=stop_after(3))
    sweep_one_line_error([*ARGV, "--out", str(wide), "--resume"], capsys, "belongs to a different sweep")
    sweep_one_line_error([*ARGV, "--aspect", "3", "--out", str(wide), "--resume"], capsys, "belongs to a different sweep")
    assert sweep_cli([*ARGV, "--aspect", "2", "--out", str(wide), "--resume"], capsys)[0] == 0
    assert wide.read_text() == S.execute(S.plan(NAMES, **ARGS, aspect=2))


# ---- rows at aspect ≠ 1 are schemes.evaluate of the non-square View --------------------------


def test_aspect_rows_equal_evaluate_of_the_view():
    aspects = [0.5, 1.0, 2.0]
    lv = S.expand_lights(ARGS["light"])[1]
    rows = json.loads(S.execute(S.plan(NAMES, **{**ARGS, "block": 5}, aspect=aspects), "json"))
    assert len(rows) == 4 * 2 * 2 * 3 * 22
    assert list(rows[0])[:5] == ["scheme", "param_eta", "f_over_n", "fov", "aspect"]
    seen = 0
    for name, options in (("P", {}), ("ZP3+LogP", {}), ("eta", {"eta": -1.0}), ("eta", {"eta": 0.5})):
        for ratio in ARGS["f_over_n"]:
            for fov in ARGS["fov"]:
                for aspect in aspects:
                    r = schemes.evaluate(name, View(1.0, ratio, fov, aspect), lv, **options)
                    mine = [row for row in rows if row["scheme"] == name and row["param_eta"] == options.get("eta")
                            and (row["f_over_n"], row["fov"], row["aspect"]) == (ratio, fov, aspect)]
                    assert len(mine) == len(lv)
                    assert np.array_equal([row["S"] for row in mine], r.S)  # JSON keeps every float's repr
                    assert np.array_equal([row["M_x"] for row in mine], r.M_x) and np.array_equal([row["M_z"] for row in mine], r.M_z)
                    seen += 1
    assert seen == 4 * 2 * 2 * 3
    # and aspect changes the rows: the overhead light's M_x scales with the image width
    p_rows = {row["aspect"]: row for row in rows if row["scheme"] == "P" and row["gamma"] == 90.0 and row["f_over_n"] == 1000.0 and row["fov"] == 30.0}
    assert p_rows[2.0]["M_x"][0] == pytest.approx(2 * p_rows[1.0]["M_x"][0], rel=1e-12) and p_rows[2.0]["M_z"] == p_rows[1.0]["M_z"]


def test_small_api_and_table_agree_with_the_chunked_output():
    names = ["Standard", "ZP3+P", "LogP"]
    for summary in (False, True):
        for fmt in ("csv", "json"):
            expected = S.format_rows(S.sweep(names, [10.0, 1000.0], [30.0, 90.0], "hemisphere:11", aspect=[1.0, 16 / 9], summary=summary), fmt)
            assert S.execute(S.plan(names, f_over_n=[10.0, 1000.0], fov=[30.0, 90.0], light="hemisphere:11", aspect=[1.0, 16 / 9], summary=summary, block=4), fmt) == expected
    t = aliasing.sweep(names, f_over_n=[10.0, 1000.0], fov=[30.0, 90.0], light="hemisphere:11", aspect=[1.0, 16 / 9], block=4)
    assert t.format("csv") == S.format_rows(S.sweep(names, [10.0, 1000.0], [30.0, 90.0], "hemisphere:11", aspect=[1.0, 16 / 9]), "csv")
    assert len(t) == 3 * 2 * 2 * 2 * 11 and t.data[0]["S"].shape == (2, 2, 2, 11)
    head = S.execute(S.plan("P", aspect=2, light="overhead")).splitlines()[0]
    assert head == "scheme,f_over_n,fov,aspect,gamma,azimuth,map,M_x,M_z,S,maps,n_prime,eta"
    summary = S.execute(S.plan("P", aspect=2, light="overhead", summary=True)).splitlines()[0]
    assert summary.split(",") == list(S.rows.with_aspect(S.SUMMARY_FIELDS))


def test_xarray_and_parquet_have_the_aspect_axis(tmp_path):
    xr = pytest.importorskip("xarray")
    t = aliasing.sweep("P,ZP3+LogP", f_over_n=[10, 100], fov=[40, 80], aspect=[0.5, 2.0], light="sphere:9")
    ds = t.to_xarray()
    assert ds["S"].dims == ("scheme", "f_over_n", "fov", "aspect", "direction")
    assert ds["M_x"].dims == ("scheme", "f_over_n", "fov", "aspect", "direction", "map")
    r = schemes.evaluate("ZP3+LogP", View(1.0, 100.0, 80.0, 2.0), aliasing.geometry.lights("sphere:9"))
    np.testing.assert_array_equal(ds["S"].sel(scheme="ZP3+LogP", f_over_n=100, fov=80, aspect=2.0).values, r.S)
    np.testing.assert_array_equal(ds["M_z"].sel(scheme="ZP3+LogP", f_over_n=100, fov=80, aspect=2.0).values, r.M_z)
    square = aliasing.sweep("P", light="sphere:9").to_xarray()
    assert "aspect" not in square.dims and "aspect" not in square.coords and "units_aspect" not in square.attrs
    summary = aliasing.sweep("P", aspect="1,2", light="sphere:9", summary=True).to_xarray()
    assert summary["S_min"].dims == ("scheme", "f_over_n", "fov", "aspect")
    assert isinstance(xr.Dataset, type)
    pa = pytest.importorskip("pyarrow")
    out = tmp_path / "s.parquet"
    S.execute(S.plan("P,ZP3+LogP", aspect="1,2", light="sphere:9", block=4), "parquet", out)
    got = pa.parquet.read_table(out)
    assert got.column_names[:5] == ["scheme", "f_over_n", "fov", "aspect", "gamma"]
    rows = got.to_pylist()
    want = json.loads(S.execute(S.plan("P,ZP3+LogP", aspect="1,2", light="sphere:9"), "json"))
    assert [(r["scheme"], r["aspect"], r["S"], r["M_x"]) for r in rows] == [(w["scheme"], w["aspect"], w["S"], w["M_x"]) for w in want]


# ---- processes and Dask at aspect ≠ 1 --------------------------------------------------------


def test_jobs_2_and_blocks_are_byte_identical_at_aspect_2(tmp_path, capsys):
    argv = [*ARGV, "--aspect", "2,0.75"]
    one = _run(tmp_path, capsys, argv, "one.csv")
    assert _run(tmp_path, capsys, [*argv, "--jobs", "2"], "two.csv") == one
    assert _run(tmp_path, capsys, [*ARGV[:-1], "3", "--aspect", "2,0.75"], "small-blocks.csv") == one  # --block 3: other chunks, same bytes
    assert one.decode() == S.execute(S.plan(NAMES, **ARGS, aspect=[2.0, 0.75]))
    assert one.splitlines()[0].startswith(b"scheme,param_eta,f_over_n,fov,aspect,gamma")


def test_dask_local_cluster_is_byte_identical_at_aspect_2(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    argv = [*ARGV, "--aspect", "2"]
    local = _run(tmp_path, capsys, argv, "local.csv")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster:
        remote = _run(tmp_path, capsys, [*argv, "--dask", cluster.scheduler_address], "dask.csv")
        t = aliasing.sweep(NAMES, aspect=2, dask=cluster.scheduler_address, **ARGS)
    assert remote == local and t.format() == local.decode()


# ---- config files ----------------------------------------------------------------------------


def test_config_key_aspect(tmp_path, capsys):
    cfg = tmp_path / "s.toml"
    cfg.write_text('schemes = ["P", "LogP"]\nlight = "hemisphere:5"\naspect = [1, 2.5]\n')
    code, out, err = sweep_cli(["--config", str(cfg)], capsys)
    assert code == 0, err
    assert out == sweep_cli(["--schemes", "P,LogP", "--light", "hemisphere:5", "--aspect", "1,2.5"], capsys)[1]
    cfg.write_text('schemes = "P"\naspect = "0.5:2:log:3"\n')
    assert sweep_cli(["--config", str(cfg)], capsys)[1].count("\n") == 1 + 3
    assert sweep_cli(["--config", str(cfg), "--aspect", "1"], capsys)[1] == sweep_cli(["--schemes", "P"], capsys)[1]  # the command line overrides
    for text, needle in (("aspect = true", "key 'aspect' must be a number"), ("aspect = [1, true]", "key 'aspect' must be"),
                         ("aspectt = 2", "unknown key 'aspectt' (did you mean 'aspect'?)"), ("aspect = 0", "aspect (image width/height) must be in (0, inf)")):
        cfg.write_text(f'schemes = "P"\n{text}\n')
        sweep_one_line_error(["--config", str(cfg)], capsys, needle)


# ---- schemes of square views only ------------------------------------------------------------


@pytest.mark.parametrize("scheme", ["FP+LogP", "FPc+ZP2+P", "gmnpr", "pyramid-log", "lispsm-zhang"])
def test_square_only_schemes_are_refused_before_any_work(tmp_path, capsys, monkeypatch, scheme):
    calls = []
    monkeypatch.setattr(S, "compute_chunk", lambda task: calls.append(task) or pytest.fail("computed"))
    out = tmp_path / "x.csv"
    err = sweep_one_line_error(["--schemes", f"P,{scheme}", "--aspect", "1,2", "--light", "sphere:8", "--out", str(out)], capsys, f"scheme {scheme!r}")
    assert "aspect 2 is not possible" in err and "takes square views only" in err
    assert not calls and list(tmp_path.iterdir()) == []  # no output, no work directory
    with pytest.raises(ValueError, match="^aspect 0.5 is not possible with scheme"):
        S.plan(scheme, aspect=0.5)
    with pytest.raises(ValueError, match="^aspect 3 is not possible with scheme"):
        S.sweep([scheme], aspect=[3.0])
    monkeypatch.undo()
    assert sweep_cli(["--schemes", f"P,{scheme}", "--aspect", "1", "--light", "sphere:8"], capsys)[0] == 0  # square: as before


def test_other_errors_are_not_blamed_on_the_aspect():
    """A rule option out of range fails at aspect 1 too: the sweep reports it as it always has."""
    with pytest.raises(ValueError, match="^eta must be in"):
        S.execute(S.plan("eta", params={"eta": 5}, aspect=2, light="overhead"))


# ---- bad aspect values: one line naming aspect -------------------------------------------------


@pytest.mark.parametrize(
    "value, needle",
    [("0", "aspect (image width/height) must be in (0, inf), got 0"), ("-2", "must be in (0, inf), got -2"), ("nan", "--aspect must be finite, got nan"),
     ("inf", "--aspect must be finite, got inf"), ("1e400", "--aspect must be finite"), ("wide", "--aspect must be a comma-separated list"),
     ("16:9", "16:9 is written as its quotient"), ("1,,2", "--aspect has an empty item"), ("2:1:lin:0", "--aspect: range '2:1:lin:0' has COUNT 0"),
     ("-1:2:log:3", "log range '-1:2:log:3' needs START and STOP > 0"), ("0:2:lin:3", "must be in (0, inf), got array with values in [0, 2]"),
     ("1:2:lin:100000000000", "aspect: this request needs about")],
)
def test_cli_bad_aspect_is_one_line(capsys, value, needle):
    sweep_one_line_error(["--schemes", "P", f"--aspect={value}"], capsys, needle)


_FINITE_BAD = st.floats(max_value=0.0, allow_nan=False, allow_infinity=False)
_NON_FINITE = st.sampled_from([math.nan, math.inf, -math.inf])
_TEXT = st.text(max_size=10).filter(lambda t: not _is_positive_number_list(t))


def _is_positive_number_list(text: str) -> bool:
    try:
        values = S.grid_values(text, "aspect")
    except ValueError:
        return False
    return all(v > 0 for v in values)


@settings(max_examples=150, deadline=None)
@given(st.one_of(_FINITE_BAD, _NON_FINITE, _TEXT, st.lists(st.one_of(_FINITE_BAD, _NON_FINITE), min_size=1, max_size=3)))
def test_generated_bad_aspects_are_refused_naming_aspect(value):
    """Through the API: zero, negative, NaN, inf, text that is no list of positive numbers."""
    with pytest.raises(ValueError, match="aspect") as info:
        S.plan("P", aspect=value)
    assert "\n" not in str(info.value)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])  # capsys is read out after every example
@given(st.one_of(_FINITE_BAD.map(repr), _NON_FINITE.map(str), _TEXT))
def test_generated_bad_aspects_on_the_command_line(capsys, value):
    """Through the CLI: exit 2, one line on stderr naming aspect, nothing on stdout."""
    if value.startswith("-"):
        value = " " + value  # argparse would read a leading '-' as an option; a space is stripped by the grid's parser
    code, out, err = sweep_cli(["--schemes", "P", f"--aspect={value}"], capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and "aspect" in err, (value, err)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(min_value=1e-3, max_value=1e3), min_size=1, max_size=3))
def test_generated_good_aspects_give_a_column_of_them(values):
    text = S.execute(S.plan("P,LogP", aspect=values, light="overhead"))
    lines = text.splitlines()
    shown = tuple(values) != (1.0,)
    assert ("aspect" in lines[0].split(",")) == shown
    assert len(lines) == 1 + 2 * len(values)
    if shown:
        col = lines[0].split(",").index("aspect")
        assert [float(line.split(",")[col]) for line in lines[1:]] == pytest.approx([*values, *values], rel=1e-9)
