"""Surface-pressure-integration reference for the FK + HS loads (paper 000 eq. 1).

F = -∫∫_{S_B(t)} p n dS over the hull mesh below the incident-wave surface, with
p = rho g (sum a cos(psi) E - z_e), E = exp(k (z_e - eta)) (Wheeler stretching) or E = 1
("decay off", LAMP-0 without the e^{kz} term). With ``waterline="planar"`` each component's
phase is linearised across the beam about the earth centreline Y = 0 at the vertex's own X,
cos(k_x X + k_y Y - w t + e) -> cos(psi0) - k_y Y sin(psi0), psi0 = k_x X - w t + e: the
volume-based model's straight waterline across each section (paper 000, steps 1-2), so the two
load models can be compared with and without that assumption. Triangles are clipped at the
wave surface (linear along edges) and pressure is taken linear between vertex values, with force
and moment integrated exactly for that: exact hydrostatics in calm water, and converging with
mesh refinement in waves. Pure numpy: it is the accuracy
reference and the speed baseline, not the production path.
"""

from __future__ import annotations

import numpy as np

from stabflow.dynamics import _kernels as K
from stabflow.geometry.frames import earth_vertices
from stabflow.constants import G


class PressureModel:
    """Pressure integration on a triangle mesh (body axes, origin midships on the baseline)."""

    def __init__(self, vertices, faces, rho, xg, zg, waves, heading_deg, speed, decay=False, waterline="exact"):
        if waterline not in ("exact", "planar"):
            raise ValueError(f"waterline must be 'exact' or 'planar', not {waterline!r}")
        self.waterline = waterline
        self.v = np.asarray(vertices, float)
        self.f = np.asarray(faces, int)
        self.rho, self.xg, self.zg = rho, xg, zg
        amp, omega, phase = (np.asarray(a, float) for a in waves)
        self.amp, self.phase = amp, phase
        self.k = omega**2 / G
        b = np.radians(heading_deg)
        self.kx, self.ky = self.k * np.cos(b), self.k * np.sin(b)
        self.we = omega - self.k * speed * np.cos(b)
        self.decay = decay

    def loads(self, t, h, phi, theta) -> np.ndarray:
        """(Fx, Fy, Fz, Mx, My, Mz) about G in earth axes [N, N m]."""
        ve = earth_vertices(self.v, phi, theta, h)
        ge = earth_vertices(np.array([[self.xg, 0.0, self.zg]]), phi, theta, h)[0]
        X, Y, Z = ve.T
        if self.amp.size:
            if self.waterline == "planar":
                psi0 = np.outer(X, self.kx) - self.we * t + self.phase
                comp = self.amp * (np.cos(psi0) - np.outer(Y, self.ky) * np.sin(psi0))
            else:
                psi = np.outer(X, self.kx) + np.outer(Y, self.ky) - self.we * t + self.phase
                comp = self.amp * np.cos(psi)
            eta = comp.sum(axis=1)
            if self.decay:
                dyn = (comp * np.exp(np.minimum(np.outer(Z - eta, self.k), 0.0))).sum(axis=1)
            else:
                dyn = eta
        else:
            eta = np.zeros_like(Z)
            dyn = eta
        p = self.rho * G * (dyn - Z)
        tri, pv = _wet_triangles(ve, self.f, Z - eta, p)
        n = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])  # outward area vector
        F = -(pv.mean(axis=1)[:, None] * n)
        r = tri - ge  # (nt, 3, 3) vertex lever arms
        # exact for linear p and r: int p r dA = A/12 (sum p_i r_i + sum p sum r)
        pr = ((pv[:, :, None] * r).sum(axis=1) + pv.sum(axis=1)[:, None] * r.sum(axis=1)) / 12.0
        M = -np.cross(pr, n)
        return np.concatenate([F.sum(axis=0), M.sum(axis=0)])


def simulate_pressure(model: PressureModel, p: np.ndarray, s0: np.ndarray, duration: float, dt: float):
    """The time domain's equations (:mod:`stabflow.dynamics.rigid_body`, parameter vector ``p``
    of :func:`stabflow.dynamics.model.parameters`) with pressure-integrated loads, Python RK4 from
    the state ``s0`` (N_STATE,). Returns (t [s], states (n, N_STATE))."""
    acc = np.empty(6)
    mq, r = np.empty((6, 6)), np.empty(6)

    def rhs(t, s):
        h = K._origin_height(s[K.S_Z], s[K.S_ROLL], s[K.S_PITCH], model.xg, model.zg)
        f = model.loads(t, h, s[K.S_ROLL], s[K.S_PITCH])
        K._accelerations(p, s, f, acc, mq, r)
        return np.concatenate([s[K.S_RATE:K.S_RATE + 6], acc, [0.0, 0.0]])

    n = int(round(duration / dt))
    s = np.asarray(s0, float).copy()
    out = np.empty((n + 1, K.N_STATE))
    out[0] = s
    for j in range(n):
        t = j * dt
        k1 = rhs(t, s)
        k2 = rhs(t + 0.5 * dt, s + 0.5 * dt * k1)
        k3 = rhs(t + 0.5 * dt, s + 0.5 * dt * k2)
        k4 = rhs(t + dt, s + dt * k3)
        prev = s[K.S_ROLL]
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        K._update_amplitude(prev, s)
        out[j + 1] = s
    return np.arange(n + 1) * dt, out


def _wet_triangles(ve, faces, d, p):
    """Clip every triangle to its wet part (d = z - eta < 0, linear along edges).

    Returns the wet triangles (m, 3, 3) and their vertex pressures (m, 3); pressure is zero where an
    edge crosses the wave surface. Orientation is kept (outward normals).
    """
    wet = d[faces] < 0
    nw = wet.sum(axis=1)
    tris = [ve[faces[nw == 3]]]
    press = [p[faces[nw == 3]]]
    for count in (1, 2):
        sel = nw == count
        if not sel.any():
            continue
        f = faces[sel]
        w = wet[sel]
        odd = np.argmax(w, axis=1) if count == 1 else np.argmin(w, axis=1)
        order = (odd[:, None] + np.arange(3)[None, :]) % 3
        f = np.take_along_axis(f, order, axis=1)
        A, B, C = ve[f[:, 0]], ve[f[:, 1]], ve[f[:, 2]]
        dA, dB, dC = d[f[:, 0]], d[f[:, 1]], d[f[:, 2]]
        tab = (dA / (dA - dB))[:, None]
        tac = (dA / (dA - dC))[:, None]
        Pab = A + tab * (B - A)
        Pac = A + tac * (C - A)
        z = np.zeros(len(f))
        if count == 1:
            tris.append(np.stack([A, Pab, Pac], axis=1))
            press.append(np.column_stack([p[f[:, 0]], z, z]))
        else:
            tris.append(np.stack([Pab, B, C], axis=1))
            press.append(np.column_stack([z, p[f[:, 1]], p[f[:, 2]]]))
            tris.append(np.stack([Pab, C, Pac], axis=1))
            press.append(np.column_stack([z, p[f[:, 2]], z]))
    return np.concatenate(tris), np.concatenate(press)
