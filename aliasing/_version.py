"""The toolkit's version, in one place: the package, the sweeps' manifests and outputs read it here."""

__version__ = "0.1.0"
