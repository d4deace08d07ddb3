"""What an engine's page read back, as arrays: per pixel shadow factor, cascade, position, normal; per cascade the light matrix.

Rows are top-down (row 0 is the image's top), as in the PNG; the pages read WebGL's
bottom-up rows and :func:`decode` flips them.  ``gl_y`` keeps the GL pixel row (for effects
that depend on ``gl_FragCoord``, such as three.js's rotated PCF taps).

Examples
--------
>>> import base64
>>> z = base64.b64encode(np.zeros(2 * 1 * 4, np.float32).tobytes()).decode()
>>> rb = decode({"engine": "threejs", "revision": "187", "width": 2, "height": 1, "shadow": z, "position": z,
...              "normal": z, "cascades": [], "frame": "data:image/png;base64,"})
>>> rb.shadow.shape, bool(np.isnan(rb.shadow).all())   # nothing drawn: w = 0 everywhere
((1, 2), True)
"""

from __future__ import annotations

import base64
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .predict import Prediction

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Readback:
    """One frame as the engine computed it.

    Attributes
    ----------
    engine, release : str
        The engine and its release as the page reports it.
    shadow : ndarray (H, W)
        The raw shadow factor the engine multiplied into the sun's light (1 lit, 0 shadowed);
        NaN where nothing is drawn.
    cascade : ndarray of int (H, W)
        The cascade the engine sampled, −1 where none (or nothing is drawn).
    position : ndarray (H, W, 3)
        World position [world units] (float32 in the engine), NaN where nothing is drawn.
    normal : ndarray (H, W, 3)
        World unit normal of the drawn face, turned towards the eye; NaN where nothing is drawn.
    matrices : ndarray (k, 4, 4)
        Per cascade: world → shadow-map coordinates (s, t, depth) in [0, 1]³ (column vectors).
    sizes : ndarray of int (k, 2)
        Per cascade: map width and height [texels].
    info : dict
        Everything else the page returned (cascade boxes, breaks, biases, renderer string, timing).
    frame : bytes
        The engine's own shaded frame (PNG).

    Examples
    --------
    >>> rb = Readback("threejs", "187", np.array([[1.0, np.nan]]), np.array([[0, -1]]), np.zeros((1, 2, 3)), np.zeros((1, 2, 3)),
    ...               np.eye(4)[None], np.array([[1024, 1024]]), {}, b"")
    >>> rb.drawn.tolist(), rb.matrices.shape
    ([[True, False]], (1, 4, 4))
    """

    engine: str
    release: str
    shadow: Array
    cascade: NDArray[np.int64]
    position: Array
    normal: Array
    matrices: Array
    sizes: NDArray[np.int64]
    info: dict
    frame: bytes

    @property
    def drawn(self) -> NDArray[np.bool_]:
        """(H, W): pixels where the engine drew geometry.

        Returns
        -------
        ndarray of bool (H, W)
            Where the shadow factor is finite.

        Examples
        --------
        >>> rb = Readback("", "", np.array([[0.5, np.nan]]), np.zeros((1, 2), np.int64), np.zeros((1, 2, 3)), np.zeros((1, 2, 3)),
        ...               np.eye(4)[None], np.array([[16, 16]]), {}, b"")
        >>> rb.drawn.tolist()
        [[True, False]]
        """
        return np.isfinite(self.shadow)


def _f32(b64: str, h: int, w: int) -> Array:
    a = np.frombuffer(base64.b64decode(b64), np.float32).astype(float)
    if a.size != h * w * 4:
        raise ValueError(f"read-back of {a.size} floats does not match the frame's {w}x{h}x4")
    return a.reshape(h, w, 4)[::-1]


