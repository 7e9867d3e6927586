"""Numba kernels (private): volume-based FK + HS forces (paper 000 eqs 9, 11, 12, 15) and RK4.

Wave input is precomputed at the stations (3-DOF: their earth positions are known beforehand,
paper 000 section 3) on the half-step grid t_j = j dt / 2 as columns: elevation eta [m] and slope
along the direction of propagation S [-] (eta_x = cos(beta) S, eta_y = sin(beta) S for
long-crested waves of heading beta), then optionally the incident pressure's decay with depth and
the waterline's curvature across the sections, in one of four layouts (``_wave_layout``):

* (eta, S): paper 000's model;
* (eta, S, 0, eta_xixi): the curved waterline (``_curved_sections``);
* (eta, S, dphi_zt, S_h, S_hz, T_yy, U_yy, H_1, ..., H_6, W): the pressure decaying with
  depth (``dphi_dzdt``): the sections' area average of d2(phi0)/dz dt [m/s^2] in the vertical
  force, the area-averaged slope of the dynamic pressure head S_h [-] in the horizontal force, its
  first moment about the section's centroid S_hz [m] in the horizontal force's lever, T_yy [m]
  for the roll moment of the vertical pressure gradient's variation across the beam and U_yy [m]
  for the yaw moment of the horizontal gradient's, at the upright pose
  (``dynamics.model.SectionDecay``); then the heeled section's six sums sum a k w cos psi (H_1,
  H_2, H_3) and sum a k w sin psi (H_4, H_5, H_6) with the weights w of
  ``SectionDecay.heel_weights`` (``_fkhs``), and W [m^2], the linear vertical force's part that
  the wave's phase across the beam adds to the planar waterline (``_fkhs``);
* the same with eta_xixi last: both.

Sections are clipped exactly (``_section``) or, when tables are given (``tab.shape[0] > 0``), read
from per-station tables of area and first moments over (effective heel psi, waterline distance d)
built by the same exact clipping (``_build_tables``): the clipped area depends on the waterline
only through its normal angle psi = atan2(a, b) and distance d = c / |(a, b)|.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from stabflow.geometry.frames import _rotate
from stabflow.geometry._kernels import _section, _section_moments
from stabflow.hydrostatics._kernels import _station_sections


@njit(cache=True)
def _build_tables(ys, zs, npts, tab, lim):
    """Fill ``tab`` (nst, npsi, nu, 3) with (area, int y dA, int z dA) and ``lim`` (nst, npsi, 3)
    with the waterline distances at which the section starts and ends being wet and (nu - 1) / span, for psi on
    [0, pi] (npsi equal steps) and d on nu equal steps between those limits."""
    nst, npsi, nu, _ = tab.shape
    dpsi = np.pi / (npsi - 1)
    for i in range(nst):
        n = npts[i]
        for j in range(npsi):
            a = np.sin(j * dpsi)
            b = np.cos(j * dpsi)
            lo = np.inf
            hi = -np.inf
            for k in range(n):
                for sgn in (-1.0, 1.0):
                    p = sgn * a * ys[i, k] + b * zs[i, k]
                    lo = min(lo, p)
                    hi = max(hi, p)
            lim[i, j, 0] = lo
            lim[i, j, 1] = hi
            lim[i, j, 2] = (nu - 1) / (hi - lo)
            for m in range(nu):
                d = lo + (hi - lo) * m / (nu - 1)
                A, Sy, Sz = _section(ys[i], zs[i], n, a, b, d)
                tab[i, j, m, 0] = A
                tab[i, j, m, 1] = Sy
                tab[i, j, m, 2] = Sz


@njit(cache=True, inline="always")
def _atan_poly(x):
    """arctan(x) for |x| <= 1: Abramowitz & Stegun 4.4.49 polynomial (|error| < 2e-8 rad)."""
    x2 = x * x
    p = 0.0028662257
    p = p * x2 - 0.0161657367
    p = p * x2 + 0.0429096138
    p = p * x2 - 0.0752896400
    p = p * x2 + 0.1065626393
    p = p * x2 - 0.1420889944
    p = p * x2 + 0.1999355085
    p = p * x2 - 0.3333314528
    return x * (1.0 + p * x2)


@njit(cache=True, inline="always")
def _row(tab, lim, i, j, d, nu):
    """Linear read of table row (i, j) at waterline distance d: (area, int y dA, int z dA)."""
    u = (d - lim[i, j, 0]) * lim[i, j, 2]
    if u <= 0.0:
        return 0.0, 0.0, 0.0
    if u >= nu - 1:
        return tab[i, j, nu - 1, 0], tab[i, j, nu - 1, 1], tab[i, j, nu - 1, 2]
    k = int(u)
    r = u - k
    t0 = tab[i, j, k]
    t1 = tab[i, j, k + 1]
    return t0[0] + r * (t1[0] - t0[0]), t0[1] + r * (t1[1] - t0[1]), t0[2] + r * (t1[2] - t0[2])


@njit(cache=True, inline="always")
def _section_tab(tab, lim, i, psi, d):
    """Bilinear read of station ``i``'s table at (psi [rad], d [m]); symmetry for psi < 0."""
    npsi = tab.shape[1]
    nu = tab.shape[2]
    sgn = 1.0
    if psi < 0.0:
        psi = -psi
        sgn = -1.0
    f = psi * ((npsi - 1) / np.pi)
    j = min(int(f), npsi - 2)
    w = min(f - j, 1.0)
    a0, y0, z0 = _row(tab, lim, i, j, d, nu)
    a1, y1, z1 = _row(tab, lim, i, j + 1, d, nu)
    return a0 + w * (a1 - a0), sgn * (y0 + w * (y1 - y0)), z0 + w * (z1 - z0)


#: columns of the station wave with the pressure decay (module docstring), planar waterline
DECAY_COLUMNS = 14


@njit(cache=True, inline="always")
def _wave_layout(nq):
    """The columns of a station wave of ``nq`` columns (module docstring): (pressure decay on, column
    of eta_xixi or -1 for the planar waterline)."""
    if nq == 4:
        return False, 3
    if nq == DECAY_COLUMNS:
        return True, -1
    if nq == DECAY_COLUMNS + 1:
        return True, DECAY_COLUMNS
    return False, -1


