"""``--config FILE.toml`` for the commands whose options are their flags.

``fit``, ``export`` and ``campaign`` read their TOML into
:class:`psdbound.pipeline.FitConfig` (sections by stage). The other commands
that take options (``cutoff``, ``validate``, ``overbound``, ``budget``,
``simulate``) read a TOML file whose keys are their long flags without the
dashes (``min_samples = 50`` for ``--min-samples 50``), at the top level or
in a table named after the command (``[overbound]``). Each value goes through
the same conversion and checks as the flag (its type, its choices, its
number of values here; its range when the command reads its options from
its schema, :func:`psdbound.cli.schema.read_options`), so a file and a
command line cannot mean different things; a flag given on the command line
wins over the file; an unknown key or a value of the wrong kind is an error
naming the file and the key.
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import Any

from psdbound.errors import InputError

__all__ = ["add_config_option", "apply_config"]

_FLAG_ACTIONS = (argparse._StoreTrueAction, argparse._StoreFalseAction)


def add_config_option(parser: argparse.ArgumentParser) -> None:
    """Add ``--config FILE.toml`` to a command (read by :func:`apply_config`)."""
    parser.add_argument(
        "--config",
        metavar="FILE",
        help="TOML file of options: keys are the long flags without dashes, at the top level "
        "or in a table named after the command; flags given here win (default: none)",
    )
    parser.set_defaults(_options_parser=parser)


def _given(action: argparse.Action, argv: Sequence[str]) -> bool:
    """Whether the command line names the option (``--flag value`` or ``--flag=value``)."""
    return any(t == s or t.startswith(s + "=") for s in action.option_strings for t in argv)


def _one(action: argparse.Action, key: str, value: Any, path: str) -> Any:
    """Convert one TOML value as the flag's ``type`` would, then check its choices."""
    if isinstance(value, dict | list | bool):
        raise InputError(f"{key} must be a single value, got {value!r}", path=path)
    try:
        out = action.type(str(value)) if action.type is not None else value
    except (TypeError, ValueError, argparse.ArgumentTypeError) as exc:
        raise InputError(f"{key}: {exc or 'invalid value'} (got {value!r})", path=path) from None
    if action.type is None and not isinstance(out, str):
        raise InputError(f"{key} must be a string, got {value!r}", path=path)
    if action.choices is not None and out not in action.choices:
        choices = ", ".join(map(repr, action.choices))
        raise InputError(f"{key} must be one of {choices}, got {value!r}", path=path)
    return out


def _value(action: argparse.Action, key: str, value: Any, path: str) -> Any:
    """Convert a TOML value for an option: a switch, a list or one value."""
    if isinstance(action, _FLAG_ACTIONS):
        if not isinstance(value, bool):
            raise InputError(f"{key} must be true or false, got {value!r}", path=path)
        return value if isinstance(action, argparse._StoreTrueAction) else not value
    many = isinstance(action, argparse._AppendAction) or action.nargs not in (None, "?")
    if not many:
        return _one(action, key, value, path)
    items = value if isinstance(value, list) else [value]
    if isinstance(action.nargs, int) and len(items) != action.nargs:
        raise InputError(f"{key} takes {action.nargs} values, got {value!r}", path=path)
    return [_one(action, key, v, path) for v in items]


def _table(data: dict[str, Any], command: str, path: str | None = None) -> dict[str, Any]:
    """Return the command's options of a TOML file: its ``[command]`` table, or the top level.

    Keys both at the top level and in a ``[command]`` table: the file is
    ambiguous (the top-level ones used to be dropped without a word).
    """
    if command in data and isinstance(data[command], dict):
        loose = sorted(k for k in data if k != command and not isinstance(data[k], dict))
        if loose:
            raise InputError(
                f"options both at the top level ({', '.join(loose)}) and in a [{command}] "
                f"table; put them all in [{command}] (or all at the top level)",
                path=path,
            )
        return data[command]
    return data


def apply_config(args: argparse.Namespace, argv: Sequence[str]) -> None:
    """Fill ``args`` from ``--config`` where the command line left an option out.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed by a parser with :func:`add_config_option` (a ``psdbound`` command
        parser, whose ``options()`` lists its arguments).
    argv : sequence of str
        The command line (to know which flags were given).

    Raises
    ------
    InputError
        The file is missing or not TOML, a key is not an option of the
        command, or a value is not what the flag takes.
    """
    parser = vars(args).pop("_options_parser", None)
    path = getattr(args, "config", None)
    if parser is None or not path:
        return
    from psdbound.common.tomlfile import read_toml

    data = _table(read_toml(path, what="configuration file"), args.command, path)
    actions = {
        flag.lstrip("-").replace("-", "_"): a
        for a in parser.options()
        if a.dest not in ("help", "config")
        for flag in a.option_strings
        if flag.startswith("--")
    }
    for key, value in data.items():
        action = actions.get(key.replace("-", "_"))
        if action is None:
            known = ", ".join(sorted(k for k in actions))
            raise InputError(
                f"{key} is not an option of psdbound {args.command} (options: {known})", path=path
            )
        if not _given(action, argv):
            setattr(args, action.dest, _value(action, key, value, path))
