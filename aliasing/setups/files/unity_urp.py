"""Unity URP: the ``UniversalRenderPipelineAsset`` (``.asset``) and, optionally, a ``.unity`` scene's
main camera and directional light.

Both are Unity's text serialization (``aliasing.setups.files._unity_yaml``; Unity's manual *Format of Text
Serialized files*).  The asset's fields, as ``UniversalRenderPipelineAsset.cs`` declares them
(``com.unity.render-pipelines.universal/Runtime/Data/UniversalRenderPipelineAsset.cs``,
Unity-Technologies/Graphics as stored, the release :mod:`aliasing.setups.unity_urp` reads), map to the
profile's keys: ``m_ShadowDistance`` [m] → ``shadowDistance``, ``m_ShadowCascadeCount``,
``m_Cascade2Split``, ``m_Cascade3Split: {x, y}``, ``m_Cascade4Split: {x, y, z}`` (fractions),
``m_CascadeBorder``, ``m_MainLightShadowmapResolution`` [texels], ``m_ShadowDepthBias`` and
``m_ShadowNormalBias`` [texels], ``m_SoftShadowsSupported`` (0/1) and ``m_SoftShadowQuality``
(the enum ``SoftShadowQuality``: 1 Low, 2 Medium, 3 High).  ``m_ConservativeEnclosingSphere`` and
``m_MainLightShadowsSupported`` are read into ``notes`` (the profile does not model them).

In a scene: the directional ``Light`` (class 108, ``m_Type: 1``) with ``m_Shadows.m_Type`` (0 none,
1 Hard, 2 Soft), ``m_Shadows.m_Bias`` and ``m_Shadows.m_NormalBias`` [texels] → ``light.shadows``,
``light.shadowBias``, ``light.shadowNormalBias``; its ``UniversalAdditionalLightData``
(``Runtime/UniversalAdditionalLightData.cs``: ``m_UsePipelineSettings`` 0/1, ``m_SoftShadowQuality``
0 UsePipelineSettings … 3 High); the ``Camera`` (class 20): ``near clip plane``, ``far clip plane`` [m]
and ``field of view``, which Unity stores VERTICAL in degrees (``Camera.fieldOfView``; the
inspector's ``m_FOVAxisMode`` only chooses which axis it shows); and each one's ``Transform``
``m_LocalRotation`` quaternion, composed up its ``m_Father`` chain.  Unity's frame is left-handed
(x right, y up, z forward); the light shines along its +Z and the camera looks along its +Z.

Examples
--------
>>> from pathlib import Path
>>> text = ("%YAML 1.1\\n%TAG !u! tag:unity3d.com,2011:\\n--- !u!114 &11400000\\nMonoBehaviour:\\n"
...         "  m_ShadowCascadeCount: 4\\n  m_Cascade4Split: {x: 0.067, y: 0.2, z: 0.467}\\n")
>>> found = read([(Path("URP.asset"), text)], None, None)
>>> found.settings
{'shadowCascadeCount': 4, 'cascade4Split.x': 0.067, 'cascade4Split.y': 0.2, 'cascade4Split.z': 0.467}
>>> patch(Path("URP.asset"), text, {"cascade4Split.y": 0.25}, found).splitlines()[-1]
'  m_Cascade4Split: {x: 0.067, y: 0.25, z: 0.467}'
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ._native import coerce, number_text, pairs, splice, text_of, typed_changes
from ._unity_yaml import WHAT, Document, Scalar, parse, ref, scalar
from .common import FileError, Found, sun_from_directions

ENGINE = "unity-urp"
TITLE = "Unity URP asset (UniversalRenderPipelineAsset .asset YAML) and a .unity scene's camera and directional light"
SOURCE = ("Unity-Technologies/Graphics Packages/com.unity.render-pipelines.universal/Runtime/Data/UniversalRenderPipelineAsset.cs "
          "(commit 016e6c15, the serialized shadow fields), Runtime/UniversalAdditionalLightData.cs (commit 4627c944: m_UsePipelineSettings, "
          "m_SoftShadowQuality), UniversalRenderPipeline.cs GetMainLightIndex; Unity's manual 'Format of Text Serialized files' and "
          "'YAML Class ID Reference'")

#: Profile key -> the asset's field path.
ASSET = {"shadowDistance": ("m_ShadowDistance",), "shadowCascadeCount": ("m_ShadowCascadeCount",), "cascade2Split": ("m_Cascade2Split",),
         "cascade3Split.x": ("m_Cascade3Split", "x"), "cascade3Split.y": ("m_Cascade3Split", "y"),
         "cascade4Split.x": ("m_Cascade4Split", "x"), "cascade4Split.y": ("m_Cascade4Split", "y"), "cascade4Split.z": ("m_Cascade4Split", "z"),
         "cascadeBorder": ("m_CascadeBorder",), "mainLightShadowmapResolution": ("m_MainLightShadowmapResolution",),
         "shadowDepthBias": ("m_ShadowDepthBias",), "shadowNormalBias": ("m_ShadowNormalBias",),
         "supportsSoftShadows": ("m_SoftShadowsSupported",), "softShadowQuality": ("m_SoftShadowQuality",)}
#: Profile key -> the Light's field path.
LIGHT = {"light.shadows": ("m_Shadows", "m_Type"), "light.shadowBias": ("m_Shadows", "m_Bias"), "light.shadowNormalBias": ("m_Shadows", "m_NormalBias")}
#: Profile key -> the UniversalAdditionalLightData's field path.
EXTRA = {"light.usePipelineSettings": ("m_UsePipelineSettings",), "light.softShadowQuality": ("m_SoftShadowQuality",)}
ENUMS = {"softShadowQuality": {1: "Low", 2: "Medium", 3: "High"},
         "light.softShadowQuality": {0: "UsePipelineSettings", 1: "Low", 2: "Medium", 3: "High"},
         "light.shadows": {1: "Hard", 2: "Soft"}}
BOOLS = ("supportsSoftShadows", "light.usePipelineSettings")
LIGHT_CLASS, CAMERA_CLASS, TRANSFORM_CLASSES, GAMEOBJECT_CLASS, RENDER_SETTINGS_CLASS = 108, 20, (4, 224), 1, 104


def sniff(path: Path, text: str) -> bool:
    """Unity's YAML with a URP asset's shadow fields, or a ``.unity`` scene."""
    if not text.lstrip().startswith("%YAML") or "--- !u!" not in text:
        return False
    return path.suffix.lower() == ".unity" or "m_ShadowCascadeCount:" in text or "\nLight:" in text


def _at(fields: dict, where: tuple) -> Any:
    node: Any = fields
    for p in where:
        if not isinstance(node, dict) or p not in node:
            return None
        node = node[p]
    return node


def _decode(path: Path, key: str, node: Scalar) -> Any:
    text = node.text.strip()
    if key in ENUMS:
        names = ENUMS[key]
        if not (text.lstrip("-").isdigit() and int(text) in names):
            raise FileError(path, f"line {node.line} / {key}", "one of " + ", ".join(f"{k} ({v})" for k, v in names.items()), repr(text))
        return names[int(text)]
    if key in BOOLS:
        if text not in ("0", "1"):
            raise FileError(path, f"line {node.line} / {key}", "0 or 1", repr(text))
        return text == "1"
    return coerce(path, node.line, ENGINE, key, text)


def _encode(key: str, value: Any) -> str:
    if key in ENUMS:
        return str(next(k for k, v in ENUMS[key].items() if v == value))
    return number_text(value)


def _number(path: Path, node: Any, what: str, unit: str) -> float:
    s = scalar(node)
    try:
        v = float(s.text) if s is not None else math.nan
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        where = f"line {s.line} / {what}" if s is not None else what
        raise FileError(path, where, f"a finite number [{unit}]" if unit else "a finite number", repr(s.text) if s is not None else "no one-line value")
    return v


class _Scene:
    """One file's objects by file id, with the names of their GameObjects."""

    def __init__(self, path: Path, docs: list[Document]) -> None:
        self.path = path
        self.docs = [d for d in docs if d.fields]
        self.by_id = {d.file_id: d for d in self.docs}
        self.names = {d.file_id: (scalar(d.fields.get("m_Name")).text if scalar(d.fields.get("m_Name")) else "")
                      for d in self.docs if d.class_id == GAMEOBJECT_CLASS}

    def name(self, d: Document) -> str:
        return self.names.get(ref(d.fields.get("m_GameObject")) or "", "") or f"&{d.file_id}"

    def tag(self, d: Document) -> str:
        """The ``m_TagString`` of ``d``'s GameObject ("" where none)."""
        go = self.by_id.get(ref(d.fields.get("m_GameObject")) or "")
        s = scalar(go.fields.get("m_TagString")) if go is not None else None
        return s.text.strip() if s is not None else ""

    def component(self, go: str | None, test) -> Document | None:
        return next((d for d in self.docs if ref(d.fields.get("m_GameObject")) == go and test(d)), None)

    def rotation(self, d: Document, notes: list[str]) -> np.ndarray:
        """The world rotation (x, y, z, w) of ``d``'s GameObject: its Transform up the m_Father chain."""
        q = np.array([0.0, 0.0, 0.0, 1.0])
        t = self.component(ref(d.fields.get("m_GameObject")), lambda c: c.class_id in TRANSFORM_CLASSES)
        seen: set[str] = set()
        while t is not None:
            if t.file_id in seen:
                raise FileError(self.path, f"line {t.line} / m_Father", "a Transform hierarchy without a loop", f"a loop through &{t.file_id}")
            seen.add(t.file_id)
            flow = t.fields.get("m_LocalRotation")
            if not isinstance(flow, dict) or any(k not in flow for k in "xyzw"):
                raise FileError(self.path, f"line {t.line} / m_LocalRotation", "{x: , y: , z: , w: } (a quaternion)", "another value")
            local = np.array([_number(self.path, flow[k], "m_LocalRotation." + k, "") for k in "xyzw"])
            norm = float(np.linalg.norm(local))
            if not (norm > 1e-12 and math.isfinite(norm)):
                raise FileError(self.path, f"line {flow['x'].line} / m_LocalRotation", "a non-zero quaternion", "(0, 0, 0, 0)")
            q = _mul(local / norm, q)
            father = ref(t.fields.get("m_Father"))
            if father is None:
                break
            t = self.by_id.get(father)
            if t is None:
                notes.append(f"the parent Transform &{father} of {self.name(d)!r} is not in {self.path.name}: its rotation taken as none")
        return q


