"""The vectorised RINEX 3 scan gives exactly what the line-by-line reader gives."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_OBS, GRAS_OBS, NYA1_OBS, shared_file

import psdbound.io._body as body
from psdbound.io import read_obs
from psdbound.simulate import demo_data


def _read_both(path, monkeypatch, **kw):
    used = []
    scan = body.scan_v3
    with monkeypatch.context() as m:
        m.setattr(body, "scan_v3", lambda *a, **k: used.append(scan(*a, **k)) or used[-1])
        fast = read_obs(path, **kw)
    assert used and used[-1] is not None  # the vectorised scan read this file
    with monkeypatch.context() as m:
        m.setattr(body, "scan_v3", lambda *a, **k: None)  # force the line-by-line scan
        slow = read_obs(path, **kw)
    return fast, slow


def _assert_same(fast, slow):
    np.testing.assert_array_equal(fast.t_gps_s, slow.t_gps_s)
    assert list(fast.blocks) == list(slow.blocks)  # systems in the same order
    for s, b in fast.blocks.items():
        o = slow.blocks[s]
        assert b.sats == o.sats and b.codes == o.codes
        np.testing.assert_array_equal(b.values, o.values)  # NaN == NaN here
        np.testing.assert_array_equal(b.lli, o.lli)
        np.testing.assert_array_equal(b.ssi, o.ssi)
    assert tuple(fast.warnings) == tuple(slow.warnings)


@pytest.mark.parametrize("kw", [{}, {"systems": "G"}, {"codes": ["L1C", "L2W"]}])
def test_simulated_file(monkeypatch, kw):
    path = demo_data().obs_paths[0]
    fast, slow = _read_both(path, monkeypatch, **kw)
    assert fast.t_gps_s.size > 1000
    _assert_same(fast, slow)


@pytest.mark.realdata
@pytest.mark.parametrize("name", [ESBC_OBS, NYA1_OBS, GRAS_OBS])
def test_real_files(monkeypatch, name):
    fast, slow = _read_both(shared_file(name), monkeypatch)
    _assert_same(fast, slow)


def test_reading_some_codes_still_checks_the_columns(tmp_path):
    """With ``codes=`` the pseudoranges the column check needs are read (then dropped)."""
    from psdbound.errors import InputError
    from psdbound.io._source import read_bytes

    text = read_bytes(demo_data().obs_paths[0])
    good = b"G    6 C1C L1C S1C C2W L2W S2W"
    assert good in text
    bad = tmp_path / "swapped.rnx"
    bad.write_bytes(text.replace(good, b"G    6 L1C C1C S1C C2W L2W S2W"))  # two labels swapped
    for codes in (None, ["L1C", "L2W"]):
        with pytest.raises(
            InputError,
            match=r"swapped.rnx, line \d+: observation L1C of system G "
            "does not follow the range",
        ):
            read_obs(bad, codes=codes)
    some = read_obs(demo_data().obs_paths[0], codes=["L1C", "L2W"])
    assert some.blocks["G"].codes == ("L1C", "L2W")
    every = read_obs(demo_data().obs_paths[0])
    np.testing.assert_array_equal(some.phase_m("G05", "L1C"), every.phase_m("G05", "L1C"))
