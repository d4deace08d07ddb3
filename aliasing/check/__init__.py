"""``check``: one report per cascade of an engine's setup, in the engine's own terms.

For a :class:`aliasing.setups.Setup` (an engine at a release, its settings, a camera with its
image height, a sun band), :func:`check` evaluates the pipeline the engine builds
(``Setup.pipeline`` of :class:`aliasing.setups.Setup`) analytically, per cascade:

``near``, ``far``
    The cascade's eye depths [world units] (overlap included).
``texel``
    [s, t]: the world size of one texel of the cascade's map [world units], from the engine's
    own fit and snap (:func:`aliasing.engines.pipeline.texels`), the largest over the sun band
    (square stabilized fits do not depend on the sun).
``error_max``, ``error_median``
    The aliasing error [px/texel] (:data:`aliasing.check.units.ERROR_NAME`, :data:`aliasing.check.units.ERROR_UNIT`): pixels of the camera's
    image per shadow-map texel, a texel's width over a pixel's width at the cascade's first depth u, max(M_x, M_z)·H/R with M of
    :func:`aliasing.engines.stable.evaluate` (Lloyd et al. 2006, eq. 2 with a uniform map), H the
    image height [pixels] and R the map's texels per side; the worst and the median over the
    sun band.  Above 1 a texel spans more than a pixel there (blocky shadows).
``stable_cost``
    ``error_max`` over that of the papers' tight fit (no snap) of the same cascades: what the
    engine's stabilized fit costs in texel size (1 for a tight fit).
``needed``
    For each bias setting of the engine's rule (:class:`aliasing.setups.BiasRule`), the value,
    in the engine's own units, that leaves every sampled receiver (below) free of acne, the
    other settings kept (:meth:`~aliasing.setups.BiasRule.minimal` with the need of
    :func:`aliasing.bias.plane_bias` for the engine's filter width).  **Sign convention:** for a
    setting whose scale is positive (normal offsets, Babylon's ``bias``) the value is a lower
    bound (set it at or above); for a setting with a negative scale (three.js's ``shadowBias``
    and ``shadow.bias``, added to the receiver's normalized depth: negative values lift it
    towards the light) the value is an upper bound (set it at or below).  ``None`` where the
    setting cannot remove the acne.
``acne``
    The fraction of the sampled receivers that acne at the given settings (0 when the engine
    draws back faces into the map: closed and one-sided receivers then compare against their
    far side and do not self-shadow).
``gap_px``
    How far the bias moves a shadow's edge on the ground, the worst sun of the band
    (:func:`aliasing.bias.edge_shift` of the rule's whole depth bias for the ground
    receiver), in pixels at the cascade's middle depth: the lit gap at the foot of a vertical
    caster for the depth terms (peter-panning), the shortening of the shadow's far end for a
    normal offset (o/tan α).
``seam_step``
    The texel's growth into the next cascade (:func:`aliasing.bias.filtering.seam_step`; None for
    the last).
``footprint_px``
    The filter's width (its taps, :class:`aliasing.setups.Filter`) in pixels at the middle depth
    (:func:`aliasing.bias.filtering.pcf_footprint`).
``shimmer_px``
    How far shadow edges jitter per frame under a walk [pixels at the middle depth]: 0 when the
    pipeline is stable (snapped, rotation-invariant fits).  Otherwise the map's grid slides with
    the camera by the walk's step projected on the light's image plane, δ per axis; a point's
    texel centre then moves by Δ with E|Δ| = 2u(1 − u)·w per axis (u = δ/w mod 1), the
    displacement that :mod:`aliasing.temporal.predict` turns into flips with a scene's edge
    density (not modelled here: no scene).
``memory``
    Bytes of the cascade's depth map (the table and the CSV: ``memory [MiB]``).

Units
-----
Every number has a unit (:mod:`aliasing.check.units`): the table's and the CSV's headers carry it in
brackets (``texel_s [m]``, lengths in the engine's world unit; ``needed_<key> [the setting's unit]``)
and show a result without a finite bound as ``unbounded``; the JSON keeps its keys, adds ``units``
(the same units by key, ``needed`` by setting) and writes such a result as null.

The receivers sampled
---------------------
Planar receivers tilted away from the sun by each slope σ of ``receivers`` (default 0: the
ground) under each of ``samples`` sun elevations e over the band: the angle between a
receiver's normal and the light is θ = 90° − e + σ.  Receivers with θ above
:data:`MAX_ANGLE` face the light too obliquely to be lit (N·L < 0.09) and are left out.  Their
depth changes along the map's vertical axis t (a light camera whose up is the world's up, as
three.js's ``lookAt`` gives), so the need is (k/2)·w·tan θ for a k-texel filter and the texel w;
``needed`` takes the largest texel side.

The check is analytic (no rasterizer): a few milliseconds for four cascades and seven suns.
With ``scene`` the receivers are instead the pixels of an eye pass over a scene
(:mod:`aliasing.check.scene`: the built-in boxes or city, or a file), each with its own normal,
depth and cascade: acne is counted in pixels, by receiver kind (a few seconds at 256²).

Example
-------
>>> from aliasing import setups
>>> s = setups.build("threejs", {"cascades": 4}, "near=0.1,far=500,fov=50,aspect=16:9,height=1080", "15..60")
>>> r = check(s)
>>> len(r.cascades), sorted(r.cascades[0]["needed"])
(4, ['shadow.normalBias', 'shadowBias'])
>>> r.cascades[3]["acne"]          # three.js casts back faces: closed receivers do not acne
0.0
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .. import _table as _tables
from .. import _validation as check_
from ..bias import edge_shift, plane_bias
from ..bias.filtering import blend_band, pcf_footprint, seam_step
from ..engines import pipeline as _pipeline
from ..engines import stable
from ..raster.draw.lookup import PCF_MAX
from ..setups import Setup
from .scene import scene_pixels as _scene_pixels
from .seen import seen_block, seen_text
from .units import ERROR_NAME, ERROR_UNIT, ERROR_WORDS, header, units

__all__ = ["ERROR_NAME", "ERROR_UNIT", "ERROR_WORDS", "MAX_ANGLE", "Report", "check", "header", "units"]

#: The largest angle between a receiver's normal and the light that is sampled [deg] (N·L = cos 85° ≈ 0.087).
MAX_ANGLE = 85.0
#: A setting meets its need within this relative tolerance (a value fed back from ``needed``).
_TOL = 1e-9
#: Columns of the tidy table (:meth:`Report.to_rows`).
COLUMNS = ("cascade", "near", "far", "texel_s", "texel_t", "error_max", "error_median", "stable_cost", "acne", "gap_px",
           "seam_step", "blend_start", "blend_end", "footprint_px", "shimmer_px", "memory_mib")


def _receivers(receivers: ArrayLike | None) -> np.ndarray:
    if receivers is None:
        return np.array([0.0])
    arr = check_.as_float_array(receivers, "receivers").ravel()
    if arr.size == 0 or not np.isfinite(arr).all() or ((arr < 0) | (arr >= 90)).any():
        raise ValueError(f"receivers must be slopes in [0, 90) degrees (0: the ground), tilted away from the sun, got {check_._show(arr)}")
    return arr


def _taps(setup: Setup) -> int:
    f = setup.pipeline.filter
    return int(min(max(1, int(f.taps)), PCF_MAX))


def _safe(value: float, upper: bool) -> float:
    """``value`` rounded to 2 significant digits on the safe side (down for an upper bound)."""
    if value == 0 or not math.isfinite(value):
        return value
    e = math.floor(math.log10(abs(value))) - 1
    scaled = value / 10**e
    return (math.floor(scaled) if upper else math.ceil(scaled)) * 10**e


def _fmt(value: float) -> str:
    return f"{value:.2g}"


@dataclass(frozen=True)
class Report:
    """What :func:`check` found: per cascade rows, verdict lines, and the setup they came from.

    ``cascades`` holds one dict per cascade (the module docstring's fields; ``texel`` as [s, t]),
    ``verdicts`` the lines, ``sample`` the receivers and suns evaluated, ``seen`` the wrong-pixel
    measure (:mod:`aliasing.check.seen`) when asked for.

    Example
    -------
    >>> from aliasing import setups
    >>> r = check(setups.build("threejs", {"cascades": 2}, sun=30))
    >>> sorted(r.to_dict())
    ['cascades', 'engine', 'release', 'settings', 'units', 'verdicts']
    >>> [row["cascade"] for row in r.to_rows()], r.to_csv().splitlines()[0].split(",")[:6]
    ([0, 1], ['cascade', 'near [world units]', 'far [world units]', 'texel_s [world units]', 'texel_t [world units]', 'error_max [px/texel]'])
    """

    setup: Setup
    cascades: tuple
    verdicts: tuple
    sample: dict = field(default_factory=dict)
    seen: dict | None = None

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract: ``engine``, ``release``, ``settings`` (every key), ``cascades``, ``units`` (of the
        cascades' fields, :func:`units`), ``verdicts`` (and ``seen`` when measured)."""
        u = units(self.setup)
        return {
            "engine": self.setup.engine,
            "release": self.setup.release,
            "settings": dict(self.setup.settings),
            "cascades": [_json(c) for c in self.cascades],
            "units": {k: u[k] for k in {k for c in self.cascades for k in c}},
            "verdicts": list(self.verdicts),
            **({"seen": self.seen} if self.seen is not None else {}),
        }

    def to_rows(self) -> list[dict]:
        """A tidy table: one row per cascade, flat columns (:data:`COLUMNS`), then ``needed_<key>`` per bias setting;
        the units of the keys are :func:`units` (``memory_mib``: MiB)."""
        rows = []
        for c in self.cascades:
            band = c["blend"] or [None, None]
            row = {"cascade": c["cascade"], "near": c["near"], "far": c["far"], "texel_s": c["texel"][0], "texel_t": c["texel"][1],
                   "blend_start": band[0], "blend_end": band[1], "memory_mib": c["memory"] / 2**20,
                   **{k: c[k] for k in COLUMNS[5:-1] if not k.startswith("blend")}}
            row = {k: row[k] for k in COLUMNS} | {k: c[k] for k in ("acne_px", "receiver_px") if k in c}
            row.update({f"needed_{k}": v for k, v in c["needed"].items()})
            rows.append(row)
        return rows

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=1) + "\n"

    def labelled(self) -> list[dict]:
        """:meth:`to_rows` with a unit in each header (``texel_s [m]``) and ``unbounded`` for an infinite value."""
        u = units(self.setup)
        return _tables.labelled(self.to_rows(), {k: header(k, u[k]) for k in u if isinstance(u[k], str)})

    def to_csv(self) -> str:
        return _tables.csv_text(self.labelled())

    def text(self) -> str:
        """An aligned table, then the verdicts."""
        s = self.setup
        unit = {st.key: st.unit for st in s.profile.settings}
        changed = ", ".join(f"{k}={v}" + (f" [{unit[k]}]" if unit.get(k) else "") for k, v in s.changed().items()) or "none"
        head = (f"{s.profile.title} {s.release}: camera {s.camera.spec()} (near, far [{s.profile.length_unit}], fov [deg], "
                f"{s.camera.width}x{s.camera.height} px), sun {s.sun.spec()} [deg]; changed: {changed}\n")
        return head + _tables.table(self.labelled()) + "".join(f"- {v}\n" for v in self.verdicts) + ("" if self.seen is None else seen_text(self.seen))

    def __str__(self) -> str:
        return self.text()


