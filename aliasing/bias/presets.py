"""The engines' bias rules for directional lights, read from their source, as presets.

Every engine moves the looked-up point (or the caster) by hand-tuned amounts, some scaled by
the cascade's texel size.  For a planar receiver at θ from the light, each kind of offset is
a depth bias along the light in disguise (:mod:`aliasing.symbolic.bias`):

* a constant along the light, b: b;
* a normal offset o (along the receiver's normal): o/cos θ;
* an offset s across the light (the normal's part perpendicular to the light): s·tan θ;
* a caster moved by o along its own normal, away from the light side: o/cos θ;
* a slope-scaled bias f of the rasterizer state: f·w·tan θ·max(|cos φ|, |sin φ|);
* a depth bias in units of the map's depth range along the light (Babylon.js: the caster's
  depth in [0, 1] over each cascade's near..far), the range taken as the map's side w·R.

:func:`equivalent_depth` sums them; :func:`aliasing.bias.plane_bias` says what is needed.  For
the lit gap at a contact (peter-panning) only the part along the light counts: a normal
offset raises the looked-up ground point and moves it across the map by amounts that cancel
exactly against a vertical caster (derived in the guide page), so ``contact_depth`` is the
constant part alone.

Each preset names the file it was read from; the lookups are modelled as k×k PCF of the
width of the engine's default filter (hardware 2×2 comparison sampling is k = 2).  The
``threejs`` and ``babylon`` presets are views of the engine profiles
(:mod:`aliasing.setups.threejs`, :mod:`aliasing.setups.babylon`: :func:`from_profile`), so a
profile's correction is the preset's.  ``faces`` says which faces the engine draws into the
map by default; the acne computed here is that of front faces casting (the receiver compares
against itself): where the back faces cast (three.js), a closed or one-sided lit receiver does
not compare against itself, so the acne shown is that of ``material.shadowSide = FrontSide``.

Example
-------
>>> p = PRESETS["filament"]
>>> round(equivalent_depth(p, 0.1, 45.0), 6)   # 0.001 + 1·sin45°·0.1/cos45° + 2·0.1·tan45°
0.301
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from .. import setups
from .plane import _receiver

Array = NDArray[np.float64]


@dataclass(frozen=True)
class BiasPreset:
    """One engine's default bias rule for a directional light (world units unless said).

    Attributes
    ----------
    name, engine : str
        Preset key and engine (release).
    source : str
        Repository file(s) the rule was read from.
    depth : float
        Constant depth bias along the light [world units].
    depth_texels : float
        Depth bias along the light in texels (× the cascade's texel size).
    normal_texels : float
        Normal offset in texels (× texel size × ``normal_scale`` of θ).
    normal_scale : str
        ``one``, ``sin`` (× sin θ) or ``one-minus-cos`` (× (1 − cos θ)).
    across_texels : float
        Offset across the light in texels, × sin θ (the normal with its along-light part removed).
    slope : float
        Slope-scaled depth bias of the rasterizer state (``glPolygonOffset`` factor, Direct3D
        ``SlopeScaledDepthBias``): × the caster's depth change per texel, max(|∂d/∂s|, |∂d/∂t|).
    pcf : int
        Width of the default filter, modelled as k×k PCF [texels].
    partial : str
        What of the engine's rule is not modelled (empty when all of it is).
    normal : float
        Normal offset in world units (× ``normal_scale`` of θ).
    depth_map : float
        Depth bias as a fraction of the map's depth range along the light, taken as the map's
        side w·R (× texel × resolution).
    faces : str
        Which faces the engine draws into the map by default: ``front``, ``back`` or ``both``.
    """

    name: str
    engine: str
    source: str
    depth: float = 0.0
    depth_texels: float = 0.0
    normal_texels: float = 0.0
    normal_scale: str = "one"
    across_texels: float = 0.0
    slope: float = 0.0
    pcf: int = 1
    partial: str = ""
    normal: float = 0.0
    depth_map: float = 0.0
    faces: str = "front"


def from_profile(name: str, engine: str, source: str, spec: str, settings: dict | None = None, partial: str = "") -> BiasPreset:
    """The bias preset of an engine profile's rule at ``settings`` (defaults: the engine's): :func:`from_rule`
    of its pipeline's rule, with the filter's width as ``pcf``.

    Example
    -------
    >>> p = from_profile("b", "Babylon.js", "", "babylon")
    >>> round(p.depth_map, 12), p.pcf, p.faces          # 1.5 × bias 0.00005 (PCF with depthClamp); PCF5; front faces
    (7.5e-05, 5, 'front')
    """
    pipeline = setups.build(spec, settings or {}).pipeline
    return from_rule(name, engine, source, pipeline.bias, max(1, pipeline.filter.taps), partial)


def from_rule(name: str, engine: str, source: str, rule, pcf: int, partial: str = "") -> BiasPreset:
    """A preset from an engine profile's bias rule (``aliasing.setups.BiasRule``): each term's
    value × scale to the preset's field of its kind (``depth_range`` to ``depth_map``; a texel
    term's ``offset`` o adds c·v·o to ``depth``), and the rule's faces.

    Raises
    ------
    ValueError
        For a term the preset cannot hold (a clamped slope, an offset outside a depth texel
        term, two normal scales), naming the term.

    Example
    -------
    >>> from aliasing.setups import bevy
    >>> p = from_rule("b", "Bevy", "", bevy.rule(bevy.PROFILES[0].defaults()), 5)
    >>> p.depth, p.normal_texels
    (0.02, 1.8)
    """
    fields = {"depth": 0.0, "depth_texels": 0.0, "depth_map": 0.0, "normal": 0.0, "normal_texels": 0.0, "across_texels": 0.0, "slope": 0.0}
    field_of = {"depth_range": "depth_map"}
    scales = set()
    for t in rule.terms:
        c = float(t.value) * float(t.scale)
        if t.kind == "tan_texels" or t.offset and t.kind != "depth_texels":
            raise ValueError(f"bias term {t.key!r} of kind {t.kind!r} has no preset field; use the engine's profile (aliasing.setups)")
        fields[field_of.get(t.kind, t.kind)] += c
        if t.kind == "depth_texels":
            fields["depth"] += c * t.offset
        if t.kind in ("normal", "normal_texels") and t.value:
            scales.add(t.normal_scale)
    if len(scales) > 1:
        raise ValueError(f"bias rule of {name!r} mixes normal scales {sorted(scales)}; a preset holds one")
    scale = scales.pop() if scales else next((t.normal_scale for t in rule.terms if t.kind in ("normal", "normal_texels")), "one")
    return BiasPreset(name, engine, source, normal_scale=scale, pcf=int(pcf), partial=partial, faces=rule.faces, **fields)


def _engine_presets() -> tuple[BiasPreset, ...]:
    """The engines' presets as views of their profiles at the defaults (:mod:`aliasing.setups`)."""
    from ..setups import bevy, filament, godot, unity_urp

    gd = godot.PROFILES[0].defaults()
    gd_res = godot.layout(int(gd[godot.SIZE]), 4)[0]
    unity, soft = unity_urp.PROFILES[0].defaults(), {**unity_urp.PROFILES[0].defaults(), "supportsSoftShadows": True}
    return (
        from_rule("filament", "Filament (1.5x)", "google/filament shaders/src/common_shadowing.fs computeLightSpacePosition (p += n·sinθ·b); "
                  "filament/src/ShadowMapManager.cpp (b = normalBias · texelSizeWorldSpace); include/filament/LightManager.h ShadowOptions (constantBias 0.001, normalBias 1, polygonOffsetSlope 2); PCF by hardware comparison "
                  "(profile aliasing.setups.filament)",
                  filament.rule(filament.PROFILES[0].defaults()), 2),
        from_rule("bevy", "Bevy (0.13+)", "bevyengine/bevy crates/bevy_pbr/src/render/shadows.wgsl sample_directional_cascade (normal_bias · cascade texel_size · n, "
                  "depth_bias · direction_to_light); DirectionalLight::DEFAULT_SHADOW_DEPTH_BIAS 0.02, DEFAULT_SHADOW_NORMAL_BIAS 1.8; default filter Gaussian (Castaño 13-tap, 5×5) "
                  "(profile aliasing.setups.bevy)",
                  bevy.rule(bevy.PROFILES[0].defaults()), 5),
        from_rule("godot", "Godot 4", "godotengine/godot scene_forward_clustered.glsl BIAS_FUNC (along the light: shadow_bias[j]; across it: "
                  "n·shadow_normal_bias[j] less its along-light part); light_storage.cpp (shadow_bias[j] = shadow_bias/100 · bias_scale · shadow_blur · "
                  "quality radius, shadow_normal_bias[j] = shadow_normal_bias · texel); renderer_scene_cull.cpp (bias_scale = 2r + pancake_size); "
                  f"defaults shadow_bias 0.1, shadow_normal_bias 2.0, pancake 20, Soft Low (radius 2); evaluated for {gd_res}² splits (the default "
                  "4096 atlas's quadrants) (profile aliasing.setups.godot)",
                  godot.rule(gd, gd_res), godot.filter_of(gd).taps,
                  partial=f"the constant term scales with the map's side: exact for {gd_res}² splits (the default atlas); other sizes: the godot profile"),
        from_rule("unity-urp", "Unity URP (12–17), hard shadows", "Unity-Technologies/Graphics Packages/com.unity.render-pipelines.universal/Runtime/ShadowUtils.cs GetShadowBias "
                  "(bias × frustumSize/resolution); ShaderLibrary/Shadows.hlsl ApplyShadowBias (caster moved along the light, and along −n by (1 − N·L)·normalBias); RenderShadowSlice SetGlobalDepthBias(1, 2.5); asset defaults 1, 1 "
                  "(profile aliasing.setups.unity_urp)",
                  unity_urp.rule(unity), 2),
        from_rule("unity-urp-soft", "Unity URP (12–17), soft shadows", "as unity-urp; GetShadowBias multiplies both by 2.5 when soft shadows are supported; 5×5 tent filter "
                  "(profile aliasing.setups.unity_urp, supportsSoftShadows)",
                  unity_urp.rule(soft), 5),
    )


