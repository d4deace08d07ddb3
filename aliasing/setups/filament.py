"""Filament: a directional light's ShadowOptions (LightManager) and the View's shadow type.

Read from google/filament as stored in the index (the bias, split and stable presets cite the
same files):

* ``filament/include/filament/LightManager.h`` ``ShadowOptions``: ``mapSize`` 1024,
  ``shadowCascades`` 1 (1–4), ``cascadeSplitPositions`` {0.125, 0.25, 0.5}, ``constantBias``
  0.001 m, ``normalBias`` 1, ``shadowFar`` 0 (the camera's far), ``shadowNearHint`` 1,
  ``shadowFarHint`` 100, ``stable`` false, ``lispsm`` true, ``polygonOffsetConstant`` 0.5,
  ``polygonOffsetSlope`` 2, ``screenSpaceContactShadows`` false, ``stepCount`` 8,
  ``maxShadowDistance`` 0.3;
* ``filament/src/ShadowMapManager.cpp`` (commit 003e5005): ``CascadeSplits`` (positions as
  fractions of (far − near) from near), ``shadowDimension = mapSize − 2`` (a one-texel border),
  the normal bias × the texel's world size;
* ``filament/src/ShadowMap.cpp`` (commit 0362f36e): the stable fit (the sphere around the
  slice corners' average, origin snapped to even texels; with ``shadowFar`` > 0 the sphere
  {camera, shadowFar} for every cascade); LiSPSM off in stable mode;
* ``shaders/src/common_shadowing.fs`` ``computeLightSpacePosition``: the receiver moves along its
  normal by normalBias·texel·sin θ; the polygon offset is the rasterizer's.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable, float32

OPTIONS = "filament/include/filament/LightManager.h ShadowOptions (google/filament as stored)"
TYPES = ("PCF", "VSM", "DPCF", "PCSS")  # View::ShadowType's first four, 0–3 (View.h; PCFd = 4 is for debugging)
STABLE_FIT, FAR_FIT, SNAP = "centroid", "far", "border"  # stable mode without / with shadowFar; the one-texel border

SETTINGS = float32((  # the fields are float (LightManager.h ShadowOptions)
    Setting("mapSize", 1024, "texels", "int", (8, 16384), source=OPTIONS, doc="side of each cascade's map (a power of two, >= 8)"),
    Setting("shadowCascades", 1, "", "int", (1, 4), source=OPTIONS, doc="number of cascades, 1 to 4"),
    Setting("cascadeSplitPositions[0]", 0.125, "fraction of (far − near)", "float", (0.0, 1.0), source=OPTIONS, doc="end of cascade 1"),
    Setting("cascadeSplitPositions[1]", 0.25, "fraction of (far − near)", "float", (0.0, 1.0), source=OPTIONS, doc="end of cascade 2"),
    Setting("cascadeSplitPositions[2]", 0.5, "fraction of (far − near)", "float", (0.0, 1.0), source=OPTIONS, doc="end of cascade 3"),
    Setting("constantBias", 0.001, "m", "float", (None, None), source=OPTIONS, doc="shadows moved away from the light by this"),
    Setting("normalBias", 1.0, "texels", "float", (None, None), source=OPTIONS, doc="the receiver moves along its normal by this × texel × sin θ"),
    Setting("shadowFar", 0.0, "m", "float", (0.0, None), source=OPTIONS, doc="where shadows end; 0: the camera's far"),
    Setting("shadowNearHint", 1.0, "m", "float", (0.0, None), source=OPTIONS, doc="LiSPSM's near hint"),
    Setting("shadowFarHint", 100.0, "m", "float", (0.0, None), source=OPTIONS, doc="LiSPSM's far hint"),
    Setting("stable", False, "", "bool", source=OPTIONS, doc="stable fit (sphere, origin snapped); LiSPSM off"),
    Setting("lispsm", True, "", "bool", source=OPTIONS,
            doc="light-space perspective warping of each map (the C++ default; the Java binding's ShadowOptions defaults it to false)"),
    Setting("polygonOffsetConstant", 0.5, "depth-buffer units", "float", (None, None), source=OPTIONS, doc="rasterizer constant depth offset"),
    Setting("polygonOffsetSlope", 2.0, "", "float", (None, None), source=OPTIONS, doc="rasterizer slope-scaled depth offset"),
    Setting("screenSpaceContactShadows", False, "", "bool", source=OPTIONS, doc="screen-space contact shadows (not modelled)"),
    Setting("stepCount", 8, "", "int", (1, 255), source=OPTIONS, doc="contact shadow steps"),
    Setting("maxShadowDistance", 0.3, "m", "float", (0.0, None), source=OPTIONS, doc="contact shadow ray length"),
    Setting("View.shadowType", "PCF", "", "choice", TYPES, aliases=dict(enumerate(TYPES)),
            source="filament/include/filament/View.h setShadowType (default PCF), enum class ShadowType",
            doc="PCF, VSM, DPCF or PCSS"),
))


def rule(s: Mapping[str, Any]) -> BiasRule:
    """constantBias along the light [m], normalBias texels × sin θ along the normal, polygonOffsetSlope."""
    return BiasRule((BiasTerm("constantBias", float(s["constantBias"]), "depth", 1.0),
                     BiasTerm("normalBias", float(s["normalBias"]), "normal_texels", 1.0, "sin"),
                     BiasTerm("polygonOffsetSlope", float(s["polygonOffsetSlope"]), "slope", 1.0)), "front")


def _filter(s: Mapping[str, Any]) -> Filter:
    kind = s["View.shadowType"]
    if kind == "PCF":
        return Filter("pcf", 2, 0.0, note="PCF by hardware comparison (one 2×2 lookup)")
    if kind == "VSM":
        return Filter("vsm", 1, 0.0, note="variance shadow maps (no depth bias needed; light bleeding instead)")
    return Filter("pcss" if kind == "PCSS" else "pcf", 2, 0.0, note=f"{kind}: soft shadows from View::setSoftShadowOptions (kernel not modelled)")


def build(s: Mapping[str, Any], camera) -> Pipeline:
    """Filament's cascades for ``camera`` (module docstring)."""
    k = int(s["shadowCascades"])
    res = int(s["mapSize"])
    if res & (res - 1):
        raise ValueError(f"mapSize must be a power of two in [8, 16384] texels, got {res}")
    far = camera.far if s["shadowFar"] <= 0 else min(float(s["shadowFar"]), camera.far)
    if not far > camera.near:
        raise ValueError(f"shadowFar must exceed the camera's near ({camera.near:g}), got {s['shadowFar']:g}")
    keys = ("cascadeSplitPositions[0]", "cascadeSplitPositions[1]", "cascadeSplitPositions[2]")[: k - 1]
    given = {f"s{i + 1}": float(s[key]) for i, key in enumerate(keys)}
    try:
        edges = partitioning.split_distances("filament", camera.near, far, k, **given)
    except ValueError as err:
        raise ValueError(f"{', '.join(keys)} must increase strictly within (0, 1): {err}") from None
    notes = ["polygonOffsetConstant: a few units of the depth format's resolution, below 1e-6 of the light's depth range (not modelled)",
             "memory assumes 4 bytes per texel (the depth format was not read)",
             "faces: the material's culling (default back faces culled) is assumed in the shadow pass"]
    if s["stable"]:
        fit, stable = (FAR_FIT, True) if s["shadowFar"] > 0 else (STABLE_FIT, True)
    else:
        fit, stable = "tight", False
        if s["lispsm"]:
            notes.append("lispsm: each map is warped (LiSPSM, Wimmer 2004) from the hints; the pipeline's texels are the unwarped box's (not modelled)")
    if s["screenSpaceContactShadows"]:
        notes.append("screen-space contact shadows are not modelled")
    return Pipeline(tuple(edges[:-1]), tuple(edges[1:]), fit, SNAP, res, rule(s), _filter(s), layout=f"array: {k} layers of {res}²",
                    stable=stable, split="filament", notes=tuple(notes))


