"""Irregular-sea ensembles: many independent records, statistics streamed record by record.

A *condition* is a ship (with an optional KG override), a seaway (``waves.seaway.Seaway``), speed,
heading, record length, RK4 step, the number of records and the master seed. Record ``r`` is fully
defined by (master seed, r): its wave components come from ``Seaway.components(seed, r)``, every
record starts from the calm-water equilibrium at rest, so any record can be regenerated alone
(``simulate_record``) — the split-time step restarts from states inside records this way.

Records are simulated in batches, in parallel over records (numba ``prange`` in
``_simulate_batch``); each record is the same computation whatever the number of threads, so the
files are bit-identical for any thread count and any sharding. Only statistics are kept
(``record_statistics``): moments, fixed-bin histograms, threshold crossings with the roll rate,
roll peaks and Hilbert-envelope peaks, capsize flag and time, roll autocovariance and response
spectra; full time histories only for the first ``samples`` records.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow.config import Ship
from stabflow.dynamics import coefficients
from stabflow.dynamics._kernels import N_STATE, P_G, S_PITCH, S_RATE, S_ROLL, S_Z, _origin_height, _simulate, _simulate_batch
from stabflow.dynamics.model import initial_state, parameters, section_decay
from stabflow.dynamics.rigid_body import lateral_specific_force
from stabflow.dynamics.tables import SectionTables, kernel_args, section_tables
from stabflow.constants import KNOT
from stabflow.geometry import Sections, build_hull
from stabflow.io import annotate
from stabflow.statistics.signals import SPECTRUM_SEGMENT, crossings, envelope, local_peaks, welch_psd
from stabflow.hydrostatics.statics import compute_statics, equilibrium
from stabflow.waves.seaway import Seaway
from stabflow.dynamics.diffraction import ftab
from stabflow.waves.synthesis import station_wave_table

DOFS = ("heave", "roll", "pitch")
SERIES = ("wave",) + DOFS  # spectra: wave elevation at midships and the three motions
BATCH = 16  # records per parallel batch


@dataclass
class Model:
    """Everything needed to simulate records of one condition."""

    ship: Ship
    cond: dict
    sea: Seaway | None
    sec: Sections
    st: xr.Dataset
    tables: SectionTables
    p: np.ndarray
    s0: np.ndarray
    #: the sections' pressure decay for the d2phi/dzdt term (``dphi_dzdt``), None without it
    decay: object
    roll_period: float
    #: the 6-DOF inputs (``dof: 6`` conditions, :mod:`stabflow.dynamics.manoeuvring`), None for 3-DOF
    six: object = None
    #: the fitted derivative model (``model: derivative`` conditions, :mod:`stabflow.dynamics.derivative`)
    derivative: object = None
    #: the coefficients (mass, inertias, added mass, damping) the model was built with
    co: object = None
    #: the body-linear diffraction force (:class:`stabflow.dynamics.diffraction.Diffraction`) of ships
    #: with ``dynamics.diffraction: capytaine``, 3-DOF volume-based records; None without it
    diffraction: object = None

    @property
    def dt(self) -> float:
        return float(self.cond["dt"])

    @property
    def nwarm(self) -> int:
        """Steps of the warm-up (``warmup_s``): the records start from rest, and their first ``nwarm``
        steps, the start's transient, are left out of the statistics and the exposure."""
        return int(round(float(self.cond.get("warmup_s", 0.0)) / self.dt))

    @property
    def nsteps(self) -> int:
        """Steps of a record: the warm-up and then ``duration``."""
        return self.nwarm + int(round(self.cond["duration"] / self.dt))

    def lost(self, last: int) -> bool:
        """A record whose last step is ``last`` ended (capsized) inside its warm-up: it counts nothing."""
        return self.nwarm > 0 and last <= self.nwarm

    @property
    def speed(self) -> float:
        return float(self.cond["speed_kn"]) * KNOT

    @property
    def curved(self) -> bool:
        """The condition's ``waterline: curved`` (the kernel's cross-beam curvature terms)."""
        return self.cond.get("waterline", "planar") == "curved"

    @property
    def mid_station(self) -> int:
        return int(np.argmin(np.abs(self.sec.x)))


