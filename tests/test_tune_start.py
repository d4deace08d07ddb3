"""``aliasing tune`` starts from the user's setup: ``--keep``, every change listed, what got worse, JSON without NaN,
the snippet on the user's light, ``--patch``/``--write`` of the user's project files (through a small fake reader here;
:func:`check_project` is the end-to-end check to run per format once its reader exists)."""

from __future__ import annotations

import json
import math
import re
import sys
import types
from pathlib import Path

import pytest

from aliasing import setups
from aliasing.cli import main
from aliasing.setups import files
from aliasing.setups.files import Found
from aliasing.tune import tune
from aliasing.tune.report import worse

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"


def _json(capsys, argv):
    assert main(argv + ["--format", "json"]) == 0
    out = capsys.readouterr()
    return json.loads(out.out, parse_constant=lambda c: pytest.fail(f"{c} in JSON")), out


def _both(argv):
    """One search, both outputs: the JSON object (as the command writes it, parsed back refusing NaN) and the table."""
    from aliasing.cli import build_parser
    from aliasing.tune import command

    result = command.run(build_parser().parse_args(argv))
    text = json.dumps(command.to_dict(result), allow_nan=False)
    return json.loads(text, parse_constant=lambda c: pytest.fail(f"{c} in JSON")), command.text(result)


def test_the_users_settings_are_the_start(capsys):
    """Babylon with λ 0.7: 'before' is 0.7 (not the engine's 0.5), λ moves, and --keep lambda holds it."""
    argv = ["tune", "--objective", "perspective", "--engine", "babylon", "--set", "lambda=0.7", "--camera", CAMERA, "--receivers", "1..200"]
    got, _ = _json(capsys, argv)
    assert got["defaults"]["settings"]["lambda"] == 0.7
    lam = [c for c in got["changes"] if c["key"] == "lambda"]
    assert lam and lam[0]["before"] == 0.7 and lam[0]["after"] != 0.7
    kept, _ = _json(capsys, argv + ["--keep", "lambda"])
    assert kept["settings"]["lambda"] == 0.7 and "lambda" not in kept["changed"] and kept["keep"] == ["lambda"]
    assert kept["objective"] >= got["objective"] * (1 - 1e-9)


def test_every_change_has_its_line():
    """A setting the user did not give that tune changes is listed; every key whose value differs has a line, in both outputs."""
    argv = ["tune", "--objective", "perspective", "--engine", "threejs", "--camera", CAMERA, "--set", "material.shadowSide=FrontSide",
            "--receivers", "1..200"]
    got, out = _both(argv)
    differ = {k for k, v in got["settings"].items() if got["defaults"]["settings"][k] != v}
    assert differ and {c["key"] for c in got["changes"]} == differ == set(got["changed"])
    assert "maxFar" in differ  # not given by the user: the engine's default 100000 was the start
    profile = setups.get("threejs")
    for c in got["changes"]:
        assert c["unit"] == profile.setting(c["key"]).unit and c["after"] == got["settings"][c["key"]]
    for k in differ:
        assert re.search(rf"^  {re.escape(k)}: .+ → ", out, re.M), k


def test_godot_max_distance_is_listed_and_the_worse_gap_named():
    """The user's 200 m shadow distance is the start; tune's 100 m is listed with its unit, and the gap that grows says so."""
    argv = ["tune", "--engine", "godot", "--set", "directional_shadow_max_distance=200", "--camera", CAMERA, "--receivers", "1..100"]
    got, out = _both(argv)
    change = {c["key"]: c for c in got["changes"]}["directional_shadow_max_distance"]
    assert (change["before"], change["after"], change["unit"]) == (200.0, 100.0, "m")
    gap = {w["measure"]: w for w in got["worse"]}["gap_px"]
    assert gap["after"] > gap["before"] and "(worse)" in gap["line"]
    held = got["held_gap"]
    assert held["max_gap_px"] == pytest.approx(gap["before"]) and held["objective"] >= got["objective"]
    assert "directional_shadow_max_distance: 200.0 → 100.0 [m]" in out and gap["line"] in out


