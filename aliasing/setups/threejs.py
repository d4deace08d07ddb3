"""three.js: the CSM addon (examples/jsm/csm) and the core DirectionalLight shadow.

Read from npm ``three`` 0.187.0 (r187; run in the tests) and 0.184.0 (r184, the last with the
older split).  ``class`` picks the addon (``CSM``, the cascades) or one ``DirectionalLight`` with
its fixed orthographic shadow camera.

Settings as three.js spells them:

* the ``CSM`` constructor's data (``examples/jsm/csm/CSM.js`` lines 61–147): ``cascades`` (3),
  ``maxFar`` (100000), ``mode`` (``practical``), ``shadowMapSize`` (2048), ``shadowBias``
  (0.000001), ``lightNear`` (1), ``lightFar`` (2000), ``lightMargin`` (200), ``fade`` (false).
  The constructor reads them as ``data.x || default``: a 0 (or false) is the default, so
  ``shadowBias: 0`` is 1e-6 and ``cascades: 0`` is 3;
* each light's ``shadow`` (``src/lights/LightShadow.js``): ``shadow.bias`` (0, line 53),
  ``shadow.normalBias`` (0, line 74), ``shadow.radius`` (1, line 87), ``shadow.mapSize.width``
  (512, line 104), and ``DirectionalLightShadow``'s camera
  (``src/lights/DirectionalLightShadow.js`` line 16: ``OrthographicCamera(-5, 5, 5, -5, 0.5, 500)``);
* the material's ``side`` and ``shadowSide`` (``src/materials/Material.js``: FrontSide, null);
* the renderer's ``shadowMap.type`` (``src/renderers/webgl/WebGLShadowMap.js`` line 89: PCFShadowMap;
  PCFSoftShadowMap is replaced by PCFShadowMap, line 101).

The rule (``shadowmap_pars_fragment.glsl.js`` line 162: ``shadowCoord.z += shadowBias``): the bias is
added to the receiver's depth in [0, 1] over the shadow camera's near..far, so a negative value
lifts the receiver towards the light by −bias·(far − near) world units; ``normalBias`` moves the
looked-up point along the world normal (line 315).  Which faces cast
(``WebGLShadowMap.js`` line 490): ``shadowSide`` if set, else the opposite of the material's
side: a FrontSide material casts with its back faces.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable

CSM = "examples/jsm/csm/CSM.js"
SHADOW = "src/lights/LightShadow.js"
SIDES = ("FrontSide", "BackSide", "DoubleSide")
_CAST = {"FrontSide": "back", "BackSide": "front", "DoubleSide": "both"}  # WebGLShadowMap.js:51 shadowSide map
_FACES = {"FrontSide": "front", "BackSide": "back", "DoubleSide": "both"}


def _settings(pkg: str) -> tuple[Setting, ...]:
    at = f" (npm three {pkg})"
    return (
        Setting("class", "CSM", "", "choice", ("CSM", "DirectionalLight"), doc="the CSM addon's cascades, or one DirectionalLight shadow"),
        Setting("cascades", 3, "", "int", (0, 64), source=f"{CSM}:61{at}", doc="number of cascades (0 reads as 3)"),
        Setting("maxFar", 100000.0, "world units", "float", (0.0, None), source=f"{CSM}:69{at}", doc="shadows end at min(camera.far, maxFar)"),
        Setting("mode", "practical", "", "choice", ("uniform", "logarithmic", "practical", "custom"), source=f"{CSM}:77{at}",
                doc="split mode (practical: λ = 0.5 fixed)"),
        Setting("customSplitsLambda", 0.5, "", "float", (0.0, 1.0),
                doc="with mode 'custom': the λ of a customSplitsCallback that lerps uniform and logarithmic breaks as practicalSplit does"),
        Setting("shadowMapSize", 2048, "texels", "int", (0, 16384), source=f"{CSM}:85{at}", doc="texels per side of each cascade (0 reads as 2048)"),
        Setting("shadowBias", 0.000001, "normalized light depth", "float", (-1.0, 1.0), source=f"{CSM}:93{at}",
                doc="added to the receiver's depth in [0, 1] over lightFar − lightNear (0 reads as 1e-6; negative lifts it)"),
        Setting("lightNear", 1.0, "world units", "float", (0.0, None), source=f"{CSM}:116{at}", doc="shadow camera near (0 reads as 1)"),
        Setting("lightFar", 2000.0, "world units", "float", (0.0, None), source=f"{CSM}:124{at}", doc="shadow camera far (0 reads as 2000)"),
        Setting("lightMargin", 200.0, "world units", "float", (0.0, None), source=f"{CSM}:132{at}",
                doc="the light sits this far behind each cascade's box (0 reads as 200)"),
        Setting("fade", False, "", "bool", source=f"{CSM}:147{at}", doc="blend between cascades (grows each box by a margin)"),
        Setting("shadow.bias", 0.0, "normalized light depth", "float", (-1.0, 1.0), source=f"{SHADOW}:53{at}",
                doc="the DirectionalLight's bias (CSM sets each light's to shadowBias)"),
        Setting("shadow.normalBias", 0.0, "world units", "float", (-1e6, 1e6), source=f"{SHADOW}:74{at}",
                doc="the looked-up point moves along the world normal by this"),
        Setting("shadow.radius", 1.0, "texels", "float", (0.0, 64.0), source=f"{SHADOW}:87{at}", doc="PCF radius"),
        Setting("shadow.mapSize.width", 512, "texels", "int", (1, 16384), source=f"{SHADOW}:104{at}",
                doc="the DirectionalLight's map size (square maps: width = height)"),
        Setting("shadow.camera.left", -5.0, "world units", "float", (None, None), source=f"src/lights/DirectionalLightShadow.js:16{at}"),
        Setting("shadow.camera.right", 5.0, "world units", "float", (None, None), source=f"src/lights/DirectionalLightShadow.js:16{at}"),
        Setting("shadow.camera.top", 5.0, "world units", "float", (None, None), source=f"src/lights/DirectionalLightShadow.js:16{at}"),
        Setting("shadow.camera.bottom", -5.0, "world units", "float", (None, None), source=f"src/lights/DirectionalLightShadow.js:16{at}"),
        Setting("shadow.camera.near", 0.5, "world units", "float", (0.0, None), source=f"src/lights/DirectionalLightShadow.js:16{at}"),
        Setting("shadow.camera.far", 500.0, "world units", "float", (0.0, None), source=f"src/lights/DirectionalLightShadow.js:16{at}"),
        Setting("material.side", "FrontSide", "", "choice", SIDES, source=f"src/materials/Material.js{at}"),
        Setting("material.shadowSide", "null", "", "choice", ("null",) + SIDES, source=f"src/materials/Material.js{at}",
                doc="faces drawn into the map; null: the opposite of material.side"),
        Setting("renderer.shadowMap.type", "PCFShadowMap", "", "choice", ("BasicShadowMap", "PCFShadowMap", "PCFSoftShadowMap", "VSMShadowMap"),
                source=f"src/renderers/webgl/WebGLShadowMap.js:89{at}", doc="PCFSoftShadowMap is replaced by PCFShadowMap (line 101)"),
    )


def _or(value: Any, default: Any) -> Any:
    """JavaScript's ``value || default``."""
    return value if value else default


