"""``--nav`` given twice: used whole (fit, inspect, campaign) or refused (one-file commands).

argparse keeps the last value of a repeated option: a second navigation file
replaced the first without a word.
"""

from __future__ import annotations

import pytest

from psdbound.cli import main
from psdbound.cli.main import build_parser


@pytest.mark.parametrize(
    "command",
    [["simulate"], ["validate"], ["overbound", "samples.csv"], ["budget"], ["cutoff"]],
)
def test_one_file_commands_refuse_a_second_nav(capsys, command):
    with pytest.raises(SystemExit) as exc:
        main([*command, "--nav", "a.rnx", "--nav", "b.rnx"])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [
        f"psdbound {command[0]}: error: --nav given twice (a.rnx and b.rnx): this "
        "command takes one file; give --nav once"
    ]


def test_cutoff_refuses_a_second_sp3(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["cutoff", "--sp3", "a.sp3", "--sp3", "b.sp3"])
    assert exc.value.code == 2 and "--sp3 given twice" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["fit", "o.rnx", "--nav", "a", "--nav", "b"], ["a", "b"]),
        (["inspect", "o.rnx", "--nav", "a", "--nav", "b"], ["a", "b"]),
        (["campaign", "o.rnx", "--nav", "a", "b", "--nav", "c"], ["a", "b", "c"]),
        (["fit", "o.rnx", "--nav", "a", "b"], ["a", "b"]),  # several after one --nav
        (["inspect", "o.rnx", "--nav", "a", "b", "--nav", "c"], ["a", "b", "c"]),
    ],
)
def test_nav_accumulates(args, expected):
    ns = build_parser().parse_args(args)
    assert ns.nav == expected
    assert ns.obs == ["o.rnx"]


def test_an_observation_file_after_nav_is_named(tmp_path, capsys):
    """``--nav`` takes every file after it: an observation file there gets one clear line."""
    from samples import write_small

    obs = write_small(tmp_path / "o.rnx")
    code = main(["fit", "--nav", str(obs), str(obs), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and not (tmp_path / "out").exists()
    assert err[-1].endswith("observation files go before --nav")
