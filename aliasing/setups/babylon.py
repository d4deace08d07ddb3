"""Babylon.js 9: the CascadedShadowGenerator and the ShadowGenerator of a DirectionalLight.

Read from npm ``@babylonjs/core`` 9.35.0 (run in node by ``tests/test_engines_js.py``).  Files
below are that package's (``Lights/Shadows/cascadedShadowGenerator.pure.js`` is ``CSG``,
``Lights/Shadows/shadowGenerator.js`` is ``SG``).  ``class`` picks the generator.

Settings as Babylon spells them (the generators' properties, and the light's and material's
where they matter):

* ``mapSize``: the constructor's first argument (no default in the engine: 1024 here, as in
  Babylon's documentation);
* CascadedShadowGenerator (``CSG`` ``_initializeGenerator``, lines 560–577): ``numCascades`` 4
  (the setter clamps to 2–4, line 51), ``lambda`` 0.5 (clamped to [0, 1], line 236),
  ``cascadeBlendPercentage`` 0.1, ``stabilizeCascades`` false, ``shadowMaxZ`` the camera's
  ``maxZ`` (the setter ignores values below the camera's minZ or above its maxZ, line 182),
  ``minDistance``/``maxDistance`` 0/1 (``setMinMaxDistance`` clamps both to [0, 1] and
  resets to 0, 1 when min > max, lines 122–127), ``depthClamp`` true, ``autoCalcDepthBounds``
  false; the filter is PCF on engines with shadow samplers (WebGL2, WebGPU; line 556);
* both (``SG`` constructor, lines 583–618): ``bias`` 0.00005, ``normalBias`` 0, ``filter``
  (``SG`` default FILTER_NONE), ``filteringQuality`` QUALITY_HIGH, ``frustumEdgeFalloff`` 0,
  ``forceBackFacesOnly`` false, ``contactHardeningLightSizeUVRatio`` 0.1;
* ShadowGenerator with a DirectionalLight (``Lights/directionalLight.pure.js``):
  ``light.shadowFrustumSize`` 0 (line 133; > 0 gives a fixed square box, lines 177–196; 0 fits
  the casters' bounding box, which needs the scene), ``light.shadowMinZ``/``light.shadowMaxZ``
  (undefined: the camera's minZ/maxZ, ``Lights/shadowLight.js`` lines 212, 220);
* the material's ``backFaceCulling`` and ``cullBackFaces`` (true, true:
  ``Materials/material.pure.js`` lines 564, 578).

The splits (``CSG`` ``_splitFrustum``, lines 345–363): between minZ = near + minDistance·(far −
near) and maxZ = near + maxDistance′·(far − near), maxDistance′ = min((shadowMaxZ − near)/(far −
near), maxDistance) where near ≤ shadowMaxZ < far, each break lerps uniform and logarithmic
splits by ``lambda`` (the practical split).

The fit (``_computeCascadeFrustum``, lines 474–514): ``stabilizeCascades`` true: the sphere
around the cascade's 8 corners' centroid, radius ceiled to 1/16 (a cube of that side);
false: the tight light-space box of the 8 corners (light view from world up); in both, the
projected world origin is rounded to a texel (lines 425–430).

The bias rule, as the shaders apply it (``Shaders/ShadersInclude``): the caster's stored depth
in [0, 1] over the cascade's light near..far grows by ``bias``
(``shadowMapVertexMetric.js``: ``vDepthMetricSM = (z + depthValuesSM.x)/depthValuesSM.y +
bias``, ``depthValuesSM`` = (1, 2) for a directional light in WebGL: (z_ndc + 1)/2); with a depth
texture (PCF and PCSS) the vertex shader also adds ``bias`` to clip z, half a unit of [0, 1]
depth, and with ``depthClamp`` (not with PCSS) the fragment shader writes the metric computed
from that z plus ``bias`` again (``shadowMapFragment.js``): the stored depth grows by 1.5·bias
for CSM with PCF (its default), 0.5·bias with PCSS or without depthClamp, 1·bias for the
float maps.  The cascade's light near..far (``_computeMatrices``, lines 364–416) is its box's
extent along the light, tightened to the shadow casters' bounds and, with depthClamp, at least
1 world unit (line 417): the rule takes the box (the casters filling it).  ``normalBias`` moves the caster's vertices inwards along their normal by
normalBias·sin θ (``shadowMapVertexNormalBias.js``), world units.  Faces
(``SG`` lines 927, 1002–1020): the material's culling (front faces cast), ``forceBackFacesOnly``
reverses it (back faces cast), ``backFaceCulling`` false casts both.

Example
-------
>>> from aliasing.setups import build
>>> s = build("babylon", camera="near=0.1,far=500,fov=50,aspect=16:9,height=1080")
>>> s.pipeline.k, s.pipeline.fit, s.pipeline.bias.faces, s.pipeline.bias.term("bias").scale
(4, 'tight', 'front', 1.5)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable

CSG = "Lights/Shadows/cascadedShadowGenerator.pure.js"
SG = "Lights/Shadows/shadowGenerator.js"
DL = "Lights/directionalLight.pure.js"
AT = " (npm @babylonjs/core 9.35.0)"
FILTERS = ("FILTER_NONE", "FILTER_EXPONENTIALSHADOWMAP", "FILTER_POISSONSAMPLING", "FILTER_BLUREXPONENTIALSHADOWMAP",
           "FILTER_CLOSEEXPONENTIALSHADOWMAP", "FILTER_BLURCLOSEEXPONENTIALSHADOWMAP", "FILTER_PCF", "FILTER_PCSS")
#: the filters' numbers (ShadowGenerator.FILTER_*, SG lines 1735–1774)
FILTER_VALUES = {name: i for i, name in enumerate(FILTERS)}
QUALITIES = ("QUALITY_HIGH", "QUALITY_MEDIUM", "QUALITY_LOW")  # 0, 1, 2 (SG lines 1783–1801)
CSM_FILTERS = ("FILTER_NONE", "FILTER_PCF", "FILTER_PCSS")  # CSG _validateFilter, line 27
#: the CascadedShadowGenerator's cascade count: default, min, max (CSG lines 1018–1026)
CASCADES = (4, 2, 4)


def _settings() -> tuple[Setting, ...]:
    return (
        Setting("class", "CascadedShadowGenerator", "", "choice", ("CascadedShadowGenerator", "ShadowGenerator"),
                doc="the cascaded generator, or one ShadowGenerator of a DirectionalLight"),
        Setting("mapSize", 1024, "texels", "int", (1, 16384), source=f"{SG} constructor{AT}",
                doc="the constructor's mapSize: texels per side of each cascade (no engine default; 1024 as in Babylon's documentation)"),
        Setting("numCascades", CASCADES[0], "", "int", (None, None), clamp=CASCADES[1:], source=f"{CSG}:51, 561, 1018{AT}",
                doc="number of cascades (the setter clamps to 2–4)"),
        Setting("lambda", 0.5, "", "float", (None, None), clamp=(0.0, 1.0), source=f"{CSG}:236, 576{AT}",
                doc="practical split weight: 0 uniform, 1 logarithmic (the setter clamps to [0, 1])"),
        Setting("cascadeBlendPercentage", 0.1, "fraction of a cascade", "float", (0.0, 1.0), source=f"{CSG}:575, 730{AT}",
                doc="the receivers blend into the next cascade over this last part of each cascade's depth range (0: no blend)"),
        Setting("stabilizeCascades", False, "", "bool", source=f"{CSG}:562, 497{AT}",
                doc="sphere fit rounded to 1/16 (no shimmer) instead of the tight light-space box"),
        Setting("shadowMaxZ", None, "world units", "float", (None, None), source=f"{CSG}:182, 572{AT}",
                doc="shadows end here; null: the camera's maxZ; values outside [camera.minZ, camera.maxZ] are ignored by the setter"),
        Setting("minDistance", 0.0, "fraction of near..far", "float", (None, None), clamp=(0.0, 1.0), source=f"{CSG}:116–128, 569{AT}",
                doc="setMinMaxDistance(min, max): the cascades start at near + min·(far − near) (clamped to [0, 1]; min > max resets both)"),
        Setting("maxDistance", 1.0, "fraction of near..far", "float", (None, None), clamp=(0.0, 1.0), source=f"{CSG}:116–128, 570{AT}",
                doc="setMinMaxDistance(min, max): the cascades end at near + max·(far − near)"),
        Setting("depthClamp", True, "", "bool", source=f"{CSG}:574, 663{AT}",
                doc="depth clamping in the caster pass (not with PCSS); with PCF it makes the stored bias 1.5·bias"),
        Setting("autoCalcDepthBounds", False, "", "bool", source=f"{CSG}:577{AT}",
                doc="min/max distances from the depth buffer each frame (scene-dependent: not modelled, the given ones are used)"),
        Setting("bias", 0.00005, "normalized light depth", "float", (-1.0, 1.0), source=f"{SG}:583, 948{AT}",
                doc="added to the caster's depth in [0, 1] over the cascade's light near..far (×1.5 with PCF and depthClamp, ×0.5 "
                    "with PCSS or without depthClamp)"),
        Setting("normalBias", 0.0, "world units", "float", (-1e6, 1e6), source=f"{SG}:584, 948{AT}",
                doc="casters move inwards along their normal by normalBias·sin θ"),
        Setting("filter", None, "", "choice", FILTERS, aliases={v: k for k, v in FILTER_VALUES.items()}, source=f"{SG}:589, 1735–1774; {CSG}:27, 556{AT}",
                doc="null: the class's default (CascadedShadowGenerator FILTER_PCF with shadow samplers, ShadowGenerator FILTER_NONE); "
                    "CascadedShadowGenerator takes NONE, PCF and PCSS (others log an error and give NONE)"),
        Setting("filteringQuality", "QUALITY_HIGH", "", "choice", QUALITIES, aliases=dict(enumerate(QUALITIES)),
                source=f"{SG}:590, 1362–1377, 1783–1801{AT}",
                doc="PCF: 5×5 (HIGH), 3×3 (MEDIUM), one hardware 2×2 comparison (LOW); PCSS: 64, 32, 16 samples"),
        Setting("contactHardeningLightSizeUVRatio", 0.1, "fraction of the map", "float", (0.0, 1.0), source=f"{SG}:591{AT}",
                doc="PCSS light size"),
        Setting("frustumEdgeFalloff", 0.0, "", "float", (0.0, 1.0), source=f"{SG}:610{AT}", doc="shadows fade out at the map's edges"),
        Setting("darkness", 0.0, "", "float", (None, None), clamp=(0.0, 1.0), source=f"{SG}:347–372, 592{AT}",
                doc="shadow strength: 0 the darkest, 1 none (setDarkness clamps to [0, 1])"),
        Setting("depthScale", 50.0, "", "float", (None, None), source=f"{SG}:126–134; Lights/shadowLight.js:112{AT}",
                doc="ESM filters: the exponent's scale (the light's getDepthScale(): 50)"),
        Setting("useKernelBlur", False, "", "bool", source=f"{SG}:588{AT}", doc="blurred ESM: a kernel blur instead of the box blur"),
        Setting("blurKernel", 1, "texels", "int", (1, 64), source=f"{SG}:587{AT}", doc="blurred ESM with useKernelBlur: the kernel size"),
        Setting("blurBoxOffset", 1, "texels", "int", (1, 64), source=f"{SG}:585{AT}", doc="blurred ESM with the box blur: its offset"),
        Setting("blurScale", 2.0, "", "float", (1.0, 64.0), source=f"{SG}:586{AT}", doc="blurred ESM: the blur map is mapSize / blurScale"),
        Setting("forceBackFacesOnly", False, "", "bool", source=f"{SG}:618, 1002–1020{AT}", doc="the back faces cast instead of the front faces"),
        Setting("material.backFaceCulling", True, "", "bool", source=f"Materials/material.pure.js:564; {SG}:927{AT}",
                doc="false: both faces cast (unless forceBackFacesOnly)"),
        Setting("material.cullBackFaces", True, "", "bool", source=f"Materials/material.pure.js:578; {SG}:927{AT}",
                doc="false: the front faces are culled, the back faces cast"),
        Setting("light.shadowFrustumSize", 0.0, "world units", "float", (0.0, None), source=f"{DL}:133, 177–196{AT}",
                doc="ShadowGenerator: > 0 a fixed square box of this side; 0 fits the casters' bounds (needs the scene)"),
        Setting("light.shadowMinZ", None, "world units", "float", (None, None), source=f"Lights/shadowLight.js:212{AT}",
                doc="ShadowGenerator: the light's depth near; null: the camera's minZ"),
        Setting("light.shadowMaxZ", None, "world units", "float", (None, None), source=f"Lights/shadowLight.js:220{AT}",
                doc="ShadowGenerator: the light's depth far; null: the camera's maxZ"),
    )


def filter_name(s: Mapping[str, Any]) -> str:
    """The filter the generator uses (the class's default, and CascadedShadowGenerator's fallback to NONE)."""
    name = s["filter"]
    if s["class"] == "CascadedShadowGenerator":
        name = "FILTER_PCF" if name is None else name
        return name if name in CSM_FILTERS else "FILTER_NONE"
    return "FILTER_NONE" if name is None else name


def bias_factor(s: Mapping[str, Any]) -> float:
    """How many units of the caster's [0, 1] depth one unit of ``bias`` adds (module docstring)."""
    name = filter_name(s)
    if name not in ("FILTER_PCF", "FILTER_PCSS"):
        return 1.0
    clamp = s["class"] == "CascadedShadowGenerator" and s["depthClamp"] and name != "FILTER_PCSS"
    return 1.5 if clamp else 0.5


