"""The sweep grid: axes from numbers, lists and ranges; scheme variants; light specs; chunks.

A :class:`Grid` is the product scheme variants × f/n × fov × aspect × light directions, split
into chunks of one variant, one f/n, one fov, one aspect and a block of directions;
:func:`compute_chunk` evaluates one chunk (vectorized).  The aspect axis (image width/height,
:class:`aliasing.View`) is the single value 1 unless asked for; only then does it show in
the output, the parameters and the command (:func:`~aliasing.sweep.rows.aspect_shown`), so
that a square sweep's output and manifest are what they were before views had an aspect.
"""

from __future__ import annotations

import hashlib
import inspect
import itertools
import json
import math
import re
import shlex
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from .. import _validation as check
from .._version import __version__
from .. import geometry, schemes, warping
from ..view import check_aspect
from . import limits
from .limits import split_lights  # noqa: F401  (re-exported: part of this module's API)
from .tables import SweepTable, _assemble_stream
from .chunks import _Batch, _Task, compute_chunk  # noqa: F401 - compute_chunk: part of this module's API before the split
from .rows import SQUARE, aspect_shown, refuse_square_only


RANGE = "START:STOP:lin|log:COUNT"
OUTPUT_FORMATS = ("csv", "json", "netcdf", "parquet")
MAX_COUNT = 100_000_000
"""Most values one range may give (800 MB of float64), whatever the memory limit."""
DEFAULT_BLOCK = 20_000
"""Light directions per chunk: large enough to amortise the per-call cost, small enough that
the (N, k, 8) arrays of ZP schemes stay in cache-friendly sizes (see benchmarks/README.md)."""


MAX_BATCH = 4
"""Most chunks evaluated together (one ``evaluate_many``).  Four keep a batch's peak memory
within :mod:`~aliasing.sweep.limits`' model of one chunk (measured with tracemalloc: four
ZP8+P schemes on 20,000 directions 30.5 MiB against the model's 78 MiB for one; four single
maps 4.9 against 9.8 MiB), so the refusal before allocating stays sound."""


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
        items: list = [s.strip() for s in value.split(",")]
        if any(items) and not all(items):
            raise ValueError(f"{name} has an empty item in {value!r} (two commas, or a comma at an end)")
        items = [s for s in items if s]
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
    bad = next((v for v in out if not math.isfinite(v)), None)
    if bad is not None:
        raise ValueError(f"{name} must be finite, got {bad}")
    return tuple(out)


