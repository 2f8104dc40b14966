"""Simulator: injected statistics, round trip through RINEX, determinism, demo cache."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.arcs import find_arcs
from psdbound.cli import main
from psdbound.errors import InputError
from psdbound.io import read_obs, read_orbit
from psdbound.isolation import isolate_dual_antenna, isolate_dual_frequency
from psdbound.simulate import MultipathModel, demo_data, gauss_markov, preset, simulate

FC = 9.55e-4


def ar1_estimates(x, dt):
    x = x - x.mean(axis=0)
    sigma = np.sqrt(np.mean(x**2))
    rho = np.sum(x[1:] * x[:-1]) / np.sum(x[:-1] ** 2)
    return sigma, -dt / np.log(rho)


@pytest.mark.parametrize(("sigma", "tau", "dt"), [(0.004, 30.0, 1.0), (0.01, 70.0, 1.0)])
def test_gauss_markov_statistics(sigma, tau, dt):
    x = gauss_markov(400_000, sigma, tau, dt, np.random.default_rng(0))[:, 0]
    s_hat, tau_hat = ar1_estimates(x, dt)
    assert s_hat == pytest.approx(sigma, rel=0.05)
    assert tau_hat == pytest.approx(tau, rel=0.10)


def test_injected_multipath_has_requested_sigma_and_tau(tmp_path):
    mp = MultipathModel(sigma_gm_m=0.004, tau_s=40.0, sigma_wn_m=0.0, b=0.0)
    sc = preset("short").replace(
        multipath=mp, receiver_noise_m=0.0, dual_antenna=False, duration_s=3 * 3600.0
    )
    res = simulate(sc, tmp_path)
    sig, taus = [], []
    for j in range(len(res.sats)):
        for f in range(2):
            x = res.truth_m[0, :, j, f]
            ok = np.isfinite(x)
            if ok.sum() > 3600 and ok[np.argmax(ok) :].all() is not None:
                seg = x[ok]
                s_hat, tau_hat = ar1_estimates(seg, 1.0)
                sig.append(s_hat)
                taus.append(tau_hat)
    print(
        f"pooled over {len(sig)} series: sigma {np.median(sig):.5f} m, tau {np.median(taus):.1f} s"
    )
    assert np.median(sig) == pytest.approx(0.004, rel=0.10)
    assert np.median(taus) == pytest.approx(40.0, rel=0.10)


@pytest.fixture(scope="module")
def round_trip(tmp_path_factory):
    sc = preset("short").replace(
        multipath=MultipathModel(sigma_gm_m=0.004, tau_s=5.0, sigma_wn_m=0.001)
    )
    out = tmp_path_factory.mktemp("rt")
    res = simulate(sc, out)
    oa, ob = read_obs(res.obs_paths[0]), read_obs(res.obs_paths[1])
    return res, oa, ob, read_orbit(res.nav_path)


def test_round_trip_dual_frequency(round_trip):
    res, oa, _, nav = round_trip
    idx = {s: j for j, s in enumerate(res.sats)}
    arcs = find_arcs(oa, ("L1C", "L2W"), orbit=nav, elevation_mask_deg=10.0)
    series = isolate_dual_frequency(arcs, FC)
    assert series.n_arcs >= 5
    for a in series.arcs():
        j, k = idx[a.sats], np.searchsorted(res.t_gps_s, a.t_gps_s)
        truth = (res.truth_m[0, k, j, 0] - res.truth_m[0, k, j, 1]) / np.sqrt(2)
        r = np.corrcoef(a.value_m, truth)[0, 1]
        err = np.sqrt(np.mean((a.value_m - truth) ** 2) / np.mean(truth**2))
        print(f"DF {a.sats}: correlation {r:.3f}, RMS error {100 * err:.1f} %")
        assert r >= 0.9 and err <= 0.2
        np.testing.assert_allclose(a.elevation_deg, res.elevation_deg[0, k, j], atol=1e-6)


def test_round_trip_dual_antenna(round_trip):
    res, oa, ob, nav = round_trip
    idx = {s: j for j, s in enumerate(res.sats)}
    series = isolate_dual_antenna(oa, ob, nav)
    assert series.n_arcs >= 4
    for a in series.arcs():
        si, sr = a.sats.split("-")
        k = np.searchsorted(res.t_gps_s, a.t_gps_s)
        tr = res.truth_m[:, k][..., 0]
        truth = (tr[0, :, idx[si]] - tr[1, :, idx[si]]) - (tr[0, :, idx[sr]] - tr[1, :, idx[sr]])
        truth = (truth - truth.mean()) / 2
        r = np.corrcoef(a.value_m, truth)[0, 1]
        err = np.sqrt(np.mean((a.value_m - truth) ** 2) / np.mean(truth**2))
        assert r >= 0.9 and err <= 0.2, (a.sats, r, err)


def test_dual_antenna_cancellation(tmp_path):
    """More common multipath -> smaller DA residual (the thesis's caveat)."""
    rms = {}
    for frac in (0.0, 0.9):
        sc = preset("short").replace(common_fraction=frac, duration_s=3600.0, slip_rate_per_h=0)
        res = simulate(sc, tmp_path / f"c{frac}")
        s = isolate_dual_antenna(
            read_obs(res.obs_paths[0]), read_obs(res.obs_paths[1]), read_orbit(res.nav_path)
        )
        rms[frac] = np.sqrt(np.mean(s.value_m**2))
    print(rms)
    assert rms[0.9] < 0.5 * rms[0.0]


def test_same_seed_same_bytes_different_seed_different(tmp_path):
    sc = preset("short").replace(duration_s=900.0)
    a = simulate(sc, tmp_path / "a")
    b = simulate(sc, tmp_path / "b")
    c = simulate(sc.replace(seed=sc.seed + 1), tmp_path / "c")
    for pa, pb, pc in zip(
        (*a.obs_paths, a.nav_path, a.truth_path, a.truth_json_path),
        (*b.obs_paths, b.nav_path, b.truth_path, b.truth_json_path),
        (*c.obs_paths, c.nav_path, c.truth_path, c.truth_json_path),
        strict=True,
    ):
        assert pa.read_bytes() == pb.read_bytes(), pa.name
        if pa.name.endswith("_MO.rnx.gz") or "truth" in pa.name:
            assert pa.read_bytes() != pc.read_bytes(), pa.name


def test_demo_cache_generated_once(tmp_path, monkeypatch):
    monkeypatch.setenv("PSDBOUND_CACHE", str(tmp_path))
    d1 = demo_data()
    assert all(p.is_file() for p in (*d1.obs_paths, d1.nav_path, d1.truth_json_path))
    stamp = d1.obs_paths[0].stat().st_mtime_ns
    d2 = demo_data()
    assert d2.obs_paths == d1.obs_paths and d2.obs_paths[0].stat().st_mtime_ns == stamp
    assert d1.truth_meta()["seed"] == 2020
    assert not list(tmp_path.glob(".demo-*"))  # no half-written folder left


def test_cli_simulate_and_bad_input(tmp_path, capsys):
    out = tmp_path / "sim"
    assert main(["simulate", "--preset", "short", "--duration-h", "0.1", "--out", str(out)]) == 0
    printed = capsys.readouterr().out.split()
    assert len(printed) == 5 and all(
        (tmp_path / "sim").joinpath(p.split("/")[-1]).is_file() for p in printed
    )
    assert main(["simulate", "--preset", "nope"]) == 2
    with pytest.raises(InputError, match="latitude"):
        preset("short").replace(lat_deg=95.0)


def test_nominal_records_match_the_ionosphere_constellation():
    """Two independent nominal GPS implementations (records vs direct) agree to 1 cm."""
    from psdbound.io.nominal import nominal_navigation
    from psdbound.io.timescales import calendar_to_gps_s
    from psdbound.ionosphere import nominal_constellation

    t0 = float(calendar_to_gps_s(2020, 6, 25, 0, 0, 0.0))
    t = t0 + np.arange(0.0, 86400.0, 600.0)
    nav, direct = nominal_navigation(t0, t0 + 86400.0), nominal_constellation("G")
    for sat in ("G01", "G07", "G13", "G24"):
        d = np.linalg.norm(nav.positions_ecef_m(sat, t) - direct.positions_ecef_m(sat, t), axis=1)
        assert d.max() < 0.01, sat
