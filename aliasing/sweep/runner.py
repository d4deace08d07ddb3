"""Execution: compute a plan's chunks in-process, in local processes or on Dask, behind one interface.

:func:`_run_chunks` is the runner used by :func:`aliasing.sweep.execute`,
:func:`collect` and the validation grids of :mod:`aliasing.raster.validate`.
"""

from __future__ import annotations

import itertools
import math
import os
import sys
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, ClassVar, Protocol, TextIO

import numpy as np

from .. import _validation as check
from .store import _EXT

if TYPE_CHECKING:  # annotations only: the tables import the store, which this module imports
    from .tables import SweepTable


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


def cores() -> int:
    """CPU cores this process may use (its affinity mask where the OS has one)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def max_jobs() -> int:
    """The most local worker processes a run may ask for: 4 × :func:`cores`."""
    return 4 * cores()


def check_jobs(value: object, name: str = "jobs") -> int:
    """``value`` as a whole number of local processes in [1, :func:`max_jobs`]; ValueError naming ``name`` otherwise.

    Example
    -------
    >>> check_jobs(2)
    2
    >>> check_jobs(99999999999999999999999)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: jobs must be a whole number >= 1 (local processes) and <= ... (4 x ... cores), got 99999999999999999999999
    """
    cap = max_jobs()
    whole = isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))
    if isinstance(value, (float, np.floating)) and math.isfinite(value) and float(value).is_integer():
        whole, value = True, int(value)
    if not (whole and 1 <= int(value) <= cap):  # type: ignore[arg-type]
        raise ValueError(f"{name} must be a whole number >= 1 (local processes) and <= {cap} (4 x {cores()} cores), got {value!r}")
    return int(value)  # type: ignore[arg-type]


def run_task(task: Task) -> Any:
    """``task.compute()``: the function sent to worker processes and Dask workers."""
    return task.compute()


def _units(grid: Plan, kind: str, todo: Sequence[int], workers: int) -> list[tuple[list[int], Any]]:
    """The work to hand out: batches of chunks when the plan makes them (:meth:`Grid.batches`), else single chunks."""
    batches = getattr(grid, "batches", None)
    if batches is None:
        return [([i], _One(grid.chunk(i, kind))) for i in todo]
    return [(b, grid.batch(b, kind)) for b in batches(todo, workers)]  # type: ignore[attr-defined]


class _One:
    """A single chunk as a unit of work: its payload in a list (the shape of a batch's)."""

    def __init__(self, task: Task) -> None:
        self.task = task

    def compute(self) -> list:
        return [self.task.compute()]


def _run_chunks(grid: Plan, kind: str, todo: Sequence[int], done: Callable[[int, object], None], jobs: int, dask: str | None) -> None:
    """Compute the chunks ``todo`` in-process, in ``jobs`` processes or on Dask; ``done`` each."""
    if dask:
        _run_dask(grid, kind, todo, done, dask)
        return
    if jobs == 1 or len(todo) <= 1:
        for indices, unit in _units(grid, kind, todo, 1):
            for i, payload in zip(indices, unit.compute()):
                done(i, payload)
        return
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    units = _units(grid, kind, todo, jobs)
    pending: dict = {}
    queue = iter(units)
    jobs = min(check_jobs(jobs), len(units))  # never more processes than units of work
    ex = ProcessPoolExecutor(max_workers=jobs)
    try:
        while True:
            for indices, unit in itertools.islice(queue, 2 * jobs - len(pending)):
                pending[ex.submit(run_task, unit)] = indices
            if not pending:
                break
            finished, _ = wait(pending, return_when=FIRST_COMPLETED)
            for fut in sorted(finished, key=lambda f: pending[f][0]):
                for i, payload in zip(pending.pop(fut), fut.result()):
                    done(i, payload)
    finally:
        ex.shutdown(wait=True, cancel_futures=True)


DASK_TIMEOUT = 10.0
"""Seconds to wait for a Dask scheduler before giving up."""


def _probe_dask(address: str) -> None:
    """Connect once, with a hard time limit, before making a Client.

    distributed's own timeout does not cover a peer that accepts the connection but never
    answers the handshake (an HTTP server: the Client waited forever), and a peer that
    answers garbage left a half-made Client whose clean-up printed a traceback at exit.
    Run in a thread of its own, so that a caller's running event loop does not matter.
    """
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect

    async def once() -> None:
        comm = await connect(address, timeout=DASK_TIMEOUT)
        await comm.close()

    with ThreadPoolExecutor(1) as pool:
        try:
            pool.submit(asyncio.run, asyncio.wait_for(once(), DASK_TIMEOUT + 1)).result()
        except Exception as exc:  # noqa: BLE001 - anything a wrong peer makes distributed raise
            detail = str(exc).splitlines()[0] if str(exc) else f"no answer within {DASK_TIMEOUT + 1:g} s"
            if not isinstance(exc, OSError) or not str(exc):  # connected, but no Dask answer (wait_for's bare TimeoutError)
                detail += " (is it a Dask scheduler?)"
            raise ValueError(f"dask: cannot reach a Dask scheduler at {address!r}: {detail}") from None


def _run_dask(grid: Plan, kind: str, todo: Sequence[int], done: Callable[[int, object], None], address: str) -> None:
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise ValueError("dask: --dask needs the optional extra: pip install \".[dask]\"") from None
    from distributed.comm.addressing import parse_address, parse_host_port

    try:  # a malformed address would leave distributed's half-made Client hanging at exit
        scheme, location = parse_address(str(address))
        if scheme in ("tcp", "tls"):
            parse_host_port(location)
    except (ValueError, TypeError) as exc:
        raise ValueError(f"dask: malformed scheduler address {address!r} ({exc}); expected e.g. tcp://host:8786") from None
    _probe_dask(address)
    try:
        client = Client(address, timeout=DASK_TIMEOUT, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise ValueError(f"dask: cannot reach a Dask scheduler at {address!r}: {exc}".splitlines()[0]) from None
    try:
        workers = max(1, sum(client.nthreads().values()))
        queue = iter(_units(grid, kind, todo, workers))
        index: dict = {}

        def submit(unit: tuple[list[int], Any]):
            fut = client.submit(run_task, unit[1], pure=False)
            index[fut.key] = unit[0]
            return fut

        stream = as_completed([submit(u) for u in itertools.islice(queue, 2 * workers)], loop=client.loop)
        for fut in stream:
            for i, payload in zip(index.pop(fut.key), fut.result()):
                done(i, payload)
            fut.release()
            nxt = next(queue, None)
            if nxt is not None:
                stream.add(submit(nxt))
    finally:
        client.close()


def _duration(seconds: float) -> str:
    if seconds < 60:
        return f"{seconds:.2g} s" if seconds < 10 else f"{seconds:.0f} s"
    minutes, sec = divmod(int(round(seconds)), 60)
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes:02d} min" if hours else f"{minutes} min {sec:02d} s"


def collect(grid: Plan, kind: str, *, jobs: int = 1, dask: str | None = None, progress: Progress | None = None) -> list:
    """Every chunk's payload of ``kind``, in output order, computed in memory (no work directory).

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
    >>> from aliasing.sweep import plan
    >>> payloads = collect(plan("P,LogP", light="overhead"), "arrays", jobs=1)
    >>> len(payloads), sorted(payloads[0])
    (2, ['M_x', 'M_z', 'S', 'eta', 'n_prime'])
    """
    jobs = check_jobs(jobs)
    kind = check.choice(kind, "payload kind", _EXT)
    payloads: dict[int, object] = {}
    total = grid.chunks

    def done(i: int, payload: object) -> None:
        payloads[i] = payload
        if progress:
            progress(len(payloads), total)

    _run_chunks(grid, kind, list(range(total)), done, jobs, dask)
    order = getattr(grid, "output_order", None)
    return [payloads[i] for i in (order() if order is not None else range(total))]


def progress_bar(stream: TextIO | None = None) -> Progress | None:
    """A tqdm progress bar of chunks on ``stream`` (stderr) if it is a terminal, else None (quiet).

    Returns a ``progress(done, total)`` callback; the bar closes when ``done`` reaches ``total``.

    Example
    -------
    >>> import io
    >>> progress_bar(io.StringIO()) is None  # not a terminal: quiet
    True
    """
    out = stream if stream is not None else sys.stderr
    try:
        if not out.isatty():
            return None
    except (AttributeError, ValueError):
        return None
    from tqdm import tqdm

    bar: list = []

    def show(done: int, total: int) -> None:
        if not bar:
            bar.append(tqdm(total=total, initial=done, unit="chunk", file=out, dynamic_ncols=True, leave=True))
        else:
            bar[0].update(done - bar[0].n)
        if done >= total:
            bar[0].close()

    return show
