"""Lloyd et al. 2006, Figure 7: the storage factor S̄ over the hemisphere of light directions.

log10 S̄ for every directional light above the viewer, seen from above (orthographic
projection of the hemisphere, :func:`aliasing.geometry.hemisphere_map`): overhead in the
centre, light behind the viewer on the left (u = −1), in front of the viewer on the right
(u = +1), sideways along v.  Three panels with one colour scale:

* without warping: a standard (uniform) shadow map, n′ = ∞ (scheme ``Standard``);
* with warping: LiSPSM, n′ = n′_LSPSM.  The paper does not say how n′_LSPSM varies with
  the light direction; we use LiSPSM's own rule n′ = (n + √(fn))/sin γ (warping rule
  ``lispsm``, Wimmer et al. 2004 §4.4), γ folded to [0°, 90°], which reverts continuously
  to n′ = ∞ as the light moves behind or in front of the viewer;
* face partitioning with warping (§5.1, "FP+W"): one LiSPSM map per chosen face, its light
  space aligned with the bisector of the face's projected side edges — scheme ``FPc+P`` of
  :mod:`aliasing.faces` (3–5 maps; their S̄ summed).

S̄ = M_x·M_z with M_x, M_z the maxima of m_x, m_z over the frustum's 8 vertices in Wimmer
light space (§4.4; :mod:`aliasing.directional`), unit resolutions.

Parameters: the paper prints none for Fig. 7 (neither its caption nor §4.4 names f/n or θ);
we use f/n = 1000 (n = 1, f = 1000) and θ = 30° (fov 60°), the view frustum of its Fig. 12.

What the paper's text says (§4.4) and this figure shows:

* "Without warping, the error is high over all light directions": log10 S̄ ∈ [5.94, 6.30].
  The minimum (f/n)(f/n − 1)/(2 tanθ) ≈ 8.65·10⁵ holds on the whole great circle γ = 90°
  (u = 0, overhead and sideways lights); S̄ = (f/n)² = 10⁶ directly behind and in front;
  the maximum → 2(f/n)² (log10 6.30) is at γ → 0° with a diagonal azimuth (the square
  frustum seen along its diagonal), i.e. near the rim at u ≈ ±1, v ≠ 0.  The spread,
  max/min ≈ 2.31, is Lloyd 2007 Table 3's Standard row.
* "With warping the error is lowest for the overhead position at the center of the plot":
  S̄ = (f/n − 1)/(2 tanθ) ≈ 865 (log10 2.94, eq. 12), and along the whole u = 0 line.
* "It is highest when the light comes from directly behind or in front of the viewer",
  where the frustum looks square, cannot be warped and the map reverts to n′ = ∞: the
  warped panel rises by more than three decades towards u = ±1, steeply where the light
  comes within θ of the view axis (|u| = |cos γ| > cos θ ≈ 0.87), and both panels agree at
  u = ±1, v = 0 (S̄ = 10⁶).  Observed nuance: the warped maximum is not at γ = 0° itself
  but in a ring at γ ≈ 9–13° (log10 S̄ ≈ 6.5–6.7, max ≈ 4.7·10⁶), *above* the standard
  map's values, because 1/sin γ does not reach n′ = ∞ fast enough.  That is Lloyd et al.
  2007's reason for its η shaping function (§6.1.1, App. B; its Table 3 1/sin γ row peaks
  at 3.65·10⁶ with n′ in light-plane units).  The extraction has no image, so whether the
  paper's LSPSM panel shows this overshoot cannot be checked.

Paper inconsistencies and what is not reproduced:

* §4.4 writes "with and without warping (n′ = ∞ and n′ = n′_LSPSM, respectively)": the
  pairing is reversed; without warping is n′ = ∞ (the extraction also prints ∞ as "1").
* §5.1 says "Figure 7 shows how face partitioning reduces the error for the problematic
  light/camera configurations", so the printed figure has a face-partitioned (FP+W) panel
  the caption does not list; ours is the third.  It does what the text says: behind and
  in front S̄ = 2(f/n − 1) + 1 ≈ 2.0·10³ (log10 3.30) instead of 10⁶, overhead the same
  865 as LiSPSM, and its maximum over the disc is more than two decades below the other
  panels' (log10 ≈ 3.5; Lloyd 2007 L18: near the four lateral-edge directions it peaks).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.patches import Circle

from aliasing import schemes
from aliasing.geometry import hemisphere_map
from aliasing.plotting import save, subplots

NAME = "lloyd2006-fig7"
NEAR, FAR, FOV = 1.0, 1000.0, 60.0  # not printed for Fig. 7: f/n = 1000, θ = 30° as in Fig. 12
SCHEMES = {"standard": "Standard", "lispsm": "lispsm", "fpw": "FPc+P"}  # column suffix → scheme name
RESOLUTION = 201


def data(resolution: int = RESOLUTION) -> dict[str, np.ndarray]:
    """log10 S̄ on a ``resolution``² grid over the unit disc (NaN outside), flattened.

    ``resolution`` must be odd so that the overhead direction (u = v = 0) is a grid point.
    """
    if resolution % 2 != 1:
        raise ValueError(f"resolution must be odd (so the overhead light is on the grid), got {resolution!r}")
    u, v, light = hemisphere_map(resolution)
    inside = ~np.isnan(light[..., 0])
    cols: dict[str, np.ndarray] = {"u": u.ravel(), "v": v.ravel()}
    results = schemes.evaluate_many(list(SCHEMES.values()), NEAR, FAR, FOV, light[inside])  # all schemes and directions in one call
    for key, r in zip(SCHEMES, results):
        s = np.full(u.shape, np.nan)
        s[inside] = r.S
        cols[f"log10S_{key}"] = np.log10(s).ravel()
    return cols


def _fill_outside(grid: np.ndarray) -> np.ndarray:
    """``grid`` with its NaN cells (outside the disc) set to the nearest inside cell's value: for the picture only."""
    from scipy import ndimage

    outside = np.isnan(grid)
    index = ndimage.distance_transform_edt(outside, return_distances=False, return_indices=True)
    return grid[tuple(index)]