PRESETS: dict[str, BiasPreset] = {p.name: p for p in (
    *_engine_presets(),
    from_profile("threejs", "three.js (r150+)", "the three.js profile (aliasing.setups.threejs, npm three 0.187.0): a DirectionalLight's "
                 "src/lights/LightShadow.js bias 0, normalBias 0 (world units along n, shadowmap_vertex.glsl.js); PCFShadowMap filter "
                 "(5 Vogel taps within radius 1, modelled as 3×3 PCF)", "threejs", {"class": "DirectionalLight"},
                 partial="the acne is that of front faces casting: by default three.js draws the back faces of FrontSide materials "
                         "(WebGLShadowMap.js), so closed and one-sided lit receivers do not compare against themselves"),
    from_profile("babylon", "Babylon.js (9.35)", "the Babylon.js profile (aliasing.setups.babylon, npm @babylonjs/core 9.35.0): "
                 "CascadedShadowGenerator bias 0.00005 added to the caster's depth over the cascade's light near..far, ×1.5 with PCF and "
                 "depthClamp (shadowMapVertexMetric.js, shadowMapFragment.js), normalBias 0 (× sin θ, shadowMapVertexNormalBias.js); PCF5",
                 "babylon",
                 partial="the cascade's light near..far is taken as the map's side (exact for stabilizeCascades; the default tight box's "
                         "depth range along the light differs, and casters narrower than the box shrink it)"),
)}

