"""Filament 1.53.4 from npm: a directional light with the C++ defaults, rendered and measured only (:class:`Filament`)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from ... import _validation as check
from ...view import tan_theta


Array = NDArray[np.float64]


def eye_buffers(scene, w: int, h: int) -> tuple[Array, Array, NDArray[np.bool_]]:
    """World positions and normals of the ``w`` × ``h`` pixels the scene's camera sees (GL rows bottom-up), and where it sees a surface.

    The toolkit's eye pass (:func:`aliasing.raster.draw.eye.eye_pass`) on a square grid of ``w``
    pixels whose middle ``h`` rows are the image where ``w − h`` is even and ≥ 0, else through
    :func:`aliasing.raster.draw.eye.image_pass`.  No far clip.  Where nothing is hit, positions
    and normals are 0.

    Examples
    --------
    >>> from aliasing.frames.scenes import frame_scene
    >>> fs = frame_scene("boxes", near=0.5, far=30.0, fov=50.0, aspect=1.5, boxes=1, ground_cells=1)
    >>> pos, nrm, hit = eye_buffers(fs, 24, 16)
    >>> pos.shape, bool(hit[0].any()), bool(hit[-1].any())       # bottom row: the ground; top row: the sky
    ((16, 24, 3), True, False)
    >>> odd = eye_buffers(fs, 25, 16)                                  # 25 − 16 is odd: the sheared pass
    >>> odd[0].shape, bool(np.array_equal(odd[2], eye_buffers(fs, 25, 16)[2])), bool(odd[2][0].all())
    ((16, 25, 3), True, True)
    """
    from ...raster.draw.eye import eye_pass, image_pass

    w, h = check.whole(w, "w", 1, 16384, " [px]"), check.whole(h, "h", 1, 16384, " [px]")
    cam = scene.camera
    if (w - h) % 2 or w < h:  # no square grid has the image as its middle rows: the sheared pass
        pos_e, nrm_e, _ = image_pass(cam.to_eye(scene.triangles), float(cam.fov), w, h, near=cam.near)
    else:
        half = np.arctan(tan_theta(cam.fov) * w / h)
        eb = eye_pass(cam.to_eye(scene.triangles), float(np.degrees(2 * half)), w, near=cam.near)
        k0 = (w - h) // 2
        pos_e, nrm_e = eb.position[k0:k0 + h], eb.normal[k0:k0 + h]          # rows bottom-up, as WebGL's
    hit = np.isfinite(pos_e[..., 0])
    pos = np.where(hit[..., None], np.nan_to_num(pos_e) @ cam.rotation + cam.eye, 0.0)
    nrm = np.where(hit[..., None], np.nan_to_num(nrm_e) @ cam.rotation, 0.0)
    return pos, nrm, hit


@dataclass(frozen=True)
class Filament:
    """Filament 1.53.4 from npm (``filament``: filament.js + filament.wasm, WebGL 2), a DIRECTIONAL light with shadows.

    Rendered, measured, not predicted.  What the npm release allows:

    * **Settings.**  Its JavaScript binding registers ``LightManager$ShadowOptions`` in the typings
      (``filament.d.ts``) and in ``Filament.shadowOptions`` (filament.js) but not the value type
      behind ``LightManager.Builder.shadowOptions`` and ``LightManager.setShadowOptions``: both
      throw "Cannot call … due to unbound types" (``web/filament-js/jsbindings.cpp``, google/filament
      as stored, commit 4c8b73e5: the value object's field ``transform`` is a ``mat4f``, a type embind
      never registers; only the ``flatmat4`` wrapper is).  The light keeps the C++ defaults of
      ``ShadowOptions`` (``mapSize`` 1024, one cascade, ``constantBias`` 0.001, ``normalBias`` 1,
      ``polygonOffsetConstant`` 0.5, ``polygonOffsetSlope`` 2, ``stable`` false, ``lispsm`` true);
      any other value is refused.  ``View.setShadowType`` is not bound either (PCF).
    * **Shadow factor.**  No material can output it (the package has no material compiler): the
      page draws the frame twice, receivers on and off (``RenderableManager.setReceiveShadows``),
      post-processing off, exposure 1, no indirect light, and the factor is the ratio of the
      two 8-bit colours where the unshadowed one is lit (:meth:`readback`).  A colour c ≥ 1 of 255
      gives the factor to ±(0.5/c)(1 + factor); a surface facing away from the sun is 0 in both
      frames and is read as shadowed (0).
    * **Positions and normals.**  From the toolkit's eye pass (:func:`aliasing.raster.draw.eye.eye_pass`)
      of the scene through the camera, checked against what the engine drew (``details``).
    * **Light matrices.**  Not readable from JavaScript: ``px_per_texel`` is not measured, and
      the exact reference shadows are drawn through the toolkit's own light box around the
      scene (:meth:`reference_matrix`, 2048² texels).

    Examples
    --------
    >>> from aliasing import setups
    >>> f = Filament()
    >>> s = f.settings({"mapSize": 1024})                       # the defaults only
    >>> s["shadowCascades"], f.cast_side(s), f.predicted(s) is not None
    (1, 'front', True)
    >>> f.settings({"mapSize": 2048})
    Traceback (most recent call last):
    ...
    ValueError: mapSize: Filament 1.53.4's JavaScript binding cannot set ShadowOptions (its value type is unbound), the frames render the defaults only (mapSize=1024), got 2048
    >>> [len(a) for a in f.measured_cascades(s, None, None)]    # the light matrices are not readable
    [0, 0, 0]
    >>> f.from_setup(setups.build("filament", {}, "near=0.5,far=60,fov=50,aspect=16:9,height=144", "35@30"))["mapSize"]
    1024
    >>> rb = f.readback(page_answer, scene, sun)  # doctest: +SKIP
    """

    engine: str = "filament"
    #: ShadowOptions' defaults (filament/include/filament/LightManager.h; filament.js ``Filament.shadowOptions``)
    defaults: dict = field(default_factory=lambda: {
        "mapSize": 1024, "shadowCascades": 1, "constantBias": 0.001, "normalBias": 1.0, "shadowFar": 0.0, "shadowNearHint": 1.0,
        "shadowFarHint": 100.0, "stable": False, "polygonOffsetConstant": 0.5, "polygonOffsetSlope": 2.0, "screenSpaceContactShadows": False,
        "stepCount": 8, "maxShadowDistance": 0.3})
    #: the exact reference's light-map side [texels]
    REFERENCE = 2048

    def settings(self, given: dict | None = None) -> dict:
        """The ShadowOptions (defaults filled in); anything but the defaults is refused (the binding cannot set them)."""
        given = dict(given or {})
        unknown = sorted(set(given) - set(self.defaults))
        if unknown:
            raise ValueError(f"unknown Filament setting {unknown[0]!r}; known: {', '.join(sorted(self.defaults))}")
        for k, v in given.items():
            if v != self.defaults[k]:
                raise ValueError(f"{k}: Filament 1.53.4's JavaScript binding cannot set ShadowOptions (its value type is unbound), "
                                 f"the frames render the defaults only ({k}={self.defaults[k]!r}), got {v!r}")
        return {**self.defaults}

    def predicted(self, s: dict) -> str | None:
        """Why the frame is not predicted."""
        return ("Filament's shadow fit (LiSPSM by default, fitted to the scene's casters and receivers) and its light matrices "
                "are not modelled and cannot be read back from the npm binding")

    def cast_side(self, s: dict) -> str:
        """The faces drawn into the map: front faces (back faces culled, as in the colour pass)."""
        return "front"

    def measured_cascades(self, s: dict, camera, rb) -> tuple[Array, Array, Array]:
        """Not readable from the binding: empty (``px_per_texel`` is an empty list)."""
        return np.zeros(0), np.zeros(0), np.zeros(0)

    @staticmethod
    def reference_matrix(triangles: Array, sun: Array) -> Array:
        """An orthographic light matrix (world → [0, 1]³, column vectors) around all ``triangles`` along ``-sun``.

        Examples
        --------
        >>> tri = np.array([[[0, 0, 0], [1, 0, 0], [0, 0, 1]]], float)
        >>> from aliasing.frames import predict
        >>> m = Filament.reference_matrix(tri, np.array([0.0, 1.0, 0.0]))
        >>> p = predict.to_map(m, tri[0])
        >>> bool(((p >= 0) & (p <= 1)).all())
        True
        """
        from ... import _validation as check

        tri = check.triangles(triangles)
        sv = check.direction(sun)
        d = -sv / np.linalg.norm(sv)                              # along the light
        up = np.array([0.0, 0.0, 1.0]) if abs(d[1]) > 0.9 else np.array([0.0, 1.0, 0.0])
        x = np.cross(up, d)
        x /= np.linalg.norm(x)
        y = np.cross(d, x)
        rot = np.array([x, y, d])
        p = tri.reshape(-1, 3) @ rot.T
        lo, hi = p.min(axis=0), p.max(axis=0)
        pad = 1e-3 * float(np.max(hi - lo)) + 1e-9
        lo, hi = lo - pad, hi + pad
        side = float(np.max(hi[:2] - lo[:2]))
        scale = np.array([1 / side, 1 / side, 1 / (hi[2] - lo[2])])
        m = np.eye(4)
        m[:3, :3] = rot * scale[:, None]
        m[:3, 3] = -lo * scale
        return m

    def readback(self, out: dict, scene, sun: Array) -> dict:
        """The page's two 8-bit frames as the read-back the other pages give (base64 float32 buffers).

        ``shadow`` = (factor, −1, n·l): factor = lit/unlit colour where the unlit colour is ≥ 1 of 255,
        else 0; ``position``/``normal`` from the toolkit's eye pass through the scene's camera;
        ``cascades``: the reference light box (:meth:`reference_matrix`).  ``checks``: the camera
        matrices against the toolkit's, and the pixels the engine drew against the eye pass.
        """
        import base64

        w, h = int(out["width"]), int(out["height"])
        if (w - h) % 2:
            raise ValueError(f"Filament's frames need an even width − height (the eye pass's square pixels), got {w}×{h}")
        lit, unlit = (np.frombuffer(base64.b64decode(out[k]), np.uint8).reshape(h, w, 4).astype(float) for k in ("lit", "unlit"))
        cam = scene.camera
        pos, nrm, hit = eye_buffers(scene, w, h)   # no far clip: Filament projects with an infinite far (getProjectionMatrix)
        sun = np.asarray(sun, float) / np.linalg.norm(sun)
        ndotl = nrm @ sun
        g_lit, g_un = lit[..., 1], unlit[..., 1]
        factor = np.where(g_un >= 1, g_lit / np.maximum(g_un, 1), 0.0)
        engine_drawn = ~((unlit[..., 0] == 0) & (unlit[..., 1] == 0) & (unlit[..., 2] == 255))   # the clear colour is pure blue
        f32 = lambda a: base64.b64encode(np.ascontiguousarray(a, np.float32).tobytes()).decode()  # noqa: E731
        one = np.ones((h, w))
        shadow = np.stack([factor, -one, np.clip(ndotl, 0, 1), one], -1)
        position = np.concatenate([pos, hit[..., None].astype(float)], -1)
        normal = np.concatenate([nrm, one[..., None]], -1)
        facing = hit & (ndotl > 0.05)
        lit_enough = facing & engine_drawn & (ndotl > 0.2) & (g_un > 0)
        expect_v = np.array([[*cam.rotation[0], -cam.rotation[0] @ cam.eye], [*cam.rotation[1], -cam.rotation[1] @ cam.eye],
                             [*-cam.rotation[2], cam.rotation[2] @ cam.eye], [0, 0, 0, 1]])
        f = 1 / tan_theta(cam.fov)
        expect_p = np.array([[f * h / w, 0, 0, 0], [0, f, 0, 0], [0, 0, -1, -2 * cam.near], [0, 0, -1, 0]])   # Filament: infinite far
        checks = {
            "view_vs_toolkit": float(np.max(np.abs(np.asarray(out["view"], float).reshape(4, 4).T - expect_v))),
            "projection_vs_toolkit": float(np.max(np.abs(np.asarray(out["projection"], float).reshape(4, 4).T - expect_p))),
            "coverage_vs_engine": float(np.mean(engine_drawn != hit)),
            "unlit_dark_facing": float(np.mean(g_un[facing] == 0)) if facing.any() else None,
            "unlit_min_facing": float(g_un[facing].min()) if facing.any() else None,
            "relit_changed": out.get("relit_changed"),
            # the unshadowed colour per n·l of the eye pass's normals (BRDF · intensity: constant for a diffuse surface)
            "unlit_per_ndotl": np.percentile(g_un[lit_enough] / 255 / ndotl[lit_enough], [5, 50, 95]).tolist() if lit_enough.any() else None,
        }
        m = self.reference_matrix(scene.triangles, sun)
        rest = {k: v for k, v in out.items() if k not in ("lit", "unlit")}
        return {**rest, "shadow": f32(shadow), "position": f32(position), "normal": f32(normal), "checks": checks,
                "cascades": [{"matrix": m.T.ravel().tolist(), "size": [self.REFERENCE, self.REFERENCE], "reference": True}]}

    def from_setup(self, setup) -> dict:
        """The settings of a Filament :class:`aliasing.setups.Setup`: the ShadowOptions, which must be the defaults,
        for an image whose width − height is even (:meth:`readback`)."""
        s = dict(setup.settings)
        cam = setup.camera
        w = round(cam.aspect * cam.height)
        if (w - cam.height) % 2:
            raise ValueError(f"--camera: Filament's frames need an even width − height (the eye pass's square pixel grid), "
                             f"got {w}×{cam.height}: change the height by one")
        if s.get("View.shadowType", "PCF") != "PCF":
            raise ValueError(f"View.shadowType: Filament 1.53.4's JavaScript binding has no View.setShadowType, the frames render PCF, got {s['View.shadowType']!r}")
        if s.get("lispsm", True) is not True:
            raise ValueError("lispsm: Filament 1.53.4's JavaScript binding cannot set ShadowOptions, the frames render lispsm=true (the C++ default)")
        for i, v in enumerate((0.125, 0.25, 0.5)):
            if s.get(f"cascadeSplitPositions[{i}]", v) != v:
                raise ValueError(f"cascadeSplitPositions[{i}]: Filament 1.53.4's JavaScript binding cannot set ShadowOptions, the frames render {v}")
        return self.settings({k: s[k] for k in self.defaults if k in s})
