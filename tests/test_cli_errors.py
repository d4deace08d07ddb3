"""One error path for the sweep command line (issues 19 and 11): bounded workers, refusal before
allocating, finite numbers, safe config files; every bad input is one line on stderr and exit 2."""

from __future__ import annotations

import os

import pytest

from aliasing import sweep as S
from aliasing.cli import main
from aliasing.sweep import limits, runner


def _run(argv, capsys):
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def _one_line(argv, capsys, needle):
    code, out, err = _run(argv, capsys)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and needle in err, err
    assert "Traceback" not in err and "Warning" not in err
    return err


@pytest.mark.parametrize(
    "argv, needle",
    [
        # issue 19: tracebacks and wrong exit codes
        (["--schemes", "P", "--jobs", "99999999999999999999999"], "--jobs must be a whole number >= 1 and <= "),
        (["--schemes", "ZP5", "--k", "inf"], "k must be finite, got inf"),
        (["--schemes", "LogP", "--param", "tau1=-inf:1:lin:2"], "START must be finite, got -inf"),
        (["--schemes", "P", "--light", "gamma:30@azimuth:Infinity"], "light azimuth must be finite, got inf"),
        (["--schemes", "P", "--light", "gamma:nan"], "light gamma must be finite, got nan"),
        (["--schemes", "P", "--near", "inf"], "--near must be finite, got inf"),
        (["--schemes", "P", "--near", "-1"], "--near must be > 0"),
        (["--schemes", "P", "--f-over-n", "1e400"], "--f-over-n must be finite, got inf"),
        (["--schemes", "P", "--block", "0"], "--block must be a whole number >= 1"),
        (["--schemes", "P", "--block", "1.5"], "--block must be a whole number"),
        # issue 11: empty items in comma lists
        (["--schemes", "P,,LogP"], "schemes has an empty item in 'P,,LogP'"),
        (["--schemes", "P", "--light", "a,,b"], "light has an empty item in 'a,,b'"),
        (["--schemes", "P", "--f-over-n", ",5000"], "--f-over-n has an empty item in ',5000'"),
        # refuse before allocating
        (["--schemes", "P", "--fov", "60:60:log:100000000000"], "fov: this request needs about"),
        (["--schemes", "P", "--light", "sphere:100000000000"], "light: this request needs about"),
        (["--schemes", "ZP99999999+P"], "schemes: this request needs about"),
        (["--schemes", "P", "--k", "1,99999999"], "schemes: this request needs about"),
        (["--schemes", "ZP64+P", "--light", "sphere:20000", "--max-memory", "100M"], "above the limit 100.0 MiB"),
        (["--schemes", "P", "--max-memory", "lots"], "--max-memory must be a size such as 4G"),
        (["--schemes", "P", "--max-memory", "inf"], "--max-memory must be finite"),
    ],
)
def test_sweep_bad_input_is_one_line(argv, needle, capsys):
    _one_line(["sweep", *argv], capsys, needle)


def test_splits_huge_k_is_refused(capsys):
    _one_line(["splits", "--near", "1", "--far", "1000", "-k", "100000000"], capsys, "-k: this request needs about")


def test_max_memory_lets_a_request_through(capsys):
    argv = ["sweep", "--schemes", "ZP64+P", "--light", "sphere:20000", "--summary"]
    _one_line([*argv, "--max-memory", "100M"], capsys, "schemes: this request needs about")
    code, out, _ = _run([*argv, "--max-memory", "2G", "--dry-run"], capsys)
    assert code == 0 and "estimated memory: " in out and "limit 2.0 GiB" in out


def test_memory_model_counts_without_allocating():
    assert limits.axis_count("60:60:log:100000000000") == 100_000_000_000
    assert limits.light_count("sphere:100000000000,overhead") == 100_000_000_001
    assert limits.scheme_counts("ZP99999999+P") == (1, 99_999_999)
    assert limits.scheme_counts("FPc+ZP3+P")[1] == 3 * limits.FACE_MAPS
    assert limits.parse_memory("4G") == 4 * 2**30 and limits.parse_memory("1.5KiB") == 1536
    # the library refuses too, before expanding the axis
    with pytest.raises(ValueError, match="^fov: this request needs about"):
        S.plan("P", fov="60:60:log:100000000000")
    with pytest.raises(ValueError, match="must be <= 100,000,000"):
        S.grid_values("1:2:lin:100000001", "x")


def test_memory_model_bounds_a_measured_peak():
    """The estimate of one chunk is above what tracemalloc measures for it (the model is an upper bound)."""
    import tracemalloc

    from aliasing import geometry, schemes

    lv = geometry.lights("sphere:2000")
    for name, maps in (("ZP8+P", 8), ("LogP", 1), ("FPc+ZP2+P", 2 * limits.FACE_MAPS)):
        schemes.evaluate(name, 1.0, 1000.0, 60.0, lv[:5])
        tracemalloc.start()
        schemes.evaluate(name, 1.0, 1000.0, 60.0, lv)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        model = len(lv) * maps * limits.ARRAYS_PER_MAP * 8
        assert peak <= model * 1.1, (name, peak, model)


# ---- workers bounded -------------------------------------------------------------------


def test_jobs_cap_is_four_times_cores(capsys):
    cap = runner.max_jobs()
    assert cap == 4 * runner.cores()
    _one_line(["sweep", "--schemes", "P", "--jobs", str(cap + 1)], capsys, f"<= {cap}")
    with pytest.raises(ValueError, match=rf"jobs must be a whole number >= 1 \(local processes\) and <= {cap}"):
        S.execute(S.plan("P"), jobs=cap + 1)


