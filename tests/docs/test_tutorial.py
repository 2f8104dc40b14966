"""The documentation's executed examples: the Kalman-filter tutorial and the TOML example."""

from __future__ import annotations

import doctest
from pathlib import Path

DOCS = Path(__file__).resolve().parents[2] / "docs"


def test_kalman_tutorial_runs():
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testfile(
        str(DOCS / "tutorial_kalman.rst"),
        module_relative=False,
        optionflags=flags,
        report=True,
        verbose=False,
    )
    assert result.attempted >= 50, result
    assert result.failed == 0, result


def test_configuration_example_is_a_valid_config(tmp_path):
    from psdbound.pipeline import FitConfig

    text = (DOCS / "user_guide" / "configuration.rst").read_text()
    block = text.split(".. code-block:: toml", 1)[1].split("\nRules\n", 1)[0]
    toml = "\n".join(line[3:] for line in block.splitlines())
    (tmp_path / "run.toml").write_text(toml)
    cfg = FitConfig.from_toml(tmp_path / "run.toml").to_dict()
    assert cfg["cutoff"]["f_c_hz"] == 9.55e-4
    assert cfg["bound"]["rule"] == "pooled" and cfg["mapping"]["kind"] == "fit"
    assert cfg["code_multipath"]["codes"] == ["C1C"] or cfg["code_multipath"]["codes"] == ("C1C",)


def test_docs_do_not_point_users_to_the_shared_folder():
    bad = [
        str(p.relative_to(DOCS))
        for p in DOCS.rglob("*")
        if p.is_file()
        and p.suffix in {".rst", ".py", ".md", ".txt"}
        and "_build" not in p.parts
        and "../shared" in p.read_text()
    ]
    assert not bad, f"'../shared' in {bad}"
