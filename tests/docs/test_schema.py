"""result.json against its shipped JSON Schema (psdbound/results/result.schema.json)."""

from __future__ import annotations

import copy
import dataclasses
import json

import pytest
from conftest import ESBC_NAV, ESBC_OBS, shared_file

import psdbound
from psdbound.errors import InputError
from psdbound.results import load_schema, schema_errors, validate

jsonschema = pytest.importorskip("jsonschema")


@pytest.fixture(scope="module")
def demo_doc():
    return psdbound.fit().document


@pytest.fixture(scope="module")
def pair_doc(tmp_path_factory):
    from psdbound.simulate import preset, simulate

    sc = dataclasses.replace(preset("demo"), duration_s=1.5 * 3600.0)
    sim = simulate(sc, tmp_path_factory.mktemp("pair"))
    files = [str(p) for p in sim.obs_paths]
    return psdbound.fit(files, nav=sim.nav_path, pair=tuple(files)).document


def _json_roundtrip(doc):
    return json.loads(json.dumps(doc))


def _walk(spec, path="(root)"):
    yield path, spec
    for key, sub in spec.get("properties", {}).items():
        yield from _walk(sub, f"{path}.{key}")
    items = spec.get("items")
    if isinstance(items, dict):
        for key, sub in items.get("properties", {}).items():
            yield from _walk(sub, f"{path}[].{key}")


def test_schema_is_a_valid_draft_2020_12_schema():
    schema = load_schema()
    assert schema["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    jsonschema.Draft202012Validator.check_schema(schema)


def test_every_field_is_documented():
    missing = [p for p, spec in _walk(load_schema()) if not spec.get("description")]
    assert not missing, f"fields without a description: {missing}"


def test_schema_requires_what_the_reader_requires():
    from psdbound.results import REQUIRED_FIELDS

    schema = load_schema()
    for dotted in REQUIRED_FIELDS:
        spec, parts = schema, dotted.split(".")
        for part in parts:
            assert part in spec.get("required", []), f"{dotted}: {part} not required"
            spec = spec["properties"][part]


def test_the_reader_requires_every_field_the_schema_requires(demo_doc, tmp_path):
    from psdbound.results import REQUIRED_FIELDS

    # REQUIRED_FIELDS is derived from the schema (its one home), nested ones included
    assert {"verdict", "error_model.state_space.phi", "bound.pooled.coverage"} <= set(
        REQUIRED_FIELDS
    )
    p = tmp_path / "result.json"
    for dotted in ("verdict", "error_model", "bound.pooled.coverage", "screening.excluded"):
        doc = copy.deepcopy(_json_roundtrip(demo_doc))
        *parents, leaf = dotted.split(".")
        node = doc
        for key in parents:
            node = node[key]
        del node[leaf]
        p.write_text(json.dumps(doc))
        with pytest.raises(InputError, match=f"lacks the field '{dotted}'"):
            psdbound.load(p)  # was a KeyError from FitResults for 'verdict'
    doc = _json_roundtrip(demo_doc)
    doc["bound"]["pooled"] = None  # null is allowed (the envelope rule): nothing inside required
    p.write_text(json.dumps(doc))
    assert psdbound.load(p).verdict == demo_doc["verdict"]


def test_schema_is_shipped_as_package_data():
    from importlib import resources

    assert resources.files("psdbound.results").joinpath("result.schema.json").is_file()


def test_demo_result_is_valid(demo_doc):
    doc = _json_roundtrip(demo_doc)
    assert schema_errors(doc) == []
    validate(doc)
    assert doc["method"] == "DF" and "demo" in doc


def test_dual_antenna_result_is_valid(pair_doc):
    doc = _json_roundtrip(pair_doc)
    assert schema_errors(doc) == []
    assert doc["method"] == "DA" and doc["cutoff"]["f_c_hz"] is None
    assert "baseline_estimate" in doc["isolation"]


@pytest.mark.realdata
@pytest.mark.slow
def test_esbc_result_is_valid():
    doc = psdbound.fit(shared_file(ESBC_OBS), nav=shared_file(ESBC_NAV)).document
    assert schema_errors(_json_roundtrip(doc)) == []


@pytest.mark.parametrize(
    "mutate, where",
    [
        (lambda d: d["bound"].pop("tau_s"), "bound"),
        (lambda d: d.pop("verdict"), "(top level)"),
        (lambda d: d["bound"].__setitem__("sigma_gm_m", "3 mm"), "bound.sigma_gm_m"),
        (lambda d: d["bound"].__setitem__("sigma_gm_m", None), "bound.sigma_gm_m"),
        (lambda d: d.__setitem__("verdict", "maybe"), "verdict"),
        (lambda d: d.__setitem__("schema_version", "2"), "schema_version"),
        (lambda d: d["windows"].__setitem__("count", 1.5), "windows.count"),
        (lambda d: d["sampling"].__setitem__("nyquist_hz", "0.5"), "sampling.nyquist_hz"),
        (
            lambda d: d["screening"].__setitem__(
                "excluded",
                [
                    {
                        "sat": "G01",
                        "start_gps_s": 0.0,
                        "stop_gps_s": 300.0,
                        "kind": "ionosphere",
                        "statistic": 0.3,
                        "threshold": 0.2,
                    }
                ],
            ),
            "screening.excluded.0",
        ),  # no reason
        (lambda d: d.__setitem__("unexpected", 1), "(top level)"),
    ],
)
def test_a_wrong_document_fails(demo_doc, mutate, where):
    doc = copy.deepcopy(_json_roundtrip(demo_doc))
    mutate(doc)
    errors = schema_errors(doc)
    assert errors and any(e.startswith(where) for e in errors), errors
    with pytest.raises(InputError, match="does not match result.schema.json"):
        validate(doc)
