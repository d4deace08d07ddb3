"""Files: atomic writes, the output target, the work directory ``<out>.parts`` and its manifest.

Every file the sweep engine writes goes through here: a temporary file in the target's
folder, fsynced, renamed over the target, the folder fsynced; a failed run never damages
an existing file.
"""

from __future__ import annotations

import io
import json
import os
import tempfile
from collections.abc import Iterable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .runner import Plan
    from .tables import SweepTable


def write(text: str, path: str | os.PathLike) -> Path:
    """Write ``text`` atomically: a failed run never truncates an existing file."""
    target = Path(path)
    if target.is_dir():
        raise ValueError(f"out {str(target)!r} is a folder; give a file name")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise ValueError(f"out {str(target)!r}: folder {str(folder)!r} does not exist")
    try:
        fd, tmp = tempfile.mkstemp(dir=folder, prefix=f".{target.name}.", suffix=".tmp")
    except OSError as exc:
        raise ValueError(f"out {str(target)!r} cannot be written: {exc.strerror}") from None
    try:
        with os.fdopen(fd, "w", newline="") as handle:
            handle.write(text)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


def _workdir(out: Path) -> Path:
    return out.with_name(out.name + ".parts")


def _check_out(out: str | os.PathLike) -> Path:
    target = Path(out)
    if target.is_dir():
        raise ValueError(f"out {str(target)!r} is a folder; give a file name")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        raise ValueError(f"out {str(target)!r}: folder {str(folder)!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK) or (target.exists() and not os.access(target, os.W_OK)):
        raise ValueError(f"out {str(target)!r} cannot be written (permission denied)")
    return target


def _atomic_bytes(data: bytes, target: Path) -> None:
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


_EXT = {"csv": "csv", "json": "json", "arrays": "npz", "rows": "jsonl"}


def _payload_bytes(kind: str, payload: object) -> bytes:
    if kind == "arrays":
        buf = io.BytesIO()
        np.savez(buf, **payload)  # type: ignore[arg-type]
        return buf.getvalue()
    if kind == "rows":  # exact: JSON keeps every float's repr (NaN and inf too), ints and bools
        return "".join(json.dumps(row) + "\n" for row in payload).encode()  # type: ignore[attr-defined]
    return str(payload).encode()


def _payload_load(kind: str, path: Path) -> object:
    if kind == "arrays":
        with np.load(path, allow_pickle=False) as data:
            return {key: data[key] for key in data.files}
    if kind == "rows":
        return [json.loads(line) for line in path.read_text().splitlines()]
    return path.read_bytes()  # UTF-8 text, copied into the output as it is


def _open_workdir(grid: Plan, fmt: str, out: Path, resume: bool, kind: str) -> tuple[Path, set[int]]:
    """Create or reopen ``<out>.parts``; the chunks already finished there."""
    from .. import __version__

    work = _workdir(out)
    digest = grid.digest(fmt)
    manifest = work / "manifest.json"
    if work.exists():
        try:
            old = json.loads(manifest.read_text())
        except (OSError, ValueError):
            raise ValueError(f"resume: {str(work)!r} is not a sweep work directory (no readable manifest.json); remove it") from None
        if not resume:
            raise ValueError(f"out {str(out)!r}: an interrupted sweep left {str(work)!r}; pass --resume to continue it, or remove it")
        if old.get("digest") != digest:
            raise ValueError(f"resume: {str(work)!r} belongs to a different sweep (its parameters differ); remove it or rerun that sweep")
    else:
        try:
            work.mkdir()
        except OSError as exc:
            raise ValueError(f"out {str(out)!r} cannot be written: {exc.strerror}") from None
        doc = {"aliasing": __version__, "digest": digest, "format": fmt, "chunks": grid.chunks, "parameters": grid.parameters(), "command": grid.command(fmt)}
        _atomic_bytes((json.dumps(doc, indent=1) + "\n").encode(), manifest)
    ext = _EXT[kind]
    finished = {int(p.stem) for p in work.glob(f"*.{ext}") if p.stem.isdigit() and int(p.stem) < grid.chunks}
    return work, finished


def _write_text_stream(parts: Iterable[str | bytes], target: Path) -> None:
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as handle:
            for part in parts:
                handle.write(part.encode() if isinstance(part, str) else part)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _write_netcdf(table: SweepTable, target: Path) -> None:
    ds = table.to_xarray()
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    os.close(fd)
    try:
        ds.to_netcdf(tmp, engine=_netcdf_engine())
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _netcdf_engine() -> str:
    import importlib.util

    for module, engine in (("netCDF4", "netcdf4"), ("h5netcdf", "h5netcdf")):
        if importlib.util.find_spec(module):
            return engine
    raise ValueError("format netcdf needs netCDF4 or h5netcdf: pip install 'aliasing[xarray]'")
