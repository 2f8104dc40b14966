"""Calibration and power of the spectral-homogeneity stationarity test (correlated data)."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.errors import InputError
from psdbound.simulate import gauss_markov
from psdbound.stationarity import test_spectral_homogeneity, test_stationarity

N = 600  # 10-min windows at 1 Hz
TRIALS = 400
ALPHA = 0.05
MC_SD = np.sqrt(ALPHA * (1 - ALPHA) / TRIALS)


def _gm(rng, n, tau_s, sigma=1.0):
    return gauss_markov(n, sigma, tau_s, 1.0, rng, 1)[:, 0]


def _stationary(rng):
    return _gm(rng, N, 30.0) + 0.3 * rng.standard_normal(N)


def _rate(make, test, seed):
    rng = np.random.default_rng(seed)
    return float(np.mean([not test(make(rng)).stationary for _ in range(TRIALS)]))


def test_level_holds_on_correlated_stationary_data():
    rate = _rate(_stationary, test_spectral_homogeneity, 1)
    print(f"spectral test rejects {100 * rate:.1f} % of stationary windows (level 5 %)")
    assert rate <= ALPHA + 2 * MC_SD


def test_thesis_tests_reject_correlated_stationary_data():
    # the evidence for the new test: Levene then K-S assume independent samples
    rate = _rate(_stationary, test_stationarity, 2)
    print(f"Levene + K-S reject {100 * rate:.1f} % of stationary windows (level 5 %)")
    assert rate > 0.5


def test_detects_a_doubling_of_the_variance():
    def step(rng):
        x = _stationary(rng)
        x[N // 2 :] *= np.sqrt(2.0)
        return x

    assert _rate(step, test_spectral_homogeneity, 3) >= 0.90


def test_detects_a_change_of_correlation_time():
    def change(rng):
        x = np.r_[_gm(rng, N // 2, 30.0), _gm(rng, N - N // 2, 300.0)]
        return x + 0.3 * rng.standard_normal(N)

    assert _rate(change, test_spectral_homogeneity, 4) >= 0.90


def test_result_fields_and_errors():
    r = test_spectral_homogeneity(np.random.default_rng(5).standard_normal(N), n_parts=2, nw=4)
    assert r.dof == r.n_frequencies * (r.n_parts - 1) and 0 <= r.p_value <= 1
    with pytest.raises(InputError, match="too short"):
        test_spectral_homogeneity(np.zeros(20))
    with pytest.raises(InputError, match="n_parts"):
        test_spectral_homogeneity(np.zeros(600), n_parts=1)


def test_windowing_with_the_spectral_test_covers_stationary_arcs():
    from psdbound.isolation import MultipathSeries
    from psdbound.stationarity import ElevationMapping, find_stationary_windows

    rng = np.random.default_rng(6)
    arcs = []
    for a in range(3):
        n = 2 * 3600
        t = 1e6 + a * 1e5 + np.arange(n, dtype=float)
        v = 0.003 * _gm(rng, n, 30.0) + 0.001 * rng.standard_normal(n)
        arcs.append(
            {"sats": f"G{a + 1:02d}", "t_gps_s": t, "value_m": v, "elevation_deg": np.full(n, 60.0)}
        )
    s = MultipathSeries.from_arcs(
        "DF", arcs, signals=("L1C", "L2W"), scaling=2**-0.5, interval_s=1.0
    )
    flat = ElevationMapping(1.0, 0.0, 10.0, "fixed")
    spectral = find_stationary_windows(s, mapping=flat, test="spectral")
    thesis = find_stationary_windows(s, mapping=flat, test="thesis")
    total_s = s.t_gps_s.size * s.interval_s
    print(
        f"never stationary: spectral {100 * spectral.uncovered_s / total_s:.1f} %, "
        f"thesis {100 * thesis.uncovered_s / total_s:.1f} %"
    )
    assert spectral.uncovered_s <= 0.05 * total_s < thesis.uncovered_s
    assert spectral.params["test"] == "spectral"
