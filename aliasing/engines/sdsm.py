"""Sample distribution shadow maps: partitions of the occupied depth range.

Lauritzen, Salvi and Lefohn, "Sample Distribution Shadow Maps", I3D 2011, and Intel's
sample (2012; ``LogPartitions.hlsl`` ``LogPartitionFromRange``,
``AdaptiveLogPartitions.hlsl``, ``KMeansPartitions.hlsl``, read from copies in the index):

* :func:`log_partitions`: C_i = z_min (z_max/z_min)^(i/k) on the occupied range;
* :func:`adaptive_log`: from a histogram, each partition ends at the log split of the
  remaining range [start, z_max] into the remaining partitions, pushed out to the next
  non-empty bin (``ComputeAdaptiveLogPartitions``);
* :func:`kmeans`: weighted 1-D Lloyd iterations on the histogram, centroids started at
  equal-weight quantiles i/(k + 1), split at the mid-points (``ComputeKMeansPartitions``).

Histograms are given as bin edges (depths, B + 1) and counts (B); a bin stands for its
lower edge, as the sample's ``BinToZ`` does.  Each partition's depth range is that of its
populated bins; its light-space bound is the frustum slice's box (a superset of the
samples' box, hence an upper bound on error and storage).  The sample's light-space
border, dilation and power-of-two quantisation are :func:`aliasing.engines.sample.sample_bounds` (options
``border``, ``dilation``, ``quantize`` of :func:`aliasing.engines.stable.evaluate`);
histograms measured by the rasterizer are :func:`aliasing.engines.validate.eye_histogram`.

Example
-------
>>> log_partitions(1.0, 1000.0, 10.0, 100.0, 2).tolist()
[10.0, 31.622776601683796, 100.0]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from . import stable
from .sample import DILATION_TEXELS, EDGE_SOFTENING_AMOUNT, sample_bounds  # noqa: F401  (re-exported)

Array = NDArray[np.float64]


def occupied(near: float, far: float, z_min: float, z_max: float) -> tuple[float, float]:
    """Validate an occupied range near ≤ z_min < z_max ≤ far [world units]."""
    n, f = (float(x) for x in check.frustum(near, far))
    lo = float(check.as_float_array(z_min, "z_min"))
    hi = float(check.as_float_array(z_max, "z_max"))
    if not (n <= lo < hi <= f):
        raise ValueError(f"occupied range [z_min, z_max] must be non-empty and inside [near, far] = [{n:g}, {f:g}], got [{lo:g}, {hi:g}]")
    return lo, hi


def log_partitions(near: float, far: float, z_min: float, z_max: float, k: int) -> Array:
    """k + 1 log split distances over the occupied range (Lauritzen et al. 2011, §4.1)."""
    lo, hi = occupied(near, far, z_min, z_max)
    if isinstance(k, bool) or int(k) != k or k < 1:
        raise ValueError(f"k must be a whole number >= 1 (number of partitions), got {k!r}")
    edges = lo * (hi / lo) ** (np.arange(int(k) + 1) / int(k))
    edges[-1] = hi
    return edges


def histogram(edges: ArrayLike, counts: ArrayLike) -> tuple[Array, Array]:
    """Validate a depth histogram: increasing positive edges (B + 1), counts (B) ≥ 0 with samples."""
    e = check.as_float_array(edges, "edges").ravel()
    c = check.as_float_array(counts, "counts").ravel()
    if e.size < 2 or np.any(np.diff(e) <= 0) or e[0] <= 0:
        raise ValueError("histogram edges must be at least two increasing positive depths")
    if c.size != e.size - 1:
        raise ValueError(f"histogram counts must have one value per bin ({e.size - 1}), got {c.size}")
    if np.any(c < 0) or c.sum() <= 0:
        raise ValueError("histogram counts must be >= 0 with at least one sample (the histogram has no samples)")
    return e, c


def _k(k: int) -> int:
    if isinstance(k, bool) or int(k) != k or k < 1:
        raise ValueError(f"k must be a whole number >= 1 (number of partitions), got {k!r}")
    return int(k)


def _ranges(e: Array, c: Array, split_bins: list[int]) -> tuple[Array, Array]:
    """Each partition's populated depth range [lower edge of its first, upper edge of its last populated bin]."""
    lo, hi = [], []
    for start, stop in zip(split_bins[:-1], split_bins[1:]):
        filled = np.nonzero(c[start:stop] > 0)[0]
        if filled.size:  # empty partitions get no map
            lo.append(e[start + filled[0]])
            hi.append(e[start + filled[-1] + 1])
    return np.array(lo), np.array(hi)


