"""Schema version ``"1"`` of ``result.json``: required fields, writing and checked reading."""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

from psdbound.common import atomic_write_text
from psdbound.errors import InputError
from psdbound.results.jsonfile import COMPACT_SECTIONS, plain_json_text, to_jsonable
from psdbound.results.jsonschema import load_schema

__all__ = [
    "SCHEMA_VERSION",
    "NUMBER_FIELDS",
    "REQUIRED_FIELDS",
    "missing_field",
    "number_problems",
    "get_field",
    "write_document",
    "read_document",
]

SCHEMA_VERSION = "1"


def _required_paths(spec: dict[str, Any], prefix: str = "") -> Iterator[str]:
    """Dotted paths of every field the schema requires, parents before children."""
    for key in spec.get("required", ()):
        yield prefix + key
        yield from _required_paths(spec.get("properties", {}).get(key, {}), f"{prefix}{key}.")


#: Dotted paths every result file must contain: every field ``result.schema.json``
#: requires (its one home), parents before their children.
REQUIRED_FIELDS: tuple[str, ...] = tuple(_required_paths(load_schema("result")))

#: Dotted paths documented as numbers: always finite numbers in a result, never ``null``.
#: The values of ``NULLABLE_WHEN`` may be ``null`` for the method named there.
NUMBER_FIELDS = (
    "bound.sigma_gm_m",
    "bound.tau_s",
    "bound.sigma_wn_m",
    "bound.n_wn_two_sided_m2_hz",
    "bound.dt_s",
    "bound.total_variance_m2",
    "cutoff.f_c_hz",
    "cutoff.tau_c_min",
    "sampling.interval_s",
    "sampling.nyquist_hz",
    "mapping.a",
    "mapping.b",
    "mapping.c_deg",
    "windows.count",
    "windows.total_duration_s",
    "screening.excluded_s",
    "screening.excluded_fraction",
    "screening.multipath_limit_m",
)
#: Number fields that are ``null`` by design for one method (no high-pass for dual-antenna).
NULLABLE_WHEN = {"cutoff.f_c_hz": "DA", "cutoff.tau_c_min": "DA"}


def number_problems(document: dict[str, Any]) -> list[str]:
    """Return the documented number fields that are not finite numbers (``null``, NaN, text).

    Fields absent from the document are not reported (:data:`REQUIRED_FIELDS` is checked
    separately); ``null`` is accepted where :data:`NULLABLE_WHEN` allows it.
    """
    out = []
    for f in NUMBER_FIELDS:
        try:
            v = get_field(document, f)
        except KeyError:
            continue
        if v is None and NULLABLE_WHEN.get(f) == document.get("method"):
            continue
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            out.append(f"'{f}' must be a finite number, got {json.dumps(to_jsonable(v))}")
    return out


def _spec(dotted: str) -> dict[str, Any]:
    """Return the schema entry of a dotted field of ``result.json``."""
    spec: dict[str, Any] = load_schema("result")
    for key in dotted.split("."):
        spec = spec["properties"][key]
    return spec


def _limit(spec: dict[str, Any]) -> tuple[Callable[[Any], bool], str]:
    """Return the test of a schema entry's ``enum`` or lower limit, and what it allows."""
    if "enum" in spec:
        allowed = tuple(spec["enum"])
        return (lambda v: v in allowed), " or ".join(f"'{a}'" for a in allowed)
    if "exclusiveMinimum" in spec:
        lo = spec["exclusiveMinimum"]
        return (lambda v: v > lo), f"> {lo:g}"
    lo = spec["minimum"]
    return (lambda v: v >= lo), f">= {lo:g}"


#: Fields whose values the reader checks beyond their type: (test, what is allowed), from
#: their ``enum`` or lower limit in ``result.schema.json`` (its one home).
_LIMITED: dict[str, tuple[Callable[[Any], bool], str]] = {
    f: _limit(_spec(f)) for f in ("verdict", "bound.sigma_gm_m", "bound.sigma_wn_m", "bound.tau_s")
}


