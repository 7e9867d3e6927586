"""Linear diffraction force from Capytaine for the volume-based time domain (the hybrid model).

Paper 000 (introduction) and paper 004 (LAMP-2, section 2 and its Table 2) describe the hybrid
time-domain codes: Froude-Krylov and hydrostatic forces body-nonlinear over the instantaneous
wetted hull, the wave-body disturbance (radiation, diffraction) from a body-linear potential-flow
solution. stabflow's kernel computes the first exactly (volume-based, paper 000) and takes the
radiation as added mass and damping (or a memory model); this module adds the body-linear
diffraction force, the scattered wave's pressure on the hull at its calm-water equilibrium.

For each wave component n (amplitude a_n, frequency w_n, phase e_n; the stations' wave is
eta = a cos psi with psi = k cos(beta) x + e - w_e t, :func:`stabflow.waves.synthesis.station_wave_table`)
the force on the hull is Re(X(w_n, beta) a_n e^(i psi_n(x = 0))), with X the complex diffraction force
per unit wave amplitude of Capytaine's problem (e^(-i w t) convention, incident wave
Re(e^(i(k (x cos beta + y sin beta) - w t))), the same x forward, y to port, z up and the same body
origin as the stations). So F(t) = sum_n [Re c_n cos(w_e,n t) + Im c_n sin(w_e,n t)] with
c_n = a_n X(w_n) e^(i e_n): one more time series, added to the kernel's loads (moments about G).

The sway the 3-DOF model holds. With sway free, the wave's sway force (FK + diffraction) sways the
ship, and that sway's radiation force on the other modes, (w^2 A_j2 + i w B_j2) y with
y = F_2 / (-w^2 (m + A_22) - i w B_22), takes most of the diffraction's roll moment about G away:
in long waves F_2 = (m + A_22) times the fluid's acceleration and the diffraction's roll moment is
A_42 times it (G. I. Taylor's limit), so the two cancel and the roll excitation is the FK's alone.
A sway-held model given the bare diffraction force would keep the A_42 term (DTMB 5415 in beam seas:
roll excitation 1.16-1.20 of the FK's at and below the roll frequency, against 0.88-0.99 with the
sway free). The records therefore take the diffraction force plus the free sway's radiation
reaction (``which="sway_free"``, the table's ``sway_reaction``), from Capytaine's sway radiation
problem at each frequency. Left out: the sway that roll itself drives (A_24), which lowers the
effective roll inertia by A_42 A_24 / (m + A_22).

Approximations, stated in the README: zero-speed diffraction of each component at its own
frequency, applied with its encounter phase (forward-speed terms of the diffraction left out, as in
the radiation's constant coefficients); the hull at its upright calm-water equilibrium (body-linear);
X is interpolated linearly in frequency (and heading) on a table, zero in the long-wave limit
(w = 0) and zero beyond the table's highest frequency, where the panels no longer resolve the
wave (``PANEL_EXTENTS_PER_WAVELENGTH`` times the largest panel's extent along the waves' direction;
stabflow's rule, not a published one). The table's frequencies are equally spaced in wave number, by ``PHASE_STEP`` / the hull's
half extent along the waves (the phase of X turns by about k times that extent), so that linear
interpolation of the complex X is within about PHASE_STEP^2 / 8 of it. Capytaine solves with a lid
on the inner waterplane (irregular frequencies removed, :func:`stabflow.dynamics.hydro.lidded_body`).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.io import annotate
from stabflow.waves.synthesis import _time_series_table, encounter_frequency, one_blas_thread

#: Capytaine's rigid-body modes in the kernel's load order (force, then moment about G)
DOFS6 = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]
#: the table's headings [degree] (0 following, 180 head): the ensemble headings' range
HEADINGS_DEG = np.arange(0.0, 181.0, 15.0)
#: phase step [rad] of the table between frequencies: dk times the hull's half extent along the waves
PHASE_STEP = 0.4
#: the shortest resolved wave: this many times the largest panel extent along the direction of
#: propagation; half the heave-pitch radiation sweep's 13 largest panel radii
#: (:data:`stabflow.dynamics.radiation.PANEL_RADII_PER_WAVELENGTH`: a compact triangle's extent is
#: about two radii), taken along the waves because the long sliver panels of a mesh such as DTMB
#: 5415's (up to 14 m along x, 2.5 m across) resolve beam waves far shorter than head waves
PANEL_EXTENTS_PER_WAVELENGTH = 6.5
#: the fewest frequencies of a table (beam seas, where the phase across the hull turns slowly)
MIN_FREQUENCIES = 16


def _along(body, heading_deg: float) -> np.ndarray:
    """The hull vertices' coordinate [m] along the direction of propagation of waves of ``heading_deg``."""
    b = np.radians(heading_deg)
    v = body.mesh.vertices
    return v[:, 0] * np.cos(b) + v[:, 1] * np.sin(b)


