"""Pictures from the rasterizer: shadowed renders, projected texel grids, error colour maps,
and cumulative error distributions over light directions.

Every picture is of a seeded :func:`~aliasing.raster.ground_and_boxes` scene seen by the
conventions' eye (origin, looking along +z, ``fov`` full field of view, ground 1 below the
eye) with one directional light, shadowed through the maps of a ``scheme`` (Standard, P,
LogP, a warping rule, each alone or after ``ZP<k>+``; or face partitions ``FPc+…``,
``FPcs+…``) sharing a fixed **texel budget**:
each of the k maps gets ⌊√(budget/k)⌋² texels, so ``ZP4+P`` at a 512² budget has four
256² maps.  Each pixel is shaded from the map of its z- or face partition
(:meth:`aliasing.raster.MapSet.assign`).

* :func:`shadow_image`: Lambert shading (ambient + diffuse·max(0, n·l)) with the
  shadow-map test of :func:`shadow_test`: the stored sample and the pixel's surface are
  compared as planes (the occluder's plane on the pixel's light ray, the receiver's plane
  on the texel centre's ray), so planar receivers never shadow themselves (no acne) and no
  bias grows with the texel (no "peter-panning": shadows touch the objects casting them);
* :func:`grid_image`: the shadow map's texel grid projected onto the scene, a line where
  the texel index (divided by ``every``) changes between neighbouring pixels (Lloyd 2006
  Fig. 15 style; one colour per z-partition);
* :func:`error_image`: the measured perspective aliasing error per pixel,
  m = max(m_x, m_z)·R_image/R_map [image pixels per texel] from finite differences of the
  map coordinates between neighbouring pixels on the same face (as in
  :mod:`aliasing.raster.measure`), on a logarithmic colour scale.  What is matched of Lloyd
  2007 Fig. 13 is only what its caption states (the extraction has no colour bar): a log
  scale, blue where m ≤ 1 (a texel no larger than a pixel: no visible perspective
  aliasing), through cyan, green and yellow to red at the high end (``vmax``, default
  64 pixels per texel); the exact hues and end value of the paper are not
  reproduced;
* :func:`error_cdf`: for a few schemes, the cumulative distribution over seeded random
  light directions (uniform on the sphere) of the maximum perspective error over the view
  [pixels per texel at the budget], Lloyd 2007 Fig. 17 style: analytic
  (:func:`aliasing.schemes.evaluate`) over many directions, and measured on probes by the
  rasterizer (:func:`aliasing.raster.measure`) over a subset as a check.

:func:`render_view` is the core of :func:`view` for any eye-space scene and map set, with one
resolution per map (explicit cascades and error-based budgets, :mod:`aliasing.pictures.scenerender`
for loaded scenes); :func:`grid_of` and :func:`error_of` draw an existing :class:`View`.

Images are float arrays (R, R, 3) in [0, 1], row 0 at the *top* (ready for
``imshow``/``imsave`` without ``origin``).  Everything is vectorised and deterministic.

Example
-------
>>> img = shadow_image(1.0, 50.0, 60.0, "gamma:60@azimuth:30", "P", image_res=48, budget=64**2, boxes=5)
>>> img.shape, bool(img.min() >= 0 and img.max() <= 1)
((48, 48, 3), True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import _validation as check
from .. import geometry, schemes
from ..raster.validate.measure import measure, pixel_errors
from ..raster.draw import LightMap, MapSampler, MapSet, backends, check_resolution, eye_pass, map_set
from ..raster.draw.lookup import BIAS, _bias, shadow_test
from ..raster.scenes.builtin import Scene, ground_and_boxes
from ..view import View as Frustum, view_args

Array = NDArray[np.float64]

SKY = np.array([0.78, 0.86, 0.95])
GROUND = np.array([0.80, 0.78, 0.72])
BOX = np.array([0.85, 0.55, 0.30])
AMBIENT = 0.3
#: Partition colours of the projected grid.
GRID_COLOURS = np.array([[0.0, 0.0, 0.0], [0.75, 0.0, 0.0], [0.0, 0.35, 0.85], [0.0, 0.55, 0.0], [0.6, 0.0, 0.6], [0.8, 0.45, 0.0]])


@dataclass(frozen=True)
class View:
    """A scene seen and shadowed through a scheme's maps (what every picture starts from).

    Attributes: ``scene``; ``ground`` (number of ground triangles, the first ones);
    ``position``, ``normal`` (R, R, 3) from the eye pass (NaN where empty, row 0 at the
    bottom); ``triangle`` (R, R); ``face`` (R, R): a planar-face id (0 for the ground, one per
    box face, −1 empty); ``maps``, ``edges`` (split depths), ``map_res`` (per map);
    ``partition`` (R, R), ``s``, ``t`` (map coordinates in the pixel's map), ``lit`` (bool:
    passes the depth test), ``light`` (unit vector towards the light), ``fov``;
    ``map_resolutions`` (each map's side when they differ, e.g. an error-based budget; None:
    all ``map_res``).
    """

    scene: Scene
    ground: int
    position: Array
    normal: Array
    triangle: NDArray[np.int64]
    face: NDArray[np.int64]
    maps: list[LightMap]
    edges: Array
    map_res: int
    partition: NDArray[np.int64]
    s: Array
    t: Array
    lit: NDArray[np.bool_]
    light: Array
    fov: float
    map_resolutions: NDArray[np.int64] | None = None

    def resolution_of(self) -> Array:
        """Map side [texels] of the map shading each pixel (R, R); NaN off the scene."""
        mr = np.full(len(self.maps), self.map_res, float) if self.map_resolutions is None else self.map_resolutions.astype(float)
        return np.where(self.partition >= 0, mr[np.maximum(self.partition, 0)], np.nan)


def map_resolution(budget: int, k: int) -> int:
    """Resolution of each of k maps sharing ``budget`` texels: ⌊√(budget/k)⌋."""
    b = float(check.positive(budget, "budget"))
    r = int(np.floor(np.sqrt(b / k) + 1e-9))
    return check_resolution(r, "budget/k (texels per side of each map)")


def view(near: float | Frustum, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, *, image_res: int = 256, budget: int = 1024**2,
         boxes: int = 40, ground_cells: int = 16, seed: int = 1, bias: float = BIAS, scene: Scene | None = None, backend: str = "numpy") -> View:
    """Render the eye pass and the shadow test of a seeded scene (see the module docstring).

    ``bias`` is the tolerance of the depth tests of :func:`shadow_test` [world units, ≥ 0].
    ``scene`` replaces the seeded ground and boxes (then ``face`` is the triangle index).
    An :class:`aliasing.View` may stand for near, far, fov: ``view(frustum, light, scheme)``.
    ``backend``: how the eye pass and the maps are drawn (:func:`render_view`).
    """
    frustum, (light, scheme) = view_args(near, far, fov, (light, scheme), (None, None, None, None, "Standard"))
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    ms = map_set(frustum, lv[0], scheme)
    rm = map_resolution(budget, len(ms.maps))
    if scene is None:
        sc = ground_and_boxes(frustum, boxes=boxes, ground_cells=ground_cells, seed=seed)
        n_ground = 2 * ground_cells**2
    else:
        sc, n_ground = scene, 0
    return render_view(sc, ms, [rm] * len(ms.maps), image_res=image_res, bias=bias, ground=n_ground, backend=backend)


def render_view(sc: Scene, ms: MapSet, resolutions: ArrayLike, *, image_res: int = 256, bias: float = BIAS, ground: int = 0, faces: ArrayLike | None = None,
                backend: str = "numpy") -> View:
    """Eye pass and shadow test of an eye-space scene through a map set, one resolution per map.

    Parameters
    ----------
    sc : Scene
        Eye-space triangles [world units].
    ms : MapSet
        The maps (:func:`aliasing.raster.map_set`, or explicit cascades).
    resolutions : array_like of int
        Each map's side [texels], one per map.
    image_res : int
        Image side [pixels].
    bias : float
        Depth-test tolerance [world units], ≥ 0.
    ground : int
        Number of leading ground triangles (one planar face; 0: one face per triangle).
    faces : array_like of int, optional
        A planar-face id per triangle (e.g. coplanar triangles of a mesh share one), for the
        error's differences; overrides ``ground``.
    backend : {"numpy", "numba", "gl"}
        How the eye pass and the maps are drawn (:mod:`aliasing.raster.draw.backends`; numba
        draws the eye pass only, the maps by numpy).
    """
    res = check_resolution(image_res, "image_res")
    rms = [check_resolution(r, "map resolution") for r in np.atleast_1d(np.asarray(resolutions)).tolist()]
    if len(rms) != len(ms.maps):
        raise ValueError(f"resolutions must give one side per map ({len(ms.maps)}), got {len(rms)}")
    bias = _bias(bias)
    eye_backend, map_backend = backends.pair(backend)
    maps, n_ground = ms.maps, ground
    eb = eye_pass(sc.triangles, ms.view, res, backend=eye_backend)
    hit = eb.triangle >= 0
    tri_id = np.maximum(eb.triangle, 0)
    if faces is not None:
        fid = np.asarray(faces, np.int64)
        if fid.shape != (len(sc.triangles),):
            raise ValueError(f"faces must give one id per triangle ({len(sc.triangles)}), got shape {fid.shape}")
        face = fid[tri_id]
    elif n_ground:
        face = np.where(tri_id < n_ground, 0, 1 + (tri_id - n_ground) // 2)
    else:
        face = tri_id.copy()
    face = np.where(hit, face, -1)
    pos = np.where(hit[..., None], eb.position, 0.0)
    pos[~hit] = [0.0, 0.0, 1.0]
    part = ms.assign(pos)
    s_all = np.full((res, res), np.nan)
    t_all = np.full((res, res), np.nan)
    lit = np.zeros((res, res), bool)
    nrm = np.where(hit[..., None], eb.normal, 0.0)
    for i, lm in enumerate(maps):
        sel = hit & (part == i)
        if not sel.any():
            continue
        p = pos[sel]
        s, t, d, _ = lm.coordinates(p)
        s_all[sel], t_all[sel] = s, t
        sm = MapSampler(sc.triangles, lm, rms[i], backend=map_backend)  # drawn at the pixels' texels only (the whole map's values)
        lit[sel] = shadow_test(lm, sm, sc.triangles, p, nrm[sel], bias=bias)
        sm.release()
    return View(sc, n_ground, eb.position, eb.normal, eb.triangle, face, list(maps), ms.edges, rms[0], np.where(hit, part, -1), s_all, t_all, lit,
                ms.light, ms.fov, np.asarray(rms, np.int64))


def _base_colour(v: View) -> Array:
    hit = v.triangle >= 0
    albedo = np.where((v.triangle < v.ground)[..., None], GROUND, BOX) if v.ground else np.broadcast_to(GROUND, v.position.shape)
    lam = np.clip(np.where(hit, np.nan_to_num(v.normal) @ v.light, 0.0), 0.0, 1.0)
    return albedo, lam, hit


def _finish(img: Array) -> Array:
    """Row 0 at the top, clipped to [0, 1]."""
    return np.clip(img[::-1], 0.0, 1.0)


def shade(v: View, *, shadows: bool = True) -> Array:
    """Lambert shading of a :class:`View` (rows bottom-up as the eye pass)."""
    albedo, lam, hit = _base_colour(v)
    diffuse = lam * (v.lit if shadows else 1.0)
    img = albedo * (AMBIENT + (1 - AMBIENT) * diffuse)[..., None]
    return np.where(hit[..., None], img, SKY)


def shadow_image(near: float | Frustum, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, **kwargs) -> Array:
    """Shadowed render (R, R, 3) of the seeded scene; ``kwargs`` as :func:`view`."""
    return _finish(shade(view(near, far, fov, light, scheme, **kwargs)))


def grid_image(near: float | Frustum, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, *, every: int = 16, **kwargs) -> Array:
    """Shadowed render with the texel grid, a line every ``every`` texels, projected on it.

    A pixel is on a line when the index ⌊s·R/every⌋ or ⌊t·R/every⌋ (R the map resolution)
    or the partition differs from its right or upper neighbour's.
    """
    _every(every)
    return grid_of(view(near, far, fov, light, scheme, **kwargs), every)


def _every(every: int) -> int:
    if isinstance(every, bool) or int(every) != every or every < 1:
        raise ValueError(f"every must be a whole number >= 1 (texels between grid lines), got {every!r}")
    return int(every)


def grid_of(v: View, every: int = 16, *, wash: float = 0.0) -> Array:
    """The texel-grid picture of a :class:`View` (see :func:`grid_image`), lines in the cascade colours.

    ``wash`` in [0, 1) lightens the shaded scene under the lines (img·(1 − wash) + wash) so
    that dark lines stay visible on shadowed surfaces.
    """
    every = _every(every)
    if not 0 <= wash < 1:
        raise ValueError(f"wash must be in [0, 1), got {wash!r}")
    img = shade(v) * (1 - wash) + wash
    hit = v.triangle >= 0
    mr = np.nan_to_num(v.resolution_of(), nan=1.0)
    ci = np.where(hit, np.floor(np.nan_to_num(v.s) * mr / every), np.nan)
    cj = np.where(hit, np.floor(np.nan_to_num(v.t) * mr / every), np.nan)
    line = np.zeros(hit.shape, bool)
    for axis in (0, 1):
        for a in (ci, cj, v.partition.astype(float)):
            nb = np.roll(a, -1, axis=axis)
            diff = (a != nb) & hit & np.roll(hit, -1, axis=axis)
            if axis == 0:
                diff[-1, :] = False
            else:
                diff[:, -1] = False
            line |= diff
    colour = GRID_COLOURS[np.maximum(v.partition, 0) % len(GRID_COLOURS)]
    img = np.where(line[..., None], colour, img)
    return _finish(img)


def error_field(v: View, image_res: int | None = None) -> Array:
    """Measured perspective error per pixel, max(m_x, m_z)·R_image/R_map [pixels per texel].

    Central differences between the pixel's neighbours on the same planar face (NaN at face
    borders and off the scene).
    """
    face = v.face
    res = face.shape[0]
    same_u = (face >= 0) & (np.roll(face, 1, 1) == face) & (np.roll(face, -1, 1) == face)
    same_v = (face >= 0) & (np.roll(face, 1, 0) == face) & (np.roll(face, -1, 0) == face)
    part = v.partition
    same_u &= (np.roll(part, 1, 1) == part) & (np.roll(part, -1, 1) == part)
    same_v &= (np.roll(part, 1, 0) == part) & (np.roll(part, -1, 0) == part)
    same_u[:, [0, -1]] = False
    same_v[[0, -1], :] = False
    ok = same_u & same_v
    # keep the true positions of every visible pixel: the border pixels of a face are the
    # neighbours of its ok pixels (a placeholder there would enter their differences)
    hit = face >= 0
    pos = np.where(hit[..., None], v.position, 0.0)
    pos[~hit] = [0.0, 0.0, 1.0]
    out = np.full((res, res), np.nan)
    for i, lm in enumerate(v.maps):
        sel = ok & (part == i)
        if not sel.any():
            continue
        got = pixel_errors(lm, pos, sel, res, v.fov)
        out[sel] = np.maximum(got["m_x"], got["m_z"])[sel]
    return out * res / v.resolution_of()


def error_colours(err: ArrayLike, vmax: float = 64.0) -> Array:
    """Colours (…, 3) of errors on the log scale: blue at ≤ 1, red at ≥ ``vmax``; grey for NaN."""
    from matplotlib import colormaps

    e = np.asarray(err, float)
    if not vmax > 1:
        raise ValueError(f"vmax must be > 1, got {vmax!r}")
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.clip(np.log(np.maximum(e, 1.0)) / np.log(vmax), 0.0, 1.0)
    rgb = colormaps["jet"](np.nan_to_num(x, nan=0.0))[..., :3]
    return np.where(np.isfinite(e)[..., None], rgb, 0.6)


def error_image(near: float | Frustum, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, *, vmax: float = 64.0, **kwargs) -> tuple[Array, Array]:
    """(image (R, R, 3), error (R, R)) of the per-pixel measured perspective error; sky white.

    Both have row 0 at the top.  Pixels at face borders (no central difference) take the
    colour of a neighbour on the same row when there is one, so edges do not show as grey.
    """
    return error_of(view(near, far, fov, light, scheme, **kwargs), vmax)


def error_of(v: View, vmax: float = 64.0) -> tuple[Array, Array]:
    """(image, error) of a :class:`View`, as :func:`error_image`."""
    err = error_field(v)
    # fill face-border pixels from the left/right neighbour (display only)
    fill = err.copy()
    for shift in (1, -1):
        nb = np.roll(err, shift, axis=1)
        fill = np.where(np.isnan(fill) & (v.triangle >= 0), nb, fill)
    img = error_colours(fill, vmax)
    img = np.where((v.triangle < 0)[..., None], 1.0, img)
    # faint shading so the scene stays readable
    _, lam, hit = _base_colour(v)
    img = np.where(hit[..., None], img * (0.75 + 0.25 * lam)[..., None], img)
    return _finish(img), err[::-1]


def random_lights(count: int, seed: int = 0) -> Array:
    """``count`` seeded unit vectors uniform on the sphere (towards the light)."""
    if isinstance(count, bool) or int(count) != count or count < 1:
        raise ValueError(f"count must be a whole number >= 1, got {count!r}")
    v = np.random.default_rng(seed).normal(size=(int(count), 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def analytic_max_error(scheme: str, near: float | Frustum, far: float | None = None, fov: float | None = None, lights: ArrayLike | None = None, *, image_res: int = 1024, budget: int = 1024**2) -> Array:
    """Max over maps of max(M_x, M_z)·R_image/R_map per light direction [pixels per texel].

    An :class:`aliasing.View` may stand for near, far, fov.
    """
    frustum, (lights,) = view_args(near, far, fov, (lights,), (None, None, None, None), ("lights",))
    r = schemes.evaluate(scheme, frustum, np.asarray(lights, float))
    rm = map_resolution(budget, r.M_x.shape[1])
    return np.maximum(r.M_x, r.M_z).max(axis=1) * image_res / rm


def measured_max_error(scheme: str, near: float | Frustum, far: float | None = None, fov: float | None = None, lights: ArrayLike | None = None, *, image_res: int = 1024, budget: int = 1024**2, resolution: int = 128,
                       cells: int = 8) -> Array:
    """The same maxima measured on probes by the rasterizer (resolution² probe image).

    An :class:`aliasing.View` may stand for near, far, fov.
    """
    frustum, (lights,) = view_args(near, far, fov, (lights,), (None, None, None, None), ("lights",))
    lv = np.asarray(lights, float).reshape(-1, 3)
    out = np.empty(len(lv))
    for i, d in enumerate(lv):
        m = measure(frustum, d, scheme, resolution=resolution, cells=cells, map_resolution=16)
        k = len(m.M_x)
        out[i] = np.nanmax(np.maximum(m.measured_x, m.measured_z)) * image_res / map_resolution(budget, k)
    return out


def cdf(values: ArrayLike) -> tuple[Array, Array]:
    """(sorted finite values, fraction ≤ each) of an empirical distribution."""
    v = np.sort(np.asarray(values, float).ravel())
    v = v[np.isfinite(v)]
    return v, np.arange(1, v.size + 1) / max(v.size, 1)


def error_cdf(schemes_: list[str], near: float | Frustum | None = None, far: float | None = None, fov: float | None = None, *, directions: int = 2000, measured: int = 24,
              seed: int = 0, image_res: int = 1024, budget: int = 1024**2, ax=None):
    """Cumulative distributions of the maximum perspective error over random light directions.

    Returns ``(fig, ax, columns)``; ``columns`` maps ``analytic[S]`` (sorted maxima over
    ``directions``), ``fraction``, and ``measured[S]`` (measured maxima at the first
    ``measured`` directions, unsorted, NaN-padded) with ``measured_direction`` indices.
    The frustum defaults to near 1, far 1000, fov 60 [deg]; an :class:`aliasing.View` may
    stand for near, far, fov.
    """
    from ..plotting import subplots

    frustum, _ = view_args(near, far, fov, (), (1.0, 1000.0, 60.0))
    lights = random_lights(directions, seed)
    if ax is None:
        fig, ax = subplots()
    else:
        fig = ax.figure
    cols: dict[str, Array] = {}
    frac = np.arange(1, directions + 1) / directions
    cols["fraction"] = frac
    n_meas = min(int(measured), directions)
    for i, sch in enumerate(schemes_):
        a = analytic_max_error(sch, frustum, lights, image_res=image_res, budget=budget)
        xs, ys = cdf(a)
        line, = ax.plot(xs, ys, label=sch)
        cols[f"analytic[{sch}]"] = np.concatenate([xs, np.full(directions - xs.size, np.nan)])
        if n_meas:
            m = measured_max_error(sch, frustum, lights[:n_meas], image_res=image_res, budget=budget)
            mx, my = cdf(m)
            ax.plot(mx, my, "o", ms=3, color=line.get_color(), alpha=0.8)
            cols[f"measured[{sch}]"] = np.concatenate([m, np.full(directions - n_meas, np.nan)])
    if n_meas:
        cols["measured_direction"] = np.concatenate([np.arange(n_meas), np.full(directions - n_meas, np.nan)])
    ax.set(xscale="log", xlabel="max perspective error [pixels per texel]", ylabel="fraction of light directions", ylim=(0, 1.02))
    ax.axvline(1.0, color="0.5", lw=0.8, ls=":")
    ax.legend(title=f"lines: analytic ({directions})\ndots: measured ({n_meas})", fontsize=7, title_fontsize=7, loc="lower right")
    return fig, ax, cols


# ----------------------------------------------------------------------------- CLI


