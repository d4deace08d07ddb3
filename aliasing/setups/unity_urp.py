"""Unity URP 17: the main directional light's cascaded shadows (UniversalRenderPipelineAsset and Light).

Read from Unity-Technologies/Graphics (com.unity.render-pipelines.universal) as stored in the index:

* ``Runtime/Data/UniversalRenderPipelineAsset.cs``: ``m_ShadowDistance`` 50, ``m_ShadowCascadeCount``
  1, ``m_Cascade2Split`` 0.25, ``m_Cascade3Split`` (0.1, 0.3), ``m_Cascade4Split`` (0.067, 0.2,
  0.467), ``m_CascadeBorder`` 0.2, ``m_ShadowDepthBias`` 1, ``m_ShadowNormalBias`` 1,
  ``m_MainLightShadowmapResolution`` 2048, ``m_SoftShadowsSupported`` false, soft shadow quality
  Medium, ``m_ConservativeEnclosingSphere`` false (the bias and split presets already cite them);
  the cascade count is 1–4 and the biases 0 to ``maxShadowBias`` (10);
* ``Runtime/ShadowUtils.cs`` ``GetShadowBias``: the texel is frustumSize / shadowResolution with
  frustumSize = 2/m00 ("a cube as we wrap shadow frustum around a sphere"); depth and normal
  bias in texels, × the soft kernel radius 1.5 / 2.5 / 3.5 (Low / Medium / High) when soft
  shadows are supported and the light's shadows are Soft; ``GetMaxTileResolutionInAtlas``:
  the cascades are tiles of one atlas (2 cascades: resolution × resolution/2; 3 or 4: a 2×2
  grid of resolution/2); 16-bit depth (``k_ShadowmapBufferBits``);
* ``ShaderLibrary/Shadows.hlsl`` ``ApplyShadowBias``: the caster moves away from the light by
  the depth bias and inwards along its normal by (1 − N·L)·normal bias;
  ``MainLightShadowCasterPass`` ``RenderShadowSlice``: ``SetGlobalDepthBias(1.0, 2.5)``;
* the per-light values (``Light.shadowBias``, ``Light.shadowNormalBias``) replace the asset's
  when the light's ``UniversalAdditionalLightData.usePipelineSettings`` is off.

What rests on assumption (the fit is computed in the engine's closed C++ source,
``CullingResults.ComputeDirectionalShadowMatricesAndCullingPrimitives``): the cascade's sphere is
modelled as the minimal sphere of its slice, unsnapped; the split fractions are taken from the
near plane over (shadowDistance − near), as the split preset ``unity-urp`` does.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable

PKG = "com.unity.render-pipelines.universal"
ASSET = f"{PKG}/Runtime/Data/UniversalRenderPipelineAsset.cs (Unity-Technologies/Graphics as stored)"
UTILS = f"{PKG}/Runtime/ShadowUtils.cs GetShadowBias (Unity-Technologies/Graphics as stored)"
RESOLUTIONS = (256, 512, 1024, 2048, 4096, 8192)
KERNEL = {"Low": 1.5, "Medium": 2.5, "High": 3.5}  # GetShadowBias: kernel radius of the 3×3, 5×5, 7×7 tent
PCF = {"Low": 3, "Medium": 5, "High": 7}
FIT, SNAP = "sphere", "none"  # assumption: the native fit is not public (module docstring)
MAX_BIAS = 10.0  # UniversalRenderPipeline.maxShadowBias

SETTINGS = (
    Setting("shadowDistance", 50.0, "m", "float", (0.0, None), source=ASSET, doc="shadows end here (m_ShadowDistance)"),
    Setting("shadowCascadeCount", 1, "", "int", (1, 4), source=ASSET, doc="1 to 4 cascades"),
    Setting("cascade2Split", 0.25, "fraction of the shadow distance", "float", (0.0, 1.0), source=ASSET, doc="with 2 cascades"),
    Setting("cascade3Split.x", 0.1, "fraction of the shadow distance", "float", (0.0, 1.0), source=ASSET, doc="with 3 cascades"),
    Setting("cascade3Split.y", 0.3, "fraction of the shadow distance", "float", (0.0, 1.0), source=ASSET, doc="with 3 cascades"),
    Setting("cascade4Split.x", 0.067, "fraction of the shadow distance", "float", (0.0, 1.0), source=ASSET, doc="with 4 cascades"),
    Setting("cascade4Split.y", 0.2, "fraction of the shadow distance", "float", (0.0, 1.0), source=ASSET, doc="with 4 cascades"),
    Setting("cascade4Split.z", 0.467, "fraction of the shadow distance", "float", (0.0, 1.0), source=ASSET, doc="with 4 cascades"),
    Setting("cascadeBorder", 0.2, "fraction", "float", (0.0, 1.0), source=ASSET, doc="shadows fade out over this last part (not a blend between cascades)"),
    Setting("mainLightShadowmapResolution", 2048, "texels", "int", (256, 8192), source=ASSET,
            doc="side of the main light's shadow atlas: 256, 512, 1024, 2048, 4096 or 8192"),
    Setting("shadowDepthBias", 1.0, "texels", "float", (0.0, MAX_BIAS), source=ASSET, doc="caster pushed away from the light by this many texels"),
    Setting("shadowNormalBias", 1.0, "texels", "float", (0.0, MAX_BIAS), source=ASSET, doc="caster pulled in along its normal by (1 − N·L) × this many texels"),
    Setting("supportsSoftShadows", False, "", "bool", source=ASSET, doc="soft shadows (the light's Soft type then filters and scales the biases)"),
    Setting("softShadowQuality", "Medium", "", "choice", ("Low", "Medium", "High"), aliases={1: "Low", 2: "Medium", 3: "High"},
            source=f"{ASSET}; {PKG}/Runtime/UniversalAdditionalLightData.cs enum SoftShadowQuality (the asset stores its number)", doc="3×3, 5×5 or 7×7 tent filter"),
    Setting("light.shadows", "Soft", "", "choice", ("Hard", "Soft"), aliases={1: "Hard", 2: "Soft"},
            source="UnityEngine.Light.shadows, enum LightShadows {None, Hard, Soft} (the editor's new Directional Light: Soft Shadows)",
            doc="the light's shadow type; Soft counts only when supportsSoftShadows"),
    Setting("light.usePipelineSettings", True, "", "bool", source=f"{PKG}/Runtime/UniversalAdditionalLightData.cs (as stored)",
            doc="take the biases from the asset; off: the light's own shadowBias and shadowNormalBias"),
    Setting("light.shadowBias", 0.05, "texels", "float", (0.0, MAX_BIAS), source="UnityEngine.Light.shadowBias (default 0.05)",
            doc="the light's depth bias, used when usePipelineSettings is off"),
    Setting("light.shadowNormalBias", 0.4, "texels", "float", (0.0, MAX_BIAS), source="UnityEngine.Light.shadowNormalBias (default 0.4)",
            doc="the light's normal bias, used when usePipelineSettings is off"),
    Setting("light.softShadowQuality", "UsePipelineSettings", "", "choice", ("UsePipelineSettings", "Low", "Medium", "High"),
            aliases={0: "UsePipelineSettings", 1: "Low", 2: "Medium", 3: "High"},
            source=f"{PKG}/Runtime/UniversalAdditionalLightData.cs (as stored)", doc="the light's soft shadow quality"),
)


def _soft(s: Mapping[str, Any]) -> str | None:
    """The soft quality in force, or None for hard shadows."""
    if not (s["supportsSoftShadows"] and s["light.shadows"] == "Soft"):
        return None
    q = s["light.softShadowQuality"]
    return s["softShadowQuality"] if q == "UsePipelineSettings" else q


def rule(s: Mapping[str, Any]) -> BiasRule:
    """GetShadowBias and ApplyShadowBias: depth and normal bias in texels (× the soft kernel radius), slope 2.5."""
    own = not s["light.usePipelineSettings"]
    depth_key, normal_key = ("light.shadowBias", "light.shadowNormalBias") if own else ("shadowDepthBias", "shadowNormalBias")
    quality = _soft(s)
    k = KERNEL[quality] if quality else 1.0
    return BiasRule((BiasTerm(depth_key, float(s[depth_key]), "depth_texels", k),
                     BiasTerm(normal_key, float(s[normal_key]), "normal_texels", k, "one-minus-cos"),
                     BiasTerm("SetGlobalDepthBias.slope", 2.5, "slope", 1.0)), "front")


def _filter(s: Mapping[str, Any]) -> Filter:
    quality = _soft(s)
    if quality is None:
        return Filter("pcf", 2, 0.0, note="hard shadows: one hardware 2×2 comparison")
    return Filter("pcf", PCF[quality], KERNEL[quality], note=f"{quality}: {PCF[quality]}×{PCF[quality]} tent filter (GetShadowBias: kernel radius {KERNEL[quality]:g})")


def layout(resolution: int, k: int) -> tuple[int, int, int, str]:
    """(tile side, atlas width, atlas height, words): URP's main light shadow atlas for ``k`` cascades.

    Example
    -------
    >>> layout(2048, 4)[:3]
    (1024, 2048, 2048)
    >>> layout(2048, 2)[:3]
    (1024, 2048, 1024)
    """
    if k == 1:
        return resolution, resolution, resolution, f"one {resolution}² map"
    height = resolution // 2 if k == 2 else resolution
    tile = resolution // 2
    return tile, resolution, height, f"atlas {resolution}×{height}: {k} tiles of {tile}²"


def build(s: Mapping[str, Any], camera) -> Pipeline:
    """URP's cascades for ``camera`` (module docstring for what is assumed)."""
    k = int(s["shadowCascadeCount"])
    res = int(s["mainLightShadowmapResolution"])
    if res not in RESOLUTIONS:
        raise ValueError(f"mainLightShadowmapResolution must be one of {', '.join(map(str, RESOLUTIONS))} texels, got {res}")
    far = min(float(s["shadowDistance"]), camera.far)
    if not far > camera.near:
        raise ValueError(f"shadowDistance must exceed the camera's near ({camera.near:g}), got {s['shadowDistance']:g}")
    keys = {2: ("cascade2Split",), 3: ("cascade3Split.x", "cascade3Split.y"), 4: ("cascade4Split.x", "cascade4Split.y", "cascade4Split.z")}.get(k, ())
    given = {f"s{i + 1}": float(s[key]) for i, key in enumerate(keys)}
    try:
        edges = partitioning.split_distances("unity-urp", camera.near, far, k, **given)
    except ValueError as err:
        raise ValueError(f"{', '.join(keys)} must increase strictly within (0, 1): {err}") from None
    tile, width, height, words = layout(res, k)
    notes = ("fit: the cascade's culling sphere is computed in closed C++ (ComputeDirectionalShadowMatricesAndCullingPrimitives); "
             "modelled as the minimal sphere of the slice, unsnapped: an assumption",
             "split fractions taken from the near plane over (shadowDistance − near), as the split preset unity-urp (the native normalisation is not public)",
             f"cascadeBorder {s['cascadeBorder']:g}: the fade-out at the end of the shadow distance (not modelled); URP does not blend between cascades",
             "SetGlobalDepthBias constant 1.0 (depth-buffer units) not modelled; conservativeEnclosingSphere not modelled",
             "faces: the Lit shader's ShadowCaster pass culls back faces (Cull [_Cull], default Back): assumed")
    return Pipeline(tuple(edges[:-1]), tuple(edges[1:]), FIT, SNAP, tile, rule(s), _filter(s), layout=words, blend=0.0, stable=False,
                    memory=width * height * 2, split="unity-urp", notes=notes)


