"""The other spellings of an engine's named values: what :meth:`aliasing.setups.Setting.coerce` takes.

Engines spell one enumerated value several ways: the constant (``ShadowGenerator.QUALITY_HIGH``,
``THREE.PCFShadowMap``, ``DirectionalLight3D.SHADOW_PARALLEL_4_SPLITS``), its short form in the
docs (``high``, ``PCF``, ``PARALLEL_4_SPLITS``), the editor's label (Godot's ``Soft Low (Fast)``)
and the integer its files store (``directional_shadow_mode = 2``).  A setting lists the integers
and other names (``aliases``, from the engine's declarations); besides these, a choice is taken
without case, with spaces or hyphens for underscores, behind a qualifier (``THREE.PCFShadowMap``,
``ShadowGenerator.QUALITY_HIGH``, ``View::ShadowType::VSM``) and without the prefix or suffix all
the choices share at a word's edge (``high`` for ``QUALITY_HIGH``, ``PCF`` for ``PCFShadowMap``).
A short form that two choices share is left out; the output keeps the canonical spelling.

Example
-------
>>> normal("DirectionalLight3D::SHADOW_PARALLEL_4_SPLITS"), normal("Soft Low (Fast)")
('directionallight3d.shadow_parallel_4_splits', 'soft_low')
>>> affixes(["QUALITY_HIGH", "QUALITY_LOW"]), affixes(["BasicShadowMap", "PCFShadowMap"])
((8, 0), (0, 9))
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from .._validation import did_you_mean

#: What a lookup returns where a text spells no value.
MISSING = object()


def numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def lookup(table: Mapping, value: object, numbers: bool = True) -> Any:
    """The value that ``value`` spells in ``table`` (:func:`spellings`), or :data:`MISSING`: an
    integer (as int or text, where ``numbers``), a name without case, or the name after a qualifier
    (``ShadowGenerator.QUALITY_HIGH``)."""
    if not table:
        return MISSING
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
        return table.get(int(value), MISSING) if numbers else MISSING
    if not isinstance(value, str):
        return MISSING
    text = normal(value)
    if text.lstrip("+-").isdigit():
        return table.get(int(text), MISSING) if numbers else MISSING
    for candidate in (text, text.rpartition(".")[2]):
        if candidate in table:
            return table[candidate]
    return MISSING


def hint(value: object, choices: Iterable, table: Mapping) -> str:
    """A did-you-mean for a misspelt ``value`` from the ``choices``, else from the other spellings in ``table``."""
    if not isinstance(value, str):
        return ""
    return did_you_mean(value, map(str, choices)) or did_you_mean(normal(value), [k for k in table if isinstance(k, str)])


def normal(text: str) -> str:
    """A spelling as :meth:`aliasing.setups.Setting.names` keys it: lower case, spaces and hyphens as underscores, a
    trailing parenthesis dropped (Godot's editor writes ``Soft Low (Fast)``)."""
    text = re.sub(r"\s*\([^)]*\)\s*$", "", text.strip()).replace("::", ".")
    return re.sub(r"[\s-]+", "_", text).lower()


def affixes(names: list[str]) -> tuple[int, int]:
    """The length of the prefix and of the suffix that all ``names`` share, cut at a word's edge
    (after an underscore; before an underscore or a capitalized word), 0 where none or where a name
    would be left empty."""
    if len(names) < 2:
        return 0, 0
    pre = os.path.commonprefix(names)
    pre = pre[: pre.rfind("_") + 1] if "_" in pre else ""
    rev = os.path.commonprefix([n[::-1] for n in names])[::-1]
    suf = ""
    for i in range(len(rev)):
        tail = rev[i:]
        if tail.startswith("_") or len(tail) > 1 and tail[0].isupper() and tail[1].islower():
            suf = tail
            break
    if any(len(n) <= len(pre) + len(suf) for n in names):
        return (len(pre), 0) if all(len(n) > len(pre) for n in names) else (0, 0)
    return len(pre), len(suf)


def spellings(setting: Any) -> dict:
    """The table behind :meth:`aliasing.setups.Setting.names`: the choices, their short forms and the aliases;
    a short form two choices share is left out (ambiguous)."""
    out: dict = {}
    clash: set = set()

    def put(key: Any, value: Any) -> None:
        if key in out and out[key] != value:
            clash.add(key)
        out[key] = value

    if setting.kind == "choice":
        names = [str(c) for c in setting.accepts if str(c).lower() != "null"]
        a, b = affixes(names)
        for c in setting.accepts:
            text = str(c)
            if text.lower() != "null" and (a or b):
                put(normal(text[a: len(text) - b].strip("_")), c)
    for key, value in setting.aliases:
        if isinstance(key, bool) or not isinstance(key, (str, int)):
            raise ValueError(f"{setting.key}: an alias must be a name or an integer, got {key!r}")
        if setting.kind == "choice" and value not in setting.accepts:
            raise ValueError(f"{setting.key}: the alias {key!r} names {value!r}, not one of {setting.accepts!r}")
        put(normal(key) if isinstance(key, str) else key, value)
    for key in clash:
        del out[key]
    if setting.default is None:  # null and none are the engine's derived default there (Babylon's filter: not FILTER_NONE)
        out.pop("null", None)
        out.pop("none", None)
    if setting.kind == "choice":
        for c in setting.accepts:  # the full names win over any short form
            out[normal(str(c))] = c
    return out
