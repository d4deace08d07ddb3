"""Rasterizer pictures (error): measured perspective error per pixel [pixels per texel], log colour scale, blue ≤ 1 … red ≥ 64 (Lloyd 2007 Fig. 13 style, matched to its caption only), for Standard, P, LogP and ZP4+P.

Scene, light and budget: see figures/_raster_panels.py (n = 1, f = 100, fov 60°,
light at γ = 110°, azimuth 60°, 256² texels shared by each scheme's maps, 256² image).
"""

from __future__ import annotations

from pathlib import Path

from aliasing.figures import _raster_panels

NAME = "raster-error"


def main(out_dir: Path) -> list[Path]:
    return _raster_panels.main(out_dir, NAME, "error")


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