def main(out_dir: Path) -> list[Path]:
    cols = data()
    res = int(round(np.sqrt(cols["u"].size)))
    grids = {key: cols[f"log10S_{key}"].reshape(res, res) for key in SCHEMES}
    lo = min(np.nanmin(g) for g in grids.values())
    hi = max(np.nanmax(g) for g in grids.values())
    fig, axes = subplots(3, width=4.4, height=4.4)
    titles = {"standard": "without warping (standard, $n'=\\infty$)", "lispsm": "with warping (LiSPSM, $n'=(n+\\sqrt{fn})/\\sin\\gamma$)", "fpw": "face partitioning + warping (FP+W)"}
    # the grid's points lie on [-1, 1] (linspace), so each cell reaches half a step beyond them; cells
    # whose centre lies just outside the disc still cover part of it: they show the nearest inside
    # value, and the picture is clipped to the disc (no background specks along the rim)
    half = 1.0 / (res - 1)
    for ax, key in zip(axes, SCHEMES):
        shown = _fill_outside(grids[key])
        im = ax.imshow(shown, origin="lower", extent=(-1 - half, 1 + half, -1 - half, 1 + half), vmin=lo, vmax=hi, cmap="viridis", interpolation="nearest")
        im.set_clip_path(ax.add_patch(Circle((0, 0), 1.0, fill=False, lw=0, transform=ax.transData)))
        ax.add_patch(Circle((0, 0), 1.0, fill=False, lw=1.2, color="k"))
        ax.grid(False)
        ax.set(title=titles[key], xlabel="u   (behind ← overhead → in front)", ylabel="v   (sideways)", xlim=(-1.02, 1.02), ylim=(-1.02, 1.02), aspect="equal")
        ax.title.set_fontsize(9)
        centre = grids[key][res // 2, res // 2]
        ax.annotate(f"{centre:.2f}", (0, 0), color="w", ha="center", va="center", fontsize=8)
    cbar = fig.colorbar(im, cax=axes[-1].inset_axes((1.05, 0.0, 0.05, 1.0)))
    cbar.set_label(r"$\log_{10}\bar S$")
    fig.suptitle(f"Lloyd et al. 2006 Fig. 7: storage factor over the hemisphere (f/n = {FAR / NEAR:g}, θ = {FOV / 2:g}°)", fontsize=10)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
