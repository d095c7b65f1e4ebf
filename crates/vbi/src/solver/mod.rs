//! Coupled vehicle–bridge crossing in modal coordinates, integrated by Newmark-β (paper §3.3,
//! Eqs. 23–29): `simulate(&ModalBasis, &Crossing, &SolverOptions) -> ResponseHistory`.
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
//! Tyre force (Eqs. 23–26), with Δ_w = Z_w − Y_w − r_w the tyre extension and
//! Δ̇_w = Ż_w − Ẏ_w − Y′_w v − r′_w v (Eq. 25):
//! P_w = S_w − k_w Δ_w − c_w Δ̇_w, with Y_w = ⟨N_w⟩Φ q and Y′_w = ⟨N_w⟩′Φ q (Eq. 26),
//! and S_w the static wheel load. A [`ContactKind::Force`] contact has P_w = S_w.
//!
//! ## Time integration (rank-T coupling, Schur complement)
//! Newmark-β with unknown end-of-step accelerations a: u = ũ + βΔt² a, u̇ = ṽ + γΔt a. The
//! bridge block of the effective matrix of Eq. 29 is diag(Dₖ) plus a rank-T term (T tyres), with
//! Dₖ = 1 + 2ζₖωₖγΔt + ωₖ²βΔt². With the T tyre-force increments s_w (P_w = P̃_w + s_w) as
//! extra unknowns, the modal accelerations are eliminated analytically,
//! a_q = D⁻¹(f_q − Φᵀ s), and the vehicle's through a constant, once-inverted matrix
//! B = M_v + γΔt C_s + βΔt² K_s (suspension only, tyres removed), a_Z = B⁻¹(f_Z + Aᵀ s). What
//! remains per step is a dense T × T system (I + G D⁻¹ Φᵀ + E A B⁻¹ Aᵀ) s = r. Per-step cost:
//! O(T·N) for the contact shapes, O(T²·N) for the T × T matrix (wheels on the deck only),
//! O(T³ + d²) for the small solve; never a factorisation of an (N + d) matrix.

mod dense;
mod element_cache;
mod errors;
mod time_step;
mod validation;

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use element_cache::ElementCache;
pub use errors::{SolverError, SolverWarning};
pub use time_step::default_time_step;
use time_step::{choose_time_step, instant_count};
use validation::{is_positive, validate};

use crate::modal::ModalBasis;
use crate::road::{RoadProfile, Track};
use crate::vehicle::{ContactKind, VehicleModel};

/// One crossing: a vehicle at constant speed on a road over the bridge.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// The vehicle (contacts, DOFs, M, C, K).
    pub vehicle: VehicleModel,
    /// Road roughness on the approach and the deck, in bridge coordinates.
    pub road: RoadProfile,
    /// Constant speed v [m/s]; must be positive.
    pub speed: f64,
    /// Lateral position y of the vehicle centreline on the deck [m], from the deck centreline,
    /// positive to the left. Default 0.
    pub lateral_position: f64,
    /// Position x of the front axle at t = 0 [m] (negative on the approach). The vehicle starts
    /// in static equilibrium on the road there, with the bridge at rest and undeflected.
    /// Default 0 (front axle at the first support).
    pub start_position: f64,
    /// Duration of free vibration recorded after the last contact leaves the deck [s].
    /// Default (None): two periods of the lowest mode, 2·2π/ω₁ (1 s if ω₁ = 0).
    pub free_vibration_duration: Option<f64>,
}

impl Crossing {
    /// A crossing on the deck centreline, front axle starting at the first support, with the
    /// default free-vibration window.
    pub fn new(vehicle: VehicleModel, road: RoadProfile, speed: f64) -> Crossing {
        Crossing {
            vehicle,
            road,
            speed,
            lateral_position: 0.0,
            start_position: 0.0,
            free_vibration_duration: None,
        }
    }
}

