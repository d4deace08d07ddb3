"""Beyond the papers: each warping rule's worst and mean S̄ over light directions on a grid of frusta.

The pyramid rules (docs/warping_rule.md).  For f/n = 10, 100, 1e3, 1e4, 1e5 and fov = 20°, 50°,
80°, 120° (near = 1, directional light, 2000 equal-solid-angle hemisphere directions; the
vertex model of :mod:`aliasing.directional`):

* top row: max over directions of S̄ divided by Standard's max (goal: ≤ 1); maxima are taken
  over the 2000 directions and a dense set near the view axis, where Standard's supremum lies
  for fov ≥ 50° (every rule whose η tends to −1 there ties with Standard: 1.0000);
* bottom row: mean of S̄ divided by the mean of the S-optimal warp of the same
  parameterization, Sopt (perspective) or LogSopt (log+perspective) (goal: ≤ 1.1).

Rules: P and LogP (Lloyd 2007 eq. 79), LiSPSM (1/sin γ), GMNPR, GLPR (Zhang 2007) and the new
pyramid / pyramid-log rules of :mod:`aliasing.adaptive_warping`.  Cells are annotated; a
cell meeting its goal has a white frame.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.adaptive_warping import RULES, grid_study
from aliasing.plotting import save, subplots

NAME = "warping-rule-grid"
LIGHT = "hemisphere:2000"


def data(light: str = LIGHT) -> dict[str, np.ndarray]:
    """Long-format columns: rule index, f/n, fov, max_ratio, mean_ratio (one row per cell)."""
    r = grid_study(light=light)
    i, j, k = np.meshgrid(np.arange(len(RULES)), np.arange(r["f_over_n"].size), np.arange(r["fov"].size), indexing="ij")
    return {
        "rule_index": i.ravel().astype(float),
        "f_over_n": r["f_over_n"][j.ravel()],
        "fov": r["fov"][k.ravel()],
        "max_over_standard_max": r["max_ratio"].ravel(),
        "mean_over_opt_mean": r["mean_ratio"].ravel(),
    }


def main(out_dir: Path, light: str = LIGHT) -> list[Path]:
    from matplotlib.colors import LogNorm

    cols = data(light)
    fns, fovs = np.unique(cols["f_over_n"]), np.unique(cols["fov"])
    shape = (len(RULES), fns.size, fovs.size)
    grids = {"max_over_standard_max": (cols["max_over_standard_max"].reshape(shape), 1.0, "max S / Standard's max"),
             "mean_over_opt_mean": (cols["mean_over_opt_mean"].reshape(shape), 1.1, "mean S / S-optimal mean")}
    from matplotlib.patches import Rectangle

    fig, axes = subplots(len(RULES), nrows=2, width=2.1, height=2.2)
    for row, (key, (vals, goal, label)) in enumerate(grids.items()):
        for c, rule in enumerate(RULES):
            ax = axes[row, c]
            v = vals[c]
            ax.imshow(np.clip(v, 0.3, 1e4), norm=LogNorm(0.3, 1e4), cmap="RdYlGn_r", origin="lower", aspect="auto")
            for a in range(fns.size):
                for b in range(fovs.size):
                    ok = v[a, b] <= goal * (1 + 1e-6)  # 1e-6: equal to Standard's max up to rounding
                    text = f"{v[a, b]:.3f}" if v[a, b] < 10 else f"{v[a, b]:.3g}" if v[a, b] < 100 else f"{v[a, b]:.0e}".replace("e+0", "e").replace("e+", "e")
                    if 0.995 < v[a, b] < 1.005:
                        text = f"{v[a, b]:.4f}"  # so that 1.0029 (above Standard's max) does not read as 1
                    ax.text(b, a, text, ha="center", va="center", fontsize=5.5, fontweight="bold" if ok else "normal")
                    if ok:
                        ax.add_patch(Rectangle((b - 0.5, a - 0.5), 1, 1, fill=False, ec="white", lw=1.2))
            ax.set_xticks(range(fovs.size), [f"{x:g}" for x in fovs], fontsize=6)
            ax.set_yticks(range(fns.size), [f"{x:g}" for x in fns], fontsize=6)
            ax.grid(False)
            if row == 0:
                ax.set_title(rule, fontsize=9)
            if c == 0:
                ax.set_ylabel(f"{label}\nf/n", fontsize=7)
            if row == 1:
                ax.set_xlabel("fov [deg]", fontsize=7)
    fig.suptitle("Warping rules over f/n × fov: worst case vs Standard (goal ≤ 1) and mean vs S-optimal (goal ≤ 1.1); framed cells meet the goal", fontsize=9)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
