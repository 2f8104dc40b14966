"""LADGNSS error budget and VPL: seed 004 numbers and closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.aviation import (
    error_budget,
    ground_sigma_pr_m,
    iono_free_multiplier,
    los_from_az_el,
    obliquity_factor,
    projection_matrix,
    smoothing_time_ratio,
    vpl,
)
from psdbound.constants import F_L1_HZ, F_L5_HZ
from psdbound.errors import InputError

K_MD_E = 2.898  # a test value (the old H1 number); real runs take the station's K_md_e

EL = np.array([12.0, 25.0, 38.0, 47.0, 60.0, 75.0, 85.0])
AZ = np.array([10.0, 80.0, 150.0, 200.0, 260.0, 320.0, 45.0])


def test_seed004_iono_free_multiplier():
    # seed 004 sec. 3.2A: "a constant IF multiplier of 2.4267 is used" (eq. 9 with
    # Table 2's L5/L1 sigma ratio 0.7); printed to 4 decimals -> tolerance 5e-5
    assert iono_free_multiplier(0.7) == pytest.approx(2.4267, abs=5e-5)
    # equal sigmas: the classic L1/L5 iono-free factor 2.588
    assert iono_free_multiplier(1.0) == pytest.approx(2.588, abs=5e-4)


def test_seed004_l5_iono_factor():
    # seed 004 sec. 3.2C: L5-based iono sigmas "multiplied by a factor of 1.79"
    assert (F_L1_HZ / F_L5_HZ) ** 2 == pytest.approx(1.79, abs=5e-3)
    el = [30.0, 50.0, 70.0, 80.0]
    l1 = error_budget(el, process="DF")
    l5 = error_budget(el, process="DF", base_frequency="L5")
    assert l5.iono / l1.iono == pytest.approx(np.full(4, (F_L1_HZ / F_L5_HZ) ** 2))
    # Table 2: L5 noise is 0.7 of L1 (ground multipath part and airborne)
    assert l5.air / l1.air == pytest.approx(np.full(4, 0.7))


def test_seed004_table1_xi_enters_the_air_term():
    # Table 1: xi = 1.1486, 1.3026, 1.3997 for 60, 30, 15 s (tau_corr 30 s), 4 decimals
    # with the seed's printed formula selected (the default is the exact variance)
    ref = error_budget(EL, tau_air_s=100.0, xi_formula="seed").air
    for tau, seed in ((60.0, 1.1486), (30.0, 1.3026), (15.0, 1.3997)):
        ratio = error_budget(EL, tau_air_s=tau, tau_gnd_s=tau, xi_formula="seed").air / ref
        assert ratio == pytest.approx(np.full(EL.size, seed), abs=5e-5)
    # the default is exact: its xi is larger than the seed's (which double-counts the
    # off-diagonal terms of a positive correlation), by up to 1.6 % at 15 s
    exact = error_budget(EL, tau_air_s=15.0, tau_gnd_s=15.0).air
    seed15 = error_budget(EL, tau_air_s=15.0, tau_gnd_s=15.0, xi_formula="seed").air
    ref_exact = error_budget(EL, tau_air_s=100.0).air
    assert (exact / ref_exact)[0] == pytest.approx(
        smoothing_time_ratio(15.0, tau_corr_s=30.0, formula="exact"), rel=1e-12
    )
    assert not np.allclose(exact / ref_exact, seed15 / ref, atol=5e-5)


def test_ground_term_closed_form_single_receiver_no_correlation():
    # M = 1, rho = 0, one satellite among N: var = ((N-1)^2 g_i^2 + sum_{j!=i} g_j^2) / N^2 + a2^2
    t = error_budget(EL, n_receivers=1, rho=0.0, tau_gnd_s=100.0, gad="A")
    g = ground_sigma_pr_m(EL, "A")
    n = EL.size
    expect = np.sqrt(((n - 1) ** 2 * g**2 + (g**2).sum() - g**2) / n**2 + 0.08**2)
    assert t.ground == pytest.approx(expect, rel=1e-12)


def test_ground_correlation_factor_exact_vs_seed():
    a = error_budget(EL, rho=0.6, rho_formula="exact", tau_gnd_s=100.0)
    b = error_budget(EL, rho=0.6, rho_formula="seed", tau_gnd_s=100.0)
    sis = 0.08
    ratio = (b.ground**2 - sis**2) / (a.ground**2 - sis**2)
    # (1 + 2 rho (M-1)) / (1 + rho (M-1)) for M = 3, rho = 0.6
    assert ratio == pytest.approx(np.full(EL.size, 3.4 / 2.2))


def test_gad_curves_and_obliquity():
    assert ground_sigma_pr_m([90.0], "B")[0] == pytest.approx(0.16 + 1.07 * np.exp(-90 / 15.5))
    assert ground_sigma_pr_m([20.0], "C")[0] == 0.24
    assert obliquity_factor([90.0])[0] == pytest.approx(1.0)
    c = 6378.1363 * np.cos(np.radians(5.0)) / (6378.1363 + 350.0)  # thin shell, 350 km
    assert obliquity_factor([5.0])[0] == pytest.approx(1 / np.sqrt(1 - c * c))


def test_iono_terms():
    matched = error_budget([90.0], tau_gnd_s=30, tau_air_s=30, x_air_m=5000)
    # F_pp = 1 at zenith: sigma_vig (x + 2 tau v) = 4e-6 (5000 + 900)
    assert matched.iono[0] == pytest.approx(4e-6 * 5900)
    mism = error_budget([90.0], tau_gnd_s=60, tau_air_s=30, x_air_m=5000)
    assert mism.iono[0] == pytest.approx(np.hypot(4e-6 * 5900, 2 * 0.004 * 30))
    assert error_budget([90.0], process="IF").iono[0] == 0.0


def test_projection_matrix_is_a_left_inverse():
    u = los_from_az_el(AZ, EL)
    assert np.linalg.norm(u, axis=1) == pytest.approx(np.ones(EL.size))
    s = projection_matrix(u, np.linspace(0.3, 1.0, EL.size))
    g = np.column_stack([-u, np.ones(EL.size)])
    assert s @ g == pytest.approx(np.eye(4), abs=1e-12)


def test_vpl_closed_form_equal_sigmas():
    u = los_from_az_el(AZ, EL)
    g = np.column_stack([-u, np.ones(EL.size)])
    sigma = 0.5
    vdop = np.sqrt(np.linalg.inv(g.T @ g)[2, 2])
    h0, eph = vpl(u, np.full(EL.size, sigma), k_md_e=K_MD_E, n_receivers=3)
    assert h0 == pytest.approx(5.810 * sigma * vdop, rel=1e-12)
    assert eph == pytest.approx(2.898 * sigma * vdop, rel=1e-12)  # x_air = 0


def test_vpl_budget_end_to_end_decreases_with_smoothing():
    u = los_from_az_el(AZ, EL)
    v = [
        vpl(u, error_budget(EL, tau_gnd_s=t, tau_air_s=t).total, k_md_e=K_MD_E)[0]
        for t in (15, 30, 60)
    ]
    assert v[0] > v[1] > v[2] > 0
    assert smoothing_time_ratio(60.0, tau_corr_s=30.0, formula="seed") > 1


def test_bad_input():
    with pytest.raises(InputError, match="elevations"):
        error_budget([np.nan, 30.0])
    with pytest.raises(InputError, match="process"):
        error_budget([30.0], process="XX")
    with pytest.raises(InputError, match="singular|n >= 4"):
        vpl(los_from_az_el([0, 90, 180], [30, 30, 30]), [1, 1, 1], k_md_e=K_MD_E)


def test_vpl_eph_uses_the_given_k_md_e_hand_computation():
    # 4 satellites, equal sigmas 1 m: S = (G^T G)^-1 G^T by hand through numpy, then
    # VPL_eph = max |S_v| x P + K_md_e sqrt(sum S_v^2); VPL_H0 = K_ffmd(M = 3) sqrt(...)
    az, el = [0.0, 90.0, 180.0, 270.0], [30.0, 45.0, 60.0, 85.0]
    u = los_from_az_el(az, el)
    g = np.column_stack([-u, np.ones(4)])
    sv = (np.linalg.inv(g.T @ g) @ g.T)[2]  # square system: S = G^-1
    sd = np.sqrt(np.sum(sv**2))
    x, p, k = 7000.0, 0.00018, 4.753
    h0, eph = vpl(u, np.ones(4), k_md_e=k, x_air_m=x, p_eph=p)
    assert eph == pytest.approx(np.max(np.abs(sv)) * x * p + k * sd, rel=1e-12)
    assert h0 == pytest.approx(5.810 * sd, rel=1e-12)
    # K_md_e is its own input: changing it moves VPL_eph only, and linearly
    h0b, eph2 = vpl(u, np.ones(4), k_md_e=2 * k, x_air_m=x, p_eph=p)
    assert h0b == h0 and eph2 - eph == pytest.approx(k * sd, rel=1e-12)
    with pytest.raises(InputError, match="k_md_e.*required"):
        vpl(u, np.ones(4), k_md_e=None)
    with pytest.raises(InputError, match="k_md_e must be"):
        vpl(u, np.ones(4), k_md_e=-1.0)


def test_multipliers_name_their_sources():
    from psdbound.aviation import multipliers

    k = multipliers(n_receivers=3, k_md_e=5.0)
    assert k["k_ffmd"]["value"] == 5.810 and "not verified" in k["k_ffmd"]["source"]
    assert k["k_md_e"]["value"] == 5.0 and "user-supplied" in k["k_md_e"]["source"]
    assert k["k_md_e"]["p_md_e_two_sided_gaussian"] == pytest.approx(5.733e-7, rel=1e-3)
    assert multipliers(n_receivers=7, k_ffmd=6.0, k_md_e=5.0)["k_ffmd"]["source"] == (
        "user-supplied"
    )
    with pytest.raises(InputError, match="no tabulated K_ffmd"):
        multipliers(n_receivers=7, k_md_e=5.0)
