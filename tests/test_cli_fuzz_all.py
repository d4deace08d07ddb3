"""Fuzzing every subcommand but ``sweep`` (which has tests/test_cli_fuzz.py): issue 19 item 5.

Generated argument lists from each subcommand's documented vocabulary (its options, their help
and epilog) mixed with garbage (NaN, ±inf, 1e400, empty list items, unicode, huge counts,
malformed ranges), run in-process through ``aliasing.cli.main``; plus a handful in a
subprocess under a time and an address-space limit.  The outcome is exit 0, or exit 2 with
exactly one line on stderr; never a traceback, warning text or another exit code.  The one
exception is documented: ``aliasing validate`` exits 1 when a validation FAILs (its report on
stdout, nothing on stderr).

Kept cheap: resolutions, probe and direction counts in the vocabulary are small (a valid run
takes well under a second), ``reproduce`` only gets ``--list`` or an unknown target, ``derive``
only ``--list`` or quick derivations.  Deterministic (profile "ci" in conftest.py);
``ALIASING_HYPOTHESIS=long`` scales every count up (and is not derandomized); ``FUZZ_DEBUG=1``
prints every command line and its stderr line (for reading what the fuzz reaches).
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import warnings

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from aliasing.cli import main  # noqa: E402

NUMBERS = ["1", "10", "100", "60", "0", "-1", "0.5", "1.5", "inf", "-inf", "nan", "Infinity", "1e400", "-1e400", "99999999999999999999999", "", " ", ",", "1,,2", "٣", "0x10", "1_0"]
INTS = ["0", "1", "2", "3", "4", "-1", "1.5", "nan", "inf", "1e400", "99999999999999999999999", "", "x"]
SMALL_RES = ["16", "32", "48", "64"]  # valid resolutions stay cheap
VECTORS = ["0,1,0", "1,2,0.5", "0,0,0", "1,1", "1,2,3,4", "nan,1,0", "inf,0,0", "1e400,0,0", "a,b,c", ",,", "1,,2", ""]
LIGHT_SPECS = ["overhead", "behind", "front", "gamma:30", "gamma:150@azimuth:45", "gamma:nan", "gamma:inf", "gamma:1e400", "gamma:30@azimuth:Infinity",
               "gamma:30@tilt:5", "gamma:", "gamma:1x", "a,,b", "sphere:5", "hemisphere:3", "sphere:-4", "sphere:0", "sphere:100000000000", "sphere:", ""]


ASPECTS = ["1", "2", "0.5", "1.7778", "0", "-1", "nan", "inf", "1e-300", "1e300", "1,2"]  # --aspect: image width/height


def _garbage(digits: bool = True):
    """Arbitrary short text; without digits where a parsed number could mean a huge (slow) request."""
    text = st.text(max_size=12)
    return text if digits else text.filter(lambda s: not any(ch.isdigit() for ch in s))


def _value(vocab, digits: bool = True):
    """Mostly the vocabulary, one time in five garbage."""
    return st.integers(0, 4).flatmap(lambda i: _garbage(digits) if i == 0 else st.sampled_from(vocab))


def _opt(flag, vocab, digits: bool = True):
    return st.tuples(st.just(flag), _value(vocab, digits))


def _flag(*flags):
    return st.tuples(st.sampled_from(flags))


def _argv(options, min_size=0, max_size=6):
    """Lists of options; one time in eight with a stray garbage word somewhere."""
    lists = st.lists(st.one_of(*options), min_size=min_size, max_size=max_size).map(lambda o: [p for opt in o for p in opt])
    stray = st.tuples(lists, _garbage(digits=False), st.integers(0, 20)).map(lambda t: [*t[0][: t[2]], t[1], *t[0][t[2]:]])
    return st.integers(0, 7).flatmap(lambda i: stray if i == 0 else lists)


def _scale(n: int) -> int:
    """``n`` examples in CI; the "long" profile's count when that is larger."""
    return max(n, settings.default.max_examples // 6)


def _run(argv, capsysbinary, ok_fail: bool = False) -> int:
    with warnings.catch_warnings(record=True) as caught:  # pytest would swallow them: a real run prints them on stderr
        warnings.simplefilter("always")
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse usage errors and --help
            code = exc.code
    out, err = capsysbinary.readouterr()
    text = err.decode(errors="replace")
    assert "Traceback" not in text and "Warning" not in text, (argv, text)
    assert not caught, (argv, [f"{w.category.__name__}: {w.message}" for w in caught])
    if ok_fail and code == 1:  # validate: a FAIL verdict, reported on stdout or in --out
        assert text == "", (argv, text)
        return code
    assert code in (0, 2), (argv, code, text)
    if code == 2:
        assert len(text.strip().splitlines()) == 1, (argv, text)
    if os.environ.get("FUZZ_DEBUG"):
        print("ERR", code, text.strip()[:160].replace(chr(10), " "), "ARGV", argv, file=sys.__stderr__)
    return code


def _fuzz(strategy, capsysbinary, examples: int, ok_fail: bool = False) -> dict:
    counts: dict = {}

    @settings(max_examples=examples, deadline=None, suppress_health_check=list(HealthCheck))
    @given(strategy)
    def run(argv):
        code = _run(argv, capsysbinary, ok_fail)
        counts[code] = counts.get(code, 0) + 1

    run()
    assert sum(counts.values()) >= examples and counts.get(2), counts
    if os.environ.get("FUZZ_DEBUG"):
        print("COUNTS", counts)
    return counts


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("fuzzall")
    verts = "v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nv -1 0 -1\nv 1 0 -1\nv 1 2 -1\nv -1 2 -1\n"
    (tmp / "s.obj").write_text(verts + "f 1 2 3 4\nf 5 6 7 8\n")  # a ground and a wall
    (tmp / "bad.obj").write_text("v 1 2\nf 1 2 9\n\x00garbage")
    (tmp / "empty.obj").write_text("")
    (tmp / "h.csv").write_text("z_lo,z_hi,count\n10,100,5\n100,1000,3\n")
    (tmp / "hbad.csv").write_text("z_lo,z_hi,count\n10,nan,5\n1e400,1,-3\n")
    (tmp / "ro").mkdir()
    return tmp


# --------------------------------------------------------------------------- reproduce, derive


def test_reproduce_fuzz(folder, capsysbinary):
    from aliasing.reproduce import TARGETS

    bad = ["nope", "ALL ", "lloyd2006-fig", "", "..", "lloyd2006-fig5,lloyd2006-fig6", "∞"]
    outs = [str(folder / "rep"), "/dev/null", str(folder / "s.obj"), "", "\x00"]
    listed = st.lists(st.one_of(_opt("--out", outs), st.tuples(st.sampled_from(list(TARGETS) + bad)), _flag("--bogus", "-x"), st.tuples(_garbage())), max_size=4)
    # never a real figure run: --list, or at least one target that does not exist
    with_list = listed.map(lambda o: ["reproduce", "--list", *(p for opt in o for p in opt)])
    with_bad = st.tuples(listed, st.one_of(st.sampled_from(bad), _garbage().filter(lambda s: s not in TARGETS and not s.startswith("-")))).map(
        lambda t: ["reproduce", *(p for opt in t[0] for p in opt), t[1]])
    _fuzz(st.one_of(with_list, with_bad.filter(lambda a: "--list" not in a and "--help" not in a and "-h" not in a)), capsysbinary, _scale(100))


QUICK_DERIVATIONS = ["lloyd2007.F_p", "zhang2007.varphi", "lloyd2006.S_zp_behind", "lloyd2007.dB_dmu", "lloyd2007.delta_e_3d", "engines.sphere_radius", "wimmer2004.s"]


def test_derive_fuzz(capsysbinary):
    bad = ["nope", "lloyd2006", "LLOYD2007.F_P", "", "lloyd2007.F_p ", "..", "∂"]
    names = st.lists(st.one_of(st.sampled_from(QUICK_DERIVATIONS + bad), _garbage().filter(lambda s: not s.startswith("-"))), min_size=1, max_size=3)
    extra = st.lists(st.one_of(_flag("--latex", "--bogus"), st.tuples(_garbage(digits=False).filter(lambda s: not s.startswith("-")))), max_size=2)
    # never the default (every derivation, over a minute): --list, or at least one name
    argv = st.one_of(
        extra.map(lambda o: ["derive", "--list", *(p for opt in o for p in opt)]),
        st.tuples(names, extra).map(lambda t: ["derive", *t[0], *(p for opt in t[1] for p in opt)]),
    )
    _fuzz(argv, capsysbinary, _scale(80))


# --------------------------------------------------------------------------- splits


def test_splits_fuzz(capsysbinary):
    from aliasing.partitioning import SPLIT_METHODS

    methods = list(SPLIT_METHODS) + ["", "nope", "LOG", "log,uniform"]
    options = [
        _opt("--method", methods),
        _opt("--lambda", NUMBERS),
        _opt("--param", ["ratio=2", "bias=0", "resolution_ratio=2", "padding=1", "exponent=3", "ratio=nan", "bias=inf", "=1", "ratio", "ratio=1e400", "exponent=-1"]),
        _opt("--near", NUMBERS),
        _opt("--far", NUMBERS),
        _opt("-k", INTS + ["8", "100000000"]),
        _opt("--fov", NUMBERS + ["179.9", "180"]),
        _opt("--light", LIGHT_SPECS, digits=False),
        _opt("--warp", ["Standard", "P", "LogP", "eta", "tsm", "ZP2+P", "", "nope"]),
        _opt("--budget", NUMBERS + ["1e6", "4194304"]),
        _opt("--image-res", NUMBERS + ["512", "1920"]),
        _opt("--allocations", ["error,equal", "pow2", "error,,equal", ",", "", "nope", "equal"]),
        _opt("--format", ["table", "csv", "json", "xml"]),
        _opt("--max-memory", ["4G", "1", "0", "lots", "inf", "-1G", "1e30T"]),
        _flag("--list"),
    ]
    base = st.tuples(st.sampled_from(["1", "0.5", "10"]), st.sampled_from(["100", "1000", "2"]), st.sampled_from(["1", "3", "4"])).map(lambda t: ["--near", t[0], "--far", t[1], "-k", t[2]])
    argv = st.tuples(st.one_of(st.just([]), base), _argv(options)).map(lambda t: ["splits", *t[0], *t[1]])
    _fuzz(argv, capsysbinary, _scale(200))


# --------------------------------------------------------------------------- render


def test_render_fuzz(folder, capsysbinary, monkeypatch):
    monkeypatch.chdir(folder)
    outs = [str(folder / "o.png"), str(folder / "ro"), str(folder / "missing" / "o.png"), "/dev/null", "", str(folder / ("n" * 250 + ".png")), str(folder / "o.txt")]
    scenes = [str(folder / "s.obj"), str(folder / "bad.obj"), str(folder / "empty.obj"), str(folder / "nope.glb"), str(folder), "/dev/null", str(folder / "h.csv")]
    options = [
        _opt("--scheme", ["Standard", "P", "LogP", "ZP2+P", "FPc+P", "Standard,P", "P,,LogP", ",", "nope", "ZP99999999+P", "eta"]),
        _opt("--f-over-n", NUMBERS),
        _opt("--fov", NUMBERS + ["179.9"]),
        _opt("--light", LIGHT_SPECS, digits=False),
        _opt("--what", ["shadows", "grid", "error", "cdf", "nope"]),
        st.tuples(st.just("--out"), st.sampled_from(outs)),
        _opt("--res", SMALL_RES + ["0", "-1", "nan", "99999999999", "1e400", ""], digits=False),
        _opt("--image-res", SMALL_RES + ["0", "-1", "nan", "99999999999", ""], digits=False),
        _opt("--every", ["1", "4", "16", "0", "-3", "99999999999", "nan"], digits=False),
        _opt("--seed", INTS),
        st.tuples(st.just("--scene"), st.sampled_from(scenes)),
        _opt("--eye", ["0,3,-8"] + VECTORS),
        _opt("--target", ["0,0,0"] + VECTORS),
        _opt("--up", VECTORS),
        _opt("--camera", ["cam", "", "Camera"]),
        _opt("--near", NUMBERS),
        _opt("--far", NUMBERS),
        _opt("--light-dir", VECTORS),
        _opt("--splits", ["log", "pssm", "practical", "filament", "bgfx", "nope", ""]),
        _opt("--lambda", NUMBERS),
        _opt("-k", ["1", "2", "3", "0", "-1", "99999999", "nan"], digits=False),
        _opt("--param", ["ratio=2", "bias=0", "ratio=nan", "=1", "ratio", "exponent=1e400"]),
        _opt("--allocation", ["equal", "error", "pow2"]),
        _opt("--format", ["text", "json", "xml", ""]),
        _opt("--aspect", ASPECTS),
    ]
    cheap = ["--res", "32", "--image-res", "32"]  # generated options may override these
    sink = st.sampled_from([["--format", "json"], ["--out", str(folder / "o.png")], ["--out", str(folder / "o.png"), "--format", "json"], []])
    argv = st.tuples(sink, _argv(options)).map(lambda t: ["render", *cheap, *t[0], *t[1]])
    _fuzz(argv, capsysbinary, _scale(150))


# --------------------------------------------------------------------------- validate


def test_validate_fuzz(folder, capsysbinary):
    schemes = ["P", "LogP", "Standard", "ZP2+P", "FPc+P", "eta", "tsm", "P,LogP", "P,,LogP", ",uniform", ",", "nope", "P,p", "ZP99999999+P", ""]
    options = [
        _opt("--scheme", schemes),
        _opt("--f-over-n", NUMBERS + ["10:100:log:2", "10:1000:log:100000000000", "1:2:lin:0", "1:nan:lin:2", "::", "10,100"]),
        _opt("--fov", NUMBERS + ["30:90:lin:2", "0:180:lin:3"]),
        _opt("--light", LIGHT_SPECS + ["gamma:30,gamma:150", "gamma:0:180:lin:100000000000", "gamma:30:150:lin:2@azimuth:0,90"], digits=False),
        _opt("--res", SMALL_RES + ["0", "15", "2049", "-1", "99999999999", "nan"], digits=False),
        _opt("--image-res", ["32", "512", "0", "-1", "nan", "99999999999"]),
        _opt("--probes", ["2", "4", "8", "1", "0", "300", "nan"], digits=False),
        _opt("--seed", INTS + ["4294967296"]),
        _opt("--reach", NUMBERS),
        _opt("--format", ["text", "json", "csv", "netcdf", "xml"]),
        _flag("--grid", "--resume", "--dry-run"),
        _opt("--jobs", ["1", "0", "-1", "nan", "99999999999"], digits=False),  # never 2+: process start-up is slow here
        st.tuples(st.just("--out"), st.sampled_from([str(folder / "v.csv"), str(folder / "ro"), "/dev/null", "", str(folder / ("n" * 250 + ".csv"))])),
        _opt("--dask", ["", "nope", "tcp://"]),
        _opt("--aspect", ASPECTS),
    ]
    scene = [
        st.tuples(st.just("--scene"), st.sampled_from([str(folder / "s.obj"), str(folder / "bad.obj"), str(folder / "empty.obj"), str(folder / "nope.obj"), "/dev/null"])),
        _opt("--eye", ["0,3,-8"] + VECTORS),
        _opt("--target", ["0,0,0"] + VECTORS),
        _opt("--up", VECTORS),
        _opt("--camera", ["cam", ""]),
        _opt("--near", NUMBERS),
        _opt("--far", NUMBERS),
        _opt("--light-dir", VECTORS),
        _opt("--splits", ["log", "pssm", "filament", "nope", ""]),
        _opt("--lambda", NUMBERS),
        _opt("-k", ["1", "2", "0", "-1", "99999999", "nan"], digits=False),
        _opt("--param", ["ratio=2", "ratio=nan", "=1", "ratio"]),
    ]
    base = ["--scheme", "P", "--f-over-n", "100", "--res", "32", "--probes", "4"]  # cheap defaults, overridable
    probes = _argv(options).map(lambda a: ["validate", *base, *a])
    grid = _argv(options, max_size=4).map(lambda a: ["validate", "--grid", *base, *a])
    scenes = _argv(scene + options[:5] + options[-1:], max_size=6).map(lambda a: ["validate", *base, "--scene", str(folder / "s.obj"), "--eye", "0,3,-8", "--target", "0,0,0", *a])
    bare = _argv(options + scene, max_size=4).map(lambda a: ["validate", *a])  # missing required options too
    _fuzz(st.one_of(probes, grid, scenes, bare), capsysbinary, _scale(260), ok_fail=True)


# --------------------------------------------------------------------------- engines


def test_engines_fuzz(folder, capsysbinary):
    specs = ["csm:filament", "csm-stable:filament", "csm:log:k=4", "csm:pssm:k=3", "csm-stable:godot:fit=sphere:snap=pad", "sdsm:k=4", "sdsm:zmin=10:zmax=1000",
             "sdsm:method=adaptive", "sdsm:method=kmeans:k=3", "vsm:high", "vsm:epic", "vsm:bias=1:first=0:last=8:pool=64", "matched", "exact",
             "csm:log:k=99999999", "vsm:bias=nan", "sdsm:zmin=inf", "csm:", "nope", "", "csm:filament,,exact", ",", "vsm:pool=1e400", "vsm:high:first=nan", "vsm:high:last=inf", "vsm:high:pool=2.5", "vsm:high:first=1.5", "csm:log:k=0"]
    options = [
        st.tuples(st.just("--schemes"), st.one_of(st.sampled_from(specs), st.lists(st.sampled_from(specs), min_size=1, max_size=3).map(",".join), _garbage())),
        _opt("--fov", NUMBERS + ["179.9"]),
        _opt("--near", NUMBERS),
        _opt("--far", NUMBERS + ["100000"]),
        _opt("--image-res", ["1920", "64", "0", "-1", "nan", "99999999999"]),
        _opt("--shadow-res", ["2048", "64", "0", "-1", "nan", "99999999999"]),
        _opt("--unit", ["cm", "m", "mm", "in", "ft", "km", ""]),
        _opt("--light", LIGHT_SPECS + ["hemisphere:200"], digits=False),
        _opt("--ground", NUMBERS),
        st.tuples(st.just("--histogram"), st.sampled_from([str(folder / "h.csv"), str(folder / "hbad.csv"), str(folder / "empty.obj"), str(folder / "nope.csv"), str(folder), "/dev/null"])),
        _opt("--format", ["table", "csv", "json", "xml"]),
        _flag("--list"),
    ]
    argv = _argv(options).map(lambda a: ["engines", "--light", "sphere:5", *a])  # few directions by default
    _fuzz(argv, capsysbinary, _scale(200))


# --------------------------------------------------------------------------- the command itself


def test_top_level_fuzz(capsysbinary):
    words = ["reproduce", "derive", "splits", "validate", "render", "engines", "spl", "Sweep", "", "-h", "--help", "--bogus", "--fo", "--version"]
    # a subcommand word followed only by help/garbage: parsing errors, help text, never a computation
    argv = st.lists(st.one_of(st.sampled_from(words), _garbage(digits=False)), max_size=3).filter(
        lambda a: not a or a[0] not in words[:6] or any(w in ("-h", "--help") for w in a) or len(a) > 1)
    argv = argv.filter(lambda a: "--" not in a and not (a and a[0] == "derive" and all(w in ("derive", "--latex") for w in a)))  # "--": every target/derivation
    _fuzz(argv, capsysbinary, _scale(50))


# --------------------------------------------------------------------------- a sample in a subprocess

SUBPROCESS = [
    ["validate", "--scheme", "P", "--f-over-n", "100", "--res", "2048", "--probes", "256", "--light", "gamma:nan"],
    ["validate", "--grid", "--scheme", "P", "--f-over-n", "10:1000:log:100000000000", "--dry-run"],
    ["render", "--res", "99999999999", "--image-res", "32", "--format", "json"],
    ["render", "--image-res", "99999999", "--format", "json"],
    ["splits", "--near", "1", "--far", "100", "-k", "100000000", "--light", "sphere:100000000000"],
    ["engines", "--light", "sphere:100000000000"],
    ["engines", "--schemes", "csm:log:k=99999999"],
    ["derive", "nope", "lloyd2006.m_x"],
]


def _limits():  # pragma: no cover - runs in the child
    resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))


