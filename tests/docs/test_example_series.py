"""The worked example of bound_series on known truths runs as documented (no real data)."""

from __future__ import annotations

import doctest
from pathlib import Path

PAGE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "any_error_series.rst"


def test_any_error_series_example_runs():
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testfile(str(PAGE), module_relative=False, optionflags=flags, verbose=False)
    assert result.attempted >= 25, result
    assert result.failed == 0, result
