"""One comparison row per engine scheme, and the ``aliasing engines`` subcommand.

Scheme specs (``:``-separated options, case-insensitive)::

    csm:SPLIT[:k=N]                          tight fit (the papers'), a split of aliasing.partitioning
    csm:ranges=A..B/C..D/...                 SPLIT may be each cascade's eye-depth range (an engine's own, --engine)
    csm-stable:SPLIT|PRESET[:k=N][:fit=sphere|diagonal|diagonal-unrounded|body|centroid|centroid16|far][:snap=none|origin|border|bevy|pad|godot][:scene=1][:overlap=P]
    sdsm[:k=N][:zmin=Z][:zmax=Z]             log partitions of the occupied range (default [near, far], k = 4)
    sdsm:method=adaptive|kmeans[:k=N]        from a depth histogram (``histogram=``; CLI ``--histogram``)
        both with [:border=B][:dilation=D][:quantize=1]: Intel's sample's partition border [units],
        dilation (fraction per side; the sample's 10/R) and power-of-two quantisation (default off)
    vsm:PRESET | vsm:bias=B[:first=L][:last=L][:pool=P][:dilation=D][:coarse=0]
        (page-marking dilation D pages, default 0.05; coarse=0 drops the coarse pages of levels 15–18)
    matched | exact

``csm-stable`` takes a stable preset (:data:`aliasing.engines.stable.PRESETS`) or a split
with the toolkit's default stable fit (a minimal bounding sphere, unsnapped: the model's
choice, not an engine's).

Row fields (errors at the given resolutions: ``--image-res`` pixels across, ``--shadow-res``
texels per cascade; the image is ``--image-res``/``--aspect`` pixels high, and a pixel is
square: its beam is 2 d tan θ_y over those rows, ``--fov`` being vertical): ``max_error``
(max over lights and receivers of max(m_x, m_z)),
``median_error`` (median over lights of each light's max), ``m_axis_min``/``m_axis_max``
(m_x along the view axis over [near, far], light overhead), ``storage_texels``, ``S_bar``
(the papers' critical storage in image areas: Σ_maps texels·M_x·M_z / (W·W/aspect), the maximum over
lights; for VSM a bound: texels·M²/(W·W/aspect)), ``pages`` (VSM: the frustum bound, or with ``ground``
the ground plane's closed form; worst light),
``overflow`` and ``extra_bias`` (VSM pool), ``coverage`` (cascades: the fraction of light
directions for which every map covers its slice; below 1 the row's error is not a valid
bound, see :func:`aliasing.engines.stable.coverage`), ``storage_ratio`` and ``error_ratio`` to the
matched limit (:mod:`aliasing.engines.limits`).

Example
-------
>>> rows = compare(["csm:log:k=4", "matched"], near=10.0, far=10000.0, lights="overhead")
>>> [r["scheme"] for r in rows], rows[1]["error_ratio"]
(['csm:log:k=4', 'matched'], 1.0)
"""

from __future__ import annotations

import argparse
import io
import json
import os
import stat
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from .. import _table as _tables
from .. import _validation as check
from .. import partitioning, setups
from . import limits, pipeline, sdsm, stable, vsm
from ..view import tan_theta

DEFAULT_SCHEMES = "csm:filament,csm-stable:filament,sdsm:k=4,vsm:high,vsm:epic,matched,exact"
FAMILIES = ("csm", "csm-stable", "sdsm", "vsm", "matched", "exact")
FIELDS = ("scheme", "max_error", "median_error", "m_axis_min", "m_axis_max", "storage_texels", "S_bar", "pages", "overflow", "extra_bias", "coverage", "storage_ratio", "error_ratio")


def _options(parts: list[str], spec: str, allowed: set[str]) -> dict[str, str]:
    opts = {}
    for item in parts:
        key, eq, value = item.partition("=")
        if not eq or key not in allowed:
            raise ValueError(f"scheme {spec!r}: unknown option {item!r}; allowed: {', '.join(sorted(allowed))}")
        opts[key] = value
    return opts


