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
The triangles are uploaded once per call, in double precision.  A compute pass prepares
them on the device: the float32 vertices that the hardware rasterizes (a triangle with a
non-finite coordinate becomes a point, which draws nothing) and each triangle's plane
(n, −n·a), n = (b − a) × (c − a), in double precision and as a float32 copy scaled to
its largest component.

A projective light map is one 4×4 matrix H (:meth:`aliasing.raster.LightMap.matrix`:
H·(p, 1) = (s·w, t·w, depth, w)).  A second compute pass finds the scene's depth range
[d₀, d₀ + Δ] (rounded outwards, widened by :data:`DEPTH_PAD` on each side); H's depth row
is rescaled to dₙ = (depth − d₀)/Δ ∈ (0, 1).  The vertex shader puts x = 2s − 1,
y = 2t − 1 into clip space and, for the depth test, z = 2dₙ − w: every point a light ray
through a texel meets has the same w (s and t fix the light-plane point), so ordering by
z/w orders by depth, and w ≥ 1 on the map (t ∈ [0, 1] ⇔ 0 ≤ y ≤ W_ly) keeps z/w within
[−1, 1].  The hardware's 24-bit depth test keeps the nearest triangle per texel (ties to
the last drawn, the highest index), and the fragment shader writes its index and its depth
at the texel centre.

That depth is not the hardware's interpolated one, which follows the snapped vertices
(measured up to 1.6e-4 of the depth range off on grazing triangles).  The light ray through
(s, t) is p~ = w q + dₙ e (q = H⁻¹(s, t, 0, 1), e = H⁻¹(0, 0, 1, 0), H with the rescaled
depth row); it meets the triangle's plane n~·p~ = 0 at dₙ = A/(A e_w − B q_w), A = n~·q,
B = n~·e, with (α, β, γ, B) = (n~·c₀, n~·c₁, n~·c₃, n~·c₂) per triangle from a third compute
pass (c_j the columns of H⁻¹), so that A = αs + βt + γ.  The shader evaluates this in double
precision (a float32 evaluation with a double-precision fallback where its error bound is
too large was tried: llvmpipe runs both branches, so it cost more).  The value is stored as
1/(1 + dₙ) in a float32 target (:data:`DEPTH_ERROR`) (0 where empty, which reads back as ``inf``), the index as its bitwise
complement in a 32-bit integer target (0 where empty, −1 once complemented back); both are
read back into the DepthMap's float64 / int64 arrays.  Triangles behind the warp's centre
of projection are clipped by the hardware (w > 0), where numpy clips them at y = −n′/2:
both leave the map's texels alone.

