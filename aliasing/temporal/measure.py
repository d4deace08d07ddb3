"""Shimmer measured: every point's shadow test through every frame's maps, and what flips.

With a still world and a still sun every change of a point's lit/shadowed state between
two frames is an artefact.  :func:`shimmer` runs a sequence and returns, per frame change,

* the flip fraction: points whose state changed / points seen in both frames (per second:
  times the frame rate);
* the same counting only points that stayed in their map, and the share of flips from
  points that changed map (cascade or clipmap level), reported apart;
* the shadow edges' displacement [pixels of the frame-0 image]: the flipped area (a point
  is a pixel) over the frame-0 edge length, measured by counting neighbouring pixels of
  different state on the same planar face (a curve of length L crosses 4L/π grid edges,
  Cauchy–Crofton, so L = count·π/4).  A wide camera's pixels are aspect : 1 wide
  (:func:`aliasing.temporal.points.sample`): lengths and areas are then in pixel heights
  (the square pixels of an image of the same rows), a pixel has area aspect, and a change
  between two pixels of a column counts aspect times (L = (c_h + aspect·c_v)·π/4);
* the prediction of :mod:`aliasing.temporal.predict` (not under a turning sun).

Example
-------
>>> from aliasing.temporal import points
>>> w = points.world("boxes", boxes=30)
>>> pts = points.sample(w, 48)
>>> r = shimmer(w, pts, "csm:log:k=3", "translate:0.05,0,0", 4, res=64)
>>> r.flip_fraction.shape, bool(r.flip_fraction.mean() > 0)
((3,), True)
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from ..raster.draw import BIAS, backends, check_resolution, resident
from . import fits, paths, predict
from .points import Points, World
from .render import MapCache

Array = NDArray[np.float64]

#: Largest frames × points of a sequence: its states (a bool and an int64 per frame and point),
#: eye coordinates and the prediction's temporaries take about 100 bytes each, so this is ≈ 2 GiB.
MAX_FRAME_POINTS = 20_000_000


@dataclass(frozen=True)
class Shimmer:
    """A measured sequence.  Per frame change (F − 1,): ``flip_fraction``,
    ``same_fraction`` (flips of points that kept their map, over the same points seen),
    ``changed_flips`` and ``flips`` (counts), ``seen`` (points in view in both frames),
    ``edge_shift_px``, ``predicted`` and ``predicted_same`` (NaN under a turning sun);
    ``ratio`` (predicted / measured flips of points that kept their map, over the whole
    sequence) and ``ratio_se`` (its bootstrap standard error, :func:`aliasing.temporal.predict.agreement`); ``lit`` and ``part``
    (F, P) the states and maps; ``shift`` (F − 1, K, 2) and ``scale`` (F − 1, K) the grid
    motion; ``g`` the edge densities and ``group`` each point's row of it
    (:class:`aliasing.temporal.predict.Densities`); ``edge_length_px``; ``drawn`` and ``reused``
    maps; ``seconds``; ``motion``; ``spec``; ``aspect`` the camera's width/height."""

    spec: str
    motion: paths.Motion
    lit: NDArray[np.bool_]
    part: NDArray[np.int64]
    flip_fraction: Array
    same_fraction: Array
    flips: NDArray[np.int64]
    changed_flips: NDArray[np.int64]
    seen: NDArray[np.int64]
    edge_shift_px: Array
    edge_length_px: float
    predicted: Array
    predicted_same: Array
    ratio: float
    ratio_se: float
    shift: Array
    scale: Array
    g: Array
    group: NDArray[np.int64]
    drawn: int
    reused: int
    seconds: float
    aspect: float = 1.0

    def row(self, fps: float = 60.0) -> dict:
        """One summary row (the CLI's): means over frame changes; an ``aspect`` entry after ``scheme`` only when ≠ 1."""
        total = int(self.flips.sum())
        sun = self.motion.kind == "sun"
        mean = float(self.flip_fraction.mean())
        none = sun or bool(np.isnan(self.predicted).all())
        pred = None if none else float(self.predicted.mean())
        pred_same = None if none else float(self.predicted_same.mean())
        same = float(self.same_fraction.mean())
        return {
            "scheme": self.spec,
            **({} if self.aspect == 1.0 else {"aspect": float(self.aspect)}),
            "flip_fraction": mean,
            "flip_fraction_max": float(self.flip_fraction.max()),
            "flips_per_second": mean * fps,
            "same_map_fraction": same,
            "map_change_share": float(self.changed_flips.sum() / total) if total else 0.0,
            "predicted_same_map": pred_same,
            "predicted_over_measured": None if none or not np.isfinite(self.ratio) else self.ratio,
            "ratio_se": None if none or not np.isfinite(self.ratio_se) else self.ratio_se,
            "predicted_fraction": pred,
            "per_degree": mean / abs(float(self.motion.step[0])) if self.motion.kind in ("sun", "rotate", "zoom") else None,
            "edge_shift_px": float(self.edge_shift_px.mean()),
            "maps_drawn": self.drawn,
            "frames": int(self.lit.shape[0]),
            "points": int(self.lit.shape[1]),
            "seconds": self.seconds,
        }


