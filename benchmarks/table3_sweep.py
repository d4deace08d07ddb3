"""Time the Lloyd et al. 2007 Table 3 sweep: 10 schemes over a hemisphere of light directions.

Schemes Standard, P, Po, Log, ZP5, ZP5+P, ZP5+Log, ZP7, ZP7+P, ZP7+Log; f/n = 1000,
θ = 30° (fov 60°); directions from ``aliasing.geometry.hemisphere_directions`` (equal solid
angle, deterministic).  Each figure is the best of ``--repeats`` runs timed with
``time.perf_counter``; the direction set is built once per count, outside the timing.

Prints markdown: the timings per scheme and for the whole sweep at each direction count,
the machine, and (as a sanity check that the sweep computes Table 3) the min / max / mean
of S̄ at 20,000 directions.

    python benchmarks/table3_sweep.py                      # 2,000 / 20,000 / 200,000
    python benchmarks/table3_sweep.py --counts 20000 --repeats 3
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time

import numpy as np

from aliasing import geometry, schemes
from _timing import best_of  # the shared timer (benchmarks/_timing.py; run these as scripts)

SCHEMES = ("Standard", "P", "Po", "Log", "ZP5", "ZP5+P", "ZP5+Log", "ZP7", "ZP7+P", "ZP7+Log")
NEAR, FAR, FOV = 1.0, 1000.0, 60.0  # f/n = 1000, θ = fov/2 = 30°
TARGET_COUNT, TARGET_SECONDS = 20_000, 1.0



def sweep(lights: np.ndarray) -> dict[str, np.ndarray]:
    """S̄ of every scheme for every direction, one ``evaluate`` call per scheme."""
    return {name: schemes.evaluate(name, NEAR, FAR, FOV, lights).S for name in SCHEMES}


def sweep_many(lights: np.ndarray) -> dict[str, np.ndarray]:
    """The same with one ``evaluate_many`` call (light frames shared by all schemes)."""
    return {name: r.S for name, r in zip(SCHEMES, schemes.evaluate_many(SCHEMES, NEAR, FAR, FOV, lights))}


def machine() -> str:
    cpu = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as fh:
            cpu = next(line.split(":", 1)[1].strip() for line in fh if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return f"{cores} cores usable (nproc), {cpu}; Python {platform.python_version()}, numpy {np.__version__}, {platform.system()} {platform.release()}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[2_000, 20_000, 200_000], help="numbers of hemisphere directions")
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per figure; the best is reported")
    args = parser.parse_args(argv)

    per_scheme: dict[int, dict[str, float]] = {}
    total: dict[int, float] = {}
    total_many: dict[int, float] = {}
    for count in args.counts:
        lights = geometry.hemisphere_directions(count)
        sweep(lights[:10])  # warm-up (imports, first-call overheads)
        per_scheme[count] = {name: best_of(lambda name=name: schemes.evaluate(name, NEAR, FAR, FOV, lights), args.repeats) for name in SCHEMES}
        total[count] = best_of(lambda: sweep(lights), args.repeats)
        total_many[count] = best_of(lambda: sweep_many(lights), args.repeats)

    print(f"Table 3 sweep, f/n = {FAR / NEAR:g}, fov = {FOV:g}° (θ = {FOV / 2:g}°), best of {args.repeats}")
    print(f"Machine: {machine()}\n")
    print("| scheme | " + " | ".join(f"{c:,} dirs [ms]" for c in args.counts) + " |")
    print("|---|" + "---:|" * len(args.counts))
    for name in SCHEMES:
        print(f"| {name} | " + " | ".join(f"{1e3 * per_scheme[c][name]:.1f}" for c in args.counts) + " |")
    print("| **sweep (10 schemes)** | " + " | ".join(f"**{1e3 * total[c]:.0f}**" for c in args.counts) + " |")
    print("| µs per direction (sweep) | " + " | ".join(f"{1e6 * total[c] / c:.1f}" for c in args.counts) + " |")
    print("| **sweep, one evaluate_many** | " + " | ".join(f"**{1e3 * total_many[c]:.0f}**" for c in args.counts) + " |")

    if TARGET_COUNT in total:
        verdict = "meets" if total[TARGET_COUNT] < TARGET_SECONDS else "MISSES"
        print(f"\n{TARGET_COUNT:,}-direction sweep: {total[TARGET_COUNT]:.3f} s, {verdict} the {TARGET_SECONDS:g} s target")

    stats = sweep(geometry.hemisphere_directions(TARGET_COUNT))
    print(f"\nS̄ over {TARGET_COUNT:,} hemisphere directions (compare Lloyd et al. 2007 Table 3):\n")
    print("| scheme | min | max | max/min | mean |")
    print("|---|---:|---:|---:|---:|")
    for name, s in stats.items():
        print(f"| {name} | {s.min():.3g} | {s.max():.3g} | {s.max() / s.min():.3g} | {s.mean():.3g} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
