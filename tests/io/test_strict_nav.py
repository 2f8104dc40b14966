"""Navigation and SP3 readers: damaged records never become positions, ids are checked."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from test_nav import G27, PRN3_RNX2, RNX2_HEADER, RNX3_HEADER, write

from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.io import read_sp3
from psdbound.io.nav import read_nav
from psdbound.io.timescales import calendar_to_gps_s


def _field(line: str, k: int, token: str) -> str:
    """Replace the k-th 19-character field of a RINEX 3 orbit line (k = 0..3)."""
    a = 4 + 19 * k
    return line[:a] + token.rjust(19) + line[a + 19 :]


def _second_g27(line_no: int, token: str, k: int = 1) -> list[str]:
    rec = list(G27)
    rec[0] = rec[0].replace("G27", "G28")
    rec[line_no] = _field(rec[line_no], k, token)
    return rec


@pytest.mark.parametrize("token", ["nan", "inf", "-inf", "1.5e+400", "NaN"])
def test_non_finite_record_is_left_out_with_a_warning(tmp_path, token):
    p = write(tmp_path, "n.rnx", RNX3_HEADER + G27 + _second_g27(2, token))
    with pytest.warns(
        PsdboundWarning,
        match=r"n\.rnx: 1 navigation record\(s\) left out .* G28 "
        r"on line \d+, non-finite eccentricity",
    ):
        nav = read_nav(p)
    assert nav.satellites == ("G27",)
    assert nav.warnings and "left out" in nav.warnings[0]
    t = calendar_to_gps_s(2024, 5, 3, 2, 0, 0.0) + np.arange(0, 3600, 300.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy warning from the propagation
        assert np.isfinite(nav.positions_ecef_m("G27", t)).all()
        assert np.isnan(nav.positions_ecef_m("G28", t)).all()


def test_impossible_elements_and_dates_are_left_out(tmp_path):
    bad_e = _second_g27(2, "1.500000000000E+00")  # eccentricity 1.5
    bad_date = list(G27)
    bad_date[0] = bad_date[0].replace("G27 2024 05 03", "G26 2024 13 03")
    p = write(tmp_path, "e.rnx", RNX3_HEADER + G27 + bad_e + bad_date)
    with pytest.warns(PsdboundWarning, match=r"2 navigation record\(s\) left out .*eccentricity"):
        nav = read_nav(p)
    assert nav.satellites == ("G27",)


@pytest.mark.parametrize("sat", ["G99", "G00", "E77", "S10"])
def test_satellite_ids_outside_their_range_are_refused(tmp_path, sat):
    rec = list(G27)
    rec[0] = sat + rec[0][3:]
    p = write(tmp_path, "s.rnx", RNX3_HEADER + G27 + rec)
    with pytest.raises(
        InputError,
        match=rf"s\.rnx, line {len(RNX3_HEADER) + 9}: satellite id "
        f"'{sat}' in columns 1-3 is not valid",
    ):
        read_nav(p)


def test_rinex2_prn_range_and_dates(tmp_path):
    rec = list(PRN3_RNX2)
    rec[0] = "99" + rec[0][2:]
    with pytest.raises(InputError, match="satellite id 'G99' in columns 1-2 is not valid"):
        read_nav(write(tmp_path, "a.10n", RNX2_HEADER + rec))
    rec = list(PRN3_RNX2)
    rec[0] = rec[0][:11] + " 25" + rec[0][14:]  # hour 25
    with pytest.warns(PsdboundWarning, match="impossible time of clock 10 3 18 25 0 0"):
        nav = read_nav(write(tmp_path, "b.10n", RNX2_HEADER + PRN3_RNX2 + rec))
    assert len(nav.ephemerides["G"]) == 1


SP3 = """\
#cP2020  6 25  0  0  0.00000000       2 ORBIT IGS14 HLM  GRG
## 2111 345600.00000000   900.00000000 59025 0.0000000000000
+    2   G01G02  0  0  0  0  0  0  0  0  0  0  0  0  0  0  0
%c G  cc GPS ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc
*  2020  6 25  0  0  0.00000000
PG01 -17254.375431  -6688.955397  18953.624591     16.079100
PG02  13872.186289  22614.262325  -1072.646795   -477.436416
*  2020  6 25  0 15  0.00000000
PG01 -18132.377363  -8602.601405  17341.431444     16.085489
PG02  13669.728336  22773.142684   1778.018909   -477.441744
EOF
"""


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("-6688.955397", "         nan", r"line 6: y of G01 \(columns 19-32\) is 'nan'"),
        ("-6688.955397", "       1e400", r"line 6: y of G01 \(columns 19-32\) is '1e400'"),
        ("2020  6 25  0 15", "2020 13 25  0 15", r"line 8: impossible epoch"),
        ("2020  6 25  0 15", "2020  6 25  0  0", r"line 8: epoch 2 is not later"),
        ("G01G02  0", "G01G99  0", r"line 3: satellite id 'G99'"),
    ],
)
def test_sp3_values_dates_and_ids(tmp_path, old, new, message):
    text = SP3
    if "15" in old:  # the second epoch line
        i = text.index(old)
        text = text[:i] + new + text[i + len(old) :]
    else:
        text = text.replace(old, new, 1)
    p = tmp_path / "o.sp3"
    p.write_text(text)
    with pytest.raises(InputError, match=r"o\.sp3, " + message):
        read_sp3(p)


def test_clean_sp3_reads(tmp_path):
    p = tmp_path / "o.sp3"
    p.write_text(SP3)
    assert read_sp3(p).sats == ("G01", "G02")
