"""Zhang et al. 2007, Figure 5: λ over the light–view angle θ (eq. 4, GMNPR, LiSPSM, GLPR).

The paper does not print Fig. 5's parameters; they are assumed equal to Fig. 6's:
n = 1, f = 100, φ = π/6 (fov 60°).  θ runs over [0°, 90°] (the package's γ folded).

What the text says and this figure shows: eq. 4's optimal λ decreases slowly as θ goes
from 90° to φ = 30° (λ1: 0.111 → 0.05), then "takes a nose-dive" (λ2) through 0 at
θ0 = 27.7° to −1/2 at θ = 0.  It is continuous at θ = φ (only its slope jumps).  GMNPR
follows λ1 down to φ and then replaces λ2 by λ2* = λ1(φ)/tan(πθ/(4φ)) (eq. 7), which rises
to ∞ as θ → 0.  LiSPSM's λ (eq. 9) equals λ1 only at θ = 90° and is larger below (a weaker
warp).  GLPR's λ (F ∝ z) is smaller still and falls to 0 at θ = φ; it does not exist
below φ.  The y axis is clipped: λ_GMNPR and λ_LiSPSM leave it near θ = 0.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.gmnpr import lambda_glpr, lambda_gmnpr, lambda_lispsm, lambda_optimal
from aliasing.plotting import save, subplots

NAME = "zhang2007-fig5"
NEAR, FAR, FOV = 1.0, 100.0, 60.0  # φ = π/6, assumed as in Fig. 6


def data() -> dict[str, np.ndarray]:
    theta = np.linspace(0.0, 90.0, 361)[1:]  # 0.25° steps, θ = φ = 30° included; θ = 0 gives λ = ∞
    return {
        "theta_deg": theta,
        "lambda_eq4": lambda_optimal(NEAR, FAR, FOV, theta),
        "lambda_GMNPR": lambda_gmnpr(NEAR, FAR, FOV, theta),
        "lambda_LiSPSM": lambda_lispsm(NEAR, FAR, FOV, theta),
        "lambda_GLPR": lambda_glpr(NEAR, FAR, FOV, theta),
    }


def main(out_dir: Path) -> list[Path]:
    cols = data()
    th, phi = cols["theta_deg"], FOV / 2
    fig, ax = subplots(width=6.0, height=4.2)
    above = th >= phi
    ax.plot(th[above], cols["lambda_eq4"][above], color="C0", lw=4, alpha=0.5, label=r"eq. 4, $\lambda_1$ ($\theta \geq \varphi$)")
    ax.plot(th[~above | (th == phi)], cols["lambda_eq4"][~above | (th == phi)], color="C0", ls="--", label=r"eq. 4, $\lambda_2$ ($\theta \leq \varphi$)")
    ax.plot(th, cols["lambda_GMNPR"], color="C1", label=r"$\lambda_{GMNPR}$ (eq. 8; $\lambda_2^*$ below $\varphi$)")
    ax.plot(th, cols["lambda_LiSPSM"], color="C2", label=r"$\lambda_{LiSPSM}$ (eq. 9)")
    ax.plot(th, cols["lambda_GLPR"], color="C3", label=r"$\lambda_{GLPR}$ ($F \propto z$, $\theta > \varphi$)")
    ax.axvline(phi, color="0.5", lw=0.8)
    ax.axhline(0.0, color="0.5", lw=0.8)
    ax.annotate(r"$\theta = \varphi$", (phi, 0.55), xytext=(3, 0), textcoords="offset points", color="0.4")
    ax.set(xlabel=r"light–view angle $\theta$ [deg]", ylabel=r"$\lambda = P_n/(P_f - P_n)$", xlim=(0, 90), ylim=(-0.55, 0.6))
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(r"Zhang et al. 2007 Fig. 5: $\lambda(\theta)$ (n = 1, f = 100, $\varphi = \pi/6$ assumed)", fontsize=9)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
