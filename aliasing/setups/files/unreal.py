"""Unreal Engine 5: the ``r.Shadow.*`` console variables of ``Config/DefaultEngine.ini``.

The format (Epic's *Configuration Files* page; ``FConfigFile::ProcessInputFileContents`` in
``Engine/Source/Runtime/Core/Private/Misc/ConfigCacheIni.cpp``, copies in the index): ``[Section]``
lines, then ``Key=Value`` lines; a line starting with ``;`` is a comment and a line without ``=``
is ignored; a key may start with ``+`` (add if absent), ``.`` (add), ``-`` (remove that value) or
``!`` (remove the key), and ``~`` (a packaging mark, skipped); a section may be repeated (its lines
merge); section and key names are compared without case.  Which sections set console variables,
and how strongly (``UE::ConfigUtilities::ApplyCVarSettingsFromIni`` with ``EConsoleVariableFlags``):

* ``[/Script/Engine.RendererSettings]``: ``ECVF_SetByProjectSetting`` (the Project Settings' page);
* ``[SystemSettings]`` and ``[ConsoleVariables]``: ``ECVF_SetBySystemSettingsIni``, stronger (where
  both set a variable, the one later in the file is taken and a note says so: the engine's order
  between the two was not read).

A value of ``True``/``Yes``/``On`` is 1 and ``False``/``No``/``Off`` is 0
(``ConvertValueFromHumanFriendlyValue``, ``Misc/ConfigUtilities.cpp``).  The reader takes the
profile's console variables (:mod:`aliasing.setups.unreal`); other ``r.Shadow.*`` variables are
named in ``notes`` as not modelled.  The DirectionalLight's properties
(``DynamicShadowDistanceMovableLight``, ``CascadeDistributionExponent``, ``ShadowBias`` …) are
not ``config`` properties: they live in the level (a binary ``.umap``), not in the ini, and
come from ``--set``; so does the camera (Unreal's ``FieldOfView`` is horizontal [deg]).

Examples
--------
>>> from pathlib import Path
>>> found = read([(Path("DefaultEngine.ini"), "[SystemSettings]\\nr.Shadow.CSMDepthBias=5\\n")], None, None)
>>> found.settings, found.where["r.Shadow.CSMDepthBias"]
({'r.Shadow.CSMDepthBias': 5.0}, 'DefaultEngine.ini line 2 [SystemSettings]')
>>> print(patch(Path("DefaultEngine.ini"), "[SystemSettings]\\nr.Shadow.CSMDepthBias=5\\n", {"r.Shadow.CSMDepthBias": 2.5}, found), end="")
[SystemSettings]
r.Shadow.CSMDepthBias=2.5
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import get
from ._native import coerce, number_text, pairs, text_of, typed_changes
from .common import FileError, Found

ENGINE = "unreal"
TITLE = "Unreal Engine DefaultEngine.ini ([SystemSettings], [ConsoleVariables], [/Script/Engine.RendererSettings] r.Shadow.* cvars)"
SOURCE = ("Engine/Source/Runtime/Core/Private/Misc/ConfigCacheIni.cpp FConfigFile::ProcessInputFileContents and "
          "Misc/ConfigUtilities.cpp ApplyCVarSettingsFromIni, ConvertValueFromHumanFriendlyValue (copies in the index; "
          "Epic's repository is private); Epic's documentation page 'Configuration Files'")

#: Sections that set console variables, and their strength (ECVF_SetBy…: higher wins).
SECTIONS = {"/script/engine.renderersettings": 3, "systemsettings": 4, "consolevariables": 4}
#: The section a new console variable is written into.
NEW_SECTION = "SystemSettings"
HUMAN = {"true": "1", "yes": "1", "on": "1", "false": "0", "no": "0", "off": "0"}
_SECTION = re.compile(r"^\s*\[(.*)\]\s*$")


@dataclass
class _Entry:
    key: str          # as the profile spells it
    value: str        # the ini's text
    line: int         # 1-based
    section: str      # as the file spells it
    strength: int


def sniff(path: Path, text: str) -> bool:
    """An ``.ini`` file, or any text with one of the console-variable sections."""
    if path.suffix.lower() == ".ini":
        return True
    return any(m and m.group(1).strip().lower() in SECTIONS for m in map(_SECTION.match, text.splitlines()[:5000]))


def _cvars() -> dict[str, str]:
    """The profile's console variables, by lower-case name."""
    return {s.key.lower(): s.key for s in get(ENGINE).settings if s.key.startswith("r.")}


