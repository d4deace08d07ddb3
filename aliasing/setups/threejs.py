"""three.js: the CSM addon (examples/jsm/csm) and the core DirectionalLight shadow.

Read from npm ``three`` 0.187.0 (r187) and 0.184.0 (r184, the last with the older split), both
run in node by the tests (``tests/test_engines_js.py``).  ``class`` picks the addon (``CSM``,
the cascades) or one ``DirectionalLight`` with its fixed orthographic shadow camera.

Settings as three.js spells them:

* the ``CSM`` constructor's data (``examples/jsm/csm/CSM.js`` lines 61–139): ``cascades`` (3),
  ``maxFar`` (100000), ``mode`` (``practical``), ``shadowMapSize`` (2048), ``shadowBias``
  (0.000001), ``lightNear`` (1), ``lightFar`` (2000), ``lightMargin`` (200).  The constructor
  reads them as ``data.x || default``: a 0 (or false) is the default, so ``shadowBias: 0`` is
  1e-6 and ``cascades: 0`` is 3.  ``fade`` (false, line 147) is NOT read from the data: set
  ``csm.fade = true`` after construction; it grows each cascade's box by
  0.25·(z/(F − near))²·(F − near), z the cascade's far end and F = max(camera.far, maxFar)
  (``_updateShadowBounds``, lines 265–275), and blends across a band around each split;
* each light's ``shadow`` (``src/lights/LightShadow.js``): ``shadow.bias`` (0, line 53),
  ``shadow.normalBias`` (0, line 74), ``shadow.radius`` (1, line 87), ``shadow.blurSamples``
  (8, line 95), ``shadow.mapSize.width`` (512, line 104), and ``DirectionalLightShadow``'s camera
  (``src/lights/DirectionalLightShadow.js`` line 16: ``OrthographicCamera(-5, 5, 5, -5, 0.5, 500)``);
* the material's ``side`` and ``shadowSide`` (``src/materials/Material.js``: FrontSide, null);
* the renderer's ``shadowMap.type`` (``src/renderers/webgl/WebGLShadowMap.js`` line 89:
  PCFShadowMap; PCFSoftShadowMap is replaced by PCFShadowMap, lines 99–102).

The rule (``shadowmap_pars_fragment.glsl.js``, r187 line 162, r184 line 122:
``shadowCoord.z += shadowBias``): the bias is added to the receiver's depth in [0, 1] over the
shadow camera's near..far, so a negative value lifts the receiver towards the light by
−bias·(far − near) world units (CSM: lightFar − lightNear); ``normalBias`` moves the looked-up
point along the world normal (``shadowmap_vertex.glsl.js``, r187 line 35, r184 line 28).  Which
faces cast (``WebGLShadowMap.js``, r187 lines 486 and 490, r184 473 and 477): ``shadowSide`` if
set, else the opposite of the material's side for Basic and PCF maps (a FrontSide material
casts with its back faces), the side itself for VSM.

The filter (PCFShadowMap): 5 Vogel-disk taps within ``shadow.radius`` texels (the outermost at
√(4.5/5) = 0.949 of it), each a hardware 2×2 comparison, rotated per pixel by interleaved
gradient noise.

r184 and r187 differ in the split only (``CSMFrustum.split``, docs/ERRATA.md G1): the filter,
the bias and the face rule are the same code (r187 adds a reversed-depth branch that subtracts
the bias from the reversed depth: the same lift).  ``mode: 'custom'`` runs any
``customSplitsCallback``; the profile models the callback that lerps uniform and logarithmic
breaks by ``customSplitsLambda`` (the ``practical`` mode's own formula with another λ).  Not
modelled: r187's ``examples/jsm/lights/SunLight.js`` (a new two-cascade sun light in one atlas).

Example
-------
>>> from aliasing.setups import build
>>> s = build("threejs", {"fade": True}, camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080")
>>> s.pipeline.bias.faces, round(s.pipeline.grow[-1], 6)   # back faces cast; the fade margin of the last cascade
('back', 0.625001)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable

CSM = "examples/jsm/csm/CSM.js"
SHADOW = "src/lights/LightShadow.js"
SIDES = ("FrontSide", "BackSide", "DoubleSide")
_CAST = {"FrontSide": "back", "BackSide": "front", "DoubleSide": "both"}  # WebGLShadowMap.js:51 shadowSide map
_FACES = {"FrontSide": "front", "BackSide": "back", "DoubleSide": "both"}
#: the sides' and the shadow map types' numbers, as three.js's JSON stores them (src/constants.js:57–108 at r187 and r184)
SIDE_NUMBERS = {0: "FrontSide", 1: "BackSide", 2: "DoubleSide"}
MAP_TYPES = ("BasicShadowMap", "PCFShadowMap", "PCFSoftShadowMap", "VSMShadowMap")
#: line numbers that moved between the releases read
_LINES = {
    "0.187.0": {"side": 88, "shadowSide": 342, "cast": "486, 490", "bias": 162, "normal": 35},
    "0.184.0": {"side": 86, "shadowSide": 340, "cast": "473, 477", "bias": 122, "normal": 28},
}
#: the outermost of three.js's 5 Vogel-disk taps, in units of shadow.radius: sqrt((4 + 0.5) / 5)
VOGEL_OUTER = (4.5 / 5) ** 0.5


def _settings(pkg: str) -> tuple[Setting, ...]:
    at = f" (npm three {pkg})"
    ln = _LINES[pkg]
    cam = f"src/lights/DirectionalLightShadow.js:16{at}"
    return (
        Setting("class", "CSM", "", "choice", ("CSM", "DirectionalLight"), doc="the CSM addon's cascades, or one DirectionalLight shadow"),
        Setting("cascades", 3, "", "int", (0, 64), source=f"{CSM}:61{at}", doc="number of cascades (0 reads as 3; the toolkit caps it at 64)"),
        Setting("maxFar", 100000.0, "world units", "float", (0.0, None), source=f"{CSM}:69{at}",
                doc="shadows end at min(camera.far, maxFar) (0 reads as 100000)"),
        Setting("mode", "practical", "", "choice", ("uniform", "logarithmic", "practical", "custom"), source=f"{CSM}:77{at}",
                doc="split mode (practical: λ = 0.5 fixed)"),
        Setting("customSplitsLambda", 0.5, "", "float", (0.0, 1.0),
                doc="not a three.js key: with mode 'custom', the λ of a customSplitsCallback that lerps uniform and "
                    "logarithmic breaks as practicalSplit does (the snippet writes that callback)"),
        Setting("shadowMapSize", 2048, "texels", "int", (0, 16384), source=f"{CSM}:85{at}", doc="texels per side of each cascade (0 reads as 2048)"),
        Setting("shadowBias", 0.000001, "normalized light depth", "float", (-1.0, 1.0), source=f"{CSM}:93{at}",
                doc="each cascade light's shadow.bias: added to the receiver's depth in [0, 1] over lightFar − lightNear "
                    "(0 reads as 1e-6; negative lifts the receiver)"),
        Setting("lightNear", 1.0, "world units", "float", (0.0, None), source=f"{CSM}:116{at}", doc="shadow camera near (0 reads as 1)"),
        Setting("lightFar", 2000.0, "world units", "float", (0.0, None), source=f"{CSM}:124{at}", doc="shadow camera far (0 reads as 2000)"),
        Setting("lightMargin", 200.0, "world units", "float", (0.0, None), source=f"{CSM}:132{at}",
                doc="the light sits this far behind each cascade's box (0 reads as 200)"),
        Setting("fade", False, "", "bool", source=f"{CSM}:147{at}",
                doc="csm.fade (set after construction; the constructor ignores data.fade): grows each box by a margin and blends across splits"),
        Setting("shadow.bias", 0.0, "normalized light depth", "float", (-1.0, 1.0), source=f"{SHADOW}:53{at}",
                doc="the DirectionalLight's bias (class DirectionalLight; CSM sets each light's to shadowBias)"),
        Setting("shadow.normalBias", 0.0, "world units", "float", (-1e6, 1e6), source=f"{SHADOW}:74{at}",
                doc="the looked-up point moves along the world normal by this"),
        Setting("shadow.radius", 1.0, "texels", "float", (0.0, 64.0), source=f"{SHADOW}:87{at}",
                doc="PCF: the Vogel disk's radius; VSM: the blur radius"),
        Setting("shadow.blurSamples", 8, "", "int", (1, 64), source=f"{SHADOW}:95{at}", doc="VSM blur samples"),
        Setting("shadow.mapSize.width", 512, "texels", "int", (1, 16384), source=f"{SHADOW}:104{at}",
                doc="the DirectionalLight's map size (class DirectionalLight; square maps: width = height)"),
        Setting("shadow.camera.left", -5.0, "world units", "float", (None, None), source=cam),
        Setting("shadow.camera.right", 5.0, "world units", "float", (None, None), source=cam),
        Setting("shadow.camera.top", 5.0, "world units", "float", (None, None), source=cam),
        Setting("shadow.camera.bottom", -5.0, "world units", "float", (None, None), source=cam),
        Setting("shadow.camera.near", 0.5, "world units", "float", (0.0, None), source=cam),
        Setting("shadow.camera.far", 500.0, "world units", "float", (0.0, None), source=cam),
        Setting("material.side", "FrontSide", "", "choice", SIDES, source=f"src/materials/Material.js:{ln['side']}; src/constants.js:92–108{at}",
                aliases=SIDE_NUMBERS),
        Setting("material.shadowSide", "null", "", "choice", ("null",) + SIDES, aliases=SIDE_NUMBERS,
                source=f"src/materials/Material.js:{ln['shadowSide']}; src/constants.js:92–108{at}",
                doc=f"faces drawn into the map; null: the opposite of material.side (VSM: the side itself; WebGLShadowMap.js:{ln['cast']})"),
        Setting("renderer.shadowMap.type", "PCFShadowMap", "", "choice", MAP_TYPES, aliases=dict(enumerate(MAP_TYPES)),
                source=f"src/renderers/webgl/WebGLShadowMap.js:89; src/constants.js:57–84{at}", doc="PCFSoftShadowMap is replaced by PCFShadowMap (lines 99–102)"),
    )


def _or(value: Any, default: Any) -> Any:
    """JavaScript's ``value || default``."""
    return value if value else default