Example
-------
>>> import numpy as np
>>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]])   # (s, t, depth): H = I
>>> if available():
...     (depth, ident), = draw_maps(tri, [np.eye(4)], [8])[0]
... else:   # without an EGL device: the numpy reference, whose buffers these are
...     from aliasing.raster.draw.core import rasterize
...     m = rasterize(tri, 8)
...     depth, ident = m.depth, m.triangle
>>> int(np.isfinite(depth).sum()), int((ident == 0).sum())   # the 8 centres on s + t = 1 are not owned
(28, 28)
"""

from __future__ import annotations

import functools
import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]

#: Relative margin of the depth-test range on each side (keeps window depths inside (−1, 1)).
DEPTH_PAD = 1e-3

#: Largest depth error of a map [fraction of the scene's depth range]: the float32 storage of
#: 1/(1 + dₙ), at most 2⁻²³·(1 + dₙ)² ≤ 2.4e-7 for dₙ ≤ 1 (dₙ itself is computed in double precision).
DEPTH_ERROR = 5e-7

#: Bytes per texel of one resolution's render targets (ids, depth buffer, depth), of their
#: pixel buffers (ids, depth) and of their host copies (ids, depth).
TARGET_BYTES = 28
#: Render targets are kept for the next draw at the same resolution up to this many bytes in all
#: (an 8192² and a 2048² set; :func:`release` frees them).
KEEP_BYTES = 2**31 + 2**28

#: Bytes per triangle of the scene buffers kept for the next draw (double-precision input,
#: float32 vertices, planes, per-map coefficients; :func:`release` frees them).
SCENE_BYTES = 72 + 36 + 32 + 32

#: What to install when there is no EGL device (Debian's Mesa packages: llvmpipe on the CPU).
EGL_PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri"

_GROUP = 64  # compute shader work-group size

# The start of every compute pass: one invocation per triangle, 64 to a work group, the
# double-precision input triangles, their count, and the test of a finite coordinate.
_COMPUTE = """
#version 430
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Triangles { double v[]; };
uniform uint count;
bool finite(double x) { return (unpackDouble2x32(x).y & 0x7ff00000u) != 0x7ff00000u; }   // exponent bits: not inf or NaN
"""

# Once per call: float32 vertices for the rasterizer (a point where a coordinate is not
# finite) and each triangle's plane (n, −n·a) in double precision.
_PREPARE = _COMPUTE + """
layout(std430, binding = 1) writeonly buffer Vertices { float p[]; };
layout(std430, binding = 2) writeonly buffer Planes { dvec4 plane[]; };
layout(std430, binding = 4) buffer Counts { uint bad; };   // triangles with a coordinate not finite
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    dvec3 a = dvec3(v[9 * i], v[9 * i + 1], v[9 * i + 2]);
    dvec3 b = dvec3(v[9 * i + 3], v[9 * i + 4], v[9 * i + 5]);
    dvec3 c = dvec3(v[9 * i + 6], v[9 * i + 7], v[9 * i + 8]);
    bool ok = true;
    for (uint k = 0u; k < 9u; k++) ok = ok && finite(v[9 * i + k]);
    for (uint k = 0u; k < 9u; k++) p[9 * i + k] = ok ? float(v[9 * i + k]) : 0.0;
    dvec3 n = cross(b - a, c - a);
    plane[i] = ok ? dvec4(n, -dot(n, a)) : dvec4(0.0LF);
    if (!ok) atomicAdd(bad, 1u);
}
"""

# Once per map: the smallest and largest depth row·(p, 1) over each work group's finite
# triangles' vertices, as order-preserving unsigned keys of float32 values rounded outwards
# (a tree in shared memory, no atomics; the host reduces the groups' keys).
_RANGE = _COMPUTE + """
layout(std430, binding = 5) writeonly buffer Groups { uvec2 groups[]; };
uniform dvec4 row;
uint key(float f) { uint u = floatBitsToUint(f); return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u; }
float down(double d) { float f = float(d); return double(f) <= d ? f : (f > 0.0 ? uintBitsToFloat(floatBitsToUint(f) - 1u) : (f < 0.0 ? uintBitsToFloat(floatBitsToUint(f) + 1u) : -1.4e-45)); }
float up(double d) { return -down(-d); }
shared uint lo[64], hi[64];
void main() {
    uint i = gl_GlobalInvocationID.x, j = gl_LocalInvocationIndex;
    bool ok = i < count;
    if (ok) for (uint k = 0u; k < 9u; k++) ok = ok && finite(v[9 * i + k]);   // a triangle that is drawn
    lo[j] = 0xffffffffu;   // no triangle: the keys' identities
    hi[j] = 0u;
    if (ok) {
        double lo_d = dot(row.xyz, dvec3(v[9 * i], v[9 * i + 1], v[9 * i + 2])) + row.w, hi_d = lo_d;
        for (uint k = 1u; k < 3u; k++) {
            double d = dot(row.xyz, dvec3(v[9 * i + 3 * k], v[9 * i + 3 * k + 1], v[9 * i + 3 * k + 2])) + row.w;
            lo_d = min(lo_d, d);
            hi_d = max(hi_d, d);
        }
        lo[j] = key(down(lo_d));
        hi[j] = key(up(hi_d));
    }
    for (uint half_ = 32u; half_ > 0u; half_ >>= 1) {
        barrier();
        if (j < half_) {
            lo[j] = min(lo[j], lo[j + half_]);
            hi[j] = max(hi[j], hi[j + half_]);
        }
    }
    if (j == 0u) groups[gl_WorkGroupID.x] = uvec2(lo[0], hi[0]);
}
"""

# Once per map: each triangle's (α, β, γ, B) = (n~·c₀, n~·c₁, n~·c₃, n~·c₂), c_j the columns of H⁻¹.
_COEFFICIENTS = _COMPUTE + """
layout(std430, binding = 2) readonly buffer Planes { dvec4 plane[]; };
layout(std430, binding = 3) writeonly buffer Coefficients { dvec4 coef[]; };
uniform dmat4 columns;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < count) coef[i] = plane[i] * columns;
}
"""

_VERTEX = """
#version 430
uniform mat4 clip;        // (p, 1) -> GL clip coordinates
in vec3 p;
void main() {
    gl_Position = clip * vec4(p, 1.0);
}
"""

# The eye pass: the nearest triangle's index only.
_IDS = """
#version 430
layout(location = 0) out int id_out;
void main() {
    id_out = ~gl_PrimitiveID;
}
"""

# A depth map: the nearest triangle's index, and its plane's depth at the texel centre in
# double precision, stored as 1/(1 + dₙ) = den/(den + A).
_DEPTH = """
#version 430
layout(std430, binding = 3) readonly buffer Coefficients { dvec4 coef[]; };
uniform dvec4 ray;        // q_w = ray.x s + ray.y t + ray.z; e_w = ray.w
uniform double texel;     // 1/R
layout(location = 0) out int id_out;
layout(location = 1) out float depth_out;
void main() {
    int id = gl_PrimitiveID;
    double s = double(gl_FragCoord.x) * texel, t = double(gl_FragCoord.y) * texel;
    dvec4 k = coef[id];
    double a = k.x * s + k.y * t + k.z;
    double den = a * ray.w - k.w * (ray.x * s + ray.y * t + ray.z);
    depth_out = float(den / (den + a));
    id_out = ~id;
}
"""


@dataclass
class _Targets:
    """The render targets of one resolution, kept for the next draw at that resolution."""

    res: int
    ids: object
    depth: object
    zbuffer: object
    maps: object   # framebuffer: ids, depth, z-buffer
    eye: object    # framebuffer: ids, z-buffer
    ids_copy: object     # pixel buffers: the targets are copied into them on the device, then read
    depth_copy: object
    raw: np.ndarray      # host copies of the targets (int32, float32), read into and converted from
    stored: np.ndarray

    def release(self) -> None:
        for obj in (self.maps, self.eye, self.ids, self.depth, self.zbuffer, self.ids_copy, self.depth_copy):
            obj.release()


@functools.lru_cache(maxsize=1)
def _setup() -> tuple[object | None, str]:
    """(moderngl context, programs, kept targets, kept buffers) or None, and why there is none; made once per process."""
    try:
        import moderngl
    except ImportError:
        return None, 'moderngl is not installed (pip install "aliasing[gl]")'
    try:
        ctx = moderngl.create_context(standalone=True, backend="egl", require=430)
    except Exception as exc:  # no libEGL, no device, no driver, no OpenGL 4.3: one line of why
        why = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        return None, f"no EGL device with OpenGL 4.3 could be opened ({why}); install a GPU driver or Mesa's llvmpipe (Debian: {EGL_PACKAGES})"
    _heap_returns_large_blocks()
    programs = {
        "prepare": ctx.compute_shader(_PREPARE),
        "range": ctx.compute_shader(_RANGE),
        "coefficients": ctx.compute_shader(_COEFFICIENTS),
        "ids": ctx.program(vertex_shader=_VERTEX, fragment_shader=_IDS),
        "depth": ctx.program(vertex_shader=_VERTEX, fragment_shader=_DEPTH),
    }
    return (ctx, programs, [], {}, [], []), ""   # context, programs, kept targets, kept buffers, live device maps, their spare targets


def _heap_returns_large_blocks() -> None:
    """Have glibc's malloc map blocks of 1 MiB and more on their own, always (``M_MMAP_THRESHOLD``).

    The driver (llvmpipe: host memory) allocates each device map's texture with malloc.
    glibc raises its mmap threshold to the largest block freed so far, so once a map is
    freed the next ones come from the heap, where freed maps stay resident: measured, a
    shimmer run's memory grew to 0.96 GB, against 0.34 GB with the threshold fixed.  Not
    glibc (or no ``mallopt``): nothing is done."""
    import ctypes
    import ctypes.util

    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        libc.mallopt(ctypes.c_int(-3), ctypes.c_int(1 << 20))  # M_MMAP_THRESHOLD = −3
    except (OSError, AttributeError):
        pass


def _targets(ctx, res: int) -> _Targets:
    """The targets for resolution ``res``: kept ones, or new ones (the least recently used
    others are freed while all would exceed :data:`KEEP_BYTES`)."""
    cache = _setup()[0][2]
    for i, t in enumerate(cache):
        if t.res == res:
            cache.append(cache.pop(i))  # most recently used last
            return t
    while cache and TARGET_BYTES * (res * res + sum(t.res * t.res for t in cache)) > KEEP_BYTES:
        cache.pop(0).release()
    ids = ctx.texture((res, res), 1, dtype="i4")
    depth = ctx.texture((res, res), 1, dtype="f4")
    zbuf = ctx.depth_renderbuffer((res, res))
    copies = (ctx.buffer(reserve=4 * res * res, dynamic=True), ctx.buffer(reserve=4 * res * res, dynamic=True))
    host = (np.zeros((res, res), np.int32), np.zeros((res, res), np.float32))  # zeros: touched once, here
    t = _Targets(res, ids, depth, zbuf, ctx.framebuffer([ids, depth], zbuf), ctx.framebuffer([ids], zbuf), *copies, *host)
    cache.append(t)
    return t


def release() -> None:
    """Free the kept render targets (:data:`TARGET_BYTES` per texel of each resolution kept),
    the kept scene buffers (:data:`SCENE_BYTES` per triangle of the largest scene drawn) and
    the device maps (:class:`DeviceMap`)."""
    state = _setup()[0]
    while state is not None and state[4]:
        state[4][-1].evict()  # a pending reader reads its map back first
    while state is not None and state[5]:
        _, ids, fbo = state[5].pop()
        fbo.release()
        ids.release()
    while state is not None and state[2]:
        state[2].pop().release()
    while state is not None and state[3]:
        state[3].popitem()[1].release()


def _buffer(ctx, name: str, nbytes: int):
    """The kept buffer ``name`` of at least ``nbytes`` bytes (made, or grown, when needed)."""
    kept = _setup()[0][3]
    if name in kept and kept[name].size >= nbytes:
        return kept[name]
    if name in kept:
        kept.pop(name).release()
    kept[name] = ctx.buffer(reserve=max(nbytes, 16))
    return kept[name]


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
    info = _info()
    return str(info.get("GL_RENDERER", ""))


@functools.lru_cache(maxsize=1)
def _info() -> dict:
    """The context's ``info`` (read while it is current: elsewhere the driver answers zeros), {} when unavailable."""
    state, _ = _setup()
    if state is None:
        return {}
    with state[0]:
        return dict(state[0].info)


