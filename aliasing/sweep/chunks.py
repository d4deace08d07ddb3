"""The work of a sweep's chunks: one chunk (:func:`compute_chunk`) or a batch sharing light frames.

A chunk is one scheme variant × one f/n × one fov × one aspect × a block of light directions.
Chunks that differ only in the scheme (same f/n, fov, aspect, block and warping-rule options) form a
batch: :func:`compute_batch` evaluates them with one :func:`aliasing.schemes.evaluate_many`
call, so every scheme shares the directions' light frames, and formats the light angles'
CSV text once.  Payloads are the same, bit for bit, as chunk by chunk.
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import geometry, schemes
from ..view import View
from . import formats
from .rows import _csv_cells, _direction_rows, _json_value, _with_cells, view_of

__all__ = ["compute_batch", "compute_chunk"]


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
    angles: tuple[np.ndarray, np.ndarray] | None = field(default=None, repr=False, compare=False)  # γ, azimuth as typed
    shared: dict[str, Any] | None = field(default=None, repr=False, compare=False)  # set by a batch: the Result, angle text
    aspect: float = 1.0  # image width/height of the view
    aspect_shown: bool = False  # the grid has an aspect column (an aspect axis other than the single value 1)

    @property
    def view(self) -> View:
        """The chunk's view (``schemes.evaluate`` makes the same View of loose near, far, fov)."""
        return view_of(self.near, self.ratio, self.fov, self.aspect)

    def compute(self) -> str | dict[str, np.ndarray]:
        """This chunk's payload (:func:`compute_chunk`)."""
        return compute_chunk(self)


def compute_chunk(task: _Task) -> str | dict[str, np.ndarray]:
    """Evaluate one chunk (vectorized over its directions); the payload of its kind.

    CSV or JSON text of its rows (no header), or the arrays S, M_x, M_z, n′, η.  Inside a
    batch (:func:`compute_batch`) the evaluation and the angles' text come ready in
    ``task.shared``.

    Example
    -------
    >>> from aliasing.sweep import plan
    >>> g = plan("ZP2+P", light="overhead,front")
    >>> print(compute_chunk(g.chunk(0, "csv")), end="")
    ZP2+P,1000,60,90,0,0,5.623413252,4.716015218,53.04020494,2,6.623413252,0
    ZP2+P,1000,60,90,0,1,5.623413252,4.716015218,53.04020494,2,209.4507176,0
    ZP2+P,1000,60,0,0,0,31.6227766,31.6227766,2000,2,inf,-1
    ZP2+P,1000,60,0,0,1,31.6227766,31.6227766,2000,2,inf,-1
    >>> compute_chunk(g.chunk(0, "arrays"))["M_x"].shape
    (2, 2)
    """
    shared = task.shared or {}
    r = shared["result"] if "result" in shared else schemes.evaluate(task.name, task.view, task.light, **dict(task.options))
    if task.kind == "arrays":
        return {"S": r.S, "M_x": r.M_x, "M_z": r.M_z, "n_prime": r.n_prime, "eta": r.eta}
    gamma, azimuth = shared["angles"] if "angles" in shared else _angles(task)
    if task.kind == "json":
        rows = _direction_rows(r.scheme.name, task.ratio, task.fov, gamma, azimuth, r, task.aspect if task.aspect_shown else None)
        rows = [_with_cells(row, task) for row in rows]
        return ",\n".join(" " + json.dumps({k: _json_value(v) for k, v in row.items()}, indent=1).replace("\n", "\n ") for row in rows)
    head = _csv_cells([r.scheme.name, *task.cells, float(task.ratio), float(task.fov), *([float(task.aspect)] if task.aspect_shown else [])])
    angles = shared.get("angle_cells")
    if angles is None:
        angles = formats.cells([gamma, azimuth])
    n, k = r.M_x.shape  # one line per direction and map (tidy: the map's number in a column, nothing packed)
    per_map = [np.tile(np.arange(k), n), r.M_x.reshape(-1), r.M_z.reshape(-1), np.repeat(r.S, k), np.repeat(r.maps_used, k), r.n_prime.reshape(-1), r.eta.reshape(-1)]
    return formats.lines(head, [np.repeat(angles, k, axis=0), per_map])


@dataclass(frozen=True)
class _Batch:
    """Chunks of the same f/n, fov, aspect, direction block and rule options, differing only in the scheme."""

    tasks: tuple[_Task, ...]

    def compute(self) -> list[str | dict[str, np.ndarray]]:
        """The chunks' payloads, in order (:func:`compute_batch`)."""
        return compute_batch(self.tasks)


def compute_batch(tasks: tuple[_Task, ...]) -> list[str | dict[str, np.ndarray]]:
    """Payloads of chunks that share f/n, fov, aspect, directions and options: one ``evaluate_many`` for all their schemes.

    Example
    -------
    >>> from aliasing.sweep import plan
    >>> g = plan("P,ZP2+P", light="overhead,front")
    >>> compute_batch((g.chunk(0, "csv"), g.chunk(1, "csv"))) == [compute_chunk(g.chunk(0, "csv")), compute_chunk(g.chunk(1, "csv"))]
    True
    """
    t0 = tasks[0]
    same = ("kind", "options", "near", "ratio", "fov", "aspect", "aspect_shown")
    if any(tuple(getattr(t, k) for k in same) != tuple(getattr(t0, k) for k in same) or t.light is not t0.light and not np.array_equal(t.light, t0.light) for t in tasks):
        raise ValueError("a batch's chunks must share kind, options, f/n, fov, aspect and light directions")
    results = schemes.evaluate_many([t.name for t in tasks], t0.view, t0.light, **dict(t0.options))
    shared: dict[str, Any] = {}
    if t0.kind != "arrays":
        shared["angles"] = _angles(t0)
    if t0.kind == "csv":
        shared["angle_cells"] = formats.cells(list(shared["angles"]))
    return [compute_chunk(dataclasses.replace(t, shared={**shared, "result": r})) for t, r in zip(tasks, results)]


def _angles(task: _Task) -> tuple[np.ndarray, np.ndarray]:
    """The chunk's (γ, azimuth) [deg]: the light specs' numbers as typed, else from the vectors."""
    return task.angles if task.angles is not None else geometry.direction_angles(task.light)
