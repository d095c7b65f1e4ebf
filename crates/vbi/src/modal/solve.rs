//! `solve_modes`: the lowest natural modes of an [`FeModel`] by sparse shift-invert Lanczos,
//! classified, and read at the deck nodes and the stations.

use crate::deck::{DeckField, DeckGeometry};
use crate::fe::{
    diagnose_mechanism, direction_energies, dominant_direction, stiffness_mass_ratio,
    validate_fe_model, Direction, FeModel, ModalError, SparseRow, Station, StationFunctional,
    REGULARISATION, RIGID_BODY_LEVEL,
};
use crate::linalg::{
    check_backward_errors, lanczos_bytes, lowest_eigenpairs_with_factor, CholeskyPattern,
    EigenError, Eigenpairs, LanczosOptions, LinalgError, SparseMatrix,
};

use super::{ModalBasis, Mode, ModeKind};
use crate::model::ModeDamping;

/// Options of [`solve_modes`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ModalOptions {
    /// Number of modes solved for (default 50). Capped at the number of degrees of freedom that
    /// carry mass, so a small model returns all its modes.
    pub mode_count: usize,
    /// Kinds of mode kept in the basis, after solving `mode_count` modes (default: all five).
    pub keep_kinds: Vec<ModeKind>,
    /// Shift σ [rad²/s²] of the shift-invert operator (K − σM)⁻¹M (default 0). It must lie below
    /// the lowest eigenvalue ω₁², since K − σM is factorised by Cholesky; a negative shift is
    /// always safe for a stable model. The solver lowers it further by a tiny
    /// α = 1e-12 · mean diag K / mean diag M so that a mechanism (singular K) still factorises
    /// and is reported by its rigid-body mode.
    pub shift: f64,
    /// Lanczos convergence tolerance on each Ritz estimate, relative to the inverted eigenvalue
    /// [-] (default 1e-10).
    pub tolerance: f64,
    /// Largest accepted backward error ‖Kφ − ω²Mφ‖₂ / ((‖K‖₁ + ω²‖M‖₁)‖φ‖₂) of a mode [-]
    /// (default 1e-6; [`crate::linalg::backward_error`]). A converged pair has about 1e-15 on
    /// any mesh; the Lanczos tolerance (1e-10 on the shift-inverted Ritz estimate, in the
    /// M-norm) allows up to about tolerance × √cond(M), ≤ 1e-7 for consistent-mass meshes whose
    /// rotational masses are 1e-6 of the translational ones; 1e-6 refuses only pairs that are
    /// not eigenpairs of the model.
    pub residual_limit: f64,
    /// Largest memory [bytes] that the modal analysis may allocate (default
    /// [`DEFAULT_MODAL_MEMORY_LIMIT`], 4 GiB): the factor of K − σM, its scratch and the Lanczos
    /// basis, estimated from the symbolic analysis before any numeric work. A model over it is
    /// refused with [`ModalError::MemoryLimit`] instead of aborting on a failed allocation.
    /// Not part of a study's specification (not serialised): it changes no result.
    #[serde(skip, default = "default_modal_memory_limit")]
    pub memory_limit_bytes: u64,
}

/// The default [`ModalOptions::memory_limit_bytes`]: 4 GiB, a quarter of a 16 GiB laptop; the
/// Lanczos time grows with it (n · dim² per restart), so a larger basis would also run for long.
/// The paper's finest model (4 × 40 m grillage at 0.1 m, 28 770 DOFs, 200 modes) needs 0.23 GiB
/// (242 MB by this estimate).
pub const DEFAULT_MODAL_MEMORY_LIMIT: u64 = 4 << 30;

/// The most arithmetic one pass of the Lanczos may take, n · dim² multiply-adds (n DOFs, a
/// Krylov basis of dim ≈ 2 × modes + 10 vectors, each orthogonalised against the others):
/// 2e10, some seconds per pass on one core, and a solve takes several passes. The paper's
/// finest model (28 770 DOFs, 200 modes, dim 410) takes 4.8e9. A 0.01 m mesh of a 2 × 20 m
/// grillage with 1000 modes (about 7e4 DOFs, dim 2010) takes 3e11 and ran for over ten minutes
/// before this limit refused it; the same mesh of a 2 × 20 m beam (1.2e4 DOFs) takes 5e10 and
/// two minutes in a test build (issue 47). A limit on work, not on time, so that the refusal
/// is the same on every machine.
pub const MODAL_WORK_LIMIT: f64 = 2e10;

fn default_modal_memory_limit() -> u64 {
    DEFAULT_MODAL_MEMORY_LIMIT
}

impl Default for ModalOptions {
    fn default() -> Self {
        Self {
            mode_count: 50,
            keep_kinds: ModeKind::ALL.to_vec(),
            shift: 0.0,
            tolerance: 1e-10,
            residual_limit: 1e-6,
            memory_limit_bytes: DEFAULT_MODAL_MEMORY_LIMIT,
        }
    }
}

