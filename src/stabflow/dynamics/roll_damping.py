"""Viscous roll damping by Ikeda's component method, as LAMP uses it (paper 004, section 2.2).

Paper 004 (LAMP, Table 1) names the sources of each viscous roll-damping component:

=============================  ==========================================  ==========
effect                         reference (paper 004 Table 1)               linearity
=============================  ==========================================  ==========
hull lift                      Himeno (1981)                               linear
bilge-keel lift                Himeno (1981); paper 004 eqs 1-11           linear
hull eddy-making               Tanaka (1960), Ikeda et al. (1978)          non-linear
bilge-keel eddy-making         Kato (1966); paper 004 eqs 12-16            non-linear
hull skin friction             Kato (1958), Tamiya (1972); eqs 17-19       (see below)
=============================  ==========================================  ==========

Paper 004 prints the equations only for the bilge-keel normal ("eddy-making") force (eqs 12-16),
the foil lift (eqs 1-11) and the skin friction in its quasi-steady form (eqs 17-19). The numbers
it does not print (Kato's frictional coefficient and equivalent radius, Ikeda's eddy-making
pressure model, Ikeda's hull lift, Ikeda's bilge-keel hull pressure and the forward-speed
corrections) are taken from the ITTC Recommended Procedure 7.5-02-07-04.5 "Estimation of Roll
Damping", Rev. 01 (2021), section 4.2 (Ikeda's method, which summarises Himeno 1981), cited
below as "ITTC eq. N", and from Kawahara, Maekawa & Ikeda (2009), "A simple prediction formula of
roll damping of conventional cargo ships on the basis of Ikeda's method and its limitation",
Proc. STAB 2009, pp. 387-398, cited as "K09 eq. N".

Conventions
-----------
SI units. Roll amplitude arguments in degrees (``roll_amplitude_deg``), everything else in SI:
``omega`` [rad/s], ``speed`` [m/s], damping coefficients B44 [N m s/rad] (linear / equivalent
linear) and [N m s^2/rad^2] (quadratic). ``OG`` is the distance from the calm waterline down to
the roll axis (taken at G), *positive when G lies below the waterline* (ITTC section 4.2, K09 §4.1),
i.e. OG = draft - KG.

Wave damping is not computed here: it is an input (``wave``), e.g. the Capytaine radiation roll
damping at the roll frequency.

Equivalent linearisation
------------------------
A quadratic moment B2 |phi'| phi' is replaced by B_eq phi' with B_eq = (8 / 3 pi) omega phi_a B2
(equal energy per cycle, ITTC eqs 15 and 26). The friction component of paper 004 (eq 17) is
already written as a coefficient times the roll-velocity *amplitude*, so its equivalent value is
the coefficient itself (see :func:`friction_damping`).

Left out (no usable source found, or not part of the LAMP table): the bilge-keel wave-making term
(ITTC eqs 60-61 give it only up to an unspecified proportionality, "~"), skeg and rudder
components, the stall cut-off of the lift (paper 004 eq 9, alpha_stall = 12 degree for hull and
bilge keels), which acts on the instantaneous angle of attack and belongs in the time-domain
kernel, not in these frequency-domain coefficients.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow.constants import G
from stabflow.geometry import Sections
from stabflow.geometry._kernels import _clip_half
from stabflow.hydrostatics.statics import equilibrium

#: sea water density [kg/m^3] (library default, as ``ship.rho``)
RHO = 1025.0
#: kinematic viscosity of sea water at 15 degC [m^2/s] (ITTC 7.5-02-01-03 fresh/sea water table)
NU = 1.19e-6

#: equivalent-linearisation factor of a quadratic moment, 8 / (3 pi) (ITTC eqs 15, 26)
EQ = 8.0 / (3.0 * np.pi)


# --------------------------------------------------------------------------------- bilge keels
@dataclass(frozen=True)
class BilgeKeels:
    """A pair (or ``count``) of bilge keels, placed as Ikeda assumes.

    Each keel is a flat plate of ``span`` (breadth b_BK) [m] normal to the hull at the middle of
    the bilge arc of the idealised section (vertical side, flat bottom, quarter-circle bilge of
    radius R; ITTC section 4.2.1, text after eq 57), running from ``x_start`` to ``x_end`` [m]
    (ship axes, from midships, positive forward).

    Parameters
    ----------
    span : float
        Bilge-keel breadth b_BK [m].
    length : float
        Bilge-keel length l_BK [m]; must equal ``x_end - x_start`` when both are given.
    x_start, x_end : float
        Longitudinal extent [m] from midships, positive forward.
    count : int
        Number of keels (2: one each side).
    """

    span: float
    length: float
    x_start: float
    x_end: float
    count: int = 2

    def __post_init__(self):
        if self.span <= 0 or self.length <= 0:
            raise ValueError("bilge keel span and length must be positive")
        if self.x_end <= self.x_start:
            raise ValueError("bilge keel x_end must lie forward of x_start")
        if abs((self.x_end - self.x_start) - self.length) > 1e-6 * max(self.length, 1.0):
            raise ValueError(f"bilge keel length {self.length} m differs from x_end - x_start "
                             f"= {self.x_end - self.x_start} m")

    @classmethod
    def from_config(cls, cfg: dict) -> "BilgeKeels":
        """From ``{"span": b, "length": l, "x_start": xa, "x_end": xf}`` [m]; any two of
        length / x_start / x_end, or ``"x_centre"`` with ``"length"``; optional ``"count"``."""
        span = float(cfg["span"])
        count = int(cfg.get("count", 2))
        if "x_centre" in cfg:
            xc, ln = float(cfg["x_centre"]), float(cfg["length"])
            return cls(span, ln, xc - ln / 2, xc + ln / 2, count)
        xa, xf, ln = cfg.get("x_start"), cfg.get("x_end"), cfg.get("length")
        if xa is None:
            xa = float(xf) - float(ln)
        if xf is None:
            xf = float(xa) + float(ln)
        if ln is None:
            ln = float(xf) - float(xa)
        return cls(span, float(ln), float(xa), float(xf), count)

    def fraction(self, x: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """Fraction of each station slab [x - dx/2, x + dx/2] covered by the keels."""
        lo = np.maximum(x - dx / 2, self.x_start)
        hi = np.minimum(x + dx / 2, self.x_end)
        return np.clip(hi - lo, 0.0, None) / dx


# ------------------------------------------------------------------------------ section geometry
def lewis_coefficients(h0, sigma):
    """Lewis-form parameters a1, a3 of sections with half-breadth/draft H0 and area coefficient sigma.

    Closed form of Lewis' two-parameter conformal map (as used by Ikeda's eddy-making model,
    ITTC eq 44, "a1, a3 are the Lewis-form parameters"): C1 = (3 + 4 sigma/pi) + (1 - 4 sigma/pi)
    ((H0 - 1)/(H0 + 1))^2, a3 = (-C1 + 3 + sqrt(9 - 2 C1)) / C1, a1 = (1 + a3)(H0 - 1)/(H0 + 1).
    (Read in von Kerczek & Tuck's form as quoted by rolldecay-estimators, ``ikeda_speed.py``.)
    Where the section cannot be mapped (9 - 2 C1 < 0) the square root is taken as zero.

    Parameters
    ----------
    h0, sigma : array_like
        H0 = B / (2 d) [-] and sigma = A / (B d) [-].

    Returns
    -------
    a1, a3 : ndarray [-]
    """
    h0 = np.asarray(h0, float)
    sigma = np.asarray(sigma, float)
    q = ((h0 - 1.0) / (h0 + 1.0)) ** 2
    c1 = (3.0 + 4.0 * sigma / np.pi) + (1.0 - 4.0 * sigma / np.pi) * q
    a3 = (-c1 + 3.0 + np.sqrt(np.clip(9.0 - 2.0 * c1, 0.0, None))) / c1
    a1 = (1.0 + a3) * (h0 - 1.0) / (h0 + 1.0)
    return a1, a3


def bilge_radius(breadth, draft, sigma):
    """Bilge radius R [m] of the idealised section (ITTC eq 57).

    R = 2 d sqrt(H0 (sigma - 1) / (pi - 4)), limited to d (H0 >= 1) or B/2 (H0 <= 1), i.e.
    R = min(R, d, B/2); zero for sigma >= 1.

    Parameters
    ----------
    breadth, draft : array_like
        Sectional breadth B and draft d [m].
    sigma : array_like
        Sectional area coefficient [-].
    """
    b = np.asarray(breadth, float)
    d = np.asarray(draft, float)
    h0 = np.divide(b, 2 * d, out=np.zeros_like(b), where=d > 0)
    arg = np.clip(h0 * (np.asarray(sigma, float) - 1.0) / (np.pi - 4.0), 0.0, None)
    r = 2.0 * d * np.sqrt(arg)  # ITTC eq 57, first case
    return np.minimum(np.minimum(r, d), b / 2)  # ITTC eq 57, second and third cases


@dataclass(frozen=True)
class HullParticulars:
    """Whole-ship quantities of the calm-water equilibrium that the method needs [SI].

    ``length`` is the waterline length (used as L_pp), ``breadth`` the maximum waterline breadth,
    ``draft`` the draft at midships, ``og`` = draft - KG (positive when G is below the waterline),
    ``cb`` = V / (L B d), ``cm`` the midship section coefficient A_M / (B d), ``volume`` [m^3].
    """

    length: float
    breadth: float
    draft: float
    og: float
    cb: float
    cm: float
    volume: float
    kg: float


def section_parameters(sec: Sections, st: xr.Dataset) -> xr.Dataset:
    """Per-station section quantities of Ikeda's method at the calm-water equilibrium.

    For each station the waterline height is z_w = (-h0 + x sin th0) / cos th0 (body axes) with
    (h0, th0) from :func:`stabflow.hydrostatics.statics.equilibrium`. The local draft is z_w minus
    the lowest point of the contour, the area is the immersed section area (both halves), and the
    breadth is the waterline breadth, or the largest immersed breadth where that is larger (bulbs,
    sonar domes), so that sigma <= 1 as Lewis forms require. Stations whose draft is below 2 % of
    the midship draft or whose breadth is below 2 % of the waterline breadth (the extreme ends)
    are marked ``valid = False`` and contribute nothing.

    Parameters
    ----------
    sec : Sections
        The ship's stations.
    st : xarray.Dataset
        The statics dataset (:func:`stabflow.hydrostatics.statics.compute_statics`).

    Returns
    -------
    xarray.Dataset
        Along ``station`` (coordinate ``x`` [m]): ``breadth`` B [m], ``draft`` d [m], ``area`` [m^2],
        ``sigma`` [-], ``h0`` = B/(2d) [-], ``bilge_radius`` R [m] (ITTC eq 57), ``lewis_a1``,
        ``lewis_a3`` [-], ``dx`` [m], ``valid`` [bool]; scalar ``og`` [m] (positive with G below
        the waterline), and the whole-ship ``length``, ``breadth_max``, ``draft_mid`` [m], ``cb``,
        ``cm`` [-], ``volume`` [m^3].
    """
    volume, lcg, kg = float(st["volume"]), float(st["lcg"]), float(st["kg"])
    h0, th0 = equilibrium(sec, volume, lcg, kg)[:2]
    ct, s_t = np.cos(th0), np.sin(th0)
    zw = (-h0 + sec.x * s_t) / ct
    nst = len(sec.x)
    breadth = np.zeros(nst)
    draft = np.zeros(nst)
    area = np.zeros(nst)
    for i in range(nst):
        n = int(sec.n[i])
        y, z = sec.y[i, :n], sec.z[i, :n]
        zk = float(z.min())
        d = zw[i] - zk
        if d <= 0:
            continue
        bw = 2.0 * sec.half_breadth(i, zw[i])
        below = z <= zw[i]
        bmax = 2.0 * float(y[below].max()) if below.any() else 0.0
        draft[i] = d
        breadth[i] = max(bw, bmax)
        area[i] = 2.0 * _clip_half(np.ascontiguousarray(y), np.ascontiguousarray(z), n, 0.0, 1.0, zw[i])[0]
    d_mid = float(st["draft_mid"])
    b_wl = float(st["bwl"])
    valid = (draft > 0.02 * d_mid) & (breadth > 0.02 * b_wl)
    sigma = np.where(valid, area / np.where(valid, breadth * draft, 1.0), 0.0)
    sigma = np.clip(sigma, 0.0, 1.0)
    h0s = np.where(valid, breadth / np.where(valid, 2 * draft, 1.0), 0.0)
    a1, a3 = lewis_coefficients(np.where(valid, h0s, 1.0), np.where(valid, sigma, 0.5))
    radius = np.where(valid, bilge_radius(breadth, draft, sigma), 0.0)
    # midship section coefficient from the station nearest midships (x = 0)
    im = int(np.argmin(np.abs(sec.x)))
    cm = float(area[im] / (breadth[im] * draft[im])) if valid[im] else float("nan")
    length = float(st["lwl"])
    og = d_mid - kg  # ITTC section 4.3: OG = d - KG, downward positive
    ds = xr.Dataset(
        {
            "breadth": ("station", breadth, {"units": "m", "long_name": "section breadth B (waterline, or largest immersed)"}),
            "draft": ("station", draft, {"units": "m", "long_name": "section draft d"}),
            "area": ("station", area, {"units": "m2", "long_name": "immersed section area"}),
            "sigma": ("station", sigma, {"units": "1", "long_name": "section area coefficient A / (B d)"}),
            "h0": ("station", h0s, {"units": "1", "long_name": "half breadth to draft ratio H0 = B / (2 d)"}),
            "bilge_radius": ("station", radius, {"units": "m", "long_name": "bilge radius R (ITTC 7.5-02-07-04.5 eq 57)"}),
            "lewis_a1": ("station", np.where(valid, a1, 0.0), {"units": "1", "long_name": "Lewis-form parameter a1"}),
            "lewis_a3": ("station", np.where(valid, a3, 0.0), {"units": "1", "long_name": "Lewis-form parameter a3"}),
            "dx": ("station", sec.dx.copy(), {"units": "m", "long_name": "station slab length"}),
            "valid": ("station", valid, {"units": "1", "long_name": "station used by the method"}),
            "og": ((), og, {"units": "m", "long_name": "distance from the waterline down to G (OG = d - KG)"}),
            "kg": ((), kg, {"units": "m", "long_name": "vertical centre of gravity above baseline"}),
            "length": ((), length, {"units": "m", "long_name": "waterline length, used as L_pp"}),
            "breadth_max": ((), b_wl, {"units": "m", "long_name": "maximum waterline breadth"}),
            "draft_mid": ((), d_mid, {"units": "m", "long_name": "draft at midships"}),
            "volume": ((), volume, {"units": "m3", "long_name": "displaced volume"}),
            "cb": ((), volume / (length * b_wl * d_mid), {"units": "1", "long_name": "block coefficient V / (L B d)"}),
            "cm": ((), cm, {"units": "1", "long_name": "midship section coefficient A_M / (B d)"}),
        },
        coords={"x": ("station", sec.x.copy(), {"units": "m", "long_name": "station position from midships, positive forward"})},
    )
    return ds


def particulars(sp: xr.Dataset) -> HullParticulars:
    """Whole-ship particulars from :func:`section_parameters`."""
    return HullParticulars(float(sp["length"]), float(sp["breadth_max"]), float(sp["draft_mid"]), float(sp["og"]),
                           float(sp["cb"]), float(sp["cm"]), float(sp["volume"]), float(sp["kg"]))


# ----------------------------------------------------------------------------------- components
def kato_friction_coefficient(r_f, phi_a, omega, nu=NU):
    """Kato's laminar frictional coefficient C_f [-] of a rolling hull.

    C_f = 1.328 (3.22 r_f^2 phi_a^2 / (T nu))^-0.5, T = 2 pi / omega (ITTC eq 38; Kato 1957;
    the effective Reynolds number 0.512 r^2 phi_a^2 omega / nu of ITTC eq 37 is the same group,
    0.512 * 2 pi = 3.22).

    Parameters
    ----------
    r_f : float
        Equivalent radius [m]. phi_a : roll amplitude [rad]. omega : frequency [rad/s].
    nu : float
        Kinematic viscosity [m^2/s].
    """
    period = 2.0 * np.pi / omega
    return 1.328 * (3.22 * r_f**2 * phi_a**2 / (period * nu)) ** -0.5  # ITTC eq 38


def friction_radius_area(length, breadth, draft, cb, og):
    """Kato's wetted surface S_f [m^2] and equivalent radius r_f [m] of the whole hull.

    S_f = L (1.7 d + C_B B) (ITTC eq 40), r_f = [(0.887 + 0.145 C_B)(1.7 d + C_B B) - 2 OG] / pi
    (ITTC eq 40.1; Kato 1957), OG positive downward.
    """
    girth = 1.7 * draft + cb * breadth
    s_f = length * girth  # ITTC eq 40
    r_f = ((0.887 + 0.145 * cb) * girth - 2.0 * og) / np.pi  # ITTC eq 40.1
    return s_f, r_f


def friction_damping(hp: HullParticulars, omega, phi_a, speed, rho=RHO, nu=NU) -> float:
    """Skin-friction roll damping b_44V [N m s/rad] of paper 004 eq 17 (Kato, Tamiya).

    b_44V = (1 + 4.1 U / (omega L)) (1/2) rho S r_s^3 C_f |eta4'| with the roll-velocity amplitude
    |eta4'| = omega phi_a (paper 004 eq 17; speed factor also ITTC eq 41), S and r_s from Kato's
    regressions (ITTC eqs 40, 40.1) and C_f Kato's laminar coefficient (ITTC eq 38).

    Because paper 004 (eqs 18-19) multiplies this coefficient by the *instantaneous* roll velocity
    with the *amplitude* held from the last peak, the equivalent linear coefficient of a harmonic
    roll is b_44V itself. Ikeda's frequency-domain form (ITTC eq 39) instead linearises the
    quadratic law, (4 / 3 pi) rho S r^3 phi_a omega C_f, i.e. 8 / (3 pi) = 0.849 times this value.
    With the laminar C_f (proportional to 1 / phi_a) the result does not depend on the amplitude.

    Parameters
    ----------
    hp : HullParticulars
    omega : float
        Roll frequency [rad/s].
    phi_a : float
        Roll amplitude [rad].
    speed : float
        Ship speed U [m/s].
    rho, nu : float
        Water density [kg/m^3], kinematic viscosity [m^2/s].

    Returns
    -------
    float
        b_44V [N m s/rad].
    """
    s_f, r_f = friction_radius_area(hp.length, hp.breadth, hp.draft, hp.cb, hp.og)
    cf = kato_friction_coefficient(r_f, phi_a, omega, nu)
    speed_factor = 1.0 + 4.1 * speed / (omega * hp.length)  # paper 004 eq 17 (Tamiya); ITTC eq 41
    return float(speed_factor * 0.5 * rho * s_f * r_f**3 * cf * omega * phi_a)  # paper 004 eq 17


def eddy_speed_factor(omega, length, speed):
    """Ikeda's forward-speed reduction of hull eddy damping, B_E / B_E0 [-].

    (0.04 K)^2 / (1 + (0.04 K)^2) with the reduced frequency K = omega L / U (ITTC eq 45;
    Ikeda, Himeno & Tanaka 1978); 1 at zero speed.
    """
    speed = np.asarray(speed, float)
    k = 0.04 * omega * length / np.where(speed > 0, speed, 1.0)
    return np.where(speed > 0, k**2 / (1.0 + k**2), 1.0)  # ITTC eq 45


def eddy_coefficient(sp: xr.Dataset) -> np.ndarray:
    """Ikeda's sectional eddy-making coefficient C_R [-] (Ikeda, Himeno & Tanaka 1978).

    C_R = (r_max / d)^2 C_P [(1 - f1 R/d)(1 - OG/d - f1 R/d) + f2 (H0 - f1 R/d)^2] (K09 eq 25;
    ITTC eq 43 prints the second factor without "- f1 R/d"), with
    C_P = 0.5 (0.87 e^-gamma - 4 e^-0.187 gamma + 3), f1 = 0.5 [1 + tanh(20 (sigma - 0.7))],
    f2 = 0.5 (1 - cos pi sigma) - 1.5 (1 - e^(-5 (1 - sigma))) sin^2 pi sigma (ITTC eq 43),
    gamma = sqrt(pi) f3 (r_max + 2 M / H sqrt(A0^2 + B0^2)) / (2 d (1 - OG/d) sqrt(H0' sigma')),
    f3 = 1 + 4 exp(-1.65e5 (1 - sigma)^2) and the Lewis-form quantities M, H, A0, B0, r_max at the
    argument psi that maximises r_max (ITTC eq 44). Zero at invalid stations, and where the fit
    of C_P goes negative (it does for gamma below about 0.2, i.e. no separation).
    """
    valid = sp["valid"].values
    b = sp["breadth"].values
    d = np.where(valid, sp["draft"].values, 1.0)
    sigma = np.where(valid, sp["sigma"].values, 0.5)
    h0 = np.where(valid, sp["h0"].values, 1.0)
    R = sp["bilge_radius"].values
    a1, a3 = sp["lewis_a1"].values, sp["lewis_a3"].values
    og = float(sp["og"])

    M = b / (2.0 * (1.0 + a1 + a3))  # ITTC eq 44

    def rmax(psi):  # ITTC eq 44
        return M * np.sqrt(((1 + a1) * np.sin(psi) - a3 * np.sin(3 * psi)) ** 2
                           + ((1 - a1) * np.cos(psi) + a3 * np.cos(3 * psi)) ** 2)

    arg = np.divide(a1 * (1 + a3), 4 * a3, out=np.full_like(a1, 2.0), where=np.abs(a3) > 1e-12)
    psi2 = np.where(np.abs(arg) <= 1.0, 0.5 * np.arccos(np.clip(arg, -1, 1)), 0.0)  # ITTC eq 44, psi_2
    r1, r2 = rmax(np.zeros_like(a1)), rmax(psi2)
    psi = np.where(r1 >= r2, 0.0, psi2)  # ITTC eq 44: psi_1 = 0 unless r_max(psi_2) is larger
    r_max = np.maximum(r1, r2)
    H = 1 + a1**2 + 9 * a3**2 + 2 * a1 * (1 - 3 * a3) * np.cos(2 * psi) - 6 * a3 * np.cos(4 * psi)  # ITTC eq 44
    A0 = (-2 * a3 * np.cos(5 * psi) + a1 * (1 - a3) * np.cos(3 * psi)
          + ((6 - 3 * a1) * a3**2 + (a1**2 - 3 * a1) * a3 + a1**2) * np.cos(psi))  # ITTC eq 44
    B0 = (-2 * a3 * np.sin(5 * psi) + a1 * (1 - a3) * np.sin(3 * psi)
          + ((6 + 3 * a1) * a3**2 + (3 * a1 + a1**2) * a3 + a1**2) * np.sin(psi))  # ITTC eq 44
    ogd = og / d
    h0p = h0 / (1 - ogd)  # ITTC eq 44, H0'
    sigp = (sigma - ogd) / (1 - ogd)  # ITTC eq 44, sigma'
    f3 = 1 + 4 * np.exp(-1.65e5 * (1 - sigma) ** 2)  # ITTC eq 44
    gamma = (np.sqrt(np.pi) * f3 * (r_max + 2 * M / H * np.sqrt(A0**2 + B0**2))
             / (2 * d * (1 - ogd) * np.sqrt(np.clip(h0p * sigp, 1e-12, None))))  # ITTC eq 44
    f1 = 0.5 * (1 + np.tanh(20 * (sigma - 0.7)))  # ITTC eq 43
    f2 = 0.5 * (1 - np.cos(np.pi * sigma)) - 1.5 * (1 - np.exp(-5 * (1 - sigma))) * np.sin(np.pi * sigma) ** 2  # ITTC eq 43
    cp = 0.5 * (0.87 * np.exp(-gamma) - 4 * np.exp(-0.187 * gamma) + 3)  # ITTC eq 43
    rd = f1 * R / d
    cr = (r_max / d) ** 2 * cp * ((1 - rd) * (1 - ogd - rd) + f2 * (h0 - rd) ** 2)  # K09 eq 25
    # the C_P fit is slightly negative for gamma < ~0.2 (no separation): no negative damping
    return np.where(valid, np.maximum(cr, 0.0), 0.0)


def eddy_damping_quadratic(sp: xr.Dataset, omega, speed, rho=RHO) -> float:
    """Hull eddy-making roll damping as a quadratic coefficient B2_E [N m s^2/rad^2].

    Ikeda's eddy moment is M = (1/2) rho d^4 C_R phi'|phi'| per unit length (ITTC eq 42), whose
    equivalent linear value (4 / 3 pi) rho d^4 omega phi_a C_R is ITTC eq 43; summed over the
    stations (sum of slab values) and reduced by the forward-speed factor of ITTC eq 45.
    """
    cr = eddy_coefficient(sp)
    d = sp["draft"].values
    b2 = float(np.sum(0.5 * rho * d**4 * cr * sp["dx"].values))  # ITTC eq 42 (per length) x dx
    return b2 * float(eddy_speed_factor(omega, float(sp["length"]), speed))  # ITTC eq 45


def hull_lift_damping(hp: HullParticulars, speed, rho=RHO) -> float:
    """Hull lift roll damping B_44L [N m s/rad] (Ikeda et al. 1978; Himeno 1981).

    B_L = (rho/2) U L d k_N l_0 l_R [1 - 1.4 OG/l_R + 0.7 OG^2 / (l_0 l_R)] (ITTC eq 33),
    l_0 = 0.3 d, l_R = 0.5 d (ITTC eq 34), k_N = 2 pi d/L + kappa (4.1 B/L - 0.045) (ITTC eq 35),
    kappa = 0, 0.1, 0.3 for C_M <= 0.92, <= 0.97, > 0.97 (ITTC eq 36). Linear in U.
    """
    L, B, d, og = hp.length, hp.breadth, hp.draft, hp.og
    l0, lr = 0.3 * d, 0.5 * d  # ITTC eq 34
    kappa = 0.0 if hp.cm <= 0.92 else (0.1 if hp.cm <= 0.97 else 0.3)  # ITTC eq 36
    kn = 2 * np.pi * d / L + kappa * (4.1 * B / L - 0.045)  # ITTC eq 35
    return float(0.5 * rho * speed * L * d * kn * l0 * lr * (1.0 - 1.4 * og / lr + 0.7 * og**2 / (l0 * lr)))  # ITTC eq 33


def _bilge_keel_geometry(sp: xr.Dataset, bk: BilgeKeels):
    """Per-station idealised bilge-keel geometry: fraction of slab with keel, root distance l
    (ITTC eq 56), lever of the keel's normal force at mid-span h_c, f (ITTC eq 51)."""
    valid = sp["valid"].values
    frac = bk.fraction(sp["x"].values, sp["dx"].values) * valid
    d = np.where(valid, sp["draft"].values, 1.0)
    b = sp["breadth"].values
    R = sp["bilge_radius"].values
    og = float(sp["og"])
    h0 = np.where(valid, sp["h0"].values, 1.0)
    k = 1 - np.sqrt(2) / 2
    # ITTC eq 56: roll axis to the keel root at the middle of the bilge arc
    l_root = d * np.sqrt((h0 - k * R / d) ** 2 + (1 - og / d - k * R / d) ** 2)
    # keel along s = (1, -1)/sqrt 2 from the bilge-circle centre (B/2 - R, R) above the keel; G at
    # height d - OG: the lever of a force normal to the keel at distance t along it is r_C . s + R + t
    lever_c = (b / 2 + d - og - 2 * R) / np.sqrt(2) + R + bk.span / 2
    f = 1 + 0.3 * np.exp(-160 * (1 - sp["sigma"].values))  # ITTC eq 51
    return frac, l_root, lever_c, f


def kato_normal_pressure(span, chord):
    """Kato's "coefficient of normal pressure" C_N [-] of a flat plate (paper 004 eq 14).

    Printed: 1.98 exp(-11.0 s/C) for s/C < 0.07, 1.98 exp(-11.0 C/s) for C/s < 0.07, and 1.18 for
    0.07 <= s/C <= 1/0.07 (s span, C chord). Implemented as printed; note that the printed branches
    do not meet at s/C = 0.07 (0.917 against 1.18).
    """
    r = span / chord
    if r < 0.07:
        return 1.98 * np.exp(-11.0 * r)  # paper 004 eq 14
    if 1.0 / r < 0.07:
        return 1.98 * np.exp(-11.0 / r)  # paper 004 eq 14
    return 1.18  # paper 004 eq 14


def kato_pressure_magnification(re):
    """Kato's "normal pressure magnification" C_A [-] (paper 004 eq 15).

    C_A = 1.95 - 0.25 lg R_E + 0.20 sin(pi/0.54 (lg R_E - 2.19)) for R_E < 1000, 1.0 above.
    Paper 004 prints "ln"; base-10 logarithms are used because only they make the printed
    formula continuous at R_E = 1000 (lg 1000 - 2.19 = 0.81 = 1.5 x 0.54, so the sine is -1 and
    C_A = 1.95 - 0.75 - 0.20 = 1.0 exactly; with natural logarithms it would jump from 0.37 to 1).
    """
    if re >= 1000.0:
        return 1.0  # paper 004 eq 15
    lg = np.log10(max(re, 1e-12))
    return float(1.95 - 0.25 * lg + 0.20 * np.sin(np.pi / 0.54 * (lg - 2.19)))  # paper 004 eq 15


def bilge_keel_normal_quadratic(sp: xr.Dataset, bk: BilgeKeels, omega, phi_a, rho=RHO, nu=NU) -> float:
    """Bilge-keel normal (eddy-making) force as a quadratic roll coefficient B2 [N m s^2/rad^2].

    LAMP's flat-plate model (paper 004 eqs 12-16, after Kato 1966): the normal flow at the keel's
    centre is V_N = h_c phi' (eq 12; h_c the lever of the keel's normal at mid-span), the force is
    (1/2) C_N C_S C_A C_K rho V_N^2 S C (eq 16) with C_S = C_K = 1 (paper 004 text), C_N from
    eq 14 with s/C = b_BK / l_BK and C_A from eq 15 at R_E = V_N S / nu (eq 13) taken at the
    peak normal velocity h_c omega phi_a. The moment of one keel per unit length is
    (1/2) C_N C_A rho b_BK h_c^3 phi'|phi'|; summed over the slabs the keels cover and the count.
    """
    frac, _, lever_c, _ = _bilge_keel_geometry(sp, bk)
    if not frac.any():
        return 0.0
    cn = kato_normal_pressure(bk.span, bk.length)  # paper 004 eq 14
    total = 0.0
    for i in np.flatnonzero(frac > 0):
        re = lever_c[i] * omega * phi_a * bk.span / nu  # paper 004 eq 13
        ca = kato_pressure_magnification(re)  # paper 004 eq 15
        total += 0.5 * cn * ca * rho * bk.span * lever_c[i] ** 3 * frac[i] * sp["dx"].values[i]  # paper 004 eq 16 x lever
    return bk.count * total


def bilge_keel_normal_ikeda_quadratic(sp: xr.Dataset, bk: BilgeKeels, phi_a, rho=RHO) -> float:
    """Ikeda's bilge-keel normal force (pair) as a quadratic coefficient B2 [N m s^2/rad^2].

    Equivalent linear value (8 / 3 pi) rho l^3 omega phi_a b_BK f^2 C_D per unit length
    (ITTC eq 50), C_D = 22.5 b_BK / (pi l phi_a f) + 2.4 (ITTC eq 48), f from ITTC eq 51,
    l from ITTC eq 56. Offered for comparison with the LAMP / Kato form; scaled to ``count``.
    """
    frac, l_root, _, f = _bilge_keel_geometry(sp, bk)
    cd = 22.5 * bk.span / (np.pi * l_root * phi_a * f) + 2.4  # ITTC eq 48
    per_len = rho * l_root**3 * bk.span * f**2 * cd  # ITTC eq 50 divided by (8/3pi) omega phi_a
    return float(np.sum(per_len * frac * sp["dx"].values)) * bk.count / 2.0


def bilge_keel_hull_damping(sp: xr.Dataset, bk: BilgeKeels, omega, phi_a, rho=RHO) -> float:
    """Hull pressure caused by the bilge keels (pair), equivalent linear B44 [N m s/rad].

    Ikeda et al. (1977a; ITTC eqs 52-57, K09 eqs 34-37): per unit length
    B' = (4 / 3 pi) rho l^2 f^2 omega phi_a d^2 (-A0 C_p- + B0 C_p+) with C_p+ = 1.2,
    C_p- = -22.5 b_BK / (pi l phi_a f) - 1.2 (ITTC eq 54), the negative-pressure length
    S0 = (0.3 pi l phi_a f / b_BK + 1.95) b_BK (ITTC eq 52) and A0, B0, m1..m8 of ITTC eq 55
    (idealised section with bilge radius R of eq 57; l of eq 56). The factor f^2 (pressure scaled
    with the flow speed at the bilge, as in the normal force of ITTC eq 50) is read from K09 eq 34;
    ITTC eq 53 prints only "4/(3 pi) C_p l_p dG". Scaled to ``count`` / 2.
    """
    frac, l_root, _, f = _bilge_keel_geometry(sp, bk)
    if not frac.any():
        return 0.0
    valid = sp["valid"].values
    d = np.where(valid, sp["draft"].values, 1.0)
    R = np.where(valid, sp["bilge_radius"].values, 0.0)
    h0 = np.where(valid, sp["h0"].values, 1.0)
    og = float(sp["og"])
    b = bk.span
    s0 = (0.3 * np.pi * l_root * phi_a * f / b + 1.95) * b  # ITTC eq 52
    cp_plus = 1.2  # ITTC text before eq 54
    cp_minus = -22.5 * b / (np.pi * l_root * phi_a * f) - 1.2  # ITTC eq 54
    m1 = R / d  # ITTC eq 55
    m2 = og / d
    m3 = 1 - m1 - m2
    m4 = h0 - m1
    den = (h0 - 0.215 * m1) * (1 - 0.215 * m1)
    m5 = (0.414 * h0 + 0.0651 * m1**2 - (0.382 * h0 + 0.0106) * m1) / den
    m6 = (0.414 * h0 + 0.0651 * m1**2 - (0.382 + 0.0106 * h0) * m1) / den
    long = s0 > 0.25 * np.pi * R
    m7 = np.where(long, s0 / d - 0.25 * np.pi * m1, 0.0)
    cos_arg = np.divide(s0, R, out=np.zeros_like(R), where=R > 0)
    m8 = np.where(long, m7 + 0.414 * m1, m7 + 1.414 * m1 * (1 - np.cos(cos_arg)))
    A0 = (m3 + m4) * m8 - m7**2  # ITTC eq 55
    B0 = (m2**2 / (3 * (h0 - 0.215 * m1)) + (1 - m1) ** 2 * (2 * m3 - m2) / (6 * (1 - 0.215 * m1))
          + m1 * (m3 * m5 + m4 * m6))  # ITTC eq 55
    integral = d**2 * (-A0 * cp_minus + B0 * cp_plus)  # ITTC eq 55
    # at large amplitudes the negative-pressure length S0 (eq 52) outgrows the idealised section and
    # the fitted distribution turns negative (DTMB 5415: beyond about 65 deg), which would feed
    # energy into the roll: a damping moment cannot, so each section's share is floored at zero
    integral = np.maximum(integral, 0.0)
    per_len = 4.0 / (3.0 * np.pi) * rho * l_root**2 * f**2 * omega * phi_a * integral  # ITTC eq 53, K09 eq 34
    return float(np.sum(per_len * frac * sp["dx"].values)) * bk.count / 2.0


def foil_lift_slope(span, chord):
    """Lift-curve slope C_Lalpha [1/rad] of a grounded foil (paper 004 eqs 6-8).

    Effective aspect ratio A_R = 2 S / C (eq 6), C_Lalpha = (pi/2) A_R for A_R < 2 (eq 7), else
    2 pi A_R / (A_R + 2) (eq 8, written 2 pi / (1 + 2/A_R) x A_R / A_R).
    """
    ar = 2.0 * span / chord  # paper 004 eq 6
    if ar < 2.0:
        return 0.5 * np.pi * ar  # paper 004 eq 7
    return 2.0 * np.pi / (1.0 + 2.0 / ar)  # paper 004 eq 8


def bilge_keel_lift_damping(sp: xr.Dataset, bk: BilgeKeels, speed, rho=RHO) -> float:
    """Bilge-keel lift roll damping [N m s/rad], linear in speed (paper 004 eqs 2-11; Himeno 1981).

    With the flow U along the chord and the normal velocity h_c phi' at the keel, the small-angle
    angle of attack is alpha = h_c phi' / U and the lift (1/2) rho C_Lalpha alpha U^2 S C (eq 11)
    acts normal to the keel with lever h_c: B = count (1/2) rho C_Lalpha U b_BK h_c^2 per unit
    keel length. For A_R < 2 this equals Jones' low-aspect-ratio lift of ITTC eqs 58-59 (Ikeda
    et al. 1994) in the small-angle limit. The stall cut-off of eq 9 is not applied here.
    """
    if speed <= 0:
        return 0.0
    frac, _, lever_c, _ = _bilge_keel_geometry(sp, bk)
    cla = foil_lift_slope(bk.span, bk.length)  # paper 004 eqs 6-8
    per_len = 0.5 * rho * cla * speed * bk.span * lever_c**2  # paper 004 eq 11, alpha = h_c phi'/U
    return float(np.sum(per_len * frac * sp["dx"].values)) * bk.count


def wave_speed_factor(omega, speed, draft, g=G):
    """Ikeda's forward-speed factor of the wave roll damping, B_W / B_W0 [-] (ITTC eqs 31-32).

    0.5 [(A2 + 1) + (A2 - 1) tanh(20 (Omega - 0.3)) + (2 A1 - A2 - 1) exp(-150 (Omega - 0.25)^2)],
    A1 = 1 + xi^-1.2 e^-2 xi, A2 = 0.5 + xi^-1 e^-2 xi, xi = omega^2 d / g, Omega = U omega / g.
    ITTC prints tanh(20 Omega - 0.3); 20 (Omega - 0.3) is used because only it gives B_W / B_W0 = 1
    at U = 0 (to within the exp(-150 x 0.25^2) tail, < 1e-3); the printed form gives 2.5 at
    omega = 0.5 rad/s, d = 6 m.
    """
    xi = omega**2 * draft / g  # ITTC eq 32
    om = speed * omega / g  # ITTC eq 32
    a1 = 1 + xi**-1.2 * np.exp(-2 * xi)  # ITTC eq 32
    a2 = 0.5 + xi**-1.0 * np.exp(-2 * xi)  # ITTC eq 32
    return 0.5 * ((a2 + 1) + (a2 - 1) * np.tanh(20 * (om - 0.3))
                  + (2 * a1 - a2 - 1) * np.exp(-150 * (om - 0.25) ** 2))  # ITTC eq 31


# ------------------------------------------------------------------------------------ public API
_LONG = {
    "friction": "skin-friction roll damping (Kato / Tamiya, paper 004 eq 17)",
    "eddy": "hull eddy-making roll damping (Ikeda, ITTC eqs 43-45)",
    "lift": "hull lift roll damping (Ikeda / Himeno, ITTC eq 33)",
    "bilge_keel_lift": "bilge-keel lift roll damping (paper 004 eqs 6-11)",
    "bilge_keel_normal": "bilge-keel normal force roll damping (Kato, paper 004 eqs 12-16)",
    "bilge_keel_hull": "hull pressure due to bilge keels (Ikeda, ITTC eqs 52-57)",
    "wave": "wave (radiation) roll damping, input",
    "total": "total roll damping",
}
COMPONENTS = tuple(_LONG)
_LINEAR = ("friction", "lift", "bilge_keel_lift", "wave")
_QUADRATIC = ("eddy", "bilge_keel_normal", "bilge_keel_hull")


def _as_keels(bilge_keels) -> BilgeKeels | None:
    if bilge_keels is None or isinstance(bilge_keels, BilgeKeels):
        return bilge_keels
    return BilgeKeels.from_config(dict(bilge_keels))


def _sp(sec, st):
    return sec if isinstance(sec, xr.Dataset) else section_parameters(sec, st)


def _parts(sp, omega, phi_a, speed, bk, wave, rho, nu, normal_force):
    """(linear [N m s/rad], quadratic [N m s^2/rad^2]) dicts of every component."""
    hp = particulars(sp)
    lin = {
        "friction": friction_damping(hp, omega, phi_a, speed, rho, nu),
        "lift": hull_lift_damping(hp, speed, rho),
        "bilge_keel_lift": bilge_keel_lift_damping(sp, bk, speed, rho) if bk else 0.0,
        "wave": float(wave),
    }
    quad = {"eddy": eddy_damping_quadratic(sp, omega, speed, rho), "bilge_keel_normal": 0.0, "bilge_keel_hull": 0.0}
    if bk:
        if normal_force == "kato":
            quad["bilge_keel_normal"] = bilge_keel_normal_quadratic(sp, bk, omega, phi_a, rho, nu)
        elif normal_force == "ikeda":
            quad["bilge_keel_normal"] = bilge_keel_normal_ikeda_quadratic(sp, bk, phi_a, rho)
        else:
            raise ValueError(f"normal_force must be 'kato' or 'ikeda', not {normal_force!r}")
        quad["bilge_keel_hull"] = bilge_keel_hull_damping(sp, bk, omega, phi_a, rho) / (EQ * omega * phi_a)
    return lin, quad


def ikeda_components(sec, st=None, *, omega: float, roll_amplitude_deg: float, speed: float,
                     bilge_keels=None, wave: float = 0.0, rho: float = RHO, nu: float = NU,
                     normal_force: str = "kato") -> xr.Dataset:
    """Equivalent linear roll damping B44 [N m s/rad] of each component at one roll condition.

    Parameters
    ----------
    sec : Sections or xarray.Dataset
        The ship's stations, or a precomputed :func:`section_parameters` dataset (then ``st`` is
        not needed).
    st : xarray.Dataset
        Statics dataset (volume, lcg, kg, draft_mid, bwl, lwl).
    omega : float
        Roll frequency [rad/s].
    roll_amplitude_deg : float
        Roll amplitude [degree].
    speed : float
        Ship speed [m/s].
    bilge_keels : BilgeKeels or dict or None
        Bilge keels (see :class:`BilgeKeels`), or None for a naked hull.
    wave : float
        Wave (radiation) roll damping [N m s/rad], e.g. Capytaine's B44 at ``omega``; added as is.
    rho, nu : float
        Water density [kg/m^3] and kinematic viscosity [m^2/s].
    normal_force : {"kato", "ikeda"}
        Bilge-keel normal force: LAMP's flat plate (paper 004 eqs 12-16, default) or Ikeda's
        oscillating-plate C_D (ITTC eqs 48-51).

    Returns
    -------
    xarray.Dataset
        Scalars ``friction``, ``eddy``, ``lift``, ``bilge_keel_lift``, ``bilge_keel_normal``,
        ``bilge_keel_hull``, ``wave``, ``total`` [N m s/rad] (``units`` and ``long_name`` attrs),
        plus ``omega`` [rad/s], ``roll_amplitude`` [degree], ``speed`` [m/s].
    """
    sp = _sp(sec, st)
    bk = _as_keels(bilge_keels)
    phi_a = np.radians(roll_amplitude_deg)
    lin, quad = _parts(sp, omega, phi_a, speed, bk, wave, rho, nu, normal_force)
    vals = dict(lin)
    vals.update({k: EQ * omega * phi_a * v for k, v in quad.items()})  # ITTC eqs 15, 26
    vals["total"] = sum(vals[k] for k in COMPONENTS if k != "total")
    ds = xr.Dataset({k: ((), float(vals[k]), {"units": "N m s/rad", "long_name": "equivalent linear " + _LONG[k]})
                     for k in COMPONENTS})
    ds["omega"] = xr.DataArray(float(omega), attrs={"units": "rad/s", "long_name": "roll frequency"})
    ds["roll_amplitude"] = xr.DataArray(float(roll_amplitude_deg), attrs={"units": "degree", "long_name": "roll amplitude"})
    ds["speed"] = xr.DataArray(float(speed), attrs={"units": "m/s", "long_name": "ship speed"})
    return ds


def linear_quadratic(sec, st=None, *, omega: float, roll_amplitude_deg: float, speed: float,
                     bilge_keels=None, wave: float = 0.0, rho: float = RHO, nu: float = NU,
                     normal_force: str = "kato") -> xr.Dataset:
    """Split the roll damping into B1 [N m s/rad] and B2 [N m s^2/rad^2].

    M = B1 phi' + B2 |phi'| phi', with B_eq = B1 + (8 / 3 pi) omega phi_a B2 (ITTC eq 15). Friction,
    hull and bilge-keel lift and wave are linear; hull eddy-making, bilge-keel normal force and
    bilge-keel hull pressure are quadratic. The hull-pressure coefficient (and, weakly, the
    friction coefficient through C_f and Kato's C_A) depend on the amplitude, so B1 and B2 are
    those at ``roll_amplitude_deg``; B_eq reproduces :func:`ikeda_components` there.

    Parameters
    ----------
    As :func:`ikeda_components`.

    Returns
    -------
    xarray.Dataset
        ``b1`` [N m s/rad], ``b2`` [N m s^2/rad^2], ``b_eq`` [N m s/rad], and per component
        ``<name>_b1`` or ``<name>_b2``.
    """
    sp = _sp(sec, st)
    bk = _as_keels(bilge_keels)
    phi_a = np.radians(roll_amplitude_deg)
    lin, quad = _parts(sp, omega, phi_a, speed, bk, wave, rho, nu, normal_force)
    b1, b2 = sum(lin.values()), sum(quad.values())
    ds = xr.Dataset({
        "b1": ((), b1, {"units": "N m s/rad", "long_name": "linear roll damping coefficient B1"}),
        "b2": ((), b2, {"units": "N m s2/rad2", "long_name": "quadratic roll damping coefficient B2"}),
        "b_eq": ((), b1 + EQ * omega * phi_a * b2,
                 {"units": "N m s/rad", "long_name": "equivalent linear roll damping B1 + 8/(3 pi) omega phi_a B2"}),
    })
    for k, v in lin.items():
        ds[f"{k}_b1"] = xr.DataArray(v, attrs={"units": "N m s/rad", "long_name": "linear " + _LONG[k]})
    for k, v in quad.items():
        ds[f"{k}_b2"] = xr.DataArray(v, attrs={"units": "N m s2/rad2", "long_name": "quadratic " + _LONG[k]})
    ds["roll_amplitude"] = xr.DataArray(float(roll_amplitude_deg), attrs={"units": "degree", "long_name": "roll amplitude"})
    return ds


def _sweep(sp, dim, values, units, long_name, make):
    rows = [make(v) for v in values]
    ds = xr.Dataset(
        {k: ((dim,), np.array([float(r[k]) for r in rows]), dict(rows[0][k].attrs)) for k in COMPONENTS},
        coords={dim: ((dim,), np.asarray(values, float), {"units": units, "long_name": long_name})},
    )
    return ds


def equivalent_damping_table(sec, st=None, *, omega: float, amplitudes_deg, speed: float, bilge_keels=None,
                             wave: float = 0.0, rho: float = RHO, nu: float = NU, normal_force: str = "kato") -> xr.Dataset:
    """B44 against roll amplitude for LAMP's quasi-steady time-domain use (paper 004 §2.2.4).

    Paper 004 (eqs 17-19 and the three-step procedure after them) evaluates the frequency-domain
    coefficients with the *running* amplitudes: at every time step, if the roll angle changed sign
    since the previous step, the roll amplitude becomes the largest |roll| since the previous zero
    crossing; likewise the roll-velocity amplitude from the roll velocity's zero crossings; the
    friction moment is then b_44V(amplitude) times the instantaneous roll velocity (eq 19). The
    kernel interpolates this table at the running amplitude (:class:`RunningAmplitude`).

    Parameters
    ----------
    amplitudes_deg : array_like
        Roll amplitudes [degree] (> 0).
    Others as :func:`ikeda_components`.

    Returns
    -------
    xarray.Dataset
        Along ``roll_amplitude`` [degree]: every component and ``total`` [N m s/rad], and ``b1``
        [N m s/rad], ``b2`` [N m s^2/rad^2] of :func:`linear_quadratic`.
    """
    sp = _sp(sec, st)
    amps = np.asarray(amplitudes_deg, float)
    kw = dict(omega=omega, speed=speed, bilge_keels=bilge_keels, wave=wave, rho=rho, nu=nu, normal_force=normal_force)
    ds = _sweep(sp, "roll_amplitude", amps, "degree", "roll amplitude",
                lambda a: ikeda_components(sp, roll_amplitude_deg=a, **kw))
    lq = [linear_quadratic(sp, roll_amplitude_deg=a, **kw) for a in amps]
    ds["b1"] = ("roll_amplitude", np.array([float(r["b1"]) for r in lq]), dict(lq[0]["b1"].attrs))
    ds["b2"] = ("roll_amplitude", np.array([float(r["b2"]) for r in lq]), dict(lq[0]["b2"].attrs))
    ds.attrs.update(omega=float(omega), speed=float(speed))
    return ds


def damping_vs_amplitude(sec, st=None, *, omega: float, amplitudes_deg, speed: float, **kw) -> xr.Dataset:
    """Components [N m s/rad] along ``roll_amplitude`` [degree] (for plots); see
    :func:`ikeda_components` for the keyword arguments."""
    return equivalent_damping_table(sec, st, omega=omega, amplitudes_deg=amplitudes_deg, speed=speed, **kw)


def damping_vs_speed(sec, st=None, *, omega: float, roll_amplitude_deg: float, speeds, **kw) -> xr.Dataset:
    """Components [N m s/rad] along ``speed`` [m/s] (for plots); see :func:`ikeda_components`."""
    sp = _sp(sec, st)
    ds = _sweep(sp, "speed", np.asarray(speeds, float), "m/s", "ship speed",
                lambda u: ikeda_components(sp, omega=omega, roll_amplitude_deg=roll_amplitude_deg, speed=u, **kw))
    ds.attrs.update(omega=float(omega), roll_amplitude=float(roll_amplitude_deg))
    return ds


class RunningAmplitude:
    """LAMP's running roll and roll-velocity amplitudes (paper 004, procedure after eq 19).

    At each step: (1) if the roll angle's sign differs from the previous step's, the roll
    amplitude becomes the largest |roll| since the previous zero crossing; (2) the same for the
    roll velocity; between crossings the amplitudes hold. Angles in whatever unit is fed in.

    Parameters
    ----------
    roll0, rate0 : float
        Initial amplitudes (used until the first zero crossings).
    """

    def __init__(self, roll0: float = 0.0, rate0: float = 0.0):
        self.roll_amplitude = float(roll0)
        self.rate_amplitude = float(rate0)
        self._prev = None
        self._max_roll = 0.0
        self._max_rate = 0.0

    def update(self, roll: float, rate: float) -> tuple[float, float]:
        """Feed one time step; returns (roll amplitude, roll-velocity amplitude)."""
        if self._prev is not None:
            pr, pv = self._prev
            if np.sign(roll) != np.sign(pr) and self._max_roll > 0:  # step 1
                self.roll_amplitude, self._max_roll = self._max_roll, 0.0
            if np.sign(rate) != np.sign(pv) and self._max_rate > 0:  # step 2
                self.rate_amplitude, self._max_rate = self._max_rate, 0.0
        self._max_roll = max(self._max_roll, abs(roll))
        self._max_rate = max(self._max_rate, abs(rate))
        self._prev = (roll, rate)
        return self.roll_amplitude, self.rate_amplitude


# --------------------------------------------------------------------------- simplified method
# Regression coefficients of Kawahara, Maekawa & Ikeda (2009), as laid out in ITTC 7.5-02-07-04.5
# (2021) Tables 1-5. Where the two differ, the paper's value is used (Q1 row 7 col 5: paper
# 31.4113508, ITTC 31.41135; Q4 row 2 col 1: paper -17.102, ITTC -17.109).
_Q1 = np.array([  # ITTC Table 1 (Q1), rows 1-18; columns multiply x1^4 .. x1^0
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [0.0, -0.002222, 0.040871, -0.286866, 0.599424],
    [0.0, 0.010185, -0.161176, 0.904989, -1.641389],
    [0.0, -0.015422, 0.220371, -1.084987, 1.834167],
    [-0.0628667, 0.4989259, 0.52735, -10.7918672, 16.616327],
    [0.1140667, -0.8108963, -2.2186833, 25.1269741, -37.7729778],
    [-0.0589333, 0.2639704, 3.1949667, -21.8126569, 31.4113508],
    [0.0107667, 0.0018704, -1.2494083, 6.9427931, -10.2018992],
    [0.0, 0.192207, -2.787462, 12.507855, -14.764856],
    [0.0, -0.350563, 5.222348, -23.974852, 29.007851],
    [0.0, 0.237096, -3.535062, 16.368376, -20.539908],
    [0.0, -0.067119, 0.966362, -4.407535, 5.894703],
    [0.0, 17.945, -166.294, 489.799, -493.142],
    [0.0, -25.507, 236.275, -698.683, 701.494],
    [0.0, 9.077, -84.332, 249.983, -250.787],
    [0.0, -16.872, 156.399, -460.689, 463.848],
    [0.0, 24.015, -222.507, 658.027, -660.665],
    [0.0, -8.56, 79.549, -235.827, 236.579]])
_Q2 = np.array([0.0, -1.402, 7.189, -10.993, 9.45])  # ITTC Table 1 (Q2): x4^4 .. x4^0
_Q3 = np.array([  # ITTC Table 2 (Q3): row i multiplies x4^(7-i); columns x2^6 .. x2^0
    [-7686.0287, 30131.5678, -49048.9664, 42480.7709, -20665.147, 5355.2035, -577.8827],
    [61639.9103, -241201.0598, 392579.5937, -340629.4699, 166348.6917, -43358.7938, 4714.7918],
    [-130677.4903, 507996.2604, -826728.7127, 722677.104, -358360.7392, 95501.4948, -10682.8619],
    [-110034.6584, 446051.22, -724186.4643, 599411.9264, -264294.7189, 58039.7328, -4774.6414],
    [709672.0656, -2803850.2395, 4553780.5017, -3888378.9905, 1839829.259, -457313.6939, 46600.823],
    [-822735.9289, 3238899.7308, -5256636.5472, 4500543.147, -2143487.3508, 538548.1194, -55751.1528],
    [299122.8727, -1175773.1606, 1907356.1357, -1634256.8172, 780020.9393, -196679.7143, 20467.0904]])
_Q4 = np.array([  # ITTC Table 3 (Q4)
    [-0.3767, 3.39, -10.356, 11.588],  # x1^3 .. x1^0
    [-17.102, 41.495, -33.234, 8.8007],  # x2^3 .. x2^0, times x4 (paper value -17.102)
    [36.566, -89.203, 71.8, -18.108],  # x2^3 .. x2^0
    [0.0, -0.0727, 0.7, -1.2818]])  # x1^3 .. x1^0 (AA32)
_Q5 = np.array([-1.05584, 12.688, -63.70534, 172.84571, -274.05701, 257.68705, -141.40915, 44.13177, -7.1654,
                -0.0495, 0.4518, -0.61655])  # ITTC Table 3 (Q5): (x4 - AA32)^9 .. ^1, then x1^2, x1, 1
_Q6 = np.array([  # ITTC Table 4 (Q6)
    [-79.414, 215.695, -215.883, 93.894, -14.848],
    [0.9717, -1.55, 0.723, 0.04567, 0.9408],
    [0.0, -219.2, 443.7, -283.3, 59.6]])
_Q7 = np.array([  # ITTC Table 5 (Q7)
    [0.0, -0.3651, 0.3907], [0.0, -2.21, 2.632], [0.00255, 0.122, 0.4794], [-0.8913, -0.0733, 0.0],
    [5.2857, -0.01185, 0.00189], [0.00125, -0.0425, -1.86], [-0.0657, 0.0586, 1.6164]])

#: range of the simplified method's regressions (K09 eqs 24, 38; ITTC eqs 82-83)
SIMPLIFIED_RANGE = {"cb": (0.50, 0.85), "b/d": (2.5, 4.5), "cm": (0.90, 0.99), "og/d": (-1.5, 0.2),
                    "omega_hat": (0.0, 1.0), "b_bk/b": (0.01, 0.06), "l_bk/l": (0.05, 0.40)}


def _simplified_wave_hat(x1, x2, x3, x4, w_hat):
    """K09 eq 24 / ITTC eqs 84-90 (x4 = 1 - OG/d here, as ITTC eq 85)."""
    p = [np.polyval(_Q1[r], x1) for r in range(18)]
    a11 = p[0] * x2**3 + p[1] * x2**2 + p[2] * x2 + p[3]  # ITTC eq 86, x4^2 terms
    a12 = p[4] * x2**3 + p[5] * x2**2 + p[6] * x2 + p[7]  # ITTC eq 86, x4^1 terms
    a13 = p[8] * x2**3 + p[9] * x2**2 + p[10] * x2 + p[11]  # ITTC eq 86, x4^0 terms
    aa11 = p[12] * x2**2 + p[13] * x2 + p[14]  # ITTC eq 87
    aa12 = p[15] * x2**2 + p[16] * x2 + p[17]  # ITTC eq 87
    aa1 = (aa11 * x3 + aa12) * (1 - x4) + 1.0  # ITTC eq 87
    a1 = (a11 * x4**2 + a12 * x4 + a13) * aa1  # ITTC eq 86
    a2 = np.polyval(_Q2, x4)  # ITTC eq 88
    aa31 = np.polyval(_Q4[0], x1) * (np.polyval(_Q4[1], x2) * x4 + np.polyval(_Q4[2], x2))  # ITTC eq 90
    xx4 = x4 - np.polyval(_Q4[3], x1)  # ITTC eq 90
    aa3 = aa31 * (np.polyval(np.r_[_Q5[:9], 0.0], xx4) + np.polyval(_Q5[9:], x1))  # ITTC eq 90
    a3 = sum(np.polyval(_Q3[i], x2) * x4 ** (6 - i) for i in range(7)) + aa3  # ITTC eq 89
    return a1 / w_hat * np.exp(-a2 * (np.log(w_hat) - a3) ** 2 / 1.44)  # K09 eq 24 (ITTC eq 84: 0.6944 = 1/1.44)


def _simplified_eddy_hat(x1, x2, x3, x4, w_hat, phi_a):
    """K09 eq 31 / ITTC eqs 99-105 with x2 = C_B (K09; ITTC eq 100 prints C_M)."""
    ae = (-0.0182 * x2 + 0.0155) * (x1 - 1.8) ** 3 + np.polyval(_Q6[0], x2)  # ITTC eq 102
    be1 = ((-0.2 * x1 + 1.6) * (3.98 * x2 - 5.1525) * x4
           * (x4 * np.polyval(_Q6[1, :3], x2) + np.polyval(_Q6[1, 3:], x2)))  # ITTC eq 103
    be2 = (0.25 * x4 + 0.95) * x4 + np.polyval(_Q6[2], x2)  # ITTC eq 104
    be3 = (46.5 - 15.0 * x1) * x2 + 11.2 * x1 - 28.6  # ITTC eq 105
    cr = ae * np.exp(be1 + be2 * x3**be3)  # ITTC eq 101
    return 4.0 * w_hat * phi_a / (3.0 * np.pi * x2 * x1**3) * cr  # ITTC eq 99


def _simplified_bk_hat(x1, x2, x3, x4, w_hat, phi_deg, x7, x8):
    """K09 eq 38 / ITTC eqs 106-113."""
    f1 = (x1 - 2.83) ** 2 * np.polyval(_Q7[0], x2) + np.polyval(_Q7[1], x2)  # ITTC eq 109
    f2 = np.polyval(_Q7[2], phi_deg)  # ITTC eq 110
    f3 = np.polyval(_Q7[3], x7) * x8**2 + np.polyval(_Q7[4], x7) * x8  # ITTC eq 108 (K09 eq 38, f3)
    bbk1 = x4 * (5.0 * x7 + 0.3 * x1 - 0.2 * x8 + np.polyval(_Q7[5], phi_deg))  # ITTC eq 111
    bbk2 = -15.0 * x7 + 1.2 * x2 - 0.1 * x1 + np.polyval(_Q7[6], x4)  # ITTC eq 112
    bbk3 = 2.5 * x4 + 15.75  # ITTC eq 113
    return f1 * f2 * f3 * np.exp(bbk1 + bbk2 * x3**bbk3) * w_hat  # ITTC eqs 106, 108


def simplified_ikeda(length: float, breadth: float, draft: float, cb: float, cm: float, og: float, *,
                     omega: float, roll_amplitude_deg: float, speed: float = 0.0, bk_span: float = 0.0,
                     bk_length: float = 0.0, rho: float = RHO, nu: float = NU, g: float = G) -> xr.Dataset:
    """Ikeda's simplified method (Kawahara, Maekawa & Ikeda 2009) [N m s/rad].

    Regression of Ikeda's method over a methodical (Taylor-series) family of cargo-ship hulls:
    friction K09 eqs 20-23 (with the C_f exponent -1/2 as corrected in ITTC eq 96 and C_B as in
    K09), wave K09 eq 24 (ITTC eqs 84-90), eddy K09 eq 31 (ITTC eqs 99-105), bilge keels
    K09 eq 38 (ITTC eqs 106-113), hull lift ITTC eqs 91-94. Forward speed: friction x
    (1 + 4.1 U/(omega L)) (ITTC eq 41), eddy x ITTC eq 45, wave x ITTC eq 31; bilge keels not
    corrected (ITTC section 4.2.1). Non-dimensional values B^ = B44 / (rho V B^2) sqrt(B / 2 g),
    omega^ = omega sqrt(B / 2 g) (ITTC eqs 27-28) with V = C_B L B d.

    Stated accuracy: within the ranges of ``SIMPLIFIED_RANGE`` the formulas agree with Ikeda's
    method to about 10 % (K09 section 5, Fig. 14). ``out_of_range`` lists the violated limits;
    nothing is clamped.

    Parameters
    ----------
    length, breadth, draft : float
        L_pp, B, d [m].
    cb, cm : float
        Block and midship-section coefficients [-].
    og : float
        Waterline to G, positive downward (OG = d - KG) [m].
    omega : float
        Roll frequency [rad/s].
    roll_amplitude_deg : float
        Roll amplitude [degree].
    speed : float
        Ship speed [m/s].
    bk_span, bk_length : float
        Bilge-keel breadth b_BK and length l_BK [m] (0: no keels).
    rho, nu, g : float
        Density [kg/m^3], kinematic viscosity [m^2/s], gravity [m/s^2].

    Returns
    -------
    xarray.Dataset
        ``friction``, ``wave``, ``eddy``, ``lift``, ``bilge_keel``, ``total`` [N m s/rad]; the
        same non-dimensional as ``<name>_hat`` [-]; attribute ``out_of_range`` (str).
    """
    phi_a = np.radians(roll_amplitude_deg)
    x1, x2, x3, x4 = breadth / draft, cb, cm, og / draft
    scale = np.sqrt(breadth / (2 * g))
    w_hat = omega * scale  # ITTC eq 28
    to_dim = rho * cb * length * breadth * draft * breadth**2 / scale  # ITTC eq 27 inverted
    # friction, K09 eqs 20-23 (ITTC eqs 95-96 with C_B)
    r_f = ((0.887 + 0.145 * cb) * (1.7 * draft + cb * breadth) - 2.0 * og) / np.pi  # K09 eq 22
    s_f = length * (1.75 * draft + cb * breadth)  # K09 eq 23
    cf = 1.328 * (3.22 * r_f**2 * phi_a**2 / (2 * np.pi / omega * nu)) ** -0.5  # K09 eq 21, ITTC eq 96
    b_f = 4.0 / (3.0 * np.pi) * rho * s_f * r_f**3 * phi_a * omega * cf  # K09 eq 20
    b_f *= 1.0 + 4.1 * speed / (omega * length)  # ITTC eq 41
    b_w = _simplified_wave_hat(x1, x2, x3, 1.0 - x4, w_hat) * to_dim * wave_speed_factor(omega, speed, draft, g)
    b_e = _simplified_eddy_hat(x1, x2, x3, x4, w_hat, phi_a) * to_dim * float(eddy_speed_factor(omega, length, speed))
    hp = HullParticulars(length, breadth, draft, og, cb, cm, cb * length * breadth * draft, draft - og)
    b_l = hull_lift_damping(hp, speed, rho) if speed > 0 else 0.0  # ITTC eqs 91-94
    b_bk = (_simplified_bk_hat(x1, x2, x3, x4, w_hat, roll_amplitude_deg, bk_span / breadth, bk_length / length)
            * to_dim) if bk_span > 0 and bk_length > 0 else 0.0
    vals = {"friction": b_f, "wave": b_w, "eddy": b_e, "lift": b_l, "bilge_keel": b_bk}
    vals["total"] = sum(vals.values())
    checks = {"cb": cb, "b/d": x1, "cm": cm, "og/d": x4, "omega_hat": w_hat}
    if bk_span > 0:
        checks.update({"b_bk/b": bk_span / breadth, "l_bk/l": bk_length / length})
    out = [f"{k} = {v:.4g} outside {SIMPLIFIED_RANGE[k][0]}..{SIMPLIFIED_RANGE[k][1]}"
           for k, v in checks.items() if not SIMPLIFIED_RANGE[k][0] <= v <= SIMPLIFIED_RANGE[k][1]]
    ds = xr.Dataset()
    for k, v in vals.items():
        ds[k] = xr.DataArray(float(v), attrs={"units": "N m s/rad", "long_name": f"simplified Ikeda {k} roll damping"})
        ds[k + "_hat"] = xr.DataArray(float(v / to_dim), attrs={"units": "1", "long_name": f"non-dimensional {k} roll damping (ITTC eq 27)"})
    ds.attrs["out_of_range"] = "; ".join(out)
    return ds
