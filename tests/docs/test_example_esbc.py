"""The worked examples on the ESBC day run as documented (real data)."""

from __future__ import annotations

import doctest
from pathlib import Path

import pytest
from conftest import ESBC_NAV, ESBC_OBS, shared_file

EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"
PAGE = EXAMPLES / "kf_araim_esbc.rst"


@pytest.mark.realdata
@pytest.mark.slow
def test_worked_example_runs(monkeypatch):
    folder = Path(shared_file(ESBC_OBS)).parent
    assert Path(shared_file(ESBC_NAV)).parent == folder
    monkeypatch.chdir(folder)  # the page names the files as a user in their folder would
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testfile(str(PAGE), module_relative=False, optionflags=flags)
    assert result.attempted > 20 and result.failed == 0


@pytest.mark.realdata
@pytest.mark.slow
def test_code_multipath_example_runs(monkeypatch):
    folder = Path(shared_file(ESBC_OBS)).parent
    monkeypatch.chdir(folder)
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testfile(
        str(EXAMPLES / "code_multipath_esbc.rst"), module_relative=False, optionflags=flags
    )
    assert result.attempted >= 12 and result.failed == 0
