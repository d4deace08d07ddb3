"""Filament: the viewer's settings JSON (``JsonSerializer`` of ``libs/viewer``).

Read from google/filament as stored in the index (1.5x): ``libs/viewer/include/viewer/Settings.h``
(``Settings`` = ``view``, ``lighting``, ``viewer`` …) and ``libs/viewer/src/Settings.cpp`` /
``Settings_generated.cpp`` (the parsers: one JSON key per field, spelled as the field; a
``float3`` is an array of three numbers; an enum a string such as ``"PCF"``).  Two shapes:

* the 1.5x viewer: ``lighting.shadowOptions`` {``mapSize``, ``shadowCascades``,
  ``cascadeSplitPositions`` [3], ``constantBias``, ``normalBias``, ``shadowFar``,
  ``shadowNearHint``, ``shadowFarHint``, ``stable``, ``lispsm``, ``polygonOffsetConstant``,
  ``polygonOffsetSlope``, ``screenSpaceContactShadows``, ``stepCount``, ``maxShadowDistance``},
  ``lighting.sunlightDirection`` [3] (the direction the light travels, default (0.6, −1, −0.8)),
  ``viewer.cameraNear``/``cameraFar`` [m] and ``viewer.cameraFocalLength`` [mm];
* later viewers: ``lighting.sunlight`` {``direction``, ``shadowOptions``} and ``camera``
  {``near``, ``far``, ``focalLength`` [mm], ``horizontalFov`` [deg] (0: the focal length),
  ``center``, ``lookAt``, ``up``};

and ``view.shadowType`` (``PCF``, ``VSM``, ``DPCF``, ``PCSS``) in both.  Older viewers' parsers (a
stored ``Settings.cpp`` with ``// TODO: constantBias``) read only ``mapSize``, ``shadowCascades``,
``cascadeSplitPositions``, ``stable``, ``lispsm``, ``screenSpaceContactShadows`` and ``vsm`` and skip
the other options with a warning; the toolkit reads every option, as later viewers do.  The focal length is that
of a 35 mm camera: the frame is 24 mm high (``FCamera::projection``, ``filament/src/details/Camera.cpp``:
h = near/2 · 24 mm / focal length), so the vertical field of view is 2·atan(12 mm / focal length).
The settings are read in the profile's keys (:mod:`aliasing.setups.filament`), distances in metres.

Examples
--------
>>> from pathlib import Path
>>> text = '{"lighting": {"shadowOptions": {"mapSize": 2048, "cascadeSplitPositions": [0.1, 0.3, 0.6]}}}'
>>> found = read([(Path("settings.json"), text)], None, None)
>>> found.settings["mapSize"], found.settings["cascadeSplitPositions[1]"]
(2048, 0.3)
>>> patch(Path("settings.json"), text, {"mapSize": 4096}, found)
'{"lighting": {"shadowOptions": {"mapSize": 4096, "cascadeSplitPositions": [0.1, 0.3, 0.6]}}}'
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .. import get
from ._native import coerce, pairs, text_of, typed_changes
from .common import FileError, Found, sun_from_directions, vertical_fov

ENGINE = "filament"
TITLE = "Filament viewer settings JSON (lighting.shadowOptions, view.shadowType)"
SOURCE = ("google/filament libs/viewer/include/viewer/Settings.h (commit 000e151b: lighting.sunlight and camera; an earlier stored "
          "1.5x version: lighting.shadowOptions, lighting.sunlightDirection, viewer.camera*) and libs/viewer/src/Settings.cpp "
          "(commit 523a261b: the ShadowOptions parser, JsonSerializer::readJson); filament/src/details/Camera.cpp FCamera::projection")

#: The ShadowOptions fields the profile has, as the JSON spells them (the profile's key is the same).
OPTIONS = ("mapSize", "shadowCascades", "constantBias", "normalBias", "shadowFar", "shadowNearHint", "shadowFarHint", "stable", "lispsm",
           "polygonOffsetConstant", "polygonOffsetSlope", "screenSpaceContactShadows", "stepCount", "maxShadowDistance")
SPLITS = tuple(f"cascadeSplitPositions[{i}]" for i in range(3))
FRAME_HEIGHT_MM = 24.0  # FCamera::projection: SENSOR_SIZE 0.024 m, the 35 mm frame's height
_NUMBER = re.compile(r"-?(?:0|[1-9]\d*)(?:\.\d+)?(?:[eE][-+]?\d+)?")
_WS = re.compile(r"[ \t\n\r]*")


def sniff(path: Path, text: str) -> bool:
    """A JSON object with the viewer's ``lighting`` (with shadow options or the sun) or ``view.shadowType``."""
    if text.lstrip()[:1] != "{" or '"entities"' in text:  # a PlayCanvas scene has entities (and a shadowType per light)
        return False
    return '"lighting"' in text and ('"shadowOptions"' in text or '"sunlight' in text) or '"view"' in text and '"shadowType"' in text


