"""What ``aliasing tune`` changes, per engine: the engine's defaults against the tuned settings.

Not a paper figure.  One figure per engine (each profile declares the settings tune may choose,
the ``tunable`` of :class:`aliasing.setups.Profile`), ``tune-<engine>.png``: a 16:9 camera (near 0.1 m, far
500 m, vertical fov 50°, 1920×1080), the sun 15–60° above the ground, 4 cascades at the engine's
default map size (the count and the size kept, so the memory is the same), front faces casting
(three.js: ``material.shadowSide = FrontSide``) so that the ground can acne, receivers up to a
10° slope kept free of acne (:func:`aliasing.tune.tune`, measured by :func:`aliasing.check.check`).

* left: the worst perspective error per cascade, px/texel at the cascade's near end
  (Lloyd et al. 2006, eq. 2 with a uniform map), defaults and tuned;
* middle: the steepest receiver free of acne per cascade, as its angle to the light, scanned from
  the flattest receiver of the band (the ground under the highest sun, 30°; "acne" where even it
  acnes) up to 85° (the ground at the lowest sun is 75°; the dotted line the steepest asked for);
* right: how far the bias moves a shadow's edge on the ground (:func:`aliasing.bias.edge_shift`:
  the lit gap at a wall's foot for a depth bias, the shortening of the shadow for a normal offset),
  the worst sun, in pixels at each cascade's middle depth, with the memory in the title.

Beside the tuned settings, each other bias setting of the engine at its own minimum alone (the
search tried it and kept the one with the smaller gap).
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import numpy as np

from aliasing import setups
from aliasing.plotting import save, subplots, write_table
from aliasing.tune import limits, measure, tune

NAME = "tune-engines"
CAMERA = "near=0.1,far=500,fov=50,aspect=16:9,height=1080"
SUN = "15..60"
SLOPE = 10.0
#: Settings beside the defaults per engine: 4 cascades (Babylon.js, Godot and Bevy have them by
#: default) and front faces casting (the other engines cast front faces by default).
SETTINGS = {"threejs": {"cascades": 4, "material.shadowSide": "FrontSide"}, "playcanvas": {"numCascades": 4},
            "unity-urp": {"shadowCascadeCount": 4}, "filament": {"shadowCascades": 4}, "unreal": {"DynamicShadowCascades": 4}}


def case(engine: str):
    """The tuned result of ``engine``'s case (module docstring), or None where nothing is tunable."""
    profile = setups.get(engine)
    if not profile.tunable:
        return None
    start = setups.build(engine, SETTINGS.get(engine, {}), CAMERA, SUN)
    fixed = tuple(t.key for t in profile.tunable if t.role in ("cascades", "size"))
    return tune(start, keep=fixed, max_slope=SLOPE)


def acne_free(setup) -> np.ndarray:
    """Per cascade, the steepest receiver free of acne: its angle to the light [deg] (0.5° steps up to 85°).

    The bias the settings give against the bias a planar receiver needs at each angle, in the
    cascade's largest texel with the filter's kernel (:mod:`aliasing.tune.measure`), from the
    flattest receiver asked (the ground under the highest sun: flatter ones do not occur in the
    band; a bias across the light, Godot's normal bias, may fall short there).  NaN where even
    that one acnes.
    """
    from aliasing.bias import plane_bias
    from aliasing.tune.measure import AZIMUTH, MAX_ANGLE, lookup

    m = measure(setup, limits(setup))
    flat = 90.0 - setup.sun.elevation[1]
    theta = np.arange(flat, MAX_ANGLE + 0.25, 0.5)
    out = []
    for w in m.texel:
        if setup.pipeline.bias.faces == "back":
            out.append(MAX_ANGLE)
            continue
        need = np.asarray(plane_bias(w, theta, AZIMUTH, lookup(setup.pipeline)).depth)
        have = np.asarray(setup.pipeline.bias.depth(w, theta, AZIMUTH))
        ok = have >= need * (1 - 1e-9) - 1e-12
        out.append(float(theta[np.argmin(ok) - 1]) if not ok.all() and ok[0] else MAX_ANGLE if ok.all() else np.nan)
    return np.array(out)


def data(t) -> dict[str, np.ndarray]:
    """Per cascade of a tuned result ``t`` (:func:`case`), defaults, tuned and each other bias alone:
    error, steepest acne-free angle, gap."""
    runs = [("defaults", t.start, t.before), ("tuned", t.setup, t.measure)]
    fixed = tuple(x.key for x in t.setup.profile.tunable if x.role in ("cascades", "size"))
    for b in (x for x in t.setup.profile.tunable if x.role == "bias" and x.active(t.setup.settings)):
        if b.key in t.changed:
            continue
        others = tuple(x.key for x in t.setup.profile.tunable if x.role == "bias" and x.key != b.key)
        alt = tune(t.start, keep=fixed + others, max_slope=SLOPE)
        runs.append((f"{b.key} alone", alt.setup, alt.measure))
    n = len(t.measure.error)
    cols: dict[str, np.ndarray] = {"cascade": np.arange(n, dtype=float)}
    for label, setup, m in runs:
        if len(m.error) != n:
            continue
        cols[f"error|{label}"] = m.error
        cols[f"angle|{label}"] = acne_free(setup)
        cols[f"gap|{label}"] = m.gap_px
        cols[f"memory|{label}"] = np.full(n, 4.0 * m.texels)
    return cols


