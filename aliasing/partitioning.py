"""Split schemes for z-partitioned (cascaded, parallel-split) shadow maps, in one registry.

Each method maps (near, far, k) to the k + 1 split distances n = C_0 < C_1 < … < C_k = f
[world units] along the view direction.  :func:`split_distances` is the dispatcher.

Example
-------
>>> split_distances("log", 1.0, 1000.0, 3)
array([   1.,   10.,  100., 1000.])
>>> split_distances("practical", 1.0, 100.0, 2, lam=0.5)
array([  1. ,  30.25, 100. ])

Engine presets name the release they reproduce (``release``); where an engine changed its
formula the older form stays under ``NAME@RELEASE`` (``threejs-csm@r184``), and a name may
carry any release the preset covers (``threejs-csm@r187`` is ``threejs-csm``):

>>> split_distances("threejs-csm@r184", 1.0, 100.0, 2).round(4)
array([  1.    ,  30.9475, 100.    ])
>>> split_distances("threejs-csm@r187", 1.0, 100.0, 2)
array([  1.  ,  30.25, 100.  ])
"""

from __future__ import annotations

import inspect
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from . import _validation as check

__all__ = [
    "SPLIT_METHODS",
    "SplitMethod",
    "partitions",
    "register",
    "resolve_name",
    "split_distances",
]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class SplitMethod:
    """A registered split scheme; ``func(near, far, k, **params) -> C (k + 1,)``.

    ``default_k`` is an engine's default cascade count (None: k must be given);
    ``min_k`` and ``max_k`` the fewest and most it supports (Babylon.js clamps its count to
    2–4; the toolkit refuses a count the engine would change); ``extend`` maps the split
    distances to each map's (near_i, far_i) where an engine pads or overlaps its cascades.
    ``release`` names the engine release or commit the preset reproduces (empty for the
    papers' schemes) and ``releases`` the release names ``NAME@RELEASE`` accepts for it.
    """

    name: str
    func: Callable[..., Array]
    source: str
    summary: str
    default_k: int | None = None
    max_k: int | None = None
    extend: Callable[..., tuple[Array, Array]] | None = None
    release: str = ""
    releases: tuple[str, ...] = ()
    min_k: int = 1


SPLIT_METHODS: dict[str, SplitMethod] = {}


def register(name: str, source: str, summary: str, *, default_k: int | None = None, max_k: int | None = None, extend: Callable | None = None, release: str = "", releases: tuple[str, ...] = (), min_k: int = 1) -> Callable:
    """Decorator adding a split method to :data:`SPLIT_METHODS`."""

    def wrap(func: Callable[..., Array]) -> Callable[..., Array]:
        if name in SPLIT_METHODS:
            raise RuntimeError(f"split method {name!r} registered twice")
        SPLIT_METHODS[name] = SplitMethod(name, func, source, summary, default_k, max_k, extend, release, tuple(releases), min_k)
        return func

    return wrap


def resolve_name(name: str, table: dict | None = None, what: str = "split method") -> str:
    """The key in ``table`` (default :data:`SPLIT_METHODS`) of a preset name, ``NAME@RELEASE`` included.

    ``NAME@RELEASE`` is the entry whose base name is NAME and whose ``releases`` hold RELEASE
    (case-insensitive); an unknown release is refused with the known ones listed.  The table's
    entries need ``name`` and ``releases`` (split methods, :data:`aliasing.engines.stable.PRESETS`).

    Example
    -------
    >>> resolve_name("threejs-csm@r184"), resolve_name("ThreeJS-CSM@r187"), resolve_name("log")
    ('threejs-csm@r184', 'threejs-csm', 'log')
    >>> resolve_name("threejs-csm@r100")
    Traceback (most recent call last):
    ...
    ValueError: split method 'threejs-csm@r100': unknown release 'r100' of 'threejs-csm'; known releases: r184, r185, r186, r187
    """
    if table is not None:
        check.instance(table, "table", dict)
    table = SPLIT_METHODS if table is None else table
    if not isinstance(what, str):
        raise ValueError(f"what (the kind of name, for messages) must be a string, got {what!r}")
    if not isinstance(name, str):
        raise ValueError(f"name (a {what}) must be a string, one of: {', '.join(table)}; got {name!r}")
    if "@" not in name:
        return check.choice(name, what, table)
    base, _, rel = name.strip().lower().partition("@")
    family = [e for e in table.values() if e.name.partition("@")[0] == base]
    if not family:
        check.choice(base, what, [key for key in table if "@" not in key])  # unknown base name: the usual message
    known = sorted({r.lower() for e in family for r in e.releases})
    for entry in family:
        if rel in (r.lower() for r in entry.releases):
            return entry.name
    if not known:
        raise ValueError(f"{what} {name!r}: {base!r} is not pinned to engine releases (drop {'@' + rel!r})")
    raise ValueError(f"{what} {name!r}: unknown release {rel!r} of {base!r}; known releases: {', '.join(known)}")