/// Options of the time integration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SolverOptions {
    /// Time step Δt [s]. Default (None): min(max_time_step, T_min / steps_per_period,
    /// road sample spacing / v), where T_min is the period of the highest retained mode.
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

/// Where a contact runs: fixed offsets from the front axle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactPath {
    /// Position relative to the front axle along the travel [m], ≤ 0.
    pub longitudinal_offset: f64,
    /// Lateral position y on the deck [m] (vehicle lateral position + contact lateral offset).
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
    /// Speed v [m/s].
    pub speed: f64,
    /// Newmark β and γ used [-].
    pub newmark: (f64, f64),
    /// Front-axle position x at each instant [m].
    pub front_axle_position: Vec<f64>,
    /// Modal coordinates qₖ(t_i) [kg^½·m], steps × modes.
    pub modal_displacement: Vec<f64>,
    /// Modal velocities q̇ₖ(t_i) [kg^½·m/s], steps × modes.
    pub modal_velocity: Vec<f64>,
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
}

/// A tyre contact prepared for the time loop.
struct Tyre {
    contact: usize,
    stiffness: f64,
    damping: f64,
    /// Dense coupling vector a_w (length d).
    coupling: Vec<f64>,
    /// The non-zero entries of a_w as (DOF, coefficient), for the per-step products.
    coupling_sparse: Vec<(usize, f64)>,
    track: Track,
    offset: f64,
    lateral: f64,
    static_load: f64,
    /// Lever-rule weights of the deck lines at the tyre's lateral position (constant).
    weights: [(usize, f64); 2],
}

/// Passes of the contact active set per time step before the set is accepted as it stands.
const MAX_CONTACT_PASSES: usize = 10;

impl Tyre {
    /// Total contact force P = S + k_t (Y + r − Z_w) + c_t (Ẏ + v r′ − Ż_w) of the tyre bonded
    /// to the road (Eq. 25), with Y = φ·q and Ẏ = φ·q̇ + v φ′·q, for a state (q, q̇, Z, Ż): `shapes` = (φ, φ′) of the modes at the
    /// tyre when it is on the deck, `road` = (r, r′) under it [m, -], speed `v` [m/s].
    fn force(
        &self,
        (q, qd, z, zd): (&[f64], &[f64], &[f64], &[f64]),
        shapes: Option<(&[f64], &[f64])>,
        (r, r_slope): (f64, f64),
        v: f64,
    ) -> f64 {
        let (y_w, yv_w) = match shapes {
            Some((phi, psi)) => {
                let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
                for (((p, sl), qk), vk) in phi.iter().zip(psi).zip(q).zip(qd) {
                    a += p * qk;
                    b += p * vk;
                    c += sl * qk;
                }
                (a, b + v * c)
            }
            None => (0.0, 0.0),
        };
        let (z_w, zv_w) = (
            sparse_dot(&self.coupling_sparse, z),
            sparse_dot(&self.coupling_sparse, zd),
        );
        self.static_load
            + self.stiffness * (y_w + r - z_w)
            + self.damping * (yv_w + v * r_slope - zv_w)
    }
}

/// a·x for a sparse a given as (index, value) pairs.
#[inline]
fn sparse_dot(a: &[(usize, f64)], x: &[f64]) -> f64 {
    a.iter().map(|&(i, f)| f * x[i]).sum()
}

