"""Pinned bounds on the demo and every real station file.

Refactors must not move these numbers. Work that changes a number on purpose
updates the pin here and says why in its commit message.

Pins (sigma_GM m, tau s, sigma_WN m, windows), measured with the defaults
(cutoff from the map, spectral stationarity test, disjoint windows, pooled
rule, multitaper, fitted mapping, screening on). History:

* issue 13 (stage chain): ESBC and UPC unchanged; the screening stage of
  issue 14 entered the chain: NYA1 7.32 cm / 48.5 s / 1117 windows ->
  2.38 cm / 47.1 s / 627 (residual ionosphere excluded, 31.8 % of the data);
  demo 6.88 mm / 29.6 s / 2.72 mm / 37 -> 4.73 mm / 15.1 s / 1.94 mm / 17
  (low-elevation blocks of its synthetic multipath exceed the ROTI threshold
  with the thesis mapping the demo is fitted with).
* issue 14: the ROTI threshold scales with the elevation mapping and the
  excluded spans get the filter's memory (0.5/f_c) as guard: NYA1 2.28 cm /
  45.8 s / 516 windows (45 % excluded); the demo is fitted with its own
  mapping (1, 9, 15 deg): 4.26 mm / 21.8 s / 2.09 mm / 29 windows (4.7 %
  excluded). ESBC and UPC unchanged.
* issue 16: the default cutoff comes from the shipped world map (time-domain
  residual criterion, interpolated in position and F10.7): ESBC 1.52e-3 Hz ->
  2.73 mm / 41.0 s / 993 windows; NYA1 2.06e-3 Hz -> 9.04 mm / 23.2 s / 829;
  demo 4.08 mm / 18.5 s / 2.02 mm / 36. UPC (dual-antenna, no cutoff) unchanged.
* issue 15: the spectral-homogeneity stationarity test (valid for correlated
  samples) with disjoint windows, and the pooled bound (95 % family-wise
  confidence, random-effects pooling of band spectra, lowest band where the
  high-pass passes 90 % of the power): demo 3.64 mm / 31.2 s / 1.20 mm / 15
  (truth 3 mm / 30 s / 1.1 mm: variance ratio 1.44); ESBC 3.09 mm / 37.8 s /
  119 (windows differ: the limits cover 99 % of them); NYA1 10.8 mm / 45.5 s
  / 67 (verdict not-bounded: 41 % never stationary); UPC 6.99 mm / 16.2 s /
  2.69 mm / 13 (between-window log-sd 1.2-1.6 over 13 windows).
* issue 15, second step: the elevation mapping is fitted to the data by
  default (normalised at zenith, b <= 100, c <= 40 deg) and disjoint windows
  come from binary segmentation: ESBC (b 8.4, c 17.1 deg) 1.76 mm / 37.8 s /
  119; NYA1 (b 1.6, c 30 deg) 17.7 mm / 45.5 s / 94, not-bounded (30 % of the
  data fail every stationarity test); UPC (b 2.6, c 22 deg) 11.7 mm / 65.6 s
  / 0 / 13 (between-window log-sd up to 1.3 at low frequency, 13 windows).
  The demo keeps its own mapping: unchanged.
* issue 15, third step: the band averages are divided by the high-pass's
  power response |H(f)|^2 (up to 11 % at the lowest band), and the spectral
  test refers its statistic to a scaled chi-square with its exact variance
  (Satterthwaite): demo 3.64 mm / 31.8 s / 1.20 mm; ESBC 1.77 mm / 37.8 s;
  NYA1 18.9 mm / 45.5 s / 93 windows; UPC (no filter) unchanged.
* issue 15, fourth step: the pooled limits hold for band means, so the bound
  is also held above U sqrt(f_hi/f_lo) at each band's lower edge and U at its
  upper edge (100 random truths: coverage 90 % -> 97.8 %), and bands no
  window reaches are dropped instead of widening the next: demo 3.85 mm /
  28.5 s / 1.24 mm; ESBC 1.85 mm / 32.8 s; NYA1 19.8 mm / 40.1 s; UPC 12.4 mm /
  58.6 s / 0.
* issue 27 (the bound's statement): exact chi-square group limits, every window's own
  upper deviation covered (a level, and a tilt where significant; distribution-free),
  groups by spectral shape on bands at least the multitaper smoothing wide, the
  high-pass divided out as the estimator sees it, dual-antenna windows sharing a
  reference clustered: demo 4.12 mm / 31.7 s / 1.20 mm; ESBC 1.85 -> 4.23 mm / 55.8 s
  (4 shape groups); NYA1 19.8 -> 18.2 mm / 40.1 s (not-bounded); UPC 12.4 -> 3.01 mm /
  80.2 s / 0.60 mm (its lowest bands no longer 10-100x above every window).
* issue 29 item 2 (three carriers): ESBC's L5Q names one ROTI-flagged block (G10, ROTI 0.17
  TECU/min) multipath and keeps it: 6.697 -> 6.704 mm / 288.7 -> 288.8 s, 119 -> 121
  windows; NYA1's ratio null names the day disturbed and is not used: unchanged.
* issue 29 (the null's local scale placed at its window's median elevation, not at the
  window's centre block: at the ends of the elevation range the window is one-sided):
  demo, ESBC, UPC unchanged; NYA1 (untrusted null) keeps two 13-min spans whose ROTI
  equalled their threshold (20.63 -> 20.43 % excluded): 25.65 -> 26.86 mm / 854.3 ->
  891.7 s / 10.76 -> 10.91 mm, 87 -> 89 windows, still not-bounded.
* issue 27 (small groups): a group's bands are merged until its windows have 40 degrees of
  freedom in each (counted from the merged width): demo 7.36 -> 5.11 mm / 55.5 -> 26.1 s
  (variance 5.4 -> 2.7 x the truth's), UPC 3.01 -> 2.77 mm / 80.2 -> 36.4 s; ESBC, NYA1
  and ZIMM unchanged.
* issue 27 (the lowest Fourier frequencies, dual antenna): data that went through no filter
  get the check of psdbound.spectra.lowest (the bound's expected narrow-multitaper estimate
  at 1/T above each shape group's upper limit): UPC's second group (two windows, 8 degrees
  of freedom at 1/T) held its limit 1.86 x above the bound's expectation: 2.77 -> 2.95 mm /
  36.4 -> 61.9 s / 0.55 -> 0.59 mm. The dual-frequency fits (demo, ESBC, NYA1) are filtered:
  unchanged.
* issue 27 (the lowest ordinates' degrees of freedom): adjacent ordinates overlap, so four of
  one window carry 7.4 degrees of freedom, not 16 (psdbound.spectra.ordinates.ordinate_dof);
  the groups' upper limits there rise: UPC 2.95 -> 3.06 mm / 61.9 -> 70.0 s / 0.589 -> 0.592
  mm. The new shape statistic at the lowest ordinates moved no UPC window; demo, ESBC, NYA1
  and ZIMM are filtered: unchanged.
"""

