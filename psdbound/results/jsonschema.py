"""The JSON Schema of ``result.json`` (Draft 2020-12), shipped with the package.

``result.schema.json`` beside this module documents every field of a result
document (type, unit, meaning) and is what the documentation's result.json
reference is generated from. :func:`validate` checks a document against it
with the `jsonschema <https://python-jsonschema.readthedocs.io>`_ library,
which is an optional dependency (the ``test`` and ``docs`` extras): reading
and writing results (:mod:`psdbound.results.schema`) does not need it.
"""

from __future__ import annotations

import json
from functools import cache
from importlib import resources
from typing import Any

from psdbound.errors import InputError

__all__ = ["SCHEMA_FILE", "load_schema", "schema_errors", "validate"]

#: Name of the schema file inside :mod:`psdbound.results`.
SCHEMA_FILE = "result.schema.json"


@cache
def _schema_text() -> str:
    return resources.files("psdbound.results").joinpath(SCHEMA_FILE).read_text(encoding="utf-8")


def load_schema() -> dict[str, Any]:
    """Return the JSON Schema of ``result.json`` as a new dictionary.

    Returns
    -------
    dict
        The Draft 2020-12 schema (``$schema``, ``properties``, ...).
    """
    return json.loads(_schema_text())


def _validator() -> Any:
    try:
        import jsonschema
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "validating result.json needs the 'jsonschema' package "
            "(pip install 'psdbound[test]' or 'jsonschema>=4')"
        ) from exc
    schema = load_schema()
    cls = jsonschema.Draft202012Validator
    cls.check_schema(schema)
    return cls(schema, format_checker=cls.FORMAT_CHECKER)


def schema_errors(document: dict[str, Any]) -> list[str]:
    """Return every schema violation of a result document, one line each.

    Parameters
    ----------
    document : dict
        A parsed ``result.json``.

    Returns
    -------
    list of str
        ``"<dotted.path>: <message>"`` per violation, sorted by path; empty
        when the document is valid.
    """
    out = []
    for err in _validator().iter_errors(document):
        path = ".".join(str(p) for p in err.absolute_path) or "(top level)"
        out.append(f"{path}: {err.message}")
    return sorted(out)


def validate(document: dict[str, Any]) -> None:
    """Check a result document against the schema.

    Parameters
    ----------
    document : dict
        A parsed ``result.json``.

    Raises
    ------
    InputError
        If the document violates the schema; the message names the first
        field at fault and how many violations there are.
    """
    errors = schema_errors(document)
    if errors:
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        raise InputError(f"result document does not match {SCHEMA_FILE}: {errors[0]}{more}")
