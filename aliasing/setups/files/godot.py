"""Godot 4's own text files: ``project.godot`` (the project settings) and ``.tscn``/``.tres`` scenes.

The formats, at godotengine/godot 4.x as stored in the index (Godot's documentation page "TSCN file
format" describes both):

* ``core/io/config_file.cpp`` (``ConfigFile::_parse``, as ``ProjectSettings`` loads
  ``project.godot``): ``[section]`` headers and ``key=value`` lines, the setting
  ``rendering/lights_and_shadows/directional_shadow/size`` kept as ``lights_and_shadows/directional_shadow/size``
  under ``[rendering]``; a ``.mobile`` (or other feature) suffix is an override for that platform;
* ``scene/resources/resource_format_text.cpp`` (``ResourceLoaderText``): a scene is ``[gd_scene …]``,
  ``[ext_resource …]``, ``[sub_resource …]`` and ``[node name="…" type="…" parent="…"]`` headers, each
  followed by ``property = value`` lines; a node of an instanced scene has ``instance=ExtResource(…)``
  instead of a type; a property at its default is not written;
* ``core/variant/variant_parser.cpp`` (``VariantWriter::write``, case ``TRANSFORM3D``): ``Transform3D(``
  the basis row by row (``m3.rows[i][j]``: xx, xy, xz, yx, …), then the origin ``)``: the basis' z
  axis (column 2) is the 3rd, 6th and 9th numbers.

Nodes (``scene/3d/light_3d.cpp``, ``scene/3d/camera_3d.cpp``): a DirectionalLight3D shines along its
local −Z (towards the sun: its basis' +Z), ``directional_shadow_mode`` is written as its enum integer
(0 SHADOW_ORTHOGONAL, 1 SHADOW_PARALLEL_2_SPLITS, 2 SHADOW_PARALLEL_4_SPLITS; default 2); a Camera3D
looks along its local −Z, ``fov`` [deg] is vertical with ``keep_aspect = 1`` (KEEP_HEIGHT, the
default) and horizontal with 0 (KEEP_WIDTH); defaults fov 75, near 0.05, far 4000.  A node's
transform is relative to its parent (``parent="."`` the root, ``parent="A/B"`` a path).

Examples
--------
>>> scene = '''[gd_scene format=3]
... [node name="Main" type="Node3D"]
... [node name="Sun" type="DirectionalLight3D" parent="."]
... transform = Transform3D(1, 0, 0, 0, 0.5, 0.8660254037844386, 0, -0.8660254037844386, 0.5, 0, 10, 0)
... shadow_enabled = true
... directional_shadow_mode = 1
... [node name="Camera" type="Camera3D" parent="."]
... fov = 60.0
... '''
>>> f = read([(Path("main.tscn"), scene)], None, None)
>>> f.settings, f.camera, f.sun
({'directional_shadow_mode': 'SHADOW_PARALLEL_2_SPLITS'}, {'fov': 60.0, 'near': 0.05, 'far': 4000.0}, (60.0, 180.0))
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..godot import PROFILES
from .common import FileError, Found, direction, pick, sun_above

ENGINE = "godot"
#: the profile whose settings the file keeps (values are checked against it before a patch)
PROFILE = PROFILES[0]
TITLE = "Godot 4 project.godot and .tscn/.tres scenes"
SOURCE = ("Godot docs 'TSCN file format'; godotengine/godot core/io/config_file.cpp, scene/resources/resource_format_text.cpp, "
          "core/variant/variant_parser.cpp VariantWriter::write (TRANSFORM3D: basis rows, then origin)")
MODES = ("SHADOW_ORTHOGONAL", "SHADOW_PARALLEL_2_SPLITS", "SHADOW_PARALLEL_4_SPLITS")
#: the light's properties the profile models (the .tscn property has the profile key's name)
LIGHT_KEYS = ("directional_shadow_mode", "directional_shadow_split_1", "directional_shadow_split_2", "directional_shadow_split_3",
              "directional_shadow_blend_splits", "directional_shadow_fade_start", "directional_shadow_max_distance",
              "directional_shadow_pancake_size", "shadow_bias", "shadow_normal_bias", "shadow_blur", "shadow_reverse_cull_face",
              "light_angular_distance")
PROJECT = "lights_and_shadows/directional_shadow/"
PROJECT_KEYS = ("size", "soft_shadow_filter_quality", "16_bits")
#: Camera3D's defaults (scene/3d/camera_3d.cpp Camera3D::Camera3D: fov 75°, near 0.05, far 4000)
CAMERA_DEFAULTS = {"fov": 75.0, "near": 0.05, "far": 4000.0}
_HEADER = re.compile(r"^\[(\w+)(\s.*)?\]\s*$")  # the attributes' values may be arrays: groups=["a", "b"]
_ATTR = re.compile(r"([\w/]+)=(\"(?:[^\"\\]|\\.)*\"|[^\s\]]+)")
_LINE = re.compile(r"^([\w/.\-:]+)\s*=\s*(.*)$")
_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*([eE][+-]?\d+)?|\.\d+([eE][+-]?\d+)?)$")


@dataclass
class Section:
    """One ``[header]`` of a Godot text file and its ``key = value`` lines (0-based line numbers)."""

    kind: str
    attrs: dict[str, str]
    line: int
    props: dict[str, tuple[str, int]] = field(default_factory=dict)
    last: int = 0


def parse(path: Path, text: str) -> list[Section]:
    """The sections of a Godot text file (ConfigFile or TSCN), or a :class:`FileError` naming the broken line.

    Examples
    --------
    >>> [(s.kind, s.props) for s in parse(Path("project.godot"), "config_version=5\\n[rendering]\\na/b=2\\n")]
    [('', {'config_version': ('5', 0)}), ('rendering', {'a/b': ('2', 2)})]
    """
    sections: list[Section] = []
    lines = text.split("\n")
    i = 0
    top = Section("", {}, -1)
    while i < len(lines):
        raw = lines[i].rstrip("\r")
        s = raw.strip()
        if not s or s.startswith(";") or s.startswith("#"):
            i += 1
            continue
        if s.startswith("["):
            m = _HEADER.match(s)
            if not m:
                raise FileError(path, f"line {i + 1}", "a section header [name key=value …]", repr(s[:60]))
            attrs = {k: v[1:-1] if v.startswith('"') else v for k, v in _ATTR.findall(m.group(2) or "")}
            sections.append(Section(m.group(1), attrs, i, last=i))
            i += 1
            continue
        m = _LINE.match(s)
        if not m:
            raise FileError(path, f"line {i + 1}", "a property line key = value or a section header", repr(s[:60]))
        start, value = i, m.group(2)
        while _open(value) > 0:  # a value over several lines: brackets and strings balance
            i += 1
            if i >= len(lines):
                raise FileError(path, f"line {start + 1}", f"the value of {m.group(1)} closed before the end of the file", "an unclosed value")
            value += "\n" + lines[i].rstrip("\r")
        if _open(value) < 0:
            raise FileError(path, f"line {start + 1}", f"a value for {m.group(1)} with balanced brackets", repr(value[:60]))
        sec = sections[-1] if sections else top
        sec.props[m.group(1)] = (value.strip(), start)
        sec.last = i
        i += 1
    if not sections and not top.props:
        raise FileError(path, "line 1", "a Godot text file ([section] headers and key = value lines)", "an empty file")
    return ([top] if top.props else []) + sections


def _open(value: str) -> int:
    depth, quoted, escape = 0, False, False
    for ch in value:
        if quoted:
            escape, quoted = (not escape and ch == "\\"), quoted and not (ch == '"' and not escape)
            continue
        if ch == '"':
            quoted = True
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
    return depth + (1 if quoted else 0)


def value(path: Path, line: int, key: str, text: str) -> Any:
    """A Godot value: a number, ``true``/``false``, a string, or ``Transform3D(…)`` (its 12 numbers).

    Examples
    --------
    >>> value(Path("a.tscn"), 0, "fov", "60.0"), value(Path("a.tscn"), 0, "on", "true")
    (60.0, True)
    """
    t = text.strip()
    if t in ("true", "false"):
        return t == "true"
    if _NUMBER.match(t):
        return int(t) if re.fullmatch(r"[+-]?\d+", t) else float(t)
    if t.startswith('"') and t.endswith('"') and len(t) >= 2:
        return t[1:-1]
    m = re.fullmatch(r"Transform3D\((.*)\)", t, re.S)
    if m:
        parts = [p.strip() for p in m.group(1).split(",")]
        if len(parts) != 12 or not all(_NUMBER.match(p) for p in parts):
            raise FileError(path, f"line {line + 1} {key}", "Transform3D( 12 numbers: the basis row by row, then the origin )", repr(t[:60]))
        return np.array([float(p) for p in parts])
    return t


def _number(path: Path, line: int, key: str, v: Any) -> Any:
    if isinstance(v, str):
        raise FileError(path, f"line {line + 1} {key}", "a number, true or false", repr(v[:40]))
    return v


def _matrix(path: Path, sec: Section) -> np.ndarray:
    """The node's local transform as a 4×4 matrix (identity where the file leaves it at the default)."""
    m = np.eye(4)
    if "transform" in sec.props:
        text, line = sec.props["transform"]
        t = value(path, line, "transform", text)
        if not isinstance(t, np.ndarray):
            raise FileError(path, f"line {line + 1} transform", "Transform3D(…12 numbers…)", repr(text[:60]))
        m[:3, :3] = t[:9].reshape(3, 3)  # rows of the basis (VariantWriter::write TRANSFORM3D)
        m[:3, 3] = t[9:]
    return m


