"""Should I stabilize?  The resolution each engine's stable cascades cost beside the shimmer they remove.

Not a paper figure.  For every stable preset of :data:`aliasing.engines.stable.PRESETS`
(Godot 4, the DirectX SDK's fit to scene, Filament with and without ``shadowFar``, Babylon.js,
Bevy; fits, snaps and splits read from their source, see each preset's ``source``) and its
unstabilized counterpart (the same split and cascade count, tight fit, no snap):

* cost (left axis of the right panel): S̄ of the stable fit over S̄ of the tight fit, the
  mean over 200 light directions of the upper hemisphere
  (:func:`aliasing.engines.stable.cost`, ``S_ratio_mean_over_dirs``): how many times more
  texels the stable maps need for the same perspective aliasing error;
* shimmer (:func:`aliasing.temporal.measure.shimmer`): the fraction of fixed surface points
  whose lit/shadowed state flips per frame, on the built-in ``boxes`` scene (ground and
  100 boxes over eye depths 1–100, fov 60°, light towards (−1, 2, 0.6), one point per pixel
  of a 96² first frame, 256² texels per cascade) under three camera paths of 24 frames:
  sideways (0.05 units per frame), forward (0.1 units per frame) and a yaw turn (0.25° per
  frame), shown as flips per second at 60 frames per second; and, in the CSV only, a turning
  sun (0.25° per frame about the vertical) as flips per degree, for the tight and the stable fit.

Besides the presets as shipped, ``dxsdk-scene+snap``: the DirectX SDK sample floors the
map's corners to texels (``m_bMoveLightTexelSize``), which its preset, a model of the fit's
size, leaves out (flooring does not change the size); with the flooring
(``csm-stable:dxsdk-scene:snap=origin``) its shimmer goes too.

Flips of points that cross a cascade boundary are counted too: a stable grid cannot remove
them (a point that changes cascade changes texel size), so "removed" is below 100 % where a
path carries points across boundaries (forward), and a preset whose split moves its
boundaries more does worse.  The numbers are in the CSV.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.engines import compare, stable
from aliasing.plotting import save, subplots, write_table
from aliasing.temporal import measure, points

NAME = "shimmer-tradeoff"
MOTIONS = (("sideways", "translate:0.05,0,0"), ("forward", "translate:0,0,0.1"), ("yaw", "rotate:yaw,0.25"))
FRAMES = 24
IMAGE_RES = 96
SHADOW_RES = 256
FPS = 60.0
LIGHTS = "hemisphere:200"
SUN = "sun:0.25"  # the light turning about the vertical: shimmer no grid can remove, as a rate per degree


#: The presets as shipped, and the DirectX SDK's with its texel flooring (the preset models the
#: fit's size only, which the flooring does not change; for shimmer the flooring is the point).
ENTRIES = tuple((name, f"csm-stable:{name}") for name in stable.PRESETS) + (("dxsdk-scene+snap", "csm-stable:dxsdk-scene:snap=origin"),)


def _tight(spec: str) -> str:
    preset = stable.PRESETS[spec.split(":")[1]]
    return f"csm:{preset.split}:k={preset.k}"


def data() -> dict[str, list]:
    """One row per preset: its cost and, per motion, the flip fraction of the tight and the stable fit."""
    w = points.world("boxes")
    pts = points.sample(w, IMAGE_RES)
    cam = w.camera
    cols: dict[str, list] = {"preset": [], "tight": [], "S_ratio": []}
    for label, _ in MOTIONS:
        for kind in ("tight", "stable"):
            cols[f"{label}_{kind}"] = []
        cols[f"{label}_removed"] = []
    cols["sun_per_degree_tight"], cols["sun_per_degree_stable"] = [], []
    memo: dict[tuple[str, str], float] = {}

    def flips(scheme: str, motion: str) -> float:  # presets sharing a split share their tight runs
        if (scheme, motion) not in memo:
            memo[scheme, motion] = float(measure.shimmer(w, pts, scheme, motion, FRAMES, res=SHADOW_RES, prediction=False).flip_fraction.mean())
        return memo[scheme, motion]

    for name, spec in ENTRIES:
        ps = compare.parse_spec(spec, fov=cam.fov, near=cam.near, far=cam.far, image_res=IMAGE_RES, shadow_res=SHADOW_RES, unit="m")
        cols["preset"].append(name)
        cols["tight"].append(_tight(spec))
        cols["S_ratio"].append(stable.cost(ps.split, cam.near, cam.far, cam.fov, LIGHTS, **ps.fit)["S_ratio_mean_over_dirs"])
        for label, motion in MOTIONS:
            t, s = flips(_tight(spec), motion), flips(spec, motion)
            cols[f"{label}_tight"].append(float(t))
            cols[f"{label}_stable"].append(float(s))
            cols[f"{label}_removed"].append(float(1 - s / t) if t > 0 else float("nan"))
        step = abs(float(SUN.split(":")[1]))
        for kind, scheme in (("tight", _tight(spec)), ("stable", spec)):
            cols[f"sun_per_degree_{kind}"].append(flips(scheme, SUN) / step)
    return cols




def main(out_dir: Path) -> list[Path]:
    cols = data()
    n = len(cols["preset"])
    x = np.arange(n)
    fig, (ax, bx) = subplots(2, width=6.0, height=4.8, gridspec_kw={"width_ratios": [1.6, 1.0]})
    width = 0.13
    for i, (label, _) in enumerate(MOTIONS):
        for j, kind in enumerate(("tight", "stable")):
            pos = x + (2 * i + j - 2.5) * width
            vals = np.asarray(cols[f"{label}_{kind}"]) * FPS
            ax.bar(pos, vals, width, color=f"C{i}", alpha=0.35 if kind == "tight" else 0.95, hatch="//" if kind == "tight" else None, edgecolor=f"C{i}",
                   label=f"{label}, {'tight (unstabilized)' if kind == 'tight' else 'stable preset'}")
    ax.set_xticks(x, [name.replace("+", "\n+").replace("-shadowfar", "\n-shadowfar") for name in cols["preset"]], fontsize=8, rotation=25, ha="right", rotation_mode="anchor")
    ax.set(ylabel=f"flips per second at {FPS:g} fps\n(share of surface points, mean over frames)")
    ax.grid(False, axis="x")
    ax.legend(fontsize=7, ncols=3, loc="upper center", bbox_to_anchor=(0.5, -0.3))
    ax.set_title("Shimmer: stable presets beside the same split fitted tight", fontsize=9)
    for i, (label, _) in enumerate(MOTIONS):
        for j, kind in enumerate(("tight", "stable")):
            vals = np.asarray(cols[f"{label}_{kind}"]) * FPS
            for p in (x + (2 * i + j - 2.5) * width)[vals == 0]:
                ax.annotate("0", (p, 0), xytext=(0, 1), textcoords="offset points", ha="center", va="bottom", fontsize=6, color=f"C{i}")
    cost = np.asarray(cols["S_ratio"])
    y = np.arange(n)[::-1]
    bx.barh(y, cost, color="0.6")
    for yy, c, row in zip(y, cost, range(n)):
        removed = ", ".join(f"{100 * cols[f'{m}_removed'][row]:.0f} %" for m, _ in MOTIONS)
        bx.annotate(f"×{c:.3g}   removes {removed}", (c, yy), xytext=(4, 0), textcoords="offset points", va="center", fontsize=7)
    bx.set_yticks(y, cols["preset"], fontsize=8)
    bx.set(xscale="log", xlim=(0.8, cost.max() * 40), xlabel="resolution cost: S̄ stable / S̄ tight\n(mean over 200 light directions; log scale)")
    bx.grid(False, axis="y")
    bx.set_title("What stabilizing costs (bars) and buys\n(shimmer removed: " + ", ".join(m for m, _ in MOTIONS) + ")", fontsize=9)
    fig.suptitle(f"Boxes scene, {FRAMES} frames per path, one point per pixel of a {IMAGE_RES}² first frame, {SHADOW_RES}² texels per cascade", fontsize=9)
    paths = save(fig, out_dir, NAME)
    return paths + [write_table(cols, Path(out_dir) / f"{NAME}.csv", digits=6)]


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