/// The lowest natural modes of the model, K φ = ω² M φ (paper Eq. 4–5), mass-normalised
/// (φᵀMφ = 1), in ascending frequency.
///
/// 1. K − σM is factorised once (sparse Cholesky); a failure means a mechanism, diagnosed by
///    [`diagnose_mechanism`] (the rigid-body mode's dominant direction is named).
/// 2. `mode_count` pairs by shift-invert Lanczos ([`crate::linalg::lowest_eigenpairs`]); an
///    eigenvalue ω² ≤ 1e-14 · mean diag K / mean diag M is a rigid-body mode (a mechanism);
///    each backward error ‖Kφ − ω²Mφ‖₂ / ((‖K‖₁ + ω²‖M‖₁)‖φ‖₂) is checked against
///    `residual_limit` and reported in [`Mode::residual`].
/// 3. Each mode is classified by [`classify_mode`] and read at the deck nodes (`deck_dofs`) and
///    at the stations (`station_functionals`; the modal moment is the mean of the left and right
///    element-end moments including the mode's inertia loads, see [`station_modal_moment`]).
/// 4. Modes of kinds not in `keep_kinds` are dropped.
/// 5. Each mode has the model's `damping_ratio`, or with a `mode_damping` law the ratio that law
///    gives the retained modes in ascending frequency (mode 1 the lowest kept).
/// 6. The check modes ([`ModalBasis::check_modes`]): where the memory and work limits allow,
///    the solve is taken on to 2 × `mode_count` pairs, and the modes above the first
///    `mode_count` of the kept kinds with ω ≤ [`CHECK_FREQUENCY_RATIO`] × ω_N (ω_N of the
///    `mode_count`-th pair) are kept beside the basis, with their damping ratios numbered on
///    from the basis's. The analysis integrates them against a crossing's contact forces,
///    without feeding back, for the convergence indicator only
///    ([`crate::analysis::DafConvergence`]).
pub fn solve_modes(model: &FeModel, options: &ModalOptions) -> Result<ModalBasis, ModalError> {
    solve_modes_with(model, options, CheckModes::Solve)
}

/// Whether a modal solve goes on to the check modes (step 6 of [`solve_modes`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CheckModes {
    /// Solve up to 2 × `mode_count` pairs where the limits allow, and keep the check modes
    /// beside the basis: what a crossing's convergence indicator needs.
    Solve,
    /// Solve `mode_count` pairs only (the basis has no check modes): for what reads the modes
    /// alone (`vbi modes`, the frequency fits of model updating). The Krylov basis is then
    /// about half as wide, and the Lanczos's dense work (n × dim per step, over as many steps)
    /// about a quarter or less: a 500-span grillage's 50 modes take 8.5 s instead of 55 s
    /// (release build).
    Skip,
}

/// [`solve_modes`], with or without the check modes ([`CheckModes`]). The first `mode_count`
/// modes are the same either way to the Lanczos tolerance, not bit for bit (the Krylov basis
/// differs).
pub fn solve_modes_with(
    model: &FeModel,
    options: &ModalOptions,
    check_modes: CheckModes,
) -> Result<ModalBasis, ModalError> {
    let ModalPlan {
        shifted,
        pattern,
        lanczos,
        count,
        solve_count,
    } = plan_modes(model, options, check_modes)?;
    let (k, m, shift) = (&model.stiffness, &model.mass, lanczos.shift);
    let factor = match pattern.factorise(&shifted) {
        Ok(factor) => factor,
        Err(LinalgError::NotPositiveDefinite { .. }) if options.shift <= 0.0 => {
            return Err(diagnose_mechanism(model));
        }
        Err(source) => return Err(EigenError::Factorisation { shift, source }.into()),
    };
    // Backward errors are checked below (the Lanczos options above do not), after the
    // mechanism check, so that a mechanism is reported as one.
    let pairs = lowest_eigenpairs_with_factor(k, m, &factor, solve_count, &lanczos)?;
    // A shift below zero lets a singular K factorise: a (near-)zero eigenvalue is a mechanism,
    // judged by the rule of `factor_is_singular` (the model's own scale, not the largest
    // eigenvalue computed, which grows with the number of modes asked for).
    let zero = RIGID_BODY_LEVEL * stiffness_mass_ratio(model);
    if let Some(index) = pairs.eigenvalues.iter().position(|&l| l <= zero) {
        let (direction, dof) = dominant_direction(model, pairs.vector(index));
        return Err(ModalError::Mechanism {
            direction,
            dof,
            eigenvalue: pairs.eigenvalues[index],
        });
    }
    check_backward_errors(&pairs, options.residual_limit)?;
    let solved = basis_from_pairs(model, &pairs);
    let kept = |range: std::ops::Range<usize>| -> Vec<usize> {
        range
            .filter(|&i| options.keep_kinds.contains(&solved.modes[i].kind))
            .collect()
    };
    let keep = kept(0..count);
    let highest = solved.modes[count - 1].circular_frequency;
    let check: Vec<usize> = kept(count..solved.modes.len())
        .into_iter()
        .filter(|&i| solved.modes[i].circular_frequency <= CHECK_FREQUENCY_RATIO * highest)
        .collect();
    let all: Vec<usize> = keep.iter().chain(&check).copied().collect();
    let mut together = solved.select_modes(&all);
    if let Some(law) = &model.mode_damping {
        apply_mode_damping(&mut together, law)?;
    }
    let headline: Vec<usize> = (0..keep.len()).collect();
    let mut basis = together.select_modes(&headline);
    if !check.is_empty() {
        let above: Vec<usize> = (keep.len()..all.len()).collect();
        basis.check_modes = Some(Box::new(together.select_modes(&above)));
    }
    Ok(basis)
}

