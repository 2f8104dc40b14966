"""Shared services: atomic writes, safe output folders, provenance, option schema, warnings.

Also which compressed stream a file holds (:func:`compression_of`).

This package sits at the bottom of the import graph (it imports nothing from
the stage packages), so any stage can use it without creating a cycle.
"""

from __future__ import annotations

from psdbound.common.atomic import atomic_folder, atomic_write_bytes, atomic_write_text
from psdbound.common.compression import compression_of
from psdbound.common.notices import PsdboundWarning, warn
from psdbound.common.options import OptionError, check_fields, option
from psdbound.common.provenance import file_sha256, package_versions

__all__ = [
    "OptionError",
    "PsdboundWarning",
    "atomic_folder",
    "atomic_write_bytes",
    "atomic_write_text",
    "check_fields",
    "compression_of",
    "file_sha256",
    "option",
    "package_versions",
    "warn",
]
