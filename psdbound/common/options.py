"""The typed option schema shared by every options dataclass, the TOML file and the CLI.

Each option of a stage is declared once, next to its stage, with
:func:`option`: its default and a :class:`Spec` saying what it accepts
(type, range, unit, choices)::

    @dataclass(frozen=True)
    class ArcOptions:
        min_length_s: float = option(1800.0, Number(lo=0, lo_open=True, hi=86400, unit="s"))

        def __post_init__(self) -> None:
            check_fields(self)

:func:`check_fields` checks every declared field when the object is built
(so the library, ``FitConfig.from_toml`` and the command line are checked
alike, before any computation) and normalises harmless spellings (an integer
where a float is expected, a list where a tuple is). A bad value raises
:class:`OptionError`, an :class:`~psdbound.errors.InputError` that names the
option, the value and what is allowed::

    order must be an integer from 1 to 20, got 4.5

Callers that know where the value came from relabel it
(:meth:`OptionError.relabel`): ``FitConfig`` as ``[filter] order``, the
command line as ``--filter-order``.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, fields
from typing import Any

from psdbound.errors import InputError

__all__ = [
    "Boolean",
    "Choice",
    "Number",
    "OptionError",
    "Spec",
    "Table",
    "Text",
    "Tuple",
    "check_fields",
    "option",
    "show_value",
    "spec_of",
]

_MISSING = object()


def show_value(value: Any) -> str:
    """Return ``value`` as the user would have typed it (``-5``, ``4.5``, ``'abc'``, ``nan``)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isfinite(value) and value.is_integer() and abs(value) < 1e15:
            return str(int(value))
        return repr(value)
    if isinstance(value, str):
        return repr(value)
    if value is None:
        return "nothing"
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


class OptionError(InputError):
    """An option value outside what its schema allows.

    Parameters
    ----------
    name : str
        The option's name (a dataclass field, e.g. ``"order"``).
    value : object
        The value given.
    expected : str
        What is allowed (``"an integer from 1 to 20"``).
    label : str, optional
        How to call the option in the message (default ``name``).
    section : str, optional
        The configuration section (``"filter"``) when known.
    path : str, optional
        The configuration file the value came from.
    """

    def __init__(
        self,
        name: str,
        value: Any,
        expected: str,
        *,
        detail: str = "",
        item: str = "",
        label: str | None = None,
        section: str | None = None,
        path: str | os.PathLike[str] | None = None,
    ) -> None:
        self.name = name
        self.value = value
        self.expected = expected
        self.detail = detail
        self.item = item
        self.label = label or name
        self.section = section
        message = f"{self.label}{item} must be {expected}, got {show_value(value)}"
        super().__init__(message + (f" ({detail})" if detail else ""), path=path)

    def relabel(
        self,
        label: str,
        *,
        value: Any = _MISSING,
        section: str | None = None,
        path: str | os.PathLike[str] | None = None,
    ) -> OptionError:
        """Return the same error naming the option ``label`` (and optionally another value)."""
        return OptionError(
            self.name,
            self.value if value is _MISSING else value,
            self.expected,
            detail=self.detail,
            item=self.item,
            label=label,
            section=section or self.section,
            path=path if path is not None else self.path,
        )


class _ItemError(ValueError):
    """An element of a list option that its item spec does not allow."""

    def __init__(self, index: int, value: Any, expected: str, detail: str) -> None:
        super().__init__(detail)
        self.index, self.value, self.expected, self.detail = index, value, expected, detail


class Spec:
    """What an option accepts; calling it checks and normalises a value."""

    def describe(self) -> str:
        """Return what is allowed, as a phrase (``"a number > 0 s"``)."""
        raise NotImplementedError

    def check(self, value: Any) -> Any:
        """Return the (normalised) value; raise ``ValueError`` when it is not allowed."""
        raise NotImplementedError

    def __call__(self, name: str, value: Any) -> Any:
        """Check ``value`` for option ``name``; raise :class:`OptionError` if not allowed."""
        try:
            return self.check(value)
        except OptionError:
            raise
        except _ItemError as exc:
            raise OptionError(
                name, exc.value, exc.expected, detail=exc.detail, item=f" item {exc.index}"
            ) from None
        except (ValueError, TypeError) as exc:
            raise OptionError(name, value, self.describe(), detail=str(exc)) from None


def _fmt(x: float) -> str:
    return f"{x:g}"


