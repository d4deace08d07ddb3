"""PlayCanvas 2: the LightComponent of a directional light and its cascaded shadow.

Read from npm ``playcanvas`` 2.23.3 (its ES modules under ``build/playcanvas/src``; run in node by
``tests/test_engines_js.py`` with a NullGraphicsDevice).  Files below are relative to that
folder: ``scene/light.js`` (the Light the component drives), ``framework/components/light/
component.js`` (the component's setters), ``scene/renderer/shadow-renderer-directional.js``
(``cull``: the splits and the fit).

Settings as the LightComponent spells them (``entity.addComponent("light", {...})``):

* ``numCascades`` 1 (light.js:134; the component floors and clamps to 1–4, component.js:163);
* ``cascadeDistribution`` 0.5 (light.js:136; clamped to [0, 1], component.js:187): the
  practical split's λ;
* ``cascadeBlend`` 0 (light.js:135; clamped to [0, 1], component.js:169);
* ``shadowDistance`` 40 (light.js:150): shadows end at min(camera far, shadowDistance);
* ``shadowResolution`` 1024 (light.js:151): the side of the one shadow map the cascades share;
* ``shadowBias`` 0.05 (component.js:64; the light gets −0.01·clamp(shadowBias, 0, 1), line 157);
* ``normalOffsetBias`` 0 (light.js:154; clamped to [0, 1], component.js:193);
* ``shadowType`` SHADOW_PCF3_32F (light.js:115), ``vsmBlurSize`` 11 (light.js:116),
  ``vsmBias`` 0.0025 (light.js:118), ``shadowSamples`` 16 and ``penumbraSize`` 1 (PCSS,
  light.js:161, 163);
* the material's ``cull`` CULLFACE_BACK (``scene/materials/material.js``:72).

The splits (``generateSplitDistances``, lines 182–191): practical, λ = cascadeDistribution, from
the camera's near to min(far, shadowDistance), stored in a Float32Array (light.js:226): the
ends are float32 numbers.  The fit (``cull``, lines 84–117): per cascade the sphere around its 8
corners' average (radius unrounded), an orthographic camera of half height = radius (aspect 1),
its centre snapped to radius/(0.25·shadowResolution); the cascades share one map, 2×2 when
there are more than one (light.js:46–51): each cascade gets half the resolution.  The shadow
camera's depth spans the shadow casters' bounds (lines 161–179).

The bias rule (PCF, the default): the caster pass has a rasterizer depth bias, constant and
slope factor both −1000·light.shadowBias = 10·shadowBias (light.js:746–755; WebGL
``gl.polygonOffset(slope, constant)``); the receiver's depth is lowered by 0.0001 of the
shadow camera's depth range (``lightFunctionShadow.js``: ``saturate(z) − 0.0001``) and its
position moves along the world normal by normalOffsetBias world units when that is non-zero.
The constant factor's unit (the depth format's smallest step) is 2⁻²⁴ of the range at most for
the 32-bit formats and 1/65535 for the 16-bit ones.  Faces: the material's cull mode, as in
the main pass (``shadow-renderer.js`` ``submitCasters``; CULLFACE_BACK: the front faces cast).

Example
-------
>>> from aliasing.setups import build
>>> s = build("playcanvas", {"numCascades": 4}, camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080")
>>> s.pipeline.far_i[-1], s.pipeline.resolution, s.pipeline.layout
(40.0, 512, 'atlas 2x2 of 1024')
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable

LIGHT = "scene/light.js"
COMP = "framework/components/light/component.js"
DIR = "scene/renderer/shadow-renderer-directional.js"
AT = " (npm playcanvas 2.23.3, build/playcanvas/src)"
#: shadowType names and their numbers (scene/constants.js lines 71–84)
SHADOW_TYPES = {"SHADOW_PCF3_32F": 0, "SHADOW_VSM_16F": 2, "SHADOW_VSM_32F": 3, "SHADOW_PCF5_32F": 4, "SHADOW_PCF1_32F": 5,
                "SHADOW_PCSS_32F": 6, "SHADOW_PCF1_16F": 7, "SHADOW_PCF3_16F": 8, "SHADOW_PCF5_16F": 9}
#: material cull modes (platform/graphics/constants.js lines 56–58) and the faces that cast
CULL = {"CULLFACE_BACK": "front", "CULLFACE_FRONT": "back", "CULLFACE_NONE": "both"}
CULL_VALUES = {"CULLFACE_NONE": 0, "CULLFACE_BACK": 1, "CULLFACE_FRONT": 2}
#: the numbers and the older names of the shadow types (scene/constants.js lines 71–84: SHADOW_PCF3 = 0, SHADOW_VSM16 = 2, …)
SHADOW_ALIASES = {**{v: k for k, v in SHADOW_TYPES.items()}, "SHADOW_PCF3": "SHADOW_PCF3_32F", "SHADOW_VSM16": "SHADOW_VSM_16F",
                  "SHADOW_VSM32": "SHADOW_VSM_32F", "SHADOW_PCF5": "SHADOW_PCF5_32F", "SHADOW_PCF1": "SHADOW_PCF1_32F"}


def _settings() -> tuple[Setting, ...]:
    return (
        Setting("castShadows", False, "", "bool", source=f"{COMP}:67, 124–127{AT}",
                doc="the light casts shadows only when true (the profile evaluates the shadow it would cast)"),
        Setting("numCascades", 1, "", "int", (None, None), clamp=(1, 4), source=f"{LIGHT}:134; {COMP}:163{AT}",
                doc="number of cascades (floored and clamped to 1–4); more than one share the map in a 2×2 grid"),
        Setting("cascadeDistribution", 0.5, "", "float", (None, None), clamp=(0.0, 1.0), source=f"{LIGHT}:136; {COMP}:187{AT}",
                doc="the practical split's λ: 0 uniform, 1 logarithmic"),
        Setting("cascadeBlend", 0.0, "fraction of a cascade's far distance", "float", (None, None), clamp=(0.0, 1.0),
                source=f"{LIGHT}:135; {COMP}:169{AT}", doc="dithered blend into the next cascade from (1 − cascadeBlend)·end to the end"),
        Setting("shadowDistance", 40.0, "world units", "float", (0.0, None), source=f"{LIGHT}:150; {DIR}:70{AT}",
                doc="shadows end at min(camera far, shadowDistance)"),
        Setting("shadowResolution", 1024, "texels", "int", (1, 16384), source=f"{LIGHT}:151, 379–388{AT}",
                doc="side of the one shadow map (the device's maxTextureSize caps it)"),
        Setting("shadowBias", 0.05, "", "float", (None, None), clamp=(0.0, 1.0), source=f"{COMP}:64, 155–158; {LIGHT}:746–755{AT}",
                doc="caster depth bias: constant and slope factor 10·clamp(shadowBias, 0, 1)"),
        Setting("normalOffsetBias", 0.0, "world units", "float", (None, None), clamp=(0.0, 1.0), source=f"{LIGHT}:154; {COMP}:193{AT}",
                doc="the receiver's looked-up point moves along its world normal by this"),
        Setting("shadowType", "SHADOW_PCF3_32F", "", "choice", tuple(SHADOW_TYPES), aliases=SHADOW_ALIASES,
                source=f"{LIGHT}:115, 314–343; scene/constants.js:71–84{AT}",
                doc="PCF1/3/5: 1, 3×3, 5×5 filters; VSM: variance maps; PCSS: soft (needs float render targets)"),
        Setting("vsmBlurSize", 11, "texels", "int", (1, 25), source=f"{LIGHT}:116{AT}", doc="VSM blur kernel"),
        Setting("vsmBias", 0.0025, "", "float", (None, None), clamp=(0.0, 1.0), source=f"{LIGHT}:118; {COMP}:241{AT}", doc="VSM bias"),
        Setting("vsmBlurMode", "BLUR_GAUSSIAN", "", "choice", ("BLUR_BOX", "BLUR_GAUSSIAN"), aliases={0: "BLUR_BOX", 1: "BLUR_GAUSSIAN"},
                source=f"{LIGHT}:117; scene/constants.js:101–102{AT}", doc="VSM blur kernel shape"),
        Setting("shadowSamples", 16, "", "int", (1, 128), source=f"{LIGHT}:161{AT}", doc="PCSS samples"),
        Setting("penumbraSize", 1.0, "", "float", (0.0, None), source=f"{LIGHT}:163{AT}", doc="PCSS penumbra size"),
        Setting("penumbraFalloff", 1.0, "", "float", (0.0, None), source=f"{LIGHT}:164{AT}", doc="PCSS penumbra falloff"),
        Setting("shadowIntensity", 1.0, "", "float", (0.0, 1.0), source=f"{LIGHT}:153{AT}", doc="shadow strength (1: full)"),
        Setting("material.cull", "CULLFACE_BACK", "", "choice", tuple(CULL), aliases={v: k for k, v in CULL_VALUES.items()},
                source=f"scene/materials/material.js:72; platform/graphics/constants.js:56–58{AT}",
                doc="faces culled in the main and shadow passes: CULLFACE_BACK casts the front faces"),
    )


def splits(s: Mapping[str, Any], near: float, far: float) -> tuple[np.ndarray, np.ndarray]:
    """The cascades' eye-depth ranges ``(near_i, far_i)`` [world units], as PlayCanvas stores them (float32).

    Example
    -------
    >>> a, b = splits(PROFILES[0].resolve({"numCascades": 2, "cascadeDistribution": 0}), 1.0, 500.0)
    >>> b.tolist()                   # uniform over near..shadowDistance 40
    [20.5, 40.0]
    """
    k = int(PROFILES[0].setting("numCascades").clamped(int(np.floor(s["numCascades"]))))
    lam = float(PROFILES[0].setting("cascadeDistribution").clamped(s["cascadeDistribution"]))
    end = min(far, float(s["shadowDistance"]))
    if not end > near:
        raise ValueError(f"shadowDistance must exceed the camera's near ({near:g}), got {s['shadowDistance']:g}")
    f = np.arange(1, k) / k
    inner = (near + (end - near) * f) + lam * (near * (end / near) ** f - (near + (end - near) * f))  # math.lerp(linear, log, λ)
    ends = np.concatenate([inner, [end]]).astype(np.float32).astype(float)  # light._shadowCascadeDistances: Float32Array
    return np.concatenate([[near], ends[:-1]]), ends


def blend_bands(s: Mapping[str, Any], near: float, far: float) -> tuple:
    """The eye-depth range (start, end) of each blend band between cascade i and i + 1 [world units].

    ``shadowCascades.js`` ``ditherShadowCascadeIndex``: from (1 − cascadeBlend)·end_i to end_i
    the receivers pick cascade i + 1 with a dithered probability rising by smoothstep; the
    start is not clipped to the cascade's own start.  None at cascadeBlend 0.

    Example
    -------
    >>> s = PROFILES[0].resolve({"numCascades": 2, "cascadeDistribution": 0, "cascadeBlend": 0.1})
    >>> blend_bands(s, 1.0, 500.0)
    ((18.45, 20.5),)
    """
    blend = float(PROFILES[0].setting("cascadeBlend").clamped(s["cascadeBlend"]))
    if blend == 0:
        return ()
    _, b = splits(s, near, far)
    return tuple((float((1.0 - blend) * e), float(e)) for e in b[:-1])


def _filter(s: Mapping[str, Any]) -> Filter:
    kind = s["shadowType"]
    if "PCF" in kind:
        k = {"1": 2, "3": 3, "5": 5}[kind.split("PCF")[1][0]]
        return Filter("pcf", k, note=f"{kind}: " + ("one hardware 2×2 comparison" if k == 2 else f"{k}×{k} Castaño filter of hardware comparisons"))
    if "VSM" in kind:
        return Filter("vsm", 1, float(s["vsmBlurSize"]), note=f"{kind}: variance shadow map blurred over vsmBlurSize {s['vsmBlurSize']} texels")
    return Filter("pcss", 1, float(s["penumbraSize"]), note=f"PCSS: {s['shadowSamples']} samples, penumbraSize {s['penumbraSize']:g}")


def _build(s: Mapping[str, Any], camera) -> Pipeline:
    a, b = splits(s, camera.near, camera.far)
    k = len(a)
    res = int(s["shadowResolution"])
    per = res if k == 1 else res // 2  # light.js:46–51: a 2×2 grid of half-size viewports
    if per < 3:
        raise ValueError(f"shadowResolution must give each cascade at least 3 texels for the toolkit's fits ({'' if k == 1 else 'half of '}"
                         f"shadowResolution with {k} cascades), got {res}")
    kind = s["shadowType"]
    v = float(PROFILES[0].setting("shadowBias").clamped(s["shadowBias"]))
    notes = ["the shadow camera's depth range spans the shadow casters' bounds + 0.2: the depth_range terms take the cascade's "
             "sphere diameter (casters filling it)"]
    if "VSM" in kind or "PCSS" in kind:
        notes.append(f"{kind}: the depth bias, normal offset and 0.0001 lift are those of PCF here; VSM uses vsmBias/(farClip/7) as its "
                     "normal offset and a fixed −2e-4 bias, PCSS no rasterizer bias (light.js:683–706, 746–749): not modelled")
    if not s["castShadows"]:
        notes.append("castShadows is false (the component's default): the light casts no shadow; this is the shadow it casts when true")
    if k > 1 and res % 2:
        notes.append(f"an odd shadowResolution ({res}) gives cascades of {res / 2:g} texels: the profile uses {per}")
    step = 2.0 ** -24 if kind.endswith("32F") else 1.0 / 65535
    terms = (BiasTerm("shadowBias", v, "slope", 10.0),
             BiasTerm("shadowBias", v, "depth_range", 10.0 * step),  # the same setting's constant factor
             BiasTerm("receiver lift 0.0001", 1e-4, "depth_range", 1.0),
             BiasTerm("normalOffsetBias", float(PROFILES[0].setting("normalOffsetBias").clamped(s["normalOffsetBias"])), "normal"))
    rule = BiasRule(terms, CULL[s["material.cull"]], resolution=per)  # the sphere's cube: its side w·per is the extent taken
    bytes_per = 2 if kind.endswith("16F") else 4 * (2 if "VSM" in kind else 1)
    return Pipeline(tuple(a), tuple(b), "centroid", "bevy", per, rule, _filter(s), layout="separate" if k == 1 else f"atlas 2x2 of {res}",
                    blend=float(PROFILES[0].setting("cascadeBlend").clamped(s["cascadeBlend"])), stable=True,
                    memory=res * res * bytes_per, notes=tuple(notes), bands=blend_bands(s, camera.near, camera.far))


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """JavaScript: the light component's data (``keys`` None: every setting, on a new component), or ``keys`` set on the
    user's light entity ``light`` (its name, ``app.root.findByName``; None: a placeholder)."""
    if keys is None:
        order = ("numCascades", "cascadeDistribution", "cascadeBlend", "shadowDistance", "shadowResolution", "shadowBias", "normalOffsetBias")
        body = ",\n".join([f"  {k}: {_js(s[k])}" for k in order] + [f"  shadowType: pc.{s['shadowType']}"]
                          + ([f"  vsmBlurSize: {s['vsmBlurSize']}", f"  vsmBias: {_js(s['vsmBias'])}"] if "VSM" in s["shadowType"] else [])
                          + ([f"  shadowSamples: {s['shadowSamples']}", f"  penumbraSize: {_js(s['penumbraSize'])}"] if "PCSS" in s["shadowType"] else []))
        out = f"sun.addComponent('light', {{\n  type: 'directional',\n  castShadows: true,\n{body},\n}});"
        if s["material.cull"] != "CULLFACE_BACK":
            out += f"\nmaterial.cull = pc.{s['material.cull']};"
        return out
    lines = [f"const sun = app.root.findByName({light!r});" if light else "const sun = light;  // your directional light entity"]
    for k in keys:
        if k == "material.cull":
            lines.append(f"material.cull = pc.{s[k]};")
        elif k == "shadowType":
            lines.append(f"sun.light.shadowType = pc.{s[k]};")
        else:
            lines.append(f"sun.light.{k} = {_js(s[k])};")
    return "\n".join(lines)


