"""Public entry points: See Also, References and an Examples block that runs."""

from __future__ import annotations

import doctest
import importlib
import inspect

import pytest
from numpydoc.docscrape import ClassDoc, FunctionDoc

ENTRY_POINTS = [
    "psdbound:fit",
    "psdbound:load",
    "psdbound.io:read_obs",
    "psdbound.io:read_orbit",
    "psdbound.arcs:find_arcs",
    "psdbound.isolation:isolate_dual_frequency",
    "psdbound.isolation:isolate_dual_antenna",
    "psdbound.isolation:isolate_code_multipath",
    "psdbound.isolation:level_shifts",
    "psdbound.stationarity:find_stationary_windows",
    "psdbound.spectra:estimate_psd",
    "psdbound.spectra:BoundModel",
    "psdbound.kalman:GaussMarkovBound",
    "psdbound.simulate:simulate",
]


def _get(entry):
    module, name = entry.split(":")
    mod = importlib.import_module(module)
    return mod, getattr(mod, name)


@pytest.mark.slow
@pytest.mark.parametrize("entry", ENTRY_POINTS)
def test_entry_point_docstring_is_complete_and_its_examples_run(entry):
    mod, obj = _get(entry)
    doc = ClassDoc(obj) if inspect.isclass(obj) else FunctionDoc(obj)
    assert doc["See Also"], f"{entry}: no See Also"
    assert doc["References"], f"{entry}: no References"
    examples = "\n".join(doc["Examples"])
    assert ">>>" in examples and "+SKIP" not in examples, f"{entry}: no runnable Examples"
    tests = doctest.DocTestFinder(recurse=False).find(obj, obj.__name__, globs=dict(vars(mod)))
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for t in tests:
        runner.run(t)
    result = runner.summarize(verbose=False)
    assert result.attempted >= 2 and result.failed == 0, entry
