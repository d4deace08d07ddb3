"""The objective and the constraints of one setup: what :func:`aliasing.tune.tune` measures.

The objective is the worst perspective error over the receivers and the sun band [px per
texel]: at eye depth d in cascade k, a map side W_k over R texels seen by an image of H rows
with vertical half angle θ_y has m = W_k·H / (2 tan θ_y · d · R) (Lloyd et al. 2006, eq. 2
with a uniform map), largest at the cascade's first receiver d = max(u_k, receivers' near).

Constraints, measured as :func:`aliasing.check.check` measures them: no acne on the
ground and the ground tilted ``max_slope`` away from the sun under each sampled elevation (the
angle to the light θ = 90° − α + slope, up to :data:`MAX_ANGLE`, as check samples them) in
each cascade's largest texel with the
filter's kernel; how far the bias moves a shadow's edge on the ground (:func:`aliasing.bias.edge_shift`:
the gap at a caster's foot, the shortening by a normal offset; the worst sun) in pixels at the
middle of the cascade's receivers; the texels
of all maps (k·R²); shadows reaching the farthest receiver; a stabilized fit for a moving camera.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from .. import _validation as check
from ..bias import edge_shift, plane_bias
from ..engines import pipeline as engine_pipeline
from ..raster.draw.lookup import PCF_MAX
from ..setups import Setup

#: Limits by name, as :attr:`aliasing.tune.Tuned.binding` names them.
LIMITS = ("max_texels", "max_gap_px", "max_slope", "moving", "receivers")
#: Sun elevations sampled over the band.
SUN_SAMPLES = 7
#: The steepest receiver sampled: an angle to the light above this is too oblique to be lit
#: (N·L < 0.09) and is left out, as :func:`aliasing.check.check` leaves it out [deg].
MAX_ANGLE = 85.0
AZIMUTH = 90.0  # a ground receiver's depth changes along the map's t axis (the light camera's up is the world's up)

@dataclass(frozen=True)
class Limits:
    """What the tuned settings must meet (validated; see :func:`tune`)."""

    receivers: tuple[float, float]
    max_texels: int
    max_gap_px: float
    max_slope: float
    moving: bool


@dataclass(frozen=True)
class Measure:
    """One setup measured against the limits: per cascade and in all.

    Attributes
    ----------
    error : ndarray
        Worst perspective error per cascade over the receivers and the sun band [px/texel]
        (NaN where no receiver uses the cascade).
    texel : ndarray
        Each cascade's largest world texel over the sun band [world units].
    need : ndarray
        The depth bias each cascade needs at its sampled receiver closest to acne
        (:func:`angles`, the cascade's largest texel) [world units].
    have : ndarray
        The depth bias the settings give there [world units].
    gap_px : ndarray
        The lit gap at a caster's foot per cascade, in pixels at its nearest receiver.
    objective : float
        ``max(error)`` [px/texel]; inf where no cascade reaches the receivers.
    texels : int
        Texels of all maps (k·R²).
    stable : bool
        Whether the fit is stabilized.
    covers : bool
        Whether shadows reach the farthest receiver.
    """

    error: np.ndarray
    texel: np.ndarray
    need: np.ndarray
    have: np.ndarray
    gap_px: np.ndarray
    objective: float
    texels: int
    stable: bool
    covers: bool

    def violations(self, limits: Limits) -> tuple[str, ...]:
        """The limits this setup breaks (empty when it meets them all)."""
        out = []
        if self.texels > limits.max_texels:
            out.append("max_texels")
        if np.any(self.have < self.need * (1 - 1e-9) - 1e-12):
            out.append("max_slope")
        if np.nanmax(self.gap_px, initial=0.0) > limits.max_gap_px * (1 + 1e-9):
            out.append("max_gap_px")
        if limits.moving and not self.stable:
            out.append("moving")
        if not self.covers:
            out.append("receivers")
        return tuple(out)


# -- measuring -------------------------------------------------------------------------------


def lookup(pipe) -> str:
    """The filter's kernel as a lookup of :func:`aliasing.bias.plane_bias` (its taps, as check takes them)."""
    return f"pcf{min(max(1, int(pipe.filter.taps)), PCF_MAX)}"


def steepest(setup: Setup, slope: float) -> float:
    """θ of the steepest lit receiver [deg]: ground tilted ``slope`` away from the lowest sun."""
    return min(90.0 - setup.sun.elevation[0] + slope, MAX_ANGLE)


def angles(setup: Setup, slope: float) -> np.ndarray:
    """θ of the receivers sampled for acne [deg]: the ground and the ground tilted ``slope`` away from the sun, under each sampled elevation.

    As :func:`aliasing.check.check` samples them (θ = 90° − e + σ), those above
    :data:`MAX_ANGLE` brought to it, none steeper than :func:`steepest`.  The steepest does not always bind: a bias that moves the
    receiver across the light (Godot's normal bias) gives less at a small θ than the filter needs
    there, so every angle is kept.
    """
    e = setup.sun.elevations(SUN_SAMPLES)
    top = steepest(setup, slope)
    th = np.concatenate([90.0 - e, 90.0 - e + slope, [top]])
    return np.unique(np.clip(th[th <= top], 0.0, MAX_ANGLE))  # a negative slope (the trade-off's): the receivers up to its θ


def sample(setup: Setup, texel: np.ndarray, slope: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(texel, θ, need) broadcast to (cascades, angles): each cascade's largest texel at every sampled angle."""
    th = angles(setup, slope)[None, :]
    w = np.broadcast_to(np.asarray(texel, float)[:, None], (len(texel), th.shape[1]))
    th = np.broadcast_to(th, w.shape)
    need = np.asarray(plane_bias(w, th, AZIMUTH, lookup(setup.pipeline)).depth, float) * np.ones_like(w)
    return w, th, need


def sample_extent(setup: Setup, shape: tuple[int, ...]) -> np.ndarray | None:
    """Each cascade's shallowest map depth range along the light over the sampled suns [world units],
    broadcast to the sample's (cascades, angles) ``shape``: the least bias a ``depth_range`` term gives
    (None where the rule has no such term)."""
    pipe = setup.pipeline
    if not pipe.bias.needs_extent:
        return None
    lights = setup.sun.direction(setup.sun.elevations(SUN_SAMPLES))
    ext = engine_pipeline.extents(pipe, setup.camera, lights)
    return np.broadcast_to(ext.min(axis=0)[:, None], shape)


def measure(setup: Setup, limits: Limits) -> Measure:
    """The objective and the constraints of one setup (module docstring).

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 4}, "near=0.1,far=500,fov=50,aspect=16:9,height=1080", "15..60")
    >>> round(measure(s, limits(s)).objective, 1)      # three.js's λ = 0.5, 10 cm in front of the eye
    677.2
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (setups.build(...)), got {type(setup).__name__}")
    if not isinstance(limits, Limits):
        raise ValueError(f"limits must be the Limits of aliasing.tune.limits(setup, ...), got {type(limits).__name__}")
    pipe, cam = setup.pipeline, setup.camera
    lights = setup.sun.direction(setup.sun.elevations(SUN_SAMPLES))
    rn, rf = limits.receivers
    t = float(cam.view.tan_theta)
    if pipe.fit == "fixed":
        texel = np.array([max(pipe.box) / pipe.resolution])
        u, v = np.array([cam.near]), np.array([cam.far])
    else:
        r = engine_pipeline.result(pipe, cam, lights)  # the texels of engine_pipeline.texels, once
        texel = np.maximum(r.width_x, r.width_y).max(axis=0) / pipe.resolution
        u, v = (np.asarray(a, float) for a in r.used)
    used = (v > rn) & (u < rf)
    d = np.maximum(u, rn)
    mid = 0.5 * (np.maximum(pipe.near_i, rn) + np.minimum(pipe.far_i, rf))  # where check measures the gap
    with np.errstate(invalid="ignore", divide="ignore"):
        error = np.where(used, texel * cam.height / (2 * t * d), np.nan)  # eq. (2): W/R over the pixel 2 t d/H
    rule = pipe.bias
    w_sun = engine_pipeline.texels(pipe, cam, lights).max(axis=-1)  # (E, K): each sun's largest texel side, as check takes it
    ext = engine_pipeline.extents(pipe, cam, lights) if rule.needs_extent else None  # (E, K) each map's depth range along the light
    w, th, need2 = sample(setup, texel, limits.max_slope)
    low = sample_extent(setup, w.shape)
    have2 = np.asarray(rule.depth(w, th, AZIMUTH, low), float) * np.ones_like(w)
    worst = np.argmin(have2 - need2, axis=1)  # per cascade, the sampled receiver closest to acne
    rows = np.arange(len(texel))
    need, have = need2[rows, worst], have2[rows, worst]
    if rule.faces == "back":
        need = np.full_like(texel, -np.inf)  # lit surfaces compare against the far side: no acne whatever the bias
    elev = setup.sun.elevations(SUN_SAMPLES)[:, None]
    gap = np.max(np.asarray(edge_shift(rule, w_sun, elev, ext), float) * np.ones_like(w_sun), axis=0)  # the worst sun, as check
    gap_px = np.where(used, gap * cam.height / (2 * t * mid), np.nan)
    covers = float(np.max(pipe.far_i)) >= rf * (1 - 1e-9) or pipe.fit == "fixed"
    objective = float(np.nanmax(error)) if np.isfinite(error).any() else math.inf  # no receiver in any cascade: no error to speak of
    return Measure(error, texel, need, have, gap_px, objective, int(pipe.k * pipe.resolution ** 2),
                   bool(pipe.stable), bool(covers))


# -- limits ----------------------------------------------------------------------------------


def depths(receivers: object, name: str = "receivers") -> tuple[float, float]:
    """``receivers`` as (NEAR, FAR) eye depths with 0 < NEAR < FAR, finite [world units]; a ValueError naming ``name`` otherwise."""
    try:
        if isinstance(receivers, (str, bytes)):
            raise TypeError
        rn, rf = (float(x) for x in receivers)  # type: ignore[union-attr]
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be (near, far) eye depths [world units], got {receivers!r}") from None
    if not (math.isfinite(rn) and math.isfinite(rf) and 0 < rn < rf):
        raise ValueError(f"{name} must be NEAR..FAR eye depths with 0 < NEAR < FAR [world units], got {rn:g}..{rf:g}")
    return rn, rf


def limits(setup: Setup, *, receivers: Iterable[float] | None = None, max_texels: int | None = None, max_gap_px: float | None = None,
           max_slope: float = 0.0, moving: bool = False) -> Limits:
    """The validated :class:`Limits` of :func:`tune` (defaults filled from ``setup``).

    Parameters
    ----------
    setup : Setup
        The engine, its settings, the camera and the sun band.
    receivers : (float, float), optional
        NEAR..FAR eye depths [world units] (default the camera's near to where ``setup``'s shadows end).
    max_texels : int, optional
        Texels of all maps together (default those of ``setup``).
    max_gap_px : float, optional
        The largest gap [px], >= 0 (default none: inf).
    max_slope : float
        The steepest acne-free receiver [deg from the ground], in [0, 90).
    moving : bool
        The camera moves.

    Example
    -------
    >>> from aliasing import setups
    >>> lim = limits(setups.build("threejs", {"cascades": 4}), receivers=(1, 200), max_slope=10)
    >>> lim.receivers, lim.max_texels, lim.max_gap_px, lim.max_slope
    ((1.0, 200.0), 16777216, inf, 10.0)
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (setups.build(...)), got {type(setup).__name__}")
    cam = setup.camera
    if receivers is None:  # where the setup casts shadows now: the camera's near to the shadows' end
        rn, rf = cam.near, min(cam.far, float(max(setup.pipeline.far_i)))
    else:
        rn, rf = depths(receivers)
        if rn >= cam.far or rf <= cam.near:
            raise ValueError(f"receivers {rn:g}..{rf:g} must overlap the camera's near..far {cam.near:g}..{cam.far:g}")
        rn, rf = max(rn, cam.near), min(rf, cam.far)
    pipe = setup.pipeline
    texels = check.whole(max_texels, "max_texels", 1) if max_texels is not None else int(pipe.k * pipe.resolution ** 2)
    gap = math.inf if max_gap_px is None else float(check.scalar(max_gap_px, "max_gap_px"))
    if not gap >= 0 or math.isnan(gap):
        raise ValueError(f"max_gap_px must be a number of pixels >= 0, got {max_gap_px!r}")
    slope = float(check.scalar(max_slope, "max_slope"))
    if not 0 <= slope < 90:
        raise ValueError(f"max_slope must be in [0, 90) degrees from the ground, got {max_slope!r}")
    return Limits((rn, rf), texels, gap, slope, check.flag(moving, "moving"))
