"""Plot helpers: one style, deterministic files.

Every helper returns ``(fig, ax)`` or writes files; nothing is shown interactively.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # figures are written to files; no display is assumed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

STYLE = {
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 10,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "legend.frameon": False,
    "svg.hashsalt": "aliasing",
}


def subplots(ncols: int = 1, *, nrows: int = 1, width: float = 5.0, height: float = 3.6, **kwargs):
    """A figure with ``nrows`` × ``ncols`` axes in the package style; returns (fig, axes).

    ``axes`` is one Axes for 1 × 1, a 1-D array for a single row, else a 2-D array;
    ``width`` and ``height`` are per panel [inches].
    """
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows), squeeze=False, **kwargs)
    for ax in axes.flat:
        ax.grid(True, alpha=STYLE["grid.alpha"])
    if nrows == 1:
        return fig, (axes[0, 0] if ncols == 1 else axes[0])
    return fig, axes


def save(fig, out_dir: str | Path, name: str, columns: Mapping[str, Sequence[float]] | None = None) -> list[Path]:
    """Write ``name.png`` (no timestamp metadata, so reruns are byte-identical) and,
    when ``columns`` are given, ``name.csv`` with the plotted numbers; returns the paths."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    png = out / f"{name}.png"
    with plt.rc_context(STYLE):
        fig.tight_layout()
        fig.savefig(png, metadata={"Software": None})
    plt.close(fig)
    paths = [png]
    if columns:
        csv = out / f"{name}.csv"
        names = list(columns)
        table = np.column_stack([np.asarray(columns[k], dtype=float) for k in names])
        np.savetxt(csv, table, delimiter=",", header=",".join(names), comments="", fmt="%.10g")
        paths.append(csv)
    return paths


def write_table(columns: Mapping[str, Sequence[object]], path: str | Path, digits: int = 10) -> Path:
    """Write columns of mixed text and numbers as CSV (floats as ``%.<digits>g``); returns the path.

    Example
    -------
    >>> import tempfile
    >>> p = write_table({"preset": ["a", "b"], "S": [1.0, 2.5]}, Path(tempfile.mkdtemp()) / "t.csv")
    >>> p.read_text().splitlines()
    ['preset,S', 'a,1', 'b,2.5']
    """
    import csv

    path = Path(path)
    with path.open("w", newline="") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(list(columns))
        for row in zip(*columns.values()):
            writer.writerow([f"{v:.{digits}g}" if isinstance(v, float) else v for v in row])
    return path
