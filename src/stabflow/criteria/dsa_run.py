"""Direct stability assessment of one ship with the ensemble engine: every cell of the scatter table
x headings x speeds, screened cheaply, simulated where it matters, aggregated by :mod:`.dsa`.

A cell is (Hs, Tz, heading, speed) with probability P(Hs, Tz) P(heading) P(speed): the IACS Rec. 34
North Atlantic table (rows read, ``resources/criteria/iacs_rec34_scatter.yaml``), a uniform heading over
the span the equally spaced headings cover (each heading the interval of one spacing around it, clipped
to 0-180 degree: :func:`heading_intervals`) and equally likely speeds (stabflow's choice; the
circular's operational assumptions were not read). The sea
of a cell is the two-parameter Bretschneider spectrum at (Hs, Tz), long-crested, through the
ensemble engine's seaway and 3-DOF model (:mod:`stabflow.statistics.ensemble`).

Failure: roll beyond min(the DSA roll limit, the angle of vanishing stability, the flooding angle),
each with its source, or the lateral acceleration at the highest crew location beyond its limit
(the lateral specific force of :func:`stabflow.dynamics.rigid_body.lateral_specific_force`). No
readable source gave that limit: without it (an override supplies it) the acceleration side is
named as missing in the results and the row gets no verdict, never one on roll alone.

Per cell, in order:

Every record starts from rest and is simulated for ``warmup_roll_periods`` natural roll periods
before its ``duration`` is counted: the transient is left out of the failures, the exposure and
the statistics (the ensemble engine's ``warmup_s``); a record that capsizes inside it counts nothing
(left truncation), and a cell whose records all do is counted from rest and flagged (``warmup_fallback``).

1. *Screening run*: ``screen.records`` records of ``screen.duration``. The Gaussian (Rice) rate of
   |roll| above the failure angle with the run's roll sigma inflated by ``screen.sigma_factor``,
   nu_hi = 2 nu_0 exp(-phi_f^2 / (2 (k sigma)^2)) with nu_0 the run's zero up-crossing rate, at least
   1 / T_roll (both sides of the roll), is the cell's bound (a heuristic); below ``screen.rate``
   [1/s] (and no roll beyond half the failure angle in the run) the cell is *screened*: rate = the
   Rice rate with the run's sigma, bounds [0, nu_hi] (nu_hi at least ``SCREEN_FLOOR``, where the
   Gaussian tail underflows); with an acceleration limit the same bound of
   the acceleration (its own sigma and zero up-crossing rate) is added, and its run must stay below
   half the limit. Head and following seas (within
   ``screen.parametric_deg``) are never screened: roll there is parametric, not Gaussian; their
   records start from ``initial_heel_deg``. Nor are the cells whose sea drives principal
   parametric roll (:func:`parametric_fraction` above ``screen.parametric_fraction``): on the DTC
   (roll period 38 s) stern-quartering seas at 60 degree build roll up over 10-30 minutes at half
   the encounter frequency (Hs 6.5 m, Tz 10.5 s, Fn 0.1, six 30-min records: sigma 3-4 degree in
   most first 5 minutes, 5-18 in the last 15; in beam seas of the same sea 1.2-3.3).
2. Otherwise *simulated*: ``records`` records of ``duration``; failures are the declustered
   exceedances of the failure angle (crossings of +-phi_f, and of +-the acceleration limit, closer
   than the decorrelation time of the cell's roll, at least one natural roll period, are one
   failure; a capsize is one) -> *counted*. With none counted, the rate of |roll| peaks beyond phi_f
   from a Poisson-GPD fit over 3.5 roll sigma, or 3.0 or 2.5 where fewer declustered peaks than a
   fit needs exceed it (``THRESHOLD_SIGMAS``; :mod:`stabflow.statistics.extremes`,
   profile-likelihood interval; not taken when its upper bound is 0) -> *extrapolated*; with an
   acceleration limit, plus the same fit of
   |acceleration| peaks over 3.5 (3.0, 2.5) of its sigma (the sum bounds the rate of either failure from above;
   the interval runs from the larger lower bound to the sum of the upper bounds). When a tail has too
   few exceedances to fit, the zero count stays *counted* (its Poisson upper bound enters the
   interval).
3. *Recheck* (``screen.recheck``, default on): every screened cell is simulated as in 2 (its own
   seeds; ``records`` x ceil(p / mean p) records, :func:`recheck_records`). Where that simulation contradicts the screening (:func:`overrules`: failures counted,
   or a fitted tail above the Gaussian bound) the cell is *overruled*: it enters the long-term rate
   as simulated (``screen_overruled``). The Gaussian bound misses the failures of strongly
   nonlinear roll (on the shipped hulls, before parametric cells were left out of the screening,
   16 of the DTC's cells at 60 degree, roll sigma 2-4.4 degree in the screening run, failed
   within 20 minutes; with them left out, 4 beam-sea cells of Hs 11.5-16.5 m). :func:`screening_recheck`
   bounds the screened cells' total contribution from their pooled counts (Fay & Feuer) and judges
   it against the interval's width.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time

import numpy as np
import xarray as xr

from stabflow.config import Ship, _fill_defaults, schema
from stabflow.constants import G, KNOT
from stabflow.criteria import dsa
from stabflow.criteria.standards import Standards
from stabflow.io import annotate

FAIL_KEY = "sgisc.direct_stability_assessment.failure_roll_angle_deg"
ACC_KEY = "sgisc.direct_stability_assessment.lateral_acceleration_limit"
#: POT thresholds of the zero-count cells, in the run's sigma, highest first: the extremes step's
#: documented default 3.5, then lower ones while fewer than ``extremes.MIN_EXCEEDANCES`` declustered
#: peaks exceed it. A cell's short records rarely reach 3.5 sigma (a 20-min record has about 120 roll
#: peaks, of which a Rayleigh tail puts 0.3 beyond 3.5 sigma and 5 beyond 2.5): with 3.5 alone the
#: run of 2026-12-04 extrapolated none of the 7 ships' 194-326 zero-count cells. None below the run's
#: peak floor (peaks under it are not kept).
THRESHOLD_SIGMAS = (3.5, 3.0, 2.5)
#: degrees of freedom needed before a measured count dispersion is used (stabflow's choice)
MIN_DISPERSION_DOF = 10
#: the smallest upper bound [1/s] a screened cell carries (the smallest positive normal double): its
#: Gaussian (Rice) bound is kept where it is larger, this where exp() underflowed to 0
SCREEN_FLOOR = float(np.finfo(float).tiny)


def acceleration_limit(std: Standards) -> float | None:
    """The lateral-acceleration limit [m/s^2] of the DSA failure, None when no source (nor override)
    gives it."""
    acc = std.get(ACC_KEY)
    return float(acc.value) if acc.available else None


def acceleration_missing(std: Standards) -> list[str]:
    """What keeps the DSA row from a verdict on the lateral-acceleration side of the failure: its
    limit, when not sourced (the row then never gives a verdict on the roll alone)."""
    if acceleration_limit(std) is None:
        return [f"{ACC_KEY} (lateral acceleration failure not assessed)"]
    return []


def failure_angle(std: Standards, vanishing: float, flooding: float) -> tuple[float, str]:
    """The failure roll angle [degree]: min(sourced DSA limit, vanishing stability, flooding), and
    which one governs."""
    lim = std.get(FAIL_KEY)
    cands = {"DSA roll limit": float(lim.value) if lim.available else math.inf,
             "angle of vanishing stability": vanishing if math.isfinite(vanishing) else math.inf,
             "flooding angle": flooding if math.isfinite(flooding) else math.inf}
    which = min(cands, key=cands.get)
    if not math.isfinite(cands[which]):
        return math.nan, "no failure angle: the DSA roll limit is not sourced and GZ stays positive"
    return cands[which], which


def cell_grid(std: Standards, headings_deg, speeds_kn, hs_max: float | None = None) -> xr.Dataset:
    """All cells with nonzero probability: P(Hs, Tz) of the scatter rows read x equally likely
    headings x equally likely speeds. Attributes: the scatter table's covered fraction."""
    P = dsa.scatter_probabilities(std.raw["iacs_rec34_scatter"])
    hs, tz = np.meshgrid(P["hs"].values, P["tz"].values, indexing="ij")
    p = P.values
    ok = np.isfinite(p) & (p > 0)
    if hs_max is not None:
        ok &= hs <= hs_max
    h = np.asarray(headings_deg, float)
    v = np.asarray(speeds_kn, float)
    a, b = heading_intervals(h)
    lo, hi = float(a[0]), float(b[-1])
    # each heading weighs its interval's share of the span (0 and 180 deg: half an interval, the
    # trapezoid rule; one heading: all of it)
    wh = (b - a) / (hi - lo) if hi > lo else np.ones(1)
    rows = [(a, b, m, u, c * w / len(v)) for a, b, c in zip(hs[ok], tz[ok], p[ok]) for m, w in zip(h, wh) for u in v]
    H, T, M, U, PR = (np.array(x, float) for x in zip(*rows))
    ds = xr.Dataset({"probability": ("cell", PR)},
                    coords={"cell": np.arange(len(PR)), "hs": ("cell", H), "tz": ("cell", T),
                            "heading": ("cell", M), "speed_kn": ("cell", U)})
    ds.attrs.update(scatter_covered_fraction=float(P.attrs.get("covered_fraction", np.nan)),
                    probability_used=float(np.nansum(p[ok])),
                    scatter_source=str(std.raw["iacs_rec34_scatter"]["meta"]["document"]),
                    heading_span=f"{lo:g}-{hi:g} deg",
                    probabilities=f"P(Hs, Tz) from the scatter table x heading weight x 1/speeds (a uniform heading "
                                  f"over {lo:g}-{hi:g} deg, port and starboard mirrored, each heading standing for the "
                                  "interval of one spacing around it clipped to 0-180 deg; speeds equally likely: "
                                  "stabflow's choice)")
    return ds


