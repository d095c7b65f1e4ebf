//! The time grid of a run: the time step Δt (the user's, checked, or the default), the warnings
//! it implies, the stability limit of a conditionally stable Newmark scheme, and the number of
//! recorded instants.

use super::validation::is_positive;
use super::{Crossing, SolverError, SolverOptions, SolverWarning};
use crate::modal::{ModalBasis, Mode};
use crate::road::RoadProfile;
use crate::vehicle::natural_modes;

/// Limit on (time steps × values recorded per step) of one run, the values that the analysis
/// derives per station included: 2.5·10⁸ values (2 GB). A run holds about 1.45 times its
/// recorded values at its peak (the history, the analysis's series, the output tables being
/// written): a platoon of 61 trucks at 1 ms (2.9·10⁸ values) peaked at 3.36 GB, and the former
/// limit of 4·10⁸ allowed 4.6 GB, an abort under a 4 GiB cap (issue 47). At 2.5·10⁸ the peak
/// stays near 3 GB.
const MAX_RECORDED_VALUES: usize = 250_000_000;

/// A retained bridge mode above this multiple of the highest excitation frequency
/// ([`excitation_frequency`]) responds quasi-statically: its dynamic magnification under a load
/// at f_e is 1/(1 − (f_e/f)²) ≤ 1/(1 − 1/25) = 1.042, and the average-acceleration Newmark
/// scheme, unconditionally stable and exact for a static load, reproduces that response with
/// few steps per period. The default time step need not resolve its period.
pub const QUASI_STATIC_FREQUENCY_FACTOR: f64 = 5.0;

/// The highest frequency [Hz] at which the crossing excites the bridge: the largest of the
/// bridge's first frequency (the free vibration that the entry of the load starts), the
/// vehicle's highest natural frequency on a rigid road (its dynamic wheel forces), and, on a
/// rough road, the rate [`road_frequency`] at which a wheel at speed v meets the road's
/// shortest waves.
pub fn excitation_frequency(basis: &ModalBasis, crossing: &Crossing) -> f64 {
    let first_mode = basis.modes.first().map_or(0.0, Mode::frequency_hz);
    let vehicle = highest_vehicle_frequency(crossing);
    first_mode
        .max(vehicle)
        .max(road_frequency(&crossing.road, crossing.highest_speed()))
}

/// The highest frequency [Hz] of the road's profile under a wheel at speed v [m/s]: v·n_max,
/// n_max the highest spatial frequency the profile carries: a generated random road's band
/// limit n₂ ([`RoadProfile::highest_spatial_frequency`]; 3 cycles/m by default, 72 Hz at
/// 86 km/h), otherwise the samples' Nyquist frequency 1/(2Δx) (240 Hz at 86 km/h on 0.05 m
/// samples). 0 on a smooth road.
pub fn road_frequency(road: &RoadProfile, speed: f64) -> f64 {
    if !road_is_rough(road) || road.spacing <= 0.0 {
        return 0.0;
    }
    let nyquist = 1.0 / (2.0 * road.spacing);
    let highest = road
        .highest_spatial_frequency
        .filter(|n| n.is_finite() && *n > 0.0)
        .map_or(nyquist, |n| n.min(nyquist));
    speed * highest
}

/// The highest natural frequency of the vehicle on a rigid road [Hz] (0 for moving forces, or
/// when the vehicle's modes cannot be computed: its own checks report that).
pub fn highest_vehicle_frequency(crossing: &Crossing) -> f64 {
    crossing
        .vehicles
        .iter()
        .filter_map(|run| natural_modes(&run.vehicle).ok())
        .flat_map(|modes| modes.into_iter().map(|m| m.frequency_hz))
        .fold(0.0, f64::max)
}

/// The highest frequency [Hz] that the default time step resolves among the bridge's modes:
/// [`QUASI_STATIC_FREQUENCY_FACTOR`] × [`excitation_frequency`].
pub fn resolved_bridge_frequency(basis: &ModalBasis, crossing: &Crossing) -> f64 {
    QUASI_STATIC_FREQUENCY_FACTOR * excitation_frequency(basis, crossing)
}

