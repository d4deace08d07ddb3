"""Lloyd 2007 Fig. 17 style: cumulative distribution over random light directions of the
maximum perspective error [image pixels per texel], n = 1, f = 1000, fov 60°, 1024² image,
1024² texel budget; Standard, P, LogP, ZP4+P.  Lines: analytic over 1000 seeded directions
(uniform on the sphere); dots: measured by the rasterizer on probes at the first 12.
"""

from __future__ import annotations

from pathlib import Path

from aliasing.plotting import save
from aliasing import pictures

NAME = "raster-cdf"
SCHEMES = ["Standard", "P", "LogP", "ZP4+P"]


def main(out_dir: Path) -> list[Path]:
    fig, ax, cols = pictures.error_cdf(SCHEMES, 1.0, 1000.0, 60.0, directions=1000, measured=12)
    ax.set_title("Lloyd 2007 Fig. 17 style: max error over light directions (f/n = 1000)", fontsize=9)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