@pytest.mark.parametrize("argv", SUBPROCESS, ids=lambda a: " ".join(a)[:40])
def test_absurd_requests_in_a_limited_subprocess(argv, tmp_path):
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    proc = subprocess.run([sys.executable, "-m", "aliasing.cli", *argv], capture_output=True, text=True, timeout=60, preexec_fn=_limits, cwd=tmp_path, env=env)
    assert proc.returncode == 2, (argv, proc.returncode, proc.stderr[-2000:])
    assert len(proc.stderr.strip().splitlines()) == 1 and "Traceback" not in proc.stderr, proc.stderr[-2000:]


# --------------------------------------------------------------------------- file scenarios found by the fuzz

FILES = [
    (["engines", "--light", "sphere:3", "--schemes", "sdsm:method=adaptive", "--histogram", "fifo.csv"], "not a regular file"),  # hung forever
    (["engines", "--light", "sphere:3", "--schemes", "sdsm:method=adaptive", "--histogram", "header.csv"], "no bins"),  # numpy's UserWarning first
    (["render", "--scene", "fifo.obj", "--eye", "0,3,-8", "--target", "0,0,0", "--format", "json"], "not a regular file"),  # said "does not exist"
    (["validate", "--scheme", "P", "--scene", "fifo.obj", "--eye", "0,3,-8", "--target", "0,0,0"], "not a regular file"),
    (["engines", "--light", "sphere:3", "--schemes", "vsm:pool=1e400"], "pool must be finite"),  # OverflowError, no parameter named
    (["engines", "--light", "sphere:3", "--schemes", "vsm:high:first=1.5"], "first (clipmap level) must be a whole number"),  # silently truncated
]


