"""``aliasing.tune.tune`` against one ``check`` and against the exhaustive grid it replaces, in the same run.

The three.js developer's case: three.js r187's CSM addon, a 16:9 camera (near 0.1, far 500, fov 50°,
1080 rows), the sun 15..60° (7 elevations), front faces casting, slopes to 10° acne-free.  Two
searches: the count and the map size kept (4 × 2048²: the split mode, λ and the biases searched),
and everything free within the texels of the engine's default (3 × 2048²).  Baselines: one
:func:`aliasing.check.check` of the start, and the exhaustive grid over the same settings evaluated
by ``check`` (λ at the profile's step of 0.05; map sizes within the budget).  Median of ``--runs``.

Run: ``python benchmarks/tune.py [--runs 5]``.
"""

from __future__ import annotations

import argparse
import itertools
import platform
import statistics
import time

import numpy as np

from aliasing import setups
from aliasing.check import check
from aliasing.tune import tune

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"


def median_of(fn, runs: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(runs):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def grid(start, fixed: tuple, budget: int) -> tuple[float, int]:
    """The grid's best worst error by check and the number of checks."""
    prof = start.profile
    free = [t for t in prof.tunable if t.role in ("cascades", "size", "split") and t.key not in fixed]
    base = dict(start.settings)
    discrete = [t for t in free if t.range is None and t.active(base)]
    best, n = np.inf, 0
    for combo in itertools.product(*(t.values for t in discrete)):
        s = {**base, **{t.key: v for t, v in zip(discrete, combo)}}
        cont = [t for t in free if t.range is not None and t.active(s)]
        for values in itertools.product(*(t.grid() for t in cont)):
            su = setups.Setup(prof, {**s, **{t.key: v for t, v in zip(cont, values)}}, start.camera, start.sun)
            if su.pipeline.k * su.pipeline.resolution ** 2 > budget:
                continue
            n += 1
            best = min(best, max(c["error_max"] for c in check(su).cascades))
    return best, n


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    print(f"python {platform.python_version()}, numpy {np.__version__}, median of {args.runs}")
    for label, settings, fixed in (("count and size kept (4 x 2048^2)", {"cascades": 4}, ("cascades", "shadowMapSize")),
                                   ("everything free (3 x 2048^2 texels)", {}, ())):
        start = setups.build("threejs", {**settings, "material.shadowSide": "FrontSide"}, CAMERA, "15..60")
        budget = start.pipeline.k * start.pipeline.resolution ** 2
        t_tune, tuned = median_of(lambda: tune(start, keep=fixed, max_slope=10.0), args.runs)
        t_check, _ = median_of(lambda: check(start), args.runs)
        t_grid, (best, n) = median_of(lambda: grid(start, fixed, budget), args.runs)
        print(f"-- {label}")
        print(f"tune                      {t_tune * 1e3:9.1f} ms   objective {tuned.objective:.4g}  ({tuned.evaluations} setups measured)")
        print(f"one check                 {t_check * 1e3:9.1f} ms   tune / check = {t_tune / t_check:6.1f}")
        print(f"exhaustive grid by check  {t_grid * 1e3:9.1f} ms   best {best:.4g} ({n} checks)   grid / tune = {t_grid / t_tune:6.1f}")


if __name__ == "__main__":
    main()
