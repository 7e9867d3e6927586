"""Time-domain 3-DOF (heave, roll, pitch) model with volume-based FK + HS forces (paper 000)."""

from stabflow.dynamics.model import Coefficients, coefficients, simulate, stiffness

__all__ = ["Coefficients", "coefficients", "simulate", "stiffness"]
