"""Cutoff validation (issue #6): Jacobi-Anger expansions, direct simulation, modes, CLI."""

from __future__ import annotations

import argparse
import csv
import json
import math

import numpy as np
import pytest
from conftest import ESBC_NAV, shared_file
from scipy.special import jv

from psdbound.cli.validate import add_parser, run
from psdbound.errors import InputError, NoDataError
from psdbound.validation import (
    AIRCRAFT_MODES,
    CONVENTION_LABELS,
    GPS_L1_WAVELENGTH_M,
    ORBIT_RATES_HZ,
    DynamicMode,
    Reflection,
    bessel_tail_bound,
    check_oscillation,
    check_rotating,
    closed_form_power_rad2,
    direct_check,
    load_modes,
    mode_table,
    oscillation_harmonics,
    oscillation_track,
    parse_geometry,
    phase_error_rad,
    power_fraction_below,
    resolve_rate,
    rotating_harmonics,
    sampling_interval_s,
    satellite_passes,
    tapered_periodogram,
    terms_for_tolerance,
    truncation_bound,
    validate_cutoff,
)

FC_THESIS_HZ = 9.55e-4  # thesis eq. 4.2 (Chicago 2020, maximum)
ESBC_XYZ_M = (3582105.2910, 532589.7313, 5232754.8054)
ORBIT = resolve_rate("orbit")


# --------------------------------------------------------------------------- expansion identity


@pytest.mark.parametrize("z", [0.5, 3.0, 10.0, 100.0, 262.75, 1000.0, 2000.0])
def test_truncated_expansion_equals_sin_z_sin_and_sin_z_cos(z):
    t = np.linspace(0.0, 2.0 * np.pi, 20001)
    for kind, g in (("ground", np.sin), ("wall", np.cos)):
        h = rotating_harmonics(z, kind=kind)  # alpha = 1, order 1: the plain identity
        err = np.max(np.abs(h.synthesize(t) - np.sin(z * g(t))))
        assert err < 1e-10, (z, kind, err)
        assert h.truncation_bound_rad <= 1e-12
    n = terms_for_tolerance(z, tol=1e-12)
    # the number of odd harmonics is z/2 plus a margin growing like z^(1/3)
    assert n >= z / 2.0
    assert n <= z / 2.0 + 4.0 * z ** (1.0 / 3.0) + 15.0
    assert truncation_bound(z, n) <= 1e-12 < truncation_bound(z, n - 1)


@pytest.mark.parametrize("z", [20.0, 300.0])
def test_truncation_bound_holds_and_is_not_vacuous(z):
    t = np.linspace(0.0, 2.0 * np.pi, 8001)
    exact = np.sin(z * np.sin(t))
    k_all = 2 * np.arange(1, terms_for_tolerance(z) + 1) - 1
    a_all = 2.0 * jv(k_all, z)
    for n in range(int(z / 2) + 1, terms_for_tolerance(z, tol=1e-9) + 1, 3):
        approx = np.sin(np.multiply.outer(t, k_all[:n])) @ a_all[:n]
        observed = np.max(np.abs(approx - exact))
        bound = truncation_bound(z, n)
        assert observed <= bound + 1e-13
        if observed > 1e-12:
            assert bound < 50.0 * observed  # a useful bound, not just a valid one


def test_bessel_tail_bound_against_direct_sums():
    for z in (0.3, 5.0, 80.0, 700.0):
        for k0 in (int(z) + 1, int(z) + 10, int(1.3 * z) + 3):
            k = np.arange(k0, k0 + 4000)
            assert np.sum(np.abs(jv(k, z))) <= bessel_tail_bound(z, k0) * (1 + 1e-12)
            assert np.sum(np.abs(jv(k[::2], z))) <= bessel_tail_bound(z, k0, step=2) * (1 + 1e-12)
    assert bessel_tail_bound(10.0, 10) == math.inf  # k_min <= z: no bound
    assert bessel_tail_bound(0.0, 1) == 0.0


