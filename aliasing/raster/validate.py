"""Validation of the analytic aliasing bounds by the rasterizer: ``aliasing validate``.

:func:`validate` measures the perspective error of one scheme for one light direction on
dense, seeded probes (:func:`aliasing.raster.measure`) and compares its maxima with the
analytic bounds of :func:`aliasing.schemes.evaluate`:

* the analytic M_x, M_z (unit resolutions) and S = M_x·M_z, the critical shadow-map area in
  image areas, per map (``ZP<k>+…`` schemes have k maps, each compared with its own bound);
* the measured maxima of m_x, m_z over the probe pixels shaded from each map, and their
  product, the measured S;
* the ratios measured/analytic.  The validation **passes** when no ratio exceeds
  1 + tolerance (the stated central-difference discretisation tolerance of
  :func:`~aliasing.raster.measure`) and every map's M_x and M_z ratios reach ``reach``
  (default 0.95): the bound holds and is attained.  The probes sit inside the frustum, so
  how close the maxima come to the bound (attained at the frustum's vertices) depends on the
  probe density: at the defaults (res 384, 24 probes per side) every tested case reaches 0.95;
  at res 192 with 12 probes a few (PSM/LiSPSM at γ = 120°, fov 170°) reach only about 0.90.

:func:`validate_rows` runs the product of schemes × f/n × fov × lights (one row per
combination, in that order), optionally in ``jobs`` local processes with output identical to
``jobs=1``; :func:`add_validate_parser` adds the ``validate`` subcommand (single case, or the
grid with ``--grid``) to the ``aliasing`` command.

Resolutions: ``res`` is the eye-pass resolution R_i of the measurement (pixels per side;
finite differences between neighbouring pixels, spacing 1/R_i); it also sets the resolution of
the shadow map rasterized for the ``self_lit`` check.  ``image_res`` (default ``res``) is the
image resolution the critical shadow-map resolutions are given for: R_s = M_x·image_res,
R_t = M_z·image_res texels per side, and the critical area S·image_res² texels.  Ratios do not
depend on ``image_res``.

Example
-------
>>> r = validate("P", 100, 60, "gamma:150", res=128, probes=8)
>>> r["passed"], r["maps"], bool(0.95 <= r["ratio_M_x"] <= 1 + r["tolerance"])
(True, 1, True)
"""

from __future__ import annotations

import argparse
import itertools
import json
import re
import sys
from collections.abc import Iterable, Sequence

import numpy as np

from .. import _validation as check
from .. import geometry, schemes
from .measure import measure
from .rasterize import light_maps
from .scenes import probes as probe_scene

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
            lv = geometry.lights(np.asarray(light, dtype=float))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"light must be a spec or a vector towards the light, got {light!r} ({exc})") from None
        label = "vector:" + ",".join(f"{x:.10g}" for x in lv.ravel())
    if lv.shape[0] != 1:
        raise ValueError(f"light must give exactly one direction, got {lv.shape[0]} from {light!r}; validate one direction at a time (for several, list gamma:DEG specs or gamma:LIST|RANGE)")
    return label, lv


