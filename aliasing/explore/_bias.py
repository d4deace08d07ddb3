"""Depth bias per cascade: an engine preset's bias against the derived minimum, and what it costs.

For a cascade setup (practical splits, one uniform map per cascade) and a light at a given
elevation above the ground, :func:`aliasing.bias.cascades.cascade_bias` gives per cascade the
ground's minimal bias, the preset's bias and the lit gap; the left panel draws, per cascade,
the minimal depth bias over the receiver angle θ (worst azimuth, :func:`aliasing.bias.plane_bias`
with the preset's filter) against the preset's rule
(:func:`aliasing.bias.presets.equivalent_depth`): where the preset's curve is below, those
surfaces acne.  A view of ``aspect`` ≠ 1 (width/height, fov 60° vertical) fits each cascade's
map to a wider (or taller) slice: its texels grow across the view, and so does a bias
that follows the larger texel side.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from ..bias import presets
from ..bias.cascades import cascade_bias
from . import widget as w

ANGLES = np.linspace(0.0, 88.0, 89)
RESOLUTIONS = [(f"{r}²", r) for r in (512, 1024, 2048, 4096)]


def compute(preset: str, elevation: float, k: int, lam: float, far: float, resolution: int, image: int, aspect: float = 1.0) -> dict[str, Any]:
    """Rows of :func:`aliasing.bias.cascades.cascade_bias` and, per cascade, the needed and offered bias over θ.

    Parameters
    ----------
    preset : str
        A bias preset (:data:`aliasing.bias.presets.PRESETS`).
    elevation : float
        Light elevation above the ground, ahead of the viewer [deg], in (0, 90).
    k : int
        Cascades.
    lam : float
        λ of the practical splits.
    far : float
        Shadow distance [world units] (near 0.1, fov 60° vertical).
    resolution : int
        Texels per side of each cascade.
    image : int
        Pixels across the view, top to bottom (the image's rows).
    aspect : float
        Image width/height, > 0 (1: the square view).

    Example
    -------
    >>> d = compute("bevy", 45.0, 3, 0.5, 100.0, 1024, 1080)
    >>> len(d["rows"]), d["need"].shape
    (3, (3, 89))
    >>> wide = compute("bevy", 45.0, 3, 0.5, 100.0, 1024, 1080, aspect=2.0)   # texels twice as wide, as tall as before
    >>> [round(w["texel_s"] / r["texel_s"], 12) for w, r in zip(wide["rows"], d["rows"])]
    [2.0, 2.0, 2.0]
    """
    rows = cascade_bias(0.1, float(far), 60.0, f"gamma:{float(elevation)}", preset, k=int(k), resolution=int(resolution), image=int(image),
                        lam=float(lam), aspect=aspect)
    p = presets.get(preset)
    az = np.radians(np.arange(0.0, 91.0, 5.0))
    th = np.radians(ANGLES)[:, None]
    need, have = [], []
    for r in rows:
        n = 0.5 * p.pcf * np.tan(th) * (np.abs(np.cos(az)) * r["texel_s"] + np.abs(np.sin(az)) * r["texel_t"])
        o = presets.equivalent_depth(p, max(r["texel_s"], r["texel_t"]), np.degrees(th), np.degrees(az), int(resolution))
        worst = np.argmax(n - o, axis=1)  # the azimuth where the rule falls shortest
        need.append(n[np.arange(len(ANGLES)), worst])
        have.append(o[np.arange(len(ANGLES)), worst])
    return {"preset": p.name, "engine": p.engine, "partial": p.partial, "elevation": float(elevation), "aspect": float(aspect), "rows": rows,
            "need": np.array(need), "have": np.array(have)}


def draw(fig: Figure, d: dict[str, Any]) -> None:
    """Needed vs offered bias over θ per cascade (left); ground margin and lit gap per cascade (right)."""
    a, b = fig.subplots(1, 2)
    for i, r in enumerate(d["rows"]):
        a.plot(ANGLES, d["need"][i], color=f"C{i}", lw=1.6, label=f"cascade {i}: needed")
        a.plot(ANGLES, d["have"][i], color=f"C{i}", lw=1.0, ls="--", label=f"cascade {i}: {d['preset']}")
    a.axvline(d["rows"][0]["ground_angle"], color="0.5", lw=0.8, ls=":")
    a.set_yscale("log")
    a.set(xlabel="receiver angle θ from the light [deg] (dotted: the ground)", ylabel="depth bias [world units]",
          title="minimal bias (solid) and the preset's (dashed)")
    a.legend(fontsize=6, ncol=2)
    i = np.arange(len(d["rows"]))
    margin = np.array([r["margin"] for r in d["rows"]])
    b.bar(i - 0.2, margin, width=0.4, color=["C3" if m < 1 else "C0" for m in margin], label="ground margin (bias / minimum)")
    b.bar(i + 0.2, [r["gap_px"] for r in d["rows"]], width=0.4, color="0.6", label="lit gap [pixels]")
    b.axhline(1.0, color="k", lw=0.8)
    top = max(float(margin.max()), max(r["gap_px"] for r in d["rows"]), 1.0)
    b.set_ylim(0.0, top * 1.3)  # headroom: the legend above the bars, however tall they are
    b.set(xlabel="cascade", xticks=i, title="below 1: the ground acnes")
    b.legend(fontsize=7)
    note = f" (not modelled: {d['partial']})" if d["partial"] else ""
    wide = "" if d.get("aspect", 1.0) == 1.0 else f", aspect = {d['aspect']:.3g}"
    fig.suptitle(f"{d['engine']}, light {d['elevation']:g}° above the ground{wide}{note}", fontsize=9)
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.15, top=0.84, wspace=0.25)


class BiasExplorer(w.Explorer):
    """Preset, light elevation, cascades, far, aspect → needed vs offered bias, ground margin and lit gap per cascade."""

    title = "Depth bias per cascade (derived minimum against the engines' rules)"
    figsize = (9.5, 3.8)

    def make_controls(self) -> dict:
        return {
            "preset": w.dropdown("preset", list(presets.PRESETS), "bevy"),
            "elevation": w.slider("light elevation [deg]", 45.0, 5.0, 85.0),
            "k": w.widgets.IntSlider(value=4, min=1, max=6, description="cascades", continuous_update=False),
            "lam": w.slider("λ", 0.5, 0.0, 1.0, 0.05),
            "far": w.widgets.BoundedFloatText(value=100.0, min=1.0, max=1e5, description="far", style={"description_width": "initial"}),
            "aspect": w.log_slider("aspect", 1.0, 0.25, 4.0),
            "resolution": w.dropdown("texels per cascade", RESOLUTIONS, 2048),
            "image": w.widgets.IntText(value=1080, description="image rows [px]", style={"description_width": "initial"}),
        }

    compute = staticmethod(compute)
    draw = staticmethod(draw)
