"""Derivative model of heave, roll and pitch (paper 001, eqs 1-7), fitted from stabflow's own
volume-based FK + HS forces instead of a panel code.

Restoring forces
    The generalized restoring forces R(q) (heave force with gravity, roll and pitch moments about
    G, the same projection as the time-domain model, :mod:`stabflow.dynamics.rigid_body`) are
    sampled at systematic hull positions around the calm-water equilibrium, q = (z, phi, theta)
    relative to it, and represented by the third-order Taylor polynomial of paper 001 eqs 1-3: the
    value and the first derivatives at equilibrium by central differences (so GM and the heave and
    pitch stiffness are exact), the second- and third-order terms by least squares over the grid; heave and pitch even in roll (1, z, theta, z^2, phi^2, theta^2, z theta, z^3,
    z^2 theta, phi^2 z, phi^2 theta, theta^2 z, theta^3), roll odd (phi, z phi, phi theta,
    z^2 phi, phi^3, theta^2 phi, z phi theta).
Wave-dependent coefficients
    In a regular wave of frequency omega and amplitude a the wave part R(q, chi) - R(q) at wave
    phase chi (the forces depend on the instantaneous wave only, so phase sampling replaces time
    sampling and the result does not depend on speed) is fitted at each phase with the terms up to
    third order in (z, phi, theta) (paper 001 eqs 1-3 write those to second order, Z_zeta_z(t) z,
    ..., K_zeta_phi(t) phi, ...; the third-order ones, e.g. phi^3 in roll, carry the change of the
    GZ curve's shape in the wave at large heel). The constant term is the wave excitation Z_w, K_w,
    M_w; all twenty terms in every row, so oblique seas keep their asymmetric terms. The first harmonic over chi divided by a is the transfer
    function of each coefficient (paper 001 step c). Terms of second order in the wave amplitude
    (the paper's Z_zeta_zeta_z ...) have no linear transfer function; their phase mean per a^2
    (``mean_over_a2``, e.g. the mean change of GM in the wave) is added as a constant,
    sum_n a_n^2 m(omega_n); their difference-frequency oscillation is left out.
Irregular seas
    Each coefficient is a sum over the wave components of a_n |T(omega_n)| cos(psi_n + arg T) at the
    encounter frequency (paper 001 eqs 4-7), from the same components (seed, record) as the
    ensembles. Mass (rigid body + added) and damping are those of the time-domain model at
    equilibrium (constant), the quadratic roll damping with its running amplitude as there.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import product

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.dynamics import _kernels as K
from stabflow.dynamics import _kernels_derivative as KD
from stabflow.dynamics.rigid_body import generalized_system
from stabflow.dynamics.tables import kernel_args
from stabflow.io import annotate
from stabflow.waves.synthesis import _time_series_table, encounter_frequency, one_blas_thread, station_wave_table

FORCES = ("heave", "roll", "pitch")
#: calm-water restoring terms (z, phi, theta exponents), paper 001 eqs 1-3
EVEN_TERMS = ((0, 0, 0), (1, 0, 0), (0, 0, 1), (2, 0, 0), (0, 2, 0), (0, 0, 2), (1, 0, 1), (3, 0, 0), (2, 0, 1),
              (1, 2, 0), (0, 2, 1), (1, 0, 2), (0, 0, 3))
ODD_TERMS = ((0, 1, 0), (1, 1, 0), (0, 1, 1), (2, 1, 0), (0, 3, 0), (0, 1, 2), (1, 1, 1))
CALM_TERMS = EVEN_TERMS + ODD_TERMS
#: wave-dependent terms: the excitation and the coefficients of every monomial up to third order
WAVE_TERMS = tuple(e for d in range(4) for e in product(range(4), repeat=3) if sum(e) == d)


_CEXP = np.array(CALM_TERMS, np.int64)
_WEXP = np.array(WAVE_TERMS, np.int64)


def term_names(terms) -> list[str]:
    """Readable monomials, e.g. (1, 2, 0) -> 'z phi^2'; (0, 0, 0) -> '1'."""
    out = []
    for e in terms:
        parts = [v + (f"^{k}" if k > 1 else "") for v, k in zip(("z", "phi", "theta"), e) if k]
        out.append(" ".join(parts) or "1")
    return out


def _design(x: np.ndarray, terms, scale) -> np.ndarray:
    """Columns x0^e0 x1^e1 x2^e2 of the scaled positions x (n, 3) / scale."""
    xs = x / np.asarray(scale)
    return np.column_stack([np.prod(xs ** np.array(e), axis=1) for e in terms])


def _taylor_fit(rel, R, R0, dR, terms, ranges) -> tuple[np.ndarray, np.ndarray]:
    """Taylor coefficients (..., n_terms) of ``terms`` for samples ``R`` (..., n) at positions ``rel``
    (n, 3): the constant ``R0`` (...) and first derivatives ``dR`` (..., 3) as given (the value and
    central differences at equilibrium: the paper's derivatives), the higher-order terms by least
    squares over the grid. Returns (coefficients, fitted values (..., n))."""
    lead = R.shape[:-1]
    out = np.zeros(lead + (len(terms),))
    fixed = np.zeros(R.shape)
    for j, e in enumerate(terms):
        if sum(e) == 0:
            out[..., j] = R0
            fixed += np.asarray(R0)[..., None]
        elif sum(e) == 1:
            k = int(np.argmax(e))
            out[..., j] = dR[..., k]
            fixed += dR[..., k][..., None] * rel[:, k]
    high = [j for j, e in enumerate(terms) if sum(e) > 1]
    if high:
        A = _design(rel, [terms[j] for j in high], ranges)
        y = (R - fixed).reshape(-1, R.shape[-1]).T
        with one_blas_thread():  # LAPACK's rounding depends on its threads: the same fit in every job
            c, *_ = np.linalg.lstsq(A, y, rcond=None)
        out[..., high] = (c / np.array([np.prod(np.asarray(ranges) ** np.array(terms[j])) for j in high])[:, None]).T.reshape(
            lead + (len(high),))
        fixed += (A @ c).T.reshape(R.shape)
    return out, fixed


@dataclass
class DerivativeModel:
    """The fitted derivative model of one ship and loading at one wave heading (see module doc)."""

    p: np.ndarray  #: parameter vector of the time-domain model (mass, damping, B44q profile)
    s0: np.ndarray  #: equilibrium state (N_STATE,)
    q0: np.ndarray  #: equilibrium (z_G [m], phi, theta [rad])
    minv: np.ndarray  #: (3, 3) inverse generalized mass at equilibrium
    damping: np.ndarray  #: (3, 3) linear damping [N s/m, N m s/rad]
    calm: np.ndarray  #: (3, n_calm) restoring coefficients on CALM_TERMS (SI, positions in m and rad)
    frequency: np.ndarray  #: (nf,) wave frequencies of the transfer functions [rad/s]
    tf: np.ndarray  #: (nf, 3, n_wave) complex transfer functions per metre of wave amplitude
    heading_deg: float
    speed: float  #: [m/s]
    dataset: xr.Dataset  #: fit, residuals and diagnostics
    mean_over_a2: np.ndarray | None = None  #: (nf, 3, n_wave) second-order mean per a^2; None: left out

    def coefficient_table(self, waves, times, dtype=np.float64) -> np.ndarray:
        """(nt, 3, n_wave) wave-dependent coefficients at equally spaced ``times`` [s] for the
        components (amp [m], omega [rad/s], phase [rad]): sum_n a_n Re[T(omega_n) e^{i psi_n}],
        psi_n = e_n - omega_e,n t (the wave at the body origin, as :func:`station_wave_table`);
        components outside the fitted frequencies contribute nothing."""
        amp, omega, phase = (np.asarray(a, float) for a in waves)
        nw = len(WAVE_TERMS)
        if len(amp) == 0:
            return np.zeros((len(times), 3, nw), dtype)
        inside = (omega >= self.frequency[0]) & (omega <= self.frequency[-1])
        T = np.empty((len(omega), 3 * nw), complex)
        flat = self.tf.reshape(len(self.frequency), 3 * nw)
        for j in range(3 * nw):
            T[:, j] = np.interp(omega, self.frequency, flat[:, j].real) + 1j * np.interp(omega, self.frequency,
                                                                                       flat[:, j].imag)
        T[~inside] = 0.0
        we = encounter_frequency(omega, self.speed, self.heading_deg)
        ce, se = np.cos(phase), np.sin(phase)
        C = (amp[None, :] * (T.real.T * ce - T.imag.T * se))
        D = (amp[None, :] * (T.real.T * se + T.imag.T * ce))
        tab = _time_series_table(we, times, [(C, D)], dtype).reshape(len(times), 3, nw)
        if self.mean_over_a2 is not None:
            # the second-order part's mean, sum_n a_n^2 m(omega_n) (paper 001's zeta-zeta terms, their
            # difference-frequency oscillation left out)
            flat2 = self.mean_over_a2.reshape(len(self.frequency), 3 * nw)
            m2 = np.array([np.interp(omega, self.frequency, flat2[:, j]) for j in range(3 * nw)])  # (3 nw, nc)
            with one_blas_thread():
                tab += (m2[:, inside] @ amp[inside] ** 2).reshape(3, nw).astype(dtype)[None]
        return tab


def _positions(q0, ranges, counts) -> np.ndarray:
    """(n, 3) grid of relative positions (z [m], phi, theta [rad]) within +-ranges, ``counts`` points each."""
    axes = [np.linspace(-r, r, n) for r, n in zip(ranges, counts)]
    return np.array(list(product(*axes)))


def _sample(args, p, q0, rel, waves) -> np.ndarray:
    """Generalized restoring forces (nw, n, 3) at the relative positions ``rel`` (n, 3)."""
    q = np.zeros((len(rel), 6))
    q[:, K.S_Z] = q0[0] + rel[:, 0]
    q[:, K.S_ROLL] = q0[1] + rel[:, 1]
    q[:, K.S_PITCH] = q0[2] + rel[:, 2]
    out = np.empty((len(waves), len(rel), 3))
    KD._restoring_samples(*args, p, np.ascontiguousarray(waves, float), q, out)
    return out


def calm_snapshot(nst: int, decay=None) -> np.ndarray:
    """A calm-water station wave (1, ``nst``, nq) in the kernel's layout with or without the
    pressure decay (``decay``, a :class:`~stabflow.dynamics.model.SectionDecay` or None)."""
    return np.zeros((1, nst, 2 if decay is None else K.DECAY_COLUMNS))


def fit_derivative(sec, tables, p: np.ndarray, s0: np.ndarray, heading_deg: float, speed: float, frequencies,
                   *, heave_range: float, roll_range_deg: float = 40.0, pitch_range_deg: float = 3.0,
                   calm_points=(9, 21, 9), wave_points=(5, 9, 5), phases: int = 16, steepness: float = 1 / 40,
                   max_amplitude: float = 1.0, derivative_step: float = 0.02, decay=None,
                   second_order: bool = True) -> DerivativeModel:
    """Fit the derivative model (module doc) for the time-domain model (sections ``sec`` with
    ``tables``, parameter vector ``p``, equilibrium state ``s0``) at one wave heading [degree] and
    ship speed [m/s].

    Parameters
    ----------
    frequencies : array
        Wave frequencies [rad/s] of the transfer functions (covering the seaways to simulate).
    heave_range, roll_range_deg, pitch_range_deg : float
        Half-widths of the hull-position grid: heave [m], roll and pitch [degree].
    calm_points, wave_points : tuple of int
        Grid points per coordinate for the calm-water and the wave fits.
    phases : int
        Wave phases per regular wave.
    steepness, max_amplitude : float
        Regular-wave amplitude of the fit: a = min(max_amplitude [m], steepness x wavelength / 2).
    derivative_step : float
        Central-difference step of the first derivatives, as a fraction of the ranges (the value and
        first derivatives at equilibrium are the Taylor coefficients; the higher orders are fitted).
    second_order : bool
        Add the mean of the coefficients' second-order part (phase mean / a^2 x a_n^2 summed over
        the components) to the simulated coefficients.
    decay : SectionDecay, optional
        The sections' pressure decay for the d2phi/dzdt term (as the time-domain model).
    """
    args = kernel_args(sec, tables)
    q0 = np.array([s0[K.S_Z], s0[K.S_ROLL], s0[K.S_PITCH]])
    ranges = np.array([heave_range, np.radians(roll_range_deg), np.radians(pitch_range_deg)])
    steps = ranges * derivative_step
    # equilibrium and +-step along each coordinate for the value and the first derivatives
    star = np.vstack([np.zeros(3), np.diag(steps), -np.diag(steps)])
    calm_snap = calm_snapshot(len(sec.x), decay)

    def value_and_slopes(S):  # S (..., 7, 3) at the star points -> (..., 3) value, (..., 3, 3) d/dq_k
        return S[..., 0, :], np.moveaxis((S[..., 1:4, :] - S[..., 4:7, :]) / (2 * steps)[:, None], -2, -1)

    # calm water
    rel = _positions(q0, ranges, calm_points)
    R = _sample(args, p, q0, rel, calm_snap)[0]
    R0, dR = value_and_slopes(_sample(args, p, q0, star, calm_snap)[0])
    calm = np.zeros((3, len(CALM_TERMS)))
    resid = np.empty(3)
    scale_of = np.empty(3)
    for i in range(3):
        use = [j for j, e in enumerate(CALM_TERMS) if (e[1] % 2 == 1) == (i == 1)]
        c, fit = _taylor_fit(rel, R[:, i], R0[i], dR[i], [CALM_TERMS[j] for j in use], ranges)
        calm[i, use] = c
        resid[i] = np.sqrt(np.mean((fit - R[:, i]) ** 2))
        scale_of[i] = np.sqrt(np.mean((R[:, i] - R[:, i].mean()) ** 2))
    # regular waves over the frequencies, sampled in phase
    freqs = np.sort(np.asarray(frequencies, float))
    relw = _positions(q0, ranges, wave_points)
    Rw0 = _sample(args, p, q0, relw, calm_snap)[0]
    wscale = np.array([np.prod(ranges ** np.array(e)) for e in WAVE_TERMS])
    Rq0 = _sample(args, p, q0, np.zeros((1, 3)), calm_snap)[0, 0]
    chi = 2 * np.pi * np.arange(phases) / phases
    nw = len(WAVE_TERMS)
    tf = np.empty((len(freqs), 3, nw), complex)
    mean2 = np.empty((len(freqs), 3, nw))
    wres = np.empty((len(freqs), 3))
    wrms = np.empty((len(freqs), 3))
    amps = np.empty(len(freqs))
    for m, w in enumerate(freqs):
        lam = 2 * np.pi * G / w**2
        a = min(max_amplitude, 0.5 * steepness * lam)
        amps[m] = a
        snaps = np.concatenate([station_wave_table([a], [w], [c], sec.x, heading_deg, 0.0, [0.0], decay)
                                for c in chi])
        W = np.moveaxis(_sample(args, p, q0, relw, snaps) - Rw0[None], -1, 1)  # (phases, 3, n)
        # the excitation (constant term) is the wave force at equilibrium; the other terms by least
        # squares over the grid (first derivatives at equilibrium, as for the calm water, leave 2-3
        # times the residual in waves shorter than the ship)
        W0 = _sample(args, p, q0, np.zeros((1, 3)), snaps)[:, 0, :] - Rq0  # (phases, 3)
        A = _design(relw, WAVE_TERMS[1:], ranges)
        c, *_ = np.linalg.lstsq(A, (W - W0[:, :, None]).reshape(-1, W.shape[-1]).T, rcond=None)
        coef = np.empty((phases, 3, nw))
        coef[:, :, 0] = W0
        coef[:, :, 1:] = (c / wscale[1:, None]).T.reshape(phases, 3, nw - 1)
        # first harmonic in chi per metre of amplitude, and the phase mean per a^2
        tf[m] = 2.0 / (a * phases) * np.tensordot(np.exp(-1j * chi), coef, axes=(0, 0))
        mean2[m] = coef.mean(axis=0) / a**2
        # what the linear transfer functions reproduce of the sampled wave forces at this amplitude
        lin = np.real(a * tf[m][None] * np.exp(1j * chi)[:, None, None])  # (phases, 3, nw)
        rec = np.einsum("kw,piw->pik", _design(relw, WAVE_TERMS, np.ones(3)), lin)  # (phases, 3, n)
        wres[m] = np.sqrt(np.mean((rec - W) ** 2, axis=(0, 2)))
        wrms[m] = np.sqrt(np.mean(W**2, axis=(0, 2)))
    # generalized mass and linear damping at equilibrium (heave, roll, pitch)
    mq, _ = generalized_system(p, s0, np.zeros(6))
    idx = [K.S_Z, K.S_ROLL, K.S_PITCH]
    M3 = mq[np.ix_(idx, idx)]
    B = p[K.P_DAMPING:K.P_DAMPING + 36].reshape(6, 6)[np.ix_(idx, idx)]
    ds = xr.Dataset(
        {
            "calm_coefficient": (("force", "calm_term"), calm),
            "calm_residual": ("force", resid),
            "calm_rms": ("force", scale_of),
            "tf_real": (("tf_frequency", "force", "wave_term"), tf.real),
            "tf_imag": (("tf_frequency", "force", "wave_term"), tf.imag),
            "mean_over_a2": (("tf_frequency", "force", "wave_term"), mean2),
            "wave_residual": (("tf_frequency", "force"), wres),
            "wave_rms": (("tf_frequency", "force"), wrms),
            "fit_amplitude": ("tf_frequency", amps),
            "generalized_mass": (("force", "force_j"), M3),
            "linear_damping": (("force", "force_j"), B),
        },
        coords={"force": list(FORCES), "force_j": list(FORCES), "calm_term": term_names(CALM_TERMS),
                "wave_term": term_names(WAVE_TERMS), "tf_frequency": freqs},
        attrs={"heading_deg": float(heading_deg), "speed": float(speed), "heave_range": float(heave_range),
               "roll_range_deg": float(roll_range_deg), "pitch_range_deg": float(pitch_range_deg),
               "calm_points": str(tuple(calm_points)), "wave_points": str(tuple(wave_points)), "phases": int(phases),
               "steepness": float(steepness), "max_amplitude": float(max_amplitude),
               "z0": float(q0[0]), "theta0": float(q0[2]),
               "method": "paper 001 eqs 1-7; coefficients fitted from stabflow's volume-based FK + HS forces"},
    )
    return DerivativeModel(p=p, s0=np.asarray(s0, float).copy(), q0=q0, minv=np.linalg.inv(M3), damping=B,
                           calm=calm, frequency=freqs, tf=tf, heading_deg=float(heading_deg), speed=float(speed),
                           dataset=annotate(ds), mean_over_a2=mean2 if second_order else None)


def run_full(model, waves, heading_deg: float, duration: float, dt: float, s0=None):
    """States (nsteps + 1, N_STATE) and the last step done of the full volume-based model of an
    ensemble-style ``model`` in the waves (amp, omega, phase), from ``s0`` (default: equilibrium),
    with the model's diffraction force (``model.diffraction``, whose heading must be ``heading_deg``)
    where it has one."""
    from stabflow.dynamics._kernels import _simulate
    from stabflow.dynamics.diffraction import ftab

    nsteps = int(round(duration / dt))
    t_half = np.arange(2 * nsteps + 1) * 0.5 * dt
    wtab = station_wave_table(*waves, model.sec.x, heading_deg, model.speed, t_half, model.decay)
    out = np.empty((nsteps + 1, K.N_STATE))
    s = model.s0 if s0 is None else np.asarray(s0, float)
    last = _simulate(*kernel_args(model.sec, model.tables), model.p, wtab,
                     ftab(model.diffraction, waves, model.speed, heading_deg, t_half), dt, 0, nsteps, s,
                     np.radians(90.0), out, np.empty((0, 6)))
    return out, last


def step_derivative(dm: DerivativeModel, ctab: np.ndarray, dt: float, n0: int, n1: int, s, phi_cap: float,
                    out: np.ndarray) -> int:
    """RK4 steps n0..n1 of the derivative model on the coefficient table ``ctab`` (2 nsteps + 1, 3,
    n_wave) of its record from state ``s`` (N_STATE,); ``out`` receives the states; returns the last
    step done (below n1 when |roll| passed ``phi_cap`` [rad])."""
    return KD._simulate_derivative(dm.p, dm.q0, dm.minv, dm.damping, dm.calm, _CEXP, ctab, _WEXP, dt, n0, n1,
                                   np.asarray(s, float), phi_cap, out)


def run_derivative(dm: DerivativeModel, waves, duration: float, dt: float, *, s0=None, n_start: int = 0,
                   n_end: int | None = None, phi_cap_deg: float = 90.0, out=None):
    """States (nsteps + 1, N_STATE) of the derivative model (same layout as the time-domain model;
    rows before ``n_start`` unset) and the last step done; from ``s0`` (default: equilibrium at rest)
    at step ``n_start``."""
    nsteps = int(round(duration / dt))
    n_end = nsteps if n_end is None else n_end
    t_half = np.arange(2 * nsteps + 1) * 0.5 * dt
    ctab = dm.coefficient_table(waves, t_half)
    out = np.empty((nsteps + 1, K.N_STATE)) if out is None else out
    s = dm.s0 if s0 is None else np.asarray(s0, float)
    return out, step_derivative(dm, ctab, dt, n_start, n_end, s, np.radians(phi_cap_deg), out)


def encounter_to_wave_frequency(we: float, speed: float, heading_deg: float) -> float:
    """Wave frequency [rad/s] whose encounter frequency is ``we`` [rad/s] (we = w - w^2 U cos(beta) / g,
    the root on the branch that starts at w = we for U = 0; head and beam seas)."""
    c = speed * np.cos(np.radians(heading_deg)) / G
    if abs(c) < 1e-12:
        return float(we)
    if c > 0:
        raise ValueError("encounter_to_wave_frequency: following seas have up to three wave frequencies per "
                         "encounter frequency; give wave frequencies instead")
    return float((-1.0 + np.sqrt(1.0 - 4.0 * c * we)) / (2.0 * -c))


def steady_amplitude(roll_deg: np.ndarray, dt: float, window: float, tol: float = 0.05) -> tuple[float, bool]:
    """Largest |roll| [deg] over the last ``window`` [s] and whether the motion is steady there (the
    previous window's largest |roll| within ``tol`` of it)."""
    n = int(round(window / dt))
    last = float(np.max(np.abs(roll_deg[-n:])))
    prev = float(np.max(np.abs(roll_deg[-2 * n:-n]))) if len(roll_deg) >= 2 * n else np.nan
    return last, bool(np.isfinite(prev) and abs(last - prev) <= tol * max(last, 1e-12))


def regular_map(model, dm: DerivativeModel, ratios, heights, duration: float, dt: float, phi0_deg: float = 2.0,
                window: float | None = None, progress: bool = False) -> xr.Dataset:
    """Roll of the full volume-based model and of the derivative model in regular waves over
    encounter-frequency ratio omega_e / omega_roll x wave height, from the equilibrium heeled by
    ``phi0_deg`` [deg] (the seed of parametric roll): the largest |roll| over the last ``window``
    [s] (default 10 roll periods), steadiness, capsize; the CPU seconds of each model's runs in
    ``ds.encoding["cpu"]`` (not written to the file)."""
    import time

    from tqdm import tqdm

    w_roll = 2 * np.pi / model.roll_period
    window = 10 * model.roll_period if window is None else window
    nsteps = int(round(duration / dt))
    s0 = model.s0.copy()
    s0[K.S_ROLL] = np.radians(phi0_deg)
    shape = (len(ratios), len(heights))
    res = {k: np.zeros(shape) for k in ("full", "deriv", "full_steady", "deriv_steady", "full_capsized",
                                        "deriv_capsized", "omega")}
    cpu = np.zeros(2)
    bar = tqdm(total=res["full"].size, desc="regular-wave map", disable=not progress, mininterval=10)
    for i, r in enumerate(ratios):
        w = encounter_to_wave_frequency(r * w_roll, model.speed, dm.heading_deg)
        for j, H in enumerate(heights):
            waves = (np.array([0.5 * H]), np.array([w]), np.array([0.0]))
            t0 = time.process_time()
            out, last = run_full(model, waves, dm.heading_deg, duration, dt, s0)
            t1 = time.process_time()
            res["full"][i, j], res["full_steady"][i, j] = steady_amplitude(np.degrees(out[:last + 1, K.S_ROLL]), dt, window)
            res["full_capsized"][i, j] = last < nsteps
            t2 = time.process_time()
            od, lastd = run_derivative(dm, waves, duration, dt, s0=s0)
            t3 = time.process_time()
            res["deriv"][i, j], res["deriv_steady"][i, j] = steady_amplitude(np.degrees(od[:lastd + 1, K.S_ROLL]), dt,
                                                                              window)
            res["deriv_capsized"][i, j] = lastd < nsteps
            res["omega"][i, j] = w
            cpu += (t1 - t0, t3 - t2)
            bar.update()
    bar.close()
    dims = ("frequency_ratio", "wave_height")
    ds = xr.Dataset(
        {
            "roll_full": (dims, res["full"]), "roll_derivative": (dims, res["deriv"]),
            "steady_full": (dims, res["full_steady"].astype(np.int8)),
            "steady_derivative": (dims, res["deriv_steady"].astype(np.int8)),
            "capsized_full": (dims, res["full_capsized"].astype(np.int8)),
            "capsized_derivative": (dims, res["deriv_capsized"].astype(np.int8)),
            "wave_frequency": ("frequency_ratio", res["omega"][:, 0]),
            "wavelength": ("frequency_ratio", 2 * np.pi * G / res["omega"][:, 0] ** 2),
        },
        coords={"frequency_ratio": np.asarray(ratios, float), "wave_height": np.asarray(heights, float)},
        attrs={"map_duration": float(duration), "map_dt": float(dt), "phi0_deg": float(phi0_deg),
               "map_window": float(window), "roll_period": float(model.roll_period)},
    )
    # the measured CPU seconds stay out of the dataset (the results files are bit-identical per config)
    ds.encoding["cpu"] = {"full": float(cpu[0]), "derivative": float(cpu[1])}
    return annotate(ds)


def study_condition(cfg: dict) -> dict:
    """The ensemble-style condition of the ``derivative`` config section (ship loading, stations,
    speed, heading) for :func:`stabflow.statistics.ensemble.build_model`."""
    cond = {"name": "derivative", "ship": cfg["ship"], "stations": int(cfg["stations"]), "speed_kn": float(cfg["speed_kn"]),
            "heading_deg": float(cfg["heading_deg"]), "dt": float(cfg["map"]["dt"]),
            "duration": float(cfg["map"]["duration"])}
    if cfg.get("kg") is not None:
        cond["kg"] = float(cfg["kg"])
    if cfg.get("dynamics"):
        cond["dynamics"] = dict(cfg["dynamics"])  # null or {}: the ship file's
    return cond


def fit_for(model, fit: dict, frequencies=None) -> DerivativeModel:
    """:func:`fit_derivative` for an ensemble-style ``model`` with the settings ``fit`` (the config's
    ``derivative.fit`` section): heave range as a fraction of the draft, frequencies from ``fit`` or
    given."""
    if frequencies is None:
        frequencies = np.linspace(fit["frequency_min"], fit["frequency_max"], int(fit["frequencies"]))
    draft = float(model.ship.loading["draft"]) if "draft" in model.ship.loading else float(model.st["draft"])
    return fit_derivative(model.sec, model.tables, model.p, model.s0, float(model.cond["heading_deg"]), model.speed,
                          frequencies, heave_range=fit["heave_range_draft"] * draft,
                          roll_range_deg=fit["roll_range_deg"], pitch_range_deg=fit["pitch_range_deg"],
                          calm_points=tuple(fit["calm_points"]), wave_points=tuple(fit["wave_points"]),
                          phases=int(fit["phases"]), steepness=float(fit["steepness"]),
                          max_amplitude=float(fit["max_amplitude"]), decay=model.decay,
                          second_order=bool(fit["second_order"]))


def derivative_study(ship, cfg: dict, progress: bool = False):
    """The derivative step: fit of ``ship`` at the section's loading, speed and heading, and the
    regular-wave map of both models. Returns (model, derivative model, dataset)."""
    from stabflow import StabflowError
    from stabflow.statistics.ensemble import build_model

    if (dict(ship.data.get("dynamics", {}), **(cfg.get("dynamics") or {}))).get("hydro") == "capytaine":
        raise StabflowError(f"config: derivative: ship {ship.name!r} takes its added mass and damping from Capytaine "
                            "(dynamics.hydro: capytaine), which this step does not run; give dynamics: {hydro: config}")
    model = build_model(ship, study_condition(cfg))
    dm = fit_for(model, cfg["fit"])
    mp = cfg["map"]
    ratios = np.arange(mp["ratio_min"], mp["ratio_max"] + 1e-9, mp["ratio_step"])
    rm = regular_map(model, dm, np.round(ratios, 6), mp["heights"], float(mp["duration"]), float(mp["dt"]),
                     float(mp["phi0_deg"]), progress=progress)
    ds = dm.dataset.merge(rm)
    ds.attrs.update(dm.dataset.attrs)
    ds.attrs.update(rm.attrs)
    ds.attrs.update(ship=ship.name, kg=float(model.st["kg"]), gm=float(model.st["gm"]), stations=len(model.sec.x))
    ds.encoding["cpu"] = dict(rm.encoding["cpu"], cells=int(rm["roll_full"].size))
    return model, dm, annotate(ds)


def record_variances(ens: xr.Dataset, dof: str) -> np.ndarray:
    """Each record's own variance of ``dof`` (heave [m^2], roll or pitch [deg^2]) from the ensemble's
    per-record moment sums."""
    S = ens["moment_sums"].sel(dof=dof)
    n = ens["steps"].values.astype(float) + 1.0
    m1 = S.sel(order=1).values / n
    return S.sel(order=2).values / n - m1**2


def ergodic_variance_cv(ens: xr.Dataset, dof: str) -> float:
    """Coefficient of variation that the per-record variance of ``dof`` would have if the process were
    ergodic and Gaussian with the ensemble's correlation: Var(s^2) / sigma^4 = (4 / T) int_0^inf rho^2
    dtau for records of length T (roll: the ensemble's autocorrelation up to its largest lag; heave
    and pitch: (2 pi / T) int S^2 dw / (int S dw)^2 from the ensemble's spectrum)."""
    T = float(ens.attrs["duration"])
    if dof == "roll":
        rho = ens["roll_autocorrelation"].values
        return float(np.sqrt(4.0 / T * np.trapezoid(rho**2, ens["lag"].values)))
    S = ens[f"{dof}_psd"].values
    w = ens["frequency"].values
    return float(np.sqrt(2 * np.pi / T * np.trapezoid(S**2, w) / np.trapezoid(S, w) ** 2))


def exceedance_probability(roll_max, level: float, alpha: float = 0.05) -> tuple[float, float, float]:
    """Share of records whose largest |roll| [deg] exceeds ``level`` [deg], with its Clopper-Pearson
    interval."""
    from scipy import stats

    x = np.asarray(roll_max, float)
    k, n = int(np.sum(x > level)), len(x)
    lo = stats.beta.ppf(alpha / 2, k, n - k + 1) if k > 0 else 0.0
    hi = stats.beta.ppf(1 - alpha / 2, k + 1, n - k) if k < n else 1.0
    return k / n, float(lo), float(hi)


def wave_autocorrelation(components, lags, envelope: bool = False) -> np.ndarray:
    """Autocorrelation of the long-crested wave elevation at a fixed point for the components
    (amp, omega, phase): sum a^2 cos(omega tau) / sum a^2; with ``envelope`` its envelope
    |sum a^2 exp(i omega tau)| / sum a^2, which returns to 1 where the record repeats itself (equally
    spaced frequencies: every 2 pi / d omega, whatever the carrier's phase there)."""
    amp, omega, _ = (np.asarray(a, float) for a in components)
    a2 = amp**2
    z = np.array([np.sum(a2 * np.exp(1j * omega * t)) for t in np.asarray(lags, float)]) / np.sum(a2)
    return np.abs(z) if envelope else z.real


def irregular_map(ship, cfg: dict, progress: bool = False) -> xr.Dataset:
    """Roll sigma and P(largest roll of a record > level) over speed x peak period for both models
    (``cfg`` the ``derivative.irregular_map`` section; the loading, heading and fit of the section)."""
    from tqdm import tqdm

    from stabflow.statistics.ensemble import build_model, simulate_record

    mp = cfg["irregular_map"]
    level = float(cfg["level_deg"])
    speeds, tps = list(mp["speeds_kn"]), list(mp["tps"])
    shape = (len(speeds), len(tps))
    out = {f"{k}_{m}": np.zeros(shape) for k in ("sigma", "p", "p_lower", "p_upper") for m in ("full", "derivative")}
    bar = tqdm(total=2 * len(speeds) * len(tps), desc="irregular map", disable=not progress, mininterval=10)
    for i, v in enumerate(speeds):
        for j, tp in enumerate(tps):
            for kind in ("full", "derivative"):
                cond = dict(study_condition(cfg), name="map", speed_kn=float(v), dt=float(mp["dt"]),
                            duration=float(mp["duration"]), seed=int(mp["seed"]),
                            model="volume" if kind == "full" else "derivative", derivative_fit=dict(cfg["fit"]),
                            dynamics=dict(cfg.get("dynamics") or {}),
                            sea={"spectrum": "jonswap", "hs": float(mp["hs"]), "tp": float(tp), "gamma": float(mp["gamma"]),
                                 "n_components": int(mp["n_components"]), "discretisation": "equal_energy"})
                model = build_model(ship, cond)
                roll, mx = [], []
                for r in range(int(mp["records"])):
                    st, last = simulate_record(model, r)
                    x = np.degrees(st[: last + 1, K.S_ROLL])
                    roll.append(x)
                    mx.append(np.max(np.abs(x)) if last == model.nsteps else 180.0)
                out[f"sigma_{kind}"][i, j] = float(np.std(np.concatenate(roll)))
                p, lo, hi = exceedance_probability(mx, level)
                out[f"p_{kind}"][i, j], out[f"p_lower_{kind}"][i, j], out[f"p_upper_{kind}"][i, j] = p, lo, hi
                bar.update()
    bar.close()
    dims = ("map_speed", "map_tp")
    ds = xr.Dataset({f"map_{k}": (dims, v) for k, v in out.items()},
                    coords={"map_speed": np.asarray(speeds, float), "map_tp": np.asarray(tps, float)},
                    attrs={"map_hs": float(mp["hs"]), "map_records": int(mp["records"]),
                           "map_record_duration": float(mp["duration"]), "map_level_deg": level})
    return annotate(ds)


def compared_ensembles(config: dict) -> dict | None:
    """{"full": key, "derivative": key} of the first ``model: derivative`` ensemble condition of the
    derivative section's ship with ``compare_with`` (the model volume condition of the same sea),
    or None."""
    ship = config["derivative"]["ship"]
    for c in config.get("ensembles", []):
        if c.get("model", "volume") == "derivative" and c.get("compare_with") and c["ship"] == ship:
            return {"full": f"{ship}_{c['compare_with']}", "derivative": f"{ship}_{c['name']}"}
    return None