def _check(scheme: str, f_over_n: float, fov: float, light: object, res: int, image_res: int | None, probes: int, reach: float) -> dict:
    if not isinstance(scheme, str):
        raise ValueError(f"scheme must be a scheme name (e.g. Standard, P, ZP4+LogP), got {scheme!r}")
    sch = schemes.parse(scheme)
    ratio = float(check.depth_ratio(f_over_n, "f_over_n"))
    fv = float(check.fov(fov))
    label, lv = _light(light)
    r = _whole(res, "res", MIN_RES, MAX_RES, " pixels per side (larger does not fit in memory)")
    ri = r if image_res is None else _whole(image_res, "image_res", 1, 1 << 20, " pixels per side")
    cells = _whole(probes, "probes", 2, min(MAX_PROBES, r // 4), f" probe cells per side (at most res/4 = {r // 4}, so that probes span pixels)")
    reach = float(check.closed_range(reach, "reach", 0.0, 1.0))
    return dict(scheme=sch, f_over_n=ratio, fov=fv, light=label, lv=lv, res=r, image_res=ri, probes=cells, reach=reach)


# --------------------------------------------------------------------------- validation


def _scalar(values: np.ndarray) -> float | list[float]:
    vals = [float(v) for v in np.ravel(values)]
    return vals[0] if len(vals) == 1 else vals


def validate(scheme: str, f_over_n: float, fov: float, light: str | Sequence[float], res: int = DEFAULT_RES, image_res: int | None = None, probes: int = DEFAULT_PROBES, *, seed: int = 0, reach: float = DEFAULT_REACH, **options) -> dict:
    """Measure a scheme's perspective error on probes and compare it with the analytic bounds.

    Parameters
    ----------
    scheme : str
        Scheme name (Standard, P, LogP, a warping rule, each alone or after ``ZP<k>+``).
    f_over_n : float
        Depth ratio far/near, > 1 (near = 1).
    fov : float
        FULL field of view [deg], in (0, 180).
    light : str or array_like
        Exactly one light direction: ``overhead``, ``behind``, ``front``,
        ``gamma:DEG[@azimuth:DEG]`` or a vector towards the light.
    res : int
        Eye-pass (measurement) resolution [pixels per side], in [16, 2048].
    image_res : int, optional
        Image resolution the critical shadow-map resolutions are given for (default ``res``).
    probes : int
        Probe grid cells per side, in [2, min(256, res/4)].
    seed : int
        Seed of the probes' depth permutation: the same inputs give the same result.
    reach : float
        Fraction of the bound every map's measured maxima must reach to pass, in [0, 1].
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
        over the probe pixels (:func:`aliasing.raster.measure.projection_factors`), about 1 by
        construction of the probes (Lloyd 2006 §3.3), so the measured error is perspective
        aliasing alone.

    Raises
    ------
    ValueError
        Unknown scheme, f/n ≤ 1, fov outside (0, 180), a light giving no or several
        directions, res outside [16, 2048], probes outside [2, min(256, res/4)].

    Example
    -------
    >>> r = validate("ZP2+P", 50, 60, "gamma:60", res=128, probes=8)
    >>> r["maps"], r["passed"], len(r["ratio_M_x"])
    (2, True, 2)
    """
    c = _check(scheme, f_over_n, fov, light, res, image_res, probes, reach)
    seed = _whole(seed, "seed", 0, 2**32 - 1)
    near, far = 1.0, c["f_over_n"]
    lv = c["lv"]
    _, edges = light_maps(near, far, c["fov"], lv, c["scheme"].name, **options)
    scene = probe_scene(near, far, c["fov"], lv, cells=c["probes"], seed=seed, splits=edges)
    m = measure(near, far, c["fov"], lv, c["scheme"].name, resolution=c["res"], scene=scene, map_resolution=c["res"], **options)
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
    }


# --------------------------------------------------------------------------- grids


def _names(value: str | Iterable[str], name: str) -> list[str]:
    items = value.split(",") if isinstance(value, str) else list(value)
    out = [str(s).strip() for s in items if str(s).strip()]
    if not out:
        raise ValueError(f"{name} is empty: the validation grid has no points")
    return out


def _numbers(value: object, name: str) -> list[float]:
    from .. import sweep

    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
        value = [value]
    return list(sweep.grid_values(value, name))  # type: ignore[arg-type]


def expand_light_specs(lights: str | Iterable[str]) -> list[str]:
    """Light specs of a validation grid, each exactly one direction.

    Comma-separated (or a list); ``gamma:LIST|RANGE[@azimuth:LIST|RANGE]`` expands to one
    ``gamma:G@azimuth:A`` spec per (γ, azimuth), γ outer.  ``sphere:N``, ``hemisphere:N``
    (several directions) are refused.

    Example
    -------
    >>> expand_light_specs("overhead,gamma:30:150:lin:3")
    ['overhead', 'gamma:30@azimuth:0', 'gamma:90@azimuth:0', 'gamma:150@azimuth:0']
    """
    from .. import sweep

    specs = sweep.split_lights(lights) if isinstance(lights, str) else [str(s).strip() for s in lights if str(s).strip()]
    if not specs:
        raise ValueError("light is empty: the validation grid has no directions")
    out: list[str] = []
    for spec in specs:
        kind, _, rest = spec.lower().partition(":")
        g_text, _, a_text = rest.partition("@")
        if kind == "gamma" and (":" in g_text or "," in rest or ":" in a_text.partition(":")[2]):
            key, _, az = a_text.partition(":")
            if a_text and key != "azimuth":
                raise ValueError(f"malformed light {spec!r}; expected gamma:DEG|RANGE[@azimuth:DEG|RANGE]")
            gs = sweep.grid_values(g_text, "light gamma")
            azs = sweep.grid_values(az, "light azimuth") if a_text else (0.0,)
            out.extend(f"gamma:{g:.10g}@azimuth:{a:.10g}" for g in gs for a in azs)
        else:
            out.append(spec)
    for spec in out:
        _light(spec)
    return out


def _task(kwargs: dict) -> dict:
    return validate(**kwargs)


def validate_rows(schemes: str | Iterable[str], f_over_n: object, fov: object, lights: str | Iterable[str], res: int = DEFAULT_RES, *, image_res: int | None = None, probes: int = DEFAULT_PROBES, seed: int = 0, reach: float = DEFAULT_REACH, jobs: int = 1) -> list[dict]:
    """Validations over the product schemes × f/n × fov × lights: one row per combination.

    Parameters
    ----------
    schemes : str or iterable of str
        Scheme names (comma-separated text or a list).
    f_over_n, fov : number, list or text
        Numbers or ranges ``START:STOP:lin|log:COUNT`` (see :func:`aliasing.sweep.grid_values`).
    lights : str or iterable of str
        Light specs, each one direction (see :func:`expand_light_specs`).
    res, image_res, probes, seed, reach
        As in :func:`validate`, for every row.
    jobs : int
        Local worker processes (concurrent.futures); the rows are identical whatever ``jobs``.

    Returns
    -------
    list of dict
        :func:`validate`'s dicts, ordered scheme (outer), f/n, fov, light (inner).

    Every input is checked before any work: a bad value anywhere raises ``ValueError``.

    Example
    -------
    >>> rows = validate_rows("Standard,P", [10, 100], 60, "gamma:60,gamma:150", res=64, probes=4)
    >>> len(rows), all(r["within_bound"] for r in rows)
    (8, True)
    """
    from .. import sweep

    names = _names(schemes, "schemes")
    ratios = _numbers(f_over_n, "f_over_n")
    fovs = _numbers(fov, "fov")
    specs = expand_light_specs(lights)
    jobs = check.jobs(jobs)
    tasks = [
        dict(scheme=s, f_over_n=r, fov=v, light=l, res=res, image_res=image_res, probes=probes, seed=seed, reach=reach)
        for s, r, v, l in itertools.product(names, ratios, fovs, specs)
    ]
    for t in tasks:  # fail fast, before any work or process starts
        _check(t["scheme"], t["f_over_n"], t["fov"], t["light"], res, image_res, probes, reach)
    _whole(seed, "seed", 0, 2**32 - 1)
    if jobs == 1 or len(tasks) <= 1:
        return [_task(t) for t in tasks]
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=min(jobs, len(tasks))) as ex:
        return list(ex.map(_task, tasks))  # map keeps the input order


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
        f"scheme {r['scheme']}  f/n {r['f_over_n']:g}  fov {r['fov']:g} deg  light {r['light']} (gamma {r['gamma']:.6g} deg)  maps {r['maps']}",
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
    cells = [keys] + [[_fmt(r[k]).replace(", ", ";") for k in keys] for r in rows]
    widths = [max(len(c[i]) for c in cells) for i in range(len(keys))]
    return "".join("  ".join(c[i].rjust(widths[i]) for i in range(len(keys))) + "\n" for c in cells)


