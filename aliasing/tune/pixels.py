"""The wrong-pixel objective: the engine's levers searched for the fewest pixels the user sees wrong.

For the engines whose frames the toolkit predicts (:data:`aliasing.frames.seen.ENGINES`: three.js,
Babylon.js, PlayCanvas, their CSM and single-map classes; Godot's Compatibility renderer) the objective is the fraction of the
sun-facing pixels that the predicted frame gets wrong (acne, false shadow and lost shadow,
:func:`aliasing.frames.seen.wrong_pixels`) on the user's scene or the reference scene, over suns
across the band.  Blockiness, the worst px/texel over the receivers
(:func:`aliasing.tune.measure.measure`), and the maps' memory [MiB] are their own axes.

The search (:func:`refine`):

* starts from the user's settings and from the perspective search's pick
  (:func:`aliasing.tune.search.tune`), the better of the two by wrong pixels;
* moves one lever at a time (coordinate-wise), in the order of the profile's ``tunable``: an
  ordered lever (cascade count, map size) to its neighbouring values, a named one (split mode,
  filter, the faces that cast, stabilization, blend band) to each of its values, a continuous
  split parameter to :data:`SPLIT_POINTS` points over its range, where shadows end to the
  receivers' far and its half and quarter, each bias term to its closed-form minimum
  (:func:`aliasing.tune.search.closed_form_bias`) times each of :data:`BIAS_STEPS` and then to
  the geometric middles on both sides of the best (a 1-D search on the wrong-pixel objective);
  another lever moves with the bias terms at the same multiple of their closed-form minimum
  (:func:`_scaled`), and in the first pass a cascade count together with the split: each
  neighbouring count at the split lever's values near the current (:func:`_with_split`);
  a move is kept where it lowers the wrong pixels by more than their count's noise
  (:func:`significant`: a few pixels of one arrangement of boxes say nothing of another scene);
  passes repeat until none moves (at most :data:`PASSES`); then each changed setting is put back
  to your value where that is not significantly worse than the descent's end;
* holds ``--max-texels``, ``--max-memory``, with ``--moving`` a stabilized fit, and
  ``--max-gap-px`` and ``--max-slope`` where given (:func:`hard`); acne and lost shadow are
  otherwise in the objective itself.

Evaluation is cheap enough by a small image (:data:`HEIGHT` rows, :data:`SUNS` suns over the band),
the eye pass and the scene kept between candidates (:func:`aliasing.frames.seen.sample`) and the
light depth maps kept while only biases, filter or blend change
(:func:`aliasing.frames.seen.remember`).  Every candidate within the limits is a point; those no
other point beats on all three axes form the Pareto front, and :data:`PREFER` orders it: the pick is
the front's first, where for ``wrong`` the points within the noise of the fewest wrong pixels count
as tied and the one with the fewest settings changed from the start is the pick.  The pick and the
start are measured again at :data:`FINAL_HEIGHT` rows and :data:`FINAL_SUNS` suns.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from .. import _validation as check
from ..frames import seen
from ..setups import Setup
from .measure import Limits, measure
from .search import closed_form_bias

#: Rows of the search's sample image [px].
HEIGHT = 240
#: Suns over the band in the search.
SUNS = 2
#: Rows [px] and suns of the final measure of the start and the pick.
FINAL_HEIGHT = 240
FINAL_SUNS = 4
#: Multiples of a bias term's closed-form minimum tried by the 1-D search.
BIAS_STEPS = (0.0, 0.25, 0.5, 1.0, 2.0, 4.0)
#: Points over a continuous split parameter's range.
SPLIT_POINTS = 5
#: Coordinate passes at most.
PASSES = 2
#: Bytes of light depth maps kept between candidates (:func:`aliasing.frames.seen.remember`): the current
#: candidates' maps; the older ones give their tables to the next maps (a fresh table costs page faults).
MEMORY = 2**28
#: Standard deviations by which a move must lower the wrong pixels' count (:func:`significant`).
NOISE_Z = 2.0
#: The pick rules: the axes in the order compared (``wrong``: fewest wrong pixels, ties by texels
#: per pixel, then memory; ``blocky``: fewest px/texel first; ``memory``: least memory first).
PREFER = {"wrong": ("wrong", "px_per_texel", "memory"), "blocky": ("px_per_texel", "wrong", "memory"),
          "memory": ("memory", "wrong", "px_per_texel")}
_ORDERED = ("cascades", "size")


def why_not(setup: Setup) -> str | None:
    """Why the wrong-pixel objective does not apply to ``setup`` (None where it does).

    Examples
    --------
    >>> from aliasing import setups
    >>> why_not(setups.build("threejs", {})) is None
    True
    >>> why_not(setups.build("godot", {"rendering/renderer/rendering_method": "gl_compatibility"})) is None
    True
    >>> why_not(setups.build("bevy", {})).startswith("the toolkit does not predict Bevy")
    True
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (setups.build(...)), got {type(setup).__name__}")
    if setup.engine not in seen.ENGINES:
        return f"the toolkit does not predict {setup.profile.title} {setup.release} shadows per pixel (only {', '.join(seen.ENGINES)})"
    try:
        seen.synth.engine_settings(setup)
    except ValueError as exc:
        return f"the toolkit does not predict these settings per pixel: {exc}"
    return None


