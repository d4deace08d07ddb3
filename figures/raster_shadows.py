"""Rasterizer pictures (shadows): Lambert shading with the shadow-map test, for Standard, P, LogP and ZP4+P.

Scene, light and budget: see figures/_raster_panels.py (n = 1, f = 100, fov 60°,
light at γ = 110°, azimuth 60°, 256² texels shared by each scheme's maps, 256² image).

The shadow test is aliasing.raster.draw.shadow_test: the stored sample and the pixel's
surface are compared as planes, with no bias that grows with the texel. So the ground never
shadows itself (no acne), and box shadows touch their boxes, even in the Standard panel,
whose 256² texels are about 0.6 × 0.5 world units here, larger than the near boxes. What
the panels then differ in is perspective aliasing alone: Standard's shadows are the boxes'
footprints on its coarse texel grid (blocky, up to a texel out of place, the far ones
lost), the warped maps' are close to the exact ones. Lit fractions: Standard 0.918, P
0.881, LogP 0.879, ZP4+P 0.878.

Checked against exact shadows (a ray from each pixel towards the light, cast with Embree,
2026-11-22): of the pixels facing the light, 8.75 % are in shadow; drawn lit although in
shadow / drawn in shadow although lit: Standard 6.1 % / 3.6 %, P 0.84 % / 0.80 %, LogP
0.55 % / 0.51 %, ZP4+P 0.33 % / 0.50 %.

(Until this was changed, the test used a depth bias of 1.5 texels' change of depth over the
surface, which is taller than the small boxes in the Standard map. Most of their shadows
came loose and vanished, "peter-panning": Standard's lit fraction was 0.99, and 8.5 % of
the pixels facing the light were drawn lit although in shadow. A bias of 0.6 texel's
change of depth, about the least free of acne (0.5 gives acne in LogP), still drew 7.9 %
so.)
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
