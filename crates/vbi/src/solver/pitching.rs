//! The pitching moment of braking and acceleration: each vehicle's exact longitudinal
//! acceleration s̈_v(t) ([`crate::traffic::law`]) loads the pitch of every body with a centre-of-mass
//! height h_b by the d'Alembert couple M_θ = m_b h_b s̈_v (nose-up positive: braking pitches the
//! nose down and loads the front axles), a known external load on the vehicle equations:
//!
//! f_Z += Σ_v s̈_v(t) g_v,  g_v = Tᵀ e_v (the vehicle's
//! [`pitch_load_per_acceleration`](crate::vehicle::VehicleModel::pitch_load_per_acceleration)),
//!
//! at every step and in the static equilibrium the vehicles start from (docs/theory.md, "Pitching
//! under braking and acceleration"). Without heights there are no entries and nothing changes.

use super::Crossing;

/// One entry of a vehicle's pitch load, in the stacked DOF numbering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PitchLoad {
    /// Index of the vehicle in [`Crossing::vehicles`] (whose acceleration it takes).
    pub(super) vehicle: usize,
    /// Stacked DOF it loads.
    pub(super) dof: usize,
    /// Generalised load per unit acceleration [kg·m].
    pub(super) coefficient: f64,
}

/// Every vehicle's pitch-load entries, DOFs shifted to the stacked numbering (the vehicles'
/// DOFs one after the other, in the order of the crossing).
pub(super) fn pitch_loads(crossing: &Crossing) -> Vec<PitchLoad> {
    let mut first = 0;
    let mut loads = Vec::new();
    for (vehicle, run) in crossing.vehicles.iter().enumerate() {
        let model = &run.vehicle;
        loads.extend(
            model
                .pitch_load_per_acceleration
                .iter()
                .map(|&(dof, coefficient)| PitchLoad {
                    vehicle,
                    dof: first + dof,
                    coefficient,
                }),
        );
        first += model.dof_count();
    }
    loads
}

/// f += Σ s̈_v g_v: adds the pitch moments of the vehicles' accelerations s̈_v [m/s²] to the
/// vehicle load vector `load` (stacked DOFs). A vehicle at constant speed adds nothing.
pub(super) fn add_pitch_moments(
    load: &mut [f64],
    pitch_loads: &[PitchLoad],
    accelerations: &[f64],
) {
    for entry in pitch_loads {
        let acceleration = accelerations[entry.vehicle];
        if acceleration != 0.0 {
            load[entry.dof] += entry.coefficient * acceleration;
        }
    }
}
