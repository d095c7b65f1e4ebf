//! Set-up of a crossing: everything that is computed once before stepping — validation, the
//! time grid and its warnings, the contacts, the modal constants Dₖ, the suspension matrix B
//! inverted once, the tyre couplings, and the static equilibrium the vehicle starts from.

use std::ops::Range;

use nalgebra::{DMatrix, DVector};

use super::dense;
use super::kinematics::ContactKinematics;
use super::newmark::NewmarkConstants;
use super::pitching::add_pitch_moments;
use super::stacked::StackedVehicles;
use super::time_step::{choose_time_step, instant_count};
use super::tyre::{prepare_contacts, MovingForce, Tyre};
use super::validation::validate;
use super::{Crossing, SolverError, SolverOptions, SolverWarning};
use crate::modal::ModalBasis;
use crate::units::metres_per_second_to_kmh;
use crate::vehicle::VehicleModel;

/// The constants of a crossing, computed once.
pub(super) struct Setup {
    /// Newmark β, γ, Δt and their products.
    pub(super) newmark: NewmarkConstants,
    /// Number of recorded instants (time steps + 1).
    pub(super) instant_count: usize,
    /// Warnings known before stepping (under-resolved modes or road).
    pub(super) warnings: Vec<SolverWarning>,
    /// The vehicles stacked into one model, and where each contact runs.
    pub(super) traffic: StackedVehicles,
    /// The motion law of the contacts.
    pub(super) kinematics: ContactKinematics,
    /// The tyres, in the vehicle's order.
    pub(super) tyres: Vec<Tyre>,
    /// The moving forces, in the vehicle's order.
    pub(super) forces: Vec<MovingForce>,
    /// The modal constants.
    pub(super) modal: ModalConstants,
    /// The vehicles' constant matrices (one block per vehicle) and the tyres' couplings.
    pub(super) vehicle: VehicleConstants,
    /// Vehicle displacements Z₀ of the static equilibrium on the road at t = 0.
    pub(super) initial_vehicle_displacement: Vec<f64>,
}

impl Setup {
    /// Validates the inputs and computes the constants of the crossing. The checks run in a
    /// fixed order (inputs, time step, stability, start position, run length, vehicle
    /// matrices, static equilibrium), so a given input always gives the same error.
    pub(super) fn new(
        basis: &ModalBasis,
        crossing: &Crossing,
        options: &SolverOptions,
    ) -> Result<Setup, SolverError> {
        validate(basis, crossing, options)?;
        let traffic = StackedVehicles::new(crossing);
        let (n, d) = (basis.mode_count(), traffic.dof_count());
        let (time_step, mut warnings) = choose_time_step(basis, crossing, options)?;
        warnings.extend(speed_changes_without_pitch(crossing));
        let newmark = NewmarkConstants::new(options.newmark_beta, options.newmark_gamma, time_step);
        let kinematics = ContactKinematics::new(crossing, &traffic.placements, basis.deck.length);
        let exit_time = kinematics.exit_time()?;
        // The history's own values, and the four per station that the DAF analysis derives from
        // it at every step (the static and dynamic deflection and moment): a 500-span beam
        // recorded little itself but its analysis asked for 40 GB (issue 17, defect 3).
        let values_per_step =
            3 * n + 2 * traffic.contacts.len() + 2 * d + 1 + 4 * basis.stations.len();
        let instant_count = instant_count(basis, crossing, exit_time, time_step, values_per_step)?;
        let (tyres, forces) = prepare_contacts(&traffic);
        let vehicle_constants = VehicleConstants::new(crossing, &traffic, &tyres, &newmark)?;
        let modal = ModalConstants::new(basis, &newmark, options);
        let initial_vehicle_displacement =
            static_equilibrium(&traffic, &tyres, &kinematics, crossing)?;
        Ok(Setup {
            traffic,
            newmark,
            instant_count,
            warnings,
            kinematics,
            tyres,
            forces,
            modal,
            vehicle: vehicle_constants,
            initial_vehicle_displacement,
        })
    }
}

/// The constants of the modes k = 1…N: q̈ₖ + 2ζₖωₖ q̇ₖ + ωₖ² qₖ = fₖ (Eq. 20 projected on the
/// mass-normalised modes), and the inverse diagonal of the bridge block of the effective matrix
/// of Eq. 29, Dₖ = 1 + 2ζₖωₖ γΔt + ωₖ² βΔt².
pub(super) struct ModalConstants {
    /// 2ζₖωₖ [1/s].
    pub(super) two_zeta_omega: Vec<f64>,
    /// ωₖ² [1/s²].
    pub(super) omega_squared: Vec<f64>,
    /// 1/Dₖ [-].
    pub(super) d_inv: Vec<f64>,
    /// βₖΔt² [s²] of each mode's corrector ([`modal_newmark_beta`]).
    pub(super) beta_dt2: Vec<f64>,
    /// Δt²(½ − βₖ) [s²] of each mode's displacement predictor.
    pub(super) displacement_predictor: Vec<f64>,
}

