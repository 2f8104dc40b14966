"""Small shared services every stage may use: atomic writes and provenance.

This package sits at the bottom of the import graph (it imports nothing from
the stage packages), so any stage can use it without creating a cycle.
"""

from __future__ import annotations

from psdbound.common.atomic import atomic_folder, atomic_write_bytes, atomic_write_text
from psdbound.common.provenance import file_sha256, package_versions

__all__ = [
    "atomic_folder",
    "atomic_write_bytes",
    "atomic_write_text",
    "file_sha256",
    "package_versions",
]
