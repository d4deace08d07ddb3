"""The search: an engine's own settings that minimise the worst perspective error within limits.

The objective and the constraints are those of :mod:`aliasing.tune.measure`.  Each kind of
setting is set the cheapest way that is exact:

* map size: the largest the engine allows within the texel budget (the error falls as 1/R, and
  so do the texel, the bias it needs and the gap that bias opens: the largest size dominates);
* where shadows end (three.js ``maxFar``): the receivers' far (any farther spreads texels over
  depths nobody sees);
* biases: not searched but set to their minimum, the closed form: the bias that the sampled
  receivers (the steepest, for most rules) need in each cascade's largest texel (:func:`aliasing.bias.plane_bias`, the filter's
  kernel included), converted to the engine's units by the profile's
  :meth:`aliasing.setups.BiasRule.minimal`, the extreme over the cascades, rounded to four
  significant digits on the safe side; where the engine has several bias settings, each is
  tried alone (the others at zero) and the one whose lit gap is smallest kept;
* cascade counts, split modes, filters, stabilization: enumerated over the values of the
  profile's ``tunable`` (:class:`aliasing.setups.Tunable`);
* continuous split parameters (λ, split fractions): a scan at the profile's step, then a bounded
  Brent search (:func:`scipy.optimize.minimize_scalar`) around the best point of the scan, one
  parameter at a time until none moves.

The user's setup is the start: its settings are where the search begins (the continuous split
parameters keep their value where no other does better, the biases are tried as they are) and
the start itself is a candidate, so a start that meets the limits is never replaced by a worse
one.  ``keep`` holds settings at the start's values.  Among equal errors the search keeps the
smaller gap, then the fewer changed settings.

The start's gap is not held as a limit: a better split brings the first cascade closer to the eye,
where the gap is measured in pixels, so holding it would often keep the start's split (Godot,
``directional_shadow_max_distance`` 200 and receivers 1..100: every split with a lower error had a
larger gap, and the search held to it returned the start).  Instead, where ``max_gap_px`` is
not given, the start leaves no acne and the tuned gap is larger than the start's (and than one
pixel), ``Tuned.held_gap`` is the search again with the start's gap as ``max_gap_px``: what
holding it would cost in error, for the user to choose.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy import optimize

from .. import _validation as check_names
from ..setups import Setup, Tunable
from .measure import AZIMUTH, LIMITS, Limits, Measure, limits, measure, sample, sample_extent, steepest
from .receivers import scene_receivers

_DIGITS = 4  # significant digits of a bias setting, rounded on the safe side


@dataclass(frozen=True)
class Tuned:
    """What :func:`tune` found.

    Attributes
    ----------
    setup : Setup
        The tuned setup (the engine's own settings).
    start : Setup
        The setup it started from: the user's (the engine's defaults where the user gave no value).
    objective : float
        Its worst perspective error over the receivers and the sun band [px/texel].
    binding : tuple of str
        The limits that bind (:data:`LIMITS`): where all are met, those whose relaxing would
        lower the objective; where they cannot all be met, those the closest setup breaks.
    feasible : bool
        Whether every limit is met.
    tradeoff : tuple of dict
        Where acne and the gap limit conflict: the smallest gap [px] reachable per steepest
        acne-free slope [deg] (``{"slope": s, "gap_px": g}``); empty otherwise.
    limits : Limits
        The limits searched under.
    measure, before : Measure
        The tuned and the starting setup measured.
    changed : dict
        The settings that differ from the start (key -> tuned value).
    evaluations : int
        Setups measured.
    keep : tuple of str
        The settings held at the start's values.
    held_gap : Tuned or None
        Where the gap grew unasked (module docstring): the same search with the start's gap as the
        limit; None otherwise.
    """

    setup: Setup
    start: Setup
    objective: float
    binding: tuple
    feasible: bool
    tradeoff: tuple
    limits: Limits
    measure: Measure
    before: Measure
    changed: dict = field(default_factory=dict)
    evaluations: int = 0
    keep: tuple = ()
    held_gap: Tuned | None = None

    @property
    def settings(self) -> dict[str, Any]:
        """Every setting of the tuned setup, by the engine's keys."""
        return dict(self.setup.settings)

    @property
    def changes(self) -> list[dict[str, Any]]:
        """Every setting that differs from the start: ``{key, before, after, unit}`` (the engine's units, ``""`` for none)."""
        profile = self.setup.profile
        return [{"key": k, "before": self.start.settings.get(k), "after": v, "unit": profile.setting(k).unit} for k, v in self.changed.items()]

    def snippet(self, light: str | None = None) -> str:
        """Code in the engine's language that sets the changed settings on the user's light ``light`` (its name; None: a placeholder)."""
        if light is not None and (not isinstance(light, str) or not light.strip()):
            raise ValueError(f"light must be the light's name in the project, got {light!r}")
        snip = self.setup.profile.snippet
        if not self.changed:
            return ""
        return snip(self.setup.settings, tuple(self.changed), light) if snip else "\n".join(f"{k} = {v!r}" for k, v in self.changed.items())