def build_model(ship: Ship, cond: dict, hydro: xr.Dataset | None = None, radiation: xr.Dataset | None = None) -> Model:
    """Cut the hull at ``cond['stations']``, apply the condition's KG, find the equilibrium,
    coefficients (Capytaine ``hydro`` if the ship uses it) and the sectional tables; 6-DOF
    conditions of a ship with ``manoeuvring.heave_pitch_radiation: memory`` take its memory model
    from the ``radiation`` step's dataset ``radiation`` (computed now if None). 3-DOF volume-based
    conditions of a ship with ``dynamics.diffraction: capytaine`` add the body-linear diffraction
    force (:func:`diffraction_for`)."""
    if cond.get("waterline", "planar") == "curved" and cond.get("model", "volume") == "derivative":
        from stabflow import StabflowError

        raise StabflowError(f"config: ensembles: {cond.get('name', '?')}: waterline: curved is a term of the "
                            "volume-based kernel; the derivative model's fit does not carry it")
    s = ship.modified(stations=cond["stations"], kg=cond.get("kg"), dynamics=cond.get("dynamics", {}))
    hull = build_hull(s)
    st = compute_statics(s, hull)
    sec = Sections(hull)
    use_hydro = hydro if s.data["dynamics"].get("hydro") == "capytaine" else None
    co = coefficients(s, sec, st, use_hydro, speed=float(cond["speed_kn"]) * KNOT)
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    decay = section_decay(sec, h0, th0) if cond.get("dphi_dzdt", False) else None
    tables = section_tables(sec, int(cond.get("table_angles", 181)), int(cond.get("table_levels", 101)))
    p = parameters(co, s.rho, float(st["lcg"]), float(st["kg"]), float(cond["heading_deg"]))
    six = None
    if int(cond.get("dof", 3)) == 6:
        if cond.get("lateral_acceleration"):
            from stabflow import StabflowError

            raise StabflowError(f"config: ensembles: {cond.get('name', '?')}: lateral_acceleration is computed for "
                                "3-DOF records only (the 6-DOF sway and yaw accelerations are not in it)")
        from stabflow.dynamics.broaching import manoeuvring_from_ship
        from stabflow.dynamics.manoeuvring import build_six_dof
        from stabflow.dynamics.radiation import ship_memory

        six = build_six_dof(sec, st, co, s.rho, float(cond["heading_deg"]), float(cond["speed_kn"]) * KNOT,
                            manoeuvring_from_ship(s, sec, st), tables=tables,
                            memory=ship_memory(ship, float(st["lcg"]), radiation),
                            waterline=cond.get("waterline", "planar"), dphi_dzdt=bool(cond.get("dphi_dzdt", False)))
    sea = Seaway.from_config(cond["sea"]) if "sea" in cond else None  # regular-wave studies have none
    model = Model(s, cond, sea, sec, st, tables, p, initial_state(sec, st), decay, co.natural_period("roll"), six, co=co)
    if cond.get("model", "volume") == "derivative":
        if six is not None:
            from stabflow import StabflowError

            raise StabflowError(f"config: ensembles: {cond.get('name', '?')}: model: derivative is a heave-roll-pitch "
                                "model (3 DOF); it cannot run with dof: 6")
        from stabflow.config import derivative_fit_settings
        from stabflow.dynamics.derivative import fit_for

        fit = derivative_fit_settings(cond.get("derivative_fit", {}))
        e = sea.edges()  # transfer functions over the seaway's frequencies
        model.derivative = fit_for(model, fit, np.linspace(float(e[0]), float(e[-1]), int(fit["frequencies"])))
    if s.data["dynamics"].get("diffraction", "none") == "capytaine" and six is None and model.derivative is None:
        model.diffraction = diffraction_for(model)
    return model


def diffraction_for(model: Model, heading_deg: float | None = None):
    """The diffraction force of ``model``'s ship at its loading and the condition's heading (or
    ``heading_deg`` [degree]) (:func:`stabflow.dynamics.diffraction.ship_diffraction` at that one
    heading: tens of BEM solves, 10-60 s; kept for the process's other conditions of the same ship,
    loading and heading)."""
    from stabflow.dynamics.diffraction import Diffraction, ship_diffraction

    lcg, kg = float(model.st["lcg"]), float(model.st["kg"])
    rest = model.s0
    h0 = _origin_height(rest[S_Z], 0.0, rest[S_PITCH], lcg, kg)
    heading = float(model.cond["heading_deg"] if heading_deg is None else heading_deg)
    table = ship_diffraction(model.ship, (h0, float(rest[S_PITCH]), lcg, kg), model.ship.rho, (heading,))
    return Diffraction(table, heading)


def wave_table(model: Model, record: int, dtype=np.float32, components=None) -> np.ndarray:
    """Wave table (2 nsteps + 1, nst, nq) of record ``record`` (or of its ``components`` when already
    drawn) on the half-step grid."""
    amp, w, ph = model.sea.components(model.cond["seed"], record) if components is None else components
    t_half = np.arange(2 * model.nsteps + 1) * 0.5 * model.dt
    return station_wave_table(amp, w, ph, model.sec.x, model.cond["heading_deg"], model.speed, t_half,
                              model.decay, dtype=dtype, curvature=model.curved)


def force_table(model: Model, components, times) -> np.ndarray:
    """The diffraction force (nt, 6) of the wave ``components`` at ``times`` (the kernel's ``ftab``,
    :func:`stabflow.dynamics.diffraction.ftab`), or a (0, 6) array for a model without it."""
    return ftab(model.diffraction, components, model.speed, float(model.cond["heading_deg"]), times)


