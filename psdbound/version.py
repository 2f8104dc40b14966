"""The installed psdbound version (``psdbound.version.__version__``)."""

from __future__ import annotations

import functools
import hashlib
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path

__all__ = ["__version__", "code_digest"]

try:
    __version__ = version("psdbound")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"


@functools.lru_cache(maxsize=1)
def code_digest() -> str:
    """Return a SHA-256 of the package's source and data files (hex, first 16 digits).

    The version number stays the same between releases while the code
    changes; caches of computed results key on this digest so that a result
    computed by other code is never reused.

    Returns
    -------
    str
    """
    root = Path(__file__).resolve().parent
    h = hashlib.sha256()
    for p in sorted(root.rglob("*")):
        if p.suffix in (".py", ".json", ".j2", ".toml") and "__pycache__" not in p.parts:
            h.update(p.relative_to(root).as_posix().encode())
            h.update(p.read_bytes())
    return h.hexdigest()[:16]
