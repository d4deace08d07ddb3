"""The rasterizer at a small resolution: shadows, the shadow map's texel grid, per-pixel error.

A seeded ground-and-boxes scene is rendered and shadowed through the scheme's maps by
:func:`aliasing.pictures.view`; the texel grid is drawn as the iso-lines of the
pixels' map coordinates s·R and t·R (every ``every`` texels); the per-pixel perspective
error is :func:`aliasing.pictures.error_field` (finite differences of the map
coordinates, texels per pixel); the measured/bound ratios are
:func:`aliasing.raster.validate.validate`'s (probes' measured M_x, M_z over the analytic
bounds of :func:`aliasing.schemes.evaluate`; ≤ 1 up to sampling, near 1 when the bound is tight).
A view of ``aspect`` ≠ 1 (width/height, ``fov`` vertical: :class:`aliasing.View`) is drawn on
the same R × R pixels, aspect : 1 wide (:func:`aliasing.raster.eye_pass`), and shown at its
width; its measured error is per pixel of the R rows.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.transforms import Bbox

from .. import pictures
from ..raster.validate import validate
from ..view import View
from . import widget as w

BUDGETS = [(f"{s}²", s * s) for s in (64, 128, 256, 512)]
#: Probe cells per side of the ratio measurement.
PROBES = 8
#: Smallest eye resolution of the ratio measurement [pixels] (8 probe cells need it), times max(aspect, 1/aspect)
#: for a non-square view: its pixels are stretched aspect : 1, and at 64 pixels its probe cells hold too few
#: to measure (aspect 2: none measured) or under-measure (aspect 4 at 128 pixels: 0.2–0.35 of the bound).
MIN_VALIDATE_RES = 64


def validate_resolution(image_res: int, aspect: float) -> int:
    """Eye resolution [pixels per side] of the ratio measurement: at least ⌈MIN_VALIDATE_RES·max(aspect, 1/aspect)⌉.

    Example
    -------
    >>> validate_resolution(32, 1.0), validate_resolution(96, 1.0), validate_resolution(96, 4.0), validate_resolution(96, 0.5)
    (64, 96, 256, 128)
    """
    return max(int(image_res), int(np.ceil(MIN_VALIDATE_RES * max(aspect, 1.0 / aspect) - 1e-9)))


def compute(scheme: str, light: str, f_over_n: float, fov: float, image_res: int, budget: int, every: int, aspect: float = 1.0) -> dict[str, Any]:
    """Render, error field and measured/bound ratios for near = 1, far = f/n.

    Parameters
    ----------
    scheme : str
        A scheme (:data:`aliasing.schemes.GRAMMAR`).
    light : str
        One light direction (``overhead``, ``gamma:DEG[@azimuth:DEG]``, …).
    f_over_n, fov : float
        far/near and the full vertical field of view [deg].
    image_res : int
        Eye image [pixels per side].
    budget : int
        Texels shared by the scheme's maps.
    every : int
        Texels between drawn grid lines.
    aspect : float
        Image width/height, > 0 (1: the square view); face partitions need 1.

    Returns
    -------
    dict
        ``shaded`` (R, R, 3), ``s``, ``t`` (R, R) map coordinates, ``partition``, ``error``
        (R, R) [pixels per texel], ``map_res``, ``maps`` and per map ``ratio_M_x``,
        ``ratio_M_z``, ``M_x``, ``M_z`` (from :func:`~aliasing.raster.validate.validate`).

    Example
    -------
    >>> d = compute("P", "gamma:60", 100.0, 60.0, 32, 64 * 64, 8)
    >>> d["shaded"].shape, d["map_res"]
    ((32, 32, 3), 64)
    """
    if isinstance(every, bool) or int(every) != every or every < 1:
        raise ValueError(f"every must be a whole number >= 1 (texels between grid lines), got {every!r}")
    view = View(1.0, float(f_over_n), fov, aspect)  # validated once, for the picture; validate takes the same numbers
    v = pictures.view(view, light, scheme, image_res=int(image_res), budget=int(budget))
    res = validate_resolution(image_res, float(view.aspect))
    val = validate(scheme, float(f_over_n), fov, light, res=res, probes=PROBES, aspect=float(view.aspect))
    return {
        "scheme": scheme, "light": light, "f_over_n": float(f_over_n), "fov": float(fov), "aspect": float(view.aspect), "image_res": int(image_res),
        "budget": int(budget), "every": int(every), "map_res": int(v.map_res), "maps": len(v.maps),
        "shaded": pictures.shade(v), "s": v.s, "t": v.t, "partition": v.partition, "error": pictures.error_field(v),
        "ratio_M_x": np.atleast_1d(val["ratio_M_x"]), "ratio_M_z": np.atleast_1d(val["ratio_M_z"]),
        "M_x": np.atleast_1d(val["M_x"]), "M_z": np.atleast_1d(val["M_z"]),
    }


def draw(fig: Figure, d: dict[str, Any]) -> None:
    """Shadows with the texel grid; the per-pixel error; the ratios."""
    wide = d.get("aspect", 1.0)
    a, b = fig.subplots(1, 2)
    a.imshow(np.clip(d["shaded"], 0, 1), origin="lower", interpolation="nearest")
    if wide != 1.0:  # the R × R pixels are aspect : 1 wide: the pictures take the view's width/height
        a.set_aspect(1.0 / wide)
        b.set_aspect(1.0 / wide)  # (an error picture's imshow sets it again)
    levels = np.arange(0, d["map_res"] + 1, d["every"])
    for part in range(d["maps"]):
        sel = d["partition"] == part
        for coord in (d["s"], d["t"]):
            field = np.where(sel, coord * d["map_res"], np.nan)
            if np.isfinite(field).sum() > 3:
                a.contour(field, levels=levels, colors=[f"C{part % 10}"], linewidths=0.8)
    a.set(xticks=[], yticks=[], title=f"shadows + texel grid (every {d['every']} of {d['map_res']}²)")
    err = d["error"]
    ok = np.isfinite(err) & (err > 0)
    if ok.any():
        im = b.imshow(np.where(ok, err, np.nan), origin="lower", norm=Normalize(*_range(err[ok])),
                      cmap="jet", interpolation="nearest", **({} if wide == 1.0 else {"aspect": 1.0 / wide}))
        if wide == 1.0:
            fig.colorbar(im, ax=b, fraction=0.046, pad=0.02, label="pixels per texel")
        else:  # beside the picture, at its height
            cax = fig.add_axes((0.0, 0.0, 0.01, 0.01))  # placed at each draw by _beside
            cax.set_axes_locator(_beside(b))
            fig.colorbar(im, cax=cax, label="pixels per texel")
    b.set(xticks=[], yticks=[], title="per-pixel error")
    fig.text(0.5, 0.03, ratio_line(d["ratio_M_x"], d["ratio_M_z"]), ha="center", fontsize=8)
    pixels = f"{d['image_res']}² pixels" if wide == 1.0 else f"aspect = {wide:.3g}, {d['image_res']}² pixels {wide:.3g} : 1 wide"
    fig.suptitle(f"{d['scheme']}, light {d['light']}, f/n = {d['f_over_n']:.4g}, fov = {d['fov']:g}°, {pixels}, "
                 f"{d['maps']} map(s)", fontsize=10)
    fig.subplots_adjust(left=0.02, right=0.9, bottom=0.1, top=0.86, wspace=0.1)  # right: room for the colour bar's label


def _beside(ax):
    """An axes locator: a thin bar right of ``ax``'s picture as drawn (after its aspect), as high as it."""
    def locate(cax, renderer):
        ax.apply_aspect()
        p = ax.get_position(original=False)
        return Bbox.from_bounds(p.x1 + 0.01, p.y0, 0.015, p.height)
    return locate