def _ranges(text: str, spec: str) -> tuple[np.ndarray, np.ndarray]:
    """``A..B/C..D/...``: each cascade's eye-depth range [units], 0 < A < B (an engine's own cascades)."""
    pairs = []
    for item in text.split("/"):
        lo, dots, hi = item.partition("..")
        try:
            a, b = float(lo), float(hi)
        except ValueError:
            a = b = float("nan")
        if not dots or not (np.isfinite(a) and np.isfinite(b) and 0 < a < b):
            raise ValueError(f"scheme {spec!r}: ranges must be NEAR..FAR per cascade, '/'-separated, 0 < NEAR < FAR, got {item!r}")
        pairs.append((a, b))
    a, b = np.array(pairs).T
    return a, b


def _num(opts: dict[str, str], key: str, spec: str, default: float | None = None) -> float | None:
    if key not in opts:
        return default
    try:
        value = float(opts[key])
    except ValueError:
        raise ValueError(f"scheme {spec!r}: {key} must be a number, got {opts[key]!r}") from None
    if not np.isfinite(value):  # refused by name before int() overflows or NaN reaches arithmetic
        raise ValueError(f"scheme {spec!r}: {key} must be finite, got {opts[key]!r}")
    return value


def _k(opts: dict[str, str], spec: str, default: int | None) -> int | None:
    k = _num(opts, "k", spec, default)
    if k is None:
        return None
    if not float(k).is_integer() or k < 1:
        raise ValueError(f"scheme {spec!r}: k must be a whole number >= 1, got {opts.get('k')}")
    return int(k)


def _cascade_row(spec: str, res: stable.StableResult, axis: stable.StableResult, t: float, image_res: int, shadow_res: int, aspect: float = 1.0) -> dict:
    rows = image_res / aspect  # the image's height in pixels (= image_res for a square view, bit for bit)
    scale = rows / shadow_res  # unit-resolution m (per row of the image) → m at W/aspect rows and R texels
    per_dir = np.maximum(res.M_x, res.M_z).max(axis=-1) * scale
    u, v = axis.used
    wx = axis.width_x[0]
    k = res.M_x.shape[1]
    return {
        "scheme": spec,
        "max_error": float(per_dir.max()),
        "median_error": float(np.median(per_dir)),
        "m_axis_min": float((wx / (2 * t * v)).min() * scale),  # m_x = W_x/(2 tanθ d), smallest at each cascade's far end
        "m_axis_max": float((wx / (2 * t * u)).max() * scale),
        "storage_texels": float(k * shadow_res**2),
        "S_bar": float(res.S.max()) / aspect,  # Σ M_x M_z per R_y² → per image area (aspect·R_y² pixels)
        "coverage": 1.0,  # tight fits cover their slices by construction
    }


@dataclass(frozen=True)
class ParsedSpec:
    """A scheme spec read by :func:`parse_spec`: what to evaluate, before any evaluation.

    ``family`` is one of :data:`FAMILIES`.  Cascades (``csm``, ``csm-stable``, ``sdsm``):
    ``split`` (a split method name, split distances, or SDSM's (near_i, far_i); None for
    ``sdsm:method=adaptive|kmeans``, whose partitions come from a histogram) and ``fit``
    (the keywords of :func:`aliasing.engines.stable.evaluate`).  ``sdsm``: ``method``,
    ``k`` (and for ``log`` ``zmin``/``zmax``).  ``vsm``: ``clipmap`` and ``pool``.
    """

    spec: str
    family: str
    split: object = None
    fit: dict = field(default_factory=dict)
    method: str = ""
    k: int | None = None
    zmin: float | None = None
    zmax: float | None = None
    clipmap: vsm.Clipmap | None = None
    pool: int = 0


