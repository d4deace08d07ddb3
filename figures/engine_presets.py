"""Engine cascade presets: worst perspective aliasing error over light directions for a fixed texel budget.

Not a paper figure.  Every engine preset of :data:`aliasing.partitioning.SPLIT_METHODS`
in its current release (three.js CSM, Babylon.js, Ogre PSSM, Filament, bgfx, Godot 4,
Unity URP, Unreal, bgfx's current split, Bevy; their split formulas and defaults read from
public source, three.js's and Babylon.js's also run in the test suite, see docs and each
preset's ``source`` and ``release``) at its default cascade count k, with its real map extents (Ogre's padding,
bgfx's and Unreal's overlaps), and, as a reference, the logarithmic split (Lloyd 2006
eqs. 15–16; Lloyd 2007 eqs. 80–82) at the same k.

Setting (ours; engines differ): near = 0.5, far = shadow distance = 500 (f/n = 1000),
fov = 60° (θ = 30°), image 1920 px, a total budget of T = 4 × 2048² texels shared by the k
maps (also for k = 3), a Standard (uniform, orthographic) map fitted to each cascade as the
engines do, and 2000 light directions over the upper hemisphere (``hemisphere:2000``).
Metric: the maximum perspective aliasing error res_i·max(M_x/res_s, M_z/res_t) (image
pixels per texel; 1 = critical) over the cascades and the directions
(:func:`aliasing.budgets.splits_report`), for two allocations of T:

* ``equal``: what engines ship, k square maps of T/k texels each;
* ``error``: Lloyd 2007 eq. 83, texels in proportion to each cascade's S = M_x·M_z and split
  between s and t as M_x/M_z (Lloyd 2006 eqs. 13–14), recomputed for every light
  direction (per frame); every cascade then has the error res_i·√(ΣS/T), the smallest
  maximum any allocation reaches, so ``error`` is never above ``equal``.

What the figure shows (numbers in the CSV): with equal shares every preset is far above the
log split, by 2.8–23× (Bevy, whose first cascade ends at a fixed 10 units, is the best preset
at 26.5, then Ogre's λ = 0.95, close to logarithmic, at 32.4; the near-uniform presets
three.js, Filament and Babylon are worst at 167–197, against 11.5 (k = 3) and 7.46 (k = 4)
for the log split).  Their nearest cascade has a huge depth ratio
(three.js 0.5 → 86: f_1/n_1 = 173), and a uniform map's S grows with the square of it.
Error-based allocation roughly halves every preset's error (1.6–2.0×) but cannot repair the
split: the presets stay 1.7–11× above the log split, whose cascades are already balanced
(equal and error allocation agree to 0.3 %).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import budgets
from aliasing.partitioning import SPLIT_METHODS
from aliasing.plotting import save, subplots, write_table

NAME = "engine-presets"
NEAR, FAR, FOV = 0.5, 500.0, 60.0
RES_IMAGE = 1920.0
BUDGET = 4 * 2048.0**2
LIGHT = "hemisphere:2000"
WARP = "Standard"
ALLOCATIONS = ("equal", "error")
PRESETS = tuple(name for name, entry in SPLIT_METHODS.items() if entry.default_k is not None and "@" not in name)  # current releases


def _report(method: str, k: int | None, light: str) -> list[dict]:
    return budgets.splits_report(method, NEAR, FAR, k, fov=FOV, light=light, warp=WARP, budget=BUDGET, res_image=RES_IMAGE, allocations=ALLOCATIONS)


def data(light: str = LIGHT) -> dict[str, list]:
    """One row per preset: its k, split distances, S_max and worst error per allocation, and
    the same for the log split at that k (``log_`` columns)."""
    cols: dict[str, list] = {key: [] for key in ("preset", "k", "far_i", "S_max", "max_error_equal", "max_error_error", "log_far_i", "log_S_max", "log_max_error_equal", "log_max_error_error")}
    log_cache: dict[int, list[dict]] = {}
    for name in PRESETS:
        k = SPLIT_METHODS[name].default_k
        rows = _report(name, None, light)
        ref = log_cache.setdefault(k, _report("log", k, light))
        cols["preset"].append(name)
        cols["k"].append(k)
        for prefix, rep in (("", rows), ("log_", ref)):
            cols[f"{prefix}far_i"].append(";".join(f"{r['far']:.6g}" for r in rep[:-1]))
            cols[f"{prefix}S_max"].append(rep[-1]["S_max"])
            for alloc in ALLOCATIONS:
                cols[f"{prefix}max_error_{alloc}"].append(rep[-1][f"max_error[{alloc}]"])
    return cols




def main(out_dir: Path) -> list[Path]:
    cols = data()
    n = len(cols["preset"])
    x = np.arange(n)
    width = 0.2
    bars = (
        ("max_error_equal", "preset, equal shares (engines)", "C0", None),
        ("max_error_error", "preset, error-based (Lloyd 2007 eq. 83)", "C1", None),
        ("log_max_error_equal", "log split, same k, equal shares", "C0", "//"),
        ("log_max_error_error", "log split, same k, error-based", "C1", "//"),
    )
    fig, ax = subplots(width=10.0, height=4.6)
    for i, (key, label, color, hatch) in enumerate(bars):
        values = np.asarray(cols[key], dtype=float)
        pos = x + (i - 1.5) * width
        ax.bar(pos, values, width, label=label, color=color, alpha=0.45 if hatch else 0.9, hatch=hatch, edgecolor=color if hatch else "none")
        for p, v in zip(pos, values):
            ax.annotate(f"{v:.3g}", (p, v), xytext=(0, 2), textcoords="offset points", ha="center", fontsize=6.5, rotation=90, va="bottom")
    ax.axhline(1.0, color="0.3", lw=0.8, ls=":", label="critical: one texel per image pixel")
    ax.set_xticks(x, [f"{p}\nk = {k}" for p, k in zip(cols["preset"], cols["k"])], fontsize=8)
    ax.set(yscale="log", ylabel="max perspective aliasing error\n(image pixels per texel, worst direction)", xlim=(-0.6, n - 0.4), ylim=(0.7, 12 * max(cols["max_error_equal"])))
    ax.grid(False, axis="x")
    ax.legend(fontsize=8, ncols=2, loc="upper right")
    ax.set_title(
        f"Engine cascade presets: near {NEAR:g}, shadow distance {FAR:g}, fov {FOV:g}°, {int(RES_IMAGE)} px image, "
        f"{BUDGET / 2048**2:g}×2048² texels, {WARP} maps, {LIGHT.split(':')[1]} directions",
        fontsize=9,
    )
    paths = save(fig, out_dir, NAME)
    return paths + [write_table(cols, Path(out_dir) / f"{NAME}.csv", digits=10)]


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