@njit(cache=True)
def _fkhs(xs, dx, ys, zs, npts, tab, lim, rho, g, xg, zg, h, phi, theta, cb, sb, wave, out, work):
    """Volume-based FK + HS force and moments about G in earth axes.

    ``wave`` (nst, nq) holds the stations' wave in one of the layouts of the module docstring.
    ``out`` (6,) receives
    (Fx, Fy, Fz, Mx, My, Mz) [N, N m]. Per station (paper 000, steps 1-7): waterline height and
    effective heel (roll + lateral slope) → clipped section volume dV and centre b (from G, body
    axes) → dF = rho g dV w with w = (-eta_x, -eta_y, 1 + dphi_zt / g) (eq. 9) and dM = (R b) x dF
    (eqs 11, 12, 15). ``work`` (nst, 5) is scratch. Since w = S (-cos beta, -sin beta, 0) + (1 + dphi_zt / g) e_z, the sums
    P = sum b dV S and Q = sum b dV (1 + dphi_zt / g) are formed in body axes (b dV needs only the
    section's area and first moments, no division) and rotated once. With the pressure decay
    (the volume integral of the dynamic pressure's gradient, -rho g a grad(e^(k z) cos psi)): the
    vertical force takes 1 + dphi_zt / g; the horizontal force takes the area-averaged slope S_h for
    S, and its lever rises by S_hz / S_h above the centroid (P_z gains dV S_hz); and the vertical
    gradient's variation across the beam, cos psi = cos psi_0 - k sin(beta) y sin psi_0, adds the
    roll moment rho g dV sin(beta) T_yy (Q_y gains dV sin(beta) T_yy, T_yy = sum a k^2 Y sin psi_0);
    the horizontal gradient's, S = S_0 - sin(beta) y sum a k^2 e^(k z) cos psi_0 across the beam, the
    yaw moment rho g dV sin(beta) cos(beta) U_yy (U_yy = -sum a k^2 Y cos psi_0; without it Mz was
    2.5-21 % off pressure integration's at oblique headings), taken at the upright pose: heeled, the
    phase's variation across the beam also runs along body z (y' = y cos phi - z sin phi), whose
    roll moment (rho g k sin^2(beta) cos psi_0 sin phi cos phi int (y^2 - (z - z_G)^2) e^(k z) dA)
    neither this term nor T_yy carries; the y^2 half alone, put in through the rotated lever, changed
    the DSA's barge rate by -36 % and the trawler's by +69 %, more than the term it stood for (since
    2026-12-07 the heeled section's cross-beam terms in H_2, H_3 carry the exact phase's heel part
    to first order, ``SectionDecay.moments``' Gamma_B).
    Heeled, the decayed pressure's first moment across the beam, I_y = int y e^(k z) dA (earth y
    from G, z below the calm waterline), is not F int y dA: to first order in the heel the rotated
    calm section gives sin(phi) A (k Y - Z - zeta_c F) (A its area, zeta_c its centroid's height
    above G) and the wedges at the waterline, where e^(k z) = 1, their whole moment
    y_1 + sin(phi) A zeta_c (y_1 the section's earth first moment about G). This adds the roll
    moment -rho g dV sum a k cos psi (I_y - F y_1) = -rho g [y_1 H_1 + sin(phi) (H_3 - z_G H_2)] dx
    and the vertical force rho g sin(beta) sum a k^2 sin psi (I_y + y_o A F), y_o = -z_G sin(phi)
    the lateral distance from the body origin's vertical, where the station's wave is, to G:
    rho g sin(beta) [y_1 H_4 + sin(phi) (H_6 - z_G H_5)] dx, with its pitch moment (H_1 ... H_6 the
    columns 7-12 of the layout, ``SectionDecay.heel_weights``). Against pressure integration with
    decay on the barge held heeled by +-10 degree (lambda 40-120 m, 45-135 degree) the heel's part
    of the roll moment's first harmonic was 15-116 % off without them; the vertical force's 3-30 %
    and the pitch moment's up to 24 % of their upright first harmonics.
    The wave's phase varies across the beam, which the sections' planar waterline and the area
    averages above take as linear (the table's columns 3-6 and 8-9 carry their cross-beam
    remainders since 2026-12-07, ``waves.synthesis``): with the decay, column 13 carries the linear vertical force's
    remainder W = sum a X cos psi per unit length [m^2] (``SectionDecay.moments``' X: the
    waterline's sinc(k_y b / 2) and the decaying pressure's cos(k_y y) across each slice), added as
    rho g W dx on the section's centreline at x_i (nothing at a dry section), so it adds to the
    vertical force and the pitch moment only: at the heeled centroid its roll moment took the
    barge's heel part of the roll moment 12 % further from pressure integration's (beam waves,
    lambda 60 m, +-10 degree), whose planar and exact surfaces differ there by 81 %; not with the curved waterline,
    whose parabola across the beam already carries a part of it. In beam waves at twice the roll
    frequency the kernel's heave force (ship held) was +39.3 % (trawler), +18.2 % (DTMB 5415) and
    +12.0 % (barge) off pressure integration with decay on the exact surface without it, +0.3,
    +0.2 and +0.1 % with it; at 45 degree, lambda 21.7 m the trawler's +10.6 % became +0.5 %
    (2026-12-07; the box: exact, a test).
    Without the decay the dynamic pressure does not vary with depth and none of these arises; with
    the decay in the horizontal force alone, the roll excitation in beam seas would be far off
    (DTMB 5415, lambda 60 m: +98 % against pressure integration with decay). Returns the volume [m^3].
    """
    ct = np.cos(theta)
    st = np.sin(theta)
    cp = np.cos(phi)
    sp = np.sin(phi)
    ict = 1.0 / ct
    vol = 0.0
    vs = 0.0
    vq = 0.0
    px = 0.0
    py = 0.0
    pz = 0.0
    qx = 0.0
    qy = 0.0
    qz = 0.0
    vu = 0.0
    hx = 0.0
    hz = 0.0
    hm = 0.0
    use_tab = tab.shape[0] > 0
    use_dz = wave.shape[1] > 2
    decay, icurv = _wave_layout(wave.shape[1])
    use_curv = icurv >= 0
    nst = xs.shape[0]
    # curved-waterline terms (earth axes, from G), zero without them
    cfx = 0.0
    cfy = 0.0
    cmx = 0.0
    cmy = 0.0
    cmz = 0.0
    if use_curv:
        cfx, cfy, cmx, cmy, cmz = _curved_sections(xs, dx, ys, zs, npts, xg, zg, h, ct, st, cp, sp, cb, sb, wave,
                                                   icurv, work)
    elif use_tab:
        # branch-free pass over the stations (vectorised by LLVM): waterline normal angle and
        # distance, psi = phi - atan(ey / ct), d = c / sqrt(ct^2 + ey^2); slopes clipped to 45 deg
        for i in range(nst):
            ey = sb * wave[i, 1]
            x = min(max(ey * ict, -1.0), 1.0)
            work[i, 0] = phi - _atan_poly(x)
            work[i, 1] = (wave[i, 0] + st * xs[i] - h) / math.sqrt(ct * ct + ey * ey)
    if use_tab and not use_curv:
        for i in range(nst):
            A, Sy, Sz = _section_tab(tab, lim, i, work[i, 0], work[i, 1])
            work[i, 2] = A
            work[i, 3] = Sy
            work[i, 4] = Sz
    elif not use_curv:
        # exact clipping: the station walk of the hydrostatics, with the lateral slope of the wave
        for i in range(nst):
            work[i, 0] = sb * wave[i, 1]
        _station_sections(xs, ys, zs, npts, ct, st, cp, sp, h, wave[:, 0], work[:, 0], work[:, 2:])
    for i in range(nst):
        # dry sections add zeros
        S = wave[i, 3] if decay else wave[i, 1]
        A = work[i, 2]
        dV = A * dx[i]
        wz = 1.0 + wave[i, 2] / g if use_dz else 1.0
        if decay and not use_curv and A > 0.0:
            # the cross-beam correction rho g W dx on the centreline (docstring)
            cw = wave[i, 13] * dx[i]
            vq += cw
            qx += (xs[i] - xg) * cw
        bx = (xs[i] - xg) * dV
        by = work[i, 3] * dx[i]
        bz = (work[i, 4] - zg * A) * dx[i]
        vol += dV
        vs += dV * S
        vq += dV * wz
        px += bx * S
        py += by * S
        pz += bz * S
        if decay:
            pz += dV * wave[i, 4]
            vu += dV * wave[i, 6]
            # the heeled section's decayed moment across the beam (docstring)
            y1 = cp * by - sp * bz
            hx -= y1 * wave[i, 7] + sp * dx[i] * (wave[i, 9] - zg * wave[i, 8])
            dfz = sb * (y1 * wave[i, 10] + sp * dx[i] * (wave[i, 12] - zg * wave[i, 11]))
            hz += dfz
            hm -= (xs[i] - xg) * dfz
        qx += bx * wz
        qy += by * wz
        if decay:
            qy += dV * sb * wave[i, 5]
        qz += bz * wz
    f = rho * g
    ux = -cb
    uy = -sb
    out[0] = f * ux * vs
    out[1] = f * uy * vs
    out[2] = f * vq
    rpx, rpy, rpz = _rotate(px, py, pz, cp, sp, ct, st)
    rqx, rqy, rqz = _rotate(qx, qy, qz, cp, sp, ct, st)
    # (R P) x u + (R Q) x e_z
    out[3] = f * (-rpz * uy + rqy)
    out[4] = f * (rpz * ux - rqx)
    out[5] = f * (rpx * uy - rpy * ux) + f * sb * cb * vu
    if decay:
        out[2] += f * hz
        out[3] += f * hx
        out[4] += f * ct * hm
    if use_curv:
        out[0] += f * cfx
        out[1] += f * cfy
        out[3] += f * cmx
        out[4] += f * cmy
        out[5] += f * cmz
    return vol


