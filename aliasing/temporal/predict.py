"""The shimmer predicted from the texel grids: grid motion × density of shadow edges.

A shadow-map test of a point p depends on the map only through the centre c of the texel
p falls in: the texel stores the surface its centre's light ray meets first, and the test
(:func:`aliasing.raster.draw.shadow_test`) compares p with it.  Write T(p, c) for that
lit/shadowed state.  The world is still, so between two frames p's state can only change
because its centre moved, from c to c′: the grid's motion.

Grid motion
    Per map and frame, :func:`grid_motion` gives the sub-texel phase shift of the grid (its
    corner's move in texels, modulo one) and its scale change (t′/t − 1).  Tight fits move
    with every camera motion; snapped square fits (sphere, diagonal, centroid) keep the
    lattice still under translation and rotation — their side does not depend on the
    view's direction, and their corner jumps by whole texels; a change of field of view
    rescales every fit.  Per point, :func:`displacement` gives Δ = c′ − c [world units].
Edge density
    The state flips when a shadow edge (of T(p, ·), seen from the centres) lies between c
    and c′.  For edges of total length ρ per unit area with orientation density ρ(ψ), the
    expected number of edges a segment Δ crosses is |Δ|·g(φ_Δ), g(φ) = ∫ ρ(ψ)|cos(φ − ψ)| dψ
    (Cauchy–Crofton; for isotropic edges g = 2ρ/π).  :func:`densities` measures g per map
    and direction in frame 0 by moving the grid alone: it draws map k again with its grid
    shifted by sub-texel offsets, which move every point's centre by a known Δ, and divides
    the state changes by Σ|Δ| per direction bin of Δ, separately for each tile of the
    frame-0 image (edges are not spread evenly, and a path may carry part of the points
    out of view).
Prediction
    With λ_p = |Δ_p|·g_k(φ_Δ) edges expected between c and c′ (k the map p uses in the new
    frame), a flip needs an odd number of crossings: for crossings at random (Poisson),
    P(flip of p) = (1 − e^(−2λ_p))/2 ≈ λ_p for small λ.  The predicted shimmer of a frame
    is its mean over the points seen in both frames (:func:`predicted`).

The prediction needs a fixed light frame: under a turning sun the shadows themselves move
on the receivers, so there is no grid motion to predict from (the rate per degree is
measured instead).

Example
-------
>>> import numpy as np
>>> g = np.array([[1.0, 1.0]])          # one density row: one crossing per unit length, both direction bins
>>> d = np.array([[[0.1, 0.0], [0.0, 0.1], [0.0, 0.0]]])   # one frame change, three points
>>> predicted(d, np.array([0, 0, 0]), g).round(6).tolist()   # 2·(1 − e^−0.2)/2 / 3
[0.060423]
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from .fits import Lattices
from .render import MapCache

Array = NDArray[np.float64]

#: Sub-texel grid shifts of the density measurement (each one draws every frame-0 map again).
SHIFTS = 12
#: Direction bins of the density measurement over [0, π) (g(φ + π) = g(φ)).
DIRECTIONS = 8
#: Tiles per side of the frame-0 image over which edge densities are measured apart.
TILES = 4
#: Points a tile needs for a density of its own (fewer: its map's).
MIN_POINTS = 40


def _lattice_and(lat: Lattices, part: object = None) -> NDArray[np.int64] | None:
    check.instance(lat, "lat", Lattices)
    if part is None:
        return None
    p = np.asarray(part)
    if p.dtype.kind not in "iu" or p.ndim != 2 or p.shape[0] != lat.x0.shape[0] or (p.size and (p.min() < -1 or p.max() >= lat.maps)):
        raise ValueError(f"part must be whole map indices in [-1, {lat.maps - 1}] of shape (frames = {lat.x0.shape[0]}, points), got {p.dtype} {p.shape}")
    return p.astype(np.int64)


def _rows(g: object) -> Array:
    a = check.finite(g, "g")
    if a.ndim != 2 or a.shape[1] < 1 or a.shape[0] < 1 or (a < 0).any():
        raise ValueError(f"g must be non-negative crossing rates of shape (rows, directions) [1/world unit], got {a.shape}")
    return a


def light_plane(positions: Array, lat: Lattices) -> Array:
    """Light-plane coordinates (F, P, 2) of world points (P, 3) in every frame's light frame."""
    _lattice_and(lat)
    positions = check.finite(positions, "positions")
    if positions.ndim != 2 or positions.shape[1] != 3:
        raise ValueError(f"positions must have shape (P, 3), got {positions.shape}")
    return np.stack([np.einsum("pj,fj->fp", positions, lat.basis[:, 0]), np.einsum("pj,fj->fp", positions, lat.basis[:, 2])], -1)


