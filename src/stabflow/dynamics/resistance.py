"""Calm-water resistance of the 6-DOF model: the friction line, Holtrop's method or a given curve.

Three methods (the ship config's ``manoeuvring.resistance.method``):

* ``friction``: the ITTC-57 friction line with a form factor, R = 1/2 rho S_w (1 + k) C_F u^2, on
  Kato's wetted surface (ITTC roll-damping procedure eq 40); no wave-making part. Above a Froude
  number of about 0.35 a long following wave's surge force (the trawler: 199 kN at H 4 m, lambda
  150 m) outgrows it by far (42.9 kN at 15 m/s) and carries the ship at the wave's celerity.
* ``holtrop_mennen``: Holtrop & Mennen (1982), Int. Shipbuilding Progress 29, pp. 166-170, with
  the re-analysis of Holtrop (1984), ISP 31(363), pp. 272-276: R_T = R_F (1 + k1) + R_APP + R_W
  + R_B + R_TR + R_A (:func:`holtrop_mennen`). The formulas and coefficients were read in two
  independent public implementations that reproduce the 1982 paper's worked example
  (ydeos/ydeos_hydrodynamics ``holtrop_mennen.py``, 5777-wq/OpenHull ``src/openhull/holtrop.py``,
  which cites the paper's pages 166-170) and, for the 1984 additions, in FreeCAD/freecad.ship
  ``resistanceHoltrop/Holtrop.py`` and B. Hoellmann's module (citing 1984 pp. 272-273); the
  papers' own pages beyond the first could not be read here. The paper's equation numbers are
  not cited (not read).
* ``curve``: a resistance curve R(u) given in the config (a tank test), interpolated monotonically.

The kernel (``_kernels_6dof._resistance``) keeps the friction line analytic and adds the rest of
the resistance (R_T minus the friction line's part) from a table over the surge speed, so that the
surge equation, the thrust that holds the commanded speed and the Melnikov surf-riding threshold
(:mod:`.surf_riding`) read one and the same R(u).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

from stabflow import StabflowError
from stabflow.constants import G
from stabflow.dynamics import _kernels_6dof as K6
from stabflow.dynamics.roll_damping import NU

#: methods of ``manoeuvring.resistance.method``
METHODS = ("friction", "holtrop_mennen", "curve")

#: Holtrop & Mennen's stern-shape coefficient C_stern (1982, as tabulated in B. Hoellmann's module
#: citing the 1984 paper p. 272, and in VTTI-CSM/ShipNetSim ``holtropmethod.cpp``)
STERN_SHAPE = {"pram_gondola": -25.0, "v_sections": -10.0, "normal": 0.0, "u_sections_hogner": 10.0}

#: the ranges within which Holtrop's regression is said to hold for "trawlers, coastal ships, tugs":
#: the table in the docstring of ydeos/ydeos_hydrodynamics ``holtrop_mennen.py`` (commit e816c74),
#: which does not state its own source; neither paper's range table could be read here
TRAWLER_RANGE = {"froude": (0.0, 0.38), "cp": (0.55, 0.65), "l_over_b": (3.9, 6.3), "b_over_t": (2.1, 3.0)}

#: the kernel's resistance table: this many points (its m slots) from 0 to TABLE_FROUDE sqrt(g L)
TABLE_POINTS = K6.N_RR
TABLE_FROUDE = 1.5


def ittc57_friction(reynolds) -> np.ndarray:
    """Frictional resistance coefficient C_F = 0.075 / (log10 Re - 2)^2 (ITTC 1957 line)."""
    return 0.075 / (np.log10(np.asarray(reynolds, float)) - 2.0) ** 2


@dataclass(frozen=True)
class HullForm:
    """The particulars Holtrop's method reads (1982 paper's notation).

    ``length`` L on the waterline, ``breadth`` B, ``draft`` T (mean), ``draft_fwd`` T_F [m];
    ``volume`` nabla [m^3]; ``lcb`` [% of L, forward of 0.5 L positive]; ``cm``, ``cwp`` [-];
    ``wetted_area`` S of the bare hull [m^2]; ``transom_area`` A_T immersed at rest, ``bulb_area``
    A_BT [m^2] and the bulb's centre ``bulb_height`` h_B above the keel [m]; ``stern`` C_stern [-]
    (:data:`STERN_SHAPE`); ``appendages`` ((area [m^2], 1 + k2 [-]), ...) wetted."""

    length: float
    breadth: float
    draft: float
    volume: float
    lcb: float
    cm: float
    cwp: float
    wetted_area: float
    draft_fwd: float | None = None
    transom_area: float = 0.0
    bulb_area: float = 0.0
    bulb_height: float = 0.0
    stern: float = 0.0
    appendages: tuple = ()

    @property
    def cp(self) -> float:
        """Prismatic coefficient nabla / (C_M B T L) [-]."""
        return self.volume / (self.cm * self.breadth * self.draft * self.length)

    @property
    def cb(self) -> float:
        """Block coefficient nabla / (L B T) [-]."""
        return self.volume / (self.length * self.breadth * self.draft)

    @property
    def tf(self) -> float:
        return self.draft if self.draft_fwd is None else self.draft_fwd


def holtrop_wetted_area(f: HullForm) -> float:
    """Holtrop & Mennen's (1982) regression for the bare hull's wetted surface S [m^2]:
    L (2T + B) sqrt(C_M) (0.453 + 0.4425 C_B - 0.2862 C_M - 0.003467 B/T + 0.3696 C_WP) + 2.38 A_BT / C_B."""
    return (f.length * (2 * f.draft + f.breadth) * math.sqrt(f.cm)
            * (0.453 + 0.4425 * f.cb - 0.2862 * f.cm - 0.003467 * f.breadth / f.draft + 0.3696 * f.cwp)
            + 2.38 * f.bulb_area / f.cb)


def _run_length(f: HullForm) -> float:
    """Length of the run L_R = L (1 - C_P + 0.06 C_P lcb / (4 C_P - 1)) [m]."""
    cp = f.cp
    return f.length * (1 - cp + 0.06 * cp * f.lcb / (4 * cp - 1))


def form_factor(f: HullForm, variant: str = "1984") -> float:
    """Holtrop's form factor 1 + k1 [-]: the 1982 expression (c12, c13) or the 1984 one (c14)."""
    L, B, T, cp = f.length, f.breadth, f.draft, f.cp
    lr = _run_length(f)
    if variant == "1982":
        tl = T / L
        c12 = tl**0.2228446 if tl > 0.05 else (48.20 * (tl - 0.02) ** 2.078 + 0.479948 if tl > 0.02 else 0.479948)
        c13 = 1 + 0.003 * f.stern
        return c13 * (0.93 + c12 * (B / lr) ** 0.92497 * (0.95 - cp) ** -0.521448 * (1 - cp + 0.0225 * f.lcb) ** 0.6906)
    if variant != "1984":
        raise StabflowError(f"holtrop_mennen: variant {variant!r} is not '1982' or '1984'")
    c14 = 1 + 0.011 * f.stern
    return (0.93 + 0.487118 * c14 * (B / L) ** 1.06806 * (T / L) ** 0.46106 * (L / lr) ** 0.121563
            * (L**3 / f.volume) ** 0.36486 * (1 - cp) ** -0.604247)


