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
//! s_w = −P̃_w (no force). It is built and solved in separate steps — the on-deck products W,
//! G, G·W and G·y ([`TyreSystem::couple_deck`]), the right-hand side, the matrix, its LU, the
//! solve — so that the matrix and its LU, which depend on the tyres' positions and contact
//! set but not on the road, can be shared. Per-step cost: O(T·N) for W and G, O(T²·N) for G·W
//! (one small GEMM), O(T³) for the LU; while no tyre is on the deck and all are in contact the
//! matrix is the constant I + E H, whose inverse is precomputed.

use super::contact::ContactSet;
use super::dense;
use super::kinematics::ContactPoints;
use super::setup::VehicleConstants;
use super::shapes::ContactShapes;
use super::tyre::{sparse_dot, Tyre};

/// Buffers and solution of the tyre-force increments of one step.
pub(super) struct TyreSystem {
    /// Number of tyres T.
    tyre_count: usize,
    /// Number of modes N.
    mode_count: usize,
    /// The tyres on the deck this step (the m tyres coupled to the modes), in tyre order.
    on_deck_tyres: Vec<usize>,
    /// W_i = D⁻¹ φ_i of the on-deck tyres: columns of an N × m matrix, column-major.
    deck_columns: Vec<f64>,
    /// g_i = e_i φ_i + h_i φ′_i of the on-deck tyres: the rows of an m × N matrix G,
    /// column-major (`force_rows[k * m + i]`).
    force_rows: Vec<f64>,
    /// G·W, m × m column-major.
    coupling_product: Vec<f64>,
    /// g_i·y of the on-deck tyres.
    deck_rhs: Vec<f64>,
    /// −e_w a_w·u of every tyre, for the off-deck system.
    off_deck_rhs: Vec<f64>,
    /// The capacitance matrix I + G W + E H (rows of tyres in flight replaced), row-major T × T;
    /// U of its LU after [`TyreSystem::factor`].
    capacitance: Vec<f64>,
    /// Row swaps of the LU.
    pivots: Vec<usize>,
    /// Elimination multipliers of the LU, per stage.
    multipliers: Vec<f64>,
    /// The right-hand side, then the solution s (tyre-force increments) [N].
    increments: Vec<f64>,
}

impl TyreSystem {
    /// Buffers for `tyre_count` tyres and `mode_count` modes.
    pub(super) fn new(tyre_count: usize, mode_count: usize) -> TyreSystem {
        let (t, n) = (tyre_count, mode_count);
        TyreSystem {
            tyre_count: t,
            mode_count: n,
            on_deck_tyres: Vec::with_capacity(t),
            deck_columns: vec![0.0; t * n],
            force_rows: vec![0.0; t * n],
            coupling_product: vec![0.0; t * t],
            deck_rhs: vec![0.0; t],
            off_deck_rhs: vec![0.0; t],
            capacitance: vec![0.0; t * t],
            pivots: vec![0; t],
            multipliers: vec![0.0; t * t],
            increments: vec![0.0; t],
        }
    }

    /// The tyre-force increments s of the last solve (zero when none was solved).
    #[inline]
    pub(super) fn increments(&self) -> &[f64] {
        &self.increments
    }

    /// Starts a step with no tyre coupled to the modes.
    #[inline]
    pub(super) fn uncouple_deck(&mut self) {
        self.on_deck_tyres.clear();
    }

    /// The on-deck products of the step, for the m tyres on the deck: W_i = D⁻¹ φ_i,
    /// g_i = e_i φ_i + h_i φ′_i with h_i = c_i v_i βΔt² (v_i the tyre's speed of travel), the
    /// right-hand side terms g_i·y (one fused pass per tyre), then G·W by one small GEMM
    /// (matrixmultiply, with its run-time SIMD kernels).
    #[inline]
    pub(super) fn couple_deck(
        &mut self,
        tyres: &[Tyre],
        shapes: &ContactShapes,
        points: &ContactPoints,
        constants: &VehicleConstants,
        d_inv: &[f64],
        y: &[f64],
        beta_dt2: f64,
    ) {
        let n = self.mode_count;
        self.on_deck_tyres.clear();
        self.on_deck_tyres
            .extend((0..self.tyre_count).filter(|&w| shapes.is_on_deck(w)));
        let m = self.on_deck_tyres.len();
        for (i, &w) in self.on_deck_tyres.iter().enumerate() {
            let t = &tyres[w];
            let h_coef = t.damping * points.travel_speed[t.contact] * beta_dt2;
            let (ew, hw) = (constants.e_coef[w], h_coef);
            let Some((pw, sw)) = shapes.of(w) else {
                unreachable!("tyre {w} is on the deck")
            };
            let dst = &mut self.deck_columns[i * n..(i + 1) * n];
            // g_i·y for the right-hand side, in the same pass.
            let mut gy = 0.0;
            for (k, ((((o, p), sl), di), yk)) in
                dst.iter_mut().zip(pw).zip(sw).zip(d_inv).zip(y).enumerate()
            {
                *o = di * p;
                let g = ew * p + hw * sl;
                self.force_rows[k * m + i] = g;
                gy += g * yk;
            }
            self.deck_rhs[i] = gy;
        }
        let g_view = nalgebra::DMatrixView::from_slice(&self.force_rows[..m * n], m, n);
        let w_view = nalgebra::DMatrixView::from_slice(&self.deck_columns[..m * n], n, m);
        let mut gw_view =
            nalgebra::DMatrixViewMut::from_slice(&mut self.coupling_product[..m * m], m, m);
        gw_view.gemm(1.0, &g_view, &w_view, 0.0);
    }

