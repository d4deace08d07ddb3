"""Face partitioning for one light direction: chosen faces, frames and per-face S (FP, FPc, FPcs).

Lloyd et al. 2007 eq. 54 chooses the faces of the view frustum whose prisms along the light
each get a map (exit faces for a light in front, entry faces behind; the near face always);
§6.1.3 (FP) fixes each side map's frame to its face, §6.5 adjusts it to the light image
plane (FPc) and splits wide faces (FPcs).  Numbers from :func:`aliasing.faces.face_errors`
and :func:`aliasing.faces.face_frames`; the picture is the frustum seen from the light.
No aspect control: face partitions are built on the four side faces of a square frustum (§6.1.3), so :mod:`aliasing.faces` refuses aspect ≠ 1.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from .. import faces, geometry
from . import widget as w

FACE_NAMES = ("near", "bottom", "top", "left", "right")
#: Corner indices (:func:`aliasing.geometry.frustum_vertices`) of each face, in FACE_NAMES order.
FACE_CORNERS = ((0, 1, 2, 3), (0, 1, 5, 4), (3, 2, 6, 7), (0, 3, 7, 4), (1, 2, 6, 5))
PARAMETERIZATIONS = {"P": "perspective", "LogP": "logperspective", "Standard": "uniform"}


def slot_labels(variant: str, k: int = 1) -> list[str]:
    """Names of :class:`aliasing.faces.FaceResult`'s map slots (near, then side faces[, halves], ranges)."""
    halves = ("/1", "/2") if variant == "fpcs" else ("",)
    ranges = [f" z{i + 1}" for i in range(k)] if k > 1 else [""]
    return ["near"] + [f"{side}{h}{r}" for side in faces.SIDES for h in halves for r in ranges]


def light_plane(light: np.ndarray) -> np.ndarray:
    """Two unit vectors (2, 3) spanning the plane ⟂ the light (the light's image plane)."""
    helper = np.array([0.0, 0.0, 1.0]) if abs(light[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    e1 = np.cross(helper, light)
    e1 /= np.linalg.norm(e1)
    return np.stack([e1, np.cross(light, e1)])


def compute(variant: str, parameterization: str, f_over_n: float, fov: float, gamma: float, azimuth: float) -> dict[str, Any]:
    """Chosen faces, per-slot M_x, M_z, S and the frames of FPc/FPcs for one direction (near = 1).

    Returns
    -------
    dict
        ``light``, ``chosen`` (5 bools, :data:`FACE_NAMES` order), ``labels``, ``M_x``,
        ``M_z``, ``S_i`` (per slot), ``S``, ``maps``, ``tau`` [deg], ``corners`` (8, 2) the
        frustum seen from the light, ``axes`` (list of (label, 2-vector, length)) for FPc/FPcs.

    Example
    -------
    >>> d = compute("fp", "logperspective", 1000.0, 60.0, 90.0, 0.0)
    >>> d["chosen"].tolist(), round(d["S"], 3)    # overhead: the bottom face only
    ([False, True, False, False, False], 5.982)
    """
    near, far = 1.0, float(f_over_n)
    lv = geometry.light_direction(gamma, azimuth)
    r = faces.face_errors(variant, parameterization, near, far, fov, lv)
    plane = light_plane(lv)
    corners = geometry.frustum_vertices(near, far, fov) @ plane.T
    axes = []
    if variant in ("fpc", "fpcs"):
        fr = faces.face_frames(variant, parameterization, near, far, fov, lv)
        for f, side in enumerate(faces.SIDES):
            for h in range(fr.used.shape[-1]):
                if fr.used[0, f, h]:
                    axes.append((f"{side}{'/' + str(h + 1) if variant == 'fpcs' else ''}", fr.axis[0, f, h] @ plane.T, float(fr.y1[0, f, h].max())))
    return {
        "variant": variant, "parameterization": parameterization, "f_over_n": far, "fov": float(fov), "gamma": float(gamma),
        "azimuth": float(azimuth), "light": lv, "chosen": r.chosen[0], "labels": slot_labels(variant), "M_x": r.M_x[0],
        "M_z": r.M_z[0], "S_i": r.M_x[0] * r.M_z[0], "S": float(r.S[0]), "maps": int(r.maps[0]), "tau": r.tau[0],
        "corners": corners, "axes": axes,
    }


def draw(fig: Figure, d: dict[str, Any]) -> dict:
    """The frustum from the light with the chosen faces filled and frames drawn; per-slot S.

    Returns the artists for :func:`redraw`.
    """
    a, b = fig.subplots(1, 2)
    polygons = []
    for i, name in enumerate(FACE_NAMES):
        chosen = bool(d["chosen"][i])
        polygons.append(a.add_patch(Polygon(np.zeros((4, 2)), closed=True, fc=f"C{i}" if chosen else "none", alpha=0.35 if chosen else 1.0,
                                            ec=f"C{i}" if chosen else "0.6", lw=1.5 if chosen else 0.6, label=name if chosen else None)))
    far, = a.plot([], [], color="0.3", lw=0.8, ls="--")
    arrows = [(a.annotate("", xy=(0, 0), xytext=(0, 0), arrowprops={"arrowstyle": "->", "color": "k", "lw": 1}, annotation_clip=False),
               a.text(0, 0, label, fontsize=7)) for label, _, _ in d["axes"]]
    a.plot(0, 0, "k.", ms=6)
    a.set(aspect="equal", xticks=[], yticks=[], title="seen from the light (arrows: map axes)")
    a.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)  # beside the drawing: no arrow label under it
    used = d["M_x"] > 0
    x = np.arange(used.sum())
    bars = b.bar(x, d["S_i"][used], color="C7")
    b.set_xticks(x, [lab for lab, u in zip(d["labels"], used) if u], fontsize=8)
    b.set(ylabel="S = M_x·M_z (unit res.)")
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.2, top=0.84, wspace=0.45)
    artists = {"a": a, "b": b, "polygons": polygons, "far": far, "arrows": arrows, "bars": bars, "used": used,
               "chosen": d["chosen"].copy(), "labels": [lab for lab, _, _ in d["axes"]], "suptitle": fig.suptitle("", fontsize=10)}
    redraw(artists, d)
    return artists