def format_rows(rows: list[dict], fmt: str = "csv") -> str:
    """Validation rows as ``csv`` (per-map lists joined with ';'), ``json`` or a ``text`` table."""
    from .. import sweep

    kind = check.choice(fmt, "format", FORMATS)
    if kind == "text":
        return _table(rows)
    return sweep.format_rows(rows, kind)


# --------------------------------------------------------------------------- command line


def _single(value: str, flag: str) -> str:
    if "," in value or re.fullmatch(r"[^:]*:[^:]*:(lin|log):.*", value.strip(), flags=re.IGNORECASE):
        raise ValueError(f"{flag} takes one value without --grid, got {value!r}; add --grid to validate a list")
    return value


def _number(value: str, flag: str) -> float:
    try:
        return float(_single(value, flag))
    except ValueError as exc:
        if "--grid" in str(exc):
            raise
        raise ValueError(f"{flag} must be a number, got {value!r}") from None


def _run(args: argparse.Namespace) -> int:
    fmt = args.format or ("csv" if args.grid else "text")
    if args.grid:
        rows = validate_rows(args.scheme, args.f_over_n, args.fov, args.light, args.res, image_res=args.image_res, probes=args.probes, seed=args.seed, reach=args.reach, jobs=args.jobs)
        sys.stdout.write(format_rows(rows, fmt))
        return 0 if all(r["passed"] for r in rows) else 1
    if args.jobs != 1:
        raise ValueError("--jobs needs --grid (one validation runs in one process)")
    kind = check.choice(fmt, "format", FORMATS)
    r = validate(
        _single(args.scheme, "--scheme"), _number(args.f_over_n, "--f-over-n"), _number(args.fov, "--fov"), _single(args.light, "--light"),
        args.res, args.image_res, args.probes, seed=args.seed, reach=args.reach,
    )
    if kind == "text":
        sys.stdout.write(format_text(r))
    elif kind == "json":
        sys.stdout.write(json.dumps({k: _json(v) for k, v in r.items()}, indent=1) + "\n")
    else:
        sys.stdout.write(format_rows([r], "csv"))
    return 0 if r["passed"] else 1


