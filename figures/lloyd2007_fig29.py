"""Lloyd et al. 2007, Figure 29: perspective error over the warping parameter η for several light directions.

App. B of the LogPSM report.  A directional light in the view frustum's yz plane (azimuth
0°) at γ ∈ {90°, 60°, 30° = θ, 15°, 0°} (rows); x-axis η ∈ [−1, 1], converted to n′ by
eq. 120 in light-plane units (:func:`aliasing.warping.n_prime_from_eta` with
``depth`` = W_ly(γ), so n′(1) = n_γ = W_ly/(f/n − 1), n′(0) = n_γ(1 + √(f/n)), n′(−1) = ∞).
Frustum n = 1, f = 1024, θ = 30° (fov 60°), unit resolutions, cos θ of δ_b dropped as in
App. B.  Columns, log y axes:

* M̃_p,s (= M̃_lp,s, F_lp,s = F_p,s): the error across the map (s), the toolkit's m_x;
* M̃_p,t: along the map (t) for the perspective parameterization F_p, the toolkit's m_z;
* M̃_lp,t: along t for the logarithmic+perspective parameterization F_lp;
* S = R_s·R_t for P and LogP, with the uniform map's S_un (η-independent) for reference.

In the M̃ panels, as in the paper: heavy dotted = v = v_n1 (the far end of the near face in
the light image plane, v = y/W_ly), thin solid = v = 1 (the far end of the bottom face),
dashed = M̃_p,t at its minimum over v, v = v_min.  R (the critical resolution factor) is the
upper envelope of each panel's curves; here R_s = M_x, R_t = M_z are the maxima over the
frustum's 8 vertices (:mod:`aliasing.directional`), which equal max(M̃(v_n1), M̃(1)) for
in-plane lights (m_x ∝ (Y + n′)/d is monotone and m_z ∝ (Y + n′)²/d convex along each back-face
edge, and the near-face and far-top vertices never dominate).  The M̃(v) profiles are
evaluated at the frustum's x = 0 section (F_p,s is constant in u) along the back faces
[top face if γ < θ] → near face → bottom face, ``samples`` points per edge.

What the paper's text says and this figure shows:

* "S_p is the same over η ∈ [0, 1] for γ = 90°" (caption; Lloyd 2006 eq. 12): flat at
  (f/n − 1)/(2 tanθ) ≈ 886, while S_lp falls to ln(f/n)/(2 tanθ) ≈ 6.0 at η = 1.
* "For an overhead light, both R and the variation in M̃ for F_p,s and F_lp,t are minimal
  at η = 1": at γ = 90° M̃_p,s ≡ 1 and M̃_lp,t(v_n1) = M̃_lp,t(1) = R_lp,t at η = 1.  At
  η = 0, M̃_p,t(v_n1) = M̃_p,t(1) (LiSPSM balances both ends) and its minimum lies inside
  (v_min ∈ (0, 1) for η ≈ −0.5 … 0.2; Fig. 28's text gives η ∈ [−0.4, 0.4] for f = 16).
* "As γ decreases, the variation in error increases slightly at η = 1, but R_p,s rises
  significantly, while R_lp,t remains practically the same": at η = 1, R_p,s = 1 → 3.0 →
  6.5 → 95 → 2047 at γ = 90°, 60°, 45°, 31°, 30°, while R_lp,t = 6.0 → 10.4 → 11.6 → 12.0 →
  12.0 (within a factor 2 down to θ).
* "At γ = θ, there is a rapid shift in R for η ∈ [0, 1]" (R_p,s(η = 1): 95 at 31°, 2047
  at 30°: the top face turns edge-on and the warping frustum must widen to the far face at
  its apex), "but the shift in R_p,t is more gradual".  "As γ continues to decrease, the
  maximum error for all the functions grows steadily until it is higher than that of a
  uniform parameterization for all η ≠ 0": we read "η ≠ −1" — at γ = 0° S_p and S_lp
  exceed S_un for every η > −1, while at 15° η ≈ −0.75 still beats the uniform map by
  ≈ 3 % (the S-optimal η of Fig. 30 reaches −1 only at γ ≈ θ/3 for P).  "It is important
  that η be close to 0 by the time γ = θ": at γ = θ, S_p is minimal at η = 0 and S_lp
  near η ≈ 0.7, both far above their γ = 90° values.
* With the light in front (γ = 0°) "the minimal maximum error is attained for all
  parameterizations at η = −1" (Fig. 28's discussion): S_p and S_lp are minimal at η = −1.
* For γ < θ the minimum of M̃_p,t lies at v = 0, the far end of the top face (now a back
  face), where the warp's texels are densest (hence values ≪ 1).

Not reproduced (the extraction has the caption and text only, no image): the paper's exact
set of γ values (it says "several light directions"; we chose 90°, 60°, 30°, 15°, 0°), its
panel layout, and any curves not named in the caption.  All curves the caption names are
drawn: M̃ at v_n1 and at v = 1 for F_p,s, F_p,t, F_lp,t, M̃_p,t at v_min, and S.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import directional, geometry
from aliasing.plotting import save, subplots
from aliasing.view import View
from aliasing.warping import n_prime_from_eta

NAME = "lloyd2007-fig29"
NEAR, FAR, FOV = 1.0, 1024.0, 60.0
GAMMAS = (90.0, 60.0, 30.0, 15.0, 0.0)
PARAMETERIZATIONS = {"P": "perspective", "LogP": "logperspective"}
SAMPLES = 101  # profile points per back-face edge



def _profile_points(samples: int) -> tuple[np.ndarray, np.ndarray]:
    """Points along the x = 0 section: top face (far→near), near face (top→bottom), bottom face (near→far).

    Returns ``(points (3·samples, 3), on_top (3·samples,) bool)``.
    """
    t = View(NEAR, FAR, FOV).tan_theta
    ft, nt, nb, fb = (np.array([0.0, s * d * t, d]) for s, d in ((1, FAR), (1, NEAR), (-1, NEAR), (-1, FAR)))
    s = np.linspace(0.0, 1.0, samples)[:, None]
    points = np.concatenate([ft + s * (nt - ft), nt + s * (nb - nt), nb + s * (fb - nb)])
    on_top = np.repeat([True, False, False], samples)
    return points, on_top


def light_fit(gamma: np.ndarray, count: int, samples: int = SAMPLES) -> tuple[directional.LightFit, np.ndarray]:
    """Light-plane fit of the frustum's 8 vertices followed by the back-face profile points.

    For in-plane lights at ``gamma`` (N,) [deg], repeated ``count`` times along the
    partition axis so that n′ may vary per light and per sample: coordinates (N, count, V).
    Also returns the profile mask (N, V − 8): True where the point lies on a back face.
    """
    gamma = np.asarray(gamma, float)
    points, on_top = _profile_points(samples)
    verts = np.concatenate([geometry.frustum_vertices(NEAR, FAR, FOV), points])
    lf = directional.fit(verts, geometry.light_direction(gamma, 0.0))  # (N, 1, V)
    n, v = lf.x.shape[0], lf.x.shape[-1]
    wide = directional.LightFit(
        x=np.broadcast_to(lf.x, (n, count, v)),
        y=np.broadcast_to(lf.y, (n, count, v)),
        depth=np.broadcast_to(lf.depth, (n, count)),
        eye_depth=np.broadcast_to(lf.eye_depth, (count, v)),
    )
    back = ~(on_top[None, :] & (gamma[:, None] >= FOV / 2))  # the top face is back-facing only for γ < θ
    return wide, back


def errors(lf: directional.LightFit, back: np.ndarray, n_prime: np.ndarray, parameterization: str) -> dict[str, np.ndarray]:
    """M̃_s, M̃_t at v_n1, at v = 1 and at M̃_t's minimum, plus R_s, R_t and S; each (N, E)."""
    mx, mz = directional.vertex_errors(lf, FOV, n_prime, parameterization)
    y = lf.y
    near = np.argmax(y[..., :4], axis=-1)[..., None]  # the near-face vertex farthest along y: v = v_n1
    far = 4 + np.argmax(y[..., 4:8], axis=-1)[..., None]  # the vertex at v = 1

    def at(m: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return np.take_along_axis(m, idx, axis=-1)[..., 0]

    prof = np.where(back[:, None, :], mz[..., 8:], np.inf)
    i_min = np.argmin(prof, axis=-1)[..., None]
    r_s, r_t = mx[..., :8].max(axis=-1), mz[..., :8].max(axis=-1)
    return {
        "s(v_n1)": at(mx, near),
        "s(1)": at(mx, far),
        "t(v_n1)": at(mz, near),
        "t(1)": at(mz, far),
        "t(v_min)": np.take_along_axis(prof, i_min, axis=-1)[..., 0],
        "v_min": at(y[..., 8:], i_min) / lf.depth,
        "v_n1": at(y, near) / lf.depth,
        "R_s": r_s,
        "R_t": r_t,
        "S": r_s * r_t,
    }


def data(count: int = 201, gammas: tuple[float, ...] = GAMMAS, samples: int = SAMPLES) -> dict[str, np.ndarray]:
    """Long-format columns: one row per (γ, η); ``count`` η samples in [−1, 1]."""
    gamma = np.asarray(gammas, float)
    eta = np.linspace(-1.0, 1.0, count)
    lf, back = light_fit(gamma, count, samples)
    npr = n_prime_from_eta(eta[None, :], NEAR, FAR, depth=lf.depth)  # (N, E), eq. 120
    cols: dict[str, np.ndarray] = {
        "gamma": np.repeat(gamma, count),
        "eta": np.tile(eta, gamma.size),
        "n_prime": npr.ravel(),
        "W_ly": lf.depth.ravel(),
    }
    for label, param in PARAMETERIZATIONS.items():
        e = errors(lf, back, npr, param)
        cols[f"M_x[{label}]"], cols[f"M_z[{label}]"] = e["R_s"].ravel(), e["R_t"].ravel()
        cols[f"S[{label}]"] = e["S"].ravel()
        for key in ("s(v_n1)", "s(1)", "t(v_n1)", "t(1)", "t(v_min)", "v_min"):
            if label == "LogP" and key in ("s(v_n1)", "s(1)"):
                continue  # F_lp,s = F_p,s
            cols[f"M_{key}[{label}]" if key != "v_min" else f"v_min[{label}]"] = e[key].ravel()
        cols["v_n1"] = e["v_n1"].ravel()
    uni = errors(lf, back, np.full(lf.depth.shape, np.inf), "uniform")
    cols["S[Standard]"] = uni["S"].ravel()
    return cols


def main(out_dir: Path) -> list[Path]:
    cols = data()
    gammas = np.unique(cols["gamma"])[::-1]
    fig, axes = subplots(4, nrows=len(gammas), width=3.3, height=2.3)
    heavy = dict(ls=":", lw=2.4)
    thin = dict(ls="-", lw=0.9)
    for row, g in zip(axes, gammas):
        sel = cols["gamma"] == g
        eta = cols["eta"][sel]
        c = {k: v[sel] for k, v in cols.items()}
        ax = row[0]
        ax.plot(eta, c["M_s(v_n1)[P]"], color="C0", **heavy, label=r"$v=v_{n1}$")
        ax.plot(eta, c["M_s(1)[P]"], color="C0", **thin, label=r"$v=1$")
        ax = row[1]
        ax.plot(eta, c["M_t(v_n1)[P]"], color="C0", **heavy, label=r"$v=v_{n1}$")
        ax.plot(eta, c["M_t(1)[P]"], color="C0", **thin, label=r"$v=1$")
        ax.plot(eta, c["M_t(v_min)[P]"], color="C2", ls="--", lw=1.0, label=r"$v=v_{min}$")
        ax = row[2]
        ax.plot(eta, c["M_t(v_n1)[LogP]"], color="C1", **heavy, label=r"$v=v_{n1}$")
        ax.plot(eta, c["M_t(1)[LogP]"], color="C1", **thin, label=r"$v=1$")
        ax = row[3]
        ax.plot(eta, c["S[Standard]"], color="0.5", ls="--", lw=1.0, label=r"$S_{un}$")
        ax.plot(eta, c["S[P]"], color="C0", label=r"$S_p$")
        ax.plot(eta, c["S[LogP]"], color="C1", label=r"$S_{lp}$")
        titles = (r"$\tilde M_{p,s}=\tilde M_{lp,s}$", r"$\tilde M_{p,t}$", r"$\tilde M_{lp,t}$", "S")
        for ax, title in zip(row, titles):
            ax.set(yscale="log", xlim=(-1, 1), title=f"{title},  γ = {g:g}°")
            ax.title.set_fontsize(9)
        row[0].set_ylabel(f"γ = {g:g}°")
    for ax in axes[-1]:
        ax.set_xlabel(r"$\eta$  ($n'=\infty$ at −1, $n_\gamma$ at 1)")
    for ax in axes[0]:
        ax.legend(fontsize=7)
    fig.suptitle(f"Lloyd et al. 2007 Fig. 29: error over η for several light directions (n = {NEAR:g}, f = {FAR:g}, θ = {FOV / 2:g}°)", fontsize=11)
    return save(fig, out_dir, NAME, cols)


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