def parse_spec(spec: str, *, fov: float, near: float, far: float, image_res: int, shadow_res: int, unit: str, aspect: float = 1.0) -> ParsedSpec:
    """Read one scheme spec (the module docstring's grammar) without evaluating it.

    Raises ValueError naming the spec and the bad option.  ``aspect`` (width/height) goes
    into the cascades' fits (``fit["aspect"]``) and into the ``vsm`` clipmap (its LOD takes
    tan θ_x = aspect·tan θ_y and the ``image_res`` pixels across, as the engine's does).

    Example
    -------
    >>> p = parse_spec("csm-stable:log:k=3:fit=diagonal:snap=origin", fov=60.0, near=1.0, far=100.0, image_res=1920, shadow_res=1024, unit="m")
    >>> p.family, p.split, p.fit["fit"], p.fit["snap"], p.fit["k"]
    ('csm-stable', 'log', 'diagonal', 'origin', 3)
    """
    text = str(spec).strip().lower()
    family, *parts = text.split(":")
    check.choice(family, "scheme family", FAMILIES)
    if family in ("matched", "exact"):
        if parts:
            raise ValueError(f"scheme {spec!r}: {family} takes no options")
        return ParsedSpec(spec, family)
    r = stable._aspect(aspect)
    if family == "vsm":
        if not parts:
            raise ValueError(f"scheme {spec!r}: vsm needs a preset ({', '.join(vsm.PRESETS)}) or bias=B")
        if "=" not in parts[0]:
            preset = check.choice(parts[0], "vsm preset", vsm.PRESETS)
            base = vsm.PRESETS[preset]
            opts = _options(parts[1:], spec, {"first", "last", "pool", "dilation", "coarse"})
        else:
            base = vsm.PRESETS["default"]
            opts = _options(parts, spec, {"bias", "first", "last", "pool", "dilation", "coarse"})
        bias = _num(opts, "bias", spec, base.bias)
        first, last, pool = (_num(opts, key, spec, d) for key, d in (("first", 6), ("last", 22), ("pool", base.pool)))
        if pool is None or pool < 1 or not float(pool).is_integer():
            raise ValueError(f"scheme {spec!r}: pool (physical pages) must be a whole number >= 1, got {pool:g}")
        for key, level in (("first", first), ("last", last)):
            if not float(level).is_integer():  # type: ignore[arg-type]
                raise ValueError(f"scheme {spec!r}: {key} (clipmap level) must be a whole number, got {level:g}")
        coarse = None if opts.get("coarse", "1") in ("0", "false", "no") else vsm.COARSE_LEVELS
        c = vsm.Clipmap(fov, image_res, bias, int(first), int(last), unit, _num(opts, "dilation", spec, vsm.DILATION), coarse, r)
        return ParsedSpec(spec, family, clipmap=c, pool=int(pool))
    if family == "sdsm":
        opts = _options(parts, spec, {"k", "zmin", "zmax", "method", "border", "dilation", "quantize"})
        k = _k(opts, spec, 4)
        method = check.choice(opts.get("method", "log"), "sdsm method", ("log", "adaptive", "kmeans"))
        sample = {"aspect": r, "border": _num(opts, "border", spec, 0.0), "dilation": _num(opts, "dilation", spec, 0.0), "quantize": opts.get("quantize", "0") not in ("0", "false", "no")}
        split = None
        zmin, zmax = _num(opts, "zmin", spec, near), _num(opts, "zmax", spec, far)
        if method == "log":
            lo, hi = sdsm.occupied(near, far, zmin, zmax)
            edges = sdsm.log_partitions(near, far, lo, hi, k)
            split = (edges[:-1], edges[1:])  # separate maps; the light space spans [near, far]
        return ParsedSpec(spec, family, split, sample, method, k, zmin if "zmin" in opts else None, zmax if "zmax" in opts else None)
    if not parts:
        raise ValueError(f"scheme {spec!r}: {family} needs a split method or preset (see aliasing splits --list)")
    name, rest = parts[0], parts[1:]
    if family == "csm":
        opts = _options(rest, spec, {"k"})
        kw = {"k": _k(opts, spec, None), "aspect": r}
    else:
        opts = _options(rest, spec, {"k", "fit", "snap", "scene", "overlap"})
        if name.partition("@")[0] in {q.name.partition("@")[0] for q in stable.PRESETS.values()}:
            name = partitioning.resolve_name(name, stable.PRESETS, "stable preset")  # NAME@RELEASE included
            p = stable.PRESETS[name]
            name, kw = p.split, {"fit": p.fit, "snap": p.snap, "overlap": p.overlap, "scene": p.scene}
            if "k" not in opts:
                opts["k"] = str(p.k)  # the preset's cascade count (see its source)
        else:
            kw = {"fit": "sphere"}
        kw["k"] = _k(opts, spec, None)
        for key in ("fit", "snap"):
            if key in opts:
                kw[key] = opts[key]
        if "scene" in opts:
            kw["scene"] = opts["scene"] not in ("0", "false", "no")
        if "overlap" in opts:
            kw["overlap"] = _num(opts, "overlap", spec)
        kw["resolution"] = float(shadow_res)
        kw["aspect"] = r
    if name.startswith("ranges="):  # an engine's own cascades (aliasing.engines.pipeline.scheme_spec)
        name = _ranges(name[len("ranges="):], spec)
    elif name == "bevy-bounds":  # Bevy's own split, its first bound 5 m in the scene's unit
        name = stable.bevy_bounds(near, far, kw.pop("k") or 4, stable.BEVY_FIRST_BOUND_M * 100.0 / vsm.CM_PER_UNIT[unit.lower()])
    else:
        name = partitioning.resolve_name(name)
        if name == "bevy":  # Bevy's first cascade bound is 10 m: in the scene's unit
            kw["first"] = partitioning.BEVY_FIRST_BOUND * 100.0 / vsm.CM_PER_UNIT[unit.lower()]
    return ParsedSpec(spec, family, name, kw)


