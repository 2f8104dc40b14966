"""Packages that import their public names on first use.

A package's ``__init__`` that imports every submodule makes ``import
psdbound.<package>`` (and every command's ``--help``) pay for numpy, scipy,
matplotlib and the rest up front: 1.3 s for ``psdbound.pipeline`` before this.
:func:`lazy_exports` gives a package a module-level ``__getattr__`` (PEP 562)
that imports a public name's submodule only when the name is first used, and
caches it; ``from psdbound.screening import screen_series`` works as before.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(
    package: str, exports: Mapping[str, tuple[str, str]]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """Return the ``__getattr__`` and ``__dir__`` of a package with lazily imported names.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    exports : mapping
        Public name -> (module, attribute) where it is defined.

    Returns
    -------
    __getattr__, __dir__ : callable
        Assign them in the package's ``__init__``.
    """

    def __getattr__(name: str) -> Any:
        try:
            module, attribute = exports[name]
        except KeyError:
            raise AttributeError(f"module {package!r} has no attribute {name!r}") from None
        value = getattr(importlib.import_module(module), attribute)
        setattr(sys.modules[package], name, value)  # the next access is a plain attribute
        return value

    def __dir__() -> list[str]:
        return sorted(set(exports) | set(vars(sys.modules[package])))

    return __getattr__, __dir__