@njit(cache=True)
def _curved_sections(xs, dx, ys, zs, npts, xg, zg, h, ct, st, cp, sp, cb, sb, wave, icurv, work):
    """The curved waterline across each section (option ``waterline="curved"``; stabflow's
    extension of paper 000, whose steps 1-3 take the wave as a plane across the section).

    ``wave`` (nst, nq) holds eta, S and in column ``icurv`` eta_xixi at the stations (xi along the
    direction of propagation). Across the section the wave departs from its tangent plane by
    delta(Y) = C2 Y^2 / 2 + O(Y^3) (C2 = sin^2(beta) eta_xixi; Y the earth lateral coordinate from
    the body origin). Two corrections to the planar model, both of the first order in the wave's
    cross-beam curvature C2 (the next, cubic terms in the layer made the mean GM worse against
    pressure integration: trawler, beam seas lambda = L, -2.5 % with them, -0.03 % without):

    * the thin layer between plane and surface over the waterline's wet chords across the hull
      (its area int delta dY / cos(theta) and first moments, lying on the plane), added to the
      section's area and first moments in ``work[:, 2:5]``; it is not clipped to the hull, so at
      deck immersion and bottom emergence it switches on and off with the chord (kept from
      emptying the section);
    * the horizontal pressure gradient's variation across the section (decay off,
      grad p = rho g grad eta): eta_y = sin(beta) S + C2 Y and eta_x = cos(beta) S + C_xy Y with
      C_xy = cos(beta) sin(beta) eta_xixi, integrated with the plane-clipped section's first and
      second moments.

    Returns the second part's (Fx, Fy, Mx, My, Mz) / (rho g) about G in earth axes [m^3, m^4].
    Measured against pressure integration (validation rows "GM in quartering waves"): the
    planar model's GM variation error of +25 % (barge) and +71 % (trawler, k_y B / 2 = 0.69)
    falls to -0.4 % and -4.1 %; in beam seas at lambda = L (trawler, k_y B / 2 = 1.0) from +229 %
    to -27 %, where the quadratic term no longer describes the wave across the beam.
    """
    ict = 1.0 / ct
    xG = ct * xg + st * cp * zg
    yG = -sp * zg
    zG0 = -st * xg + ct * cp * zg  # Z_G - h
    fx = 0.0
    fy = 0.0
    mx = 0.0
    my = 0.0
    mz = 0.0
    for i in range(xs.shape[0]):
        x = xs[i]
        eta = wave[i, 0]
        ey = sb * wave[i, 1]
        c2 = sb * sb * wave[i, icurv]
        cxy = cb * sb * wave[i, icurv]
        a = ct * sp - ey * cp
        b = ct * cp + ey * sp
        c = eta + st * x - h
        A, Sy, Sz, Iyy, Iyz, Izz, j0, j1, j2, j3 = _section_moments(ys[i], zs[i], npts[i], a, b, c)
        dA = 0.0
        dSy = 0.0
        dSz = 0.0
        if j0 > 0.0 and A > 0.0:
            # points of the line: (y, z) = (c (a, b) + s (b, -a)) / n2, with Y = Y0 + (ct / n2) s;
            # J_k = int s^k ds over the wet chords
            n2 = a * a + b * b
            y0 = -c * ey / n2
            yr = ct / n2
            iy2 = yr * (y0 * y0 * j0 + 2.0 * y0 * yr * j1 + yr * yr * j2)  # int Y^2 dY
            iy3 = yr * (y0 * y0 * y0 * j0 + 3.0 * y0 * y0 * yr * j1 + 3.0 * y0 * yr * yr * j2 + yr * yr * yr * j3)
            d0 = 0.5 * c2 * iy2  # int delta dY
            d1 = 0.5 * c2 * iy3  # int delta Y dY
            # y and z on the line, linear in Y: s = (Y - Y0) / yr
            ly1 = b / (yr * n2)
            lz1 = -a / (yr * n2)
            ly0 = c * a / n2 - ly1 * y0
            lz0 = c * b / n2 - lz1 * y0
            dA = d0 * ict
            dSy = (ly0 * d0 + ly1 * d1) * ict
            dSz = (lz0 * d0 + lz1 * d1) * ict
            if A + dA < 0.0:
                # the layer is not clipped to the hull: where it would empty the section (a flat
                # bottom just wet), keep the area at zero
                r = -A / dA
                dA *= r
                dSy *= r
                dSz *= r
        work[i, 2] = A + dA
        work[i, 3] = Sy + dSy
        work[i, 4] = Sz + dSz
        # the plane-clipped section in earth axes (body area): int Y, Y^2, X Y, (Z - h) Y dA
        iy = cp * Sy - sp * Sz
        yy_b = cp * Iyy - sp * Iyz  # int y Y dA
        zy_b = cp * Iyz - sp * Izz  # int z Y dA
        iyy = cp * yy_b - sp * zy_b
        ixy = ct * x * iy + st * (sp * yy_b + cp * zy_b)
        izy = -st * x * iy + ct * (sp * yy_b + cp * zy_b)
        w = dx[i]
        # the extra force density -(C_xy Y, C2 Y, 0) and its moment (r - r_G) x it
        zy = (izy - zG0 * iy) * w
        fx -= cxy * iy * w
        fy -= c2 * iy * w
        mx += c2 * zy
        my -= cxy * zy
        mz += (-c2 * (ixy - xG * iy) + cxy * (iyy - yG * iy)) * w
    return fx, fy, mx, my, mz


