"""Read the package's docstrings as their authors meant them.

* numpydoc knows an "Examples" section; the package heads it "Example" (numpydoc would drop it
  with a warning), so the heading is renamed before numpydoc parses the docstring.
* Docstrings write ``|x|`` for absolute values and norms, which reST reads as a substitution
  reference; outside code, roles, doctests, literal blocks and tables the bars are escaped.
"""

from __future__ import annotations

import re

from sphinx.application import Sphinx

_INLINE = re.compile(r"(``.+?``|:[a-z:]+:`[^`]+`|`[^`]+`_?)")
_TABLE_OR_LINE_BLOCK = re.compile(r"^(\|( |$)|\+[-=])")


def escape_pipes(lines: list[str]) -> list[str]:
    """``lines`` with the bars of ``|x|`` escaped outside code, doctests and literal blocks."""
    out, doctest, literal = [], False, None
    for line in lines:
        stripped, indent = line.strip(), len(line) - len(line.lstrip())
        if doctest and not stripped:
            doctest = False
        if literal is not None and stripped and indent <= literal:
            literal = None
        if stripped.startswith(">>>"):
            doctest = True
        if "|" in line and not (doctest or literal is not None or _TABLE_OR_LINE_BLOCK.match(stripped)):
            parts = _INLINE.split(line)
            line = "".join(p if k % 2 else re.sub(r"(?<!\\)\|", r"\\|", p) for k, p in enumerate(parts))
        if stripped.endswith("::") and not doctest and literal is None:
            literal = indent
        out.append(line)
    return out


def _process(app, what, name, obj, options, lines):
    for i in range(len(lines) - 1):
        if lines[i].strip() == "Example" and set(lines[i + 1].strip()) == {"-"}:
            pad = lines[i][: len(lines[i]) - len(lines[i].lstrip())]
            lines[i], lines[i + 1] = pad + "Examples", pad + "--------"
    lines[:] = escape_pipes(lines)


def setup(app: Sphinx) -> dict:
    app.connect("autodoc-process-docstring", _process, priority=100)  # before numpydoc (500)
    return {"parallel_read_safe": True, "version": "1"}