def centres(lat: Lattices, part: NDArray[np.int64], xy: Array) -> Array:
    """The centre (F, P, 2) of the texel each point uses in each frame [world units] (NaN: no map).

    ``part`` (F, P) the map of each point (−1: none), ``xy`` (F, P, 2) its light-plane coordinates.
    """
    part = _lattice_and(lat, part)
    xy = check.as_float_array(xy, "xy")
    if xy.shape != part.shape + (2,):
        raise ValueError(f"xy must have shape {part.shape + (2,)} (frames, points, 2), got {xy.shape}")
    k = np.maximum(part, 0)
    f = np.arange(part.shape[0])[:, None]
    out = np.empty(xy.shape)
    for axis, (o, t) in enumerate(((lat.x0, lat.tx), (lat.y0, lat.ty))):
        oo, tt = o[f, k], t[f, k]
        out[..., axis] = oo + (np.floor((xy[..., axis] - oo) / tt) + 0.5) * tt
    out[part < 0] = np.nan
    return out


def displacement(lat: Lattices, part: NDArray[np.int64], xy: Array) -> Array:
    """Δ = c′ − c (F − 1, P, 2) of each point's texel centre between consecutive frames (NaN where not in view in both)."""
    c = centres(lat, part, xy)
    d = c[1:] - c[:-1]
    return np.where(np.abs(d) <= 1e-10 * (np.abs(c[1:]) + np.abs(c[:-1])), 0.0, d)  # a still centre: rounding, not motion


def grid_motion(lat: Lattices) -> tuple[Array, Array]:
    """Per frame change and map: the corner's move [texels of the earlier frame] (F − 1, K, 2) and the scale change t′/t − 1 (F − 1, K)."""
    _lattice_and(lat)
    with np.errstate(invalid="ignore"):
        shift = np.stack([(lat.x0[1:] - lat.x0[:-1]) / lat.tx[:-1], (lat.y0[1:] - lat.y0[:-1]) / lat.ty[:-1]], -1)
        scale = lat.tx[1:] / lat.tx[:-1] - 1
    return shift, scale


def _shifts(count: int) -> Array:
    """``count`` grid shifts (count, 2) [texels] spread over the texel (the R2 sequence, Roberts 2018)."""
    m = np.arange(1, count + 1)[:, None]
    return np.mod(0.5 + m * np.array([0.7548776662466927, 0.5698402909980532]), 1.0)


@dataclass(frozen=True)
class Densities:
    """Edge densities and their samples.

    ``g`` (G + K + 1, D) [1/world unit]: one row per tile group (frame-0 map k × tile of the
    frame-0 image, G = K × :data:`TILES` squared), then one per map, then the pooled row; ``group``
    (P,) the row each point uses (its tile's, or its map's where the tile holds fewer than
    :data:`MIN_POINTS` points, or the pooled one where no map held it in frame 0);
    ``counts`` and ``lengths`` (P, D) the per-point samples (state changes and Σ|Δ| per
    direction bin), ``tile_group`` (P,) the tile group of each point (−1: none), for
    :func:`agreement`'s resampling; ``maps`` K.
    """

    g: Array
    group: NDArray[np.int64]
    counts: Array
    lengths: Array
    tile_group: NDArray[np.int64]
    maps: int


