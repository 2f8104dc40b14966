"""The one JSON writer of psdbound: every command's JSON files go through it.

One NaN policy: JSON has no NaN or infinity, so every non-finite float is
written as ``null`` (:func:`to_jsonable`); NumPy arrays and scalars, tuples
and paths become plain JSON data. One layout: indented, except the sections
named in ``compact`` (plot data, read by programs, not by eye), which the C
encoder writes on one line. Files are written atomically.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.common import atomic_write_text

__all__ = ["COMPACT_SECTIONS", "json_text", "plain_json_text", "to_jsonable", "write_json"]

_PLAIN = (int, str, bool, type(None))
_NUMBERS = frozenset({float, int})

#: Top-level sections of a result document written on one line (its plot data).
COMPACT_SECTIONS = frozenset({"figures"})


def _finite_or_none(x: float) -> float | None:
    return x if math.isfinite(x) else None


def _finite_numbers(seq: list[Any] | tuple[Any, ...]) -> bool:
    """Whether a sequence holds only Python floats and ints, all finite (nothing to convert).

    Checked in C (the set of the element types, then one array of the
    values) for the long float lists of a result's plot data, which the
    element-by-element conversion walks slowly.
    """
    if len(seq) < 16 or not set(map(type, seq)) <= _NUMBERS:
        return False
    return bool(np.isfinite(np.array(seq, dtype=np.float64)).all())


def _plain_sequence(seq: list[Any] | tuple[Any, ...]) -> list[Any]:
    """Return a list or tuple as a JSON list (its elements converted)."""
    if _finite_numbers(seq):
        return list(seq)
    return [
        v if type(v) in _PLAIN else _finite_or_none(v) if type(v) is float else to_jsonable(v)
        for v in seq
    ]


def to_jsonable(obj: Any) -> Any:
    """Convert numpy arrays/scalars, tuples and paths to plain JSON data.

    Non-finite floats become ``None`` (JSON has no NaN or infinity).
    """
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return _plain_sequence(obj)
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "biu":
            return obj.tolist()
        if obj.dtype.kind == "f":
            bad = ~np.isfinite(obj)
            if not bad.any():
                return obj.tolist()
            out = obj.astype(object)
            out[bad] = None
            return out.tolist()
        return to_jsonable(obj.tolist())
    if isinstance(obj, np.generic):
        return to_jsonable(obj.item())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    return obj


def json_text(obj: Any, *, compact: frozenset[str] | set[str] = frozenset()) -> str:
    """Return the JSON text of a document: indented, the ``compact`` sections on one line.

    Indented JSON goes through Python's slow encoder; a result document's
    ``figures`` section (about two thirds of a station day's file) written
    compactly by the C encoder halves the time and cuts the size by a third.
    The text parses to the same data.

    Parameters
    ----------
    obj : dict or any JSON-able value
        The document (converted by :func:`to_jsonable`: non-finite floats
        become ``null``).
    compact : set of str, optional
        Top-level keys whose values are written on one line.

    Returns
    -------
    str
        The JSON text, ending with a newline.
    """
    return plain_json_text(to_jsonable(obj), compact=compact)


def plain_json_text(data: Any, *, compact: frozenset[str] | set[str] = frozenset()) -> str:
    """:func:`json_text` of data that is plain JSON already (:func:`to_jsonable` applied).

    Parameters
    ----------
    data : dict or any plain JSON value
        No numpy value, no non-finite float.
    compact : set of str, optional
        Top-level keys whose values are written on one line.

    Returns
    -------
    str
        The JSON text, ending with a newline.
    """
    if not isinstance(data, dict) or not compact:
        return json.dumps(data, indent=1, allow_nan=False) + "\n"
    parts = []
    for key, value in data.items():
        if key in compact:
            body = json.dumps(value, allow_nan=False, separators=(",", ":"))
        else:
            body = json.dumps(value, indent=1, allow_nan=False).replace("\n", "\n ")
        parts.append(f" {json.dumps(key)}: {body}")
    return "{\n" + ",\n".join(parts) + "\n}\n"


def write_json(
    path: str | os.PathLike[str], obj: Any, *, compact: frozenset[str] | set[str] = frozenset()
) -> Path:
    """Write a document as JSON (:func:`json_text`), atomically; return its path.

    Parameters
    ----------
    path : str or path-like
        Target file.
    obj : dict or any JSON-able value
        The document.
    compact : set of str, optional
        Top-level keys written on one line.

    Returns
    -------
    Path
    """
    return Path(atomic_write_text(path, json_text(obj, compact=compact)))
