"""Resolution budgets: share a texel budget T among the maps of a scheme, and the error it gives.

With unit-resolution maxima M_x, M_z of map i (from :func:`aliasing.schemes.evaluate`), a
map of res_s × res_t texels viewed by an image of res_i pixels has the maximum perspective
aliasing error

    m_i = res_i · max(M_x,i / res_s,i, M_z,i / res_t,i)      (Lloyd 2006 eqs. 7–10 scaled)

Allocations (one registry, :data:`ALLOCATIONS`):

* ``error``: Lloyd et al. 2007 eq. 83: σ_i = S_i/Σ S_j of the budget, split between s and t
  as res_s/res_t = M_x/M_z (Lloyd 2006 eqs. 13–14); every map then has the same error
  res_i·√(Σ S_j / T), the smallest maximum any allocation can reach;
* ``equal``: what engines ship: k square maps of T/k texels each;
* ``equal-balanced``: T/k texels per map, split between s and t by eqs. 13–14;
* ``pow2``: Zhang et al. 2006 §3.5, square maps of 2^(K−i) texels a side (areas ∝ 4^−i),
  scaled to the budget.

Example
-------
>>> import numpy as np
>>> mx, mz = np.array([[10.0, 2.0]]), np.array([[5.0, 2.0]])
>>> rs, rt = allocate("error", mx, mz, budget=1000.0)
>>> round(float((rs * rt).sum()), 9), max_error(mx, mz, rs, rt).round(6)  # √((50 + 4)/1000)
(1000.0, array([[0.232379, 0.232379]]))
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check

__all__ = [
    "ALLOCATIONS",
    "allocate",
    "max_error",
    "splits_report",
]

Array = NDArray[np.float64]


def _error(mx: Array, mz: Array, budget: Array) -> tuple[Array, Array]:
    s = mx * mz
    sigma = s / s.sum(axis=-1, keepdims=True)  # eq. (83): σ_i = S_i / Σ S_j
    share = sigma * budget
    return np.sqrt(mx / mz * share), np.sqrt(mz / mx * share)  # eq. (83); Lloyd 2006 eqs. (13)–(14)


def _equal(mx: Array, mz: Array, budget: Array) -> tuple[Array, Array]:
    side = np.sqrt(budget / mx.shape[-1]) * np.ones_like(mx)
    return side, side


def _equal_balanced(mx: Array, mz: Array, budget: Array) -> tuple[Array, Array]:
    share = budget / mx.shape[-1]
    return np.sqrt(mx / mz * share), np.sqrt(mz / mx * share)  # Lloyd 2006 eqs. (13)–(14) per map


def _pow2(mx: Array, mz: Array, budget: Array) -> tuple[Array, Array]:
    k = mx.shape[-1]
    area = 4.0 ** -np.arange(1, k + 1)  # Zhang 2006 §3.5: resolution(T_i) = 2^(k−i) × 2^(k−i)
    side = np.sqrt(budget * area / area.sum()) * np.ones_like(mx)
    return side, side


# A range of M_x, M_z and budget in which every allocation's arithmetic stays inside float64
# (its products and ratios of two such numbers); outside it allocate refuses rather than
# returning inf or 0 texels.
_LO, _HI = 1e-150, 1e150

ALLOCATIONS: dict[str, tuple[Callable[[Array, Array, Array], tuple[Array, Array]], str]] = {
    "error": (_error, "Lloyd et al. 2007 eq. 83: texels in proportion to each map's S, s/t by eqs. 13–14"),
    "equal": (_equal, "engines: k square maps of T/k texels"),
    "equal-balanced": (_equal_balanced, "T/k texels per map, s/t by Lloyd 2006 eqs. 13–14"),
    "pow2": (_pow2, "Zhang et al. 2006 §3.5: square maps whose side halves from split to split"),
}


@check.public
def allocate(method: str, M_x: ArrayLike, M_z: ArrayLike, budget: ArrayLike) -> tuple[Array, Array]:
    """Resolutions (res_s, res_t) [texels] of each map, shape of ``M_x`` (…, K).

    Parameters
    ----------
    method : {"error", "equal", "equal-balanced", "pow2"}
    M_x, M_z : array_like
        Unit-resolution maxima of each map, last axis = maps.
    budget : array_like
        Total texels T over all maps; at least one texel per map.
    """
    key = check.choice(method, "allocation method", ALLOCATIONS)
    mx = check.positive(M_x, "M_x")
    mz = check.positive(M_z, "M_z")
    t = check.positive(budget, "budget")
    if mx.ndim == 0 or mx.shape != mz.shape or mx.shape[-1] == 0:
        raise ValueError(f"M_x and M_z must have the same shape (..., K) with K >= 1 maps on the last axis, got {mx.shape} and {mz.shape}")
    if (t < mx.shape[-1]).any():
        raise ValueError(f"budget must be at least one texel per map ({mx.shape[-1]} maps), got {check._show(t)}")
    tt = np.asarray(t)[..., None] if np.ndim(t) else t
    check.broadcast(M_x=mx, budget=tt)
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):  # anything not finite is refused below
        res_s, res_t = ALLOCATIONS[key][0](mx, mz, tt)
    if not (np.isfinite(res_s).all() and np.isfinite(res_t).all() and (res_s > 0).all() and (res_t > 0).all()):
        raise ValueError(f"M_x, M_z and budget give resolutions outside the float range; keep M_x, M_z and budget within [{_LO:g}, {_HI:g}]")
    return res_s, res_t


@check.public
def max_error(M_x: ArrayLike, M_z: ArrayLike, res_s: ArrayLike, res_t: ArrayLike, res_image: ArrayLike = 1.0) -> Array:
    """Maximum perspective aliasing error of each map, res_i·max(M_x/res_s, M_z/res_t)."""
    ri = check.positive(res_image, "res_image")
    mx, mz = check.positive(M_x, "M_x"), check.positive(M_z, "M_z")
    rs, rt = check.positive(res_s, "res_s"), check.positive(res_t, "res_t")
    check.broadcast(M_x=mx, M_z=mz, res_s=rs, res_t=rt, res_image=ri)
    with np.errstate(over="ignore", under="ignore"):  # an error beyond 1.8e308 is inf, which is its honest value
        return ri * np.maximum(mx / rs, mz / rt)


@check.public
def splits_report(
    method: str,
    near: float,
    far: float,
    k: int | None = None,
    *,
    fov: float = 60.0,
    aspect: float = 1.0,
    light: str | ArrayLike = "overhead",
    warp: str = "Standard",
    budget: float | None = None,
    res_image: float | None = None,
    allocations: tuple[str, ...] = ("error", "equal"),
    **params: float,
) -> list[dict]:
    """Split distances, each partition's S and, for a budget, its resolution and error.

    Every partition is fitted separately with the warp ``warp`` (a scheme base name:
    ``Standard``, ``P``, ``LogP``, a warping rule, …) and evaluated over the light
    directions.  S_max is the largest S of the partition over the directions.  For each
    allocation the error of a partition is its largest over the directions (allocations that
    depend on the direction, like ``error``, are recomputed for every direction) and the
    resolution reported is the one at the direction where the scheme's overall error peaks.
    The last row, ``partition = "all"``, holds the totals and overall maxima.

    Parameters
    ----------
    method : str
        Split method or engine preset (:data:`aliasing.partitioning.SPLIT_METHODS`);
        padded or overlapping presets are evaluated with their real map extents.
    near, far : float
        Eye near and far (shadow) distances [world units].
    k : int, optional
        Number of partitions (an engine preset's default when omitted).
    fov : float
        Full (vertical) field of view [deg].
    aspect : float
        Image width/height, > 0 (default 1, square): see :class:`aliasing.View`.
    light : str or array_like
        Light spec or vectors.
    warp : str
        Warp used inside each partition.
    budget : float, optional
        Total texels over all maps; needs ``res_image``.
    res_image : float, optional
        Image resolution [pixels per side; rows of a non-square image, square pixels].
    allocations : tuple of str
        Allocation methods to compare (:data:`ALLOCATIONS`).
    **params
        Split-method parameters (``lam``, …).

    Example
    -------
    >>> rows = splits_report("log", 1.0, 1000.0, 4, warp="P", budget=4096**2, res_image=1024)
    >>> [round(r["far"], 3) for r in rows[:-1]], round(rows[-1]["max_error[error]"], 4)  # 1024·√(S/4096²)
    ([5.623, 31.623, 177.828, 1000.0], 1.0005)
    """
    from . import partitioning, schemes
    from .view import View

    if (budget is None) != (res_image is None):
        raise ValueError("budget and res_image (image resolution) go together: give both or neither")
    if isinstance(allocations, str) or not isinstance(allocations, (tuple, list)) or not all(isinstance(a, str) for a in allocations):
        raise ValueError(f"allocations must be a tuple of allocation names ({', '.join(ALLOCATIONS)}), got {allocations!r:.60}")
    for name in allocations:
        check.choice(name, "allocations entry", ALLOCATIONS)
    check.instance(warp, "warp", str)
    if budget is not None:
        budget, res_image = check.scalar(budget, "budget"), check.scalar(res_image, "res_image")
    n_i, f_i = partitioning.partitions(method, near, far, k, **params)
    r = schemes.evaluate(warp, View(near, far, fov, aspect), light, edges=(n_i, f_i))
    s = r.M_x * r.M_z  # (N, K)
    rows = [{"partition": i + 1, "near": float(n_i[i]), "far": float(f_i[i]), "S_max": float(s[:, i].max())} for i in range(len(n_i))]
    total = {"partition": "all", "near": float(n_i.min()), "far": float(f_i.max()), "S_max": float(r.S.max())}
    if budget is not None:
        for name in allocations:
            rs, rt = allocate(name, r.M_x, r.M_z, budget)
            err = max_error(r.M_x, r.M_z, rs, rt, res_image)  # (N, K)
            worst = int(np.argmax(err.max(axis=-1)))
            for i, row in enumerate(rows):
                row[f"res_s[{name}]"] = float(rs[worst, i])
                row[f"res_t[{name}]"] = float(rt[worst, i])
                row[f"max_error[{name}]"] = float(err[:, i].max())
            total[f"res_s[{name}]"] = total[f"res_t[{name}]"] = float("nan")
            total[f"max_error[{name}]"] = float(err.max())
    return rows + [total]