def scheme_row(spec: str, *, fov: float, near: float, far: float, lights: str | np.ndarray, image_res: int, shadow_res: int, unit: str, ground: float | None = None, histogram: tuple | None = None, aspect: float = 1.0) -> dict:
    """The comparison row of one scheme spec (see the module docstring); ``aspect`` = width/height, ``fov`` vertical."""
    ps = parse_spec(spec, fov=fov, near=near, far=far, image_res=image_res, shadow_res=shadow_res, unit=unit, aspect=aspect)
    r = stable._aspect(aspect)
    family = ps.family
    t = float(tan_theta(fov))
    if family in ("matched", "exact"):
        return limits.row(family, image_res, r)
    if family == "vsm":
        c = ps.clipmap
        worst = vsm.frustum_max(c, near, far)
        lo, hi = vsm.m_axis_range(c, near, far)
        pool_info = vsm.pool_check(c, near, far, lights, ps.pool, ground)
        texels = pool_info["pages"] * vsm.PAGE**2
        return {
            "scheme": spec,
            "max_error": worst,
            "median_error": worst,  # the clipmap is centred on the camera: no light dependence in m
            "m_axis_min": lo,
            "m_axis_max": hi,
            "storage_texels": float(texels),
            "S_bar": float(np.float64(texels) * np.float64(worst) ** 2 / (image_res**2 / r)) if texels else 0.0,  # per image area (W·W/aspect pixels); inf for a vanishing fov; no pages: no storage
            "pages": pool_info["pages"],
            "overflow": bool(pool_info["overflow"]),
            "extra_bias": pool_info["extra_bias"],
        }
    if family == "sdsm":
        sample = ps.fit
        if ps.method == "log":
            split, n_fit, f_fit = ps.split, near, far
        else:
            if histogram is None:
                raise ValueError(f"scheme {spec!r}: method={ps.method} needs a depth histogram (--histogram CSV: z_lo,z_hi,count)")
            parts_lo, parts_hi = (sdsm.adaptive_log if ps.method == "adaptive" else sdsm.kmeans)(histogram[0], histogram[1], ps.k)
            sdsm.occupied(near, far, parts_lo[0], parts_hi[-1])  # the histogram must lie in [near, far]
            split, n_fit, f_fit = (parts_lo, parts_hi), near, far
        res = stable.evaluate(split, n_fit, f_fit, fov, lights, **sample)
        axis = stable.evaluate(split, n_fit, f_fit, fov, "overhead", **sample)
        return _cascade_row(spec, res, axis, t, image_res, shadow_res, r)
    name, kw = ps.split, dict(ps.fit)
    res = stable.evaluate(name, near, far, fov, lights, **kw)
    axis = stable.evaluate(name, near, far, fov, "overhead", **kw)
    row = _cascade_row(spec, res, axis, t, image_res, shadow_res, r)
    row["coverage"] = stable.coverage(name, near, far, fov, lights, **kw) if family == "csm-stable" else 1.0
    return row


