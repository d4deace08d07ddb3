"""Each engine's settings (its own keys and defaults) and the toolkit's model of its shadow pass.

A model turns the engine's settings into what the toolkit predicts: which faces cast, which
cascade each pixel samples, the bias and the filter (from the engine's shader source in the
pinned package), and the cascades' ends and map sides from the toolkit's presets
(:data:`aliasing.engines.stable.PRESETS`, :func:`aliasing.partitioning.split_distances`).

Examples
--------
>>> sorted(MODELS)
['babylon', 'godot', 'playcanvas', 'threejs']
>>> MODELS["threejs"].settings({"shadowBias": 0})["shadowBias"]   # CSM: `data.shadowBias || 0.000001`
1e-06
"""

from __future__ import annotations


import numpy as np
from numpy.typing import NDArray

from ..predict import Prediction, reference
from ..single import BabylonSingle, ThreeDirectional
from .babylon import BabylonCSM, tight_sides
from .filament import Filament
from .godot import Godot
from .playcanvas import PlayCanvas
from .threejs import ThreeCSM

Array = NDArray[np.float64]
__all__ = ["MODELS", "SINGLE", "Prediction", "reference", "tight_sides", "ThreeCSM", "ThreeDirectional", "BabylonCSM", "BabylonSingle",
           "PlayCanvas", "Filament", "Godot", "model_for", "from_setup"]


MODELS = {"threejs": ThreeCSM(), "babylon": BabylonCSM(), "playcanvas": PlayCanvas(), "godot": Godot()}
#: the engines' single-map classes, by the ``class`` setting
SINGLE = {("threejs", "DirectionalLight"): ThreeDirectional(), ("babylon", "ShadowGenerator"): BabylonSingle()}


def model_for(engine: str, settings: dict):
    """The model of ``engine`` for these settings: its single-map class where ``settings["class"]`` names one, else its cascades'.

    Examples
    --------
    >>> type(model_for("threejs", {"class": "DirectionalLight"})).__name__, type(model_for("threejs", {})).__name__
    ('ThreeDirectional', 'ThreeCSM')
    """
    if engine == "filament":
        return FILAMENT
    if engine not in MODELS:
        raise ValueError(f"engine must be one of {', '.join(sorted(MODELS))}, got {engine!r}")
    return SINGLE.get((engine, (settings or {}).get("class")), MODELS[engine])


_THREE_SIDE = {"FrontSide": "front", "BackSide": "back", "DoubleSide": "double"}
_FACES = {"front": "front", "back": "back", "both": "double"}
_PC_TYPES = {"SHADOW_PCF3_32F": 0, "SHADOW_VSM_16F": 2, "SHADOW_VSM_32F": 3, "SHADOW_PCF5_32F": 4, "SHADOW_PCF1_32F": 5, "SHADOW_PCSS_32F": 6,
             "SHADOW_PCF1_16F": 7, "SHADOW_PCF3_16F": 8, "SHADOW_PCF5_16F": 9}
_PC_CULL = {"CULLFACE_BACK": "back", "CULLFACE_FRONT": "front", "CULLFACE_NONE": "none"}


