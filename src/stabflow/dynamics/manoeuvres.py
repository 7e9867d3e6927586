"""Standard manoeuvres and events of 6-DOF records (issue 17).

Turning circle: advance and transfer at 90 degree heading change, tactical diameter (transfer at
180 degree), steady turning diameter; zig-zag: first and second overshoot angles; events of a
record in waves: capsize, broach (heading deviation beyond a limit with the rudder at its stop)
and surf-riding (speed along the waves locked to their celerity for longer than a set time).
Trajectories are in the earth frame: X = surge + U t along the mean course, Y = sway (to port).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.dynamics import _kernels_6dof as K6


def _crossing_time(t, y, level):
    """First time ``y`` (increasing from y[0] < level) reaches ``level`` (linear interpolation), or None."""
    idx = np.nonzero(y >= level)[0]
    if not len(idx) or idx[0] == 0:
        return None
    i = idx[0]
    return t[i - 1] + (level - y[i - 1]) / (y[i] - y[i - 1]) * (t[i] - t[i - 1])


def trajectory(ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """Earth position of G (X along the mean course, Y to port) [m] of a 6-DOF record."""
    return ds["surge"].values + ds.attrs["speed"] * ds["time"].values, ds["sway"].values


def turning_circle(ds: xr.Dataset) -> dict:
    """Advance, transfer [m] at 90 degree of heading change, tactical diameter [m] at 180 degree
    (transfer then) and the steady turning diameter [m] (2 V / |r| at the record's end), with the
    speed loss [-] at the end, for a turn to either side started at t = 0. NaN where the heading
    change is not reached (the row says so; the record was too short or the ship did not turn)."""
    t = ds["time"].values
    X, Y = trajectory(ds)
    turn = np.abs(np.unwrap(np.radians(ds["yaw"].values)) - np.radians(float(ds["yaw"][0])))
    out = {}
    for name, ang in (("advance", 90.0), ("tactical", 180.0)):
        tc = _crossing_time(t, np.degrees(turn), ang)
        if tc is None:
            out[name] = out[f"{name}_transfer"] = np.nan
            continue
        out[name] = float(np.interp(tc, t, X) - X[0])
        out[f"{name}_transfer"] = float(abs(np.interp(tc, t, Y) - Y[0]))
    speed = float(np.hypot(ds["u"][-1], ds["v"][-1]))
    r = abs(np.radians(float(ds["yaw_rate"][-1])))
    return {"advance": out["advance"], "transfer": out["advance_transfer"], "tactical_diameter": out["tactical_transfer"],
            "steady_diameter": 2.0 * speed / r if r > 0 else np.inf,
            "speed_loss": 1.0 - speed / ds.attrs["speed"]}


def zigzag_overshoots(ds: xr.Dataset, switch_deg: float) -> tuple[float, float]:
    """First and second overshoot angles [degree] of a zig-zag started to starboard (heading
    decreasing): how far the heading goes beyond -switch after the first helm reversal, and beyond
    +switch after the second. NaN if the record ends before the overshoot is complete."""
    psi = ds["yaw"].values - float(ds["yaw"][0])
    # helm reversals: the heading passes -switch (first) and then +switch (second)
    i1 = np.nonzero(psi <= -switch_deg)[0]
    if not len(i1):
        return np.nan, np.nan
    i2 = np.nonzero(psi[i1[0]:] >= switch_deg)[0]
    first_seg = psi[i1[0]:i1[0] + i2[0]] if len(i2) else None
    first = float(-first_seg.min() - switch_deg) if first_seg is not None else np.nan
    if not len(i2):
        return first, np.nan
    j = i1[0] + i2[0]
    i3 = np.nonzero(psi[j:] <= -switch_deg)[0]
    second = float(psi[j:j + i3[0]].max() - switch_deg) if len(i3) else np.nan
    return first, second


def record_events(ds: xr.Dataset, *, broach_deg: float, celerity: float, surf_tolerance: float,
                  surf_min_s: float, heading_deg: float) -> dict:
    """Events of a 6-DOF record in waves, never NaN: ``capsized`` (0/1) and its time, ``broach`` (0/1:
    heading deviation from the autopilot's course beyond ``broach_deg`` while the rudder is at its
    stop) and its first time, ``surf_riding`` (0/1: the speed of G along the wave direction within
    ``surf_tolerance`` x ``celerity`` of the celerity [m/s] for at least ``surf_min_s`` [s]) with its
    longest duration [s]. Times are -1 where the event did not happen."""
    t = ds["time"].values
    dt = float(ds.attrs["dt"])
    capsized = int(ds.attrs["status"] == K6.CAPSIZED)
    dev = ds["yaw"].values - float(ds.attrs.get("course_deg", 0.0))
    dev = np.abs((dev + 180.0) % 360.0 - 180.0)  # wrapped: a ship that turned full circle is back on course
    at_stop = np.abs(ds["rudder"].values) >= float(ds.attrs.get("max_rudder_deg", 35.0)) - 1e-6
    b = np.nonzero((dev > broach_deg) & at_stop)[0]
    beta = np.radians(heading_deg)
    xd = ds.attrs["speed"] + np.gradient(ds["surge"].values, dt)
    yd = np.gradient(ds["sway"].values, dt)
    along = xd * np.cos(beta) + yd * np.sin(beta)
    locked = np.abs(along - celerity) <= surf_tolerance * celerity
    longest, run = 0, 0
    for v in locked:
        run = run + 1 if v else 0
        longest = max(longest, run)
    surf = longest * dt >= surf_min_s
    first_surf = -1.0
    if surf:
        run = 0
        for i, v in enumerate(locked):
            run = run + 1 if v else 0
            if run * dt >= surf_min_s:
                first_surf = float(t[i - run + 1])
                break
    return {"capsized": capsized, "capsize_time": float(t[-1]) if capsized else -1.0,
            "broach": int(len(b) > 0), "broach_time": float(t[b[0]]) if len(b) else -1.0,
            "surf_riding": int(surf), "surf_riding_time": first_surf, "surf_riding_longest": float(longest * dt)}
