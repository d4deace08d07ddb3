"""Babylon.js's ``.babylon`` scene: the JSON of ``SceneSerializer.Serialize(scene)`` at @babylonjs/core 9.35.0.

Read as the engine writes it (files of the npm package ``@babylonjs/core`` 9.35.0):

* ``Misc/sceneSerializer.js`` ``Serialize``: ``cameras[]``, ``activeCameraID``, ``lights[]``,
  ``shadowGenerators[]``, ``useRightHandedSystem``;
* ``Cameras/camera.pure.js`` ``serialize``: ``fov`` [rad], ``fovMode`` (``FOVMODE_VERTICAL_FIXED`` 0,
  ``FOVMODE_HORIZONTAL_FIXED`` 1, line 1241), ``minZ``, ``maxZ``, ``position``; a FreeCamera's
  ``rotation`` (yaw ``y``, pitch ``x``: forward is ``Matrix.RotationYawPitchRoll(y, x, z)`` applied to
  +z), a ``lockedTarget``, or an ArcRotateCamera's ``target`` with ``alpha``, ``beta``, ``radius``;
* ``Lights/light.pure.js`` ``serialize``: ``type`` (``getTypeID``: 1 a DirectionalLight), ``id``,
  ``name``, ``direction`` (the light shines along it); ``shadowFrustumSize``, ``shadowMinZ``,
  ``shadowMaxZ`` (``Lights/shadowLight.js``);
* ``Lights/Shadows/shadowGenerator.js`` ``serialize`` (line 1587) and ``Parse`` (line 1634):
  ``className``, ``lightId``, ``mapSize``, ``bias``, ``normalBias``, ``darkness``, ``forceBackFacesOnly``,
  ``frustumEdgeFalloff``, ``contactHardeningLightSizeUVRatio``, ``filteringQuality`` (QUALITY_HIGH 0,
  MEDIUM 1, LOW 2, lines 1783–1801), ``depthScale``, the blur settings, and the filter as flags
  (``usePercentageCloserFiltering``, ``useContactHardeningShadow``, ``usePoissonSampling``, the four
  exponential ones): ``Parse`` sets the first true one in that order, none leaves the class's default;
* ``Lights/Shadows/cascadedShadowGenerator.pure.js`` ``serialize`` (line 930): ``numCascades``,
  ``stabilizeCascades``, ``lambda``, ``cascadeBlendPercentage``, ``depthClamp``, ``autoCalcDepthBounds``,
  ``shadowMaxZ``, ``minDistance``, ``maxDistance``.

Babylon's world is left-handed (x right, y up, z forward) unless ``useRightHandedSystem``: the
sun's azimuth (positive to the camera's right) is taken in that frame.

Examples
--------
>>> import json
>>> scene = {"cameras": [{"id": "c", "name": "c", "type": "FreeCamera", "fov": 0.8, "minZ": 0.5, "maxZ": 800,
...          "position": [0, 0, 0], "rotation": [0, 0, 0]}], "activeCameraID": "c",
...          "lights": [{"id": "sun", "name": "sun", "type": 1, "direction": [-1, -1, 0]}],
...          "shadowGenerators": [{"className": "CascadedShadowGenerator", "lightId": "sun", "mapSize": 2048, "lambda": 0.7}]}
>>> f = read([(Path("scene.babylon"), json.dumps(scene))], None, None)
>>> f.settings, round(f.camera["fov"], 4), f.sun
({'class': 'CascadedShadowGenerator', 'mapSize': 2048, 'lambda': 0.7}, 45.8366, (45.0, 90.0))
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from . import jsontext
from ..babylon import PROFILES
from .common import FileError, Found, direction, number, one_file, pick, sun_above, vector

ENGINE = "babylon"
#: the profile whose settings the file keeps (values are checked against it before a patch)
PROFILE = PROFILES[0]
TITLE = "a Babylon.js .babylon scene (SceneSerializer JSON)"
SOURCE = ("npm @babylonjs/core 9.35.0: Misc/sceneSerializer.js Serialize, Lights/Shadows/shadowGenerator.js serialize (line 1587) "
          "and Parse (line 1634), Lights/Shadows/cascadedShadowGenerator.pure.js serialize (line 930), Cameras/camera.pure.js")

#: generator JSON keys read straight into the profile's keys of the same name
DIRECT = ("mapSize", "bias", "normalBias", "darkness", "forceBackFacesOnly", "frustumEdgeFalloff", "contactHardeningLightSizeUVRatio",
          "depthScale", "blurBoxOffset", "blurKernel", "blurScale", "useKernelBlur", "numCascades", "stabilizeCascades", "lambda",
          "cascadeBlendPercentage", "depthClamp", "autoCalcDepthBounds", "shadowMaxZ", "minDistance", "maxDistance")
#: the filter flags in the order ShadowGenerator.Parse tries them, and the filter each sets
FLAGS = (("usePercentageCloserFiltering", "FILTER_PCF"), ("useContactHardeningShadow", "FILTER_PCSS"),
         ("usePoissonSampling", "FILTER_POISSONSAMPLING"), ("useExponentialShadowMap", "FILTER_EXPONENTIALSHADOWMAP"),
         ("useBlurExponentialShadowMap", "FILTER_BLUREXPONENTIALSHADOWMAP"),
         ("useCloseExponentialShadowMap", "FILTER_CLOSEEXPONENTIALSHADOWMAP"),
         ("useBlurCloseExponentialShadowMap", "FILTER_BLURCLOSEEXPONENTIALSHADOWMAP"))
QUALITIES = ("QUALITY_HIGH", "QUALITY_MEDIUM", "QUALITY_LOW")
#: generator keys written by serialize that the profile does not model, at their defaults (said in the notes when set otherwise)
IGNORED = {"transparencyShadow": False, "debug": False, "penumbraDarkness": 1, "freezeShadowCastersBoundingInfo": False}
LIGHT_KEYS = {"shadowFrustumSize": "light.shadowFrustumSize", "shadowMinZ": "light.shadowMinZ", "shadowMaxZ": "light.shadowMaxZ"}


def sniff(path: Path, text: str) -> bool:
    """A ``.babylon`` file, or JSON text with Babylon's scene keys."""
    if path.suffix.lower() == ".babylon":
        return True
    head = text.lstrip()[:1]
    return head == "{" and '"shadowGenerators"' in text and '"cameras"' in text