def edge_length(pts: Points, lit0: NDArray[np.bool_], seen0: NDArray[np.bool_]) -> float:
    """Length [pixels] of the frame-0 shadow edges on the points' image (Cauchy–Crofton: count·π/4).

    ``lit0`` and ``seen0`` (P,) are the points' frame-0 states and whether a map holds them.
    For a wide image (``pts.aspect`` ≠ 1: pixels aspect : 1 wide) the length is in pixel
    heights: the changes between horizontal neighbours, c_h, are the curve's crossings of
    the rows' centre lines (1 apart), (2/π)·L on average over orientations, and those
    between vertical neighbours, c_v, its crossings of the columns' (aspect apart),
    (2/π)·L/aspect; so L = (c_h + aspect·c_v)·π/4.

    Example
    -------
    >>> r, rho = 200, 60.0                      # a disc of radius 60 pixel heights on a 2:1 image
    >>> rows, cols = np.mgrid[0:r, 0:r]
    >>> pix = np.stack([rows.ravel(), cols.ravel()], -1)
    >>> pts = Points(np.zeros((r * r, 3)), np.zeros((r * r, 3)), pix, np.zeros(r * r, np.int64), r, 2.0)
    >>> lit = (2.0 * (pix[:, 1] - r / 2)) ** 2 + (pix[:, 0] - r / 2) ** 2 < rho**2
    >>> round(edge_length(pts, lit, np.ones(r * r, bool)) / (2 * np.pi * rho), 2)   # ≈ 1 (Cauchy–Crofton)
    1.0
    """
    check.instance(pts, "pts", Points)
    lit0, seen0 = (np.asarray(v) for v in (lit0, seen0))
    if lit0.shape != (pts.count,) or seen0.shape != (pts.count,) or lit0.dtype != bool or seen0.dtype != bool:
        raise ValueError(f"lit0 and seen0 must be booleans of shape ({pts.count},), got {lit0.dtype} {lit0.shape} and {seen0.dtype} {seen0.shape}")
    r = pts.resolution
    state = np.full((r, r), -1, np.int64)
    plane = np.full((r, r), -1, np.int64)
    ok = seen0
    state[pts.pixel[ok, 0], pts.pixel[ok, 1]] = lit0[ok]
    plane[pts.pixel[ok, 0], pts.pixel[ok, 1]] = pts.plane[ok]
    ch, cv = (int(np.count_nonzero((a >= 0) & (b >= 0) & (pa == pb) & (a != b)))
              for a, b, pa, pb in ((state[:, 1:], state[:, :-1], plane[:, 1:], plane[:, :-1]), (state[1:], state[:-1], plane[1:], plane[:-1])))
    return (ch + pts.aspect * cv) * np.pi / 4  # (ch + cv)·π/4 exactly at aspect 1


def check_size(frames: int, count: int) -> None:
    """Refuse a sequence whose states would not fit (:data:`MAX_FRAME_POINTS`) before any work."""
    frames, count = check.whole(frames, "frames", 1), check.whole(count, "count", 1)
    if frames * count > MAX_FRAME_POINTS:
        raise ValueError(f"frames × points = {frames} × {count} = {frames * count:,} is over {MAX_FRAME_POINTS:,} (the states would need about "
                         f"{frames * count * 100 / 2**30:.1f} GiB); use fewer frames or a lower image resolution")