def volume_tables(model: Model, record: int):
    """(wave table, diffraction force table) of a volume-based 3-DOF record on the half-step grid, its
    components drawn once."""
    comps = model.sea.components(model.cond["seed"], record)
    t_half = np.arange(2 * model.nsteps + 1) * 0.5 * model.dt
    return wave_table(model, record, components=comps), force_table(model, comps, t_half)


def record_table(model: Model, record: int):
    """The record's excitation on the half-step grid, computed once per record: (the stations' wave
    table, the diffraction force table) (volume-based 3-DOF), the derivative model's coefficient
    table, or None (6-DOF: the wave is tabulated around the ship chunk by chunk)."""
    if model.six is not None:
        return None
    if model.derivative is not None:
        t_half = np.arange(2 * model.nsteps + 1) * 0.5 * model.dt
        return model.derivative.coefficient_table(model.sea.components(model.cond["seed"], record), t_half,
                                                  dtype=np.float32)
    return volume_tables(model, record)


def state_size(model: Model) -> int:
    """Length of the state vector of the condition's model (6-DOF carries the rudder, the autopilot and
    any heave-pitch radiation memory)."""
    if model.six is not None:
        return model.six.s0.size
    return N_STATE


def advance(model: Model, record: int, table, s, n0: int, n1: int, out: np.ndarray, phi_cap: float = np.radians(90.0),
            components=None) -> int:
    """Steps ``n0`` to ``n1`` of record ``record`` from state ``s`` (at step n0) on the time grid,
    with the record's ``table`` (:func:`record_table`); ``out`` (nsteps + 1, state size) receives rows
    n0..; returns the last step done (below n1 when |roll| passed ``phi_cap`` [rad])."""
    s = np.asarray(s, float).copy()
    if model.six is not None:
        from stabflow.dynamics.manoeuvring import run_six_dof

        comps = model.sea.components(model.cond["seed"], record) if components is None else components
        st6, n, _ = run_six_dof(model.six, comps, (n1 - n0) * model.dt, model.dt, phi_cap_deg=np.degrees(phi_cap),
                                s0=s, t0=n0 * model.dt)
        out[n0: n0 + n + 1] = st6
        return n0 + n
    if model.derivative is not None:
        from stabflow.dynamics.derivative import step_derivative

        return step_derivative(model.derivative, table, model.dt, n0, n1, s, phi_cap, out)
    wtab, ftab = table
    return _simulate(*kernel_args(model.sec, model.tables), model.p, wtab, ftab, model.dt, n0, n1, s, phi_cap, out,
                     np.empty((0, 6)))


def simulate_record(model: Model, record: int, s_start=None, n_start: int = 0, n_end: int | None = None,
                    phi_cap_deg: float = 90.0, wtab=None):
    """Regenerate record ``record`` (optionally from state ``s_start`` at step ``n_start`` up to step
    ``n_end``; ``wtab`` the record's table when already computed). Returns (states (nsteps + 1, state
    size) — rows before ``n_start`` unset — and the last step done). Bit-identical to the same steps
    of the ensemble run.

    6-DOF conditions: states with the rudder and autopilot states; bit-identical to the ensemble run
    from the start of the record; a restart inside it tabulates the wave around the ship on other
    chunks (float32 table values, differences of order 1e-7 relative)."""
    n_end = model.nsteps if n_end is None else n_end
    table = record_table(model, record) if wtab is None else wtab
    out = np.empty((model.nsteps + 1, state_size(model)))
    s0 = (model.six.s0 if model.six is not None else model.s0) if s_start is None else s_start
    return out, advance(model, record, table, s0, n_start, n_end, out, np.radians(phi_cap_deg))


def bins(cond: dict) -> dict[str, np.ndarray]:
    """Fixed histogram bin edges: roll [degree], heave [m], pitch [degree]."""
    h = cond["histogram"]
    return {"roll": np.arange(-90.0, 90.0 + 1e-9, h["roll_bin_deg"]),
            "heave": np.arange(-h["heave_range"], h["heave_range"] + 1e-9, h["heave_bin"]),
            "pitch": np.arange(-h["pitch_range_deg"], h["pitch_range_deg"] + 1e-9, h["pitch_bin_deg"])}


