"""Godot 4: DirectionalLight3D's shadow (Forward+ / Mobile renderers) and its project settings.

Read from godotengine/godot as stored in the index (Godot 4, 4.4 or later: the light has
``shadow_caster_mask``; release ``4``); each file at the commit it was stored at:

* ``scene/3d/light_3d.cpp`` (commit 8ea4ec95): the properties and their editor ranges
  (``Light3D::_bind_methods``, ``DirectionalLight3D::_bind_methods``) and defaults
  (``Light3D::Light3D``: split offsets 0.1, 0.2, 0.5, pancake 20, blur 1, bias 0.1;
  ``DirectionalLight3D::DirectionalLight3D``: max distance 100, fade start 0.8, normal bias 2.0,
  ``SHADOW_PARALLEL_4_SPLITS``, blend splits off);
* ``servers/rendering/renderer_scene_cull.cpp`` (commit 0001ea78)
  ``_light_instance_setup_directional_shadow``: the splits (``distances[i + 1] = min_distance +
  split_i·range`` from the camera near to min(max_distance, camera far)), the fit (the sphere
  around the slice corners' average, radius × R/(R − 2), ends snapped to 4r/R), the blend overlap
  (with blend splits on, split i ≥ 1 is fitted from ``distances[i − 1]``) and the bias scale
  ``z_max − z_min_cam`` = 2r + pancake_size;
* ``servers/rendering/renderer_rd/storage_rd/light_storage.cpp`` (the light data):
  ``shadow_bias[j] = shadow_bias / 100 · bias_scale · soft_shadow_scale`` with
  ``soft_shadow_scale = shadow_blur · directional_shadow_quality_radius`` (PCF, no angular size),
  ``shadow_normal_bias[j] = shadow_normal_bias · shadow_texel_size`` (2r/R), and
  ``get_directional_light_shadow_size``: 4 splits are quadrants of the one atlas (R = size/2),
  2 splits halves (size × size/2), orthogonal the whole atlas;
* ``servers/rendering/renderer_scene_render_rd.cpp`` ``directional_soft_shadow_filter_set_quality``:
  the quality radius 1, 1.5, 2, 2, 3, 4 and Vogel-disk samples 0, 1, 4, 8, 16, 32 (Hard … Ultra);
* ``scene_forward_clustered.glsl`` ``BIAS_FUNC``: the receiver moves along the light by
  ``shadow_bias[j]`` and across it by ``normal · shadow_normal_bias[j]`` less its part along the
  light; the blend ``smoothstep(0.9·split, split, depth)``;
* ``servers/rendering_server.cpp``: ``directional_shadow/size`` 4096 (256–16384) and
  ``soft_shadow_filter_quality`` 2 (Soft Low).

The renderer (``rendering/renderer/rendering_method``, default ``forward_plus``, Godot's desktop
default) picks the rest.  Forward+ and Mobile: the RD light data and ``BIAS_FUNC`` above.
``gl_compatibility`` (the web export; what ``aliasing frames --engine godot`` renders and measures,
docs/ERRATA.md F13), from 4.6-stable's ``drivers/gles3/shaders/scene.glsl`` (as the web runtime's
``index.wasm`` holds it) and ``drivers/gles3/rasterizer_scene_gles3.cpp`` ``_render_shadow_pass`` /
``_setup_lights``: the depth pass moves each caster vertex by ``v·b/|v|²`` in the light's view
(b = ``shadow_bias``/100 · (2r + pancake_size), about ``shadow_bias``/100 world units), the receiver
moves along its normal by ``shadow_normal_bias`` · 2r/R on every face turned to the sun, the filter
is one hardware lookup or a fixed 5- or 13-tap PCF (:data:`COMPAT_PCF`), blend splits mix over
the whole split.

The constant term (Forward+), in world units along the light, is therefore
``shadow_bias/100 · (2r + pancake_size) · shadow_blur · quality_radius``: at the defaults
0.001·(w·2048 + 20)·2 per cascade of texel w, about 4.1 texels plus 4 cm.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable

LIGHT = "scene/3d/light_3d.cpp"
CULL = "servers/rendering/renderer_scene_cull.cpp _light_instance_setup_directional_shadow"
STORAGE = "servers/rendering/renderer_rd/storage_rd/light_storage.cpp"
SERVER = "servers/rendering_server.cpp"
AT = " (godotengine/godot commit 8ea4ec95)"
RENDERER = "rendering/renderer/rendering_method"
RENDERERS = ("forward_plus", "mobile", "gl_compatibility")
COMPAT = "drivers/gles3/shaders/scene.glsl (Godot 4.6-stable, as its web runtime's index.wasm holds it)"
#: gl_compatibility: soft_shadow_filter_quality → taps of scene.glsl's sample_shadow (1: one hardware 2×2 lookup;
#: 5: SHADOW_MODE_PCF_5, ±1 texel; 13: SHADOW_MODE_PCF_13, ±2 texels); measured in Godot 4.6's web runtime (ERRATA F13)
COMPAT_PCF = {0: 1, 1: 1, 2: 5, 3: 5, 4: 13, 5: 13}
MODES = ("SHADOW_ORTHOGONAL", "SHADOW_PARALLEL_2_SPLITS", "SHADOW_PARALLEL_4_SPLITS")
SPLITS = {"SHADOW_ORTHOGONAL": 1, "SHADOW_PARALLEL_2_SPLITS": 2, "SHADOW_PARALLEL_4_SPLITS": 4}
SIZE = "rendering/lights_and_shadows/directional_shadow/size"
QUALITY = "rendering/lights_and_shadows/directional_shadow/soft_shadow_filter_quality"
BITS = "rendering/lights_and_shadows/directional_shadow/16_bits"
#: directional_soft_shadow_filter_set_quality: (quality radius, Vogel-disk samples) for Hard … Soft Ultra
QUALITY_RADIUS = {0: (1.0, 0), 1: (1.5, 1), 2: (2.0, 4), 3: (2.0, 8), 4: (3.0, 16), 5: (4.0, 32)}
QUALITY_NAMES = ("Hard", "Soft Very Low", "Soft Low", "Soft Medium", "Soft High", "Soft Ultra")
#: the numbers .tscn files store: DirectionalLight3D::ShadowMode (scene/3d/light_3d.h) and RenderingServer::ShadowQuality
#: (servers/rendering_server.h: SHADOW_QUALITY_HARD = 0 … SHADOW_QUALITY_SOFT_ULTRA = 5; the project setting's hint spells them as QUALITY_NAMES)
MODE_NUMBERS = dict(enumerate(MODES))
QUALITY_ALIASES = {**{n: i for i, n in enumerate(QUALITY_NAMES)},
                   **{"SHADOW_QUALITY_" + n.upper().replace(" ", "_"): i for i, n in enumerate(QUALITY_NAMES)}}
BLEND_BAND = 0.1  # smoothstep(split − 0.1·split, split, depth) in scene_forward_clustered.glsl
FIT, SNAP = "centroid", "godot"  # the stable fit of renderer_scene_cull.cpp (aliasing.engines.stable)

SETTINGS = (
    Setting("directional_shadow_mode", "SHADOW_PARALLEL_4_SPLITS", "", "choice", MODES, aliases=MODE_NUMBERS,
            source=f"{LIGHT} DirectionalLight3D::DirectionalLight3D; scene/3d/light_3d.h ShadowMode{AT}", doc="orthogonal (1 map), PSSM 2 or PSSM 4 splits"),
    Setting("directional_shadow_split_1", 0.1, "fraction of (max distance − near)", "float", (0.0, 1.0),
            source=f"{LIGHT} Light3D::Light3D (PARAM_SHADOW_SPLIT_1_OFFSET){AT}", doc="end of split 1 (2 and 4 splits)"),
    Setting("directional_shadow_split_2", 0.2, "fraction of (max distance − near)", "float", (0.0, 1.0),
            source=f"{LIGHT} Light3D::Light3D (PARAM_SHADOW_SPLIT_2_OFFSET){AT}", doc="end of split 2 (4 splits)"),
    Setting("directional_shadow_split_3", 0.5, "fraction of (max distance − near)", "float", (0.0, 1.0),
            source=f"{LIGHT} Light3D::Light3D (PARAM_SHADOW_SPLIT_3_OFFSET){AT}", doc="end of split 3 (4 splits)"),
    Setting("directional_shadow_blend_splits", False, "", "bool", source=f"{LIGHT} DirectionalLight3D::DirectionalLight3D{AT}",
            doc="blend each split into the next over its last 10 % (the next split's map then covers both)"),
    Setting("directional_shadow_fade_start", 0.8, "fraction of max distance", "float", (0.0, 1.0),
            source=f"{LIGHT} DirectionalLight3D::DirectionalLight3D{AT}", doc="shadows fade out from here to the max distance"),
    Setting("directional_shadow_max_distance", 100.0, "m", "float", (0.0, None),
            source=f"{LIGHT} DirectionalLight3D::DirectionalLight3D{AT}", doc="shadows end at min(this, camera far); 0: camera far"),
    Setting("directional_shadow_pancake_size", 20.0, "m", "float", (0.0, None),
            source=f"{LIGHT} Light3D::Light3D{AT}", doc="depth kept in front of each split's sphere; part of the bias scale"),
    Setting("shadow_bias", 0.1, "% of (2r + pancake_size)", "float", (0.0, 10.0), source=f"{LIGHT} Light3D::Light3D{AT}",
            doc="the receiver moves along the light by shadow_bias/100 · (2r + pancake) · shadow_blur · quality radius"),
    Setting("shadow_normal_bias", 2.0, "texels", "float", (0.0, 10.0), source=f"{LIGHT} DirectionalLight3D::DirectionalLight3D{AT}",
            doc="the receiver moves across the light by normal · this · the split's texel (along-light part removed)"),
    Setting("shadow_blur", 1.0, "", "float", (0.0, 10.0), source=f"{LIGHT} Light3D::Light3D{AT}",
            doc="scales the PCF radius and the constant bias"),
    Setting("shadow_reverse_cull_face", False, "", "bool", source=f"{LIGHT} Light3D::_bind_methods{AT}",
            doc="draw the back faces into the map instead of the front faces"),
    Setting("light_angular_distance", 0.0, "deg", "float", (0.0, 90.0), source=f"{LIGHT} Light3D::_bind_methods{AT}",
            doc="> 0: PCSS soft shadows (the quality radius no longer scales the bias)"),
    Setting(SIZE, 4096, "texels", "int", (256, 16384), source=f"{SERVER} GLOBAL_DEF",
            doc="side of the one directional shadow atlas (4 splits: quadrants of size/2)"),
    Setting(QUALITY, 2, "", "int", (0, 5), aliases=QUALITY_ALIASES, source=f"{SERVER} GLOBAL_DEF; servers/rendering_server.h ShadowQuality{AT}",
            doc="0 Hard, 1 Soft Very Low, 2 Soft Low, 3 Soft Medium, 4 Soft High, 5 Soft Ultra"),
    Setting(BITS, True, "", "bool", source=f"{SERVER} GLOBAL_DEF", doc="16-bit depth atlas (else 32-bit)"),
    Setting(RENDERER, "forward_plus", "", "choice", RENDERERS, source="main/main.cpp GLOBAL_DEF_RST_BASIC (the first renderer hint: forward_plus on desktop; rendering_method.web: gl_compatibility)",
            doc="forward_plus and mobile: the RD renderer's bias and filter; gl_compatibility (the web export): its own (rule, filter_of)"),
)


def distances(s: Mapping[str, Any], camera) -> tuple[list[float], int]:
    """The split distances [m] (camera near … min(max distance, far)) and the split count, as
    ``_light_instance_setup_directional_shadow`` computes them (module docstring).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> s = {st.key: st.default for st in SETTINGS}
    >>> [round(d, 2) for d in distances(s, SimpleNamespace(near=0.5, far=40.0))[0]]
    [0.5, 4.45, 8.4, 20.25, 40.0]
    """
    k = SPLITS[s["directional_shadow_mode"]]
    far = camera.far
    if s["directional_shadow_max_distance"] > 0:
        far = min(float(s["directional_shadow_max_distance"]), far)
    far = max(far, camera.near + 0.001)  # MAX(max_distance, z_near + 0.001)
    keys = ("directional_shadow_split_1", "directional_shadow_split_2", "directional_shadow_split_3")
    given = {f"s{i + 1}": float(s[key]) for i, key in enumerate(keys[: k - 1])}
    try:
        edges = partitioning.split_distances("godot", camera.near, far, k, **given)
    except ValueError as err:
        raise ValueError(f"{', '.join(keys[: k - 1])} must increase strictly within (0, 1) for {s['directional_shadow_mode']} "
                         f"(got {', '.join(f'{s[key]:g}' for key in keys[: k - 1])}): {err}") from None
    return [float(x) for x in edges], k


def filter_of(s: Mapping[str, Any]) -> Filter:
    """The directional filter: the RD renderer's Vogel disk, or the Compatibility renderer's fixed PCF (:data:`COMPAT_PCF`).

    Examples
    --------
    >>> s = {st.key: st.default for st in SETTINGS}
    >>> filter_of({**s, RENDERER: "gl_compatibility"}).taps, filter_of(s).taps
    (3, 5)
    """
    quality = int(s[QUALITY])
    if s.get(RENDERER, "forward_plus") == "gl_compatibility":
        taps = COMPAT_PCF[quality]
        if taps == 1:
            return Filter("pcf", 2, 0.0, note=f"Compatibility, {QUALITY_NAMES[quality]}: one hardware 2×2 comparison ({COMPAT} sample_shadow)")
        return Filter("pcf", 3 if taps == 5 else 5, 1.0 if taps == 5 else 2.0,
                      note=f"Compatibility, {QUALITY_NAMES[quality]}: SHADOW_MODE_PCF_{taps}, {taps} hardware 2×2 comparisons "
                      f"to ±{1 if taps == 5 else 2} atlas texels ({COMPAT} sample_shadow)")
    radius, samples = QUALITY_RADIUS[quality]
    if s["light_angular_distance"] > 0:
        return Filter("pcss", max(2, samples), 0.0, note="PCSS-like soft shadows from light_angular_distance (penumbra samples, not modelled as PCF)")
    if quality == 0:
        return Filter("pcf", 2, 0.0, note="Hard: one hardware 2×2 comparison")
    r = float(s["shadow_blur"]) * radius
    taps = max(2, 2 * math.ceil(r - 1e-9) + 1)
    return Filter("pcf", taps, r, note=f"{QUALITY_NAMES[quality]}: {samples} Vogel-disk taps over a radius of shadow_blur × {radius:g} atlas "
                  "texels, each a hardware 2×2 comparison; later splits scale the radius by the split ratio (blur_factor)")


def rule(s: Mapping[str, Any], resolution: int) -> BiasRule:
    """Godot's bias rule for splits of ``resolution`` texels (the split's texture size R).

    Constant: ``shadow_bias``/100 · (2r + pancake_size) · shadow_blur · quality radius along the
    light, with 2r = w·R (w the split's texel): a ``depth_texels`` term of scale R·soft/100 and
    offset pancake/R.  Normal: ``shadow_normal_bias`` texels across the light (``across_texels``).
    """
    faces = "back" if s["shadow_reverse_cull_face"] else "front"
    if s.get(RENDERER, "forward_plus") == "gl_compatibility":
        # the caster moves v·b/|v|² in the light's view, b = shadow_bias/100·(2r + pancake): about b/(r + pancake),
        # shadow_bias/100 world units for a small r (exact in aliasing.frames.models.godot); the receiver moves along
        # its normal by shadow_normal_bias texels on every face turned to the sun (scene.glsl's base_normal_bias)
        return BiasRule((BiasTerm("shadow_bias", float(s["shadow_bias"]), "depth", 0.01),
                         BiasTerm("shadow_normal_bias", float(s["shadow_normal_bias"]), "normal_texels", 1.0)), faces)
    angular = float(s["light_angular_distance"])
    soft = float(s["shadow_blur"]) * (QUALITY_RADIUS[int(s[QUALITY])][0] if angular <= 0 else 1.0)
    return BiasRule((BiasTerm("shadow_bias", float(s["shadow_bias"]), "depth_texels", resolution * soft / 100.0,
                              offset=float(s["directional_shadow_pancake_size"]) / resolution),
                     BiasTerm("shadow_normal_bias", float(s["shadow_normal_bias"]), "across_texels", 1.0)), faces)


def layout(size: int, k: int) -> tuple[int, int, str]:
    """(texels across, texels along t, words) of each split in Godot's one directional atlas of ``size`` × ``size`` texels.

    Example
    -------
    >>> layout(4096, 4)
    (2048, 2048, 'atlas 2x2: one 4096² texture, each split a 2048² quadrant')
    >>> layout(4096, 2)[:2]
    (4096, 2048)
    """
    if k == 4:
        return size // 2, size // 2, f"atlas 2x2: one {size}² texture, each split a {size // 2}² quadrant"
    if k == 2:
        return size, size // 2, f"atlas 1x2: one {size}² texture, each split a {size}×{size // 2} half"
    return size, size, f"one {size}² texture"


def build(s: Mapping[str, Any], camera) -> Pipeline:
    """Godot's pipeline for ``camera`` (module docstring)."""
    edges, k = distances(s, camera)
    size = int(s[SIZE])
    res, rows, words = layout(size, k)
    blend = bool(s["directional_shadow_blend_splits"]) and k > 1
    near_i = [edges[i - 1] if blend and i > 0 else edges[i] for i in range(k)]
    far_i = edges[1:]
    if s.get(RENDERER, "forward_plus") == "gl_compatibility":  # scene.glsl: smoothstep(previous offset, offset, depth), the whole split
        bands = tuple((edges[i] if i else 0.0, edges[i + 1]) for i in range(k - 1)) if blend else ()
    else:
        bands = tuple((edges[i + 1] * (1 - BLEND_BAND), edges[i + 1]) for i in range(k - 1)) if blend else ()
    frac = max(((b - a) / (edges[i + 1] - edges[i]) for i, (a, b) in enumerate(bands)), default=0.0)
    notes = [
        f"directional_shadow_fade_start: shadows fade out over [{s['directional_shadow_fade_start']:g}, 1] × {edges[-1]:g} (not modelled)",
        "each split's ends are snapped to 4r/R: the map's size is kept to within one snap unit (not modelled)",
        "one directional light with shadows is assumed: more lights split the atlas further (_get_directional_shadow_rect)",
    ]
    return Pipeline(tuple(near_i), tuple(far_i), FIT, SNAP, res, rule(s, res), filter_of(s), layout=words, blend=frac,
                    stable=True, memory=size * size * (2 if s[BITS] else 4), split="godot", notes=tuple(notes), rows=rows if rows != res else 0,
                    bands=bands)


def _gd(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return f"{v:g}" if isinstance(v, float) else str(v)


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """GDScript that sets ``keys`` of ``s`` (None: every setting) on the user's light, then the project settings' renderer calls.

    ``light`` is the DirectionalLight3D's node name (``$Name``); None writes ``$Sun`` marked as a placeholder.
    """
    want = set(s) if keys is None else set(keys)
    node = f"${light}" if light and light.replace("_", "").isalnum() else f'get_node("{light}")' if light else "$Sun  # your light"
    lines = [f"var light: DirectionalLight3D = {node}"]
    if keys is None:
        lines.append("light.shadow_enabled = true")
    if "directional_shadow_mode" in want:
        lines.append(f"light.directional_shadow_mode = DirectionalLight3D.{s['directional_shadow_mode']}")
    for key in ("directional_shadow_split_1", "directional_shadow_split_2", "directional_shadow_split_3", "directional_shadow_blend_splits",
                "directional_shadow_fade_start", "directional_shadow_max_distance", "directional_shadow_pancake_size", "shadow_bias",
                "shadow_normal_bias", "shadow_blur", "shadow_reverse_cull_face", "light_angular_distance"):
        if key in want:
            lines.append(f"light.{key} = {_gd(s[key])}")
    if want & {SIZE, BITS}:
        lines.append(f"RenderingServer.directional_shadow_atlas_set_size({s[SIZE]}, {_gd(s[BITS])})  # {SIZE}, {BITS}")
    if QUALITY in want:
        quality = ("HARD", "SOFT_VERY_LOW", "SOFT_LOW", "SOFT_MEDIUM", "SOFT_HIGH", "SOFT_ULTRA")[int(s[QUALITY])]
        lines.append(f"RenderingServer.directional_soft_shadow_filter_set_quality(RenderingServer.SHADOW_QUALITY_{quality})  # {QUALITY}")
    return "\n".join(lines)


_SPLITS = frozenset(("SHADOW_PARALLEL_2_SPLITS", "SHADOW_PARALLEL_4_SPLITS"))
#: What :func:`aliasing.tune.tune` searches: the mode (1, 2 or 4 splits), the split fractions
#: each mode reads, the max distance, the atlas size, both biases, blend splits and, with the
#: Compatibility renderer, its filter quality.
TUNABLE = (
    Tunable("directional_shadow_mode", "cascades", values=("SHADOW_ORTHOGONAL", "SHADOW_PARALLEL_2_SPLITS", "SHADOW_PARALLEL_4_SPLITS")),
    Tunable("directional_shadow_split_1", "split", range=(0.0, 1.0), step=0.05, when=(("directional_shadow_mode", _SPLITS),)),
    Tunable("directional_shadow_split_2", "split", range=(0.0, 1.0), step=0.05, when=(("directional_shadow_mode", "SHADOW_PARALLEL_4_SPLITS"),)),
    Tunable("directional_shadow_split_3", "split", range=(0.0, 1.0), step=0.05, when=(("directional_shadow_mode", "SHADOW_PARALLEL_4_SPLITS"),)),
    Tunable("directional_shadow_max_distance", "distance"),
    Tunable("rendering/lights_and_shadows/directional_shadow/size", "size", values=(1024, 2048, 4096, 8192, 16384)),
    Tunable("shadow_bias", "bias"),
    Tunable("shadow_normal_bias", "bias"),
    Tunable("directional_shadow_blend_splits", "blend", values=(False, True), when=(("directional_shadow_mode", _SPLITS),)),
    # the Compatibility renderer's three filters (COMPAT_PCF: Hard, Soft Low, Soft High are one lookup, PCF_5, PCF_13; the
    # qualities between repeat them), which the frames render and predict; Forward+'s Vogel disk is not searched
    Tunable(QUALITY, "filter", values=(0, 2, 4), when=((RENDERER, "gl_compatibility"),)),
)

PROFILES = (
    Profile("godot", "Godot DirectionalLight3D", "4", SETTINGS, build, releases=("4.4", "4.5", "4.6"), snippet=snippet,
            language="gdscript", source="godotengine/godot as stored (light_3d.cpp 8ea4ec95, renderer_scene_cull.cpp 0001ea78; "
            "light_storage.cpp, scene_forward_clustered.glsl, rendering_server.cpp as stored)", tunable=TUNABLE),
)