# -- the search ------------------------------------------------------------------------------


class _Search:
    """One search: the setups measured, cached by their settings."""

    def __init__(self, start: Setup, lim: Limits, keep: frozenset):
        self.start, self.limits, self.keep = start, lim, keep
        self.profile = start.profile
        self.cache: dict = {}

    def tunables(self, settings: Mapping[str, Any], role: str) -> list[Tunable]:
        return [t for t in self.profile.tunable if t.role == role and t.key not in self.keep and t.active(settings)]

    def setup(self, settings: Mapping[str, Any]) -> Setup | None:
        key = tuple(sorted((k, repr(v)) for k, v in settings.items()))
        if key not in self.cache:
            try:
                s = Setup(self.profile, dict(settings), self.start.camera, self.start.sun)
                self.cache[key] = (s, measure(s, self.limits))
            except ValueError:
                self.cache[key] = None
        return self.cache[key]

    def objective(self, settings: Mapping[str, Any]) -> float:
        got = self.setup(settings)
        return math.inf if got is None else got[1].objective

    # closed forms --------------------------------------------------------------------------

    def distance(self, settings: dict) -> dict:
        """Shadows end at the farthest receiver (left alone where they already do)."""
        out = dict(settings)
        got = self.setup(out)
        if got is not None and math.isclose(max(got[0].pipeline.far_i), self.limits.receivers[1], rel_tol=1e-12):
            return out
        for t in self.tunables(out, "distance"):
            try:
                out[t.key] = self.profile.setting(t.key).coerce(float(self.limits.receivers[1]))
            except ValueError:
                pass
        return out

    def size(self, settings: dict) -> dict:
        """The largest map size within the texel budget (the smallest where none fits)."""
        out = dict(settings)
        for t in self.tunables(out, "size"):
            out[t.key] = min(t.values)
            for value in sorted(t.values, reverse=True):  # texels grow with the size: the first that fits
                got = self.setup({**out, t.key: value})
                if got is not None and got[1].texels <= self.limits.max_texels:
                    out[t.key] = value
                    break
        return out

    def splits(self, settings: dict) -> dict:
        """Continuous split parameters: a scan at the profile's step, then bounded Brent, one at a time."""
        out = dict(settings)
        free = self.tunables(out, "split")
        free = [t for t in free if t.range is not None]
        if not free:
            return out
        best = self.objective(out)
        for _ in range(4):
            moved = False
            for t in free:
                grid = t.grid()
                values = [self.objective({**out, t.key: g}) for g in grid]
                i = int(np.argmin(values))
                lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
                x, f = grid[i], values[i]
                if hi > lo and math.isfinite(f):
                    r = optimize.minimize_scalar(lambda v, k=t.key: self.objective({**out, k: float(v)}), bounds=(lo, hi), method="bounded",
                                                 options={"xatol": 1e-5 * (t.range[1] - t.range[0])})
                    if r.fun < f:
                        x, f = float(r.x), float(r.fun)
                if f < best * (1 - 1e-12):
                    moved = moved or not math.isclose(x, out.get(t.key), rel_tol=1e-9, abs_tol=1e-12)
                    out[t.key], best = x, f
            if not moved:
                break
        if len(free) > 1:  # one at a time stalls where two cascades share the worst error: all together, smoothed
            out, best = self.jointly(out, free, best)
        for t in free:  # four significant digits, as a snippet prints them
            out[t.key] = self.profile.setting(t.key).coerce(float(f"{out[t.key]:.4g}"))
        return out

    def jointly(self, settings: dict, free: list[Tunable], best: float) -> tuple[dict, float]:
        """Every split parameter at once: Nelder–Mead on the p-norm of the cascades' errors.

        The worst error is a maximum over cascades: where two share it, moving one parameter
        raises the other's, and a search one parameter at a time stops there.  The p-norm
        (p = 16, then 64) is smooth and tends to the maximum; each parameter is searched on a log
        scale of its distance from the range's low end (split fractions span decades near 0).
        The result is kept only where its worst error is lower.  (Powell's method was tried: its
        line searches cross the values an engine refuses, unordered fractions, and stop there.)
        """
        lows = np.array([t.range[0] for t in free])
        spans = np.array([t.range[1] - t.range[0] for t in free])
        floor = np.log(spans * 1e-5)

        def values(y):
            return {t.key: float(v) for t, v in zip(free, lows + np.exp(np.clip(y, floor, np.log(spans))))}

        out = dict(settings)
        for p in (16.0, 64.0):
            def smooth(y, p=p):
                got = self.setup({**out, **values(y)})
                if got is None or not math.isfinite(got[1].objective):
                    return 1e6
                e = got[1].error[np.isfinite(got[1].error)] / best
                return float(np.mean(e ** p) ** (1 / p))
            y0 = np.log(np.maximum(np.array([out[t.key] for t in free], float) - lows, spans * 1e-5))
            r = optimize.minimize(smooth, y0, method="Nelder-Mead", bounds=list(zip(floor, np.log(spans))),
                                  options={"xatol": 1e-4, "fatol": 1e-7, "maxfev": 400 * len(free)})
            trial = {**out, **values(r.x)}
            f = self.objective(trial)
            if f < best * (1 - 1e-12):
                out, best = trial, f
        return out, best

    def biases(self, settings: dict) -> list[dict]:
        """Each free bias setting alone at its minimum (the others neutral): the candidates."""
        free = self.tunables(settings, "bias")
        if not free:
            return [dict(settings)]
        neutral = {t.key: _neutral(self.profile.setting(t.key)) for t in free}
        base = {**settings, **neutral}
        got, now = self.setup(base), self.setup(settings)
        if got is None:
            return [dict(settings)]
        if now is not None:  # a setting the engine reads as the same bias keeps its value (three.js: shadowBias 0 is 1e-6)
            for key in neutral:
                try:
                    if got[0].pipeline.bias.term(key).value == now[0].pipeline.bias.term(key).value:
                        base[key] = settings[key]
                except ValueError:
                    pass
            got = self.setup(base)
        s, m = got
        out = [dict(settings)]  # the biases as they are, where they suffice
        if np.all(m.have >= m.need):
            return out + [base]  # nothing needed (back faces cast, or the fixed terms suffice)
        for t in free:
            value = _minimal(s, t.key, m, self.limits.max_slope)
            if value is None:
                continue
            out.append({**base, t.key: value})
        return out


