"""--config FILE.toml of the commands whose options are their flags: the same as the flags."""

from __future__ import annotations

import argparse

import pytest

from psdbound.cli.config_file import apply_config
from psdbound.cli.main import build_parser, main
from psdbound.errors import InputError

#: A command line that parses for each command (its required arguments).
BASE = {
    "cutoff": ["cutoff"],
    "validate": ["validate", "--cutoff-hz", "1e-3"],
    "overbound": ["overbound", "samples.csv"],
    "budget": ["budget"],
    "simulate": ["simulate"],
}


def _parse(argv: list[str]) -> argparse.Namespace:
    args = build_parser(argv[0]).parse_args(argv)
    apply_config(args, argv)
    return args


def _options(command: str) -> list[argparse.Action]:
    """The command's typed and choice options (each a TOML key)."""
    parser = build_parser(command)
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    p = sub.choices[command]
    return [
        a
        for a in p._actions
        if a.option_strings
        and a.dest not in ("help", "config")
        and (a.choices or a.type in (int, float))
        and a.nargs in (None, "?")
        and not isinstance(a, argparse._AppendAction)
    ]


def _value(action: argparse.Action):
    if action.choices:
        return list(action.choices)[-1]
    return 3 if action.type is int else 0.25


@pytest.mark.parametrize("command", sorted(BASE))
def test_every_option_reads_from_toml_as_from_its_flag(command, tmp_path):
    actions = _options(command)
    assert actions, command
    for action in actions:
        if set(action.option_strings) & set(BASE[command]):
            continue  # on the base command line, which wins
        key = action.option_strings[-1].lstrip("-")
        value = _value(action)
        toml = tmp_path / f"{key}.toml"
        text = f'"{value}"' if isinstance(value, str) else str(value)
        toml.write_text(f"[{command}]\n{key.replace('-', '_')} = {text}\n")
        flagged = _parse([*BASE[command], action.option_strings[-1], str(value)])
        filed = _parse([*BASE[command], "--config", str(toml)])
        assert getattr(filed, action.dest) == getattr(flagged, action.dest), key


def test_command_line_wins_and_top_level_keys_work(tmp_path):
    toml = tmp_path / "o.toml"
    toml.write_text("min_samples = 50\nmethod = 'cdf'\n")
    args = _parse(["overbound", "s.csv", "--config", str(toml), "--min-samples", "70"])
    assert args.min_samples == 70 and args.method == "cdf"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("frobnicate = 1", "frobnicate is not an option of psdbound overbound"),
        ("method = 'median'", "method must be one of"),
        ("min_samples = 'many'", "min_samples"),
        ("min_samples = [1, 2]", "min_samples must be a single value"),
        # keys at the top level beside an [overbound] table were dropped without a word
        ("min_samples = 50\n[overbound]\nmethod = 'cdf'", "both at the top level"),
    ],
)
def test_bad_keys_and_values_name_the_file_and_key(tmp_path, text, message):
    toml = tmp_path / "bad.toml"
    toml.write_text(text + "\n")
    with pytest.raises(InputError, match=message) as exc:
        _parse(["overbound", "s.csv", "--config", str(toml)])
    assert "bad.toml" in str(exc.value)


def test_bad_config_is_exit_2(tmp_path, capsys):
    toml = tmp_path / "bad.toml"
    toml.write_text("frobnicate = 1\n")
    assert main(["budget", "--config", str(toml)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "frobnicate" in err and "bad.toml" in err
