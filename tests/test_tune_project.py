"""``aliasing tune --project``: for each of the seven project-file formats, the user's own sample file is the start, and
``--patch``/``--write`` change exactly the settings tune changed, in the file's own format, touching nothing else."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from aliasing.cli import main
from aliasing.setups import files

FILES = Path(__file__).parent / "files"

#: (sample files, extra options): one case per format
CASES = {
    "godot": (["project.godot", "main.tscn"], []),
    "babylon": (["scene.babylon"], []),
    "threejs": (["scene.three.json"], ["--set", "cascades=4"]),
    "playcanvas": (["scene.playcanvas.json"], []),
    "unity-urp": (["urp_high.asset", "urp_scene.unity"], []),
    "unreal": (["unreal_DefaultEngine.ini"], ["--camera", "near=10,far=100000,fov=50", "--receivers", "100..20000"]),
    "filament": (["filament_settings.json"], []),
}


def _unchanged_kept(old: str, new: str, diff: str) -> bool:
    """Every line of ``old`` that the diff does not remove is in ``new``, in the same order."""
    removed = {ln[1:] for ln in diff.splitlines() if ln.startswith("-") and not ln.startswith("---")}
    kept = [ln for ln in old.splitlines() if ln not in removed]
    it = iter(new.splitlines())
    return all(any(ln == other for other in it) for ln in kept)


@pytest.mark.parametrize("engine", sorted(CASES))
def test_tune_patches_the_users_own_files(engine, tmp_path, capsys):
    names, extra = CASES[engine]
    paths = []
    for name in names:
        shutil.copy(FILES / name, tmp_path / name)
        paths.append(tmp_path / name)
    before = {p: p.read_text(encoding="utf-8") for p in paths}
    start = files.read(paths)
    assert start.engine == engine
    argv = ["tune", *[a for p in paths for a in ("--project", str(p))], "--write", "--format", "json", "--objective", "perspective"]  # the JSON holds the diffs too; the fast objective: the patch is the point here
    argv += extra if "--receivers" in extra else [*extra, "--receivers", "1..200"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(f"{c} in JSON"))
    changed = out["changed"]
    assert changed, f"tune changed nothing for {engine}: the case proves nothing"
    listed = {c["key"] for c in out["changes"]}
    assert listed == set(changed)  # every change listed, with its old value
    for c in out["changes"]:
        assert c["before"] != c["after"]
    apart = out["unplaced"]  # settings no file holds (Unreal's light lives in the level): named, not written
    assert set(apart) <= set(changed)
    placed = {k: v for k, v in changed.items() if k not in apart}
    assert placed, f"tune changed nothing in {engine}'s files: the case proves nothing"
    back = files.read(paths)
    assert {k: back.settings.get(k) for k in placed} == placed  # read back: exactly tune's settings
    for k, v in start.settings.items():  # nothing else the files set has moved
        if k not in placed:
            assert back.settings[k] == v, k
    diffs = out["patch"]
    assert diffs and set(diffs) <= {str(p) for p in paths}
    for p in paths:
        diff = diffs.get(str(p), "")
        new = p.read_text(encoding="utf-8")
        if not diff:
            assert new == before[p]
            continue
        added = [ln for ln in diff.splitlines() if ln.startswith("+") and not ln.startswith("+++")]
        assert 0 < len(added) <= 2 * len(placed)  # a value line each, and a section header where one is new
        assert _unchanged_kept(before[p], new, diff)