def test_never_more_processes_than_chunks(monkeypatch):
    import concurrent.futures

    seen = []
    real = concurrent.futures.ProcessPoolExecutor

    def spy(max_workers=None, **kw):
        seen.append(max_workers)
        return real(max_workers=max_workers, **kw)

    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", spy)
    grid = S.plan("P,LogP", light="sphere:20", block=10)  # 4 chunks
    assert grid.chunks == 4
    text = S.execute(grid, jobs=min(runner.max_jobs(), 8))
    assert seen == [4] and text == S.execute(grid)


# ---- configs --------------------------------------------------------------------------


def test_config_fifo_is_refused_without_blocking(tmp_path, capsys):
    fifo = tmp_path / "cfg.toml"
    os.mkfifo(fifo)
    _one_line(["sweep", "--config", str(fifo)], capsys, "is not a regular file")


@pytest.mark.parametrize(
    "content, needle",
    [
        (b"params = { eta = " + b"[" * 5000 + b"]" * 5000 + b" }\n", "nested too deeply"),
        (b'schemes = "\xff\xfe"\n', "is not UTF-8 text"),
        (b"schemes = 'P'\n" + b"#" * (2 << 20) + b"\n", "a config is at most"),
        (b"schemes = [", "is not valid TOML"),
    ],
    ids=["deep", "not-utf8", "too-large", "bad-toml"],
)
def test_bad_config_files_are_one_line(tmp_path, capsys, content, needle):
    path = tmp_path / "c.toml"
    path.write_bytes(content)
    _one_line(["sweep", "--config", str(path)], capsys, needle)


def test_config_folder_and_missing_file(tmp_path, capsys):
    _one_line(["sweep", "--config", str(tmp_path)], capsys, "is not a regular file")
    _one_line(["sweep", "--config", str(tmp_path / "nope.toml")], capsys, "cannot be read: No such file")


def test_no_runtime_warning_text_reaches_stderr(capsys):
    # a legitimate sweep into the light (inf and NaN cells) prints data, and no warning text
    code, out, err = _run(["sweep", "--schemes", "LogP,P,ETA", "--light", "behind,overhead,front"], capsys)
    assert code == 0 and err == "" and "inf" in out


# ---- render --out -----------------------------------------------------------------------


def test_render_out_fifo_is_one_line(tmp_path, capsys):
    fifo = tmp_path / "p.png"
    os.mkfifo(fifo)
    _one_line(["render", "--res", "32", "--image-res", "32", "--out", str(fifo)], capsys, "is not a regular file (a FIFO)")


def test_render_out_symlink_and_readonly(tmp_path, capsys):
    real = tmp_path / "real.png"
    real.write_bytes(b"old")
    link = tmp_path / "link.png"
    link.symlink_to(real)
    code, out, err = _run(["render", "--res", "32", "--image-res", "32", "--out", str(link)], capsys)
    assert code == 0 and err == "" and link.is_symlink() and real.read_bytes()[:4] == b"\x89PNG"
    if os.geteuid() == 0:  # root ignores the mode bits; test_render_out_permission_errors_are_one_line simulates it
        pytest.skip("root may write read-only files")
    ro = tmp_path / "ro"
    ro.mkdir()
    (ro / "x.png").write_bytes(b"old")
    os.chmod(ro / "x.png", 0o444)
    os.chmod(ro, 0o555)
    try:
        _one_line(["render", "--res", "32", "--image-res", "32", "--out", str(ro / "x.png")], capsys, "cannot be written")
        _one_line(["render", "--res", "32", "--image-res", "32", "--out", str(ro / "y.png")], capsys, "cannot be written")
    finally:
        os.chmod(ro, 0o755)


def test_validate_grid_empty_scheme_item_is_one_line(capsys):
    _one_line(["validate", "--grid", "--scheme", ",uniform", "--f-over-n", "10", "--light", "gamma:60"], capsys, "schemes has an empty item in ',uniform'")


def test_render_out_permission_errors_are_one_line(tmp_path, capsys, monkeypatch):
    """A read-only file or folder (simulated: the suite may run as root, who may write anyway)."""
    from aliasing.sweep import store

    argv = ["render", "--res", "32", "--image-res", "32", "--out", str(tmp_path / "x.png")]
    monkeypatch.setattr(store.os, "access", lambda path, mode: False)
    _one_line(argv, capsys, "cannot be written (permission denied)")
    monkeypatch.undo()

    def denied(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(store.tempfile, "mkstemp", denied)
    _one_line(argv, capsys, "cannot be written: Permission denied")
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize(
    "argv",
    [
        ["sweep", "--schemes", "P", "--fov", "60:60:log:100000000000"],
        ["sweep", "--schemes", "P", "--light", "sphere:100000000000"],
        ["sweep", "--schemes", "ZP99999999+P"],
        ["splits", "--near", "1", "--far", "1000", "-k", "100000000"],
        ["sweep", "--config", "FIFO"],
    ],
    ids=["fov-count", "light-count", "zp-k", "splits-k", "config-fifo"],
)
def test_absurd_requests_in_a_subprocess_with_limits(argv, tmp_path):
    """As a user runs them: a separate process under a 2 GiB address-space limit and a time limit;
    one line and exit 2, never a kill (the kernel's answer before) or a hang."""
    import resource
    import subprocess
    import sys

    if "FIFO" in argv:
        os.mkfifo(tmp_path / "cfg.toml")
        argv = [a.replace("FIFO", str(tmp_path / "cfg.toml")) for a in argv]

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))

    proc = subprocess.run([sys.executable, "-c", "import sys; from aliasing.cli import main; sys.exit(main(sys.argv[1:]))", *argv],
                          capture_output=True, text=True, timeout=120, preexec_fn=limit)
    assert proc.returncode == 2 and proc.stdout == "" and len(proc.stderr.strip().splitlines()) == 1, proc.stderr