def adaptive_log(edges: ArrayLike, counts: ArrayLike, k: int) -> tuple[Array, Array]:
    """(near_i, far_i) of the adaptive-log partitions (Intel SDSM sample, AdaptiveLogPartitions.hlsl).

    Example
    -------
    >>> e = np.geomspace(1.0, 1024.0, 11)  # one bin per octave
    >>> lo, hi = adaptive_log(e, [0, 0, 5, 5, 0, 0, 0, 0, 5, 5], 2)
    >>> lo.tolist(), hi.tolist()
    ([4.0, 256.0], [16.0, 1024.0])
    """
    e, c = histogram(edges, counts)
    kk = _k(k)
    filled = np.nonzero(c > 0)[0]
    first, max_bin = int(filled[0]), int(filled[-1]) + 1
    max_z, bins, start = e[max_bin], [first], first
    for i in range(kk - 1):
        target = e[start] * (max_z / e[start]) ** (1.0 / (kk - i))  # log split of what remains
        nxt = min(int(np.searchsorted(e, target, side="right")) - 1, len(c))
        later = filled[filled >= nxt]
        nxt = int(later[0]) if later.size else len(c)  # pushed out to a populated bin
        bins.append(nxt)
        start = min(nxt, len(c) - 1)
    bins.append(len(c))
    return _ranges(e, c, bins)


def kmeans(edges: ArrayLike, counts: ArrayLike, k: int, iterations: int = 32) -> tuple[Array, Array]:
    """(near_i, far_i) of k-means partitions (Intel SDSM sample, KMeansPartitions.hlsl).

    ``iterations``: the sample's default ``lloydIterations`` = 32 (``main.cpp``).

    Example
    -------
    >>> e = np.arange(1.0, 12.0)
    >>> lo, hi = kmeans(e, [5, 5, 0, 0, 0, 0, 0, 0, 5, 5], 2)
    >>> lo.tolist(), hi.tolist()
    ([1.0, 9.0], [3.0, 11.0])
    """
    e, c = histogram(edges, counts)
    kk = _k(k)
    z = e[:-1]  # BinToZ: a bin's lower edge
    cum = np.cumsum(c)
    quant = np.arange(1, kk + 1) * cum[-1] / (kk + 1)
    centroids = z[np.minimum(np.searchsorted(cum, quant, side="left"), len(c) - 1)]  # equal-weight start
    for _ in range(int(iterations)):
        mids = (centroids[:-1] + centroids[1:]) / 2
        cell = np.searchsorted(mids, z, side="right")  # bin → nearest centroid's cell
        w = np.bincount(cell, weights=c, minlength=kk)
        zs = np.bincount(cell, weights=c * z, minlength=kk)
        centroids = np.where(w > 0, zs / np.where(w > 0, w, 1), centroids)
    mids = (centroids[:-1] + centroids[1:]) / 2
    split = np.searchsorted(e, mids, side="right") - 1  # ZToBin of the mid-points
    return _ranges(e, c, [0, *np.clip(split, 0, len(c)).tolist(), len(c)])


def occupancy(near: float, far: float, fov: float, light: str | ArrayLike, k: int, fractions: ArrayLike, *, anchor: str = "near") -> list[dict[str, float]]:
    """How S̄ and the maximum error change with the occupied fraction q of [near, far].

    The occupied range is [near, near + q(far − near)] (``anchor="near"``: the scene ends
    before the far plane) or [far − q(far − near), far] (``"far"``: nothing close to the
    eye); k log partitions on it, tight slice boxes (unit resolutions).  Each row: ``q``,
    ``S`` and ``M`` (max over the light directions; M = max over maps of max(M_x, M_z)) and
    their ratios to q = 1.

    With the light overhead the result is closed: each of the k partitions has the depth
    ratio ρ = (z_max/z_min)^(1/k), M_x = ρ (far width 2t·f_i over 2t·n_i) and
    M_z = (ρ − 1)/(2t), so S̄ = k·ρ(ρ − 1)/(2t) (t = tan θ; tested): S̄ falls about as
    (z_max/z_min)^(2/k) and M as (z_max/z_min)^(1/k) with the occupied depth ratio.

    Example
    -------
    >>> rows = occupancy(1.0, 1000.0, 60.0, "overhead", 4, [1.0, 0.1])
    >>> rows[0]["S_ratio"], rows[1]["S_ratio"] < 1.0
    (1.0, True)
    """
    n, f = (float(x) for x in check.frustum(near, far))
    side = check.choice(anchor, "anchor", ("near", "far"))
    qs = check.as_float_array(fractions, "fractions").ravel()
    if qs.size == 0 or np.any((qs <= 0) | (qs > 1)):
        raise ValueError("fractions (occupied fraction of [near, far]) must be in (0, 1]")
    rows = []
    for q in np.concatenate([[1.0], qs]):
        lo, hi = (n, n + q * (f - n)) if side == "near" else (f - q * (f - n), f)
        r = stable.evaluate(log_partitions(n, f, lo, hi, k), lo, hi, fov, light)
        rows.append({"q": float(q), "S": float(r.S.max()), "M": float(np.maximum(r.M_x, r.M_z).max())})
    full = rows.pop(0)
    for row in rows:
        row["S_ratio"], row["M_ratio"] = row["S"] / full["S"], row["M"] / full["M"]
    return rows
