"""Headless Chromium (the system's, through Playwright for Python) running an engine's page.

The pages (``aliasing/frames/pages``) and the engines' installed packages are served to the
browser by Playwright's request routing from the local files under a made-up origin: nothing
is fetched from the network, and any other request is refused.  WebGL 2 runs on SwiftShader
(``--use-angle=swiftshader``): no GPU is needed.

:class:`Browser` launches Chromium once; :meth:`Browser.render` loads an engine's page, calls
its ``window.frame(job)`` and returns what the page read back.  Each page load and each frame
has a time limit; a page that throws reports its first error line (:class:`PageError`).

Examples
--------
>>> chromium_path() is None or chromium_path().endswith("chromium")
True
"""

from __future__ import annotations

import base64
import json
import mimetypes
import os
import shutil
from pathlib import Path

from .install import PINS, MissingTool, package_root

PAGES = Path(__file__).parent / "pages"
ORIGIN = "http://frames.invalid"
ARGS = ["--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--no-sandbox", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run", "--ignore-gpu-blocklist",
        "--disable-features=BlockInsecurePrivateNetworkRequests,PrivateNetworkAccessSendPreflights,LocalNetworkAccessChecks"]  # Godot: 127.0.0.1
CANDIDATES = ("/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome")


_CALL = """async ({job, ms}) => {
  const limit = new Promise((_, reject) => setTimeout(() => reject(new Error(`the frame took longer than ${ms / 1000} s`)), ms));
  try { return await Promise.race([window.frame(job), limit]); } catch (e) { return { error: String(e && e.message || e) }; }
}"""


class _LocalFiles:
    """A read-only HTTP server on 127.0.0.1 (a free port) for the files of one folder, in a thread.

    Godot's runtime (a 37 MB WebAssembly) is served this way: through Playwright's request routing
    its body would cross the DevTools protocol, which takes seconds.  Any path outside the folder,
    and any method but GET and HEAD, is refused.
    """

    def __init__(self, folder: Path):
        import http.server
        import threading

        root = Path(folder).resolve()

        class Handler(http.server.SimpleHTTPRequestHandler):
            def __init__(self, *a, **k):
                super().__init__(*a, directory=str(root), **k)

            def end_headers(self):
                self.send_header("Access-Control-Allow-Origin", ORIGIN)
                self.send_header("Cache-Control", "no-store")
                super().end_headers()

            def log_message(self, *a):  # quiet
                pass

        Handler.extensions_map = {**Handler.extensions_map, ".wasm": "application/wasm", ".js": "text/javascript"}
        self._server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.url = f"http://127.0.0.1:{self._server.server_address[1]}/"
        self._thread = threading.Thread(target=self._server.serve_forever, daemon=True)
        self._thread.start()

    def close(self) -> None:
        self._server.shutdown()
        self._server.server_close()


class PageError(RuntimeError):
    """The engine's page threw, timed out or could not load: the message is one line.

    Parameters
    ----------
    message : str
        One line: the engine and the page's first error line.

    Examples
    --------
    >>> str(PageError("threejs page threw: x is not defined"))
    'threejs page threw: x is not defined'
    """


def chromium_path() -> str | None:
    """The system Chromium (``$ALIASING_CHROMIUM``, or Debian's ``/usr/bin/chromium``), None when there is none.

    Returns
    -------
    str or None
        The executable's path.

    Examples
    --------
    >>> old = os.environ.get("ALIASING_CHROMIUM")
    >>> os.environ["ALIASING_CHROMIUM"] = "/nonexistent/chromium"        # set but not executable: none
    >>> chromium_path() is None
    True
    >>> _ = os.environ.pop("ALIASING_CHROMIUM") if old is None else os.environ.update(ALIASING_CHROMIUM=old)
    """
    env = os.environ.get("ALIASING_CHROMIUM")
    if env:
        return env if os.access(env, os.X_OK) else None
    for c in CANDIDATES:
        if os.access(c, os.X_OK):
            return c
    found = shutil.which("chromium")
    return found


def _first_line(text: str) -> str:
    lines = [ln.strip() for ln in str(text).splitlines() if ln.strip()]
    return lines[0] if lines else "unknown error"


