"""Serve MathJax 3 from the built site itself (no CDN).

MathJax comes from the npm registry at build time: when ``docs/_mathjax/node_modules/mathjax``
is missing this runs ``npm install --prefix docs/_mathjax mathjax@3`` (Node.js/npm must be on
PATH; set ``ALIASING_MATHJAX`` to an existing ``tex-svg-full.js`` to skip npm). The single-file
SVG build (fonts inside the script) is copied into ``_static/mathjax/`` and used as
``mathjax_path``, so every page renders its formulas offline.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from sphinx.application import Sphinx
from sphinx.errors import ExtensionError

BUNDLE = "tex-svg-full.js"


def _find_or_install(docs: Path) -> Path:
    env = os.environ.get("ALIASING_MATHJAX")
    if env:
        return Path(env)
    prefix = docs / "_mathjax"
    js = prefix / "node_modules" / "mathjax" / "es5" / BUNDLE
    if not js.exists():
        npm = shutil.which("npm")
        if npm is None:
            raise ExtensionError("MathJax is not installed and npm is missing: install Node.js/npm, or set "
                                 "ALIASING_MATHJAX to a local mathjax@3 es5/tex-svg-full.js")
        prefix.mkdir(exist_ok=True)
        subprocess.run([npm, "install", "--prefix", str(prefix), "--no-audit", "--no-fund", "mathjax@3"],
                       check=True, stdout=subprocess.DEVNULL)
    return js


def _setup_mathjax(app: Sphinx) -> None:
    src = _find_or_install(Path(app.srcdir))
    static = Path(app.srcdir) / "_mathjax" / "static"
    (static / "mathjax").mkdir(parents=True, exist_ok=True)
    shutil.copyfile(src, static / "mathjax" / BUNDLE)
    app.config.html_static_path.append(str(static))


def setup(app: Sphinx) -> dict:
    app.setup_extension("sphinx.ext.mathjax")

    app.connect("builder-inited", _setup_mathjax)
    return {"parallel_read_safe": True, "version": "1"}