@pytest.mark.parametrize("order", [1, 2, 3])
def test_sum_of_harmonic_powers_matches_closed_form(order):
    for z in (1.0, 15.765, 262.75, 1650.9):
        h = rotating_harmonics(z, kind="wall", alpha=0.3, order=order)
        closed = closed_form_power_rad2(z, alpha=0.3, order=order)
        assert h.variance_rad2 == pytest.approx(closed, rel=1e-10, abs=1e-14)
    # first order: sum_n (2 J_{2n-1}(z))^2 = 1 - J_0(2z)
    z = 262.75
    h = rotating_harmonics(z, kind="ground")
    assert np.sum(h.amplitude_rad**2) == pytest.approx(1.0 - jv(0, 2 * z), abs=1e-12)


def test_thesis_second_order_amplitudes_eq_2_16():
    z, alpha = 50.0, 0.4
    h = rotating_harmonics(z, kind="ground", alpha=alpha, order=2)
    k = h.orders
    expected = alpha * (2.0 * jv(k, z) - alpha * jv(k, 2.0 * z))
    # ground form: a_k sin(k t) = 2 Re(X_k e^{ikt}) with X_k = -i a_k / 2
    assert np.allclose(-2.0 * h.coefficients.imag, expected, atol=1e-14)


# --------------------------------------------------------------------------- O(alpha^3)


def test_second_order_form_error_scales_as_alpha_cubed():
    alphas = [0.2, 0.1, 0.05, 0.025, 0.0125]
    psi = np.linspace(-np.pi, np.pi, 20001)
    err2 = [
        np.max(np.abs(phase_error_rad(psi, a, order=2) - phase_error_rad(psi, a))) for a in alphas
    ]
    err1 = [
        np.max(np.abs(phase_error_rad(psi, a, order=1) - phase_error_rad(psi, a))) for a in alphas
    ]
    ratios2 = [err2[i] / err2[i + 1] for i in range(len(alphas) - 1)]
    ratios1 = [err1[i] / err1[i + 1] for i in range(len(alphas) - 1)]
    assert all(7.8 < r < 8.7 for r in ratios2), ratios2  # halving alpha: ~8x
    assert ratios2[-1] == pytest.approx(8.0, abs=0.15)
    assert all(3.7 < r < 4.4 for r in ratios1), ratios1  # first order: O(alpha^2), ~4x
    # leading term alpha^3 sin(3 psi) / 3
    assert err2[-1] / alphas[-1] ** 3 == pytest.approx(1.0 / 3.0, rel=0.02)


def test_second_order_expansion_against_exact_arctan_along_geometry():
    """The Bessel-series form itself (not only alpha sin - alpha^2/2 sin 2) is O(alpha^3)."""
    z = 100.0
    t = np.linspace(0.0, 2.0 * np.pi, 8001)
    errs = []
    for a in (0.1, 0.05, 0.025):
        h = rotating_harmonics(z, kind="wall", alpha=a, order=2)
        exact = np.arctan2(a * np.sin(z * np.cos(t)), 1.0 + a * np.cos(z * np.cos(t)))
        errs.append(np.max(np.abs(h.synthesize(t) - exact)))
    assert 7.8 < errs[0] / errs[1] < 8.7
    assert 7.8 < errs[1] / errs[2] < 8.7


# --------------------------------------------------------------------------- geometry and units


