"""What the high-pass removes, as a slow Gauss-Markov component (issue 28, part 2)."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.isolation import HighPass
from psdbound.spectra.models import gm_psd_sampled
from psdbound.validation import direct_check, parse_geometry
from psdbound.validation.removed import removed_multipath, slow_gauss_markov

DT = 30.0
FC = 1.5e-3


@pytest.mark.parametrize(("sigma", "tau"), [(0.002, 60.0), (0.004, 400.0), (0.001, 2000.0)])
def test_slow_fit_recovers_a_gauss_markov_spectrum(sigma, tau):
    f = np.geomspace(1e-6, 0.5 / DT, 300)
    s, t = slow_gauss_markov(f, gm_psd_sampled(f, sigma, tau, DT), DT)
    assert s == pytest.approx(sigma, rel=0.03) and t == pytest.approx(tau, rel=0.06)
    assert np.all(gm_psd_sampled(f, s, t, DT) >= gm_psd_sampled(f, sigma, tau, DT) * (1 - 1e-9))


def _passes(h_m, alpha=0.1, n=4):
    """Rising passes of a ground reflection: elevation 10 -> 80 -> 10 deg over 6 h."""
    geom = parse_geometry(f"ground:h={h_m}")
    t = np.arange(0.0, 6 * 3600.0, 5.0)
    out = []
    for k in range(n):
        el = np.radians(10.0 + 70.0 * np.sin(np.pi * t / t[-1]) ** (1.0 + 0.2 * k))
        out.append(direct_check(geom, el, 5.0, cutoff_hz=FC, alpha=alpha, source="satellite"))
    return out


def test_removed_part_of_a_low_reflector_is_bounded_at_every_frequency():
    hp = HighPass()

    def gain(f):
        return hp.response(f, DT, FC) ** 2

    checks = _passes(0.3)
    rm = removed_multipath(checks, wavelengths_m=[0.1903, 0.2442], power_response=gain, dt_s=DT)
    assert rm.n_passes == 4 and rm.rms_m > 0
    # the slow GM lies above the removed spectrum everywhere on its grid
    assert np.all(gm_psd_sampled(rm.f_hz, rm.sigma_m, rm.tau_s, DT) >= rm.psd_m2_hz * (1 - 1e-9))
    # what is removed agrees with the validation's own fraction below f_c (a hard cutoff
    # there, the filter's smooth response here; each pass's offset counted here)
    lam2 = np.mean([(lam / (2 * np.pi)) ** 2 for lam in (0.1903, 0.2442)])
    frac = np.mean([c.fraction_below_cutoff for c in checks])
    assert 0.7 < rm.rms_m**2 / (frac * 0.1**2 / 2 * lam2) < 1.4
    # twice the amplitude ratio: four times the removed variance and the slow variance
    strong = removed_multipath(_passes(0.3, alpha=0.2), wavelengths_m=[0.1903, 0.2442],
                               power_response=gain, dt_s=DT)  # fmt: skip
    assert strong.rms_m == pytest.approx(2 * rm.rms_m, rel=0.05)
    assert strong.sigma_m == pytest.approx(2 * rm.sigma_m, rel=0.05)


def test_no_passes_no_component():
    assert removed_multipath([], wavelengths_m=[0.19], power_response=np.ones_like, dt_s=DT) is None
