"""Every option's --help states its default and its unit, from each command's option schema."""

from __future__ import annotations

import argparse
import re

import pytest

from psdbound.cli.fit import OPTIONS
from psdbound.cli.main import build_parser
from psdbound.cli.schema import help_text
from psdbound.pipeline import FitConfig

#: what counts as a unit (or an explicit statement that there is none)
UNITS = re.compile(
    r"\b(s|m|Hz|deg|degrees|min|minutes|h|hours|seconds|metres|TECU/min|sfu|dB|"
    r"m\^2|MHz|km|count|dimensionless|probability|fraction|percent)\b"
)


def _actions():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sp in sub.choices.items():
        for a in sp._actions:
            if isinstance(a, argparse._HelpAction | argparse._StoreTrueAction):
                continue
            yield name, a


@pytest.mark.parametrize(
    ("command", "action"),
    list(_actions()),
    ids=lambda x: x if isinstance(x, str) else "/".join(x.option_strings) or x.dest,
)
def test_help_states_default_and_unit(command, action):
    h = " ".join(help_text(action).split())  # as --help prints it: the schema's default added
    assert h, f"{command} {action.dest}: no help"
    assert re.search(r"default|required", h), f"{command} {action.option_strings}: {h!r}"
    if action.type in (int, float):
        assert UNITS.search(h), f"{command} {action.option_strings}: no unit in {h!r}"


def test_fit_help_defaults_are_the_library_defaults():
    """The default printed by fit --help comes from FitConfig (one source of truth)."""
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    fit = {a.option_strings[-1]: a for a in sub.choices["fit"]._actions if a.option_strings}
    cfg = FitConfig()
    checked = 0
    for opt in OPTIONS:
        flag, section, name = opt.flag, opt.section, opt.name
        if flag not in fit or opt.sets:
            continue
        value = getattr(getattr(cfg, section), name)
        if value is None or isinstance(value, bool) or value == ():
            continue
        m = re.search(r"\(default: ([^)]*)\)", help_text(fit[flag]))
        assert m, flag
        stated = m.group(1).split()[0]
        if isinstance(value, float):
            factor = 1 / 60 if flag == "--min-arc-min" else 1.0
            assert float(stated) == pytest.approx(value * factor), flag
        elif isinstance(value, tuple):
            assert stated == ",".join(map(str, value)), flag
        else:
            assert stated == str(value), flag
        checked += 1
    assert checked >= 25


def test_fit_options_are_generated_from_the_schema():
    # one table of flags (each written once); choices and number types come from the schema
    from psdbound.common.options import Choice, Number
    from psdbound.pipeline.config import section_spec

    flags = [f for o in OPTIONS for f in o.flags]
    assert len(flags) == len(set(flags))
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    fit = {a.option_strings[-1]: a for a in sub.choices["fit"]._actions if a.option_strings}
    for opt in OPTIONS:
        spec = section_spec(opt.section, opt.name)
        assert spec is not None, (opt.section, opt.name)
        action = fit.get(opt.flag)
        if action is None or opt.convert is not None or "type" in opt.kwargs:
            continue
        if isinstance(spec, Choice) and "choices" not in opt.kwargs:
            assert tuple(action.choices) == spec.choices, opt.flag
        if isinstance(spec, Number):
            assert action.type is (int if spec.integer else float), opt.flag
