"""A scheme's shadow maps for one light with any split method or engine preset, and the
texel budget shared among them.

``cascade_set(…, splits="threejs-csm", scheme="P")``: the split distances (and an engine's
padding or overlap) of :func:`aliasing.partitioning.partitions`, one map per partition fitted
to its sub-frustum with the scheme's warp, exactly as :func:`aliasing.schemes.evaluate`
with ``edges=`` evaluates it.  Without ``splits``, the scheme's own maps
(:func:`aliasing.raster.map_set`: single, ``ZP<k>+…``, face partitions).

:func:`budget_shares` divides a budget of T texels among the maps: ``equal`` (what engines
ship, ⌊√(T/k)⌋² each) or ``error`` (Lloyd et al. 2007 eq. 83: in proportion to each map's
storage factor S_i = M_x·M_z for this light, as square maps).

Example
-------
>>> cs = cascade_set(1.0, 100.0, 60.0, "overhead", "P", splits="practical", k=3, lam=0.5)   # as `aliasing splits`
>>> len(cs.maps.maps), cs.maps.edges.round(3).tolist()
(3, [1.0, 19.321, 44.272, 100.0])
>>> budget_shares(cs, 3 * 64**2, "equal").tolist()
[64, 64, 64]
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ... import geometry, partitioning, schemes
from .core import check_resolution
from .facemaps import MapSet, map_set
from .lightmap import light_map
from ...view import View, view_args

Array = NDArray[np.float64]

ALLOCATIONS = ("equal", "error")


@dataclass(frozen=True)
class CascadeSet:
    """Maps of a scheme for one light with their analytic unit-resolution maxima.

    Attributes: ``maps`` (:class:`~aliasing.raster.MapSet`), ``label`` (e.g. "threejs-csm+P"),
    ``near_i``, ``far_i`` (each map's depth range [world units]; NaN for face partitions),
    ``M_x``, ``M_z`` (each map's analytic maxima at unit resolution, Lloyd 2006 eqs. 7–10).
    """

    maps: MapSet
    label: str
    near_i: Array
    far_i: Array
    M_x: Array
    M_z: Array


def cascade_set(near: float | View, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, *, splits: str | None = None, k: int | None = None,
                **params: float) -> CascadeSet:
    """The maps of ``scheme`` for one light, with the partitions of split method ``splits``.

    Parameters
    ----------
    near, far : float
        Eye near and far (shadow) distances [world units], 0 < near < far; or a
        :class:`~aliasing.View` in ``near``: ``cascade_set(view, light, scheme, splits=…)``.
    fov : float
        Full field of view [deg].
    light : str or array_like
        One direction (spec or eye-space vector towards the light).
    scheme : str
        Default Standard.  Any scheme (:data:`aliasing.schemes.GRAMMAR`); with ``splits`` a single-map warp
        (Standard, P, LogP, a warping rule) used inside every partition.
    splits : str, optional
        A split method or engine preset of :data:`aliasing.partitioning.SPLIT_METHODS`.
    k : int, optional
        Number of partitions (default: the preset's own).
    **params
        The split method's parameters (``lam``, ``ratio``, ``padding``, …).
    """
    view, (light, scheme) = view_args(near, far, fov, (light, scheme), (None, None, None, None, "Standard"))
    if view.shape != ():
        raise ValueError(f"cascade_set takes one view: near, far and fov must be scalars, got shape {view.shape}")
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    n, f = view.near, view.far
    if splits is None:
        if k is not None or params:
            raise ValueError("k and split parameters need splits (a split method name)")
        ms = map_set(view, lv, scheme)
        r = schemes.evaluate(scheme, view, lv)
        cols = ms.slots
        if ms.faces:
            lo = hi = np.full(len(ms.maps), np.nan)
        else:
            lo, hi = ms.edges[:-1], ms.edges[1:]
        return CascadeSet(ms, r.scheme.name, lo, hi, r.M_x[0, cols], r.M_z[0, cols])  # the canonical name (docs/cli.rst)
    sch = schemes.parse(scheme)
    if sch.k != 1 or sch.faces:
        raise ValueError(f"scheme must be a single-map warp (Standard, P, LogP, a warping rule) with --splits, got {scheme!r}")
    lo, hi = partitioning.partitions(splits, n, f, k, **params)
    edges = partitioning.split_distances(splits, n, f, len(lo), **{key: v for key, v in params.items() if key in _split_params(splits)})
    maps = [light_map(view.between(float(a), float(b)), lv, sch) for a, b in zip(lo, hi)]
    r = schemes.evaluate(sch, view, lv, edges=(lo, hi))
    ms = MapSet(maps, np.arange(len(maps)), edges, "", view, lv[0])
    return CascadeSet(ms, f"{splits}+{sch.name}", lo, hi, r.M_x[0], r.M_z[0])


def _split_params(method: str) -> set[str]:
    import inspect

    entry = partitioning.SPLIT_METHODS[partitioning.resolve_name(method)]
    return set(inspect.signature(entry.func).parameters) - {"near", "far", "k"}


def budget_shares(cs: CascadeSet, budget: int, allocation: str = "equal") -> NDArray[np.int64]:
    """Side [texels] of each (square) map sharing ``budget`` texels.

    ``equal``: ⌊√(T/k)⌋ each.  ``error``: ⌊√(σ_i T)⌋ with σ_i = S_i/Σ S_j (Lloyd et al.
    2007 eq. 83), S_i = M_x,i·M_z,i of this light (square maps: the s/t split of eqs. 13–14
    is not applied, since the rasterizer's maps are square).
    """
    key = check.choice(allocation, "allocation", dict.fromkeys(ALLOCATIONS))
    t = float(check.positive(budget, "budget"))
    k = len(cs.maps.maps)
    if key == "equal":
        side = np.full(k, np.floor(np.sqrt(t / k) + 1e-9))
    else:
        s = cs.M_x * cs.M_z
        sigma = s / s.sum()  # eq. (83)
        side = np.floor(np.sqrt(sigma * t) + 1e-9)
    return np.array([check_resolution(int(v), "budget share (texels per side of a map)") for v in side], np.int64)
