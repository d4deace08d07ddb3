"""The light-space bounds of an SDSM partition as Intel's sample sizes them.

Shared by the SDSM partitions (:mod:`aliasing.engines.sdsm`) and the stable fits that take
the sample's border, dilation and quantisation as options
(:func:`aliasing.engines.stable.evaluate`).

Example
-------
>>> round(float(sample_bounds(10.0, 100.0, dilation=DILATION_TEXELS / 1024)), 4)   # 10 texels of 1024 on each side
10.1992
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check

Array = NDArray[np.float64]

DILATION_TEXELS = 10.0  # SDSMPartitions.cpp constructor: mDilationFactor = 10 / shadowTextureDim
EDGE_SOFTENING_AMOUNT = 0.02  # main.cpp: edgeSofteningAmount [world units], used only with edgeSoftening (default 0)


def sample_bounds(width: ArrayLike, full: ArrayLike, *, border: float = 0.0, dilation: float = 0.0, quantize: bool = False) -> Array:
    """Map side [world units] of an SDSM partition from its bounds' side, as Intel's sample sizes it.

    Intel SDSM sample (2012), ``SDSMPartitions.hlsl`` ``ComputePartitionDataFromBounds``
    (copies in the index), in the light's texture space of side ``full`` = L (the light
    projection over the whole view; the sample's ``App.cpp`` builds it from the frustum
    extents, or from the scene's box when quantising):

    1. border: the bounds grow by B on each side (``mLightSpaceBorder``; the sample's
       edge-softening blur, ``edgeSofteningAmount`` world units, 0 with edge softening
       off, its default): w + 2B;
    2. dilation δ (``mDilationFactor``, 10/R texels in ``SDSMPartitions.cpp``): the scale
       is multiplied by (1 − 2δ), so the side becomes W = (w + 2B)/(1 − 2δ);
    3. quantisation (``quantizePartitions``, default off): the scale L/W is rounded *down*
       to a power of two, at least 1: W_q = L / max(1, 2^⌊log2(L/W)⌋), so
       W ≤ W_q < 2W while W ≤ L (the partition grows to the next power-of-two fraction of
       the light space); the bias is then floored to a texel, which the dilation covers.

    The clamp to ``mMaxScale`` (only with edge softening) is not modelled.  Each step is
    non-decreasing in w, so applied to the slice's box (a superset of the samples') the
    result bounds the sample's map side.

    Parameters
    ----------
    width : array_like
        Side of the partition's bounds [world units], > 0.
    full : array_like
        Side L of the light's whole texture space [world units], broadcast with ``width``.
    border : float
        B [world units], ≥ 0.
    dilation : float
        δ, fraction of the map per side, in [0, 0.5).
    quantize : bool
        Round the scale down to a power of two.

    Example
    -------
    >>> sample_bounds([3.0, 10.0], 100.0, dilation=0.0, quantize=True).tolist()
    [3.125, 12.5]
    """
    w = check.positive(width, "width")
    L = check.positive(full, "full")
    b = float(check.closed_range(border, "border", 0.0, np.inf, " world units"))
    d = float(check.as_float_array(dilation, "dilation"))
    if not 0.0 <= d < 0.5:
        raise ValueError(f"dilation (fraction of the map per side) must be in [0, 0.5), got {d:g}")
    side = (w + 2 * b) / (1 - 2 * d)  # scale = (1 − 2δ)/(w + 2B)
    if quantize:
        side = L / np.maximum(1.0, 2.0 ** np.floor(np.log2(L / side)))  # scale rounded down to 2^n ≥ 1
    return np.asarray(side, float)