def heading_intervals(headings_deg) -> tuple[np.ndarray, np.ndarray]:
    """(from, to) [degree] of the interval each of the equally spaced, increasing ``headings_deg``
    stands for in a uniform heading: one spacing around it, clipped to 0-180 (port and starboard
    mirrored; one heading: itself). Raises StabflowError (naming ``dsa.headings_deg``) if they are not."""
    from stabflow import StabflowError

    h = np.asarray(headings_deg, float)
    if len(h) == 1:
        return h.copy(), h.copy()
    d = np.diff(h)
    if np.any(d <= 0) or not np.allclose(d, d[0], rtol=0, atol=1e-9):
        raise StabflowError(f"dsa.headings_deg: {list(map(float, h))} are not equally spaced in increasing order: each "
                            "heading stands for an equal interval of a uniform heading around it")
    return np.maximum(h - 0.5 * d[0], 0.0), np.minimum(h + 0.5 * d[0], 180.0)


def cell_seed(master: int, *indices: int) -> int:
    """Seed of one cell and stage from the master seed and the cell's grid indices (independent of
    the grid's order and of the other cells)."""
    return int(np.random.SeedSequence([int(master), *map(int, indices)]).generate_state(1)[0])


def condition(cfg: dict, ship: str, hs: float, tz: float, heading: float, speed_kn: float, records: int,
              duration: float, seed: int, phi_f: float, floor: float, lateral: dict | None = None,
              warmup: float = 0.0) -> dict:
    """An ensemble condition (the ensembles schema, defaults filled) for one cell; ``lateral`` the
    engine's ``lateral_acceleration`` settings (crew height above G, limits, peak floor) or None;
    ``warmup`` [s] simulated from rest before each record's ``duration`` is counted."""
    tp = tz / dsa.tz_over_tm()
    c = {"name": "dsa", "ship": ship, "speed_kn": float(speed_kn), "heading_deg": float(heading),
         "sea": {"spectrum": "bretschneider", "hs": float(hs), "tp": float(tp), "n_components": int(cfg["n_components"])},
         "records": int(records), "duration": float(duration), "warmup_s": float(warmup), "dt": float(cfg["dt"]),
         "seed": int(seed),
         "stations": int(cfg["stations"]), "thresholds_deg": [float(phi_f)], "peak_floor_deg": float(floor),
         "samples": 0, "max_lag": float(cfg["max_lag"])}
    if cfg.get("dynamics"):
        c["dynamics"] = dict(cfg["dynamics"])
    if cfg.get("dphi_dzdt", False):
        c["dphi_dzdt"] = True
    if lateral:
        c["lateral_acceleration"] = dict(lateral)
    return _fill_defaults(schema("config")["properties"]["ensembles"]["items"], c)


