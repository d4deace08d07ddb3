"""``aliasing tune``'s wrong-pixel pick against the engine's defaults and a brute-force grid, all rendered in the engine.

Per browser engine (three.js, Babylon.js, PlayCanvas, Godot's web runtime at their pinned releases): a 16:9 camera (near 0.5,
far 60, fov 50°), the sun band 20..60°.  tune searches on the reference scene
(:func:`aliasing.frames.seen.reference_scene`); the frames are rendered on a scene NOT used in tuning: the
built-in boxes scene with another seed and count (:data:`SEED`, :data:`BOXES`).  Rendered, each at
``--height`` rows under ``--suns`` suns over the band: tune's pick, the engine's defaults, and a grid over
the engine's cascade count, its split parameter (three.js ``mode``, Babylon.js ``lambda``, PlayCanvas
``cascadeDistribution``, Godot ``directional_shadow_split_1``) and its main bias term (the closed-form minimum times 0.5, 1 and 2).  For each:
the wrong pixels measured in the engine's frame and predicted by the toolkit (fractions of the sun-facing
pixels), the worst px/texel over the receivers, whether tune's pick differs from the grid's best beyond the
counts' noise (:func:`aliasing.tune.pixels.significant`).

Then the times a user waits, each as one ``aliasing tune`` command (a fresh process, import included) from
4 cascades of 2048² (:data:`TIMED`; Godot: 4 splits of its 4096² atlas): without ``--frames`` and with ``--frames 8``, the load average beside.

Run: ``python benchmarks/tune_frames.py [--engines threejs,babylon,playcanvas,godot] [--height 240] [--suns 3] [--more]``
(needs ``aliasing frames --install``; about 4 minutes per engine).
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import subprocess
import sys
import time

from aliasing import setups
from aliasing.frames import seen
from aliasing.frames.scenes import frame_scene
from aliasing.tune import closed_form_bias, pixels, proof, search
from aliasing.tune.measure import measure

CAMERA = "near=0.5,far=60,fov=50,aspect=16:9,height=720"
SUN = "20..60"
SEED, BOXES = 23, 30
#: More arrangements of the test scene (other seeds, none the reference scene's), predicted only.
MORE_SEEDS = (1, 2, 3, 4, 5, 6, 11, 12)
#: Per engine: the start (the engine's defaults, with enough cascades to tune), the grid's count lever and values,
#: its split lever and values, and the main bias term.
CASES = {
    "threejs": ({"cascades": 3}, "cascades", (2, 4), "mode", ("practical", "uniform", "logarithmic"), "shadow.normalBias"),
    "babylon": ({"numCascades": 4}, "numCascades", (2, 4), "lambda", (0.3, 0.5, 0.7), "bias"),
    "playcanvas": ({"numCascades": 1, "shadowDistance": 40.0}, "numCascades", (1, 4), "cascadeDistribution", (0.3, 0.5, 0.7), "shadowBias"),
    # Godot's web runtime renders the Compatibility renderer; its main bias there is the normal bias (ERRATA F13)
    "godot": ({"rendering/renderer/rendering_method": "gl_compatibility"}, "directional_shadow_mode",
              ("SHADOW_PARALLEL_2_SPLITS", "SHADOW_PARALLEL_4_SPLITS"), "directional_shadow_split_1", (0.05, 0.1, 0.15), "shadow_normal_bias"),
}
#: The timed commands' start: 4 cascades of 2048².
TIMED = {"threejs": ["cascades=4", "shadowMapSize=2048"], "babylon": ["numCascades=4", "mapSize=2048"],
         "playcanvas": ["numCascades=4", "shadowResolution=2048"],
         "godot": ["rendering/renderer/rendering_method=gl_compatibility", "directional_shadow_mode=SHADOW_PARALLEL_4_SPLITS"]}


def run(engine: str, height: int, suns: int, seeds=()) -> dict:
    given, count_key, counts, split_key, splits, bias_key = CASES[engine]
    start = setups.build(engine, given, CAMERA, SUN)
    t0 = time.perf_counter()
    tuned = search.tune(start)
    got = pixels.refine(start, tuned.setup, tuned.limits, keep=frozenset(tuned.keep))
    t_tune = time.perf_counter() - t0
    cam = start.camera
    fs = frame_scene("boxes", near=cam.near, far=cam.far, fov=cam.fov, aspect=round(cam.aspect * height) / height, boxes=BOXES, seed=SEED)
    grid = []
    for c, sp in itertools.product(counts, splits):
        s = start.with_settings(**{count_key: c, split_key: sp})
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
            "evaluations": got.evaluations, "more": more_scenes(start, rows, height, suns, seeds)}


def more_scenes(start, rows: list, height: int, suns: int, seeds) -> list:
    """The same rows predicted (not rendered: the prediction is within 0.02 points of the engines' frames) on more
    arrangements of the test scene, seeds ``seeds``: per seed the wrong pixels of each row."""
    cam = start.camera
    out = []
    for seed in seeds:
        fs = frame_scene("boxes", near=cam.near, far=cam.far, fov=cam.fov, aspect=round(cam.aspect * height) / height, boxes=BOXES, seed=seed)
        where = seen.sample(start, fs, height=height, suns=suns)
        counts = []
        for _, settings in rows:
            t = seen.count(setups.Setup(start.profile, settings, start.camera, start.sun), where).total
            counts.append(round(t["wrong"] * t["pixels"]))
        out.append({"seed": seed, "pixels": int(t["pixels"]), "wrong_px": counts})
    return out


def _command(engine: str, command: str, *extra: str) -> float:
    """Wall time [s] of one ``aliasing COMMAND`` process from 4 cascades of 2048² (:data:`TIMED`; Godot: 4 splits of its 4096² atlas)."""
    argv = [sys.executable, "-m", "aliasing.cli", command, "--engine", engine, "--camera", CAMERA, "--sun", SUN, "--format", "json", *extra]
    for kv in TIMED[engine]:
        argv += ["--set", kv]
    t = time.perf_counter()
    done = subprocess.run(argv, capture_output=True, text=True, check=False)
    wall = time.perf_counter() - t
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(argv[2:])} failed: {done.stderr.strip()[-300:]}")
    return wall


def timed(engine: str, frames: int | None) -> dict:
    """One ``aliasing tune`` command as a user runs it, from 4 cascades of 2048²: its wall time [s], the load average, and
    beside it the baseline: one ``aliasing check --seen`` of the same setup (a process, its import, one wrong-pixel measure)."""
    load = os.getloadavg()[0]
    base = _command(engine, "check", "--seen")
    wall = _command(engine, "tune", *(["--frames", str(frames)] if frames else []))
    return {"frames": frames, "seconds": round(wall, 1), "check_seen_s": round(base, 1), "ratio": round(wall / base, 1),
            "load_before": round(load, 2), "load_after": round(os.getloadavg()[0], 2)}


def pct(v) -> str:
    return "n/a" if v is None else f"{100 * v:.2f} %"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--engines", default="threejs,babylon,playcanvas,godot")
    ap.add_argument("--height", type=int, default=240, help="rows of each rendered frame [px]")
    ap.add_argument("--suns", type=int, default=3, help="suns over the band per frame")
    ap.add_argument("--no-timing", action="store_true", help="skip the timed aliasing tune commands")
    ap.add_argument("--timing-only", action="store_true", help="only the timed aliasing tune commands (no grid)")
    ap.add_argument("--more", action="store_true", help="also predict the rows on more arrangements of the test scene (MORE_SEEDS)")
    ap.add_argument("--json", help="write the results here too")
    args = ap.parse_args()
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; camera {CAMERA}, sun {SUN}; frames at {args.height} rows, "
          f"{args.suns} suns; test scene: boxes seed {SEED}, {BOXES} boxes (tuned on the reference scene)")
    results = []
    for engine in args.engines.split(","):
        if args.timing_only:
            t = [timed(engine, None), timed(engine, 8)]
            results.append({"engine": engine, "timed": t})
            print(f"{engine}: " + "; ".join(f"aliasing tune {'--frames 8 ' if x['frames'] else ''}from 4 x 2048²: {x['seconds']} s = "
                                            f"{x['ratio']} x check --seen ({x['check_seen_s']} s; load {x['load_before']} -> {x['load_after']})"
                                            for x in t))
            continue
        r = run(engine, args.height, args.suns, MORE_SEEDS if args.more else ())
        results.append(r)
        print(f"\n{engine}: tune {r['tune_s']} s ({r['evaluations']} candidates), {r['frames']} frames {r['frames_s']} s")
        print(f"  {'':9} {'measured':>9} {'predicted':>9} {'acne':>8} {'lost':>8} {'px/texel':>9}  changed")
        for row in r["rows"]:
            m, p = row["measured"], row["predicted"]
            print(f"  {row['name']:9} {pct(m['wrong']):>9} {pct(p['wrong']):>9} {pct(m['acne']):>8} {pct(m['lost_shadow']):>8} "
                  f"{row['px_per_texel']:9.3g}  {row['changed']}")
        best = min((x for x in r["rows"] if x["name"].startswith("grid")), key=lambda x: x["measured"]["wrong"])
        grid_best, n = best["measured"]["wrong"], r["rows"][0]["measured"]["pixels"]
        pick, dflt = r["rows"][0]["measured"]["wrong"], r["rows"][1]["measured"]["wrong"]
        gap = max(abs(x["measured"]["wrong"] - x["predicted"]["wrong"]) for x in r["rows"])
        noise = ("grid best significantly fewer" if pixels.significant(grid_best, pick, n) else
                 "tune significantly fewer" if pixels.significant(pick, grid_best, n) else "within the noise")
        r["verdict"] = {"ratio": pick / grid_best if grid_best else None, "noise": noise, "pixels": n, "grid_best": best["name"]}
        print(f"  tune / grid best ({best['name']}) = {pick / grid_best if grid_best else float('inf'):.2f} (target <= 1.1; {noise}, "
              f"{n} pixels); tune < defaults: {pick < dflt}; largest |measured - predicted| = {100 * gap:.2f} points (target <= 1)")
        if r["more"]:
            names = [x["name"] for x in r["rows"]]
            grid_idx = [i for i, x in enumerate(names) if x.startswith("grid")]
            for m in r["more"]:
                w = m["wrong_px"]
                b = min(w[i] for i in grid_idx)
                print(f"  seed {m['seed']:2d} (predicted): tune {w[0]} px, defaults {w[1]}, grid best {b}: tune / grid best {w[0] / max(b, 1):.2f}")
            tot = [sum(m["wrong_px"][i] for m in r["more"]) for i in range(len(names))]
            bi = min(grid_idx, key=lambda i: tot[i])
            r["more_verdict"] = {"tune": tot[0], "defaults": tot[1], "grid_best": tot[bi], "grid_best_row": names[bi], "ratio": tot[0] / max(tot[bi], 1)}
            print(f"  over the {len(r['more'])} seeds (predicted): tune {tot[0]} px, defaults {tot[1]}, the grid point best over all "
                  f"({names[bi]}) {tot[bi]}: tune / grid best {tot[0] / max(tot[bi], 1):.2f}")
        if not args.no_timing:
            r["timed"] = [timed(engine, None), timed(engine, 8)]
            print("  " + "; ".join(f"aliasing tune {'--frames 8 ' if t['frames'] else ''}from 4 x 2048²: {t['seconds']} s "
                                  f"= {t['ratio']} x check --seen ({t['check_seen_s']} s; load {t['load_before']} -> {t['load_after']})"
                                  for t in r["timed"]))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1, default=str)


if __name__ == "__main__":
    main()
