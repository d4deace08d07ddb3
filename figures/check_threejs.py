"""What ``aliasing check`` tells a three.js developer: per cascade, the texel size, the bias it needs, the gap it costs.

Not a paper figure.  The three.js CSM addon (r187) with 4 cascades of 2048² texels, a 16:9 camera
(near 0.1 m, far 500 m, vertical fov 50°, 1920×1080), the sun 15–60° above the ground
(:func:`aliasing.check.check` of :func:`aliasing.setups.build`).

* left: the perspective error along the view, px/texel (a texel's width over a pixel's at
  eye depth z, the texel from three.js's own fit: the diagonal-sized, texel-snapped box), one
  sawtooth tooth per cascade;
* middle: the ``shadow.normalBias`` each cascade needs so that the ground does not acne where front
  faces cast (``material.shadowSide = FrontSide``; three.js's default casts back faces, and closed
  receivers then do not acne), over the sun's elevation; one value serves every cascade, so the
  last cascade's sets it;
* right: the peter-panning (lit gap at the foot of a wall, pixels at each cascade's middle depth)
  that fixing the acne with ``shadowBias`` instead costs at the lowest sun: the CSM addon gives every
  cascade the same ``shadowBias``, so the last cascade's need opens the widest gaps in the nearest.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import setups
from aliasing.check import check
from aliasing.plotting import save, subplots
from aliasing.view import tan_theta

NAME = "check-threejs"
CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
SETTINGS = {"cascades": 4, "shadowMapSize": 2048, "material.shadowSide": "FrontSide"}
SUNS = np.arange(15.0, 61.0, 5.0)


def data() -> dict[str, np.ndarray]:
    """Per cascade: near, far, texel, the normalBias needed at each sun, and the gap at the common shadowBias."""
    s = setups.build("threejs", SETTINGS, CAMERA, "15..60")
    r = check(s)
    cols: dict[str, np.ndarray] = {
        "cascade": np.arange(4.0),
        "near": np.array([c["near"] for c in r.cascades]),
        "far": np.array([c["far"] for c in r.cascades]),
        "texel": np.array([max(c["texel"]) for c in r.cascades]),
        "error_max": np.array([c["error_max"] for c in r.cascades]),
    }
    for e in SUNS:
        one = check(setups.build("threejs", SETTINGS, CAMERA, float(e)))
        cols[f"normalBias_{e:g}"] = np.array([c["needed"]["shadow.normalBias"] for c in one.cascades])
    bias = min(c["needed"]["shadowBias"] for c in r.cascades)  # the last cascade's: an upper bound, the most negative
    fixed = check(s.with_settings(shadowBias=bias))
    cols["shadowBias"] = np.full(4, bias)
    cols["gap_px"] = np.array([c["gap_px"] for c in fixed.cascades])
    cols["acne_after"] = np.array([c["acne"] for c in fixed.cascades])
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, axes = subplots(3, width=4.3, height=3.8)
    ax = axes[0]
    h, t = 1080, tan_theta(50.0)
    for k in range(4):
        z = np.geomspace(max(cols["near"][k], 0.5), cols["far"][k], 60)
        ax.plot(z, cols["texel"][k] * h / (2 * t * z), color=f"C{k}", lw=2, label=f"cascade {k}: {cols['texel'][k] * 100:.1f} cm texel")
    ax.axhline(1.0, color="k", lw=0.8, ls=":")
    ax.set(xscale="log", yscale="log", xlabel="eye depth z [m]", ylabel="pixels per texel (error)", title="Error along the view")
    ax.legend(fontsize=7.5)
    ax = axes[1]
    for k in range(4):
        ax.plot(SUNS, [cols[f"normalBias_{e:g}"][k] for e in SUNS], color=f"C{k}", marker="o", ms=3, label=f"cascade {k}")
    ax.set(xlabel="sun elevation [deg]", ylabel="shadow.normalBias needed [m]", title="normalBias that removes ground acne")
    ax.legend(fontsize=7.5)
    ax = axes[2]
    ax.bar(np.arange(4), cols["gap_px"], color=[f"C{k}" for k in range(4)])
    for k, g in enumerate(cols["gap_px"]):
        ax.text(k, g, f"{g:.1f}", ha="center", va="bottom", fontsize=8)
    ax.set(xticks=range(4), xlabel="cascade", ylabel="lit gap at a wall's foot [px]",
           title=f"Gap with shadowBias = {cols['shadowBias'][0]:.2g} (sun 15°)")
    fig.suptitle("three.js r187 CSM, 4 × 2048², 1920×1080, fov 50°, near 0.1 m, far 500 m", fontsize=10)
    return save(fig, out_dir, NAME, columns=cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