def _models(ship: Ship, cfg: dict, headings, speeds, hydro, phi_f):
    """One engine model per (heading, speed): hull, statics, coefficients (speed-dependent damping)
    and the sectional tables are built once and shared by the cells."""
    from stabflow.statistics.ensemble import build_model

    out = {}
    for m in headings:
        for u in speeds:
            c = condition(cfg, ship.name, 1.0, 8.0, m, u, 1, 60.0, 0, phi_f, 1.0)
            out[(float(m), float(u))] = build_model(ship, c, hydro)
    return out


@functools.lru_cache(maxsize=1024)
def _sea_grid(hs: float, tz: float, n: int) -> tuple[np.ndarray, np.ndarray, float]:
    """(omega [rad/s], Bretschneider S [m^2 s], its integral [m^2]) on ``n`` points of the spectrum's
    band: one per sea state, shared by its headings and speeds (read-only arrays)."""
    lo, hi = dsa.spectrum_band(hs, tz)
    w = np.linspace(lo, hi, n)
    S = dsa.band_spectrum(w, hs, tz, (lo, hi))
    w.flags.writeable = S.flags.writeable = False
    return w, S, float(np.trapezoid(S, w))


def parametric_fraction(hs: float, tz: float, heading_deg: float, speed: float, roll_period: float, length: float,
                        band: float, wavelengths: tuple[float, float], n: int = 2000) -> float:
    """Fraction [-] of the sea's variance carried by wave components that can drive principal
    parametric roll: encounter frequency within ``band`` (relative) of twice the natural roll
    frequency, w_e = 2 w_phi (1 +- band), and wave length along the ship lambda / |cos mu| within
    ``wavelengths`` x ``length`` (the restoring varies most with the wave's crest or trough
    amidships when that length is close to the ship's: the wave cases of parametric roll and pure
    loss of stability take lambda = L, Circ.1627). Bretschneider (Hs [m], Tz [s]) on its band
    (:func:`stabflow.criteria.dsa.band_spectrum`); ``heading_deg`` 0 following; ``speed`` [m/s],
    ``roll_period`` [s], ``length`` [m].

    A criterion for leaving a cell out of the Gaussian screening (stabflow's choice, no standard):
    the screening run is a few minutes from upright, shorter than parametric roll takes to build up,
    and its roll is then not Gaussian. Heading alone does not find these cells: a long roll period
    meets w_e = 2 w_phi at lambda / |cos mu| = L in stern-quartering seas (the DTC at 30 degree off
    the stern, roll period 38 s at Fn 0.1)."""
    from stabflow.waves.synthesis import encounter_frequency

    w, S, total = _sea_grid(float(hs), float(tz), int(n))
    we = np.abs(encounter_frequency(w, speed, heading_deg))
    w2 = 4.0 * math.pi / roll_period
    c = abs(math.cos(math.radians(heading_deg)))
    lam = 2.0 * math.pi * G / w**2
    along = (lam >= wavelengths[0] * length * c) & (lam <= wavelengths[1] * length * c)
    sel = (np.abs(we / w2 - 1.0) <= band) & along
    return float(np.trapezoid(np.where(sel, S, 0.0), w)) / total if total > 0 else 0.0


def overrules(method: str, failures: int, rate: float, bound: float) -> bool:
    """Whether a screened cell's simulation (``method`` "counted" with ``failures``, or
    "extrapolated" with ``rate`` [1/s]) contradicts its screening ``bound`` [1/s]: failures counted,
    or a fitted tail rate above the bound. A zero count without a fit does not (its Poisson bound
    says only that the record was short)."""
    return (method == "counted" and failures > 0) or (method == "extrapolated" and rate > bound)


def recheck_records(probability: float, mean_probability: float, records: int, allocation: str) -> int:
    """Records of one screened cell's recheck.

    ``"uniform"``: ``records``, as every simulated cell. ``"probability"`` (default): ``records`` x
    ceil(p / p_mean), so that a cell's weight in the pooled bound, w = p / T, is at most
    p_mean / (records x duration) whatever its probability: the zero counts of many short rechecks
    then bound the screened cells' total contribution as tightly as one long record of their summed
    exposure would (:func:`screening_recheck`; Fay & Feuer 1997 take w_M = max w). The cost is at most
    ``records`` x (cells + sum p / p_mean) records over the screened cells."""
    if allocation == "uniform":
        return int(records)
    if allocation != "probability":
        raise ValueError(f"dsa.screen.recheck_allocation: {allocation!r} is not 'probability' or 'uniform'")
    return int(records) * max(1, math.ceil(probability / mean_probability - 1e-12))


def failures_per_record(ens: xr.Dataset, window: float) -> np.ndarray:
    """Declustered failures of each record (in the order of ``ens.record``): crossings of +-phi_f
    (the only threshold) and, when the run kept them, of +-the first lateral-acceleration limit,
    closer than ``window`` [s] within a record are one failure; a capsize is one (it crossed phi_f
    first)."""
    rec = ens["crossing_record"].values
    t = ens["crossing_time"].values
    if "lateral_crossing_time" in ens:
        first = ens["lateral_crossing_limit"].values == 0
        rec = np.concatenate([rec, ens["lateral_crossing_record"].values[first]])
        t = np.concatenate([t, ens["lateral_crossing_time"].values[first]])
    recs = ens["record"].values if "record" in ens.coords else np.unique(rec)
    out = np.zeros(len(recs), np.int64)
    for i, r in enumerate(recs):
        tt = np.sort(t[rec == r])
        out[i] = (1 + int((np.diff(tt) > window).sum())) if len(tt) else 0
    return out


def run_cell(model, cond: dict):
    """Simulate ``cond`` with the engine ``model`` (its sea and records replaced): merged dataset."""
    from stabflow.statistics.ensemble import merge, run_shard
    from stabflow.waves.seaway import Seaway

    m = dataclasses.replace(model, cond=cond, sea=Seaway.from_config(cond["sea"]))
    return merge([run_shard(m, range(cond["records"]), progress=False)])