impl ModalConstants {
    fn new(
        basis: &ModalBasis,
        newmark: &NewmarkConstants,
        options: &SolverOptions,
    ) -> ModalConstants {
        let (dt, gdt) = (newmark.time_step, newmark.gamma_dt);
        let omega: Vec<f64> = basis.modes.iter().map(|m| m.circular_frequency).collect();
        let two_zeta_omega: Vec<f64> = basis
            .modes
            .iter()
            .map(|m| 2.0 * m.damping_ratio * m.circular_frequency)
            .collect();
        let omega_squared: Vec<f64> = omega.iter().map(|w| w * w).collect();
        let beta: Vec<f64> = omega
            .iter()
            .map(|&w| modal_newmark_beta(options, dt, w))
            .collect();
        let beta_dt2: Vec<f64> = beta.iter().map(|b| b * dt * dt).collect();
        let displacement_predictor: Vec<f64> = beta.iter().map(|b| dt * dt * (0.5 - b)).collect();
        let d_inv: Vec<f64> = (0..basis.mode_count())
            .map(|k| 1.0 / (1.0 + gdt * two_zeta_omega[k] + beta_dt2[k] * omega_squared[k]))
            .collect();
        ModalConstants {
            two_zeta_omega,
            omega_squared,
            d_inv,
            beta_dt2,
            displacement_predictor,
        }
    }
}

/// The largest ωΔt [rad] of a mode whose β is period-matched ([`modal_newmark_beta`]): four
/// steps per period. Above it a mode keeps the scheme's β (average acceleration by default,
/// unconditionally stable), as a mode that the step does not resolve responds quasi-statically.
pub const PERIOD_MATCHED_LIMIT: f64 = std::f64::consts::FRAC_PI_2;

/// Newmark's β for a bridge mode of circular frequency ω [rad/s]. With γ = ½ the scheme's
/// free vibration of an undamped mode has the discrete frequency Ω̄ of
/// cos(Ω̄Δt) = 1 − (ωΔt)²/(2(1 + β(ωΔt)²)) (Hughes, *The Finite Element Method*, 2000, §9.3;
/// average acceleration β = ¼ lengthens the period by (ωΔt)²/12). The β of
///
///   βₖ = 1/(4 sin²(x/2)) − 1/x²,   x = ωₖΔt,
///
/// makes Ω̄ = ω exactly (β → 1/12 as x → 0: Fox–Goodwin's fourth-order scheme): the free
/// vibration of every resolved mode keeps its phase over the whole crossing, where the period
/// error of β = ¼ accumulates to ω t (ωΔt)²/12 rad at time t (0.35 rad for a 32 Hz mode after
/// 0.5 s at Δt = 1 ms, issue 46). Taken when `options.period_matched_modes`, γ = ½ and β = ¼ (the defaults)
/// and x ≤ [`PERIOD_MATCHED_LIMIT`], where it lies from 1/12 to 0.0947 and the scheme, stable
/// for x < 1/√(¼ − βₖ) (≥ 2.449), has a margin of 1.56 at least; otherwise the scheme's β.
pub fn modal_newmark_beta(options: &SolverOptions, time_step: f64, omega: f64) -> f64 {
    let x = omega * time_step;
    let default_scheme = options.newmark_beta == 0.25 && options.newmark_gamma == 0.5;
    if !(options.period_matched_modes && default_scheme && x > 0.0 && x <= PERIOD_MATCHED_LIMIT) {
        return options.newmark_beta;
    }
    if x < 1.0e-2 {
        // The series 1/12 + x²/240 + O(x⁴): the closed form cancels 1/x² against itself.
        1.0 / 12.0 + x * x / 240.0
    } else {
        let half_sine = (0.5 * x).sin();
        1.0 / (4.0 * half_sine * half_sine) - 1.0 / (x * x)
    }
}

