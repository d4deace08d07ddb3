"""Unreal Engine 5: a movable DirectionalLight's cascaded shadow maps (CSM) and the r.Shadow console variables.

Epic's repository is private; read from copies of its files in the index (not pinned to a
commit; UE5 by their includes of ``VirtualShadowMaps``):

* ``Engine/Source/Runtime/Engine/Classes/Components/DirectionalLightComponent.h`` and the
  constructor in ``DirectionalLightComponent.cpp``: ``DynamicShadowDistanceMovableLight`` 20000
  (cm), ``DynamicShadowCascades`` 3, ``CascadeDistributionExponent`` 3, ``CascadeTransitionFraction``
  0.1, ``ShadowDistanceFadeoutFraction`` 0.1, ``ShadowCascadeBiasDistribution`` 1;
  ``LightComponent``: ``ShadowBias`` 0.5, ``ShadowSlopeBias`` 0.5;
* ``DirectionalLightComponent.cpp`` ``GetSplitDistance`` (near + the accumulated
  exponent scale × (shadow distance − near)), ``GetShadowSplitBounds`` (each non-last cascade
  extended by ``CascadeTransitionFraction`` of its length: the transition band) and
  ``GetShadowSplitBoundsDepthRange`` (the minimal sphere of the slice: the centre equidistant
  from the near and far corners, clamped into the slice: the toolkit's ``sphere`` fit);
  the distance × ``r.Shadow.DistanceScale`` clamped to [0, 2];
* ``Engine/Source/Runtime/Renderer/Private/ShadowRendering.cpp`` (UE5): ``r.Shadow.CSMDepthBias``
  10, ``r.Shadow.CSMSlopeScaleDepthBias`` 3, and ``FProjectedShadowInfo::UpdateShaderDepthBias``:
  DepthBias = CSMDepthBias / (MaxSubjectZ − MinSubjectZ) · lerp(1, W/Res, ShadowCascadeBiasDistribution)
  · ShadowBias (W the bounding sphere's radius), at most 0.1; slope = DepthBias · CSMSlopeScaleDepthBias
  · ShadowSlopeBias;
* ``ShadowDepthVertexShader.usf``: the caster's depth grows by DepthBias + SlopeBias · min(tan θ,
  ``r.Shadow.ShadowMaxSlopeScaleDepthBias``).

In world units along the light that is CSMDepthBias · ShadowBias · (w/2) · (1 + CSMSlopeScaleDepthBias
· ShadowSlopeBias · min(tan θ, max slope)) with w = 2W/Res the texel (distribution 1): 2.5 texels
at the defaults, facing the light.  Distances are Unreal's centimetres.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable, float32

COMPONENT = "Engine/Source/Runtime/Engine/Classes/Components/DirectionalLightComponent.h (copies in the index; Epic's repository is private)"
LIGHTCOMP = ("Engine/Source/Runtime/Engine/Classes/Components/LightComponent.h ULightComponent (ShadowBias 0.5, ShadowSlopeBias 0.5: "
             "read from re-implementations of its header in the index, not from Epic's file)")
RENDERING = "Engine/Source/Runtime/Renderer/Private/ShadowRendering.cpp (UE5, a copy in the index)"
CVAR = "console variable"
FIT, SNAP = "sphere", "origin"

SETTINGS = float32((  # the console variables and properties are float
    Setting("DynamicShadowDistanceMovableLight", 20000.0, "cm", "float", (0.0, None), source=COMPONENT, doc="where CSM shadows end"),
    Setting("DynamicShadowCascades", 3, "", "int", (0, 10), clamp=(0, 10), source=COMPONENT, doc="cascades (0: none; at most r.Shadow.CSM.MaxCascades)"),
    Setting("CascadeDistributionExponent", 3.0, "", "float", (1.0, 4.0), source=COMPONENT, doc="> 1 puts the cascades' ends closer to the camera"),
    Setting("CascadeTransitionFraction", 0.1, "fraction of a cascade", "float", (0.0, 0.3), source=COMPONENT,
            doc="each non-last cascade extends by this fraction of its length: the transition band"),
    Setting("ShadowDistanceFadeoutFraction", 0.1, "fraction", "float", (0.0, 1.0), source=COMPONENT, doc="fade-out at the shadow distance (not modelled)"),
    Setting("ShadowCascadeBiasDistribution", 1.0, "", "float", (0.0, 1.0), source=COMPONENT,
            doc="1: depth bias in texels of each cascade; 0: the same normalized bias in every cascade"),
    Setting("ShadowBias", 0.5, "", "float", (0.0, 10.0), source=LIGHTCOMP, doc="scales r.Shadow.CSMDepthBias (and the slope bias)"),
    Setting("ShadowSlopeBias", 0.5, "", "float", (0.0, 10.0), source=LIGHTCOMP, doc="scales r.Shadow.CSMSlopeScaleDepthBias"),
    Setting("r.Shadow.MaxCSMResolution", 2048, "texels", "int", (4, 16384),
            source="Engine/Source/Runtime/Engine/Private/Components/DirectionalLightComponent.cpp CVarShadowMaxCSMShadowResolution (a copy in the index)",
            doc="side of each cascade's map (range 4 to the hardware limit)"),
    Setting("r.Shadow.CSMDepthBias", 10.0, "", "float", (None, None), source=f"{RENDERING} CVarCSMShadowDepthBias", doc="constant depth bias of CSM"),
    Setting("r.Shadow.CSMSlopeScaleDepthBias", 3.0, "", "float", (None, None), source=f"{RENDERING} CVarCSMShadowSlopeScaleDepthBias",
            doc="slope-scaled depth bias of CSM"),
    Setting("r.Shadow.ShadowMaxSlopeScaleDepthBias", 1.0, "", "float", (0.0, None), source=f"{RENDERING} CVarShadowMaxSlopeScaleDepthBias",
            doc="clamp of the slope tan θ"),
    Setting("r.Shadow.DistanceScale", 1.0, "", "float", (0.0, None), clamp=(0.0, 2.0),
            source=f"{CVAR} (GetCSMMaxDistance clamps it to [0, 2]: seen in a re-implementation of DirectionalLightComponent.cpp, not in Epic's file)",
            doc="scales DynamicShadowDistanceMovableLight"),
    Setting("r.Shadow.Virtual.Enable", 0, "", "int", (0, 1), source=f"{CVAR} (code default 0 assumed, not read; new UE5 projects set 1 in DefaultEngine.ini)",
            doc="1: virtual shadow maps instead of CSM (aliasing.engines.vsm)"),
))


def rule(s: Mapping[str, Any]) -> BiasRule:
    """UpdateShaderDepthBias in world units along the light, for a cascade of texel w (module docstring)."""
    dist = float(s["ShadowCascadeBiasDistribution"])
    if dist != 1.0:
        raise ValueError(f"ShadowCascadeBiasDistribution {dist:g}: only 1 (bias in texels of each cascade) is modelled; "
                         "below 1 the bias depends on each cascade's subject depth range")
    c = float(s["r.Shadow.CSMDepthBias"]) / 2.0  # W/Res = w/2
    user = float(s["ShadowBias"])
    slope = float(s["r.Shadow.CSMSlopeScaleDepthBias"])
    cap = float(s["r.Shadow.ShadowMaxSlopeScaleDepthBias"])
    return BiasRule((BiasTerm("ShadowBias", user, "depth_texels", c),
                     BiasTerm("ShadowSlopeBias", float(s["ShadowSlopeBias"]), "tan_texels", c * user * slope, cap=cap)), "front")


def build(s: Mapping[str, Any], camera) -> Pipeline:
    """Unreal's CSM for ``camera`` [cm]; refuses virtual shadow maps (module docstring)."""
    if int(s["r.Shadow.Virtual.Enable"]):
        raise ValueError("r.Shadow.Virtual.Enable=1 selects virtual shadow maps, not a cascade set: "
                         "set r.Shadow.Virtual.Enable=0 for CSM, or see `aliasing engines --schemes vsm:epic`")
    k = int(s["DynamicShadowCascades"])
    if k < 1:
        raise ValueError("DynamicShadowCascades 0: the light has no CSM cascades")
    scale = min(max(float(s["r.Shadow.DistanceScale"]), 0.0), 2.0)
    far = min(float(s["DynamicShadowDistanceMovableLight"]) * scale, camera.far)
    if not far > camera.near:
        raise ValueError(f"DynamicShadowDistanceMovableLight × r.Shadow.DistanceScale must exceed the camera's near ({camera.near:g} cm), got {far:g}")
    params = {"exponent": float(s["CascadeDistributionExponent"]), "transition": float(s["CascadeTransitionFraction"])}
    lo, hi = partitioning.partitions("unreal", camera.near, far, k, **params)
    edges = partitioning.split_distances("unreal", camera.near, far, k, exponent=params["exponent"])
    bands = tuple((edges[i + 1], hi[i]) for i in range(k - 1))
    res = int(s["r.Shadow.MaxCSMResolution"])
    notes = ("depth bias capped at 0.1 of each cascade's subject depth range (MaxSubjectZ − MinSubjectZ, scene-dependent): not modelled",
             "ShadowBias also scales the slope term: a ShadowBias found with the slope term held fixed is sufficient, not minimal",
             "fit: the minimal sphere of each slice (GetShadowSplitBoundsDepthRange); the texel snap of the origin is assumed (not read)",
             "the shadow depth pass culls back faces (front faces cast): assumed; filter: r.ShadowQuality's PCF kernel, modelled as 5×5 (not read)",
             f"ShadowDistanceFadeoutFraction {s['ShadowDistanceFadeoutFraction']:g}: the fade at the shadow distance is not modelled",
             "memory assumes 4 bytes per texel (the depth format was not read)")
    return Pipeline(tuple(lo), tuple(hi), FIT, SNAP, res, rule(s), Filter("pcf", 5, 2.0, note="manual PCF of r.ShadowQuality (Epic: 5×5), assumed"),
                    layout=f"atlas of {k} maps of {res}²", blend=float(s["CascadeTransitionFraction"]), stable=True, split="unreal",
                    notes=notes, bands=bands)


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """The console variables (DefaultEngine.ini ``[SystemSettings]``) and the light's properties (its .ini/.uasset defaults)
    of ``keys`` (None: every setting); ``light`` names the DirectionalLight actor (None: a placeholder)."""
    want = set(s) if keys is None else set(keys)
    cvars = [k for k in s if k.startswith("r.") and k in want]
    props = [k for k in s if not k.startswith("r.") and k in want]
    lines = ["; DefaultEngine.ini", "[SystemSettings]"] + [f"{k}={s[k]:g}" if isinstance(s[k], float) else f"{k}={s[k]}" for k in cvars] if cvars else []
    if props:
        lines += ([""] if lines else []) + [f"; the DirectionalLight component of {light} (Details panel or C++)" if light else
                                            "; the DirectionalLight component of your sun (Details panel or C++)"]
        lines += [f"; DirectionalLight->{k} = {s[k]:g}" if isinstance(s[k], float) else f"; DirectionalLight->{k} = {s[k]}" for k in props]
    return "\n".join(lines)


#: What :func:`aliasing.tune.tune` searches: the cascade count, the distribution exponent, the
#: dynamic shadow distance, the CSM resolution and both biases.
TUNABLE = (
    Tunable("DynamicShadowCascades", "cascades", values=tuple(range(1, 11))),
    Tunable("CascadeDistributionExponent", "split", range=(1.0, 4.0), step=0.1),
    Tunable("DynamicShadowDistanceMovableLight", "distance"),
    Tunable("r.Shadow.MaxCSMResolution", "size", values=(512, 1024, 2048, 4096, 8192)),
    Tunable("ShadowBias", "bias"),
    Tunable("ShadowSlopeBias", "bias"),
)

PROFILES = (
    Profile("unreal", "Unreal Engine DirectionalLight (CSM)", "5", SETTINGS, build, releases=("5.4", "5.5", "5.6", "ue5"), snippet=snippet,
            language="ini", source="copies of Epic's files in the index (DirectionalLightComponent, ShadowRendering.cpp, ShadowDepthVertexShader.usf); not pinned", tunable=TUNABLE),
)
