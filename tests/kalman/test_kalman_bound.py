"""The bound object: result-file reading, validation, state-space export, white-noise
conventions and elevation mapping."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import trapezoid

from psdbound.errors import InputError
from psdbound.kalman import ErrorProcess, GaussMarkovBound
from psdbound.spectra.bound import fit_bound
from psdbound.spectra.models import gm_acf, gm_psd_sampled, white_psd
from psdbound.stationarity.mapping import THESIS_MAPPING, ElevationMapping

# (sigma_gm, tau, sigma_wn, data dt, filter dt)
SS_CASES = [
    (0.005, 45.0, 0.002, 1.0, 1.0),  # thesis DA
    (0.04, 70.0, 0.009, 30.0, 30.0),  # thesis DF at 30 s
    (0.01, 10.0, 0.001, 1.0, 5.0),  # filter slower than the data
    (0.02, 300.0, 0.0, 30.0, 1.0),  # filter faster, no white noise
    (0.003, 2.0, 0.004, 0.5, 0.5),  # dt comparable to tau
]


def result_doc(**over):
    doc = {
        "schema_version": "1",
        "bound": {
            "sigma_gm_m": 0.005,
            "tau_s": 45.0,
            "sigma_wn_m": 0.002,
            "n_wn_two_sided_m2_hz": 0.002**2 * 30.0,
            "dt_s": 30.0,
        },
        "sampling": {"interval_s": 30.0, "nyquist_hz": 1.0 / 60.0},
        "mapping": {"a": 1.0, "b": 29.0, "c_deg": 10.0},
        # the rest of a schema-1 document (psdbound.results.REQUIRED_FIELDS); not read here
        "method": "DA",
        "cutoff": {"f_c_hz": None, "source": "none"},
        "windows": {"count": 0, "total_duration_s": 0.0, "per_window": []},
        "validation": {},
        "warnings": [],
        "provenance": {
            "inputs": [],
            "versions": {},
            "configuration": {},
            "created_utc": "2026-01-01T00:00:00+00:00",
            "anything": "ignored",
        },
        "figures": {},
    }
    for k, v in over.items():
        sec, _, key = k.partition("__")
        if key:
            if v is KeyError:
                del doc[sec][key]
            else:
                doc[sec][key] = v
        elif v is KeyError:
            del doc[sec]
        else:
            doc[sec] = v
    return doc


# --------------------------------------------------------------------------- bound object
def test_from_result_reads_the_schema(tmp_path):
    p = tmp_path / "result.json"
    p.write_text(json.dumps(result_doc()))
    b = GaussMarkovBound.from_result(p)
    assert (b.sigma_gm_m, b.tau_s, b.sigma_wn_m, b.dt_s) == (0.005, 45.0, 0.002, 30.0)
    assert b.n_wn_two_sided_m2_hz == pytest.approx(0.002**2 * 30.0, rel=1e-15)
    assert b.nyquist_hz == pytest.approx(1 / 60)
    assert b.mapping == ElevationMapping(1.0, 29.0, 10.0)
    assert b.source == str(p)
    p.write_text(json.dumps(result_doc(mapping=None)))
    assert GaussMarkovBound.from_result(p).mapping is None


@pytest.mark.parametrize(
    ("over", "message"),
    [
        # schema version and required fields: psdbound.results.read_document
        ({"bound__tau_s": KeyError}, "lacks the field 'bound.tau_s'"),
        ({"sampling": KeyError}, "lacks the field 'sampling'"),
        ({"mapping": KeyError}, "lacks the field 'mapping'"),
        ({"schema_version": "2"}, "result schema version '2' is not supported"),
        ({"schema_version": 1}, "result schema version 1 is not supported"),
        ({"schema_version": KeyError}, "not a psdbound result: it has no schema_version"),
        ({"bound": [1, 2]}, "lacks the field 'bound.sigma_gm_m'"),
        # the bound's own checks
        ({"bound__dt_s": KeyError}, "missing key 'bound.dt_s'"),
        ({"mapping__c_deg": KeyError}, "missing key 'mapping.c_deg'"),
        ({"mapping": 5}, "key 'mapping' must hold a JSON object"),
        ({"bound__sigma_gm_m": -0.001}, "'bound.sigma_gm_m' must be >= 0"),
        ({"bound__sigma_wn_m": -1.0}, "'bound.sigma_wn_m' must be >= 0"),
        ({"bound__tau_s": 0.0}, "'bound.tau_s' must be > 0"),
        ({"bound__dt_s": "30"}, "'bound.dt_s' must be a finite number"),
        ({"bound__n_wn_two_sided_m2_hz": 1.0}, "disagrees with sigma_wn_m^2 * dt_s"),
        ({"sampling__interval_s": 1.0}, "'sampling.interval_s' = 1.0 disagrees"),
        ({"sampling__nyquist_hz": 0.5}, "'sampling.nyquist_hz' = 0.5 disagrees"),
    ],
)
def test_from_result_specific_errors(tmp_path, over, message):
    p = tmp_path / "result.json"
    p.write_text(json.dumps(result_doc(**over)))
    with pytest.raises(InputError) as e:
        GaussMarkovBound.from_result(p)
    assert message in str(e.value)
    assert str(p) in str(e.value)


def test_from_result_not_json_or_missing(tmp_path):
    p = tmp_path / "result.json"
    # messages of psdbound.results.read_document
    p.write_text("sigma_gm_m = 0.005\n")
    with pytest.raises(InputError, match="not a JSON result file") as e:
        GaussMarkovBound.from_result(p)
    assert "line 1" in str(e.value) and str(p) in str(e.value)
    p.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(InputError, match="not a JSON result file"):
        GaussMarkovBound.from_result(p)
    p.write_text("[1, 2]")
    with pytest.raises(InputError, match="top level is not an object"):
        GaussMarkovBound.from_result(p)
    with pytest.raises(InputError, match="result file not found"):
        GaussMarkovBound.from_result(tmp_path / "absent.json")


def test_from_params_validation_and_from_fit():
    with pytest.raises(InputError, match="sigma_gm_m must be >= 0"):
        GaussMarkovBound.from_params(-1.0, 45.0, 0.0, 1.0)
    with pytest.raises(InputError, match="tau_s must be > 0"):
        GaussMarkovBound.from_params(0.01, 0.0, 0.0, 1.0)
    with pytest.raises(InputError, match="dt_s must be > 0"):
        GaussMarkovBound.from_params(0.01, 10.0, 0.0, -1.0)
    with pytest.raises(InputError, match="must be finite"):
        GaussMarkovBound.from_params(0.01, math.inf, 0.0, 1.0)
    b = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0)
    with pytest.raises(InputError, match="unknown white_noise mode"):
        b.to_state_space(1.0, white_noise="flat")
    with pytest.raises(InputError, match="no elevation mapping"):
        b.to_state_space(1.0, elevation_deg=30.0)
    # from a real fit: same PSD as the BoundFit
    dt = 1.0
    f = np.linspace(1e-3, 0.5, 300)
    s = gm_psd_sampled(f, 0.005, 45.0, dt) + white_psd(f, 0.002, dt)
    from types import SimpleNamespace

    fit = fit_bound([SimpleNamespace(f_hz=f, psd_m2_hz=s)], dt)
    gb = GaussMarkovBound.from_fit(fit, mapping=THESIS_MAPPING)
    np.testing.assert_allclose(gb.sampled_psd(f), fit.psd(f), rtol=1e-13)
    assert gb.total_variance_m2 == pytest.approx(fit.total_variance_m2, rel=1e-13)
    assert gb.params() == pytest.approx(fit.params())
    assert "tau=" in str(gb)


@pytest.mark.parametrize(("sigma", "tau", "sigma_wn", "dt_data", "dt"), SS_CASES)
def test_state_space_reproduces_acf_and_sampled_psd(sigma, tau, sigma_wn, dt_data, dt):
    b = GaussMarkovBound.from_params(sigma, tau, sigma_wn, dt_data)
    phi, qd, r = b.to_state_space(dt, white_noise="psd")
    assert phi == pytest.approx(math.exp(-dt / tau), rel=1e-15)
    assert r == pytest.approx(sigma_wn**2 * dt_data / dt, rel=1e-14)  # N_WN / dt
    # autocorrelation of the AR(1) recursion at lags k dt == continuous sigma^2 exp(-k dt/tau)
    lags = np.arange(0, 400)
    stationary = qd / (1 - phi**2)
    acf_ss = stationary * phi**lags
    np.testing.assert_allclose(acf_ss, gm_acf(lags * dt, sigma, tau), rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(
        b.acf(lags * dt, dt, white_noise="psd"),
        acf_ss + np.where(lags == 0, r, 0.0),
        rtol=1e-12,
        atol=1e-300,
    )
    proc = ErrorProcess.from_bound(b, dt, white_noise="psd")
    np.testing.assert_allclose(
        proc.acf(lags.size), b.acf(lags * dt, dt, white_noise="psd"), rtol=1e-10, atol=1e-300
    )
    # PSD of the state-space model (transfer function of (Phi, Qd, R)) == sampled bound PSD
    nyq = 0.5 / dt
    f = np.r_[0.0, np.geomspace(nyq * 1e-5, nyq, 400)]
    expected = gm_psd_sampled(f, sigma, tau, dt) + white_psd(f, math.sqrt(r), dt)
    np.testing.assert_allclose(proc.psd(f), expected, rtol=1e-9)
    np.testing.assert_allclose(b.sampled_psd(f, dt, white_noise="psd"), expected, rtol=1e-13)
    # ... == 2 dt * (two-sided sum of the autocovariance): ACF and PSD agree
    k = np.arange(1, 20000)
    r_k = stationary * phi**k
    two_sided = dt * (stationary + r + 2 * np.cos(2 * np.pi * np.outer(f[::40], k) * dt) @ r_k)
    np.testing.assert_allclose(2 * two_sided, expected[::40], rtol=1e-8)
    # variance = integral over [0, f_N]
    fg = np.linspace(0, nyq, 200001)
    assert trapezoid(b.sampled_psd(fg, dt, white_noise="psd"), fg) == pytest.approx(
        sigma**2 + r, rel=1e-5
    )


def test_state_space_matches_simulation():
    b = GaussMarkovBound.from_params(0.01, 20.0, 0.004, 1.0)
    x = b.simulate(400, 2.0, n_series=3000, rng=1)
    emp = np.array([np.mean(x[:, 100:300] * x[:, 100 + k : 300 + k]) for k in (0, 1, 5, 20)])
    np.testing.assert_allclose(emp, b.acf(np.array([0, 1, 5, 20]) * 2.0, 2.0), rtol=0.05)


def test_white_noise_conventions_for_another_interval():
    b = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0)
    # filter at 5 s: "psd" keeps N_WN (averaging), "per_sample" keeps sigma_wn^2 (decimation)
    assert b.white_variance_m2(5.0, white_noise="psd") == pytest.approx(0.002**2 / 5)
    assert b.white_variance_m2(5.0) == pytest.approx(0.002**2)  # default: conservative
    assert b.white_variance_m2(5.0, white_noise="per_sample") == pytest.approx(0.002**2)
    assert b.white_variance_m2(5.0, white_noise="conservative") == pytest.approx(0.002**2)
    assert b.white_variance_m2(0.5, white_noise="conservative") == pytest.approx(0.002**2 * 2)
    for mode in ("psd", "per_sample", "conservative"):
        assert b.white_variance_m2(1.0, white_noise=mode) == pytest.approx(0.002**2)
    # the flat PSD level 2 N_WN is invariant under "psd"
    f = np.array([0.05])
    for dt in (0.2, 1.0, 7.0):
        white = b.sampled_psd(f, dt, white_noise="psd") - gm_psd_sampled(f, 0.005, 45.0, dt)
        assert white[0] == pytest.approx(2 * b.n_wn_two_sided_m2_hz, rel=1e-9)
    # decimating by k folds the data-rate bound PSD: that is the "per_sample" model at k dt
    k = 5
    dtf = 5.0
    f = np.linspace(0, 0.5 / dtf, 101)
    folded = np.zeros_like(f)
    for j in range(k):
        g = np.mod(f + j / dtf, 1.0)
        folded += b.sampled_psd(np.minimum(g, 1.0 - g), 1.0)
    np.testing.assert_allclose(b.sampled_psd(f, dtf, white_noise="per_sample"), folded, rtol=1e-10)


def test_elevation_mapping_scales_sigma():
    b = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0, mapping=THESIS_MAPPING)
    m = float(THESIS_MAPPING.factor(15.0))
    be = b.at_elevation(15.0)
    assert be.sigma_gm_m == pytest.approx(0.005 * m)
    assert be.sigma_wn_m == pytest.approx(0.002 * m)
    assert be.tau_s == b.tau_s and be.mapping is None
    phi, qd, r = b.to_state_space(1.0, elevation_deg=[15.0, 90.0])
    np.testing.assert_allclose(qd, [be.to_state_space(1.0).qd_m2, b.to_state_space(1.0).qd_m2])
    np.testing.assert_allclose(r, [be.to_state_space(1.0).r_m2, b.to_state_space(1.0).r_m2 * 1.0])
    assert b.at_elevation(90.0).sigma_gm_m == pytest.approx(0.005, rel=1e-12)
    with pytest.raises(InputError, match="no elevation mapping"):
        be.at_elevation(20.0)


def test_export_refuses_a_not_bounded_result_and_gives_p0(tmp_path):
    p = tmp_path / "result.json"
    doc = result_doc()
    doc.update(verdict="not-bounded", verdict_reasons=["tau at the end of its grid"])
    p.write_text(json.dumps(doc))
    with pytest.raises(InputError, match="not-bounded.*tau at the end of its grid"):
        GaussMarkovBound.from_result(p)
    b = GaussMarkovBound.from_result(p, allow_not_bounded=True)
    ss = b.to_state_space(30.0)
    assert ss.p0_m2 == pytest.approx(b.sigma_gm_m**2, rel=1e-12)
    phi, qd, r = ss  # still unpacks as three
    assert qd == pytest.approx(b.sigma_gm_m**2 * (1 - phi**2))


def test_filter_step_shorter_than_the_data_interval_warns():
    b = GaussMarkovBound.from_params(0.004, 60.0, 0.001, 30.0)
    with pytest.warns(UserWarning, match="shorter than the data interval"):
        b.to_state_space(1.0)


def test_library_entries_refuse_what_they_cannot_use():
    """from_fit takes a bound_series result; counts, intervals and elevations are checked."""
    import psdbound

    rng = np.random.default_rng(3)
    res = psdbound.bound_series([rng.normal(0, 0.002, 512) for _ in range(8)], 1.0)
    kb = GaussMarkovBound.from_fit(res)
    assert (kb.sigma_gm_m, kb.tau_s) == (res.bound.sigma_gm_m, res.bound.tau_s)
    with pytest.raises(InputError, match="from_fit takes the result of psdbound.bound_series"):
        GaussMarkovBound.from_fit(None)
    with pytest.raises(InputError, match="n_samples must be an integer >= 1"):
        kb.simulate(2.7)
    with pytest.raises(InputError, match="n_series must be an integer >= 1"):
        kb.simulate(10, n_series=0)
    for bad in ("1", True):
        with pytest.raises(InputError, match="filter interval dt_s must be a number > 0 s"):
            kb.to_state_space(bad)
    with pytest.raises(InputError, match=r"in \[0, 90\]"):
        kb.mapping_factor([-5.0, 100.0])