def _wave_coefficients(f: HullForm) -> dict:
    """The speed-independent coefficients of Holtrop's wave resistance."""
    L, B, T, V, cp = f.length, f.breadth, f.draft, f.volume, f.cp
    lr = _run_length(f)
    ie = 1 + 89 * math.exp(-(L / B) ** 0.80856 * (1 - f.cwp) ** 0.30484 * (1 - cp - 0.0225 * f.lcb) ** 0.6367
                           * (lr / B) ** 0.34574 * (100 * V / L**3) ** 0.16302)
    bl = B / L
    c7 = 0.229577 * bl**0.33333 if bl < 0.11 else (bl if bl < 0.25 else 0.5 - 0.0625 * L / B)
    c1 = 2223105 * c7**3.78613 * (T / B) ** 1.07961 * (90 - ie) ** -1.37565
    abt, hb, tf = f.bulb_area, f.bulb_height, f.tf
    c3 = 0.56 * abt**1.5 / (B * T * (0.31 * math.sqrt(abt) + tf - hb)) if abt > 0 else 0.0
    c2 = math.exp(-1.89 * math.sqrt(c3))
    c5 = 1 - 0.8 * f.transom_area / (B * T * f.cm)
    c16 = 8.07981 * cp - 13.8673 * cp**2 + 6.984388 * cp**3 if cp < 0.8 else 1.73014 - 0.7067 * cp
    m1 = 0.0140407 * L / T - 1.75254 * V ** (1 / 3) / L - 4.79323 * B / L - c16
    slender = L**3 / V
    c15 = -1.69385 if slender < 512 else (-1.69385 + (L / V ** (1 / 3) - 8) / 2.36 if slender < 1726.91 else 0.0)
    lam = 1.446 * cp - 0.03 * L / B if L / B < 12 else 1.446 * cp - 0.36
    out = {"i_e": ie, "c1": c1, "c2": c2, "c3": c3, "c5": c5, "c7": c7, "c15": c15, "c16": c16, "m1": m1, "lambda": lam}
    if L / B > 2:  # 1984's R_W-B: (L/B - 2)^1.40692
        out["c17"] = 6919.3 * f.cm**-1.3346 * (V / L**3) ** 2.00977 * (L / B - 2) ** 1.40692
        out["m3"] = -7.2035 * bl**0.326869 * (T / B) ** 0.605375
    return out


