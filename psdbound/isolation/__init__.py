"""Multipath isolation: dual-frequency (DF) and dual-antenna (DA) pipelines."""

from __future__ import annotations

from psdbound.isolation.series import ArcView, MultipathSeries

__all__ = ["ArcView", "MultipathSeries"]