def _extent_along(body, heading_deg: float) -> np.ndarray:
    """Each hull panel's extent [m] along the direction of propagation of waves of ``heading_deg``."""
    f = _along(body, heading_deg)[np.asarray(body.mesh.faces)]
    return f.max(axis=1) - f.min(axis=1)


def resolved_omega(body, headings_deg) -> float:
    """Highest wave frequency [rad/s] the panels resolve at every one of ``headings_deg``: wave length
    ``PANEL_EXTENTS_PER_WAVELENGTH`` times the largest panel extent along the waves."""
    ext = max(float(_extent_along(body, h).max()) for h in np.atleast_1d(headings_deg))
    return float(np.sqrt(2.0 * np.pi * G / (PANEL_EXTENTS_PER_WAVELENGTH * ext)))


def table_frequencies(body, headings_deg) -> np.ndarray:
    """Frequencies [rad/s] of the table (w = 0 excluded): equally spaced in wave number up to
    :func:`resolved_omega`, dk = ``PHASE_STEP`` / r with r the hull's largest half extent along the
    headings' directions of propagation, at least ``MIN_FREQUENCIES`` of them."""
    r = max(0.5 * float(np.ptp(_along(body, h))) for h in np.atleast_1d(headings_deg))
    k_max = resolved_omega(body, headings_deg) ** 2 / G
    n = max(MIN_FREQUENCIES, int(np.ceil(k_max * r / PHASE_STEP)))
    return np.sqrt(G * np.linspace(k_max / n, k_max, n))


