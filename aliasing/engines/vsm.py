"""Unreal Engine 5 virtual shadow-map clipmaps for a directional light.

Read from ``Engine/Source/Runtime/Renderer/Private/VirtualShadowMaps/VirtualShadowMapClipmap.cpp``
(the copy stored as unicorn2022/UE5.8.0, commit 5d9a05c1; Epic's repository is private):

* level l has radius R_l = 2^(l+1) (``GetLevelRadius``) and a 16384² virtual map
  (``VirtualMaxResolutionXY``) spanning 2·``HalfLevelDim`` = 4·R_l, so its texel is
  t_l = 2^(l+3)/16384 = 2^(l−11) [cm; the engine's unit] and its page (128² texels) is
  2^(l−4) wide;
* ``LodScale = 0.5/ProjectionScale.X · 16384/CameraViewportWidth`` (the engine's comment:
  the roll invariance of the directional light depends on square pixels, "so we just base
  everything on the camera X scales/resolution"); the resolution LOD bias is
  B′ = max(0, bias + log2(LodScale)) (the clamp is the engine's);
* a receiver at distance d_c from the camera takes level L = floor(log2 d_c + B′)
  (``VirtualShadowMapProjectionCommon.ush``, same copy: ``CalcAbsoluteClipmapLevel`` =
  ½·log2 of the squared distance to the clipmap origin, the level index
  max(0, level − FirstLevel), the bias added per level), clamped to [FirstLevel,
  LastLevel]; ``VirtualShadowMapPageMarking.ush`` (same copy) ``GetBiasedClipmapLevel``
  floors log2 d + ResolutionLodBias + GlobalResolutionLodBias (the global bias is where
  the dynamic resolution's extra bias goes) and ``MarkPageDirectional`` marks no page past
  the last level (``ClipmapLevelCountRemaining``), so receivers beyond its radius
  2^(last+1) get no virtual-shadow-map shadow;
* page-marking dilation (``MarkPage``, same file): a pixel also marks the pages at
  floor(p ± δ·d) in page units, d = (±1, ±1) a per-pixel dither of one diagonal
  (``VirtualShadowMapPageMarking.usf`` ``PageDilationDither`` from the thread index), δ =
  ``r.Shadow.Virtual.PageDilationBorderSizeDirectional`` = 0.05 (``VirtualShadowMapArray.cpp``
  copies in the index): the marked region grows by δ page on every side;
* coarse pages (``MarkCoarsePages`` in ``VirtualShadowMapPageMarking.usf``, same copy): for
  every coarse level (``r.Shadow.Virtual.Clipmap.FirstCoarseLevel`` 15 …
  ``LastCoarseLevel`` 18, ``VirtualShadowMapClipmap.cpp`` copies;
  ``r.Shadow.Virtual.MarkCoarsePagesDirectional`` = 1) the 4 pages around the clipmap's
  origin, floor/ceil(p − ½), are marked whatever the receivers: at most 4 per coarse level;
* defaults in this version: FirstLevel 6, LastLevel 22, ``ResolutionLodBiasDirectional``
  0.0 (−0.5 in older 5.x copies, e.g. reza-shahriari/UnrealEngine-lite).

A camera of any aspect.  ``CameraViewportWidth`` is ``CameraViewRectSize.X``, the view
rect's width in pixels (raised to ``r.Shadow.Virtual.Clipmap.MinCameraViewportWidth`` when
that is set; orthographic cameras are not modelled).  ``ProjectionScale.X`` is
|``ProjectionMatrix.M[0][0]``| (``FViewMatrices::Init`` in
``Engine/Source/Runtime/Engine/Private/SceneView.cpp``, same copy; a stereo eye doubles it),
the horizontal entry: it maps the image's left and right edges to clip x = ±1, so it is
1/tan θ_x whatever the field of view was given as (``TReversedZPerspectiveMatrix`` in
``Engine/Source/Runtime/Core/Public/Math/PerspectiveMatrix.h``, read in the copy
chenyong2github/UnrealEngine as the UE 5.8 copy does not store it, puts 1/tan(HalfFOV) in
M[0][0] and Width/tan(HalfFOV)/Height in M[1][1]: M[1][1] = 1/tan θ_y with square pixels).  So for the toolkit's camera — ``fov`` the
vertical full field of view, ``aspect`` = width/height, as in :class:`aliasing.View` —

    tan θ_y = tan(fov/2),   tan θ_x = aspect·tan θ_y   (:attr:`aliasing.View.tan_theta_x`),
    W = the image's pixels across (its height W/aspect),
    LodScale = ½·tan θ_x·16384/W,

and a pixel at eye depth d spans 2 tan θ_x d/W = 2 tan θ_y d/(W/aspect) across and up.
:class:`Clipmap` takes ``fov`` (vertical), ``width`` (W) and ``aspect``; at aspect 1 the
vertical and horizontal angles are one θ and every result is the square model's bit for
bit.

Scalability: Epic's "Hillside sample" documentation quotes the Epic level's original
``r.Shadow.Virtual.ResolutionLodBiasDirectional=-1.5``; the Low–High bias 0 and the pool
sizes 512/512/2048/4096/8192 (Low…Cinematic) are the issue's list — ``BaseScalability.ini``
was not stored, so they are marked as such in :data:`PRESETS`.

Result derived here (not stated by the engine; :mod:`aliasing.symbolic.engines` derives it,
the tests check it): with W eye pixels across and d_c = d (on the view axis), outside the
clamps,

    m(d) = t_L / (2 tanθ_x d / W) = 2^(1 + bias − φ),   φ = frac(log2 d + B′),

so m saw-tooths between 2^bias (exclusive) and 2^(1+bias) once per octave of distance,
independent of fov, aspect, W and the scene unit (a wider view moves the level flips, by
log2 of its tan θ_x, not the saw-tooth's range).  Off the axis d_c = d/cos ψ, so over the
frustum M = 2^(1+bias)·√(1 + tan²θ_x + tan²θ_y) (the image corners; a supremum;
√(1 + 2 tan²θ) for a square image).

Example
-------
>>> c = Clipmap(fov=90.0, width=1920, bias=0.0)
>>> round(float(m_axis(c, np.array([1000.0]))[0]), 6) <= 2.0
True
"""

