//! Natural frequencies of a vehicle on a rigid road and the dominant motion of each mode.

use nalgebra::{DMatrix, SymmetricEigen};
use serde::{Deserialize, Serialize};

use super::spec::is_axle_name;
use super::{VehicleError, VehicleModel};

/// The kind of motion that dominates a vehicle mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MotionKind {
    /// Vertical motion of a body.
    BodyBounce,
    /// Pitch of a body.
    BodyPitch,
    /// Roll of a body.
    BodyRoll,
    /// Vertical motion of an axle (wheel hop).
    AxleHop,
    /// Roll of an axle (axle tramp).
    AxleTramp,
}

impl MotionKind {
    /// Label: `bounce`, `pitch`, `roll`, `hop` or `tramp`.
    pub fn label(self) -> &'static str {
        match self {
            MotionKind::BodyBounce => "bounce",
            MotionKind::BodyPitch => "pitch",
            MotionKind::BodyRoll => "roll",
            MotionKind::AxleHop => "hop",
            MotionKind::AxleTramp => "tramp",
        }
    }
}

/// One natural mode of a vehicle on a rigid road.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VehicleMode {
    /// Natural frequency f = ω/2π [Hz].
    pub frequency_hz: f64,
    /// The dominant motion.
    pub motion: MotionKind,
    /// The part that moves most: a body name or `axle<n>`.
    pub part: String,
    /// Share of the modal kinetic energy in the dominant DOF, 0 to 1.
    pub energy_share: f64,
    /// Mass-normalised mode shape in the model's DOFs (φᵀ M φ = 1).
    pub shape: Vec<f64>,
}

impl VehicleMode {
    /// Human label, for example `tractor bounce` or `axle 3 hop`.
    pub fn label(&self) -> String {
        match self.part.strip_prefix("axle") {
            Some(number) if is_axle_name(&self.part) => {
                format!("axle {number} {}", self.motion.label())
            }
            _ => format!("{} {}", self.part, self.motion.label()),
        }
    }
}

/// Natural modes of the vehicle on a rigid road, lowest first: K φ = ω² M φ, a generalised
/// symmetric eigenproblem reduced to a standard one by the Cholesky factor M = L Lᵀ,
/// (L⁻¹ K L⁻ᵀ) y = ω² y, φ = L⁻ᵀ y (nalgebra's symmetric eigensolver).
///
/// The dominant motion is the DOF holding the largest share of the modal kinetic energy,
/// |φ_i (M φ)_i| normalised by Σ_i |φ_i (M φ)_i|. DOF names ending in `_bounce`, `_pitch` and
/// `_roll` classify it; the DOFs of `axle<n>` are hop (bounce) and tramp (roll).
/// A model without DOFs (moving forces) has no modes.
pub fn natural_modes(model: &VehicleModel) -> Result<Vec<VehicleMode>, VehicleError> {
    let n = model.dof_count();
    if n == 0 {
        return Ok(Vec::new());
    }
    let (eigenvalues, shapes) = generalised_eigen(&model.mass_matrix, &model.stiffness_matrix)?;
    let mut modes = Vec::with_capacity(n);
    for k in 0..n {
        let omega_squared = eigenvalues[k];
        if !(omega_squared.is_finite() && omega_squared > 0.0) {
            return Err(VehicleError::Unstable);
        }
        let shape = shapes.column(k).into_owned();
        let momentum = &model.mass_matrix * &shape;
        let energies: Vec<f64> = (0..n).map(|i| (shape[i] * momentum[i]).abs()).collect();
        let total: f64 = energies.iter().sum();
        let (dominant, energy) = energies
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(i, e)| (i, *e))
            .unwrap_or((0, 0.0));
        let (part, motion) = classify(&model.dof_names[dominant]);
        modes.push(VehicleMode {
            frequency_hz: omega_squared.sqrt() / (2.0 * std::f64::consts::PI),
            motion,
            part,
            energy_share: if total > 0.0 { energy / total } else { 0.0 },
            shape: shape.iter().copied().collect(),
        });
    }
    modes.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    Ok(modes)
}

/// Natural frequencies [Hz] with the label of the dominant motion (`tractor bounce`,
/// `axle 2 hop`, ...), lowest first. See [`natural_modes`].
pub fn natural_frequencies(model: &VehicleModel) -> Result<Vec<(f64, String)>, VehicleError> {
    Ok(natural_modes(model)?
        .into_iter()
        .map(|m| (m.frequency_hz, m.label()))
        .collect())
}

/// Eigenvalues ω² (unsorted) and M-normalised eigenvectors (columns) of K φ = ω² M φ.
/// Errors: M not positive definite; K with a zero-frequency mode (a mechanism), detected as
/// ω²_min ≤ 1e-10 ω²_max (real vehicles span 0.5–20 Hz, a ratio of 1e-3 in ω²; round-off in a
/// singular K leaves ~1e-16 ω²_max).
pub(super) fn generalised_eigen(
    mass: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
) -> Result<(Vec<f64>, DMatrix<f64>), VehicleError> {
    let cholesky = mass
        .clone()
        .cholesky()
        .ok_or(VehicleError::MassNotPositiveDefinite)?;
    let l_inverse = cholesky
        .l()
        .try_inverse()
        .ok_or(VehicleError::MassNotPositiveDefinite)?;
    let a = &l_inverse * stiffness * l_inverse.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let eigen = SymmetricEigen::new(a);
    let largest = eigen.eigenvalues.iter().fold(0.0_f64, |m, v| m.max(*v));
    if !(largest.is_finite() && largest > 0.0)
        || eigen
            .eigenvalues
            .iter()
            .any(|v| !v.is_finite() || *v <= 1e-10 * largest)
    {
        return Err(VehicleError::Unstable);
    }
    let shapes = l_inverse.transpose() * &eigen.eigenvectors;
    Ok((eigen.eigenvalues.iter().copied().collect(), shapes))
}

fn classify(dof_name: &str) -> (String, MotionKind) {
    let (part, suffix) = dof_name.rsplit_once('_').unwrap_or((dof_name, "bounce"));
    let axle = is_axle_name(part);
    let motion = match (axle, suffix) {
        (true, "roll") => MotionKind::AxleTramp,
        (true, _) => MotionKind::AxleHop,
        (false, "pitch") => MotionKind::BodyPitch,
        (false, "roll") => MotionKind::BodyRoll,
        (false, _) => MotionKind::BodyBounce,
    };
    (part.to_string(), motion)
}