@check.public
def split_params(lam: float | None, items: Sequence[str]) -> dict[str, float]:
    """Split-method parameters from the command line: ``--lambda`` and ``--param KEY=NUMBER`` items.

    Shared by ``aliasing splits``, ``aliasing render`` and ``aliasing validate --scene`` (not
    part of the API: the functions take the parameters as keywords).

    Example
    -------
    >>> split_params(0.5, ["ratio=2", "bias=0.1"])
    {'lam': 0.5, 'ratio': 2.0, 'bias': 0.1}
    """
    params = {} if lam is None else {"lam": float(lam)}
    for item in items:
        key, sep, value = item.partition("=")
        try:
            params[key.strip()] = float(value)
        except ValueError:
            sep = ""
        if not sep or not key.strip():
            raise ValueError(f"--param takes KEY=NUMBER, got {item!r}")
    return params


def split_distances(method: str, near: float, far: float, k: int | None = None, **params: float) -> Array:
    """The k + 1 split distances C_0 = near < … < C_k = far of a named scheme [world units].

    For engine presets ``far`` is the engine's shadow distance (three.js ``maxFar``, Godot
    ``max_distance``, Unity's shadow distance, …): shadows end there.

    Parameters
    ----------
    method : str
        A name in :data:`SPLIT_METHODS` (case-insensitive).
    near, far : float
        Eye near and far (shadow) distances [world units], 0 < near < far.
    k : int, optional
        Number of partitions, ≥ 1; an engine preset's default when omitted.
    **params
        Method parameters (``lam`` for ``practical``, …); unknown ones are an error.

    Raises
    ------
    ValueError
        Unknown method or parameter, k < 1 or above the engine's maximum, near ≤ 0,
        far ≤ near, λ outside [0, 1].
    """
    entry, n, f, kk = _resolve(method, near, far, k)
    accepted = set(inspect.signature(entry.func).parameters) - {"near", "far", "k"}
    own = {key: v for key, v in params.items() if key in accepted}
    unknown = set(params) - accepted - _extend_params(entry)
    if unknown:
        raise ValueError(f"split method {entry.name!r} takes {sorted(accepted | _extend_params(entry)) or 'no parameters'}, not {sorted(unknown)}")
    edges = np.asarray(entry.func(n, f, kk, **own), dtype=float)
    edges[0], edges[-1] = n, f  # exact ends, whatever the rounding inside
    return edges


@check.public
def partitions(method: str, near: float, far: float, k: int | None = None, **params: float) -> tuple[Array, Array]:
    """Each map's (near_i, far_i) [world units]: the split distances, padded or overlapped
    the way the engine does it (Ogre's padding, bgfx's and Unreal's overlaps)."""
    entry, n, f, kk = _resolve(method, near, far, k)
    own = {key: v for key, v in params.items() if key not in _extend_params(entry)}
    edges = split_distances(method, near, far, kk, **own)
    if entry.extend is None:
        return edges[:-1], edges[1:]
    extra = {key: v for key, v in params.items() if key in _extend_params(entry)}
    lo, hi = entry.extend(edges, **extra)
    return np.maximum(lo, n), np.minimum(hi, f)


def _extend_params(entry: SplitMethod) -> set[str]:
    return set() if entry.extend is None else set(inspect.signature(entry.extend).parameters) - {"edges"}


