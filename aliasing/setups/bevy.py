"""Bevy: a DirectionalLight with its CascadeShadowConfig (cascaded shadow maps).

Read from bevyengine/bevy as stored in the index (the current layout with ``crates/bevy_light``):

* ``crates/bevy_light/src/cascade.rs`` (commit 0876f40a, ``aliasing.partitioning.BEVY_RELEASE``):
  ``CascadeShadowConfigBuilder::default`` (4 cascades, ``minimum_distance`` 0.1,
  ``maximum_distance`` 150, ``first_cascade_far_bound`` 10, ``overlap_proportion`` 0.2),
  ``calculate_cascade_bounds`` (geometric from the first bound) and ``build`` (near bound of
  cascade i = (1 − overlap_proportion)·far bound of i − 1);
* ``crates/bevy_pbr/src/light/mod.rs`` ``calculate_cascade`` (commit c62a6fcd): the map side is
  ceil(max(body diagonal, far-face diagonal)), the centre floored to a texel (fit ``diagonal``,
  snap ``bevy`` of :mod:`aliasing.engines.stable`), ``texel_size = diameter / size``;
* ``DirectionalLight::DEFAULT_SHADOW_DEPTH_BIAS`` 0.02 and ``DEFAULT_SHADOW_NORMAL_BIAS`` 1.8,
  ``DirectionalLightShadowMap::default`` 2048, ``ShadowFilteringMethod::default`` Gaussian (the
  bias preset ``bevy`` already cites them);
* ``crates/bevy_pbr/src/render/light.rs`` ``prepare_lights`` (as stored): the light's biases
  go to the GPU unchanged, the maps are layers of one ``Depth32Float`` array of ``size`` × ``size`` texels, at
  most ``MAX_CASCADES_PER_LIGHT`` (4) cascades per light;
* ``crates/bevy_pbr/src/render/shadows.wgsl`` ``sample_directional_cascade``: the receiver moves
  by ``shadow_normal_bias · texel_size`` along its normal and ``shadow_depth_bias`` towards the
  light; ``fetch_directional_shadow`` blends cascade i into i + 1 linearly over
  [(1 − overlap_proportion)·far_i, far_i]; ``shadow_sampling.wgsl``: Hardware2x2 one comparison,
  Gaussian Castaño's 5×5 filter (``sample_shadow_map_castano_thirteen``: 9 bilinear comparison
  taps weighted over 6×6 texels), Temporal Jimenez's 8 rotating taps.

Distances are Bevy's metres; the cascades start at ``minimum_distance``, not the camera's near.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .. import partitioning
from .profile import BiasRule, BiasTerm, Filter, Pipeline, Profile, Setting, Tunable, float32

CASCADE = "crates/bevy_light/src/cascade.rs CascadeShadowConfigBuilder::default (bevyengine/bevy commit 0876f40a)"
LIGHT = "crates/bevy_light/src/directional_light.rs (bevyengine/bevy as stored)"
MAX_CASCADES = 4  # MAX_CASCADES_PER_LIGHT (non-WebGL)
FIT, SNAP = "diagonal", "bevy"
FILTERS = ("Hardware2x2", "Gaussian", "Temporal")

SETTINGS = float32((  # the fields are f32 (DirectionalLight, CascadeShadowConfig)
    Setting("num_cascades", 4, "", "int", (1, 64), clamp=(1, MAX_CASCADES), source=CASCADE,
            doc="cascades (build asserts > 0; at most MAX_CASCADES_PER_LIGHT = 4 are rendered, so shadows end at the 4th bound)"),
    Setting("minimum_distance", 0.1, "m", "float", (0.0, None), source=CASCADE, doc="where the first cascade starts"),
    Setting("maximum_distance", 150.0, "m", "float", (0.0, None), source=CASCADE, doc="where the last cascade ends"),
    Setting("first_cascade_far_bound", 10.0, "m", "float", (0.0, None), source=CASCADE,
            doc="end of the first cascade; the others grow geometrically to maximum_distance"),
    Setting("overlap_proportion", 0.2, "", "float", (0.0, 0.99), source=CASCADE,
            doc="each cascade starts this fraction before the previous one ends; the blend band (build asserts < 1)"),
    Setting("shadow_depth_bias", 0.02, "m", "float", (None, None), source=f"{LIGHT} DEFAULT_SHADOW_DEPTH_BIAS",
            doc="the receiver moves this far towards the light"),
    Setting("shadow_normal_bias", 1.8, "texels", "float", (None, None), source=f"{LIGHT} DEFAULT_SHADOW_NORMAL_BIAS",
            doc="the receiver moves this many texels along its normal"),
    Setting("DirectionalLightShadowMap.size", 2048, "texels", "int", (1, 16384),
            source="crates/bevy_light/src/directional_light.rs DirectionalLightShadowMap::default (bevyengine/bevy as stored)",
            doc="side of each cascade's layer (capped at the device's max_texture_dimension_2d)"),
    Setting("ShadowFilteringMethod", "Gaussian", "", "choice", FILTERS,
            source="crates/bevy_pbr/src/lib.rs ShadowFilteringMethod::default (bevyengine/bevy as stored)",
            doc="Hardware2x2, Gaussian (Castaño 2013, 5×5) or Temporal (Jimenez 2014)"),
))


def _filter(s: Mapping[str, Any]) -> Filter:
    method = s["ShadowFilteringMethod"]
    if method == "Hardware2x2":
        return Filter("pcf", 2, 0.0, note="one hardware 2×2 comparison")
    if method == "Gaussian":
        return Filter("pcf", 5, 2.5, note="Castaño 2013 5×5 filter: 9 bilinear comparison taps weighted over 6×6 texels (sample_shadow_map_castano_thirteen)")
    return Filter("pcf", 5, 2.5, note="Jimenez 2014: 8 rotating taps accumulated over frames (sample_shadow_map_jimenez_fourteen); "
                  "modelled with the Gaussian's 5×5 footprint (the disk's radius was not read)")


def rule(s: Mapping[str, Any]) -> BiasRule:
    """``shadow_depth_bias`` along the light [m] and ``shadow_normal_bias`` texels along the normal."""
    return BiasRule((BiasTerm("shadow_depth_bias", float(s["shadow_depth_bias"]), "depth", 1.0),
                     BiasTerm("shadow_normal_bias", float(s["shadow_normal_bias"]), "normal_texels", 1.0, "one")), "front")


def build(s: Mapping[str, Any], camera) -> Pipeline:
    """Bevy's cascades (``calculate_cascade_bounds``), fit and bias for ``camera`` (module docstring)."""
    k_set = int(s["num_cascades"])
    near, far, first = float(s["minimum_distance"]), float(s["maximum_distance"]), float(s["first_cascade_far_bound"])
    p = float(s["overlap_proportion"])
    if not far > near:
        raise ValueError(f"maximum_distance must exceed minimum_distance ({near:g} m), got {far:g}")
    if k_set > 1 and not near < first < far:
        raise ValueError(f"first_cascade_far_bound must be in (minimum_distance, maximum_distance) = ({near:g}, {far:g}) m, got {first:g}")
    notes = ["faces: the material's cull_mode (StandardMaterial: back faces culled) is assumed in the shadow pass (not read)"]
    if s["ShadowFilteringMethod"] == "Temporal":
        notes.append("Temporal filtering: Jimenez's rotating disk modelled with the Gaussian's 5×5 footprint (its radius not read)")
    lo, hi = partitioning.partitions("bevy", near, far, k_set, first=first, overlap=p)
    edges = partitioning.split_distances("bevy", near, far, k_set, first=first)
    k = min(k_set, MAX_CASCADES)  # only MAX_CASCADES_PER_LIGHT are rendered: shadows end at the 4th bound
    lo, hi, edges = lo[:k], hi[:k], edges[: k + 1]
    if lo[0] < camera.near:
        notes.append(f"minimum_distance {near:g} is before the camera's near {camera.near:g}: Bevy fits the first map from minimum_distance, "
                     "the toolkit from the near plane")
        lo = np.maximum(lo, camera.near)
        if np.any(lo >= hi):
            i = int(np.argmax(lo >= hi))
            raise ValueError(f"the camera's near ({camera.near:g}) is beyond the end of cascade {i} ({hi[i]:g} m): "
                             "raise first_cascade_far_bound or lower the camera's near")
    bands = tuple(((1 - p) * edges[i + 1], edges[i + 1]) for i in range(k - 1))
    frac = max(((b - a) / (edges[i + 1] - edges[i]) for i, (a, b) in enumerate(bands)), default=0.0)
    res = int(s["DirectionalLightShadowMap.size"])
    return Pipeline(tuple(lo), tuple(hi), FIT, SNAP, res, rule(s), _filter(s), layout=f"array: {k} layers of {res}² (Depth32Float)",
                    blend=frac, stable=True, memory=k * res * res * 4, split="bevy", notes=tuple(notes), bands=bands)