def with_initial_heel(model, heel_deg: float):
    """The engine model starting its records from the equilibrium heeled by ``heel_deg``: the seed of
    roll in long-crested head and following seas, where the waves excite none."""
    from stabflow.dynamics._kernels import S_ROLL

    s0 = model.s0.copy()
    s0[S_ROLL] += math.radians(heel_deg)
    return dataclasses.replace(model, s0=s0)


def zero_crossing_rate(ens: xr.Dataset, roll_period: float) -> float:
    """Mean zero up-crossing rate of roll [1/s]: sqrt(m2 / m0) / 2 pi of the run's roll spectrum, at
    least 1 / T_roll (the spectrum needs records of 512 steps or more)."""
    S = ens["roll_psd"].values
    if int(ens["psd_count"]) > 0 and S.any():
        # Rice's rate at level 0: sqrt(m2 / m0) / 2 pi
        return max(1.0 / roll_period, dsa.rice_upcrossing_rate(ens["frequency"].values, S, 0.0))
    return 1.0 / roll_period


def _extrapolate(ens: xr.Dataset, phi_f: float, alpha: float, tau: float, floors=(0.0, 0.0)):
    """(rate, lo, hi) [1/s] of declustered |roll| peaks beyond phi_f (window ``tau`` [s], as the
    counted failures) from a Poisson-GPD fit over the highest of ``THRESHOLD_SIGMAS`` x the run's
    sigma that enough peaks exceed and that is not below the run's peak floor (``floors``: roll
    [degree], acceleration [m/s2]); with the run's lateral-acceleration peaks, plus the same fit of
    |acceleration| beyond its first limit: (rate_roll + rate_acc, max(lo_roll, lo_acc), hi_roll +
    hi_acc). Returns those and the thresholds used (in sigma; roll, then acceleration or NaN); the
    rates are NaN when a fit has too few peaks at every threshold."""
    from stabflow.statistics.extremes import block_estimates

    recs = ens["record"].values
    hours = float(ens["exposure_hours"])
    capd = ens["capsized"].values.astype(bool)
    series = [("peak", "roll_std", phi_f)]
    if "lateral_peak_value" in ens:
        series.append(("lateral_peak", "lateral_acceleration_std", float(ens["lateral_limit"][0])))
    out, used = [], [math.nan, math.nan]
    for j, (name, sd, level) in enumerate(series):
        est = (math.nan, math.nan, math.nan)
        for m in THRESHOLD_SIGMAS:
            u = m * float(ens[sd])
            if u < floors[j]:
                break
            # report None: no fixed-shape interval (the extremes step's shape share; not used here)
            R, LO, HI, *_ = block_estimates(ens[f"{name}_record"].values, ens[f"{name}_time"].values.astype(float),
                                            np.abs(ens[f"{name}_value"].values.astype(float)), recs[capd],
                                            ens["capsize_time"].values[capd], recs, hours, [u], [level], tau, alpha, None)
            if np.isfinite(R[0, 0]):
                est, used[j] = (R[0, 0] / 3600.0, LO[0, 0] / 3600.0, HI[0, 0] / 3600.0), m
                break
        out.append(est)
    r, lo, hi = (np.array(x) for x in zip(*out))
    return float(r.sum()), float(lo.max()), float(hi.sum()), used


