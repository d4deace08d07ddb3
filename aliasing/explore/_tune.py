"""The tuned settings as the camera and the limits move: :func:`aliasing.tune.tune` behind controls.

For an engine whose profile declares tunable settings, the camera (near, far, vertical fov,
aspect, rows), the sun band, the receivers' depths and the limits (texel budget, steepest
acne-free slope, largest gap, a moving camera) set the search; the panel shows the worst error
per cascade of the engine's defaults and of the tuned settings, the settings that changed, the
limits that bind and the snippet's first lines.
"""

from __future__ import annotations

import math

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from .. import setups
from ..tune import tune
from . import widget as w

BUDGETS = [(f"{k} × {r}²", k * r * r) for k, r in ((1, 2048), (2, 2048), (3, 2048), (4, 1024), (4, 2048), (4, 4096))]


def _engines() -> list[str]:
    out = []
    for e in setups.ENGINES:
        try:
            if setups.get(e).tunable:
                out.append(e)
        except ValueError:
            continue
    return out


def compute(engine: str, near: float, far: float, fov: float, aspect: float, height: int, sun_low: float, sun_high: float,
            receivers_near: float, receivers_far: float, budget: int, max_slope: float, max_gap_px: str, moving: bool,
            keep_budget_shape: bool, front_faces: bool = True) -> dict[str, Any]:
    """The tuned result for the controls' values.

    Parameters
    ----------
    engine : str
        An engine whose profile declares tunable settings.
    near, far : float
        The camera's near and far [world units].
    fov : float
        Vertical field of view [deg].
    aspect : float
        Width/height.
    height : int
        Image rows [pixels].
    sun_low, sun_high : float
        The sun band [deg above the ground].
    receivers_near, receivers_far : float
        The receivers' eye depths [world units].
    budget : int
        Texels of all maps.
    max_slope : float
        The steepest receiver kept free of acne [deg from the ground].
    max_gap_px : str
        The largest gap [px] as text (empty or ``inf``: no limit).
    moving : bool
        A moving camera (no shimmer).
    keep_budget_shape : bool
        Keep the engine's default count and size (only the splits and biases searched).
    front_faces : bool
        Front faces cast (three.js: ``material.shadowSide = FrontSide``), so the ground can acne.

    Example
    -------
    >>> d = compute("threejs", 0.1, 500.0, 50.0, 16 / 9, 1080, 15.0, 60.0, 1.0, 200.0, 4 * 2048 * 2048, 10.0, "", False, True)
    >>> d["changed"]["customSplitsLambda"], round(d["objective"], 2)
    (0.9132, 5.33)
    """
    settings: dict[str, Any] = {}
    if engine == "threejs":
        settings = {"cascades": 4, "shadowMapSize": 2048, **({"material.shadowSide": "FrontSide"} if front_faces else {})}
    cam = setups.Camera(float(near), float(far), float(fov), float(aspect), int(height))
    lo, hi = sorted((float(sun_low), float(sun_high)))
    start = setups.build(engine, settings, cam, setups.Sun((lo, hi)))
    gap = str(max_gap_px).strip()
    limit = math.inf if gap in ("", "inf", "none") else float(gap)
    kept = tuple(t.key for t in start.profile.tunable if t.role in ("cascades", "size")) if keep_budget_shape else ()
    t = tune(start, receivers=(float(receivers_near), float(receivers_far)), max_texels=int(budget), max_gap_px=limit,
             max_slope=float(max_slope), moving=bool(moving), keep=kept)
    return {"engine": engine, "title": start.profile.title, "before": t.before.error, "after": t.measure.error, "objective": t.objective,
            "objective_before": t.before.objective, "changed": dict(t.changed), "binding": list(t.binding), "feasible": t.feasible,
            "snippet": t.snippet(), "gap_px": float(np.nanmax(t.measure.gap_px, initial=0.0)), "splits": [*t.setup.pipeline.near_i,
                                                                                                             t.setup.pipeline.far_i[-1]]}


def draw(fig: Figure, d: dict[str, Any]) -> None:
    """Worst error per cascade, defaults against tuned (left); the changed settings and the binding limits (right)."""
    a, b = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.1, 1.0]})
    n = max(len(d["before"]), len(d["after"]))
    for j, (key, label, color) in enumerate((("before", "defaults", "0.6"), ("after", "tuned", "C0"))):
        v = np.asarray(d[key], float)
        x = np.arange(v.size) + (j - 0.5) * 0.4
        a.bar(x, np.nan_to_num(v), 0.4, color=color, label=f"{label}: worst {np.nanmax(v):.3g}")
        for xi in x[np.isnan(v)]:  # a cascade no receiver uses
            a.text(xi, 0.02, "no receivers", rotation=90, ha="center", va="bottom", fontsize=6, color=color, transform=a.get_xaxis_transform())
    a.set_yscale("log")
    w.readable_log_ticks(a.yaxis)
    a.set(xlabel="cascade", xticks=range(n), ylabel="pixels per texel (error)", title="worst error per cascade over the receivers")
    a.legend(fontsize=7)
    b.axis("off")
    lines = [f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}" for k, v in d["changed"].items()] or ["(the defaults are best)"]
    lines += ["", "binding: " + (", ".join(d["binding"]) or "none") + ("" if d["feasible"] else "  (not all met)"),
              f"gap: {d['gap_px']:.3g} px", "splits: " + ", ".join(f"{c:.3g}" for c in d["splits"])]
    b.text(0.0, 1.0, "\n".join(lines), va="top", family="monospace", fontsize=8, transform=b.transAxes)
    b.set_title("tuned settings", fontsize=9)
    fig.suptitle(f"{d['title']}: {d['objective_before']:.3g} → {d['objective']:.3g} px/texel", fontsize=9)
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.15, top=0.84, wspace=0.15)


class TuneExplorer(w.Explorer):
    """Camera, sun, receivers and limits → the tuned settings and the error before and after."""

    title = "What to set: the engine's own settings, tuned as the camera and the limits move"
    figsize = (9.5, 3.8)

    def make_controls(self) -> dict:
        engines = _engines()
        return {
            "engine": w.dropdown("engine", engines, engines[0] if engines else None),
            "near": w.log_slider("near", 0.1, 0.01, 10.0),
            "far": w.log_slider("far", 500.0, 20.0, 1e4),
            "fov": w.slider("fov [deg]", 50.0, 20.0, 120.0),
            "aspect": w.log_slider("aspect", 16 / 9, 0.25, 4.0),
            "height": w.widgets.IntText(value=1080, description="rows [px]", style={"description_width": "initial"}),
            "sun_low": w.slider("sun low [deg]", 15.0, 1.0, 90.0),
            "sun_high": w.slider("sun high [deg]", 60.0, 1.0, 90.0),
            "receivers_near": w.log_slider("receivers from", 1.0, 0.01, 100.0),
            "receivers_far": w.log_slider("receivers to", 200.0, 10.0, 1e4),
            "budget": w.dropdown("texels", BUDGETS, 4 * 2048 * 2048),
            "max_slope": w.slider("acne-free to slope [deg]", 10.0, 0.0, 60.0),
            "max_gap_px": w.text("max gap [px]", "", "inf"),
            "moving": w.widgets.Checkbox(value=False, description="moving camera"),
            "keep_budget_shape": w.widgets.Checkbox(value=True, description="keep count and size"),
        }

    compute = staticmethod(compute)
    draw = staticmethod(draw)

