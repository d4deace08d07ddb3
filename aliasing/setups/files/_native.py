"""What the Unity URP, Unreal and Filament readers share: typing a file's value as the profile's
setting (a one-line :class:`~aliasing.setups.files.common.FileError` where it does not fit), writing a value back in
the file's spelling, and the text checks every reader makes first.

Examples
--------
>>> coerce("URP.asset", 12, "unity-urp", "shadowDistance", "80")
80.0
>>> coerce("URP.asset", 12, "unity-urp", "shadowCascadeCount", "7")
Traceback (most recent call last):
...
aliasing.setups.files.common.FileError: URP.asset: line 12 / shadowCascadeCount: expected a whole number in [1, 4], got '7'
>>> number_text(50.0), number_text(0.467), number_text(2048)
('50', '0.467', '2048')
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .. import get
from ..profile import Setting
from .common import FileError


def setting(engine: str, key: str) -> Setting:
    """The profile's setting ``key`` of ``engine`` (the newest release's)."""
    return get(engine).setting(key)


def coerce(path: str | Path, line: int | str, engine: str, key: str, value: Any) -> Any:
    """``value`` (the file's text or number) as the profile's type of ``key``; a :class:`FileError`
    naming the file, the line (or JSON key) and the setting where it does not fit."""
    s = setting(engine, key)
    where = f"line {line} / {key}" if isinstance(line, int) else f"{line}"
    try:
        return s.coerce(value)
    except ValueError:
        unit = f" [{s.unit}]" if s.unit else ""
        raise FileError(path, where, s.allowed() + unit, repr(value)) from None


def pairs(files: Any, light: Any, camera: Any) -> list[tuple[Path, str]]:
    """``files`` as a non-empty list of (path, text) pairs, and ``light``/``camera`` None or names (ValueError naming them)."""
    if not isinstance(files, (list, tuple)) or not files or not all(
            isinstance(f, tuple) and len(f) == 2 and isinstance(f[0], Path) and isinstance(f[1], str) for f in files):
        raise ValueError(f"files must be a non-empty list of (Path, text) pairs, got {type(files).__name__}")
    for name, value in (("light", light), ("camera", camera)):
        if value is not None and (not isinstance(value, str) or not value.strip()):
            raise ValueError(f"{name} must be a node or object name, got {value!r}")
    return list(files)


def text_of(path: str | Path, text: str, what: str) -> None:
    """Refuse text that is empty or holds NUL bytes (a binary file decoded as UTF-8)."""
    if not text.strip():
        raise FileError(path, "the whole file", what, "an empty file")
    if "\x00" in text:
        line = text.count("\n", 0, text.index("\x00")) + 1
        raise FileError(path, f"line {line}", what, "a NUL byte (a binary file)")


def number_text(value: Any) -> str:
    """A number as text that reads back to the same float: whole floats without ``.0``."""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float) and math.isfinite(value) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    return repr(value) if isinstance(value, float) else str(value)


def typed_changes(path: str | Path, engine: str, changes: Any) -> dict[str, Any]:
    """``changes`` (engine keys to values) typed and range-checked by the profile (ValueError naming the key)."""
    if not isinstance(changes, Mapping) or not all(isinstance(k, str) for k in changes):
        raise ValueError(f"changes must be a mapping of {engine} setting names to values, got {changes!r:.80}")
    profile = get(engine)
    return {key: profile.setting(key).coerce(value) for key, value in changes.items()}


def splice(lines: list[str], line: int, start: int, end: int, new: str) -> None:
    """Replace columns ``[start, end)`` of 1-based ``line`` in ``lines`` (each with its line ending) by ``new``."""
    old = lines[line - 1]
    lines[line - 1] = old[:start] + new + old[end:]
