"""Engine scale: shimmer, validation and rendering with 2048² maps, wall time and peak memory per backend.

Run by hand, not under pytest.  Each case runs the command line (``aliasing.cli.main``) in a
fresh subprocess, which reports its own peak resident memory when it ends (``VmHWM`` of
``/proc/self/status``: the peak of its own address space; ``ru_maxrss`` elsewhere); the wall time is the parent's ``time.perf_counter`` around the
subprocess (interpreter start-up and imports included).  The backends run side by side in
the same run, case by case, alternating, best of ``--repeats``:

* ``shimmer``: ``aliasing shimmer --schemes csm:threejs-csm:k=4 --motion translate:0.05,0,0
  --frames 30 --near 0.1 --far 500 --fov 50 --aspect 1.7778 --image-res 96 --shadow-res 2048``
  (4 cascades of 2048², one point per pixel of a 96-row image, the prediction included: its
  12 shifted copies of every frame-0 map);
* ``validate``: ``aliasing validate --scene city.obj`` (the procedural city of
  ``aliasing shimmer --scene city``, written to a temporary OBJ, seen from its street camera),
  ``--scheme Standard --splits log -k 4 --res 2048`` (a 2048² eye pass);
* ``render``: ``aliasing render --scene city.obj`` with the same camera, 4 log-split cascades
  sharing a 4096² budget (2048² each), a 512² image.

``--before DIR`` runs the numpy cases also with the package found in DIR (e.g. an export of
an earlier commit: ``git archive <commit> aliasing | tar -x -C DIR``), in the same run.

Usage::

    python benchmarks/engine_scale.py                       # all cases, numpy and gl, best of 1
    python benchmarks/engine_scale.py --cases shimmer --repeats 3 --before /tmp/base
    python benchmarks/engine_scale.py --cases shimmer --test-step   # also a gl map's steps: draw, test on the device, on the host, the floor
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The child's own peak: VmHWM of its address space (Linux).  ru_maxrss is not used: after a
# fork and exec it keeps the forking parent's peak (this script holds a gl context).
PEAK = """
import resource, sys
from aliasing.cli import main
code = main(sys.argv[1:])
try:
    peak = next(int(line.split()[1]) * 1024 for line in open("/proc/self/status") if line.startswith("VmHWM:"))
