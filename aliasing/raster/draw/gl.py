"""The ``gl`` backend: depth maps and the eye pass drawn by OpenGL (moderngl, headless EGL).

The optional ``gl`` extra (``pip install "aliasing[gl]"``: moderngl) draws through a
standalone EGL context: a GPU's driver where there is one, or Mesa's llvmpipe on the CPU
(Debian packages ``libegl1 libegl-mesa0 libgl1-mesa-dri``).  It reproduces the numpy
reference's buffers (:mod:`aliasing.raster.draw.core`: texel centres at (i + ½)/R, row 0 at
the bottom, left and bottom edges own the centres on them, the nearest depth kept, ties to
the highest triangle index) up to the hardware's sub-texel vertex snapping (8 bits on
llvmpipe and current GPUs): a texel centre within about 1/256 texel of an edge may go to
the neighbouring triangle, and near-coincident surfaces are told apart by a 24-bit
depth test.

How a map is drawn
------------------
A projective light map is one 4×4 matrix H (:meth:`aliasing.raster.LightMap.matrix`:
H·(p, 1) = (s·w, t·w, depth, w)).  The vertex shader puts x = 2s − 1, y = 2t − 1 into clip
space and, for the depth test, z = k·(depth − d₀) − w with d₀ the smallest depth over the
scene's bounding box and k = 2/range: every point a light ray through a texel meets has the
same w (s and t fix the light-plane point), so ordering by z/w orders by depth, and w ≥ 1
on the map (t ∈ [0, 1] ⇔ 0 ≤ y ≤ W_ly) keeps z/w within [−1, 1].  The first pass keeps, per
texel, the nearest triangle's ``gl_PrimitiveID`` (a 32-bit integer target; 24-bit hardware
depth test, ties to the last drawn, the highest index).  A second pass, once per texel,
computes the depth of that triangle's plane at the texel centre in double precision (the
light ray through (s, t) met with the plane; no interpolated attribute, so the value does
not depend on the vertices' snapping), stores it as two float32 (hi + lo, 48 bits) beside
the id (−1 where empty), and both are read back into float64 / int64 arrays.  Triangles behind the warp's centre of
projection are clipped by the hardware (w > 0), where numpy clips them at y = −n′/2: both
leave the map's texels alone.

Example
-------
>>> import numpy as np
>>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]])   # (s, t, depth): H = I
>>> if available():
...     depth, ident = draw_maps(tri, [np.eye(4)], [8])[0]
... else:   # without an EGL device: the numpy reference, whose buffers these are
...     from aliasing.raster.draw.core import rasterize
...     m = rasterize(tri, 8)
...     depth, ident = m.depth, m.triangle
>>> int(np.isfinite(depth).sum()), int((ident == 0).sum())   # the 8 centres on s + t = 1 are not owned
(28, 28)
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]

#: Relative margin of the depth-test range (keeps window depths below 1, the cleared value).
DEPTH_PAD = 1e-3

#: Bytes per texel of one resolution's render targets (ids, depth buffer, depth hi/lo, visible ids).
TARGET_BYTES = 20
#: Render targets are kept for the next draw at the same resolution up to this many bytes in all
#: (an 8192² and a 2048² set; :func:`release` frees them).
KEEP_BYTES = 3 * 2**29

#: What to install when there is no EGL device (Debian's Mesa packages: llvmpipe on the CPU).
EGL_PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri"

_VERTEX = """
#version 430
uniform mat4 clip;        // (p, 1) -> GL clip coordinates
in vec3 p;
void main() {
    gl_Position = clip * vec4(p, 1.0);
}
"""

# First pass: the hardware z-buffer keeps the nearest triangle per texel; its index is stored.
_FRAGMENT = """
#version 430
layout(location = 0) out int id_out;
void main() {
    id_out = gl_PrimitiveID;
}
"""

# Second pass, once per texel: the depth of the visible triangle at the texel centre, in double
# precision.  The light ray through (s, t) is p~ = w q + d e (q = H⁻¹(s, t, 0, 1),
# e = H⁻¹(0, 0, 1, 0)); it meets the triangle's plane n~.p~ = 0, p~ homogeneous (last
# coordinate 1), at d = A/(A e_w − B q_w), A = n~.q = αs + βt + γ, B = n~.e; (α, β, γ, B) per
# triangle and map come from the host (``_coefficients``).  No interpolated attribute: the
# value does not depend on the vertices' snapping.  Stored as float32 hi + lo (48 bits).
_RESOLVE_VERTEX = """
#version 430
void main() {
    vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;
    gl_Position = vec4(corner, 0.0, 1.0);   // one triangle over the whole viewport
}
"""

_RESOLVE = """
#version 430
layout(std430, binding = 0) readonly buffer Coefficients { dvec4 coef[]; };
uniform isampler2D ids;
uniform sampler2D zbuffer;
uniform dvec4 ray;        // q_w = ray.x s + ray.y t + ray.z; e_w = ray.w
uniform double texel;     // 1/R
layout(location = 0) out vec2 depth_out;
layout(location = 1) out int id_out;
void main() {
    ivec2 c = ivec2(gl_FragCoord.xy);
    if (texelFetch(zbuffer, c, 0).r == 1.0) {   // the cleared value: nothing drawn here
        depth_out = vec2(uintBitsToFloat(0x7f800000u), 0.0);
        id_out = -1;
        return;
    }
    int id = texelFetch(ids, c, 0).r;
    double s = double(gl_FragCoord.x) * texel, t = double(gl_FragCoord.y) * texel;
    dvec4 k = coef[id];
    double a = k.x * s + k.y * t + k.z;
    double d = a / (a * ray.w - k.w * (ray.x * s + ray.y * t + ray.z));
    float hi = float(d);
    depth_out = vec2(hi, float(d - double(hi)));
    id_out = id;
}
"""


@dataclass
class _Targets:
    """The render targets of one resolution, kept for the next draw at that resolution."""

    res: int
    ids: object
    zbuffer: object
    draw: object
    depth: object
    visible: object
    resolve: object

    def release(self) -> None:
        for obj in (self.resolve, self.draw, self.depth, self.visible, self.ids, self.zbuffer):
            obj.release()


@functools.lru_cache(maxsize=1)
def _setup() -> tuple[object | None, str]:
    """(moderngl context, programs, target cache) or None, and why there is none; made once per process."""
    try:
        import moderngl
    except ImportError:
        return None, 'moderngl is not installed (pip install "aliasing[gl]")'
    try:
        ctx = moderngl.create_context(standalone=True, backend="egl")
    except Exception as exc:  # no libEGL, no device, no driver: one line of why
        why = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        return None, f"no EGL device could be opened ({why}); install a GPU driver or Mesa's llvmpipe (Debian: {EGL_PACKAGES})"
    draw = ctx.program(vertex_shader=_VERTEX, fragment_shader=_FRAGMENT)
    resolve = ctx.program(vertex_shader=_RESOLVE_VERTEX, fragment_shader=_RESOLVE)
    resolve["ids"].value = 0
    resolve["zbuffer"].value = 1
    return (ctx, draw, resolve, []), ""


def _targets(ctx, res: int) -> _Targets:
    """The targets for resolution ``res``: kept ones, or new ones (the least recently used
    others are freed while all would exceed :data:`KEEP_BYTES`)."""
    cache = _setup()[0][3]
    for i, t in enumerate(cache):
        if t.res == res:
            cache.append(cache.pop(i))  # most recently used last
            return t
    while cache and TARGET_BYTES * (res * res + sum(t.res * t.res for t in cache)) > KEEP_BYTES:
        cache.pop(0).release()
    ids = ctx.texture((res, res), 1, dtype="i4")
    zbuf = ctx.depth_texture((res, res))
    zbuf.compare_func = ""  # read the stored depth, not a comparison
    depth = ctx.texture((res, res), 2, dtype="f4")
    visible = ctx.texture((res, res), 1, dtype="i4")
    t = _Targets(res, ids, zbuf, ctx.framebuffer([ids], zbuf), depth, visible, ctx.framebuffer([depth, visible]))
    cache.append(t)
    return t


def release() -> None:
    """Free the kept render targets (:data:`TARGET_BYTES` per texel of each resolution kept)."""
    state = _setup()[0]
    while state is not None and state[3]:
        state[3].pop().release()


def available() -> bool:
    """Whether the ``gl`` backend can draw here (moderngl installed and an EGL context opened)."""
    return _setup()[0] is not None


def require() -> None:
    """Raise ``ValueError`` naming ``backend`` and what is missing, unless :func:`available`."""
    state, why = _setup()
    if state is None:
        raise ValueError(f"backend 'gl' cannot draw here: {why}")


def renderer() -> str:
    """The OpenGL renderer's name (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"), "" when unavailable."""
    state, _ = _setup()
    return "" if state is None else str(state[0].info["GL_RENDERER"])


