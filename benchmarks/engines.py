"""Time one ``aliasing engines`` comparison over 20,000 light directions; run by hand, not under pytest.

The comparison is :func:`aliasing.engines.compare.compare` with the default scheme list of
``aliasing engines`` (csm:filament, csm-stable:filament, sdsm:k=4, vsm:high, vsm:epic,
matched, exact) at near 10 cm, far 1 km, fov 60°, 1920 px, 4 × 2048² per cascade; the
directions (``hemisphere_directions(N)``) are built once, outside the timed region.  The
plain baseline timed side by side in the same run is the papers' evaluation of the same
number of maps, ``schemes.evaluate("Standard", edges=log split, light=directions)``: a tight
fit of 4 cascades over the same directions.  Each figure is the best of ``--repeats`` runs
(``time.perf_counter``); the load average is printed with the result.

    python benchmarks/engines.py                    # 20,000 directions, best of 3
    python benchmarks/engines.py --counts 2000 20000 --repeats 5
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from aliasing import geometry, partitioning, schemes
from aliasing.engines import compare
from _timing import best_of  # the shared timer (benchmarks/_timing.py; run these as scripts)

SCHEMES = ["csm:filament", "csm-stable:filament", "sdsm:k=4", "vsm:high", "vsm:epic", "matched", "exact"]
NEAR, FAR, FOV = 10.0, 1e5, 60.0



def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--counts", type=int, nargs="+", default=[20_000])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    edges = partitioning.split_distances("log", NEAR, FAR, 4)
    print(f"machine: {os.cpu_count()} cores, {platform.processor() or platform.machine()}, Python {platform.python_version()}, numpy {np.__version__}")
    print("| directions | comparison [s] | baseline ZP4 Standard [s] | ratio |")
    print("|---:|---:|---:|---:|")
    for n in args.counts:
        lv = geometry.hemisphere_directions(n)
        t_cmp = best_of(lambda: compare.compare(SCHEMES, fov=FOV, near=NEAR, far=FAR, lights=lv), args.repeats)
        t_base = best_of(lambda: schemes.evaluate("Standard", NEAR, FAR, FOV, lv, edges=edges), args.repeats)
        print(f"| {n:,} | {t_cmp:.3f} | {t_base:.3f} | {t_cmp / t_base:.1f} |")
    print(f"load average (1, 5, 15 min) after the run: {os.getloadavg()}")


if __name__ == "__main__":
    main()
