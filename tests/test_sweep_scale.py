"""Sweeps at scale: grids, config files, chunks, processes, Dask, resume, labelled outputs."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

import aliasing
from aliasing import sweep as S
from conftest import Stop, interrupt_after, stop_after, sweep_cli, sweep_one_line_error


# ---- grids ------------------------------------------------------------------------------


def test_grid_values_lists_and_ranges():
    assert S.grid_values("10:10000:log:4", "f") == (10.0, 100.0, 1000.0, 10000.0)
    assert S.grid_values("30:90:lin:7", "fov") == (30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0)
    assert S.grid_values([5, "1:2:lin:2"], "x") == (5.0, 1.0, 2.0)
    assert S.grid_values(45, "fov") == (45.0,)
    assert S.grid_values("7:9:lin:1", "x") == (7.0,)


@pytest.mark.parametrize(
    "value, needle",
    [("1:2:lin:0", "COUNT 0"), ("1:2:cubic:3", "malformed range"), ("0:10:log:3", "START and STOP > 0"), ("", "is empty"), ([True], "numbers or ranges"), ("ten", "numbers or ranges")],
)
def test_grid_values_bad(value, needle):
    with pytest.raises(ValueError, match="^fov") as info:
        S.grid_values(value, "fov")
    assert needle in str(info.value)


def test_k_and_rule_options_expand_the_scheme_axis():
    variants = S.expand_schemes("Standard,LogP,eta,tsm", k="1:3:lin:2", params={"eta": "-1:1:lin:3", "focus": [0.2]})
    labels = [v.label for v in variants]
    assert labels[:4] == ["Standard", "ZP3", "LogP", "ZP3+LogP"]
    assert labels[4:7] == ["eta[eta=-1]", "eta[eta=0]", "eta[eta=1]"]
    assert labels[-2:] == ["tsm[focus=0.2]", "ZP3+tsm[focus=0.2]"]
    assert len(labels) == 2 + 2 + 6 + 2
    with pytest.raises(ValueError, match="already names its k"):
        S.expand_schemes("ZP5+P", k=[1, 2])
    with pytest.raises(ValueError, match="param 'focus' is taken by none"):
        S.expand_schemes("P,LogP", params={"focus": 0.2})
    with pytest.raises(ValueError, match="appears more than once"):
        S.expand_schemes("P,p")
    with pytest.raises(ValueError, match="k must be whole numbers"):
        S.expand_schemes("P", k="0.5")


def test_light_specs_lists_and_gamma_ranges():
    specs, lv = S.expand_lights("overhead, gamma:0:180:lin:5@azimuth:0:90:lin:3, hemisphere:10")
    assert len(specs) == 3 and lv.shape == (1 + 15 + 10, 3)
    gamma, azimuth = aliasing.geometry.direction_angles(lv[1:16])
    np.testing.assert_allclose(gamma.reshape(5, 3)[:, 0], [0, 45, 90, 135, 180], atol=1e-12)
    np.testing.assert_allclose(azimuth.reshape(5, 3)[2], [0, 45, 90], atol=1e-12)  # at γ = 90°
    assert S.expand_lights("gamma:30,60@azimuth:0,45")[1].shape == (4, 3)
    with pytest.raises(ValueError, match="light is empty"):
        S.expand_lights(" , ")


def test_split_lights_keeps_gamma_lists_together():
    assert S.split_lights("gamma:30,60@azimuth:0,90,behind,sphere:4") == ["gamma:30,60@azimuth:0,90", "behind", "sphere:4"]
    with pytest.raises(ValueError, match="light has an empty item"):  # issue 19: an empty item is an error, not dropped
        S.split_lights("gamma:30,60@azimuth:0,90,behind, ,sphere:4")
    with pytest.raises(ValueError, match="light must be text"):
        S.split_lights(["overhead"])


@pytest.mark.parametrize("jobs", [0, -1, 1.5, True, float("nan"), float("inf"), "2", None])
def test_jobs_must_be_a_whole_number_at_least_1(jobs):
    with pytest.raises(ValueError, match=r"^jobs must be a whole number >= 1 \(local processes\)"):
        S.execute(S.plan("P"), jobs=jobs)


def test_engine_helpers_check_their_input():
    g = S.plan("P", light="overhead")
    with pytest.raises(ValueError, match="sample must be a whole number >= 1"):
        S.estimate(g, sample=0)
    with pytest.raises(ValueError, match="unknown payload kind 'xml'"):
        S.collect(g, "xml")
    with pytest.raises(ValueError, match="count must be a whole number >= 1"):
        S.spread(0)
    assert S.spread(9, 3) == [0, 4, 8] and len(S.collect(g, "csv")) == 1


def test_plan_counts_the_product_and_chunks():
    g = S.plan("P,LogP", f_over_n="10:1000:log:3", fov="30:90:lin:4", light="sphere:25", k=[1, 5], block=10)
    assert g.shape == (4, 3, 4, 1, 25) and g.size == 4 * 3 * 4 * 25  # (variants, f/n, fov, aspect, directions)
    assert g.blocks == 3 and g.chunks == 4 * 3 * 4 * 3
    last = g.chunk(g.chunks - 1, "csv")
    assert (last.name, last.ratio, last.fov, len(last.light)) == ("ZP5+LogP", 1000.0, 90.0, 5)


# ---- chunked output is the unchunked output, byte for byte ----------------------------------


@pytest.mark.parametrize("fmt", ["csv", "json"])
@pytest.mark.parametrize("summary", [False, True])
def test_chunked_output_is_byte_identical_to_format_rows(fmt, summary):
    names = ["Standard", "ZP3+P", "LogP"]
    grid = S.plan(names, f_over_n=[10.0, 1000.0], fov=[30.0, 90.0], light="hemisphere:11", summary=summary, block=11)
    expected = S.format_rows(S.sweep(names, [10.0, 1000.0], [30.0, 90.0], "hemisphere:11", summary=summary), fmt)
    assert S.execute(grid, fmt) == expected
    if summary:  # summaries gather the direction blocks of one (scheme, f/n, fov) first
        blocked = S.plan(names, f_over_n=[10.0, 1000.0], fov=[30.0, 90.0], light="hemisphere:11", summary=True, block=4)
        np.testing.assert_allclose([float(line.split(",")[-1]) for line in S.execute(blocked, "csv").splitlines()[1:]], [r["S_mean"] for r in S.sweep(names, [10.0, 1000.0], [30.0, 90.0], "hemisphere:11", summary=True)], rtol=1e-9)
    if fmt == "json":
        json.loads(S.execute(grid, fmt))


def test_direction_blocks_give_the_same_rows():
    a = S.execute(S.plan("P,ZP2+Po", f_over_n=[100.0], light="sphere:50", block=50))
    b = S.execute(S.plan("P,ZP2+Po", f_over_n=[100.0], light="sphere:50", block=7))
    assert a.splitlines()[0] == b.splitlines()[0]
    assert len(a.splitlines()) == len(b.splitlines()) == 1 + (1 + 2) * 50  # a line per direction and map
    np.testing.assert_allclose(np.loadtxt(io.StringIO(a), delimiter=",", skiprows=1, usecols=(3, 4, 8)), np.loadtxt(io.StringIO(b), delimiter=",", skiprows=1, usecols=(3, 4, 8)), rtol=1e-13)


def test_option_columns_in_csv():
    text = S.execute(S.plan("eta,P", light="overhead", params={"eta": "-1,1"}))
    lines = text.splitlines()
    assert lines[0].startswith("scheme,param_eta,f_over_n,") and lines[0].endswith(",n_prime,eta")
    assert lines[1].startswith("eta,-1,1000,") and lines[3].startswith("P,,1000,")
    assert lines[2].split(",")[-2:] == ["1", "1"]  # η = 1 is PSM: n′ = near


# ---- the CLI: grids, config, dry run, processes --------------------------------------------


def test_cli_grid_jobs_2_is_byte_identical_to_jobs_1(tmp_path, capsys):
    argv = ["--schemes", "P,LogP,eta", "--k", "1,2", "--param", "eta=-1:1:lin:3", "--f-over-n", "10:1000:log:3", "--fov", "40:80:lin:2", "--light", "sphere:40", "--block", "16"]
    one, two = tmp_path / "one.csv", tmp_path / "two.csv"
    assert sweep_cli([*argv, "--out", str(one)], capsys)[0] == 0
    code, out, err = sweep_cli([*argv, "--out", str(two), "--jobs", "2"], capsys)
    assert code == 0 and out == "" and err == ""  # no progress bar: stderr is not a terminal
    assert one.read_bytes() == two.read_bytes()
    assert len(one.read_text().splitlines()) == 1 + (1 + 2 + 1 + 2 + 3 * (1 + 2)) * 3 * 2 * 40  # a line per map: ZP2+… has two
    assert sorted(p.name for p in tmp_path.iterdir()) == ["one.csv", "two.csv"]  # work directories removed


def test_cli_config_file_equals_flags(tmp_path, capsys):
    cfg = tmp_path / "sweep.toml"
    cfg.write_text('schemes = ["P", "LogP"]\nk = [1, 5]\nf_over_n = "10:1000:log:3"\nfov = [60]\nlight = "hemisphere:20"\nsummary = true\n[params]\nc_fraction = "0.2,0.4"\n')
    code, from_config, _ = sweep_cli(["--config", str(cfg)], capsys)
    assert code == 0
    code, from_flags, _ = sweep_cli(["--schemes", "P,LogP", "--k", "1,5", "--f-over-n", "10:1000:log:3", "--light", "hemisphere:20", "--summary", "--param", "c_fraction=0.2,0.4"], capsys)
    assert from_config == from_flags and len(from_config.splitlines()) == 1 + 2 * 2 * 2 * 3
    code, overridden, _ = sweep_cli(["--config", str(cfg), "--fov", "90"], capsys)
    assert code == 0 and ",90," in overridden.splitlines()[1]


@pytest.mark.parametrize(
    "text, needle",
    [
        ('schemes = "P"\nfovv = 60\n', "unknown key 'fovv'"),
        ('schemes = "P"\nfov = true\n', "key 'fov' must be a number, a list of numbers or a range string"),
        ("schemes = 3\n", "key 'schemes' must be a string or a list of strings"),
        ('schemes = "P"\n[params]\neta = {a = 1}\n', "params.eta must be"),
        ('schemes = "P"\nfov = [60, true]\n', "key 'fov' must be"),
        ("schemes = [P]\n", "is not valid TOML"),
        ('schemes = "P"\nfov = "30:90:lin:0"\n', "COUNT 0"),
    ],
)
def test_cli_config_errors_are_one_line(tmp_path, capsys, text, needle):
    cfg = tmp_path / "bad.toml"
    cfg.write_text(text)
    sweep_one_line_error(["--config", str(cfg)], capsys, needle)


def test_cli_missing_config_and_schemes(tmp_path, capsys):
    sweep_one_line_error(["--config", str(tmp_path / "none.toml")], capsys, "cannot be read")
    sweep_one_line_error([], capsys, "needs --schemes")


def test_cli_dry_run_prints_size_and_estimate(tmp_path, capsys):
    out = tmp_path / "never.csv"
    code, text, _ = sweep_cli(["--schemes", "P,LogP", "--k", "1,5", "--f-over-n", "10:10000:log:7", "--fov", "30:90:lin:7", "--light", "hemisphere:100", "--jobs", "2", "--dry-run", "--out", str(out)], capsys)
    assert code == 0
    lines = text.splitlines()
    assert lines[0] == "grid: 4 schemes × 7 f/n × 7 fov × 100 directions = 19,600 evaluations in 196 chunks"
    assert lines[1].startswith("estimated time: ") and "with 2 jobs" in lines[1]
    assert not out.exists()


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["--schemes", "P", "--fov", "30:90:lin:0"], "--fov: range '30:90:lin:0' has COUNT 0"),
        (["--schemes", "P", "--light", ","], "light is empty"),
        (["--schemes", "P", "--k", "0"], "k must be whole numbers >= 1"),
        (["--schemes", "P", "--param", "eta"], "--param takes KEY=VALUES"),
        (["--schemes", "P", "--jobs", "0"], "jobs must be a whole number >= 1"),
        (["--schemes", "P", "--resume"], "resume needs an output file"),
        (["--schemes", "P", "--format", "netcdf"], "netcdf needs an output file"),
    ],
)
def test_cli_grid_bad_input(argv, needle, capsys):
    sweep_one_line_error(argv, capsys, needle)


def test_cli_unwritable_output_keeps_nothing(tmp_path, capsys):
    sweep_one_line_error(["--schemes", "P", "--out", str(tmp_path / "missing" / "x.csv")], capsys, "does not exist")
    sweep_one_line_error(["--schemes", "P", "--out", str(tmp_path)], capsys, "is a folder")
    assert list(tmp_path.iterdir()) == []


# ---- no data lost: interrupt, resume, refuse a different sweep -------------------------


ARGS = dict(f_over_n=[10.0, 1000.0], fov=[60.0], light="sphere:30", block=10)
ARGV = ["--schemes", "P,ZP3+LogP", "--f-over-n", "10,1000", "--fov", "60", "--light", "sphere:30", "--block", "10"]


@pytest.mark.parametrize("jobs", [1, 2])
def test_interrupted_sweep_resumes_to_identical_bytes(tmp_path, capsys, monkeypatch, jobs):
    whole, part = tmp_path / "whole.csv", tmp_path / "part.csv"
    assert sweep_cli([*ARGV, "--out", str(whole)], capsys)[0] == 0
    part.write_text("precious\n")
    grid = S.plan("P,ZP3+LogP", **ARGS)
    assert grid.chunks == 12
    with pytest.raises(Stop):
        S.execute(grid, "csv", part, jobs=jobs, progress=stop_after(5))
    assert part.read_text() == "precious\n"  # a failed run never touches the output
    work = tmp_path / "part.csv.parts"
    saved = sorted(p.name for p in work.glob("*.csv"))
    assert len(saved) >= 5 and (work / "manifest.json").exists()
    assert not [p for p in work.iterdir() if p.name.endswith(".tmp")]
    # without --resume the interrupted work is not thrown away
    sweep_one_line_error([*ARGV, "--out", str(part)], capsys, "pass --resume")
    calls = []
    real = S.compute_chunk
    monkeypatch.setattr(S, "compute_chunk", lambda task: calls.append(task.index) or real(task))
    assert sweep_cli([*ARGV, "--out", str(part), "--resume"], capsys)[0] == 0
    assert part.read_bytes() == whole.read_bytes()
    assert sorted(calls) == [i for i in range(12) if f"{i:06d}.csv" not in saved]  # finished chunks not recomputed
    assert not work.exists()


def test_resume_refuses_a_different_sweep(tmp_path, capsys):
    out = tmp_path / "s.json"
    out.write_text("old\n")
    with pytest.raises(Stop):
        S.execute(S.plan("P,ZP3+LogP", **ARGS), "json", out, progress=stop_after(2))
    sweep_one_line_error([*ARGV, "--format", "json", "--out", str(out), "--resume", "--fov", "61"], capsys, "belongs to a different sweep")
    sweep_one_line_error([*ARGV, "--out", str(out), "--resume"], capsys, "belongs to a different sweep")  # csv ≠ json
    assert out.read_text() == "old\n"
    assert sweep_cli([*ARGV, "--format", "json", "--out", str(out), "--resume"], capsys)[0] == 0
    assert json.loads(out.read_text())[-1]["scheme"] == "ZP3+LogP"


def test_resume_of_a_summary_sweep(tmp_path, capsys):
    whole, part = tmp_path / "w.csv", tmp_path / "p.csv"
    assert sweep_cli([*ARGV, "--summary", "--out", str(whole)], capsys)[0] == 0
    with pytest.raises(Stop):
        S.execute(S.plan("P,ZP3+LogP", summary=True, **ARGS), "csv", part, progress=stop_after(7))
    assert sweep_cli([*ARGV, "--summary", "--out", str(part), "--resume"], capsys)[0] == 0
    assert part.read_bytes() == whole.read_bytes()


def test_progress_bar_only_on_a_terminal():
    class Tty(io.StringIO):
        def isatty(self):
            return True

    assert S.progress_bar(io.StringIO()) is None
    tty = Tty()
    S.execute(S.plan("P", light="sphere:5", block=2), progress=S.progress_bar(tty))
    text = tty.getvalue()
    assert "100%" in text and "3/3" in text and "chunk" in text and text.endswith("\n")  # tqdm's bar, closed at the end


# ---- the table object, pandas, xarray, NetCDF -------------------------------------------


def test_aliasing_sweep_returns_a_table():
    t = aliasing.sweep("LogP", f_over_n="10:1000:log:3", fov=60, light="hemisphere:6", k=[1, 5], block=4)
    assert isinstance(t, S.SweepTable) and len(t) == 2 * 3 * 6
    assert t.format("csv") == S.execute(S.plan("LogP", f_over_n="10:1000:log:3", fov=60, light="hemisphere:6", k=[1, 5], block=4))
    assert t.rows() == S.sweep(["LogP", "ZP5+LogP"], [10.0, 100.0, 1000.0], [60.0], "hemisphere:6")
    assert aliasing.sweep.sweep is S.sweep  # the module keeps its functions
    two = aliasing.sweep("LogP", f_over_n="10:1000:log:3", fov=60, light="hemisphere:6", k=[1, 5], block=4, jobs=2)
    assert two.format("json") == t.format("json")


def test_table_to_pandas():
    pd = pytest.importorskip("pandas")
    t = aliasing.sweep("P,eta", light="hemisphere:3", params={"eta": [0.5]})
    df = t.to_pandas()
    assert isinstance(df, pd.DataFrame) and list(df.columns[:2]) == ["scheme", "param_eta"] and len(df) == 6
    assert df["param_eta"].isna().sum() == 3


def test_table_to_xarray_labels():
    pytest.importorskip("xarray")
    t = aliasing.sweep("P,ZP3+LogP,eta", f_over_n=[10, 100], fov=[40, 80], light="sphere:9", params={"eta": "-1,0"})
    ds = t.to_xarray()
    assert ds["S"].dims == ("scheme", "f_over_n", "fov", "direction")
    assert ds["M_x"].dims == ("scheme", "f_over_n", "fov", "direction", "map") and ds.sizes["map"] == 3
    assert list(ds["scheme"].values) == ["P", "ZP3+LogP", "eta[eta=-1]", "eta[eta=0]"]
    r = aliasing.schemes.evaluate("ZP3+LogP", 1.0, 100.0, 80.0, "sphere:9")
    np.testing.assert_array_equal(ds["S"].sel(scheme="ZP3+LogP", f_over_n=100, fov=80).values, r.S)
    np.testing.assert_array_equal(ds["M_z"].sel(scheme="ZP3+LogP", f_over_n=100, fov=80).values, r.M_z)
    assert np.isnan(ds["M_x"].sel(scheme="P").values[..., 1:]).all()
    assert json.loads(ds.attrs["parameters"])["light"] == ["sphere:9"]
    summary = aliasing.sweep("P", f_over_n=[10, 100], light="sphere:9", summary=True).to_xarray()
    assert summary["S_max_over_min"].dims == ("scheme", "f_over_n", "fov")


def test_cli_netcdf_has_labels_parameters_version_and_command(tmp_path, capsys):
    xr = pytest.importorskip("xarray")
    pytest.importorskip("h5netcdf")
    out = tmp_path / "s.nc"
    code, _, err = sweep_cli(["--schemes", "P,LogP", "--k", "1,3", "--f-over-n", "10:1000:log:3", "--light", "hemisphere:8", "--block", "5", "--format", "netcdf", "--out", str(out)], capsys)
    assert code == 0, err
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert dict(ds.sizes) == {"scheme": 4, "f_over_n": 3, "fov": 1, "direction": 8, "map": 3}
        assert list(ds["scheme"].values) == ["P", "ZP3+P", "LogP", "ZP3+LogP"]
        assert ds.attrs["aliasing_version"] == aliasing.__version__
        assert ds.attrs["command"].startswith("aliasing sweep --schemes P,ZP3+P,LogP,ZP3+LogP")
        assert json.loads(ds.attrs["parameters"])["f_over_n"] == [10.0, 100.0, 1000.0]
        expected = aliasing.sweep("P,LogP", k=[1, 3], f_over_n="10:1000:log:3", light="hemisphere:8").to_xarray()
        np.testing.assert_array_equal(ds["S"].values, expected["S"].values)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.nc"]


# ---- Dask ---------------------------------------------------------------------------------


def test_dask_local_cluster_is_byte_identical(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    local, remote = tmp_path / "local.csv", tmp_path / "dask.csv"
    assert sweep_cli([*ARGV, "--out", str(local)], capsys)[0] == 0
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster:
        code, _, err = sweep_cli([*ARGV, "--out", str(remote), "--dask", cluster.scheduler_address], capsys)
        assert code == 0, err
        t = aliasing.sweep("P,ZP3+LogP", dask=cluster.scheduler_address, **ARGS)
    assert remote.read_bytes() == local.read_bytes()
    assert t.format() == local.read_text()


def test_dask_unreachable_address_is_one_line(tmp_path, capsys, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr(S, "DASK_TIMEOUT", 0.5)
    out = tmp_path / "x.csv"
    out.write_text("old\n")
    sweep_one_line_error(["--schemes", "P", "--out", str(out), "--dask", "tcp://127.0.0.1:1"], capsys, "cannot reach a Dask scheduler at 'tcp://127.0.0.1:1'")
    assert out.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.csv"]  # no work directory left


def test_dask_malformed_address_is_one_line(capsys):
    pytest.importorskip("distributed")
    sweep_one_line_error(["--schemes", "P", "--dask", "no-port-here"], capsys, "malformed scheduler address 'no-port-here'")


def test_cli_ctrl_c_keeps_chunks_and_resume_finishes(tmp_path, capsys, monkeypatch):
    whole, part = tmp_path / "whole.csv", tmp_path / "part.csv"
    assert sweep_cli([*ARGV, "--out", str(whole)], capsys)[0] == 0
    monkeypatch.setattr(S, "progress_bar", interrupt_after(4))
    code, _, err = sweep_cli([*ARGV, "--out", str(part)], capsys)
    assert code == 130 and "interrupted; finished chunks are kept in" in err and "--resume" in err
    assert not part.exists() and len(list((tmp_path / "part.csv.parts").glob("*.csv"))) == 4
    monkeypatch.undo()
    assert sweep_cli([*ARGV, "--out", str(part), "--resume"], capsys)[0] == 0
    assert part.read_bytes() == whole.read_bytes()
