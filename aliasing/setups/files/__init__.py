"""Your project as it is: the engines' own scene and project files read, and patched, in their own format.

One reader module per engine file format, each citing where the format is documented at the pinned
release (:mod:`.common` says what a reader defines and returns).  :func:`read` picks the reader by
the file's extension and content, :func:`patch` writes changed settings back into the same file
touching nothing else, :func:`write` applies that patch atomically.

=============  ==========================================================
engine         files
=============  ==========================================================
godot          ``project.godot`` and a ``.tscn``/``.tres`` scene
babylon        a ``.babylon`` scene (SceneSerializer's JSON)
threejs        the Object JSON of ``scene.toJSON()`` and the editor
playcanvas     a PlayCanvas scene JSON
unity-urp      a URP asset (``.asset`` YAML) and, optionally, a ``.unity`` scene
unreal         ``DefaultEngine.ini`` (``r.Shadow.*``)
filament       the viewer's settings JSON (``shadowOptions``)
=============  ==========================================================

Examples
--------
>>> sorted(FORMATS)
['babylon', 'filament', 'godot', 'playcanvas', 'threejs', 'unity-urp', 'unreal']
"""

from __future__ import annotations

import importlib
import os
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import ModuleType
from typing import Any

from .common import FileError, Found, merge_camera, sun_from_directions, vertical_fov

#: The formats, by the toolkit's engine name, and the module that reads them.
FORMATS: dict[str, str] = {
    "godot": "godot",
    "babylon": "babylon",
    "threejs": "threejs",
    "playcanvas": "playcanvas",
    "unity-urp": "unity_urp",
    "unreal": "unreal",
    "filament": "filament",
}

__all__ = ["FORMATS", "FileError", "Found", "detect", "merge_camera", "patch", "read", "reader", "sun_from_directions", "vertical_fov", "write"]


def reader(engine: str) -> ModuleType:
    """The reader module of ``engine`` (a key of :data:`FORMATS`)."""
    if engine not in FORMATS:
        raise ValueError(f"engine must be one of {', '.join(FORMATS)} for a project file, got {engine!r}")
    return importlib.import_module(f"{__name__}.{FORMATS[engine]}")


def _readers() -> list[ModuleType]:
    out = []
    for engine in FORMATS:
        try:
            out.append(reader(engine))
        except ModuleNotFoundError:
            continue
    return out


def _text(path: str | Path) -> tuple[Path, str]:
    if not isinstance(path, (str, Path)) or not str(path).strip():
        raise ValueError(f"project must be a file path, got {path!r}")
    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise ValueError(f"project file {str(p)!r} cannot be read: {exc.strerror or exc}") from None
    try:
        return p, data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise FileError(p, "byte " + str(data.find(b"\x80") if b"\x80" in data else 0), "UTF-8 text (a project file in the engine's text format)") from None


def detect(path: str | Path, text: str | None = None) -> str:
    """The engine whose file ``path`` is (by extension and content).

    Raises
    ------
    ValueError
        Naming the file and the formats it could be.
    """
    if text is not None and not isinstance(text, str):
        raise ValueError(f"text must be the file's text (str) or None to read the file, got {type(text).__name__}")
    if text is not None and (not isinstance(path, (str, Path)) or not str(path).strip()):
        raise ValueError(f"path must be a file path, got {path!r}")
    p, t = _text(path) if text is None else (Path(path), text)
    hits = [m.ENGINE for m in _readers() if m.sniff(p, t)]
    if not hits:
        raise FileError(p, "the whole file", "one of: " + "; ".join(m.TITLE for m in _readers()), "a file of none of these formats")
    return hits[0]


def read(paths: str | Path | Sequence[str | Path], light: str | None = None, camera: str | None = None) -> Found:
    """The shadow setup in the engine's own files ``paths`` (one engine's; several where it splits them).

    Parameters
    ----------
    paths : path or sequence of paths
        The files (``project.godot`` and ``main.tscn``; ``scene.babylon``; ...).
    light, camera : str, optional
        The light (or shadow generator) and the camera to take, by the name the file gives them, where a
        file holds more than one.

    Raises
    ------
    ValueError
        A file that cannot be read, of no known format, of two engines, or damaged (:class:`FileError`).
    """
    items = [paths] if isinstance(paths, (str, Path)) else list(paths) if isinstance(paths, Sequence) else None
    if not items:
        raise ValueError(f"project must be one or more file paths, got {paths!r}")
    for name, value in (("light", light), ("camera", camera)):
        if value is not None and (not isinstance(value, str) or not value.strip()):
            raise ValueError(f"{name} must be a node or object name, got {value!r}")
    files = [_text(p) for p in items]
    engines = {str(p): detect(p, t) for p, t in files}
    if len(set(engines.values())) > 1:
        raise ValueError("project files must be one engine's, got " + ", ".join(f"{k} ({v})" for k, v in engines.items()))
    engine = next(iter(engines.values()))
    return reader(engine).read(files, light, camera)


def patch(path: str | Path, changes: Mapping[str, Any], light: str | None = None, camera: str | None = None) -> str:
    """The text of ``path`` with ``changes`` (engine keys to values) written in the file's own format.

    Nothing else in the file changes; reading the result back gives the changed values exactly.
    """
    if not isinstance(changes, Mapping):
        raise ValueError(f"changes must be a mapping of engine keys to values, got {type(changes).__name__}")
    p, text = _text(path)
    engine = detect(p, text)
    mod = reader(engine)
    profile = getattr(mod, "PROFILE", None)
    typed = {}
    for key, value in changes.items():
        if not isinstance(key, str):
            raise ValueError(f"changes must map the engine's setting keys (text) to values, got the key {key!r}")
        try:
            typed[key] = value if profile is None else profile.setting(key).coerce(value)
        except ValueError as exc:
            raise ValueError(f"changes[{key!r}]: {exc}") from None
    found = mod.read([(p, text)], light, camera)
    return mod.patch(p, text, typed, found)


def write(path: str | Path, changes: Mapping[str, Any], light: str | None = None, camera: str | None = None) -> Path:
    """Apply :func:`patch` to ``path`` atomically (a temporary file beside it, then a rename); returns the path.

    The new text is read back first: where it does not give ``changes`` exactly, nothing is written.
    """
    new = patch(path, changes, light, camera)
    p = Path(path)
    engine = detect(p, new)
    back = reader(engine).read([(p, new)], light, camera)
    profile = getattr(reader(engine), "PROFILE", None)
    typed = {k: v if profile is None else profile.setting(k).coerce(v) for k, v in changes.items()}
    wrong = {k: (v, back.settings.get(k)) for k, v in typed.items() if back.settings.get(k) != v}
    if wrong:
        raise ValueError(f"{p.name}: the patch does not read back as written ({wrong}); the file is unchanged")
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", dir=p.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
            fh.write(new)
        os.replace(tmp, p)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return p