@dataclass(frozen=True)
class Number(Spec):
    """A finite real number (or integer) within a range.

    Parameters
    ----------
    lo, hi : float, optional
        Bounds (None: unbounded on that side).
    lo_open, hi_open : bool
        Exclude the bound itself.
    integer : bool
        Only whole numbers (an integral float such as ``4.0`` is accepted).
    unit : str
        Unit named in messages.
    optional : bool
        ``None`` is allowed (the option is unset).
    """

    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    integer: bool = False
    unit: str = ""
    optional: bool = False

    def describe(self) -> str:
        """Describe what is allowed (see :meth:`Spec.describe`)."""
        kind = "an integer" if self.integer else "a number"
        if self.lo is not None and self.hi is not None and not (self.lo_open or self.hi_open):
            rng = f"from {_fmt(self.lo)} to {_fmt(self.hi)}"
        else:
            parts = []
            if self.lo is not None:
                parts.append(f"{'>' if self.lo_open else '>='} {_fmt(self.lo)}")
            if self.hi is not None:
                parts.append(f"{'<' if self.hi_open else '<='} {_fmt(self.hi)}")
            rng = " and ".join(parts) or "(finite)"
        unit = f" {self.unit}" if self.unit else ""
        return f"{kind} {rng}{unit}"

    def check(self, value: Any) -> Any:
        """Check and normalise ``value`` (see :meth:`Spec.check`)."""
        if value is None and self.optional:
            return None
        if isinstance(value, bool) or value is None or isinstance(value, str | bytes):
            raise ValueError("")
        if getattr(getattr(value, "dtype", None), "kind", "") == "b":  # a NumPy boolean
            raise ValueError("")
        try:
            x = float(value)
        except (TypeError, ValueError, OverflowError):
            raise ValueError("") from None
        if not math.isfinite(x):
            raise ValueError("")
        if self.integer:
            if not x.is_integer():
                raise ValueError("")
            out: Any = int(x)
        else:
            out = x
        if self.lo is not None and (x < self.lo or (self.lo_open and x == self.lo)):
            raise ValueError("")
        if self.hi is not None and (x > self.hi or (self.hi_open and x == self.hi)):
            raise ValueError("")
        return out


@dataclass(frozen=True)
class Choice(Spec):
    """One of a fixed set of strings (``noun`` names the kind of thing in messages)."""

    choices: tuple[str, ...] = ()
    optional: bool = False
    noun: str = ""

    def describe(self) -> str:
        """Describe what is allowed (see :meth:`Spec.describe`)."""
        return "one of " + ", ".join(repr(c) for c in self.choices)

    def check(self, value: Any) -> Any:
        """Check and normalise ``value`` (see :meth:`Spec.check`)."""
        if value is None and self.optional:
            return None
        if not isinstance(value, str) or value not in self.choices:
            raise ValueError(f"unknown {self.noun}" if self.noun else "")
        return value


@dataclass(frozen=True)
class Boolean(Spec):
    """``True`` or ``False`` (not a string, not a number)."""

    def describe(self) -> str:
        """Describe what is allowed (see :meth:`Spec.describe`)."""
        return "true or false"

    def check(self, value: Any) -> Any:
        """Check and normalise ``value`` (see :meth:`Spec.check`)."""
        if not isinstance(value, bool):
            raise ValueError("")
        return value


@dataclass(frozen=True)
class Text(Spec):
    """A non-empty string, optionally matching a pattern; path-like objects become strings.

    Parameters
    ----------
    pattern : str, optional
        Regular expression the whole text must match.
    what : str
        Description used in messages (``"a file name"``).
    optional : bool
        ``None`` is allowed.
    validate : callable, optional
        Further check; raises ``ValueError`` (or InputError) with a reason.
    """

    pattern: str | None = None
    what: str = "a non-empty text"
    optional: bool = False
    paths: bool = False
    validate: Callable[[str], Any] | None = None

    def describe(self) -> str:
        """Describe what is allowed (see :meth:`Spec.describe`)."""
        return self.what

    def check(self, value: Any) -> Any:
        """Check and normalise ``value`` (see :meth:`Spec.check`)."""
        if value is None and self.optional:
            return None
        if self.paths and isinstance(value, os.PathLike):
            value = os.fspath(value)
        if not isinstance(value, str) or not value.strip():
            raise ValueError("")
        if self.pattern is not None and re.fullmatch(self.pattern, value) is None:
            raise ValueError("")
        if self.validate is not None:
            try:
                self.validate(value)
            except InputError as exc:
                raise ValueError(exc.reason) from None
        return value


def _number_text(text: Any) -> Any:
    """Return the number a piece of split text spells (``" 15"`` -> 15.0), else the text."""
    try:
        return float(str(text).strip())
    except ValueError:
        return text