def redraw(artists: dict, d: dict[str, Any]) -> bool:
    """New data into :func:`draw`'s artists; False (draw anew) when the chosen faces, maps or frames change."""
    used = d["M_x"] > 0
    if (not np.array_equal(used, artists["used"]) or not np.array_equal(d["chosen"], artists["chosen"])
            or [lab for lab, _, _ in d["axes"]] != artists["labels"]):
        return False
    a, b, c = artists["a"], artists["b"], d["corners"]
    for poly, idx in zip(artists["polygons"], FACE_CORNERS):
        poly.set_xy(c[list(idx)])
    artists["far"].set_data(*c[[4, 5, 6, 7, 4]].T)
    tips = [axis * length * 0.85 for _, axis, length in d["axes"]]
    for (arrow, text), tip in zip(artists["arrows"], tips):
        arrow.xy = tuple(tip)
        text.set_position(tuple(tip * 1.02))
        text.set_ha("left" if tip[0] >= 0 else "right")  # the label beyond the tip, away from the other arrows
        text.set_va("bottom" if tip[1] >= 0 else "top")
    pts = np.vstack([c, *tips]) if tips else c  # the arrows may reach past the frustum's outline: keep them inside
    span = np.ptp(pts, axis=0).max()
    a.set_xlim(pts[:, 0].min() - 0.12 * span, pts[:, 0].max() + 0.12 * span)  # room for the labels at the tips
    a.set_ylim(pts[:, 1].min() - 0.12 * span, pts[:, 1].max() + 0.12 * span)
    for rect, height in zip(artists["bars"], d["S_i"][used]):
        rect.set_height(height)
    b.set_ylim(0.0, d["S_i"][used].max() * 1.08)
    taus = ", ".join(f"{n} {t:.0f}°" for n, t in zip(faces.SIDES, d["tau"]) if np.isfinite(t))
    b.set_title(f"S̄ = {d['S']:.4g} over {d['maps']} map(s)", fontsize=9)
    b.set_xlabel(f"τ: {taus or '—'}", fontsize=8)  # one angle per side face: a line of its own, never past the edge
    artists["suptitle"].set_text(f"{d['variant'].upper()}+{d['parameterization']}, γ = {d['gamma']:g}°, azimuth = {d['azimuth']:g}°, "
                                 f"f/n = {d['f_over_n']:.4g}, fov = {d['fov']:g}°")
    return True


class FacesExplorer(w.Explorer):
    """The face partition for a light direction; controls variant, side parameterization, f/n, fov, γ, azimuth."""

    title = "Face partitioning (Lloyd et al. 2007 eq. 54, §6.1.3, §6.5)"
    figsize = (9.5, 3.8)

    def make_controls(self) -> dict:
        return {
            "variant": w.dropdown("variant", [("FP", "fp"), ("FPc", "fpc"), ("FPcs", "fpcs")], "fpc"),
            "parameterization": w.dropdown("side faces", list(PARAMETERIZATIONS.items()), "logperspective"),
            "f_over_n": w.log_slider("f/n", 100.0, 1.5, 1e5),
            "fov": w.slider("fov [deg]", 60.0, 5.0, 150.0),
            "gamma": w.slider("γ [deg]", 60.0, 0.0, 180.0),
            "azimuth": w.slider("azimuth [deg]", 30.0, -180.0, 180.0),
        }

    # the module's functions, so that tests and notebooks can call them without a widget
    compute = staticmethod(compute)
    draw = staticmethod(draw)
    redraw = staticmethod(redraw)
