"""Vectorized sweeps of schemes over depth ratios, fields of view and light directions.

Rows are plain dicts (ready for ``pandas.DataFrame(rows)``), written as CSV or JSON by
:func:`write`.  Per-map quantities (M_x, M_z, n′, η of a ``ZP<k>`` scheme) are lists.

Example
-------
>>> rows = sweep(["Standard", "ZP5+LogP"], f_over_n=[1000.0], fov=[60.0], light="overhead", summary=True)
>>> [(r["scheme"], round(r["S_min"], 3)) for r in rows]
[('Standard', 865159.378), ('ZP5+LogP', 5.982)]
"""

from __future__ import annotations

import csv
import hashlib
import inspect
import io
import itertools
import json
import os
import re
import shlex
import shutil
import sys
import tempfile
import types
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Protocol, TextIO

import numpy as np
from numpy.typing import ArrayLike

from . import _validation as check
from . import geometry, schemes, warping

FORMATS = ("csv", "json")
ROW_FIELDS = ("scheme", "f_over_n", "fov", "gamma", "azimuth", "M_x", "M_z", "S", "maps", "n_prime", "eta")
SUMMARY_FIELDS = ("scheme", "f_over_n", "fov", "directions", "maps", "S_min", "S_max", "S_max_over_min", "S_mean")


def sweep(scheme_names: Iterable[str], f_over_n: ArrayLike = (1000.0,), fov: ArrayLike = (60.0,), light: str | ArrayLike = "overhead", *, near: float = 1.0, summary: bool = False, **options) -> list[dict]:
    """Evaluate every scheme × f/n × fov over the light directions.

    Parameters
    ----------
    scheme_names : iterable of str
        Scheme names (:data:`aliasing.schemes.GRAMMAR`).
    f_over_n : array_like
        Depth ratios far/near, each > 1.
    fov : array_like
        Full fields of view [deg], each in (0, 180).
    light : str or array_like
        Light spec (:data:`aliasing.geometry.LIGHT_SPEC`) or vectors ``(N, 3)``.
    near : float
        Near distance [world units]; results depend on f/n only.
    summary : bool
        One row per scheme, f/n and fov with min, max, max/min and mean of S̄ over the
        directions (the layout of Lloyd et al. 2007 Table 3) instead of one row per direction.
    **options
        Passed to the warping rules.

    Returns
    -------
    list of dict
        With the keys :data:`ROW_FIELDS` or :data:`SUMMARY_FIELDS`.
    """
    parsed = [schemes.parse(name) for name in scheme_names]
    if not parsed:
        raise ValueError("schemes must name at least one scheme")
    ratios = np.atleast_1d(check.depth_ratio(f_over_n))
    fovs = np.atleast_1d(check.fov(fov))
    lv = geometry.lights(light)
    gamma, azimuth = geometry.direction_angles(lv)
    rows: list[dict] = []
    for sch in parsed:
        for ratio in ratios:
            for fv in fovs:
                r = schemes.evaluate(sch, near, near * ratio, fv, lv, **options)
                if summary:
                    rows.append(_summary_row(sch.name, ratio, fv, r))
                else:
                    rows.extend(_direction_rows(sch.name, ratio, fv, gamma, azimuth, r))
    return rows


def _summary_row(name: str, ratio: float, fov: float, r: schemes.Result) -> dict:
    s_min, s_max = float(r.S.min()), float(r.S.max())
    return {"scheme": name, "f_over_n": float(ratio), "fov": float(fov), "directions": int(r.S.size), "maps": _mean_maps(r), "S_min": s_min, "S_max": s_max, "S_max_over_min": s_max / s_min, "S_mean": float(r.S.mean())}


def _mean_maps(r: schemes.Result) -> int | float:
    """The number of maps, or its mean over the directions when it varies (face partitions)."""
    used = r.maps_used
    return int(used[0]) if np.all(used == used[0]) else float(used.mean())


def _direction_rows(name: str, ratio: float, fov: float, gamma: np.ndarray, azimuth: np.ndarray, r: schemes.Result) -> list[dict]:
    per_map = {"M_x": r.M_x.tolist(), "M_z": r.M_z.tolist(), "n_prime": r.n_prime.tolist(), "eta": r.eta.tolist()}
    used = r.maps_used.tolist()
    return [
        {
            "scheme": name,
            "f_over_n": float(ratio),
            "fov": float(fov),
            "gamma": float(gamma[i]),
            "azimuth": float(azimuth[i]),
            "M_x": _scalar(per_map["M_x"][i]),
            "M_z": _scalar(per_map["M_z"][i]),
            "S": float(r.S[i]),
            "maps": used[i],
            "n_prime": _scalar(per_map["n_prime"][i]),
            "eta": _scalar(per_map["eta"][i]),
        }
        for i in range(r.S.size)
    ]


def _scalar(values: list[float]) -> float | list[float]:
    return values[0] if len(values) == 1 else values


def format_rows(rows: Sequence[dict], fmt: str = "csv") -> str:
    """Rows as CSV (lists joined with ';') or JSON (a list of row objects)."""
    kind = check.choice(fmt, "format", FORMATS)
    if kind == "json":
        return json.dumps([{k: _json_value(v) for k, v in row.items()} for row in rows], indent=1) + "\n"
    if not rows:
        return ""
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: ";".join(f"{x:.10g}" for x in v) if isinstance(v, list) else (f"{v:.10g}" if isinstance(v, float) else v) for k, v in row.items()})
    return buf.getvalue()


def _json_value(value):
    """JSON has no inf/NaN: write them as strings, like CSV does."""
    if isinstance(value, list):
        return [_json_value(v) for v in value]
    if isinstance(value, float) and not np.isfinite(value):
        return str(value)
    return value


def write(text: str, path: str | os.PathLike) -> Path:
    """Write ``text`` atomically: a failed run never truncates an existing file."""
    target = Path(path)
    if target.is_dir():
        raise ValueError(f"out {str(target)!r} is a folder; give a file name")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise ValueError(f"out {str(target)!r}: folder {str(folder)!r} does not exist")
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as exc:
        raise ValueError(f"out {str(target)!r} cannot be written: {exc.strerror}") from None
    try:
        with os.fdopen(fd, "w", newline="") as handle:
            handle.write(text)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


# ---------------------------------------------------------------------------------------
# Sweeps at scale: grids, chunks, processes or Dask, resumable work directories
# ---------------------------------------------------------------------------------------

RANGE = "START:STOP:lin|log:COUNT"
OUTPUT_FORMATS = ("csv", "json", "netcdf")
DEFAULT_BLOCK = 20_000
"""Light directions per chunk: large enough to amortise the per-call cost, small enough that
the (N, k, 8) arrays of ZP schemes stay in cache-friendly sizes (see benchmarks/README.md)."""


