"""``aliasing validate --scene FILE``: the perspective error measured on a scene's own surfaces
against the analytic bound for that view and light.

The probes of :mod:`aliasing.raster.validate` face the bisector of the eye and light
directions, so their error is perspective aliasing alone and the analytic maxima are
reached.  A real scene's surfaces are not half-way oriented: the **perspective error**
m_x, m_z measured on them (:func:`aliasing.raster.validate.measure.pixel_errors`: the texel's
light-beam footprint over the eye-beam width, Lloyd 2006 eqs. 2–4) must still stay within
each map's analytic M_x, M_z (the maxima of the beam ratios over the frustum), but need not
reach them; the **projection factor** cos ψ_e / cos ψ_l (Lloyd 2006 §3.3) is reported
separately, with the **image error** m_s, m_t that a viewer sees (perspective × projection,
plus the off-axis stretch).  Measured: pixels whose four neighbours lie on the same planar
face (coplanar triangles merged) and map, within [near, far], on surfaces facing the light
(n·l > :data:`aliasing.raster.scenes.MIN_COS_LIGHT`).  PASS: every map's ratio
measured/analytic ≤ 1 + tolerance (the finite differences' 1e-3 of
:func:`aliasing.raster.validate.measure.measure`).

Example
-------
>>> from aliasing.raster import scenes
>>> from aliasing.raster.scenes import procedural
>>> st = scenes.setup(procedural.city(2000, seed=1, size=60.0), eye="-40,6,-35", target="0,0,0", near=0.5, far=90.0, light_dir="-1,0.8,0.3")
>>> r = validate_scene(st, "ZP2+P", res=96)
>>> r["maps"], r["passed"], r["max_ratio"] <= 1.001
(2, True, True)
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable

import numpy as np

from ..draw.cascades import cascade_set
from .measure import pixel_errors, projection_factors
from ..draw import EyeBuffer, check_resolution, eye_pass
from ... import partitioning
from ..scenes.world import MIN_COS_LIGHT, SceneSetup, add_scene_arguments, json_safe, setup

#: Relative tolerance of the finite differences (as :func:`aliasing.raster.validate.measure.measure` states it).
TOLERANCE = 1e-3


def measurable_pixels(st: SceneSetup, res: int, assign: Callable[[np.ndarray, np.ndarray], np.ndarray], *, backend: str = "numpy") -> tuple[EyeBuffer, np.ndarray, np.ndarray, np.ndarray]:
    """The eye pass of a scene and the pixels whose error can be measured there.

    ``assign(pos, hit)`` gives each pixel's map index.  Returns the eye buffer, the eye-space
    positions ``(res, res, 3)`` (a placeholder ahead of the eye where nothing is hit), the map
    index per pixel (−1 where nothing is hit) and the mask of measurable pixels: lit
    (n·l > ``MIN_COS_LIGHT``), not beyond far, and with the same face and map on all four
    neighbours (the finite differences stay on one plane and one map), border excluded.
    ``backend`` draws the eye pass (:func:`aliasing.raster.eye_pass`).
    """
    cam = st.camera
    eb = eye_pass(st.scene.triangles, cam.view, res, backend=backend)  # the camera's View: its aspect widens the pass
    hit = eb.triangle >= 0
    if not hit.any():
        raise ValueError("no triangles in front of the camera: the image is empty")
    face = np.where(hit, st.faces[np.maximum(eb.triangle, 0)], -1)
    pos = np.where(hit[..., None], eb.position, 0.0)
    pos[~hit] = [0.0, 0.0, 1.0]
    part = np.where(hit, assign(pos, hit), -1)
    ok = (face >= 0) & (pos[..., 2] <= cam.far) & (np.nan_to_num(eb.normal) @ st.light > MIN_COS_LIGHT)
    for a in (face, part):
        for axis in (0, 1):
            ok &= (np.roll(a, 1, axis) == a) & (np.roll(a, -1, axis) == a)
    ok[[0, -1], :] = False
    ok[:, [0, -1]] = False
    return eb, pos, part, ok


def validate_scene(st: SceneSetup, scheme: str, *, res: int = 384, splits: str | None = None, k: int | None = None, backend: str = "numpy", **params: float) -> dict:
    """Measured perspective error per map on the scene against the analytic M_x, M_z.

    Parameters
    ----------
    st : SceneSetup
        The scene in eye space (:func:`aliasing.raster.scenes.setup`).
    scheme : str
        Any scheme; with ``splits`` a single-map warp used in every cascade.
    res : int
        Eye-pass resolution [pixels per side].
    splits, k, **params
        A split method or engine preset (:func:`aliasing.raster.draw.cascades.cascade_set`).
    backend : {"numpy", "numba", "gl"}
        How the eye pass is drawn (:func:`aliasing.raster.eye_pass`).

    Returns
    -------
    dict
        ``scheme``, ``maps``, per map lists ``near``, ``far``, ``M_x``, ``M_z`` (analytic,
        unit resolutions), ``measured_M_x``, ``measured_M_z``, ``ratio_M_x``, ``ratio_M_z``,
        ``pixels`` (measured per map); ``max_ratio``, ``tolerance``, ``passed``;
        ``projection_p10``, ``projection_median``, ``projection_p90`` (cos ψ_e / cos ψ_l over the
        measured pixels); ``image_ratio_s``, ``image_ratio_t`` (max of m_s/M_x, m_t/M_z);
        the camera and light; ``aspect`` (image width/height) when the camera's is not 1.
    """
    r = check_resolution(res, "res")
    cam = st.camera
    cs = cascade_set(cam.view, st.light, scheme, splits=splits, k=k, **params)
    eb, pos, part, ok = measurable_pixels(st, r, lambda pos, hit: cs.maps.assign(pos), backend=backend)
    k_maps = len(cs.maps.maps)
    mx, mz, ms_, mt_, count = (np.full(k_maps, np.nan) for _ in range(5))
    for i, lm in enumerate(cs.maps.maps):
        sel = ok & (part == i)
        count[i] = sel.sum()
        if not sel.any():
            continue
        got = pixel_errors(lm, pos, sel, r, cam.view)
        mx[i], mz[i] = np.nanmax(got["m_x"]), np.nanmax(got["m_z"])
        ms_[i], mt_[i] = np.nanmax(got["m_s"]), np.nanmax(got["m_t"])
    if not count.sum():
        raise ValueError("no measurable pixels: no lit planar surface within [near, far] covers 3 x 3 pixels; raise --res or move the camera")
    proj = projection_factors(eb.position[ok], eb.normal[ok], st.light)
    rx, rz = mx / cs.M_x, mz / cs.M_z
    ratios = np.concatenate([rx, rz])
    max_ratio = float(np.nanmax(ratios))
    out = {
        "source": st.source, "scheme": cs.label, "camera": cam.name, "near": cam.near, "far": cam.far, "fov": cam.fov,
        "light_eye_space": st.light.tolist(), "gamma": float(np.degrees(np.arccos(np.clip(st.light[2], -1, 1)))),
        "res": r, "maps": k_maps, "triangles": int(len(st.scene.triangles)), "degenerate_skipped": st.degenerate,
        "near_i": cs.near_i.tolist(), "far_i": cs.far_i.tolist(),
        "M_x": cs.M_x.tolist(), "M_z": cs.M_z.tolist(), "measured_M_x": mx.tolist(), "measured_M_z": mz.tolist(),
        "ratio_M_x": rx.tolist(), "ratio_M_z": rz.tolist(), "pixels": count.astype(int).tolist(),
        "max_ratio": max_ratio, "tolerance": TOLERANCE, "passed": bool(max_ratio <= 1 + TOLERANCE),
        "projection_p10": float(np.nanpercentile(proj, 10)), "projection_median": float(np.nanmedian(proj)),
        "projection_p90": float(np.nanpercentile(proj, 90)),
        "image_ratio_s": float(np.nanmax(ms_ / cs.M_x)), "image_ratio_t": float(np.nanmax(mt_ / cs.M_z)),
    }
    return out if cam.aspect == 1.0 else out | {"aspect": float(cam.aspect)}


def format_text(r: dict) -> str:
    """A scene validation as a short plain-text report."""
    lines = [
        f"scene {r['source'] or '(arrays)'}: {r['triangles']} triangles ({r['degenerate_skipped']} degenerate skipped), camera {r['camera']}, "
        f"near {r['near']:g}, far {r['far']:g}, fov {r['fov']:g} deg{', aspect %g' % r['aspect'] if 'aspect' in r else ''}, light gamma {r['gamma']:.4g} deg",
        f"scheme {r['scheme']}  maps {r['maps']}  res {r['res']} px",
        f"{'map':>4s}{'near':>10s}{'far':>10s}{'pixels':>9s}{'M_x':>11s}{'measured':>11s}{'ratio':>9s}{'M_z':>11s}{'measured':>11s}{'ratio':>9s}",
    ]
    for i in range(r["maps"]):
        lines.append(f"{i:>4d}{r['near_i'][i]:>10.4g}{r['far_i'][i]:>10.4g}{r['pixels'][i]:>9d}{r['M_x'][i]:>11.5g}{r['measured_M_x'][i]:>11.5g}"
                     f"{r['ratio_M_x'][i]:>9.4f}{r['M_z'][i]:>11.5g}{r['measured_M_z'][i]:>11.5g}{r['ratio_M_z'][i]:>9.4f}")
    lines.append(f"projection factor cos(psi_e)/cos(psi_l) on the measured surfaces: p10 {r['projection_p10']:.4g}, median {r['projection_median']:.4g}, "
                 f"p90 {r['projection_p90']:.4g} (real surfaces are not half-way oriented)")
    lines.append(f"image error / analytic bound (what a viewer sees, with projection): max {r['image_ratio_s']:.4g} (s), {r['image_ratio_t']:.4g} (t)")
    verdict = "PASS" if r["passed"] else "FAIL"
    lines.append(f"{verdict}: max ratio {r['max_ratio']:.6f} <= 1 + {r['tolerance']:g} (a scene need not reach the bound)")
    return "\n".join(lines) + "\n"


def add_scene_options(p: argparse.ArgumentParser) -> None:
    """Add ``--scene`` and its camera, light and split options to ``aliasing validate``'s parser ``p``."""
    g = p.add_argument_group("your own scene (instead of probes; --f-over-n is then not used)")
    add_scene_arguments(g, g, "with a single-map --scheme")
    f_over_n = p._option_string_actions.get("--f-over-n")
    if f_over_n is not None and f_over_n.required:  # not needed with --scene; checked in run() without it
        f_over_n.required = False
        required = True
    else:
        required = False
    probes_run = p.get_default("run")

    def run(args: argparse.Namespace) -> int:
        if args.scene is None:
            for flag, value in (("--eye", args.eye), ("--camera", args.camera), ("--light-dir", args.light_dir), ("--splits", args.splits)):
                if value is not None:
                    raise ValueError(f"{flag} needs --scene FILE (probe validation is in eye space, with ZP<k> partitions)")
            if required and getattr(args, "f_over_n", None) is None:
                raise ValueError("--f-over-n is required (or --scene FILE)")
            return probes_run(args)
        if args.grid:
            raise ValueError("--grid validates probes over parameter grids; it does not take --scene")
        fmt = args.format or "text"
        if fmt not in ("text", "json"):
            raise ValueError(f"--format with --scene must be text or json, got {fmt!r}")
        try:
            fov = None if args.fov == "60" and args.camera else float(args.fov)
        except ValueError:
            raise ValueError(f"--fov must be a number, got {args.fov!r}") from None
        light = None if args.light_dir is not None else args.light
        st = setup(args.scene, eye=args.eye, target=args.target, up=args.up, camera=args.camera, near=args.near, far=args.far, fov=fov,
                   light_dir=args.light_dir, light=light, aspect=getattr(args, "aspect", 1.0))
        r = validate_scene(st, args.scheme, res=args.res, splits=args.splits, k=args.k, backend=args.backend, **partitioning.split_params(args.lam, args.param))
        if fmt == "json":
            sys.stdout.write(json.dumps(json_safe(r), indent=1) + "\n")
        else:
            sys.stdout.write(format_text(r))
        return 0 if r["passed"] else 1

    p.set_defaults(run=run)
