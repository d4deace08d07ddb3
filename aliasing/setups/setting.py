"""One shadow setting of an engine (:class:`Setting`: key, unit, default, range, spellings, source) and the
other spellings of its named values: what :meth:`Setting.coerce` takes.

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
>>> s = Setting("filteringQuality", "QUALITY_HIGH", "", "choice", ("QUALITY_HIGH", "QUALITY_LOW"), aliases={0: "QUALITY_HIGH", 2: "QUALITY_LOW"})
>>> [s.coerce(v) for v in ("high", 0, "ShadowGenerator.QUALITY_LOW", "2", "quality low")]
['QUALITY_HIGH', 'QUALITY_HIGH', 'QUALITY_LOW', 'QUALITY_LOW', 'QUALITY_LOW']
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

import numpy as np

from .. import _validation as check

__all__ = ["FLOAT32_MAX", "TYPES", "Setting", "float32"]

TYPES = ("float", "int", "bool", "choice")
#: What a lookup returns where a text spells no value.
_MISSING = object()


def _numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _lookup(table: Mapping, value: object, numbers: bool = True) -> Any:
    """The value that ``value`` spells in ``table`` (``_spellings``), or ``_MISSING``: an
    integer (as int or text, where ``numbers``), a name without case, or the name after a qualifier
    (``ShadowGenerator.QUALITY_HIGH``)."""
    if not table:
        return _MISSING
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
        return table.get(int(value), _MISSING) if numbers else _MISSING
    if not isinstance(value, str):
        return _MISSING
    text = _normal(value)
    if text.lstrip("+-").isdigit():
        return table.get(int(text), _MISSING) if numbers else _MISSING
    for candidate in (text, text.rpartition(".")[2]):
        if candidate in table:
            return table[candidate]
    return _MISSING


def _hint(value: object, choices: Iterable, table: Mapping) -> str:
    """A did-you-mean for a misspelt ``value`` from the ``choices``, else from the other spellings in ``table``."""
    if not isinstance(value, str):
        return ""
    return check.did_you_mean(value, map(str, choices)) or check.did_you_mean(_normal(value), [k for k in table if isinstance(k, str)])


def _normal(text: str) -> str:
    """A spelling as :meth:`Setting.names` keys it: lower case, spaces and hyphens as underscores, a
    trailing parenthesis dropped (Godot's editor writes ``Soft Low (Fast)``)."""
    text = re.sub(r"\s*\([^)]*\)\s*$", "", text.strip()).replace("::", ".")
    return re.sub(r"[\s-]+", "_", text).lower()


def _affixes(names: list[str]) -> tuple[int, int]:
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


def _spellings(setting: Any) -> dict:
    """The table behind :meth:`Setting.names`: the choices, their short forms and the aliases;
    a short form two choices share is left out (ambiguous)."""
    out: dict = {}
    clash: set = set()

    def put(key: Any, value: Any) -> None:
        if key in out and out[key] != value:
            clash.add(key)
        out[key] = value

    if setting.kind == "choice":
        names = [str(c) for c in setting.accepts if str(c).lower() != "null"]
        a, b = _affixes(names)
        for c in setting.accepts:
            text = str(c)
            if text.lower() != "null" and (a or b):
                put(_normal(text[a: len(text) - b].strip("_")), c)
    for key, value in setting.aliases:
        if isinstance(key, bool) or not isinstance(key, (str, int)):
            raise ValueError(f"{setting.key}: an alias must be a name or an integer, got {key!r}")
        if setting.kind == "choice" and value not in setting.accepts:
            raise ValueError(f"{setting.key}: the alias {key!r} names {value!r}, not one of {setting.accepts!r}")
        put(_normal(key) if isinstance(key, str) else key, value)
    for key in clash:
        del out[key]
    if setting.default is None:  # null and none are the engine's derived default there (Babylon's filter: not FILTER_NONE)
        out.pop("null", None)
        out.pop("none", None)
    if setting.kind == "choice":
        for c in setting.accepts:  # the full names win over any short form
            out[_normal(str(c))] = c
    return out


#: The largest 32-bit float (FLT_MAX): the bound of a setting the engine keeps in a C++ ``float`` or a Rust ``f32``.
FLOAT32_MAX = float(np.finfo(np.float32).max)


def float32(settings: tuple) -> tuple:
    """``settings`` with each open end of a ``float`` setting's ``accepts`` at ±:data:`FLOAT32_MAX`: for an
    engine that keeps them in 32-bit floats (Bevy's ``f32`` fields, Filament's and Unreal's ``float``), so
    that a value it cannot hold (1.7e308) is refused rather than carried into an overflow.

    Example
    -------
    >>> float32((Setting("bias", 0.0, "m", "float"),))[0].allowed()
    'a number in [-3.40282e+38, 3.40282e+38] (a 32-bit float)'
    """
    if not isinstance(settings, (tuple, list)) or not all(isinstance(s, Setting) for s in settings):
        raise ValueError(f"settings must be a tuple of Setting, got {type(settings).__name__}")
    out = []
    for s in settings:
        lo, hi = s.accepts if s.kind == "float" else (0, 0)
        out.append(s if s.kind != "float" else replace(s, accepts=(-FLOAT32_MAX if lo is None else lo, FLOAT32_MAX if hi is None else hi)))
    return tuple(out)


@dataclass(frozen=True)
class Setting:
    """One shadow setting of an engine, as the engine spells it.

    Attributes
    ----------
    key : str
        The engine's own name (``shadowBias``, ``shadow.normalBias``, ``lambda``).
    default : float, int, bool, str or None
        The engine's default at the profile's release; None where the engine derives it from
        something else (Babylon's ``shadowMaxZ`` is the camera's ``maxZ``: ``doc`` says what).
    unit : str
        What one unit means (``world units``, ``normalized light depth``, ``texels``, ``m``, ``""``).
    kind : str
        ``float``, ``int``, ``bool`` or ``choice``.
    accepts : tuple
        ``(low, high)``: the values the engine accepts (inclusive; ``None`` for open), or, for
        ``choice``, the choices.
    clamp : tuple or None
        ``(low, high)`` the engine clamps an accepted value to, silently (Babylon clamps
        ``numCascades`` to 2–4), or None.
    source : str
        The file and line it was read from, at the pinned release.
    doc : str
        What the setting does, in a line.
    aliases : mapping or pairs of (str or int, value)
        Other spellings of a ``choice`` (or of an ``int`` the engine names) mapped to the canonical
        value: the integers the engine's files store and its other names (cite their declaration in
        ``source``); the module docstring says what else :meth:`coerce` takes.
    """

    key: str
    default: Any
    unit: str
    kind: str
    accepts: tuple = (None, None)
    clamp: tuple | None = None
    source: str = ""
    doc: str = ""
    aliases: tuple = ()
    _names: Mapping = field(init=False, repr=False, compare=False, hash=False)

    def __post_init__(self) -> None:
        if self.kind not in TYPES:
            raise ValueError(f"kind must be one of {', '.join(TYPES)}, got {self.kind!r}")
        object.__setattr__(self, "aliases", tuple((k, v) for k, v in (self.aliases.items() if isinstance(self.aliases, Mapping) else self.aliases)))
        object.__setattr__(self, "_names", MappingProxyType(_spellings(self)))

    def names(self) -> dict:
        """Every spelling :meth:`coerce` takes for a ``choice`` or a named ``int``, normalized
        (lower case, underscores; integers as int), mapped to the canonical value.

        Example
        -------
        >>> s = Setting("q", "QUALITY_HIGH", "", "choice", ("QUALITY_HIGH", "QUALITY_LOW"), aliases={0: "QUALITY_HIGH", 2: "QUALITY_LOW"})
        >>> sorted((k for k, v in s.names().items() if v == "QUALITY_LOW"), key=str)
        [2, 'low', 'quality_low']
        """
        return dict(self._names)

    def allowed(self) -> str:
        """The values the engine accepts, in words (for error messages)."""
        if self.kind == "bool":
            return "true or false"
        if self.kind == "choice":
            return "one of " + ", ".join(map(repr, self.accepts))
        lo, hi = self.accepts
        what = "a whole number" if self.kind == "int" else "a number"
        if lo is None or hi is None:
            return what if lo is None and hi is None else f"{what} >= {lo:g}" if hi is None else f"{what} <= {hi:g}"
        return f"{what} in [{lo:g}, {hi:g}]" + (" (a 32-bit float)" if FLOAT32_MAX in (-lo, hi) else "")

    def coerce(self, value: object) -> Any:
        """``value`` (from JSON, TOML or a ``--set`` text) as this setting's type, validated.

        Raises
        ------
        ValueError
            Naming the key and what it accepts.
        """
        bad = ValueError(f"{self.key} must be {self.allowed()}" + (f" [{self.unit}]" if self.unit else "")
                         + (" or null (the engine's derived default)" if self.default is None else "") + f", got {value!r}")
        if self.default is None and (value is None or isinstance(value, str) and value.strip().lower() in ("null", "none")):
            return None  # the engine's derived default (JSON null, --set KEY=null)
        named = _lookup(self._names, value, numbers=self.kind == "choice")
        if named is not _MISSING:
            return named if self.kind == "choice" else self.coerce(named)
        if isinstance(value, str) and self.kind != "choice":
            text = value.strip()
            if self._names and not _numeric(text):
                names = ", ".join(repr(k) for k, _ in self.aliases if isinstance(k, str))
                raise ValueError(f"{self.key} must be {self.allowed()} or one of the engine's names ({names}), got {value!r}{_hint(value, (), self._names)}")
            if self.kind == "bool":
                if text.lower() not in ("true", "false"):
                    raise bad
                return text.lower() == "true"
            try:
                value = int(text) if self.kind == "int" and text.lstrip("+-").isdigit() else float(text)
            except ValueError:
                raise bad from None
        if self.kind == "bool":
            if not isinstance(value, (bool, np.bool_)):
                raise bad
            return bool(value)
        if self.kind == "choice":
            numbers = ", ".join(str(k) for k in sorted(k for k in self._names if isinstance(k, int)))
            raise ValueError(f"{self.key} must be {self.allowed()}" + (f" (or the engine's numbers {numbers})" if numbers else "")
                             + (" or null (the engine's derived default)" if self.default is None else "")
                             + f", got {value!r}{_hint(value, self.accepts, self._names)}")
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise bad
        number = float(value)
        if not math.isfinite(number):
            raise bad
        if self.kind == "int":
            if not number.is_integer():
                raise bad
            number = int(number)
        lo, hi = self.accepts
        if lo is not None and number < lo or hi is not None and number > hi:
            raise bad
        return number

    def clamped(self, value: Any) -> Any:
        """The value as the engine uses it, after its own clamp."""
        if self.clamp is None:
            return value
        lo, hi = self.clamp
        out = value if lo is None else max(lo, value)
        return out if hi is None else min(hi, out)
