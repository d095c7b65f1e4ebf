//! The T × T system of the tyre-force increments (rank-T coupling, Schur complement of the
//! effective matrix of Eq. 29).
//!
//! With the T tyre-force increments s_w (P_w = P̃_w + s_w) as extra unknowns, the modal and
//! vehicle accelerations are eliminated analytically: a_q = D⁻¹(f_q − Φᵀ s) = y − W s with
//! W = D⁻¹Φᵀ, and a_Z = B⁻¹(f_Z + Aᵀ s) = u + B⁻¹Aᵀ s. The tyre forces are linear in the
//! accelerations, P_w = P̃_w − e_w a_w·a_Z + g_w·a_q with e_w = k_w βΔt² + c_w γΔt and
//! g_w = e_w φ_w + h_w φ′_w, h_w = c_w v βΔt² (the rows of ∂P/∂a_q, G). What remains is the
//! capacitance system
//!
//! (I + G W + E H) s = G y − E A u,   H = A B⁻¹ Aᵀ,
//!
//! where the G terms exist for the tyres on the deck only, and a tyre in flight has the row
//! s_w = −P̃_w (no force).
//!
//! H is block-diagonal over the vehicles, and G W couples the tyres on the deck only: a vehicle
//! with no tyre on the deck is coupled to nothing, and its T_v × T_v block of the system,
//! (I + E_v H_v) s_v = −E_v A_v u_v, is solved on its own — with its constant inverse, which is
//! precomputed, while all its tyres are in contact, else by its own LU. The coupled system
//! holds the tyres of the vehicles with a tyre on the deck only (all their tyres: those still
//! on the road are coupled through H_v). It is built and solved in separate steps — the on-deck
//! products W, G, G·W and G·y ([`TyreSystem::couple_deck`]), the right-hand side, the matrix,
//! its LU, the solve — so that the matrix and its LU, which depend on the tyres' positions and
//! contact set but not on the road, can be shared. Per-step cost, for m tyres on the deck and
//! T_c tyres of the vehicles they belong to: O(m·N) for W and G, O(m²·N) for G·W (one small
//! GEMM), O(T_c³) for the LU, and O(T_v²) for each vehicle off the deck: linear in modes ×
//! tyres on the deck, however many vehicles wait on the approach road or have left.

use super::contact::ContactSet;
use super::dense;
use super::kinematics::ContactPoints;
use super::setup::{ModalConstants, VehicleBlock, VehicleConstants};
use super::shapes::ContactShapes;
use super::tyre::{sparse_dot, Tyre};

/// The position-dependent part of a step's tyre system: which tyres and vehicles the deck
/// couples, the on-deck products W, G and G·W, and the LU of the coupled matrix for each contact
/// set met at this instant. It depends on the tyres' positions, the vehicles and Δt, not on the
/// road or the state: crossings that differ only in their road share it, instant by instant
/// ([`super::batch`]).
pub(super) struct DeckCoupling {
    /// Number of modes N.
    mode_count: usize,
    /// Number of tyres T of the crossing (the largest coupled system).
    tyre_count: usize,
    /// Whether each vehicle has a tyre on the deck this step (it is in the coupled system).
    coupled_vehicles: Vec<bool>,
    /// The tyres of the coupled vehicles, in tyre order: the unknowns of the coupled system.
    coupled_tyres: Vec<usize>,
    /// The tyres on the deck this step (the m tyres coupled to the modes), in tyre order, each
    /// with its row in the coupled system.
    on_deck_tyres: Vec<(usize, usize)>,
    /// W_i = D⁻¹ φ_i of the on-deck tyres: columns of an N × m matrix, column-major.
    deck_columns: Vec<f64>,
    /// g_i = e_i φ_i + h_i φ′_i of the on-deck tyres: the rows of an m × N matrix G,
    /// column-major (`force_rows[k * m + i]`).
    force_rows: Vec<f64>,
    /// G·W, m × m column-major.
    coupling_product: Vec<f64>,
    /// The coupled matrix's LU for each contact set met at this instant (in practice one: every
    /// tyre in contact): the first `factorisation_count` entries; the others are buffers kept
    /// for reuse, so that a step allocates nothing.
    factorisations: Vec<CoupledFactorisation>,
    factorisation_count: usize,
}