except OSError:
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * (1 if sys.platform == "darwin" else 1024)
print("peak-bytes", peak, file=sys.stderr)
sys.exit(code)
"""

CAMERA = ["--eye=-66,20,-66", "--target=-31.43,9.52,-31.43", "--near", "0.5", "--far", "180", "--light-dir=-1,2,0.5"]


def cases(city: str, png: str) -> dict[str, list[str]]:
    return {
        "shimmer": ["shimmer", "--schemes", "csm:threejs-csm:k=4", "--motion", "translate:0.05,0,0", "--frames", "30", "--near", "0.1", "--far", "500",
                    "--fov", "50", "--aspect", "1.7778", "--image-res", "96", "--shadow-res", "2048", "--format", "json"],
        "validate": ["validate", "--scene", city, *CAMERA, "--scheme", "Standard", "--splits", "log", "-k", "4", "--res", "2048", "--format", "json"],
        "render": ["render", "--scene", city, *CAMERA, "--scheme", "Standard", "--splits", "log", "-k", "4", "--res", "4096", "--image-res", "512",
                   "--format", "json", "--out", png],
    }


def write_city(path: str) -> None:
    """The city of ``aliasing shimmer --scene city`` as an OBJ file."""
    sys.path.insert(0, ROOT)
    from aliasing.raster.scenes import procedural

    tri = procedural.city(20_000, seed=1, size=120.0)
    with open(path, "w") as f:
        f.write("".join(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in tri.reshape(-1, 3)))
        f.write("".join(f"f {3 * i + 1} {3 * i + 2} {3 * i + 3}\n" for i in range(len(tri))))


def run(src: str, argv: list[str]) -> tuple[float, int, str]:
    """(wall [s], peak resident [bytes], stdout) of one command in a fresh interpreter using the package in ``src``."""
    env = {**os.environ, "PYTHONPATH": src, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", PEAK, *argv], capture_output=True, text=True, env=env, cwd=src)
    wall = time.perf_counter() - start
    if done.returncode not in (0, 1):  # validate exits 1 on a failed validation, with its report
        raise SystemExit(f"{' '.join(argv[:1])} failed ({done.returncode}): {done.stderr.strip()[-400:]}")
    peak = int(next(line.split()[1] for line in done.stderr.splitlines() if line.startswith("peak-bytes")))
    return wall, peak, done.stdout


def summary(name: str, out: str) -> str:
    """A few numbers of the output, to see that the backends computed the same thing."""
    data = json.loads(out)
    if name == "shimmer":
        r = data[0]
        return f"flips {r['flip_fraction']:.5f}, predicted/measured {r['predicted_over_measured']:.3f}, maps {r['maps_drawn']}"
    if name == "validate":
        return f"max ratio {data['max_ratio']:.6f}, pixels {sum(data['pixels'])}"
    s = data["schemes"][0]
    return f"p50 {s['p50']:.4f}, p99 {s['p99']:.4f}, max {s['max']:.4f}"


def test_step(repeats: int) -> float | None:
    """The gl shimmer case's frame-0 maps in this process, the steps of one map timed apart
    (the best of ``repeats`` × 10, as the machine's load allows): drawing its box of ids, the shadow test of its points run on
    the device (one bit per point back), and the same test on the host (the texels fetched back,
    compared in numpy), and the floor of drawing each map's box (:func:`_floor`); returns the mean floor per map [s]."""
    sys.path.insert(0, ROOT)
    import numpy as np

    from aliasing.raster.draw import gl, lookup, resident
    from aliasing.temporal import fits, paths, points, render

    if not gl.available():
        print(f"test step skipped: {gl._setup()[1]}")
        return None
    w = points.world("boxes", near=0.1, far=500.0, fov=50.0, aspect=1.7778)
    pts = points.sample(w, 96)
    cam = w.camera
    poses = paths.frames(paths.parse_motion("translate:0.05,0,0"), cam.eye, cam.rotation, cam.fov, w.light, 2)
    lat = fits.plan("csm:threejs-csm:k=4", w, poses, 2048, positions=pts.position, image_res=pts.resolution)
    part = fits.assign(lat, fits.eye_coordinates(pts.position, poses[0], poses[1]), poses[2], cam.near, cam.far)
    cache = render.MapCache(w.triangles, backend="gl")
    ctx = gl._context()
    n = 10 * max(repeats, 1)
    steps = {"draw": [], "device": [], "host": [], "floor": []}
    floor = _floor(ctx, 2048)
    same = True
    for k in np.unique(part[0][part[0] >= 0]):
        sel = np.nonzero(part[0] == k)[0]
        p, nrm = pts.position[sel], pts.normal[sel]
        cache.test(lat, 0, int(k), p, nrm)  # drawn over the box of the points' texels
        lm, sm, sub = cache.maps[next(reversed(cache.maps))]
        box, matrix = sm._device.box, lm.matrix()
        times = []
        for _ in range(n):
            start = time.perf_counter()
            m = resident.draw_device_map(sub, matrix, 2048, box=box)
            with ctx:
                ctx.finish()
            times.append(time.perf_counter() - start)
            m.release()
        steps["draw"].append(min(times))
        steps["floor"].append(floor(box, n))
        for where, on in (("device", True), ("host", False)):
            lookup._ON_DEVICE = on
            times = []
            for _ in range(n):
                sm._texels, sm._depth, sm._ident = np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64)  # fetched again
                start = time.perf_counter()
                lit = lookup.shadow_test(lm, sm, sub, p, nrm, bias=cache.bias)
                times.append(time.perf_counter() - start)
            steps[where].append(min(times))
            same &= bool(np.array_equal(lit, lookup.shadow_test(lm, sm, sub, p, nrm, bias=cache.bias))) if on else True
            if not on:
                lookup._ON_DEVICE = True
                same &= bool(np.array_equal(lit, lookup.shadow_test(lm, sm, sub, p, nrm, bias=cache.bias)))
        print(f"map {k}: {len(sel)} points, box {box[2]}×{box[3]} texels: draw {steps['draw'][-1] * 1e3:6.2f} ms "
              f"(floor: clear and one quad {steps['floor'][-1] * 1e3:5.2f} ms), "
              f"test on the device {steps['device'][-1] * 1e3:5.2f} ms, on the host (texels fetched) {steps['host'][-1] * 1e3:5.2f} ms")
    lookup._ON_DEVICE = True
    cache.release()
    print(f"frame-0 maps, sum: draw {sum(steps['draw']) * 1e3:.1f} ms (floor {sum(steps['floor']) * 1e3:.1f} ms), "
          f"test on the device {sum(steps['device']) * 1e3:.2f} ms, on the host {sum(steps['host']) * 1e3:.2f} ms; the same states: {same}")
    return sum(steps["floor"]) / len(steps["floor"])