@dataclass(frozen=True)
class Tuple(Spec):
    """A sequence of items, each checked by ``item``; stored as a tuple.

    Parameters
    ----------
    item : Spec
        Check of each element.
    min_len, max_len : int
        Allowed number of elements.
    lengths : tuple of int, optional
        Exact allowed lengths (e.g. ``(0, 2)``), instead of a range.
    split : str, optional
        A single string is split at this separator (``"L1C,L2W"``); without
        it a single string is one element.
    what : str
        Description used in messages.
    optional : bool
        ``None`` is allowed (the option is unset).
    """

    item: Spec = field(default_factory=lambda: Text())
    min_len: int = 0
    max_len: int | None = None
    lengths: tuple[int, ...] = ()
    split: str | None = None
    what: str = "a list"
    distinct: bool = False
    optional: bool = False

    def describe(self) -> str:
        """Describe what is allowed (see :meth:`Spec.describe`)."""
        return self.what

    def _items_of_text(self, text: str | bytes) -> list[Any]:
        """Split a text value into items (numbers written as text, ``"5,15,30"``, read)."""
        items = text.split(self.split) if self.split and isinstance(text, str) else [text]
        if isinstance(self.item, Number):
            items = [_number_text(v) for v in items]
        return items

    def check(self, value: Any) -> Any:
        """Check and normalise ``value`` (see :meth:`Spec.check`)."""
        if value is None and self.optional:
            return None
        if isinstance(value, str | os.PathLike):
            value = self._items_of_text(os.fspath(value))
        if isinstance(value, Mapping) or not isinstance(value, list | tuple):
            raise ValueError("")
        n = len(value)
        if self.lengths and n not in self.lengths:
            raise ValueError("")
        if n < self.min_len or (self.max_len is not None and n > self.max_len):
            raise ValueError("")
        out = []
        for k, v in enumerate(value):
            try:
                out.append(self.item.check(v))
            except _ItemError:
                raise
            except ValueError as exc:
                raise _ItemError(k + 1, v, self.item.describe(), str(exc)) from None
        if self.distinct and len(set(map(repr, out))) != len(out):
            raise ValueError("the items must differ")
        return tuple(out)


@dataclass(frozen=True)
class Table(Spec):
    """A table (dict) of string keys to scalar values (numbers, booleans, strings)."""

    what: str = "a table of name = value options"

    def describe(self) -> str:
        """Describe what is allowed (see :meth:`Spec.describe`)."""
        return self.what

    def check(self, value: Any) -> Any:
        """Check and normalise ``value`` (see :meth:`Spec.check`)."""
        if not isinstance(value, Mapping):
            raise ValueError("")
        out = {}
        for k, v in value.items():
            if not isinstance(k, str) or not k:
                raise ValueError(f"key {show_value(k)} is not a name")
            if isinstance(v, float) and not math.isfinite(v):
                raise ValueError(f"{k} = {show_value(v)} is not a finite number")
            if not isinstance(v, bool | int | float | str):
                raise ValueError(f"{k} = {show_value(v)} is not a number, boolean or text")
            out[k] = v
        return out


def option(
    default: Any = _MISSING,
    spec: Spec | None = None,
    *,
    default_factory: Callable[[], Any] | None = None,
) -> Any:
    """Declare a dataclass field with its schema (:class:`Spec`).

    Parameters
    ----------
    default : object
        Default value.
    spec : Spec
        What the option accepts.
    default_factory : callable, optional
        For mutable defaults (instead of ``default``).

    Returns
    -------
    dataclasses.Field
    """
    meta = {"spec": spec}
    if default_factory is not None:
        return field(default_factory=default_factory, metadata=meta)
    return field(default=default, metadata=meta)


def spec_of(obj: Any, name: str) -> Spec | None:
    """Return the :class:`Spec` declared for field ``name`` of a dataclass (or None)."""
    for f in fields(obj):
        if f.name == name:
            return f.metadata.get("spec")
    return None


def check_fields(obj: Any) -> None:
    """Check every field of a frozen dataclass declared with :func:`option`.

    Normalised values (``4`` -> ``4.0`` for a float option, a list -> a
    tuple) are written back.

    Raises
    ------
    OptionError
        For the first field whose value its spec does not allow.
    """
    for f in fields(obj):
        spec = f.metadata.get("spec")
        if spec is None:
            continue
        value = getattr(obj, f.name)
        new = spec(f.name, value)
        if new is not value:
            object.__setattr__(obj, f.name, new)
