"""CPU-seconds per simulated hour: volume-based FK+HS vs surface-pressure integration, one run.

DTMB 5415 (hull config stations, and a 21-station cut), one core, irregular-like wave of 220
components (Bretschneider SS8, stern quartering), RK4 dt = 0.05 s, with the planar and the curved
waterline across the sections. The pressure reference is timed over a short record and scaled. Run: python benchmarks/bench_timedomain.py
"""

import copy
import time
from pathlib import Path

import numpy as np

from stabflow.config import Ship, load_ship
from stabflow.dynamics import simulate
from stabflow.dynamics.model import config_coefficients
from stabflow.dynamics.model import initial_state, parameters
from stabflow.dynamics.pressure import PressureModel, simulate_pressure
from stabflow.geometry import Sections, build_hull
from stabflow.geometry.mesh import load_mesh
from stabflow.hydrostatics.statics import compute_statics
from stabflow.waves.spectra import bretschneider

ROOT = Path(__file__).resolve().parents[1]


def components(n=220, hs=11.5, tm=16.4, seed=1):
    rng = np.random.default_rng(seed)
    w = np.linspace(0.2, 1.6, n)
    dw = w[1] - w[0]
    w = w + rng.uniform(-0.5, 0.5, n) * dw
    return np.sqrt(2 * bretschneider(w, hs, tm) * dw), w, rng.uniform(-np.pi, np.pi, n)


def main():
    base = load_ship(ROOT / "config/ships/dtmb5415.yaml")
    W = components()
    dt = 0.05
    for n in (21, base.hull["stations"]):
        d = copy.deepcopy(base.data)
        d["hull"]["stations"] = n
        ship = Ship(base.name, base.path, d)
        hull = build_hull(ship)
        st = compute_statics(ship, hull)
        sec = Sections(hull)
        co = config_coefficients(ship, sec, st)  # the config constants (the ship file asks for Capytaine)
        simulate(sec, st, co, ship.rho, W, 45.0, 0.0, 10.0, dt)  # JIT warm-up
        t0 = time.process_time()
        ds = simulate(sec, st, co, ship.rho, W, 45.0, 0.0, 1800.0, dt)
        cpu = time.process_time() - t0
        print(f"volume-based, {n:3d} stations: {cpu / 0.5:8.3f} CPU-s per simulated hour "
              f"(30 min record incl. wave precomputation, roll std {float(ds['roll'].std()):.2f} deg)")
        simulate(sec, st, co, ship.rho, W, 45.0, 0.0, 10.0, dt, waterline="curved")  # JIT warm-up
        t0 = time.process_time()
        dc = simulate(sec, st, co, ship.rho, W, 45.0, 0.0, 1800.0, dt, waterline="curved")
        cpu_c = time.process_time() - t0
        print(f"  curved waterline, {n:3d} stations: {cpu_c / 0.5:8.3f} CPU-s per simulated hour, "
              f"{cpu_c / cpu:.2f} x the planar (roll std {float(dc['roll'].std()):.2f} deg)")
    tr = base.hull.get("transform", {})
    mesh = load_mesh(base.hull_file(), 1.0, False, tr.get("translate", [0, 0, 0]))
    pm = PressureModel(mesh.vertices, mesh.faces, base.rho, float(st.lcg), float(st.kg), W, 45.0, 0.0, decay=True)
    t0 = time.process_time()
    simulate_pressure(pm, parameters(co, base.rho, float(st.lcg), float(st.kg), 45.0), initial_state(sec, st), 5.0, dt)
    cpu_p = (time.process_time() - t0) / 5.0 * 3600.0
    print(f"pressure integration ({len(mesh.faces)} panels, decay on): {cpu_p:10.1f} CPU-s per simulated hour")
    print(f"ratio pressure / volume ({n} stations): {cpu_p / (cpu / 0.5):.0f} x")
    print("SimpleCode (published): 0.7 CPU-s per simulated hour; pipeline target 0.035")


if __name__ == "__main__":
    main()
