"""The ship's profile: deck-edge points, the angle of deck-edge immersion, and the lateral
(profile) areas above and below the waterline with their centroids (the weather criterion's
windage lever, IS Code 2.3.2, when the ship config asks for the hull's own windage)."""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from stabflow.geometry import Sections
from stabflow.hydrostatics.statics import equilibrium


def deck_edges(sec: Sections) -> np.ndarray:
    """Deck-edge point (x, y, z) of every station [m]: among the contour points in the upper half of
    the section's height, those at least half as far out as the widest of them, the highest (the
    outermost of equal height). (The upper half keeps a bulbous bow's station, whose bulb is wider
    than the stem above it, from taking a point on the bulb for its deck edge. A wave-piercing bow
    whose sides close to the centreline above a knuckle, as the DTMB 5415 tumblehome's forward of
    x = 59 m, gives the knuckle: 0.35 m above that ship's waterline, immersed at 7.7 degree of heel.)"""
    out = np.empty((len(sec.x), 3))
    for i in range(len(sec.x)):
        n = sec.n[i]
        y, z = sec.y[i, :n], sec.z[i, :n]
        upper = z >= 0.5 * (z.min() + z.max())
        cand = np.flatnonzero(upper & (y >= 0.5 * y[upper].max()))
        j = cand[np.lexsort((-y[cand], -z[cand]))[0]]
        out[i] = sec.x[i], y[j], z[j]
    return out


def _deck_margin(edges: np.ndarray, phi: float, h: float, theta: float) -> float:
    """Smallest height of a starboard deck-edge point above the waterline at heel phi [rad] (roll
    positive starboard down, y to port), trim theta [rad], heave h [m] (the kernels' convention:
    a body point is wet when cos(theta)(sin(phi) y + cos(phi) z) <= sin(theta) x - h)."""
    x, y, z = edges.T
    return float((math.cos(theta) * (-math.sin(phi) * y + math.cos(phi) * z) - (math.sin(theta) * x - h)).min())


def deck_edge_immersion(sec: Sections, volume: float, lcg: float, kg: float, step_deg: float = 1.0,
                        max_deg: float = 90.0) -> float:
    """Heel [degree] at which the first deck-edge point along the length reaches the calm waterline
    (free trim); NaN when none does up to ``max_deg``."""
    edges = deck_edges(sec)

    def margin(phi_deg):
        h, th, _ = equilibrium(sec, volume, lcg, kg, heel=math.radians(phi_deg))
        return _deck_margin(edges, math.radians(phi_deg), h, th)

    prev_phi, prev = 0.0, margin(0.0)
    if prev <= 0:
        return 0.0
    for phi in np.arange(step_deg, max_deg + 1e-9, step_deg):
        m = margin(phi)
        if m <= 0:
            return brentq(margin, prev_phi, phi, xtol=1e-8)
        prev_phi, prev = phi, m
    return math.nan


def lateral_areas(sec: Sections, volume: float, lcg: float, kg: float) -> dict:
    """Profile areas of the upright ship at its equilibrium [m^2] and their centroid heights above
    the baseline [m]: above the waterline to the deck edge (the hull's own windage, no
    superstructure) and below it (the underwater lateral area)."""
    h, th, _ = equilibrium(sec, volume, lcg, kg)
    edges = deck_edges(sec)
    zw = (math.sin(th) * sec.x - h) / math.cos(th)  # body height of the waterline at each station
    keel = np.array([sec.z[i, : sec.n[i]].min() for i in range(len(sec.x))])
    top = edges[:, 2]
    wet = np.clip(zw, keel, top) - keel
    dry = top - np.clip(zw, keel, top)
    a_wet, a_dry = float((wet * sec.dx).sum()), float((dry * sec.dx).sum())
    z_wet = float((wet * sec.dx * (keel + 0.5 * wet)).sum() / a_wet) if a_wet > 0 else math.nan
    z_dry = float((dry * sec.dx * (top - 0.5 * dry)).sum() / a_dry) if a_dry > 0 else math.nan
    return {"area_above": a_dry, "z_above": z_dry, "area_below": a_wet, "z_below": z_wet}
