"""Property (issue 11 item 6): every split method's distances increase and cover [near, far],
and every engine's maps (padded or overlapped) cover it too, for generated frusta, k and λ."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import assume, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from aliasing.partitioning import SPLIT_METHODS, partitions, split_distances  # noqa: E402


@settings(max_examples=300, deadline=None)
@given(
    method=st.sampled_from(sorted(SPLIT_METHODS)),
    near=st.floats(1e-3, 1e3),
    ratio=st.one_of(st.floats(1.0 + 1e-9, 10.0), st.floats(10.0, 1e6)),
    k=st.integers(1, 16),
    lam=st.floats(0.0, 1.0),
)
def test_splits_increase_and_cover_the_frustum(method, near, ratio, k, lam):
    entry = SPLIT_METHODS[method]
    k = min(k, entry.max_k) if entry.max_k else k
    k = max(k, entry.min_k)  # Babylon.js: 2 to 4 cascades
    assume(not (method == "godot" and k == 3))  # Godot has 1, 2 or 4 splits (refused: test_partitioning_budgets)
    far = near * ratio
    params = {"lam": lam} if "lam" in inspect.signature(entry.func).parameters else {}
    if "first" in inspect.signature(entry.func).parameters:  # Bevy's first cascade bound [world units], inside (near, far)
        params["first"] = near * ratio**0.5
        assume(near < params["first"] < far)
    c = split_distances(method, near, far, k, **params)
    assert c.shape == (k + 1,)
    assert c[0] == near and c[-1] == far
    assert np.all(np.diff(c) >= 0), c
    if ratio >= 1.01:
        # strictly increasing; as f/n -> 1 three.js's breaks (C_i/F applied from n) approach far
        # together, (f - n)^2/f apart, below rounding at f/n = 1 + 1e-6: not separable in float64
        assert np.all(np.diff(c) > 0), c
    lo, hi = partitions(method, near, far, k, **params)
    assert np.all(hi >= lo)
    order = np.argsort(lo)
    lo, hi = lo[order], hi[order]
    # the maps' depth ranges leave no gap inside [near, far]
    assert lo[0] <= near and np.maximum.accumulate(hi)[-1] >= far
    assert np.all(lo[1:] <= np.maximum.accumulate(hi)[:-1])


@settings(max_examples=200, deadline=None)
@given(base=st.sampled_from(sorted({m.partition("@")[0] for m in SPLIT_METHODS}) + ["nosuch"]), release=st.text(max_size=12))
def test_any_release_name_resolves_or_is_refused_in_one_line(base, release):
    from aliasing.partitioning import resolve_name

    name = f"{base}@{release}"
    try:
        key = resolve_name(name)
    except ValueError as exc:
        text = str(exc)
        assert "\n" not in text and ("known releases" in text or "not pinned" in text or "unknown split method" in text), text
    else:
        entry = SPLIT_METHODS[key]
        assert entry.name.partition("@")[0] == base and release.strip().lower() in (r.lower() for r in entry.releases)
