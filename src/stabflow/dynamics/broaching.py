"""Paper 004's stern-quartering scenario with the 6-DOF model (issue 17).

Lin, Meinhold & Salvesen (1998) simulate the 20.7 m fishing vessel *Italian Gold* with LAMP-2 at
10 kn in waves 45 degree off the stern from starboard, autopilot holding the course, the ship
starting on course in the trough: regular waves of height 1.8 m and lengths 21.3, 30.5, 42.7 and
85.3 m (their Table 3) and Pierson-Moskowitz seas of Hs 3.1, 4.0 and 4.6 m (Table 4), with G at
midships 0.08 m above the design waterline ("heavy loading"). stabflow runs the same cases on its
25 m trawler at that heavy loading (same mass, KG = midship draft + 0.08 m) and at its tank-test
loading, and reports the six motions and the rudder, and which records capsize, broach or surf-ride.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import xarray as xr

from stabflow.config import Ship
from stabflow.constants import G, KNOT
from stabflow.dynamics import _kernels as K
from stabflow.dynamics.manoeuvres import record_events
from stabflow.dynamics.manoeuvring import (LINEAR_DERIVATIVES, Autopilot, Foil, Manoeuvring, SixDof, build_six_dof,
                                           first_harmonic, hull_derivative_sets, linear_regular_response,
                                           linearised_course_change, simulate_six_dof)
from stabflow.dynamics.model import coefficients
from stabflow.dynamics.roll_damping import section_parameters
from stabflow.dynamics.tables import section_tables
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import compute_statics, equilibrium
from stabflow.io import annotate
from stabflow.waves.seaway import Seaway

MOTIONS = ("surge", "sway", "heave", "roll", "pitch", "yaw", "rudder")

#: stations of the lateral profile on which the hull derivatives are computed, whatever the ship's
#: own count (the larger of the two). The slender-body trailing edge is the aft face of a station's
#: slab, so on the ship's stations it moves by up to a slab as their count changes (trawler:
#: x_T -8.88 m at 81 stations, -8.93 m at 321; Y'r, N'r 0.8 % apart), and a 6-DOF record with
#: them did not converge with the count (roll and yaw over 30 s in the benchmark's sea, 81 and
#: 161 stations 2.7-7.8 % from 641; with the derivatives of 641 stations 0.1-0.4 %). At 321 the
#: derivatives are within 0.12 % of 1281 stations' on the trawler (N'v; the others 0.02-0.04 %)
#: and 0.43 % on the DTC (Y'r), which uses Clarke's.
PROFILE_STATIONS = 321


def profile_derivative_sets(ship: Ship, st: xr.Dataset) -> dict:
    """Both hull derivative sets (:func:`stabflow.dynamics.manoeuvring.hull_derivative_sets`) of
    the ship's lateral profile cut at :data:`PROFILE_STATIONS` stations, at the loading of the
    statics ``st``."""
    n = max(PROFILE_STATIONS, int(ship.hull["stations"]))
    fine = Sections(build_hull(ship if n == int(ship.hull["stations"]) else ship.modified(stations=n)))
    return hull_derivative_sets(section_parameters(fine, st))


def manoeuvring_from_ship(ship: Ship, sec: Sections, st: xr.Dataset, heading_deg: float = 0.0) -> Manoeuvring:
    """The ship config's ``manoeuvring`` section as a :class:`Manoeuvring` (added mass from Capytaine's
    zero-frequency limit of the hull mesh unless the config says ``clarke`` or gives values)."""
    cfg = ship.data.get("manoeuvring", {})
    foils = tuple(Foil(x=f["x"], z=f["z"], span=f["span"], chord=f["chord"], rudder=f.get("rudder", False),
                       stall_deg=f.get("stall_deg", 24.0), trail_deg=f.get("trail_deg", 12.0))
                  for f in cfg.get("foils", []))
    ap = cfg.get("autopilot", {})
    autopilot = Autopilot(ga=ap.get("ga", 0.9), gb=ap.get("gb", 20.0),
                          proportional_band_deg=ap.get("proportional_band_deg", 5.0),
                          slew_rate_deg_s=ap.get("slew_rate_deg_s", 5.5), max_deg=ap.get("max_deg", 35.0),
                          heading_deg=heading_deg)
    am = cfg.get("added_mass", "capytaine")
    if am == "capytaine":
        from stabflow.dynamics.hydro import bem_mesh, manoeuvring_added_mass

        h0, th0, _ = equilibrium(sec, float(st["volume"]), float(st["lcg"]), float(st["kg"]))
        added = manoeuvring_added_mass(bem_mesh(ship), h0, th0, float(st["lcg"]), float(st["kg"]), ship.rho)
    elif am == "clarke":
        added = None
    else:
        added = np.array([[am["a11"], 0.0, 0.0], [0.0, am["a22"], am["a26"]], [0.0, am["a26"], am["a66"]]])
    der = {k: v for k, v in cfg.get("derivatives", {}).items() if k != "source"}
    hull = cfg.get("hull_derivatives", "clarke")
    # the slender-body set needs the profile finely cut (PROFILE_STATIONS); Clarke's regression
    # reads whole-hull particulars only, and values given for all four need neither
    sets = profile_derivative_sets(ship, st) if hull == "slender_body" and not set(LINEAR_DERIVATIVES) <= set(der) \
        else None
    return Manoeuvring(foils=foils, autopilot=autopilot, derivatives=der, hull=hull,
                       form_factor=cfg.get("form_factor", 0.0), resistance=dict(cfg.get("resistance", {})),
                       side_force_height=cfg.get("side_force_height"), added_mass=added,
                       radiation_forward_speed=cfg.get("radiation_forward_speed", False), hull_sets=sets)


def six_dof_model(ship: Ship, heading_deg: float, speed_kn: float, kg: float | None = None,
                  tables: tuple[int, int] = (181, 101), radiation: xr.Dataset | None = None,
                  waterline: str = "planar", dphi_dzdt: bool = False) -> SixDof:
    """The ship (optionally loaded to ``kg`` [m]) ready for 6-DOF records at ``speed_kn`` [kn] in waves
    of ``heading_deg`` [degree] relative to the course (0 following), with its config coefficients
    and, if the ship asks for it, the heave-pitch radiation memory (from the ``radiation`` step's
    dataset ``radiation``, or computed now: :func:`stabflow.dynamics.radiation.ship_memory`);
    ``waterline`` and ``dphi_dzdt`` (the incident pressure's decay with depth) as
    :func:`stabflow.dynamics.simulate`."""
    from stabflow.dynamics.radiation import ship_memory

    s = ship.modified(kg=kg) if kg is not None else ship
    hull = build_hull(s)
    st = compute_statics(s, hull)
    sec = Sections(hull)
    co = coefficients(s, sec, st, None, speed=speed_kn * KNOT)
    return build_six_dof(sec, st, co, s.rho, heading_deg, speed_kn * KNOT, manoeuvring_from_ship(s, sec, st),
                         tables=section_tables(sec, *tables), memory=ship_memory(ship, float(st["lcg"]), radiation),
                         waterline=waterline, dphi_dzdt=dphi_dzdt)


def heavy_kg(ship: Ship, above_waterline: float) -> float:
    """KG [m] that puts G ``above_waterline`` [m] above the ship's upright midship waterline (paper
    004: 0.08 m), the mass unchanged."""
    hull = build_hull(ship)
    st = compute_statics(ship, hull)
    return float(st["draft_mid"]) + above_waterline


def trough_phase(model: SixDof, omega: float) -> float:
    """Phase of a regular wave of frequency ``omega`` that puts a trough at G at t = 0 (paper 004:
    "the ship is at the bottom of the incident wave")."""
    k = omega**2 / float(model.p[K.P_G])
    return float(np.pi - k * float(model.p[K.P_XG]) * np.cos(np.radians(model.heading_deg)))


def scenario(ship: Ship, cfg: dict, progress: bool = False, radiation: xr.Dataset | None = None) -> xr.Dataset:
    """Run paper 004's cases (``cfg``: the config's ``broaching`` section) at each loading; returns
    time histories along (loading, case, time), NaN after a record's end (``end_time``), the
    events of each record and its step's check (``step_error`` [%]: the first ``TRAJECTORY_S``
    seconds again at dt / ``REFINE``, :func:`scenario_step_row`). ``radiation``: the ship's
    heave-pitch memory dataset, if it uses one (:func:`six_dof_model`)."""
    from tqdm import tqdm

    from stabflow.validation.ensemble import TRAJECTORY_S

    dt = float(cfg["dt"])
    loads = {}
    for name, spec in cfg["loadings"].items():
        loads[name] = heavy_kg(ship, float(spec["kg_above_waterline"])) if "kg_above_waterline" in spec else spec.get("kg")
    reg, irr = cfg["regular"], cfg["irregular"]
    cases = [("regular", float(lam), float(reg["height"])) for lam in reg["wavelengths"]]
    cases += [("irregular", np.nan, float(hs)) for hs in irr["hs"]]
    duration = max(float(reg["duration"]), float(irr["duration"]))
    n = int(round(duration / dt)) + 1
    data = {v: np.full((len(loads), len(cases), n), np.nan) for v in MOTIONS}
    ev_names = ("capsized", "capsize_time", "broach", "broach_time", "surf_riding", "surf_riding_time",
                "surf_riding_longest", "end_time")
    ev = {k: np.zeros((len(loads), len(cases))) for k in ev_names}
    step = np.zeros((len(loads), len(cases)))
    check_s = min(TRAJECTORY_S, float(reg["duration"]), float(irr["duration"]))
    kgs = np.zeros(len(loads))
    wave = np.full((len(cases), 3), np.nan)  # wave number, encounter frequency, phase (regular cases)
    bar = tqdm(total=len(loads) * len(cases), desc=f"{ship.name} paper 004 cases", disable=not progress)
    for i, (lname, kg) in enumerate(loads.items()):
        model = six_dof_model(ship, float(cfg["heading_deg"]), float(cfg["speed_kn"]), kg, radiation=radiation,
                              waterline=cfg.get("waterline", "planar"), dphi_dzdt=bool(cfg.get("dphi_dzdt", False)))
        kgs[i] = float(model.p[K.P_ZG])
        for j, (kind, lam, h) in enumerate(cases):
            if kind == "regular":
                w = np.sqrt(G * 2 * np.pi / lam)
                waves = (np.array([0.5 * h]), np.array([w]), np.array([trough_phase(model, w)]))
                dur, cel = float(reg["duration"]), w / (2 * np.pi / lam)
                k = 2 * np.pi / lam
                wave[j] = (k, w - k * model.speed * np.cos(np.radians(model.heading_deg)), waves[2][0])
            else:
                sea = Seaway(kind=irr["spectrum"], hs=h, n_components=int(irr["n_components"]))
                waves = sea.components(int(irr["seed"]), j)
                dur, cel = float(irr["duration"]), G / sea.modal_frequency
            ds = simulate_six_dof(model, waves, dur, dt)
            step[i, j] = _step_error(model, waves, ds, dt, check_s)
            m = ds.sizes["time"]
            for v in MOTIONS:
                data[v][i, j, :m] = ds[v].values
            e = record_events(ds, broach_deg=float(cfg["broach_deg"]), celerity=cel,
                              surf_tolerance=float(cfg["surf_tolerance"]), surf_min_s=float(cfg["surf_min_s"]),
                              heading_deg=float(cfg["heading_deg"]))
            for k in ev_names[:-1]:
                ev[k][i, j] = e[k]
            ev["end_time"][i, j] = ds.attrs["end_time"]
            bar.update()
    bar.close()
    dims = ("loading", "case", "time")
    out = xr.Dataset({v: (dims, data[v]) for v in MOTIONS}, coords={
        "loading": list(loads), "case": [f"R-{k + 1}" if c[0] == "regular" else f"IR-{k + 1 - len(reg['wavelengths'])}"
                                         for k, c in enumerate(cases)],
        "time": np.arange(n) * dt})
    out["wavelength"] = ("case", np.array([c[1] for c in cases]))
    out["wave_height"] = ("case", np.array([c[2] for c in cases]))
    out["kg"] = ("loading", kgs)
    out["wave_number"] = ("case", wave[:, 0])
    out["encounter_frequency"] = ("case", wave[:, 1])
    out["wave_phase"] = ("case", wave[:, 2])
    hull = build_hull(ship)
    sp = section_parameters(Sections(hull), compute_statics(ship, hull))
    out = out.assign_coords(outline_x=("station", sp["x"].values),
                            outline_halfbreadth=("station", 0.5 * sp["breadth"].values))
    for k in ev_names:
        out[k] = (("loading", "case"), ev[k].astype(int) if k in ("capsized", "broach", "surf_riding") else ev[k])
    out["step_error"] = (("loading", "case"), step)
    out.attrs.update(ship=ship.name, speed_kn=float(cfg["speed_kn"]), heading_deg=float(cfg["heading_deg"]), dt=dt,
                     step_seconds=check_s,
                     waterline=cfg.get("waterline", "planar"), dphi_dzdt=int(bool(cfg.get("dphi_dzdt", False))),
                     lcg=float(model.p[K.P_XG]),
                     reference="Lin, Meinhold & Salvesen (1998), USCG CG-D-17-98, Tables 3-4, Figs 7-14",
                     note="NaN after a record's end (capsize): see end_time")
    return annotate(out)


def manoeuvre_checks(ship: Ship, cfg: dict, radiation: xr.Dataset | None = None):
    """Calm-water manoeuvres at the ship file's loading and the commanded speed, and the surf-riding
    thresholds in regular following waves of the scenario's height at its two longest wavelengths;
    with a heave-pitch memory model (``radiation``, :func:`six_dof_model`), its fit against the BEM.

    Returns (dataset of the results, validation rows, turning tracks, zig-zag histories)."""
    from dataclasses import replace

    from stabflow.dynamics.manoeuvres import trajectory, turning_circle, zigzag_overshoots
    from stabflow.dynamics.resistance import reference_rows
    from stabflow.dynamics.surf_riding import melnikov_threshold, simulated_threshold
    from stabflow.validation import Check

    from stabflow.dynamics.radiation import bem_from_dataset, radiation_checks, ship_radiation, uses_memory

    if radiation is None and uses_memory(ship):
        radiation = ship_radiation(ship)
    model = six_dof_model(ship, 0.0, float(cfg["speed_kn"]), radiation=radiation,
                          dphi_dzdt=bool(cfg.get("dphi_dzdt", False)))
    mc = cfg["manoeuvres"]
    calm = ([], [], [])
    dt = float(cfg["dt"])
    L = model.length
    out, tracks, zigzags, rows = {}, {}, {}, []
    straight = simulate_six_dof(replace(model, m=_steer(model, "fixed", 0.0)), calm, mc["straight_s"], dt)
    dev = float(np.max(np.abs(straight["yaw"])))
    rows.append(Check(f"calm water, rudder amidships, {mc['straight_s']:g} s: largest heading deviation", dev, 1e-6, "degree",
                      "a straight course (the hull is symmetric)", kind="consistency"))
    for helm in (35.0, 20.0):
        ds = simulate_six_dof(replace(model, m=_steer(model, "fixed", helm)), calm, mc["turning_s"], dt)
        tc = turning_circle(ds)
        for k, v in tc.items():
            out[f"turning_{int(helm)}_{k}"] = v
        tracks[f"turning circle, rudder {helm:g}°"] = trajectory(ds)
    from stabflow.dynamics import _kernels_6dof as K6
    from stabflow.dynamics.manoeuvring import sway_yaw_eigenvalues, with_hull_derivatives

    rudder = bool(np.any(model.foils[:, K6.F_RUDDER] != 0.0)) if len(model.foils) else False
    no_rudder = "the ship's manoeuvring section has no rudder foil: the autopilot cannot steer"

    def sway_yaw_eigenvalue(mod):  # open-loop directional stability: the largest real part
        return float(np.max(sway_yaw_eigenvalues(mod).real))

    lam_max = sway_yaw_eigenvalue(model)
    out["sway_yaw_eigenvalue"] = lam_max
    for k in LINEAR_DERIVATIVES:
        out[f"derivative_{k}"] = float(model.derivatives[k])
    # both sources of hull derivatives side by side (the report's table), each with its eigenvalue
    statics = _statics(ship)
    for name, der in profile_derivative_sets(ship, statics).items():
        if isinstance(der, str):
            out[f"{name}_unavailable"] = der
            continue
        for k in LINEAR_DERIVATIVES:
            out[f"{name}_{k}"] = float(der[k])
        out[f"sway_yaw_eigenvalue_{name}"] = sway_yaw_eigenvalue(with_hull_derivatives(model, der))
    for z in (10.0, 20.0):
        ds = simulate_six_dof(replace(model, m=_steer(model, "zigzag", z, z)), calm, mc["zigzag_s"], dt)
        first, second = zigzag_overshoots(ds, z)
        out[f"zigzag_{int(z)}_first_overshoot"] = first
        out[f"zigzag_{int(z)}_second_overshoot"] = second
        zigzags[f"{z:g}/{z:g}"] = (ds["time"].values, ds["yaw"].values, ds["rudder"].values)
        name = f"zig-zag {z:g}°/{z:g}° in calm water completes (both overshoot angles measured in {mc['zigzag_s']:g} s)"
        ref = "the manoeuvre's definition (IMO MSC.137(76) 4.2.6)"
        if not rudder:
            rows.append(Check.not_applicable(name, no_rudder, "-", ref))
        elif np.isfinite(first) and np.isfinite(second):
            rows.append(Check(name, 1.0, np.nan, "-", ref, lower=1.0))
        else:
            why = (f"the heading did not come back after the helm reversal: open-loop sway-yaw eigenvalue "
                   f"{lam_max:+.3f} 1/s ({'directionally unstable' if lam_max > 0 else 'stable'} with these hull "
                   "derivatives and foils)")
            rows.append(Check.failed(name, why, "-", ref, lower=1.0))
    step = simulate_six_dof(replace(model, m=_steer(model, "autopilot", 0.0, heading=10.0)), calm, mc["step_s"], dt)
    out["autopilot_step_overshoot"] = float(step["yaw"].max()) - 10.0
    out["autopilot_step_final"] = float(step["yaw"][-1])
    _, lin = linearised_course_change(model, 10.0, mc["step_s"])
    out["autopilot_step_overshoot_linear"] = float(lin.max()) - 10.0
    small = simulate_six_dof(replace(model, m=_steer(model, "autopilot", 0.0, heading=1.0)), calm, mc["step_s"], dt)
    _, lin1 = linearised_course_change(model, 1.0, mc["step_s"])
    n1 = min(len(lin1), small.sizes["time"])
    out["autopilot_1deg_deviation"] = float(np.max(np.abs(small["yaw"].values[:n1] - lin1[:n1])))
    rows_ap = [
        ("autopilot, 1° course change in calm water (below the servo's slew limit): largest |yaw - linear theory| "
         "/ step", out["autopilot_1deg_deviation"] / 1.0, dict(tolerance=0.05),
         f"linear theory of the same equations (closed loop, continuous servo): overshoot {lin1.max() - 1.0:.4f}°"),
        (f"autopilot, 10° course change in calm water: heading after {mc['step_s']:g} s / 10° - 1",
         out["autopilot_step_final"] / 10.0 - 1.0, dict(tolerance=0.01), "the commanded course"),
        ("autopilot, 10° course change: overshoot beyond the linear theory's (the slew limit only slows the turn)",
         # one-sided: less overshoot than the linear theory's (the slew limit) passes
         out["autopilot_step_overshoot"] - max(out["autopilot_step_overshoot_linear"], 0.0),
         dict(tolerance=np.nan, upper=0.01),
         f"linear theory of the same equations: overshoot {out['autopilot_step_overshoot_linear']:.4f}°"),
    ]
    for name, value, band, ref in rows_ap:
        rows.append(Check(name, value, unit="-" if "/" in name else "degree", reference=ref, kind="consistency", **band)
                    if rudder else Check.not_applicable(name, no_rudder, "-", ref, kind="consistency"))
    # small regular waves (H / lambda = 1/2000) against the linear frequency-domain solution of the
    # same equations, autopilot on
    for head, ratio in mc["small_waves"]:
        if not rudder:
            rows.append(Check.not_applicable(f"small regular waves, heading {head:g}°, lambda/L {ratio:g}: first "
                                             "harmonics / linear frequency domain", no_rudder + " (no steady state)",
                                             "-", "linear frequency-domain solution", kind="consistency"))
            continue
        mw = with_condition(model, head, model.speed)
        lam = ratio * L
        a = lam / 4000.0
        k = 2 * np.pi / lam
        w = np.sqrt(G * k)
        we = abs(w - k * mw.speed * np.cos(np.radians(head)))
        X = linear_regular_response(mw, lam, a)
        xi_g = float(mw.p[K.P_XG]) * np.cos(np.radians(head))
        ds = simulate_six_dof(mw, (np.array([a]), np.array([w]), np.array([-k * xi_g])), mc["small_wave_s"],
                              mc["small_wave_dt"], ramp_s=mc["small_wave_s"] / 6)
        fh = first_harmonic(ds, we, mc["small_wave_s"] * 0.55)
        lin = {"surge": abs(X[0]), "sway": abs(X[1]), "heave": abs(X[2]), "roll": np.degrees(abs(X[3])),
               "pitch": np.degrees(abs(X[4])), "yaw": np.degrees(abs(X[5]))}
        for v in ("surge", "sway", "heave", "roll", "pitch", "yaw"):
            out[f"small_wave_{int(head)}_{v}_ratio"] = fh[v] / lin[v]
            rows.append(Check(f"small regular waves, heading {head:g}°, lambda/L {ratio:g}, H/lambda 1/2000, autopilot on, "
                              f"dt {mc['small_wave_dt']:g} s: {v} first harmonic / linear - 1", fh[v] / lin[v] - 1.0,
                              0.05, "-", "linear frequency-domain solution of the same equations (closed loop, "
                              "continuous servo)", kind="consistency"))
    h = float(cfg["regular"]["height"])
    lams = sorted(float(x) for x in cfg["regular"]["wavelengths"])[-2:]
    thr = np.full((len(lams), 4), np.nan)
    full = "full 6-DOF"
    wave_ref = ("Melnikov's method on the surge equation with the mean wave-induced surge force of the linear "
                "heave-pitch response, k w_e Re(X^H B X) / 2 (absorbed wave momentum, Gerritsma & Beukelman 1972)")
    for i, lam in enumerate(lams):
        tag = f"surf-riding threshold, regular following wave lambda {lam:g} m (lambda/L {lam / L:.2f}), H {h:g} m"
        names = (f"{tag}: 6-DOF with only surge free (the surge equation in time) / Melnikov - 1",
                 f"{tag}: {full} / Melnikov - 1",
                 f"{tag}: {full} / Melnikov with the mean wave-induced surge force - 1")
        refs = ("Melnikov's method on the surge equation",) * 2 + (wave_ref,)
        if not mc["surf_riding"]:
            for name, ref in zip(names, refs):
                rows.append(Check.not_applicable(name, "broaching.manoeuvres.surf_riding is off in this config", "-", ref))
            continue
        c = np.sqrt(G * lam / (2 * np.pi))
        try:
            u_m = melnikov_threshold(model, lam, h)
        except ValueError as e:
            for name, ref in zip(names, refs):
                rows.append(Check.failed(name, f"Melnikov's threshold not found: {e}", "-", ref, kind="consistency",
                                         tolerance=0.05))
            continue
        thr[i, 0] = u_m
        for j, flags in ((1, (1, 0, 0, 0, 0, 0)), (2, (1, 1, 1, 1, 1, 1))):
            p = model.p.copy()
            p[K.P_FREE:K.P_FREE + 6] = flags
            try:
                thr[i, j] = simulated_threshold(replace(model, p=p), lam, h, 0.3 * u_m, 0.98 * c, tol=0.01)
            except ValueError as e:
                thr[i, j] = np.nan
                out[f"surf_riding_{lam:g}_{j}_error"] = str(e)
        try:
            thr[i, 3] = melnikov_threshold(model, lam, h, wave_force=True)
            wave_err = None
        except ValueError as e:
            wave_err = str(e)
        for name, ref, sim, u_ref, err in ((names[0], f"{refs[0]}: U_cr {u_m:.3f} m/s", thr[i, 1], u_m, None),
                                           (names[1], f"{refs[1]}: U_cr {u_m:.3f} m/s", thr[i, 2], u_m, None),
                                           (names[2], f"{refs[2]}: U_cr {thr[i, 3]:.3f} m/s", thr[i, 2], thr[i, 3],
                                            wave_err)):
            if err is not None:
                rows.append(Check.failed(name, f"Melnikov's threshold with the wave force: {err} (the 6-DOF "
                                         f"threshold is {thr[i, 2]:.3f} m/s)", "-", refs[2], kind="consistency",
                                         tolerance=0.05))
            elif np.isfinite(sim):
                rows.append(Check(name, sim / u_ref - 1.0, 0.05, "-", ref, kind="consistency"))
            else:
                rows.append(Check.failed(name, "the bisection bracket [0.3 U_cr, 0.98 c] did not hold a threshold",
                                         "-", ref, kind="consistency", tolerance=0.05))
    rows.extend(_following_wave_load_rows(ship, model, lams, h, thr[:, 0], out, mc["surf_riding"]))
    res = resistance_curve(model, sorted(float(x) for x in cfg["regular"]["wavelengths"]), h)
    rows.extend(reference_rows())
    if model.memory is not None:
        rows.extend(radiation_checks(bem_from_dataset(radiation), model.memory))
        out["memory_poles"] = float(len(model.memory.poles))
    ds = xr.Dataset({k: ((), v) for k, v in out.items() if not isinstance(v, str)})
    ds.attrs.update({k: v for k, v in out.items() if k.endswith("_unavailable")})
    ds.attrs["heave_pitch_radiation"] = "memory" if model.memory is not None else "constant"
    ds["surf_riding_wavelength"] = ("surf_case", np.array(lams))
    ds["surf_riding_melnikov"] = ("surf_case", thr[:, 0])
    ds["surf_riding_surge_only"] = ("surf_case", thr[:, 1])
    ds["surf_riding_six_dof"] = ("surf_case", thr[:, 2])
    ds["surf_riding_melnikov_wave_force"] = ("surf_case", thr[:, 3])
    ds = ds.merge(res)
    ds.attrs.update(res.attrs)
    ds.attrs.update(manoeuvre_length=L, manoeuvre_speed=model.speed,
                    hull_derivatives=str(ship.data.get("manoeuvring", {}).get("hull_derivatives", "clarke")),
                    manoeuvre_breadth=float(statics["bwl"]))  # particulars' breadth: the waterline breadth
    return ds, rows, tracks, zigzags


def resistance_curve(model: SixDof, wavelengths, height: float, froude_max: float = 1.2, n: int = 121) -> xr.Dataset:
    """The 6-DOF model's calm-water resistance R(u) from 0 to ``froude_max`` sqrt(g L), the
    ITTC-57 friction line on Kato's wetted surface with the form factor beside it (the model's
    resistance before the wave-making part, for comparison), and the Froude-Krylov surge-force
    amplitude of regular following waves of ``height`` [m] at ``wavelengths`` [m] with their
    celerities (:func:`stabflow.dynamics.surf_riding.surge_force`): where the amplitude exceeds R
    at the celerity, the wave can carry the ship at its speed."""
    from dataclasses import replace

    from stabflow.dynamics import _kernels_6dof as K6
    from stabflow.dynamics.surf_riding import resistance, surge_force

    u = np.linspace(0.0, froude_max * np.sqrt(G * model.length), n)
    # the kernel's resistance with its friction line alone (no table)
    m = model.m.copy()
    m[K6.M_RES], m[K6.M_RR_DU] = model.resistance["resistance_friction_line_factor"], 0.0
    line = resistance(replace(model, m=m), u)
    lams = np.asarray(wavelengths, float)
    amp = np.array([surge_force(model, lam, height)[0] for lam in lams])
    ds = xr.Dataset(
        {"resistance": ("resistance_speed", resistance(model, u),
                        {"units": "N", "long_name": f"calm-water resistance ({model.resistance['resistance_method']})"}),
         "resistance_friction_only": ("resistance_speed", line,
                                      {"units": "N", "long_name": "ITTC-57 friction line on Kato's wetted surface"}),
         "resistance_wave_surge_amplitude": ("resistance_wave", amp,
                                             {"units": "N", "long_name": f"FK surge-force amplitude, H {height:g} m"}),
         "resistance_wave_celerity": ("resistance_wave", np.sqrt(G * lams / (2 * np.pi)),
                                      {"units": "m/s", "long_name": "wave celerity"})},
        coords={"resistance_speed": ("resistance_speed", u, {"units": "m/s", "long_name": "surge velocity"}),
                "resistance_wave": ("resistance_wave", lams, {"units": "m", "long_name": "wavelength"})})
    ds.attrs.update({k: v for k, v in model.resistance.items()})
    ds.attrs["resistance_wave_height"] = float(height)
    return ds


#: tolerances of the following-wave load rows (:func:`_following_wave_load_rows`): the mean surge
#: force (second order: it sets the surf-riding threshold; measured 0.2-0.5 % on the trawler) and
#: the first harmonics (complex difference, amplitude and phase) and mean pitch moment (per its
#: first harmonic), the latter as the time-domain rows against pressure integration
#: (:mod:`stabflow.validation.dynamics`)
FOLLOWING_WAVE_TOLERANCE = {"mean": 0.01, "h1": 0.04}
#: commanded speed of those rows, a fraction of Melnikov's threshold: periodic surging
FOLLOWING_WAVE_SPEED = 0.6


def _following_wave_load_rows(ship: Ship, model, lams, height: float, melnikov, out: dict, enabled: bool = True) -> list:
    """Validation rows: the 6-DOF kernel's FK + HS loads on the surging, heaving and pitching hull in
    the surf-riding cases' regular following waves against surface-pressure integration on the hull
    mesh at the same poses (:func:`stabflow.dynamics.surf_riding.following_wave_loads`), at
    ``FOLLOWING_WAVE_SPEED`` x Melnikov's threshold; SKIPPED without a mesh, with replaced topsides
    (the STL carries the original ones, and the pitching hull's reach is not bounded beforehand) or
    with the surf-riding cases off (``enabled``)."""
    from stabflow.dynamics.surf_riding import following_wave_loads
    from stabflow.validation import Check
    from stabflow.validation.dynamics import NotApplicable, pressure_mesh

    ref = ("surface-pressure integration on the hull mesh at the record's poses (exact surface, "
           + ("the pressure decaying with depth as the kernel's dphi_dzdt)" if model.decay is not None
              else "decay off as the kernel's paper 000 eq 9)"))
    ref_off = ("surface-pressure integration on the hull mesh at the record's poses (exact surface, decay off as the "
               "kernel's paper 000 eq 9)")
    rows = []
    h1 = "|kernel - pressure integration| / |pressure integration| (complex: amplitude and phase)"
    # (label, load, what, tolerance key, row name's measure)
    specs = (("mean surge force", "fx", "mean", "mean", "kernel / pressure integration - 1"),
             ("surge force first harmonic", "fx", "h1", "h1", h1),
             ("heave force first harmonic", "fz", "h1", "h1", h1),
             ("pitch moment first harmonic", "my", "h1", "h1", h1),
             ("mean pitch moment", "my", "mean", "h1",
              "(kernel - pressure integration) / pressure's first-harmonic amplitude"))
    try:
        mesh = pressure_mesh(ship) if enabled else "broaching.manoeuvres.surf_riding is off in this config"
    except NotApplicable as e:
        mesh = str(e)
    for lam, u_m in zip(lams, melnikov):
        speed = FOLLOWING_WAVE_SPEED * float(u_m) if np.isfinite(u_m) else np.nan
        tag = (f"6-DOF loads, regular following wave lambda {lam:g} m, H {height:g} m, surging at "
               f"{speed:.2f} m/s ({FOLLOWING_WAVE_SPEED:g} x Melnikov's threshold)")
        names = [f"{tag}: {label}, {measure}" for label, _, _, _, measure in specs]
        # with the decay, the mean surge force with it off on both sides too (below)
        off = (f"{tag}: mean surge force with the pressure decay off on both sides, kernel / pressure integration - 1"
               if model.decay is not None else None)
        if isinstance(mesh, str):
            rows.extend(Check.not_applicable(n, mesh, "-", ref) for n in names)
            if off:
                rows.append(Check.not_applicable(off, mesh, "-", ref_off))
            continue
        try:
            if not np.isfinite(speed):
                raise ValueError("Melnikov's threshold was not found")
            r = following_wave_loads(model, *mesh, lam, height, speed)
        except ValueError as e:
            rows.extend(Check.failed(n, str(e), "-", ref, tolerance=FOLLOWING_WAVE_TOLERANCE[tol])
                        for n, (_, _, _, tol, _) in zip(names, specs))
            if off:
                rows.append(Check.failed(off, str(e), "-", ref_off, tolerance=FOLLOWING_WAVE_TOLERANCE["mean"]))
            continue
        for k, v in r.items():
            out[f"following_wave_{lam:g}_{k}".replace(".", "_")] = v  # e.g. following_wave_42_7_pitch_deg
        for name, (_, f, what, tol, _) in zip(names, specs):
            p = r[f"pressure_{f}_{what}"]
            if what == "h1":
                value = r[f"{f}_h1_difference"]
            elif tol == "mean":
                value = r[f"kernel_{f}_mean"] / p - 1.0
            else:
                value = (r[f"kernel_{f}_mean"] - p) / r[f"pressure_{f}_h1"]
            rows.append(Check(name, value, FOLLOWING_WAVE_TOLERANCE[tol], "-",
                              f"{ref}: {p:.4g} {'N m' if f == 'my' else 'N'} (pitch {r['pitch_deg']:.1f} degree, "
                              f"encounter {r['encounter_frequency']:.3f} rad/s)"))
        if off:
            # the same mean with the decay off on both sides (paper 000's eq 9 against pressure
            # integration without decay, the ship's own record without it): the geometry of the
            # second-order force (stations on the surging, pitching hull, tilted sections) apart
            # from how the decay is carried above and below the calm waterline, where the kernel's
            # calm-section average and the reference's Wheeler stretching differ by choice
            try:
                r0 = following_wave_loads(dataclasses.replace(model, decay=None), *mesh, lam, height, speed)
            except ValueError as e:
                rows.append(Check.failed(off, str(e), "-", ref_off, tolerance=FOLLOWING_WAVE_TOLERANCE["mean"]))
                continue
            p0 = r0["pressure_fx_mean"]
            out[f"following_wave_{lam:g}_decay_off_kernel_fx_mean".replace(".", "_")] = r0["kernel_fx_mean"]
            out[f"following_wave_{lam:g}_decay_off_pressure_fx_mean".replace(".", "_")] = p0
            rows.append(Check(off, r0["kernel_fx_mean"] / p0 - 1.0, FOLLOWING_WAVE_TOLERANCE["mean"], "-",
                              f"{ref_off}: {p0:.4g} N (pitch {r0['pitch_deg']:.1f} degree, encounter "
                              f"{r0['encounter_frequency']:.3f} rad/s)"))
    return rows


def _statics(ship: Ship) -> xr.Dataset:
    return compute_statics(ship, build_hull(ship))


def _steer(model: SixDof, mode: str, helm: float, zigzag: float = 10.0, heading: float = 0.0) -> np.ndarray:
    """A copy of the model's manoeuvring vector with the steering mode set."""
    from stabflow.dynamics import _kernels_6dof as K6

    m = model.m.copy()
    m[K6.M_STEERING] = {"fixed": K6.STEER_FIXED, "autopilot": K6.STEER_AUTOPILOT, "zigzag": K6.STEER_ZIGZAG}[mode]
    m[K6.M_HELM] = np.radians(helm)
    m[K6.M_ZIGZAG] = np.radians(zigzag)
    m[K6.M_PSID] = np.radians(heading)
    return m


def with_condition(model: SixDof, heading_deg: float, speed: float) -> SixDof:
    """The same ship at another wave heading [degree] and commanded speed [m/s] (thrust re-balanced
    to the calm-water resistance there); the coefficients are the ship config's, independent of
    speed."""
    from dataclasses import replace

    from stabflow.dynamics import _kernels_6dof as K6
    from stabflow.dynamics.surf_riding import resistance

    p = model.p.copy()
    b = np.radians(heading_deg)
    p[K.P_COS_BETA], p[K.P_SIN_BETA] = np.cos(b), np.sin(b)
    m = model.m.copy()
    m[K6.M_SPEED] = speed
    out = replace(model, p=p, m=m, speed=float(speed), heading_deg=float(heading_deg))
    m[K6.M_THRUST] = float(resistance(out, speed))
    return out


def probability_map(ship: Ship, cfg: dict, progress: bool = False, radiation: xr.Dataset | None = None) -> xr.Dataset:
    """Capsize and broach probabilities per record over wave heading x speed for one sea state
    (``cfg``: the broaching section's ``map``), with Clopper-Pearson intervals on every cell.

    Each cell simulates ``records`` independent records of ``duration`` seconds (seaway record
    index unique over the map, from the map's seed) with the autopilot on the original course; the
    first ``TRAJECTORY_S`` seconds of each cell's first record are simulated again at dt / ``REFINE``
    for the step's check (``map_step_error`` [%], :func:`map_step_row`)."""
    from scipy.stats import binomtest
    from tqdm import tqdm

    from stabflow.validation.ensemble import TRAJECTORY_S

    mc = cfg["map"]
    lspec = cfg["loadings"][mc["loading"]]
    kg = heavy_kg(ship, float(lspec["kg_above_waterline"])) if "kg_above_waterline" in lspec else lspec.get("kg")
    base = six_dof_model(ship, 0.0, float(cfg["speed_kn"]), kg, radiation=radiation,
                         waterline=cfg.get("waterline", "planar"), dphi_dzdt=bool(cfg.get("dphi_dzdt", False)))
    sea = Seaway(kind=mc["sea"]["spectrum"], hs=float(mc["sea"]["hs"]), tp=mc["sea"].get("tp"),
                 n_components=int(mc["sea"].get("n_components", 220)))
    heads, speeds = np.asarray(mc["headings_deg"], float), np.asarray(mc["speeds_kn"], float)
    n = int(mc["records"])
    dt, dur = float(mc["dt"]), float(mc["duration"])
    cap = np.zeros((len(heads), len(speeds)), int)
    bro = np.zeros_like(cap)
    step = np.zeros(cap.shape)
    check_s = min(TRAJECTORY_S, dur)
    bar = tqdm(total=cap.size * n, desc=f"{ship.name} heading x speed map", disable=not progress)
    for i, h in enumerate(heads):
        for j, v in enumerate(speeds):
            model = with_condition(base, h, v * KNOT)
            for r in range(n):
                rec = (i * len(speeds) + j) * n + r
                waves = sea.components(int(mc["seed"]), rec)
                ds = simulate_six_dof(model, waves, dur, dt)
                if r == 0:
                    step[i, j] = _step_error(model, waves, ds, dt, check_s)
                e = record_events(ds, broach_deg=float(cfg["broach_deg"]), celerity=G / sea.modal_frequency,
                                  surf_tolerance=float(cfg["surf_tolerance"]), surf_min_s=float(cfg["surf_min_s"]),
                                  heading_deg=h)
                cap[i, j] += e["capsized"]
                bro[i, j] += e["broach"]
                bar.update()
    bar.close()
    alpha = float(mc.get("alpha", 0.05))

    def ci(k):
        lo, hi = np.zeros(k.shape), np.zeros(k.shape)
        for idx in np.ndindex(k.shape):
            c = binomtest(int(k[idx]), n).proportion_ci(confidence_level=1 - alpha, method="exact")
            lo[idx], hi[idx] = c.low, c.high
        return lo, hi

    dims = ("map_heading", "map_speed")
    out = xr.Dataset(coords={"map_heading": heads, "map_speed": speeds})
    for name, k in (("capsize", cap), ("broach", bro)):
        lo, hi = ci(k)
        out[f"map_{name}_count"] = (dims, k)
        out[f"map_{name}_probability"] = (dims, k / n)
        out[f"map_{name}_lower"] = (dims, lo)
        out[f"map_{name}_upper"] = (dims, hi)
    out["map_step_error"] = (dims, step)
    out.attrs.update(map_records=n, map_duration=dur, map_dt=dt, map_step_seconds=check_s, map_loading=mc["loading"],
                     map_kg=float(base.p[K.P_ZG]),
                     map_sea=f"{mc['sea']['spectrum']} Hs {float(mc['sea']['hs']):g} m", map_alpha=alpha,
                     map_interval="Clopper-Pearson (exact binomial)")
    return annotate(out)


def _step_error(model: SixDof, waves, ds: xr.Dataset, dt: float, seconds: float) -> float:
    """The step's check of a record ``ds`` simulated at ``dt``: its first ``seconds`` again at dt /
    ``REFINE``, the largest roll or yaw difference relative to the largest value (at least 1
    degree) [%] (``validation.ensemble.relative_trajectory_error``, the ensembles' measure)."""
    from stabflow.validation.ensemble import REFINE, relative_trajectory_error

    fine = simulate_six_dof(model, waves, seconds, dt / REFINE)
    return relative_trajectory_error(*(np.radians(np.column_stack([d["roll"].values, d["yaw"].values]))
                                       for d in (ds.sel(time=slice(None, seconds)), fine)), REFINE)


def _step_row(err: np.ndarray, what: str, dt: float, seconds: float):
    """A step-size row (consistency): the largest of ``err`` [%] (one per record, :func:`_step_error`)
    against the ensembles' trajectory tolerance (``validation.ensemble.TOL_TRAJECTORY``); FAIL with the
    reason where a record has none."""
    from stabflow.validation import run_check
    from stabflow.validation.ensemble import REFINE, TOL_TRAJECTORY

    name = (f"{what}, step size: roll and yaw over the first {seconds:g} s at dt = {dt:g} s vs dt = "
            f"{dt / REFINE:g} s ({np.size(err)} records): largest difference / largest value (at least 1 deg)")

    def value():
        if not np.all(np.isfinite(err)):
            raise ValueError(f"{int(np.sum(~np.isfinite(err)))} records without a step error")
        return float(np.max(err))

    return run_check(value, name, "%", f"the same records at dt / {REFINE} = {dt / REFINE:g} s", "consistency",
                     tolerance=TOL_TRAJECTORY)


def scenario_step_row(ds: xr.Dataset):
    """The scenario's step-size row from :func:`scenario`'s dataset (every loading and case)."""
    return _step_row(ds["step_error"].values, "paper 004's cases", float(ds.attrs["dt"]),
                     float(ds.attrs["step_seconds"]))


def map_step_row(pm: xr.Dataset):
    """The probability map's step-size row from :func:`probability_map`'s dataset (each cell's first
    record)."""
    return _step_row(pm["map_step_error"].values, "probability map, each cell's first record",
                     float(pm.attrs["map_dt"]), float(pm.attrs["map_step_seconds"]))
