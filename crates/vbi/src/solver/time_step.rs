//! The time grid of a run: the time step Δt (the user's, checked, or the default), the warnings
//! it implies, the stability limit of a conditionally stable Newmark scheme, and the number of
//! recorded instants.

use super::validation::is_positive;
use super::{Crossing, SolverError, SolverOptions, SolverWarning};
use crate::modal::ModalBasis;
use crate::road::RoadProfile;

/// Limit on (time steps × values recorded per step) of one run: 4·10⁸ values (3.2 GB).
const MAX_RECORDED_VALUES: usize = 400_000_000;

/// The time step [s] that [`simulate`](super::simulate) uses by default for this basis and
/// crossing: min(max_time_step, T_min / steps_per_period, road sample spacing / v), where T_min
/// is the period of the highest retained mode; the road term only when the road is not smooth.
pub fn default_time_step(basis: &ModalBasis, crossing: &Crossing, options: &SolverOptions) -> f64 {
    let mut dt = options.max_time_step;
    let omega_max = basis
        .modes
        .iter()
        .map(|m| m.circular_frequency)
        .fold(0.0, f64::max);
    if omega_max > 0.0 {
        dt = dt.min(2.0 * std::f64::consts::PI / omega_max / options.steps_per_period);
    }
    if road_is_rough(&crossing.road) && crossing.speed > 0.0 {
        dt = dt.min(crossing.road.spacing / crossing.speed);
    }
    dt
}

fn road_is_rough(road: &RoadProfile) -> bool {
    road.left.iter().chain(road.right.iter()).any(|&h| h != 0.0)
}

/// The time step Δt of the run and the warnings known before stepping. A user-given step is
/// checked (positive and finite) and warned about when it under-resolves a mode (fewer than
/// `steps_per_period` steps per period) or the road (a wheel crossing more than one road sample
/// per step); otherwise [`default_time_step`]. A conditionally stable Newmark scheme (2β < γ)
/// must satisfy ω Δt ≤ 1 / √(γ/2 − β) for every mode.
pub(super) fn choose_time_step(
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
) -> Result<(f64, Vec<SolverWarning>), SolverError> {
    let v = crossing.speed;
    let (beta, gamma) = (options.newmark_beta, options.newmark_gamma);
    let mut warnings = Vec::new();
    let dt = match options.time_step {
        Some(dt) => {
            if !is_positive(dt) {
                return Err(SolverError::InvalidTimeStep { time_step: dt });
            }
            warnings.extend(mode_warning(basis, dt, options.steps_per_period));
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
        None => default_time_step(basis, crossing, options),
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
