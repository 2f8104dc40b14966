"""RINEX 4.00-4.02 observation files read exactly as the RINEX 3 files they were made from.

No real RINEX 4 observation file is in ../shared/data: the files are RINEX 3
files converted by :mod:`rinex4_samples` (version in line 1, the new header
records DOI, LICENSE OF USE and STATION INFORMATION), written plain, gzip,
Hatanaka, Hatanaka+gzip and zip.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
from conftest import ESBC_OBS, shared_file
from rinex4_samples import cut_obs, header_line, obs_to_v4, with_version, write_variants
from samples import moving_observations

from psdbound.cli import main
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.io import Observations, read_obs
from psdbound.io._source import read_bytes
from psdbound.io.write import format_obs_v3


def assert_same_observations(a: Observations, b: Observations) -> None:
    """Every epoch, flag, satellite, code, value and indicator equal; the headers' content too."""
    np.testing.assert_array_equal(a.t_gps_s, b.t_gps_s)
    np.testing.assert_array_equal(a.epoch_flag, b.epoch_flag)
    assert list(a.blocks) == list(b.blocks)
    for s, x in a.blocks.items():
        y = b.blocks[s]
        assert (x.sats, x.codes) == (y.sats, y.codes), s
        np.testing.assert_array_equal(x.values, y.values, err_msg=s)  # NaN == NaN here
        np.testing.assert_array_equal(x.lli, y.lli, err_msg=s)
        np.testing.assert_array_equal(x.ssi, y.ssi, err_msg=s)
    ha, hb = a.header, b.header
    for name in (
        "file_system",
        "marker_name",
        "receiver_type",
        "antenna_type",
        "interval_s",
        "time_system",
        "obs_types",
        "glonass_channels",
        "leap_seconds",
        "first_obs",
        "last_obs",
        "type_lines",
    ):
        if name == "type_lines":  # the new records come after the type lists: same lines
            assert ha.type_lines == hb.type_lines
        else:
            assert getattr(ha, name) == getattr(hb, name), name
    np.testing.assert_array_equal(ha.approx_position_m, hb.approx_position_m)
    np.testing.assert_array_equal(ha.antenna_delta_hen_m, hb.antenna_delta_hen_m)


def _read_quietly(path: Path, **kw) -> Observations:
    with warnings.catch_warnings():
        warnings.simplefilter("error", PsdboundWarning)
        return read_obs(path, **kw)


def _write(tmp_path: Path, text: bytes, name: str) -> Path:
    p = tmp_path / name
    p.write_bytes(text)
    return p


# ------------------------------------------------------------ synthetic files


@pytest.mark.parametrize("version", ["4.00", "4.01", "4.02"])
def test_rinex4_obs_reads_as_its_rinex3_source(tmp_path, version):
    text3 = format_obs_v3(moving_observations()).encode("ascii")
    text4 = obs_to_v4(text3, version)
    assert b"LICENSE OF USE" in text4
    assert text4.split(b"\n")[0].startswith(f"{version:>9s}".encode())
    a = _read_quietly(_write(tmp_path, text3, "a.rnx"))
    b = _read_quietly(_write(tmp_path, text4, "b.rnx"))  # no warning: DOI etc. are known
    assert b.header.version == float(version)
    assert_same_observations(a, b)
    assert "RINEX 4.0" in b.summary()


def test_unknown_header_records_are_counted_in_one_warning(tmp_path):
    text3 = format_obs_v3(moving_observations()).encode("ascii")
    extra = (("x", "FUTURE RECORD"), ("y", "FUTURE RECORD"), ("z", "SPARE THING"))
    text4 = obs_to_v4(text3, "4.01", extra)
    line = next(i for i, ln in enumerate(text4.split(b"\n"), 1) if b"FUTURE RECORD" in ln)
    with pytest.warns(PsdboundWarning) as caught:
        b = read_obs(_write(tmp_path, text4, "u.rnx"))
    msgs = [str(w.message) for w in caught]
    assert len(msgs) == 1, msgs
    assert f"u.rnx, line {line}: 3 header record(s) of a type not in RINEX" in msgs[0]
    assert "'FUTURE RECORD' x2, 'SPARE THING'" in msgs[0]
    assert b.warnings == (msgs[0],)
    assert_same_observations(read_obs(_write(tmp_path, text3, "a.rnx")), b)