/// The LU of the coupled capacitance matrix for one contact set.
struct CoupledFactorisation {
    /// Whether each coupled tyre is in flight (the rows of the identity).
    in_flight: Vec<bool>,
    /// False when the matrix is singular (then `system` holds no usable factors).
    regular: bool,
    /// The factors (U, pivots, multipliers).
    system: DenseSystem,
}

impl CoupledFactorisation {
    /// A placeholder without buffers.
    fn empty() -> CoupledFactorisation {
        CoupledFactorisation {
            in_flight: Vec::new(),
            regular: false,
            system: DenseSystem::new(0),
        }
    }
}

/// The per-crossing part of a step's tyre system: the right-hand sides, a vehicle's own system
/// and the solution.
pub(super) struct TyreSystem {
    /// g_i·y of the on-deck tyres.
    deck_rhs: Vec<f64>,
    /// The coupled right-hand side, then its solution.
    coupled_solution: Vec<f64>,
    /// One vehicle's own system (a vehicle off the deck).
    own: DenseSystem,
    /// The tyre-force increments s of every tyre [N].
    increments: Vec<f64>,
}

/// A square system solved by [`dense::lu_factor`] and [`dense::lu_solve`], in buffers sized for
/// the largest one.
struct DenseSystem {
    /// Its size m.
    size: usize,
    /// The matrix, row-major m × m; U of its LU after [`DenseSystem::factor_and_solve`].
    matrix: Vec<f64>,
    /// Row swaps of the LU.
    pivots: Vec<usize>,
    /// Elimination multipliers of the LU, per stage.
    multipliers: Vec<f64>,
    /// The right-hand side, then the solution.
    solution: Vec<f64>,
}

impl DenseSystem {
    fn new(largest: usize) -> DenseSystem {
        DenseSystem {
            size: 0,
            matrix: vec![0.0; largest * largest],
            pivots: vec![0; largest],
            multipliers: vec![0.0; largest * largest],
            solution: vec![0.0; largest],
        }
    }

    /// LU factorisation in place and solve (the right-hand side in place); false if singular.
    fn factor_and_solve(&mut self) -> bool {
        if !self.factor() {
            return false;
        }
        let m = self.size;
        let (matrix, multipliers) = (&self.matrix[..m * m], &self.multipliers[..m * m]);
        dense::lu_solve(
            matrix,
            &self.pivots[..m],
            multipliers,
            &mut self.solution[..m],
            m,
        );
        true
    }

    /// LU factorisation of the matrix in place; false if singular.
    fn factor(&mut self) -> bool {
        let m = self.size;
        let (matrix, multipliers) = (&mut self.matrix[..m * m], &mut self.multipliers[..m * m]);
        dense::lu_factor(matrix, &mut self.pivots[..m], multipliers, m)
    }

    /// Solves with the factors of [`DenseSystem::factor`], `rhs` (length m) in place.
    fn solve(&self, rhs: &mut [f64]) {
        let m = self.size;
        dense::lu_solve(
            &self.matrix[..m * m],
            &self.pivots[..m],
            &self.multipliers[..m * m],
            rhs,
            m,
        );
    }

    /// The row of tyre `local` of a vehicle block, starting at column `first_column`:
    /// e_w H_v row + the identity (the other vehicles' columns are left as they are).
    fn set_block_row(
        &mut self,
        row: usize,
        first_column: usize,
        block: &VehicleBlock,
        local: usize,
        e_w: f64,
    ) {
        let (m, t_v) = (self.size, block.tyres.len());
        let h_row = &block.h_matrix[local * t_v..(local + 1) * t_v];
        let row = &mut self.matrix[row * m + first_column..row * m + first_column + t_v];
        for (c, (x, h)) in row.iter_mut().zip(h_row).enumerate() {
            *x = e_w * h + if c == local { 1.0 } else { 0.0 };
        }
    }

