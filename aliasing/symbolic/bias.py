"""Depth bias against shadow acne and the peter-panning it costs, derived from the texel footprint.

No paper prints these; each is derived here from the geometry of one texel, and the numeric
code (:mod:`aliasing.bias`) is tested against it on grids.

Set-up.  A directional light; the map plane is perpendicular to it, with axes s (x) and t (y)
and height h along the direction to the light.  A planar receiver whose normal makes the
angle θ with the direction to the light has height h = −tan θ·(x cos φ + y sin φ) over the
map plane: its depth (−h) grows fastest along the azimuth φ, measured from the s axis, at
tan θ per world unit.  A texel is the square [−w/2, w/2]² around its centre c (w: the texel
width [world units]); it stores the receiver's depth on the ray through c.

* ``bias.corners``: nearest lookup.  A point p of the texel is compared with the depth
  stored at c; it shadows itself (acne) when its depth exceeds the stored one by more than
  the bias b.  Depth is affine in p, so the largest excess over the texel is at a corner:
  b_min = max over the four corners of tan θ·(±w/2·cos φ ± w/2·sin φ)
  = (w/2)·tan θ·(|cos φ| + |sin φ|).
* ``bias.depth``: that maximum in closed form (for φ in the first quadrant; the numeric code
  uses |cos φ|, |sin φ|, tested against ``bias.corners`` for every φ).
* ``bias.pcf``: k×k percentage-closer filtering.  Tap (i, j), i, j ∈ {−(k−1)/2 … (k−1)/2},
  reads the texel under p + w·(i, j) and compares p's own depth with it: the excess is
  tan θ·((i + a)·w cos φ + (j + b)·w sin φ) with |a|, |b| ≤ 1/2, largest at the outermost tap
  and the far corner of its texel: b_min = (k/2)·w·tan θ·(|cos φ| + |sin φ|) (k = 1 is nearest).
* ``bias.receiver_plane``: receiver-plane depth bias (Isidoro 2006): each tap compares the
  receiver plane's own depth at the tap's position, not p's, with the depth stored at its
  texel's centre: the excess is that of one texel, for every k: b_min = (w/2)·tan θ·(|cos φ| + |sin φ|).
* ``bias.normal_offset``: moving the looked-up point by o along the receiver's normal raises
  it o cos θ towards the light and shifts it o sin θ across the map, where the plane lies
  o sin θ·tan θ lower: the point stands o/cos θ above the plane along the light, a depth
  bias of o/cos θ wherever it lands.  Hence o_min = b_min·cos θ = (w/2)·sin θ·(|cos φ| + |sin φ|).
* ``bias.slope``: the slope-scaled factor of a depth bias b = factor·max(|∂d/∂s|, |∂d/∂t|)
  (Direct3D ``SlopeScaledDepthBias``, the depth slope per texel): w·tan θ·max(|cos φ|, |sin φ|)
  per texel, so factor_min = (k/2)·(|cos φ| + |sin φ|)/max(|cos φ|, |sin φ|): k/2 on an axis, k at 45°,
  independent of θ (a slope-scaled bias alone fits every tilt at one azimuth).
* ``bias.lit_gap``: peter-panning.  A vertical caster stands on horizontal ground lit at
  elevation α.  The ground point at distance g behind the caster's foot sees the caster on
  its ray to the light at height g·tan α, g/cos α nearer the light along the ray; a constant
  depth bias b keeps it lit while g/cos α ≤ b: the lit gap is g = b·cos α.  The map stores the
  caster's surface nearest the light: for a caster of thickness D (a box) the ray leaves it
  (g + D)/cos α nearer the light, and the gap is b·cos α − D (while positive, and for casters
  taller than b·sin α; a shorter one casts no shadow at all).
* ``bias.pcf_footprint``: a k×k PCF kernel reaches k texels of width w: k·w world units, k·w/p
  pixels where a pixel covers p world units (across the view at depth z: p = 2 z tan(fov/2)/N for N
  pixels across).
* ``bias.blend_band``: the seam between cascades i and i + 1.  At their boundary the two maps'
  texels are w_i and w_{i+1} = s·w_i (s: the step); a kernel fixed in texels jumps from k·w_i to
  k·s·w_i.  Blending the two filtered results with a weight t that ramps linearly from 0 to 1
  over N pixels filters with the mixture (1 − t)·K_i + t·K_{i+1}, whose mean radius is
  (1 − t)·r_i + t·r_{i+1}: the blur width changes by (s − 1)·k·w_i/N per pixel.  Keeping that
  below a fraction f of the narrower width k·w_i needs N ≥ (s − 1)/f pixels, whatever k.

Example
-------
>>> import sympy as sp
>>> sp.simplify(normal_offset() - depth() * sp.cos(theta))
0
>>> lit_gap().subs(D, 0)
b*cos(alpha)
"""

