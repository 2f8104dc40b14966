"""RINEX observation reader: synthetic round trips, real files, bad input."""

from __future__ import annotations

import gzip

import numpy as np
import pytest
from conftest import (
    ESBC_OBS,
    GRAS_OBS,
    NYA1_OBS,
    UPC1_OBS,
    UPC2_OBS,
    shared_file,
)
from samples import NAV3_TEXT, small_observations, write_small

from psdbound.errors import InputError, NoDataError
from psdbound.io import read_obs
from psdbound.io.write import format_obs_v3


def _same(a, b):
    assert a.blocks.keys() == b.blocks.keys()
    np.testing.assert_array_equal(a.t_gps_s, b.t_gps_s)
    for s in a.blocks:
        x, y = a.blocks[s], b.blocks[s]
        assert x.sats == y.sats and x.codes == y.codes
        np.testing.assert_array_equal(x.values, y.values)
        np.testing.assert_array_equal(x.lli, y.lli)
        np.testing.assert_array_equal(x.ssi, y.ssi)


@pytest.mark.parametrize("suffix", [".rnx", ".rnx.gz", ".crx", ".crx.gz"])
def test_round_trip_all_compressions(tmp_path, suffix):
    import hatanaka

    obs = small_observations()
    plain = write_small(tmp_path / "a.rnx")
    target = tmp_path / f"b{suffix}"
    data = plain.read_bytes()
    if ".crx" in suffix:
        data = hatanaka.rnx2crx(data)
    if suffix.endswith(".gz"):
        data = gzip.compress(data)
    target.write_bytes(data)
    back = read_obs(target)
    _same(obs, back)
    # the loss-of-lock flag and the missing epochs survive
    assert back.lli("G05", "L1C")[20] == 1
    assert np.isnan(back.get("G12", "L1C")[10:13]).all()


def test_code_and_system_selection(tmp_path):
    p = write_small(tmp_path / "a.rnx")
    obs = read_obs(p, systems="G", codes=["L1C", "L2W"])
    assert obs.codes("G") == ("L1C", "L2W")
    lam1 = 299792458.0 / 1575.42e6
    np.testing.assert_allclose(obs.phase_m("G05", "L1C"), obs.get("G05", "L1C") * lam1)


def test_epoch_times_are_gps_seconds(tmp_path):
    obs = read_obs(write_small(tmp_path / "a.rnx"))
    assert obs.t_gps_s[0] == 1277078400.0  # 2020-06-25T00:00:00 GPS = week 2111 day 4
    assert obs.interval_s == 30.0
    assert str(obs.times[1]) == "2020-06-25T00:00:30.000000000"


# ---------------------------------------------------------------- bad input


def test_empty_file(tmp_path):
    p = tmp_path / "empty.rnx"
    p.write_bytes(b"")
    with pytest.raises(InputError, match=r"empty\.rnx: file is empty"):
        read_obs(p)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="nope.rnx: file not found"):
        read_obs(tmp_path / "nope.rnx")


def test_truncated_mid_epoch(tmp_path):
    text = format_obs_v3(small_observations())
    cut = text[: text.index("> 2020 06 25 00 15") + 60]  # epoch line + part of a record
    p = tmp_path / "cut.rnx"
    p.write_text(cut)
    with pytest.raises(InputError, match=r"cut\.rnx, line \d+: truncated epoch 2020 06 25 00 15"):
        read_obs(p)


def test_truncated_inside_a_number(tmp_path):
    text = format_obs_v3(small_observations())
    last = text.rstrip("\n").rsplit("\n", 1)
    p = tmp_path / "cut2.rnx"
    p.write_text(last[0] + "\n" + last[1][:25] + "\n")
    with pytest.raises(InputError, match=r"cut2\.rnx, line \d+: satellite G\d\d, observation"):
        read_obs(p)


def test_navigation_file_given_as_observations(tmp_path):
    p = tmp_path / "brdc.rnx"
    p.write_text(NAV3_TEXT)
    with pytest.raises(
        InputError,
        match=r"brdc\.rnx, line 1: this is a navigation file.*"
        "expected an observation file",
    ):
        read_obs(p)