@pytest.mark.parametrize("argv, message", FILES, ids=lambda a: " ".join(a)[:50] if isinstance(a, list) else None)
def test_file_scenarios_are_one_line(argv, message, tmp_path):
    os.mkfifo(tmp_path / "fifo.csv")
    os.mkfifo(tmp_path / "fifo.obj")
    (tmp_path / "header.csv").write_text("z_lo,z_hi,count\n")
    proc = subprocess.run([sys.executable, "-m", "aliasing.cli", *argv], capture_output=True, text=True, timeout=60, cwd=tmp_path)
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1 and message in proc.stderr, proc.stderr


EXTREMES = [  # found by probing the edges of the documented ranges: (argv, exit code, text on stderr or in stdout)
    (["engines", "--light", "sphere:3", "--ground", "1e308"], 0, "vsm:high"),  # OverflowError (h**2) before
    (["engines", "--light", "sphere:3", "--fov", "1e-300", "--format", "csv"], 2, "must be at least 1e-06 degrees"),  # OverflowError (worst**2) before; now refused by the shared fov check
    (["engines", "--light", "sphere:3", "--schemes", "vsm:high:first=-99999:last=99999"], 2, "first (clipmap level) must be a whole number in [-64, 64]"),  # OverflowError
    (["render", "--f-over-n", "abc", "--format", "json"], 2, "--f-over-n must be a number"),  # "could not convert string to float"
    (["render", "--seed", "-1", "--format", "json"], 2, "--seed must be a whole number >= 0"),  # numpy's "expected non-negative integer"
    (["render", "--f-over-n", "1e300", "--scheme", "LogP", "--format", "json"], 2, "far/near must be <= 1e+15 for the rasterizer"),  # "points must not be NaN"
    (["validate", "--scheme", "LogP", "--f-over-n", "1e30", "--res", "32", "--probes", "4"], 2, "far/near must be <= 1e+15"),  # "row_centres must be 32 increasing values"
    (["validate", "--scheme", "P", "--f-over-n", "100", "--fov", "1e-300", "--res", "32", "--probes", "4"], 2, "must be at least 1e-06 degrees"),  # "points must not be NaN"
    (["splits", "--near", "1e-300", "--far", "1e300", "-k", "3"], 2, "far/near must be at most 1.8e308"),  # "edges as (near_i, far_i) need equal lengths ..."
    (["validate", "--scheme", "P", "--scene", "s.obj", "--eye", "0,3,-8", "--target", "0,0,0", "--fov", "abc"], 2, "--fov must be a number"),  # float()'s message
]


@pytest.mark.parametrize("argv, code, text", EXTREMES, ids=lambda a: " ".join(a)[-40:] if isinstance(a, list) else None)
def test_extremes(argv, code, text, capsys):
    assert main(argv) == code
    out, err = capsys.readouterr()
    assert text in (err if code else out) and "nan" not in out.lower() and len(err.strip().splitlines()) == code // 2, (out, err)


def test_dask_address_of_a_server_that_never_answers_is_one_line(capsys, monkeypatch):
    """--dask at a port that accepts but never speaks Dask (e.g. an HTTP server) waited forever."""
    pytest.importorskip("distributed")
    import socket
    import threading

    from aliasing.sweep import runner

    monkeypatch.setattr(runner, "DASK_TIMEOUT", 1.0)
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()
    held = []
    threading.Thread(target=lambda: held.append(server.accept()), daemon=True).start()
    try:
        argv = ["validate", "--grid", "--scheme", "P", "--f-over-n", "100", "--res", "32", "--probes", "4", "--dask", f"tcp://127.0.0.1:{server.getsockname()[1]}"]
        assert main(argv) == 2
    finally:
        server.close()
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "cannot reach a Dask scheduler" in err and "is it a Dask scheduler?" in err, err