def wave_resistance(f: HullForm, froude, rho: float = 1025.0, g: float = G, variant: str = "1984") -> np.ndarray:
    """Holtrop's wave resistance R_W [N] at Froude numbers ``froude`` [-] (d = -0.9).

    ``variant`` "1982": c1 c2 c5 nabla rho g exp(m1 Fn^d + m2 cos(lambda Fn^-2)), m2 = c15 C_P^2
    exp(-0.1 Fn^-2), the paper's single formula (its 1984 successor says it is poor above Fn 0.5).
    "1984": R_W-A with m4 = 0.4 c15 exp(-0.034 Fn^-3.29) in place of m2 below Fn 0.40; R_W-B =
    c17 c2 c5 nabla rho g exp(m3 Fn^d + m4 cos(lambda Fn^-2)) above 0.55; between them linear in
    Fn from R_W-A(0.40) to R_W-B(0.55) (as FreeCAD's and Hoellmann's modules; Molland et al. 2017
    write the same weight as (20 Fn - 8) / 3)."""
    c = _wave_coefficients(f)
    fn = np.atleast_1d(np.asarray(froude, float))
    w = c["c2"] * c["c5"] * f.volume * rho * g
    d = -0.9

    def rwa(x, m):
        return c["c1"] * w * np.exp(c["m1"] * x**d + m * np.cos(c["lambda"] * x**-2.0))

    def m4(x):
        return 0.4 * c["c15"] * np.exp(-0.034 * x**-3.29)

    out = np.zeros_like(fn)
    pos = fn > 0
    x = fn[pos]
    if variant == "1982":
        out[pos] = rwa(x, c["c15"] * f.cp**2 * np.exp(-0.1 * x**-2.0))
        return out.reshape(np.shape(froude))
    if variant != "1984":
        raise StabflowError(f"holtrop_mennen: variant {variant!r} is not '1982' or '1984'")
    if "c17" not in c:
        raise StabflowError(f"holtrop_mennen: L/B {f.length / f.breadth:.2f} <= 2, outside Holtrop's (1984) R_W-B")

    def rwb(x):
        return c["c17"] * w * np.exp(c["m3"] * x**d + m4(x) * np.cos(c["lambda"] * x**-2.0))

    a40, b55 = float(rwa(0.40, m4(0.40))), float(rwb(0.55))
    out[pos] = np.where(x < 0.40, rwa(x, m4(x)), np.where(x > 0.55, rwb(x), a40 + (10 * x - 4) / 1.5 * (b55 - a40)))
    return out.reshape(np.shape(froude))