def _nodes(path: Path, sections: list[Section]) -> dict[str, Section]:
    """The scene's nodes by path from the root (the root is ``.``)."""
    out: dict[str, Section] = {}
    for sec in sections:
        if sec.kind != "node":
            continue
        if "name" not in sec.attrs:
            raise FileError(path, f"line {sec.line + 1}", 'a node header with name="…"', "none")
        parent = sec.attrs.get("parent")
        key = "." if parent is None else sec.attrs["name"] if parent == "." else f"{parent}/{sec.attrs['name']}"
        out[key] = sec
    return out


def _world(path: Path, nodes: dict[str, Section], key: str) -> np.ndarray:
    """The node's transform composed with its parents' within the file."""
    m = _matrix(path, nodes[key])
    parts = key.split("/") if key != "." else []
    for depth in range(len(parts) - 1, -1, -1):
        parent = "/".join(parts[:depth]) or "."
        sec = nodes.get(parent)
        if sec is None:
            raise FileError(path, f"line {nodes[key].line + 1}", f"the parent node {parent!r} in the same file", "none")
        if "instance" in sec.attrs and parent != ".":
            raise FileError(path, f"line {sec.line + 1}", f"a parent of {key!r} whose transform the file holds (not an instanced scene)",
                            f"the instanced node {parent!r}")
        m = _matrix(path, sec) @ m
    return m


