"""A one-page HTML report of a command's result: a headline, lines, tables and its figures.

The ``overbound``, ``budget``, ``cutoff`` and ``validate`` commands write
their JSON (with its schema) and figures through :mod:`psdbound.results` and
:mod:`psdbound.reports`; this page puts them side by side for a reader, in
the fit report's style, with each figure inlined (the page stays readable
when moved alone) and linked to its PNG file beside it.
"""

from __future__ import annotations

import base64
import os
from collections.abc import Sequence
from pathlib import Path

from psdbound.common import atomic_write_text

__all__ = ["Figure", "Table", "write_page"]

#: A figure of the page: caption, PNG bytes and, optionally, the PNG file beside the page.
Figure = tuple[str, bytes] | tuple[str, bytes, str]
#: A table of the page: caption ("" for none), column headers with units, rows as text.
Table = tuple[str, list[str], list[list[str]]]


def _figure(fig: Figure) -> dict[str, str | None]:
    caption, png = fig[0], fig[1]
    href = fig[2] if len(fig) > 2 else None
    return {"caption": caption, "png": base64.b64encode(png).decode(), "href": href}


def write_page(
    path: str | os.PathLike[str],
    *,
    command: str,
    title: str,
    json_name: str,
    lines: list[str],
    table: tuple[list[str], list[list[str]]] | None = None,
    figures: Sequence[Figure] = (),
    headline: str | None = None,
    tables: Sequence[Table] = (),
    schema_name: str | None = None,
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
        The JSON file beside it.
    lines : list of str
        Sentences above the tables.
    table : (headers, rows), optional
        Column headers with their units, and the rows, as text (shown first,
        without a caption).
    figures : sequence of (caption, PNG bytes) or (caption, PNG bytes, file name)
        Inlined in order; with a file name (relative to the page), the
        figure and its caption link to that PNG file.
    headline : str, optional
        The result in one sentence (the verdict, the recommended value),
        shown in bold under the title.
    tables : sequence of (caption, headers, rows), optional
        More tables, after ``table``, each under its caption.
    schema_name : str, optional
        The JSON Schema of ``json_name`` (default ``<stem>.schema.json``).

    Returns
    -------
    Path
    """
    from psdbound.reports.templating import template
    from psdbound.version import __version__

    all_tables = [] if table is None else [{"caption": "", "headers": table[0], "rows": table[1]}]
    all_tables += [{"caption": c, "headers": h, "rows": r} for c, h, r in tables]
    html = template("page.html.j2").render(
        command=command,
        title=title,
        version=__version__,
        json_name=json_name,
        schema_name=schema_name or f"{Path(json_name).stem}.schema.json",
        headline=headline,
        lines=lines,
        tables=all_tables,
        figures=[_figure(f) for f in figures],
    )
    return Path(atomic_write_text(path, html))
