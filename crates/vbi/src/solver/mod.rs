//! Coupled vehicle–bridge crossing in modal coordinates, integrated by Newmark-β (paper §3.3,
//! Eqs. 23–29): `simulate(&ModalBasis, &Crossing, &SolverOptions) -> ResponseHistory`, or the
//! same one time step at a time with an [`Integrator`].
//!
//! ## Equations
//! Bridge, mass-normalised modes k = 1…N (Eq. 20 projected on the modes):
//! q̈ₖ + 2ζₖωₖ q̇ₖ + ωₖ² qₖ = −Σ_w φₖ(x_w, y_w) P_w,
//! where P_w is the compressive (downward on the deck) force of contact w.
//!
//! Vehicle (Eq. 19), DOFs Z from static equilibrium on a flat rigid road, upwards positive:
//! M_v Z̈ + C_v Ż + K_v Z = Σ_w a_w [k_w (Y_w + r_w) + c_w (Ẏ_w + r′_w v)],
//! where a_w is the wheel's coupling vector (wheel displacement Z_w = a_w·Z), and C_v, K_v
//! already contain the tyre on a rigid road.
//!
//! Tyre force (Eqs. 23–26), P_w = S_w − k_w Δ_w − c_w Δ̇_w with Δ_w the tyre extension, on the
//! deck shape Y_w = ⟨N_w⟩Φ q; a [`ContactKind::Force`](crate::vehicle::ContactKind::Force) contact has P_w = S_w.
//!
//! Time integration: Newmark-β with the end-of-step accelerations as unknowns; the bridge block
//! of the effective matrix of Eq. 29 is diagonal plus a rank-T term (T tyres), so the modal and
//! vehicle accelerations are eliminated analytically and a dense T × T system in the tyre-force
//! increments remains. Per-step cost: O(T·N) for the contact shapes, O(T²·N) for the T × T
//! matrix (wheels on the deck only), O(T³ + d²) for the small solve; never a factorisation of
//! an (N + d) matrix.
//!
//! ## Parts (one job per file, the equations documented next to the code)
//! - `setup`: validation (`validation`), the time grid (`time_step`), the contacts
//!   (`tyre`), the modal constants Dₖ, the suspension matrix B inverted once, the tyre
//!   couplings, the static equilibrium — everything computed once.
//! - `kinematics`: where each contact is at an instant (deck position, speed of travel, road
//!   point); the only place that knows the motion law (one vehicle at constant speed).
//! - `newmark`: predictor and corrector. `shapes` (with `deck::ElementCubic`): the mode values
//!   and slopes at the tyres. `loads`: predicted tyre forces, modal and vehicle right-hand
//!   sides. `tyre_system`: the T × T Schur complement (right-hand side, capacitance matrix,
//!   its LU, solve, accelerations), with `dense` kernels; its position-dependent part
//!   (`DeckCoupling`) and the shapes form the instant's `step_geometry`.
//! - `pitching`: the pitch moments of braking and acceleration on the vehicle loads f_Z.
//! - `stacked`: the vehicles of a crossing stacked into one multibody system (their
//!   [`VehicleRun`]s, speed laws and checks come from [`crate::traffic`]).
//! - `contact`: the tyre contact active set (tyres leaving and landing on the road).
//! - `recorder`: the histories being written, and the [`ResponseHistory`] at the end.
//! - `integrator`: the per-step kernel and the public stepping API [`Integrator`];
//!   [`simulate`] is a loop over it. `batch`: [`simulate_batch`], crossings that differ only in
//!   their road stepped together, sharing the step geometry (the same histories, bit for bit).

mod batch;
mod contact;
mod dense;
mod errors;
mod integrator;
mod kinematics;
mod loads;
mod newmark;
mod pitching;
mod recorder;
mod setup;
mod shapes;
mod stacked;
mod step_geometry;
mod time_step;
mod tyre;
mod tyre_system;
mod validation;

use serde::{Deserialize, Serialize};

pub use batch::{simulate_batch, LockstepBatch};
pub use errors::{SolverError, SolverWarning};
pub use integrator::Integrator;
pub use setup::{modal_newmark_beta, PERIOD_MATCHED_LIMIT};
// The traffic types the solver reads, under their former paths too.
pub use crate::traffic::{
    check_vehicles_apart, first_catching_up, CatchingUp, SpeedKnot, SpeedProfile, StopsAt,
    TravelDirection, VehicleRun,
};
pub use time_step::{
    default_time_step, excitation_frequency, highest_vehicle_frequency, mode_is_quasi_static,
    passage_frequency, resolved_bridge_frequency, road_frequency, QUASI_STATIC_FREQUENCY_FACTOR,
};

