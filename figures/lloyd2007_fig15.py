"""Lloyd et al. 2007, Figure 15: S̄ over the light angle γ for z-partitioning and face partitioning.

Caption: "z-partitioning using various parameterizations. z-partitioning leads to
significant error reductions but requires many partitions to converge to the same error as
a face partitioning scheme that uses a logarithmic+perspective parameterization.
(f/n = 1024, θ = 30°)".  The text (§7): "for other light positions increasing k produces
drastic reductions in error that then trail off.  The benefit of warping is also reduced.
For comparison, the error for FP+Log and FPcs+LogP are also shown … A small rise in
FPcs+LogP can be seen at γ = θ where a new face partition appears and is split."

Our choices (the image is not in the text extraction): a directional light in the view's
vertical plane (azimuth 0), γ from 0.25° to 90° in 0.25° steps; three panels for the
uniform (ZPk), perspective (ZPk+P) and log+perspective (ZPk+LogP) maps with k = 1, 2, 3,
5, 7 (k = 1 is the single map); FP+LogP and FPcs+LogP (τ0 = 120°, τ1 = 150°) in every
panel; S̄ on a log axis, 1/cos²θ omitted as in Table 3.

Output: ``lloyd2007-fig15.png`` and ``.csv`` (one column per curve).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import schemes
from aliasing.geometry import light_direction
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig15"
NEAR, FAR, FOV = 1.0, 1024.0, 60.0
KS = (1, 2, 3, 5, 7)
BASES = (("", "uniform (ZPk)"), ("+P", "perspective (ZPk+P)"), ("+LogP", "log+perspective (ZPk+LogP)"))
FACES = ("FP+LogP", "FPcs+LogP")


def data() -> dict[str, np.ndarray]:
    gamma = np.arange(1, 361) * 0.25
    light = light_direction(gamma, 0.0)
    cols: dict[str, np.ndarray] = {"gamma": gamma}
    names = [f"ZP{k}{base}" for base, _ in BASES for k in KS]
    results = schemes.evaluate_many(names + list(FACES), NEAR, FAR, FOV, light)  # one light frame for all rows
    for name, r in zip(names, results):
        cols[name] = r.S
    for name, r in zip(FACES, results[len(names) :]):
        cols[name], cols[f"{name} maps"] = r.S, r.maps_used.astype(float)
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    g = cols["gamma"]
    fig, axes = subplots(3, width=4.2, height=3.6, sharey=True)
    for ax, (base, title) in zip(axes, BASES):
        for i, k in enumerate(KS):
            ax.plot(g, cols[f"ZP{k}{base}"], color=f"C{i}", lw=1.2, label="single map" if k == 1 else f"k = {k}")
        ax.plot(g, cols["FP+LogP"], color="k", lw=1.4, label="FP+LogP")
        ax.plot(g, cols["FPcs+LogP"], color="k", lw=1.0, ls="--", label="FPcs+LogP")
        ax.axvline(FOV / 2, color="0.6", ls=":", lw=1)
        ax.set(title=title, xlabel="γ [deg] (light in the view's vertical plane)", yscale="log", xlim=(0, 90))
    axes[0].set(ylabel=r"storage factor $\bar S$ (1/cos²θ omitted)")
    # in the empty band between the single map (~10⁶) and k = 2 (~2·10³) of the uniform panel, right of γ = θ
    axes[0].legend(fontsize=7.5, ncol=2, loc="center", bbox_to_anchor=(0.7, 0.71))
    fig.suptitle(f"Lloyd et al. 2007 Fig. 15: z-partitioning vs face partitioning (f/n = {FAR / NEAR:g}, θ = {FOV / 2:g}°)", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
