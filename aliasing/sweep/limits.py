"""Refuse before allocating: the memory a sweep request needs, estimated from its counts alone.

Counts are read from the request's text (range COUNTs, ``sphere:N``, ``ZP<k>``, ``--k``)
without expanding anything, so that ``--fov 60:60:log:100000000000`` or ``--schemes
ZP99999999+P`` are refused with one line instead of being killed by the kernel.

The model (bytes): every direction's vector (3 float64, held twice: the grid and a chunk),
every axis value (a Python float in a tuple, ~40 bytes), and per worker one chunk's
evaluation: directions per chunk × maps × :data:`ARRAYS_PER_MAP` float64 (a batch of up to
:data:`aliasing.sweep.grid.MAX_BATCH` chunks evaluated together stays within it, measured).  Results kept in
memory (no ``--out``, summaries, NetCDF, :func:`aliasing.sweep.table`) add 5 float64 per
row × map.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable

import numpy as np

from .. import _validation as check

ARRAYS_PER_MAP = 64
"""Peak float64 per direction × map of one ``schemes.evaluate`` call: measured with tracemalloc
on 20,000 directions (P 64.5, LogP 65.5, ZP8+P 60.6, ZP32+P 60.1, ZP4+TSM 61.1)."""
FACE_MAPS = 5
"""Upper bound of the maps per z-partition of a face partition (FPc+ZP3+P uses up to 13 = 4.3 × 3)."""
DEFAULT_MAX_MEMORY = 4 * 2**30
"""Default limit [bytes] of a request's estimated memory (``--max-memory`` overrides it)."""
_UNITS = {"": 1, "b": 1, "k": 2**10, "kb": 2**10, "kib": 2**10, "m": 2**20, "mb": 2**20, "mib": 2**20, "g": 2**30, "gb": 2**30, "gib": 2**30, "t": 2**40, "tb": 2**40, "tib": 2**40}


def parse_memory(value: object, name: str = "max_memory") -> int:
    """A memory size in bytes from a number or text like ``4G``, ``512M``, ``1.5GiB`` (binary units).

    Example
    -------
    >>> parse_memory("4G"), parse_memory("512M"), parse_memory(1000)
    (4294967296, 536870912, 1000)
    """
    if isinstance(value, bool):
        raise ValueError(f"{name} must be a size such as 4G or 512M, got {value!r}")
    if isinstance(value, (int, float, np.integer, np.floating)):
        number, unit = float(value), ""
    else:
        if str(value).strip().lower().lstrip("+-") in ("inf", "infinity", "nan"):
            raise ValueError(f"{name} must be finite, got {value!r}")
        m = re.fullmatch(r"\s*([0-9.eE+-]+)\s*([A-Za-z]*)\s*", str(value))
        if not m or m.group(2).lower() not in _UNITS:
            raise ValueError(f"{name} must be a size such as 4G, 512M or 1.5GiB, got {value!r}")
        try:
            number, unit = float(m.group(1)), m.group(2).lower()
        except ValueError:
            raise ValueError(f"{name} must be a size such as 4G, 512M or 1.5GiB, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite, got {value!r}")
    size = number * _UNITS[unit]
    if not 1 <= size < 2**63:
        raise ValueError(f"{name} must be in [1 byte, 8 EiB), got {value!r}")
    return int(size)


def human(size: float) -> str:
    """Bytes as text with a binary unit.

    Example
    -------
    >>> human(3 * 2**30), human(1536)
    ('3.0 GiB', '1.5 KiB')
    """
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if size < 1024 or unit == "PiB":
            return f"{size:.0f} {unit}" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1024
    raise AssertionError  # pragma: no cover


def _int(text: str) -> int:
    try:
        return int(text.strip())
    except ValueError:
        return 1  # malformed: left to the full parser's message