def _faces(s: Mapping[str, Any]) -> str:
    side = s["material.shadowSide"]
    return _FACES[side] if side != "null" else _CAST[s["material.side"]]


def _filter(s: Mapping[str, Any]) -> Filter:
    kind = s["renderer.shadowMap.type"]
    if kind == "BasicShadowMap":
        return Filter("hard", 1, note="one comparison")
    if kind == "VSMShadowMap":
        return Filter("vsm", 1, float(s["shadow.radius"]), note="variance shadow map, blurred by shadow.radius")
    r = float(s["shadow.radius"])
    return Filter("pcf", max(2, int(round(2 * r)) + 1), r,
                  note="5 Vogel-disk taps of radius shadow.radius texels, each a hardware 2×2 comparison (shadowmap_pars_fragment.glsl.js)")


def _build(split_form: str):
    def build(s: Mapping[str, Any], camera) -> Pipeline:
        faces = _faces(s)
        if s["class"] == "DirectionalLight":
            near, far = float(s["shadow.camera.near"]), float(s["shadow.camera.far"])
            width = float(s["shadow.camera.right"]) - float(s["shadow.camera.left"])
            height = float(s["shadow.camera.top"]) - float(s["shadow.camera.bottom"])
            if not (width > 0 and height > 0 and far > near):
                raise ValueError("shadow.camera must have right > left, top > bottom and far > near")
            res = int(s["shadow.mapSize.width"])
            rule = BiasRule((BiasTerm("shadow.bias", float(s["shadow.bias"]), "depth", -(far - near)),
                             BiasTerm("shadow.normalBias", float(s["shadow.normalBias"]), "normal")), faces)
            return Pipeline((camera.near,), (camera.far,), "fixed", "none", res, rule, _filter(s), box=(width, height),
                            depth_range=(near, far), notes=("the shadow camera is a fixed world box: shadows outside it are lost",))
        k = int(_or(s["cascades"], 3))
        res = int(_or(s["shadowMapSize"], 2048))
        bias = float(_or(s["shadowBias"], 0.000001))
        light_near, light_far = float(_or(s["lightNear"], 1.0)), float(_or(s["lightFar"], 2000.0))
        far = min(camera.far, float(_or(s["maxFar"], 100000.0)))
        if not far > camera.near:
            raise ValueError(f"maxFar must exceed the camera's near ({camera.near:g}), got {s['maxFar']:g}")
        mode = s["mode"]
        if mode == "practical":
            ends = partitioning.split_distances("practical", camera.near, far, k, lam=0.5)
        elif mode == "custom":
            ends = partitioning.split_distances("practical", camera.near, far, k, lam=float(s["customSplitsLambda"]))
        else:
            ends = partitioning.split_distances("uniform" if mode == "uniform" else "log", camera.near, far, k)
        if split_form == "r184":  # CSMFrustum.split lerps the corners by the breaks C/F from near (r184 and earlier)
            ends = camera.near + ends / far * (far - camera.near)
        rule = BiasRule((BiasTerm("shadowBias", bias, "depth", -(light_far - light_near)),
                         BiasTerm("shadow.normalBias", float(s["shadow.normalBias"]), "normal")), faces)
        notes = ["fade grows each box by 0.25·(z/(far − near))²·(far − near), not in the fit"] if s["fade"] else []
        return Pipeline(tuple(ends[:-1]), tuple(ends[1:]), "diagonal-unrounded", "bevy", res, rule, _filter(s),
                        layout="separate", blend=0.0, stable=True, depth_range=(light_near, light_far),
                        split=f"threejs-csm{'@r184' if split_form == 'r184' else ''}" if mode == "practical" else mode, notes=tuple(notes))
    return build


