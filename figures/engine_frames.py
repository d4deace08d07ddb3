"""The engines' own frames beside the toolkit's prediction: three.js, Babylon.js and PlayCanvas at their defaults, three.js with front faces casting.

Not a paper figure.  Each engine (pinned npm release) renders the built-in boxes scene in
headless Chromium with WebGL 2 on SwiftShader (:mod:`aliasing.frames`); per row: the
engine's frame, the toolkit's predicted shadow factor for the same pixels, the acne map (lit
receivers the engine shades as shadowed: red where the toolkit predicts it too, yellow where
only the engine, blue where only the toolkit) and the error map (pixels per texel of the
cascade each pixel samples, from the engine's light matrices, on a log scale; above 1 a texel
covers more than a pixel: the shadow is blocky there).

Setting (ours): near 0.5, far 60, vertical fov 50°, 16:9, 512 × 288 px, sun 35° above the
ground and 30° from the view direction; 30 boxes.  Needs Chromium, npm and Playwright
(``pip install ".[frames]"``, ``aliasing frames --install``).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from aliasing import setups
from aliasing.frames import browser, scenes
from aliasing.frames.run import frame_setup
from aliasing.plotting import save, subplots
from aliasing.view import tan_theta

NAME = "engine-frames"
CASES = (("threejs", {}, "three.js r187, defaults"), ("threejs", {"material.shadowSide": "FrontSide"}, "three.js r187, front faces cast"),
         ("babylon", {}, "Babylon.js 9.35, defaults"), ("playcanvas", {}, "PlayCanvas 2.23.3, defaults"))
CAMERA, SUN = "near=0.5,far=60,fov=50,aspect=16:9,height=288", "35@30"


def _ppt(result, scene) -> np.ndarray:
    rb = result.readback
    depth = scene.camera.to_eye(np.nan_to_num(rb.position))[..., 2]
    sides = np.array([max(1 / np.linalg.norm(m[0, :3]), 1 / np.linalg.norm(m[1, :3])) for m in rb.matrices])
    tex = sides / rb.sizes[:, 0]
    pixel = 2 * depth * tan_theta(scene.camera.fov) / rb.shadow.shape[0]
    c = rb.cascade
    return np.where(rb.drawn & (c >= 0), tex[np.clip(c, 0, None)] / pixel, np.nan)


def main(out_dir: Path) -> list[Path]:
    fs = scenes.frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=30, ground_cells=8)
    sun = scenes.sun_direction(35.0, 30.0, fs.camera)
    with browser.Browser(timeout=120) as b:
        results = [(title, frame_setup(b, setups.build(engine, settings, CAMERA, SUN), fs)) for engine, settings, title in CASES]
    import io

    import matplotlib
    import matplotlib.image
    from matplotlib.colors import LogNorm

    fig, axes = subplots(4, nrows=len(results), width=3.2, height=2.0)
    axes = np.asarray(axes).reshape(len(results), 4)
    rows = []
    for (title, r), ax in zip(results, axes):
        rb = r.readback
        ax[0].imshow(matplotlib.image.imread(io.BytesIO(rb.frame)))
        ax[0].set_title(title, fontsize=8)
        gray = matplotlib.colormaps["gray"].with_extremes(bad="black")  # no surface drawn: black, as the engines' clear colour in three.js
        ax[1].imshow(np.where(rb.drawn, r.prediction.factor, np.nan), cmap=gray, vmin=0, vmax=1)
        ax[1].set_title("toolkit: predicted shadow factor", fontsize=8)
        rec = r.reference & ((np.nan_to_num(rb.normal) @ sun) > 0.05)
        m, p = rec & (np.nan_to_num(rb.shadow, nan=1) < 0.5), rec & (np.nan_to_num(r.prediction.factor, nan=1) < 0.5)
        acne = np.zeros(rb.shadow.shape + (3,))
        acne[rb.drawn] = 0.85
        acne[m & p], acne[m & ~p], acne[~m & p] = (0.85, 0.1, 0.1), (0.95, 0.8, 0.1), (0.1, 0.3, 0.95)
        rep = r.report
        ax[2].imshow(acne)
        ax[2].set_title(f"acne: engine {100 * rep['measured']['acne']:.2f} %, toolkit {100 * rep['predicted']['acne']:.2f} %", fontsize=8)
        im = ax[3].imshow(_ppt(r, fs), cmap="viridis", norm=LogNorm(0.1, 10.0))  # 1: a texel per pixel; above, blocky
        ax[3].set_title("pixels per texel (engine's matrices)", fontsize=8)
        fig.colorbar(im, ax=ax[3], shrink=0.8, extend="both")
        for a in ax:
            a.set_xticks([]), a.set_yticks([])
        rows.append({"case": title, **{f"measured_{k}": v for k, v in rep["measured"].items()}, **{f"predicted_{k}": v for k, v in rep["predicted"].items()}})
    fig.suptitle("The engines' own frames (headless Chromium, SwiftShader) against the toolkit's prediction: boxes, sun 35° up, 30° off the view", fontsize=9)
    paths = save(fig, out_dir, NAME)
    path = Path(out_dir) / f"{NAME}.json"
    path.write_text(json.dumps(rows, indent=1) + "\n")
    return [*paths, path]


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