    /// Sets every increment to zero (the first instant, or no tyre).
    #[inline]
    pub(super) fn clear_increments(&mut self) {
        self.increments.fill(0.0);
    }

    /// s = (I + E H)⁻¹ (−E A u): every tyre in contact on the rigid road.
    #[inline]
    pub(super) fn solve_off_deck(
        &mut self,
        tyres: &[Tyre],
        constants: &VehicleConstants,
        u: &[f64],
    ) {
        let t_count = self.tyre_count;
        for w in 0..t_count {
            self.off_deck_rhs[w] = -constants.e_coef[w] * sparse_dot(&tyres[w].coupling_sparse, u);
        }
        dense::mat_vec(
            &constants.off_deck_inverse,
            &self.off_deck_rhs,
            &mut self.increments,
            t_count,
            t_count,
        );
    }

    /// The right-hand side G y − E A u into the increments; a tyre in flight gets −P̃_w.
    #[inline]
    pub(super) fn assemble_right_hand_side(
        &mut self,
        tyres: &[Tyre],
        constants: &VehicleConstants,
        u: &[f64],
        contact_set: &ContactSet,
        predicted_force: &[f64],
    ) {
        let s = &mut self.increments;
        for w in 0..self.tyre_count {
            s[w] = -constants.e_coef[w] * sparse_dot(&tyres[w].coupling_sparse, u);
        }
        for (i, &w) in self.on_deck_tyres.iter().enumerate() {
            s[w] += self.deck_rhs[i];
        }
        for w in contact_set.in_flight() {
            s[w] = -predicted_force[w];
        }
    }

    /// The capacitance matrix I + E H + G W; the row of a tyre in flight is that of the
    /// identity (P_w = P̃_w + s_w = 0).
    #[inline]
    pub(super) fn assemble_matrix(
        &mut self,
        constants: &VehicleConstants,
        contact_set: &ContactSet,
    ) {
        let t_count = self.tyre_count;
        let cap = &mut self.capacitance;
        for w in 0..t_count {
            let ew = constants.e_coef[w];
            for w2 in 0..t_count {
                cap[w * t_count + w2] =
                    ew * constants.h_matrix[w * t_count + w2] + if w == w2 { 1.0 } else { 0.0 };
            }
        }
        let m = self.on_deck_tyres.len();
        for (i, &w) in self.on_deck_tyres.iter().enumerate() {
            for (j, &w2) in self.on_deck_tyres.iter().enumerate() {
                cap[w * t_count + w2] += self.coupling_product[j * m + i];
            }
        }
        for w in contact_set.in_flight() {
            cap[w * t_count..(w + 1) * t_count].fill(0.0);
            cap[w * t_count + w] = 1.0;
        }
    }

    /// LU factorisation of the capacitance matrix in place; false if it is singular.
    #[inline]
    pub(super) fn factor(&mut self) -> bool {
        dense::lu_factor(
            &mut self.capacitance,
            &mut self.pivots,
            &mut self.multipliers,
            self.tyre_count,
        )
    }

    /// Solves for the increments with the LU of [`TyreSystem::factor`] (the right-hand side
    /// in place).
    #[inline]
    pub(super) fn solve(&mut self) {
        dense::lu_solve(
            &self.capacitance,
            &self.pivots,
            &self.multipliers,
            &mut self.increments,
            self.tyre_count,
        );
    }

    /// The accelerations of the increments: a_q = y − Σ_deck W_i s_i and a_Z = u + Σ_w B⁻¹a_w s_w
    /// (terms with s_w = 0 skipped).
    #[inline]
    pub(super) fn accelerations(
        &self,
        constants: &VehicleConstants,
        (y, u): (&[f64], &[f64]),
        (qdd, zdd): (&mut [f64], &mut [f64]),
    ) {
        let (n, d, s) = (self.mode_count, constants.dof_count, &self.increments);
        qdd.copy_from_slice(y);
        for (i, &w) in self.on_deck_tyres.iter().enumerate() {
            if s[w] != 0.0 {
                let col = &self.deck_columns[i * n..(i + 1) * n];
                for k in 0..n {
                    qdd[k] -= col[k] * s[w];
                }
            }
        }
        zdd.copy_from_slice(u);
        for w in 0..self.tyre_count {
            if s[w] != 0.0 {
                let col = &constants.b_inv_a[w * d..(w + 1) * d];
                for j in 0..d {
                    zdd[j] += col[j] * s[w];
                }
            }
        }
    }
}