/// The check modes reach up to this multiple of the highest solved mode's circular frequency
/// ω_N (step 6 of [`solve_modes`]). On the paper's 3 × 30 m grillage the shear forces' DAFs
/// move first at vertical bending modes 20–35 % above ω_N of 50 modes; a replay of the rule on
/// grillages of 20–57 kept modes and on two beams bounded every entry's error at 2 ω_N
/// (docs/theory.md, "The convergence indicator").
pub const CHECK_FREQUENCY_RATIO: f64 = 2.0;

/// What [`solve_modes`] knows before any numeric work: K − σM, its symbolic Cholesky analysis,
/// the Lanczos options and the number of pairs.
struct ModalPlan {
    shifted: SparseMatrix,
    pattern: CholeskyPattern,
    lanczos: LanczosOptions,
    /// The modes of the basis.
    count: usize,
    /// The pairs solved: `count`, or up to twice as many for the check modes where the limits
    /// allow.
    solve_count: usize,
}

/// Refuses, before any numeric work, what [`solve_modes`] would refuse before it: an invalid
/// model or option, no DOF with mass, or a memory estimate over
/// [`ModalOptions::memory_limit_bytes`] ([`ModalError::MemoryLimit`]). The symbolic analysis
/// costs a fraction of the factorisation: `vbi check` calls it.
pub fn check_modal_plan(model: &FeModel, options: &ModalOptions) -> Result<(), ModalError> {
    plan_modes(model, options, CheckModes::Solve).map(|_| ())
}

/// Validates, analyses K − σM symbolically and estimates the memory of the solve (see
/// [`solve_modes`], step 1).
fn plan_modes(
    model: &FeModel,
    options: &ModalOptions,
    check_modes: CheckModes,
) -> Result<ModalPlan, ModalError> {
    validate_fe_model(model)?;
    if options.mode_count == 0 {
        return Err(ModalError::InvalidOption {
            option: "mode_count",
            value: 0.0,
            allowed: "at least 1",
        });
    }
    for (option, value) in [
        ("tolerance", options.tolerance),
        ("residual_limit", options.residual_limit),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(ModalError::InvalidOption {
                option,
                value,
                allowed: "a positive number",
            });
        }
    }
    if !options.shift.is_finite() {
        return Err(ModalError::InvalidOption {
            option: "shift",
            value: options.shift,
            allowed: "a finite number below the lowest eigenvalue",
        });
    }
    let k = &model.stiffness;
    let m = &model.mass;
    let with_mass = m.diagonal().iter().filter(|&&d| d > 0.0).count();
    let count = options.mode_count.min(with_mass);
    if count == 0 {
        return Err(ModalError::InvalidModel {
            message: "no degree of freedom carries mass".into(),
        });
    }
    // A singular K (a mechanism) may still factorise with a round-off pivot; the tiny extra
    // shift makes K − σM safely positive definite so that the rigid-body mode comes out with
    // ω² ≈ 0 and is reported below, instead of spoiling the Krylov space.
    let shift = options.shift - REGULARISATION * stiffness_mass_ratio(model);
    let shifted = SparseMatrix::linear_combination(1.0, k, -shift, m);
    let lanczos = LanczosOptions {
        shift,
        tolerance: options.tolerance,
        residual_limit: f64::INFINITY,
        ..Default::default()
    };
    let pattern = CholeskyPattern::analyse(&shifted)
        .map_err(|source| EigenError::Factorisation { shift, source })?;
    let needed = pattern.factorisation_bytes() + lanczos_bytes(k.size, count, &lanczos);
    if needed > options.memory_limit_bytes {
        return Err(ModalError::MemoryLimit {
            needed_bytes: needed,
            limit_bytes: options.memory_limit_bytes,
            degrees_of_freedom: k.size,
            modes: count,
        });
    }
    let krylov_dimension = crate::linalg::krylov_dimension(k.size, count, &lanczos);
    let work = k.size as f64 * (krylov_dimension as f64).powi(2);
    if work > MODAL_WORK_LIMIT {
        return Err(ModalError::WorkLimit {
            work,
            degrees_of_freedom: k.size,
            modes: count,
            krylov_dimension,
        });
    }
    // The check modes' pairs, where they fit the same limits (else the basis goes without).
    let extended = (2 * count).min(with_mass);
    let fits = |solve: usize| {
        let bytes = pattern.factorisation_bytes() + lanczos_bytes(k.size, solve, &lanczos);
        let dimension = crate::linalg::krylov_dimension(k.size, solve, &lanczos);
        bytes <= options.memory_limit_bytes
            && k.size as f64 * (dimension as f64).powi(2) <= MODAL_WORK_LIMIT
    };
    let solve_count = if check_modes == CheckModes::Solve && fits(extended) {
        extended
    } else {
        count
    };
    Ok(ModalPlan {
        shifted,
        pattern,
        lanczos,
        count,
        solve_count,
    })
}

