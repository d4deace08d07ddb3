"""Benchmark of a shimmer sequence (aliasing.temporal); run by hand, not under pytest.

A 240-frame sequence of 4 cascades at the ``aliasing shimmer`` defaults: the built-in
``boxes`` scene (or ``--scene city``), one point per pixel of a 128² first frame, 256²
texels per cascade, the camera moving sideways (``translate:0.05,0,0``), measured and
predicted (:func:`aliasing.temporal.measure.shimmer`).  Two schemes:

* ``csm:log:k=4`` (tight fit: its grid moves every frame, so every frame draws 4 maps);
* ``csm-stable:log:k=4:fit=sphere:snap=origin`` (a snapped sphere: a map is drawn again
  only when its corner jumps a texel, otherwise reused).

Baseline, timed side by side in the same run: drawing one frame's 4 depth maps of the
tight fit (:class:`aliasing.temporal.render.MapCache`, fresh).  The ratio sequence/baseline
says how many frames' worth of maps the sequence costs: 240 would be "only the maps, each
drawn once per frame"; the edge-density maps of the prediction (12 shifted copies of the
frame-0 maps) and the shadow tests add to it, map reuse takes from it.  Each time is the
best of ``--repeats`` (time.perf_counter); setup (scene, points) outside the timed region.

Usage::

    python benchmarks/shimmer.py                 # boxes, 240 frames, best of 2
    python benchmarks/shimmer.py --scene city --repeats 1
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from aliasing.temporal import fits, measure, paths, points  # noqa: E402
from aliasing.temporal.render import MapCache  # noqa: E402
from _timing import timed  # noqa: E402 - the shared timer, benchmarks/_timing.py

SCHEMES = ("csm:log:k=4", "csm-stable:log:k=4:fit=sphere:snap=origin")
MOTION = "translate:0.05,0,0"


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="boxes")
    ap.add_argument("--frames", type=int, default=240)
    ap.add_argument("--image-res", type=int, default=128)
    ap.add_argument("--shadow-res", type=int, default=256)
    ap.add_argument("--repeats", type=int, default=2)
    args = ap.parse_args(argv)
    w = points.world(args.scene)
    pts = points.sample(w, args.image_res)
    cam = w.camera
    poses = paths.frames(paths.parse_motion(MOTION), cam.eye, cam.rotation, cam.fov, w.light, 2)
    lat = fits.plan(SCHEMES[0], w, poses, args.shadow_res)

    def one_frame():
        mc = MapCache(w.triangles)
        for k in range(lat.maps):
            mc.window(lat.basis[0], lat.x0[0, k], lat.y0[0, k], lat.tx[0, k], lat.ty[0, k], int(lat.n[0, k]))

    base, _ = timed(one_frame, args.repeats)
    print(f"scene {w.name}: {len(w.triangles)} triangles, {pts.count} points, {args.frames} frames, {lat.maps} cascades of {args.shadow_res}², motion {MOTION}")
    print(f"baseline: one frame's {lat.maps} depth maps {base * 1e3:.0f} ms")
    for spec in SCHEMES:
        t, r = timed(lambda: measure.shimmer(w, pts, spec, MOTION, args.frames, res=args.shadow_res), args.repeats)
        print(f"{spec}: {t:.1f} s = {t / base:.0f} x baseline ({t / args.frames * 1e3:.0f} ms per frame); maps drawn {r.drawn}, reused {r.reused}; "
              f"flip fraction {r.flip_fraction.mean():.5f}, predicted/measured {r.ratio:.3f} ± {r.ratio_se:.3f}")


if __name__ == "__main__":
    main()