def test_geometry_delays_and_both_conventions():
    g = parse_geometry("wall:d=25")
    assert g == Reflection("wall", 25.0)
    assert g.path_delay_m(0.0) == pytest.approx(50.0)
    assert parse_geometry(" Ground : h = 1.5 ").path_delay_m(np.pi / 2) == pytest.approx(3.0)
    lam = GPS_L1_WAVELENGTH_M
    assert g.z(convention="thesis") == pytest.approx(50.0 / lam)  # thesis: z = 50 / lambda(L1)
    assert g.z(convention="physical") == pytest.approx(4.0 * np.pi * 25.0 / lam)
    assert g.z(convention="physical") / g.z(convention="thesis") == pytest.approx(2.0 * np.pi)
    # psi in the physical convention is the carrier phase of the extra path
    assert g.phase_rad(0.3) == pytest.approx(2.0 * np.pi * g.path_delay_m(0.3) / lam)
    assert g.axis == "lateral" and parse_geometry("ground:h=10").axis == "longitudinal"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("wall25", "cannot parse geometry"),
        ("roof:d=3", "unknown reflection geometry 'roof'"),
        ("wall:h=25", "wall geometry takes d=<metres>"),
        ("ground:d=1.5", "ground geometry takes h=<metres>"),
        ("wall:d=-25", "d must be a finite distance > 0 m"),
        ("ground:h=0", "h must be a finite distance > 0 m"),
        ("wall:d=abc", "d must be a number of metres"),
    ],
)
def test_bad_geometry_messages(text, message):
    with pytest.raises(InputError, match=message):
        parse_geometry(text)


# --------------------------------------------------------------------------- thesis cases


def test_thesis_rooftop_wall_25m_orbit_rate():
    """Thesis fig. 4.11 (a): '< 10 %' removed. Its convention gives 13 %; physical gives 2 %."""
    g = parse_geometry("wall:d=25")
    th = check_rotating(g, cutoff_hz=FC_THESIS_HZ, rate=ORBIT, convention="thesis", alpha=0.1)
    ph = check_rotating(g, cutoff_hz=FC_THESIS_HZ, rate=ORBIT, convention="physical", alpha=0.1)
    assert ORBIT.frequency_hz == pytest.approx(2.0 / 86164.0905)
    # harmonics 1, 3, ..., 41 lie below f_c (f_c / f_orbit = 41.1)
    assert th.z == pytest.approx(262.75, abs=0.01)
    assert th.fraction_first_order == pytest.approx(0.1299, abs=0.002)
    assert th.fraction_second_order == pytest.approx(0.1290, abs=0.002)
    assert not th.passed  # the visual '< 10 %' does not survive a number at exactly d = 25 m
    assert ph.z == pytest.approx(1650.9, abs=0.1)
    assert ph.fraction_first_order == pytest.approx(0.0216, abs=0.002)
    assert ph.fraction_below_cutoff < 0.03 and ph.passed
    # the thesis-convention fraction swings around 10 % within +-0.3 m of 25 m
    sw = check_rotating(
        g, cutoff_hz=FC_THESIS_HZ, rate=ORBIT, convention="thesis", distance_tolerance_m=0.15
    )
    lo, hi = sw.fraction_range
    assert lo < 0.10 < hi


def test_thesis_rooftop_ground_1p5m_not_satisfactory_in_both_conventions():
    g = parse_geometry("ground:h=1.5")
    th = check_rotating(g, cutoff_hz=FC_THESIS_HZ, rate=ORBIT, convention="thesis")
    ph = check_rotating(g, cutoff_hz=FC_THESIS_HZ, rate=ORBIT, convention="physical")
    assert th.fraction_first_order > 0.999 and not th.passed  # every harmonic is below f_c
    assert 0.25 < ph.fraction_first_order < 0.35 and not ph.passed


@pytest.mark.parametrize(
    ("mode", "geometry"), [("phugoid", "ground:h=10"), ("spiral", "wall:d=40")]
)
def test_thesis_aircraft_cases_below_one_percent(mode, geometry):
    rate = resolve_rate(mode)
    g = parse_geometry(geometry)
    assert AIRCRAFT_MODES[mode].geometry_kind == g.kind  # longitudinal->ground, lateral->wall
    for conv in ("thesis", "physical"):
        rot = check_rotating(g, cutoff_hz=FC_THESIS_HZ, rate=rate, convention=conv)
        # f_mode > f_c: no harmonic (2n-1) f_mode lies below f_c
        assert rot.fraction_below_cutoff == 0.0 and rot.passed
        osc = check_oscillation(
            g, cutoff_hz=FC_THESIS_HZ, rate=rate, theta0_deg=30.0, convention=conv
        )
        assert osc.fraction_below_cutoff < 0.01 and osc.passed