def grid_values(value: str | float | Sequence, name: str) -> tuple[float, ...]:
    """Numbers of one grid axis from a number, a list, or text with numbers and ranges.

    A range ``START:STOP:lin:COUNT`` is ``numpy.linspace``, ``START:STOP:log:COUNT``
    ``numpy.geomspace`` (both ends included); text is comma-separated.

    Parameters
    ----------
    value : str, float or sequence
        E.g. ``"10:10000:log:4"``, ``"30,60"``, ``[30, "60:90:lin:2"]`` or ``45``.
    name : str
        The parameter's name, for error messages.

    Returns
    -------
    tuple of float

    Example
    -------
    >>> grid_values("10:10000:log:4", "f_over_n")
    (10.0, 100.0, 1000.0, 10000.0)
    >>> grid_values("30:90:lin:3,120", "fov")
    (30.0, 60.0, 90.0, 120.0)
    """
    if isinstance(value, str):
        items: list = [s.strip() for s in value.split(",") if s.strip()]
    elif isinstance(value, (list, tuple, np.ndarray)):
        items = list(np.asarray(value, dtype=object).ravel())
    else:
        items = [value]
    out: list[float] = []
    for item in items:
        if isinstance(item, str) and ":" in item:
            out.extend(_range(item, name))
            continue
        if isinstance(item, (bool, np.bool_)) or not isinstance(item, (int, float, str, np.integer, np.floating)):
            raise ValueError(f"{name} must be a comma-separated list of numbers or ranges {RANGE}, got {item!r}")
        try:
            out.append(float(item))
        except ValueError:
            raise ValueError(f"{name} must be a comma-separated list of numbers or ranges {RANGE}, got {value!r}") from None
    if not out:
        raise ValueError(f"{name} is empty: the sweep grid has no points")
    if any(np.isnan(v) for v in out):
        raise ValueError(f"{name} must not be NaN")
    return tuple(out)


def _range(text: str, name: str) -> list[float]:
    parts = [p.strip() for p in text.split(":")]
    try:
        if len(parts) != 4 or parts[2].lower() not in ("lin", "log"):
            raise ValueError
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[3])
    except ValueError:
        raise ValueError(f"{name}: malformed range {text!r}; expected {RANGE}, e.g. 10:10000:log:7") from None
    if count < 1:
        raise ValueError(f"{name}: range {text!r} has COUNT {count}; it must be >= 1 (the sweep grid would be empty)")
    if parts[2].lower() == "log":
        if start <= 0 or stop <= 0:
            raise ValueError(f"{name}: log range {text!r} needs START and STOP > 0")
        values = np.geomspace(start, stop, count)
    else:
        values = np.linspace(start, stop, count)
    return [float(v) for v in values]


@dataclass(frozen=True)
class Variant:
    """One point of the scheme axis: a canonical scheme name and its warping-rule options."""

    name: str
    options: tuple[tuple[str, float], ...] = ()

    @property
    def label(self) -> str:
        """Unique label, e.g. ``ETA[eta=-0.5]``."""
        if not self.options:
            return self.name
        return f"{self.name}[{','.join(f'{k}={v:.10g}' for k, v in self.options)}]"


def _rule_options(scheme: schemes.Scheme) -> set[str]:
    rule = warping.WARPING_RULES.get(scheme.rule)
    if rule is None:
        return set()
    return set(inspect.signature(rule.func).parameters) - {"near", "far"} - set(warping.CONTEXT)


def expand_schemes(names: str | Iterable[str], k: ArrayLike | str | None = None, params: dict | None = None) -> tuple[Variant, ...]:
    """The scheme axis: names × k × the warping-rule options each scheme takes.

    Parameters
    ----------
    names : str or iterable of str
        Scheme names (comma-separated text or a list).
    k : int, list or str, optional
        Numbers of z-partitions: each base scheme ``B`` becomes ``ZP<k>+B`` (k = 1 keeps ``B``).
    params : dict, optional
        Warping-rule option → grid values (:func:`grid_values`); each scheme is crossed with
        the options its rule takes (e.g. ``eta`` for the ``eta`` rule, ``c_fraction`` for P
        and LogP, ``focus`` and ``line`` for TSM).

    Example
    -------
    >>> [v.label for v in expand_schemes("P,eta", k=[1, 5], params={"eta": [-1, 0]})]
    ['P', 'ZP5+P', 'ETA[eta=-1]', 'ETA[eta=0]', 'ZP5+ETA[eta=-1]', 'ZP5+ETA[eta=0]']
    """
    listed = [n.strip() for n in names.split(",")] if isinstance(names, str) else [str(n).strip() for n in names]
    listed = [n for n in listed if n]
    if not listed:
        raise ValueError("schemes must name at least one scheme")
    ks: tuple[int, ...] | None = None
    if k is not None:
        raw = grid_values(k, "k")
        if any(v != int(v) or v < 1 for v in raw):
            raise ValueError(f"k must be whole numbers >= 1 (z-partitions), got {k!r}")
        ks = tuple(int(v) for v in raw)
    params = dict(params or {})
    grids = {key: grid_values(value, f"param {key}") for key, value in params.items()}
    for key in grids:
        if key in warping.CONTEXT:
            raise ValueError(f"param {key!r} is swept by the grid itself (f_over_n, fov, light), not a rule option")
    used: set[str] = set()
    out: list[Variant] = []
    for text in listed:
        base = schemes.parse(text)
        if ks is None:
            parsed = [base]
        else:
            if base.k != 1 or text.lower().startswith("zp"):
                raise ValueError(f"k: scheme {text!r} already names its k; give the base scheme (e.g. LogP) with k")
            parsed = [base if kv == 1 else schemes.parse(f"ZP{kv}+{base.name}") for kv in ks]
        for sch in parsed:
            keys = [key for key in grids if key in _rule_options(sch)]
            used.update(keys)
            for combo in itertools.product(*(grids[key] for key in keys)):
                out.append(Variant(sch.name, tuple(zip(keys, combo))))
    unused = sorted(set(grids) - used)
    if unused:
        raise ValueError(f"param {unused[0]!r} is taken by none of the schemes {', '.join(listed)}")
    labels = [v.label for v in out]
    dupes = sorted({lab for lab in labels if labels.count(lab) > 1})
    if dupes:
        raise ValueError(f"schemes: {dupes[0]!r} appears more than once in the grid")
    return tuple(out)


def expand_lights(light: str | Sequence[str] | ArrayLike) -> tuple[tuple[str, ...], np.ndarray]:
    """Light specs (comma-separated or a list) → ``(specs, vectors (N, 3))``.

    Besides :data:`aliasing.geometry.LIGHT_SPEC`, ``gamma:RANGE[@azimuth:RANGE]`` with
    ranges or numbers sweeps the product of γ (outer) and azimuth (inner).

    Example
    -------
    >>> specs, lv = expand_lights("overhead,gamma:0:180:lin:3@azimuth:0,90")
    >>> specs, lv.shape
    (('overhead', 'gamma:0:180:lin:3@azimuth:0,90'), (7, 3))
    """
    if isinstance(light, str):
        specs = split_lights(light)
    elif isinstance(light, (list, tuple)) and all(isinstance(s, str) for s in light):
        specs = [s.strip() for s in light if s.strip()]
    else:
        lv = geometry.lights(light)
        return ("vectors:" + _digest_bytes(np.ascontiguousarray(lv).tobytes())[:16],), lv
    if not specs:
        raise ValueError("light is empty: the sweep grid has no directions")
    blocks = []
    for spec in specs:
        text = spec.lower()
        kind, _, rest = text.partition(":")
        g_text, _, a_text = rest.partition("@")
        if kind == "gamma" and (":" in g_text or ":" in a_text.partition(":")[2] or "," in rest):
            key, _, az = a_text.partition(":")
            if a_text and key != "azimuth":
                raise ValueError(f"malformed light {spec!r}; expected gamma:DEG|RANGE[@azimuth:DEG|RANGE]")
            g = np.array(grid_values(g_text, "light gamma"))
            a = np.array(grid_values(az, "light azimuth") if a_text else (0.0,))
            blocks.append(geometry.light_direction(g[:, None], a[None, :]).reshape(-1, 3))
        else:
            blocks.append(geometry.lights(spec))
    return tuple(specs), np.concatenate(blocks)