/// The vehicles' constant matrices (Eq. 19, M_v Z̈ + C_v Ż + K_v Z = Σ_w a_w [k_w (Y_w + r_w) +
/// c_w (Ẏ_w + r′_w v)], DOFs Z from static equilibrium, upwards positive, C_v and K_v holding
/// the tyres on a rigid road) and the tyres' couplings, for the elimination of the vehicles'
/// accelerations: with the suspension alone (C_s = C_v − Σ c_w a_w a_wᵀ, K_s likewise),
/// B = M_v + γΔt C_s + βΔt² K_s is constant and inverted once, and a_Z = B⁻¹(f_Z + Aᵀ s) for
/// the tyre-force increments s. Vehicles interact only through the bridge, so B, B⁻¹ and
/// H = A B⁻¹ Aᵀ are block-diagonal: each vehicle keeps its own blocks ([`VehicleBlock`]), and
/// no matrix over all the vehicles' DOFs or tyres is formed.
pub(super) struct VehicleConstants {
    /// Number of vehicle DOFs d (all vehicles).
    pub(super) dof_count: usize,
    /// C_s as (row, column, value) of its non-zero entries, stacked DOFs (springs join a few
    /// DOFs); the indices as u32 (16-byte entries, a sixth fewer bytes to stream every step
    /// than with usize; [`VehicleConstants::new`] refuses more DOFs than u32 counts).
    pub(super) suspension_damping: Vec<(u32, u32, f64)>,
    /// K_s likewise.
    pub(super) suspension_stiffness: Vec<(u32, u32, f64)>,
    /// e_w = k_w βΔt² + c_w γΔt for each tyre: −∂P_w/∂(a_w·a_Z).
    pub(super) e_coef: Vec<f64>,
    /// Each vehicle's blocks, in the crossing's order.
    pub(super) blocks: Vec<VehicleBlock>,
    /// The largest number of tyres of one vehicle.
    pub(super) largest_tyre_count: usize,
}

/// One vehicle's blocks of the constant matrices, over its d_v DOFs and its T_v tyres.
pub(super) struct VehicleBlock {
    /// Its DOFs in the stacked numbering.
    pub(super) dofs: Range<usize>,
    /// Its tyres in the stacked tyre order.
    pub(super) tyres: Range<usize>,
    /// B_v⁻¹, row-major d_v × d_v.
    pub(super) b_inv: Vec<f64>,
    /// M_v⁻¹, row-major d_v × d_v (the initial accelerations).
    pub(super) m_inv: Vec<f64>,
    /// B_v⁻¹ a_w for each of its tyres (tyre-major, length d_v each).
    pub(super) b_inv_a: Vec<f64>,
    /// H_v = A_v B_v⁻¹ A_vᵀ, row-major T_v × T_v.
    pub(super) h_matrix: Vec<f64>,
    /// (I + E_v H_v)⁻¹, row-major T_v × T_v: its tyre system while none of its tyres is on the
    /// deck (constant).
    pub(super) off_deck_inverse: Vec<f64>,
}

impl VehicleConstants {
    fn new(
        crossing: &Crossing,
        traffic: &StackedVehicles,
        tyres: &[Tyre],
        newmark: &NewmarkConstants,
    ) -> Result<VehicleConstants, SolverError> {
        if u32::try_from(traffic.dof_count()).is_err() {
            return Err(SolverError::InvalidCrossing {
                name: "vehicle DOFs in all",
                value: traffic.dof_count() as f64,
                reason: "at most 2^32 - 1 vehicle DOFs in one crossing",
            });
        }
        let e_coef: Vec<f64> = tyres
            .iter()
            .map(|t| t.stiffness * newmark.beta_dt2 + t.damping * newmark.gamma_dt)
            .collect();
        let mut blocks = Vec::with_capacity(crossing.vehicles.len());
        let (mut suspension_damping, mut suspension_stiffness) = (Vec::new(), Vec::new());
        for (v, run) in crossing.vehicles.iter().enumerate() {
            // The tyres are stacked in vehicle order: each vehicle's are consecutive.
            let first = tyres.partition_point(|t| t.vehicle < v);
            let own = first..first + tyres[first..].partition_point(|t| t.vehicle == v);
            let dofs = traffic.dofs[v].clone();
            let (c_s, k_s) = suspension_matrices(&run.vehicle, &tyres[own.clone()]);
            suspension_damping.extend(non_zero_entries(&c_s, dofs.start));
            suspension_stiffness.extend(non_zero_entries(&k_s, dofs.start));
            blocks.push(VehicleBlock::new(
                &run.vehicle,
                (dofs, own),
                (&c_s, &k_s),
                (tyres, &e_coef),
                newmark,
            )?);
        }
        Ok(VehicleConstants {
            dof_count: traffic.dof_count(),
            suspension_damping,
            suspension_stiffness,
            largest_tyre_count: blocks.iter().map(|b| b.tyres.len()).max().unwrap_or(0),
            e_coef,
            blocks,
        })
    }
}

