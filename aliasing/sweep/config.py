"""Sweep config files (TOML): reading them safely and checking their keys (:data:`CONFIG_KEYS`)."""

from __future__ import annotations

import os
import stat

from .. import _validation as check


MAX_CONFIG_BYTES = 1 << 20
"""Largest config file read [bytes]: a sweep's parameters fit in a few hundred."""


def _load_toml(path: str | os.PathLike) -> dict:
    try:
        import tomllib
    except ImportError:  # Python 3.10: the tomli dependency
        import tomli as tomllib  # type: ignore[no-redef]
    where = f"config {str(path)!r}"
    try:
        st = os.stat(path)
        if not stat.S_ISREG(st.st_mode):  # a FIFO would block open() forever, a device never end
            raise ValueError(f"{where} is not a regular file")
        if st.st_size > MAX_CONFIG_BYTES:
            raise ValueError(f"{where} is {st.st_size:,} bytes; a config is at most {MAX_CONFIG_BYTES:,}")
        with open(path, "rb") as handle:
            data = handle.read(MAX_CONFIG_BYTES + 1)
    except OSError as exc:
        raise ValueError(f"{where} cannot be read: {exc.strerror}") from None
    if len(data) > MAX_CONFIG_BYTES:
        raise ValueError(f"{where} is larger than {MAX_CONFIG_BYTES:,} bytes")
    try:
        return tomllib.loads(data.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise ValueError(f"{where} is not UTF-8 text (byte {exc.start}: {exc.reason})") from None
    except RecursionError:
        raise ValueError(f"{where} is nested too deeply") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{where} is not valid TOML: {exc}".splitlines()[0]) from None


_NUM = "a number, a list of numbers or a range string"
CONFIG_KEYS: dict[str, tuple[tuple[type, ...], str]] = {
    "schemes": ((str, list), "a string or a list of strings"),
    "k": ((int, list, str), "a whole number, a list or a range string"),
    "f_over_n": ((int, float, list, str), _NUM),
    "fov": ((int, float, list, str), _NUM),
    "aspect": ((int, float, list, str), _NUM),
    "light": ((str, list), "a string or a list of strings"),
    "near": ((int, float), "a number"),
    "params": ((dict,), "a table of option = values"),
    "summary": ((bool,), "true or false"),
    "format": ((str,), "a string"),
    "out": ((str,), "a string"),
    "block": ((int,), "a whole number"),
    "jobs": ((int,), "a whole number"),
    "dask": ((str,), "a string"),
}
"""Keys of a sweep config file, the TOML types each takes, and how to say it."""


def read_config(path: str | os.PathLike) -> dict:
    r"""A sweep's TOML config: keys :data:`CONFIG_KEYS`; ValueError on unknown keys or types.

    Example
    -------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "sweep.toml"
    >>> _ = path.write_text('schemes = ["P", "LogP"]\nk = [1, 5]\nf_over_n = "10:10000:log:7"\n[params]\nc_fraction = [0.2, 0.4]\n')
    >>> read_config(path)["f_over_n"]
    '10:10000:log:7'
    >>> _ = path.write_text('schemes = "P"\nfovv = 60\n')
    >>> read_config(path)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: config '...sweep.toml': unknown key 'fovv' (did you mean 'fov'?); allowed: schemes, k, f_over_n, fov, aspect, light, near, params, summary, format, out, block, jobs, dask
    """
    doc = _load_toml(path)
    where = f"config {str(path)!r}"
    for key, value in doc.items():
        if key not in CONFIG_KEYS:
            raise ValueError(f"{where}: unknown key {key!r}{check.did_you_mean(key, CONFIG_KEYS)}; allowed: {', '.join(CONFIG_KEYS)}")
        types, says = CONFIG_KEYS[key]
        bad = isinstance(value, bool) and bool not in types
        if bad or not isinstance(value, types):
            raise ValueError(f"{where}: key {key!r} must be {says}, got {type(value).__name__} {value!r}")
        items = value if isinstance(value, list) else []
        if key in ("schemes", "light") and not all(isinstance(v, str) for v in items):
            raise ValueError(f"{where}: key {key!r} must be {says}, got {value!r}")
        if key in ("f_over_n", "fov", "aspect", "k") and any(isinstance(v, bool) or not isinstance(v, (int, float, str)) for v in items):
            raise ValueError(f"{where}: key {key!r} must be {says}, got {value!r}")
        if key == "params":
            for name, v in value.items():
                if isinstance(v, bool) or not isinstance(v, (int, float, str, list)):
                    raise ValueError(f"{where}: params.{name} must be {_NUM}, got {v!r}")
    return doc
