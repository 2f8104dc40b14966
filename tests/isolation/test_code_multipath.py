"""Code multipath by carrier levelling: closed form, RINEX 2, errors, and gnssmultipath."""

from __future__ import annotations

import gzip
import time
import warnings
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, UPC1_OBS, UPC_NAV, shared_file

from psdbound.arcs import find_arcs
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError, NoDataError
from psdbound.io import ObsHeader, read_obs, read_orbit
from psdbound.io.obs import Observations, SystemBlock
from psdbound.io.signals import carrier_frequency_hz
from psdbound.isolation import isolate_code_multipath, level_shifts, rms_by_satellite

# ---------------------------------------------------------------- synthetic observations

SYSTEMS = {  # codes (P_i, P_j, Phi_i, Phi_j) and satellites of each synthetic system
    "G": (("C1C", "C2W", "L1C", "L2W"), ("G07", "G21")),
    "E": (("C1C", "C5Q", "L1C", "L5Q"), ("E11", "E24")),
    "R": (("C1C", "C2P", "L1C", "L2P"), ("R03", "R17")),  # FDMA/FDMA: f1/f2 = 9/7 for all k
    "R3": (("C1C", "C3Q", "L1C", "L3Q"), ("R03", "R17")),  # FDMA/CDMA: coefficients per satellite
}
GLONASS_K = {"R03": -7, "R17": 6}  # FDMA channels: wavelengths differ per satellite


def rms(v):
    return float(np.sqrt(np.mean(np.square(v))))


def synthetic(
    system="G",
    *,
    n=960,
    dt=30.0,
    seed=0,
    mp_m=0.5,
    noise_m=0.2,
    iono_m=15.0,
    slip_at=400,
    extra_codes=(),
    drop_codes=(),
):
    """Two satellites: code = range + I + MP, phase = range - I + N lambda (metres).

    Per satellite: a common geometric range, an ionosphere ramp with a bend
    (``iono_m`` metres on band i over the span, scaled by (f_i/f_b)^2 on band
    b, +I on code, -I on phase), integer ambiguities, a slip of 7 cycles on
    Phi_i at ``slip_at`` (two arcs), code multipath = sinusoid + white noise
    on P_i and P_j (other codes none). P_i of the first satellite is blank at
    5 epochs and 0 at one.
    Returns the observations and the injected multipath per satellite.
    """
    rng = np.random.default_rng(seed)
    (ci, cj, li, lj), sats = SYSTEMS[system]
    system = system[0]
    codes = tuple(c for c in (ci, cj, li, lj, *extra_codes) if c not in drop_codes)
    t = 1.3e9 + dt * np.arange(n)
    x = (t - t[0]) / (t[-1] - t[0])
    v = np.full((n, len(sats), len(codes)), np.nan)
    truth = {}
    for s, sat in enumerate(sats):
        fi, fj = (carrier_frequency_hz(sat, c, GLONASS_K) for c in (li, lj))
        rho = 2.1e7 + 3.0e6 * np.sin(np.pi * x + s)
        ii = 2.0 + iono_m * (x + 0.3 * x**2)
        mp = [
            mp_m * np.sin(2 * np.pi * (t - t[0]) / rng.uniform(300, 900) + rng.uniform(0, 6))
            + rng.normal(0.0, noise_m, n)
            for _ in range(2)
        ]
        n_i, n_j = rng.integers(-(10**6), 10**6, 2)
        slip = np.where(np.arange(n) >= slip_at, 7, 0) if slip_at else 0
        cols = {ci: mp[0], cj: mp[1], li: slip + n_i, lj: n_j}  # on top of range and ionosphere
        for k, c in enumerate(codes):
            fb = carrier_frequency_hz(sat, c, GLONASS_K)
            ib = ii * (fi / fb) ** 2
            if c[0] == "C":
                v[:, s, k] = rho + ib + cols.get(c, 0.0)
            else:
                v[:, s, k] = (rho - ib) * fb / 299792458.0 + cols.get(c, 1000.0)
        truth[sat] = mp
    if ci in codes and n > 200:
        v[100:105, 0, codes.index(ci)] = np.nan
        v[200, 0, codes.index(ci)] = 0.0
    lli = np.where(np.isfinite(v), 0, -1).astype(np.int8)
    header = ObsHeader(
        version=3.04,
        file_system=system,
        marker_name="SYN",
        receiver_type="",
        antenna_type="",
        approx_position_m=None,
        antenna_delta_hen_m=np.zeros(3),
        interval_s=dt,
        time_system="GPS",
        obs_types={system: codes},
        glonass_channels=dict(GLONASS_K) if system == "R" else {},
    )
    block = SystemBlock(system, sats, codes, v, lli, lli.copy())
    obs = Observations("synthetic.rnx", header, t, np.zeros(n, np.int8), {system: block})
    return obs, truth


