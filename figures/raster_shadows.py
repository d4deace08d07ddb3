"""Rasterizer pictures (shadows): Lambert shading with the shadow-map test, for Standard, P, LogP and ZP4+P.

Scene, light and budget: see figures/_raster_panels.py (n = 1, f = 100, fov 60°,
gamma:110@azimuth:60, 256² texels shared by each scheme's maps, 256² image).

Known limitation of this picture: with 256² texels a Standard map's texels are so large that
the slope-scaled depth bias (1.5 texels of depth change) exceeds the small boxes' heights,
so most of their shadows leak ("peter-panning"; lit fraction 0.99 against 0.89 for the
warped maps). It shows a real consequence of large texels, but a smaller bias with acne
checks would make the comparison fairer.
"""

from __future__ import annotations

from pathlib import Path

from aliasing.figures import _raster_panels

NAME = "raster-shadows"


def main(out_dir: Path) -> list[Path]:
    return _raster_panels.main(out_dir, NAME, "shadows")


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
