"""Lloyd et al. 2006, Figure 6: M_x, M_z and S̄ over the warping parameter η.

n = 1, f = 100, θ = 30° (fov 60°; the normalised curves do not depend on it), η ∈ [−1, 1]
mapped to n′ by eq. 11: n′(−1) = ∞, n′(0) = n′_LiSPSM = 11, n′(1) = n.  As in the paper
each curve is normalised by its maximum over η to share one axis (drawn on a log axis
so that the flat S̄ for η ≥ 0 stays visible).

What the text says and this figure shows: M_z is piecewise linear in η, maximal at both
ends and minimal (1/√(f/n) of its maximum) at η = 0; M_x falls monotonically from f/n to
1; S̄ = M_x·M_z is minimal and constant for all η ≥ 0 (eq. 12), i.e. for
n ≤ n′ ≤ n′_LiSPSM, which is the equivalence of PSM, LiSPSM and TSM of §4.3.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.error import max_error_x, max_error_z, storage_factor
from aliasing.plotting import save, subplots
from aliasing.warping import n_prime_from_eta

NAME = "lloyd2006-fig6"
NEAR, FAR, FOV = 1.0, 100.0, 60.0


def data() -> dict[str, np.ndarray]:
    eta = np.linspace(-1.0, 1.0, 401)
    npr = n_prime_from_eta(eta, NEAR, FAR)
    mx = max_error_x(NEAR, FAR, npr)
    mz = max_error_z(NEAR, FAR, FOV, npr)
    s = storage_factor(NEAR, FAR, FOV, npr)
    return {"eta": eta, "n_prime": npr, "M_x": mx, "M_z": mz, "S": s, "M_x/max": mx / mx.max(), "M_z/max": mz / mz.max(), "S/max": s / s.max()}


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, ax = subplots()
    for key, label in (("M_x/max", r"$M_x$"), ("M_z/max", r"$M_z$"), ("S/max", r"$\bar S$")):
        ax.plot(cols["eta"], cols[key], label=label)
    ax.set(xlabel=r"$\eta$  ($n'=\infty$ at $-1$, $n'_{LiSPSM}$ at 0, $n$ at 1)", ylabel="normalised to maximum", yscale="log", xlim=(-1, 1))
    ax.legend()
    ax.set_title("Lloyd et al. 2006 Fig. 6: varying n' (n = 1, f = 100)")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
