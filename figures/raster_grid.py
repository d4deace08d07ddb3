"""Rasterizer pictures (grid): texel grid every 8 texels projected on the scene (Lloyd 2006 Fig. 15 style), for Standard, P, LogP and ZP4+P.

Scene, light and budget: see figures/_raster_panels.py (n = 1, f = 100, fov 60°,
light at γ = 110°, azimuth 60°, 256² texels shared by each scheme's maps, 256² image).
"""

from __future__ import annotations

from pathlib import Path

from aliasing.figures import _raster_panels

NAME = "raster-grid"


def main(out_dir: Path) -> list[Path]:
    return _raster_panels.main(out_dir, NAME, "grid")


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