from __future__ import annotations

import pytest
from conftest import (
    ESBC_NAV,
    ESBC_OBS,
    NYA1_NAV,
    NYA1_OBS,
    UPC1_OBS,
    UPC2_OBS,
    UPC_NAV,
    shared_file,
)

import psdbound

PINS = {
    # case: (sigma_gm_m, tau_s, sigma_wn_m, windows)
    # issue 29: screening against the multipath null (demo: nothing excluded, 13 windows of
    # which one forms a shape group of its own); issue 27: that group's bands merged to 40
    # degrees of freedom (7.36 mm / 55.5 s before, its one-window limits set the bound)
    "demo": (0.005113150636623277, 26.134560727245194, 0.0011079101398980308, 13),
    # ESBC: the data do not bound tau above; below the lowest band the bound covers the
    # admitted models up to the prior 900 s (issue 28: was 4.23 mm / 55.8 s, extrapolated)
    "esbc": (0.006703963218877296, 288.7882798248829, 0.0, 121),
    # NYA1: its null is not trusted, so only the single-block test runs, at the whole false-
    # alarm probability (issue 29, coherence across satellites: three tests share it)
    "nya1": (0.026859132394042282, 891.6686737502989, 0.010905763723775433, 89),
    # UPC: two groups of two windows, their bands merged to 40 degrees of freedom (issue 27:
    # 3.01 mm / 80.2 s / 0.60 mm before); the lowest-frequency check (unfiltered data) raised
    # it for the second group (2.77 mm / 36.4 s / 0.55 mm before), with its ordinates'
    # effective degrees of freedom (2.95 mm / 61.9 s / 0.59 mm with four per ordinate)
    "upc": (0.0030635096426720955, 69.97208292373458, 0.0005917637627209875, 13),
}

