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
``px_per_texel``
    Per cascade: the map texel's larger side over the eye pixel's side at the cascade's first
    depth (side / R over 2 d tan(fov/2) / H), from the engine's light matrices and breaks
    (measured) and from the toolkit's split and fit (predicted): the pixels one texel spans,
    ``check``'s aliasing error in the same direction and unit [px/texel]
    (:data:`aliasing.check.units.ERROR_UNIT`), at the cascade's near end.

Examples
--------
>>> m = np.array([[True, True, False, False, False]] * 3)
>>> away_from_edges(m, m).astype(int).tolist()[1]
[1, 0, 0, 1, 1]
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy import ndimage
from .. import _validation as check
from ..view import tan_theta

Array = NDArray[np.float64]
MIN_COS = 0.05
GAP_REACH = 8


def _same_shape(*named) -> None:
    """Refuse arrays that are not 2-d images of one shape, naming each."""
    shapes = [(n, np.shape(a)) for n, a in named]
    if len(shapes[0][1]) != 2 or any(s != shapes[0][1] for _, s in shapes):
        raise ValueError(f"{', '.join(n for n, _ in shapes)} must be 2-d (H, W) arrays of one shape, got "
                         + ", ".join(f"{n} {s}" for n, s in shapes))


def away_from_edges(a: NDArray[np.bool_], b: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Pixels whose 3 × 3 neighbourhood (clipped at the image border) holds one value in both masks ``a`` and ``b``.

    Parameters
    ----------
    a, b : array_like of bool (H, W)
        Two masks of one image [per pixel: shadowed or not].

    Returns
    -------
    ndarray of bool (H, W)
        True where neither mask changes within 1 px [px].

    Examples
    --------
    >>> a = np.zeros((3, 3), bool); a[0, 0] = True        # one shadowed corner pixel
    >>> away_from_edges(a, np.zeros((3, 3), bool)).astype(int).tolist()
    [[0, 0, 1], [0, 0, 1], [1, 1, 1]]
    """
    a, b = np.asarray(a, bool), np.asarray(b, bool)
    if a.shape != b.shape or a.ndim != 2:
        raise ValueError(f"a and b must be 2-d masks of one shape, got {a.shape} and {b.shape}")
    same = np.ones(a.shape, bool)
    for m in (a, b):
        same &= ndimage.maximum_filter(m, 3, mode="nearest") == ndimage.minimum_filter(m, 3, mode="nearest")
    return same


def agreement(measured: Array, predicted: Array, drawn: NDArray[np.bool_]) -> float:
    """Fraction of drawn pixels away from edges where the masks (factor < ½) agree (NaN when none).

    Parameters
    ----------
    measured, predicted : array_like (H, W)
        Shadow factors [fraction of the sun's light, 0 shadowed … 1 lit]; NaN counts as lit (nothing drawn).
    drawn : array_like of bool (H, W)
        The pixels the engine drew.

    Returns
    -------
    float
        The agreeing fraction [fraction of drawn pixels away from edges, in [0, 1]], NaN when no pixel is kept.

    Examples
    --------
    >>> m = np.zeros((3, 3)); p = np.zeros((3, 3)); p[1, 1] = 1.0    # the centre lit in the prediction only
    >>> agreement(m, m, np.ones((3, 3), bool)), agreement(m, p, np.ones((3, 3), bool))
    (1.0, nan)
    >>> agreement(np.zeros((5, 5)), np.zeros((5, 5)), np.ones((5, 5), bool))   # all shadowed in both
    1.0
    """
    _same_shape(("measured", measured), ("predicted", predicted), ("drawn", drawn))
    mm, pm = (np.nan_to_num(measured, nan=1.0) < 0.5), (np.nan_to_num(predicted, nan=1.0) < 0.5)
    # pixels not drawn count as lit in both (their edges with drawn shadow are excluded)
    keep = away_from_edges(mm, pm) & drawn & ndimage.binary_erosion(drawn, np.ones((3, 3)), border_value=1)
    return float(np.mean(mm[keep] == pm[keep])) if keep.any() else float("nan")


def acne(factor: Array, receivers: NDArray[np.bool_]) -> float:
    """Fraction of the lit ``receivers`` shaded as shadowed (factor < ½); NaN when there are none.

    Parameters
    ----------
    factor : array_like (H, W)
        Shadow factor [fraction of the sun's light, 0 shadowed … 1 lit] (NaN where nothing is drawn).
    receivers : array_like of bool (H, W)
        The lit receiver pixels (facing the sun and lit in the exact reference).

    Returns
    -------
    float
        The acne [fraction of lit receiver pixels, in [0, 1]], NaN without receivers.

    Examples
    --------
    >>> f = np.array([[1.0, 0.2, 1.0], [1.0, 1.0, 0.0], [0.4, 1.0, 1.0]])
    >>> acne(f, np.ones((3, 3), bool))                     # 3 of 9 lit receivers shaded
    0.3333333333333333
    """
    _same_shape(("factor", factor), ("receivers", receivers))
    factor, receivers = np.asarray(factor, float), np.asarray(receivers, bool)
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
    """Mean lit gap [px] at the feet of what stands on the ground (module docstring); None without ground pixels.

    Parameters
    ----------
    factor : array_like (H, W)
        Shadow factor [fraction of the sun's light, 0 shadowed … 1 lit].
    ref_lit : array_like of bool (H, W)
        The exact reference's lit pixels.
    ground, drawn : array_like of bool (H, W)
        The ground's pixels and every drawn pixel.

    Returns
    -------
    float or None
        The lit gap's mean width [px], None without ground pixels in shadow next to a standing object.

    Examples
    --------
    >>> drawn = np.ones((3, 3), bool); ground = drawn.copy(); ground[:, 0] = False   # a wall in column 0
    >>> ref = np.ones((3, 3), bool); ref[:, 1] = False                               # its shadow: column 1
    >>> f = np.ones((3, 3))                                                          # shaded lit: the gap is 1 px wide
    >>> gap(f, ref, ground, drawn), gap(np.where(ref, 1.0, 0.0), ref, ground, drawn)
    (1.0, 0.0)
    """
    _same_shape(("factor", factor), ("ref_lit", ref_lit), ("ground", ground), ("drawn", drawn))
    factor, ref_lit, ground, drawn = np.asarray(factor, float), np.asarray(ref_lit, bool), np.asarray(ground, bool), np.asarray(drawn, bool)
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


def px_per_texel(starts: Array, sides: Array, resolution: Array, fov: float, height: int) -> list[float]:
    """Per cascade: (side / resolution) / (2 d tan(fov/2) / height) at the cascade's first depth ``d`` [world units]:
    the pixels a texel spans [px/texel], ``check``'s aliasing error.

    Parameters
    ----------
    starts : array_like (k,)
        Each cascade's first eye depth d [world units], > 0.
    sides : array_like (k,)
        Each cascade's map side [world units], > 0.
    resolution : array_like (k,)
        Each cascade's map resolution [texels per side], > 0.
    fov : float
        Vertical field of view [deg], in (0, 180).
    height : int
        Image height [px], >= 1.

    Returns
    -------
    list of float
        Per cascade: the texel's side over the eye pixel's [px/texel].

    Examples
    --------
    >>> px_per_texel([1.0, 10.0], [2.0, 20.0], [1024, 1024], 90.0, 512)   # tan 45° = 1: d / 512 over 2 d / 512
    [0.5, 0.5]
    """
    starts, sides, resolution = (np.asarray(check.positive(v, n), float) for v, n in ((starts, "starts"), (sides, "sides"), (resolution, "resolution")))
    if not (starts.ndim == 1 and starts.shape == sides.shape == resolution.shape):
        raise ValueError(f"starts, sides and resolution must be 1-d arrays of one length (one per cascade), got {starts.shape}, {sides.shape}, {resolution.shape}")
    check.fov(fov)
    check.whole(height, "height", 1, what=" [px]")
    starts, sides, resolution = (np.asarray(v, float) for v in (starts, sides, resolution))
    pixel = 2 * starts * tan_theta(fov) / height
    return ((sides / resolution) / pixel).tolist()
