"""``aliasing.raster.validate``: rasterizer validation of the analytic bounds, its grid and its CLI."""

from __future__ import annotations

import csv
import io
import json
import sys

import numpy as np
import pytest

from aliasing import geometry, schemes
from aliasing.cli import _Parser
from aliasing.raster.validate import add_validate_parser, expand_light_specs, validate, validate_rows

# a light above and to the side, and one nearly behind the viewer (P's rule gives n' = inf there)
LIGHTS = ("gamma:60@azimuth:30", "gamma:170")


@pytest.mark.parametrize("scheme", ["Standard", "P"])
@pytest.mark.parametrize("light", LIGHTS)
def test_measured_maxima_reach_but_never_exceed_the_bounds(scheme, light):
    r = validate(scheme, 100, 60, light, res=256, probes=16)
    ref = schemes.evaluate(scheme, 1.0, 100.0, 60.0, light)
    assert r["maps"] == 1
    assert r["M_x"] == pytest.approx(float(ref.M_x[0, 0]), rel=1e-12)
    assert r["M_z"] == pytest.approx(float(ref.M_z[0, 0]), rel=1e-12)
    assert r["S"] == pytest.approx(float(ref.S[0]), rel=1e-12)
    assert r["measured_S"] == pytest.approx(r["measured_M_x"] * r["measured_M_z"], rel=1e-12)
    assert 0 < r["tolerance"] <= 1e-3
    for key in ("ratio_M_x", "ratio_M_z", "ratio_S"):
        assert r[key] <= 1 + r["tolerance"]
    assert r["max_ratio"] <= 1 + r["tolerance"]
    assert r["max_ratio"] >= 0.95 and r["min_ratio"] >= 0.95
    assert r["within_bound"] and r["reached"] and r["passed"]
    assert r["pixels"] > 2000
    assert r["gamma"] == pytest.approx(float(light.split(":")[1].split("@")[0]))


def test_partitioned_scheme_reports_per_map():
    r = validate("ZP4+P", 1000, 60, "gamma:150", res=256, probes=16, image_res=1024)
    assert r["maps"] == 4
    for key in ("M_x", "M_z", "S", "measured_M_x", "measured_M_z", "measured_S", "ratio_M_x", "ratio_M_z", "ratio_S", "critical_res_s"):
        assert isinstance(r[key], list) and len(r[key]) == 4
    ref = schemes.evaluate("ZP4+P", 1.0, 1000.0, 60.0, "gamma:150")
    np.testing.assert_allclose(r["M_x"], ref.M_x[0], rtol=1e-12)
    assert r["S_total"] == pytest.approx(float(ref.S[0]), rel=1e-12)
    np.testing.assert_allclose(r["critical_res_s"], np.array(r["M_x"]) * 1024, rtol=1e-12)
    assert r["critical_area"] == pytest.approx(r["S_total"] * 1024**2)
    assert max(r["ratio_M_x"] + r["ratio_M_z"]) <= 1 + r["tolerance"]
    assert min(r["ratio_M_x"] + r["ratio_M_z"]) >= 0.95 and r["passed"]


def test_deterministic_and_vector_light_equals_spec():
    a = validate("LogP", 100, 60, "gamma:60@azimuth:30", res=128, probes=8)
    b = validate("LogP", 100, 60, "gamma:60@azimuth:30", res=128, probes=8)
    assert a == b
    v = validate("LogP", 100, 60, geometry.lights("gamma:60@azimuth:30")[0], res=128, probes=8)
    assert v["light"].startswith("vector:")
    assert v["ratio_M_x"] == a["ratio_M_x"] and v["ratio_M_z"] == a["ratio_M_z"]
    c = validate("LogP", 100, 60, "gamma:60@azimuth:30", res=128, probes=8, seed=3)
    assert c["pixels"] > 0 and c["within_bound"]


def test_reach_decides_pass():
    r = validate("P", 100, 60, "gamma:60", res=64, probes=4, reach=1.0)
    assert r["within_bound"] and not r["reached"] and not r["passed"]


