"""Validation of the analytic aliasing bounds by the rasterizer: ``aliasing validate``.

Modules: one validation and its formats are :mod:`aliasing.raster.validate.single` (re-exported
here); this module holds the validation grids and the command glue.

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

Grids: :func:`plan` checks and expands the product schemes × f/n × fov × lights (one row
per combination, in that order) into a :class:`ValidationGrid`, one validation per chunk,
which runs through the engine of ``aliasing sweep`` (:func:`aliasing.sweep.execute`): in
``jobs`` local processes or on a Dask cluster, with output files written chunk by chunk
(atomically, resumable without redoing finished validations) and identical however it ran.
``aspect`` (image width/height, one value) applies to every validation of a grid; rows of a
non-square view carry it, and at aspect 1 the grid and its output are those without it.
:func:`validate_sweep` runs a grid in memory and returns a :class:`ValidationTable` (a
:class:`~aliasing.sweep.SweepTable`: rows, CSV/JSON/text, pandas, xarray);
:func:`validate_rows` is its rows.  :func:`add_validate_parser` adds the ``validate``
subcommand (single case, or the grid with ``--grid``) to the ``aliasing`` command.

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
import shlex
import sys
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ... import _validation as check
from ... import setups, sweep
from ...view import check_aspect
from ..draw import backends
from .single import (  # noqa: F401  (re-exported: the public names of one validation)
    DEFAULT_PROBES,
    DEFAULT_REACH,
    DEFAULT_RES,
    FORMATS,
    MAX_PROBES,
    MAX_RES,
    MIN_RES,
    TEXT_KEYS,
    _check,
    _light,
    _whole,
    format_rows,
    format_text,
    validate,
)


# --------------------------------------------------------------------------- grids


def _names(value: str | Iterable[str], name: str) -> list[str]:
    items = value.split(",") if isinstance(value, str) else list(value)
    if any(str(s).strip() for s in items) and not all(str(s).strip() for s in items):
        raise ValueError(f"{name} has an empty item in {value!r} (two commas, or a comma at an end)")  # as aliasing sweep
    out = [str(s).strip() for s in items if str(s).strip()]
    if not out:
        raise ValueError(f"{name} is empty: the validation grid has no points")
    return out


def _numbers(value: object, name: str) -> list[float]:
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


GRID_FORMATS = ("csv", "json", "text", "netcdf")
"""Output formats of a validation grid (netcdf needs an output file and the xarray extra)."""
PER_MAP = ("M_x", "M_z", "S", "measured_M_x", "measured_M_z", "measured_S", "ratio_M_x", "ratio_M_z", "ratio_S", "critical_res_s", "critical_res_t")
"""Row keys with one value per map (a list when the scheme has several maps)."""


@dataclass(frozen=True)
class ValidationTask:
    """One chunk of a validation grid: the keyword arguments of one :func:`validate` call."""

    index: int
    arguments: tuple[tuple[str, object], ...]

    def compute(self) -> list[dict]:
        """The chunk's rows: ``[validate(**arguments)]``."""
        return [validate(**dict(self.arguments))]