FILES = {
    "demo": ((), None),
    "esbc": ((ESBC_OBS,), ESBC_NAV),
    "nya1": ((NYA1_OBS,), NYA1_NAV),
    "upc": ((UPC1_OBS, UPC2_OBS), UPC_NAV),
}
#: a dual-antenna pair is named explicitly
OPTIONS = {"upc": {"pair": ("UPC1", "UPC2")}}


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(PINS))
def test_pinned_bound(case):
    obs, nav = FILES[case]
    res = psdbound.fit(
        [shared_file(o) for o in obs],
        nav=shared_file(nav) if nav else None,
        **OPTIONS.get(case, {}),
    )
    b, d = res.bound, res.document
    sigma_gm, tau, sigma_wn, n_windows = PINS[case]
    print(f"{case}: {b.sigma_gm_m!r} {b.tau_s!r} {b.sigma_wn_m!r} {d['windows']['count']}")
    assert b.sigma_gm_m == pytest.approx(sigma_gm, rel=1e-6)
    assert b.tau_s == pytest.approx(tau, rel=1e-6)
    assert b.sigma_wn_m == pytest.approx(sigma_wn, rel=1e-6, abs=1e-12)
    assert d["windows"]["count"] == n_windows
    # the bound is stated up to Nyquist and never drawn past it
    nyq = d["sampling"]["nyquist_hz"]
    assert nyq == pytest.approx(0.5 / d["sampling"]["interval_s"])
    assert max(d["figures"]["bound_curve"]["f_hz"]) <= nyq * (1 + 1e-9)
    if case == "nya1":  # 30 % of the screened day fails every test: said, not hidden
        assert res.verdict == "not-bounded"
        assert any("data outside the bound" in r for r in res.verdict_reasons)
    else:
        assert res.verdict == "bounded", res.verdict_reasons
    w = d["windows"]
    assert w["covered_s"] + w["never_stationary_s"] == pytest.approx(w["data_s"], rel=0.02)
    assert d["bound"]["rule"] == "pooled" and d["bound"]["confidence_level"] == 0.95
    scr = d["screening"]
    if case == "esbc":  # quiet mid-latitude day: screening leaves it alone
        assert scr["excluded_fraction"] < 0.05
    if case == "nya1":  # 78.9 N: disturbed spans listed with their reasons, bands <= 2.5 cm
        kinds = {e["kind"] for e in scr["excluded"]}
        assert "ionosphere" in kinds
        # values beyond the carrier-multipath limit inside disturbed spans are named there
        assert any("carrier-multipath limit" in e["reason"] for e in scr["excluded"])
        for e in scr["excluded"]:
            assert e["sat"] and e["stop_gps_s"] >= e["start_gps_s"] and e["reason"]
            assert (
                e["statistic"] > e["threshold"]
                or e["kind"] == "short remainder"
                or "improbable under" in e["reason"]
            )  # a 15-min run (persistence)
        # the tightest bound over the bands (before the low-frequency prior raised it)
        assert d["bound"]["low_frequency"]["before"]["sigma_gm_m"] <= 0.025
        assert scr["multipath_limit_m"] == pytest.approx(0.0770, abs=2e-4)
