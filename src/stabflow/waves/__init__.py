"""Seaway: spectra and their moments (irregular-wave synthesis builds on these)."""

from stabflow.waves.spectra import bretschneider, cutoff_frequencies, jonswap, pierson_moskowitz, spectral_moments, spectrum

__all__ = ["bretschneider", "jonswap", "pierson_moskowitz", "spectrum", "cutoff_frequencies", "spectral_moments"]
