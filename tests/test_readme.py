"""The README's examples run: its Python blocks and every `aliasing …` command in its shell blocks."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from aliasing.cli import main

README = (Path(__file__).resolve().parents[1] / "README.md").read_text()


def _blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", README, flags=re.S)


def _commands() -> list[str]:
    # a shell line ending in a backslash continues on the next one, as in a terminal
    lines = [line.split("#")[0].strip() for block in _blocks("sh") for line in block.replace("\\\n", " ").splitlines()]
    return [line for line in lines if line.startswith("aliasing ")]


def test_readme_has_examples():
    assert _blocks("python") and len(_commands()) >= 5


@pytest.mark.parametrize("index", range(len(_blocks("python"))))
def test_python_block_runs(index, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    exec(compile(_blocks("python")[index], f"README.md python block {index}", "exec"), {})


#: the engines' sample project files the README's --project commands read (tests/files)
SAMPLES = Path(__file__).resolve().parent / "files"


@pytest.mark.parametrize("command", _commands())
def test_command_runs(command, tmp_path, monkeypatch, capsys):
    for name in ("project.godot", "main.tscn", "scene.babylon", "scene.three.json", "scene.playcanvas.json"):
        (tmp_path / name).write_bytes((SAMPLES / name).read_bytes())
    monkeypatch.chdir(tmp_path)
    assert main(shlex.split(command)[1:]) == 0