@dataclass(frozen=True)
class Point:
    """One candidate of the wrong-pixel search: its settings and its three axes.

    Attributes
    ----------
    settings : dict
        The engine's settings.
    wrong, acne, false_shadow, lost_shadow : float
        Fractions of the sun-facing pixels of the search's sample [0..1].
    px_per_texel : float
        The worst perspective error over the receivers [px/texel] (inf where no cascade reaches them).
    memory : float
        The maps' memory [MiB].
    """

    settings: dict
    wrong: float
    acne: float
    false_shadow: float
    lost_shadow: float
    px_per_texel: float
    memory: float

    def axes(self, prefer: str) -> tuple:
        """The point's values in the order of ``PREFER[prefer]`` (``prefer`` one of :data:`PREFER`)."""
        return tuple(round(getattr(self, a), 12) for a in PREFER[check.choice(prefer, "prefer", tuple(PREFER))])

    def to_dict(self, changed: Mapping[str, Any] | None = None) -> dict:
        """JSON-ready (no inf: None), with ``changed``: the settings that differ from ``changed``'s (the start)."""
        out = {k: (v if math.isfinite(v) else None) for k in ("wrong", "acne", "false_shadow", "lost_shadow", "px_per_texel", "memory")
               for v in (float(getattr(self, k)),)}
        if changed is not None:
            out["changed"] = {k: v for k, v in self.settings.items() if changed.get(k) != v}
        return out


@dataclass(frozen=True)
class Seen:
    """What :func:`refine` found: the pick, the front, the start and the pick at the final measure.

    Attributes
    ----------
    setup : Setup
        The pick.
    pareto : tuple of Point
        The Pareto front, in the pick rule's order (the pick first).
    prefer : str
        The pick rule (:data:`PREFER`).
    before, after : dict
        The start's and the pick's :func:`aliasing.frames.seen.wrong_pixels` totals at the final measure.
    sample, final : dict
        The search's and the final measure's sample: ``scene``, ``height_px``, ``suns`` (and the
        search's ``pixels``: the sun-facing pixels its fractions are of, :func:`significant`).
    evaluations : int
        Candidates measured.
    seconds : float
        The search's wall time [s].
    """

    setup: Setup
    pareto: tuple
    prefer: str
    before: dict
    after: dict
    sample: dict
    final: dict
    evaluations: int
    seconds: float
    points: tuple = field(default=(), repr=False)
    where: Any = field(default=None, repr=False)


class Infeasible(ValueError):
    """No candidate of the wrong-pixel search meets the limits (the command's exit status 3)."""