def faces(s: Mapping[str, Any]) -> str:
    """Which faces cast: ``front``, ``back`` or ``both`` (WebGLShadowMap.js getDepthMaterial)."""
    side = s["material.shadowSide"]
    if side != "null":
        return _FACES[side]
    return _FACES[s["material.side"]] if s["renderer.shadowMap.type"] == "VSMShadowMap" else _CAST[s["material.side"]]


def _filter(s: Mapping[str, Any]) -> Filter:
    kind = s["renderer.shadowMap.type"]
    r = float(s["shadow.radius"])
    if kind == "BasicShadowMap":
        return Filter("hard", 1, note="one comparison")
    if kind == "VSMShadowMap":
        return Filter("vsm", 1, r, note=f"variance shadow map, blurred by shadow.radius {r:g} with shadow.blurSamples {s['shadow.blurSamples']}")
    # the disk's centres span 2·0.949·r texels; counted as the k×k PCF of the taps' centres (as the bias presets do)
    return Filter("pcf", max(2, int(round(2 * r)) + 1), r,
                  note=f"5 Vogel-disk taps within {VOGEL_OUTER:.3f}·shadow.radius texels, each a hardware 2×2 comparison "
                       "(shadowmap_pars_fragment.glsl.js); modelled as k×k PCF, k = round(2·radius) + 1")


