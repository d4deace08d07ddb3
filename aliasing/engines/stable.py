"""Stabilized cascade fits and what they cost against the tight fit.

Each cascade k has a *fit range* [a_k, b_k] (the eye depths its map must cover) and a
*used range* [u_k, v_k] (the receivers that sample it: the split interval, the finest
cascade wins).  Its map is orthographic (uniform), side W_x × W_y in the light image
plane (:mod:`aliasing.directional`'s light space), so with unit resolutions

    m_x(d) = W_x / (2 tanθ d),  m_z(d) = W_y / (2 tanθ d)     (Lloyd et al. 2006, eq. 2 with
                                                               a uniform map, eqs. 7–8)

and the maxima are at the first used depth u_k: M_x,k = W_x/(2 tanθ u_k), likewise M_z,k;
S̄ = Σ_k M_x,k M_z,k.  For the tight fit with fit range = used range this is exactly
:func:`aliasing.schemes.evaluate` of ``Standard`` with the same edges (tested).

Fits
----
``tight``
    W_x, W_y the extents of the slice's 8 corners in light space (depends on the light).
``sphere``
    A square of side 2r, r the radius of the slice's *minimal* enclosing sphere, closed
    form in :func:`sphere_radius` (derived in :mod:`aliasing.symbolic.engines`).  Independent
    of the light direction, so rotation-stable.  Engines that centre the sphere on the
    corners' average (and round r) use a slightly larger sphere; that variant's source was
    not read in this session, so it is not modelled.
``diagonal``
    A square of side D = max(|c0 − c6|, |c4 − c6|): the slice's body diagonal or its far
    face's diagonal, whichever is longer, rounded up to a whole world unit (Bevy
    ``crates/bevy_pbr/src/light/mod.rs``, ``calculate_cascade``, bevyengine/bevy as stored,
    commit c62a6fcd; the same construction as the DirectX SDK's CascadedShadowMaps11
    "fit to cascades" stable mode, whose source was not read here).
``diagonal-unrounded``
    The same square without the rounding, side max(|c0 − c6|, |c4 − c6|): three.js's CSM
    (``examples/jsm/csm/CSM.js`` ``_updateShadowBounds``, npm three 0.187.0 and 0.184.0: the
    distance from far corner 0 to far corner 2 or to near corner 2, whichever is longer,
    unrounded; ``update`` then floors the centre to a texel, as Bevy does).
``body``
    A square of side |c0 − c6| only, the body diagonal (DirectX SDK
    ``CascadedShadowMaps11/CascadedShadowsManager.cpp`` ``InitFrame``, FIT_TO_SCENE branch,
    walbourn/directx-sdk-samples commit 1494e2be: "pad the projection to be the size of the
    diagonal of the frustum partition", min and max floored to texels).  Finding: when the
    far face's diagonal 2√2·t·b is longer than the body diagonal (wide fov or a slice
    starting near the eye, as fit to scene always does) this square does **not** cover the
    slice for every light direction; :func:`coverage` measures it.  Bevy's max() fixes it.
``centroid``
    A square of side 2r, r the largest distance from the corners' average (on the axis at
    (a + b)/2) to a corner: r = √(((b − a)/2)² + 2t²b²) (Godot 4
    ``servers/rendering/renderer_scene_cull.cpp`` ``_light_instance_setup_directional_shadow``,
    a Godot 4 copy in the index); never smaller than the minimal sphere.  Filament's stable
    mode uses the same sphere (``filament/src/ShadowMap.cpp``, google/filament commit
    0362f36e: ``computeFocusParams`` with ``stable``, ``computeBoundingSphere`` = the 8
    corners' average and the largest distance to it, scale s = 1/r on NDC [−1, 1]).
``centroid16``
    The ``centroid`` sphere with r rounded up to 1/16 of a world unit (Babylon.js
    ``packages/dev/core/src/Lights/Shadows/cascadedShadowGenerator.ts``
    ``_computeCascadeFrustum`` with ``stabilizeCascades``, BabylonJS/Babylon.js commit
    043d0bd0: ``sphereRadius = Math.ceil(sphereRadius * 16) / 16``).
``far``
    A square of side 2·far for every cascade: Filament's stable mode when the light's
    ``shadowFar`` > 0 takes the sphere {camera position, shadowFar} for each cascade
    (same ``computeFocusParams``), so every cascade covers the whole shadow range.  Finding:
    all cascades then have the last one's texel size, and the sphere (radius far, on the
    camera) does not contain the far corners at distance far·√(1 + 2t²): :func:`coverage`
    below 1 for grazing lights.
Non-square views (``aspect``)
    ``fov`` is the vertical field of view and ``aspect`` = width/height (:class:`aliasing.View`):
    ``tight`` fits the wide slices' eight corners, the other fits take the radii with
    c² = tan²θ_x + tan²θ_y in place of 2t²; the errors stay per square pixel of unit vertical
    resolution (W/(2 tanθ_y d)).  Aspect 1 is the square view, bit for bit.
Fit to scene (``scene=True``)
    Every cascade's fit range starts at the near plane: [near, b_k] (DirectX SDK
    FIT_TO_SCENE, same source: "interval 1 is covered by cascades 1 to 8").
Texel snapping (``snap``)
    ``"none"``: sizes unchanged.  ``"origin"``: the map's origin is moved to a whole texel
    (Babylon.js rounds the projected world origin to a texel; Filament's
    ``snapLightFrustum`` to an even texel): the size is unchanged.  ``"border"``: the map
    keeps a one-texel border on each side, so the fit's side spans R − 2 of its R texels,
    W′ = W·R/(R − 2) (Filament ``ShadowMapManager.cpp`` ``shadowDimension = mapSize − 2``,
    commit 003e5005; its ``snapLightFrustum`` then moves the origin only).
    ``"bevy"``: the map centre is floored to a texel (three.js's CSM does the same);
    Bevy keeps the side D (so up to one texel at one border may be uncovered) —
    the size is unchanged.  ``"pad"``: a coverage-preserving snap: the side grows by one
    texel, W′ = W·R/(R − 1) at R texels per side (the model's assumption for engines that
    pad by a texel; a bound, not read from an engine).  ``"godot"``: Godot's
    ``radius *= R/(R − 2)`` ("add a texel by each side"), then both ends snapped to
    4r/R (the size is kept to within one snap unit, not modelled).
Overlap
    Engines that pad or overlap cascades (``ogre-pssm``, ``bgfx``, ``unreal`` in
    :mod:`aliasing.partitioning`) fit each map to :func:`aliasing.partitioning.partitions`
    and use it on the split interval; ``overlap=p`` adds Bevy's overlap: cascade k's fit
    range starts at (1 − p)·C_(k−1) (Bevy ``calculate_cascade_bounds`` /
    ``overlap_proportion``).

Example
-------
>>> r = evaluate("log", 1.0, 1000.0, 60.0, "overhead", k=3, fit="sphere")
>>> t = evaluate("log", 1.0, 1000.0, 60.0, "overhead", k=3, fit="tight")
>>> bool(r.S[0] > t.S[0])
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from .. import directional, geometry, partitioning
from ..setups import bevy as _bevy
from ..setups import filament as _filament
from ..setups import godot as _godot
from ..view import View, check_aspect, tan_theta
from .sample import sample_bounds

Array = NDArray[np.float64]
FITS = ("tight", "sphere", "diagonal", "diagonal-unrounded", "body", "centroid", "centroid16", "far")
SNAPS = ("none", "origin", "border", "bevy", "pad", "godot")


@dataclass(frozen=True)
class StablePreset:
    """An engine's stable cascade mode: fit, snap, overlap, its split preset and source.

    ``release`` names the engine release or commit it reproduces, ``releases`` the names
    ``NAME@RELEASE`` accepts (:func:`aliasing.partitioning.resolve_name`).
    """

    name: str
    split: str
    fit: str
    snap: str
    overlap: float
    source: str
    scene: bool = False
    k: int = 4  # cascades evaluated when the spec gives no k
    release: str = ""
    releases: tuple[str, ...] = ()


# Only modes whose source was read.  Unity's StableFit/CloseFit (QualitySettings.shadowProjection;
# URP ShadowUtils.cs calls the native CullingResults.ComputeDirectionalShadowMatricesAndCullingPrimitives)
# are computed in the engine's closed C++ source: its public docs say only "Stable shadow maps with
# spherical fadeout", so no Unity preset is shipped (the project does not invent a fit).
PRESETS: dict[str, StablePreset] = {
    "godot": StablePreset(  # the fit and snap of the godot engine profile (aliasing.setups.godot)
        "godot",
        "godot",
        _godot.FIT,
        _godot.SNAP,
        0.0,
        "Godot 4 renderer_scene_cull.cpp _light_instance_setup_directional_shadow (a Godot 4 copy in the index): sphere around the "
        "corners' average, radius × R/(R − 2), ends snapped to 4r/R; split: the toolkit's godot preset; blend_splits off",
        release="Godot 4.x, not pinned to a minor release (a copy in the index; read from source only)",
    ),
    "dxsdk-scene": StablePreset(
        "dxsdk-scene",
        "log",
        "body",
        "none",
        0.0,
        "DirectX SDK CascadedShadowMaps11 CascadedShadowsManager.cpp InitFrame, FIT_TO_SCENE + m_bMoveLightTexelSize (walbourn/directx-sdk-samples); "
        "scene=True; split: the sample's partitions are user-set, the toolkit's log split stands in",
        scene=True,
        release="DirectX SDK samples, walbourn/directx-sdk-samples commit 1494e2be (read from source only)",
    ),
    "filament": StablePreset(  # the filament engine profile with stable = true (aliasing.setups.filament)
        "filament",
        "filament",
        _filament.STABLE_FIT,
        _filament.SNAP,
        0.0,
        "Filament ShadowOptions::stable (default false) in filament/src/ShadowMap.cpp computeFocusParams/computeBoundingSphere/"
        "snapLightFrustum (google/filament commit 0362f36e) and ShadowMapManager.cpp updateCascadeShadowMaps (commit 003e5005): "
        "per cascade the sphere around its 8 corners' average, origin snapped to even texels, shadowDimension = mapSize - 2 "
        "(1-texel border); LiSPSM off in stable mode; ShadowOptions defaults (LightManager.h): shadowFar = 0, mapSize 1024, "
        "cascadeSplitPositions {0.125, 0.25, 0.5}, shadowCascades = 1 (the preset evaluates 4 cascades, the split's; k=1 is the engine default)",
        release="Filament commits 0362f36e (ShadowMap.cpp) and 003e5005 (ShadowMapManager.cpp) (read from source only)",
    ),
    "filament-shadowfar": StablePreset(  # the same with shadowFar > 0
        "filament-shadowfar",
        "filament",
        _filament.FAR_FIT,
        _filament.SNAP,
        0.0,
        "as filament, with ShadowOptions::shadowFar > 0 (= the shadow distance): computeFocusParams takes the sphere "
        "{camera position, shadowFar} for every cascade (google/filament ShadowMap.cpp commit 0362f36e)",
        release="Filament commit 0362f36e (read from source only)",
    ),
    "babylon": StablePreset(
        "babylon",
        "babylon",
        "centroid16",
        "origin",
        0.0,
        "Babylon.js CascadedShadowGenerator stabilizeCascades (default false), cascadedShadowGenerator.ts "
        "_computeCascadeFrustum/_computeMatrices (BabylonJS/Babylon.js commit 043d0bd0): sphere around the slice corners' "
        "centroid, radius ceil to 1/16 unit, projected origin rounded to a texel; split: practical lambda 0.5, DEFAULT_CASCADES_COUNT 4, "
        "cascadeBlendPercentage 0.1 blends in the shader (no fit overlap)",
        release="Babylon.js 9.35.0 (npm @babylonjs/core, run in the tests; source read at commit 043d0bd0)",
        releases=("9.35.0",),
    ),
    "bevy": StablePreset(  # the bevy engine profile's fit and snap (aliasing.setups.bevy), with the older first bound
        "bevy",
        "bevy-bounds",
        _bevy.FIT,
        _bevy.SNAP,
        0.2,
        "Bevy crates/bevy_pbr/src/light/mod.rs (bevyengine/bevy as stored): calculate_cascade (diameter = ceil(max(body, far-face "
        "diagonal)), centre floored to a texel), calculate_cascade_bounds (geometric from first_cascade_far_bound), "
        "CascadeShadowConfigBuilder defaults 4 cascades, first bound 5 m, overlap_proportion 0.2",
        release="Bevy bevy_pbr/src/light/mod.rs at bevyengine/bevy commit c62a6fcd, first bound 5 m (read from source only; "
        "the current cascade.rs defaults to 10 m: split preset 'bevy')",
    ),
    "threejs": StablePreset(
        "threejs",
        "threejs-csm",
        "diagonal-unrounded",
        "bevy",
        0.0,
        "three.js examples/jsm/csm/CSM.js _updateShadowBounds (side = the longer of the far-face and body diagonals, unrounded; "
        "fade off, the default) and update (centre floored to a texel); split: threejs-csm, 3 cascades (CSM's default)",
        k=3,
        release=partitioning.THREEJS_CURRENT,
        releases=("r185", "r186", "r187"),
    ),
    "threejs@r184": StablePreset(
        "threejs@r184",
        "threejs-csm@r184",
        "diagonal-unrounded",
        "bevy",
        0.0,
        "as threejs, with the split of three.js r184 and earlier (CSMFrustum.split lerps by the break itself)",
        k=3,
        release="three.js r184 and earlier (run in the tests: npm three 0.184.0)",
        releases=("r184",),
    ),
}


@dataclass(frozen=True)
class StableResult:
    """Unit-resolution errors of a cascade set over N light directions and K maps."""

    M_x: Array  # (N, K)
    M_z: Array  # (N, K)
    S: Array  # (N,)
    width_x: Array  # (N, K) map sides [world units]
    width_y: Array  # (N, K)
    used: tuple[Array, Array]  # (u_k, v_k) [world units]
    fit_range: tuple[Array, Array]  # (a_k, b_k)


def _corner2(fov: ArrayLike, aspect: ArrayLike) -> tuple[Array, Array | None]:
    """(c², tan θ) with c² = tan²θ_x + tan²θ_y, the squared distance of a corner ray from the view axis at
    unit depth; tan θ is None unless the view is square (aspect 1: c² = 2 tan²θ, formed as before).

    θ = θ_y = fov/2 is the vertical half angle [rad], tan θ_x = aspect·tan θ_y (the engines' convention).
    """
    r = check_aspect(aspect)
    t = tan_theta(fov)
    if np.all(r == 1.0):
        return 2 * t**2, t
    return (r * t) ** 2 + t**2, None


def sphere_radius(a: ArrayLike, b: ArrayLike, fov: ArrayLike, aspect: ArrayLike = 1.0) -> Array:
    """Radius [world units] of the minimal sphere around a frustum slice [a, b].

    With t = tan(fov/2) the corners lie at depth a (radius √2·t·a from the axis) and b;
    the centre on the axis equidistant from both rings is z_c = (a + b)(1 + 2t²)/2; if
    z_c ≥ b the far ring alone decides: r = √2·t·b.  Otherwise
    r² = (b − z_c)² + 2t²b².  Derived and tested in :mod:`aliasing.symbolic.engines`.
    A non-square view (``aspect`` = width/height, ``fov`` vertical) puts the corners at
    c·a and c·b from the axis, c² = tan²θ_x + tan²θ_y: 2t² becomes c² throughout.

    Example
    -------
    >>> float(sphere_radius(1.0, 3.0, 90.0))  # far ring decides: z_c = 6 > 3
    4.242640687119285
    """
    a, b = check.frustum(a, b)
    c2, _ = _corner2(fov, aspect)  # 2 t² (square) or tan²θ_x + tan²θ_y
    zc = (a + b) * (1 + c2) / 2
    r_far = np.sqrt(c2) * b
    return np.where(zc >= b, r_far, np.sqrt((b - np.minimum(zc, b)) ** 2 + c2 * b**2))


def centroid_radius(a: ArrayLike, b: ArrayLike, fov: ArrayLike, aspect: ArrayLike = 1.0) -> Array:
    """Largest distance from the corners' average to a corner of the slice [a, b] [world units].

    The average lies on the axis at (a + b)/2, so the far corners are farthest:
    r = √(((b − a)/2)² + 2t²b²) (Godot 4's stable fit, before its texel padding); 2t² is
    tan²θ_x + tan²θ_y for a non-square view (``aspect`` = width/height, ``fov`` vertical).

    Example
    -------
    >>> round(float(centroid_radius(1.0, 3.0, 90.0)), 6)
    4.358899
    """
    a, b = check.frustum(a, b)
    c2, _ = _corner2(fov, aspect)
    return np.sqrt(((b - a) / 2) ** 2 + c2 * b**2)


def diagonal(a: ArrayLike, b: ArrayLike, fov: ArrayLike, aspect: ArrayLike = 1.0) -> Array:
    """Bevy's cascade diameter before rounding: max(body diagonal, far-face diagonal).

    Body diagonal |c0 − c6| from a near corner to the opposite far corner:
    √((b − a)² + 2t²(a + b)²); far face |c4 − c6|: 2√2·t·b (t = tan(fov/2)).  For a
    non-square view (``aspect`` = width/height, ``fov`` vertical) √2·t is c = √(tan²θ_x + tan²θ_y).

    Example
    -------
    >>> round(float(diagonal(1.0, 2.0, 90.0)), 6)
    5.656854
    """
    a, b = check.frustum(a, b)
    c2, t = _corner2(fov, aspect)
    body = np.sqrt((b - a) ** 2 + c2 * (a + b) ** 2)
    return np.maximum(body, 2 * np.sqrt(2) * t * b if t is not None else 2 * np.sqrt(c2) * b)


BEVY_FIRST_BOUND_M = 5.0  # CascadeShadowConfigBuilder::default first_cascade_far_bound [m]


def bevy_bounds(near: float, far: float, k: int = 4, first: float = BEVY_FIRST_BOUND_M) -> Array:
    """Bevy's split distances: near, then C_i = first·(far/first)^((i−1)/(k−1)) for i = 1…k.

    Bevy ``calculate_cascade_bounds``: the first cascade ends at ``first_cascade_far_bound``,
    the others are geometric up to the maximum distance [world units].

    Example
    -------
    >>> bevy_bounds(0.1, 1000.0, 4, 5.0).round(3).tolist()
    [0.1, 5.0, 29.24, 170.998, 1000.0]
    """
    n, f = (float(x) for x in check.frustum(near, far))
    if isinstance(k, bool) or int(k) != k or k < 1:
        raise ValueError(f"k must be a whole number >= 1 (number of cascades), got {k!r}")
    if int(k) == 1:
        return np.array([n, f])
    fb = float(check.as_float_array(first, "first"))
    if not n < fb < f:
        raise ValueError(f"first (Bevy's first_cascade_far_bound) must be in (near, far) = ({n:g}, {f:g}), got {fb:g}")
    edges = np.concatenate([[n], fb * (f / fb) ** (np.arange(int(k)) / (int(k) - 1))])
    edges[-1] = f
    return edges


def body_diagonal(a: ArrayLike, b: ArrayLike, fov: ArrayLike, aspect: ArrayLike = 1.0) -> Array:
    """|c0 − c6| = √((b − a)² + 2t²(a + b)²) [world units], the DirectX SDK's cascade bound.

    2t² is tan²θ_x + tan²θ_y for a non-square view (``aspect`` = width/height, ``fov`` vertical).

    Example
    -------
    >>> round(float(body_diagonal(0.0 + 1e-9, 1.0, 90.0)), 6)
    1.732051
    """
    a, b = check.frustum(a, b)
    c2, _ = _corner2(fov, aspect)
    return np.sqrt((b - a) ** 2 + c2 * (a + b) ** 2)


def _aspect(aspect: ArrayLike) -> float:
    """One image width/height, 0 < aspect < inf (ValueError naming ``aspect``)."""
    r = check_aspect(aspect)
    if r.ndim != 0:
        raise ValueError(f"aspect must be a single number (image width/height in (0, inf)), got shape {r.shape}")
    return float(r)


def _slices(a: ArrayLike, b: ArrayLike, fov: ArrayLike, aspect: float) -> Array:
    """The 8 corners of the slices [a, b] of a view with vertical ``fov`` [deg] and ``aspect``, ``(K, 8, 3)``."""
    return geometry.frustum_vertices(View(a, b, fov, aspect))  # aspect 1: the square corners, bit for bit


def coverage(split: str | ArrayLike, near: float, far: float, fov: float, light: str | ArrayLike = "hemisphere:200", *, aspect: float = 1.0, **options) -> float:
    """Fraction of light directions for which every cascade's map covers its slice (tight extents ≤ sides).

    ``aspect`` is the view's width/height (``fov`` vertical), as in :func:`evaluate`; the
    other options are :func:`evaluate`'s.

    Example
    -------
    >>> coverage("log", 0.1, 100.0, 60.0, "hemisphere:100", k=3, fit="diagonal")
    1.0
    """
    fit_keys = {"fit", "snap", "resolution", "scene", "overlap", "border", "dilation", "quantize"}
    base = {key: v for key, v in options.items() if key not in fit_keys}
    for key in ("scene", "overlap"):
        if key in options:
            base[key] = options[key]
    r = _aspect(aspect)
    tight = evaluate(split, near, far, fov, light, aspect=r, **base)  # same fit ranges, tight extents
    other = evaluate(split, near, far, fov, light, aspect=r, **options)
    ok = (other.width_x >= tight.width_x * (1 - 1e-12)) & (other.width_y >= tight.width_y * (1 - 1e-12))
    if options.get("fit") == "far":  # centred on the camera, not on the slice: every corner within ±side/2
        a, b = tight.fit_range
        corners = _slices(a, b, fov, r)  # (K, 8, 3), camera at the origin
        basis = geometry.light_space(geometry.lights(light))  # (N, 3, 3)
        half_x = np.abs(np.einsum("kvj,nj->nkv", corners, basis[:, 0])).max(axis=-1)
        half_y = np.abs(np.einsum("kvj,nj->nkv", corners, basis[:, 2])).max(axis=-1)
        ok &= (half_x <= other.width_x / 2 * (1 + 1e-12)) & (half_y <= other.width_y / 2 * (1 + 1e-12))
    return float(ok.all(axis=-1).mean())


def cascade_ranges(split: str | ArrayLike, near: float, far: float, k: int | None = None, *, scene: bool = False, overlap: float = 0.0, **params: float) -> tuple[tuple[Array, Array], tuple[Array, Array]]:
    """(fit ranges, used ranges) of a split preset or explicit split distances.

    Example
    -------
    >>> (a, b), (u, v) = cascade_ranges("log", 1.0, 100.0, 2, scene=True)
    >>> a.tolist(), u.tolist()
    ([1.0, 1.0], [1.0, 10.0])
    """
    n, f = (float(x) for x in check.frustum(near, far))
    if isinstance(split, tuple) and len(split) == 2:  # (near_i, far_i) of separate maps, e.g. SDSM's populated ranges
        lo, hi = (check.as_float_array(x, "split").ravel() for x in split)
        if lo.size == 0 or lo.shape != hi.shape or np.any(hi <= lo) or lo.min() < n * (1 - 1e-12) or hi.max() > f * (1 + 1e-12):
            raise ValueError("split as (near_i, far_i) needs equal non-empty lengths, near_i < far_i, inside [near, far]")
        return (lo.copy(), hi.copy()), (lo.copy(), hi.copy())
    if isinstance(split, str):
        edges = partitioning.split_distances(split, n, f, k, **params)
        lo, hi = partitioning.partitions(split, n, f, k, **params)
    else:
        edges = check.as_float_array(split, "split").ravel()
        if edges.size < 2 or np.any(np.diff(edges) <= 0) or not (np.isclose(edges[0], n) and np.isclose(edges[-1], f)):
            raise ValueError("split distances must increase from near to far")
        lo, hi = edges[:-1].copy(), edges[1:].copy()
    p = float(check.closed_range(overlap, "overlap", 0.0, 0.99))
    lo = lo.copy()
    lo[1:] = np.minimum(lo[1:], (1 - p) * edges[1:-1])  # Bevy: near bound = (1 − p)·previous far bound
    if scene:
        lo = np.full_like(lo, n)
    return (np.maximum(lo, n), hi), (edges[:-1], edges[1:])


def evaluate(split: str | ArrayLike, near: float, far: float, fov: float, light: str | ArrayLike = "overhead", *, k: int | None = None, aspect: float = 1.0, fit: str = "tight", snap: str = "none", resolution: float = 2048.0, scene: bool = False, overlap: float = 0.0, border: float = 0.0, dilation: float = 0.0, quantize: bool = False, **params: float) -> StableResult:
    """M_x, M_z, S̄ (unit resolutions) of a cascade set with a given fit, per light direction.

    Parameters
    ----------
    split : str, array_like or tuple
        A split method of :mod:`aliasing.partitioning`, split distances near … far [world
        units], or a pair (near_i, far_i) of separate maps' ranges (used where they are fitted).
    near, far : float
        Eye near and shadow distance [world units], 0 < near < far.
    fov : float
        Vertical full field of view [deg].
    light : str or array_like
        Light spec (:data:`aliasing.geometry.LIGHT_SPEC`) or vectors ``(N, 3)``.
    k : int, optional
        Number of cascades (the preset's default when omitted).
    aspect : float
        Image width/height, 0 < aspect < inf (default 1, the square view): tan θ_x =
        aspect·tan θ_y.  The slices' corners (``tight``) and the radii of the other fits
        (:func:`sphere_radius` …) take it; the errors stay per pixel of unit vertical
        resolution (square pixels), M = W/(2 tan θ_y u).  Aspect 1 gives the square view's
        numbers bit for bit.
    fit : {"tight", "sphere", "diagonal", "diagonal-unrounded", "body", "centroid", "centroid16", "far"}
    snap : {"none", "origin", "border", "bevy", "pad", "godot"}
    resolution : float
        Texels per side of each map (``snap`` "pad", "border", "godot" depend on it), > 2.
    scene : bool
        Fit to scene: every fit range starts at ``near``.
    overlap : float
        Bevy's overlap proportion in [0, 0.99].
    border, dilation, quantize
        Intel's SDSM sample's partition border [world units], dilation (fraction per side)
        and power-of-two quantisation (:func:`aliasing.engines.sample.sample_bounds`), applied
        after the fit, the light space L being the tight box of the whole [near, far].
    """
    kind = check.choice(fit, "fit", FITS)
    r = _aspect(aspect)
    snapping = check.choice(snap, "snap", SNAPS)
    res = float(check.closed_range(resolution, "resolution", 3.0, np.inf, " texels"))
    (a, b), (u, v) = cascade_ranges(split, near, far, k, scene=scene, overlap=overlap, **params)
    lv = geometry.lights(light)
    t = tan_theta(fov)
    if kind == "tight":
        lf = directional.fit(_slices(a, b, fov, r), lv)
        wx, wy = np.ptp(lf.x, axis=-1), lf.depth
    else:
        if kind == "sphere":
            side = 2 * sphere_radius(a, b, fov, r)
        elif kind == "centroid":
            side = 2 * centroid_radius(a, b, fov, r)
        elif kind == "centroid16":
            side = 2 * np.ceil(centroid_radius(a, b, fov, r) * 16) / 16  # Babylon.js: ceil(r·16)/16
        elif kind == "far":
            side = np.full_like(a, 2 * float(far))  # Filament shadowFar: sphere {camera, shadowFar}
        elif kind == "diagonal":
            side = np.ceil(diagonal(a, b, fov, r))  # Bevy rounds up to a whole unit
        elif kind == "diagonal-unrounded":
            side = diagonal(a, b, fov, r)  # three.js CSM: the longer diagonal as it is
        else:
            side = body_diagonal(a, b, fov, r)
        wx = wy = np.broadcast_to(side, (len(lv), len(a)))
    if snapping == "pad":
        wx, wy = wx * res / (res - 1), wy * res / (res - 1)  # one texel more, W′ = W + W′/R
    elif snapping in ("godot", "border"):
        wx, wy = wx * res / (res - 2), wy * res / (res - 2)  # a texel on each side: W spans R − 2 texels
    if border or dilation or quantize:
        whole = directional.fit(_slices(np.array([float(near)]), np.array([float(far)]), fov, r), lv)  # App.cpp: the view's extents
        wx = sample_bounds(wx, np.ptp(whole.x, axis=-1), border=border, dilation=dilation, quantize=quantize)
        wy = sample_bounds(wy, whole.depth, border=border, dilation=dilation, quantize=quantize)
    M_x, M_z = wx / (2 * t * u), wy / (2 * t * u)  # eq. (2) with a uniform map, maximal at u_k
    return StableResult(M_x, M_z, (M_x * M_z).sum(axis=-1), np.asarray(wx, float), np.asarray(wy, float), (u, v), (a, b))


def cost(split: str | ArrayLike, near: float, far: float, fov: float, light: str | ArrayLike = "hemisphere:200", *, aspect: float = 1.0, **options) -> dict[str, float]:
    """Cost of a stable fit as ratios to the tight fit of the same cascades.

    ``aspect`` is the view's width/height (``fov`` vertical), as in :func:`evaluate`.

    Returns per-direction ratios summarised over the given directions: ``S_ratio_min``,
    ``S_ratio_max``, ``M_ratio_min``, ``M_ratio_max`` (M = max over maps of max(M_x, M_z)),
    and ``S_ratio_mean_over_dirs`` (mean S̄ of the fit over mean S̄ of the tight fit).

    Example
    -------
    >>> c = cost("log", 1.0, 1000.0, 60.0, "overhead", k=4, fit="sphere")
    >>> c["S_ratio_min"] > 1.0
    True
    """
    fit_keys = {"fit", "snap", "resolution", "scene", "overlap", "border", "dilation", "quantize"}
    params = {key: v for key, v in options.items() if key not in fit_keys}
    r = _aspect(aspect)
    tight = evaluate(split, near, far, fov, light, aspect=r, **params)  # today's fit: tight, no snap, no overlap
    other = evaluate(split, near, far, fov, light, aspect=r, **options)
    rs = other.S / tight.S
    m_t = np.maximum(tight.M_x, tight.M_z).max(axis=-1)
    m_o = np.maximum(other.M_x, other.M_z).max(axis=-1)
    rm = m_o / m_t
    return {
        "S_ratio_min": float(rs.min()),
        "S_ratio_max": float(rs.max()),
        "M_ratio_min": float(rm.min()),
        "M_ratio_max": float(rm.max()),
        "S_ratio_mean_over_dirs": float(other.S.mean() / tight.S.mean()),
    }
