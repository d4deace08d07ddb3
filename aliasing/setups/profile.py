"""An engine's shadow settings and the shadow pipeline they give: the types every profile fills in.

A :class:`Profile` is one engine at one release.  It holds the engine's user-facing shadow
settings (:class:`Setting`: the key as the engine spells it, unit, default, the values the
engine accepts and the clamp it applies, and the source file and line they were read from),
and one function from the settings and the camera to the :class:`Pipeline` the engine builds:

* the cascades: their count and eye-depth ranges (overlap included), the fit and snap of each
  map (names of :data:`aliasing.engines.stable.FITS` and ``SNAPS``), the map size and layout;
* the blend band between cascades;
* the bias rule (:class:`BiasRule`): every offset the engine applies, one :class:`BiasTerm` per
  setting, with its conversion from the engine's units to world units, and which faces cast;
* the filter (:class:`Filter`).

Bias terms in world units
-------------------------
For a planar receiver at θ from the light (the angle between its normal and the direction to
the light), each kind of offset is a depth bias along the light in disguise
(:mod:`aliasing.symbolic.bias`); a term of value v and scale c contributes

* ``depth``: c·v (a constant along the light [world units per unit]);
* ``depth_texels``: c·v·w (× the cascade's texel w);
* ``depth_range``: c·v·D (× the cascade's map depth range D along the light [world units], where
  the engine fits the shadow camera's near..far to each cascade: Babylon.js, PlayCanvas; D is
  passed as ``extent``, :func:`aliasing.engines.pipeline.extents` gives it);
* ``normal``: c·v·g(θ)/cos θ (an offset along the receiver's normal; c in world units per unit);
* ``normal_texels``: c·v·w·g(θ)/cos θ;
* ``across_texels``: c·v·w·sin θ·tan θ (the normal's part across the light);
* ``slope``: c·v·w·tan θ·max(|cos φ|, |sin φ|) (slope-scaled bias of the rasterizer state);
* ``tan_texels``: c·v·w·min(tan θ, cap) (a slope bias computed per vertex from the normal and
  clamped, Unreal's ``ShadowMaxSlopeScaleDepthBias``);

with g(θ) = 1, sin θ or 1 − cos θ (``scale``); in the texel kinds w may carry a fixed ``offset``
(w + offset: Godot's constant bias is a fraction of the map's side plus its pancake depth).
A negative c says the engine's sign: three.js
adds ``shadow.bias`` to the receiver's depth, so a negative value lifts it towards the light.

Example
-------
>>> rule = BiasRule((BiasTerm("bias", -0.001, "depth", -1000.0), BiasTerm("normalBias", 0.0, "normal")))
>>> float(rule.depth(0.1, 45.0))          # -0.001 · -1000 = 1 world unit along the light
1.0
>>> round(rule.minimal("normalBias", 3.0, 0.1, 45.0), 6)   # 1 + v/cos 45° = 3: v = 2·cos 45°
1.414214
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from .setting import FLOAT32_MAX, TYPES, Setting, float32  # noqa: F401  (defined there, re-exported here)

Array = NDArray[np.float64]

KINDS = ("depth", "depth_texels", "depth_range", "normal", "normal_texels", "across_texels", "slope", "tan_texels")
SCALES = ("one", "sin", "one-minus-cos")
FACES = ("front", "back", "both")
LENGTH_UNITS = ("m", "cm", "world units")
ROLES = ("cascades", "size", "split", "distance", "bias", "filter", "stable", "blend", "faces", "depth", "radius")


@dataclass(frozen=True)
class BiasTerm:
    """One of the engine's offsets against acne: a setting's value and how it acts (module docstring).

    Attributes
    ----------
    key : str
        The setting it comes from (the engine's spelling), or a name for a fixed part of the rule.
    value : float
        Its value in the engine's units.
    kind : str
        One of :data:`KINDS`.
    scale : float
        World units (or texels) per unit of the setting; negative where the engine's sign lowers
        the receiver for positive values.
    normal_scale : str
        g(θ) of the normal kinds: ``one``, ``sin`` or ``one-minus-cos``.
    contact : bool
        Whether the term moves the surface along the light and so opens a lit gap at a contact
        (constant and texel depth terms: True; normal offsets cancel against a vertical caster).
    cap : float
        The clamp of tan θ in ``tan_texels``, >= 0 (inf: none).
    offset : float
        Added to the texel w in the texel kinds [world units] (0: none).
    """

    key: str
    value: float
    kind: str
    scale: float = 1.0
    normal_scale: str = "one"
    contact: bool | None = None
    cap: float = math.inf
    offset: float = 0.0

    def __post_init__(self) -> None:
        check.choice(self.kind, "kind", KINDS)
        check.choice(self.normal_scale, "normal_scale", SCALES)
        if not (isinstance(self.cap, (int, float)) and self.cap >= 0) or not (isinstance(self.offset, (int, float)) and math.isfinite(self.offset)):
            raise ValueError(f"cap must be >= 0 and offset finite, got cap={self.cap!r}, offset={self.offset!r}")
        if self.contact is None:
            object.__setattr__(self, "contact", self.kind in ("depth", "depth_texels", "depth_range"))

    def per_unit(self, texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike = 0.0, extent: ArrayLike | None = None) -> float | Array:
        """World depth bias along the light per unit of the setting, for a texel w [world] and θ, φ [deg].

        ``extent``: the cascade's map depth range along the light [world units], needed by
        ``depth_range`` terms only (ValueError naming ``extent`` when it is missing there).
        """
        w = check.positive(texel, "texel")
        th = np.radians(check.closed_range(angle, "angle", 0.0, 90.0, " degrees"))
        ph = np.radians(check.finite(azimuth, "azimuth"))
        if self.kind == "depth_range":
            if extent is None:
                raise ValueError(f"extent is needed for the bias term {self.key!r} (depth_range: the cascade's map depth range along "
                                 "the light [world units], aliasing.engines.pipeline.extents)")
            d = check.positive(extent, "extent")
        else:
            d = np.ones(())
        w, th, ph, d = np.broadcast_arrays(w, th, ph, d)
        w = w + self.offset
        g = np.sin(th) if self.normal_scale == "sin" else 1.0 - np.cos(th) if self.normal_scale == "one-minus-cos" else np.ones_like(th)
        with np.errstate(divide="ignore", invalid="ignore"):
            k = {
                "depth": np.ones_like(w),
                "depth_texels": w,
                "depth_range": d,
                "normal": g / np.cos(th),
                "normal_texels": w * g / np.cos(th),
                "across_texels": w * np.sin(th) * np.tan(th),
                "slope": w * np.tan(th) * np.maximum(np.abs(np.cos(ph)), np.abs(np.sin(ph))),
                "tan_texels": w * np.minimum(np.tan(th), self.cap),
            }[self.kind]
        out = self.scale * np.where(np.isfinite(k), k, np.inf)
        return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class BiasRule:
    """An engine's whole bias rule: its terms and which faces are drawn into the map.

    ``faces`` is ``front`` (the lit side casts: lit surfaces compare against themselves and
    acne without bias), ``back`` (the side away from the light casts: a closed or one-sided
    lit surface compares against the far side of its object, so it does not acne; the gap at
    a contact and light leaks move instead) or ``both``.

    ``resolution`` (texels per side of each map, 0: none): where it is set, a ``depth_range``
    term given no ``extent`` takes the map's side w·resolution for the cascade's depth range
    (the cube around a sphere fit: exact for Babylon.js's stabilized cascades and PlayCanvas;
    the tight box's own range along the light differs: :func:`aliasing.engines.pipeline.extents`).
    """

    terms: tuple[BiasTerm, ...] = ()
    faces: str = "front"
    resolution: int = 0

    def __post_init__(self) -> None:
        check.choice(self.faces, "faces", FACES)
        object.__setattr__(self, "terms", tuple(self.terms))
        if isinstance(self.resolution, bool) or not isinstance(self.resolution, (int, np.integer)) or self.resolution < 0:
            raise ValueError(f"resolution must be a whole number of texels >= 0, got {self.resolution!r}")

    def _extent(self, texel: ArrayLike, extent: ArrayLike | None) -> ArrayLike | None:
        """``extent``, or the map's side w·resolution where the rule has one and a depth_range term needs it."""
        if extent is None and self.resolution and self.needs_extent:
            return check.positive(texel, "texel") * self.resolution
        return extent

    def term(self, key: str) -> BiasTerm:
        for t in self.terms:
            if t.key == key:
                return t
        raise ValueError(f"unknown bias setting {key!r}{check.did_you_mean(key, [t.key for t in self.terms])}; "
                         f"this rule has: {', '.join(t.key for t in self.terms) or 'none'}")

    @property
    def needs_extent(self) -> bool:
        """Whether a term scales with the cascade's map depth range (pass ``extent`` to the methods)."""
        return any(t.kind == "depth_range" for t in self.terms)

    def depth(self, texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike = 0.0, extent: ArrayLike | None = None) -> float | Array:
        """All terms as one depth bias along the light [world units] (positive: towards the light).

        ``extent``: the cascade's map depth range along the light [world units], for rules with
        ``depth_range`` terms (:attr:`needs_extent`).
        """
        extent = self._extent(texel, extent)
        total = sum((t.value * np.asarray(t.per_unit(texel, angle, azimuth, extent)) for t in self.terms), np.zeros(()))
        total = np.broadcast_to(total, np.broadcast_shapes(np.shape(texel), np.shape(angle), np.shape(azimuth))) if not self.terms else total
        return float(total) if np.ndim(total) == 0 else np.asarray(total, float)

    def contact(self, texel: ArrayLike, extent: ArrayLike | None = None) -> float | Array:
        """The part along the light [world units]: what opens a lit gap at the foot of a caster."""
        w = check.positive(texel, "texel")
        extent = self._extent(w, extent)
        total = np.zeros(np.broadcast_shapes(w.shape, np.shape(extent)) if extent is not None else w.shape)
        for t in self.terms:
            if t.contact:
                total = total + t.value * np.asarray(t.per_unit(w, 0.0, 0.0, extent))
        return float(total) if total.ndim == 0 else total

    def minimal(self, key: str, need: ArrayLike, texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike = 0.0,
                extent: ArrayLike | None = None) -> float | Array:
        """The value of setting ``key`` that, the other terms kept, gives the depth bias ``need`` [world units].

        A bound from below where the term's scale is positive, from above where it is negative
        (three.js's ``shadow.bias``); ±inf where the term cannot help (a normal offset on a
        receiver facing the light, θ = 0).  A setting that acts through several terms (PlayCanvas's
        ``shadowBias``: a slope and a constant rasterizer bias) counts with all of them.
        """
        self.term(key)  # the ValueError with a did-you-mean
        need = check.finite(need, "need")
        extent = self._extent(texel, extent)
        own = [t for t in self.terms if t.key == key]
        per = sum((np.asarray(t.per_unit(texel, angle, azimuth, extent), float) for t in own), np.zeros(()))
        part = sum((t.value * np.asarray(t.per_unit(texel, angle, azimuth, extent)) for t in own), np.zeros(()))
        rest = np.asarray(self.depth(texel, angle, azimuth, extent)) - part
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.where(per != 0, (need - rest) / np.where(per != 0, per, 1.0), np.where(need - rest <= 0, 0.0, np.inf))
        return float(out) if np.ndim(out) == 0 else out


@dataclass(frozen=True)
class Tunable:
    """A setting that :func:`aliasing.tune.tune` may choose, and the values it searches.

    Attributes
    ----------
    key : str
        The setting's key (a :class:`Setting` of the same profile).
    role : str
        What it does to the shadows (:data:`ROLES`): ``cascades`` (their count), ``size`` (texels
        per side of each map), ``split`` (the split mode or a split parameter), ``distance``
        (where shadows end), ``bias`` (a term of the bias rule: set to its minimum, not searched),
        ``filter``, ``stable`` (stabilization), ``blend`` (the blend band) or ``faces`` (which faces cast:
        searched by the wrong-pixel objective only, :mod:`aliasing.tune.pixels`; the perspective error cannot
        tell the shadow that thin casters lose when only their back faces cast), ``depth`` (the light's
        depth range, a margin behind the casters) or ``radius`` (the filter's radius): these two also by
        the wrong-pixel objective only (the perspective error does not depend on them).
    values : tuple
        The values searched, for discrete settings (map sizes, counts, modes, booleans).
    range : tuple or None
        ``(low, high)`` searched for a continuous setting (a split λ or fraction).
    step : float
        The resolution of a grid over ``range`` (the exhaustive grid of the tests; the search
        itself refines below it).
    when : tuple of (key, value)
        The other settings this one acts under (three.js's λ only with ``mode: "custom"``); a
        ``frozenset`` value means any of its members (Filament's first split position with 2, 3
        or 4 cascades).
    """

    key: str
    role: str
    values: tuple = ()
    range: tuple | None = None
    step: float = 0.0
    when: tuple = ()

    def __post_init__(self) -> None:
        check.choice(self.role, "role", ROLES)
        object.__setattr__(self, "values", tuple(self.values))
        object.__setattr__(self, "when", tuple(tuple(w) for w in self.when))
        if self.range is not None:
            lo, hi = self.range
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise ValueError(f"tunable {self.key!r}: range must be (low, high) with low < high, got {self.range!r}")
            if not self.step > 0:
                raise ValueError(f"tunable {self.key!r}: a continuous range needs a step > 0, got {self.step!r}")

    def active(self, settings: Mapping[str, Any]) -> bool:
        """Whether the setting acts under ``settings`` (every ``when`` pair holds)."""
        return all(settings.get(k) in v if isinstance(v, frozenset) else settings.get(k) == v for k, v in self.when)

    def grid(self) -> tuple:
        """The values of an exhaustive grid: ``values``, or ``range`` at ``step`` (ends included)."""
        if self.range is None:
            return self.values
        lo, hi = self.range
        n = int(round((hi - lo) / self.step))
        return tuple(float(v) for v in np.linspace(lo, hi, n + 1))


@dataclass(frozen=True)
class Filter:
    """The engine's shadow filter: ``hard`` (one comparison), ``pcf`` (k×k comparisons over ``taps``
    texels; hardware 2×2 comparison sampling is k = 2), ``pcss``, ``vsm``, ``esm``; ``radius``
    a world or texel radius where the engine sets one; ``taps`` the kernel's width [texels]."""

    kind: str = "pcf"
    taps: int = 1
    radius: float = 0.0
    note: str = ""


@dataclass(frozen=True)
class Pipeline:
    """What the engine builds from its settings and a camera.

    Attributes
    ----------
    near_i, far_i : tuple of float
        Eye depths where each cascade's map starts and ends (overlap included) [world units].
    fit, snap : str
        Names of :data:`aliasing.engines.stable.FITS` and ``SNAPS`` (``tight`` and ``none``:
        the papers' fit). ``fit="fixed"``: a world box of ``box`` sides that does not follow
        the view (three.js's single DirectionalLight shadow camera).
    resolution : int
        Texels per side of each cascade's map.
    layout : str
        How the maps are stored (``separate``, ``array``, ``atlas 2x2 of 4096``).
    blend : float
        The blend band between cascades as a fraction of each cascade's depth range (0: none).
    bias : BiasRule
        The offsets and faces.
    filter : Filter
        The lookup filter.
    stable : bool
        Whether the fit is stabilized (snapped and rotation-invariant): no shimmer under motion.
    box : tuple or None
        ``(width, height)`` of a fixed world box [world units] when ``fit == "fixed"``.
    grow : tuple of float
        World units the engine adds to each cascade's box side after the fit (three.js CSM's
        ``fade`` margin), one per cascade; empty: none.
    depth_range : tuple of float or None
        The light's depth range (near, far) [world units] where the engine's depth unit is a
        fraction of it.
    min_extent : float
        The smallest depth range the engine gives a cascade's map [world units] where it fits
        near..far per cascade (Babylon.js with depthClamp: 1); 0: none.
    memory : int
        Bytes of the depth maps.
    rows : int
        Texels along the map's t axis where they differ from ``resolution`` (Godot's two splits
        are halves of a square atlas: each split ``resolution`` wide, ``resolution/2`` tall);
        0: square maps.
    bands : tuple of (float, float)
        The eye-depth range (start, end) of each blend band between cascade i and i + 1
        [world units]; empty when the engine does not blend.
    notes : tuple of str
        What the profile does not model, in words (empty when all of it is).
    """

    near_i: tuple
    far_i: tuple
    fit: str
    snap: str
    resolution: int
    bias: BiasRule
    filter: Filter
    layout: str = "separate"
    blend: float = 0.0
    stable: bool = False
    box: tuple | None = None
    grow: tuple = ()
    depth_range: tuple | None = None
    min_extent: float = 0.0
    memory: int = 0
    split: str = ""
    notes: tuple = ()
    rows: int = 0
    bands: tuple = ()

    def __post_init__(self) -> None:
        n, f = np.asarray(self.near_i, float), np.asarray(self.far_i, float)
        if n.shape != f.shape or n.ndim != 1 or n.size < 1:
            raise ValueError("near_i and far_i must be equal-length lists of cascade depths")
        if not (np.all(np.isfinite(n)) and np.all(np.isfinite(f)) and np.all(n > 0) and np.all(f > n)):
            raise ValueError(f"cascade depths must be finite with 0 < near_i < far_i, got {n.tolist()}, {f.tolist()}")
        object.__setattr__(self, "near_i", tuple(map(float, n)))
        object.__setattr__(self, "far_i", tuple(map(float, f)))
        if not (isinstance(self.resolution, (int, float, np.integer, np.floating)) and 3 <= self.resolution < math.inf):
            raise ValueError(f"each map must be at least 3 texels per side to have a texel grid to study, got {self.resolution!r}")
        object.__setattr__(self, "notes", tuple(self.notes))
        grow = np.asarray(self.grow, float)
        if grow.size and (grow.shape != n.shape or not np.all(np.isfinite(grow)) or np.any(grow < 0)):
            raise ValueError(f"grow must be one finite value >= 0 per cascade, got {self.grow!r}")
        object.__setattr__(self, "grow", tuple(map(float, grow)))
        object.__setattr__(self, "bands", tuple((float(a), float(b)) for a, b in self.bands))
        if not self.memory:
            object.__setattr__(self, "memory", int(len(n) * self.resolution * (self.rows or self.resolution) * 4))

    @property
    def k(self) -> int:
        """Number of cascades."""
        return len(self.near_i)


@dataclass(frozen=True)
class Profile:
    """One engine at one release: its settings and the pipeline they build.

    Attributes
    ----------
    engine : str
        The toolkit's name (``threejs``, ``babylon``, ...).
    title : str
        The engine's own name and what part of it (``three.js CSM addon``).
    release : str
        The release as the engine numbers it (``r187``, ``9.35``).
    releases : tuple of str
        Other spellings ``NAME@RELEASE`` accepts for this profile.
    settings : tuple of Setting
        Every user-facing shadow setting.
    build : callable
        ``build(settings, camera) -> Pipeline``; ``settings`` has every key, validated.
    snippet : callable or None
        ``snippet(settings, keys=None, light=None) -> str``: code in the engine's language that sets
        ``keys`` of ``settings`` (None: every setting, on a new light) on the user's light named
        ``light`` (None: a placeholder the user recognises).
    language : str
        The snippet's language.
    source : str
        Where the engine's code was read (repository and commit or npm package and version).
    tunable : tuple of Tunable
        The settings :func:`aliasing.tune.tune` may choose, with the values it searches.
    """

    engine: str
    title: str
    release: str
    settings: tuple
    build: Callable[[Mapping[str, Any], Any], Pipeline]
    releases: tuple = ()
    snippet: Callable[..., str] | None = None
    language: str = ""
    source: str = ""
    npm: str = ""
    tunable: tuple = ()
    _by_key: Mapping[str, Setting] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        keys = [s.key for s in self.settings]
        if len(set(keys)) != len(keys):
            raise ValueError(f"{self.engine}@{self.release}: duplicate setting keys")
        object.__setattr__(self, "settings", tuple(self.settings))
        object.__setattr__(self, "_by_key", MappingProxyType({s.key: s for s in self.settings}))
        object.__setattr__(self, "tunable", tuple(self.tunable))
        for t in self.tunable:
            if t.key not in self._by_key:
                raise ValueError(f"{self.engine}@{self.release}: tunable {t.key!r} is not one of its settings")

    @property
    def name(self) -> str:
        return f"{self.engine}@{self.release}"

    @property
    def length_unit(self) -> str:
        """The engine's world unit: that of its first setting in ``m``, ``cm`` or ``world units`` (Unreal's
        ``cm``, Godot's and Unity's ``m``; ``world units`` where the engine fixes none, as three.js)."""
        return next((s.unit for s in self.settings if s.unit in LENGTH_UNITS), "world units")

    def setting(self, key: str) -> Setting:
        """The setting ``key``; a ValueError with a did-you-mean from this engine's keys."""
        if isinstance(key, str) and key in self._by_key:
            return self._by_key[key]
        hint = check.did_you_mean(key, self._by_key) if isinstance(key, str) else ""
        raise ValueError(f"unknown {self.title} setting {key!r}{hint}; its settings are: {', '.join(self._by_key)}")

    def defaults(self) -> dict[str, Any]:
        """Every setting at the engine's default."""
        return {s.key: s.default for s in self.settings}

    def resolve(self, settings: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """The defaults with ``settings`` applied, every value validated (ValueError naming the key)."""
        if settings is not None and not isinstance(settings, Mapping):
            raise ValueError(f"settings must be a mapping of {self.title} setting names to values, got {type(settings).__name__}")
        out = self.defaults()
        for key, value in (settings or {}).items():
            out[key] = self.setting(key).coerce(value)
        return out