def value_problems(document: dict[str, Any]) -> list[str]:
    """Return the limited fields whose values the schema does not allow (a verdict, a sigma < 0).

    Fields absent or not numbers are left to :func:`missing_field` and
    :func:`number_problems`.
    """
    out = []
    for f, (ok, allowed) in _LIMITED.items():
        try:
            v = get_field(document, f)
            good = bool(ok(v))
        except (KeyError, TypeError):
            continue
        if not good:
            out.append(f"'{f}' must be {allowed}, got {json.dumps(to_jsonable(v))}")
    return out


def get_field(document: dict[str, Any], dotted: str) -> Any:
    """Return ``document[a][b]...`` for ``dotted = "a.b..."``; KeyError if absent."""
    cur: Any = document
    for part in dotted.split("."):
        if not isinstance(cur, dict) or part not in cur:
            raise KeyError(dotted)
        cur = cur[part]
    return cur


def missing_field(
    document: dict[str, Any], required: Sequence[str] = REQUIRED_FIELDS
) -> str | None:
    """Return the first of the required fields the document lacks, or None.

    A field inside an object is required only where that object is not
    ``null``: the schema allows ``null`` for some (``bound.pooled`` of the
    envelope rule).

    Parameters
    ----------
    document : dict
        A result document.
    required : sequence of str, default :data:`REQUIRED_FIELDS`
        Dotted fields, parents before their children.

    Returns
    -------
    str or None
    """
    for f in required:
        parent, _, key = f.rpartition(".")
        try:
            node = get_field(document, parent) if parent else document
        except KeyError:  # its parent is missing: reported as that, earlier in the list
            continue
        if node is not None and not (isinstance(node, dict) and key in node):
            return f
    return None


def write_document(path: str | os.PathLike[str], document: dict[str, Any]) -> Path:
    """Write a result document as JSON, atomically.

    Parameters
    ----------
    path : str or path-like
        Target file (``result.json``).
    document : dict
        The document; numpy values are converted, NaN becomes ``null`` (only
        where the schema allows it: see :data:`NUMBER_FIELDS`).

    Returns
    -------
    Path
        The written path.

    Raises
    ------
    ValueError
        A documented number (:data:`NUMBER_FIELDS`) is NaN, infinite or
        missing its value: a result that looks like a number but is none is
        never written (an internal error: the stages must not produce it).
    """
    data = to_jsonable(document)
    bad = number_problems(data)
    if bad:
        raise ValueError(
            "refusing to write a result whose documented numbers are not numbers: " + ", ".join(bad)
        )
    return atomic_write_text(path, plain_json_text(data, compact=COMPACT_SECTIONS))


def read_document(
    path: str | os.PathLike[str], *, required: Sequence[str] = REQUIRED_FIELDS
) -> dict[str, Any]:
    """Read and check a result file.

    Parameters
    ----------
    path : str or path-like
        A ``result.json`` written by psdbound.
    required : sequence of str, default :data:`REQUIRED_FIELDS`
        Dotted fields it must hold (parents before children); a reader that
        needs only some (the bound export) names those.

    Returns
    -------
    dict
        The document.

    Raises
    ------
    InputError
        Missing file, invalid JSON, wrong schema version or a missing field
        (the message names the file and the field).
    """
    p = Path(path)
    if not p.is_file():
        raise InputError("result file not found", path=p)
    try:
        data = json.loads(p.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"not a JSON result file: {exc}", path=p) from None
    if not isinstance(data, dict):
        raise InputError("not a psdbound result (top level is not an object)", path=p)
    version = data.get("schema_version")
    if version is None:
        raise InputError(
            "not a psdbound result: it has no schema_version (give the result.json a "
            "psdbound command wrote)",
            path=p,
        )
    if version != SCHEMA_VERSION:
        raise InputError(
            f"result schema version {version!r} is not supported (expected {SCHEMA_VERSION!r})",
            path=p,
        )
    missing = missing_field(data, required)
    if missing is not None:
        raise InputError(
            f"result file lacks the field {missing!r}, which schema version {SCHEMA_VERSION} "
            "requires (a file written by an older psdbound, or edited: fit again)",
            path=p,
        )
    bad = number_problems(data)
    if bad:
        raise InputError(f"no number where the schema documents one: {bad[0]}", path=p)
    bad = value_problems(data)
    if bad:
        raise InputError(f"a value the schema does not allow: {bad[0]} (edited?)", path=p)
    return data
