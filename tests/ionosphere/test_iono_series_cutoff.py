"""Ionosphere cutoff of one series: envelope and criteria (psdbound.ionosphere, issue #4).

Must-show: a synthetic sum of sinusoids of known amplitudes, replicated over
7 sidereal days like the simulated delays: the envelope lies on or above
every local maximum, f_c lands where the 40 dB line is crossed (within one
grid step), and equals the value the known amplitudes give. The
Lomb-Scargle periodogram itself is tested in tests/periodogram; orbits,
slant delays, batch runs and the command line in the other files here.
"""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError
from psdbound.ionosphere import (
    fit_envelope,
    local_maxima,
    series_cutoff,
)

DT_S = 12.0
N_DAY = int(np.ceil(SIDEREAL_DAY_S / DT_S))  # 7181 epochs in one sidereal day

LS_METHODS = [pytest.param("gridfft", id="gridfft"), pytest.param("astropy", id="astropy")]
ENV_METHODS = [pytest.param("quantreg", id="quantreg"), pytest.param("linprog", id="linprog")]


# --------------------------------------------------------------------------- synthetic


def synthetic_series(seed: int, alpha: float = 1.0, noise_m: float = 1e-7):
    """Sinusoids at harmonics m / P (m = 1 .. ~3300), amplitude A0 / m^alpha, + tiny noise.

    Returns times (s), values (m), harmonic numbers and amplitudes.
    """
    rng = np.random.default_rng(seed)
    t = DT_S * np.arange(N_DAY)
    m = np.unique(np.round(np.geomspace(1, 3300, 60)).astype(int))
    amp = 1.0 / m**alpha
    phase = rng.uniform(0, 2 * np.pi, m.size)
    y = (
        amp[:, None] * np.cos(2 * np.pi * m[:, None] * t[None, :] / SIDEREAL_DAY_S + phase[:, None])
    ).sum(axis=0)
    y += rng.normal(0.0, noise_m, t.size)
    return t, y, m, amp


@pytest.mark.parametrize("env_method", ENV_METHODS)
@pytest.mark.parametrize("ls_method", LS_METHODS)
@pytest.mark.parametrize("seed", [1, 2])
def test_synthetic_sinusoids_envelope_and_40db_crossing(seed, ls_method, env_method):
    t, y, m, amp = synthetic_series(seed)
    r = series_cutoff(
        t, y, ls_method=ls_method, envelope_method=env_method, reference="psd", keep_spectrum=True
    )
    f, p = r.frequency_hz, r.psd_m2_hz
    # the periodogram peak is the m = 1 line, with the LS "psd" height N A^2 / 4 (one-sided x 2 dt)
    n_total = 7 * N_DAY
    assert r.peak_hz == pytest.approx(1 / SIDEREAL_DAY_S, rel=1e-3)
    assert r.peak_psd_m2_hz == pytest.approx(2 * DT_S * n_total * amp[0] ** 2 / 4, rel=1e-3)
    # envelope on or above every local maximum
    i = local_maxima(p)
    assert i.size > 1000
    assert np.all(r.envelope(f[i]) >= p[i] * (1 - 1e-9))
    # f_c where the 40 dB line is crossed, within one grid step
    thr = r.peak_psd_m2_hz / 1e4
    assert r.threshold_m2_hz == pytest.approx(thr)
    env = r.envelope(f)
    j = np.searchsorted(f, r.f_c_hz) - 1
    assert f[j] <= r.f_c_hz <= f[j + 1]
    assert env[j] >= thr * (1 - 1e-9) and env[j + 1] < thr
    assert np.all(env[j + 1 :] < thr)  # and stays below
    assert r.envelope(r.f_c_hz) == pytest.approx(thr, rel=1e-6)
    # known amplitudes: line power ~ m^-2, 40 dB below the m = 1 line at m = 100
    assert r.f_c_hz == pytest.approx(100 / SIDEREAL_DAY_S, rel=0.08)
    assert r.reached


def test_synthetic_steeper_spectrum_moves_cutoff_down():
    t, y, *_ = synthetic_series(3, alpha=2.0)
    r = series_cutoff(t, y, reference="psd")
    # line power ~ m^-4: 40 dB below the fundamental at m = 10
    assert r.f_c_hz == pytest.approx(10 / SIDEREAL_DAY_S, rel=0.15)


def test_relative_criterion_is_scale_invariant_and_absolute_is_not():
    t, y, *_ = synthetic_series(4)
    a = series_cutoff(t, y)
    b = series_cutoff(t, 10.0 * y)
    assert b.f_c_hz == pytest.approx(a.f_c_hz, rel=1e-9)
    va = series_cutoff(t, y, criterion="absolute", variance_m2=1e-4)
    vb = series_cutoff(t, 10.0 * y, criterion="absolute", variance_m2=1e-4)
    assert vb.f_c_hz > va.f_c_hz
    # the residual above f_c is the allowance
    assert va.residual_m2 == pytest.approx(1e-4, rel=1e-6)


def test_one_day_window_starts_in_a_gap_and_drops_short_arcs():
    from psdbound.ionosphere import one_day_series

    t = DT_S * np.arange(int((SIDEREAL_DAY_S + 12 * 3600) / DT_S))
    phase = np.mod(t, SIDEREAL_DAY_S) / 3600.0
    visible = (phase >= 22.0) | (phase < 3.0) | ((phase >= 10.0) & (phase < 10.2))
    y = np.where(visible, 1.0 + t / 1e5, np.nan)
    tw, yw = one_day_series(t, y)
    assert 3.0 <= tw[0] / 3600.0 and tw[-1] - tw[0] < SIDEREAL_DAY_S
    # one arc, the pass across midnight, unbroken; the 12-min arc is dropped
    assert np.all(np.diff(tw) == DT_S)
    assert tw[-1] - tw[0] == pytest.approx(SIDEREAL_DAY_S - 19 * 3600.0, abs=2 * DT_S)
    np.testing.assert_array_equal(yw, 1.0 + tw / 1e5)
    t_all, y_all = one_day_series(t, y, min_arc_s=0)
    assert t_all.size == tw.size + int(0.2 * 3600 / DT_S)


# --------------------------------------------------------------------------- envelope


@pytest.mark.parametrize("method", ["quantreg", "linprog"])
@pytest.mark.parametrize("degree", [2, 3, 5])
def test_envelope_covers_all_local_maxima_of_random_spectra(method, degree):
    rng = np.random.default_rng(10 + degree)
    f = np.linspace(1e-5, 4e-2, 5000)
    p = 1e3 * (f / 1e-5) ** -1.7 * rng.exponential(1.0, f.size)
    env = fit_envelope(f, p, degree=degree, method=method)
    i = local_maxima(p)
    assert np.all(env(f[i]) >= p[i] * (1 - 1e-9))
    assert env.shift_dex >= 0
    assert env.n_fitted < env.n_maxima
    # close: the envelope is no more than ~1 decade above the highest maxima locally
    assert np.median(env.log10(f[i]) - np.log10(p[i])) < 1.5


def test_local_maxima_definition():
    assert local_maxima([0, 1, 0, 2, 2, 1, 3]).tolist() == [1, 3]
    assert local_maxima([1, 2]).size == 0


def test_envelope_bad_input():
    with pytest.raises(InputError, match="unknown envelope method"):
        fit_envelope(np.arange(1, 10.0), np.ones(9), method="spline")
    with pytest.raises(InputError, match="local maxima"):
        fit_envelope(np.arange(1, 10.0), np.arange(1, 10.0))