#: quadratic roll damping B44q is tabulated against the running roll amplitude (LAMP's quasi-steady
#: form, paper 004 eqs 17-19) at AMPLITUDE_STEP [rad] steps from 0 to 90 degrees; a constant
#: table is the plain quadratic damping
N_AMPLITUDES = 46
AMPLITUDE_STEP = math.pi / 2.0 / (N_AMPLITUDES - 1)

# positions in the parameter vector ``p`` of the RK4 kernels (built by
# ``stabflow.dynamics.model.ModelParameters.vector``): scalars, the B44q table, then the 3x3
# inertia tensor about G in body axes, the 6x6 added-mass and linear damping matrices of the
# generalized coordinates and the six free/held flags (all row-major)
P_RHO = 0
P_G = 1
P_XG = 2
P_ZG = 3
P_MASS = 4
P_COS_BETA = 5
P_SIN_BETA = 6
P_B44Q = 7
P_INERTIA = P_B44Q + N_AMPLITUDES
P_ADDED_MASS = P_INERTIA + 9
P_DAMPING = P_ADDED_MASS + 36
P_FREE = P_DAMPING + 36
N_PARAMETERS = P_FREE + 6

# the state: generalized coordinates q = (x, y, z of G in the earth frame moving with the mean
# speed and course [m]; roll phi, pitch theta, yaw psi [rad], Euler angles of R = Rz Ry Rx), their
# rates q' at positions S_RATE + j, and two memory states held constant within a step: the running
# roll amplitude S_AMP (the largest |phi| between the last two zero crossings) and S_PEAK, the
# largest |phi| since the last zero crossing [rad] (paper 004, procedure after eq 19)
S_X = 0
S_Y = 1
S_Z = 2
S_ROLL = 3
S_PITCH = 4
S_YAW = 5
S_RATE = 6
S_AMP = 12
S_PEAK = 13
N_STATE = 14


@njit(cache=True, inline="always")
def _b44q(p, amp):
    """Quadratic roll damping [N m s^2/rad^2] at the running roll amplitude ``amp`` [rad]: linear
    interpolation in the table (held at its ends)."""
    u = amp / AMPLITUDE_STEP
    if u >= N_AMPLITUDES - 1:
        return p[P_B44Q + N_AMPLITUDES - 1]
    k = int(u)
    r = u - k
    b0 = p[P_B44Q + k]
    return b0 + r * (p[P_B44Q + k + 1] - b0)


@njit(cache=True)
def _update_amplitude(prev_roll, s):
    """After a completed step from roll ``prev_roll``: at a zero crossing of roll the running
    amplitude becomes the largest |roll| since the previous crossing, else that largest value
    grows (paper 004, procedure after eq 19)."""
    a = abs(s[S_ROLL])
    if (prev_roll > 0.0 and s[S_ROLL] <= 0.0) or (prev_roll < 0.0 and s[S_ROLL] >= 0.0):
        s[S_AMP] = s[S_PEAK]
        s[S_PEAK] = a
    elif a > s[S_PEAK]:
        s[S_PEAK] = a


@njit(cache=True, inline="always")
def _origin_height(z, phi, theta, xg, zg):
    """Earth height [m] of the body origin (keel, midships) when G (body x = xg, z = zg, on the
    centreline) is at height z: z_G = h + (R r_G)_z = h - sin(theta) xg + cos(theta) cos(phi) zg."""
    return z + math.sin(theta) * xg - math.cos(theta) * math.cos(phi) * zg


@njit(cache=True)
def _generalized_system(p, s, f, mq, r):
    """Rigid-body equations about G as M(q) q'' = r(q, q', loads).

    ``f`` (6,) holds the loads of ``_fkhs`` (force and moment about G, in the heading frame: earth
    axes turned by the yaw psi). Newton for G in earth axes, m v_G' = F + m g_vec, and Euler in
    body axes, I w' + w x I w = M_b, with w = E(phi, theta) (phi', theta', psi') the body angular
    velocity of the ZYX Euler angles, projected on the generalized coordinates q (Kane's method:
    J^T of each equation, J = diag(1, 1, 1, E)); the added mass A and linear damping B act on q
    (seakeeping axes, constant), and the quadratic roll damping B44q(running amplitude) on phi'. Fills ``mq`` (6, 6) =
    J^T M_RB J + A and ``r`` (6,) = J^T (tau - M_RB J' q' - (0, w x I w)) - B q'
    - B44q phi'|phi'| e_phi.
    """
    m = p[P_MASS]
    phi = s[S_ROLL]
    th = s[S_PITCH]
    psi = s[S_YAW]
    pd = s[S_RATE + S_ROLL]
    td = s[S_RATE + S_PITCH]
    yd = s[S_RATE + S_YAW]
    cp = math.cos(phi)
    sp = math.sin(phi)
    ct = math.cos(th)
    st = math.sin(th)
    cy = math.cos(psi)
    sy = math.sin(psi)
    # force in earth axes (heading frame turned by psi) with gravity; moment in body axes,
    # M_b = (Ry Rx)^T M
    r[0] = cy * f[0] - sy * f[1]
    r[1] = sy * f[0] + cy * f[1]
    r[2] = f[2] - m * p[P_G]
    x1 = ct * f[3] - st * f[5]
    z1 = st * f[3] + ct * f[5]
    mb0 = x1
    mb1 = cp * f[4] + sp * z1
    mb2 = -sp * f[4] + cp * z1
    # w = E eta', eta = (phi, theta, psi); a = E' eta' (the velocity part of w')
    e00, e01, e02 = 1.0, 0.0, -st
    e10, e11, e12 = 0.0, cp, sp * ct
    e20, e21, e22 = 0.0, -sp, cp * ct
    w0 = pd - st * yd
    w1 = cp * td + sp * ct * yd
    w2 = -sp * td + cp * ct * yd
    a0 = -ct * td * yd
    a1 = -sp * pd * td + (cp * ct * pd - sp * st * td) * yd
    a2 = -cp * pd * td - (sp * ct * pd + cp * st * td) * yd
    I = p[P_INERTIA:P_INERTIA + 9]
    # body-axis torque left for the angular acceleration: M_b - w x I w - I a
    iw0 = I[0] * w0 + I[1] * w1 + I[2] * w2
    iw1 = I[3] * w0 + I[4] * w1 + I[5] * w2
    iw2 = I[6] * w0 + I[7] * w1 + I[8] * w2
    t0 = mb0 - (w1 * iw2 - w2 * iw1) - (I[0] * a0 + I[1] * a1 + I[2] * a2)
    t1 = mb1 - (w2 * iw0 - w0 * iw2) - (I[3] * a0 + I[4] * a1 + I[5] * a2)
    t2 = mb2 - (w0 * iw1 - w1 * iw0) - (I[6] * a0 + I[7] * a1 + I[8] * a2)
    E = ((e00, e01, e02), (e10, e11, e12), (e20, e21, e22))
    T = (t0, t1, t2)
    for i in range(3):
        r[3 + i] = E[0][i] * T[0] + E[1][i] * T[1] + E[2][i] * T[2]
    for i in range(6):
        for j in range(6):
            mq[i, j] = p[P_ADDED_MASS + 6 * i + j]
    for i in range(3):
        mq[i, i] += m
        for j in range(3):
            # (E^T I E)[i, j]
            acc = 0.0
            for k in range(3):
                for l in range(3):
                    acc += E[k][i] * I[3 * k + l] * E[l][j]
            mq[3 + i, 3 + j] += acc
    for i in range(6):
        acc = 0.0
        for j in range(6):
            acc += p[P_DAMPING + 6 * i + j] * s[S_RATE + j]
        r[i] -= acc
    r[S_ROLL] -= _b44q(p, s[S_AMP]) * pd * abs(pd)


