"""Command-line glue: running a plan for ``aliasing sweep`` / ``aliasing validate``."""

from __future__ import annotations

import os
import sys
from collections.abc import Callable

from .engine import execute
from .runner import Plan, progress_bar
from .store import _workdir, resolve_out


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
    >>> from aliasing.sweep import plan
    >>> run_command(plan("P", f_over_n=100, light="behind"), "csv", None, name="sweep")
    scheme,f_over_n,fov,gamma,azimuth,map,M_x,M_z,S,maps,n_prime,eta
    P,100,60,180,0,0,100,100,10000,1,inf,-1
    0
    """
    def notice(line: str) -> None:
        print(f"aliasing {name}: {line}", file=sys.stderr)

    try:
        result = execute(grid, fmt, out, jobs=jobs, dask=dask, resume=resume, progress=progress_bar(sys.stderr), command=command, on_payloads=on_payloads, notice=notice)
    except KeyboardInterrupt:
        target = resolve_out(out) if out is not None else None
        kept = f"; finished chunks are kept in {_workdir(target)}: rerun with --resume" if target is not None else ""
        print(f"\naliasing {name}: interrupted{kept}", file=sys.stderr)
        return 130
    if out is None:
        sys.stdout.write(str(result))
    return 0
