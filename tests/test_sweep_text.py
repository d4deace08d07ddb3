"""The vectorized CSV text (issue 12 item 4) and batches of chunks sharing light frames (item 1).

:mod:`aliasing.sweep.formats` must write exactly what CPython's ``'%.10g' % x`` writes, for
every float64: generated doubles from their bit patterns cover every exponent, subnormals,
signed zeros, infinities and NaNs; the hand-picked cases are the boundaries of the method
(powers of ten, values that round up to the next power, exact halfway cases).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from aliasing import sweep as S
from aliasing.sweep import chunks, formats


def _python(a: np.ndarray) -> list[str]:
    return ["%.10g" % v for v in np.asarray(a, dtype=float).ravel().tolist()]


@given(hnp.arrays(np.float64, hnp.array_shapes(max_dims=3, max_side=40), elements=st.floats(width=64, allow_nan=True, allow_infinity=True)))
def test_g10_is_percent_10g_for_any_doubles(a):
    assert formats.g10(a).ravel().tolist() == _python(a)
    assert formats.g10(a).shape == a.shape


@given(st.lists(st.integers(0, 2**64 - 1), min_size=1, max_size=300))
def test_g10_on_raw_bit_patterns(bits):
    a = np.array(bits, dtype=np.uint64).view(np.float64)  # every exponent with the same weight
    assert formats.g10(a).tolist() == _python(a)


@given(st.lists(st.integers(10**9, 10**10 - 1), min_size=1, max_size=200), st.integers(-300, 290))
def test_g10_on_halfway_and_short_decimals(digits, exp):
    q = np.array(digits, dtype=float)
    for a in (q * 10 + 5, q / 10.0 ** (9 - min(exp, 280) % 20), np.round(q, -5) * 10.0**exp):  # ties at the 11th digit, short decimals
        assert formats.g10(a).tolist() == _python(a)


def test_g10_boundaries():
    k = np.arange(-323, 309)
    p = 10.0**k.astype(float)
    nines = np.array([float(f"9.9999999995e{e}") for e in range(-300, 300)])
    cases = np.concatenate([p, np.nextafter(p, 0), np.nextafter(p, np.inf), nines, np.nextafter(nines, 0), np.nextafter(nines, np.inf),
                            [0.0, -0.0, np.inf, -np.inf, np.nan, -np.nan, 5e-324, -5e-324, 1.7976931348623157e308, 1e-5, 1e-4, 0.5, 12345678905.0, 9999999999.5]])
    for a in (cases, -cases):
        assert formats.g10(a).tolist() == _python(a)


def test_csv_lines_joins_columns_and_lists():
    n = np.array([3, 40], dtype=np.int64)
    text = formats.csv_lines('"a,b",7', [np.array([0.1, 2.0]), np.array([[1e-5, np.nan], [np.inf, -0.0]]), n])
    assert text == '"a,b",7,0.1,1e-05;nan,3\n"a,b",7,2,inf;-0,40\n'
    assert formats.csv_lines("", [np.array([1.5])]) == "1.5\n"
    assert formats.csv_lines("x", [np.zeros((0, 2))]) == ""


@pytest.mark.parametrize("bad, match", [
    (dict(head="a\0b", columns=[np.ones(2)]), "NUL"),
    (dict(head="a", columns=[np.ones(2), np.ones(3)]), "same length"),
    (dict(head="a", columns=[np.array(["x", "y"])]), "numbers"),
    (dict(head="a", columns=[np.array([10**10])]), "below 10\\*\\*10"),
])
def test_csv_lines_refuses_what_it_cannot_write_exactly(bad, match):
    with pytest.raises(ValueError, match=match):
        formats.csv_lines(**bad)


# ---- batches: one evaluate_many per (f/n, fov, block, options) ------------------------------------


def test_batch_payloads_equal_chunk_payloads_bit_for_bit():
    g = S.plan("P,ZP3+LogP,FPc+P,eta", params={"eta": [-0.5, 0.5]}, f_over_n=[10, 1000], light="sphere:40,overhead,behind", block=15)
    for kind in ("csv", "json", "arrays"):
        for batch in g.batches(range(g.chunks)):
            got = g.batch(batch, kind).compute()
            want = [chunks.compute_chunk(g.chunk(i, kind)) for i in batch]
            if kind == "arrays":
                for a, b in zip(got, want):
                    assert sorted(a) == sorted(b) and all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)
            else:
                assert got == want


def test_batches_group_schemes_of_the_same_directions_and_options():
    g = S.plan("P,LogP,eta", params={"eta": [-1.0, 0.5]}, light="sphere:30", block=10)
    assert g.shape == (4, 1, 1, 1, 30) and g.chunks == 12  # (variants, f/n, fov, aspect, directions)
    batches = g.batches(range(g.chunks))
    assert sorted(i for b in batches for i in b) == list(range(12))
    for b in batches:
        tasks = [g.chunk(i, "csv") for i in b]
        assert len({(t.ratio, t.fov, t.options, t.light.tobytes()) for t in tasks}) == 1
    assert [len(b) for b in batches] == [2, 1, 1] * 3  # P and LogP share options (none); each eta value alone
    assert all(len(b) == 1 for b in g.batches([0, 5], workers=4))  # halved so that 4 workers have work
    assert g.batches([], workers=2) == []


def test_output_order_is_row_order_and_old_work_directories_are_refused():
    g = S.plan("P,LogP", f_over_n=[10, 100], light="sphere:20", block=10)
    order = g.output_order()
    assert sorted(order) == list(range(g.chunks))
    keys = [(g.chunk(i, "csv").name, g.chunk(i, "csv").ratio) for i in order]
    assert keys == sorted(keys, key=lambda k: (["P", "LogP"].index(k[0]), k[1]))
    # the chunk numbering is part of the manifest's hash: a work directory numbered otherwise is not resumed
    params = g.parameters()
    assert params.pop("chunk_order") == "f_over_n,fov,block,variant"
    assert S.parameters_digest(params, "csv") != S.parameters_digest(g.parameters(), "csv")


@pytest.mark.parametrize("bad", [np.array(["1"]), np.array([1 + 2j]), np.array([None, 1.0], dtype=object)])
def test_g10_refuses_what_is_not_real_numbers(bad):
    with pytest.raises(ValueError, match="x must be an array of real numbers"):
        formats.g10(bad)


def test_batches_hold_at_most_max_batch_chunks():
    from aliasing.sweep.grid import MAX_BATCH

    g = S.plan("P,LogP,Po,Standard,ZP2,ZP3,ZP2+P,ZP3+P,ZP2+LogP", light="sphere:20", block=10)
    batches = g.batches(range(g.chunks))
    assert max(len(b) for b in batches) == MAX_BATCH and sorted(i for b in batches for i in b) == list(range(g.chunks))
    assert S.execute(g, "csv") == S.table("P,LogP,Po,Standard,ZP2,ZP3,ZP2+P,ZP3+P,ZP2+LogP", light="sphere:20", block=10).format("csv")
