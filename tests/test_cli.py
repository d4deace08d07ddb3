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


def test_reproduce_all_runs_every_target_and_lists_what_it_wrote(tmp_path, capsys, monkeypatch):
    # `reproduce all` runs each target's script once, in the listed order, and prints the files written and then
    # what to run next. The scripts themselves run in the documentation build, whose gallery calls the same
    # main(out) of every target (tests/test_docs.py checks each one's PNG and CSV there): here they are stand-ins,
    # so that the figures are not all drawn twice in the suite.
    import importlib

    from aliasing.reproduce import NEXT

    calls = []

    def stand_in(name):
        def main(out):
            calls.append(name)
            out.mkdir(parents=True, exist_ok=True)
            files = [out / f"{name}.png", out / f"{name}.csv"]
            for f in files:
                f.write_text(name)
            return files
        return main

    for name, target in TARGETS.items():
        monkeypatch.setattr(importlib.import_module(f"aliasing.figures.{target.module}"), "main", stand_in(name))
    code, out, err = run(capsys, "reproduce", "all", "--out", str(tmp_path))
    assert code == 0
    assert calls == list(TARGETS)
    assert out.splitlines() == [str(tmp_path / f"{name}.{ext}") for name in TARGETS for ext in ("png", "csv")]
    assert NEXT in err


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
