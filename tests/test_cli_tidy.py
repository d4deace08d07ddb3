"""What the command line says back: --version, suggestions for misspelt names, numbers and
scheme names echoed as given (one canonical form, docs/cli.rst), tidy per-map output, no NaN
where a value exists."""

from __future__ import annotations

import csv
import io
import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import aliasing
from aliasing import _validation, partitioning, reproduce, schemes
from aliasing.cli import main


def run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exc:  # argparse's exits (--version, usage errors)
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


# --- --version ------------------------------------------------------------------------------


def test_version(capsys):
    code, out, err = run(capsys, "--version")
    assert code == 0 and out == f"aliasing {aliasing.__version__}\n" and not err
    from aliasing._version import __version__

    assert aliasing.__version__ == __version__ == "0.1.0"


# --- did you mean ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "argv, suggestion",
    [
        (["sweeep"], "'sweep'"),
        (["reproduce", "lloyd2006-fig55"], "'lloyd2006-fig5'"),
        (["derive", "lloyd2006.n_prime_of_et"], "'lloyd2006.n_prime_of_eta'"),
        (["sweep", "--schemes", "LogQ"], "'LogP'"),
        (["sweep", "--schemes", "ZP5+LgP"], "'ZP5+LogP'"),
        (["sweep", "--schemes", "lispms"], "'lispsm'"),
        (["sweep", "--schemes", "FPc+LgP"], "'LogP'"),
        (["sweep", "--schemes", "P", "--format", "jsn"], "'json'"),
        (["splits", "--method", "practcal", "--near", "1", "--far", "100", "-k", "3"], "'practical'"),
        (["splits", "--method", "unrael", "--near", "1", "--far", "100"], "'unreal'"),
        (["engines", "--schemes", "csm-stable:unrael"], "'unreal'"),
        (["engines", "--schemes", "csm-stabel:unreal"], "'csm-stable'"),
        (["engines", "--schemes", "csm-stable:unreal:fit=spher"], "'sphere'"),
        (["render", "--scheme", "Lgp", "--out", "never.png"], "'LogP'"),
    ],
)
def test_misspelt_names_get_suggestions(capsys, argv, suggestion):
    code, out, err = run(capsys, *argv)
    assert code == 2 and not out and len(err.splitlines()) == 1, err
    assert f"(did you mean {suggestion}" in err or f"or {suggestion}" in err, err


def test_no_suggestion_for_a_far_off_name(capsys):
    code, _, err = run(capsys, "splits", "--method", "zzzzzz", "--near", "1", "--far", "100")
    assert code == 2 and "did you mean" not in err and "choose one of" in err


@settings(max_examples=60, deadline=None)
@given(st.sampled_from([*partitioning.SPLIT_METHODS, *reproduce.TARGETS, *aliasing.WARPING_RULES]), st.data())
def test_one_typo_is_suggested_back(name, data):
    # a known name with one character deleted, doubled or swapped with its neighbour
    if len(name) < 4:  # too short for a one-letter typo to stay closest (and 'p' leaves no position to draw)
        return
    i = data.draw(st.integers(0, len(name) - 2))
    typo = data.draw(st.sampled_from([name[:i] + name[i + 1 :], name[:i] + name[i] + name[i:], name[:i] + name[i + 1] + name[i] + name[i + 2 :]]))
    known = [*partitioning.SPLIT_METHODS, *reproduce.TARGETS, *aliasing.WARPING_RULES]
    if typo in known:
        return
    assert repr(name) in _validation.did_you_mean(typo, known)


# --- scheme names: one canonical form -------------------------------------------------------


CANONICAL = {"eta": "eta", "LiSPSM": "lispsm", "LISPSM": "lispsm", "log": "LogP", "Log": "LogP", "uniform": "Standard",
             "zp05+log": "ZP5+LogP", "ZP3+GMNPR": "ZP3+gmnpr", "fpc+zp2+p": "FPc+ZP2+P", "pyramid-log": "pyramid-log"}


@pytest.mark.parametrize("typed, name", CANONICAL.items())
def test_canonical_scheme_name(typed, name):
    assert schemes.parse(typed).name == name
    assert schemes.parse(name).name == name  # the canonical form reads back as itself


def test_sweep_and_render_write_the_same_canonical_names(capsys, tmp_path):
    typed = ["eta", "LiSPSM", "log"]
    code, out, _ = run(capsys, "sweep", "--schemes", ",".join(typed), "--light", "overhead", "--format", "json")
    assert code == 0 and [r["scheme"] for r in json.loads(out)] == ["eta", "lispsm", "LogP"]
    code, out, _ = run(capsys, "render", "--scheme", "LiSPSM,log", "--res", "32", "--image-res", "32", "--out", str(tmp_path / "r.png"))
    assert code == 0
    table = out.split("\n", 1)[1]
    assert table.splitlines()[1].split()[0] == "lispsm" and table.splitlines()[2].split()[0] == "LogP"


# --- numbers as typed -----------------------------------------------------------------------


