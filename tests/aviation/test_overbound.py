"""Gaussian overbounds: closed forms (Gaussian, Student-t, mixture), bins and bad input."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from psdbound.aviation import (
    cdf_overbound_sigma,
    overbound_by_elevation,
    two_step_overbound,
)
from psdbound.errors import InputError

N = 100_000
P = (np.arange(1, N + 1) - 0.5) / N  # Hazen positions: "exact" quantile samples


def _step_bound(q_lo: float) -> float:
    """Closed form for quantile samples whose extreme tail dominates.

    The lowest sample is F^-1(0.5/n) and the empirical CDF there is 1/n, so
    the bound needs Phi(x_(1) / s) >= 1/n: s = |F^-1(0.5/n)| / Phi^-1(1 - 1/n).
    """
    return abs(q_lo) / stats.norm.isf(1.0 / N)


def test_exact_gaussian_quantiles_give_the_step_closed_form():
    x = 2.0 * stats.norm.ppf(P)
    expected = _step_bound(2.0 * stats.norm.ppf(0.5 / N))  # 2 * 1.0357 for n = 1e5
    for sigma in (cdf_overbound_sigma(x), two_step_overbound(x)[1]):
        assert sigma == pytest.approx(expected, rel=1e-9)
    assert expected / 2.0 == pytest.approx(1.0357, abs=1e-4)


def test_random_gaussian_inflation_near_one():
    rng = np.random.default_rng(7)
    x = rng.normal(0.3, 1.5, N)
    res = overbound_by_elevation(x, unit="m", method="two_step")
    (b,) = res.bins
    assert 1.0 <= b.inflation < 1.10
    assert b.bias == pytest.approx(0.3, abs=0.02)  # two-step: the median
    # a zero-mean CDF bound must absorb the 0.3 m offset: larger sigma
    assert cdf_overbound_sigma(x) > b.sigma
    # the paired bound with b >= |median| recovers about the sample sigma
    assert cdf_overbound_sigma(x, bias=0.35) == pytest.approx(1.5, rel=0.08)


def test_student_t_tail_dominates():
    infl = []
    for nu in (3, 5, 10):
        x = stats.t.ppf(P, nu)
        expected = _step_bound(stats.t.ppf(0.5 / N, nu))
        sigma = cdf_overbound_sigma(x)
        assert sigma == pytest.approx(expected, rel=1e-9)
        infl.append(sigma / x.std(ddof=1))
    # heavier tails (smaller nu) need more inflation; all above 1
    assert infl[0] > infl[1] > infl[2] > 1.2


def test_student_t_inflation_grows_with_sample_size():
    infl = []
    for n in (1_000, 10_000, 100_000):
        p = (np.arange(1, n + 1) - 0.5) / n
        x = stats.t.ppf(p, 4)
        infl.append(cdf_overbound_sigma(x) / x.std(ddof=1))
    assert infl[0] < infl[1] < infl[2]


def test_mixture_tail_approaches_wide_component():
    # 0.9 N(0, 1) + 0.1 N(0, 3^2): std sqrt(1.8); far tails follow the 3-sigma part
    w, s1, s2 = 0.1, 1.0, 3.0
    xs = np.linspace(-30, 30, 600_001)
    cdf = (1 - w) * stats.norm.cdf(xs / s1) + w * stats.norm.cdf(xs / s2)
    x = np.interp(P, cdf, xs)
    sigma = cdf_overbound_sigma(x)
    assert sigma == pytest.approx(_step_bound(x[0]), rel=1e-6)
    assert 2.5 < sigma < 3.0
    assert sigma / np.sqrt((1 - w) * s1**2 + w * s2**2) > 1.8


def test_bound_holds_at_every_sample_point():
    rng = np.random.default_rng(3)
    x = np.sort(rng.standard_t(4, 5000))
    n = x.size
    m, s = two_step_overbound(x, min_abs_z=0.25)
    ecdf_hi = np.arange(1, n + 1) / n
    ecdf_lo = np.arange(0, n) / n
    g = stats.norm.cdf((x - m) / s)
    core = np.abs(stats.norm.ppf(np.minimum(ecdf_hi, 1 - ecdf_lo))) < 0.25
    left, right = (x < m) & ~core, (x > m) & ~core
    assert (g[left] >= ecdf_hi[left] - 1e-12).all()
    assert (g[right] <= ecdf_lo[right] + 1e-12).all()


def test_core_without_exclusion_is_unbounded():
    x = np.array([-2.0, -1.0, 1.0, 2.0])
    assert cdf_overbound_sigma(x, min_abs_z=0.0) == np.inf


def test_elevation_bins_and_summary():
    rng = np.random.default_rng(11)
    el = rng.uniform(5, 90, 40_000)
    x = rng.standard_normal(el.size) * (0.2 + 0.8 * np.exp(-el / 15))
    res = overbound_by_elevation(x, el, edges_deg=(5, 30, 60, 90), method="cdf")
    assert [b.label for b in res.bins] == ["[5, 30) deg", "[30, 60) deg", "[60, 90) deg"]
    assert res.counts.sum() == el.size
    assert (res.sigma[:-1] > res.sigma[1:]).all()  # noisier at low elevation
    # sigma varies inside the wide low bins: a scale mixture, heavier tails than
    # its std; the 60-90 deg bin is nearly homogeneous
    assert (res.inflation[:2] > 1.2).all()
    assert 1.0 < res.inflation[2] < 1.2
    text = res.summary()
    assert "inflation" in text and "[30, 60) deg" in text
    d = res.to_dict()
    assert d["bins"][0]["elevation_deg"] == [5.0, 30.0] and d["method"] == "cdf"


def test_too_few_samples_names_the_bin():
    el = np.r_[np.full(500, 10.0), np.full(20, 70.0)]
    with pytest.raises(InputError, match=r"elevation bin \[60, 90\) deg: 20 sample"):
        overbound_by_elevation(np.zeros(el.size) + np.arange(el.size), el)


def test_nan_names_the_bin():
    el = np.r_[np.full(500, 10.0), np.full(500, 50.0)]
    x = np.random.default_rng(0).standard_normal(el.size)
    x[700] = np.nan
    with pytest.raises(InputError, match=r"elevation bin \[45, 60\) deg: 1 sample\(s\) are NaN"):
        overbound_by_elevation(x, el)


def test_bad_method_and_lengths():
    with pytest.raises(InputError, match="method"):
        overbound_by_elevation(np.zeros(200), method="qq")
    with pytest.raises(InputError, match="elevations"):
        overbound_by_elevation(np.zeros(200), np.zeros(10))
