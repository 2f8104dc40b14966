"""Zero-phase high-pass filters that remove the ionosphere from DF differences.

The default is a 4th-order Butterworth filter run forwards and backwards
(:func:`scipy.signal.sosfiltfilt`), so the applied response is
``|H(f)|^2``: zero phase, -6 dB (half amplitude) at the cutoff, 160 dB per
decade below it. Other designs can be selected (Chebyshev type II, a
windowed-sinc FIR). Edge transients are handled explicitly:

``"trim"`` (default)
    the arc is extended at both ends by odd reflection over ``3 / f_c``
    (at most the arc length), filtered, and then ``1 / f_c`` seconds are
    removed at each end, where the response has not settled;
``"pad"``
    the same padding, nothing removed. Cheaper in data but not leak-free:
    on simulated 1 Hz arcs (tests/test_dual_frequency.py) the error in the
    first and last sixth of a 2 h arc is 2-6 times that of the middle,
    because near an edge low-frequency multipath and ionosphere cannot be
    told apart.

What was done is recorded by :meth:`HighPass.describe`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.common.options import Choice, Number, check_fields, option
from psdbound.errors import InputError

__all__ = ["HighPass", "FILTER_KINDS", "MAX_ORDER"]

FILTER_KINDS = ("butter", "cheby2", "fir")
#: Highest IIR order accepted (the zero-phase response has twice the order).
MAX_ORDER = 20
_MAX_TAPS = 2_000_000


@dataclass(frozen=True)
class HighPass:
    """A zero-phase high-pass filter design.

    Parameters
    ----------
    kind : {"butter", "cheby2", "fir"}, default "butter"
        Butterworth IIR, Chebyshev type II IIR (stopband ``stopband_db``
        below the passband, edge at the cutoff) or windowed-sinc FIR
        (Hamming window, ``4 / f_c`` long).
    order : int, default 4
        Order of the IIR designs, 1 to :data:`MAX_ORDER` (20); the
        zero-phase response has twice the order; ignored for FIR.
    edge : {"trim", "pad"}, default "trim"
        Edge-transient handling (see the module docstring).
    stopband_db : float, default 40
        Stopband attenuation of the Chebyshev design, dB (> 0, at most 200).

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range.
    """

    kind: str = option("butter", Choice(FILTER_KINDS, noun="filter kind"))
    order: int = option(4, Number(lo=1, hi=MAX_ORDER, integer=True))
    edge: str = option("trim", Choice(("trim", "pad"), noun="edge handling"))
    stopband_db: float = option(40.0, Number(lo=0.0, hi=200.0, lo_open=True, unit="dB"))

    def __post_init__(self) -> None:
        check_fields(self)

    def check_cutoff(self, cutoff_hz: float, interval_s: float) -> float:
        """Raise :class:`InputError` unless 0 < cutoff < Nyquist; return Nyquist, Hz."""
        nyq = 0.5 / interval_s
        if not 0.0 < cutoff_hz < nyq:
            raise InputError(
                f"cutoff {cutoff_hz:g} Hz must lie between 0 and the Nyquist frequency "
                f"{nyq:g} Hz of {interval_s:g} s sampling"
            )
        return nyq

    def apply(
        self, x: NDArray[np.float64], interval_s: float, cutoff_hz: float
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Filter one evenly sampled arc.

        Parameters
        ----------
        x : ndarray of float64
            The series (metres), evenly sampled.
        interval_s : float
            Sampling interval, seconds.
        cutoff_hz : float
            Cutoff frequency, Hz.

        Returns
        -------
        y : ndarray of float64
            Filtered series, same length as ``x``.
        keep : ndarray of bool
            Samples to keep (all True for ``edge="pad"``; False on the
            trimmed ends for ``edge="trim"``).
        """
        self.check_cutoff(cutoff_hz, interval_s)
        n = x.size
        pad = int(min(n - 1, np.ceil(3.0 / (cutoff_hz * interval_s))))
        if self.kind == "fir":
            y = self._fir(x, interval_s, cutoff_hz, pad)
        else:
            sos, zi = self.sos(interval_s, cutoff_hz), self.initial_state(interval_s, cutoff_hz)
            y = _zero_phase(np.asarray(x, dtype=np.float64), sos, zi, pad)
        keep = np.ones(n, dtype=bool)
        if self.edge == "trim":
            k = int(np.ceil(1.0 / (cutoff_hz * interval_s)))
            keep[:k] = False
            keep[max(n - k, 0) :] = False
        return y, keep

    def sos(self, interval_s: float, cutoff_hz: float) -> NDArray[np.float64]:
        """Second-order sections of the single-pass IIR design (a copy of the cached design)."""
        return _iir_design(*self._iir_key(interval_s, cutoff_hz)).copy()

    def initial_state(self, interval_s: float, cutoff_hz: float) -> NDArray[np.float64]:
        """Step-response initial state of :meth:`sos` (``scipy.signal.sosfilt_zi``; a copy)."""
        return _iir_state(*self._iir_key(interval_s, cutoff_hz)).copy()

    def _iir_key(self, interval_s: float, cutoff_hz: float) -> tuple[str, int, float, float, float]:
        """Return the cached IIR design's key; refuse the FIR design, which has none."""
        if self.kind not in ("butter", "cheby2"):
            raise InputError("the FIR design has no second-order sections")
        return self.kind, self.order, self.stopband_db, interval_s, cutoff_hz

    @staticmethod
    def _numtaps(interval_s: float, cutoff_hz: float) -> int:
        """Length of the FIR design, ``4 / f_c`` seconds (odd); refused when absurdly long."""
        n = 4.0 / (cutoff_hz * interval_s)
        if not n <= _MAX_TAPS:
            raise InputError(
                f"the FIR high-pass at {cutoff_hz:g} Hz and {interval_s:g} s sampling would "
                f"need {n:.3g} taps (4 / (f_c dt), at most {_MAX_TAPS:g}); raise the cutoff "
                "or use an IIR design (butter, cheby2)"
            )
        return int(np.ceil(n)) | 1

    def _fir(self, x: NDArray[np.float64], interval_s: float, cutoff_hz: float, pad: int):
        from scipy import signal  # deferred: the options class is imported by every --help

        numtaps = self._numtaps(interval_s, cutoff_hz)
        taps = _fir_design(numtaps, interval_s, cutoff_hz)
        half = numtaps // 2
        m = min(half, x.size - 1)
        ext = np.concatenate([2 * x[0] - x[m:0:-1], x, 2 * x[-1] - x[-2 : -m - 2 : -1]])
        full = signal.oaconvolve(ext, taps, mode="same")
        return full[m : m + x.size]

    def response(self, f_hz: NDArray[np.float64], interval_s: float, cutoff_hz: float):
        """Zero-phase amplitude response (applied forward-backward for IIR) at ``f_hz``."""
        from scipy import signal  # deferred: the options class is imported by every --help

        self.check_cutoff(cutoff_hz, interval_s)
        fs = 1.0 / interval_s
        if self.kind == "fir":
            taps = _fir_design(self._numtaps(interval_s, cutoff_hz), interval_s, cutoff_hz)
            _, h = signal.freqz(taps, worN=f_hz, fs=fs)
            return np.abs(h)
        _, h = signal.sosfreqz(self.sos(interval_s, cutoff_hz), worN=f_hz, fs=fs)
        return np.abs(h) ** 2

    def passband_start_hz(
        self, interval_s: float, cutoff_hz: float, *, power: float = 0.9
    ) -> float:
        """Lowest frequency above which the filter passes at least ``power`` of the PSD, Hz.

        Below it the high-passed series under-represents the multipath
        spectrum by more than ``1 - power``; the pooled bound starts there.

        Parameters
        ----------
        interval_s : float
            Sampling interval, seconds.
        cutoff_hz : float
            Cutoff frequency, Hz.
        power : float, default 0.9
            Power response ``|H(f)|^2`` required, in (0, 1).

        Returns
        -------
        float
        """
        nyq = self.check_cutoff(cutoff_hz, interval_s)
        f = np.geomspace(cutoff_hz, nyq, 2000)
        low = np.flatnonzero(self.response(f, interval_s, cutoff_hz) ** 2 < power)
        if low.size == 0:
            return float(cutoff_hz)
        return float(f[min(low[-1] + 1, f.size - 1)])

    def describe(self, interval_s: float, cutoff_hz: float) -> dict[str, Any]:
        """Provenance of the filter as applied: design, zero-phase method, edges."""
        d: dict[str, Any] = {
            "kind": self.kind,
            "cutoff_hz": cutoff_hz,
            "zero_phase": "forward-backward (sosfiltfilt)"
            if self.kind != "fir"
            else "symmetric FIR, centred convolution",
            "edge": self.edge,
            "padding": "odd reflection over min(3/f_c, arc length)",
        }
        if self.kind != "fir":
            d["order"] = self.order
            d["effective_order"] = 2 * self.order
        if self.kind == "cheby2":
            d["stopband_db"] = self.stopband_db
        if self.edge == "trim":
            d["trim_s"] = float(np.ceil(1.0 / (cutoff_hz * interval_s)) * interval_s)
        return d