def _resolve(method: str, near: float, far: float, k: int | None) -> tuple[SplitMethod, float, float, int]:
    key = resolve_name(method)
    entry = SPLIT_METHODS[key]
    n, f = (float(v) for v in check.frustum(check.scalar(near, "near"), check.scalar(far, "far")))
    if k is None:
        if entry.default_k is None:
            raise ValueError(f"split method {key!r} needs k (number of partitions)")
        k = entry.default_k
    kk = _partitions(k)
    if entry.min_k > 1 and not entry.min_k <= kk <= (entry.max_k or MAX_PARTITIONS):
        raise ValueError(f"k must be at least {entry.min_k} and at most {entry.max_k} for {key!r} (the engine clamps its cascade count to that range), got {kk}")
    if entry.max_k is not None and kk > entry.max_k:
        raise ValueError(f"k must be at most {entry.max_k} for {key!r}, got {kk}")
    return entry, n, f, kk


# Most partitions any method accepts (k + 1 split distances; engines use at most 8).
MAX_PARTITIONS = 1024


def _partitions(k: int) -> int:
    return check.whole(k, "k", 1, MAX_PARTITIONS, " (number of partitions)")


def _lam(lam: float) -> float:
    return float(check.closed_range(check.scalar(lam, "lambda"), "lambda", 0.0, 1.0))


def _log(n: float, f: float, k: int) -> Array:
    return n * (f / n) ** (np.arange(k + 1) / k)  # Lloyd 2006 eqs. (15)–(16); Lloyd 2007 eqs. (80)–(81)


def _uniform(n: float, f: float, k: int) -> Array:
    return n + (f - n) * np.arange(k + 1) / k


@register("log", "Lloyd et al. 2006 eqs. 15–16; Lloyd et al. 2007 eqs. 80–82", "self-similar: C_i = n (f/n)^(i/k), equal f_i/n_i")
def _log_method(near: float, far: float, k: int) -> Array:
    return _log(near, far, k)


@register("uniform", "equal depth ranges (the uniform split of the PSSM literature)", "equal depth ranges: C_i = n + (f − n) i/k")
def _uniform_method(near: float, far: float, k: int) -> Array:
    return _uniform(near, far, k)


@register("practical", "the PSSM 'practical split' as engines implement it (three.js, Babylon.js, Ogre, Filament); not in the supplied Zhang 2006 text (ERRATA P1)", "C_i = λ C_i^log + (1 − λ) C_i^uni")
def _practical(near: float, far: float, k: int, lam: float = 0.5) -> Array:
    w = _lam(lam)
    return w * _log(near, far, k) + (1 - w) * _uniform(near, far, k)


def _ratio_param(ratio: float, name: str) -> float:
    value = check.scalar(ratio, name)
    if not value > 1.0 or not np.isfinite(value):
        raise ValueError(f"{name} must be in (1, inf), got {value:g}")
    return value


@register("pssm", "Zhang et al. 2006 eqs. 1–3 (as printed in the supplied text)", "C_i = min(n + (f − n)/γ^(k−i) + δ_bias, f): distances from near grow by γ")
def _pssm(near: float, far: float, k: int, ratio: float = 2.0, bias: float = 0.0) -> Array:
    """Zhang 2006's "theoretic split scheme": L_i = C_i − n grows geometrically, L_(i+1) = γ L_i.

    The text gives no value for γ or δ_bias; γ = 2 and δ_bias = 0 are our defaults.  Eq. 3
    adds δ_bias to every plane, where eqs. 1–2 imply γ^(i−1)·δ_bias (ERRATA P2): eq. 3 as
    printed is implemented.
    """
    g = _ratio_param(ratio, "ratio")
    d = float(check.closed_range(check.scalar(bias, "bias"), "bias", 0.0, np.inf))
    i = np.arange(k + 1)
    c = np.minimum(near + (far - near) / g ** (k - i) + d, far)  # eq. (3)
    c[0] = near
    if np.any(np.diff(c) <= 0):
        raise ValueError("bias too large: the split planes must increase (eq. 3 clamps them at far)")
    return c


@register("pssm-transition", "Zhang et al. 2006 eq. 4 (consistent aliasing transition), uniform maps per split", "C_i = n + (f − n)(1 − λ^−i)/(1 − λ^−k): E1 drops by the resolution ratio λ at each plane")
def _pssm_transition(near: float, far: float, k: int, resolution_ratio: float = 2.0) -> Array:
    """Eq. 4 with uniform maps: E1 ∝ (f_i − n_i)/z, so E1^i/E1^(i+1) = λ means l_i = λ l_(i+1).

    λ = ds_(i+1)/ds_i is the resolution ratio between neighbouring maps (2 in the paper); as
    λ → 1 this tends to the uniform split.
    """
    lam = _ratio_param(resolution_ratio, "resolution_ratio")
    i = np.arange(k + 1)
    return near + (far - near) * (1 - lam ** (-i)) / (1 - lam ** (-k))


