"""Discretisation of a wave spectrum into a finite sum of components, one seaway per record.

Frequency bins span the 0.1 %-of-peak cut-offs (paper 004 eqs 23, 28). Methods:

``geometric``
    LAMP (paper 004 eqs 24-27): half of the bins below the modal frequency, half above, their widths
    growing geometrically away from it. The lower side uses the ratio ``ratio`` (LAMP: 1.25, meant
    for a few tens of components; with ~110 bins per side that ratio would make the bins at the peak
    1e-10 of the outer ones, so the default is milder); the upper side shares the width of the bin at
    the peak and solves its own ratio so that its bins end at the upper cut-off (eq. 28).
``equal_energy``
    Bins of equal spectral energy m0 / N.
``uniform``
    Equal widths (repeats itself after 2 pi / d_omega unless randomised).

Each component's amplitude is sqrt(2 S(w) dw) (eq. 29). With ``randomise`` the frequency is drawn
uniformly inside its bin, which removes the self-repetition of equally spaced sums; phases are
uniform on [-pi, pi). The random numbers of a record come only from (master seed, record index), so
any record can be regenerated on its own (the split-time step relies on this).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.optimize import brentq

from stabflow.waves.spectra import cutoff_frequencies, pierson_moskowitz_modal_frequency, spectrum

METHODS = ("geometric", "equal_energy", "uniform")


@dataclass(frozen=True)
class Seaway:
    """A long-crested irregular sea: spectrum (``kind``, Hs [m], modal period Tp [s], JONSWAP gamma)
    and its discretisation (``n_components``, ``method``, ``randomise``, geometric ``ratio``)."""

    kind: str
    hs: float
    tp: float | None = None
    gamma: float = 3.3
    n_components: int = 220
    method: str = "geometric"
    randomise: bool = True
    ratio: float = 1.01

    @classmethod
    def from_config(cls, cfg: dict) -> "Seaway":
        return cls(kind=cfg["spectrum"], hs=float(cfg["hs"]), tp=cfg.get("tp"), gamma=cfg.get("gamma", 3.3),
                   n_components=int(cfg.get("n_components", 220)), method=cfg.get("discretisation", "geometric"),
                   randomise=bool(cfg.get("randomise", True)), ratio=float(cfg.get("geometric_ratio", 1.01)))

    @property
    def density(self):
        return spectrum(self.kind, self.hs, self.tp, self.gamma)

    @property
    def modal_frequency(self) -> float:
        """w0 [rad/s]."""
        if self.kind == "pierson_moskowitz":
            return pierson_moskowitz_modal_frequency(self.hs)
        return 2 * np.pi / self.tp

    def edges(self) -> np.ndarray:
        """Bin edges (n_components + 1) [rad/s] (computed once per seaway)."""
        return self._edges

    @cached_property
    def _edges(self) -> np.ndarray:
        S, w0, n = self.density, self.modal_frequency, self.n_components
        lo, hi = cutoff_frequencies(S, w0)
        if self.method == "uniform":
            return np.linspace(lo, hi, n + 1)
        if self.method == "equal_energy":
            grid = np.linspace(lo, hi, 20001)
            cum = np.concatenate([[0.0], np.cumsum(0.5 * (S(grid[1:]) + S(grid[:-1])) * np.diff(grid))])
            return np.interp(np.linspace(0, cum[-1], n + 1), cum, grid)
        if self.method == "geometric":
            n1 = n // 2
            n2 = n - n1
            d = self.ratio
            # eq. 26: widths w1 d^m (m = 0 at the peak) add up to w0 - w_min
            w1 = (w0 - lo) * (d - 1) / (d**n1 - 1) if d != 1 else (w0 - lo) / n1
            below = w0 - w1 * np.cumsum(d ** np.arange(n1))
            # eq. 28: the upper ratio makes n2 bins of first width w1 reach w_max
            span = hi - w0
            if w1 * n2 >= span:
                d2 = 1.0
                w1u = span / n2
            else:
                # upper bracket kept below overflow of r^n2 (thousands of components)
                d2 = brentq(lambda r: w1 * (r**n2 - 1) / (r - 1) - span, 1 + 1e-12, min(10.0, np.exp(600.0 / n2)))
                w1u = w1
            above = w0 + w1u * np.cumsum(d2 ** np.arange(n2))
            above[-1] = hi
            below[-1] = lo
            return np.concatenate([below[::-1], [w0], above])
        raise ValueError(f"unknown discretisation {self.method!r}; choose one of {METHODS}")

    def components(self, seed: int, record: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(amplitude [m], frequency [rad/s], phase [rad]) of record ``record`` for master ``seed``."""
        e = self.edges()
        rng = np.random.default_rng([int(seed), int(record)])
        u = rng.random(len(e) - 1) if self.randomise else np.full(len(e) - 1, 0.5)
        phase = rng.uniform(-np.pi, np.pi, len(e) - 1)
        w = e[:-1] + u * np.diff(e)
        if self.method == "equal_energy":
            m0 = np.trapezoid(self.density(np.linspace(e[0], e[-1], 20001)), np.linspace(e[0], e[-1], 20001))
            amp = np.full(len(w), np.sqrt(2 * m0 / len(w)))
        else:
            amp = np.sqrt(2 * self.density(w) * np.diff(e))
        return amp, w, phase