def _spans(text: str) -> dict[tuple, tuple[int, int]]:
    """Each value's (start, end) offsets in ``text`` by its path (object keys and array indices).

    ``text`` is valid JSON (json.loads has read it), so the scan needs no error handling of its own.
    """
    out: dict[tuple, tuple[int, int]] = {}
    decode = json.decoder.scanstring

    def value(i: int, path: tuple) -> int:
        i = _WS.match(text, i).end()
        start = i
        c = text[i]
        if c == "{":
            i = _WS.match(text, i + 1).end()
            while text[i] != "}":
                key, i = decode(text, i + 1)
                i = _WS.match(text, i).end() + 1  # the colon
                i = _WS.match(text, value(i, path + (key,))).end()
                if text[i] == ",":
                    i = _WS.match(text, i + 1).end()
            i += 1
        elif c == "[":
            i = _WS.match(text, i + 1).end()
            k = 0
            while text[i] != "]":
                i = _WS.match(text, value(i, path + (k,))).end()
                k += 1
                if text[i] == ",":
                    i = _WS.match(text, i + 1).end()
            i += 1
        elif c == '"':
            i = decode(text, i + 1)[1]
        else:
            m = _NUMBER.match(text, i)
            i = m.end() if m and m.end() > i else i + next(len(w) for w in ("true", "false", "null") if text.startswith(w, i))
        out[path] = (start, i)
        return i

    value(0, ())
    return out


def _line(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1


def _load(path: Path, text: str) -> dict:
    text_of(path, text, "the Filament viewer's settings JSON")

    def constant(name: str) -> None:
        raise ValueError(name)

    try:
        data = json.loads(text, parse_constant=constant)
    except json.JSONDecodeError as err:
        raise FileError(path, f"line {err.lineno} column {err.colno}", "JSON", err.msg) from None
    except ValueError as err:
        raise FileError(path, "a number", "a finite JSON number", str(err)) from None
    except RecursionError:
        raise FileError(path, "the whole file", "JSON nested fewer than 1000 levels deep", "deeper nesting") from None
    if not isinstance(data, dict):
        raise FileError(path, "the whole file", "a JSON object (the viewer's Settings)", type(data).__name__)
    return data


def _at(data: Any, path: tuple) -> Any:
    for p in path:
        if not isinstance(data, dict) or p not in data:
            return None
        data = data[p]
    return data


def _shape(data: dict) -> str:
    """``old`` (lighting.shadowOptions, viewer.camera*) or ``new`` (lighting.sunlight, camera)."""
    return "new" if isinstance(_at(data, ("lighting", "sunlight")), dict) or isinstance(data.get("camera"), dict) else "old"


def _paths(shape: str) -> dict[str, tuple]:
    """Profile key -> the JSON path of its value, in ``shape``."""
    base = ("lighting", "sunlight", "shadowOptions") if shape == "new" else ("lighting", "shadowOptions")
    out = {k: base + (k,) for k in OPTIONS}
    out.update({k: base + ("cascadeSplitPositions", i) for i, k in enumerate(SPLITS)})
    out["View.shadowType"] = ("view", "shadowType")
    return out


def _name(path: tuple) -> str:
    return ".".join(str(p) if isinstance(p, str) else f"[{p}]" for p in path).replace(".[", "[")


def _vector(path: Path, data: dict, where: tuple, text: str, spans: dict) -> list[float] | None:
    v = _at(data, where)
    if v is None:
        return None
    ok = isinstance(v, list) and len(v) == 3 and all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v)
    if not ok or not any(v):
        line = _line(text, spans[where][0])
        raise FileError(path, f"line {line} / {_name(where)}", "an array of three finite numbers, not all zero", json.dumps(v)[:60])
    return [float(x) for x in v]


def _number(path: Path, data: dict, where: tuple, text: str, spans: dict, unit: str) -> float | None:
    v = _at(data, where)
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise FileError(path, f"line {_line(text, spans[where][0])} / {_name(where)}", f"a number [{unit}]", json.dumps(v)[:60])
    return float(v)


