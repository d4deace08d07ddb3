"""Maps resident on the gl device: drawn there, kept there, read texel by texel.

A depth map of the ``gl`` backend (:mod:`aliasing.raster.draw.gl`) that its callers only look
up need not come back whole: :func:`draw_device_map` draws the visible triangle's index per
texel on the device (the depth test of :func:`aliasing.raster.draw.gl.draw_maps`, over the
whole map or a box of it) and keeps it there with the triangles' depth coefficients;
:meth:`DeviceMap.fetch` runs a compute pass that evaluates the depth of the asked texels
there (the expression the map's fragment shader stores, in double precision, stored as
float32: within ``gl.DEPTH_ERROR`` of the scene's depth range) and returns those texels
only.  The values are ``draw_maps``'s, bit for bit on llvmpipe (checked in the tests).
:meth:`DeviceMap.test` runs :func:`aliasing.raster.draw.shadow_test`'s comparisons there
(double precision, numpy's order of operations, no fused multiply-add), and only one bit per
point comes back: the host test's result on the same texels, bit for bit on llvmpipe (checked
in the tests; GLSL does not promise correctly rounded double division on every device).

Memory stays bounded: at most :data:`DEVICE_BYTES` of maps are kept (the least recently
drawn are freed first, and their render targets are reused for the next map of the same
size: making a texture costs more than drawing it on llvmpipe).  A map bigger than the
device allows is refused in one line before any work (:func:`check_size`).

Example
-------
>>> import numpy as np
>>> from aliasing.raster.draw import gl
>>> tri = np.array([[[0.0, 0.0, 0.5], [1.0, 0.0, 0.5], [0.0, 1.0, 0.5]]])   # (s, t, depth): H = I
>>> if gl.available():
...     m = draw_device_map(tri, np.eye(4), 8)
...     depth, ident = m.fetch(np.array([0, 7, 63]))   # texels (0, 0), (0, 7), (7, 7)
...     m.release()
... else:   # without an EGL device: the numpy reference, whose values these are
...     from aliasing.raster.draw.core import rasterize
...     r = rasterize(tri, 8)
...     depth, ident = r.depth.ravel()[[0, 7, 63]], r.triangle.ravel()[[0, 7, 63]]
>>> ident.tolist(), bool(np.isinf(depth[2]))
([0, -1, -1], True)
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from .. import gl
from ..gl import _GROUP, _Scene, _buffer, _context, _info, _pool, _read, _render, _setup, _targets, _uniform

Array = NDArray[np.float64]

#: Bytes per texel of a map kept on the device (:class:`DeviceMap`: the triangle ids, 4 bytes).
DEVICE_TEXEL_BYTES = 4
#: Device maps are kept up to this many bytes in all (eight 2048² maps); beyond it the least
#: recently drawn are freed (their samplers draw them again if asked for a texel they lack).
DEVICE_BYTES = 2**27
#: Texels per pass of :meth:`DeviceMap.fetch` (its buffers: 12 bytes per texel; 2²¹ / 64 =
#: 32768 work groups, within the 65535 that OpenGL guarantees per dispatch).
FETCH_BLOCK = 1 << 21


# A device map's texels at the asked flat indices row·R + column: the stored id, and the depth
# that :data:`_DEPTH` stores there (the same expression of the visible triangle's
# coefficients at the texel centre, in double precision), as its float32 bits; (0, 0) where empty.
_FETCH = """
#version 430
layout(local_size_x = 64) in;
layout(std430, binding = 6) readonly buffer Asked { int asked[]; };
layout(std430, binding = 7) writeonly buffer Found { ivec2 found[]; };
layout(std430, binding = 8) readonly buffer Coefficients { dvec4 coef[]; };
uniform isampler2D ids_map;
uniform dvec4 ray;        // q_w = ray.x s + ray.y t + ray.z; e_w = ray.w
uniform double texel;     // 1/R
uniform uint count;
uniform int res;
uniform int first;        // every: the texels first, first + 1, … (no asked buffer)
uniform bool every;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    int flat_ = every ? first + int(i) : asked[i];
    ivec2 at = ivec2(flat_ % res, flat_ / res);   // (column, row): row 0 at the bottom
    int raw = texelFetch(ids_map, at, 0).r;
    float stored = 0.0;
    if (raw != 0) {
        dvec4 k = coef[~raw];
        double s = (double(at.x) + 0.5LF) * texel, t = (double(at.y) + 0.5LF) * texel;   // gl_FragCoord of the texel centre
        double a = k.x * s + k.y * t + k.z;
        double den = a * ray.w - k.w * (ray.x * s + ray.y * t + ray.z);
        stored = float(den / (den + a));
    }
    found[i] = ivec2(raw, floatBitsToInt(stored));
}
"""


# The whole map at once (:meth:`DeviceMap.read`): one full-screen triangle whose fragments do what
# :data:`_FETCH` does per texel, written to the targets that :func:`.gl.draw_maps` reads back.
_RESOLVE_VERTEX = """
#version 430
void main() {
    gl_Position = vec4(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0, 0.0, 1.0);
}
"""
_RESOLVE = """
#version 430
layout(std430, binding = 8) readonly buffer Coefficients { dvec4 coef[]; };
uniform isampler2D ids_map;
uniform dvec4 ray;
uniform double texel;
layout(location = 0) out int id_out;
layout(location = 1) out float depth_out;
void main() {
    int raw = texelFetch(ids_map, ivec2(gl_FragCoord.xy), 0).r;
    float stored = 0.0;
    if (raw != 0) {
        dvec4 k = coef[~raw];
        double s = double(gl_FragCoord.x) * texel, t = double(gl_FragCoord.y) * texel;
        double a = k.x * s + k.y * t + k.z;
        double den = a * ray.w - k.w * (ray.x * s + ray.y * t + ray.z);
        stored = float(den / (den + a));
    }
    id_out = raw;
    depth_out = stored;
}
"""


# The shadow test of :func:`aliasing.raster.draw.shadow_test` at points, run where the map is:
# per point, its texel's stored depth as :data:`_FETCH` evaluates it and as the host converts it
# (Δ/stored + offset, in double precision), then the test's three comparisons within ``bias``:
# the point's depth against it, the receiver's plane met on the texel centre's ray (``receiver``,
# −μ of the host's test, +inf where the plane holds the light direction) against it, and the
# occluder's plane met on the point's ray (λ, from the triangle's plane row: vertex a₀ and
# n·up, normal n and whether the plane is usable) against 0.  ``precise`` keeps every product
# and sum rounded as numpy rounds it (no fused multiply-add), in numpy's order.  One bit per
# point comes back: set where lit.
_TEST = """
#version 430
layout(local_size_x = 64) in;
layout(std430, binding = 6) readonly buffer Asked { int asked[]; };
layout(std430, binding = 7) buffer Lit { uint bits[]; };
layout(std430, binding = 8) readonly buffer Coefficients { dvec4 coef[]; };
layout(std430, binding = 3) readonly buffer Points { dvec4 point[]; };       // p.xyz, the point's depth d
layout(std430, binding = 4) readonly buffer Receivers { double receiver[]; };
layout(std430, binding = 5) readonly buffer Planes { dvec4 plane[]; };       // per triangle: (a0, n·up), (n, usable)
uniform isampler2D ids_map;
uniform dvec4 ray;
uniform double texel;
uniform double span;
uniform double offset;
uniform double bias;
uniform uint count;
uniform int res;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    int flat_ = asked[i];
    ivec2 at = ivec2(flat_ % res, flat_ / res);
    int raw = texelFetch(ids_map, at, 0).r;
    bool lit = true;   // an empty texel: nothing nearer the light
    if (raw != 0) {
        dvec4 k = coef[~raw];
        double s = (double(at.x) + 0.5LF) * texel, t = (double(at.y) + 0.5LF) * texel;
        double a = k.x * s + k.y * t + k.z;
        double den = a * ray.w - k.w * (ray.x * s + ray.y * t + ray.z);
        float stored = float(den / (den + a));
        // Δ/stored + offset; ±0 stored gives ±infinity, as IEEE division on the host (built from its bits here)
        precise double depth = stored != 0.0 ? span / double(stored) + offset
                                             : packDouble2x32(uvec2(0u, (floatBitsToUint(stored) & 0x80000000u) | 0x7FF00000u));
        precise double limit = depth + bias;
        dvec4 q = point[i];
        lit = q.w <= limit || receiver[i] <= limit;
        dvec4 o = plane[2 * ~raw], n = plane[2 * ~raw + 1];
        if (!lit && n.w != 0.0LF) {
            precise double lam = ((o.x - q.x) * n.x + (o.y - q.y) * n.y + (o.z - q.z) * n.z) / o.w;
            lit = lam <= bias;
        }
    }
    if (lit) atomicOr(bits[i >> 5], 1u << (i & 31u));
}
"""


def max_resolution() -> int:
    """The largest map side this device can draw [texels] (its texture, render-buffer and
    viewport limits), 0 when the backend is unavailable."""
    info = _info()
    if not info:
        return 0
    dims = info.get("GL_MAX_VIEWPORT_DIMS", (2**31, 2**31))
    return int(min(info.get("GL_MAX_TEXTURE_SIZE", 2**31), info.get("GL_MAX_RENDERBUFFER_SIZE", 2**31), *dims))


def check_size(resolution: int, name: str = "resolution") -> None:
    """Raise ``ValueError`` (one line, with the limit) if a map of ``resolution`` texels per
    side is bigger than the device allows (:func:`max_resolution`), before any work; first
    :func:`aliasing.raster.draw.gl.require` (no device: one line)."""
    gl.require()
    limit = max_resolution()
    if int(resolution) > limit:
        raise ValueError(f"{name} {int(resolution)} is over the largest map the gl device draws, {limit}² texels ({gl.renderer()})")


class DeviceMap:
    """A depth map that stays on the device where it was drawn (:func:`draw_device_map`).

    The device holds the visible triangle's index per texel of the drawn box and the
    triangles' depth coefficients.  :meth:`fetch` returns the depth and triangle of asked
    texels: a compute pass evaluates the depth there (the expression the map's fragment
    shader stores, :data:`_DEPTH`, in double precision, stored as float32) and only those
    texels come back; :meth:`read` is the same for every texel.  The values are
    :func:`.gl.draw_maps`'s (checked in the tests).  ``box`` (x, y, width, height) [texels] is
    the part drawn; a ``released`` map (:meth:`release`, or freed beyond :data:`DEVICE_BYTES`)
    holds nothing.
    """

    def __init__(self, ids, fbo, coef, res: int, box: tuple[int, int, int, int], span: float, offset: float, ray: Array) -> None:
        self._ids, self._fbo, self._coef = ids, fbo, coef
        self.resolution, self.box, self.span, self.offset, self._ray = res, box, span, offset, ray
        self.released = False
        #: Called (if set, and if it returns a callable: e.g. a ``weakref.WeakMethod``) before
        #: the map is freed by :meth:`evict`: a reader that still needs the map reads it then.
        self.on_evict = None

    def evict(self) -> None:
        """Free the map, after its pending reader (:attr:`on_evict`), if any, has read it back."""
        reader = self.on_evict() if self.on_evict is not None and not self.released else None
        if reader is not None:
            reader()
        self.release()

    def covers(self, texels: NDArray[np.int64]) -> bool:
        """Whether every flat texel index of ``texels`` lies in the drawn box."""
        flat = np.asarray(texels, np.int64)
        x, y, w, h = self.box
        row, col = flat // self.resolution, flat % self.resolution
        return bool(((row >= y) & (row < y + h) & (col >= x) & (col < x + w)).all())

    def fetch(self, texels: NDArray[np.int64]) -> tuple[Array, NDArray[np.int64]]:
        """(depth [the map's depth units, ``inf`` where empty], triangle (−1 where empty)) of
        flat texel indices ``texels`` (row·R + column) inside the drawn box."""
        flat = np.asarray(texels, np.int64).ravel()
        if flat.size and (flat.min() < 0 or flat.max() >= self.resolution**2 or not self.covers(flat)):
            raise ValueError(f"texels must be flat indices in [0, {self.resolution**2 - 1}] inside the drawn box {self.box}")
        return self._run(flat, flat.size)

    def read(self) -> tuple[Array, NDArray[np.int64]]:
        """The whole map (drawn whole): (depth, triangle), each (R, R), as :func:`.gl.draw_maps` returns them.

        A full-screen pass evaluates every texel's depth (the fetch pass's expression, run as
        fragments: llvmpipe runs those faster than a compute pass) into the render targets
        that :func:`.gl.draw_maps` reads back, and they are read back and converted the same way."""
        import moderngl

        res = self.resolution
        if self.box != (0, 0, res, res):
            raise ValueError(f"only a map drawn whole can be read whole; this one holds the box {self.box}")
        if self.released:
            raise ValueError("this device map was released: draw it again")
        ctx = _context()
        with ctx:
            programs = _setup()[0][1]
            if "resolve" not in programs:
                programs["resolve"] = ctx.program(vertex_shader=_RESOLVE_VERTEX, fragment_shader=_RESOLVE)
                programs["resolve-array"] = ctx.vertex_array(programs["resolve"], [])
            prog = programs["resolve"]
            self._ids.use(0)
            prog["ids_map"].value = 0
            _uniform(prog, "ray", self._ray)
            _uniform(prog, "texel", np.float64(1.0 / res))
            self._coef.bind_to_storage_buffer(8)
            tg = _targets(ctx, res)
            tg.maps.use()
            tg.maps.viewport = (0, 0, res, res)
            ctx.disable(moderngl.DEPTH_TEST)
            programs["resolve-array"].render(moderngl.TRIANGLES, vertices=3)
            depth, ids = _read(tg, self.span, self.offset)
        return depth, ids

    def test(self, texels: NDArray[np.int64], points: Array, receiver: Array, planes: Array, bias: float) -> NDArray[np.bool_]:
        """The shadow test of :func:`aliasing.raster.draw.shadow_test` run on the device: lit (True) or not, per point.

        ``texels`` (P,) the points' flat texel indices inside the drawn box; ``points`` (P, 4)
        their positions [world units] and depths [the map's depth units]; ``receiver`` (P,)
        the receiver term −μ (+inf where unusable); ``planes`` the triangles' plane rows
        (``_plane_rows``, uploaded to a kept buffer); ``bias`` [world units].  Only one bit per
        point comes back."""
        flat = np.asarray(texels, np.int64).ravel()
        count = flat.size
        points, receiver = np.asarray(points, np.float64), np.asarray(receiver, np.float64)
        if not np.isfinite(bias) or bias < 0:
            raise ValueError(f"bias must be a finite tolerance >= 0 [world units], got {bias}")
        if points.shape != (count, 4) or receiver.shape != (count,):
            raise ValueError(f"points must have shape ({count}, 4) and receiver ({count},), got {points.shape} and {receiver.shape}")
        drawn = self._coef.size // 32  # the triangles the map was drawn from
        if np.shape(planes)[1:] != (4,) or len(planes) < 2 * drawn:
            raise ValueError(f"planes must be the plane rows of the map's {drawn} triangles, shape ({2 * drawn}, 4), got {np.shape(planes)}")
        if count and (flat.min() < 0 or flat.max() >= self.resolution**2 or not self.covers(flat)):
            raise ValueError(f"texels must be flat indices in [0, {self.resolution**2 - 1}] inside the drawn box {self.box}")
        if self.released:
            raise ValueError("this device map was released: draw it again")
        out = np.empty(count, bool)
        ctx = _context()
        with ctx:
            programs = _setup()[0][1]
            if "test" not in programs:
                programs["test"] = ctx.compute_shader(_TEST)
            prog = programs["test"]
            self._ids.use(0)
            prog["ids_map"].value = 0
            _uniform(prog, "ray", self._ray)
            for name, value in (("texel", 1.0 / self.resolution), ("span", self.span), ("offset", self.offset), ("bias", bias)):
                _uniform(prog, name, np.float64(value))
            prog["res"].value = self.resolution
            self._coef.bind_to_storage_buffer(8)
            rows = np.ascontiguousarray(planes, np.float64)
            kept = _buffer(ctx, "planes", max(rows.nbytes, 32))
            kept.write(rows)
            kept.bind_to_storage_buffer(5)
            for a in range(0, count, FETCH_BLOCK):
                n = min(FETCH_BLOCK, count - a)
                words = (n + 31) // 32
                for name, binding, data in (("asked", 6, flat[a:a + n].astype(np.int32)), ("points", 3, np.ascontiguousarray(points[a:a + n], np.float64)),
                                            ("receivers", 4, np.ascontiguousarray(receiver[a:a + n], np.float64)), ("lit", 7, np.zeros(words, np.uint32))):
                    buf = _buffer(ctx, name, data.nbytes)
                    buf.write(data)
                    buf.bind_to_storage_buffer(binding)
                prog["count"].value = n
                prog.run(group_x=(n + _GROUP - 1) // _GROUP)
                ctx.memory_barrier()
                bits = np.frombuffer(_buffer(ctx, "lit", 4 * words).read(4 * words), np.uint32)
                out[a:a + n] = np.unpackbits(bits.view(np.uint8), bitorder="little")[:n].astype(bool)
        return out

    def _run(self, flat: NDArray[np.int64] | None, count: int) -> tuple[Array, NDArray[np.int64]]:
        """(depth, triangle) of ``flat`` texels, or of the first ``count`` ones (``flat`` None).

        Each block's stored (id, depth) pairs are converted by :func:`.gl._pool`'s threads
        while the next block is evaluated: ids −1 − raw (the cleared 0 gives −1), depth
        Δ/stored + offset (``inf`` where 0 is stored), as :func:`.gl.draw_maps` converts them."""
        if self.released:
            raise ValueError("this device map was released: draw it again")
        depth = np.empty(count)
        ids = np.empty(count, np.int64)
        if not count:
            return depth, ids

        def convert(host: np.ndarray, a: int, lo: int, hi: int) -> None:
            np.subtract(-1, host[lo:hi, 0], out=ids[a + lo:a + hi], dtype=np.int64)  # ~id = −1 − id
            with np.errstate(divide="ignore"):
                np.divide(self.span, host[lo:hi, 1].view(np.float32), out=depth[a + lo:a + hi], dtype=np.float64)  # Δ (1 + dₙ)
            depth[a + lo:a + hi] += self.offset

        pending = []
        ctx = _context()
        with ctx:
            programs = _setup()[0][1]
            if "fetch" not in programs:
                programs["fetch"] = ctx.compute_shader(_FETCH)
            prog = programs["fetch"]
            self._ids.use(0)
            prog["ids_map"].value = 0
            _uniform(prog, "ray", self._ray)
            _uniform(prog, "texel", np.float64(1.0 / self.resolution))
            prog["res"].value = self.resolution
            prog["every"].value = flat is None
            self._coef.bind_to_storage_buffer(8)
            for a in range(0, count, FETCH_BLOCK):
                n = min(FETCH_BLOCK, count - a)
                if flat is not None:
                    asked = _buffer(ctx, "asked", 4 * n)
                    asked.write(flat[a:a + n].astype(np.int32))
                    asked.bind_to_storage_buffer(6)
                else:
                    _buffer(ctx, "asked", 4).bind_to_storage_buffer(6)  # not read
                    prog["first"].value = a
                found = _buffer(ctx, "found", 8 * n)
                found.bind_to_storage_buffer(7)
                prog["count"].value = n
                prog.run(group_x=(n + _GROUP - 1) // _GROUP)
                ctx.memory_barrier()
                host = np.empty((n, 2), np.int32)
                found.read_into(host, 8 * n)
                step = max(1 << 16, -(-n // (4 * gl.THREADS)))
                pending += [_pool().submit(convert, host, a, lo, min(lo + step, n)) for lo in range(0, n, step)]
        for job in pending:
            job.result()
        return depth, ids

    def release(self) -> None:
        """Free the map's device memory (a released map cannot be read)."""
        if self.released:
            return
        self.released = True
        state = _setup()[0]
        if state is not None and self in state[4]:
            state[4].remove(self)
        spare = state[5] if state is not None else []
        with _context():
            self._coef.release()
            if state is not None and DEVICE_TEXEL_BYTES * (self.resolution**2 + sum(r * r for r, _, _ in spare)) <= DEVICE_BYTES:
                spare.append((self.resolution, self._ids, self._fbo))  # kept for the next map of this size (making one costs more than drawing it on llvmpipe)
            else:
                self._fbo.release()
                self._ids.release()


def _plane_rows(triangles: Array, up: Array) -> Array:
    """The occluder planes of :func:`aliasing.raster.draw.shadow_test`, two rows per triangle
    for :meth:`DeviceMap.test`: (a₀, n·up) and (n, 1 where usable else 0), n = (a₁ − a₀) × (a₂ − a₀),
    computed as the host's test computes them per point (numpy's own arithmetic, so the same
    doubles); shape (2T, 4)."""
    a = np.asarray(triangles, float)
    n_o = np.cross(a[:, 1, :] - a[:, 0, :], a[:, 2, :] - a[:, 0, :])
    across = n_o @ up
    ok = np.abs(across) > 1e-9 * np.linalg.norm(n_o, axis=-1)
    rows = np.empty((len(a), 2, 4))
    rows[:, 0, :3], rows[:, 0, 3] = a[:, 0, :], across
    rows[:, 1, :3], rows[:, 1, 3] = n_o, ok
    return rows.reshape(-1, 4)


def draw_device_map(triangles: Array, matrix: Array, resolution: int, *, box: tuple[int, int, int, int] | None = None) -> DeviceMap:
    """The depth map of eye-space ``triangles`` (T, 3, 3) through the projective map ``matrix``
    (4×4, :meth:`aliasing.raster.LightMap.matrix`) at ``resolution``, kept on the device.

    Only the visible triangles' indices are drawn (the depth test is :func:`.gl.draw_maps`'s),
    within ``box`` (x, y, width, height) [texels] if given (default: the whole map); the
    depths are evaluated where they are fetched (:class:`DeviceMap`).  Raises ``ValueError``
    (one line) when there is no device or the map is bigger than it allows
    (:func:`check_size`), before any work.
    """
    return draw_device_maps(triangles, [matrix], [resolution], boxes=[box])[0][0]


def draw_device_maps(triangles: Array, matrices: Sequence[Array], resolutions: Sequence[int], *,
                     boxes: Sequence[tuple[int, int, int, int] | None] | None = None) -> tuple[list[DeviceMap], int]:
    """:func:`draw_device_map` of several maps, the triangles uploaded and prepared once; and the
    number of triangles not drawn because a coordinate is not finite.

    Maps kept from earlier calls are freed, least recently drawn first, until this call's maps
    fit in :data:`DEVICE_BYTES` with the others (a map with a pending reader, such as a
    :class:`~aliasing.raster.draw.DepthMap` of ``shadow_map(..., backend="gl")``, is read back
    to the host first: :meth:`DeviceMap.evict`).
    """
    import moderngl

    rs = [int(r) for r in resolutions]
    for r in rs:
        check_size(r)
    tri = np.asarray(triangles, float)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise ValueError(f"triangles must have shape (T, 3, 3), got {tri.shape}")
    if len(matrices) != len(rs):
        raise ValueError(f"matrices and resolutions must have one entry per map, got {len(matrices)} and {len(rs)}")
    given = [None] * len(rs) if boxes is None else list(boxes)
    chosen = []
    for res, box in zip(rs, given):
        box = (0, 0, res, res) if box is None else tuple(int(v) for v in box)
        if len(box) != 4 or box[0] < 0 or box[1] < 0 or box[2] < 1 or box[3] < 1 or box[0] + box[2] > res or box[1] + box[3] > res:
            raise ValueError(f"box must be (x, y, width, height) inside the {res}² map, got {box}")
        chosen.append(box)
    state = _setup()[0]
    ctx, live, spare = state[0], state[4], state[5]
    need = DEVICE_TEXEL_BYTES * sum(r * r for r in rs)
    while live and need + sum(DEVICE_TEXEL_BYTES * m.resolution**2 for m in live) > DEVICE_BYTES:
        live[0].evict()  # the least recently drawn
    out = []
    with ctx:
        scene = _Scene(ctx, state[1], tri) if tri.shape[0] else None
        bad = scene.bad if scene is not None else 0
        try:
            for h, res, box in zip(matrices, rs, chosen):
                kept = [i for i, (r, _, _) in enumerate(spare) if r == res]
                if kept:
                    _, ids, fbo = spare.pop(kept[-1])
                else:
                    while spare and DEVICE_TEXEL_BYTES * (res * res + sum(r * r for r, _, _ in spare) + sum(m.resolution**2 for m in live)) > DEVICE_BYTES:
                        _, old_ids, old_fbo = spare.pop(0)
                        old_fbo.release()
                        old_ids.release()
                    ids = ctx.texture((res, res), 1, dtype="i4")
                    ids.filter = (moderngl.NEAREST, moderngl.NEAREST)  # an integer texture is complete only so
                    fbo = ctx.framebuffer([ids], _zbuffer(ctx, res))
                coef = ctx.buffer(reserve=max(32 * tri.shape[0], 16))
                span, offset, ray = 1.0, 0.0, np.zeros(4)
                if scene is not None and scene.bad < scene.count:
                    span, offset, ray = _render(scene, np.asarray(h, float), res, fbo, program="ids", box=box)
                    ctx.copy_buffer(coef, scene.coefficients, 32 * tri.shape[0])  # the next map's draw overwrites the kept ones
                else:
                    fbo.use()
                    fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0, viewport=box)
                m = DeviceMap(ids, fbo, coef, res, box, span, offset, ray)
                live.append(m)
                out.append(m)
        finally:
            if scene is not None:
                scene.release()
    return out, bad


def _zbuffer(ctx, res: int):
    """The z-buffer shared by the device maps of resolution ``res`` (kept; :func:`release` frees it)."""
    kept = _setup()[0][3]
    name = f"zbuffer{res}"
    if name not in kept:
        kept[name] = ctx.depth_renderbuffer((res, res))
    return kept[name]