def correlation_allowance(f: HullForm) -> float:
    """Holtrop & Mennen's model-ship correlation allowance C_A [-] (1982):
    0.006 (L + 100)^-0.16 - 0.00205 + 0.003 sqrt(L / 7.5) C_B^4 c2 (0.04 - c4), c4 = min(T_F / L, 0.04)."""
    c2 = _wave_coefficients(f)["c2"]
    c4 = min(f.tf / f.length, 0.04)
    return 0.006 * (f.length + 100) ** -0.16 - 0.00205 + 0.003 * math.sqrt(f.length / 7.5) * f.cb**4 * c2 * (0.04 - c4)


def holtrop_mennen(f: HullForm, speed, rho: float = 1025.0, nu: float = NU, g: float = G,
                   variant: str = "1984") -> xr.Dataset:
    """Holtrop's calm-water resistance and its components along ``speed`` [m/s].

    R_T = R_F (1 + k1) + R_APP + R_W + R_B + R_TR + R_A with R_F = 1/2 rho V^2 S C_F (ITTC-57 on
    the waterline length), R_APP = 1/2 rho V^2 C_F sum S_APP (1 + k2), R_B the bulb's
    (0.11 exp(-3 P_B^-2) F_ni^3 A_BT^1.5 rho g / (1 + F_ni^2)), R_TR the immersed transom's
    (1/2 rho V^2 A_T c6, c6 = 0.2 (1 - 0.2 F_nT) below F_nT = 5, F_nT = V / sqrt(2 g A_T / (B +
    B C_WP))), R_A = 1/2 rho V^2 S C_A (:func:`correlation_allowance`), R_W :func:`wave_resistance`,
    1 + k1 :func:`form_factor`, both of ``variant``.

    Returns
    -------
    xarray.Dataset
        Along ``speed``: ``froude`` [-], ``r_friction`` R_F (1 + k1), ``r_appendages``, ``r_wave``,
        ``r_bulb``, ``r_transom``, ``r_correlation``, ``r_total`` [N]; attrs the form factor, C_A,
        the wave coefficients and the variant.
    """
    v = np.atleast_1d(np.asarray(speed, float))
    L, B = f.length, f.breadth
    fn = v / math.sqrt(g * L)
    q = 0.5 * rho * v**2
    cf = np.where(v > 0, ittc57_friction(np.maximum(v * L / nu, 1e3)), 0.0)
    k1 = form_factor(f, variant)
    rf = q * f.wetted_area * cf * k1
    rapp = q * cf * sum(a * k for a, k in f.appendages)
    rw = wave_resistance(f, fn, rho, g, variant)
    rb = np.zeros_like(v)
    if f.bulb_area > 0:
        abt, tf, hb = f.bulb_area, f.tf, f.bulb_height
        pb = 0.56 * math.sqrt(abt) / (tf - 1.5 * hb)
        fni = v / np.sqrt(g * (tf - hb - 0.25 * math.sqrt(abt)) + 0.15 * v**2)
        rb = 0.11 * math.exp(-3 * pb**-2) * fni**3 * abt**1.5 * rho * g / (1 + fni**2)
    rtr = np.zeros_like(v)
    if f.transom_area > 0:
        fnt = v / math.sqrt(2 * g * f.transom_area / (B + B * f.cwp))
        rtr = q * f.transom_area * np.where(fnt < 5, 0.2 * (1 - 0.2 * fnt), 0.0)
    ca = correlation_allowance(f)
    ra = q * f.wetted_area * ca
    total = rf + rapp + rw + rb + rtr + ra

    def var(x, name):
        return ("speed", x, {"units": "N", "long_name": name})

    coeffs = {f"hm_{k}": float(x) for k, x in _wave_coefficients(f).items()}
    return xr.Dataset(
        {"froude": ("speed", fn, {"units": "1", "long_name": "Froude number V / sqrt(g L)"}),
         "r_friction": var(rf, "frictional resistance R_F (1 + k1), ITTC-57"),
         "r_appendages": var(rapp, "appendage resistance R_APP"), "r_wave": var(rw, "wave resistance R_W"),
         "r_bulb": var(rb, "bulb resistance R_B"), "r_transom": var(rtr, "immersed-transom resistance R_TR"),
         "r_correlation": var(ra, "model-ship correlation allowance R_A"), "r_total": var(total, "total resistance R_T")},
        coords={"speed": ("speed", v, {"units": "m/s", "long_name": "speed"})},
        attrs={"hm_variant": variant, "hm_form_factor": k1, "hm_correlation_allowance": ca, **coeffs})


