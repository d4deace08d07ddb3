"""Shimmer along a camera path: the fixed points seen from each frame, the ones that flip marked.

:func:`aliasing.temporal.measure.shimmer` runs the sequence once per scene, scheme, motion,
frame count and resolutions (kept while only the frame changes); the frame slider (and its
play button) steps through it.  Left: the points from frame f's camera, lit or shadowed,
those whose state changed since frame f − 1 in red (orange: they also changed cascade or
clipmap level).  Right: the flip fraction per frame, measured and predicted
(:mod:`aliasing.temporal.predict`).
The ``aspect`` slider is the camera's width/height (its field of view is vertical): the points
are one per pixel of an R × R image whose pixels are aspect : 1 wide, every frame's maps are
fitted to the wider slices, and the left panel shows the view at its shape (the title names
the aspect when it is not 1).  ``vsm`` schemes take it into the clipmap's LOD.
"""

from __future__ import annotations

from typing import Any

import ipywidgets as widgets
import numpy as np
from matplotlib.ticker import MaxNLocator
from matplotlib.figure import Figure

from .. import _validation as check
from ..temporal import fits, measure, paths, points
from ..view import check_aspect, tan_theta
from . import widget as w

_CACHE: dict[tuple, tuple] = {}


def _sequence(scene: str, scheme: str, motion: str, frames: int, image_res: int, shadow_res: int, aspect: float = 1.0) -> tuple:
    wide = float(check_aspect(check.scalar(aspect, "aspect")))  # refused before the cache is looked at
    key = (scene, scheme, motion, int(frames), int(image_res), int(shadow_res), wide)
    if key not in _CACHE:
        world = points.world(scene, aspect=wide)
        pts = points.sample(world, int(image_res))
        r = measure.shimmer(world, pts, scheme, motion, int(frames), res=int(shadow_res))
        cam = world.camera
        poses = paths.frames(r.motion, cam.eye, cam.rotation, cam.fov, world.light, int(frames))
        _CACHE.clear()  # one sequence at a time: a sequence holds frames × points states
        _CACHE[key] = (world, pts, r, poses)
    return _CACHE[key]


def compute(scene: str, scheme: str, motion: str, frames: int, frame: int, image_res: int, shadow_res: int, aspect: float = 1.0) -> dict[str, Any]:
    """The points of frame ``frame`` in its image, their states and flips, and the per-frame curves.

    ``aspect`` is the camera's width/height (0 < aspect < inf; the field of view is vertical).

    Returns
    -------
    dict
        ``uv`` (P, 2) image coordinates in [−aspect, aspect] × [−1, 1] of the points in view
        (x and y over z·tan θ, θ the vertical half angle; NaN otherwise), ``aspect``,
        ``lit``, ``flipped``, ``changed`` (P,) bools, ``flip_fraction`` and ``predicted``
        (F − 1,), ``frame``, ``row`` (:meth:`aliasing.temporal.measure.Shimmer.row`).

    Example
    -------
    >>> d = compute("boxes", "csm:log:k=3", "translate:0.05,0,0", 3, 1, 32, 64)
    >>> d["uv"].shape[1], d["flip_fraction"].shape
    (2, (2,))
    >>> wide = compute("boxes", "csm:log:k=3", "translate:0.05,0,0", 3, 1, 32, 64, aspect=2.0)
    >>> bool(np.nanmax(np.abs(wide["uv"][:, 0])) > 1.5), bool(np.nanmax(np.abs(wide["uv"][:, 1])) <= 1.0)
    (True, True)
    """
    world, pts, r, poses = _sequence(scene, scheme, motion, frames, image_res, shadow_res, aspect)
    f = int(np.clip(frame, 0, int(frames) - 1))
    eye = fits.eye_coordinates(pts.position, poses[0][f:f + 1], poses[1][f:f + 1])[0]
    t = tan_theta(poses[2][f])
    seen = r.part[f] >= 0
    with np.errstate(divide="ignore", invalid="ignore"):
        uv = np.where(seen[:, None], eye[:, :2] / (eye[:, 2:3] * t), np.nan)
    if f > 0:
        both = seen & (r.part[f - 1] >= 0)
        flipped = both & (r.lit[f] != r.lit[f - 1])
        changed = flipped & (r.part[f] != r.part[f - 1])
    else:
        flipped = changed = np.zeros(pts.count, bool)
    return {"uv": uv, "lit": r.lit[f], "flipped": flipped, "changed": changed, "flip_fraction": r.flip_fraction, "predicted": r.predicted,
            "frame": f, "row": r.row(), "scheme": scheme, "motion": motion, "aspect": float(world.camera.aspect)}


