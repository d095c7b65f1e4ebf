//! The right-hand sides of a step at the Newmark predictor: the predicted tyre forces P̃_w, the
//! modal loads f_q (bridge, Eq. 20) and the vehicle loads f_Z (Eq. 19, with the pitch moments
//! of braking and acceleration), and the accelerations
//! they give with no tyre-force increment, y = D⁻¹ f_q and u = B⁻¹ f_Z.

use super::dense;
use super::kinematics::ContactPoints;
use super::newmark::NewmarkState;
use super::pitching::{add_pitch_moments, PitchLoad};
use super::setup::{ModalConstants, VehicleConstants};
use super::shapes::ContactShapes;
use super::tyre::{MovingForce, Tyre};
use crate::deck::DeckReader;
use crate::modal::ModalBasis;

/// The loads of one step and their uncoupled accelerations.
pub(super) struct StepLoads<'a> {
    /// P̃_w: the force of each tyre bonded to the road at the predicted state [N].
    pub(super) predicted_force: Vec<f64>,
    /// f_q, length N.
    pub(super) modal: Vec<f64>,
    /// f_Z, length d.
    pub(super) vehicle: Vec<f64>,
    /// y = D⁻¹ f_q (M = I at the first instant).
    pub(super) modal_uncoupled: Vec<f64>,
    /// u = B⁻¹ f_Z (M_v⁻¹ f_Z at the first instant).
    pub(super) vehicle_uncoupled: Vec<f64>,
    /// The deck sums (φ·q̃, φ·ṽ, φ′·q̃) of each tyre on the deck (scratch).
    deck_sums: Vec<[f64; 3]>,
    /// Mode values at a moving force (scratch).
    force_values: Vec<f64>,
    /// Each moving force's reader of the mode shapes (its element cubic, or the stencil).
    force_readers: Vec<DeckReader<'a>>,
}