@register("pssm-transition-log", "Zhang et al. 2006 eq. 4 (consistent aliasing transition), logarithmic maps per split", "C_i = n (f/n)^((1 − λ^−i)/(1 − λ^−k)); the log split as λ → 1")
def _pssm_transition_log(near: float, far: float, k: int, resolution_ratio: float = 2.0) -> Array:
    """Eq. 4 with logarithmic maps: E1 ∝ ln(f_i/n_i), so ln a_i = λ ln a_(i+1) with a_i = C_i/C_(i−1)."""
    lam = _ratio_param(resolution_ratio, "resolution_ratio")
    i = np.arange(k + 1)
    return near * (far / near) ** ((1 - lam ** (-i)) / (1 - lam ** (-k)))


def _fractions(n: float, f: float, k: int, fractions: tuple[float, ...]) -> Array:
    """Fixed fractions of (f − n) measured from n; C_k = f."""
    return n + (f - n) * np.array([0.0, *fractions[: k - 1], 1.0])


def _given_fractions(method: str, k: int, defaults: tuple[float, ...], s1: float | None, s2: float | None, s3: float | None) -> tuple[float, ...]:
    """The first k − 1 split fractions, ``s1 … s3`` where given (an engine's own split settings), else the defaults;
    each in (0, 1) and increasing (ValueError naming the parameter)."""
    out = []
    for i, (name, value) in enumerate((("s1", s1), ("s2", s2), ("s3", s3))[: k - 1]):
        v = defaults[i] if value is None else float(check.closed_range(check.scalar(value, name), name, 0.0, 1.0))
        if not 0.0 < v < 1.0 or (out and v <= out[-1]):
            raise ValueError(f"{name} (split fraction {i + 1} of {method!r}) must be in (0, 1) and above the previous one, got {v:g}")
        out.append(v)
    return tuple(out)


# --- engine presets: formulas read from the engines' public source (see each source) ----


THREEJS_CURRENT = "three.js r185 and later (npm three 0.185.0 on; run in the tests: 0.187.0)"


@register(
    "threejs-csm",
    "three.js examples/jsm/csm/CSM.js _getBreaks() + CSMFrustum.js split() (npm three 0.187.0)",
    "practical, λ = 0.5 fixed; cascade i ends at b_i·F = C_i (breaks b_i = C_i/F)",
    default_k=3,
    release=THREEJS_CURRENT,
    releases=("r185", "r186", "r187"),
)
def _threejs(near: float, far: float, k: int) -> Array:
    """three.js's CSM since r185: ``split()`` lerps the corners by α = (b·F − n)/(F − n), so cascade
    i ends at depth b_i·F, the practical split itself (b_i = C_i/F from ``_getBreaks``)."""
    return 0.5 * _log(near, far, k) + 0.5 * _uniform(near, far, k)  # λ is a literal 0.5 in _getBreaks


@register(
    "threejs-csm@r184",
    "three.js examples/jsm/csm/CSM.js _getBreaks() + CSMFrustum.js split() (npm three 0.184.0)",
    "practical, λ = 0.5 fixed; breaks C/F applied as fractions of F − n from n (the form before r185)",
    default_k=3,
    release="three.js r184 and earlier (run in the tests: npm three 0.184.0)",
    releases=("r184",),
)
def _threejs_r184(near: float, far: float, k: int) -> Array:
    c = 0.5 * _log(near, far, k) + 0.5 * _uniform(near, far, k)  # λ is a literal 0.5 in getBreaks
    return near + c / far * (far - near)  # CSMFrustum.split lerps the corners by C/F


