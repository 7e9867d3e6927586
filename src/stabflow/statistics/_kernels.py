"""Numba kernels (private) of the statistics package: the Poisson-GPD log-likelihood sums."""

from __future__ import annotations

import math

from numba import njit

#: |xi| below this is the exponential limit (the same as ``tail.XI_ZERO``)
_XI_ZERO = 1e-7


@njit(cache=True, inline="always")
def _logsf(z, xi, sigma):
    """log S(z) of the GPD (location 0); -inf beyond the end point."""
    if z < 0.0:
        z = 0.0
    if abs(xi) < _XI_ZERO:
        return -z / sigma
    a = 1.0 + xi * z / sigma
    if a <= 0.0:
        return -math.inf
    return -math.log(a) / xi


@njit(cache=True)
def _tail_loglik(exc, right, left, n_below, zeta, xi, sigma):
    """Log-likelihood of cluster maxima given their number (``tail._Likelihood.rest``): n_below
    maxima below u, exact excesses ``exc``, right-censored excesses (> c) ``right`` and left-censored
    bounds above u (excess < c) ``left``."""
    ll = 0.0
    if n_below > 0:
        ll += n_below * math.log1p(-zeta)
    n_exc = len(exc) + len(right)
    if n_exc > 0:
        ll += n_exc * math.log(zeta)
    ls = math.log(sigma)
    for z in exc:
        if abs(xi) < _XI_ZERO:
            ll += -ls - z / sigma
        else:
            a = 1.0 + xi * z / sigma
            if a <= 0.0 or z < 0.0:
                return -math.inf
            ll += -ls - (1.0 + 1.0 / xi) * math.log(a)
    for z in right:
        ll += _logsf(z, xi, sigma)
    for z in left:
        ll += math.log1p(-zeta * math.exp(_logsf(z, xi, sigma)))
    return ll