def _rates(ct: Array, lt: Array, nt: Array, K: int) -> Array:
    """Rows of g from per-tile-group sums (..., G, D) and point counts (..., G): tiles, maps, pooled.

    A tile with fewer than :data:`MIN_POINTS` points, or a bin without samples, takes its map's
    value; a map without samples the pooled one.
    """
    T2 = ct.shape[-2] // K
    ck = ct.reshape(ct.shape[:-2] + (K, T2, ct.shape[-1])).sum(-2)
    lk = lt.reshape(lt.shape[:-2] + (K, T2, lt.shape[-1])).sum(-2)
    cp, lp = ck.sum(-2, keepdims=True), lk.sum(-2, keepdims=True)
    gp = cp / np.maximum(lp, 1e-300)
    gk = np.where(lk > 0, ck / np.maximum(lk, 1e-300), gp)
    parent = np.repeat(gk, T2, axis=-2)
    gt = np.where((lt > 0) & (nt[..., None] >= MIN_POINTS), ct / np.maximum(lt, 1e-300), parent)
    return np.concatenate([gt, gk, gp], axis=-2)


def _rows_of(tile_group: NDArray[np.int64], nt: Array, K: int) -> NDArray[np.int64]:
    """The row of g each point uses (see :class:`Densities`)."""
    T2 = len(nt) // K
    own = np.maximum(tile_group, 0)
    row = np.where(nt[own] >= MIN_POINTS, own, len(nt) + own // T2)
    return np.where(tile_group >= 0, row, len(nt) + K).astype(np.int64)


def densities(cache: MapCache, lat: Lattices, part0: NDArray[np.int64], positions: Array, normals: Array, lit0: NDArray[np.bool_], tile: NDArray[np.int64],
              *, directions: int = DIRECTIONS, shifts: int = SHIFTS) -> Densities:
    """g(φ_j): edge crossings per unit length [1/world unit] around the points, per tile of each frame-0 map.

    Shadow edges are where they are in the world, and a path may carry part of a map's
    points out of view: so the density is measured where the points are, per tile group
    (frame-0 map × ``tile``, the point's tile of the frame-0 image in [0, :data:`TILES` squared)),
    and a point keeps its tile's density whichever map it uses later.

    Map k of frame 0 is drawn again with its grid shifted by each of ``shifts`` sub-texel
    offsets spread over the texel; a point's centre then moves by a known Δ (by the shift,
    or by the shift less a texel where it changes texel).  Per direction bin j of Δ
    (``directions`` bins over [0, π)), g = state changes / Σ|Δ| (the crossing model's
    ratio estimator); see :class:`Densities` for the fallbacks of sparse tiles.
    """
    tile = np.asarray(tile)
    if tile.shape != (len(positions),) or tile.dtype.kind not in "iu" or (tile.size and (tile.min() < 0 or tile.max() >= TILES**2)):
        raise ValueError(f"tile must be tile indices in [0, {TILES**2 - 1}] of shape ({len(positions)},)")
    K, D = lat.maps, int(directions)
    P = len(positions)
    counts, lengths = np.zeros((P, D)), np.zeros((P, D))
    xy = light_plane(positions, lat)[0]
    for k in range(K):
        sel = np.nonzero(part0 == k)[0]
        if not sel.size or lat.n[0, k] == 0:
            continue
        tx, ty, x0, y0 = lat.tx[0, k], lat.ty[0, k], lat.x0[0, k], lat.y0[0, k]
        cx = x0 + (np.floor((xy[sel, 0] - x0) / tx) + 0.5) * tx
        cy = y0 + (np.floor((xy[sel, 1] - y0) / ty) + 0.5) * ty
        for hx, hy in _shifts(int(shifts)):  # a few shifted maps per cascade, each test vectorized over its points
            dx, dy = hx * tx, hy * ty
            nx = x0 + dx + (np.floor((xy[sel, 0] - x0 - dx) / tx) + 0.5) * tx - cx
            ny = y0 + dy + (np.floor((xy[sel, 1] - y0 - dy) / ty) + 0.5) * ty - cy
            lit = cache.test(lat, 0, k, positions[sel], normals[sel], dx=dx, dy=dy)
            j = np.floor(np.mod(np.arctan2(ny, nx), np.pi) / (np.pi / D)).astype(np.int64) % D
            np.add.at(counts, (sel, j), lit != lit0[sel])
            np.add.at(lengths, (sel, j), np.hypot(nx, ny))
    G = K * TILES**2
    tile_group = np.where(part0 >= 0, part0 * TILES**2 + tile, -1).astype(np.int64)
    ok = tile_group >= 0
    ct, lt = np.zeros((G, D)), np.zeros((G, D))
    np.add.at(ct, tile_group[ok], counts[ok])
    np.add.at(lt, tile_group[ok], lengths[ok])
    nt = np.bincount(tile_group[ok], minlength=G).astype(float)
    return Densities(_rates(ct, lt, nt, K), _rows_of(tile_group, nt, K), counts, lengths, tile_group, K)


def crossing_rate(g: Array, phi: Array) -> Array:
    """g_k at angles φ [rad] (any shape, broadcast with g's leading axes), linear and π-periodic in the measured directions."""
    g = check.finite(g, "g")
    phi = check.finite(phi, "phi")
    if g.ndim < 1 or g.shape[-1] < 1:
        raise ValueError(f"g must have a last axis of directions, got shape {g.shape}")
    D = g.shape[-1]
    u = np.mod(phi, np.pi) / (np.pi / D) - 0.5  # bin j holds the angles [j, j + 1)·π/D: its value sits at its centre
    j0 = np.floor(u).astype(np.int64) % D
    frac = u - np.floor(u)
    j1 = (j0 + 1) % D
    return np.take_along_axis(g, j0, -1) * (1 - frac) + np.take_along_axis(g, j1, -1) * frac


def flip_probability(delta: Array, group: NDArray[np.int64], g: Array) -> Array:
    """P(flip) = (1 − exp(−2|Δ|·g_k(φ_Δ)))/2 per point (F − 1, P); NaN where Δ is undefined.

    ``group`` (P,) is each point's row of ``g`` (:attr:`Densities.group`).
    """
    g = _rows(g)
    try:
        delta = np.asarray(delta, dtype=float)  # NaN: a point without a map in one of the frames
    except (TypeError, ValueError):
        raise ValueError("delta must be centre displacements of shape (..., 2) [world units]") from None
    if delta.ndim < 1 or delta.shape[-1] != 2 or np.isinf(delta).any():
        raise ValueError(f"delta must be centre displacements of shape (..., 2) [world units] (NaN where undefined), got {delta.shape}")
    group = np.asarray(group)
    if group.dtype.kind not in "iu" or (group.size and (group.min() < 0 or group.max() >= g.shape[0])):
        raise ValueError(f"group must be rows of g in [0, {g.shape[0] - 1}] (Densities.group)")
    length = np.hypot(delta[..., 0], delta[..., 1])
    phi = np.arctan2(delta[..., 1], delta[..., 0])
    k = np.broadcast_to(group, length.shape)
    rate = crossing_rate(g[k], np.nan_to_num(phi)[..., None])[..., 0]
    return -0.5 * np.expm1(-2.0 * length * rate)  # P(odd count) of Poisson crossings


def predicted(delta: Array, group: NDArray[np.int64], g: Array) -> Array:
    """The predicted flip fraction of each frame change (F − 1,): mean P(flip) over points seen in both frames."""
    p = flip_probability(delta, group, g)
    ok = np.isfinite(p)
    return np.where(ok, p, 0.0).sum(-1) / np.maximum(ok.sum(-1), 1)


def _bin_weights(delta: Array, D: int) -> tuple[Array, NDArray[np.int64], NDArray[np.int64], Array]:
    """|Δ|, the two direction bins Δ's rate interpolates between, and the second one's weight."""
    length = np.hypot(delta[..., 0], delta[..., 1])
    u = np.mod(np.arctan2(delta[..., 1], delta[..., 0]), np.pi) / (np.pi / D) - 0.5
    j0 = np.floor(u).astype(np.int64) % D
    return length, j0, (j0 + 1) % D, u - np.floor(u)


def agreement(dens: Densities, delta: Array, use: NDArray[np.bool_], flips: NDArray[np.bool_], predicted_total: float,
              *, replicates: int = 200, seed: int = 0) -> tuple[float, float]:
    """Predicted / measured flips and its standard error, resampling the points (bootstrap).

    The points are the sample: which of them lie near a shadow edge decides both the
    measured flips and the densities the prediction uses.  Each replicate draws the points
    with replacement, estimates g again from their frame-0 samples (with the same fallbacks)
    and re-weights the prediction linearly in g (λ = |Δ|·g; the Poisson saturation is kept
    as a fixed factor) and the measured count.

    Parameters
    ----------
    dens : Densities
    delta : ndarray (F − 1, P, 2)
        Centre displacements (:func:`displacement`).
    use : ndarray of bool (F − 1, P)
        The (point, frame) pairs counted (seen in both frames, the same map).
    flips : ndarray of bool (F − 1, P)
        Measured flips.
    predicted_total : float
        Σ P(flip) over the same pairs.

    Returns
    -------
    ratio : float
        Predicted over measured flips.
    se : float
        Its bootstrap standard error (NaN when nothing flipped or nothing was predicted; inf
        when so few flipped that a replicate draws none of them).
    """
    check.instance(dens, "dens", Densities)
    P, D = dens.counts.shape
    K = dens.maps
    T2 = TILES**2
    G = K * T2
    length, j0, j1, frac = _bin_weights(np.where(use[..., None], np.nan_to_num(delta), 0.0), D)
    length = np.where(use, length, 0.0)
    pts = np.broadcast_to(np.arange(P), length.shape)
    A = np.zeros((P, D))  # Σ over frames of |Δ| · bin weight, per point and bin
    np.add.at(A, (pts, j0), length * (1 - frac))
    np.add.at(A, (pts, j1), length * frac)
    m = np.where(use, flips, False).sum(0).astype(float)  # measured flips per point
    measured = float(m.sum())
    lam_hat = float((dens.g[dens.group] * A).sum())
    if measured == 0 or lam_hat == 0:
        return (np.inf if predicted_total > 0 else np.nan) if measured == 0 else 0.0, np.nan
    rng = np.random.default_rng(seed)
    W = rng.multinomial(P, np.full(P, 1.0 / P), size=int(replicates)).astype(float)  # (R, P)
    R = len(W)
    ct, lt, nt, At = np.zeros((R, G, D)), np.zeros((R, G, D)), np.zeros((R, G)), np.zeros((R, G, D))
    for grp in np.unique(dens.tile_group[dens.tile_group >= 0]):  # per tile group (not per point): its points' weighted sums
        idx = np.nonzero(dens.tile_group == grp)[0]
        w = W[:, idx]
        ct[:, grp], lt[:, grp], nt[:, grp], At[:, grp] = w @ dens.counts[idx], w @ dens.lengths[idx], w.sum(1), w @ A[idx]
    g_rep = _rates(ct, lt, nt, K)  # (R, G + K + 1, D)
    own = nt >= MIN_POINTS  # (R, G): the tile keeps its own row, else its map's
    lam_rep = (np.where(own[..., None], g_rep[:, :G], np.repeat(g_rep[:, G:G + K], T2, axis=1)) * At).sum((-1, -2))
    outside = dens.tile_group < 0
    lam_rep = lam_rep + ((W[:, outside] @ A[outside]) * g_rep[:, -1]).sum(-1)
    ratio_rep = predicted_total * (lam_rep / lam_hat) / np.maximum(W @ m, 1e-300)
    with np.errstate(over="ignore"):  # a replicate without a measured flip (a handful of flips in all): the error is unbounded, inf
        return predicted_total / measured, float(np.std(ratio_rep, ddof=1))
