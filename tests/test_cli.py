"""The ``aliasing`` command line: reproduce, derive, and one-line errors with exit 2."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

from aliasing.cli import main
from aliasing.reproduce import TARGETS


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_reproduce_list(capsys):
    code, out, _ = run(capsys, "reproduce", "--list")
    assert code == 0
    assert [line.split()[0] for line in out.splitlines()] == list(TARGETS)


def test_reproduce_all_writes_every_figure(tmp_path, capsys):
    code, out, _ = run(capsys, "reproduce", "all", "--out", str(tmp_path))
    assert code == 0
    written = [line.strip() for line in out.splitlines()]
    for name in TARGETS:
        files = [p for p in tmp_path.iterdir() if p.stem == name]
        assert files, f"{name} wrote nothing"
        assert (tmp_path / f"{name}.png").exists(), f"{name} wrote no PNG"  # as the README says: every target writes one
        csv = tmp_path / f"{name}.csv"  # every target writes its numbers: a header and data rows
        assert len(csv.read_text().strip().splitlines()) >= 2
    pngs = [p for p in tmp_path.glob("*.png")]
    assert all(p.stat().st_size > 10_000 for p in pngs)
    assert sorted(written) == sorted(str(p) for p in tmp_path.iterdir())


def test_reproduce_is_deterministic(tmp_path, capsys):
    run(capsys, "reproduce", "lloyd2006-fig6", "--out", str(tmp_path / "a"))
    run(capsys, "reproduce", "lloyd2006-fig6", "--out", str(tmp_path / "b"))
    for suffix in ("png", "csv"):
        assert (tmp_path / "a" / f"lloyd2006-fig6.{suffix}").read_bytes() == (tmp_path / "b" / f"lloyd2006-fig6.{suffix}").read_bytes()


def test_derive_prints_named_result(capsys):
    code, out, _ = run(capsys, "derive", "lloyd2006.n_prime_lispsm")
    assert code == 0
    assert "sqrt(f)*sqrt(n) + n" in out


def test_derive_latex(capsys):
    code, out, _ = run(capsys, "derive", "wimmer2004.n_opt", "--latex")
    assert code == 0
    assert r"\sqrt{z_{f}}" in out


def test_derive_list(capsys):
    code, out, _ = run(capsys, "derive", "--list")
    assert code == 0
    assert "lloyd2006.storage_factor" in out and "wimmer2004.dp_ds" in out


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["reproduce", "fig99"], "valid targets: all, lloyd2006-fig5"),
        (["derive", "nothing"], "unknown derivation 'nothing'"),
        (["frobnicate"], "invalid choice"),
        (["derive", "--latx"], "unrecognized arguments"),
    ],
)
def test_errors_are_one_line_exit_2(argv, needle, capsys):
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse usage errors exit from inside parse_args
        code = exc.code
    _, err = capsys.readouterr()
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and needle in err


def test_out_that_is_a_file_is_an_error(tmp_path, capsys):
    path = tmp_path / "file.txt"
    path.write_text("keep me")
    code, _, err = run(capsys, "reproduce", "all", "--out", str(path))
    assert code == 2 and "is a file" in err
    assert path.read_text() == "keep me"


def test_console_script_runs_without_traceback():
    exe = shutil.which("aliasing") or shutil.which("aliasing", path=str(__import__("pathlib").Path(sys.executable).parent))
    assert exe, "the 'aliasing' console script is not installed"
    proc = subprocess.run([exe, "reproduce", "nope"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
