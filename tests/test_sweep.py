"""Sweeps and the ``aliasing sweep`` command."""

from __future__ import annotations

import json

import numpy as np
import pytest

from aliasing import schemes
from aliasing.cli import main
from aliasing.sweep import ROW_FIELDS, SUMMARY_FIELDS, format_rows, sweep, write


def test_rows_cover_the_product_and_match_evaluate():
    rows = sweep(["Standard", "ZP3+P"], f_over_n=[10.0, 1000.0], fov=[30.0, 60.0, 90.0], light="hemisphere:7")
    assert len(rows) == 2 * 2 * 3 * 7
    assert tuple(rows[0]) == ROW_FIELDS
    r = schemes.evaluate("ZP3+P", 1.0, 1000.0, 90.0, "hemisphere:7")
    ours = [row for row in rows if row["scheme"] == "ZP3+P" and row["f_over_n"] == 1000.0 and row["fov"] == 90.0]
    np.testing.assert_allclose([row["S"] for row in ours], r.S, rtol=1e-15)
    assert all(len(row["M_x"]) == 3 and row["maps"] == 3 for row in ours)


def test_results_depend_on_ratio_only():
    a = sweep(["P"], [100.0], [60.0], "sphere:11", near=1.0)
    b = sweep(["P"], [100.0], [60.0], "sphere:11", near=7.5)
    np.testing.assert_allclose([r["S"] for r in a], [r["S"] for r in b], rtol=1e-12)


def test_summary_layout():
    rows = sweep(["ZP5"], [1000.0], [60.0], "hemisphere:50", summary=True)
    assert len(rows) == 1 and tuple(rows[0]) == SUMMARY_FIELDS
    row = rows[0]
    assert row["S_max_over_min"] == pytest.approx(row["S_max"] / row["S_min"])
    assert row["directions"] == 50 and row["maps"] == 5


def test_json_has_field_names_and_no_nan_tokens():
    rows = sweep(["Standard"], [100.0], [60.0], "front")
    data = json.loads(format_rows(rows, "json"))
    assert set(data[0]) == set(ROW_FIELDS)
    assert data[0]["n_prime"] == ["inf"]  # uniform map: inf written as a string, valid JSON (per-map values: arrays)


def test_write_is_atomic(tmp_path):
    path = tmp_path / "keep.csv"
    path.write_text("old\n")
    with pytest.raises(ValueError, match="is a folder"):
        write("new", tmp_path)
    assert path.read_text() == "old\n"
    write("new\n", path)
    assert path.read_text() == "new\n"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.csv"]  # no temporary left behind


def test_cli_sweep_csv_to_file(tmp_path, capsys):
    out = tmp_path / "s.csv"
    code = main(["sweep", "--schemes", "Standard,LogP", "--f-over-n", "1000", "--fov", "60", "--light", "overhead", "--summary", "--out", str(out)])
    assert code == 0
    lines = out.read_text().splitlines()
    assert lines[0].split(",") == list(SUMMARY_FIELDS)
    # Lloyd et al. 2007 Table 3, "Log" row, min S: 5.98
    assert float(lines[2].split(",")[5]) == pytest.approx(5.98, abs=0.005)


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["--schemes", "ZP0"], "must be >= 1"),
        (["--schemes", "Nope"], "grammar: Standard | P"),
        (["--schemes", "P", "--f-over-n", "1"], "f_over_n must be in (1, inf)"),
        (["--schemes", "P", "--f-over-n", "ten"], "--f-over-n must be a comma-separated list"),
        (["--schemes", "P", "--fov", "180"], "(0, 180) degrees"),
        (["--schemes", "P", "--light", "gamma:1x"], "malformed light"),
        (["--schemes", "P", "--light", "hemisphere:0"], "N must be a whole number >= 1"),
        (["--schemes", "P", "--light", "sphere:-4"], "N must be a whole number >= 1"),
        (["--schemes", "P", "--format", "xml"], "invalid choice"),
        (["--schemes", ","], "at least one scheme"),
    ],
)
def test_cli_sweep_bad_input(argv, needle, capsys):
    try:
        code = main(["sweep", *argv])
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and needle in err
