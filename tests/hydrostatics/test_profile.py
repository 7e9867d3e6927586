"""Deck edges (``stabflow.hydrostatics.profile``)."""

import types

import numpy as np

from stabflow.hydrostatics.profile import deck_edges


def _sections(contours):
    """A stand-in for ``Sections`` with the contours (y, z) given, one station each at x = 0, 1, ..."""
    n = max(len(y) for y, _ in contours)
    y = np.zeros((len(contours), n))
    z = np.zeros((len(contours), n))
    for i, (yc, zc) in enumerate(contours):
        y[i, :len(yc)], z[i, :len(zc)] = yc, zc
    return types.SimpleNamespace(x=np.arange(len(contours), dtype=float), n=np.array([len(c[0]) for c in contours]),
                                 y=y, z=z)


def test_deck_edge_above_a_bulb_wider_than_the_stem():
    """A bulbous bow's station (bulb 1.6 m wide at 1 m, stem 0.4 m wide up to the deck at 8 m) has its
    deck edge at the top of the stem, not on the bulb (the rule before took the bulb's widest point,
    below the waterline, and so a deck-edge immersion of 0 degree); a box section, a cambered deck
    (centreline higher) and a flared side keep theirs at the side's top."""
    bulb = ([0.0, 1.2, 1.6, 1.2, 0.4, 0.4, 0.4, 0.0], [0.0, 0.3, 1.0, 1.8, 2.5, 5.0, 8.0, 8.0])
    box = ([0.0, 5.0, 5.0, 0.0], [0.0, 0.0, 6.0, 6.0])
    camber = ([0.0, 5.0, 5.0, 2.0, 0.0], [0.0, 0.0, 6.0, 6.1, 6.15])
    flare = ([0.0, 3.0, 4.0, 5.5, 0.0], [0.0, 0.0, 3.0, 7.0, 7.0])
    e = deck_edges(_sections([bulb, box, camber, flare]))
    np.testing.assert_array_equal(e[:, 1:], [[0.4, 8.0], [5.0, 6.0], [5.0, 6.0], [5.5, 7.0]])