def outside_range(f: HullForm, froude_max: float | None = None) -> list[str]:
    """The particulars (and ``froude_max``, the highest Froude number used, if given) outside
    :data:`TRAWLER_RANGE`, as text."""
    vals = {"froude": froude_max, "cp": f.cp, "l_over_b": f.length / f.breadth, "b_over_t": f.breadth / f.draft}
    names = {"froude": "Fn", "cp": "C_P", "l_over_b": "L/B", "b_over_t": "B/T"}
    return [f"{names[k]} {vals[k]:.3g} outside {lo:g}-{hi:g}" for k, (lo, hi) in TRAWLER_RANGE.items()
            if vals[k] is not None and not lo <= vals[k] <= hi]


# ------------------------------------------------------------------------------ references
#: Holtrop & Mennen (1982), section 5's worked example: inputs and printed values [kN] as pinned in
#: 5777-wq/OpenHull tests/test_holtrop.py (commit 7acd452; "transcribed from page images" of the
#: paper, pp. 166-170) and quoted in ydeos/ydeos_hydrodynamics tests/test_holtrop_mennen.py (commit
#: e816c74); nu 1.18831e-6 m^2/s reproduces the printed Reynolds number (OpenHull), g 9.81, rho 1025.
WORKED_EXAMPLE_1982 = {
    "form": HullForm(length=205.0, breadth=32.0, draft=10.0, volume=37500.0, lcb=-0.75, cm=0.98, cwp=0.75,
                     wetted_area=7381.45, transom_area=16.0, bulb_area=20.0, bulb_height=4.0, stern=10.0,
                     appendages=((50.0, 1.5),)),
    "speed": 25.0 * 1852.0 / 3600.0, "nu": 1.18831e-6, "g": 9.81, "rho": 1025.0,
    "printed_kn": {"r_friction_bare": 869.63, "r_appendages": 8.83, "r_wave": 557.11, "r_bulb": 0.049,
                   "r_transom": 0.0, "r_correlation": 221.98, "r_total": 1793.26},
}

#: Holtrop's (1984) method run by peer implementations on a small beamy test hull (L 21.72 m, B 6.78,
#: T 3.0, nabla 247.13 m^3, lcb -3.7 %, C_M 0.80, C_WP 0.80, S 160 m^2, no transom, bulb or
#: appendages; rho 1025, nu 1.18831e-6, g 9.81), R_W and R_T [kN] at the Froude numbers: a stored
#: public Python module following Molland, Turnock & Hudson (2017) (the code index's file id
#: 4934821950; its repository name is not shown), run unchanged on 2026-12-08 (/work/notes/
#: hm_peer_values.md); FreeCAD/freecad.ship resistanceHoltrop/Holtrop.py (commit c83a423) gives the
#: same outside 0.40 < Fn < 0.55, where it takes m4 at the current Fn inside the interpolation's end
#: values (8.8 % lower R_W at Fn 0.45).
PEER_1984 = {
    "form": HullForm(length=21.72, breadth=6.78, draft=3.0, volume=247.13, lcb=-3.7, cm=0.80, cwp=0.80,
                     wetted_area=160.0),
    "nu": 1.18831e-6, "g": 9.81, "rho": 1025.0,
    "froude": (0.25, 0.35, 0.40, 0.45, 0.50, 0.55, 0.60, 0.80, 1.00),
    "r_wave_kn": (1.79120, 28.7003, 58.9904, 94.7205, 130.451, 166.181, 230.203, 391.492, 559.947),
    "r_total_kn": (6.15771, 36.9207, 69.5609, 107.918, 146.549, 185.451, 252.913, 430.609, 619.620),
    "source": "Holtrop (1984) in a public Molland-based module (code index file 4934821950), run unchanged",
}