@pytest.fixture(scope="module")
def godot():
    """The Godot case: the user's 200 m shadow distance, receivers 1..100 m."""
    return tune(setups.build("godot", {"directional_shadow_max_distance": 200}, CAMERA, "15..60"), receivers=(1.0, 100.0))


def test_worse_lists_what_grew_and_nothing_else(godot):
    """Each entry of worse is a measure that grew; the error (lower after tuning) is never one."""
    t = godot
    got = worse(t)
    assert got and all(w["after"] > w["before"] for w in got)
    assert "error" not in {w["measure"] for w in got} and t.objective < t.before.objective
    with pytest.raises(ValueError, match="tuned"):
        worse("tuned")


def test_no_nan_in_json_when_the_start_misses_the_receivers():
    """Unity's shadows end at 50 m: receivers at 100..200 m have no error before: null with the reason, never NaN."""
    got, out = _both(["tune", "--engine", "unity-urp", "--receivers", "100..200"])
    assert got["measured"]["objective_before"] is None
    assert "50" in got["measured"]["objective_before_reason"] and "100" in got["measured"]["objective_before_reason"]
    assert got["objective"] is not None and math.isfinite(got["objective"])
    assert "worst perspective error: none (the start's shadows end at 50" in out


#: Settings an engine sets as one whole (Bevy's cascade config is built from all its builder's fields).
WHOLE = {"bevy": {"num_cascades", "minimum_distance", "maximum_distance", "first_cascade_far_bound", "overlap_proportion"}}
#: Engines whose changed settings here are not the light's (a CSM, Unity's URP asset): the snippet needs no light's name.
NOT_THE_LIGHT = {"threejs", "unity-urp"}


@pytest.mark.parametrize("engine", list(setups.ENGINES))
def test_snippet_sets_only_the_changes_on_the_users_light(engine):
    """The snippet names the user's light (or a placeholder) and carries each changed value, and no unchanged setting's key."""
    start = setups.build(engine, None, CAMERA, "15..60")
    keep = tuple(t.key for t in start.profile.tunable if t.role in ("cascades", "size"))
    t = tune(start, receivers=(1.0, 100.0), keep=keep, max_gap_px=math.inf)
    assert t.changed, engine
    named = t.snippet("MySun")
    assert "MySun" in named or engine in NOT_THE_LIGHT
    text = t.snippet()
    for key, v in t.changed.items():
        assert key.split(".")[-1].split("[")[0] in text or isinstance(v, float) and f"{v:g}" in text, (engine, key)
    untouched = [k for k in t.setup.settings if k not in t.changed and k.isidentifier() and len(k) > 6 and k not in WHOLE.get(engine, ())
                 and not any(k in c or c in k for c in t.changed)]
    assert not [k for k in untouched if re.search(rf"\b{re.escape(k)}\b\s*[=:]", text)], (engine, text)
    with pytest.raises(ValueError, match="light"):
        t.snippet("")


