"""Rasterizer pictures (shadows): a seeded ground-and-boxes scene, n = 1, f = 100, fov 60°,
light gamma:110@azimuth:60, 256² texel budget shared by each scheme's maps, 256² image.

shadows: Lambert + shadow-map test for Standard, P, LogP, ZP4+P.  grid: texel grid every 8
texels projected on the scene (Lloyd 2006 Fig. 15 style).  error: measured perspective error
per pixel [pixels per texel], log colour scale, blue ≤ 1 … red ≥ 64 (Lloyd 2007 Fig. 13
style, matched to its caption only).  The CSV holds per scheme the fraction of lit pixels
(shadows), grid-line pixels (grid) or error percentiles (error).

Known limitation of this picture: with 256² texels a Standard map's texels are so large that
the slope-scaled depth bias (1.5 texels of depth change) exceeds the small boxes' heights,
so most of their shadows leak ("peter-panning"; lit fraction 0.99 against 0.89 for the
warped maps). It shows a real consequence of large texels, but a smaller bias with acne
checks would make the comparison fairer.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.plotting import save, subplots
from aliasing.raster import pictures

NAME = "raster-shadows"
WHAT = "shadows"
NEAR, FAR, FOV, LIGHT, BUDGET, IMAGE = 1.0, 100.0, 60.0, "gamma:110@azimuth:60", 256**2, 256
SCHEMES = ["Standard", "P", "LogP", "ZP4+P"]


def data() -> tuple[list[np.ndarray], dict[str, np.ndarray]]:
    imgs, stat = [], []
    for sch in SCHEMES:
        kw = dict(image_res=IMAGE, budget=BUDGET)
        if WHAT == "shadows":
            img = pictures.shadow_image(NEAR, FAR, FOV, LIGHT, sch, **kw)
            v = pictures.view(NEAR, FAR, FOV, LIGHT, sch, **kw)
            stat.append(float(v.lit[v.triangle >= 0].mean()))
        elif WHAT == "grid":
            img = pictures.grid_image(NEAR, FAR, FOV, LIGHT, sch, every=8, **kw)
            stat.append(float(np.mean(np.any(img == 0, axis=-1))))
        else:
            img, err = pictures.error_image(NEAR, FAR, FOV, LIGHT, sch, **kw)
            stat.append(float(np.nanpercentile(err, 99)))
        imgs.append(img)
    return imgs, {"scheme_index": np.arange(len(SCHEMES)), "value": np.array(stat)}


def main(out_dir: Path) -> list[Path]:
    imgs, cols = data()
    fig, axes = subplots(len(SCHEMES), width=3.0, height=3.1)
    for ax, img, sch, val in zip(axes, imgs, SCHEMES, cols["value"]):
        ax.imshow(img, interpolation="nearest")
        ax.set_axis_off()
        ax.set_title(f"{sch} ({val:.3g})", fontsize=9)
    fig.suptitle(f"{NAME}: f/n = 100, {LIGHT}, 256² texels; value: " + {"shadows": "lit fraction", "grid": "line fraction", "error": "99th pct error"}[WHAT], fontsize=9)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