@register(
    "babylon",
    "Babylon.js cascadedShadowGenerator.ts _splitFrustum() (BabylonJS/Babylon.js)",
    "practical over [minZ, maxZ], λ = 0.5, 4 cascades (2–4)",
    default_k=4,
    max_k=4,
    min_k=2,
    release="Babylon.js 9.35.0 (npm @babylonjs/core, run in the tests; source read at commit 043d0bd0)",
    releases=("9.35.0",),
)
def _babylon(near: float, far: float, k: int, lam: float = 0.5) -> Array:
    return _practical(near, far, k, lam)


def _ogre_padding(edges: Array, padding: float = 1.0) -> tuple[Array, Array]:
    pad = float(check.closed_range(check.scalar(padding, "padding"), "padding", 0.0, np.inf))
    lo, hi = edges[:-1].copy(), edges[1:].copy()
    lo[1:] -= pad  # each inner boundary is covered ±padding (getShadowCamera)
    hi[:-1] += pad
    return lo, hi


@register(
    "ogre-pssm",
    "Ogre OgreShadowCameraSetupPSSM.cpp calculateSplitPoints() / getShadowCamera(); default λ in the header (OGRECave/ogre)",
    "practical, λ = 0.95, 3 splits, inner boundaries padded by 1 world unit",
    default_k=3,
    extend=_ogre_padding,
    release="Ogre 1.x: OgreShadowCameraSetupPSSM.h as stored at OGRECave/ogre commit 00bcfdec (lambda = 0.95); read from source only",
)
def _ogre(near: float, far: float, k: int, lam: float = 0.95) -> Array:
    return _practical(near, far, k, lam)


@register(
    "filament",
    "Filament ShadowMapManager.cpp CascadeSplits; LightManager.h cascadeSplitPositions {0.125, 0.25, 0.5} (google/filament; default read from copies)",
    "split positions 0.125, 0.25, 0.5 of (far − near) from near (s1, s2, s3: ShadowOptions::cascadeSplitPositions); up to 4 cascades",
    default_k=4,
    max_k=4,
    release="not pinned: ShadowOptions defaults read from copies of LightManager.h (read from source only)",
)
def _filament(near: float, far: float, k: int, s1: float | None = None, s2: float | None = None, s3: float | None = None) -> Array:
    return _fractions(near, far, k, _given_fractions("filament", k, (0.125, 0.25, 0.5), s1, s2, s3))


def _bgfx_overlap(edges: Array) -> tuple[Array, Array]:
    lo, hi = edges[:-1].copy(), edges[1:].copy()
    hi[:-1] = 1.005 * lo[1:]  # far_i = 1.005 × near_{i+1}
    return lo, hi


@register(
    "bgfx",
    "bgfx examples/16-shadowmaps/shadowmaps.cpp splitFrustum() (bkaradzic/bgfx, long-standing version)",
    "practical at s = (2i − 1)/(2k), λ = 0.6, 4 splits, far_i = 1.005 near_(i+1)",
    default_k=4,
    max_k=4,
    extend=_bgfx_overlap,
    release="bgfx before commit 01dbbbc0 (the long-standing splitFrustum; read from source only)",
)
def _bgfx(near: float, far: float, k: int, lam: float = 0.6) -> Array:
    w = _lam(lam)
    s = np.concatenate([[0.0], (2 * np.arange(1, k) - 1) / (2 * k), [1.0]])  # odd half-steps, not i/k
    return w * near * (far / near) ** s + (1 - w) * (near + (far - near) * s)


@register(
    "godot",
    "Godot 4 scene/3d/light_3d.cpp defaults; renderer_scene_cull.cpp _light_instance_setup_directional_shadow (godotengine/godot)",
    "fixed fractions 0.1, 0.2, 0.5 of (max_distance − near) from near (s1, s2, s3: directional_shadow_split_1..3); PSSM 4 (or 2) splits",
    default_k=4,
    max_k=4,
    release="Godot 4.x, not pinned to a minor release: light_3d.cpp defaults read from copies (read from source only)",
)
def _godot(near: float, far: float, k: int, s1: float | None = None, s2: float | None = None, s3: float | None = None) -> Array:
    if k == 3:
        raise ValueError("k must be 1, 2 or 4 for 'godot' (orthogonal, PSSM 2 or PSSM 4 splits)")
    return _fractions(near, far, k, _given_fractions("godot", k, (0.1, 0.2, 0.5), s1, s2, s3))