def _range(text: str, name: str) -> list[float]:
    parts = [p.strip() for p in text.split(":")]
    try:
        if len(parts) != 4 or parts[2].lower() not in ("lin", "log"):
            raise ValueError
        start, stop, count = float(parts[0]), float(parts[1]), int(parts[3])
    except ValueError:
        ratio = " (a width:height such as 16:9 is written as its quotient, e.g. 1.777777778)" if "aspect" in name and len(parts) == 2 else ""
        raise ValueError(f"{name}: malformed range {text!r}; expected {RANGE}, e.g. 10:10000:log:7{ratio}") from None
    if count < 1:
        raise ValueError(f"{name}: range {text!r} has COUNT {count}; it must be >= 1 (the sweep grid would be empty)")
    if count > MAX_COUNT:
        raise ValueError(f"{name}: range {text!r} has COUNT {count}; it must be <= {MAX_COUNT:,} (see --max-memory)")
    for end, v in (("START", start), ("STOP", stop)):
        if not math.isfinite(v):
            raise ValueError(f"{name}: range {text!r}: {end} must be finite, got {v}")
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
        """Unique label, e.g. ``eta[eta=-0.5]``."""
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
    ['P', 'ZP5+P', 'eta[eta=-1]', 'eta[eta=0]', 'ZP5+eta[eta=-1]', 'ZP5+eta[eta=0]']
    """
    listed = check.names(names, "schemes")
    if any(listed) and not all(listed):
        raise ValueError(f"schemes has an empty item in {names!r} (two commas, or a comma at an end)")
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
            raise ValueError(f"param {key!r} is swept by the grid itself (f_over_n, fov, aspect, light), not a rule option")
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


def expand_lights(light: str | Sequence[str] | ArrayLike, *, angles: bool = False) -> tuple:
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
        spec_tuple = ("vectors:" + _digest_bytes(np.ascontiguousarray(lv).tobytes())[:16],)
        return (spec_tuple, lv, np.stack(geometry.direction_angles(lv), axis=-1)) if angles else (spec_tuple, lv)
    if not specs:
        raise ValueError("light is empty: the sweep grid has no directions")
    blocks, typed = [], []
    for spec in specs:
        text = spec.lower()
        kind, _, rest = text.partition(":")
        g_text, _, a_text = rest.partition("@")
        key, _, az = a_text.partition(":")
        for label, part in (("light gamma", g_text if kind == "gamma" else ""), ("light azimuth", az if key == "azimuth" else "")):
            for token in re.split(r"[,:]", part):  # ±inf and NaN by their names, before any arithmetic
                try:
                    number = float(token)
                except ValueError:
                    continue
                if not math.isfinite(number):
                    raise ValueError(f"{label} must be finite, got {number}")
        if kind == "gamma" and (":" in g_text or ":" in a_text.partition(":")[2] or "," in rest):
            if a_text and key != "azimuth":
                raise ValueError(f"malformed light {spec!r}; expected gamma:DEG|RANGE[@azimuth:DEG|RANGE]")
            g = np.array(grid_values(g_text, "light gamma"))
            a = np.array(grid_values(az, "light azimuth") if a_text else (0.0,))
            blocks.append(geometry.light_direction(g[:, None], a[None, :]).reshape(-1, 3))
            typed.append(np.stack(np.broadcast_arrays(g[:, None], a[None, :]), axis=-1).reshape(-1, 2))
        else:
            blocks.append(geometry.lights(spec))
            typed.append(np.stack(geometry._typed_angles(spec), axis=-1))
    if angles:  # (N, 2): γ and azimuth as typed, for the output (not recomputed from the vectors)
        return tuple(specs), np.concatenate(blocks), np.concatenate(typed)
    return tuple(specs), np.concatenate(blocks)


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
    """A planned sweep: the product scheme variants × f/n × fov × aspect × light directions.

    Build it with :func:`plan`; it is split into chunks of one variant, one f/n, one fov,
    one aspect and a block of at most ``block`` directions.  Chunks are numbered by f/n,
    fov, aspect, block and then variant, so that the chunks of the same directions are
    neighbours (a batch, :meth:`batches`); the output is in row order, variant first
    (:meth:`output_order`).  With the default aspect axis (the single value 1) the numbering
    is the one of a grid without aspect.
    """

    variants: tuple[Variant, ...]
    f_over_n: tuple[float, ...]
    fov: tuple[float, ...]
    light: tuple[str, ...]
    directions: np.ndarray = field(repr=False, compare=False)
    near: float = 1.0
    summary: bool = False
    block: int = DEFAULT_BLOCK
    angles: np.ndarray | None = field(default=None, repr=False, compare=False)  # (N, 2) γ, azimuth as typed
    aspect: tuple[float, ...] = SQUARE  # image width/height of the views

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
    def aspect_shown(self) -> bool:
        """Whether the aspect axis shows (a column, a parameter): any axis but the single value 1."""
        return aspect_shown(self.aspect)

    @property
    def shape(self) -> tuple[int, int, int, int, int]:
        """(variants, f/n values, fovs, aspects, directions)."""
        return (len(self.variants), len(self.f_over_n), len(self.fov), len(self.aspect), len(self.directions))

    @property
    def size(self) -> int:
        """Number of direction × scheme × frustum evaluations."""
        return int(np.prod(self.shape))

    @property
    def blocks(self) -> int:
        """Direction blocks per (variant, f/n, fov, aspect)."""
        return -(-len(self.directions) // self.block)

    @property
    def chunks(self) -> int:
        """Number of chunks."""
        return len(self.variants) * len(self.f_over_n) * len(self.fov) * len(self.aspect) * self.blocks

    def direction_angles(self, start: int = 0, stop: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(γ, azimuth) [deg] of directions ``start:stop``: the light specs' numbers as typed."""
        if self.angles is None:
            return geometry.direction_angles(self.directions[start:stop])
        return self.angles[start:stop, 0], self.angles[start:stop, 1]

    def chunk(self, index: int, kind: str) -> _Task:
        """The work of chunk ``index`` (0 ≤ index < :attr:`chunks`) for a payload ``kind``."""
        cell, v = divmod(index, len(self.variants))
        r, rest = divmod(cell, len(self.fov) * len(self.aspect) * self.blocks)
        f, rest = divmod(rest, len(self.aspect) * self.blocks)
        a, b = divmod(rest, self.blocks)
        var = self.variants[v]
        lo, hi = b * self.block, (b + 1) * self.block
        return _Task(index, kind, var.name, var.options, self.columns, self._cells(var), self.near, self.f_over_n[r], self.fov[f], self.directions[lo:hi], self.direction_angles(lo, hi),
                     aspect=self.aspect[a], aspect_shown=self.aspect_shown)

    def batches(self, todo: Sequence[int], workers: int = 1) -> list[list[int]]:
        """The chunks ``todo`` grouped into batches that share f/n, fov, aspect, direction block and rule options.

        A batch is evaluated at once (:func:`~aliasing.sweep.chunks.compute_batch`: light
        frames shared by its schemes), at most :data:`MAX_BATCH` chunks.  With several ``workers``, batches are halved until there
        are at least two per worker (or single chunks), so that every worker has work.

        Example
        -------
        >>> g = plan("P,LogP,ZP3", light="hemisphere:30", block=10)
        >>> g.batches(range(g.chunks))
        [[0, 1, 2], [3, 4, 5], [6, 7, 8]]
        >>> g.batches([1, 2, 4], workers=2)
        [[1], [2], [4]]
        """
        groups: dict[tuple, list[int]] = {}
        for i in todo:
            cell, v = divmod(int(i), len(self.variants))
            groups.setdefault((cell, self.variants[v].options), []).append(int(i))
        out = sorted(group[i : i + MAX_BATCH] for group in groups.values() for i in range(0, len(group), MAX_BATCH))
        while len(out) < 2 * workers and any(len(b) > 1 for b in out):
            big = max(range(len(out)), key=lambda j: len(out[j]))
            half = len(out[big]) // 2
            out[big : big + 1] = [out[big][:half], out[big][half:]]
        return out

    def output_order(self) -> list[int]:
        """Chunk indices in the order of the output rows: variant, f/n, fov, aspect, block.

        Example
        -------
        >>> plan("P,LogP", light="hemisphere:30", block=10).output_order()
        [0, 2, 4, 1, 3, 5]
        """
        cells = self.chunks // len(self.variants)
        return [cell * len(self.variants) + v for v in range(len(self.variants)) for cell in range(cells)]

    def batch(self, indices: Sequence[int], kind: str) -> _Batch:
        """The work of the chunks ``indices`` (one batch of :meth:`batches`) for a payload ``kind``."""
        return _Batch(tuple(self.chunk(i, kind) for i in indices))

    def parameters(self) -> dict:
        """Every parameter of the sweep, JSON-ready (what the manifest's hash covers).

        ``aspect`` (and the aspect in ``chunk_order``) only when :attr:`aspect_shown`: a square
        sweep has the parameters, and so the digest, it had before views had an aspect
        (its interrupted runs resume), and any other aspect axis a different digest.
        """
        order = "f_over_n,fov,aspect,block,variant" if self.aspect_shown else "f_over_n,fov,block,variant"
        return {
            "chunk_order": order,  # the numbering of chunk files (work directories of other numberings are refused)
            "schemes": [v.name for v in self.variants],
            "options": [dict(v.options) for v in self.variants],
            "f_over_n": list(self.f_over_n),
            "fov": list(self.fov),
            **({"aspect": list(self.aspect)} if self.aspect_shown else {}),
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
        if self.aspect_shown:
            parts += ["--aspect", ",".join(f"{x:.10g}" for x in self.aspect)]
        parts += ["--light", ",".join(self.light), "--near", f"{self.near:.10g}", "--block", str(self.block), "--format", fmt]
        return shlex.join(parts + (["--summary"] if self.summary else []))

    def describe(self) -> str:
        """One line: the grid's axes, size and chunks."""
        v, r, f, a, n = self.shape
        aspects = f" × {a} aspect" if self.aspect_shown else ""
        return f"grid: {v} schemes × {r} f/n × {f} fov{aspects} × {n} directions = {self.size:,} evaluations in {self.chunks:,} chunks"

    def payload_kind(self, fmt: str) -> str:
        """How chunks are kept for output ``fmt``: CSV or JSON text, or arrays (summaries, NetCDF)."""
        return "arrays" if self.summary or fmt in ("netcdf", "parquet") else fmt

    def assemble(self, payload_kind: str, fmt: str, payloads: Iterable[object]) -> Iterator[str | bytes]:
        """The output text in pieces, from every chunk's payload in order."""
        return _assemble_stream(self, payload_kind, fmt, payloads)

    def table(self, payloads: Sequence[object], command: str | None = None) -> SweepTable:
        """The :class:`SweepTable` of every chunk's ``arrays`` payload, in order."""
        return SweepTable._from_payloads(self, list(payloads), command)

    def timing(self, kind: str, sample: int = 500) -> tuple[list[tuple[_Task, int]], str]:
        """Chunks to time for :func:`estimate` (``sample`` directions of up to 8 schemes), with their evaluations."""
        small = Grid(self.variants, self.f_over_n[:1], self.fov[:1], self.light, self.directions[:sample], self.near, self.summary, sample, None if self.angles is None else self.angles[:sample], self.aspect[:1])
        tasks = [(small.chunk(v, kind), len(small.directions)) for v in spread(len(self.variants))]
        return tasks, f"timed on {len(small.directions)} directions per scheme"


def plan(
    schemes: str | Iterable[str],
    f_over_n: ArrayLike | str = (1000.0,),
    fov: ArrayLike | str = (60.0,),
    light: str | Sequence[str] | ArrayLike = "overhead",
    *,
    aspect: ArrayLike | str = SQUARE,
    k: ArrayLike | str | None = None,
    params: dict | None = None,
    near: float = 1.0,
    summary: bool = False,
    block: int = DEFAULT_BLOCK,
    max_memory: int | str | None = None,
) -> Grid:
    """Validate and expand a sweep's parameters into a :class:`Grid`.

    Every axis takes a number, a list or text with ranges (:func:`grid_values`).

    Parameters
    ----------
    schemes : str or iterable of str
        Scheme names (:data:`aliasing.schemes.GRAMMAR`).
    f_over_n, fov : array_like or str
        Depth ratios far/near (> 1) and full (vertical) fields of view [deg] in (0, 180).
    light : str, sequence of str or array_like
        Light specs (:func:`expand_lights`) or vectors ``(N, 3)``.
    aspect : array_like or str
        Image width/height of the views, in (0, inf) (:class:`aliasing.View`; default: one
        square view).  Any other axis adds an ``aspect`` column after ``fov``.  A scheme
        that takes square views only (face partitions, the rules written with θ alone) is
        refused with aspect ≠ 1, before any work.
    k, params
        See :func:`expand_schemes`.
    near : float
        Near distance [world units].
    summary : bool
        One row per scheme, f/n, fov (and aspect) (min, max, max/min, mean of S̄).
    block : int
        Directions per chunk.
    max_memory : int or str, optional
        Refuse (ValueError) a request whose estimated memory exceeds this [bytes, or text
        like ``4G``], judged from its counts before anything is allocated
        (:mod:`aliasing.sweep.limits`; default :data:`~aliasing.sweep.limits.DEFAULT_MAX_MEMORY`).

    Example
    -------
    >>> g = plan("P,LogP", f_over_n="10:1000:log:3", fov=[60], light="hemisphere:100", k=[1, 5])
    >>> g.shape, g.size, g.chunks
    ((4, 3, 1, 1, 100), 1200, 12)
    >>> plan("P", aspect="1,2", light="overhead").describe()
    'grid: 1 schemes × 1 f/n × 1 fov × 2 aspect × 1 directions = 2 evaluations in 2 chunks'
    """
    limit = None if max_memory is None else limits.parse_memory(max_memory)
    limits.check_request(schemes, f_over_n, fov, light, aspect=aspect, k=k, params=params, block=block, limit=limit)  # before allocating
    variants = expand_schemes(schemes, k, params)
    ratios = grid_values(f_over_n, "f_over_n")
    check.depth_ratio(ratios)
    fovs = grid_values(fov, "fov")
    check.fov(fovs)
    aspects = grid_values(aspect, "aspect")
    check_aspect(aspects)
    specs, lv, angles = expand_lights(light, angles=True)
    if np.ndim(near) != 0:
        raise ValueError(f"near must be a single number > 0 (a distance), got an array of shape {np.shape(near)}")
    near = float(check.positive(near, "near"))
    if np.ndim(block) != 0:
        raise ValueError(f"block must be a whole number >= 1 (directions per chunk), got an array of shape {np.shape(block)}")
    if isinstance(block, bool) or int(block) != block or block < 1:
        raise ValueError(f"block must be a whole number >= 1 (directions per chunk), got {block!r}")
    refuse_square_only([(v.label, v.name, dict(v.options)) for v in variants], near, ratios[0], fovs[0], aspects, lv[:1])
    return Grid(variants, ratios, fovs, specs, lv, near, bool(summary), int(block), angles, aspects)
