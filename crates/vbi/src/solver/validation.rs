//! Validation of a crossing's inputs before any set-up: the modal basis, the crossing, the
//! solver options and the vehicle model. Every check returns a typed [`SolverError`].

use super::{check_vehicles_apart, Crossing, SolverError, SolverOptions, SpeedProfile};
use crate::modal::ModalBasis;
use crate::vehicle::{ContactKind, VehicleModel};

/// True for a finite x > 0 (false for NaN).
pub(super) fn is_positive(x: f64) -> bool {
    x > 0.0 && x.is_finite()
}

/// True for a finite x ≥ 0 (false for NaN).
pub(super) fn is_non_negative(x: f64) -> bool {
    x >= 0.0 && x.is_finite()
}

/// Checks the basis, the crossing, the options and the vehicle, in that order; the first problem
/// found is the error.
pub(super) fn validate(
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
) -> Result<(), SolverError> {
    validate_basis(basis)?;
    validate_crossing(crossing)?;
    validate_options(options)?;
    for run in &crossing.vehicles {
        validate_vehicle(&run.vehicle)?;
    }
    check_vehicles_apart(&crossing.vehicles, basis.deck.length)
        .map_err(SolverError::VehiclesOverlap)
}

/// At least one mode, shape tables of the deck's size, deck lines of two nodes or more, and
/// modes with finite non-negative frequencies and damping ratios.
fn validate_basis(basis: &ModalBasis) -> Result<(), SolverError> {
    let n = basis.mode_count();
    if n == 0 {
        return Err(SolverError::InvalidBasis {
            reason: "no modes",
            expected: 1,
            found: 0,
        });
    }
    let nodes = basis.deck.node_count();
    for (reason, len, expected) in [
        (
            "deck_deflection length",
            basis.deck_deflection.len(),
            nodes * n,
        ),
        ("deck_slope length", basis.deck_slope.len(), nodes * n),
    ] {
        if len != expected {
            return Err(SolverError::InvalidBasis {
                reason,
                expected,
                found: len,
            });
        }
    }
    if basis.deck.lines.iter().any(|l| l.node_positions.len() < 2) || basis.deck.lines.is_empty() {
        return Err(SolverError::InvalidBasis {
            reason: "deck lines need at least two nodes each",
            expected: 2,
            found: basis
                .deck
                .lines
                .iter()
                .map(|l| l.node_positions.len())
                .min()
                .unwrap_or(0),
        });
    }
    for (k, m) in basis.modes.iter().enumerate() {
        if !is_non_negative(m.circular_frequency) || !is_non_negative(m.damping_ratio) {
            return Err(SolverError::InvalidMode {
                mode: k + 1,
                circular_frequency: m.circular_frequency,
                damping_ratio: m.damping_ratio,
            });
        }
    }
    Ok(())
}

/// At least one vehicle, each with positive finite speeds (knots increasing strictly), finite
/// positions, and a non-negative finite free-vibration window.
fn validate_crossing(crossing: &Crossing) -> Result<(), SolverError> {
    if crossing.vehicles.is_empty() {
        return Err(SolverError::NoVehicle);
    }
    for (v, run) in crossing.vehicles.iter().enumerate() {
        validate_speed(v + 1, &run.speed)?;
        for (name, value) in [
            ("lateral_position", run.lateral_position),
            ("start_position", run.start_position),
        ] {
            if !value.is_finite() {
                return Err(SolverError::InvalidCrossing {
                    name,
                    value,
                    reason: "must be finite",
                });
            }
        }
    }
    if let Some(free) = crossing.free_vibration_duration {
        if !is_non_negative(free) {
            return Err(SolverError::InvalidCrossing {
                name: "free_vibration_duration",
                value: free,
                reason: "must be zero or positive and finite",
            });
        }
    }
    Ok(())
}

/// Positive finite speeds; the knots of a profile at finite, strictly increasing travels.
fn validate_speed(vehicle: usize, profile: &SpeedProfile) -> Result<(), SolverError> {
    let knots = match profile {
        SpeedProfile::Constant(speed) => {
            return match is_positive(*speed) {
                true => Ok(()),
                false => Err(SolverError::InvalidSpeed { speed: *speed }),
            }
        }
        SpeedProfile::Knots(knots) => knots,
    };
    if knots.is_empty() {
        return Err(SolverError::InvalidSpeedProfile { vehicle, knot: 0 });
    }
    for (i, knot) in knots.iter().enumerate() {
        if !is_positive(knot.speed) {
            return Err(SolverError::InvalidSpeed { speed: knot.speed });
        }
        let increasing = i == 0 || knot.travel > knots[i - 1].travel;
        if !knot.travel.is_finite() || !increasing {
            return Err(SolverError::InvalidSpeedProfile {
                vehicle,
                knot: i + 1,
            });
        }
    }
    Ok(())
}

/// Newmark β ≥ 0 and γ ≥ 0.5, and positive finite time-step bounds.
fn validate_options(options: &SolverOptions) -> Result<(), SolverError> {
    let (beta, gamma) = (options.newmark_beta, options.newmark_gamma);
    if !is_non_negative(beta) || !is_non_negative(gamma - 0.5) {
        return Err(SolverError::InvalidNewmark { beta, gamma });
    }
    for (name, value) in [
        ("max_time_step", options.max_time_step),
        ("steps_per_period", options.steps_per_period),
    ] {
        if !is_positive(value) {
            return Err(SolverError::InvalidCrossing {
                name,
                value,
                reason: "solver option must be positive and finite",
            });
        }
    }
    Ok(())
}

/// Matrices of the vehicle's size with finite entries, at least one contact, finite offsets
/// and loads, non-negative tyre stiffness and damping, and couplings to existing DOFs.
fn validate_vehicle(vehicle: &VehicleModel) -> Result<(), SolverError> {
    let d = vehicle.dof_count();
    let bad = |reason: String| SolverError::InvalidVehicle {
        vehicle: vehicle.name.clone(),
        reason,
    };
    for (name, m) in [
        ("mass", &vehicle.mass_matrix),
        ("damping", &vehicle.damping_matrix),
        ("stiffness", &vehicle.stiffness_matrix),
    ] {
        if m.nrows() != d || m.ncols() != d {
            return Err(bad(format!(
                "{name} matrix is {}×{}, expected {d}×{d}",
                m.nrows(),
                m.ncols()
            )));
        }
        if m.iter().any(|v| !v.is_finite()) {
            return Err(bad(format!("{name} matrix has a non-finite entry")));
        }
    }
    if vehicle.contacts.is_empty() {
        return Err(bad("no contacts".into()));
    }
    for (w, c) in vehicle.contacts.iter().enumerate() {
        if !c.longitudinal_offset.is_finite()
            || !c.lateral_offset.is_finite()
            || !c.static_load.is_finite()
        {
            return Err(bad(format!("contact {w} has a non-finite offset or load")));
        }
        if let ContactKind::Tyre {
            stiffness,
            damping,
            coupling,
        } = &c.kind
        {
            if !is_non_negative(*stiffness) || !is_non_negative(*damping) {
                return Err(bad(format!(
                    "contact {w}: tyre stiffness {stiffness} and damping {damping} must be >= 0"
                )));
            }
            if let Some(&(dof, _)) = coupling
                .iter()
                .find(|&&(dof, f)| dof >= d || !f.is_finite())
            {
                return Err(bad(format!(
                    "contact {w} couples to DOF {dof}, but the vehicle has {d} DOFs (or a non-finite coefficient)"
                )));
            }
        }
    }
    Ok(())
}