def _parse(path: Path, text: str) -> tuple[dict[str, list[_Entry]], list[str], list[tuple[str, int]]]:
    """(entries by profile key in file order of effect, notes, sections as (name, header line))."""
    text_of(path, text, "an Unreal .ini ([Section] lines and Key=Value lines)")
    cvars = _cvars()
    values: dict[tuple[str, str], list[_Entry]] = {}
    notes: list[str] = []
    sections: list[tuple[str, int]] = []
    section: str | None = None
    for n, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        m = _SECTION.match(raw)
        if m:
            section = m.group(1).strip()
            sections.append((section, n))
            continue
        if not line or line.startswith(";") or section is None:
            continue
        if "=" not in line:
            if section.lower() in SECTIONS:
                notes.append(f"line {n} [{section}] has no '=': ignored, as Unreal ignores it ({line[:40]!r})")
            continue
        strength = SECTIONS.get(section.lower())
        key, _, value = line.partition("=")
        key = key.strip().lstrip("~")
        cmd = key[:1] if key[:1] in "+-.!" else ""
        key = key[len(cmd):].strip()
        value = value.strip()
        if len(value) >= 2 and value[0] == value[-1] == '"':
            value = value[1:-1]
        name = cvars.get(key.lower())
        if name is None:
            if strength and key.lower().startswith("r.shadow."):
                notes.append(f"{key} (line {n} [{section}]): read, not modelled (the profile has no such setting)")
            continue
        if strength is None:
            notes.append(f"{key} (line {n}) is in [{section}], which sets no console variables: ignored")
            continue
        slot = values.setdefault((section.lower(), name), [])
        entry = _Entry(name, value, n, section, strength)
        if cmd == "!":
            slot.clear()
        elif cmd == "-":
            slot[:] = [e for e in slot if e.value != value]
        elif cmd == "+":
            if all(e.value != value for e in slot):
                slot.append(entry)
        elif cmd == ".":
            slot.append(entry)
        else:
            slot[:] = [entry]
    by_key: dict[str, list[_Entry]] = {}
    for (_, name), slot in values.items():
        if slot:
            by_key.setdefault(name, []).append(slot[-1])
    for name, entries in by_key.items():
        entries.sort(key=lambda e: (e.strength, e.line))
        top = [e for e in entries if e.strength == entries[-1].strength]
        if len({e.section.lower() for e in top}) > 1 and len({e.value for e in top}) > 1:
            notes.append(f"{name} is set in both [{top[0].section}] (line {top[0].line}) and [{top[-1].section}] (line {top[-1].line}) "
                         f"with different values: line {top[-1].line} taken (the engine's order between the two was not read)")
    return by_key, notes, sections


def _value(path: Path, e: _Entry) -> Any:
    text = HUMAN.get(e.value.strip().lower(), e.value)
    return coerce(path, e.line, ENGINE, e.key, text)


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The console variables of one or more ``.ini`` files (later files override earlier ones, as
    Unreal's hierarchy does for ``DefaultEngine.ini`` over ``BaseEngine.ini``).

    ``files``: (path, text) pairs; ``light`` and ``camera`` are refused (the ini holds no lights or
    cameras).  Returns the console variables in the profile's types, where each was set, and notes.
    A damaged or foreign file raises :class:`~aliasing.setups.files.common.FileError` (file, line, key).
    """
    files = pairs(files, light, camera)
    for name, value in (("light", light), ("camera", camera)):
        if value is not None:
            raise ValueError(f"{name} {value!r}: DefaultEngine.ini holds no lights or cameras (the level does); "
                             "give the light's properties with --set and the camera with --camera")
    settings: dict[str, Any] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    for path, text in files:
        by_key, more, sections = _parse(path, text)
        if not sections:
            raise FileError(path, "the whole file", "an Unreal .ini with [Section] lines", "no section")
        notes += more
        for key, entries in by_key.items():
            e = entries[-1]
            settings[key] = _value(path, e)
            where[key] = f"{path.name} line {e.line} [{e.section}]"
    notes += ["distances are Unreal's centimetres (r.Shadow.* and the light's DynamicShadowDistanceMovableLight [cm])",
              "the camera is not in the ini: give it with --camera in centimetres; Unreal's FieldOfView is HORIZONTAL [deg], "
              "the toolkit's fov is vertical (2·atan(tan(h/2)/aspect))",
              "the DirectionalLight's properties (DynamicShadowDistanceMovableLight, DynamicShadowCascades, CascadeDistributionExponent, "
              "ShadowBias, ShadowSlopeBias …) are in the level, not the ini: give them with --set"]
    return Found(ENGINE, settings, None, None, None, None, where, tuple(notes))


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with each changed console variable's value rewritten on the line that sets it (the
    strongest section's), or a new line at the end of the last ``[SystemSettings]`` section (one
    added at the end of the file where there is none).

    The reader interface (:mod:`aliasing.setups.files.common`): ``changes`` are profile keys to values,
    typed and range-checked by the profile (ValueError naming the key); ``found`` is what :func:`read`
    found in ``text``.  Reading the result back gives ``changes`` exactly.
    """
    new = typed_changes(path, ENGINE, changes)  # unknown keys: a did-you-mean
    cvars = set(_cvars().values())
    for key in new:
        if key not in cvars:
            raise ValueError(f"{key} is a property of the DirectionalLight (in the level), not a console variable of "
                             f"{path.name}: set it in the editor or give it with --set")
    by_key, _, sections = _parse(path, text)
    lines = text.splitlines(keepends=True)
    eol = "\r\n" if "\r\n" in text else "\n"
    added: list[str] = []
    for key, value in new.items():
        written = number_text(value)
        if key in by_key:
            e = by_key[key][-1]
            raw = lines[e.line - 1]
            body = raw.rstrip("\r\n")
            head, _, rest = body.partition("=")
            quoted = rest.strip().startswith('"') and rest.strip().endswith('"') and len(rest.strip()) >= 2
            lead = rest[: len(rest) - len(rest.lstrip())]
            shown = f'"{written}"' if quoted else written
            lines[e.line - 1] = f"{head}={lead}{shown}" + raw[len(body):]
        else:
            added.append(f"{key}={written}")
    if added:
        blocks = [n for name, n in sections if name.lower() == NEW_SECTION.lower()]
        if blocks:
            start = blocks[-1]
            nxt = min([n for _, n in sections if n > start], default=len(lines) + 1)
            at = start
            for i in range(start, nxt - 1):
                if lines[i].strip():
                    at = i + 1
            if at == len(lines) and lines and not lines[-1].endswith(("\n", "\r")):
                lines[-1] += eol
            lines[at:at] = [a + eol for a in added]
        else:
            if lines and not lines[-1].endswith(("\n", "\r")):
                lines[-1] += eol
            lines += ([eol] if lines else []) + [f"[{NEW_SECTION}]{eol}"] + [a + eol for a in added]
    return "".join(lines)
