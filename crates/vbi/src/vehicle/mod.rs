//! Vehicle models: moving forces up to 3D multibody trucks, assembled as M, C, K (paper Eq. 19).

use nalgebra::DMatrix;

/// How a tyre meets the road.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactKind {
    /// A constant moving force: the contact has no stiffness and no DOF (the paper's §2 load).
    Force,
    /// A tyre spring and damper under a wheel whose vertical displacement is a combination of
    /// vehicle DOFs.
    Tyre {
        /// Tyre stiffness k_t [N/m].
        stiffness: f64,
        /// Tyre damping c_t [N·s/m].
        damping: f64,
        /// Wheel vertical displacement [m] = Σ coefficient · Z[dof] (upwards positive).
        coupling: Vec<(usize, f64)>,
    },
}

/// One tyre contact (one wheel, or one axle of a 2D model).
#[derive(Debug, Clone, PartialEq)]
pub struct TyreContact {
    /// Position along the direction of travel relative to the front axle [m]; ≤ 0.
    pub longitudinal_offset: f64,
    /// Lateral position from the vehicle centreline [m], positive to the left.
    pub lateral_offset: f64,
    /// Static load on the road at equilibrium [N], downwards positive.
    pub static_load: f64,
    /// Force-only or tyre.
    pub kind: ContactKind,
}

/// A vehicle as the solver needs it. DOFs Z are measured from static equilibrium on a flat rigid
/// road, upwards positive; so gravity is already balanced by the static tyre loads.
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleModel {
    /// Name (preset name or file stem).
    pub name: String,
    /// One name per DOF, for example `tractor_bounce`, `axle3_roll`.
    pub dof_names: Vec<String>,
    /// Mass matrix M_v [kg, kg·m²].
    pub mass_matrix: DMatrix<f64>,
    /// Damping matrix C_v [N·s/m, ...].
    pub damping_matrix: DMatrix<f64>,
    /// Stiffness matrix K_v, suspension and tyres on a rigid road [N/m, ...].
    pub stiffness_matrix: DMatrix<f64>,
    /// Tyre contacts, front to back.
    pub contacts: Vec<TyreContact>,
}

impl VehicleModel {
    /// Number of vehicle DOFs.
    pub fn dof_count(&self) -> usize {
        self.dof_names.len()
    }

    /// Total weight carried by the contacts [N].
    pub fn total_static_load(&self) -> f64 {
        self.contacts.iter().map(|c| c.static_load).sum()
    }
}
