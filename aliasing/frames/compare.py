"""Measured against predicted: shadow mask, acne, peter-panning gap and texel footprint of one frame.

The same measures are taken of the engine's shadow factor and of the toolkit's predicted one,
on the same pixels (those the engine drew, at the positions and normals it computed):

``shadow_agreement`` (measured only)
    The fraction of drawn pixels, farther than 1 px from a shadow edge of either mask (the
    3 × 3 neighbourhood holds one value in both), where the engine's mask (factor < ½) equals
    the predicted one.
``acne``
    The fraction of lit receiver pixels (facing the sun by cos > :data:`MIN_COS` and lit
    in the exact reference) that are shaded as shadowed (factor < ½).
``lost_shadow``
    The other side of the bias: the fraction of the pixels facing the sun (cos >
    :data:`MIN_COS`) and in the exact reference's shadow that are shaded lit (factor ≥ ½).
    Surfaces facing away from the sun are dark whatever their factor, and left out.
    Filtering alone loses the edge pixels of thin shadows; a bias or normal offset that moves
    the casters or the lookups loses more.
``gap_px``
    Peter-panning at the feet of boxes: ground pixels in the exact reference's shadow that
    are shaded lit (factor ≥ ½) within :data:`GAP_REACH` px of a non-ground pixel, over the
    ground pixels in shadow that touch one (the contact line's length in pixels): the lit
    gap's mean width [px].  None for a scene without a ground.
``texels_per_pixel``
    Per cascade: the eye pixel's side at the cascade's first depth over the map texel's
    larger side (2 d tan(fov/2) / H over side / R), from the engine's light matrices and
    breaks (measured) and from the toolkit's split and fit (predicted).

Example
-------
>>> m = np.array([[True, True, False, False, False]] * 3)
>>> away_from_edges(m, m).astype(int).tolist()[1]
[1, 0, 0, 1, 1]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage
from ..view import tan_theta

Array = NDArray[np.float64]
MIN_COS = 0.05
GAP_REACH = 8


def away_from_edges(a: NDArray[np.bool_], b: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Pixels whose 3 × 3 neighbourhood (clipped at the image border) holds one value in both masks ``a`` and ``b``."""
    a, b = np.asarray(a, bool), np.asarray(b, bool)
    if a.shape != b.shape or a.ndim != 2:
        raise ValueError(f"a and b must be 2-d masks of one shape, got {a.shape} and {b.shape}")
    same = np.ones(a.shape, bool)
    for m in (a, b):
        same &= ndimage.maximum_filter(m, 3, mode="nearest") == ndimage.minimum_filter(m, 3, mode="nearest")
    return same


def agreement(measured: Array, predicted: Array, drawn: NDArray[np.bool_]) -> float:
    """Fraction of drawn pixels away from edges where the masks (factor < ½) agree (NaN when none)."""
    mm, pm = (np.nan_to_num(measured, nan=1.0) < 0.5), (np.nan_to_num(predicted, nan=1.0) < 0.5)
    # pixels not drawn count as lit in both (their edges with drawn shadow are excluded)
    keep = away_from_edges(mm, pm) & drawn & ndimage.binary_erosion(drawn, np.ones((3, 3)), border_value=1)
    return float(np.mean(mm[keep] == pm[keep])) if keep.any() else float("nan")


def acne(factor: Array, receivers: NDArray[np.bool_]) -> float:
    """Fraction of the lit ``receivers`` shaded as shadowed (factor < ½); NaN when there are none."""
    return float(np.mean(factor[receivers] < 0.5)) if receivers.any() else float("nan")


def lost_shadow(factor: Array, ref_lit: NDArray[np.bool_], facing: NDArray[np.bool_]) -> float:
    """Fraction of the ``facing`` pixels in the exact shadow (not ``ref_lit``) shaded lit (factor ≥ ½); NaN when there are none.

    Parameters
    ----------
    factor : array_like, shape (H, W)
        The shadow factor per pixel, 0 (shadowed) to 1 (lit) [1].
    ref_lit, facing : array_like of bool, shape (H, W)
        The exact reference's lit pixels, and the drawn pixels facing the sun (cos > :data:`MIN_COS`).

    Returns
    -------
    float
        [fraction of the exactly shadowed pixels].

    Examples
    --------
    >>> f = np.array([[1.0, 0.0, 0.7], [0.0, 0.0, 1.0]])
    >>> ref = np.array([[True, False, False], [False, False, True]])
    >>> lost_shadow(f, ref, np.ones((2, 3), bool))             # one of the four shadowed pixels is shaded lit
    0.25
    """
    factor, ref_lit, facing = np.asarray(factor, float), np.asarray(ref_lit, bool), np.asarray(facing, bool)
    if not factor.shape == ref_lit.shape == facing.shape:
        raise ValueError(f"factor, ref_lit and facing must have one shape, got {factor.shape}, {ref_lit.shape} and {facing.shape}")
    shadowed = facing & ~ref_lit
    return float(np.mean(np.nan_to_num(factor[shadowed], nan=1.0) >= 0.5)) if shadowed.any() else float("nan")


def gap(factor: Array, ref_lit: NDArray[np.bool_], ground: NDArray[np.bool_], drawn: NDArray[np.bool_]) -> float | None:
    """Mean lit gap [px] at the feet of what stands on the ground (module docstring); None without ground pixels."""
    if not ground.any():
        return None
    other = drawn & ~ground
    shadowed = ground & ~ref_lit
    contact = shadowed & ndimage.binary_dilation(other, structure=ndimage.generate_binary_structure(2, 1))
    if not contact.any():
        return None
    near = ndimage.binary_dilation(other, iterations=GAP_REACH)
    lit_gap = shadowed & near & (factor >= 0.5)
    return float(lit_gap.sum() / contact.sum())


def texels_per_pixel(starts: Array, sides: Array, resolution: Array, fov: float, height: int) -> list[float]:
    """Per cascade: (2 d tan(fov/2) / height) / (side / resolution) at the cascade's first depth ``d`` [world units]."""
    starts, sides, resolution = (np.asarray(v, float) for v in (starts, sides, resolution))
    pixel = 2 * starts * tan_theta(fov) / height
    return (pixel / (sides / resolution)).tolist()
