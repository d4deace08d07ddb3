"""The sweep's files: checked resume (issue 19 item 1) and output that never damages a file (issue 11 item 4)."""

from __future__ import annotations

import json
import os
import stat

import pytest

from aliasing import sweep as S
from aliasing.cli import main
from aliasing.sweep import store
from conftest import Stop, stop_after, sweep_cli, sweep_one_line_error

ARGV = ["--schemes", "P,ZP3+LogP", "--f-over-n", "10,1000", "--fov", "60", "--light", "sphere:30", "--block", "10"]
ARGS = dict(f_over_n=[10.0, 1000.0], fov=[60.0], light="sphere:30", block=10)


# ---- resume checks what it reuses -------------------------------------------------------


@pytest.fixture(scope="module")
def whole(tmp_path_factory):
    path = tmp_path_factory.mktemp("whole") / "whole.csv"
    assert main(["sweep", *ARGV, "--out", str(path)]) == 0
    return path.read_bytes()


def _interrupted(tmp_path, fmt="csv"):
    part = tmp_path / f"part.{fmt}"
    with pytest.raises(Stop):
        S.execute(S.plan("P,ZP3+LogP", **ARGS), fmt, part, progress=stop_after(5))
    work = tmp_path / f"part.{fmt}.parts"
    doc = json.loads((work / "manifest.json").read_text())
    assert sorted(doc["finished"]) == [str(i) for i in range(5)]
    data = (work / "000002.csv").read_bytes()
    assert doc["finished"]["2"] == {"sha256": __import__("hashlib").sha256(data).hexdigest(), "rows": 10}
    return part, work


@pytest.mark.parametrize(
    "damage, why",
    [
        (lambda p: p.write_bytes(p.read_bytes()[:37]), "checksum differs"),  # truncated
        (lambda p: p.write_bytes(b"\x00garbage\xff"), "checksum differs"),  # overwritten
        (lambda p: p.unlink(), "missing"),  # deleted
    ],
    ids=["truncated", "garbage", "deleted"],
)
def test_resume_recomputes_a_damaged_chunk(tmp_path, capsys, monkeypatch, whole, damage, why):
    part, work = _interrupted(tmp_path)
    damage(work / "000002.csv")
    calls = []
    real = S.compute_chunk
    monkeypatch.setattr(S, "compute_chunk", lambda task: calls.append(task.index) or real(task))
    code, _, err = sweep_cli([*ARGV, "--out", str(part), "--resume"], capsys)
    assert code == 0
    assert part.read_bytes() == whole  # never the damaged bytes
    assert sorted(calls) == [2, *range(5, 12)]  # the damaged chunk and the unfinished ones
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "recomputing 1 damaged chunk" in lines[0] and f"000002.csv ({why})" in lines[0]


def test_resume_with_intact_chunks_says_nothing(tmp_path, capsys, whole):
    part, _ = _interrupted(tmp_path)
    code, _, err = sweep_cli([*ARGV, "--out", str(part), "--resume"], capsys)
    assert code == 0 and err == "" and part.read_bytes() == whole


def test_resume_recounts_rows_of_an_npz_chunk(tmp_path):
    out = tmp_path / "s.csv"
    grid = S.plan("P,LogP", light="sphere:30", block=10, summary=True)
    with pytest.raises(Stop):
        S.execute(grid, "csv", out, progress=stop_after(2))
    work = tmp_path / "s.csv.parts"
    (work / "000001.npz").write_bytes(b"PK\x03\x04 not a zip")
    lines = []
    S.execute(grid, "csv", out, resume=True, notice=lines.append)
    assert len(lines) == 1 and "000001.npz (checksum differs)" in lines[0]
    assert out.read_text() == S.execute(grid, "csv")


# ---- output that never damages a file --------------------------------------------------------