@pytest.mark.parametrize("kwargs, match", [
    (dict(scheme="Bogus"), "unknown scheme"),
    (dict(f_over_n=1.0), r"f_over_n must be in \(1, inf\)"),
    (dict(f_over_n=float("nan")), "f_over_n must not be NaN"),
    (dict(fov=0.0), r"fov .* must be in \(0, 180\)"),
    (dict(fov=180.0), r"fov .* must be in \(0, 180\)"),
    (dict(light="sphere:10"), "light must give exactly one direction, got 10"),
    (dict(light="hemisphere:2"), "exactly one direction, got 2"),
    (dict(light=[[0, 1, 0], [0, 0, 1]]), "exactly one direction, got 2"),
    (dict(light="gamma:200"), "light"),
    (dict(light="sideways"), "malformed light"),
    (dict(res=0), r"res must be in \[16, 2048\]"),
    (dict(res=-5), r"res must be in \[16, 2048\]"),
    (dict(res=100_000), r"res must be in \[16, 2048\]"),
    (dict(res=2.5), "res must be a whole number"),
    (dict(res=True), "res must be a whole number"),
    (dict(image_res=0), r"image_res must be in \[1, "),
    (dict(probes=1), r"probes must be in \[2, "),
    (dict(probes=100), r"probes must be in \[2, 32\]"),
    (dict(reach=1.5), r"reach must be in \[0, 1\]"),
])
def test_bad_input(kwargs, match):
    args = dict(scheme="P", f_over_n=100, fov=60, light="overhead", res=128)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        validate(**args)


# ----------------------------------------------------------------------------- grids


def test_expand_light_specs():
    assert expand_light_specs("overhead,gamma:30:150:lin:3") == ["overhead", "gamma:30@azimuth:0", "gamma:90@azimuth:0", "gamma:150@azimuth:0"]
    assert expand_light_specs("gamma:60@azimuth:0,90") == ["gamma:60@azimuth:0", "gamma:60@azimuth:90"]
    assert expand_light_specs(["behind", "gamma:60"]) == ["behind", "gamma:60"]
    with pytest.raises(ValueError, match="exactly one direction"):
        expand_light_specs("gamma:60,sphere:4")
    with pytest.raises(ValueError, match="empty"):
        expand_light_specs(" , ")


def test_grid_rows_are_the_product_and_jobs_do_not_change_them():
    args = ("Standard,P", [10, 100], "60", "gamma:60,gamma:150")
    one = validate_rows(*args, res=64, probes=4)
    assert len(one) == 2 * 2 * 1 * 2
    assert [(r["scheme"], r["f_over_n"], r["light"]) for r in one[:3]] == [("Standard", 10.0, "gamma:60"), ("Standard", 10.0, "gamma:150"), ("Standard", 100.0, "gamma:60")]
    assert all(r["within_bound"] for r in one)
    two = validate_rows(*args, res=64, probes=4, jobs=2)
    assert two == one
    # each row is the single validation
    assert one[-1] == validate("P", 100, 60, "gamma:150", res=64, probes=4)


@pytest.mark.parametrize("kwargs, match", [
    (dict(schemes=""), "schemes is empty"),
    (dict(f_over_n="10,0.5"), "f_over_n must be in"),
    (dict(fov="30:90:lin:0"), "COUNT 0"),
    (dict(lights="gamma:60,sphere:3"), "exactly one direction"),
    (dict(jobs=0), "jobs must be a whole number >= 1"),
])
def test_grid_bad_input_before_any_work(kwargs, match):
    args = dict(schemes="P", f_over_n="10", fov="60", lights="overhead", res=64, probes=4)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        validate_rows(**args)


# ----------------------------------------------------------------------------- command line


def main(argv: list[str]) -> int:
    """What aliasing.cli.main does, with only the validate subcommand attached."""
    parser = _Parser(prog="aliasing")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    add_validate_parser(sub)
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except ValueError as exc:
        print(f"aliasing {args.command}: error: {exc}", file=sys.stderr)
        return 2


def run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


BASE = ("validate", "--res", "128", "--probes", "8")


def test_cli_text_and_json(capsys):
    code, out, err = run(capsys, *BASE, "--scheme", "P", "--f-over-n", "100", "--fov", "60", "--light", "gamma:170")
    assert code == 0 and err == ""
    assert "analytic" in out and "measured" in out and "ratio" in out and "PASS" in out
    code, out, _ = run(capsys, *BASE, "--scheme", "P", "--f-over-n", "100", "--fov", "60", "--light", "gamma:170", "--format", "json")
    assert code == 0
    got = json.loads(out)
    ref = validate("P", 100, 60, "gamma:170", res=128, probes=8)
    assert got == json.loads(json.dumps(ref))
    assert got["ratio_M_x"] <= 1 + got["tolerance"] and got["passed"] is True


