"""Overhead light: m_x, m_z along z (Lloyd et al. 2006 Fig. 5) and M_x, M_z, S̄ over η (Fig. 6).

For a light overhead (γ = 90°) the shadow map's s axis runs across the view and t along
z; a warp with centre of projection n′ before the near plane gives the errors of Lloyd
2006 eqs. 7–8 (m_x, m_z at depth z), their maxima eqs. 9–10 and the storage factor
S̄ = M_x·M_z (eq. 12), all from :mod:`aliasing.error`.  The warp is a rule (uniform, PSM,
LiSPSM), a value of η ∈ [−1, 1] (eq. 11) or an n′ typed in.

Those closed forms are of a square view.  At ``aspect`` ≠ 1 (width/height, ``fov``
vertical: :class:`aliasing.View`) the curves come from the general evaluation instead
(:mod:`aliasing.directional`: the map fitted to the wide frustum's vertices, the errors at
points of its edges), and the picture says so; :mod:`aliasing.symbolic.aspect` derives what
they are: m_x and M_x times the aspect, m_z and M_z unchanged, S̄ times the aspect.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from .. import _validation as check
from .. import directional, error, geometry, warping
from ..view import View
from . import widget as w

RULES = {"uniform": "uniform", "PSM": "psm", "LiSPSM": "lispsm", "η (slider)": "eta", "n′ (typed)": "n_prime"}
#: Samples along z and along η.
Z_SAMPLES, ETA_SAMPLES = 200, 201
#: The overhead light (γ = 90°), exactly (0, 1, 0).
OVERHEAD = geometry.light_direction(90.0)


def general_errors(view: View, z: np.ndarray, n_prime: float, n_primes: np.ndarray) -> dict[str, np.ndarray]:
    """m_x, m_z along z and M_x, M_z over n′ for an overhead light, by the general evaluation.

    The map is fitted to the frustum's vertices (:func:`aliasing.directional.fit`); m_x, m_z
    at depth z are :func:`aliasing.directional.vertex_errors` at the four points of the
    frustum's edges at that depth (inside the fit: they do not move it), the maxima
    :func:`aliasing.directional.max_errors` over the 8 vertices, one map per n′.  Any
    ``aspect`` of ``view``; at aspect 1 these are Lloyd 2006 eqs. 7–10 up to rounding.

    Parameters
    ----------
    view : View
        The eye's view (near, far [world units], vertical fov [deg], aspect).
    z : ndarray
        Eye depths [world units] from near to far, its first and last the near and far.
    n_prime : float
        n′ [world units] of the curves along z.
    n_primes : ndarray
        n′ [world units] of the maxima (e.g. over η).

    Returns
    -------
    dict
        ``m_x``, ``m_z`` (len(z),) and ``M_x``, ``M_z`` (len(n_primes),), unit resolutions.

    Example
    -------
    >>> g = general_errors(View(1.0, 100.0, 90.0, 2.0), np.geomspace(1.0, 100.0, 3), 11.0, np.array([11.0]))
    >>> g["M_x"].round(9).tolist(), g["M_z"].round(9).tolist()     # M_x: 2 × 10, M_z: 4.95 as at aspect 1
    ([20.0], [4.95])
    """
    rays = view.corner_rays  # (4, 3) at unit eye depth
    edges = (np.asarray(z, float)[:, None, None] * rays).reshape(-1, 3)  # 4 edge points per depth, the vertices among them
    mx, mz = directional.vertex_errors(directional.fit(edges, OVERHEAD), view, n_prime)
    verts = np.broadcast_to(geometry.frustum_vertices(view), (len(n_primes), 8, 3))  # one map per n′
    big_x, big_z = directional.max_errors(verts, OVERHEAD, view, np.asarray(n_primes, float)[None])
    return {"m_x": mx[0, 0].reshape(len(z), 4).max(axis=1), "m_z": mz[0, 0].reshape(len(z), 4).max(axis=1),
            "M_x": big_x[0], "M_z": big_z[0]}


def compute(f_over_n: float, fov: float, rule: str, eta: float, n_prime: str, res_image: int, aspect: float = 1.0) -> dict[str, Any]:
    """Curves of Figs. 5–6 and the critical resolution for near = 1, far = f/n.

    Parameters
    ----------
    f_over_n : float
        Depth ratio far/near (> 1).
    fov : float
        Full field of view [deg].
    rule : {"uniform", "psm", "lispsm", "eta", "n_prime"}
        How n′ is chosen.
    eta : float
        η for ``rule="eta"`` (Lloyd 2006 eq. 11), in [−1, 1].
    n_prime : str
        n′ [world units] for ``rule="n_prime"`` (a number or ``inf``).
    res_image : int
        Image resolution [pixels per side; rows of a non-square image] for the critical
        shadow-map resolution.
    aspect : float
        Image width/height (``fov`` vertical, :class:`aliasing.View`).  1: Lloyd 2006's
        closed forms; otherwise the general evaluation (:func:`general_errors`).

    Returns
    -------
    dict
        ``z``, ``m_x``, ``m_z`` (along z), ``eta_axis``, ``M_x_eta``, ``M_z_eta``, ``S_eta``
        (over η), and at the chosen warp ``n_prime``, ``eta``, ``M_x``, ``M_z``, ``S``,
        ``res_s``, ``res_t`` (critical resolution [texels]); ``aspect`` and ``closed_form``
        (whether the closed forms gave them).

    Example
    -------
    >>> d = compute(100.0, 90.0, "lispsm", 0.0, "inf", 1024)
    >>> round(float(d["S"]), 1)       # eq. (12) with n' = n + sqrt(nf)
    49.5
    >>> round(float(compute(100.0, 90.0, "lispsm", 0.0, "inf", 1024, aspect=2.0)["S"]), 1)   # S̄ times the aspect
    99.0
    """
    view = View(1.0, float(f_over_n), fov, aspect)  # validated once
    near, far = 1.0, float(f_over_n)
    if rule == "n_prime":
        try:
            npr = float(n_prime)
        except ValueError:
            raise ValueError(f"n′ must be a number > 0 or 'inf' [world units], got {n_prime!r}") from None
        if not npr > 0:
            raise ValueError(f"n′ must be > 0 (distance of the centre of projection before the near plane), got {n_prime!r}")
    elif rule == "eta":
        npr = float(warping.n_prime_from_eta(eta, near, far))
    else:
        npr = float(warping.warping_parameter(rule, near, far, gamma=90.0))
    z = np.geomspace(near, far, Z_SAMPLES)
    eta_axis = np.linspace(-1.0, 1.0, ETA_SAMPLES)
    np_eta = warping.n_prime_from_eta(eta_axis, near, far)
    eta_chosen = float(warping.eta_from_n_prime(npr, near, far)) if npr >= near else float("nan")
    if not view.square:  # no closed form: the general evaluation
        ri = float(check.positive(res_image, "res_image"))
        g = general_errors(view, z, npr, np.append(np_eta, npr))
        mx_eta, mz_eta = g["M_x"][:-1], g["M_z"][:-1]
        big_x, big_z = float(g["M_x"][-1]), float(g["M_z"][-1])
        return {
            "f_over_n": far, "fov": float(fov), "aspect": float(view.aspect), "closed_form": False, "rule": rule, "n_prime": npr,
            "eta": eta_chosen, "z": z, "m_x": g["m_x"], "m_z": g["m_z"],
            "eta_axis": eta_axis, "M_x_eta": mx_eta, "M_z_eta": mz_eta, "S_eta": mx_eta * mz_eta,
            "M_x": big_x, "M_z": big_z, "S": big_x * big_z, "res_s": big_x * ri, "res_t": big_z * ri,
        }
    mx_eta = error.max_error_x(near, far, np_eta)
    mz_eta = error.max_error_z(near, far, fov, np_eta)
    res_s, res_t = error.critical_resolution(near, far, fov, npr, res_image=res_image)
    return {
        "f_over_n": far, "fov": float(fov), "aspect": 1.0, "closed_form": True, "rule": rule, "n_prime": npr,
        "eta": eta_chosen,
        "z": z, "m_x": error.m_x(z, near, far, npr), "m_z": error.m_z(z, near, far, fov, npr),
        "eta_axis": eta_axis, "M_x_eta": mx_eta, "M_z_eta": mz_eta, "S_eta": error.storage_factor(near, far, fov, np_eta),
        "M_x": float(error.max_error_x(near, far, npr)), "M_z": float(error.max_error_z(near, far, fov, npr)),
        "S": float(error.storage_factor(near, far, fov, npr)), "res_s": float(res_s), "res_t": float(res_t),
    }


def draw(fig: Figure, d: dict[str, Any]) -> dict:
    """Fig. 5 (left) and Fig. 6 (right) with the chosen warp marked; returns the artists for :func:`redraw`."""
    a, b = fig.subplots(1, 2)
    a.loglog(d["z"], d["m_x"], label="m_x")
    a.loglog(d["z"], d["m_z"], label="m_z")
    a.axhline(1.0, color="0.6", lw=0.8)
    a.set(xlabel="z [world units]", ylabel="m (texel/pixel width, unit res.)")
    a.legend(fontsize=8)
    b.semilogy(d["eta_axis"], d["M_x_eta"], label="M_x")
    b.semilogy(d["eta_axis"], d["M_z_eta"], label="M_z")
    b.semilogy(d["eta_axis"], d["S_eta"], label="S̄", color="k")
    marker = b.axvline(0.0, color="C3", lw=1, ls="--")
    b.set(xlabel="η (−1 uniform, 0 LiSPSM, 1 PSM)")
    b.legend(fontsize=8)
    w.readable_log_ticks(a.xaxis, a.yaxis, b.yaxis)  # ≥ 3 labelled ticks at any f/n (f/n = 1.5 is under a decade)
    fig.subplots_adjust(left=0.1, right=0.98, bottom=0.15, top=0.84, wspace=0.22)
    artists = {"a": a, "b": b, "marker": marker, "suptitle": fig.suptitle("", fontsize=10)}
    redraw(artists, d)
    return artists


def redraw(artists: dict, d: dict[str, Any]) -> bool:
    """Put new data into the artists of :func:`draw` (the same lines; limits, titles, marker)."""
    a, b = artists["a"], artists["b"]
    a.lines[0].set_data(d["z"], d["m_x"])
    a.lines[1].set_data(d["z"], d["m_z"])
    for line, key in zip(b.lines[:3], ("M_x_eta", "M_z_eta", "S_eta")):
        line.set_data(d["eta_axis"], d[key])
    for ax in (a, b):
        ax.relim()
        ax.autoscale_view()
    artists["marker"].set_xdata([d["eta"]] * 2 if np.isfinite(d["eta"]) else [0.0, 0.0])
    artists["marker"].set_visible(bool(np.isfinite(d["eta"])))
    closed = d.get("closed_form", True)
    a.set_title(f"{'Lloyd 2006 Fig. 5' if closed else 'Fig. 5, general evaluation'}: n′ = {d['n_prime']:.4g}")
    b.set_title(f"Fig. 6: S̄ = {d['S']:.4g}, critical res. {d['res_s']:.4g} × {d['res_t']:.4g}", fontsize=9)
    wide = "" if closed else f", aspect = {d['aspect']:.3g} (Lloyd 2006's closed forms are square: general evaluation)"
    artists["suptitle"].set_text(f"overhead light, f/n = {d['f_over_n']:.4g}, fov = {d['fov']:g}°{wide}, warp {d['rule']}")
    return True


class OverheadExplorer(w.Explorer):
    """m_x, m_z and S̄ for an overhead light; controls f/n (log), fov, aspect (log), warp rule, η, n′, image resolution.

    Example
    -------
    >>> from aliasing import explore
    >>> e = explore.overhead(f_over_n=100.0, fov=90.0, rule="lispsm")   # doctest: +SKIP
    >>> round(e.data["S"], 1)                                            # doctest: +SKIP
    49.5
    """

    title = "Overhead light (Lloyd et al. 2006 Figs. 5–6)"

    def make_controls(self) -> dict:
        return {
            "f_over_n": w.log_slider("f/n", 1000.0, 1.5, 1e5),
            "fov": w.slider("fov [deg]", 60.0, 5.0, 150.0),
            "aspect": w.log_slider("aspect", 1.0, 0.25, 4.0),
            "rule": w.dropdown("warp", list(RULES.items()), "lispsm"),
            "eta": w.slider("η", 0.0, -1.0, 1.0, 0.01),
            "n_prime": w.text("n′ [world units]", "inf", "number > 0 or inf"),
            "res_image": w.widgets.IntText(value=1024, description="image res. [px]", style={"description_width": "initial"}),
        }

    # the module's functions, so that tests and notebooks can call them without a widget
    compute = staticmethod(compute)
    draw = staticmethod(draw)
    redraw = staticmethod(redraw)