class _Pixels:
    """The candidates measured, cached by their settings."""

    def __init__(self, start: Setup, lim: Limits, where, max_memory: float | None, hard: frozenset):
        self.start, self.limits, self.where, self.max_memory, self.hard = start, lim, where, max_memory, hard
        self.cache: dict = {}
        self.closed: dict = {}  # closed-form bias minima by (settings, key)
        self.pixels = 0  # the sample's sun-facing pixels (the same for every candidate)

    def point(self, settings: Mapping[str, Any]) -> Point | None:
        key = _key(settings)
        if key not in self.cache:
            self.cache[key] = self._measure(settings)
        return self.cache[key]

    def _measure(self, settings: Mapping[str, Any]) -> Point | None:
        try:
            s = Setup(self.start.profile, dict(settings), self.start.camera, self.start.sun)
            m = measure(s, self.limits)
            hard = self.hard & set(m.violations(self.limits))
            memory = s.pipeline.memory / 2**20
            if hard or (self.max_memory is not None and memory > self.max_memory * (1 + 1e-12)):
                return None
            t = seen.count(s, self.where).total
        except ValueError:  # a value the engine refuses, or settings the frames' models do not predict
            return None
        if t["wrong"] is None:
            return None
        self.pixels = int(t["pixels"])
        return Point(dict(s.settings), t["wrong"], t["acne"], t["false_shadow"], t["lost_shadow"], float(m.objective), float(memory))

    def wrong(self, settings: Mapping[str, Any]) -> float:
        p = self.point(settings)
        return math.inf if p is None else p.wrong

    def better(self, a: Mapping[str, Any], b: Mapping[str, Any]) -> bool:
        """Whether settings ``a`` have fewer wrong pixels than ``b`` beyond the noise (:func:`significant`)."""
        wa, wb = self.wrong(a), self.wrong(b)
        return wa < wb and (math.isinf(wb) or significant(wa, wb, self.pixels))


def _key(settings: Mapping[str, Any]) -> tuple:
    """A candidate's key in the cache: its settings, sorted."""
    return tuple(sorted((k, repr(v)) for k, v in settings.items()))


def significant(a: float, b: float, pixels: int, z: float = NOISE_Z) -> bool:
    """Whether wrong-pixel fraction ``a`` is lower than ``b`` by more than ``z`` standard deviations of their counts.

    Over ``pixels`` pixels the counts are A = a·pixels and B = b·pixels; taken as Poisson counts
    the difference B − A has the standard deviation √(A + B), and a move counts where
    B − A > z·√(A + B) (z = :data:`NOISE_Z`: about 2.3 % one-sided).  A few pixels more or
    fewer on one arrangement of the reference scene are how its boxes happen to fall, not
    what the settings do on another scene.

    Parameters
    ----------
    a, b : float
        Fractions of the pixels [0..1].
    pixels : int
        The pixels the fractions are of, >= 0.
    z : float
        Standard deviations, >= 0.

    Examples
    --------
    >>> significant(0.0004, 0.0006, 50000), significant(0.0002, 0.0006, 50000)    # 20 against 30 pixels; 10 against 30
    (False, True)
    """
    n = check.whole(pixels, "pixels", 0)
    z = float(check.closed_range(z, "z", 0.0, math.inf))
    for v, name in ((a, "a"), (b, "b")):
        check.closed_range(v, name, 0.0, 1.0)
    return (b - a) * n > z * math.sqrt((a + b) * n)


def hard(lim: Limits, max_gap_given: bool) -> frozenset:
    """The limits every candidate must meet: the texels, a stabilized fit when moving, the gap where given, acne up to a slope above 0.

    Examples
    --------
    >>> from aliasing import setups
    >>> from aliasing.tune.measure import limits
    >>> sorted(hard(limits(setups.build("threejs", {})), False))
    ['max_texels', 'moving']
    """
    if not isinstance(lim, Limits):
        raise ValueError(f"lim must be aliasing.tune.measure.Limits (limits(...)), got {type(lim).__name__}")
    out = {"max_texels", "moving"} | ({"max_gap_px"} if check.flag(max_gap_given, "max_gap_given") else set())
    return frozenset(out | ({"max_slope"} if lim.max_slope > 0 else set()))


def _tunables(profile, settings: Mapping[str, Any], keep: frozenset) -> list:
    return [t for t in profile.tunable if t.key not in keep and t.active(settings)]


def _tries(px: _Pixels, t, settings: dict) -> list:
    """The values one lever is moved to (module docstring)."""
    now = settings.get(t.key)
    setting = px.start.profile.setting(t.key)
    if t.role == "bias":
        try:
            c = closed_form_bias(px.start.with_settings(**settings), t.key, receivers=px.limits.receivers)
        except ValueError:
            c = None
        base = c if c else (now if isinstance(now, (int, float)) and now else setting.default)
        if not isinstance(base, (int, float)) or not base:
            return []
        return [float(f"{base * f:.4g}") for f in BIAS_STEPS]
    if t.range is not None:
        lo, hi = t.range
        return [lo + (hi - lo) * (i + 0.5) / SPLIT_POINTS for i in range(SPLIT_POINTS)]
    if t.role == "distance":
        far = px.limits.receivers[1]
        return [far, far / 2, far / 4]
    if t.role in _ORDERED and now in t.values:
        i = t.values.index(now)
        return list(t.values[max(i - 1, 0):i + 2])
    return list(t.values)


