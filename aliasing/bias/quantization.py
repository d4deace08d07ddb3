"""Depth quantization: the bias a stored depth's rounding adds, for 16-, 24- and 32-bit depth buffers.

The map stores depth over the light's depth range R [world units] (its near-to-far extent).
Fixed-point depth (16- and 24-bit UNORM) rounds to the nearest of 2ⁿ − 1 steps: an error of
at most R/(2·(2ⁿ − 1)).  32-bit floating-point depth in [0, 1] has a spacing of at most 2⁻²⁴
(the binade [½, 1)), rounded to nearest: at most R·2⁻²⁵.  Add this to the geometric minimum
of :func:`aliasing.bias.plane_bias` (the two errors add in the worst case).

Example
-------
>>> [f"{quantization_bias(100.0, b):.3g}" for b in (16, 24, 32)]
['0.000763', '2.98e-06', '2.98e-06']
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check

#: Depth-buffer formats: bits → kind.
FORMATS = {16: "unorm", 24: "unorm", 32: "float"}


@check.public
def quantization_bias(depth_range: ArrayLike, bits: int = 24) -> float | NDArray[np.float64]:
    """Largest rounding error of a stored depth [world units] over a light depth range ``depth_range``.

    Parameters
    ----------
    depth_range : array_like
        R, the light's near-to-far depth range [world units], > 0.
    bits : int
        16 or 24 (fixed point) or 32 (float).
    """
    r = check.as_float_array(depth_range, "depth_range")
    if not np.isfinite(r).all() or (r <= 0).any():
        raise ValueError(f"depth_range must be a finite depth range > 0 [world units], got {check._show(r)}")
    if bits not in FORMATS or isinstance(bits, bool):
        raise ValueError(f"bits must be one of 16, 24 (fixed point) or 32 (float), got {check._repr(bits)}")
    step = r / (2.0 * (2.0**bits - 1.0)) if FORMATS[bits] == "unorm" else r * 2.0**-25
    return float(step) if step.ndim == 0 else step
