"""Issue #17, one test per case of "Why", through the command line (in process).

Synthetic files (tests/samples.py) so that these run without ../shared/data;
the real-data versions are in test_fuzz.py and test_column_shift.py. The
reader-level details are in tests/io/test_strict_obs.py and
tests/io/test_strict_nav.py, the options in tests/cli/test_options.py, the
output folders in tests/cli/test_outputs.py.
"""

from __future__ import annotations

import gzip
import json
import math
from pathlib import Path

import pytest
from fuzzlib import run_cli
from samples import moving_observations

from psdbound.errors import InputError
from psdbound.io.write import format_obs_v3
from psdbound.results import REQUIRED_FIELDS, number_problems, read_document, write_document


@pytest.fixture
def text() -> str:
    return format_obs_v3(moving_observations())


def _write(tmp_path: Path, name: str, data: str | bytes) -> Path:
    p = tmp_path / name
    p.write_bytes(data.encode() if isinstance(data, str) else data)
    return p


def _one_error_line(r, name: str) -> str:
    lines = r.err.strip().splitlines()
    assert r.code == 2 and len(lines) == 1 and name in lines[0], r.err
    assert "Traceback" not in r.err
    return lines[0]


# "A wrong bound from a damaged header"
def test_blanked_observation_code_is_refused_naming_the_line(tmp_path, text):
    lines = text.split("\n")
    k = next(i for i, ln in enumerate(lines) if "SYS / # / OBS TYPES" in ln)
    lines[k] = lines[k][:11] + "   " + lines[k][14:]
    p = _write(tmp_path, "blank.rnx", "\n".join(lines))
    err = _one_error_line(run_cli(["inspect", p]), "blank.rnx")
    assert f"blank.rnx, line {k + 1}:" in err and "observation code 2 of 5 is blank" in err


# "Epochs and intervals trusted blindly"
@pytest.mark.parametrize("value", ["1e30", "nan", "inf", "-30"])
def test_header_interval_is_checked_against_the_epochs(tmp_path, text, value):
    tail = " " * 50 + "INTERVAL"
    bad = text.replace("    30.000" + tail, value.rjust(10) + tail)
    r = run_cli(["inspect", _write(tmp_path, "iv.rnx", bad), "--min-arc-min", "5"])
    assert r.code == 0, r.err
    assert "interval 30 s" in r.out and "span 0.33 h" in r.out
    assert "psdbound inspect: warning: " in r.err and "INTERVAL" in r.err
    assert len(r.err.strip().splitlines()) == 1


def test_out_of_order_epochs_are_refused_naming_the_line(tmp_path, text):
    lines = text.split("\n")
    starts = [i for i, ln in enumerate(lines) if ln.startswith(">")]
    a, b = starts[5], starts[9]
    lines[a : a + 3], lines[b : b + 3] = lines[b : b + 3], lines[a : a + 3]
    err = _one_error_line(
        run_cli(["inspect", _write(tmp_path, "o.rnx", "\n".join(lines))]), "o.rnx"
    )
    assert f"o.rnx, line {a + 4}: epoch" in err and "earlier than the epoch before it" in err


@pytest.mark.parametrize(
    ("old", "new"),
    [
        ("> 2020 06 25 00 05", "> 2020 13 25 00 05"),
        ("> 2020 06 25 00 05", "> 2020 06 32 00 05"),
        ("> 2020 06 25 00 05", "> 2020 06 25 25 05"),
        ("> 2020 06 25 00 05", "> 9999 06 25 00 05"),
        ("> 2020 06 25 00 05  0.0000000", "> 2020 06 25 00 05        nan"),
        ("> 2020 06 25 00 05  0.0000000", "> 2020 06 25 00 05       1e30"),
    ],
)
def test_impossible_dates_are_refused(tmp_path, text, old, new):
    err = _one_error_line(
        run_cli(["inspect", _write(tmp_path, "d.rnx", text.replace(old, new))]), "d.rnx"
    )
    assert "epoch date" in err


def test_non_numeric_values_and_satellite_ids_are_refused(tmp_path, text):
    lines = text.split("\n")
    k = next(i for i, ln in enumerate(lines) if ln.startswith("G05"))
    for new, what in (
        (lines[k][:19] + "           nan" + lines[k][33:], "not an F14.3 number"),
        ("G99" + lines[k][3:], "satellite id 'G99' is not valid"),
        ("G00" + lines[k][3:], "satellite id 'G00' is not valid"),
    ):
        bad = lines.copy()
        bad[k] = new
        err = _one_error_line(
            run_cli(["inspect", _write(tmp_path, "v.rnx", "\n".join(bad))]), "v.rnx"
        )
        assert f"v.rnx, line {k + 1}:" in err and what in err


