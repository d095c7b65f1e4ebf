//! Finite-element discretisation: `discretise(&BridgeModel, &MeshOptions) -> FeModel`, the
//! stations it defines, the checks of an FE model (consistency, mechanism), and the exact static
//! response from the full stiffness.

use serde::{Deserialize, Serialize};

use crate::deck::DeckGeometry;
use crate::linalg::SparseMatrix;

mod check;
pub mod influence;
pub mod statics;

pub use check::{diagnose_mechanism, validate_fe_model, ModalError};
pub(crate) use check::{
    direction_energies, dominant_direction, factor_is_singular, stiffness_mass_ratio,
    REGULARISATION, RIGID_BODY_LEVEL,
};
// Stations are part of the bridge's description (an imported model lists its own); re-exported
// here, where the FE stage defines and reads them.
pub use crate::model::station::{Quantity, Station, StationTarget};

// The DOF directions belong to the model (an imported model lists them); re-exported here,
// where the FE stage uses them.
pub use crate::model::Direction;

/// A linear functional of the free displacements, `value = Σ coefficient · u[dof]`.
pub type SparseRow = Vec<(usize, f64)>;

/// How a deck node's vertical deflection and slope dw/dx read the free DOFs.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct DeckNodeDofs {
    /// Deflection w [m] = Σ coefficient · u (empty at a vertically restrained node).
    pub deflection: SparseRow,
    /// Slope dw/dx [-] = Σ coefficient · u (the rotation DOF with its sign).
    pub slope: SparseRow,
}

/// Linear functionals that read a station's responses from the free displacements.
///
/// The bending moment comes from element end forces, not from curvature differences.
/// `moment_left` uses the element ending at the station, `moment_right` the one starting there;
/// each (k_e u_e, the stiffness row) is exact for static loads outside its own element. Under
/// the inertia loads of a mode the element end force is (k_e − ω² m_e) φ_e: the `_mass` rows are
/// the same end-moment rows of the element's consistent mass m_e, so that the modal moment is
/// `moment_left·φ − ω² moment_left_mass·φ` (empty rows: no inertia correction).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct StationFunctional {
    /// Deflection [m] positive upwards.
    pub deflection: SparseRow,
    /// Sagging-positive bending moment [N·m] from the element left of the station.
    pub moment_left: SparseRow,
    /// Sagging-positive bending moment [N·m] from the element right of the station.
    pub moment_right: SparseRow,
    /// Row of the left element's consistent mass for the same end moment [kg·m per unit DOF]:
    /// the end moment of the element's inertia forces is −ω²·(this row)·u (default empty).
    #[serde(default)]
    pub moment_left_mass: SparseRow,
    /// Row of the right element's consistent mass for the same end moment (default empty).
    #[serde(default)]
    pub moment_right_mass: SparseRow,
    /// Shear force V = dM/dx [N] from the end force of the element left of the station,
    /// V = −f_w2 (exact for static loads outside that element). Empty at a support.
    #[serde(default)]
    pub shear_left: SparseRow,
    /// Shear force [N] from the element right of the station, V = +f_w1.
    #[serde(default)]
    pub shear_right: SparseRow,
    /// Consistent-mass rows of the same end forces (as for the moment).
    #[serde(default)]
    pub shear_left_mass: SparseRow,
    /// Consistent-mass row of `shear_right`.
    #[serde(default)]
    pub shear_right_mass: SparseRow,
    /// Support reaction [N], upward positive, from the free displacements: the stiffness rows
    /// K_cf of the restrained vertical DOFs at the station (R = K_cf u − f_c), or −k at an
    /// elastic support's spring. Empty away from supports.
    #[serde(default)]
    pub reaction: SparseRow,
    /// The consistent-mass rows M_cf of the same restrained DOFs: a mode's reaction is
    /// (K_cf − ω² M_cf) φ.
    #[serde(default)]
    pub reaction_mass: SparseRow,
    /// Deck nodes whose vertical DOF is restrained by the station's bearings: a load's share on
    /// such a node (the restrained component −f_c of its consistent load) goes straight into
    /// the reaction.
    #[serde(default)]
    pub reaction_nodes: Vec<usize>,
}

impl StationFunctional {
    /// Adds one girder line's functional to a whole-section one: the section's deflection is
    /// the mean of the lines' (each weighted by `deflection_share`), its forces and moments the
    /// sum.
    pub(crate) fn add_line(&mut self, line: StationFunctional, deflection_share: f64) {
        self.deflection.extend(
            line.deflection
                .iter()
                .map(|&(d, c)| (d, c * deflection_share)),
        );
        self.moment_left.extend(line.moment_left);
        self.moment_right.extend(line.moment_right);
        self.moment_left_mass.extend(line.moment_left_mass);
        self.moment_right_mass.extend(line.moment_right_mass);
        self.shear_left.extend(line.shear_left);
        self.shear_right.extend(line.shear_right);
        self.shear_left_mass.extend(line.shear_left_mass);
        self.shear_right_mass.extend(line.shear_right_mass);
        self.reaction.extend(line.reaction);
        self.reaction_mass.extend(line.reaction_mass);
        self.reaction_nodes.extend(line.reaction_nodes);
    }
}

/// The discretised bridge: sparse K and M over the free DOFs, and how to read the deck and the
/// stations from them.
#[derive(Debug, Clone, PartialEq)]
pub struct FeModel {
    /// Stiffness K over free DOFs [N/m, N, N·m].
    pub stiffness: SparseMatrix,
    /// Consistent mass M over free DOFs [kg, kg·m, kg·m²].
    pub mass: SparseMatrix,
    /// Direction of each free DOF (for mode classification by kinetic energy).
    pub dof_directions: Vec<Direction>,
    /// Deck lines and nodes.
    pub deck: DeckGeometry,
    /// For each deck node, how its deflection and slope read the free DOFs.
    pub deck_dofs: Vec<DeckNodeDofs>,
    /// Stations of interest.
    pub stations: Vec<Station>,
    /// For each station, the functionals that read its responses.
    pub station_functionals: Vec<StationFunctional>,
    /// Modal damping ratio ζ given to every mode [-], unless `mode_damping` is given.
    pub damping_ratio: f64,
    /// A ratio per retained mode or Rayleigh damping, applied by
    /// [`crate::modal::solve_modes`] after its `keep_kinds` filter (None: `damping_ratio`).
    pub mode_damping: Option<crate::model::ModeDamping>,
    /// Total mass of the model, members plus added masses [kg] (for imported matrices the
    /// mass moving with a vertical translation of the free DOFs).
    pub total_mass: f64,
    /// Whether the station functionals read shear forces and support reactions (vbi's own
    /// models); imported matrices hold neither, and their bases and influence lines leave them
    /// out.
    pub has_station_forces: bool,
}

impl FeModel {
    /// Number of free degrees of freedom.
    pub fn dof_count(&self) -> usize {
        self.stiffness.size
    }
}

mod assembly;
mod damage;
pub mod element;
mod error;
mod export;
mod imported;

pub use export::{export_imported, export_matrices, ExportedMatrices};
pub use imported::discretise_imported;

pub use error::FeError;

pub use assembly::{
    deck_plan, discretise, support_reactions, DeckPlan, MemberKind, MeshOptions, PlanMember,
    StationRequest, SupportReaction, MAX_ELEMENTS_PER_SPAN, MAX_NODE_COUNT,
};