from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from .. import geometry
from ..view import View, check_aspect

Array = NDArray[np.float64]
VIRTUAL_RES = 16384  # FVirtualShadowMap::VirtualMaxResolutionXY
PAGE = 128  # texels per page side (VSM_PAGE_SIZE)
LOAD_FACTOR = 0.85  # the "engine's 0.85 load factor" (r.Shadow.Virtual.DynamicRes.MaxPagePoolLoadFactor; cvar not read here)
CM_PER_UNIT = {"cm": 1.0, "m": 100.0, "mm": 0.1, "in": 2.54, "ft": 30.48}
BIAS_RANGE = (-8.0, 8.0)  # the cvar is an unclamped float; the model accepts ±8 octaves
DILATION = 0.05  # r.Shadow.Virtual.PageDilationBorderSizeDirectional [pages]
COARSE_LEVELS = (15, 18)  # r.Shadow.Virtual.Clipmap.FirstCoarseLevel, LastCoarseLevel
COARSE_PAGES_PER_LEVEL = 4  # MarkCoarsePages: floor/ceil of the origin's page address − ½ in x and y
LEVEL_RANGE = (-64, 64)  # clipmap levels (the engine's default 6..22); level L spans 2^L cm, 2^64 cm ≈ 1.8e17 km


@dataclasses.dataclass(frozen=True)
class VSMPreset:
    name: str
    bias: float
    pool: int
    source: str


PRESETS: dict[str, VSMPreset] = {
    "low": VSMPreset("low", 0.0, 512, "bias and pool from the issue's list (BaseScalability.ini not stored)"),
    "medium": VSMPreset("medium", 0.0, 512, "bias and pool from the issue's list (BaseScalability.ini not stored)"),
    "high": VSMPreset("high", 0.0, 2048, "bias and pool from the issue's list (BaseScalability.ini not stored)"),
    "epic": VSMPreset("epic", -1.5, 4096, "bias −1.5: Epic's Hillside sample docs ('Original' Epic value); pool from the issue's list"),
    "cinematic": VSMPreset("cinematic", -1.5, 8192, "bias and pool from the issue's list (BaseScalability.ini not stored)"),
    "default": VSMPreset("default", 0.0, 4096, "VirtualShadowMapClipmap.cpp UE 5.8 copy: bias 0.0; pool 4096 is r.Shadow.Virtual.MaxPhysicalPages as quoted in Epic's docs copies"),
}