from __future__ import annotations

import sympy as sp

from .registry import derivation

theta = sp.Symbol("theta", positive=True)  # receiver normal to the direction to the light, [0, π/2)
phi = sp.Symbol("phi", real=True)  # azimuth of the steepest depth increase from the s axis
w = sp.Symbol("w", positive=True)  # texel width [world units]
k = sp.Symbol("k", positive=True, integer=True)  # PCF kernel width [texels]
o = sp.Symbol("o", positive=True)  # normal offset [world units]
alpha = sp.Symbol("alpha", positive=True)  # light elevation above the ground
b = sp.Symbol("b", positive=True)  # constant depth bias [world units]
g = sp.Symbol("g", positive=True)  # distance along the ground from the caster's foot
p_px = sp.Symbol("p", positive=True)  # a pixel's width at the receiver [world units]
s_step = sp.Symbol("s", positive=True)  # texel step across a cascade boundary, w_{i+1}/w_i
f_rate = sp.Symbol("f", positive=True)  # allowed change of the blur width per pixel, a fraction of the narrower
n_px = sp.Symbol("N", positive=True)  # width of the blend band [pixels]
D = sp.Symbol("D", nonnegative=True)  # the caster's thickness along the light's horizontal direction (0: a wall)


def _excess(dx: sp.Expr, dy: sp.Expr) -> sp.Expr:
    """Depth at c + (dx, dy) minus depth at c on the receiver plane: tan θ·(dx cos φ + dy sin φ)."""
    return sp.tan(theta) * (dx * sp.cos(phi) + dy * sp.sin(phi))


@derivation("bias.corners", "derived (texel geometry)", "nearest lookup: the largest self-shadowing excess over a texel, the maximum over its four corners")
def corners() -> sp.Expr:
    # p = c + δ, the stored depth is at c: excess d(p) − d(c) is affine in δ, largest at a corner
    return sp.Max(*[_excess(sx * w / 2, sy * w / 2) for sx in (-1, 1) for sy in (-1, 1)])


@derivation("bias.depth", "derived (texel geometry)", "nearest lookup: minimal constant depth bias, (w/2) tan θ (|cos φ| + |sin φ|)")
def depth() -> sp.Expr:
    # in the first quadrant (cos φ, sin φ ≥ 0) the corner (+w/2, +w/2) is the largest
    first = _excess(w / 2, w / 2)
    return sp.factor(sp.simplify(first.subs(sp.cos(phi), sp.Abs(sp.cos(phi))).subs(sp.sin(phi), sp.Abs(sp.sin(phi)))))


@derivation("bias.pcf", "derived (texel geometry)", "k×k PCF: minimal constant depth bias, (k/2) w tan θ (|cos φ| + |sin φ|)")
def pcf() -> sp.Expr:
    # outermost tap i = j = (k − 1)/2 (by symmetry, the sign that matches cos φ, sin φ), far corner a = b = 1/2
    tap = (k - 1) / 2 + sp.Rational(1, 2)
    first = _excess(tap * w, tap * w)
    return sp.factor(sp.simplify(first.subs(sp.cos(phi), sp.Abs(sp.cos(phi))).subs(sp.sin(phi), sp.Abs(sp.sin(phi)))))


def pcf_taps(kk: int) -> sp.Expr:
    """The k×k PCF maximum by brute force for a given integer k: every tap, every corner of its texel."""
    offs = [sp.Rational(2 * i - (kk - 1), 2) for i in range(kk)]
    return sp.Max(*[_excess((i + sx / sp.Integer(2)) * w, (j + sy / sp.Integer(2)) * w) for i in offs for j in offs for sx in (-1, 1) for sy in (-1, 1)])


@derivation("bias.receiver_plane", "derived (texel geometry); receiver-plane depth bias after Isidoro 2006", "k×k PCF with receiver-plane depth: each tap's excess is one texel's, for every k")
def receiver_plane() -> sp.Expr:
    # tap at q = p + w(i, j): reference = the plane's depth at q; stored = the plane's depth at q's
    # texel centre c_q; q − c_q = w(a, b) with |a|, |b| ≤ 1/2 whatever i, j: affine, largest at a corner
    a_, b_ = sp.symbols("a b", real=True)
    excess = _excess(a_ * w, b_ * w)
    first = excess.subs({a_: sp.Rational(1, 2), b_: sp.Rational(1, 2)})
    return sp.factor(sp.simplify(first.subs(sp.cos(phi), sp.Abs(sp.cos(phi))).subs(sp.sin(phi), sp.Abs(sp.sin(phi)))))


