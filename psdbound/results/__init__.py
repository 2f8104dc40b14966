"""The result document (``result.json``): its schema version, writer and reader.

This is the one owner of the result format. The front door
(:func:`psdbound.fit`, :func:`psdbound.load`), the reports and the Kalman
filter tools (:meth:`psdbound.kalman.GaussMarkovBound.from_result`) all read
and write through it. The JSON Schema of the document,
``result.schema.json``, is shipped beside it (:func:`load_schema`,
:func:`validate`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.results.jsonfile import json_text, to_jsonable, write_json
    from psdbound.results.jsonschema import SCHEMA_FILE, load_schema, schema_errors, validate
    from psdbound.results.schema import (
        NUMBER_FIELDS,
        REQUIRED_FIELDS,
        SCHEMA_VERSION,
        get_field,
        number_problems,
        read_document,
        write_document,
    )

__all__ = [
    "NUMBER_FIELDS",
    "REQUIRED_FIELDS",
    "SCHEMA_FILE",
    "SCHEMA_VERSION",
    "get_field",
    "json_text",
    "load_schema",
    "number_problems",
    "read_document",
    "schema_errors",
    "to_jsonable",
    "validate",
    "write_document",
    "write_json",
]

#: Where each public name lives (imported on first use: the headline module, which the
#: light verdict module uses, must not pull NumPy in through this package).
_EXPORTS = {
    **{n: ("psdbound.results.jsonfile", n) for n in ("json_text", "to_jsonable", "write_json")},
    **{
        n: ("psdbound.results.jsonschema", n)
        for n in ("SCHEMA_FILE", "load_schema", "schema_errors", "validate")
    },
    **{
        n: ("psdbound.results.schema", n)
        for n in (
            "NUMBER_FIELDS",
            "REQUIRED_FIELDS",
            "SCHEMA_VERSION",
            "get_field",
            "number_problems",
            "read_document",
            "write_document",
        )
    },
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
