"""Command-line options generated from the option schema: one table, three uses.

Each option of a configuration (a field of a ``FitConfig`` section, declared
once with its type, range, unit and default by
:func:`psdbound.common.options.option`) that has a flag is listed once, as a
:class:`CliOption`: its flag, its help sentence and its argument group. From
that table and the schema this module

* adds the arguments (:func:`add_options`: ``choices`` from a
  :class:`~psdbound.common.options.Choice`, ``int``/``float`` from a
  :class:`~psdbound.common.options.Number`);
* reads the values given on the command line back into configuration
  sections (:func:`given_values`), converting the few flags that are not a
  field as typed (``--min-arc-min`` is minutes, ``--mapping`` sets four
  fields, repeated flags become tuples);
* names an option by its flag in error messages (:func:`flag_of`), and
  states every default, with its unit, in ``--help`` (:func:`default_text`),
  from the schema, so help and behaviour cannot differ.

The schema is imported only when the help is printed or the values are read,
so building a parser stays cheap (``benchmarks/cli_latency.py``).
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

__all__ = ["CliOption", "add_options", "default_text", "flag_of", "given_values"]


@dataclass(frozen=True)
class CliOption:
    """One configuration field on the command line.

    Attributes
    ----------
    section, name : str
        The field: ``FitConfig`` section and field name.
    flags : tuple of str
        Its flags (``("-o", "--out")``), or one positional name (``("obs",)``).
    help : str
        What it does, in words, with its unit.
    group : str
        The ``--help`` group it is listed under.
    kwargs : dict
        Extra :meth:`argparse.ArgumentParser.add_argument` keywords (``nargs``,
        ``metavar``, ``action``, ``type``).
    convert : callable, optional
        Command-line value -> ``{field: value}`` of its section (default:
        ``{name: value}``, a list becoming a tuple).
    scale : float, default 1
        Field value = command-line value x ``scale`` (``--min-arc-min``: 60);
        the help states the default divided by it, in ``unit``.
    unit : str, optional
        The command-line unit when it is not the field's.
    sets : tuple of str
        Other fields of the section the option sets through ``convert``
        (``--mapping``: ``a``, ``b``, ``c_deg``), for messages.
    """

    section: str
    name: str
    flags: tuple[str, ...]
    help: str
    group: str
    kwargs: dict[str, Any] = field(default_factory=dict)
    convert: Callable[[Any], dict[str, Any]] | None = None
    scale: float = 1.0
    unit: str | None = None
    sets: tuple[str, ...] = ()

    @property
    def flag(self) -> str:
        """The flag messages name (the long one)."""
        return self.flags[-1]

    @property
    def dest(self) -> str:
        """The attribute of the parsed namespace (argparse's own rule)."""
        return self.flags[-1].lstrip("-").replace("-", "_")


def _spec_kwargs(opt: CliOption, spec: Any) -> dict[str, Any]:
    """``choices`` / ``type`` of an option from its schema entry (explicit kwargs win)."""
    from psdbound.common.options import Choice, Number

    out: dict[str, Any] = {}
    if opt.kwargs.get("action") in ("store_true", "store_false", "append_const"):
        return out
    if isinstance(spec, Choice):
        out["choices"] = spec.choices
    elif isinstance(spec, Number):
        out["type"] = int if spec.integer else float
    return out


def add_options(
    parser: argparse.ArgumentParser,
    table: Iterable[CliOption],
    specs: Callable[[str, str], Any],
    *,
    groups: Iterable[str],
) -> dict[str, Any]:
    """Add the table's options of the given groups, one argument group each, in order.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    table : iterable of CliOption
    specs : callable
        ``(section, name) -> Spec`` of the schema (None: no type check here).
    groups : iterable of str
        Group titles, in the order ``--help`` lists them.

    Returns
    -------
    dict of str to argparse argument group
        The groups added, by title (for arguments that are not options).
    """
    rows = list(table)
    out = {}
    for title in groups:
        g = out[title] = parser.add_argument_group(title)
        for opt in (r for r in rows if r.group == title):
            kw = {**_spec_kwargs(opt, specs(opt.section, opt.name)), **opt.kwargs}
            if opt.flags[0].startswith("-"):
                kw.setdefault("default", None)
            g.add_argument(*opt.flags, help=opt.help, **kw)
    return out


def _as_field(opt: CliOption, value: Any) -> dict[str, Any]:
    if opt.convert is not None:
        return opt.convert(value)
    if isinstance(value, list):
        value = tuple(value)
    elif opt.scale != 1.0:
        value = value * opt.scale
    return {opt.name: value}


def given_values(
    args: argparse.Namespace, table: Iterable[CliOption]
) -> dict[str, list[tuple[CliOption, dict[str, Any]]]]:
    """Return, per section, the options given on the command line and their field values.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed by a parser built with :func:`add_options`.
    table : iterable of CliOption

    Returns
    -------
    dict of str to list of (CliOption, dict)
        ``{section: [(option, {field: value}), ...]}``; an option not given
        (None, or an empty list) is left out.
    """
    out: dict[str, list[tuple[CliOption, dict[str, Any]]]] = {}
    for opt in table:
        value = getattr(args, opt.dest, None)
        if value is None or value == []:
            continue
        out.setdefault(opt.section, []).append((opt, _as_field(opt, value)))
    return out


def flag_of(table: Iterable[CliOption], section: str, name: str) -> str | None:
    """Return the flag that sets a field (None: no flag; ``--mapping`` sets four)."""
    for opt in table:
        if opt.section == section and (opt.name == name or name in opt.sets):
            return opt.flag
    return None


def default_text(opt: CliOption, value: Any, unit: str) -> str | None:
    """Return ``"<default> <unit>"`` for ``--help`` (None: no default worth stating).

    Parameters
    ----------
    opt : CliOption
    value : object
        The field's default in the schema.
    unit : str
        The field's unit in the schema (the option's own ``unit`` wins).
    """
    if value is None or value == () or isinstance(value, bool):
        return None
    if isinstance(value, int | float) and opt.scale != 1.0:
        value = value / opt.scale
    if isinstance(value, float):
        text = f"{value:g}"
    elif isinstance(value, tuple):
        text = ",".join(map(str, value))
    else:
        text = str(value)
    return f"{text} {opt.unit or unit}".strip()