def reference_rows() -> list:
    """Validation rows of :func:`holtrop_mennen`: the 1982 paper's worked example (R_W, R_T within
    0.2 %) and the 1984 set against a peer implementation (largest relative difference of R_W and
    R_T over Fn 0.25-1.0, within 0.01 %: printed to 6 significant figures)."""
    from stabflow.validation import Check

    ex = WORKED_EXAMPLE_1982
    d = holtrop_mennen(ex["form"], ex["speed"], ex["rho"], ex["nu"], ex["g"], variant="1982")
    ref = "Holtrop & Mennen (1982), worked example (L 205 m, 25 kn), printed values as pinned in OpenHull's tests"
    rows = [Check(f"Holtrop & Mennen (1982) worked example: {name} / printed ({ex['printed_kn'][key]:g} kN) - 1",
                  float(d[key][0]) / 1e3 / ex["printed_kn"][key] - 1.0, 0.002, "-", ref)
            for key, name in (("r_wave", "wave resistance R_W"), ("r_total", "total resistance R_T"))]
    pe = PEER_1984
    v = np.asarray(pe["froude"]) * math.sqrt(pe["g"] * pe["form"].length)
    d = holtrop_mennen(pe["form"], v, pe["rho"], pe["nu"], pe["g"])
    for key, name in (("r_wave", "R_W"), ("r_total", "R_T")):
        err = d[key].values / 1e3 / np.asarray(pe[f"{key}_kn"]) - 1.0
        rows.append(Check(f"Holtrop (1984) on a 21.7-m test hull, Fn 0.25-1.0: largest |{name} / peer - 1|",
                          float(np.max(np.abs(err))), 1e-4, "-", pe["source"]))
    return rows


# ------------------------------------------------------------------------------ from the hull
def _waterline(sec, st: xr.Dataset) -> np.ndarray:
    """Body height of the calm waterline at each station, at the free-trim equilibrium."""
    from stabflow.hydrostatics.statics import equilibrium

    h0, th0 = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))[:2]
    return (-h0 + sec.x * math.sin(th0)) / math.cos(th0)


def wetted_area(sec, st: xr.Dataset, zw: np.ndarray | None = None) -> float:
    """Wetted surface [m^2] of the hull at its calm-water equilibrium (``zw``: the waterline's body
    height at each station, :func:`_waterline`, if already found): the immersed girth of each
    station (both sides, the half contour's closing segments on the centreline left out) times its
    slab length (the girth's longitudinal slope left out)."""
    zw = _waterline(sec, st) if zw is None else zw
    total = 0.0
    for i in range(len(sec.x)):
        n = int(sec.n[i])
        y, z = sec.y[i, :n], sec.z[i, :n]
        za, zb = z[:-1], z[1:]
        seg = np.hypot(np.diff(y), zb - za)
        seg[(y[:-1] == 0.0) & (y[1:] == 0.0)] = 0.0  # a closing line on the centreline is not hull
        lo, hi = np.minimum(za, zb), np.maximum(za, zb)
        # the part of each segment below the waterline (straight segments: by its height fraction)
        frac = np.where(hi > lo, np.clip((zw[i] - lo) / np.where(hi > lo, hi - lo, 1.0), 0.0, 1.0),
                        (lo <= zw[i]).astype(float))
        total += 2.0 * float(np.sum(seg * frac)) * float(sec.dx[i])
    return total


