"""NetCDF output: one table of CF attributes and atomic writing."""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

import xarray as xr

#: name -> (units, long_name). Every variable stabflow writes takes its attributes from here.
CF_ATTRS: dict[str, tuple[str, str]] = {
    # hull
    "station": ("1", "station index"),
    "point": ("1", "contour point index"),
    "x": ("m", "station longitudinal position from midships, positive forward"),
    "dx": ("m", "station slab length"),
    "n_points": ("1", "number of points in the half contour"),
    "y": ("m", "half-contour transverse offset (half-breadth), positive to port"),
    "z": ("m", "half-contour height above baseline"),
    "bonjean_area": ("m2", "half-section area below the horizontal waterline through the point"),
    "bonjean_moment_y": ("m3", "first moment of that half-section area about the centreline"),
    "bonjean_moment_z": ("m3", "first moment of that half-section area about the baseline"),
    "section_area_full": ("m2", "full section area to the deck"),
    # statics
    "heel": ("degree", "heel angle, positive starboard down"),
    "gz": ("m", "righting arm GZ, free trim"),
    "draft_mid": ("m", "draft at midships, earth-vertical, from the baseline"),
    "trim": ("degree", "trim angle at each heel (free trim), positive bow down"),
    "trim_upright": ("degree", "trim angle of the upright equilibrium, positive bow down"),
    "heave": ("m", "statics: earth height of the body origin (midships, baseline) above calm water at each heel; "
                   "time series: rise of G above its calm-water equilibrium (heave of G), positive up"),
    "volume": ("m3", "displaced volume"),
    "mass": ("kg", "displacement mass"),
    "lcb": ("m", "longitudinal centre of buoyancy from midships, positive forward"),
    "lcg": ("m", "longitudinal centre of gravity from midships, positive forward"),
    "kb": ("m", "vertical centre of buoyancy above baseline"),
    "kg": ("m", "vertical centre of gravity above baseline"),
    "bm": ("m", "transverse metacentric radius"),
    "km": ("m", "transverse metacentre above baseline"),
    "gm": ("m", "transverse metacentric height, fluid-free"),
    "gm_from_gz_slope": ("m", "GM from the slope of the computed GZ curve at zero heel"),
    "waterplane_area": ("m2", "waterplane area"),
    "lwl": ("m", "waterline length (slabs with a wet waterline)"),
    "bwl": ("m", "maximum waterline breadth"),
    # waves
    "wavelength_ratio": ("1", "wave length over waterline length, lambda / L"),
    "steepness": ("1", "wave steepness H / lambda"),
    "crest_position": ("m", "wave crest position from midships, positive forward"),
    "gm_wave": ("m", "metacentric height in waves, GM(x_c) (paper 002 eq. A24)"),
    "kb_wave": ("m", "vertical centre of buoyancy in waves"),
    "bm_wave": ("m", "transverse metacentric radius of the wave waterplane"),
    "gz_wave": ("m", "righting arm in waves, free trim"),
    "gz_crest": ("m", "righting arm with a crest amidships, lambda = L"),
    "gz_trough": ("m", "righting arm with a trough amidships, lambda = L"),
    "gz_calm": ("m", "righting arm in calm water"),
    "sea_state": ("1", "sea state"),
    "hs": ("m", "significant wave height"),
    "tm": ("s", "modal wave period"),
    "gm_cr": ("m", "critical GM: calm-water GZ maximum at the critical angle, not below the minimum GM"),
    "kg_cr": ("m", "KG giving the critical GM"),
    "roll_period": ("s", "roll period at the critical GM, 0.8 B / sqrt(GM_cr) (paper 002 eq. 11)"),
    "mean_tbc": ("s", "mean time below critical GM (paper 002 eq. 10)"),
    "metric_c": ("1", "early-stage assessment metric C = m(tbc) / T_phi (paper 002 eq. 11)"),
    "weight_sum": ("1", "sum of the statistical weights W_ij over the assessment grid"),
    "sigma_zeta": ("m", "standard deviation of wave elevation"),
    "k1": ("rad/m", "mean wave number (paper 002 eq. 5)"),
    "k2": ("rad/m", "spectral bandwidth wave number (paper 002 eq. 5)"),
    "gz_max": ("m", "maximum righting arm"),
    "heel_gz_max": ("degree", "heel angle of the maximum righting arm"),
    "heel_vanishing": ("degree", "angle of vanishing stability"),
    # dynamics
    "time": ("s", "time"),
    "roll": ("degree", "roll angle, positive starboard down"),
    "pitch": ("degree", "pitch angle from equilibrium trim, positive bow down"),
    "roll_rate": ("degree/s", "roll rate"),
    "pitch_rate": ("degree/s", "pitch rate"),
    "heave_rate": ("m/s", "vertical velocity of G, positive up"),
    "surge": ("m", "x of G in the frame moving with the commanded speed along the mean course"),
    "sway": ("m", "y of G in the frame moving with the commanded speed, positive to port"),
    "yaw": ("degree", "heading deviation from the mean course, positive to port"),
    "yaw_rate": ("degree/s", "yaw rate, positive to port"),
    "rudder": ("degree", "rudder angle, positive trailing edge to starboard (turns to starboard)"),
    "u": ("m/s", "surge velocity in the heading frame"),
    "v": ("m/s", "sway velocity in the heading frame, positive to port"),
    "fz": ("N", "vertical FK + hydrostatic force, earth axes"),
    "mx": ("N m", "FK + hydrostatic roll moment about G, earth axes"),
    "my": ("N m", "FK + hydrostatic pitch moment about G, earth axes"),
    "mz": ("N m", "FK yaw moment about G, earth axes (paper 000 eq. 15)"),
    "hull_volume": ("m3", "total enclosed hull volume to the deck"),
    # ensembles (roll and pitch statistics in degree, heave in m)
    "record": ("1", "record index (with the master seed, defines the record's seaway)"),
    "steps": ("1", "RK4 steps of the record in its statistics, after its warm-up (fewer than planned if it capsized)"),
    "warmup_lost": ("1", "1: the record ended (capsized) inside its warm-up and counts no steps, capsize or statistic"),
    "warmup_lost_count": ("1", "records that ended (capsized) inside their warm-up, left out of every statistic"),
    "capsized": ("1", "1 if roll passed 90 degree in the record"),
    "capsize_time": ("s", "time of capsize in the record (NaN if none)"),
    "roll_max": ("degree", "largest absolute roll in the record"),
    "moment_sums": ("1", "sums of x^k, k = order, over the record's samples (heave in m^k, roll and pitch in degree^k: mixed units, a raw accumulator)"),
    "threshold": ("degree", "roll threshold"),
    "crossing_record": ("1", "record of the crossing"),
    "crossing_threshold": ("1", "index of the roll threshold crossed"),
    "crossing_side": ("1", "+1 up-crossing of +threshold, -1 down-crossing of -threshold"),
    "crossing_time": ("s", "crossing time (linear interpolation)"),
    "crossing_roll_rate": ("degree/s", "roll rate at the crossing (linear interpolation); not a crossing frequency"),
    "crossing_step": ("1", "RK4 step just before the crossing"),
    "peak_record": ("1", "record of the roll peak"),
    "peak_time": ("s", "time of the roll peak (parabolic refinement)"),
    # roll decay
    "peak_roll": ("degree", "positive roll peak of the decay record"),
    "cycle_amplitude": ("degree", "mean of two successive positive roll peaks"),
    "cycle_zeta": ("1", "equivalent damping ratio of the cycle, delta / sqrt(4 pi^2 + delta^2), delta = ln(a_n / a_n+1)"),
    "peak_value": ("degree", "roll at the peak (maxima positive, minima negative)"),
    "envelope_peak_record": ("1", "record of the envelope peak"),
    "envelope_peak_time": ("s", "time of the roll-envelope peak"),
    "envelope_peak_value": ("degree", "Hilbert envelope of roll at its peak"),
    "lag": ("s", "time lag"),
    "acov_sum": ("degree2", "sum over records of sum_t roll(t) roll(t + lag)"),
    "acov_count": ("1", "number of products in acov_sum"),
    "roll_autocorrelation": ("1", "roll autocorrelation over the ensemble"),
    "frequency": ("rad/s", "encounter frequency"),
    # derivative model (paper 001)
    "calm_coefficient": ("SI", "calm-water restoring polynomial coefficient: N (heave) or N m (roll, pitch) per m^a rad^b of its term"),
    "calm_residual": ("SI", "RMS residual of the calm-water polynomial over the hull-position grid [N or N m]"),
    "calm_rms": ("SI", "RMS of the calm-water restoring force about its mean over the grid [N or N m]"),
    "tf_real": ("SI", "real part of the wave-dependent coefficient's transfer function, per m of wave amplitude"),
    "tf_imag": ("SI", "imaginary part of the wave-dependent coefficient's transfer function, per m of wave amplitude"),
    "mean_over_a2": ("SI", "phase mean of the wave-dependent coefficient per squared wave amplitude (second order)"),
    "wave_residual": ("SI", "RMS of the wave forces not reproduced by the linear transfer functions at the fit amplitude"),
    "wave_rms": ("SI", "RMS of the wave part of the restoring forces over grid and phases at the fit amplitude"),
    "fit_amplitude": ("m", "regular-wave amplitude of the transfer-function fit"),
    "tf_frequency": ("rad/s", "wave frequency of the transfer functions"),
    "generalized_mass": ("SI", "generalized mass (rigid body + added) at equilibrium, heave-roll-pitch [kg, kg m, kg m2]"),
    "linear_damping": ("SI", "linear damping, heave-roll-pitch [N s/m, N m s/rad, ...]"),
    "roll_full": ("degree", "largest |roll| over the last window, full volume-based model"),
    "roll_derivative": ("degree", "largest |roll| over the last window, derivative model"),
    "steady_full": ("1", "1 if the full model's roll amplitude is steady (two windows within 5 %)"),
    "steady_derivative": ("1", "1 if the derivative model's roll amplitude is steady (two windows within 5 %)"),
    "capsized_full": ("1", "1 if the full model capsized (roll beyond 90 degree)"),
    "capsized_derivative": ("1", "1 if the derivative model capsized (roll beyond 90 degree)"),
    "frequency_ratio": ("1", "encounter frequency / roll natural frequency"),
    "wave_height": ("m", "regular wave height"),
    "wave_frequency": ("rad/s", "wave frequency"),
    "wavelength": ("m", "wavelength"),
    "wave_psd_sum": ("m2 s", "sum over records of the Welch spectra of wave elevation at midships (per rad/s)"),
    "heave_psd_sum": ("m2 s", "sum over records of the Welch spectra of heave (per rad/s)"),
    "roll_psd_sum": ("degree2 s", "sum over records of the Welch spectra of roll (per rad/s)"),
    "pitch_psd_sum": ("degree2 s", "sum over records of the Welch spectra of pitch (per rad/s)"),
    "psd_count": ("1", "number of records in the *_psd_sum variables"),
    "wave_psd": ("m2 s", "mean encounter spectrum of wave elevation at midships, per rad/s"),
    "heave_psd": ("m2 s", "mean encounter spectrum of heave, per rad/s"),
    "roll_psd": ("degree2 s", "mean encounter spectrum of roll, per rad/s"),
    "pitch_psd": ("degree2 s", "mean encounter spectrum of pitch, per rad/s"),
    "heave_mean": ("m", "mean heave from equilibrium"),
    "roll_mean": ("degree", "mean roll"),
    "pitch_mean": ("degree", "mean pitch from equilibrium trim"),
    "heave_std": ("m", "standard deviation of heave"),
    "roll_std": ("degree", "standard deviation of roll"),
    "pitch_std": ("degree", "standard deviation of pitch"),
    "skewness": ("1", "skewness"),
    "kurtosis": ("1", "kurtosis (3 for a Gaussian)"),
    "exposure_hours": ("h", "simulated time of the ensemble"),
    "capsize_count": ("1", "records that capsized"),
    "lateral_limit": ("m/s2", "lateral-acceleration level whose crossings are recorded"),
    "lateral_crossing_record": ("1", "record of the lateral-acceleration crossing"),
    "lateral_crossing_limit": ("1", "index of the lateral-acceleration level crossed"),
    "lateral_crossing_side": ("1", "side of the crossing: +1 up through +level, -1 down through -level"),
    "lateral_crossing_time": ("s", "lateral-acceleration crossing time (linear interpolation)"),
    "lateral_peak_record": ("1", "record of the lateral-acceleration peak"),
    "lateral_peak_time": ("s", "time of the lateral-acceleration peak"),
    "lateral_peak_value": ("m/s2", "lateral acceleration at the peak (maxima positive, minima negative)"),
    "lateral_max": ("m/s2", "largest absolute lateral acceleration at the crew location in the record"),
    "lateral_sum": ("m/s2", "sum of the lateral acceleration over the record's steps"),
    "lateral_sum_squares": ("m2/s4", "sum of the squared lateral acceleration over the record's steps"),
    "lateral_zero_upcrossings": ("1", "zero up-crossings of the lateral acceleration in the record"),
    "lateral_acceleration_std": ("m/s2", "standard deviation of the lateral acceleration at the crew location"),
    "lateral_zero_upcrossing_rate": ("1/s", "mean zero up-crossing rate of the lateral acceleration"),
    "broached": ("1", "record broached (6-DOF: heading deviation beyond broach_deg with the rudder at its stop)"),
    "broach_time": ("s", "first time of broaching in the record (NaN if none)"),
    "surf_riding": ("1", "record surf-rode (6-DOF: speed along the waves near the peak wave's celerity)"),
    "broach_count": ("1", "records that broached"),
    "surf_riding_count": ("1", "records that surf-rode"),
    "map_heading": ("degree", "probability map: wave heading relative to the course (0 following)"),
    "map_speed": ("knot", "probability map: commanded speed"),
    **{f"map_{e}_{q}": ("1", f"probability map: {w.format(e)}") for e in ("capsize", "broach")
       for q, w in (("count", "records with a {}"), ("probability", "probability of a {} per record"),
                    ("lower", "lower bound of the Clopper-Pearson interval of the {} probability"),
                    ("upper", "upper bound of the Clopper-Pearson interval of the {} probability"))},
    "step_error": ("%", "paper 004's case: roll and yaw over the record's first step_seconds at dt vs dt / 5, "
                        "largest difference / largest value (at least 1 degree)"),
    "map_step_error": ("%", "probability map: roll and yaw over the cell's first record's first map_step_seconds "
                            "at dt vs dt / 5, largest difference / largest value (at least 1 degree)"),
    "capsize_rate": ("1/h", "capsizes per simulated hour (brute force)"),
    "hist_roll": ("1", "roll histogram counts"),
    "hist_heave": ("1", "heave histogram counts"),
    "hist_pitch": ("1", "pitch histogram counts"),
    "roll_bin": ("degree", "roll histogram bin centre"),
    "heave_bin": ("m", "heave histogram bin centre"),
    "pitch_bin": ("degree", "pitch histogram bin centre"),
    "sample_wave": ("m", "wave elevation at the midship station (sample records)"),
    "sample_heave": ("m", "heave from equilibrium (sample records)"),
    "sample_roll": ("degree", "roll (sample records)"),
    "sample_pitch": ("degree", "pitch from equilibrium trim (sample records)"),
    "sample_roll_rate": ("degree/s", "roll rate (sample records)"),
    # extremes
    "block": ("1", "independent sample (block of records)"),
    "target": ("degree", "roll angle whose exceedance rate is estimated"),
    "decorrelation_time": ("s", "lag after which the roll autocorrelation envelope stays below 0.05"),
    "sample_roll_std": ("degree", "roll standard deviation of the sample"),
    "gpd_shape": ("1", "generalized Pareto shape xi"),
    "gpd_scale": ("degree", "generalized Pareto scale"),
    "n_exceedances": ("1", "declustered exceedances of the threshold in the sample"),
    "sample_hours": ("h", "simulated time of the sample"),
    "rate_estimate": ("1/h", "rate of independent exceedances of the target (GPD extrapolation)"),
    "rate_lower": ("1/h", "lower confidence bound of the rate"),
    "rate_upper": ("1/h", "upper confidence bound of the rate"),
    "rate_bruteforce": ("1/h", "rate counted directly in the rest of the ensemble"),
    "bruteforce_hours": ("h", "simulated time of the brute-force count"),
    "inside": ("1", "1 if the brute-force rate lies inside the confidence interval"),
    "bootstrap_too_few": ("1", "bootstrap resamples with too few exceedances to fit a GPD (ranked lowest)"),
    "bootstrap_failed": ("1", "bootstrap resamples whose GPD fit failed (left out of the interval)"),
    "coverage": ("1", "fraction of samples whose interval contains the brute-force rate"),
    "rate_ratio": ("1", "estimated over brute-force rate"),
    # split-time
    "split_threshold": ("degree", "roll threshold of the split-time method"),
    "crossings": ("1", "threshold crossings in the sample"),
    "crossing_rate_raw": ("1/h", "crossing rate, paper 003 eq. 2"),
    "crossing_rate_lower": ("1/h", "binomial lower bound of the crossing rate"),
    "crossing_rate_upper": ("1/h", "binomial upper bound of the crossing rate"),
    "clusters": ("1", "independent crossing clusters in the sample"),
    "cluster_rate": ("1/h", "rate of independent crossing clusters"),
    "metric_threshold": ("1", "threshold of the GPD fit to the metric"),
    "metric_gpd_shape": ("1", "GPD shape of the metric tail"),
    "metric_gpd_scale": ("1", "GPD scale of the metric tail"),
    "metric_exceedances": ("1", "declustered metrics above the GPD threshold"),
    "capsize_probability": ("1", "P(capsize | independent crossing), GPD extrapolated to y = 1"),
    "capsize_rate_splittime": ("1/h", "capsize rate by the split-time method"),
    "capsize_rate_lower": ("1/h", "lower bound of the split-time capsize rate"),
    "capsize_rate_upper": ("1/h", "upper bound of the split-time capsize rate"),
    "perturbed_runs": ("1", "perturbed simulations run"),
    "capsizing_crossings": ("1", "crossings whose unperturbed motion capsizes in the window"),
    "capsize_rate_bruteforce": ("1/h", "capsize rate counted in the other records"),
    "capsize_rate_bruteforce_lower": ("1/h", "Poisson (Garwood) lower bound"),
    "capsize_rate_bruteforce_upper": ("1/h", "Poisson (Garwood) upper bound"),
    "bruteforce_capsizes": ("1", "capsizes counted in the other records"),
    "crossing_threshold_deg": ("degree", "threshold of the crossing"),
    "critical_perturbation": ("degree/s", "smallest roll-rate perturbation leading to capsize"),
    "metric": ("1", "capsizing metric y = phidot_U / phidot_Cr (1 at capsize)"),
    # criteria
    "criterion": ("1", "criterion index"),
    "criterion_name": ("1", "criterion"),
    "criterion_level": ("1", "rule and level the criterion belongs to"),
    "criterion_value": ("1", "the ship's value (unit in criterion_unit)"),
    "criterion_unit": ("1", "unit of the value and the standard"),
    "criterion_limit": ("1", "standard value (NaN: not sourced)"),
    "criterion_sense": ("1", "the value must be >= or <= the standard"),
    "criterion_source": ("1", "the standard's source and where it was read"),
    "verdict": ("1", "PASS, FAIL or NOT EVALUATED"),
    "verdict_reason": ("1", "missing items (NOT EVALUATED) or how the value was obtained"),
    "verdict_draft": ("1", "verdict against a draft's value where only drafted standards are missing (indicative, never the verdict; empty otherwise)"),
    "criterion_draft_limit": ("1", "limit of the indicative verdict: the standard's value in a readable draft where the adopted one is missing, the adopted one where only another needed standard is drafted (NaN otherwise)"),
    "criterion_draft_source": ("1", "the draft, the paragraph and where it was read, with the words printed"),
    "gm_wave_min": ("m", "smallest GM on a wave of the ship's length over crest positions"),
    "gm_wave_max": ("m", "largest GM on a wave of the ship's length over crest positions"),
    "delta_gm_wave": ("m", "half the range of GM on the wave (lambda = L)"),
    "delta_gm_waterplane": ("m", "(I(d + H/2) - I(d - H/2)) / 2V, waterplane inertias without the wave"),
    "deck_edge_immersion": ("degree", "angle of deck-edge immersion (first deck-edge point, free trim)"),
    "flooding_angle": ("degree", "angle of flooding (NaN: no openings given)"),
    "block_coefficient": ("1", "block coefficient V / (L B d)"),
    "froude_service": ("1", "Froude number at the service speed"),
    "wc_lw1": ("m", "weather criterion: steady wind heeling lever lw1"),
    "wc_lw2": ("m", "weather criterion: gust wind heeling lever lw2"),
    "wc_phi0": ("degree", "weather criterion: heel under steady wind phi0"),
    "wc_phi1": ("degree", "weather criterion: roll-back angle phi1"),
    "wc_phi_lw2": ("degree", "weather criterion: first intercept of lw2 with GZ"),
    "wc_phi_c": ("degree", "weather criterion: second intercept of lw2 with GZ"),
    "wc_phi2": ("degree", "weather criterion: upper limit of area b"),
    "wc_area_a": ("m rad", "weather criterion: area a"),
    "wc_area_b": ("m rad", "weather criterion: area b"),
    "wc_windage_area": ("m2", "weather criterion: windage area A"),
    "wc_windage_lever": ("m", "weather criterion: windage lever Z"),
    "wc_limit_phi0": ("degree", "weather criterion: limit on phi0"),
    "wc_X1": ("1", "weather criterion: factor X1(B/d)"),
    "wc_X2": ("1", "weather criterion: factor X2(CB)"),
    "wc_k": ("1", "weather criterion: factor k (bilge form, bilge keels)"),
    "wc_r": ("1", "weather criterion: r = a + b OG/d"),
    "wc_C": ("1", "weather criterion: roll period coefficient C"),
    "wc_T": ("s", "weather criterion: roll period T = f C B / sqrt(GM)"),
    "wc_s": ("1", "weather criterion: factor s(T)"),
    "wc_OG": ("m", "weather criterion: OG = KG - d"),
    "midship_coefficient": ("1", "midship section coefficient Cm at the draught"),
    "sr_wavelength_ratio": ("1", "wave length over waterline length of the surf-riding cases"),
    "sr_steepness": ("1", "wave steepness H / lambda of the surf-riding cases"),
    "sr_froude_critical": ("1", "critical Froude number of surf-riding, Melnikov's method (NaN: none below the celerity)"),
    "pr_heading": ("degree", "wave heading of the parametric-roll cases, 0 following, 180 head"),
    "pr_froude": ("1", "Froude number of the parametric-roll cases"),
    "pr_steepness": ("1", "wave steepness H / lambda of the parametric-roll cases (lambda = L)"),
    "pr_roll_1dof": ("degree", "largest |roll| over the last quarter, 1-DOF model with GZ on the passing wave (90: capsized)"),
    "pr_roll_3dof": ("degree", "largest |roll| over the last quarter, 3-DOF time domain (90: capsized)"),
    "pr_encounter_ratio": ("1", "encounter frequency over the natural roll frequency"),
    "depth_midship": ("m", "moulded depth D at midships (deck edge above the baseline)"),
    "freeboard_volume_ratio": ("1", "(V_D - V) / (A_W (D - d)), level-1 simplified method"),
    "rpr": ("1", "parametric rolling level-1 standard R_PR from the sourced formula"),
    **{f"l1_{m}_{k}": (u, f"level 1 {m.replace('_', ' ')}, waterplane route: {d}") for m in ("pure_loss", "parametric")
       for k, u, d in (("d_H", "m", "draft d_H"), ("d_L", "m", "draft d_L"), ("I_H", "m4", "waterplane inertia at d_H"),
                       ("I_L", "m4", "waterplane inertia at d_L"), ("KB_L", "m", "KB at d_L"),
                       ("gm_min", "m", "GMmin = KB(d_L) + I_L/V - KG"), ("delta_gm1", "m", "(I_H - I_L) / 2V"))},
    # level-2 sea-state physics (stabflow.criteria.sea_states) over the Rec. 34 table (hs, tz)
    "tz": ("s", "zero up-crossing period"),
    "sea_probability": ("1", "probability of the sea state (IACS Rec. 34 count / nominal total)"),
    "ew_effective_height": ("m", "significant effective wave height 4 sigma (Grim, lambda = L)"),
    "ew_height": ("m", "wave height of the effective-wave table (lambda = L)"),
    "ew_gm_min": ("m", "smallest GM over crest positions on the effective wave"),
    "ew_gm_max": ("m", "largest GM over crest positions on the effective wave"),
    "ew_delta_gm_ratio": ("1", "(GMmax - GMmin) / 2 / GM0 on the effective wave"),
    "ew_heel_vanishing": ("degree", "smallest angle of vanishing stability over crest positions on the effective wave"),
    "ew_gz_max": ("m", "smallest GZmax over crest positions on the effective wave"),
    "ew_table_gm_min": ("m", "smallest GM over crest positions (table over wave height)"),
    "ew_table_gm_max": ("m", "largest GM over crest positions (table over wave height)"),
    "ew_table_heel_vanishing": ("degree", "smallest angle of vanishing stability over crest positions (table)"),
    "ew_table_gz_max": ("m", "smallest GZmax over crest positions (table over wave height)"),
    "ew_table_gz": ("m", "GZ on the wave lambda = L over height, crest position and heel (free sinkage and trim)"),
    "ew_crest": ("m", "crest position of the effective-wave table (from midships, over one wave length)"),
    "ew_heel": ("degree", "heel of the effective-wave table"),
    "ew_roll_1dof": ("degree", "largest roll of the 1-DOF model with GZ on the passing effective wave (90: capsized)"),
    "pr_inertia": ("kg m2", "roll inertia I44 + A44 of the 1-DOF model"),
    "c1_case": ("1", "regular wave of parametric rolling's first level-2 check (2013 draft, Table 3-A-1)"),
    "c1_weight": ("1", "weight W_i of the wave"),
    "c1_wave_length": ("m", "wave length lambda_i"),
    "c1_wave_height": ("m", "wave height H_i"),
    "c1_gm_wave": ("m", "GM(H_i, lambda_i): mean metacentric height on the wave over the crest positions, sinkage and trim balanced"),
    "c1_delta_gm": ("m", "dGM(H_i, lambda_i): half the range of the metacentric height on the wave over the crest positions"),
    "c1_gm_ratio": ("1", "dGM / GM(H_i, lambda_i) (NaN where GM(H_i, lambda_i) <= 0 or no equilibrium on the wave)"),
    "c1_speed_resonance": ("m s-1", "V_PR,i: ship speed of principal parametric resonance (NaN where GM(H_i, lambda_i) <= 0 or the speed requirement is not evaluated)"),
    "c1_fails": ("1", "C_i: 1 where neither the GM nor the speed requirement holds, else 0 (NaN: no equilibrium on the wave)"),
    "c1": ("1", "C1 = sum W_i C_i, parametric rolling level 2, first check (2013 draft)"),
    "pr_b44": ("N m s/rad", "linear roll damping of the 1-DOF model"),
    "pr_b44q": ("N m s2/rad2", "quadratic roll damping of the 1-DOF model"),
    "ew_probability_gm_negative": ("1", "probability of the sea states with GMmin < 0 on the effective wave"),
    "ew_probability_delta_gm_above_rpr": ("1", "probability of the sea states with delta GM / GM above level 1's R_PR"),
    "ew_probability_breaking": ("1", "probability of the sea states whose effective wave exceeds the steepness 1/7 (left out)"),
    "ds_roll_std": ("degree", "standard deviation of roll, beam seas without way (linearised)"),
    "ds_roll_period": ("s", "mean zero-crossing period of roll 2 pi sqrt(m0 / m2)"),
    "ds_b44_eq": ("N m s/rad", "stochastically linearised roll damping"),
    "ds_failure_rate": ("1/s", "rate of roll beyond the failure angle on either side (Rice)"),
    "ds_long_term_rate": ("1/year", "dead-ship failure rate over the scatter table"),
    "ds_failure_log10_rate": ("1", "log10 of the rate of roll beyond the failure angle [1/s] (Rice, in log space)"),
    "ds_long_term_log10_rate": ("1", "log10 of the dead-ship failure rate over the scatter table [1/year]"),
    "ds_heel_wind": ("degree", "heel under the steady wind (IS Code phi0; 0 without windage)"),
    "ds_failure_angle": ("degree", "failure roll angle of the dead-ship rates"),
    "ea_level": ("m/s2", "lateral-acceleration level"),
    "ea_acceleration_std": ("m/s2", "standard deviation of the lateral acceleration at the crew location"),
    "ea_exceedance_rate": ("1/s", "rate of |lateral acceleration| above the level (Rice, both sides)"),
    "ea_long_term_rate": ("1/year", "rate of |lateral acceleration| above the level over the scatter table"),
    "ea_exceedance_log10_rate": ("1", "log10 of the rate of |lateral acceleration| above the level [1/s]"),
    "ea_long_term_log10_rate": ("1", "log10 of the rate of |lateral acceleration| above the level over the scatter "
                                     "table [1/year]"),
    "ea_crew_height": ("m", "height of the crew location above the baseline"),
    "ea_height_above_g": ("m", "height of the crew location above G"),
    "ea_roll_period": ("s", "undamped natural roll period of the 3-DOF model"),
    "ea_acceleration_per_roll": ("m/s2", "lateral acceleration per radian of roll at the natural period, g + 4 pi^2 h / T^2"),
}


