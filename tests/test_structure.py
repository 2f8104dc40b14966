"""The package's shape: no import cycles, small functions, no private names across modules.

These checks read the source (``ast``), they import nothing: a failure names
the module and line to fix.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[1] / "psdbound"
#: The most code lines (docstring excluded) and the highest McCabe complexity of a function.
MAX_FUNCTION_LINES = 80
MAX_COMPLEXITY = 10
NUMERIC = ("numpy", "scipy", "matplotlib", "astropy", "statsmodels")


def _modules() -> dict[str, Path]:
    out = {}
    for p in sorted(PKG.rglob("*.py")):
        rel = p.relative_to(PKG.parent).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = p
    return out


MODULES = _modules()


def _package_of(mod: str) -> str:
    return mod if MODULES[mod].name == "__init__.py" else mod.rpartition(".")[0]


def _imports(mod: str) -> list[tuple[int, str, list[str]]]:
    """(line, imported module, imported names) for every psdbound import, at any depth."""
    tree = ast.parse(MODULES[mod].read_text())
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("psdbound"):
                    out.append((node.lineno, a.name, []))
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = _package_of(mod).split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join([*base, node.module] if node.module else base)
            else:
                target = node.module or ""
            if target.startswith("psdbound"):
                out.append((node.lineno, target, [a.name for a in node.names]))
    return out


def _edges(mod: str) -> set[str]:
    deps = set()
    for _, target, names in _imports(mod):
        for n in names or [None]:
            sub = f"{target}.{n}" if n else None
            dep = sub if sub in MODULES else target
            if dep in MODULES and dep != mod:
                deps.add(dep)
    return deps


def test_no_import_cycles():
    graph = {m: _edges(m) for m in MODULES}
    state: dict[str, int] = {}
    stack: list[str] = []
    cycles = []

    def visit(m: str) -> None:
        state[m] = 1
        stack.append(m)
        for d in sorted(graph[m]):
            if state.get(d) == 1:
                cycles.append(stack[stack.index(d) :] + [d])
            elif d not in state:
                visit(d)
        stack.pop()
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m)
    assert not cycles, "import cycles:\n" + "\n".join(" -> ".join(c) for c in cycles)


#: Functions allowed over MAX_FUNCTION_LINES or MAX_COMPLEXITY, each with its reason. The
#: list only shrinks: an entry that is within both limits again fails the test below.
LARGE_FUNCTIONS: dict[str, str] = {}


def _function_sizes() -> dict[str, int]:
    """Code lines (docstring excluded) of every function and method, as ``module.name``."""
    out = {}
    for mod, path in MODULES.items():
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                continue
            n = node.end_lineno - node.lineno + 1
            doc = node.body[0]
            if isinstance(doc, ast.Expr) and isinstance(doc.value, ast.Constant):
                n -= doc.end_lineno - doc.lineno + 1
            key = f"{mod}.{node.name}"
            out[key] = max(n, out.get(key, 0))
    return out


def _complexities() -> dict[str, int]:
    """McCabe complexity above MAX_COMPLEXITY (ruff's C901), as ``module.name``."""
    import json
    import shutil
    import subprocess

    ruff = shutil.which("ruff")
    if ruff is None:
        pytest.skip("ruff is not installed (it is in the test extra)")
    cmd = [
        ruff,
        "check",
        str(PKG),
        "--select",
        "C901",
        "--output-format",
        "json",
        "--config",
        f"lint.mccabe.max-complexity = {MAX_COMPLEXITY}",
        "--exit-zero",
    ]
    out = {}
    for hit in json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout):
        rel = Path(hit["filename"]).resolve().relative_to(PKG.parent).with_suffix("")
        mod = ".".join(p for p in rel.parts if p != "__init__")
        name = hit["message"].split("`")[1]
        out[f"{mod}.{name}"] = int(hit["message"].split("(")[1].split()[0])
    return out


def _too_large() -> dict[str, str]:
    sizes, complexity = _function_sizes(), _complexities()
    out = {
        k: f"{n} code lines (> {MAX_FUNCTION_LINES})"
        for k, n in sizes.items()
        if n > MAX_FUNCTION_LINES
    }
    for k, c in complexity.items():
        out[k] = (out[k] + ", " if k in out else "") + f"complexity {c} (> {MAX_COMPLEXITY})"
    return out


def test_functions_are_small_and_simple():
    bad = [f"{k}: {why}" for k, why in sorted(_too_large().items()) if k not in LARGE_FUNCTIONS]
    assert not bad, (
        "split these functions by concern (or list one in LARGE_FUNCTIONS, with "
        "its reason):\n" + "\n".join(bad)
    )


def test_large_function_list_is_current():
    stale = sorted(set(LARGE_FUNCTIONS) - set(_too_large()))
    assert not stale, f"within the limits again: remove from LARGE_FUNCTIONS: {stale}"


