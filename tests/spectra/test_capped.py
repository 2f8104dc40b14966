"""A window's upper deviation below its data: the f^-2 cap (spectra.pooled.capped_below_data)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate
from scipy.signal import lfilter

import psdbound
from psdbound.spectra.bands import BandSpectra
from psdbound.spectra.models import gm_psd_sampled
from psdbound.spectra.pooled import capped_below_data


def _bands(have: np.ndarray) -> BandSpectra:
    edges = np.geomspace(1e-3, 1e-1, have.shape[1] + 1)
    psd = np.where(have, 1.0, np.nan)
    return BandSpectra(edges, np.sqrt(edges[:-1] * edges[1:]), psd, np.where(have, 10.0, 0.0))


def test_the_cap_in_closed_form() -> None:
    have = np.array([[True] * 6, [False, False, True, True, True, True]])
    gb = _bands(have)
    own = np.full((2, 6), 5.0)
    own[:, 2:] = 0.3
    mean_up = np.array([4.0, 3.0, 2.0, 1.5, 1.0, 0.5])
    out = capped_below_data(own, gb, mean_up)
    np.testing.assert_array_equal(out[0], own[0])  # data in every band: unchanged
    lo, r = gb.edges_hz[:-1], gb.edges_hz[1:] / gb.edges_hz[:-1]
    b = np.arange(2)
    cap = (
        0.3
        + np.log(2.0 / mean_up[b])
        + np.log(r[2])
        + 2 * np.log(lo[2] / lo[b])
        - 0.5 * np.log(r[b])
    )
    np.testing.assert_allclose(out[1, :2], np.minimum(5.0, cap))
    np.testing.assert_array_equal(out[1, 2:], own[1, 2:])


def test_a_smaller_extrapolation_is_kept() -> None:
    have = np.array([[False, True, True]])
    gb = _bands(have)
    own = np.array([[0.1, 0.2, 0.2]])
    out = capped_below_data(own, gb, np.ones(3))
    assert out[0, 0] == 0.1


@pytest.mark.parametrize("seed", range(6))
def test_the_premise_holds_for_gauss_markov_and_white_sums(seed: int) -> None:
    """``S(f) <= r_j mean_j (l_j / f)^2`` below band ``j``, for exact band means of sampled sums."""
    rng = np.random.default_rng(seed)
    dt = 1.0
    terms = [(rng.uniform(0.5, 5.0), float(np.exp(rng.uniform(0.0, 7.0)))) for _ in range(3)]
    white = rng.uniform(0.0, 3.0)

    def psd(f):
        return sum(gm_psd_sampled(np.atleast_1d(f), s, t, dt) for s, t in terms) + 2 * dt * white

    edges = np.geomspace(1e-4, 0.5, 40)
    for j in range(5, 39):
        l_j, h_j = edges[j], edges[j + 1]
        mean_j = integrate.quad(lambda f: psd(f)[0], l_j, h_j, limit=200)[0] / (h_j - l_j)
        f = np.geomspace(1e-5, l_j, 50)
        assert np.all(psd(f) <= (h_j / l_j) * mean_j * (l_j / f) ** 2 * (1 + 1e-9))


def _gm(rng: np.random.Generator, n: int, sigma: float, tau: float) -> np.ndarray:
    phi = np.exp(-1.0 / tau)
    e = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    e[0] = rng.normal(0.0, sigma)
    return lfilter([1.0], [1.0, -phi], e)


def test_a_steep_short_window_no_longer_sets_an_absurd_limit() -> None:
    """15 windows of 3 mm / 30 s (5-60 min) and one 400-s window of 20 mm / 900 s, at 1 s.

    Its tilt, extrapolated from 0.0125 Hz to f_min (0.0017 Hz), put its group's limit 26 dB
    above every window there and the bound at 59 mm (41 times the slow truth at its
    closest); capped, 28 mm, and the slow truth still covered.
    """
    rng = np.random.default_rng(3)
    xs = [
        _gm(rng, int(n), 3e-3, 30.0) + rng.normal(0.0, 1e-3, int(n))
        for n in rng.uniform(300, 3600, 15)
    ]
    xs.append(_gm(rng, 400, 2e-2, 900.0))
    res = psdbound.bound_series(xs, 1.0)
    f = np.geomspace(res.f_min_hz, 0.5, 300)
    ratio = res.bound.sampled_psd(f) / gm_psd_sampled(f, 2e-2, 900.0, 1.0)
    assert ratio.min() >= 1.0
    assert res.bound.sigma_gm_m < 0.035
