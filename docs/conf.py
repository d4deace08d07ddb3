"""Sphinx configuration of the aliasing documentation site.

Build (from the repository root, after ``pip install ".[docs]"``)::

    sphinx-build -W -n -b html docs docs/_build/html

Nothing is loaded from the network when a page is viewed: MathJax 3 is installed from the
npm registry at build time (``npm install mathjax@3`` into ``docs/_mathjax``, done by
:mod:`_ext.local_mathjax` when missing) and served from ``_static``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(ROOT))

import aliasing  # noqa: E402

project = "aliasing"
author = "the aliasing authors"
copyright = "the aliasing authors, MIT licence"
release = version = aliasing.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "matplotlib.sphinxext.plot_directive",  # the drawn geometry of getting-started
    "myst_nb",
    "sphinx_gallery.gen_gallery",
    "local_mathjax",  # docs/_ext: MathJax from npm, no CDN
    "cli_reference",  # docs/_ext: the argparse parser of aliasing.cli as pages
    "gallery_targets",  # docs/_ext: gallery examples generated from aliasing.reproduce.TARGETS
    "api_pages",  # docs/_ext: one API page per public module
    "docstring_text",  # docs/_ext: "Example" headings and |x| in docstrings, read as intended
    "xref_resolve",  # docs/_ext: public import paths (aliasing.View) -> defining module
]

exclude_patterns = ["_more_pages.rst", "_build", "_mathjax", "_gallery_src", "auto_gallery/data", "**.ipynb_checkpoints", "auto_gallery/*.ipynb",
                    "auto_gallery/*.py", "auto_gallery/*.zip", "auto_gallery/*.json"]
templates_path = ["_templates"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"

# -- cross-references: nitpicky on the project's own names ------------------------------
mathjax_path = "mathjax/tex-svg-full.js"  # copied into _static by docs/_ext/local_mathjax.py
nitpicky = True
# Third-party types in signatures and docstrings have no intersphinx inventory offline
# (no network at build time), so they cannot resolve; the project's own names are never here.
nitpick_ignore_regex = [
    (r"py:.*", r"(functools|types|numpy|np|npt|numpy\.typing|sympy|sp|scipy|matplotlib|plt|mpl|pandas|pd|xarray|xr|dask|distributed|ipywidgets|trimesh|embreex|argparse|collections|pathlib|os|typing|typing_extensions|dataclasses|contextlib|enum|concurrent|tqdm)(\..*)?"),
    # traitlets/ipywidgets annotate with ``import typing as t`` (the explorers' base class, a VBox)
    (r"py:.*", r"t\.\w+"),
    # numpy.typing.ArrayLike and friends as they appear unqualified in rendered signatures
    # (``Array`` is the modules' alias of numpy.typing.NDArray[np.float64], unevaluated in some signatures)
    (r"py:.*", r"(Array|ArrayLike|NDArray|DTypeLike|Path|Sequence|Mapping|Iterable|Iterator|Callable|Any|Literal|Self|Figure|Axes|Expr|Symbol|Matrix|Number|Integral|Real)"),
    # Python builtins and the type words numpydoc reads in "Parameters" lines
    (r"py:.*", r"(int|float|str|bool|complex|bytes|dict|list|tuple|set|frozenset|object|type|None|callable|optional|array_like|array-like|ndarray|default|of|or|shape|sequence|mapping|iterable)"),
]

# -- autodoc / autosummary / numpydoc --------------------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_typehints = "signature"
autodoc_member_order = "bysource"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# -- MyST / notebooks ------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
nb_execution_mode = os.environ.get("ALIASING_DOCS_NB_EXECUTION", "force")  # the notebooks are stored without outputs: run them at build time
nb_execution_timeout = 180
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_ipywidgets_js: dict = {}  # no require.js / widget manager from a CDN: widgets show their text form
# with no widget manager the widget view renders as nothing: an explorer's output shows the picture of its
# state that its display bundle carries beside the view (image/png, aliasing.explore.widget.Explorer)
nb_mime_priority_overrides = [("html", "application/vnd.jupyter.widget-view+json", None)]
nb_merge_streams = True
suppress_warnings = ["mystnb.unknown_mime_type"]

# -- HTML ------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"aliasing {release}"
html_static_path = ["_static"]
html_css_files = ["aliasing.css"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 8,
    "navbar_end": ["theme-switcher", "navbar-icon-links"],
}
html_context = {"default_mode": "auto"}  # empty by default: the theme then logs a console error
html_show_sourcelink = False
html_copy_source = False
html_last_updated_fmt = None

# -- gallery (examples generated from aliasing.reproduce.TARGETS by docs/_ext/gallery_targets.py)
sphinx_gallery_conf = {
    "examples_dirs": "_gallery_src",
    "gallery_dirs": "auto_gallery",
    "filename_pattern": r"plot_",
    "image_scrapers": ("gallery_targets.png_scraper",),
    "download_all_examples": False,
    "show_memory": False,
    "line_numbers": False,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "reset_modules": (),
    "remove_config_comments": True,
    "show_signature": False,
    "within_subsection_order": "gallery_targets.TargetOrder",  # the order of aliasing.reproduce.TARGETS
    "matplotlib_animations": False,
    "min_reported_time": 10**6,
    "write_computation_times": False,
}

# -- notebooks: copies of ../notebooks (stored without outputs; executed by myst-nb) -------
def _copy_notebooks() -> None:
    import shutil

    dest = HERE / "notebooks"
    dest.mkdir(exist_ok=True)
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        target = dest / nb.name
        if not target.exists() or target.read_bytes() != nb.read_bytes():
            shutil.copyfile(nb, target)


_copy_notebooks()


# -- other pages under docs/ (helpers may add docs/*.md): listed in the index's second toctree
def _more_pages() -> None:
    known = {"ERRATA", "benchmarks"}
    extra = sorted(p.stem for p in HERE.glob("*.md") if p.stem not in known)
    text = "" if not extra else ".. toctree::\n   :maxdepth: 1\n   :caption: More\n\n" + "".join(f"   {e}\n" for e in extra)
    target = HERE / "_more_pages.rst"
    if not target.exists() or target.read_text() != text:
        target.write_text(text)


_more_pages()

# -- drawn figures (matplotlib's plot directive, run at build time) ----------------------
plot_include_source = False
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 150)]
plot_basedir = str(HERE)

# numpydoc's signature hook re-reads raw docstrings and warns about their "Example" heading;
# the rendered docstrings get it renamed to "Examples" by docs/_ext/docstring_text.py.
import warnings  # noqa: E402

warnings.filterwarnings("ignore", message="Unknown section Example", category=UserWarning)
