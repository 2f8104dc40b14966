"""Every option's --help states its default and its unit; fit's defaults are the library's."""

from __future__ import annotations

import argparse
import re

import pytest

from psdbound.cli.fit import FLAGS, help_text
from psdbound.cli.main import build_parser
from psdbound.pipeline import FitConfig

#: what counts as a unit (or an explicit statement that there is none)
UNITS = re.compile(r"\b(s|m|Hz|deg|degrees|min|minutes|h|hours|seconds|metres|TECU/min|sfu|dB|"
                   r"m\^2|MHz|km|count|dimensionless|probability|fraction|percent)\b")  # fmt: skip


def _actions():
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sp in sub.choices.items():
        for a in sp._actions:
            if isinstance(a, argparse._HelpAction | argparse._StoreTrueAction):
                continue
            yield name, a


@pytest.mark.parametrize(("command", "action"), list(_actions()),
                         ids=lambda x: x if isinstance(x, str) else "/".join(
                             x.option_strings) or x.dest)  # fmt: skip
def test_help_states_default_and_unit(command, action):
    shared = command in ("fit", "campaign", "export")  # fit's day options and formatter
    h = " ".join((help_text(action) if shared else action.help or "").split())
    assert h, f"{command} {action.dest}: no help"
    assert re.search(r"default|required", h), f"{command} {action.option_strings}: {h!r}"
    if action.type in (int, float):
        assert UNITS.search(h), f"{command} {action.option_strings}: no unit in {h!r}"


def test_fit_help_defaults_are_the_library_defaults():
    """The default printed by fit --help comes from FitConfig (one source of truth)."""
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    fit = {a.option_strings[0]: a for a in sub.choices["fit"]._actions if a.option_strings}
    cfg = FitConfig()
    checked = 0
    for (section, name), flag in FLAGS.items():
        if flag not in fit or list(FLAGS.values()).count(flag) != 1:
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