def _cpp(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        text = f"{v:g}"
        return (text if any(c in text for c in ".en") else text + ".0") + "f"
    return str(v)


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """C++ that sets ``keys`` of ``s`` (None: every setting, on a new light) on the user's sun entity.

    With ``keys`` the light's own ShadowOptions are read, changed and set back
    (``LightManager::getShadowOptions``/``setShadowOptions``, filament/include/filament/LightManager.h); ``light``
    names the entity's variable (None: ``sun``, marked as a placeholder).
    """
    want = set(s) if keys is None else set(keys)
    order = ("mapSize", "shadowCascades", "constantBias", "normalBias", "shadowFar", "shadowNearHint", "shadowFarHint", "stable", "lispsm",
             "polygonOffsetConstant", "polygonOffsetSlope", "screenSpaceContactShadows", "stepCount", "maxShadowDistance")
    sets = [f"options.{k} = {_cpp(s[k])};" for k in order if k in want]
    sets += [f"options.cascadeSplitPositions[{i}] = {_cpp(s[f'cascadeSplitPositions[{i}]'])};" for i in range(3)
             if f"cascadeSplitPositions[{i}]" in want]
    view = [f"view->setShadowType(View::ShadowType::{s['View.shadowType']});"] if "View.shadowType" in want else []
    if keys is None:
        return "\n".join(["LightManager::ShadowOptions options;", *sets,
                          "LightManager::Builder(LightManager::Type::SUN).castShadows(true).shadowOptions(options).build(*engine, sun);", *view])
    if not sets:
        return "\n".join(view)
    entity = light or "sun"
    return "\n".join(["auto& lm = engine->getLightManager();",
                      f"auto instance = lm.getInstance({entity});" + ("" if light else "  // sun: your light's entity"),
                      "LightManager::ShadowOptions options = lm.getShadowOptions(instance);", *sets,
                      "lm.setShadowOptions(instance, options);", *view])


#: What :func:`aliasing.tune.tune` searches: the cascade count, the split positions that count
#: reads, the map size, both biases, stabilization and shadowFar.
TUNABLE = (
    Tunable("shadowCascades", "cascades", values=(1, 2, 3, 4)),
    Tunable("cascadeSplitPositions[0]", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascades", frozenset((2, 3, 4))),)),
    Tunable("cascadeSplitPositions[1]", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascades", frozenset((3, 4))),)),
    Tunable("cascadeSplitPositions[2]", "split", range=(0.0, 1.0), step=0.05, when=(("shadowCascades", 4),)),
    Tunable("mapSize", "size", values=(512, 1024, 2048, 4096, 8192)),
    Tunable("constantBias", "bias"),
    Tunable("normalBias", "bias"),
    Tunable("stable", "stable", values=(False, True)),
    Tunable("shadowFar", "distance"),
)

PROFILES = (
    Profile("filament", "Filament directional light", "1.5x", SETTINGS, build, releases=("main", "1"), snippet=snippet, language="cpp",
            source="google/filament as stored: LightManager.h ShadowOptions, ShadowMapManager.cpp 003e5005, ShadowMap.cpp 0362f36e, common_shadowing.fs", tunable=TUNABLE),
)