def _max_value(value: object) -> int:
    """The largest finite number in an axis' text or list (range ends included), at least 1."""
    items = value.split(",") if isinstance(value, str) else np.atleast_1d(np.asarray(value, dtype=object)).tolist()
    best = 1.0
    for item in items:
        parts = str(item).split(":")
        for text in parts[:2] if len(parts) == 4 else parts[:1]:
            try:
                v = float(text)
            except (ValueError, OverflowError):
                continue
            if math.isfinite(v):
                best = max(best, v)
    return int(min(best, 2.0**62))


def grid_bytes(grid: object, jobs: int = 1, in_memory: bool = False) -> tuple[int, str] | None:
    """:func:`estimate_bytes` of a planned sweep grid (None for a plan without scheme variants)."""
    from .. import schemes

    variants = getattr(grid, "variants", None)
    if variants is None:
        return None
    maps = max(schemes.parse(v.name).k * (FACE_MAPS if schemes.parse(v.name).faces else 1) for v in variants)
    g = grid
    return estimate_bytes(len(variants), len(g.f_over_n), len(g.fov), len(g.directions), maps, g.block, jobs, in_memory, aspects=len(getattr(g, "aspect", (1.0,))))  # type: ignore[attr-defined]


def axis_count(value: object) -> int:
    """How many values a grid axis gives (:func:`aliasing.sweep.grid_values` syntax), without making them.

    Example
    -------
    >>> axis_count("10:10000:log:4,30"), axis_count([1, "1:2:lin:100000000000"]), axis_count(5)
    (5, 100000000001, 1)
    """
    if isinstance(value, str):
        items: Iterable = value.split(",")
    elif isinstance(value, (list, tuple)):
        items = value
    elif isinstance(value, np.ndarray):
        return int(value.size)
    else:
        return 1
    total = 0
    for item in items:
        parts = str(item).split(":") if isinstance(item, str) else []
        total += max(_int(parts[3]), 0) if len(parts) == 4 else 1
    return total