@dataclasses.dataclass(frozen=True)
class Clipmap:
    """A directional light's clipmap as the engine configures it.

    Parameters
    ----------
    fov : float
        Full vertical field of view [deg], in (0, 180) (the toolkit's convention; at
        ``aspect`` 1 also the horizontal one).
    width : int
        Viewport width W [pixels across], ≥ 1; the image is W/aspect pixels high (square
        pixels).
    bias : float
        ``r.Shadow.Virtual.ResolutionLodBiasDirectional`` [octaves], in [−8, 8].
    first, last : int
        ``Clipmap.FirstLevel`` / ``LastLevel``, first ≤ last.
    unit : str
        The scene's length unit (cm, m, mm, in, ft); lengths in and out are in it.
    dilation : float
        Page-marking dilation δ [pages], in [0, 0.5] (0.05: the engine's).
    coarse : tuple of int or None
        (first, last) coarse level whose 4 central pages are always marked; None: no coarse pages.
    aspect : float
        Image width/height, 0 < aspect < inf (default 1: square): tan θ_x = aspect·tan θ_y,
        and the engine's LOD scale takes tan θ_x (module docstring).

    Example
    -------
    >>> wide = Clipmap(fov=60.0, width=1920, aspect=16 / 9)
    >>> round(wide.tan_x / wide.tan_y, 12), round(wide.lod_bias - Clipmap(fov=60.0, width=1920).lod_bias, 12)
    (1.777777777778, 0.830074998558)
    """

    fov: float = 90.0
    width: int = 1920
    bias: float = 0.0
    first: int = 6
    last: int = 22
    unit: str = "cm"
    dilation: float = DILATION
    coarse: tuple[int, int] | None = COARSE_LEVELS
    aspect: float = 1.0

    def __post_init__(self) -> None:
        check.closed_range(self.dilation, "dilation", 0.0, 0.5, " pages")
        if self.coarse is not None and (len(self.coarse) != 2 or int(self.coarse[0]) > int(self.coarse[1])):
            raise ValueError(f"coarse must be (first coarse level, last coarse level) with first <= last, or None, got {self.coarse!r}")
        check.fov(self.fov)
        if not (float(self.width) >= 1 and float(self.width).is_integer()):
            raise ValueError(f"width (viewport pixels) must be a whole number >= 1, got {self.width!r}")
        check.closed_range(self.bias, "bias", *BIAS_RANGE, " octaves")
        for name, level in (("first", self.first), ("last", self.last)):  # 2^level stays a finite float
            if isinstance(level, bool) or not (LEVEL_RANGE[0] <= float(level) <= LEVEL_RANGE[1] and float(level).is_integer()):
                raise ValueError(f"{name} (clipmap level) must be a whole number in [{LEVEL_RANGE[0]}, {LEVEL_RANGE[1]}], got {level!r}")
        if int(self.first) > int(self.last):
            raise ValueError(f"first level must be <= last level, got first={self.first}, last={self.last}")
        check.choice(self.unit, "unit", CM_PER_UNIT)
        check.scalar(self.aspect, "aspect")
        # the angles, as every View has them (the one degrees → radians conversion is there;
        # near and far do not enter them): validates aspect once, naming it
        object.__setattr__(self, "_view", View(1.0, 2.0, float(self.fov), float(self.aspect)))
        with np.errstate(over="ignore"):
            tx = self.tan_x
        if not np.isfinite(0.5 * tx * VIRTUAL_RES):  # LodScale = ½·tanθ_x·16384/W must be a number
            raise ValueError(f"aspect (image width/height) is too large for fov {float(self.fov):g}: aspect·tan(fov/2) overflows the LOD scale, got {float(self.aspect):g}")

    @property
    def tan_y(self) -> float:
        """tan θ_y [dimensionless]: the vertical half-width of the image at unit eye depth."""
        return float(self._view.tan_theta)  # type: ignore[attr-defined]

    @property
    def tan_x(self) -> float:
        """tan θ_x = aspect·tan θ_y [dimensionless]: 1/``ProjectionMatrix.M[0][0]``, the engine's X scale."""
        return float(self._view.tan_theta_x)  # type: ignore[attr-defined]

    @property
    def tan(self) -> float:
        """The engine's tan θ (its LOD takes the X scale): :attr:`tan_x`."""
        return self.tan_x

    @property
    def corner(self) -> float:
        """d_c/d at the image corners, √(1 + tan²θ_x + tan²θ_y) [dimensionless] (√(1 + 2tan²θ) at aspect 1, bit for bit)."""
        tx, ty = np.float64(self.tan_x), np.float64(self.tan_y)
        with np.errstate(over="ignore"):  # a view wide enough to overflow: the corner is at infinity
            return float(np.sqrt(1 + (tx**2 + ty**2)))

    @property
    def lod_bias(self) -> float:
        """B′ = max(0, bias + log2(0.5·tanθ_x·16384/W)) [octaves] (VirtualShadowMapClipmap.cpp)."""
        lod_scale = 0.5 * self.tan * VIRTUAL_RES / self.width
        return max(0.0, self.bias + float(np.log2(lod_scale)))

    def to_cm(self, x: ArrayLike) -> Array:
        return np.asarray(x, float) * CM_PER_UNIT[self.unit.lower()]