def diffraction_dataset(body, rho: float, omegas=None, headings_deg=HEADINGS_DEG) -> xr.Dataset:
    """Diffraction (and, for checks, Froude-Krylov) force per unit wave amplitude on ``body`` (a
    Capytaine FloatingBody with the six rigid-body modes about G, at its calm-water equilibrium).

    Parameters
    ----------
    body : capytaine.FloatingBody
        Immersed hull with the dofs ``DOFS6`` (:func:`stabflow.dynamics.hydro.lidded_body`).
    rho : float
        Water density [kg/m^3].
    omegas : array, optional
        Wave frequencies [rad/s]; default :func:`table_frequencies`.
    headings_deg : array
        Wave headings [degree], 0 following, 180 head seas.

    Returns
    -------
    xarray.Dataset over (diffraction_omega, diffraction_heading, diffraction_mode): ``diffraction_re``/``_im``
    and ``froude_krylov_re``/``_im`` [N/m for forces, N for moments about G, per metre of wave
    amplitude]; ``sway_reaction_re``/``_im``: the radiation force of the sway the wave's sway force
    (Capytaine's FK + diffraction) drives on a free ship, (w^2 A_j2 + i w B_j2) F_2 / (-w^2 (m + A_22)
    - i w B_22), m = rho times the immersed volume (module docstring); the row omega = 0 is zero
    (long-wave limit).
    """
    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force

    cpt.set_logging("ERROR")
    headings_deg = np.asarray(headings_deg, float)
    w_max = resolved_omega(body, headings_deg)
    omegas = table_frequencies(body, headings_deg) if omegas is None else np.asarray(omegas, float)
    solver = cpt.BEMSolver()
    xd = np.zeros((len(omegas) + 1, len(headings_deg), 6), complex)
    fk = np.zeros_like(xd)
    sway = np.zeros_like(xd)
    mass = rho * float(body.mesh.volume)
    with one_blas_thread():  # the solve's rounding depends on BLAS's threads: the same in every job
        for i, w in enumerate(omegas):
            rad = solver.solve(cpt.RadiationProblem(body=body, radiating_dof="Sway", omega=float(w), rho=rho, g=G))
            # radiation force on mode q per unit sway (Capytaine's e^(-i w t)): w^2 A_q2 + i w B_q2
            react = np.array([w**2 * rad.added_mass[d] + 1j * w * rad.radiation_damping[d] for d in DOFS6])
            z22 = -w**2 * (mass + rad.added_mass["Sway"]) - 1j * w * rad.radiation_damping["Sway"]
            for j, b in enumerate(headings_deg):
                pb = cpt.DiffractionProblem(body=body, omega=float(w), wave_direction=float(np.radians(b)), rho=rho, g=G)
                res = solver.solve(pb)
                f = froude_krylov_force(pb)
                for q, d in enumerate(DOFS6):
                    xd[i + 1, j, q] = res.forces[d]
                    fk[i + 1, j, q] = f[d]
                sway[i + 1, j] = react * (fk[i + 1, j, 1] + xd[i + 1, j, 1]) / z22
    coords = {"diffraction_omega": np.concatenate([[0.0], omegas]), "diffraction_heading": headings_deg,
              "diffraction_mode": DOFS6}
    dims = ("diffraction_omega", "diffraction_heading", "diffraction_mode")
    ds = xr.Dataset(
        {
            "diffraction_re": (dims, xd.real), "diffraction_im": (dims, xd.imag),
            "froude_krylov_re": (dims, fk.real), "froude_krylov_im": (dims, fk.imag),
            "sway_reaction_re": (dims, sway.real), "sway_reaction_im": (dims, sway.imag),
        },
        coords=coords,
        attrs={"omega_max": w_max, "panels": int(body.mesh.nb_faces), "mass": mass,
               "lid_panels": int(body.lid_mesh.nb_faces) if body.lid_mesh is not None else 0, "rho": float(rho),
               "convention": "Capytaine e^(-i w t); incident wave Re(a e^(i(k(x cos b + y sin b) - w t))); "
                             "forces in earth axes, moments about G, per metre of wave amplitude"},
    )
    return annotate(ds)


class Diffraction:
    """The diffraction force of a table (:func:`diffraction_dataset`) at one heading, as time series
    of wave records.

    Parameters
    ----------
    ds : xarray.Dataset
        The table.
    heading_deg : float
        Wave heading [degree] of the records (interpolated linearly between the table's headings).
    which : str
        ``"sway_free"`` (the default: the diffraction force plus the free sway's radiation reaction,
        the force the sway-held 3-DOF records take, module docstring), ``"diffraction"`` (the bare
        diffraction force) or ``"froude_krylov"`` (the check against the kernel's own FK force).
    """

    def __init__(self, ds: xr.Dataset, heading_deg: float, which: str = "sway_free"):
        if which == "sway_free":
            x = ds["diffraction_re"] + ds["sway_reaction_re"] + 1j * (ds["diffraction_im"] + ds["sway_reaction_im"])
        else:
            x = ds[f"{which}_re"] + 1j * ds[f"{which}_im"]
        h = ds["diffraction_heading"].values
        if np.any(np.abs(h - heading_deg) < 1e-9):
            x = x.sel(diffraction_heading=h[np.argmin(np.abs(h - heading_deg))])
        elif len(h) > 1 and h[0] <= heading_deg <= h[-1]:
            x = x.interp(diffraction_heading=float(heading_deg))
        else:
            raise ValueError(f"heading {heading_deg} deg is not in the diffraction table's headings {list(h)}")
        self.omega = ds["diffraction_omega"].values
        self.x = x.transpose("diffraction_omega", "diffraction_mode").values  # (nw, 6)
        self.omega_max = float(self.omega[-1])
        self.heading_deg = float(heading_deg)

    def transfer(self, omega) -> np.ndarray:
        """X (n, 6) per unit amplitude at wave frequencies ``omega`` [rad/s]: linear in frequency,
        zero beyond the table's highest frequency (unresolved by the panels)."""
        omega = np.asarray(omega, float)
        out = np.empty((len(omega), 6), complex)
        for q in range(6):
            out[:, q] = (np.interp(omega, self.omega, self.x[:, q].real, right=0.0)
                         + 1j * np.interp(omega, self.omega, self.x[:, q].imag, right=0.0))
        return out

    def force_table(self, amp, omega, phase, speed: float, times) -> np.ndarray:
        """(nt, 6) float64 force [N] and moment about G [N m] of the components (amp [m], omega
        [rad/s], phase [rad]) at ``times`` [s] (equally spaced) for a ship at ``speed`` [m/s] on the
        table's heading: sum_n Re(a_n X(w_n) e^(i(e_n - w_e,n t))) (the kernel's ``ftab``)."""
        amp = np.asarray(amp, float)
        omega = np.asarray(omega, float)
        if not len(amp):
            return np.zeros((len(times), 6))
        c = amp[:, None] * self.transfer(omega) * np.exp(1j * np.asarray(phase, float))[:, None]  # (nc, 6)
        we = encounter_frequency(omega, speed, self.heading_deg)
        cols = [(c[None, :, q].real, c[None, :, q].imag) for q in range(6)]
        return _time_series_table(we, times, cols, np.float64)[:, 0, :]


