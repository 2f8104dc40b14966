"""Tests of the RINEX navigation reader (psdbound.io.nav)."""

from __future__ import annotations

import gzip
import time

import numpy as np
import pytest
from conftest import ESBC_NAV, NYA1_NAV, UPC_NAV, shared_file

from psdbound.errors import InputError
from psdbound.io.nav import KeplerEphemerides, Navigation, read_nav
from psdbound.io.timescales import calendar_to_gps_s, utc_to_gps_s


def hdr(content: str, label: str) -> str:
    return f"{content:<60}{label:<20}"


RNX3_HEADER = [
    hdr("     3.05           N: GNSS NAV DATA    M: MIXED", "RINEX VERSION / TYPE"),
    hdr("test                test                20240504 003737 UTC", "PGM / RUN BY / DATE"),
    hdr("    18", "LEAP SECONDS"),
    hdr("", "END OF HEADER"),
]

G27 = """\
G27 2024 05 03 02 00 00-2.202996984124E-05-2.046363078989E-12 0.000000000000E+00
     4.200000000000E+01-9.562500000000E+00 4.543403536708E-09 1.651359513615E+00
    -5.774199962616E-07 1.256587530952E-02 7.808208465576E-06 5.153678092957E+03
     4.392000000000E+05-2.402812242508E-07 1.466243505647E+00 4.656612873077E-08
     9.623062617470E-01 2.312500000000E+02 7.882833055638E-01-8.204627469952E-09
    -3.828730910582E-10 1.000000000000E+00 2.312000000000E+03 0.000000000000E+00
     2.000000000000E+00 0.000000000000E+00 1.862645149231E-09 4.200000000000E+01
     4.320180000000E+05 4.000000000000E+00
""".splitlines()

E11 = """\
E11 2024 05 03 02 10 00 3.692881320603e-03 2.480362581991e-10 0.000000000000e+00
     5.100000000000e+01 5.646875000000e+01 3.104057867898e-09-2.440907356789e-01
     2.551823854446e-06 4.458994371817e-04 1.376494765282e-06 5.440605798721e+03
     4.398000000000e+05-1.862645149231e-09 2.295024911377e+00-1.024454832077e-07
     9.883634572138e-01 3.245000000000e+02 7.522768715341e-01-5.925603968047e-09
     2.253665302777e-10 5.170000000000e+02 2.312000000000e+03
     3.120000000000e+00 0.000000000000e+00-1.536682248116e-08-1.676380634308e-08
     4.391870000000e+05
""".splitlines()

C10 = """\
C10 2024 05 03 02 00 00-5.154609680176e-04-6.708145150469e-11 0.000000000000e+00
     1.000000000000e+00-4.142968750000e+02-3.141559429989e-09-1.101749161212e+00
    -1.366203650832e-05 3.830116475001e-04-1.177610829473e-05 6.493378950119e+03
     4.392000000000e+05-6.146728992462e-08 2.697580724014e+00 6.146728992462e-08
     1.136268367853e-01 3.549843750000e+02-1.027125663175e+00 4.100527946305e-09
     3.321566928024e-10 0.000000000000e+00 9.560000000000e+02
     2.000000000000e+00 0.000000000000e+00 1.000000000000e-10-9.300000000000e-09
     4.384276000000e+05 0.000000000000e+00
""".splitlines()

R01 = """\
R01 2024 05 03 01 45 00 6.355997174978e-05 0.000000000000e+00 3.438000000000e+05
     1.372008105469e+04 1.682619094849e+00-0.000000000000e+00 0.000000000000e+00
     1.826717285156e+03 2.401678085327e+00 0.000000000000e+00 1.000000000000e+00
     2.143656884766e+04-1.280283927917e+00-2.793967723846e-09 0.000000000000e+00
                         .999999999999e+09 1.500000000000e+01
""".splitlines()

S23 = """\
S23 2024 05 03 00 00 16 0.000000000000e+00 0.000000000000e+00 3.456300000000e+05
     3.594460000000e+04 0.000000000000e+00 0.000000000000e+00 6.300000000000e+01
     2.204414000000e+04 0.000000000000e+00 0.000000000000e+00 3.276700000000e+04
     0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 9.200000000000e+01
""".splitlines()

RNX2_HEADER = [
    hdr("     2              NAVIGATION DATA", "RINEX VERSION / TYPE"),
    hdr("CCRINEXN V1.6.0 UX  CDDIS               19-MAR-10 02:51", "PGM / RUN BY / DATE"),
    hdr("    15", "LEAP SECONDS"),
    hdr("", "END OF HEADER"),
]

