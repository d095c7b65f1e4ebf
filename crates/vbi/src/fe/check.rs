//! Checks of an FE model before any solve: that its parts fit together
//! ([`validate_fe_model`]), and whether its stiffness is singular, with the free direction of a
//! mechanism named ([`factor_is_singular`], [`diagnose_mechanism`]). The static solve
//! ([`super::statics`]) and the modal analysis (`solve_modes` of the `modal` stage) both use them.
//!
//! [`ModalError`] lives here, not in `modal`, because a mechanism found by either solve is
//! reported with the same value: the static solve wraps it in
//! [`StaticError::Mechanism`](super::statics::StaticError::Mechanism), and `modal` re-exports
//! the type as `modal::ModalError` for its own errors (eigensolver, options).

use thiserror::Error;

use crate::linalg::{
    lowest_eigenpairs, CholeskyFactor, EigenError, LanczosOptions, LinalgError, SparseMatrix,
};

use super::{Direction, FeModel};

/// Errors of the checks of an FE model and of its modal analysis (a mechanism, an indefinite
/// stiffness, inconsistent parts; and, from `modal::solve_modes`, the eigensolver and its options).
/// Re-exported as `modal::ModalError`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ModalError {
    /// The model can move without straining: a zero (or negative) eigenvalue.
    #[error(
        "the bridge model is a mechanism: it can move freely in {direction:?} (a rigid-body mode \
         with ω² = {eigenvalue:e} rad²/s², largest at degree of freedom {dof}); add a support \
         that restrains {direction:?}"
    )]
    Mechanism {
        /// Dominant direction of the rigid-body motion, by kinetic energy.
        direction: Direction,
        /// The degree of freedom that moves most.
        dof: usize,
        /// The eigenvalue found [rad²/s²] (≈ 0, or negative).
        eigenvalue: f64,
    },
    /// The stiffness matrix is indefinite and no rigid-body mode could be isolated.
    #[error(
        "the stiffness matrix is not positive definite (Cholesky failed at degree of freedom \
         {dof}, direction {direction:?}): the model is unstable or unrestrained in {direction:?}"
    )]
    Unstable {
        /// Degree of freedom where the factorisation failed.
        dof: usize,
        /// Its direction.
        direction: Direction,
    },
    /// The eigensolver failed.
    #[error(transparent)]
    Eigen(#[from] EigenError),
    /// The model's parts are inconsistent (a programming error upstream).
    #[error("inconsistent FE model: {message}")]
    InvalidModel {
        /// What is inconsistent.
        message: String,
    },
    /// The damping law cannot give the retained modes their ratios.
    #[error("invalid modal damping: {0}")]
    Damping(#[from] crate::model::ModelError),
    /// The analysis would allocate more than `ModalOptions::memory_limit_bytes`.
    #[error(
        "the modal analysis of {degrees_of_freedom} degrees of freedom for {modes} modes would \
         need about {:.1} GiB (the Cholesky factor and the Lanczos basis), over the limit of \
         {:.1} GiB; ask for fewer modes or use a coarser mesh (a longer element_length_m)",
        *needed_bytes as f64 / (1u64 << 30) as f64,
        *limit_bytes as f64 / (1u64 << 30) as f64
    )]
    MemoryLimit {
        /// The estimate [bytes].
        needed_bytes: u64,
        /// The limit [bytes].
        limit_bytes: u64,
        /// Size of the model.
        degrees_of_freedom: usize,
        /// Modes asked for (capped at the DOFs with mass).
        modes: usize,
    },
    /// The analysis would take more arithmetic than [`MODAL_WORK_LIMIT`](crate::modal::MODAL_WORK_LIMIT).
    #[error(
        "the modal analysis of {degrees_of_freedom} degrees of freedom for {modes} modes would \
         take about {} multiply-adds per Lanczos pass (n × dim², a Krylov basis of {krylov_dimension} \
         vectors), over the limit of {}: hours of work; ask for fewer modes or use a coarser \
         mesh (a longer element_length_m)",
        crate::units::shown(*work),
        crate::units::shown(crate::modal::MODAL_WORK_LIMIT)
    )]
    WorkLimit {
        /// The estimate [multiply-adds per pass].
        work: f64,
        /// Size of the model.
        degrees_of_freedom: usize,
        /// Modes asked for (capped at the DOFs with mass).
        modes: usize,
        /// Vectors of the Krylov basis.
        krylov_dimension: usize,
    },
    /// An option is out of range.
    #[error("modal option `{option}` = {value} is not allowed: {allowed}")]
    InvalidOption {
        /// Name of the option.
        option: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
}

