"""``aliasing tune``'s wrong-pixel pick against the engine's defaults and a small brute-force grid, all rendered in the engine.

Per browser engine (three.js, Babylon.js, PlayCanvas at their pinned releases): a 16:9 camera (near 0.5,
far 60, fov 50°), the sun band 20..60°.  tune searches on the reference scene
(:func:`aliasing.frames.seen.reference_scene`); the frames are rendered on a scene NOT used in tuning: the
built-in boxes scene with another seed and count (:data:`SEED`, :data:`BOXES`).  Rendered, each at
``--height`` rows under ``--suns`` suns over the band: tune's pick, the engine's defaults, and a small grid
over the engine's cascade count (or map size) and its main bias term (the closed-form minimum times 0.5,
1 and 2).  For each: the wrong pixels measured in the engine's frame and predicted by the toolkit (fractions
of the sun-facing pixels), the worst px/texel over the receivers, and the time.

Run: ``python benchmarks/tune_frames.py [--engines threejs,babylon,playcanvas] [--height 144] [--suns 2]``
(needs ``aliasing frames --install``).  The grid is kept small on purpose: the machine is shared.
"""

from __future__ import annotations

import argparse
import json
import os
import time

from aliasing import setups
from aliasing.frames.scenes import frame_scene
from aliasing.tune import closed_form_bias, pixels, proof, search
from aliasing.tune.measure import measure

CAMERA = "near=0.5,far=60,fov=50,aspect=16:9,height=720"
SUN = "20..60"
SEED, BOXES = 23, 30
#: Per engine: the start (the engine's defaults, with enough cascades to tune), the grid's count lever and bias term.
CASES = {
    "threejs": ({"cascades": 3}, "cascades", (2, 4), "shadow.normalBias"),
    "babylon": ({"numCascades": 4}, "numCascades", (2, 4), "bias"),
    "playcanvas": ({"numCascades": 1, "shadowDistance": 40.0}, "numCascades", (1, 4), "shadowBias"),
}


def run(engine: str, height: int, suns: int) -> dict:
    given, count_key, counts, bias_key = CASES[engine]
    start = setups.build(engine, given, CAMERA, SUN)
    t0 = time.perf_counter()
    tuned = search.tune(start)
    got = pixels.refine(start, tuned.setup, tuned.limits, keep=frozenset(tuned.keep))
    t_tune = time.perf_counter() - t0
    cam = start.camera
    fs = frame_scene("boxes", near=cam.near, far=cam.far, fov=cam.fov, aspect=round(cam.aspect * height) / height, boxes=BOXES, seed=SEED)
    grid = []
    for c in counts:
        s = start.with_settings(**{count_key: c})
        base = closed_form_bias(s, bias_key, receivers=tuned.limits.receivers) or float(s.settings[bias_key]) or 1e-3
        for f in (0.5, 1.0, 2.0):
            grid.append({**s.settings, bias_key: float(f"{base * f:.4g}")})
    rows = [("tune", dict(got.setup.settings)), ("defaults", dict(start.settings))] + [(f"grid {i}", g) for i, g in enumerate(grid)]
    t1 = time.perf_counter()
    frames = proof.render(start, [r[1] for r in rows], scene=fs, height=height, suns=suns)
    t_frames = time.perf_counter() - t1
    out = []
    for (name, settings), r in zip(rows, frames["rows"]):
        s = setups.Setup(start.profile, settings, start.camera, start.sun)
        tpp = measure(s, tuned.limits).objective
        changed = {k: v for k, v in settings.items() if start.settings.get(k) != v}
        out.append({"name": name, "changed": changed, "measured": r["measured"], "predicted": r["predicted"], "px_per_texel": tpp})
    return {"engine": engine, "tune_s": round(t_tune, 1), "frames_s": round(t_frames, 1), "frames": len(rows), "rows": out,
            "evaluations": got.evaluations}


def pct(v) -> str:
    return "n/a" if v is None else f"{100 * v:.2f} %"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engines", default="threejs,babylon,playcanvas")
    ap.add_argument("--height", type=int, default=144, help="rows of each rendered frame [px]")
    ap.add_argument("--suns", type=int, default=2, help="suns over the band per frame")
    ap.add_argument("--json", help="write the results here too")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; camera {CAMERA}, sun {SUN}; frames at {args.height} rows, "
          f"{args.suns} suns; test scene: boxes seed {SEED}, {BOXES} boxes (tuned on the reference scene)")
    results = []
    for engine in args.engines.split(","):
        r = run(engine, args.height, args.suns)
        results.append(r)
        print(f"\n{engine}: tune {r['tune_s']} s ({r['evaluations']} candidates), {r['frames']} frames {r['frames_s']} s")
        print(f"  {'':9} {'measured':>9} {'predicted':>9} {'acne':>8} {'lost':>8} {'px/texel':>9}  changed")
        for row in r["rows"]:
            m, p = row["measured"], row["predicted"]
            print(f"  {row['name']:9} {pct(m['wrong']):>9} {pct(p['wrong']):>9} {pct(m['acne']):>8} {pct(m['lost_shadow']):>8} "
                  f"{row['px_per_texel']:9.3g}  {row['changed']}")
        grid_best = min(x["measured"]["wrong"] for x in r["rows"] if x["name"].startswith("grid"))
        pick, dflt = r["rows"][0]["measured"]["wrong"], r["rows"][1]["measured"]["wrong"]
        gap = max(abs(x["measured"]["wrong"] - x["predicted"]["wrong"]) for x in r["rows"])
        print(f"  tune / grid best = {pick / grid_best if grid_best else float('inf'):.2f} (target <= 1.1); tune < defaults: {pick < dflt}; "
              f"largest |measured - predicted| = {100 * gap:.2f} points (target <= 1)")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1, default=str)


if __name__ == "__main__":
    main()
