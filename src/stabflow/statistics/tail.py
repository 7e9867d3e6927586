"""Peaks-over-threshold tail rates with censored observations and profile-likelihood intervals.

One estimator serves the extremes step (rate of roll beyond x from declustered |roll| maxima) and
the split-time step (capsize rate = cluster rate x P(metric >= 1)). The data are N independent
cluster maxima observed over an exposure of T hours; each is either

* exact: the value y is known;
* left-censored: only y < c is known (a split-time bracket that never capsized: the metric lies
  below the value at the largest perturbation tried);
* right-censored: only y > c is known (a record that capsized: its roll exceeded the capsize angle).

Model (Davison & Smith 1990, "Models for exceedances over high thresholds", J. R. Stat. Soc. B 52; the Poisson-GPD form of peaks over
threshold): clusters occur as a Poisson process of rate lambda [1/h]; a cluster maximum exceeds the
threshold u with probability zeta; an exceedance's excess over u is generalized Pareto
(shape xi, scale sigma). The rate of maxima beyond x >= u is

    theta(x) = lambda * zeta * S(x - u; xi, sigma),   S(z) = (1 + xi z / sigma)^(-1/xi)  (exp(-z/sigma) at xi = 0).

Log-likelihood (each observation's probability under the model):

    N log(lambda) - lambda T
    + sum_exact,y<=u log(1 - zeta) + sum_exact,y>u [log zeta + log g(y - u)]
    + sum_left,c<=u log(1 - zeta) + sum_left,c>u log(1 - zeta S(c - u))
    + sum_right [log zeta + log S(c - u)]        (right-censored bounds c must be >= u)

Intervals are profile-likelihood intervals for theta (Coles 2001, "An Introduction to Statistical
Modeling of Extreme Values", Springer: profile likelihood, threshold models): the set of theta whose profile deviance
2 (l_max - l_p(theta)) is below the chi-square(1) quantile. They carry the Poisson count of
clusters, the exceedance probability and both GPD parameters (the extrapolation). The same interval
with the shape fixed at its estimate carries only the counts and the scale; the ratio of the two
log-widths is reported as the share of the uncertainty due to the shape (the extrapolation).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy import optimize, stats

from stabflow.statistics._kernels import _XI_ZERO, _logsf, _tail_loglik

#: shape range searched; xi < -1 makes the likelihood unbounded at the largest observation
XI_RANGE = (-1.0, 3.0)
#: |xi| below this is treated as the exponential limit
XI_ZERO = _XI_ZERO
#: how far below the estimate (a factor) the lower profile bound is searched before it is called 0
LOWER_SEARCH = 1e-12


def _quiet(fn):
    """Run ``fn`` with numpy floating-point warnings off: the optimisers probe parameters outside the
    support, where the log-likelihood is -inf by design."""
    @functools.wraps(fn)
    def wrapper(*a, **k):
        with np.errstate(all="ignore"):
            return fn(*a, **k)
    return wrapper


def gpd_logpdf(z: np.ndarray, xi: float, sigma: float) -> np.ndarray:
    """log g(z) of the GPD (location 0); -inf outside the support."""
    z = np.asarray(z, float)
    if abs(xi) < XI_ZERO:
        return -np.log(sigma) - z / sigma
    a = 1.0 + xi * z / sigma
    with np.errstate(divide="ignore", invalid="ignore"):
        out = -np.log(sigma) - (1.0 + 1.0 / xi) * np.log(a)
    return np.where((a > 0) & (z >= 0), out, -np.inf)


def gpd_logsf(z: np.ndarray, xi: float, sigma: float) -> np.ndarray:
    """log S(z) = log P(Z > z) of the GPD (location 0); -inf beyond the upper end point."""
    z = np.maximum(np.asarray(z, float), 0.0)
    if abs(xi) < XI_ZERO:
        return -z / sigma
    a = 1.0 + xi * z / sigma
    with np.errstate(divide="ignore", invalid="ignore"):
        out = -np.log(a) / xi
    return np.where(a > 0, out, -np.inf)


@dataclass
class TailData:
    """Cluster maxima of one sample and its exposure.

    Attributes
    ----------
    exact : values known exactly (cluster maxima) [any unit, the same as u and x].
    left : upper bounds c of left-censored maxima (y < c).
    right : lower bounds c of right-censored maxima (y > c).
    hours : exposure [h].
    """

    exact: np.ndarray
    hours: float
    left: np.ndarray = None
    right: np.ndarray = None

    def __post_init__(self):
        self.exact = np.asarray(self.exact, float)
        self.left = np.zeros(0) if self.left is None else np.asarray(self.left, float)
        self.right = np.zeros(0) if self.right is None else np.asarray(self.right, float)

    @property
    def n(self) -> int:
        """Number of clusters N."""
        return len(self.exact) + len(self.left) + len(self.right)


class _Likelihood:
    """The log-likelihood above, split into the parts that depend on lambda and on (zeta, xi, sigma)."""

    def __init__(self, data: TailData, u: float):
        self.u = float(u)
        self.T = float(data.hours)
        self.N = data.n
        e = data.exact
        self.exc = e[e > u] - u                      # exact exceedances
        self.n_below = int(np.sum(e <= u) + np.sum(data.left <= u))
        self.left = data.left[data.left > u] - u     # left-censored above u: below u or an excess < c - u
        if np.any(data.right < u):
            raise ValueError(f"right-censored maxima below the threshold u = {u:g}: only bounds >= u are modelled")
        self.right = data.right - u                  # right-censored: an exceedance with excess > c - u
        self.n_exc = len(self.exc) + len(self.right)  # certain exceedances

    def rest(self, zeta: float, xi: float, sigma: float) -> float:
        """Log-likelihood of the cluster maxima given N (everything but the Poisson count)."""
        if not (0.0 < zeta < 1.0 or (zeta == 1.0 and self.n_below == 0 and len(self.left) == 0)):
            return -np.inf
        if sigma <= 0 or not (XI_RANGE[0] <= xi <= XI_RANGE[1]):
            return -np.inf
        ll = _tail_loglik(self.exc, self.right, self.left, self.n_below, zeta, xi, sigma)
        return ll if np.isfinite(ll) else -np.inf

    def poisson(self, lam: float) -> float:
        """N log(lambda T) - lambda T (the constant log N! left out)."""
        if lam <= 0:
            return -np.inf if self.N > 0 else 0.0
        return self.N * np.log(lam * self.T) - lam * self.T if self.N else -lam * self.T


def _unpack(p):
    zeta = 1.0 / (1.0 + np.exp(-p[0]))
    return zeta, float(p[1]), float(np.exp(p[2]))


def _nm(f, p0):
    """Nelder-Mead minimum of f from p0 (tight tolerances, restarted once from its own optimum)."""
    best = optimize.minimize(f, p0, method="Nelder-Mead", options=dict(xatol=1e-7, fatol=1e-9, maxiter=4000))
    again = optimize.minimize(f, best.x, method="Nelder-Mead", options=dict(xatol=1e-8, fatol=1e-10, maxiter=4000))
    return again if again.fun <= best.fun else best


@dataclass
class TailFit:
    """Maximum-likelihood fit of the Poisson-GPD model (see module docstring)."""

    u: float
    lam: float      # cluster rate [1/h]
    zeta: float     # P(maximum > u)
    xi: float       # GPD shape
    sigma: float    # GPD scale
    loglik: float
    n: int          # clusters
    n_exceed: int   # certain exceedances (exact above u + right-censored)

    def rate(self, x: float) -> float:
        """theta(x) [1/h] at the estimate."""
        return float(self.lam * self.zeta * np.exp(gpd_logsf(x - self.u, self.xi, self.sigma)))


@_quiet
def fit(data: TailData, u: float, xi: float | None = None) -> TailFit:
    """Maximum-likelihood Poisson-GPD fit above ``u`` (shape fixed at ``xi`` if given).

    Raises ValueError with fewer than 3 exceedances (no GPD can be fitted)."""
    L = _Likelihood(data, u)
    if L.n_exc < 3:
        raise ValueError(f"tail fit above u = {u:g}: {L.n_exc} exceedances, at least 3 are needed")
    # start: zeta from the counts, (xi, sigma) from scipy's exact-data fit (moments if that fails)
    z0 = min(max(L.n_exc / max(L.N, 1), 1e-6), 1 - 1e-6)
    base = np.concatenate([L.exc, L.right]) if len(L.right) else L.exc
    try:
        c0, _, s0 = stats.genpareto.fit(base, floc=0.0)
    except (RuntimeError, ValueError, FloatingPointError):
        c0, s0 = 0.0, float(np.mean(base))
    c0 = float(np.clip(c0, -0.9, 2.5)) if xi is None else float(xi)
    s0 = float(s0) if np.isfinite(s0) and s0 > 0 else float(np.mean(base))
    if xi is None:
        f = lambda p: -L.rest(*_unpack(p))  # noqa: E731
        r = _nm(f, np.array([np.log(z0 / (1 - z0)), c0, np.log(s0)]))
        zeta, xh, sh = _unpack(r.x)
    else:
        f = lambda p: -L.rest(*_unpack([p[0], xi, p[1]]))  # noqa: E731
        r = _nm(f, np.array([np.log(z0 / (1 - z0)), np.log(s0)]))
        zeta, xh, sh = _unpack([r.x[0], xi, r.x[1]])
    lam = L.N / L.T
    return TailFit(float(u), lam, zeta, xh, sh, -float(r.fun) + L.poisson(lam), L.N, L.n_exc)


@dataclass
class RateInterval:
    """theta(x) with its profile-likelihood interval."""

    rate: float
    lower: float
    upper: float
    fit: TailFit
    level: float


@_quiet
def profile_interval(data: TailData, u: float, x: float, alpha: float = 0.05, xi: float | None = None,
                     fitted: TailFit | None = None) -> RateInterval:
    """theta(x) [1/h] and its (1 - alpha) profile-likelihood interval (shape fixed at ``xi`` if given).

    The profile log-likelihood l_p(theta) maximises over (zeta, xi, sigma) with lambda =
    theta / (zeta S(x - u)). Where the estimate is 0 (a bounded GPD ending below x) the lower bound
    is 0 and the upper bound is where the deviance of theta > 0 reaches the chi-square quantile; it
    is 0 too when even the smallest positive rate (the best fit whose end point reaches x) lies
    outside: the sample then rules out any rate at this level. With the shape fixed at a bounded
    estimate ending below x the interval is [0, 0] (no fixed-shape fit reaches x).
    """
    L = _Likelihood(data, u)
    f0 = fitted if fitted is not None else fit(data, u, xi)
    crit = stats.chi2.ppf(1 - alpha, 1)
    z = x - u
    free_shape = xi is None

    def unpack(p):
        return _unpack(p) if free_shape else _unpack([p[0], xi, p[1]])

    def nll(p, log_theta):
        zeta, c, s = unpack(p)
        lsf = _logsf(z, c, s)
        if lsf == -np.inf:
            return np.inf
        lam = np.exp(log_theta - np.log(zeta) - lsf)
        v = L.rest(zeta, c, s) + L.poisson(lam)
        return -v if np.isfinite(v) else np.inf

    def pack(zeta, c, s):
        return np.array([np.log(zeta / (1 - zeta)), c, np.log(s)]) if free_shape else \
            np.array([np.log(zeta / (1 - zeta)), np.log(s)])

    zeta_hat = min(f0.zeta, 1 - 1e-9)
    theta_hat = f0.rate(x)
    start = pack(zeta_hat, f0.xi, f0.sigma)
    if theta_hat <= 0:
        # bounded tail ending below x: a feasible start has its end point u - sigma / xi beyond x
        if not free_shape:
            return RateInterval(0.0, 0.0, 0.0, f0, 1 - alpha)
        c = -f0.sigma / (1.05 * z)
        start = pack(zeta_hat, max(c, XI_RANGE[0] + 1e-6), f0.sigma if c >= XI_RANGE[0] else -XI_RANGE[0] * 1.05 * z)
    cache = {"p": start}

    def deviance(log_theta):
        r = optimize.minimize(lambda p: nll(p, log_theta), cache["p"], method="Nelder-Mead",
                              options=dict(xatol=1e-6, fatol=1e-7, maxiter=2000))
        if np.isfinite(r.fun):
            cache["p"] = r.x
        return 2.0 * (f0.loglik + r.fun)

    def bound(log_from, step):
        """Walk from log_from in growing steps until the deviance passes crit, then bracket the
        root; -inf when the walk downwards passes LOWER_SEARCH, None when log_from is outside."""
        cache["p"] = start
        a, da = log_from, deviance(log_from)
        if da >= crit:
            return None
        for _ in range(60):
            b = a + step
            if step < 0 and b < log_from + np.log(LOWER_SEARCH):
                if deviance(log_from + np.log(LOWER_SEARCH)) < crit:
                    return -np.inf
                b = log_from + np.log(LOWER_SEARCH)
            db = deviance(b)
            if db >= crit:
                # bisection on the observed side of crit (warm starts make re-evaluation path-dependent)
                while abs(b - a) > 2e-3:
                    m = 0.5 * (a + b)
                    if deviance(m) >= crit:
                        b = m
                    else:
                        a = m
                return 0.5 * (a + b)
            a, da = b, db
            step *= 2.0
        return np.inf

    if theta_hat > 0:
        lt = np.log(theta_hat)
        lo = bound(lt, -0.25)
        hi = bound(lt, +0.25)
        # None: the optimiser did not reproduce the maximum at the estimate; the bound is unknown (NaN)
        return RateInterval(theta_hat, float(np.exp(lo)) if lo is not None else np.nan,
                            float(np.exp(hi)) if hi is not None else np.nan, f0, 1 - alpha)
    # theta_hat = 0: the profile at theta -> 0+ is the best bounded-beyond-x fit; walk upwards from a
    # small theta (the rate of one cluster in 10^6 exposures)
    lt0 = np.log(L.N / L.T * 1e-6) if L.N else np.log(1e-6 / L.T)
    hi = bound(lt0, +0.5)
    return RateInterval(0.0, 0.0, float(np.exp(hi)) if hi is not None else 0.0, f0, 1 - alpha)


def rate_estimate(data: TailData, u: float, x: float, alpha: float = 0.05, fixed_shape: bool = True,
                  fitted: TailFit | None = None) -> dict:
    """theta(x) [1/h] with its profile-likelihood interval and, unless ``fixed_shape`` is False, the
    interval with the shape fixed at its estimate (the same fit: the shape's estimate is the
    maximum). Returns dict(rate, lower, upper, lower_fixed, upper_fixed, xi, sigma, u, n_u); NaN
    entries (n_u 0) when fewer than 3 maxima exceed u."""
    out = dict(rate=np.nan, lower=np.nan, upper=np.nan, lower_fixed=np.nan, upper_fixed=np.nan, xi=np.nan,
               sigma=np.nan, u=float(u), n_u=0)
    try:
        full = profile_interval(data, u, x, alpha, fitted=fitted)
    except ValueError:
        return out
    out.update(rate=full.rate, lower=full.lower, upper=full.upper, xi=full.fit.xi, sigma=full.fit.sigma,
               n_u=full.fit.n_exceed)
    if fixed_shape:
        fx = profile_interval(data, u, x, alpha, xi=full.fit.xi, fitted=full.fit)
        out.update(lower_fixed=fx.lower, upper_fixed=fx.upper)
    return out


def consistent_with(rates, lower, upper, axis: int) -> np.ndarray:
    """True where every finite one of ``rates`` along ``axis`` lies in [lower, upper] (the reported
    threshold's interval, broadcast along ``axis``); thresholds without an estimate are left out."""
    rates = np.asarray(rates, float)
    with np.errstate(invalid="ignore"):
        inside = (rates >= lower) & (rates <= upper)
    return np.all(inside | np.isnan(rates), axis=axis)


def shape_share(lower, upper, lower_fixed, upper_fixed) -> np.ndarray:
    """Share of an interval's log-width due to the GPD shape (the extrapolation):
    1 - log(upper_fixed / lower_fixed) / log(upper / lower), clipped to [0, 1]; NaN where a width is
    infinite or zero (a lower bound of 0, or no tail)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        wf = np.log(np.asarray(upper, float) / np.asarray(lower, float))
        wx = np.log(np.asarray(upper_fixed, float) / np.asarray(lower_fixed, float))
        return np.where(np.isfinite(wf) & np.isfinite(wx) & (wf > 0), np.clip(1 - wx / wf, 0, 1), np.nan)