/// The frequency [Hz] at which a load moving at speed v drives mode `k`, v·κ/2π, with κ its
/// longitudinal wavenumber from the deck shape, κ² = Σ (dφ/dx)² / Σ φ² over the deck nodes
/// (exact for a sine, φ = sin κx: mode n of a simply supported span of L has κ = nπ/L and is
/// driven at n·v/2L), at most π/h for the shortest deck element h (the shortest wave the deck
/// nodes carry: the rotation-dominated top-of-spectrum FE modes have φ ≈ 0 at the nodes and
/// large slopes, which no load passing the nodes can drive faster).
pub fn passage_frequency(basis: &ModalBasis, k: usize, speed: f64) -> f64 {
    passage_frequency_below(basis, k, speed, deck_nyquist_wavenumber(basis))
}

/// π/h for the shortest deck element h [rad/m]: the shortest wave the deck nodes carry.
fn deck_nyquist_wavenumber(basis: &ModalBasis) -> f64 {
    let shortest_element = basis
        .deck
        .lines
        .iter()
        .flat_map(|line| line.node_positions.windows(2).map(|w| w[1] - w[0]))
        .filter(|&h| h > 0.0)
        .fold(f64::INFINITY, f64::min);
    std::f64::consts::PI / shortest_element
}

/// [`passage_frequency`] with the deck's [`deck_nyquist_wavenumber`] given.
fn passage_frequency_below(basis: &ModalBasis, k: usize, speed: f64, nyquist: f64) -> f64 {
    let n = basis.mode_count();
    let column = |table: &[f64]| -> f64 { table.iter().skip(k).step_by(n).map(|v| v * v).sum() };
    let (deflection, slope) = (column(&basis.deck_deflection), column(&basis.deck_slope));
    if deflection > 0.0 && slope.is_finite() {
        let wavenumber = (slope / deflection).sqrt().min(nyquist);
        speed * wavenumber / (2.0 * std::f64::consts::PI)
    } else {
        0.0
    }
}

/// Whether bridge mode `k` responds quasi-statically: its frequency is above
/// [`QUASI_STATIC_FREQUENCY_FACTOR`] × both the crossing's [`excitation_frequency`] and the
/// mode's own [`passage_frequency`].
pub fn mode_is_quasi_static(basis: &ModalBasis, crossing: &Crossing, k: usize) -> bool {
    let excitation = excitation_frequency(basis, crossing).max(passage_frequency(
        basis,
        k,
        crossing.highest_speed(),
    ));
    basis.modes[k].frequency_hz() > QUASI_STATIC_FREQUENCY_FACTOR * excitation
}

/// [`mode_is_quasi_static`] of every mode, with the crossing's excitation frequency (the
/// vehicle's modes, a scan of the road) and the deck's shortest element computed once.
fn quasi_static_modes(basis: &ModalBasis, crossing: &Crossing) -> Vec<bool> {
    let crossing_excitation = excitation_frequency(basis, crossing);
    let nyquist = deck_nyquist_wavenumber(basis);
    let speed = crossing.highest_speed();
    (0..basis.mode_count())
        .map(|k| {
            let passage = passage_frequency_below(basis, k, speed, nyquist);
            let excitation = crossing_excitation.max(passage);
            basis.modes[k].frequency_hz() > QUASI_STATIC_FREQUENCY_FACTOR * excitation
        })
        .collect()
}

