"""Babylon.js 9.35's cascade matrices, predicted as ``CascadedShadowGenerator._computeMatrices`` builds them.

Each cascade (Lights/Shadows/cascadedShadowGenerator.pure.js, ``_computeFrustumInWorldSpace``
:437, ``_computeCascadeFrustum`` :474, ``_computeMatrices`` :364; Babylon.js's left-handed
world, which is the job's world mirrored in z):

* the camera's view (the FreeCamera's ``setTarget`` and ``_getViewMatrix``) times its
  ``PerspectiveFovLH`` (the render's width / height as aspect), inverted, takes the NDC cube's
  corners to the world; the slice's 8 corners cut the near-to-far corner rays at the cascade's
  breaks, and c is their centroid;
* ``stabilizeCascades``: a cube of half side r = ⌈16 · (the corners' largest distance from c)⌉ / 16 about c; otherwise
  the corners' box in the frame ``Matrix.LookAtLH(c, c + d, Up)``;
* the shadow camera at c + d · min z, ``LookAtLH(camera, c, Up)``; its depth range [0, box depth]
  tightened to the casters' bounding box with depth clamp (z min = max(0, casters' min),
  z max = max(z min + 1, min(box depth, casters' max)));
* ``Matrix.OrthoOffCenterLH`` of the box's x and y and that depth range, and the world origin
  rounded to a whole texel of the map (the projection translated by the rounding offset).

The result is returned as the read-back's matrices are (:func:`aliasing.frames.readback.decode`):
world of the job → (s, t, depth) in [0, 1]³, column vectors.

**Float32.** ``Matrix`` keeps its 16 values in a ``Float32Array`` (Babylon.js without
``useHighPrecisionMatrix``, as the pages run it); ``Vector3`` holds JS numbers (float64).  Every
matrix the chain stores is rounded to float32 here, where the engine stores it (the camera's
``LookAtLH``, its inverse, the Euler angles' rotation matrix, the view, the projection, their
product and its inverse; each cascade's light frame, view, projection, texel shift and their
products), and everything between (``Vector3.TransformCoordinates``, the corners, the centroid,
the extents, the rounding of the origin) stays float64, in the engine's order of operations.
The matrices so predicted equal the engine's bit for bit (node, ``NullEngine``, for the boxes
and the city; ERRATA F6); ``float32=False`` gives the float64 arithmetic the engine would do
with high-precision matrices.

Examples
--------
>>> from aliasing.frames.scenes import frame_scene, sun_direction
>>> fs = frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=4, ground_cells=2)
>>> from aliasing.frames.models import MODELS
>>> m = matrices(MODELS["babylon"].settings({"stabilizeCascades": True}), fs.camera, sun_direction(35, 30, fs.camera), fs.triangles)
>>> m.shape
(4, 4, 4)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import _validation as check

Array = NDArray[np.float64]
MIRROR = np.diag([1.0, 1.0, -1.0])
UP = np.array([0.0, 1.0, 0.0])
# CascadedShadowGenerator._FrustumCornersNdcSpace (cascadedShadowGenerator.pure.js:1001): near corners, then far
NDC = np.array([[-1.0, 1, -1], [1, 1, -1], [1, -1, -1], [-1, -1, -1], [-1, 1, 1], [1, 1, 1], [1, -1, 1], [-1, -1, 1]])


def look_at_lh(eye: Array, target: Array, up: Array = UP) -> Array:
    """``Matrix.LookAtLH`` as a 4×4 column-vector matrix (world → view; x ∝ up × z, z towards the target).

    Parameters
    ----------
    eye, target : array_like (3,)
        The viewer and the point it looks at [world units], finite, different.
    up : array_like (3,)
        The world up (x is ±x of the world when ``up`` is along the view).

    Returns
    -------
    ndarray (4, 4)
        World → view [world units] (column vectors).

    Examples
    --------
    >>> v = look_at_lh(np.array([0.0, 0.0, -5.0]), np.zeros(3))   # looking along +z from 5 units before the origin
    >>> (v @ [0.0, 0.0, 0.0, 1.0]).tolist()                        # the target lies 5 units ahead
    [0.0, 0.0, 5.0, 1.0]
    """
    eye, target, up = (check.finite(v, n) for v, n in ((eye, "eye"), (target, "target"), (up, "up")))
    if not np.linalg.norm(target - eye) > 0:
        raise ValueError("target must differ from eye")
    z = target - eye
    z = z / np.linalg.norm(z)
    x = np.cross(up, z)
    nx = np.linalg.norm(x)
    x = np.array([1.0, 0.0, 0.0]) if nx == 0 else x / nx
    y = np.cross(z, x)
    y /= np.linalg.norm(y)
    v = np.eye(4)
    v[:3, :3] = np.stack([x, y, z])
    v[:3, 3] = -v[:3, :3] @ eye
    return v


def ortho_off_center_lh(left: float, right: float, bottom: float, top: float, near: float, far: float) -> Array:
    """``Matrix.OrthoOffCenterLH`` (NDC z in [−1, 1]) as a 4×4 column-vector matrix.

    Parameters
    ----------
    left, right, bottom, top : float
        The box's sides in view x and y [world units], right ≠ left, top ≠ bottom.
    near, far : float
        Its depth range along view z [world units], far ≠ near.

    Returns
    -------
    ndarray (4, 4)
        View → NDC (column vectors).

    Examples
    --------
    >>> p = ortho_off_center_lh(-2.0, 2.0, -1.0, 1.0, 0.0, 10.0)
    >>> (p @ [2.0, -1.0, 10.0, 1.0]).tolist()                      # the box's corner on the far plane
    [1.0, -1.0, 1.0, 1.0]
    """
    if not (right != left and top != bottom and far != near) or not np.all(np.isfinite([left, right, bottom, top, near, far])):
        raise ValueError("left, right, bottom, top, near and far must be finite with right ≠ left, top ≠ bottom and far ≠ near")
    p = np.diag([2 / (right - left), 2 / (top - bottom), 2 / (far - near), 1.0])
    p[:3, 3] = [(left + right) / (left - right), (top + bottom) / (bottom - top), -(far + near) / (far - near)]
    return p


def _r(x, float32: bool) -> Array:
    """A store into ``Matrix._m`` (a ``Float32Array``): rounded to float32, or kept (float64)."""
    x = np.asarray(x, np.float64)
    return x.astype(np.float32).astype(np.float64) if float32 else x


def _normalize(v: Array) -> Array:
    """``Vector3.normalize``: scaled by 1/length (JS numbers), unchanged at length 0 or 1."""
    n = float(np.sqrt(v @ v))
    return v if n in (0.0, 1.0) else v * (1.0 / n)


def _look_at_values(eye: Array, target: Array, up: Array) -> Array:
    """``Matrix.LookAtLHToRef``'s 16 values as a row-vector matrix (math.vector.pure.js:6925), before they are stored."""
    z = _normalize(target - eye)
    x = np.cross(up, z)
    x2 = float(x @ x)
    x = np.array([1.0, x[1], x[2]]) if x2 == 0 else x * (1.0 / np.sqrt(x2))
    y = _normalize(np.cross(z, x))
    b = np.zeros((4, 4))
    b[:3, 0], b[:3, 1], b[:3, 2] = x, y, z
    b[3] = [-(x @ eye), -(y @ eye), -(z @ eye), 1.0]
    return b