def _decode(key: int) -> float:
    """The float32 value of an order-preserving key of :data:`_RANGE`."""
    u = key & 0x7FFFFFFF if key & 0x80000000 else ~key & 0xFFFFFFFF
    return float(np.array([u], np.uint32).view(np.float32)[0])


class _Scene:
    """The triangles on the device: double-precision input, float32 vertices, planes, and counts."""

    def __init__(self, ctx, programs, tri: Array):
        self.ctx, self.programs, self.count = ctx, programs, tri.shape[0]
        t = self.count
        self.source = _buffer(ctx, "source", 72 * t)
        self.source.write(np.ascontiguousarray(tri, dtype=np.float64))
        self.vertices = _buffer(ctx, "vertices", 36 * t)
        self.planes = _buffer(ctx, "planes", 32 * t)
        self.coefficients = _buffer(ctx, "coefficients", 32 * t)
        self.counts = _buffer(ctx, "counts", 4)
        self.counts.write(np.zeros(1, np.uint32))
        for binding, buf in enumerate((self.source, self.vertices, self.planes, self.coefficients, self.counts)):
            buf.bind_to_storage_buffer(binding)
        prep = programs["prepare"]
        prep["count"].value = t
        prep.run(group_x=(t + _GROUP - 1) // _GROUP)
        ctx.memory_barrier()  # the vertices, planes and count are read next (draw, shaders, host)
        self.bad = int(np.frombuffer(self.counts.read(4), np.uint32)[0])
        self.arrays = {}

    def draw(self, name: str) -> None:
        """Draw the triangles with program ``name`` (the kept vertex buffer may be longer)."""
        import moderngl

        if name not in self.arrays:
            self.arrays[name] = self.ctx.vertex_array(self.programs[name], [(self.vertices, "3f", "p")])
        self.arrays[name].render(moderngl.TRIANGLES, vertices=3 * self.count)

    def depth_range(self, row: Array) -> tuple[float, float]:
        """(d₀, Δ): the finite vertices' depths ``row``·(p, 1) lie strictly inside (d₀, d₀ + Δ)."""
        rng = self.programs["range"]
        rng["count"].value = self.count
        rng["row"].write(np.asarray(row, np.float64).tobytes())
        groups = (self.count + _GROUP - 1) // _GROUP
        out = _buffer(self.ctx, "groups", 8 * groups)
        out.bind_to_storage_buffer(5)
        rng.run(group_x=groups)
        self.ctx.memory_barrier()
        keys = np.frombuffer(out.read(8 * groups), np.uint32).reshape(groups, 2)
        lo, hi = int(keys[:, 0].min()), int(keys[:, 1].max())
        if lo == 0xFFFFFFFF:  # no finite triangle
            return 0.0, 1.0
        d_lo, d_hi = _decode(lo), _decode(hi)
        width = max(d_hi - d_lo, 1e-6 * max(abs(d_lo), abs(d_hi)), 1e-30)
        return d_lo - DEPTH_PAD * width, width * (1.0 + 2.0 * DEPTH_PAD)

    def release(self) -> None:
        for vao in self.arrays.values():  # the buffers are kept for the next call (:func:`release` frees them)
            vao.release()


def _map_clip(h: Array, d_lo: float, span: float) -> tuple[Array, Array]:
    """(clip matrix, H with its depth row rescaled to (depth − d₀)/Δ)."""
    hn = np.array(h, float)
    hn[2] = (h[2] - d_lo * np.array([0.0, 0.0, 0.0, 1.0])) / span
    return np.stack([2 * hn[0] - hn[3], 2 * hn[1] - hn[3], 2 * hn[2] - hn[3], hn[3]]), hn


def _uniform(prog, name: str, value: np.ndarray) -> None:
    """Set a uniform from an array of its type, unless the driver optimized it away."""
    member = prog.get(name, None)
    if member is not None:
        member.write(np.ascontiguousarray(value).tobytes())


#: Threads that convert the read-back targets into the DepthMap's arrays.
THREADS = min(os.cpu_count() or 1, 8)


@functools.lru_cache(maxsize=1)
def _pool() -> ThreadPoolExecutor:
    """Threads for the host's conversions (numpy releases the GIL in them)."""
    return ThreadPoolExecutor(max_workers=THREADS, thread_name_prefix="aliasing-gl")


def _blocks(res: int) -> list[slice]:
    """Row blocks of a map, four per thread of :func:`_pool`."""
    step = max(64, -(-res // (4 * THREADS)))
    return [slice(i, i + step) for i in range(0, res, step)]


def _read(tg: _Targets, span: float, offset: float) -> tuple[Array, NDArray[np.int64]]:
    """Read the targets back into the DepthMap's new arrays: ids −1 − raw (the cleared 0 gives
    −1), depth Δ/stored + offset (``inf`` where 0 is stored).  :func:`_pool`'s threads convert
    in row blocks (their first touch of the new memory is most of the cost), the ids while
    the depth is read."""
    res = tg.res
    ids = np.empty((res, res), np.int64)
    depth = np.empty((res, res))

    def convert_ids(block: slice) -> None:
        np.subtract(-1, tg.raw[block], out=ids[block], dtype=np.int64)  # ~id = −1 − id

    def convert_depth(block: slice) -> None:
        with np.errstate(divide="ignore"):
            np.divide(span, tg.stored[block], out=depth[block], dtype=np.float64)  # Δ (1 + dₙ)
        depth[block] += offset

    tg.ids.read_into(tg.ids_copy)  # on the device; a GPU's driver reads a pixel buffer faster than a texture
    tg.depth.read_into(tg.depth_copy)
    tg.ids_copy.read_into(tg.raw)
    pending = [_pool().submit(convert_ids, b) for b in _blocks(res)]
    tg.depth_copy.read_into(tg.stored)
    pending += [_pool().submit(convert_depth, b) for b in _blocks(res)]
    for job in pending:
        job.result()
    return depth, ids


def _draw_map(scene: _Scene, h: Array, res: int) -> tuple[Array, NDArray[np.int64]]:
    tg = _targets(scene.ctx, res)
    span, offset, _ = _render(scene, h, res, tg.maps)
    return _read(tg, span, offset)


def _render(scene: _Scene, h: Array, res: int, fbo, *, program: str = "depth", box: tuple[int, int, int, int] | None = None) -> tuple[float, float, Array]:
    """Draw the map of matrix ``h`` into framebuffer ``fbo`` (ids, depth, z-buffer of ``res``²;
    ``program`` "ids": ids and z-buffer only), within ``box`` (x, y, width, height) [texels]
    if given; returns (Δ, d₀ − Δ, ray): the depth is Δ/stored + d₀ − Δ, ``ray`` the depth
    shader's uniform (for :mod:`.resident`'s fetch pass)."""
    import moderngl

    ctx, prog = scene.ctx, scene.programs[program]
    d_lo, span = scene.depth_range(h[2])
    clip, hn = _map_clip(h, d_lo, span)
    inverse = np.linalg.inv(hn)
    coef = scene.programs["coefficients"]
    coef["count"].value = scene.count
    _uniform(coef, "columns", inverse[:, [0, 1, 3, 2]].T.astype(np.float64))  # GLSL: column-major
    coef.run(group_x=(scene.count + _GROUP - 1) // _GROUP)
    ctx.memory_barrier()  # the fragment shader reads the coefficients
    ray = inverse[3, [0, 1, 3, 2]].astype(np.float64)
    _uniform(prog, "clip", np.ascontiguousarray(clip.T, dtype=np.float32))
    _uniform(prog, "ray", ray)
    _uniform(prog, "texel", np.float64(1.0 / res))
    fbo.use()
    fbo.viewport = (0, 0, res, res)
    fbo.scissor = box  # None: the whole map
    fbo.use()
    fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0, viewport=box)  # ids 0 (−1 complemented), depth 0 (inf)
    ctx.enable(moderngl.DEPTH_TEST)
    ctx.depth_func = "<="  # ties to the last drawn, the highest index, as in numpy
    scene.draw(program)
    fbo.scissor = None
    return span, d_lo - span, ray


def _context():
    """The context, made current by ``with``; scenes and targets are made inside it."""
    require()
    return _setup()[0][0]


def draw_maps(triangles: Array, matrices: Sequence[Array], resolutions: Sequence[int]) -> tuple[list[tuple[Array, NDArray[np.int64]]], int]:
    """Depth maps of eye-space ``triangles`` (T, 3, 3, checked) through projective maps.

    ``matrices``: each map's H (:meth:`aliasing.raster.LightMap.matrix`); ``resolutions``:
    each map's R.  The triangles are uploaded and prepared once.  Returns the maps and the
    number of triangles not drawn because a coordinate is not finite; per map (depth,
    triangle): the depth (R, R) [the map's depth units], ``inf`` where empty, and the visible
    triangle's index into ``triangles``, −1 where empty.
    """
    tri = np.asarray(triangles, float)
    blank = [(np.full((r, r), np.inf), np.full((r, r), -1, np.int64)) for r in resolutions] if tri.shape[0] == 0 else None
    if blank is not None:
        return blank, 0
    ctx = _context()
    with ctx:
        scene = _Scene(ctx, _setup()[0][1], tri)
        try:
            if scene.bad == scene.count:
                return [(np.full((r, r), np.inf), np.full((r, r), -1, np.int64)) for r in resolutions], scene.bad
            return [_draw_map(scene, np.asarray(h, float), int(r)) for h, r in zip(matrices, resolutions)], scene.bad
        finally:
            scene.release()


def eye_ids(triangles: Array, tan_half: float, resolution: int, near: float, *, tan_y: float | None = None) -> NDArray[np.int64]:
    """The visible triangle per pixel of the eye pass (index into ``triangles``, −1 where empty).

    The camera of :func:`aliasing.raster.eye_pass`: eye at the origin looking along +z,
    u = ½ + x/(2z·tanθ), v = ½ + y/(2z·tanθ_y) (``tan_y``, default ``tan_half``: a square
    view; a non-square one has tan θ_x = ``tan_half``), row 0 at the bottom; clipped at z = ``near``.  The depth test is a
    perspective one between ``near`` (or the nearest vertex, if farther) and the farthest
    vertex, ties to the highest index.
    """
    import moderngl

    tri = np.asarray(triangles, float)
    empty = np.full((resolution, resolution), -1, np.int64)
    if tri.shape[0] == 0:
        return empty
    ctx = _context()
    with ctx:
        scene = _Scene(ctx, _setup()[0][1], tri)
        try:
            z_lo, z_span = scene.depth_range(np.array([0.0, 0.0, 1.0, 0.0]))
            z_far = z_lo + z_span
            if scene.bad == scene.count or not z_far > near:
                return empty
            z_near = max(float(near), z_lo)  # the nearest vertex, or the clipping plane
            a, b = (z_far + z_near) / (z_far - z_near), -2.0 * z_far * z_near / (z_far - z_near)
            ty = tan_half if tan_y is None else tan_y
            clip = np.array([[1 / tan_half, 0, 0, 0], [0, 1 / ty, 0, 0], [0, 0, a, b], [0, 0, 1, 0]], float)
            prog = scene.programs["ids"]
            _uniform(prog, "clip", np.ascontiguousarray(clip.T, dtype=np.float32))
            tg = _targets(ctx, int(resolution))
            tg.eye.use()
            tg.eye.viewport = (0, 0, resolution, resolution)
            tg.eye.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
            ctx.enable(moderngl.DEPTH_TEST)
            ctx.depth_func = "<="
            scene.draw("ids")
            tg.ids.read_into(tg.ids_copy)
            tg.ids_copy.read_into(tg.raw)
            return np.subtract(-1, tg.raw, dtype=np.int64)
        finally:
            scene.release()