@dataclass(frozen=True)
class ValidationGrid:
    """A planned validation grid: schemes × f/n × fov × lights, one validation per chunk.

    Build it with :func:`plan`; run it with :func:`aliasing.sweep.execute` (chunked, resumable
    output files, processes or Dask, as ``aliasing sweep``) or :func:`validate_sweep` (in
    memory).  Chunks are in row order: scheme (outer), f/n, fov, light (inner).  ``aspect``
    (image width/height) is one value for every validation; at 1 (the default) the grid,
    its parameters and its rows are those of a grid without it.
    """

    schemes: tuple[str, ...]
    f_over_n: tuple[float, ...]
    fov: tuple[float, ...]
    lights: tuple[str, ...]
    res: int = DEFAULT_RES
    image_res: int | None = None
    probes: int = DEFAULT_PROBES
    seed: int = 0
    reach: float = DEFAULT_REACH
    aspect: float = 1.0

    formats: ClassVar[tuple[str, ...]] = GRID_FORMATS

    @property
    def shape(self) -> tuple[int, int, int, int]:
        """(schemes, f/n values, fovs, lights)."""
        return (len(self.schemes), len(self.f_over_n), len(self.fov), len(self.lights))

    @property
    def chunks(self) -> int:
        """Number of chunks, one validation each (also :attr:`size`, the number of validations)."""
        return len(self.schemes) * len(self.f_over_n) * len(self.fov) * len(self.lights)

    size = chunks

    def chunk(self, index: int, kind: str = "rows") -> ValidationTask:
        """The validation of chunk ``index`` (0 ≤ index < :attr:`chunks`)."""
        s, r, f, l = (int(i) for i in np.unravel_index(index, self.shape))
        args = dict(scheme=self.schemes[s], f_over_n=self.f_over_n[r], fov=self.fov[f], light=self.lights[l], res=self.res, image_res=self.image_res, probes=self.probes, seed=self.seed, reach=self.reach)
        if self.aspect != 1.0:
            args["aspect"] = self.aspect
        return ValidationTask(index, tuple(args.items()))

    def payload_kind(self, fmt: str) -> str:
        """Chunks are kept as their rows (JSON lines), whatever the output format."""
        return "rows"

    def parameters(self) -> dict:
        """Every parameter of the grid, JSON-ready (what the manifest's hash covers; ``aspect`` only when not 1)."""
        out = {"validate": True, "schemes": list(self.schemes), "f_over_n": list(self.f_over_n), "fov": list(self.fov), "lights": list(self.lights),
               "res": self.res, "image_res": self.image_res, "probes": self.probes, "seed": self.seed, "reach": self.reach}
        return out if self.aspect == 1.0 else out | {"aspect": self.aspect}

    def digest(self, fmt: str) -> str:
        """SHA-256 of the parameters, the output format and the toolkit version."""
        return sweep.parameters_digest(self.parameters(), fmt)

    def command(self, fmt: str = "csv") -> str:
        """An ``aliasing validate --grid`` command line for this grid."""
        def nums(values: Sequence[float]) -> str:
            return ",".join(f"{x:.10g}" for x in values)

        parts = ["aliasing", "validate", "--grid", "--scheme", ",".join(self.schemes), "--f-over-n", nums(self.f_over_n), "--fov", nums(self.fov), "--light", ",".join(self.lights)]
        parts += ["--aspect", f"{self.aspect:.17g}"] if self.aspect != 1.0 else []
        parts += ["--res", str(self.res)] + (["--image-res", str(self.image_res)] if self.image_res is not None else [])
        parts += ["--probes", str(self.probes), "--seed", str(self.seed), "--reach", f"{self.reach:.10g}", "--format", fmt]
        return shlex.join(parts)

    def describe(self) -> str:
        """One line: the grid's axes, size and chunks."""
        s, r, f, l = self.shape
        wide = f", aspect {self.aspect:g}" if self.aspect != 1.0 else ""
        return f"grid: {s} schemes × {r} f/n × {f} fov × {l} lights = {self.size:,} validations in {self.chunks:,} chunks (res {self.res}, {self.probes}x{self.probes} probes{wide})"

    def assemble(self, payload_kind: str, fmt: str, payloads: Iterable[list[dict]]) -> Iterator[str]:
        """The output text (:func:`format_rows`) of every chunk's rows, in order."""
        yield format_rows([row for rows in payloads for row in rows], fmt)

    def table(self, payloads: Sequence[list[dict]], command: str | None = None) -> ValidationTable:
        """The :class:`ValidationTable` of every chunk's rows, in order."""
        return ValidationTable(self, [row for rows in payloads for row in rows], command)

    def timing(self, kind: str = "rows", sample: int = 500) -> tuple[list[tuple[ValidationTask, int]], str]:
        """One validation of up to 8 schemes (spread over the axis) for :func:`aliasing.sweep.estimate`; ``sample`` is unused."""
        per_scheme = self.chunks // len(self.schemes)
        picks = sweep.spread(len(self.schemes))
        return [(self.chunk(i * per_scheme, kind), 1) for i in picks], f"timed on one validation of {len(picks)} scheme{'s' if len(picks) > 1 else ''}"