def _invert(m: Array) -> Array:
    """``InvertMatrixToArray`` (ThinMaths/thinMath.matrix.functions.js:159): the adjugate over the determinant, in JS numbers."""
    (m00, m01, m02, m03), (m10, m11, m12, m13), (m20, m21, m22, m23), (m30, m31, m32, m33) = m.tolist()
    d2233, d2133, d2132 = m22 * m33 - m32 * m23, m21 * m33 - m31 * m23, m21 * m32 - m31 * m22
    d2033, d2032, d2031 = m20 * m33 - m30 * m23, m20 * m32 - m22 * m30, m20 * m31 - m30 * m21
    c00 = +(m11 * d2233 - m12 * d2133 + m13 * d2132)
    c01 = -(m10 * d2233 - m12 * d2033 + m13 * d2032)
    c02 = +(m10 * d2133 - m11 * d2033 + m13 * d2031)
    c03 = -(m10 * d2132 - m11 * d2032 + m12 * d2031)
    det = m00 * c00 + m01 * c01 + m02 * c02 + m03 * c03
    if det == 0:
        raise ValueError("the matrix is singular")
    inv = 1 / det
    d1233, d1133, d1132 = m12 * m33 - m32 * m13, m11 * m33 - m31 * m13, m11 * m32 - m31 * m12
    d1033, d1032, d1031 = m10 * m33 - m30 * m13, m10 * m32 - m30 * m12, m10 * m31 - m30 * m11
    d1223, d1123, d1122 = m12 * m23 - m22 * m13, m11 * m23 - m21 * m13, m11 * m22 - m21 * m12
    d1023, d1022, d1021 = m10 * m23 - m20 * m13, m10 * m22 - m20 * m12, m10 * m21 - m20 * m11
    c10 = -(m01 * d2233 - m02 * d2133 + m03 * d2132)
    c11 = +(m00 * d2233 - m02 * d2033 + m03 * d2032)
    c12 = -(m00 * d2133 - m01 * d2033 + m03 * d2031)
    c13 = +(m00 * d2132 - m01 * d2032 + m02 * d2031)
    c20 = +(m01 * d1233 - m02 * d1133 + m03 * d1132)
    c21 = -(m00 * d1233 - m02 * d1033 + m03 * d1032)
    c22 = +(m00 * d1133 - m01 * d1033 + m03 * d1031)
    c23 = -(m00 * d1132 - m01 * d1032 + m02 * d1031)
    c30 = -(m01 * d1223 - m02 * d1123 + m03 * d1122)
    c31 = +(m00 * d1223 - m02 * d1023 + m03 * d1022)
    c32 = -(m00 * d1123 - m01 * d1023 + m03 * d1021)
    c33 = +(m00 * d1122 - m01 * d1022 + m02 * d1021)
    return np.array([[c00, c10, c20, c30], [c01, c11, c21, c31], [c02, c12, c22, c32], [c03, c13, c23, c33]]) * inv


