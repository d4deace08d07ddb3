"""The documentation site: built with warnings as errors, then checked in headless Chromium.

The build is README's command (``sphinx-build -W -n``, run as ``python -m sphinx``). Chromium,
driven over the DevTools protocol, opens the index, the gallery, one API page and one user-guide
page of the built site and fails on: a JavaScript error or console error, any request that is not
a local file (no CDN: the site must work offline), an image that did not load, a link to a local
page or anchor that does not exist, and mathematics left unrendered (math in the page's source
but no MathJax ``mjx-container``, or a MathJax error). Screenshots of each page are kept in
``docs/_build/screenshots/`` as artifacts.

Skipped with the reason when the ``docs`` extra or Chromium is missing; CI installs both
(``.ci/run`` installs Debian's chromium, the test extra includes the docs extra).
"""

from __future__ import annotations

import base64
import importlib.util
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse
import urllib.request
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
HTML = DOCS / "_build" / "html"
SHOTS = DOCS / "_build" / "screenshots"
PAGES = ["index.html", "auto_gallery/index.html", "api/aliasing.error.html", "guide/overhead.html", "getting-started.html",
         "auto_gallery/plot_lloyd2006_fig5.html", "notebooks/01_overhead_light.html", "cli.html"]
DOCS_MODULES = ["sphinx", "pydata_sphinx_theme", "numpydoc", "sphinx_gallery", "myst_nb", "websocket"]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--no-first-run"]

missing = [m for m in DOCS_MODULES if importlib.util.find_spec(m) is None]
pytestmark = [
    pytest.mark.skipif(bool(missing), reason=f"the docs extra is not installed (missing {', '.join(missing)}): "
                                              "pip install \".[docs]\""),
    pytest.mark.skipif(CHROMIUM is None, reason="chromium is not installed (Debian: apt-get install -y chromium)"),
]


@pytest.fixture(scope="module")
def site() -> Path:
    """Build the site as README says, with warnings as errors and nitpicky references."""
    # -E: read every source again; an incremental build re-emits no warning of an unchanged page, so a
    # stale docs/_build once hid an unresolved reference that a fresh clone's build reported
    cmd = [sys.executable, "-m", "sphinx", "-E", "-W", "--keep-going", "-n", "-b", "html", str(DOCS), str(HTML)]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=900)
    warnings = [line for line in proc.stderr.splitlines() if "WARNING" in line or "ERROR" in line]
    assert proc.returncode == 0, "docs build failed:\n" + "\n".join(warnings[-40:] or proc.stderr.splitlines()[-40:])
    return HTML


class Browser:
    """Headless Chromium with one page, driven over the DevTools protocol."""

    def __init__(self) -> None:
        import websocket

        self.profile = tempfile.mkdtemp(prefix="aliasing-docs-chromium-")
        self.proc = subprocess.Popen([CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={self.profile}",
                                      "--remote-debugging-port=0", "--window-size=1280,1000", "about:blank"],
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        port_file = Path(self.profile) / "DevToolsActivePort"
        deadline = time.monotonic() + 60
        while not (port_file.exists() and port_file.read_text().strip()):
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.close()
                raise RuntimeError("chromium did not start its DevTools endpoint")
            time.sleep(0.1)
        port = port_file.read_text().split()[0]
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30) as r:
            page = next(t for t in json.load(r) if t["type"] == "page")
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=60, suppress_origin=True)
        self.next_id = 0
        self.events: list[dict] = []
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.call(f"{domain}.enable")
        self.call("Emulation.setDeviceMetricsOverride", width=1280, height=1000, deviceScaleFactor=1, mobile=False)

    def call(self, method: str, **params):
        self.next_id += 1
        self.ws.send(json.dumps({"id": self.next_id, "method": method, "params": params}))
        while True:
            msg = json.loads(self.ws.recv())
            if msg.get("id") == self.next_id:
                if "error" in msg:
                    raise RuntimeError(f"{method}: {msg['error']}")
                return msg["result"]
            self.events.append(msg)

    def wait_for(self, method: str, timeout: float = 60.0) -> None:
        deadline = time.monotonic() + timeout
        while not any(e.get("method") == method for e in self.events):
            if time.monotonic() > deadline:
                raise TimeoutError(method)
            self.events.append(json.loads(self.ws.recv()))

    def evaluate(self, expression: str):
        res = self.call("Runtime.evaluate", expression=expression, awaitPromise=True, returnByValue=True)
        if "exceptionDetails" in res:
            raise RuntimeError(f"{expression}: {res['exceptionDetails']}")
        return res["result"].get("value")

    def close(self) -> None:
        if getattr(self, "ws", None) is not None:
            self.ws.close()
        self.proc.terminate()
        try:
            self.proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        shutil.rmtree(self.profile, ignore_errors=True)