/// Gives the retained modes (ascending frequency, numbered from 1 as `vbi modes` lists them)
/// the ratios of the damping law ([`ModeDamping::ratios`]).
fn apply_mode_damping(basis: &mut ModalBasis, law: &ModeDamping) -> Result<(), ModalError> {
    let frequencies: Vec<f64> = basis.modes.iter().map(|m| m.circular_frequency).collect();
    for (mode, ratio) in basis.modes.iter_mut().zip(law.ratios(&frequencies)?) {
        mode.damping_ratio = ratio;
    }
    Ok(())
}

/// Shares of Σ_x Σ_l w_l(x)² (the deck lines' vertical deflections at the node positions x of the
/// first line) in three orthogonal parts, each in [0, 1]: with w_l^s = ½[w(x, y_l) + w(x, −y_l)]
/// and w_l^a = ½[w(x, y_l) − w(x, −y_l)] (the field read at the mirror image −y_l of line l), and
/// w̄ the mean over the lines of w_l^s,
/// - `uniform` = Σ Σ_l w̄² / Σ Σ_l w_l²: the deck moving as one (vertical bending);
/// - `symmetric` = Σ Σ_l (w_l^s − w̄)² / Σ Σ_l w_l²: symmetric about the axis, not uniform
///   (differential bending: centre girders against edge girders);
/// - `antisymmetric` = Σ Σ_l (w_l^a)² / Σ Σ_l w_l²: antisymmetric about the axis (torsion).
///
/// For lines placed symmetrically about the axis (every preset) the three sum to 1. A deck of
/// one line, or a field without deflection, is all `uniform`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeckVerticalShares {
    /// Share of the uniform part [-].
    pub uniform: f64,
    /// Share of the symmetric, non-uniform part [-].
    pub symmetric: f64,
    /// Share of the antisymmetric part [-].
    pub antisymmetric: f64,
}

/// The [`DeckVerticalShares`] of a deck field.
pub fn deck_vertical_shares(deck: &DeckGeometry, field: &DeckField) -> DeckVerticalShares {
    let all_uniform = DeckVerticalShares {
        uniform: 1.0,
        symmetric: 0.0,
        antisymmetric: 0.0,
    };
    if deck.lines.len() < 2 {
        return all_uniform;
    }
    // Points are compared at the same distance s from each line's first node, so that a skewed
    // deck (lines starting at x = y·tan θ + c) is read along its girders; a line's start at a
    // lateral position between lines is interpolated like the deflection (lever rule).
    let start = |y: f64| -> f64 {
        deck.lateral_weights(y)
            .iter()
            .map(|&(l, w)| w * deck.lines[l].node_positions[0])
            .sum()
    };
    let read = |s: f64, y: f64| deck.stencil(s + start(y), y).evaluate(field).0;
    let (mut total, mut uniform, mut symmetric, mut antisymmetric) = (0.0, 0.0, 0.0, 0.0);
    let mut symmetric_parts = vec![0.0; deck.lines.len()];
    let first = deck.lines[0].node_positions[0];
    for &x in &deck.lines[0].node_positions {
        let s = x - first;
        for (l, line) in deck.lines.iter().enumerate() {
            let (here, mirror) = (
                read(s, line.lateral_position),
                read(s, -line.lateral_position),
            );
            total += here * here;
            symmetric_parts[l] = 0.5 * (here + mirror);
            antisymmetric += (0.5 * (here - mirror)).powi(2);
        }
        let mean = symmetric_parts.iter().sum::<f64>() / symmetric_parts.len() as f64;
        uniform += mean * mean * symmetric_parts.len() as f64;
        symmetric += symmetric_parts
            .iter()
            .map(|w| (w - mean).powi(2))
            .sum::<f64>();
    }
    if total > 0.0 {
        DeckVerticalShares {
            uniform: uniform / total,
            symmetric: symmetric / total,
            antisymmetric: antisymmetric / total,
        }
    } else {
        all_uniform
    }
}

