"""Face partitioning: one shadow map per chosen face of the view frustum.

Lloyd et al. 2006 §5.1 and Lloyd et al. 2007 §4.3, §6.1.3 and §6.5.  Along a light ray
the eye-beam width (the perspective factor δ̃_e of Lloyd 2007 eq. 30) is smallest where
the ray enters or exits the frustum (eq. 54), so each partition — the prism swept along
the light by one chosen face — only needs the error on its face.  For a directional
light eq. 54 chooses the exit faces (n̂·l̂ < 0) when the light is in front of the viewer
(v̂·l̂ > 0) and the entry faces (n̂·l̂ > 0) when it is behind; the near face is always
chosen and the far face never.  Faces seen edge-on (n̂·l̂ = 0) cover no area and get no
map, so an overhead light needs one map (the bottom face) and a generic direction 3–5.

Three variants (Lloyd 2007 §7's names):

``FP``
    The parameterization is fixed to the face (the PSM cube map of Kozlov 2004, §6.1.3):
    the near face is uniform; a side face gets F_p / F_lp of eqs. 75–78 in its own frame
    (Fig. 5: y along the centre line from the eye, y0 = n/cosθ, y1 = f/cosθ) with
    a = √(y0 y1) (LiSPSM's parameter, §7: "the LiSPSM parameter is used for warping") for
    P and a = 0 for LogP (App. A: "the optimal parameter is always a = 0").  The light
    image plane is the face (§4.4), so δ_b carries cos φ_lx, cos φ_ly (eqs. 55, 61–62).
``FPc``
    Coordinate-frame adjustment (§6.5, Lloyd 2006 §5.1): each side face is parameterized
    in the light image plane ⟂ l̂, in a warping frustum whose axis is the bisector of the
    face's two projected side edges (they meet at the eye's projection, τ apart), fitted
    to the face's vertices, with a = √(Y0 Y1) (P) or a = 0 (LogP) measured from the eye's
    projection along that axis.  Not a tight fit, so S rises; the shear falls.
``FPcs``
    FPc, and a side face whose τ exceeds τ0 is split along its bisector into two halves,
    each with its own adjusted frame; over [τ0, τ1] the halves' axes ease in from the
    whole face's bisector to their own (§6.5).  τ0 > 90° splits no face twice.  The
    paper does not give the τ0, τ1 it used: ours are parameters (``tau0``, ``tau1``).

Errors follow the vertex model of :mod:`aliasing.directional` (Lloyd 2007 §6.2: δ_l/δ_b
at the vertices, cos θ of δ_b omitted as in Table 3): at unit resolutions,
m_x = (texel width across) / (pixel width 2d tanθ), m_z likewise along, evaluated at the
face's vertices, which bound the partition (d is affine and m_x ∝ (Y + a)/d
linear-fractional, m_z ∝ (Y + a)²/d or (Y + a)/d convex on the face).  ``k > 1`` splits
each side face into k self-similar depth ranges (Lloyd 2006's FP+ZP+W, eq. 21).

Example
-------
>>> from aliasing.geometry import light_direction
>>> r = face_errors("fp", "logperspective", 1.0, 1000.0, 60.0, light_direction(90.0))
>>> round(float(r.S[0]), 3), int(r.maps[0])     # only the bottom face: ln(f/n)/(2 tanθ)
(5.982, 1)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import _validation as check
from .geometry import VIEW
from .view import View, split_view, theta_of, view_args

Array = NDArray[np.float64]
VARIANTS = ("fp", "fpc", "fpcs")
FACE_PARAMETERIZATIONS = ("uniform", "perspective", "logperspective")
SIDES = ("bottom", "top", "left", "right")
FACES = ("near", *SIDES)  # the far face is never chosen (eq. 54, see the module docstring)
TAU0, TAU1 = 120.0, 150.0  # [deg] our defaults; §6.5 only requires τ0 > 90°
_EDGE_ON = 1e-12
K_MAX = 1024  # most depth ranges per face (the bound of schemes.parse's k); bounds the arrays
# Largest far [world units]: eq. (97)'s (y + a)²(y1 − y0) is a cube of depths and overflows above ~5e102.
FAR_MAX = 1e100


@dataclass(frozen=True)
class FaceResult:
    """Per-map errors of a face-partitioned scheme over N directions (unit resolutions).

    ``M_x``, ``M_z`` have one column per map slot: the near face, then for each side face
    (bottom, top, left, right) — for FPcs, for each of its two halves (the second is
    unused unless the face is split) — its k depth ranges.  Unused slots hold 0.
    """

    M_x: Array  # (N, 1 + 4k), FPcs (N, 1 + 8k)
    M_z: Array  # same shape as M_x
    S: Array  # (N,)  Σ M_x M_z
    maps: Array  # (N,)  number of shadow maps the direction needs
    tau: Array  # (N, 4) angle between each side face's projected side edges [deg]; NaN if not chosen
    chosen: Array  # (N, 5) bool: near, bottom, top, left, right


def side_frames(fov: float | View) -> tuple[Array, Array, Array, Array]:
    """Each side face's unit normal (outward), centre line ŷ_f, across x̂_f and side edges.

    ``fov``: the full field of view [deg], or a :class:`~aliasing.View` (its θ is used as is).

    Lloyd 2007 Fig. 5 (bottom row): the origin is the eye, y runs along the face's centre
    line and z along its normal.  Returns ``normal (4, 3)``, ``centre (4, 3)``,
    ``across (4, 3)`` and the side edges ``(4, 2, 3)`` scaled to unit eye depth.
    """
    th = theta_of(fov if isinstance(fov, View) else check.scalar(fov, "fov"))
    c, s, t = np.cos(th), np.sin(th), np.tan(th)
    out = np.array([[0, -1, 0], [0, 1, 0], [-1, 0, 0], [1, 0, 0]], float)  # bottom, top, left, right
    normal = out * c - VIEW * s
    centre = out * s + VIEW * c
    across = np.cross(normal, centre)
    other = np.abs(np.array([[1, 0, 0], [1, 0, 0], [0, 1, 0], [0, 1, 0]], float))
    edges = np.stack([out * t - other * t + VIEW, out * t + other * t + VIEW], axis=1)
    return normal, centre, across, edges


def chosen_faces(light: ArrayLike, fov: float | View) -> Array:
    """Eq. 54's faces for directional lights ``(N, 3)`` (towards the light): ``(N, 5)`` bool.

    Exit faces (n̂·l̂ < 0) when v̂·l̂ ≥ 0, entry faces otherwise; faces seen edge-on are not
    chosen.  Order: near, bottom, top, left, right.
    """
    lv = _unit(light)
    normal, *_ = side_frames(fov)
    normals = np.vstack([-VIEW, normal])  # (5, 3)
    side = np.where(lv @ VIEW >= 0, 1.0, -1.0)[:, None]  # eq. (54): the sign of v̂·l̂ picks exit or entry
    return side * (lv @ normals.T) < -_EDGE_ON


@check.public
def partition_of(points: ArrayLike, near: float | View, far: float | None = None, fov: float | None = None, light: ArrayLike | None = None) -> NDArray[np.int_]:
    """The face partition (0 near, 1 bottom, 2 top, 3 left, 4 right) of eye-space points.

    A point belongs to the chosen face that its light ray reaches first while travelling
    towards smaller eye depth — the exit face along −l̂ when v̂·l̂ ≥ 0, else the entry face
    along +l̂ (eq. 54): the partition polyhedra are the faces swept along the light.  Points
    ``(..., 3)`` inside the frustum, one directional ``light`` ``(3,)``; returns ``(...)``.
    A :class:`~aliasing.View` may stand for near, far, fov: ``partition_of(points, view, light)``.

    Example
    -------
    >>> int(partition_of([0.0, 0.0, 500.0], 1.0, 1000.0, 60.0, [0.0, 1.0, 0.0]))  # overhead → bottom
    1
    """
    view, (light,) = view_args(near, far, fov, (light,), (None, None, None, None), ("light",))
    if view.shape != ():
        raise ValueError(f"near, far and fov must be scalars here, got shape {view.shape}")
    n = view.near
    pts = check.finite(points, "points")
    if pts.shape[-1:] != (3,):
        raise ValueError(f"points must have shape (..., 3), got {pts.shape}")
    lv = _unit(light)
    if lv.shape[0] != 1:
        raise ValueError("partition_of takes one light direction (3,)")
    travel = -lv[0] if lv[0] @ VIEW >= 0 else lv[0]  # eq. (54): towards the smaller eye depth
    normal, *_ = side_frames(view)
    normals = np.vstack([-VIEW, normal])  # (5, 3), the planes n̂·p = h with h = −n (near), 0 (sides)
    offset = np.array([-n, 0.0, 0.0, 0.0, 0.0])
    speed = normals @ travel
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (offset - pts @ normals.T) / speed
    t = np.where(speed > _EDGE_ON, np.maximum(t, 0.0), np.inf)
    return np.argmin(t, axis=-1)


@dataclass(frozen=True)
class FaceFrames:
    """Light-plane frames of the FPc / FPcs side-face maps (§6.5) for N directions.

    H = 1 (FPc) or 2 (FPcs: a face's two halves, the second used only when split), k depth
    ranges.  A map's frame: Y along ``axis`` from the eye's projection (the origin), X along
    ``across`` = l̂ × axis, centre of projection at Y = −a; its (half) face's vertices are
    the side edges ``edges`` at the eye depths ``depth[i]``, ``depth[i + 1]``.

    Attributes
    ----------
    axis, across : ndarray (N, 4, H, 3)
        Unit vectors ⟂ l̂ [eye space].
    edges : ndarray (N, 4, H, 2, 3)
        The (half) face's two side edges, scaled to unit eye depth.
    depth : ndarray (k + 1,)
        Eye depths bounding the k ranges [world units].
    Y, X : ndarray (N, 4, H, k, 4)
        The vertices' frame coordinates [world units] (vertex order: edge a, edge b at the
        range's near depth, edge b, edge a at its far depth).
    a : ndarray (N, 4, H, k)
        Centre-of-projection offset [world units]: √(Y0 Y1) (P), 0 (LogP), ∞ (uniform).
    y0, y1 : ndarray (N, 4, H, k)
        Min and max of Y over the vertices [world units].
    s_lo, s_hi : ndarray (N, 4, H, k)
        Range of X/(Y + a) over the vertices (of X for uniform): the map's s spans it.
    used : ndarray of bool (N, 4, H)
        The slot has a map: the face is chosen (eq. 54) and, for a second half, split.
    tau : ndarray (N, 4)
        Angle between each face's projected side edges [deg].
    """

    axis: Array
    across: Array
    edges: Array
    depth: Array
    Y: Array
    X: Array
    a: Array
    y0: Array
    y1: Array
    s_lo: Array
    s_hi: Array
    used: NDArray[np.bool_]
    tau: Array


def _arguments(variant: str, parameterization: str, near: float | View, far: float | None, fov: float | None, light: ArrayLike | None, k: int, tau0: float, tau1: float) -> tuple[str, str, View, Array, int]:
    var = check.choice(variant, "variant", VARIANTS)
    kind = check.choice(parameterization, "parameterization", FACE_PARAMETERIZATIONS)
    view, light = split_view(near, far, fov, light, (None, None, None, None))
    if view.shape != ():
        raise ValueError(f"near, far and fov must be scalars here, got shape {view.shape}")
    view.require_square("face partitions (Lloyd et al. 2007 §6.1.3: the four side faces of a square frustum)")
    if view.far > FAR_MAX:
        raise ValueError(f"far must be at most {FAR_MAX:g} [world units] here (the face closed forms cube depths), got {view.far:g}")
    k = check.whole(k, "k", 1, K_MAX, " (depth ranges per face)")
    if not 90.0 < check.scalar(tau0, "tau0") <= check.scalar(tau1, "tau1") <= 180.0:
        raise ValueError(f"tau0 and tau1 must satisfy 90 < tau0 <= tau1 <= 180 [deg], got {tau0!r}, {tau1!r}")
    return var, kind, view, _unit(light), int(k)


def face_frames(variant: str, parameterization: str, near: float | View, far: float | None = None, fov: float | None = None, light: ArrayLike | None = None, *, k: int = 1, tau0: float = TAU0, tau1: float = TAU1) -> FaceFrames:
    """The adjusted light-plane frames of FPc or FPcs side-face maps (module docstring).

    The one definition of the FPc / FPcs side maps: :func:`face_errors` evaluates its
    errors on them and :func:`aliasing.raster.map_set` rasterizes through them.

    Parameters
    ----------
    variant : {"fpc", "fpcs"}
        Coordinate-frame adjusted, or adjusted and split.
    parameterization, near, far, fov, light, k, tau0, tau1
        As in :func:`face_errors`.

    Returns
    -------
    FaceFrames

    Example
    -------
    >>> fr = face_frames("fpc", "perspective", 1.0, 100.0, 60.0, [0.0, 1.0, 0.0])   # overhead
    >>> fr.used[0, :, 0].tolist(), fr.axis[0, 0, 0].round(12).tolist()   # the bottom face, axis ∥ view
    ([True, False, False, False], [0.0, 0.0, 1.0])
    >>> float(fr.a[0, 0, 0, 0]) == float(np.sqrt(fr.y0[0, 0, 0, 0] * fr.y1[0, 0, 0, 0]))
    True
    """
    var = check.choice(variant, "variant", ("fpc", "fpcs"))
    _, kind, view, lv, k = _arguments(var, parameterization, near, far, fov, light, k, tau0, tau1)
    return _frames(var, kind, view, lv, k, float(tau0), float(tau1))


def _frames(var: str, kind: str, view: View, lv: Array, k: int, tau0: float, tau1: float) -> FaceFrames:
    """:func:`face_frames` on checked arguments."""
    n, f = view.near, view.far
    depth = n * (f / n) ** (np.arange(k + 1) / k)
    depth[-1] = f
    chosen = chosen_faces(lv, view)
    _, _, _, edges = side_frames(view)
    halves = 1 if var == "fpc" else 2
    N = lv.shape[0]
    axis = np.zeros((N, 4, halves, 3))
    bounds = np.zeros((N, 4, halves, 2, 3))
    used = np.zeros((N, 4, halves), bool)
    tau = np.full((N, 4), np.nan)
    for j in range(4):  # four faces; everything inside is vectorized over directions
        e0, e1 = _project(edges[j, 0], lv), _project(edges[j, 1], lv)  # (N, 3)
        tau[:, j] = np.degrees(np.arccos(np.clip(np.sum(_normalize(e0) * _normalize(e1), -1), -1, 1)))
        bis = _normalize(_normalize(e0) + _normalize(e1))
        split = np.zeros(N, bool) if var == "fpc" else tau[:, j] > tau0
        with np.errstate(divide="ignore", invalid="ignore"):  # an edge ∥ light: the face is edge-on, not chosen
            mid = edges[j, 0] / np.linalg.norm(e0, axis=-1)[:, None] + edges[j, 1] / np.linalg.norm(e1, axis=-1)[:, None]
            mid = mid / (mid @ VIEW)[:, None]  # the split line: the ray from the eye projecting onto the bisector
        whole = (np.broadcast_to(edges[j, 0], mid.shape), np.broadcast_to(edges[j, 1], mid.shape))
        ease = np.clip((tau[:, j] - tau0) / max(tau1 - tau0, 1e-300), 0.0, 1.0) if tau1 > tau0 else (tau[:, j] >= tau0).astype(float)
        for h, (a_edge, b_edge, toward) in enumerate([(whole[0], mid, e0), (mid, whole[1], e1)][:halves]):
            axis[:, j, h] = _eased_axis(bis, toward, np.where(split, ease * tau[:, j] / 4, 0.0))
            bounds[:, j, h, 0] = np.where(split[:, None], a_edge, whole[0])
            bounds[:, j, h, 1] = np.where(split[:, None], b_edge, whole[1])
            used[:, j, h] = chosen[:, 1 + j] & (split if h == 1 else True)
    across = np.cross(lv[:, None, None, :], axis)
    lo, hi = depth[:-1], depth[1:]
    vdepth = np.stack([lo, lo, hi, hi], axis=-1)  # (k, 4)
    ends = bounds[:, :, :, [0, 1, 1, 0]]  # (N, 4, H, 4, 3)
    verts = vdepth[None, None, None, :, :, None] * ends[:, :, :, None]  # (N, 4, H, k, 4, 3)
    Y = np.einsum("nfhkvj,nfhj->nfhkv", verts, axis)
    X = np.einsum("nfhkvj,nfhj->nfhkv", verts, across)
    y0, y1 = Y.min(axis=-1), Y.max(axis=-1)
    # faces not chosen (and so discarded) may have Y ≤ 0 here
    with np.errstate(invalid="ignore", divide="ignore"):
        a = _face_a(kind, y0, y1)
        q = X if kind == "uniform" else X / (Y + a[..., None])
    return FaceFrames(axis, across, bounds, depth, Y, X, a, y0, y1, q.min(axis=-1), q.max(axis=-1), used, tau)


def face_errors(variant: str, parameterization: str, near: float | View, far: float | None = None, fov: float | None = None, light: ArrayLike | None = None, *, k: int = 1, tau0: float = TAU0, tau1: float = TAU1) -> FaceResult:
    """M_x, M_z, S̄ and map counts of FP, FPc or FPcs for every light direction.

    Parameters
    ----------
    variant : {"fp", "fpc", "fpcs"}
        Face-fixed, coordinate-frame adjusted, or adjusted and split (module docstring).
    parameterization : {"uniform", "perspective", "logperspective"}
        On the side faces (Lloyd 2007 eqs. 74, 75–76, 78); the near face is uniform.
    near, far : float
        Eye near and far distances [world units], 0 < near < far; or a
        :class:`aliasing.View` in ``near``, followed by ``light``.
    fov : float
        Full field of view [deg] of the square frustum.
    light : array_like
        Unit vectors ``(N, 3)`` or ``(3,)`` towards the (directional) light.
    k : int
        Self-similar depth ranges per side face (Lloyd 2006 eqs. 15–16); 1 = none.
    tau0, tau1 : float
        FPcs split threshold and end of the ease-in [deg], 90 < tau0 <= tau1 <= 180.

    Returns
    -------
    FaceResult

    Example
    -------
    >>> r = face_errors("fp", "perspective", 1.0, 1000.0, 60.0, [0.0, 0.0, 1.0])
    >>> round(float(r.S[0]), 1), int(r.maps[0])   # four sides at (f/n − 1)/2, the near face 1
    (1999.0, 5)
    """
    var, kind, view, lv, k = _arguments(variant, parameterization, near, far, fov, light, k, tau0, tau1)
    n, f = view.near, view.far
    chosen = chosen_faces(lv, view)
    near_x, near_z = _near_face(lv)
    tan = view.tan_theta
    if var == "fp":
        normal, centre, across, edges = side_frames(view)
        depth = n * (f / n) ** (np.arange(k + 1) / k)
        depth[-1] = f
        mx = np.zeros((lv.shape[0], 4, 1, k))
        mz = np.zeros_like(mx)
        for j in range(4):
            mx[:, j, 0], mz[:, j, 0] = _fixed_side(lv, normal[j], centre[j], across[j], depth[:-1], depth[1:], view, kind)
        e0, e1 = (np.stack([_project(edges[j, i], lv) for j in range(4)], axis=1) for i in (0, 1))
        tau = np.degrees(np.arccos(np.clip(np.sum(_normalize(e0) * _normalize(e1), -1), -1, 1)))
        used = chosen[:, 1:, None]
    else:
        fr = _frames(var, kind, view, lv, k, float(tau0), float(tau1))
        mx, mz = _adjusted_side(fr, tan, kind)
        tau, used = fr.tau, fr.used
    mx, mz = np.where(used[..., None], mx, 0.0), np.where(used[..., None], mz, 0.0)
    M_x = np.concatenate([np.where(chosen[:, 0], near_x, 0.0)[:, None], mx.reshape(len(lv), -1)], axis=1)
    M_z = np.concatenate([np.where(chosen[:, 0], near_z, 0.0)[:, None], mz.reshape(len(lv), -1)], axis=1)
    halves = np.where(var == "fpcs", (tau > tau0) & chosen[:, 1:], False)
    maps = chosen[:, 0] + k * (chosen[:, 1:].sum(axis=1) + halves.sum(axis=1))
    return FaceResult(M_x, M_z, (M_x * M_z).sum(axis=1), maps.astype(int), np.where(chosen[:, 1:], tau, np.nan), chosen)


def _unit(light: ArrayLike) -> Array:
    lv = np.atleast_2d(check.finite(light, "light"))  # an infinite vector has no direction
    if lv.shape[-1] != 3 or lv.ndim != 2 or lv.shape[0] == 0:
        raise ValueError(f"light must be vectors of shape (N, 3) with N >= 1 or (3,), got shape {lv.shape}")
    if np.any(np.abs(lv).max(axis=-1) == 0):
        raise ValueError("light directions must be non-zero vectors")
    return check.unit_rows(lv)  # plain v/|v|, except for lengths that over- or underflow


def _normalize(v: Array) -> Array:
    """Unit vectors; zero vectors stay zero (a side edge parallel to the light, τ = 0)."""
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return np.divide(v, norm, out=np.zeros_like(v), where=norm > 0)


def _project(v: Array, lv: Array) -> Array:
    """Vectors ``(3,)`` projected onto the light image planes ⟂ l̂ ``(N, 3)``."""
    return v - (lv @ v)[:, None] * lv


def _cos_phi(lv: Array, across: Array, centre: Array, normal: Array) -> tuple[Array, Array]:
    """cos φ_lx, cos φ_ly: the light's angle to the face normal in its xz and yz planes (§4.4)."""
    lx, ly, lz = lv @ across, lv @ centre, np.abs(lv @ normal)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.nan_to_num(lz / np.hypot(lx, lz)), np.nan_to_num(lz / np.hypot(ly, lz))


def _near_face(lv: Array) -> tuple[Array, Array]:
    """Uniform map fixed to the near face: m = cos φ_l in each direction (eqs. 55, 58)."""
    return _cos_phi(lv, np.array([1.0, 0, 0]), np.array([0, 1.0, 0]), -VIEW)


def _face_a(kind: str, y0: Array, y1: Array) -> Array:
    """a of the side-face parameterization: ∞ (uniform), √(y0 y1) (P, LiSPSM), 0 (LogP)."""
    if kind == "uniform":
        return np.full_like(y0, np.inf)
    return np.sqrt(y0 * y1) if kind == "perspective" else np.zeros_like(y0)


def _widths(kind: str, y: Array, y0: Array, y1: Array, a: Array) -> tuple[Array, Array]:
    """Texel widths along y at y, per unit t, and the across factor (y + a)/(y1 + a).

    Eqs. 96–97 and 102 (Lloyd 2007): spacings of F_p,s, F_p,t and F_log,t (= F_lp,t).
    """
    if kind == "uniform":
        return np.broadcast_to(y1 - y0, np.broadcast(y, y0).shape), np.ones(np.broadcast(y, y1).shape)
    if kind == "perspective":
        along = (y + a) ** 2 * (y1 - y0) / ((y0 + a) * (y1 + a))  # eq. (97)
    else:
        along = np.log((y1 + a) / (y0 + a)) * (y + a)  # eq. (102)
    return along, (y + a) / (y1 + a)  # eq. (96)


def _fixed_side(lv: Array, normal: Array, centre: Array, across: Array, lo: Array, hi: Array, view: View, kind: str) -> tuple[Array, Array]:
    """FP: F_p / F_lp / F_un fixed to a side face, M_x and M_z per depth range ``(N, k)``."""
    cos_t = view.cos_theta
    cx, cy = _cos_phi(lv, across, normal=normal, centre=centre)
    y0, y1 = lo / cos_t, hi / cos_t  # Fig. 5: the face's ends along its centre line
    a = _face_a(kind, y0, y1)
    out_x, out_z = [], []
    for y in (y0, y1):  # δ_l/δ_b is monotone or convex in y: its maxima are at the ends
        along, frac = _widths(kind, y, y0, y1, a)
        d = y * cos_t  # eye depth of the points at y (eq. 59)
        out_x.append(frac * hi / d)  # texel across W(y1)(y + a)/(y1 + a), W(y1) = 2 hi tanθ; pixel 2d tanθ
        out_z.append(along / d)  # texel along the face over the pixel 2d tanθ (the 2 tanθ below)
    mx = np.maximum(*out_x)[None] * cx[:, None]
    mz = np.maximum(*out_z)[None] * cy[:, None] / (2 * view.tan_theta)
    return mx, mz


def _eased_axis(bis: Array, toward: Array, angle: Array) -> Array:
    """The bisector turned by ``angle`` [deg] towards the projected edge ``toward``."""
    perp = _normalize(toward - np.sum(toward * bis, -1, keepdims=True) * bis)
    r = np.radians(angle)[:, None]
    return np.cos(r) * bis + np.sin(r) * perp


def _adjusted_side(fr: FaceFrames, tan: float, kind: str) -> tuple[Array, Array]:
    """FPc: M_x, M_z ``(N, 4, H, k)`` of the warping frusta of :func:`face_frames`.

    At unit resolutions, per vertex: the texel across, (Y + a)·(s_hi − s_lo) (eq. 3 on the
    face's own frustum; s_hi − s_lo for uniform), and along (eqs. 96–97, 102), over the
    pixel width 2 d tanθ at the vertex's eye depth d; the maxima over the vertices.
    """
    lo, hi = fr.depth[:-1], fr.depth[1:]
    w_i = 2 * tan * np.stack([lo, lo, hi, hi], axis=-1)  # (k, 4)
    with np.errstate(invalid="ignore", divide="ignore"):
        a, y0, y1 = fr.a[..., None], fr.y0[..., None], fr.y1[..., None]
        along, _ = _widths(kind, fr.Y, y0, y1, a)
        span = (fr.s_hi - fr.s_lo)[..., None]
        w_x = span * np.ones_like(fr.Y) if kind == "uniform" else (fr.Y + a) * span
    return (w_x / w_i).max(axis=-1), (along / w_i).max(axis=-1)