# RINEX 2 record with Fortran D exponents and a 2-digit year
PRN3_RNX2 = """\
 3 10  3 18  0  0  0.0 0.529540702701D-03 0.511590769747D-11 0.000000000000D+00
    0.270000000000D+02-0.626562500000D+02 0.526664794845D-08-0.215164111688D+01
   -0.326521694660D-05 0.128967179917D-01 0.726059079170D-05 0.515369729996D+04
    0.345600000000D+06 0.141561031342D-06-0.544880431040D+00-0.670552253723D-07
    0.927184923877D+00 0.218593750000D+03 0.984421008561D+00-0.826391565383D-08
   -0.434303804782D-09 0.100000000000D+01 0.157500000000D+04 0.000000000000D+00
    0.200000000000D+01 0.000000000000D+00-0.419095158577D-08 0.270000000000D+02
    0.338418000000D+06 0.400000000000D+01 0.000000000000D+00 0.000000000000D+00
""".splitlines()


def write(tmp_path, name: str, lines: list[str]) -> str:
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return str(p)


# ------------------------------------------------------------------ synthetic


def test_rinex3_mixed_fields(tmp_path):
    path = write(tmp_path, "mixed.rnx", RNX3_HEADER + G27 + R01 + E11 + S23 + C10 + S23)
    nav = read_nav(path)
    assert isinstance(nav, Navigation)
    assert nav.version == pytest.approx(3.05)
    assert nav.leap_seconds == 18
    assert set(nav.ephemerides) == {"G", "E", "C"}
    assert nav.skipped == {"S": 2}  # GLONASS records are read (test_glonass.py)
    assert nav.systems == ("C", "E", "G", "R")
    assert nav.satellites == ("C10", "E11", "G27", "R01")

    g = nav.ephemerides["G"]
    assert isinstance(g, KeplerEphemerides)
    assert len(g) == 1
    assert g.sat[0] == "G27"
    # negative numbers running together on the epoch line
    assert g.af0_s[0] == pytest.approx(-2.202996984124e-05, rel=1e-15)
    assert g.af1[0] == pytest.approx(-2.046363078989e-12, rel=1e-15)
    assert g.iode[0] == 42
    assert g.crs_m[0] == pytest.approx(-9.5625)
    assert g.e[0] == pytest.approx(1.256587530952e-02)
    assert g.sqrt_a[0] == pytest.approx(5.153678092957e03)
    assert g.omega_dot_rad_s[0] == pytest.approx(-8.204627469952e-09)
    assert g.idot_rad_s[0] == pytest.approx(-3.828730910582e-10)
    assert g.health[0] == 0
    assert g.data_source[0] == 0
    toc = calendar_to_gps_s(2024, 5, 3, 2, 0, 0)
    assert g.toc_gps_s[0] == toc
    assert g.toe_gps_s[0] == 2312 * 604800.0 + 439200.0 == toc
    assert g.toe_sow_s[0] == 439200.0

    e = nav.ephemerides["E"]
    assert e.data_source[0] == 517
    assert e.iode[0] == 51
    assert e.toc_gps_s[0] == calendar_to_gps_s(2024, 5, 3, 2, 10, 0)
    assert e.toe_gps_s[0] == 2312 * 604800.0 + 439800.0

    c = nav.ephemerides["C"]
    # BDT labels: GPS = BDT + 14 s; BDT week 956 = GPS week 2312
    assert c.toc_gps_s[0] == calendar_to_gps_s(2024, 5, 3, 2, 0, 0) + 14.0
    assert c.toe_gps_s[0] == (956 + 1356) * 604800.0 + 439200.0 + 14.0 == c.toc_gps_s[0]
    assert c.toe_sow_s[0] == 439200.0


def test_rinex2_d_exponents_two_digit_year(tmp_path):
    path = write(tmp_path, "brdc0770.10n", RNX2_HEADER + PRN3_RNX2 + PRN3_RNX2)
    nav = read_nav(path)
    assert nav.version == 2.0
    assert nav.leap_seconds == 15
    g = nav.ephemerides["G"]
    assert len(g) == 2
    assert list(g.sat) == ["G03", "G03"]
    assert g.af0_s[0] == pytest.approx(0.529540702701e-03, rel=1e-15)
    assert g.crs_m[0] == pytest.approx(-0.626562500000e02)
    assert g.cuc_rad[0] == pytest.approx(-0.326521694660e-05)
    assert g.toc_gps_s[0] == calendar_to_gps_s(2010, 3, 18, 0, 0, 0)
    assert g.toe_gps_s[0] == 1575 * 604800.0 + 345600.0


def test_week_rollover_is_fixed_by_toc(tmp_path):
    # week written modulo 1024 (551 = 1575 - 1024) must still give toe in 2010
    rec = list(PRN3_RNX2)
    rec[5] = rec[5].replace("0.157500000000D+04", "0.551000000000D+03")
    nav = read_nav(write(tmp_path, "roll.10n", RNX2_HEADER + rec))
    assert nav.ephemerides["G"].toe_gps_s[0] == 1575 * 604800.0 + 345600.0


