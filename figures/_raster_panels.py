"""Shared code of the rasterizer picture scripts (raster_shadows, raster_grid, raster_error).

A seeded ground-and-boxes scene, n = 1, f = 100, fov 60°, light at γ = 110°, azimuth 60°, a 256²
texel budget shared by each scheme's maps, a 256² image, schemes Standard, P, LogP, ZP4+P.
The CSV holds per scheme the fraction of lit pixels (shadows), grid-line pixels (grid) or
the 99th percentile of the error (error).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.plotting import save, subplots
from aliasing import pictures

NEAR, FAR, FOV, GAMMA, AZIMUTH, BUDGET, IMAGE = 1.0, 100.0, 60.0, 110.0, 60.0, 256**2, 256
LIGHT = f"gamma:{GAMMA:g}@azimuth:{AZIMUTH:g}"
# what each picture shows, and what the number beside each scheme's name is
TITLES = {"shadows": ("Shadowed renders", "fraction of the scene's pixels that are lit"),
          "grid": ("Shadow-map texel grid (every 8th texel line)", "fraction of pixels on grid lines"),
          "error": ("Measured perspective error", "99th percentile of the error [pixels per texel]")}
SCHEMES = ["Standard", "P", "LogP", "ZP4+P"]


def data(what: str) -> tuple[list[np.ndarray], dict[str, np.ndarray]]:
    imgs, stat = [], []
    for sch in SCHEMES:
        kw = dict(image_res=IMAGE, budget=BUDGET)
        if what == "shadows":
            img = pictures.shadow_image(NEAR, FAR, FOV, LIGHT, sch, **kw)
            v = pictures.view(NEAR, FAR, FOV, LIGHT, sch, **kw)
            stat.append(float(v.lit[v.triangle >= 0].mean()))
        elif what == "grid":
            img = pictures.grid_image(NEAR, FAR, FOV, LIGHT, sch, every=8, **kw)
            stat.append(float(np.mean(np.any(img == 0, axis=-1))))
        else:
            img, err = pictures.error_image(NEAR, FAR, FOV, LIGHT, sch, **kw)
            stat.append(float(np.nanpercentile(err, 99)))
        imgs.append(img)
    return imgs, {"scheme_index": np.arange(len(SCHEMES)), "value": np.array(stat)}


def main(out_dir: Path, name: str, what: str) -> list[Path]:
    imgs, cols = data(what)
    fig, axes = subplots(len(SCHEMES), width=3.0, height=3.1)
    for ax, img, sch, val in zip(axes, imgs, SCHEMES, cols["value"]):
        ax.imshow(img, interpolation="nearest")
        ax.set_axis_off()
        ax.set_title(f"{sch}: {val:.3g}", fontsize=9)
    if what == "error":  # the colours of pictures.error_colours: jet on a log scale from 1 to 64
        from matplotlib import colormaps
        from matplotlib.cm import ScalarMappable
        from matplotlib.colors import LogNorm

        bar = fig.colorbar(ScalarMappable(LogNorm(1.0, 64.0), colormaps["jet"]), ax=axes[-1], fraction=0.05, pad=0.02)
        bar.set_label("error [pixels per texel]", fontsize=8)
    title, number = TITLES[what]
    fig.suptitle(f"{title}: f/n = {FAR / NEAR:g}, light at γ = {GAMMA:g}°, azimuth {AZIMUTH:g}°, {round(BUDGET ** 0.5)}² texels per scheme\n"
                 f"beside each scheme: the {number}", fontsize=9)
    return save(fig, out_dir, name, cols)
