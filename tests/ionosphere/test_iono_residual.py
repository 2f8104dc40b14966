"""The residual (time-domain) cutoff criterion (issue #16).

Must-show:

* closed form: a synthetic slant delay with a known spectrum (a metre-level
  once-per-sidereal-day term plus a centimetre sinusoid at 0.5 mHz), on
  realistic satellite passes, gives the cutoff the analytic steady-state
  response of the fit's filter predicts, within 10 %;
* leakage: that cutoff does not depend on the pass length beyond a minimum,
  while the 40 dB Lomb-Scargle criterion on the same signal moves with the
  passes (its 40 dB point is set by the windows, not by the signal);
* the batched filtering is the fit's :meth:`HighPass.apply`, sample for sample.
"""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError
from psdbound.io.geometry import geodetic_to_ecef, satellite_azel
from psdbound.ionosphere import (
    nominal_constellation,
    one_day_series,
    residual_cutoff,
    residual_cutoffs,
    residual_rms,
    residual_threshold_m,
    series_cutoff,
)
from psdbound.ionosphere.residual import highpass_arcs, split_arcs
from psdbound.isolation import HighPass

DT_S = 30.0
F0_HZ = 5e-4
A0_M = 0.01
THR_M = 1e-5


def analytic_cutoff(thr_m: float, amp_m: float, f0_hz: float, order: int = 4) -> float:
    """f_c at which the zero-phase Butterworth leaves thr_m RMS of a sinusoid (steady state).

    The applied response is |H|^2 = x^(2n) / (1 + x^(2n)), x = f0 / f_c, so
    amp / sqrt(2) * |H|^2 = thr gives x^(2n) = r / (1 - r), r = sqrt(2) thr / amp.
    """
    r = np.sqrt(2.0) * thr_m / amp_m
    return f0_hz * (r / (1.0 - r)) ** (-1.0 / (2 * order))


def signal(t: np.ndarray, slow_m: float = 3.0) -> np.ndarray:
    """Metre-level daily term (removed by any cutoff) + the centimetre test line."""
    return slow_m * (1.2 + np.cos(2 * np.pi * t / SIDEREAL_DAY_S + 0.4)) + A0_M * np.cos(
        2 * np.pi * F0_HZ * t + 1.0
    )


@pytest.fixture(scope="module")
def passes():
    """Visibility of nominal GPS satellites above 10 deg from Chicago, one sidereal day + 12 h."""
    orbit = nominal_constellation("G")
    t = 1.26e9 + DT_S * np.arange(int((SIDEREAL_DAY_S + 43200) / DT_S))
    rx = geodetic_to_ecef(41.84, -87.63, 0.0)
    out = {}
    for sat in orbit.satellites[:8]:
        _, el = satellite_azel(orbit, sat, t, rx)
        out[sat] = (t, el >= 10.0)
    return out