def faces(s: Mapping[str, Any]) -> str:
    """Which faces cast: ``front``, ``back`` or ``both``."""
    if s["forceBackFacesOnly"]:  # culling forced on, the side orientation reversed
        return "back" if s["material.cullBackFaces"] else "front"
    if not s["material.backFaceCulling"]:
        return "both"
    return "front" if s["material.cullBackFaces"] else "back"


def _filter(s: Mapping[str, Any]) -> Filter:
    name = filter_name(s)
    quality = s["filteringQuality"]
    if name == "FILTER_PCF":
        k = {"QUALITY_HIGH": 5, "QUALITY_MEDIUM": 3, "QUALITY_LOW": 2}[quality]
        return Filter("pcf", k, note=f"{name} {quality}: computeShadowWithCSMPCF{5 if k == 5 else 3 if k == 3 else 1} "
                                     "(Castaño's optimized PCF with hardware comparisons)")
    if name == "FILTER_PCSS":
        n = {"QUALITY_HIGH": 64, "QUALITY_MEDIUM": 32, "QUALITY_LOW": 16}[quality]
        return Filter("pcss", 1, float(s["contactHardeningLightSizeUVRatio"]), note=f"PCSS{n}: {n} samples, light size "
                      f"{s['contactHardeningLightSizeUVRatio']:g} of the map")
    if name == "FILTER_POISSONSAMPLING":
        return Filter("pcf", 1, note="Poisson sampling (shadowsFragmentFunctions.js computeShadowWithPoissonSampling): counted as one comparison")
    if "EXPONENTIAL" in name:
        blur = ""
        if name.startswith("FILTER_BLUR"):
            blur = (f", blurred by a kernel of {s['blurKernel']}" if s["useKernelBlur"] else f", box-blurred with offset {s['blurBoxOffset']}") \
                + f" at 1/{s['blurScale']:g} of the map's size"
        return Filter("esm", 1, note=f"{name}: exponential shadow map (depthScale {s['depthScale']:g}){blur}")
    return Filter("hard", 1, note="one comparison")