class Browser:
    """One headless Chromium for many frames (a context manager).

    Parameters
    ----------
    timeout : float
        Seconds each page load and each frame may take, > 0.

    Raises
    ------
    MissingTool
        Playwright for Python or Chromium is missing (one line saying how to install it).

    Examples
    --------
    >>> Browser(timeout=0)
    Traceback (most recent call last):
    ...
    ValueError: timeout must be > 0 seconds, got 0

    Launching Chromium is not run here (it needs the browser and Playwright)::

        with Browser(timeout=120) as b:
            out = b.render("threejs", job)
    """

    def __init__(self, timeout: float = 60.0):
        if not (isinstance(timeout, (int, float)) and timeout > 0):
            raise ValueError(f"timeout must be > 0 seconds, got {timeout!r}")
        self.timeout = float(timeout)
        try:
            from playwright.sync_api import sync_playwright
        except ImportError:
            raise MissingTool("Playwright for Python is not installed: pip install 'aliasing[frames]' (the system Chromium is used; no browser download)") from None
        exe = chromium_path()
        if exe is None:
            raise MissingTool("Chromium not found: install it (Debian: apt-get install chromium) or set ALIASING_CHROMIUM to its path")
        self._pw = sync_playwright().start()
        try:
            self._browser = self._pw.chromium.launch(executable_path=exe, args=ARGS, headless=True)
        except Exception as e:  # noqa: BLE001 - Playwright's launch errors are plain Exceptions
            self._pw.stop()
            raise MissingTool(f"Chromium at {exe} did not start: {_first_line(e)}") from None
        self._roots: dict[str, Path] = {}
        self._local: _LocalFiles | None = None

    def __enter__(self) -> "Browser":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Close Chromium and Playwright (again: nothing).

        Returns
        -------
        None

        Examples
        --------
        Needs a running browser, so it is not run here:

        >>> b = Browser()                  # doctest: +SKIP
        >>> b.close(); b.close()           # doctest: +SKIP
        """
        if getattr(self, "_local", None) is not None:
            self._local.close()
            self._local = None
        if getattr(self, "_browser", None) is not None:
            self._browser.close()
            self._browser = None
            self._pw.stop()

    def _serve(self, route) -> None:
        url = route.request.url
        if self._local is not None and url.startswith(self._local.url) and ".." not in url:
            route.continue_()
            return
        if not url.startswith(ORIGIN + "/"):
            route.abort()
            return
        rel = url[len(ORIGIN) + 1:].split("?")[0]
        path = None
        if rel.startswith("pages/"):
            path = PAGES / rel[len("pages/"):]
        elif rel.startswith("node_modules/"):
            for root in self._roots.values():
                cand = root / rel
                if cand.is_file():
                    path = cand
                    break
        if path is None or not path.is_file() or ".." in Path(rel).parts:
            route.fulfill(status=404, body="not found")
            return
        ctype = "text/javascript" if path.suffix in (".js", ".mjs") else "application/wasm" if path.suffix == ".wasm" else (mimetypes.guess_type(path.name)[0] or "application/octet-stream")
        route.fulfill(status=200, body=path.read_bytes(), headers={"content-type": ctype, "cache-control": "no-store"})

    def render(self, engine: str, job: dict) -> dict:
        """Render ``job`` with ``engine``'s page; the page's read-back as a dict.

        Parameters
        ----------
        engine : str
            One of :data:`aliasing.frames.install.PINS`.
        job : dict
            The page's job (:func:`aliasing.frames.run.make_job`; ``width`` and ``height`` [px]).

        Returns
        -------
        dict
            The page's answer (:func:`aliasing.frames.readback.decode`).

        Raises
        ------
        ValueError
            ``engine`` is not one of the pinned engines.
        MissingTool
            The engine's package is not installed.
        PageError
            The page threw (its first error line), or loading or rendering ran past the time limit.

        Examples
        --------
        Needs Chromium and the installed engine, so it is not run here:

        >>> from aliasing.frames.run import make_job, frame_scene
        >>> job = make_job(frame_scene("boxes", near=1.0, far=30.0, fov=50.0, aspect=1.0), [0.3, 0.9, 0.3], {}, 64)
        >>> with Browser() as b:                                   # doctest: +SKIP
        ...     out = b.render("threejs", job)
        >>> from aliasing.frames.readback import decode
        >>> decode(out).shadow.shape                               # doctest: +SKIP
        (64, 64)
        """
        if not isinstance(job, dict) or not all(k in job for k in ("width", "height")):
            raise ValueError("job must be the page's job dict with width and height [px] (aliasing.frames.run.make_job)")
        if engine not in PINS:
            raise ValueError(f"engine must be one of {', '.join(sorted(PINS))}, got {engine!r}")
        self._roots[engine] = package_root(engine)
        if engine == "godot":  # Godot's runtime checked, and the job's scene as its main pack
            from .godot import job_pack
            from .install import godot_runtime

            runtime = godot_runtime(self._roots[engine])
            if self._local is None:
                self._local = _LocalFiles(runtime)
            job = {**job, "pack": base64.b64encode(job_pack({k: v for k, v in job.items() if k not in ("pack", "runtime")})).decode(),
                   "runtime": self._local.url}
        page = self._browser.new_page(viewport={"width": int(job["width"]), "height": int(job["height"])})
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(_first_line(e)))
        page.on("console", lambda m: errors.append(_first_line(m.text)) if m.type == "error" else None)
        page.route("**/*", self._serve)
        ms = int(self.timeout * 1000)
        try:
            page.goto(f"{ORIGIN}/pages/index.html?engine={engine}", timeout=ms)
            page.wait_for_function("window.frameReady === true || window.frameError !== undefined", timeout=ms)
            failed = page.evaluate("window.frameError")
            if failed:
                raise PageError(f"{engine} page did not load: {_first_line(failed)}")
            page.set_default_timeout(ms)
            out = page.evaluate(_CALL, {"job": job, "ms": ms})
        except PageError:
            raise
        except Exception as e:  # noqa: BLE001 - Playwright's TimeoutError and evaluation errors
            first = errors[0] if errors else _first_line(e)
            raise PageError(f"{engine} page failed: {first}") from None
        finally:
            page.close()
        if not isinstance(out, dict):
            raise PageError(f"{engine} page returned {json.dumps(out)[:80]}")
        if "error" in out:
            said = f" (its console: {errors[0]})" if errors else ""
            raise PageError(f"{engine} page threw: {_first_line(out['error'])}{said}")
        return out
