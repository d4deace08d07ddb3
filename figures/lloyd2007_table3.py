"""Lloyd et al. 2007, Table 3: storage factor S̄ over all light directions (non-FP rows).

f/n = 1000, θ = 30° (fov 60°), a directional light, the 1/cos²θ factor not included (as
the table's caption says).  Rows Standard, P, Po, Log, ZP5, ZP5+P, ZP5+Log, ZP7, ZP7+P,
ZP7+Log; the FP rows come with the face-partitioning issue.  Directions: the overhead
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
* means differ by 1–2 % (sampling not stated), more for P and Po.

The "Rel. mean" column (relative to FP+LogP) is left out until FP+LogP exists.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from aliasing import geometry, schemes

NAME = "lloyd2007-table3"
F_OVER_N, FOV, DIRECTIONS = 1000.0, 60.0, 20_000
ROWS = ("Standard", "P", "Po", "Log", "ZP5", "ZP5+P", "ZP5+Log", "ZP7", "ZP7+P", "ZP7+Log")
COLUMNS = ("S_min", "S_max", "S_max_over_min", "S_mean", "maps")
# Lloyd et al. 2007, Table 3, as printed: min S, max S, max/min, mean, mean # SMs
PRINTED = {
    "Standard": (8.65e5, 2.00e6, 2.31, 1.32e6, 1),
    "P": (865, 3.65e6, 4.22e3, 2.53e5, 1),
    "Po": (865, 1.99e6, 2.30e3, 1.80e5, 1),
    "Log": (5.98, 1.99e6, 3.33e5, 1.88e5, 1),
    "ZP5": (51.4, 158, 3.07, 94.1, 5),
    "ZP5+P": (12.9, 159, 26.4, 46.7, 5),
    "ZP5+Log": (5.98, 158, 26.4, 46.7, 5),
    "ZP7": (27.4, 100, 3.67, 56.6, 7),
    "ZP7+P": (10.2, 100, 9.84, 42.1, 7),
    "ZP7+Log": (5.98, 100, 16.8, 38.5, 7),
}
NOTES = {
    "P": "printed P and Po rows are swapped (ERRATA L5): compare with the printed Po row",
    "Po": "printed P and Po rows are swapped (ERRATA L5): compare with the printed P row",
    "ZP5+P": "printed max/min and mean repeat the ZP5+Log row (ERRATA L6)",
}


def lights(directions: int = DIRECTIONS) -> np.ndarray:
    return np.vstack([geometry.lights("overhead"), geometry.hemisphere_directions(directions)])


def data(directions: int = DIRECTIONS) -> dict[str, dict[str, float]]:
    """Our statistics per row: S_min, S_max, S_max_over_min, S_mean, maps."""
    lv = lights(directions)
    out = {}
    for name in ROWS:
        s = schemes.evaluate(name, 1.0, F_OVER_N, FOV, lv).S
        out[name] = {"S_min": s.min(), "S_max": s.max(), "S_max_over_min": s.max() / s.min(), "S_mean": s.mean(), "maps": float(schemes.parse(name).k)}
    return out


def main(out_dir: Path, directions: int = DIRECTIONS) -> list[Path]:
    ours = data(directions)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    csv_lines = ["row," + ",".join(f"{c},{c}_printed,{c}_rel_diff" for c in COLUMNS) + ",note"]
    md = [
        f"# Lloyd et al. 2007, Table 3 (non-FP rows): ours vs printed\n\nf/n = {F_OVER_N:g}, θ = {FOV / 2:g}°, overhead + {directions} hemisphere directions. Cells: ours / printed (relative difference).\n",
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
