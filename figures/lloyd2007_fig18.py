"""Lloyd et al. 2007, Figure 18: the error-bound spacing δ_b,t^side(v) of a side face.

App. A of the LogPSM report.  δ_b,t^side(v) = W_e y(v) cos θ/((y1 − y0) y0 cos φ_ly(v)) (eq. 62,
:func:`aliasing.logpsm.delta_bound_side_t`) for a point light at l_y = κ (y1 − y0),
l_z = σ (y1 − y0); panels κ = −0.5, 0.5, 1 (left to right), curves σ = 0.1, 0.2, 0.5, 1, ∞
(dark to light); θ = 45°, n_e = 1, f_e = 1000 (the caption's values).

Our choices (the extraction has the caption, not the image): x axis v ∈ [0, 1] (y from
y0 = √2 to y1 = 1000√2), linear y axes (so that the σ = ∞ line reads as a line), cos θ kept
in, δ_b not normalised (the curves differ by the factor 1/cos φ_ly, which is what the text
discusses; Fig. 19's caption, "the cos θ term has been factored out", suggests the paper
plots δ_b unnormalised too); the light's foot point y = l_y is marked where it lies on the
face.

What the text says and this figure shows:

* "As the light moves away toward infinity, the spacing function converges to a linear
  function": the σ = ∞ curve is W_e y(v) cos θ/((y1 − y0) y0), and normalised, ρ_b δ_b, it
  is δ_log,t of eq. 102 with a = 0 ("This spacing distribution is linear, as is that of
  δ_b,t^side for a directional light (see Figure 18)").
* "When the light is close to the face, the spacing function is an undulating curve with
  dense sampling near the light and the viewer": every curve lies above σ = ∞ and touches
  it only under the light (cos φ_ly = 1); δ_b ∝ y √((y − l_y)² + l_z²) has a local minimum
  just before l_y when l_z < l_y/(2√2) (2d² + l_y d + l_z² = 0, d = y − l_y): κ = 0.5 with
  σ = 0.1, κ = 1 with σ = 0.1, 0.2.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import logpsm
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig18"
KAPPAS = (-0.5, 0.5, 1.0)


def data(count: int = 401) -> dict[str, np.ndarray]:
    """Columns ``v`` and ``delta_b[kappa=…][sigma=…]``."""
    v = np.linspace(0.0, 1.0, count)
    blocks = {}
    for kappa in KAPPAS:
        blocks[f"delta_b[kappa={kappa:g}]"] = logpsm.delta_bound_side_t(v, A.NEAR, A.FAR, A.FOV, ly=kappa * A.SPAN, lz=A.heights())  # eq. (62)
    return A.columns("v", v, blocks)


def main(out_dir: Path) -> list[Path]:
    cols = data()
    v = cols["v"]
    fig, axes = subplots(len(KAPPAS), width=3.6, height=3.2)
    for ax, kappa in zip(axes, KAPPAS):
        rows = np.array([cols[f"delta_b[kappa={kappa:g}][sigma={A.sigma_key(s)}]"] for s in A.SIGMAS])
        A.draw_curves(ax, v, rows)
        v_light = (kappa * A.SPAN - A.Y0) / A.SPAN
        if 0.0 <= v_light <= 1.0:
            ax.axvline(v_light, color="0.6", ls=":", lw=0.8)
        ax.set(xlim=(0, 1), ylim=(0, None), xlabel="v", title=f"κ = {kappa:g}  ($l_y$ = {kappa * A.SPAN:.0f})")
    axes[0].set_ylabel(r"$\delta_{b,t}^{side}(v)$")
    axes[0].legend(fontsize=7)
    fig.suptitle("Lloyd et al. 2007 Fig. 18: error-bound spacing in t on a side face (θ = 45°, n = 1, f = 1000, $l_z$ = σ($y_1-y_0$))", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
