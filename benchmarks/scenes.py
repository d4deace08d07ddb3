"""Benchmark of depth maps of large scenes (aliasing.raster.scenes.procedural); run by hand, not under pytest.

The seeded city block (:func:`aliasing.raster.scenes.procedural.city`, 400 × 400 world units)
at 10⁴ … 10⁶ triangles, seen by its "street" camera (near 0.5, far 600, fov 60°), converted
to eye space, one light (world direction (−1, 0.8, 0.3)), the P map fitted to the view
frustum.  Timed (best of ``--repeats``, time.perf_counter): :func:`aliasing.raster.shadow_map`
of the whole scene, setup (scene, conversion, map fit) outside the timed region.

* target: the 10⁶-triangle time at most 2× the 10⁴-triangle time scaled by the triangle
  count (the baseline is the same call on the small scene, timed in the same run);
* the peak of traced allocations (tracemalloc) of the 10⁶-triangle, 2048² map, and the
  process's peak resident memory (resource.getrusage ru_maxrss) at the end;
* how cost grows: triangles at 2048², and resolution at 10⁵ triangles.

Usage::

    python benchmarks/scenes.py                      # 1e4, 1e5, 1e6 at 2048²; 512²..4096² at 1e5
    python benchmarks/scenes.py --repeats 3 --quick  # 1e4, 1e5 only
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import tracemalloc

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from aliasing import raster  # noqa: E402
from aliasing.raster.scenes import procedural  # noqa: E402
from _timing import best_of  # noqa: E402 - the shared timer, benchmarks/_timing.py

LIGHT_WORLD = (-1.0, 0.8, 0.3)



def scene(count: int):
    cam = procedural.street_camera()
    tri = cam.to_eye(procedural.city(count, seed=1))
    lm = raster.light_map(cam.near, cam.far, cam.fov, cam.direction_to_eye(LIGHT_WORLD), "P")
    return tri, lm


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="skip the 10⁶-triangle scene")
    args = ap.parse_args(argv)
    print(f"load average (1, 5, 15 min): {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    counts = [10_000, 100_000] + ([] if args.quick else [1_000_000])
    times = {}
    print("triangles  res   time [s]  per 1e6 triangles [s]  texels covered")
    for n in counts:
        tri, lm = scene(n)
        t = best_of(lambda: raster.shadow_map(tri, lm, 2048), args.repeats if n < 1_000_000 else max(1, args.repeats - 1))
        m = raster.shadow_map(tri, lm, 2048)
        times[n] = t
        print(f"{len(tri):9d}  2048  {t:8.3f}  {t / len(tri) * 1e6:21.3f}  {int(np.isfinite(m.depth).sum()):14d}")
    if 1_000_000 in times:
        ratio = times[1_000_000] / (times[10_000] * 100)
        print(f"1e6 time / (1e4 time × 100) = {ratio:.3f}  (target <= 2)")
        tri, lm = scene(1_000_000)
        tracemalloc.start()
        raster.shadow_map(tri, lm, 2048)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        print(f"traced peak of the 1e6-triangle 2048² map: {peak / 2**20:.0f} MiB (scene array {tri.nbytes / 2**20:.0f} MiB held before)")
    tri, lm = scene(100_000)
    print("resolution at 1e5 triangles:  res   time [s]")
    for res in (512, 1024, 2048, 4096):
        t = best_of(lambda: raster.shadow_map(tri, lm, res), args.repeats)
        print(f"{'':29s}{res:5d}  {t:8.3f}")
    print(f"process peak resident memory: {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB")
    print(f"load average (1, 5, 15 min): {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