def expected(obs, truth, series, weights):
    """Injected multipath, ``w_i MP_i + w_j MP_j`` per satellite, minus its mean over each arc."""
    out = np.empty_like(series.value_m)
    for (lo, hi), sat in zip(series.arc_bounds(), series.arc_sats, strict=True):
        k = np.searchsorted(obs.t_gps_s, series.t_gps_s[lo:hi])
        wi, wj = weights(sat)
        mp = wi * truth[sat][0][k] + wj * truth[sat][1][k]
        out[lo:hi] = mp - mp.mean()
    return out


@pytest.mark.parametrize("system", list(SYSTEMS))
@pytest.mark.parametrize("seed", [0, 1])
def test_single_code_recovers_injected_multipath_minus_arc_mean(system, seed):
    obs, truth = synthetic(system, seed=seed)
    s = isolate_code_multipath(obs, "C1C")
    (_, _, li, lj), sats = SYSTEMS[system]
    coef = s.meta["coefficients"]
    assert s.method == "CODE" and s.scaling == 1.0 and s.cutoff_hz is None
    assert s.unfiltered_m is None and s.signals == ("C1C", li, lj)
    assert s.meta["phases"] == (li, lj) and s.meta["code_missing_samples"] == 6
    assert s.n_arcs == 4 and s.meta["arcs_in"] == 4  # the slip splits each satellite
    assert np.isnan(s.elevation_deg).all() and not s.meta["has_elevation"]
    err = s.value_m - expected(obs, truth, s, lambda sat: (1.0, 0.0))
    assert np.abs(err).max() < 1e-3, np.abs(err).max()
    got = rms_by_satellite(s)
    assert list(got) == sorted(sats)
    for sat in sats:
        assert got[sat] == pytest.approx(rms(s.value_m[np.asarray(s.arc_sats)[s.arc_id] == sat]))
    if system == "R3":  # per-satellite coefficients, as many values as satellites
        assert set(coef["Phi_j"]) == set(sats) and len(set(coef["Phi_j"].values())) == 2
    else:
        f = [carrier_frequency_hz(sats[0], c, GLONASS_K) for c in (li, lj)]
        assert coef["Phi_j"] == pytest.approx(2 / ((f[0] / f[1]) ** 2 - 1), rel=1e-12)


@pytest.mark.parametrize("system", list(SYSTEMS))
def test_ionosphere_free_recovers_injected_combination(system):
    obs, truth = synthetic(system, seed=3)
    (ci, cj, li, lj), sats = SYSTEMS[system]
    s = isolate_code_multipath(obs, (ci, cj))
    assert s.method == "CODE-IF" and s.signals == (ci, cj, li, lj)

    def weights(sat):
        fi, fj = (carrier_frequency_hz(sat, c, GLONASS_K) for c in (li, lj))
        return fi**2 / (fi**2 - fj**2), -(fj**2) / (fi**2 - fj**2)

    err = s.value_m - expected(obs, truth, s, weights)
    assert np.abs(err).max() < 1e-3, np.abs(err).max()
    assert len({np.round(weights(sat), 12).tobytes() for sat in sats}) == (
        2 if system == "R3" else 1
    )


