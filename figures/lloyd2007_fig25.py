"""Lloyd et al. 2007, Figure 25: the critical resolution factor R_log,t^side of the logarithmic parameterization.

App. A of the LogPSM report.  R_log,t^side = max_v δ_log,t(v)/δ_b,t^side(v) (eqs. 47, 62, 102)
against the light's position l_y along a side face, for l_z = σ (y1 − y0), σ = 0.1, 0.2, 0.5,
1, ∞ (dark to light); θ = 45°, n_e = 1, f_e = 1000.  Computed by
:mod:`aliasing.face_factors`.

Our choices (the extraction has the caption and the text, not the image): solid lines are
R_log,t with the parameter a of eq. 77 optimised for each light position
(:func:`~aliasing.face_factors.optimal_factors`, ``minimize="R_t"``; we read the figure as
showing the optimum because the text discusses a_opt, and Figs. 23–24 show optima), dashed
lines a = 0, the optimum of the overhead light (eq. 103) and the a that LogPSMs use (the
S-optimal a of Fig. 26); the thin grey line is R_b,t^side at σ = 0.1 for comparison.  x axis
l_y/(y1 − y0) ∈ [−1, 2], grey band: the light over the face (y0 ≤ l_y ≤ y1).  The CSV also
holds the optimal a.

What the text says and this figure shows:

* "When the cos φ_l factor in δ_b,t^side becomes 1 for a directional light, the optimal
  a_opt = 0 gives a perfect match for the y(v) term ... the same as R_b,t^side" (eq. 103):
  σ = ∞ gives ln(f/n)/sin 2θ = 6.908 with a_opt = 0, the maximum over all positions (eq. 72).
* "Because δ_log,t^side is not the best match for the cos φ_l factor, the error is not as low
  as it could be when the light is close to the face, but it is on the same order as
  R_b,t^side": R_log,t ≥ R_b,t everywhere (R_b = ρ_b is the least R of any parameterization)
  and at most 4.8 times it on this grid (σ = 0.1, the light just beyond the far end; 3.1, 1.8,
  1.4 for σ = 0.2, 0.5, 1).
* With a = 0, R_log,t equals its maximum 6.908 whenever the light is over the face
  (δ_log,t/δ_b,t ∝ cos φ_ly, which is 1 under the light); the optimal a lowers it there, by up
  to ≈ 33 % at σ = 0.1 — our reading of App. A's garbled "when the light is over the face,
  R_lp,t^side the error is higher than R_log,t^side. However R_log,t^side is still the same".
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.face_factors import face_factors, optimal_factors
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig25"


def data(count: int = 121) -> dict[str, np.ndarray]:
    """Columns ``kappa``, ``R_log_t_opt[sigma=…]``, ``a_opt[…]``, ``R_log_t_a0[…]``, ``R_b_t[…]``."""
    kappa = np.linspace(-1.0, 2.0, count)
    light = dict(ly=kappa * A.SPAN, lz=A.heights())
    best = optimal_factors("log", A.NEAR, A.FAR, A.FOV, minimize="R_t", **light)
    blocks = {
        "R_log_t_opt": best["R_t"],
        "a_opt": best["a"],
        "R_log_t_a0": face_factors("log", A.NEAR, A.FAR, A.FOV, a=0.0, **light)["R_t"],
        "R_b_t": face_factors("bound", A.NEAR, A.FAR, A.FOV, **light)["R_t"],
    }
    return A.columns("kappa", kappa, blocks)


def main(out_dir: Path) -> list[Path]:
    cols = data()
    kappa = cols["kappa"]
    rows = lambda name: np.array([cols[f"{name}[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS])  # noqa: E731
    fig, ax = subplots(width=5.6, height=3.8)
    A.shade(ax, A.Y0 / A.SPAN, A.Y1 / A.SPAN)
    A.draw_curves(ax, kappa, rows("R_log_t_opt"))
    A.draw_curves(ax, kappa, rows("R_log_t_a0"), ls="--", lw=0.9)
    ax.plot(kappa, cols["R_b_t[sigma=0.1]"], color="0.5", lw=0.8, label=r"$R_{b,t}^{side}$, σ = 0.1")
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles[:5] + handles[-1:], labels[:5] + labels[-1:], fontsize=7, loc="upper center", ncol=3)
    ax.set(xlabel="$l_y/(y_1-y_0)$", ylabel=r"$R_{log,t}^{side}$", ylim=(0, 9.5))
    ax.set_title("Lloyd et al. 2007 Fig. 25: $R_{log,t}^{side}$ vs light position\n(solid: optimal a, dashed: a = 0; θ = 45°, n = 1, f = 1000, $l_z$ = σ($y_1-y_0$))", fontsize=9)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