def record_statistics(model: Model, record: int, states: np.ndarray, last: int, wave_mid: np.ndarray) -> dict:
    """Everything kept from one record (``states`` (nsteps + 1, N_STATE), valid up to ``last``).

    The warm-up's steps (``model.nwarm``) are left out of every statistic and of the exposure
    (``steps``: the steps counted, after ``model.nwarm``); times and step indices
    stay those of the record. A record that ends inside its warm-up (a capsize) is *lost*: it counts
    no steps, no capsize and no statistic (``lost`` 1; its ``roll_max`` is the whole record's, so
    that no one reads it as calm), as the 1-DOF capsize validation's warm-up does. For a stationary
    failure rate this is left truncation: the records that reach the end of the warm-up carry the
    rate, whatever happened before (keeping a lost record's capsize with its short exposure, while the
    others drop theirs, would raise the pooled rate by up to (warm-up + duration) / duration)."""
    cond = model.cond
    n = last + 1
    lost = model.lost(last)
    w = n if lost else model.nwarm
    t = np.arange(n) * model.dt
    h = states[:n, S_Z] - model.s0[S_Z]
    roll = np.degrees(states[:n, S_ROLL])
    pitch = np.degrees(states[:n, S_PITCH] - model.s0[S_PITCH])
    rate = np.degrees(states[:n, S_RATE + S_ROLL])
    whole = float(np.abs(roll).max())
    tw, h, roll, pitch, rate = t[w:], h[w:], roll[w:], pitch[w:], rate[w:]
    series = {"heave": h, "roll": roll, "pitch": pitch}
    out = {"steps": 0 if lost else last - w, "lost": int(lost),
           "capsized": int(last < model.nsteps and not lost),
           "capsize_time": float(t[-1]) if last < model.nsteps and not lost else np.nan,
           "roll_max": whole if lost else float(np.abs(roll).max()),
           "moments": np.array([[np.sum(s**k) for k in range(1, 5)] for s in series.values()])}
    edges = bins(cond)
    out["hist"] = {k: np.histogram(v, edges[k])[0] for k, v in series.items()}
    ev = []
    for j, thr in enumerate(cond["thresholds_deg"]):
        for side in (1, -1):
            tc, rc, nc = crossings(tw, roll, rate, side * thr, up=side > 0)
            ev.append(np.column_stack([np.full(len(tc), j), np.full(len(tc), side), tc, rc, nc + w]))
    out["crossings"] = np.concatenate(ev) if ev else np.zeros((0, 5))
    floor = cond["peak_floor_deg"]
    tp, vp = local_peaks(tw, roll, floor)
    tm, vm = local_peaks(tw, -roll, floor)
    order = np.argsort(np.concatenate([tp, tm]), kind="stable")
    out["peaks"] = np.column_stack([np.concatenate([tp, tm]), np.concatenate([vp, -vm])])[order]
    env = envelope(roll)
    te, ve = local_peaks(tw, env, floor)
    out["envelope_peaks"] = np.column_stack([te, ve])
    # autocovariance sums (zero-padded FFT) and Welch spectra, for records long enough
    maxlag = int(round(cond["max_lag"] / model.dt))
    x = roll - roll.mean() if len(roll) else roll
    nfft = 1 << int(np.ceil(np.log2(2 * max(len(x), maxlag + 1))))
    fx = np.fft.rfft(x, nfft)
    acov = np.fft.irfft(fx * np.conj(fx), nfft)[: maxlag + 1]
    cnt = np.maximum(len(x) - np.arange(maxlag + 1), 0)
    out["acov"] = np.where(cnt > 0, acov, 0.0)
    out["acov_n"] = cnt
    out["psd"] = welch_psd(np.array([wave_mid[w:n], h, roll, pitch]), model.dt) if len(tw) >= SPECTRUM_SEGMENT else None
    la = cond.get("lateral_acceleration")
    if la:
        acc = lateral_specific_force(states[:n], model.dt, float(la["height"]), float(model.p[P_G]))
        out["lateral"] = lateral_statistics(tw, acc[w:], la)
        if lost:
            out["lateral"]["max"] = float(np.abs(acc).max())  # the whole record's, as roll_max
    return out


def lateral_statistics(t: np.ndarray, acc: np.ndarray, la: dict) -> dict:
    """What is kept of a record's lateral acceleration ``acc`` [m/s^2] at the crew location
    (condition's ``lateral_acceleration``): crossings of +-each limit (limit index, side, time), signed
    local peaks of |acc| above ``peak_floor``, the sum and sum of squares, the largest |acc| and the
    zero up-crossings."""
    ev = []
    for j, lim in enumerate(la["limits"]):
        for side in (1, -1):
            tc, _, _ = crossings(t, acc, acc, side * float(lim), up=side > 0)  # no rate kept
            ev.append(np.column_stack([np.full(len(tc), j), np.full(len(tc), side), tc]))
    floor = float(la["peak_floor"])
    tp, vp = local_peaks(t, acc, floor)
    tm, vm = local_peaks(t, -acc, floor)
    order = np.argsort(np.concatenate([tp, tm]), kind="stable")
    return {"crossings": np.concatenate(ev), "peaks": np.column_stack([np.concatenate([tp, tm]),
                                                                         np.concatenate([vp, -vm])])[order],
            "sums": np.array([acc.sum(), (acc**2).sum()]), "max": float(np.abs(acc).max()) if len(acc) else 0.0,
            "zero_upcrossings": len(crossings(t, acc, acc, 0.0, up=True)[0])}



def _events(rows, rec, width):
    return np.concatenate([np.column_stack([np.full(len(r), k), r]) for k, r in zip(rec, rows)]) if rows else np.zeros((0, width + 1))