def _floor(ctx, res: int):
    """A timer of the least that drawing a box of a ``res``² map costs on this device: clearing
    the box's ids and z-buffer and filling it with one quad of a shader that writes only the
    primitive's index (no triangle, no depth of our own).  Returns ``time(box, n)``, the best
    of ``n`` [s]."""
    import moderngl
    import numpy as np

    with ctx:
        ids = ctx.texture((res, res), 1, dtype="i4")
        fbo = ctx.framebuffer([ids], ctx.depth_renderbuffer((res, res)))
        prog = ctx.program(vertex_shader="#version 430\nin vec2 p; void main() { gl_Position = vec4(p, 0.5, 1.0); }",
                           fragment_shader="#version 430\nout int id; void main() { id = gl_PrimitiveID; }")
        quad = ctx.buffer(np.array([-1, -1, 1, -1, -1, 1, 1, -1, 1, 1, -1, 1], "f4"))
        vao = ctx.vertex_array(prog, [(quad, "2f", "p")])

    def time_box(box, n: int) -> float:
        best = float("inf")
        with ctx:
            fbo.use()
            fbo.viewport = (0, 0, res, res)
            ctx.enable(moderngl.DEPTH_TEST)
            for _ in range(n):
                ctx.finish()
                start = time.perf_counter()
                fbo.scissor = box
                fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0, viewport=box)
                vao.render()
                ctx.finish()
                best = min(best, time.perf_counter() - start)
            fbo.scissor = None
        return best

    return time_box


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="shimmer,validate,render")
    ap.add_argument("--backends", default="numpy,gl")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--before", metavar="DIR", help="also run the numpy and gl cases with the package in DIR")
    ap.add_argument("--test-step", action="store_true", help="also time, in this process, the steps of the gl shimmer case's frame-0 maps: drawing, the test on the device, on the host, and the floor of drawing (a clear and one quad over each map's box)")
    args = ap.parse_args(argv)
    sys.path.insert(0, ROOT)
    from aliasing.raster.draw import gl

    names = [c.strip() for c in args.cases.split(",") if c.strip()]
    backends = [b.strip() for b in args.backends.split(",") if b.strip()]
    if "gl" in backends and not gl.available():
        print(f"gl skipped: {gl._setup()[1]}")
        backends.remove("gl")
    print(f"renderer: {gl.renderer() or 'none'}; cores: {os.cpu_count()}; load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    with tempfile.TemporaryDirectory() as tmp:
        city = os.path.join(tmp, "city.obj")
        write_city(city)
        table = cases(city, os.path.join(tmp, "render.png"))
        sources = [("", ROOT)] + ([(" (before)", os.path.abspath(args.before))] if args.before else [])
        results: dict[tuple[str, str], tuple[float, int, str]] = {}
        for name in names:
            for _ in range(args.repeats):
                for label, src in sources:
                    for b in backends:
                        wall, peak, out = run(src, table[name] + ["--backend", b])
                        key = (name, b + label)
                        if key not in results or wall < results[key][0]:
                            results[key] = (wall, max(peak, results.get(key, (0, 0))[1]), out)
            for label, _ in sources:
                base = results.get((name, "numpy" + label))
                for b in backends:
                    wall, peak, out = results[(name, b + label)]
                    ratio = f"{wall / base[0]:.3f}" if base else "-"
                    print(f"{name:9s} {b + label:15s} wall {wall:7.2f} s  peak {peak / 2**20:7.0f} MiB  x numpy{label} {ratio:>6s}  {summary(name, out)}", flush=True)
    if args.test_step:
        per_map = test_step(args.repeats)
        shimmer = [(b, results[("shimmer", b)]) for b in backends if ("shimmer", b) in results]
        for b, (wall, _, out) in shimmer:
            maps = json.loads(out)[0]["maps_drawn"]
            if b == "numpy" and per_map is not None:
                print(f"the gl case's {maps} maps at the frame-0 maps' mean floor ({per_map * 1e3:.2f} ms each) take at least "
                      f"{maps * per_map:.2f} s = {maps * per_map / wall:.3f} × numpy's shimmer wall time in this run ({wall:.2f} s)")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