/// The suspension alone, (C_s, K_s) = (C_v, K_v) − Σ_w (c_w, k_w) a_w a_wᵀ over the vehicle's
/// own tyres (the tyres on a rigid road removed).
fn suspension_matrices(vehicle: &VehicleModel, tyres: &[Tyre]) -> (DMatrix<f64>, DMatrix<f64>) {
    let d = vehicle.dof_count();
    let mut c_s = vehicle.damping_matrix.clone();
    let mut k_s = vehicle.stiffness_matrix.clone();
    for t in tyres {
        for i in 0..d {
            for j in 0..d {
                c_s[(i, j)] -= t.damping * t.coupling[i] * t.coupling[j];
                k_s[(i, j)] -= t.stiffness * t.coupling[i] * t.coupling[j];
            }
        }
    }
    (c_s, k_s)
}

impl VehicleBlock {
    /// The blocks of one vehicle over its `dofs` and its tyres `own` (of `tyres`, with their
    /// e_w in `e_coef`), with its suspension matrices (C_s, K_s).
    fn new(
        vehicle: &VehicleModel,
        (dofs, own): (Range<usize>, Range<usize>),
        (c_s, k_s): (&DMatrix<f64>, &DMatrix<f64>),
        (tyres, e_coef): (&[Tyre], &[f64]),
        newmark: &NewmarkConstants,
    ) -> Result<VehicleBlock, SolverError> {
        let (tyres, e_coef) = (&tyres[own.clone()], &e_coef[own.clone()]);
        let d = vehicle.dof_count();
        let t_count = tyres.len();
        let b_matrix = &vehicle.mass_matrix + c_s * newmark.gamma_dt + k_s * newmark.beta_dt2;
        let b_inv = inverse(
            b_matrix,
            vehicle,
            "M + γΔt C + βΔt² K of the suspension is singular",
        )?;
        let m_inv = inverse(
            vehicle.mass_matrix.clone(),
            vehicle,
            "mass matrix is singular",
        )?;
        // B⁻¹ a_w for each tyre (tyre-major, length d each), and H = A B⁻¹ Aᵀ.
        let mut b_inv_a = vec![0.0; t_count * d];
        for (w, t) in tyres.iter().enumerate() {
            dense::mat_vec(&b_inv, &t.coupling, &mut b_inv_a[w * d..(w + 1) * d], d, d);
        }
        let mut h_matrix = vec![0.0; t_count * t_count];
        for w in 0..t_count {
            for w2 in 0..t_count {
                h_matrix[w * t_count + w2] =
                    dense::dot(&tyres[w].coupling, &b_inv_a[w2 * d..(w2 + 1) * d]);
            }
        }
        let off_deck_inverse = off_deck_inverse(vehicle, e_coef, &h_matrix)?;
        Ok(VehicleBlock {
            dofs,
            tyres: own,
            b_inv,
            m_inv,
            b_inv_a,
            h_matrix,
            off_deck_inverse,
        })
    }
}

/// The inverse of a vehicle matrix, row-major (empty for a vehicle without DOFs).
fn inverse(
    matrix: DMatrix<f64>,
    vehicle: &VehicleModel,
    reason: &str,
) -> Result<Vec<f64>, SolverError> {
    if matrix.nrows() == 0 {
        return Ok(Vec::new());
    }
    let inverse = matrix
        .try_inverse()
        .ok_or_else(|| invalid_vehicle(vehicle, reason))?;
    Ok(row_major(&inverse))
}

/// (I + E H)⁻¹ of one vehicle, row-major: its T_v × T_v tyre system while none of its tyres is on
/// the deck (constant).
fn off_deck_inverse(
    vehicle: &VehicleModel,
    e_coef: &[f64],
    h_matrix: &[f64],
) -> Result<Vec<f64>, SolverError> {
    let t_count = e_coef.len();
    let mut m = DMatrix::<f64>::identity(t_count, t_count);
    for w in 0..t_count {
        for w2 in 0..t_count {
            m[(w, w2)] += e_coef[w] * h_matrix[w * t_count + w2];
        }
    }
    let inv = m
        .try_inverse()
        .ok_or_else(|| invalid_vehicle(vehicle, "tyre system on a rigid road is singular"))?;
    Ok(row_major(&inv))
}

