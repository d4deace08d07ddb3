"""Lloyd et al. 2006, Figure 13: which scheme has the lowest error with the light behind the viewer.

Caption: "This graph shows the parameter values for which the z-partitioning (ZP, ZP+W)
schemes and face partitioning (FP+ZP+W) yield the lowest error.  z-partitioning is the best
scheme for high depth range with few shadow maps."

Axes (not printed; inferred): depth ratio f/n (log, 10 … 10⁵) × number of shadow maps
j (1 … 40).  With the light behind, neither eq. 20 nor eq. 21 depends on θ, so θ cannot be
an axis, and f/n and j are the only parameters left.  ZP and ZP+W coincide behind ("a ZP
scheme cannot use warping because the view frustum is square"), so there are two regions.

Storage factors (lambdified from :mod:`aliasing.symbolic.lloyd2006`, the same as Fig. 12):

* ZP = ZP+W: eq. 20, S̄ = k (f/n)^(2/k) with k = j maps;
* FP+ZP+W: eq. 21, S̄ = 4 S̄_ZP+W,overhead(θ = 45°) + 1 = 2k((f/n)^(1/k) − 1) + 1, with
  j = 4k + 1 maps (four side faces per z-partitioning plus the near face; Fig. 12's count).
  With j maps it uses k = ⌊(j − 1)/4⌋ z-partitionings (j ≥ 5; left-over maps unused);
  for j < 5 it is not available.

Region map: every integer j and f/n, coloured by the scheme with the lower S̄.  Boundary
curve: the continuous crossover j*(f/n), the root of

    j (f/n)^(2/j) = 2k((f/n)^(1/k) − 1) + 1,  k = (j − 1)/4,

and its large-f/n asymptote j* ≈ 2 ln(f/n)/ln(1 + √2) ≈ 2.27 ln(f/n) (put j = c ln(f/n):
e^(2/c) = (e^(4/c) − 1)/2, so e^(2/c) = 1 + √2).  ZP wins below the curve, FP+ZP+W above.
The whole-j region follows the curve in steps: FP+ZP+W only improves at j = 4k + 1, while
ZP with k = j maps has passed its minimum (k* = 2 ln(f/n) < j*) and keeps growing, so it can
be overtaken inside a block of four maps too (the small notches before each step).

What the text says and this figure shows: "z-partitioning is the best scheme for high depth
range with few shadow maps".  The continuous crossover is j* = 6.4, 11.7, 16.9, 22.1 at
f/n = 10, 100, 1000, 10⁴; the first whole number of maps at which FP+ZP+W is lower is
9, 13, 17, 25 (= 4k + 1).  At f/n = 1000 (Fig. 12's frustum) the switch is at 17 maps:
FP+ZP+W 38.0 against ZP 38.3, as in Fig. 12's right panel.  Counting rule caveat: the
paper does not say whether ZP is charged its best k ≤ j or exactly k = j; Fig. 12's ZP
curve grows past k* = 2 ln(f/n) ("decreases rapidly and then begins to grow slowly"), so
k = j is used here.  With the best k ≤ j instead, the switch at f/n = 1000 moves to 21.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from aliasing.plotting import save, subplots

NAME = "lloyd2006-fig13"
NEAR = 1.0
F_OVER_N = np.logspace(1.0, 5.0, 161)
MAPS = 40
ASYMPTOTE = 2.0 / np.log(1.0 + np.sqrt(2.0))  # j* / ln(f/n) as f/n → ∞


def _forms():
    from aliasing.figures.lloyd2006_fig12 import closed_forms

    cf = closed_forms()
    zp = lambda a, k: np.asarray(cf["eq20"](a * NEAR, NEAR, k, 0.0), dtype=float)  # noqa: E731  θ-free
    fp = lambda a, k: np.asarray(cf["eq21"](a * NEAR, NEAR, k, 0.0), dtype=float)  # noqa: E731  θ-free
    return zp, fp


def crossover(f_over_n: float) -> float:
    """Continuous j* at which eq. 20 (k = j) equals eq. 21 (k = (j − 1)/4)."""
    zp, fp = _forms()
    a = float(f_over_n)
    g = lambda j: np.log(zp(a, j)) - np.log(fp(a, (j - 1.0) / 4.0))  # noqa: E731
    lo = 5.0 if g(5.0) < 0 else 2.0  # FP+ZP+W with k < 1 overflows for huge f/n; ZP wins there anyway
    return float(brentq(g, lo, 50.0 + 4.0 * np.log(a), xtol=1e-12))  # j*/ln(f/n) < 4 for f/n ≥ 2


def data(f_over_n: np.ndarray = F_OVER_N, maps: int = MAPS) -> dict[str, np.ndarray]:
    """The region map flattened (rows: f/n outer, j inner) with the boundary per f/n."""
    zp, fp = _forms()
    a_axis = np.asarray(f_over_n, dtype=float)
    j_axis = np.arange(1, maps + 1, dtype=float)
    a, j = np.meshgrid(a_axis, j_axis, indexing="ij")
    k_fp = np.floor((j - 1.0) / 4.0)
    s_zp = zp(a, j)
    s_fp = np.full(a.shape, np.nan)
    ok = k_fp >= 1
    s_fp[ok] = fp(a[ok], k_fp[ok])
    fp_wins = ok & (np.where(ok, s_fp, np.inf) < s_zp)
    first = np.where(fp_wins.any(axis=1), np.argmax(fp_wins, axis=1) + 1.0, np.nan)  # smallest j where FP wins
    j_star = np.array([crossover(v) for v in a_axis])
    rep = lambda v: np.repeat(v, j_axis.size)  # noqa: E731
    return {
        "f_over_n": a.ravel(),
        "j": j.ravel(),
        "S_ZP": s_zp.ravel(),
        "S_FPZPW": s_fp.ravel(),
        "FPZPW_lower": fp_wins.ravel().astype(float),
        "j_first_FPZPW": rep(first),
        "j_star": rep(j_star),
        "j_asymptote": rep(ASYMPTOTE * np.log(a_axis)),
    }


def main(out_dir: Path) -> list[Path]:
    cols = data()
    maps = int(cols["j"].max())
    a_axis = cols["f_over_n"][::maps]
    win = cols["FPZPW_lower"].reshape(a_axis.size, maps)
    loga = np.log10(a_axis)
    step = loga[1] - loga[0]
    x_edges = 10 ** np.concatenate([[loga[0] - step / 2], (loga[:-1] + loga[1:]) / 2, [loga[-1] + step / 2]])
    y_edges = np.arange(0.5, maps + 1.0)
    fig, ax = subplots(width=6.2, height=4.6)
    from matplotlib.colors import ListedColormap

    ax.pcolormesh(x_edges, y_edges, win.T, cmap=ListedColormap(["#cfe3f5", "#d3efcf"]), vmin=0, vmax=1, shading="flat")
    ax.plot(a_axis, cols["j_star"][::maps], color="k", lw=1.6, label=r"crossover $j^*$: $j\,(f/n)^{2/j} = 2k((f/n)^{1/k}-1)+1$, $k=(j-1)/4$")
    ax.plot(a_axis, cols["j_asymptote"][::maps], color="k", ls="--", lw=1, label=r"asymptote $2\ln(f/n)/\ln(1+\sqrt{2}) \approx 2.27\,\ln(f/n)$")
    i = int(np.argmin(np.abs(a_axis - 1000.0)))
    j_first = cols["j_first_FPZPW"][i * maps]
    ax.plot([a_axis[i]], [j_first], marker="o", color="C3", ls="none", label=f"f/n = {a_axis[i]:g}: FP+ZP+W lower from j = {j_first:g} (Fig. 12)")
    ax.text(0.05, 0.88, "FP+ZP+W lowest", transform=ax.transAxes, fontsize=11, color="#2d6a2d", weight="bold")
    ax.text(0.60, 0.24, "ZP, ZP+W lowest", transform=ax.transAxes, fontsize=11, color="#1f4e79", weight="bold")
    ax.set(xscale="log", xlabel="depth ratio f/n", ylabel="number of shadow maps j", xlim=(x_edges[0], x_edges[-1]), ylim=(0.5, maps + 0.5))
    ax.grid(False)
    ax.legend(fontsize=7.5, loc="lower right", frameon=True, framealpha=0.9)
    ax.set_title("Lloyd et al. 2006 Fig. 13: lowest error, light behind (θ-free)", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