def test_plain_text(tmp_path):
    p = tmp_path / "notes.txt"
    p.write_text("hello\nthis is not RINEX\n")
    with pytest.raises(InputError, match=r"notes\.txt, line 1: not a RINEX file"):
        read_obs(p)


def test_unknown_signal(tmp_path):
    p = write_small(tmp_path / "a.rnx")
    with pytest.raises(InputError, match=r"a\.rnx: observation code 'L9Z' is not in the header"):
        read_obs(p, codes=["L9Z"])
    obs = read_obs(p)
    with pytest.raises(
        InputError,
        match=r"signal 'L5Q' is not in the file for GPS; "
        "available: C1C L1C L2W S1C",
    ):
        obs.phase_m("G05", "L5Q")


def test_requested_system_without_epochs(tmp_path):
    p = write_small(tmp_path / "a.rnx")
    with pytest.raises(
        NoDataError,
        match=r"a\.rnx: no Galileo \(E\) observations: the file "
        r"holds GPS \(G\) only",
    ):
        read_obs(p, systems="GE")


def test_corrupted_hatanaka_stream(tmp_path):
    import hatanaka

    crx = bytearray(hatanaka.rnx2crx(write_small(tmp_path / "a.rnx").read_bytes()))
    mid = len(crx) // 2
    crx[mid : mid + 200] = b"#" * 200
    p = tmp_path / "bad.crx"
    p.write_bytes(bytes(crx))
    with pytest.raises(InputError, match=r"bad\.crx: corrupted Hatanaka"):
        read_obs(p)


def test_corrupted_gzip(tmp_path):
    data = gzip.compress(write_small(tmp_path / "a.rnx").read_bytes())
    p = tmp_path / "bad.rnx.gz"
    p.write_bytes(data[: len(data) // 2])
    with pytest.raises(InputError, match=r"bad\.rnx\.gz: cannot decompress"):
        read_obs(p)


# ---------------------------------------------------------------- real files


@pytest.mark.parametrize(
    ("name", "version", "n_epoch", "interval", "systems"),
    [
        (ESBC_OBS, 3.05, 2880, 30.0, {"G", "E", "R", "C", "J", "S"}),
        (NYA1_OBS, 3.05, 2880, 30.0, {"G", "E", "R", "C"}),
        (GRAS_OBS, 3.04, 900, 1.0, {"G", "E", "R", "C", "S"}),
        (UPC1_OBS, 2.11, 3600, 1.0, {"G"}),
        (UPC2_OBS, 2.11, 3600, 1.0, {"G"}),
    ],
)
def test_real_files(name, version, n_epoch, interval, systems):
    obs = read_obs(shared_file(name))
    assert obs.header.version == version
    assert obs.t_gps_s.size == n_epoch
    assert obs.interval_s == interval
    assert set(obs.systems) == systems
    steps = np.diff(obs.t_gps_s)
    assert (steps > 0).all()
    assert obs.header.approx_position_m is not None
    assert 6.3e6 < np.linalg.norm(obs.header.approx_position_m) < 6.4e6
    # every system has carrier phases with realistic magnitudes (1e7..3e8 cycles)
    for b in obs.blocks.values():
        k = [i for i, c in enumerate(b.codes) if c.startswith("L")]
        ph = np.abs(b.values[:, :, k])
        ph = ph[np.isfinite(ph) & (ph > 0)]
        assert ph.size > 1000 and 1e6 < np.median(ph) < 3e8


def test_nya1_loss_of_lock_on_every_signal():
    """NYA1 (Trimble) carries LLI flags; L5 and Galileo E5/E6 keep theirs."""
    obs = read_obs(shared_file(NYA1_OBS), systems="GE")
    for sys_, code in [
        ("G", "L1C"),
        ("G", "L2W"),
        ("G", "L5X"),
        ("E", "L5X"),
        ("E", "L6X"),
        ("E", "L7X"),
    ]:
        b = obs.blocks[sys_]
        k = b.codes.index(code)
        lost = (b.lli[:, :, k] > 0) & (b.lli[:, :, k] & 1 > 0)
        assert lost.sum() > 0, f"{sys_} {code}: no loss-of-lock flag read"
