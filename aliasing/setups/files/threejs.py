"""three.js's Object JSON (format 4.x): what ``scene.toJSON()`` and the editor's scene export write.

Read as the pinned npm ``three`` 0.187.0 writes it:

* ``src/core/Object3D.js`` ``toJSON`` (line 1294): ``metadata.type`` ``"Object"``, the ``object`` tree
  (``type``, ``name``, ``uuid``, ``children``), each node's ``matrix``: its LOCAL transform, 16 numbers
  column-major (``Matrix4.toArray``), composed with its parents' for the world;
* ``src/cameras/PerspectiveCamera.js`` ``toJSON`` (line 383): ``fov`` (vertical, [deg]), ``zoom``
  (the view's fov is 2·atan(tan(fov/2)/zoom)), ``near``, ``far``, ``aspect``; a camera looks along its
  local −z;
* ``src/lights/DirectionalLight.js`` ``toJSON`` (line 100): ``shadow`` (``src/lights/LightShadow.js``
  ``toJSON``: ``bias``, ``normalBias``, ``radius``, ``blurSamples``, ``mapSize`` [w, h], ``camera``:
  the OrthographicCamera's ``left``, ``right``, ``top``, ``bottom``, ``near``, ``far``) and ``target``:
  the uuid of the object the light shines towards (``src/loaders/ObjectLoader.js``
  ``bindLightTargets``: an object of the file, else a new Object3D at the origin); the light shines
  from its world position towards its target's.

The file holds one DirectionalLight's own shadow, so the profile's ``class`` is ``DirectionalLight``;
the CSM addon's options are not in it (``--set`` them).  The editor's project file (``app.json``,
``editor/js/Editor.js`` ``toJSON``: ``{"project": {"shadows", "shadowType", …}, "camera": …, "scene": …}``)
is read too: ``project.shadowType`` is the renderer's ``shadowMap.type`` (0 BasicShadowMap, 1
PCFShadowMap, 2 PCFSoftShadowMap, 3 VSMShadowMap: ``src/constants.js``), ``camera`` the camera the
published app renders with; a bare ``scene.toJSON()`` file has no renderer: ``--set`` its
``renderer.shadowMap.type``.

Examples
--------
>>> import json
>>> light = {"type": "DirectionalLight", "name": "Sun", "uuid": "l", "castShadow": True, "target": "t",
...          "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 10, 10, 1], "shadow": {"bias": -0.001, "mapSize": [1024, 1024]}}
>>> cam = {"type": "PerspectiveCamera", "name": "Camera", "uuid": "c", "fov": 40, "near": 0.5, "far": 300, "aspect": 2,
...        "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}
>>> doc = {"metadata": {"type": "Object", "version": 4.7}, "object": {"type": "Scene", "uuid": "s", "children": [light, cam]}}
>>> f = read([(Path("scene.json"), json.dumps(doc))], None, None)
>>> f.settings, f.camera, f.sun
({'class': 'DirectionalLight', 'shadow.bias': -0.001, 'shadow.mapSize.width': 1024}, {'near': 0.5, 'far': 300.0, 'fov': 40.0, 'aspect': 2.0}, (45.0, 180.0))
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from . import jsontext
from ...view import narrowed_fov
from ..threejs import PROFILES
from .common import FileError, Found, direction, number, one_file, pick, sun_above

ENGINE = "threejs"
#: the profile whose settings the file keeps (values are checked against it before a patch)
PROFILE = PROFILES[0]
TITLE = "three.js Object JSON (scene.toJSON(), the editor's scene export)"
SOURCE = ("npm three 0.187.0: src/core/Object3D.js toJSON (line 1294), src/lights/DirectionalLight.js toJSON (line 100), "
          "src/lights/LightShadow.js toJSON, src/cameras/PerspectiveCamera.js toJSON (line 383), src/loaders/ObjectLoader.js bindLightTargets")
#: LightShadow.toJSON's keys and the profile's
SHADOW = {"bias": "shadow.bias", "normalBias": "shadow.normalBias", "radius": "shadow.radius", "blurSamples": "shadow.blurSamples"}
BOX = ("left", "right", "top", "bottom", "near", "far")


#: the renderer's shadowMap.type numbers (src/constants.js lines 57–84) as the editor's project.shadowType keeps them
SHADOW_TYPES = {0: "BasicShadowMap", 1: "PCFShadowMap", 2: "PCFSoftShadowMap", 3: "VSMShadowMap"}


def sniff(path: Path, text: str) -> bool:
    """JSON whose ``metadata.type`` is ``"Object"`` (Object3D.toJSON's header), or the editor's project (``app.json``)."""
    head = text.lstrip()[:1]
    return head == "{" and '"metadata"' in text and '"Object"' in text and '"object"' in text


def _walk(path: Path, node: Any, where: tuple, parent: np.ndarray, out: list) -> None:
    if not isinstance(node, dict):
        raise FileError(path, _name(where), "an object of the scene tree", type(node).__name__)
    m = node.get("matrix")
    local = np.eye(4)
    if m is not None:
        if not isinstance(m, list) or len(m) != 16:
            raise FileError(path, _name(where + ("matrix",)), "16 numbers (column-major)", repr(m)[:60])
        local = np.array([number(path, _name(where + ("matrix", i)), v) for i, v in enumerate(m)]).reshape(4, 4).T
    world = parent @ local
    out.append((node, where, world))
    kids = node.get("children", [])
    if not isinstance(kids, list):
        raise FileError(path, _name(where + ("children",)), "a list", type(kids).__name__)
    for i, kid in enumerate(kids):
        _walk(path, kid, where + ("children", i), world, out)


def _name(where: tuple) -> str:
    return "".join(f"[{s}]" if isinstance(s, int) else (f".{s}" if i else s) for i, s in enumerate(where))


def _object(path: Path, data: Any, at: tuple) -> dict:
    """The Object JSON at ``at`` (its ``metadata.type`` checked)."""
    if not isinstance(data, dict) or not isinstance(data.get("metadata"), dict) or data["metadata"].get("type") != "Object":
        raise FileError(path, _name(at + ("metadata", "type")), '"Object" (three.js Object JSON of scene.toJSON())', "another JSON")
    if not isinstance(data.get("object"), dict):
        raise FileError(path, _name(at + ("object",)), "the scene's object tree", type(data.get("object")).__name__)
    return data


def _doc(path: Path, text: str) -> tuple[list, dict | None, list]:
    """(the scene's nodes, the editor's ``project`` or None, the editor's camera node where it has one)."""
    data = jsontext.load(path, text)
    out: list = []
    if isinstance(data, dict) and isinstance(data.get("scene"), dict) and isinstance(data.get("project"), dict):  # editor/js/Editor.js toJSON
        _walk(path, _object(path, data["scene"], ("scene",))["object"], ("scene", "object"), np.eye(4), out)
        cams: list = []
        if data.get("camera") is not None:
            _walk(path, _object(path, data["camera"], ("camera",))["object"], ("camera", "object"), np.eye(4), cams)
        return out, data["project"], cams[:1]
    _walk(path, _object(path, data, ())["object"], ("object",), np.eye(4), out)
    return out, None, []


def _pick(path: Path, nodes: list, kind: str, want: str | None, flag: str) -> tuple | None:
    found = [n for n in nodes if n[0].get("type") == kind]
    if not found and want is None:
        return None
    names = [str(n[0].get("name") or n[0].get("uuid")) for n in found]
    return found[pick(path, kind, names, want, flag)]


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The DirectionalLight's shadow, the PerspectiveCamera and the sun of one Object JSON file."""
    path, text = one_file(files, "one three.js Object JSON file")
    nodes, project, app_camera = _doc(path, text)
    settings: dict[str, Any] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    if project is not None:
        if "shadowType" in project:
            if project["shadowType"] not in SHADOW_TYPES or isinstance(project["shadowType"], bool):
                raise FileError(path, "project.shadowType", "one of " + ", ".join(f"{i} ({n})" for i, n in SHADOW_TYPES.items()),
                                repr(project["shadowType"]))
            settings["renderer.shadowMap.type"] = SHADOW_TYPES[project["shadowType"]]
            where["renderer.shadowMap.type"] = f"{path.name} project.shadowType"
        if project.get("shadows") is False:
            notes.append("project.shadows is false: the renderer draws no shadows; this is the shadow it draws when true")
    cam = towards = forward = None
    lname = cname = None
    lt = _pick(path, nodes, "DirectionalLight", light, "--light-node")
    if lt is not None:
        node, at, world = lt
        lname = str(node.get("name") or node.get("uuid"))
        settings["class"], where["class"] = "DirectionalLight", f"{path.name} {_name(at)}.type"
        notes.append("class DirectionalLight: the file's light casts its own shadow (--set class=CSM for the CSM addon)")
        if node.get("castShadow") is not True:
            notes.append(f"{lname}: castShadow is false: the light casts no shadow; this is the shadow it casts when true")
        shadow = node.get("shadow", {})
        if not isinstance(shadow, dict):
            raise FileError(path, _name(at + ("shadow",)), "LightShadow.toJSON's object", type(shadow).__name__)
        for key, ours in SHADOW.items():
            if key in shadow:
                settings[ours], where[ours] = shadow[key], f"{path.name} {_name(at + ('shadow', key))}"
        if "mapSize" in shadow:
            size = shadow["mapSize"]
            if not isinstance(size, list) or len(size) != 2:
                raise FileError(path, _name(at + ("shadow", "mapSize")), "[width, height] texels", repr(size)[:40])
            settings["shadow.mapSize.width"], where["shadow.mapSize.width"] = size[0], f"{path.name} {_name(at + ('shadow', 'mapSize'))}"
            if size[1] != size[0]:
                notes.append(f"shadow.mapSize is {size[0]}×{size[1]}: the toolkit takes the width")
        box = shadow.get("camera", {})
        if isinstance(box, dict):
            for key in BOX:
                if key in box:
                    settings[f"shadow.camera.{key}"] = box[key]
                    where[f"shadow.camera.{key}"] = f"{path.name} {_name(at + ('shadow', 'camera', key))}"
            if box.get("zoom", 1) != 1:
                notes.append(f"shadow.camera.zoom {box['zoom']} is not modelled (the box is taken at zoom 1)")
        target = next((n for n in nodes if n[0].get("uuid") == node.get("target")), None)
        if target is None:
            notes.append("the light's target is not in the file: at the origin (ObjectLoader.bindLightTargets)")
        aim = target[2][:3, 3] if target is not None else np.zeros(3)
        towards = direction(path, f"{_name(at)}.matrix (the light at its target)", world[:3, 3] - aim)
    ct = app_camera[0] if app_camera and camera is None and app_camera[0][0].get("type") == "PerspectiveCamera" else \
        _pick(path, nodes, "PerspectiveCamera", camera, "--camera-node")
    if ct is not None:
        node, at, world = ct
        cname = str(node.get("name") or node.get("uuid"))
        cam = {}
        for key in ("near", "far", "fov", "aspect"):
            if key in node:
                cam[key] = number(path, _name(at + (key,)), node[key])
                where[f"camera.{key}"] = f"{path.name} {_name(at + (key,))}"
        zoom = number(path, _name(at + ("zoom",)), node.get("zoom", 1))
        if zoom != 1 and "fov" in cam:
            if not zoom > 0:
                raise FileError(path, _name(at + ("zoom",)), "a zoom > 0", repr(zoom))
            fov = float(narrowed_fov(cam["fov"], zoom, "camera.fov"))
            notes.append(f"camera.fov {cam['fov']:.12g}° at zoom {zoom:g} = {fov:.12g}° (PerspectiveCamera.getEffectiveFOV)")
            cam["fov"] = fov
        forward = -world[:3, 2]
    sun = sun_above(towards, forward, notes)
    return Found(ENGINE, settings, camera=cam, sun=sun, light=lname, camera_name=cname, where=where, notes=tuple(notes))


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with ``changes`` (the profile's ``shadow.*`` keys) written into the light's ``shadow`` object."""
    nodes, project, _ = _doc(path, text)
    if "renderer.shadowMap.type" in changes:
        if project is None:
            raise ValueError(f"{path.name}: renderer.shadowMap.type is the renderer's, not kept in scene.toJSON()'s Object JSON "
                             "(the editor's project file keeps it as project.shadowType)")
        number_ = next(i for i, n in SHADOW_TYPES.items() if n == changes["renderer.shadowMap.type"])
        text = jsontext.put(text, ("project", "shadowType"), number_)
        changes = {k: v for k, v in changes.items() if k != "renderer.shadowMap.type"}
    if not changes:
        return text
    lt = _pick(path, nodes, "DirectionalLight", found.light, "--light-node")
    if lt is None:
        raise FileError(path, "object", "a DirectionalLight to write to", "none")
    at = lt[1]
    ours = {v: k for k, v in SHADOW.items()}
    for key, v in changes.items():
        if key in ours:
            text = jsontext.put(text, at + ("shadow", ours[key]), v)
        elif key == "shadow.mapSize.width":
            text = jsontext.put(text, at + ("shadow", "mapSize"), [v, v]) if "mapSize" not in lt[0].get("shadow", {}) else \
                jsontext.put(jsontext.put(text, at + ("shadow", "mapSize", 0), v), at + ("shadow", "mapSize", 1), v)
        elif key.startswith("shadow.camera.") and key[len("shadow.camera."):] in BOX:
            text = jsontext.put(text, at + ("shadow", "camera", key[len("shadow.camera."):]), v)
        else:
            raise ValueError(f"{path.name}: {key} is not kept in three.js Object JSON (it keeps the light's shadow.*: "
                             f"{', '.join(list(ours) + ['shadow.mapSize.width'] + [f'shadow.camera.{b}' for b in BOX])})")
    return text