@pytest.fixture(scope="module")
def browser():
    b = Browser()
    yield b
    b.close()


PAGE_STATE = """(async () => {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) { await MathJax.startup.promise; }
  await new Promise(r => setTimeout(r, 300));
  return {
    brokenImages: [...document.images].filter(i => !i.complete || i.naturalWidth === 0).map(i => i.src),
    links: [...document.querySelectorAll('a[href]')].map(a => a.href),
    ids: [...document.querySelectorAll('[id]')].map(e => e.id),
    mathSource: document.querySelectorAll('.math, span.math, div.math').length,
    mathRendered: document.querySelectorAll('mjx-container').length,
    mathErrors: document.querySelectorAll('mjx-merror').length,
    height: Math.min(document.documentElement.scrollHeight, 6000),
  };
})()"""


def _problems(events: list[dict]) -> list[str]:
    out = []
    for e in events:
        m, p = e.get("method"), e.get("params", {})
        if m == "Runtime.exceptionThrown":
            out.append(f"JavaScript error: {p['exceptionDetails'].get('exception', {}).get('description') or p['exceptionDetails'].get('text')}")
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console error: " + " ".join(str(a.get("value", a.get("description", ""))) for a in p.get("args", [])))
        elif m == "Log.entryAdded" and p["entry"].get("level") == "error":
            out.append(f"browser error: {p['entry'].get('text')} {p['entry'].get('url', '')}")
        elif m == "Network.requestWillBeSent" and not p["request"]["url"].startswith(("file:", "data:", "blob:", "about:")):
            out.append(f"network request (the site must work offline): {p['request']['url']}")
        elif m == "Network.loadingFailed" and not p.get("canceled"):
            out.append(f"failed to load: {p.get('errorText')} ({p.get('type')})")
    return out


def _link_problems(page: Path, links: list[str], ids: list[str]) -> list[str]:
    out = []
    for href in links:
        url = urllib.parse.urlsplit(href)
        if url.scheme != "file":
            continue  # external links are not followed (no network); nothing is *loaded* from them
        target = Path(urllib.parse.unquote(url.path))
        if not target.exists():
            out.append(f"broken link: {href}")
        elif url.fragment and target == page and url.fragment not in ids:
            out.append(f"broken anchor: {href}")
        elif url.fragment and target != page and target.suffix == ".html":
            text = target.read_text(encoding="utf-8", errors="replace")
            if f'id="{url.fragment}"' not in text:
                out.append(f"broken anchor: {href}")
    return out


def test_every_reproduce_target_wrote_its_figure_and_numbers(site: Path) -> None:
    # the gallery runs every target's script (main(out), as `aliasing reproduce all` does) into auto_gallery/data:
    # each writes a PNG of a real figure and its numbers, a CSV with a header and data rows (README: every target does)
    from aliasing.reproduce import TARGETS

    data = DOCS / "auto_gallery" / "data"
    for name in TARGETS:
        png, csv = data / f"{name}.png", data / f"{name}.csv"
        assert png.exists() and png.stat().st_size > 10_000, f"{name} wrote no figure"
        assert csv.exists() and len(csv.read_text().strip().splitlines()) >= 2, f"{name} wrote no numbers"


