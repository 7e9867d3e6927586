"""Direct stability assessment (DSA): long-term failure rate over a wave scatter table.

A *cell* is one operating condition: significant wave height Hs [m], zero-crossing period Tz [s],
heading [degree, 0 following seas, 180 head seas] and speed [m/s]. Its probability is
p_i = P(Hs, Tz) P(heading) P(speed). For every cell the assessment gives a failure rate r_i [1/s]:

``counted``
    k_i failures (declustered exceedances of a roll angle) counted in T_i seconds of simulation;
    r_i = k_i / T_i, k_i Poisson.
``extrapolated``
    no failure counted; the rate and its interval (lo_i, hi_i) come from another method (a tail fit).
``screened``
    shown by a cheaper method to be negligible; an upper bound hi_i (and lo_i, usually 0).

The long-term rate is R = sum_i p_i r_i per second, reported per year (365.25 d).

Interval
    The counted part sum_i w_i k_i, w_i = p_i / T_i, is a weighted sum of Poisson counts; its
    interval is the gamma interval of Fay & Feuer (1997) (:func:`fay_feuer_interval`), which reduces
    to the exact Garwood interval when the weights are equal. The extrapolated and screened parts
    add their own bounds, sum_i p_i lo_i and sum_i p_i hi_i. This addition is conservative in width:
    it assumes every cell's error takes its extreme value at once, with no cancellation between
    independent cells or with the counted part. It is not a formal joint confidence level: the
    total covers the true rate at least whenever every part's interval covers its own (by
    Bonferroni, with probability at least 1 - the sum of the parts' alphas).

Clustered counts
    Fay-Feuer assumes Poisson counts, which declustered failures are meant to be. For counts of
    clustered events (Var k = phi E k) ``dispersion`` phi gives the same interval for k / phi
    events of weight phi w (quasi-Poisson); phi = 1 is the default.

Exact verification
    :class:`LinearRoll`, linear 1-DOF roll in long-crested beam waves (the Froude-Krylov small-ship
    limit: the wave moment equals the restoring moment of the wave slope), is a zero-mean
    stationary Gaussian process whose up-crossing rate Rice's formula gives exactly
    (:func:`rice_upcrossing_rate`). :func:`dsa_verification` simulates it over the IACS Rec. 34
    cells that were read (wave slope synthesized from random-phase components, the project's RK4
    1-DOF kernel with a linear restoring table), counts every up-crossing of a roll level,
    aggregates the counts with :func:`long_term_rate` and compares with the exact long-term sum.
    Raw up-crossings of lightly damped roll come in groups (dispersion about 2 at the default
    settings), so the verification gives the interval both as Poisson and with the dispersion
    measured from independent records of each cell. Measured at the defaults (level 30 deg, w0 0.5
    rad/s, zeta 0.05, 3 h per cell in 6 records, 197 cells, about 2 s): the estimate over 120 seeds
    is 0.991 +- 0.004 (standard error) of the exact rate with a scatter of 4.8 % per run (a bias of
    about 1 %, if any, from the finite number of components, is far below that); the Poisson
    interval covered the exact rate in 95 % of the seeds, the one with the dispersion in all.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import xarray as xr
from scipy import stats
from scipy.integrate import simpson

from stabflow.constants import G

#: seconds in one year of 365.25 days [s]
SECONDS_PER_YEAR = 365.25 * 86400.0

#: the kinds of cell rates, in the order of the split
METHODS = ("counted", "extrapolated", "screened")

#: random streams of the verification: phases of a cell (with the master seed and the cell index)
#: and the component frequencies shared by the cells of one run (with the master seed)
VERIFICATION_STREAM = 34
FREQUENCY_STREAM = 35


# --------------------------------------------------------------------------------------------------
# scatter table
# --------------------------------------------------------------------------------------------------

def _var(dims, data, units: str, long_name: str):
    """(dims, data, attrs) of a Dataset variable with its units and long name."""
    return dims, data, {"units": units, "long_name": long_name}


def _number(x) -> float | None:
    try:
        return float(x)
    except (TypeError, ValueError):
        return None


def scatter_probabilities(table: dict) -> xr.DataArray:
    """P(Hs, Tz) of a scatter table as parsed from ``resources/criteria/iacs_rec34_scatter.yaml``.

    Parameters
    ----------
    table : the parsed file: ``tz_centres`` [s], ``hs_rows`` (each ``{hs [m], counts}``, counts a
        list aligned with ``tz_centres`` with nulls where not read, or null for a row not read) and
        ``total`` (the nominal total of occurrences, a number or ``{value: ...}``).

    Returns
    -------
    xarray.DataArray (hs, tz) [-]: count / nominal total for every cell that was read, NaN (never 0)
    for a cell whose count was not read, so that a caller cannot drop it silently. The
    probabilities are not renormalised: they add up to ``covered_fraction``.
    Attributes: ``covered_fraction`` (sum of the read counts / nominal total), ``missing_rows``
    (list of str: every row or part of a row not read, with the file's note), ``total``.
    Rows whose Hs is not a number (e.g. "5.5 and above") have no coordinate and appear only in
    ``missing_rows``.
    """
    tz = np.asarray(table["tz_centres"], float)
    total = table["total"]
    total = float(total["value"] if isinstance(total, dict) else total)
    hs, rows, missing = [], [], []
    for row in table["hs_rows"]:
        h = _number(row.get("hs"))
        note = str(row.get("missing", "")).strip()
        counts = row.get("counts")
        if h is None:
            missing.append(f"Hs {row.get('hs')} m: not read" + (f" ({note})" if note else ""))
            continue
        if counts is None:
            counts = [None] * len(tz)
        if len(counts) != len(tz):
            raise ValueError(f"scatter table: row Hs {h:g} m has {len(counts)} counts for {len(tz)} Tz columns")
        c = np.array([np.nan if v is None else float(v) for v in counts])
        if np.isnan(c).any():
            lost = tz[np.isnan(c)]
            what = "not read" if np.isnan(c).all() else f"Tz {', '.join(f'{t:g}' for t in lost)} s not read"
            missing.append(f"Hs {h:g} m: {what}" + (f" ({note})" if note else ""))
        hs.append(h)
        rows.append(c)
    counts = np.array(rows).reshape(len(hs), len(tz))
    p = xr.DataArray(counts / total, dims=("hs", "tz"),
                     coords={"hs": _var("hs", np.array(hs), "m", "significant wave height (bin centre)"),
                             "tz": _var("tz", tz, "s", "zero up-crossing period (bin centre)")},
                     name="probability")
    p.attrs.update(units="1", long_name="probability of the sea state (count / nominal total; NaN: not read)",
                   covered_fraction=float(np.nansum(counts) / total), missing_rows=missing, total=total)
    return p


# --------------------------------------------------------------------------------------------------
# aggregation
# --------------------------------------------------------------------------------------------------

def fay_feuer_interval(k, w, alpha: float = 0.05, dispersion=1.0) -> tuple[float, float, float]:
    """Interval of sum_i w_i E[k_i] from independent Poisson counts ``k`` and weights ``w`` > 0.

    Fay, M. P. & Feuer, E. J. (1997), "Confidence intervals for directly standardized rates: a method
    based on the gamma distribution", Statistics in Medicine 16:791-801. With y = sum w k,
    v = sum w^2 k and w_M = max w (over all cells, those with k = 0 included):

        lower = Gamma^-1(alpha / 2; shape y^2 / v, scale v / y)                   (0 when y = 0)
        upper = Gamma^-1(1 - alpha / 2; shape (y + w_M)^2 / (v + w_M^2), scale (v + w_M^2) / (y + w_M))

    Equal weights w give w times the Garwood interval of the total count.

    ``dispersion`` phi >= 1 (a number or one per cell) is for overdispersed counts (clustered
    events, Var k = phi E k): the same interval of k / phi "independent events" of weight w phi,
    i.e. v = sum w^2 phi k and w_M = max w phi (quasi-Poisson; phi = 1 is Fay & Feuer's interval).
    Returns (y, lower, upper) in the units of w times a count (no cells: zeros).
    """
    k = np.asarray(k, float)
    if k.size == 0:
        return 0.0, 0.0, 0.0
    w = np.asarray(w, float)
    phi = np.broadcast_to(np.asarray(dispersion, float), k.shape)
    y = float(np.sum(w * k))
    v = float(np.sum(w**2 * phi * k))
    wm = float(np.max(w * phi))
    lo = float(stats.gamma.ppf(alpha / 2, y**2 / v, scale=v / y)) if y > 0 else 0.0
    hi = float(stats.gamma.ppf(1 - alpha / 2, (y + wm) ** 2 / (v + wm**2), scale=(v + wm**2) / (y + wm)))
    return y, lo, hi


def count_dispersion(record_counts, weights) -> tuple[float, int]:
    """Dispersion Var k / E k of the cells' counts, from each cell's records: phi = sum_i w_i^2 s_i^2 /
    sum_i w_i^2 mean_i (s_i^2 and mean_i the sample variance and mean of cell i's record counts, w_i
    its weight in the aggregate, e.g. p_i / T_i: the aggregate's own variance ratio), over the cells
    with two or more records and a count. Returns (phi, degrees of freedom sum (n_i - 1)); (NaN, 0)
    without such cells."""
    num = den = 0.0
    dof = 0
    for k, w in zip(record_counts, np.broadcast_to(np.asarray(weights, float), (len(record_counts),))):
        k = np.asarray(k, float)
        if len(k) >= 2 and k.sum() > 0:
            num += w**2 * k.var(ddof=1)
            den += w**2 * k.mean()
            dof += len(k) - 1
    return (num / den, dof) if dof else (float("nan"), 0)


def _check_cells(cells: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    p = np.asarray(cells["probability"].values, float)
    method = np.asarray(cells["method"].values).astype(str)
    bad = ~np.isfinite(p) | (p < 0)
    if bad.any():
        raise ValueError(f"long_term_rate: cells {np.nonzero(bad)[0].tolist()} have no valid probability "
                         "(NaN: a scatter cell that was not read; drop it explicitly and report the coverage)")
    unknown = sorted(set(method) - set(METHODS))
    if unknown:
        raise ValueError(f"long_term_rate: unknown method {unknown}; use one of {METHODS}")
    cnt = method == "counted"
    if cnt.any():
        k = np.asarray(cells["failures"].values, float)[cnt]
        T = np.asarray(cells["exposure"].values, float)[cnt]
        if not (np.all(np.isfinite(k)) and np.all(k >= 0) and np.all(k == np.round(k))):
            raise ValueError("long_term_rate: counted cells need a failure count >= 0")
        if not (np.all(np.isfinite(T)) and np.all(T > 0)):
            raise ValueError("long_term_rate: counted cells need an exposure > 0 s")
    other = ~cnt
    if other.any():
        lo, r, hi = (np.asarray(cells[v].values, float)[other] for v in ("rate_lo", "rate", "rate_hi"))
        if not np.all(np.isfinite(np.stack([lo, r, hi]))):
            raise ValueError("long_term_rate: extrapolated and screened cells need finite rate_lo, rate, rate_hi")
        if not np.all((0 <= lo) & (lo <= r) & (r <= hi)):
            raise ValueError("long_term_rate: extrapolated and screened cells need 0 <= rate_lo <= rate <= rate_hi")
    return p, method


def long_term_rate(cells: xr.Dataset, alpha: float = 0.05, dispersion: float = 1.0) -> xr.Dataset:
    """Long-term failure rate sum_i p_i r_i per year, with its interval and each cell's contribution.

    Parameters
    ----------
    cells : Dataset with dimension ``cell`` and variables
        ``probability`` [-] (p_i; NaN raises: an unread scatter cell must be dropped explicitly),
        ``method`` (str: "counted", "extrapolated" or "screened"),
        ``failures`` [-] (counted cells: k_i >= 0; others -1 or NaN),
        ``exposure`` [s] (counted cells: T_i > 0),
        ``rate_lo``, ``rate``, ``rate_hi`` [1/s] (extrapolated and screened cells; ignored for counted).
        Other coordinates (hs, tz, heading, speed) are carried through.
    alpha : 1 - confidence level of the interval.
    dispersion : Var k / E k of the counted cells' counts (1: Poisson, the DSA's declustered failures;
        > 1 for clustered events, see :func:`fay_feuer_interval`).

    Returns
    -------
    xarray.Dataset with
        ``rate``, ``rate_lo``, ``rate_hi`` [1/year]: the long-term rate and its interval (counted part
        by Fay & Feuer 1997, plus the bounds of the other parts: conservative, see the module notes);
        ``cell_rate``, ``cell_rate_lo``, ``cell_rate_hi`` (cell) [1/s]: each cell's rate (counted:
        k / T with the Garwood interval of :func:`stabflow.statistics.splittime.poisson_interval`);
        ``contribution`` (cell) [1/year]: p_i r_i; ``share`` (cell) [-]: its fraction of the total;
        ``part_rate``, ``part_rate_lo``, ``part_rate_hi``, ``part_share`` (part) [1/year, -]: the split
        into counted / extrapolated / screened cells;
        ``ff_y``, ``ff_v``, ``ff_w_max``: the Fay-Feuer sums y = sum w k [1/s], v = sum w^2 k
        [1/s^2] and max w [1/s], w = p / T over the counted cells.
    """
    from stabflow.statistics.splittime import poisson_interval

    p, method = _check_cells(cells)
    dispersion = float(dispersion)
    if not dispersion > 0:
        raise ValueError(f"long_term_rate: dispersion {dispersion} must be > 0")
    n = len(p)
    cnt = method == "counted"
    r = np.full(n, np.nan)
    rlo = np.full(n, np.nan)
    rhi = np.full(n, np.nan)
    k = np.asarray(cells["failures"].values, float) if "failures" in cells else np.full(n, np.nan)
    T = np.asarray(cells["exposure"].values, float) if "exposure" in cells else np.full(n, np.nan)
    for i in np.nonzero(cnt)[0]:
        r[i], rlo[i], rhi[i] = poisson_interval(int(k[i]), T[i], alpha)  # per second: T in s
    for v, out in (("rate_lo", rlo), ("rate", r), ("rate_hi", rhi)):
        if (~cnt).any():
            out[~cnt] = np.asarray(cells[v].values, float)[~cnt]
    y, ff_lo, ff_hi = fay_feuer_interval(k[cnt], p[cnt] / T[cnt], alpha, dispersion)
    contrib = p * r
    parts = np.zeros((3, len(METHODS)))  # (rate, lo, hi) x part, per second
    parts[:, 0] = (y, ff_lo, ff_hi)
    for j, m in enumerate(METHODS[1:], start=1):
        sel = method == m
        parts[:, j] = (np.sum(p[sel] * r[sel]), np.sum(p[sel] * rlo[sel]), np.sum(p[sel] * rhi[sel]))
    total = parts[0].sum()
    yr = SECONDS_PER_YEAR
    with np.errstate(invalid="ignore", divide="ignore"):
        share = contrib / total if total > 0 else np.zeros(n)
        pshare = parts[0] / total if total > 0 else np.zeros(len(METHODS))
    w = p[cnt] / T[cnt]
    cell_coords = {c: cells.coords[c] for c in cells.coords if cells.coords[c].dims == ("cell",)}

    ds = xr.Dataset(
        {
            "rate": _var((), total * yr, "1/year", "long-term failure rate sum p_i r_i"),
            "rate_lo": _var((), parts[1].sum() * yr, "1/year", "lower bound of the long-term rate"),
            "rate_hi": _var((), parts[2].sum() * yr, "1/year", "upper bound of the long-term rate"),
            "method": ("cell", method.astype(object), {"long_name": "how the cell's rate was obtained"}),
            "probability": _var("cell", p, "1", "probability of the cell"),
            "cell_rate": _var("cell", r, "1/s", "failure rate of the cell"),
            "cell_rate_lo": _var("cell", rlo, "1/s", "lower bound of the cell's rate (counted: Garwood)"),
            "cell_rate_hi": _var("cell", rhi, "1/s", "upper bound of the cell's rate (counted: Garwood)"),
            "contribution": _var("cell", contrib * yr, "1/year", "p_i r_i, the cell's contribution"),
            "share": _var("cell", share, "1", "the cell's share of the long-term rate"),
            "part_rate": _var("part", parts[0] * yr, "1/year", "long-term rate of the cells of each kind"),
            "part_rate_lo": _var("part", parts[1] * yr, "1/year", "lower bound of the part (counted: Fay-Feuer)"),
            "part_rate_hi": _var("part", parts[2] * yr, "1/year", "upper bound of the part (counted: Fay-Feuer)"),
            "part_share": _var("part", pshare, "1", "the part's share of the long-term rate"),
            "ff_y": _var((), y, "1/s", "Fay-Feuer y = sum w_i k_i, w_i = p_i / T_i (counted cells)"),
            "ff_v": _var((), float(np.sum(w**2 * k[cnt])), "1/s2", "Fay-Feuer v = sum w_i^2 k_i (without dispersion)"),
            "ff_w_max": _var((), float(np.max(w)) if w.size else 0.0, "1/s", "Fay-Feuer w_M = max w_i"),
        },
        coords={**cell_coords, "part": ("part", list(METHODS), {"long_name": "kind of cell rate"})},
        attrs={"alpha": alpha, "seconds_per_year": yr, "count_dispersion": dispersion,
               "interval": "counted cells: Fay & Feuer (1997) gamma interval of a weighted Poisson sum; "
                           "extrapolated and screened cells: their bounds added (conservative in width, "
                           "no joint confidence level)"},
    )
    return ds


# --------------------------------------------------------------------------------------------------
# Rice
# --------------------------------------------------------------------------------------------------

def moments(omega, S) -> tuple[float, float]:
    """(m0, m2) of a one-sided spectrum ``S`` on the grid ``omega`` [rad/s] (Simpson's rule)."""
    w = np.asarray(omega, float)
    s = np.asarray(S, float)
    return float(simpson(s, x=w)), float(simpson(w**2 * s, x=w))


def rice_rate(m0: float, m2: float, level: float) -> float:
    """Up-crossing rate [1/s] of ``level`` by a zero-mean stationary Gaussian process with spectral
    moments m0, m2: Rice's formula nu+(a) = (1 / 2 pi) sqrt(m2 / m0) exp(-a^2 / (2 m0)) (0 for a
    process without variance)."""
    if not m0 > 0:
        return 0.0
    return float(np.sqrt(m2 / m0) / (2 * np.pi) * np.exp(-level**2 / (2 * m0)))


def rice_log10_rate(m0: float, m2: float, level: float) -> float:
    """log10 of :func:`rice_rate` computed without exp(), so that a rate far below the smallest
    double (a calm sea state's Gaussian tail) keeps its order of magnitude instead of underflowing
    to 0; -inf for a process without variance (m0 = 0), NaN for NaN moments, as :func:`rice_rate`."""
    if math.isnan(m0) or math.isnan(m2):
        return math.nan
    if not m0 > 0 or not m2 > 0:
        return -math.inf  # no variance, or no up-crossings (m2 = 0): rice_rate's 0
    return float((0.5 * math.log(m2 / m0) - math.log(2 * math.pi) - level**2 / (2 * m0)) / math.log(10.0))


def rice_upcrossing_rate(omega, S, level: float) -> float:
    """Up-crossing rate [1/s] of ``level`` by a zero-mean stationary Gaussian process of one-sided
    spectral density ``S`` [unit^2 s/rad] on the grid ``omega`` [rad/s] (increasing; it must cover
    the spectrum): :func:`rice_rate` with the moments of :func:`moments`."""
    return rice_rate(*moments(omega, S), level)


# --------------------------------------------------------------------------------------------------
# exact verification model
# --------------------------------------------------------------------------------------------------

@functools.lru_cache(maxsize=None)
def tz_over_tm() -> float:
    """Tz / Tm of the Bretschneider spectrum from its own moments, Tz = 2 pi sqrt(m0 / m2) (quadrature
    at Tm = 2 pi, i.e. modal frequency 1 rad/s; m2 converges, its w^-3 tail beyond 10^4 rad/s is
    below 1e-8 of it)."""
    from stabflow.waves.spectra import bretschneider, spectral_moments

    S = lambda w: bretschneider(w, 1.0, 2 * np.pi)  # noqa: E731
    lo = spectral_moments(S, 0.1, 1.0, orders=(0, 2))
    hi = spectral_moments(S, 1.0, 1e4, orders=(0, 2))
    return float(np.sqrt((lo[0] + hi[0]) / (lo[2] + hi[2])))


def bretschneider_tz(omega, hs: float, tz: float):
    """Two-parameter Bretschneider (ITTC) spectrum [m^2 s] for Hs [m] and zero-crossing period Tz [s]
    (:func:`stabflow.waves.spectra.bretschneider` at the modal period Tm = Tz / (Tz / Tm), the ratio
    from the spectrum's own moments)."""
    from stabflow.waves.spectra import bretschneider

    return bretschneider(omega, hs, tz / tz_over_tm())


def band_spectrum(omega, hs: float, tz: float, band: tuple[float, float] | None = None) -> np.ndarray:
    """Bretschneider spectrum in (Hs [m], Tz [s]) on ``omega`` [rad/s] [m^2 s], zero outside the band
    where it is above 1e-3 of its peak: the band of the ensembles' seaways (paper 004 eqs 23, 28;
    :func:`stabflow.waves.spectra.cutoff_frequencies`); ``band`` that band when already found
    (:func:`spectrum_band`)."""
    w = np.asarray(omega, float)
    lo, hi = band or spectrum_band(hs, tz)
    return np.where((w >= lo) & (w <= hi), bretschneider_tz(w, hs, tz), 0.0)


def spectrum_band(hs: float, tz: float) -> tuple[float, float]:
    """(lowest, highest) frequency [rad/s] where the Bretschneider spectrum in (Hs, Tz) is above
    1e-3 of its peak."""
    from stabflow.waves.spectra import cutoff_frequencies

    return cutoff_frequencies(lambda w: bretschneider_tz(w, hs, tz), 2 * np.pi * tz_over_tm() / tz)


@dataclass(frozen=True)
class LinearRoll:
    """Linear 1-DOF roll in long-crested beam waves at zero speed (Froude-Krylov small-ship limit):

        phi'' + 2 zeta w0 phi' + w0^2 phi = w0^2 alpha(t),   alpha = k eta (wave slope, k = w^2 / g),

    i.e. the wave moment per unit slope equals the restoring moment per radian. Roll is a zero-mean
    Gaussian process with the response spectrum |H|^2 S_alpha, H = w0^2 / (w0^2 - w^2 + 2 i zeta w0 w),
    S_alpha = (w^2 / g)^2 S_eta, S_eta the Bretschneider spectrum in (Hs, Tz).

    The sea of the model is that spectrum on the band [w_min, w_max]: the band is part of the model's
    definition, so the exact rate and the simulation describe the same process (the time step cannot
    resolve components far beyond w_max; :meth:`band_loss` gives what the band leaves out of the
    unbounded spectrum's m0 and m2).

    Simulation: the band is cut into bins whose density is 1 / dw_max + (|H|^2 / max |H|^2) / dw_min,
    fine (dw_min) across the resonance and at most dw_max wide elsewhere, so that the roll variance
    is spread over some hundreds of components even in the narrow resonance peak (a sum of N
    fixed-amplitude random-phase components has excess kurtosis -1.5 sum a^4 / (sum a^2)^2, which
    would thin the tail that Rice's formula counts). One component per bin, its frequency uniform in
    the bin (no repetition of the record; shared by the records of one run), its phase uniform.

    Attributes
    ----------
    w0 : natural roll frequency [rad/s].
    zeta : damping ratio [-].
    w_min, w_max : band of the wave spectrum [rad/s].
    dw_min, dw_max : bin width at the resonance and the largest bin width [rad/s].
    dt : time step of the simulation [s].
    warmup : simulated seconds from rest before counting [s] (the transient decays as exp(-zeta w0 t)).
    fine : sub-intervals per bin of the spectrum's quadrature (even: Simpson per bin).
    """

    w0: float = 0.5
    zeta: float = 0.05
    w_min: float = 0.05
    w_max: float = 3.0
    dw_min: float = 0.00025
    dw_max: float = 0.01
    dt: float = 0.2
    warmup: float = 300.0
    fine: int = 4

    # ---- frequency domain ----
    def transfer(self, omega) -> np.ndarray:
        """Complex roll per unit wave slope H(w) [rad/rad] at frequencies ``omega`` [rad/s]."""
        w = np.asarray(omega, float)
        return self.w0**2 / (self.w0**2 - w**2 + 2j * self.zeta * self.w0 * w)

    def slope_spectrum(self, omega, hs: float, tz: float) -> np.ndarray:
        """One-sided spectrum of the wave slope alpha [rad^2 s/rad] on the model's band (0 outside)
        for Hs [m] and Tz [s]."""
        w = np.asarray(omega, float)
        s = (w**2 / G) ** 2 * bretschneider_tz(w, hs, tz)
        return np.where((w >= self.w_min) & (w <= self.w_max), s, 0.0)

    def response_spectrum(self, omega, hs: float, tz: float) -> np.ndarray:
        """One-sided roll spectrum [rad^2 s/rad] at ``omega`` [rad/s] in the sea state (Hs [m], Tz [s])."""
        return np.abs(self.transfer(omega)) ** 2 * self.slope_spectrum(omega, hs, tz)

    @functools.cached_property
    def edges(self) -> np.ndarray:
        """Bin edges of the simulation's components on [w_min, w_max] [rad/s]."""
        w = np.linspace(self.w_min, self.w_max, 400001)
        h2 = np.abs(self.transfer(w)) ** 2
        rho = 1.0 / self.dw_max + h2 / h2.max() / self.dw_min
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (rho[1:] + rho[:-1]) * np.diff(w))])
        n = int(np.ceil(cum[-1]))
        e = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, w)
        e[0], e[-1] = self.w_min, self.w_max
        return e

    @functools.cached_property
    def grid(self) -> np.ndarray:
        """Quadrature grid of the band [rad/s]: ``fine`` equal sub-intervals in every bin, so that
        Simpson's rule on it is Simpson's rule bin by bin."""
        e = self.edges
        f = np.linspace(0.0, 1.0, self.fine + 1)[:-1]
        return np.concatenate([(e[:-1, None] + f[None, :] * np.diff(e)[:, None]).ravel(), e[-1:]])

    def moments(self, hs: float, tz: float) -> tuple[float, float]:
        """(m0 [rad^2], m2 [rad^2/s^2]) of the roll spectrum on the band (Simpson on :attr:`grid`)."""
        w = self.grid
        return moments(w, self.response_spectrum(w, hs, tz))

    def exact_rate(self, hs: float, tz: float, level_deg: float) -> float:
        """Exact up-crossing rate [1/s] of roll = +level [degree] in (Hs [m], Tz [s]) (Rice's formula)."""
        w = self.grid
        return rice_upcrossing_rate(w, self.response_spectrum(w, hs, tz), np.radians(level_deg))

    def band_loss(self, hs: float, tz: float, w_hi: float = 20.0) -> tuple[float, float]:
        """Relative loss of (m0, m2) of the roll spectrum by the band [w_min, w_max], against the
        unbounded Bretschneider spectrum integrated to ``w_hi`` [rad/s] (information only)."""
        w = np.concatenate([np.linspace(1e-3, self.w_max, 200001), np.linspace(self.w_max, w_hi, 200001)[1:]])
        s = np.abs(self.transfer(w)) ** 2 * (w**2 / G) ** 2 * bretschneider_tz(w, hs, tz)
        m0, m2 = moments(w, s)
        b0, b2 = self.moments(hs, tz)
        return float(1 - b0 / m0), float(1 - b2 / m2)

    # ---- time domain ----
    def bin_energies(self, hs: float, tz: float) -> np.ndarray:
        """Roll variance carried by each bin, int_bin S_phi dw [rad^2] (Simpson per bin); they add up
        to m0 of :meth:`moments`."""
        s = self.response_spectrum(self.grid, hs, tz)
        wts = np.ones(self.fine + 1)
        wts[1:-1:2], wts[2:-1:2] = 4.0, 2.0
        nb = len(self.edges) - 1
        idx = np.arange(nb)[:, None] * self.fine + np.arange(self.fine + 1)[None, :]
        return (s[idx] * wts).sum(axis=1) * np.diff(self.edges) / (3.0 * self.fine)

    def frequencies(self, seed: int) -> np.ndarray:
        """Component frequencies [rad/s], one uniform in each bin, drawn from ``seed``."""
        e = self.edges
        rng = np.random.default_rng(np.random.SeedSequence([int(seed), FREQUENCY_STREAM]))
        return e[:-1] + rng.random(len(e) - 1) * np.diff(e)

    def components(self, hs: float, tz: float, omega: np.ndarray, seed: int) -> tuple[np.ndarray, np.ndarray]:
        """(slope amplitude [rad], phase [rad]) of a record's wave-slope components at ``omega``.

        The amplitude carries its bin's exact share of the roll variance,
        c_n^2 |H(w_n)|^2 / 2 = int_bin S_phi dw, so the synthesized roll's variance is m0 of the band
        in every record (and c_n^2 / 2 -> S_alpha(w_n) dw as the bins narrow); the phase is drawn
        from ``seed``."""
        amp = np.sqrt(2 * self.bin_energies(hs, tz)) / np.abs(self.transfer(omega))
        phase = np.random.default_rng(int(seed)).uniform(-np.pi, np.pi, len(omega))
        return amp, phase

    def excitation(self, amp, omega, phase, n: int) -> np.ndarray:
        """Wave slope alpha = sum c cos(w t + e) [rad] and its derivative [rad/s] at t = 0, dt, ...,
        (n - 1) dt for several records at once: ``amp`` and ``phase`` (nrec, nc), ``omega`` (nc,).
        Returns (n, nrec, 2), by the project's blocked phasor synthesis
        (:func:`stabflow.waves.synthesis._time_series_table`)."""
        from stabflow.waves.synthesis import _time_series_table

        c, ph = np.atleast_2d(amp), np.atleast_2d(phase)
        cc, sc = c * np.cos(ph), c * np.sin(ph)
        # cos(wt + e) = cos e cos wt - sin e sin wt;  d/dt = -w (sin e cos wt + cos e sin wt)
        cols = [(cc, -sc), (-omega * sc, -omega * cc)]
        return _time_series_table(np.asarray(omega, float), np.arange(n) * self.dt, cols, np.float64)

    def one_dof(self, duration: float):
        """The project's 1-DOF RK4 model (:class:`stabflow.dynamics.one_dof.OneDof`) with a linear
        restoring table (GZ / GM = phi; linear interpolation and extrapolation of it are exact) and no
        capsize; its own excitation filter is not used."""
        from stabflow.dynamics.one_dof import OneDof

        dphi = np.radians(1.0)
        return OneDof(w0=self.w0, zeta=self.zeta, restoring=np.arange(0.0, 181.0) * dphi, dphi=dphi, cap=np.inf,
                      wf=self.w0, zf=1.0, sigma=0.0, dt=self.dt, warmup=self.warmup, duration=duration)

    def records(self, hs, tz, duration: float, seed: int, cells=None):
        """Yield (position i, roll record [rad, rad/s] of shape (nsteps + 1, 2) from rest over
        warmup + duration) for the sea states ``hs[i]``, ``tz[i]`` [m, s].

        All records of a call share the component frequencies (drawn from ``seed``); the phases of
        record i come from :func:`stabflow.dynamics.one_dof.record_seeds` (seed, stream, cells[i])
        (``cells`` default: 0, 1, ...), so a record depends only on (seed, cells[i]) and any one can
        be regenerated alone. The wave slope of a chunk of records (about 64 MiB) is one matrix
        product over the shared time factors."""
        from stabflow.dynamics.one_dof import record_seeds

        hs, tz = np.atleast_1d(np.asarray(hs, float)), np.atleast_1d(np.asarray(tz, float))
        cells = np.arange(len(hs)) if cells is None else np.asarray(cells)
        m = self.one_dof(duration)
        om = self.frequencies(seed)
        seeds = record_seeds(seed, VERIFICATION_STREAM, cells)
        chunk = max(1, int(2**26 // (16 * m.nexc)))  # excitation of a chunk: about 64 MiB
        for j0 in range(0, len(hs), chunk):
            sl = slice(j0, min(j0 + chunk, len(hs)))
            ap = [self.components(h, t, om, s) for h, t, s in zip(hs[sl], tz[sl], seeds[sl])]
            exc = self.excitation(np.array([a for a, _ in ap]), om, np.array([p for _, p in ap]), m.nexc)
            for j in range(exc.shape[1]):
                out, _ = m.record(0, np.ascontiguousarray(exc[:, j, :]))
                yield j0 + j, out

    def simulate_cells(self, hs, tz, level_deg: float, duration: float, seed: int) -> tuple[np.ndarray, float]:
        """Up-crossings of roll = +level [degree] in ``duration`` seconds after the warm-up, for each
        sea state (``hs`` [m], ``tz`` [s]); every up-crossing counts (no declustering), as in Rice's
        rate. Returns (counts, exposure [s])."""
        from stabflow.statistics.signals import crossings

        m = self.one_dof(duration)
        hs = np.atleast_1d(np.asarray(hs, float))
        counts = np.zeros(len(hs), np.int64)
        level = np.radians(level_deg)
        for i, out in self.records(hs, tz, duration, seed):
            x = out[m.nwarm:]
            counts[i] = len(crossings(np.arange(len(x)) * self.dt, x[:, 0], x[:, 1], level, up=True)[2])
        return counts, (m.nsteps - m.nwarm) * self.dt

    def simulate(self, hs: float, tz: float, level_deg: float, duration: float, seed: int) -> tuple[int, float]:
        """Up-crossings of roll = +level [degree] in one sea state (Hs [m], Tz [s]) over ``duration``
        seconds after the warm-up (cell 0 of :meth:`simulate_cells`). Returns (count, exposure [s])."""
        k, T = self.simulate_cells([hs], [tz], level_deg, duration, seed)
        return int(k[0]), T


def dsa_verification(level_deg: float = 30.0, duration: float = 3 * 3600.0, records: int = 6, seed: int = 0,
                     model: LinearRoll | None = None, table: dict | None = None,
                     alpha: float = 0.05) -> xr.Dataset:
    """Exact verification of the DSA aggregation: linear roll over the read IACS Rec. 34 cells.

    Beam seas only (heading 90 degree, probability 1), zero speed (probability 1). Every read cell
    with a non-zero probability is simulated as ``records`` independent records of
    ``duration / records`` counted seconds (record r of cell i has its own phases from the master
    ``seed`` and the index i records + r, :func:`stabflow.dynamics.one_dof.record_seeds`), and its
    up-crossings of +level are counted: every one (no declustering), as Rice's rate counts them.
    All cells are "counted" (zero counts included, so every cell enters the Fay-Feuer w_M). The
    counts are aggregated with :func:`long_term_rate`; the exact long-term rate is sum_i p_i nu_i
    over the same cells, nu_i from Rice's formula. Unread cells (NaN) are left out of both sums; the
    table's coverage is reported.

    Raw up-crossings of a lightly damped (narrow-band) roll come in groups, so their counts are
    overdispersed (about 2 here): the Poisson (Fay-Feuer) interval is then too narrow. The records
    give the dispersion, phi = sum_i w_i^2 s_i^2 / sum_i w_i^2 mean_i over the cells (s_i^2 and
    mean_i: sample variance and mean of the cell's record counts, w_i = p_i / T_i: the aggregate's
    own variance ratio), and the interval is also given with it (``rate_lo_dispersed``,
    ``rate_hi_dispersed``; :func:`fay_feuer_interval`).

    Parameters
    ----------
    level_deg : roll level [degree].
    duration : counted simulation time per cell [s] (all its records together).
    records : independent records per cell (>= 2 for the dispersion).
    seed : master seed.
    model : the linear roll model (default :class:`LinearRoll()`: w0 = 0.5 rad/s, zeta = 0.05).
    table : parsed scatter table (default: ``resources/criteria/iacs_rec34_scatter.yaml``).
    alpha : 1 - confidence level.

    Returns
    -------
    The :func:`long_term_rate` Dataset (Poisson interval) with, added: ``exact_rate`` [1/year] (the
    exact long-term sum), ``inside`` [-] (1 if it lies in [rate_lo, rate_hi]), ``ratio`` [-]
    (estimate / exact), ``dispersion`` [-], ``rate_lo_dispersed``, ``rate_hi_dispersed`` [1/year],
    ``inside_dispersed`` [-], ``exact_cell_rate`` (cell) [1/s], ``expected_failures`` (cell) [-] (exact
    rate x exposure), ``failures`` (cell) [-], ``record_failures`` (cell, record) [-], ``exposure``
    (cell) [s], ``roll_std`` (cell) [degree]; the model and settings as attributes.
    """
    from stabflow.criteria.standards import DATA_DIR
    from stabflow.config import load_yaml

    model = model or LinearRoll()
    if records < 2:
        raise ValueError("dsa_verification: records must be >= 2 (the dispersion needs them)")
    if table is None:
        table = load_yaml(DATA_DIR / "iacs_rec34_scatter.yaml")
    P = scatter_probabilities(table)
    st = P.stack(cell=("hs", "tz"))
    st = st[np.isfinite(st.values) & (st.values > 0)]
    hs = st["hs"].values.astype(float)
    tz = st["tz"].values.astype(float)
    p = st.values.astype(float)
    n = len(p)
    nu = np.array([model.exact_rate(h, t, level_deg) for h, t in zip(hs, tz)])
    sd = np.array([np.degrees(np.sqrt(model.moments(h, t)[0])) for h, t in zip(hs, tz)])
    kr, T1 = model.simulate_cells(np.repeat(hs, records), np.repeat(tz, records), level_deg, duration / records, seed)
    kr = kr.reshape(n, records)
    k = kr.sum(axis=1)
    T = np.full(n, T1 * records)
    phi, _ = count_dispersion(list(kr), p / T)
    phi = 1.0 if not np.isfinite(phi) else phi
    nan = np.full(n, np.nan)
    cells = xr.Dataset(
        {"probability": ("cell", p), "failures": ("cell", k), "exposure": ("cell", T), "rate_lo": ("cell", nan),
         "rate": ("cell", nan), "rate_hi": ("cell", nan), "method": ("cell", np.array(["counted"] * n, dtype=object))},
        coords={"cell": np.arange(n),
                "hs": _var("cell", hs, "m", "significant wave height"),
                "tz": _var("cell", tz, "s", "zero up-crossing period"),
                "heading": _var("cell", np.full(n, 90.0), "degree", "wave heading (0 following, 180 head)"),
                "speed": _var("cell", np.zeros(n), "m/s", "ship speed")})
    ds = long_term_rate(cells, alpha)
    dsp = long_term_rate(cells, alpha, dispersion=max(phi, 1.0))
    exact = float(np.sum(p * nu) * SECONDS_PER_YEAR)
    lo, hi = float(ds["rate_lo"]), float(ds["rate_hi"])
    lod, hid = float(dsp["rate_lo"]), float(dsp["rate_hi"])
    ds = ds.assign(
        exact_rate=_var((), exact, "1/year", "exact long-term up-crossing rate (Rice) over the same cells"),
        inside=_var((), int(lo <= exact <= hi), "1", "1 if the exact rate lies in the Poisson interval"),
        ratio=_var((), float(ds["rate"]) / exact, "1", "estimate over exact long-term rate"),
        dispersion=_var((), phi, "1", "Var k / E k of the counts, from the records (aggregate-weighted)"),
        rate_lo_dispersed=_var((), lod, "1/year", "lower bound with the counts' dispersion"),
        rate_hi_dispersed=_var((), hid, "1/year", "upper bound with the counts' dispersion"),
        inside_dispersed=_var((), int(lod <= exact <= hid), "1", "1 if the exact rate lies in the dispersed interval"),
        exact_cell_rate=_var("cell", nu, "1/s", "exact up-crossing rate of the cell (Rice)"),
        expected_failures=_var("cell", nu * T, "1", "exact rate x exposure"),
        failures=_var("cell", k, "1", "up-crossings counted in the simulation"),
        record_failures=_var(("cell", "record"), kr, "1", "up-crossings counted in each record"),
        exposure=_var("cell", T, "s", "counted simulation time"),
        roll_std=_var("cell", sd, "degree", "standard deviation of roll (spectrum)"),
    )
    ds.attrs.update(level_deg=level_deg, duration=duration, records=records, seed=seed, w0=model.w0, zeta=model.zeta,
                    w_min=model.w_min, w_max=model.w_max, dw_min=model.dw_min, dw_max=model.dw_max, dt=model.dt,
                    warmup=model.warmup, covered_fraction=P.attrs["covered_fraction"], cells_used=n,
                    cells_unread="; ".join(P.attrs["missing_rows"]),
                    note="beam seas (heading 90 degree, probability 1), zero speed; every up-crossing counted")
    return ds