def level(c: Clipmap, distance: ArrayLike) -> Array:
    """Clipmap level of receivers at ``distance`` [scene units] from the camera (float; NaN beyond the last level).

    Example
    -------
    >>> level(Clipmap(fov=90, width=2048, bias=0.0), [1.0, 1000.0]).tolist()
    [6.0, 11.0]
    """
    d = check.positive(distance, "distance") * CM_PER_UNIT[c.unit.lower()]
    raw = np.floor(np.log2(d) + c.lod_bias)  # CalcAbsoluteClipmapLevel + bias
    lv = np.maximum(raw, c.first)  # clamp to the first level
    return np.where(d < 2.0 ** (c.last + 1), np.minimum(lv, c.last), np.nan)


def texel(c: Clipmap, lv: ArrayLike) -> Array:
    """Texel size [scene units] of level ``lv``: 2^(l+3)/16384 cm."""
    return 2.0 ** (np.asarray(lv, float) + 3) / VIRTUAL_RES / CM_PER_UNIT[c.unit.lower()]


def m_at(c: Clipmap, depth: ArrayLike, distance: ArrayLike) -> Array:
    """Error m = texel / pixel footprint at eye depth and camera distance [scene units].

    The pixel spans 2 tanθ_x d/W across (= 2 tanθ_y d/(W/aspect) up: square pixels).
    """
    d = check.positive(depth, "depth")
    return texel(c, level(c, distance)) * c.width / (2 * c.tan_x * d)  # eq. (2) of Lloyd 2006 at W pixels


def m_axis(c: Clipmap, depth: ArrayLike) -> Array:
    """m along the view axis (distance = depth): the saw-tooth 2^(1 + bias − φ) between clamps."""
    return m_at(c, depth, depth)


def m_axis_range(c: Clipmap, near: float, far: float) -> tuple[float, float]:
    """(inf, sup) of m on the axis over [near, far] [scene units], from the closed form.

    Inside the unclamped levels m ∈ (2^(b′), 2^(1+b′)] with b′ = B′ − log2(0.5·tanθ_x·16384/W)
    (= bias unless B′ was clamped at 0); at the first level's clamp m grows as 1/d towards
    the camera.  Breakpoints d = 2^(L − B′) are evaluated from both sides.
    """
    n, f = (float(x) for x in check.frustum(near, far))
    lo_cm, hi_cm = n * CM_PER_UNIT[c.unit.lower()], min(f * CM_PER_UNIT[c.unit.lower()], 2.0 ** (c.last + 1))
    if lo_cm >= hi_cm:
        return float("nan"), float("nan")
    levels = np.arange(np.floor(np.log2(lo_cm) + c.lod_bias), np.floor(np.log2(hi_cm) + c.lod_bias) + 1)
    breaks = 2.0 ** (levels[1:] - c.lod_bias)
    pts = np.concatenate([[lo_cm, hi_cm], breaks * (1 + 1e-12), breaks * (1 - 1e-12)]) / CM_PER_UNIT[c.unit.lower()]  # both sides of each flip
    pts = pts[(pts >= n) & (pts <= f)]
    m = m_axis(c, pts)
    return float(np.nanmin(m)), float(np.nanmax(m))


