"""Speed targets of the analytic core: the toolkit against a plain implementation, timed side by side.

The baseline is an independent, straightforward numpy implementation of the vertex-based S̄
(Lloyd et al. 2006 §4.4; Lloyd et al. 2007 §6.1.1, App. B): **per scheme, per map**, rotate
the map's 8 frustum vertices into every direction's light frame (Wimmer et al. 2004 §3.4),
fit the map (uniform, perspective with the η rule, or log+perspective), take the maxima of
m_x and m_z over the vertices.  Warping: "P" and "LogP" use Lloyd 2007's η shaping (eq. 79,
γ_a = θ/3 resp. θ/2, η_b = −0.2, η_c = 0 resp. 1, γ_c = θ + 0.4(90° − θ)) and eq. 120's n′(η)
with n_γ = W_ly/(f/n − 1); "Po" is n_γ(1 + √(f/n))/sin γ.  It shares no code with the toolkit
(the directions come from ``aliasing.geometry.hemisphere_directions``, outside the timing),
and the script checks that both agree to 1e-12 (relative) on every direction before timing.

Timed (interleaved in one process, median of ``--repeats``):

* ``toolkit``: ``schemes.evaluate_many`` of Table 3's ten non-FP rows;
* ``baseline``: the same ten rows with the plain code below;
* ``floor``: the vertex transform plus min/max per map only (no fit, no errors);
* ``single``: one single-map scheme (``P``) through ``schemes.evaluate``;
* the face partitions FP+P, FPc+P, FPcs+P and FP+LogP, per direction beside a single map.

    python benchmarks/baseline.py                 # 20,000 directions, median of 5
    python benchmarks/baseline.py --counts 2000 20000 200000 --repeats 3
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

from aliasing import geometry, schemes

ROWS = ("Standard", "P", "Po", "LogP", "ZP5", "ZP5+P", "ZP5+LogP", "ZP7", "ZP7+P", "ZP7+LogP")
FACE_ROWS = ("FP+P", "FPc+P", "FPcs+P", "FP+LogP")
NEAR, FAR, FOV = 1.0, 1000.0, 60.0
SIGNS = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], float)


# --- the plain implementation ------------------------------------------------------------------


def plain_basis(light: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """x_L and z_L ``(N, 3)`` of Wimmer 2004 §3.4's light space (z_L = eye up if l ∥ v)."""
    y = light / np.linalg.norm(light, axis=1, keepdims=True)
    view, up = np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
    z = np.cross(np.cross(y, view), y)
    bad = np.linalg.norm(z, axis=1) < 1e-300
    z[bad] = np.cross(np.cross(y[bad], up), y[bad])
    z /= np.linalg.norm(z, axis=1, keepdims=True)
    return np.cross(y, z), z


def plain_vertices(n: float, f: float, fov: float) -> np.ndarray:
    t = np.tan(np.radians(fov) / 2)
    d = np.array([n] * 4 + [f] * 4)
    s = np.vstack([SIGNS, SIGNS])
    return np.column_stack([s[:, 0] * d * t, s[:, 1] * d * t, d])  # (8, 3)


def plain_eta(gamma: np.ndarray, fov: float, a: float, eta_c: float) -> np.ndarray:
    """Lloyd 2007 eq. 79 with γ folded to [0°, 90°] (ERRATA L1–L3)."""
    g = np.minimum(gamma, 180 - gamma)
    th = fov / 2
    ga, gb, gc, eb = a * th, th, th + 0.4 * (90 - th), -0.2
    return np.select([g <= ga, g <= gb, g <= gc], [-1.0, -1 + (eb + 1) * (g - ga) / (gb - ga), eb + (eta_c - eb) * np.sin(np.pi / 2 * (g - gb) / (gc - gb))], eta_c)


