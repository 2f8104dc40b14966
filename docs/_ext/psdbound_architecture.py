"""Local Sphinx extension: the package diagram, drawn from the code's own imports.

``.. psdbound-architecture::`` reads every module of ``psdbound/`` with
:mod:`ast` (nothing is imported), collects which top-level package imports
which (at any depth: deferred imports count), places each package one layer
above the highest package it imports, and writes

* an SVG diagram (HTML builders; arrows point from the importer down to the
  package it uses; arrows into the foundation packages that nearly every
  package imports, ``common``, ``constants``, ``errors``, ``version``, are
  left out of the picture, not out of the table), and
* a table: package, layer, the first line of its docstring, what it imports.

Built at every docs build, so the picture cannot drift from the code.
"""

from __future__ import annotations

import ast
from pathlib import Path
from typing import Any

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

PKG = Path(__file__).resolve().parents[2] / "psdbound"
#: Packages nearly every other one imports: drawn, but their arrows are left out.
FOUNDATION = frozenset({"common", "constants", "errors", "version"})
BOX_W, BOX_H, GAP_X, GAP_Y = 120, 30, 16, 46


def _package(path: Path) -> str:
    """Top-level package (or module) of a file under psdbound/."""
    rel = path.relative_to(PKG)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _targets(tree: ast.AST) -> set[str]:
    out = set()
    for node in ast.walk(tree):
        names = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
            names = [node.module]
        out |= {n.split(".")[1] for n in names if n.startswith("psdbound.")}
    return out


def package_graph() -> dict[str, set[str]]:
    """Return ``{package: packages it imports}`` for psdbound's top-level packages."""
    graph: dict[str, set[str]] = {}
    for path in sorted(PKG.rglob("*.py")):
        pkg = _package(path)
        if pkg in ("__init__", "__main__"):
            continue
        deps = _targets(ast.parse(path.read_text()))
        graph.setdefault(pkg, set()).update(d for d in deps if d != pkg)
    return {k: {d for d in v if d in graph} for k, v in graph.items()}


def layers(graph: dict[str, set[str]]) -> dict[str, int]:
    """Layer of each package: 0 for one that imports none, else 1 + its highest import."""
    out: dict[str, int] = {}

    def depth(p: str, seen: frozenset[str]) -> int:
        if p not in out:
            deps = [d for d in graph[p] if d not in seen]
            out[p] = 1 + max((depth(d, seen | {p}) for d in deps), default=-1)
        return out[p]

    for p in graph:
        depth(p, frozenset())
    return out


def _positions(layer: dict[str, int]) -> tuple[dict[str, tuple[float, float]], float, float]:
    top = max(layer.values())
    rows: dict[int, list[str]] = {}
    for p in sorted(layer):
        rows.setdefault(layer[p], []).append(p)
    width = max(len(r) for r in rows.values()) * (BOX_W + GAP_X) + GAP_X
    pos = {}
    for lev, members in rows.items():
        row_w = len(members) * (BOX_W + GAP_X) - GAP_X
        x0 = (width - row_w) / 2
        for i, p in enumerate(members):
            pos[p] = (x0 + i * (BOX_W + GAP_X), GAP_Y / 2 + (top - lev) * (BOX_H + GAP_Y))
    return pos, width, (top + 1) * (BOX_H + GAP_Y)


def svg(graph: dict[str, set[str]]) -> str:
    """Return the diagram as an SVG document (layers bottom-up, arrows down to imports)."""
    pos, width, height = _positions(layers(graph))
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" '
        f'height="{height:.0f}" font-family="sans-serif" font-size="12">',
        '<defs><marker id="a" markerWidth="8" markerHeight="6" refX="8" refY="3" '
        'orient="auto"><path d="M0,0 L8,3 L0,6 z" fill="#888"/></marker></defs>',
    ]
    for p, deps in sorted(graph.items()):
        x, y = pos[p]
        for d in sorted(deps - FOUNDATION):
            u, v = pos[d]
            parts.append(
                f'<line x1="{x + BOX_W / 2:.0f}" y1="{y + BOX_H:.0f}" '
                f'x2="{u + BOX_W / 2:.0f}" y2="{v:.0f}" stroke="#bbb" '
                'marker-end="url(#a)"/>'
            )
    for p, (x, y) in sorted(pos.items()):
        parts.append(
            f'<rect x="{x:.0f}" y="{y:.0f}" width="{BOX_W}" height="{BOX_H}" rx="4" '
            'fill="#eef3fb" stroke="#4a6fa5"/>'
        )
        parts.append(
            f'<text x="{x + BOX_W / 2:.0f}" y="{y + BOX_H / 2 + 4:.0f}" '
            f'text-anchor="middle">{p}</text>'
        )
    parts.append("</svg>")
    return "\n".join(parts)


def _summary(pkg: str) -> str:
    path = PKG / pkg / "__init__.py"
    if not path.is_file():
        path = PKG / f"{pkg}.py"
    doc = ast.get_docstring(ast.parse(path.read_text())) or ""
    return doc.strip().splitlines()[0] if doc.strip() else ""


class ArchitectureDirective(SphinxDirective):
    """``.. psdbound-architecture::``: the package diagram and table, from the imports."""

    def run(self) -> list[nodes.Node]:
        """Return the diagram (raw SVG) and the table of packages."""
        graph = package_graph()
        layer = layers(graph)
        out: list[nodes.Node] = [nodes.raw("", svg(graph), format="html")]
        lines = [
            ".. list-table::",
            "   :header-rows: 1",
            "   :widths: 14 6 50 30",
            "",
            "   * - package",
            "     - layer",
            "     - what it holds",
            "     - imports",
        ]
        for p in sorted(graph, key=lambda k: (-layer[k], k)):
            deps = ", ".join(f"``{d}``" for d in sorted(graph[p])) or "nothing"
            lines += [
                f"   * - ``{p}``",
                f"     - {layer[p]}",
                f"     - {_summary(p).replace('*', '')}",
                f"     - {deps}",
            ]
        node = nodes.section()
        nested_parse_with_titles(self.state, StringList(lines, source="psdbound"), node)
        return out + list(node.children)


def setup(app: Sphinx) -> dict[str, Any]:
    """Register the directive."""
    app.add_directive("psdbound-architecture", ArchitectureDirective)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