def six_dof_events(model: Model, states: np.ndarray, last: int) -> dict:
    """Broaching and surf-riding of a 6-DOF record (states up to ``last``; the celerity of the
    spectral peak's deep-water wave), as the broaching step's event detection."""
    from stabflow.constants import G
    from stabflow.dynamics import _kernels_6dof as K6
    from stabflow.dynamics.manoeuvres import record_events
    from stabflow.dynamics.manoeuvring import six_dof_dataset

    cond = model.cond
    status = K6.CAPSIZED if last < model.nsteps else K6.OK
    if model.lost(last):  # lost in its warm-up (record_statistics): no event
        return {"broached": 0, "broach_time": np.nan, "surf_riding": 0}
    w = model.nwarm  # as record_statistics: the warm-up left out
    ev = record_events(six_dof_dataset(model.six, states[w:], model.dt, status), broach_deg=float(cond["broach_deg"]),
                       celerity=G / model.sea.modal_frequency, surf_tolerance=float(cond["surf_tolerance"]),
                       surf_min_s=float(cond["surf_min_s"]), heading_deg=float(cond["heading_deg"]))
    return {"broached": ev["broach"], "broach_time": w * model.dt + ev["broach_time"] if ev["broach"] else np.nan,
            "surf_riding": ev["surf_riding"]}


def run_shard(model: Model, records: range, progress: bool = True) -> xr.Dataset:
    """Simulate ``records`` in parallel batches and return the shard's statistics dataset."""
    from tqdm import tqdm

    cond = model.cond
    edges = bins(cond)
    per = []
    samples = {}
    args = kernel_args(model.sec, model.tables)
    recs = list(records)
    bar = tqdm(total=len(recs), desc=f"{model.ship.name} records {recs[0] if recs else 0}-", disable=not progress, mininterval=10,
               unit="rec")
    if model.six is not None or model.derivative is not None:
        # 6-DOF (the wave is tabulated around the ship as it moves) and the derivative model (its
        # coefficient table dominates): one record at a time, through simulate_record
        t_mid = np.arange(model.nsteps + 1) * model.dt
        for r in recs:
            states, last = simulate_record(model, r)
            amp, w, ph = model.sea.components(cond["seed"], r)
            # wave elevation at midships on the mean track (the spectra's reference series)
            wave_mid = station_wave_table(amp, w, ph, model.sec.x[[model.mid_station]], cond["heading_deg"], model.speed,
                                          t_mid)[:, 0, 0]
            out = states[:, :N_STATE]
            per.append(record_statistics(model, r, out, int(last), wave_mid))
            if model.six is not None:
                per[-1].update(six_dof_events(model, states[: last + 1], last))
            if r < cond["samples"]:
                samples[r] = (out, int(last), wave_mid)
            bar.update()
        bar.close()
        return shard_dataset(model, recs, per, samples, edges)
    for b0 in range(0, len(recs), BATCH):
        batch = recs[b0: b0 + BATCH]
        pairs = [volume_tables(model, r) for r in batch]
        tabs = np.stack([w for w, _ in pairs])
        ftabs = np.stack([f for _, f in pairs])
        out = np.empty((len(batch), model.nsteps + 1, N_STATE))
        last = np.empty(len(batch), np.int64)
        _simulate_batch(*args, model.p, tabs, ftabs, model.dt, model.nsteps, model.s0, np.radians(90.0), out, last)
        for q, r in enumerate(batch):
            wave_mid = tabs[q, ::2, model.mid_station, 0].astype(float)
            per.append(record_statistics(model, r, out[q], int(last[q]), wave_mid))
            if r < cond["samples"]:
                samples[r] = (out[q], int(last[q]), wave_mid)
        bar.update(len(batch))
    bar.close()
    return shard_dataset(model, recs, per, samples, edges)