/// Checks that the parts of an FE model fit together.
pub fn validate_fe_model(model: &FeModel) -> Result<(), ModalError> {
    let n = model.stiffness.size;
    let bad = |message: String| Err(ModalError::InvalidModel { message });
    if n == 0 {
        return bad("the model has no free degree of freedom".into());
    }
    if model.mass.size != n {
        return bad(format!("K is {n}×{n} but M is {0}×{0}", model.mass.size));
    }
    if model.dof_directions.len() != n {
        return bad(format!(
            "{} DOF directions for {n} DOFs",
            model.dof_directions.len()
        ));
    }
    if model.deck_dofs.len() != model.deck.node_count() {
        return bad(format!(
            "{} deck-node DOF maps for {} deck nodes",
            model.deck_dofs.len(),
            model.deck.node_count()
        ));
    }
    if model.station_functionals.len() != model.stations.len() {
        return bad(format!(
            "{} station functionals for {} stations",
            model.station_functionals.len(),
            model.stations.len()
        ));
    }
    let rows = model
        .deck_dofs
        .iter()
        .flat_map(|d| [&d.deflection, &d.slope])
        .chain(model.station_functionals.iter().flat_map(|f| {
            [
                &f.deflection,
                &f.moment_left,
                &f.moment_right,
                &f.moment_left_mass,
                &f.moment_right_mass,
                &f.shear_left,
                &f.shear_right,
                &f.shear_left_mass,
                &f.shear_right_mass,
                &f.reaction,
                &f.reaction_mass,
            ]
        }));
    let deck_nodes = model.deck.node_count();
    for f in &model.station_functionals {
        if let Some(&node) = f.reaction_nodes.iter().find(|&&node| node >= deck_nodes) {
            return bad(format!(
                "a reaction reads deck node {node} (the deck has {deck_nodes} nodes)"
            ));
        }
    }
    for row in rows {
        for &(dof, c) in row {
            if dof >= n || !c.is_finite() {
                return bad(format!(
                    "a functional reads DOF {dof} with coefficient {c} (the model has {n} DOFs)"
                ));
            }
        }
    }
    if !(model.damping_ratio.is_finite() && model.damping_ratio >= 0.0) {
        return bad(format!("damping ratio {}", model.damping_ratio));
    }
    if let Some(law) = &model.mode_damping {
        law.validate()?;
    }
    Ok(())
}

/// Relative size of the shift added below `ModalOptions::shift`, times mean diag(K)/mean diag(M)
/// (≈ the largest ω² of the mesh): 1e-12 is 10⁴ × round-off, enough for a singular K to
/// factorise. A shift, not a threshold: eigenvalues are judged by [`RIGID_BODY_LEVEL`].
pub(crate) const REGULARISATION: f64 = 1e-12;

/// Level, times mean diag(K)/mean diag(M), at or below which an eigenvalue (or the Rayleigh
/// quotient of inverse iteration) is zero, i.e. a rigid-body mode of a mechanism. A rigid-body
/// mode comes out of the factorisation at round-off, at most ε ‖K‖/‖M‖ with ε = 2.2·10⁻¹⁶ and a
/// modest growth (10⁻²² of the ratio for the free axial motion of a beam): 10⁻¹⁴ is 45 ε. A
/// beam's lowest mode, ω₁² ≈ c (h/L)⁴ × the ratio (c ≈ 3 simply supported, 0.4 cantilever),
/// stays above it up to the `fe::MAX_ELEMENTS_PER_SPAN` = 2000 elements per span that the mesher
/// allows (1.9·10⁻¹³ measured simply supported, 2.4·10⁻¹⁴ for a cantilever).
pub(crate) const RIGID_BODY_LEVEL: f64 = 1e-14;

/// mean |diag K| / mean |diag M| [rad²/s²]: the scale of the mesh's largest eigenvalues.
pub(crate) fn stiffness_mass_ratio(model: &FeModel) -> f64 {
    let mean = |d: Vec<f64>| d.iter().map(|v| v.abs()).sum::<f64>() / d.len().max(1) as f64;
    let (k, m) = (
        mean(model.stiffness.diagonal()),
        mean(model.mass.diagonal()),
    );
    if k > 0.0 && m > 0.0 && (k / m).is_finite() {
        k / m
    } else {
        1.0
    }
}

