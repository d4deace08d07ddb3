"""``aliasing tune``'s wrong-pixel objective: the search, the Pareto front, the why lines, the exit status, ``--frames``.

Small cameras (far 60) and small maps keep each search to seconds.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aliasing import setups
from aliasing.cli import main
from aliasing.tune import pixels
from aliasing.tune.command import INFEASIBLE
from aliasing.tune.measure import limits
from conftest import need_frames

ROOT = Path(__file__).resolve().parents[1]

CAMERA = "near=0.5,far=60,fov=50,aspect=16:9,height=720"
PLAYCANVAS = ["tune", "--engine", "playcanvas", "--set", "numCascades=2", "--set", "shadowResolution=512", "--set", "shadowBias=0",
              "--camera", CAMERA, "--sun", "30..50"]


def _json(capsys, argv, code=0):
    assert main(argv + ["--format", "json"]) == code
    out = capsys.readouterr()
    return json.loads(out.out), out.err


@pytest.fixture(scope="module")
def playcanvas():
    """The command's JSON for PlayCanvas from shadowBias 0 (acne over the whole ground)."""
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(PLAYCANVAS + ["--format", "json"]) == 0
    return json.loads(buf.getvalue())


def test_the_objective_is_wrong_pixels_and_falls(playcanvas):
    got = playcanvas
    assert got["objective_kind"] == "wrong" and got["objective_note"] is None
    w = got["wrong"]
    assert w["before"]["acne"] > 0.1  # shadowBias 0: acne
    assert w["after"]["wrong"] < w["before"]["wrong"] / 10
    assert w["sample"]["height_px"] == pixels.HEIGHT and w["final"]["height_px"] == pixels.FINAL_HEIGHT
    assert got["settings"]["shadowBias"] > 0


def test_readme_numbers(playcanvas):
    """README's 'Tune your engine' (this fixture's command): wrong pixels 42.3 % → 0.719 %, and its why line for shadowBias."""
    w = playcanvas["wrong"]
    assert (f"{100 * w['before']['wrong']:.3g}", f"{100 * w['after']['wrong']:.3g}") == ("42.3", "0.719")
    line = next(x["line"] for x in playcanvas["why"] if x["key"] == "shadowBias")
    assert line == ("shadowBias 0 → 0.1486: wrong pixels 35.6 % → 0.798 %, acne 21.8 % → 0 %, false shadow 13.4 % → 0.169 %, "
                    "lost shadow 0.369 % → 0.629 %")
    with open(ROOT / "README.md", encoding="utf-8") as f:
        readme = f.read()
    assert "wrong pixels fall from 42.3 % to\n0.719 %" in readme and line in readme


def test_every_change_has_its_why_line(playcanvas):
    got = playcanvas
    assert {c["key"] for c in got["changes"]} == {w["key"] for w in got["why"]}
    for w in got["why"]:
        assert w["line"].startswith(f"{w['key']} ") and "→" in w["line"]


def test_the_front_is_not_dominated_and_the_pick_is_first(playcanvas):
    front = playcanvas["pareto"]
    assert front
    keys = ("wrong", "px_per_texel", "memory")
    for a in front[1:]:  # the front; the pick first may be beaten there within the noise only
        for b in front[1:]:
            if a is not b:
                assert not (all(a[k] <= b[k] for k in keys) and any(a[k] < b[k] for k in keys))
    assert front[0]["changed"] == playcanvas["changed"]
    assert [p["wrong"] for p in front[1:]] == sorted(p["wrong"] for p in front[1:])
    n = playcanvas["wrong"]["sample"]["pixels"]
    best = min(p["wrong"] for p in front)
    assert n > 1000 and not pixels.significant(best, front[0]["wrong"], n)  # the pick: within the noise of the fewest


_POINT = st.builds(lambda w, t, m, k: pixels.Point({"k": k}, w, 0.0, 0.0, w, t, m), st.floats(0, 1), st.floats(0.1, 1e3),
                   st.sampled_from([1.0, 4.0, 16.0]), st.integers(0, 10**6))