def _bias_refine(px: _Pixels, key: str, settings: dict, tried: list) -> dict:
    """Between the best bias value and its neighbours among ``tried``: the geometric (or arithmetic, around 0) middles."""
    values = sorted({v for v in tried if px.point({**settings, key: v}) is not None})
    if len(values) < 2:
        return settings
    best = min(values, key=lambda v: px.wrong({**settings, key: v}))
    i = values.index(best)
    out = settings
    for j in (i - 1, i + 1):
        if 0 <= j < len(values):
            a, b = best, values[j]
            mid = math.sqrt(a * b) if a * b > 0 else (a + b) / 2
            mid = float(f"{mid:.4g}")
            if px.better({**out, key: mid}, out):
                out = {**out, key: mid}
    return {**out, key: best} if px.better({**settings, key: best}, out) else out


def _closed_forms(px: _Pixels, settings: Mapping[str, Any], keys: list) -> dict:
    """Each bias term's closed-form minimum at ``settings`` (:func:`aliasing.tune.search.closed_form_bias`), cached; None where none."""
    out = {}
    for key in keys:
        cache_key = (_key(settings), key)
        if cache_key not in px.closed:
            try:
                px.closed[cache_key] = closed_form_bias(px.start.with_settings(**settings), key, receivers=px.limits.receivers)
            except ValueError:
                px.closed[cache_key] = None
        out[key] = px.closed[cache_key]
    return out


def _scaled(px: _Pixels, now: dict, trial: dict, keep: frozenset) -> dict:
    """``trial`` (a lever other than a bias moved from ``now``) with each free bias term at ``now``'s multiple of its
    closed-form minimum (:func:`aliasing.tune.search.closed_form_bias`, where it changed by over 5 %): a count, split, size
    or filter changes the bias a surface needs, and at ``now``'s bias a finer map would lose to its acne, a coarser one to
    its peter-panning."""
    keys = [t.key for t in _tunables(px.start.profile, trial, keep) if t.role == "bias" and isinstance(trial.get(t.key), (int, float))
            and trial.get(t.key)]
    if not keys:
        return trial
    a, b = _closed_forms(px, now, keys), _closed_forms(px, trial, keys)
    scaled = dict(trial)
    for key in keys:
        if a[key] and b[key] and abs(b[key] / a[key] - 1) > 0.05:
            try:
                scaled[key] = px.start.profile.setting(key).coerce(float(f"{trial[key] * b[key] / a[key]:.4g}"))
            except ValueError:  # beyond the setting's range: kept
                pass
    return scaled


def _with_split(px: _Pixels, now: dict, trial: dict, keep: frozenset) -> list:
    """``trial`` (a cascade count moved from ``now``) at each value of the first split lever active there (of a continuous
    one the three points nearest its value), biases :func:`_scaled`: one lever at a time leaves the count at the split
    that suited the old count."""
    splits = [u for u in _tunables(px.start.profile, trial, keep) if u.role == "split" and u.key in trial]
    if not splits:
        return []
    u = splits[0]
    tries = _tries(px, u, trial)
    if u.range is not None and isinstance(trial[u.key], (int, float)):  # a continuous split: the three points nearest the current
        tries = sorted(tries, key=lambda w: abs(w - trial[u.key]))[:3]
    return [_scaled(px, now, {**trial, u.key: w}, keep) for w in (_coerced(px, u.key, w) for w in tries) if w is not None and w != trial[u.key]]


def _coerced(px: _Pixels, key: str, value: Any) -> Any:
    """``value`` as setting ``key`` takes it, or None where it refuses it."""
    try:
        return px.start.profile.setting(key).coerce(value)
    except ValueError:
        return None