def shimmer(w: World, pts: Points, spec: str, motion: str | paths.Motion, frames: int, *, res: int = 256, sdsm_res: int = 64, unit: str = "m",
            bias: float = BIAS, directions: int = predict.DIRECTIONS, shifts: int = predict.SHIFTS, prediction: bool = True, backend: str = "numpy") -> Shimmer:
    """Measure (and predict) the shimmer of scheme ``spec`` over a camera or sun path.

    Parameters
    ----------
    w : World
        The still scene, its frame-0 camera and light (:func:`aliasing.temporal.points.world`);
        the camera's aspect (width/height) holds for every frame.
    pts : Points
        The fixed points (:func:`aliasing.temporal.points.sample`), sampled at the camera's aspect.
    spec : str
        A scheme of the engines grammar (``csm:…``, ``csm-stable:…``, ``sdsm…``, ``vsm:…``).
    motion : str or Motion
        :func:`aliasing.temporal.paths.parse_motion`'s grammar.
    frames : int
        Frames of the sequence, in [2, :data:`aliasing.temporal.paths.MAX_FRAMES`].
    res : int
        Texels per side of every cascade.
    sdsm_res : int
        Eye-pass resolution of SDSM's per-frame depth bounds [pixels per side].
    unit : str
        The scene's length unit (VSM).
    bias : float
        The shadow test's tolerance [world units].
    directions : int
        Direction bins of the edge-density measurement (≥ 2).
    shifts : int
        Sub-texel grid shifts of the edge-density measurement (≥ 1; each draws the frame-0 maps again).
    prediction : bool
        Also predict (False: the measure alone, ``predicted`` NaN; saves the density maps).
    backend : {"numpy", "numba", "gl"}
        How the depth maps are drawn (:mod:`aliasing.raster.draw.backends`; numpy, the reference).
    """
    start = time.perf_counter()
    check.instance(w, "w", World)
    check.instance(pts, "pts", Points)
    m = paths.parse_motion(motion) if not isinstance(motion, paths.Motion) else motion
    n = paths.check_frames(frames)
    check_size(n, pts.count)
    if backends.pair(backend)[1] == "gl":
        resident.check_size(check_resolution(res, "res"), "res")  # before any work
    dirs = check.whole(directions, "directions", 2)
    n_shifts = check.whole(shifts, "shifts", 1)
    cam = w.camera
    if pts.aspect != cam.aspect:
        raise ValueError(f"pts were sampled at aspect {pts.aspect:g}, the camera of w has aspect {cam.aspect:g}: sample the points from this world")
    poses = paths.frames(m, cam.eye, cam.rotation, cam.fov, w.light, n)
    lat = fits.plan(spec, w, poses, res, positions=pts.position, sdsm_res=sdsm_res, image_res=pts.resolution, unit=unit)
    eye_pos = fits.eye_coordinates(pts.position, poses[0], poses[1])
    part = fits.assign(lat, eye_pos, poses[2], cam.near, cam.far)
    lit = np.ones(part.shape, bool)
    cache = MapCache(w.triangles, bias=bias, backend=backend)
    dens = None
    for f in range(n):  # per frame: one vectorized shadow test per map, maps reused while their grid holds
        for k in np.unique(part[f][part[f] >= 0]):
            sel = np.nonzero(part[f] == k)[0]
            lit[f, sel] = cache.test(lat, f, int(k), pts.position[sel], pts.normal[sel])
        if f == 0 and m.kind != "sun" and prediction:
            tile = (pts.pixel[:, 0] * predict.TILES // pts.resolution) * predict.TILES + pts.pixel[:, 1] * predict.TILES // pts.resolution
            dens = predict.densities(cache, lat, part[0], pts.position, pts.normal, lit[0], tile, directions=dirs, shifts=n_shifts)
        cache.next_frame()
    seen = (part[1:] >= 0) & (part[:-1] >= 0)
    flipped = seen & (lit[1:] != lit[:-1])
    changed = seen & (part[1:] != part[:-1])
    n_seen = seen.sum(-1)
    denom = np.maximum(n_seen, 1)
    length = edge_length(pts, lit[0], part[0] >= 0)
    ratio, se = np.nan, np.nan
    if dens is None:  # a turning sun (the shadows move: no grid motion to predict from), or not asked
        pred = pred_same = np.full(n - 1, np.nan)
        shift, scale = np.full((n - 1, lat.maps, 2), np.nan), np.full((n - 1, lat.maps), np.nan)
        g = np.full((lat.maps * (predict.TILES**2 + 1) + 1, dirs), np.nan)
        group = np.full(pts.count, len(g) - 1, np.int64)
    else:
        g, group = dens.g, dens.group
        delta = predict.displacement(lat, part, predict.light_plane(pts.position, lat))
        prob = predict.flip_probability(delta, group, g)
        prob = np.where(seen, np.nan_to_num(prob), 0.0)
        pred = prob.sum(-1) / denom
        keep = seen & ~changed
        pred_same = np.where(keep, prob, 0.0).sum(-1) / denom
        ratio, se = predict.agreement(dens, delta, keep, flipped, float(np.where(keep, prob, 0.0).sum()))
        shift, scale = predict.grid_motion(lat)
    return Shimmer(
        spec, m, lit, part, flipped.sum(-1) / denom, (flipped & ~changed).sum(-1) / denom, flipped.sum(-1), (flipped & changed).sum(-1), n_seen,
        flipped.sum(-1) * pts.aspect / max(length, 1e-300) if length > 0 else np.zeros(n - 1), length, pred, pred_same, float(ratio), float(se), shift, scale, g, group, cache.drawn, cache.reused,
        time.perf_counter() - start, pts.aspect,
    )