def _finite(tri: Array) -> tuple[Array, NDArray[np.int64] | None]:
    """The finite triangles, and their input indices (None when all are)."""
    good = np.isfinite(tri).all(axis=(1, 2))
    if good.all():
        return tri, None
    idx = np.nonzero(good)[0]
    return tri[idx], idx


def _planes(tri: Array) -> Array:
    """Each triangle's plane (n, −n·a) [eye space], n = (b − a) × (c − a), float64 (T, 4)."""
    a = tri[:, 0]
    n = np.cross(tri[:, 1] - a, tri[:, 2] - a)
    return np.concatenate([n, -(n * a).sum(axis=1, keepdims=True)], axis=1)


def _draw(tri: Array, jobs: Sequence[tuple[Array, Array | None, int]]) -> list[tuple[Array, NDArray[np.int64]]]:
    """Draw the finite triangles ``tri`` (T, 3, 3) once per job (clip 4×4, H⁻¹ or None, R).

    With H⁻¹, the depth at each texel centre is computed from the visible triangle's plane
    (second pass); without, only ids are drawn (depth 0 where covered).  Returns per job the
    depth (R, R) float64 (``inf`` where empty) and the primitive index (R, R) int64 (−1
    where empty).
    """
    import moderngl

    require()
    ctx, draw, resolve, _ = _setup()[0]
    exact = any(j[1] is not None for j in jobs)
    out = []
    with ctx:
        vbo = ctx.buffer(np.ascontiguousarray(tri, dtype=np.float32).tobytes())
        planes = _planes(tri) if exact else None
        coef = ctx.buffer(reserve=planes.nbytes) if exact else None
        vao = ctx.vertex_array(draw, [(vbo, "3f", "p")])
        quad = ctx.vertex_array(resolve, [])
        ctx.disable(moderngl.CULL_FACE)
        try:
            for clip, inverse, res in jobs:
                tg = _targets(ctx, res)
                tg.draw.use()
                tg.draw.viewport = (0, 0, res, res)
                tg.draw.clear(depth=1.0)
                ctx.enable(moderngl.DEPTH_TEST)
                ctx.depth_func = "<="  # ties to the last drawn, the highest index, as in numpy
                draw["clip"].write(np.ascontiguousarray(clip.T, dtype=np.float32).tobytes())  # GLSL: column-major
                vao.render(moderngl.TRIANGLES)
                ids32 = np.empty((res, res), np.int32)
                if inverse is None:
                    tg.ids.read_into(ids32)
                    zb = np.empty((res, res), np.float32)
                    tg.zbuffer.read_into(zb)
                    empty = zb == 1.0
                    depth = np.where(empty, np.inf, 0.0)
                    ids = ids32.astype(np.int64)
                    ids[empty] = -1
                else:
                    ctx.disable(moderngl.DEPTH_TEST)
                    tg.resolve.use()
                    tg.resolve.viewport = (0, 0, res, res)
                    tg.ids.use(0)
                    tg.zbuffer.use(1)
                    coef.write(planes @ inverse[:, [0, 1, 3, 2]])  # (α, β, γ, B) per triangle
                    coef.bind_to_storage_buffer(0)
                    resolve["ray"].write(inverse[3, [0, 1, 3, 2]].astype(np.float64).tobytes())
                    resolve["texel"].write(np.float64(1.0 / res).tobytes())
                    quad.render(moderngl.TRIANGLES, vertices=3)
                    hilo = np.empty((res, res, 2), np.float32)
                    tg.depth.read_into(hilo)
                    depth = np.add(hilo[..., 0], hilo[..., 1], dtype=np.float64)  # inf + 0 where empty
                    del hilo
                    tg.visible.read_into(ids32)  # −1 where empty
                    ids = ids32.astype(np.int64)
                out.append((depth, ids))
        finally:
            quad.release()
            vao.release()
            vbo.release()
            if coef is not None:
                coef.release()
    return out


