"""Regular-wave sweeps of the time-domain model: response amplitude vs lambda / L (paper 000 Figs 7-9).

Each wave is simulated from rest for ``n_periods`` encounter periods; the steady-state response is
the first harmonic at the encounter frequency, fitted by least squares over the last
``fit_periods`` periods (transients from the start have decayed by then). Heave is normalised by
the wave amplitude a, roll and pitch by the wave slope k a.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.io import annotate
from stabflow.constants import G
from stabflow.waves.synthesis import regular
from stabflow.dynamics.model import simulate


def first_harmonic(t: np.ndarray, x: np.ndarray, omega: float) -> tuple[float, float]:
    """Amplitude and phase [rad] of the x(t) component at ``omega`` (least squares with a mean)."""
    A = np.column_stack([np.cos(omega * t), np.sin(omega * t), np.ones_like(t)])
    c, s, _ = np.linalg.lstsq(A, x, rcond=None)[0]
    return float(np.hypot(c, s)), float(np.arctan2(-s, c))


def rao_sweep(sec, st, co, rho, lwl, ratios, steepness, heading_deg, speed, dt, n_periods=40, fit_periods=10,
              dphi_dzdt=False) -> xr.Dataset:
    """Heave / a, roll / (k a), pitch / (k a) over lambda / L for one condition."""
    beta = np.radians(heading_deg)
    rows = []
    for r in ratios:
        lam = r * lwl
        k = 2 * np.pi / lam
        w = np.sqrt(G * k)
        we = abs(w - k * speed * np.cos(beta))
        Te = 2 * np.pi / max(we, 1e-6)
        # at least 40 encounter periods and 3 roll decay times
        dur = max(n_periods * Te, 600.0)
        dur = min(dur, 3600.0)
        a = 0.5 * steepness * lam
        ds = simulate(sec, st, co, rho, regular(2 * a, lam), heading_deg, speed, dur, dt, dphi_dzdt=dphi_dzdt)
        t = ds["time"].values
        sel = t >= t[-1] - fit_periods * Te
        # heave [m]; roll and pitch from degrees to radians for the slope-normalised RAOs
        amps = [first_harmonic(t[sel], ds["heave"].values[sel], we)[0]]
        amps += [first_harmonic(t[sel], np.radians(ds[v].values[sel]), we)[0] for v in ("roll", "pitch")]
        rows.append((amps[0] / a, amps[1] / (k * a), amps[2] / (k * a), we, ds.attrs["capsized"]))
    arr = np.array(rows)
    out = xr.Dataset(
        {
            "heave_rao": ("wavelength_ratio", arr[:, 0], {"units": "1", "long_name": "heave amplitude / wave amplitude"}),
            "roll_rao": ("wavelength_ratio", arr[:, 1], {"units": "1", "long_name": "roll amplitude / wave slope k a"}),
            "pitch_rao": ("wavelength_ratio", arr[:, 2], {"units": "1", "long_name": "pitch amplitude / wave slope k a"}),
            "encounter_frequency": ("wavelength_ratio", arr[:, 3], {"units": "rad/s", "long_name": "encounter frequency"}),
            "capsized": ("wavelength_ratio", arr[:, 4].astype(np.int8), {"units": "1", "long_name": "1 if the run capsized"}),
        },
        coords={"wavelength_ratio": np.asarray(ratios, float)},
        attrs={"heading_deg": heading_deg, "speed": speed, "steepness": steepness, "dt": dt, "dphi_dzdt": int(dphi_dzdt)},
    )
    return annotate(out)