    /// The row of a tyre in flight: that of the identity (P_w = P̃_w + s_w = 0).
    fn set_identity_row(&mut self, row: usize) {
        let m = self.size;
        self.matrix[row * m..(row + 1) * m].fill(0.0);
        self.matrix[row * m + row] = 1.0;
    }
}

impl DeckCoupling {
    /// Buffers for the tyres of `constants` and `mode_count` modes.
    pub(super) fn new(constants: &VehicleConstants, mode_count: usize) -> DeckCoupling {
        let (t, n) = (constants.e_coef.len(), mode_count);
        DeckCoupling {
            mode_count: n,
            tyre_count: t,
            coupled_vehicles: vec![false; constants.blocks.len()],
            coupled_tyres: Vec::with_capacity(t),
            on_deck_tyres: Vec::with_capacity(t),
            deck_columns: vec![0.0; t * n],
            force_rows: vec![0.0; t * n],
            coupling_product: vec![0.0; t * t],
            factorisations: Vec::new(),
            factorisation_count: 0,
        }
    }

    /// A placeholder without buffers.
    pub(super) fn empty() -> DeckCoupling {
        DeckCoupling {
            mode_count: 0,
            tyre_count: 0,
            coupled_vehicles: Vec::new(),
            coupled_tyres: Vec::new(),
            on_deck_tyres: Vec::new(),
            deck_columns: Vec::new(),
            force_rows: Vec::new(),
            coupling_product: Vec::new(),
            factorisations: Vec::new(),
            factorisation_count: 0,
        }
    }

    /// Starts an instant with no tyre coupled to the modes and no factorisation.
    #[inline]
    pub(super) fn uncouple_deck(&mut self) {
        self.coupled_vehicles.fill(false);
        self.coupled_tyres.clear();
        self.on_deck_tyres.clear();
        self.factorisation_count = 0;
    }

    /// The vehicles with a tyre on the deck, their tyres (the coupled system's unknowns) and
    /// the tyres on the deck with their rows.
    fn select_coupled(&mut self, constants: &VehicleConstants, shapes: &ContactShapes) {
        self.uncouple_deck();
        for (v, block) in constants.blocks.iter().enumerate() {
            if !block.tyres.clone().any(|w| shapes.is_on_deck(w)) {
                continue;
            }
            self.coupled_vehicles[v] = true;
            for w in block.tyres.clone() {
                if shapes.is_on_deck(w) {
                    self.on_deck_tyres.push((w, self.coupled_tyres.len()));
                }
                self.coupled_tyres.push(w);
            }
        }
    }

    /// The on-deck products of the step, for the m tyres on the deck: W_i = D⁻¹ φ_i and the
    /// tyre force's sensitivity to each mode's acceleration,
    /// g_ik = (k_i βₖΔt² + c_i γΔt) φ_ik + c_i v_i βₖΔt² φ′_ik (v_i the tyre's speed of travel,
    /// βₖ the mode's own β: [`super::modal_newmark_beta`]), then G·W by one small GEMM
    /// (matrixmultiply, with its run-time SIMD kernels); and the vehicles they couple.
    #[inline]
    pub(super) fn couple_deck(
        &mut self,
        tyres: &[Tyre],
        shapes: &ContactShapes,
        points: &ContactPoints,
        constants: &VehicleConstants,
        modal: &ModalConstants,
        gamma_dt: f64,
    ) {
        let n = self.mode_count;
        self.select_coupled(constants, shapes);
        let m = self.on_deck_tyres.len();
        for (i, &(w, _)) in self.on_deck_tyres.iter().enumerate() {
            let t = &tyres[w];
            let damping_dt = t.damping * gamma_dt;
            let travelling_damping = t.damping * points.travel_speed[t.contact];
            let Some((pw, sw)) = shapes.of(w) else {
                unreachable!("tyre {w} is on the deck")
            };
            let dst = &mut self.deck_columns[i * n..(i + 1) * n];
            let columns = dst.iter_mut().zip(pw).zip(sw);
            let constants_k = modal.d_inv.iter().zip(&modal.beta_dt2);
            for (k, (((o, p), sl), (di, bdt2))) in columns.zip(constants_k).enumerate() {
                *o = di * p;
                self.force_rows[k * m + i] =
                    (t.stiffness * bdt2 + damping_dt) * p + travelling_damping * bdt2 * sl;
            }
        }
        let g_view = nalgebra::DMatrixView::from_slice(&self.force_rows[..m * n], m, n);
        let w_view = nalgebra::DMatrixView::from_slice(&self.deck_columns[..m * n], n, m);
        let mut gw_view =
            nalgebra::DMatrixViewMut::from_slice(&mut self.coupling_product[..m * m], m, m);
        gw_view.gemm(1.0, &g_view, &w_view, 0.0);
    }