def _neutral(setting) -> Any:
    lo, hi = setting.accepts
    return setting.coerce(min(max(0.0, lo if lo is not None else 0.0), hi if hi is not None else 0.0)) if setting.kind in ("float", "int") else setting.default


def _round_safe(value: float, up: bool) -> float:
    """``value`` to :data:`_DIGITS` significant digits, rounded away from the unsafe side."""
    if value == 0 or not math.isfinite(value):
        return value
    q = 10.0 ** (math.floor(math.log10(abs(value))) - _DIGITS + 1)
    return float(f"{(math.ceil(value / q) if up else math.floor(value / q)) * q:.{_DIGITS}g}")


def _per_sign(rule, key: str, need: np.ndarray, texel: np.ndarray, angle: float, extent=None) -> np.ndarray:
    """The sign of the depth bias one unit of ``key`` gives, per cascade (0: it cannot help).

    From the rule's own :meth:`~aliasing.setups.BiasRule.minimal`, linear in the need: a unit
    more need moves the value by 1/per (every term of the setting, and the map's depth range
    where a term scales with it, counted as the rule counts them).
    """
    with np.errstate(invalid="ignore"):
        step = (np.asarray(rule.minimal(key, need + 1.0, texel, angle, AZIMUTH, extent), float)
                - np.asarray(rule.minimal(key, need, texel, angle, AZIMUTH, extent), float))
    return np.where(np.isfinite(step), np.sign(step), 0.0)


