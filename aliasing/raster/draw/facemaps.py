"""Face-partition maps (Lloyd 2007 §6.1.3, §6.5) and the map set of any scheme for one light.

:func:`frame_map` builds an FPc / FPcs side face's adjusted frame, :func:`fixed_face_map` an
FP side face's map in the face's own plane, :func:`near_face_map` the near face's uniform map, and :func:`map_set` the maps of any scheme with which map shades
which point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ... import directional, faces, geometry, schemes
from .lightmap import LightMap, _light_maps, _unit_vector
from ...view import View, view_args

Array = NDArray[np.float64]


def frame_map(light: ArrayLike, axis: ArrayLike, y0: float, y1: float, a: float, s_lo: float, s_hi: float, parameterization: str) -> LightMap:
    """The map of a warping frustum with an explicit light-plane frame (FPc side faces).

    Y is measured along ``axis`` (⟂ the light) from the origin's projection, X along
    l̂ × axis; the map spans Y ∈ [y0, y1] and its centre of projection is at Y = −a, so
    n′ = y0 + a.  s ∝ X/(Y + a) over [s_lo, s_hi] (X itself when uniform); t is the
    perspective warp of that frustum (Lloyd 2006 eq. 6) or, for ``logperspective``,
    ln((Y + a)/(y0 + a))/ln((y1 + a)/(y0 + a)) (Lloyd 2007 eqs. 77–78), or uniform.

    Parameters
    ----------
    light : array_like, shape (3,)
        Direction towards the light (any length > 0).
    axis : array_like, shape (3,)
        The frame's Y direction, non-zero and ⟂ ``light`` (made unit here).
    y0, y1 : float
        The map's near and far edges along Y [world units], y0 + a > 0, y1 > y0.
    a : float
        Offset of the centre of projection [world units], ≥ 0; ``inf`` for uniform.
    s_lo, s_hi : float
        Range of X/(Y + a) (of X if uniform) the map's s spans, s_lo < s_hi.
    parameterization : {"uniform", "perspective", "logperspective"}

    Returns
    -------
    LightMap

    Example
    -------
    >>> fr = faces.face_frames("fpc", "logperspective", 1.0, 100.0, 60.0, [0.0, 1.0, 0.0])
    >>> i = (0, 0, 0, 0)   # first direction, bottom face, whole face, depth range 0
    >>> lm = frame_map([0.0, 1.0, 0.0], fr.axis[i[:3]], fr.y0[i], fr.y1[i], fr.a[i], fr.s_lo[i], fr.s_hi[i], "logperspective")
    >>> s, t, _, _ = lm.coordinates(geometry.frustum_vertices(1.0, 100.0, 60.0)[[0, 1, 4, 5]])   # the bottom face's corners
    >>> np.round(s, 12).tolist(), np.round(t, 12).tolist()
    ([0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0])
    """
    kind = check.choice(parameterization, "parameterization", faces.FACE_PARAMETERIZATIONS)
    lv = _unit_vector(light, "light")
    ax = check.finite(axis, "axis")
    if ax.shape != (3,) or not np.abs(ax).max() > 0 or abs(check.unit_rows(ax) @ lv) > 1e-9:
        raise ValueError(f"axis must be a non-zero vector (3,) perpendicular to light, got {check._repr(ax)}")
    ax = check.unit_rows(ax)  # plain ax/|ax| unless |ax| over- or underflows
    lo, hi, lo_s, hi_s = (check.scalar(v, n) for v, n in ((y0, "y0"), (y1, "y1"), (s_lo, "s_lo"), (s_hi, "s_hi")))
    off = check.scalar(a, "a")
    if not np.isfinite(lo) or not hi > lo or not np.isfinite(hi) or not np.isfinite(hi - lo):
        raise ValueError(f"y0 and y1 must be finite with y1 > y0 [world units], got {lo!r}, {hi!r}")
    if not lo_s < hi_s or not np.isfinite(hi_s - lo_s):
        raise ValueError(f"s_lo and s_hi must be finite with s_lo < s_hi, got {lo_s!r}, {hi_s!r}")
    if kind == "uniform":
        npr = np.inf
    else:
        if not (off >= 0 and np.isfinite(off)) or not lo + off > 0:
            raise ValueError(f"a must be in [0, inf) with y0 + a > 0 (centre of projection behind the map) [world units], got a = {off!r}, y0 = {lo!r}")
        npr = lo + off
    scale = 1.0 if kind == "uniform" else npr
    wf = directional.WarpingFrustum(n_prime=np.array([[npr]]), depth=np.array([[hi - lo]]), x_lo=np.array([[scale * lo_s]]), x_hi=np.array([[scale * hi_s]]))
    return LightMap(np.stack([np.cross(lv, ax), lv, ax]), lo, wf, kind, float(npr))


def fixed_face_map(near: float | View, far: float | None = None, fov: float | None = None, light: ArrayLike | None = None, face: str | None = None, parameterization: str | None = None) -> LightMap:
    """A side face's face-fixed map (FP, Lloyd 2007 §6.1.3, Fig. 5), as a light-plane map.

    The map's image plane is the face itself: a point's light ray is followed to the face's
    plane (an oblique projection along l̂) and parameterized in the face's own frame, y along
    its centre line from the eye over [y0, y1] = [n, f]/cosθ, x across it.  s ∝ x/(y + a)
    over the face's width at y1 and t is F_p along y with a = √(y0 y1) for
    ``perspective`` (eqs. 75–76; LiSPSM's parameter, §7), F_lp with a = 0 for
    ``logperspective`` (eqs. 77–78; App. A), or uniform — as :func:`aliasing.faces.face_errors`
    ("fp") models it.

    As a :class:`~aliasing.raster.LightMap`: light-plane axes x_L ∝ l̂ × ŷ_f and
    z_L ∝ x̂_f × l̂ (unit, ⟂ l̂, not orthogonal), so X = x cos φ_lx and Y = y cos φ_ly for the
    ray meeting the face at (x, y) — the light-beam widths of eqs. 55, 61–62 — and the
    warping frustum of (x, y) scaled by those factors.

    Parameters
    ----------
    near, far : float
        The face's eye-depth range [world units], 0 < near < far (a depth range's ends for
        ``FP+ZP<k>``).  Or a :class:`~aliasing.View` in ``near``:
        ``fixed_face_map(view, light, face, parameterization)``.
    fov : float
        Full field of view [deg].
    light : array_like, shape (3,)
        Direction towards the light; not in the face's plane (the face is then edge-on).
    face : {"bottom", "top", "left", "right"}
    parameterization : {"uniform", "perspective", "logperspective"}

    Example
    -------
    >>> lm = fixed_face_map(1.0, 100.0, 60.0, [0.0, 1.0, 0.0], "bottom", "logperspective")
    >>> s, t, _, _ = lm.coordinates(geometry.frustum_vertices(1.0, 100.0, 60.0)[[0, 1, 4, 5]])   # the face's corners
    >>> np.round(s, 12).tolist(), np.round(t, 12).tolist()   # LogP's a = 0: s spans the face's wedge at every y
    ([1.0, 0.0, 1.0, 0.0], [0.0, 0.0, 1.0, 1.0])

    (s runs along x̂_f = n̂ × ŷ_f, which is −x on the bottom face.)
    """
    view, (light, face, parameterization) = view_args(near, far, fov, (light, face, parameterization), (None,) * 6, ("light", "face", "parameterization"))
    if view.shape != ():
        raise ValueError(f"near, far and fov must be scalars here, got shape {view.shape}")
    j = faces.SIDES.index(check.choice(face, "face", faces.SIDES))
    kind = check.choice(parameterization, "parameterization", faces.FACE_PARAMETERIZATIONS)
    return _fixed_face_map(view, _unit_vector(light, "light"), j, kind)


def _fixed_face_map(view: View, lv: Array, j: int, kind: str) -> LightMap:
    """:func:`fixed_face_map` on a validated View, unit light ``lv`` (3,), face index and parameterization."""
    n, f = view.near, view.far
    face = faces.SIDES[j]
    normal, centre, across, _ = faces.side_frames(view)
    if not abs(lv @ normal[j]) > 1e-12:  # the edge-on test of aliasing.faces.chosen_faces
        raise ValueError(f"light must not lie in the {face} face's plane (the face is then edge-on, no map), got {lv!r}")
    x_l, z_l = np.cross(lv, centre[j]), np.cross(across[j], lv)
    x_l, z_l = x_l / np.linalg.norm(x_l), z_l / np.linalg.norm(z_l)
    x_l, z_l = x_l * np.sign(x_l @ across[j]), z_l * np.sign(z_l @ centre[j])  # s grows with x, t with y
    cx, cy = float(x_l @ across[j]), float(z_l @ centre[j])  # cos φ_lx, cos φ_ly (eqs. 55, 61–62)
    th = view.theta
    y0, y1 = n / np.cos(th), f / np.cos(th)  # Fig. 5: the face's ends along its centre line
    half = y1 * np.sin(th)  # the face's half-width at y1
    if kind == "uniform":
        a, npr, x_hi = np.inf, np.inf, cx * half
    else:
        a = np.sqrt(y0 * y1) if kind == "perspective" else 0.0  # eq. (76): LiSPSM's a; App. A: a = 0 for LogP
        npr = cy * (y0 + a)  # the centre of projection at y = −a, in light-plane units
        with np.errstate(over="ignore"):
            x_hi = npr * cx * half / (cy * (y1 + a))  # n′·max X/(Y + a cos φ_ly) over the face
    if not np.isfinite(x_hi):
        raise ValueError(f"near and far give a face map whose extent exceeds 1.8e308 [world units], got near={n:g}, far={f:g}")
    wf = directional.WarpingFrustum(n_prime=np.array([[npr]]), depth=np.array([[cy * (y1 - y0)]]), x_lo=np.array([[-x_hi]]), x_hi=np.array([[x_hi]]))
    return LightMap(np.stack([x_l, lv, z_l]), cy * y0, wf, kind, float(npr))


def near_face_map(near: float | View, fov: float | None = None, light: ArrayLike | None = None) -> LightMap:
    """The near face's uniform map (face-fixed, Lloyd 2007 §6.1.3), as a light-plane map.

    A point's (s, t) are those of the point where its light ray meets the near plane, in
    the near face's rectangle: an affine map of the light plane, with light-plane axes
    x_L ∝ l̂ × ŷ (⟂ the face's t-edges) and z_L ∝ x̂ × l̂ (⟂ its s-edges).  The light-beam
    widths along them, 2n tanθ·cos φ_lx and 2n tanθ·cos φ_ly per unit s and t, are the
    analytic model's (m = cos φ_l at the near face, eqs. 55, 58).

    Parameters
    ----------
    near : float
        Eye near distance [world units], > 0; or a :class:`~aliasing.View` in ``near``
        (``near_face_map(view, light)``; its far distance is not used).
    fov : float
        Full field of view [deg].
    light : array_like, shape (3,)
        Direction towards the light; not parallel to the near plane (the face is then edge-on).

    Example
    -------
    >>> lm = near_face_map(1.0, 90.0, [0.3, 0.4, -0.8])
    >>> s, t, _, _ = lm.coordinates([[-1.0, -1.0, 1.0], [1.0, 1.0, 1.0], [0.0, 0.0, 1.0]])
    >>> np.round(s, 12).tolist(), np.round(t, 12).tolist()
    ([0.0, 1.0, 0.5], [0.0, 1.0, 0.5])
    """
    if isinstance(near, View):
        if fov is not None and light is not None:
            raise ValueError("with a View, pass light once (near_face_map(view, light)), not fov")
        view, light = near, fov if light is None else light
        if view.shape != ():
            raise ValueError(f"near and fov must be scalars here, got shape {view.shape}")
    else:
        if fov is None:
            raise ValueError("fov required (or a View in place of near)")
        n = float(check.positive(check.scalar(near, "near"), "near"))
        view = View(n, 2 * n, check.scalar(fov, "fov"))  # the far distance is not used
    if light is None:
        raise ValueError("light required")
    return _near_face_map(view, _unit_vector(light, "light"))


def _near_face_map(view: View, lv: Array) -> LightMap:
    """:func:`near_face_map` on a validated View and a unit light (3,)."""
    n = view.near
    h = n * view.tan_theta
    if abs(lv[2]) < 1e-9:
        raise ValueError(f"light must not be parallel to the near plane (the near face is then edge-on, no map), got {lv!r}")
    x_l = np.cross(lv, [0.0, 1.0, 0.0])
    z_l = np.cross([1.0, 0.0, 0.0], lv)
    x_l, z_l = x_l / np.linalg.norm(x_l), z_l / np.linalg.norm(z_l)
    x_l, z_l = x_l * np.sign(x_l[0]), z_l * np.sign(z_l[1])  # s grows with eye x, t with eye y
    corners = np.array([[-h, -h, n], [h, h, n]])
    x, y = corners @ x_l, corners @ z_l
    wf = directional.WarpingFrustum(n_prime=np.array([[np.inf]]), depth=np.array([[y[1] - y[0]]]), x_lo=np.array([[x[0]]]), x_hi=np.array([[x[1]]]))
    return LightMap(np.stack([x_l, lv, z_l]), float(y[0]), wf, "uniform", float("inf"))


@dataclass(frozen=True)
class MapSet:
    """The shadow maps of a scheme for one light, and which map shades which point.

    Attributes
    ----------
    maps : list of LightMap
        One per map the light needs (z-partitions in depth order; for face partitions the
        near face's map first if chosen, then the side faces' in :mod:`aliasing.faces`'
        slot order).
    slots : ndarray of int (len(maps),)
        Each map's column in :func:`aliasing.schemes.evaluate`'s ``M_x``, ``M_z``.
    edges : ndarray (k + 1,)
        Depth split points: z-partitions' C_0 … C_k, or a face's k depth ranges
        (eye depth of the face point a light ray meets) [world units].
    faces : str
        "" (z-partitions), "fp", "fpc" or "fpcs".
    view : View
        The view frustum (``near``, ``far`` [world units] and ``fov`` [deg] are its fields,
        also read as the set's attributes).
    light : ndarray (3,)
        Unit vector towards the light.
    frames : FaceFrames or None
        The side faces' frames (:func:`aliasing.faces.face_frames`, for this one light) of
        FPc / FPcs partitions; None for z-partitions and face-fixed FP.
    """

    maps: list[LightMap]
    slots: NDArray[np.int_]
    edges: Array
    faces: str
    view: View
    light: Array
    frames: faces.FaceFrames | None = None

    @property
    def near(self) -> float:
        """Eye near distance [world units]."""
        return self.view.near

    @property
    def far(self) -> float:
        """Eye far distance [world units]."""
        return self.view.far

    @property
    def fov(self) -> float:
        """Full field of view [deg]."""
        return self.view.fov

    def assign(self, points: ArrayLike) -> NDArray[np.int_]:
        """Index into ``maps`` of the map shading each eye-space point ``(..., 3)`` in the frustum.

        z-partitions: the partition holding the point's eye depth.  Face partitions: the
        chosen face its light ray meets (:func:`aliasing.faces.partition_of`), for FPcs the
        half of that face, and the depth range of the point where the ray meets it.
        """
        p = check.as_float_array(points, "points")
        if p.shape[-1:] != (3,):
            raise ValueError(f"points must have shape (..., 3), got {p.shape}")
        k = self.edges.size - 1
        if not self.faces:
            return np.clip(np.searchsorted(self.edges, p[..., 2], side="right") - 1, 0, k - 1)
        face = faces.partition_of(p, self.view, self.light)
        fr = self.frames
        if fr is None and self.faces != "fp":
            raise ValueError(f"frames must be the face frames of the {self.faces} partitions (see map_set), got None")
        halves = 1 if fr is None else fr.used.shape[2]
        normal, *_ = faces.side_frames(self.view)
        lv = self.light
        travel = -lv if lv[2] >= 0 else lv  # eq. (54), as in partition_of
        j = np.clip(face - 1, 0, 3)
        nj = normal[j]
        with np.errstate(divide="ignore", invalid="ignore"):
            hit = p - ((p * nj).sum(-1) / (nj @ travel))[..., None] * travel  # on the side face's plane
        rng = np.clip(np.searchsorted(self.edges, hit[..., 2], side="right") - 1, 0, k - 1)
        half = np.zeros(face.shape, int)
        if halves == 2:  # FPcs: the side of the split ray (half 0's second edge) holding the point
            split = fr.edges[0, j, 0, 1]  # (..., 3)
            first = fr.edges[0, j, 0, 0]
            side = np.cross(split, p) @ lv
            ref = np.cross(split, first) @ lv
            half = np.where(fr.used[0, j, 1] & (side * ref < 0), 1, 0)
        slot = np.where(face == 0, 0, 1 + (j * halves + half) * k + rng)
        lookup = np.full(1 + 4 * halves * k, -1)
        lookup[self.slots] = np.arange(len(self.maps))
        return lookup[slot]


@check.public
def map_set(near: float | View, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, **options: ArrayLike) -> MapSet:
    """The maps of any scheme for one light: single, z-partitioned or face-partitioned.

    ``ZP<k>+…`` and single-map schemes: :func:`light_maps`.  ``FPc+P|LogP|Standard`` and
    ``FPcs+…`` (options ``tau0``, ``tau1``; also with ``+ZP<k>``): the near face's uniform
    map (:func:`near_face_map`) if chosen and each used side-face slot's adjusted frame
    (:func:`aliasing.faces.face_frames`, through :func:`frame_map`) — the same frames
    :func:`aliasing.faces.face_errors` evaluates.  Face-fixed ``FP+…`` (also ``FP+ZP<k>+…``):
    the near face's map and each chosen side face's map in its own plane
    (:func:`fixed_face_map`), per depth range.

    Parameters
    ----------
    near, far, fov, light
        The view frustum (0 < near < far [world units], full field of view [deg]) and one
        light direction, as for :func:`light_map`; or ``map_set(view, light, scheme)`` with a
        :class:`~aliasing.View`.
    scheme : str
        Any scheme of :mod:`aliasing.schemes`.
    **options
        Warping-rule options, or ``tau0``, ``tau1`` for face partitions.

    Example
    -------
    >>> ms = map_set(1.0, 100.0, 60.0, "gamma:60@azimuth:30", "FPc+LogP")
    >>> len(ms.maps), ms.slots.tolist()
    (3, [0, 1, 3])
    >>> ms.assign([[0.0, -20.0, 50.0], [-25.0, 20.0, 50.0], [0.0, 0.0, 1.0]]).tolist()   # bottom, left, near
    [1, 2, 0]
    """
    view, (light, scheme) = view_args(near, far, fov, (light, scheme), (None, None, None, None, "Standard"))
    if view.shape != ():
        raise ValueError(f"map_set takes one view: near, far and fov must be scalars, got shape {view.shape}")
    check.instance(scheme, "scheme", (str, schemes.Scheme))
    sch = schemes.parse(scheme) if isinstance(scheme, str) else scheme
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    return _map_set(view, lv, sch, options)


def _map_set(view: View, lv: Array, sch: schemes.Scheme, options: dict) -> MapSet:
    """:func:`map_set` on a validated View, one light ``lv`` (1, 3) and a parsed scheme."""
    n, f = view.near, view.far
    if not sch.faces:
        # light_maps normalizes its light once more (geometry.lights is not idempotent to the last bit)
        maps, edges = _light_maps(view, geometry.lights(lv), schemes.parse(sch.name), options)
        return MapSet(maps, np.arange(len(maps)), edges, "", view, lv[0])
    view.require_square("face partitions (Lloyd et al. 2007 §6.1.3: the four side faces of a square frustum)")  # as faces.face_errors says it
    unknown = set(options) - {"tau0", "tau1"}
    if unknown:
        raise ValueError(f"unknown options for {sch.name}: {', '.join(sorted(unknown))}; face partitions take tau0, tau1")
    maps, slots = [], []
    chosen = faces.chosen_faces(lv, view)[0]
    if chosen[0]:
        maps.append(_near_face_map(view, _unit_vector(lv[0], "light")))
        slots.append(0)
    k = sch.k
    if sch.faces == "fp":
        faces.face_errors("fp", sch.parameterization, view, lv, k=k, **{key: float(v) for key, v in options.items()})  # validates tau0, tau1
        depth = n * (f / n) ** (np.arange(k + 1) / k)  # the depth ranges of face_errors
        depth[-1] = f
        kind = check.choice(sch.parameterization, "parameterization", faces.FACE_PARAMETERIZATIONS)
        for j in range(len(faces.SIDES)):
            if chosen[1 + j]:
                for i in range(k):
                    maps.append(_fixed_face_map(view.between(depth[i], depth[i + 1]), _unit_vector(lv[0], "light"), j, kind))
                    slots.append(1 + j * k + i)
        return MapSet(maps, np.asarray(slots), depth, sch.faces, view, lv[0], None)
    fr = faces.face_frames(sch.faces, sch.parameterization, view, lv, k=k, **{key: float(v) for key, v in options.items()})
    halves = fr.used.shape[2]
    for j in range(4):  # ≤ 4 faces × 2 halves × k ranges
        for h in range(halves):
            if not fr.used[0, j, h]:
                continue
            for i in range(k):
                c = (0, j, h, i)
                maps.append(frame_map(lv[0], fr.axis[0, j, h], fr.y0[c], fr.y1[c], fr.a[c], fr.s_lo[c], fr.s_hi[c], sch.parameterization))
                slots.append(1 + (j * halves + h) * k + i)
    return MapSet(maps, np.asarray(slots), fr.depth, sch.faces, view, lv[0], fr)
