"""Vectorized sweeps of schemes over depth ratios, fields of view, aspect ratios and light directions.

A package with one concern per module, lower modules never importing higher ones:

- :mod:`~aliasing.sweep.rows`: :func:`sweep` (rows as dicts) and :func:`format_rows` (CSV/JSON text);
- :mod:`~aliasing.sweep.formats`: CSV text of whole columns (exact ``'%.10g'``, vectorized);
- :mod:`~aliasing.sweep.chunks`: the work of one chunk, or of a batch of chunks sharing light frames;
- :mod:`~aliasing.sweep.grid`: axes, ranges, scheme variants, light specs, :class:`Grid`, :func:`plan`, chunks and batches;
- :mod:`~aliasing.sweep.limits`: memory estimates from a request's counts, refused before allocating;
- :mod:`~aliasing.sweep.store`: atomic writes, the output target, the work directory and its manifest;
- :mod:`~aliasing.sweep.runner`: the runner (in-process, local processes or Dask), :func:`collect`, progress;
- :mod:`~aliasing.sweep.tables`: :class:`SweepTable`, the assembled output, Parquet;
- :mod:`~aliasing.sweep.engine`: :func:`execute` (resumable output files), :func:`table`, estimates;
- :mod:`~aliasing.sweep.config`: TOML configs (:func:`read_config`);
- :mod:`~aliasing.sweep.command`: the command-line glue (:func:`run_command`).

The package is callable: ``aliasing.sweep(...)`` is :func:`table`.

Example
-------
>>> rows = sweep(["Standard", "ZP5+LogP"], f_over_n=[1000.0], fov=[60.0], light="overhead", summary=True)
>>> [(r["scheme"], round(r["S_min"], 3)) for r in rows]
[('Standard', 865159.378), ('ZP5+LogP', 5.982)]
"""

from __future__ import annotations

import sys
import types

from . import chunks, command, config, engine, formats, grid, limits, rows, runner, store, tables
from .command import run_command
from .config import CONFIG_KEYS, read_config
from .engine import dry_run, estimate, execute, table
from .grid import (
    DEFAULT_BLOCK,
    OUTPUT_FORMATS,
    RANGE,
    Grid,
    Variant,
    compute_chunk,
    expand_lights,
    expand_schemes,
    grid_values,
    parameters_digest,
    plan,
    split_lights,
    spread,
)
from .rows import FORMATS, ROW_FIELDS, SUMMARY_FIELDS, format_rows, sweep
from .runner import DASK_TIMEOUT, Plan, Progress, Task, check_jobs, collect, cores, max_jobs, progress_bar, run_task
from .store import write
from .tables import SweepTable, import_xarray

_MODULES = (rows, formats, chunks, grid, limits, store, runner, tables, engine, config, command)

__all__ = [
    "CONFIG_KEYS", "DASK_TIMEOUT", "DEFAULT_BLOCK", "FORMATS", "OUTPUT_FORMATS", "RANGE", "ROW_FIELDS", "SUMMARY_FIELDS",
    "Grid", "Plan", "Progress", "SweepTable", "Task", "Variant", "check_jobs", "collect", "cores", "max_jobs", "compute_chunk", "dry_run", "estimate",
    "execute", "expand_lights", "expand_schemes", "format_rows", "grid_values", "import_xarray", "parameters_digest",
    "plan", "progress_bar", "read_config", "run_command", "run_task", "split_lights", "spread", "sweep", "table", "write",
]


class _CallableModule(types.ModuleType):
    """This package, callable: ``aliasing.sweep(...)`` is :func:`table`.

    Setting a name on the package (``monkeypatch.setattr(aliasing.sweep, "compute_chunk", f)``)
    also sets it in the submodules that use it, as it did when the engine was one module.
    """

    def __call__(self, *args, **kwargs) -> SweepTable:
        return table(*args, **kwargs)

    def __setattr__(self, name: str, value: object) -> None:
        super().__setattr__(name, value)
        if not isinstance(value, types.ModuleType):
            for module in self.__dict__.get("_MODULES", ()):
                if name in vars(module):
                    setattr(module, name, value)


sys.modules[__name__].__class__ = _CallableModule
