"""Rows of a sweep as plain dicts, and their CSV/JSON text.

The small, direct API: :func:`sweep` evaluates every scheme × f/n × fov (× aspect) over the light
directions into rows (ready for ``pandas.DataFrame(rows)``); :func:`format_rows` writes
them as CSV or JSON.  Per-map quantities (M_x, M_z, n′, η) are lists, one value per map (of a
``ZP<k>`` or face-partition scheme, or the one map of the others): arrays in JSON, and in CSV
one row per map with the map's number in a ``map`` column (tidy data, nothing packed in a cell).

Example
-------
>>> rows = sweep(["Standard", "ZP5+LogP"], f_over_n=[1000.0], fov=[60.0], light="overhead", summary=True)
>>> [(r["scheme"], round(r["S_min"], 3)) for r in rows]
[('Standard', 865159.378), ('ZP5+LogP', 5.982)]
"""

from __future__ import annotations

import csv
import io
import json
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .. import _validation as check
from .. import geometry, schemes
from ..view import View, check_aspect


FORMATS = ("csv", "json")
ROW_FIELDS = ("scheme", "f_over_n", "fov", "gamma", "azimuth", "M_x", "M_z", "S", "maps", "n_prime", "eta")
CSV_FIELDS = ("scheme", "f_over_n", "fov", "gamma", "azimuth", "map", "M_x", "M_z", "S", "maps", "n_prime", "eta")  # per-direction CSV
SUMMARY_FIELDS = ("scheme", "f_over_n", "fov", "directions", "maps", "S_min", "S_max", "S_max_over_min", "S_mean")
SQUARE = (1.0,)
"""The default aspect axis: one square view.  Only another axis adds an ``aspect`` column
after ``fov`` (:func:`with_aspect`), so that the output of a square sweep is what it was
before views had an aspect, byte for byte."""


def aspect_shown(aspects: Sequence[float]) -> bool:
    """Whether an aspect axis is shown as a column: any axis but the single value 1.

    Example
    -------
    >>> aspect_shown((1.0,)), aspect_shown((1.0, 2.0)), aspect_shown((2.0,))
    (False, True, True)
    """
    return tuple(float(a) for a in aspects) != SQUARE


def with_aspect(fields: Sequence[str]) -> tuple[str, ...]:
    """``fields`` with ``aspect`` after ``fov`` (the columns of a sweep over non-square views).

    Example
    -------
    >>> with_aspect(SUMMARY_FIELDS)[:4]
    ('scheme', 'f_over_n', 'fov', 'aspect')
    """
    out = list(fields)
    out.insert(out.index("fov") + 1, "aspect")
    return tuple(out)