@pytest.mark.parametrize("name", PAGES)
def test_page_in_chromium(site: Path, browser: Browser, name: str) -> None:
    page = site / name
    assert page.exists(), f"{name} was not built"
    browser.events.clear()
    browser.call("Page.navigate", url=page.as_uri())
    browser.wait_for("Page.loadEventFired")
    state = browser.evaluate(PAGE_STATE)
    problems = _problems(browser.events)
    problems += [f"broken image: {src}" for src in state["brokenImages"]]
    problems += _link_problems(page, state["links"], state["ids"])
    if state["mathSource"] and not state["mathRendered"]:
        problems.append(f"{state['mathSource']} math elements in the source, none rendered by MathJax")
    if state["mathErrors"]:
        problems.append(f"{state['mathErrors']} MathJax errors")
    SHOTS.mkdir(parents=True, exist_ok=True)
    shot = browser.call("Page.captureScreenshot", format="png", captureBeyondViewport=True,
                        clip={"x": 0, "y": 0, "width": 1280, "height": state["height"], "scale": 1})
    (SHOTS / (name.replace("/", "__").removesuffix(".html") + ".png")).write_bytes(base64.b64decode(shot["data"]))
    assert not problems, f"{name}:\n" + "\n".join(problems)
    if name in ("index.html", "guide/overhead.html"):
        assert state["mathRendered"] > 0, "this page's source has math; MathJax rendered none"


def test_every_public_function_is_in_the_api_reference(site: Path) -> None:
    """Each public function/class of every API module has its own entry (an anchor) in the pages."""
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import api_pages
    finally:
        sys.path.remove(str(DOCS / "_ext"))
    missing_entries = []
    for modname in api_pages.public_modules():
        mod = importlib.import_module(modname)
        own, _, _ = api_pages.members(mod)
        text = (site / "api" / f"{modname}.html").read_text(encoding="utf-8")
        missing_entries += [f"{modname}.{n}" for n in own if f'id="{modname}.{n}"' not in text]
    assert not missing_entries, missing_entries
    # the equations travel with the docstrings: a function implementing a paper names its equation
    error_page = (site / "api" / "aliasing.error.html").read_text(encoding="utf-8")
    assert "eq. 7" in error_page or "eq. (7)" in error_page or "eqs. 7" in error_page


def _png_size(path: Path) -> tuple[int, int]:
    """(width, height) [pixels] from a PNG's header."""
    head = path.read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def test_notebook_pages_show_the_explorers_pictures(site: Path) -> None:
    """Each notebook cell that shows an explorer gives an <img> of its picture on the page (no widget manager runs
    there): the PNG the explorer's display bundle carries beside the widget view, at the explorer's pixel size."""
    import re

    pytest.importorskip("ipywidgets")
    from aliasing.explore import widget

    sizes = {(int(c.figsize[0] * c.dpi), int(c.figsize[1] * c.dpi)) for c in _explorer_classes(widget.Explorer)}
    checked = 0
    for nb in sorted((ROOT / "notebooks").glob("*.ipynb")):
        cells = json.loads(nb.read_text(encoding="utf-8"))["cells"]
        shown = sum(1 for c in cells if c["cell_type"] == "code" and re.search(r"explore\.\w+\(", "".join(c["source"])))
        if not shown:
            continue
        page = site / "notebooks" / f"{nb.stem}.html"
        text = page.read_text(encoding="utf-8")
        assert "widget-view+json" not in text, f"{page.name}: an unrendered widget view is left on the page"
        pictures = [src for src in re.findall(r'<img [^>]*src="([^"]+)"', text)
                    if (page.parent / src).resolve().exists() and _png_size((page.parent / src).resolve()) in sizes]
        assert len(pictures) >= shown, f"{page.name}: {shown} explorer(s) shown, {len(pictures)} explorer picture(s) on the page"
        if 'id="play-with-it"' in text:  # the picture follows the heading that introduces the explorer
            assert any(text.index(f'src="{src}"') > text.index('id="play-with-it"') for src in pictures), page.name
        checked += 1
    assert checked >= 5


def _explorer_classes(base: type) -> list[type]:
    import importlib
    import pkgutil

    import aliasing.explore as pkg

    for info in pkgutil.iter_modules(pkg.__path__):
        importlib.import_module(f"aliasing.explore.{info.name}")
    out, todo = [], list(base.__subclasses__())
    while todo:
        c = todo.pop()
        out.append(c)
        todo += c.__subclasses__()
    return out