@njit(cache=True)
def _accelerations(p, s, f, acc, mq, r):
    """Generalized accelerations q'' (6,) into ``acc`` for the loads ``f`` (``mq`` (6, 6) and ``r``
    (6,) are scratch). A held coordinate (``p[P_FREE + j] == 0``) gets the row q_j'' = 0; the
    6x6 system is solved by Gaussian elimination with partial pivoting (no allocation)."""
    _generalized_system(p, s, f, mq, r)
    _solve_free(p, mq, r, acc)


@njit(cache=True)
def _solve_free(p, mq, r, acc):
    """Solve ``mq`` q'' = ``r`` for the free coordinates into ``acc`` (held ones: q_j'' = 0);
    ``mq`` and ``r`` are overwritten."""
    for j in range(6):
        if p[P_FREE + j] == 0.0:
            for k in range(6):
                mq[j, k] = 0.0
            mq[j, j] = 1.0
            r[j] = 0.0
    for c in range(6):
        piv = c
        big = abs(mq[c, c])
        for i in range(c + 1, 6):
            if abs(mq[i, c]) > big:
                big = abs(mq[i, c])
                piv = i
        if piv != c:
            for k in range(6):
                t = mq[c, k]
                mq[c, k] = mq[piv, k]
                mq[piv, k] = t
            t = r[c]
            r[c] = r[piv]
            r[piv] = t
        for i in range(c + 1, 6):
            fac = mq[i, c] / mq[c, c]
            if fac != 0.0:
                for k in range(c, 6):
                    mq[i, k] -= fac * mq[c, k]
                r[i] -= fac * r[c]
    for i in range(5, -1, -1):
        v = r[i]
        for k in range(i + 1, 6):
            v -= mq[i, k] * acc[k]
        acc[i] = v / mq[i, i]


@njit(cache=True)
def _loads(xs, dx, ys, zs, npts, tab, lim, p, wave, s, f, work):
    """FK + HS loads ``f`` (6,) (``_fkhs``) for the state ``s``: body origin placed from G."""
    h = _origin_height(s[S_Z], s[S_ROLL], s[S_PITCH], p[P_XG], p[P_ZG])
    _fkhs(xs, dx, ys, zs, npts, tab, lim, p[P_RHO], p[P_G], p[P_XG], p[P_ZG], h, s[S_ROLL], s[S_PITCH],
          p[P_COS_BETA], p[P_SIN_BETA], wave, f, work)


@njit(cache=True)
def _rhs(xs, dx, ys, zs, npts, tab, lim, p, wave, fd, s, ds, f, work, mq, r):
    """State derivative of s = (q, q') (``S_*`` positions); p = parameter vector (``P_*``).

    The FK + HS loads are evaluated with the body origin placed from G's height (``_loads``) at
    the stations' tabulated wave (3-DOF: surge, sway and yaw held, so the stations' horizontal
    positions are the tabulated ones); ``fd`` (6,) is added to them: the body-linear diffraction
    force at this instant (:mod:`stabflow.dynamics.diffraction`; zeros without it)."""
    _loads(xs, dx, ys, zs, npts, tab, lim, p, wave, s, f, work)
    for q in range(6):
        f[q] += fd[q]
    for j in range(6):
        ds[j] = s[S_RATE + j]
    _accelerations(p, s, f, ds[S_RATE:S_RATE + 6], mq, r)
    ds[S_AMP] = 0.0
    ds[S_PEAK] = 0.0


@njit(cache=True, nogil=True)
def _simulate(xs, dx, ys, zs, npts, tab, lim, p, wtab, ftab, dt, n0, nsteps, s0, phi_cap, out, forces):
    """Fixed-step RK4 from step ``n0`` to ``nsteps``; ``wtab`` (2 nsteps + 1, nst, nq) on the
    half-step grid, ``ftab`` (2 nsteps + 1, 6) float64 the diffraction force on the same grid
    (:mod:`stabflow.dynamics.diffraction`), or a (0, 6) array without it.

    ``out`` (nsteps + 1, N_STATE) receives the state (row n0 is set to ``s0``); ``forces``
    (nsteps + 1, 6) the FK+HS loads (without the diffraction force), or pass a (0, 6) array to skip
    them. Stops when |phi| > phi_cap (capsize). Returns the index of the last step done; no
    allocation in the loop.
    """
    ns = N_STATE
    s = np.empty(ns)
    k1 = np.empty(ns)
    k2 = np.empty(ns)
    k3 = np.empty(ns)
    k4 = np.empty(ns)
    tmp = np.empty(ns)
    f = np.empty(6)
    mq = np.empty((6, 6))
    r = np.empty(6)
    work = np.empty((xs.shape[0], 5))
    keep = forces.shape[0] > 0
    for q in range(ns):
        s[q] = s0[q]
        out[n0, q] = s0[q]
    if keep:
        _loads(xs, dx, ys, zs, npts, tab, lim, p, wtab[2 * n0], s, f, work)
        for q in range(6):
            forces[n0, q] = f[q]
    zero = np.zeros(6)
    dif = ftab.shape[0] > 0
    for n in range(n0, nsteps):
        j = 2 * n
        f0 = ftab[j] if dif else zero
        f1 = ftab[j + 1] if dif else zero
        f2 = ftab[j + 2] if dif else zero
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j], f0, s, k1, f, work, mq, r)
        for q in range(ns):
            tmp[q] = s[q] + 0.5 * dt * k1[q]
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 1], f1, tmp, k2, f, work, mq, r)
        for q in range(ns):
            tmp[q] = s[q] + 0.5 * dt * k2[q]
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 1], f1, tmp, k3, f, work, mq, r)
        for q in range(ns):
            tmp[q] = s[q] + dt * k3[q]
        _rhs(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 2], f2, tmp, k4, f, work, mq, r)
        prev = s[S_ROLL]
        for q in range(ns):
            s[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q])
        _update_amplitude(prev, s)
        for q in range(ns):
            out[n + 1, q] = s[q]
        if keep:
            _loads(xs, dx, ys, zs, npts, tab, lim, p, wtab[j + 2], s, f, work)
            for q in range(6):
                forces[n + 1, q] = f[q]
        if abs(s[S_ROLL]) > phi_cap:
            return n + 1
    return nsteps