@register(
    "unity-urp",
    "Unity URP UniversalRenderPipelineAsset.cs cascade split defaults (read from copies; normalisation not public)",
    "fixed fractions of the shadow distance: 0.25 | 0.1, 0.3 | 0.067, 0.2, 0.467 (s1, s2, s3: the asset's cascade2Split/3Split/4Split)",
    default_k=4,
    max_k=4,
    release="not pinned: URP asset defaults read from copies (read from source only)",
)
def _unity(near: float, far: float, k: int, s1: float | None = None, s2: float | None = None, s3: float | None = None) -> Array:
    table = {1: (), 2: (0.25,), 3: (0.1, 0.3), 4: (0.067, 0.2, 0.467)}
    return _fractions(near, far, k, _given_fractions("unity-urp", k, table[k], s1, s2, s3))


def _unreal_overlap(edges: Array, transition: float = 0.1) -> tuple[Array, Array]:
    frac = float(check.closed_range(check.scalar(transition, "transition"), "transition", 0.0, 1.0))
    lo, hi = edges[:-1].copy(), edges[1:].copy()
    hi[:-1] += frac * (hi[:-1] - lo[:-1])  # each non-last cascade extended by 10 % of its length
    return lo, hi


@register(
    "unreal",
    "Unreal Engine 4 CSM: CascadeDistributionExponent, CascadeTransitionFraction (read from copies; Epic's repository is private)",
    "geometric: C_i = n + (E^i − 1)/(E^k − 1)(f − n), E = 3, 3 cascades, +10 % overlap",
    default_k=3,
    extend=_unreal_overlap,
    release="Unreal Engine 4, not pinned: read from copies, Epic's repository is private (read from source only)",
)
def _unreal(near: float, far: float, k: int, exponent: float = 3.0) -> Array:
    e = check.scalar(exponent, "exponent")
    if e <= 0:
        raise ValueError(f"exponent must be in (0, inf), got {e:g}")
    i = np.arange(k + 1)
    frac = i / k if e == 1.0 else (e**i - 1) / (e**k - 1)
    return near + frac * (far - near)


@register(
    "osg-pssm",
    "OpenSceneGraph src/osgShadow/ParallelSplitShadowMap.cpp calculateFrustumCorners(), SPLIT_EXP (openscenegraph/OpenSceneGraph, commit 029da13c)",
    "power-law split C_i = n + (f − n)(i/k)^(bias + 1), bias = 0.66 (static fSplitSchemeBias; SPLIT_EXP is the constructor's mode), k from the constructor",
    release="OpenSceneGraph commit 029da13c (read from source only)",
)
def _osg_pssm(near: float, far: float, k: int, bias: float = 0.66) -> Array:
    """OSG's "exponential" split: the fraction of (f − n) grows as a power of i/k, C_0 = n, C_k = f.

    Read from the public source (not copied): split ``i`` starts at
    n + (f − n)(i/k)^(bias + 1); OSG clamps bias to [0, 3] where we raise a ValueError.
    It is not a blend of log and uniform splits; bias = 0 is the uniform split.

    Example
    -------
    >>> split_distances("osg-pssm", 1.0, 101.0, 2).round(4)
    array([  1.    ,  32.6439, 101.    ])
    """
    b = float(check.closed_range(bias, "bias", 0.0, 3.0))
    return near + (far - near) * (np.arange(k + 1) / k) ** (b + 1.0)


def _bgfx_current_splits(near: float, setting_far: float, k: int, lam: float) -> Array:
    """bgfx's calculateCascadeSplits(): the far end of each of the k cascades, for its m_far."""
    s = (2 * np.arange(k) + 1) / (2.5 * k)  # odd indices over 2.5 k, not 2 k: the last is (2k − 1)/(2.5k) < 1
    return lam * near * (setting_far / near) ** s + (1 - lam) * (near + (setting_far - near) * s)