def _transform_coordinates(v: Array, m: Array) -> Array:
    """``Vector3.TransformCoordinatesFromFloatsToRef`` (math.vector.pure.js:2184) of row vectors ``v`` (..., 3): JS numbers."""
    h = v @ m[:3] + m[3]
    return h[..., :3] * (1 / h[..., 3:])


def _camera_view(eye: Array, target: Array, up: Array, float32: bool) -> Array:
    """The FreeCamera's view matrix as the page sets it up (position, upVector, setTarget), Babylon's world.

    ``TargetCamera.setTarget`` (Cameras/targetCamera.pure.js:262) turns the target into Euler
    angles through a float32 ``LookAtLH``, its inverse and a quaternion; ``_getViewMatrix`` (:455)
    rebuilds the target from a float32 ``RotationYawPitchRoll`` matrix and stores ``LookAtLH``
    of the position, that target and the camera's up.
    """
    pos, up = eye.copy(), _normalize(up)
    focal = float(np.sqrt((target - pos) @ (target - pos)))
    if focal == 0:
        raise ValueError("the camera's target must differ from its eye")
    if pos[2] == target[2]:
        pos[2] += 0.001  # Epsilon (Maths/math.constants.js:22)
    t = _r(_invert(_r(_look_at_values(pos, target, UP), float32)), float32)
    (m11, m12, m13, _), (m21, m22, m23, _), (m31, m32, m33, _) = t.T[:3].tolist()  # m12 = data[4]: the column-major reading
    trace = m11 + m22 + m33  # Quaternion.FromRotationMatrixToRef (math.vector.pure.js:4653)
    if trace > 0:
        s = 0.5 / np.sqrt(trace + 1.0)
        q = (0.25 / s, (m32 - m23) * s, (m13 - m31) * s, (m21 - m12) * s)
    elif m11 > m22 and m11 > m33:
        s = 2.0 * np.sqrt(1.0 + m11 - m22 - m33)
        q = ((m32 - m23) / s, 0.25 * s, (m12 + m21) / s, (m13 + m31) / s)
    elif m22 > m33:
        s = 2.0 * np.sqrt(1.0 + m22 - m11 - m33)
        q = ((m13 - m31) / s, (m12 + m21) / s, 0.25 * s, (m23 + m32) / s)
    else:
        s = 2.0 * np.sqrt(1.0 + m33 - m11 - m22)
        q = ((m21 - m12) / s, (m13 + m31) / s, (m23 + m32) / s, 0.25 * s)
    qw, qx, qy, qz = (float(v) for v in q)
    zy = qy * qz - qx * qw  # Quaternion.toEulerAnglesToRef (math.vector.pure.js:4521); roll set to 0
    if abs(zy) > 0.4999999:
        yaw, pitch = 2 * np.arctan2(qy, qw), (np.pi / 2 if zy < 0 else -np.pi / 2)
    else:
        yaw, pitch = np.arctan2(2.0 * (qz * qx + qy * qw), qz * qz - qx * qx - qy * qy + qw * qw), np.arcsin(-2.0 * zy)
    sp, cp, sy, cy = np.sin(pitch * 0.5), np.cos(pitch * 0.5), np.sin(yaw * 0.5), np.cos(yaw * 0.5)
    x, y, z, w = cy * sp, sy * cp, -sy * sp, cy * cp  # Quaternion.RotationYawPitchRollToRef (:4938), roll 0
    rot = _r(np.array([[1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (z * x - y * w), 0],  # Matrix.FromQuaternionToRef (:7561)
                       [2 * (x * y - z * w), 1 - 2 * (z * z + x * x), 2 * (y * z + x * w), 0],
                       [2 * (z * x + y * w), 2 * (y * z - x * w), 1 - 2 * (y * y + x * x), 0], [0, 0, 0, 1.0]]), float32)
    return _r(_look_at_values(pos, pos + _transform_coordinates(np.array([0.0, 0.0, focal]), rot), up), float32)