#: the radiation step's 2 x 2 entries on disk (issue 17, heave-pitch memory model): suffix, (i, j) and
#: the units of an added mass, a damping and a retardation function (or residue) there
RADIATION_ENTRIES = (("33", (0, 0), "kg", "N s/m", "N/(m s)"), ("35", (0, 1), "kg m", "N s", "N/s"),
                     ("53", (1, 0), "kg m", "N s", "N/s"), ("55", (1, 1), "kg m2", "N m s", "N m/s"))
#: the radiation step's quantities written entry by entry: name, dims before (i, j), which of the
#: entry's units (index in RADIATION_ENTRIES' rows), long name
RADIATION_QUANTITIES = (
    ("added_mass", ("radiation_omega",), 2, "added mass A(w) from the BEM"),
    ("damping", ("radiation_omega",), 3, "radiation damping B(w) from the BEM"),
    ("added_mass_inf", (), 2, "added mass at infinite frequency from the BEM"),
    ("added_mass_fit", ("radiation_omega",), 2, "added mass A(w) of the fitted memory model, A(inf) + Im K^(w) / w"),
    ("damping_fit", ("radiation_omega",), 3, "radiation damping B(w) of the fitted memory model, Re K^(w)"),
    ("kernel", ("time",), 4, "retardation function (2/pi) int B(w) cos(w t) dw of the BEM's B up to its last frequency"),
    ("kernel_fit", ("time",), 4, "retardation function of the fitted memory model, sum_p Re(c_p exp(l_p t))"),
    ("residue_re", ("pole",), 4, "real part of the residue c_p of the fitted memory model"),
    ("residue_im", ("pole",), 4, "imaginary part of the residue c_p of the fitted memory model"),
)
_RADIATION_MODES = {"33": "heave-heave", "35": "heave force per pitch", "53": "pitch moment per heave",
                    "55": "pitch-pitch"}
