"""The timer shared by the benchmark scripts (imported as a sibling module: run them as scripts)."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any


def best_of(fn: Callable[[], Any], repeats: int) -> float:
    """Smallest wall time [s] of ``repeats`` calls of ``fn``."""
    return timed(fn, repeats)[0]


def timed(fn: Callable[[], Any], repeats: int) -> tuple[float, Any]:
    """Smallest wall time [s] of ``repeats`` calls of ``fn``, and the last call's result."""
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out