def plain_n_prime(eta: np.ndarray, n: float, f: float, depth: np.ndarray) -> np.ndarray:
    """Lloyd 2006 eq. 11 / Lloyd 2007 eq. 120 with n_γ = W_ly/(f/n − 1)."""
    a = f / n
    ng, ra = depth / (a - 1), np.sqrt(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        lower = ng * (ra + 1 - eta * (a - 1)) / (eta + 1)
        upper = ng * (ra + 1) / (eta * ra + 1)
    return np.where(eta <= 0, np.where(eta == -1, np.inf, lower), upper)


def plain_map(x: np.ndarray, y: np.ndarray, d: np.ndarray, rule: str, gamma: np.ndarray, n: float, f: float, fov: float) -> tuple[np.ndarray, np.ndarray]:
    """M_x, M_z ``(N,)`` of one map fitted to vertices x, y ``(N, 8)`` at eye depths d ``(8,)``."""
    y = y - y.min(axis=1, keepdims=True)
    D = y.max(axis=1)
    w_i = 2 * np.tan(np.radians(fov) / 2) * d
    if rule == "Standard":
        W = x.max(axis=1) - x.min(axis=1)
        return (W[:, None] / w_i).max(axis=1), (D[:, None] / w_i).max(axis=1)
    if rule == "Po":
        s = np.sin(np.radians(gamma))
        npr = np.where(s > 1e-12, D / (f / n - 1) * (1 + np.sqrt(f / n)) / np.where(s > 1e-12, s, 1), np.inf)
    else:
        npr = plain_n_prime(plain_eta(gamma, fov, 1 / 3 if rule == "P" else 1 / 2, 0.0 if rule == "P" else 1.0), n, f, D)
    npr = npr[:, None]
    zp = 1 + y / npr  # z′/n′; exactly 1 for n′ = ∞
    q = x / zp
    W = q.max(axis=1) - q.min(axis=1)
    inf = np.isinf(npr)
    if rule == "LogP":
        with np.errstate(invalid="ignore"):
            along = zp * np.where(inf, D[:, None], npr * np.log1p(D[:, None] / npr))
    else:
        with np.errstate(invalid="ignore"):
            along = zp * np.where(inf, 1.0, (npr + y) / (npr + D[:, None])) * D[:, None]
    return (zp * W[:, None] / w_i).max(axis=1), (along / w_i).max(axis=1)


def plain_scheme(name: str, light: np.ndarray) -> np.ndarray:
    """S̄ ``(N,)`` of a Table 3 row: per scheme, per map, rotate → fit → max."""
    k, rule = (int(name[2]), name.partition("+")[2] or "Standard") if name.startswith("ZP") else (1, name)
    bx, bz = plain_basis(light)
    l = light / np.linalg.norm(light, axis=1, keepdims=True)
    gamma = np.degrees(np.arccos(np.clip(np.abs(l[:, 2]), 0, 1)))
    edges = NEAR * (FAR / NEAR) ** (np.arange(k + 1) / k)
    edges[-1] = FAR
    S = np.zeros(len(light))
    for n, f in zip(edges[:-1], edges[1:]):
        v = plain_vertices(n, f, FOV)
        mx, mz = plain_map(bx @ v.T, bz @ v.T, v[:, 2], rule, gamma, n, f, FOV)
        S += mx * mz
    return S


def floor_kernel(light: np.ndarray) -> float:
    """The floor: per map of the ten rows, the vertex transform and min/max only.

    Written for speed, not plainness: one basis, vertex-major ``(8, N)`` products (a BLAS
    matmul) and reductions over the leading axis (contiguous slabs).
    """
    bx, bz = plain_basis(light)
    basis = np.vstack([bx.T, bz.T]).reshape(2, 3, -1)  # (2, 3, N)
    acc = 0.0
    for name in ROWS:
        k = int(name[2]) if name.startswith("ZP") else 1
        edges = NEAR * (FAR / NEAR) ** (np.arange(k + 1) / k)
        for n, f in zip(edges[:-1], edges[1:]):
            v = plain_vertices(n, f, FOV)
            x, y = v @ basis[0], v @ basis[1]  # (8, N)
            acc += float(x.min(axis=0)[0] + x.max(axis=0)[0] + y.min(axis=0)[0] + y.max(axis=0)[0])
    return acc


# --- timing --------------------------------------------------------------------------------------


def toolkit(light: np.ndarray) -> list[np.ndarray]:
    return [r.S for r in schemes.evaluate_many(ROWS, NEAR, FAR, FOV, light)]


def baseline(light: np.ndarray) -> list[np.ndarray]:
    return [plain_scheme(name, light) for name in ROWS]


def check_agreement(light: np.ndarray) -> float:
    """Largest relative difference of S̄ between toolkit and baseline; must be ≤ 1e-12."""
    worst = 0.0
    for name, a, b in zip(ROWS, toolkit(light), baseline(light)):
        rel = float(np.max(np.abs(a - b) / np.abs(b)))
        if not rel <= 1e-12:
            raise SystemExit(f"{name}: toolkit and baseline differ by {rel:.3g} (relative) > 1e-12")
        worst = max(worst, rel)
    return worst


def interleaved(funcs: dict[str, object], repeats: int) -> dict[str, float]:
    """Median wall time [s] of each function, the runs interleaved (one of each per round)."""
    times: dict[str, list[float]] = {k: [] for k in funcs}
    for _ in range(repeats):
        for k, fn in funcs.items():
            t0 = time.perf_counter()
            fn()  # type: ignore[operator]
            times[k].append(time.perf_counter() - t0)
    return {k: float(np.median(v)) for k, v in times.items()}


def scaling(repeats: int, count: int = 20_000) -> None:
    """How the toolkit's cost grows with partitions k and with schemes sharing one frame."""
    light = geometry.hemisphere_directions(count)
    ks = (1, 2, 5, 10, 20, 50)
    t = interleaved({k: lambda k=k: schemes.evaluate(f"ZP{k}+P", NEAR, FAR, FOV, light) for k in ks}, repeats)
    print(f"\nZPk+P over {count:,} directions (median of {repeats}):\n")
    print("| k | time [ms] | µs per map and direction |")
    print("|---:|---:|---:|")
    for k in ks:
        print(f"| {k} | {1e3 * t[k]:.1f} | {1e6 * t[k] / (k * count):.3f} |")
    sets = {1: ROWS[1:2], 3: ROWS[1:4], 6: ROWS[1:4] + ROWS[5:7] + ROWS[8:9], 10: ROWS}
    t = interleaved({n: lambda names=names: schemes.evaluate_many(names, NEAR, FAR, FOV, light) for n, names in sets.items()}, repeats)
    print(f"\nevaluate_many over {count:,} directions (median of {repeats}):\n")
    print("| schemes | maps | time [ms] |")
    print("|---|---:|---:|")
    for n, names in sets.items():
        maps = sum(int(r[2]) if r.startswith("ZP") else 1 for r in names)
        print(f"| {', '.join(names)} | {maps} | {1e3 * t[n]:.1f} |")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--counts", type=int, nargs="+", default=[20_000])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--scaling", action="store_true", help="also time ZPk+P over k and evaluate_many over the number of schemes")
    args = parser.parse_args(argv)
    print(f"load before: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f} (1/5/15 min); numpy {np.__version__}")
    for count in args.counts:
        light = geometry.hemisphere_directions(count)
        worst = check_agreement(light)
        funcs = {
            "toolkit (10 rows, evaluate_many)": lambda: toolkit(light),
            "toolkit (10 rows, one evaluate each)": lambda: [schemes.evaluate(r, NEAR, FAR, FOV, light).S for r in ROWS],
            "baseline (10 rows)": lambda: baseline(light),
            "floor (transform + min/max, 40 maps)": lambda: floor_kernel(light),
            "single map: evaluate('P')": lambda: schemes.evaluate("P", NEAR, FAR, FOV, light),
            "single map: evaluate('Standard')": lambda: schemes.evaluate("Standard", NEAR, FAR, FOV, light),
        }
        for name in FACE_ROWS:
            funcs[f"faces: evaluate('{name}')"] = lambda name=name: schemes.evaluate(name, NEAR, FAR, FOV, light)
        t = interleaved(funcs, args.repeats)
        tk, base, floor = t["toolkit (10 rows, evaluate_many)"], t["baseline (10 rows)"], t["floor (transform + min/max, 40 maps)"]
        print(f"\n{count:,} hemisphere directions, f/n = {FAR / NEAR:g}, fov {FOV:g}°; median of {args.repeats}, interleaved; agreement {worst:.2g} (max relative)\n")
        print("| what | time [ms] | µs per direction |")
        print("|---|---:|---:|")
        for k, v in t.items():
            print(f"| {k} | {1e3 * v:.1f} | {1e6 * v / count:.2f} |")
        print(f"\ntoolkit / baseline = {tk / base:.3f} (target <= 0.25: {'met' if tk / base <= 0.25 else 'MISSED'})")
        print(f"toolkit / floor = {tk / floor:.2f}")
        single = t["single map: evaluate('P')"]
        print(f"single map P: {1e3 * single:.1f} ms (target <= 20 ms: {'met' if single <= 0.020 else 'MISSED'})")
    if args.scaling:
        scaling(args.repeats)
    print(f"load after: {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} {os.getloadavg()[2]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
