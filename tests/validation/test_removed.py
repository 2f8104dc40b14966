"""What the high-pass removes, as a slow Gauss-Markov component (issue 28, part 2)."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.isolation import HighPass
from psdbound.spectra.models import gm_psd_sampled
from psdbound.validation import parse_geometry
from psdbound.validation.removed import removed_along_arcs, slow_gauss_markov

DT = 30.0
FC = 1.5e-3
LAMS = (0.1903, 0.2442)


@pytest.mark.parametrize(("sigma", "tau"), [(0.002, 60.0), (0.004, 400.0), (0.001, 2000.0)])
def test_slow_fit_recovers_a_gauss_markov_spectrum(sigma, tau):
    f = np.r_[0.0, np.geomspace(1e-6, 0.5 / DT, 300)]
    s, t = slow_gauss_markov(f, gm_psd_sampled(f, sigma, tau, DT), DT)
    assert s == pytest.approx(sigma, rel=0.03) and t == pytest.approx(tau, rel=0.06)
    assert np.all(gm_psd_sampled(f, s, t, DT) >= gm_psd_sampled(f, sigma, tau, DT) * (1 - 1e-9))


def _arcs(n=4, hours=6.0):
    """Passes rising from 10 deg to a culmination and setting, one arc each."""
    t = np.arange(0.0, hours * 3600.0, DT)
    el = [10.0 + (50.0 + 8 * k) * np.sin(np.pi * t / t[-1]) for k in range(n)]
    return np.concatenate(el), np.repeat(np.arange(n), t.size)


def _removed(h_m, alpha):
    el, arc = _arcs()
    return removed_along_arcs(
        el,
        arc,
        geometry=parse_geometry(f"ground:h={h_m}"),
        alpha=alpha,
        wavelengths_m=LAMS,
        highpass=HighPass(),
        dt_s=DT,
        cutoff_hz=FC,
    )


def test_the_slow_component_lies_above_the_removed_spectrum_everywhere():
    rm = _removed(0.3, 0.1)
    assert rm.n_arcs == 4 and rm.rms_m > 0
    assert np.all(gm_psd_sampled(rm.f_hz, rm.sigma_m, rm.tau_s, DT) >= rm.psd_m2_hz * (1 - 1e-9))
    # the spectrum holds the removed variance (Parseval, 0 Hz included; the 0 Hz bin is
    # doubled like the others, a few % conservative)
    df = rm.f_hz[1] - rm.f_hz[0]
    assert 1.0 <= np.sum(rm.psd_m2_hz) * df / rm.rms_m**2 < 1.05


def test_a_low_reflector_loses_most_of_its_multipath_to_the_filter():
    # small alpha: the DF combination of two carriers' errors has about alpha^2/2 (lam/2pi)^2 / 2
    # per carrier; a 0.3 m reflector oscillates a few times per pass: mostly below f_c
    full = 0.1**2 / 2 * np.mean([(lam / (2 * np.pi)) ** 2 for lam in LAMS])
    low, high = _removed(0.3, 0.1), _removed(3.0, 0.1)
    assert low.rms_m**2 > 0.5 * full
    assert high.rms_m < low.rms_m
    # the removed multipath scales with the amplitude ratio (small alpha)
    strong = _removed(0.3, 0.2)
    assert strong.rms_m == pytest.approx(2 * low.rms_m, rel=0.05)
    assert strong.sigma_m == pytest.approx(2 * low.sigma_m, rel=0.05)


def test_no_elevations_no_component():
    el, arc = _arcs()
    assert (
        removed_along_arcs(
            np.full_like(el, np.nan),
            arc,
            geometry=parse_geometry("ground:h=1"),
            alpha=0.1,
            wavelengths_m=LAMS,
            highpass=HighPass(),
            dt_s=DT,
            cutoff_hz=FC,
        )
        is None
    )
