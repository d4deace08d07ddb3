"""The filter's reach and the cascade seams: PCF footprints, texel steps, blend bands, filter biases.

Derived in :mod:`aliasing.symbolic.bias` (``bias.pcf_footprint``, ``bias.blend_band``,
``bias.pcf``, ``bias.receiver_plane``):

* a k×k PCF kernel covers k texels, k·w world units, k·w/p pixels where a pixel is p world
  units wide (:func:`pcf_footprint`, :func:`pixel_size`);
* across a cascade boundary the texel grows by the step s = w_{i+1}/w_i, both maps taken at the
  boundary (:func:`seam_step`): a kernel fixed in texels jumps in width by the same factor;
* blending the two cascades' filtered results linearly over N pixels keeps the blur width's
  change per pixel at most a fraction f of the narrower width when N ≥ |s − 1|/(f·min(1, s))
  (:func:`blend_band`; (s − 1)/f for the usual s ≥ 1), whatever k;
* the two engine rules for the kernel (:func:`kernel_rules`): fixed in texels (its world width
  k·w_i grows with each cascade) or constant in world units R (R/w_i texels, fewer each cascade);
* the bias the filter needs: k×k PCF needs k times the nearest-lookup bias, receiver-plane depth
  bias needs the nearest-lookup bias whatever k (:func:`filter_bias`).

:func:`filter_rows` turns :func:`aliasing.bias.cascades.cascade_bias` rows into the per-cascade
filter table of ``aliasing bias --filter``.

Example
-------
>>> round(pcf_footprint(3, 0.01, 0.005), 6)      # 3 texels of 1 cm under 5 mm pixels
6.0
>>> round(blend_band(2.0, 0.1), 6)              # the texel doubles: a 10-pixel band
10.0
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from ..view import View
from . import presets as _presets
from .plane import PlaneBias, plane_bias

Array = NDArray[np.float64]


def _out(arr: Array) -> float | Array:
    return float(arr) if arr.ndim == 0 else arr


def _positive(value: ArrayLike, name: str, what: str) -> Array:
    arr = check.as_float_array(value, name)
    if not np.isfinite(arr).all() or (arr <= 0).any():
        raise ValueError(f"{name} must be finite and > 0 ({what}), got {check._show(arr)}")
    return arr


def _kernel(k: ArrayLike) -> Array:
    arr = check.as_float_array(k, "k")
    if not np.isfinite(arr).all() or (arr < 1).any() or (arr != np.round(arr)).any():
        raise ValueError(f"k must be a whole kernel width >= 1 [texels], got {check._show(arr)}")
    return arr


@check.public
def pixel_size(depth: ArrayLike, fov: ArrayLike, image: int) -> float | Array:
    """Width [world units] of one pixel across the view at view depth ``depth``: 2·z·tan(fov/2)/N.

    Parameters
    ----------
    depth : array_like
        View depth z [world units], > 0.
    fov : array_like
        Full field of view [deg], in (0, 180).
    image : int
        N, pixels across the view.

    Example
    -------
    >>> round(pixel_size(10.0, 90.0, 1000), 6)
    0.02
    """
    z = _positive(depth, "depth", "view depth [world units]")
    n = check.whole(image, "image", 1, 1 << 16, " (pixels across the view)")
    tan_half = View(1.0, 2.0, fov).tan_theta
    return _out(2.0 * z * tan_half / n)


@check.public
def pcf_footprint(k: ArrayLike, texel: ArrayLike, pixel: ArrayLike) -> float | Array:
    """Pixels covered by a k×k PCF kernel: k·w/p (``bias.pcf_footprint``).

    Parameters
    ----------
    k : array_like
        Kernel width [texels], a whole number >= 1.
    texel : array_like
        w, the texel width at the receiver [world units], > 0.
    pixel : array_like
        p, a pixel's width at the receiver [world units], > 0 (:func:`pixel_size`).

    Example
    -------
    >>> pcf_footprint([1, 5], 0.02, 0.01).tolist()
    [2.0, 10.0]
    """
    kk = _kernel(k)
    w = _positive(texel, "texel", "texel width [world units]")
    p = _positive(pixel, "pixel", "pixel width [world units]")
    return _out(kk * w / p)  # eq. bias.pcf_footprint


@check.public
def seam_step(texel_here: ArrayLike, texel_there: ArrayLike) -> float | Array:
    """The texel's (and a texel-fixed kernel's blur width's) growth across a cascade boundary: w_{i+1}/w_i.

    Both texels are those of the two maps at the same boundary point [world units], > 0.

    Example
    -------
    >>> seam_step(0.01, 0.025)
    2.5
    """
    a = _positive(texel_here, "texel_here", "texel of the nearer cascade at the boundary [world units]")
    b = _positive(texel_there, "texel_there", "texel of the farther cascade at the boundary [world units]")
    return _out(b / a)


@check.public
def blend_band(step: ArrayLike, fraction: ArrayLike = 0.1) -> float | Array:
    """Pixels over which two cascades must be blended to hide their seam (``bias.blend_band``).

    Blending the filtered results with a weight ramping linearly over N pixels filters with the
    mixture of the two kernels, whose mean radius ramps linearly from one cascade's to the other's:
    the blur width changes by |s − 1|·W_i/N per pixel.  At most ``fraction`` of the narrower width
    min(W_i, s·W_i) per pixel needs N ≥ |s − 1|/(f·min(1, s)); (s − 1)/f for s ≥ 1.

    Parameters
    ----------
    step : array_like
        s, the texel step across the boundary (:func:`seam_step`), > 0.
    fraction : array_like
        f, the allowed change of the blur width per pixel, a fraction of the narrower width, in (0, 1].

    Returns
    -------
    float or ndarray
        N [pixels]; 0 where s = 1 (no seam).

    Example
    -------
    >>> blend_band([1.0, 1.5, 0.5], 0.25).tolist()
    [0.0, 2.0, 4.0]
    """
    s = _positive(step, "step", "texel step across the boundary, w_(i+1)/w_i")
    f = check.as_float_array(fraction, "fraction")
    if not np.isfinite(f).all() or ((f <= 0) | (f > 1)).any():
        raise ValueError(f"fraction must be in (0, 1] (change of the blur width per pixel), got {check._show(f)}")
    return _out(np.abs(s - 1.0) / (f * np.minimum(1.0, s)))  # eq. bias.blend_band


class KernelRules(NamedTuple):
    """A kernel fixed in texels against one constant in world units, per cascade."""

    world: float | Array  #: world width [world units] of a kernel of k texels: k·w_i
    texels: float | Array  #: texels [texels] spanned by a kernel R world units wide: R/w_i


@check.public
def kernel_rules(texel: ArrayLike, k: ArrayLike, radius: ArrayLike) -> KernelRules:
    """Both engine rules for the filter per cascade: fixed in texels, and constant in world space.

    Parameters
    ----------
    texel : array_like
        w_i, each cascade's texel [world units], > 0.
    k : array_like
        Kernel width of the texel-fixed rule [texels], whole >= 1.
    radius : array_like
        R, the world width of the world-constant rule [world units], > 0.

    Example
    -------
    >>> r = kernel_rules([0.01, 0.02, 0.04], 3, 0.03)
    >>> r.world.round(6).tolist(), r.texels.round(6).tolist()
    ([0.03, 0.06, 0.12], [3.0, 1.5, 0.75])
    """
    w = _positive(texel, "texel", "texel width [world units]")
    kk = _kernel(k)
    r = _positive(radius, "radius", "world width of the kernel [world units]")
    return KernelRules(_out(kk * w), _out(r / w))


@check.public
def filter_bias(texel: ArrayLike, angle: ArrayLike, azimuth: ArrayLike = 0.0, k: int = 3) -> tuple[PlaneBias, PlaneBias]:
    """Minimal biases of a k×k PCF lookup: (plain PCF, with receiver-plane depth bias).

    :func:`aliasing.bias.plane_bias` with ``pcf<k>`` (``bias.pcf``: k/2·w·tan θ·(|cos φ| + |sin φ|))
    and with ``receiver-plane`` (``bias.receiver_plane``: the nearest-lookup value, whatever k).

    Example
    -------
    >>> plain, rp = filter_bias(0.1, 45.0, 0.0, k=5)
    >>> round(plain.depth, 6), round(rp.depth, 6)
    (0.25, 0.05)
    """
    kk = check.whole(k, "k", 1, 15, " (kernel width [texels])")
    return plane_bias(texel, angle, azimuth, f"pcf{kk}"), plane_bias(texel, angle, azimuth, "receiver-plane")


def filter_rows(rows: list[dict], fov: float, image: int = 1080, fraction: float = 0.1, radius: float | None = None) -> list[dict]:
    """Per cascade of :func:`aliasing.bias.cascades.cascade_bias` rows: the filter's reach and its seams.

    Columns: ``k`` (the preset's kernel), ``texel`` (the larger side at the cascade's middle),
    ``pcf_world`` and ``pcf_px`` (the texel-fixed kernel in world units and pixels),
    ``world_texels`` (texels spanned by a kernel constant in world units, ``radius``; default the
    first cascade's k·w), ``step`` (the texel step at the far boundary), ``band_px`` and
    ``band_world`` (the blend band that keeps the blur width's change per pixel within
    ``fraction``, in pixels and in world units across the view at the boundary), and the minimal
    depth biases of the plain PCF and of the receiver-plane lookup on the ground (``need_pcf``,
    ``need_rp``: ``need_depth`` and ``need_depth``/k, the ratio ``bias.pcf``/``bias.receiver_plane``).

    Example
    -------
    >>> from aliasing.bias.cascades import cascade_bias
    >>> rows = filter_rows(cascade_bias(1.0, 100.0, 60.0, "gamma:60", "bevy", k=3, resolution=1024), 60.0)
    >>> [r["k"] for r in rows], bool(rows[0]["world_texels"] == 5.0), bool(rows[1]["world_texels"] < 5.0)
    ([5, 5, 5], True, True)
    """
    if not rows:
        raise ValueError("rows must hold at least one cascade row (from cascade_bias)")
    blend_band(1.0, fraction)  # validates fraction, whether or not a boundary follows
    if radius is not None:
        _positive(radius, "radius", "world width of the kernel [world units]")
    out = []
    ref = {}
    for r in rows:
        k = _presets.get(r["preset"]).pcf
        w = max(r["texel_s"], r["texel_t"])
        ref.setdefault(r["preset"], k * w if radius is None else float(radius))
        rules = kernel_rules(w, k, ref[r["preset"]])
        last = not np.isfinite(r["step"])
        band = float("nan") if last else float(blend_band(r["step"], fraction))
        out.append({
            "preset": r["preset"], "cascade": r["cascade"], "near": r["near"], "far": r["far"], "k": k, "texel": w,
            "pcf_world": float(rules.world), "pcf_px": r["pcf_px"], "world_texels": float(rules.texels),
            "step": r["step"], "band_px": band,
            "band_world": float("nan") if last else band * float(pixel_size(r["far"], fov, image)),
            "need_pcf": r["need_depth"], "need_rp": r["need_depth"] / k,
        })
    return out