def splits(s: Mapping[str, Any], near: float, far: float) -> tuple[np.ndarray, np.ndarray]:
    """The cascades' eye-depth ranges ``(near_i, far_i)`` [world units] (``_splitFrustum``).

    Example
    -------
    >>> a, b = splits(PROFILES[0].resolve({"lambda": 0}), 1.0, 101.0)
    >>> b.round(9).tolist()          # uniform: four equal slices of 1..101
    [26.0, 51.0, 76.0, 101.0]
    """
    k = int(PROFILES[0].setting("numCascades").clamped(s["numCascades"]))
    lam = float(PROFILES[0].setting("lambda").clamped(s["lambda"]))
    lo, hi = (min(max(float(s[key]), 0.0), 1.0) for key in ("minDistance", "maxDistance"))
    if lo > hi:
        lo, hi = 0.0, 1.0
    cut = s["shadowMaxZ"]
    cut = far if cut is None or not near <= float(cut) <= far else float(cut)  # the setter ignores the rest
    top = min((cut - near) / (far - near), hi) if near <= cut < far else hi
    span = far - near
    z0, z1 = near + lo * span, near + top * span
    if not z1 > z0:
        raise ValueError(f"the cascades are empty: minDistance {lo:g} must lie below maxDistance {top:g} (and shadowMaxZ above near)")
    p = np.arange(1, k + 1) / k
    ends = lam * (z0 * (z1 / z0) ** p - (z0 + (z1 - z0) * p)) + z0 + (z1 - z0) * p
    return np.concatenate([[z0], ends[:-1]]), ends