def test_cli_grid_csv_json_and_jobs(capsys):
    grid = (*BASE, "--grid", "--scheme", "Standard,P", "--f-over-n", "10,100", "--light", "gamma:60,gamma:150")
    code, out1, err = run(capsys, *grid)
    assert code == 0 and err == ""
    rows = list(csv.DictReader(io.StringIO(out1)))
    assert len(rows) == 8 and {r["scheme"] for r in rows} == {"Standard", "P"}
    code, out2, _ = run(capsys, *grid, "--jobs", "2")
    assert code == 0 and out2 == out1
    code, out3, _ = run(capsys, *grid, "--format", "json")
    assert code == 0 and len(json.loads(out3)) == 8
    code, out4, _ = run(capsys, *grid, "--format", "text")
    assert code == 0 and len(out4.splitlines()) == 9


def test_cli_failed_validation_exits_1(capsys):
    code, out, _ = run(capsys, *BASE, "--scheme", "P", "--f-over-n", "100", "--reach", "1")
    assert code == 1 and "FAIL" in out


@pytest.mark.parametrize("argv, match", [
    (("--scheme", "P", "--f-over-n", "100", "--light", "sphere:10"), "exactly one direction"),
    (("--scheme", "P", "--f-over-n", "100", "--res", "0"), "res must be in"),
    (("--scheme", "P", "--f-over-n", "100", "--res", "99999"), "res must be in"),
    (("--scheme", "P", "--f-over-n", "0.5"), "f_over_n must be in"),
    (("--scheme", "P", "--f-over-n", "100", "--fov", "190"), "fov"),
    (("--scheme", "Bogus", "--f-over-n", "100"), "unknown scheme"),
    (("--scheme", "P,LogP", "--f-over-n", "100"), "--grid"),
    (("--scheme", "P", "--f-over-n", "abc"), "--f-over-n must be a number"),
    (("--scheme", "P", "--f-over-n", "100", "--jobs", "2"), "--jobs needs --grid"),
    (("--scheme", "P", "--f-over-n", "100", "--res", "abc"), "--res"),
    (("--scheme", "P", "--f-over-n", "100", "--format", "xml"), "--format"),
    (("--f-over-n", "100",), "--scheme"),
    (("--grid", "--scheme", "P", "--f-over-n", "10", "--light", "gamma:60,hemisphere:4"), "exactly one direction"),
    (("--grid", "--scheme", "P", "--f-over-n", "10", "--jobs", "0"), "jobs"),
])
def test_cli_bad_input_one_line_exit_2(capsys, argv, match):
    code, out, err = run(capsys, "validate", *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and match in err


def test_projection_factor_reported_about_one_on_probes(capsys):
    r = validate("ZP2+LogP", 100, 60, "gamma:60@azimuth:30", res=128, probes=8)
    assert r["projection_min"] <= r["projection_median"] <= r["projection_max"]
    assert abs(r["projection_median"] - 1) < 5e-3
    assert 0.92 < r["projection_min"] < 1 < r["projection_max"] < 1.08
    code, out, _ = run(capsys, *BASE, "--scheme", "P", "--f-over-n", "100", "--light", "gamma:60@azimuth:30")
    assert code == 0 and "projection factor cos(psi_e)/cos(psi_l) on the probes: min " in out
    code, out, _ = run(capsys, *BASE, "--grid", "--scheme", "P", "--f-over-n", "100", "--light", "gamma:60@azimuth:30")
    row = next(csv.DictReader(io.StringIO(out)))
    assert float(row["projection_median"]) == pytest.approx(validate("P", 100, 60, "gamma:60@azimuth:30", res=128, probes=8)["projection_median"], rel=1e-9)


# ----------------------------------------------------------------------------- grids through the sweep engine

import aliasing.raster.validate as V  # noqa: E402
import aliasing.raster.validate.grid as VG  # noqa: E402  (where the grid tasks call validate)
from aliasing import sweep as S  # noqa: E402
from conftest import Stop, interrupt_after, stop_after  # noqa: E402

GRID = ("--grid", "--scheme", "Standard,ZP2+P", "--f-over-n", "10,100", "--light", "gamma:60,gamma:150", "--res", "48", "--probes", "4", "--reach", "0.8")
GRID_ARGS = dict(schemes="Standard,ZP2+P", f_over_n="10,100", fov=60, lights="gamma:60,gamma:150", res=48, probes=4, reach=0.8)


def test_grid_plan_chunks_and_bad_input():
    g = V.plan(**GRID_ARGS)
    assert g.shape == (2, 2, 1, 2) and g.chunks == g.size == 8
    assert dict(g.chunk(5, "rows").arguments)["scheme"] == "ZP2+P" and dict(g.chunk(5, "rows").arguments)["light"] == "gamma:150"
    assert g.digest("csv") != V.plan(**{**GRID_ARGS, "res": 64}).digest("csv") != g.digest("json")
    with pytest.raises(ValueError, match="appears more than once"):
        V.plan("P,p", 10, 60, "overhead", res=48, probes=4)
    with pytest.raises(ValueError, match=r"^unknown format 'xml'"):
        S.execute(g, "xml")


@pytest.mark.parametrize("fmt", ["csv", "json", "text"])
def test_grid_file_jobs_2_is_byte_identical_to_jobs_1_and_stdout(tmp_path, capsys, fmt):
    one, two = tmp_path / "one", tmp_path / "two"
    code, out, err = run(capsys, "validate", *GRID, "--format", fmt, "--out", str(one))
    assert code == 0 and out == "" and err == ""  # no progress bar: stderr is not a terminal
    assert run(capsys, "validate", *GRID, "--format", fmt, "--out", str(two), "--jobs", "2")[0] == 0
    assert one.read_bytes() == two.read_bytes()
    code, printed, _ = run(capsys, "validate", *GRID, "--format", fmt)
    assert code == 0 and printed == one.read_text()
    assert one.read_text() == V.validate_sweep(**GRID_ARGS).format(fmt)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["one", "two"]  # work directories removed


@pytest.mark.parametrize("jobs", [1, 2])
def test_interrupted_grid_resumes_to_identical_bytes_without_redoing_validations(tmp_path, capsys, monkeypatch, jobs):
    whole, part = tmp_path / "whole.csv", tmp_path / "part.csv"
    assert run(capsys, "validate", *GRID, "--out", str(whole))[0] == 0
    part.write_text("precious\n")
    with pytest.raises(Stop):
        S.execute(V.plan(**GRID_ARGS), "csv", part, jobs=jobs, progress=stop_after(3))
    assert part.read_text() == "precious\n"  # a failed run never touches the output
    work = tmp_path / "part.csv.parts"
    saved = sorted(p.name for p in work.glob("*.jsonl"))
    assert 3 <= len(saved) < 8 and (work / "manifest.json").exists()
    code, _, err = run(capsys, "validate", *GRID, "--out", str(part))  # without --resume nothing is thrown away
    assert code == 2 and len(err.strip().splitlines()) == 1 and "pass --resume" in err
    calls = []
    real = VG.validate
    monkeypatch.setattr(VG, "validate", lambda **kw: calls.append((kw["scheme"], kw["f_over_n"], kw["light"])) or real(**kw))
    assert run(capsys, "validate", *GRID, "--out", str(part), "--resume")[0] == 0
    assert part.read_bytes() == whole.read_bytes()
    assert len(calls) == 8 - len(saved)  # finished validations not redone
    assert not work.exists()


def test_ctrl_c_keeps_validations_and_resume_finishes(tmp_path, capsys, monkeypatch):
    whole, part = tmp_path / "whole.json", tmp_path / "part.json"
    assert run(capsys, "validate", *GRID, "--format", "json", "--out", str(whole))[0] == 0
    monkeypatch.setattr(S, "progress_bar", interrupt_after(2))
    code, _, err = run(capsys, "validate", *GRID, "--format", "json", "--out", str(part))
    assert code == 130 and "aliasing validate: interrupted; finished chunks are kept in" in err
    assert not part.exists() and len(list((tmp_path / "part.json.parts").glob("*.jsonl"))) == 2
    monkeypatch.undo()
    assert run(capsys, "validate", *GRID, "--format", "json", "--out", str(part), "--resume")[0] == 0
    assert part.read_bytes() == whole.read_bytes()


@pytest.mark.parametrize("change", [("--res", "64"), ("--light", "gamma:60,gamma:151"), ("--format", "json")])
def test_resume_refuses_a_different_validation_grid(tmp_path, capsys, change):
    out = tmp_path / "v.csv"
    out.write_text("old\n")
    with pytest.raises(Stop):
        S.execute(V.plan(**GRID_ARGS), "csv", out, progress=stop_after(2))
    code, printed, err = run(capsys, "validate", *GRID, *change, "--out", str(out), "--resume")
    assert code == 2 and printed == "" and len(err.strip().splitlines()) == 1 and "belongs to a different sweep" in err
    assert out.read_text() == "old\n"
    # nor does a sweep resume a validation grid's work directory
    code, _, err = _sweep_cli(["--schemes", "P", "--out", str(out), "--resume"], capsys)
    assert code == 2 and "belongs to a different sweep" in err


def _sweep_cli(argv, capsys):
    from aliasing.cli import main as aliasing_main

    code = aliasing_main(["sweep", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_failed_validation_in_a_grid_file_exits_1(tmp_path, capsys):
    out = tmp_path / "v.csv"
    code, _, _ = run(capsys, "validate", *GRID, "--reach", "1", "--out", str(out))
    assert code == 1 and "False" in out.read_text()


def test_grid_dry_run_and_single_case_flags(tmp_path, capsys):
    out = tmp_path / "never.csv"
    code, text, _ = run(capsys, "validate", *GRID, "--jobs", "2", "--dry-run", "--out", str(out))
    assert code == 0 and not out.exists()
    lines = text.splitlines()
    assert lines[0] == "grid: 2 schemes × 2 f/n × 1 fov × 2 lights = 8 validations in 8 chunks (res 48, 4x4 probes)"
    assert lines[1].startswith("estimated time: ") and "with 2 jobs (timed on one validation of 2 schemes)" in lines[1]
    for flag in (("--out", str(out)), ("--resume",), ("--dask", "tcp://127.0.0.1:1"), ("--dry-run",)):
        code, printed, err = run(capsys, "validate", "--scheme", "P", "--f-over-n", "10", *flag)
        assert code == 2 and printed == "" and f"{flag[0]} needs --grid" in err and len(err.strip().splitlines()) == 1


def test_grid_table_pandas_xarray_and_netcdf(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    t = V.validate_sweep(**GRID_ARGS)
    assert isinstance(t, S.SweepTable) and len(t) == 8 and t.rows() == V.validate_rows(**GRID_ARGS)
    df = t.to_pandas()
    assert len(df) == 8 and "projection_median" in df.columns
    out = tmp_path / "v.nc"
    assert run(capsys, "validate", *GRID, "--format", "netcdf", "--out", str(out))[0] == 0
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert dict(ds.sizes) == {"scheme": 2, "f_over_n": 2, "fov": 1, "light": 2, "map": 2}
        assert ds.attrs["command"].startswith("aliasing validate --grid --scheme Standard,ZP2+P")
        row = t.rows()[-1]  # ZP2+P, f/n 100, gamma:150
        np.testing.assert_array_equal(ds["ratio_M_x"].sel(scheme="ZP2+P", f_over_n=100, light="gamma:150").values[0], row["ratio_M_x"])
        assert bool(ds["passed"].sel(scheme="Standard", f_over_n=10, light="gamma:60").values[0]) == t.rows()[0]["passed"]
        assert np.isnan(ds["M_x"].sel(scheme="Standard").values[..., 1]).all()
        assert float(ds["gamma"].sel(light="gamma:150")) == 150.0


def test_dask_local_cluster_grid_is_byte_identical(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    local, remote = tmp_path / "local.csv", tmp_path / "dask.csv"
    assert run(capsys, "validate", *GRID, "--out", str(local))[0] == 0
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster:
        code, _, err = run(capsys, "validate", *GRID, "--out", str(remote), "--dask", cluster.scheduler_address)
        assert code == 0, err
        t = V.validate_sweep(**GRID_ARGS, dask=cluster.scheduler_address)
    assert remote.read_bytes() == local.read_bytes()
    assert t.format("csv") == local.read_text()