def fade_margins(ends: np.ndarray, near: float, camera_far: float, max_far: float) -> np.ndarray:
    """CSM's fade margin added to each cascade's box side [world units] (``_updateShadowBounds``).

    0.25·(z/(F − near))²·(F − near), z each cascade's far end, F = max(camera.far, maxFar).
    """
    big = max(camera_far, max_far)
    return 0.25 * (np.asarray(ends, float) / (big - near)) ** 2 * (big - near)


def blend_bands(breaks: np.ndarray, near: float, shadow_far: float) -> tuple:
    """The eye-depth range (start, end) of CSM's fade band around each inner break [world units].

    ``CSMShader.js``: in linear depth z/(shadowFar − cameraNear) the cascades meet at the breaks b
    (split/shadowFar) and overlap by 0.25·b² around each: the band is b ∓ 0.125·b², times
    (shadowFar − near) in eye depth.

    Example
    -------
    >>> blend_bands(np.array([0.5]), 0.0, 100.0)
    ((46.875, 53.125),)
    """
    b = np.asarray(breaks, float)
    half = 0.125 * b**2
    return tuple((float((x - h) * (shadow_far - near)), float((x + h) * (shadow_far - near))) for x, h in zip(b, half))


def _build(split_form: str):
    def build(s: Mapping[str, Any], camera) -> Pipeline:
        side = faces(s)
        if s["class"] == "DirectionalLight":
            near, far = float(s["shadow.camera.near"]), float(s["shadow.camera.far"])
            width = float(s["shadow.camera.right"]) - float(s["shadow.camera.left"])
            height = float(s["shadow.camera.top"]) - float(s["shadow.camera.bottom"])
            if not (width > 0 and height > 0 and far > near):
                raise ValueError("shadow.camera must have right > left, top > bottom and far > near")
            res = int(s["shadow.mapSize.width"])
            rule = BiasRule((BiasTerm("shadow.bias", float(s["shadow.bias"]), "depth", -(far - near)),
                             BiasTerm("shadow.normalBias", float(s["shadow.normalBias"]), "normal")), side)
            return Pipeline((camera.near,), (camera.far,), "fixed", "none", res, rule, _filter(s), box=(width, height),
                            depth_range=(near, far), notes=("the shadow camera is a fixed world box: shadows outside it are lost",))
        k = int(_or(s["cascades"], 3))
        res = int(_or(s["shadowMapSize"], 2048))
        if res < 3:
            raise ValueError(f"shadowMapSize must be 0 (read as 2048) or at least 3 texels for the toolkit's cascade fits, got {res}")
        bias = float(_or(s["shadowBias"], 0.000001))
        light_near, light_far = float(_or(s["lightNear"], 1.0)), float(_or(s["lightFar"], 2000.0))
        if not light_far > light_near:
            raise ValueError(f"lightFar must exceed lightNear ({light_near:g}), got {light_far:g}")
        max_far = float(_or(s["maxFar"], 100000.0))
        far = min(camera.far, max_far)
        if not far > camera.near:
            raise ValueError(f"maxFar must exceed the camera's near ({camera.near:g}), got {s['maxFar']:g}")
        mode = s["mode"]
        if mode == "practical":
            ends = partitioning.split_distances("practical", camera.near, far, k, lam=0.5)
        elif mode == "custom":
            ends = partitioning.split_distances("practical", camera.near, far, k, lam=float(s["customSplitsLambda"]))
        else:
            ends = partitioning.split_distances("uniform" if mode == "uniform" else "log", camera.near, far, k)
        breaks = np.asarray(ends[1:-1], float) / far  # CSM's breaks: split / min(camera.far, maxFar)
        if split_form == "r184":  # CSMFrustum.split lerps the corners by the breaks C/F from near (r184 and earlier)
            ends = np.concatenate([[camera.near], camera.near + ends[1:] / far * (far - camera.near)])
        rule = BiasRule((BiasTerm("shadowBias", bias, "depth", -(light_far - light_near)),
                         BiasTerm("shadow.normalBias", float(s["shadow.normalBias"]), "normal")), side)
        notes = ["the shader picks cascade i for eye depths in [b_(i−1), b_i)·(far − near) (CSMShader.js: linearDepth = "
                 "z/(shadowFar − cameraNear) against the breaks b = split/far): the ranges read differ from the maps' by b·near at each split"]
        grow: tuple = ()
        bands: tuple = ()
        if s["fade"]:  # the fade band: 0.25·b²·(far − near) of eye depth around each break b (CSMShader.js), not a fixed fraction
            grow = tuple(fade_margins(ends[1:], camera.near, camera.far, max_far))
            bands = blend_bands(breaks, camera.near, far)
        return Pipeline(tuple(ends[:-1]), tuple(ends[1:]), "diagonal-unrounded", "bevy", res, rule, _filter(s),
                        layout="separate", blend=0.0, stable=True, depth_range=(light_near, light_far), grow=grow,
                        split=f"threejs-csm{'@r184' if split_form == 'r184' else ''}" if mode == "practical" else mode, notes=tuple(notes),
                        bands=bands)
    return build


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """JavaScript that sets ``keys`` of ``s`` (None: every setting) on the user's light or CSM.

    ``light`` is the DirectionalLight's name in the scene (``scene.getObjectByName``); None writes a
    placeholder.  A CSM reads its count, map size, bias and light range in its constructor
    (``CSM`` constructor and ``createLights``, examples/jsm/csm/CSM.js at the pinned release): where one of
    those changes, the CSM is built anew; the split mode, ``maxFar`` and the lights' shadow
    properties are set on the user's ``csm``, then ``csm.updateFrustums()``.
    """
    want = set(s) if keys is None else set(keys)
    lines = []
    if s["class"] == "DirectionalLight":
        lines.append(f"const light = scene.getObjectByName({_js(light)});" if light else "const light = sun;  // your DirectionalLight")
        if keys is None:
            lines.append("light.castShadow = true;")
        lines += [f"light.{k} = {_js(s[k])};" for k in s if k.startswith("shadow.") and k in want]
    else:
        built = ("cascades", "shadowMapSize", "shadowBias", "lightNear", "lightFar", "lightMargin")
        if keys is None or want & set(built):
            order = ("cascades", "maxFar", "mode", "shadowMapSize", "shadowBias", "lightNear", "lightFar", "lightMargin")
            body = ",\n".join(f"  {k}: {_js(s[k])}" for k in order)
            lines.append(f"csm.dispose();  // your CSM, built anew: its count, map size, bias and light range are read once\n"
                         f"csm = new CSM({{\n{body},\n  camera, parent: scene, lightDirection,\n}});" if keys is not None else
                         f"const csm = new CSM({{\n{body},\n  camera, parent: scene, lightDirection,\n}});")
            want |= {"mode", "customSplitsLambda", "fade", "shadow.normalBias", "shadow.radius", "shadow.blurSamples"}
        else:
            lines.append("// csm: your CSM")
            lines += [f"csm.{k} = {_js(s[k])};" for k in ("maxFar", "mode") if k in want]
        if s["mode"] == "custom" and want & {"mode", "customSplitsLambda"}:
            lines.append(f"csm.customSplitsCallback = (n, near, far, breaks) => {{ for (let i = 1; i < n; i++) "
                         f"breaks.push(THREE.MathUtils.lerp((near + (far - near) * i / n) / far, near * (far / near) ** (i / n) / far, "
                         f"{s['customSplitsLambda']:g})); breaks.push(1); }};")
        if "fade" in want and (s["fade"] or keys is not None):
            lines.append(f"csm.fade = {_js(s['fade'])};  // the constructor ignores data.fade")
        each = [f"light.shadow.{k[7:]} = {_js(s[k])};" for k in ("shadow.normalBias", "shadow.radius", "shadow.blurSamples") if k in want]
        if each:
            lines.append(f"for (const light of csm.lights) {{ {' '.join(each)} }}")
        lines.append("csm.updateFrustums();")
    if "material.side" in want and (keys is not None or s["material.side"] != "FrontSide"):
        lines.append(f"material.side = THREE.{s['material.side']};")
    if "material.shadowSide" in want and (keys is not None or s["material.shadowSide"] != "null"):
        lines.append(f"material.shadowSide = {'null' if s['material.shadowSide'] == 'null' else 'THREE.' + s['material.shadowSide']};")
    if "renderer.shadowMap.type" in want:
        lines.append(f"renderer.shadowMap.type = THREE.{s['renderer.shadowMap.type']};")
    return "\n".join(lines)