def frustum_max(c: Clipmap, near: float, far: float, samples: int = 4096) -> float:
    """Max m over the frustum [dimensionless]: on the corner rays, where d_c/d = √(1 + tan²θ_x + tan²θ_y) is largest.

    At a given eye depth m grows with the camera distance d_c (through the level) up to the
    last level's radius R = 2^(last+1) cm, beyond which nothing is shadowed by the clipmap;
    so each depth is evaluated at d_c = min(k·d, R⁻), the corner ray while it is covered.
    NaN when no receiver in [near, far] is covered (near ≥ R).
    """
    n, f = (float(x) for x in check.frustum(near, far))
    d = np.geomspace(n, f, samples)
    k = c.corner
    scale = CM_PER_UNIT[c.unit.lower()]
    br = 2.0 ** (np.arange(c.first, c.last + 1) - c.lod_bias) / scale / k  # level flips on the corner ray
    d = np.sort(np.concatenate([d, br[(br > n) & (br < f)]]))
    covered = 2.0 ** (c.last + 1) / scale * (1 - 1e-12)  # just inside the last level's radius
    with np.errstate(over="ignore", invalid="ignore"):
        dc = np.minimum(d * k, covered)  # = d·k bit for bit wherever the corner ray is covered
    if not (n < covered):
        return float("nan")
    return float(np.nanmax(m_at(c, d, np.maximum(dc, d))))


def coarse_pages(c: Clipmap) -> int:
    """Pages ``MarkCoarsePages`` marks whatever the receivers: 4 per coarse level inside [first, last].

    Example
    -------
    >>> coarse_pages(Clipmap()), coarse_pages(Clipmap(coarse=None)), coarse_pages(Clipmap(last=16))
    (16, 0, 8)
    """
    if c.coarse is None:
        return 0
    lo, hi = max(int(c.coarse[0]), int(c.first)), min(int(c.coarse[1]), int(c.last))
    return COARSE_PAGES_PER_LEVEL * max(0, hi - lo + 1)


