"""The one JSON writer: its NaN policy and its conversions, on short and long sequences."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from psdbound.results.jsonfile import COMPACT_SECTIONS, json_text, plain_json_text, to_jsonable


@pytest.mark.parametrize("n", [3, 16, 500])
def test_non_finite_floats_become_null_in_lists_of_any_length(n: int) -> None:
    values = [0.5 * k for k in range(n)]
    values[1], values[-1] = math.nan, -math.inf
    got = to_jsonable({"a": values, "b": tuple(values)})
    assert got["a"][1] is None and got["a"][-1] is None and got["b"][-1] is None
    assert got["a"][2:-1] == values[2:-1]


@pytest.mark.parametrize("n", [3, 500])
def test_numpy_scalars_paths_and_nesting_are_converted(n: int) -> None:
    mixed = [1.5] * n + [np.float32(2.5), np.int64(3), Path("x/y"), [np.nan], True]
    got = to_jsonable(mixed)
    assert got[n:] == [2.5, 3, "x/y", [None], True]
    assert type(got[n]) is float and type(got[n + 1]) is int
    json.dumps(got, allow_nan=False)  # plain JSON: no numpy value, no NaN


def test_long_finite_number_lists_are_kept_as_they_are() -> None:
    values = [0.1 * k for k in range(1000)] + [7]
    got = to_jsonable((values,))
    assert got == [values] and type(got[0][-1]) is int


def test_plain_text_equals_the_converting_text() -> None:
    doc = {"x": np.array([1.0, np.nan]), "figures": {"f": list(np.linspace(0, 1, 40))}}
    assert plain_json_text(to_jsonable(doc), compact=COMPACT_SECTIONS) == json_text(
        doc, compact=COMPACT_SECTIONS
    )
    assert json.loads(json_text(doc))["x"] == [1.0, None]
