"""A requested system the file does not hold: the error names the systems it does hold.

Reported: ``fit --system R`` on a GPS-only file said "observation code 'L1C'
is not in the header; available:" with an empty list.
"""

from __future__ import annotations

import warnings

import pytest
from samples import V2_TEXT, moving_observations

from psdbound.common.notices import PsdboundWarning
from psdbound.errors import NoDataError
from psdbound.io import read_obs
from psdbound.io.write import format_obs_v3


def _write(tmp_path, text: str, name: str = "f.rnx"):
    p = tmp_path / name
    p.write_text(text)
    return p


def _with_glonass_types(text: str) -> str:
    """The header also lists GLONASS observation types (no GLONASS record follows)."""
    line = "R    2 L1C L2P".ljust(60) + "SYS / # / OBS TYPES"
    k = text.index("    30.000")
    return text[:k] + line + "\n" + text[k:]


HEADER_MSG = (
    r"f\.rnx: no GLONASS \(R\) observations: the file holds GPS \(G\) only \(its header's "
    r"observation types\); choose one of those systems \(--system G\) or give a file with "
    r"GLONASS \(R\) observations"
)


@pytest.mark.parametrize("codes", [None, ("L1C", "L2P")])
def test_system_absent_from_the_header(tmp_path, codes):
    p = _write(tmp_path, format_obs_v3(moving_observations(seed=3)))
    with pytest.raises(NoDataError, match=HEADER_MSG):
        read_obs(p, systems="R", codes=codes)


@pytest.mark.parametrize("repeat", [False, True])  # vectorised scan, line-by-line scan
def test_system_in_the_header_but_never_observed(tmp_path, repeat):
    text = _with_glonass_types(format_obs_v3(moving_observations(seed=3)))
    if repeat:  # an exact repeat of the first epoch: the line-by-line scan
        lines = text.split("\n")
        k = next(i for i, ln in enumerate(lines) if ln.startswith(">"))
        lines[k + 3 : k + 3] = lines[k : k + 3]
        text = "\n".join(lines)
    p = _write(tmp_path, text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PsdboundWarning)  # the repeat
        assert read_obs(p, systems="G").systems == ("G",)
    msg = (
        r"f\.rnx: no GLONASS \(R\) observations: the file holds GPS \(G\) only \(its observed "
        r"satellites\); choose one of those systems \(--system G\)"
    )
    with pytest.raises(NoDataError, match=msg):
        read_obs(p, systems="R", codes=("L1C", "L2P"))


def test_rinex2_mixed_file_names_its_observed_systems(tmp_path):
    text = V2_TEXT.replace("G (GPS)            ", "M (MIXED)          ")
    p = _write(tmp_path, text, "m.10o")
    msg = r"m\.10o: no Galileo \(E\) observations: the file holds GPS \(G\) only \(its observed"
    with pytest.raises(NoDataError, match=msg):
        read_obs(p, systems="E")


def _gps_and_galileo_text() -> str:
    """A RINEX 3 file of GPS and Galileo records (Galileo a renamed copy of GPS)."""
    from dataclasses import replace

    obs = moving_observations(seed=3)
    g = obs.blocks["G"]
    e = replace(g, system="E", sats=tuple("E" + s[1:] for s in g.sats))
    header = replace(obs.header, obs_types={**obs.header.obs_types, "E": g.codes})
    return format_obs_v3(replace(obs, header=header, blocks={"G": g, "E": e}))


@pytest.mark.parametrize("repeat", [False, True])  # vectorised scan, line-by-line scan
def test_systems_in_file_names_every_system_read_or_not(tmp_path, repeat):
    text = _gps_and_galileo_text()
    if repeat:  # an exact repeat of the first epoch: the line-by-line scan
        lines = text.split("\n")
        k = next(i for i, ln in enumerate(lines) if ln.startswith(">"))
        n = int(lines[k][32:35])
        lines[k:k] = lines[k : k + n + 1]
        text = "\n".join(lines)
    p = _write(tmp_path, text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PsdboundWarning)  # the repeat
        for systems, read in (("G", ("G",)), ("E", ("E",)), (None, ("G", "E"))):
            obs = read_obs(p, systems=systems)
            assert set(obs.systems) == set(read) and obs.systems_in_file == ("E", "G")
    v2 = _write(tmp_path, V2_TEXT, "b.10o")
    assert read_obs(v2, systems="G").systems_in_file == tuple(sorted(read_obs(v2).systems))


def test_a_fit_says_which_systems_it_did_not_analyse(tmp_path):
    # the fit analyses one system: the others a file holds are named, never left silently
    from psdbound.pipeline.inputs import _unanalysed

    p = _write(tmp_path, _gps_and_galileo_text(), "mixed.rnx")
    (note,) = _unanalysed([read_obs(p, systems="G")], "G")
    assert note.startswith("mixed.rnx: the file also holds Galileo (E) observations, not ")
    assert "here GPS (G); give another with --system" in note
    assert _unanalysed([read_obs(p, systems=None)], "G")  # read or not: the same note
    gps_only = _write(tmp_path, format_obs_v3(moving_observations(seed=3)), "g.rnx")
    assert _unanalysed([read_obs(gps_only, systems="G")], "G") == []
