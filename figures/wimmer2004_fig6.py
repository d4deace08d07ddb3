"""Wimmer et al. 2004, Figure 6: perspective aliasing dp/ds over z for three methods.

Eq. 3 with z_n = 1, z_f = 100 for a uniform shadow map (n → ∞), a perspective shadow map
(n = z_n) and LiSPSM (n = n_opt = z_n + √(z_n z_f) = 11).

What the text says and this figure shows: uniform falls hyperbolically from
z_f − z_n = 99; PSM rises linearly to 99; LiSPSM falls to its minimum at z = √(z_n z_f) = 10
and rises again, with equal maxima (z_f − z_n)/√z_f = 9.9 at both ends, "roughly √z_f".
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.error import dp_ds
from aliasing.plotting import save, subplots
from aliasing.warping import n_prime_lispsm

NAME = "wimmer2004-fig6"
Z_N, Z_F = 1.0, 100.0


def data() -> dict[str, np.ndarray]:
    z = np.linspace(Z_N, Z_F, 500)
    return {
        "z": z,
        "uniform": dp_ds(z, Z_N, Z_F, np.inf),
        "PSM": dp_ds(z, Z_N, Z_F, Z_N),
        "LiSPSM": dp_ds(z, Z_N, Z_F, n_prime_lispsm(Z_N, Z_F)),
    }


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, ax = subplots()
    for key in ("uniform", "PSM", "LiSPSM"):
        ax.plot(cols["z"], cols[key], label=key)
    ax.set(xlabel="eye depth z", ylabel="dp/ds", xlim=(Z_N, Z_F), ylim=(0, 100))
    ax.legend()
    ax.set_title(r"Wimmer et al. 2004 Fig. 6 ($z_n$ = 1, $z_f$ = 100)")
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