impl<'a> StepLoads<'a> {
    /// Buffers for `tyre_count` tyres, the moving `forces` on `basis`'s deck, `basis`'s modes
    /// and `dof_count` vehicle DOFs.
    pub(super) fn new(
        basis: &'a ModalBasis,
        tyre_count: usize,
        forces: &[MovingForce],
        dof_count: usize,
    ) -> StepLoads<'a> {
        let mode_count = basis.mode_count();
        StepLoads {
            predicted_force: vec![0.0; tyre_count],
            modal: vec![0.0; mode_count],
            vehicle: vec![0.0; dof_count],
            modal_uncoupled: vec![0.0; mode_count],
            vehicle_uncoupled: vec![0.0; dof_count],
            deck_sums: vec![[0.0; 3]; tyre_count],
            force_values: vec![0.0; mode_count],
            force_readers: (forces.iter())
                .map(|force| DeckReader::new(&basis.deck, force.lateral, mode_count))
                .collect(),
        }
    }

    /// P̃_w of every tyre (Eq. 25) at the predicted state of the bridge and the vehicle: where
    /// the shapes are arranged mode by mode (crossings sharing them), the deck sums of the tyres
    /// on the deck side by side ([`ContactShapes::deck_sums`]) and each tyre's force from them
    /// ([`Tyre::force_of_deck_sums`]; zero sums on a rigid road); else tyre by tyre
    /// ([`Tyre::force_at`]). The same numbers either way, bit for bit.
    #[inline]
    pub(super) fn predict_tyre_forces(
        &mut self,
        tyres: &[Tyre],
        shapes: &ContactShapes,
        points: &ContactPoints,
        bridge: &NewmarkState,
        vehicle: &NewmarkState,
    ) {
        let ((q, qd), (z, zd)) = (bridge.predicted(), vehicle.predicted());
        if !shapes.by_mode() {
            for (w, t) in tyres.iter().enumerate() {
                self.predicted_force[w] = t.force_at((q, qd, z, zd), shapes.of(w), points);
            }
            return;
        }
        let deck_tyres = shapes.deck_tyres();
        let deck_sums = &mut self.deck_sums[..deck_tyres.len()];
        shapes.deck_sums(q, qd, deck_sums);
        let mut on_deck = deck_tyres.iter().zip(deck_sums.iter()).peekable();
        for (w, t) in tyres.iter().enumerate() {
            let sums = match on_deck.next_if(|&(&d, _)| d == w) {
                Some((_, sums)) => *sums,
                None => [0.0; 3],
            };
            let (road, v) = (points.road[t.contact], points.travel_speed[t.contact]);
            self.predicted_force[w] = t.force_of_deck_sums(sums, (z, zd), road, v);
        }
    }

    /// The modal loads at the predictor (Eq. 20 projected on the modes, P_w compressive):
    /// f_q = −(2ζω ṽ + ω² q̃) − Σ_forces φ(x_w, y_w) S_w − Σ_tyres on deck φ(x_w, y_w) P̃_w,
    /// accumulated in that order.
    #[inline]
    pub(super) fn assemble_modal(
        &mut self,
        basis: &ModalBasis,
        modal: &ModalConstants,
        bridge: &NewmarkState,
        forces: &[MovingForce],
        shapes: &ContactShapes,
        points: &ContactPoints,
    ) {
        let n = self.modal.len();
        let (q_pred, v_pred) = bridge.predicted();
        let f_q = &mut self.modal;
        for k in 0..n {
            f_q[k] = -(modal.two_zeta_omega[k] * v_pred[k] + modal.omega_squared[k] * q_pred[k]);
        }
        // The mode values at a moving force by the route of a tyre's (`ContactShapes`).
        let fields = (&basis.deck_deflection[..], &basis.deck_slope[..]);
        for (force, reader) in forces.iter().zip(&mut self.force_readers) {
            let values = &mut self.force_values;
            if reader.values(fields, points.position[force.contact], values) {
                for k in 0..n {
                    f_q[k] -= force.load * values[k];
                }
            }
        }
        for (w, &p) in self.predicted_force.iter().enumerate() {
            if let Some((phi, _)) = shapes.of(w) {
                for k in 0..n {
                    f_q[k] -= p * phi[k];
                }
            }
        }
    }

    /// The vehicle loads at the predictor (Eq. 19 with the tyres' forces as loads):
    /// f_Z = −C_s ṽ − K_s Z̃ + Σ_w a_w (P̃_w − S_w).
    #[inline]
    pub(super) fn assemble_vehicle(
        &mut self,
        constants: &VehicleConstants,
        tyres: &[Tyre],
        vehicle: &NewmarkState,
    ) {
        if constants.dof_count == 0 {
            return;
        }
        let (z_pred, zv_pred) = vehicle.predicted();
        let f_z = &mut self.vehicle;
        f_z.fill(0.0);
        for &(i, j, c) in &constants.suspension_damping {
            f_z[i as usize] -= c * zv_pred[j as usize];
        }
        for &(i, j, k) in &constants.suspension_stiffness {
            f_z[i as usize] -= k * z_pred[j as usize];
        }
        for (w, t) in tyres.iter().enumerate() {
            let dp = self.predicted_force[w] - t.static_load;
            for &(j, f) in &t.coupling_sparse {
                f_z[j] += f * dp;
            }
        }
    }

    /// The pitch moments of the vehicles' braking and acceleration added to f_Z
    /// ([`super::pitching`]): f_Z += Σ_v s̈_v(t) g_v, nothing without centre-of-mass heights.
    #[inline]
    pub(super) fn add_pitch_moments(&mut self, pitch_loads: &[PitchLoad], points: &ContactPoints) {
        add_pitch_moments(&mut self.vehicle, pitch_loads, &points.acceleration);
    }

    /// y = D⁻¹ f_q and u = B⁻¹ f_Z, one vehicle block u_v = B_v⁻¹ f_Z,v at a time (B is
    /// block-diagonal: O(Σ d_v²), not O(d²)); at the first instant (βΔt² = γΔt = 0) D = I and
    /// B = M_v.
    #[inline]
    pub(super) fn uncoupled_accelerations(
        &mut self,
        modal: &ModalConstants,
        vehicle: &VehicleConstants,
        initial: bool,
    ) {
        self.uncoupled_modal_accelerations(modal, initial);
        self.uncoupled_vehicle_accelerations(vehicle, initial);
    }

    /// y = D⁻¹ f_q (M = I at the first instant).
    #[inline]
    fn uncoupled_modal_accelerations(&mut self, modal: &ModalConstants, initial: bool) {
        for k in 0..self.modal.len() {
            let dk = if initial { 1.0 } else { modal.d_inv[k] };
            self.modal_uncoupled[k] = dk * self.modal[k];
        }
    }

    /// u = B⁻¹ f_Z, one vehicle block at a time (M_v⁻¹ f_Z at the first instant).
    #[inline]
    pub(super) fn uncoupled_vehicle_accelerations(
        &mut self,
        vehicle: &VehicleConstants,
        initial: bool,
    ) {
        for block in &vehicle.blocks {
            let (dofs, d) = (block.dofs.clone(), block.dofs.len());
            let inv = if initial { &block.m_inv } else { &block.b_inv };
            let (load, acceleration) = (
                &self.vehicle[dofs.clone()],
                &mut self.vehicle_uncoupled[dofs],
            );
            dense::mat_vec(inv, load, acceleration, d, d);
        }
    }
}