def _depth_range(tri: Array, row: Array) -> tuple[float, float]:
    """Smallest depth and depth range of ``row``·(p, 1) over the triangles' bounding box."""
    lo, hi = tri.min(axis=(0, 1)), tri.max(axis=(0, 1))
    corners = np.array(np.meshgrid(*zip(lo, hi), indexing="ij")).reshape(3, -1).T
    d = corners @ row[:3] + row[3]
    d_lo, span = float(d.min()), float(d.max() - d.min())
    return d_lo, span if span > 0 else 1.0


def draw_maps(triangles: Array, matrices: Sequence[Array], resolutions: Sequence[int]) -> list[tuple[Array, NDArray[np.int64]]]:
    """Depth maps of eye-space ``triangles`` (T, 3, 3, checked) through projective maps.

    ``matrices``: each map's H (:meth:`aliasing.raster.LightMap.matrix`); ``resolutions``:
    each map's R.  The triangles are uploaded once.  Returns per map (depth, triangle): the
    depth (R, R) [the map's depth units], ``inf`` where empty, and the visible triangle's
    index into ``triangles``, −1 where empty.  Non-finite triangles are not drawn.
    """
    tri, idx = _finite(np.asarray(triangles, float))
    if tri.shape[0] == 0:
        return [(np.full((r, r), np.inf), np.full((r, r), -1, np.int64)) for r in resolutions]
    jobs = []
    e3 = np.array([0.0, 0.0, 0.0, 1.0])
    for h, res in zip(matrices, resolutions):
        h = np.asarray(h, float)
        d_lo, span = _depth_range(tri, h[2])
        k = 2.0 / (span * (1.0 + DEPTH_PAD))
        clip = np.stack([2 * h[0] - h[3], 2 * h[1] - h[3], k * (h[2] - d_lo * e3) - h[3], h[3]])
        jobs.append((clip, np.linalg.inv(h), int(res)))
    out = _draw(tri, jobs)
    if idx is not None:
        out = [(d, np.where(i >= 0, idx[np.maximum(i, 0)], -1)) for d, i in out]
    return out