def assess_cells(ship: Ship, cfg: dict, phi_f: float, lwl: float, hydro: xr.Dataset | None = None,
                 std: Standards | None = None, progress: bool = False, crew_z: float | None = None) -> xr.Dataset:
    """Every cell's rate (method, failures, exposure, rate and interval, roll sigma) for one ship.

    Parameters
    ----------
    cfg : the pipeline's ``dsa`` section (headings_deg, froude_numbers, records, duration, screen, dt,
        stations, n_components, seed, alpha, hs_max).
    phi_f : failure roll angle [degree].
    lwl : waterline length [m] of the loading (speeds from the Froude numbers).
    crew_z : height of the highest crew location above the baseline [m]; needed when ``std`` gives a
        lateral-acceleration limit (then a failure too).
    """
    from stabflow import StabflowError
    from tqdm import tqdm

    from stabflow.statistics.signals import decorrelation_time

    std = std or Standards()
    t0 = time.process_time()
    speeds = [fn * math.sqrt(G * lwl) / KNOT for fn in cfg["froude_numbers"]]
    cells = cell_grid(std, cfg["headings_deg"], speeds, cfg.get("hs_max"))
    acc_lim = acceleration_limit(std)
    if acc_lim is not None and crew_z is None:
        raise StabflowError(f"dsa: {ship.name}: a lateral-acceleration limit is given but no crew location height")
    models = _models(ship, cfg, cfg["headings_deg"], speeds, hydro, phi_f)
    lateral = None
    if acc_lim is not None:
        lateral = {"height": crew_z - float(next(iter(models.values())).st["kg"]), "limits": [acc_lim],
                   "peak_floor": 0.0}
    # every record starts from rest: its first warmup_roll_periods natural roll periods (the transient,
    # in which roll has not reached its stationary variance) are simulated and left out of the cell's
    # failures, exposure and statistics (the engine's warmup_s)
    periods = float(cfg.get("warmup_roll_periods", schema("config")["properties"]["dsa"]["properties"]
                            ["warmup_roll_periods"]["default"]))
    warm = {key: periods * mo.roll_period for key, mo in models.items()}
    warm_mean = float(np.mean(list(warm.values())))
    t_build = time.process_time() - t0
    n = cells.sizes["cell"]
    method = np.empty(n, object)
    k = np.full(n, -1, np.int64)
    T = np.full(n, np.nan)
    r, lo, hi, sig, rmax, asig = (np.full(n, np.nan) for _ in range(6))
    thr = np.full((n, 2), np.nan)  # the extrapolated cells' tail thresholds [sigma]: roll, acceleration
    scr = cfg["screen"]
    t_screen = t_sim = 0.0
    # grid indices of each cell (its seeds do not depend on the order of the cells)
    idx = {k: np.searchsorted(np.unique(cells[k].values), cells[k].values) for k in ("hs", "tz", "heading", "speed_kn")}
    parametric = float(scr["parametric_deg"])
    pf = np.full(n, np.nan)
    resonant = np.zeros(n, bool)  # away from head and following seas, left unscreened for parametric roll
    per_record, weights = [], []
    recheck = bool(scr.get("recheck", True))
    # the screened cells simulated as the others (their own seeds), to check the screening; kept
    # beside the cells, and in the long-term rate where they overrule the screening
    rc_method = np.full(n, "none", object)
    rc_k = np.full(n, -1, np.int64)
    rc_r, rc_lo, rc_hi, rc_max, rc_T = (np.full(n, np.nan) for _ in range(5))
    overruled = np.zeros(n, np.int8)
    t_recheck = 0.0
    # records of each recheck: proportional to the cell's probability (see recheck_records)
    allocation = str(scr.get("recheck_allocation", "probability"))
    p_mean = float(cells["probability"].mean())
    rc_n = np.zeros(n, np.int64)
    lost = np.zeros(n, np.int64)  # records of the cell's runs lost in their warm-up
    fallback = np.zeros(n, np.int8)  # 1: every record lost, the cell counted from rest

    def note_warmup(i, ens):
        lost[i] += int(ens["warmup_lost_count"]) + int(ens.attrs.get("warmup_lost_first", 0))
        fallback[i] = max(int(fallback[i]), int(ens.attrs.get("warmup_fallback", 0)))

    def simulate(model, cf, s, lat):
        """(method, failures, exposure [s], rate, lo, hi [1/s], thresholds, records' counts or None,
        dataset) of one simulated cell: declustered failures counted, a zero count extrapolated."""
        ens = run_cell(model, cf)
        if float(ens["exposure_hours"]) == 0.0 and cf["warmup_s"] > 0.0:
            # every record capsized inside its warm-up (a cell failing within minutes from rest):
            # nothing is left to count, so the cell is counted from rest instead (its transient in,
            # which can only lower the rate of so severe a cell: a lower estimate), and flagged
            lost_first = int(ens["warmup_lost_count"])
            ens = run_cell(model, dict(cf, warmup_s=0.0))
            ens.attrs.update(warmup_fallback=1, warmup_lost_first=lost_first)
        T = float(ens["exposure_hours"]) * 3600.0
        # declustering window: the decorrelation time of the cell's roll (as the extremes step), at
        # least one natural roll period; the same for the counted failures and the tail fit
        window = max(model.roll_period, decorrelation_time(ens["roll_autocorrelation"]))
        per = failures_per_record(ens, window)
        k = int(per.sum())
        per = None if int(ens["capsize_count"]) else per  # records of equal length only
        if k == 0:
            floors = (max(0.5, 2.0 * s), 0.0 if lat is None else lat["peak_floor"])  # as the condition's
            *rr, used = _extrapolate(ens, phi_f, float(cfg["alpha"]), window, floors)
            # a fit whose upper bound is 0 (its tail ends below the failure angle even at the
            # interval's edge, from a handful of peaks) is not taken: the zero count's Poisson bound stays
            if all(np.isfinite(rr)) and rr[2] > 0.0:
                return "extrapolated", -1, T, *rr, used, per, ens
        return "counted", k, T, np.nan, np.nan, np.nan, [np.nan, np.nan], per, ens

    for i in tqdm(range(n), desc=f"{ship.name} DSA cells", disable=not progress, mininterval=10):
        c = cells.isel(cell=i)
        key = (float(c.heading), float(c.speed_kn))
        model = models[key]
        ix = [idx[k][i] for k in ("hs", "tz", "heading", "speed_kn")]
        # head and following seas, and any sea with energy where principal parametric roll can be
        # driven (parametric_fraction): roll is parametric, not Gaussian: never screened
        pf[i] = parametric_fraction(float(c.hs), float(c.tz), key[0], key[1] * KNOT, model.roll_period, lwl,
                                    float(scr["parametric_band"]), tuple(scr["parametric_wavelength_ratio"]))
        off_axis = parametric < key[0] < 180.0 - parametric
        resonant[i] = off_axis and pf[i] > float(scr["parametric_fraction"])
        gaussian = off_axis and not resonant[i]
        a = time.process_time()
        es = None
        if gaussian:
            cs = condition(cfg, ship.name, float(c.hs), float(c.tz), *key, scr["records"], scr["duration"],
                           cell_seed(cfg["seed"], *ix, 0), phi_f, 1.0, lateral, warm[key])
            es = run_cell(model, cs)
            note_warmup(i, es)
            t_screen += time.process_time() - a
            s = float(es["roll_std"])
            # Gaussian (Rice) rates of exceedance on both sides, (zero up-crossing rate, level, sigma) of
            # the roll and, with a limit, of the lateral acceleration
            sides = [(zero_crossing_rate(es, model.roll_period), phi_f, s)]
            calm = float(es["roll_max"].max()) < 0.5 * phi_f and int(es["capsize_count"]) == 0
            if lateral is not None:
                sides.append((max(float(es["lateral_zero_upcrossing_rate"]), 1.0 / model.roll_period), acc_lim,
                              float(es["lateral_acceleration_std"])))
                calm = calm and float(es["lateral_max"].max()) < 0.5 * acc_lim

            def rice(factor):
                # both sides, Rice's formula with the sigma scaled by factor (m2 = (2 pi nu0 sigma)^2)
                return sum(2 * dsa.rice_rate((factor * sd) ** 2, (2 * math.pi * nu0 * factor * sd) ** 2, lev)
                           for nu0, lev, sd in sides)

            bound = rice(scr["sigma_factor"])
            if lateral is not None:
                asig[i] = sides[1][2]
            if bound < scr["rate"] and calm:
                # a bound below the smallest positive double (a calm cell: the Gaussian tail's exp()
                # underflows to 0) is kept as that double, so that the upper bound stays an upper
                # bound and no cell's interval is a bare [0, 0]
                method[i], r[i], lo[i], hi[i], sig[i], rmax[i] = ("screened", rice(1.0), 0.0, max(bound, SCREEN_FLOOR),
                                                                   s, float(es["roll_max"].max()))
                if recheck:
                    a = time.process_time()
                    lat = None if lateral is None else dict(lateral, peak_floor=2.0 * asig[i])
                    rc_n[i] = recheck_records(float(c.probability), p_mean, cfg["records"], allocation)
                    cf = condition(cfg, ship.name, float(c.hs), float(c.tz), *key, rc_n[i], cfg["duration"],
                                   cell_seed(cfg["seed"], *ix, 2), phi_f, max(0.5, 2.0 * s), lat, warm[key])
                    rc_method[i], rc_k[i], rc_T[i], rc_r[i], rc_lo[i], rc_hi[i], used, per, ens = simulate(model, cf, s,
                                                                                                          lat)
                    rc_max[i] = float(ens["roll_max"].max())
                    note_warmup(i, ens)
                    t_recheck += time.process_time() - a
                    if overrules(rc_method[i], rc_k[i], rc_r[i], hi[i]):
                        # the simulation contradicts the screening (failures counted, or a fitted
                        # tail above the Gaussian bound): the cell enters the long-term rate as simulated
                        overruled[i] = 1
                        method[i], k[i], T[i], r[i], lo[i], hi[i], thr[i] = (rc_method[i], rc_k[i], rc_T[i], rc_r[i],
                                                                            rc_lo[i], rc_hi[i], used)
                        sig[i], rmax[i] = float(ens["roll_std"]), rc_max[i]
                        if lateral is not None:
                            asig[i] = float(ens["lateral_acceleration_std"])
                        if per is not None:
                            per_record.append(per)
                            weights.append(float(c.probability) / T[i])
                continue
        a = time.process_time()
        s = float(es["roll_std"]) if es is not None else 1.0
        lat = None if lateral is None else dict(lateral, peak_floor=2.0 * asig[i] if np.isfinite(asig[i]) else 0.0)
        cf = condition(cfg, ship.name, float(c.hs), float(c.tz), *key, cfg["records"], cfg["duration"],
                       cell_seed(cfg["seed"], *ix, 1), phi_f, max(0.5, 2.0 * s), lat, warm[key])
        method[i], k[i], T[i], r[i], lo[i], hi[i], thr[i], per, ens = simulate(
            model if gaussian else with_initial_heel(model, float(cfg["initial_heel_deg"])), cf, s, lat)
        t_sim += time.process_time() - a
        note_warmup(i, ens)
        sig[i], rmax[i] = float(ens["roll_std"]), float(ens["roll_max"].max())
        if lateral is not None:
            asig[i] = float(ens["lateral_acceleration_std"])
        if per is not None:
            per_record.append(per)
            weights.append(float(c.probability) / T[i])
    cells["method"] = ("cell", method.astype(str))
    cells["failures"] = ("cell", k)
    cells["exposure"] = ("cell", T)
    cells["rate"], cells["rate_lo"], cells["rate_hi"] = (("cell", x) for x in (r, lo, hi))
    cells["roll_sigma"] = ("cell", sig, {"units": "degree", "long_name": "roll standard deviation of the cell's run"})
    cells["roll_max_cell"] = ("cell", rmax, {"units": "degree", "long_name": "largest |roll| of the cell's run"})
    cells["warmup_lost"] = ("cell", lost, {"units": "1", "long_name": "records of the cell's runs (screening, "
                                           "simulation, recheck) that capsized inside their warm-up and count nothing"})
    cells["warmup_fallback"] = ("cell", fallback, {"units": "1", "long_name": "1: every record of the cell's simulation "
                                                   "capsized inside its warm-up; the cell was counted from rest instead"})
    cells["parametric_fraction"] = ("cell", pf, {"units": "1", "long_name": "fraction of the sea's variance at "
                                                 "encounter frequencies and lengths that drive principal parametric roll"})
    cells["tail_threshold_sigma"] = ("cell", thr[:, 0], {"units": "1", "long_name": "threshold of the extrapolated "
                                                         "cell's roll tail fit, in the run's roll sigma"})
    if recheck:
        cells["recheck_method"] = ("cell", rc_method.astype(str), {
            "long_name": "the screened cell simulated as the others: counted or extrapolated (none: not screened)"})
        cells["recheck_failures"] = ("cell", rc_k, {"units": "1", "long_name": "declustered failures of the screened "
                                                    "cell's simulation (-1: extrapolated or not screened)"})
        # a counted recheck's rate is its failures over its exposure, its interval Garwood's (as the
        # counted cells': stabflow.criteria.dsa.long_term_rate)
        from stabflow.statistics.splittime import poisson_interval

        for j in np.nonzero(rc_method == "counted")[0]:
            rc_r[j], rc_lo[j], rc_hi[j] = poisson_interval(int(rc_k[j]), rc_T[j], float(cfg["alpha"]))  # per second
        for name, x, what in (("recheck_rate", rc_r, "failure rate"), ("recheck_rate_lo", rc_lo, "lower bound"),
                              ("recheck_rate_hi", rc_hi, "upper bound")):
            cells[name] = ("cell", x, {"units": "1/s", "long_name": f"{what} of the screened cell's simulation (counted: "
                                       "failures / exposure; extrapolated: the tail fit's)"})
        cells["recheck_records"] = ("cell", rc_n, {"units": "1", "long_name": "records of the screened cell's "
                                                   "simulation (0: not screened)"})
        cells["recheck_exposure"] = ("cell", rc_T, {"units": "s", "long_name": "simulated time of the screened "
                                                    "cell's simulation"})
        cells["screen_overruled"] = ("cell", overruled, {
            "units": "1", "long_name": "1: screened, but its simulation counted failures or fitted a tail above the "
                                       "screening bound, so it enters the long-term rate as simulated"})
        cells["recheck_roll_max"] = ("cell", rc_max, {"units": "degree",
                                                      "long_name": "largest |roll| of the screened cell's simulation"})
    if lateral is not None:
        cells["lateral_sigma"] = ("cell", asig, {"units": "m/s2", "long_name": "standard deviation of the lateral "
                                                 "acceleration at the crew location in the cell's run"})
        cells["lateral_tail_threshold_sigma"] = ("cell", thr[:, 1], {
            "units": "1", "long_name": "threshold of the extrapolated cell's lateral-acceleration tail fit, in the "
                                       "run's acceleration sigma"})
    disp, dof = dsa.count_dispersion(per_record, weights)
    if lateral is not None:
        cells.attrs.update(lateral_acceleration_limit=acc_lim, crew_height_above_g=lateral["height"],
                           lateral_acceleration_source=std.get(ACC_KEY).cite())
    cells.attrs.update(parametric_cells=int(resonant.sum()), dphi_dzdt=int(bool(cfg.get("dphi_dzdt", False))),
                       warmup_roll_periods=periods,
                       warmup_s=warm_mean,
                       warmup=f"each record simulated from rest for {periods:g} natural roll "
                              f"periods ({warm_mean:.1f} s) before its failures, exposure and "
                              "statistics are counted; a record that capsizes inside it counts nothing (left "
                              f"truncation: {int(lost.sum())} records in {int((lost > 0).sum())} cells), a cell that "
                              f"loses every record is counted from rest ({int(fallback.sum())} cells)")
    cells.attrs.update(ship=ship.name, failure_angle=phi_f, lwl=lwl, count_dispersion_estimate=disp,
                       count_dispersion_dof=dof,
                       screening=f"Gaussian (Rice) bound with roll sigma x {scr['sigma_factor']:g}"
                                 + ("" if lateral is None else " plus the same bound of the lateral acceleration")
                                 + f" below {scr['rate']:g} /s and no roll beyond half the failure angle"
                                 + ("" if lateral is None else " nor acceleration beyond half its limit")
                                 + "; not applied within "
                                 + f"{parametric:g} deg of head and following seas nor where more than "
                                 + f"{float(scr['parametric_fraction']):g} of the sea's variance lies within "
                                 + f"{float(scr['parametric_band']):g} of twice the roll frequency in encounter at a "
                                 + "length along the ship of " + "-".join(f"{x:g}" for x in scr["parametric_wavelength_ratio"])
                                 + " L (parametric roll; records there start from "
                                 + f"{float(cfg['initial_heel_deg']):g} deg heel): a heuristic, not a proven bound")
    # CPU seconds: for the log and the benchmark, not written (the file must not change between runs)
    cells.encoding["cpu"] = {"build": t_build, "screen": t_screen, "simulate": t_sim, "recheck": t_recheck, "total": time.process_time() - t0}
    return annotate(cells)


