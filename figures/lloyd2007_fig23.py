"""Lloyd et al. 2007, Figure 23: optimal critical resolution factors of the perspective parameterization.

App. A of the LogPSM report (eqs. 96–101).  From left to right min_a R_p,s^side, min_a R_p,t^side
and min_a S_p^side (each with its own optimal perspective parameter a, chosen per light by
:func:`aliasing.face_factors.optimal_factors`) against the light's position, for point lights at
l_z = σ (y1 − y0), σ = 0.1, 0.2, 0.5, 1, ∞ (dark to light); θ = 45°, n_e = 1, f_e = 1000; the
cos θ term factored out of R_p,s^side.  Axes and grey bands as in Figs. 21–22 (R_s over l_x,
the others over l_y, in units of y1 − y0).

What the text says, and what this figure shows (tests/test_figures_lloyd2007_fig22_24.py):

* "R_p,s^side is minimized when a = 0", leaving cos φ_lx/cos θ: the optimal a for R_s is 0
  and cos θ·R_p,s equals Fig. 22's R_un,t^end-like cos φ_lx factor, 1 at σ = ∞ (eq. 99).
* σ = ∞ (overhead) gives eq. 100's min_a R_p,t = (f/n − 1)/(sin 2θ √(f/n)) = 31.59 at
  a = √(y0 y1) (LiSPSM), and eq. 101's min_a S_p = (f/n − 1)/(sin 2θ cos θ) = 1412.8 (both in
  their corrected later forms, ERRATA L16); every other curve lies below (eq. 72).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.face_factors import optimal_factors
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save

NAME = "lloyd2007-fig23"
END_HALF = A.W_E * A.FAR / A.NEAR / 2 / A.SPAN
PANELS = (
    ("R_p_s_side_times_cos", r"min$_a R_{p,s}^{side}\cos\theta$", (-1.5, 1.5), (-END_HALF, END_HALF), "$l_x/(y_1-y_0)$"),
    ("R_p_t_side", r"min$_a R_{p,t}^{side}$", (-1.0, 2.0), (A.Y0 / A.SPAN, A.Y1 / A.SPAN), "$l_y/(y_1-y_0)$"),
    ("S_p_side", r"min$_a S_{p}^{side}$", (-1.0, 2.0), (A.Y0 / A.SPAN, A.Y1 / A.SPAN), "$l_y/(y_1-y_0)$"),
)


def panel(name: str, kappa: np.ndarray, samples: int = 65) -> dict[str, np.ndarray]:
    """Optimal factors for one panel, ``(σ, κ)`` arrays: the factor and its optimal ``a``."""
    pos, lz = kappa * A.SPAN, A.heights()
    if name == "R_p_s_side_times_cos":
        f = optimal_factors("perspective", A.NEAR, A.FAR, A.FOV, minimize="R_s", lx=pos, lz=lz, samples=samples)
        return {"value": f["R_s"] * A.COS_THETA, "a": f["a"]}
    f = optimal_factors("perspective", A.NEAR, A.FAR, A.FOV, minimize="R_t" if name == "R_p_t_side" else "S", ly=pos, lz=lz, samples=samples)
    return {"value": f["R_t"] if name == "R_p_t_side" else f["S"], "a": f["a"]}


def data(count: int = 61, samples: int = 65) -> dict[str, np.ndarray]:
    """Columns per panel: ``kappa[<panel>]``, ``<panel>[sigma=…]`` and ``a_opt[<panel>][sigma=…]``."""
    cols: dict[str, np.ndarray] = {}
    for name, _, (lo, hi), _, _ in PANELS:
        kappa = np.linspace(lo, hi, count)
        p = panel(name, kappa, samples)
        cols.update(A.columns(f"kappa[{name}]", kappa, {name: p["value"], f"a_opt[{name}]": p["a"]}))
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig = A.panel_figure(cols, PANELS, "Lloyd et al. 2007 Fig. 23: optimal R and S of the perspective parameterization vs light position (θ = 45°, n = 1, f = 1000)")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
