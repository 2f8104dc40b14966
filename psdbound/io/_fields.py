"""Vectorised parsing of RINEX observation fields (F14.3 + LLI + SSI).

A RINEX observation field is 16 characters: the value in Fortran ``F14.3``
(decimal point in column 11), the loss-of-lock indicator and the signal
strength indicator, each one digit or blank. Parsing millions of fields with
``float()`` is the bottleneck of every pure-Python reader; here the digits
of a whole block are combined with one matrix product. The result is exactly
what ``float(text)`` gives: the integer ``value * 1000`` is formed exactly in
float64 (fewer than 16 significant digits) and one correctly rounded
division by 1000 yields the double nearest to the decimal number.

Fields must be blank or in the strict ``F14.3`` layout: optional minus sign,
digits, the decimal point in column 11 and three decimals. Anything else (a
misplaced point, an exponent, ``nan``, letters, a fragment of a line cut
short or shifted) is reported with its row and field index: a value that is
not where the format puts it is never guessed.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

FIELD_WIDTH = 16
VALUE_WIDTH = 14
_POINT = 10  # 0-based position of the decimal point in F14.3

# weight of each character position in the integer value*1000
_WEIGHTS = np.zeros(VALUE_WIDTH, dtype=np.float64)
_WEIGHTS[:_POINT] = 10.0 ** np.arange(_POINT + 2, 2, -1)
_WEIGHTS[_POINT + 1 :] = 10.0 ** np.arange(2, -1, -1)

_SPACE, _MINUS, _DOT, _ZERO = 32, 45, 46, 48

# look-up tables indexed by character code
_DIGIT = np.zeros(256, dtype=np.float64)
_DIGIT[_ZERO : _ZERO + 10] = np.arange(10)
_MINUS_CODE, _DOT_CODE, _OTHER = 1 << 5, 1 << 9, 1 << 14
_CLASS = np.full(256, float(_OTHER))
_CLASS[_ZERO : _ZERO + 10] = 0.0
_CLASS[_SPACE] = 1.0
_CLASS[_MINUS] = float(_MINUS_CODE)
_CLASS[_DOT] = float(_DOT_CODE)
_ONES = np.ones(VALUE_WIDTH)
# column 0 counts the classes, column 1 weights them by position
_COUNT_AND_POSITION = np.column_stack([_ONES, np.arange(VALUE_WIDTH, dtype=np.float64)])
_INDICATOR = np.full(256, -1, dtype=np.int8)
_INDICATOR[_ZERO : _ZERO + 10] = np.arange(10, dtype=np.int8)


class FieldError(ValueError):
    """A field that is not a number; ``row`` and ``field`` locate it."""

    def __init__(self, row: int, field: int, text: str) -> None:
        self.row, self.field, self.text = row, field, text
        super().__init__(f"field {field + 1} is not a number: {text!r}")


def _right_justified(code: NDArray[np.int32]) -> NDArray[np.float64]:
    """Position-weighted class sum of a right-justified field with this class code.

    With ``s`` spaces, ``m`` minus signs (0 or 1) and the point in column 11,
    the field is right-justified and contiguous (spaces first, then the sign)
    exactly when the position-weighted sum is ``s(s-1)/2 + 32 s m + 512 * 10``:
    with three digits after the point, no other placement of the spaces and
    the sign gives that sum (moving the sign before a space adds at least 32,
    moving spaces right adds at most 25).
    """
    s = (code & 0x1F).astype(np.float64)
    m = ((code >> 5) & 0xF).astype(np.float64)
    return s * (s - 1.0) / 2.0 + _MINUS_CODE * s * m + _DOT_CODE * _POINT


def parse_fields(
    chars: NDArray[np.uint8],
) -> tuple[NDArray[np.float64], NDArray[np.int8], NDArray[np.int8]]:
    """Parse a block of observation fields.

    Parameters
    ----------
    chars : ndarray of uint8, shape (n_rows, n_fields, 16)
        Space-padded characters.

    Returns
    -------
    values : ndarray of float64, shape (n_rows, n_fields)
        NaN where the value is blank.
    lli, ssi : ndarray of int8, shape (n_rows, n_fields)
        The indicator digits; -1 where blank.
    """
    val = chars[:, :, :VALUE_WIDTH]
    scaled = _DIGIT[val] @ _WEIGHTS
    # class code sum: spaces count in bits 0-4, minus signs 5-8, points 9-13; and the
    # class codes weighted by position (see _RIGHT_JUSTIFIED)
    sums = _CLASS[val] @ _COUNT_AND_POSITION
    code = sums[:, :, 0].astype(np.int32)
    empty = code == VALUE_WIDTH
    values = scaled / 1000.0
    np.negative(values, out=values, where=(code & 0x1E0) != 0)
    values[empty] = np.nan
    ok = (code < _OTHER) & ((code & 0x3E00) == _DOT_CODE) & (code & 0x1E0 <= _MINUS_CODE)
    ok &= val[:, :, _POINT] == _DOT
    # three decimals after the point (a field cut short or shifted has not); writers may
    # drop the zero before the point ("-.931")
    for k in (_POINT + 1, _POINT + 2, _POINT + 3):
        ok &= (val[:, :, k] - _ZERO) < 10
    ok &= sums[:, :, 1] == _right_justified(code)
    bad = ~ok & ~empty
    if bad.any():
        r, f = (int(k[0]) for k in np.nonzero(bad))
        text = val[r, f].tobytes().decode("ascii", "replace")
        raise FieldError(r, f, text.strip() if text.strip() else text)
    lli = _INDICATOR[chars[:, :, VALUE_WIDTH]]
    ssi = _INDICATOR[chars[:, :, VALUE_WIDTH + 1]]
    return values, lli, ssi


def pad_lines(lines: list[bytes], width: int) -> NDArray[np.uint8]:
    """Stack byte lines into a space-padded (n_lines, width) uint8 array.

    Lines longer than ``width`` are cut to ``width``.
    """
    if not lines:
        return np.zeros((0, width), dtype=np.uint8)
    buf = b"".join([ln[:width].ljust(width) for ln in lines])
    return np.frombuffer(buf, dtype=np.uint8).reshape(len(lines), width)


def format_fields(
    values: NDArray[np.float64], lli: NDArray[np.int8], ssi: NDArray[np.int8]
) -> NDArray[np.uint8]:
    """Format observation fields as ``F14.3`` + LLI + SSI characters (inverse of parsing).

    Parameters
    ----------
    values : ndarray of float64
        Values (NaN -> blank field).
    lli, ssi : ndarray of int8, same shape
        Indicator digits (-1 -> blank).

    Returns
    -------
    ndarray of uint8, shape ``values.shape + (16,)``
        Characters, right-justified, decimal point in column 11.
    """
    v = np.asarray(values, dtype=np.float64)
    finite = np.isfinite(v)
    k = np.rint(np.abs(np.where(finite, v, 0.0)) * 1000.0).astype(np.int64)
    if np.any(k >= 10**13):
        raise ValueError("value too large for the F14.3 format")
    neg = (v < 0) & (k > 0)
    out = np.full(v.shape + (FIELD_WIDTH,), _SPACE, dtype=np.uint8)
    rem = k.copy()
    n_digits = np.ones(v.shape, dtype=np.int64)  # integer digits written (>= 1)
    for pos in range(VALUE_WIDTH - 1, -1, -1):
        if pos == _POINT:
            out[..., pos] = _DOT
            continue
        rem, d = np.divmod(rem, 10)
        if pos > _POINT:
            out[..., pos] = _ZERO + d
        else:
            show = (pos == _POINT - 1) | (d > 0) | (rem > 0)
            out[..., pos] = np.where(show, _ZERO + d, _SPACE)
            n_digits += show & (pos < _POINT - 1)
    sign_pos = _POINT - 1 - n_digits
    if np.any(neg & (sign_pos < 0)):
        raise ValueError("negative value too large for the F14.3 format")
    idx = np.nonzero(neg)
    out[idx + (sign_pos[idx],)] = _MINUS
    li = np.asarray(lli)
    si = np.asarray(ssi)
    out[..., VALUE_WIDTH] = np.where(li >= 0, _ZERO + np.clip(li, 0, 9), _SPACE)
    out[..., VALUE_WIDTH + 1] = np.where(si >= 0, _ZERO + np.clip(si, 0, 9), _SPACE)
    out[~finite] = _SPACE
    return out
