"""Repository-wide pytest hooks: doctests of optional-dependency modules skip without them."""

from __future__ import annotations

import importlib.util

import pytest

#: module file (relative to the repository) -> (optional module it needs, the extra that brings it)
OPTIONAL_DOCTESTS = {"aliasing/raster/validate/raycast.py": ("embreex", "bench")}


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    for path, (module, extra) in OPTIONAL_DOCTESTS.items():
        if importlib.util.find_spec(module) is not None:
            continue
        skip = pytest.mark.skip(reason=f"{module} is not installed (optional extra: pip install 'aliasing[{extra}]')")
        for item in items:
            if item.nodeid.startswith(path + "::"):
                item.add_marker(skip)

# aliasing/explore/ imports ipywidgets (the explore extra) at import time: without it, its
# modules' doctests are not collected (tests/test_explore.py skips itself).
collect_ignore_glob = [] if importlib.util.find_spec("ipywidgets") is not None else ["aliasing/explore/_*.py", "aliasing/explore/widget.py"]