    /// Whether any tyre is coupled (some vehicle has a tyre on the deck).
    #[inline]
    fn has_coupled_tyres(&self) -> bool {
        !self.coupled_tyres.is_empty()
    }

    /// The LU of the coupled matrix for `contact_set`: the one already computed at this instant
    /// for the same set, else assembled ([`DeckCoupling::assemble_matrix`]) and factorised.
    fn factorisation(
        &mut self,
        tyres: &[Tyre],
        constants: &VehicleConstants,
        contact_set: &ContactSet,
    ) -> &CoupledFactorisation {
        let same_set = |f: &CoupledFactorisation| {
            f.in_flight
                .iter()
                .zip(&self.coupled_tyres)
                .all(|(&flight, &w)| flight == contact_set.is_in_flight(w))
        };
        let count = self.factorisation_count;
        if let Some(found) = self.factorisations[..count].iter().position(same_set) {
            return &self.factorisations[found];
        }
        if count == self.factorisations.len() {
            self.factorisations.push(CoupledFactorisation {
                in_flight: Vec::with_capacity(self.tyre_count),
                regular: false,
                system: DenseSystem::new(self.tyre_count),
            });
        }
        let mut entry = std::mem::replace(
            &mut self.factorisations[count],
            CoupledFactorisation::empty(),
        );
        self.assemble_matrix(&mut entry.system, tyres, constants, contact_set);
        entry.regular = entry.system.factor();
        entry.in_flight.clear();
        let flights = self
            .coupled_tyres
            .iter()
            .map(|&w| contact_set.is_in_flight(w));
        entry.in_flight.extend(flights);
        self.factorisations[count] = entry;
        self.factorisation_count = count + 1;
        &self.factorisations[count]
    }

    /// The coupled capacitance matrix I + E H + G W: each vehicle's block of E H on the
    /// diagonal, zero between vehicles, G W between the tyres on the deck; the row of a tyre
    /// in flight is that of the identity (P_w = P̃_w + s_w = 0).
    #[inline]
    fn assemble_matrix(
        &self,
        system: &mut DenseSystem,
        tyres: &[Tyre],
        constants: &VehicleConstants,
        contact_set: &ContactSet,
    ) {
        let m = self.coupled_tyres.len();
        system.size = m;
        system.matrix[..m * m].fill(0.0);
        for (i, &w) in self.coupled_tyres.iter().enumerate() {
            let block = &constants.blocks[tyres[w].vehicle];
            let local = w - block.tyres.start;
            // A coupled vehicle's tyres are consecutive unknowns: its first is at i − local.
            system.set_block_row(i, i - local, block, local, constants.e_coef[w]);
        }
        let deck_count = self.on_deck_tyres.len();
        for (i, &(_, row)) in self.on_deck_tyres.iter().enumerate() {
            for (j, &(_, column)) in self.on_deck_tyres.iter().enumerate() {
                system.matrix[row * m + column] += self.coupling_product[j * deck_count + i];
            }
        }
        for (i, &w) in self.coupled_tyres.iter().enumerate() {
            if contact_set.is_in_flight(w) {
                system.set_identity_row(i);
            }
        }
    }
}

