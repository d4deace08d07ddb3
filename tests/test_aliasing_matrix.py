"""Lloyd et al. 2007 §3.4 (eqs. 32–40): the 3D aliasing matrix M_a, derived and numeric.

* the chain of eq. 35 (each factor by differentiating its projection) equals sympy's own
  derivative of the composite map s → u → p_l → p → p_e → i, and the 3D Jacobians equal
  eqs. 8, 9 and the corrected eq. 26 as printed;
* (a) in a configuration in the y–z plane, M_a is diagonal and its t–j element is the 2D m
  of eq. 19;
* (b) the numeric M_a equals the lambdified symbolic one and a finite-difference Jacobian of
  an independent implementation of the pipeline;
* (c) on the half-way surface of §3.3, |det M_a| is the ratio of the beams' cross-section
  areas (the two 3D definitions of m̃ agree for the determinant), while the norms do not.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from aliasing import logpsm
from aliasing.aliasing_matrix import Camera, aliasing_matrix, camera_axes, cross_sections, error_metric, halfway_normal, spacing_eye, spacing_light
from aliasing.symbolic import lloyd2007 as L2
from aliasing.symbolic import lloyd2007_matrix as M

RNG_SEED = 2007


# --- symbolic ----------------------------------------------------------------------------------


def test_eqs8_9_26_hold_in_3d():
    pj = M.printed_jacobians_3d()
    assert sp.simplify(M.jacobian_eye_3d() - pj["eq8"]) == sp.zeros(3, 3)
    assert sp.simplify(M.jacobian_light_3d() - pj["eq9"]) == sp.zeros(3, 3)
    assert sp.simplify(M.jacobian_directional_3d() - pj["eq26"]) == sp.zeros(3, 3)


@pytest.mark.parametrize("light", ["point", "directional"])
def test_eq35_chain_equals_derivative_of_the_composite_map(light):
    rng = np.random.default_rng(RNG_SEED)
    direct, _ = M.direct_jacobian(light)
    chain_syms = M.di_ds(light).free_symbols
    vals = {}
    for q in sorted(direct.free_symbols | chain_syms, key=str):
        num = int(rng.integers(1, 40)) if q.is_positive else int(rng.integers(-40, 40))
        vals[q] = sp.Rational(num, int(rng.integers(1, 9)))
    p_light = M.light_plane_point().xreplace(vals)
    project = M.project_point_light if light == "point" else M.project_directional
    point = project(p_light).xreplace(vals)
    chain = M.di_ds(light, p_light=p_light).xreplace({**vals, **dict(zip(M.p, point))})
    assert direct.xreplace(vals) - chain == sp.zeros(2, 2)  # exact rationals


@pytest.mark.parametrize("light, m2d", [("point", L2.m_point_2d), ("directional", L2.m_directional_2d)])
def test_a_in_plane_M_a_reduces_to_eq19(light, m2d):
    Mi = M.M_a_in_plane(light)
    assert Mi[0, 1] == 0 and Mi[1, 0] == 0
    assert sp.cancel(sp.together(Mi[1, 1] / m2d())) == 1
    if light == "point":  # and the s–i element: (r_i/r_s) g11 (W_lx/W_ex)(n_e/n_l)(d_l/d_e), the x analogue
        g = L2.configuration_2d()
        d_e, d_l = g["subs"][L2.d_e], g["subs"][L2.d_l]
        target = M.r_i / M.r_s * M.g11 * M.W_lx / M.W_ex * L2.n_e / L2.n_l * d_l / d_e
        assert sp.cancel(sp.together(Mi[0, 0] / target)) == 1


def test_eq40_delta_e_and_the_3d_form_of_eq27():
    # in the plane δ_e = (∂i/∂u)⁻¹ is diagonal and its t element is the 2D δ_e of eq. 27 (exact, random rationals)
    origin, nz = sp.zeros(3, 1), sp.Matrix([0, 0, 1])
    de = M.delta_e_3d("point", origin, nz).xreplace(M.embedding_2d())
    ref = L2.delta_e()
    rng = np.random.default_rng(1)
    for _ in range(3):
        pt = {q: sp.Rational(int(rng.integers(1, 30)), int(rng.integers(1, 7))) for q in de.free_symbols | ref.free_symbols}
        pt.update({L2.L2: pt.get(L2.L2, 1) + 40, L2.E2: pt.get(L2.E2, 1) + 40})  # eye and light above the surface
        assert de[0, 1].xreplace(pt) == 0 and de[1, 0].xreplace(pt) == 0
        assert de[1, 1].xreplace(pt) == ref.xreplace(pt)


# --- configurations ----------------------------------------------------------------------------


def _rotation(rng, k):
    q, r = np.linalg.qr(rng.normal(size=(k, 3, 3)))
    q = q * np.sign(np.diagonal(r, axis1=-2, axis2=-1))[:, None, :]
    return q * np.sign(np.linalg.det(q))[:, None, None]  # proper rotations, rows x, y, z


def _frame_towards(rng, target_dir, k):
    """Axes whose −ẑ is within ~30° of target_dir (so the target is in front)."""
    z = -(target_dir + 0.4 * rng.normal(size=(k, 3)) * np.linalg.norm(target_dir, axis=-1, keepdims=True))
    return camera_axes(-z, rng.normal(size=(k, 3)))


def random_configurations(k=40, directional=False, seed=RNG_SEED):
    """k random configurations with the point in front of the eye and of a point light, on its lit side."""
    rng = np.random.default_rng(seed)
    point = rng.normal(size=(k, 3))
    e = point + rng.uniform(2, 8, (k, 1)) * rng.normal(size=(k, 3))
    eye_axes = _frame_towards(rng, point - e, k)
    if directional:
        l_dir = rng.normal(size=(k, 3))
        l_axes, towards_light = _frame_towards(rng, -l_dir, k), l_dir
        keep = np.einsum("ki,ki->k", l_axes[:, 2], l_dir) > 0.2
    else:
        l_pos = point + rng.uniform(2, 8, (k, 1)) * rng.normal(size=(k, 3))
        l_axes, towards_light = _frame_towards(rng, point - l_pos, k), l_pos - point
        keep = np.einsum("ki,ki->k", l_axes[:, 2], l_pos - point) > 0
    keep &= np.einsum("ki,ki->k", eye_axes[:, 2], e - point) > 0
    normal = rng.normal(size=(k, 3))
    normal = normal * np.sign(np.einsum("ki,ki->k", normal, towards_light))[:, None]  # lit side
    keep &= np.abs(np.einsum("ki,ki->k", normal, towards_light)) > 0.05 * np.linalg.norm(normal, axis=-1) * np.linalg.norm(towards_light, axis=-1)
    delta_l = np.eye(2) + 0.3 * rng.normal(size=(k, 2, 2))
    eye = Camera(axes=eye_axes[keep], position=e[keep], near=rng.uniform(0.2, 2, k)[keep], width=rng.uniform(0.5, 3, (k, 2))[keep])
    if directional:
        light = Camera(axes=l_axes[keep], direction=l_dir[keep], width=rng.uniform(2, 20, (k, 2))[keep])
    else:
        light = Camera(axes=l_axes[keep], position=l_pos[keep], near=rng.uniform(0.2, 2, k)[keep], width=rng.uniform(0.5, 3, (k, 2))[keep])
    assert keep.sum() >= k // 2
    return point[keep], normal[keep], eye, light, delta_l[keep]


@pytest.mark.parametrize("directional", [False, True])
def test_b_numeric_equals_symbolic(directional):
    point, normal, eye, light, delta_l = random_configurations(12, directional)
    expr = M.aliasing_matrix_directional() if directional else M.aliasing_matrix()
    groups = [(M.p, point), (M.N, normal), (M.e, eye.position), (M.x_e, eye.axes[:, 0]), (M.y_e, eye.axes[:, 1]), (M.z_e, eye.axes[:, 2]),
              (M.x_l, light.axes[:, 0]), (M.y_l, light.axes[:, 1]), (M.z_l, light.axes[:, 2])]
    groups.append((M.l_hat, light.direction) if directional else (M.l, light.position))
    syms, cols = [], []
    for vec, arr in groups:
        syms += list(vec)
        cols += [arr[:, k] for k in range(3)]
    scal = [(M.n_e, eye.near), (M.n_l, light.near), (M.W_ex, eye.width[:, 0]), (M.W_ey, eye.width[:, 1]), (M.W_lx, light.width[:, 0]), (M.W_ly, light.width[:, 1]),
            (M.r_i, 640.0), (M.r_j, 480.0), (M.r_s, 1024.0), (M.r_t, 512.0),
            (M.g11, delta_l[:, 0, 0]), (M.g12, delta_l[:, 0, 1]), (M.g21, delta_l[:, 1, 0]), (M.g22, delta_l[:, 1, 1])]
    syms += [q for q, _ in scal]
    cols += [np.broadcast_to(val, point.shape[:1]) for _, val in scal]
    used = [k for k, q in enumerate(syms) if q in expr.free_symbols]
    got = aliasing_matrix(point, normal, eye, light, delta_l=delta_l, res_image=[640.0, 480.0], res_map=[1024.0, 512.0])
    ref = sp.lambdify([syms[k] for k in used], expr, modules="numpy", cse=True)(*[cols[k] for k in used])
    ref = np.moveaxis(np.array(ref, dtype=float), -1, 0)  # (k, 2, 2)
    np.testing.assert_allclose(got, ref, rtol=1e-10, atol=1e-12 * np.abs(ref).max())


def _pipeline(s, G, surface_point, normal, eye, light):
    """Independent forward map s → i: window point, ray–plane intersection, similar triangles."""
    u = G(s)
    if light.directional:
        origin = np.zeros(3) - light.width[0] / 2 * light.axes[0] - light.width[1] / 2 * light.axes[1]
        p_l = origin + u[0] * light.width[0] * light.axes[0] + u[1] * light.width[1] * light.axes[1]
        ray = -light.direction
    else:
        corner = light.position - light.near * light.axes[2] - light.width[0] / 2 * light.axes[0] - light.width[1] / 2 * light.axes[1]
        p_l = corner + u[0] * light.width[0] * light.axes[0] + u[1] * light.width[1] * light.axes[1]
        ray = p_l - light.position
    tau = np.dot(normal, surface_point - p_l) / np.dot(normal, ray)
    p = p_l + tau * ray
    d_e = np.dot(eye.axes[2], eye.position - p)
    p_e = eye.position + eye.near / d_e * (p - eye.position)
    corner_e = eye.position - eye.near * eye.axes[2] - eye.width[0] / 2 * eye.axes[0] - eye.width[1] / 2 * eye.axes[1]
    return np.array([np.dot(eye.axes[0], p_e - corner_e) / eye.width[0], np.dot(eye.axes[1], p_e - corner_e) / eye.width[1]]), p


@pytest.mark.parametrize("directional", [False, True])
def test_b_M_a_equals_finite_difference_jacobian_of_the_pipeline(directional):
    point, normal, eye, light, _ = random_configurations(25, directional, seed=11)
    rng = np.random.default_rng(5)
    h = 1e-6
    checked = 0
    for k in range(point.shape[0]):
        A, c = np.eye(2) + 0.2 * rng.normal(size=(2, 2)), rng.uniform(0.5, 2.0, 2)
        G = lambda s: 0.5 + A @ (s - 0.5) + 0.1 * np.sin(c * s[::-1])  # noqa: E731  nonlinear u = G(s)
        dG = lambda s: A + 0.1 * np.array([[0.0, c[0] * np.cos(c[0] * s[1])], [c[1] * np.cos(c[1] * s[0]), 0.0]])  # noqa: E731
        s0 = rng.uniform(0.2, 0.8, 2)
        ek = Camera(axes=eye.axes[k], position=eye.position[k], near=eye.near[k], width=eye.width[k])
        lk = Camera(axes=light.axes[k], direction=light.direction[k], width=light.width[k]) if directional else Camera(
            axes=light.axes[k], position=light.position[k], near=light.near[k], width=light.width[k])
        _, p = _pipeline(s0, G, point[k], normal[k], ek, lk)
        if np.dot(ek.axes[2], ek.position - p) <= 0 or (not directional and np.dot(lk.axes[2], lk.position - p) <= 0):
            continue  # this s lands behind a camera
        fd = np.column_stack([(_pipeline(s0 + h * d, G, point[k], normal[k], ek, lk)[0] - _pipeline(s0 - h * d, G, point[k], normal[k], ek, lk)[0]) / (2 * h) for d in np.eye(2)])
        dG_num = np.column_stack([(G(s0 + h * d) - G(s0 - h * d)) / (2 * h) for d in np.eye(2)])
        np.testing.assert_allclose(dG(s0), dG_num, rtol=1e-8)
        got = aliasing_matrix(p, normal[k], ek, lk, delta_l=dG(s0))
        np.testing.assert_allclose(got, fd, rtol=1e-6, atol=1e-9 * np.abs(fd).max())
        checked += 1
    assert checked >= 10


def _in_plane_axes(angle_deg):
    """Axes with x̂ = (1, 0, 0) and the camera looking along −ẑ = −(0, cos a, sin a)."""
    c, s = np.cos(np.radians(angle_deg)), np.sin(np.radians(angle_deg))
    zero, one = np.zeros_like(c), np.ones_like(c)
    return np.stack([np.stack([one, zero, zero], -1), np.stack([zero, s, -c], -1), np.stack([zero, c, s], -1)], -2)


def _in_plane_grid():
    """A grid of in-plane configurations: eye and light directions, surface tilts, points."""
    eye_ang, light_ang, tilt, y = np.meshgrid([40.0, 60.0, 80.0, 110.0], [50.0, 75.0, 95.0, 130.0], [-20.0, 0.0, 25.0], [-1.0, 0.5, 2.0], indexing="ij")
    point = np.stack([np.zeros_like(y), y, np.zeros_like(y)], -1)
    tr = np.radians(tilt)
    normal = np.stack([np.zeros_like(tr), np.sin(tr), np.cos(tr)], -1)
    ea, la = np.radians(eye_ang), np.radians(light_ang)
    e = point + 6.0 * np.stack([np.zeros_like(ea), np.cos(ea), np.sin(ea)], -1)
    l_pos = point + 9.0 * np.stack([np.zeros_like(la), np.cos(la), np.sin(la)], -1)
    eye = Camera(axes=_in_plane_axes(eye_ang + 5.0), position=e, near=0.7, width=[1.3, 1.1])
    light = Camera(axes=_in_plane_axes(light_ang - 8.0), position=l_pos, near=0.9, width=[2.5, 2.0])
    return point, normal, eye, light


def _angles(point, normal, cam):
    """(d, cos φ, cos ψ) of a camera at a point: depth, beam vs image-plane normal, beam vs surface normal."""
    to = cam.position - point
    dist = np.linalg.norm(to, axis=-1)
    return np.einsum("...k,...k", cam.axes[..., 2, :], to), np.einsum("...k,...k", cam.axes[..., 2, :], to) / dist, np.einsum("...k,...k", normal, to) / dist


def test_a_in_plane_grid_numeric_t_j_element_is_eq19():
    point, normal, eye, light = _in_plane_grid()
    dG = 0.8
    Ma = aliasing_matrix(point, normal, eye, light, delta_l=np.diag([1.3, dG]), res_image=[640.0, 480.0], res_map=1024.0)
    assert Ma.shape == point.shape[:-1] + (2, 2)
    np.testing.assert_array_less(np.abs(Ma[..., [0, 1], [1, 0]]), 1e-13 * np.abs(Ma).max())
    d_e, cphi_e, cpsi_e = _angles(point, normal, eye)
    d_l, cphi_l, cpsi_l = _angles(point, normal, light)
    assert (cphi_e > 0).all() and (cpsi_e > 0).all() and (cphi_l > 0).all() and (cpsi_l > 0).all()
    deg = lambda q: np.degrees(np.arccos(q))  # noqa: E731
    m = logpsm.aliasing_error(dG, 2.0, 1.1, 0.7, d_e, deg(cphi_l), deg(cphi_e), deg(cpsi_e), deg(cpsi_l), n_l=0.9, d_l=d_l, res_image=480.0, res_t=1024.0)
    np.testing.assert_allclose(np.abs(Ma[..., 1, 1]), m, rtol=1e-11)


# --- (c) the half-way surface and the metric h ------------------------------------------------------


def test_c_in_plane_halfway_surface_has_projection_factor_one():
    point, _, eye, light = _in_plane_grid()
    nh = halfway_normal(point, eye, light)
    d_e, cphi_e, cpsi_e = _angles(point, nh, eye)
    d_l, cphi_l, cpsi_l = _angles(point, nh, light)
    np.testing.assert_allclose(cpsi_e, cpsi_l, rtol=1e-13)  # §3.3: cos ψ_e = cos ψ_l
    Ma = aliasing_matrix(point, nh, eye, light, delta_l=np.diag([1.0, 0.8]), res_image=480.0, res_map=1024.0)
    deg = lambda q: np.degrees(np.arccos(q))  # noqa: E731
    delta_tilde = logpsm.perspective_factor(2.0, 1.1, 0.7, d_e, deg(cphi_l), deg(cphi_e), n_l=0.9, d_l=d_l)
    np.testing.assert_allclose(np.abs(Ma[..., 1, 1]), 480.0 / 1024.0 * 0.8 / delta_tilde, rtol=1e-11)  # eq. 31: m = m̃
    # in the plane both §3.4 definitions agree direction by direction: |M_kk| = |X_l,kk|/|X_e,kk| ...
    X_l, X_e = cross_sections(point, eye, light, delta_l=np.diag([1.0, 0.8]), res_image=480.0, res_map=1024.0)
    for k in (0, 1):
        np.testing.assert_allclose(np.abs(Ma[..., k, k]), np.abs(X_l[..., k, k] / X_e[..., k, k]), rtol=1e-11)


@pytest.mark.parametrize("directional", [False, True])
def test_c_determinant_is_the_ratio_of_beam_areas_norms_are_not(directional):
    point, normal, eye, light, delta_l = random_configurations(200, directional, seed=3)
    X_l, X_e = cross_sections(point, eye, light, delta_l=delta_l, res_image=[800.0, 600.0], res_map=[512.0, 1024.0])
    area = error_metric(X_l, "det") / error_metric(X_e, "det")
    nh = halfway_normal(point, eye, light)
    Ma_half = aliasing_matrix(point, nh, eye, light, delta_l=delta_l, res_image=[800.0, 600.0], res_map=[512.0, 1024.0])
    np.testing.assert_allclose(error_metric(Ma_half, "det"), area, rtol=1e-10)  # §3.4's two definitions agree for h = |det|
    # any surface: |det M_a| = (area ratio) · cos ψ_e / cos ψ_l, the 3D form of eq. 29's factorisation
    Ma = aliasing_matrix(point, normal, eye, light, delta_l=delta_l, res_image=[800.0, 600.0], res_map=[512.0, 1024.0])
    to_l = light.direction if directional else light.position - point
    cos_psi_l = np.einsum("ki,ki->k", normal, to_l) / np.linalg.norm(normal, axis=-1) / np.linalg.norm(to_l, axis=-1)
    to_e = eye.position - point
    cos_psi_e = np.einsum("ki,ki->k", normal, to_e) / np.linalg.norm(normal, axis=-1) / np.linalg.norm(to_e, axis=-1)
    np.testing.assert_allclose(error_metric(Ma, "det"), area * np.abs(cos_psi_e) / cos_psi_l, rtol=1e-9)
    # why: the half-way surface is the mirror reflecting the light beam into the eye beam, so it carries
    # one cross-section onto the other isometrically, M_a = X_e⁻¹ P X_l with P orthogonal ...
    P = X_e @ Ma_half @ np.linalg.inv(X_l)
    np.testing.assert_allclose(np.swapaxes(P, -1, -2) @ P, np.broadcast_to(np.eye(2), P.shape), atol=1e-11)
    P_any = X_e @ Ma @ np.linalg.inv(X_l)
    assert np.abs(np.swapaxes(P_any, -1, -2) @ P_any - np.eye(2)).max(axis=(-2, -1)).min() > 1e-3  # not for other normals
    # ... but "unlike the 2D case, these two approaches are not guaranteed to be equivalent" for a norm:
    # for h = 2-norm, h(X_l)/h(X_e) ≤ h(M_a) ≤ cond(X_e) h(X_l)/h(X_e), and both ends occur
    sv = np.linalg.svd(X_e, compute_uv=False)
    r2 = error_metric(Ma_half, 2) / (error_metric(X_l, 2) / error_metric(X_e, 2))
    assert (r2 >= 1 - 1e-12).all() and (r2 <= sv[:, 0] / sv[:, 1] * (1 + 1e-12)).all()
    assert r2.min() < 1.01 and r2.max() > 5
    for kind in ("fro", "column"):
        ratio = error_metric(Ma_half, kind) / (error_metric(X_l, kind) / error_metric(X_e, kind))
        assert ratio.max() > 5 and ratio.min() < 1.2, kind


# --- API: shapes, validation, degenerate inputs --------------------------------------------------


def test_shapes_scalar_nd_and_identity_relations():
    point, normal, eye, light, delta_l = random_configurations(40)
    sel = slice(0, 12)
    point, normal, delta_l = point[sel], normal[sel], delta_l[sel]
    eye = Camera(axes=eye.axes[sel], position=eye.position[sel], near=eye.near[sel], width=eye.width[sel])
    light = Camera(axes=light.axes[sel], position=light.position[sel], near=light.near[sel], width=light.width[sel])
    Ma = aliasing_matrix(point.reshape(3, 4, 3), normal.reshape(3, 4, 3), Camera(axes=eye.axes.reshape(3, 4, 3, 3), position=eye.position.reshape(3, 4, 3), near=eye.near.reshape(3, 4),
                         width=eye.width.reshape(3, 4, 2)), Camera(axes=light.axes.reshape(3, 4, 3, 3), position=light.position.reshape(3, 4, 3), near=light.near.reshape(3, 4),
                         width=light.width.reshape(3, 4, 2)), delta_l=delta_l.reshape(3, 4, 2, 2))
    assert Ma.shape == (3, 4, 2, 2)
    flat = aliasing_matrix(point, normal, eye, light, delta_l=delta_l)
    np.testing.assert_allclose(Ma.reshape(12, 2, 2), flat, rtol=1e-15)
    one = aliasing_matrix(point[0], normal[0], Camera(axes=eye.axes[0], position=eye.position[0], near=eye.near[0], width=eye.width[0]),
                          Camera(axes=light.axes[0], position=light.position[0], near=light.near[0], width=light.width[0]), delta_l=delta_l[0])
    assert one.shape == (2, 2) and np.allclose(one, flat[0], rtol=1e-15)
    # eq. 27 in 3D: M_a = δ_e⁻¹ δ_l (unit resolutions); eq. 39: δ_l = (∂F/∂u)⁻¹
    np.testing.assert_allclose(flat, np.linalg.solve(spacing_eye(point, normal, eye, light), delta_l), rtol=1e-10)
    np.testing.assert_allclose(spacing_light(np.linalg.inv(delta_l)), delta_l, rtol=1e-12)


def test_light_exactly_overhead_and_eye_straight_down():
    eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 10.0], near=1.0, width=2.0)
    sun = Camera(axes=np.eye(3), direction=[0.0, 0.0, 1.0], width=20.0)
    xs = np.linspace(-3, 3, 7)
    pts = np.stack([xs, 0 * xs, 0 * xs], -1)
    Ma = aliasing_matrix(pts, [0.0, 0.0, 1.0], eye, sun)
    # image plane parallel to the floor: a pixel covers W_e d_e/n_e = 20 units everywhere, as does a texel
    np.testing.assert_allclose(Ma, np.broadcast_to(np.eye(2), (7, 2, 2)), rtol=1e-14, atol=1e-15)


@pytest.mark.parametrize(
    "call, word",
    [
        (lambda: Camera(axes=np.eye(3)), "exactly one of position"),
        (lambda: Camera(axes=2 * np.eye(3), position=[0, 0, 1]), "orthonormal"),
        (lambda: Camera(axes=np.eye(2), position=[0, 0, 1]), "shape (..., 3, 3)"),
        (lambda: Camera(axes=np.eye(3), position=[0, 0, 1], near=0.0), "near must be in (0, inf)"),
        (lambda: Camera(axes=np.eye(3), direction=[0, 0, 0]), "direction must be a non-zero vector"),
        (lambda: camera_axes([0, 1, 0], [0, 2, 0]), "up must not be parallel to view"),
        (lambda: error_metric(np.eye(2), "max"), "unknown metric 'max'"),
        (lambda: error_metric(np.eye(3), "2"), "shape (..., 2, 2)"),
        (lambda: spacing_light(np.zeros((2, 2))), "dF_du must be invertible"),
    ],
)
def test_validation(call, word):
    with pytest.raises(ValueError) as err:
        call()
    assert word in str(err.value)


def test_degenerate_configurations_are_rejected():
    eye = Camera(axes=np.eye(3), position=[0.0, 0.0, 10.0])
    lamp_in_plane = Camera(axes=camera_axes([-1.0, 0.0, 0.0]), position=[5.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="must not lie in the surface plane"):
        aliasing_matrix([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], eye, lamp_in_plane)  # light in the surface's plane
    grazing = Camera(axes=camera_axes([-1.0, 0.0, 0.0]), direction=[1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="must not be parallel to the surface"):
        aliasing_matrix([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], eye, grazing)
    with pytest.raises(ValueError, match="in front of the eye"):
        aliasing_matrix([0.0, 0.0, 20.0], [0.0, 0.0, 1.0], eye, grazing)
    with pytest.raises(ValueError, match="in front of the light"):
        aliasing_matrix([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], eye, Camera(axes=np.eye(3), position=[0.0, 0.0, -5.0]))
    with pytest.raises(ValueError, match="must have a position"):
        aliasing_matrix([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], Camera(axes=np.eye(3), direction=[0, 0, 1]), eye)
