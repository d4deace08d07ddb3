"""The subset of YAML that Unity writes in its text-serialized assets and scenes, read line by line.

Unity's manual, *Format of Text Serialized files* (and *YAML Class ID Reference*): a file starts
with ``%YAML 1.1`` and ``%TAG !u! tag:unity3d.com,2011:``; each object is a document
``--- !u!CLASSID &FILEID`` (``stripped`` after it for a prefab's stand-in) whose one top-level key
is the class (``MonoBehaviour:``, ``Light:``, ``Camera:``, ``Transform:``, ``GameObject:``) and
whose fields follow, two spaces deeper: ``key: value`` (keys may hold spaces: ``field of view``),
nested blocks, sequences written ``- item`` at the key's own indent, and flow mappings on one
line (``{x: 0.1, y: 0.3}``, ``{fileID: 0}``).  A long plain string may run on over deeper lines.
Every scalar keeps its line and columns, so that a patch can rewrite that value alone.

Examples
--------
>>> docs = parse("a.asset", "%YAML 1.1\\n--- !u!114 &1\\nMonoBehaviour:\\n  m_Cascade3Split: {x: 0.1, y: 0.3}\\n")
>>> d = docs[0]
>>> d.class_id, d.kind, d.fields["m_Cascade3Split"]["y"].text, d.fields["m_Cascade3Split"]["y"].line
(114, 'MonoBehaviour', '0.3', 4)
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Union

from .common import FileError

WHAT = "Unity's text serialization (YAML: %YAML 1.1, --- !u!CLASS &ID documents, KEY: VALUE lines)"
_HEADER = re.compile(r"^--- !u!(\d+) &(-?\d+)( stripped)?\s*$")


@dataclass
class Scalar:
    """A value as written: its text (quotes removed), 1-based line and columns [start, end) of the raw text."""

    text: str
    line: int
    start: int
    end: int
    multiline: bool = False


Node = Union[Scalar, dict, list]


@dataclass
class Document:
    """One object: class id (114 MonoBehaviour, 108 Light, 20 Camera, 4 Transform, 1 GameObject), file id, class name, fields."""

    class_id: int
    file_id: str
    kind: str
    line: int
    fields: dict = field(default_factory=dict)


def _bad(path: str | Path, n: int, raw: str, expected: str = "KEY: VALUE at this depth (Unity's YAML)") -> FileError:
    shown = raw.strip()
    return FileError(path, f"line {n}", expected, repr(shown[:60] + ("…" if len(shown) > 60 else "")))


def _key(body: str) -> tuple[str, str, int] | None:
    """(key, value text, column of the value in ``body``) of ``key: value`` / ``key:``, or None."""
    k = body.find(": ")
    if k < 0:
        if not body.endswith(":"):
            return None
        k = len(body) - 1
    key = body[:k]
    if not key or key != key.strip() or any(c in key for c in "{}[],#") or key[0] in "'\"&*!|>%@`-":
        return None
    value_at = k + 1
    while value_at < len(body) and body[value_at] == " ":
        value_at += 1
    return key, body[value_at:].rstrip(), value_at


def _flow(path: str | Path, n: int, raw: str, text: str, col: int) -> dict:
    """``{k: v, k: v}`` on line ``n`` at column ``col`` as a dict of :class:`Scalar` (nested braces kept as text)."""
    if not text.endswith("}"):
        raise _bad(path, n, raw, "a flow mapping {KEY: VALUE, …} closed on its line")
    out: dict = {}
    depth, i, start = 0, 1, 1
    inner = len(text) - 1
    parts = []
    while i <= inner:
        c = text[i] if i < inner else ","
        if c in "{[":
            depth += 1
        elif c in "}]":
            depth -= 1
            if depth < 0:
                raise _bad(path, n, raw, "balanced braces in a flow mapping")
        elif c == "," and depth == 0:
            parts.append((start, i))
            start = i + 1
        i += 1
    if depth != 0:
        raise _bad(path, n, raw, "balanced braces in a flow mapping")
    if len(parts) == 1 and not text[1:inner].strip():
        return out
    for a, b in parts:
        piece = text[a:b]
        lead = len(piece) - len(piece.lstrip())
        kv = _key(piece.strip())
        if kv is None:
            raise _bad(path, n, raw, "KEY: VALUE pairs in a flow mapping")
        key, value, at = kv
        s = col + a + lead + at
        out[key] = _scalar(path, n, raw, value, s)
    return out


def _scalar(path: str | Path, n: int, raw: str, value: str, col: int) -> Node:
    if value.startswith("{"):
        return _flow(path, n, raw, value, col)
    text, multiline = value, False
    if value[:1] in "'\"":
        q = value[0]
        if len(value) >= 2 and value.endswith(q):
            text = value[1:-1].replace("''", "'") if q == "'" else value[1:-1]
        else:
            text, multiline = value[1:], True
    return Scalar(text, n, col, col + len(value), multiline)


def _skip(rows: list[tuple[int, str]], i: int) -> tuple[int, int, str, int, str]:
    """(index, line, raw, indent, body) of the first non-blank row from ``i`` (index len(rows) and indent −1 at the end)."""
    while i < len(rows) and not rows[i][1].strip():
        i += 1
    if i == len(rows):
        return i, 0, "", -1, ""
    n, raw = rows[i]
    ind = len(raw) - len(raw.lstrip(" "))
    return i, n, raw, ind, raw[ind:]


def _block(path: str | Path, rows: list[tuple[int, str]], i: int, indent: int) -> tuple[dict, int]:
    out: dict = {}
    while True:
        i, n, raw, ind, body = _skip(rows, i)
        if ind < indent:
            break
        if ind > indent or body.startswith("- ") or body == "-":
            if ind == indent:
                break  # a sequence at the parent key's indent
            raise _bad(path, n, raw)
        kv = _key(body)
        if kv is None:
            raise _bad(path, n, raw)
        key, value, at = kv
        i += 1
        if value:
            node = _scalar(path, n, raw, value, ind + at)
            while True:  # a plain or quoted string running on over deeper lines (blank lines within)
                j, jn, jraw, jind, _ = _skip(rows, i)
                if jind <= indent:
                    break
                if not isinstance(node, Scalar):
                    raise _bad(path, jn, jraw)
                node.multiline = True
                i = j + 1
        else:
            j, _, _, nxt, nbody = _skip(rows, i)
            if nxt >= indent and (nbody.startswith("- ") or nbody == "-"):
                node, i = _seq(path, rows, j, nxt)
            elif nxt > indent:
                node, i = _block(path, rows, j, nxt)
            else:
                node = Scalar("", n, len(raw), len(raw))
        if key in out:
            raise _bad(path, n, raw, f"one {key!r} per object (a duplicate key)")
        out[key] = node
    return out, i


def _seq(path: str | Path, rows: list[tuple[int, str]], i: int, indent: int) -> tuple[list, int]:
    out: list = []
    while True:
        i, n, raw, ind, body = _skip(rows, i)
        if ind < 0:
            break
        if ind != indent or not (body.startswith("- ") or body == "-"):
            if ind > indent:
                raise _bad(path, n, raw, "- ITEM at the sequence's indent")
            break
        item = body[2:]
        if _key(item) is not None and not item.startswith("{"):
            rows[i] = (n, raw[:ind] + "  " + item)  # the item's first key, two deeper: a mapping item
            node, i = _block(path, rows, i, indent + 2)
        else:
            node = _scalar(path, n, raw, item.rstrip(), ind + 2) if item.strip() else Scalar("", n, len(raw), len(raw))
            i += 1
        out.append(node)
    return out, i


def parse(path: str | Path, text: str) -> list[Document]:
    """The documents of a Unity text-serialized file; a :class:`FileError` naming the line that breaks the subset."""
    lines = text.splitlines()
    docs: list[Document] = []
    i = 0
    while i < len(lines) and not lines[i].startswith("---"):
        s = lines[i].strip()
        if s and not s.startswith("%"):
            raise _bad(path, i + 1, lines[i], "%YAML/%TAG directives, then --- !u!CLASS &ID")
        i += 1
    while i < len(lines):
        m = _HEADER.match(lines[i])
        if not m:
            raise _bad(path, i + 1, lines[i], "--- !u!CLASS &ID (a document header)")
        head = i + 1
        j = i + 1
        while j < len(lines) and not lines[j].startswith("---"):
            j += 1
        rows = [(k + 1, lines[k].rstrip("\r")) for k in range(i + 1, j)]
        body = [r for r in rows if r[1].strip()]
        if not body:
            raise _bad(path, head, lines[i], "a class name (MonoBehaviour:, Light: …) after the document header")
        top, k = _block(path, rows, 0, 0)
        if k != len(rows):
            raise _bad(path, rows[k][0], rows[k][1])
        if len(top) != 1 or not isinstance(next(iter(top.values())), dict):
            raise _bad(path, body[0][0], body[0][1], "one class name (MonoBehaviour:, Light: …) with its fields below it")
        kind, fields = next(iter(top.items()))
        docs.append(Document(int(m.group(1)), m.group(2), kind, head, fields))
        i = j
    return docs


def scalar(node: Node | None) -> Scalar | None:
    """``node`` where it is a one-line :class:`Scalar`, else None."""
    return node if isinstance(node, Scalar) and not node.multiline else None


def ref(node: Node | None) -> str | None:
    """The ``fileID`` of ``{fileID: N}`` (None for 0 or absent)."""
    if isinstance(node, dict) and isinstance(node.get("fileID"), Scalar):
        v = node["fileID"].text
        return None if v in ("0", "") else v
    return None