@settings(max_examples=40, deadline=None)
@given(st.lists(_POINT, max_size=12), st.sampled_from(sorted(pixels.PREFER)))
def test_front_of_any_points(points, prefer):
    got = pixels.front(points, prefer)
    axes = pixels.PREFER[prefer]
    assert [p.axes(prefer) for p in got] == sorted(p.axes(prefer) for p in got)
    for p in points:  # every point is on the front or beaten (or equalled) by one on it
        assert any(all(getattr(q, a) <= getattr(p, a) for a in axes) for q in got)


@settings(max_examples=60, deadline=None)
@given(st.lists(_POINT, min_size=1, max_size=12), st.integers(0, 10**5))
def test_the_pick_is_the_fewest_changes_within_the_noise(points, n):
    start = {"k": points[0].settings["k"]}
    got = pixels.front(points, "wrong", start, n)
    best = min(p.wrong for p in points)
    tied = [p for p in points if not pixels.significant(best, p.wrong, n)]  # the front's and those beaten only within the noise
    assert got[0] in tied
    changes = [sum(start.get(k) != v for k, v in p.settings.items()) for p in tied]
    assert sum(start.get(k) != v for k, v in got[0].settings.items()) == min(changes)
    assert [p.axes("wrong") for p in got[1:]] == sorted(p.axes("wrong") for p in got[1:])
    rest = pixels.front(points, "wrong", start)
    assert set(map(id, got[1:])) <= set(map(id, rest))  # after the pick: the front


@settings(max_examples=100, deadline=None)
@given(st.floats(0, 1), st.floats(0, 1), st.integers(0, 10**7), st.floats(0, 5))
def test_significant_is_one_sided_and_grows_with_the_pixels(a, b, n, z):
    if pixels.significant(a, b, n, z):
        assert a < b and not pixels.significant(b, a, n, z)
        assert pixels.significant(a, b, 4 * n, z)  # the difference grows as n, its deviation as √n
    if n and a < b:
        assert pixels.significant(a, b, n, 0.0)


@pytest.mark.parametrize("call, name", [((0.1, 0.2, -1), "pixels"), ((0.1, 0.2, 1.5), "pixels"), ((-0.1, 0.2, 10), "a"),
                                        ((0.1, 2.0, 10), "b"), ((0.1, 0.2, 10, -1.0), "z"), ((0.1, float("nan"), 10), "b")])
def test_significant_refuses_by_name(call, name):
    with pytest.raises(ValueError, match=name):
        pixels.significant(*call)


def test_threejs_front_faces_at_bias_zero():
    """three.js with front faces casting and shadowBias 0 (its 1e-6): acne everywhere; the pick removes it."""
    s = setups.build("threejs", {"cascades": 2, "shadowMapSize": 512, "material.shadowSide": "FrontSide"}, CAMERA, "30..50")
    lim = limits(s)
    got = pixels.refine(s, s, lim, keep=frozenset({"cascades", "shadowMapSize", "mode", "maxFar"}), height=64, suns=1)
    assert got.before["acne"] > 0.1 and got.after["wrong"] < got.before["wrong"] / 5
    assert got.setup.settings != s.settings


def test_other_engines_keep_the_perspective_objective(capsys):
    got, _ = _json(capsys, ["tune", "--engine", "bevy", "--camera", CAMERA, "--sun", "30..50", "--receivers", "1..40"])
    assert got["objective_kind"] == "perspective" and got["objective_note"].startswith("the toolkit does not predict Bevy")
    assert got["pareto"] == [] and got["wrong"] is None
    # Godot's Forward+ (its desktop default) is not predicted per pixel: its Compatibility renderer is (tests/test_godot_seen.py)
    got, _ = _json(capsys, ["tune", "--engine", "godot", "--camera", CAMERA, "--sun", "30..50", "--receivers", "1..40"])
    assert got["objective_kind"] == "perspective" and got["objective_note"].startswith(
        "the toolkit does not predict these settings per pixel: rendering/renderer/rendering_method must be gl_compatibility")
    assert main(["tune", "--engine", "godot", "--camera", CAMERA, "--sun", "30..50", "--receivers", "1..40"]) == 0
    assert "objective: worst perspective error (the toolkit does not predict" in capsys.readouterr().out


