"""Sweeps at scale: 10^6 direction × scheme evaluations, --jobs 2 vs 1, Dask overhead per chunk.

Run by hand (not under pytest)::

    python benchmarks/sweep_scale.py                 # 10^6 evaluations, best of 3
    python benchmarks/sweep_scale.py --directions 50000 --repeats 1 --no-dask

What it times (wall clock, ``time.perf_counter``, best of ``--repeats``):

1. ``aliasing sweep`` as the CLI runs it (:func:`aliasing.sweep.plan` + :func:`aliasing.sweep.execute`)
   for the four single-map schemes Standard, P, Po, LogP over ``--directions`` hemisphere
   directions (250,000 → 10^6 evaluations), f/n = 1000, fov 60°, chunks of 20,000
   directions, with ``jobs`` 1 and 2, writing

   * the full per-direction CSV (10^6 rows, ~100 MB) to a temporary folder, and
   * the summary CSV (Lloyd 2007 Table 3 layout; compute only, tiny output).

   Process start-up, the work directory and the final atomic assembly are included.
2. The Dask overhead per chunk: the same summary sweep with ``block=1`` (one direction per
   chunk, so the evaluation itself is negligible) on a ``distributed.LocalCluster`` of 2
   single-threaded worker processes, minus the same chunks run in-process (jobs 1), divided
   by the number of chunks.  Cluster start-up is not included.
3. ``--output`` (only this part): output at scale.  A sweep of 10^6
   per-direction rows (``ZP3+LogP,P,LogP,FPc+P`` over ``--directions`` hemisphere directions)
   with ``jobs 2`` written as the per-direction CSV and as Parquet, against the summary run of
   the same sweep (the same evaluations, a tiny output: the baseline), timed side by side;
   the CSV text of one 20,000-direction ZP3+LogP chunk (:mod:`aliasing.sweep.formats`, whole
   columns at once) against one %-format per row (the first writer, kept here as the baseline);
   and the four schemes of one block evaluated one by one against one batch (``evaluate_many``,
   as ``aliasing sweep`` runs a batch of chunks).  Wall time (median of interleaved rounds)
   and the CPU time of the parent and its workers (``getrusage``) are printed.
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from aliasing import sweep as S
from _timing import best_of  # the shared timer (benchmarks/_timing.py; run these as scripts)

SCHEMES = "Standard,P,Po,LogP"



def _cpu() -> float:
    """CPU seconds of this process and its finished children (the worker processes), user + system."""
    import resource

    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def _rowwise_fragment(task, gamma, azimuth, r) -> str:
    """A row-at-a-time CSV writer (one %-format per line: one direction's map), the baseline of the column-wise one."""
    from aliasing.sweep.rows import _csv_cells

    head = _csv_cells([r.scheme.name, *task.cells, float(task.ratio), float(task.fov)]).replace("%", "%%")
    line = head + ",%.10g,%.10g,%d,%.10g,%.10g,%.10g,%d,%.10g,%.10g\n"
    n, k = r.M_x.shape
    mx, mz, s, used, npr, eta = r.M_x.tolist(), r.M_z.tolist(), r.S.tolist(), r.maps_used.tolist(), r.n_prime.tolist(), r.eta.tolist()
    g, a = gamma.tolist(), azimuth.tolist()
    return "".join([line % (g[i], a[i], j, mx[i][j], mz[i][j], s[i], used[i], npr[i][j], eta[i][j]) for i in range(n) for j in range(k)])


def output(args) -> None:
    from aliasing import geometry, schemes
    import dataclasses

    from aliasing.sweep.chunks import compute_chunk

    load = os.getloadavg()
    print(f"python {platform.python_version()}, numpy {np.__version__}, {os.cpu_count()} CPUs, {platform.machine()}, load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at start")
    names = "ZP3+LogP,P,LogP,FPc+P"
    light = f"hemisphere:{args.directions}"
    with tempfile.TemporaryDirectory() as tmp:
        runs = (("summary (baseline)", "csv", True), ("per-direction CSV", "csv", False), ("Parquet", "parquet", False))
        grids = {label: S.plan(names, f_over_n=1000, fov=60, light=light, summary=summary) for label, _, summary in runs}
        samples: dict[str, list[float]] = {label: [] for label, _, _ in runs}
        cpu: dict[str, list[float]] = {label: [] for label, _, _ in runs}
        sizes = {}
        for _ in range(args.repeats):  # interleaved rounds, so that load changes hit all three alike
            for label, fmt, _ in runs:
                out = Path(tmp) / f"out.{fmt}"
                c0 = _cpu()
                t0 = time.perf_counter()
                S.execute(grids[label], fmt, out, jobs=2)
                samples[label].append(time.perf_counter() - t0)
                cpu[label].append(_cpu() - c0)
                sizes[label] = out.stat().st_size / 1e6
        times = {label: float(np.median(v)) for label, v in samples.items()}
        print(f"wall, median of {args.repeats} interleaved rounds; per round: " + "; ".join(f"{k} " + " ".join(f"{t:.2f}" for t in v) for k, v in samples.items()))
        cpu_med = {label: float(np.median(v)) for label, v in cpu.items()}
        print("CPU time of the parent and its worker processes (median): " + ", ".join(f"{k} {t:.2f} s ({t / cpu_med['summary (baseline)']:.2f}x)" for k, t in cpu_med.items()))
        base = times["summary (baseline)"]
        rows = S.plan(names, f_over_n=1000, fov=60, light=light).size
        for label, t in times.items():
            print(f"{label:20s} {rows:,} rows, jobs 2: {t:.2f} s, {sizes[label]:.1f} MB, {t / base:.2f}x the summary run")
        grid = S.plan("ZP3+LogP", f_over_n=1000, fov=60, light="hemisphere:20000")
        task = grid.chunk(0, "csv")
        r = schemes.evaluate(task.name, task.near, task.near * task.ratio, task.fov, task.light)
        gamma, azimuth = geometry.direction_angles(task.light)
        ready = dataclasses.replace(task, shared={"result": r, "angles": (gamma, azimuth)})  # the text alone
        assert compute_chunk(ready) == _rowwise_fragment(task, gamma, azimuth, r)
        col = best_of(lambda: compute_chunk(ready), args.repeats)
        row = best_of(lambda: _rowwise_fragment(task, gamma, azimuth, r), args.repeats)
        ev = best_of(lambda: schemes.evaluate(task.name, task.near, task.near * task.ratio, task.fov, task.light), args.repeats)
        print(f"one ZP3+LogP chunk of 20,000 rows: evaluate {ev * 1e3:.0f} ms, CSV vectorized {col * 1e3:.0f} ms, row-wise %-format (baseline) {row * 1e3:.0f} ms: {row / col:.2f}x")
        many = names.split(",")
        lv = task.light
        one = best_of(lambda: [schemes.evaluate(n, 1.0, 1000.0, 60.0, lv) for n in many], args.repeats)
        shared = best_of(lambda: schemes.evaluate_many(many, 1.0, 1000.0, 60.0, lv), args.repeats)
        print(f"the four schemes on one block of 20,000 directions: one evaluate each {one * 1e3:.0f} ms, one evaluate_many (a batch) {shared * 1e3:.0f} ms: {one / shared:.2f}x")
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at end")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--directions", type=int, default=250_000, help="directions per scheme (default 250,000: 10^6 evaluations)")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--dask-chunks", type=int, default=400, help="chunks for the Dask overhead measurement")
    parser.add_argument("--no-dask", action="store_true")
    parser.add_argument("--output", action="store_true", help="only part 3: 10^6 rows as CSV and Parquet vs the summary run")
    args = parser.parse_args()
    if args.output:
        output(args)
        return

    print(f"python {platform.python_version()}, numpy {np.__version__}, {os.cpu_count()} CPUs, {platform.machine()}")
    light = f"hemisphere:{args.directions}"
    with tempfile.TemporaryDirectory() as tmp:
        for summary in (False, True):
            grid = S.plan(SCHEMES, f_over_n=1000, fov=60, light=light, summary=summary)
            label = "summary CSV" if summary else "per-direction CSV"
            times = {}
            for jobs in (1, 2):
                out = Path(tmp) / f"s{jobs}.csv"
                times[jobs] = best_of(lambda: S.execute(grid, "csv", out, jobs=jobs), args.repeats)
                size = out.stat().st_size / 1e6
            rate = grid.size / times[2] / 1e6
            print(f"{label:18s} {grid.size:,} evaluations, {grid.chunks} chunks, {size:.1f} MB: "
                  f"jobs 1 {times[1]:.2f} s, jobs 2 {times[2]:.2f} s, speed-up {times[1] / times[2]:.2f}x, {rate:.2f} M evaluations/s (jobs 2)")

    if args.no_dask:
        return
    from distributed import LocalCluster

    n = args.dask_chunks
    tiny = S.plan("P", f_over_n=1000, fov=60, light=f"hemisphere:{n}", summary=True, block=1)
    local = best_of(lambda: S.execute(tiny, "csv"), args.repeats)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        S.execute(tiny, "csv", dask=cluster.scheduler_address)  # warm-up: workers import aliasing
        remote = best_of(lambda: S.execute(tiny, "csv", dask=cluster.scheduler_address), args.repeats)
    print(f"dask overhead: {n} one-direction chunks: in-process {local * 1e3:.0f} ms, LocalCluster (2 processes) {remote * 1e3:.0f} ms "
          f"(including client connect): {(remote - local) / n * 1e3:.2f} ms per chunk")


if __name__ == "__main__":
    sys.exit(main())