# "Internal errors (exit 1)"
def test_corrupt_gzip_and_unreadable_files_are_bad_input(tmp_path, text, monkeypatch):
    z = bytearray(gzip.compress(text.encode(), mtime=0))
    z[len(z) // 2 : len(z) // 2 + 4] = b"\x00\xff\x13\x37"
    err = _one_error_line(run_cli(["inspect", _write(tmp_path, "z.rnx.gz", bytes(z))]), "z.rnx.gz")
    assert "cannot decompress" in err
    p = _write(tmp_path, "locked.rnx", text)
    real = Path.read_bytes

    def denied(self):
        if self.name == "locked.rnx":
            raise PermissionError(13, "Permission denied", str(self))
        return real(self)

    monkeypatch.setattr(Path, "read_bytes", denied)
    err = _one_error_line(run_cli(["inspect", p]), "locked.rnx")
    assert "Permission denied" in err


def test_tiny_cutoff_and_toml_types_are_bad_input(tmp_path, text):
    p = _write(tmp_path, "a.rnx", text)
    r = run_cli(["fit", p, "--nav", p, "--cutoff-hz", "1e-30"])
    assert r.code == 2 and "--cutoff-hz must be a number from 1e-06" in r.err
    toml = _write(tmp_path, "t.toml", "[filter]\norder = 4.5\n")
    r = run_cli(["fit", p, "--nav", p, "--config", toml])
    assert r.code == 2 and "t.toml: [filter] order must be an integer" in r.err


# result.json never holds null where a number is documented
def test_documented_numbers_are_never_null(tmp_path):
    doc = {
        "schema_version": "1",
        "method": "DF",
        "bound": {
            "sigma_gm_m": math.nan,
            "tau_s": 10.0,
            "sigma_wn_m": 0.0,
            "n_wn_two_sided_m2_hz": 0.0,
        },
        "cutoff": {"f_c_hz": 1e-3},
        "sampling": {"interval_s": 30.0, "nyquist_hz": 1 / 60},
    }
    assert number_problems(json.loads(json.dumps(doc).replace("NaN", "null"))) == [
        "'bound.sigma_gm_m' must be a finite number, got null"
    ]
    with pytest.raises(ValueError, match="'bound.sigma_gm_m' must be a finite number, got null"):
        write_document(tmp_path / "result.json", doc)
    assert not (tmp_path / "result.json").exists()
    da = {
        **doc,
        "method": "DA",
        "bound": {**doc["bound"], "sigma_gm_m": 0.01},
        "cutoff": {"f_c_hz": None, "tau_c_min": None},
    }
    assert number_problems(da) == []  # no high-pass for dual-antenna: null by design
    full: dict = {}
    leaves = [f for f in REQUIRED_FIELDS if not any(g.startswith(f + ".") for g in REQUIRED_FIELDS)]
    for f in leaves:  # a complete document, every required leaf filled with a number
        *parents, leaf = f.split(".")
        node = full
        for k in parents:
            node = node.setdefault(k, {})
        node.setdefault(leaf, 1.0)
    full.update(schema_version="1", method="DF")
    full["bound"]["sigma_gm_m"] = None
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(full))
    with pytest.raises(
        InputError,
        match=r"bad\.json: no number where the schema documents one: "
        r"'bound\.sigma_gm_m' must be a finite number, got "
        "null",
    ):
        read_document(bad)


@pytest.mark.parametrize(
    ("field", "value", "words"),
    [
        ("bound.sigma_gm_m", -0.01, "'bound.sigma_gm_m' must be >= 0, got -0.01"),
        ("bound.tau_s", 0.0, "'bound.tau_s' must be > 0, got 0.0"),
        ("verdict", "weird", "'verdict' must be 'bounded' or 'not-bounded', got \"weird\""),
    ],
)
def test_an_edited_result_with_impossible_values_is_refused(tmp_path, field, value, words):
    """report rendered 'sigma -100 cm' and 'Verdict: weird' from an edited result.json."""
    from psdbound.results.schema import value_problems

    full: dict = {}
    leaves = [f for f in REQUIRED_FIELDS if not any(g.startswith(f + ".") for g in REQUIRED_FIELDS)]
    for f in leaves:
        *parents, leaf = f.split(".")
        node = full
        for k in parents:
            node = node.setdefault(k, {})
        node.setdefault(leaf, 1.0)
    full.update(schema_version="1", method="DF", verdict="bounded")
    assert value_problems(full) == []
    *parents, leaf = field.split(".")
    node = full
    for k in parents:
        node = node[k]
    node[leaf] = value
    bad = tmp_path / "edited.json"
    bad.write_text(json.dumps(full))
    with pytest.raises(InputError, match="a value the schema does not allow") as exc:
        read_document(bad)
    assert words in str(exc.value)