def pages(c: Clipmap, near: float, far: float, light: str | ArrayLike = "overhead") -> Array:
    """Pages (128² texels) the frustum can touch, an upper bound per light direction ``(N,)``.

    For each level, the receivers using it have camera distance in [2^(L−B′), 2^(L+1−B′))
    (the first level from 0, the last to its radius); they lie in the frustum slice with eye
    depth in [d_lo·cos ψ_max, d_hi] (cos ψ_max = 1/√(1 + tan²θ_x + tan²θ_y), the corner ray).  The slice's light-space
    box (:func:`aliasing.directional.fit`) in pages, grown by the marking's dilation δ page on
    each side, +1 per axis for its alignment to the page grid, capped at 128 per axis, summed
    over levels; plus the coarse pages (:func:`coarse_pages`; counted apart, so a bound).
    """
    n, f = (float(x) for x in check.frustum(near, far))
    scale = CM_PER_UNIT[c.unit.lower()]
    cos_max = 1 / c.corner
    lv = np.arange(c.first, c.last + 1)
    d_lo = np.where(lv == c.first, 0.0, 2.0 ** (lv - c.lod_bias)) / scale
    d_hi = np.where(lv == c.last, 2.0 ** (c.last + 1), 2.0 ** (lv + 1 - c.lod_bias)) / scale
    a, b = np.maximum(d_lo * cos_max, n), np.minimum(d_hi, f)
    keep = a < b
    lvk, a, b = lv[keep], a[keep], b[keep]
    lights = geometry.lights(light)
    if lvk.size == 0:
        return np.full(len(lights), float(coarse_pages(c)))
    basis = geometry.light_space(lights)  # (N, 3, 3): rows x, −, y of the light image plane
    page = PAGE * texel(c, lvk)
    grow = 2 * c.dilation  # MarkPage: ± δ page around every marked point
    px = np.minimum(np.ceil(slice_extent(a, b, c.tan_y, basis[:, 0], c.aspect) / page + grow) + 1, VIRTUAL_RES // PAGE)
    py = np.minimum(np.ceil(slice_extent(a, b, c.tan_y, basis[:, 2], c.aspect) / page + grow) + 1, VIRTUAL_RES // PAGE)
    return (px * py).sum(axis=-1) + coarse_pages(c)


def slice_extent(a: ArrayLike, b: ArrayLike, tan: float, axis: ArrayLike, aspect: float = 1.0) -> Array:
    """Extent [scene units] of frustum slices [a, b] ``(K,)`` along unit eye-space axes ``(N, 3)``: ``(N, K)``.

    ``tan`` is tan θ_y (the vertical half-angle), ``aspect`` the image's width/height, so the
    slice's corners are (±d·aspect·t, ±d·t, d).  A corner projects to
    d·(e_z ± aspect·t e_x ± t e_y), so with q = t(aspect·|e_x| + |e_y|) the extent is
    max(a(e_z + q), b(e_z + q)) − min(a(e_z − q), b(e_z − q)) (q = t(|e_x| + |e_y|) at
    aspect 1, bit for bit).  Closed form of :func:`aliasing.directional.fit`'s ptp (tested
    against it).

    Example
    -------
    >>> slice_extent(1.0, 2.0, 1.0, [[1.0, 0.0, 0.0]]).tolist(), slice_extent(1.0, 2.0, 1.0, [[1.0, 0.0, 0.0]], 2.0).tolist()
    ([[4.0]], [[8.0]])
    """
    e = np.atleast_2d(np.asarray(axis, float))[:, None, :]
    aa, bb = np.asarray(a, float)[None], np.asarray(b, float)[None]
    r = float(check_aspect(check.scalar(aspect, "aspect")))
    q = tan * (r * np.abs(e[..., 0]) + np.abs(e[..., 1]))  # r·|e_x| is |e_x| exactly at aspect 1
    hi, lo = e[..., 2] + q, e[..., 2] - q
    return np.maximum(aa * hi, bb * hi) - np.minimum(aa * lo, bb * lo)


def pool_check(c: Clipmap, near: float, far: float, light: str | ArrayLike, pool: int, ground: float | None = None) -> dict[str, object]:
    """Whether the frustum bound (or, with ``ground`` = camera height, the ground plane's
    pages, :func:`ground_pages`) overflows ``pool`` pages at the 0.85 load factor, and the extra bias.

    The extra bias is the smallest non-negative one (to 1/16 octave, bisection; pages fall
    monotonically with bias) whose page bound fits 0.85·pool for the worst light direction;
    ``inf`` when none up to the model's bias limit does (the coarse pages alone may exceed a
    tiny pool).
    The engine's own dynamic-resolution stepping was not read; this is the model's answer.
    """
    if not (float(pool) >= 1 and float(pool).is_integer()):
        raise ValueError(f"pool (physical pages) must be a whole number >= 1, got {pool!r}")
    budget = LOAD_FACTOR * pool
    lights = geometry.lights(light)

    def per_light(clip: Clipmap, lv: Array) -> Array:
        return pages(clip, near, far, lv) if ground is None else ground_pages(clip, ground, far, lv)

    def biased(extra: float) -> Clipmap:
        return dataclasses.replace(c, bias=min(c.bias + extra, BIAS_RANGE[1]))

    top = BIAS_RANGE[1] - c.bias  # the model's largest bias

    def bisect(lv: Array) -> float:
        if per_light(biased(top), lv).max() > budget:
            return float("inf")  # no bias fits: the coarse pages and one page per level exceed the pool
        lo, hi = 0.0, top
        while hi - lo > 1 / 16:
            mid = (lo + hi) / 2
            lo, hi = (lo, mid) if per_light(biased(mid), lv).max() <= budget else (mid, hi)
        return hi

    first = per_light(c, lights)
    need = float(first.max())
    extra = 0.0
    if need > budget:
        # Bisect on the heaviest directions only: an infeasible bias for them is infeasible for
        # all; the answer is then verified on every direction (else bisect on all of them).
        heavy = lights[first >= 0.5 * need]
        extra = bisect(heavy)
        if np.isfinite(extra) and per_light(biased(extra), lights).max() > budget:
            extra = bisect(lights)
    return {"pages": need, "budget": budget, "overflow": need > budget, "extra_bias": extra}


def ground_area(rho: ArrayLike, height: float, fov: float, aspect: float = 1.0) -> Array:
    """Visible ground area within horizontal distance ρ [scene units²], closed form.

    Camera at ``height`` above a plane, looking horizontally, vertical half-angle θ_y
    (``fov``/2) and tan θ_x = ``aspect``·tan θ_y: a ground point (x, −h, z) is in the image
    when h ≤ z tanθ_y and |x| ≤ z tanθ_x, so the plane is seen from z₀ = h/tanθ_y on, inside
    the wedge of half-angle φ = atan(tanθ_x).  Then A(ρ) = 0 for ρ ≤ z₀;
    ρ² acos(z₀/ρ) − z₀√(ρ² − z₀²) (a circular segment, inside the wedge while the chord
    √(ρ² − z₀²) ≤ z₀ tanθ_x) for z₀ < ρ ≤ z₀/cos φ; φρ² − z₀² tanθ_x (the wedge minus its
    unseen triangle) beyond.  φ is computed as θ_y + atan((tanθ_x − tanθ_y)/(1 + tanθ_x tanθ_y)),
    which is θ_y exactly at aspect 1 (the square image's θ, bit for bit).  Derived here;
    tested against a Monte Carlo count.

    Example
    -------
    >>> round(float(ground_area(10.0, 1.0, 90.0)), 4)  # θ = 45°: z₀ = 1, wedge π/4·100 − 1
    77.5398
    """
    r = np.asarray(check.as_float_array(rho, "rho"), float)
    h = float(check.positive(height, "height"))
    v = View(1.0, 2.0, fov, check.scalar(aspect, "aspect"))  # the angles only: near and far do not enter
    th, ty, tx = float(v.theta), float(v.tan_theta), float(v.tan_theta_x)
    with np.errstate(over="ignore", invalid="ignore"):
        delta = float(np.arctan((tx - ty) / (1 + tx * ty)))  # atan(tx) − atan(ty), 0 at aspect 1
    phi = th + delta if np.isfinite(delta) else float(np.arctan(tx))  # (tan θ_x overflowing: φ = π/2)
    z0 = np.float64(h) / ty  # numpy's float: an enormous height overflows to inf, as numpy does, not OverflowError
    with np.errstate(invalid="ignore"):
        seg = r**2 * np.arccos(np.clip(z0 / np.maximum(r, z0), -1, 1)) - z0 * np.sqrt(np.maximum(r**2 - z0**2, 0))
    wedge = phi * r**2 - z0**2 * tx
    return np.where(r <= z0, 0.0, np.where(r <= z0 / np.cos(phi), seg, wedge))


def ground_pages(c: Clipmap, height: float, far: float, light: str | ArrayLike = "overhead") -> Array:
    """Pages a flat ground needs per light direction ``(N,)``: an area estimate in closed form.

    Receivers on the ground at camera distance d_c = √(h² + ρ²) use level L (:func:`level`);
    the ground between the level's distance bounds, seen within ``far``, has area
    ΔA (:func:`ground_area`) and projects onto the light's image plane with area
    ΔA·|l_y| (l the unit vector towards the light, y up); divided by the page area (128 t_L)²;
    plus the coarse pages (:func:`coarse_pages`).  Partial pages at the borders and the
    marking's dilation are not counted, so this is the area's worth of pages, not an upper
    bound.  Lights below the horizon give the coarse pages only.
    """
    h = float(check.positive(height, "height"))
    f = float(check.positive(far, "far"))
    lv = geometry.lights(light)
    scale = CM_PER_UNIT[c.unit.lower()]
    levels = np.arange(c.first, c.last + 1)
    d_lo = np.where(levels == c.first, 0.0, 2.0 ** (levels - c.lod_bias)) / scale
    d_hi = np.where(levels == c.last, 2.0 ** (c.last + 1), 2.0 ** (levels + 1 - c.lod_bias)) / scale
    d_lo, d_hi = np.minimum(d_lo, f), np.minimum(d_hi, f)
    rho = lambda d: np.sqrt(np.maximum((d - h) * (d + h), 0.0))  # noqa: E731  (d**2 - h**2 overflowed for a huge h)
    area = ground_area(rho(d_hi), h, c.fov, c.aspect) - ground_area(rho(d_lo), h, c.fov, c.aspect)  # (L,)
    page = PAGE * texel(c, levels)
    cos_l = np.clip(lv[:, 1] / np.linalg.norm(lv, axis=-1), 0.0, None)  # projected area factor
    return cos_l * (area / page**2).sum() + coarse_pages(c)
