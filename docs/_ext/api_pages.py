"""Write the API reference pages (``docs/api/``, generated, not committed) from the package itself.

One page per public module of :mod:`aliasing` (names starting with ``_`` and the figure
scripts, shown in the gallery, are left out). A page documents the public functions and classes
*defined* in that module (its ``__all__`` when it has one), each with its full numpydoc
docstring, so every equation reference the docstrings carry appears; names a package merely
re-exports are linked to where they are defined, not documented twice.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import pkgutil
from pathlib import Path

from docstring_text import escape_pipes
from sphinx.application import Sphinx

SKIP = ("aliasing.figures",)


def public_modules() -> list[str]:
    import aliasing

    names = ["aliasing"]
    for info in pkgutil.walk_packages(aliasing.__path__, "aliasing."):
        if any(part.startswith("_") for part in info.name.split(".")) or info.name.startswith(SKIP):
            continue
        names.append(info.name)
    return sorted(names)


def _assigned(mod) -> set[str]:
    """Names assigned at the top level of ``mod``'s source (its own data, not imports)."""
    try:
        tree = ast.parse(inspect.getsource(mod))
    except (OSError, TypeError):
        return set()
    out = set()
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        out.update(t.id for t in targets if isinstance(t, ast.Name))
    return out


def members(mod) -> tuple[list[str], list[str], list[str]]:
    """(defined here, re-exported from elsewhere, public constants) of ``mod``.

    Public constants are UPPER_CASE names assigned in the module (tables such as
    ``WARPING_RULES``) that docstrings refer to with ``:data:``.
    """
    names = getattr(mod, "__all__", None)
    if names is None:
        names = [n for n in vars(mod) if not n.startswith("_")]
    own, reexported = [], []
    for n in names:
        obj = getattr(mod, n, None)
        if not (inspect.isfunction(obj) or inspect.isclass(obj)):
            continue
        if obj.__module__ == mod.__name__:
            own.append(n)
        elif isinstance(obj.__module__, str) and getattr(importlib.import_module(obj.__module__), obj.__name__, None) is obj:
            reexported.append(n)
    data = sorted(n for n in _assigned(mod) if n.isupper() and not n.startswith("_") and n != "__all__")
    return own, reexported, data


def _summary(obj) -> str:
    """The docstring's first paragraph on one line (reST as written, bars escaped)."""
    doc = inspect.getdoc(obj) or ""
    para = " ".join(doc.split("\n\n", 1)[0].split())
    return escape_pipes([para])[0] or "—"


def _rel(target: str, modname: str) -> str:
    """autosummary wants names relative to the current module."""
    return target[len(modname) + 1:] if target.startswith(modname + ".") else target


def page(modname: str) -> str:
    mod = importlib.import_module(modname)
    own, rex, data = members(mod)
    lines = [modname, "=" * len(modname), "", f".. automodule:: {modname}", "   :no-members:", ""]
    if own:  # a table of our own: autosummary cuts summaries at "eq." (it ends a sentence there)
        lines += ["**Contents**", "", ".. list-table::", "   :widths: 30 70", ""]
        for n in own:
            obj = getattr(mod, n)
            role = "class" if inspect.isclass(obj) else "func"
            lines += [f"   * - :{role}:`~{modname}.{n}`", f"     - {_summary(obj)}"]
        lines.append("")
    if rex:
        lines += ["**Re-exported here** (documented where they are defined)", "", ".. autosummary::",
                  "   :nosignatures:", ""]
        lines += [f"   {_rel(getattr(mod, n).__module__ + '.' + getattr(mod, n).__name__, modname)}" for n in rex] + [""]
    for n in data:
        value = getattr(mod, n, None)
        text = repr(value)
        shown = f"``{text}``" if len(text) <= 100 and "`" not in text and "\n" not in text else f"a ``{type(value).__name__}``"
        lines += [f".. py:data:: {n}", f"   :module: {modname}", "", f"   Constant of :mod:`{modname}`: {shown}.", ""]
    for n in own:
        obj = getattr(mod, n)
        if inspect.isclass(obj):
            lines += [f".. autoclass:: {modname}.{n}", "   :members:", "   :special-members: __call__", ""]
        else:
            lines += [f".. autofunction:: {modname}.{n}", ""]
    return "\n".join(lines)


INDEX = """\
API reference
=============

Every public module, function and class of :mod:`aliasing`, generated from the docstrings
(numpydoc). Functions that implement a paper name it and its equation numbers in their
docstrings. The angle convention of the whole package is in :mod:`aliasing`.

.. toctree::
   :maxdepth: 1

"""


def write_pages(app: Sphinx) -> None:
    out = Path(app.srcdir) / "api"
    out.mkdir(exist_ok=True)
    mods = public_modules()
    for m in mods:
        text = page(m)
        path = out / f"{m}.rst"
        if not path.exists() or path.read_text() != text:  # unchanged pages keep their mtime
            path.write_text(text)
    index = INDEX + "".join(f"   {m}\n" for m in mods)
    if not (out / "index.rst").exists() or (out / "index.rst").read_text() != index:
        (out / "index.rst").write_text(index)


def setup(app: Sphinx) -> dict:
    app.connect("builder-inited", write_pages)
    return {"parallel_read_safe": True, "version": "1"}
