"""Local Sphinx extension: reference pages generated from the code at build time.

Directives
----------
``.. psdbound-cli::``
    The command-line reference: imports :func:`psdbound.cli.main.build_parser`
    and writes, for the main parser and every subcommand, its description,
    usage and every option (with ``.. program::`` / ``.. option::``, so
    ``:option:`psdbound fit --pair``` links work).
``.. psdbound-result-schema::``
    The ``result.json`` reference: reads ``psdbound/results/result.schema.json``
    and writes one table per top-level section, one row per field (dotted
    path, JSON type, required or not, description with units).

Nothing here needs a new dependency: argparse and json only.
"""

from __future__ import annotations

import argparse
import json
import re
from importlib import resources
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

_SPECIAL = re.compile(r"([\\`*_|])")


def _escape(text: str) -> str:
    """Escape reStructuredText inline markup in plain help text."""
    return _SPECIAL.sub(r"\\\1", " ".join(str(text).split()))


def _subparsers(parser: argparse.ArgumentParser) -> list[tuple[str, str, argparse.ArgumentParser]]:
    out = []
    for action in parser._actions:  # argparse keeps its subcommands here
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help or "" for a in action._choices_actions}
            for name, sub in action.choices.items():
                out.append((name, helps.get(name, ""), sub))
    return out


def _option_lines(parser: argparse.ArgumentParser, program: str) -> list[str]:
    formatter = parser._get_formatter()
    lines = [f".. program:: {program}", ""]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            continue
        if action.option_strings:
            if action.nargs == 0:
                sig = ", ".join(action.option_strings)
            else:
                meta = formatter._format_args(action, action.dest.upper())
                sig = ", ".join(f"{o} {meta}" for o in action.option_strings)
        else:
            sig = action.metavar or action.dest
        help_text = "" if action.help is None else formatter._expand_help(action)
        if action.help == argparse.SUPPRESS:
            continue
        extra = []
        if action.choices is not None and not isinstance(action.choices, dict):
            extra.append("choices: " + ", ".join(f"``{c}``" for c in action.choices))
        if (
            action.option_strings
            and action.default not in (None, False, "", argparse.SUPPRESS)
            and action.nargs != 0
        ):
            extra.append(f"default: ``{action.default!s}``")
        lines += [f".. option:: {sig}", ""]
        lines += [f"   {_escape(help_text) or '(no help text)'}", ""]
        if extra:
            lines += ["   (" + "; ".join(extra) + ")", ""]
    return lines


def _usage_lines(parser: argparse.ArgumentParser) -> list[str]:
    usage = parser.format_usage().strip()
    usage = usage[len("usage: ") :] if usage.startswith("usage: ") else usage
    return [".. code-block:: text", ""] + ["   " + ln for ln in usage.splitlines()] + [""]


class CliDirective(SphinxDirective):
    """Emit the reference of ``python -m psdbound`` and every subcommand."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        """Return the parsed reference sections."""
        from psdbound.cli.main import build_parser

        parser = build_parser()
        lines: list[str] = []
        lines += [_escape(parser.description or ""), ""]
        lines += _usage_lines(parser)
        lines += _option_lines(parser, "psdbound")
        if parser.epilog:
            lines += [_escape(parser.epilog), ""]
        for name, short, sub in _subparsers(parser):
            title = f"psdbound {name}"
            lines += [title, "-" * len(title), ""]
            lines += [f"*{_escape(short)}*", ""] if short else []
            if sub.description:
                lines += [_escape(sub.description), ""]
            lines += _usage_lines(sub)
            lines += _option_lines(sub, f"psdbound {name}")
            if sub.epilog:
                lines += [_escape(sub.epilog), ""]
        return self._parse(lines)

    def _parse(self, lines: list[str]) -> list[nodes.Node]:
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, StringList(lines, source="psdbound-cli"), node)
        return node.children


def _json_type(spec: dict[str, Any]) -> str:
    t = spec.get("type", "any")
    types = t if isinstance(t, list) else [t]
    if "array" in types and isinstance(spec.get("items"), dict) and "type" in spec["items"]:
        it = spec["items"]["type"]
        it = " or ".join(it) if isinstance(it, list) else it
        types = [f"array of {it}" if x == "array" else x for x in types]
    out = " or ".join(types)
    if "enum" in spec:
        out += " (" + ", ".join(f"``{json.dumps(v)}``" for v in spec["enum"]) + ")"
    if "const" in spec:
        out += f" (``{json.dumps(spec['const'])}``)"
    return out


def _rows(prefix: str, spec: dict[str, Any], required: bool) -> list[tuple[str, str, str, str]]:
    rows = [(prefix, _json_type(spec), "yes" if required else "no", spec.get("description", ""))]
    props = spec.get("properties")
    if props:
        req = set(spec.get("required", []))
        for key, sub in props.items():
            rows += _rows(f"{prefix}.{key}", sub, key in req)
    items = spec.get("items")
    if isinstance(items, dict) and items.get("properties"):
        req = set(items.get("required", []))
        for key, sub in items["properties"].items():
            rows += _rows(f"{prefix}[].{key}", sub, key in req)
    return rows


class SchemaDirective(SphinxDirective):
    """Emit the field-by-field reference of ``result.json`` from its JSON Schema."""

    has_content = False

    def run(self) -> list[nodes.Node]:
        """Return one table per top-level section of the schema."""
        text = resources.files("psdbound.results").joinpath("result.schema.json").read_text()
        schema = json.loads(text)
        lines = [_escape(schema.get("description", "")), ""]
        req = set(schema.get("required", []))
        for key, spec in schema["properties"].items():
            title = f"``{key}``"
            lines += [title, "-" * len(title), ""]
            lines += [_escape(spec.get("description", "")), ""]
            lines += [".. list-table::", "   :header-rows: 1", "   :widths: 30 15 8 47", ""]
            lines += ["   * - field", "     - type", "     - required", "     - description"]
            for path, typ, is_req, desc in _rows(key, spec, key in req):
                lines += [
                    f"   * - ``{path}``",
                    f"     - {typ}",
                    f"     - {is_req}",
                    f"     - {_escape(desc)}",
                ]
            lines += [""]
        node = nodes.section()
        node.document = self.state.document
        nested_parse_with_titles(self.state, StringList(lines, source="result.schema.json"), node)
        return node.children


def setup(app: Sphinx) -> dict[str, Any]:
    """Register the directives."""
    app.add_directive("psdbound-cli", CliDirective)
    app.add_directive("psdbound-result-schema", SchemaDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
