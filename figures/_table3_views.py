"""Views of the Lloyd 2007 Table 3 comparison (:mod:`lloyd2007_table3`): a PNG and an HTML table.

Both show, per cell, our value, the printed value it is compared with and the relative
difference, coloured by the cell's status: agrees at the printed precision, differs but is
explained by an erratum (docs/ERRATA.md), or differs unexplained.  The HTML table is read
from the CSV that ``lloyd2007_table3.main`` writes (the docs' gallery page shows it).
"""

from __future__ import annotations

import csv
import html
from pathlib import Path

COLUMNS = ("S_min", "S_max", "S_max_over_min", "S_mean", "rel_mean", "maps")
HEADERS = ("min S̄", "max S̄", "max/min", "mean S̄", "rel. mean", "mean # maps")  # the paper's column heads
STATUS = {  # kind → (colour, what it means)
    "agrees": ("#b8e0b0", "agrees with the printed value at its precision"),
    "explained": ("#fde3a7", "differs; explained by the erratum named in the cell (docs/ERRATA.md)"),
    "unexplained": ("#f5b3b3", "differs; unexplained (no hypothesis of ERRATA L20 fits)"),
}


def kind(status: str) -> str:
    """"agrees", "explained" or "unexplained" for a cell's status text."""
    if status == "agrees":
        return "agrees"
    return "unexplained" if status.startswith("UNEXPLAINED") else "explained"


def erratum(status: str) -> str:
    """The erratum a status names ("L6", "L17/L20"), or ""."""
    return status.split(":")[0].split(" ")[-1].strip("()") if kind(status) == "explained" else ""


def _second_line(printed: float, rel: float, status: str) -> str:
    tag = erratum(status)
    return f"printed {printed:.3g}, {rel:+.1%}" + (f" · {tag}" if tag else "")


def figure(rows: list[str], cells: dict, notes: dict[str, str], title: str):
    """The comparison as a coloured table (matplotlib Figure): ``cells[(row, col)] = (ours, printed, status)``."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from aliasing.plotting import STYLE

    order = list(STATUS)
    grid = [[order.index(kind(cells[(r, c)][2])) for c in COLUMNS] for r in rows]
    with plt.rc_context({**STYLE, "axes.grid": False}):
        fig, ax = plt.subplots(figsize=(12.5, 0.5 * len(rows) + 2.0))
    ax.imshow(grid, cmap=ListedColormap([STATUS[k][0] for k in order]), vmin=-0.5, vmax=len(order) - 0.5, aspect="auto")
    for i, r in enumerate(rows):
        for j, c in enumerate(COLUMNS):
            ours, printed, status = cells[(r, c)]
            rel = (ours - printed) / printed
            ax.text(j, i - 0.16, f"{ours:.4g}", ha="center", va="center", fontsize=9, fontweight="bold")
            ax.text(j, i + 0.2, _second_line(printed, rel, status), ha="center", va="center", fontsize=7)
    ax.set_xticks(range(len(COLUMNS)), HEADERS, fontsize=9)
    ax.xaxis.tick_top()
    ax.set_yticks(range(len(rows)), [f"{r}\n({notes[r]})" if r in notes else r for r in rows], fontsize=8.5)
    ax.set_xticks([j + 0.5 for j in range(len(COLUMNS) - 1)], minor=True)
    ax.set_yticks([i + 0.5 for i in range(len(rows) - 1)], minor=True)
    ax.grid(which="minor", color="w", lw=2)
    ax.tick_params(which="both", length=0)
    for side in ax.spines.values():
        side.set_visible(False)
    ax.legend(handles=[Patch(color=STATUS[k][0], label=STATUS[k][1]) for k in order], loc="upper center",
              bbox_to_anchor=(0.5, -0.01), ncol=3, fontsize=8, frameon=False, handlelength=1.5)
    ax.set_title(title, fontsize=10, pad=28)
    return fig


def html_table(csv_path: str | Path, notes: dict[str, str] | None = None) -> str:
    """The comparison as an HTML table, read from the CSV that ``lloyd2007_table3.main`` wrote."""
    notes = notes or {}
    with open(csv_path, newline="") as fh:
        records = list(csv.DictReader(fh))
    css = "border:1px solid #fff;padding:3px 6px;text-align:center;font-size:0.85em;line-height:1.25"
    head = "".join(f'<th style="{css}">{html.escape(h)}</th>' for h in ("row", *HEADERS))
    body = []
    for rec in records:
        row = rec["row"]
        label = html.escape(row) + (f'<br><small>{html.escape(notes[row])}</small>' if row in notes else "")
        tds = [f'<th style="{css};text-align:left">{label}</th>']
        for c in COLUMNS:
            status = rec[f"{c}_status"]
            ours, printed, rel = float(rec[c]), float(rec[f"{c}_printed"]), float(rec[f"{c}_rel_diff"])
            tip = html.escape(status, quote=True)
            tds.append(f'<td style="{css};background:{STATUS[kind(status)][0]};color:#000" title="{tip}"><b>{ours:.4g}</b><br>'
                       f"<small>{html.escape(_second_line(printed, rel, status))}</small></td>")
        body.append("<tr>" + "".join(tds) + "</tr>")
    legend = " ".join(f'<span style="background:{colour};color:#000;padding:1px 6px;margin-right:6px">{html.escape(text)}</span>'
                      for colour, text in STATUS.values())
    return (f'<div style="overflow-x:auto"><table style="border-collapse:collapse;margin:0.5em 0">'
            f"<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table></div><p>{legend}</p>")


class HTMLTable:
    """An object whose rich display (Jupyter, sphinx-gallery) is :func:`html_table`."""

    def __init__(self, csv_path: str | Path, notes: dict[str, str] | None = None) -> None:
        self.text = html_table(csv_path, notes)

    def _repr_html_(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return "Lloyd 2007 Table 3 comparison (HTML; see the CSV for the numbers)"
