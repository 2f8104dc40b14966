"""A one-page HTML report of a command's result: lines, one table and its figures.

The ``overbound`` and ``budget`` commands write their JSON (with its schema)
and figure through :mod:`psdbound.results` and :mod:`psdbound.reports`; this
page puts them side by side for a reader, in the fit report's style, with
the figure inlined (the folder stays self-contained).
"""

from __future__ import annotations

import base64
import os
from pathlib import Path

from psdbound.common import atomic_write_text

__all__ = ["write_page"]


def write_page(
    path: str | os.PathLike[str],
    *,
    command: str,
    title: str,
    json_name: str,
    lines: list[str],
    table: tuple[list[str], list[list[str]]] | None = None,
    figures: list[tuple[str, bytes]] = (),
) -> Path:
    """Write the page, atomically; return its path.

    Parameters
    ----------
    path : str or path-like
        The HTML file.
    command : str
        The command (``"overbound"``).
    title : str
        What the page is about.
    json_name : str
        The JSON file beside it (its schema is ``<stem>.schema.json``).
    lines : list of str
        Sentences above the table.
    table : (headers, rows), optional
        Column headers with their units, and the rows, as text.
    figures : list of (caption, PNG bytes), optional

    Returns
    -------
    Path
    """
    from psdbound.reports.templating import template
    from psdbound.version import __version__

    html = template("page.html.j2").render(
        command=command,
        title=title,
        version=__version__,
        json_name=json_name,
        schema_name=f"{Path(json_name).stem}.schema.json",
        lines=lines,
        table=None if table is None else {"headers": table[0], "rows": table[1]},
        figures=[{"caption": c, "png": base64.b64encode(png).decode()} for c, png in figures],
    )
    return Path(atomic_write_text(path, html))
