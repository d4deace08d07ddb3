"""The tuned split against the papers' splits for the same camera, fit and texel budget.

For an engine whose splits are set freely (three.js's ``custom`` λ, Babylon's λ, PlayCanvas's
distribution, Unity's and Godot's fractions, Bevy's first bound, Unreal's exponent), how far
does its own split family get?  :func:`compare_splits` evaluates, with the engine's own fit and
snap, its map size and count, over the receivers and the sun band (the objective of
:mod:`aliasing.tune.measure`):

``start``, ``tuned``
    The engine's split before and after :func:`aliasing.tune.tune`.
``log``
    Lloyd et al. 2006's logarithmic split C_i = n·(f/n)^(i/k) (eq. 12 there: the split whose
    cascades' errors are equal for the tight fit of a view with n′ = n).
``practical``
    Zhang et al. 2006's practical split, the mean of the logarithmic and uniform splits (λ = 0.5).
``equal-error``
    The best any split distances can do with this fit: the minimax split, found by bisection on
    the error e (each cascade grown from the previous end until its error reaches e; feasible when
    k cascades reach the far end).  Every cascade then has the same worst error.
``budget``
    Lloyd et al. 2007, eq. 83: the logarithmic split with the same texel budget shared by error
    instead of equally (maps of unequal size, each map's sides in the ratio M_x/M_z): every map's
    error is then H·√(Σ_j M_x,j M_z,j / T) (:func:`aliasing.budgets.allocate`, ``error``).  Maps
    of unequal size are not what engines build; it bounds what a different allocation could add.

The ranges are contiguous (no overlap or blend band), the engine's first cascade starts at the
camera's near plane and the last ends where the tuned shadows end.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .. import _validation as _check
from .. import budgets, partitioning
from ..engines import pipeline as engine_pipeline
from ..setups import Camera, Pipeline
from .measure import depths
from .search import Tuned

METHODS = ("start", "tuned", "log", "practical", "equal-error", "budget")


def _errors(pipe, cam, lights, near_i, far_i, receivers) -> np.ndarray:
    """Worst error per cascade [px/texel] of contiguous ranges with the pipeline's fit, over the sun band and receivers."""
    a, b = np.asarray(near_i, float), np.asarray(far_i, float)
    r = engine_pipeline.result(pipe, cam, lights, ranges=(a, b))
    rn, rf = receivers
    u, v = (np.asarray(x, float) for x in r.used)
    err = np.maximum(r.M_x, r.M_z).max(axis=0) * cam.height / pipe.resolution * u / np.maximum(u, rn)  # eq. (2) at max(u, rn)
    return np.where((v > rn) & (u < rf), err, np.nan)


def equal_error_split(pipe, cam, lights, k: int, near: float, far: float, receivers, iterations: int = 40) -> np.ndarray:
    """The split distances near = C_0 < … < C_k = far whose worst error is least (all cascades equal) [world units].

    Parameters
    ----------
    pipe : Pipeline
        The engine's pipeline (its fit, snap and map resolution).
    cam : Camera
        The camera (:class:`aliasing.setups.Camera`).
    lights : array_like
        Directions towards the sun, (L, 3).
    k : int
        Cascades, >= 1.
    near, far : float
        Where the first cascade starts and the last ends, 0 < near < far [world units].
    receivers : (float, float)
        The receivers' eye depths [world units].
    iterations : int
        Bisection steps on the error, 1 to 200.

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 2})
    >>> c = equal_error_split(s.pipeline, s.camera, s.sun.direction(s.sun.elevations(3)), 2, 0.1, 100.0, (0.1, 100.0), iterations=20)
    >>> len(c), float(c[0]), float(c[-1])
    (3, 0.1, 100.0)
    """
    _check.instance(pipe, "pipe", Pipeline)
    _check.instance(cam, "cam", Camera)
    lights = _check.as_float_array(lights, "lights")
    if lights.ndim != 2 or lights.shape[1] != 3 or not len(lights) or not np.isfinite(lights).all() or not (np.abs(lights).sum(axis=1) > 0).all():
        raise ValueError(f"lights must be finite non-zero directions of shape (L, 3), got shape {lights.shape}")
    k = _check.whole(k, "k", 1, 64)
    near, far = _check.scalar(near, "near"), _check.scalar(far, "far")
    if not (math.isfinite(near) and math.isfinite(far) and 0 < near < far):
        raise ValueError(f"near and far must be finite with 0 < near < far [world units], got {near!r}, {far!r}")
    receivers = depths(receivers)
    iterations = _check.whole(iterations, "iterations", 1, 200)

    def walk(e: float) -> np.ndarray | None:
        ends = [near]
        for _ in range(k):
            a = ends[-1]
            if a >= far:
                break
            lo, hi = a, far
            grid = np.geomspace(a * (1 + 1e-9), far, 200)
            for _ in range(2):  # a coarse grid, then a finer one between its last two points
                err = _errors(pipe, cam, lights, np.full(grid.size, a), grid, receivers)
                ok = ~(err > e)  # NaN (no receiver) counts as fine
                if not ok[0]:
                    return None
                i = ok.size - 1 if ok.all() else int(np.argmin(ok)) - 1  # the end of the first run within e
                lo, hi = grid[i], grid[min(i + 1, grid.size - 1)]
                if hi <= lo:
                    break
                grid = np.linspace(lo, hi, 200)
            ends.append(float(lo))
        return np.array(ends) if ends[-1] >= far * (1 - 1e-9) else None

    top = float(np.nanmax(_errors(pipe, cam, lights, [near], [far], receivers)))
    lo, hi = 0.0, top * (1 + 1e-9)
    best = np.array([near, far])
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        got = walk(mid)
        if got is None:
            lo = mid
        else:
            hi, best = mid, got
    if best.size < k + 1:  # fewer cascades reach: split the last evenly (the error cannot grow)
        best = np.concatenate([best[:-1], np.linspace(best[-2], far, k + 2 - best.size)[1:]])
    return best