def _js(v: Any) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)


#: What :func:`aliasing.tune.tune` searches: count, resolution, the practical split's λ, the
#: shadow distance, both biases and the cascades' blend band.
TUNABLE = (
    Tunable("numCascades", "cascades", values=(1, 2, 3, 4)),
    Tunable("shadowResolution", "size", values=(512, 1024, 2048, 4096, 8192)),
    Tunable("cascadeDistribution", "split", range=(0.0, 1.0), step=0.05),
    Tunable("shadowDistance", "distance"),
    Tunable("shadowBias", "bias"),
    Tunable("normalOffsetBias", "bias"),
    # the dithered blend band: scene/light.js cascadeBlend (line 135 at the pin; framework/components/light/component.js:169)
    Tunable("cascadeBlend", "blend", values=(0.0, 0.1, 0.2)),
)

PROFILES = (
    Profile("playcanvas", "PlayCanvas", "2.23", _settings(), _build, releases=("2.23.3", "2"), snippet=snippet, language="javascript",
            source="npm playcanvas 2.23.3 (build/playcanvas/src: scene/light.js, scene/renderer/shadow-renderer-directional.js, "
                   "framework/components/light/component.js, shader-lib chunks)",
            npm="playcanvas@2.23.3", tunable=TUNABLE),
)
