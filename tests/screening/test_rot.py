"""ROT / ROTI on synthetic geometry-free phases with known TEC rates."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.errors import InputError
from psdbound.screening import (
    geometry_free_m_per_tecu,
    multipath_limit_m,
    rate_of_tec,
    roti_blocks,
)

F1, F2, F5 = 1575.42e6, 1227.60e6, 1176.45e6
C = 299792458.0


def test_geometry_free_factor_closed_form():
    k = geometry_free_m_per_tecu(F1, F2)
    assert k == pytest.approx(40.3e16 * (1 / F2**2 - 1 / F1**2))
    assert k == pytest.approx(0.10505, rel=1e-4)  # GPS L1/L2: 0.105 m per TECU
    assert geometry_free_m_per_tecu(F1, F5) > k  # L1/L5 are further apart
    with pytest.raises(InputError):
        geometry_free_m_per_tecu(F1, F1)


@pytest.mark.parametrize("dt", [1.0, 5.0, 30.0])
def test_constant_tec_rate_gives_that_rot_and_zero_roti(dt):
    rate_tecu_min = 0.8
    t = np.arange(0.0, 3600.0, dt)
    k = geometry_free_m_per_tecu(F1, F2)
    gf = 3.0 + k * rate_tecu_min * t / 60.0
    tm, rot = rate_of_tec(t, gf, k)
    assert np.allclose(rot, rate_tecu_min)
    assert np.allclose(np.diff(tm), 30.0)  # always sampled at 30 s (Pi et al. 1997)
    blocks = roti_blocks(tm, rot, t0_gps_s=t[0], t1_gps_s=t[-1])
    assert blocks.roti_tecu_min.size == 12
    assert np.nanmax(blocks.roti_tecu_min) < 1e-9


def test_sinusoidal_tec_has_the_closed_form_roti():
    # STEC = A sin(2 pi t / P): ROT samples are a sinusoid of amplitude
    # A * 2 sin(pi dt / P) / (dt/60); its std over whole periods is that / sqrt(2)
    amp_tecu, period_s, dt = 0.5, 300.0, 30.0
    t = np.arange(0.0, 7200.0 + dt, dt)
    k = geometry_free_m_per_tecu(F1, F2)
    gf = k * amp_tecu * np.sin(2 * np.pi * t / period_s)
    tm, rot = rate_of_tec(t, gf, k)
    expect = amp_tecu * 2 * np.sin(np.pi * dt / period_s) / (dt / 60.0) / np.sqrt(2.0)
    blocks = roti_blocks(tm, rot, t0_gps_s=0.0, t1_gps_s=7200.0)
    assert np.nanmedian(blocks.roti_tecu_min) == pytest.approx(expect, rel=1e-6)


def test_half_empty_blocks_are_nan():
    t = np.r_[np.arange(0.0, 300.0, 30.0), np.arange(600.0, 660.0, 30.0)]
    tm, rot = rate_of_tec(t, np.zeros_like(t), 0.105)
    b = roti_blocks(tm, rot, t0_gps_s=0.0, t1_gps_s=660.0)
    assert np.isfinite(b.roti_tecu_min[0]) and np.isnan(b.roti_tecu_min[-1])


def test_plausibility_limit_closed_form():
    lam1, lam2 = C / F1, C / F2
    df = multipath_limit_m([lam1, lam2], 1 / np.sqrt(2))
    assert df == pytest.approx((lam1 + lam2) / (4 * np.sqrt(2)))
    assert df == pytest.approx(0.0770, abs=2e-4)  # 7.7 cm, the GPS L1/L2 DF limit
    assert multipath_limit_m([lam1] * 4, 0.5) == pytest.approx(lam1 / 2)
    with pytest.raises(InputError):
        multipath_limit_m([lam1, -1.0], 1.0)
