"""IMO second-generation intact stability criteria (MSC.1/Circ.1627): the physics of each failure
mode's vulnerability levels, computed whatever the standards' availability, and verdicts where the
standards are sourced (``resources/criteria/sgisc.yaml``).

Pure loss of stability and parametric rolling, level 1: the metacentric height on a wave of the
ship's length over crest positions (the waves step's quasi-static balance, paper 002 eqs A20-A24),
and the second route the level-1 criteria use, waterplane inertias at two drafts without the wave
(delta GM = (I_H - I_L) / 2V). Both are tabulated over wave steepness H / lambda: which steepness
and which standard apply is the circular's, and reads as NOT EVALUATED until sourced.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import xarray as xr

from stabflow.criteria.standards import Standards
from stabflow.criteria.verdicts import Row, against
from stabflow.geometry import Sections
from stabflow.stability_in_waves.wave_pass import wave_gm

SG = "sgisc.failure_modes"
CIRC = "MSC.1/Circ.1627"


def waterplane_inertia(sec: Sections, draft: float) -> float:
    """Transverse second moment of the even-keel waterplane at ``draft`` [m^4] (sum of (2/3) y^3 dx)."""
    y = np.array([sec.half_breadth(i, draft) for i in range(len(sec.x))])
    return float((2.0 / 3.0 * y**3 * sec.dx).sum())


def gm_on_wave(sec: Sections, volume: float, lcg: float, kg: float, lwl: float, steepness, n_crest: int = 24,
               draft: float | None = None) -> xr.Dataset:
    """GM on a wave of length L (the waterline length) over crest positions, and the waterplane route.

    Parameters
    ----------
    steepness : wave steepnesses H / lambda [-].
    n_crest : crest positions over one wave length.
    draft : midship draught d [m] for the waterplane route (drafts d +- H/2).

    Returns
    -------
    Dataset along ``steepness`` (and ``crest_position`` for ``gm_wave``): ``gm_wave`` [m],
    ``gm_wave_min``/``gm_wave_max`` [m], ``delta_gm_wave`` = (max - min) / 2 [m] and
    ``delta_gm_waterplane`` = (I(d + H/2) - I(d - H/2)) / 2V [m].
    """
    s = np.asarray(steepness, float)
    lam = lwl
    k = 2 * math.pi / lam
    xc = np.arange(n_crest) * lam / n_crest - lam / 2
    gm = np.empty((len(s), n_crest))
    for i, si in enumerate(s):
        guess = (None, None)
        for j, x in enumerate(xc):
            gm[i, j], _, _, guess = wave_gm(sec, volume, lcg, kg, 0.5 * si * lam, k, x, guess)
    ds = xr.Dataset(
        {"gm_wave": (("steepness", "crest_position"), gm)},
        coords={"steepness": s, "crest_position": xc},
    )
    ds["gm_wave_min"] = ds["gm_wave"].min("crest_position")
    ds["gm_wave_max"] = ds["gm_wave"].max("crest_position")
    ds["delta_gm_wave"] = 0.5 * (ds["gm_wave_max"] - ds["gm_wave_min"])
    if draft is not None:
        dwp = [(waterplane_inertia(sec, draft + 0.5 * si * lam) - waterplane_inertia(sec, max(draft - 0.5 * si * lam, 0.0)))
               / (2 * volume) for si in s]
        ds["delta_gm_waterplane"] = ("steepness", np.array(dwp))
    return ds


def simplified_level1(sec: Sections, volume: float, kg: float, draft: float, depth: float, lwl: float, sw: float,
                      low_fraction: float) -> dict:
    """The waterplane-inertia route of level 1 at wave steepness ``sw`` (drafts as the sourced rule,
    ``sgisc.yaml``: d_H = d + min(D - d, L SW/2), d_L = d - min(d - f d, L SW/2), f = ``low_fraction``).

    Returns d_H, d_L [m], I_H, I_L [m^4], KB(d_L) [m], GMmin = KB(d_L) + I_L / V - KG [m] and
    delta GM1 = (I_H - I_L) / 2V [m] (V the loading's volume).
    """
    from stabflow.hydrostatics.statics import _volume_at

    half = 0.5 * lwl * sw
    dh = draft + min(depth - draft, half)
    dl = draft - min(draft - low_fraction * draft, half)
    ih, il = waterplane_inertia(sec, dh), waterplane_inertia(sec, dl)
    kb_l = _volume_at(sec, -dl)[2]
    return {"d_H": dh, "d_L": dl, "I_H": ih, "I_L": il, "KB_L": kb_l, "gm_min": kb_l + il / volume - kg,
            "delta_gm1": (ih - il) / (2 * volume)}


def rpr(std: Standards, cm: float, keel_area: float, lwl: float, breadth: float, bilge: str) -> tuple[float, str]:
    """Parametric-rolling level-1 standard R_PR [-] from the sourced formula (coefficients in
    ``sgisc.yaml``, RPR_*): f = min(100 Ak / (L B), cap); 0.17 + c f with c by the midship
    coefficient Cm. Returns (R_PR, how it was chosen)."""
    pr = f"{SG}.parametric_rolling.level_1"
    if bilge == "sharp":
        return float(std.value(f"{pr}.RPR_sharp_bilge")), "sharp bilge"
    f = min(100 * keel_area / (lwl * breadth), float(std.value(f"{pr}.RPR_bilge_keel_term_max")))
    if cm > float(std.value(f"{pr}.RPR_Cm_upper")):
        c = float(std.value(f"{pr}.RPR_coef_Cm_above_0_96"))
    elif cm >= float(std.value(f"{pr}.RPR_Cm_lower")):
        c = float(std.value(f"{pr}.RPR_coef_Cm_0_94_to_0_96_slope")) * cm + float(std.value(f"{pr}.RPR_coef_Cm_0_94_to_0_96_intercept"))
    else:
        c = float(std.value(f"{pr}.RPR_coef_Cm_below_0_94"))
    return float(std.value(f"{pr}.RPR_base")) + c * f, f"Cm = {cm:.3f}, 100 Ak/(L B) = {100 * keel_area / (lwl * breadth):.3f}"


def level1_rows(gw: xr.Dataset, simple: dict, gm0: float, lwl: float, fn: float | None, std: Standards,
                r_pr: tuple[float, str], reserve: float) -> list[Row]:
    """Level-1 rows of pure loss, parametric rolling and surf-riding, each route its own row
    (NOT EVALUATED where the circular's numbers are not sourced; the curves are in the results
    either way). ``simple`` maps "pure_loss"/"parametric" to :func:`simplified_level1` results."""
    rows = []
    pl, pr = f"{SG}.pure_loss_of_stability.level_1", f"{SG}.parametric_rolling.level_1"
    fn_app = std.get_or_missing(f"{pl}.froude_number_applicability", f"{CIRC}, pure loss application")
    app = (f"applies when Fn > {fn_app.value:g} ({fn_app.source}); " + (f"Fn = {fn:.3f}" if fn is not None else
           "service speed not given") if fn_app.available else "")
    sw = std.get_or_missing(f"{pl}.wave_steepness_SW", f"{CIRC}, pure loss level 1")
    r = std.get_or_missing(f"{pl}.RPL_standard_GM_min", f"{CIRC}, pure loss level 1")
    miss = [] if sw.available else [f"{sw.key} ({sw.source})"]
    lvl = "SGISC pure loss, level 1"
    v = simple["pure_loss"]["gm_min"] if sw.available else math.nan
    rows.append(against("pure loss: GMmin by waterplane inertia at d_L", lvl, v, "m", r, ">=", missing=miss,
                        note=(f"d_L = {simple['pure_loss']['d_L']:.3f} m, SW = {sw.value} ({sw.cite()}); {app}"
                              if sw.available else app)))
    v = float(gw["gm_wave_min"].interp(steepness=float(sw.value))) if sw.available else math.nan
    rows.append(against("pure loss: GMmin on the wave lambda = L, H = SW L (stabflow's direct route)", lvl, v, "m", r,
                        ">=", missing=miss, note="quasi-static balance on the wave over crest positions (free sinkage "
                        "and trim); the circular's wording for a direct route was not read"))
    rr = std.get_or_missing(f"{pl}.freeboard_volume_ratio_min", f"{CIRC}, level-1 simplified method")
    rows.append(against("level-1 simplified method: (V_D - V) / (A_W (D - d))", lvl + " and parametric rolling, level 1",
                        reserve, "-", rr, ">=", note="its role in the circular (condition of the simplified method "
                        "or a pass condition) was not verified (sgisc.yaml note)"))
    sw = std.get_or_missing(f"{pr}.wave_steepness_SW", f"{CIRC}, parametric rolling level 1")
    miss = [] if sw.available else [f"{sw.key} ({sw.source})"]
    lvl = "SGISC parametric rolling, level 1"
    limit = std.get(f"{pr}.RPR_base")
    for name, v in (("parametric rolling: delta GM1 / GM by waterplane inertias", simple["parametric"]["delta_gm1"]),
                    ("parametric rolling: delta GM / GM on the wave lambda = L (stabflow's direct route)",
                     float(gw["delta_gm_wave"].interp(steepness=float(sw.value))) if sw.available else math.nan)):
        row = against(name, lvl, v / gm0 if sw.available else math.nan, "-", limit, "<=", missing=miss,
                      note=f"R_PR = {r_pr[0]:.3f} ({r_pr[1]})" + (f"; SW = {sw.value}" if sw.available else ""))
        row.limit = r_pr[0]
        row.source = "; ".join(std.get(f"{pr}.{k}").cite() for k in ("RPR_base", "wave_steepness_SW"))
        rows.append(row)
    lim_l = std.get_or_missing(f"{SG}.surf_riding_broaching.level_1.length_limit_m", f"{CIRC}, surf-riding level 1")
    lim_f = std.get_or_missing(f"{SG}.surf_riding_broaching.level_1.froude_number_limit", f"{CIRC}, surf-riding level 1")
    # one row: not vulnerable when L is above its limit OR Fn below its limit
    name, lvl = "surf-riding/broaching: L above the limit or Fn below the limit", "SGISC surf-riding, level 1"
    draft_l = None if lim_l.available or lim_l.draft is None else float(lim_l.draft["value"])
    if lim_l.available and lwl >= float(lim_l.value):
        rows.append(against(name, lvl, lwl, "m", lim_l, ">=", note="L above the length limit: not vulnerable"))
    elif lim_f.available and fn is not None and fn <= float(lim_f.value):
        # either condition alone clears the ship: a sourced Froude limit it is below needs no length limit
        rows.append(against(name, lvl, fn, "-", lim_f, "<=", note=f"L = {lwl:.1f} m; Fn below the Froude-number "
                            "limit: not vulnerable"))
    elif draft_l is not None and lwl >= draft_l:
        # the adopted length limit unread: the draft's says "not vulnerable" (indicative only)
        rows.append(against(name, lvl, lwl, "m", lim_l, ">=", note="L above the draft's length limit"))
    else:
        miss = [] if fn is not None else ["service speed (ship config criteria.service_speed_kn)"]
        if not lim_l.available:
            miss.append(f"{lim_l.key} ({lim_l.source})")
        below = (f", below the length limit {lim_l.value:g} m" if lim_l.available else
                 f", below the draft's length limit {draft_l:g} m" if draft_l is not None else "")
        rows.append(against(name, lvl, fn if fn is not None else math.nan, "-", lim_f, "<=", missing=miss,
                            drafted=[lim_l], note=f"L = {lwl:.1f} m" + below))
    return rows


def wave_gz_table(sec: Sections, volume: float, lcg: float, kg: float, lam: float, height: float, heel_deg,
                  n_crest: int = 24) -> np.ndarray:
    """GZ [m] on a regular wave (length ``lam``, height ``height``) at ``n_crest`` crest positions
    over one wave length x heels ``heel_deg`` (free sinkage and trim at each), shape (n_crest, heels)."""
    from stabflow.stability_in_waves.wave_pass import wave_gz

    k = 2 * math.pi / lam
    xc = np.arange(n_crest) * lam / n_crest
    return np.array([wave_gz(sec, volume, lcg, kg, 0.5 * height, k, x, heel_deg) for x in xc])


def roll_1dof(table: np.ndarray, heel_deg: np.ndarray, lam: float, v_rel: float, inertia: float, b44: float,
              b44q: float, weight: float, phi0_deg: float, duration: float, dt: float) -> np.ndarray:
    """Roll [degree] of the 1-DOF model with the restoring moment of the ship on the passing wave:

        (I44 + A44) phi'' + B44 phi' + B44q phi' |phi'| + W GZ(phi; x_c(t)) = 0,
        x_c(t) = v_rel t  (crest position, periodic over the wave length),

    GZ from :func:`wave_gz_table` (odd in heel), W = the ship's weight [N], RK4 with step ``dt``
    [s] (numba kernel ``stabflow.criteria._kernels._roll_1dof``), from rest at ``phi0_deg`` (the level-2 parametric-roll idea of a roll model whose
    restoring varies as the wave passes; the circular's exact equation was not read). Stops (NaN
    after) when |phi| leaves the table."""
    from stabflow.criteria._kernels import _roll_1dof

    h = np.radians(np.asarray(heel_deg, float))
    hh = np.r_[-h[:0:-1], h]
    tab = np.ascontiguousarray(np.concatenate([-table[:, :0:-1], table], axis=1))
    n = int(round(duration / dt))
    out = np.empty(n + 1)
    _roll_1dof(tab, hh, float(lam), float(v_rel), float(inertia), float(b44), float(b44q), float(weight),
               math.radians(phi0_deg), n, float(dt), out)
    return np.degrees(out)


def parametric_roll_cases(ship, cfg: dict, lam: float, hydro: xr.Dataset | None = None) -> xr.Dataset:
    """Parametric roll in regular waves of the ship's length, following and head seas over speed x
    steepness, by two routes: the 1-DOF roll with the GZ of the ship on the passing wave
    (:func:`roll_1dof`) and the 3-DOF volume-based time domain in the same wave from the same heel.

    Parameters
    ----------
    cfg : ``parametric`` of the criteria section: steepness (H/lambda), froude_numbers, headings_deg
        (0 and/or 180), duration [s], dt [s], phi0_deg, stations.
    lam : wave length [m], the ship's waterline length.
    hydro : Capytaine coefficients for ships whose dynamics use them (the hydro step's file).

    Returns
    -------
    Dataset (heading, froude, steepness): ``pr_roll_1dof``, ``pr_roll_3dof`` (largest |roll| over the
    last quarter of the run [degree], 90 when it capsized), ``pr_encounter_ratio`` (omega_e / omega_roll);
    over froude the 1-DOF coefficients ``pr_inertia`` (I44 + A44), ``pr_b44``, ``pr_b44q``; attributes
    the ship's weight ``pr_weight`` [N] and the step ``pr_dt`` [s].
    """
    from stabflow.config import _fill_defaults, schema
    from stabflow.constants import G, KNOT
    from stabflow.dynamics import _kernels as K
    from stabflow.dynamics.derivative import run_full
    from stabflow.statistics.ensemble import diffraction_for
    from stabflow.dynamics.model import parameters
    from stabflow.statistics.ensemble import build_model

    heel = np.arange(0.0, 70.01, 1.0)
    hs = np.asarray(cfg["headings_deg"], float)
    fns = np.asarray(cfg["froude_numbers"], float)
    steep = np.asarray(cfg["steepness"], float)
    r1, r3, ratio = (np.full((len(hs), len(fns), len(steep)), np.nan) for _ in range(3))
    dt, dur = float(cfg["dt"]), float(cfg["duration"])
    keep = int(round(0.25 * dur / dt))
    k = 2 * math.pi / lam
    w = math.sqrt(G * k)
    tables = None
    inertia, b44, b44q = (np.empty(len(fns)) for _ in range(3))
    for b, fn in enumerate(fns):
        U = fn * math.sqrt(G * lam)
        c = _fill_defaults(schema("config")["properties"]["ensembles"]["items"],
                           {"name": "pr", "ship": ship.name, "speed_kn": U / KNOT, "heading_deg": float(hs[0]),
                            "records": 1, "stations": int(cfg["stations"]), "duration": dur, "dt": dt})
        # one model per speed (the damping depends on it); the headings differ only in the kernel's
        # parameter vector
        model = build_model(ship, c, hydro)
        co, sec, st = model.co, model.sec, model.st
        inertia[b], b44[b], b44q[b] = co.i44 + co.a44, co.b44, co.b44q
        if tables is None:  # GZ on the wave depends on the wave alone: once per steepness
            tables = [wave_gz_table(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]), lam, x * lam, heel)
                      for x in steep]
        s0 = model.s0.copy()
        s0[K.S_ROLL] = math.radians(float(cfg["phi0_deg"]))
        for a, mu in enumerate(hs):
            m = dataclasses.replace(model, p=parameters(co, model.ship.rho, float(st["lcg"]), float(st["kg"]), float(mu)),
                                    diffraction=None if model.diffraction is None else diffraction_for(model, float(mu)))
            v_rel = w / k * math.cos(math.radians(mu)) - U
            ratio[a, b, :] = abs(k * v_rel) * model.roll_period / (2 * math.pi)
            for j, s in enumerate(steep):
                H = s * lam
                roll = roll_1dof(tables[j], heel, lam, v_rel, co.i44 + co.a44, co.b44, co.b44q, float(st["mass"]) * G,
                                 float(cfg["phi0_deg"]), dur, dt)
                r1[a, b, j] = 90.0 if np.isnan(roll[-1]) else float(np.nanmax(np.abs(roll[-keep:])))
                out, last = run_full(m, (np.array([0.5 * H]), np.array([w]), np.array([0.0])), float(mu), dur, dt, s0)
                rr = np.degrees(out[: last + 1, K.S_ROLL])
                r3[a, b, j] = 90.0 if last < len(out) - 1 else float(np.abs(rr[-keep:]).max())
    return xr.Dataset(
        {"pr_roll_1dof": (("pr_heading", "pr_froude", "pr_steepness"), r1),
         "pr_roll_3dof": (("pr_heading", "pr_froude", "pr_steepness"), r3),
         "pr_encounter_ratio": (("pr_heading", "pr_froude", "pr_steepness"), ratio),
         # the 1-DOF model's coefficients at each speed (the sea-state runs use them too)
         "pr_inertia": ("pr_froude", inertia), "pr_b44": ("pr_froude", b44), "pr_b44q": ("pr_froude", b44q)},
        coords={"pr_heading": hs, "pr_froude": fns, "pr_steepness": steep},
        attrs={"pr_wave_length": lam, "pr_phi0_deg": float(cfg["phi0_deg"]), "pr_duration": dur,
               "pr_weight": float(st["mass"]) * G, "pr_dt": dt})


def parametric_level2_row(pr: xr.Dataset, std: Standards) -> Row:
    """Parametric rolling, level 2 (second check's idea): the largest roll of the 1-DOF model over
    stabflow's regular wave cases, against the roll-angle standard; NOT EVALUATED while the
    circular's wave cases, RPR0 and the angle are not sourced (the roll is computed regardless)."""
    lvl = f"{SG}.parametric_rolling.level_2"
    wc = std.get("sgisc.wave_data.pure_loss_and_parametric_roll_level2_wave_cases.cases")
    miss = [f"{wc.key} ({wc.source})"] if not wc.available else []
    r0 = std.get(f"{lvl}.RPR0")
    if not r0.available:
        miss.append(f"{r0.key} ({r0.source})")
    v = float(pr["pr_roll_1dof"].max())
    return against("parametric rolling: largest roll of the 1-DOF model with GZ on the wave", "SGISC parametric rolling, level 2",
                   v, "deg", std.get(f"{lvl}.roll_angle_threshold_deg"), "<=", missing=miss,
                   note=f"stabflow's cases: lambda = L, headings {', '.join(f'{h:g}' for h in pr.pr_heading.values)} deg, "
                        f"Fn {', '.join(f'{f:g}' for f in pr.pr_froude.values)}, H/lambda "
                        f"{', '.join(f'{x:g}' for x in pr.pr_steepness.values)}; the 3-DOF time domain in the same waves "
                        f"gives {float(pr['pr_roll_3dof'].max()):.1f} deg (results pr_roll_3dof)")


#: crest positions per wave length for GM(H_i, lambda_i) of parametric rolling's first level-2 check
#: (stabflow's reading: the 2013 draft's "series of waves" names none; its level 1, 2.11.2.2, puts the
#: crest at the LCG and at each 0.1 L forward and aft, ten positions a wave length)
C1_CRESTS = 10
#: the level-2 wave cases' entry (the adopted circular's, null; the 2013 draft's under ``draft``)
C1_CASES = "sgisc.wave_data.pure_loss_and_parametric_roll_level2_wave_cases.cases"


def c1_cases(std: Standards) -> tuple[np.ndarray, str]:
    """The regular waves of parametric rolling's first level-2 check: (n, 3) rows (W_i [-],
    lambda_i [m], H_i [m]) and where they come from: the adopted (or overridden) table, whose rows
    are laid out as the entry's ``columns_expected`` (case number, W_i, H_i, lambda_i), else the 2013
    draft's Table 3-A-1 (``sgisc.yaml``, rows W_i, lambda_i, H_i). StabflowError naming the entry
    when neither is there or the adopted value is not such a table."""
    from stabflow import StabflowError

    wc = std.get(C1_CASES)
    if wc.available:
        t = np.asarray(wc.value, dtype=object)
        if t.ndim != 2 or t.shape[1] != 4:
            raise StabflowError(f"criteria data: '{C1_CASES}': the value must be a table of rows (case number, W_i, "
                                f"H_i [m], lambda_i [m]), not {wc.value!r}")
        t = t.astype(float)
        return t[:, [1, 3, 2]], wc.cite()
    if wc.draft is None:
        raise StabflowError(f"criteria data: '{C1_CASES}' has neither a value nor a draft")
    return np.asarray(wc.draft["value"], float), wc.cite_draft()


def parametric_c1(sec: Sections, volume: float, lcg: float, kg: float, gm0: float, cases: np.ndarray, r_pr: float,
                  t_phi: float, v_d: float | None) -> xr.Dataset:
    """Parametric rolling, level 2, first check, as the 2013 draft states it (SLF 55/WP.3 Annex 1,
    2.11.3.2, read in Umeda, ISSW 2013, pp. 11-13): C1 = sum_i W_i C_i over the regular waves
    (W_i, lambda_i, H_i) of ``cases``, C_i = 0 where either requirement holds, 1 where neither:

    * 2.11.3.2.1, the GM variation: GM(H_i, lambda_i) > 0 and dGM(H_i, lambda_i) / GM(H_i, lambda_i)
      < R_PR (``r_pr``, level 1's standard), GM the mean and dGM half the range of the metacentric
      height of the ship balanced in sinkage and trim on the wave over ``C1_CRESTS`` crest positions;
    * 2.11.3.2.2, the speed: V_PR,i > V_D, V_PR,i = |2 lambda_i / T_phi sqrt(GM(H_i, lambda_i) / GM)
      - sqrt(g lambda_i / (2 pi))| where GM(H_i, lambda_i) > 0 (the speed of principal parametric
      resonance in head or following waves), T_phi the calm-water natural roll period [s] (``t_phi``),
      GM the calm-water metacentric height (``gm0``) [m], V_D the service speed [m/s] (``v_d``).

    The speed requirement is not evaluated (C1 then counts the GM requirement alone, an upper bound;
    attribute ``c1_speed_requirement`` says why) without a service speed, or where GM <= 0 or T_phi is
    not finite. A wave on which the ship finds no equilibrium at some crest position leaves that case's
    GM NaN and C1 NaN (``c1_no_equilibrium`` names the cases).

    Returns a Dataset along ``c1_case``: ``c1_weight``, ``c1_wave_length``, ``c1_wave_height``,
    ``c1_gm_wave`` (mean) and ``c1_delta_gm`` [m], ``c1_gm_ratio`` (dGM / GM), ``c1_speed_resonance``
    V_PR [m/s] (NaN where GM(H, lambda) <= 0 or not evaluated), ``c1_fails`` C_i, and the scalar ``c1``.
    """
    from stabflow import StabflowError
    from stabflow.constants import G

    W, lam, H = (np.asarray(cases, float)[:, j] for j in range(3))
    gm = np.full((len(W), C1_CRESTS), np.nan)
    for i in range(len(W)):
        guess = (None, None)
        for j, f in enumerate(np.arange(C1_CRESTS) / C1_CRESTS - 0.5):
            try:
                gm[i, j], _, _, guess = wave_gm(sec, volume, lcg, kg, 0.5 * H[i], 2 * math.pi / lam[i],
                                                lcg + f * lam[i], guess)
            except StabflowError:  # no equilibrium on this wave: the case stays NaN, C1 NaN
                break
    bad = ~np.isfinite(gm).all(axis=1)
    mean = np.where(bad, np.nan, gm.mean(axis=1))
    delta = np.where(bad, np.nan, 0.5 * (gm.max(axis=1) - gm.min(axis=1)))
    why = ("no service speed (criteria.service_speed_kn)" if v_d is None else
           f"calm-water GM {gm0:.3g} m, not positive" if not gm0 > 0 else
           "no finite calm-water roll period" if not math.isfinite(t_phi) else "")
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(mean > 0, delta / mean, np.nan)
        vpr = (np.where(mean > 0, np.abs(2 * lam / t_phi * np.sqrt(mean / gm0) - np.sqrt(G * lam / (2 * math.pi))),
                        np.nan) if not why else np.full(len(W), np.nan))
    gm_ok = (mean > 0) & (ratio < r_pr)
    speed_ok = (vpr > v_d) if not why else np.zeros(len(W), bool)
    fails = np.where(bad, np.nan, (~(gm_ok | speed_ok)).astype(float))
    ds = xr.Dataset(
        {"c1_weight": ("c1_case", W), "c1_wave_length": ("c1_case", lam), "c1_wave_height": ("c1_case", H),
         "c1_gm_wave": ("c1_case", mean), "c1_delta_gm": ("c1_case", delta), "c1_gm_ratio": ("c1_case", ratio),
         "c1_speed_resonance": ("c1_case", vpr), "c1_fails": ("c1_case", fails)},
        coords={"c1_case": np.arange(1, len(W) + 1)},
    )
    ds["c1"] = float(np.sum(W * fails))
    ds.attrs.update(c1_r_pr=float(r_pr), c1_roll_period=float(t_phi), c1_gm=float(gm0),
                    c1_service_speed=np.nan if v_d is None else float(v_d), c1_crest_positions=C1_CRESTS,
                    c1_speed_requirement=f"not evaluated: {why}" if why else "evaluated",
                    c1_no_equilibrium=", ".join(str(i + 1) for i in np.flatnonzero(bad)) or "none")
    return ds


def parametric_c1_row(c1: xr.Dataset, std: Standards, cases_source: str) -> Row:
    """Parametric rolling, level 2, first check: C1 against RPR0 (the draft's "less than RPR0": not
    vulnerable, read here as C1 <= RPR0 like every limit, within round-off; else the second check C2
    decides, :func:`stabflow.criteria.sea_states.parametric_c2`). NOT EVALUATED while RPR0 and the wave cases are the
    drafts'; with the speed requirement unevaluated C1 is an upper bound and no indicative verdict."""
    wc = std.get(C1_CASES)
    miss, drafted = [], []
    if not wc.available:
        miss.append(f"{wc.key} ({wc.source})")
        drafted.append(wc)
    speed = str(c1.attrs["c1_speed_requirement"])
    if speed != "evaluated":
        miss.append(f"the speed requirement ({speed.removeprefix('not evaluated: ')}): C1 an upper bound")
    if c1.attrs["c1_no_equilibrium"] != "none":
        miss.append(f"GM on the wave: no equilibrium on wave case(s) {c1.attrs['c1_no_equilibrium']}")
    n = int(c1.sizes["c1_case"])
    return against("parametric rolling: C1 over the level-2 regular waves (GM and speed requirements)",
                   "SGISC parametric rolling, level 2", float(c1["c1"]), "-", std.get(f"{SG}.parametric_rolling.level_2.RPR0"),
                   "<=", missing=miss, drafted=drafted,
                   note=f"{n} waves ({cases_source}); R_PR {c1.attrs['c1_r_pr']:.3f}, T_phi {c1.attrs['c1_roll_period']:.2f} s, "
                        f"{int(np.nansum(c1['c1_fails']))} of {n} fail both; GM on the wave over {C1_CRESTS} crest positions; "
                        "where C1 exceeds RPR0 the second check C2 (its row) decides")


def surf_riding_thresholds(ship, cfg: dict, L: float, radiation: xr.Dataset | None = None) -> xr.Dataset:
    """Surf-riding level-2 physics: the critical Froude number of Melnikov's method on the surge
    equation (:func:`stabflow.dynamics.surf_riding.melnikov_threshold`, the ship's own resistance
    and Froude-Krylov surge force) in regular following waves over lambda/L x H/lambda. The
    resistance is the 6-DOF model's calm-water resistance (the ship's ``manoeuvring.resistance``,
    :mod:`stabflow.dynamics.resistance`; by default the ITTC-57 friction line with the form factor,
    no wave-making part), named in ``sr_resistance``; ``L`` [m] the waterline length.

    For a ship with the heave-pitch memory model (``manoeuvring.heave_pitch_radiation: memory``)
    and its ``radiation`` step's dataset, the same grid with the mean wave-induced surge force of
    the heave-pitch response (``wave_force=True``; the broaching step's check shows it is what puts
    the free ship's threshold 26 % below plain Melnikov's at lambda 42.7 m on the trawler) as
    ``sr_froude_critical_wave_force``; otherwise ``sr_wave_force_not_computed`` says why (the ship
    file's constant heave-pitch damping, one frequency's, does not vanish at low encounter frequency
    and overstates that force)."""
    from stabflow.constants import G
    from stabflow.dynamics.broaching import six_dof_model
    from stabflow.dynamics.radiation import uses_memory
    from stabflow.dynamics.surf_riding import melnikov_threshold

    from stabflow import StabflowError

    # the commanded speed only sets the model's thrust, which the threshold does not use; roll
    # damping does not enter the surge equation: the config coefficients stand in for Capytaine/Ikeda
    memory = uses_memory(ship)
    surge = ship.modified(dynamics={"hydro": "config", "roll_damping": "coefficients"})
    with_memory = surge.modified()
    # heave and pitch do not enter the surge equation: no heave-pitch memory model (its BEM) for it
    surge.data.get("manoeuvring", {})["heave_pitch_radiation"] = "constant"
    try:
        model = six_dof_model(surge, 0.0, 10.0, tables=(91, 51))
    except StabflowError as e:
        return xr.Dataset(attrs={"sr_not_computed": f"the 6-DOF surge model could not be built: {e}"})
    models = {"sr_froude_critical": (model, False)}
    why = None
    if not memory:
        why = ("the ship keeps constant heave-pitch coefficients (one frequency's), which overstate the mean wave force "
               "near the celerity; manoeuvring.heave_pitch_radiation: memory computes it")
    elif radiation is None:
        why = "the radiation step's heave-pitch coefficients were not given"
    else:
        try:
            models["sr_froude_critical_wave_force"] = (six_dof_model(with_memory, 0.0, 10.0, tables=(91, 51),
                                                                     radiation=radiation), True)
        except StabflowError as e:
            why = f"the 6-DOF model with the heave-pitch memory could not be built: {e}"
    ratios = np.asarray(cfg["wavelength_ratios"], float)
    steep = np.asarray(cfg["steepness"], float)
    out = {}
    beyond = 0  # wave cases whose mean wave force exceeds the resistance along the whole orbit
    for name, (m, wave_force) in models.items():
        fn = np.full((len(ratios), len(steep)), np.nan)
        for i, r in enumerate(ratios):
            for j, s in enumerate(steep):
                celerity = math.sqrt(G * r * L / (2 * math.pi))
                try:
                    u = melnikov_threshold(m, r * L, s * r * L, wave_force=wave_force)
                except ValueError as e:
                    beyond += "exceeds the resistance" in str(e)
                    u = math.nan
                # no threshold below the celerity (the root sits on the bracket's end): NaN, reported as such
                fn[i, j] = u / math.sqrt(G * L) if u < 0.999 * celerity else np.nan
        out[name] = (("sr_wavelength_ratio", "sr_steepness"), fn)
    attrs = {"sr_method": "Melnikov's method on the surge equation (stabflow.dynamics.surf_riding)",
             "sr_resistance": str(model.resistance.get("resistance_method", ""))}
    if why is not None:
        attrs["sr_wave_force_not_computed"] = why
    else:
        attrs["sr_wave_force_exceeds_resistance"] = int(beyond)
    return xr.Dataset(out, coords={"sr_wavelength_ratio": ratios, "sr_steepness": steep}, attrs=attrs)


def surf_riding_level2_row(sr: xr.Dataset, fn: float | None, std: Standards) -> Row:
    """Surf-riding level 2: stabflow computes the Melnikov critical Froude number over regular
    following waves; the circular's index (wave cases and weights) and R_SR are not sourced."""
    r = std.get(f"{SG}.surf_riding_broaching.level_2.R_SR")
    wc = std.get("sgisc.wave_data.level2_wave_scatter_table")
    miss = ["the circular's surf-riding wave cases (not read)"]
    if "sr_froude_critical" not in sr:
        return against("surf-riding/broaching: C (Melnikov critical Froude number)", "SGISC surf-riding, level 2",
                       math.nan, "-", r, "<=", missing=[sr.attrs["sr_not_computed"]] + miss)
    lowest = float(sr["sr_froude_critical"].min())
    return against("surf-riding/broaching: C (Melnikov critical Froude number)", "SGISC surf-riding, level 2", math.nan,
                   "-", r, "<=", missing=miss,
                   note=f"lowest critical Fn over stabflow's regular following waves {lowest:.3f}"
                        + (f" against the service Fn {fn:.3f}" if fn is not None else "") + f"; {wc.key}: "
                        + ("read" if wc.available else "not read"))