def _json(c: dict) -> dict:
    def clean(v: Any) -> Any:
        if isinstance(v, float) and not math.isfinite(v):
            return None
        if isinstance(v, dict):
            return {k: clean(x) for k, x in v.items()}
        if isinstance(v, list):
            return [clean(x) for x in v]
        return v

    return clean(dict(c))


def check(setup: Setup, *, receivers: ArrayLike | None = None, scene: object = None, eye: ArrayLike | str | None = None,
          target: ArrayLike | str | None = None, pixels: int = 256, walk: float = 0.05, samples: int = 7, wrong: bool = False) -> Report:
    """The per-cascade report of an engine's setup (module docstring).

    Parameters
    ----------
    setup : Setup
        The engine, its settings, the camera and the sun (:func:`aliasing.setups.build`).
    receivers : array_like, optional
        Slopes of the sampled planar receivers, tilted away from the sun [deg] in [0, 90)
        (default: the ground alone).
    scene : {"boxes", "city"}, str, path or array_like, optional
        A scene whose visible pixels are the receivers instead (:mod:`aliasing.check.scene`):
        ``acne`` is then the fraction of the pixels facing the sun in each cascade that acne
        over the band, with ``acne_px`` (at the worst sun) and ``receiver_px`` per cascade.
    eye, target : array_like or "X,Y,Z", optional
        The camera of a city, file or triangle scene [world units].
    pixels : int
        The eye pass's pixels per side for ``scene``, 16 to 1024 (default 256).
    walk : float
        The camera's step per frame along its view direction [world units], > 0 (default
        0.05: 3 m/s at 60 frames per second), for ``shimmer_px``.
    samples : int
        Sun elevations over the band, 1 to 361 (default 7; one for a single sun).
    wrong : bool
        Also predict what the user sees wrong per cascade (``Report.seen``, :mod:`aliasing.check.seen`):
        the engine's frame predicted without a browser, one to a few seconds (default False).

    Returns
    -------
    Report

    Raises
    ------
    ValueError
        Naming the parameter and what it takes.

    Example
    -------
    >>> from aliasing import setups
    >>> s = setups.build("threejs", {"cascades": 4, "material.shadowSide": "FrontSide"}, sun="15..60")
    >>> r = check(s)
    >>> r.cascades[3]["acne"] > 0, "shadowBias" in r.verdicts[0]
    (True, True)
    >>> fixed = s.with_settings(**{"shadow.normalBias": r.cascades[3]["needed"]["shadow.normalBias"]})
    >>> check(fixed).cascades[3]["acne"]
    0.0
    """
    if not isinstance(setup, Setup):
        raise ValueError(f"setup must be an aliasing.setups.Setup (aliasing.setups.build(...)), got {type(setup).__name__}")
    if scene is not None and receivers is not None:
        raise ValueError("give either receivers (slopes of planar receivers) or scene (a scene's own receivers), not both")
    slopes = _receivers(receivers)
    step = check_.scalar(walk, "walk")
    if not (math.isfinite(step) and step > 0):
        raise ValueError(f"walk must be a finite step per frame > 0 [world units], got {walk!r}")
    n = check_.whole(samples, "samples", 1, 361, " (sun elevations over the band)")
    if not isinstance(wrong, (bool, np.bool_)):
        raise ValueError(f"wrong must be True or False, got {wrong!r}")
    pl, cam, sun, profile = setup.pipeline, setup.camera, setup.sun, setup.profile
    elev = sun.elevations(n)
    lv = sun.direction(elev)  # (E, 3) eye-space vectors towards the sun
    seen = None
    if scene is not None:
        seen = _scene_pixels(setup, scene, eye, target, pixels)
        lv = seen.light(elev, sun.azimuth)
    tex = _pipeline.texels(pl, cam, lv)  # (E, K, 2)
    K, H, R = pl.k, cam.height, float(pl.resolution)
    t = float(cam.view.tan_theta)
    near_i, far_i = np.asarray(pl.near_i), np.asarray(pl.far_i)
    u = near_i if pl.fit != "fixed" else np.array([cam.near])
    if pl.fit == "fixed":
        err = tex.max(axis=-1) * H / (2 * t * u)  # a texel over a pixel at the near plane
        cost = np.ones(K)
    else:
        res = _pipeline.result(pl, cam, lv)
        err = np.maximum(res.M_x, res.M_z) * H / R  # eq. (2): pixels per texel of an H-row image
        tight = stable.evaluate((near_i, far_i), cam.near, float(far_i.max()), cam.fov, lv, aspect=cam.aspect, resolution=R)
        cost = err.max(axis=0) / (np.maximum(tight.M_x, tight.M_z) * H / R).max(axis=0)
    w = tex.max(axis=-1)  # (E, K) the largest texel side
    ext = _pipeline.extents(pl, cam, lv) if pl.bias.needs_extent else None  # (E, K) each map's depth range along the light
    taps = _taps(setup)
    lookup = f"pcf{taps}"
    rule = pl.bias
    back = rule.faces == "back"
    if seen is None:  # the sample: slopes × elevations, θ = 90 − e + σ, the depth changing along the map's t (φ = 90°)
        theta = 90.0 - elev[None, :] + slopes[:, None]  # (S, E)
        sun_i = np.broadcast_to(np.arange(len(elev))[None, :], theta.shape)
        phi = np.full(theta.shape, 90.0)
        member = np.ones((K,) + theta.shape, bool)
    else:  # the scene's visible pixels under each sun: θ from their normals, φ in the map's axes, the cascade by eye depth
        theta, phi = seen.angles(lv)  # (E, P)
        sun_i = np.broadcast_to(np.arange(len(elev))[:, None], theta.shape)
        member = seen.cascades(near_i, far_i)[:, None, :] & np.ones(theta.shape, bool)  # (K, E, P)
    valid = theta <= MAX_ANGLE
    th = np.where(valid, theta, 0.0)
    known = {st.key for st in profile.settings}
    keys = [term.key for term in rule.terms if term.key in known]
    mid = 0.5 * (near_i + far_i)
    pixel = 2 * mid * t / H
    lo_sun = float(elev.min())
    cascades, verdicts = [], []
    unreachable: dict[int, list[str]] = {}
    bands = list(pl.bands) + [None] * (K - len(pl.bands))
    if back:
        verdicts.append(f"{profile.title} draws back faces into the map: closed and one-sided receivers do not self-shadow (acne 0); "
                        "'needed' holds where front faces cast (thin or two-sided receivers)")
    for k in range(K):
        wk = w[sun_i, k]  # the texel under each sample's sun
        dk = None if ext is None else ext[sun_i, k]
        need = np.asarray(plane_bias(wk, th, phi, lookup).depth)
        have = np.asarray(rule.depth(wk, th, phi, dk))
        inside = valid & member[k]
        short = inside & (have < need * (1 - _TOL) - 1e-300)
        acne = 0.0 if back else float(short.sum() / max(1, inside.sum()))
        needed: dict[str, float | None] = {}
        for key in keys:
            term = rule.term(key)
            m = np.asarray(rule.minimal(key, need, wk, th, phi, dk))[inside]
            upper = _upper(rule, key)
            if m.size == 0:
                needed[key] = term.value
                continue
            v = float(m.min()) if upper else float(m.max())
            v, limit = _accepted(profile.setting(key), v, upper)
            needed[key] = v
            if limit:
                unreachable.setdefault(k, []).append(limit)
        gap = float(np.max(edge_shift(rule, w[:, k], elev, None if ext is None else ext[:, k]))) / pixel[k]  # each sun, its texel
        shimmer = 0.0 if pl.stable else _shimmer(lv, w[:, k], step) / pixel[k]
        row = {
            "cascade": k, "near": float(near_i[k]), "far": float(far_i[k]),
            "texel": [float(tex[:, k, 0].max()), float(tex[:, k, 1].max())],
            "error_max": float(err[:, k].max()), "error_median": float(np.median(err[:, k])), "stable_cost": float(cost[k]),
            "needed": needed, "acne": acne, "gap_px": gap,
            **({} if seen is None else {"acne_px": 0 if back else int(short.sum(axis=-1).max()),
                                        "receiver_px": int(inside.sum(axis=-1).max())}),
            "seam_step": float(seam_step(w[:, k].max(), w[:, k + 1].max())) if k + 1 < K else None,
            "blend": None if k + 1 >= K or bands[k] is None else [float(bands[k][0]), float(bands[k][1])],
            "footprint_px": float(pcf_footprint(taps, float(w[:, k].max()), pixel[k])),
            "shimmer_px": float(shimmer), "memory": int(pl.memory // K),
        }
        cascades.append(row)
        if short.any() and not back:
            verdicts.append(_acne_verdict(k, short, slopes, elev, needed, rule, acne) if seen is None else
                            seen.verdict(k, short, elev, _fixes(needed, rule), acne))
        for limit in unreachable.get(k, []):
            verdicts.append(f"cascade {k}: {limit}")
        if not math.isfinite(gap):
            verdicts.append(f"cascade {k}: shadow edges on the ground move without bound at the lowest sun, {lo_sun:g}°: the bias "
                            f"({', '.join(t_.key for t_ in rule.terms)}) is beyond what the map's depth can hold")
        elif gap >= 1.0:
            verdicts.append(f"cascade {k}: shadow edges on the ground move by {gap:.1f} px at the lowest sun, {lo_sun:g}° (detached at contacts, "
                            f"shortened by normal offsets: {', '.join(t_.key for t_ in rule.terms)})")
        if k + 1 < K:
            seam = _seam_verdict(k, row, 2 * t / H, profile.length_unit)  # a pixel's world width per unit of eye depth
            if seam:
                verdicts.append(seam)
    verdicts.append(f"{ERROR_NAME} at each cascade's near end [{ERROR_UNIT}]: " + ", ".join(f"{c['error_max']:.3g}" for c in cascades)
                    + f" ({ERROR_WORDS}: above 1 a texel spans more than a pixel; the first cascade's near end is the camera's near plane)")
    if not pl.stable:
        verdicts.append(f"the fit is not stabilized: shadow edges shimmer up to {max(c['shimmer_px'] for c in cascades):.2g} px per frame "
                        f"under a {step:g} m/frame walk")
    if not back and not any(c["acne"] for c in cascades):
        verdicts.append("no acne on the sampled receivers at these settings" if seen is None else
                        f"no acne on the scene's {seen.source} receivers facing the sun at these settings")
    verdicts += [f"not modelled: {note}" for note in pl.notes]
    sample = {"elevations": elev.tolist(), "max_angle": MAX_ANGLE, "lookup": lookup, "walk": step}
    sample |= {"slopes": slopes.tolist()} if seen is None else {"scene": seen.source, "pixels": int(len(seen.position))}
    return Report(setup, tuple(cascades), tuple(verdicts), sample, seen_block(setup, scene, eye, target) if wrong else None)


def _acne_verdict(k: int, short: np.ndarray, slopes: np.ndarray, elev: np.ndarray, needed: dict, rule, acne: float) -> str:
    parts = []
    for i, s in enumerate(slopes):
        if short[i].any():
            where = "ground" if s == 0 else f"{s:g}° slopes"
            hit = elev[short[i]]
            clean = elev[~short[i] & (elev > hit.max())]
            when = (f"below {clean.min():g}° sun" if clean.size else f"at the sun of {elev.min():g}°" if elev.min() == elev.max() else
                    f"at every sun of {elev.min():g}–{elev.max():g}°" if hit.size == elev.size else f"at suns of {hit.min():g}–{hit.max():g}°")
            parts.append(f"{where} {when}")
    return f"cascade {k} acnes on {'; '.join(parts)} ({acne:.0%} of the sampled receivers): " + _fixes(needed, rule)


def _fixes(needed: dict, rule) -> str:
    fixes = []
    for key, v in needed.items():
        if v is None:
            continue
        upper = _upper(rule, key)
        fixes.append(f"{key} {'≤' if upper else '≥'} {_fmt(_safe(v, upper))}")
    return " or ".join(fixes) or "no single bias setting removes it within the engine's limits"


def _upper(rule, key: str) -> bool:
    """Whether ``needed`` of ``key`` is an upper bound (its scale is negative: three.js's ``shadowBias``, ``shadow.bias``)."""
    return rule.term(key).scale < 0


def _accepted(setting, value: float, upper: bool) -> tuple[float | None, str | None]:
    """``value`` against what the engine accepts (``accepts`` and its silent ``clamp``): (the value to report, a verdict or None).

    A lower bound below the accepted low (an upper bound above the accepted high) is met by every
    accepted value: the accepted bound is reported.  One beyond the other end cannot be reached
    by this setting alone: None, and a line naming the limit.
    """
    if not math.isfinite(value):
        return None, None
    lo, hi = setting.accepts if setting.kind in ("float", "int") else (None, None)
    if setting.clamp is not None:
        clo, chi = setting.clamp
        lo = clo if lo is None else lo if clo is None else max(lo, clo)
        hi = chi if hi is None else hi if chi is None else min(hi, chi)
    if setting.kind == "int":
        value = float(math.floor(value) if upper else math.ceil(value))
    if not upper:
        if lo is not None and value <= lo:
            return float(lo), None
        if hi is not None and value > hi:
            return None, (f"{setting.key} would need ≥ {_fmt(_safe(value, False))}, beyond the engine's limit {hi:g} "
                          f"(it accepts {setting.allowed()}): this setting alone cannot remove the acne")
        return value, None
    if hi is not None and value >= hi:
        return float(hi), None
    if lo is not None and value < lo:
        return None, (f"{setting.key} would need ≤ {_fmt(_safe(value, True))}, beyond the engine's limit {lo:g} "
                      f"(it accepts {setting.allowed()}): this setting alone cannot remove the acne")
    return value, None


def _seam_verdict(k: int, row: dict, pixel: float, world: str = "world units") -> str | None:
    """The seam between cascade k and k + 1: the texel's step and whether the blend band hides it.

    The band's width in pixels is counted at the boundary's depth for a receiver facing the
    camera (its eye-depth width over a pixel's world width there); receivers seen at a grazing
    angle (the ground from eye height) span fewer pixels.  The band hides the step where it
    spans the ramp :func:`aliasing.bias.filtering.blend_band` asks for (the blur width changing by
    at most 10 % per pixel).
    """
    step = row["seam_step"]
    if step is None or step < 1.05:
        return None
    need = float(blend_band(step))
    end = row["far"]
    if row["blend"] is None:
        return (f"seam {k}|{k + 1} near depth {end:.3g} {world}: the texel grows ×{step:.2g} with no blend band: the step shows as a line "
                f"(a band of ≥ {need:.0f} px would hide it)")
    a, b = row["blend"]
    px = (b - a) / (pixel * 0.5 * (a + b))
    if px >= need:
        return (f"seam {k}|{k + 1}: the texel grows ×{step:.2g} inside the blend band {a:.3g}–{b:.3g} {world} (up to {px:.0f} px wide, "
                f"{need:.0f} px needed): the band hides the step where receivers face the camera")
    return (f"seam {k}|{k + 1}: the texel grows ×{step:.2g}; the blend band {a:.3g}–{b:.3g} {world} spans at most {px:.0f} px, "
            f"{need:.0f} px are needed to hide the step")


def _shimmer(lv: np.ndarray, w: np.ndarray, step: float) -> float:
    """E|Δ| [world units] of a texel centre per frame of a walk along the view, the worst over the sun band."""
    d = np.array([0.0, 0.0, 1.0])
    up = np.array([0.0, 1.0, 0.0])
    out = 0.0
    for l, wi in zip(lv, w):
        s = np.cross(up, l)
        s = s / np.linalg.norm(s) if np.linalg.norm(s) > 1e-12 else np.array([1.0, 0.0, 0.0])
        tt = np.cross(l, s)
        e = 0.0
        for axis in (s, tt):
            frac = np.mod(abs(float(d @ axis)) * step / wi, 1.0)
            e += (2 * frac * (1 - frac) * wi) ** 2
        out = max(out, math.sqrt(e))
    return out
