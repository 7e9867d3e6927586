"""2008 IS Code, Part A: the general intact criteria (2.2) and the severe wind and rolling
(weather) criterion (2.3), from stabflow's own free-trim GZ curve.

Every standard (limits, the wind pressure, the roll-back formula's constants and tables) is read
from ``resources/criteria/is_code_2008.yaml`` with its source; nothing is typed here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from stabflow.criteria.standards import Standards
from stabflow.criteria.verdicts import Row, against

GEN = "is_code_2008.general_criteria"
WC = "is_code_2008.weather_criterion"
PHI1 = f"{WC}.roll_back_angle_phi1"


@dataclass
class Stability:
    """What the IS Code criteria need of a loaded ship.

    Attributes
    ----------
    heel : heel grid from 0 [degree] (fine, e.g. 0.25 degree steps).
    gz : free-trim righting arm on ``heel`` [m] (odd in heel: a port-starboard symmetric hull).
    gm0 : initial metacentric height [m].
    kg : vertical centre of gravity above the baseline [m].
    draft : mean (midship) draught d [m].
    breadth : moulded (waterline) breadth B [m].
    lwl : waterline length [m].
    block : block coefficient C_B = V / (L B d) [-].
    displacement : displacement [t].
    deck_edge : angle of deck-edge immersion [degree] (first deck-edge point along the length).
    flooding : angle of flooding [degree], NaN when the ship config gives no openings.
    """

    heel: np.ndarray
    gz: np.ndarray
    gm0: float
    kg: float
    draft: float
    breadth: float
    lwl: float
    block: float
    displacement: float
    deck_edge: float
    flooding: float = math.nan

    def __post_init__(self):
        h = np.asarray(self.heel, float)
        # odd extension to negative heel (the roll-back of the weather criterion goes to windward)
        self._spline = CubicSpline(np.radians(np.r_[-h[:0:-1], h]), np.r_[-np.asarray(self.gz)[:0:-1], self.gz])

    def gz_at(self, phi_deg):
        """GZ [m] at heel ``phi_deg`` [degree] (cubic spline through the computed points)."""
        return self._spline(np.radians(phi_deg))

    def area(self, a_deg: float, b_deg: float) -> float:
        """Area under the GZ curve from ``a_deg`` to ``b_deg`` [m rad]."""
        return float(self._spline.integrate(math.radians(a_deg), math.radians(b_deg)))

    def crossing(self, lever: float, start: float = 0.0, down: bool = False) -> float:
        """First heel [degree] >= ``start`` where GZ crosses ``lever`` upward (or downward); NaN if none."""
        h = self.heel[self.heel >= start]
        d = self.gz_at(h) - lever
        for j in range(1, len(h)):
            if (d[j - 1] < 0 <= d[j]) if not down else (d[j - 1] > 0 >= d[j]):
                return brentq(lambda p: float(self.gz_at(p)) - lever, h[j - 1], h[j], xtol=1e-10)
        return math.nan

    @property
    def vanishing(self) -> float:
        """Angle of vanishing stability [degree] (NaN if GZ stays positive on the grid)."""
        k = int(np.argmax(self.gz))
        return self.crossing(0.0, start=float(self.heel[k]), down=True)


def general_criteria(stab: Stability, std: Standards) -> list[Row]:
    """IS Code Part A 2.2: areas under GZ, GZ at 30 degree or more, angle of GZmax, GM0."""
    lvl = "IS Code 2008 A 2.2"
    rows = []
    up = std.get(f"{GEN}.area_0_to_40_or_flooding.upper_angle_deg")
    phi_f = stab.flooding
    upper = float(up.value) if not math.isfinite(phi_f) else min(float(up.value), phi_f)
    fnote = (f"flooding angle {phi_f:.1f} deg" if math.isfinite(phi_f)
             else "no unprotected openings given in the ship config: the flooding angle does not limit")
    rows.append(against("area under GZ, 0 to 30 deg", lvl + ".1", stab.area(0, 30), "m rad",
                        std.get(f"{GEN}.area_0_to_30"), ">="))
    rows.append(against(f"area under GZ, 0 to {upper:.1f} deg (40 deg or flooding)", lvl + ".1", stab.area(0, upper),
                        "m rad", std.get(f"{GEN}.area_0_to_40_or_flooding"), ">=", note=fnote))
    a3040 = stab.area(30, upper) if upper > 30 else math.nan
    rows.append(against(f"area under GZ, 30 to {upper:.1f} deg", lvl + ".1", a3040, "m rad",
                        std.get(f"{GEN}.area_30_to_40_or_flooding"), ">=",
                        note=fnote if upper > 30 else f"flooding angle {phi_f:.1f} deg is below 30 deg"))
    at = float(std.get(f"{GEN}.gz_min_at_or_beyond_30.at_angle_deg").value)
    beyond = stab.heel[stab.heel >= at]
    rows.append(against(f"largest GZ at heel >= {at:g} deg", lvl + ".2", float(stab.gz_at(beyond).max()), "m",
                        std.get(f"{GEN}.gz_min_at_or_beyond_30"), ">="))
    k = int(np.argmax(stab.gz))
    rows.append(against("angle of maximum GZ", lvl + ".3", float(stab.heel[k]), "deg",
                        std.get(f"{GEN}.angle_of_max_gz_min"), ">=",
                        note=f"the Code prefers more than {std.entries[f'{GEN}.angle_of_max_gz_min']['preferred_deg']} deg"))
    rows.append(against("initial metacentric height GM0", lvl + ".4", stab.gm0, "m", std.get(f"{GEN}.gm0_min"), ">=",
                        note="fluid-free GM (no free-surface correction: no tanks in the ship config)"))
    return rows


@dataclass
class Windage:
    """Projected lateral windage area above the waterline A [m^2] and the vertical distance Z [m]
    from its centroid to the centre of the underwater lateral area (IS Code 2.3.2)."""

    area: float
    lever: float
    note: str = ""


def roll_back(stab: Stability, std: Standards, bilge: str = "round", keel_area: float = 0.0) -> dict:
    """Roll-back angle phi1 [degree] (IS Code 2.3.4) with its factors and the roll period T [s].

    Parameters
    ----------
    bilge : "round" or "sharp" (sharp bilge: k from its own entry).
    keel_area : total area of bilge keels and bar keel Ak [m^2] (0: none).
    """
    B, d, L = stab.breadth, stab.draft, stab.lwl
    x1, y1, _ = std.table(f"{PHI1}.X1_table")
    x2, y2, _ = std.table(f"{PHI1}.X2_table")
    xs, ys, _ = std.table(f"{PHI1}.s_table")
    # np.interp clamps at the end rows, as the sources do (is_code_2008.yaml, interpolation notes)
    X1 = float(np.interp(B / d, x1, y1))
    X2 = float(np.interp(stab.block, x2, y2))
    if bilge == "sharp":
        k = float(std.value(f"{PHI1}.k.sharp_bilge"))
    elif keel_area > 0:
        xk, yk, _ = std.table(f"{PHI1}.k.with_bilge_or_bar_keels_table")
        k = float(np.interp(keel_area * 100.0 / (L * B), xk, yk))
    else:
        k = float(std.value(f"{PHI1}.k.round_bilge_no_keels"))
    og = stab.kg - d
    r = float(std.value(f"{PHI1}.r.a")) + float(std.value(f"{PHI1}.r.b")) * og / d
    c = (float(std.value(f"{PHI1}.roll_period_T.C.c0")) + float(std.value(f"{PHI1}.roll_period_T.C.c1")) * B / d
         - float(std.value(f"{PHI1}.roll_period_T.C.c2")) * L / float(std.value(f"{PHI1}.roll_period_T.C.Lwl_divisor")))
    T = float(std.value(f"{PHI1}.roll_period_T.f")) * c * B / math.sqrt(stab.gm0) if stab.gm0 > 0 else math.nan
    s = float(np.interp(T, xs, ys)) if math.isfinite(T) else math.nan
    phi1 = float(std.value(f"{PHI1}.C0")) * k * X1 * X2 * math.sqrt(r * s) if r * s >= 0 else math.nan
    return {"X1": X1, "X2": X2, "k": k, "r": r, "C": c, "T": T, "s": s, "phi1": phi1, "OG": og}


def weather_criterion(stab: Stability, std: Standards, wind: Windage | None, bilge: str = "round",
                      keel_area: float = 0.0) -> tuple[list[Row], dict]:
    """IS Code Part A 2.3, severe wind and rolling: rows (area b >= area a, steady-wind heel) and the
    intermediate quantities (levers, angles, areas, the roll-back factors).

    Without ``wind`` (no windage in the ship config) the roll-back angle is still computed and the
    rows are NOT EVALUATED, naming the windage as missing.
    """
    lvl = "IS Code 2008 A 2.3"
    rb = roll_back(stab, std, bilge, keel_area)
    q = {f"wc_{k}": v for k, v in rb.items()}
    app = f"{WC}.applicability_of_table_method"
    outside = []
    if stab.breadth / stab.draft >= float(std.value(f"{app}.B_over_d_max")):
        outside.append(f"B/d = {stab.breadth / stab.draft:.2f}")
    kgd = std._node(app)["KG_over_d_minus_1"]  # a range under the sourced applicability entry
    if not kgd["min"] <= stab.kg / stab.draft - 1 <= kgd["max"]:
        outside.append(f"KG/d - 1 = {stab.kg / stab.draft - 1:.2f}")
    if not rb["T"] < float(std.value(f"{app}.T_max")):
        outside.append(f"T = {rb['T']:.1f} s")
    app_note = ("outside the limits of the roll-back tables (IS Code 2.3.5: " + ", ".join(outside)
                + "); the Code then allows model tests (MSC.1/Circ.1200)") if outside else ""
    missing = [] if wind is not None else ["windage area and its lever (ship config criteria.windage)"]
    nan = math.nan
    if wind is not None:
        P = float(std.value(f"{WC}.wind_pressure_P"))
        g = float(std.value(f"{WC}.steady_wind_lever_lw1.constants.g"))
        lw1 = P * wind.area * wind.lever / (float(std.value(f"{WC}.steady_wind_lever_lw1.constants.divisor_1000"))
                                            * g * stab.displacement)
        lw2 = float(std.value(f"{WC}.gust_wind_lever_lw2.factor")) * lw1
        phi0 = stab.crossing(lw1)
        phi_l2 = stab.crossing(lw2)
        phi_c = stab.crossing(lw2, start=phi_l2, down=True) if math.isfinite(phi_l2) else nan
        cap = float(std.value(f"{WC}.angle_limits.phi2.cap_deg"))
        phi2 = min(cap, stab.flooding if math.isfinite(stab.flooding) else cap, phi_c if math.isfinite(phi_c) else cap)
        gzmax = float(np.max(stab.gz))
        if lw1 >= gzmax or lw2 >= gzmax:
            # the wind heels the ship beyond its largest righting arm: no equilibrium (lw1) or no
            # area b (lw2): the criterion fails, it is not "not evaluated"
            phi0 = math.inf if lw1 >= gzmax else phi0
            area_a, area_b = (math.inf, 0.0)
            q.update(wc_lw1=lw1, wc_lw2=lw2, wc_phi0=phi0, wc_area_a=area_a, wc_area_b=area_b,
                     wc_windage_area=wind.area, wc_windage_lever=wind.lever)
        elif math.isfinite(phi0) and math.isfinite(phi_l2) and math.isfinite(rb["phi1"]):
            lo = phi0 - rb["phi1"]
            # area a: between the gust lever and GZ from the roll-back angle to the first intercept
            area_a = lw2 * math.radians(phi_l2 - lo) - stab.area(lo, phi_l2)
            # area b: above the gust lever from the first intercept to phi2
            area_b = stab.area(phi_l2, phi2) - lw2 * math.radians(phi2 - phi_l2) if phi2 > phi_l2 else 0.0
        else:
            area_a = area_b = nan
        if lw1 < gzmax and lw2 < gzmax:
            q.update(wc_lw1=lw1, wc_lw2=lw2, wc_phi0=phi0, wc_phi_lw2=phi_l2, wc_phi_c=phi_c, wc_phi2=phi2,
                     wc_area_a=area_a, wc_area_b=area_b, wc_windage_area=wind.area, wc_windage_lever=wind.lever)
    else:
        phi0 = area_a = area_b = nan
    note = "; ".join(x for x in (app_note, wind.note if wind else "") if x)
    if area_a == math.inf:
        ratio = 0.0
    else:
        ratio = area_b / area_a if (math.isfinite(area_a) and area_a > 0) else (math.inf if area_a == 0 else nan)
    rows = [against("weather criterion: area b / area a", lvl + ".1.4", ratio, "-",
                    std.get(f"{WC}.acceptance.area_b_over_area_a_min"), ">=", note=note, missing=missing)]
    lim = std.get(f"{WC}.acceptance.steady_wind_heel_phi0_max.limit_deg")
    frac = std.get(f"{WC}.acceptance.steady_wind_heel_phi0_max.deck_edge_fraction")
    # deck edge never immersed up to 90 deg (NaN): the 16-deg limit alone applies
    limit = min(float(lim.value), float(frac.value) * stab.deck_edge) if math.isfinite(stab.deck_edge) else float(lim.value)
    r = against("weather criterion: steady-wind heel phi0", lvl + ".1.2", phi0, "deg", lim, "<=",
                note=(f"limit min({lim.value:g} deg, {frac.value:g} x deck-edge immersion {stab.deck_edge:.1f} deg)"
                      + (f"; {note}" if note else "")), missing=missing)
    r.limit = limit
    r.source = f"{lim.cite()}; {frac.cite()}"
    rows.append(r)
    q["wc_limit_phi0"] = limit
    return rows, q
