"""S̄ over the hemisphere of light directions (Lloyd et al. 2006 Fig. 7 style) for any scheme.

The map is the orthographic view from above of :func:`aliasing.geometry.hemisphere_map`:
overhead in the centre, the light behind the viewer on the left, in front on the right.
Each direction's S̄ comes from :func:`aliasing.schemes.evaluate` (Lloyd et al. 2007
§6.2's vertex model); beside it the chosen direction's per-map M_x, M_z, n′ and η, and
Lloyd 2007 Table 3's statistics (min, max, mean S̄, shadow maps) over ``hemisphere:N``
equal-solid-angle directions.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

from .. import geometry, schemes
from ..view import View
from . import widget as w

#: Directions of the Table 3 statistics (equal solid angle, upper hemisphere).
STAT_DIRECTIONS = 1024


def compute(scheme: str, f_over_n: float, fov: float, gamma: float, azimuth: float, resolution: int, aspect: float = 1.0) -> dict[str, Any]:
    """The hemisphere map of S̄, the chosen direction's per-map errors and Table 3's statistics.

    Parameters
    ----------
    scheme : str
        A scheme in :data:`aliasing.schemes.GRAMMAR`.
    f_over_n : float
        far/near (near = 1).
    fov : float
        Full (vertical) field of view [deg].
    gamma, azimuth : float
        The chosen direction [deg] (:func:`aliasing.geometry.light_direction`).
    resolution : int
        Side of the hemisphere map [cells].
    aspect : float
        Image width/height (:class:`aliasing.View`; face partitions need 1).

    Returns
    -------
    dict
        ``u``, ``v``, ``S_map`` (resolution², NaN outside the disc), ``maps_map``; the chosen
        direction's ``light``, ``M_x``, ``M_z``, ``n_prime``, ``eta`` (per map), ``S``; the
        statistics ``S_min``, ``S_max``, ``S_mean``, ``maps_min``, ``maps_max``.

    Example
    -------
    >>> d = compute("LogP", 1000.0, 60.0, 90.0, 0.0, 16)
    >>> round(d["S"], 3)       # overhead: ln(f/n)/(2 tan 30°), Lloyd 2006 eq. 19
    5.982
    """
    sch = schemes.parse(scheme)
    view = View(1.0, float(f_over_n), fov, aspect)  # validated once, for the three evaluations
    far = view.far
    u, v, light = geometry.hemisphere_map(int(resolution))
    inside = np.isfinite(light[..., 0])
    r = schemes.evaluate(sch, view, light[inside])
    s_map = np.full(u.shape, np.nan)
    s_map[inside] = r.S
    maps_map = np.zeros(u.shape, int)
    maps_map[inside] = r.maps_used
    lv = geometry.light_direction(gamma, azimuth)
    one = schemes.evaluate(sch, view, lv[None])
    st = schemes.evaluate(sch, view, f"hemisphere:{STAT_DIRECTIONS}")
    return {
        "scheme": sch.name, "f_over_n": far, "fov": float(view.fov), "aspect": float(view.aspect), "gamma": float(gamma), "azimuth": float(azimuth),
        "u": u, "v": v, "S_map": s_map, "maps_map": maps_map,
        "light": lv, "M_x": one.M_x[0], "M_z": one.M_z[0], "n_prime": one.n_prime[0], "eta": one.eta[0],
        "S": float(one.S[0]), "maps": int(one.maps_used[0]),
        "S_min": float(st.S.min()), "S_max": float(st.S.max()), "S_mean": float(st.S.mean()),
        "maps_min": int(st.maps_used.min()), "maps_max": int(st.maps_used.max()),
    }


def map_position(light: np.ndarray) -> tuple[float, float]:
    """(u, v) of a direction on the hemisphere map (u = towards the view direction, v = x)."""
    return float(light[2]), float(light[0])


def draw(fig: Figure, d: dict[str, Any]) -> dict:
    """The S̄ map with the chosen direction, and its per-map errors with Table 3's statistics.

    Returns the artists for :func:`redraw`.
    """
    a, b = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0, 1.25]})
    im = a.pcolormesh(d["u"], d["v"], d["S_map"], norm=LogNorm(1.0, 2.0), cmap="viridis", shading="auto")
    cb = fig.colorbar(im, ax=a, fraction=0.05, pad=0.02)
    marker, = a.plot([0.0], [0.0], "o", mfc="none", mec="r", ms=10, mew=2)
    a.set(aspect="equal", xlabel="← light behind      light in front →", yticks=[], title="S̄ over the hemisphere (colour, log)")
    k = np.arange(1, len(d["M_x"]) + 1)
    used = d["M_x"] > 0
    bx = b.bar(k[used] - 0.2, d["M_x"][used], 0.4, label="M_x")
    bz = b.bar(k[used] + 0.2, d["M_z"][used], 0.4, label="M_z")
    heights = np.concatenate([d["M_x"][used], d["M_z"][used]])
    b.set_ylim(heights.min() / 1.5, heights.max() * 6.0)  # as redraw sets it; before the log scale, never a singular range
    b.set_yscale("log")
    w.readable_log_ticks(b.yaxis)
    step = -(-int(used.sum()) // 10)  # at most 10 labelled maps (FPcs+ZP4 has up to 29 slots): the labels never overlap
    b.set_xticks(k[used], [str(m) if i % step == 0 else "" for i, m in enumerate(k[used])])
    b.set(xlabel="map", ylabel="max. error (unit res.)")
    b.legend(fontsize=8, loc="upper left")
    text = b.text(0.98, 0.97, "", transform=b.transAxes, ha="right", va="top", fontsize=8, bbox={"fc": "white", "ec": "0.7"})
    fig.subplots_adjust(left=0.04, right=0.98, bottom=0.15, top=0.84, wspace=0.5)  # the colour bar's labels clear of the bars' y label
    artists = {"a": a, "b": b, "im": im, "cb": cb, "marker": marker, "bx": bx, "bz": bz, "text": text, "used": used,
               "shape": d["S_map"].shape, "suptitle": fig.suptitle("", fontsize=10)}
    redraw(artists, d)
    return artists


def redraw(artists: dict, d: dict[str, Any]) -> bool:
    """New data into :func:`draw`'s artists; False (draw anew) when the map size or the maps used change."""
    used = d["M_x"] > 0
    if d["S_map"].shape != artists["shape"] or not np.array_equal(used, artists["used"]):
        return False
    finite = d["S_map"][np.isfinite(d["S_map"])]
    lo, hi = float(finite.min()), float(finite.max())
    hi = hi if hi > lo else lo * 1.001
    artists["im"].set_array(d["S_map"])
    artists["im"].set_clim(lo, hi)
    ticks = np.geomspace(lo, hi, 5)
    artists["cb"].set_ticks(ticks, labels=[w.short_number(x) for x in ticks])
    artists["cb"].minorticks_off()
    artists["marker"].set_data(*([v] for v in map_position(d["light"])))
    artists["marker"].set_visible(bool(d["light"][1] >= 0))
    for bars, key in ((artists["bx"], "M_x"), (artists["bz"], "M_z")):
        for rect, height in zip(bars, d[key][used]):
            rect.set_height(height)
    b = artists["b"]
    heights = np.concatenate([d["M_x"][used], d["M_z"][used]])
    b.set_ylim(heights.min() / 1.5, heights.max() * 6.0)  # log axis: room for the legend and the statistics
    npr = ", ".join("—" if not np.isfinite(x) else f"{x:.3g}" for x in d["n_prime"][used][:4])
    eta = ", ".join("—" if not np.isfinite(x) else f"{x:.2f}" for x in d["eta"][used][:4])
    warp = f"n′: {npr}\nη: {eta}\n" if np.isfinite(d["n_prime"][used]).any() else ""
    b.set_title(f"γ = {d['gamma']:g}°, az = {d['azimuth']:g}°: S̄ = {d['S']:.4g}, {d['maps']} map(s)", fontsize=10)
    artists["text"].set_text(f"{warp}Table 3 over {STAT_DIRECTIONS} dirs:\nmin {d['S_min']:.4g}  max {d['S_max']:.4g}\n"
                             f"mean {d['S_mean']:.4g}  maps {d['maps_min']}–{d['maps_max']}")
    wide = "" if d.get("aspect", 1.0) == 1.0 else f", aspect = {d['aspect']:.3g}"
    artists["suptitle"].set_text(f"{d['scheme']}, f/n = {d['f_over_n']:.4g}, fov = {d['fov']:g}°{wide}")
    return True


