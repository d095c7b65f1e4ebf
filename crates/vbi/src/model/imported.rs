//! A bridge brought as matrices from another FE program (OpenSees, ANSYS, Abaqus, ospgrillage):
//! sparse K and M over the model's free degrees of freedom, the node and direction of each, and
//! the deck lines (girders) that the wheels run on.
//!
//! [`crate::fe::discretise`] turns it into an [`FeModel`](crate::fe::FeModel) as it does vbi's
//! own models, so the modal analysis (vbi's Lanczos), the exact static reference (influence
//! lines from K), the stations and the crossing are the same code. Everything here is in vbi's
//! units and axes (SI; x along the bridge from the first support, y to the left, z up): the
//! input reader converts the declared units and axes once.
//!
//! The bending moment at a station is the end moment of a Hermite beam element between two
//! consecutive deck nodes of its line, k_e u_e with the line's EI (and −ω² m_e u_e with its mass
//! per length for a mode), as for vbi's own girders: exact when the other program's girder is
//! an Euler–Bernoulli frame member between those nodes. Shear forces and support reactions are
//! not available (the matrices hold no restrained DOF and no element).

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::linalg::SparseMatrix;

use super::{Damage, Direction, ModeDamping, ModelError};

/// One longitudinal line of deck nodes (a girder) of an imported model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImportedDeckLine {
    /// Lateral position y of the line [m], from the deck's centreline, positive to the left.
    pub lateral_position: f64,
    /// Node tags along the line, in the other program's numbering, by ascending x.
    pub nodes: Vec<u64>,
    /// Longitudinal position x of each node [m] from the first support, strictly ascending,
    /// from 0 to the bridge length.
    pub node_positions: Vec<f64>,
    /// Flexural rigidity EI of the girder in vertical bending [N·m²]: reads the bending moment
    /// at the line's stations.
    pub flexural_rigidity: f64,
    /// Mass per length of the girder [kg/m] in its consistent-mass matrix (0 for a lumped-mass
    /// model): the inertia part of a mode's moment.
    pub mass_per_length: f64,
}

/// A bridge given as the sparse stiffness and mass matrices of another program's FE model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImportedMatrices {
    /// Stiffness K over the free DOFs, both triangles [N/m, N, N·m by DOF kind].
    pub stiffness: Arc<SparseMatrix>,
    /// Mass M over the same DOFs [kg, kg·m, kg·m²].
    pub mass: Arc<SparseMatrix>,
    /// Node tag of each DOF (matrix row), in the other program's numbering.
    pub dof_nodes: Arc<Vec<u64>>,
    /// Direction of each DOF in vbi's axes.
    pub dof_directions: Arc<Vec<Direction>>,
    /// The deck lines, at least one, in any order.
    pub deck_lines: Vec<ImportedDeckLine>,
    /// Span lengths between consecutive support lines [m].
    pub span_lengths: Vec<f64>,
    /// Modal damping ratio ζ [-] of every mode (unless `mode_damping` is given).
    pub damping_ratio: f64,
    /// A ratio per mode or Rayleigh damping instead of `damping_ratio`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode_damping: Option<ModeDamping>,
    /// Always intact: stiffness losses and changed supports need vbi's own model (kept so that
    /// every bridge answers [`super::BridgeModel::damage`]).
    #[serde(default, skip_serializing_if = "Damage::is_intact")]
    pub damage: Damage,
    /// Where the matrices came from (the files), for messages and reports.
    pub source: String,
}

/// Relative asymmetry above which a matrix is refused: |a_ij − a_ji| against the larger of
/// |a_ij|, |a_ji| and 10⁻¹² of the largest diagonal entry. Programs write 15 to 17 significant
/// digits; 10⁻⁸ leaves room for a format with 9 (single-precision exports are refused).
pub const SYMMETRY_TOLERANCE: f64 = 1e-8;

/// The worst asymmetric pair of a square sparse matrix: (row, column, relative difference),
/// None when every pair agrees within [`SYMMETRY_TOLERANCE`].
pub fn asymmetry(matrix: &SparseMatrix) -> Option<(usize, usize, f64)> {
    let diagonal_scale = matrix
        .diagonal()
        .iter()
        .fold(0.0_f64, |a, d| a.max(d.abs()));
    let entry = |row: usize, column: usize| -> f64 {
        let range = matrix.column_pointers[column]..matrix.column_pointers[column + 1];
        let rows = &matrix.row_indices[range.clone()];
        rows.binary_search(&row)
            .map_or(0.0, |k| matrix.values[range.start + k])
    };
    let mut worst: Option<(usize, usize, f64)> = None;
    for column in 0..matrix.size {
        for k in matrix.column_pointers[column]..matrix.column_pointers[column + 1] {
            let row = matrix.row_indices[k];
            if row <= column {
                continue;
            }
            let (a, b) = (matrix.values[k], entry(column, row));
            let scale = a.abs().max(b.abs()).max(1e-12 * diagonal_scale);
            let relative = if scale > 0.0 {
                (a - b).abs() / scale
            } else {
                0.0
            };
            if relative > SYMMETRY_TOLERANCE && worst.is_none_or(|w| relative > w.2) {
                worst = Some((row, column, relative));
            }
        }
    }
    worst
}