#: Most maps whose ratios are listed one by one (more: their range).
LISTED_MAPS = 4


def ratio_line(ratio_x: np.ndarray, ratio_z: np.ndarray) -> str:
    """The measured/bound ratios as one line: per map for up to :data:`LISTED_MAPS` maps, else their range.

    Example
    -------
    >>> ratio_line(np.array([0.95, 0.5]), np.array([0.98, 0.7]))
    'measured/bound (M_x, M_z) per map: map 1: 0.95, 0.98   map 2: 0.50, 0.70'
    >>> ratio_line(np.linspace(0.5, 1.0, 9), np.full(9, 0.9))
    'measured/bound over 9 maps: M_x 0.50–1.00, M_z 0.90–0.90'
    """
    if len(ratio_x) <= LISTED_MAPS:
        return "measured/bound (M_x, M_z) per map: " + "   ".join(f"map {i + 1}: {x:.2f}, {z:.2f}" for i, (x, z) in enumerate(zip(ratio_x, ratio_z)))
    span = lambda r: f"{np.nanmin(r):.2f}–{np.nanmax(r):.2f}"  # noqa: E731
    return f"measured/bound over {len(ratio_x)} maps: M_x {span(ratio_x)}, M_z {span(ratio_z)}"


def _range(values: np.ndarray) -> tuple[float, float]:
    """Colour range: 1st to 99th percentile (face-border pixels give a few huge differences)."""
    lo, hi = np.percentile(values, [1.0, 99.0])
    return float(lo), float(max(hi, lo * 1.01))


class RasterExplorer(w.Explorer):
    """The rasterizer's view of a scheme; controls scheme, light, f/n, fov, aspect, image size, texel budget, grid spacing."""

    title = "Rasterizer (shadows, texel grid, per-pixel error, measured/bound)"
    figsize = (9.0, 4.4)

    def make_controls(self) -> dict:
        return {
            "scheme": w.text("scheme", "LogP", "e.g. P, ZP3+P, FPc+LogP"),
            "light": w.text("light", "gamma:60@azimuth:30", "overhead | gamma:DEG[@azimuth:DEG]"),
            "f_over_n": w.log_slider("f/n", 100.0, 1.5, 1e4),
            "fov": w.slider("fov [deg]", 60.0, 10.0, 120.0),
            "aspect": w.log_slider("aspect", 1.0, 0.25, 4.0),
            "image_res": w.widgets.IntSlider(value=96, min=32, max=256, step=16, description="image [px]", continuous_update=False),
            "budget": w.dropdown("texels", BUDGETS, 128 * 128),
            "every": w.widgets.IntSlider(value=8, min=1, max=64, description="grid every", continuous_update=False),
        }

    def compute(self, **values: Any) -> dict:
        return compute(**values)

    def draw(self, fig: Figure, data: dict) -> None:
        draw(fig, data)