# --------------------------------------------------------------------------- direct vs expansion


def _direct_vs_expansion(mode, geometry, cutoff_hz, theta0_deg, convention, alpha=0.1):
    rate = resolve_rate(mode)
    g = parse_geometry(geometry)
    amp = rate.mode.amplitude_deg
    exp = check_oscillation(
        g,
        cutoff_hz=cutoff_hz,
        rate=rate,
        theta0_deg=theta0_deg,
        alpha=alpha,
        convention=convention,
    )
    max_rate = math.radians(amp) * 2.0 * math.pi * rate.frequency_hz
    dt = sampling_interval_s(g, max_rate_rad_s=max_rate, convention=convention)
    _, theta, step = oscillation_track(
        rate.frequency_hz, theta0_deg=theta0_deg, amplitude_deg=amp, dt_s=dt, n_periods=64
    )
    d = direct_check(g, theta, step, cutoff_hz=cutoff_hz, alpha=alpha, convention=convention)
    return exp, d


@pytest.mark.parametrize(
    ("mode", "geometry"), [("phugoid", "ground:h=10"), ("spiral", "wall:d=40")]
)
@pytest.mark.parametrize("convention", ["thesis", "physical"])
def test_direct_and_expansion_agree_for_aircraft_cases(mode, geometry, convention):
    f_mode = AIRCRAFT_MODES[mode].frequency_hz
    # the thesis cutoff (all harmonics above it), then cutoffs splitting the harmonic comb
    for fc, th0 in (
        (FC_THESIS_HZ, 30.0),
        (2.5 * f_mode, 30.0),
        (4.5 * f_mode, 60.0),
        (10.5 * f_mode, 0.0),
    ):
        exp, d = _direct_vs_expansion(mode, geometry, fc, th0, convention)
        diff = abs(d.fraction_below_cutoff - exp.fraction_second_order)
        assert diff < 0.02, (fc / f_mode, th0, d.fraction_below_cutoff, exp.fraction_second_order)
        if fc == FC_THESIS_HZ:
            assert d.fraction_below_cutoff < 0.01


def test_direct_agreement_is_not_automatic():
    """The naive thesis-form mapping sin(z_osc sin t) ignores theta0 and disagrees."""
    rate = resolve_rate("spiral")
    fc = 4.5 * rate.frequency_hz
    exp, d = _direct_vs_expansion("spiral", "wall:d=40", fc, 30.0, "physical")
    naive = rotating_harmonics(exp.z_oscillation, kind="wall", alpha=0.1, order=2)
    f_naive = power_fraction_below(naive.orders * rate.frequency_hz, naive.power_rad2, fc)
    assert abs(f_naive - d.fraction_below_cutoff) > 0.02
    assert abs(exp.fraction_second_order - d.fraction_below_cutoff) < 0.005


def test_oscillation_expansion_reproduces_the_signal_and_reduces_to_thesis_form():
    z, alpha = 660.0, 0.1
    phi = np.linspace(0.0, 2.0 * np.pi, 20001)
    for kind, th0 in (("ground", 0.3), ("wall", 1.1)):
        h = oscillation_harmonics(
            z, kind=kind, theta0_rad=th0, amplitude_rad=0.04, alpha=alpha, order=2
        )
        theta = th0 + 0.04 * np.sin(phi)
        psi = z * (np.sin(theta) if kind == "ground" else np.cos(theta))
        assert np.max(np.abs(h.synthesize(phi) - phase_error_rad(psi, alpha, order=2))) < 1e-10
    # ground, theta0 = 0, small A: sin(z sin(A sin phi)) ~ sin(zA sin phi), the thesis form
    a = 1e-3
    h = oscillation_harmonics(z, kind="ground", theta0_rad=0.0, amplitude_rad=a)
    thesis = rotating_harmonics(z * a, kind="ground")
    assert np.allclose(h.power_rad2[thesis.orders], thesis.power_rad2, atol=1e-6)
    assert np.allclose(h.power_rad2[0::2], 0.0, atol=1e-20)  # odd harmonics only


