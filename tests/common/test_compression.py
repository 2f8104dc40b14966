"""A byte stream's container, told from its first bytes, on streams the libraries write."""

from __future__ import annotations

import bz2
import gzip
import io
import zipfile

import pytest

from psdbound.common.compression import compression_of

TEXT = b"     3.04           OBSERVATION DATA    M                   RINEX VERSION / TYPE\n"


def _zip(members: dict[str, bytes]) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for name, data in members.items():
            z.writestr(name, data)
    return buf.getvalue()


@pytest.mark.parametrize(
    ("stream", "kind"),
    [
        (gzip.compress(TEXT), "gzip"),
        (bz2.compress(TEXT), "bz2"),
        (_zip({"a.rnx": TEXT}), "zip"),
        (_zip({}), "zip"),
        (b"\x1f\x9d\x90" + TEXT, "Z"),
        (TEXT, ""),
        (b"", ""),
        (b"\x1f", ""),
    ],
)
def test_compression_of(stream, kind):
    assert compression_of(stream[:4]) == kind
