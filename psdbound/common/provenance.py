"""Provenance helpers: file digests and the versions of what computed a result."""

from __future__ import annotations

import hashlib
import os
import platform
from importlib import metadata

__all__ = ["file_sha256", "package_versions", "DEPENDENCIES"]

#: Runtime dependencies whose versions are recorded with every result.
DEPENDENCIES = (
    "numpy",
    "scipy",
    "astropy",
    "statsmodels",
    "hatanaka",
    "PyIRI",
    "matplotlib",
    "jinja2",
    "dask",
)


def file_sha256(path: str | os.PathLike[str]) -> str:
    """Return the SHA-256 hex digest of a file's bytes (read in 1 MiB chunks)."""
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def package_versions() -> dict[str, str]:
    """Return the versions of psdbound, Python and every runtime dependency."""
    from psdbound.version import __version__

    out = {"psdbound": __version__, "python": platform.python_version()}
    for name in DEPENDENCIES:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out