def _coordinate(px: _Pixels, settings: dict, keep: frozenset) -> dict:
    """Coordinate-wise descent on the wrong pixels from ``settings`` (module docstring)."""
    best = dict(settings)
    for n in range(PASSES):
        moved = False
        for t in _tunables(px.start.profile, best, keep):
            if t.key not in best:
                continue
            tried, trials = [], []
            now = dict(best)
            for v in (_coerced(px, t.key, v) for v in _tries(px, t, now)):
                if v is None:
                    continue
                tried.append(v)
                trials.append({**now, t.key: v} if t.role == "bias" else _scaled(px, now, {**now, t.key: v}, keep))
                if t.role == "cascades" and n == 0:  # the count and the split together, in the first pass (module docstring)
                    trials += _with_split(px, now, {**now, t.key: v}, keep)
            for trial in trials:
                if px.better(trial, best):
                    best, moved = trial, True
            if t.role == "bias" and tried:
                got = _bias_refine(px, t.key, best, tried + [best[t.key]])
                if px.better(got, best):
                    best, moved = got, True
        if not moved:
            break
    return best


def _undo(px: _Pixels, settings: dict, start: Mapping[str, Any]) -> dict:
    """Each setting the descent changed, put back to the start's value where that is not significantly worse than the
    descent's end ``settings`` (one at a time in the settings' order, then the levers of one role together, as split
    fractions that must stay in order; again until none goes back): a change is kept only where it pays beyond the noise
    on its own.  Compared with the end, not with the last put back: steps each within the noise add up to more."""
    best = dict(settings)
    roles = {t.key: t.role for t in px.start.profile.tunable}
    while True:
        keys = [k for k, v in best.items() if k in start and start[k] != v]
        groups = [[k] for k in keys] + [g for r in {roles.get(k) for k in keys} if len(g := [k for k in keys if roles.get(k) == r]) > 1]
        for group in groups:
            back = {**best, **{k: start[k] for k in group}}
            if back != best and px.point(back) is not None and not px.better(settings, back):
                best = back
                break
        else:
            return best


def front(points, prefer: str = "wrong", start: Mapping[str, Any] | None = None, pixels: int | None = None) -> tuple:
    """The points no other beats on all three axes (wrong, px/texel, memory), in the order of ``PREFER[prefer]``, the pick first.

    Of points equal on all three axes only one is kept: the one with the fewest settings changed from ``start``.
    With ``pixels`` (the count the fractions are of) and ``prefer`` "wrong", every point whose wrong
    pixels are within the noise of the fewest (not more by :func:`significant`) is tied, on the
    front or beaten there only within the noise, and the pick, put first, is the tied point with
    the fewest settings changed from ``start`` (then the usual order); the front follows.

    Parameters
    ----------
    points : iterable of Point
    prefer : str
        One of :data:`PREFER`.
    start : dict, optional
        The start's settings (default: the first point's).

    Examples
    --------
    >>> a = Point({"k": 1}, 0.01, 0.0, 0.0, 0.01, 5.0, 64.0); b = Point({"k": 2}, 0.02, 0.0, 0.0, 0.02, 2.0, 64.0)
    >>> c = Point({"k": 3}, 0.03, 0.0, 0.0, 0.03, 6.0, 64.0)                       # worse than a on every axis
    >>> [p.settings["k"] for p in front([a, b, c])], [p.settings["k"] for p in front([a, b, c], "blocky")]
    ([1, 2], [2, 1])
    >>> [p.settings["k"] for p in front([a, b, c], start={"k": 2}, pixels=1000)]   # 10 against 20 pixels: tied, b is the start
    [2, 1]
    """
    rule = check.choice(prefer, "prefer", tuple(PREFER))
    pts = [p for p in points if isinstance(p, Point)]
    keys = ("wrong", "px_per_texel", "memory")

    def beats(a, b):
        va, vb = [getattr(a, k) for k in keys], [getattr(b, k) for k in keys]
        return all(x <= y for x, y in zip(va, vb)) and any(x < y for x, y in zip(va, vb))

    base = dict(start) if start is not None else (pts[0].settings if pts else {})
    unique: dict = {}
    for p in sorted(pts, key=lambda p: sum(base.get(k) != v for k, v in p.settings.items())):
        unique.setdefault(p.axes("wrong"), p)
    out = sorted((p for p in unique.values() if not any(beats(q, p) for q in unique.values() if q is not p)), key=lambda p: p.axes(rule))
    if pixels is not None and rule == "wrong" and out:
        n = check.whole(pixels, "pixels", 0)
        least = min(p.wrong for p in unique.values())
        tied = [p for p in unique.values() if not significant(least, p.wrong, n)]  # beaten only within the noise counts too
        pick = min(tied, key=lambda p: (sum(base.get(k) != v for k, v in p.settings.items()), p.axes(rule)))
        out = [pick] + [p for p in out if p is not pick]
    return tuple(out)