def compare(schemes: Sequence[str], *, fov: float = 60.0, near: float = 10.0, far: float = 100000.0, lights: str | np.ndarray = "hemisphere:200", image_res: int = 1920, shadow_res: int = 2048, unit: str = "cm", ground: float | None = None, histogram: tuple | None = None, aspect: float = 1.0) -> list[dict]:
    """Rows for ``schemes`` with their ratios to the matched limit.

    Parameters
    ----------
    schemes : sequence of str
        Scheme specs (module docstring).
    fov : float
        Vertical full field of view [deg].
    near, far : float
        Eye near and shadow distance [scene units].
    lights : str or array_like
        Light specs, comma-separated (the sweep's), or vectors ``(N, 3)``.
    image_res : int
        Eye image width [pixels]; the image is ``image_res / aspect`` pixels high.
    shadow_res : int
        Texels per side of each cascade.
    unit : str
        The scene's unit (VSM's constants are in cm).
    ground : float, optional
        Camera height above a ground plane [scene units]: VSM pages, overflow and extra bias
        from the ground plane's closed form instead of the frustum's upper bound.
    histogram : (edges, counts), optional
        A depth histogram for ``sdsm:method=adaptive|kmeans`` (:func:`aliasing.engines.sdsm.histogram`).
    aspect : float
        Image width/height, 0 < aspect < inf (default 1, the square view; aspect 1 gives the
        square rows bit for bit).  Square pixels: errors are per pixel of ``image_res/aspect``
        rows (the beam 2 d tan θ_y over them), so a wider view at the same width has larger
        pixels and smaller m; the cascades' fits take the wider slices; ``S_bar`` is per image
        area; the limits' storage is per pixel of the W × W/aspect image.  ``vsm`` schemes
        take it into the clipmap (:class:`aliasing.engines.vsm.Clipmap`: the engine's LOD
        from tan θ_x and W).
    """
    check.fov(fov)
    check.frustum(near, far)
    r = stable._aspect(aspect)
    for value, name in ((image_res, "image_res"), (shadow_res, "shadow_res")):
        if not (float(value) >= 1 and float(value).is_integer()):
            raise ValueError(f"{name} must be a whole number >= 1 (pixels/texels per side), got {value!r}")
    check.choice(unit, "unit", vsm.CM_PER_UNIT)
    if not schemes:
        raise ValueError("schemes is empty: name at least one scheme")
    if isinstance(lights, str):
        from ..sweep import expand_lights

        lights = expand_lights(lights)[1]
    ref = limits.row("matched", int(image_res), r)
    rows = []
    for spec in schemes:
        row = {key: None for key in FIELDS}
        row.update(scheme_row(spec, fov=float(fov), near=float(near), far=float(far), lights=lights, image_res=int(image_res), shadow_res=int(shadow_res), unit=unit, ground=ground, histogram=histogram, aspect=r))
        row["storage_ratio"] = row["storage_texels"] / ref["storage_texels"]
        row["error_ratio"] = row["max_error"] / ref["max_error"]
        rows.append(row)
    return rows


