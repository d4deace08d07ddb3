"""Light depth maps kept while a search redraws the same maps: :func:`remember`.

A search that changes only the biases, the filter or the blend band draws the same triangles
through the same light matrices at the same size again and gets the same map.  Within
:func:`remember`'s block :func:`aliasing.frames.lightmaps.depth.light_depth_map` and
:func:`~aliasing.frames.lightmaps.depth.sampled_depth_map` keep the maps they drew (by a digest of the
mapped triangles and the size), and :func:`~aliasing.frames.predict.reference` the exact
reference it found (by a digest of the matrices, cascades, pixels, sun and scene); the least
recently used are dropped beyond the block's byte limit; outside it nothing is kept.

Examples
--------
>>> import numpy as np
>>> from aliasing.frames.lightmaps.depth import light_depth_map
>>> tri = np.array([[[0.1, 0.1, 0.5], [0.9, 0.1, 0.5], [0.1, 0.9, 0.5]]])
>>> with remember():
...     light_depth_map(tri, np.eye(4), 8) is light_depth_map(tri, np.eye(4), 8)
True
>>> light_depth_map(tri, np.eye(4), 8) is light_depth_map(tri, np.eye(4), 8)
False
"""

from __future__ import annotations

import contextlib
import threading
from collections import OrderedDict
from collections.abc import Iterator

from ... import _validation as check
from ..lightmaps import depth
from ..lightmaps.sampled import SampledMap


class _Kept(OrderedDict):
    """Maps by key, the least recently used dropped beyond ``limit`` bytes (:func:`_bytes`)."""

    def __init__(self, limit: int):
        super().__init__()
        self.limit = limit
        self.lock = threading.RLock()  # the suns of a count are measured on threads

    def __getitem__(self, key):
        with self.lock:
            self.move_to_end(key)
            return super().__getitem__(key)

    def __setitem__(self, key, value):
        with self.lock:
            super().__setitem__(key, value)
            while len(self) > 1 and sum(_bytes(v) for v in self.values()) > self.limit:
                self.popitem(last=False)


def _bytes(kept) -> int:
    """A kept value's bytes: a sampled map's texels found so far and its slot table, an array's, a whole map's 16 per texel."""
    return int(kept.nbytes) if hasattr(kept, "nbytes") else int(kept.resolution) ** 2 * 16


def remember(limit: int = 2**30) -> contextlib.AbstractContextManager:
    """Within the block the light depth maps drawn are kept (module docstring).

    Parameters
    ----------
    limit : int
        The most bytes the kept maps hold together, 0 to 2⁴⁰ [bytes] (at least the last map is kept).

    Examples
    --------
    >>> remember(-1)
    Traceback (most recent call last):
    ...
    ValueError: limit must be a whole number >= 0 [bytes], got -1
    """
    return _remembering(check.whole(limit, "limit", 0, 2**40, " [bytes]"))


@contextlib.contextmanager
def _remembering(limit: int) -> Iterator[None]:
    outer = depth.KEPT["maps"]
    depth.KEPT["maps"] = _Kept(limit) if outer is None else outer
    try:
        yield
    finally:
        depth.KEPT["maps"] = outer
