"""Lloyd et al. 2007, Figure 19: the error-bound spacing δ_b,t^end(v) of an end face.

App. A of the LogPSM report.  δ_b,t^end(v)/cos θ = 1/cos φ_ly(v) (eqs. 57–58,
:func:`aliasing.logpsm.delta_bound_end`, "the cos θ term has been factored out") on the far
face (y(v) = W_e (f/n)(v − 1/2), W_e f/n = 2000 wide) for a point light at l_y = 0 (over the
face's centre) and l_z = σ (y1 − y0), σ = 0.1, 0.2, 0.5, 1, ∞ (dark to light), y0, y1 of the
side face as in the other App. A figures; θ = 45°, n_e = 1, f_e = 1000.

Our choices: the far face (the text: "Figure 19 shows how δ_b,t^end on the far face changes
with light position"), x axis v ∈ [0, 1], linear y axis.

What the text says and this figure shows:

* "Close to the face, δ_b,t^end resembles an absolute value function with a rounded tip":
  1/cos φ_ly = √((y − l_y)² + l_z²)/l_z, which tends to |y − l_y|/l_z away from the light and
  is 1 (its minimum, the rounded tip) under it.
* "As l_z → ∞, cos φ_ly converges to a constant and the spacing function converges to
  uniform": σ = ∞ is the constant 1; so R_un,t^end = R_b,t^end = 1/cos θ (eqs. 87, 93).
* "Moving the light in y simply translates the function along the v-axis" (a function of
  y − l_y only).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import logpsm
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig19"


def data(count: int = 401) -> dict[str, np.ndarray]:
    """Columns ``v`` and ``delta_b_over_cos[sigma=…]``."""
    v = np.linspace(0.0, 1.0, count)
    rows = logpsm.delta_bound_end(v, A.NEAR, A.FAR, A.FOV, ly=0.0, lz=A.heights(), face="far") / A.COS_THETA  # eq. (58)
    return A.columns("v", v, {"delta_b_over_cos": rows})


def main(out_dir: Path) -> list[Path]:
    cols = data()
    v = cols["v"]
    fig, ax = subplots(width=4.6, height=3.4)
    A.draw_curves(ax, v, np.array([cols[f"delta_b_over_cos[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS]))
    ax.set(xlim=(0, 1), ylim=(0, None), xlabel="v  (far face, light over its centre)", ylabel=r"$\delta_{b,t}^{end}(v)/\cos\theta$")
    ax.legend(fontsize=7)
    ax.set_title("Lloyd et al. 2007 Fig. 19: error-bound spacing, far face", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