#[cfg(test)]
use crate::deck::ElementCubic;
#[cfg(test)]
use crate::road::Track;
#[cfg(test)]
use crate::vehicle::ContactKind;

use crate::bits::same_bits;
use crate::modal::ModalBasis;
use crate::road::RoadProfile;
use crate::vehicle::VehicleModel;

/// One crossing event: one or several vehicles, each with its own direction, lane and speed
/// law, on one road over the bridge.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// The vehicles, each with its motion; at least one. Their DOFs and contacts are numbered in
    /// this order in the [`ResponseHistory`].
    pub vehicles: Vec<VehicleRun>,
    /// Road roughness on the approaches and the deck, in deck coordinates x [m]. A vehicle's
    /// left tyres run on the left track in the vehicle's own sense of travel.
    pub road: RoadProfile,
    /// Duration of free vibration recorded after the last contact leaves the deck [s].
    /// Default (None): two periods of the lowest mode, 2·2π/ω₁ (1 s if ω₁ = 0).
    pub free_vibration_duration: Option<f64>,
}

impl Crossing {
    /// A crossing of one vehicle on the deck centreline at constant speed v [m/s], front axle
    /// starting at the first support, with the default free-vibration window.
    pub fn new(vehicle: VehicleModel, road: RoadProfile, speed: f64) -> Crossing {
        Crossing {
            vehicles: vec![VehicleRun::forward(vehicle, speed)],
            road,
            free_vibration_duration: None,
        }
    }

    /// The first vehicle (the one whose front axle `ResponseHistory::front_axle_position`
    /// follows).
    ///
    /// # Panics
    /// If the crossing has no vehicle (the solver refuses one before).
    pub fn first_vehicle(&self) -> &VehicleRun {
        &self.vehicles[0]
    }

    /// The vehicles' names for reports: the name of one vehicle, two or three joined by ` + `,
    /// or `N vehicles (first, …)` for more.
    pub fn vehicle_names(&self) -> String {
        let names: Vec<&str> = self
            .vehicles
            .iter()
            .map(|v| v.vehicle.name.as_str())
            .collect();
        match names.len() {
            0..=3 => names.join(" + "),
            n => format!("{n} vehicles ({}, …)", names[0]),
        }
    }

    /// The highest speed of any vehicle [m/s] (the speed the road and the passage frequencies
    /// must be resolved at).
    pub fn highest_speed(&self) -> f64 {
        self.vehicles
            .iter()
            .map(|v| v.speed.highest_speed())
            .fold(0.0, f64::max)
    }
}

/// What a run records of its state at every instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Recording {
    /// Everything: q, q̇, q̈, the vehicle's Z and Z̈, the contacts' positions and forces, the
    /// front axle's position.
    #[default]
    Everything,
    /// What the DAF analysis reads: q, the contacts' positions and forces and the front axle's
    /// position. The modal velocities and accelerations and the vehicle's histories are left
    /// empty: a study's crossings, whose histories then take a third of the memory.
    ForDafAnalysis,
    /// No table: the history states the run's length, exit, contact losses and warnings, and
    /// its tables are empty. For a caller that reads each instant from the [`Integrator`] as
    /// it is computed: the pipeline's streamed DAF analysis
    /// ([`Recording::ForDafAnalysis`]'s numbers, bit for bit, without holding a history).
    OutcomeOnly,
}

