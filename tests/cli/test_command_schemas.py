"""cutoff, validate, overbound, budget, simulate, export, campaign: options from one schema.

Each command lists its options once (``OPTIONS``, rows of
:class:`psdbound.cli.schema.CliOption`) over its schema (``SCHEMA``: the
domain's options dataclass where there is one, the command's own for the
rest); the parser's types and choices, the defaults ``--help`` states and
the values read back all come from there.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import inspect
import re

import pytest

from psdbound.cli.main import build_parser, main
from psdbound.cli.schema import help_text, read_options
from psdbound.common.options import Choice, Number

COMMANDS = ("cutoff", "validate", "overbound", "budget", "simulate", "export", "campaign")
#: Options that set a name the domain reads but that is not a field (CutoffSettings.from_mapping).
NOT_FIELDS = {("cutoff", "settings", "carrier")}


def _module(command: str):
    return importlib.import_module(f"psdbound.cli.{command}")


def _actions(command: str) -> dict[str, argparse.Action]:
    parser = build_parser(command)
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {(a.option_strings or [a.dest])[-1]: a for a in sub.choices[command]._actions}


@pytest.mark.parametrize("command", COMMANDS)
def test_every_option_is_a_schema_field_listed_once(command):
    mod = _module(command)
    flags = [f for o in mod.OPTIONS for f in o.flags]
    assert len(flags) == len(set(flags))
    for opt in mod.OPTIONS:
        names = {f.name for f in dataclasses.fields(mod.SCHEMA.options_class(opt.section))}
        assert opt.name in names or (command, opt.section, opt.name) in NOT_FIELDS, opt.flag


@pytest.mark.parametrize("command", COMMANDS)
def test_parser_types_and_choices_come_from_the_schema(command):
    mod = _module(command)
    actions = _actions(command)
    for opt in mod.OPTIONS:
        spec = mod.SCHEMA.spec(opt.section, opt.name)
        action = actions[opt.flag]
        if isinstance(spec, Choice) and "choices" not in opt.kwargs:
            assert tuple(action.choices) == spec.choices, opt.flag
        if isinstance(spec, Number) and "type" not in opt.kwargs and opt.convert is None:
            assert action.type is (int if spec.integer else float), opt.flag


@pytest.mark.parametrize("command", COMMANDS)
def test_help_states_the_schema_default_with_its_unit(command):
    mod = _module(command)
    actions = _actions(command)
    checked = 0
    for opt in mod.OPTIONS:
        value = mod.SCHEMA.default(opt.section, opt.name)
        own = "(default" in (opt.help or "")
        if own or value is None or isinstance(value, bool) or value in ((), ""):
            continue
        m = re.search(r"\(default: ([^);]*)", help_text(actions[opt.flag]))
        assert m, opt.flag
        stated = m.group(1).split()
        if isinstance(value, float):
            assert float(stated[0]) == pytest.approx(value / opt.scale), opt.flag
        elif isinstance(value, tuple):
            assert [float(x) for x in stated[: len(value)]] == list(value), opt.flag
        else:
            assert stated[0] == str(value), opt.flag
        unit = opt.unit or getattr(mod.SCHEMA.spec(opt.section, opt.name), "unit", "")
        if unit and not isinstance(value, tuple):
            assert stated[1] == unit, opt.flag
        checked += 1
    # simulate's defaults are the preset's; export's own state theirs in words
    assert checked >= (0 if command in ("simulate", "export") else 2)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["cutoff", "--lat", "1", "--lon", "2", "--f107", "10"], "--f107 must be a number from 50"),
        (["cutoff", "--lat", "1", "--lon", "2", "--workers", "-1"], "--workers must be an integer"),
        (["cutoff", "--lat", "1", "--lon", "2", "--quantile", "0.2"], "--quantile must be"),
        (
            ["validate", "--cutoff-hz", "1e-3", "--geometry", "wall:d=2", "--theta0-deg", "95"],
            "--theta0-deg must be a number from -90 to 90 deg, got 95",
        ),
        (
            ["validate", "--cutoff-hz", "1e-3", "--geometry", "wall:d=2", "--min-pass-min", "0"],
            "--min-pass-min must be a number > 0 and <= 1440 min, got 0",
        ),
        (["overbound", "s.csv", "--confidence", "1"], "--confidence must be a number > 0 and < 1"),
        (["overbound", "s.csv", "--min-samples", "1"], "--min-samples must be an integer >= 2"),
        (["simulate", "--duration-h", "0"], "--duration-h must be a number > 0 and <= 8784 h"),
        (["simulate", "--lat-deg", "95"], "--lat-deg must be within [-90, 90] deg, got 95"),
        (["campaign", "a.rnx", "--nav", "n", "--workers", "-1"], "--workers must be an integer"),
        (["export", "--name", "a/b"], "--name must be a run name"),
    ],
)
def test_bad_values_name_the_flag(argv, message, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err, err


def test_values_are_read_in_the_fields_units():
    mod = _module("validate")
    argv = ["validate", "--cutoff-hz", "1e-3", "--min-pass-min", "30", "--alpha", "0.2"]
    args = build_parser("validate").parse_args(argv)
    given = read_options(args, mod.OPTIONS, mod.SCHEMA.spec)
    assert given["check"]["min_pass_s"] == 1800.0 and given["validation"]["alpha"] == 0.2
    budget = _module("budget")
    args = build_parser("budget").parse_args(["budget", "--x-air-km", "2"])
    assert read_options(args, budget.OPTIONS, budget.SCHEMA.spec)["budget"]["x_air_m"] == 2000.0


def test_budget_defaults_are_the_models():
    from psdbound.aviation import error_budget

    defaults = {
        n: p.default
        for n, p in inspect.signature(error_budget).parameters.items()
        if p.kind is inspect.Parameter.KEYWORD_ONLY
    }
    opts = _module("budget").BudgetOptions()
    for name, value in {**opts.budget_options(), "n_receivers": opts.n_receivers}.items():
        assert defaults[name] == value, name


def test_cutoff_settings_schema_and_validate_agree():
    # CutoffSettings.validate keeps the library's messages; each value its schema
    # refuses at a bound, validate refuses too, and the bounds themselves pass alike
    from psdbound.errors import InputError
    from psdbound.ionosphere import CutoffSettings

    checked = 0
    for f in dataclasses.fields(CutoffSettings):
        spec = f.metadata.get("spec")
        if not isinstance(spec, Number):
            continue
        for bound, is_open, step in ((spec.lo, spec.lo_open, -1), (spec.hi, spec.hi_open, 1)):
            if bound is None:
                continue
            outside = bound + step * (1 if spec.integer else 1e-9 * max(1.0, abs(bound)))
            with pytest.raises(InputError):
                CutoffSettings.from_mapping({f.name: outside})
            if is_open:
                with pytest.raises(InputError):
                    CutoffSettings.from_mapping({f.name: bound})
            else:
                CutoffSettings.from_mapping({f.name: bound})
            checked += 1
    assert checked >= 12