def _mul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The quaternion product a·b, (x, y, z, w)."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz])


def _forward(q: np.ndarray) -> np.ndarray:
    """Unity's +Z rotated by q, in a right-handed frame (z negated: x right, y up, −z forward)."""
    u, w = q[:3], q[3]
    v = np.array([0.0, 0.0, 1.0])
    r = v + 2.0 * w * np.cross(u, v) + 2.0 * np.cross(u, np.cross(u, v))
    return r * np.array([1.0, 1.0, -1.0])


def _pick(path: Path, docs: list[Document], scene: _Scene, name: str | None, what: str) -> Document | None:
    if name is not None:
        hit = [d for d in docs if scene.name(d) == name]
        if not hit:
            known = ", ".join(repr(scene.name(d)) for d in docs) or "none"
            raise FileError(path, what, f"the name of one of its {what}s ({known})", repr(name))
        return hit[0]
    if len(docs) > 1:
        raise FileError(path, what, f"one {what}, or {what}= naming one of " + ", ".join(repr(scene.name(d)) for d in docs), f"{len(docs)} of them")
    return docs[0] if docs else None


def _files(files: list[tuple[Path, str]]) -> tuple[tuple[Path, Document] | None, list[_Scene]]:
    asset: tuple[Path, Document] | None = None
    scenes = []
    for path, text in files:
        text_of(path, text, WHAT)
        if not sniff(path, text):
            raise FileError(path, "the whole file", WHAT + " of a URP asset or a .unity scene", "another file")
        docs = parse(path, text)
        for d in docs:
            if d.kind == "MonoBehaviour" and "m_ShadowCascadeCount" in d.fields:
                if asset is not None:
                    raise FileError(path, f"line {d.line}", "one URP asset", f"a second one (the first in {asset[0].name})")
                asset = (path, d)
        if any(d.class_id in (LIGHT_CLASS, CAMERA_CLASS) for d in docs):
            scenes.append(_Scene(path, docs))
    if asset is None and not scenes:
        path = files[0][0]
        raise FileError(path, "the whole file", "a URP asset (m_ShadowCascadeCount …) or a scene with a Light or Camera", "neither")
    return asset, scenes


