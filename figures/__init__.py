"""Figure scripts, one per reproduced figure; installed as :mod:`aliasing.figures`.

Each module has ``main(out_dir) -> list[Path]`` and runs standalone:
``python figures/lloyd2006_fig5.py --out DIR``.  :mod:`aliasing.reproduce` registers them.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path


def run_standalone(main: Callable[[Path], list[Path]], doc: str | None) -> None:
    """Command-line entry for a figure script: ``--out DIR`` (default ``out``)."""
    parser = argparse.ArgumentParser(description=(doc or "").strip().splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    for path in main(parser.parse_args().out):
        print(path)