def _breaks(near: float, far: float, shadow_max_z: float | None, k: int, lam: float) -> tuple[Array, Array]:
    """``_splitFrustum`` (cascadedShadowGenerator.pure.js:351): each cascade's (prevBreakDistance, breakDistance), JS numbers."""
    camera_range = far - near
    smz = far if shadow_max_z is None else float(shadow_max_z)
    max_distance = min((smz - near) / (far - near), 1.0) if near <= smz < far else 1.0
    min_z, max_z = near + 0.0 * camera_range, near + max_distance * camera_range
    rng, ratio = max_z - min_z, max_z / min_z
    brk = []
    for i in range(k):
        p = (i + 1) / k
        log, uniform = min_z * ratio**p, min_z + rng * p
        brk.append((lam * (log - uniform) + uniform - near) / camera_range)
    return np.array([0.0, *brk[:-1]]), np.array(brk)


KEYS = ("mapSize", "numCascades", "lambda", "stabilizeCascades", "depthClamp", "shadowMaxZ")


def _settings(settings: dict) -> dict:
    if not isinstance(settings, dict) or any(k not in settings for k in KEYS):
        raise ValueError(f"settings must be Babylon.js's filled settings (aliasing.frames.models.MODELS['babylon'].settings), with {', '.join(KEYS)}")
    s = {k: settings[k] for k in KEYS}
    checks = [("mapSize", isinstance(s["mapSize"], (int, np.integer)) and 1 <= s["mapSize"] <= 16384, "a whole number of texels in [1, 16384]"),
              ("numCascades", isinstance(s["numCascades"], (int, np.integer)) and 1 <= s["numCascades"] <= 4, "a whole number in [1, 4]"),
              ("lambda", np.isfinite(s["lambda"]) and 0 <= s["lambda"] <= 1, "in [0, 1]"),
              ("depthClamp", s["depthClamp"] is True, "true (the depth range modelled)"),
              ("shadowMaxZ", s["shadowMaxZ"] is None or (np.isfinite(s["shadowMaxZ"]) and s["shadowMaxZ"] > 0), "null or a positive distance")]
    for key, ok, what in checks:
        if not ok:
            raise ValueError(f"{key} must be {what}, got {s[key]!r}")
    return s