/// The time step [s] that [`simulate`](super::simulate) uses by default for this basis and
/// crossing: min(max_time_step, T_b / steps_per_period, T_v / steps_per_period, road sample
/// spacing / v), where T_b is the period of the highest retained bridge mode that does not
/// respond quasi-statically ([`mode_is_quasi_static`]; a run that leaves such modes
/// under-resolved says so: [`SolverWarning::ModesQuasiStatic`]) and T_v the shortest period of the
/// vehicle's own modes (all resolved: an axle hops on its tyre at √((k_s + k_t)/m_u)); the road
/// term only when the road is not smooth; times 2^−`default_step_refinement` (the check of the
/// step, [`crate::crossing::time_step_check`]).
pub fn default_time_step(basis: &ModalBasis, crossing: &Crossing, options: &SolverOptions) -> f64 {
    default_time_step_of(
        basis,
        crossing,
        options,
        &quasi_static_modes(basis, crossing),
    )
}

/// [`default_time_step`] given [`quasi_static_modes`].
fn default_time_step_of(
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
    quasi_static: &[bool],
) -> f64 {
    let bridge = (0..basis.mode_count())
        .filter(|&k| !quasi_static[k])
        .map(|k| basis.modes[k].frequency_hz())
        .fold(0.0, f64::max);
    let highest = bridge.max(highest_vehicle_frequency(crossing));
    let mut dt = options.max_time_step;
    if highest > 0.0 {
        dt = dt.min(1.0 / (highest * options.steps_per_period));
    }
    let speed = crossing.highest_speed();
    if road_is_rough(&crossing.road) && speed > 0.0 {
        dt = dt.min(crossing.road.spacing / speed);
    }
    // The check of the step doubles or halves it (crate::crossing::time_step_check); 2⁻ʳ is
    // exact.
    dt * 0.5f64.powi(options.default_step_refinement.clamp(-60, 60))
}

/// The note of a default time step that leaves retained bridge modes above
/// [`resolved_bridge_frequency`] under-resolved.
fn quasi_static_warning(
    basis: &ModalBasis,
    crossing: &Crossing,
    quasi_static: &[bool],
    dt: f64,
    steps_per_period: f64,
) -> Option<SolverWarning> {
    let bad: Vec<usize> = (0..basis.mode_count())
        .filter(|&k| quasi_static[k] && basis.modes[k].frequency_hz() * dt * steps_per_period > 1.0)
        .collect();
    let &first = bad.first()?;
    Some(SolverWarning::ModesQuasiStatic {
        mode: first + 1,
        frequency_hz: basis.modes[first].frequency_hz(),
        further_modes: bad.len() - 1,
        excitation_frequency_hz: excitation_frequency(basis, crossing),
        time_step: dt,
    })
}

/// The warning of a user-given time step that under-resolves one of the vehicle's own modes.
fn vehicle_mode_warning(
    crossing: &Crossing,
    dt: f64,
    steps_per_period: f64,
) -> Option<SolverWarning> {
    let modes: Vec<_> = crossing
        .vehicles
        .iter()
        .filter_map(|run| natural_modes(&run.vehicle).ok())
        .flatten()
        .collect();
    let bad: Vec<_> = modes
        .iter()
        .filter(|m| m.frequency_hz * dt * steps_per_period > 1.0)
        .collect();
    let first = bad.first()?;
    Some(SolverWarning::VehicleModeUnderResolved {
        mode: first.label(),
        frequency_hz: first.frequency_hz,
        time_step: dt,
        steps_per_period,
        further_modes: bad.len() - 1,
    })
}

fn road_is_rough(road: &RoadProfile) -> bool {
    road.left.iter().chain(road.right.iter()).any(|&h| h != 0.0)
}

