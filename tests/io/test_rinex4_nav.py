"""RINEX 4.00-4.02 navigation files: the legacy ephemerides read as from RINEX 3, the rest counted.

No real RINEX 4 navigation file is in ../shared/data: the files are RINEX 3
files converted by :mod:`rinex4_samples` (``> EPH <sat> <message>`` record
headers per RINEX 4.00, the header's corrections as ION/STO records, an EOP
record and a GPS CNAV record to be skipped).
"""

from __future__ import annotations

import gzip
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from conftest import ESBC_NAV, shared_file
from rinex4_samples import cnav_record, eop_record, header_line, nav_to_v4, with_version
from samples import moving_observations

from psdbound.cli import main
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.io import read_nav, read_orbit
from psdbound.io.navigation import Navigation, merge_navigation
from psdbound.io.nominal import nominal_navigation
from psdbound.io.write import format_nav_v3, format_obs_v3

T0 = 1_400_000_000.0  # 2024-05-19, GPS seconds


def _v3_text() -> str:
    """A small RINEX 3.04 navigation file: nominal GPS and Galileo records over 6 h."""
    return format_nav_v3(nominal_navigation(T0, T0 + 6 * 3600.0, systems="GE"))


def _write(tmp_path: Path, text: str, name: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def _body_start(lines: list[str]) -> int:
    return next(i for i, ln in enumerate(lines) if "END OF HEADER" in ln) + 1


def _read_v4(tmp_path: Path, text: str, name: str = "n4.rnx") -> tuple[Navigation, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        nav = read_nav(_write(tmp_path, text, name))
    return nav, [str(w.message) for w in caught if w.category is PsdboundWarning]


def assert_same_orbits(a: Navigation, b: Navigation, step_s: float = 60.0) -> int:
    """Positions and clocks of every satellite equal at ``step_s`` over the records' span.

    Returns the number of (satellite, time) positions compared.
    """
    assert a.satellites == b.satellites and a.systems == b.systems
    ref = np.concatenate([a.reference_times_gps_s(s) for s in a.systems])
    t = np.arange(ref.min() - 3600.0, ref.max() + 3600.0, step_s)
    n = 0
    for sat in a.satellites:
        pa, pb = a.positions_ecef_m(sat, t), b.positions_ecef_m(sat, t)
        np.testing.assert_array_equal(np.isnan(pa), np.isnan(pb), err_msg=sat)
        np.testing.assert_allclose(pb, pa, rtol=0, atol=1e-3, err_msg=sat)  # the millimetre
        np.testing.assert_array_equal(a.satellite_clock_s(sat, t), b.satellite_clock_s(sat, t))
        n += int(np.isfinite(pa[:, 0]).sum())
    return n


# ------------------------------------------------------------ synthetic files


@pytest.mark.parametrize("version", ["4.00", "4.01", "4.02"])
def test_rinex4_nav_gives_the_rinex3_orbits(tmp_path, version):
    text3 = _v3_text()
    a = read_nav(_write(tmp_path, text3, "n3.rnx"))
    b, msgs = _read_v4(tmp_path, nav_to_v4(text3, version))
    assert b.version == float(version)
    assert assert_same_orbits(a, b) > 1000
    for s in a.ephemerides:  # the same records, field by field
        for f in ("sat", "toc_gps_s", "toe_gps_s", "sqrt_a", "m0_rad", "health", "data_source"):
            np.testing.assert_array_equal(
                getattr(a.ephemerides[s], f), getattr(b.ephemerides[s], f)
            )
    assert b.unused == {"EOP": 1, "EPH G CNAV": 1}
    assert msgs == list(b.warnings) and len(msgs) == 1
    assert "2 RINEX 4 navigation record(s) skipped" in msgs[0]
    assert "EOP 1" in msgs[0] and "EPH G CNAV 1" in msgs[0]


def test_every_record_type_and_unused_message_is_counted(tmp_path):
    text = nav_to_v4(_v3_text())
    lines = text.split("\n")
    k = _body_start(lines)
    extra = [
        "> STO G01 LNAV",
        "    2024 05 19 00 00 00 GPUT",
        "    " + "0" * 19 * 4,
        "> STO E   IFNV",
        "    2024 05 19 00 00 00 GAGP",
        "    " + "0" * 19 * 4,
        "> ION C08 D1D2",
        "    2024 05 19 00 00 00",
        "    x",
        "    y",
        "> EPH C21 CNV1",
        *(["    z"] * 10),
        "> EPH R01 L1OC",
        *(["    z"] * 6),
        "> EPH I09 L1NV",
        *(["    z"] * 9),
        "> XYZ G01 LNAV",
        "    something new",
    ]
    nav, msgs = _read_v4(tmp_path, "\n".join(lines[:k] + extra + lines[k:]))
    assert nav.unused == {
        "EOP": 1,
        "EPH C CNV1": 1,
        "EPH G CNAV": 1,
        "EPH I L1NV": 1,
        "EPH R L1OC": 1,
        "ION": 1,
        "STO": 2,
        "unknown record type XYZ": 1,
    }
    assert len(msgs) == 1 and "9 RINEX 4 navigation record(s) skipped" in msgs[0]
    assert "STO 2" in msgs[0]


def test_sbas_and_navic_records_are_counted_per_system_as_in_rinex3(tmp_path):
    text = nav_to_v4(_v3_text())
    lines = text.split("\n")
    k = _body_start(lines)
    sbas = [
        "> EPH S23 SBAS",
        "S23 2024 05 19 00 00 16" + " 0.000000000000E+00" * 3,
        *(["    " + " 0.000000000000E+00" * 4] * 3),
    ]
    nav, _ = _read_v4(tmp_path, "\n".join(lines[:k] + sbas + sbas + lines[k:]))
    assert nav.skipped == {"S": 2} and nav.unused["EPH S SBAS"] == 2


def test_a_cnav_record_is_not_read_as_lnav(tmp_path):
    """The CNAV record of the converted file would move its satellite if it were read."""
    text3 = _v3_text()
    text4 = nav_to_v4(text3)
    a = read_nav(_write(tmp_path, text3, "n3.rnx"))
    lines = text4.split("\n")
    h = next(i for i, ln in enumerate(lines) if ln.endswith(" CNAV"))
    sat = lines[h][6:9]
    lines[h] = lines[h].replace("CNAV", "LNAV")
    del lines[h + 9]  # the CNAV record's ninth line: the rest has the LNAV layout
    relabelled, _ = _read_v4(tmp_path, "\n".join(lines), "wrong.rnx")
    toes = [e.toe_gps_s[e.sat == sat] for e in (relabelled.ephemerides["G"], a.ephemerides["G"])]
    t = np.setdiff1d(*toes)  # the relabelled record's time of ephemeris
    assert t.size == 1
    assert np.linalg.norm(relabelled.positions_ecef_m(sat, t) - a.positions_ecef_m(sat, t)) > 1e5


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            lambda r: ["> EPH G01"] + r[1:],
            r"line {h}: cannot read the record header '> EPH G01'; "
            r"expected '>', the record type in columns 3-5, the satellite in columns 7-9",
        ),
        (
            lambda r: [r[0].replace(">", " ", 1)] + r[1:],
            r"line {h}: expected a record header such "
            r"as '> EPH G01 LNAV'",
        ),
        (
            lambda r: [r[0], "G02" + r[1][3:]] + r[2:],
            r"line {f}: the record header names G01 but "
            r"the record's first line holds 'G02' in columns 1-3",
        ),
        (
            lambda r: [r[0].replace("G01", "G77")] + r[1:],
            r"line {h}: satellite id 'G77' in columns "
            r"7-9 is not valid",
        ),
        (
            lambda r: [r[0].replace("> EPH G01", "> EPH X01")] + r[1:],
            r"line {h}: unknown "
            r"satellite system letter 'X' in the record header \(columns 7-9\); expected one of "
            r"G, R, E, C, J, S, I",
        ),
    ],
)
def test_damaged_record_headers_are_refused_with_the_line(tmp_path, edit, message):
    lines = nav_to_v4(_v3_text()).split("\n")
    h = next(i for i, ln in enumerate(lines) if ln.startswith("> EPH G01 LNAV"))
    lines[h : h + 9] = edit(lines[h : h + 9])
    with pytest.raises(InputError, match=r"bad\.rnx, " + message.format(h=h + 1, f=h + 2)):
        read_nav(_write(tmp_path, "\n".join(lines), "bad.rnx"))


