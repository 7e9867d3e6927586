"""3-DOF hybrid model: nonlinear volume-based FK + HS forces, ODE-like radiation terms.

Rigid-body equations about G (:mod:`stabflow.dynamics.rigid_body`): Newton for G and Euler in body
axes, projected on the coordinates (heave of G, roll, pitch) with surge, sway and yaw held
(constant speed and heading), plus added mass A33, A44, A55, linear damping B33, B44, B55 and
quadratic roll damping B44q on those coordinates. F, M from ``_fkhs`` (paper 000 eqs 9, 11, 12)
about G, with the body origin placed from G's height. Fixed-step RK4 (``_simulate``), wave
precomputed at the stations on the half-step grid.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import xarray as xr

from stabflow.config import Ship
from stabflow.geometry import Sections
from stabflow.io import annotate
from stabflow.constants import G
from stabflow.hydrostatics.statics import equilibrium
from stabflow.dynamics.diffraction import ftab as diffraction_ftab
from stabflow.waves.synthesis import station_wave_table
from stabflow.dynamics import _kernels as K
from stabflow.dynamics._kernels import _simulate
from stabflow.dynamics.rigid_body import THREE_DOF, coordinates_from_origin
from stabflow.dynamics.tables import SectionTables, kernel_args


@dataclass(frozen=True)
class Coefficients:
    """Rigid-body and wave-body coefficients [SI]: masses [kg], inertias about G [kg m^2], damping
    [N s/m, N m s/rad, N m s^2/rad^2], and the stiffnesses used to scale them. ``i66`` (yaw) is
    kept for 6-DOF use; the 3-DOF model does not use it."""

    mass: float
    a33: float
    i44: float
    a44: float
    i55: float
    a55: float
    b33: float
    b44: float
    b44q: float
    b55: float
    c33: float
    c44: float
    c55: float
    i66: float
    #: B44q [N m s^2/rad^2] against the running roll amplitude on the kernels' grid (0 to 90 degree
    #: in N_AMPLITUDES steps), from Ikeda's components (``dynamics.roll_damping: ikeda``); None:
    #: the constant ``b44q``
    b44q_table: np.ndarray | None = None
    #: where the roll damping comes from: "coefficients" (config / Capytaine) or "ikeda"
    roll_damping: str = "coefficients"

    def b44q_profile(self) -> np.ndarray:
        """B44q on the kernels' amplitude grid [N m s^2/rad^2] (constant unless Ikeda's)."""
        if self.b44q_table is not None:
            return np.asarray(self.b44q_table, float)
        return np.full(K.N_AMPLITUDES, self.b44q)

    def linear_roll(self) -> "Coefficients":
        """The same coefficients without quadratic roll damping (small-amplitude comparisons)."""
        return replace(self, b44q=0.0, b44q_table=None)

    def inertia_tensor(self) -> np.ndarray:
        """Inertia tensor about G in body axes (3, 3) [kg m^2] (principal axes assumed)."""
        return np.diag([self.i44, self.i55, self.i66])

    def added_mass_matrix(self) -> np.ndarray:
        """Added mass of the generalized coordinates (6, 6) [kg, kg m^2]: A33, A44, A55."""
        return np.diag([0.0, 0.0, self.a33, self.a44, self.a55, 0.0])

    def damping_matrix(self) -> np.ndarray:
        """Linear damping of the generalized coordinates (6, 6) [N s/m, N m s/rad]."""
        return np.diag([0.0, 0.0, self.b33, self.b44, self.b55, 0.0])

    def natural_frequency(self, mode: str) -> float:
        """Undamped natural frequency [rad/s] of 'heave', 'roll' or 'pitch'."""
        return 2 * np.pi / self.natural_period(mode)

    def natural_period(self, mode: str) -> float:
        """Undamped natural period [s] of 'heave', 'roll' or 'pitch'."""
        m, c = {"heave": (self.mass + self.a33, self.c33), "roll": (self.i44 + self.a44, self.c44),
                "pitch": (self.i55 + self.a55, self.c55)}[mode]
        return 2 * np.pi * np.sqrt(m / c)


def stiffness(sec: Sections, rho, xg, zg, h0, th0) -> tuple[float, float, float]:
    """C33 [N/m], C44 [N m/rad], C55 [N m/rad]: the diagonal of the restoring matrix
    (:func:`stabflow.dynamics.linear.stiffness_matrix`, central differences of step 1e-4)."""
    from stabflow.dynamics.linear import stiffness_matrix

    C = stiffness_matrix(sec, rho, xg, zg, h0, th0, step=1e-4)
    return float(C[0, 0]), float(C[1, 1]), float(C[2, 2])


def coefficients(ship: Ship, sec: Sections, st: xr.Dataset, hydro: xr.Dataset | None = None,
                 speed: float = 0.0) -> Coefficients:
    """Coefficients from the ship's ``dynamics`` config, or, with ``hydro`` (the Capytaine dataset
    of ``dynamics.hydro``), added mass and radiation damping at the natural frequencies plus the
    configured viscous roll damping.

    Each quantity is the absolute SI value when the config gives it (``i44`` [kg m^2], ``a33``
    [kg], ``b44`` [N m s/rad], ``b44q`` [N m s^2/rad^2], ...), else its fractional form (radius of
    gyration, ratio to the rigid-body value, fraction of critical damping at the mode's natural
    frequency, B44q / (I44 + A44)) with the schema's documented default when neither is given:
    kxx 0.40 B_wl, kyy = kzz 0.25 L_wl, A33/m 1.0, A44/I44 0.2, A55/I55 1.0, zeta 0.2 (heave,
    pitch) and 0.05 (roll), B44q/(I44+A44) 0.

    With ``dynamics.roll_damping: ikeda`` the roll damping comes from the hull and its bilge keels
    (:func:`ikeda_roll_damping`) at the ship ``speed`` [m/s]: B44 the linear part (friction, lifts,
    Capytaine wave damping) and B44q the quadratic part at ``dynamics.ikeda_amplitude_deg``, with
    the table of B44q against the running roll amplitude for the time domain.

    Raises
    ------
    StabflowError
        ``"<ship file>: dynamics.<a> and dynamics.<b>: give one, not both"`` when both forms of a
        quantity are given (the schema rejects this at load; overrides through
        :meth:`Ship.modified` are checked here); Ikeda's damping without the Capytaine ``hydro``
        dataset (the wave part) or with roll damping also given in the config.
    """
    from stabflow import StabflowError

    d = ship.data.get("dynamics", {})
    # each quantity: (absolute SI key, fractional key), as in the ship schema; at most one of each
    pairs = (("i44", "roll_gyradius"), ("i55", "pitch_gyradius"), ("i66", "yaw_gyradius"),
             ("a33", "added_mass_heave"), ("a44", "added_inertia_roll"), ("a55", "added_inertia_pitch"),
             ("b33", "damping_heave"), ("b44", "roll_damping_linear"), ("b55", "damping_pitch"),
             ("b44q", "roll_damping_quadratic"))
    for a, b in pairs:
        if a in d and b in d:
            raise StabflowError(f"{ship.path}: dynamics.{a} and dynamics.{b}: give one, not both")
    rho = ship.rho
    mass = float(st["mass"])
    L = float(st["lwl"])
    B = float(st["bwl"])

    def inertia(key, gyradius, default_k):
        return float(d[key]) if key in d else mass * d.get(gyradius, default_k) ** 2

    i44 = inertia("i44", "roll_gyradius", 0.40 * B)
    i55 = inertia("i55", "pitch_gyradius", 0.25 * L)
    i66 = inertia("i66", "yaw_gyradius", 0.25 * L)
    a33 = float(d["a33"]) if "a33" in d else d.get("added_mass_heave", 1.0) * mass
    a44 = float(d["a44"]) if "a44" in d else d.get("added_inertia_roll", 0.2) * i44
    a55 = float(d["a55"]) if "a55" in d else d.get("added_inertia_pitch", 1.0) * i55
    h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
    c33, c44, c55 = stiffness(sec, rho, float(st["lcg"]), float(st["kg"]), h0, th0)

    def crit(m, c, zeta):
        return 2 * zeta * np.sqrt(max(m * c, 0.0))

    def damping(key, fraction, default, m, c):
        """Absolute ``key`` [SI] if given, else ``fraction`` of critical for total inertia m."""
        return float(d[key]) if key in d else crit(m, c, d.get(fraction, default))

    def quadratic(m44):
        return float(d["b44q"]) if "b44q" in d else d.get("roll_damping_quadratic", 0.0) * m44

    if d.get("roll_damping", "coefficients") == "ikeda":
        given = [k for k in ("b44", "roll_damping_linear", "b44q", "roll_damping_quadratic") if k in d]
        if given:
            raise StabflowError(f"{ship.path}: dynamics.{given[0]}: roll damping is computed with roll_damping: ikeda; "
                                "give one, not both")
        if hydro is None:
            raise StabflowError(f"{ship.path}: dynamics.roll_damping: ikeda needs dynamics.hydro: capytaine "
                                "(the wave part of the roll damping is Capytaine's radiation damping)")
        a44h = float(hydro["added_roll"])
        b1, b2, table = ikeda_roll_damping(ship, sec, st, i44 + a44h, c44, float(hydro["damping_roll"]), speed)
        return Coefficients(
            mass=mass, a33=float(hydro["added_heave"]), i44=i44, a44=a44h, i55=i55,
            a55=float(hydro["added_pitch"]), b33=float(hydro["damping_heave"]), b44=b1, b44q=b2,
            b55=float(hydro["damping_pitch"]), c33=c33, c44=c44, c55=c55, i66=i66, b44q_table=table,
            roll_damping="ikeda",
        )
    if hydro is not None:
        a44h = float(hydro["added_roll"])
        bv = damping("b44", "roll_damping_linear", 0.05, i44 + a44h, c44)  # viscous part
        return Coefficients(
            mass=mass, a33=float(hydro["added_heave"]), i44=i44, a44=a44h, i55=i55,
            a55=float(hydro["added_pitch"]), b33=float(hydro["damping_heave"]), b44=float(hydro["damping_roll"]) + bv,
            b44q=quadratic(i44 + a44h), b55=float(hydro["damping_pitch"]), c33=c33, c44=c44, c55=c55, i66=i66,
        )
    return Coefficients(
        mass=mass, a33=a33, i44=i44, a44=a44, i55=i55, a55=a55,
        b33=damping("b33", "damping_heave", 0.2, mass + a33, c33),
        b44=damping("b44", "roll_damping_linear", 0.05, i44 + a44, c44),
        b44q=quadratic(i44 + a44),
        b55=damping("b55", "damping_pitch", 0.2, i55 + a55, c55),
        c33=c33, c44=c44, c55=c55, i66=i66,
    )


def config_coefficients(ship: Ship, sec: Sections, st: xr.Dataset) -> Coefficients:
    """:func:`coefficients` from the config alone: no Capytaine dataset, and the roll damping of the
    config keys (their defaults) even where the ship selects ``roll_damping: ikeda`` (the natural
    frequencies for the BEM run, and the equation checks of the validation)."""
    return coefficients(ship.modified(dynamics={"roll_damping": "coefficients"}), sec, st)


def ikeda_inputs(ship: Ship) -> dict:
    """The ship's Ikeda settings as keyword arguments of :mod:`stabflow.dynamics.roll_damping`:
    ``bilge_keels`` (:class:`~stabflow.dynamics.roll_damping.BilgeKeels` or None), ``normal_force``
    and ``rho``. Raises StabflowError naming the file and ``bilge_keels`` for inconsistent keels."""
    from stabflow import StabflowError
    from stabflow.dynamics.roll_damping import BilgeKeels

    keels = ship.data.get("bilge_keels")
    try:
        keels = None if keels is None else BilgeKeels.from_config(keels)
    except (ValueError, TypeError, KeyError) as e:
        raise StabflowError(f"{ship.path}: bilge_keels: {e}") from None
    return dict(bilge_keels=keels, normal_force=ship.data["dynamics"].get("ikeda_normal_force", "kato"), rho=ship.rho)


def ikeda_roll_damping(ship: Ship, sec: Sections, st: xr.Dataset, m44: float, c44: float, wave: float,
                       speed: float) -> tuple[float, float, np.ndarray]:
    """Roll damping from Ikeda's components (:mod:`stabflow.dynamics.roll_damping`, paper 004
    section 2.2) at the undamped natural roll frequency sqrt(C44 / (I44 + A44)) (``m44`` [kg m^2],
    ``c44`` [N m/rad]), ship ``speed`` [m/s], the ship's ``bilge_keels`` and the radiation
    damping ``wave`` [N m s/rad]: (B1 [N m s/rad], B2 [N m s^2/rad^2] at
    ``dynamics.ikeda_amplitude_deg``, B2 on the kernels' running-amplitude grid). The table's
    zero-amplitude entry takes the value at 1 degree (the components are defined for phi_a > 0)."""
    from stabflow.dynamics.roll_damping import equivalent_damping_table

    grid = np.degrees(np.arange(K.N_AMPLITUDES) * K.AMPLITUDE_STEP)
    ref = float(ship.data["dynamics"].get("ikeda_amplitude_deg", 10.0))
    tab = equivalent_damping_table(sec, st, amplitudes_deg=np.append(np.maximum(grid, 1.0), ref),
                                   omega=float(np.sqrt(c44 / m44)), speed=speed, wave=wave, **ikeda_inputs(ship))
    return float(tab["b1"][-1]), float(tab["b2"][-1]), tab["b2"].values[:-1].copy()


#: horizontal slices per section for :class:`SectionDecay` (exact where the width is linear across
#: a slice: everywhere on a polygon but in the slices holding its vertices)
DECAY_SLICES = 64


#: the half-height of the band about the calm waterline over which ``SectionDecay`` takes the side's
#: slope (the heeled section's waterline ends, ``SectionDecay.moments``' Gamma_B), as a fraction of
#: the waterline's breadth. The heel's part of the roll moment is sensitive to it on flared hulls
#: (beam waves at 2 w_phi, +-2 degree, against pressure integration on the exact surface: DTMB 5415
#: 8.9 / 5.7 / 1.5 / 5.8 / 30.5 % and the trawler 3.5 / 3.1 / 2.9 / 12.4 / 29.3 % at bands 0.005 /
#: 0.01 / 0.02 / 0.05 / 0.1; stabflow measurement 2026-12-07): the hull sections' polygons make the
#: local slope a noisy quantity; 0.02, the central secant over +-0.13 m (trawler) to +-0.4 m, was
#: chosen after these measurements, one value for all ships.
FLARE_BAND = 0.02


#: spacing of the wave-number grid of ``SectionDecay.tabulated`` times the sections' deepest slice
#: depth plus their largest half breadth L [m]: the integrands' k-derivatives scale with L, so
#: the four-point interpolation's error is about 0.023 (h L)^4 of the quantity's scale. Measured
#: (stabflow, 2026-12-07, 220 random wave numbers to 1 and 3 /m, the two cross-beam nodes at
#: 45 degree, each quantity's error against the exact slice sums relative to its largest value
#: over k at the station): at 0.1 F, Z, Y <= 1.9e-7, X <= 1.3e-5, D <= 1.6e-6 on the trawler,
#: barge, flared and tumblehome DTMB 5415 (0.05: <= 4.9e-7; 0.2: <= 2.0e-4), far inside the decay
#: factorisation's 1 % (``waves.synthesis.DECAY_RANK_TOLERANCE``). (The factor 0.023 is the interior
#: intervals'; in the first, read from nodes 0 ... 3, it is about 0.042.)
MOMENT_TABLE_STEP = 0.1
#: the most grid nodes of one ``SectionDecay.tabulated`` table; a call with a wave number beyond
#: them is summed exactly throughout (``SectionDecay.moments``)
MOMENT_TABLE_NODES = 4096


class SectionDecay:
    """The calm-water sections' area average of the incident wave's pressure decay,
    F_i(k) = (1 / A_i) int_{A_i} e^(k z) dA (z below the calm waterline, deep water), for the
    d2(phi0)/dz dt term of the volume-based vertical force, and of the horizontal pressure
    gradient (F_i and its first moment about the centroid, :meth:`moments`).

    Why this average: the linear Froude-Krylov heave force of a section is
    rho g a cos(psi) (b - k int_A e^(k z) dA) (Gauss's theorem on the section, b the waterline
    breadth), and the volume-based force is rho g (A + b eta) plus the term
    rho A d2phi0/dzdt: with d2phi0/dzdt = -g sum_n a_n k_n F_i(k_n) cos(psi_n) it is that force
    exactly for any section shape (a bulb, a skeg). Likewise the horizontal FK force is
    -rho g a k sin(psi) A F_i (the pressure gradient's area integral) and its moment about the
    centroid's height -rho g a k sin(psi) A Z_i. For a rectangle of draft T, F = (1 - e^(-k T)) /
    (k T). (Until 2026-12-05 the term used that rectangle formula with T = A / b, which a bulbous
    bow's small waterline breadth turned into 142-1806 m on the DTC and 1238 m on the trawler: no
    decay at those stations.)

    Parameters
    ----------
    sec : Sections
    h0 : float
        Calm-water height of the body origin [m] (``_kernels._origin_height``).
    th0 : float
        Calm-water trim [rad].
    slices : int
        Horizontal slices per section.
    """

    def __init__(self, sec: Sections, h0: float, th0: float, slices: int = DECAY_SLICES):
        from stabflow.geometry._kernels import _section_moments

        ct, st = np.cos(th0), np.sin(th0)
        nst = len(sec.x)
        self.slice_area = np.zeros((nst, slices))  # slice areas [m^2]
        self.slice_depth = np.zeros((nst, slices))  # slice mid-heights below the calm waterline [m] (< 0)
        self.slice_offset = np.zeros((nst, slices))  # slice centroid - mid-height [m]
        self.half_height = np.zeros(nst)  # slices' half height [m]
        self.slice_yy = np.zeros((nst, slices))  # slice int y^2 dA [m^4]
        self.slice_yy_tilt = np.zeros((nst, slices))  # upper half's int y^2 dA - lower half's [m^4]
        self.slice_breadth = np.zeros((nst, slices))  # slice area / height: its mean breadth [m]
        self.waterline_breadth = np.zeros(nst)  # breadth at the calm waterline [m]
        self.waterline_flare = np.zeros(nst)  # d(half breadth)/dz at the calm waterline [-]
        self.origin_height = np.zeros(nst)  # the body origin's height above the section's calm waterline [m]
        for i in range(nst):
            n = sec.n[i]
            c = st * sec.x[i] - h0  # calm waterline b z = c in the section's plane (a = 0, b = cos th0)
            zw = c / ct
            lo = float(np.min(sec.z[i, :n]))
            if lo >= zw:
                continue
            # slice bounds and mid-heights (int y^2 dA on both halves of each slice)
            fine = np.linspace(lo, zw, 2 * slices + 1)
            r = np.array([_section_moments(sec.y[i], sec.z[i], n, 0.0, 1.0, z) for z in fine])
            levels = fine[::2]
            a, m = r[::2, 0], r[::2, 2]
            dA = np.diff(a)
            yy = np.diff(r[:, 3])
            self.slice_yy[i] = yy[0::2] + yy[1::2]
            self.slice_yy_tilt[i] = yy[1::2] - yy[0::2]
            zm = 0.5 * (levels[1:] + levels[:-1])
            with np.errstate(invalid="ignore", divide="ignore"):
                zc = np.where(dA > 0, np.diff(m) / np.where(dA > 0, dA, 1.0), zm)
            self.slice_area[i] = dA
            self.slice_breadth[i] = dA / ((zw - lo) / slices)
            # the calm waterline's breadth: dA/dz over the top ten-thousandth of the depth
            dz = 1e-4 * (zw - lo)
            self.waterline_breadth[i] = (a[-1] - _section_moments(sec.y[i], sec.z[i], n, 0.0, 1.0, zw - dz)[0]) / dz
            # the side's slope at the waterline, d(b / 2)/dz: the breadths FLARE_BAND b above and below
            band = FLARE_BAND * self.waterline_breadth[i]
            if band > 0:
                above, below = ((_section_moments(sec.y[i], sec.z[i], n, 0.0, 1.0, z + dz)[0]
                                 - _section_moments(sec.y[i], sec.z[i], n, 0.0, 1.0, z)[0]) / dz
                                for z in (zw + band, zw - band - dz))
                self.waterline_flare[i] = (above - below) / (4.0 * band)
            self.origin_height[i] = -zw * ct
            self.slice_depth[i] = (zm - zw) * ct
            self.slice_offset[i] = (zc - zm) * ct
            self.half_height[i] = 0.5 * (zw - lo) / slices * ct
        self.total = self.slice_area.sum(axis=1)  # section areas [m^2]
        # the wave-number grid of :meth:`tabulated` (0: none, a dry hull) and its tables by heading
        reach = float(np.max(-self.slice_depth + self.half_height[:, None], initial=0.0)
                      + 0.5 * np.max(self.slice_breadth, initial=0.0))
        self.table_step = MOMENT_TABLE_STEP / reach if reach > 0 else 0.0  # [1/m]
        self._tables = {}
        # the calm sections' centroid height above the body origin [m] (body axes; 0 when dry)
        wet = self.total > 0
        depth = np.sum(self.slice_area * (self.slice_depth + self.slice_offset), axis=1) / np.where(wet, self.total, 1.0)
        self.centroid_height = np.where(wet, (st * np.asarray(sec.x) - h0 + depth) / ct, 0.0)

    def heel_weights(self, k, moments=None) -> tuple[np.ndarray, ...]:
        """The weights w_i(k_n) (each (nst, nc)) of the heeled section's six terms
        ``dynamics._kernels._fkhs`` sums as sum_n a_n k_n w_i(k_n) cos psi_n (the first three) and
        sin psi_n (the last three): 1 - F, A (1 - F), A (z_c (1 - F) + k Y - Z), then k, A k and
        A (z_c k (1 - F) + k^2 Y - k Z), with A the calm section's area [m^2] and z_c its centroid's
        height above the body origin [m] (F, Z, Y of :meth:`moments`, or ``moments`` when the
        caller has them for these ``k``)."""
        k = np.atleast_1d(np.asarray(k, float))
        F, Z, Y = self.moments(k) if moments is None else moments
        A = self.total[:, None]
        zc = self.centroid_height[:, None]
        kk = k[None, :]
        one = np.ones_like(F)
        return (1.0 - F, A * (1.0 - F), A * (zc * (1.0 - F) + kk * Y - Z),
                kk * one, A * kk * one, A * (zc * kk * (1.0 - F) + kk**2 * Y - kk * Z))

    def __call__(self, k) -> np.ndarray:
        """F_i(k_n) (nst, nc) for wave numbers ``k`` (nc,) [1/m]; 1 at a dry station."""
        return self.moments(k)[0]

    def moments(self, k, sin_beta=None) -> tuple[np.ndarray, ...]:
        """(F_i(k_n), Z_i(k_n), Y_i(k_n)), each (nst, nc), for wave numbers ``k`` (nc,) [1/m]: the
        area averages of e^(k z) [-], of (z - z_c) e^(k z) [m] (z_c the section's centroid) and of
        y^2 e^(k z) [m^2] (F = 1, Z = Y = 0 at a dry station). Z / F is the height of the horizontal
        pressure gradient's resultant above the centroid (it acts higher, where the pressure has
        decayed less); Y gives the roll moment of the vertical pressure gradient's variation across
        the beam (``_kernels._fkhs``). Y takes each slice's int y^2 dA as a density linear in z
        with its two halves' integrals I_1 (lower) and I_2 (upper) exact: e^(k z_m) [(I_1 + I_2) s1
        + 2 (I_2 - I_1) s2] (the density is (2 / 3) y_w^3, cubic in z for a width linear in z: the
        error is second order in k h, the slice's half height h; the slice's total at its mid-height
        alone was first order, 1.3e-2 on the DTC at k = 2 /m).

        With ``sin_beta`` (the waves' heading's sine, or a sequence of them: then (nb, nst, nc)) a
        fourth array, X_i(k_n) [m]: the linear
        vertical FK force's part that the sections' planar waterline leaves out. Gauss's theorem on
        a section in a long-crested wave of wave number k and k_y = k sin(beta) across the ship
        gives the force per unit length rho g a cos(psi) (b sinc(k_y b / 2) -
        k int e^(k z) cos(k_y y) dA) (b the calm waterline breadth, a symmetric section); the
        planar waterline and :meth:`moments`' F give rho g a cos(psi) (b - k A F). Their
        difference, X = b (sinc(k_y b / 2) - 1) - k int e^(k z) (sinc(k_y B / 2) - 1) dA (each
        slice's breadth B: one interval of y at each depth), is 0 in head and following waves and
        for waves long against the beam; in beam waves twice the roll frequency it is a third of the
        trawler's heave force (``_kernels._fkhs`` adds rho g X a cos(psi) per unit length: the
        linear heave force is then exact for any heading and section shape with one wet interval
        of y at each depth; the pitch moment keeps the surge force's part, whose area average F
        has no cos(k_y y); trimmed by theta the waterline's breadth is b / cos(theta), which X
        leaves out, a relative error of about theta^2 / 2).

        And a fifth, D (6, nst, nc) (or (nb, 6, nst, nc)): the same remainder of the horizontal
        force, its lever and the roll and yaw moments, as increments dF, dZ, dY_r, dY_y of F, Z and
        Y (``_kernels._decay_moments``). On the symmetric section, Gauss's theorem with the exact
        phase psi + k_y y gives the linear sway and surge forces rho g a (k_y, k_x) sin(psi)
        int e^(k z) cos(k_y y) dA (F's e^(k z) times each slice's mean sinc(k_y B / 2): dF, and at
        the height of their resultant: dZ), the yaw moment of the horizontal gradient's variation
        across the beam with int y sin(k_y y) e^(k z) dA in place of k_y int y^2 e^(k z) dA (each
        slice's y^2 moment times R(k_y B / 2) = 3 (sin u - u cos u) / u^3: dY_y) and the roll
        moment of the vertical gradient's the same, less the waterline's own term,
        -rho g a sin(psi) int (y sin(k_y y) - k_y y^2) dy = -rho g a sin(psi) k_y b^3 (R(k_y b / 2)
        - 1) / 12 (the planar waterline's lateral slope takes the wave as linear across the
        breadth): dY_r = dY_y - b^3 (R(k_y b / 2) - 1) / (12 k A). The kernel's S_h, S_hz, T_yy
        and U_yy then use F + dF, Z + dZ, Y + dY_r and Y + dY_y (``waves.synthesis``): the upright
        section's linear FK loads are then those of the exact phase in all six modes.

        D's last two, Gamma_B [m^2] and X + dF_y [m], are the heeled section's: the heel's part of
        the roll moment (the restoring's variation that drives parametric roll) of the field
        q = rho g a cos(psi) e^(k z) c(y), c = cos(k_y y) - 1, by which the exact phase's
        symmetric part exceeds the linearised one, for the section rotated by phi about the body
        origin (``origin_height`` z_B above the calm waterline): per unit length and rho g a
        cos(psi), dM_B/dphi = Gamma_B and dF_y/dphi = dF_y, so that about G, z_G above the origin,
        dM_G/dphi = Gamma_B + z_G (X + dF_y). With the rotation field (-z, y), the waterline's
        chord turning (-int y g(y, 0) dy) and the origin's lateral shift z_B phi,
        dM_O/dphi = -int e^(k z) [-k z c - 2 k y z c' + z^2 c'' + k^2 y^2 c - y c'] dA
        + k int_wl y^2 c dy - z_B int e^(k z) [k c + k y c' - z c''] dA
        + c(b / 2) b (z_B - (b / 2) tan(gamma)) (the waterline's ends moving with the side's slope
        tan(gamma) = d(b / 2)/dz, ``waterline_flare``), dF_y/dphi = int e^(k z) [z c'' - k y c'] dA
        + int_wl y c' dy - z_B int e^(k z) c'' dA, Gamma_B = dM_O/dphi + z_B dF_y/dphi, the
        slices' y-integrals in closed form (P(u) = 3 (u^2 sin u + 2 u cos u - 2 sin u) / u^3 for
        int y^2 cos(k_y y) dy). Checked against brute-force integration over a heeled box and a
        flared trapezoid (0.13 and 0.01 %; ``tests/dynamics/test_model.py``). The kernel adds them
        to the heeled section's W_2 and W_3 (``heel_weights``: (X + dF_y) / k and -Gamma_B / k).
        First order in the heel: on the box the field's heel part at 10 degree is 18 % below
        Gamma sin(10 degree). With the curved waterline none of D is applied, as X is not
        (``waves.synthesis``, ``_kernels_6dof._crossbeam_weights``), though only the waterline's
        parts are the parabola's: there the sway force in short beam waves stays 1 / sinc high
        (barge, 30 m: 2.42 times the exact surface's; an independent review, 2026-12-07)."""
        k = np.ascontiguousarray(np.atleast_1d(np.asarray(k, float)))
        nst = self.slice_area.shape[0]
        F, Z, Y = (np.empty((nst, len(k))) for _ in range(3))
        sbs = np.atleast_1d(np.asarray([] if sin_beta is None else sin_beta, float))
        X = np.empty((len(sbs), nst, len(k)))
        D = np.empty((len(sbs), 6, nst, len(k)))
        K._decay_moments(k, self.half_height, self.slice_depth, self.slice_area, self.slice_offset, self.slice_yy,
                         self.slice_yy_tilt, self.total, F, Z, Y, sbs, self.slice_breadth, self.waterline_breadth, X, D,
                         self.waterline_flare, self.origin_height)
        return _heading_shaped(sin_beta, F, Z, Y, X, D)

    def tabulated(self, k, sin_beta=None) -> tuple[np.ndarray, ...]:
        """:meth:`moments` by four-point (cubic) Lagrange interpolation in k on a uniform grid of
        spacing ``table_step`` [1/m] (``MOMENT_TABLE_STEP``), whose nodes are summed exactly on first
        need and kept for the heading sines ``sin_beta``: a record's 220 wave numbers then cost an
        interpolation (about 1 ms on 81 stations) instead of the slice sums (about 60 ms with the
        two cross-beam nodes of a 6-DOF record), and the grid up to the trawler's k = 1 /m is 74
        nodes. Each node does not depend on which others were computed before, so a record's
        moments do not depend on the records before it. Exact at the nodes (to round-off), and for
        a dry station (F = 1, the rest 0) exactly; error about
        0.023 (h L)^4 of each quantity's scale between them (``MOMENT_TABLE_STEP``; tested against
        :meth:`moments` in ``tests/dynamics/test_model.py``). A call with a wave number beyond
        ``MOMENT_TABLE_NODES`` nodes, and a dry hull (``table_step`` 0, also the way to ask for the
        exact sums), take :meth:`moments` itself."""
        k = np.ascontiguousarray(np.atleast_1d(np.asarray(k, float)))
        if len(k) and not (np.all(np.isfinite(k)) and np.min(k) >= 0):
            raise ValueError("SectionDecay.tabulated: wave numbers must be finite and >= 0")
        h = self.table_step
        need = int(np.floor(np.max(k, initial=0.0) / h)) + 4 if h > 0 else MOMENT_TABLE_NODES + 1
        if need > MOMENT_TABLE_NODES:
            return self.moments(k, sin_beta)
        sbs = np.atleast_1d(np.asarray([] if sin_beta is None else sin_beta, float))
        key = (h, *(float(v) for v in sbs))  # the grid's spacing too: ``table_step`` is public
        nst, nb = len(self.total), len(sbs)
        tab = self._tables.get(key, np.empty((0, 3 + 7 * nb, nst)))
        if tab.shape[0] < need:
            # the new nodes (a quarter more than needed, so that a few more records do not each
            # add one), each exact: F, Z, Y, then per heading X and D's six
            nodes = h * np.arange(tab.shape[0], max(need, min(MOMENT_TABLE_NODES, (5 * need) // 4)))
            F, Z, Y, X, D = self.moments(nodes, sbs)
            new = np.concatenate([np.stack([F, Z, Y]), np.concatenate([X[:, None], D], axis=1).reshape(7 * nb, nst,
                                                                                                        len(nodes))])
            tab = np.ascontiguousarray(np.concatenate([tab, new.transpose(2, 0, 1)]))
            self._tables[key] = tab
        out = np.empty((tab.shape[1], nst, len(k)))
        # in differences, so that a dry station's constants come out exactly (with plain weights,
        # whose sum is 1 only to round-off, 1 - F of 1e-17 there took a rank of the factorisation)
        K._lagrange_nodes(k, h, tab, out)
        XD = out[3:].reshape(nb, 7, nst, len(k))
        return _heading_shaped(sin_beta, out[0], out[1], out[2], XD[:, 0], XD[:, 1:])


def _heading_shaped(sin_beta, F, Z, Y, X, D):
    """:meth:`SectionDecay.moments`' return for its ``sin_beta``: (F, Z, Y) without one, X and D of
    the one heading for a scalar, of each (leading axis) for a sequence."""
    if sin_beta is None:
        return F, Z, Y
    return (F, Z, Y, X[0], D[0]) if np.ndim(sin_beta) == 0 else (F, Z, Y, X, D)


def section_decay(sec: Sections, h0: float, th0: float) -> SectionDecay:
    """:class:`SectionDecay` of ``sec`` at the calm-water pose (origin height ``h0`` [m], trim
    ``th0`` [rad])."""
    return SectionDecay(sec, h0, th0)


@dataclass(frozen=True)
class ModelParameters:
    """What the RK4 kernels need besides the sections and the wave, by name.

    Attributes: water density ``rho`` [kg/m^3], gravity ``g`` [m/s^2], centre of gravity ``xg``
    (from midships, + forward) and ``zg`` (above the baseline) [m], ``mass`` [kg], quadratic roll
    damping ``b44q`` (N_AMPLITUDES,) [N m s^2/rad^2] against the running roll amplitude, the wave
    heading as ``cos_beta``, ``sin_beta``, the inertia tensor about G in body axes ``inertia``
    (3, 3) [kg m^2], the ``added_mass`` and linear ``damping`` (6, 6) of the generalized coordinates
    (surge, sway, heave of G, roll, pitch, yaw)
    [kg, kg m^2; N s/m, N m s/rad] and ``free`` (6,): 1 for a free coordinate, 0 for a held one.
    """

    rho: float
    g: float
    xg: float
    zg: float
    mass: float
    b44q: np.ndarray
    cos_beta: float
    sin_beta: float
    inertia: np.ndarray
    added_mass: np.ndarray
    damping: np.ndarray
    free: tuple = THREE_DOF

    def vector(self) -> np.ndarray:
        """The kernels' parameter vector, in the order of the ``P_*`` positions of ``_kernels``."""
        v = np.empty(K.N_PARAMETERS)
        for name in self.__dataclass_fields__:
            x = np.ravel(np.asarray(getattr(self, name), float))
            i = getattr(K, f"P_{name.upper()}")
            v[i:i + x.size] = x
        return v


def parameters(co: Coefficients, rho: float, lcg: float, kg: float, heading_deg: float,
               free=THREE_DOF) -> np.ndarray:
    """Parameter vector of the RK4 kernels (``_rhs``) for coefficients ``co``, loading (LCG, KG [m]),
    wave heading [degree] and the free coordinates (default: the 3-DOF heave, roll, pitch)."""
    b = np.radians(heading_deg)
    return ModelParameters(rho=rho, g=G, xg=lcg, zg=kg, mass=co.mass, b44q=co.b44q_profile(), cos_beta=np.cos(b),
                           sin_beta=np.sin(b), inertia=co.inertia_tensor(), added_mass=co.added_mass_matrix(),
                           damping=co.damping_matrix(), free=tuple(free)).vector()


def initial_state(sec: Sections, st: xr.Dataset, phi0_deg: float = 0.0) -> np.ndarray:
    """State (N_STATE,) at rest in the free-floating calm-water equilibrium at heel ``phi0_deg``
    [degree] (heave and trim balanced at that heel, as a model heeled by a moment and released)."""
    V, lcg, kg = float(st["volume"]), float(st["lcg"]), float(st["kg"])
    phi0 = np.radians(phi0_deg)
    h0, th0, _ = equilibrium(sec, V, lcg, kg)
    h, th = (h0, th0) if phi0 == 0.0 else equilibrium(sec, V, lcg, kg, heel=phi0, guess=(h0, th0))[:2]
    s = np.zeros(K.N_STATE)
    s[:6] = coordinates_from_origin(h, phi0, th, lcg, kg)
    s[K.S_AMP] = s[K.S_PEAK] = abs(phi0)  # released from phi0: the first half-cycle's amplitude
    return s


#: the wave across each section in the FK + HS kernel
WATERLINES = ("planar", "curved")


def _check_waterline(waterline: str) -> bool:
    """True for the curved waterline; ValueError for an unknown name."""
    if waterline not in WATERLINES:
        raise ValueError(f"waterline must be one of {WATERLINES}, not {waterline!r}")
    return waterline == "curved"


def simulate(sec: Sections, st: xr.Dataset, co: Coefficients, rho: float, waves, heading_deg: float,
             speed: float, duration: float, dt: float, *, dphi_dzdt: bool = False, phi0_deg: float = 0.0,
             phi_cap_deg: float = 90.0, tables: SectionTables | None = None,
             waterline: str = "planar", diffraction=None) -> xr.Dataset:
    """Simulate one record from the calm-water equilibrium (optionally heeled to ``phi0_deg``).

    Parameters
    ----------
    waves : tuple of arrays
        (amp [m], omega [rad/s], phase [rad]) of the wave components (empty arrays: calm water).
    heading_deg : float
        Wave heading [degree], 0 following, 180 head seas.
    speed : float
        Ship speed [m/s].
    duration, dt : float
        Record length and RK4 step [s].
    phi0_deg, phi_cap_deg : float
        Initial heel and the capsize angle that stops the record [degree].
    tables : SectionTables, optional
        Tabulated sectional properties (fast); default: exact clipping.
    waterline : {"planar", "curved"}
        The wave across each section: its tangent plane at the centreline (paper 000, the default)
        or with the cross-beam curvature terms (:func:`stabflow.dynamics._kernels._curved_sections`;
        exact clipping, ``tables`` unused).
    diffraction : stabflow.dynamics.diffraction.Diffraction, optional
        The body-linear diffraction force added to the FK + HS loads (its table's heading must be
        ``heading_deg``); default none (paper 000's model).

    Returns
    -------
    xarray.Dataset along ``time`` [s]: heave of G [m] and its rate [m/s], roll and pitch [degree] and
    their rates [degree/s] (angles in degrees like every stabflow output), FK+HS loads; attributes
    ``capsized`` (0/1) and ``capsize_time`` [s] (record stops at the capsize angle, never NaN).
    """
    curved = _check_waterline(waterline)
    lcg, kg = float(st["lcg"]), float(st["kg"])
    rest = initial_state(sec, st)
    th0 = rest[K.S_PITCH]
    h0 = K._origin_height(rest[K.S_Z], 0.0, th0, lcg, kg)
    nsteps = int(round(duration / dt))
    t_half = np.arange(2 * nsteps + 1) * 0.5 * dt
    decay = section_decay(sec, h0, th0) if dphi_dzdt else None
    amp, omega, phase = waves
    if len(amp):
        wtab = station_wave_table(amp, omega, phase, sec.x, heading_deg, speed, t_half, decay, curvature=curved)
    else:
        wtab = np.zeros((len(t_half), len(sec.x), 2))
    ftab = diffraction_ftab(diffraction, waves, speed, heading_deg, t_half)
    p = parameters(co, rho, lcg, kg, heading_deg)
    s0 = rest if phi0_deg == 0.0 else initial_state(sec, st, phi0_deg)
    out = np.empty((nsteps + 1, K.N_STATE))
    forces = np.empty((nsteps + 1, 6))
    done = _simulate(*kernel_args(sec, None if curved else tables), p, wtab, ftab, dt, 0, nsteps, s0,
                     np.radians(phi_cap_deg), out, forces)
    n = done + 1
    t = np.arange(n) * dt
    r = K.S_RATE
    ds = xr.Dataset(
        {
            "heave": ("time", out[:n, K.S_Z] - rest[K.S_Z]), "roll": ("time", np.degrees(out[:n, K.S_ROLL])),
            "pitch": ("time", np.degrees(out[:n, K.S_PITCH] - th0)), "heave_rate": ("time", out[:n, r + K.S_Z]),
            "roll_rate": ("time", np.degrees(out[:n, r + K.S_ROLL])),
            "pitch_rate": ("time", np.degrees(out[:n, r + K.S_PITCH])),
            "fz": ("time", forces[:n, 2]), "mx": ("time", forces[:n, 3]), "my": ("time", forces[:n, 4]),
            "mz": ("time", forces[:n, 5]),
        },
        coords={"time": t},
    )
    capsized = int(done < nsteps)
    ds.attrs.update(capsized=capsized, capsize_time=float(t[-1]) if capsized else -1.0, dt=dt,
                    heading_deg=heading_deg, speed=speed, dphi_dzdt=int(dphi_dzdt), waterline=waterline)
    return annotate(ds)
