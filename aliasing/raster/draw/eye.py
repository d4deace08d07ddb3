"""The eye pass: what each image pixel sees (visible triangle, exact position, normal)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ... import _validation as check
from . import backends, compiled, gl, occlusion
from .core import CHUNK, _triangles, check_chunk, check_resolution, clip_near, zbuffer
from ...view import View, tan_theta

Array = NDArray[np.float64]

#: Pixels per band of the numpy outputs (temporaries of ~8 arrays this long stay in cache).
OUTPUT_BAND = 1 << 15


@dataclass(frozen=True)
class EyeBuffer:
    """What each image pixel sees.

    Attributes
    ----------
    position : ndarray (R, R, 3)
        Visible eye-space point [world units] (ray through the pixel centre ∩ the visible
        triangle's plane); NaN where nothing is visible.  Row j is v = (j + ½)/R (bottom up),
        column i is u = (i + ½)/R (left to right).
    normal : ndarray (R, R, 3)
        Unit face normal of the visible triangle, facing the eye; NaN where empty.
    triangle : ndarray of int64 (R, R)
        Visible triangle index, −1 where empty.
    resolution, fov, aspect
        R, the full (vertical) field of view [deg] and the view's width/height: the R × R
        pixels span the frustum, so at aspect ≠ 1 they are aspect : 1 wide.
    """

    position: Array
    normal: Array
    triangle: NDArray[np.int64]
    resolution: int
    fov: float
    aspect: float = 1.0


def _fov_tan(fov: float | View) -> tuple[float, float, float, float]:
    """(fov [deg], aspect, tan θ_x, tan θ_y) of a View (as it is) or of a loose field of view
    (validated here, once; a square view)."""
    if isinstance(fov, View):
        if fov.shape != ():
            raise ValueError(f"the view must be one frustum (scalar near, far, fov), got shape {fov.shape}")
        return fov.fov, fov.aspect, fov.tan_theta_x, fov.tan_theta
    fv = check.scalar(fov, "fov")
    t = float(tan_theta(fv))
    return fv, 1.0, t, t


@check.public
def project(points: ArrayLike, fov: float | View) -> tuple[Array, Array, Array]:
    """Image coordinates (u, v) ∈ [0, 1]² and depth z of eye-space points (square image).

    u = ½ + x/(2 z tanθ_x), v = ½ + y/(2 z tanθ_y), θ_y = fov/2; ``fov`` [deg] or a
    :class:`~aliasing.View` (its near and far are not used; tanθ_x = aspect·tanθ_y).
    """
    p = check.finite(points, "points")
    if p.shape[-1:] != (3,):
        raise ValueError(f"points must have shape (..., 3), got {p.shape}")
    if (p[..., 2] <= 0).any():
        raise ValueError("points must lie in front of the eye (depth z > 0)")
    _, _, tx, ty = _fov_tan(fov)
    return _project(p, tx, ty)


def _project(p: Array, tx: float, ty: float) -> tuple[Array, Array, Array]:
    """:func:`project` on checked points with tan θ_x = ``tx``, tan θ_y = ``ty``."""
    z = p[..., 2]
    return 0.5 + p[..., 0] / (2 * z * tx), 0.5 + p[..., 1] / (2 * z * ty), z


def eye_pass(triangles: ArrayLike, fov: float | View, resolution: int, *, near: float = 1e-3, chunk: int = CHUNK, backend: str = "numpy") -> EyeBuffer:
    """Render eye-space triangles with the perspective camera of the conventions.

    The eye is at the origin looking along +z, x right, y up, square image of full field of
    view ``fov`` [deg]; triangles are clipped at z = ``near`` [world units].  Visibility is
    a z-buffer on 1/z (affine in the image for planar triangles), rasterized nearest first
    with occlusion culling (:mod:`.occlusion`: the buffers of the plain z-buffer, ties to
    the highest triangle index); each visible pixel's position is recomputed exactly as the
    intersection of its pixel-centre ray with the triangle's plane.  A scene wholly behind
    the eye gives an empty buffer (all −1 / NaN).

    Parameters
    ----------
    triangles : array_like, shape (T, 3, 3)
        Eye-space triangles [world units].
    fov : float or View
        Full field of view [deg], in (0, 180), or a :class:`~aliasing.View` (its field of
        view and aspect; its near and far do not clip: ``near`` below does).  A non-square
        view is drawn on the same R × R pixels, which then span tan θ_x = aspect·tan θ_y:
        pixels aspect : 1 wide.  The perspective error measured from the buffer does not
        depend on the pixels' shape (:mod:`aliasing.raster.validate.measure`).
    resolution : int
        R, pixels per side, 1 ≤ R ≤ :data:`~aliasing.raster.MAX_RESOLUTION`.
    near : float
        Clipping distance [world units], > 0.
    chunk : int
        Rows, or texels, per vectorized step (bounds the temporaries), ≥ 1.
    backend : {"numpy", "numba", "gl"}
        ``"numba"`` runs the z-test and the per-pixel outputs as compiled loops
        (:mod:`.compiled`, the optional ``fast`` extra; ``chunk`` is not needed there): the
        same buffers bit for bit, about 2× faster at 2048² (benchmarks/README.md).
        ``"gl"`` draws the G-buffer's triangle ids with OpenGL (:mod:`.gl`, the optional
        ``gl`` extra; a hardware depth test on the perspective depth), and the positions and
        normals are then computed from them exactly as numpy does, in double precision: the
        same visible triangle but where the hardware's sub-pixel snapping of edges, or its
        24-bit depth test between near-coincident surfaces, decides otherwise.

    Returns
    -------
    EyeBuffer

    Raises
    ------
    ValueError
        Malformed ``triangles``, a parameter outside its range (named in the message), or
        ``backend="numba"`` without numba installed.

    Example
    -------
    >>> wall = np.array([[[-9, -9, 5], [9, -9, 5], [0, 9, 5]]], float)
    >>> eb = eye_pass(wall, 60.0, 8)
    >>> np.allclose(eb.position[4, 4], [0.5 * 5 * np.tan(np.pi / 6) / 4, 0.5 * 5 * np.tan(np.pi / 6) / 4, 5.0])
    True
    """
    tri = _triangles(triangles)
    res = check_resolution(resolution)
    fv, aspect, tx, ty = _fov_tan(fov)
    zc = float(check.positive(check.scalar(near, "near"), "near"))
    chunk = check_chunk(chunk)
    name = backends.check(backend, "eye_pass")
    if name == "gl":
        ids = gl.eye_ids(tri, float(tx), res, zc, tan_y=float(ty))
        return _buffer(tri, ids.ravel(), np.arange(tri.shape[0]), res, fv, aspect, tx, ty, _outputs_numpy)
    draw, outputs = KERNELS[name]()
    clipped, src = clip_near(tri, zc)
    if clipped.shape[0] == 0:
        empty = np.full((res, res, 3), np.nan)
        return EyeBuffer(empty, empty.copy(), np.full((res, res), -1, np.int64), res, fv, aspect)
    u, v, z = _project(clipped, tx, ty)
    # depth key: -1/z is affine in (u, v) over a plane and increases with z; the eye sees
    # much overdraw, so hidden triangles and pieces of spans are culled (front_to_back)
    key = np.stack([u, v, -1.0 / z], axis=-1)
    dm = zbuffer(key, res, np.ones((key.shape[0], 3)), (np.arange(res) + 0.5) / res, True, chunk, front_to_back=True, draw=draw)
    return _buffer(tri, dm.triangle.ravel(), src, res, fv, aspect, tx, ty, outputs)


def image_pass(triangles: ArrayLike, fov: float, width: int, height: int, *, near: float = 1e-3) -> tuple[Array, Array, NDArray[np.int64]]:
    """The eye pass of a ``width`` × ``height`` image (any two sizes): per pixel, rows bottom up, the eye-space position
    [world units] and unit normal (NaN where nothing is seen) and the visible triangle (−1).

    :func:`eye_pass` draws square R × R images; here R = max(width, height) and a shear of eye space
    (x′ = a x + b z, y′ = c y + d z: linear, so planes, visibility and the near plane are kept) puts the
    image's pixel centres, at vertical field of view ``fov`` [deg] and aspect width / height, on the
    square's first ``width`` columns and ``height`` rows.

    Examples
    --------
    >>> ground = np.array([[[-50.0, -1.0, 1.0], [50.0, -1.0, 1.0], [0.0, -1.0, 100.0]]])   # 1 below the eye, ahead
    >>> pos, nrm, tri = image_pass(ground, 50.0, 5, 2)
    >>> tri.tolist(), np.round(nrm[0, 2], 9).tolist()            # the lower row sees it, the upper one the sky
    ([[0, 0, 0, 0, 0], [-1, -1, -1, -1, -1]], [0.0, 1.0, 0.0])
    >>> t = tan_theta(50.0); bool(np.allclose(pos[0, 2], [0.0, -1.0, 1.0 / (0.5 * t)]))   # the centre pixel's ray (0, −t/2, 1)
    True
    """
    w = check.whole(width, "width", 1, 16384, " [px]")
    h = check.whole(height, "height", 1, 16384, " [px]")
    r = max(w, h)
    t = float(tan_theta(fov))
    tx = t * w / h  # the image's horizontal half-width at unit depth
    # the square's pixel centres (i + ½)/R, i < W (j < H), fall on the image's (i + ½)/W ((j + ½)/H)
    shear = np.array([[t * w / (r * tx), 0.0, t * (w / r - 1)], [0.0, h / r, t * (h / r - 1)], [0.0, 0.0, 1.0]])
    buf = eye_pass(np.asarray(triangles, float) @ shear.T, float(fov), r, near=near)
    p = buf.position[:h, :w] @ np.linalg.inv(shear).T  # back to eye space: p = S⁻¹ p′
    n = buf.normal[:h, :w] @ shear  # planes: n ∝ Sᵀ n′ (facing the eye is kept: n·p = n′·p′)
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    return p, n, buf.triangle[:h, :w]


def _buffer(tri: Array, tri_id: NDArray[np.int64], src: NDArray[np.int64], res: int, fv: float, aspect: float, tx: float, ty: float, outputs) -> EyeBuffer:
    """The eye buffer of the visible (drawn) triangle ids ``tri_id`` (−1 where empty; ``src``: their input indices)."""
    # exact positions: the ray (X, Y, 1) through the pixel centre ∩ the source triangle's
    # plane n·p = n·a, so p = λ(X, Y, 1) with λ = n·a / (n_x X + n_y Y + n_z)
    c = (np.arange(res) + 0.5) / res
    X = (2 * c - 1) * tx  # columns
    Y = (2 * c - 1) * ty  # rows (the same numbers as X at aspect 1)
    a, b, cc = tri[:, 0], tri[:, 1], tri[:, 2]
    nrm = np.cross(b - a, cc - a)
    with np.errstate(divide="ignore", invalid="ignore"):  # a zero-area triangle (never drawn) gets a NaN normal
        nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    ident, position, normal = outputs(tri_id, src, X, Y, nrm, (nrm * a).sum(-1), res)
    return EyeBuffer(position, normal, ident, res, fv, aspect)


def _outputs_numpy(tri_id: NDArray[np.int64], src: NDArray[np.int64], X: Array, Yr: Array, nrm: Array, lam_num: Array, res: int) -> tuple[NDArray[np.int64], Array, Array]:
    """Source ids, positions and normals per pixel (:func:`eye_pass`), vectorized.

    Per-triangle tables (one per coordinate) end in a NaN row, which empty pixels (id −1)
    pick: no masks over the image.  Bands of :data:`OUTPUT_BAND` pixels are done at a time,
    so the temporaries stay in cache and each output is written once.
    """
    ident = np.append(src, -1).take(tri_id).reshape(res, res)  # -1 (empty) picks the appended -1
    nan = np.array([np.nan])
    nx, ny, nz = (np.concatenate([nrm[:, i], nan]) for i in range(3))
    num = np.concatenate([lam_num, nan])
    position = np.empty((res, res, 3))
    normal = np.empty((res, res, 3))
    step = max(1, OUTPUT_BAND // res)
    with np.errstate(divide="ignore", invalid="ignore"):
        for r0 in range(0, res, step):
            ids, Y = ident[r0:r0 + step], Yr[r0:r0 + step, None]
            gx, gy, gz = nx.take(ids), ny.take(ids), nz.take(ids)
            den = gx * X
            den += gy * Y
            den += gz  # n·(X, Y, 1), summed in a dot product's order
            lam = num.take(ids)
            lam /= den
            pos, nor = position[r0:r0 + step], normal[r0:r0 + step]
            np.multiply(X, lam, out=pos[..., 0])
            np.multiply(Y, lam, out=pos[..., 1])
            pos[..., 2] = lam
            flip = den > 0  # face the eye: −n where n·ray > 0
            for i, g in enumerate((gx, gy, gz)):
                np.negative(g, out=g, where=flip)
                nor[..., i] = g
    return ident, position, normal


def _outputs_numba(tri_id: NDArray[np.int64], src: NDArray[np.int64], X: Array, Y: Array, nrm: Array, lam_num: Array, res: int) -> tuple[NDArray[np.int64], Array, Array]:
    """:func:`_outputs_numpy` in one compiled pass (:func:`.compiled.eye_outputs`)."""
    ident = np.empty(res * res, np.int64)
    position = np.empty((res * res, 3))
    normal = np.empty((res * res, 3))
    compiled.eye_outputs(tri_id, src, X, Y, np.ascontiguousarray(nrm), lam_num, ident, position, normal)
    return ident.reshape(res, res), position.reshape(res, res, 3), normal.reshape(res, res, 3)


def _numpy():
    return occlusion.draw_visible, _outputs_numpy


def _numba():
    return compiled.draw, _outputs_numba


#: Kernels of :func:`eye_pass` per backend (:mod:`.backends`): name → loader of (how a group
#: of triangles is drawn, per-pixel outputs).
KERNELS = {"numpy": _numpy, "numba": _numba}
