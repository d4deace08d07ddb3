"""Lloyd et al. 2006, Figure 10: storage factor S̄ over the number of z-partitions k, light overhead.

Caption: "The storage factor is an aggregate measure of x and z error.  This plot shows
the storage required for a varying number of z-partitions k.  As k increases, the storage
factor approaches that of the optimal, logarithmic parameterization."

Parameters: the caption and §5.3 print none for Fig. 10; we use those of Fig. 12,
f/n = 1000 (n = 1, f = 1000) and θ = 30° (fov 60°), with k = 1 … 16 and S̄ on a log axis.

Curves (the closed forms of §5.3, derived with sympy in :mod:`aliasing.symbolic.lloyd2006`
and lambdified, not retyped):

* ZP+W, eq. 18: k self-similar partitions (eqs. 15–16), each warped with
  n′ ≤ n′_LiSPSM: S̄ = k((f/n)^(1/k) − 1)/(2 tanθ);
* ZP, eq. 17: the same partitions with uniform maps (n′ = ∞), which keep the factor
  (f/n)^(1/k);
* optimal, App. C: the logarithmic parameterization, S̄ = ln(f/n)/(2 tanθ), a horizontal line.

Markers: the general vertex evaluation :func:`aliasing.schemes.evaluate` of ``ZP<k>+LiSPSM``
and ``ZP<k>`` at the overhead light: they coincide with eqs. 18 and 17 (to 1e-12).

What the text says and this figure shows: "as k increases, S̄_ZP+W,overhead approaches the
optimal storage factor", from above and monotonically: 865.2, 53.0, 23.4, 16.0, 12.9, 11.2,
10.2, 9.50, 9.00, 8.62 for k = 1 … 10 and 6.53 at k = 40 (not drawn), against the optimum
5.98.  Both eq. 17 and eq. 18 tend to ln(f/n)/(2 tanθ) as k → ∞; most of the gain comes from
the first few partitions (k = 4 is within a factor 2.7 of the optimum with warping).
Eq. 17 falls from 8.65·10⁵ at k = 1 (a single uniform map) to 11.5 at k = 16: partitioning
alone, without warping, already brings S̄ down by almost five decades.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import schemes
from aliasing.plotting import save, subplots
from aliasing.view import View

NAME = "lloyd2006-fig10"
NEAR, FAR, FOV = 1.0, 1000.0, 60.0  # not printed for Fig. 10: f/n = 1000, θ = 30° as in Fig. 12
K_MAX = 16


def data(k_max: int = K_MAX) -> dict[str, np.ndarray]:
    from aliasing.figures.lloyd2006_fig12 import closed_forms

    cf = closed_forms()
    theta = View(NEAR, FAR, FOV).theta
    k = np.arange(1, k_max + 1, dtype=float)
    return {
        "k": k,
        "ZP": cf["eq17"](FAR, NEAR, k, theta),
        "ZPW": cf["eq18"](FAR, NEAR, k, theta),
        "optimal": np.full(k.shape, float(cf["optimal"](FAR, NEAR, 1.0, theta))),
        "general_ZP": np.array([schemes.evaluate(f"ZP{int(m)}", NEAR, FAR, FOV, "overhead").S[0] for m in k]),
        "general_ZPW": np.array([schemes.evaluate(f"ZP{int(m)}+LiSPSM", NEAR, FAR, FOV, "overhead").S[0] for m in k]),
    }


def main(out_dir: Path) -> list[Path]:
    cols = data()
    k = cols["k"]
    fig, ax = subplots(width=6.0, height=4.2)
    ax.plot(k, cols["ZP"], color="C0", label="ZP, no warping (eq. 17)")
    ax.plot(k, cols["ZPW"], color="C1", label=r"ZP+W, $n' \leq n'_{LiSPSM}$ (eq. 18)")
    ax.plot(k, cols["general_ZP"], ls="none", marker="x", color="k", alpha=0.7, label="ZP<k>, general evaluation")
    ax.plot(k, cols["general_ZPW"], ls="none", marker="+", ms=8, color="k", alpha=0.7, label="ZP<k>+LiSPSM, general evaluation")
    opt = cols["optimal"][0]
    ax.axhline(opt, color="C2", ls="--", label=f"optimal, logarithmic (App. C): ln(f/n)/(2 tanθ) = {opt:.2f}")
    picks = [i for i in (0, 1, 3, 9, k.size - 1) if i < k.size]
    text = "ZP+W / optimum:\n" + "\n".join(f"k = {int(k[i]):2d}: {cols['ZPW'][i]:7.2f}  ({cols['ZPW'][i] / opt:.2f}×)" for i in sorted(set(picks)))
    ax.text(0.55, 0.42, text, transform=ax.transAxes, fontsize=8, family="monospace", color="C1", va="center")
    ax.set(xlabel="number of z-partitions k (= number of shadow maps)", ylabel=r"storage factor $\bar S$", yscale="log", xlim=(0.5, k[-1] + 0.5))
    ax.set_xticks(k[:: 1 if k.size <= 16 else 2])
    ax.legend(fontsize=8)
    ax.set_title(f"Lloyd et al. 2006 Fig. 10: light overhead (f/n = {FAR / NEAR:g}, θ = {FOV / 2:g}°, assumed)", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