@derivation("bias.offset_height", "derived (receiver geometry)", "height along the light of a point moved by o along the receiver's normal, above the receiver plane where it lands: o / cos θ")
def offset_height() -> sp.Expr:
    # light along +h; the normal n = (sin θ·(cos φ, sin φ), cos θ): tilted towards where the plane falls away
    n = sp.Matrix([sp.sin(theta) * sp.cos(phi), sp.sin(theta) * sp.sin(phi), sp.cos(theta)])
    x0, y0 = sp.symbols("x0 y0", real=True)
    plane_h = lambda x, y: -sp.tan(theta) * (x * sp.cos(phi) + y * sp.sin(phi))  # noqa: E731
    p = sp.Matrix([x0, y0, plane_h(x0, y0)])
    q = p + o * n
    # check that n is the plane's normal: orthogonal to both tangents
    t1 = sp.Matrix([1, 0, sp.diff(plane_h(x0, y0), x0)])
    t2 = sp.Matrix([0, 1, sp.diff(plane_h(x0, y0), y0)])
    assert sp.simplify(n.dot(t1)) == 0 and sp.simplify(n.dot(t2)) == 0
    return sp.simplify(q[2] - plane_h(q[0], q[1]))


@derivation("bias.normal_offset", "derived (receiver geometry)", "minimal normal offset: o with o / cos θ equal to the minimal depth bias, (w/2) sin θ (|cos φ| + |sin φ|)")
def normal_offset() -> sp.Expr:
    (sol,) = sp.solve(sp.Eq(offset_height(), depth()), o)
    return sp.simplify(sol)


@derivation("bias.slope", "derived (texel geometry)", "minimal slope-scaled factor on max(|∂d/∂s|, |∂d/∂t|) per texel, first octant 0 ≤ φ ≤ π/4")
def slope() -> sp.Expr:
    per_texel = w * sp.tan(theta) * sp.cos(phi)  # max(|cos φ|, |sin φ|) = cos φ for 0 ≤ φ ≤ π/4
    return sp.simplify(pcf() / per_texel.subs(sp.cos(phi), sp.Abs(sp.cos(phi))))


@derivation("bias.lit_gap", "derived (caster geometry)", "lit gap behind a vertical caster of thickness D on horizontal ground, light at elevation α, constant depth bias b: b cos α − D")
def lit_gap() -> sp.Expr:
    # ground point (−g, 0) behind the caster's shadow-side face x = 0; its ray to the light
    # (cos α, sin α)·λ leaves the caster through its lit face x = D at λ = (g + D)/cos α (a
    # caster taller than b sin α): the depth stored there is that far nearer the light
    lam = sp.Symbol("lambda", positive=True)
    (hit,) = sp.solve(sp.Eq(-g + lam * sp.cos(alpha), D), lam)
    (gap,) = sp.solve(sp.Eq(hit, b), g)  # lit while the stored surface is no more than b nearer along the ray
    return gap


@derivation("bias.projection_ground", "Lloyd 2006 §3.3 (projection factor), derived for the ground", "cos ψ_e / cos ψ_l on the ground: h / (sin α sqrt(h² + d²))")
def projection_ground() -> sp.Expr:
    h, dd = sp.symbols("h d", positive=True)
    n = sp.Matrix([0, 1, 0])  # the ground's normal; the eye at height h, the point d away horizontally
    to_eye = sp.Matrix([0, h, -dd]) / sp.sqrt(h**2 + dd**2)
    to_light = sp.Matrix([0, sp.sin(alpha), sp.cos(alpha)])
    return sp.simplify(n.dot(to_eye) / n.dot(to_light))


@derivation("bias.pcf_footprint", "derived (texel geometry)", "k×k PCF footprint in pixels: k·w/p (k texels of width w, pixels p world units wide)")
def pcf_footprint() -> sp.Expr:
    return k * w / p_px


@derivation("bias.blend_band", "derived (mixture of two kernels)", "blend band hiding a cascade seam: N ≥ (s − 1)/f pixels for a blur width changing by at most f per pixel")
def blend_band() -> sp.Expr:
    t = sp.Symbol("t", nonnegative=True)  # blend weight, 0 at the band's start, 1 at its end
    width = (1 - t) * k * w + t * k * s_step * w  # mean radius of the mixture (1 − t)K_i + t K_{i+1}, × 2
    per_pixel = sp.diff(width, t) / n_px  # t = x/N over the band's N pixels
    (n,) = sp.solve(sp.Eq(per_pixel, f_rate * k * w), n_px)
    return sp.simplify(n)