def format_rows(rows: list[dict], fmt: str) -> str:
    """Rows as ``table``, ``csv`` or ``json`` text."""
    if fmt == "json":
        return json.dumps(rows, indent=1) + "\n"
    if fmt == "csv":
        return _tables.csv_text(rows, FIELDS)
    return _tables.aligned([list(FIELDS)] + [[_cell(r[k]) for k in FIELDS] for r in rows])


def _cell(v: object) -> str:
    return ("yes" if v else "no") if isinstance(v, bool) else _tables.cell(v)


LISTING = """families and presets:
  csm:SPLIT[:k=N]                 split methods: {splits}
  csm-stable:SPLIT|PRESET[:k=N][:fit=sphere|diagonal|diagonal-unrounded|body|centroid|centroid16|far][:snap=none|origin|border|bevy|pad|godot][:scene=1][:overlap=P]
                                  stable presets: {stables}
  sdsm[:k=N][:zmin=Z][:zmax=Z]    log partitions of the occupied range (Lauritzen et al. 2011)
  sdsm:method=adaptive|kmeans[:k=N]  from --histogram (Intel's SDSM sample)
    sdsm options [:border=B][:dilation=D][:quantize=1]: the sample's partition border, dilation, power-of-two quantisation
  vsm:PRESET | vsm:bias=B[:first=L][:last=L][:pool=P][:dilation=D][:coarse=0]
                                  presets: {vsms}
  matched                         resolution-matched, power-of-two levels (Lefohn et al. 2007)
  exact                           irregular z-buffer / ray-traced shadows
"""


def _run(args: argparse.Namespace) -> int:
    if args.list:
        print(LISTING.format(splits=", ".join(partitioning.SPLIT_METHODS), stables=", ".join(f"{p.name} ({p.source}; release: {p.release})" for p in stable.PRESETS.values()), vsms=", ".join(f"{p.name} (bias {p.bias:g}, pool {p.pool})" for p in vsm.PRESETS.values())), end="")
        return 0
    setup, camera, sun = setups.resolve(args)
    given = args.schemes
    schemes = [s for s in (DEFAULT_SCHEMES if given is None else given).split(",") if s.strip()]
    if setup is not None:  # the engine's own cascades first, at its own map size; the limits after
        schemes = [pipeline.scheme_spec(setup.pipeline)] + ([s for s in given.split(",") if s.strip()] if given is not None else ["matched", "exact"])
        args.far, args.shadow_res = max(setup.pipeline.far_i), setup.pipeline.resolution
    if camera is not None:  # --image-res here is the image's WIDTH: the camera's aspect·height
        args.near, args.fov, args.aspect, args.image_res = camera.near, camera.fov, camera.aspect, camera.width
        args.far = args.far if setup is not None else camera.far
    if sun is not None:
        args.light = ",".join(sun.light(e) for e in sun.elevations(7))
    if args.unit is None:
        args.unit = "m" if camera is not None else "cm"
    histogram = _read_histogram(args.histogram) if args.histogram else None
    rows = compare(schemes, fov=args.fov, near=args.near, far=args.far, lights=args.light, image_res=args.image_res, shadow_res=args.shadow_res, unit=args.unit, ground=args.ground, histogram=histogram, aspect=args.aspect)
    if setup is not None:
        rows[0]["scheme"] = setup.profile.name  # the engine's row (its cascades: aliasing check)
    print(format_rows(rows, args.format), end="")
    return 0


MAX_HISTOGRAM_BYTES = 16 << 20
"""Largest --histogram file read [bytes]."""