def _enabled(docs: list[Document]) -> list[Document]:
    """The components not switched off (``m_Enabled: 0``); all of them where every one is."""
    on = [d for d in docs if not (scalar(d.fields.get("m_Enabled")) and d.fields["m_Enabled"].text.strip() == "0")]
    return on or docs


def _light(scene: _Scene, name: str | None, notes: list[str] | None = None) -> Document | None:
    """The directional light ``name``, else URP's main light: ``RenderSettings.sun`` (the scene's
    ``m_Sun``), else the brightest (``UniversalRenderPipeline.GetMainLightIndex``)."""
    lights = [d for d in scene.docs if d.class_id == LIGHT_CLASS and scalar(d.fields.get("m_Type")) and d.fields["m_Type"].text.strip() == "1"]
    if name is None and len(_enabled(lights)) > 1:
        lights = _enabled(lights)
        sun = next((ref(d.fields.get("m_Sun")) for d in scene.docs if d.class_id == RENDER_SETTINGS_CLASS), None)
        main = [d for d in lights if d.file_id == sun]
        if not main:
            power = {d.file_id: _number(scene.path, d.fields.get("m_Intensity"), "m_Intensity", "") for d in lights if "m_Intensity" in d.fields}
            top = max(power.values(), default=None)
            main = [d for d in lights if power.get(d.file_id) == top] if top is not None else []
        if len(main) == 1:
            if notes is not None:
                how = "RenderSettings m_Sun" if main[0].file_id == sun else "the brightest (m_Intensity)"
                notes.append(f"light {scene.name(main[0])!r}: URP's main light of {len(lights)} directional lights, {how} (GetMainLightIndex)")
            return main[0]
    return _pick(scene.path, lights, scene, name, "light")


