"""Engine bias rules per cascade: the ground's margin, the receiver angle from which each rule acnes, and the lit gap.

Not a paper figure.  Each engine's default bias rule for a directional light, read from its
source (``aliasing bias --list``: Filament, Bevy, Godot 4's normal bias, Unity URP with hard
and soft shadows, three.js), converted to one depth bias along the light
(:func:`aliasing.bias.presets.equivalent_depth`) and set against the derived minimum
(:func:`aliasing.bias.map_bias`, :func:`aliasing.bias.plane_bias`) per cascade by
:func:`aliasing.bias.cascades.cascade_bias`.

Setting (ours): near 0.1, shadow distance 100, fov 60°, 4 practical cascades (λ = 0.5) of
2048² texels with uniform maps, a 1080-pixel view, the light ahead of the viewer at 45° and at
20° above the ground.  Panels: the ground's margin (the preset's bias over its minimum; below 1
the ground acnes) at 20°; the smallest receiver angle from the light at which the rule falls
short for some azimuth, at 45° (none drawn at 90°: no acne below 89°); the lit gap at the foot
of a vertical caster, in pixels, at 45°.

What it shows (numbers in the CSV): Bevy's normal offset, constant in texels, falls short on
surfaces steeper than 40°–62° from the light under its 5×5 filter and, with the sun 20° up, on
the ground itself in the two far cascades (margins 0.93 and 0.87); Filament's and Unity's
slope-scaled rasterizer bias covers their 2×2 filters everywhere, and Unity pays 0.5–0.7
pixels of lit gap (hard shadows) and 1.2–1.9 (soft) at every contact; three.js' default
zero bias acnes at every tilt; Godot's normal bias, applied across the light, vanishes as
θ² for surfaces nearly facing the light (its constant term, not modelled, must cover them).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from aliasing.bias.cascades import cascade_bias
from aliasing.bias.presets import PRESETS
from aliasing.plotting import save, subplots

NAME = "bias-presets"
NEAR, FAR, FOV, K, LAM, RES, IMAGE = 0.1, 100.0, 60.0, 4, 0.5, 2048, 1080
ELEVATIONS = (45.0, 20.0)


def data() -> list[dict]:
    """All rows of :func:`cascade_bias` for every preset at both elevations (an ``elevation`` column added)."""
    rows = []
    for el in ELEVATIONS:
        for name in PRESETS:
            for r in cascade_bias(NEAR, FAR, FOV, f"gamma:{el:g}", name, k=K, resolution=RES, image=IMAGE, lam=LAM):
                rows.append({"elevation": el, **r})
    return rows


def main(out_dir: Path) -> list[Path]:
    rows = data()
    names = list(PRESETS)
    fig, (a, b, c) = subplots(3, width=4.4, height=3.8)
    x = np.arange(K)
    width = 0.8 / len(names)
    pick = lambda el, name, key: np.array([r[key] for r in rows if r["elevation"] == el and r["preset"] == name], float)  # noqa: E731
    for i, name in enumerate(names):
        pos = x + (i - (len(names) - 1) / 2) * width
        margin = pick(20.0, name, "margin")
        a.bar(pos, margin, width, color=f"C{i}", label=name)
        frm = pick(45.0, name, "acne_from")
        b.bar(pos, np.where(np.isfinite(frm), frm, 90.0), width, color=f"C{i}")
        for p_, m_, f_ in zip(pos, margin, frm):
            if m_ < 0.05:  # a zero margin is no bar: say so
                a.annotate("0", (p_, 0.0), xytext=(0, 2), textcoords="offset points", ha="center", fontsize=7, color=f"C{i}")
            if f_ < 5:
                b.annotate(f"{f_:g}", (p_, f_), xytext=(0, 2), textcoords="offset points", ha="center", fontsize=7, color=f"C{i}")
        c.bar(pos, pick(45.0, name, "gap_px"), width, color=f"C{i}")
    a.axhline(1.0, color="k", lw=0.9)
    a.set(xticks=x, xlabel="cascade", ylabel="ground margin (bias / minimum)", ylim=(0, 5.2), title="sun 20° up: below 1 the ground acnes")
    a.legend(fontsize=7, loc="upper center", ncols=3)
    b.set(xticks=x, xlabel="cascade", ylabel="receiver angle from the light [deg]", ylim=(0, 92),
          title="sun 45° up: acne from this angle on\n(90: none below 89°)")
    c.set(xticks=x, xlabel="cascade", ylabel="lit gap at a contact [pixels]", title="sun 45° up: peter-panning")
    fig.suptitle(f"Engine bias rules per cascade: near {NEAR:g}, far {FAR:g}, fov {FOV:g}°, {K} practical cascades (λ {LAM:g}) "
                 f"of {RES}² texels, {IMAGE} px", fontsize=9)
    paths = save(fig, out_dir, NAME)
    path = Path(out_dir) / f"{NAME}.csv"
    with path.open("w", newline="") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(list(rows[0]))
        for r in rows:
            writer.writerow([f"{v:.10g}" if isinstance(v, float) else v for v in r.values()])
    return paths + [path]


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