@pytest.mark.parametrize("codes", ["C1C", ("C1C", "C2W")])
@pytest.mark.parametrize("iono_m", [5.0, 40.0])
def test_ionosphere_ramp_is_removed(codes, iono_m):
    """No multipath injected: the result is zero although code-minus-carrier drifts by 2 I."""
    obs, _ = synthetic("G", mp_m=0.0, noise_m=0.0, iono_m=iono_m, seed=5)
    s = isolate_code_multipath(obs, codes)
    assert np.abs(s.value_m).max() < 1e-3
    cmc = obs.get("G21", "C1C") - obs.phase_m("G21", "L1C")
    cmc = cmc[:400] - cmc[:400].mean()  # first arc, without the slip
    assert np.ptp(cmc) > 0.5 * iono_m  # the ramp the combination removed


def test_outliers_are_counted_and_warned_not_dropped():
    obs, _ = synthetic("G", seed=2)
    v = obs.blocks["G"].values
    v[600, 1, 0] += 80.0  # G21 C1C: a gross code error in the second arc
    with pytest.warns(PsdboundWarning, match=r"G21 arc \d+ .*beyond 30 m"):
        s = isolate_code_multipath(obs, "C1C")
    assert s.meta["outlier_samples_gt_m"] == {"G21": 1}
    assert s.meta["outlier_threshold_m"] == 30.0
    assert np.abs(s.value_m).max() > 70.0  # kept
    assert s.t_gps_s.size == 2 * 960 - 6


def test_arcs_short_after_code_loss_are_dropped_and_counted():
    obs, _ = synthetic("G", seed=4, n=200, slip_at=None)
    obs.blocks["G"].values[30:, 0, 0] = np.nan  # G07 keeps 30 epochs (15 min) of C1C
    s = isolate_code_multipath(obs, "C1C", min_length_s=1200.0)
    assert s.arc_sats == ("G21",)
    assert s.meta["arcs_dropped_code_missing"] == 1
    assert s.meta["code_missing_samples"] == 170
    obs.blocks["G"].values[:, :, 0] = np.nan
    with pytest.raises(NoDataError, match="C1C"):
        isolate_code_multipath(obs, "C1C")


@pytest.mark.parametrize(
    "code, phases",
    [
        ("C1C", ("L1C", "L2W")),
        ("C1W", ("L1C", "L2W")),
        ("C2W", ("L2W", "L1C")),
        ("C2L", ("L2L", "L1C")),
    ],
)
def test_default_phases(code, phases):
    obs, _ = synthetic("G", seed=6, extra_codes=("C1W", "C2L", "L2L"))
    assert isolate_code_multipath(obs, code).meta["phases"] == phases


# ---------------------------------------------------------------- errors


def test_unknown_code_names_it_and_the_available_codes():
    obs, _ = synthetic("G")
    with pytest.raises(InputError, match=r"'C9Z'.*available: C1C C2W L1C L2W"):
        isolate_code_multipath(obs, "C9Z")


def test_code_without_phase_on_its_band():
    obs, _ = synthetic("G", extra_codes=("C5Q",))
    with pytest.raises(InputError, match=r"band 5 .* C5Q.*phases in the file: L1C L2W"):
        isolate_code_multipath(obs, "C5Q")


def test_no_second_carrier():
    obs, _ = synthetic("G", drop_codes=("L2W",))
    with pytest.raises(InputError, match="second carrier"):
        isolate_code_multipath(obs, "C1C")


@pytest.mark.parametrize(
    "codes, phases, match",
    [
        (("C1C", "C1W"), None, "same band"),
        ("L1C", None, "not a pseudorange"),
        ("C1C", ("L2W", "L1C"), "do not match"),
        ("C1C", ("L1C", "L1C"), "same band"),
        ("C1C", ("L1C",), "pair"),
        (("C1C", "C2W", "C1W"), None, "one or two"),
    ],
)
def test_bad_code_or_phase_choices(codes, phases, match):
    obs, _ = synthetic("G", extra_codes=("C1W",))
    with pytest.raises(InputError, match=match):
        isolate_code_multipath(obs, codes, phases=phases)