def _camera(scene: _Scene, name: str | None, notes: list[str] | None = None) -> Document | None:
    """The camera ``name``, else the one camera, else the enabled one on the GameObject tagged MainCamera (``Camera.main``)."""
    cams = [d for d in scene.docs if d.class_id == CAMERA_CLASS]
    if name is None and len(cams) > 1:
        tagged = [d for d in _enabled(cams) if scene.tag(d) == "MainCamera"]
        if len(tagged) == 1:
            if notes is not None:
                notes.append(f"camera {scene.name(tagged[0])!r}: the one tagged MainCamera of {len(cams)} cameras (Camera.main)")
            return tagged[0]
    return _pick(scene.path, cams, scene, name, "camera")


def _extra(scene: _Scene, light: Document) -> Document | None:
    return scene.component(ref(light.fields.get("m_GameObject")), lambda c: c.kind == "MonoBehaviour" and "m_UsePipelineSettings" in c.fields)


def read(files: list[tuple[Path, str]], light: str | None, camera: str | None) -> Found:
    """The URP asset's settings and, from a scene, the light's settings, the camera and the sun.

    ``files``: (path, text) pairs, the URP asset and at most one scene; ``light``, ``camera``: the
    names of the directional light and the camera (their GameObjects' ``m_Name``) where a scene holds
    several.  Returns the settings in the profile's keys and types, the camera (near, far [m], vertical
    fov [deg]) and the sun (elevation, azimuth [deg]) from a scene, where each was found, and notes.
    A damaged or foreign file raises :class:`~aliasing.setups.files.common.FileError` (file, line, key).
    """
    files = pairs(files, light, camera)
    asset, scenes = _files(files)
    settings: dict[str, Any] = {}
    where: dict[str, str] = {}
    notes: list[str] = []

    def take(path: Path, fields: dict, table: dict) -> None:
        for key, at in table.items():
            node = _at(fields, at)
            if node is None:
                continue
            s = scalar(node)
            if s is None:
                raise FileError(path, ".".join(at), "a one-line value", "a block")
            if key == "light.shadows" and s.text.strip() == "0":
                notes.append(f"{path.name} line {s.line}: the light casts no shadows (m_Shadows.m_Type 0); light.shadows not taken")
                continue
            settings[key] = _decode(path, key, s)
            where[key] = f"{path.name} line {s.line} ({'.'.join(at)})"

    if asset is not None:
        path, doc = asset
        take(path, doc.fields, ASSET)
        for field, words in (("m_ConservativeEnclosingSphere", "conservative enclosing sphere"), ("m_MainLightShadowsSupported", "main light shadows")):
            s = scalar(doc.fields.get(field))
            if s is not None:
                notes.append(f"{field} {s.text} ({words} {'on' if s.text.strip() == '1' else 'off'}): read, not modelled")
    cam, sun, light_name, camera_name = None, None, None, None
    scene = scenes[0] if scenes else None
    if len(scenes) > 1:
        raise FileError(scenes[1].path, "the whole file", "one scene with the camera and the light", "a second scene")
    if scene is not None:
        ld, cd = _light(scene, light, notes), _camera(scene, camera, notes)
        if ld is not None:
            light_name = scene.name(ld)
            take(scene.path, ld.fields, LIGHT)
            extra = _extra(scene, ld)
            if extra is not None:
                take(scene.path, extra.fields, EXTRA)
        if cd is not None:
            camera_name = scene.name(cd)
            cam = {}
            for field, key, unit in (("near clip plane", "near", "m"), ("far clip plane", "far", "m"), ("field of view", "fov", "deg")):
                if field in cd.fields:
                    cam[key] = _number(scene.path, cd.fields[field], field, unit)
                    where[f"camera.{key}"] = f"{scene.path.name} line {cd.fields[field].line} ({field})"
            ortho = scalar(cd.fields.get("orthographic"))
            if ortho is not None and ortho.text.strip() == "1":
                raise FileError(scene.path, f"line {ortho.line} / orthographic", "a perspective camera (orthographic: 0)", "1")
            notes.append("camera: Unity stores the field of view vertical [deg] (m_FOVAxisMode only picks the inspector's axis); near and far in metres")
            mode = scalar(cd.fields.get("m_projectionMatrixMode"))
            if mode is not None and mode.text.strip() == "2":
                notes.append("camera: a physical camera (m_projectionMatrixMode 2): the stored field of view is taken; "
                             "the sensor's gate fit (m_GateFitMode, m_SensorSize, m_LensShift) is not modelled")
        if ld is not None:
            towards = -_forward(scene.rotation(ld, notes))
            if cd is not None:
                forward = _forward(scene.rotation(cd, notes))
            else:
                forward = np.array([0.0, 0.0, -1.0])
                notes.append("no camera in the scene: the sun's azimuth is taken from the world's +Z (Unity's forward)")
            elevation, azimuth = (round(a, 4) + 0.0 for a in sun_from_directions(towards, forward))  # float32 quaternions: 1e-4° is below their precision
            where["sun"] = f"{scene.path.name} Transform of {light_name!r} (m_LocalRotation: the light shines along its +Z)"
            if elevation > 0:
                sun = (elevation, azimuth)
            else:
                notes.append(f"the light {light_name!r} shines from {-elevation:.4g}° below the horizon: no sun taken")
    return Found(ENGINE, settings, cam or None, sun, light_name, camera_name, where, tuple(notes))


