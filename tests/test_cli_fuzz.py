"""Fuzzing the sweep command line (issue 19 item 5): generated argument lists from the documented
vocabulary plus garbage, run in-process through ``aliasing.cli.main``.

The outcome of every list is exit 0, or exit 2 with exactly one line on stderr; never a
traceback or another exit code.  Deterministic (profile "ci" in conftest.py); at least 1,000
examples; ``ALIASING_HYPOTHESIS=long`` runs the "long" profile's count instead.
"""

from __future__ import annotations

import warnings

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from aliasing.cli import main  # noqa: E402

# Values are tiny (fast to compute) or absurd (refused before allocating): never in between.
NUMBERS = ["1", "10", "1000", "60", "0", "-1", "1.5", "inf", "-inf", "nan", "Infinity", "1e400", "99999999999999999999999", "", " ", ",", "1,,2", "٣", "0x10"]
RANGES = ["10:1000:log:3", "30:90:lin:2", "1:2:lin:0", "1:2:cubic:3", "0:10:log:3", "60:60:log:100000000000", "-inf:1:lin:2", "1:nan:lin:2", "1:2:lin:1e3", "::", "1:2:lin"]
SCHEMES = ["P", "LogP", "Standard", "ZP3+LogP", "FPc+ZP2+P", "eta", "tsm", "Po", "ZP0", "ZP99999999+P", "P,,LogP", ",", "Nope", "P,p", "ZP2"]
LIGHTS = ["overhead", "behind", "front", "sphere:5", "hemisphere:3", "gamma:30", "gamma:0:180:lin:3@azimuth:0,90", "sphere:100000000000", "gamma:30@azimuth:Infinity",
          "gamma:nan", "a,,b", "sphere:-4", "hemisphere:0", "gamma:1x", "gamma:30@tilt:5", "sphere:", ""]
PARAMS = ["eta=-1,0", "eta=-1:1:lin:3", "c_fraction=0.2", "tau1=-inf:1:lin:2", "focus=0.2", "eta", "=1", "near=2", "eta=nan"]
FORMATS = ["csv", "json", "xml", "netcdf", "parquet"]
MEMORY = ["4G", "100M", "1", "0", "lots", "inf", "-1G", "1e30T"]
JOBS = ["1", "0", "-1", "1.5", "nan", "inf", "99999999999999999999999", "abc"]  # never 2+: process start-up is slow here
BLOCKS = ["1", "3", "20000", "0", "-5", "1.5", "1e400"]


def _garbage():
    return st.text(max_size=12)


def _value(vocab):
    return st.one_of(st.sampled_from(vocab), _garbage())


def _option(tmp):
    outs = ["-", "/dev/stdout", "/dev/null", str(tmp / "o.csv"), str(tmp), str(tmp / "missing" / "x.csv"), str(tmp / ("n" * 250 + ".csv"))]
    return st.one_of(
        st.tuples(st.just("--schemes"), _value(SCHEMES)),
        st.tuples(st.just("--light"), _value(LIGHTS)),
        st.tuples(st.just("--f-over-n"), _value(NUMBERS + RANGES)),
        st.tuples(st.just("--fov"), _value(NUMBERS + RANGES)),
        st.tuples(st.just("--aspect"), _value(NUMBERS + RANGES + ["1", "2", "1.7778", "16:9", "0.25,4"])),
        st.tuples(st.just("--k"), _value(["1", "3", "1,3", "1:3:lin:2", "inf", "0", "0.5", "99999999", "1e400"])),
        st.tuples(st.just("--param"), _value(PARAMS)),
        st.tuples(st.just("--near"), _value(NUMBERS)),
        st.tuples(st.just("--format"), _value(FORMATS)),
        st.tuples(st.just("--jobs"), _value(JOBS)),
        st.tuples(st.just("--block"), _value(BLOCKS)),
        st.tuples(st.just("--max-memory"), _value(MEMORY)),
        st.tuples(st.just("--out"), st.sampled_from(outs)),
        st.tuples(st.just("--config"), st.sampled_from([str(tmp / "cfg.toml"), str(tmp / "deep.toml"), str(tmp / "nope.toml"), str(tmp), "/dev/null"])),
        st.tuples(st.sampled_from(["--summary", "--resume", "--dry-run", "--bogus", "-x"])),
        st.tuples(_garbage()),
    )


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("fuzz")
    (tmp / "cfg.toml").write_text('schemes = ["P", "LogP"]\nlight = "sphere:5"\nf_over_n = "10:1000:log:2"\n')
    (tmp / "deep.toml").write_text("params = { eta = " + "[" * 3000 + "]" * 3000 + " }\n")
    return tmp


EXAMPLES = max(1000, settings.default.max_examples)


def test_sweep_command_line_fuzz(folder, capsysbinary):
    counts = {0: 0, 2: 0}

    @settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=list(HealthCheck))
    @given(st.lists(_option(folder), min_size=0, max_size=5))
    def run(options):
        argv = ["sweep", *(part for option in options for part in option)]
        with warnings.catch_warnings(record=True) as caught:  # pytest would swallow them: a real run prints them on stderr
            warnings.simplefilter("always")
            try:
                code = main(argv)
            except SystemExit as exc:  # argparse: usage errors
                code = exc.code
        out, err = capsysbinary.readouterr()
        text = err.decode(errors="replace")
        assert "Traceback" not in text and "Warning" not in text, (argv, text)
        assert not caught, (argv, [f"{w.category.__name__}: {w.message}" for w in caught])
        assert code in (0, 2), (argv, code, text)
        if code == 2:
            assert len(text.strip().splitlines()) == 1, (argv, text)
        counts[code] += 1

    run()
    assert counts[0] + counts[2] >= EXAMPLES and counts[0] > 0 and counts[2] > 0, counts