def series_on(t: np.ndarray, visible: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d = np.where(visible, signal(t - t[0]), np.nan)
    return one_day_series(t, d)


def test_closed_form_cutoff_on_realistic_passes(passes):
    expected = analytic_cutoff(THR_M, A0_M, F0_HZ)
    assert expected == pytest.approx(1.14e-3, rel=0.01)
    series = [series_on(t, v) for t, v in passes.values()]
    found = residual_cutoffs(series, dt_s=DT_S, thresholds_m=[THR_M])
    for (t, _), r in zip(series, found, strict=True):
        assert len(split_arcs(t, t, DT_S)) >= 1 and r.reached and not r.floor
        assert r.f_c_hz == pytest.approx(expected, rel=0.10)
        # the residual curve falls with the cutoff above f_c and crosses the threshold there
        assert np.all(r.curve_rms_m[r.curve_f_hz > r.f_c_hz] <= THR_M)


def test_cutoff_does_not_depend_on_pass_length_but_the_periodogram_does():
    """Same signal on 3, 5 and 8 h passes (one per sidereal day, gaps between)."""
    t_all = DT_S * np.arange(int(SIDEREAL_DAY_S / DT_S))
    res, ls = [], []
    for hours in (3.0, 5.0, 8.0):
        vis = (t_all >= 3600.0) & (t_all < 3600.0 + hours * 3600.0)
        t, y = t_all[vis], signal(t_all[vis])
        res.append(residual_cutoff(t, y, dt_s=DT_S, threshold_m=THR_M).f_c_hz)
        ls.append(series_cutoff(t, y, dt_s=DT_S, criterion="relative").f_c_hz)
    expected = analytic_cutoff(THR_M, A0_M, F0_HZ)
    assert np.allclose(res, expected, rtol=0.10), res
    assert max(res) / min(res) < 1.1
    # the 40 dB point of the untapered Lomb-Scargle is set by the 3 m term's window leakage
    # (f^-2 sidelobes of each pass): it sits far above the test line and moves with the passes
    assert min(ls) > 2 * expected and max(ls) / min(ls) > 2, ls


def test_batched_filter_is_the_fit_filter():
    """The arcs' filter is scipy's sosfiltfilt to the bit; the batched RMS equals it per arc."""
    from scipy.signal import sosfiltfilt

    rng = np.random.default_rng(3)
    arcs = [np.cumsum(rng.normal(size=n)) for n in (2, 40, 301, 1500)]
    for hp in (HighPass(), HighPass(order=2), HighPass(kind="cheby2"), HighPass(edge="pad")):
        for f_c in (3e-4, 2e-3, 1e-2):
            for x, (y, keep) in zip(arcs, highpass_arcs(arcs, DT_S, f_c, highpass=hp), strict=True):
                pad = min(x.size - 1, int(np.ceil(3.0 / (f_c * DT_S))))
                y0 = sosfiltfilt(hp.sos(DT_S, f_c), x, padtype="odd", padlen=pad)
                assert np.array_equal(y, y0)
                assert np.array_equal(keep, hp.apply(x, DT_S, f_c)[1])
            rms, n = residual_rms(arcs, DT_S, f_c, highpass=hp, min_kept_s=0.0)
            ss = cnt = 0.0
            for x in arcs:
                y0, keep0 = hp.apply(x - x.mean(), DT_S, f_c)
                if keep0.sum() >= 2:
                    ss += np.sum(y0[keep0] ** 2)
                    cnt += keep0.sum()
            assert n == cnt and rms == pytest.approx(np.sqrt(ss / cnt), rel=1e-12)


def test_thresholds_order_and_scale():
    t = DT_S * np.arange(int(6 * 3600 / DT_S))
    y = signal(t)
    thr = [residual_threshold_m(1e-3, m) for m in (40.0, 20.0, 30.0, 50.0)]
    r = residual_cutoffs([(t, y)], dt_s=DT_S, thresholds_m=thr)[0]
    f = [r.f_c_by_threshold[v] for v in thr]
    assert r.f_c_hz == f[0] and f[1] < f[2] < f[0] < f[3]
    # scaling the series by 1/sqrt(2) is the same as raising the threshold by sqrt(2)
    a = residual_cutoff(t, y, dt_s=DT_S, threshold_m=THR_M, scale=2**-0.5).f_c_hz
    b = residual_cutoff(t, y, dt_s=DT_S, threshold_m=THR_M * 2**0.5).f_c_hz
    assert a == pytest.approx(b, rel=1e-9)


def test_edges_of_the_search():
    t = DT_S * np.arange(400)
    tiny = residual_cutoff(t, 1e-9 * np.sin(t / 300.0), dt_s=DT_S, threshold_m=THR_M)
    assert tiny.floor and tiny.reached and tiny.f_c_hz == pytest.approx(1e-4)
    noisy = np.random.default_rng(0).normal(0.0, 1e-3, t.size)
    top = residual_cutoff(t, noisy, dt_s=DT_S, threshold_m=THR_M)
    assert not top.reached and top.f_c_hz == pytest.approx(0.5 * 0.5 / DT_S)
    with pytest.raises(InputError):
        residual_cutoff(t, noisy, dt_s=DT_S, threshold_m=0.0)
    with pytest.raises(InputError):
        residual_threshold_m(-1.0, 40.0)