def compare_splits(tuned: Tuned) -> list[dict[str, Any]]:
    """The tuned split against the papers' (module docstring): one row per method.

    Each row: ``method``, ``splits`` (C_0 … C_k [world units]), ``error`` (the worst over the
    receivers and the sun band [px/texel]) and ``ratio`` (error over the equal-error split's).

    Example
    -------
    >>> from aliasing import setups
    >>> from aliasing.tune import tune
    >>> s = setups.build("threejs", {"cascades": 4}, "near=0.1,far=500,fov=50,aspect=16:9,height=1080", "15..60")
    >>> rows = {r["method"]: r for r in compare_splits(tune(s, keep=("cascades", "shadowMapSize")))}
    >>> round(rows["tuned"]["error"], 2), round(rows["equal-error"]["error"], 2), round(rows["practical"]["error"], 1)
    (9.05, 9.05, 677.2)
    """
    if not isinstance(tuned, Tuned):
        raise ValueError(f"tuned must be the result of aliasing.tune.tune, got {type(tuned).__name__}")
    pipe, cam = tuned.setup.pipeline, tuned.setup.camera
    if pipe.fit == "fixed":
        raise ValueError("tuned has a fixed shadow box (no cascades to split)")
    lights = tuned.setup.sun.direction(tuned.setup.sun.elevations(7))
    rec = tuned.limits.receivers
    k, near, far = pipe.k, cam.near, float(max(pipe.far_i))
    rows = []

    def row(method: str, splits, error: float) -> None:
        rows.append({"method": method, "splits": [float(c) for c in splits], "error": float(error)})

    for method, setup in (("start", tuned.start), ("tuned", tuned.setup)):
        p = setup.pipeline
        row(method, [*p.near_i, p.far_i[-1]], float(np.nanmax(tuned.measure.error if method == "tuned" else tuned.before.error)))
    for method, name, params in (("log", "log", {}), ("practical", "practical", {"lam": 0.5})):
        c = partitioning.split_distances(name, near, far, k, **params)
        row(method, c, float(np.nanmax(_errors(pipe, cam, lights, c[:-1], c[1:], rec))))
    c = equal_error_split(pipe, cam, lights, k, near, far, rec)
    row("equal-error", c, float(np.nanmax(_errors(pipe, cam, lights, c[:-1], c[1:], rec))))
    c = partitioning.split_distances("log", near, far, k)
    r = engine_pipeline.result(pipe, cam, lights, ranges=(c[:-1], c[1:]))  # near: the camera's; far: c[-1]
    u = np.asarray(r.used[0], float)
    scale = u / np.maximum(u, rec[0])  # the error at the first receiver
    mx, mz = r.M_x * scale, r.M_z * scale
    budget = float(pipe.k * pipe.resolution ** 2)
    rs, rt = budgets.allocate("error", mx, mz, budget)  # eq. (83): σ_i = S_i / Σ S_j of the budget
    m = budgets.max_error(mx, mz, rs, rt, cam.height)
    row("budget", c, float(np.nanmax(m)))
    best = next(x["error"] for x in rows if x["method"] == "equal-error")
    for x in rows:
        x["ratio"] = x["error"] / best if best > 0 and math.isfinite(best) else math.nan
    return rows
