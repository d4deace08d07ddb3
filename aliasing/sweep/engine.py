"""Running a planned grid: :func:`execute` (chunked, resumable output files), :func:`table` (in memory), estimates."""

from __future__ import annotations

import os
import shutil
import sys
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from .. import _validation as check
from . import limits
from .grid import DEFAULT_BLOCK, plan
from .runner import Plan, Progress, _duration, _run_chunks, check_jobs, collect
from .store import WorkDir, _check_out, _open_workdir, _write_netcdf, _write_text_stream, resolve_out
from .tables import SweepTable, import_pyarrow, import_xarray, write_parquet


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
    notice: Callable[[str], None] | None = None,
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
        Output format, one of ``grid.formats``: csv, json, parquet (needs ``out`` and the
        ``parquet`` extra; a row group per chunk, streamed), netcdf (needs ``out`` and the
        ``xarray`` extra); validation grids also write a text table.
    out : path, optional
        Output file; without it the text is returned (no work directory, no resume); ``-``
        or ``/dev/stdout`` streams it to standard output (and returns ``"-"``).  A symbolic
        link is followed (its target is replaced atomically); devices, FIFOs and sockets are
        refused before any work (:func:`aliasing.sweep.store.resolve_out`).
    jobs : int
        Local processes.
    dask : str, optional
        Address of a running Dask scheduler to compute the chunks on instead.
    resume : bool
        Continue the work directory of an interrupted run of the same sweep.  Only chunks
        whose SHA-256 and row count match the manifest are reused; the others are
        recomputed and ``notice`` is told so in one line.
    progress : callable, optional
        ``progress(done, total)`` after each chunk (an exception from it stops the run,
        keeping the finished chunks).
    command : str, optional
        The command line, stored in NetCDF attributes.
    on_payloads : callable, optional
        Called with the list of every chunk's payload, in order, once all are done and
        before the output is written (resumed chunks included), e.g. to check the rows of
        a validation grid; for small payloads only (it holds them all in memory).
    notice : callable, optional
        Receives the one line naming damaged chunks recomputed on resume (default: printed
        on stderr).

    Returns
    -------
    str or Path
        The text (without ``out``) or the path written.

    Example
    -------
    >>> g = plan("P", f_over_n=100, fov=60, light="overhead,behind")
    >>> print(execute(g), end="")
    scheme,f_over_n,fov,gamma,azimuth,map,M_x,M_z,S,maps,n_prime,eta
    P,100,60,90,0,0,10,8.573651497,85.73651497,1,11,0
    P,100,60,180,0,0,100,100,10000,1,inf,-1
    """
    kind = check.choice(fmt, "format", grid.formats)
    jobs = check_jobs(jobs)
    stream = out is not None and resolve_out(out) is None
    if stream:
        out = None
    if kind in ("netcdf", "parquet") and out is None:
        raise ValueError(f"format {kind} needs an output file (--out)")
    if resume and out is None:
        raise ValueError("resume needs an output file (--out): the work directory sits beside it")
    if kind == "netcdf":
        import_xarray()
    if kind == "parquet":
        import_pyarrow()
    payload_kind = grid.payload_kind(kind)
    total = grid.chunks
    results: dict[int, object] = {}
    work: WorkDir | None = None
    target = _check_out(out) if out is not None else None
    finished: set[int] = set()
    if target is not None:
        work, finished = _open_workdir(grid, kind, target, resume, payload_kind)
        if work.damaged:
            line = f"resume: recomputing {len(work.damaged)} damaged chunk{'s' if len(work.damaged) > 1 else ''} in {str(work.path)!r}: {', '.join(work.damaged)}"
            (notice or _stderr_notice)(line)
    count = len(finished)
    if progress and count:
        progress(count, total)

    def done(i: int, payload: object) -> None:
        nonlocal count
        if work is not None:
            work.save(i, payload)
        else:
            results[i] = payload
        count += 1
        if progress:
            progress(count, total)

    try:
        _run_chunks(grid, payload_kind, [i for i in range(total) if i not in finished], done, jobs, dask)
    except BaseException:
        if work is not None and count == 0:  # nothing worth keeping: leave no work directory
            shutil.rmtree(work.path, ignore_errors=True)
        raise

    def load(i: int) -> object:
        if work is None:
            return results[i]
        return work.load(i)

    payloads: Iterable[object] = (load(i) for i in _output_order(grid))
    if on_payloads is not None or kind == "netcdf":
        payloads = list(payloads)
        if on_payloads is not None:
            on_payloads(payloads)
    if stream:
        for part in grid.assemble(payload_kind, kind, payloads):
            sys.stdout.write(part if isinstance(part, str) else part.decode())
        sys.stdout.flush()
        return "-"
    if target is None:
        return "".join(str(part) for part in grid.assemble(payload_kind, kind, payloads))
    if kind == "parquet":
        write_parquet(grid, payloads, target)  # type: ignore[arg-type]
    elif kind == "netcdf":
        _write_netcdf(grid.table(payloads, command or grid.command(kind)), target)  # type: ignore[arg-type]
    else:
        _write_text_stream(grid.assemble(payload_kind, kind, payloads), target)
    shutil.rmtree(work.path)  # type: ignore[union-attr]
    return target


def _output_order(grid: Plan) -> Sequence[int]:
    """Chunk indices in output order (:meth:`Grid.output_order`; chunk order for plans without one)."""
    order = getattr(grid, "output_order", None)
    return order() if order is not None else range(grid.chunks)


def _stderr_notice(line: str) -> None:
    print(f"aliasing: {line}", file=sys.stderr)


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

    jobs = check_jobs(jobs)
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


def dry_run(grid: Plan, fmt: str = "csv", jobs: int = 1, in_memory: bool | None = None, max_memory: int | None = None) -> str:
    """The grid size and a time estimate, as printed by ``aliasing sweep --dry-run``.

    Example
    -------
    >>> print(dry_run(plan("P,LogP", light="hemisphere:1000")).splitlines()[0])
    grid: 2 schemes × 1 f/n × 1 fov × 1000 directions = 2,000 evaluations in 2 chunks
    """
    seconds, note = _estimate(grid, fmt, jobs)
    text = f"{grid.describe()}\nestimated time: {_duration(seconds)} with {jobs} job{'s' if jobs > 1 else ''} ({note})\n"
    held = grid.payload_kind(fmt) == "arrays" if in_memory is None else in_memory
    size = limits.grid_bytes(grid, jobs, held)
    if size is not None:
        cap = limits.DEFAULT_MAX_MEMORY if max_memory is None else max_memory
        text += f"estimated memory: {limits.human(size[0])} (limit {limits.human(cap)}, --max-memory)\n"
    return text


def table(
    schemes: str | Iterable[str],
    f_over_n: ArrayLike | str = (1000.0,),
    fov: ArrayLike | str = (60.0,),
    light: str | Sequence[str] | ArrayLike = "overhead",
    *,
    aspect: ArrayLike | str = (1.0,),
    k: ArrayLike | str | None = None,
    params: dict | None = None,
    near: float = 1.0,
    summary: bool = False,
    block: int = DEFAULT_BLOCK,
    jobs: int = 1,
    dask: str | None = None,
    progress: Progress | None = None,
    max_memory: int | str | None = None,
) -> SweepTable:
    """Run a sweep grid in memory and return a :class:`SweepTable` (``.to_pandas()``, ``.to_xarray()``).

    Parameters are those of :func:`plan` (every axis a number, list or range text) and
    of :func:`execute` (``jobs``, ``dask``, ``progress``); ``max_memory`` as in :func:`plan`
    (here counting the table held in memory).  Also callable as
    ``aliasing.sweep(...)``.

    Example
    -------
    >>> import aliasing
    >>> t = aliasing.sweep("LogP", f_over_n="10:1000:log:3", fov=60, light="overhead", k=[1, 5], summary=True)
    >>> [(r["scheme"], r["f_over_n"], round(r["S_min"], 2)) for r in t.rows()][-1]
    ('ZP5+LogP', 1000.0, 5.98)
    """
    limit = None if max_memory is None else limits.parse_memory(max_memory)
    limits.check_request(schemes, f_over_n, fov, light, aspect=aspect, k=k, params=params, block=block, jobs=jobs, in_memory=True, limit=limit)
    grid = plan(schemes, f_over_n, fov, light, aspect=aspect, k=k, params=params, near=near, summary=summary, block=block, max_memory=max_memory)
    return grid.table(collect(grid, "arrays", jobs=jobs, dask=dask, progress=progress))
