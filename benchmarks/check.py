"""``aliasing.check.check``: the per-cascade report of an engine's setup, timed against two baselines in the same run.

The three.js developer's case: three.js r187's CSM addon, 4 cascades of 2048², a 16:9 camera (near
0.1, far 500, fov 50°, 1080 rows), the sun 15..60° (7 elevations). Baselines: the engine's own fit
alone (:func:`aliasing.engines.pipeline.result`, what check builds on) and the older bias rows of one
sun (:func:`aliasing.bias.cascades.cascade_bias` with the ``threejs`` preset). Best of ``--repeats``.

Run: ``python benchmarks/check.py [--repeats 20]``.
"""

from __future__ import annotations

import argparse
import platform

import numpy as np
from _timing import best_of

from aliasing import setups
from aliasing.bias.cascades import cascade_bias
from aliasing.check import check
from aliasing.engines import pipeline

CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20)
    args = parser.parse_args()
    s = setups.build("threejs", {"cascades": 4, "shadowMapSize": 2048}, CAMERA, "15..60")
    lv = s.sun.direction(s.sun.elevations(7))
    t_check = best_of(lambda: check(s), args.repeats)
    t_build = best_of(lambda: setups.build("threejs", {"cascades": 4, "shadowMapSize": 2048}, CAMERA, "15..60"), args.repeats)
    t_fit = best_of(lambda: pipeline.result(s.pipeline, s.camera, lv), args.repeats)
    t_old = best_of(lambda: cascade_bias(0.1, 500.0, 50.0, "gamma:15", "threejs", k=4, aspect=16 / 9), args.repeats)
    print(f"python {platform.python_version()}, numpy {np.__version__}, best of {args.repeats}")
    print(f"check (4 cascades, 7 suns)          {t_check * 1e3:8.2f} ms")
    print(f"setups.build (the Setup value)      {t_build * 1e3:8.2f} ms")
    print(f"baseline: engine fit alone          {t_fit * 1e3:8.2f} ms   check / fit  = {t_check / t_fit:6.1f}")
    print(f"baseline: cascade_bias, one sun     {t_old * 1e3:8.2f} ms   check / bias = {t_check / t_old:6.2f}")


if __name__ == "__main__":
    main()
