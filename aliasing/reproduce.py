"""Registry of reproduced figures and tables: target name → script under figures/.

Example
-------
>>> from aliasing.reproduce import TARGETS
>>> "lloyd2006-fig5" in TARGETS
True
"""

from __future__ import annotations

import importlib
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path


@dataclass(frozen=True)
class Target:
    """A reproducible figure or table."""

    name: str
    module: str
    description: str


TARGETS: dict[str, Target] = {
    t.name: t
    for t in (
        Target("lloyd2006-fig5", "lloyd2006_fig5", "Lloyd 2006 Fig. 5: m_x, m_z along z for several n' (n=1, f=20)"),
        Target("lloyd2006-fig6", "lloyd2006_fig6", "Lloyd 2006 Fig. 6: M_x, M_z, S over eta (n=1, f=100)"),
        Target("wimmer2004-fig6", "wimmer2004_fig6", "Wimmer 2004 Fig. 6: dp/ds over z, uniform/PSM/LiSPSM (z_n=1, z_f=100)"),
    )
}


def resolve(names: Iterable[str]) -> list[Target]:
    """Targets for ``names`` (``all`` expands to every target); ``ValueError`` lists valid names."""
    names = list(names) or ["all"]
    chosen: list[Target] = []
    for name in names:
        if name == "all":
            chosen.extend(TARGETS.values())
        elif name in TARGETS:
            chosen.append(TARGETS[name])
        else:
            raise ValueError(f"unknown reproduce target {name!r}; valid targets: all, {', '.join(TARGETS)}")
    return list(dict.fromkeys(chosen))


def reproduce(names: Iterable[str], out_dir: str | Path) -> list[Path]:
    """Run the figure scripts for ``names`` and return the files written into ``out_dir``."""
    targets = resolve(names)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ValueError(f"out must be a folder, but {str(out)!r} is a file")
    written: list[Path] = []
    for target in targets:
        module = importlib.import_module(f"aliasing.figures.{target.module}")
        written.extend(module.main(out))
    return written