def test_no_private_names_across_modules():
    bad = []
    for mod in MODULES:
        pkg = _package_of(mod)
        for line, target, names in _imports(mod):
            parts = target.split(".")
            private_mod = next((i for i, p in enumerate(parts) if p.startswith("_")), None)
            if private_mod is not None:
                owner = ".".join(parts[:private_mod])
                if owner != pkg:
                    bad.append(f"{MODULES[mod]}:{line} imports private module {target}")
            for n in names:
                if n.startswith("_") and not n.startswith("__"):
                    bad.append(f"{MODULES[mod]}:{line} imports private name {target}.{n}")
        tree = ast.parse(MODULES[mod].read_text())
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Attribute)
                and node.attr.startswith("_")
                and not node.attr.startswith("__")
                and isinstance(node.value, ast.Name)
                and node.value.id not in ("self", "cls")
                and node.value.id not in sys.stdlib_module_names
                and node.value.id[0].islower()
            ):
                bad.append(f"{MODULES[mod]}:{node.lineno} uses {node.value.id}.{node.attr}")
    assert not bad, "private names used across modules:\n" + "\n".join(bad)


def test_cli_modules_do_no_numerical_work():
    bad = []
    for mod, path in MODULES.items():
        if not mod.startswith("psdbound.cli"):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level:
                names = [node.module or ""]
            for n in names:
                if n.split(".")[0] in NUMERIC:
                    bad.append(f"{path}:{node.lineno} imports {n}")
    assert not bad, "CLI modules only parse and print:\n" + "\n".join(bad)


def _constant_values() -> dict[float, str]:
    """Every float constant of psdbound/constants.py (evaluated: some are expressions)."""
    import psdbound.constants as c

    return {float(getattr(c, n)): n for n in c.__all__ if isinstance(getattr(c, n), float)}


def test_one_definition_of_each_physical_constant():
    # a physical constant is written once, in psdbound/constants.py; any other
    # module that spells its value defines it a second time
    values = _constant_values()
    bad = []
    for mod, path in MODULES.items():
        if mod == "psdbound.constants":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Constant) and type(node.value) is float and node.value:
                hit = values.get(node.value)
                if hit is not None:
                    bad.append(
                        f"{path}:{node.lineno} writes {node.value!r}: use psdbound.constants.{hit}"
                    )
    assert not bad, "constants defined twice:\n" + "\n".join(bad)


#: Modules that encode JSON for something other than a file a user reads, with the reason.
JSON_ENCODERS = {
    "psdbound.results.jsonfile": "the one JSON writer",
    "psdbound.results.schema": "a value quoted in an error message",
    "psdbound.compute.cache": "cache keys and the cache's own payload (not a user file)",
    "psdbound.simulate.scenario": "canonical text of a scenario for its digest and CLI echo",
    "psdbound.simulate.simulator": "truth.json beside the simulated files: sorted keys, so "
    "a simulation is byte-identical run to run",
    "psdbound.validation.outputs": "a list inside one CSV cell",
}


def test_one_json_writer():
    # every command's JSON files are written by psdbound.results.write_json (one NaN policy:
    # null; one layout); any other json.dump/json.dumps is listed above with its reason
    bad = []
    for mod, path in MODULES.items():
        if mod in JSON_ENCODERS:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if (
                isinstance(node, ast.Attribute)
                and node.attr in ("dump", "dumps")
                and isinstance(node.value, ast.Name)
                and node.value.id == "json"
            ):
                bad.append(f"{path}:{node.lineno} encodes JSON: use psdbound.results.write_json")
    assert not bad, "\n".join(bad)


LINTED = ("psdbound", "tests", "benchmarks", "docs/_ext")


def _ruff(*args: str) -> str:
    import shutil
    import subprocess

    ruff = shutil.which("ruff")
    if ruff is None:
        pytest.skip("ruff is not installed (it is in the test extra)")
    r = subprocess.run([ruff, *args, *LINTED], capture_output=True, text=True, cwd=PKG.parent)
    return "" if r.returncode == 0 else r.stdout + r.stderr


def test_ruff_check_is_clean():
    assert not (out := _ruff("check", "-q")), out


def test_ruff_format_is_clean():
    # the code is formatted by ruff, not packed by hand (no exemptions: see below)
    assert not (out := _ruff("format", "--check", "-q")), out


def test_no_formatting_exemptions():
    markers = tuple("# fmt: " + word for word in ("skip", "off"))  # not spelled: this file
    bad = []
    for folder in LINTED:
        for path in sorted((PKG.parent / folder).rglob("*.py")):
            for n, line in enumerate(path.read_text().splitlines(), start=1):
                if any(m in line for m in markers):
                    bad.append(f"{path}:{n}")
    assert not bad, "formatting exemptions (format the code instead):\n" + "\n".join(bad)