def _scene_read(path: Path, text: str, light: str | None, camera: str | None, out: dict) -> None:
    nodes = _nodes(path, parse(path, text))
    lights = [k for k, s in nodes.items() if s.attrs.get("type") == "DirectionalLight3D"]
    cams = [k for k, s in nodes.items() if s.attrs.get("type") == "Camera3D"]
    by_name = lambda keys, want: want if want is None or want in keys else next((k for k in keys if k.split("/")[-1] == want), want)  # noqa: E731
    if lights or light is not None:
        key = lights[pick(path, "DirectionalLight3D", lights, by_name(lights, light), "--light-node")]
        sec = nodes[key]
        out["light"] = key
        for prop in LIGHT_KEYS:
            if prop in sec.props:
                text_, line = sec.props[prop]
                v = _number(path, line, prop, value(path, line, prop, text_))
                if prop == "directional_shadow_mode":
                    if not isinstance(v, int) or isinstance(v, bool) or not 0 <= v <= 2:
                        raise FileError(path, f"line {line + 1} {prop}", "0 (ORTHOGONAL), 1 (PARALLEL_2_SPLITS) or 2 (PARALLEL_4_SPLITS)", repr(v))
                    v = MODES[v]
                out["settings"][prop] = v
                out["where"][prop] = f"{path.name} line {line + 1}"
        enabled = sec.props.get("shadow_enabled")
        if enabled is None or value(path, enabled[1], "shadow_enabled", enabled[0]) is not True:
            out["notes"].append(f"{key}: shadow_enabled is false (the default): the light casts no shadow; this is the shadow it casts when true")
        out["towards"] = direction(path, f"line {sec.line + 1} transform", _world(path, nodes, key)[:3, 2])
    current = [k for k in cams if value(path, 0, "current", nodes[k].props.get("current", ("false", 0))[0]) is True]
    if cams or camera is not None:
        # several cameras: the one marked current = true is the one Godot renders with (Camera3D::make_current)
        key = current[0] if camera is None and len(cams) > 1 and len(current) == 1 else \
            cams[pick(path, "Camera3D", cams, by_name(cams, camera), "--camera-node")]
        sec = nodes[key]
        if "projection" in sec.props and value(path, sec.props["projection"][1], "projection", sec.props["projection"][0]) != 0:
            raise FileError(path, f"line {sec.props['projection'][1] + 1} projection", "0 (PROJECTION_PERSPECTIVE): the toolkit's camera is a "
                            "perspective one", sec.props["projection"][0])
        out["camera_name"] = key
        fields = dict(CAMERA_DEFAULTS)  # a property at its default is not written
        for prop in ("fov", "near", "far"):
            if prop in sec.props:
                text_, line = sec.props[prop]
                fields[prop] = float(_number(path, line, prop, value(path, line, prop, text_)))
                out["where"][f"camera.{prop}"] = f"{path.name} line {line + 1}"
        aspect = sec.props.get("keep_aspect")
        if aspect is not None:
            keep = value(path, aspect[1], "keep_aspect", aspect[0])
            if keep not in (0, 1) or isinstance(keep, bool):
                raise FileError(path, f"line {aspect[1] + 1} keep_aspect", "0 (KEEP_WIDTH) or 1 (KEEP_HEIGHT)", repr(keep))
            if keep == 0:
                fields["horizontal_fov"] = fields.pop("fov", 75.0)
                out["notes"].append(f"camera.fov: keep_aspect = 0 (KEEP_WIDTH): fov {fields['horizontal_fov']:g}° is horizontal")
        out["camera"] = fields
        out["forward"] = -_world(path, nodes, key)[:3, 2]