def split_lights(text: str) -> list[str]:
    """Split light specs at commas, keeping ``gamma:…@azimuth:30,60`` lists inside one spec.

    Parameters
    ----------
    text : str
        Comma-separated light specs (:data:`aliasing.geometry.LIGHT_SPEC`, with lists and
        ranges after ``gamma:`` and ``@azimuth:``).

    Returns
    -------
    list of str
        The specs, stripped; empty parts are dropped.

    Example
    -------
    >>> split_lights("overhead, gamma:30,60@azimuth:0,90, hemisphere:10")
    ['overhead', 'gamma:30,60@azimuth:0,90', 'hemisphere:10']
    """
    if not isinstance(text, str):
        raise ValueError(f"light must be text of comma-separated specs, got {text!r}")
    out: list[str] = []
    for part in (p.strip() for p in text.split(",")):
        if not part:
            continue
        starts_spec = re.match(r"(overhead|behind|front|gamma|sphere|hemisphere)\b", part, flags=re.IGNORECASE)
        if out and out[-1].lower().startswith("gamma") and not starts_spec:
            out[-1] += "," + part
        else:
            out.append(part)
    return out


def _digest_bytes(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def parameters_digest(parameters: dict, fmt: str, data: bytes = b"") -> str:
    """SHA-256 of a grid's parameters (JSON-ready), its output format, the toolkit version and ``data``.

    What a work directory's manifest records, so that ``--resume`` refuses a different grid.

    Example
    -------
    >>> a = parameters_digest({"fov": [60.0]}, "csv")
    >>> len(a), a == parameters_digest({"fov": [60.0]}, "json")
    (64, False)
    """
    from . import __version__

    text = json.dumps({"parameters": parameters, "format": fmt, "aliasing": __version__}, sort_keys=True)
    return _digest_bytes(text.encode() + data)


def spread(count: int, most: int = 8) -> list[int]:
    """At most ``most`` indices in ``range(count)``, spread evenly with both ends (for timing samples).

    Example
    -------
    >>> spread(20, 4), spread(3)
    ([0, 6, 13, 19], [0, 1, 2])
    """
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise ValueError(f"count must be a whole number >= 1, got {count!r}")
    if isinstance(most, bool) or not isinstance(most, (int, np.integer)) or most < 1:
        raise ValueError(f"most must be a whole number >= 1, got {most!r}")
    return sorted(set(np.linspace(0, count - 1, min(most, count)).round().astype(int).tolist()))


@dataclass(frozen=True)
class Grid:
    """A planned sweep: the product scheme variants × f/n × fov × light directions.

    Build it with :func:`plan`; it is split into chunks of one variant, one f/n, one fov
    and a block of at most ``block`` directions, in that (row) order.
    """

    variants: tuple[Variant, ...]
    f_over_n: tuple[float, ...]
    fov: tuple[float, ...]
    light: tuple[str, ...]
    directions: np.ndarray = field(repr=False, compare=False)
    near: float = 1.0
    summary: bool = False
    block: int = DEFAULT_BLOCK

    formats: ClassVar[tuple[str, ...]] = OUTPUT_FORMATS

    @property
    def param_names(self) -> tuple[str, ...]:
        """Warping-rule options swept, in first-seen order."""
        seen: dict[str, None] = {}
        for v in self.variants:
            seen.update(dict.fromkeys(k for k, _ in v.options))
        return tuple(seen)

    @property
    def columns(self) -> tuple[str, ...]:
        """Output columns of the swept options: ``param_<name>``."""
        return tuple(f"param_{key}" for key in self.param_names)

    def _cells(self, var: Variant) -> tuple[float | None, ...]:
        return tuple(dict(var.options).get(key) for key in self.param_names)

    @property
    def shape(self) -> tuple[int, int, int, int]:
        """(variants, f/n values, fovs, directions)."""
        return (len(self.variants), len(self.f_over_n), len(self.fov), len(self.directions))

    @property
    def size(self) -> int:
        """Number of direction × scheme × frustum evaluations."""
        return int(np.prod(self.shape))

    @property
    def blocks(self) -> int:
        """Direction blocks per (variant, f/n, fov)."""
        return -(-len(self.directions) // self.block)

    @property
    def chunks(self) -> int:
        """Number of chunks."""
        return len(self.variants) * len(self.f_over_n) * len(self.fov) * self.blocks

    def chunk(self, index: int, kind: str) -> _Task:
        """The work of chunk ``index`` (0 ≤ index < :attr:`chunks`) for a payload ``kind``."""
        v, rest = divmod(index, len(self.f_over_n) * len(self.fov) * self.blocks)
        r, rest = divmod(rest, len(self.fov) * self.blocks)
        f, b = divmod(rest, self.blocks)
        var = self.variants[v]
        return _Task(index, kind, var.name, var.options, self.columns, self._cells(var), self.near, self.f_over_n[r], self.fov[f], self.directions[b * self.block : (b + 1) * self.block])

    def parameters(self) -> dict:
        """Every parameter of the sweep, JSON-ready (what the manifest's hash covers)."""
        return {
            "schemes": [v.name for v in self.variants],
            "options": [dict(v.options) for v in self.variants],
            "f_over_n": list(self.f_over_n),
            "fov": list(self.fov),
            "light": list(self.light),
            "directions": len(self.directions),
            "near": self.near,
            "summary": self.summary,
            "block": self.block,
        }

    def digest(self, fmt: str) -> str:
        """SHA-256 of the parameters, the directions, the output format and the toolkit version."""
        return parameters_digest(self.parameters(), fmt, np.ascontiguousarray(self.directions).tobytes())

    def command(self, fmt: str = "csv") -> str:
        """An ``aliasing sweep`` command line for this sweep."""
        names = ",".join(dict.fromkeys(v.name for v in self.variants))
        parts = ["aliasing", "sweep", "--schemes", names]
        for key in self.param_names:
            values = dict.fromkeys(dict(v.options)[key] for v in self.variants if key in dict(v.options))
            parts += ["--param", f"{key}=" + ",".join(f"{x:.10g}" for x in values)]
        parts += ["--f-over-n", ",".join(f"{x:.10g}" for x in self.f_over_n), "--fov", ",".join(f"{x:.10g}" for x in self.fov)]
        parts += ["--light", ",".join(self.light), "--near", f"{self.near:.10g}", "--block", str(self.block), "--format", fmt]
        return shlex.join(parts + (["--summary"] if self.summary else []))

    def describe(self) -> str:
        """One line: the grid's axes, size and chunks."""
        v, r, f, n = self.shape
        return f"grid: {v} schemes × {r} f/n × {f} fov × {n} directions = {self.size:,} evaluations in {self.chunks:,} chunks"

    def payload_kind(self, fmt: str) -> str:
        """How chunks are kept for output ``fmt``: CSV or JSON text, or arrays (summaries, NetCDF)."""
        return "arrays" if self.summary or fmt == "netcdf" else fmt

    def assemble(self, payload_kind: str, fmt: str, payloads: Iterable[object]) -> Iterator[str | bytes]:
        """The output text in pieces, from every chunk's payload in order."""
        return _assemble_stream(self, payload_kind, fmt, payloads)

    def table(self, payloads: Sequence[object], command: str | None = None) -> SweepTable:
        """The :class:`SweepTable` of every chunk's ``arrays`` payload, in order."""
        return SweepTable._from_payloads(self, list(payloads), command)

    def timing(self, kind: str, sample: int = 500) -> tuple[list[tuple[_Task, int]], str]:
        """Chunks to time for :func:`estimate` (``sample`` directions of up to 8 schemes), with their evaluations."""
        small = Grid(self.variants, self.f_over_n[:1], self.fov[:1], self.light, self.directions[:sample], self.near, self.summary, sample)
        tasks = [(small.chunk(v, kind), len(small.directions)) for v in spread(len(self.variants))]
        return tasks, f"timed on {len(small.directions)} directions per scheme"


def plan(
    schemes: str | Iterable[str],
    f_over_n: ArrayLike | str = (1000.0,),
    fov: ArrayLike | str = (60.0,),
    light: str | Sequence[str] | ArrayLike = "overhead",
    *,
    k: ArrayLike | str | None = None,
    params: dict | None = None,
    near: float = 1.0,
    summary: bool = False,
    block: int = DEFAULT_BLOCK,
) -> Grid:
    """Validate and expand a sweep's parameters into a :class:`Grid`.

    Every axis takes a number, a list or text with ranges (:func:`grid_values`).

    Parameters
    ----------
    schemes : str or iterable of str
        Scheme names (:data:`aliasing.schemes.GRAMMAR`).
    f_over_n, fov : array_like or str
        Depth ratios far/near (> 1) and full fields of view [deg] in (0, 180).
    light : str, sequence of str or array_like
        Light specs (:func:`expand_lights`) or vectors ``(N, 3)``.
    k, params
        See :func:`expand_schemes`.
    near : float
        Near distance [world units].
    summary : bool
        One row per scheme, f/n and fov (min, max, max/min, mean of S̄).
    block : int
        Directions per chunk.

    Example
    -------
    >>> g = plan("P,LogP", f_over_n="10:1000:log:3", fov=[60], light="hemisphere:100", k=[1, 5])
    >>> g.shape, g.size, g.chunks
    ((4, 3, 1, 100), 1200, 12)
    """
    variants = expand_schemes(schemes, k, params)
    ratios = grid_values(f_over_n, "f_over_n")
    check.depth_ratio(ratios)
    fovs = grid_values(fov, "fov")
    check.fov(fovs)
    specs, lv = expand_lights(light)
    near = float(check.positive(near, "near"))
    if isinstance(block, bool) or int(block) != block or block < 1:
        raise ValueError(f"block must be a whole number >= 1 (directions per chunk), got {block!r}")
    return Grid(variants, ratios, fovs, specs, lv, near, bool(summary), int(block))


@dataclass(frozen=True)
class _Task:
    """One chunk's work, small and picklable (sent to processes or Dask workers)."""

    index: int
    kind: str  # "csv" | "json" text fragments, or "arrays"
    name: str
    options: tuple[tuple[str, float], ...]
    columns: tuple[str, ...]  # param_<option> columns of the whole grid
    cells: tuple[float | None, ...]  # this variant's values in them (None: not taken)
    near: float
    ratio: float
    fov: float
    light: np.ndarray

    def compute(self) -> str | dict[str, np.ndarray]:
        """This chunk's payload (:func:`compute_chunk`)."""
        return compute_chunk(self)


def compute_chunk(task: _Task) -> str | dict[str, np.ndarray]:
    """Evaluate one chunk (vectorized over its directions); the payload of its kind.

    CSV or JSON text of its rows (no header), or the arrays S, M_x, M_z, n′, η.

    Example
    -------
    >>> g = plan("ZP2+P", light="overhead,front")
    >>> print(compute_chunk(g.chunk(0, "csv")), end="")
    ZP2+P,1000,60,90,0,5.623413252;5.623413252,4.716015218;4.716015218,53.04020494,2,6.623413252;209.4507176,0;0
    ZP2+P,1000,60,0,0,31.6227766;31.6227766,31.6227766;31.6227766,2000,2,inf;inf,-1;-1
    >>> compute_chunk(g.chunk(0, "arrays"))["M_x"].shape
    (2, 2)
    """
    r = schemes.evaluate(task.name, task.near, task.near * task.ratio, task.fov, task.light, **dict(task.options))
    if task.kind == "arrays":
        return {"S": r.S, "M_x": r.M_x, "M_z": r.M_z, "n_prime": r.n_prime, "eta": r.eta}
    gamma, azimuth = geometry.direction_angles(task.light)
    if task.kind == "json":
        rows = _direction_rows(r.scheme.name, task.ratio, task.fov, gamma, azimuth, r)
        rows = [_with_cells(row, task) for row in rows]
        return ",\n".join(" " + json.dumps({k: _json_value(v) for k, v in row.items()}, indent=1).replace("\n", "\n ") for row in rows)
    return _csv_fragment(task, gamma, azimuth, r)


def _with_cells(row: dict, task: _Task) -> dict:
    """Insert the swept rule options' columns (``param_<name>``) after ``scheme``."""
    if not task.columns:
        return row
    head = {"scheme": row["scheme"], **dict(zip(task.columns, task.cells))}
    head.update((k, v) for k, v in row.items() if k != "scheme")
    return head


def _fmt(x: object) -> str:
    if x is None:
        return ""
    return f"{x:.10g}" if isinstance(x, float) else str(x)


def _csv_cells(cells: Sequence[object]) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="").writerow([_fmt(c) for c in cells])
    return buf.getvalue()


def _column(a: np.ndarray) -> tuple[str, list]:
    """A %-format and the values of one output column (per-map lists joined with ';')."""
    if a.ndim == 2 and a.shape[1] == 1:
        a = a[:, 0]
    if a.ndim == 1:
        return "%.10g", a.tolist()
    return "%s", [";".join(f"{x:.10g}" for x in row) for row in a.tolist()]


def _csv_fragment(task: _Task, gamma: np.ndarray, azimuth: np.ndarray, r: schemes.Result) -> str:
    """CSV lines of the per-direction rows, byte-identical to :func:`format_rows`.

    One %-format per chunk (``'%.10g' % x`` is ``f"{x:.10g}"``), about 1.5x faster than
    formatting value by value.
    """
    head = _csv_cells([r.scheme.name, *task.cells, float(task.ratio), float(task.fov)]).replace("%", "%%")
    cols = [_column(c) for c in (gamma, azimuth, r.M_x, r.M_z, r.S)] + [("%d", r.maps_used.tolist())] + [_column(c) for c in (r.n_prime, r.eta)]
    f = [c[0] for c in cols]
    line = f"{head},{f[0]},{f[1]},{f[2]},{f[3]},{f[4]},{f[5]},{f[6]},{f[7]}\n"
    return "".join([line % row for row in zip(*(c[1] for c in cols))])


# ---- execution ------------------------------------------------------------------------

Progress = Callable[[int, int], None]


class Task(Protocol):
    """One chunk's work: small, picklable (sent to processes or Dask workers)."""

    def compute(self) -> Any:
        """The chunk's payload."""


class Plan(Protocol):
    """What :func:`execute` runs: a planned grid split into chunks.

    :class:`Grid` (``aliasing sweep``) and :class:`aliasing.raster.validate.ValidationGrid`
    (``aliasing validate --grid``) are plans.  ``payload_kind(fmt)`` says how the chunks
    are kept for an output format: ``csv`` / ``json`` (text), ``arrays`` (``.npz``) or
    ``rows`` (a list of row dicts, kept as JSON lines).
    """

    formats: ClassVar[tuple[str, ...]]

    @property
    def chunks(self) -> int: ...
    @property
    def size(self) -> int: ...
    def chunk(self, index: int, kind: str) -> Task: ...
    def payload_kind(self, fmt: str) -> str: ...
    def parameters(self) -> dict: ...
    def digest(self, fmt: str) -> str: ...
    def command(self, fmt: str = "csv") -> str: ...
    def describe(self) -> str: ...
    def assemble(self, payload_kind: str, fmt: str, payloads: Iterable[object]) -> Iterator[str | bytes]: ...
    def table(self, payloads: Sequence[object], command: str | None = None) -> SweepTable: ...
    def timing(self, kind: str, sample: int = 500) -> tuple[list[tuple[Task, int]], str]: ...


def run_task(task: Task) -> Any:
    """``task.compute()``: the function sent to worker processes and Dask workers."""
    return task.compute()


def _run_chunks(grid: Plan, kind: str, todo: Sequence[int], done: Callable[[int, object], None], jobs: int, dask: str | None) -> None:
    """Compute the chunks ``todo`` in-process, in ``jobs`` processes or on Dask; ``done`` each."""
    if dask:
        _run_dask(grid, kind, todo, done, dask)
        return
    if jobs == 1 or len(todo) <= 1:
        for i in todo:
            done(i, grid.chunk(i, kind).compute())
        return
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    pending: dict = {}
    queue = iter(todo)
    ex = ProcessPoolExecutor(max_workers=jobs)
    try:
        while True:
            for i in itertools.islice(queue, 2 * jobs - len(pending)):
                pending[ex.submit(run_task, grid.chunk(i, kind))] = i
            if not pending:
                break
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            for fut in sorted(finished, key=pending.__getitem__):
                done(pending.pop(fut), fut.result())
    finally:
        ex.shutdown(wait=True, cancel_futures=True)


DASK_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler before giving up."""


def _run_dask(grid: Plan, kind: str, todo: Sequence[int], done: Callable[[int, object], None], address: str) -> None:
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ValueError("dask: --dask needs the optional extra: pip install 'aliasing[dask]'") from None
    from distributed.comm.addressing import parse_address, parse_host_port

    try:  # a malformed address would leave distributed's half-made Client hanging at exit
        scheme, location = parse_address(str(address))
        if scheme in ("tcp", "tls"):
            parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"dask: malformed scheduler address {address!r} ({exc}); expected e.g. tcp://host:8786") from None
    try:
        client = Client(address, timeout=DASK_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise ValueError(f"dask: cannot reach a Dask scheduler at {address!r}: {exc}".splitlines()[0]) from None
    try:
        workers = max(1, sum(client.nthreads().values()))
        queue = iter(todo)
        index: dict = {}

        def submit(i: int):
            fut = client.submit(run_task, grid.chunk(i, kind), pure=False)
            index[fut.key] = i
            return fut

        stream = as_completed([submit(i) for i in itertools.islice(queue, 2 * workers)], loop=client.loop)
        for fut in stream:
            i = index.pop(fut.key)
            done(i, fut.result())
            fut.release()
            nxt = next(queue, None)
            if nxt is not None:
                stream.add(submit(nxt))
    finally:
        client.close()


def _workdir(out: Path) -> Path:
    return out.with_name(out.name + ".parts")


def _check_out(out: str | os.PathLike) -> Path:
    target = Path(out)
    if target.is_dir():
        raise ValueError(f"out {str(target)!r} is a folder; give a file name")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise ValueError(f"out {str(target)!r}: folder {str(folder)!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK) or (target.exists() and not os.access(target, os.W_OK)):
        raise ValueError(f"out {str(target)!r} cannot be written (permission denied)")
    return target


def _atomic_bytes(data: bytes, target: Path) -> None:
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


_EXT = {"csv": "csv", "json": "json", "arrays": "npz", "rows": "jsonl"}


def _payload_bytes(kind: str, payload: object) -> bytes:
    if kind == "arrays":
        buf = io.BytesIO()
        np.savez(buf, **payload)  # type: ignore[arg-type]
        return buf.getvalue()
    if kind == "rows":  # exact: JSON keeps every float's repr (NaN and inf too), ints and bools
        return "".join(json.dumps(row) + "\n" for row in payload).encode()  # type: ignore[attr-defined]
    return str(payload).encode()


def _payload_load(kind: str, path: Path) -> object:
    if kind == "arrays":
        with np.load(path, allow_pickle=False) as data:
            return {key: data[key] for key in data.files}
    if kind == "rows":
        return [json.loads(line) for line in path.read_text().splitlines()]
    return path.read_bytes()  # UTF-8 text, copied into the output as it is


def _open_workdir(grid: Plan, fmt: str, out: Path, resume: bool, kind: str) -> tuple[Path, set[int]]:
    """Create or reopen ``<out>.parts``; the chunks already finished there."""
    from . import __version__

    work = _workdir(out)
    digest = grid.digest(fmt)
    manifest = work / "manifest.json"
    if work.exists():
        try:
            old = json.loads(manifest.read_text())
        except (OSError, ValueError):
            raise ValueError(f"resume: {str(work)!r} is not a sweep work directory (no readable manifest.json); remove it") from None
        if not resume:
            raise ValueError(f"out {str(out)!r}: an interrupted sweep left {str(work)!r}; pass --resume to continue it, or remove it")
        if old.get("digest") != digest:
            raise ValueError(f"resume: {str(work)!r} belongs to a different sweep (its parameters differ); remove it or rerun that sweep")
    else:
        try:
            work.mkdir()
        except OSError as exc:
            raise ValueError(f"out {str(out)!r} cannot be written: {exc.strerror}") from None
        doc = {"aliasing": __version__, "digest": digest, "format": fmt, "chunks": grid.chunks, "parameters": grid.parameters(), "command": grid.command(fmt)}
        _atomic_bytes((json.dumps(doc, indent=1) + "\n").encode(), manifest)
    ext = _EXT[kind]
    finished = {int(p.stem) for p in work.glob(f"*.{ext}") if p.stem.isdigit() and int(p.stem) < grid.chunks}
    return work, finished


def execute(
    grid: Plan,
    fmt: str = "csv",
    out: str | os.PathLike | None = None,
    *,
    jobs: int = 1,
    dask: str | None = None,
    resume: bool = False,
    progress: Progress | None = None,
    command: str | None = None,
    on_payloads: Callable[[list], None] | None = None,
) -> str | Path:
    """Run a planned sweep chunk by chunk; write ``out`` (atomically) or return the text.

    With ``out``, every finished chunk is saved (atomically) in the work directory
    ``<out>.parts`` beside it, with a ``manifest.json`` holding a hash of the sweep; the
    output is assembled and atomically put in place at the end and the work directory
    removed.  A failed or interrupted run leaves the work directory (and any existing
    output untouched); ``resume=True`` continues it without recomputing finished chunks,
    and refuses a work directory of a different sweep.  The output is byte-identical
    whatever ``jobs``, ``dask`` and interruptions.

    Parameters
    ----------
    grid : Plan
        From :func:`plan`, or a validation grid from :func:`aliasing.raster.validate.plan`.
    fmt : str
        Output format, one of ``grid.formats``: csv, json, netcdf (needs ``out`` and the
        ``xarray`` extra); validation grids also write a text table.
    out : path, optional
        Output file; without it the text is returned (no work directory, no resume).
    jobs : int
        Local processes.
    dask : str, optional
        Address of a running Dask scheduler to compute the chunks on instead.
    resume : bool
        Continue the work directory of an interrupted run of the same sweep.
    progress : callable, optional
        ``progress(done, total)`` after each chunk (an exception from it stops the run,
        keeping the finished chunks).
    command : str, optional
        The command line, stored in NetCDF attributes.
    on_payloads : callable, optional
        Called with the list of every chunk's payload, in order, once all are done and
        before the output is written (resumed chunks included), e.g. to check the rows of
        a validation grid; for small payloads only (it holds them all in memory).

    Returns
    -------
    str or Path
        The text (without ``out``) or the path written.

    Example
    -------
    >>> g = plan("P", f_over_n=100, fov=60, light="overhead,behind")
    >>> print(execute(g), end="")
    scheme,f_over_n,fov,gamma,azimuth,M_x,M_z,S,maps,n_prime,eta
    P,100,60,90,0,10,8.573651497,85.73651497,1,11,0
    P,100,60,180,0,100,100,10000,1,inf,-1
    """
    kind = check.choice(fmt, "format", grid.formats)
    jobs = check.jobs(jobs)
    if kind == "netcdf" and out is None:
        raise ValueError("format netcdf needs an output file (--out)")
    if resume and out is None:
        raise ValueError("resume needs an output file (--out): the work directory sits beside it")
    if kind == "netcdf":
        import_xarray()
    payload_kind = grid.payload_kind(kind)
    total = grid.chunks
    results: dict[int, object] = {}
    work: Path | None = None
    target = _check_out(out) if out is not None else None
    finished: set[int] = set()
    if target is not None:
        work, finished = _open_workdir(grid, kind, target, resume, payload_kind)
    count = len(finished)
    if progress and count:
        progress(count, total)

    def done(i: int, payload: object) -> None:
        nonlocal count
        if work is not None:
            _atomic_bytes(_payload_bytes(payload_kind, payload), work / f"{i:06d}.{_EXT[payload_kind]}")
        else:
            results[i] = payload
        count += 1
        if progress:
            progress(count, total)

    try:
        _run_chunks(grid, payload_kind, [i for i in range(total) if i not in finished], done, jobs, dask)
    except BaseException:
        if work is not None and count == 0:  # nothing worth keeping: leave no work directory
            shutil.rmtree(work, ignore_errors=True)
        raise

    def load(i: int) -> object:
        if work is None:
            return results[i]
        return _payload_load(payload_kind, work / f"{i:06d}.{_EXT[payload_kind]}")

    payloads: Iterable[object] = (load(i) for i in range(total))
    if on_payloads is not None or kind == "netcdf":
        payloads = list(payloads)
        if on_payloads is not None:
            on_payloads(payloads)
    if target is None:
        return "".join(str(part) for part in grid.assemble(payload_kind, kind, payloads))
    if kind == "netcdf":
        _write_netcdf(grid.table(payloads, command or grid.command(kind)), target)  # type: ignore[arg-type]
    else:
        _write_text_stream(grid.assemble(payload_kind, kind, payloads), target)
    shutil.rmtree(work)  # type: ignore[arg-type]
    return target


def _assemble_stream(grid: Grid, payload_kind: str, fmt: str, payloads: Iterable[object]) -> Iterator[str | bytes]:
    """The output in pieces: text, or the bytes of chunk files as they are (UTF-8)."""
    if payload_kind == "arrays":  # summary rows (small)
        yield format_rows(SweepTable._from_payloads(grid, list(payloads)).rows(), fmt)
        return
    header = _with_cells(dict.fromkeys(ROW_FIELDS), grid.chunk(0, fmt))
    if fmt == "csv":
        yield _csv_cells(list(header)) + "\n"
        yield from payloads  # type: ignore[misc]
        return
    yield "[\n"
    first = True
    for text in payloads:
        if text:
            if not first:
                yield ",\n"
            yield text  # type: ignore[misc]
            first = False
    yield "\n]\n"


def _write_text_stream(parts: Iterable[str | bytes], target: Path) -> None:
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as handle:
            for part in parts:
                handle.write(part.encode() if isinstance(part, str) else part)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def import_xarray() -> types.ModuleType:
    """The ``xarray`` module; ValueError naming the optional extra to install if it is missing."""
    try:
        import xarray
    except ImportError:
        raise ValueError("format netcdf needs the optional extra: pip install 'aliasing[xarray]'") from None
    return xarray


def _write_netcdf(table: SweepTable, target: Path) -> None:
    ds = table.to_xarray()
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine=_netcdf_engine())
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _netcdf_engine() -> str:
    import importlib.util

    for module, engine in (("netCDF4", "netcdf4"), ("h5netcdf", "h5netcdf")):
        if importlib.util.find_spec(module):
            return engine
    raise ValueError("format netcdf needs netCDF4 or h5netcdf: pip install 'aliasing[xarray]'")


def estimate(grid: Plan, fmt: str = "csv", jobs: int = 1, sample: int = 500) -> float:
    """Estimated wall time [s] of :func:`execute`, from timing a few chunks (``grid.timing``).

    For a sweep :class:`Grid`, ``sample`` directions of at most 8 scheme variants (spread
    over the axis; the others are assumed to cost the mean); for a validation grid, one
    validation of at most 8 schemes.  The first timed chunk runs once more before, to warm
    up.  Process start-up and file writing are not included.

    Example
    -------
    >>> seconds = estimate(plan("P,LogP", light="hemisphere:100000"), jobs=2)
    >>> 0 < seconds < 600
    True
    """
    return _estimate(grid, fmt, jobs, sample)[0]


def _estimate(grid: Plan, fmt: str, jobs: int, sample: int = 500) -> tuple[float, str]:
    import time

    jobs = check.jobs(jobs)
    kind = grid.payload_kind(check.choice(fmt, "format", grid.formats))
    if isinstance(sample, bool) or not isinstance(sample, (int, np.integer)) or sample < 1:
        raise ValueError(f"sample must be a whole number >= 1 (directions timed per scheme), got {sample!r}")
    tasks, note = grid.timing(kind, int(sample))
    tasks[0][0].compute()  # warm-up
    per: list[float] = []
    for task, evaluations in tasks:
        t0 = time.perf_counter()
        task.compute()
        per.append((time.perf_counter() - t0) / evaluations)
    per_eval = float(np.mean(per))
    return per_eval * grid.size / min(jobs, grid.chunks), note


def _duration(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"
    minutes, sec = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes:02d} min" if hours else f"{minutes} min {sec:02d} s"


def dry_run(grid: Plan, fmt: str = "csv", jobs: int = 1) -> str:
    """The grid size and a time estimate, as printed by ``aliasing sweep --dry-run``.

    Example
    -------
    >>> print(dry_run(plan("P,LogP", light="hemisphere:1000")).splitlines()[0])
    grid: 2 schemes × 1 f/n × 1 fov × 1000 directions = 2,000 evaluations in 2 chunks
    """
    seconds, note = _estimate(grid, fmt, jobs)
    return f"{grid.describe()}\nestimated time: {_duration(seconds)} with {jobs} job{'s' if jobs > 1 else ''} ({note})\n"


# ---- the table object -----------------------------------------------------------------


class SweepTable:
    """A finished sweep in memory: rows, pandas, xarray.

    ``S`` and the per-map arrays are kept per scheme variant with shape
    ``(f/n, fov, directions[, maps])``.  Build it with :func:`table` (also reachable as
    ``aliasing.sweep(...)``).

    Example
    -------
    >>> t = table("P,ZP3+P", f_over_n=[10, 100], fov=60, light="hemisphere:4")
    >>> len(t), t.rows()[0]["scheme"], t.to_xarray()["S"].dims
    (16, 'P', ('scheme', 'f_over_n', 'fov', 'direction'))
    """

    def __init__(self, grid: Grid, data: list[dict[str, np.ndarray]], command: str | None = None) -> None:
        self.grid = grid
        self.data = data
        self.command = command or grid.command()

    @classmethod
    def _from_payloads(cls, grid: Grid, payloads: list, command: str | None = None) -> SweepTable:
        _, nr, nf, _ = grid.shape
        per = nr * nf * grid.blocks
        data = []
        for v in range(len(grid.variants)):
            chunk = payloads[v * per : (v + 1) * per]
            merged = {}
            for key in chunk[0]:
                arr = np.concatenate([c[key] for c in chunk])  # blocks in order, per (r, f)
                merged[key] = arr.reshape((nr, nf, -1) + arr.shape[1:])
            data.append(merged)
        return cls(grid, data, command)

    def __len__(self) -> int:
        v, r, f, n = self.grid.shape
        return v * r * f if self.grid.summary else self.grid.size

    def rows(self) -> list[dict]:
        """Rows as :func:`sweep` gives them (plus a column per swept rule option)."""
        g = self.grid
        gamma, azimuth = geometry.direction_angles(g.directions)
        rows: list[dict] = []
        for var, d in zip(g.variants, self.data):
            task = _Task(0, "", var.name, var.options, g.columns, g._cells(var), g.near, 0.0, 0.0, g.directions)
            maps = d["M_x"].shape[-1]
            sch = schemes.parse(var.name)
            for r, ratio in enumerate(g.f_over_n):
                for f, fv in enumerate(g.fov):
                    res = schemes.Result(sch, d["M_x"][r, f], d["M_z"][r, f], d["S"][r, f], d["n_prime"][r, f], d["eta"][r, f], maps)
                    new = [_summary_row(sch.name, ratio, fv, res)] if g.summary else _direction_rows(sch.name, ratio, fv, gamma, azimuth, res)
                    rows.extend(_with_cells(row, task) for row in new)
        return rows

    def format(self, fmt: str = "csv") -> str:
        """CSV or JSON text, the bytes ``aliasing sweep`` writes."""
        return format_rows(self.rows(), fmt)

    def attributes(self) -> dict:
        """Attributes of :meth:`to_xarray` (and NetCDF files): toolkit version, command, parameters (JSON)."""
        from . import __version__

        return {"aliasing_version": __version__, "command": self.command, "parameters": json.dumps(self.grid.parameters())}

    def to_pandas(self):
        """A ``pandas.DataFrame`` of :meth:`rows` (needs pandas)."""
        import pandas as pd

        return pd.DataFrame(self.rows())

    def to_xarray(self):
        """An ``xarray.Dataset`` with dims scheme, f_over_n, fov, direction (and map).

        Per-map variables (M_x, M_z, n_prime, eta) have a ``map`` dimension padded with NaN
        up to the largest number of maps; attributes hold every parameter, the toolkit
        version and the command.  In summary mode the variables are S_min, S_max,
        S_max_over_min and S_mean over the directions.
        """
        xr = import_xarray()
        g = self.grid
        gamma, azimuth = geometry.direction_angles(g.directions)
        kmax = max(d["M_x"].shape[-1] for d in self.data)
        coords: dict = {"scheme": [v.label for v in g.variants], "f_over_n": list(g.f_over_n), "fov": list(g.fov)}
        coords["scheme_name"] = ("scheme", [v.name for v in g.variants])
        coords["maps"] = ("scheme", [d["M_x"].shape[-1] for d in self.data])
        for key, column in zip(g.param_names, g.columns):
            coords[column] = ("scheme", [float(dict(v.options).get(key, np.nan)) for v in g.variants])
        S = np.stack([d["S"] for d in self.data])
        attrs = self.attributes()
        attrs.update(near=g.near, light=",".join(g.light), summary=int(g.summary), block=g.block)
        attrs.update(units_fov="degrees (full field of view)", units_gamma="degrees", units_S="image areas (unit resolutions)")
        if g.summary:
            s_min, s_max = S.min(axis=-1), S.max(axis=-1)
            data = {"S_min": (("scheme", "f_over_n", "fov"), s_min), "S_max": (("scheme", "f_over_n", "fov"), s_max),
                    "S_max_over_min": (("scheme", "f_over_n", "fov"), s_max / s_min), "S_mean": (("scheme", "f_over_n", "fov"), S.mean(axis=-1))}
            coords["directions"] = len(g.directions)
            return xr.Dataset(data, coords=coords, attrs=attrs)
        coords.update(direction=np.arange(len(g.directions)), gamma=("direction", gamma), azimuth=("direction", azimuth), map=np.arange(kmax))
        dims = ("scheme", "f_over_n", "fov", "direction", "map")
        data = {"S": (dims[:4], S)}
        for key in ("M_x", "M_z", "n_prime", "eta"):
            padded = np.full(S.shape + (kmax,), np.nan)
            for i, d in enumerate(self.data):
                padded[i, ..., : d[key].shape[-1]] = d[key]
            data[key] = (dims, padded)
        return xr.Dataset(data, coords=coords, attrs=attrs)


def table(
    schemes: str | Iterable[str],
    f_over_n: ArrayLike | str = (1000.0,),
    fov: ArrayLike | str = (60.0,),
    light: str | Sequence[str] | ArrayLike = "overhead",
    *,
    k: ArrayLike | str | None = None,
    params: dict | None = None,
    near: float = 1.0,
    summary: bool = False,
    block: int = DEFAULT_BLOCK,
    jobs: int = 1,
    dask: str | None = None,
    progress: Progress | None = None,
) -> SweepTable:
    """Run a sweep grid in memory and return a :class:`SweepTable` (``.to_pandas()``, ``.to_xarray()``).

    Parameters are those of :func:`plan` (every axis a number, list or range text) and
    of :func:`execute` (``jobs``, ``dask``, ``progress``).  Also callable as
    ``aliasing.sweep(...)``.

    Example
    -------
    >>> import aliasing
    >>> t = aliasing.sweep("LogP", f_over_n="10:1000:log:3", fov=60, light="overhead", k=[1, 5], summary=True)
    >>> [(r["scheme"], r["f_over_n"], round(r["S_min"], 2)) for r in t.rows()][-1]
    ('ZP5+LogP', 1000.0, 5.98)
    """
    grid = plan(schemes, f_over_n, fov, light, k=k, params=params, near=near, summary=summary, block=block)
    return grid.table(collect(grid, "arrays", jobs=jobs, dask=dask, progress=progress))


def collect(grid: Plan, kind: str, *, jobs: int = 1, dask: str | None = None, progress: Progress | None = None) -> list:
    """Every chunk's payload of ``kind``, in order, computed in memory (no work directory).

    Parameters
    ----------
    grid : Plan
        A sweep :class:`Grid` or a validation grid.
    kind : str
        Payload kind (``arrays`` for a :class:`Grid`'s table, ``rows`` for a validation grid).
    jobs, dask, progress
        As in :func:`execute`.

    Example
    -------
    >>> payloads = collect(plan("P,LogP", light="overhead"), "arrays", jobs=1)
    >>> len(payloads), sorted(payloads[0])
    (2, ['M_x', 'M_z', 'S', 'eta', 'n_prime'])
    """
    jobs = check.jobs(jobs)
    kind = check.choice(kind, "payload kind", _EXT)
    payloads: dict[int, object] = {}
    total = grid.chunks

    def done(i: int, payload: object) -> None:
        payloads[i] = payload
        if progress:
            progress(len(payloads), total)

    _run_chunks(grid, kind, list(range(total)), done, jobs, dask)
    return [payloads[i] for i in range(total)]


def _load_toml(path: str | os.PathLike) -> dict:
    try:
        import tomllib
    except ImportError:  # Python 3.10
        try:
            import tomli as tomllib  # type: ignore[no-redef]
        except ImportError:
            raise ValueError(f"config {str(path)!r}: reading TOML needs Python >= 3.11 (or: pip install tomli)") from None
    try:
        with open(path, "rb") as handle:
            return tomllib.load(handle)
    except OSError as exc:
        raise ValueError(f"config {str(path)!r} cannot be read: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"config {str(path)!r} is not valid TOML: {exc}".splitlines()[0]) from None


_NUM = "a number, a list of numbers or a range string"
CONFIG_KEYS: dict[str, tuple[tuple[type, ...], str]] = {
    "schemes": ((str, list), "a string or a list of strings"),
    "k": ((int, list, str), "a whole number, a list or a range string"),
    "f_over_n": ((int, float, list, str), _NUM),
    "fov": ((int, float, list, str), _NUM),
    "light": ((str, list), "a string or a list of strings"),
    "near": ((int, float), "a number"),
    "params": ((dict,), "a table of option = values"),
    "summary": ((bool,), "true or false"),
    "format": ((str,), "a string"),
    "out": ((str,), "a string"),
    "block": ((int,), "a whole number"),
    "jobs": ((int,), "a whole number"),
    "dask": ((str,), "a string"),
}
"""Keys of a sweep config file, the TOML types each takes, and how to say it."""


def read_config(path: str | os.PathLike) -> dict:
    r"""A sweep's TOML config: keys :data:`CONFIG_KEYS`; ValueError on unknown keys or types.

    Example
    -------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep.toml"
    >>> _ = path.write_text('schemes = ["P", "LogP"]\nk = [1, 5]\nf_over_n = "10:10000:log:7"\n[params]\nc_fraction = [0.2, 0.4]\n')
    >>> read_config(path)["f_over_n"]
    '10:10000:log:7'
    >>> _ = path.write_text('schemes = "P"\nfovv = 60\n')
    >>> read_config(path)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: config '...sweep.toml': unknown key 'fovv'; allowed: schemes, k, f_over_n, fov, light, near, params, summary, format, out, block, jobs, dask
    """
    doc = _load_toml(path)
    where = f"config {str(path)!r}"
    for key, value in doc.items():
        if key not in CONFIG_KEYS:
            raise ValueError(f"{where}: unknown key {key!r}; allowed: {', '.join(CONFIG_KEYS)}")
        types, says = CONFIG_KEYS[key]
        bad = isinstance(value, bool) and bool not in types
        if bad or not isinstance(value, types):
            raise ValueError(f"{where}: key {key!r} must be {says}, got {type(value).__name__} {value!r}")
        items = value if isinstance(value, list) else []
        if key in ("schemes", "light") and not all(isinstance(v, str) for v in items):
            raise ValueError(f"{where}: key {key!r} must be {says}, got {value!r}")
        if key in ("f_over_n", "fov", "k") and any(isinstance(v, bool) or not isinstance(v, (int, float, str)) for v in items):
            raise ValueError(f"{where}: key {key!r} must be {says}, got {value!r}")
        if key == "params":
            for name, v in value.items():
                if isinstance(v, bool) or not isinstance(v, (int, float, str, list)):
                    raise ValueError(f"{where}: params.{name} must be {_NUM}, got {v!r}")
    return doc


def progress_bar(stream: TextIO | None = None, width: int = 30) -> Progress | None:
    """A one-line ``\\r`` progress bar on ``stream`` (stderr) if it is a terminal, else None.

    Example
    -------
    >>> import io
    >>> progress_bar(io.StringIO()) is None  # not a terminal: quiet
    True
    """
    import time

    out = stream if stream is not None else sys.stderr
    try:
        if not out.isatty():
            return None
    except (AttributeError, ValueError):
        return None
    start = time.monotonic()
    first: list[int] = []

    def show(done: int, total: int) -> None:
        if not first:
            first.append(done)
        frac = done / total if total else 1.0
        filled = int(round(width * frac))
        elapsed = time.monotonic() - start
        fresh = done - first[0]
        left = f", {_duration(elapsed / fresh * (total - done))} left" if fresh and done < total else ""
        out.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} chunks {100 * frac:3.0f}%{left}   ")
        if done >= total:
            out.write("\n")
        out.flush()

    return show


def run_command(
    grid: Plan,
    fmt: str,
    out: str | os.PathLike | None,
    *,
    name: str,
    jobs: int = 1,
    dask: str | None = None,
    resume: bool = False,
    command: str | None = None,
    on_payloads: Callable[[list], None] | None = None,
) -> int:
    """:func:`execute` for a command line; returns the exit status.

    A progress bar on stderr if it is a terminal; without ``out`` the text goes to stdout;
    Ctrl-C stops with a line saying where the finished chunks are kept, and status 130.
    ``name`` is the subcommand (``sweep``, ``validate``) for that line.  Errors
    (``ValueError``) propagate: ``aliasing.cli.main`` prints them as one line, status 2.

    Example
    -------
    >>> run_command(plan("P", f_over_n=100, light="behind"), "csv", None, name="sweep")
    scheme,f_over_n,fov,gamma,azimuth,M_x,M_z,S,maps,n_prime,eta
    P,100,60,180,0,100,100,10000,1,inf,-1
    0
    """
    try:
        result = execute(grid, fmt, out, jobs=jobs, dask=dask, resume=resume, progress=progress_bar(sys.stderr), command=command, on_payloads=on_payloads)
    except KeyboardInterrupt:
        kept = f"; finished chunks are kept in {out}.parts: rerun with --resume" if out is not None else ""
        print(f"\naliasing {name}: interrupted{kept}", file=sys.stderr)
        return 130
    if out is None:
        sys.stdout.write(str(result))
    return 0


class _CallableModule(types.ModuleType):
    """This module, callable: ``aliasing.sweep(...)`` is :func:`table`."""

    def __call__(self, *args, **kwargs) -> SweepTable:
        return table(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