def test_periodogram_and_fraction_basics():
    dt, n = 2.0, 4096
    t = np.arange(n) * dt
    f0 = 50.0 / (n * dt)
    f, p = tapered_periodogram(3.0 + np.sin(2 * np.pi * f0 * t), dt)
    assert p[0] == 0.0
    assert np.sum(p) * (f[1] - f[0]) == pytest.approx(0.5, rel=0.02)  # variance of the sine
    assert power_fraction_below(f, p, 0.8 * f0) < 1e-6
    assert power_fraction_below(f, p, 1.2 * f0) > 1 - 1e-6
    assert power_fraction_below([0.0, 1.0], [5.0, 0.0], 2.0) == 0.0  # no AC power


def test_direct_refuses_a_too_coarse_step():
    g = parse_geometry("wall:d=40")
    _, theta, _ = oscillation_track(3.1e-3, theta0_deg=30, amplitude_deg=2, dt_s=20.0)
    with pytest.raises(InputError, match="too coarse"):
        direct_check(g, theta, 20.0, cutoff_hz=FC_THESIS_HZ)


# --------------------------------------------------------------------------- satellite tracks


def test_direct_along_real_satellite_passes():
    orbit_path = shared_file(ESBC_NAV)
    from psdbound.io import read_orbit

    orbit = read_orbit(orbit_path)
    sats = ["G01", "G05", "G12", "G20", "G25"]
    passes = satellite_passes(orbit, ESBC_XYZ_M, sats=sats, min_duration_s=3 * 3600)
    assert {p.sat for p in passes} <= set(sats) and len(passes) >= 4
    for p in passes:
        assert p.duration_s >= 3 * 3600 and np.degrees(p.elevation_rad.min()) > 5.0
    rep = validate_cutoff(
        ["wall:d=25", "ground:h=1.5"],
        cutoff_hz=FC_THESIS_HZ,
        orbit=orbit,
        receiver_xyz_m=ESBC_XYZ_M,
        sats=sats,
        min_pass_s=3 * 3600,
    )
    sat_rows = [d for d in rep.direct if d.source == "satellite"]
    assert len(sat_rows) == 4 * len(passes)

    def median(label, conv):
        return np.median(
            [
                d.fraction_below_cutoff
                for d in sat_rows
                if (d.geometry.label, d.convention) == (label, conv)
            ]
        )

    # long passes: the wall case removes little in the physical convention, the ground case a lot
    assert median("wall:d=25", "physical") < 0.10
    assert median("ground:h=1.5", "physical") > 0.30
    assert median("ground:h=1.5", "thesis") > 0.99
    with pytest.raises(NoDataError):
        satellite_passes(orbit, ESBC_XYZ_M, sats=["G01"], min_duration_s=20 * 3600)


# --------------------------------------------------------------------------- modes and rates


def test_mode_table_is_user_extendable(tmp_path):
    assert AIRCRAFT_MODES["phugoid"].frequency_hz == 5.5e-3
    assert AIRCRAFT_MODES["spiral"].frequency_hz == 3.1e-3
    assert AIRCRAFT_MODES["phugoid"].geometry_kind == "ground"
    assert AIRCRAFT_MODES["spiral"].geometry_kind == "wall"
    table = mode_table({"dutch_roll": {"frequency_hz": 0.15, "axis": "lateral"}})
    assert resolve_rate("Dutch_Roll", modes=table).mode.geometry_kind == "wall"
    p = tmp_path / "modes.toml"
    p.write_text('[modes.short_period]\nfrequency_hz = 0.2\naxis = "longitudinal"\n')
    assert load_modes(p)["short_period"].geometry_kind == "ground"
    assert "short_period" in mode_table(p) and "phugoid" in mode_table(p)
    assert resolve_rate("orbit-galileo").frequency_hz == pytest.approx(
        ORBIT_RATES_HZ["orbit-galileo"]
    )
    assert resolve_rate("1e-3").frequency_hz == 1e-3


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: resolve_rate("dutch_roll"), "unknown rate 'dutch_roll'"),
        (lambda: resolve_rate("-1"), "rate must be a frequency > 0 Hz"),
        (lambda: DynamicMode("x", 0.0, "lateral"), "frequency_hz must be > 0"),
        (lambda: DynamicMode("x", 1.0, "vertical"), "axis must be 'longitudinal' or 'lateral'"),
        (
            lambda: check_rotating(Reflection("wall", 25), cutoff_hz=0.0, rate=ORBIT),
            "cutoff frequency must be > 0 Hz",
        ),
        (
            lambda: check_rotating(Reflection("wall", 25), cutoff_hz=1e-3, rate=ORBIT, alpha=1.2),
            "alpha must be in",
        ),
        (
            lambda: check_oscillation(
                Reflection("wall", 25), cutoff_hz=1e-3, rate=ORBIT, theta0_deg=30
            ),
            "not an aircraft mode",
        ),
        (lambda: validate_cutoff([], cutoff_hz=1e-3), "at least one reflection geometry"),
    ],
)
def test_bad_input_messages(call, message):
    with pytest.raises(InputError, match=message):
        call()


