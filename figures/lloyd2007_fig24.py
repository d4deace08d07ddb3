"""Lloyd et al. 2007, Figure 24: the range of optimal perspective parameters a of S_p^side.

App. A of the LogPSM report: R_p,s and R_p,t share one a when F_p is a projective matrix, so
a is chosen to minimise S_p^side = R_p,s R_p,t; "a range of parameters (those below the curve)
produce the same storage factor S_p^side for each light position (l_y = 0.5 y1)", and "it is
advisable to choose the largest a possible on the equivalent range.  For an overhead
directional light this corresponds to the LiSPSM parameter" √(y0 y1).

Left: S_p^side(a)/min_a S_p^side against a for point lights at l_y = 0.5 y1,
l_z = σ (y1 − y0), σ = 0.1, 0.2, 0.5, 1, ∞ (our reading of the caption's left panel: the
extraction has no image; the curve whose region "below" is optimal is drawn on the right).
Right: the largest a of the optimal range, :func:`a_range_top`, against l_y for each σ.
θ = 45°, n_e = 1, f_e = 1000.  "The same S" is taken as within 1e-6 relative (``TOLERANCE``).

What the toolkit finds (tests/test_figures_lloyd2007_fig22_24.py; ERRATA L21):

* overhead (σ = ∞), the top of the range is √(y0 y1) = 44.72 at every l_y, as the text says;
* σ = 1 at l_y = 0.5 y1: a flat range up to 44.71, as the text says;
* σ = 0.5, 0.2, 0.1 at l_y = 0.5 y1: S rises from a = 0 on (by 0.19 %, 4.5 %, 5.7 % at a = 44):
  the optimal range shrinks to a ≈ 0 — the range exists for distant point lights only.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.face_factors import face_factors
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig24"
TOLERANCE = 1e-6
A_TOP = 1e4  # search bound for a [world units]


def storage(a, ly, lz, samples: int = 257) -> np.ndarray:
    """S_p^side for perspective parameter(s) ``a`` and light(s) (l_y, l_z) [world units]."""
    return face_factors("perspective", A.NEAR, A.FAR, A.FOV, ly=ly, lz=lz, a=a, samples=samples)["S"]


def a_range_top(ly, lz, tolerance: float = TOLERANCE, iterations: int = 50) -> np.ndarray:
    """Largest a with S_p^side(a) ≤ (1 + tolerance)·S_p^side(0) [world units] (bisection, vectorised).

    S_p^side is non-decreasing in a beyond its optimal range (a = 0 is always optimal here: the
    figure's claim is about how far the flat range extends).
    """
    ly, lz = np.broadcast_arrays(np.asarray(ly, float), np.asarray(lz, float))
    s0 = storage(0.0, ly, lz)
    lo, hi = np.zeros(ly.shape), np.full(ly.shape, A_TOP)
    for _ in range(iterations):  # bisection over a, vectorised over the lights
        mid = 0.5 * (lo + hi)
        ok = storage(mid, ly, lz) <= s0 * (1 + tolerance)
        lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
    return lo


def data(count: int = 121, a_count: int = 121) -> dict[str, np.ndarray]:
    """``a`` and ``S_over_min[sigma=…]`` (left), ``kappa`` and ``a_top[sigma=…]`` (right); one CSV, so count = a_count."""
    lz = A.heights()
    a = np.concatenate([[0.0], np.geomspace(1e-2, 1e3, a_count - 1)])
    s = storage(a[None, :], 0.5 * A.Y1, lz)
    left = A.columns("a", a, {"S_over_min": s / s.min(axis=1, keepdims=True)})
    kappa = np.linspace(-1.0, 2.0, count)
    right = A.columns("kappa", kappa, {"a_top": a_range_top(kappa[None, :] * A.SPAN, lz)})
    return {**left, **right}


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, axes = subplots(2, width=4.2, height=3.3)
    a = cols["a"]
    A.draw_curves(axes[0], np.maximum(a, 1e-2), np.array([cols[f"S_over_min[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS]))
    axes[0].axvline(np.sqrt(A.Y0 * A.Y1), color="0.5", ls=":", lw=1)
    axes[0].set(xscale="log", xlabel="perspective parameter a", ylabel=r"$S_p^{side}(a)/\min_a S_p^{side}$", title="$l_y = 0.5 y_1$", ylim=(0.99, 1.3))
    axes[0].text(np.sqrt(A.Y0 * A.Y1) * 1.1, 1.25, r"$\sqrt{y_0 y_1}$", fontsize=8, color="0.4")
    A.shade(axes[1], A.Y0 / A.SPAN, A.Y1 / A.SPAN)
    A.draw_curves(axes[1], cols["kappa"], np.array([cols[f"a_top[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS]))
    axes[1].set(xlabel="$l_y/(y_1-y_0)$", ylabel="largest optimal a", title="top of the optimal range of a", ylim=(0, None))
    axes[0].legend(fontsize=7)
    fig.suptitle("Lloyd et al. 2007 Fig. 24: optimal perspective parameter of $S_p^{side}$ (θ = 45°, n = 1, f = 1000, $l_z$ = σ($y_1-y_0$))", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
