"""The light depth maps the frames' models draw: whole (:mod:`.depth`) or only at the texels looked up (:mod:`.sampled`).

The engines' rules that read them (their filters, biases and atlases) are in :mod:`aliasing.frames.predict`.
"""
