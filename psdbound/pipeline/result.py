"""The result of a ``fit`` run: a versioned JSON document and its reader.

``result.json`` (schema version ``"1"``) holds the bound, cutoff, sampling,
mapping, windows, validation, warnings and provenance, plus a ``figures``
section with the (decimated) data every report figure is drawn from, so a
report can be re-rendered from the file alone (``psdbound report``).
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.errors import InputError

__all__ = ["SCHEMA_VERSION", "FitResult", "REQUIRED_FIELDS"]

SCHEMA_VERSION = "1"

#: Dotted paths every result file must contain.
REQUIRED_FIELDS = (
    "schema_version",
    "method",
    "bound.sigma_gm_m",
    "bound.tau_s",
    "bound.sigma_wn_m",
    "bound.n_wn_two_sided_m2_hz",
    "cutoff.f_c_hz",
    "cutoff.source",
    "sampling.interval_s",
    "sampling.nyquist_hz",
    "mapping",
    "windows.count",
    "windows.total_duration_s",
    "windows.per_window",
    "validation",
    "warnings",
    "provenance.inputs",
    "provenance.versions",
    "provenance.configuration",
    "provenance.created_utc",
    "figures",
)


def _jsonable(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _jsonable(obj.tolist())
    if isinstance(obj, np.generic):
        return _jsonable(obj.item())
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, Path):
        return str(obj)
    return obj


def _get(d: dict, dotted: str) -> Any:
    cur: Any = d
    for part in dotted.split("."):
        if not isinstance(cur, dict) or part not in cur:
            raise KeyError(dotted)
        cur = cur[part]
    return cur


@dataclass(frozen=True)
class FitResult:
    """A fit result (the content of ``result.json``).

    Attributes
    ----------
    data : dict
        The JSON document (see the module docstring for its sections).
    """

    data: dict[str, Any]

    @property
    def bound(self) -> dict[str, Any]:
        """The ``bound`` section (parameters with units in their names)."""
        return self.data["bound"]

    def to_json(self, path: str | os.PathLike[str]) -> Path:
        """Write the result as JSON atomically (temporary file + rename)."""
        p = Path(path)
        tmp = p.with_name(p.name + ".part")
        tmp.write_text(json.dumps(_jsonable(self.data), indent=1, allow_nan=False) + "\n")
        os.replace(tmp, p)
        return p

    @classmethod
    def from_json(cls, path: str | os.PathLike[str]) -> FitResult:
        """Read and check a result file.

        Raises
        ------
        InputError
            Missing file, invalid JSON, wrong schema version or a missing field.
        """
        p = Path(path)
        if not p.is_file():
            raise InputError("result file not found", path=p)
        try:
            data = json.loads(p.read_text())
        except (json.JSONDecodeError, UnicodeDecodeError) as exc:
            raise InputError(f"not a JSON result file: {exc}", path=p) from None
        if not isinstance(data, dict):
            raise InputError("not a psdbound result (top level is not an object)", path=p)
        version = data.get("schema_version")
        if version != SCHEMA_VERSION:
            raise InputError(
                f"result schema version {version!r} is not supported (expected {SCHEMA_VERSION!r})",
                path=p,
            )
        for f in REQUIRED_FIELDS:
            try:
                _get(data, f)
            except KeyError:
                raise InputError(f"result file lacks the field {f!r}", path=p) from None
        return cls(data)

    def summary(self) -> str:
        """Return a short text summary (bound, cutoff, sampling, windows, verdict)."""
        d = self.data
        b, c, s, w = d["bound"], d["cutoff"], d["sampling"], d["windows"]
        fc = "n/a" if c["f_c_hz"] is None else f"{c['f_c_hz']:.4g} Hz ({c['source']})"
        lines = [
            f"psdbound fit ({d['method']}): sigma_GM = {100 * b['sigma_gm_m']:.3f} cm, "
            f"tau = {b['tau_s']:.1f} s, sigma_WN = {100 * b['sigma_wn_m']:.3f} cm "
            f"(per sample at {s['interval_s']:g} s)",
            f"  cutoff {fc}; Nyquist {s['nyquist_hz']:.4g} Hz; {w['count']} stationary windows "
            f"({w['total_duration_s'] / 3600:.2f} h); validation: "
            f"{d['validation'].get('verdict', 'n/a')}",
        ]
        if d["warnings"]:
            lines.append(f"  {len(d['warnings'])} warning(s): " + "; ".join(d["warnings"][:3]))
        return "\n".join(lines)
