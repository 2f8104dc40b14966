"""The reports' Jinja2 templates (``psdbound/reports/templates``), one environment."""

from __future__ import annotations

from functools import cache
from typing import Any

__all__ = ["template"]


@cache
def _environment() -> Any:
    import jinja2

    return jinja2.Environment(
        loader=jinja2.PackageLoader("psdbound.reports", "templates"),
        autoescape=jinja2.select_autoescape(["html", "j2"]),
        undefined=jinja2.StrictUndefined,
    )


def template(name: str) -> Any:
    """Return a template of ``psdbound/reports/templates`` (HTML autoescaped, strict).

    Parameters
    ----------
    name : str
        File name, e.g. ``"report.html.j2"``.

    Returns
    -------
    jinja2.Template
    """
    return _environment().get_template(name)