/// Options of the time integration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverOptions {
    /// Time step Δt [s]. Default (None): [`default_time_step`], min(max_time_step,
    /// T_b / steps_per_period, T_v / steps_per_period, road sample spacing / v), T_b the period
    /// of the highest retained mode that does not respond quasi-statically, T_v the vehicle's
    /// shortest.
    pub time_step: Option<f64>,
    /// Newmark β [-]. Default 0.25 (average acceleration, unconditionally stable, no numerical
    /// damping).
    pub newmark_beta: f64,
    /// Newmark γ [-]; at least 0.5. Default 0.5.
    pub newmark_gamma: f64,
    /// Upper bound of the default time step [s]. Default 1e-3.
    pub max_time_step: f64,
    /// Time steps per period required of every retained mode [-]. Default 20. A user-given time
    /// step coarser than that gets a warning naming the first under-resolved mode.
    pub steps_per_period: f64,
    /// Whether a tyre may leave the road. Default true: a tyre whose force would become tensile
    /// lifts off and carries no force until its would-be force is compressive again (an active
    /// set per time step). False keeps every tyre bonded (linear model; tensile forces are then
    /// reported as contact losses, never hidden).
    #[serde(default = "default_true")]
    pub tyre_separation: bool,
    /// Whether each bridge mode resolved by the step (ωΔt ≤ π/2) takes the Newmark β that
    /// gives its free vibration its exact period ([`modal_newmark_beta`]). Default true; it
    /// applies with the default β = ¼, γ = ½ only.
    #[serde(default = "default_true")]
    pub period_matched_modes: bool,
    /// Whether a run at the default step is checked by a run at twice it, and the step halved
    /// until its deflection and moment DAFs hold ([`crate::crossing::time_step_check`]).
    /// Default true; no check with a given `time_step`.
    #[serde(default = "default_true")]
    pub time_step_check: bool,
    /// The default step is multiplied by 2^−`default_step_refinement` [-]: 1 halves it, −1
    /// doubles it (the check's coarse run). Set by the check, 0 otherwise.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub default_step_refinement: i32,
}

fn is_zero(value: &i32) -> bool {
    *value == 0
}

fn default_true() -> bool {
    true
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            time_step: None,
            newmark_beta: 0.25,
            newmark_gamma: 0.5,
            max_time_step: 1.0e-3,
            steps_per_period: 20.0,
            tyre_separation: true,
            period_matched_modes: true,
            time_step_check: true,
            default_step_refinement: 0,
        }
    }
}

/// A tyre that lost contact. With `SolverOptions::tyre_separation` (the default) the tyre left
/// the road: it carried no force in the interval, and `minimum_force` is the most tensile force
/// a tyre bonded to the road would have had to carry (the would-be force, a measure of the gap).
/// Without it the linear model keeps the tyre attached and the force itself became tensile
/// (P_w < 0). Either way the interval is reported, so that no result hides it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactLoss {
    /// Contact index (into the vehicle's contacts).
    pub contact: usize,
    /// Time the force first became negative [s].
    pub start_time: f64,
    /// Time it was compressive again, or the end of the run [s].
    pub end_time: f64,
    /// Most tensile (would-be) force in the interval [N] (negative).
    pub minimum_force: f64,
}

/// Where a contact runs: fixed offsets from its vehicle's front axle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactPath {
    /// Index of its vehicle in [`Crossing::vehicles`].
    #[serde(default)]
    pub vehicle: usize,
    /// Position relative to the front axle along the travel [m], ≤ 0.
    pub longitudinal_offset: f64,
    /// Lateral position y on the deck [m] (vehicle lateral position ± contact lateral offset:
    /// minus for a vehicle travelling backward, whose left is the deck's right).
    pub lateral_position: f64,
    /// Static load [N], downwards positive.
    pub static_load: f64,
}

/// Everything recorded during one crossing, at t_i = i·Δt, i = 0…step_count − 1.
/// Tables are step-major: `modal_displacement[i * mode_count + k]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResponseHistory {
    /// Time step Δt [s].
    pub time_step: f64,
    /// Number of recorded instants (time steps + 1).
    pub step_count: usize,
    /// Number of modes N.
    pub mode_count: usize,
    /// Speed v of the first vehicle at t = 0 [m/s].
    pub speed: f64,
    /// Newmark β and γ used [-].
    pub newmark: (f64, f64),
    /// Deck position x of the first vehicle's front axle at each instant [m].
    pub front_axle_position: Vec<f64>,
    /// Deck position x of every contact at each instant [m], steps × contacts (what the
    /// static reference and the static correction evaluate the influence lines at).
    pub contact_position: Vec<f64>,
    /// Modal coordinates qₖ(t_i) [kg^½·m], steps × modes.
    pub modal_displacement: Vec<f64>,
    /// Modal velocities q̇ₖ(t_i) [kg^½·m/s], steps × modes.
    pub modal_velocity: Vec<f64>,
    /// Modal accelerations q̈ₖ(t_i) [kg^½·m/s²], steps × modes (the bridge accelerations at
    /// stations are Σₖ φₖ q̈ₖ).
    pub modal_acceleration: Vec<f64>,
    /// Contact paths, in the vehicle's contact order.
    pub contacts: Vec<ContactPath>,
    /// Total contact force P_w(t_i) [N], compressive positive (static load included),
    /// steps × contacts.
    pub contact_force: Vec<f64>,
    /// Vehicle DOF names.
    pub vehicle_dof_names: Vec<String>,
    /// Vehicle displacements Z(t_i) from static equilibrium [m, rad], steps × DOFs.
    pub vehicle_displacement: Vec<f64>,
    /// Vehicle accelerations Z̈(t_i) [m/s², rad/s²], steps × DOFs.
    pub vehicle_acceleration: Vec<f64>,
    /// First instant at which every contact has left the deck (start of free vibration).
    pub exit_step: usize,
    /// Intervals of tensile tyre force.
    pub contact_losses: Vec<ContactLoss>,
    /// Warnings (under-resolved modes or road).
    pub warnings: Vec<SolverWarning>,
}

