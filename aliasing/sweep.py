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
import io
import json
import os
import tempfile
from collections.abc import Iterable, Sequence
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from . import _validation as check
from . import geometry, schemes

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
    return {"scheme": name, "f_over_n": float(ratio), "fov": float(fov), "directions": int(r.S.size), "maps": r.maps, "S_min": s_min, "S_max": s_max, "S_max_over_min": s_max / s_min, "S_mean": float(r.S.mean())}


def _direction_rows(name: str, ratio: float, fov: float, gamma: np.ndarray, azimuth: np.ndarray, r: schemes.Result) -> list[dict]:
    per_map = {"M_x": r.M_x.tolist(), "M_z": r.M_z.tolist(), "n_prime": r.n_prime.tolist(), "eta": r.eta.tolist()}
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
            "maps": r.maps,
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
