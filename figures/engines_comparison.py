"""Today's engine schemes: error along the view axis and storage over light directions.

Not a paper figure.  Setting (ours): near 10 cm, shadow distance 1 km (10⁵ cm), fov 60°,
1920 px image, 4 cascades of 2048² texels, light overhead for panel (a), γ from 0° to 180°
(azimuth 0) for panel (b).

(a) m_x along the view axis [image pixels per texel; 1 = critical]: Filament's split with
the tight fit (``csm:filament``) and with Filament's own stable mode (``csm-stable:filament``:
the sphere around each slice's corner centroid, a one-texel border), SDSM log partitions
on the whole range, UE5 virtual shadow maps at High (bias 0) and Epic (bias −1.5, clamped by
the engine to an effective −1.30 at this width and fov), the resolution-matched limit with
power-of-two levels (a saw-tooth in (1/2, 1]) and exact sampling (1).
(b) the critical storage S̄ [image areas] (the papers' Σ M_x·M_z; for VSM the frustum's page
bound × M²) over γ.

What it shows: the CSM presets' error spans three orders of magnitude over distance (the
first cascade is huge against near = 10 cm); the stable fit adds a constant factor and
removes the light dependence; VSM's saw-tooth stays within one octave (2^bias…2^(1+bias))
except near the camera, where the first level's clamp (level 6) makes m grow as 1/d.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import geometry
from aliasing.engines import sdsm, stable, vsm
from aliasing.plotting import save, subplots
from aliasing.view import View

NAME = "engines-comparison"
NEAR, FAR, FOV, WIDTH, RES = 10.0, 1e5, 60.0, 1920, 2048
T = View(NEAR, FAR, FOV).tan_theta


def _csm_axis(res: stable.StableResult, d: np.ndarray) -> np.ndarray:
    u, v = res.used
    i = np.clip(np.searchsorted(v, d, side="left"), 0, len(v) - 1)
    return res.width_x[0, i] / (2 * T * d) * WIDTH / RES


def data(samples: int = 4000, gammas: int = 91) -> dict[str, np.ndarray]:
    """The plotted columns: distance d and m per scheme; γ and S̄ per scheme."""
    d = np.geomspace(NEAR, FAR, samples)
    g = np.linspace(0.0, 180.0, gammas)
    lights = geometry.light_direction(g, 0.0)
    fits = {
        "csm_filament": dict(split="filament", fit="tight"),
        "csm_stable_filament": dict(split="filament", fit="centroid", snap="border", resolution=RES),  # stable.PRESETS["filament"]
        "sdsm_k4": dict(split=sdsm.log_partitions(NEAR, FAR, NEAR, FAR, 4), fit="tight"),
    }
    cols: dict[str, np.ndarray] = {"d": d, "gamma": g}
    for key, kw in fits.items():
        split = kw.pop("split")
        cols[f"m_{key}"] = _csm_axis(stable.evaluate(split, NEAR, FAR, FOV, "overhead", **kw), d)
        cols[f"S_{key}"] = stable.evaluate(split, NEAR, FAR, FOV, lights, **kw).S
    for name in ("high", "epic"):
        c = vsm.Clipmap(FOV, WIDTH, vsm.PRESETS[name].bias)
        cols[f"m_vsm_{name}"] = vsm.m_axis(c, d)
        worst = vsm.frustum_max(c, NEAR, FAR)
        cols[f"S_vsm_{name}"] = vsm.pages(c, NEAR, FAR, lights) * vsm.PAGE**2 * worst**2 / WIDTH**2
    w = 2 * T * d / WIDTH
    cols["m_matched"] = 2.0 ** (np.floor(np.log2(w)) - np.log2(w))
    return cols


LABELS = {
    "csm_filament": "csm:filament (tight)",
    "csm_stable_filament": "csm-stable:filament (Filament's stable)",
    "sdsm_k4": "sdsm:k=4 (whole range)",
    "vsm_high": "vsm:high (bias 0)",
    "vsm_epic": "vsm:epic (bias −1.5)",
}


def main(out_dir: str | Path) -> list[Path]:
    cols = data()
    fig, (a, b) = subplots(2, width=5.6, height=4.0)
    for key, label in LABELS.items():
        a.loglog(cols["d"] / 100, cols[f"m_{key}"], label=label, lw=1.2)
        b.semilogy(cols["gamma"], cols[f"S_{key}"], label=label, lw=1.2)
    a.loglog(cols["d"] / 100, cols["m_matched"], color="k", lw=0.8, label="matched (power-of-two)")
    a.axhline(1.0, color="k", ls=":", lw=1.0, label="exact")
    a.set_xlabel("distance along the view axis d [m]")
    a.set_ylabel("m_x [pixels per texel]")
    a.set_title("(a) error along the view, light overhead")
    a.legend(fontsize=7)
    b.axhline(1.0, color="k", ls=":", lw=1.0, label="matched / exact (S̄ = 1)")
    b.set_xlabel("γ [deg] (azimuth 0)")
    b.set_ylabel("critical storage S̄ [image areas]")
    b.set_title("(b) storage over light directions")
    b.legend(fontsize=7)
    return save(fig, out_dir, NAME, cols_for_csv(cols))


def cols_for_csv(cols: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Columns of equal length for the CSV: the distance samples (the γ samples go into a second block)."""
    n = len(cols["d"])
    out = {k: v for k, v in cols.items() if len(v) == n}
    g = len(cols["gamma"])
    for k, v in cols.items():
        if len(v) == g and k not in out:
            out[k] = np.concatenate([v, np.full(n - g, np.nan)])
    return out