/// Fraction t ∈ [0, 1] of the deck's vertical motion in which the deck lines do not move
/// together: the symmetric non-uniform and the antisymmetric shares of
/// [`deck_vertical_shares`], t = 1 − uniform. A bending mode (all girders in phase) has t ≈ 0,
/// torsion and differential bending t ≈ 1. Zero for a deck of one line.
pub fn deck_twist_fraction(deck: &DeckGeometry, field: &DeckField) -> f64 {
    let shares = deck_vertical_shares(deck, field);
    shares.symmetric + shares.antisymmetric
}

/// Classifies a mode by its kinetic-energy shares (φᵀMφ split by `dof_directions`):
/// - longitudinal: translation x;
/// - lateral: translation y + rotation z;
/// - vertical: translation z + rotation y, split by the deck shape's
///   [`deck_vertical_shares`]: vertical bending its uniform share, differential bending its
///   symmetric share;
/// - torsion: rotation x, plus the antisymmetric share of the vertical one.
///
/// The kind with the largest share wins; a tie goes to the first in the order vertical bending,
/// differential bending, torsion, lateral, longitudinal.
pub fn classify_mode(
    m: &SparseMatrix,
    directions: &[Direction],
    vector: &[f64],
    deck: &DeckGeometry,
    deck_shape: &DeckField,
) -> ModeKind {
    let e = direction_energies(m, directions, vector);
    let deck_shares = deck_vertical_shares(deck, deck_shape);
    let vertical = e[2] + e[4];
    let shares = [
        (ModeKind::VerticalBending, deck_shares.uniform * vertical),
        (
            ModeKind::DifferentialBending,
            deck_shares.symmetric * vertical,
        ),
        (
            ModeKind::Torsion,
            e[3] + deck_shares.antisymmetric * vertical,
        ),
        (ModeKind::Lateral, e[1] + e[5]),
        (ModeKind::Longitudinal, e[0]),
    ];
    kind_of_largest_share(&shares)
}

/// The kind with the largest share; a tie goes to the first listed.
pub(super) fn kind_of_largest_share(shares: &[(ModeKind, f64)]) -> ModeKind {
    let mut best = shares[0];
    for share in &shares[1..] {
        if share.1 > best.1 {
            best = *share;
        }
    }
    best.0
}

/// Σ coefficient · u[dof].
fn apply_row(row: &SparseRow, u: &[f64]) -> f64 {
    row.iter().map(|&(dof, c)| c * u[dof]).sum()
}

/// The row read as a station's static bending moment: the mean of `moment_left` and
/// `moment_right`, ½(r_left + r_right). Both rows are element-end moments from k_e u_e, exact
/// for nodal (static) loads.
pub fn station_moment_row(left: &SparseRow, right: &SparseRow) -> SparseRow {
    left.iter()
        .map(|&(d, c)| (d, 0.5 * c))
        .chain(right.iter().map(|&(d, c)| (d, 0.5 * c)))
        .collect()
}

/// A station's modal bending moment for mode (ω², φ): the mean of the element end moments from
/// both sides including the mode's inertia loads,
/// M = ½[(k_l − ω² m_l)φ + (k_r − ω² m_r)φ] (rows of [`StationFunctional`]).
///
/// A mode's loads are the distributed inertia forces ω²Mφ inside the elements. The stiffness
/// rows alone (element equilibrium without those forces) miss each element's fixed-end moment of
/// its inertia load, relative error ≈ (nπh/L)²/12 for mode n (4 % at mode 9 with 40 elements per
/// span). With the consistent-mass rows each side is the exact end moment of the FE element in
/// harmonic motion, f_e = (k_e − ω² m_e)φ_e; the remaining error is the FE discretisation error of
/// the mode itself, O((nπh/L)⁴) for Hermite elements. The mean of both sides makes the value
/// independent of which side a station is read from (mirror-image modes).
pub fn station_modal_moment(
    functional: &StationFunctional,
    omega_squared: f64,
    phi: &[f64],
) -> f64 {
    let side = |k: &SparseRow, m: &SparseRow| apply_row(k, phi) - omega_squared * apply_row(m, phi);
    0.5 * (side(&functional.moment_left, &functional.moment_left_mass)
        + side(&functional.moment_right, &functional.moment_right_mass))
}

/// A station's modal force for mode (ω², φ): at a support the reaction
/// R = (K_cf − ω² M_cf) φ (the restrained DOFs' equilibrium in harmonic motion, ü = −ω² φ);
/// elsewhere the shear force, the mean of both sides' element end forces
/// V = ½[(k_l − ω² m_l)φ + (k_r − ω² m_r)φ], as for the moment (both sides are equal at a
/// node without a support: the node's vertical equilibrium).
pub fn station_modal_force(
    station: &Station,
    functional: &StationFunctional,
    omega_squared: f64,
    phi: &[f64],
) -> f64 {
    let side = |k: &SparseRow, m: &SparseRow| apply_row(k, phi) - omega_squared * apply_row(m, phi);
    if station.support {
        side(&functional.reaction, &functional.reaction_mass)
    } else {
        0.5 * (side(&functional.shear_left, &functional.shear_left_mass)
            + side(&functional.shear_right, &functional.shear_right_mass))
    }
}