def refine(start: Setup, perspective: Setup, lim: Limits, *, scene: Any = None, keep: frozenset = frozenset(), prefer: str = "wrong",
           max_memory: float | None = None, max_gap_given: bool = False, height: int = HEIGHT, suns: int = SUNS) -> Seen:
    """The wrong-pixel search (module docstring) from the user's ``start`` and the perspective search's pick ``perspective``.

    Parameters
    ----------
    start, perspective : Setup
        The user's setup and the perspective search's pick (one engine, camera and sun band).
    lim : Limits
        The limits (:func:`aliasing.tune.measure.limits`).
    scene : FrameScene or str, optional
        The scene (:func:`aliasing.frames.seen.wrong_pixels`); None: the reference scene.
    keep : frozenset of str
        Settings held at the start's values.
    prefer : str
        The pick rule, one of :data:`PREFER`.
    max_memory : float, optional
        The most memory of all maps [MiB], > 0.
    max_gap_given : bool
        Whether the user set ``lim.max_gap_px`` (then it binds every candidate, :func:`hard`).
    height : int
        Rows of the search's sample image [px], 16 to 1080.
    suns : int
        Suns over the band in the search, 1 to 16.

    Returns
    -------
    Seen

    Raises
    ------
    Infeasible
        No candidate meets the limits.
    ValueError
        Naming the parameter: an engine whose frames are not predicted (:func:`why_not`), a bad
        ``prefer``, ``max_memory``, ``height`` or ``suns``.

    Examples
    --------
    >>> from aliasing import setups
    >>> from aliasing.tune.measure import limits
    >>> s = setups.build("playcanvas", {"numCascades": 2, "shadowResolution": 512, "shadowBias": 0.0},
    ...                  "near=0.5,far=60,fov=50,aspect=16:9,height=720", "30..50")
    >>> got = refine(s, s, limits(s), keep=frozenset({"numCascades", "shadowResolution", "cascadeDistribution", "shadowDistance",
    ...              "cascadeBlend", "normalOffsetBias"}), height=48, suns=1)
    >>> got.after["wrong"] < got.before["wrong"], got.setup.settings["shadowBias"] > 0
    (True, True)
    """
    for name, s in (("start", start), ("perspective", perspective)):
        if not isinstance(s, Setup):
            raise ValueError(f"{name} must be an aliasing.setups.Setup (setups.build(...)), got {type(s).__name__}")
    why = why_not(start)
    if why:
        raise ValueError(f"start: {why}")
    rule = check.choice(prefer, "prefer", tuple(PREFER))
    if max_memory is not None:
        max_memory = float(check.scalar(max_memory, "max_memory"))
        if not (math.isfinite(max_memory) and max_memory > 0):
            raise ValueError(f"max_memory must be a number of MiB > 0, got {max_memory!r}")
    h = check.whole(height, "height", 16, 1080, " [px] (rows of the search's sample image)")
    n = check.whole(suns, "suns", 1, 16, " (suns over the band in the search)")
    t0 = time.perf_counter()
    where = seen.sample(start, scene, height=h, suns=n)
    px = _Pixels(start, lim, where, max_memory, hard(lim, max_gap_given))
    with seen.remember(MEMORY):
        first = dict(perspective.settings) if px.better(perspective.settings, start.settings) else dict(start.settings)
        _undo(px, _coordinate(px, first, keep), start.settings)
    points = [p for p in px.cache.values() if p is not None]
    if not points:
        raise Infeasible("no setting the search reached meets the limits (--max-texels, --max-memory, --moving, --max-gap-px, "
                         "--max-slope): relax one")
    pareto = front(points, rule, start.settings, px.pixels)
    pick = Setup(start.profile, dict(pareto[0].settings), start.camera, start.sun)
    final_where = seen.sample(start, scene, height=FINAL_HEIGHT, suns=FINAL_SUNS)
    before, after = seen.count(start, final_where).total, seen.count(pick, final_where).total
    return Seen(pick, pareto, rule, before, after, {"scene": where.scene.name, "height_px": h, "suns": n, "pixels": px.pixels},
                {"scene": where.scene.name, "height_px": FINAL_HEIGHT, "suns": FINAL_SUNS}, len(px.cache), time.perf_counter() - t0,
                tuple(points), where)
