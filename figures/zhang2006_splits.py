"""Zhang et al. 2006 (PSSM), §3.3: split positions C_0 = n < C_1 < … < C_m = f of six split schemes.

Parameters: n = 1, f = 800 (the paper's experiments: "near = 1m and far = 800m are
configured" for Robot War, Huge Chessboard and Knights; Mining Terrain uses 1000 m) and
m = 3 ("PSSM(3) achieves the best tradeoff", §3.6, §4) and m = 4 (the most the paper
times, Fig. 8).  One horizontal "ladder" per scheme on a log depth axis, the planes as rungs,
the interior planes labelled; the largest depth ratio max f_i/n_i of a split (what Lloyd
2006's S̄ grows with, eq. 12) at the right.  All positions come from
:func:`aliasing.partitioning.split_distances`:

* ``log``: C_i = n (f/n)^(i/m), Lloyd 2006 eqs. 15–16 (equal f_i/n_i);
* ``uniform``: C_i = n + (f − n) i/m;
* ``practical`` (λ = 0.5): the average of the two, the "practical split" engines ship.  It is
  **not** in the supplied Zhang 2006 text (docs/ERRATA.md P1), only in the published version
  Lloyd 2007 cites and in GPU Gems 3;
* ``pssm``: eqs. 1–3 as printed, C_i = min(n + (f − n)/γ^(m−i) + δ_bias, f), with γ = 2 and
  δ_bias = 0 (the text gives no value for either): the distances from the near plane double;
* ``pssm-transition``: eq. 4 (consistent aliasing transition, resolution ratio λ = 2 as in
  the text) solved for uniform maps per split: each split half as long as the one before;
* ``pssm-transition-log``: eq. 4 with logarithmic maps per split: ln(f_i/n_i) halves.

What the text says and this figure shows:

* "shadow map with higher resolution is used for the part closer to the viewer": eq. 4
  with λ = 2 halves E1 from one split to the next, so the farther (coarser) maps must cover
  *shorter* stretches (uniform: 1 | 457.6 | 685.9 | 800) or smaller depth ratios (log:
  1 | 45.6 | 307.9 | 800).  Eq. 3's geometric growth of C_i − n goes the other way
  (1 | 200.75 | 400.5 | 800), so eq. 4 cannot be "combined with eq. 3" (the text's last
  step; no γ > 1 satisfies both, see the notes behind docs/ERRATA.md).
* Every scheme except ``log`` gives the nearest split a huge depth ratio (m = 3: 138 for
  practical, 201 for pssm, 267 for uniform, 458 for pssm-transition, against 9.28 for log):
  in Lloyd 2006's metric the first split dominates the error.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.partitioning import split_distances
from aliasing.plotting import save, subplots

NAME = "zhang2006-splits"
NEAR, FAR = 1.0, 800.0  # Zhang 2006 §4: near = 1 m, far = 800 m
SPLITS = (3, 4)
METHODS = {  # column → (split method, parameters, label)
    "log": ("log", {}, "log (Lloyd eqs. 15–16)"),
    "uniform": ("uniform", {}, "uniform"),
    "practical": ("practical", {"lam": 0.5}, "practical, λ = 0.5"),
    "pssm": ("pssm", {"ratio": 2.0, "bias": 0.0}, "eqs. 1–3, γ = 2, δ = 0"),
    "pssm-transition": ("pssm-transition", {"resolution_ratio": 2.0}, "eq. 4, uniform maps, λ = 2"),
    "pssm-transition-log": ("pssm-transition-log", {"resolution_ratio": 2.0}, "eq. 4, log maps, λ = 2"),
}


def data(splits: tuple[int, ...] = SPLITS) -> dict[str, np.ndarray]:
    """Rows (m, i) for each m, i = 0 … m; one column of C_i per scheme."""
    m_col = np.concatenate([np.full(m + 1, float(m)) for m in splits])
    i_col = np.concatenate([np.arange(m + 1, dtype=float) for m in splits])
    cols: dict[str, np.ndarray] = {"m": m_col, "i": i_col}
    for key, (method, params, _) in METHODS.items():
        cols[key] = np.concatenate([split_distances(method, NEAR, FAR, m, **params) for m in splits])
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, axes = subplots(nrows=len(SPLITS), width=10.0, height=3.6)
    for ax, m in zip(axes.flat, SPLITS):
        rows = cols["m"] == m
        for y, (key, (_, _, label)) in enumerate(reversed(list(METHODS.items()))):
            c = cols[key][rows]
            for i in range(m):
                ax.plot(c[i : i + 2], [y, y], lw=7, solid_capstyle="butt", color=f"C{i}", alpha=0.55)
            ax.plot(c, np.full(c.shape, y), ls="none", marker="|", ms=16, mew=1.6, color="k")
            last = None
            for v in c[1:-1]:
                if last is None or np.log10(v / last) >= 0.2:  # skip crowded labels; all planes are listed at the right
                    ax.annotate(f"{v:.1f}", (v, y), xytext=(0, 9), textcoords="offset points", ha="center", fontsize=7.5)
                    last = v
            ratio = np.max(c[1:] / c[:-1])
            ax.annotate(f"{ratio:6.1f}   " + ", ".join(f"{v:.1f}" for v in c[1:-1]), (1.01, y), xycoords=("axes fraction", "data"), va="center", fontsize=8, family="monospace")
        ax.set_yticks(range(len(METHODS)), [label for (_, _, label) in reversed(list(METHODS.values()))], fontsize=8)
        ax.set(xscale="log", xlim=(NEAR * 0.8, FAR * 1.25), ylim=(-0.6, len(METHODS) - 0.3), xlabel="eye depth z (near = 1, far = 800)")
        ax.set_title(f"m = {m} splits", fontsize=9, loc="left")
        ax.annotate("max $f_i/n_i$   interior planes $C_1 … C_{m-1}$", (1.01, len(METHODS) - 0.45), xycoords=("axes fraction", "data"), va="bottom", fontsize=7.5)
        ax.grid(True, axis="x", which="both", alpha=0.2)
        ax.grid(False, axis="y")
    fig.suptitle("Zhang et al. 2006 (PSSM): split positions, n = 1, f = 800", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