/// The time step Δt of the run and the warnings known before stepping. A user-given step is
/// checked (positive and finite) and warned about when it under-resolves a bridge mode or a
/// vehicle mode (fewer than `steps_per_period` steps per period) or the road (a wheel crossing
/// more than one road sample per step); otherwise [`default_time_step`], with a note when it
/// leaves bridge modes to respond quasi-statically. A conditionally stable Newmark scheme (2β < γ)
/// must satisfy ω Δt ≤ 1 / √(γ/2 − β) for every mode.
pub(super) fn choose_time_step(
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
) -> Result<(f64, Vec<SolverWarning>), SolverError> {
    let v = crossing.highest_speed();
    let (beta, gamma) = (options.newmark_beta, options.newmark_gamma);
    let mut warnings = Vec::new();
    let dt = match options.time_step {
        Some(dt) => {
            if !is_positive(dt) {
                return Err(SolverError::InvalidTimeStep { time_step: dt });
            }
            warnings.extend(mode_warning(basis, dt, options.steps_per_period));
            warnings.extend(vehicle_mode_warning(crossing, dt, options.steps_per_period));
            if road_is_rough(&crossing.road) && dt * v > crossing.road.spacing {
                warnings.push(SolverWarning::RoadUnderResolved {
                    time_step: dt,
                    speed: v,
                    distance_per_step: dt * v,
                    sample_spacing: crossing.road.spacing,
                });
            }
            dt
        }
        None => {
            let quasi_static = quasi_static_modes(basis, crossing);
            let dt = default_time_step_of(basis, crossing, options, &quasi_static);
            warnings.extend(quasi_static_warning(
                basis,
                crossing,
                &quasi_static,
                dt,
                options.steps_per_period,
            ));
            dt
        }
    };
    if !is_positive(dt) {
        return Err(SolverError::InvalidTimeStep { time_step: dt });
    }
    // Conditional stability of Newmark (2β < γ): ω Δt ≤ 1 / √(γ/2 − β).
    if 2.0 * beta < gamma {
        let limit_omega_dt = 1.0 / (0.5 * gamma - beta).sqrt();
        let n = basis.mode_count();
        if let Some(k) = (0..n).find(|&k| basis.modes[k].circular_frequency * dt > limit_omega_dt) {
            let w = basis.modes[k].circular_frequency;
            return Err(SolverError::UnstableTimeStep {
                time_step: dt,
                mode: k + 1,
                circular_frequency: w,
                limit: limit_omega_dt / w,
                beta,
                gamma,
            });
        }
    }
    Ok((dt, warnings))
}

fn mode_warning(basis: &ModalBasis, dt: f64, steps_per_period: f64) -> Option<SolverWarning> {
    let bad: Vec<usize> = (0..basis.mode_count())
        .filter(|&k| {
            let w = basis.modes[k].circular_frequency;
            w > 0.0 && dt > 2.0 * std::f64::consts::PI / w / steps_per_period
        })
        .collect();
    let &first = bad.first()?;
    let mode = &basis.modes[first];
    Some(SolverWarning::ModeUnderResolved {
        mode: first + 1,
        frequency_hz: mode.frequency_hz(),
        period: 1.0 / mode.frequency_hz(),
        time_step: dt,
        steps_per_period,
        further_modes: bad.len() - 1,
    })
}

/// Number of recorded instants t_i = i·Δt, i = 0…steps: the run lasts until `exit_time` (the
/// last contact leaves the deck) plus the free-vibration window (default two periods of mode 1,
/// 2·2π/ω₁, or 1 s if ω₁ = 0), rounded up to whole steps. Errs when steps × `values_per_step`
/// exceeds the recording limit.
pub(super) fn instant_count(
    basis: &ModalBasis,
    crossing: &Crossing,
    exit_time: f64,
    dt: f64,
    values_per_step: usize,
) -> Result<usize, SolverError> {
    let free_duration = crossing.free_vibration_duration.unwrap_or_else(|| {
        let w1 = basis.modes[0].circular_frequency;
        if w1 > 0.0 {
            2.0 * 2.0 * std::f64::consts::PI / w1
        } else {
            1.0
        }
    });
    let steps = ((exit_time + free_duration) / dt).ceil() as usize;
    if steps.saturating_mul(values_per_step) > MAX_RECORDED_VALUES {
        return Err(SolverError::TooLong {
            steps,
            values_per_step,
            limit: MAX_RECORDED_VALUES,
        });
    }
    Ok(steps + 1)
}