def eye_ids(triangles: Array, tan_half: float, resolution: int, near: float, *, tan_y: float | None = None) -> NDArray[np.int64]:
    """The visible triangle per pixel of the eye pass (index into ``triangles``, −1 where empty).

    The camera of :func:`aliasing.raster.eye_pass`: eye at the origin looking along +z,
    u = ½ + x/(2z·tanθ), v = ½ + y/(2z·tanθ_y) (``tan_y``, default ``tan_half``: a square
    view; a non-square one has tan θ_x = ``tan_half``), row 0 at the bottom; clipped at z = ``near``.  The depth test is a
    perspective one between ``near`` (or the nearest vertex, if farther) and the farthest
    vertex, ties to the highest index.
    """
    tri, idx = _finite(np.asarray(triangles, float))
    z = tri[..., 2]
    if tri.shape[0] == 0 or not (z > near).any():
        return np.full((resolution, resolution), -1, np.int64)
    z_far = float(z.max()) * (1.0 + DEPTH_PAD) + DEPTH_PAD
    z_near = max(float(near), float(z.min()) * (1.0 - DEPTH_PAD))  # the nearest vertex, or the clipping plane
    a, b = (z_far + z_near) / (z_far - z_near), -2.0 * z_far * z_near / (z_far - z_near)
    ty = tan_half if tan_y is None else tan_y
    clip = np.array([[1 / tan_half, 0, 0, 0], [0, 1 / ty, 0, 0], [0, 0, a, b], [0, 0, 1, 0]], float)
    (_, ids), = _draw(tri, [(clip, None, int(resolution))])
    if idx is not None:
        ids = np.where(ids >= 0, idx[np.maximum(ids, 0)], -1)
    return ids