/// Fills a [`ModalBasis`] from mass-normalised eigenpairs of the model.
pub fn basis_from_pairs(model: &FeModel, pairs: &Eigenpairs) -> ModalBasis {
    let count = pairs.count();
    let nodes = model.deck.node_count();
    let stations = model.stations.len();
    let mut deck_deflection = vec![0.0; nodes * count];
    let mut deck_slope = vec![0.0; nodes * count];
    let mut station_deflection = vec![0.0; stations * count];
    let mut station_moment = vec![0.0; stations * count];
    let mut station_force = vec![0.0; stations * count];
    let mut modes = Vec::with_capacity(count);
    for k in 0..count {
        let phi = pairs.vector(k);
        let mut field = DeckField {
            deflection: vec![0.0; nodes],
            slope: vec![0.0; nodes],
        };
        for (node, rows) in model.deck_dofs.iter().enumerate() {
            field.deflection[node] = apply_row(&rows.deflection, phi);
            field.slope[node] = apply_row(&rows.slope, phi);
            deck_deflection[node * count + k] = field.deflection[node];
            deck_slope[node * count + k] = field.slope[node];
        }
        for s in 0..stations {
            station_deflection[s * count + k] =
                apply_row(&model.station_functionals[s].deflection, phi);
            station_moment[s * count + k] = station_modal_moment(
                &model.station_functionals[s],
                pairs.eigenvalues[k].max(0.0),
                phi,
            );
            station_force[s * count + k] = station_modal_force(
                &model.stations[s],
                &model.station_functionals[s],
                pairs.eigenvalues[k].max(0.0),
                phi,
            );
        }
        let kind = classify_mode(&model.mass, &model.dof_directions, phi, &model.deck, &field);
        modes.push(Mode {
            circular_frequency: pairs.eigenvalues[k].max(0.0).sqrt(),
            damping_ratio: model.damping_ratio,
            kind,
            residual: pairs.residuals[k],
        });
    }
    ModalBasis {
        modes,
        deck: model.deck.clone(),
        deck_deflection,
        deck_slope,
        stations: model.stations.clone(),
        station_deflection,
        station_moment,
        station_force: if model.has_station_forces {
            station_force
        } else {
            Vec::new()
        },
        dof_count: model.dof_count(),
        check_modes: None,
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::fe::{discretise, MeshOptions, StationRequest};
    use crate::modal::{Quantity, StationTarget};
    use crate::model::{BeamSection, BridgeModel, ContinuousBeam};

    /// The 25 m simply supported beam of examples/bridges/ss-beam-25m.toml (EI = 3.5e10 ×
    /// 1.3901 N·m², m̄ = 18358 kg/m) on `elements` elements, stations off.
    fn fine_simply_supported_beam(elements: usize) -> (FeModel, f64, f64, f64) {
        let (l, ei, mass) = (25.0, 3.5e10 * 1.3901, 18358.0);
        let beam = ContinuousBeam::pinned(
            vec![l],
            BeamSection {
                flexural_rigidity: ei,
                mass_per_length: mass,
            },
        );
        let options = MeshOptions {
            elements_per_span: Some(elements),
            default_stations: false,
            ..MeshOptions::default()
        };
        let fe = discretise(&BridgeModel::ContinuousBeam(beam), &options).unwrap();
        (fe, l, ei, mass)
    }

    /// Issue 17, defect 3: a fine mesh with many modes aborted on a failed allocation. The
    /// estimate comes before any numeric work: it is at least the Krylov basis (2 × n ×
    /// (dim + 1) values, dim = 2 · 30 + 10) and the factor's values; a limit below it is refused
    /// with both numbers, and the default limit passes the same model.
    #[test]
    fn a_model_over_the_memory_limit_is_refused_with_the_estimate() {
        let (fe, ..) = fine_simply_supported_beam(500);
        let n = fe.stiffness.size as u64;
        let options = ModalOptions {
            mode_count: 30,
            memory_limit_bytes: 1 << 20,
            ..ModalOptions::default()
        };
        match solve_modes(&fe, &options) {
            Err(ModalError::MemoryLimit {
                needed_bytes,
                limit_bytes,
                degrees_of_freedom,
                modes,
            }) => {
                assert_eq!(
                    (limit_bytes, degrees_of_freedom, modes),
                    (1 << 20, n as usize, 30)
                );
                assert!(needed_bytes >= 8 * (2 * n * 71 + n * 30), "{needed_bytes}");
                assert!(
                    needed_bytes < 8 * (2 * n * 71 + n * 30) * 2,
                    "{needed_bytes}"
                );
            }
            other => panic!("expected MemoryLimit, got {other:?}"),
        }
        let basis = solve_modes(
            &fe,
            &ModalOptions {
                memory_limit_bytes: DEFAULT_MODAL_MEMORY_LIMIT,
                ..options
            },
        )
        .unwrap();
        assert_eq!(basis.modes.len(), 30);
    }

    /// Closed form of a simply supported Euler–Bernoulli beam, ω_n² = (nπ/L)⁴ EI/m̄
    /// (docs/verification.md §1).
    fn closed_form_eigenvalue(n: usize, l: f64, ei: f64, mass: f64) -> f64 {
        (n as f64 * PI / l).powi(4) * ei / mass
    }

    /// Round-off bound of ω_n² on `elements` elements: ω² is the Rayleigh quotient φᵀKφ (φᵀMφ
    /// = 1), whose rounding is ≈ (u/2)|φ|ᵀ|K||φ| ≈ (u/2) · 24EI/(m̄h⁴) for a smooth φ
    /// (‖φ‖² ≈ 1/(m̄h), row sums of |K| ≈ 24EI/h³), relative (u/2) · 24 (L/h)⁴/(nπ)⁴:
    /// 1.7e-6 for mode 1 at L/h = 500. The Hermite FE error (nπh/L)⁴/720 is far below it.
    fn rounding_bound(n: usize, elements: usize) -> f64 {
        0.5 * f64::EPSILON * 24.0 * (elements as f64 / (n as f64 * PI)).powi(4)
    }

    /// 0.05 m elements on a 25 m beam (L/h = 500, 1002 DOFs): refused before by the relative
    /// residual ‖Kφ − λMφ‖/‖Kφ‖ = 6.8e-6 > 1e-6 of mode 1 (issue 14). The backward error is at
    /// round-off, and ω_n² matches the closed form within [`rounding_bound`] (measured 1.2e-7
    /// for mode 1 against the bound 1.7e-6).
    #[test]
    fn a_beam_meshed_at_span_over_500_is_accepted_and_matches_the_closed_form_frequencies() {
        let (fe, l, ei, mass) = fine_simply_supported_beam(500);
        let options = ModalOptions {
            mode_count: 5,
            ..ModalOptions::default()
        };
        let basis = solve_modes(&fe, &options).expect("a fine mesh is a valid model");
        for (index, mode) in basis.modes.iter().enumerate() {
            let exact = closed_form_eigenvalue(index + 1, l, ei, mass);
            let error = (mode.circular_frequency.powi(2) - exact).abs() / exact;
            let bound = rounding_bound(index + 1, 500);
            assert!(
                error < bound,
                "mode {}: ω² error {error:e} > {bound:e}",
                index + 1
            );
            assert!(
                mode.residual < 1e-12,
                "mode {}: η {:e}",
                index + 1,
                mode.residual
            );
        }
    }

    /// 340 modes of the 25 m beam on 250 elements (502 DOFs): mode 1 (ω² = 660.9 rad²/s²) was
    /// called a mechanism, because zero was judged relative to the largest eigenvalue computed
    /// (1e-10 × 7e12), which grows with the number of modes (issue 17, defect 7). Zero is now
    /// the model's scale 1e-12 · mean diag K / mean diag M, whatever the number of modes.
    #[test]
    fn many_modes_of_a_fine_beam_are_not_a_mechanism_and_mode_1_matches_the_closed_form() {
        let (fe, l, ei, mass) = fine_simply_supported_beam(250);
        let options = ModalOptions {
            mode_count: 340,
            ..ModalOptions::default()
        };
        let basis = solve_modes(&fe, &options).expect("a supported beam is no mechanism");
        assert_eq!(basis.mode_count(), 340);
        let exact = closed_form_eigenvalue(1, l, ei, mass);
        let error = (basis.modes[0].circular_frequency.powi(2) - exact).abs() / exact;
        let bound = rounding_bound(1, 250);
        assert!(error < bound, "mode 1: ω² error {error:e} > {bound:e}");
    }

    /// A pair that is not an eigenpair is still refused: the first mode of the fine beam with
    /// 1e-4 of a deterministic rough vector added (relative, in the 2-norm), λ its Rayleigh
    /// quotient. Its rough part excites the top of the spectrum, so its backward error is
    /// ≈ 1e-4 ≫ 1e-6, while the exact pair's is at round-off.
    #[test]
    fn a_perturbed_eigenpair_of_a_fine_beam_is_refused_by_the_backward_error() {
        use crate::linalg::{backward_error, lowest_eigenpairs, LanczosOptions, PencilNorms};
        let (fe, ..) = fine_simply_supported_beam(500);
        let (k, m) = (&fe.stiffness, &fe.mass);
        let lanczos = LanczosOptions {
            shift: -1.0,
            ..LanczosOptions::default()
        };
        let mut pairs = lowest_eigenpairs(k, m, 1, &lanczos).unwrap();
        check_backward_errors(&pairs, 1e-6).expect("the computed pair is accepted");
        let phi = pairs.vector(0).to_vec();
        let norm = phi.iter().map(|v| v * v).sum::<f64>().sqrt();
        let rough: Vec<f64> = (0..phi.len())
            .map(|i| ((i * 7919) % 101) as f64 / 101.0 - 0.5)
            .collect();
        let rough_norm = rough.iter().map(|v| v * v).sum::<f64>().sqrt();
        let wrong: Vec<f64> = phi
            .iter()
            .zip(&rough)
            .map(|(p, r)| p + 1e-4 * norm * r / rough_norm)
            .collect();
        let lambda = k.bilinear(&wrong, &wrong) / m.bilinear(&wrong, &wrong);
        let eta = backward_error(k, m, PencilNorms::of(k, m), lambda, &wrong);
        assert!(eta > 1e-5, "backward error of the perturbed pair {eta:e}");
        pairs.vectors = wrong;
        pairs.eigenvalues[0] = lambda;
        pairs.residuals[0] = eta;
        assert!(matches!(
            check_backward_errors(&pairs, 1e-6),
            Err(EigenError::ResidualTooLarge { index: 0, .. })
        ));
    }

    /// Modal bending moments of a simply supported beam (40 elements) against the closed form
    /// M_n(x) = EI φ_n''(x) = −EI (nπ/L)² √(2/(m̄L)) sin(nπx/L) for modes 1–10, at a station
    /// x = 0.35 L (no mode of 1–10 has a node there; |sin(nπx/L)| ≥ 0.156), the error measured
    /// relative to the amplitude EI (nπ/L)² √(2/(m̄L)).
    /// Reference: docs/verification.md §1 (SS beam modes, modal mass m̄L/2).
    #[test]
    fn modal_moments_of_a_simply_supported_beam_match_the_curvature_for_modes_1_to_10() {
        let (l, ei, mass) = (20.0, 4.86535e10, 18358.0);
        let beam = ContinuousBeam::pinned(
            vec![l],
            BeamSection {
                flexural_rigidity: ei,
                mass_per_length: mass,
            },
        );
        let elements = 40;
        let h = l / elements as f64;
        let x = 0.35 * l;
        let options = MeshOptions {
            elements_per_span: Some(elements),
            default_stations: false,
            stations: vec![StationRequest {
                name: Some("x7".into()),
                position: x,
                target: StationTarget::Section,
            }],
            ..MeshOptions::default()
        };
        let fe = discretise(&BridgeModel::ContinuousBeam(beam), &options).unwrap();
        let basis = solve_modes(
            &fe,
            &ModalOptions {
                mode_count: 10,
                ..ModalOptions::default()
            },
        )
        .unwrap();
        let deflection = basis.station_values(0, Quantity::Deflection);
        let moment = basis.station_values(0, Quantity::BendingMoment);
        let amplitude = (2.0 / (mass * l)).sqrt();
        // The stiffness rows alone (the reading before the inertia rows), for comparison.
        let mut stiffness_only = fe.clone();
        for f in &mut stiffness_only.station_functionals {
            f.moment_left_mass.clear();
            f.moment_right_mass.clear();
        }
        let old_basis = solve_modes(
            &stiffness_only,
            &ModalOptions {
                mode_count: 10,
                ..ModalOptions::default()
            },
        )
        .unwrap();
        let old_moment = old_basis.station_values(0, Quantity::BendingMoment);
        for n in 1..=10 {
            let k = n as f64 * PI / l;
            let sine = (k * x).sin();
            // Sign of the FE mode: from its deflection at the station (nodal deflections are
            // superconvergent, the sign is unambiguous where |sin| > 0.1; here |sin| ≥ 0.156).
            let sign = (deflection[n - 1] / (amplitude * sine)).signum();
            let exact = -ei * k * k * amplitude * sine * sign;
            let scale = ei * k * k * amplitude;
            let error = (moment[n - 1] - exact).abs() / scale;
            // Tolerance: with the inertia rows the end forces are those of the FE solution, so
            // the error is the Hermite discretisation error of the mode, O((nπh/L)⁴): eigenvalue
            // error (nπh/L)⁴/720 and a comparable curvature error at the nodes. Bound
            // (nπh/L)⁴/100 (≤ 3.8e-3 at n = 10), against the stiffness-only reading's
            // (nπh/L)²/12 (5 % at n = 10).
            let khat = k * h;
            let bound = khat.powi(4) / 100.0 + 1e-9;
            assert!(
                error <= bound,
                "mode {n}: moment {} vs {exact}: relative error {error:e} > {bound:e}",
                moment[n - 1]
            );
            // The stiffness-only reading is off by ≈ (nπh/L)²/12 of the amplitude·|sin|.
            let old_error = (old_moment[n - 1] - exact).abs() / (scale * sine.abs());
            let expected = khat * khat / 12.0;
            assert!(
                (old_error - expected).abs() <= 0.2 * expected,
                "mode {n}: stiffness-only error {old_error:e}, expected ≈ {expected:e}"
            );
            // Deflection amplitude check: (nπh/L)⁴-level nodal error.
            let w_error = (deflection[n - 1] - amplitude * sine * sign).abs() / amplitude;
            assert!(w_error <= bound, "mode {n}: deflection error {w_error:e}");
        }
    }
}