def _figure(engine: str, t, cols: dict[str, np.ndarray], out_dir: Path) -> list[Path]:
    k = np.arange(len(cols["cascade"]))
    labels = [c.split("|", 1)[1] for c in cols if c.startswith("error|")]
    colors = ["0.6", "C0", "C1", "C2", "C3"]
    fig, axes = subplots(3, width=4.2, height=3.6)
    w = 0.8 / len(labels)
    need = min(90 - t.setup.sun.elevation[0] + SLOPE, 85.0)
    for ax, key, title, ylabel in ((axes[0], "error", "Worst error per cascade", "pixels per texel (error)"),
                                   (axes[1], "angle", "Steepest receiver free of acne", "angle to the light [deg]"),
                                   (axes[2], "gap", "Shadow edges moved", "edge shift on the ground [px]")):
        for j, label in enumerate(labels):
            v = cols[f"{key}|{label}"]
            x = k + (j - (len(labels) - 1) / 2) * w
            bars = ax.bar(x, np.nan_to_num(v), w, color=colors[j % len(colors)], label=label)
            for b, val in zip(bars, v):
                ax.text(b.get_x() + b.get_width() / 2, b.get_height(), "acne" if np.isnan(val) else f"{val:.3g}", ha="center", va="bottom", fontsize=6)
        ax.set(xticks=k, xlabel="cascade", ylabel=ylabel, title=title)
        ax.legend(fontsize=7)
    axes[0].set_yscale("log")
    axes[1].axhline(need, color="k", lw=0.8, ls=":")
    axes[1].set_ylim(0, 120)
    flat = 90 - t.setup.sun.elevation[1]
    axes[1].text(k[0] - 0.4, 104, f"asked: {flat:g}–{need:g}°\n(ground to {SLOPE:g}° slopes)", fontsize=7)
    axes[1].legend(fontsize=7, loc="upper right")
    axes[2].set_yscale("symlog", linthresh=1.0)
    axes[2].set_ylim(0, max(10.0, float(np.nanmax([cols[c] for c in cols if c.startswith("gap|")]))) * 5)
    axes[2].set_title(f"Shadow edges moved by the bias ({cols['memory|tuned'][0] / 2**20:.0f} MiB each)", fontsize=10)
    changed = ", ".join(f"{key}={v:.4g}" if isinstance(v, float) else f"{key}={v}" for key, v in t.changed.items())
    head = f"{t.setup.profile.title} {t.setup.release} (4 cascades, 1920×1080, fov 50°, near 0.1 m, far 500 m, sun 15–60°), defaults vs tuned"
    lines = textwrap.wrap(f"tuned: {changed}", 150)
    fig.suptitle("\n".join([head, *lines]), fontsize=9)
    return save(fig, out_dir, f"tune-{engine}", columns={c.replace("|", "_").replace(" ", "_"): v for c, v in cols.items()})


def _overview(rows: list[tuple[str, dict[str, np.ndarray]]], out_dir: Path) -> list[Path]:
    """``tune-engines.png``: every engine's worst error and largest gap over its cascades, defaults and tuned."""
    names = [name for name, _ in rows]
    x = np.arange(len(rows))
    fig, axes = subplots(2, width=5.0, height=3.6)
    columns: dict[str, np.ndarray] = {}
    for ax, key, title, ylabel, reduce in ((axes[0], "error", "Worst error over the cascades", "pixels per texel (error)", np.nanmax),
                                           (axes[1], "gap", "Largest peter-panning over the cascades", "lit gap at a wall's foot [px]", np.nanmax)):
        for j, (label, color) in enumerate((("defaults", "0.6"), ("tuned", "C0"))):
            v = np.array([float(reduce(cols[f"{key}|{label}"])) for _, cols in rows])
            columns[f"{key}_{label}"] = v
            bars = ax.bar(x + (j - 0.5) * 0.4, v, 0.4, color=color, label=label)
            for b, val in zip(bars, v):
                ax.text(b.get_x() + b.get_width() / 2, b.get_height(), f"{val:.3g}", ha="center", va="bottom", fontsize=6)
        ax.set(xticks=x, title=title, ylabel=ylabel)
        ax.set_xticklabels(names, rotation=30, ha="right")
        ax.legend(fontsize=7)
    axes[0].set_yscale("log")
    axes[1].set_yscale("symlog", linthresh=1.0)
    fig.suptitle(f"aliasing tune per engine: 4 cascades, 1920×1080, fov 50°, near 0.1 m, far 500 m, sun 15–60°, receivers to {SLOPE:g}° slopes kept free of acne, no gap limit "
                 "(tune-<engine>.png: per cascade)", fontsize=9)
    return save(fig, out_dir, NAME) + [write_table({"engine": names, **columns}, Path(out_dir) / f"{NAME}.csv")]


def main(out_dir: Path) -> list[Path]:
    """One figure per engine with tunable settings, then the overview ``tune-engines.png`` (with its CSV)."""
    paths: list[Path] = []
    rows = []
    for engine in setups.ENGINES:
        t = case(engine)
        if t is None:
            continue
        cols = data(t)
        paths += _figure(engine, t, cols, Path(out_dir))
        rows.append((engine, cols))
    return paths + _overview(rows, Path(out_dir))
