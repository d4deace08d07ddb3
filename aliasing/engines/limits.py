"""The floors every scheme is measured against: resolution-matched and exact sampling.

``matched``
    Resolution-matched shadow maps (Lefohn et al. 2007) and adaptive shadow maps (Fernando
    et al. 2001) give each pixel a power-of-two level of texel size at most its footprint:
    t = 2^floor(log2 w), so m = t/w = 2^(−φ) with φ = frac(log2 w) ∈ [0, 1), m ∈ (1/2, 1].
    Texels per pixel 1/m² = 4^φ ∈ [1, 4); if φ is uniform over the pixels (log-uniform
    footprints, the model's assumption), the mean is ∫₀¹ 4^φ dφ = 3/ln 4 ≈ 2.164 (derived in
    :mod:`aliasing.symbolic.engines`).  Its critical storage S̄ (texels × m² per pixel) is 1.
``exact``
    The irregular z-buffer (Aila and Laine 2004; Johnson et al. 2005) and ray-traced
    shadows sample at the pixels themselves: m = 1, one sample per pixel, S̄ = 1.

Example
-------
>>> round(MATCHED_TEXELS_PER_PIXEL, 4)
2.164
"""

from __future__ import annotations

import math

from .. import _validation as check
from ..view import check_aspect

MATCHED_TEXELS_PER_PIXEL = 3 / math.log(4)  # ∫₀¹ 4^φ dφ
LIMITS = {
    "matched": {"max_error": 1.0, "m_axis_min": 0.5, "m_axis_max": 1.0, "texels_per_pixel": MATCHED_TEXELS_PER_PIXEL, "S_bar": 1.0},
    "exact": {"max_error": 1.0, "m_axis_min": 1.0, "m_axis_max": 1.0, "texels_per_pixel": 1.0, "S_bar": 1.0},
}


def row(name: str, image_res: int, aspect: float = 1.0) -> dict[str, float | str]:
    """The comparison row of a limit for an image ``image_res`` pixels wide and ``image_res/aspect`` high.

    ``aspect`` (width/height, default 1: ``image_res`` pixels per side) scales the pixel count
    and so the storage; the errors and S̄ (per pixel, per image area) do not change.

    Example
    -------
    >>> row("exact", 100)["storage_texels"]
    10000.0
    """
    if name not in LIMITS:
        raise ValueError(f"unknown limit {name!r}{check.did_you_mean(name, LIMITS)}; choose one of: {', '.join(LIMITS)}")
    lim = LIMITS[name]
    return {
        "scheme": name,
        "max_error": lim["max_error"],
        "median_error": lim["max_error"],
        "m_axis_min": lim["m_axis_min"],
        "m_axis_max": lim["m_axis_max"],
        "storage_texels": float(lim["texels_per_pixel"] * image_res**2) / float(check_aspect(aspect)),  # W × W/aspect pixels
        "S_bar": lim["S_bar"],
    }