impl ImportedMatrices {
    /// Total length between the end supports [m].
    pub fn length(&self) -> f64 {
        self.span_lengths.iter().sum()
    }

    /// The mass that moves with a unit vertical translation of every free vertical DOF,
    /// rᵀ M r with r = 1 on each z translation [kg]: the model's vertically moving mass (the
    /// mass lumped on restrained DOFs is not in M).
    pub fn vertical_mass(&self) -> f64 {
        let r: Vec<f64> = self
            .dof_directions
            .iter()
            .map(|&d| f64::from(u8::from(d == Direction::TranslationZ)))
            .collect();
        self.mass.bilinear(&r, &r)
    }

    /// Checks the matrices, the DOF list and the deck lines against each other.
    pub fn validate(&self) -> Result<(), ModelError> {
        let invalid = |message: String| Err(ModelError::ImportedMatrices { message });
        let n = self.stiffness.size;
        if n == 0 {
            return invalid("the stiffness matrix has no row".into());
        }
        if self.mass.size != n {
            return invalid(format!("K is {n}×{n} but M is {0}×{0}", self.mass.size));
        }
        if self.dof_nodes.len() != n || self.dof_directions.len() != n {
            return invalid(format!(
                "the DOF map lists {} DOFs for {n} matrix rows",
                self.dof_nodes.len()
            ));
        }
        for (name, matrix) in [("K", &self.stiffness), ("M", &self.mass)] {
            if let Some(value) = matrix.values.iter().find(|v| !v.is_finite()) {
                return invalid(format!("{name} holds the value {value}"));
            }
            if let Some((row, column, relative)) = asymmetry(matrix) {
                return invalid(format!(
                    "{name} is not symmetric: entries ({}, {}) and ({}, {}) differ by {relative:.2e} \
                     relative (at most {SYMMETRY_TOLERANCE:e})",
                    row + 1,
                    column + 1,
                    column + 1,
                    row + 1
                ));
            }
            if let Some(row) = matrix.diagonal().iter().position(|&d| d < 0.0) {
                return invalid(format!(
                    "{name} has a negative diagonal entry at row {} (a stiffness or mass matrix \
                     is positive semi-definite)",
                    row + 1
                ));
            }
        }
        super::require_spans(&self.span_lengths)?;
        if self.deck_lines.is_empty() {
            return invalid("no deck line given".into());
        }
        let length = self.length();
        let tolerance = 1e-6 * length;
        for line in &self.deck_lines {
            self.validate_line(line, length, tolerance)?;
        }
        let mut positions: Vec<f64> = self.deck_lines.iter().map(|l| l.lateral_position).collect();
        positions.sort_by(f64::total_cmp);
        if positions.windows(2).any(|w| w[1] - w[0] <= 1e-6) {
            return invalid("two deck lines at the same lateral position".into());
        }
        super::require_damping(self.damping_ratio)?;
        if !self.damage.is_intact() {
            return invalid(
                "stiffness losses and changed supports need one of vbi's own models; change the \
                 imported model in its own program instead"
                    .into(),
            );
        }
        if let Some(law) = &self.mode_damping {
            law.validate()?;
        }
        Ok(())
    }

    fn validate_line(
        &self,
        line: &ImportedDeckLine,
        length: f64,
        tolerance: f64,
    ) -> Result<(), ModelError> {
        let invalid = |message: String| Err(ModelError::ImportedMatrices { message });
        let y = line.lateral_position;
        if !y.is_finite() {
            return invalid(format!("a deck line's lateral position is {y}"));
        }
        if line.nodes.len() < 2 || line.nodes.len() != line.node_positions.len() {
            return invalid(format!(
                "the deck line at y = {y} m has {} node(s) and {} position(s); at least 2 of \
                 each, as many positions as nodes",
                line.nodes.len(),
                line.node_positions.len()
            ));
        }
        let xs = &line.node_positions;
        if xs.iter().any(|x| !x.is_finite()) || xs.windows(2).any(|w| w[1] <= w[0]) {
            return invalid(format!(
                "the nodes of the deck line at y = {y} m are not in strictly ascending x"
            ));
        }
        let (first, last) = (xs[0], xs[xs.len() - 1]);
        if first.abs() > tolerance || (last - length).abs() > tolerance {
            return invalid(format!(
                "the deck line at y = {y} m runs from x = {first} m to {last} m; it must run \
                 from the first support (x = 0) to the last (x = {length} m)"
            ));
        }
        super::require_positive("deck line flexural rigidity", line.flexural_rigidity)?;
        super::require_non_negative("deck line mass per length", line.mass_per_length)?;
        Ok(())
    }
}