def decode(out: dict) -> Readback:
    """The page's answer (a dict of base64 float32 buffers and per-cascade lists) as a :class:`Readback`.

    Parameters
    ----------
    out : dict
        ``engine``, ``width`` and ``height`` [px], ``shadow`` (per pixel: factor, cascade, n·l),
        ``position`` (world x, y, z [world units] and 1 where drawn) and ``normal`` (base64 float32,
        H × W × 4, GL rows bottom up), ``cascades`` (per cascade ``matrix``, 16 numbers column-major,
        and ``size`` [texels]), ``frame`` (a PNG data URL), and anything else (kept in ``info``).

    Returns
    -------
    Readback
        Rows top down.

    Raises
    ------
    ValueError
        ``out`` misses a field or its buffers do not match its size.

    Examples
    --------
    >>> b64 = lambda a: base64.b64encode(np.asarray(a, np.float32).tobytes()).decode()
    >>> rb = decode({"engine": "threejs", "revision": "187", "width": 1, "height": 2, "frame": "data:image/png;base64,",
    ...              "shadow": b64([[[0.0, 1, 0.5, 0]], [[1.0, 0, 0.5, 0]]]),            # GL row 0 (bottom), row 1
    ...              "position": b64([[[0, 0, -5, 1]], [[0, 0, 0, 0]]]), "normal": b64([[[0, 2, 0, 0]], [[0, 0, 0, 0]]]),
    ...              "cascades": [{"matrix": np.eye(4).ravel().tolist(), "size": [512, 512]}]})
    >>> rb.shadow.tolist(), rb.cascade.tolist(), rb.normal[1, 0].tolist()       # top row: nothing drawn
    ([[nan], [0.0]], [[-1], [1]], [0.0, 1.0, 0.0])
    """
    if not isinstance(out, dict):
        raise ValueError(f"out must be the page's dict, got {type(out).__name__}")
    missing = [k for k in ("engine", "width", "height", "shadow", "position", "normal", "cascades", "frame") if k not in out]
    if missing:
        raise ValueError(f"the page's answer misses {', '.join(missing)}")
    for k in ("width", "height"):
        v = out[k]
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not np.isfinite(v) or v != int(v) or not 1 <= v <= 16384:
            raise ValueError(f"out[{k!r}] must be a whole number of pixels in [1, 16384], got {v!r}")
    h, w = int(out["height"]), int(out["width"])
    sh, pos, nrm = (_f32(out[k], h, w) for k in ("shadow", "position", "normal"))
    drawn = pos[..., 3] > 0.5
    shadow = np.where(drawn, sh[..., 0], np.nan)
    cascade = np.where(drawn, np.rint(sh[..., 1]), -1).astype(np.int64)
    position = np.where(drawn[..., None], pos[..., :3], np.nan)
    n = nrm[..., :3]
    n = n / np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-30)
    normal = np.where(drawn[..., None], n, np.nan)
    # three.js: column-major elements of world -> [0, 1]^3; Babylon.js: row-vector world -> clip (flagged "clip")
    to_unit = np.array([[0.5, 0, 0, 0.5], [0, 0.5, 0, 0.5], [0, 0, 0.5, 0.5], [0, 0, 0, 1.0]])
    mats = np.array([(to_unit if c.get("clip") else np.eye(4)) @ np.asarray(c["matrix"], float).reshape(4, 4).T
                     for c in out["cascades"]]).reshape(-1, 4, 4)
    sizes = np.array([c["size"] for c in out["cascades"]], np.int64).reshape(-1, 2)
    png = out["frame"].split(",", 1)[1] if "," in out["frame"] else ""
    info = {k: v for k, v in out.items() if k not in ("shadow", "position", "normal", "frame")}
    info["ndotl"] = np.where(drawn, sh[..., 2], np.nan)
    return Readback(str(out["engine"]), str(out.get("revision", out.get("release", ""))), shadow, cascade, position, normal,
                    mats, sizes, info, base64.b64decode(png))


@dataclass(frozen=True)
class FrameResult:
    """An engine's frame against the toolkit's prediction: ``readback`` (:class:`Readback`),
    ``prediction``, the exact reference's lit pixels ``reference``, the filled ``settings``, and
    ``report`` (the JSON-ready ``engine``, ``release``, ``measured``, ``predicted``).

    Examples
    --------
    >>> import base64
    >>> from aliasing.frames.models import MODELS
    >>> from aliasing.frames.paths import parse_path, pose_camera
    >>> from aliasing.frames.run import measure
    >>> from aliasing.frames.scenes import frame_scene, sun_direction
    >>> fs = frame_scene("boxes", near=1.0, far=20.0, fov=50.0, aspect=2.0, boxes=2, ground_cells=2)
    >>> sun = sun_direction(20.0, 30.0, fs.camera); m = MODELS["threejs"]; s = m.settings({"cascades": 2, "shadowMapSize": 256})
    >>> b64 = lambda a: base64.b64encode(np.asarray(a, np.float32).tobytes()).decode()
    >>> out = {"engine": "threejs", "revision": "187", "width": 2, "height": 1, "frame": "data:image/png;base64,",   # a page's answer, by hand:
    ...        "shadow": b64([[[0, 0, 0, 0], [1, 1, 0.3, 0]]]),                     # per pixel factor, cascade, n·l
    ...        "position": b64([[[-2.0, -1.0, -4.25, 1.0], [0.0, -1.0, -12.0, 1.0]]]), # two ground pixels, drawn (w = 1)
    ...        "normal": b64([[[0, 1, 0, 0]] * 2]), "breaks": (m.edges(s, fs.camera)[1:] / 20.0).tolist(),
    ...        "cascades": [{"matrix": c.T.ravel().tolist(), "size": [256, 256]} for c in m.matrices(s, fs.camera, sun)]}
    >>> r = measure("threejs", fs, sun, s, out)                                  # a FrameResult
    >>> r.readback.shadow.tolist(), r.prediction.factor.tolist(), r.reference.tolist()
    ([[0.0, 1.0]], [[0.0, 1.0]], [[False, True]])
    """

    readback: Readback
    prediction: Prediction
    reference: NDArray[np.bool_]
    settings: dict
    report: dict
