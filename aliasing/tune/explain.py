"""Why each change of the wrong-pixel search's pick: one line per changed setting, in the engine's units.

For each setting :func:`aliasing.tune.pixels.refine`'s pick changed, the pick with that setting alone put back to the
start's value is measured on the search's own sample, and the line names what the change fixes and what it costs:
``"shadowBias 0 → 0.1486: wrong pixels 35.6 % → 0.798 %, acne 21.8 % → 0 %, ..."``.
"""

from __future__ import annotations

import math
from typing import Any

from ..frames import seen
from ..setups import Setup
from .measure import Limits
from .pixels import MEMORY, Seen, _key, _Pixels, refine  # noqa: F401 - refine for the example


def why(result: Seen, start: Setup, lim: Limits) -> list[dict]:
    """For each setting the pick changed: what it fixes and what it costs, that setting alone put back to the start's value.

    Each entry: ``key``, ``before``, ``after``, ``unit`` and ``line`` (``"shadowBias 0.001 → 0.05: acne 12 % → 0.04 %, lost
    shadow 0.1 % → 2 %"``), the numbers the pick's with the setting at the start's value (the first) and at the pick's (the
    second), on the search's sample; a setting that acts only with another changed one says so.

    Examples
    --------
    >>> from aliasing import setups
    >>> from aliasing.tune.measure import limits
    >>> s = setups.build("playcanvas", {"shadowResolution": 1024, "shadowBias": 0.0}, "near=0.5,far=40,fov=60,aspect=2,height=600", "40")
    >>> lim = limits(s)
    >>> r = refine(s, s, lim, keep=frozenset(k for k in s.settings if k != "shadowBias"), height=32, suns=1)
    >>> [line["line"].split(":")[0] for line in why(r, s, lim)]
    ['shadowBias 0 → 0.09998']
    """
    if not isinstance(result, Seen) or not isinstance(start, Setup) or not isinstance(lim, Limits):
        raise ValueError("result must be a Seen (refine(...)), start an aliasing.setups.Setup and lim a Limits (limits(...))")
    pick = result.setup
    px = _Pixels(start, lim, result.where, None, frozenset())
    px.cache.update((_key(p.settings), p) for p in result.points)  # the search measured these on the same sample
    after = px.point(pick.settings)
    out = []
    with seen.remember(MEMORY):
        for key, value in pick.settings.items():
            old = start.settings.get(key)
            if old == value:
                continue
            unit = pick.profile.setting(key).unit
            head = f"{key} {_value(old)} → {_value(value)}" + (f" [{unit}]" if unit else "")
            back = px.point({**pick.settings, key: old})
            if back is None or after is None:
                line = f"{head}: acts together with the other changes (put back alone, the engine refuses it or the frame is not predicted)"
            else:
                parts = [f"{name} {_pct(getattr(back, a))} → {_pct(getattr(after, a))}" for a, name in _AXES[:4]
                         if abs(getattr(back, a) - getattr(after, a)) >= 5e-5]
                for a, name, u in (("px_per_texel", "worst px/texel", ""), ("memory", "memory", " MiB")):
                    va, vb = getattr(back, a), getattr(after, a)
                    if not math.isclose(va, vb, rel_tol=1e-6):
                        parts.append(f"{name} {va:.3g}{u} → {vb:.3g}{u}")
                line = f"{head}: " + (", ".join(parts) if parts else "no change on the sample alone (it acts with the other changes)")
            out.append({"key": key, "before": old, "after": value, "unit": unit, "line": line})
    return out


_AXES = (("wrong", "wrong pixels"), ("acne", "acne"), ("false_shadow", "false shadow"), ("lost_shadow", "lost shadow"))


def _pct(v: float) -> str:
    return f"{100 * v:.3g} %"


def _value(v: Any) -> str:
    return f"{v:g}" if isinstance(v, float) else str(v)