def test_light_angles_echoed_as_typed(capsys, tmp_path):
    code, out, _ = run(capsys, "sweep", "--schemes", "P,ZP2+P", "--light", "gamma:30@azimuth:45", "--format", "json")
    rows = json.loads(out)
    assert code == 0 and {(r["gamma"], r["azimuth"]) for r in rows} == {(30.0, 45.0)}
    for jobs in ("1", "2"):  # streamed through chunk files too
        path = tmp_path / f"s{jobs}.csv"
        code, _, _ = run(capsys, "sweep", "--schemes", "P", "--light", "gamma:10:30:lin:3@azimuth:0,45,gamma:30,front", "--out", str(path), "--jobs", jobs)
        got = [(r["gamma"], r["azimuth"]) for r in csv.DictReader(io.StringIO(path.read_text()))]
        assert code == 0 and got == [("10", "0"), ("10", "45"), ("20", "0"), ("20", "45"), ("30", "0"), ("30", "45"), ("30", "0"), ("0", "0")]
    # the vector's own angle would not read as typed: the echo is the typed number, not a recomputation
    assert float(aliasing.geometry.direction_angles(aliasing.geometry.lights("gamma:30"))[0][0]) != 30.0
    code, out, _ = run(capsys, "sweep", "--schemes", "P", "--light", "gamma:30", "--summary", "--format", "json")
    assert code == 0 and "29.99999" not in out
    code, out, _ = run(capsys, "render", "--scheme", "P", "--light", "gamma:30@azimuth:45", "--res", "32", "--image-res", "32", "--format", "json")
    assert code == 0 and json.loads(out)["gamma"] == 30.0  # not 30.000000000000004 from the eye-space vector


# --- tidy per-map output --------------------------------------------------------------------


def test_sweep_csv_has_one_row_per_map_and_json_arrays(capsys):
    code, out, _ = run(capsys, "sweep", "--schemes", "P,ZP3+P", "--light", "overhead,gamma:30")
    rows = list(csv.DictReader(io.StringIO(out)))
    assert code == 0 and ";" not in out
    assert [(r["scheme"], r["map"]) for r in rows] == [("P", "0"), ("P", "0")] + [("ZP3+P", str(m)) for _ in range(2) for m in range(3)]
    zp = [r for r in rows if r["scheme"] == "ZP3+P" and r["gamma"] == "90"]
    assert [float(r["n_prime"]) for r in zp] == pytest.approx([4.16227766, 41.6227766, 416.227766])  # each map its own n′
    assert len({r["S"] for r in zp}) == 1 and {r["maps"] for r in zp} == {"3"}  # per-direction values repeat
    code, out, _ = run(capsys, "sweep", "--schemes", "P,ZP3+P", "--light", "overhead", "--format", "json")
    data = json.loads(out)
    assert [len(r["M_x"]) for r in data] == [1, 3] and all(isinstance(r[k], list) for r in data for k in ("M_x", "M_z", "n_prime", "eta"))


def test_the_rows_and_the_streamed_csv_agree():
    from aliasing import sweep

    grid = sweep.plan("P,ZP3+P,FP+P", light="hemisphere:40", block=7)
    streamed = sweep.execute(grid, "csv")
    assert streamed == sweep.format_rows(sweep.sweep(["P", "ZP3+P", "FP+P"], light="hemisphere:40"), "csv")
    assert ";" not in streamed and streamed.splitlines()[0].split(",")[5] == "map"


def test_validate_splits_engines_pack_nothing(capsys):
    for argv in (["validate", "--scheme", "ZP3+P", "--f-over-n", "100", "--light", "overhead", "--res", "32", "--probes", "2", "--format", "csv"],
                 ["splits", "--method", "log", "--near", "1", "--far", "100", "-k", "3", "--budget", "4000000", "--image-res", "1024", "--format", "csv"],
                 ["engines", "--schemes", "csm:godot,vsm:high", "--format", "csv"]):
        code, out, err = run(capsys, *argv)
        assert code in (0, 1) and out and ";" not in out, (argv, err)
    code, out, _ = run(capsys, "validate", "--scheme", "ZP3+P", "--f-over-n", "100", "--light", "overhead", "--res", "32", "--probes", "2", "--format", "csv")
    rows = list(csv.DictReader(io.StringIO(out)))
    assert [r["map"] for r in rows] == ["0", "1", "2"] and len({r["S_total"] for r in rows}) == 1


# --- no NaN where a value exists ------------------------------------------------------------


def test_render_table_of_face_partitions_has_no_nan(capsys, tmp_path):
    code, out, _ = run(capsys, "render", "--scheme", "FP+P,P", "--res", "48", "--image-res", "48", "--out", str(tmp_path / "r.png"))
    assert code == 0 and "nan" not in out.lower()
    lines = out.splitlines()
    cascades = [line.split() for line in lines[next(i for i, line in enumerate(lines) if line.split()[:2] == ["scheme", "map"]) + 1 :]]
    face_rows = [row for row in cascades if row[:1] == ["FP+P"]]
    assert face_rows and all(row[2] == row[3] == "—" for row in face_rows)
    assert "— for a face partition's map" in out
    p_row = [row for row in cascades if row[:2] == ["P", "0"]]
    assert p_row and p_row[0][2:4] == ["1", "100"]  # a depth slice keeps its numbers
