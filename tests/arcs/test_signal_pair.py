"""The dual-frequency pair a file holds: per carrier, the first candidate with phases."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from samples import small_observations, write_small

from psdbound.arcs import DEFAULT_SIGNALS, SIGNAL_CANDIDATES, default_pair
from psdbound.errors import InputError
from psdbound.io import read_obs


def _renamed(obs, names):
    """The observations with their codes renamed (another receiver's tracking modes)."""
    b = obs.blocks["G"]
    codes = tuple(names.get(c, c) for c in b.codes)
    header = replace(obs.header, obs_types={"G": codes})
    return replace(obs, header=header, blocks={"G": replace(b, codes=codes)})


def test_the_default_pair_is_the_first_candidate_of_each_carrier():
    for system, (first, second) in SIGNAL_CANDIDATES.items():
        assert DEFAULT_SIGNALS[system] == (first[0], second[0])
        assert {c[1] for c in first}.isdisjoint({c[1] for c in second})  # two carriers


def test_a_file_with_the_default_pair_keeps_it():
    assert default_pair(small_observations(), "G") == ("L1C", "L2W")


@pytest.mark.parametrize(
    ("names", "pair"),
    [
        ({"L1C": "L1X", "L2W": "L2L"}, ("L1X", "L2L")),  # another receiver's tracking modes
        ({"L2W": "L5Q"}, ("L1C", "L5Q")),  # an L1/L5 receiver (a phone)
    ],
)
def test_other_tracking_modes_are_used_in_order_of_preference(names, pair):
    assert default_pair(_renamed(small_observations(), names), "G") == pair


def test_a_listed_code_without_phases_is_passed_over():
    obs = small_observations()
    b = obs.blocks["G"]
    v = b.values.copy()
    v[:, :, b.codes.index("L2W")] = np.nan  # in the header, never observed
    extra = replace(b, codes=(*b.codes, "L2L"), values=np.concatenate([v, v[:, :, 1:2]], axis=2))
    extra = replace(
        extra,
        lli=np.concatenate([b.lli, b.lli[:, :, 1:2]], axis=2),
        ssi=np.concatenate([b.ssi, b.ssi[:, :, 1:2]], axis=2),
    )
    obs = replace(obs, blocks={"G": extra})
    assert obs.phase_count("G", "L2W") == 0 and obs.phase_count("G", "L2L") > 0
    assert default_pair(obs, "G") == ("L1C", "L2L")


def test_listed_codes_without_phases_keep_the_default_and_its_reason():
    """No candidate with phases: the listed default stays, so the empty arcs say what is missing."""
    obs = small_observations()
    b = obs.blocks["G"]
    v = b.values.copy()
    v[:, :, b.codes.index("L2W")] = np.nan
    assert default_pair(replace(obs, blocks={"G": replace(b, values=v)}), "G") == ("L1C", "L2W")


def test_no_candidate_is_one_clear_error():
    obs = _renamed(small_observations(), {"L2W": "L9Z"})
    with pytest.raises(InputError, match="give the pair with --signals"):
        default_pair(obs, "G")


def test_reader_keeps_every_listed_alternative(tmp_path):
    path = write_small(tmp_path / "s.rnx")
    obs = read_obs(path, codes=[("L1X", "L1C"), ("L2L", "L2W")])
    assert set(obs.codes("G")) >= {"L1C", "L2W"}
    with pytest.raises(InputError, match="any of L5Q, L5X"):
        read_obs(path, codes=["L1C", ("L5Q", "L5X")])
