"""Simulated SNR carries the injected ground reflections: GNSS-IR recovers height and alpha.

The simulator adds ``10 log10(1 + alpha^2 + 2 alpha cos psi)`` dB per
reflection to the SNR, with the same ``psi`` per carrier as the phase error
(``psi = 4 pi h sin(el) / lambda`` for a ground reflector ``h`` below the
antenna). :func:`psdbound.validation.reflector_heights` on the written RINEX
must find ``h`` and ``alpha`` again, and nothing without a reflection.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from psdbound.constants import SPEED_OF_LIGHT_M_S
from psdbound.io import read_obs, read_orbit
from psdbound.io.signals import carrier_frequency_hz
from psdbound.simulate import Reflection, preset, simulate
from psdbound.validation import reflector_heights

CASES = [(1.0, 0.15), (2.5, 0.2)]  # ground reflector height (m), amplitude ratio alpha
# The simulated direct SNR is 30 + 20 sin(el) dB-Hz (~32-38 dB-Hz over 5-25 deg, 3 dB lower on
# the second carrier): a reflection's oscillation is ~alpha x 56 volts/volt on L1 and ~alpha x 40
# on L2/L5, so the second carriers are analysed with a 4 volts/volt amplitude threshold (gnssrefl's
# default of 6 rejects alpha = 0.15 there; at alpha = 0.1 it rejects most L1 arcs too).
SIGNALS = {"S1C": 6.0, "S2W": 4.0, "S5Q": 4.0}  # SNR code: min_peak_amplitude, volts/volt


def _scenario(reflections):
    base = preset("short").replace(
        name="gnssir", duration_s=86400.0, interval_s=30.0, systems="GE", dual_antenna=False
    )
    return base.replace(multipath=replace(base.multipath, reflections=tuple(reflections)))


def _run(tmp_path_factory, reflections):
    res = simulate(_scenario(reflections), tmp_path_factory.mktemp("gnssir"))
    return res, read_obs(res.obs_paths[0]), read_orbit(res.nav_path)


@pytest.fixture(scope="module")
def without(tmp_path_factory):
    return _run(tmp_path_factory, ())


@pytest.fixture(scope="module", params=CASES, ids=[f"h{h:g}-alpha{a:g}" for h, a in CASES])
def with_ground(request, tmp_path_factory):
    h, alpha = request.param
    return h, alpha, _run(tmp_path_factory, [Reflection("ground", h, alpha)])


def test_snr_change_is_the_interference_power(with_ground, without):
    """Same seed, same everything else: the SNR differs by 10 log10 |1 + alpha e^{i psi}|^2."""
    h, alpha, (res, obs, _) = with_ground
    _, obs0, _ = without
    el = res.elevation_deg[0]
    for system, codes in (("G", ("S1C", "S2W")), ("E", ("S1C", "S5Q"))):
        block, block0 = obs.blocks[system], obs0.blocks[system]
        cols = [res.sats.index(s) for s in block.sats]
        for code in codes:
            k = block.codes.index(code)
            lam = np.array(
                [SPEED_OF_LIGHT_M_S / carrier_frequency_hz(s, "L" + code[1:]) for s in block.sats]
            )
            psi = 4.0 * np.pi * h * np.sin(np.radians(el[:, cols])) / lam
            expected = 10.0 * np.log10(1.0 + alpha**2 + 2.0 * alpha * np.cos(psi))
            got = block.values[..., k] - block0.values[..., k]
            ok = np.isfinite(got)
            assert np.count_nonzero(ok) > 1000, (system, code)
            np.testing.assert_allclose(got[ok], expected[ok], atol=1.1e-3, err_msg=code)
    for system in obs.blocks:  # code and signal strength indicators are unchanged
        b, b0 = obs.blocks[system], obs0.blocks[system]
        code = [k for k, c in enumerate(b.codes) if c.startswith("C")]
        assert np.array_equal(b.values[..., code], b0.values[..., code], equal_nan=True)
        np.testing.assert_array_equal(b.ssi, b0.ssi)


@pytest.mark.parametrize("signal", list(SIGNALS))
def test_reflector_heights_recover_the_ground_reflection(with_ground, signal):
    h, alpha, (_, obs, orbit) = with_ground
    r = reflector_heights(obs, orbit, signal=signal, min_peak_amplitude=SIGNALS[signal])
    print(f"h {h} m, alpha {alpha}, {signal}: {r.summary()}")
    assert r.n_accepted >= 0.5 * r.n_arcs and r.n_accepted >= 20, r.summary()
    assert abs(r.median_height_m - h) < 0.03, r.summary()
    assert abs(r.median_alpha - alpha) < 0.25 * alpha, r.summary()


@pytest.mark.parametrize("signal", list(SIGNALS))
def test_no_reflection_no_accepted_arc(without, signal):
    # seen: 0 of 144 (S1C), 0 of 78 (S2W), 0 of 66 (S5Q) arcs accepted. The simulated SNR is
    # noise-free, so its periodogram peak stands far above the "noise" (peak-to-noise in the
    # thousands); what rejects the arcs is the amplitude test: the largest peak is ~0.002
    # volts/volt (polynomial misfit and 0.001 dB rounding).
    _, obs, orbit = without
    r = reflector_heights(obs, orbit, signal=signal, min_peak_amplitude=SIGNALS[signal])
    print(f"no reflection, {signal}: {r.summary()}")
    assert r.n_arcs >= 50
    assert r.n_accepted == 0, r.summary()
    assert np.nanmax(r.peak_amplitude) < 0.1
