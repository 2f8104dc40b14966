"""Which compressed stream a file holds, told from its first bytes.

One home for the magic numbers of the containers psdbound reads: the RINEX
and SP3 reader (:mod:`psdbound.io`), the sample files of ``overbound``
(:mod:`psdbound.aviation`) and the series files a fit writes
(:mod:`psdbound.results`) all ask :func:`compression_of`.
"""

from __future__ import annotations

__all__ = ["compression_of"]

#: First bytes of each container, by the name :func:`compression_of` returns.
_MAGIC: tuple[tuple[str, bytes], ...] = (
    ("gzip", b"\x1f\x8b"),  # RFC 1952
    ("Z", b"\x1f\x9d"),  # Unix compress (LZW)
    ("bz2", b"BZh"),
    ("zip", b"PK\x03\x04"),  # a member's local header
    ("zip", b"PK\x05\x06"),  # the end record of an empty archive
)


def compression_of(head: bytes) -> str:
    """Return the container a byte stream starts with.

    Parameters
    ----------
    head : bytes
        The stream's first bytes (at least four to tell a zip archive).

    Returns
    -------
    str
        ``"gzip"``, ``"Z"``, ``"bz2"``, ``"zip"``, or ``""`` for none of them
        (plain data).
    """
    for name, magic in _MAGIC:
        if head.startswith(magic):
            return name
    return ""