def _read_histogram(path: str) -> tuple[np.ndarray, np.ndarray]:
    """A CSV of contiguous depth bins ``z_lo,z_hi,count`` (one header line) → (edges, counts)."""
    try:
        st = os.stat(path)
        if not stat.S_ISREG(st.st_mode):  # a FIFO would block forever, a device never end
            raise ValueError(f"--histogram {path!r}: not a regular file")
        if st.st_size > MAX_HISTOGRAM_BYTES:
            raise ValueError(f"--histogram {path!r}: {st.st_size:,} bytes; a histogram CSV is at most {MAX_HISTOGRAM_BYTES:,}")
        with open(path, encoding="utf-8") as handle:
            text = handle.read(MAX_HISTOGRAM_BYTES + 1)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "input contained no data": refused below, in one line
            table = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1, ndmin=2)
    except (OSError, ValueError, UnicodeError) as exc:
        if str(exc).startswith("--histogram"):
            raise
        raise ValueError(f"--histogram {path!r}: cannot read a CSV of z_lo,z_hi,count ({exc})") from None
    if table.shape[0] == 0:
        raise ValueError(f"--histogram {path!r}: no bins (needs rows z_lo,z_hi,count after the header line)")
    if table.shape[1] != 3 or np.any(table[1:, 0] != table[:-1, 1]):
        raise ValueError(f"--histogram {path!r}: needs columns z_lo,z_hi,count with contiguous bins (z_lo of a bin = z_hi of the previous)")
    return sdsm.histogram(np.append(table[:, 0], table[-1, 1]), table[:, 2])


def add_engines_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``engines`` subcommand to the ``aliasing`` command's subparsers ``sub``.

    ValueErrors (bad input) are printed by ``aliasing.cli.main`` as one line, exit 2.
    """
    p = sub.add_parser(
        "engines",
        help="compare today's engine schemes (stable CSM, SDSM, UE5 VSM) with the matched and exact limits",
        description="One row per scheme: error at the given resolutions (max, median over lights, along the view axis), "
        "storage in texels and as the papers' S, VSM pages and pool, and ratios to the resolution-matched limit.",
        epilog="schemes: csm:SPLIT[:k=N] | csm-stable:SPLIT|PRESET[:fit=..][:snap=..][:scene=1][:overlap=P] | sdsm[:k=N][:zmin=Z][:zmax=Z] | "
        "vsm:PRESET | vsm:bias=B[:first=L][:last=L][:pool=P] | matched | exact (see --list).",
    )
    p.add_argument("--schemes", help=f"comma list of scheme specs (default {DEFAULT_SCHEMES}; with --engine: the engine's own cascades, matched, exact)")
    p.add_argument("--fov", type=float, default=60.0, help="VERTICAL full field of view in degrees (default 60)")
    p.add_argument("--aspect", type=float, default=1.0, help="image width/height (default 1; the image is --image-res pixels wide, --image-res/aspect high)")
    p.add_argument("--near", type=float, default=10.0, help="near distance in --unit (default 10)")
    p.add_argument("--far", type=float, default=100000.0, help="shadow distance in --unit (default 100000)")
    p.add_argument("--image-res", type=int, default=1920, help="eye image WIDTH in pixels (default 1920; the height is --image-res/--aspect; "
                   "--camera gives it as aspect·height)")
    p.add_argument("--shadow-res", type=int, default=2048, help="texels per side of each cascade (default 2048)")
    p.add_argument("--unit", help="scene length unit: cm (default, as Unreal), m (default with --camera or --engine), mm, in, ft")
    p.add_argument("--light", default="hemisphere:200", help="light directions, the sweep's comma-separated specs (default hemisphere:200)")
    p.add_argument("--ground", type=float, help="camera height above a ground plane in --unit: VSM pages from the plane's closed form (default: the frustum's upper bound)")
    p.add_argument("--histogram", metavar="CSV", help="depth histogram for sdsm:method=adaptive|kmeans: columns z_lo,z_hi,count, one header line")
    p.add_argument("--format", default="table", choices=["table", "csv", "json"], help="output format (default table)")
    p.add_argument("--list", action="store_true", help="list the families and presets and exit")
    setups.add_arguments(p, sun=None)  # --engine: the engine's own cascades; --camera and --sun replace near, far, fov, aspect, --image-res, --light
    p.set_defaults(run=_run)
    return p
