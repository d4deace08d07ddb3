"""Shared setting of the Lloyd et al. 2007 App. A figure scripts (Figs. 18–21, 25, 26).

The captions' frustum: θ = 45° (fov 90°), n_e = 1, f_e = 1000; the side face in the frame of
the paper's Fig. 5 (origin at the eye, y along the face's centre line, z its normal),
y0 = n/cos θ, y1 = f/cos θ; light heights l_z = σ (y1 − y0), σ = 0.1, 0.2, 0.5, 1, ∞ drawn from
dark to light.  Light positions along the figures' x axes are written κ = l/(y1 − y0) (Fig.
18's caption uses l_y = κ (y1 − y0)); the grey band marks the light positions over the face.
"""

from __future__ import annotations

import numpy as np

from aliasing import logpsm

NEAR, FAR, FOV = 1.0, 1000.0, 90.0
SIGMAS = (0.1, 0.2, 0.5, 1.0, np.inf)
Y0, Y1, W_E, COS_THETA = (float(q) for q in logpsm.side_face(NEAR, FAR, FOV))
SPAN = Y1 - Y0  # l = κ·SPAN, l_z = σ·SPAN


def colors(count: int = len(SIGMAS)) -> np.ndarray:
    """Dark to light, one per σ."""
    from matplotlib import colormaps

    return colormaps["Blues"](np.linspace(0.95, 0.4, count))


def sigma_label(sigma: float) -> str:
    return "σ = ∞" if np.isinf(sigma) else f"σ = {sigma:g}"


def sigma_key(sigma: float) -> str:
    return "inf" if np.isinf(sigma) else f"{sigma:g}"


def heights(sigmas=SIGMAS, scale: float = SPAN) -> np.ndarray:
    """l_z = σ·scale as a column (σ on axis 0)."""
    return np.asarray(sigmas, float)[:, None] * scale


def draw_curves(ax, x: np.ndarray, curves: np.ndarray, sigmas=SIGMAS, **style) -> None:
    """One curve per σ (rows of ``curves``), dark to light."""
    for c, sigma, y in zip(colors(len(sigmas)), sigmas, curves):
        ax.plot(x, y, color=c, label=sigma_label(sigma), **style)


def shade(ax, lo: float, hi: float) -> None:
    """The grey band of light positions over the face."""
    ax.axvspan(lo, hi, color="0.88", zorder=0, lw=0)


def columns(x_name: str, x: np.ndarray, blocks: dict[str, np.ndarray], sigmas=SIGMAS) -> dict[str, np.ndarray]:
    """Wide CSV columns: x, then ``name[sigma=…]`` for every block (rows = σ)."""
    cols = {x_name: x}
    for name, rows in blocks.items():
        for sigma, row in zip(sigmas, rows):
            cols[f"{name}[sigma={sigma_key(sigma)}]"] = row
    return cols


def panel_figure(cols: dict[str, np.ndarray], panels, title: str):
    """Figs. 21–23's layout: one panel per ``(name, label, _, band, xlabel)``, a curve per σ.

    ``cols`` holds ``kappa[name]`` and ``name[sigma=…]`` columns (:func:`columns`).
    """
    from aliasing.plotting import subplots

    fig, axes = subplots(len(panels), width=3.6, height=3.2)
    for ax, (name, label, _, band, xlabel) in zip(axes, panels):
        shade(ax, *band)
        draw_curves(ax, cols[f"kappa[{name}]"], np.array([cols[f"{name}[sigma={sigma_key(s)}]"] for s in SIGMAS]))
        ax.set(xlabel=xlabel, ylim=(0, None), title=label)
    axes[0].legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    return fig