def test_several_systems_need_system():
    obs, _ = synthetic("G")
    e, _ = synthetic("E")
    both = Observations(
        obs.path,
        obs.header,
        obs.t_gps_s,
        obs.epoch_flag,
        {"G": obs.blocks["G"], "E": e.blocks["E"]},
    )
    with pytest.raises(InputError, match="give system"):
        isolate_code_multipath(both, "C1C")
    assert isolate_code_multipath(both, "C1C", system="E").arc_sats[0] == "E11"


# ---------------------------------------------------------------- RINEX 2 (UPC1)


@pytest.fixture(scope="module")
def upc():
    return read_obs(shared_file(UPC1_OBS)), read_orbit(shared_file(UPC_NAV))


@pytest.mark.realdata
@pytest.mark.parametrize(
    "code, signals",
    [
        ("C1", ("C1", "L1", "L2")),
        ("P2", ("P2", "L2", "L1")),
        ("P1", ("P1", "L1", "L2")),
        ("C2W", ("P2", "L2", "L1")),
    ],
)
def test_rinex2(upc, code, signals):
    obs, nav = upc
    s = isolate_code_multipath(obs, code, orbit=nav, elevation_mask_deg=5.0)
    assert s.signals == signals and s.meta["has_elevation"]
    assert all(a.duration_s >= 600.0 for a in s.arcs())
    assert np.nanmin(s.elevation_deg) >= 5.0
    got = rms_by_satellite(s)
    print(code, {k: round(v, 3) for k, v in got.items()})
    assert len(got) >= 6
    assert all(0.05 < v < 5.0 for v in got.values()), got


# ---------------------------------------------------------------- gnssmultipath cross-check

GM_SIGNALS = [
    ("G", "GPS", "Band_1", "C1C"),
    ("G", "GPS", "Band_2", "C2W"),
    ("G", "GPS", "Band_5", "C5Q"),
    ("E", "Galileo", "Band_1", "C1C"),
]
MIN_COMMON_S = 7200.0


@pytest.fixture(scope="module")
def esbc(tmp_path_factory):
    obs_gz, nav_gz = shared_file(ESBC_OBS), shared_file(ESBC_NAV)
    gm = pytest.importorskip("gnssmultipath", reason="gnssmultipath (test dependency) absent")
    hatanaka = pytest.importorskip("hatanaka")
    d = tmp_path_factory.mktemp("esbc")
    rinex, nav = d / "ESBC.rnx", d / "ESBC_MN.rnx"
    rinex.write_bytes(hatanaka.decompress(obs_gz.read_bytes()))
    nav.write_bytes(gzip.decompress(nav_gz.read_bytes()))
    t0 = time.perf_counter()
    with warnings.catch_warnings():  # its numpy warnings on satellites without data
        warnings.simplefilter("ignore")
        result = gm.GNSS_MultipathAnalysis(
            str(rinex),
            broadcastNav1=str(nav),
            desiredGNSSsystems=["G", "E"],
            outputDir=str(d),
            plotEstimates=False,
            plot_polarplot=False,
            save_results_as_pickle=False,
            write_results_to_csv=False,
            use_LaTex=False,
            include_SNR=False,
        )
    t1 = time.perf_counter()
    obs, orbit = read_obs(rinex, systems="GE"), read_orbit(nav)
    t2 = time.perf_counter()
    print(f"\ngnssmultipath G+E {t1 - t0:.1f} s; psdbound read obs + orbit {t2 - t1:.1f} s")
    w = result["ExtraOutputInfo"]["time_epochs_gps_time"]
    t_gm = w[:, 0] * 604800.0 + w[:, 1]
    assert np.array_equal(t_gm, obs.t_gps_s)  # same epochs, row for row
    return SimpleNamespace(result=result, obs=obs, orbit=orbit)


