"""Benchmark of the numpy rasterizer (aliasing.raster); run by hand, not under pytest.

Times depth maps of a seeded ~10,000-triangle scene (a ground grid of 2·50² triangles and
417 boxes of 12, over f/n = 1000) through the Standard, P and LogP maps of one light
(γ = 60°, azimuth 20°, fov 60°), and the eye pass, at the given resolutions; best of
``--repeats`` runs (time.perf_counter), setup (scene, map fit) outside the timed region.
Beside each map, in the same run, the ray-casting reference
(:func:`aliasing.raster.validate.raycast.raycast_shadow_map`, Intel Embree through embreex: one
orthographic ray per texel through its centre mapped back to the light plane, BVH build
included) is timed the same way; the script prints raster / ray-cast time and the fraction of
texels whose depths agree (:func:`aliasing.raster.validate.raycast.agreement`).  Without embreex
(``pip install ".[bench]"``) it says so on one line and skips that part.
The eye pass (occlusion-culled, :mod:`aliasing.raster.draw.occlusion`) is timed interleaved with
the three depth maps (one round = each map, then the eye pass, then the compiled eye pass
``backend="numba"`` when numba is installed, then the plain reference eye
pass as it was before the speed work — ``reference_eye_pass`` of tests/reference_eye.py, imported by path: the plain z-buffer in
triangle order and masked positions — so that load changes hit all alike); the script prints eye pass /
depth map for each map and each eye pass, the speed-up over the reference, whether the buffers are identical,
wall-clock and CPU time (process_time; its system part from os.times), best of the rounds or with ``--median`` their median, and the
load average (os.getloadavg) before and after.  Then, once per resolution and outside the
timings, the peak of traced allocations (tracemalloc) of one LogP map.  Pin one core with e.g. ``taskset -c 0`` and
``OMP_NUM_THREADS=1``; the rasterizer itself does not use threads, and Embree's threads
(TBB, BVH build only) are held to the pinned core.

Usage::

    python benchmarks/raster.py                       # 2048², best of 3
    python benchmarks/raster.py --res 2048 4096 --repeats 5
    python benchmarks/raster.py --no-raycast          # without the ray-casting reference
    python benchmarks/raster.py --no-reference        # without the plain (earlier) eye pass
    python benchmarks/raster.py --no-raycast --median --repeats 7   # the eye-pass ratios against the 1.5x target
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import time
from pathlib import Path
import tracemalloc

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from aliasing import raster  # noqa: E402
from aliasing.raster.draw import compiled  # noqa: E402
from aliasing.raster.validate import raycast  # noqa: E402
from _timing import timed  # noqa: E402 - the shared timer, benchmarks/_timing.py

NEAR, FAR, FOV, LIGHT = 1.0, 1000.0, 60.0, "gamma:60@azimuth:20"


def _reference_eye_pass():
    """tests/reference_eye.py's reference_eye_pass, imported by path (the package ships no reference code)."""
    spec = importlib.util.spec_from_file_location("reference_eye", Path(__file__).resolve().parents[1] / "tests" / "reference_eye.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.reference_eye_pass



def rounds(fns: dict, repeats: int, stat=min) -> tuple[dict, dict, dict, dict]:
    """Interleaved timing: ``repeats`` rounds of every function; ``stat`` (best, or median) of the
    wall and CPU times [s], the kernel's share of the CPU time (system time [s], from
    os.times), and the last outputs.

    A function's previous output is released before it runs again: an eye pass's 300 MB of
    buffers kept alive across the next call made the kernel compact memory for the new
    huge pages (transparent huge pages, defrag=madvise here), 0.1–0.3 s of system time
    charged to whichever function ran next.
    """
    walls = {k: [] for k in fns}
    cpus = {k: [] for k in fns}
    syss = {k: [] for k in fns}
    out = {}
    for _ in range(repeats):
        for k, fn in fns.items():
            out.pop(k, None)
            s0, w0, c0 = os.times().system, time.perf_counter(), time.process_time()
            out[k] = fn()
            walls[k].append(time.perf_counter() - w0)
            cpus[k].append(time.process_time() - c0)
            syss[k].append(os.times().system - s0)
    agg = lambda d: {k: float(stat(v)) for k, v in d.items()}  # noqa: E731
    return agg(walls), agg(cpus), agg(syss), out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--res", type=int, nargs="+", default=[2048])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-memory", action="store_true", help="skip the tracemalloc peak")
    ap.add_argument("--no-raycast", action="store_true", help="skip the ray-casting reference")
    ap.add_argument("--no-reference", action="store_true", help="skip the plain (earlier) eye pass")
    ap.add_argument("--no-numba", action="store_true", help="skip the compiled eye pass (backend='numba', the fast extra)")
    ap.add_argument("--median", action="store_true", help="median of the interleaved rounds instead of the best")
    args = ap.parse_args(argv)
    numba_eye = not args.no_numba and compiled.available()
    if not args.no_numba and not numba_eye:
        print("compiled eye pass skipped: numba is not installed (pip install \".[fast]\")")
    if numba_eye:  # compile (or load the cached kernels) outside the timings
        raster.eye_pass(raster.ground_and_boxes(NEAR, FAR, FOV, boxes=3, ground_cells=2, seed=0).triangles, FOV, 16, backend="numba")
    cast = not args.no_raycast and raycast.available()
    if not args.no_raycast and not cast:
        print("ray-casting reference skipped: embreex is not installed (pip install \".[bench]\")")
    scene = raster.ground_and_boxes(NEAR, FAR, FOV, boxes=417, ground_cells=50, seed=args.seed)
    print(f"scene: {len(scene.triangles)} triangles, seed {args.seed}; light {LIGHT}, f/n {FAR / NEAR:g}, fov {FOV:g}")
    maps = {name: raster.light_map(NEAR, FAR, FOV, LIGHT, name) for name in ("Standard", "P", "LogP")}
    for res in args.res:
        times = {}
        for name, lm in maps.items():
            sec, m = timed(lambda lm=lm: raster.shadow_map(scene.triangles, lm, res), args.repeats)
            times[name] = sec
            cover = float(np.isfinite(m.depth).mean())
            print(f"{res}² {name:8s} depth map {sec:7.3f} s   covered {cover:6.1%}   rasterized {m.rasterized}, degenerate {m.degenerate}")
            if cast:
                ray_sec, r = timed(lambda lm=lm: raycast.raycast_shadow_map(scene.triangles, lm, res), args.repeats)
                agree = raycast.agreement(m, r, scene.triangles)
                differ = int((m.triangle != r.triangle).sum())
                print(f"{res}² {name:8s} ray cast  {ray_sec:7.3f} s   raster / ray cast {sec / ray_sec:.2f}   "
                      f"depths agree on {agree:.5%} of texels ({res * res * (1 - agree):.0f} differ; {differ} name another triangle)")
        # LogP's map covers more of the scene than Standard's (it fits the frustum tighter in t):
        # LogP / P compares the logarithmic rasterization with the same map rasterized straight
        print(f"{res}² LogP / P {times['LogP'] / times['P']:.2f}, LogP / Standard {times['LogP'] / times['Standard']:.2f}, P / Standard {times['P'] / times['Standard']:.2f}")
        # the eye pass against the depth maps, interleaved rounds
        fns = {name: (lambda lm=lm: raster.shadow_map(scene.triangles, lm, res)) for name, lm in maps.items()}
        fns["eye"] = lambda: raster.eye_pass(scene.triangles, FOV, res)
        if numba_eye:
            fns["eye numba"] = lambda: raster.eye_pass(scene.triangles, FOV, res, backend="numba")
        if not args.no_reference:
            fns["reference"] = lambda ref=_reference_eye_pass(): ref(scene.triangles, FOV, res)
        load0 = os.getloadavg()[0]
        wall, cpu, sys_, out = rounds(fns, args.repeats, stat=np.median if args.median else min)
        load1 = os.getloadavg()[0]
        eb = out["eye"]
        stat = "median" if args.median else "best"
        print(f"{res}² eye pass          {wall['eye']:7.3f} s (CPU {cpu['eye']:.3f} s; {stat} of {args.repeats} rounds)   "
              f"covered {float((eb.triangle >= 0).mean()):6.1%}   load average {load0:.2f} before, {load1:.2f} after")
        for eye in [k for k in ("eye", "eye numba") if k in out]:
            for name in maps:
                print(f"{res}² {eye:9s} / {name:8s} depth map: wall {wall[eye] / wall[name]:.2f} (eye {wall[eye]:.3f} s, map {wall[name]:.3f} s), "
                      f"CPU {cpu[eye] / cpu[name]:.2f} (eye {cpu[eye]:.3f} s, map {cpu[name]:.3f} s; of which system {sys_[eye]:.3f} s, {sys_[name]:.3f} s)")
        if "eye numba" in out:
            nb = out["eye numba"]
            same = np.array_equal(eb.triangle, nb.triangle) and np.array_equal(eb.position, nb.position, equal_nan=True) and np.array_equal(eb.normal, nb.normal, equal_nan=True)
            print(f"{res}² numpy / numba eye pass: wall {wall['eye'] / wall['eye numba']:.2f}, CPU {cpu['eye'] / cpu['eye numba']:.2f}; identical buffers: {same}")
        if "reference" in out:
            pos, nrm, ident = out["reference"]
            same = np.array_equal(eb.triangle, ident) and np.array_equal(eb.position, pos, equal_nan=True) and np.array_equal(eb.normal, nrm, equal_nan=True)
            print(f"{res}² reference eye pass {wall['reference']:7.3f} s (CPU {cpu['reference']:.3f} s)   reference / eye pass {wall['reference'] / wall['eye']:.2f} "
                  f"(CPU {cpu['reference'] / cpu['eye']:.2f}), reference / Standard {wall['reference'] / wall['Standard']:.2f}; identical buffers: {same}")
        if not args.no_memory:
            tracemalloc.start()
            raster.shadow_map(scene.triangles, maps["LogP"], res)
            peak = tracemalloc.get_traced_memory()[1]
            tracemalloc.stop()
            print(f"{res}² LogP depth map peak traced memory {peak / 2**20:.0f} MiB")


if __name__ == "__main__":
    main()