# The designs depend on the options, the sampling and the cutoff alone; a station day
# filters hundreds of arcs (and the validation filters them again) with one design,
# which scipy would otherwise compute anew each time (about 1 ms each). The cached
# arrays are read-only; sos() hands out copies.
@lru_cache(maxsize=64)
def _iir_design(
    kind: str, order: int, stopband_db: float, interval_s: float, cutoff_hz: float
) -> NDArray[np.float64]:
    """Second-order sections of a high-pass Butterworth or Chebyshev II design (read-only)."""
    from scipy import signal  # deferred: the options class is imported by every --help

    fs = 1.0 / interval_s
    if kind == "butter":
        sos = signal.butter(order, cutoff_hz, btype="highpass", fs=fs, output="sos")
    else:
        sos = signal.cheby2(order, stopband_db, cutoff_hz, btype="highpass", fs=fs, output="sos")
    sos.setflags(write=False)
    return np.asarray(sos, dtype=np.float64)


@lru_cache(maxsize=64)
def _iir_state(
    kind: str, order: int, stopband_db: float, interval_s: float, cutoff_hz: float
) -> NDArray[np.float64]:
    """``sosfilt_zi`` of :func:`_iir_design` (read-only): a linear solve per section."""
    from scipy.signal import sosfilt_zi

    zi = sosfilt_zi(_iir_design(kind, order, stopband_db, interval_s, cutoff_hz))
    zi.setflags(write=False)
    return np.asarray(zi, dtype=np.float64)