def matrices(settings: dict, camera, sun: Array, triangles: Array, aspect: float | None = None, float32: bool = True) -> Array:
    """Per cascade, the predicted world → [0, 1]³ matrix (k, 4, 4) of the job's world.

    Parameters
    ----------
    settings : dict
        Babylon.js's filled settings (:data:`aliasing.frames.models.MODELS` ``["babylon"]``).
    camera : aliasing.raster.scenes.camera.Camera
        The camera the cascades are fitted to.
    sun : array_like (3,)
        World direction towards the sun (the light shines along −sun).
    triangles : array_like (T, 3, 3)
        The shadow casters [world units] (their bounding box sets the depth range; the page
        sends them as float32, and so they are taken).
    aspect : float, optional
        The render's width over height [1] (``Engine.getAspectRatio``: the canvas's, round(aspect · H) / H
        for the frames); the camera's aspect by default.
    float32 : bool
        Round where the engine stores into a ``Float32Array`` (its ``Matrix``), as Babylon.js
        does without ``useHighPrecisionMatrix`` (default); False: all in float64.

    Returns
    -------
    ndarray (k, 4, 4)
        As :func:`aliasing.frames.readback.decode` gives the engine's matrices (column vectors).

    Raises
    ------
    ValueError
        A setting the model does not cover (``depthClamp`` false), ``triangles`` or ``sun`` of
        the wrong shape, or ``aspect`` not positive and finite.

    Examples
    --------
    >>> from aliasing.frames.scenes import frame_scene, sun_direction
    >>> from aliasing.frames.models import MODELS
    >>> fs = frame_scene("boxes", near=0.5, far=60.0, fov=50.0, aspect=16 / 9, boxes=4, ground_cells=2)
    >>> s, sun = MODELS["babylon"].settings({}), sun_direction(35, 30, fs.camera)
    >>> m32, m64 = matrices(s, fs.camera, sun, fs.triangles), matrices(s, fs.camera, sun, fs.triangles, float32=False)
    >>> lin = 2 * m32[:, :3, :3]                                    # the engine's float32 values, halved by [0, 1]³
    >>> bool((lin == lin.astype(np.float32)).all())
    True
    >>> print(f"{np.max(np.abs(map_sides(m32) / map_sides(m64) - 1)):.1e}")   # the map sides float32 moves
    2.6e-06
    """
    s = _settings(settings)
    tri = check.triangles(triangles)
    sv = check.direction(sun)
    aspect = float(camera.aspect if aspect is None else aspect)
    if not (np.isfinite(aspect) and aspect > 0):
        raise ValueError(f"aspect must be a positive finite width / height, got {aspect!r}")
    f32 = bool(float32)
    # the light: DirectionalLight(mz(-sun)), _computeMatrices (:364) normalizes it (JS numbers)
    d = _normalize(MIRROR @ (-sv))
    if abs(d @ UP) == 1.0:
        d[2] = 1e-13
    # the casters' bounding box: the page's float32 positions, z negated (mz)
    pts = tri.reshape(-1, 3).astype(np.float32).astype(np.float64) @ MIRROR
    lo, hi = pts.min(0), pts.max(0)
    box = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])])
    # the camera: its view (setTarget, _getViewMatrix), PerspectiveFovLHToRef (math.vector.pure.js:7297), their product
    eye = np.asarray(camera.eye, float)
    view = _camera_view(MIRROR @ eye, MIRROR @ (eye + camera.rotation[2]), MIRROR @ camera.rotation[1], f32)
    n, f = float(camera.near), float(camera.far)
    t = 1.0 / np.tan(camera.fov * np.pi / 180 * 0.5)
    persp = _r([[t / aspect, 0, 0, 0], [0, t, 0, 0], [0, 0, (f + n) / (f - n), 1.0], [0, 0, (-2.0 * f * n) / (f - n), 0]], f32)
    inv = _r(_invert(_r(view @ persp, f32)), f32)  # _computeFrustumInWorldSpace (:437): Matrix.Invert(getTransformationMatrix())
    full = _transform_coordinates(NDC, inv)  # the frustum's near and far corners
    prev, brk = _breaks(n, f, s["shadowMaxZ"], int(s["numCascades"]), float(s["lambda"]))
    res = float(s["mapSize"])
    to_unit = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
    out = []
    for a, b in zip(prev, brk):
        ray = full[4:] - full[:4]
        corners = np.concatenate([full[:4] + ray * a, ray * b + full[:4]])
        c = corners[0]  # _computeCascadeFrustum (:474): the centroid, summed in order
        for v in corners[1:]:
            c = c + v
        c = c * (1 / 8)
        if s["stabilizeCascades"]:
            r = np.ceil(np.max(np.sqrt(np.sum((corners - c) ** 2, axis=1))) * 16) / 16
            mn, mx = np.full(3, -r), np.full(3, r)
        else:
            lc = _transform_coordinates(corners, _r(_look_at_values(c, c + d, UP), f32))
            mn, mx = lc.min(0), lc.max(0)
        light_view = _r(_look_at_values(c + d * mn[2], c, UP), f32)  # _computeMatrices: the shadow camera
        zmin, zmax = 0.0, float(mx[2] - mn[2])
        cz = _transform_coordinates(box, light_view)[:, 2]  # the casters' box in the light view (BoundingBox._update)
        if not cz.min() > zmax:  # depth clamp: the range tightened to the casters
            zmax = min(zmax, float(cz.max()))
            zmin = max(zmin, float(cz.min()))
            zmax = max(zmin + 1.0, zmax)
        l, rr, bt, tp = mn[0], mx[0], mn[1], mx[1]  # Matrix.OrthoOffCenterLHToRef (math.vector.pure.js:7134)
        proj = _r([[2.0 / (rr - l), 0, 0, 0], [0, 2.0 / (tp - bt), 0, 0], [0, 0, 2.0 / (zmax - zmin), 0],
                   [(l + rr) / (l - rr), (tp + bt) / (bt - tp), -(zmax + zmin) / (zmax - zmin), 1.0]], f32)
        origin = _transform_coordinates(np.zeros(3), _r(light_view @ proj, f32)) * (res / 2)  # the world origin [texels]
        off = (np.floor(origin + 0.5) - origin) * (2 / res)  # Math.round
        shift = np.eye(4)
        shift[3, :2] = _r(off[:2], f32)  # Matrix.TranslationToRef
        proj = _r(proj @ shift, f32)
        m = _r(light_view @ proj, f32)  # the cascade's transform: row vectors, Babylon's world -> clip
        m[2] = -m[2]  # the page: the row taking z, into the job's world
        out.append(to_unit @ m.T)
    return np.array(out)