def sweep(scheme_names: Iterable[str], f_over_n: ArrayLike = (1000.0,), fov: ArrayLike = (60.0,), light: str | ArrayLike = "overhead", *, aspect: ArrayLike = SQUARE, near: float = 1.0, summary: bool = False, **options) -> list[dict]:
    """Evaluate every scheme × f/n × fov × aspect over the light directions.

    Parameters
    ----------
    scheme_names : iterable of str
        Scheme names (:data:`aliasing.schemes.GRAMMAR`).
    f_over_n : array_like
        Depth ratios far/near, each > 1.
    fov : array_like
        Full (vertical) fields of view [deg], each in (0, 180).
    light : str or array_like
        Light spec (:data:`aliasing.geometry.LIGHT_SPEC`) or vectors ``(N, 3)``.
    aspect : array_like
        Image width/height of the views, each in (0, inf) (default: one square view).  Any
        other axis adds an ``aspect`` key after ``fov`` (:func:`aspect_shown`); schemes
        of square views only (face partitions, θ-only rules) refuse aspect ≠ 1.
    near : float
        Near distance [world units]; results depend on f/n only.
    summary : bool
        One row per scheme, f/n, fov (and aspect) with min, max, max/min and mean of S̄ over the
        directions (the layout of Lloyd et al. 2007 Table 3) instead of one row per direction.
    **options
        Passed to the warping rules.

    Returns
    -------
    list of dict
        With the keys :data:`ROW_FIELDS` or :data:`SUMMARY_FIELDS`.
    """
    parsed = [schemes.parse(name) for name in check.names(scheme_names, "scheme_names")]
    if not parsed:
        raise ValueError("schemes must name at least one scheme")
    ratios = np.atleast_1d(check.depth_ratio(f_over_n))
    fovs = np.atleast_1d(check.fov(fov))
    aspects = np.atleast_1d(check_aspect(aspect))
    shown = aspect_shown(aspects.tolist())
    lv = geometry.lights(light)
    gamma, azimuth = geometry._typed_angles(light)  # as typed: gamma:30 is 30
    refuse_square_only([(sch.name, sch, options) for sch in parsed], near, ratios[0], fovs[0], aspects.tolist(), lv[:1])
    # every scheme of a (f/n, fov, aspect) cell shares its directions' light frames (schemes.evaluate_many)
    cells = {(i, j, a): schemes.evaluate_many(parsed, view_of(near, ratio, fv, av), lv, **options)
             for i, ratio in enumerate(ratios) for j, fv in enumerate(fovs) for a, av in enumerate(aspects)}
    rows: list[dict] = []
    for s, sch in enumerate(parsed):
        for i, ratio in enumerate(ratios):
            for j, fv in enumerate(fovs):
                for a, av in enumerate(aspects):
                    r = cells[i, j, a][s]
                    shown_aspect = float(av) if shown else None
                    if summary:
                        rows.append(_summary_row(sch.name, ratio, fv, r, shown_aspect))
                    else:
                        rows.extend(_direction_rows(sch.name, ratio, fv, gamma, azimuth, r, shown_aspect))
    return rows


def refuse_square_only(variants: Iterable[tuple[str, str | schemes.Scheme, dict]], near: float, ratio: float, fov: float, aspects: Sequence[float], light: ArrayLike) -> None:
    """Refuse, before any work, a scheme that takes square views only in a sweep with aspect ≠ 1.

    Face partitions and the rules written with θ alone (:meth:`aliasing.View.require_square`)
    have no value at a non-square view: a sweep that crosses them with aspect ≠ 1 is refused
    in one line naming the scheme and the aspect, instead of failing part-way.  Each
    ``(label, scheme, options)`` is evaluated on the direction(s) ``light`` at the first
    aspect ≠ 1 of the axis and, if that raises, at aspect 1: only a scheme that works at
    aspect 1 is refused here (another error is left to the sweep itself, as before).

    Example
    -------
    >>> refuse_square_only([("FP+P", "FP+P", {})], 1.0, 100.0, 60.0, (1.0, 2.0), [[0.0, 1.0, 0.0]])
    Traceback (most recent call last):
    ...
    ValueError: aspect 2 is not possible with scheme 'FP+P', which takes square views only: aspect must be 1 for face partitions (Lloyd et al. 2007 §6.1.3: the four side faces of a square frustum) (a square view), got 2
    """
    wide = next((float(a) for a in aspects if float(a) != 1.0), None)
    if wide is None:
        return
    for label, scheme, options in variants:
        try:
            schemes.evaluate(scheme, view_of(near, ratio, fov, wide), light, **options)
        except ValueError as exc:
            try:
                schemes.evaluate(scheme, view_of(near, ratio, fov), light, **options)
            except ValueError:
                continue  # wrong at aspect 1 too: not the aspect's doing
            raise ValueError(f"aspect {wide:g} is not possible with scheme {label!r}, which takes square views only: {exc}") from None


def view_of(near: float, ratio: float, fov: float, aspect: float = 1.0) -> View:
    """The View of one sweep cell: near, far = near·ratio, fov [deg] and aspect (validated by View).

    Example
    -------
    >>> view_of(1.0, 100.0, 60.0, 2.0)
    View(near=1.0, far=100.0, fov=60.0, aspect=2.0)
    """
    return View(near, near * ratio, fov, aspect)