def light_count(light: object) -> int:
    """How many directions light specs give, without making them.

    Example
    -------
    >>> light_count("overhead,sphere:100000000000"), light_count("gamma:0:180:lin:19@azimuth:0:90:lin:4")
    (100000000001, 76)
    """
    if isinstance(light, str):
        try:
            specs = split_lights(light)
        except ValueError:
            return 1  # left to the full parser's message
    elif isinstance(light, (list, tuple)) and all(isinstance(s, str) for s in light):
        specs = list(light)
    else:
        return max(1, int(np.size(light)) // 3)
    total = 0
    for spec in specs:
        kind, _, rest = spec.strip().lower().partition(":")
        if kind in ("sphere", "hemisphere"):
            total += max(_int(rest), 1)
        elif kind == "gamma":
            g_text, _, a_text = rest.partition("@")
            total += axis_count(g_text) * (axis_count(a_text.partition(":")[2]) if a_text else 1)
        else:
            total += 1
    return total


def scheme_counts(names: object, k: object = None, params: dict | None = None) -> tuple[int, int]:
    """(variants, most maps of one variant) of a scheme axis, read from the names, ``k`` and ``params``.

    Example
    -------
    >>> scheme_counts("P,ZP99999999+P"), scheme_counts("P,LogP", k="1:8:lin:8", params={"c_fraction": "0:1:lin:3"})
    ((2, 99999999), (48, 8))
    """
    listed = [n for n in check.names(() if names is None else names, "schemes") if n]
    top = _max_value(k) if k is not None else 1
    most = 1
    for name in listed:
        m = re.search(r"zp\s*(\d+)", name, flags=re.IGNORECASE)
        kn = int(m.group(1)) if m else 1
        faces = FACE_MAPS if re.match(r"\s*fp", name, flags=re.IGNORECASE) else 1
        most = max(most, kn * faces * top)
    combos = 1
    for value in (params or {}).values():
        combos *= axis_count(value)
    return len(listed) * axis_count(k if k is not None else 1) * combos, most


def estimate_bytes(variants: int, ratios: int, fovs: int, directions: int, maps: int, block: int, jobs: int = 1, in_memory: bool = False, *, aspects: int = 1) -> tuple[int, str]:
    """Estimated peak bytes of a sweep, and the parameter that drives it most.

    ``aspects``: values of the aspect axis (1, the default square view, adds no term: the
    estimate of a square sweep is what it was before views had an aspect).

    Example
    -------
    >>> size, what = estimate_bytes(1, 1, 1, 100_000_000_000, 1, 20_000)
    >>> human(size), what
    ('4.4 TiB', 'light')
    """
    per_chunk = min(block, directions) * maps * ARRAYS_PER_MAP * 8 * max(jobs, 1)
    terms = {
        "light": directions * 3 * 8 * 2,
        "f_over_n": ratios * 40,
        "fov": fovs * 40,
        "schemes": per_chunk if maps > 1 else 0,
        "jobs": per_chunk if maps <= 1 else 0,
    }
    if aspects > 1:
        terms["aspect"] = aspects * 40
    if in_memory:
        axes = {"schemes": variants, "f_over_n": ratios, "fov": fovs, "aspect": aspects, "light": directions}
        biggest = max(axes, key=axes.get)  # type: ignore[arg-type]
        terms[biggest] = terms.get(biggest, 0) + variants * ratios * fovs * aspects * directions * maps * 5 * 8
    total = sum(terms.values())
    return int(total), max(terms, key=terms.get)  # type: ignore[arg-type]


def check_bytes(size: int, what: str, limit: int | None, flag: str = "--max-memory") -> None:
    """ValueError naming ``what`` and the limit when ``size`` exceeds ``limit`` (None: the default)."""
    cap = DEFAULT_MAX_MEMORY if limit is None else limit
    if size > cap:
        raise ValueError(f"{what}: this request needs about {human(size)} of memory, above the limit {human(cap)}; reduce it or raise {flag}")


def check_request(schemes: object, f_over_n: object, fov: object, light: object, *, aspect: object = 1, k: object = None, params: dict | None = None, block: int = 20_000, jobs: int = 1, in_memory: bool = False, limit: int | None = None) -> int:
    """Estimate a sweep request from its counts and refuse it above ``limit``; the estimate [bytes].

    Example
    -------
    >>> check_request("P", 1000, 60, "sphere:100000000000")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: light: this request needs about 4.4 TiB of memory, above the limit 4.0 GiB; reduce it or raise --max-memory
    """
    variants, maps = scheme_counts(schemes, k, params)
    blk = block if isinstance(block, int) and block >= 1 else 20_000
    size, what = estimate_bytes(variants, axis_count(f_over_n), axis_count(fov), light_count(light), maps, blk, jobs if isinstance(jobs, int) else 1, in_memory, aspects=axis_count(aspect))
    check_bytes(size, what, limit)
    return size


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
        The specs, stripped; an empty item (``a,,b``) is a ValueError.

    Example
    -------
    >>> split_lights("overhead, gamma:30,60@azimuth:0,90, hemisphere:10")
    ['overhead', 'gamma:30,60@azimuth:0,90', 'hemisphere:10']
    """
    if not isinstance(text, str):
        raise ValueError(f"light must be text of comma-separated specs, got {text!r}")
    out: list[str] = []
    parts = [p.strip() for p in text.split(",")]
    if any(parts) and not all(parts):
        raise ValueError(f"light has an empty item in {text!r} (two commas, or a comma at an end)")
    for part in parts:
        if not part:
            continue
        starts_spec = re.match(r"(overhead|behind|front|gamma|sphere|hemisphere)\b", part, flags=re.IGNORECASE)
        if out and out[-1].lower().startswith("gamma") and not starts_spec:
            out[-1] += "," + part
        else:
            out.append(part)
    return out
