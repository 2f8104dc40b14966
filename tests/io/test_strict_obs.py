"""The observation reader is strict: damaged files are refused with file and line, never misread.

One test per case of issue #17 ("bad input never becomes a number"), on small
synthetic files so that they run without ../shared/data.
"""

from __future__ import annotations

import gzip
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from samples import V2_TEXT, moving_observations, small_observations

from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.io import read_obs
from psdbound.io.write import format_obs_v3


def _text() -> str:
    return format_obs_v3(moving_observations())


def _lines(text: str) -> list[str]:
    return text.split("\n")


def _line_of(text: str, pattern: str) -> int:
    """1-based number of the first line matching ``pattern``."""
    return next(i for i, ln in enumerate(_lines(text), 1) if re.search(pattern, ln))


def _write(tmp_path: Path, text: str | bytes, name: str = "f.rnx") -> Path:
    p = tmp_path / name
    p.write_bytes(text.encode() if isinstance(text, str) else text)
    return p


def _replace_line(text: str, lineno: int, new: str) -> str:
    lines = _lines(text)
    lines[lineno - 1] = new
    return "\n".join(lines)


# ------------------------------------------------------------- observation-type lists


def test_blank_code_in_type_list_is_refused_with_its_line(tmp_path):
    text = _text()
    k = _line_of(text, "SYS / # / OBS TYPES")
    ln = _lines(text)[k - 1]
    p = _write(tmp_path, _replace_line(text, k, ln[:11] + "   " + ln[14:]))  # L1C blanked
    with pytest.raises(InputError, match=rf"f\.rnx, line {k}: .*observation code 2 of 5 is blank"):
        read_obs(p)


def test_type_count_must_match_the_codes(tmp_path):
    text = _text()
    k = _line_of(text, "SYS / # / OBS TYPES")
    ln = _lines(text)[k - 1]
    p = _write(tmp_path, _replace_line(text, k, ln[:3] + "  6" + ln[6:]))
    with pytest.raises(InputError, match=rf"line {k}: .*observation code 6 of 6 is blank"):
        read_obs(p)
    # a continuation line of a long list lost
    codes = " ".join([f"{c}{b}C" for c in "CLDS" for b in "125"] + ["C1W"])
    long = "G   14 " + codes
    p = _write(tmp_path, _replace_line(text, k, long.ljust(60) + "SYS / # / OBS TYPES"))
    with pytest.raises(
        InputError,
        match=rf"line {k}: the observation types of system G declare "
        "14 codes but list 13",
    ):
        read_obs(p)
    p = _write(tmp_path, _replace_line(text, k, ln[:3] + "  4" + ln[6:]))
    with pytest.raises(InputError, match=rf"line {k}: .*more observation types than the 4"):
        read_obs(p)


def test_dropped_code_with_its_count_is_refused_by_the_line_width(tmp_path):
    text = _text()
    k = _line_of(text, "SYS / # / OBS TYPES")
    # S1C dropped and the count decremented: every record is one field too wide
    p = _write(
        tmp_path, _replace_line(text, k, "G    4 C1C L1C L2W D1C".ljust(60) + "SYS / # / OBS TYPES")
    )
    with pytest.raises(
        InputError,
        match=r"f\.rnx, line \d+: satellite G05: the record is .* "
        r"observation types of G end at column 67",
    ):
        read_obs(p)


def test_mislabelled_phase_column_is_refused(tmp_path):
    text = _text()
    k = _line_of(text, "SYS / # / OBS TYPES")
    # L1C and L2W swapped in the header: each phase is read with the other wavelength
    p = _write(
        tmp_path,
        _replace_line(text, k, "G    5 C1C L2W L1C D1C S1C".ljust(60) + "SYS / # / OBS TYPES"),
    )
    with pytest.raises(
        InputError,
        match=rf"line {k}: observation L2W of system G does not "
        "follow the range",
    ):
        read_obs(p)