def test_bad_mode_file(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[modes.x]\naxis = 'lateral'\n")
    with pytest.raises(InputError, match="missing frequency_hz"):
        load_modes(p)
    p.write_text("not = [toml")
    with pytest.raises(InputError, match="invalid TOML"):
        load_modes(p)


def test_pairing_note_when_mode_and_geometry_disagree():
    rep = validate_cutoff(
        ["wall:d=40"], cutoff_hz=FC_THESIS_HZ, rate="phugoid", conventions=("physical",)
    )
    assert any("longitudinal mode" in n for n in rep.notes)


# --------------------------------------------------------------------------- results and CLI


def test_report_dict_is_json_and_labels_conventions():
    rep = validate_cutoff(["wall:d=25"], cutoff_hz=FC_THESIS_HZ, rate="spiral")
    d = json.loads(json.dumps(rep.to_dict()))
    assert d["conventions"] == CONVENTION_LABELS
    rows = d["expansion"] + d["direct"]
    assert {r["convention"] for r in rows} == {"thesis", "physical"}
    for r in rows:
        assert r["z_definition"] == CONVENTION_LABELS[r["convention"]]
        assert r["verdict"] in ("pass", "fail") and 0.0 <= r["fraction_below_cutoff"] <= 1.0
        assert r["threshold"] == 0.10
    assert "thesis" in rep.summary() and "physical" in rep.summary()


def _parser():
    p = argparse.ArgumentParser()
    add_parser(p.add_subparsers(dest="command"))
    return p


def test_cli_writes_table_and_figures(tmp_path, capsys):
    out = tmp_path / "v"
    args = _parser().parse_args(
        [
            "validate",
            "--cutoff-hz",
            "9.55e-4",
            "--geometry",
            "wall:d=25",
            "--geometry",
            "ground:h=1.5",
            "--rate",
            "orbit",
            "--alpha",
            "0.2",
            "--out",
            str(out),
        ]
    )
    assert run(args) == 0
    text = capsys.readouterr().out
    assert "wall:d=25" in text and "FAIL" in text and "physical" in text
    names = sorted(p.name for p in out.iterdir())
    assert names == [
        "validation.csv",
        "validation.html",
        "validation.json",
        "validation_expansion.png",
    ]
    assert (out / "validation_expansion.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    doc = json.loads((out / "validation.json").read_text())
    assert doc["passed"] is False and doc["threshold"] == 0.1 and doc["alpha"] == 0.2
    rows = list(csv.DictReader((out / "validation.csv").open()))
    assert len(rows) == 4
    assert {(r["geometry"], r["convention"]) for r in rows} == {
        (g, c) for g in ("wall:d=25", "ground:h=1.5") for c in ("thesis", "physical")
    }


def test_cli_aircraft_mode_with_user_modes(tmp_path, capsys):
    modes = tmp_path / "m.toml"
    modes.write_text(
        '[modes.slow]\nfrequency_hz = 2e-3\naxis = "longitudinal"\namplitude_deg = 1\n'
    )
    out = tmp_path / "o"
    args = _parser().parse_args(
        [
            "validate",
            "--cutoff-hz",
            "9.55e-4",
            "--geometry",
            "ground:h=10",
            "--rate",
            "slow",
            "--modes",
            str(modes),
            "--convention",
            "physical",
            "--out",
            str(out),
        ]
    )
    assert run(args) == 0
    doc = json.loads((out / "validation.json").read_text())
    assert [r["model"] for r in doc["expansion"]] == ["rotating", "oscillation"]
    (direct,) = doc["direct"]
    assert abs(direct["fraction_below_cutoff"] - direct["expansion_fraction"]) < 0.02
    assert (out / "validation_direct.png").is_file()
    html = (out / "validation.html").read_text()
    assert 'href="validation_direct.png"' in html and "Direct simulation" in html
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporary files left


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--cutoff-hz", "1e-3"], "give at least one --geometry"),
        (["--cutoff-hz", "0", "--geometry", "wall:d=25"], "--cutoff-hz must be > 0"),
        (["--cutoff-hz", "1e-3", "--geometry", "wall:d=-3"], "must be a finite distance > 0"),
        (["--cutoff-hz", "1e-3", "--geometry", "tree:r=3"], "unknown reflection geometry"),
        (["--cutoff-hz", "1e-3", "--geometry", "wall:d=3", "--rate", "dutch"], "unknown rate"),
        (["--cutoff-hz", "1e-3", "--geometry", "wall:d=3", "--nav", "x.rnx"], "--receiver-ecef"),
        (
            ["--cutoff-hz", "1e-3", "--geometry", "wall:d=3", "--sat", "5"],
            "expected a satellite id",
        ),
    ],
)
def test_cli_bad_input_raises_input_error(argv, message):
    args = _parser().parse_args(["validate", *argv])
    with pytest.raises(InputError, match=message):
        run(args)