def patch(path: Path, text: str, changes: Mapping[str, Any], found: Found) -> str:
    """``text`` with each changed value rewritten in its field's line (the rest byte for byte).

    The reader interface (:mod:`aliasing.setups.files.common`): ``changes`` are profile keys to values,
    typed and range-checked by the profile (ValueError naming the key); ``found`` is what :func:`read`
    found in ``text``.  Reading the result back gives ``changes`` exactly.
    """
    new = typed_changes(path, ENGINE, changes)
    asset, scenes = _files([(path, text)])
    lines = text.splitlines(keepends=True)
    edits: list[tuple[int, int, int, str]] = []
    for key, value in new.items():
        if key in ASSET:
            fields, at = (asset[1].fields if asset else None), ASSET[key]
            holder = "the URP asset"
        else:
            scene = scenes[0] if scenes else None
            ld = _light(scene, found.light) if scene else None
            holder = "the scene's directional light"
            if key in LIGHT:
                fields, at = (ld.fields if ld else None), LIGHT[key]
            else:
                extra = _extra(scene, ld) if ld else None
                fields, at = (extra.fields if extra else None), EXTRA[key]
                holder = "the light's UniversalAdditionalLightData"
        node = scalar(_at(fields, at)) if fields is not None else None
        if node is None:
            raise ValueError(f"{key}: {path.name} has no one-line {'.'.join(at)} of {holder} to rewrite")
        edits.append((node.line, node.start, node.end, _encode(key, value)))
    for line, start, end, written in sorted(edits, key=lambda e: (e[0], -e[1])):  # right to left on a line
        splice(lines, line, start, end, written)
    return "".join(lines)