def _camera(path: Path, data: dict, shape: str, text: str, spans: dict, where: dict, notes: list) -> dict | None:
    keys = ({"near": ("camera", "near"), "far": ("camera", "far"), "focal": ("camera", "focalLength"), "hfov": ("camera", "horizontalFov")}
            if shape == "new" else
            {"near": ("viewer", "cameraNear"), "far": ("viewer", "cameraFar"), "focal": ("viewer", "cameraFocalLength"), "hfov": ()})
    got = {k: _number(path, data, p, text, spans, "deg" if k == "hfov" else "mm" if k == "focal" else "m") if p else None for k, p in keys.items()}
    camera: dict[str, Any] = {}
    for k in ("near", "far"):
        if got[k] is not None:
            camera[k] = got[k]
            where[f"camera.{k}"] = f"{path.name} line {_line(text, spans[keys[k]][0])} ({_name(keys[k])})"
    if got["hfov"]:
        camera["fov"] = vertical_fov(got["hfov"], 16 / 9)
        camera["aspect"] = 16 / 9
        where["camera.fov"] = f"{path.name} line {_line(text, spans[keys['hfov']][0])} ({_name(keys['hfov'])})"
        notes.append(f"camera.horizontalFov {got['hfov']:g}° (horizontal) = {camera['fov']:.4f}° vertical at the aspect 16:9 "
                     "(the window's aspect is not in the file: 16:9 assumed; give --camera aspect=…)")
    elif got["focal"] is not None:
        if not got["focal"] > 0:
            raise FileError(path, f"line {_line(text, spans[keys['focal']][0])} / {_name(keys['focal'])}", "a focal length > 0 [mm]", f"{got['focal']:g}")
        camera["fov"] = math.degrees(2.0 * math.atan(FRAME_HEIGHT_MM / 2.0 / got["focal"]))
        where["camera.fov"] = f"{path.name} line {_line(text, spans[keys['focal']][0])} ({_name(keys['focal'])})"
        notes.append(f"{_name(keys['focal'])} {got['focal']:g} mm = a vertical fov of {camera['fov']:.4f}° (35 mm frame, 24 mm high)")
    if shape == "new" and isinstance(data.get("camera"), dict) and data["camera"].get("enabled") is False:
        notes.append("camera.enabled is false: the viewer keeps its own camera; the camera block's values are taken as written")
    return camera or None