impl TyreSystem {
    /// Buffers for the tyres of `constants`.
    pub(super) fn new(constants: &VehicleConstants) -> TyreSystem {
        let t = constants.e_coef.len();
        TyreSystem {
            deck_rhs: vec![0.0; t],
            coupled_solution: vec![0.0; t],
            own: DenseSystem::new(constants.largest_tyre_count),
            increments: vec![0.0; t],
        }
    }

    /// The tyre-force increments s of the last solve (zero when none was solved).
    #[inline]
    pub(super) fn increments(&self) -> &[f64] {
        &self.increments
    }

    /// The right-hand side terms g_i·y of the tyres on the deck (the rows of G of
    /// [`DeckCoupling::couple_deck`], summed over k = 1…N in order).
    #[inline]
    pub(super) fn deck_right_hand_side(&mut self, coupling: &DeckCoupling, y: &[f64]) {
        let (n, m) = (coupling.mode_count, coupling.on_deck_tyres.len());
        let sums = &mut self.deck_rhs[..m];
        sums.fill(0.0);
        if m == 0 {
            return;
        }
        // Row k of G holds g_i[k] of every tyre: the m sums advance together, each in the
        // order k = 1…N.
        for (row, yk) in coupling.force_rows[..n * m].chunks_exact(m).zip(y) {
            for (sum, g) in sums.iter_mut().zip(row) {
                *sum += g * yk;
            }
        }
    }

    /// Sets every increment to zero (the first instant, or no tyre).
    #[inline]
    pub(super) fn clear_increments(&mut self) {
        self.increments.fill(0.0);
    }

    /// Solves the coupled system and each uncoupled vehicle's own system for the increments;
    /// false if a system is singular.
    #[inline]
    pub(super) fn solve(
        &mut self,
        coupling: &mut DeckCoupling,
        tyres: &[Tyre],
        constants: &VehicleConstants,
        u: &[f64],
        contact_set: &ContactSet,
        predicted_force: &[f64],
    ) -> bool {
        if coupling.has_coupled_tyres() {
            self.assemble_right_hand_side(
                coupling,
                tyres,
                constants,
                u,
                contact_set,
                predicted_force,
            );
            let m = coupling.coupled_tyres.len();
            let factors = coupling.factorisation(tyres, constants, contact_set);
            if !factors.regular {
                return false;
            }
            factors.system.solve(&mut self.coupled_solution[..m]);
            for (i, &w) in coupling.coupled_tyres.iter().enumerate() {
                self.increments[w] = self.coupled_solution[i];
            }
        }
        for (v, block) in constants.blocks.iter().enumerate() {
            if coupling.coupled_vehicles[v] || block.tyres.is_empty() {
                continue;
            }
            let in_contact = !block.tyres.clone().any(|w| contact_set.is_in_flight(w));
            let own = (tyres, constants, block, u);
            if in_contact {
                self.solve_off_deck(own);
            } else if !self.solve_own_system(own, contact_set, predicted_force) {
                return false;
            }
        }
        true
    }

    /// s_v = (I + E_v H_v)⁻¹ (−E_v A_v u_v): a vehicle off the deck with every tyre in contact
    /// on the rigid road.
    #[inline]
    fn solve_off_deck(&mut self, (tyres, constants, block, u): OwnVehicle) {
        let t_v = block.tyres.len();
        let rhs = &mut self.own.solution[..t_v];
        for (x, w) in rhs.iter_mut().zip(block.tyres.clone()) {
            *x = -constants.e_coef[w] * sparse_dot(&tyres[w].coupling_sparse, u);
        }
        let increments = &mut self.increments[block.tyres.clone()];
        dense::mat_vec(&block.off_deck_inverse, rhs, increments, t_v, t_v);
    }

