"""overbound.json, budget.json and vpl.json follow their shipped JSON Schemas."""

from __future__ import annotations

import json

import numpy as np
import pytest

from psdbound.cli.main import main
from psdbound.results import load_schema, schema_errors

pytest.importorskip("jsonschema")

SATS = [a for s in ("10,12", "80,25", "150,38", "200,47", "260,60") for a in ("--sat", s)]


def _described(schema: dict, path: str = "") -> list[str]:
    """Every property of a schema without a description (dotted paths)."""
    out = []
    for name, spec in (schema.get("properties") or {}).items():
        where = f"{path}.{name}" if path else name
        if "description" not in spec:
            out.append(where)
        out += _described(spec, where)
        if isinstance(spec.get("items"), dict):
            out += _described(spec["items"], where + "[]")
    return out


@pytest.mark.parametrize("name", ["overbound", "budget", "vpl"])
def test_every_field_is_described(name):
    assert _described(load_schema(name)) == []


def test_overbound_json_is_valid(tmp_path, capsys):
    rng = np.random.default_rng(3)
    el = rng.uniform(5.0, 90.0, 4000)
    err = rng.standard_t(4, el.size) * (0.2 + np.exp(-el / 20.0))
    csv = tmp_path / "s.csv"
    np.savetxt(csv, np.c_[err, el], delimiter=",", header="error_m,elevation_deg", comments="")
    out = tmp_path / "ob"
    out.mkdir()
    assert main(["overbound", str(csv), "--out", str(out)]) == 0
    doc = json.loads((out / "overbound.json").read_text())
    assert schema_errors(doc, schema="overbound") == []
    html = (out / "overbound.html").read_text()
    assert "<table>" in html and "data:image/png;base64," in html and "overbound.json" in html
    assert 'href="overbound_qq.png"' in html
    doc["overbound"]["bins"][0]["sigma"] = "wide"
    assert any("sigma" in e for e in schema_errors(doc, schema="overbound"))


def test_budget_and_vpl_json_are_valid(tmp_path, capsys):
    out = tmp_path / "b"
    assert main(["budget", "--k-md-e", "5", *SATS, "--out", str(out)]) == 0
    doc = json.loads((out / "budget.json").read_text())
    assert schema_errors(doc, schema="budget") == []
    page = (out / "budget.html").read_text()
    assert "K_md_e = 5" in page and page.count("<tr>") == 1 + len(SATS) // 2
    out2 = tmp_path / "v"
    args = ["budget", "--k-md-e", "5", "--nominal", "GE", "--position", "55.49,8.46,59"]
    assert main([*args, "--hours", "2", "--val-m", "10", "--out", str(out2)]) == 0
    vpl = json.loads((out2 / "vpl.json").read_text())
    assert schema_errors(vpl, schema="vpl") == []
    assert 0.0 <= vpl["vpl"]["availability"] <= 1.0
    page = (out2 / "vpl.html").read_text()
    assert "data:image/png;base64," in page and 'href="vpl.png"' in page
