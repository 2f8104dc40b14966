"""Cross-check of our observation reader against georinex (test-only dependency).

For every carrier-phase signal georinex reads, the phase values, their NaN
pattern and the loss-of-lock indicators (georinex NaN <-> our -1) must be
identical. georinex drops the loss-of-lock indicators of L5/E5/E6 signals;
we check that ours are present there.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from conftest import GRAS_OBS, NYA1_OBS, UPC1_OBS, shared_file

from psdbound.io import read_obs

gr = pytest.importorskip("georinex")


def _load_georinex(path, systems, tlim=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return gr.load(path, use=set(systems), meas=["L"], useindicators=True, tlim=tlim)


@pytest.mark.realdata
@pytest.mark.slow
@pytest.mark.parametrize(
    ("name", "systems", "tlim"),
    [
        (GRAS_OBS, "GE", None),
        (UPC1_OBS, "G", None),
        (NYA1_OBS, "GE", ("2024-05-03T00:00", "2024-05-03T02:00")),
    ],
)
def test_phases_and_lli_identical_to_georinex(name, systems, tlim):
    path = shared_file(name)
    ref = _load_georinex(path, systems, tlim)
    obs = read_obs(path, systems=systems)
    ref_t = ref.time.values.astype("datetime64[ns]")
    sel = np.isin(obs.times, ref_t)
    np.testing.assert_array_equal(obs.times[sel], ref_t)

    n_signals = n_lli = 0
    n_flags = 0
    for code in ref.data_vars:
        if code.endswith(("lli", "ssi")):
            continue
        for sv in ref.sv.values:
            sv = str(sv)
            theirs = ref[code].sel(sv=sv).values
            if sv not in obs.satellites or code not in obs.codes(sv[0]):
                assert np.isnan(theirs).all(), f"{sv} {code} read by georinex, not by us"
                continue
            ours = obs.get(sv, code)[sel]
            np.testing.assert_array_equal(ours, theirs, err_msg=f"{name} {sv} {code}")
            n_signals += 1
            if code + "lli" in ref:
                lli_theirs = ref[code + "lli"].sel(sv=sv).values
                lli_ours = obs.lli(sv, code)[sel].astype(float)
                lli_ours[lli_ours < 0] = np.nan
                np.testing.assert_array_equal(lli_ours, lli_theirs, err_msg=f"{sv} {code} LLI")
                n_lli += 1
                n_flags += int(np.nansum(lli_ours > 0))
    assert n_signals > 10 and n_lli > 10
    if name == NYA1_OBS:
        assert n_flags > 50  # the file really exercises loss-of-lock flags


@pytest.mark.realdata
def test_lli_kept_where_georinex_drops_it():
    """georinex has no L5X/L7X/L8X LLI; ours holds every LLI digit of the file text."""
    from psdbound.io._source import read_bytes

    path = shared_file(GRAS_OBS)
    ref = _load_georinex(path, "GE")
    obs = read_obs(path, systems="GE")
    text = read_bytes(path).decode("ascii").split("\n")
    for sys_, code in [("G", "L5X"), ("E", "L5X"), ("E", "L7X"), ("E", "L8X")]:
        assert code in ref and code + "lli" not in ref
        col = 3 + 16 * obs.header.obs_types[sys_].index(code) + 14
        in_text = [ln[col] for ln in text if ln[:1] == sys_ and len(ln) > col and ln[col] != " "]
        b = obs.blocks[sys_]
        lli = b.lli[:, :, b.codes.index(code)]
        assert len(in_text) > 0
        assert (lli >= 0).sum() == len(in_text)
        assert (lli > 0).sum() == sum(c != "0" for c in in_text)