def from_setup(setup) -> dict:
    """The settings the engine's page and the model take, from an :class:`aliasing.setups.Setup`
    (every key in the engine's own spelling, defaults filled), checked against what is rendered
    and modelled here; the pipeline's faces that cast must be the model's.

    Raises
    ------
    ValueError
        A setting the frames do not render or model (its key and why), or a pipeline that
        disagrees with the model about the faces that cast.

    Examples
    --------
    >>> from aliasing import setups
    >>> s = from_setup(setups.build("threejs", {"cascades": 2}, "near=0.5,far=60,fov=50,aspect=16:9,height=144", "35@30"))
    >>> s["cascades"], s["shadowMapSize"], s["side"]
    (2, 2048, 'front')
    """
    if not (hasattr(setup, "settings") and hasattr(setup, "engine") and hasattr(setup, "pipeline")):
        raise ValueError(f"setup must be an aliasing.setups.Setup, got {type(setup).__name__}")
    engine, s = setup.engine, dict(setup.settings)
    if engine == "filament":
        return FILAMENT.from_setup(setup)
    if engine == "godot":
        from ...setups.godot import RENDERER

        if s[RENDERER] != "gl_compatibility":
            raise ValueError(f"{RENDERER} must be gl_compatibility: Godot's frames are its web runtime, the Compatibility renderer, the "
                             f"one the toolkit renders and predicts (set {RENDERER}=gl_compatibility: its bias and filter are then "
                             f"the ones checked and tuned), got {s[RENDERER]!r}")
    if engine not in MODELS:
        raise ValueError(f"engine must be one of {', '.join(sorted(MODELS))}, got {engine!r}")
    if engine == "threejs" and s["class"] == "DirectionalLight":
        out = {"class": "DirectionalLight", "mapSize": s["shadow.mapSize.width"], "bias": s["shadow.bias"], "normalBias": s["shadow.normalBias"],
               "radius": s["shadow.radius"], "shadowMapType": s["renderer.shadowMap.type"], "side": _THREE_SIDE[s["material.side"]],
               "shadowSide": None if s["material.shadowSide"] == "null" else _THREE_SIDE[s["material.shadowSide"]],
               **{k: s[f"shadow.camera.{k}"] for k in ("left", "right", "top", "bottom", "near", "far")}}
        if out["shadowMapType"] == "PCFSoftShadowMap":  # WebGLShadowMap replaces it (lines 99-102)
            out["shadowMapType"] = "PCFShadowMap"
    elif engine == "threejs":
        if s["class"] != "CSM":
            raise ValueError(f"class must be CSM or DirectionalLight for the frames, got {s['class']!r}")
        if s["shadow.bias"] != 0:
            raise ValueError("shadow.bias is overwritten by CSM's shadowBias on every cascade light: set shadowBias")
        out = {k: s[k] for k in ("cascades", "maxFar", "mode", "shadowMapSize", "shadowBias", "lightNear", "lightFar", "lightMargin", "fade")}
        out.update(normalBias=s["shadow.normalBias"], shadowRadius=s["shadow.radius"], shadowMapType=s["renderer.shadowMap.type"],
                   side=_THREE_SIDE[s["material.side"]], shadowSide=None if s["material.shadowSide"] == "null" else _THREE_SIDE[s["material.shadowSide"]])
        if out["shadowMapType"] == "PCFSoftShadowMap":  # WebGLShadowMap replaces it (lines 99-102)
            out["shadowMapType"] = "PCFShadowMap"
    elif engine == "babylon" and s["class"] == "ShadowGenerator":
        if s["filter"] not in (None, "FILTER_NONE"):
            raise ValueError(f"filter must be null or FILTER_NONE for a ShadowGenerator's frames (modelled), got {s['filter']!r}")
        for key, want in (("darkness", 0.0), ("frustumEdgeFalloff", 0.0)):
            if s[key] != want:
                raise ValueError(f"{key} must be {want!r} for the frames (modelled), got {s[key]!r}")
        if s["material.backFaceCulling"] != s["material.cullBackFaces"] and not s["material.cullBackFaces"]:
            raise ValueError("material.cullBackFaces false (front faces culled) is not rendered by the frames")
        out = {"class": "ShadowGenerator", "mapSize": s["mapSize"], "bias": s["bias"], "normalBias": s["normalBias"],
               "shadowFrustumSize": s["light.shadowFrustumSize"], "shadowMinZ": s["light.shadowMinZ"], "shadowMaxZ": s["light.shadowMaxZ"],
               "forceBackFacesOnly": s["forceBackFacesOnly"], "backFaceCulling": s["material.backFaceCulling"]}
    elif engine == "babylon":
        if s["class"] != "CascadedShadowGenerator":
            raise ValueError(f"class must be CascadedShadowGenerator or ShadowGenerator for the frames, got {s['class']!r}")
        for key, want in (("filter", None), ("minDistance", 0.0), ("maxDistance", 1.0), ("light.shadowMinZ", None), ("light.shadowMaxZ", None),
                          ("light.shadowFrustumSize", 0.0)):
            if s[key] != want:
                raise ValueError(f"{key} must be {want!r} for the frames (modelled), got {s[key]!r}")
        out = {k: s[k] for k in ("mapSize", "numCascades", "lambda", "bias", "normalBias", "frustumEdgeFalloff", "stabilizeCascades",
                                 "cascadeBlendPercentage", "depthClamp", "autoCalcDepthBounds", "shadowMaxZ", "forceBackFacesOnly")}
        out["filteringQuality"] = {"QUALITY_HIGH": 0, "QUALITY_MEDIUM": 1, "QUALITY_LOW": 2}[s["filteringQuality"]]
        if s["material.backFaceCulling"] != s["material.cullBackFaces"] and not s["material.cullBackFaces"]:
            raise ValueError("material.cullBackFaces false (front faces culled) is not rendered by the frames")
        out["backFaceCulling"] = s["material.backFaceCulling"]
    elif engine == "godot":
        out = dict(s)
    else:
        out = {k: s[k] for k in ("shadowBias", "normalOffsetBias", "shadowResolution", "numCascades", "cascadeDistribution", "cascadeBlend",
                                 "shadowDistance")}
        out["shadowType"] = _PC_TYPES[s["shadowType"]]
        out["cull"] = _PC_CULL[s["material.cull"]]
    model = model_for(engine, out)
    full = model.settings(out)
    if getattr(model, "predicts", True):
        faces = _FACES[setup.pipeline.bias.faces]
        if faces != model.cast_side(full):
            raise ValueError(f"the setup's pipeline casts {setup.pipeline.bias.faces} faces, the frames' model {model.cast_side(full)}")
    return full


FILAMENT = Filament()