    /// The T_v × T_v system (I + E_v H_v) s_v = −E_v A_v u_v of a vehicle off the deck with
    /// tyres in flight (their rows s_w = −P̃_w), by its own LU; false if singular.
    fn solve_own_system(
        &mut self,
        (tyres, constants, block, u): OwnVehicle,
        contact_set: &ContactSet,
        predicted_force: &[f64],
    ) -> bool {
        let system = &mut self.own;
        system.size = block.tyres.len();
        for (local, w) in block.tyres.clone().enumerate() {
            if contact_set.is_in_flight(w) {
                system.set_identity_row(local);
                system.solution[local] = -predicted_force[w];
            } else {
                system.set_block_row(local, 0, block, local, constants.e_coef[w]);
                system.solution[local] =
                    -constants.e_coef[w] * sparse_dot(&tyres[w].coupling_sparse, u);
            }
        }
        if !system.factor_and_solve() {
            return false;
        }
        let increments = &mut self.increments[block.tyres.clone()];
        increments.copy_from_slice(&system.solution[..system.size]);
        true
    }

    /// The coupled right-hand side G y − E A u; a tyre in flight gets −P̃_w.
    #[inline]
    fn assemble_right_hand_side(
        &mut self,
        coupling: &DeckCoupling,
        tyres: &[Tyre],
        constants: &VehicleConstants,
        u: &[f64],
        contact_set: &ContactSet,
        predicted_force: &[f64],
    ) {
        let s = &mut self.coupled_solution;
        for (i, &w) in coupling.coupled_tyres.iter().enumerate() {
            s[i] = -constants.e_coef[w] * sparse_dot(&tyres[w].coupling_sparse, u);
        }
        for (i, &(_, row)) in coupling.on_deck_tyres.iter().enumerate() {
            s[row] += self.deck_rhs[i];
        }
        for (i, &w) in coupling.coupled_tyres.iter().enumerate() {
            if contact_set.is_in_flight(w) {
                s[i] = -predicted_force[w];
            }
        }
    }

    /// The accelerations of the increments: a_q = y − Σ_deck W_i s_i and, vehicle by vehicle,
    /// a_Z,v = u_v + Σ_{w of v} B_v⁻¹a_w s_w (terms with s_w = 0 skipped).
    #[inline]
    pub(super) fn accelerations(
        &self,
        coupling: &DeckCoupling,
        constants: &VehicleConstants,
        (y, u): (&[f64], &[f64]),
        (qdd, zdd): (&mut [f64], &mut [f64]),
    ) {
        self.modal_accelerations(coupling, y, qdd);
        self.vehicle_accelerations(constants, u, zdd);
    }

    /// a_q = y − Σ_deck W_i s_i.
    #[inline]
    fn modal_accelerations(&self, coupling: &DeckCoupling, y: &[f64], qdd: &mut [f64]) {
        let (n, s) = (coupling.mode_count, &self.increments);
        qdd.copy_from_slice(y);
        for (i, &(w, _)) in coupling.on_deck_tyres.iter().enumerate() {
            if s[w] != 0.0 {
                let col = &coupling.deck_columns[i * n..(i + 1) * n];
                for k in 0..n {
                    qdd[k] -= col[k] * s[w];
                }
            }
        }
    }

    /// a_Z,v = u_v + Σ_{w of v} B_v⁻¹a_w s_w, vehicle by vehicle.
    #[inline]
    pub(super) fn vehicle_accelerations(
        &self,
        constants: &VehicleConstants,
        u: &[f64],
        zdd: &mut [f64],
    ) {
        let s = &self.increments;
        zdd.copy_from_slice(u);
        for block in &constants.blocks {
            let d = block.dofs.len();
            let own = &mut zdd[block.dofs.clone()];
            for (local, w) in block.tyres.clone().enumerate() {
                if s[w] != 0.0 {
                    let col = &block.b_inv_a[local * d..(local + 1) * d];
                    for (z, c) in own.iter_mut().zip(col) {
                        *z += c * s[w];
                    }
                }
            }
        }
    }
}

/// One vehicle's part of a step: the tyres, the constants, its block and u.
type OwnVehicle<'a> = (
    &'a [Tyre],
    &'a VehicleConstants,
    &'a VehicleBlock,
    &'a [f64],
);
