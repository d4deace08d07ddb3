"""Output at scale (issue 12 item 4): the column-wise CSV writer and Parquet."""

from __future__ import annotations

import numpy as np
import pytest

from aliasing import schemes
from aliasing import sweep as S
from aliasing.cli import main

SCHEMES = "P,ZP3+LogP,FPc+ZP2+P,FP+LogP,eta,Standard"
ARGS = dict(f_over_n=[10, 1000], fov=[30, 90], light="sphere:60,overhead,behind,front", params={"eta": [-1, 0.5]}, block=25)


def test_column_wise_csv_is_byte_identical_to_the_row_formatter():
    grid = S.plan(SCHEMES, **ARGS)
    fast = S.execute(grid, "csv")  # chunk fragments, formatted a column at a time
    slow = S.table(SCHEMES, **ARGS).format("csv")  # row dicts through format_rows, value by value
    assert fast == slow
    # one line per direction and map slot (tidy: nothing packed with ";"); a face partition has a near-face slot and 4 side faces (× k)
    maps = {"P": 1, "ZP3+LogP": 3, "FPc+ZP2+P": 1 + 4 * 2, "FP+LogP": 1 + 4, "eta": 1, "Standard": 1}
    assert [schemes.evaluate(name, 1.0, 10.0, 30.0, "sphere:60").maps for name in maps] == list(maps.values())
    per_direction = sum(maps.values()) + maps["eta"]  # eta swept over two values
    assert fast.count("\n") == 1 + per_direction * grid.size // len(grid.variants) and ";" not in fast and ",inf," in fast


def test_parquet_round_trips_through_pandas(tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    out = tmp_path / "s.parquet"
    argv = ["sweep", "--schemes", SCHEMES, "--param", "eta=-1,0.5", "--f-over-n", "10,1000", "--fov", "30,90",
            "--light", "sphere:60,overhead,behind,front", "--block", "25", "--format", "parquet", "--out", str(out)]
    assert main(argv) == 0
    df = pd.read_parquet(out)
    rows = S.table(SCHEMES, **ARGS).rows()
    assert list(df.columns) == list(rows[0]) and len(df) == len(rows)
    assert df["scheme"].tolist() == [r["scheme"] for r in rows]
    assert df["maps"].tolist() == [r["maps"] for r in rows]
    np.testing.assert_array_equal(df["S"].to_numpy(), [r["S"] for r in rows])  # exact: the same float64
    for key in ("M_x", "eta"):
        for got, row in zip(df[key], rows):
            np.testing.assert_array_equal(got, np.atleast_1d(row[key]))
    assert np.isnan(df["param_eta"][df["scheme"] == "P"]).all()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.parquet"]


def test_parquet_summary_and_resume(tmp_path):
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    from conftest import Stop, stop_after

    grid = S.plan("P,ZP3+LogP", light="sphere:40", block=10, summary=True)
    out = tmp_path / "t.parquet"
    with pytest.raises(Stop):
        S.execute(grid, "parquet", out, progress=stop_after(3))
    S.execute(grid, "parquet", out, resume=True)
    df = pd.read_parquet(out)
    assert df.to_dict("records") == S.table("P,ZP3+LogP", light="sphere:40", block=10, summary=True).rows()


def test_parquet_needs_a_file(capsys):
    code = main(["sweep", "--schemes", "P", "--format", "parquet", "--out", "-"])
    err = capsys.readouterr().err
    assert code == 2 and "format parquet needs an output file" in err and len(err.splitlines()) == 1
