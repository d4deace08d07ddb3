"""The derived minimal depth bias is the acne threshold, measured in the rasterizer.

Not a paper figure.  A plane 60° from the light, its depth growing fastest 30° from the map's
s axis, fills the map of a view (near 1, far 20, fov 60°, light 60° from the view direction);
128² texels, uniform (Standard), perspective-warped (P) and logarithmic (LogP) maps.  Each of
30 000 points on the plane is looked up with the engines' plain depth compare
(:func:`aliasing.raster.draw.depth_test`) with a constant bias of ``factor`` times its own
derived minimum (:func:`aliasing.bias.map_bias`: (k/2)(|g·e_s| + |g·e_t|) with the local texel
sides e_s, e_t); the curve is the fraction of lit points that shadow themselves (acne), for
nearest lookup and 3×3 PCF.

What it shows (numbers in the CSV): the acne falls to zero at factor 1 in the uniform map
(both filters) and for nearest lookup in the perspective map; in the warped maps with 3×3 PCF
and in the logarithmic map it reaches zero at 1.025–1.05: the minimum uses the texel's sides at
the point (first order), and a warped texel, and more so the k texels a filter reads, grow
across their extent (the logarithmic map's t side by ln(1 + W/n′)/R per texel).  At 0.9 every
case acnes (0.5–5.5 % of the points), so the derived minimum is the threshold, not a bound
with slack.  PCF's curve is steeper: its worst case (the outermost tap's far corner) is reached
by more points.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing.bias import kernel, map_bias
from aliasing.plotting import save, subplots
from aliasing.raster.draw import depth_test, light_map, shadow_map

NAME = "bias-threshold"
THETA, PHI, RES, POINTS = 60.0, 30.0, 128, 30000
FACTORS = np.round(np.linspace(0.5, 1.5, 41), 3)
SCHEMES = ("Standard", "P", "LogP")
LOOKUPS = ("nearest", "pcf3")


def tilted_plane(scheme: str, theta: float, phi: float, res: int, n: int = 30000, seed: int = 0):
    """(light map, depth map, points, normals) of a plane at ``theta`` [deg] from the light, its steepest depth change
    at ``phi`` [deg] in light space, filling a ``res``² map of ``scheme``; ``n`` seeded points on it (also the
    scene of tests/test_bias.py's threshold tests)."""
    lm = light_map(1.0, 20.0, 60.0, "gamma:60", scheme)
    xl, up, zl = lm.basis
    th, ph = np.radians(theta), np.radians(phi)
    nrm = np.cos(th) * up + np.sin(th) * (np.cos(ph) * xl + np.sin(ph) * zl)
    p0 = np.array([0.0, -1.0, 8.0])
    a = np.cross(nrm, [0.3, 0.5, 0.7])
    a /= np.linalg.norm(a)
    b = np.cross(nrm, a)
    tri = np.array([[p0 + 400.0 * (np.cos(t) * a + np.sin(t) * b) for t in (0.0, 2.1, 4.2)]])
    sm = shadow_map(tri, lm, res)
    s, t = np.random.default_rng(seed).uniform(0.02, 0.98, (2, n))
    c0 = lm.plane_point(*lm.inverse(s, t))
    p = c0 + (((p0 - c0) @ nrm) / (nrm @ up))[:, None] * up
    return lm, sm, p, np.broadcast_to(nrm, p.shape)


def data() -> dict[str, np.ndarray]:
    """``factor`` and one acne-fraction column per scheme and lookup."""
    cols = {"factor": FACTORS}
    for scheme in SCHEMES:
        lm, sm, p, n = tilted_plane(scheme, THETA, PHI, RES, POINTS)
        for lookup in LOOKUPS:
            k, rp = kernel(lookup)
            need = map_bias(lm, RES, p, n, lookup).depth
            cols[f"{scheme}_{lookup}"] = np.array([(depth_test(lm, sm, p, n, bias=f * need, pcf=k, receiver_plane=rp) < 1).mean() for f in FACTORS])
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    fig, ax = subplots(width=6.5, height=4.0)
    for i, scheme in enumerate(SCHEMES):
        for lookup, ls in zip(LOOKUPS, ("-", "--")):
            ax.plot(cols["factor"], 100 * cols[f"{scheme}_{lookup}"], color=f"C{i}", ls=ls, marker=".", ms=3, label=f"{scheme}, {lookup}")
    ax.axvline(1.0, color="k", lw=0.9)
    ax.set(xlabel="constant depth bias / derived minimum", ylabel="lit points that shadow themselves [%]")
    ax.set_title(f"Acne against the derived minimum\nplane {THETA:g}° from the light, azimuth {PHI:g}°, {RES}² texels", fontsize=10)
    ax.legend(fontsize=8)
    return save(fig, out_dir, NAME, columns=cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