def test_unknown_header_records_of_rinex3_files_are_counted_too(tmp_path):
    text3 = format_obs_v3(moving_observations()).encode("ascii")
    lines = text3.split(b"\n")
    lines.insert(2, header_line("odd", "MY VENDOR RECORD").encode())
    with pytest.warns(PsdboundWarning, match=r"line 3: 1 header record\(s\) .*'MY VENDOR RECORD'"):
        read_obs(_write(tmp_path, b"\n".join(lines), "v3.rnx"))


@pytest.mark.parametrize("version", ["5.00", "1.00", "0.50"])
def test_unsupported_versions_exit_2_with_a_specific_error(tmp_path, capsys, version):
    text = format_obs_v3(moving_observations())
    lines = text.split("\n")
    lines[0] = with_version(lines[0], version)
    p = _write(tmp_path, "\n".join(lines).encode(), "v.rnx")
    expected = (
        rf"v\.rnx, line 1: RINEX version {float(version):g} is not supported \(2\.1x, 3\.0x "
        r"and 4\.00-4\.02 are\); convert the file"
    )
    with pytest.raises(InputError, match=expected):
        read_obs(p)
    assert main(["inspect", str(p)]) == 2
    assert f"RINEX version {float(version):g} is not supported" in capsys.readouterr().err


def test_a_newer_rinex4_minor_version_is_read_with_a_warning(tmp_path):
    text4 = obs_to_v4(format_obs_v3(moving_observations()).encode("ascii"), "4.03")
    with pytest.warns(PsdboundWarning, match=r"line 1: RINEX 4\.03 is newer than the 4\.02"):
        b = read_obs(_write(tmp_path, text4, "n.rnx"))
    assert b.header.version == 4.03


def test_bad_version_field_names_the_columns(tmp_path):
    lines = format_obs_v3(moving_observations()).split("\n")
    lines[0] = "    4.O0" + lines[0][8:]
    with pytest.raises(InputError, match=r"line 1: bad RINEX version .* in columns 1-9"):
        read_obs(_write(tmp_path, "\n".join(lines).encode(), "b.rnx"))


# ------------------------------------------------------------ the real ESBC file


@pytest.fixture(scope="module")
def esbc_v3_text() -> bytes:
    """The first 2 h (240 epochs at 30 s) of the ESBC RINEX 3.05 file, plain text."""
    return cut_obs(read_bytes(shared_file(ESBC_OBS)), 240)


@pytest.mark.realdata
@pytest.mark.parametrize("form", ["plain", "gzip", "hatanaka", "hatanaka+gzip", "zip"])
def test_esbc_as_rinex4_reads_as_rinex3_in_every_container(tmp_path, esbc_v3_text, form):
    ref = read_obs(_write(tmp_path, esbc_v3_text, "esbc3.rnx"))
    files = write_variants(tmp_path, "ESBC4", obs_to_v4(esbc_v3_text, "4.01"))
    obs = _read_quietly(files[form])
    assert obs.header.version == 4.01 and obs.t_gps_s.size == 240
    assert set(obs.systems) == {"G", "R", "E", "C", "J", "S"}
    assert_same_observations(ref, obs)
    assert obs.warnings == ref.warnings


@pytest.mark.realdata
def test_esbc_as_rinex4_with_systems_and_codes(tmp_path, esbc_v3_text):
    p3 = _write(tmp_path, esbc_v3_text, "esbc3.rnx")
    p4 = _write(tmp_path, obs_to_v4(esbc_v3_text), "esbc4.rnx")
    kw = {"systems": "GE", "codes": ["L1C", "L2W", "L5Q"], "optional_codes": ["S1C"]}
    assert_same_observations(read_obs(p3, **kw), _read_quietly(p4, **kw))
