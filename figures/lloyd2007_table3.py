"""Lloyd et al. 2007, Table 3: storage factor S̄ over all light directions, all 16 rows.

f/n = 1000, θ = 30° (fov 60°), a directional light, the 1/cos²θ factor not included (as
the table's caption says).  Rows Standard, P, Po, Log, FP+P, FPc+P, FPcs+P, ZP5, ZP5+P,
ZP5+Log, ZP7, ZP7+P, ZP7+Log, FP+Log, FPc+Log, FPcs+Log (face partitions:
:mod:`aliasing.faces`, FPcs with our τ0 = 120°, τ1 = 150°).  Directions: the overhead
light (where every row's minimum lies) plus 20,000 equal-solid-angle directions on the
hemisphere above the viewer (the paper does not state its sampling; by the symmetries of
the square frustum and of l ↔ −l the hemisphere gives the sphere's statistics).

Output: ``lloyd2007-table3.csv`` and ``.md``, each cell beside the printed value with the
relative difference.  What the comparison shows (docs/ERRATA.md):

* minima agree at the printed precision everywhere;
* maxima agree within the sampling (Standard's supremum 2(f/n)² = 2.00e6 is approached
  only as γ → 0 along the frustum diagonal);
* the printed P and Po rows are swapped (L5): our P (eq. 79 shaping) is the printed Po row
  and our Po (1/sin γ) the printed P row, as the paper's own text requires;
* the printed ZP5+P max/min and mean repeat the ZP5+Log row (L6);
* means differ by 1–2 % (sampling not stated), more for P and Po;
* FP: minima and maxima agree at the printed precision (the maximum is the closed form
  2(f/n − 1) + 1, resp. 2 ln(f/n) + 1, at γ = 0); the means are 6–7 % lower (L17);
* FPc, FPcs: means within 1.5 % and FPcs's 3.8 maps agree; the printed maxima are sample
  maxima of an unbounded S (L18): ours depend on the sampling the same way;
* FP's mean map count is 1 + 4(90° + θ)/180° = 3.67 exactly, printed 3.6 (L17).

"Rel. mean" is the mean relative to FP+Log's, as in the paper.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import geometry, schemes

NAME = "lloyd2007-table3"
F_OVER_N, FOV, DIRECTIONS = 1000.0, 60.0, 20_000
ROWS = ("Standard", "P", "Po", "Log", "FP+P", "FPc+P", "FPcs+P", "ZP5", "ZP5+P", "ZP5+Log", "ZP7", "ZP7+P", "ZP7+Log", "FP+Log", "FPc+Log", "FPcs+Log")
COLUMNS = ("S_min", "S_max", "S_max_over_min", "S_mean", "rel_mean", "maps")
# Lloyd et al. 2007, Table 3, as printed: min S, max S, max/min, mean, rel. mean, mean # SMs
PRINTED = {
    "Standard": (8.65e5, 2.00e6, 2.31, 1.32e6, 1.21e5, 1),
    "P": (865, 3.65e6, 4.22e3, 2.53e5, 2.32e4, 1),
    "Po": (865, 1.99e6, 2.30e3, 1.80e5, 1.64e4, 1),
    "Log": (5.98, 1.99e6, 3.33e5, 1.88e5, 1.71e4, 1),
    "FP+P": (865, 2000, 2.31, 1490, 136, 3.6),
    "FPc+P": (865, 3170, 3.66, 1860, 170, 3.6),
    "FPcs+P": (865, 3630, 4.19, 1900, 174, 3.8),
    "ZP5": (51.4, 158, 3.07, 94.1, 8.60, 5),
    "ZP5+P": (12.9, 159, 26.4, 46.7, 4.93, 5),
    "ZP5+Log": (5.98, 158, 26.4, 46.7, 4.26, 5),
    "ZP7": (27.4, 100, 3.67, 56.6, 5.17, 7),
    "ZP7+P": (10.2, 100, 9.84, 42.1, 3.85, 7),
    "ZP7+Log": (5.98, 100, 16.8, 38.5, 3.51, 7),
    "FP+Log": (5.98, 14.8, 2.47, 10.9, 1, 3.6),
    "FPc+Log": (5.98, 26.3, 4.4, 14, 1.28, 3.6),
    "FPcs+Log": (5.98, 31.7, 5.3, 14.3, 1.31, 3.8),
}
NOTES = {
    "P": "printed P and Po rows are swapped (ERRATA L5): compare with the printed Po row",
    "Po": "printed P and Po rows are swapped (ERRATA L5): compare with the printed P row",
    "ZP5+P": "printed max/min and mean repeat the ZP5+Log row (ERRATA L6)",
    "FP+P": "mean 6 % low, map count 3.67 exactly (ERRATA L17)",
    "FP+Log": "mean 7 % low, map count 3.67 exactly (ERRATA L17)",
    "FPc+P": "max is a sample maximum: S is unbounded (ERRATA L18)",
    "FPcs+P": "max is a sample maximum: S is unbounded (ERRATA L18); tau0, tau1 ours",
    "FPc+Log": "max is a sample maximum: S is unbounded (ERRATA L18)",
    "FPcs+Log": "max is a sample maximum: S is unbounded (ERRATA L18); tau0, tau1 ours",
}


def lights(directions: int = DIRECTIONS) -> np.ndarray:
    return np.vstack([geometry.lights("overhead"), geometry.hemisphere_directions(directions)])


def data(directions: int = DIRECTIONS) -> dict[str, dict[str, float]]:
    """Our statistics per row: S_min, S_max, S_max_over_min, S_mean, rel_mean, maps."""
    lv = lights(directions)
    out = {}
    for name, r in zip(ROWS, schemes.evaluate_many(ROWS, 1.0, F_OVER_N, FOV, lv)):
        s = r.S
        out[name] = {"S_min": s.min(), "S_max": s.max(), "S_max_over_min": s.max() / s.min(), "S_mean": s.mean(), "maps": float(r.maps_used.mean())}
    for row in out.values():
        row["rel_mean"] = row["S_mean"] / out["FP+Log"]["S_mean"]
    return out


def main(out_dir: Path, directions: int = DIRECTIONS) -> list[Path]:
    ours = data(directions)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    csv_lines = ["row," + ",".join(f"{c},{c}_printed,{c}_rel_diff" for c in COLUMNS) + ",note"]
    md = [
        f"# Lloyd et al. 2007, Table 3: ours vs printed\n\nf/n = {F_OVER_N:g}, θ = {FOV / 2:g}°, overhead + {directions} hemisphere directions. Cells: ours / printed (relative difference).\n",
        "| row | " + " | ".join(COLUMNS) + " | note |",
        "|---" * (len(COLUMNS) + 2) + "|",
    ]
    for name in ROWS:
        cells_csv, cells_md = [], []
        for col, printed in zip(COLUMNS, PRINTED[name]):
            value = ours[name][col]
            rel = (value - printed) / printed
            cells_csv.append(f"{value:.6g},{printed:g},{rel:+.4f}")
            cells_md.append(f"{value:.4g} / {printed:g} ({rel:+.1%})")
        note = NOTES.get(name, "")
        csv_lines.append(f"{name}," + ",".join(cells_csv) + f",{note}")
        md.append(f"| {name} | " + " | ".join(cells_md) + f" | {note} |")
    csv_path, md_path = out / f"{NAME}.csv", out / f"{NAME}.md"
    csv_path.write_text("\n".join(csv_lines) + "\n")
    md_path.write_text("\n".join(md) + "\n")
    return [csv_path, md_path]


if __name__ == "__main__":
    from aliasing.figures import run_standalone

    run_standalone(main, __doc__)
