"""JSON project files read with line numbers in their errors and patched in place, value by value.

:func:`locate` finds the characters of one value by its path (keys and indices), :func:`put` rewrites
that value (or inserts the key into its object) and leaves every other character as it was: key
order, indentation and the other numbers' spellings stay byte for byte.  Numbers are written as
Python's ``repr`` (the shortest text that reads back to the same double).

Examples
--------
>>> text = '{\\n  "a": {"b": 1, "c": [1, 2]},\\n  "d": true\\n}'
>>> print(put(text, ("a", "c", 1), 0.25))
{
  "a": {"b": 1, "c": [1, 0.25]},
  "d": true
}
>>> print(put(text, ("a", "e"), False))
{
  "a": {"e": false, "b": 1, "c": [1, 2]},
  "d": true
}
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .common import FileError

_WS = re.compile(r"[ \t\n\r]*")
_DECODER = json.JSONDecoder()


def load(path: str | Path, text: str) -> Any:
    """``text`` parsed as JSON, else a :class:`FileError` naming the line and column.

    Examples
    --------
    >>> load("a.json", '{"a": [1,')
    Traceback (most recent call last):
    ...
    aliasing.setups.files.common.FileError: a.json: line 1 column 10: expected valid JSON, got expecting value
    """
    if not text.strip():
        raise FileError(path, "line 1", "JSON text", "an empty file")
    try:
        return json.loads(text, parse_constant=lambda name: _refuse(path, name))
    except json.JSONDecodeError as exc:
        raise FileError(path, f"line {exc.lineno} column {exc.colno}", "valid JSON", exc.msg.lower()) from None
    except RecursionError:
        raise FileError(path, "line 1", "JSON nested at most a few hundred levels deep", "deeper nesting") from None


def _refuse(path: str | Path, name: str) -> None:
    raise FileError(path, name, "a finite number (JSON has no NaN or Infinity)", name)


def _skip(text: str, i: int) -> int:
    return _WS.match(text, i).end()


def _end(text: str, i: int) -> int:
    """The index just past the JSON value starting at ``i``."""
    return _DECODER.raw_decode(text, i)[1]


def locate(text: str, path: Sequence[str | int]) -> tuple[int, int]:
    """(start, end) of the value at ``path`` in ``text``; KeyError where the path is not there.

    Examples
    --------
    >>> locate('{"a": [10, 20]}', ("a", 1))
    (11, 13)
    """
    i = _skip(text, 0)
    for step in path:
        if isinstance(step, str):
            if text[i] != "{":
                raise KeyError(step)
            i = _skip(text, i + 1)
            while text[i] != "}":
                key, i = json.decoder.scanstring(text, i + 1)
                i = _skip(text, _skip(text, i) + 1)  # past ':'
                if key == step:
                    break
                i = _skip(text, _end(text, i))
                if text[i] == ",":
                    i = _skip(text, i + 1)
            else:
                raise KeyError(step)
        else:
            if text[i] != "[":
                raise KeyError(step)
            i = _skip(text, i + 1)
            for _ in range(step):
                if text[i] == "]":
                    raise KeyError(step)
                i = _skip(text, _end(text, i))
                if text[i] == ",":
                    i = _skip(text, i + 1)
            if text[i] == "]":
                raise KeyError(step)
    return i, _end(text, i)


def dumps(value: Any) -> str:
    """``value`` as JSON text: numbers repr-exact, finite only.

    Examples
    --------
    >>> dumps(0.1 + 0.2)
    '0.30000000000000004'
    """
    return json.dumps(value, allow_nan=False)


def put(text: str, path: Sequence[str | int], value: Any) -> str:
    """``text`` with the value at ``path`` set to ``value``; a missing last key is inserted first in its object."""
    try:
        a, b = locate(text, path)
        return text[:a] + dumps(value) + text[b:]
    except KeyError:
        if not path or not isinstance(path[-1], str):
            raise
    a, b = locate(text, path[:-1])
    if text[a] != "{":
        raise KeyError(path[-1])
    inner = _skip(text, a + 1)
    gap = text[a + 1:inner]
    member = f"{dumps(path[-1])}: {dumps(value)}"
    if text[inner] == "}":
        return text[:a + 1] + member + text[a + 1:]
    return text[:inner] + member + "," + (gap if gap else " ") + text[inner:]