def ftab(diffraction: "Diffraction | None", components, speed: float, heading_deg: float, times) -> np.ndarray:
    """The kernel's ``ftab`` for the wave ``components`` (amp, omega, phase) met at ``heading_deg``
    [degree] and ``speed`` [m/s] at ``times`` [s]: ``diffraction``'s force table, or a (0, 6) array
    without one (None). Raises ValueError when the force is for another heading."""
    if diffraction is None:
        return np.empty((0, 6))
    if abs(diffraction.heading_deg - heading_deg) > 1e-9:
        raise ValueError(f"the diffraction force is for {diffraction.heading_deg} deg, the waves come from "
                         f"{heading_deg} deg")
    return diffraction.force_table(*components, speed, times)


def generalized(X, xg: float, zg: float, h0: float, th0: float) -> np.ndarray:
    """Generalized forces (n, 3) on heave of G, roll and pitch of Capytaine-convention complex loads
    ``X`` (n, 6) (force, moment about G; amplitude A meaning Re(A e^(-i w t))) for the ship at rest at
    its equilibrium (origin height h0 [m], trim th0 [rad]; G at body x ``xg``, z ``zg`` [m]), in the
    e^(i w t) convention of :func:`stabflow.dynamics.linear.fk_excitation` (the complex conjugate)."""
    from stabflow.dynamics import _kernels as K
    from stabflow.dynamics.linear import _rest_parameters
    from stabflow.dynamics.rigid_body import coordinates_from_origin, generalized_loads

    p = _rest_parameters(1.0, xg, zg)
    q = coordinates_from_origin(h0, 0.0, th0, xg, zg)
    dofs = [K.S_Z, K.S_ROLL, K.S_PITCH]
    return np.array([generalized_loads(p, q, x.real)[dofs] - 1j * generalized_loads(p, q, x.imag)[dofs]
                     for x in np.atleast_2d(X)])


def ship_diffraction(ship, hull_equilibrium, rho: float, headings_deg=tuple(HEADINGS_DEG)) -> xr.Dataset:
    """The diffraction table of ``ship`` at its calm-water equilibrium ``hull_equilibrium`` =
    (h0 [m], th0 [rad], lcg [m], kg [m]) and ``headings_deg``, on its BEM mesh
    (:func:`stabflow.dynamics.hydro.bem_mesh`); kept in memory for the process (the same ship file,
    loading and headings are not solved twice)."""
    from stabflow.dynamics.hydro import bem_mesh, lidded_body

    h0, th0, xg, zg = (float(v) for v in hull_equilibrium)
    headings = tuple(float(b) for b in headings_deg)
    key = (str(ship.path), ship.name, h0, th0, xg, zg, float(rho), headings)
    if key not in _TABLES:
        body = lidded_body(bem_mesh(ship), h0, th0, xg, zg, DOFS6)
        ds = diffraction_dataset(body, rho, headings_deg=np.asarray(headings))
        ds.attrs.update(ship=ship.name, lcg=xg, kg=zg, h0=h0, th0=th0)
        _TABLES[key] = ds
    return _TABLES[key].copy()


#: the tables solved in this process (:func:`ship_diffraction`)
_TABLES: dict = {}