_SCALES = ("one", "sin", "one-minus-cos")


def get(name: str) -> BiasPreset:
    """A preset by name; ValueError names ``preset`` and lists the known ones.

    Example
    -------
    >>> get("Bevy").pcf
    5
    """
    if not isinstance(name, str) or name.strip().lower() not in PRESETS:
        hint = check.did_you_mean(name, list(PRESETS)) if isinstance(name, str) else ""
        raise ValueError(f"unknown bias preset {name!r}{hint}; choose one of: {', '.join(PRESETS)}")
    return PRESETS[name.strip().lower()]


def _normal_scale(preset: BiasPreset, theta: Array) -> Array:
    if preset.normal_scale == "sin":
        return np.sin(theta)
    if preset.normal_scale == "one-minus-cos":
        return 1.0 - np.cos(theta)
    return np.ones_like(theta)


def _map_side(p: BiasPreset, w: Array, resolution: ArrayLike | None) -> Array | float:
    """The depth_map term: depth_map × w × resolution (ValueError naming resolution where it is needed and missing)."""
    if not p.depth_map:
        return 0.0
    if resolution is None:
        raise ValueError(f"resolution (texels per side of the map) is needed for the {p.name} preset: its bias scales with the map's depth range")
    return p.depth_map * w * check.positive(resolution, "resolution")