def blend_bands(s: Mapping[str, Any], near: float, far: float) -> tuple:
    """The eye-depth range (start, end) of each blend band between cascade i and i + 1 [world units].

    The receivers blend cascade i into i + 1 over the last ``cascadeBlendPercentage`` of cascade
    i's depth range (``lightFragment.js``: ``diff < frustumLength·cascadeBlendPercentage``;
    ``CSG`` line 730); none at 0 or for a ShadowGenerator.

    Example
    -------
    >>> s = PROFILES[0].resolve({"lambda": 0})
    >>> [tuple(round(x, 9) for x in band) for band in blend_bands(s, 1.0, 101.0)]
    [(23.5, 26.0), (48.5, 51.0), (73.5, 76.0)]
    """
    p = float(s["cascadeBlendPercentage"])
    if s["class"] != "CascadedShadowGenerator" or p == 0:
        return ()
    a, b = splits(s, near, far)
    return tuple((float(bi - p * (bi - ai)), float(bi)) for ai, bi in zip(a[:-1], b[:-1]))


#: The name of the ShadowGenerator's half-float rounding in its bias rule (a fixed part, not a setting).
HALF_FLOAT = "half-float map"
#: Half a unit in the last place of a half float in [½, 1): the most the stored depth rounds by [normalized depth].
HALF_FLOAT_STEP = 2.0**-12