class ValidationTable(sweep.SweepTable):
    """A finished validation grid in memory: a :class:`~aliasing.sweep.SweepTable` of its rows.

    ``.rows()`` (:func:`validate`'s dicts, in grid order), ``.format("csv" | "json" |
    "text")``, ``.to_pandas()``, ``.to_xarray()``, and ``.passed`` (every validation passed).

    Example
    -------
    >>> t = validate_sweep("P", [10, 100], 60, "gamma:60,gamma:150", res=64, probes=4)
    >>> len(t), t.passed, t.to_xarray()["ratio_M_x"].dims
    (4, True, ('scheme', 'f_over_n', 'fov', 'light', 'map'))
    """

    grid: ValidationGrid

    def __init__(self, grid: ValidationGrid, rows: list[dict], command: str | None = None) -> None:
        super().__init__(grid, rows, command)  # type: ignore[arg-type]

    def __len__(self) -> int:
        return len(self.data)

    @property
    def passed(self) -> bool:
        """Whether every validation passed."""
        return all(r["passed"] for r in self.data)

    def rows(self) -> list[dict]:
        """:func:`validate`'s dicts, scheme (outer), f/n, fov, light (inner)."""
        return [dict(r) for r in self.data]

    def format(self, fmt: str = "csv") -> str:
        """CSV, JSON or a text table (:func:`format_rows`), the bytes ``aliasing validate --grid`` writes."""
        return format_rows(self.rows(), fmt)

    def to_xarray(self):
        """An ``xarray.Dataset`` with dims scheme, f_over_n, fov, light (and map, for :data:`PER_MAP`).

        Per-map variables are padded with NaN up to the largest number of maps; ``gamma`` is a
        coordinate of ``light``, ``maps`` of ``scheme``; res, probes, seed, reach and the other
        parameters (``aspect`` when not 1), the toolkit version and the command are attributes.
        """
        xr = sweep.import_xarray()
        g, rows = self.grid, self.data
        dims = ("scheme", "f_over_n", "fov", "light")
        kmax = max(r["maps"] for r in rows)
        coords: dict = {"scheme": list(g.schemes), "f_over_n": list(g.f_over_n), "fov": list(g.fov), "light": list(g.lights), "map": np.arange(kmax)}
        coords["gamma"] = ("light", [r["gamma"] for r in rows[: len(g.lights)]])
        coords["maps"] = ("scheme", [r["maps"] for r in rows[:: self.grid.chunks // len(g.schemes)]])
        skip = {*dims, "gamma", "maps", "res", "image_res", "probes", "seed", "reach", "aspect"}
        data: dict = {}
        for key in (k for k in rows[0] if k not in skip):
            if key in PER_MAP:
                padded = np.full((len(rows), kmax), np.nan)
                for i, r in enumerate(rows):
                    values = r[key] if isinstance(r[key], list) else [r[key]]
                    padded[i, : len(values)] = values
                data[key] = ((*dims, "map"), padded.reshape(g.shape + (kmax,)))
            else:
                data[key] = (dims, np.array([r[key] for r in rows]).reshape(g.shape))
        attrs = self.attributes()
        attrs.update(res=g.res, image_res=rows[0]["image_res"], probes=g.probes, seed=g.seed, reach=g.reach)
        if g.aspect != 1.0:
            attrs.update(aspect=g.aspect)
        attrs.update(units_fov="degrees (full field of view)", units_gamma="degrees", units_S="image areas (unit resolutions)")
        return xr.Dataset(data, coords=coords, attrs=attrs)


def plan(schemes: str | Iterable[str], f_over_n: object, fov: object, lights: str | Iterable[str], res: int = DEFAULT_RES, *, image_res: int | None = None, probes: int = DEFAULT_PROBES, seed: int = 0, reach: float = DEFAULT_REACH,
         aspect: float = 1.0) -> ValidationGrid:
    """Check and expand a validation grid's parameters into a :class:`ValidationGrid`.

    Every combination is checked before any work: a bad value anywhere raises ``ValueError``.

    Parameters
    ----------
    schemes : str or iterable of str
        Scheme names (comma-separated text or a list).
    f_over_n, fov : number, list or text
        Depth ratios far/near (> 1) and FULL fields of view [deg] in (0, 180): numbers or
        ranges ``START:STOP:lin|log:COUNT`` (see :func:`aliasing.sweep.grid_values`).
    lights : str or iterable of str
        Light specs, each one direction (see :func:`expand_light_specs`).
    res, image_res, probes, seed, reach
        As in :func:`validate`, for every validation.
    aspect : float
        Image width/height of every validation, 0 < aspect < inf (default 1: square; ``fov``
        is the vertical field of view).  Schemes of a square view only (face partitions,
        θ-only warping rules) are refused at aspect ≠ 1, as by :func:`validate`.

    Returns
    -------
    ValidationGrid

    Example
    -------
    >>> g = plan("P,LogP", "10:1000:log:3", 60, "gamma:30:150:lin:5", res=64, probes=4)
    >>> g.shape, g.chunks
    ((2, 3, 1, 5), 30)
    """
    names = _names(schemes, "schemes")
    ratios = _numbers(f_over_n, "f_over_n")
    fovs = _numbers(fov, "fov")
    specs = expand_light_specs(lights)
    seed = _whole(seed, "seed", 0, 2**32 - 1)
    aspect = float(check_aspect(check.scalar(aspect, "aspect")))  # one value for the whole grid, checked once here
    canonical: dict[str, None] = {}
    for name, ratio, fv, spec in itertools.product(names, ratios, fovs, specs):  # fail fast, before any work
        canonical[_check(name, ratio, fv, spec, res, image_res, probes, reach, aspect)["scheme"].name] = None
    if len(canonical) != len(names):
        raise ValueError(f"schemes: a scheme appears more than once in {', '.join(names)}")
    c = _check(names[0], ratios[0], fovs[0], specs[0], res, image_res, probes, reach, aspect)
    ri = None if image_res is None else c["image_res"]
    return ValidationGrid(tuple(canonical), tuple(ratios), tuple(fovs), tuple(specs), c["res"], ri, c["probes"], seed, c["reach"], aspect)


def validate_sweep(schemes: str | Iterable[str], f_over_n: object, fov: object, lights: str | Iterable[str], res: int = DEFAULT_RES, *, image_res: int | None = None, probes: int = DEFAULT_PROBES, seed: int = 0, reach: float = DEFAULT_REACH,
                   aspect: float = 1.0, jobs: int = 1, dask: str | None = None, progress: sweep.Progress | None = None) -> ValidationTable:
    """Validations over the product schemes × f/n × fov × lights, in memory, as a :class:`ValidationTable`.

    The Python side of ``aliasing validate --grid`` (which writes files chunk by chunk
    through :func:`aliasing.sweep.execute`, resumable).  The rows are identical whatever
    ``jobs`` and ``dask``.

    Parameters
    ----------
    schemes, f_over_n, fov, lights, res, image_res, probes, seed, reach, aspect
        As in :func:`plan`.
    jobs : int
        Local worker processes.
    dask : str, optional
        Address of a running Dask scheduler to run the validations on instead.
    progress : callable, optional
        ``progress(done, total)`` after each validation.

    Returns
    -------
    ValidationTable

    Example
    -------
    >>> t = validate_sweep("Standard,P", [10, 100], 60, "gamma:60,gamma:150", res=64, probes=4)
    >>> len(t), t.rows()[0]["scheme"], all(r["within_bound"] for r in t.rows())
    (8, 'Standard', True)
    """
    grid = plan(schemes, f_over_n, fov, lights, res, image_res=image_res, probes=probes, seed=seed, reach=reach, aspect=aspect)
    return grid.table(sweep.collect(grid, "rows", jobs=jobs, dask=dask, progress=progress))


def validate_rows(schemes: str | Iterable[str], f_over_n: object, fov: object, lights: str | Iterable[str], res: int = DEFAULT_RES, *, image_res: int | None = None, probes: int = DEFAULT_PROBES, seed: int = 0, reach: float = DEFAULT_REACH,
                  aspect: float = 1.0, jobs: int = 1) -> list[dict]:
    """Validations over the product schemes × f/n × fov × lights: one row per combination.

    ``validate_sweep(...).rows()`` (see :func:`validate_sweep` for the parameters).

    Returns
    -------
    list of dict
        :func:`validate`'s dicts, ordered scheme (outer), f/n, fov, light (inner).

    Example
    -------
    >>> rows = validate_rows("Standard,P", [10, 100], 60, "gamma:60,gamma:150", res=64, probes=4)
    >>> len(rows), all(r["within_bound"] for r in rows)
    (8, True)
    """
    return validate_sweep(schemes, f_over_n, fov, lights, res, image_res=image_res, probes=probes, seed=seed, reach=reach, aspect=aspect, jobs=jobs).rows()


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


def _run_grid(args: argparse.Namespace, fmt: str) -> int:
    if args.backend != "numpy":
        raise ValueError(f"--backend {args.backend} draws one validation (without --grid); a grid is drawn by numpy, the reference")
    grid = plan(args.scheme, args.f_over_n, args.fov, args.light, args.res, image_res=args.image_res, probes=args.probes, seed=args.seed, reach=args.reach, aspect=args.aspect)
    if args.dry_run:
        sys.stdout.write(sweep.dry_run(grid, fmt, args.jobs))
        return 0
    failed: list[dict] = []

    def verdict(payloads: list) -> None:
        failed.extend(r for rows in payloads for r in rows if not r["passed"])

    code = sweep.run_command(grid, fmt, args.out, name="validate", jobs=args.jobs, dask=args.dask, resume=args.resume, on_payloads=verdict)
    return code or (1 if failed else 0)


def _run(args: argparse.Namespace) -> int:
    fmt = args.format or ("csv" if args.grid else "text")
    backends.check(args.backend, "eye_pass")
    if args.grid:
        return _run_grid(args, fmt)
    for flag, given in (("--jobs", args.jobs != 1), ("--out", args.out), ("--resume", args.resume), ("--dask", args.dask), ("--dry-run", args.dry_run)):
        if given:
            raise ValueError(f"{flag} needs --grid (one validation runs in one process, its report goes to stdout)")
    kind = check.choice(fmt, "format", FORMATS)
    r = validate(
        _single(args.scheme, "--scheme"), _number(args.f_over_n, "--f-over-n"), _number(args.fov, "--fov"), _single(args.light, "--light"),
        args.res, args.image_res, args.probes, aspect=args.aspect, seed=args.seed, reach=args.reach, backend=args.backend,
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
        help="measure a scheme's aliasing error with the rasterizer and compare it with the analytic bounds (--grid: a resumable sweep of them)",
        description="Rasterize seeded probe planes, measure the perspective error m_x, m_z per pixel and compare their maxima "
        "(and S = M_x*M_z) with the analytic bounds (unit resolutions). PASS: no ratio above 1 + tolerance and every map's "
        "ratios at least --reach. Exit status 0 pass, 1 fail, 2 bad input. With --grid, every option takes a comma list "
        "(numbers also ranges START:STOP:lin|log:COUNT) and the product is validated, one row each, through the engine of "
        "'aliasing sweep': one validation per chunk, --jobs N processes or --dask ADDRESS, and with --out each finished chunk "
        "kept in <out>.parts until the output is complete (--resume continues an interrupted grid); the output does not "
        "depend on how it ran. Reports include the projection factor cos(psi_e)/cos(psi_l) measured from the normals on "
        "the probes (about 1 by construction).",
        epilog="schemes: Standard | P | Po | LogP (Log) | Sopt | LogSopt | <warping rule> | ZP<k> | ZP<k>+<any> | FP|FPc|FPcs[+ZP<k>]+P|LogP|Standard.  "
        "light: overhead | behind | front | gamma:DEG[@azimuth:DEG] (one direction; with --grid comma-separated, gamma and azimuth take lists and ranges).",
    )
    p.add_argument("--scheme", required=True, help="scheme name, e.g. P or ZP4+LogP (with --grid: comma list)")
    p.add_argument("--f-over-n", required=True, help="depth ratio far/near > 1 (with --grid: list or range)")
    p.add_argument("--fov", default="60", help="FULL field of view in degrees (the papers' theta is half; default 60; with --grid: list or range)")
    p.add_argument("--aspect", type=float, default=1.0, help="image width/height, > 0 (default 1: square; --fov is then the vertical field of view); one value, with --grid for every case, "
                   "with --scene for its camera; face partitions (FP...) and the theta-only warping rules take 1 only")
    p.add_argument("--light", default="overhead", help="one light direction, e.g. gamma:150 (default overhead; with --grid: comma list)")
    p.add_argument("--res", type=int, default=DEFAULT_RES, help=f"measurement (eye-pass) resolution in pixels per side, {MIN_RES}..{MAX_RES} (default {DEFAULT_RES})")
    p.add_argument("--image-res", type=int, help="the image's HEIGHT in pixels (rows) for the critical shadow-map resolutions (default --res)")
    p.add_argument("--probes", type=int, default=DEFAULT_PROBES, help=f"probe grid cells per side (default {DEFAULT_PROBES})")
    p.add_argument("--seed", type=int, default=0, help="seed of the probe depths (default 0)")
    p.add_argument("--reach", type=float, default=DEFAULT_REACH, help=f"fraction of the bound the maxima must reach to pass (default {DEFAULT_REACH})")
    p.add_argument("--format", choices=GRID_FORMATS, help="text (default; with --grid a table) | json | csv (default with --grid) | netcdf (--grid --out only; xarray extra)")
    p.add_argument("--backend", default="numpy", help="how the eye pass and the maps are drawn: numpy (default, the reference), numba (the eye pass; fast extra) or gl (OpenGL, gl extra); one validation only")
    p.add_argument("--grid", action="store_true", help="validate the product of comma lists, one row per combination")
    p.add_argument("--jobs", type=int, default=1, help="local worker processes with --grid (default 1); the output does not depend on it")
    p.add_argument("--out", help="with --grid: output file (default: standard output); written atomically, never truncated by a failed run")
    p.add_argument("--resume", action="store_true", help="with --grid --out: continue an interrupted grid from <out>.parts without redoing finished validations")
    p.add_argument("--dask", metavar="ADDRESS", help="with --grid: run the validations on a running Dask scheduler, e.g. tcp://host:8786 (dask extra)")
    p.add_argument("--dry-run", action="store_true", help="with --grid: print the grid size and an estimated time, validate nothing")
    p.set_defaults(run=_run)
    from .scene import add_scene_options  # --scene FILE (aliasing.raster.validate.scene)

    add_scene_options(p)
    setups.add_arguments(p, sun=None, camera=False, uses=(  # --camera SPEC
        "with --scene FILE, validate measures the engine's own cascades (its ranges, fit, snap and map size) on the scene "
        "against the analytic bounds (not for a fixed box, three.js's fade margin or Godot's two-split atlas); without --scene "
        "it takes only the last cascade's far (the shadow far) and the probes' maps are the validated schemes' own"))  # and --sun: f/n, fov, aspect, --image-res, --light; --engine: its far
    scene_run = p.get_default("run")

    def run(args: argparse.Namespace) -> int:
        setup, camera, sun = setups.resolve(args)
        if camera is not None:  # --image-res is the image's rows: the camera's height
            if "=" in (args.camera or ""):
                args.camera = None
            far = max(setup.pipeline.far_i) if setup is not None else camera.far
            args.f_over_n, args.fov, args.aspect, args.image_res = repr(far / camera.near), repr(camera.fov), camera.aspect, camera.height
            if args.scene is not None:
                args.near, args.far = camera.near, far
        if sun is not None:
            args.light = sun.light()
        return scene_run(args)

    p.set_defaults(run=run)
    return p