def _section_at(x: float, xs: np.ndarray, values: np.ndarray) -> float:
    """``values`` at the stations ``xs`` taken at ``x``: linear between stations, extrapolated
    linearly from the two nearest beyond them, never below 0."""
    from scipy.interpolate import interp1d

    return max(float(interp1d(xs, values, fill_value="extrapolate")(x)), 0.0)


def hull_form(sec, st: xr.Dataset, cfg: dict | None = None) -> HullForm:
    """Holtrop's particulars of the hull at its calm-water equilibrium from the stations and the
    statics; ``cfg`` the config's ``manoeuvring.resistance`` (stern shape and appendages, and
    ``transom_area``, ``bulb_area`` and ``bulb_height`` if given).

    L, its ends and lcb (% of L from its midpoint) refer to the waterline: the stations whose
    waterline breadth is not zero (the statics' ``lwl``). Unless given, the immersed transom A_T
    and the bulb's transverse area A_BT (and its centroid's height above the keel h_B) are the
    immersed section areas at the waterline's aft and forward ends, interpolated between the
    stations (extrapolated beyond the last), as Holtrop defines them (A_BT where the still-water
    surface meets the stem): near zero for a hull that leaves the water at both ends. T_F is T
    (no separate forward draft), and h_B keeps the bulb centroid's depth below the waterline."""
    from stabflow.dynamics.roll_damping import section_parameters
    from stabflow.geometry._kernels import _clip_half

    cfg = cfg or {}
    sp = section_parameters(sec, st)
    xs, dx = sec.x, sec.dx
    zw = _waterline(sec, st)
    wl = np.array([sec.half_breadth(i, zw[i]) for i in range(len(xs))]) > 0
    aft, fwd = float((xs - 0.5 * dx)[wl].min()), float((xs + 0.5 * dx)[wl].max())
    L, B, T = float(st["lwl"]), float(st["bwl"]), float(st["draft_mid"])
    lcb = 100.0 * (float(st["lcb"]) - 0.5 * (aft + fwd)) / L
    area = sp["area"].values
    transom = cfg.get("transom_area")
    if transom is None:
        transom = _section_at(aft, xs, area)
    bulb, hb = cfg.get("bulb_area"), cfg.get("bulb_height")
    if bulb is None:
        bulb = _section_at(fwd, xs, area)
        # the bulb's centroid above the keel at the station nearest the waterline's forward end
        i = int(np.argmin(np.abs(xs - fwd)))
        n = int(sec.n[i])
        y, z = np.ascontiguousarray(sec.y[i, :n]), np.ascontiguousarray(sec.z[i, :n])
        a, _, mz = _clip_half(y, z, n, 0.0, 1.0, zw[i])
        # Holtrop reads the bulb through T_F - h_B, its centroid's depth below the waterline; with
        # T_F the mean draft T (this model has no separate forward draft), h_B = T - that depth
        hb = T - (zw[i] - mz / a) if (bulb > 0 and a > 0) else 0.0
    stern = cfg.get("stern", "normal")
    if stern not in STERN_SHAPE:
        raise StabflowError(f"manoeuvring.resistance.stern {stern!r} is not one of {sorted(STERN_SHAPE)}")
    return HullForm(length=L, breadth=B, draft=T, volume=float(st["volume"]), lcb=lcb, cm=float(sp["cm"]),
                    cwp=float(st["waterplane_area"]) / (L * B), wetted_area=wetted_area(sec, st, zw),
                    draft_fwd=T, transom_area=float(transom), bulb_area=float(bulb), bulb_height=float(hb or 0.0),
                    stern=STERN_SHAPE[stern],
                    appendages=tuple((float(a["area"]), float(a["k2"])) for a in cfg.get("appendages", [])))


# ------------------------------------------------------------------------------ the kernel's table
def _check_rising(r: np.ndarray, u: np.ndarray, what: str) -> None:
    """The resistance must rise with speed: the thrust that holds the commanded speed and
    Melnikov's threshold (a root of mean thrust minus resistance) assume it."""
    bad = np.flatnonzero(np.diff(r) < 0.0)
    if bad.size:
        i = int(bad[0])
        raise StabflowError(f"manoeuvring.resistance: {what} falls between {u[i]:.2f} and {u[i + 1]:.2f} m/s "
                            f"({r[i]:.0f} -> {r[i + 1]:.0f} N); the surge model needs a resistance that rises with speed")


