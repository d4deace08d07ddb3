"""The package's architecture, checked mechanically: layers, no import circles, sizes.

* the layers contract of pyproject.toml ([tool.importlinter]) holds: data flows one way,
  from the command line down to geometry and the View (import-linter);
* the import graph has no circle, function-level imports included (grimp);
* an upward import planted in a copy of the package breaks the contract (the check can fail);
* no module is longer than 600 lines and no sub-package holds more than 12 modules.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

grimp = pytest.importorskip("grimp", reason="import-linter (the test extra) brings grimp")

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "aliasing"
MAX_LINES = 600
MAX_MODULES = 12


def _lint(cwd: Path) -> subprocess.CompletedProcess:
    code = "import sys; from importlinter.cli import lint_imports_command; sys.exit(lint_imports_command())"
    env = {"PYTHONPATH": str(cwd), "PATH": "/usr/bin:/bin"}
    return subprocess.run([sys.executable, "-c", code, "--config", str(cwd / "pyproject.toml"), "--no-cache"], cwd=cwd, capture_output=True, text=True, env=env, timeout=300)


def test_layers_contract_is_kept():
    proc = _lint(ROOT)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-2000:]
    assert "1 kept, 0 broken" in proc.stdout


def test_an_upward_import_breaks_the_contract(tmp_path):
    """The contract can fail: the View importing the command line is refused."""
    copy = tmp_path / "repo"
    shutil.copytree(PACKAGE, copy / "aliasing", symlinks=False, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "pyproject.toml", copy / "pyproject.toml")
    view = copy / "aliasing" / "view.py"
    view.write_text(view.read_text() + "\n\ndef _upward():\n    from . import cli  # an import against the flow\n\n    return cli\n")
    proc = _lint(copy)
    assert proc.returncode != 0 and "aliasing.view -> aliasing.cli" in proc.stdout, proc.stdout[-3000:]


def _cycles(graph) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out = []
    counter = 0
    for start in sorted(graph.modules):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.find_modules_directly_imported_by(start))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(graph.find_modules_directly_imported_by(w)))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def test_no_import_circles():
    """No two modules import each other, directly or around a loop (function-level imports count;
    imports under ``if TYPE_CHECKING:`` only name types in annotations and never run)."""
    graph = grimp.build_graph("aliasing", exclude_type_checking_imports=True)
    assert _cycles(graph) == []


def test_the_circle_finder_finds_a_circle():
    graph = grimp.ImportGraph()
    for a, b in (("p.a", "p.b"), ("p.b", "p.c"), ("p.c", "p.a"), ("p.c", "p.d")):
        graph.add_import(importer=a, imported=b)
    assert _cycles(graph) == [["p.a", "p.b", "p.c"]]


def test_no_module_over_600_lines():
    long = {str(p.relative_to(ROOT)): n for p in PACKAGE.rglob("*.py") if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert long == {}


def test_no_subpackage_of_more_than_12_modules():
    """Each sub-package is one concern.  The top level (the analytic modules, one per paper's
    concept, at the public addresses ``aliasing.error``, ``aliasing.warping``, ...) and the
    figure scripts (one per reproduced figure, addressed by name) are flat on purpose: see the
    architecture page."""
    crowded = {}
    for d in PACKAGE.rglob("*"):
        if d.is_dir() and d != PACKAGE and (d / "__init__.py").exists() and d.name != "figures":
            n = len([p for p in d.glob("*.py") if p.name != "__init__.py"])
            if n > MAX_MODULES:
                crowded[str(d.relative_to(ROOT))] = n
    assert crowded == {}