def test_rinex2_type_list_and_widths(tmp_path):
    k = _line_of(V2_TEXT, "TYPES OF OBSERV")
    blank = V2_TEXT.replace("    C1    L1    L2    P2", "    C1          L2    P2")
    with pytest.raises(InputError, match=rf"line {k}: .*observation code 2 of 4 is blank"):
        read_obs(_write(tmp_path, blank, "a.10o"))
    wide = V2_TEXT.replace("  22018001.000 6\n", "  22018001.000 6  22018001.000 6\n")
    with pytest.raises(InputError, match=r"satellite G05: characters beyond column 64"):
        read_obs(_write(tmp_path, wide, "b.10o"))
    assert read_obs(_write(tmp_path, V2_TEXT, "c.10o")).interval_s == 30.0


# ------------------------------------------------------------- epochs


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("month", "13"),
        ("day", "32"),
        ("hour", "25"),
        ("second", "        nan"),
        ("second", "       1e30"),
        ("year", "9999"),
        ("minute", "60"),
        ("day", "31"),
    ],
)
def test_impossible_epoch_dates_are_refused_with_the_line(tmp_path, field, value):
    text = _text()
    k = _line_of(text, r"^> 2020 06 25 00 05  0\.")
    ln = _lines(text)[k - 1]
    cols = {
        "year": (2, 6),
        "month": (7, 9),
        "day": (10, 12),
        "hour": (13, 15),
        "minute": (16, 18),
        "second": (18, 29),
    }[field]
    new = ln[: cols[0]] + value.rjust(cols[1] - cols[0]) + ln[cols[1] :]
    p = _write(tmp_path, _replace_line(text, k, new))
    with pytest.raises(InputError, match=rf"f\.rnx, line {k}: (impossible|bad) epoch date"):
        read_obs(p)


def test_out_of_order_epochs_are_refused_with_the_line(tmp_path):
    text = _text()
    a = _line_of(text, r"^> 2020 06 25 00 05  0\.")
    b = _line_of(text, r"^> 2020 06 25 00 10  0\.")
    lines = _lines(text)
    lines[a - 1 : a + 2], lines[b - 1 : b + 2] = lines[b - 1 : b + 2], lines[a - 1 : a + 2]
    p = _write(tmp_path, "\n".join(lines))
    message = rf"line {a + 3}: epoch 2020-06-25 00:05:30.000 is earlier than .*line {a}"
    with pytest.raises(InputError, match=message):
        read_obs(p)


def test_repeated_epoch_with_same_data_is_dropped_with_a_warning(tmp_path):
    text = _text()
    a = _line_of(text, r"^> 2020 06 25 00 05  0\.")
    lines = _lines(text)
    lines[a + 2 : a + 2] = lines[a - 1 : a + 2]
    p = _write(tmp_path, "\n".join(lines))
    with pytest.warns(PsdboundWarning, match=rf"f\.rnx, line {a + 3}: 1 epoch\(s\) repeated"):
        obs = read_obs(p)
    ref = read_obs(_write(tmp_path, text, "ref.rnx"))
    np.testing.assert_array_equal(obs.t_gps_s, ref.t_gps_s)
    np.testing.assert_array_equal(obs.blocks["G"].values, ref.blocks["G"].values)
    assert obs.warnings and "repeated" in obs.warnings[0]


def test_repeated_epoch_with_other_data_is_refused(tmp_path):
    text = _text()
    a = _line_of(text, r"^> 2020 06 25 00 05  0\.")
    lines = _lines(text)
    rep = lines[a - 1 : a + 2]
    rep[1] = rep[1][:14] + ("1" if rep[1][14] != "1" else "2") + rep[1][15:]
    lines[a + 2 : a + 2] = rep
    with pytest.raises(
        InputError,
        match=rf"line {a + 3}: epoch 2020-06-25 00:05:00.000 appears "
        rf"twice with different data \(lines {a} and {a + 3}\)",
    ):
        read_obs(_write(tmp_path, "\n".join(lines)))