def test_positions_for_absent_satellite_are_nan(tmp_path):
    nav = read_nav(write(tmp_path, "g.rnx", RNX3_HEADER + G27))
    t = calendar_to_gps_s(2024, 5, 3, 2, 0, 0) + np.array([0.0, 60.0])
    assert np.all(np.isnan(nav.positions_ecef_m("G01", t)))
    assert np.all(np.isnan(nav.positions_ecef_m("E01", t)))
    pos = nav.positions_ecef_m("G27", t)
    assert pos.shape == (2, 3)
    r = np.linalg.norm(pos, axis=1)
    assert np.all((r > 2.6e7) & (r < 2.7e7))
    with pytest.raises(ValueError, match="satellite id"):
        nav.positions_ecef_m("GPS27", t)


def test_gzip_input(tmp_path):
    p = tmp_path / "g.rnx.gz"
    p.write_bytes(gzip.compress(("\n".join(RNX3_HEADER + G27) + "\n").encode()))
    assert read_nav(p).satellites == ("G27",)


# ------------------------------------------------------------------ bad input


def test_observation_file_rejected(tmp_path):
    obs = [
        hdr("     3.04           OBSERVATION DATA    M (MIXED)", "RINEX VERSION / TYPE"),
        hdr("G    4 C1C L1C D1C S1C", "SYS / # / OBS TYPES"),
        hdr("", "END OF HEADER"),
        "> 2020 06 25 00 00  0.0000000  0  1",
    ]
    path = write(tmp_path, "ESBC.obs.rnx", obs)
    with pytest.raises(
        InputError,
        match=r"ESBC\.obs\.rnx, line 1: .*OBSERVATION DATA.*"
        r"expected a navigation file",
    ) as exc:
        read_nav(path)
    assert exc.value.line == 1
    assert exc.value.path == path


def test_truncated_record(tmp_path):
    path = write(tmp_path, "cut.rnx", RNX3_HEADER + G27 + E11[:5])
    n_lines = len(RNX3_HEADER) + len(G27) + 5
    with pytest.raises(
        InputError,
        match=rf"cut\.rnx, line {n_lines}: truncated navigation record: .*record of E11"
        r" \(it has 5 of its 8 lines\)",
    ):
        read_nav(path)


def test_truncated_rinex2_record(tmp_path):
    path = write(tmp_path, "cut.10n", RNX2_HEADER + PRN3_RNX2 + PRN3_RNX2[:3])
    with pytest.raises(InputError, match=r"cut\.10n, line 15: truncated .*record of G03"):
        read_nav(path)


def test_incomplete_record_mid_file(tmp_path):
    path = write(tmp_path, "gap.rnx", RNX3_HEADER + G27[:6] + E11)
    with pytest.raises(InputError, match=r"line 10: incomplete navigation record of G27: 6 lines"):
        read_nav(path)


def test_plain_text_rejected(tmp_path):
    path = write(tmp_path, "notes.txt", ["hello world", "this is not RINEX"])
    with pytest.raises(InputError, match=r"notes\.txt, line 1: not a RINEX file.*RINEX VERSION"):
        read_nav(path)


def test_sp3_passed_to_read_nav(tmp_path):
    path = write(tmp_path, "orbit.sp3", ["#cP2020  6 25  0  0  0.00000000      96 ORBIT"])
    with pytest.raises(InputError, match=r"orbit\.sp3.*SP3 precise orbit file.*read_sp3"):
        read_nav(path)


def test_no_end_of_header(tmp_path):
    path = write(tmp_path, "nohdr.rnx", RNX3_HEADER[:3])
    with pytest.raises(InputError, match=r"nohdr\.rnx, line 3: no 'END OF HEADER'"):
        read_nav(path)


def test_unparsable_number(tmp_path):
    rec = list(G27)
    rec[2] = rec[2][:23] + " 1.25658753x952E-02" + rec[2][42:]
    path = write(tmp_path, "bad.rnx", RNX3_HEADER + rec)
    with pytest.raises(
        InputError,
        match=r"bad\.rnx, line 7: cannot parse number '1\.25658753x952E-02' in columns 24-42 "
        r"\(eccentricity of G27\)",
    ):
        read_nav(path)


def test_bad_epoch(tmp_path):
    rec = list(G27)
    rec[0] = "G27 2024 O5" + rec[0][11:]
    path = write(tmp_path, "ep.rnx", RNX3_HEADER + rec)
    with pytest.raises(InputError, match=r"ep\.rnx, line 5: cannot parse the epoch .* of G27"):
        read_nav(path)