CF_ATTRS.update({f"radiation_{q}_{e[0]}": (e[u], f"{_RADIATION_MODES[e[0]]} {long}")
                 for q, _, u, long in RADIATION_QUANTITIES for e in RADIATION_ENTRIES})
CF_ATTRS.update({"radiation_omega": ("rad/s", "wave frequency of the heave-pitch BEM"),
                 "pole_re": ("1/s", "real part of a pole l_p of the fitted memory model"),
                 "pole_im": ("rad/s", "imaginary part of a pole l_p of the fitted memory model")})


def annotate(ds: xr.Dataset) -> xr.Dataset:
    """Attach CF attributes to every variable and coordinate of ``ds`` found in the table."""
    for name, v in ds.variables.items():  # the dataset's own Variable objects (ds[name] builds a DataArray)
        if name in CF_ATTRS:
            units, long_name = CF_ATTRS[name]
            v.attrs.update(units=units, long_name=long_name)
    return ds


@contextmanager
def atomic_path(path: str | Path, suffix: str = ".tmp"):
    """Yield a temporary path beside ``path``; rename it onto ``path`` only if the block succeeds."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=suffix, dir=path.parent)
    os.close(fd)
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def write_netcdf(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file in the same folder, then rename).

    No history/date attributes are written, so the same inputs give bit-identical files. No
    dimension is declared unlimited: xarray keeps declared unlimited dimensions (also the ones it
    carries in ``encoding`` from files it read) in a set, which orders them by Python's per-process
    string hash, so the file bytes would change from run to run. Dimensions are then created in the
    order the variables use them (a dimension of length 0, e.g. an ensemble without threshold
    crossings, still becomes an unlimited one in the file, as netCDF requires).
    """
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", unlimited_dims=[])
    return Path(path)


