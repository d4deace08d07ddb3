"""Finished sweeps: :class:`SweepTable` (rows, pandas, xarray) and the assembled output text."""

from __future__ import annotations

import json
import types
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

import numpy as np

from .. import geometry, schemes
from .._version import __version__
from .chunks import _Task
from .rows import CSV_FIELDS, ROW_FIELDS, _csv_cells, _direction_rows, _summary_row, _with_cells, format_rows, with_aspect
from .store import atomic_target

if TYPE_CHECKING:  # annotations only: the grid imports this module
    from .grid import Grid


def _assemble_stream(grid: Grid, payload_kind: str, fmt: str, payloads: Iterable[object]) -> Iterator[str | bytes]:
    """The output in pieces: text, or the bytes of chunk files as they are (UTF-8)."""
    if payload_kind == "arrays":  # summary rows (small)
        yield format_rows(SweepTable._from_payloads(grid, list(payloads)).rows(), fmt)
        return
    fields = CSV_FIELDS if fmt == "csv" else ROW_FIELDS
    header = _with_cells(dict.fromkeys(with_aspect(fields) if grid.aspect_shown else fields), grid.chunk(0, fmt))
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


def import_xarray() -> types.ModuleType:
    """The ``xarray`` module; ValueError naming the optional extra to install if it is missing."""
    try:
        import xarray
    except ImportError:
        raise ValueError("format netcdf needs the optional extra: pip install \".[xarray]\"") from None
    return xarray