def _extreme(rule, key: str, need: np.ndarray, texel: np.ndarray, angle: float, extent=None) -> tuple[float, bool] | None:
    """The minimal value of ``key`` over the cascades and whether it is a bound from below (None: it cannot help)."""
    sign = _per_sign(rule, key, need, texel, angle, extent)
    if not (np.all(sign > 0) or np.all(sign < 0)):
        return None
    values = np.asarray(rule.minimal(key, need, texel, angle, AZIMUTH, extent), float)
    up = bool(np.all(sign > 0))
    value = float(values.max() if up else values.min())
    return (value, up) if math.isfinite(value) else None


def _minimal(setup: Setup, key: str, m: Measure, slope: float) -> float | None:
    """The closed-form minimum of bias setting ``key`` over the cascades and the sampled receivers, in the engine's units (None: it cannot help)."""
    rule = setup.pipeline.bias
    if key not in {t.key for t in rule.terms}:
        return None
    w, th, need = sample(setup, m.texel, slope)
    ext = sample_extent(setup, w.shape)
    got = _extreme(rule, key, need, w, th, ext)
    if got is None:
        return None
    value, up = got
    value = _round_safe(value, up)
    for v in (value, 1e-9 if up else -1e-9) if value == 0 else (value,):  # an engine may read 0 as its default (three.js)
        try:
            v = setup.profile.setting(key).coerce(v)
            s = setup.with_settings(**{key: v})
        except ValueError:
            return None
        if np.all(np.asarray(s.pipeline.bias.depth(w, th, AZIMUTH, ext)) >= need * (1 - 1e-9) - 1e-12):
            return v
    return None


def closed_form_bias(setup: Setup, key: str, *, max_slope: float = 0.0, receivers=None) -> float | None:
    """The minimal value of bias setting ``key`` [the engine's units] that leaves no acne up to ``max_slope``.

    The other free bias settings at zero; every sampled receiver's need (the ground and the
    ground tilted ``max_slope`` under each sampled sun, :func:`aliasing.tune.measure.angles`) in each cascade's largest
    texel (:func:`aliasing.bias.plane_bias`, the filter's kernel) through the rule's
    :meth:`aliasing.setups.BiasRule.minimal`, exact (not rounded).  None where the setting cannot
    remove the acne.

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 4, "material.shadowSide": "FrontSide"}, sun="15..60")
    >>> v = closed_form_bias(s, "shadow.normalBias")
    >>> 0.1 < v < 1.0
    True
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (setups.build(...)), got {type(setup).__name__}")
    terms = [t.key for t in setup.pipeline.bias.terms]
    if not isinstance(key, str) or key not in terms:
        raise ValueError(f"key must be a bias setting of {setup.profile.title}, one of {', '.join(terms)}; got {key!r}"
                         + check_names.did_you_mean(key, terms))
    lim = limits(setup, receivers=receivers, max_slope=max_slope)
    free = [t.key for t in setup.profile.tunable if t.role == "bias" and t.active(setup.settings)]
    s = setup.with_settings(**{k: _neutral(setup.profile.setting(k)) for k in free if k != key})
    m = measure(s, lim)
    w, th, need = sample(s, m.texel, lim.max_slope)
    got = _extreme(s.pipeline.bias, key, need, w, th, sample_extent(s, w.shape))
    return None if got is None else got[0]


def _changes(a: Mapping[str, Any], b: Mapping[str, Any]) -> int:
    return sum(1 for k in a if a[k] != b.get(k))


def _keys(setup: Setup, keep: Any) -> frozenset:
    """The settings of ``keep`` (one key or an iterable of keys), validated against the profile's keys."""
    if isinstance(keep, str):
        keep = (keep,)
    if isinstance(keep, (bytes, Mapping)) or not isinstance(keep, Iterable):
        raise ValueError(f"keep must be setting keys of {setup.profile.title} (a str or an iterable of str), got {type(keep).__name__}")
    out = set()
    for k in keep:
        if not isinstance(k, str):
            raise ValueError(f"keep must hold setting keys (str), got {k!r}")
        try:
            out.add(setup.profile.setting(k.strip()).key)
        except ValueError as exc:
            raise ValueError(f"keep: {exc}") from None
    return frozenset(out)


