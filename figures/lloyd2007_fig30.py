"""Lloyd et al. 2007, Figure 30: shaping functions for the warping parameter, error over γ.

App. B of the LogPSM report.  A directional light in the view frustum's yz plane (azimuth
0°), x-axis γ ∈ [0°, 90°] (0° = light in front, looking into it; 90° = overhead); frustum
n = 1, f = 1024, θ = 30° (fov 60°), unit resolutions, cos θ of δ_b dropped as in App. B.
η ↔ n′ by eq. 120 in light-plane units (depth = W_ly(γ), n_γ = W_ly/(f/n − 1)).

Rows, the strategy choosing η(γ) for the perspective (P, F_p) and log+perspective (LogP,
F_lp) parameterizations:

1. ``fixed``: the γ = 90° optimum without shaping, η_p = 0 (LiSPSM), η_lp = 1;
2. ``1/sin(gamma)``: LiSPSM's modulation of that optimum, n′ = n′(η_opt)/sin γ, converted
   back to η.  For P this is warping rule ``po``, n′ = n_γ(1 + √(f/n))/sin γ (Lloyd 2007
   Table 3's Po, in light-plane units), not rule ``lispsm``, (n + √(fn))/sin γ, whose n′
   ignores the light-plane depth W_ly that eq. 120's η is measured in; for LogP it is
   n′ = n_γ/sin γ (§6.1.1: "the LogPSM analogue");
3. ``S-optimal``: η minimising S per direction (schemes ``Sopt``, ``LogSopt``);
4. ``eq. 79``: the paper's shaping function (rules ``p``, ``logp``: γ_a = θ/3 resp. θ/2,
   γ_b = θ, η_b = −0.2, η_c = 0 resp. 1, γ_c = θ + 0.4(90° − θ) = 54° as in eq. 79; the
   App. B text says 0.3, i.e. 48°; docs/ERRATA.md L3).

Columns (caption: "solid lines are v = v_n, dotted lines are v = 1, and the dashed line is
v = v_min for M̃_p,t"): η(γ) (uniform drawn at η = −1); M̃_s at v_n1 and v = 1; M̃_t at v_n1,
v = 1 and M̃_p,t's minimum; S for the uniform map, P and LogP (log axes).  M̃ are evaluated as
in :mod:`aliasing.figures.lloyd2007_fig29` (frustum vertices in Wimmer light space, back-face
profile at x = 0); R_s, R_t, S are the vertex maxima of :mod:`aliasing.directional`.

What the paper's text says and this figure shows:

* Row 1: "the error for γ < θ is very high": S_p exceeds S_un below γ ≈ 26°, S_lp below
  ≈ 29.5°, up to S_p ≈ 1.5·10⁸ and S_lp ≈ 1.9·10⁹ at γ = 0° (S_un ≈ 1.05·10⁶).
* Row 2: 1/sin γ has a "relatively minor" effect for γ ∈ [θ, 90°] (η stays near its
  optimum), "but for γ ∈ [0°, θ] the falloff is not fast enough": S_p peaks at ≈ 3.9·10⁶
  (γ ≈ 11°; Table 3's 1/sin γ row: 3.65·10⁶ at f/n = 1000) and S_lp at ≈ 1.2·10⁸, both above
  S_un; "M̃_lp,s has even higher error because η_lp is further from −1 than η_p" (the M̃_s
  column, orange above blue for γ < θ).
* Row 3: "for γ ∈ [θ, 90°] η is the same as with no shaping at all" (η_p ≈ 0, η_lp = 1;
  at γ = 90° S_p is flat over η ∈ [0, 1] (Fig. 29), so the optimiser's η_p = 0.05 there is a
  tie, not a jump).  "At γ = θ, η suddenly jumps to 0 and then decreases almost linearly to
  −1 as γ approaches a point somewhere between 0 and θ": observed for LogP (η_lp = 1 above
  θ, ≈ 0.73 at θ, ≈ 0 at 29.5°, −1 from ≈ 16° ≈ θ/2 down); P's optimum is already ≈ 0 above
  θ and falls almost linearly to −1 at ≈ 11° ≈ θ/3, the γ_a of eq. 79 for each.  "The
  optimal S_p and S_lp never rise above S_un" (true at every γ), and "S can change very
  rapidly near γ = θ" (S_lp ×13 between 30.5° and 29.99°).
* Row 4: eq. 79 follows the S-optimal η below θ and keeps S at the fixed optimum for
  γ ≥ γ_c; its η_b = −0.2 at γ = θ costs S there (S_p ≈ 2.1·10⁵, S_lp ≈ 4.0·10⁵ against
  3.0·10⁴ and 2.4·10⁴ S-optimal), the price the text accepts for a smoother transition.
  The maxima of S_p and S_lp over γ equal S_un's (1.05·10⁶ at γ = 0°), unlike row 2, as
  Table 3's discussion says; just past γ_a, S exceeds S_un by < 0.1 % (γ ≈ 10–11° for P,
  15–16.5° for LogP).

Not reproduced (the extraction has caption and text only, no image): the paper's exact
panel arrangement, and whether its η panel draws the uniform line; what its M̃ columns
contain beyond the caption's line styles is inferred from Fig. 29's.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import schemes
from aliasing.figures.lloyd2007_fig29 import FAR, FOV, NEAR, errors, light_fit
from aliasing.geometry import light_direction
from aliasing.plotting import save, subplots
from aliasing.warping import eta_from_n_prime, n_prime_from_eta, warping_parameter

NAME = "lloyd2007-fig30"
STRATEGIES = ("fixed", "1/sin(gamma)", "S-optimal", "eq. 79")  # CSV column tags (ASCII)
DISPLAY = {"1/sin(gamma)": "1/sin γ"}
OPTIMUM = {"P": 0.0, "LogP": 1.0}  # η minimising S at γ = 90° (Lloyd 2006 eq. 12; App. C)
PARAMETERIZATIONS = {"P": "perspective", "LogP": "logperspective"}
SCHEME = {("S-optimal", "P"): "Sopt", ("S-optimal", "LogP"): "LogSopt", ("eq. 79", "P"): "P", ("eq. 79", "LogP"): "LogP"}


def n_prime(strategy: str, label: str, gamma: np.ndarray, depth: np.ndarray) -> np.ndarray:
    """n′ (N, 1) [light-plane units] of a strategy for parameterization ``label`` at γ (N,)."""
    g = gamma[:, None]
    if strategy == "fixed":
        return n_prime_from_eta(np.full(g.shape, OPTIMUM[label]), NEAR, FAR, depth=depth)
    if strategy == "1/sin(gamma)":
        if label == "P":
            return warping_parameter("po", NEAR, FAR, gamma=g, depth=depth)
        s = np.sin(np.radians(g))
        with np.errstate(divide="ignore"):
            return np.where(s > 1e-12, n_prime_from_eta(1.0, NEAR, FAR, depth=depth) / np.where(s > 1e-12, s, 1.0), np.inf)
    return schemes.evaluate(SCHEME[strategy, label], NEAR, FAR, FOV, light_direction(gamma, 0.0)).n_prime


def data(count: int = 361, samples: int = 101) -> dict[str, np.ndarray]:
    """Columns over ``count`` γ samples in [0°, 90°]: η, M̃ and S per strategy and parameterization."""
    gamma = np.linspace(0.0, 90.0, count)
    lf, back = light_fit(gamma, 1, samples)
    cols: dict[str, np.ndarray] = {"gamma": gamma, "W_ly": lf.depth[:, 0]}
    uni = errors(lf, back, np.full(lf.depth.shape, np.inf), "uniform")
    cols["S[Standard]"] = uni["S"][:, 0]
    for strategy in STRATEGIES:
        for label, param in PARAMETERIZATIONS.items():
            npr = n_prime(strategy, label, gamma, lf.depth)
            e = errors(lf, back, npr, param)
            tag = f"[{strategy}|{label}]"
            cols[f"n_prime{tag}"] = npr[:, 0]
            cols[f"eta{tag}"] = eta_from_n_prime(npr, NEAR, FAR, depth=lf.depth)[:, 0]
            for key in ("s(v_n1)", "s(1)", "t(v_n1)", "t(1)"):
                cols[f"M_{key}{tag}"] = e[key][:, 0]
            if label == "P":
                cols[f"M_t(v_min){tag}"] = e["t(v_min)"][:, 0]
            cols[f"M_x{tag}"], cols[f"M_z{tag}"], cols[f"S{tag}"] = e["R_s"][:, 0], e["R_t"][:, 0], e["S"][:, 0]
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    g = cols["gamma"]
    fig, axes = subplots(4, nrows=len(STRATEGIES), width=3.4, height=2.5)
    colour = {"P": "C0", "LogP": "C1"}
    theta = FOV / 2
    s_lo = min(np.nanmin(v) for k, v in cols.items() if k.startswith("S"))
    s_hi = max(np.nanmax(v) for k, v in cols.items() if k.startswith("S"))
    m_lo = min(np.nanmin(v) for k, v in cols.items() if k.startswith("M_"))
    m_hi = max(np.nanmax(v) for k, v in cols.items() if k.startswith("M_"))
    for row, strategy in zip(axes, STRATEGIES):
        shown = DISPLAY.get(strategy, strategy)
        ax_eta, ax_s, ax_t, ax_S = row
        ax_eta.axhline(-1.0, color="0.5", ls="--", lw=1.0, label="uniform")
        ax_S.plot(g, cols["S[Standard]"], color="0.5", ls="--", lw=1.0, label=r"$S_{un}$")
        for label in PARAMETERIZATIONS:
            tag, c = f"[{strategy}|{label}]", colour[label]
            sub = "p" if label == "P" else "lp"
            ax_eta.plot(g, cols[f"eta{tag}"], color=c, label=rf"$\eta_{{{sub}}}$")
            ax_s.plot(g, cols[f"M_s(v_n1){tag}"], color=c, lw=1.2, label=rf"$\tilde M_{{{sub},s}}(v_{{n1}})$")
            ax_s.plot(g, cols[f"M_s(1){tag}"], color=c, ls=":", lw=1.6, label=rf"$\tilde M_{{{sub},s}}(1)$")
            ax_t.plot(g, cols[f"M_t(v_n1){tag}"], color=c, lw=1.2, label=rf"$\tilde M_{{{sub},t}}(v_{{n1}})$")
            ax_t.plot(g, cols[f"M_t(1){tag}"], color=c, ls=":", lw=1.6, label=rf"$\tilde M_{{{sub},t}}(1)$")
            if label == "P":
                ax_t.plot(g, cols[f"M_t(v_min){tag}"], color="C2", ls="--", lw=1.0, label=r"$\tilde M_{p,t}(v_{min})$")
            ax_S.plot(g, cols[f"S{tag}"], color=c, label=rf"$S_{{{sub}}}$")
        ax_eta.set(ylim=(-1.1, 1.1), ylabel=f"row {STRATEGIES.index(strategy) + 1}: {shown}")
        ax_s.set(yscale="log", ylim=(m_lo / 2, m_hi * 2))
        ax_t.set(yscale="log", ylim=(m_lo / 2, m_hi * 2))
        ax_S.set(yscale="log", ylim=(s_lo / 2, s_hi * 2))
        for ax, title in zip(row, (r"$\eta(\gamma)$", r"$\tilde M_s$", r"$\tilde M_t$", "S")):
            ax.axvline(theta, color="k", lw=0.6, alpha=0.5)
            ax.set(xlim=(0, 90), xticks=(0, 15, 30, 45, 60, 75, 90), title=f"{title}: {shown}")
            ax.title.set_fontsize(9)
    for ax in axes[-1]:
        ax.set_xlabel(r"$\gamma$ [deg]  (0 = light in front, 90 = overhead; line at $\theta$)")
        ax.xaxis.label.set_fontsize(8)
    top = axes[0]
    top[0].legend(fontsize=6.5, loc="center", bbox_to_anchor=(0.62, 0.27))
    top[1].legend(fontsize=6.5, loc="lower left", ncol=2)
    top[2].legend(fontsize=6.5, loc="upper right", ncol=2)
    top[3].legend(fontsize=6.5, loc="upper right")
    fig.suptitle(f"Lloyd et al. 2007 Fig. 30: shaping functions for the warping parameter (n = {NEAR:g}, f = {FAR:g}, θ = {FOV / 2:g}°)", fontsize=11)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