def _cs(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return f"{v:g}f" if isinstance(v, float) else str(v)


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """C# that sets ``keys`` of ``s`` (None: every setting): the URP asset, then the user's light.

    ``light`` is the light's GameObject name (``GameObject.Find``); None writes a placeholder.
    """
    want = set(s) if keys is None else set(keys)
    asset = [f"asset.shadowDistance = {_cs(s['shadowDistance'])};" if "shadowDistance" in want else "",
             f"asset.shadowCascadeCount = {s['shadowCascadeCount']};" if "shadowCascadeCount" in want else "",
             f"asset.cascade2Split = {_cs(s['cascade2Split'])};" if "cascade2Split" in want else "",
             f"asset.cascade3Split = new Vector2({_cs(s['cascade3Split.x'])}, {_cs(s['cascade3Split.y'])});"
             if want & {"cascade3Split.x", "cascade3Split.y"} else "",
             f"asset.cascade4Split = new Vector3({_cs(s['cascade4Split.x'])}, {_cs(s['cascade4Split.y'])}, {_cs(s['cascade4Split.z'])});"
             if want & {"cascade4Split.x", "cascade4Split.y", "cascade4Split.z"} else ""]
    asset += [f"asset.{k} = {_cs(s[k]) if k != 'mainLightShadowmapResolution' else s[k]};" for k in
              ("cascadeBorder", "mainLightShadowmapResolution", "shadowDepthBias", "shadowNormalBias") if k in want]
    if want & {"supportsSoftShadows", "softShadowQuality"}:
        asset.append(f"// supportsSoftShadows = {_cs(s['supportsSoftShadows'])} and softShadowQuality = SoftShadowQuality.{s['softShadowQuality']} "
                     "are set in the asset's inspector")
    asset = [a for a in asset if a]
    lines = (["var asset = (UniversalRenderPipelineAsset)GraphicsSettings.currentRenderPipeline;"] + asset) if asset else []
    own = [f"light.shadows = LightShadows.{s['light.shadows']};" if "light.shadows" in want else "",
           f"light.shadowBias = {_cs(s['light.shadowBias'])};" if "light.shadowBias" in want else "",
           f"light.shadowNormalBias = {_cs(s['light.shadowNormalBias'])};" if "light.shadowNormalBias" in want else ""]
    data = [f"data.usePipelineSettings = {_cs(s['light.usePipelineSettings'])};" if "light.usePipelineSettings" in want else "",
            f"data.softShadowQuality = SoftShadowQuality.{s['light.softShadowQuality']};" if "light.softShadowQuality" in want else ""]
    own, data = [x for x in own if x], [x for x in data if x]
    if own or data:
        lines.append(f'var light = GameObject.Find("{light}").GetComponent<Light>();' if light
                     else "var light = RenderSettings.sun;  // your main light")
        lines += own
    if data:
        lines += ["var data = light.GetUniversalAdditionalLightData();"] + data
    return "\n".join(lines)


#: What :func:`aliasing.tune.tune` searches: the cascade count, the split fractions that count
#: reads, the shadow distance, the resolution, both biases and soft shadows.
TUNABLE = (
    Tunable("shadowCascadeCount", "cascades", values=(1, 2, 3, 4)),
    Tunable("cascade2Split", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascadeCount", 2),)),
    Tunable("cascade3Split.x", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascadeCount", 3),)),
    Tunable("cascade3Split.y", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascadeCount", 3),)),
    Tunable("cascade4Split.x", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascadeCount", 4),)),
    Tunable("cascade4Split.y", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascadeCount", 4),)),
    Tunable("cascade4Split.z", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascadeCount", 4),)),
    Tunable("shadowDistance", "distance"),
    Tunable("mainLightShadowmapResolution", "size", values=RESOLUTIONS),
    Tunable("shadowDepthBias", "bias"),
    Tunable("shadowNormalBias", "bias"),
    Tunable("supportsSoftShadows", "filter", values=(False, True)),
)

PROFILES = (
    Profile("unity-urp", "Unity URP main light", "17", SETTINGS, build, releases=("17.0", "6000.0", "unity6"), snippet=snippet, language="csharp",
            source="Unity-Technologies/Graphics com.unity.render-pipelines.universal as stored (UniversalRenderPipelineAsset.cs, ShadowUtils.cs, "
            "Shadows.hlsl, MainLightShadowCasterPass.cs); the fit is in closed C++", tunable=TUNABLE),
)