def _json(value: object) -> object:
    """JSON has no inf/NaN: write them as strings (as :mod:`aliasing.sweep` does)."""
    if isinstance(value, list):
        return [_json(v) for v in value]
    if isinstance(value, float) and not np.isfinite(value):
        return str(value)
    return value


def add_validate_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``validate`` subcommand to the ``aliasing`` command's subparsers ``sub``.

    Its handler is ``set_defaults(run=...)``; it returns 0 when every validation passes, 1
    when one fails, and raises ``ValueError`` on bad input (``aliasing.cli.main`` prints one
    line and exits 2).
    """
    p = sub.add_parser(
        "validate",
        help="measure a scheme's aliasing error with the rasterizer and compare it with the analytic bounds",
        description="Rasterize seeded probe planes, measure the perspective error m_x, m_z per pixel and compare their maxima "
        "(and S = M_x*M_z) with the analytic bounds (unit resolutions). PASS: no ratio above 1 + tolerance and every map's "
        "ratios at least --reach. Exit status 0 pass, 1 fail, 2 bad input. With --grid, every option takes a comma list "
        "(numbers also ranges START:STOP:lin|log:COUNT) and the product is validated, one row each.",
        epilog="schemes: Standard | P | Po | LogP (Log) | Sopt | LogSopt | <warping rule> | ZP<k> | ZP<k>+<any>.  "
        "light: overhead | behind | front | gamma:DEG[@azimuth:DEG] (one direction; with --grid comma-separated, gamma and azimuth take lists and ranges).",
    )
    p.add_argument("--scheme", required=True, help="scheme name, e.g. P or ZP4+LogP (with --grid: comma list)")
    p.add_argument("--f-over-n", required=True, help="depth ratio far/near > 1 (with --grid: list or range)")
    p.add_argument("--fov", default="60", help="FULL field of view in degrees (the papers' theta is half; default 60; with --grid: list or range)")
    p.add_argument("--light", default="overhead", help="one light direction, e.g. gamma:150 (default overhead; with --grid: comma list)")
    p.add_argument("--res", type=int, default=DEFAULT_RES, help=f"measurement (eye-pass) resolution in pixels per side, {MIN_RES}..{MAX_RES} (default {DEFAULT_RES})")
    p.add_argument("--image-res", type=int, help="image resolution for the critical shadow-map resolutions (default --res)")
    p.add_argument("--probes", type=int, default=DEFAULT_PROBES, help=f"probe grid cells per side (default {DEFAULT_PROBES})")
    p.add_argument("--seed", type=int, default=0, help="seed of the probe depths (default 0)")
    p.add_argument("--reach", type=float, default=DEFAULT_REACH, help=f"fraction of the bound the maxima must reach to pass (default {DEFAULT_REACH})")
    p.add_argument("--format", choices=FORMATS, help="text (default; with --grid a table) | json | csv (default with --grid)")
    p.add_argument("--grid", action="store_true", help="validate the product of comma lists, one row per combination")
    p.add_argument("--jobs", type=int, default=1, help="local worker processes with --grid (default 1); the output does not depend on it")
    p.set_defaults(run=_run)
    return p
