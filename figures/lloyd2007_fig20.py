"""Lloyd et al. 2007, Figure 20: the error-bound spacing δ_b,s^side(u, v) of a side face.

App. A of the LogPSM report.  δ_b,s^side(u, v) = (y(v)/y1) cos θ/cos φ_lx(u) (eq. 61,
:func:`aliasing.logpsm.delta_bound_side_s`) "with the light centered over the face":
l_x = 0, l_y = (y0 + y1)/2; θ = 45°, n_e = 1, f_e = 1000 as in the other App. A figures.

Our choices (the caption gives no height and the extraction has no image): l_z = 0.1 (y1 − y0)
(σ = 0.1, the lowest light of Figs. 18–21, where the shape is most pronounced); a colour map
over the (u, v) domain of the shadow map, log colour scale, shown on the face only (the
trapezoid u0(v) ≤ u ≤ u1(v), eq. 69; outlined), with contour lines.  The CSV holds δ_b,s on
the whole domain (eq. 61 is defined there) and a 0/1 column ``on_face``.

What the text says and this figure shows: "δ_b,s^side is essentially δ_b,t^end extruded along
the y direction and scaled by y": δ_b,s^side(u, v) = (y(v)/y1) · δ_b,t^end(u) of the far face
(whose width W_e f/n equals the side face's u-domain width x1(y1) − x0(y1)) with l_y → l_x —
exactly, each row is the Fig. 19 curve scaled by y(v)/y1.  Its minimum on each row is under
the light (u = 1/2).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import logpsm
from aliasing.figures import _lloyd2007_appendix_a as A
from aliasing.plotting import save, subplots

NAME = "lloyd2007-fig20"
SIGMA = 0.1


def data(count: int = 101) -> dict[str, np.ndarray]:
    """Long-format columns ``u``, ``v``, ``delta_b_s`` and ``on_face`` over a count × count grid."""
    u, v = np.meshgrid(np.linspace(0.0, 1.0, count), np.linspace(0.0, 1.0, count))
    delta = logpsm.delta_bound_side_s(u, v, A.NEAR, A.FAR, A.FOV, lx=0.0, lz=SIGMA * A.SPAN)  # eq. (61)
    y = A.Y0 + A.SPAN * v
    on_face = np.abs(u - 0.5) <= y / (2 * A.Y1) + 1e-12  # u0(v) ≤ u ≤ u1(v), eq. (69)
    return {"u": u.ravel(), "v": v.ravel(), "delta_b_s": delta.ravel(), "on_face": on_face.ravel().astype(float)}


def main(out_dir: Path) -> list[Path]:
    from matplotlib.colors import LogNorm

    count = 101
    cols = data(count)
    u, v = cols["u"].reshape(count, count), cols["v"].reshape(count, count)
    delta = np.where(cols["on_face"] > 0, cols["delta_b_s"], np.nan).reshape(count, count)
    fig, ax = subplots(width=5.2, height=4.2)
    mesh = ax.pcolormesh(u, v, delta, norm=LogNorm(np.nanmin(delta), np.nanmax(delta)), cmap="viridis", shading="nearest")
    ax.contour(u, v, delta, levels=np.geomspace(1e-3, 4.0, 9), colors="w", linewidths=0.5)
    edge = np.linspace(0.0, 1.0, 2)
    half = (A.Y0 + A.SPAN * edge) / (2 * A.Y1)
    ax.plot(np.concatenate([0.5 - half, (0.5 + half)[::-1], [0.5 - half[0]]]), np.concatenate([edge, edge[::-1], [0.0]]), color="k", lw=0.8)
    fig.colorbar(mesh, ax=ax, label=r"$\delta_{b,s}^{side}(u, v)$")
    ax.set(xlim=(0, 1), ylim=(0, 1), xlabel="u", ylabel="v", title=f"Lloyd et al. 2007 Fig. 20: $\\delta_{{b,s}}^{{side}}(u, v)$ on a side face\n(light centred, $l_z$ = {SIGMA:g}($y_1-y_0$), θ = 45°, n = 1, f = 1000)")
    ax.title.set_fontsize(9)
    ax.grid(False)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