@pytest.mark.parametrize("argv", [["--engine", "godot", "--max-texels", "1"],
                                  ["--engine", "playcanvas", "--set", "shadowResolution=512", "--max-memory", "0.001"]])
def test_infeasible_limits_exit_3(argv, capsys):
    assert INFEASIBLE not in (0, 2)
    code = main(["tune", *argv, "--camera", CAMERA, "--sun", "30..50"])
    out = capsys.readouterr()
    assert code == INFEASIBLE
    assert len(out.err.strip().splitlines()) == 1 and f"(exit status {INFEASIBLE})" in out.err
    assert out.out  # the closest settings are still printed


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(["--prefer", "--max-memory", "--frames", "--objective"]),
       st.one_of(st.sampled_from(["nan", "inf", "-1", "0", "1e400", "", "x", "65", "blockyy"]), st.text(max_size=6)))
def test_bad_flags_refused_in_one_line(flag, value):
    import contextlib
    import io

    err = io.StringIO()
    argv = PLAYCANVAS[:1] + ["--engine", "godot", "--camera", CAMERA, "--sun", "30..50", "--receivers", "1..40", flag, value]
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse's choices and types
            code = exc.code
    if code == 2:
        assert len(err.getvalue().strip().splitlines()) == 1, err.getvalue()
    else:
        assert code in (0, INFEASIBLE)


