"""No tracker words ("issue 12", "issues 11 and 19") in anything a user reads.

Searched: README.md; the documentation's sources (docs/, without build outputs and the pages
generated from other sources) and what they include (benchmarks/README.md); the notebooks;
every subcommand's --help; the lists of reproduce targets and derivations; and every string
in the package and the figure scripts (docstrings, figure titles, messages).  Comments are
not searched: nobody reads them on a page.
"""

from __future__ import annotations

import ast
import io
import re
from contextlib import redirect_stdout
from pathlib import Path

import pytest

from aliasing import cli

ROOT = Path(__file__).resolve().parents[1]
TRACKER = re.compile(r"\bissues?[ -]\d+", re.IGNORECASE)
GENERATED = {"_build", "_mathjax", "auto_gallery", "_gallery_src", "api", "notebooks", "node_modules", "cli"}


def _hits(text: str, where: str) -> list[str]:
    return [f"{where}: {text[max(0, m.start() - 40) : m.end() + 20]!r}" for m in TRACKER.finditer(text)]


def _doc_sources() -> list[Path]:
    files = [ROOT / "README.md", ROOT / "benchmarks" / "README.md", *sorted((ROOT / "notebooks").glob("*.ipynb"))]
    for path in sorted((ROOT / "docs").rglob("*")):
        rel = path.relative_to(ROOT / "docs")
        if path.is_file() and not GENERATED & set(rel.parts[:-1]) and path.suffix in {".md", ".rst", ".py", ".html", ".txt", ".css", ".js"}:
            files.append(path)
    return files


def _strings(path: Path) -> list[str]:
    """Every string constant of a Python file (docstrings, titles, messages), not its comments."""
    return [node.value for node in ast.walk(ast.parse(path.read_text())) if isinstance(node, ast.Constant) and isinstance(node.value, str)]


def _help_texts() -> dict[str, str]:
    parser = cli.build_parser()
    texts = {"aliasing --help": parser.format_help()}
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    texts.update({f"aliasing {name} --help": p.format_help() for name, p in sub.choices.items()})
    return texts


def test_the_pattern_finds_tracker_words():
    assert _hits("as issue 12 item 4 says", "x") and _hits("(issues 11 and 19)", "x") and _hits("pre-issue-12", "x")
    assert not _hits("the tissue 12 cm deep, an issue with 3 maps", "x")


def test_docs_readme_and_notebooks_name_no_tracker_issue():
    files = _doc_sources()
    assert ROOT / "docs" / "warping_rule.md" in files and len(files) > 10
    hits = [h for path in files for h in _hits(path.read_text(), str(path.relative_to(ROOT)))]
    assert not hits, "\n".join(hits)


def test_package_and_figure_strings_name_no_tracker_issue():
    files = sorted((ROOT / "aliasing").rglob("*.py")) + sorted((ROOT / "figures").glob("*.py"))
    assert any(p.name == "lloyd2007_table3.py" for p in files)
    hits = [h for path in files for s in _strings(path) for h in _hits(s, str(path.relative_to(ROOT)))]
    assert not hits, "\n".join(hits)


def test_cli_help_and_lists_name_no_tracker_issue():
    texts = _help_texts()
    assert {"aliasing sweep --help", "aliasing render --help", "aliasing engines --help"} <= set(texts)
    for args in (["reproduce", "--list"], ["derive", "--list"], ["splits", "--list"]):
        out = io.StringIO()
        with redirect_stdout(out):
            assert cli.main(args) == 0
        texts["aliasing " + " ".join(args)] = out.getvalue()
    hits = [h for where, text in texts.items() for h in _hits(text, where)]
    assert not hits, "\n".join(hits)


@pytest.mark.parametrize("name", ["lloyd2007-table3", "engines-comparison"])
def test_gallery_titles_name_no_tracker_issue(name):
    from aliasing.reproduce import TARGETS

    assert not _hits(TARGETS[name].description, name)
