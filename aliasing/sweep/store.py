"""Files: atomic writes, the output target, the work directory ``<out>.parts`` and its manifest.

Every file the sweep engine writes goes through :func:`atomic_target`: a temporary file in
the target's folder (a name within NAME_MAX), fsynced, given mode ``0666 & ~umask``,
renamed over the target, the folder fsynced; a failed run never damages an existing file.
:func:`resolve_out` follows symbolic links to their target, maps ``-`` and ``/dev/stdout``
to standard output and refuses devices, FIFOs and sockets before any work.  The manifest of
a work directory records the SHA-256 and row count of every finished chunk; a resumed run
reuses only chunks that still match.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import os
import stat
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._version import __version__

if TYPE_CHECKING:  # annotations only: the runner and the tables import this module
    from .runner import Plan
    from .tables import SweepTable

NAME_MAX = 255
"""Longest file name (bytes) on common file systems; temporary and work-directory names stay within it."""
STDOUT_NAMES = ("-", "/dev/stdout")
"""``--out`` values that mean standard output."""
_KINDS = ((stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISSOCK, "a socket"))


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _short(name: str, keep: int) -> str:
    """``name`` if it has at most ``keep`` bytes, else a prefix and a hash of it (deterministic)."""
    if len(name.encode()) <= keep:
        return name
    digest = hashlib.sha256(name.encode()).hexdigest()[:12]
    cut = name.encode()[: keep - 13].decode(errors="ignore")
    return f"{cut}-{digest}"


def _fsync_folder(folder: Path) -> None:
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:  # some file systems do not fsync folders
        pass
    finally:
        os.close(fd)


@contextlib.contextmanager
def atomic_target(target: str | os.PathLike) -> Iterator[Path]:
    """A temporary path beside ``target`` that replaces it atomically once the block succeeds.

    The data is fsynced before the rename and the folder after it; the file gets mode
    ``0666 & ~umask``; on any exception the temporary file is removed and ``target`` is
    untouched.

    Example
    -------
    >>> import pathlib, tempfile
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "x.txt"
    >>> with atomic_target(out) as tmp:
    ...     _ = tmp.write_text("hello")
    >>> out.read_text(), oct(out.stat().st_mode & 0o777) == oct(0o666 & ~_umask())
    ('hello', True)
    """
    target = Path(target)
    folder = target.parent
    fd, name = tempfile.mkstemp(dir=folder, prefix="." + _short(target.name, NAME_MAX - 30) + ".", suffix=".tmp")
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        fd = os.open(tmp, os.O_RDONLY)
        try:
            os.fsync(fd)  # the data is on disk before the name points at it
        finally:
            os.close(fd)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    _fsync_folder(folder)


def _atomic_bytes(data: bytes, target: Path) -> None:
    with atomic_target(target) as tmp:
        tmp.write_bytes(data)


def _write_text_stream(parts: Iterable[str | bytes], target: Path) -> None:
    with atomic_target(target) as tmp, open(tmp, "wb") as handle:
        for part in parts:
            handle.write(part.encode() if isinstance(part, str) else part)


def resolve_out(out: str | os.PathLike, option: str = "out") -> Path | None:
    """The file to write for ``out``: None for standard output (``-``, ``/dev/stdout``).

    A symbolic link resolves to its target (written in the target's folder); a folder, a
    missing folder, a file that cannot be written and any non-regular file (device, FIFO,
    socket) are refused with a ValueError naming ``option``, before any work.

    Example
    -------
    >>> resolve_out("-") is None, resolve_out("/dev/stdout") is None
    (True, True)
    >>> resolve_out("/dev/null")
    Traceback (most recent call last):
    ValueError: out '/dev/null' is not a regular file (a character device); refusing to replace it
    """
    text = os.fspath(out)
    if not isinstance(text, str):
        raise ValueError(f"{option} must be a file name, got {out!r}")
    if text in STDOUT_NAMES:
        return None
    if not text.strip():
        raise ValueError(f"{option} is empty; give a file name, or - for standard output")
    target = Path(os.path.realpath(text)) if os.path.islink(text) else Path(text)
    try:
        st = os.stat(target)
    except FileNotFoundError:
        st = None
    except OSError as exc:
        raise ValueError(f"{option} {text!r} cannot be written: {exc.strerror}") from None
    if st is not None and stat.S_ISDIR(st.st_mode):
        raise ValueError(f"{option} {text!r} is a folder; give a file name")
    if st is not None and not stat.S_ISREG(st.st_mode):
        kind = next((says for test, says in _KINDS if test(st.st_mode)), "not a file")
        raise ValueError(f"{option} {text!r} is not a regular file ({kind}); refusing to replace it")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise ValueError(f"{option} {text!r}: folder {str(folder)!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK) or (st is not None and not os.access(target, os.W_OK)):
        raise ValueError(f"{option} {text!r} cannot be written (permission denied)")
    return target


def _check_out(out: str | os.PathLike) -> Path:
    target = resolve_out(out)
    if target is None:
        raise ValueError("out: standard output is not a file here; give a file name")
    return target


def write(text: str, path: str | os.PathLike) -> Path:
    r"""Write ``text`` atomically: a failed run never truncates an existing file (see :func:`atomic_target`).

    Example
    -------
    >>> import pathlib, tempfile
    >>> write("a,b\n", pathlib.Path(tempfile.mkdtemp()) / "t.csv").read_text()
    'a,b\n'
    """
    target = _check_out(path)
    try:
        _write_text_stream([text.encode()], target)
    except OSError as exc:
        raise ValueError(f"out {str(path)!r} cannot be written: {exc.strerror}") from None
    return target


def _workdir(out: Path) -> Path:
    return out.with_name(_short(out.name, NAME_MAX - 6) + ".parts")


_EXT = {"csv": "csv", "json": "json", "arrays": "npz", "rows": "jsonl"}


def _payload_bytes(kind: str, payload: object) -> bytes:
    if kind == "arrays":
        buf = io.BytesIO()
        np.savez(buf, **payload)  # type: ignore[arg-type]
        return buf.getvalue()
    if kind == "rows":  # exact: JSON keeps every float's repr (NaN and inf too), ints and bools
        return "".join(json.dumps(row) + "\n" for row in payload).encode()  # type: ignore[attr-defined]
    return str(payload).encode()


def _payload_rows(kind: str, data: bytes) -> int:
    """Rows in a chunk file's bytes (-1 if unreadable): a second check beside the checksum."""
    if kind == "arrays":
        try:
            with np.load(io.BytesIO(data), allow_pickle=False) as arrays:
                return int(arrays["S"].shape[0])
        except Exception:  # any damage: not a readable .npz
            return -1
    if kind == "json":  # rows are indented objects opening with a line " {"
        return data.count(b"\n {\n") + data.startswith(b" {\n")
    return data.count(b"\n") + (0 if kind == "rows" or not data or data.endswith(b"\n") else 1)


def _payload_load(kind: str, path: Path) -> object:
    if kind == "arrays":
        with np.load(path, allow_pickle=False) as data:
            return {key: data[key] for key in data.files}
    if kind == "rows":
        return [json.loads(line) for line in path.read_text().splitlines()]
    return path.read_bytes()  # UTF-8 text, copied into the output as it is


class WorkDir:
    """The work directory ``<out>.parts``: chunk files and ``manifest.json`` (checksums of finished chunks)."""

    def __init__(self, path: Path, doc: dict, kind: str) -> None:
        self.path, self.doc, self.kind = path, doc, kind
        self.damaged: list[str] = []

    def file(self, i: int) -> Path:
        """The file of chunk ``i``."""
        return self.path / f"{i:06d}.{_EXT[self.kind]}"

    def save(self, i: int, payload: object) -> None:
        """Write chunk ``i`` atomically, then record its SHA-256 and rows in the manifest."""
        data = _payload_bytes(self.kind, payload)
        _atomic_bytes(data, self.file(i))
        self.doc["finished"][str(i)] = {"sha256": hashlib.sha256(data).hexdigest(), "rows": _payload_rows(self.kind, data)}
        self._write_manifest()

    def load(self, i: int) -> object:
        """Chunk ``i``'s payload."""
        return _payload_load(self.kind, self.file(i))

    def _write_manifest(self) -> None:
        _atomic_bytes((json.dumps(self.doc, indent=1) + "\n").encode(), self.path / "manifest.json")

    def verified(self, chunks: int) -> set[int]:
        """Finished chunks whose file still matches its record; the others are dropped (see :attr:`damaged`)."""
        ok: set[int] = set()
        for key, rec in list(self.doc["finished"].items()):
            i = int(key) if key.isdigit() else -1
            path = self.file(i) if 0 <= i < chunks else None
            try:
                data = path.read_bytes() if path is not None else None
            except OSError:
                data = None
            if data is None:
                why = "missing"
            elif not isinstance(rec, dict) or hashlib.sha256(data).hexdigest() != rec.get("sha256"):
                why = "checksum differs"
            elif _payload_rows(self.kind, data) != rec.get("rows"):
                why = "row count differs"
            else:
                ok.add(i)
                continue
            self.damaged.append(f"{path.name if path else key} ({why})")
            del self.doc["finished"][key]
        if self.damaged:
            self._write_manifest()
        return ok


def _open_workdir(grid: Plan, fmt: str, out: Path, resume: bool, kind: str) -> tuple[WorkDir, set[int]]:
    """Create or reopen ``<out>.parts``; the finished chunks there whose checksums still match."""
    work = _workdir(out)
    digest = grid.digest(fmt)
    manifest = work / "manifest.json"
    if work.exists():
        try:
            old = json.loads(manifest.read_text())
            if not isinstance(old, dict):
                raise ValueError
        except (OSError, ValueError):
            raise ValueError(f"resume: {str(work)!r} is not a sweep work directory (no readable manifest.json); remove it") from None
        if not resume:
            raise ValueError(f"out {str(out)!r}: an interrupted sweep left {str(work)!r}; pass --resume to continue it, or remove it")
        if old.get("digest") != digest:
            raise ValueError(f"resume: {str(work)!r} belongs to a different sweep (its parameters differ); remove it or rerun that sweep")
        if not isinstance(old.get("finished"), dict):
            old["finished"] = {}
        wd = WorkDir(work, old, kind)
        return wd, wd.verified(grid.chunks)
    try:
        work.mkdir()
    except OSError as exc:
        raise ValueError(f"out {str(out)!r} cannot be written: {exc.strerror}") from None
    doc = {"aliasing": __version__, "digest": digest, "format": fmt, "chunks": grid.chunks, "parameters": grid.parameters(), "command": grid.command(fmt), "finished": {}}
    wd = WorkDir(work, doc, kind)
    wd._write_manifest()
    return wd, set()


def _write_netcdf(table: SweepTable, target: Path) -> None:
    ds = table.to_xarray()
    with atomic_target(target) as tmp:
        ds.to_netcdf(tmp, engine=_netcdf_engine())


def _netcdf_engine() -> str:
    import importlib.util

    for module, engine in (("netCDF4", "netcdf4"), ("h5netcdf", "h5netcdf")):
        if importlib.util.find_spec(module):
            return engine
    raise ValueError("format netcdf needs netCDF4 or h5netcdf: pip install \".[xarray]\"")
