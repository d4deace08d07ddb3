"""Lloyd et al. 2006, Figure 5: distribution of m_x and m_z along the view frustum.

Plots the last (z-dependent) terms of eqs. 7 and 8 over z ∈ [n, f] for n = 1, f = 20 and
n′ ∈ {n (PSM), 2, n′_LiSPSM = n + √(fn) ≈ 5.47, 20, ∞ (uniform)}:

* x: f(n′ + z − n)/(z(n′ + f − n)), i.e. m_x at unit resolutions;
* z: (n′ + z − n)²/(z n′(n′ + f − n)), i.e. m_z·2 tanθ/(f − n) at unit resolutions.

What the paper's text says and this figure shows: the x error is maximal at z = n for
every n′; the z error is maximal at the near plane for n′ > n′_LiSPSM and at the far
plane below it, and at n′_LiSPSM both ends are equal (1/√(f/n) ≈ 0.224).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.error import m_x, m_z
from aliasing.plotting import save, subplots
from aliasing.view import tan_theta
from aliasing.warping import n_prime_lispsm

NAME = "lloyd2006-fig5"
NEAR, FAR = 1.0, 20.0
FOV = 90.0  # tanθ = 1; the plotted z term is independent of the field of view


def data() -> dict[str, np.ndarray]:
    z = np.linspace(NEAR, FAR, 400)
    cols: dict[str, np.ndarray] = {"z": z}
    for label, npr in curves():
        cols[f"mx[{label}]"] = m_x(z, NEAR, FAR, npr)
        cols[f"mz[{label}]"] = m_z(z, NEAR, FAR, FOV, npr) * 2 * tan_theta(FOV) / (FAR - NEAR)
    return cols


def curves() -> list[tuple[str, float]]:
    n_l = float(n_prime_lispsm(NEAR, FAR))
    return [("n'=n (PSM)", NEAR), ("n'=2", 2.0), (f"n'=n'_LiSPSM={n_l:.2f}", n_l), ("n'=20", 20.0), ("n'=inf (uniform)", np.inf)]


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, (ax_x, ax_z) = subplots(2)
    for label, _ in curves():
        ax_x.plot(cols["z"], cols[f"mx[{label}]"], label=label)
        ax_z.plot(cols["z"], cols[f"mz[{label}]"], label=label)
    ax_x.set(xlabel="eye depth z", ylabel=r"$f(n'+z-n)\,/\,(z(n'+f-n))$", title=r"$m_x$ term (eq. 7)", yscale="log")
    ax_z.set(xlabel="eye depth z", ylabel=r"$(n'+z-n)^2/(z\,n'(n'+f-n))$", title=r"$m_z$ term (eq. 8)", yscale="log")
    ax_x.legend(fontsize=8, loc="upper right")
    fig.suptitle("Lloyd et al. 2006 Fig. 5: error along the frustum (n = 1, f = 20)")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
