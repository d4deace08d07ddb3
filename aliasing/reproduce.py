"""Registry of reproduced figures and tables: target name → script under figures/.

Example
-------
>>> from aliasing.reproduce import TARGETS
>>> "lloyd2006-fig5" in TARGETS
True
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

from . import _validation as check


@dataclass(frozen=True)
class Target:
    """A reproducible figure or table."""

    name: str
    module: str
    description: str


TARGETS: dict[str, Target] = {
    t.name: t
    for t in (
        Target("lloyd2006-fig5", "lloyd2006_fig5", "Lloyd 2006 Fig. 5: m_x, m_z along z for several n' (n=1, f=20)"),
        Target("lloyd2006-fig6", "lloyd2006_fig6", "Lloyd 2006 Fig. 6: M_x, M_z, S over eta (n=1, f=100)"),
        Target("wimmer2004-fig6", "wimmer2004_fig6", "Wimmer 2004 Fig. 6: dp/ds over z, uniform/PSM/LiSPSM (z_n=1, z_f=100)"),
        Target("zhang2007-fig5", "zhang2007_fig5", "Zhang 2007 Fig. 5: lambda over theta, eq. 4/GMNPR/LiSPSM/GLPR (n=1, f=100, phi=pi/6 assumed)"),
        Target("zhang2007-fig6", "zhang2007_fig6", "Zhang 2007 Fig. 6: F over z, LiSPSM and GMNPR, theta above/below phi (n=1, f=100, phi=pi/6)"),
        Target("lloyd2006-fig7", "lloyd2006_fig7", "Lloyd 2006 Fig. 7: log10 S over the hemisphere of light directions, standard vs LiSPSM (f/n=1000, theta=30)"),
        Target("lloyd2007-fig29", "lloyd2007_fig29", "Lloyd 2007 Fig. 29: M_s, M_t and S over eta for several light directions, P and LogP (n=1, f=1024, theta=30)"),
        Target("lloyd2007-fig30", "lloyd2007_fig30", "Lloyd 2007 Fig. 30: eta shaping strategies over gamma (fixed, 1/sin, S-optimal, eq. 79), P and LogP (n=1, f=1024, theta=30)"),
        Target("lloyd2006-fig10", "lloyd2006_fig10", "Lloyd 2006 Fig. 10: S over the number of z-partitions k, ZP/ZP+W (eqs. 17-18) vs the log optimum, light overhead (f/n=1000, theta=30 assumed)"),
        Target("lloyd2006-fig12", "lloyd2006_fig12", "Lloyd 2006 Fig. 12: S over the number of shadow maps, ZP/ZP+W/FP+ZP+W, light overhead and behind (f/n=1000, theta=30)"),
        Target("lloyd2006-fig13", "lloyd2006_fig13", "Lloyd 2006 Fig. 13: lowest-error scheme with the light behind over f/n x number of maps, crossover j*(f/n)"),
        Target("zhang2006-splits", "zhang2006_splits", "Zhang 2006 PSSM: split positions of log/uniform/practical/eqs. 1-3/eq. 4 schemes (n=1, f=800, m=3, 4)"),
        Target("engine-presets", "engine_presets", "Engine cascade presets vs the log split: worst aliasing error over light directions, equal vs error-based allocation (near 0.5, far 500, fov 60, 4x2048^2 texels, 1920 px)"),
        Target("raster-shadows", "raster_shadows", "Rasterizer: shadowed renders, Standard/P/LogP/ZP4+P at one 256^2 texel budget (f/n=100, gamma 110, azimuth 60)"),
        Target("raster-grid", "raster_grid", "Rasterizer: shadow-map texel grid projected on the scene, every 8 texels (Lloyd 2006 Fig. 15 style)"),
        Target("raster-error", "raster_error", "Rasterizer: measured per-pixel perspective error, log colour scale blue<=1..red (Lloyd 2007 Fig. 13 style)"),
        Target("raster-cdf", "raster_cdf", "Rasterizer: CDF of max error over random light directions, analytic + measured (Lloyd 2007 Fig. 17 style, f/n=1000)"),
        Target("lloyd2007-table3", "lloyd2007_table3", "Lloyd 2007 Table 3, all 16 rows (FP/FPc/FPcs included), beside the printed values (f/n=1000, theta=30)"),
        Target("lloyd2007-fig15", "lloyd2007_fig15", "Lloyd 2007 Fig. 15: S over gamma, ZPk with uniform/P/LogP maps vs FP+LogP and FPcs+LogP (f/n=1024, theta=30)"),
        Target("lloyd2007-fig18", "lloyd2007_fig18", "Lloyd 2007 Fig. 18: error-bound spacing delta_b,t on a side face for lights at l_y = kappa(y1-y0), l_z = sigma(y1-y0) (theta=45, n=1, f=1000)"),
        Target("lloyd2007-fig19", "lloyd2007_fig19", "Lloyd 2007 Fig. 19: error-bound spacing delta_b,t on the far face, light over its centre, cos theta factored out"),
        Target("lloyd2007-fig20", "lloyd2007_fig20", "Lloyd 2007 Fig. 20: error-bound spacing delta_b,s(u, v) on a side face, light centred (l_z = 0.1(y1-y0) assumed)"),
        Target("lloyd2007-fig21", "lloyd2007_fig21", "Lloyd 2007 Fig. 21: R_b (t end, s side, t side) of the error-bound parameterizations vs light position"),
        Target("lloyd2007-fig25", "lloyd2007_fig25", "Lloyd 2007 Fig. 25: R_log,t on a side face vs light position, optimal a and a = 0"),
        Target("lloyd2007-fig26", "lloyd2007_fig26", "Lloyd 2007 Fig. 26: S of the linear log+perspective form, parabolic fits, two-parabola S vs light position"),
        Target("lloyd2007-fig22", "lloyd2007_fig22", "Lloyd 2007 Fig. 22: R_un (t end, s side, t side) of the uniform parameterization vs light position"),
        Target("lloyd2007-fig23", "lloyd2007_fig23", "Lloyd 2007 Fig. 23: optimal R_p,s, R_p,t and S_p of the perspective parameterization vs light position"),
        Target("lloyd2007-fig24", "lloyd2007_fig24", "Lloyd 2007 Fig. 24: the range of optimal perspective parameters a of S_p (l_y = 0.5 y1) and its top vs light position"),
        Target("warping-rule-grid", "warping_rule_grid", "New: max S / Standard's max and mean S / S-optimal mean of P, LogP, LiSPSM, GMNPR, GLPR and the pyramid rules over f/n 10..1e5 x fov 20..120 (2000 directions)"),
        Target("bias-threshold", "bias_threshold", "Depth bias: acne against the derived minimum in the rasterizer, uniform/perspective/log maps, nearest and 3x3 PCF (plane 60 deg from the light)"),
        Target("bias-presets", "bias_presets", "Engine bias rules per cascade: ground margin, acne angle and lit gap in pixels for Filament, Bevy, Godot 4, Unity URP, three.js (near 0.1, far 100, 4 cascades, 2048^2)"),
        Target("engines-comparison", "engines_comparison", "Engine schemes: m_x along the view and critical storage over gamma, stable CSM, SDSM, UE5 VSM High/Epic, matched and exact limits (near 10 cm, far 1 km, fov 60, 1920 px)"),
        Target("check-threejs", "check_threejs", "aliasing check for three.js r187's CSM (4 x 2048^2, 1920x1080, fov 50, near 0.1, far 500, sun 15-60): error along the view, the normalBias each cascade needs, the gap a common shadowBias costs"),
        Target("tune-engines", "tune_engines", "aliasing tune per engine (tune-engines.png: every engine's worst error and gap; tune-<engine>.png: per cascade): defaults vs tuned, worst error, acne margin and peter-panning per cascade at the same memory (4 cascades, 1920x1080, fov 50, near 0.1, far 500, sun 15-60, slopes to 10 deg)"),
        Target("shimmer-tradeoff", "shimmer_tradeoff", "New: should I stabilize? Each engine stable preset's resolution cost (S ratio to the tight fit) beside the shimmer it removes (flips per second, boxes scene, sideways, forward and yaw paths)"),
    )
}


#: What ``aliasing reproduce`` says at its end: what to run next.
NEXT = ("next: check your own engine's shadows, e.g. aliasing check --engine threejs --set cascades=4 "
        "--camera near=0.1,far=500,fov=50,aspect=16:9,height=1080 --sun 15..60 (aliasing check --help; "
        "the guide's 'Check your engine' page)")


def resolve(names: Iterable[str]) -> list[Target]:
    """Targets for ``names`` (``all`` expands to every target); ``ValueError`` lists valid names."""
    names = list(names) or ["all"]
    chosen: list[Target] = []
    for name in names:
        if name == "all":
            chosen.extend(TARGETS.values())
        elif name in TARGETS:
            chosen.append(TARGETS[name])
        else:
            hint = check.did_you_mean(name, ["all", *TARGETS])
            raise ValueError(f"unknown reproduce target {name!r}{hint}; valid targets: all, {', '.join(TARGETS)}")
    return list(dict.fromkeys(chosen))


def reproduce(names: Iterable[str], out_dir: str | Path) -> list[Path]:
    """Run the figure scripts for ``names`` and return the files written into ``out_dir``."""
    targets = resolve(names)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ValueError(f"out must be a folder, but {str(out)!r} is a file")
    written: list[Path] = []
    for target in targets:
        module = importlib.import_module(f"aliasing.figures.{target.module}")
        written.extend(module.main(out))
    return written
