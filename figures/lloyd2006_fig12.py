"""Lloyd et al. 2006, Figure 12: storage factor S̄ over the number of shadow maps j.

Caption: "The storage factor is shown for the light overhead and behind the viewer for
various combinations of z-partitioning (ZP), face partitioning (FP), and warping (W).
(View frustum parameters: f/n = 1000 and θ = 30°)".  Here n = 1, f = 1000, fov = 60°,
j = 1 … 40, S̄ on a log axis; light overhead (left panel) and behind the viewer (right).

Curves: the closed forms of §5.3, derived with sympy in :mod:`aliasing.symbolic.lloyd2006`
and lambdified here (never retyped):

* overhead: ZP = eq. 17 and ZP+W = eq. 18, each with k = j z-partitions (one map each);
  FP+ZP+W = eq. 18 again (eq. 19: "only one face is visible to the light");
* behind: ZP = ZP+W = eq. 20 with k = j ("a ZP scheme cannot use warping because the view
  frustum is square"; the two coincide); FP+ZP+W = eq. 21.

Markers: the general vertex evaluation of :func:`aliasing.schemes.evaluate` for ``ZP<j>``
(ZP) and ``ZP<j>+LiSPSM`` (ZP+W, LiSPSM's rule n′ = n′_LiSPSM/sin γ, which becomes n′ = ∞
when the light is behind) at ``overhead`` / ``behind``; they equal the closed forms to
rounding (the tests check 1e-12).  FP+ZP+W behind is also evaluated generally, by
:mod:`aliasing.faces` (``FPc+ZP<k>+P``: the near face and four side faces, each split
into k depth ranges and warped in a bisector-aligned warping frustum, Lloyd 2006 §5.1);
it equals eq. 21 to rounding.  Overhead, the general evaluation needs only the bottom
face (the others are edge-on), i.e. k maps — eq. 19's "only one face is visible".

How FP+ZP+W counts shadow maps (the paper does not say it in one place; our reading):

* the text: "Since we must use a fixed number of z-partitions over all light directions in
  order to avoid popping, the FP+ZP+W scheme gets only one z-partitioning for every four
  shadow maps", and eq. 23, S̄ ∝ j (f/n)^(4/j), which is eq. 18 at k = j/4;
* eq. 21 adds the near face as a map of its own ("in addition we need to add in the near
  plane, for which the storage factor is 1").

So FP+ZP+W is drawn overhead at j = 4k (k = j/4: four side faces per z-partitioning, the
near face left out as §5.2 allows "for high depth ratios") and behind at j = 4k + 1
(k = (j − 1)/4: eq. 21's near-face map counted), only where k is whole.  Counting the near
map overhead too would shift the overhead FP+ZP+W points one map to the right.

What the text says and this figure shows:

* "Even ZP without warping does better than FP+ZP+W in the overhead case": for every j ≥ 4
  the ZP points lie below FP+ZP+W (j = 8: ZP 22.5, FP+ZP+W 53.0; j = 16: 11.5 vs 16.0;
  j = 40: 7.76 vs 8.62).
* Overhead values at j = 1, 5, 9: ZP 8.65·10⁵, 51.4, 19.4; ZP+W 865.2, 12.9, 9.00;
  the optimum ln(f/n)/(2 tanθ) = 5.98 (App. C) is drawn for reference.
* Behind, "the error for ZP schemes decreases rapidly and then begins to grow slowly"
  (overlap): k (f/n)^(2/k) has its minimum 37.6 at j = 14 (continuous k* = 2 ln(f/n) =
  13.8), then grows (43.5 at j = 25).
* "The FP+ZP+W scheme … eventually has lower error than the ZP schemes": first at j = 17
  (FP+ZP+W 38.0 against ZP 38.3), the crossover of Fig. 13.  Eq. 21 does not depend on θ
  (each side face seen from behind is the overhead case with tan θ′ = 1, for any θ),
  nor does eq. 20.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import sympy as sp

from aliasing import schemes
from aliasing.plotting import save, subplots
from aliasing.view import View

NAME = "lloyd2006-fig12"
NEAR, FAR, FOV = 1.0, 1000.0, 60.0  # printed in the caption: f/n = 1000, θ = 30°
MAPS = 40


@lru_cache(maxsize=1)
def closed_forms() -> dict[str, object]:
    """The §5.3 storage factors lambdified from the sympy derivations, as functions of
    (f, n, k, θ [rad]); k may be any positive real (eqs. 17, 18, 20, 21 and App. C)."""
    from aliasing.symbolic import lloyd2006 as L

    args = (L.f, L.n, L.k, L.theta)
    exprs = {
        "eq17": L.storage_zp_overhead(),
        "eq18": L.storage_zp_w_overhead(),
        "eq20": L.storage_zp_behind(),
        "eq21": L.storage_fp_zp_w_behind(),
        "optimal": L.storage_factor_optimal(),
    }
    return {key: sp.lambdify(args, expr, "numpy") for key, expr in exprs.items()}


def _where(mask: np.ndarray, func, k: np.ndarray) -> np.ndarray:
    out = np.full(k.shape, np.nan)
    out[mask] = func(k[mask])
    return out


def data(maps: int = MAPS) -> dict[str, np.ndarray]:
    cf = closed_forms()
    theta = View(NEAR, FAR, FOV).theta
    j = np.arange(1, maps + 1, dtype=float)
    # pass k as float: lambdify would otherwise raise integer arrays to negative powers
    S = {name: (lambda k, fn=cf[name]: np.broadcast_to(fn(FAR, NEAR, k, theta), np.shape(k)).astype(float)) for name in cf}
    cols: dict[str, np.ndarray] = {"j": j}
    cols["ZP_overhead"] = S["eq17"](j)
    cols["ZPW_overhead"] = S["eq18"](j)
    cols["FPZPW_overhead"] = _where(j % 4 == 0, lambda jj: S["eq18"](jj / 4), j)  # eq. 19, k = j/4
    cols["ZP_behind"] = S["eq20"](j)
    cols["ZPW_behind"] = S["eq20"](j)  # no warping possible from behind: ZP+W = ZP
    cols["FPZPW_behind"] = _where(((j - 1) % 4 == 0) & (j >= 5), lambda jj: S["eq21"]((jj - 1) / 4), j)  # eq. 21, j = 4k + 1
    cols["optimal"] = np.full(j.shape, float(S["optimal"](1.0)))
    for light in ("overhead", "behind"):
        for key, base in (("ZP", ""), ("ZPW", "+LiSPSM")):
            cols[f"general_{key}_{light}"] = np.array([r.S[0] for r in schemes.evaluate_many([f"ZP{int(m)}{base}" for m in j], NEAR, FAR, FOV, light)])
    fp_general = lambda jj: np.array([schemes.evaluate(f"FPc+ZP{int(k)}+P", NEAR, FAR, FOV, "behind").S[0] for k in (jj - 1) / 4])  # noqa: E731
    cols["general_FPZPW_behind"] = _where(np.isfinite(cols["FPZPW_behind"]), fp_general, j)
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    j = cols["j"]
    fig, axes = subplots(2, width=5.0, height=4.0, sharey=True)
    style = {"ZP": dict(color="C0"), "ZPW": dict(color="C1"), "FPZPW": dict(color="C2")}
    labels = {"ZP": "ZP", "ZPW": "ZP+W", "FPZPW": "FP+ZP+W"}
    for ax, light in zip(axes, ("overhead", "behind")):
        for key in ("ZP", "ZPW", "FPZPW"):
            y = cols[f"{key}_{light}"]
            ok = np.isfinite(y)
            if key == "ZPW" and light == "behind":
                ax.plot(j[ok], y[ok], ls="--", lw=1.2, label="ZP+W (= ZP, eq. 20)", **style[key])
            else:
                ax.plot(j[ok], y[ok], marker="o" if key == "FPZPW" else None, ms=4, label=labels[key], **style[key])
        for key, marker in (("ZP", "x"), ("ZPW", "+"), ("FPZPW", "1")):
            if f"general_{key}_{light}" in cols:
                ax.plot(j, cols[f"general_{key}_{light}"], ls="none", marker=marker, ms=6, color="k", alpha=0.7, label=f"{labels[key]}, general evaluation")
        ax.set(xlabel="number of shadow maps j", yscale="log", xlim=(0, j[-1] + 1))
    axes[0].axhline(cols["optimal"][0], color="0.5", ls=":", lw=1, label=f"optimal, ln(f/n)/(2 tanθ) = {cols['optimal'][0]:.2f}")
    axes[0].set(ylabel=r"storage factor $\bar S$", title="light overhead (eqs. 17, 18, 19; FP at j = 4k)")
    axes[1].set(title="light behind (eqs. 20, 21; FP at j = 4k + 1)")
    fp, zp = cols["FPZPW_behind"], cols["ZP_behind"]
    first = int(j[np.nonzero(fp < zp)[0][0]])
    axes[1].axvline(first, color="0.5", ls=":", lw=1)
    axes[1].annotate(f"FP+ZP+W lower\nfrom j = {first}", (first, zp[first - 1]), xytext=(first + 1.5, 300), fontsize=8, arrowprops=dict(arrowstyle="->", color="0.4"))
    for ax in axes:
        ax.legend(fontsize=7.5)
    fig.suptitle(f"Lloyd et al. 2006 Fig. 12: storage factor over the number of shadow maps (f/n = {FAR / NEAR:g}, θ = {FOV / 2:g}°)", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
