//! Modal analysis: `solve_modes(&FeModel, &ModalOptions) -> ModalBasis`, and modal bases
//! imported from other programs.
//!
//! A [`ModalBasis`] is everything later stages need of the bridge: frequencies, damping, mode
//! kinds, mass-normalised mode shapes on the deck (to couple wheels), and each mode's deflection
//! and bending moment at the stations (to build responses). An imported basis fills the same
//! type, so later stages work on it exactly as on our own.

use serde::{Deserialize, Serialize};

use crate::deck::DeckGeometry;

pub mod curvature;
pub mod flexibility;
pub mod import;
pub mod imported_influence;
mod solve;

pub use solve::{
    basis_from_pairs, check_modal_plan, classify_mode, deck_twist_fraction, deck_vertical_shares,
    solve_modes, solve_modes_with, station_moment_row, CheckModes, DeckVerticalShares,
    ModalOptions, CHECK_FREQUENCY_RATIO, MODAL_WORK_LIMIT,
};

// The stations and the checks of an FE model belong to `fe`; re-exported here, where they were
// first defined, for the callers of the modal stage.
pub use crate::fe::{
    diagnose_mechanism, validate_fe_model, ModalError, Quantity, Station, StationTarget,
};

// What a mode does is part of an imported bridge's description too; re-exported here, where the
// modal analysis classifies modes.
pub use crate::model::mode_kind::ModeKind;

/// One natural mode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mode {
    /// Circular frequency ω [rad/s].
    pub circular_frequency: f64,
    /// Modal damping ratio ζ [-].
    pub damping_ratio: f64,
    /// Classification from kinetic-energy shares.
    pub kind: ModeKind,
    /// Backward error ‖Kφ − ω²Mφ‖₂ / ((‖K‖₁ + ω²‖M‖₁)‖φ‖₂) [-]
    /// ([`crate::linalg::backward_error`]); 0 for an imported mode.
    pub residual: f64,
}

impl Mode {
    /// Natural frequency f = ω / 2π [Hz].
    pub fn frequency_hz(&self) -> f64 {
        self.circular_frequency / (2.0 * std::f64::consts::PI)
    }
}

/// Mass-normalised modes as later stages use them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModalBasis {
    /// Modes in ascending frequency.
    pub modes: Vec<Mode>,
    /// Deck lines and nodes on which the shapes below are given.
    pub deck: DeckGeometry,
    /// Vertical mode-shape value at deck nodes, node-major: `deck_deflection[node * modes.len() + k]`
    /// [m per unit modal coordinate; modal coordinates have unit kg^½·m so that φᵀMφ = 1].
    pub deck_deflection: Vec<f64>,
    /// Longitudinal slope of the shape at deck nodes, same layout [1/m × the above].
    pub deck_slope: Vec<f64>,
    /// Stations where responses are recorded.
    pub stations: Vec<Station>,
    /// Modal deflection at stations, station-major: `station_deflection[s * modes.len() + k]`.
    pub station_deflection: Vec<f64>,
    /// Modal bending moment at stations, same layout [N·m per unit modal coordinate].
    pub station_moment: Vec<f64>,
    /// Modal force at stations, same layout [N per unit modal coordinate]: the support reaction
    /// at a station over a support, the shear force elsewhere
    /// ([`Station::quantities`](crate::fe::Station::quantities)). Empty when the basis does not
    /// have them (an imported basis).
    #[serde(default)]
    pub station_force: Vec<f64>,
    /// Number of degrees of freedom of the model the modes came from (0 if imported).
    pub dof_count: usize,
    /// The modes solved above the basis, of the kept kinds, up to
    /// [`CHECK_FREQUENCY_RATIO`] × the highest solved frequency
    /// (`solve_modes`, step 6): never in a crossing's coupled solution; the analysis integrates
    /// them against its contact forces for the convergence indicator only. None for an imported
    /// basis, a basis restricted to some of its modes, or where the limits left no room.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub check_modes: Option<Box<ModalBasis>>,
}

impl ModalBasis {
    /// Number of modes.
    pub fn mode_count(&self) -> usize {
        self.modes.len()
    }

    /// Station values of one quantity for all modes of station `s`; empty where the basis does
    /// not have that quantity at that station ([`has_quantity`](Self::has_quantity)).
    pub fn station_values(&self, s: usize, quantity: Quantity) -> &[f64] {
        let n = self.modes.len();
        let table = match quantity {
            Quantity::Deflection => &self.station_deflection,
            Quantity::BendingMoment => &self.station_moment,
            Quantity::ShearForce | Quantity::SupportReaction if self.has_quantity(s, quantity) => {
                &self.station_force
            }
            Quantity::ShearForce | Quantity::SupportReaction => return &[],
        };
        &table[s * n..(s + 1) * n]
    }

    /// Whether the basis has `quantity` at station `s`: deflection and moment always; the
    /// station's force quantity (reaction at a support, shear elsewhere) when the basis carries
    /// modal forces.
    pub fn has_quantity(&self, s: usize, quantity: Quantity) -> bool {
        match quantity {
            Quantity::Deflection | Quantity::BendingMoment => true,
            Quantity::ShearForce | Quantity::SupportReaction => {
                self.station_force.len() == self.stations.len() * self.modes.len()
                    && self.stations[s].quantities()[2] == quantity
            }
        }
    }

    /// The quantities the basis has at station `s`, in the order of a station's entries.
    pub fn station_quantities(&self, s: usize) -> Vec<Quantity> {
        Quantity::ALL
            .into_iter()
            .filter(|&q| self.has_quantity(s, q))
            .collect()
    }

    /// The basis restricted to the modes `keep` (indices into `modes`, ascending).
    pub fn select_modes(&self, keep: &[usize]) -> ModalBasis {
        let n = self.modes.len();
        let pick = |table: &[f64], rows: usize| -> Vec<f64> {
            let mut out = Vec::with_capacity(rows * keep.len());
            for r in 0..rows {
                out.extend(keep.iter().map(|&k| table[r * n + k]));
            }
            out
        };
        let nodes = self.deck.node_count();
        let stations = self.stations.len();
        ModalBasis {
            modes: keep.iter().map(|&k| self.modes[k].clone()).collect(),
            deck: self.deck.clone(),
            deck_deflection: pick(&self.deck_deflection, nodes),
            deck_slope: pick(&self.deck_slope, nodes),
            stations: self.stations.clone(),
            station_deflection: pick(&self.station_deflection, stations),
            station_moment: pick(&self.station_moment, stations),
            station_force: if self.station_force.is_empty() {
                Vec::new()
            } else {
                pick(&self.station_force, stations)
            },
            dof_count: self.dof_count,
            check_modes: None,
        }
    }
}