def map_sides(matrices: Array) -> Array:
    """Per cascade: the map's larger side [world units] of world → [0, 1]³ matrices (k, 4, 4), 1 / the shorter row of x and y.

    Examples
    --------
    >>> m = np.diag([1 / 20, 1 / 10, 1.0, 1.0])[None]   # a 20 x 10 box
    >>> map_sides(m).tolist()
    [20.0]
    """
    m = np.asarray(matrices, float)
    if m.ndim != 3 or m.shape[1:] != (4, 4):
        raise ValueError(f"matrices must have shape (k, 4, 4), got {m.shape}")
    return np.maximum(1 / np.linalg.norm(m[:, 0, :3], axis=1), 1 / np.linalg.norm(m[:, 1, :3], axis=1))


def offset_casters(triangles: Array, sun: Array, normal_bias: float) -> Array:
    """Babylon.js's caster-side normal bias (shadowMapVertexNormalBias): each corner moves by
    −n · normalBias · sin(n, l) along its face's unit normal n [world units].

    Examples
    --------
    >>> wall = np.array([[[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]])   # normal +x, the sun overhead
    >>> offset_casters(wall, np.array([0.0, 1.0, 0.0]), 0.1)[0, 0].tolist()      # moved 0.1 · sin 90° inwards
    [-0.1, 0.0, 0.0]
    """
    triangles, sun = check.finite(triangles, "triangles"), check.finite(sun, "sun")
    normal_bias = float(check.finite(normal_bias, "normal_bias"))
    if normal_bias == 0:
        return triangles
    n = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    n = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    cos = n @ sun
    return triangles - (normal_bias * np.sqrt(np.clip(1 - cos**2, 0, 1)))[:, None, None] * n[:, None, :]
