"""Lloyd et al. 2007, Figure 21: critical resolution factors R_b of the error-bound parameterizations.

App. A of the LogPSM report.  R_b = ρ_b (eq. 47 with δ_l ∝ δ_b; eqs. 63–68, eq. 67's constant
corrected, erratum L12), from left to right R_b,t^end, R_b,s^side = max_v ρ_b,s^side(v) and
R_b,t^side, against the light's position, for l_z = σ (y1 − y0), σ = 0.1, 0.2, 0.5, 1, ∞
(dark to light); θ = 45°, n_e = 1, f_e = 1000; "the cos θ term has been factored out of
R_b,t^end and R_b,s^side".  Computed by :func:`aliasing.face_factors.face_factors`
(``kind="bound"``).

Our choices (the extraction has the caption, not the image): the end face is the far face
(as in Fig. 19, 2000 wide); the x axes are the light's coordinate across the face that the
factor depends on, in units of y1 − y0: l_y for R_b,t^end and R_b,t^side, l_x for R_b,s^side
(cos φ_lx, eqs. 57 and 61, does not depend on l_y, so a sweep in l_y would be flat); the
grey band is the face's extent in that coordinate (|l| ≤ 1000 for the far face and for the
side face's widest row, y0 ≤ l_y ≤ y1 along the side face).

What the text says and this figure shows:

* "It is for this position [an overhead directional light] that R_b reaches its maximum
  value", the closed forms of eqs. 87–89: σ = ∞ gives 1, 1 (cos θ factored out) and
  ln(f/n)/sin 2θ = 6.908; every other curve lies below (eq. 72).
* "In general, R_b is smaller when the light is close to the plane containing the face"
  (the curves rise with σ at every position) "It also falls off as the light moves to either
  side of the face".
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.face_factors import face_factors
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save

NAME = "lloyd2007-fig21"
END_HALF = A.W_E * A.FAR / A.NEAR / 2 / A.SPAN  # the far face's half width, in units of y1 − y0
PANELS = (
    ("R_b_t_end_times_cos", r"$R_{b,t}^{end}\cos\theta$", (-1.5, 1.5), (-END_HALF, END_HALF), "$l_y/(y_1-y_0)$"),
    ("R_b_s_side_times_cos", r"$R_{b,s}^{side}\cos\theta$", (-1.5, 1.5), (-END_HALF, END_HALF), "$l_x/(y_1-y_0)$"),
    ("R_b_t_side", r"$R_{b,t}^{side}$", (-1.0, 2.0), (A.Y0 / A.SPAN, A.Y1 / A.SPAN), "$l_y/(y_1-y_0)$"),
)


def data(count: int = 121) -> dict[str, np.ndarray]:
    """Columns per panel: ``kappa[<panel>]`` and ``<panel>[sigma=…]``."""
    cols: dict[str, np.ndarray] = {}
    lz = A.heights()
    for name, _, (lo, hi), _, _ in PANELS:
        kappa = np.linspace(lo, hi, count)
        pos = kappa * A.SPAN
        if name == "R_b_t_end_times_cos":
            rows = face_factors("bound", A.NEAR, A.FAR, A.FOV, ly=pos, lz=lz, face="far")["R_t"] * A.COS_THETA
        elif name == "R_b_s_side_times_cos":
            rows = face_factors("bound", A.NEAR, A.FAR, A.FOV, lx=pos, lz=lz)["R_s"] * A.COS_THETA
        else:
            rows = face_factors("bound", A.NEAR, A.FAR, A.FOV, ly=pos, lz=lz)["R_t"]
        cols.update(A.columns(f"kappa[{name}]", kappa, {name: rows}))
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig = A.panel_figure(cols, PANELS, "Lloyd et al. 2007 Fig. 21: R of the error-bound parameterizations vs light position (θ = 45°, n = 1, f = 1000, $l_z$ = σ($y_1-y_0$))")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
