"""Figures, one module per pipeline step; every axis carries units. Figures are matplotlib PNG
files written atomically under ``results/``."""