def tune(setup: Setup, *, receivers: Iterable[float] | None = None, scene: Any = None, max_texels: int | None = None,
         max_gap_px: float | None = None, max_slope: float = 0.0, moving: bool = False, keep: Iterable[str] = ()) -> Tuned:
    """The engine's own settings with the lowest worst perspective error within the limits, from the user's setup.

    ``setup`` is the start (the user's settings, the engine's defaults for the rest): the search
    begins there and the start itself is a candidate.  Only the settings the profile declares
    tunable (the ``tunable`` of :class:`aliasing.setups.Profile`) and not in ``keep`` move; the
    rest keep ``setup``'s values.  How each kind is set: the module docstring.

    Parameters
    ----------
    setup : Setup
        The engine, the user's settings (the start), the camera and the sun band.
    receivers : (float, float), optional
        Eye depths of the receivers, NEAR..FAR [world units] (default the camera's near to where
        ``setup``'s shadows end).
    scene : Scene or str, optional
        A scene whose visible depths give the receivers (instead of ``receivers``).
    max_texels : int, optional
        Texels of all maps together (default: those of ``setup``).
    max_gap_px : float, optional
        The largest lit gap at a caster's foot [px]; ``math.inf`` for none.  Default: where the
        start leaves no acne up to ``max_slope``, its own largest gap (at least 1 px), so that
        tune does not trade a larger gap for a smaller error unasked; otherwise none.
    max_slope : float
        The steepest receiver that must stay free of acne: ground tilted this far away from the
        lowest sun [deg from the ground], in [0, 90).
    moving : bool
        The camera moves: the fit must be stabilized (no shimmer).
    keep : str or iterable of str
        Setting keys held at the start's values (the engine's own keys).

    Returns
    -------
    Tuned
        The setup, its objective [px/texel], every change from the start, the binding
        limits and, where acne and the gap limit conflict, the trade-off between them.

    Raises
    ------
    ValueError
        A malformed limit (naming it) or an unknown setting in ``keep`` (with a did-you-mean).

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 4}, "near=0.1,far=500,fov=50,aspect=16:9,height=1080", "15..60")
    >>> t = tune(s, keep=("cascades", "shadowMapSize"))
    >>> t.setup.settings["mode"], round(t.objective, 2), t.binding
    ('logarithmic', 9.05, ())
    >>> t.changes
    [{'key': 'mode', 'before': 'practical', 'after': 'logarithmic', 'unit': ''}]
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (setups.build(...)), got {type(setup).__name__}")
    if scene is not None:
        if receivers is not None:
            raise ValueError("give receivers or scene, not both")
        receivers = scene_receivers(scene, setup)
    keep = _keys(setup, keep)
    lim = limits(setup, receivers=receivers, max_texels=max_texels, max_gap_px=max_gap_px, max_slope=max_slope, moving=moving)
    before = measure(setup, lim)
    search = _Search(setup, lim, keep)
    start = dict(setup.settings)

    # every combination of the enumerated settings (cascade counts, split modes, filters, stabilization, blends)
    candidates: list[tuple[Setup, Measure]] = []
    seen: set = set()

    def expand(settings: dict, roles: tuple) -> list[dict]:
        out = [settings]
        for role in roles:
            nxt = []
            for s in out:
                ts = [t for t in search.tunables(s, role) if t.values and t.range is None]
                if not ts:
                    nxt.append(s)
                    continue
                for combo in itertools.product(*(t.values for t in ts)):
                    nxt.append({**s, **{t.key: v for t, v in zip(ts, combo)}})
            out = nxt
        return out

    for s in expand(start, ("cascades", "split", "stable", "blend")):
        s = search.splits(search.size(search.distance(s)))
        for b in (b for f in expand(s, ("filter",)) for b in search.biases(f)):  # the filter moves only the bias
            key = tuple(sorted((k, repr(v)) for k, v in b.items()))
            if key in seen:
                continue
            seen.add(key)
            got = search.setup(b)
            if got is not None:
                candidates.append(got)
    candidates.append((setup, before))  # the start itself: a start within the limits is never replaced by a worse setup

    def rank(c):
        s, m = c
        return (len(m.violations(lim)) > 0, round(m.objective, 9), round(_gap(m), 9), _changes(s.settings, start))

    feasible = [c for c in candidates if not c[1].violations(lim)]
    if feasible:
        best = min(feasible, key=rank)
        binding = _binding_feasible(search, candidates, best, lim)
        tradeoff: tuple = ()
    else:
        best, binding = _closest(candidates, lim, start)
        tradeoff = _tradeoff(search, candidates, lim) if {"max_gap_px", "max_slope"} & set(binding) else ()
    s, m = best
    held = None
    if max_gap_px is None and "max_slope" not in before.violations(lim) and _gap(m) > max(_gap(before), 1.0) * (1 + 1e-9):
        held = tune(setup, receivers=lim.receivers, max_texels=lim.max_texels, max_gap_px=max(_gap(before), 1.0), max_slope=lim.max_slope,
                    moving=lim.moving, keep=keep)
    return Tuned(s, setup, m.objective, tuple(binding), not m.violations(lim), tradeoff, lim, m, before,
                 {k: v for k, v in s.settings.items() if start.get(k) != v}, len(search.cache), tuple(sorted(keep)), held)


def _binding_feasible(search: _Search, candidates, best, lim: Limits) -> list[str]:
    """Limits whose relaxing would lower the objective of a feasible optimum."""
    s, m = best
    out = []
    for name in LIMITS:
        if name == "max_texels":
            bigger = False
            for t in search.tunables(s.settings, "size"):
                larger = [v for v in t.values if v > s.settings[t.key]]
                bigger = bigger or bool(larger)
            counts = [c for c in candidates if c[1].objective < m.objective * (1 - 1e-9) and set(c[1].violations(lim)) <= {"max_texels"}]
            if bigger or counts:
                out.append(name)
            continue
        better = [c for c in candidates if c[1].objective < m.objective * (1 - 1e-9) and set(c[1].violations(lim)) == {name}]
        if better:
            out.append(name)
    return out


def _gap(m: Measure) -> float:
    return float(np.nanmax(m.gap_px, initial=0.0))


_HARD = ("max_texels", "moving", "receivers")


def _closest(candidates, lim: Limits, start: Mapping[str, Any]):
    """Where no candidate meets every limit: the closest, and the limits that bind.

    The hardware's and the camera's limits (texels, a moving camera, coverage) first, the fewest
    texels over the budget, then no acne, then the smallest gap, then the lowest error.  Where the gap breaks only because the
    acne limit holds (some candidate meets the gap by giving up acne), both bind.
    """
    def key(c):
        s, m = c
        v = m.violations(lim)
        return (sum(x in _HARD for x in v), max(m.texels / lim.max_texels, 1.0), "max_slope" in v,
                round(_gap(m), 9) if "max_gap_px" in v else 0.0, round(m.objective, 9), _changes(s.settings, start))

    best = min(candidates, key=key)
    binding = list(best[1].violations(lim))
    if "max_gap_px" in binding and "max_slope" not in binding:
        hard = [x for x in binding if x in _HARD]
        if any(set(m.violations(lim)) - set(hard) == {"max_slope"} for _, m in candidates):
            binding.append("max_slope")
    return best, binding


def _tradeoff(search: _Search, candidates, lim: Limits, n: int = 10) -> tuple:
    """The smallest gap [px] that leaves no acne on every receiver up to each angle θ to the light.

    ``slope`` is the same receiver as a tilt from the ground away from the lowest sun (negative:
    towards it).  Over every candidate's split, count, size and filter, each bias alone at its
    minimum.
    """
    low = search.start.sun.elevation[0]
    top = steepest(search.start, lim.max_slope)
    bias_keys = {t.key for t in search.profile.tunable if t.role == "bias"}
    bases = {}
    for s, _ in candidates:
        bases.setdefault(tuple(sorted((k, repr(v)) for k, v in s.settings.items() if k not in bias_keys)), s)
    out = []
    for angle in np.linspace(0.0, top, n):
        slope = float(angle - (90.0 - low))
        sub = replace(lim, max_gap_px=math.inf, max_slope=slope)
        inner = _Search(search.start, sub, search.keep)
        best = math.inf
        for s in bases.values():
            for b in inner.biases(dict(s.settings)):
                got = inner.setup(b)
                if got is not None and not got[1].violations(sub):
                    best = min(best, _gap(got[1]))
        out.append({"angle": float(angle), "slope": slope, "gap_px": best})
    return tuple(out)