def _scene(path: Path, text: str) -> dict:
    data = jsontext.load(path, text)
    if not isinstance(data, dict):
        raise FileError(path, "the top level", "a JSON object (a Babylon.js scene)", type(data).__name__)
    for key in ("lights", "cameras", "shadowGenerators"):
        if key in data and not isinstance(data[key], list):
            raise FileError(path, key, "a list", type(data[key]).__name__)
    return data


def _generator(path: Path, data: dict, light: str | None) -> tuple[int, dict, dict]:
    gens = [g for g in data.get("shadowGenerators", []) if isinstance(g, dict)]
    lights = {l.get("id"): l for l in data.get("lights", []) if isinstance(l, dict)}
    if not gens:
        raise FileError(path, "shadowGenerators", "a shadow generator of a directional light (SceneSerializer writes shadowGenerators[])",
                        "none")
    names = []
    for g in gens:
        lt = lights.get(g.get("lightId"), {})
        names.append(str(lt.get("name", g.get("lightId"))))
    want = light
    if want is not None and want not in names:
        ids = [str(g.get("lightId")) for g in gens]
        if want in ids:
            want = names[ids.index(want)]
    i = pick(path, "light", names, want, "--light-node")
    g = gens[i]
    lt = lights.get(g.get("lightId"))
    if lt is None:
        raise FileError(path, f"shadowGenerators[{i}].lightId", "the id of one of lights[]", repr(g.get("lightId")))
    if lt.get("type") != 1:
        raise FileError(path, f"light {names[i]!r} type", "1 (a DirectionalLight)", repr(lt.get("type")))
    return data["shadowGenerators"].index(g), g, lt