@njit(cache=True, parallel=True)
def _simulate_batch(xs, dx, ys, zs, npts, tab, lim, p, wtabs, ftabs, dt, nsteps, s0, phi_cap, out, last):
    """Records in parallel (``prange``): ``wtabs`` (nrec, 2 nsteps + 1, nst, nq) and ``ftabs``
    (nrec, 2 nsteps + 1, 6) the diffraction force (or (nrec, 0, 6) without it) → ``out``
    (nrec, nsteps + 1, N_STATE), ``last`` (nrec,) index of the last step done. Each record is the same
    computation as ``_simulate``, so results do not depend on the number of threads."""
    nofo = np.empty((0, 6))
    for r in prange(wtabs.shape[0]):
        last[r] = _simulate(xs, dx, ys, zs, npts, tab, lim, p, wtabs[r], ftabs[r], dt, 0, nsteps, s0, phi_cap, out[r],
                            nofo)


# --- 1-DOF roll in Gaussian excitation (the analytic-grade capsize case, issue 16) ------------------
# phi'' + 2 zeta w0 phi' + w0^2 r(phi) = w0^2 e(t): r = GZ / GM tabulated on 0 <= phi <= phi_max (odd),
# e the excitation as an equivalent static heel [rad], sampled with its derivative on the time grid
# and cubic-Hermite interpolated between samples (RK4's mid-step value and any off-grid time).
# Parameters: q = (w0 [rad/s], zeta [-], dphi of the table [rad]).


@njit(cache=True, nogil=True)
def _r1_excitation(rng, n, phi, chol_q, chol_s, out):
    """Exact discretisation of the linear filter state X = (e, e') at spacing dt: X_0 ~ N(0, Sigma),
    X_{i+1} = Phi X_i + w_i, w_i ~ N(0, Q), Q = Sigma - Phi Sigma Phi^T (Cholesky factors given;
    ``rng`` a numpy Generator, two standard normals per sample)."""
    z0 = rng.standard_normal()
    z1 = rng.standard_normal()
    out[0, 0] = chol_s[0, 0] * z0
    out[0, 1] = chol_s[1, 0] * z0 + chol_s[1, 1] * z1
    for i in range(1, n):
        z0 = rng.standard_normal()
        z1 = rng.standard_normal()
        a = out[i - 1, 0]
        b = out[i - 1, 1]
        out[i, 0] = phi[0, 0] * a + phi[0, 1] * b + chol_q[0, 0] * z0
        out[i, 1] = phi[1, 0] * a + phi[1, 1] * b + chol_q[1, 0] * z0 + chol_q[1, 1] * z1


@njit(cache=True, inline="always")
def _r1_restoring(x, tab, dphi):
    a = abs(x) / dphi
    i = min(int(a), len(tab) - 2)
    v = tab[i] + (a - i) * (tab[i + 1] - tab[i])
    return v if x >= 0 else -v


@njit(cache=True, inline="always")
def _r1_acc(x, v, e, q, tab):
    return -2.0 * q[1] * q[0] * v - q[0] * q[0] * (_r1_restoring(x, tab, q[2]) - e)


@njit(cache=True, inline="always")
def _r1_rk4(x, v, e0, em, e1, dt, q, tab):
    """One RK4 step of the roll equation with the excitation at the start, middle and end."""
    k1x = v
    k1v = _r1_acc(x, v, e0, q, tab)
    k2x = v + 0.5 * dt * k1v
    k2v = _r1_acc(x + 0.5 * dt * k1x, k2x, em, q, tab)
    k3x = v + 0.5 * dt * k2v
    k3v = _r1_acc(x + 0.5 * dt * k2x, k3x, em, q, tab)
    k4x = v + dt * k3v
    k4v = _r1_acc(x + dt * k3x, k4x, e1, q, tab)
    return (x + dt / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x),
            v + dt / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v))


@njit(cache=True, inline="always")
def _r1_hermite(exc, i, s, h):
    """Cubic Hermite between samples i and i + 1 (spacing h) at the fraction s."""
    s2 = s * s
    s3 = s2 * s
    return ((2 * s3 - 3 * s2 + 1) * exc[i, 0] + (s3 - 2 * s2 + s) * h * exc[i, 1]
            + (-2 * s3 + 3 * s2) * exc[i + 1, 0] + (s3 - s2) * h * exc[i + 1, 1])


@njit(cache=True, inline="always")
def _r1_exc_at(exc, dt, t):
    """Excitation at time t [s]."""
    i = min(int(t / dt), exc.shape[0] - 2)
    return _r1_hermite(exc, i, t / dt - i, dt)


@njit(cache=True, inline="always")
def _r1_grid_step(exc, k, dt, x, v, q, tab):
    """RK4 step k -> k + 1 on the grid (samples at the ends, Hermite at the middle)."""
    return _r1_rk4(x, v, exc[k, 0], _r1_hermite(exc, k, 0.5, dt), exc[k + 1, 0], dt, q, tab)


@njit(cache=True, nogil=True)
def _r1_substep(exc, dt, t0, tau, x, v, q, tab):
    """RK4 step of length tau from time t0 (off the grid)."""
    return _r1_rk4(x, v, _r1_exc_at(exc, dt, t0), _r1_exc_at(exc, dt, t0 + 0.5 * tau),
                   _r1_exc_at(exc, dt, t0 + tau), tau, q, tab)


@njit(cache=True, nogil=True)
def _r1_run(exc, dt, n0, n1, x, v, q, tab, cap, out):
    """Integrate from grid step n0 (state x, v) to n1, storing (roll, rate) in ``out`` (unless it has
    no rows); stops after the first step with |roll| > cap. Returns the last step done (a capsize on
    the very last step returns n1, like the 3-DOF ``_simulate``: a record counts as capsized when
    it stopped early)."""
    keep = out.shape[0] > 0
    if keep:
        out[n0, 0] = x
        out[n0, 1] = v
    for k in range(n0, n1):
        x, v = _r1_grid_step(exc, k, dt, x, v, q, tab)
        if keep:
            out[k + 1, 0] = x
            out[k + 1, 1] = v
        if abs(x) > cap:
            return k + 1
    return n1


@njit(cache=True, nogil=True)
def _r1_perturbed(exc, dt, base, base_last, n0, tc, x, v, q, tab, cap, ret, nmax):
    """Follow a perturbed state (x, v) at time tc (between grid steps n0 and n0 + 1) until it capsizes
    (|roll| > cap: returns 1), returns to the unperturbed solution ``base`` (distance
    sqrt(dx^2 + (dv / w0)^2) below ``ret`` at a grid step: returns 0) or reaches step ``nmax``
    (returns -1). Beyond ``base_last`` (the unperturbed run capsized) there is nothing to return to."""
    x, v = _r1_substep(exc, dt, tc, (n0 + 1) * dt - tc, x, v, q, tab)
    k = n0 + 1
    while True:
        if abs(x) > cap:
            return 1
        if k <= base_last:
            dx = x - base[k, 0]
            dv = (v - base[k, 1]) / q[0]
            if dx * dx + dv * dv < ret * ret:
                return 0
        if k >= nmax:
            return -1
        x, v = _r1_grid_step(exc, k, dt, x, v, q, tab)
        k += 1