@check.public
def equivalent_depth(preset: BiasPreset | str, texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike = 0.0,
                     resolution: ArrayLike | None = None) -> float | Array:
    """The preset's offsets as one depth bias along the light [world units], for a plane at ``angle`` from the light.

    b + b_t·w + b_m·w·R + (o + o_t·w)·g(θ)/cos θ + s_t·w·sin θ·tan θ + f·w·tan θ·max(|cos φ|, |sin φ|)
    (module docstring).

    Parameters
    ----------
    preset : BiasPreset or str
        A preset of :data:`PRESETS`.
    texel : array_like
        Texel size w of the cascade [world units], > 0.
    angle : array_like
        θ between the receiver's normal and the direction to the light [deg], in [0, 90).
    azimuth : array_like
        φ, the receiver's steepest depth change from the map's s axis [deg] (the slope term only).
    resolution : array_like, optional
        Texels per side of the map R, > 0: needed by presets with ``depth_map`` (Babylon.js).

    Example
    -------
    >>> round(equivalent_depth("bevy", 0.05, 0.0), 6)   # facing the light: 0.02 + 1.8·0.05
    0.11
    """
    p = get(preset) if isinstance(preset, str) else preset
    check.instance(p, "preset", BiasPreset)
    w, th, ph = _receiver(texel, angle, azimuth)
    steep = np.maximum(np.abs(np.cos(ph)), np.abs(np.sin(ph)))
    b = (p.depth + p.depth_texels * w + _map_side(p, w, resolution) + (p.normal + p.normal_texels * w) * _normal_scale(p, th) / np.cos(th)
         + p.across_texels * w * np.sin(th) * np.tan(th) + p.slope * w * np.tan(th) * steep)
    return float(b) if b.ndim == 0 else b


def contact_depth(preset: BiasPreset | str, texel: ArrayLike, resolution: ArrayLike | None = None) -> float | Array:
    """The part of the preset's bias along the light [world units]: what opens a lit gap at a contact.

    ``resolution``: texels per side of the map, for presets with ``depth_map``.

    Example
    -------
    >>> contact_depth("unity-urp-soft", 0.04)
    0.1
    >>> round(contact_depth("babylon", 0.1, 1024), 9)       # 7.5e-5 of the map's side 0.1·1024
    0.00768
    """
    p = get(preset) if isinstance(preset, str) else preset
    w = check.as_float_array(texel, "texel")
    b = p.depth + p.depth_texels * w + _map_side(p, w, resolution)
    return float(b) if np.ndim(b) == 0 else b
