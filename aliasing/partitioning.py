"""Split schemes for z-partitioned (cascaded, parallel-split) shadow maps, in one registry.

Each method maps (near, far, k) to the k + 1 split distances n = C_0 < C_1 < … < C_k = f
[world units] along the view direction.  :func:`split_distances` is the dispatcher.

Example
-------
>>> split_distances("log", 1.0, 1000.0, 3)
array([   1.,   10.,  100., 1000.])
>>> split_distances("practical", 1.0, 100.0, 2, lam=0.5)
array([  1. ,  30.25, 100. ])
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from . import _validation as check

Array = NDArray[np.float64]


@dataclass(frozen=True)
class SplitMethod:
    """A registered split scheme; ``func(near, far, k, **params) -> C (k + 1,)``."""

    name: str
    func: Callable[..., Array]
    source: str
    summary: str


SPLIT_METHODS: dict[str, SplitMethod] = {}


def register(name: str, source: str, summary: str) -> Callable:
    """Decorator adding a split method to :data:`SPLIT_METHODS`."""

    def wrap(func: Callable[..., Array]) -> Callable[..., Array]:
        if name in SPLIT_METHODS:
            raise RuntimeError(f"split method {name!r} registered twice")
        SPLIT_METHODS[name] = SplitMethod(name, func, source, summary)
        return func

    return wrap


def split_distances(method: str, near: float, far: float, k: int, **params: float) -> Array:
    """The k + 1 split distances C_0 = near < … < C_k = far of a named scheme [world units].

    Parameters
    ----------
    method : str
        A name in :data:`SPLIT_METHODS` (case-insensitive).
    near, far : float
        Eye near and far distances [world units], 0 < near < far.
    k : int
        Number of partitions, ≥ 1.
    **params
        Method parameters (``lam`` for ``practical``, …); unknown ones are an error.

    Raises
    ------
    ValueError
        Unknown method or parameter, k < 1, near ≤ 0, far ≤ near, λ outside [0, 1].
    """
    key = check.choice(method, "split method", SPLIT_METHODS)
    entry = SPLIT_METHODS[key]
    n, f = (float(v) for v in check.frustum(near, far))
    kk = _partitions(k)
    accepted = set(inspect.signature(entry.func).parameters) - {"near", "far", "k"}
    unknown = set(params) - accepted
    if unknown:
        raise ValueError(f"split method {key!r} takes {sorted(accepted) or 'no parameters'}, not {sorted(unknown)}")
    edges = np.asarray(entry.func(n, f, kk, **params), dtype=float)
    edges[0], edges[-1] = n, f  # exact ends, whatever the rounding inside
    return edges


def _partitions(k: int) -> int:
    if isinstance(k, bool) or int(k) != k or k < 1:
        raise ValueError(f"k must be a whole number >= 1 (number of partitions), got {k!r}")
    return int(k)


def _lam(lam: float) -> float:
    return float(check.closed_range(lam, "lambda", 0.0, 1.0))


def _log(n: float, f: float, k: int) -> Array:
    return n * (f / n) ** (np.arange(k + 1) / k)  # Lloyd 2006 eqs. (15)–(16); Lloyd 2007 eqs. (80)–(81)


def _uniform(n: float, f: float, k: int) -> Array:
    return n + (f - n) * np.arange(k + 1) / k


@register("log", "Lloyd et al. 2006 eqs. 15–16; Lloyd et al. 2007 eqs. 80–82; Zhang et al. 2006 eq. 1", "self-similar: C_i = n (f/n)^(i/k), equal f_i/n_i")
def _log_method(near: float, far: float, k: int) -> Array:
    return _log(near, far, k)


@register("uniform", "Zhang et al. 2006 eq. 2", "equal depth ranges: C_i = n + (f − n) i/k")
def _uniform_method(near: float, far: float, k: int) -> Array:
    return _uniform(near, far, k)


@register("practical", "Zhang et al. 2006 eq. 3 (λ-weighted form used by engines)", "C_i = λ C_i^log + (1 − λ) C_i^uni")
def _practical(near: float, far: float, k: int, lam: float = 0.5) -> Array:
    w = _lam(lam)
    return w * _log(near, far, k) + (1 - w) * _uniform(near, far, k)