def shard_dataset(model: Model, recs, per, samples, edges) -> xr.Dataset:
    cond = model.cond
    nrec = len(recs)
    cr = _events([p["crossings"] for p in per], recs, 5)
    pk = _events([p["peaks"] for p in per], recs, 2)
    ep = _events([p["envelope_peaks"] for p in per], recs, 2)
    maxlag = int(round(cond["max_lag"] / model.dt))
    psds = [p["psd"] for p in per if p["psd"] is not None]
    nfreq = SPECTRUM_SEGMENT // 2 + 1
    freq = np.fft.rfftfreq(SPECTRUM_SEGMENT, model.dt) * 2 * np.pi
    # the variables are gathered in order and the dataset is built once (each Dataset assignment
    # re-merges every variable: ~30 ms per one-record shard)
    var = {name: xr.Variable(*dv) for name, dv in {
        "steps": ("record", np.array([p["steps"] for p in per], np.int64)),
        "warmup_lost": ("record", np.array([p["lost"] for p in per], np.int8)),
        "capsized": ("record", np.array([p["capsized"] for p in per], np.int8)),
        "capsize_time": ("record", np.array([p["capsize_time"] for p in per])),
        "roll_max": ("record", np.array([p["roll_max"] for p in per])),
        "moment_sums": (("record", "dof", "order"), np.array([p["moments"] for p in per]).reshape(nrec, 3, 4)),
        "crossing_record": ("crossing", cr[:, 0].astype(np.int64)),
        "crossing_threshold": ("crossing", cr[:, 1].astype(np.int64)),
        "crossing_side": ("crossing", cr[:, 2].astype(np.int8)),
        "crossing_time": ("crossing", cr[:, 3]),
        "crossing_roll_rate": ("crossing", cr[:, 4]),
        "crossing_step": ("crossing", cr[:, 5].astype(np.int64)),
        "peak_record": ("peak", pk[:, 0].astype(np.int64)),
        "peak_time": ("peak", pk[:, 1].astype(np.float32)),
        "peak_value": ("peak", pk[:, 2].astype(np.float32)),
        "envelope_peak_record": ("envelope_peak", ep[:, 0].astype(np.int64)),
        "envelope_peak_time": ("envelope_peak", ep[:, 1]),
        "envelope_peak_value": ("envelope_peak", ep[:, 2]),
        "acov_sum": ("lag", np.sum([p["acov"] for p in per], axis=0) if per else np.zeros(maxlag + 1)),
        "acov_count": ("lag", np.sum([p["acov_n"] for p in per], axis=0) if per else np.zeros(maxlag + 1)),
        "psd_count": ((), len(psds)),
    }.items()}
    var.update({c: xr.Variable(c, x) for c, x in (
        ("record", np.array(recs, np.int64)), ("dof", list(DOFS)), ("order", [1, 2, 3, 4]),
        ("threshold", np.array(cond["thresholds_deg"], float)), ("lag", np.arange(maxlag + 1) * model.dt),
        ("frequency", freq))})
    if cond.get("lateral_acceleration"):  # the crew location's lateral acceleration
        lat = [p["lateral"] for p in per]
        lc = _events([q["crossings"] for q in lat], recs, 3)
        lp = _events([q["peaks"] for q in lat], recs, 2)
        var["lateral_crossing_record"] = xr.Variable("lateral_crossing", lc[:, 0].astype(np.int64))
        var["lateral_crossing_limit"] = xr.Variable("lateral_crossing", lc[:, 1].astype(np.int64))
        var["lateral_crossing_side"] = xr.Variable("lateral_crossing", lc[:, 2].astype(np.int8))
        var["lateral_crossing_time"] = xr.Variable("lateral_crossing", lc[:, 3])
        var["lateral_peak_record"] = xr.Variable("lateral_peak", lp[:, 0].astype(np.int64))
        var["lateral_peak_time"] = xr.Variable("lateral_peak", lp[:, 1])
        var["lateral_peak_value"] = xr.Variable("lateral_peak", lp[:, 2])
        var["lateral_max"] = xr.Variable("record", np.array([q["max"] for q in lat]))
        var["lateral_sum"] = xr.Variable("record", np.array([q["sums"][0] for q in lat]))
        var["lateral_sum_squares"] = xr.Variable("record", np.array([q["sums"][1] for q in lat]))
        var["lateral_zero_upcrossings"] = xr.Variable("record", np.array([q["zero_upcrossings"] for q in lat], np.int64))
        var["lateral_limit"] = xr.Variable("lateral_limit", np.array(cond["lateral_acceleration"]["limits"], float))
    if model.six is not None:  # 6-DOF events per record
        var["broached"] = xr.Variable("record", np.array([p["broached"] for p in per], np.int8))
        var["broach_time"] = xr.Variable("record", np.array([p["broach_time"] for p in per]))
        var["surf_riding"] = xr.Variable("record", np.array([p["surf_riding"] for p in per], np.int8))
    psd_sum = np.sum(psds, axis=0) if psds else np.zeros((len(SERIES), nfreq))
    for j, s in enumerate(SERIES):  # one variable per series: each carries its own units
        var[f"{s}_psd_sum"] = xr.Variable("frequency", psd_sum[j])
    for k in DOFS:
        var[f"hist_{k}"] = xr.Variable(f"{k}_bin", np.sum([p["hist"][k] for p in per], axis=0).astype(np.int64)
                                       if per else np.zeros(len(edges[k]) - 1, np.int64))
        var[f"{k}_bin"] = xr.Variable(f"{k}_bin", 0.5 * (edges[k][1:] + edges[k][:-1]))
    if samples:
        keys = sorted(samples)
        n = model.nsteps + 1
        arr = np.full((len(keys), 5, n), np.nan)
        for q, r in enumerate(keys):
            st, last, wm = samples[r]
            m = last + 1
            arr[q, 0, :m] = wm[:m]
            arr[q, 1, :m] = st[:m, S_Z] - model.s0[S_Z]
            arr[q, 2, :m] = np.degrees(st[:m, S_ROLL])
            arr[q, 3, :m] = np.degrees(st[:m, S_PITCH] - model.s0[S_PITCH])
            arr[q, 4, :m] = np.degrees(st[:m, S_RATE + S_ROLL])
        for j, name in enumerate(["sample_wave", "sample_heave", "sample_roll", "sample_pitch", "sample_roll_rate"]):
            var[name] = xr.Variable(("sample", "time"), arr[:, j])
        var["sample"] = xr.Variable("sample", np.array(keys, np.int64))
        var["time"] = xr.Variable("time", np.arange(n) * model.dt)
    ds = xr.Dataset(var)  # the variables named after their dimension are its coordinates
    ds.attrs.update(condition_attrs(model))
    return annotate(ds)