def _sun(path: Path, data: dict, shape: str, text: str, spans: dict, where: dict, notes: list) -> tuple[float, float] | None:
    at = ("lighting", "sunlight", "direction") if shape == "new" else ("lighting", "sunlightDirection")
    d = _vector(path, data, at, text, spans)
    if d is None:
        return None
    forward = [0.0, 0.0, -1.0]
    center, look = (_vector(path, data, ("camera", k), text, spans) for k in ("center", "lookAt")) if shape == "new" else (None, None)
    if center is not None and look is not None and any(a != b for a, b in zip(center, look)):
        forward = [b - a for a, b in zip(center, look)]
    else:
        notes.append("the camera's direction is not in the file: the sun's azimuth is taken from −Z (the viewer's home view)")
    elevation, azimuth = sun_from_directions([-x for x in d], forward)
    where["sun"] = f"{path.name} line {_line(text, spans[at][0])} ({_name(at)}: the direction the light travels)"
    if not elevation > 0:
        notes.append(f"{_name(at)} {d}: the sun is {-elevation:g}° below the horizon; no sun taken")
        return None
    return elevation, azimuth


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The shadow options, shadow type, sun and camera of one viewer settings file.

    ``files``: one (path, text) pair; ``light`` and ``camera`` are refused (the settings hold one
    sun and one camera, unnamed).  Returns the settings in the profile's keys and types, the camera
    (near, far [m], vertical fov [deg]) and the sun (elevation, azimuth [deg]), where each was found, and notes.
    A damaged or foreign file raises :class:`~aliasing.setups.files.common.FileError` (file, line, key).
    """
    files = pairs(files, light, camera)
    if len(files) != 1:
        raise ValueError(f"project must be one Filament settings JSON, got {len(files)} files")
    for name, value in (("light", light), ("camera", camera)):
        if value is not None:
            raise ValueError(f"{name} {value!r}: the viewer's settings hold one sun and one camera, unnamed; leave {name} out")
    path, text = files[0]
    data = _load(path, text)
    if not sniff(path, text) or not any(isinstance(data.get(k), dict) for k in ("lighting", "view")):
        raise FileError(path, "the top level", "the viewer's Settings: an object with \"lighting\" or \"view\"", ", ".join(map(repr, data))[:80] or "{}")
    spans = _spans(text)
    shape = _shape(data)
    base = _paths(shape)["mapSize"][:-1]
    for at in [base[:k] for k in range(1, len(base) + 1)] + [("view",), ("viewer",), ("camera",)]:
        v = _at(data, at)
        if v is not None and not isinstance(v, dict):
            raise FileError(path, f"line {_line(text, spans[at][0])} / {_name(at)}", "a JSON object", json.dumps(v)[:60])
    settings: dict[str, Any] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    for key, at in _paths(shape).items():
        v = _at(data, at[:-1]) if isinstance(at[-1], int) else _at(data, at)
        if isinstance(at[-1], int):
            if v is None:
                continue
            if not (isinstance(v, list) and len(v) == 3):
                raise FileError(path, f"line {_line(text, spans[at[:-1]][0])} / {_name(at[:-1])}", "an array of three numbers", json.dumps(v)[:60])
            v = v[at[-1]]
        elif v is None:
            continue
        line = _line(text, spans[at][0])
        settings[key] = coerce(path, f"line {line} / {_name(at)}", ENGINE, key, v if not isinstance(v, (dict, list)) else json.dumps(v)[:60])
        where[key] = f"{path.name} line {line} ({_name(at)})"
    for flag in ("enableShadows", "enableSunlight"):
        if _at(data, ("lighting", flag)) is False:
            notes.append(f"lighting.{flag} is false: the viewer draws no sun shadows")
    cam = _camera(path, data, shape, text, spans, where, notes)
    sun = _sun(path, data, shape, text, spans, where, notes)
    notes.append("distances in metres (Filament's world units)")
    return Found(ENGINE, settings, cam, sun, "sunlight", "camera" if cam else None, where, tuple(notes))


def _insert(text: str, spans: dict, data: dict, path: tuple, value: Any) -> str:
    """``text`` with ``value`` added at ``path`` inside the deepest object of ``path`` the file has."""
    k = len(path) - 1
    while k > 0 and not isinstance(_at(data, path[:k]), dict):
        k -= 1
    parent = path[:k]
    nested: Any = value
    for p in reversed(path[k + 1:]):
        nested = {p: nested}
    member = f"{json.dumps(path[k])}: {json.dumps(nested)}"
    start, end = spans[parent]
    close = end - 1  # the closing brace
    body = text[start + 1:close]
    if not body.strip():
        return text[:start + 1] + member + text[close:]
    last = start + 1 + len(body.rstrip())
    line_start = text.rfind("\n", 0, last) + 1
    indent = re.match(r"[ \t]*", text[line_start:]).group(0)
    sep = f",\n{indent}" if "\n" in body else ", "
    return text[:last] + sep + member + text[last:]


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with each changed value rewritten in place (the rest byte for byte); a key the
    file lacks is added to its object (the object, or its parents, created where absent).

    The reader interface (:mod:`aliasing.setups.files.common`): ``changes`` are profile keys to values,
    typed and range-checked by the profile (ValueError naming the key); ``found`` is what :func:`read`
    found in ``text``.  Reading the result back gives ``changes`` exactly.
    """
    new = typed_changes(path, ENGINE, changes)
    data = _load(path, text)
    paths = _paths(_shape(data))
    splits = {k: v for k, v in new.items() if k in SPLITS}
    plain = {k: v for k, v in new.items() if k not in SPLITS}
    for key, value in plain.items():
        spans = _spans(text)
        at = paths[key]
        if at in spans:
            s, e = spans[at]
            text = text[:s] + json.dumps(value) + text[e:]
        else:
            text = _insert(text, spans, data, at, value)
        data = json.loads(text)
    if splits:
        spans = _spans(text)
        at = paths[SPLITS[0]][:-1]
        current = _at(data, at)
        if isinstance(current, list) and len(current) == 3:
            for key, value in sorted(splits.items(), key=lambda kv: -SPLITS.index(kv[0])):  # right to left: offsets stay valid
                s, e = spans[at + (SPLITS.index(key),)]
                text = text[:s] + json.dumps(value) + text[e:]
        else:
            defaults = get(ENGINE).defaults()
            full = [splits.get(k, found.settings.get(k, defaults[k])) for k in SPLITS]
            text = (text[:spans[at][0]] + json.dumps(full) + text[spans[at][1]:]) if at in spans else _insert(text, spans, data, at, full)
    return text
