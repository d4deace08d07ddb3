"""Regenerate the engine-made sample project files under tests/files/ with the engines' own code in node.

    PYTHONPATH=. python tests/files/make/make.py          # writes the files (needs node and the pinned packages:
                                                           # aliasing frames --install)

* ``scene.babylon``: Babylon.js's ``SceneSerializer.Serialize`` (``babylon_scene.mjs``);
* ``babylon_cameras.json``: Babylon.js's serialized ArcRotateCamera and FreeCamera with each one's own
  forward direction (``babylon_cameras.mjs``);
* ``scene.three.json``: three.js's ``scene.toJSON()`` (``three_scene.mjs``);
* ``scene.playcanvas.parsed.json``: what PlayCanvas's own ``SceneParser`` makes of the hand-written
  ``scene.playcanvas.json`` (``playcanvas_scene.mjs``; the editor's format, which the engine only reads).

``tests/test_project_files.py`` runs :func:`outputs` where node is installed and checks that they
equal the committed files.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
FILES = HERE.parent


def outputs() -> dict[str, str]:
    """The files' texts as the pinned engines write them now (name -> text)."""
    from aliasing.frames import install

    node = shutil.which("node")
    if node is None:
        raise RuntimeError("node not found: install Node.js (Debian: apt-get install nodejs npm)")

    def run(script: str, engine: str, *extra: str) -> str:
        done = subprocess.run([node, str(HERE / script), str(install.package_root(engine)), *extra], capture_output=True, text=True,
                              timeout=300, check=False)
        if done.returncode:
            raise RuntimeError(f"{script} failed: {done.stderr.strip()[-2000:]}")
        return done.stdout

    return {"scene.babylon": run("babylon_scene.mjs", "babylon"), "babylon_cameras.json": run("babylon_cameras.mjs", "babylon"),
            "scene.three.json": run("three_scene.mjs", "threejs"),
            "scene.playcanvas.parsed.json": run("playcanvas_scene.mjs", "playcanvas", str(FILES / "scene.playcanvas.json"))}


if __name__ == "__main__":
    for name, text in outputs().items():
        (FILES / name).write_text(text, encoding="utf-8")
        print(f"wrote {FILES / name}", file=sys.stderr)