def _zero_phase(
    x: NDArray[np.float64], sos: NDArray[np.float64], zi: NDArray[np.float64], pad: int
) -> NDArray[np.float64]:
    """``scipy.signal.sosfiltfilt(sos, x, padtype="odd", padlen=pad)``, ``zi`` given.

    The same arithmetic as scipy's (odd extension, forward pass started at
    ``zi x[0]``, backward pass at ``zi y[-1]``), without recomputing
    ``sosfilt_zi(sos)`` for every arc;
    ``tests/ionosphere/test_iono_residual.py`` checks the equality to the bit.
    """
    from scipy.signal import sosfilt

    if pad > 0:
        ext = np.concatenate([2 * x[0] - x[pad:0:-1], x, 2 * x[-1] - x[-2 : -pad - 2 : -1]])
    else:
        ext = x
    y, _ = sosfilt(sos, ext, zi=zi * ext[0])
    y, _ = sosfilt(sos, y[::-1], zi=zi * y[-1])
    y = y[::-1]
    return y[pad : y.size - pad] if pad > 0 else y


@lru_cache(maxsize=16)
def _fir_design(numtaps: int, interval_s: float, cutoff_hz: float) -> NDArray[np.float64]:
    """Taps of the windowed-sinc (Hamming) high-pass FIR design (read-only)."""
    from scipy import signal  # deferred: the options class is imported by every --help

    taps = signal.firwin(numtaps, cutoff_hz, pass_zero=False, fs=1.0 / interval_s, window="hamming")
    taps.setflags(write=False)
    return np.asarray(taps, dtype=np.float64)
