"""The JSON Schemas of every command's JSON output (Draft 2020-12), shipped with the package.

``result.schema.json`` beside this module documents every field of a result
document (type, unit, meaning) and is what the documentation's result.json
reference is generated from; ``overbound.schema.json``, ``budget.schema.json``,
``vpl.schema.json``, ``campaign.schema.json``, ``cutoff.schema.json``,
``cutoff_map.schema.json`` and ``validation.schema.json`` document the
outputs of ``overbound``, ``budget``, ``campaign``, ``cutoff`` (a station's
``cutoff_<name>.json``; ``--map``: ``cutoff_map.json``) and ``validate``
(``validation.json``) (:data:`SCHEMAS`). :func:`validate` checks a document against it
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

__all__ = ["SCHEMAS", "SCHEMA_FILE", "load_schema", "schema_errors", "validate"]

#: Name of the schema file of ``result.json`` inside :mod:`psdbound.results`.
SCHEMA_FILE = "result.schema.json"
#: The schema of each command's JSON output, by name: file inside :mod:`psdbound.results`.
SCHEMAS = {
    "result": SCHEMA_FILE,
    "overbound": "overbound.schema.json",
    "budget": "budget.schema.json",
    "vpl": "vpl.schema.json",
    "campaign": "campaign.schema.json",
    "cutoff": "cutoff.schema.json",
    "cutoff_map": "cutoff_map.schema.json",
    "validation": "validation.schema.json",
}


@cache
def _schema_text(name: str = "result") -> str:
    if name not in SCHEMAS:
        raise InputError(f"unknown schema {name!r}; choose from {', '.join(SCHEMAS)}")
    return resources.files("psdbound.results").joinpath(SCHEMAS[name]).read_text(encoding="utf-8")


def load_schema(name: str = "result") -> dict[str, Any]:
    """Return a JSON Schema as a new dictionary.

    Parameters
    ----------
    name : str, default "result"
        A key of :data:`SCHEMAS`: ``result`` (``result.json``), ``overbound``,
        ``budget``, ``vpl``, ``campaign``, ``cutoff`` (``cutoff_<name>.json``),
        ``cutoff_map`` or ``validation``.

    Returns
    -------
    dict
        The Draft 2020-12 schema (``$schema``, ``properties``, ...).
    """
    return json.loads(_schema_text(name))


def _validator(name: str = "result") -> Any:
    try:
        import jsonschema
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise ImportError(
            "validating result.json needs the 'jsonschema' package "
            "(pip install 'psdbound[test]' or 'jsonschema>=4')"
        ) from exc
    schema = load_schema(name)
    cls = jsonschema.Draft202012Validator
    cls.check_schema(schema)
    return cls(schema, format_checker=cls.FORMAT_CHECKER)


def schema_errors(document: dict[str, Any], *, schema: str = "result") -> list[str]:
    """Return every schema violation of a document, one line each.

    Parameters
    ----------
    document : dict
        A parsed ``result.json`` (or another command's JSON output).
    schema : str, default "result"
        Which schema (a key of :data:`SCHEMAS`).

    Returns
    -------
    list of str
        ``"<dotted.path>: <message>"`` per violation, sorted by path; empty
        when the document is valid.
    """
    out = []
    for err in _validator(schema).iter_errors(document):
        path = ".".join(str(p) for p in err.absolute_path) or "(top level)"
        out.append(f"{path}: {err.message}")
    return sorted(out)


def validate(document: dict[str, Any], *, schema: str = "result") -> None:
    """Check a document against its schema.

    Parameters
    ----------
    document : dict
        A parsed ``result.json`` (or another command's JSON output).
    schema : str, default "result"
        Which schema (a key of :data:`SCHEMAS`).

    Raises
    ------
    InputError
        If the document violates the schema; the message names the first
        field at fault and how many violations there are.
    """
    errors = schema_errors(document, schema=schema)
    if errors:
        more = f" (and {len(errors) - 1} more)" if len(errors) > 1 else ""
        raise InputError(f"document does not match {SCHEMAS[schema]}: {errors[0]}{more}")