@njit(cache=True, nogil=True)
def _r1_record_last(rng, nsteps, dt, phi, chol_q, chol_s, q, tab, cap, exc):
    """Brute force of one record from rest: its excitation into ``exc`` (the same draws as
    ``_r1_excitation``), then RK4 until capsize; returns the last step done (< nsteps: capsized)."""
    _r1_excitation(rng, nsteps + 1, phi, chol_q, chol_s, exc)
    return _r1_run(exc, dt, 0, nsteps, 0.0, 0.0, q, tab, cap, np.empty((0, 2)))


@njit(cache=True, inline="always")
def _crossbeam_ratios(u):
    """(sinc(u) - 1, R(u) - 1, P(u) - 1) for u = k_y B / 2 of a strip of breadth B across a wave of
    wave number k_y: sinc(u) = sin(u) / u is the strip's mean of cos(k_y y), R(u) = 3 (sin u -
    u cos u) / u^3 the ratio of int y sin(k_y y) dy to its linearisation k_y int y^2 dy and
    P(u) = 3 (u^2 sin u + 2 u cos u - 2 sin u) / u^3 that of int y^2 cos(k_y y) dy to int y^2 dy.
    By their Taylor series (Horner) below |u| 0.5, the last term there about 1e-15 of the first
    (no cancellation, no sine; R - 1 = sum_{n >= 2} (-1)^(n+1) 6 n u^(2n-2) / (2n+1)!,
    P - 1 = sum_{n >= 1} (-1)^n 3 u^(2n) / ((2n + 3) (2n)!)), else closed form from one sine and
    cosine."""
    x = u * u
    if x < 0.25:
        s = -x / 6.0 * (1.0 - x / 20.0 * (1.0 - x / 42.0 * (1.0 - x / 72.0 * (1.0 - x / 110.0 * (1.0 - x / 156.0 * (
            1.0 - x / 210.0))))))
        # R's terms' ratio -x n' / (n (2n+2)(2n+3)), n' = n + 1
        r = -x / 10.0 * (1.0 - x * 3.0 / (2.0 * 6.0 * 7.0) * (1.0 - x * 4.0 / (3.0 * 8.0 * 9.0) * (
            1.0 - x * 5.0 / (4.0 * 10.0 * 11.0) * (1.0 - x * 6.0 / (5.0 * 12.0 * 13.0) * (
                1.0 - x * 7.0 / (6.0 * 14.0 * 15.0))))))
        p = -0.3 * x * (1.0 - x * 5.0 / (7.0 * 3.0 * 4.0) * (1.0 - x * 7.0 / (9.0 * 5.0 * 6.0) * (
            1.0 - x * 9.0 / (11.0 * 7.0 * 8.0) * (1.0 - x * 11.0 / (13.0 * 9.0 * 10.0) * (
                1.0 - x * 13.0 / (15.0 * 11.0 * 12.0))))))
        return s, r, p
    sn = math.sin(u)
    cs = math.cos(u)
    return (sn / u - 1.0, 3.0 * (sn - u * cs) / (x * u) - 1.0,
            3.0 * (x * sn + 2.0 * u * cs - 2.0 * sn) / (x * u) - 1.0)


@njit(cache=True, inline="always")
def _slice_exp(e, j, rec, step, z, k):
    """e^(k z) at slice ``j`` (mid-depth ``z``) from the previous slice's ``e``: by the recurrence
    factor ``step`` (``rec``), reset to the exact value every 16 slices and near underflow."""
    if not rec or (j & 15) == 0 or e < 1e-290:
        return math.exp(z * k)
    return e * step