/// The static equilibrium of the vehicles on the road at t = 0, the bridge at rest and
/// undeflected: K_v Z₀ = Σ_w k_w a_w r_w + Σ_v s̈_v(0) g_v for each vehicle (zero on a road
/// that is flat under its tyres, for a vehicle entering at constant speed; g_v the pitch load
/// of braking and acceleration, [`super::pitching`]), solved with its own K_v.
fn static_equilibrium(
    traffic: &StackedVehicles,
    tyres: &[Tyre],
    kinematics: &ContactKinematics,
    crossing: &Crossing,
) -> Result<Vec<f64>, SolverError> {
    let mut rhs = vec![0.0; traffic.dof_count()];
    let start = kinematics.start_points(&crossing.road);
    for t in tyres {
        let (r, _) = start.road[t.contact];
        let own = &mut rhs[traffic.dofs[t.vehicle].clone()];
        for (x, a) in own.iter_mut().zip(&t.coupling) {
            *x += t.stiffness * a * r;
        }
    }
    add_pitch_moments(&mut rhs, &traffic.pitch_loads, &start.acceleration);
    let mut z = vec![0.0; rhs.len()];
    for (run, dofs) in crossing.vehicles.iter().zip(&traffic.dofs) {
        let own = &rhs[dofs.clone()];
        if own.iter().any(|&x| x != 0.0) {
            let vehicle = &run.vehicle;
            let z0 = vehicle
                .stiffness_matrix
                .clone()
                .lu()
                .solve(&DVector::from_column_slice(own))
                .ok_or_else(|| {
                    invalid_vehicle(
                        vehicle,
                        "stiffness matrix is singular: no static equilibrium",
                    )
                })?;
            z[dofs.clone()].copy_from_slice(z0.as_slice());
        }
    }
    Ok(z)
}

fn invalid_vehicle(vehicle: &VehicleModel, reason: &str) -> SolverError {
    SolverError::InvalidVehicle {
        vehicle: vehicle.name.clone(),
        reason: reason.to_string(),
    }
}

/// The entries of a matrix, row-major.
fn row_major(m: &DMatrix<f64>) -> Vec<f64> {
    let mut out = Vec::with_capacity(m.nrows() * m.ncols());
    for i in 0..m.nrows() {
        for j in 0..m.ncols() {
            out.push(m[(i, j)]);
        }
    }
    out
}

/// The non-zero entries of a vehicle's matrix as (row, column, value), with its DOFs numbered
/// from `first`: the suspension matrices are sparse, and the vehicle right-hand side is
/// evaluated every step. The entries come in rounds, the r-th non-zero of each row in round r:
/// each row's terms keep their column order (so every row sum is the same, bit for bit, as the
/// row-major sum), while consecutive terms update different rows and do not wait for each other
/// (row-major, a row's terms formed one chain of dependent additions through memory: 8 % of an
/// approach step, issue 16).
fn non_zero_entries(m: &DMatrix<f64>, first: usize) -> Vec<(u32, u32, f64)> {
    let rows: Vec<Vec<(u32, u32, f64)>> = (0..m.nrows())
        .map(|i| {
            (0..m.ncols())
                .filter(|&j| m[(i, j)] != 0.0)
                // Lossless: the stacked DOFs fit in u32 (checked by `VehicleConstants::new`).
                .map(|j| ((first + i) as u32, (first + j) as u32, m[(i, j)]))
                .collect()
        })
        .collect();
    let rounds = rows.iter().map(Vec::len).max().unwrap_or(0);
    (0..rounds)
        .flat_map(|r| rows.iter().filter_map(move |row| row.get(r).copied()))
        .collect()
}

/// A warning for each vehicle with a body (a multibody model, not moving forces) whose speed
/// changes while none of its bodies has a centre-of-mass height: braking or acceleration then
/// changes its speed alone ([`SolverWarning::SpeedChangeWithoutPitch`]).
fn speed_changes_without_pitch(crossing: &Crossing) -> Vec<SolverWarning> {
    crossing
        .vehicles
        .iter()
        .enumerate()
        .filter(|(_, run)| {
            let (lowest, highest) = (run.speed.lowest_speed(), run.speed.highest_speed());
            run.vehicle.dof_count() > 0
                && run.vehicle.pitch_load_per_acceleration.is_empty()
                && lowest != highest
        })
        .map(|(i, run)| SolverWarning::SpeedChangeWithoutPitch {
            vehicle: i + 1,
            name: run.vehicle.name.clone(),
            lowest_kmh: metres_per_second_to_kmh(run.speed.lowest_speed()),
            highest_kmh: metres_per_second_to_kmh(run.speed.highest_speed()),
        })
        .collect()
}
