"""Sample distribution shadow maps: partitions of the occupied depth range.

Lauritzen, Salvi and Lefohn, "Sample Distribution Shadow Maps", I3D 2011: the depth
buffer is reduced to the occupied range [z_min, z_max] and split logarithmically
(Intel's sample ``LogPartitions.hlsl``; the sample's source was not stored in the index,
so the split here is the paper's log split, C_i = z_min (z_max/z_min)^(i/k)).  Each
partition's light-space bound is taken analytically as the frustum slice's box (a
superset of the samples' box, hence an upper bound on the error and storage).

Adaptive-log and k-means partitions from a histogram, the sample's border, dilation and
power-of-two quantisation are not implemented (see the report of issue 18).

Example
-------
>>> log_partitions(1.0, 1000.0, 10.0, 100.0, 2).tolist()
[10.0, 31.622776601683796, 100.0]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check

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
