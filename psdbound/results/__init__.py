"""The result document (``result.json``): its schema version, writer and reader.

This is the one owner of the result format. The front door
(:func:`psdbound.fit`, :func:`psdbound.load`), the reports and the Kalman
filter tools (:meth:`psdbound.kalman.GaussMarkovBound.from_result`) all read
and write through it.
"""

from __future__ import annotations

from psdbound.results.schema import (
    NUMBER_FIELDS,
    REQUIRED_FIELDS,
    SCHEMA_VERSION,
    get_field,
    number_problems,
    read_document,
    to_jsonable,
    write_document,
)

__all__ = [
    "NUMBER_FIELDS",
    "REQUIRED_FIELDS",
    "SCHEMA_VERSION",
    "get_field",
    "number_problems",
    "read_document",
    "to_jsonable",
    "write_document",
]
