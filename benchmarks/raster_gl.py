"""Benchmark of the gl backend against the numpy rasterizer (depth maps); run by hand, not under pytest.

The seeded city block (:func:`aliasing.raster.scenes.procedural.city`) at 10⁴ and 10⁶
triangles, seen by its "street" camera (near 0.5, far 600, fov 60°) and converted to eye
space, one light (world direction (−1, 0.8, 0.3)), the P map fitted to the view frustum: the
scene of benchmarks/scenes.py.  Timed (wall clock, time.perf_counter, and the process's CPU
time, which counts llvmpipe's threads): ``shadow_map(tri, lm, R)`` with ``backend="numpy"``
and ``backend="gl"`` at R = 2048 and 8192, the readback into float64 / int64 arrays included
(the call returns the same DepthMap either way; a gl map stays on the device until its arrays
are first read, so the timed call reads them).  The rounds interleave every case of both
backends; the figures are medians over the rounds.  The OpenGL context is made and the
shaders compiled once, before the rounds (printed).  Each round also checks that the two maps
agree (coverage difference, same visible triangle, depth gap) so that a fast wrong answer
cannot pass.  The renderer's name is printed: llvmpipe on a CPU, or the GPU's.

Targets: gl ≤ 0.1 × numpy at 2048² with 10⁴ triangles, ≤ 0.02 × numpy with 10⁶ triangles.

Usage::

    python benchmarks/raster_gl.py                 # 3 rounds, 10⁴ and 10⁶ triangles, 2048² and 8192²
    python benchmarks/raster_gl.py --rounds 5 --quick   # 10⁴ triangles only
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from aliasing import raster  # noqa: E402
from aliasing.raster.draw import gl  # noqa: E402
from scenes import scene  # noqa: E402 - the city and its P map of benchmarks/scenes.py


def timed(fn):
    w0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - w0, time.process_time() - c0, out


def read(m: raster.DepthMap) -> raster.DepthMap:
    """The map with its arrays on the host (a gl map is read back when they are first asked for)."""
    m.depth, m.triangle
    return m


def agreement(a: raster.DepthMap, b: raster.DepthMap) -> tuple[float, float, float]:
    """(coverage difference, same-triangle fraction, largest depth difference there / depth range)."""
    ca, cb = a.triangle >= 0, b.triangle >= 0
    both = ca & cb
    same = both & (a.triangle == b.triangle)
    gap = float(np.abs(a.depth[same] - b.depth[same]).max() / np.ptp(a.depth[ca]))
    return float((ca != cb).mean()), float(same.sum() / both.sum()), gap


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="skip the 10⁶-triangle scene")
    ap.add_argument("--res", type=int, nargs="+", default=[2048, 8192])
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    gl.require()
    print(f"renderer: {gl.renderer()} (context and shaders ready in {time.perf_counter() - t0:.2f} s)")
    counts = [10_000] + ([] if args.quick else [1_000_000])
    scenes = {n: scene(n) for n in counts}
    cases = [(n, r) for n in counts for r in args.res]
    # warm-up: one small gl draw per resolution (llvmpipe compiles shader variants on first use)
    for r in args.res:
        raster.shadow_map(scenes[counts[0]][0], scenes[counts[0]][1], r, backend="gl")
    load = [os.getloadavg()[0]]
    times: dict[tuple, list[tuple[float, float]]] = {(n, r, b): [] for n, r in cases for b in ("numpy", "gl")}
    checks: dict[tuple, list[tuple[float, float]]] = {c: [] for c in cases}
    for k in range(args.rounds):
        for n, r in cases:
            tri, lm = scenes[n]
            w, c, ref = timed(lambda: raster.shadow_map(tri, lm, r))
            times[(n, r, "numpy")].append((w, c))
            w, c, got = timed(lambda: read(raster.shadow_map(tri, lm, r, backend="gl")))
            times[(n, r, "gl")].append((w, c))
            checks[(n, r)].append(agreement(ref, got))
            del ref, got
        load.append(os.getloadavg()[0])
        print(f"round {k + 1}/{args.rounds} done, load average {load[-1]:.2f}", flush=True)
    print(f"\nload average (1 min) before and after each round: {' → '.join(f'{x:.2f}' for x in load)}")
    print(f"medians over {args.rounds} rounds [s]; gl / numpy of the medians")
    print("| triangles | map | numpy wall | gl wall | gl / numpy (wall) | numpy CPU | gl CPU | gl / numpy (CPU) | coverage differs | same triangle | depth gap / range |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n, r in cases:
        tri, _ = scenes[n]
        nw, nc = np.median(np.array(times[(n, r, "numpy")]), axis=0)
        gw, gc = np.median(np.array(times[(n, r, "gl")]), axis=0)
        cov = max(c[0] for c in checks[(n, r)])
        same = min(c[1] for c in checks[(n, r)])
        gap = max(c[2] for c in checks[(n, r)])
        print(f"| {len(tri):,} | {r}² | {nw:.3f} | {gw:.3f} | **{gw / nw:.3f}** | {nc:.3f} | {gc:.3f} | {gc / nc:.3f} | {cov:.1e} | {same:.5f} | {gap:.1e} |")


if __name__ == "__main__":
    main()
