"""``cutoff`` and ``validate`` write what the other commands write: JSON with a schema, a page.

Each command runs once on a small case (a station-day of the nominal GPS
constellation without the cache; one ground reflection) with some of its
options from ``--config``; its JSON must follow its shipped schema, its
HTML page must name the result and link its figures, and the TOML values
must be in the outputs. ``simulate`` and ``export`` take ``--config`` too.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from psdbound.cli.main import build_parser, main
from psdbound.results import load_schema, schema_errors
from psdbound.results.jsonschema import SCHEMAS

pytest.importorskip("jsonschema")


def _undescribed(spec: dict, where: str = "") -> list[str]:
    """Every property of a schema, at any depth, without a description (dotted paths)."""
    out = []
    for name, sub in (spec.get("properties") or {}).items():
        path = f"{where}.{name}" if where else name
        if not sub.get("description"):
            out.append(path)
        out += _undescribed(sub, path)
    if isinstance(spec.get("items"), dict):
        out += _undescribed(spec["items"], where + "[]")
    if isinstance(spec.get("additionalProperties"), dict):
        out += _undescribed(spec["additionalProperties"], where + ".*")
    return out


@pytest.mark.parametrize("name", sorted(SCHEMAS))
def test_every_field_is_described(name):
    schema = load_schema(name)
    assert schema["description"] and _undescribed(schema) == []


def _figure_links(html: str, folder: Path) -> list[str]:
    """The PNG files a page links, each checked to exist beside it."""
    names = sorted({part.split('"')[0] for part in html.split('href="')[1:]})
    assert all((folder / n).is_file() for n in names), names
    return names


# --------------------------------------------------------------------------- cutoff


@pytest.fixture(scope="module")
def cutoff_run(tmp_path_factory):
    """One station-day, its name, day, workers, cache and mask from ``--config``."""
    folder = tmp_path_factory.mktemp("cutoff")
    toml = folder / "cutoff.toml"
    toml.write_text(
        '[cutoff]\nname = "CFG"\ndays = "2020-01-06"\nworkers = 0\nno_cache = true\n'
        f"cache_dir = {json.dumps(str(folder / 'cache'))}\nmask_deg = 15.0\n"
    )
    out = folder / "out"
    argv = ["cutoff", "--lat", "41.84", "--lon", "-87.63", "--out", str(out)]
    assert main([*argv, "--config", str(toml)]) == 0
    return out


def test_cutoff_json_follows_its_schema_and_the_config(cutoff_run):
    assert sorted(p.name for p in cutoff_run.iterdir()) == [
        "cutoff_CFG.csv",
        "cutoff_CFG.html",
        "cutoff_CFG.json",
        "cutoff_CFG_residual.png",
    ]
    doc = json.loads((cutoff_run / "cutoff_CFG.json").read_text())
    assert schema_errors(doc, schema="cutoff") == []
    assert doc["days"] == ["2020-01-06"] and doc["from_cache"] == [False]
    assert not (cutoff_run.parent / "cache").exists()  # no_cache = true
    assert doc["settings"]["elevation_mask_deg"] == 15.0 and doc["station"]["name"] == "CFG"
    doc["summary"]["recommended_f_c_hz"] = "fast"
    doc["rows"][0]["unknown"] = 1
    errors = schema_errors(doc, schema="cutoff")
    assert any("recommended_f_c_hz" in e for e in errors) and any("unknown" in e for e in errors)


def test_cutoff_page_names_the_cutoff_and_links_its_figure(cutoff_run):
    doc = json.loads((cutoff_run / "cutoff_CFG.json").read_text())
    html = (cutoff_run / "cutoff_CFG.html").read_text()
    rec = doc["summary"]["recommended_f_c_hz"]
    assert f"Recommended cutoff f_c = {rec:.3e} Hz" in html
    assert "cutoff_CFG.json" in html and "cutoff.schema.json" in html
    assert _figure_links(html, cutoff_run) == ["cutoff_CFG_residual.png"]
    assert "data:image/png;base64," in html and "<caption>Per day</caption>" in html


def test_world_map_outputs_follow_their_schema(tmp_path):
    from psdbound.ionosphere.outputs import write_world_map_outputs
    from psdbound.ionosphere.worldmap import load_map

    shipped = load_map()
    assert schema_errors(shipped, schema="cutoff_map") == []
    files = write_world_map_outputs(shipped, tmp_path, install_path=tmp_path / "copy.json")
    assert [f.name for f in files] == [
        "cutoff_map.json",
        "cutoff_map.csv",
        "cutoff_map.png",
        "cutoff_map.html",
        "copy.json",
    ]
    for name in ("cutoff_map.json", "copy.json"):
        assert json.loads((tmp_path / name).read_text()) == shipped
    html = (tmp_path / "cutoff_map.html").read_text()
    assert "World cutoff map: 20 reference stations" in html
    assert _figure_links(html, tmp_path) == ["cutoff_map.png"]
    assert "cutoff_map.schema.json" in html


# --------------------------------------------------------------------------- validate


@pytest.fixture(scope="module")
def validate_run(tmp_path_factory):
    """One ground reflection, its geometry, threshold and alpha from ``--config``."""
    folder = tmp_path_factory.mktemp("validate")
    toml = folder / "validate.toml"
    toml.write_text('[validate]\ngeometry = ["ground:h=1.5"]\nthreshold = 0.35\nalpha = 0.2\n')
    out = folder / "out"
    argv = ["validate", "--cutoff-hz", "9.55e-4", "--out", str(out)]
    assert main([*argv, "--config", str(toml)]) == 0
    return out


def test_validation_json_follows_its_schema_and_the_config(validate_run):
    assert sorted(p.name for p in validate_run.iterdir()) == [
        "validation.csv",
        "validation.html",
        "validation.json",
        "validation_expansion.png",
    ]
    doc = json.loads((validate_run / "validation.json").read_text())
    assert schema_errors(doc, schema="validation") == []
    assert doc["threshold"] == 0.35 and doc["alpha"] == 0.2
    assert {r["geometry"] for r in doc["expansion"]} == {"ground:h=1.5"}
    doc["verdict"] = "maybe"
    assert any("verdict" in e for e in schema_errors(doc, schema="validation"))


def test_validation_page_names_the_verdict_and_links_its_figure(validate_run):
    doc = json.loads((validate_run / "validation.json").read_text())
    html = (validate_run / "validation.html").read_text()
    verdict = "pass" if doc["passed"] else "FAIL"
    assert f"Verdict (physical convention): {verdict}" in html and "(threshold 35 %)" in html
    assert _figure_links(html, validate_run) == ["validation_expansion.png"]
    assert "validation.schema.json" in html and html.count("<tr>") == 1 + len(doc["expansion"])


# --------------------------------------------------------------------------- simulate, export


def test_simulate_takes_its_flags_from_config(tmp_path, capsys):
    toml = tmp_path / "sim.toml"
    toml.write_text('preset = "short"\nduration_h = 0.25\nsingle_antenna = true\nseed = 7\n')
    out = tmp_path / "sim"
    assert main(["simulate", "--config", str(toml), "--out", str(out), "--seed", "8"]) == 0
    truth = json.loads(next(out.glob("*_truth.json")).read_text())["scenario"]
    assert truth["seed"] == 8  # the command line wins
    assert truth["duration_s"] == 900.0 and truth["dual_antenna"] is False
    assert truth["name"].startswith("psdbound-short")


def test_export_reads_the_fit_configuration(tmp_path):
    from psdbound.cli.export import _as_fit_args
    from psdbound.cli.fit import build_config

    toml = tmp_path / "fit.toml"
    toml.write_text("[arcs]\nmin_length_s = 2400.0\n")
    args = build_parser("export").parse_args(["export", "--config", str(toml)])
    assert build_config(_as_fit_args(args)).arcs.min_length_s == 2400.0