def test_epoch_before_time_of_first_obs_is_refused(tmp_path):
    text = _text().replace(
        "  2020     6    25     0     0    0.0000000     GPS",
        "  2020     6    25     0     5    0.0000000     GPS",
    )
    with pytest.raises(InputError, match="is before the header's TIME OF FIRST OBS"):
        read_obs(_write(tmp_path, text))


@pytest.mark.parametrize("value", ["nan", "inf", "-30", "1e30", "abc", "15"])
def test_interval_comes_from_the_epochs(tmp_path, value):
    text = _text().replace(
        "    30.000" + " " * 50 + "INTERVAL", value.rjust(10) + " " * 50 + "INTERVAL"
    )
    assert value.rjust(10) + " " * 50 + "INTERVAL" in text
    with pytest.warns(PsdboundWarning, match="INTERVAL"):
        obs = read_obs(_write(tmp_path, text))
    assert obs.interval_s == 30.0
    assert "interval 30 s" in obs.summary()


def test_epoch_flags_and_record_counts_are_checked(tmp_path):
    text = _text()
    k = _line_of(text, r"^> 2020 06 25 00 05  0\.")
    ln = _lines(text)[k - 1]
    with pytest.raises(InputError, match=rf"line {k}: epoch flag 7 is not a RINEX epoch flag"):
        read_obs(_write(tmp_path, _replace_line(text, k, ln[:31] + "7" + ln[32:])))
    with pytest.raises(
        InputError,
        match=rf"line {k + 2}: epoch .* announces 1 satellite records "
        "but the next epoch starts after 2 lines",
    ):
        read_obs(_write(tmp_path, _replace_line(text, k, ln[:32] + "  1")))
    # an event (flag 4) that redefines the observation types
    lines = _lines(text)
    event = [
        "> 2020 06 25 00 05 10.0000000  4  1",
        "G    2 C1C L1C".ljust(60) + "SYS / # / OBS TYPES",
    ]
    lines[k + 2 : k + 2] = event
    with pytest.raises(InputError, match=rf"line {k + 4}: the observation types are redefined"):
        read_obs(_write(tmp_path, "\n".join(lines)))


# ------------------------------------------------------------- values and satellites


@pytest.mark.parametrize("token", ["nan", "inf", "1e30", "1.0D+05", "12 34.567", "abc"])
def test_values_outside_the_format_are_refused_with_line_and_field(tmp_path, token):
    text = _text()
    k = _line_of(text, r"^G05")
    ln = _lines(text)[k - 1]
    new = ln[:19] + token.rjust(14) + ln[33:]  # the L1C field
    with pytest.raises(
        InputError,
        match=rf"f\.rnx, line {k}: satellite G05, observation L1C: "
        ".* is not an F14.3 number",
    ):
        read_obs(_write(tmp_path, _replace_line(text, k, new)))


@pytest.mark.parametrize("sat", ["G99", "G00", "GAB", "G 0"])
def test_satellite_ids_outside_the_format_are_refused(tmp_path, sat):
    text = _text()
    k = _line_of(text, r"^G12")
    ln = _lines(text)[k - 1]
    with pytest.raises(InputError, match=rf"line {k}: satellite id .* is not valid"):
        read_obs(_write(tmp_path, _replace_line(text, k, sat + ln[3:])))


def test_values_that_cannot_be_their_type_are_refused(tmp_path):
    text = _text()
    k = _line_of(text, r"^G05")
    ln = _lines(text)[k - 1]
    new = ln[:67] + "-45.000".rjust(14) + ln[81:]  # a negative signal strength
    with pytest.raises(
        InputError,
        match=rf"line {k}: satellite G05, observation S1C: -45.000 "
        "is not a signal strength",
    ):
        read_obs(_write(tmp_path, _replace_line(text, k, new)))


def test_two_records_of_one_satellite_in_an_epoch(tmp_path):
    text = _text()
    k = _line_of(text, r"^> 2020 06 25 00 05  0\.")
    lines = _lines(text)
    lines[k + 1] = lines[k]
    with pytest.raises(InputError, match=rf"line {k + 2}: satellite G05 has two records"):
        read_obs(_write(tmp_path, "\n".join(lines)))


