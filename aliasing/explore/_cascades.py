"""Cascaded (z-partitioned) shadow maps: split methods and engine presets, budgets, allocations.

The split distances come from :func:`aliasing.partitioning.partitions` (self-similar
log splits, Lloyd et al. 2006 eqs. 15–16 / Lloyd et al. 2007 eqs. 80–82; the PSSM splits
of Zhang et al. 2006; the engines' presets with their padding and overlaps), each
partition's S̄ and, for a texel budget shared by an allocation (equal squares as engines
ship, or Lloyd 2007 eq. 83's error-based shares), its resolution and worst error over
light directions from :func:`aliasing.budgets.splits_report`, for a view of any ``aspect``
(width/height, ``fov`` vertical: :class:`aliasing.View`): the splits do not depend on it, each
partition's map is fitted to its wider slice.
"""

from __future__ import annotations

import inspect
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Polygon
from matplotlib.ticker import FuncFormatter

from .. import budgets, partitioning
from . import widget as w
from ..view import tan_theta

#: Light directions the worst error is taken over (equal solid angle over the whole sphere).
SLOTS = 8  # partitions drawn without a new layout (the k slider's maximum)
LIGHTS = "sphere:256"
BUDGETS = [(f"{s}² ({s * s / 2**20:g} Mi)", s * s) for s in (512, 1024, 2048, 4096, 8192)]


def method_takes_lambda(method: str) -> bool:
    """Whether a split method has a λ parameter (``lam``)."""
    entry = partitioning.SPLIT_METHODS[method.lower()]
    return "lam" in inspect.signature(entry.func).parameters


def compute(method: str, k: int, lam: float, near: float, far: float, fov: float, warp: str, budget: int, allocation: str, res_image: int,
            aspect: float = 1.0) -> dict[str, Any]:
    """Splits, per-partition S̄, resolution and worst error of a cascade setting.

    Parameters
    ----------
    method : str
        Split method or engine preset (:data:`aliasing.partitioning.SPLIT_METHODS`).
    k : int
        Number of partitions.
    lam : float
        λ of the practical split (used by the methods that take it), in [0, 1].
    near, far : float
        Eye near and far (shadow) distance [world units].
    fov : float
        Full vertical field of view [deg].
    warp : str
        Warp inside each partition (``Standard``, ``P``, ``LogP``, a warping rule, …).
    budget : int
        Texels over all maps.
    allocation : str
        :data:`aliasing.budgets.ALLOCATIONS` name.
    res_image : int
        Image resolution [pixels per side; rows of a non-square image, square pixels].
    aspect : float
        Image width/height, > 0 (1: the square view of the papers).

    Returns
    -------
    dict
        ``rows`` (:func:`aliasing.budgets.splits_report`'s rows), ``near_i``, ``far_i``,
        ``S_max`` (per partition), ``res_s``, ``res_t``, ``error`` (per partition) and
        ``worst`` (the largest error over partitions and :data:`LIGHTS`) [px/texel].

    Example
    -------
    >>> d = compute("log", 4, 0.5, 1.0, 1000.0, 60.0, "P", 4096**2, "error", 1024)
    >>> d["far_i"].round(3).tolist()
    [5.623, 31.623, 177.828, 1000.0]
    >>> wide = compute("log", 4, 0.5, 1.0, 1000.0, 60.0, "P", 4096**2, "error", 1024, aspect=16 / 9)
    >>> bool((wide["far_i"] == d["far_i"]).all() and (wide["S_max"] > d["S_max"]).all())   # the same splits, wider maps
    True
    """
    params = {"lam": float(lam)} if method_takes_lambda(method) else {}
    rows = budgets.splits_report(method, float(near), float(far), int(k), fov=float(fov), aspect=aspect, light=LIGHTS, warp=warp,
                                 budget=float(budget), res_image=float(res_image), allocations=(allocation,), **params)
    parts, total = rows[:-1], rows[-1]
    col = lambda key: np.array([r[key] for r in parts], float)  # noqa: E731
    return {
        "method": method, "k": len(parts), "lam": float(lam) if params else None, "near": float(near), "far": float(far),
        "fov": float(fov), "aspect": float(aspect), "warp": warp, "budget": int(budget), "allocation": allocation, "res_image": int(res_image),
        "rows": rows, "near_i": col("near"), "far_i": col("far"), "S_max": col("S_max"),
        "res_s": col(f"res_s[{allocation}]"), "res_t": col(f"res_t[{allocation}]"), "error": col(f"max_error[{allocation}]"),
        "worst": float(total[f"max_error[{allocation}]"]), "S_total": float(total["S_max"]),
    }


def _band(lo: float, hi: float, tan: float) -> np.ndarray:
    """Outline (60, 2) of the frustum between depths lo and hi in the side view (z, y)."""
    z = np.geomspace(lo, hi, 30)
    return np.column_stack([np.concatenate([z, z[::-1]]), np.concatenate([-z * tan, (z * tan)[::-1]])])


