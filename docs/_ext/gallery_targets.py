"""Gallery examples generated from :data:`aliasing.reproduce.TARGETS`.

The ``figures/`` scripts are ``main(out_dir)`` functions that save a PNG and its CSV (they do
not leave a matplotlib figure open), so sphinx-gallery cannot run them as they are. Instead,
one thin example per target is written to ``docs/_gallery_src/`` when this extension loads
(before sphinx-gallery scans that folder): its text is the target's description, the paper
reference, the script's own docstring and a link to the CSV; its code calls the script's
``main``. :func:`png_scraper` hands the PNGs the script wrote to sphinx-gallery, which shows
them and makes the thumbnails.
"""

from __future__ import annotations

import importlib
import re
import shutil
from pathlib import Path

from docstring_text import escape_pipes
from sphinx.application import Sphinx

HEADER = """\
Gallery of reproduced figures
=============================

Every figure and table that ``aliasing reproduce all`` writes, built by running its script in
``figures/`` while the site is built. Each page names the paper's figure it reproduces, shows the
script's own account of what is plotted and links to the numbers as CSV. Disagreements with the
papers are explained in the :doc:`/ERRATA`.
"""

TEMPLATE = '''\
"""
{title}
{underline}

{description}

**Reproduces:** {reference}. **Script:** ``figures/{module}.py`` (``aliasing reproduce {name}``).
**Numbers:** {downloads}.

{body}
"""

# %%
from pathlib import Path

from aliasing.figures import {module} as script

written = script.main(Path("../auto_gallery/data"))  # the PNG and its numbers (CSV)
{extra}'''


def _reference(description: str) -> str:
    head = description.split(":", 1)[0]
    return head if re.search(r"(19|20)\d\d|Table|Fig", head) else f"{head} (new figure, no paper counterpart)"


def _title(description: str) -> str:
    """"Lloyd 2006 Fig. 5" from "Lloyd 2006 Fig. 5: m_x, ..."; "Rasterizer: shadowed renders" from
    "Rasterizer: shadowed renders, Standard/...": short, and distinct between targets."""
    head, _, rest = description.partition(":")
    if (re.search(r"(19|20)\d\d", head) and len(head) <= 40) or len(head) >= 20:
        return head
    text = head if not rest else f"{head}: {rest.strip()}"
    return re.split(r",| \(", text, maxsplit=1)[0]


def _body(mod) -> str:
    """The script's docstring after its title line; roles naming the script's own helpers (which
    have no API page: the scripts are documented here) become plain code."""
    lines = (mod.__doc__ or "").strip().splitlines()[1:]
    text = "\n".join(escape_pipes(lines)).strip().replace('"""', "'''").replace("\\", "\\\\")
    own = lambda m: f"``{m.group(1)}``" if hasattr(mod, m.group(1).lstrip("~.")) else m.group(0)
    return re.sub(r":(?:func|class|data|obj):`([^`<>]+)`", own, text)


def write_examples(src: Path) -> None:
    from aliasing.reproduce import TARGETS

    if src.exists():
        shutil.rmtree(src)
    src.mkdir(parents=True)
    (src / "GALLERY_HEADER.rst").write_text(HEADER)
    for target in TARGETS.values():
        mod = importlib.import_module(f"aliasing.figures.{target.module}")
        title = _title(target.description)
        outputs = ["csv"] + (["md"] if target.module == "lloyd2007_table3" else [])
        downloads = ", ".join(f":download:`{target.name}.{ext} <data/{target.name}.{ext}>`" for ext in outputs)
        extra = ""
        if "md" in outputs:  # a table: shown as an HTML table (the block's last value, its _repr_html_), beside its PNG
            extra = ("\n# %%\n# The same comparison as a table (hover over a cell for its status; the Markdown file lists the\n"
                     "# explained and unexplained cells and the pyramid rules' rows).\n\n"
                     "from aliasing.figures import _table3_views\n\n"
                     "_table3_views.HTMLTable(Path('../auto_gallery/data/lloyd2007-table3.csv'), script.SHORT_NOTES)\n")
        (src / f"plot_{target.module}.py").write_text(TEMPLATE.format(
            title=title, underline="=" * len(title), description=target.description,
            reference=_reference(target.description), module=target.module, name=target.name,
            downloads=downloads, body=_body(mod), extra=extra))


def png_scraper(block, block_vars, gallery_conf, **kwargs):
    """sphinx-gallery image scraper: the PNGs listed in the example's ``written`` variable."""
    from sphinx_gallery.scrapers import figure_rst

    glob = block_vars["example_globals"]
    written = glob.pop("written", None) or []
    images = []
    for path in written:
        if Path(path).suffix == ".png":
            dest = next(block_vars["image_path_iterator"])
            shutil.copyfile(path, dest)
            images.append(dest)
    return figure_rst(images, gallery_conf["src_dir"])


def setup(app: Sphinx) -> dict:
    write_examples(Path(app.srcdir) / "_gallery_src")
    (Path(app.srcdir) / "auto_gallery" / "data").mkdir(parents=True, exist_ok=True)
    return {"parallel_read_safe": True, "version": "1"}


class TargetOrder:
    """sphinx-gallery sort key: the examples in the order of ``TARGETS`` (paper by paper)."""

    def __init__(self, src_dir) -> None:
        from aliasing.reproduce import TARGETS

        self.order = {f"plot_{t.module}.py": i for i, t in enumerate(TARGETS.values())}

    def __call__(self, filename: str) -> tuple[int, str]:
        return self.order.get(Path(filename).name, len(self.order)), filename