def _aspect_after_fov(row: dict, aspect: float | None) -> dict:
    """``row`` with ``aspect`` after ``fov`` when an aspect is shown (not None)."""
    if aspect is None:
        return row
    out: dict = {}
    for key, value in row.items():
        out[key] = value
        if key == "fov":
            out["aspect"] = float(aspect)
    return out


def _summary_row(name: str, ratio: float, fov: float, r: schemes.Result, aspect: float | None = None) -> dict:
    s_min, s_max = float(r.S.min()), float(r.S.max())
    row = {"scheme": name, "f_over_n": float(ratio), "fov": float(fov), "directions": int(r.S.size), "maps": _mean_maps(r), "S_min": s_min, "S_max": s_max, "S_max_over_min": s_max / s_min, "S_mean": float(r.S.mean())}
    return _aspect_after_fov(row, aspect)


def _mean_maps(r: schemes.Result) -> int | float:
    """The number of maps, or its mean over the directions when it varies (face partitions)."""
    used = r.maps_used
    return int(used[0]) if np.all(used == used[0]) else float(used.mean())


def _direction_rows(name: str, ratio: float, fov: float, gamma: np.ndarray, azimuth: np.ndarray, r: schemes.Result, aspect: float | None = None) -> list[dict]:
    per_map = {"M_x": r.M_x.tolist(), "M_z": r.M_z.tolist(), "n_prime": r.n_prime.tolist(), "eta": r.eta.tolist()}  # lists, one per map
    used = r.maps_used.tolist()
    view = {"fov": float(fov)} if aspect is None else {"fov": float(fov), "aspect": float(aspect)}
    return [
        {
            "scheme": name,
            "f_over_n": float(ratio),
            **view,
            "gamma": float(gamma[i]),
            "azimuth": float(azimuth[i]),
            "M_x": per_map["M_x"][i],
            "M_z": per_map["M_z"][i],
            "S": float(r.S[i]),
            "maps": used[i],
            "n_prime": per_map["n_prime"][i],
            "eta": per_map["eta"][i],
        }
        for i in range(r.S.size)
    ]


def format_rows(rows: Sequence[dict], fmt: str = "csv") -> str:
    """Rows as CSV or JSON (a list of row objects; per-map values as arrays).

    In CSV, when some field holds a list (one value per map), each row becomes one row per
    map, with the map's number (from 0) in a ``map`` column before the first such field; the
    other fields repeat (tidy data: no cell packs several values).

    Example
    -------
    >>> print(format_rows([{"scheme": "ZP2", "S": 5.0, "M_x": [1.5, 2.0]}, {"scheme": "P", "S": 2.0, "M_x": 1.0}]), end="")
    scheme,S,map,M_x
    ZP2,5,0,1.5
    ZP2,5,1,2
    P,2,0,1
    """
    kind = check.choice(fmt, "format", FORMATS)
    if kind == "json":
        return json.dumps([{k: _json_value(v) for k, v in row.items()} for row in rows], indent=1) + "\n"
    if not rows:
        return ""
    fields = list(rows[0])
    listed = [k for k in fields if any(isinstance(row.get(k), list) for row in rows)]
    if listed:
        fields.insert(fields.index(listed[0]), "map")
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        cells = {k: f"{v:.10g}" if isinstance(v, float) else v for k, v in row.items()}
        if not listed:
            writer.writerow(cells)
            continue
        count = max((len(row[k]) for k in listed if isinstance(row.get(k), list)), default=1)
        for j in range(count):
            writer.writerow({**cells, "map": j, **{k: _fmt(row[k][j]) if isinstance(row[k], list) else cells[k] for k in listed if k in row}})
    return buf.getvalue()


def _json_value(value):
    """JSON has no inf/NaN: write them as strings, like CSV does."""
    if isinstance(value, list):
        return [_json_value(v) for v in value]
    if isinstance(value, float) and not np.isfinite(value):
        return str(value)
    return value


def _with_cells(row: dict, task: Any) -> dict:
    """Insert the swept rule options' columns (``param_<name>``, ``task.columns`` and ``.cells``) after ``scheme``."""
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