def _project_read(path: Path, text: str, out: dict) -> None:
    for sec in parse(path, text):
        if sec.kind != "rendering":
            continue
        for key, (text_, line) in sec.props.items():
            if not key.startswith(PROJECT):
                continue
            name, _, feature = key[len(PROJECT):].partition(".")
            if name in PROJECT_KEYS and not feature:
                out["settings"]["rendering/" + PROJECT + name] = _number(path, line, key, value(path, line, key, text_))
                out["where"]["rendering/" + PROJECT + name] = f"{path.name} line {line + 1}"
            elif name in PROJECT_KEYS:
                out["notes"].append(f"{path.name} line {line + 1}: {key} (an override for the {feature} feature) is not taken")


def _is_project(path: Path, text: str) -> bool:
    return path.name == "project.godot" or path.suffix == ".godot" or text.lstrip().startswith("config_version")


def sniff(path: Path, text: str) -> bool:
    """``project.godot``, or a ``.tscn``/``.tres`` text scene (``[gd_scene``/``[gd_resource`` header)."""
    if path.suffix.lower() in (".tscn", ".tres", ".godot"):
        return True
    head = text.lstrip()[:40]
    return head.startswith("[gd_scene") or head.startswith("[gd_resource") or head.startswith("config_version")


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The light's and camera's properties of the scene(s) and the project settings of ``project.godot``."""
    out: dict[str, Any] = {"settings": {}, "where": {}, "notes": [], "camera": None, "light": None, "camera_name": None}
    scenes = [(p, t) for p, t in files if not _is_project(p, t)]
    for p, t in files:
        if _is_project(p, t):
            _project_read(p, t, out)
    if len(scenes) > 1:
        raise ValueError(f"project takes one Godot scene with the light and camera, got {len(scenes)}: {', '.join(p.name for p, _ in scenes)}")
    for p, t in scenes:
        _scene_read(p, t, light, camera, out)
        if "towards" not in out:
            out["notes"].append(f"{p.name}: no DirectionalLight3D (the light's settings are the defaults and --set's)")
    sun = sun_above(out.get("towards"), out.get("forward"), out["notes"])
    return Found(ENGINE, out["settings"], camera=out["camera"], sun=sun, light=out["light"], camera_name=out["camera_name"],
                 where=out["where"], notes=tuple(out["notes"]))


def _godot(v: Any, key: str) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if key == "directional_shadow_mode":
        return str(MODES.index(v))
    return repr(float(v)) if isinstance(v, float) else str(v)


def _set_line(lines: list[str], sec: Section, key: str, text: str, sep: str) -> None:
    if key in sec.props:
        _, line = sec.props[key]
        indent = lines[line][: len(lines[line]) - len(lines[line].lstrip())]
        end = line
        while _open("\n".join(lines[line:end + 1]).partition("=")[2]) > 0:
            end += 1
        lines[line:end + 1] = [f"{indent}{key}{sep}{text}"]
    else:
        lines.insert(sec.last + 1, f"{key}{sep}{text}")


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with ``changes`` written: the light's property lines in its node's section of a scene, the
    ``[rendering]`` lines of ``project.godot`` (a line inserted where the file left the default)."""
    nl = "\r\n" if "\r\n" in text else "\n"
    lines = text.replace("\r\n", "\n").split("\n")
    project = _is_project(path, text)
    for key, v in changes.items():
        sections = parse(path, "\n".join(lines))
        if project:
            if not key.startswith("rendering/" + PROJECT):
                raise ValueError(f"{path.name}: {key} is a light property, kept in the scene (.tscn), not in project.godot")
            sec = next((s for s in sections if s.kind == "rendering"), None)
            if sec is None:  # a new section at the end, laid out as Godot writes it
                while lines and lines[-1] == "":
                    lines.pop()
                lines += ["", "[rendering]", "", f"{key[len('rendering/'):]}={_godot(v, key)}", ""]
                continue
            _set_line(lines, sec, key[len("rendering/"):], _godot(v, key), "=")
        else:
            if key not in LIGHT_KEYS:
                raise ValueError(f"{path.name}: {key} is not a DirectionalLight3D property (project settings go in project.godot)")
            nodes = _nodes(path, sections)
            if found.light is None or found.light not in nodes:
                raise FileError(path, "the scene", "a DirectionalLight3D node to write to", "none")
            _set_line(lines, nodes[found.light], key, _godot(v, key), " = ")
    return nl.join(lines)