def kernel_resistance(cfg: dict | None, sec, st: xr.Dataset, rho: float, kato_area: float, form_factor_k: float,
                      length: float, nu: float = NU) -> tuple[float, float, np.ndarray, dict]:
    """The kernel's resistance (``_kernels_6dof._resistance``) for the config's
    ``manoeuvring.resistance`` ``cfg`` (``method``, :data:`METHODS`): its friction factor
    1/2 rho S (1 + k) [kg/m] on the ITTC-57 line (``M_RES``), and the rest of R(u) as a table,
    spacing [m/s] and values [N] at :data:`TABLE_POINTS` speeds from 0 to Fn :data:`TABLE_FROUDE`
    (beyond it the kernel lets the last value grow as u^2), with attributes that describe it.

    ``friction``: Kato's wetted surface ``kato_area`` [m^2] with the form factor ``form_factor_k``
    (the manoeuvring section's ``form_factor``), no table. ``holtrop_mennen``: the girth-integrated
    wetted surface with Holtrop's 1 + k1 and the appendages' 1 + k2 analytic, the wave, bulb,
    transom and correlation parts in the table. ``curve``: no friction line, the curve in the table
    (monotone cubic through the given points)."""
    cfg = dict(cfg or {})
    method = cfg.get("method", "friction")
    if method not in METHODS:
        raise StabflowError(f"manoeuvring.resistance.method {method!r} is not one of {list(METHODS)}")
    q = 0.5 * rho
    u = np.linspace(0.0, TABLE_FROUDE * math.sqrt(G * length), TABLE_POINTS)
    if method == "friction":
        return q * kato_area * (1.0 + form_factor_k), 0.0, np.zeros(TABLE_POINTS), {
            "resistance_method": "friction (ITTC-57 line with the form factor, no wave-making part)",
            "resistance_form_factor": 1.0 + form_factor_k, "resistance_wetted_area": kato_area}
    if method == "curve":
        from scipy.interpolate import PchipInterpolator

        sp, val = np.asarray(cfg.get("speeds", []), float), np.asarray(cfg.get("values", []), float)
        if sp.size < 2 or sp.size != val.size or np.any(np.diff(sp) <= 0) or sp[0] != 0.0 or val[0] != 0.0:
            raise StabflowError("manoeuvring.resistance: the curve needs as many values as speeds, the speeds rising "
                                "from 0 m/s with the value 0 N there")
        r = np.where(u <= sp[-1], PchipInterpolator(sp, val)(np.minimum(u, sp[-1])), val[-1] * (u / sp[-1]) ** 2)
        _check_rising(r, u, "the curve")
        return 0.0, float(u[1]), r, {"resistance_method": "curve", "resistance_source": str(cfg.get("source", ""))}
    form = hull_form(sec, st, cfg)
    hm = holtrop_mennen(form, u, rho, nu)
    rest = (hm["r_wave"] + hm["r_bulb"] + hm["r_transom"] + hm["r_correlation"]).values
    k1 = float(hm.attrs["hm_form_factor"])
    friction = q * (form.wetted_area * k1 + sum(a * k for a, k in form.appendages))
    _check_rising(hm["r_total"].values, u, "Holtrop's R(u) for this hull")
    return friction, float(u[1]), rest, {
        "resistance_method": "holtrop_mennen (Holtrop & Mennen 1982 with Holtrop 1984)",
        "resistance_form_factor": k1, "resistance_wetted_area": form.wetted_area,
        "resistance_transom_area": form.transom_area, "resistance_bulb_area": form.bulb_area,
        "resistance_outside_range": "; ".join(outside_range(form)) or "none",
        "resistance_froude_range_max": TRAWLER_RANGE["froude"][1]}