class SweepTable:
    """A finished sweep in memory: rows, pandas, xarray.

    ``S`` and the per-map arrays are kept per scheme variant with shape
    ``(f/n, fov, aspect, directions[, maps])``.  Build it with :func:`table` (also reachable as
    ``aliasing.sweep(...)``).

    Example
    -------
    >>> from aliasing.sweep import table
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
        _, nr, nf, na, _ = grid.shape
        per = nr * nf * na * grid.blocks
        data = []
        for v in range(len(grid.variants)):
            chunk = payloads[v * per : (v + 1) * per]
            merged = {}
            for key in chunk[0]:
                arr = np.concatenate([c[key] for c in chunk])  # blocks in order, per (r, f, a)
                merged[key] = arr.reshape((nr, nf, na, -1) + arr.shape[1:])
            data.append(merged)
        return cls(grid, data, command)

    def __len__(self) -> int:
        v, r, f, a, n = self.grid.shape
        return v * r * f * a if self.grid.summary else self.grid.size

    def rows(self) -> list[dict]:
        """Rows as :func:`sweep` gives them (plus a column per swept rule option)."""
        g = self.grid
        gamma, azimuth = g.direction_angles()
        rows: list[dict] = []
        for var, d in zip(g.variants, self.data):
            task = _Task(0, "", var.name, var.options, g.columns, g._cells(var), g.near, 0.0, 0.0, g.directions)
            maps = d["M_x"].shape[-1]
            sch = schemes.parse(var.name)
            for r, ratio in enumerate(g.f_over_n):
                for f, fv in enumerate(g.fov):
                    for a, av in enumerate(g.aspect):
                        res = schemes.Result(sch, d["M_x"][r, f, a], d["M_z"][r, f, a], d["S"][r, f, a], d["n_prime"][r, f, a], d["eta"][r, f, a], maps)
                        shown = av if g.aspect_shown else None
                        new = [_summary_row(sch.name, ratio, fv, res, shown)] if g.summary else _direction_rows(sch.name, ratio, fv, gamma, azimuth, res, shown)
                        rows.extend(_with_cells(row, task) for row in new)
        return rows

    def format(self, fmt: str = "csv") -> str:
        """CSV or JSON text, the bytes ``aliasing sweep`` writes."""
        return format_rows(self.rows(), fmt)

    def attributes(self) -> dict:
        """Attributes of :meth:`to_xarray` (and NetCDF files): toolkit version, command, parameters (JSON)."""
        return {"aliasing_version": __version__, "command": self.command, "parameters": json.dumps(self.grid.parameters())}

    def to_pandas(self):
        """A ``pandas.DataFrame`` of :meth:`rows` (needs pandas)."""
        import pandas as pd

        return pd.DataFrame(self.rows())

    def to_xarray(self):
        """An ``xarray.Dataset`` with dims scheme, f_over_n, fov, (aspect,) direction (and map).

        The ``aspect`` dimension is there when the grid has an aspect axis other than the
        single value 1 (:attr:`Grid.aspect_shown`), as the ``aspect`` column of the other formats.

        Per-map variables (M_x, M_z, n_prime, eta) have a ``map`` dimension padded with NaN
        up to the largest number of maps; attributes hold every parameter, the toolkit
        version and the command.  In summary mode the variables are S_min, S_max,
        S_max_over_min and S_mean over the directions.
        """
        xr = import_xarray()
        g = self.grid
        gamma, azimuth = g.direction_angles()
        kmax = max(d["M_x"].shape[-1] for d in self.data)
        coords: dict = {"scheme": [v.label for v in g.variants], "f_over_n": list(g.f_over_n), "fov": list(g.fov)}
        shown = g.aspect_shown
        if shown:
            coords["aspect"] = list(g.aspect)
        views = ("scheme", "f_over_n", "fov", "aspect") if shown else ("scheme", "f_over_n", "fov")
        coords["scheme_name"] = ("scheme", [v.name for v in g.variants])
        coords["maps"] = ("scheme", [d["M_x"].shape[-1] for d in self.data])
        for key, column in zip(g.param_names, g.columns):
            coords[column] = ("scheme", [float(dict(v.options).get(key, np.nan)) for v in g.variants])
        S = np.stack([d["S"] for d in self.data])
        if not shown:  # the one square view: no aspect dimension (the Dataset of a sweep without aspect)
            S = S[:, :, :, 0]
        attrs = self.attributes()
        attrs.update(near=g.near, light=",".join(g.light), summary=int(g.summary), block=g.block)
        attrs.update(units_fov="degrees (full field of view)", units_gamma="degrees", units_S="image areas (unit resolutions)")
        if shown:
            attrs.update(units_aspect="image width/height (fov is the vertical field of view)")
        if g.summary:
            s_min, s_max = S.min(axis=-1), S.max(axis=-1)
            data = {"S_min": (views, s_min), "S_max": (views, s_max), "S_max_over_min": (views, s_max / s_min), "S_mean": (views, S.mean(axis=-1))}
            coords["directions"] = len(g.directions)
            return xr.Dataset(data, coords=coords, attrs=attrs)
        coords.update(direction=np.arange(len(g.directions)), gamma=("direction", gamma), azimuth=("direction", azimuth), map=np.arange(kmax))
        dims = (*views, "direction", "map")
        data = {"S": (dims[:-1], S)}
        for key in ("M_x", "M_z", "n_prime", "eta"):
            padded = np.full(S.shape + (kmax,), np.nan)
            for i, d in enumerate(self.data):
                padded[i, ..., : d[key].shape[-1]] = d[key] if shown else d[key][:, :, 0]
            data[key] = (dims, padded)
        return xr.Dataset(data, coords=coords, attrs=attrs)


def import_pyarrow() -> types.ModuleType:
    """The ``pyarrow`` module (with ``pyarrow.parquet``); ValueError naming the optional extra if it is missing."""
    try:
        import pyarrow
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise ValueError("format parquet needs the optional extra: pip install \".[parquet]\"") from None
    return pyarrow


def _parquet_schema(pa: types.ModuleType, grid: Grid, listed: bool):
    per_map = pa.list_(pa.float64()) if listed else pa.float64()
    fields = [("scheme", pa.string())] + [(c, pa.float64()) for c in grid.columns]
    fields += [("f_over_n", pa.float64()), ("fov", pa.float64())] + ([("aspect", pa.float64())] if grid.aspect_shown else []) + [("gamma", pa.float64()), ("azimuth", pa.float64())]
    fields += [("M_x", per_map), ("M_z", per_map), ("S", pa.float64()), ("maps", pa.int64()), ("n_prime", per_map), ("eta", per_map)]
    return pa.schema(fields)


def parquet_batches(grid: Grid, payloads: Iterable[object]) -> Iterator:
    """``pyarrow.RecordBatch`` es of the per-direction rows, one per chunk, in order.

    The columns of :data:`~aliasing.sweep.rows.ROW_FIELDS` (with ``param_<name>`` after
    ``scheme``, and ``aspect`` after ``fov`` when the grid shows it); per-map quantities are ``list<double>`` when some scheme has more than one
    map, else ``double``.
    """
    pa = import_pyarrow()
    listed = any(schemes.parse(v.name).k > 1 or schemes.parse(v.name).faces for v in grid.variants)
    schema = _parquet_schema(pa, grid, listed)
    for i, payload in zip(grid.output_order(), payloads):
        task = grid.chunk(i, "arrays")
        d: dict = payload  # type: ignore[assignment]
        n = len(d["S"])
        gamma, azimuth = task.angles if task.angles is not None else geometry.direction_angles(task.light)

        def per_map(a: np.ndarray):
            a = np.asarray(a, dtype=float).reshape(n, -1)
            if not listed:
                return pa.array(a[:, 0])
            return pa.ListArray.from_arrays(pa.array(np.arange(0, a.size + 1, a.shape[1], dtype=np.int32)), pa.array(a.ravel()))

        cells = [pa.nulls(n, pa.float64()) if c is None else pa.array(np.full(n, float(c))) for c in task.cells]
        view = [pa.array(np.full(n, float(task.ratio))), pa.array(np.full(n, float(task.fov)))] + ([pa.array(np.full(n, float(task.aspect)))] if grid.aspect_shown else [])
        columns = [pa.array([task.name] * n, pa.string()), *cells, *view, pa.array(gamma), pa.array(azimuth)]
        columns += [per_map(d["M_x"]), per_map(d["M_z"]), pa.array(np.asarray(d["S"], dtype=float)), pa.array(np.count_nonzero(np.asarray(d["M_x"]).reshape(n, -1) > 0, axis=-1).astype(np.int64))]
        columns += [per_map(d["n_prime"]), per_map(d["eta"])]
        yield pa.RecordBatch.from_arrays(columns, schema=schema)


def write_parquet(grid: Grid, payloads: Iterable[object], target) -> None:
    """Write a grid's ``arrays`` payloads as Parquet at ``target`` (atomically; a row group per chunk, streamed).

    Summaries are one row per scheme, f/n, fov (and aspect) (:data:`~aliasing.sweep.rows.SUMMARY_FIELDS`).
    """
    pa = import_pyarrow()
    pq = pa.parquet
    with atomic_target(target) as tmp:
        if grid.summary:
            pq.write_table(pa.Table.from_pylist(SweepTable._from_payloads(grid, list(payloads)).rows()), tmp)
            return
        writer = None
        try:
            for batch in parquet_batches(grid, payloads):
                if writer is None:
                    # dictionary encoding only for the columns constant within a chunk: tried on the float
                    # columns of every row (pyarrow's default) it took 2.7x the time and gave a larger file
                    constant = ["scheme", "f_over_n", "fov", *(["aspect"] if grid.aspect_shown else []), *grid.columns]
                    writer = pq.ParquetWriter(tmp, batch.schema, use_dictionary=constant)
                writer.write_batch(batch)
        finally:
            if writer is not None:
                writer.close()
