"""Stability in waves (paper 002): quasi-static wave pass (GM and GZ as a crest passes) and the
early-stage assessment metric C."""
