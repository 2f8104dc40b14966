"""The one check of a number option (common.options.Number), as the library's entries use it."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.common.options import Number, OptionError
from psdbound.spectra.models import INTERVAL_S


@pytest.mark.parametrize("value", [0.0, -1.0, float("nan"), float("inf"), "1", None, True])
def test_an_interval_must_be_a_finite_positive_number(value):
    with pytest.raises(OptionError, match=r"dt_s must be a number > 0 s, got "):
        INTERVAL_S("dt_s", value)


@pytest.mark.parametrize("value", [np.True_, np.array(True)])
def test_numpy_booleans_are_not_numbers(value):
    with pytest.raises(OptionError, match="must be a number"):
        Number()("x", value)


@pytest.mark.parametrize("value", [1, 2.5, np.float32(30.0), np.int64(1), np.float64(0.5)])
def test_numpy_and_python_numbers_become_floats(value):
    out = INTERVAL_S("dt_s", value)
    assert type(out) is float and out == float(value)