def assess_dsa(ship: Ship, crit: xr.Dataset, cfg: dict, hydro: xr.Dataset | None = None, std: Standards | None = None,
               progress: bool = False) -> xr.Dataset:
    """The ship's direct stability assessment: cells (rates, methods) and the long-term rate.

    Parameters
    ----------
    crit : the criteria step's dataset (angle of vanishing stability, flooding angle, waterline length).
    cfg : the pipeline's ``dsa`` section.

    Returns
    -------
    Dataset along ``cell`` (and ``part``): the cells of :func:`assess_cells`, the long-term rate and
    its interval (:func:`stabflow.criteria.dsa.long_term_rate`), ``screen_bound`` (the screened
    cells' upper-bound contribution [1/year]) against ``interval_width`` [1/year], the failure angle
    and what governs it, and the DSA criterion row (NOT EVALUATED while no standard is sourced).
    """
    from stabflow import StabflowError
    from stabflow.criteria.verdicts import against

    std = std or Standards()
    phi_f, governs = failure_angle(std, float(crit["heel_vanishing"]), float(crit["flooding_angle"]))
    if not math.isfinite(phi_f):
        raise StabflowError(f"dsa: {ship.name}: {governs}")
    crew_z = float(crit["ea_crew_height"]) if "ea_crew_height" in crit else None
    cells = assess_cells(ship, cfg, phi_f, float(crit["lwl"]), hydro, std, progress, crew_z)
    # declustered failures are taken as Poisson; where the records allow (cells with two or more
    # records and failures, at least MIN_DISPERSION_DOF degrees of freedom) an overdispersion
    # measured from them widens the counted cells' interval (never narrows it)
    disp, dof = cells.attrs["count_dispersion_estimate"], cells.attrs["count_dispersion_dof"]
    used = max(1.0, disp) if dof >= MIN_DISPERSION_DOF else 1.0
    lt = dsa.long_term_rate(cells, float(cfg["alpha"]), dispersion=used)
    # the cells' own rates are in lt as cell_rate (counted cells with their Garwood interval)
    out = cells.drop_vars(["rate", "rate_lo", "rate_hi"]).merge(lt.drop_vars(["method", "probability"]))
    parts = list(lt["part"].values)
    bound = float(lt["part_rate_hi"].values[parts.index("screened")])
    sim = [parts.index(k) for k in ("counted", "extrapolated")]
    width = float(lt["part_rate_hi"].values[sim].sum() - lt["part_rate_lo"].values[sim].sum())  # simulated cells
    out["screen_bound"] = ((), bound, {"units": "1/year", "long_name": "upper bound of the screened cells' contribution"})
    out["interval_width"] = ((), width, {"units": "1/year", "long_name": "width of the simulated cells' interval"})
    out["failure_angle"] = ((), phi_f, {"units": "degree", "long_name": "failure roll angle"})
    recheck = screening_recheck(out, width, float(cfg["alpha"]), used)
    acc_lim = acceleration_limit(std)
    what = "roll beyond the failure angle" + ("" if acc_lim is None else
                                               f" or lateral acceleration beyond {acc_lim:g} m/s2 at the crew location")
    # judged on the rate's interval (stabflow's choice; the circular's own statistical procedure was
    # not readable): PASS when its upper bound meets the standard, FAIL when its lower bound exceeds
    # it, no verdict when it straddles it (more simulation would decide)
    level = 100 * (1 - float(cfg["alpha"]))
    standard = std.get("sgisc.direct_stability_assessment.long_term_standard")
    lo, est, hi = float(lt["rate_lo"]), float(lt["rate"]), float(lt["rate_hi"])
    missing = acceleration_missing(std)
    value, judged = est, "estimate"
    if standard.available:
        if hi <= float(standard.value):
            value, judged = hi, "upper bound"
        elif lo > float(standard.value):
            value, judged = lo, "lower bound"
        else:
            missing.append(f"a decision: the {level:g} % interval [{lo:.4g}, {hi:.4g}] straddles the standard (more "
                           "simulation would decide)")
    row = against(f"DSA long-term failure rate ({what}), {judged} of its {level:g} % interval",
                  "SGISC direct stability assessment", value, "1/year", standard, "<=",
                  note=f"estimate {est:.4g} per year, interval [{lo:.4g}, {hi:.4g}]; failure angle {phi_f:.1f} deg "
                       f"({governs}); the cells assessed hold {100 * cells.attrs['probability_used']:.2f} % of the "
                       f"scatter table's probability; a year at sea in the Rec. 34 North Atlantic, uniform heading "
                       f"over {cells.attrs['heading_span']}, "
                       "equally likely speeds (stabflow's operational assumptions)",
                  missing=missing)
    out.encoding.update(cells.encoding)
    out.attrs["count_dispersion_used"] = used
    out.attrs.update(cells.attrs, failure_angle_governed_by=governs, failure_angle_source=std.get(FAIL_KEY).cite(),
                     standards_overridden="; ".join(std.overrides_summary()) or "none",
                     row_criterion=row.criterion, row_value=row.value,
                     row_limit=math.nan if row.limit is None else row.limit, row_verdict=row.verdict,
                     row_reason=row.reason, row_source=row.source,
                     interval=lt.attrs["interval"], alpha=float(cfg["alpha"]),
                     screening_changes_less_than_interval=int(bound < width), **recheck)
    return out


