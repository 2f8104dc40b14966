"""Merging consecutive observation files of one station (issue 18)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from samples import esbc_hours

from psdbound.errors import InputError
from psdbound.io import read_obs
from psdbound.io.merge import merge_observations, same_station, station_key


def _hours(tmp_path, hours, name):
    return read_obs(esbc_hours(tmp_path / name, hours), systems="G")


@pytest.fixture(scope="module")
def pieces(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("merge")
    return _hours(tmp, (0, 1), "a.rnx"), _hours(tmp, (1, 2), "b.rnx"), _hours(tmp, (4,), "c.rnx")


@pytest.mark.realdata
def test_overlap_kept_once_and_said(pieces):
    a, b, c = pieces
    m = merge_observations([c, b, a])  # any order
    assert np.all(np.diff(m.t_gps_s) > 0)
    assert m.t_gps_s.size == 3 * 120 + 120  # hours 0, 1, 2 and 4 at 30 s
    assert any("120 epoch(s) present in more than one" in w for w in m.warnings)
    assert m.path.startswith(a.path) and station_key(m) == "ESBC"
    blk, blk_a = m.blocks["G"], a.blocks["G"]
    i, j = m.codes("G").index("L1C"), blk_a.codes.index("L1C")
    for s in blk_a.sats:
        np.testing.assert_array_equal(
            blk.values[:120, blk.sats.index(s), i], blk_a.values[:120, blk_a.sats.index(s), j]
        )


@pytest.mark.realdata
def test_union_of_codes_and_errors(pieces):
    a, b, _ = pieces
    blk = b.blocks["G"]
    fewer = replace(
        b,
        blocks={
            "G": replace(
                blk,
                codes=blk.codes[:-1],
                values=blk.values[..., :-1],
                lli=blk.lli[..., :-1],
                ssi=blk.ssi[..., :-1],
            )
        },
    )
    m = merge_observations([a, fewer])
    last = m.codes("G").index(blk.codes[-1])
    assert np.isnan(m.blocks["G"].values[-1, :, last]).all()  # missing code: NaN, not dropped
    other = replace(b, header=replace(b.header, marker_name="ZZZZ"))
    assert not same_station(a, other)
    with pytest.raises(InputError, match="different stations.*'ESBC'.*'ZZZZ'"):
        merge_observations([a, other])
    slow = replace(
        b,
        t_gps_s=b.t_gps_s[::2],
        epoch_flag=b.epoch_flag[::2],
        header=replace(b.header, interval_s=60.0),
        blocks={"G": replace(blk, values=blk.values[::2], lli=blk.lli[::2], ssi=blk.ssi[::2])},
    )
    with pytest.raises(InputError, match="different sampling intervals"):
        merge_observations([a, slow])


def test_zip_members_and_duplicate_names(tmp_path):
    import zipfile

    from psdbound.io.archive import extract_zip, zip_members

    plain = tmp_path / "a.rnx"
    plain.write_text("not a zip\n")
    assert zip_members(plain) == []
    z = tmp_path / "two.zip"
    with zipfile.ZipFile(z, "w") as zf:
        zf.writestr("x/a.rnx", "1")
        zf.writestr("y/a.rnx", "2")
        zf.writestr("y/", "")
    assert zip_members(z) == ["x/a.rnx", "y/a.rnx"]
    out = tmp_path / "out"
    out.mkdir()
    with pytest.raises(InputError, match="two members named 'a.rnx'"):
        extract_zip(z, out)