def draw(fig: Figure, d: dict[str, Any]) -> dict:
    """The partitions on the frustum (side view, log depth) and per-partition S̄, resolution, error.

    Artists for ``SLOTS`` partitions (more if k is larger) are made once and the unused
    ones hidden, so that changing k is an update in place, not a new layout.  Returns the
    artists for :func:`redraw`.
    """
    a, b = fig.subplots(1, 2)
    slots = max(d["k"], SLOTS)
    frustum = a.add_patch(Polygon(np.zeros((3, 2)), closed=True, fc="0.93", ec="none"))
    bands = [a.add_patch(Polygon(np.zeros((3, 2)), closed=True, fc=f"C{i % 10}", alpha=0.45, lw=0)) for i in range(slots)]
    planes = [a.axvline(1.0, color=f"C{i % 10}", lw=0.8) for i in range(slots)]
    a.set_xscale("log")
    w.readable_log_ticks(a.xaxis)
    a.yaxis.set_major_formatter(FuncFormatter(lambda y, pos: w.short_number(y)))  # far up to 10¹²: short labels
    a.set(xlabel="z [world units] (log)", ylabel="y", title="partitions on the frustum (side view)")
    i = np.arange(1, slots + 1)
    bars = b.bar(i, np.ones(slots), color=[f"C{j % 10}" for j in range(slots)])
    b.axhline(1.0, color="0.5", lw=0.8, ls="--")
    b.set(xlabel="partition", ylabel="worst error m (texel/pixel width)")
    texts = [b.text(i[j], 0.0, "", ha="center", va="bottom", fontsize=7) for j in range(slots)]
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.15, top=0.84, wspace=0.25)
    artists = {"a": a, "b": b, "frustum": frustum, "bands": bands, "planes": planes, "bars": bars, "texts": texts, "slots": slots,
               "suptitle": fig.suptitle("", fontsize=10)}
    redraw(artists, d)
    return artists


def redraw(artists: dict, d: dict[str, Any]) -> bool:
    """New data into :func:`draw`'s artists; False (draw anew) when k exceeds their slots."""
    k = d["k"]
    if k > artists["slots"]:
        return False
    a, b = artists["a"], artists["b"]
    t = tan_theta(d["fov"])
    artists["frustum"].set_xy(_band(d["near"], d["far"], t))
    for j, (band, plane) in enumerate(zip(artists["bands"], artists["planes"])):
        band.set_visible(j < k)
        plane.set_visible(j < k)
        if j < k:
            band.set_xy(_band(d["near_i"][j], d["far_i"][j], t))
            plane.set_xdata([d["far_i"][j]] * 2)
    a.set_xlim(d["near"], d["far"] * 1.05)
    a.set_ylim(-d["far"] * t * 1.05, d["far"] * t * 1.05)
    for j, (bar, text) in enumerate(zip(artists["bars"], artists["texts"])):
        bar.set_visible(j < k)
        text.set_visible(j < k)
        if j < k:
            bar.set_height(d["error"][j])
            text.set_position((j + 1, d["error"][j]))
            side = f"{d['res_s'][j]:.0f}²" if d["res_s"][j] == d["res_t"][j] else f"{d['res_s'][j]:.0f}×{d['res_t'][j]:.0f}"
            text.set_text(f"S̄ {w.short_number(d['S_max'][j])}\n{side}")
            text.set_fontsize(7 if k <= 5 else 6)  # eight labels side by side fit at 6 pt
    b.set_xlim(0.4, k + 0.6)  # as a bar chart of k bars autoscales, whatever the hidden slots
    b.set_xticks(np.arange(1, k + 1))
    b.set_ylim(0, max(d["error"].max(), 1.0) * 1.35)
    b.set_title(f"{d['allocation']}: worst {d['worst']:.3g} over {LIGHTS}", fontsize=10)
    lam = f", λ = {d['lam']:g}" if d["lam"] is not None else ""
    wide = "" if d.get("aspect", 1.0) == 1.0 else f", aspect {d['aspect']:.3g}"
    artists["suptitle"].set_text(f"{d['method']} k = {d['k']}{lam}, [{d['near']:g}, {d['far']:g}]{wide}, warp {d['warp']}, "
                                 f"budget {d['budget']:,} texels, image {d['res_image']}")
    return True


class CascadesExplorer(w.Explorer):
    """Cascade settings → splits, per-partition S̄ and resolution, worst error over light directions."""

    title = "Cascades (Lloyd et al. 2007 eqs. 80–83, Zhang et al. 2006, engine presets)"
    figsize = (9.5, 3.8)

    def make_controls(self) -> dict:
        return {
            "method": w.dropdown("split", sorted(partitioning.SPLIT_METHODS), "practical"),
            "k": w.widgets.IntSlider(value=4, min=1, max=8, description="k", continuous_update=False),
            "lam": w.slider("λ", 0.5, 0.0, 1.0, 0.05),
            "near": w.widgets.BoundedFloatText(value=1.0, min=1e-6, max=1e9, description="near", style={"description_width": "initial"}),
            "far": w.widgets.BoundedFloatText(value=1000.0, min=1e-6, max=1e12, description="far", style={"description_width": "initial"}),
            "fov": w.slider("fov [deg]", 60.0, 5.0, 150.0),
            "aspect": w.log_slider("aspect", 1.0, 0.25, 4.0),
            "warp": w.text("warp", "Standard", "Standard, P, LogP, lispsm, …"),
            "budget": w.dropdown("texel budget", BUDGETS, 4096 * 4096),
            "allocation": w.dropdown("allocation", list(budgets.ALLOCATIONS), "equal"),
            "res_image": w.widgets.IntText(value=1024, description="image res. [px]", style={"description_width": "initial"}),
        }

    # the module's functions, so that tests and notebooks can call them without a widget
    compute = staticmethod(compute)
    draw = staticmethod(draw)
    redraw = staticmethod(redraw)