def _build(s: Mapping[str, Any], camera) -> Pipeline:
    side = faces(s)
    res = int(s["mapSize"])
    factor = bias_factor(s)
    normal = BiasTerm("normalBias", float(s["normalBias"]), "normal", 1.0, "sin")
    notes = []
    if s["filter"] is not None and filter_name(s) != s["filter"]:
        notes.append(f"CascadedShadowGenerator does not take {s['filter']}: it logs an error and uses FILTER_NONE")
    if s["class"] == "ShadowGenerator":
        size = float(s["light.shadowFrustumSize"])
        if not size > 0:
            raise ValueError("light.shadowFrustumSize must be > 0 [world units] for a ShadowGenerator: at 0 Babylon fits the shadow "
                             "casters' bounding box, which needs the scene")
        lo = camera.near if s["light.shadowMinZ"] is None else float(s["light.shadowMinZ"])
        hi = camera.far if s["light.shadowMaxZ"] is None else float(s["light.shadowMaxZ"])
        if not hi > lo:
            raise ValueError(f"light.shadowMaxZ must exceed light.shadowMinZ ({lo:g}), got {hi:g}")
        terms = (BiasTerm("bias", float(s["bias"]), "depth", factor * (hi - lo)), normal)
        if filter_name(s) == "FILTER_NONE":
            # shadowGenerator.js 659–668: the map is a half-float colour target where the device renders and filters half
            # floats (WebGL 2 does); the stored (z + 1)/2 + bias keeps 11 significant bits, so it lies up to half a unit in
            # the last place, 2⁻¹² above depth ½, below the caster's: bias lost, not a shift of the surface (no contact)
            terms += (BiasTerm(HALF_FLOAT, -HALF_FLOAT_STEP, "depth", hi - lo, contact=False),)
            notes.append(f"the map is half float (11 significant bits): up to 2⁻¹²·(shadowMaxZ − shadowMinZ) = {HALF_FLOAT_STEP * (hi - lo):.3g} "
                         "world units of the bias is lost to the stored depth's rounding")
        rule = BiasRule(terms, side)
        return Pipeline((camera.near,), (camera.far,), "fixed", "none", res, rule, _filter(s), box=(size, size), depth_range=(lo, hi),
                        notes=tuple(notes + ["the shadow box is fixed (light.shadowFrustumSize): shadows outside it are lost"]))
    if res < 3:
        raise ValueError(f"mapSize must be at least 3 texels for the toolkit's cascade fits, got {res}")
    a, b = splits(s, camera.near, camera.far)
    stable = bool(s["stabilizeCascades"])
    rule = BiasRule((BiasTerm("bias", float(s["bias"]), "depth_range", factor), normal), side, resolution=res)
    clamp = bool(s["depthClamp"]) and filter_name(s) != "FILTER_PCSS"
    notes.append("the cascade's light near..far shrinks to the shadow casters' bounds: the bias rule takes the fitted box's extent "
                 "along the light (casters filling it)" + (", at least 1 world unit (depthClamp, line 417)" if clamp else ""))
    if s["autoCalcDepthBounds"]:
        notes.append("autoCalcDepthBounds sets minDistance/maxDistance from the depth buffer each frame: the given ones are used")
    if float(s["frustumEdgeFalloff"]):
        notes.append(f"frustumEdgeFalloff {s['frustumEdgeFalloff']:g} fades the shadows near the map's edges (not modelled)")
    return Pipeline(tuple(a), tuple(b), "centroid16" if stable else "tight", "origin", res, rule, _filter(s),
                    layout=f"array of {len(a)}", blend=float(s["cascadeBlendPercentage"]), stable=stable, min_extent=1.0 if clamp else 0.0,
                    split="babylon" if float(s["lambda"]) == 0.5 and s["minDistance"] == 0 and s["maxDistance"] == 1 else "",
                    notes=tuple(notes), bands=blend_bands(s, camera.near, camera.far))


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """JavaScript that sets ``keys`` of ``s`` (None: every setting, on a new generator) on the user's light's generator.

    ``light`` is the light's name in the scene (``scene.getLightByName``); None writes a placeholder.
    The generator is the light's own: the one for ``camera`` (a cascaded generator is registered
    under its camera), else the light's first (``Light.getShadowGenerator(camera)`` returns null for
    an unregistered camera and ``getShadowGenerators()`` lists them all, src/Lights/light.ts; the
    inspector takes it the same way); its map size through the ``mapSize`` setter, which recreates
    the map (``ShadowGenerator.mapSize``, src/Lights/Shadows/shadowGenerator.ts).
    """
    cls = s["class"]
    if keys is None:
        want = set(s)
        lines = [f"const gen = new BABYLON.{cls}({s['mapSize']}, light{', undefined, camera' if cls == 'CascadedShadowGenerator' else ''});"]
    else:
        want = set(keys)
        lines = [f"const light = scene.getLightByName({light!r});" if light else "const light = sun;  // your DirectionalLight",
                 "const gen = light.getShadowGenerator(camera) ?? light.getShadowGenerators().values().next().value;"]
        if "mapSize" in want:
            lines.append(f"gen.mapSize = {s['mapSize']};")
    order = (["numCascades", "lambda", "cascadeBlendPercentage", "stabilizeCascades", "depthClamp", "autoCalcDepthBounds"]
             if cls == "CascadedShadowGenerator" else [])
    order += ["bias", "normalBias", "frustumEdgeFalloff", "forceBackFacesOnly", "contactHardeningLightSizeUVRatio", "darkness"]
    if s["filter"] is not None and "EXPONENTIAL" in s["filter"]:
        order += ["depthScale", "useKernelBlur", "blurKernel", "blurBoxOffset", "blurScale"]
    lines += [f"gen.{k} = {_js(s[k])};" for k in order if k in want]
    if cls == "CascadedShadowGenerator":
        if s["shadowMaxZ"] is not None and "shadowMaxZ" in want:
            lines.append(f"gen.shadowMaxZ = {_js(s['shadowMaxZ'])};")
        if want & {"minDistance", "maxDistance"} and (keys is not None or (s["minDistance"], s["maxDistance"]) != (0.0, 1.0)):
            lines.append(f"gen.setMinMaxDistance({_js(s['minDistance'])}, {_js(s['maxDistance'])});")
    else:
        if "light.shadowFrustumSize" in want:
            lines.append(f"light.shadowFrustumSize = {_js(s['light.shadowFrustumSize'])};")
        for k in ("light.shadowMinZ", "light.shadowMaxZ"):
            if s[k] is not None and k in want:
                lines.append(f"{k} = {_js(s[k])};")
    if s["filter"] is not None and "filter" in want:
        lines.append(f"gen.filter = BABYLON.ShadowGenerator.{s['filter']};")
    if "filteringQuality" in want:
        lines.append(f"gen.filteringQuality = BABYLON.ShadowGenerator.{s['filteringQuality']};")
    for k in ("material.backFaceCulling", "material.cullBackFaces"):
        if k in want and (keys is not None or not s[k]):
            lines.append(f"{k} = {_js(s[k])};")
    return "\n".join(lines)


