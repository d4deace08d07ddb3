"""Zhang et al. 2007, Figure 6: the aliasing distributions F(z) of LiSPSM and GMNPR.

n = 1, f = 100, φ = π/6 (fov 60°), as printed.  Top row F_LiSPSM, bottom row F_GMNPR
(eq. 2 with λ of eq. 9 and eq. 8); left θ ∈ [φ, π/2], right θ ∈ [0, φ] on a log10 scale.
The extraction has no axis labels; here F is drawn over the eye depth z ∈ [n, f], one
curve per θ.

What the text says and this figure shows: for θ ≥ φ GMNPR's errors at the two ends of
the depth range "remain equal for all possible θ values" and "the shape of F_GMNPR keeps
unchanged" (ϕ ≡ √(fn), so only the scale ψ(θ) changes: F(n) = F(f) from 17.1 at 90° to
20.0 at φ), while "as θ decreases, the aliasing errors at near regions in LiSPSM increase"
(F(n) from 17.1 to 65.3, F(f) falling).  For θ < φ both "become extremely large for small
θ values" (F(n) ≈ 10³ at θ = 10° for both), and neither equalises F(n) and F(f).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.gmnpr import generalized_error, lambda_gmnpr, lambda_lispsm
from aliasing.plotting import save, subplots

NAME = "zhang2007-fig6"
NEAR, FAR, FOV = 1.0, 100.0, 60.0  # φ = π/6
THETA_NONDEGENERATE = (90.0, 75.0, 60.0, 45.0, 30.0)  # θ ∈ [φ, π/2], degrees
THETA_DEGENERATE = (30.0, 25.0, 20.0, 15.0, 10.0, 5.0)  # θ ∈ [0, φ], degrees
METHODS = {"LiSPSM": lambda_lispsm, "GMNPR": lambda_gmnpr}


def data() -> dict[str, np.ndarray]:
    z = np.linspace(NEAR, FAR, 496)
    cols = {"z": z}
    for method, lam in METHODS.items():
        for th in sorted(set(THETA_NONDEGENERATE + THETA_DEGENERATE), reverse=True):
            cols[f"F_{method}[theta={th:g}]"] = generalized_error(lam(NEAR, FAR, FOV, th), NEAR, FAR, FOV, th, z)
    return cols


def main(out_dir: Path) -> list[Path]:
    from matplotlib import colormaps

    cols = data()
    fig, axes = subplots(2, nrows=2, width=5.0, height=3.6)
    for row, method in enumerate(METHODS):
        for col, thetas in enumerate((THETA_NONDEGENERATE, THETA_DEGENERATE)):
            ax = axes[row, col]
            colors = colormaps["viridis"](np.linspace(0.0, 0.85, len(thetas)))
            for th, c in zip(thetas, colors):
                ax.plot(cols["z"], cols[f"F_{method}[theta={th:g}]"], color=c, label=rf"$\theta$ = {th:g}°")
            rng = r"$\varphi \leq \theta \leq \pi/2$" if col == 0 else r"$0 \leq \theta \leq \varphi$, log$_{10}$ scale"
            ax.set(xlabel="eye depth z", ylabel=rf"$F_{{{method}}}$", xlim=(NEAR, FAR), title=rf"$F_{{{method}}}$, {rng}")
            if col == 0:
                ax.set_ylim(0, 70)
            else:
                ax.set_yscale("log")
            ax.legend(fontsize=7, ncol=2 if col else 1)
    fig.suptitle(r"Zhang et al. 2007 Fig. 6: aliasing distributions (n = 1, f = 100, $\varphi = \pi/6$)")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
