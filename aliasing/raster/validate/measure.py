"""Perspective aliasing measured from sampled positions, against the analytic M_x, M_z.

For every image pixel on a probe, the eye pass (:func:`aliasing.raster.eye_pass`) gives the
visible point X; the light map gives its shadow-map coordinates (s, t).  Central differences
between the pixel's neighbours on the same probe (pixel spacing 1/R_i in image units u, v)
give the Jacobian J = ∂(s, t)/∂(u, v) and ∂X/∂(u, v).  With unit resolutions (one pixel
spans the image, one texel the map, as in :mod:`aliasing.directional`):

* the **image error** of Lloyd 2007 eqs. 85–86 style: the extent of a texel in the image,
  m_s = |∂(u, v)/∂s|, m_t = |∂(u, v)/∂t| (columns of J⁻¹); m = max(m_s, m_t).  This
  includes the projection factor of the surface and the off-axis stretch of the pinhole
  image that the analytic model leaves out (it uses w_i = 2 d tanθ at every pixel);
* the **perspective error** as the analytic model defines it: the light-beam footprint of a
  texel reconstructed from the sampled surface points, ∂X/∂s = X_u u_s + X_v v_s, projected
  on the light plane's axes, over the eye-beam width w_i = 2 d tanθ at the point's depth d:
  m_x = |x_L·∂X/∂s|/w_i, m_z = |z_L·∂X/∂t|/w_i (Lloyd 2006 eqs. 2–4; 2007 eqs. 96–97);
  the ratios m_s/m_x and m_t/m_z are the projection factors (with the off-axis stretch).
* the **projection factor** cos ψ_e / cos ψ_l from the eye pass's normals
  (:func:`projection_factors`; ψ_e, ψ_l the angles of the normal to the eye and light
  directions): the factor by which the image error exceeds the perspective error on a
  surface (Lloyd 2006 §3.3).  The probes face the bisector of the two directions, so it is
  about 1 on them: this is what makes them measure perspective aliasing alone.

Their maxima over dense probes are compared with :func:`aliasing.schemes.evaluate`'s M_x,
M_z for the same light and parameterization; with ``ZP<k>+…`` schemes each pixel uses the
map of the z-partition holding its eye depth, with face partitions (``FP+…``, ``FPc+…``, ``FPcs+…``)
the map of its face partition (:meth:`~aliasing.raster.MapSet.assign`), and each map is
compared with its own bound (:func:`aliasing.faces.face_errors`' per-map M_x, M_z).

What this witnesses: the perspective error checks the closed-form beam widths of
:mod:`aliasing.directional` and the claim that their maxima lie at the frustum's vertices,
through independent sampling (rasterized visible points, finite differences of the map
coordinates); it does not re-derive the parameterizations themselves (the coordinates are
those of :class:`~aliasing.raster.LightMap`).  The image error is what a viewer sees; it
exceeds the model where the model's simplifications (no 1/cos² off-axis factor, projection
factor 1) do not hold: reported, not tolerated away.

Example
-------
>>> r = measure(1.0, 100.0, 60.0, "overhead", "P", resolution=128, cells=8)
>>> bool(0.9 < r.ratio_x[0] <= 1.0 + r.tolerance and 0.9 < r.ratio_z[0] <= 1.0 + r.tolerance)
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from ... import geometry, schemes
from ..draw import backends
from ..draw.core import check_resolution
from ..draw.eye import _fov_tan, eye_pass
from ..draw.facemaps import _map_set
from ..draw.lightmap import LightMap
from ..draw.shadow import MapSampler
from ..scenes.builtin import Scene, probes
from ...view import View, view_args

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Measurement:
    """Measured errors per pixel (NaN off the probes or at probe borders) and their maxima.

    Per-pixel arrays (R, R), row j is v = (j + ½)/R: ``m_s``, ``m_t`` (image error),
    ``m_x``, ``m_z`` (perspective error), ``s``, ``t`` (map coordinates of the visible point in
    its partition's map), ``partition`` (index of the pixel's map, −1 off the probes).
    Per map, shape (k,) (k maps of :func:`~aliasing.raster.map_set`, in its order): ``M_x``, ``M_z`` analytic (unit resolutions, from
    :func:`aliasing.schemes.evaluate`); ``measured_x``, ``measured_z`` the maxima of m_x, m_z
    over the pixels shaded from that map (NaN if none); ``ratio_x``, ``ratio_z``
    measured/analytic; ``n_prime`` [world units].  Scalars: ``image_ratio_s``,
    ``image_ratio_t`` the maxima of m_s/M_x and m_t/M_z; ``tolerance`` the stated relative
    discretisation tolerance; ``pixels`` the number of measured pixels; ``scheme``;
    ``edges`` the split depths (k + 1,); ``self_lit`` the fraction of measured pixels whose
    texel in the rasterized shadow map (``map_resolution``) holds the pixel's own probe (the
    sampled map and the coordinates agree; undersampling — texels larger than a probe — and
    probes shadowing each other lower it).
    """

    m_s: Array
    m_t: Array
    m_x: Array
    m_z: Array
    projection: Array
    s: Array
    t: Array
    partition: NDArray[np.int64]
    M_x: Array
    M_z: Array
    measured_x: Array
    measured_z: Array
    ratio_x: Array
    ratio_z: Array
    image_ratio_s: float
    image_ratio_t: float
    tolerance: float
    pixels: int
    scheme: str
    n_prime: Array
    edges: Array
    self_lit: float


def _differences(a: Array, same: NDArray[np.bool_], axis: int, spacing: float) -> Array:
    """Central difference of a along an image axis (1 = u, 0 = v); NaN where not ``same``."""
    fwd = np.roll(a, -1, axis=axis)
    bwd = np.roll(a, 1, axis=axis)
    with np.errstate(invalid="ignore"):  # inf − inf off the map's partition: masked below
        d = np.where(same[(...,) + (None,) * (a.ndim - same.ndim)], (fwd - bwd) / (2 * spacing), np.nan)
    return d


@check.public
def measure(near: float | View, far: float | None = None, fov: float | None = None, light: str | ArrayLike | None = None, scheme: str | None = None, *, resolution: int = 512, cells: int = 32, scene: Scene | None = None, map_resolution: int = 512,
            backend: str = "numpy", **options: ArrayLike) -> Measurement:
    """Measure the aliasing error of a scheme's maps on probes and compare with their bounds.

    Parameters
    ----------
    near, far : float
        Eye near and far distances [world units], 0 < near < far; or a
        :class:`~aliasing.View` in ``near``: ``measure(view, light, scheme)``.
    fov : float
        Full field of view [deg].
    light : str or array_like
        One light direction (spec or vector towards the light).
    scheme : str
        Scheme (default Standard: Standard, P, LogP, a warping rule, each alone or after ``ZP<k>+``; or
        ``FP+…``, ``FPc+…``, ``FPcs+…``): each pixel is measured in the map of its z- or face partition.
    resolution : int
        Image resolution R_i [pixels per side].
    cells : int
        Probe grid (see :func:`aliasing.raster.probes`); ignored when ``scene`` is given.
    scene : Scene, optional
        A scene with probes (group ≥ 0); default ``probes(near, far, fov, light, cells=cells,
        splits=...)`` with the scheme's z split depths (none for face partitions).
    map_resolution : int
        Resolution of the shadow map rasterized for the ``self_lit`` check [texels per side].
    backend : {"numpy", "numba", "gl"}
        How the eye pass and the shadow maps are drawn (:mod:`aliasing.raster.draw.backends`;
        numba draws the eye pass only, its maps by numpy).
    **options
        Warping-rule options for :func:`aliasing.schemes.evaluate`.

    Returns
    -------
    Measurement

    Example
    -------
    >>> r = measure(1.0, 50.0, 60.0, "gamma:150", "ZP2+P", resolution=128, cells=8)
    >>> r.pixels > 1000, bool(np.all(r.measured_x <= r.M_x * (1 + r.tolerance)))
    (True, True)
    """
    view, (light, scheme) = view_args(near, far, fov, (light, scheme), (None, None, None, None, "Standard"))
    if view.shape != ():
        raise ValueError(f"measure takes one view: near, far and fov must be scalars, got shape {view.shape}")
    res = check_resolution(resolution)
    rm = check_resolution(map_resolution, "map_resolution")
    eye_backend, map_backend = backends.pair(backend)
    if scene is not None:
        check.instance(scene, "scene", Scene)
    check.instance(scheme, "scheme", (str, schemes.Scheme))
    sch = schemes.parse(scheme) if isinstance(scheme, str) else scheme
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    ms = _map_set(view, lv, sch, options)
    maps, edges = ms.maps, ms.edges
    analytic = schemes.evaluate(sch, view, lv, **options)
    sc = probes(view, light, cells=cells, splits=None if ms.faces else edges) if scene is None else scene
    if not (sc.group >= 0).any():
        raise ValueError("scene must contain probes (triangles with group >= 0)")
    eb = eye_pass(sc.triangles, view, res, backend=eye_backend)
    group = np.where(eb.triangle >= 0, sc.group[np.maximum(eb.triangle, 0)], -1)
    on = group >= 0
    pos = np.where(on[..., None], eb.position, 0.0)
    pos[~on] = [0.0, 0.0, 1.0]
    same_u = on & (np.roll(group, 1, 1) == group) & (np.roll(group, -1, 1) == group)
    same_v = on & (np.roll(group, 1, 0) == group) & (np.roll(group, -1, 0) == group)
    same_u[:, [0, -1]] = False
    same_v[[0, -1], :] = False
    ok = same_u & same_v
    if not ok.any():
        raise ValueError(f"no probe pixel could be measured: increase resolution (got {res}) or reduce cells")
    # each pixel is shaded from the map of its z- or face partition
    part = ms.assign(pos)
    fields = {key: np.full((res, res), np.nan) for key in ("s", "t", "m_s", "m_t", "m_x", "m_z")}
    measured_x, measured_z, self_lit = [], [], []
    for i, lm in enumerate(maps):
        sel = ok & (part == i)
        if not sel.any():
            measured_x.append(np.nan)
            measured_z.append(np.nan)
            continue
        got = _errors(lm, pos, ok, res, view.tan_theta)
        for key, val in got.items():
            fields[key][sel] = val[sel]
        measured_x.append(float(np.nanmax(got["m_x"][sel])))
        measured_z.append(float(np.nanmax(got["m_z"][sel])))
        # the sampled map: the texel of each measured pixel should hold the pixel's own probe
        # (drawn at those texels only: :class:`~aliasing.raster.draw.shadow.MapSampler`, the whole map's values)
        sm = MapSampler(sc.triangles, lm, rm, backend=map_backend)
        col = np.clip((got["s"][sel] * rm).astype(np.int64), 0, rm - 1)
        row = np.clip((got["t"][sel] * rm).astype(np.int64), 0, rm - 1)
        texel = sm.at(row, col)[1]
        sm.release()
        own = np.where(texel >= 0, sc.group[np.maximum(texel, 0)], -2) == group[sel]
        self_lit.append(own)
    M_x, M_z = analytic.M_x[0][ms.slots], analytic.M_z[0][ms.slots]
    mx, mz = np.array(measured_x), np.array(measured_z)
    # stated discretisation tolerance: the central differences' truncation error is
    # h² |third derivative| / (6 |first derivative|), relative, h = 1/R: observed ≤ 1e-5 at
    # R = 384 over the tested schemes and lights; 1e-3 bounds it with margin
    tol = 1e-3
    count = int(ok.sum())
    projection = np.where(ok, projection_factors(eb.position, eb.normal, light), np.nan)
    m_s, m_t, m_x, m_z = fields["m_s"], fields["m_t"], fields["m_x"], fields["m_z"]
    s, t = fields["s"], fields["t"]
    M_x_pix, M_z_pix = M_x[np.maximum(part, 0)], M_z[np.maximum(part, 0)]
    with np.errstate(invalid="ignore"):
        image_ratio_s = float(np.nanmax(m_s / M_x_pix))
        image_ratio_t = float(np.nanmax(m_t / M_z_pix))
    self_lit_frac = float(np.concatenate(self_lit).mean())
    return Measurement(
        m_s=m_s, m_t=m_t, m_x=m_x, m_z=m_z, projection=projection, s=s, t=t, partition=np.where(on, part, -1),
        M_x=M_x, M_z=M_z, measured_x=mx, measured_z=mz,
        ratio_x=mx / M_x, ratio_z=mz / M_z,
        image_ratio_s=image_ratio_s, image_ratio_t=image_ratio_t,
        tolerance=tol, pixels=count, scheme=analytic.scheme.name,
        n_prime=np.array([m.n_prime for m in maps]), edges=edges, self_lit=self_lit_frac,
    )


def pixel_errors(lm: LightMap, position: ArrayLike, ok: ArrayLike, resolution: int, fov: float | View) -> dict[str, Array]:
    """Per-pixel map coordinates and the image and perspective errors through one light map.

    Central differences between a pixel's neighbours (pixel spacing 1/R in image units) of
    the map coordinates (s, t) and of the visible points X; see the module docstring for
    the quantities.

    Parameters
    ----------
    lm : LightMap
        The map (:func:`aliasing.raster.light_map`, or one of :func:`~aliasing.raster.light_maps`).
    position : array_like, shape (R, R, 3)
        Visible eye-space point per pixel [world units] (:attr:`EyeBuffer.position`); it
        must be finite with z > 0 wherever ``ok``.
    ok : array_like of bool, shape (R, R)
        Pixels to measure: those whose four neighbours lie on the same plane (and map).
    resolution : int
        R [pixels per side], the image resolution of ``position``.
    fov : float or View
        Full (vertical) field of view [deg], in (0, 180), or the :class:`~aliasing.View`:
        w_i = 2 d tan θ_y at any aspect (square pixels of unit vertical resolution, as in
        :func:`aliasing.schemes.evaluate`).

    Returns
    -------
    dict of ndarray (R, R)
        ``s``, ``t`` (map coordinates, everywhere), ``m_s``, ``m_t`` (image error) and
        ``m_x``, ``m_z`` (perspective error), unit resolutions, NaN off ``ok``.

    Example
    -------
    >>> from aliasing.raster.draw import eye_pass, light_map
    >>> from aliasing.raster.scenes import probes
    >>> lm = light_map(1.0, 100.0, 60.0, "overhead", "Standard")
    >>> sc = probes(1.0, 100.0, 60.0, "overhead", cells=4)
    >>> eb = eye_pass(sc.triangles, 60.0, 64)
    >>> g = np.where(eb.triangle >= 0, sc.group[eb.triangle], -1)  # probe of each pixel
    >>> ok = (g >= 0) & (g == np.roll(g, 1, 0)) & (g == np.roll(g, -1, 0)) & (g == np.roll(g, 1, 1)) & (g == np.roll(g, -1, 1))
    >>> got = pixel_errors(lm, np.where(ok[..., None], eb.position, 1.0), ok, 64, 60.0)
    >>> bound = schemes.evaluate("Standard", 1.0, 100.0, 60.0, "overhead").M_x[0, 0]
    >>> sorted(got), bool(np.nanmax(got["m_x"]) <= bound * 1.001)
    (['m_s', 'm_t', 'm_x', 'm_z', 's', 't'], True)
    """
    if not isinstance(lm, LightMap):
        raise ValueError(f"lm must be a LightMap (aliasing.raster.light_map), got {type(lm).__name__}")
    res = check_resolution(resolution)
    tan = _fov_tan(fov)[3]  # tan θ_y: w_i of a pixel of unit vertical resolution
    pos = np.asarray(position, dtype=float)
    if pos.shape != (res, res, 3):
        raise ValueError(f"position must have shape (resolution, resolution, 3) = ({res}, {res}, 3), got {pos.shape}")
    mask = np.asarray(ok)
    if mask.shape != (res, res) or mask.dtype != bool:
        raise ValueError(f"ok must be a boolean array of shape ({res}, {res}), got {mask.dtype} {mask.shape}")
    if not (np.all(np.isfinite(pos[mask])) and np.all(pos[mask][:, 2] > 0)):
        raise ValueError("position must be finite with z > 0 (in front of the eye) at every ok pixel")
    return _errors(lm, pos, mask, res, tan)


def projection_factors(position: ArrayLike, normal: ArrayLike, light: str | ArrayLike) -> Array:
    """The projection aliasing factor cos ψ_e / cos ψ_l of each visible point, from its normal.

    ψ_e is the angle between the surface normal and the direction to the eye, ψ_l the angle
    between the normal and the direction to the light (Lloyd 2006 §3.3; Lloyd 2007 eqs.
    29–31: the aliasing error is the perspective error times this factor).  Probe planes
    face the bisector of the two directions, so the factor is 1 at their centres and close
    to 1 over them; on a ground plane seen at a grazing angle it is far below 1.

    Parameters
    ----------
    position : array_like, shape (..., 3)
        Eye-space points [world units] (:attr:`EyeBuffer.position`; NaN where empty).
    normal : array_like, shape (..., 3)
        Unit normals facing the eye (:attr:`EyeBuffer.normal`; NaN where empty).
    light : str or array_like
        One light direction (spec or vector towards the light).

    Returns
    -------
    ndarray, shape (...)
        The factor (dimensionless), NaN where nothing is visible or the surface faces away
        from the light (cos ψ_l ≤ 0: in its own shadow).

    Example
    -------
    >>> # a ground plane (normal +y) seen 10 units ahead from 1 unit above, lit from overhead
    >>> round(float(projection_factors([0.0, -1.0, 10.0], [0.0, 1.0, 0.0], "overhead")), 4)
    0.0995
    """
    pos = np.asarray(position, dtype=float)
    nrm = np.asarray(normal, dtype=float)
    if pos.ndim < 1 or pos.shape[-1] != 3 or nrm.shape != pos.shape:
        raise ValueError(f"position and normal must have the same shape (..., 3), got {pos.shape} and {nrm.shape}")
    lv = geometry.lights(light)
    if lv.shape[0] != 1:
        raise ValueError(f"light must be a single direction, got {lv.shape[0]}")
    with np.errstate(invalid="ignore", divide="ignore"):
        to_eye = -pos / np.linalg.norm(pos, axis=-1, keepdims=True)
        cos_e = np.sum(nrm * to_eye, axis=-1)
        cos_l = nrm @ lv[0]
        return np.where(cos_l > 0, cos_e / np.where(cos_l > 0, cos_l, 1.0), np.nan)


def _errors(lm: LightMap, pos: Array, ok: NDArray[np.bool_], res: int, tan: float) -> dict[str, Array]:
    """Per-pixel s, t and the image and perspective errors through one map (NaN off ``ok``); ``tan`` = tan θ."""
    s, t, _, _ = lm.coordinates(pos)
    h = 1.0 / res
    s_u, t_u = _differences(s, ok, 1, h), _differences(t, ok, 1, h)
    s_v, t_v = _differences(s, ok, 0, h), _differences(t, ok, 0, h)
    x_u, x_v = _differences(pos, ok, 1, h), _differences(pos, ok, 0, h)
    fill = np.where(ok, 1.0, np.nan)
    s_u, t_u, s_v, t_v = (np.where(ok, a, 0.0) for a in (s_u, t_u, s_v, t_v))
    det = s_u * t_v - s_v * t_u
    det = np.where(ok & (det != 0), det, 1.0)
    u_s, v_s = t_v / det, -t_u / det  # J⁻¹ columns: ∂(u, v)/∂s and ∂(u, v)/∂t
    u_t, v_t = -s_v / det, s_u / det
    x_u, x_v = np.where(ok[..., None], x_u, 0.0), np.where(ok[..., None], x_v, 0.0)
    dX_ds = x_u * u_s[..., None] + x_v * v_s[..., None]
    dX_dt = x_u * u_t[..., None] + x_v * v_t[..., None]
    w_i = 2 * tan * pos[..., 2]
    return {
        "s": s, "t": t,
        "m_s": np.hypot(u_s, v_s) * fill, "m_t": np.hypot(u_t, v_t) * fill,
        "m_x": np.abs(dX_ds @ lm.basis[0]) / w_i * fill, "m_z": np.abs(dX_dt @ lm.basis[2]) / w_i * fill,
    }