class DirectionsExplorer(w.Explorer):
    """S̄ over light directions for a typed scheme; controls scheme, f/n, fov, aspect, γ, azimuth, map size."""

    title = "Light directions (Lloyd et al. 2006 Fig. 7, Lloyd et al. 2007 Table 3)"
    figsize = (9.5, 3.8)

    def make_controls(self) -> dict:
        return {
            "scheme": w.text("scheme", "LogP", "e.g. P, ZP4+LogP, FPc+LogP, lispsm"),
            "f_over_n": w.log_slider("f/n", 1000.0, 1.5, 1e5),
            "fov": w.slider("fov [deg]", 60.0, 5.0, 150.0),
            "aspect": w.log_slider("aspect", 1.0, 0.25, 4.0),
            "gamma": w.slider("γ [deg]", 60.0, 0.0, 180.0),
            "azimuth": w.slider("azimuth [deg]", 0.0, -90.0, 90.0),
            "resolution": w.widgets.IntSlider(value=64, min=8, max=256, description="map cells", continuous_update=False),
        }

    # the module's functions, so that tests and notebooks can call them without a widget
    compute = staticmethod(compute)
    draw = staticmethod(draw)
    redraw = staticmethod(redraw)

    def pick(self, u: float, v: float) -> bool:
        """Choose the direction at map position (u, v) (e.g. a click on the map)."""
        h2 = 1.0 - u * u - v * v
        if h2 < 0:
            raise ValueError(f"(u, v) = ({u}, {v}) is outside the hemisphere map (u² + v² ≤ 1)")
        gamma = float(np.degrees(np.arccos(np.clip(u, -1.0, 1.0))))
        azimuth = float(np.degrees(np.arctan2(v, np.sqrt(h2))))
        return self.set_state({"gamma": round(gamma, 6), "azimuth": round(azimuth, 6)})
