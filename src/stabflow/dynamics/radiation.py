"""Heave and pitch radiation with memory (Cummins 1962) for the 6-DOF model (issue 17).

The 6-DOF model's constant heave-pitch added mass and damping are one frequency's values (the ship
file's). In following seas the encounter frequency sweeps down towards zero as the ship nears the
wave celerity, and in deep water the radiation damping vanishes there: constant coefficients then
overstate the damping and with it the mean wave-induced surge force of :mod:`.surf_riding`.
Cummins' equation replaces them by the infinite-frequency added mass and a convolution with the
retardation functions,

    F_i(t) = -A_ij(inf) q''_j - int_0^t K_ij(t - tau) q'_j(tau) dtau,   i, j in {heave, pitch},
    K_ij(t) = (2 / pi) int_0^inf B_ij(w) cos(w t) dw                     (Ogilvie 1964),

q the heave of G [m] and the pitch [rad], with A(w), B(w) and A(inf) of the hull at its calm-water
equilibrium about G from Capytaine (linear potential flow at zero speed).

Forward speed (``manoeuvring.radiation_forward_speed``, off by default): the zero-speed
coefficients carried to the ship's speed by strip theory's terms (Salvesen, Tuck & Faltinsen 1970),
written in the time domain by the kernel (``_kernels_6dof._memory``): each section's relative
vertical velocity is z' - x theta' + u (theta - theta_0), its force the -(d/dt - u d/dx) of its
momentum, and the flow leaves a transom stern with the momentum of the transom's section (its
added mass by Lewis's map, :func:`transom`). For harmonic motions they are STF's table with the
transom's added mass (B35, B53 +- U A33; A35, A53 -+ U B33 / w_e^2; A55 + U^2 A33 / w_e^2, B55 +
U^2 B33 / w_e^2, and the transom's terms: :func:`forward_speed_coefficients`), which grow as the
encounter frequency falls. Why off: the excitation of the 6-DOF model is the Froude-Krylov force
without diffraction, and STF's speed terms are balanced by the speed terms of the diffraction force
(a hull that follows the water's motion disturbs nothing). Without them the long-wave limit is
lost: on the trawler at 10 kn, 45 degrees off the stern, H 1.8 m, the linear pitch is 0.81 degree
against a wave slope of 0.76 with the zero-speed coefficients in a 300-m wave and 2.89 with the
speed terms; 3.08 against 6.93 degree at lambda 85.3 m (slope 2.69); and the straight run turns
unstable in pitch above 9.9 m/s (Fn 0.63). The option stays for sensitivity studies. Also left out: the
transom's damping b^A and the speed's effect on the free-surface Green function (the BEM is at zero
speed, evaluated at the encounter frequency). The constant-coefficient model has no speed terms.

The convolution runs as a state-space system. Its frequency response K^(w) = int_0^inf K(t)
exp(-i w t) dt = B(w) + i w (A(w) - A(inf)) is fitted in the frequency domain (Perez & Fossen 2009)
by one rational function of the four entries with a common denominator (Sanathanan & Koerner's
iteration), of relative degree 1 and with a zero at s = 0 (K^(0) = 0: no damping at zero
frequency); its poles l_p and residues give K_ij(t) = sum_p Re(c_ijp exp(l_p t)) (Im l_p >= 0), so
each velocity q'_j drives the complex states w_jp' = l_p w_jp + q'_j and the force is
mu_i = sum_jp Re(c_ijp w_jp). The fit extends the coefficients beyond the BEM's last frequency with
the rational function's decay; the BEM stops where the wavelength is 13 largest panel radii
(:func:`bem_frequencies`; Capytaine itself warns below 8, where the trawler's damping turned
negative). Checks: the fitted A(w), B(w) against Capytaine's (the fit), A(inf) extrapolated from
the finite-frequency coefficients alone against Capytaine's infinite-frequency solution (causality
of the BEM data, Kramers-Kronig), and passivity of the fitted damping.

On disk (:func:`radiation_dataset`) each 2 x 2 quantity is written entry by entry (``_33``, ``_35``,
``_53``, ``_55``: heave-heave, heave force per pitch, pitch moment per heave, pitch-pitch), each with
its own units.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.io import RADIATION_ENTRIES as ENTRIES
from stabflow.io import RADIATION_QUANTITIES as QUANTITIES
from stabflow.io import annotate

#: Capytaine's names of the two modes, in the order of the kernel's (heave, pitch)
HEAVE_PITCH = ("Heave", "Pitch")
#: the frequency grid of the BEM [rad/s]: first frequency and step (the last: :func:`bem_frequencies`)
FREQUENCY_START = 0.1
FREQUENCY_STEP = 0.1
#: panels per wavelength: the BEM's last wavelength is this many times the largest panel radius
PANEL_RADII_PER_WAVELENGTH = 13.0
#: sampling of the retardation functions written with the results [s]: step and length
KERNEL_DT = 0.1
KERNEL_T = 30.0


def bem_frequencies(max_panel_radius: float) -> np.ndarray:
    """BEM frequencies [rad/s] from FREQUENCY_START in steps of FREQUENCY_STEP up to the deep-water
    frequency whose wavelength is PANEL_RADII_PER_WAVELENGTH times the largest panel radius [m]
    (stabflow's resolution rule, not a published one: the trawler's mesh, largest radius 0.60 m,
    gave negative damping above 3.6 rad/s, where the wavelength is 8 radii)."""
    w_max = float(np.sqrt(2 * np.pi * G / (PANEL_RADII_PER_WAVELENGTH * max_panel_radius)))
    n = int(np.floor((w_max - FREQUENCY_START) / FREQUENCY_STEP + 1e-9)) + 1
    return FREQUENCY_START + FREQUENCY_STEP * np.arange(n)


def bem_radiation(mesh, h0: float, th0: float, xg: float, zg: float, rho: float, omegas=None, progress: bool = False
                  ) -> xr.Dataset:
    """Heave-pitch added mass and radiation damping of the hull ``mesh`` (trimesh, ship axes) at its
    calm-water equilibrium (heave h0 [m], trim th0 [rad]) about G (``xg``, ``zg`` [m]) at the
    frequencies ``omegas`` [rad/s] (None: :func:`bem_frequencies` of the immersed mesh) and at
    infinite frequency, by Capytaine with a lid on the inner waterplane (irregular-frequency removal),
    on one BLAS thread (bit-identical files). Returns a Dataset with ``added_mass`` and ``damping``
    (omega, i, j) and ``added_mass_inf`` (i, j), i, j in (heave, pitch) [kg, kg m, kg m^2; N s/m,
    N s, N m s]."""
    import capytaine as cpt

    from stabflow.dynamics.hydro import lidded_body

    body = lidded_body(mesh, h0, th0, xg, zg, HEAVE_PITCH)
    hull, lid = body.mesh, body.lid_mesh
    from tqdm import tqdm

    from stabflow.waves.synthesis import one_blas_thread

    solver = cpt.BEMSolver()
    radius = float(np.max(hull.faces_radiuses))
    omegas = bem_frequencies(radius) if omegas is None else np.asarray(omegas, float)
    freqs = list(omegas) + [np.inf]
    A = np.zeros((len(freqs), 2, 2))
    B = np.zeros((len(freqs), 2, 2))
    with one_blas_thread():
        for n, w in enumerate(tqdm(freqs, desc="Capytaine heave-pitch radiation", disable=not progress, mininterval=10)):
            for j, d in enumerate(HEAVE_PITCH):
                r = solver.solve(cpt.RadiationProblem(body=body, radiating_dof=d, omega=w, rho=rho, g=G))
                for i, e in enumerate(HEAVE_PITCH):
                    A[n, i, j] = r.added_mass[e]
                    B[n, i, j] = r.radiation_damping[e]
    dims = ("omega", "i", "j")
    ds = xr.Dataset(
        {"added_mass": (dims, A[:-1]), "damping": (dims, B[:-1]), "added_mass_inf": (("i", "j"), A[-1])},
        coords={"omega": omegas, "i": ["heave", "pitch"], "j": ["heave", "pitch"]},
        attrs={"panels": int(body.mesh.nb_faces), "lid_panels": int(lid.nb_faces), "max_panel_radius": radius,
               "xg": float(xg), "zg": float(zg), "heave0": float(h0), "trim0": float(th0), "rho": float(rho),
               "source": f"Capytaine {cpt.__version__} (linear potential flow, zero speed, lid for irregular frequencies)"},
    )
    return annotate(ds)


def retardation(omega, damping, t) -> np.ndarray:
    """Retardation functions K_ij(t) = (2 / pi) int B_ij(w) cos(w t) dw (Ogilvie 1964) [N/m, N, N m]
    at times ``t`` [s] from the damping ``damping`` (nw, 2, 2) at ``omega`` (nw,) [rad/s]: the
    trapezoidal rule over the grid with B(0) = 0 (deep water) prepended; B beyond the last
    frequency is taken as zero (the truncation the added-mass check measures)."""
    w = np.concatenate([[0.0], np.asarray(omega, float)])
    b = np.concatenate([np.zeros((1, 2, 2)), np.asarray(damping, float)])
    c = np.cos(np.outer(np.asarray(t, float), w))  # (nt, nw)
    return 2.0 / np.pi * np.trapezoid(c[:, :, None, None] * b[None], w, axis=1)


@dataclass(frozen=True)
class Memory:
    """State-space heave-pitch radiation: ``poles`` (np,) complex with Im >= 0 [1/s], ``residues``
    (2, 2, np) complex, K_ij(t) = sum_p Re(residues[i, j, p] exp(poles[p] t)); ``added_mass_inf``
    (2, 2)."""

    poles: np.ndarray
    residues: np.ndarray
    added_mass_inf: np.ndarray

    def kernel(self, t) -> np.ndarray:
        """K(t) (nt, 2, 2) of the fitted model."""
        e = np.exp(np.outer(np.asarray(t, float), self.poles))  # (nt, np)
        return np.real(np.einsum("ijp,tp->tij", self.residues, e))

    def response(self, omega) -> np.ndarray:
        """K^(w) = int_0^inf K(t) exp(-i w t) dt (nw, 2, 2) of the fitted model: each term
        Re(c exp(l t)) = (c exp(l t) + conj(c) exp(conj(l) t)) / 2 transforms to
        (c / (i w - l) + conj(c) / (i w - conj(l))) / 2."""
        iw = 1j * np.asarray(omega, float)[:, None]
        h1 = 1.0 / (iw - self.poles[None, :])
        h2 = 1.0 / (iw - np.conj(self.poles)[None, :])
        return 0.5 * (np.einsum("ijp,wp->wij", self.residues, h1) + np.einsum("ijp,wp->wij", np.conj(self.residues), h2))

    def damping(self, omega) -> np.ndarray:
        """B(w) (nw, 2, 2) implied by the fitted model: Re K^(w)."""
        return np.real(self.response(omega))

    def added_mass(self, omega) -> np.ndarray:
        """A(w) (nw, 2, 2) implied by the fitted model: A(inf) + Im K^(w) / w."""
        w = np.asarray(omega, float)
        return self.added_mass_inf[None] + np.imag(self.response(w)) / w[:, None, None]

    @property
    def n_states(self) -> int:
        """Real states of the kernel: two inputs x poles x (real, imaginary)."""
        return 4 * len(self.poles)


def _entry_scale(H: np.ndarray) -> np.ndarray:
    """Weights (4,) of the four responses (rows of ``H``: 33, 35, 53, 55): 1 / sqrt(max|H_ii| max|H_jj|),
    so the coupling is weighed in the units of the diagonal it couples (a hull symmetric fore and aft
    has a coupling of round-off size, which its own maximum would blow up to the diagonal's weight)."""
    d = np.max(np.abs(H[[0, 3]]), axis=1)
    d = np.where(d > 0.0, d, 1.0)
    return 1.0 / np.sqrt(np.array([d[0] * d[0], d[0] * d[1], d[1] * d[0], d[1] * d[1]]))


def _sk_fit(s: np.ndarray, H: np.ndarray, n: int, nnum: int, iterations: int = 30) -> tuple[np.ndarray, np.ndarray]:
    """Rational least squares H_r(s) ~ N_r(s) / Q(s) with one denominator for all responses
    (Sanathanan & Koerner 1963: the linearised problem N - H Q = 0 reweighted by 1 / |Q| of the last
    iterate): Q monic of degree ``n``, N_r of degree ``nnum`` with N_r(0) = 0. ``s`` (nw,) the
    (scaled) Laplace variable i w, ``H`` (nr, nw). Returns the ascending coefficients q (n + 1,) and
    N (nr, nnum + 1)."""
    nr, nw = H.shape
    scale = _entry_scale(H)
    wgt = np.ones(nw)
    sp = s[None, :] ** np.arange(max(n, nnum) + 1)[:, None]  # (k, nw) powers of s
    q = np.r_[np.zeros(n), 1.0]
    for _ in range(iterations):
        M = np.zeros((nr * nw, n + nr * nnum), complex)
        rhs = np.zeros(nr * nw, complex)
        for r in range(nr):
            rows = slice(r * nw, (r + 1) * nw)
            w = wgt * scale[r]
            M[rows, :n] = -(H[r] * w)[:, None] * sp[:n].T
            M[rows, n + r * nnum: n + (r + 1) * nnum] = w[:, None] * sp[1:nnum + 1].T
            rhs[rows] = H[r] * sp[n] * w
        x = np.linalg.lstsq(np.vstack([M.real, M.imag]), np.r_[rhs.real, rhs.imag], rcond=None)[0]
        q = np.r_[x[:n], 1.0]
        wgt = 1.0 / np.abs(np.polyval(q[::-1], s))
    N = np.zeros((nr, nnum + 1))
    N[:, 1:] = x[n:].reshape(nr, nnum)
    return q, N


def _residues(s: np.ndarray, H: np.ndarray, poles: np.ndarray, with_slope: bool = False):
    """Residues (nr, np) of H_r(s) = sum_p r_p / (s - l_p) [+ s a_r] for fixed poles (complex ones in
    conjugate pairs, given once with Im > 0), least squares with real unknowns: each pair contributes
    c / (s - l) + conj(c) / (s - conj(l)) with c = a + i b, a real pole c / (s - l) with c real, and
    ``with_slope`` a real a_r (then returned as well, (nr,)). The zero at s = 0 (H(0) = 0) is kept as
    a constraint (a row weighted 1e6 times the data's)."""
    cols, zero = [], []
    for lp in poles:
        h1, h2 = 1.0 / (s - lp), 1.0 / (s - np.conj(lp))
        if lp.imag > 0.0:
            cols += [h1 + h2, 1j * (h1 - h2)]
            zero += [2.0 * np.real(-1.0 / lp), 2.0 * np.real(-1j / lp)]  # (a, b) terms of H(0)
        else:
            cols.append(h1)
            zero.append(np.real(-1.0 / lp))
    if with_slope:
        cols.append(s)
        zero.append(0.0)
    X = np.column_stack(cols)
    z = np.asarray(zero)
    out = np.zeros((H.shape[0], len(poles)), complex)
    slope = np.zeros(H.shape[0])
    scale = _entry_scale(H)
    for r in range(H.shape[0]):
        w = scale[r]
        big = 1e6 * np.sqrt(len(s)) / np.max(np.abs(z))
        M = np.vstack([(X * w).real, (X * w).imag, big * w * z[None, :]])
        x = np.linalg.lstsq(M, np.r_[(H[r] * w).real, (H[r] * w).imag, 0.0], rcond=None)[0]
        j = 0
        for p, lp in enumerate(poles):
            out[r, p] = x[j] + (1j * x[j + 1] if lp.imag > 0.0 else 0.0)
            j += 2 if lp.imag > 0.0 else 1
        slope[r] = x[-1] if with_slope else 0.0
    return (out, slope) if with_slope else out


def _poles(q: np.ndarray, scale: float) -> np.ndarray:
    """Stable poles [1/s] of the denominator q (ascending, in s / scale), one of each conjugate pair
    (Im > 0) and the real ones; unstable roots are reflected into the left half-plane."""
    z = np.roots(q[::-1]) * scale
    z = np.where(z.real > 0.0, -z.real + 1j * z.imag, z)
    real = z[np.abs(z.imag) <= 1e-9 * np.abs(z)].real + 0j
    return np.concatenate([z[z.imag > 1e-9 * np.abs(z)], real])


def fit_memory(ds: xr.Dataset, order: int | None = None, max_order: int = 10, tolerance: float = 0.02) -> Memory:
    """Fit the state-space model (module docstring) to the BEM coefficients ``ds``
    (:func:`bem_radiation`) in the frequency domain (Perez & Fossen 2009): the four responses
    K^_ij(i w) = B_ij(w) + i w (A_ij(w) - A_ij(inf)) by one rational function of relative degree 1
    with a zero at s = 0 (K(0) finite, K^(0) = 0), common denominator of degree ``order`` or the
    smallest up to ``max_order`` whose largest error is within ``tolerance`` of the largest |K^| of
    the diagonal entries (:func:`_entry_scale`; else the best); unstable poles reflected, residues refitted to the stable poles.
    The order is at most 0.8 times the number of frequencies (the real unknowns, about 5 per degree,
    stay below the 8 equations per frequency by a factor of 2); a fit that is not passive
    (:func:`passivity`) or has a pole of damping ratio below MIN_POLE_DAMPING (a resonance of the
    fit between data points, which would ring in the time domain) is taken only if nothing else
    is."""
    omega = ds["omega"].values
    A, B = ds["added_mass"].values, ds["damping"].values
    a_inf = ds["added_mass_inf"].values
    H = (B + 1j * omega[:, None, None] * (A - a_inf[None])).reshape(len(omega), 4).T  # (4, nw)
    sc = float(omega[-1])
    s = 1j * omega / sc
    best = None
    top = max(2, min(max_order, int(0.8 * len(omega))))
    for n in ([order] if order is not None else range(2, top + 1)):
        q, _ = _sk_fit(s, H, n, n - 1)
        lam = _poles(q, sc)
        res = _residues(1j * omega, H, lam)  # residues of K^ in s = i w (unscaled)
        # K(t) = sum over all poles r e^{l t}: a pair r, conj(r) gives Re(2 r e^{l t}); a real pole r e^{l t}
        c = np.where(lam.imag > 0.0, 2.0, 1.0)[None, :] * res
        mem = Memory(lam, c.reshape(2, 2, len(lam)), a_inf)
        Hf = mem.response(omega).reshape(len(omega), 4).T
        err = float(np.max(np.abs(Hf - H) * _entry_scale(H)[:, None]))
        # a fit that would feed energy into the motions somewhere is taken only if nothing else is
        ratio = float(np.min(-lam.real / np.abs(lam)))
        key = (passivity(mem, sc) < -PASSIVITY_TOLERANCE or ratio < MIN_POLE_DAMPING, err)
        if best is None or key < best[0]:
            best = (key, mem)
        if not key[0] and err <= tolerance:
            break
    return best[1]


#: smallest damping ratio -Re(l) / |l| of a fitted pole (the trawler's lightest: 0.013)
MIN_POLE_DAMPING = 0.005
#: largest negative eigenvalue of the fitted damping, relative to its largest, that counts as passive
PASSIVITY_TOLERANCE = 0.01


def passivity(mem: Memory, w_max: float) -> float:
    """Smallest eigenvalue over 0 < w <= 4 ``w_max`` [rad/s] of the symmetric part of the fitted
    damping B(w) scaled by its diagonal, D^-1/2 B D^-1/2 with D_ii the largest B_ii(w) (heave and
    pitch in their own units): >= 0 for a passive radiation model (the hull can only take energy out
    of the motions), negative where the fit would feed energy in (-0.2: a heave damping down to
    -20 % of its peak)."""
    w = np.linspace(1e-3 * w_max, 4.0 * w_max, 801)
    b = mem.damping(w)
    d = np.sqrt(np.maximum(np.max(np.abs(np.diagonal(b, axis1=1, axis2=2)), axis=0), 1e-300))
    sym = 0.5 * (b + np.transpose(b, (0, 2, 1))) / np.outer(d, d)[None]
    return float(np.min(np.linalg.eigvalsh(sym)))


def model_order(mem: Memory) -> int:
    """Degree of the fitted model's denominator: two per complex pole pair, one per real pole."""
    return int(sum(2 if p.imag > 0.0 else 1 for p in mem.poles))


def infinite_frequency_estimate(ds: xr.Dataset, order: int) -> np.ndarray:
    """A(inf) (2, 2) extrapolated from the finite-frequency coefficients alone: B + i w A fitted as
    K^(i w) + i w A(inf), K^ a causal rational function of denominator degree ``order`` (the poles of
    a Sanathanan-Koerner fit, unstable ones reflected, then the residues and A(inf) by least squares
    with K^(0) = 0). Compared with the BEM's own infinite-frequency solution it tests the
    coefficients' causality (the Kramers-Kronig relations between A and B) and the frequency range."""
    omega = ds["omega"].values
    A, B = ds["added_mass"].values, ds["damping"].values
    H = (B + 1j * omega[:, None, None] * A).reshape(len(omega), 4).T
    sc = float(omega[-1])
    q, _ = _sk_fit(1j * omega / sc, H, order, order + 1)
    _, a_inf = _residues(1j * omega, H, _poles(q, sc), with_slope=True)
    return a_inf.reshape(2, 2)


def transom(sp: xr.Dataset, xg: float, rho: float) -> tuple[float, float]:
    """The transom of the hull's section parameters ``sp`` (:func:`stabflow.dynamics.roll_damping.section_parameters`):
    the aft face of the aftmost immersed station, x_T from G at ``xg`` [m], and that section's heave
    added mass at infinite frequency [kg/m], Lewis's conformal map (Lewis 1929): the section mapped
    from the unit circle by z = M (zeta + a1 / zeta + a3 / zeta^3), half-breadth b = M (1 + a1 + a3),
    has in vertical motion, reflected in the free surface (phi = 0 there), the added mass
    rho pi M^2 ((1 + a1)^2 + 3 a3^2) / 2 (a semicircle of radius R: rho pi R^2 / 2; a flat plate of
    half-width b: rho pi b^2 / 2). It is the boundary term of the -u d/dx part at the hull's aft end,
    whatever the stern: a stern that tapers to nothing has a small a_T there, a transom stern the
    added mass of its immersed transom (taken at the last station's centre)."""
    ok = np.flatnonzero(sp["valid"].values)
    if ok.size == 0:
        return 0.0, 0.0
    i = int(ok[np.argmin(sp["x"].values[ok])])
    x_t = float(sp["x"].values[i] - 0.5 * sp["dx"].values[i]) - xg
    a1, a3 = float(sp["lewis_a1"].values[i]), float(sp["lewis_a3"].values[i])
    mm = 0.5 * float(sp["breadth"].values[i]) / (1.0 + a1 + a3)
    return x_t, float(0.5 * rho * np.pi * mm * mm * ((1.0 + a1) ** 2 + 3.0 * a3 * a3))


def forward_speed_coefficients(mem: Memory, omega, speed: float, transom: tuple[float, float] = (0.0, 0.0)
                               ) -> tuple[np.ndarray, np.ndarray]:
    """Added mass and damping (nw, 2, 2) of heave and pitch at ``speed`` U [m/s] and the encounter
    frequencies ``omega`` [rad/s] implied by the kernel's forward-speed terms for the fitted model's
    zero-speed A(w), B(w) (``_kernels_6dof._memory``; force -A x'' - B x' for harmonic x):

        A35 - U B33 / w^2,  B35 + U A33,  A53 + U B33 / w^2,  B53 - U A33,
        A55 + (U^2 A33 + U (B35 - B53)) / w^2,  B55 + U^2 B33 / w^2 - U (A35 - A53 - A35(inf) + A53(inf)),

    and with the ``transom`` (x_T [m] from G, a_T [kg/m]) B33 + U a_T, A35 - U^2 a_T / w^2,
    B35 - U x_T a_T, B53 - U x_T a_T, A55 + U^2 x_T a_T / w^2, B55 + U x_T^2 a_T: Salvesen, Tuck &
    Faltinsen's (1970) table with the transom's added mass (its damping b^A left out) when the
    zero-speed coefficients are symmetric, as potential flow makes them (the fit's asymmetry is kept
    so that the kernel and this agree)."""
    w = np.asarray(omega, float)
    A = mem.added_mass(w)
    B = mem.damping(w)
    ai = mem.added_mass_inf
    U = float(speed)
    w2 = (w * w)[:, None]
    a33, b33 = A[:, 0, 0], B[:, 0, 0]
    Au, Bu = A.copy(), B.copy()
    Au[:, 0, 1] -= U * b33 / w2[:, 0]
    Bu[:, 0, 1] += U * a33
    Au[:, 1, 0] += U * b33 / w2[:, 0]
    Bu[:, 1, 0] -= U * a33
    Au[:, 1, 1] += (U * U * a33 + U * (B[:, 0, 1] - B[:, 1, 0])) / w2[:, 0]
    Bu[:, 1, 1] += U * U * b33 / w2[:, 0] - U * (A[:, 0, 1] - A[:, 1, 0] - ai[0, 1] + ai[1, 0])
    xt, at = transom
    Bu[:, 0, 0] += U * at
    Au[:, 0, 1] -= U * U * at / w2[:, 0]
    Bu[:, 0, 1] -= U * xt * at
    Bu[:, 1, 0] -= U * xt * at
    Au[:, 1, 1] += U * U * xt * at / w2[:, 0]
    Bu[:, 1, 1] += U * xt * xt * at
    return Au, Bu


def memory_parameters(mem: Memory, forward_speed: bool = False, trim: float = 0.0,
                      transom: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """The kernel's tail of the manoeuvring vector ``m`` (``_kernels_6dof.M_MEMORY`` on): the number
    of poles, the poles (re, im), the residues (re, im) in (pole, i, j) order, then 1 with strip
    theory's forward-speed terms (``_kernels_6dof._memory``; 0 without), the calm-water ``trim``
    theta_0 [rad] from which the pitch's relative velocity term counts and the ``transom`` (x_T from
    G [m], a_T [kg/m], :func:`transom`)."""
    n = len(mem.poles)
    out = np.zeros(1 + 2 * n + 8 * n + 4)
    out[-4] = 1.0 if forward_speed else 0.0
    out[-3] = trim
    out[-2:] = transom
    out[0] = n
    out[1:1 + 2 * n:2] = mem.poles.real
    out[2:2 + 2 * n:2] = mem.poles.imag
    c = np.transpose(mem.residues, (2, 0, 1)).ravel()  # (pole, i, j)
    out[1 + 2 * n:1 + 10 * n:2] = c.real
    out[2 + 2 * n:2 + 10 * n:2] = c.imag
    return out


def memory_forward_speed(model) -> tuple[float, float] | None:
    """The transom (x_T [m], a_T [kg/m]) if the 6-DOF model's radiation memory carries strip
    theory's forward-speed terms (the flag after the residues in ``model.m``), else None."""
    from stabflow.dynamics import _kernels_6dof as K6

    if model.m.size <= K6.M_MEMORY:
        return None
    e = K6.M_MEMORY + 1 + 10 * int(model.m[K6.M_MEMORY])
    if model.m.size <= e or model.m[e] == 0.0:
        return None
    return float(model.m[e + 2]), float(model.m[e + 3])


def radiation_checks(ds: xr.Dataset, mem: Memory) -> list:
    """Validation rows of the memory model against the BEM coefficients ``ds`` (matrix form,
    :func:`bem_radiation` or :func:`bem_from_dataset`): the largest error over the BEM's frequencies
    of the fitted damping and added mass of heave, pitch and their coupling, each relative to the
    entry's largest |B| / A(inf) of the diagonal it couples (consistency: the fit); A(inf) of heave
    and pitch extrapolated from the finite-frequency coefficients (:func:`infinite_frequency_estimate`
    at the model's order) against the BEM's infinite-frequency solution (independent: causality of
    the BEM data and the frequency range); passivity of the fitted damping (:func:`passivity`)."""
    from stabflow.validation import Check
    from stabflow.waves.synthesis import one_blas_thread

    omega = ds["omega"].values
    B, A = ds["damping"].values, ds["added_mass"].values
    Bf, Af = mem.damping(omega), mem.added_mass(omega)
    a_inf = ds["added_mass_inf"].values
    with one_blas_thread():
        est = infinite_frequency_estimate(ds, model_order(mem))
    src = ds.attrs.get("source", "Capytaine")
    band = f"{omega[0]:g}-{omega[-1]:.1f} rad/s"
    bmax = np.max(np.abs(np.diagonal(B, axis1=1, axis2=2)), axis=0)  # (2,) largest B33, B55
    rows = []
    for i, j, name in ((0, 0, "heave"), (1, 1, "pitch"), (0, 1, "heave-pitch coupling")):
        sb = np.sqrt(bmax[i] * bmax[j])
        sa = np.sqrt(abs(a_inf[i, i] * a_inf[j, j]))
        eb = float(np.max(np.abs(Bf[:, i, j] - B[:, i, j])) / sb)
        ea = float(np.max(np.abs(Af[:, i, j] - A[:, i, j])) / sa)
        scale = "max B" if i == j else "sqrt(max B33 max B55)"
        rows.append(Check(f"heave-pitch memory model ({len(mem.poles)} poles, order {model_order(mem)}): {name} "
                          f"damping B(w) of the fit vs the BEM's, largest error / {scale} over {band}",
                          eb, 0.05, "-", src, kind="consistency"))
        rows.append(Check(f"heave-pitch memory model: {name} added mass A(w) of the fit vs the BEM's, largest error / "
                          f"{'A(inf)' if i == j else 'sqrt(A33(inf) A55(inf))'} over {band}", ea, 0.05, "-", src,
                          kind="consistency"))
    for i, name in enumerate(("heave", "pitch")):
        rows.append(Check(f"heave-pitch radiation: {name} A(inf) extrapolated from A(w), B(w) over {band} (causal "
                          f"rational fit of order {model_order(mem)}) / the BEM's infinite-frequency solution - 1",
                          float(est[i, i] / a_inf[i, i] - 1.0), 0.05, "-", f"{src}, omega = inf", kind="independent"))
    rows.append(Check(f"heave-pitch memory model: passive (smallest eigenvalue of the fitted damping matrix scaled "
                      f"by its diagonal, over 0-{4 * omega[-1]:.1f} rad/s)", passivity(mem, float(omega[-1])), np.nan,
                      "-", "energy dissipation of radiation (B(w) positive semi-definite)", kind="consistency",
                      lower=-PASSIVITY_TOLERANCE))
    return rows


def _matrix(ds: xr.Dataset, q: str) -> np.ndarray:
    """(..., 2, 2) array of quantity ``q`` from its entries on disk."""
    first = ds[f"radiation_{q}_33"].values
    out = np.zeros(first.shape + (2, 2), dtype=first.dtype)
    for e in ENTRIES:
        out[(...,) + e[1]] = ds[f"radiation_{q}_{e[0]}"].values
    return out


def radiation_dataset(ds: xr.Dataset, mem: Memory) -> xr.Dataset:
    """The radiation step's results file: the BEM coefficients ``ds`` (matrix form) with the fitted
    model's A(w), B(w), K(t), poles and residues beside them, every 2 x 2 quantity entry by entry
    (module docstring)."""
    omega = ds["omega"].values
    t = np.arange(0.0, KERNEL_T + 0.5 * KERNEL_DT, KERNEL_DT)
    values = {"added_mass": ds["added_mass"].values, "damping": ds["damping"].values,
              "added_mass_inf": ds["added_mass_inf"].values, "added_mass_fit": mem.added_mass(omega),
              "damping_fit": mem.damping(omega), "kernel": retardation(omega, ds["damping"].values, t),
              "kernel_fit": mem.kernel(t), "residue_re": np.moveaxis(mem.residues.real, 2, 0),
              "residue_im": np.moveaxis(mem.residues.imag, 2, 0)}
    out = xr.Dataset(coords={"radiation_omega": omega, "time": t, "pole": np.arange(len(mem.poles))},
                     attrs=dict(ds.attrs))
    for q, dims, _, _ in QUANTITIES:
        for e in ENTRIES:
            out[f"radiation_{q}_{e[0]}"] = (dims, values[q][(...,) + e[1]])
    out["pole_re"] = ("pole", mem.poles.real)
    out["pole_im"] = ("pole", mem.poles.imag)
    out.attrs["fit"] = ("rational fit of K^(i w) = B + i w (A - A(inf)) with common poles (Sanathanan-Koerner "
                        "iteration; Perez & Fossen 2009), relative degree 1, zero at s = 0")
    out.attrs["order"] = model_order(mem)
    return annotate(out)


def bem_from_dataset(ds: xr.Dataset) -> xr.Dataset:
    """The BEM coefficients in matrix form (as :func:`bem_radiation` returns them) from the radiation
    step's file."""
    return xr.Dataset({"added_mass": (("omega", "i", "j"), _matrix(ds, "added_mass")),
                       "damping": (("omega", "i", "j"), _matrix(ds, "damping")),
                       "added_mass_inf": (("i", "j"), _matrix(ds, "added_mass_inf"))},
                      coords={"omega": ds["radiation_omega"].values}, attrs=dict(ds.attrs))


def memory_from_dataset(ds: xr.Dataset) -> Memory:
    """The fitted model stored by :func:`radiation_dataset`."""
    res = _matrix(ds, "residue_re") + 1j * _matrix(ds, "residue_im")  # (pole, 2, 2)
    return Memory(ds["pole_re"].values + 1j * ds["pole_im"].values, np.moveaxis(res, 0, 2),
                  _matrix(ds, "added_mass_inf"))


def uses_memory(ship) -> bool:
    """True if the ship's 6-DOF model radiates in heave and pitch through the memory model (ship
    config ``manoeuvring.heave_pitch_radiation: memory``)."""
    return ship.data.get("manoeuvring", {}).get("heave_pitch_radiation", "constant") == "memory"


def ship_radiation(ship, progress: bool = False) -> xr.Dataset:
    """The ``radiation`` step: heave-pitch BEM coefficients of the ship's mesh at its config loading
    (:func:`bem_radiation`), the fitted memory model (on one BLAS thread, like the BEM: bit-identical
    files) and the results file (:func:`radiation_dataset`)."""
    from stabflow.dynamics.hydro import bem_mesh
    from stabflow.geometry import Sections, build_hull
    from stabflow.hydrostatics.statics import compute_statics, equilibrium
    from stabflow.waves.synthesis import one_blas_thread

    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    sec = Sections(hull)
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    ds = bem_radiation(bem_mesh(ship), h0, th0, float(st["lcg"]), float(st["kg"]), ship.rho, progress=progress)
    ds.attrs.update(ship=ship.name)
    with one_blas_thread():
        return radiation_dataset(ds, fit_memory(ds))


def ship_memory(ship, lcg: float, radiation: xr.Dataset | None = None, progress: bool = False) -> Memory | None:
    """The ship's heave-pitch memory model for a loading with G at ``lcg`` [m] (None when the ship
    keeps the constant coefficients): from the ``radiation`` step's dataset, or computed now.

    The BEM coefficients are about G of the ship file's loading. Another KG moves the pitch axis
    vertically by dz: heave and the heave-pitch coupling's heave part are unchanged, and the pitch
    terms change only through the surge terms (A55 - 2 dz A15 + dz^2 A11, likewise B55 and K55; A35
    - dz A13), which the heave-pitch BEM does not compute and which are left out. Another LCG, ship
    or water density is refused."""
    if not uses_memory(ship):
        return None
    if radiation is None:
        radiation = ship_radiation(ship, progress=progress)
    from stabflow import StabflowError

    a = radiation.attrs
    field = f"{ship.path}: manoeuvring.heave_pitch_radiation"
    if a.get("ship", ship.name) != ship.name:
        raise StabflowError(f"{field}: the radiation coefficients are of ship {a['ship']!r}, not {ship.name!r}")
    if abs(float(a["xg"]) - lcg) > 1e-3:
        raise StabflowError(f"{field}: the radiation coefficients are about x = {float(a['xg']):.3f} m, the loading's "
                            f"G is at {lcg:.3f} m")
    if "rho" in a and abs(float(a["rho"]) - ship.rho) > 1e-6 * ship.rho:
        raise StabflowError(f"{field}: the radiation coefficients are for water of {float(a['rho']):g} kg/m3, the "
                            f"ship's is {ship.rho:g} kg/m3")
    return memory_from_dataset(radiation)
