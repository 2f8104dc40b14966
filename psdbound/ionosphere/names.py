"""Defaults and choices of a cutoff run and the thesis's cutoffs, in a module importing nothing.

The cutoff policy (options), the residual-ionosphere criterion, the
simulation, the periodogram criteria and the batch settings
(:class:`~psdbound.ionosphere.CutoffSettings`, whose schema the ``cutoff``
command's options read) all use them; living at the bottom, they create no
import cycle and load no numerical library (``psdbound cutoff --help``).
"""

from __future__ import annotations

from psdbound.constants import F_L1_HZ, F_L2_HZ, F_L5_HZ

__all__ = [
    "ALT_RESOLUTIONS",
    "CRITERIA",
    "DEFAULT_DROP_DB",
    "DEFAULT_F107_SFU",
    "DEFAULT_MARGIN_DB",
    "DEFAULT_MP_SIGMA_M",
    "DEFAULT_SHELL_HEIGHT_KM",
    "DEFAULT_VARIANCE_M2",
    "FREQUENCIES_HZ",
    "F_MIN_HZ",
    "IRI_MODELS",
    "METHODS",
    "MIN_ARC_S",
    "MIN_KEPT_S",
    "MIN_SERIES_SAMPLES",
    "NOMINAL_SYSTEMS",
    "REFERENCES",
    "THESIS_CHICAGO_2020_HZ",
]

#: Reference multipath sigma (per carrier, the bound's units), m.
DEFAULT_MP_SIGMA_M = 1e-3
#: Residual ionosphere below the reference multipath, dB (amplitude factor 100).
DEFAULT_MARGIN_DB = 40.0
#: The thesis's Chicago 2020 cutoffs (section 4.3.3): mean, min and max over
#: about 350 satellite-days, Hz; the maximum is its recommended cutoff (eq. 4.2).
THESIS_CHICAGO_2020_HZ = {"mean": 6.73e-4, "min": 5.03e-4, "max": 9.55e-4}

#: Cutoff criteria.
CRITERIA = ("relative", "absolute")
#: Reference levels of the relative criterion.
REFERENCES = ("envelope", "psd")
#: Relative criterion: power drop below the reference, dB.
DEFAULT_DROP_DB = 40.0
#: Absolute criterion: allowed residual ionospheric variance, m^2 ((1 mm)^2).
DEFAULT_VARIANCE_M2 = 1e-6
#: Shortest series (samples above the mask in the one-day series) analysed: 30 min at 12 s.
MIN_SERIES_SAMPLES = 150
#: Arcs shorter than this are dropped before the periodogram, s (the DF pipeline's default).
MIN_ARC_S = 1800.0
#: Default F10.7 solar flux, sfu (2019-2020 solar minimum level).
DEFAULT_F107_SFU = 70.0
#: Altitude node sets of the density integral (see :func:`altitude_nodes_km`).
ALT_RESOLUTIONS = ("fine", "coarse")
#: PyIRI models: classic URSI or CCIR foF2 maps, or the spherical-harmonics model.
IRI_MODELS = ("ursi", "ccir", "sh")
#: Arcs shorter than this after edge trimming are dropped (the DF isolation's default), s.
MIN_KEPT_S = 600.0
#: Lowest cutoff searched, Hz: the fit's trimming then removes 2.8 h at each arc end.
F_MIN_HZ = 1e-4
#: Default thin-shell height, km.
DEFAULT_SHELL_HEIGHT_KM = 350.0
#: Carrier frequencies by name, Hz.
FREQUENCIES_HZ = {
    "L1": F_L1_HZ,
    "L2": F_L2_HZ,
    "L5": F_L5_HZ,
    "E1": F_L1_HZ,
    "E5a": F_L5_HZ,
    "E5b": 1207.14e6,
}
#: Systems with a nominal constellation (:func:`psdbound.io.nominal.nominal_elements`),
#: the geometry of a cutoff run; a fit of another system takes the first (GPS).
NOMINAL_SYSTEMS = ("G", "E")
#: Line-of-sight integration methods.
METHODS = ("line-of-sight", "thin-shell")