def test_pass_track_samples_a_fast_turn_finely_enough():
    """A coarse track whose spline turns faster than its sampled rate (an orbit glitch: the
    GLONASS SP3 of OPEC 2022-01-01 stopped a fit with exit 2) is resampled until the phase
    advances at most pi/4 per sample, and the direct check then runs."""
    from psdbound.validation.direct import SatellitePass, pass_track, sampling_interval_s

    t = np.arange(0.0, 7200.0, 30.0)
    el = np.radians(10.0 + 60.0 * t / t[-1])
    el[t >= 3600.0] += np.radians(4.0)  # a jump between two coarse samples
    p = SatellitePass("R10", t, el)
    g = parse_geometry("wall:d=25")
    naive = sampling_interval_s(g, max_rate_rad_s=p.max_rate_rad_s)
    with pytest.raises(InputError, match="too coarse"):
        direct_check(g, p.resample(naive)[1], naive, cutoff_hz=1e-3)
    dt, track = pass_track(p, g)
    assert dt < naive
    psi = g.phase_rad(track, wavelength_m=GPS_L1_WAVELENGTH_M, convention="physical")
    assert np.max(np.abs(np.diff(psi))) <= np.pi / 4
    assert 0.0 <= direct_check(g, track, dt, cutoff_hz=1e-3).fraction_below_cutoff <= 1.0


def test_passes_name_a_missing_system_or_satellite_not_no_pass():
    """'no satellite pass of 60 min' was said for an orbit without the system, or a typo."""
    from types import SimpleNamespace

    from psdbound.validation.direct import satellite_passes

    rx = np.array([4.0e6, 6.0e5, 4.9e6])
    gal = SimpleNamespace(satellites=["E01", "E02"])
    with pytest.raises(InputError, match="no satellite of system G .it holds E"):
        satellite_passes(gal, rx, system="G", span_gps_s=(0.0, 60.0))
    with pytest.raises(InputError, match="satellite.s. G99 not in the orbit file"):
        satellite_passes(gal, rx, sats=["G99"], span_gps_s=(0.0, 60.0))