/// True when a factorised K (possibly with a round-off pivot) is numerically singular: a few
/// steps of inverse iteration x ← K⁻¹Mx converge to the lowest mode from above, and a Rayleigh
/// quotient xᵀKx/xᵀMx below [`RIGID_BODY_LEVEL`] × [`stiffness_mass_ratio`] is a rigid-body mode.
pub(crate) fn factor_is_singular(model: &FeModel, factor: &CholeskyFactor) -> bool {
    let n = model.dof_count();
    let mut x: Vec<f64> = (0..n)
        .map(|i| 1.0 + ((i * 7919) % 101) as f64 / 101.0)
        .collect();
    let mut y = vec![0.0; n];
    let mut quotient = f64::INFINITY;
    for _ in 0..8 {
        model.mass.multiply(&x, &mut y);
        if factor.solve_in_place(&mut y).is_err() {
            return true;
        }
        let norm = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return !norm.is_finite();
        }
        for (a, b) in x.iter_mut().zip(&y) {
            *a = b / norm;
        }
        let mass = model.mass.bilinear(&x, &x);
        if mass > 0.0 {
            quotient = model.stiffness.bilinear(&x, &x) / mass;
        }
    }
    quotient <= RIGID_BODY_LEVEL * stiffness_mass_ratio(model)
}

/// Names the free direction of a model whose stiffness does not factorise.
///
/// K + αM, with α = c · mean(diag K)/mean(diag M) > 0, is positive definite when K is only
/// singular; its lowest eigenpair is then the rigid-body mode (ω² ≈ 0), whose dominant direction
/// by kinetic energy is returned in [`ModalError::Mechanism`]. c is tried from
/// [`REGULARISATION`] up to 1e-6: a small α keeps the rigid-body mode apart from the first
/// elastic one in the inverted spectrum (1/α against 1/(α + ω₁²), which a fine mesh's small ω₁²
/// would merge at a large α), a larger one lets a K indefinite by more than round-off
/// factorise. If K + αM fails at every α (K is indefinite beyond −α), the failing pivot's
/// direction is returned in [`ModalError::Unstable`].
pub fn diagnose_mechanism(model: &FeModel) -> ModalError {
    let k = &model.stiffness;
    let m = &model.mass;
    let ratio = stiffness_mass_ratio(model);
    for level in [REGULARISATION, 1e-9, 1e-6] {
        // No residual limit: a rigid-body mode has Kφ ≈ 0, so its relative residual means
        // nothing.
        let options = LanczosOptions {
            shift: -level * ratio,
            residual_limit: f64::INFINITY,
            ..Default::default()
        };
        if let Ok(pairs) = lowest_eigenpairs(k, m, 1, &options) {
            let (direction, dof) = dominant_direction(model, pairs.vector(0));
            return ModalError::Mechanism {
                direction,
                dof,
                eigenvalue: pairs.eigenvalues[0],
            };
        }
    }
    let dof = match CholeskyFactor::new(k) {
        Err(LinalgError::NotPositiveDefinite { dof, .. }) => dof,
        _ => 0,
    };
    ModalError::Unstable {
        dof,
        direction: model
            .dof_directions
            .get(dof)
            .copied()
            .unwrap_or(Direction::TranslationZ),
    }
}

/// Direction with the largest kinetic-energy share of a vector, and its largest DOF.
pub(crate) fn dominant_direction(model: &FeModel, vector: &[f64]) -> (Direction, usize) {
    let shares = direction_energies(&model.mass, &model.dof_directions, vector);
    let direction = Direction::ALL
        .iter()
        .zip(shares)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(d, _)| *d)
        .unwrap_or(Direction::TranslationZ);
    let dof = vector
        .iter()
        .enumerate()
        .filter(|(i, _)| model.dof_directions[*i] == direction)
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map(|(i, _)| i)
        .unwrap_or(0);
    (direction, dof)
}

/// Kinetic-energy share of each direction (in the order of `Direction::ALL`):
/// e_d = Σ_{i: dir(i) = d} φ_i (Mφ)_i, clamped at zero (consistent-mass coupling between
/// translations and rotations can make a small share negative).
pub(crate) fn direction_energies(
    m: &SparseMatrix,
    directions: &[Direction],
    vector: &[f64],
) -> [f64; 6] {
    let mut mv = vec![0.0; m.size];
    m.multiply(vector, &mut mv);
    let mut e = [0.0; 6];
    for i in 0..m.size {
        let d = Direction::ALL
            .iter()
            .position(|&a| a == directions[i])
            .unwrap_or(2);
        e[d] += vector[i] * mv[i];
    }
    e.map(|v| v.max(0.0))
}
