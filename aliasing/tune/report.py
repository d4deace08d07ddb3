"""What tune changed and what got worse: the start against the tuned setup, measure by measure.

:func:`worse` compares the user's setup (the start) with the tuned one on every measure that
``check`` reports, so that no trade is made silently: the worst error over the receivers
[px/texel], the acne (the share of the sampled receivers, ground and ``max_slope``), the
gap at a caster's foot [px], the step of the texel at a cascade seam [×], the shimmer under a walk
[px per frame] and the memory of the maps [MiB].  Each measure that grows is one entry, with its
line of text.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..check import check
from .search import Tuned

__all__ = ["MEASURES", "changes_text", "worse"]

#: The measures compared: (name, words, unit).
MEASURES = (("error", "worst error over the receivers", "px/texel"), ("acne", "acne", "of the sampled receivers"),
            ("gap_px", "gap at the walls' foot over the receivers", "px"), ("seam_step", "seam step", "×"), ("shimmer_px", "shimmer", "px per frame"),
            ("memory", "memory", "MiB"))


def _most(rows: list[dict], key: str) -> float | None:
    values = [float(r[key]) for r in rows if r.get(key) is not None and math.isfinite(float(r[key]))]
    return max(values) if values else None


def _values(tuned: Tuned, which: str) -> dict[str, float | None]:
    setup, m = (tuned.start, tuned.before) if which == "before" else (tuned.setup, tuned.measure)
    slopes = [0.0, tuned.limits.max_slope] if tuned.limits.max_slope > 0 else None
    rows = check(setup, receivers=slopes).cascades
    gap = m.gap_px[np.isfinite(m.gap_px)]
    return {"error": m.objective if math.isfinite(m.objective) else None, "acne": _most(rows, "acne"),
            "gap_px": float(gap.max()) if gap.size else None, "seam_step": _most(rows, "seam_step"), "shimmer_px": _most(rows, "shimmer_px"),
            "memory": sum(int(r["memory"]) for r in rows) / 2**20}


def _num(v: float, unit: str) -> str:
    if unit == "of the sampled receivers":
        return f"{100 * v:.3g} %"
    return f"{v:.4g} {unit}" if unit != "×" else f"×{v:.3g}"


def worse(tuned: Tuned) -> list[dict[str, Any]]:
    """Every measure that is worse after tuning than at the start (module docstring).

    Each entry: ``measure`` (a name of :data:`MEASURES`), ``unit``, ``before``, ``after`` and
    ``line`` (``"gap at the walls' foot: 39.3 px → 53.4 px (worse)"``).  A measure the start does
    not have (no cascade reaches the receivers, no seam) is not compared.

    Parameters
    ----------
    tuned : Tuned
        The result of :func:`aliasing.tune.tune`.

    Example
    -------
    >>> from aliasing import setups
    >>> from aliasing.tune import tune
    >>> s = setups.build("godot", {"directional_shadow_max_distance": 200}, sun="15..60")
    >>> [w["line"] for w in worse(tune(s, receivers=(1, 100)))]
    ["gap at the walls' foot over the receivers: 29.52 px → 31.65 px (worse)", 'seam step: ×2.53 → ×3.2 (worse)']
    """
    if not isinstance(tuned, Tuned):
        raise ValueError(f"tuned must be the result of aliasing.tune.tune, got {type(tuned).__name__}")
    a, b = _values(tuned, "before"), _values(tuned, "after")
    out = []
    for name, words, unit in MEASURES:
        before, after = a[name], b[name]
        if before is None or after is None or not after > before * (1 + 1e-9) + 1e-12:
            continue
        out.append({"measure": name, "unit": unit, "before": before, "after": after,
                    "line": f"{words}: {_num(before, unit)} → {_num(after, unit)} (worse)"})
    return out


def changes_text(tuned: Tuned) -> list[str]:
    """One line per changed setting: ``key: before → after [unit]`` (the engine's units; a value the engine derives, None, in words).

    Example
    -------
    >>> from aliasing import setups
    >>> from aliasing.tune import tune
    >>> s = setups.build("babylon", {"lambda": 0.7}, sun="15..60")
    >>> changes_text(tune(s, receivers=(1, 200), keep=("bias", "normalBias", "filteringQuality", "numCascades", "mapSize")))
    ['lambda: 0.7 → 0.9132', 'shadowMaxZ: unset (the engine derives it) → 200.0 [world units]']
    """
    if not isinstance(tuned, Tuned):
        raise ValueError(f"tuned must be the result of aliasing.tune.tune, got {type(tuned).__name__}")
    def value(v: Any) -> str:
        return "unset (the engine derives it)" if v is None else repr(v)

    return [f"{c['key']}: {value(c['before'])} → {value(c['after'])}" + (f" [{c['unit']}]" if c["unit"] else "") for c in tuned.changes]