def condition_attrs(model: Model) -> dict:
    c = model.cond
    return {"ship": model.ship.name, "condition": c["name"], "spectrum": model.sea.kind, "hs": model.sea.hs,
            "tp": model.sea.tp if model.sea.tp is not None else -1.0, "n_components": model.sea.n_components,
            "discretisation": model.sea.method, "randomise": int(model.sea.randomise),
            "speed_kn": float(c["speed_kn"]), "heading_deg": float(c["heading_deg"]), "duration": float(c["duration"]),
            "warmup_s": model.nwarm * model.dt,
            "dt": model.dt, "seed": int(c["seed"]), "stations": len(model.sec.x), "kg": float(model.st["kg"]),
            "dof": int(c.get("dof", 3)), "model": str(c.get("model", "volume")),
            "gm": float(model.st["gm"]), "roll_period": model.roll_period, "diffraction": diffraction_label(model)}


def diffraction_label(model: Model) -> str:
    """What the records carry of the diffraction force (an attribute of every ensemble file)."""
    asked = model.ship.data["dynamics"].get("diffraction", "none") == "capytaine"
    if model.diffraction is not None:
        return f"capytaine (zero speed, panels resolve w <= {model.diffraction.omega_max:.3g} rad/s)"
    if asked and model.six is not None:
        return "none: the 6-DOF model runs without it (the ship asks for capytaine)"
    if asked:
        return "none: the derivative model runs without it (the ship asks for capytaine)"
    return "none"


def sample_counts(steps, lost=None) -> np.ndarray:
    """Samples in each record's statistics: steps + 1, none for a record lost in its warm-up."""
    n = np.asarray(steps, float) + 1.0
    return n if lost is None else np.where(np.asarray(lost) != 0, 0.0, n)


def record_samples(ens: xr.Dataset) -> xr.DataArray:
    """Samples in each record's statistics of a merged ensemble (:func:`sample_counts`; shards
    written before 2026-12-07 have no ``warmup_lost``)."""
    lost = ens["warmup_lost"].values if "warmup_lost" in ens else None
    return xr.DataArray(sample_counts(ens["steps"].values, lost), coords={"record": ens["record"].values},
                        dims="record")