def draw(fig: Figure, d: dict[str, Any]) -> None:
    """Points of the frame (lit grey, shadowed dark, flips red/orange) and the flip fraction over frames."""
    wide = d.get("aspect", 1.0)
    a, b = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0 if wide == 1.0 else float(np.clip(wide, 1.0, 2.0)), 1.3]})
    uv, lit, flipped, changed = d["uv"], d["lit"], d["flipped"], d["changed"]
    calm = ~flipped
    a.set_facecolor("#dde6f0")  # no point: sky, beyond far, or a face turned from the light (in its own shadow)
    a.fill_between([], [], color="#dde6f0", label="no point: sky, or a face turned from the light")
    a.scatter(*uv[calm & lit].T, s=5, c="#f2d16b", lw=0, label="lit")
    a.scatter(*uv[calm & ~lit].T, s=5, c="#3a3f4b", lw=0, label="shadowed")
    a.scatter(*uv[flipped & ~changed].T, s=14, c="#d62728", lw=0, label="flipped")
    a.scatter(*uv[changed].T, s=14, c="#ff7f0e", lw=0, label="flipped, changed map")
    a.set(xlim=(-wide, wide), ylim=(-1, 1), aspect="equal", xticks=[], yticks=[], title=f"frame {d['frame']} seen by its camera: {int(flipped.sum())} flips", )
    a.title.set_fontsize(9)
    a.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.02), ncols=2, markerscale=1.5, frameon=False, columnspacing=0.8)
    x = np.arange(1, len(d["flip_fraction"]) + 1)
    b.plot(x, d["flip_fraction"], "-o", ms=3, label="measured")
    if np.isfinite(d["predicted"]).any():
        b.plot(x, d["predicted"], "--", label="predicted (grid motion × edge density)")
    b.axvline(d["frame"], color="0.5", lw=0.8)
    b.set(xlabel="frame", ylabel="flip fraction (points seen in both frames)")
    shown = np.concatenate([np.asarray(d["flip_fraction"], float), np.asarray(d["predicted"], float)])
    peak = float(shown[np.isfinite(shown)].max(initial=0.0))
    top = 1.4 * peak if peak > 0 else 0.01
    b.set_ylim(-0.03 * top, top)  # fractions are ≥ 0 (a curve at 0 is shown, not clipped); headroom above for the legend
    b.xaxis.set_major_locator(MaxNLocator(integer=True))  # whole frames
    b.legend(fontsize=7, loc="upper center", ncols=1)
    row = d["row"]
    ratio = row["predicted_over_measured"]
    b.set_title(f"mean {row['flip_fraction']:.3g} = {row['flips_per_second']:.3g}/s at 60 fps"
                + (("; " if wide == 1.0 else "\n") + f"predicted/measured {ratio:.2f} ± {row['ratio_se']:.2f}" if ratio is not None else ""), fontsize=8)
    fig.suptitle(f"{d['scheme']} under {d['motion']}" + ("" if wide == 1.0 else f", aspect = {wide:.3g} (width/height)"), fontsize=10)
    fig.subplots_adjust(left=0.03, right=0.98, bottom=0.2, top=0.86, wspace=0.18 if wide == 1.0 else 0.3)  # room for the curve's axis labels


class ShimmerExplorer(w.Explorer):
    """Plays a camera or sun path; controls scene, scheme, motion, frames, frame, resolutions, aspect."""

    title = "Shimmer of a still world along a camera path (aliasing.temporal)"
    figsize = (10.0, 4.2)

    def __init__(self, **values: Any) -> None:
        super().__init__(**values)
        self.play = widgets.Play(value=0, min=0, max=int(self.controls["frames"].value) - 1, interval=250, description="play")
        widgets.jslink((self.play, "value"), (self.controls["frame"], "value"))
        self.controls["frames"].observe(self._frames_changed, names="value")
        self._frames_changed({"new": self.controls["frames"].value})
        self.children = (self.children[0], self.play, *self.children[1:])

    def _frames_changed(self, change: dict) -> None:
        top = max(int(change["new"]) - 1, 1)
        self.controls["frame"].max = top
        if hasattr(self, "play"):
            self.play.max = top

    def make_controls(self) -> dict:
        return {
            "scene": w.dropdown("scene", [(name, name) for name in points.SCENES], "boxes"),
            "scheme": w.text("scheme", "csm:log:k=4", "csm:…, csm-stable:…, sdsm…, vsm:…"),
            "motion": w.text("motion", "translate:0.05,0,0", "translate:DX,DY,DZ | rotate:yaw|pitch,DEG | zoom:DEG | sun:DEG"),
            "frames": widgets.IntSlider(value=24, min=2, max=240, description="frames"),
            "frame": widgets.IntSlider(value=1, min=0, max=239, description="frame"),  # max follows frames
            "image_res": w.dropdown("points", [("48²", 48), ("64²", 64), ("96²", 96), ("128²", 128)], 96),
            "shadow_res": w.dropdown("texels", [("128²", 128), ("256²", 256), ("512²", 512)], 256),
            "aspect": w.log_slider("aspect", 1.0, 0.25, 4.0),
        }

    compute = staticmethod(compute)
    draw = staticmethod(draw)
