"""Lloyd et al. 2007, Figure 26: storage factors of the logarithmic+perspective parameterizations.

App. A of the LogPSM report (eqs. 104–110), computed by :mod:`aliasing.face_factors`.

* Left: S_lp^side = R_p,s R_lp,t of "the linear form of δ_lp,t that we use for LogPSMs"
  (b = ∞), with a optimised numerically per light position
  (:func:`~aliasing.face_factors.optimal_factors`, ``minimize="S"``).
* Middle: "parabolic spacing functions that can give a good fit to δ_b,t^side": for one light,
  the spacing δ_b,t^side that the bound requires and those that the linear form (a = 0),
  one parabola (a = 0, b optimised, :func:`~aliasing.face_factors.optimal_root`) and two
  parabolas (the face split at y_s = l_y, a = 0 and b optimised in each part) provide at their
  critical resolution: (y1 − y0) δ_b,t and W δ_lp,t/R_lp,t, in world units along y per image
  pixel (r_j = 1; W is the width in y of the part a parabola covers).  A spacing function
  fits where its curve meets the bound's; none crosses it.
* Right: "the two parabola form gives a storage factor that approaches that of δ_b,t^side":
  S = Σ R_s R_t over the two parts (one part when the light is not over the face), beside the
  error-bound S_b = R_b,s R_b,t (dashed).

Frustum θ = 45°, n_e = 1, f_e = 1000; l_x = 0.  Heights as printed in this caption,
l_z = σ y1 (the other App. A captions have σ (y1 − y0), 0.1 % lower; docs/ERRATA.md), σ = 0.1,
0.2, 0.5, 1, ∞ (dark to light); x axes l_y/(y1 − y0) ∈ [−1, 2], grey band: the light over the
face.  Our choices (no image in the extraction): the middle panel's light, l_y = (y1 − y0)/2
and σ = 0.1 (no light is given; this is where δ_b,t^side undulates most, Fig. 18); the
S_lp of the left panel uses the optimal a that we find; the bound's S_b on the right.

What the text says and this figure shows:

* "We find the optimal a parameter numerically.  It appears that the optimal parameter is
  always a = 0": on this grid the S-optimal a is 0 for every light position (column
  ``a_opt``), and S_lp ≤ (1/cos θ) ln(f/n)/sin 2θ = 9.77 (eqs. 99 × 103) with equality at σ = ∞.
* "The two parabola form gives a storage factor that approaches that of δ_b,t^side" and
  "the curves for R_lp,t^side are very similar to those for R_b,t^side": on this grid the
  two-parabola S is at most 9.8 % above S_b (σ = 0.1; equal at σ = ∞, where each part's
  linear form is exact), while the linear form's S_lp is up to 7.1 times S_b.  In the middle
  panel R_t = 6.91 (linear), 5.12 (one parabola), 2.14 (two parabolas), ρ_b,t = 1.99.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import logpsm
from aliasing.face_factors import face_factors, optimal_factors, optimal_root
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig26"
FIT_KAPPA, FIT_SIGMA = 0.5, 0.1


def two_parabolas(ly, lz, samples: int = 129) -> dict[str, np.ndarray]:
    """Σ R_s R_t of the face split at y_s = l_y into two parts, each with a = 0 and its optimal b.

    Lights not over the face (l_y ∉ (y0, y1)) get one part.  Returns ``S``, ``R_t`` (the sum),
    and per part ``R_t1``, ``R_t2``, ``b1``, ``b2``, ``y_s``.
    """
    ly, lz = np.broadcast_arrays(np.asarray(ly, float), np.asarray(lz, float))
    split = (ly > A.Y0 * (1 + 1e-9)) & (ly < A.Y1 * (1 - 1e-9))
    y_s = np.where(split, ly, A.Y1)
    ct = A.COS_THETA
    # the parts are the side faces of the sub-frusta [n, y_s cos θ] and [y_s cos θ, f] (same eye, same frame)
    one = optimal_root(A.NEAR, np.where(split, y_s * ct, A.FAR), A.FOV, ly=ly, lz=lz, samples=samples)
    two = optimal_root(np.where(split, y_s * ct, A.NEAR), A.FAR, A.FOV, ly=ly, lz=lz, samples=samples)
    S = one["S"] + np.where(split, two["S"], 0.0)
    return {"S": S, "R_t": one["R_t"] + np.where(split, two["R_t"], 0.0), "R_t1": one["R_t"], "R_t2": np.where(split, two["R_t"], 0.0),
            "b1": one["b"], "b2": np.where(split, two["b"], np.nan), "y_s": np.where(split, y_s, np.nan)}


def fits(count: int = 401) -> dict[str, np.ndarray]:
    """The middle panel: y, the bound's (y1 − y0) δ_b,t and the fits' W δ/R (world units per pixel)."""
    ly, lz = FIT_KAPPA * A.SPAN, FIT_SIGMA * A.Y1
    v = np.linspace(0.0, 1.0, count)
    y = A.Y0 + A.SPAN * v
    out = {"y": y, "bound": A.SPAN * logpsm.delta_bound_side_t(v, A.NEAR, A.FAR, A.FOV, ly=ly, lz=lz)}  # eq. (62)
    lin = face_factors("logp", A.NEAR, A.FAR, A.FOV, ly=ly, lz=lz)
    out["linear"] = A.SPAN * logpsm.spacing("logp_t", v, A.NEAR, A.FAR, A.FOV) / lin["R_t"]  # eq. (102) with a = 0
    par = optimal_root(A.NEAR, A.FAR, A.FOV, ly=ly, lz=lz)
    out["one_parabola"] = A.SPAN * logpsm.spacing("logp_t", v, A.NEAR, A.FAR, A.FOV, b=par["b"]) / par["R_t"]  # eq. (109)
    two = two_parabolas(ly, lz)
    curve = np.empty_like(y)
    for lo, hi, b, R in ((A.Y0, ly, two["b1"], two["R_t1"]), (ly, A.Y1, two["b2"], two["R_t2"])):
        part = (y >= lo) & (y <= hi)
        vp = np.clip((y[part] - lo) / (hi - lo), 0.0, 1.0)
        curve[part] = (hi - lo) * logpsm.spacing("logp_t", vp, lo * A.COS_THETA, hi * A.COS_THETA, A.FOV, b=b) / R
    out["two_parabolas"] = curve
    out["R"] = np.array([float(lin["R_t"]), float(par["R_t"]), float(two["R_t"]), float(face_factors("bound", A.NEAR, A.FAR, A.FOV, ly=ly, lz=lz)["R_t"])])
    return out


def data(count: int = 61) -> dict[str, np.ndarray]:
    """Columns ``kappa``, ``S_lp[sigma=…]``, ``a_opt[…]``, ``S_two_parabolas[…]``, ``S_b[…]``."""
    kappa = np.linspace(-1.0, 2.0, count)
    light = dict(ly=kappa * A.SPAN, lz=A.heights(scale=A.Y1))
    lin = optimal_factors("logp", A.NEAR, A.FAR, A.FOV, minimize="S", samples=129, **light)
    blocks = {
        "S_lp": lin["S"],
        "a_opt": lin["a"],
        "S_two_parabolas": two_parabolas(**light)["S"],
        "S_b": face_factors("bound", A.NEAR, A.FAR, A.FOV, **light)["S"],
    }
    return A.columns("kappa", kappa, blocks)


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fit = fits()
    kappa = cols["kappa"]
    rows = lambda name: np.array([cols[f"{name}[sigma={A.sigma_key(s)}]"] for s in A.SIGMAS])  # noqa: E731
    fig, axes = subplots(3, width=3.8, height=3.4)
    band = (A.Y0 / A.SPAN, A.Y1 / A.SPAN)
    ax = axes[0]
    A.shade(ax, *band)
    A.draw_curves(ax, kappa, rows("S_lp"))
    ax.set(xlabel="$l_y/(y_1-y_0)$", ylim=(0, None), title=r"$S_{lp}^{side}$, linear $\delta_{lp,t}$ (b = ∞), optimal a")
    ax.legend(fontsize=7, loc="lower center")
    ax = axes[1]
    ax.plot(fit["y"], fit["bound"], color="k", lw=2.0, label=r"bound $(y_1-y_0)\,\delta_{b,t}^{side}$")
    for key, label, style in (("linear", "linear (b = ∞)", dict(color="C1", ls="--")), ("one_parabola", "one parabola", dict(color="C2")),
                              ("two_parabolas", "two parabolas ($y_s = l_y$)", dict(color="C3", ls="-."))):
        ax.plot(fit["y"], fit[key], lw=1.1, label=label, **style)
    ax.axvline(FIT_KAPPA * A.SPAN, color="0.6", ls=":", lw=0.8)
    ax.set(xlabel="y", ylabel="spacing at critical resolution", xlim=(A.Y0, A.Y1), ylim=(0, None),
           title=f"fits, $l_y$ = {FIT_KAPPA:g}($y_1-y_0$), $l_z$ = {FIT_SIGMA:g}$y_1$")
    ax.legend(fontsize=7)
    ax = axes[2]
    A.shade(ax, *band)
    A.draw_curves(ax, kappa, rows("S_two_parabolas"))
    A.draw_curves(ax, kappa, rows("S_b"), ls="--", lw=0.8)
    ax.set(xlabel="$l_y/(y_1-y_0)$", ylim=(0, None), title="S, two parabolas (dashed: $S_b$)")
    for ax in axes:
        ax.title.set_fontsize(9)
    fig.suptitle("Lloyd et al. 2007 Fig. 26: log+perspective parameterizations (θ = 45°, n = 1, f = 1000, $l_x$ = 0, $l_z$ = σ$y_1$)", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