def snippet(s: Mapping[str, Any]) -> str:
    """JavaScript that sets the settings (the CSM constructor's data, then each light's shadow)."""
    if s["class"] == "DirectionalLight":
        lines = ["light.castShadow = true;"]
        lines += [f"light.{k} = {_js(s[k])};" for k in s if k.startswith("shadow.")]
    else:
        keys = ("cascades", "maxFar", "mode", "shadowMapSize", "shadowBias", "lightNear", "lightFar", "lightMargin", "fade")
        body = ",\n".join(f"  {k}: {_js(s[k])}" for k in keys)
        lines = [f"const csm = new CSM({{\n{body},\n  camera, parent: scene, lightDirection,\n}});"]
        if s["mode"] == "custom":
            lines.append(f"csm.customSplitsCallback = (n, near, far, breaks) => {{ for (let i = 1; i < n; i++) "
                         f"breaks.push(THREE.MathUtils.lerp((near + (far - near) * i / n) / far, near * (far / near) ** (i / n) / far, "
                         f"{s['customSplitsLambda']:g})); breaks.push(1); }};")
        lines.append(f"for (const light of csm.lights) {{ light.shadow.normalBias = {_js(s['shadow.normalBias'])}; "
                     f"light.shadow.radius = {_js(s['shadow.radius'])}; }}")
    if s["material.shadowSide"] != "null":
        lines.append(f"material.shadowSide = THREE.{s['material.shadowSide']};")
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
#: map size and biases (its fixed box is the user's).  ``fade`` is not searched: its grown boxes
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
)

PROFILES = (
    Profile("threejs", "three.js", "r187", _settings("0.187.0"), _build("r185"), releases=("r185", "r186", "0.187.0", "0.187"),
            snippet=snippet, language="javascript", source="npm three 0.187.0 (examples/jsm/csm, src/lights, src/renderers/webgl)",
            npm="three@0.187.0", tunable=TUNABLE),
    Profile("threejs", "three.js", "r184", _settings("0.184.0"), _build("r184"), releases=("0.184.0", "0.184"),
            snippet=snippet, language="javascript", source="npm three 0.184.0 (CSMFrustum.split lerps by the break itself)",
            npm="three@0.184.0", tunable=TUNABLE),
)
