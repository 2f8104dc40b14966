"""Command-line options generated from the option schema: one table per command, three uses.

Each option of a command is declared once, with its type, range, unit and
default, as a field of an options dataclass (:func:`psdbound.common.options.option`):
a ``FitConfig`` section for ``fit``, ``export`` and ``campaign``; the domain's
own dataclass where there is one (``CutoffSettings``, ``ValidationOptions``,
``Scenario``); a dataclass of the command's own options otherwise. Each
option that has a flag is listed once in the command's table, as a
:class:`CliOption`: its flag, its help sentence and its argument group. From
that table and the schema (a :class:`Schema`, or ``section_spec`` of
``FitConfig``) this module

* adds the arguments (:func:`add_options`: ``choices`` from a
  :class:`~psdbound.common.options.Choice`, ``int``/``float`` from a
  :class:`~psdbound.common.options.Number`; argument groups and mutually
  exclusive groups from the table);
* reads the values given on the command line (or by ``--config``) back into
  configuration sections (:func:`given_values`; :func:`read_options` also
  checks each against its schema entry, the error naming the flag),
  converting the few flags that are not a field as typed (``--min-arc-min``
  is minutes, ``--mapping`` sets four fields, repeated flags become tuples);
* names an option by its flag in error messages (:func:`flag_of`), and
  states every default, with its unit, in ``--help`` (:class:`SchemaHelpFormatter`,
  :func:`default_text`), from the schema, so help and behaviour cannot differ.

The schema is imported only when the help is printed or the values are read,
so building a parser stays cheap (``benchmarks/cli_latency.py``).
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "CliOption",
    "Schema",
    "SchemaHelpFormatter",
    "add_options",
    "default_text",
    "flag_of",
    "given_values",
    "help_text",
    "read_options",
]

#: Where a parser keeps an option's stated default (a callable: see :func:`help_text`).
_DEFAULT_ATTR = "schema_default"


@dataclass(frozen=True)
class CliOption:
    """One configuration field on the command line.

    Attributes
    ----------
    section, name : str
        The field: section of the command's schema and field name.
    flags : tuple of str
        Its flags (``("-o", "--out")``), or one positional name (``("obs",)``).
    help : str
        What it does, in words, with its unit.
    group : str or None
        The ``--help`` group it is listed under (None: the parser's own
        ``options``, or ``positional arguments``).
    kwargs : dict
        Extra :meth:`argparse.ArgumentParser.add_argument` keywords (``nargs``,
        ``metavar``, ``action``, ``type``, ``dest``).
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
    exclusive : str
        Name of a mutually exclusive group within ``group`` (options with the
        same name exclude each other); empty: none.
    note : str
        Said after the default in ``--help`` (``"--legacy: 12"``).
    """

    section: str
    name: str
    flags: tuple[str, ...]
    help: str
    group: str | None
    kwargs: dict[str, Any] = field(default_factory=dict)
    convert: Callable[[Any], dict[str, Any]] | None = None
    scale: float = 1.0
    unit: str | None = None
    sets: tuple[str, ...] = ()
    exclusive: str = ""
    note: str = ""

    @property
    def flag(self) -> str:
        """The flag messages name (the long one)."""
        return self.flags[-1]

    @property
    def dest(self) -> str:
        """The attribute of the parsed namespace (``dest``, else argparse's own rule)."""
        return self.kwargs.get("dest") or self.flags[-1].lstrip("-").replace("-", "_")


@dataclass(frozen=True)
class Schema:
    """A command's option schema: each section's options dataclass, imported when first needed.

    Parameters
    ----------
    sections : mapping of str to str
        Section name -> ``"module:Class"`` of the frozen dataclass whose
        fields (declared with :func:`psdbound.common.options.option`) are the
        section's options, defaults and checks.
    """

    sections: Mapping[str, str]

    def options_class(self, section: str) -> Any:
        """Return the dataclass of ``section`` (imported here, not with the parser)."""
        module, _, name = self.sections[section].partition(":")
        return getattr(importlib.import_module(module), name)

    def _field(self, section: str, name: str) -> dataclasses.Field[Any] | None:
        cls = self.options_class(section)
        return next((f for f in dataclasses.fields(cls) if f.name == name), None)

    def spec(self, section: str, name: str) -> Any:
        """Return the :class:`~psdbound.common.options.Spec` of a field (None: not declared)."""
        f = self._field(section, name)
        return None if f is None else f.metadata.get("spec")

    def default(self, section: str, name: str) -> Any:
        """Return the default of a field (None: not a field, or no default)."""
        f = self._field(section, name)
        if f is None:
            return None
        if f.default is not dataclasses.MISSING:
            return f.default
        if f.default_factory is not dataclasses.MISSING:
            return f.default_factory()
        return None

    def build(self, section: str, values: Mapping[str, Any]) -> Any:
        """Return the section's dataclass with ``values`` and the defaults for the rest."""
        return self.options_class(section)(**values)


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


def _stated(
    opt: CliOption,
    specs: Callable[[str, str], Any],
    defaults: Callable[[str, str], Any],
) -> Callable[[], str | None]:
    """Return the callable that states ``opt``'s default for ``--help`` (see :func:`help_text`)."""

    def stated() -> str | None:
        unit = getattr(specs(opt.section, opt.name), "unit", "") or ""
        return default_text(opt, defaults(opt.section, opt.name), unit)

    return stated


def add_options(
    parser: argparse.ArgumentParser,
    table: Iterable[CliOption],
    specs: Callable[[str, str], Any],
    *,
    groups: Iterable[str | None],
    defaults: Callable[[str, str], Any] | None = None,
) -> dict[str | None, Any]:
    """Add the table's options of the given groups, one argument group each, in order.

    Parameters
    ----------
    parser : argparse.ArgumentParser
    table : iterable of CliOption
    specs : callable
        ``(section, name) -> Spec`` of the schema (None: no type check here).
    groups : iterable of str or None
        Group titles, in the order ``--help`` lists them (None: the parser's
        own groups).
    defaults : callable, optional
        ``(section, name) -> default`` of the schema: ``--help`` states it,
        with its unit, after the help of an option that does not state its
        default itself (:class:`SchemaHelpFormatter`). Evaluated only when
        the help is printed.

    Returns
    -------
    dict of str to argparse argument group
        The groups added, by title (for arguments that are not options).
    """
    rows = list(table)
    out: dict[str | None, Any] = {}
    for title in groups:
        g = out[title] = parser if title is None else parser.add_argument_group(title)
        exclusive: dict[str, Any] = {}
        for opt in (r for r in rows if r.group == title):
            kw = {**_spec_kwargs(opt, specs(opt.section, opt.name)), **opt.kwargs}
            if opt.flags[0].startswith("-"):
                kw.setdefault("default", None)
            target = g
            if opt.exclusive:
                target = exclusive.get(opt.exclusive) or g.add_mutually_exclusive_group()
                exclusive[opt.exclusive] = target
            action = target.add_argument(*opt.flags, help=opt.help, **kw)
            if defaults is not None:
                setattr(action, _DEFAULT_ATTR, _stated(opt, specs, defaults))
    return out


def help_text(action: argparse.Action) -> str:
    """Return an option's help with its default (and unit) appended from the schema if unstated.

    The default is that of the option's field in the command's schema
    (:func:`add_options` with ``defaults``), evaluated when the help is
    printed; an option whose help already says ``(default`` (a default that
    is not a value: "the header's") keeps its own words.
    """
    text = action.help or ""
    stated = getattr(action, _DEFAULT_ATTR, None)
    if stated is None or "(default" in text:
        return text
    default = stated()
    return text if default is None else f"{text} (default: {default})"


class SchemaHelpFormatter(argparse.HelpFormatter):
    """Help formatter that states every option's default from the schema (see :func:`help_text`)."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        return help_text(action)


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


def _checked(opt: CliOption, spec: Any, value: Any) -> Any:
    """Return a command-line value checked by its field's spec (in the command-line unit)."""
    from psdbound.common.options import Number

    if isinstance(value, list):
        value = tuple(value)
    if spec is None:
        return value
    if opt.scale == 1.0 or not isinstance(spec, Number):
        return spec(opt.flag, value)
    lo, hi = (None if b is None else b / opt.scale for b in (spec.lo, spec.hi))
    unit = opt.unit or spec.unit
    return dataclasses.replace(spec, lo=lo, hi=hi, unit=unit)(opt.flag, value) * opt.scale


def read_options(
    args: argparse.Namespace,
    table: Iterable[CliOption],
    specs: Callable[[str, str], Any],
) -> dict[str, dict[str, Any]]:
    """Return, per section, the field values of the options given, each checked by its schema.

    Parameters
    ----------
    args : argparse.Namespace
        Parsed by a parser built with :func:`add_options` (and filled from
        ``--config`` by :func:`psdbound.cli.config_file.apply_config`).
    table : iterable of CliOption
    specs : callable
        ``(section, name) -> Spec`` of the schema.

    Returns
    -------
    dict of str to dict
        ``{section: {field: value}}`` of the options given (absent: not
        given, the schema's default applies); scaled to the field's unit.

    Raises
    ------
    OptionError
        A value its schema entry does not allow; the message names the flag
        (``--theta0-deg must be a number from -90 to 90 deg, got 95``).
    """
    out: dict[str, dict[str, Any]] = {}
    for opt in table:
        raw = getattr(args, opt.dest, None)
        if raw is None or raw == []:
            continue
        values = out.setdefault(opt.section, {})
        if opt.convert is not None:
            for name, value in opt.convert(raw).items():
                values[name] = _checked(opt, specs(opt.section, name), value)
        else:
            values[opt.name] = _checked(opt, specs(opt.section, opt.name), raw)
    return out


def flag_of(table: Iterable[CliOption], section: str, name: str) -> str | None:
    """Return the flag that sets a field (None: no flag; ``--mapping`` sets four)."""
    for opt in table:
        if opt.section == section and (opt.name == name or name in opt.sets):
            return opt.flag
    return None


def _text(value: Any, sep: str) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, tuple):
        return sep.join(_text(v, sep) if sep == " " else str(v) for v in value)
    return str(value)


def default_text(opt: CliOption, value: Any, unit: str) -> str | None:
    """Return ``"<default> <unit>[; <note>]"`` for ``--help`` (None: no default worth stating).

    Parameters
    ----------
    opt : CliOption
    value : object
        The field's default in the schema.
    unit : str
        The field's unit in the schema (the option's own ``unit`` wins).
    """
    if value is None or value == () or value == "" or isinstance(value, bool):
        return None
    if isinstance(value, int | float) and opt.scale != 1.0:
        value = value / opt.scale
    many = opt.kwargs.get("nargs") in ("+", "*") or isinstance(opt.kwargs.get("nargs"), int)
    text = f"{_text(value, ' ' if many else ',')} {opt.unit or unit}".strip()
    return f"{text}; {opt.note}" if opt.note else text
