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
equilibrium about G from Capytaine (linear potential flow at zero speed; the forward-speed terms of
strip theory are left out, as in the constant model).

The convolution runs as a state-space system. Its frequency response K^(w) = int_0^inf K(t)
exp(-i w t) dt = B(w) + i w (A(w) - A(inf)) is fitted in the frequency domain (Perez & Fossen 2009)
by one rational function of the four entries with a common denominator (Sanathanan & Koerner's
iteration), of relative degree 1 and with a zero at s = 0; its poles l_p and residues give
K_ij(t) = sum_p Re(c_ijp exp(l_p t)) (Im l_p >= 0), so each velocity q'_j drives the complex states
w_jp' = l_p w_jp + q'_j and the force is mu_i = sum_jp Re(c_ijp w_jp). The fit extends the
coefficients beyond the BEM's last frequency with the rational function's decay; the BEM stops
where the longest panel radius is a tenth of the wavelength (:func:`bem_frequencies`: above it the
trawler's damping turned negative). Checks: the fitted A(w), B(w) against Capytaine's (the fit), and
A(inf) extrapolated from the finite-frequency coefficients alone against Capytaine's
infinite-frequency solution (causality of the BEM data, Kramers-Kronig).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow.constants import G
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

    from stabflow.geometry.frames import earth_vertices

    cpt.set_logging("ERROR")
    ve = earth_vertices(np.asarray(mesh.vertices, float), 0.0, th0, h0)
    ge = earth_vertices(np.array([[xg, 0.0, zg]]), 0.0, th0, h0)[0]
    hull = cpt.Mesh(vertices=ve, faces=np.asarray(mesh.faces)).immersed_part()
    lid = hull.generate_lid(z=-1e-3 * float(np.ptp(hull.vertices[:, 2])))
    body = cpt.FloatingBody(mesh=hull, lid_mesh=lid, dofs=cpt.rigid_body_dofs(rotation_center=tuple(ge)))
    body = body.with_only_dofs(list(HEAVE_PITCH))
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


def _sk_fit(s: np.ndarray, H: np.ndarray, n: int, nnum: int, iterations: int = 30) -> tuple[np.ndarray, np.ndarray]:
    """Rational least squares H_r(s) ~ N_r(s) / Q(s) with one denominator for all responses
    (Sanathanan & Koerner 1963: the linearised problem N - H Q = 0 reweighted by 1 / |Q| of the last
    iterate): Q monic of degree ``n``, N_r of degree ``nnum`` with N_r(0) = 0. ``s`` (nw,) the
    (scaled) Laplace variable i w, ``H`` (nr, nw). Returns the ascending coefficients q (n + 1,) and
    N (nr, nnum + 1)."""
    nr, nw = H.shape
    scale = 1.0 / np.max(np.abs(H), axis=1)
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


def _residues(s: np.ndarray, H: np.ndarray, poles: np.ndarray) -> np.ndarray:
    """Residues (nr, np) of H_r(s) = sum_p r_p / (s - l_p) for fixed poles (complex ones in conjugate
    pairs, given once with Im > 0), least squares with real kernels: each pair contributes
    c / (s - l) + conj(c) / (s - conj(l)), a real pole c / (s - l) with c real."""
    cols, kind = [], []
    for lp in poles:
        h1, h2 = 1.0 / (s - lp), 1.0 / (s - np.conj(lp))
        if lp.imag > 0.0:
            cols += [h1 + h2, 1j * (h1 - h2)]  # c = a + i b: a (h1 + h2) + b i (h1 - h2)
            kind += [(len(cols) - 2, 1.0), (len(cols) - 1, 1j)]
        else:
            cols.append(h1)
            kind.append((len(cols) - 1, 1.0))
    X = np.column_stack(cols)
    out = np.zeros((H.shape[0], len(poles)), complex)
    for r in range(H.shape[0]):
        w = 1.0 / np.max(np.abs(H[r]))
        x = np.linalg.lstsq(np.vstack([(X * w).real, (X * w).imag]), np.r_[(H[r] * w).real, (H[r] * w).imag],
                            rcond=None)[0]
        c = np.zeros(len(poles), complex)
        j = 0
        for p, lp in enumerate(poles):
            c[p] = x[j] + (1j * x[j + 1] if lp.imag > 0.0 else 0.0)
            j += 2 if lp.imag > 0.0 else 1
        out[r] = c
    return out


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
    smallest up to ``max_order`` whose largest error is within ``tolerance`` of each response's
    largest |K^| (else the best); unstable poles reflected, residues refitted to the stable poles."""
    omega = ds["omega"].values
    A, B = ds["added_mass"].values, ds["damping"].values
    a_inf = ds["added_mass_inf"].values
    H = (B + 1j * omega[:, None, None] * (A - a_inf[None])).reshape(len(omega), 4).T  # (4, nw)
    sc = float(omega[-1])
    s = 1j * omega / sc
    best = None
    for n in ([order] if order is not None else range(2, max_order + 1)):
        q, _ = _sk_fit(s, H, n, n - 1)
        lam = _poles(q, sc)
        res = _residues(1j * omega, H, lam)  # residues of K^ in s = i w (unscaled)
        # K(t) = sum over all poles r e^{l t}: a pair r, conj(r) gives Re(2 r e^{l t}); a real pole r e^{l t}
        c = np.where(lam.imag > 0.0, 2.0, 1.0)[None, :] * res
        mem = Memory(lam, c.reshape(2, 2, len(lam)), a_inf)
        Hf = mem.response(omega).reshape(len(omega), 4).T
        err = float(np.max(np.abs(Hf - H) / np.max(np.abs(H), axis=1, keepdims=True)))
        # a fit that would feed energy into the motions somewhere is taken only if nothing else is
        key = (passivity(mem, sc) < -PASSIVITY_TOLERANCE, err)
        if best is None or key < best[0]:
            best = (key, mem)
        if not key[0] and err <= tolerance:
            break
    return best[1]


#: largest negative eigenvalue of the fitted damping, relative to its largest, that counts as passive
PASSIVITY_TOLERANCE = 0.01


def passivity(mem: Memory, w_max: float) -> float:
    """Smallest eigenvalue of the symmetric part of the fitted damping B(w) over 0 < w <= 4 ``w_max``
    [rad/s], relative to the largest |B_ij| there: >= 0 for a passive radiation model (the hull can
    only take energy out of the motions), negative where the fit would feed energy in."""
    w = np.linspace(1e-3 * w_max, 4.0 * w_max, 801)
    b = mem.damping(w)
    sym = 0.5 * (b + np.transpose(b, (0, 2, 1)))
    return float(np.min(np.linalg.eigvalsh(sym)) / np.max(np.abs(b)))


def infinite_frequency_estimate(ds: xr.Dataset, order: int) -> np.ndarray:
    """A(inf) (2, 2) extrapolated from the finite-frequency coefficients alone: B + i w A = K^(i w) +
    i w A(inf) fitted as one rational function whose numerator has degree order + 1 (its leading
    coefficient is A(inf)); compared with the BEM's own infinite-frequency solution it tests the
    coefficients' causality (the Kramers-Kronig relations) and the frequency range."""
    omega = ds["omega"].values
    A, B = ds["added_mass"].values, ds["damping"].values
    H = (B + 1j * omega[:, None, None] * A).reshape(len(omega), 4).T
    sc = float(omega[-1])
    _, N = _sk_fit(1j * omega / sc, H, order, order + 1)
    # N / Q in s / sc: the leading coefficient of the numerator in s is N_{n+1} / sc
    return (N[:, -1] / sc).reshape(2, 2)


def memory_parameters(mem: Memory) -> np.ndarray:
    """The kernel's tail of the manoeuvring vector ``m`` (``_kernels_6dof.M_MEMORY`` on): the number
    of poles, the poles (re, im) and the residues (re, im) in (pole, i, j) order."""
    n = len(mem.poles)
    out = np.zeros(1 + 2 * n + 8 * n)
    out[0] = n
    out[1:1 + 2 * n:2] = mem.poles.real
    out[2:2 + 2 * n:2] = mem.poles.imag
    c = np.transpose(mem.residues, (2, 0, 1)).ravel()  # (pole, i, j)
    out[1 + 2 * n::2] = c.real
    out[2 + 2 * n::2] = c.imag
    return out


def radiation_checks(ds: xr.Dataset, mem: Memory) -> list:
    """Validation rows of the memory model against the BEM coefficients ``ds``, for the diagonal
    entries: the largest error over the BEM's frequencies of the fitted damping and added mass, each
    relative to the entry's largest |B| / its A(inf) (consistency: the fit), and A(inf) extrapolated
    from the finite-frequency coefficients (:func:`infinite_frequency_estimate`) against the BEM's
    infinite-frequency solution (independent: causality of the BEM data and the frequency range)."""
    from stabflow.validation import Check

    omega = ds["omega"].values
    B, A = ds["damping"].values, ds["added_mass"].values
    Bf, Af = mem.damping(omega), mem.added_mass(omega)
    a_inf = ds["added_mass_inf"].values
    est = infinite_frequency_estimate(ds, len(mem.poles) * 2)
    src = ds.attrs.get("source", "Capytaine")
    band = f"{omega[0]:g}-{omega[-1]:.1f} rad/s"
    rows = []
    for i, name in enumerate(("heave", "pitch")):
        eb = float(np.max(np.abs(Bf[:, i, i] - B[:, i, i])) / np.max(np.abs(B[:, i, i])))
        ea = float(np.max(np.abs(Af[:, i, i] - A[:, i, i])) / abs(a_inf[i, i]))
        rows.append(Check(f"heave-pitch memory model ({len(mem.poles)} poles): {name} damping B(w) of the fit vs the "
                          f"BEM's, largest error / max B over {band}", eb, 0.05, "-", src, kind="consistency"))
        rows.append(Check(f"heave-pitch memory model: {name} added mass A(w) of the fit vs the BEM's, largest error "
                          f"/ A(inf) over {band}", ea, 0.05, "-", src, kind="consistency"))
        rows.append(Check(f"heave-pitch radiation: {name} A(inf) extrapolated from A(w), B(w) over {band} (rational "
                          f"fit, Kramers-Kronig) / the BEM's infinite-frequency solution - 1",
                          float(est[i, i] / a_inf[i, i] - 1.0), 0.05, "-", f"{src}, omega = inf", kind="independent"))
    rows.append(Check(f"heave-pitch memory model: passive (smallest eigenvalue of the fitted damping matrix over "
                      f"0-{4 * omega[-1]:.1f} rad/s / its largest entry)", passivity(mem, float(omega[-1])), np.nan, "-",
                      "energy dissipation of radiation (B(w) positive semi-definite)", kind="consistency",
                      lower=-PASSIVITY_TOLERANCE))
    return rows


def radiation_dataset(ds: xr.Dataset, mem: Memory) -> xr.Dataset:
    """The BEM coefficients with the fitted model's A(w), B(w) and K(t) beside them (results file of
    the ``radiation`` rule)."""
    omega = ds["omega"].values
    t = np.arange(0.0, KERNEL_T + 0.5 * KERNEL_DT, KERNEL_DT)
    out = ds.copy()
    dims = ("omega", "i", "j")
    out["added_mass_fit"] = (dims, mem.added_mass(omega))
    out["damping_fit"] = (dims, mem.damping(omega))
    out = out.assign_coords(time=("time", t), pole=("pole", np.arange(len(mem.poles))))
    out["kernel"] = (("time", "i", "j"), retardation(omega, ds["damping"].values, t))
    out["kernel_fit"] = (("time", "i", "j"), mem.kernel(t))
    out["pole_re"] = ("pole", mem.poles.real)
    out["pole_im"] = ("pole", mem.poles.imag)
    out["residue_re"] = (("i", "j", "pole"), mem.residues.real)
    out["residue_im"] = (("i", "j", "pole"), mem.residues.imag)
    out.attrs["fit"] = ("rational fit of K^(i w) = B + i w (A - A(inf)) with common poles (Sanathanan-Koerner "
                        "iteration; Perez & Fossen 2009), relative degree 1, zero at s = 0")
    return annotate(out)


def memory_from_dataset(ds: xr.Dataset) -> Memory:
    """The fitted model stored by :func:`radiation_dataset`."""
    return Memory(ds["pole_re"].values + 1j * ds["pole_im"].values, ds["residue_re"].values + 1j * ds["residue_im"].values,
                  ds["added_mass_inf"].values)


def uses_memory(ship) -> bool:
    """True if the ship's 6-DOF model radiates in heave and pitch through the memory model (ship
    config ``manoeuvring.heave_pitch_radiation: memory``)."""
    return ship.data.get("manoeuvring", {}).get("heave_pitch_radiation", "constant") == "memory"


def ship_radiation(ship, progress: bool = False) -> xr.Dataset:
    """The ``radiation`` step: heave-pitch BEM coefficients of the ship's mesh at its config loading
    (:func:`bem_radiation`), the fitted memory model and its checks
    (:func:`radiation_dataset`)."""
    from stabflow.dynamics.hydro import bem_mesh
    from stabflow.geometry import Sections, build_hull
    from stabflow.hydrostatics.statics import compute_statics, equilibrium

    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    sec = Sections(hull)
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    ds = bem_radiation(bem_mesh(ship), h0, th0, float(st["lcg"]), float(st["kg"]), ship.rho, progress=progress)
    return radiation_dataset(ds, fit_memory(ds))


def ship_memory(ship, lcg: float, radiation: xr.Dataset | None = None, progress: bool = False) -> Memory | None:
    """The ship's heave-pitch memory model for a loading with G at ``lcg`` [m] (None when the ship
    keeps the constant coefficients): from the ``radiation`` step's dataset, or computed now.

    The BEM coefficients are about G of the ship file's loading. Another KG moves the pitch axis
    vertically, which changes A55 and A35 only through the surge terms (A55 + 2 dz A15 + dz^2 A11),
    left out (for the trawler's heavy loading, dz = 0.42 m, about 0.4 % of A55); another LCG would
    change the heave-pitch coupling and is refused."""
    if not uses_memory(ship):
        return None
    if radiation is None:
        radiation = ship_radiation(ship, progress=progress)
    if abs(float(radiation.attrs["xg"]) - lcg) > 1e-3:
        from stabflow import StabflowError

        raise StabflowError(f"{ship.path}: manoeuvring.heave_pitch_radiation: the radiation coefficients are about "
                            f"x = {float(radiation.attrs['xg']):.3f} m, the loading's G is at {lcg:.3f} m")
    return memory_from_dataset(radiation)
