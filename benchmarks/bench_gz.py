"""Time a 0-180 deg GZ curve at 1 deg for DTMB 5415: stabflow vs navaltoolbox, same run.

Run: python benchmarks/bench_gz.py
"""

import time
from pathlib import Path

import numpy as np

from stabflow.config import load_ship
from stabflow.geometry import Sections, build_hull
from stabflow.hydrostatics.statics import gz_curve, loading, particulars
from stabflow.validation.statics import navaltoolbox_gz

ROOT = Path(__file__).resolve().parents[1]


def best_of(fn, n):
    times = []
    for _ in range(n):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def main():
    ship = load_ship(ROOT / "config/ships/dtmb5415.yaml")
    hull = build_hull(ship)
    sec = Sections(hull)
    ld = loading(ship, sec)
    particulars(sec, ld["volume"], ld["lcg"], ld["kg"], ship.rho)  # warm the JIT cache
    heels = np.arange(0.0, 180.5, 1.0)
    gz_curve(sec, ld["volume"], ld["lcg"], ld["kg"], heels)
    t_sf, ours = best_of(lambda: gz_curve(sec, ld["volume"], ld["lcg"], ld["kg"], heels), 5)
    t_nt, ref = best_of(lambda: navaltoolbox_gz(ship, ld["volume"], ld["lcg"], ld["kg"], heels), 1)
    print(f"DTMB 5415, {len(heels)} heels 0-180 deg, free trim, {hull.sizes['station']} stations")
    print(f"stabflow     : {t_sf * 1e3:9.1f} ms  (best of 5)")
    print(f"navaltoolbox : {t_nt * 1e3:9.1f} ms")
    print(f"speed-up     : {t_nt / t_sf:9.1f} x")
    k = heels <= 60
    print(f"max |GZ diff| 0-60 deg: {np.abs(ours['gz'].values[k] - ref[k]).max():.4f} m")


if __name__ == "__main__":
    main()