def test_keep_is_validated(capsys):
    with pytest.raises(ValueError, match="keep.*did you mean 'cascades'"):
        tune(setups.build("threejs", None, CAMERA), keep=("cascade",))
    assert main(["tune", "--engine", "threejs", "--keep", "cascade"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--keep" in err and "did you mean 'cascades'" in err


@pytest.mark.parametrize("flag", ["--patch", "--write"])
def test_patch_needs_a_project(capsys, flag):
    assert main(["tune", "--engine", "threejs", flag]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{flag} needs --project" in err and "Traceback" not in err


def test_limits_and_measure_refuse_garbage():
    from aliasing.tune import closed_form_bias, limits, measure, scene_receivers

    s = setups.build("threejs", None, CAMERA)
    for call, name in ((lambda: limits([]), "setup"), (lambda: limits(s, receivers="1..2"), "receivers"),
                       (lambda: measure([], None), "setup"), (lambda: measure(s, {}), "limits"),
                       (lambda: closed_form_bias([], "shadowBias"), "setup"), (lambda: scene_receivers([], s), "scene")):
        with pytest.raises((ValueError, TypeError), match=name):
            call()


hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

_GARBAGE = st.one_of(st.none(), st.booleans(), st.integers(-3, 3), st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=4),
                     st.lists(st.floats(-5, 5), max_size=3), st.complex_numbers(max_magnitude=2), st.just({}), st.just(b"x"))


@settings(max_examples=30, deadline=None, derandomize=True)
@given(name=st.sampled_from(["receivers", "max_texels", "max_gap_px", "max_slope", "moving", "keep"]), value=_GARBAGE)
def test_fuzz_tune_arguments(name, value):
    """Any value for one argument: a result without NaN, or a ValueError/TypeError naming that argument."""
    s = setups.build("threejs", {"cascades": 2, "shadowMapSize": 512, "mode": "uniform"}, CAMERA, "30")
    every = ("cascades", "shadowMapSize", "mode", "maxFar", "customSplitsLambda", "renderer.shadowMap.type")
    kwargs = {"keep": every, name: value} if name != "keep" else {"keep": value}
    try:
        t = tune(s, **kwargs)
    except (ValueError, TypeError) as exc:
        assert name in str(exc) or name == "keep" and "setting" in str(exc), str(exc)
        return
    assert math.isfinite(t.objective) or not t.feasible
    assert not any(isinstance(v, float) and math.isnan(v) for c in t.changes for v in (c["before"], c["after"]))


# -- --patch and --write: a fake reader -----------------------------------------------------------------------------------


def _fake_reader(monkeypatch):
    """A reader of 'fake' project files for three.js: ``KEY = VALUE`` lines (JSON values), one file or two (``*.light`` holds
    the light's keys, ``*.project`` the renderer's); a key in no file is taken by the ``.project`` file."""
    mod = types.ModuleType("aliasing.setups.files.fake")
    mod.ENGINE, mod.TITLE, mod.SOURCE = "threejs", "fake three.js project (tests)", "tests/test_tune_start.py"

    def sniff(path, text):
        return path.suffix in (".light", ".project")

    def read(items, light, camera):
        settings, where = {}, {}
        for path, text in items:
            for n, line in enumerate(text.splitlines(), 1):
                if "=" in line and not line.startswith("#"):
                    k, v = (x.strip() for x in line.split("=", 1))
                    settings[k], where[k] = json.loads(v), f"{path.name} line {n}"
        return Found("threejs", settings, light=light or "Sun", where=where)

    def patch(path, text, changes, found):
        lines = text.splitlines(keepends=True)
        for k, v in changes.items():
            if path.suffix == ".light" and k.startswith("renderer."):
                raise ValueError(f"{path.name}: {k} belongs in the project file")
            at = found.where.get(k, "")
            if at.startswith(path.name + " "):
                n = int(at.rsplit(" ", 1)[1]) - 1
                lines[n] = f"{k} = {json.dumps(v)}\n"
            elif path.suffix == ".project":
                lines.append(f"{k} = {json.dumps(v)}\n")
            else:
                raise ValueError(f"{path.name}: {k} belongs in the project file")
        return "".join(lines)

    mod.sniff, mod.read, mod.patch = sniff, read, patch
    monkeypatch.setitem(sys.modules, "aliasing.setups.files.fake", mod)
    monkeypatch.setattr(files, "FORMATS", {"threejs": "fake"})
    return mod


def _with_project(monkeypatch, paths):
    """tune's command with a ``--project`` option as the shared setup vocabulary will give it (the user's settings from the files)."""
    from aliasing.tune import command

    real = setups.from_args

    def from_args(args):
        found = files.read(paths)
        args.set_ = [f"{k}={json.dumps(v) if not isinstance(v, str) else v}" for k, v in found.settings.items()] + list(args.set_ or [])
        return real(args)

    monkeypatch.setattr(command.setups, "from_args", from_args)
    monkeypatch.setattr(command, "_project", lambda args: [Path(p) for p in paths])


def check_project(capsys, monkeypatch, paths, engine, extra=()):
    """End to end on sample project files ``paths`` of ``engine``: the diff touches only changed keys, reading the patched
    files back gives tune's settings, and ``--write`` writes exactly the diff's text (every other line unchanged)."""
    base = ["tune", "--objective", "perspective", "--engine", engine, "--camera", CAMERA, "--receivers", "1..200", *extra]
    got, _ = _json(capsys, base)
    changed = got["changed"]
    assert changed
    assert main(base + ["--patch"]) == 0
    diff = capsys.readouterr().out
    removed = [ln for ln in diff.splitlines() if ln.startswith("-") and not ln.startswith("---")]
    added = [ln for ln in diff.splitlines() if ln.startswith("+") and not ln.startswith("+++")]
    assert added and len(removed) <= len(added)
    for ln in added:
        assert any(k in ln for k in changed), ln  # every added line carries a changed key
    before = {p: Path(p).read_text() for p in paths}
    assert main(base + ["--write"]) == 0
    assert "wrote" in capsys.readouterr().err
    back = files.read(paths)
    assert {k: back.settings[k] for k in changed} == changed  # read back: tune's settings
    for p in paths:  # every line not in the diff is untouched
        old, new = before[p].splitlines(), Path(p).read_text().splitlines()
        assert [ln for ln in old if ln in new] == [ln for ln in old if f"-{ln}" not in removed]
    return changed


def test_patch_and_write_a_project_through_a_reader(capsys, monkeypatch, tmp_path):
    """Two files: the light's keys in one, the renderer's in the other; keys in no file go where the reader takes them."""
    _fake_reader(monkeypatch)
    light = tmp_path / "scene.light"
    light.write_text('# my light\ncascades = 4\nshadowMapSize = 2048\nmaterial.shadowSide = "FrontSide"\nmaxFar = 500\n')
    project = tmp_path / "game.project"
    project.write_text('# renderer\nrenderer.shadowMap.type = "PCFShadowMap"\n')
    paths = [str(light), str(project)]
    _with_project(monkeypatch, paths)
    changed = check_project(capsys, monkeypatch, paths, "threejs", ["--keep", "cascades,shadowMapSize"])
    assert "maxFar" in changed and light.read_text().count("maxFar") == 1  # replaced in place, in the light's file
    assert "mode" in changed and "mode = " in project.read_text()  # in no file: the reader's patch placed it


def test_write_is_atomic(capsys, monkeypatch, tmp_path):
    """A patch that does not read back as written leaves the file as it was, and no temporary file beside it."""
    mod = _fake_reader(monkeypatch)
    light = tmp_path / "scene.light"
    text = "cascades = 4\nmaxFar = 500\n"
    light.write_text(text)
    mod.patch = lambda path, t, changes, found: t + "maxFar = 1\n" if "maxFar" in changes else t  # the second maxFar wins on read
    _with_project(monkeypatch, [str(light)])
    status = main(["tune", "--objective", "perspective", "--engine", "threejs", "--camera", CAMERA, "--receivers", "1..200", "--keep", "cascades", "--write"])
    assert status == 2 and "does not read back" in capsys.readouterr().err
    assert light.read_text() == text and sorted(p.name for p in tmp_path.iterdir()) == ["scene.light"]


def test_readme_and_guide_numbers(godot):
    """README's 'Tune your engine': count and size kept 67.7 → 5.33 with the seam step ×2.3 → ×4.96 named; free, 8 × 1024² (half the memory) give 5.03.
    The guide's Godot case: 24.4 → 3.67 px/texel, or 24.41 holding the start's 29.52 px."""
    start = setups.build("threejs", {"cascades": 4, "shadowMapSize": 2048}, CAMERA, "15..60")
    kept = tune(start, receivers=(1.0, 200.0), keep="cascades,shadowMapSize".split(","))
    assert (round(kept.before.objective, 1), round(kept.objective, 2)) == (67.7, 5.33)
    assert [w["line"] for w in worse(kept)] == ["seam step: ×2.3 → ×4.96 (worse)"]
    free = tune(start, receivers=(1.0, 200.0))
    assert (free.setup.pipeline.k, free.setup.pipeline.resolution, round(free.objective, 2)) == (8, 1024, 5.03)
    assert 2 * free.measure.texels == kept.measure.texels  # half the memory
    g = godot
    assert (round(g.before.objective, 1), round(g.objective, 2)) == (24.4, 3.67)
    assert round(g.held_gap.limits.max_gap_px, 2) == 29.52 and round(g.held_gap.objective, 2) == 24.41 and not g.held_gap.changed