def _rs(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return f"{float(v)!r}" if isinstance(v, float) else str(v)


def snippet(s: Mapping[str, Any], keys: Any = None, light: str | None = None) -> str:
    """Rust that sets ``keys`` of ``s``: None spawns a DirectionalLight entity with every setting; otherwise a system sets
    the changed ones on the user's light (the entity whose ``Name`` is ``light``; None: every DirectionalLight).

    The cascade config is rebuilt whole from its builder (CascadeShadowConfigBuilder::build, crates/bevy_pbr/src/light/mod.rs).
    """
    config = ["    CascadeShadowConfigBuilder {",
              f"        num_cascades: {int(s['num_cascades'])},",
              f"        minimum_distance: {_rs(s['minimum_distance'])},",
              f"        maximum_distance: {_rs(s['maximum_distance'])},",
              f"        first_cascade_far_bound: {_rs(s['first_cascade_far_bound'])},",
              f"        overlap_proportion: {_rs(s['overlap_proportion'])},",
              "    }"]
    if keys is None:
        return "\n".join([
            f"app.insert_resource(DirectionalLightShadowMap {{ size: {int(s['DirectionalLightShadowMap.size'])} }});",
            "commands.spawn((",
            "    DirectionalLight {",
            "        shadows_enabled: true,",
            f"        shadow_depth_bias: {_rs(s['shadow_depth_bias'])},",
            f"        shadow_normal_bias: {_rs(s['shadow_normal_bias'])},",
            "        ..default()",
            "    },",
            *config,
            "    .build(),",
            "));",
            f"// on the camera entity: ShadowFilteringMethod::{s['ShadowFilteringMethod']}",
        ])
    want = set(keys)
    lines = ["fn tune_shadows(mut map: ResMut<DirectionalLightShadowMap>,",
             "                mut lights: Query<(&Name, &mut DirectionalLight, &mut CascadeShadowConfig)>) {"]
    if "DirectionalLightShadowMap.size" in want:
        lines.append(f"    map.size = {int(s['DirectionalLightShadowMap.size'])};")
    lines.append("    for (name, mut light, mut config) in &mut lights {")
    lines.append(f"        if name.as_str() != {light!r} {{ continue; }}".replace("'", '"') if light else "        // every DirectionalLight: filter by your light's Name")
    lines += [f"        light.{k} = {_rs(s[k])};" for k in ("shadow_depth_bias", "shadow_normal_bias") if k in want]
    if want & {"num_cascades", "minimum_distance", "maximum_distance", "first_cascade_far_bound", "overlap_proportion"}:
        lines += ["        *config = " + config[0].strip()] + ["    " + c for c in config[1:]] + ["        .build();"]
    lines += ["    }", "}"]
    if "ShadowFilteringMethod" in want:
        lines.append(f"// on the camera entity: ShadowFilteringMethod::{s['ShadowFilteringMethod']}")
    return "\n".join(lines)


#: What :func:`aliasing.tune.tune` searches: the count, the first cascade's far bound (metres,
#: up to the default maximum distance: a bound beyond ``maximum_distance`` is refused), the
#: maximum distance, the overlap, the map size and both biases.
TUNABLE = (
    Tunable("num_cascades", "cascades", values=(1, 2, 3, 4)),
    Tunable("first_cascade_far_bound", "split", range=(0.0, 150.0), step=2.5),
    Tunable("maximum_distance", "distance"),
    Tunable("overlap_proportion", "blend", values=(0.0, 0.1, 0.2)),
    Tunable("DirectionalLightShadowMap.size", "size", values=(512, 1024, 2048, 4096, 8192)),
    Tunable("shadow_depth_bias", "bias"),
    Tunable("shadow_normal_bias", "bias"),
)

PROFILES = (
    Profile("bevy", "Bevy DirectionalLight (cascaded shadow maps)", "0.17", SETTINGS, build, releases=("main", "current"), snippet=snippet,
            language="rust", source="bevyengine/bevy as stored: crates/bevy_light/src/cascade.rs 0876f40a, crates/bevy_pbr/src/light/mod.rs "
            "c62a6fcd, crates/bevy_pbr/src/render/light.rs and shadows.wgsl as stored", tunable=TUNABLE),
)