def atomic_savefig(fig, path: str | Path, **kw) -> Path:
    """Save a matplotlib figure atomically; metadata stripped for reproducible files."""
    path = Path(path)
    meta = {"Software": None} if path.suffix == ".png" else {"Date": None}
    with atomic_path(path, suffix=path.suffix) as tmp:
        fig.savefig(tmp, metadata=meta, **kw)
    return path


def atomic_text(text: str, path: str | Path) -> Path:
    """Write a text file atomically."""
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text)
    return Path(path)


def compare_results(a: str | Path, b: str | Path) -> list[dict]:
    """Compare every NetCDF file under folder ``a`` with the file at the same relative path under
    ``b``: byte-identical, or else the largest relative difference over the numeric variables
    (|x_a - x_b| / max|x_a|, NaN-aware) and the variables whose text or shape differs.

    Returns one dict per file: ``file``, ``status`` ('identical bytes', 'equal values',
    'different', 'missing'), ``max_rel`` and ``variables`` (names that differ).
    """
    import numpy as np

    a, b = Path(a), Path(b)
    rows = []
    for fa in sorted(a.rglob("*.nc")):
        rel = fa.relative_to(a)
        fb = b / rel
        if not fb.exists():
            rows.append(dict(file=str(rel), status="missing", max_rel=np.nan, variables=[]))
            continue
        if fa.read_bytes() == fb.read_bytes():
            rows.append(dict(file=str(rel), status="identical bytes", max_rel=0.0, variables=[]))
            continue
        with xr.open_dataset(fa) as da, xr.open_dataset(fb) as db:
            worst, names = 0.0, []
            for v in sorted(set(da.variables) | set(db.variables)):
                if v not in da.variables or v not in db.variables or da[v].shape != db[v].shape:
                    names.append(v)
                    worst = np.inf
                    continue
                x, y = da[v].values, db[v].values
                if x.dtype.kind in "fiuc":
                    x, y = x.astype(float), y.astype(float)
                    same = np.isnan(x) == np.isnan(y)
                    d = np.abs(np.nan_to_num(x - y))
                    scale = max(float(np.nanmax(np.abs(x))) if np.isfinite(x).any() else 0.0, 1e-300)
                    r = float(d.max()) / scale if d.size else 0.0
                    if r > 0 or not same.all():
                        names.append(v)
                        worst = max(worst, r if same.all() else np.inf)
                elif not np.array_equal(x, y):
                    names.append(v)
                    worst = np.inf
            if da.attrs != db.attrs:
                names.append("(attributes)")
                worst = np.inf
        rows.append(dict(file=str(rel), status="equal values" if not names else "different", max_rel=worst,
                         variables=names))
    return rows


CF_ATTRS.update({
    "diffraction_omega": ("rad/s", "wave frequency of the diffraction table"),
    "diffraction_heading": ("degree", "wave heading of the diffraction table, 0 following, 180 head seas"),
    "diffraction_mode": ("1", "rigid-body mode of the diffraction table: forces Surge, Sway, Heave [N/m]; moments about G Roll, Pitch, Yaw [N m/m]"),
    "diffraction_re": ("N/m", "real part of the diffraction force per metre of wave amplitude (moments N m/m)"),
    "diffraction_im": ("N/m", "imaginary part of the diffraction force per metre of wave amplitude (moments N m/m)"),
    "froude_krylov_re": ("N/m", "real part of the Froude-Krylov force per metre of wave amplitude (moments N m/m)"),
    "froude_krylov_im": ("N/m", "imaginary part of the Froude-Krylov force per metre of wave amplitude (moments N m/m)"),
    "sway_reaction_re": ("N/m", "real part of the radiation force of the free sway driven by the wave's sway force, per "
                                "metre of wave amplitude (moments N m/m)"),
    "sway_reaction_im": ("N/m", "imaginary part of the radiation force of the free sway driven by the wave's sway force, "
                                "per metre of wave amplitude (moments N m/m)"),
})