def bgfx_current_setting_far(near: float, far: float, k: int = 4, lam: float = 0.6) -> float:
    """The m_far [world units] at which bgfx's current split makes its last cascade end at ``far``.

    bgfx's cascades stop short of its far plane: with n = 1, m_far = 550, k = 4, λ = 0.6 the last
    one ends at 203.83.  ``far`` here is where shadows end (as for every engine preset), so the
    setting is found by a root search (the end is increasing in m_far).

    Example
    -------
    >>> round(bgfx_current_setting_far(1.0, 203.8255785, 4, 0.6), 3)
    550.0
    """
    from scipy.optimize import brentq

    n, f = (float(v) for v in check.frustum(near, far))
    w, kk = _lam(lam), _partitions(k)
    end = lambda m: _bgfx_current_splits(n, m, kk, w)[-1] - f
    hi = f
    while end(hi) < 0:  # the end is below m_far, so a finite bracket exists
        hi *= 2.0
    return float(brentq(end, f, hi, xtol=1e-12 * f, rtol=1e-14))


@register(
    "bgfx-current",
    "bgfx examples/16-shadowmaps/shadowmaps.cpp calculateCascadeSplits() (bkaradzic/bgfx, commit 01dbbbc0; GPU Gems 3 ch. 10 blend)",
    "log/uniform blend λ = 0.6 at s = (2i + 1)/(2.5k), 4 cascades, no overlap; the last cascade ends before m_far (far = that end)",
    default_k=4,
    max_k=4,
    release="bgfx commit 01dbbbc0 (read from source only)",
)
def _bgfx_current(near: float, far: float, k: int, lam: float = 0.6) -> Array:
    """bgfx's current cascade split: cascade i ends at λ n (m/n)^s_i + (1 − λ)(n + (m − n) s_i),
    s_i = (2i + 1)/(2.5k), m = m_far; cascade 0 starts at n.  ``far`` is where the last cascade
    ends, and m_far is solved for (:func:`bgfx_current_setting_far`).

    Example
    -------
    >>> split_distances("bgfx-current", 1.0, 203.8255785, 4, lam=0.6).round(2)
    array([  1.  ,  23.49,  70.26, 124.27, 203.83])
    """
    m = bgfx_current_setting_far(near, far, k, lam)
    return np.concatenate([[near], _bgfx_current_splits(near, m, k, _lam(lam))])


BEVY_FIRST_BOUND = 10.0  # CascadeShadowConfigBuilder::default first_cascade_far_bound [m]
BEVY_RELEASE = "Bevy crates/bevy_light/src/cascade.rs at bevyengine/bevy commit 0876f40a (read from source only)"


def _bevy_overlap(edges: Array, overlap: float = 0.2) -> tuple[Array, Array]:
    p = float(check.closed_range(check.scalar(overlap, "overlap"), "overlap", 0.0, 0.99))
    lo, hi = edges[:-1].copy(), edges[1:].copy()
    lo[1:] = (1 - p) * edges[1:-1]  # near bound of cascade i = (1 − overlap_proportion)·far bound of i − 1
    return lo, hi


@register(
    "bevy",
    "Bevy crates/bevy_light/src/cascade.rs calculate_cascade_bounds(), build_directional_light_cascades(), CascadeShadowConfigBuilder::default",
    "geometric from the first bound: C_i = first·(far/first)^((i − 1)/(k − 1)), first = 10 m, 4 cascades, near bounds (1 − 0.2)·C_(i−1)",
    default_k=4,
    extend=_bevy_overlap,
    release=BEVY_RELEASE,
)
def _bevy(near: float, far: float, k: int, first: float = BEVY_FIRST_BOUND) -> Array:
    """Bevy's cascade bounds: the first cascade spans [minimum_distance, first_cascade_far_bound],
    the far bounds grow geometrically to maximum_distance; ``near`` is Bevy's ``minimum_distance``
    (default 0.1 m), ``far`` its ``maximum_distance`` (default 150 m), ``first`` in world units
    (Bevy's are metres).  One cascade spans [near, far] (Bevy ignores ``first`` then).

    Example
    -------
    >>> split_distances("bevy", 0.1, 150.0).round(4).tolist()
    [0.1, 10.0, 24.6621, 60.822, 150.0]
    >>> [round(float(x), 4) for x in partitions("bevy", 0.1, 150.0)[0]]
    [0.1, 8.0, 19.7297, 48.6576]
    """
    if k == 1:
        return np.array([near, far])
    fb = check.scalar(first, "first")
    if not near < fb < far:
        raise ValueError(f"first (Bevy's first_cascade_far_bound) must be in (near, far) = ({near:g}, {far:g}), got {fb:g}")
    return np.concatenate([[near], fb * (far / fb) ** (np.arange(k) / (k - 1))])