@njit(cache=True)
def _decay_moments(k, half_height, depth, area, offset, yy, yy_tilt, total, F, Z, Y, sbs, breadth, beam_wl, X, D,
                   flare, origin):
    """Fill F, Z, Y (nst, nc) with the sections' area averages of e^(k z), (z - z_c) e^(k z) and
    y^2 e^(k z) from their horizontal slices (``model.SectionDecay``: half heights (nst,), slice
    mid-depths, areas, centroid offsets, int y^2 dA and its upper-minus-lower halves (nst, ns), section
    areas (nst,)); a dry station (area 0) gets F = 1, Z = Y = 0. One pass over the slices per station
    and wave number (``SectionDecay.moments`` documents the slice integrals). With ``X`` (nb, nst, nc)
    and ``D`` (nb, 6, nst, nc), the cross-beam remainders for waves of heading sines ``sbs`` (nb,)
    (``SectionDecay.moments``), k_y = k sin(beta), b the calm waterline breadth ``beam_wl`` (nst,)
    and B each slice's breadth ``breadth`` (nst, ns): X = b (sinc(k_y b / 2) - 1) - k int e^(k z)
    (sinc(k_y B / 2) - 1) dA [m], then dF = int e^(k z) (sinc - 1) dA / A, dZ = int (z - z_c)
    e^(k z) (sinc - 1) dA / A [m], dY_r = dY_y - b^3 (R(k_y b / 2) - 1) / (12 k A) [m^2] and
    dY_y = int y^2 e^(k z) (R(k_y B / 2) - 1) dA / A [m^2] (``_crossbeam_ratios``), in this order
    along D's second axis, then the heeled section's: Gamma_B [m^2] and X + dF_y [m]
    (``SectionDecay.moments``; ``flare`` (nst,) the half breadth's slope at the calm waterline,
    ``origin`` (nst,) the body origin's height above it [m]); all 0 at a dry station and in head and
    following waves."""
    nst, ns = area.shape
    nc = k.shape[0]
    nb = X.shape[0]
    # the cross-beam slice sums for each heading: int e^(k z) (sinc - 1) dA, int z e^(k z) (sinc - 1) dA,
    # int y^2 e^(k z) (R - 1) dA (sinc, R of k_y B / 2), and the heeled section's
    # (``SectionDecay.moments``): int e^(k z) (1, z, z^2) sinc dA, int y^2 e^(k z) (1, z) R dA and
    # int y^2 e^(k z) (P - 1) dA
    acc = np.zeros((9, nb))
    xb, zb, yb, hs0, hs1, hs2, hr0, hr1, hp0 = acc[0], acc[1], acc[2], acc[3], acc[4], acc[5], acc[6], acc[7], acc[8]
    c = np.empty(ns)  # 3 (slice centroid - mid-height) / h of a station's slices
    for i in range(nst):
        a_i = total[i]
        if a_i <= 0.0:
            for n in range(nc):
                F[i, n] = 1.0
                Z[i, n] = 0.0
                Y[i, n] = 0.0
                for b in range(nb):
                    X[b, i, n] = 0.0
                    for q in range(6):
                        D[b, q, i, n] = 0.0
            continue
        h = half_height[i]
        zc = 0.0
        for j in range(ns):
            zc += area[i, j] * (depth[i, j] + offset[i, j])
        zc /= a_i
        for j in range(ns):
            c[j] = 3.0 * offset[i, j] / h
        # the slices are equally spaced (2 h apart): e^(k z_m) by a geometric recurrence, reset to
        # the exact value every 16 slices; otherwise (not by ``SectionDecay``'s construction) exp each
        even = True
        for j in range(1, ns):
            if abs(depth[i, j] - depth[i, 0] - 2.0 * h * j) > 1e-13 * (1.0 + abs(depth[i, 0])):
                even = False
        for n in range(nc):
            # a slice of half height h, area dA and centroid c above its middle z_m, its width linear
            # in z: int e^(k z) w dz = e^(k z_m) dA [s1(x) + 3 (c / h) s2(x)], x = k h,
            # s1 = sinh(x) / x, s2 = s1' = (x cosh x - sinh x) / x^2; its k-derivative,
            # int z e^(k z) w dz, is e^(k z_m) dA [z_m (s1 + 3 (c / h) s2) + h (s2 + 3 (c / h) s2')],
            # s2' = s1 - 2 s2 / x; int y^2 dA as a density linear across the slice:
            # int u e^(k u) du over (-h, h) = 2 h^2 s2, its slope (I_2 - I_1) / h^2
            x = h * k[n]
            if x < 1e-3:
                s1 = 1.0 + x * x / 6.0
                s2 = x / 3.0 + x * x * x / 30.0
                d2 = 1.0 / 3.0 + x * x / 10.0
            else:
                sh = math.sinh(x)
                s1 = sh / x
                s2 = (x * math.cosh(x) - sh) / (x * x)
                d2 = s1 - 2.0 * s2 / x
            f = 0.0
            first = 0.0
            y = 0.0
            # the recurrence only where its factor is finite and e^(k z_m) far from underflow (wave
            # numbers of centimetre waves; exp at every slice there)
            rec = even and 2.0 * h * k[n] < 700.0
            step = math.exp(2.0 * h * k[n]) if rec else 1.0
            e = 1.0
            for j in range(ns):
                e = _slice_exp(e, j, rec, step, depth[i, j], k[n])
                ea = e * area[i, j]
                w = s1 + c[j] * s2
                f += ea * w
                first += ea * (depth[i, j] * w + h * (s2 + c[j] * d2))
                y += e * (yy[i, j] * s1 + 2.0 * yy_tilt[i, j] * s2)
            if nb > 0:
                # the cross-beam integrals in a second pass over the slices (the same e^(k z_m) and
                # slice integrals), so that the pass above stays as fast without them
                acc[:, :] = 0.0
                e = 1.0
                for j in range(ns):
                    e = _slice_exp(e, j, rec, step, depth[i, j], k[n])
                    ea = e * area[i, j]
                    w = s1 + c[j] * s2
                    eaw = ea * w
                    eaz = ea * (depth[i, j] * w + h * (s2 + c[j] * d2))
                    eyy = e * (yy[i, j] * s1 + 2.0 * yy_tilt[i, j] * s2)
                    for b in range(nb):
                        if sbs[b] != 0.0:
                            ds, dr, dp = _crossbeam_ratios(0.5 * k[n] * sbs[b] * breadth[i, j])
                            xb[b] += eaw * ds
                            zb[b] += eaz * ds
                            yb[b] += eyy * dr
                            hs0[b] += eaw * (ds + 1.0)
                            hs1[b] += eaz * (ds + 1.0)
                            hs2[b] += eaz * depth[i, j] * (ds + 1.0)
                            hr0[b] += eyy * (dr + 1.0)
                            hr1[b] += eyy * depth[i, j] * (dr + 1.0)
                            hp0[b] += eyy * dp
            F[i, n] = f / a_i
            Z[i, n] = first / a_i - zc * F[i, n]
            Y[i, n] = y / a_i
            for b in range(nb):
                if sbs[b] == 0.0 or k[n] <= 0.0:  # head and following waves (and k = 0): none
                    X[b, i, n] = 0.0
                    for q in range(6):
                        D[b, q, i, n] = 0.0
                else:
                    bw = beam_wl[i]
                    ub = 0.5 * k[n] * sbs[b] * bw
                    ds, dr, dp = _crossbeam_ratios(ub)
                    X[b, i, n] = bw * ds - k[n] * xb[b]
                    df = xb[b] / a_i
                    D[b, 0, i, n] = df
                    D[b, 1, i, n] = zb[b] / a_i - zc * df
                    D[b, 2, i, n] = yb[b] / a_i - bw * bw * bw * dr / (12.0 * k[n] * a_i)
                    D[b, 3, i, n] = yb[b] / a_i
                    # the heeled section (``SectionDecay.moments``): with c = cos(k_y y) - 1,
                    # int c' y e^(k z) dA = -k_y^2 int y^2 R e^(k z) dA, int c'' ... = -k_y^2 int sinc ...
                    kn = k[n]
                    q2 = (kn * sbs[b]) ** 2
                    zo = origin[i]
                    i3 = bw * bw * bw / 12.0
                    wl_y2c = i3 * dp
                    wl_yc1 = -q2 * i3 * (dr + 1.0)
                    yc1 = -q2 * hr0[b]
                    zyc1 = -q2 * hr1[b]
                    c2 = -q2 * hs0[b]
                    zc2 = -q2 * hs1[b]
                    z2c2 = -q2 * hs2[b]
                    c_end = -2.0 * math.sin(0.5 * ub) ** 2  # cos(u_b) - 1
                    dmo = (kn * zb[b] + 2.0 * kn * zyc1 - z2c2 - kn * kn * hp0[b] + yc1 + kn * wl_y2c
                           - zo * (kn * xb[b] + kn * yc1 - zc2) + c_end * bw * (zo - 0.5 * bw * flare[i]))
                    dfy = zc2 - kn * yc1 + wl_yc1 - zo * c2
                    D[b, 4, i, n] = dmo + zo * dfy
                    D[b, 5, i, n] = X[b, i, n] + dfy


@njit(cache=True)
def _lagrange_nodes(k, h, tab, out):
    """Fill ``out`` (nq, nst, nc) with the four-point Lagrange (cubic) interpolant at the wave
    numbers ``k`` (nc,) >= 0 [1/m] of ``tab`` (nn, nq, nst), tabulated at k = j ``h``, j = 0 ... nn - 1
    (nn >= 4): nodes j0 ... j0 + 3 with j0 = floor(k / h) - 1 (0 in the first interval, nn - 4 past
    the last but one), exact for cubics (to round-off) and constants exactly: written in differences
    from the second node, whose weight is 1 - w0 - w2 - w3 (``model.SectionDecay.tabulated``)."""
    nn, nq, nst = tab.shape
    for n in range(k.shape[0]):
        u = k[n] / h
        j0 = min(max(int(math.floor(u)) - 1, 0), nn - 4)
        t = u - j0
        w0 = -(t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0
        w2 = -t * (t - 1.0) * (t - 3.0) / 2.0
        w3 = t * (t - 1.0) * (t - 2.0) / 6.0
        for q in range(nq):
            for i in range(nst):
                # in differences from the second node: a constant (a dry station's F = 1, its other
                # moments 0) comes out exactly, not to the weights' round-off
                b = tab[j0 + 1, q, i]
                out[q, i, n] = b + (w0 * (tab[j0, q, i] - b) + w2 * (tab[j0 + 2, q, i] - b)
                                    + w3 * (tab[j0 + 3, q, i] - b))
