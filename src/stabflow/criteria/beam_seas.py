"""The ship without way in beam seas, by the linear frequency-domain solution of the time domain's own
equations: the physics of the second-generation dead-ship (level 2) and excessive-acceleration
(levels 1-2) checks, sea state by sea state of a scatter table.

Model
    The 3-DOF equations of the ensembles (heave of G, roll, pitch) linearised about the calm-water
    equilibrium, [-w^2 (M + A) + i w B + C] X = F, at zero speed in beam waves (heading 90 degree):
    F the first harmonic of the volume-based Froude-Krylov loads on the ship held at equilibrium
    (:func:`stabflow.dynamics.linear.fk_excitation`), C the restoring matrix
    (:func:`stabflow.dynamics.linear.stiffness_matrix`). The excitation is computed on a coarse
    frequency grid and interpolated (cubic spline of its real and imaginary parts) to a fine one that
    resolves the roll resonance; C and M do not depend on frequency.

Quadratic roll damping
    By stochastic (statistical) linearisation: for a zero-mean Gaussian roll velocity of standard
    deviation s, the linear coefficient that best replaces B44q p|p| in the mean-square sense is
    E[p^2 |p|] / E[p^2] B44q = sqrt(8 / pi) s B44q (E|p|^3 = 2 sqrt(2 / pi) s^3 for a Gaussian), so
    B44_eq = B44 + sqrt(8 / pi) s B44q, solved by (relaxed) fixed-point iteration with the response.

    The amplitude-dependent B44q of Ikeda's components is read at sqrt(2) sigma_roll, the amplitude of
    a harmonic roll of the same variance (an approximation: the time domain reads it at the running
    peak amplitude, which is Rayleigh distributed).

Steady wind (dead ship)
    The ship rolls about the heel phi_w of the steady wind lever of the IS Code weather criterion
    (its phi0, 2.3), where the restoring is W GZ'(phi_w) instead of W GM; with no windage in the ship
    config the wind heel is left out (phi_w = 0) and the results say so; a wind lever above GZmax
    (no equilibrium, phi0 infinite) or a heel beyond the failure angle makes the rate infinite. Roll is
    Gaussian about phi_w; failure is an excursion beyond the failure angle phi_f on either side, at
    the rate (Rice)

        nu = nu0 [exp(-(phi_f - phi_w)^2 / 2 m0) + exp(-(phi_f + phi_w)^2 / 2 m0)],  nu0 = sqrt(m2 / m0) / 2 pi.

Lateral acceleration
    At a height h above G, in body axes, a_y = g sin(phi) - h phi'' (gravity's component along the
    heeled deck plus the point's acceleration about the roll axis through G; sway is not a degree of
    freedom of the model), in the frequency domain (g + w^2 h) X_roll, for the upright ship without
    wind (zero mean). Its exceedance rate of a level a on either side is 2 nu+(a) by Rice's formula.

Waves and bands
    Deep water (the wave length of a frequency is 2 pi g / w^2). Each sea state's spectrum is cut
    where it falls below 1e-3 of its peak, as the ensembles' seaways (paper 004 eqs 23, 28;
    :func:`stabflow.criteria.dsa.band_spectrum`): the frequency-domain results describe the sea the
    time domain simulates. A sea state whose band reaches beyond the model's frequency grid is an
    error, never silently cut.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import xarray as xr
from scipy.interpolate import CubicSpline

from stabflow.constants import G
from stabflow.criteria.dsa import band_spectrum, moments, rice_log10_rate, rice_rate, spectrum_band

#: sqrt(8 / pi): the stochastic linearisation factor of p |p| for a Gaussian p
STOCHASTIC = math.sqrt(8.0 / math.pi)
#: ln 10, for sums of rates kept as log10
LN10 = math.log(10.0)
#: wave steepness H / lambda of the regular waves whose FK first harmonic gives the excitation
EXCITATION_STEEPNESS = 1.0 / 1000.0


@dataclasses.dataclass
class BeamSeaModel:
    """Linear beam-sea response of one ship at zero speed on a fine frequency grid.

    Attributes
    ----------
    omega : fine frequency grid [rad/s].
    force : complex generalized FK forces per unit wave amplitude (len(omega), 3) [N/m, N m/m, N m/m].
    stiffness : 3 x 3 restoring matrix [N/m, N/rad, N m/m, N m/rad].
    mass : diagonal generalized mass + added mass (3,) [kg, kg m^2, kg m^2].
    damping : linear damping (3,) [N s/m, N m s/rad, N m s/rad].
    b44q : quadratic roll damping on the kernels' amplitude grid [N m s^2/rad^2].
    amplitudes : that grid [rad].
    roll_period : undamped natural roll period [s].
    """

    omega: np.ndarray
    force: np.ndarray
    stiffness: np.ndarray
    mass: np.ndarray
    damping: np.ndarray
    b44q: np.ndarray
    amplitudes: np.ndarray
    roll_period: float

    def impedance(self, b44: float | None = None, c44: float | None = None) -> np.ndarray:
        """-w^2 (M + A) + i w B + C (len(omega), 3, 3) with the roll damping ``b44`` [N m s/rad] and
        restoring ``c44`` [N m/rad] (defaults: the model's B44 and upright C44)."""
        B = self.damping.astype(complex)
        C = self.stiffness.astype(complex).copy()
        if b44 is not None:
            B[1] = b44
        if c44 is not None:
            C[1, 1] = c44
        w = self.omega[:, None, None]
        return -(w**2) * np.diag(self.mass) + 1j * w * np.diag(B) + C

    def rao(self, b44: float | None = None, c44: float | None = None) -> np.ndarray:
        """Complex (heave, roll, pitch) per unit wave amplitude (len(omega), 3) by the full solve with
        the impedance of :meth:`impedance`."""
        return np.linalg.solve(self.impedance(b44, c44), self.force[..., None])[..., 0]

    def roll_rao(self, b44: float | None = None, c44: float | None = None) -> np.ndarray:
        """The roll column of :meth:`rao`, by Cramer's rule: only Z[1, 1] depends on b44 and c44, and
        it is not in the numerator (the roll column replaced by F), so
        X_roll = N / (D0 + (i w (b44 - B44) + (c44 - C44)) M11) with N, D0 (at the model's B44, C44)
        and the heave-pitch minor M11 computed once: the damping iteration costs no solve."""
        N, D0, M11 = self._cramer
        db = 0.0 if b44 is None else b44 - self.damping[1]
        dc = 0.0 if c44 is None else c44 - self.stiffness[1, 1]
        return N / (D0 + (1j * self.omega * db + dc) * M11)

    @functools.cached_property
    def _cramer(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        Z = self.impedance()
        Zr = Z.copy()
        Zr[:, :, 1] = self.force
        keep = [0, 2]
        return np.linalg.det(Zr), np.linalg.det(Z), np.linalg.det(Z[:, keep][:, :, keep])

    def b44q_at(self, amplitude: float) -> float:
        """Quadratic roll damping [N m s^2/rad^2] at the roll amplitude ``amplitude`` [rad]."""
        return float(np.interp(amplitude, self.amplitudes, self.b44q))


def beam_sea_model(model, w_min: float = 0.05, w_max: float = 7.0, n_coarse: int = 140,
                   dw: float = 0.0005) -> BeamSeaModel:
    """The linear beam-sea model of an ensemble engine model (:func:`stabflow.statistics.ensemble.build_model`
    at zero speed): the FK excitation at ``n_coarse`` frequencies on [w_min, w_max] [rad/s],
    interpolated to a grid of step ``dw`` [rad/s]."""
    from stabflow.dynamics import _kernels as K
    from stabflow.dynamics.linear import KernelLoads, fk_excitation, stiffness_matrix
    from stabflow.hydrostatics.statics import equilibrium
    from stabflow.waves.synthesis import regular

    st, sec, co = model.st, model.sec, model.co
    V, lcg, kg = float(st["volume"]), float(st["lcg"]), float(st["kg"])
    h0, th0, _ = equilibrium(sec, V, lcg, kg)
    C = stiffness_matrix(sec, model.ship.rho, lcg, kg, h0, th0)
    coarse = np.linspace(w_min, w_max, n_coarse)
    F = np.empty((n_coarse, 3), complex)
    for i, w in enumerate(coarse):
        lam = 2 * math.pi * G / w**2
        amp = 0.5 * EXCITATION_STEEPNESS * lam
        loads = KernelLoads(sec, model.ship.rho, lcg, kg, regular(2 * amp, lam), 90.0, 0.0, model.decay)
        F[i] = fk_excitation(loads, h0, th0, w) / amp
    if model.diffraction is not None:
        F += diffraction_excitation(model, h0, th0, coarse)
    fine = np.arange(w_min, w_max + 0.5 * dw, dw)
    force = CubicSpline(coarse, F.real, axis=0)(fine) + 1j * CubicSpline(coarse, F.imag, axis=0)(fine)
    return BeamSeaModel(fine, force, C, np.array([co.mass + co.a33, co.i44 + co.a44, co.i55 + co.a55]),
                        np.array([co.b33, co.b44, co.b55]), co.b44q_profile(),
                        np.radians(np.linspace(0.0, 90.0, K.N_AMPLITUDES)), co.natural_period("roll"))


def diffraction_excitation(model, h0: float, th0: float, omega) -> np.ndarray:
    """Generalized diffraction forces (n, 3) (heave of G, roll, pitch) per unit wave amplitude of the
    ``model``'s diffraction force (:mod:`stabflow.dynamics.diffraction`, heading 90 degree) at the
    wave frequencies ``omega`` [rad/s], the ship at its equilibrium (origin height h0 [m], trim th0
    [rad]): the same force the time domain adds to its loads, in this module's e^(i w t) convention
    (the complex conjugate of Capytaine's e^(-i w t) amplitude)."""
    from stabflow.dynamics.diffraction import generalized

    if abs(model.diffraction.heading_deg - 90.0) > 1e-9:
        raise ValueError(f"the beam-sea model needs the diffraction force at 90 deg, not {model.diffraction.heading_deg}")
    return generalized(model.diffraction.transfer(omega), float(model.st["lcg"]), float(model.st["kg"]), h0, th0)


def linearised_response(bsm: BeamSeaModel, S: np.ndarray, c44: float | None = None, tol: float = 1e-6,
                        max_iter: int = 200) -> tuple[np.ndarray | None, float]:
    """Roll RAO per unit wave amplitude (complex, on ``bsm.omega``) in the sea of spectrum ``S``
    [m^2 s] with the stochastically linearised roll damping, and that damping B44_eq [N m s/rad];
    (None, NaN) when the iteration (relaxed by 1/2) does not converge."""
    b = bsm.damping[1]
    w = bsm.omega
    for _ in range(max_iter):
        X = bsm.roll_rao(b, c44)
        m0, m2 = moments(w, np.abs(X) ** 2 * S)
        new = bsm.damping[1] + STOCHASTIC * math.sqrt(m2) * bsm.b44q_at(math.sqrt(2 * m0))
        if abs(new - b) <= tol * new:
            return bsm.roll_rao(new, c44), new
        b = 0.5 * (b + new)
    return None, math.nan


def beam_sea_cells(bsm: BeamSeaModel, p: xr.DataArray, phi_f_deg: float, phi_w_deg: float, c44_heeled: float | None,
                   crew_height: float, levels) -> xr.Dataset:
    """Dead-ship roll and lateral acceleration in every sea state (hs, tz) of the scatter table ``p``.

    Parameters
    ----------
    phi_f_deg : failure angle [degree] (NaN: rates NaN); phi_w_deg : heel under the steady wind
        [degree] (0: none; infinite: no equilibrium under the wind, rates infinite).
    c44_heeled : roll restoring W GZ'(phi_w) [N m/rad] about the wind heel (None: upright C44).
    crew_height : height of the crew location above G [m].
    levels : lateral-acceleration levels [m/s^2] of the exceedance rates.

    Sea states whose probability is not positive (or NaN) are skipped (NaN).

    Returns
    -------
    Dataset over (hs, tz): ``ds_roll_std`` [degree], ``ds_roll_period`` [s] (mean zero-crossing period
    2 pi sqrt(m0 / m2)), ``ds_b44_eq`` [N m s/rad], ``ds_failure_rate`` [1/s]; ``ea_acceleration_std``
    [m/s^2] (upright, no wind); and over (ea_level, hs, tz) ``ea_exceedance_rate`` [1/s] of |a_y| > level.
    """
    w = bsm.omega
    lv = np.asarray(levels, float)
    shape = p.shape
    sd, tzr, beq, rate, asd, lrate = (np.full(shape, np.nan) for _ in range(6))
    exc = np.full((len(lv),) + shape, np.nan)
    lexc = np.full((len(lv),) + shape, np.nan)
    a_lee = math.radians(phi_f_deg - phi_w_deg) if math.isfinite(phi_w_deg) else -math.inf
    a_wind = math.radians(phi_f_deg + phi_w_deg)
    heeled = phi_w_deg != 0.0 and math.isfinite(phi_w_deg)
    for i, hs in enumerate(p.hs.values):
        for j, tz in enumerate(p.tz.values):
            if not p.values[i, j] > 0:
                continue
            band = spectrum_band(float(hs), float(tz))
            if band[1] > w[-1]:
                raise ValueError(f"beam seas: the sea state Hs {float(hs):g} m, Tz {float(tz):g} s reaches {band[1]:.2f} "
                                 f"rad/s, beyond the model's frequency grid ({w[-1]:.2f} rad/s)")
            S = band_spectrum(w, float(hs), float(tz), band)
            X, beq[i, j] = linearised_response(bsm, S, c44_heeled if heeled else None)
            if X is None:
                continue
            m0, m2 = moments(w, np.abs(X) ** 2 * S)
            sd[i, j], tzr[i, j] = math.degrees(math.sqrt(m0)), 2 * math.pi * math.sqrt(m0 / m2)
            if math.isnan(phi_f_deg):
                rate[i, j] = math.nan
            elif a_lee <= 0:
                rate[i, j] = lrate[i, j] = math.inf  # the steady heel is at or beyond the failure angle
            else:
                rate[i, j] = rice_rate(m0, m2, a_lee) + rice_rate(m0, m2, a_wind)
                lrate[i, j] = np.logaddexp(rice_log10_rate(m0, m2, a_lee) * LN10,
                                           rice_log10_rate(m0, m2, a_wind) * LN10) / LN10
            # lateral acceleration of the upright ship without wind
            Xa = linearised_response(bsm, S)[0] if heeled else X
            if Xa is None:
                continue
            a0, a2 = moments(w, np.abs((G + w**2 * crew_height) * Xa) ** 2 * S)
            asd[i, j] = math.sqrt(a0)
            exc[:, i, j] = [2 * rice_rate(a0, a2, a) for a in lv]
            lexc[:, i, j] = [math.log10(2.0) + rice_log10_rate(a0, a2, a) for a in lv]
    dims = ("hs", "tz")
    return xr.Dataset({"ds_roll_std": (dims, sd), "ds_roll_period": (dims, tzr), "ds_b44_eq": (dims, beq),
                       "ds_failure_rate": (dims, rate), "ds_failure_log10_rate": (dims, lrate),
                       "ea_acceleration_std": (dims, asd), "ea_exceedance_rate": (("ea_level",) + dims, exc),
                       "ea_exceedance_log10_rate": (("ea_level",) + dims, lexc)},
                      coords={"hs": p.hs, "tz": p.tz, "ea_level": lv})