def test_frames_refused_without_the_engine(monkeypatch, capsys, tmp_path):
    monkeypatch.setenv("ALIASING_ENGINES_JS_CACHE", str(tmp_path))  # an empty cache: no engine installed
    assert main(PLAYCANVAS + ["--frames", "2"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "aliasing frames --install" in err


def test_frames_2_end_to_end(capsys, monkeypatch):
    need_frames("playcanvas", "PlayCanvas")
    from aliasing.tune import proof

    monkeypatch.setattr(proof, "HEIGHT", 48)
    monkeypatch.setattr(proof, "SUNS", 1)
    keep = "numCascades,shadowResolution,cascadeDistribution,shadowDistance,cascadeBlend,normalOffsetBias"  # shadowBias searched alone
    got, _ = _json(capsys, PLAYCANVAS + ["--frames", "2", "--keep", keep])
    fr = got["frames"]
    assert len(fr["candidates"]) == 2 and 0 <= fr["pick"] < 2
    for c in fr["candidates"]:
        assert 0 <= c["measured"]["wrong"] <= 1 and 0 <= c["predicted"]["wrong"] <= 1
    assert got["settings"] == fr["candidates"][fr["pick"]]["settings"]


_GARBAGE = st.one_of(st.none(), st.booleans(), st.integers(-10**6, 10**6), st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=6),
                     st.lists(st.integers(), max_size=3))


@settings(max_examples=40, deadline=None)
@given(_GARBAGE)
def test_api_refuses_garbage_naming_it(bad):
    from aliasing.frames import seen
    from aliasing.tune import proof

    s = setups.build("playcanvas", {}, CAMERA, "30..50")
    lim = limits(s)
    calls = [(lambda: pixels.refine(bad, s, lim), "start"), (lambda: pixels.refine(s, bad, lim), "perspective"),
             (lambda: pixels.hard(bad, False), "lim"), (lambda: pixels.why_not(bad), "setup"), (lambda: seen.count(s, bad), "where")]
    if not (isinstance(bad, str) and bad in pixels.PREFER):
        calls += [(lambda: pixels.front([], bad), "prefer"), (lambda: pixels.refine(s, s, lim, prefer=bad), "prefer")]
    whole = isinstance(bad, (int, float)) and not isinstance(bad, bool) and math.isfinite(bad) and float(bad).is_integer()
    if not (whole and 1 <= bad <= 64):
        calls.append((lambda: proof.candidates([], "wrong", bad), "n"))
    for call, name in calls:
        with pytest.raises(ValueError, match=name):
            call()


def test_scene_file_seen_from_its_camera(capsys, tmp_path):
    """A glTF scene with a camera: the receivers and the wrong pixels both come from it, seen from that camera."""
    trimesh = pytest.importorskip("trimesh")
    import numpy as np

    ground = trimesh.creation.box(extents=[80, 0.1, 80])
    ground.apply_translation([0, -1.05, -40])
    box = trimesh.creation.box(extents=[1, 2, 1])
    box.apply_translation([0.5, 0, -8])
    sc = trimesh.Scene([ground, box])
    sc.camera = trimesh.scene.Camera(name="cam", fov=(50 * 16 / 9, 50), resolution=(1280, 720))
    sc.camera_transform = np.eye(4)
    path = tmp_path / "yard.glb"
    sc.export(str(path))
    keep = "numCascades,shadowResolution,cascadeDistribution,shadowDistance,cascadeBlend,normalOffsetBias"
    got, _ = _json(capsys, PLAYCANVAS + ["--scene", str(path), "--keep", keep])
    assert got["wrong"]["sample"]["scene"] == "yard.glb" and got["objective_kind"] == "wrong"
    assert got["wrong"]["after"]["wrong"] < got["wrong"]["before"]["wrong"]


class _Table(pixels._Pixels):
    """A search whose wrong pixels are a table over (cascade count, λ): no frame drawn."""

    def __init__(self, start, table):
        super().__init__(start, limits(start), None, None, frozenset())
        self.table, self.pixels = table, 100_000

    def _measure(self, settings):
        n = self.table.get((settings["numCascades"], round(settings["lambda"], 6)), 500)
        return pixels.Point(dict(settings), n / self.pixels, 0.0, 0.0, n / self.pixels, 1.0, 16.0)


def test_the_count_moves_with_the_split(monkeypatch):
    """(3 cascades, λ 1) beats moving either lever alone, (4, 0.9) beats it beyond the noise: the count tried at each split
    point finds it; one lever at a time does not (Babylon.js's reference scene had this shape)."""
    start = setups.build("babylon", {"numCascades": 3, "lambda": 1.0, "bias": 0.002}, CAMERA, "20..60")
    table = {(3, 1.0): 40, (4, 1.0): 136, (3, 0.9): 107, (4, 0.9): 2}
    keep = frozenset(k for k in start.settings if k not in ("numCascades", "lambda", "bias"))
    got = pixels._coordinate(_Table(start, table), dict(start.settings), keep)
    assert (got["numCascades"], got["lambda"]) == (4, 0.9)
    assert got["bias"] != start.settings["bias"]               # kept at its multiple of the closed-form minimum of 4 cascades, λ 0.9
    monkeypatch.setattr(pixels, "_with_split", lambda *a: [])
    alone = pixels._coordinate(_Table(start, table), dict(start.settings), keep)
    assert (alone["numCascades"], alone["lambda"]) == (3, 1.0)


class _Counts(pixels._Pixels):
    """A search whose wrong pixels are a table over the settings that differ from the start: no frame drawn."""

    def __init__(self, start, table):
        super().__init__(start, limits(start), None, None, frozenset())
        self.table, self.pixels = table, 100_000

    def _measure(self, settings):
        n = self.table[frozenset(k for k, v in settings.items() if v != self.start.settings[k])]
        return pixels.Point(dict(settings), n / self.pixels, 0.0, 0.0, n / self.pixels, 1.0, 16.0)


def test_changes_go_back_against_the_end_not_the_last_step():
    """Three changes, each put back alone within the noise of the descent's end (100 → 115, 2√215 = 29 pixels), but all
    three back is 100 → 190: the put-backs stop before their sum is significant (against the last step each of them would
    pass: 100 → 115 → 140 → 190)."""
    start = setups.build("babylon", {"numCascades": 3, "lambda": 0.5, "bias": 0.002}, CAMERA, "20..60")
    end = {**start.settings, "numCascades": 4, "lambda": 0.9, "bias": 0.004}
    n, l, b = "numCascades", "lambda", "bias"
    table = {frozenset({n, l, b}): 100, frozenset({l, b}): 115, frozenset({n, b}): 115, frozenset({n, l}): 115,
             frozenset({b}): 140, frozenset({l}): 140, frozenset({n}): 140, frozenset(): 190}
    got = pixels._undo(_Counts(start, table), end, start.settings)
    changed = {k for k in (n, l, b) if got[k] != start.settings[k]}
    assert len(changed) == 2 and table[frozenset(changed)] == 115