def _compare(esbc, system, name, band, code):
    """Both series on the epochs both have, per satellite, as is and re-levelled.

    Common segments: the epochs of one of our arcs within one run of finite
    gnssmultipath values (its slip-free periods are delimited by NaN).
    """
    c = esbc.result[name][band][code]
    phases = (c["phase1_Code"], c["phase2_Code"])
    t0 = time.perf_counter()
    ours = isolate_code_multipath(esbc.obs, code, phases=phases, orbit=esbc.orbit, system=system)
    runtime = time.perf_counter() - t0
    arcs = find_arcs(esbc.obs, phases, system=system, orbit=esbc.orbit, min_length_s=600.0)
    theirs = c["multipath_range1"]
    sats = np.asarray(ours.arc_sats)[ours.arc_id]
    rows = {}
    for sat in sorted(set(ours.arc_sats)):
        m = sats == sat
        idx = np.searchsorted(esbc.obs.t_gps_s, ours.t_gps_s[m])
        col = theirs[:, int(sat[1:])]
        fin = np.isfinite(col)
        run = np.cumsum(np.r_[True, fin[1:] != fin[:-1]])
        both = fin[idx]
        o, g = ours.value_m[m][both], col[idx][both]
        seg = ours.arc_id[m][both] * 10**6 + run[idx][both]
        o2, g2 = o.copy(), g.copy()
        for k in np.unique(seg):
            j = seg == k
            o2[j] -= o2[j].mean()
            g2[j] -= g2[j].mean()
        # our slips strictly inside one of gnssmultipath's slip-free periods
        starts = [a.epoch_index[0] for a in arcs if a.sat == sat and a.start_reason == "cycle slip"]
        spanned = [i for i in starts if fin[i] and fin[i - 1]]  # same finite run
        rows[sat] = SimpleNamespace(
            common_s=both.sum() * esbc.obs.interval_s,
            ours=o,
            theirs=g,
            ours_lev=o2,
            theirs_lev=g2,
            spanned=spanned,
        )
    return ours, rows, runtime


@pytest.mark.realdata
@pytest.mark.slow
@pytest.mark.parametrize("system, name, band, code", GM_SIGNALS)
def test_agrees_with_gnssmultipath(esbc, system, name, band, code):
    """Per-satellite RMS of ours and gnssmultipath's MP on the same epochs.

    Like for like by construction: both series are re-levelled (mean removed)
    on each common segment (one of our arcs within one of gnssmultipath's
    slip-free periods), where their raw combinations can differ only by a
    constant. Then every sample agrees to 1 mm and every satellite with 2 h
    of common data to 5 % in RMS (in practice to 1e-8).

    As is (each with its own levelling), the RMS agree to 5 % except on
    satellites where gnssmultipath's period spans a cycle slip that our arcs
    break at: its slip test (ionospheric rate 4/60 m/s, i.e. a geometry-free
    jump of 1.29 m in 30 s) misses the 0.5-1.25 m jumps of ESBC GPS C1C on
    G21, G24 and G26 (0.04 m threshold in ``find_arcs``), and its period mean
    then mixes two ambiguities (G26: 1.28 m RMS against 0.36 m). That is the
    only satellite exclusion, applied by rule, for the as-is comparison only.
    """
    ours, rows, runtime = _compare(esbc, system, name, band, code)
    c = esbc.result[name][band][code]
    judged = {s: r for s, r in rows.items() if r.common_s >= MIN_COMMON_S}
    rel_lev = {s: rms(r.ours_lev) / rms(r.theirs_lev) - 1 for s, r in judged.items()}
    rel_raw = {s: rms(r.ours) / rms(r.theirs) - 1 for s, r in judged.items()}
    spanned = sorted(s for s, r in judged.items() if r.spanned)
    worst = max(rel_lev, key=lambda s: abs(rel_lev[s]))
    clean = [s for s in judged if s not in spanned]
    print(
        f"\n{system} {code} ({c['phase1_Code']}-{c['phase2_Code']}): psdbound {runtime:.2f} s, "
        f"{len(judged)} satellites with >= 2 h common, re-levelled max |rel| "
        f"{abs(rel_lev[worst]):.1e} ({worst}); as is max |rel| without spanned slips "
        f"{max(abs(rel_raw[s]) for s in clean):.2e}; spanned slips: {spanned or 'none'} "
        + " ".join(f"{s} {100 * rel_raw[s]:+.1f} %" for s in spanned)
    )
    assert len(judged) >= 10
    assert all(abs(v) < 0.05 for v in rel_lev.values()), rel_lev
    for sat, r in rows.items():  # every satellite, every common sample
        assert np.abs(r.ours_lev - r.theirs_lev).max() < 1e-3, sat
    assert all(abs(rel_raw[s]) < 0.05 for s in clean), {s: rel_raw[s] for s in clean}
    assert len(spanned) <= 0.2 * len(judged)

    # the day: all common samples; and each series over all of its own samples
    o_lev = np.concatenate([r.ours_lev for r in rows.values()])
    g_lev = np.concatenate([r.theirs_lev for r in rows.values()])
    assert rms(o_lev) == pytest.approx(rms(g_lev), rel=1e-3)
    theirs_all = c["multipath_range1"]
    day = {}
    for label, drop in (("all", set()), ("without spanned slips", set(spanned))):
        keep = np.array([f"{system}{p:02d}" not in drop for p in range(theirs_all.shape[1])])
        g = theirs_all[:, keep]
        o = ours.value_m[~np.isin(np.asarray(ours.arc_sats)[ours.arc_id], list(drop))]
        day[label] = (rms(o), rms(g[np.isfinite(g)]), o.size, int(np.isfinite(g).sum()))
    print(
        "day RMS psdbound / gnssmultipath (samples): "
        + "; ".join(f"{k} {a:.4f} / {b:.4f} m ({n} / {m})" for k, (a, b, n, m) in day.items())
        + f"; common re-levelled {rms(o_lev):.4f} / {rms(g_lev):.4f} m"
    )
    a, b, n, m = day["without spanned slips"]
    assert a == pytest.approx(b, rel=0.05) and n == pytest.approx(m, rel=0.02)
    n_common = sum(r.ours.size for r in rows.values())
    assert n_common >= 0.99 * ours.value_m.size  # the comparison covers our series


