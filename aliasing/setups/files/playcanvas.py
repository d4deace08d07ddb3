"""PlayCanvas's scene JSON: the editor's scene format as the pinned engine's ``SceneParser`` reads it.

Read as npm ``playcanvas`` 2.23.3 reads it (files under ``build/playcanvas/src``):

* ``framework/parsers/scene.js`` ``SceneParser.parse``: ``entities``, an object of entities by
  ``resource_id``, each with ``name``, ``parent`` (null for the root), ``children`` (resource ids),
  ``position``, ``rotation`` (Euler angles [deg]: ``setLocalEulerAngles``, the quaternion of
  ``core/math/quat.js`` ``setFromEulerAngles``), ``scale`` and ``components``; an uncompressed
  scene (a ``compressedFormat`` one is refused);
* ``framework/components/light/system.js`` ``initializeComponentData``: ``components.light`` sets the
  LightComponent's properties by their own names: ``type`` ``"directional"``, ``castShadows``,
  ``shadowDistance``, ``shadowResolution``, ``numCascades``, ``cascadeDistribution``, ``cascadeBlend``,
  ``shadowBias``, ``normalOffsetBias``, ``shadowType`` (its integer: ``scene/constants.js`` lines
  71–84), ``vsmBlurSize``, ``vsmBlurMode`` (0 BLUR_BOX, 1 BLUR_GAUSSIAN), ``vsmBias``,
  ``shadowSamples``, ``penumbraSize``, ``penumbraFalloff``, ``shadowIntensity``;
* ``framework/components/camera/component.js``: ``components.camera`` ``fov`` [deg], vertical unless
  ``horizontalFov`` is true, ``nearClip``, ``farClip``.

A directional light shines along its entity's local −Y (``scene/lighting/light-slot-uniforms.js``
line 134: ``wtm.getY(directional._direction).mulScalar(-1)``); a camera looks along its local −Z.

Examples
--------
>>> import json
>>> scene = {"entities": {
...     "r": {"name": "Root", "resource_id": "r", "parent": None, "children": ["l", "c"], "position": [0, 0, 0],
...           "rotation": [0, 0, 0], "scale": [1, 1, 1], "components": {}},
...     "l": {"name": "Sun", "resource_id": "l", "parent": "r", "children": [], "position": [0, 0, 0],
...           "rotation": [30, 0, 0], "scale": [1, 1, 1],
...           "components": {"light": {"type": "directional", "castShadows": True, "numCascades": 4, "shadowType": 4}}},
...     "c": {"name": "Camera", "resource_id": "c", "parent": "r", "children": [], "position": [0, 2, 0],
...           "rotation": [0, 0, 0], "scale": [1, 1, 1],
...           "components": {"camera": {"fov": 60, "nearClip": 0.3, "farClip": 700}}}}}
>>> f = read([(Path("scene.json"), json.dumps(scene))], None, None)
>>> f.settings, f.camera, f.sun
({'castShadows': True, 'numCascades': 4, 'shadowType': 'SHADOW_PCF5_32F'}, {'near': 0.3, 'far': 700.0, 'fov': 60.0}, (60.0, 180.0))
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from . import jsontext
from ..playcanvas import PROFILES
from .common import FileError, Found, direction, number, one_file, pick, sun_above, vector

ENGINE = "playcanvas"
#: the profile whose settings the file keeps (values are checked against it before a patch)
PROFILE = PROFILES[0]
TITLE = "a PlayCanvas scene JSON (the editor's format, SceneParser)"
SOURCE = ("npm playcanvas 2.23.3: build/playcanvas/src/framework/parsers/scene.js SceneParser, framework/components/light/system.js "
          "initializeComponentData, core/math/quat.js setFromEulerAngles, scene/constants.js lines 71–84")
#: components.light keys read straight into the profile's keys of the same name
DIRECT = ("castShadows", "numCascades", "cascadeDistribution", "cascadeBlend", "shadowDistance", "shadowResolution", "shadowBias",
          "normalOffsetBias", "vsmBlurSize", "vsmBias", "shadowSamples", "penumbraSize", "penumbraFalloff", "shadowIntensity")
#: shadowType integers (scene/constants.js lines 71–84)
SHADOW_TYPES = {0: "SHADOW_PCF3_32F", 2: "SHADOW_VSM_16F", 3: "SHADOW_VSM_32F", 4: "SHADOW_PCF5_32F", 5: "SHADOW_PCF1_32F",
                6: "SHADOW_PCSS_32F", 7: "SHADOW_PCF1_16F", 8: "SHADOW_PCF3_16F", 9: "SHADOW_PCF5_16F"}
BLUR_MODES = {0: "BLUR_BOX", 1: "BLUR_GAUSSIAN"}
#: the camera component's defaults (scene/camera.js lines 98–105: farClip 1000, fov 45°, nearClip 0.1)
CAMERA_DEFAULTS = {"near": 0.1, "far": 1000.0, "fov": 45.0}
ENUMS = {"shadowType": SHADOW_TYPES, "vsmBlurMode": BLUR_MODES}


def sniff(path: Path, text: str) -> bool:
    """JSON with an ``entities`` object whose entities carry ``resource_id`` (the editor's scene)."""
    head = text.lstrip()[:1]
    return head == "{" and '"entities"' in text and '"resource_id"' in text


def rotation(euler_deg) -> np.ndarray:
    """The 3×3 rotation of PlayCanvas Euler angles [deg] (``Quat.setFromEulerAngles``, then the quaternion's matrix).

    Examples
    --------
    >>> rotation([90, 0, 0]).round(12).tolist()      # local −Y (a light's direction) turns to −Z
    [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]
    """
    ex, ey, ez = (math.radians(float(a)) / 2 for a in euler_deg)
    sx, cx, sy, cy, sz, cz = math.sin(ex), math.cos(ex), math.sin(ey), math.cos(ey), math.sin(ez), math.cos(ez)
    x = sx * cy * cz - cx * sy * sz
    y = cx * sy * cz + sx * cy * sz
    z = cx * cy * sz - sx * sy * cz
    w = cx * cy * cz + sx * sy * sz
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def _entities(path: Path, text: str) -> dict:
    data = jsontext.load(path, text)
    if not isinstance(data, dict) or not isinstance(data.get("entities"), dict):
        raise FileError(path, "entities", "an object of entities by resource_id (a PlayCanvas scene)", "another JSON")
    if data.get("compressedFormat"):
        raise FileError(path, "compressedFormat", "an uncompressed scene (the editor's export)", "a compressed scene")
    for key, e in data["entities"].items():
        if not isinstance(e, dict):
            raise FileError(path, f"entities.{key}", "an entity object", type(e).__name__)
        if e.get("components") is not None and not isinstance(e.get("components"), dict):
            raise FileError(path, f"entities.{key}.components", "an object of components", type(e["components"]).__name__)
    return data["entities"]


def _world(path: Path, ents: dict, key: str) -> np.ndarray:
    """The entity's world rotation (its parents' composed; scale is not taken)."""
    r = np.eye(3)
    seen = set()
    while key is not None:
        if key in seen or key not in ents:
            raise FileError(path, f"entities.{key}", "a parent chain of entities in the file ending at the root", "a missing or circular parent")
        seen.add(key)
        e = ents[key]
        r = rotation(vector(path, f"entities.{key}.rotation", e.get("rotation", [0, 0, 0]))) @ r
        key = e.get("parent")
    return r


def _pick(path: Path, ents: dict, comp: str, ok, want: str | None, flag: str) -> str | None:
    keys = [k for k, e in ents.items() if isinstance((e.get("components") or {}).get(comp), dict) and ok(e["components"][comp])]
    if not keys and want is None:
        return None
    names = [str(ents[k].get("name", k)) for k in keys]
    return keys[pick(path, "directional light" if comp == "light" else comp, names, want, flag)]


def _is_directional(c: dict) -> bool:
    return c.get("type", "directional") == "directional"


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The directional light's component, the camera's and the sun of one scene JSON."""
    path, text = one_file(files, "one PlayCanvas scene JSON")
    ents = _entities(path, text)
    settings: dict[str, Any] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    cam = towards = forward = None
    lkey = _pick(path, ents, "light", _is_directional, light, "--light-node")
    if lkey is not None:
        comp = ents[lkey]["components"]["light"]
        at = f"entities.{lkey}.components.light"
        for key in DIRECT:
            if key in comp:
                settings[key], where[key] = comp[key], f"{path.name} {at}.{key}"
        for key, table in ENUMS.items():
            if key in comp:
                if comp[key] not in table or isinstance(comp[key], bool):
                    raise FileError(path, f"{at}.{key}", "one of " + ", ".join(f"{i} ({n})" for i, n in table.items()), repr(comp[key]))
                settings[key], where[key] = table[comp[key]], f"{path.name} {at}.{key}"
        towards = direction(path, f"entities.{lkey}.rotation", _world(path, ents, lkey)[:, 1])
    ckey = _pick(path, ents, "camera", lambda c: True, camera, "--camera-node")
    if ckey is not None:
        comp = ents[ckey]["components"]["camera"]
        at = f"entities.{ckey}.components.camera"
        if comp.get("projection", 0) != 0:  # PROJECTION_PERSPECTIVE 0, PROJECTION_ORTHOGRAPHIC 1 (scene/constants.js)
            raise FileError(path, f"{at}.projection", "0 (PROJECTION_PERSPECTIVE): the toolkit's camera is a perspective one",
                            repr(comp.get("projection")))
        cam = dict(CAMERA_DEFAULTS)  # a key the scene leaves out is the component's default
        for key, ours in (("nearClip", "near"), ("farClip", "far"), ("fov", "fov")):
            if key in comp:
                cam[ours] = number(path, f"{at}.{key}", comp[key])
                where[f"camera.{ours}"] = f"{path.name} {at}.{key}"
        if comp.get("horizontalFov") is True:
            cam["horizontal_fov"] = cam.pop("fov")
            notes.append(f"camera.fov: horizontalFov is true: fov {cam['horizontal_fov']:g}° is horizontal")
        forward = -_world(path, ents, ckey)[:, 2]
    sun = sun_above(towards, forward, notes)
    return Found(ENGINE, settings, camera=cam, sun=sun, light=None if lkey is None else str(ents[lkey].get("name", lkey)),
                 camera_name=None if ckey is None else str(ents[ckey].get("name", ckey)), where=where, notes=tuple(notes))


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with ``changes`` written into the light entity's ``components.light``."""
    ents = _entities(path, text)
    lkey = _pick(path, ents, "light", _is_directional, found.light, "--light-node")
    if lkey is None:
        raise FileError(path, "entities", "a directional light to write to", "none")
    for key, v in changes.items():
        if key in DIRECT:
            text = jsontext.put(text, ("entities", lkey, "components", "light", key), v)
        elif key in ENUMS:
            number_ = next(i for i, n in ENUMS[key].items() if n == v)
            text = jsontext.put(text, ("entities", lkey, "components", "light", key), number_)
        else:
            raise ValueError(f"{path.name}: {key} is not kept in a PlayCanvas light component (it keeps: {', '.join(DIRECT + tuple(ENUMS))})")
    return text