def test_a_record_of_the_wrong_length_is_left_out_with_a_warning(tmp_path):
    text3 = _v3_text()
    lines = nav_to_v4(text3).split("\n")
    h = next(i for i, ln in enumerate(lines) if ln.startswith("> EPH G01 LNAV"))
    del lines[h + 8]  # the last orbit line of the first G01 record
    nav, msgs = _read_v4(tmp_path, "\n".join(lines))
    ref = read_nav(_write(tmp_path, text3, "n3.rnx")).ephemerides["G"]
    assert len(nav.ephemerides["G"]) == len(ref) - 1
    damage = [m for m in msgs if "left out" in m]
    assert len(damage) == 1 and f"G01 on line {h + 1}" in damage[0]
    assert "7 lines after the record header, LNAV records have 8" in damage[0]


def test_a_file_cut_in_a_record_is_refused(tmp_path):
    text = nav_to_v4(_v3_text()).rstrip("\n")
    cut = "\n".join(text.split("\n")[:-3])
    with pytest.raises(
        InputError,
        match=r"cut\.rnx, line \d+: truncated navigation record: the "
        r"file ends in the middle of the record of E\d\d \(it has 5 of its 8 "
        r"lines\)",
    ):
        read_nav(_write(tmp_path, cut, "cut.rnx"))


