"""The arcs' running median against scipy.ndimage.median_filter (mode "mirror")."""

import numpy as np
import pytest
from scipy.ndimage import median_filter

from psdbound.arcs.find import _NOISE_WINDOW, _SLIP_WINDOW, _running_median

LENGTHS = [1, 2, 3, 4, 5, 6, 7, 10, 11, 12, 30, 60, 61, 62, 63, 200, 1001]


def _sizes(n: int) -> set[int]:
    """The window sizes detect_slips uses on n samples, and others within one reflection."""
    used = {min(_SLIP_WINDOW, n | 1), min(_NOISE_WINDOW, n | 1)}
    return used | {s for s in (1, 2, 3, 4, 5, 8, 11, 60, 61) if s // 2 < n}


@pytest.mark.parametrize("n", LENGTHS)
def test_running_median_equals_scipy_mirror(n):
    rng = np.random.default_rng(20240531 + n)
    for trial in range(5):
        x = rng.normal(size=n) * 10.0 ** rng.integers(-3, 3)
        if trial == 1 and n > 3:
            x[rng.integers(0, n, n // 2)] = x[0]  # ties
        if trial == 2:
            x = np.round(x, 1)  # many ties
        for size in sorted(_sizes(n)):
            got = _running_median(x, size)
            want = median_filter(x, size=size, mode="mirror")
            assert got.dtype == want.dtype and got.shape == want.shape
            np.testing.assert_array_equal(got, want, err_msg=f"n={n} size={size}")


def test_sizes_cover_series_shorter_than_the_windows():
    # the lengths above include series shorter than both windows, where the size is n | 1
    short = [n for n in LENGTHS if n < _SLIP_WINDOW]
    assert short and all(min(_SLIP_WINDOW, n | 1) == n | 1 for n in short)
    assert any(n < _NOISE_WINDOW <= m for n in LENGTHS for m in LENGTHS)


def test_numpy_path_is_the_one_compared_and_long_arcs_agree():
    from psdbound.arcs.find import _SCIPY_MEDIAN_FROM

    assert max(LENGTHS) < _SCIPY_MEDIAN_FROM  # the cross-check above runs the numpy code
    x = np.random.default_rng(7).normal(size=_SCIPY_MEDIAN_FROM + 1)
    np.testing.assert_array_equal(
        _running_median(x, _SLIP_WINDOW), median_filter(x, size=_SLIP_WINDOW, mode="mirror")
    )
