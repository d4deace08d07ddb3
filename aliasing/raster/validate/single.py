"""One rasterizer validation of the analytic aliasing bounds, and its text/CSV/JSON formats.

:func:`validate` measures the perspective error of one scheme for one light direction on
dense, seeded probes (:func:`aliasing.raster.measure`) and compares its maxima with the
analytic bounds of :func:`aliasing.schemes.evaluate`; :func:`format_text` and
:func:`format_rows` write the results.  The grids of validations and the ``aliasing
validate`` command live in :mod:`aliasing.raster.validate` (which re-exports every public
name here); the method is described there.

Example
-------
>>> r = validate("P", 100, 60, "gamma:150", res=128, probes=8)
>>> r["passed"], r["maps"], bool(0.95 <= r["ratio_M_x"] <= 1 + r["tolerance"])
(True, 1, True)
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ... import _table as _tables
from ... import _validation as check
from ... import geometry, schemes, sweep
from ..scenes.camera import check_raster_frustum
from .measure import measure
from ..draw import map_set
from ..scenes.builtin import probes as probe_scene
from ...view import View

MIN_RES = 16
"""Smallest measurement resolution: probes need interior pixels with both neighbours."""
MAX_RES = 2048
"""Largest measurement resolution: the eye pass and the per-pixel fields (about 20 arrays of
R² floats) stay under ~1 GB."""
MAX_PROBES = 256
DEFAULT_RES = 384
DEFAULT_PROBES = 24
DEFAULT_REACH = 0.95
FORMATS = ("text", "json", "csv")


# --------------------------------------------------------------------------- input checks


def _whole(value: object, name: str, lo: int, hi: int, why: str = "") -> int:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer, float, np.floating)) or not float(value).is_integer():
        raise ValueError(f"{name} must be a whole number in [{lo}, {hi}]{why}, got {value!r}")
    v = int(value)
    if v < lo or v > hi:
        raise ValueError(f"{name} must be in [{lo}, {hi}]{why}, got {v}")
    return v


def _light(light: object) -> tuple[str, np.ndarray]:
    """One light direction: (label, vector (1, 3)); more than one → ValueError."""
    if isinstance(light, str):
        label = light.strip()
        lv = geometry.lights(label)
    else:
        try:
            lv = geometry.lights(check.as_float_array(light, "light"))  # complex, huge ints, ragged: ValueError
        except (TypeError, ValueError) as exc:
            raise ValueError(f"light must be a spec or a vector towards the light, got {light!r} ({exc})") from None
        label = "vector:" + ",".join(f"{x:.10g}" for x in lv.ravel())
    if lv.shape[0] != 1:
        raise ValueError(f"light must give exactly one direction, got {lv.shape[0]} from {light!r}; validate one direction at a time (for several, list gamma:DEG specs or gamma:LIST|RANGE)")
    return label, lv


def _check(scheme: str, f_over_n: float | View, fov: float | None, light: object, res: int, image_res: int | None, probes: int, reach: float, aspect: float = 1.0) -> dict:
    if not isinstance(scheme, str):
        raise ValueError(f"scheme must be a scheme name (e.g. Standard, P, ZP4+LogP), got {scheme!r}")
    sch = schemes.parse(scheme)
    if isinstance(f_over_n, View):
        view = f_over_n
        if view.shape != ():
            raise ValueError(f"the view must be one frustum (scalar near, far, fov), got shape {view.shape}")
        ratio = view.ratio
        if aspect != 1.0:
            raise ValueError("aspect is the View's: pass it in the View, not again")
    else:
        for name, value, what in (("f_over_n", f_over_n, "a depth ratio far/near > 1"), ("fov", fov, "a full field of view in degrees"),
                                  ("aspect", aspect, "the image's width/height > 0")):
            if value is not None and np.ndim(value) != 0:
                raise ValueError(f"{name} must be a single number ({what}), got an array of shape {np.shape(value)}")
        ratio = float(check.depth_ratio(f_over_n, "f_over_n"))
        if fov is None:
            raise ValueError("fov required (or a View in place of f_over_n)")
        view = View(1.0, ratio, fov, aspect)
    fv = view.fov
    check_raster_frustum(view.near, view.far, fv)
    label, lv = _light(light)
    if not view.square:  # before any work: face partitions and the θ-only warping rules have square closed forms only
        try:
            schemes.evaluate(sch.name, view, lv)
        except ValueError as exc:
            raise ValueError(f"scheme {sch.name}: {exc}") from None
    r = _whole(res, "res", MIN_RES, MAX_RES, " pixels per side (larger does not fit in memory)")
    ri = r if image_res is None else _whole(image_res, "image_res", 1, 1 << 20, " pixels per side")
    cells = _whole(probes, "probes", 2, min(MAX_PROBES, r // 4), f" probe cells per side (at most res/4 = {r // 4}, so that probes span pixels)")
    if np.ndim(reach) != 0:
        raise ValueError(f"reach must be a single number in [0, 1] (fraction of the bound), got an array of shape {np.shape(reach)}")
    reach = float(check.closed_range(reach, "reach", 0.0, 1.0))
    return dict(scheme=sch, f_over_n=ratio, fov=fv, view=view, light=label, lv=lv, res=r, image_res=ri, probes=cells, reach=reach)


# --------------------------------------------------------------------------- validation


def _scalar(values: np.ndarray) -> float | list[float]:
    vals = [float(v) for v in np.ravel(values)]
    return vals[0] if len(vals) == 1 else vals


def validate(scheme: str, f_over_n: float | View, fov: float | None = None, light: str | Sequence[float] | None = None, res: int | None = None, image_res: int | None = None, probes: int | None = None, *, aspect: float = 1.0, seed: int = 0, reach: float = DEFAULT_REACH,
             backend: str = "numpy", **options) -> dict:
    """Measure a scheme's perspective error on probes and compare it with the analytic bounds.

    Parameters
    ----------
    scheme : str
        Scheme name (Standard, P, LogP, a warping rule, each alone or after ``ZP<k>+``; or
        ``FPc+…``, ``FPcs+…``, whose per-map bounds are :func:`aliasing.faces.face_errors`).
    f_over_n : float
        Depth ratio far/near, > 1 (near = 1); or a :class:`~aliasing.View` in its place,
        followed by the light: ``validate(scheme, view, light, ...)``.
    fov : float
        FULL (vertical) field of view [deg], in (0, 180).
    aspect : float
        Image width/height, > 0 (default 1); the rows hold ``res`` pixels (see
        :class:`aliasing.View` and :func:`aliasing.raster.eye_pass`).  The result gains an
        ``aspect`` entry when it is not 1.
    light : str or array_like
        Exactly one light direction: ``overhead``, ``behind``, ``front``,
        ``gamma:DEG[@azimuth:DEG]`` or a vector towards the light.
    res : int
        Eye-pass (measurement) resolution [pixels per side], in [16, 2048] (default 384).
    image_res : int, optional
        Image resolution the critical shadow-map resolutions are given for (default ``res``).
    probes : int
        Probe grid cells per side, in [2, min(256, res/4)] (default 24).
    seed : int
        Seed of the probes' depth permutation: the same inputs give the same result.
    reach : float
        Fraction of the bound every map's measured maxima must reach to pass, in [0, 1].
    backend : {"numpy", "numba", "gl"}
        How the eye pass and the maps are drawn (:func:`aliasing.raster.validate.measure.measure`).
    **options
        Warping-rule options for :func:`aliasing.schemes.evaluate`.

    Returns
    -------
    dict
        ``scheme``, ``f_over_n``, ``fov``, ``light``, ``gamma`` [deg], ``res``, ``image_res``,
        ``probes``, ``seed``, ``maps`` (k); per map (a float when k = 1, else a list):
        ``M_x``, ``M_z``, ``S`` (analytic, unit resolutions), ``measured_M_x``,
        ``measured_M_z``, ``measured_S`` (maxima over the probes), ``ratio_M_x``,
        ``ratio_M_z``, ``ratio_S``, ``critical_res_s``, ``critical_res_t`` (analytic M·image_res);
        totals ``S_total``, ``measured_S_total``, ``ratio_S_total``, ``critical_area``
        (S_total·image_res² texels); ``max_ratio``, ``min_ratio`` (over maps, of the M_x and
        M_z ratios), ``tolerance``, ``reach``, ``within_bound``, ``reached``, ``passed``,
        ``pixels``, ``self_lit``; ``projection_min``, ``projection_median``,
        ``projection_max``: the projection factor cos ψ_e / cos ψ_l measured from the normals
        over the probe pixels (:func:`aliasing.raster.validate.measure.projection_factors`), about 1 by
        construction of the probes (Lloyd 2006 §3.3), so the measured error is perspective
        aliasing alone.

    Raises
    ------
    ValueError
        Unknown scheme, f/n ≤ 1, fov outside (0, 180), a light giving no or several
        directions, res outside [16, 2048], probes outside [2, min(256, res/4)], aspect ≤ 0
        or not finite, or aspect ≠ 1 with a scheme of a square view only (face partitions,
        the θ-only warping rules).

    Example
    -------
    >>> r = validate("ZP2+P", 50, 60, "gamma:60", res=128, probes=8)
    >>> r["maps"], r["passed"], len(r["ratio_M_x"])
    (2, True, 2)
    """
    if isinstance(f_over_n, View):  # the arguments after the View move up one place
        seq = [fov, light, res, image_res, probes]
        run = next((i for i, v in enumerate(seq) if v is None), len(seq))
        if run == len(seq):
            raise ValueError("with a View, pass the arguments that follow it (light, res, ...) once each, not fov")
        out: list = [None] * 4
        for j, value in enumerate(seq):
            i = j if j < run else j - 1
            if value is not None:
                if out[i] is not None:
                    raise ValueError("with a View, pass the arguments that follow it (light, res, ...) once each, not fov")
                out[i] = value
        fov, (light, res, image_res, probes) = None, out
    if light is None:
        raise ValueError("light required")
    res = DEFAULT_RES if res is None else res
    probes = DEFAULT_PROBES if probes is None else probes
    c = _check(scheme, f_over_n, fov, light, res, image_res, probes, reach, aspect)
    seed = _whole(seed, "seed", 0, 2**32 - 1)
    view = c["view"]
    lv = c["lv"]
    ms = map_set(view, lv, c["scheme"].name, **options)
    scene = probe_scene(view, lv, cells=c["probes"], seed=seed, splits=None if ms.faces else ms.edges)
    m = measure(view, lv, c["scheme"].name, resolution=c["res"], scene=scene, map_resolution=c["res"], backend=backend, **options)
    S = m.M_x * m.M_z
    measured_S = m.measured_x * m.measured_z
    ratios = np.concatenate([m.ratio_x, m.ratio_z])
    tol = float(m.tolerance)
    within = bool(np.all(np.isfinite(ratios)) and np.all(ratios <= 1.0 + tol))
    reached = bool(np.all(np.isfinite(ratios)) and np.all(ratios >= c["reach"]))
    gamma = float(np.degrees(np.arccos(np.clip(lv[0, 2], -1.0, 1.0))))
    ri = c["image_res"]
    return {
        "scheme": m.scheme,
        "f_over_n": c["f_over_n"],
        "fov": c["fov"],
        "light": c["light"],
        "gamma": round(gamma, 9),
        "res": c["res"],
        "image_res": ri,
        "probes": c["probes"],
        "seed": seed,
        "maps": int(m.M_x.size),
        "M_x": _scalar(m.M_x),
        "M_z": _scalar(m.M_z),
        "S": _scalar(S),
        "measured_M_x": _scalar(m.measured_x),
        "measured_M_z": _scalar(m.measured_z),
        "measured_S": _scalar(measured_S),
        "ratio_M_x": _scalar(m.ratio_x),
        "ratio_M_z": _scalar(m.ratio_z),
        "ratio_S": _scalar(measured_S / S),
        "critical_res_s": _scalar(m.M_x * ri),
        "critical_res_t": _scalar(m.M_z * ri),
        "S_total": float(S.sum()),
        "measured_S_total": float(measured_S.sum()),
        "ratio_S_total": float(measured_S.sum() / S.sum()),
        "critical_area": float(S.sum() * ri**2),
        "max_ratio": float(np.max(ratios)),
        "min_ratio": float(np.min(ratios)),
        "tolerance": tol,
        "reach": c["reach"],
        "within_bound": within,
        "reached": reached,
        "passed": within and reached,
        "pixels": int(m.pixels),
        "self_lit": float(m.self_lit),
        "projection_min": float(np.nanmin(m.projection)),
        "projection_median": float(np.nanmedian(m.projection)),
        "projection_max": float(np.nanmax(m.projection)),
    } | ({} if view.square else {"aspect": float(view.aspect)})


# --------------------------------------------------------------------------- output


TEXT_KEYS = ("M_x", "M_z", "S")


def _fmt(v: object) -> str:
    if isinstance(v, list):
        return ", ".join(_fmt(x) for x in v)
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)


def format_text(r: dict) -> str:
    """One validation as a short plain-text report."""
    lines = [
        f"scheme {r['scheme']}  f/n {r['f_over_n']:g}  fov {r['fov']:g} deg{'  aspect %g' % r['aspect'] if 'aspect' in r else ''}  light {r['light']} (gamma {r['gamma']:.6g} deg)  maps {r['maps']}",
        f"measurement: res {r['res']} px, {r['probes']}x{r['probes']} probes, seed {r['seed']}, {r['pixels']} pixels, self-lit {r['self_lit']:.3f}",
        f"projection factor cos(psi_e)/cos(psi_l) on the probes: min {r['projection_min']:.4f}, median {r['projection_median']:.4f}, "
        f"max {r['projection_max']:.4f} (about 1 by construction: perspective aliasing alone)",
        f"{'':10s}{'map':>4s}{'analytic':>14s}{'measured':>14s}{'ratio':>12s}",
    ]
    k = r["maps"]
    for key in TEXT_KEYS:
        cols = [r[key], r["measured_" + key], r["ratio_" + key]]
        cols = [c if isinstance(c, list) else [c] for c in cols]
        for i in range(k):
            lines.append(f"{key if i == 0 else '':10s}{i:>4d}{cols[0][i]:>14.6g}{cols[1][i]:>14.6g}{cols[2][i]:>12.6f}")
    if k > 1:
        lines.append(f"{'S total':10s}{'':>4s}{r['S_total']:>14.6g}{r['measured_S_total']:>14.6g}{r['ratio_S_total']:>12.6f}")
    lines.append(f"critical resolution for a {r['image_res']}^2 image: {_fmt(r['critical_res_s'])} x {_fmt(r['critical_res_t'])} texels per map (total area {r['critical_area']:.6g} texels)")
    verdict = "PASS" if r["passed"] else "FAIL"
    lines.append(
        f"{verdict}: max ratio {r['max_ratio']:.6f} <= 1 + {r['tolerance']:g}: {'yes' if r['within_bound'] else 'NO'}; "
        f"min ratio {r['min_ratio']:.6f} >= {r['reach']:g}: {'yes' if r['reached'] else 'NO'}"
    )
    return "\n".join(lines) + "\n"


def _table(rows: list[dict]) -> str:
    keys = ["scheme", "f_over_n", "fov", "light", "maps", "ratio_M_x", "ratio_M_z", "ratio_S", "max_ratio", "min_ratio", "projection_min", "projection_max", "passed"]
    if any("aspect" in r for r in rows):  # a non-square view's column, after the field of view
        keys.insert(keys.index("fov") + 1, "aspect")
    return _tables.aligned([keys] + [[_fmt(r.get(k, 1.0)).replace(", ", ";") for k in keys] for r in rows])


def format_rows(rows: list[dict], fmt: str = "csv") -> str:
    """Validation rows as ``csv`` (one row per map when a row has per-map lists), ``json`` or a ``text`` table."""
    kind = check.choice(fmt, "format", FORMATS)
    if kind == "text":
        return _table(rows)
    return sweep.format_rows(rows, kind)