def _js(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return repr(v)
    return f"{v:g}" if isinstance(v, float) else str(v)


_CSM = (("class", "CSM"),)
_LIGHT = (("class", "DirectionalLight"),)
#: What :func:`aliasing.tune.tune` may set: the CSM addon's count, map size, split (the named modes
#: and a custom callback's λ), where shadows end, the bias pair and the filter; one DirectionalLight's
#: map size and biases (its fixed box is the user's); which faces cast (``material.shadowSide``), the light's depth
#: margin and the filter's radius.  ``fade`` is not searched: its grown boxes
#: are not in the fit (the profile's notes).
TUNABLE = (
    Tunable("cascades", "cascades", values=tuple(range(1, 9)), when=_CSM),
    Tunable("shadowMapSize", "size", values=(512, 1024, 2048, 4096, 8192, 16384), when=_CSM),
    Tunable("mode", "split", values=("practical", "uniform", "logarithmic", "custom"), when=_CSM),
    Tunable("customSplitsLambda", "split", range=(0.0, 1.0), step=0.05, when=(("class", "CSM"), ("mode", "custom"))),
    Tunable("maxFar", "distance", when=_CSM),
    Tunable("shadowBias", "bias", when=_CSM),
    Tunable("shadow.normalBias", "bias"),
    Tunable("shadow.mapSize.width", "size", values=(512, 1024, 2048, 4096, 8192, 16384), when=_LIGHT),
    Tunable("shadow.bias", "bias", when=_LIGHT),
    Tunable("renderer.shadowMap.type", "filter", values=("PCFShadowMap", "BasicShadowMap")),
    # which faces cast (src/materials/Material.js shadowSide; src/renderers/webgl/WebGLShadowMap.js getDepthMaterial)
    Tunable("material.shadowSide", "faces", values=("null",) + SIDES),
    # the light's depth range behind the casters' box (examples/jsm/csm/CSM.js lightMargin, line 132 at the pin)
    Tunable("lightMargin", "depth", values=(50.0, 100.0, 200.0, 400.0), when=_CSM),
    # the PCF disk's radius (src/lights/LightShadow.js radius, line 87 at the pin)
    Tunable("shadow.radius", "radius", values=(1.0, 2.0, 4.0)),
)

PROFILES = (
    Profile("threejs", "three.js", "r187", _settings("0.187.0"), _build("r185"), releases=("r185", "r186", "0.187.0", "0.187"),
            snippet=snippet, language="javascript", source="npm three 0.187.0 (examples/jsm/csm, src/lights, src/renderers/webgl)",
            npm="three@0.187.0", tunable=TUNABLE),
    Profile("threejs", "three.js", "r184", _settings("0.184.0"), _build("r184"), releases=("0.184.0", "0.184"),
            snippet=snippet, language="javascript", source="npm three 0.184.0 (CSMFrustum.split lerps by the break itself)",
            npm="three@0.184.0", tunable=TUNABLE),
)