def test_out_through_a_symlink_writes_its_target(tmp_path, capsys):
    folder = tmp_path / "real"
    folder.mkdir()
    target = folder / "data.csv"
    target.write_text("old\n")
    link = tmp_path / "link.csv"
    link.symlink_to(target)
    assert sweep_cli(["--schemes", "P", "--out", str(link)], capsys)[0] == 0
    assert link.is_symlink() and os.readlink(link) == str(target)  # the link is kept
    assert target.read_text().startswith("scheme,") and link.read_text() == target.read_text()
    assert sorted(p.name for p in folder.iterdir()) == ["data.csv"]  # no temp or work files left


@pytest.mark.parametrize("name", ["-", "/dev/stdout"])
def test_out_dash_streams_to_stdout(name, capsys):
    code, out, err = sweep_cli(["--schemes", "P", "--light", "overhead,behind", "--out", name], capsys)
    assert code == 0 and err == ""
    assert out == S.execute(S.plan("P", light="overhead,behind"))


def test_out_fifo_is_refused_before_work(tmp_path, capsys, monkeypatch):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    monkeypatch.setattr(S, "compute_chunk", lambda task: pytest.fail("work started"))
    sweep_one_line_error(["--schemes", "P", "--out", str(fifo)], capsys, "is not a regular file (a FIFO)")
    assert stat.S_ISFIFO(os.stat(fifo).st_mode)


@pytest.mark.parametrize("device", ["/dev/null", "/dev/full"])
def test_out_device_is_refused_before_work(device, capsys, monkeypatch):
    if not os.path.exists(device):
        pytest.skip(f"no {device}")
    monkeypatch.setattr(S, "compute_chunk", lambda task: pytest.fail("work started"))
    sweep_one_line_error(["--schemes", "P", "--out", device], capsys, "a character device")
    assert stat.S_ISCHR(os.stat(device).st_mode)


def test_out_socket_is_refused(tmp_path):
    import socket

    path = tmp_path / "s.sock"
    with socket.socket(socket.AF_UNIX) as sock:
        sock.bind(str(path))
        with pytest.raises(ValueError, match="a socket"):
            S.execute(S.plan("P"), "csv", path)


def test_finished_file_mode_follows_umask(tmp_path, capsys):
    old = os.umask(0o027)
    try:
        out = tmp_path / "m.csv"
        assert sweep_cli(["--schemes", "P", "--out", str(out)], capsys)[0] == 0
        assert stat.S_IMODE(os.stat(out).st_mode) == 0o640
    finally:
        os.umask(old)


def test_data_fsynced_before_rename_and_folder_after(tmp_path, monkeypatch):
    events = []
    real_fsync, real_replace = os.fsync, os.replace
    monkeypatch.setattr(store.os, "fsync", lambda fd: events.append(("fsync", stat.S_ISDIR(os.fstat(fd).st_mode))) or real_fsync(fd))
    monkeypatch.setattr(store.os, "replace", lambda a, b: events.append(("replace", os.path.basename(b))) or real_replace(a, b))
    store.write("x\n", tmp_path / "f.txt")
    assert events == [("fsync", False), ("replace", "f.txt"), ("fsync", True)]


def test_254_character_file_name(tmp_path, capsys):
    out = tmp_path / ("n" * 250 + ".csv")
    assert len(out.name) == 254
    assert sweep_cli(["--schemes", "P,LogP", "--light", "sphere:30", "--block", "10", "--out", str(out)], capsys)[0] == 0
    assert out.read_text().startswith("scheme,")
    assert sorted(p.name for p in tmp_path.iterdir()) == [out.name]


def test_254_character_file_name_resumes(tmp_path, capsys):
    out = tmp_path / ("r" * 250 + ".csv")
    with pytest.raises(Stop):
        S.execute(S.plan("P,ZP3+LogP", **ARGS), "csv", out, progress=stop_after(3))
    (work,) = [p for p in tmp_path.iterdir() if p.is_dir()]
    assert len(work.name) <= 255 and work.name.endswith(".parts")
    assert sweep_cli([*ARGV, "--out", str(out), "--resume"], capsys)[0] == 0
    assert out.read_text() == S.execute(S.plan("P,ZP3+LogP", **ARGS))
