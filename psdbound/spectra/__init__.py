"""Spectra and bounds: PSD estimators, the GMRP + white-noise model, bound fitting."""

from __future__ import annotations

from psdbound.spectra.models import gm_acf, gm_psd_continuous, gm_psd_sampled, white_psd

__all__ = ["gm_acf", "gm_psd_continuous", "gm_psd_sampled", "white_psd"]
