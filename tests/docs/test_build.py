"""The documentation builds with warnings as errors (``python -m sphinx -W``)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

DOCS = Path(__file__).resolve().parents[2] / "docs"


@pytest.mark.slow
def test_sphinx_html_build_has_no_warnings(tmp_path):
    pytest.importorskip("sphinx")
    pytest.importorskip("numpydoc")
    pytest.importorskip("pydata_sphinx_theme")
    out = tmp_path / "html"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "sphinx",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            "-d",
            str(tmp_path / "doctrees"),
            str(DOCS),
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert r.returncode == 0, r.stdout[-4000:] + r.stderr[-8000:]
    pages = {p.relative_to(out).as_posix() for p in out.rglob("*.html")}
    for page in (
        "index.html",
        "tutorial_kalman.html",
        "bibliography.html",
        "reference/cli.html",
        "reference/result_json.html",
        "method/bound.html",
        "method/cutoff.html",
        "user_guide/dual_antenna.html",
    ):
        assert page in pages, page
    cli = (out / "reference" / "cli.html").read_text()
    assert "--pair" in cli and "psdbound campaign" in cli
    arch = (out / "reference" / "architecture.html").read_text()
    assert "<svg" in arch and ">pipeline</text>" in arch and ">constants</text>" in arch
    ref = (out / "reference" / "result_json.html").read_text()
    assert "bound.sigma_gm_m" in ref and "n_wn_two_sided_m2_hz" in ref


def test_architecture_graph_is_the_code_s_imports():
    # the diagram's graph is read from the sources: the runner's imports appear, and
    # the layers put every package above what it imports
    sys.path.insert(0, str(DOCS / "_ext"))
    try:
        import psdbound_architecture as arch
    finally:
        sys.path.pop(0)
    graph = arch.package_graph()
    layer = arch.layers(graph)
    assert {"spectra", "screening", "stationarity"} <= graph["pipeline"]
    assert graph["constants"] == set() and layer["constants"] == 0
    assert all(layer[p] > layer[d] for p, deps in graph.items() for d in deps)
    assert arch.svg(graph).count("<rect") == len(graph)