def merge(shards: list[xr.Dataset]) -> xr.Dataset:
    """Merge shard datasets (in record order) into the condition's ensemble dataset, with derived
    statistics: mean, standard deviation, skewness and kurtosis per DOF, roll autocorrelation,
    mean response spectra, exposure time, capsize count and rate."""
    shards = sorted(shards, key=lambda d: int(d["record"][0]) if d.sizes["record"] else 0)
    first = shards[0].variables
    # (warmup_lost: shards written before 2026-12-07 have none)
    rec_vars = ["steps"] + (["warmup_lost"] if "warmup_lost" in first else [])
    rec_vars += ["capsized", "capsize_time", "roll_max", "moment_sums"]
    rec_vars += [v for v in ("broached", "broach_time", "surf_riding", "lateral_max", "lateral_sum", "lateral_sum_squares",
                             "lateral_zero_upcrossings") if v in first]
    ev = {"crossing": [v for v in shards[0].data_vars if v.startswith("crossing_")],
          "peak": ["peak_record", "peak_time", "peak_value"],
          "envelope_peak": ["envelope_peak_record", "envelope_peak_time", "envelope_peak_value"]}
    if "lateral_max" in first:
        ev.update(lateral_crossing=[v for v in shards[0].data_vars if v.startswith("lateral_crossing_")],
                  lateral_peak=["lateral_peak_record", "lateral_peak_time", "lateral_peak_value"])

    # The dataset is built once from its variables, in the order (and with the values, dtypes,
    # attributes and encodings) that concatenating the shards and assigning the statistics one group
    # after another gives: each Dataset assignment re-merged and re-aligned every variable, which
    # made merging a one-record shard (a DSA cell: 1,000 or more a ship) cost ~40 ms.
    def joined(names, dim):
        # the shards' variables end to end along dim (a single shard's as they are), as xr.concat's
        if len(shards) == 1:
            return {v: first[v].copy(deep=False) for v in names}
        return {v: xr.Variable.concat([d.variables[v] for d in shards], dim) for v in names}

    def index(name, group):
        # a dimension coordinate end to end, with the first shard's attributes and encoding (as
        # xr.concat gives; IndexVariable.concat alone drops the encoding)
        v = xr.IndexVariable.concat([d[name] for d in group], name)
        v.encoding = dict(group[0][name].encoding)
        return v

    var = joined(rec_vars, "record")
    for c in [c for c in first if c in ("record", "dof", "order")]:  # in the first shard's order
        var[c] = index(c, [d.variables for d in shards]) if c == "record" else first[c].copy(deep=False)
    for dim, names in ev.items():
        var.update(joined(names, dim))
    # the sums over the shards, each after its coordinate (lag, frequency, bins), without attributes
    # or encoding, as DataArray arithmetic leaves them
    sums = ["acov_sum", "acov_count", "psd_count"] + [f"{s}_psd_sum" for s in SERIES] + [f"hist_{k}" for k in DOFS]
    for v in sums:
        dims = first[v].dims
        for c in dims:
            var.setdefault(c, first[c])
        var[v] = xr.Variable(dims, sum(d.variables[v].values for d in shards))
    smp = [d.variables for d in shards if "sample" in d.dims]
    if smp:
        var.update({v: xr.Variable.concat([d[v] for d in smp], "sample") for v in smp[0] if v.startswith("sample_")})
        for c in [c for c in smp[0] if c in ("sample", "time")]:
            var[c] = index(c, smp) if c == "sample" else smp[0][c]
    var["threshold"] = first["threshold"]
    dt = shards[0].attrs["dt"]
    steps = var["steps"].values
    n = sample_counts(steps, var["warmup_lost"].values if "warmup_lost" in var else None)
    dofs = list(first["dof"].values)
    orders = list(first["order"].values)
    # raw moment sums per DOF: (dof, order) summed over the records
    S = np.nansum(var["moment_sums"].values, axis=0)  # as xarray's sum (NaN skipped)
    S1, S2, S3, S4 = (S[:, orders.index(k)] for k in (1, 2, 3, 4))
    N = n.sum() or np.nan  # no sample: every record lost in its warm-up (warmup_lost_count), moments NaN
    mean = S1 / N
    m2 = S2 / N - mean**2
    m3 = S3 / N - 3 * mean * S2 / N + 2 * mean**3
    m4 = S4 / N - 4 * mean * S3 / N + 6 * mean**2 * S2 / N - 3 * mean**4
    for k in DOFS:  # heave [m], roll and pitch [degree]: one variable each, with its units
        var[f"{k}_mean"] = xr.Variable((), mean[dofs.index(k)])
        var[f"{k}_std"] = xr.Variable((), np.sqrt(m2[dofs.index(k)]))
    var["skewness"] = xr.Variable(("dof",), m3 / m2**1.5)
    var["kurtosis"] = xr.Variable(("dof",), m4 / m2**2)
    count = var["acov_count"].values
    acf = var["acov_sum"].values / np.where(count > 0, count, np.nan)
    var["roll_autocorrelation"] = xr.Variable(("lag",), acf / acf[0])
    for s in SERIES:
        var[f"{s}_psd"] = var[f"{s}_psd_sum"] / max(int(var["psd_count"].values), 1)
    hours = float(steps.sum()) * dt / 3600.0
    var["exposure_hours"] = xr.Variable((), hours)
    if "warmup_lost" in var:
        var["warmup_lost_count"] = xr.Variable((), int(var["warmup_lost"].values.sum()))
    caps = var["capsized"].values
    var["capsize_count"] = xr.Variable((), int(caps.sum()))
    # no exposure: every record capsized inside its warm-up (warmup_lost_count says so): no rate
    var["capsize_rate"] = xr.Variable((), int(caps.sum()) / hours if hours > 0 else np.nan)
    if "lateral_max" in first:
        mean_a = float(np.nansum(var["lateral_sum"].values)) / N
        var["lateral_acceleration_std"] = xr.Variable((), float(np.sqrt(max(float(np.nansum(var["lateral_sum_squares"].values))
                                                                             / N - mean_a**2, 0.0))))
        var["lateral_zero_upcrossing_rate"] = xr.Variable((), float(var["lateral_zero_upcrossings"].values.sum())
                                                          / (hours * 3600.0) if hours > 0 else np.nan)
        var["lateral_limit"] = first["lateral_limit"]
    if "broached" in first:
        var["broach_count"] = xr.Variable((), int(var["broached"].values.sum()))
        var["surf_riding_count"] = xr.Variable((), int(var["surf_riding"].values.sum()))
    out = xr.Dataset(var)  # the variables named after their dimension are its coordinates
    out.attrs.update(shards[0].attrs)
    out.attrs["n_records"] = int(out.sizes["record"])
    return annotate(out)