impl ResponseHistory {
    /// Time t_i = i·Δt [s].
    pub fn time(&self, step: usize) -> f64 {
        step as f64 * self.time_step
    }

    /// Modal coordinates of all modes at one instant.
    pub fn modal_displacements_at(&self, step: usize) -> &[f64] {
        let n = self.mode_count;
        &self.modal_displacement[step * n..(step + 1) * n]
    }

    /// Number of vehicle DOFs.
    pub fn vehicle_dof_count(&self) -> usize {
        self.vehicle_dof_names.len()
    }

    /// Whether this run's wheels take the paths `contacts` (lateral positions and static loads)
    /// and `positions` (each contact's position at every recorded instant, step-major) bit for
    /// bit: then everything that depends on where the wheels are, and not on the road or the
    /// response, is the same for both runs (the static reference, the mode values at the
    /// wheels).
    pub fn has_wheel_paths(&self, contacts: &[ContactPath], positions: &[f64]) -> bool {
        self.wheel_paths().same_as(contacts, positions)
    }

    /// Where this run's wheels are at every recorded instant.
    pub fn wheel_paths(&self) -> WheelPaths<'_> {
        WheelPaths {
            contacts: &self.contacts,
            positions: &self.contact_position,
            step_count: self.step_count,
        }
    }
}

/// Where every contact of a run is at every instant, with its lateral position and static
/// load: all that the static reference and the mode values at the wheels depend on (not the
/// road, nor the response). A [`ResponseHistory`] records it
/// ([`ResponseHistory::wheel_paths`]); an [`Integrator`] gives it before the run
/// ([`Integrator::contact_positions_of_run`]).
#[derive(Debug, Clone, Copy)]
pub struct WheelPaths<'a> {
    /// The contacts, in the run's contact order.
    pub contacts: &'a [ContactPath],
    /// Position x of each contact at each instant [m], step-major:
    /// `positions[i · contacts.len() + w]`.
    pub positions: &'a [f64],
    /// Number of instants.
    pub step_count: usize,
}

impl WheelPaths<'_> {
    /// Whether these are the paths `contacts` (lateral positions and static loads) and
    /// `positions`, bit for bit.
    pub fn same_as(&self, contacts: &[ContactPath], positions: &[f64]) -> bool {
        let lateral_and_load = |c: &ContactPath| [c.lateral_position, c.static_load];
        self.contacts.len() == contacts.len()
            && self
                .contacts
                .iter()
                .zip(contacts)
                .all(|(a, b)| same_bits(&lateral_and_load(a), &lateral_and_load(b)))
            && same_bits(self.positions, positions)
    }
}

/// Runs one crossing (paper §3.3, Eqs. 23–29): the vehicle starts at `crossing.start_position`
/// in static equilibrium with the bridge at rest, moves at constant speed, and the run ends
/// `free_vibration_duration` after its last contact has left the deck. The same as driving an
/// [`Integrator`] to its end.
pub fn simulate(
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
) -> Result<ResponseHistory, SolverError> {
    let mut integrator = Integrator::new(basis, crossing, options)?;
    while !integrator.is_finished() {
        integrator.step()?;
    }
    integrator.finish()
}

#[cfg(test)]
mod tests;