# ---------------------------------------------------------------- level shifts (hidden slips)


def test_level_shifts_white_noise_growing_tenfold_never_splits():
    """Code noise grows ~10x towards the horizon: a local scale must not split noise."""
    rng = np.random.default_rng(7)
    n_cuts = 0
    for _ in range(200):
        sigma = np.linspace(0.1, 3.0, 1000) ** rng.uniform(0.5, 2.0)
        n_cuts += level_shifts(rng.normal(0.0, sigma)).size
    assert n_cuts == 0


@pytest.mark.parametrize("seed", range(5))
def test_level_shifts_finds_a_step_and_ignores_a_spike(seed):
    rng = np.random.default_rng(seed)
    x = rng.normal(0.0, 0.3, 800)
    at = int(rng.integers(50, 750))
    x[at:] += rng.choice([-1, 1]) * rng.uniform(3.0, 10.0)
    spike = (at + 200) % 800
    x[spike] += 12.0
    assert level_shifts(x).tolist() == [at]


def test_equal_metre_slip_invisible_to_geometry_free_is_split():
    """77 cycles on L1 and 60 on L2 move L1 - L2 by 0.03 mm but the MP combination by 14.7 m."""
    obs, truth = synthetic("G", seed=3)
    (_, _, li, lj), _ = SYSTEMS["G"]
    block = obs.blocks["G"]
    at = 650
    block.values[at:, 1, block.codes.index(li)] += 77
    block.values[at:, 1, block.codes.index(lj)] += 60
    arcs = find_arcs(obs, (li, lj), min_length_s=600.0)
    assert sum(a.sat == "G21" for a in arcs) == 2  # only the 7-cycle slip at 400 is seen
    with pytest.warns(PsdboundWarning, match=r"G21 .*level steps by 1[3-5]\.\d m"):
        mp = isolate_code_multipath(obs, "C1C")
    assert mp.meta["level_shift_breaks"] == {"G21": 1}
    want = expected(obs, truth, mp, lambda sat: (1.0, 0.0))
    assert np.max(np.abs(mp.value_m - want)) < 1e-3
    naive = isolate_code_multipath(obs, "C1C", min_jump_m=np.inf)
    assert naive.meta["level_shift_breaks"] == {}
    err = naive.value_m - expected(obs, truth, naive, lambda sat: (1.0, 0.0))
    assert np.max(np.abs(err)) > 5.0
