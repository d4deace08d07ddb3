"""Per frame, each map's texel lattice in the world: where every scheme puts its texels.

A still world is seen through maps whose texel grids may move.  For every frame and map
this module gives the grid in the world-fixed light frame B (rows x̂, l̂, ŷ of
:func:`aliasing.geometry.light_space` of the world light): the map's origin (x0, y0), its
texel sides (tx, ty) and its texels per side; and which map each point uses.

Cascades (``csm``, ``csm-stable``, ``sdsm``; :func:`aliasing.engines.compare.parse_spec`)
are fitted as :func:`aliasing.engines.stable.evaluate` fits them, here placed in the world:

* the side: ``tight`` — the slice's 8 world corners' extent along x̂ and ŷ; every other
  fit — the square side of :func:`aliasing.engines.stable.evaluate` (light-independent),
  with the snap's size factor (``pad``, ``border``, ``godot``) for all fits alike;
* the centre: ``tight``, ``diagonal``, ``body`` — the corners' light-plane box centre;
  ``sphere`` — the minimal sphere's centre on the view axis (z_c of
  :func:`aliasing.engines.stable.sphere_radius`, at most b, with c² = tan²θ_x + tan²θ_y:
  2 tan²θ for a square view); ``centroid``, ``centroid16``
  — the corners' average ((a + b)/2 on the axis); ``far`` — the camera;
* snapping, in the world-fixed light frame: ``origin`` and ``pad`` floor the map's corner
  to a whole texel, ``border`` and ``godot`` to two texels (Filament's even texels,
  Godot's 4r/R), ``bevy`` floors the centre to a texel; ``none`` keeps the fit's origin.

SDSM's depth bounds are re-measured every frame from what the camera sees (its eye pass,
:func:`aliasing.engines.validate.eye_histogram`), then fitted tight.  VSM clipmap levels
(:mod:`aliasing.engines.vsm`) snap whole pages in a world-fixed lattice, so a level's
texels never move with the camera; a point's level follows its distance to the camera.
Only the window of texels a level's points use is drawn (the stored depth of a texel
depends only on its centre, so a window of the lattice holds the same texels as the
whole virtual map).

The camera's aspect (width/height, :attr:`aliasing.raster.scenes.Camera.view`; the field of
view is vertical) widens every slice: the tight fits take the wide slice's corners, the
other fits the radii of :func:`aliasing.engines.stable.evaluate` at that aspect, SDSM's
eye pass is the wide view, and :func:`assign` tests |x| ≤ z·tan θ_x.  It stays fixed along
a path (a zoom changes the vertical field of view at that aspect).  ``vsm`` takes it into
the clipmap's LOD (:class:`aliasing.engines.vsm.Clipmap`: tan θ_x = aspect·tan θ_y, the
viewport ``image_res`` pixels across): at the same width a view ``aspect`` times wider
has pixels ``aspect`` times larger, and each level's distance bound moves nearer the camera
by that factor (while B′ is not clamped).
Aspect 1 gives the square view's lattices bit for bit.

Example
-------
>>> from aliasing.temporal import paths, points
>>> w = points.world("boxes", boxes=10)
>>> poses = paths.frames(paths.parse_motion("translate:0.1,0,0"), w.camera.eye, w.camera.rotation, 60.0, w.light, 3)
>>> lat = plan("csm-stable:log:k=3:fit=sphere:snap=origin", w, poses, 64)
>>> lat.x0.shape, bool(np.all(lat.tx == lat.tx[0]))
((3, 3), True)
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check
from .. import geometry
from ..engines import compare, sdsm, stable, vsm
from ..engines.sample import sample_bounds
from ..engines.validate import eye_histogram
from ..raster.draw import MAX_RESOLUTION, check_resolution
from ..view import View, check_aspect, tan_theta
from .points import World

Array = NDArray[np.float64]

#: Snap unit [texels] of the map corner, per snap (``bevy`` snaps the centre).
SNAP_UNIT = {"origin": 1.0, "pad": 1.0, "border": 2.0, "godot": 2.0, "bevy": 1.0}
#: Side factor of the snap (:func:`aliasing.engines.stable.evaluate`): a texel more, or one each side.
SNAP_SIDE = {"pad": lambda r: r / (r - 1), "border": lambda r: r / (r - 2), "godot": lambda r: r / (r - 2)}


@dataclass(frozen=True)
class Lattices:
    """Texel grids per frame and map.

    ``basis`` (F, 3, 3) the world light frame; ``x0``, ``y0`` (F, K) the map corners,
    ``tx``, ``ty`` (F, K) the texel sides [world units]; ``n`` (F, K) texels per side (0:
    the map is not drawn in that frame); ``lo``, ``hi`` (F, K) each map's used eye-depth
    range (cascades) or distance range (VSM levels) [world units]; ``family``; ``levels``
    (VSM: the clipmap level of each map); ``by_distance`` (maps chosen by distance to the
    camera, VSM, rather than eye depth); ``aspect`` the view's width/height (the
    camera's, :func:`assign`'s frustum test).
    """

    basis: Array
    x0: Array
    y0: Array
    tx: Array
    ty: Array
    n: NDArray[np.int64]
    lo: Array
    hi: Array
    family: str
    levels: NDArray[np.int64]
    by_distance: bool
    aspect: float = 1.0

    @property
    def maps(self) -> int:
        return self.x0.shape[1]


def _shaped(value: object, name: str, shape: tuple) -> Array:
    """A finite float array whose shape matches ``shape`` (None: any length)."""
    a = check.finite(value, name)
    if a.ndim != len(shape) or any(s is not None and s != n for s, n in zip(shape, a.shape)):
        want = "(" + ", ".join("N" if s is None else str(s) for s in shape) + ")"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    return a


def eye_coordinates(positions: Array, eyes: Array, rots: Array) -> Array:
    """Eye-space coordinates (F, P, 3) of world points (P, 3) in every frame's camera
    (``eyes`` (F, 3) [world units], ``rots`` (F, 3, 3) rows right, up, forward)."""
    p = _shaped(positions, "positions", (None, 3))
    e = _shaped(eyes, "eyes", (None, 3))
    r = _shaped(rots, "rots", (len(e), 3, 3))
    return np.einsum("fpj,fij->fpi", p[None] - e[:, None], r)


def assign(lat: Lattices, eye_pos: Array, fovs: Array, near: float, far: float) -> NDArray[np.int64]:
    """The map of every point in every frame (F, P): −1 outside the view frustum or any map.

    ``eye_pos`` (F, P, 3) eye coordinates [world units], ``fovs`` (F,) vertical [deg], ``near`` < ``far``
    [world units]; the view's width is ``lat.aspect`` times its height (|x| ≤ z·aspect·tan θ).
    """
    check.instance(lat, "lat", Lattices)
    eye_pos = _shaped(eye_pos, "eye_pos", (lat.x0.shape[0], None, 3))
    fovs = check.fov(_shaped(fovs, "fovs", (lat.x0.shape[0],)))
    near, far = (float(v) for v in check.frustum(near, far))
    wide = float(check_aspect(check.scalar(lat.aspect, "lat.aspect"), "aspect"))
    z = eye_pos[..., 2]
    t = np.asarray(tan_theta(fovs))[:, None]
    inside = (z >= near) & (z <= far) & (np.abs(eye_pos[..., 0]) <= z * (wide * t)) & (np.abs(eye_pos[..., 1]) <= z * t)
    key = np.linalg.norm(eye_pos, axis=-1) if lat.by_distance else z
    out = np.full(z.shape, -1, np.int64)
    for f in range(z.shape[0]):  # per frame, vectorized over points (K ≤ a few dozen maps)
        lo, hi = lat.lo[f], lat.hi[f]
        i = np.clip(np.searchsorted(hi, key[f], side="left"), 0, len(hi) - 1)
        ok = inside[f] & (key[f] >= lo[i] * (1 - 1e-12)) & (key[f] <= hi[i] * (1 + 1e-12))
        out[f] = np.where(ok, i, -1)
    return out


def _snap(x0: Array, xc: Array, side: Array, texel: Array, snap: str) -> Array:
    if snap == "none":
        return x0
    if snap == "bevy":
        return np.floor(xc / texel) * texel - side / 2
    unit = SNAP_UNIT[snap] * texel
    return np.floor(x0 / unit) * unit


def _cascades(parsed: compare.ParsedSpec, w: World, poses, res: int, sdsm_res: int) -> Lattices:
    eyes, rots, fovs, lights = poses
    cam = w.camera
    near, far, wide = cam.near, cam.far, float(cam.aspect)
    kw = dict(parsed.fit)
    sample = {key: kw.pop(key) for key in ("border", "dilation", "quantize") if key in kw}
    fit, snap = kw.get("fit", "tight"), kw.get("snap", "none")
    kw["resolution"] = float(res)
    F = len(fovs)
    basis = geometry.light_space(lights)  # (F, 3, 3) world light frames
    rows = []
    for f in range(F):  # per frame: a handful of maps, each computed in closed form
        split = parsed.split
        if parsed.family == "sdsm":
            tri_e = (w.triangles - eyes[f]) @ rots[f].T
            edges, counts = eye_histogram(tri_e, near, far, View(near, far, fovs[f], wide), resolution=sdsm_res, bins=64)  # the wide eye pass
            filled = np.nonzero(counts)[0]
            if not filled.size:
                raise ValueError(f"frame {f}: the camera sees nothing within [near, far] (SDSM has no depth bounds)")
            if parsed.method == "log":
                z_lo = float(edges[filled[0]]) if parsed.zmin is None else parsed.zmin
                z_hi = float(edges[filled[-1] + 1]) if parsed.zmax is None else parsed.zmax
                e = sdsm.log_partitions(near, far, *sdsm.occupied(near, far, z_lo, z_hi), parsed.k)
                split = (e[:-1], e[1:])
            else:
                split = (sdsm.adaptive_log if parsed.method == "adaptive" else sdsm.kmeans)(edges, counts, parsed.k)
        light_e = rots[f] @ lights[f]
        r = stable.evaluate(split, near, far, fovs[f], light_e[None], **kw)
        (a, b), (u, v) = r.fit_range, r.used
        corners = eyes[f] + geometry.frustum_vertices(View(a, b, fovs[f], wide)) @ rots[f]  # (K, 8, 3) world
        B = basis[f]
        px, py = corners @ B[0], corners @ B[2]
        box_x, box_y = (px.min(-1) + px.max(-1)) / 2, (py.min(-1) + py.max(-1)) / 2
        if fit == "tight":
            wx, wy = np.ptp(px, -1), np.ptp(py, -1)
            if snap in SNAP_SIDE:
                wx, wy = wx * SNAP_SIDE[snap](res), wy * SNAP_SIDE[snap](res)
        else:
            wx, wy = r.width_x[0].copy(), r.width_y[0].copy()
        if sample:
            whole = eyes[f] + geometry.frustum_vertices(View(np.array([near]), np.array([far]), fovs[f], wide))[0] @ rots[f]
            wx = sample_bounds(wx, np.ptp(whole @ B[0]), **sample)
            wy = sample_bounds(wy, np.ptp(whole @ B[2]), **sample)
        tan = float(tan_theta(fovs[f]))
        c2 = (wide * tan) ** 2 + tan**2  # tan²θ_x + tan²θ_y (stable.sphere_radius's c²; 2 tan²θ exactly at aspect 1)
        if fit == "sphere":
            zc = np.minimum((a + b) * (1 + c2) / 2, b)
            centre = eyes[f] + zc[:, None] * rots[f][2]
            xc, yc = centre @ B[0], centre @ B[2]
        elif fit in ("centroid", "centroid16"):
            centre = eyes[f] + ((a + b) / 2)[:, None] * rots[f][2]
            xc, yc = centre @ B[0], centre @ B[2]
        elif fit == "far":
            xc, yc = np.full_like(a, eyes[f] @ B[0]), np.full_like(a, eyes[f] @ B[2])
        else:
            xc, yc = box_x, box_y
        tx, ty = wx / res, wy / res
        x0 = _snap(xc - wx / 2, xc, wx, tx, snap)
        y0 = _snap(yc - wy / 2, yc, wy, ty, snap)
        rows.append((x0, y0, tx, ty, u, v))
    K = max(len(row[0]) for row in rows)
    if any(len(row[0]) != K for row in rows):  # SDSM may merge partitions: pad with empty maps
        rows = [tuple(np.concatenate([x, np.full(K - len(x), np.nan)]) for x in row) for row in rows]
    x0, y0, tx, ty, lo, hi = (np.array([row[i] for row in rows]) for i in range(6))
    n = np.where(np.isfinite(x0), res, 0).astype(np.int64)
    return Lattices(basis, x0, y0, tx, ty, n, np.nan_to_num(lo, nan=np.inf), np.nan_to_num(hi, nan=np.inf), parsed.family, np.zeros(0, np.int64), False, wide)


def _vsm(parsed: compare.ParsedSpec, w: World, poses, positions: Array, eye_pos: Array) -> Lattices:
    eyes, rots, fovs, lights = poses
    c = parsed.clipmap
    F = len(fovs)
    levels = np.arange(c.first, c.last + 1)
    cm = vsm.CM_PER_UNIT[c.unit.lower()]
    lo = np.zeros((F, len(levels)))
    hi = np.zeros((F, len(levels)))
    for f in range(F):  # the level boundaries depend on the frame's fov (the LOD bias)
        cf = replace(c, fov=float(fovs[f]))  # the camera's aspect and width kept: tan θ_x = aspect·tan θ_y of this frame
        # level L holds distances with floor(log2 d_cm + B′) = L (clamped to [first, last])
        edge = 2.0 ** (levels + 1 - cf.lod_bias) / cm
        lo[f] = np.concatenate([[0.0], edge[:-1]])
        hi[f] = edge
        hi[f, -1] = 2.0 ** (c.last + 1) / cm  # nothing beyond the last level's radius
    basis = geometry.light_space(lights)
    tex = vsm.texel(c, levels)  # (K,) world units
    lat = Lattices(basis, np.zeros((F, len(levels))), np.zeros((F, len(levels))), np.broadcast_to(tex, (F, len(levels))).copy(),
                   np.broadcast_to(tex, (F, len(levels))).copy(), np.zeros((F, len(levels)), np.int64), lo, hi, "vsm", levels, True, float(w.camera.aspect))
    part = assign(lat, eye_pos, fovs, w.camera.near, w.camera.far)
    still = np.allclose(lights, lights[0])  # a world-fixed lattice: one window per level for the whole sequence
    px = np.einsum("pj,fj->fp", positions, basis[:, 0])
    py = np.einsum("pj,fj->fp", positions, basis[:, 2])
    for k in range(len(levels)):
        groups = [np.arange(F)] if still else [np.array([f]) for f in range(F)]
        for g in groups:
            sel = part[g] == k
            if not sel.any():
                continue
            xs, ys = px[g][sel], py[g][sel]
            t = tex[k]
            i0, j0 = np.floor(xs.min() / t) - 1, np.floor(ys.min() / t) - 1
            size = int(max(np.floor(xs.max() / t) - i0, np.floor(ys.max() / t) - j0)) + 2
            if size > MAX_RESOLUTION:
                raise ValueError(f"{parsed.spec}: level {levels[k]} needs a window of {size} texels per side (over {MAX_RESOLUTION}); raise bias or lower the image resolution")
            lat.x0[g, k], lat.y0[g, k], lat.n[g, k] = i0 * t, j0 * t, size
    return lat


def plan(spec: str, w: World, poses, res: int, *, positions: Array | None = None, sdsm_res: int = 64, image_res: int = 128, unit: str = "m") -> Lattices:
    """The texel lattices of scheme ``spec`` over the frames ``poses`` (:func:`aliasing.temporal.paths.frames`).

    Parameters
    ----------
    spec : str
        A scheme of the engines grammar: ``csm:…``, ``csm-stable:…``, ``sdsm…``, ``vsm:…``.
    w : World
        The scene, its frame-0 camera (near, far, aspect) and light.
    poses : tuple
        (eyes, rotations, fovs, lights) per frame.
    res : int
        Texels per side of every cascade.
    positions : ndarray (P, 3), optional
        The points (VSM draws only the windows they use; required for ``vsm``).
    sdsm_res : int
        Eye-pass resolution of SDSM's per-frame depth bounds [pixels per side].
    image_res : int
        The viewport width VSM's level selection assumes [pixels].
    unit : str
        The scene's length unit (VSM's constants are in cm).
    """
    r = check_resolution(res, "res")
    check.instance(w, "w", World)
    if not isinstance(poses, (tuple, list)) or len(poses) != 4:
        raise ValueError("poses must be (eyes, rotations, fovs, lights) of aliasing.temporal.paths.frames")
    eyes = _shaped(poses[0], "poses' eyes", (None, 3))
    n = len(eyes)
    poses = (eyes, _shaped(poses[1], "poses' rotations", (n, 3, 3)), check.fov(_shaped(poses[2], "poses' fovs", (n,))), _shaped(poses[3], "poses' lights", (n, 3)))
    if positions is not None:
        positions = _shaped(positions, "positions", (None, 3))
    cam = w.camera
    view = cam.view  # validates the camera's aspect (a World built by hand)
    parsed = compare.parse_spec(spec, fov=cam.fov, near=cam.near, far=cam.far, image_res=check_resolution(image_res, "image_res"), shadow_res=r, unit=unit, aspect=view.aspect)
    if parsed.family in ("matched", "exact"):
        raise ValueError(f"scheme {spec!r}: {parsed.family} is a limit without a texel grid; shimmer needs csm, csm-stable, sdsm or vsm")
    if parsed.family == "vsm":
        if positions is None:
            raise ValueError("positions are needed for vsm (the windows of texels its points use)")
        eyes, rots, fovs, _ = poses
        return _vsm(parsed, w, poses, positions, eye_coordinates(positions, eyes, rots))
    return _cascades(parsed, w, poses, r, check_resolution(sdsm_res, "sdsm_res"))