def test_a_newer_minor_version_is_read_with_a_warning(tmp_path):
    nav, msgs = _read_v4(tmp_path, nav_to_v4(_v3_text(), "4.03"))
    assert nav.version == 4.03 and len(nav.ephemerides["G"]) > 10
    assert any("RINEX 4.03 is newer than the 4.02 this reader knows" in m for m in msgs)


def test_rinex4_records_in_a_rinex3_file_are_refused(tmp_path):
    text = nav_to_v4(_v3_text()).split("\n")
    text[0] = "     3.05" + text[0][9:]
    with pytest.raises(
        InputError,
        match=r"a RINEX 4 record header \('> EPH \.\.\.'\) in a file "
        r"whose line 1 gives a RINEX 3 version",
    ):
        read_nav(_write(tmp_path, "\n".join(text), "mixed.rnx"))


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            lambda ln: [with_version(ln[0], "5.00"), *ln[1:]],
            r"line 1: RINEX 5\.00 navigation files are not supported; expected RINEX 2, 3 or 4",
        ),
        (
            lambda ln: [x.replace("> EPH G01 LNAV", "> EPH G01") for x in ln],
            r"line \d+: cannot read the record header '> EPH G01'",
        ),
    ],
)
def test_bad_navigation_input_exits_2_naming_the_line(tmp_path, capsys, edit, message):
    obs = _write(tmp_path, format_obs_v3(moving_observations()), "o.rnx")
    nav = _write(tmp_path, "\n".join(edit(nav_to_v4(_v3_text()).split("\n"))), "bad_nav.rnx")
    assert main(["inspect", str(obs), "--nav", str(nav)]) == 2
    err = capsys.readouterr().err
    assert re.search(r"bad_nav\.rnx, " + message, err), err


def test_merged_files_sum_the_unused_records(tmp_path):
    text = nav_to_v4(_v3_text())
    a, _ = _read_v4(tmp_path, text, "a.rnx")
    b, _ = _read_v4(tmp_path, text, "b.rnx")
    assert merge_navigation([a, b], "a+b").unused == {"EOP": 2, "EPH G CNAV": 2}


def test_sample_records_have_the_rinex4_layout():
    eop = eop_record("2020 06 25 00 00 00")
    assert [len(x) for x in eop] == [14, 80, 80, 80] and eop[2][:23].isspace()
    lnav = _v3_text().split("\n")[3:11]
    cnav = cnav_record(lnav)
    assert cnav[0] == f"> EPH {lnav[0][:3]} CNAV" and len(cnav) == 10
    assert header_line("x", "DOI") == f"{'x':<60s}DOI"


# ------------------------------------------------------------ the real ESBC file


@pytest.fixture(scope="module")
def esbc(tmp_path_factory) -> tuple[Path, Path]:
    """The ESBC RINEX 3.05 navigation file and its RINEX 4.00 conversion."""
    v3 = shared_file(ESBC_NAV)
    v4 = tmp_path_factory.mktemp("nav4") / "ESBC00DNK_R_20201770000_01D_MN.rnx4.gz"
    v4.write_bytes(gzip.compress(nav_to_v4(gzip.decompress(v3.read_bytes()).decode()).encode()))
    return v3, v4


