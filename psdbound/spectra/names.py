"""The spectra stage's choices and defaults, in a module that imports nothing heavy.

Option checks (``BoundOptions``, ``SpectraOptions``, the verdict and every
command's ``--help``) need these names but not numpy's or scipy's spectral
code: importing them from here keeps ``psdbound fit --help`` fast.
"""

from __future__ import annotations

__all__ = ["METHODS", "OBJECTIVES", "POLICIES", "RULES", "TAU_MAX_S"]

#: PSD estimators accepted by :func:`psdbound.spectra.estimate_psd`.
METHODS: tuple[str, ...] = ("blackman-tukey", "welch", "multitaper")
#: Tightness objectives of the bound: total variance, or area under the PSD.
OBJECTIVES = ("variance", "area")
#: How the data to bound are formed: pooled confidence limits or the thesis's envelope.
RULES = ("pooled", "envelope")
#: Default prior upper limit of the multipath time constant, seconds.
TAU_MAX_S = 900.0
#: What to do when the data do not bound tau above: use the prior, or refuse.
POLICIES = ("prior", "refuse")
