"""Lloyd et al. 2007, Figure 22: critical resolution factors R_un of the uniform parameterization.

App. A of the LogPSM report (eqs. 90–95).  From left to right R_un,t^end, R_un,s^side and
R_un,t^side against the light's position, for point lights at l_z = σ (y1 − y0),
σ = 0.1, 0.2, 0.5, 1, ∞ (dark to light); θ = 45°, n_e = 1, f_e = 1000; "the cos θ term has been
factored out of R_un,t^end and R_un,s^side".  Computed by
:func:`aliasing.face_factors.face_factors` (``kind="uniform"``); axes and grey bands as in
Fig. 21 (``figures/lloyd2007_fig21.py``: far face, l_y resp. l_x in units of y1 − y0).

What the text says, and what this figure shows (tests/test_figures_lloyd2007_fig22_24.py):

* σ = ∞ gives the closed forms eqs. 93–95: 1, f/n = 1000 (cos θ factored out) and
  (f/n − 1)/sin 2θ = 999; every other curve lies below (eq. 72).
* "R_un reaches its maximum whenever the light position is over the face": on the end face
  yes (cos θ·R = 1 over the whole band, every σ); on the side face only over the near edge
  (ERRATA L19).
* "when the light is not directly over the face, the shapes of the graphs are nearly
  identical [to Fig. 21], but on the side face, the magnitudes … differ significantly" (by
  the f/n of the y(v) term): R_un,t^side/R_b,t^side = 999/6.908 = 145 at σ = ∞.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.face_factors import face_factors
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save

NAME = "lloyd2007-fig22"
END_HALF = A.W_E * A.FAR / A.NEAR / 2 / A.SPAN  # the far face's half width, in units of y1 − y0
PANELS = (
    ("R_un_t_end_times_cos", r"$R_{un,t}^{end}\cos\theta$", (-1.5, 1.5), (-END_HALF, END_HALF), "$l_y/(y_1-y_0)$"),
    ("R_un_s_side_times_cos", r"$R_{un,s}^{side}\cos\theta$", (-1.5, 1.5), (-END_HALF, END_HALF), "$l_x/(y_1-y_0)$"),
    ("R_un_t_side", r"$R_{un,t}^{side}$", (-1.0, 2.0), (A.Y0 / A.SPAN, A.Y1 / A.SPAN), "$l_y/(y_1-y_0)$"),
)


def panel(name: str, kappa: np.ndarray, kind: str = "uniform") -> np.ndarray:
    """One panel's curves ``(σ, κ)`` for ``kind`` ("uniform" here; "bound" gives Fig. 21's)."""
    pos, lz = kappa * A.SPAN, A.heights()
    if name.endswith("t_end_times_cos"):
        return face_factors(kind, A.NEAR, A.FAR, A.FOV, ly=pos, lz=lz, face="far")["R_t"] * A.COS_THETA
    if name.endswith("s_side_times_cos"):
        return face_factors(kind, A.NEAR, A.FAR, A.FOV, lx=pos, lz=lz)["R_s"] * A.COS_THETA
    return face_factors(kind, A.NEAR, A.FAR, A.FOV, ly=pos, lz=lz)["R_t"]


def data(count: int = 121) -> dict[str, np.ndarray]:
    """Columns per panel: ``kappa[<panel>]`` and ``<panel>[sigma=…]``."""
    cols: dict[str, np.ndarray] = {}
    for name, _, (lo, hi), _, _ in PANELS:
        kappa = np.linspace(lo, hi, count)
        cols.update(A.columns(f"kappa[{name}]", kappa, {name: panel(name, kappa)}))
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig = A.panel_figure(cols, PANELS, "Lloyd et al. 2007 Fig. 22: R of the uniform parameterization vs light position (θ = 45°, n = 1, f = 1000, $l_z$ = σ($y_1-y_0$))")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