def test_rinex5_rejected(tmp_path):
    lines = [hdr("     5.00           N: GNSS NAV DATA    M: MIXED", "RINEX VERSION / TYPE")]
    with pytest.raises(
        InputError,
        match=r"v5\.rnx, line 1: RINEX 5\.00 navigation files are "
        r"not supported; expected RINEX 2, 3 or 4 \(up to 4\.02\)",
    ):
        read_nav(write(tmp_path, "v5.rnx", lines + RNX3_HEADER[2:]))


# ------------------------------------------------------------------ real files


def _read_timed(name: str) -> tuple[Navigation, float]:
    path = shared_file(name)
    utc_to_gps_s(0.0)  # the one-off erfa import (GLONASS epochs) is not the reader's cost
    t0 = time.perf_counter()
    nav = read_nav(path)
    return nav, time.perf_counter() - t0


def _consecutive_records_agree(nav: Navigation, system: str, tol_m: float) -> int:
    """Positions of consecutive records of a satellite agree half-way between toes.

    Returns the number of pairs checked; at most 2 % may disagree (real files
    hold the odd stale record, e.g. G25 at 00:00 in brdc0770.10n).
    """
    eph = nav.ephemerides[system]
    from psdbound.io.ephemeris import kepler_positions_ecef_m

    checked = 0
    bad = []
    for sat in eph.satellites:
        rows = np.flatnonzero((eph.sat == sat) & (eph.health == 0))
        toe = np.unique(eph.toe_gps_s[rows])
        for a, b in zip(toe[:-1], toe[1:], strict=True):
            if b - a > 7200.0:
                continue
            tm = 0.5 * (a + b)
            ia = rows[eph.toe_gps_s[rows] == a][:1]
            ib = rows[eph.toe_gps_s[rows] == b][:1]
            pa = kepler_positions_ecef_m(eph.select(ia), sat, tm)
            pb = kepler_positions_ecef_m(eph.select(ib), sat, tm)
            if not np.linalg.norm(pa - pb) < tol_m:
                bad.append((sat, a, b))
            checked += 1
    assert len(bad) <= 0.02 * checked, bad
    return checked


@pytest.mark.realdata
def test_esbc_mixed_nav():
    nav, dt = _read_timed(ESBC_NAV)
    print(f"\nread {ESBC_NAV}: {dt * 1e3:.0f} ms")
    assert dt < 0.5
    assert nav.version == pytest.approx(3.05)
    assert nav.leap_seconds == 18
    sats = nav.satellites
    assert sum(s[0] == "G" for s in sats) >= 30
    assert sum(s[0] == "E" for s in sats) >= 20
    assert {"G", "E"} <= set(nav.ephemerides)
    assert len(nav.glonass) > 100 and "R" not in nav.skipped
    assert nav.skipped.get("S", 0) > 100
    e = nav.ephemerides["E"]
    # both I/NAV (517) and F/NAV (258) records are kept
    assert set(np.unique(e.data_source)) >= {517, 258}
    day = calendar_to_gps_s(2020, 6, 25, 0, 0, 0)
    for eph in nav.ephemerides.values():
        assert np.all(np.abs(eph.toe_gps_s - day - 43200.0) < 86400.0)
        assert np.all(np.abs(eph.toe_gps_s - eph.toc_gps_s) < 7200.0)
        # (E14 and E18 are in eccentric orbits, e = 0.16)
        assert np.all((eph.e >= 0) & (eph.e < 0.2))
    assert _consecutive_records_agree(nav, "G", 10.0) > 50


@pytest.mark.realdata
def test_nya1_gps_nav():
    nav, dt = _read_timed(NYA1_NAV)
    print(f"\nread {NYA1_NAV}: {dt * 1e3:.0f} ms")
    assert dt < 0.5
    assert set(nav.ephemerides) == {"G"}
    assert len(nav.satellites) >= 28
    g = nav.ephemerides["G"]
    day = calendar_to_gps_s(2024, 5, 3, 0, 0, 0)
    assert np.all(np.abs(g.toe_gps_s - day - 43200.0) < 86400.0)
    assert _consecutive_records_agree(nav, "G", 10.0) > 50


@pytest.mark.realdata
def test_upc_rinex2_nav():
    nav, dt = _read_timed(UPC_NAV)
    print(f"\nread {UPC_NAV}: {dt * 1e3:.0f} ms")
    assert dt < 0.5
    assert nav.version == 2.0
    assert nav.leap_seconds == 15
    assert len(nav.satellites) >= 28
    g = nav.ephemerides["G"]
    assert g.sat[0] == "G02"
    assert g.toc_gps_s[0] == calendar_to_gps_s(2010, 3, 18, 0, 0, 0)
    assert g.toe_gps_s[0] == 1575 * 604800.0 + 345600.0
    assert g.sqrt_a[0] == pytest.approx(0.515379825401e04)
    assert _consecutive_records_agree(nav, "G", 10.0) > 50
