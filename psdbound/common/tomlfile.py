"""Reading a TOML file with one clear error per failure (configuration, scenario)."""

from __future__ import annotations

import os
import tomllib
from pathlib import Path
from typing import Any

from psdbound.errors import InputError

__all__ = ["read_toml"]


def read_toml(path: str | os.PathLike[str], *, what: str) -> dict[str, Any]:
    """Return the tables of a TOML file.

    Parameters
    ----------
    path : path
        The file.
    what : str
        What the file is, for messages (``"configuration file"``).

    Returns
    -------
    dict

    Raises
    ------
    InputError
        Missing or unreadable file, or invalid TOML (naming the file).
    """
    p = Path(path)
    if p.is_dir():
        raise InputError(f"is a folder; give the {what} (a .toml file) in it", path=p)
    if not p.is_file():
        raise InputError(f"{what} not found", path=p)
    try:
        return tomllib.loads(p.read_text())
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"not valid TOML: {exc}", path=p) from None
    except OSError as exc:
        raise InputError(f"cannot read the file: {exc.strerror}", path=p) from None