def _js(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return f"{v:g}" if isinstance(v, float) else str(v)


_CSG = (("class", "CascadedShadowGenerator"),)
#: What :func:`aliasing.tune.tune` searches: the CascadedShadowGenerator's count, size, λ,
#: stabilization and shadowMaxZ, both biases and the PCF quality (PCF's kernel moves only the bias), which faces
#: cast (``forceBackFacesOnly``) and the blend band.
TUNABLE = (
    Tunable("numCascades", "cascades", values=(2, 3, 4), when=_CSG),
    Tunable("mapSize", "size", values=(512, 1024, 2048, 4096, 8192)),
    Tunable("lambda", "split", range=(0.0, 1.0), step=0.05, when=_CSG),
    Tunable("stabilizeCascades", "stable", values=(False, True), when=_CSG),
    Tunable("shadowMaxZ", "distance", when=_CSG),
    Tunable("bias", "bias"),
    Tunable("normalBias", "bias"),
    Tunable("filteringQuality", "filter", values=("QUALITY_HIGH", "QUALITY_MEDIUM", "QUALITY_LOW")),
    # which faces cast: Lights/Shadows/shadowGenerator.js forceBackFacesOnly (lines 618, 1002–1020 at the pin)
    Tunable("forceBackFacesOnly", "faces", values=(False, True)),
    # the blend band: Lights/Shadows/cascadedShadowGenerator.pure.js cascadeBlendPercentage (lines 575, 730 at the pin)
    Tunable("cascadeBlendPercentage", "blend", values=(0.0, 0.05, 0.1, 0.2), when=_CSG),
)

PROFILES = (
    Profile("babylon", "Babylon.js", "9.35", _settings(), _build, releases=("9.35.0", "9"), snippet=snippet, language="javascript",
            source="npm @babylonjs/core 9.35.0 (Lights/Shadows, Lights/directionalLight, Shaders/ShadersInclude/shadowMap*)",
            npm="@babylonjs/core@9.35.0", tunable=TUNABLE),
)