@pytest.mark.realdata
def test_esbc_rinex4_positions_equal_rinex3_to_the_millimetre(esbc):
    a = read_orbit(esbc[0])
    with pytest.warns(PsdboundWarning, match=r"2137 RINEX 4 navigation record\(s\) skipped"):
        b = read_orbit(esbc[1])
    assert b.systems == ("C", "E", "G", "J", "R")
    assert assert_same_orbits(a, b) > 100_000  # 110 satellites over the day, every minute
    assert b.skipped == a.skipped == {"S": 2130}
    assert b.unused == {"EOP": 1, "EPH G CNAV": 1, "EPH S SBAS": 2130, "ION": 2, "STO": 3}
    assert b.glonass_channels == a.glonass_channels
    for s, eph in a.ephemerides.items():
        assert len(b.ephemerides[s]) == len(eph), s


# ------------------------------------------------------------ georinex cross-check

_GEORINEX_FIELDS = {  # georinex name -> ours
    "SVclockBias": "af0_s",
    "SVclockDrift": "af1",
    "Crs": "crs_m",
    "DeltaN": "delta_n_rad_s",
    "M0": "m0_rad",
    "Cuc": "cuc_rad",
    "Eccentricity": "e",
    "Cus": "cus_rad",
    "sqrtA": "sqrt_a",
    "Toe": "toe_sow_s",
    "Cic": "cic_rad",
    "Omega0": "omega0_rad",
    "Cis": "cis_rad",
    "Io": "i0_rad",
    "Crc": "crc_m",
    "omega": "omega_rad",
    "OmegaDot": "omega_dot_rad_s",
    "IDOT": "idot_rad_s",
}


def _georinex_records(ds, system: str) -> np.ndarray:
    """(toc as int ns, fields...) rows of one system's records, sorted."""
    rows = []
    for sv in ds.sv.values:
        if not str(sv).startswith(system):
            continue
        sub = ds.sel(sv=sv)
        ok = np.isfinite(sub["sqrtA"].values)
        t = sub.time.values[ok].astype("datetime64[ns]").astype(np.int64).astype(np.float64)
        cols = [np.full(ok.sum(), float(str(sv)[1:3])), t]
        cols += [sub[name].values[ok] for name in _GEORINEX_FIELDS]
        rows.append(np.column_stack(cols))
    out = np.concatenate(rows)
    return out[np.lexsort(out.T[::-1])]


def _our_records(nav: Navigation, system: str) -> np.ndarray:
    from psdbound.io.timescales import gps_s_to_datetime64

    eph = nav.ephemerides[system]
    t = gps_s_to_datetime64(eph.toc_gps_s).astype("datetime64[ns]").astype(np.int64)
    cols = [np.array([float(s[1:]) for s in eph.sat]), t.astype(np.float64)]
    cols += [getattr(eph, ours) for ours in _GEORINEX_FIELDS.values()]
    out = np.column_stack(cols)
    return out[np.lexsort(out.T[::-1])]


@pytest.mark.realdata
def test_rinex4_elements_equal_georinex_reading_the_rinex3_source(esbc):
    """georinex (test-only) reads the RINEX 3 file; our RINEX 4 reading has the same elements.

    GPS and QZSS: georinex 1.16 turns every Galileo record of this file into NaN
    (their spare fields are blank, which its ``float`` does not take).
    """
    gr = pytest.importorskip("georinex")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = gr.load(esbc[0], use={"G", "J"})
        ours = read_nav(esbc[1])
    for system in ("G", "J"):
        theirs, mine = _georinex_records(ref, system), _our_records(ours, system)
        assert theirs.shape == mine.shape, system
        np.testing.assert_array_equal(mine, theirs, err_msg=system)


@pytest.mark.realdata
def test_georinex_on_the_rinex4_file(esbc):
    """Where georinex reads RINEX 4 navigation, it agrees with us; 1.16 refuses it."""
    gr = pytest.importorskip("georinex")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            ref = gr.load(esbc[1], use={"G", "J"})
        except LookupError as exc:  # georinex 1.16: "unknown RINEX {'version': 4.0, ...}"
            pytest.skip(f"georinex {gr.__version__} does not read RINEX 4 navigation: {exc}")
        ours = read_nav(esbc[1])
    for system in ("G", "J"):
        np.testing.assert_array_equal(_our_records(ours, system), _georinex_records(ref, system))
