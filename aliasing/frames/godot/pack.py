"""Godot's main pack for the frames: a PCK (pack format 3) holding the job's scene, written at run time.

Godot 4.6's web export template loads its game from a ``.pck`` file.  The format, as Godot
reads it (``core/io/file_access_pack.cpp`` ``PackedSourcePCK::try_open_pack`` and written by
``core/io/pck_packer.cpp`` ``PCKPacker::flush`` at 4.6-stable), little endian:

* the header: the magic ``GDPC``, the pack format (3), Godot's major, minor and patch version
  (uint32 each), the pack flags (uint32; 2 = ``PACK_REL_FILEBASE``: file offsets count from the
  file base), the file base and the directory's offset (uint64 each), then 16 reserved uint32;
* the files, from the file base, each padded to 16 bytes;
* the directory: the file count (uint32), then per file its path without ``res://`` (uint32
  length padded to 4 bytes, the path, zero padding), its offset and size (uint64 each), its MD5
  (16 bytes) and its flags (uint32, 0: neither encrypted nor removed).

The pack holds text resources only (``project.godot``, ``main.tscn``, ``main.gd``: package data
under ``aliasing/frames/pages/godot/``) and the job as ``job.json``: no binary tokens, no
``.remap`` files.

Examples
--------
>>> data = write_pack({"a.txt": b"hello"})
>>> data[:4], read_pack(data)
(b'GDPC', {'a.txt': b'hello'})
"""

from __future__ import annotations

import hashlib
import json
import struct
from pathlib import Path

GODOT = Path(__file__).parent.parent / "pages" / "godot"
#: pack format version and the engine version (major, minor, patch) written into the header
FORMAT, VERSION = 3, (4, 6, 0)
REL_FILEBASE = 2
HEADER = struct.Struct("<4sIIIIIQQ")
ALIGN = 16


def _pad(n: int, to: int) -> int:
    return (to - n % to) % to


def write_pack(files: dict[str, bytes]) -> bytes:
    """A PCK (pack format 3) holding ``files`` (path without ``res://`` → content).

    Parameters
    ----------
    files : dict of str to bytes
        At least one file; each path relative (no ``res://``, no ``..``), each content bytes.

    Returns
    -------
    bytes
        The pack.

    Raises
    ------
    ValueError
        ``files`` is empty, a path is not a relative POSIX path, or a content is not bytes.

    Examples
    --------
    >>> p = write_pack({"project.godot": b"config_version=5", "main.gd": b"extends Node"})
    >>> struct.unpack_from("<4sIIII", p)            # magic, format, Godot 4.6.0
    (b'GDPC', 3, 4, 6, 0)
    >>> write_pack({})
    Traceback (most recent call last):
    ...
    ValueError: files must hold at least one file (path -> bytes), got none
    """
    if not isinstance(files, dict) or not files:
        raise ValueError("files must hold at least one file (path -> bytes), got none")
    for path, data in files.items():
        if not isinstance(path, str) or not path or path.startswith(("/", "res://")) or ".." in path.split("/") or "\\" in path:
            raise ValueError(f"files: each path must be relative to res:// without '..' (e.g. 'main.gd'), got {path!r}")
        if not isinstance(data, (bytes, bytearray)):
            raise ValueError(f"files[{path!r}] must be bytes, got {type(data).__name__}")
    base = HEADER.size + 16 * 4
    base += _pad(base, ALIGN)
    body, where = bytearray(), {}
    for path, data in files.items():
        where[path] = (len(body), len(data))
        body += data + b"\0" * _pad(len(data), ALIGN)
    directory = bytearray(struct.pack("<I", len(files)))
    for path, data in files.items():
        name = path.encode()
        name += b"\0" * _pad(len(name), 4)
        off, size = where[path]
        directory += struct.pack("<I", len(name)) + name + struct.pack("<QQ", off, size) + hashlib.md5(bytes(data)).digest() + struct.pack("<I", 0)
    header = HEADER.pack(b"GDPC", FORMAT, *VERSION, REL_FILEBASE, base, base + len(body))
    return header + b"\0" * (base - HEADER.size) + bytes(body) + bytes(directory)


def read_pack(data: bytes) -> dict[str, bytes]:
    """The files of a pack written by :func:`write_pack` (pack format 3, offsets from the file base).

    Parameters
    ----------
    data : bytes
        The pack.

    Returns
    -------
    dict of str to bytes
        Path (without ``res://``) → content.

    Raises
    ------
    ValueError
        ``data`` is not a format-3 pack with relative offsets, or its directory runs past its end.

    Examples
    --------
    >>> read_pack(b"PK\\x03\\x04" + bytes(100))
    Traceback (most recent call last):
    ...
    ValueError: data must be a Godot pack (magic GDPC, format 3, relative file base), got magic b'PK\\x03\\x04' format 0
    """
    if not isinstance(data, (bytes, bytearray)) or len(data) < HEADER.size:
        raise ValueError(f"data must be the bytes of a Godot pack of at least {HEADER.size} bytes")
    magic, fmt, _, _, _, flags, base, diro = HEADER.unpack_from(data)
    if magic != b"GDPC" or fmt != FORMAT or not flags & REL_FILEBASE:
        raise ValueError(f"data must be a Godot pack (magic GDPC, format 3, relative file base), got magic {magic!r} format {fmt}")
    if not HEADER.size <= diro <= len(data) - 4 or base > diro:
        raise ValueError(f"data: the pack's directory offset {diro} lies outside its {len(data)} bytes")
    try:
        (n,) = struct.unpack_from("<I", data, diro)
        o, out = diro + 4, {}
        for _ in range(n):
            (length,) = struct.unpack_from("<I", data, o)
            name = bytes(data[o + 4:o + 4 + length]).rstrip(b"\0").decode()
            o += 4 + length
            off, size = struct.unpack_from("<QQ", data, o)
            o += 16 + 16 + 4
            if base + off + size > len(data):
                raise ValueError(f"data: the file {name!r} runs past the pack's end")
            out[name] = bytes(data[base + off:base + off + size])
    except struct.error:
        raise ValueError("data: the pack's directory runs past its end") from None
    return out


def job_pack(job: dict) -> bytes:
    """The main pack of one frame: the project (window of the job's size), the scene, its script and ``job.json``.

    Parameters
    ----------
    job : dict
        The page's job (:func:`aliasing.frames.run.make_job`): ``width`` and ``height`` [px] among the rest.

    Returns
    -------
    bytes
        The pack (:func:`write_pack`).

    Examples
    --------
    >>> files = read_pack(job_pack({"width": 64, "height": 32, "settings": {}}))
    >>> sorted(files), b"viewport_width=64" in files["project.godot"]
    (['job.json', 'main.gd', 'main.tscn', 'project.godot'], True)
    """
    if not isinstance(job, dict) or not all(isinstance(job.get(k), int) and job[k] > 0 for k in ("width", "height")):
        raise ValueError("job must be the page's job dict with width and height [px] (aliasing.frames.run.make_job)")
    project = (GODOT / "project.godot").read_text().replace("WIDTH", str(job["width"])).replace("HEIGHT", str(job["height"]))
    return write_pack({"project.godot": project.encode(), "main.tscn": (GODOT / "main.tscn").read_bytes(),
                       "main.gd": (GODOT / "main.gd").read_bytes(), "job.json": json.dumps(job).encode()})