def screening_recheck(out: xr.Dataset, width: float, alpha: float = 0.05, dispersion: float = 1.0) -> dict:
    """The screening checked by simulation (``screen.recheck``): every screened cell simulated as the
    others (its own seeds, ``recheck_records`` records) counts its declustered failures k_i in its
    exposure T_i. The screened cells' true contribution C = sum p_i r_i is bounded by the Fay & Feuer
    (1997) interval of the weighted Poisson sum sum (p_i / T_i) k_i (:func:`stabflow.criteria.dsa.fay_feuer_interval`,
    ``dispersion`` as the counted cells'), pooled over all screened cells: with every count zero its
    upper bound is -ln(alpha / 2) max_i p_i / T_i, which holds exactly (all counts are zero with
    probability exp(-sum mu_i) <= exp(-C / w_M)). A zero-count cell whose tail was fitted enters with
    its count, 0; the fit decides only whether the cell is overruled. The bound covers the overruled cells
    too (they are in the long-term rate as simulated, so what the screening still changes is
    smaller): it is a bound on what the screening could change even without the overrule, free of
    the selection of the cells that stay screened by their own zero counts.

    Adds ``screen_recheck_rate`` and ``screen_recheck_rate_hi`` [1/year] (the estimate sum p k / T and the
    upper bound) to ``out``; returns the attributes: cells rechecked, their failures, cells overruled
    and their simulated contribution, cells resting on a zero count without a tail fit, the pooled
    weight bound, and the verdict on the issue's test that screening changes the long-term rate by
    less than its interval (``width`` [1/year], the simulated cells' interval width): PASS when the
    upper bound meets it, FAIL when the estimate exceeds it, NOT SHOWN in between (the rechecks too
    short to decide), SKIPPED (with the reason) when nothing was screened or the recheck is off."""
    if "recheck_method" not in out:
        return {"screen_recheck_verdict": "SKIPPED", "screen_recheck_reason": "screen.recheck is off"}
    rc = out["recheck_method"].values.astype(str)
    sel = rc != "none"
    if not sel.any():
        return {"screen_recheck_verdict": "SKIPPED", "screen_recheck_reason": "no cell was screened"}
    yr = dsa.SECONDS_PER_YEAR
    over = out["screen_overruled"].values.astype(bool) if "screen_overruled" in out else np.zeros(len(rc), bool)
    kept = sel & ~over
    p = out["probability"].values
    T = out["recheck_exposure"].values[sel]
    if not (np.all(np.isfinite(T)) and np.all(T > 0)):
        raise ValueError("screening_recheck: every rechecked cell needs an exposure > 0 s")
    # an extrapolated recheck had a zero count (the tail is fitted only then)
    k = np.where(rc[sel] == "counted", out["recheck_failures"].values[sel], 0).astype(float)
    w = p[sel] / T
    est, _, up = (x * yr for x in dsa.fay_feuer_interval(k, w, alpha, dispersion))

    def contribution(mask, var):
        return float(np.sum(p[mask] * out[var].values[mask]) * yr)

    out["screen_recheck_rate"] = ((), est, {"units": "1/year", "long_name": "the screened cells' contribution by "
                                            "their simulation, sum p k / T (estimate)"})
    out["screen_recheck_rate_hi"] = ((), up, {"units": "1/year", "long_name": "upper bound of the screened cells' "
                                              "contribution by their simulation (Fay-Feuer, pooled)"})
    failures = int(k.sum())
    unfitted = int((kept & (rc == "counted") & (out["recheck_failures"].values == 0)).sum())
    verdict = "PASS" if up <= width else "FAIL" if est > width else "NOT SHOWN"
    hours = float(T.sum()) / 3600.0
    return {"screen_recheck_cells": int(sel.sum()), "screen_recheck_failures": failures,
            "screen_recheck_hours": hours, "screen_recheck_w_max": float(np.max(w)) * yr,
            "screen_overruled_cells": int(over.sum()), "screen_overruled_rate": contribution(over, "recheck_rate"),
            "screen_recheck_zero_unfitted": unfitted, "screen_recheck_verdict": verdict,
            "screen_recheck_reason": (f"the {int(sel.sum())} screened cells simulated for {hours:.4g} h in all: "
                                      f"{failures} failures; {int(over.sum())} cells overruled (failures counted or a "
                                      f"fitted tail above the Gaussian bound), {contribution(over, 'recheck_rate'):.3g} "
                                      f"per year, now in the long-term rate as simulated; all screened cells together "
                                      f"contribute {est:.3g} per year by simulation, upper bound {up:.3g} (Fay-Feuer "
                                      f"{100 * (1 - alpha):g} % over their pooled counts, largest weight p/T "
                                      f"{float(np.max(w)) * yr:.3g} per year), against the simulated cells' interval "
                                      f"width {width:.3g}")}