def _camera(path: Path, data: dict, camera: str | None) -> tuple[int, dict] | None:
    cams = [c for c in data.get("cameras", []) if isinstance(c, dict)]
    if not cams:
        return None
    names = [str(c.get("name", c.get("id"))) for c in cams]
    if camera is None:
        active = [i for i, c in enumerate(cams) if c.get("id") == data.get("activeCameraID")]
        if active:
            return active[0], cams[active[0]]
    i = pick(path, "camera", names, camera, "--camera-node")
    return i, cams[i]


def _forward(path: Path, where: str, c: dict) -> np.ndarray:
    """The camera's forward direction in Babylon's world."""
    pos = vector(path, f"{where}.position", c.get("position", [0, 0, 0]))
    if c.get("type") == "ArcRotateCamera" or "alpha" in c:
        a = number(path, f"{where}.alpha", c.get("alpha"))
        b = number(path, f"{where}.beta", c.get("beta"))
        target = vector(path, f"{where}.target", c.get("target", [0, 0, 0]))
        # ArcRotateCamera._getViewMatrix: position = target + radius·(cos α sin β, cos β, sin α sin β)
        return direction(path, f"{where}.alpha/beta", -np.array([math.cos(a) * math.sin(b), math.cos(b), math.sin(a) * math.sin(b)]))
    if c.get("lockedTarget") is not None:
        return direction(path, f"{where}.lockedTarget", vector(path, f"{where}.lockedTarget", c["lockedTarget"]) - pos)
    x, y, _ = vector(path, f"{where}.rotation", c.get("rotation", [0, 0, 0]))
    # Matrix.RotationYawPitchRoll(yaw y, pitch x, roll z) applied to (0, 0, 1)
    return np.array([math.sin(y) * math.cos(x), -math.sin(x), math.cos(y) * math.cos(x)])


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The shadow generator, its light and the active camera of one ``.babylon`` scene."""
    path, text = one_file(files, "one .babylon scene for Babylon.js")
    data = _scene(path, text)
    gi, g, lt = _generator(path, data, light)
    name = str(lt.get("name", lt.get("id")))
    at = f"shadowGenerators[{gi}]"
    settings: dict[str, Any] = {}
    where: dict[str, str] = {}
    notes: list[str] = []
    cls = g.get("className", "ShadowGenerator")
    if cls not in ("ShadowGenerator", "CascadedShadowGenerator"):
        raise FileError(path, f"{at}.className", "ShadowGenerator or CascadedShadowGenerator", repr(cls))
    settings["class"], where["class"] = cls, f"{path.name} {at}.className"
    for key in DIRECT:
        if key in g:
            settings[key], where[key] = g[key], f"{path.name} {at}.{key}"
    for flag, name_ in FLAGS:
        if g.get(flag):
            settings["filter"], where["filter"] = name_, f"{path.name} {at}.{flag}"
            break
    if "filteringQuality" in g:
        q = g["filteringQuality"]
        if isinstance(q, bool) or q not in (0, 1, 2):
            raise FileError(path, f"{at}.filteringQuality", "0 (QUALITY_HIGH), 1 (QUALITY_MEDIUM) or 2 (QUALITY_LOW)", repr(q))
        settings["filteringQuality"], where["filteringQuality"] = QUALITIES[q], f"{path.name} {at}.filteringQuality"
    li = data["lights"].index(lt)
    for key, ours in LIGHT_KEYS.items():
        if key in lt:
            settings[ours], where[ours] = lt[key], f"{path.name} lights[{li}].{key}"
    unused = [f"{k} {g[k]!r}" for k, default in IGNORED.items() if k in g and g[k] != default]
    if unused:
        notes.append(f"{at}: {', '.join(unused)} (not modelled by the toolkit)")
    handed = bool(data.get("useRightHandedSystem", False))
    towards = -direction(path, f"lights[{li}].direction", vector(path, f"lights[{li}].direction", lt.get("direction")))
    cam, sun, cname = None, None, None
    found_cam = _camera(path, data, camera)
    if found_cam is not None:
        ci, c = found_cam
        cname = str(c.get("name", c.get("id")))
        cw = f"cameras[{ci}]"
        if c.get("mode", 0) != 0:  # Camera.PERSPECTIVE_CAMERA 0, ORTHOGRAPHIC_CAMERA 1 (Cameras/camera.pure.js)
            raise FileError(path, f"{cw}.mode", "0 (PERSPECTIVE_CAMERA): the toolkit's camera is a perspective one", repr(c.get("mode")))
        cam = {}
        for key, ours in (("minZ", "near"), ("maxZ", "far")):
            if key in c:
                cam[ours], where[f"camera.{ours}"] = number(path, f"{cw}.{key}", c[key]), f"{path.name} {cw}.{key}"
        if "fov" in c:
            fov = number(path, f"{cw}.fov", c["fov"], "a number [rad]")
            mode = c.get("fovMode", 0)
            if mode not in (0, 1) or isinstance(mode, bool):
                raise FileError(path, f"{cw}.fovMode", "0 (FOVMODE_VERTICAL_FIXED) or 1 (FOVMODE_HORIZONTAL_FIXED)", repr(mode))
            deg = math.degrees(fov)
            cam["horizontal_fov" if mode == 1 else "fov"] = deg
            where["camera.fov"] = f"{path.name} {cw}.fov"
            notes.append(f"camera.fov {fov:.12g} rad ({'horizontal' if mode == 1 else 'vertical'}) = {deg:.12g}°")
        fwd = _forward(path, cw, c)
        flip = np.array([1.0, 1.0, 1.0 if handed else -1.0])  # left-handed: mirror z into the right-handed frame
        sun = sun_above(towards * flip, fwd * flip, notes)
    else:
        notes.append("no camera in the file: the sun's azimuth is --sun's")
    return Found(ENGINE, settings, camera=cam, sun=sun, light=name, camera_name=cname, where=where, notes=tuple(notes))


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with ``changes`` (the profile's keys) written into the generator's (or its light's) JSON keys."""
    data = _scene(path, text)
    gi, g, lt = _generator(path, data, found.light)
    li = data["lights"].index(lt)
    light_keys = {v: k for k, v in LIGHT_KEYS.items()}
    for key, value in changes.items():
        if key in DIRECT:
            text = jsontext.put(text, ("shadowGenerators", gi, key), value)
        elif key in light_keys:
            text = jsontext.put(text, ("lights", li, light_keys[key]), value)
        elif key == "filteringQuality":
            text = jsontext.put(text, ("shadowGenerators", gi, key), QUALITIES.index(value))
        elif key == "filter":
            if value == "FILTER_NONE":  # Parse sets the first true flag; none true leaves the class's default filter
                raise ValueError(f"{path.name}: a .babylon scene cannot keep filter FILTER_NONE: ShadowGenerator.Parse leaves the class's "
                                 "default filter when no filter flag is true (CascadedShadowGenerator: FILTER_PCF); null writes no flag")
            for flag, name_ in FLAGS:
                if flag in g or name_ == value:
                    text = jsontext.put(text, ("shadowGenerators", gi, flag), name_ == value)
        elif key == "class":
            text = jsontext.put(text, ("shadowGenerators", gi, "className"), value)
        else:
            raise ValueError(f"{path.name}: {key} is not kept in a .babylon scene (the keys it keeps: {', '.join(DIRECT + tuple(light_keys))}, "
                             "filter, filteringQuality, class)")
    return text