/// Runs one crossing (paper §3.3, Eqs. 23–29): the vehicle starts at `crossing.start_position`
/// in static equilibrium with the bridge at rest, moves at constant speed, and the run ends
/// `free_vibration_duration` after its last contact has left the deck.
pub fn simulate(
    basis: &ModalBasis,
    crossing: &Crossing,
    options: &SolverOptions,
) -> Result<ResponseHistory, SolverError> {
    validate(basis, crossing, options)?;
    let n = basis.mode_count();
    let vehicle = &crossing.vehicle;
    let d = vehicle.dof_count();
    let v = crossing.speed;
    let (beta, gamma) = (options.newmark_beta, options.newmark_gamma);
    let deck_length = basis.deck.length;

    // Time step and warnings.
    let (dt, mut warnings) = choose_time_step(basis, crossing, options)?;

    // Duration.
    let last_offset = vehicle
        .contacts
        .iter()
        .map(|c| c.longitudinal_offset)
        .fold(0.0, f64::min);
    let exit_distance = deck_length - last_offset - crossing.start_position;
    if !is_positive(exit_distance) {
        return Err(SolverError::StartsBeyondDeck {
            start_position: crossing.start_position,
            deck_length,
        });
    }
    let contact_count = vehicle.contacts.len();
    let values_per_step = 2 * n + contact_count + 2 * d + 1;
    let step_count = instant_count(basis, crossing, exit_distance / v, dt, values_per_step)?;

    // Contacts.
    let mut tyres = Vec::new();
    let mut forces = Vec::new(); // (contact, offset, lateral, load)
    for (w, c) in vehicle.contacts.iter().enumerate() {
        let lateral = crossing.lateral_position + c.lateral_offset;
        match &c.kind {
            ContactKind::Force => forces.push((w, c.longitudinal_offset, lateral, c.static_load)),
            ContactKind::Tyre {
                stiffness,
                damping,
                coupling,
            } => {
                let mut a = vec![0.0; d];
                for &(dof, f) in coupling {
                    a[dof] += f;
                }
                tyres.push(Tyre {
                    contact: w,
                    stiffness: *stiffness,
                    damping: *damping,
                    coupling_sparse: a
                        .iter()
                        .enumerate()
                        .filter(|(_, &f)| f != 0.0)
                        .map(|(i, &f)| (i, f))
                        .collect(),
                    coupling: a,
                    track: Track::of_lateral_offset(c.lateral_offset),
                    offset: c.longitudinal_offset,
                    lateral,
                    static_load: c.static_load,
                    weights: basis.deck.lateral_weights(lateral),
                });
            }
        }
    }
    let t_count = tyres.len();

    // Vehicle matrices: suspension only (tyres on a rigid road removed).
    let mut c_s = vehicle.damping_matrix.clone();
    let mut k_s = vehicle.stiffness_matrix.clone();
    for t in &tyres {
        for i in 0..d {
            for j in 0..d {
                c_s[(i, j)] -= t.damping * t.coupling[i] * t.coupling[j];
                k_s[(i, j)] -= t.stiffness * t.coupling[i] * t.coupling[j];
            }
        }
    }
    let bdt2 = beta * dt * dt;
    let gdt = gamma * dt;
    let invalid = |reason: &str| SolverError::InvalidVehicle {
        vehicle: vehicle.name.clone(),
        reason: reason.to_string(),
    };
    let b_matrix = &vehicle.mass_matrix + &c_s * gdt + &k_s * bdt2;
    let b_inv = if d > 0 {
        b_matrix
            .try_inverse()
            .ok_or_else(|| invalid("M + γΔt C + βΔt² K of the suspension is singular"))?
    } else {
        DMatrix::zeros(0, 0)
    };
    let m_inv = if d > 0 {
        vehicle
            .mass_matrix
            .clone()
            .try_inverse()
            .ok_or_else(|| invalid("mass matrix is singular"))?
    } else {
        DMatrix::zeros(0, 0)
    };
    let flat = |m: &DMatrix<f64>| -> Vec<f64> {
        let mut out = Vec::with_capacity(m.nrows() * m.ncols());
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                out.push(m[(i, j)]);
            }
        }
        out
    };
    let b_inv_flat = flat(&b_inv);
    let m_inv_flat = flat(&m_inv);
    // Suspension matrices as (row, column, value) lists: they are sparse (springs between a few
    // DOFs), and the vehicle right-hand side is evaluated every step.
    let sparse = |m: &DMatrix<f64>| -> Vec<(usize, usize, f64)> {
        let mut out = Vec::new();
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                if m[(i, j)] != 0.0 {
                    out.push((i, j, m[(i, j)]));
                }
            }
        }
        out
    };
    let c_s_sparse = sparse(&c_s);
    let k_s_sparse = sparse(&k_s);
    // B⁻¹ a_w for each tyre (tyre-major, length d each), and H = A B⁻¹ Aᵀ.
    let mut b_inv_a = vec![0.0; t_count * d];
    for (w, t) in tyres.iter().enumerate() {
        dense::mat_vec(
            &b_inv_flat,
            &t.coupling,
            &mut b_inv_a[w * d..(w + 1) * d],
            d,
            d,
        );
    }
    let mut h_matrix = vec![0.0; t_count * t_count];
    for w in 0..t_count {
        for w2 in 0..t_count {
            h_matrix[w * t_count + w2] =
                dense::dot(&tyres[w].coupling, &b_inv_a[w2 * d..(w2 + 1) * d]);
        }
    }
    let e_coef: Vec<f64> = tyres
        .iter()
        .map(|t| t.stiffness * bdt2 + t.damping * gdt)
        .collect();
    // (I + E H)⁻¹: the T × T matrix while no tyre is on the deck.
    let off_deck_inverse = {
        let mut m = DMatrix::<f64>::identity(t_count, t_count);
        for w in 0..t_count {
            for w2 in 0..t_count {
                m[(w, w2)] += e_coef[w] * h_matrix[w * t_count + w2];
            }
        }
        let inv = m
            .try_inverse()
            .ok_or_else(|| invalid("tyre system on a rigid road is singular"))?;
        flat(&inv)
    };
    let mut rhs_off = vec![0.0; t_count];

    let h_coef: Vec<f64> = tyres.iter().map(|t| t.damping * v * bdt2).collect();

    // Modal constants.
    let omega: Vec<f64> = basis.modes.iter().map(|m| m.circular_frequency).collect();
    let two_zeta_omega: Vec<f64> = basis
        .modes
        .iter()
        .map(|m| 2.0 * m.damping_ratio * m.circular_frequency)
        .collect();
    let omega2: Vec<f64> = omega.iter().map(|w| w * w).collect();
    let d_inv: Vec<f64> = (0..n)
        .map(|k| 1.0 / (1.0 + gdt * two_zeta_omega[k] + bdt2 * omega2[k]))
        .collect();

    // State.
    let mut q = vec![0.0; n];
    let mut qd = vec![0.0; n];
    let mut qdd = vec![0.0; n];
    let mut z = vec![0.0; d];
    let mut zd = vec![0.0; d];
    let mut zdd = vec![0.0; d];

    // Static equilibrium on the road at the start: K_v Z₀ = Σ k_w a_w r_w (bridge at rest).
    let x0 = crossing.start_position;
    if d > 0 {
        let mut rhs = DVector::zeros(d);
        for t in &tyres {
            let (r, _) = crossing.road.elevation_and_slope(t.track, x0 + t.offset);
            for i in 0..d {
                rhs[i] += t.stiffness * t.coupling[i] * r;
            }
        }
        if rhs.iter().any(|&x| x != 0.0) {
            let z0 = vehicle
                .stiffness_matrix
                .clone()
                .lu()
                .solve(&rhs)
                .ok_or_else(|| invalid("stiffness matrix is singular: no static equilibrium"))?;
            z.copy_from_slice(z0.as_slice());
        }
    }

    // Records.
    let mut rec_x = Vec::with_capacity(step_count);
    let mut rec_q = Vec::with_capacity(step_count * n);
    let mut rec_qd = Vec::with_capacity(step_count * n);
    let mut rec_p = Vec::with_capacity(step_count * contact_count);
    let mut rec_z = Vec::with_capacity(step_count * d);
    let mut rec_zdd = Vec::with_capacity(step_count * d);
    let mut contact_losses: Vec<ContactLoss> = Vec::new();
    let mut open_loss: Vec<Option<usize>> = vec![None; contact_count];
    let mut contact_force = vec![0.0; contact_count];
    for &(w, _, _, load) in &forces {
        contact_force[w] = load;
    }

    // Work buffers.
    let mut phi = vec![0.0; t_count * n];
    let mut psi = vec![0.0; t_count * n];
    let mut wmat = vec![0.0; t_count * n];
    let mut gmat = vec![0.0; t_count * n];
    let mut tmp_v = vec![0.0; n];
    let mut tmp_s = vec![0.0; n];
    let mut on_deck = vec![false; t_count];
    let mut p_pred = vec![0.0; t_count];
    let mut q_pred = vec![0.0; n];
    let mut v_pred = vec![0.0; n];
    let mut z_pred = vec![0.0; d];
    let mut zv_pred = vec![0.0; d];
    let mut f_q = vec![0.0; n];
    let mut f_z = vec![0.0; d];
    let mut y = vec![0.0; n];
    let mut u = vec![0.0; d];
    let mut cap = vec![0.0; t_count * t_count];
    let mut pivots = vec![0; t_count];
    let mut multipliers = vec![0.0; t_count * t_count];
    let mut gw = vec![0.0; t_count * t_count];
    let mut active: Vec<usize> = Vec::with_capacity(t_count);
    let mut s = vec![0.0; t_count];
    let mut last_exit = None;
    let mut caches: Vec<ElementCache> = (0..t_count).map(|_| ElementCache::new(n)).collect();
    // Tyres in flight (SolverOptions::tyre_separation), the road under each tyre this step, and
    // the force a tyre in flight would carry if it were pressed onto the road (negative: gap).
    let mut separated = vec![false; t_count];
    let mut road_at = vec![(0.0, 0.0); t_count];
    let mut would_be = vec![0.0; t_count];
    // First time and number of steps whose contact set did not settle.
    let mut unsettled: Option<(f64, usize)> = None;

    // One step's effective system. With (bdt2, gdt) = (0, 0) it gives the initial accelerations
    // (D = I, B = M).
    for i in 0..step_count {
        let time = i as f64 * dt;
        let x_front = x0 + v * time;
        let initial = i == 0;
        // Predictors (at i = 0 the state itself).
        let (pb, pg) = if initial { (0.0, 0.0) } else { (bdt2, gdt) };
        if initial {
            q_pred.copy_from_slice(&q);
            v_pred.copy_from_slice(&qd);
            z_pred.copy_from_slice(&z);
            zv_pred.copy_from_slice(&zd);
        } else {
            let c1 = dt * dt * (0.5 - beta);
            let c2 = dt * (1.0 - gamma);
            for k in 0..n {
                q_pred[k] = q[k] + dt * qd[k] + c1 * qdd[k];
                v_pred[k] = qd[k] + c2 * qdd[k];
            }
            for j in 0..d {
                z_pred[j] = z[j] + dt * zd[j] + c1 * zdd[j];
                zv_pred[j] = zd[j] + c2 * zdd[j];
            }
        }
        for k in 0..n {
            f_q[k] = -(two_zeta_omega[k] * v_pred[k] + omega2[k] * q_pred[k]);
        }
        // Moving forces.
        for &(_, offset, lateral, load) in &forces {
            let stencil = basis.deck.stencil(x_front + offset, lateral);
            if stencil.is_empty() {
                continue;
            }
            stencil.evaluate_many(
                &basis.deck_deflection,
                &basis.deck_slope,
                n,
                &mut tmp_v,
                &mut tmp_s,
            );
            for k in 0..n {
                f_q[k] -= load * tmp_v[k];
            }
        }
        // Tyres: predicted forces P̃_w.
        for (w, t) in tyres.iter().enumerate() {
            let x = x_front + t.offset;
            road_at[w] = crossing.road.elevation_and_slope(t.track, x);
            // On the deck exactly where `DeckGeometry::stencil` has terms.
            on_deck[w] =
                (0.0..=deck_length).contains(&x) && t.weights.iter().any(|&(_, l)| l != 0.0);
            if on_deck[w] {
                let (pw, sw) = (&mut phi[w * n..(w + 1) * n], &mut psi[w * n..(w + 1) * n]);
                let cached = caches[w].evaluate(
                    &basis.deck,
                    &t.weights,
                    &basis.deck_deflection,
                    &basis.deck_slope,
                    n,
                    x,
                    pw,
                    sw,
                );
                if !cached {
                    let stencil = basis.deck.stencil(x, t.lateral);
                    stencil.evaluate_many(&basis.deck_deflection, &basis.deck_slope, n, pw, sw);
                }
            }
            let shapes = on_deck[w].then(|| (&phi[w * n..(w + 1) * n], &psi[w * n..(w + 1) * n]));
            let predicted = (&q_pred[..], &v_pred[..], &z_pred[..], &zv_pred[..]);
            let p = t.force(predicted, shapes, road_at[w], v);
            p_pred[w] = p;
            if on_deck[w] {
                let pw = &phi[w * n..(w + 1) * n];
                for k in 0..n {
                    f_q[k] -= p * pw[k];
                }
            }
        }
        // Vehicle right-hand side f_Z = −C_s ṽ − K_s Z̃ + Σ a_w (P̃_w − S_w).
        if d > 0 {
            f_z.fill(0.0);
            for &(i, j, c) in &c_s_sparse {
                f_z[i] -= c * zv_pred[j];
            }
            for &(i, j, k) in &k_s_sparse {
                f_z[i] -= k * z_pred[j];
            }
            for (w, t) in tyres.iter().enumerate() {
                let dp = p_pred[w] - t.static_load;
                for &(j, f) in &t.coupling_sparse {
                    f_z[j] += f * dp;
                }
            }
        }
        // y = D⁻¹ f_q; u = B⁻¹ f_Z (or M⁻¹ at the first instant).
        for k in 0..n {
            let dk = if initial { 1.0 } else { d_inv[k] };
            y[k] = dk * f_q[k];
        }
        if d > 0 {
            let inv = if initial { &m_inv_flat } else { &b_inv_flat };
            dense::mat_vec(inv, &f_z, &mut u, d, d);
        }
        // Tyre-force increments s from the T × T system (none at the first instant, where
        // βΔt² = γΔt = 0 makes every coefficient vanish).
        let any_on_deck = on_deck.iter().any(|&o| o);
        active.clear();
        if !initial && t_count > 0 && any_on_deck {
            // For the m tyres on the deck (compressed to i = 0..m): W_i = D⁻¹ φ_i (columns of an
            // n × m matrix) and g_i = e_i φ_i + h_i ψ_i (the row of ∂P_i/∂a_q, stored as
            // the rows of an m × n column-major matrix), then G·W; one fused pass per tyre writes W_i and g_i and forms g_i·y.
            active.extend((0..t_count).filter(|&w| on_deck[w]));
            let m = active.len();
            for (i, &w) in active.iter().enumerate() {
                let (ew, hw) = (e_coef[w], h_coef[w]);
                let (pw, sw) = (&phi[w * n..(w + 1) * n], &psi[w * n..(w + 1) * n]);
                let dst = &mut wmat[i * n..(i + 1) * n];
                // g_i·y for the right-hand side, in the same pass.
                let mut gy = 0.0;
                for (k, ((((o, p), sl), di), yk)) in dst
                    .iter_mut()
                    .zip(pw)
                    .zip(sw)
                    .zip(&d_inv)
                    .zip(&y)
                    .enumerate()
                {
                    *o = di * p;
                    let g = ew * p + hw * sl;
                    gmat[k * m + i] = g;
                    gy += g * yk;
                }
                rhs_off[i] = gy;
            }
            // G·W by one small GEMM (matrixmultiply, with its run-time SIMD kernels).
            {
                let g_view = nalgebra::DMatrixView::from_slice(&gmat[..m * n], m, n);
                let w_view = nalgebra::DMatrixView::from_slice(&wmat[..m * n], n, m);
                let mut gw_view = nalgebra::DMatrixViewMut::from_slice(&mut gw[..m * m], m, m);
                gw_view.gemm(1.0, &g_view, &w_view, 0.0);
            }
        }
        // Active set of the tyres in flight: solve with the current set; a tyre in contact
        // whose force came out tensile leaves the road, a tyre in flight whose would-be contact
        // force came out compressive lands; repeat until the set holds (a few passes at most).
        let mut passes = 0;
        loop {
            let any_separated = separated.iter().any(|&f| f);
            s.fill(0.0);
            if !initial && t_count > 0 && !any_on_deck && !any_separated {
                // Every tyre on the rigid road: the T × T matrix is the constant I + E H.
                for w in 0..t_count {
                    rhs_off[w] = -e_coef[w] * sparse_dot(&tyres[w].coupling_sparse, &u);
                }
                dense::mat_vec(&off_deck_inverse, &rhs_off, &mut s, t_count, t_count);
            } else if !initial && t_count > 0 {
                let m = active.len();
                for w in 0..t_count {
                    let ew = e_coef[w];
                    s[w] = -ew * sparse_dot(&tyres[w].coupling_sparse, &u);
                    for w2 in 0..t_count {
                        cap[w * t_count + w2] =
                            ew * h_matrix[w * t_count + w2] + if w == w2 { 1.0 } else { 0.0 };
                    }
                }
                for (i, &w) in active.iter().enumerate() {
                    s[w] += rhs_off[i];
                    for (j, &w2) in active.iter().enumerate() {
                        cap[w * t_count + w2] += gw[j * m + i];
                    }
                }
                // A tyre in flight carries no force: P_w = P̃_w + s_w = 0.
                for w in (0..t_count).filter(|&w| separated[w]) {
                    cap[w * t_count..(w + 1) * t_count].fill(0.0);
                    cap[w * t_count + w] = 1.0;
                    s[w] = -p_pred[w];
                }
                if !dense::lu_factor(&mut cap, &mut pivots, &mut multipliers, t_count) {
                    return Err(SolverError::SingularSystem { time });
                }
                dense::lu_solve(&cap, &pivots, &multipliers, &mut s, t_count);
            }
            // Accelerations a_q = y − D⁻¹Φᵀ s, a_Z = u + B⁻¹Aᵀ s.
            qdd.copy_from_slice(&y);
            for (i, &w) in active.iter().enumerate() {
                if s[w] != 0.0 {
                    let col = &wmat[i * n..(i + 1) * n];
                    for k in 0..n {
                        qdd[k] -= col[k] * s[w];
                    }
                }
            }
            zdd.copy_from_slice(&u);
            for w in 0..t_count {
                if s[w] != 0.0 {
                    let col = &b_inv_a[w * d..(w + 1) * d];
                    for j in 0..d {
                        zdd[j] += col[j] * s[w];
                    }
                }
            }
            for k in 0..n {
                q[k] = q_pred[k] + pb * qdd[k];
                qd[k] = v_pred[k] + pg * qdd[k];
            }
            for j in 0..d {
                z[j] = z_pred[j] + pb * zdd[j];
                zd[j] = zv_pred[j] + pg * zdd[j];
            }
            if initial || !options.tyre_separation {
                break;
            }
            // The would-be force of every tyre in flight, from this pass's final state.
            for (w, t) in tyres.iter().enumerate().filter(|&(w, _)| separated[w]) {
                let state = (&q[..], &qd[..], &z[..], &zd[..]);
                let shapes =
                    on_deck[w].then(|| (&phi[w * n..(w + 1) * n], &psi[w * n..(w + 1) * n]));
                would_be[w] = t.force(state, shapes, road_at[w], v);
            }
            if passes >= MAX_CONTACT_PASSES {
                // The set did not settle: keep this pass.
                unsettled.get_or_insert((time, 0)).1 += 1;
                break;
            }
            // Tyres in flight whose would-be force is compressive land; tyres in contact whose
            // force is tensile lift off.
            let mut changed = false;
            for w in 0..t_count {
                let lands = separated[w] && would_be[w] > 0.0;
                let lifts = !separated[w] && p_pred[w] + s[w] < 0.0;
                if lands || lifts {
                    separated[w] = !separated[w];
                    changed = true;
                }
            }
            if !changed {
                break;
            }
            passes += 1;
        }
        // Contact forces and loss of contact.
        for (w, t) in tyres.iter().enumerate() {
            // In flight: no force, and the loss is measured by the would-be (tensile) force.
            let (p, lost, measure) = if separated[w] {
                (0.0, true, would_be[w])
            } else {
                let p = p_pred[w] + s[w];
                (p, p < 0.0, p)
            };
            contact_force[t.contact] = p;
            match (lost, open_loss[t.contact]) {
                (true, None) => {
                    open_loss[t.contact] = Some(contact_losses.len());
                    contact_losses.push(ContactLoss {
                        contact: t.contact,
                        start_time: time,
                        end_time: time,
                        minimum_force: measure,
                    });
                }
                (true, Some(idx)) => {
                    let loss = &mut contact_losses[idx];
                    loss.minimum_force = loss.minimum_force.min(measure);
                    loss.end_time = time;
                }
                (false, Some(idx)) => {
                    contact_losses[idx].end_time = time;
                    open_loss[t.contact] = None;
                }
                (false, None) => {}
            }
        }
        if last_exit.is_none() && x_front + last_offset > deck_length {
            last_exit = Some(i);
        }
        // Record.
        rec_x.push(x_front);
        rec_q.extend_from_slice(&q);
        rec_qd.extend_from_slice(&qd);
        rec_p.extend_from_slice(&contact_force);
        rec_z.extend_from_slice(&z);
        rec_zdd.extend_from_slice(&zdd);
        if !q[0].is_finite()
            || s.iter().any(|x| !x.is_finite())
            || zdd.iter().any(|x| !x.is_finite())
        {
            return Err(SolverError::NonFinite { time });
        }
    }
    if let Some(k) = rec_q.iter().position(|x| !x.is_finite()) {
        return Err(SolverError::NonFinite {
            time: (k / n) as f64 * dt,
        });
    }
    if let Some((first_time, steps)) = unsettled {
        warnings.push(SolverWarning::ContactSetUnsettled {
            first_time,
            steps,
            passes: MAX_CONTACT_PASSES,
        });
    }

    Ok(ResponseHistory {
        time_step: dt,
        step_count,
        mode_count: n,
        speed: v,
        newmark: (beta, gamma),
        front_axle_position: rec_x,
        modal_displacement: rec_q,
        modal_velocity: rec_qd,
        contacts: vehicle
            .contacts
            .iter()
            .map(|c| ContactPath {
                longitudinal_offset: c.longitudinal_offset,
                lateral_position: crossing.lateral_position + c.lateral_offset,
                static_load: c.static_load,
            })
            .collect(),
        contact_force: rec_p,
        vehicle_dof_names: vehicle.dof_names.clone(),
        vehicle_displacement: rec_z,
        vehicle_acceleration: rec_zdd,
        exit_step: last_exit.unwrap_or(step_count - 1),
        contact_losses,
        warnings,
    })
}

#[cfg(test)]
mod tests;