# ------------------------------------------------------------- files


def test_crlf_reads_the_same(tmp_path):
    text = _text()
    a = read_obs(_write(tmp_path, text, "a.rnx"))
    b = read_obs(_write(tmp_path, text.replace("\n", "\r\n"), "b.rnx"))
    np.testing.assert_array_equal(a.blocks["G"].values, b.blocks["G"].values)


def test_damaged_gzip_and_unreadable_files(tmp_path, monkeypatch):
    data = bytearray(gzip.compress(_text().encode(), mtime=0))
    data[40:44] = b"\x00\xff\x13\x37"
    with pytest.raises(InputError, match=r"bad\.rnx\.gz: cannot decompress"):
        read_obs(_write(tmp_path, bytes(data), "bad.rnx.gz"))
    with pytest.raises(InputError, match="is a folder, not a file"):
        read_obs(tmp_path)
    p = _write(tmp_path, _text(), "locked.rnx")

    def denied(self):
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(Path, "read_bytes", denied)
    with pytest.raises(InputError, match=r"locked\.rnx: cannot read the file: Permission denied"):
        read_obs(p)


def test_zip_archives_of_one_file_read_like_the_file(tmp_path):
    import zipfile

    text = _text()
    plain = read_obs(_write(tmp_path, text, "a.rnx"))
    for name, data in (("a.rnx", text.encode()), ("a.rnx.gz", gzip.compress(text.encode()))):
        with zipfile.ZipFile(tmp_path / f"{name}.zip", "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr(name, data)  # a plain member, and a gzip file inside the archive
        got = read_obs(tmp_path / f"{name}.zip")
        np.testing.assert_array_equal(got.blocks["G"].values, plain.blocks["G"].values)
    zipfile.ZipFile(tmp_path / "empty.zip", "w").close()  # was 'not a RINEX file ... PK'
    with pytest.raises(InputError, match=r"empty\.zip: zip archive holds no file"):
        read_obs(tmp_path / "empty.zip")
    with zipfile.ZipFile(tmp_path / "note.zip", "w") as z:
        z.writestr("note.txt", "hello\n")  # was 'cannot decompress: file is too short ...'
    with pytest.raises(InputError, match=r"note\.zip, line 1: not a RINEX file.*'hello'"):
        read_obs(tmp_path / "note.zip")


def test_clean_files_give_no_warning(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        read_obs(_write(tmp_path, _text(), "a.rnx"))
        read_obs(_write(tmp_path, format_obs_v3(small_observations()), "b.rnx"))
        read_obs(_write(tmp_path, V2_TEXT, "c.10o"))


def test_rinex2_file_ending_inside_the_last_records_blank_continuation(tmp_path):
    """CRX2RNX output can lose the blank continuation line of the last record at the file's end
    (IGS york0440.15d): read it as blank, and say so; a missing satellite stays an error."""
    six = V2_TEXT.replace(
        "     4    C1    L1    L2    P2                              # / TYPES OF OBSERV",
        "     6    C1    L1    L2    P2    S1    S2                  # / TYPES OF OBSERV",
    )
    lines = six.splitlines()
    body = lines.index(next(ln for ln in lines if ln.startswith(" 20  6 25  0  0  0.0")))
    out = lines[:body]
    for ln in lines[body:]:
        out.append(ln if not ln.startswith("  2") else ln + "        45.000  ")
        if ln.startswith("  2"):
            out.append("")  # S2 blank: an empty continuation line
    whole = "\n".join(out) + "\n"
    ref = read_obs(_write(tmp_path, whole, "whole.10o"))
    cut = whole.rstrip("\n") + "\n"  # the last (blank) continuation line is gone
    assert cut != whole
    with pytest.warns(PsdboundWarning, match=r"ends 1 line\(s\) into the last epoch's last record"):
        obs = read_obs(_write(tmp_path, cut, "cut.10o"))
    np.testing.assert_array_equal(obs.blocks["G"].values, ref.blocks["G"].values)
    short = "\n".join(out[:-3]) + "\n"  # the last satellite's record is gone
    with pytest.raises(InputError, match="truncated epoch"):
        read_obs(_write(tmp_path, short, "short.10o"))


# ------------------------------------------------------------- records shifted from their columns


def _shifted(text: str, label: str, body: str) -> tuple[str, int]:
    k = _line_of(text, re.escape(label))
    return _replace_line(text, k, f"{body:<60}{label:<20}"), k


def _read_noting(p: Path, k: int, label: str):
    match = rf"line {k}: {re.escape(label)} is not in the columns"
    with pytest.warns(PsdboundWarning, match=match):
        return read_obs(p)


def test_position_in_15_wide_fields_reads_with_a_note(tmp_path):
    """Some writers use F15.4: the fixed columns split a number, blanks do not."""
    ref = read_obs(_write(tmp_path, _text(), "ref.rnx"))
    label = "APPROX POSITION XYZ"
    body = "".join(f"{x:15.4f}" for x in ref.header.approx_position_m)
    text, k = _shifted(_text(), label, body)
    obs = _read_noting(_write(tmp_path, text), k, label)
    np.testing.assert_allclose(
        obs.header.approx_position_m, ref.header.approx_position_m, atol=1e-4
    )


def test_time_of_first_obs_shifted_by_one_column_reads_with_a_note(tmp_path):
    ref = read_obs(_write(tmp_path, _text(), "ref.rnx"))
    label = "TIME OF FIRST OBS"
    text, k = _shifted(_text(), label, "  2020     6    25     0     0     0.0000000     GPS")
    obs = _read_noting(_write(tmp_path, text), k, label)
    assert obs.header.first_obs == ref.header.first_obs
    assert obs.header.time_system == "GPS"
    np.testing.assert_array_equal(obs.t_gps_s, ref.t_gps_s)


@pytest.mark.parametrize(
    "body",
    [
        "  2020     6    25     0     0    0 .0000000     GPS",  # a blank inside the seconds
        "  2020     6    25     0     0     0.0000000     XYZ",  # no known time system
        "  2020     6    25     0     0",  # seconds missing
    ],
)
def test_time_records_that_blanks_cannot_explain_are_still_refused(tmp_path, body):
    text, k = _shifted(_text(), "TIME OF FIRST OBS", body)
    with pytest.raises(InputError, match=rf"f\.rnx, line {k}: "):
        read_obs(_write(tmp_path, text))


def test_position_that_blanks_cannot_explain_is_still_refused(tmp_path):
    body = "  3582105.2910   532589.77 13  5232754.8054"  # four tokens
    text, k = _shifted(_text(), "APPROX POSITION XYZ", body)
    with pytest.raises(InputError, match=rf"line {k}: .*'APPROX POSITION XYZ'"):
        read_obs(_write(tmp_path, text))


@pytest.mark.parametrize(
    ("body", "expected"),
    [
        ("  3 R11 -5 R19  3 R23 -6", {"R11": -5, "R19": 3, "R23": -6}),
        ("  3 R11 -5R19 +3R23 -6", {"R11": -5, "R19": 3, "R23": -6}),  # no blank after I2
    ],
)
def test_glonass_channels_with_and_without_the_blank_after_each(body, expected):
    from psdbound.io._header_records import HeaderRecords

    rec = HeaderRecords(3.04, Path("f.rnx"))
    rec.read(f"{body:<60}GLONASS SLOT / FRQ #", 12)
    assert rec.glo == expected


@pytest.mark.parametrize("body", ["  2 R11 -5 R19", "  1 R11 12", "  1 R11 -5 junk"])
def test_glonass_channels_that_are_not_pairs_are_refused(body):
    from psdbound.io._header_records import HeaderRecords

    rec = HeaderRecords(3.04, Path("f.rnx"))
    with pytest.raises(InputError, match=r"line 12: cannot parse header record 'GLONASS SLOT"):
        rec.read(f"{body:<60}GLONASS SLOT / FRQ #", 12)
