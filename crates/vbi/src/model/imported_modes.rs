//! A modal basis as another program gives it (ANSYS, Midas, SAP2000, OpenSees): frequencies,
//! damping, mass-normalised vertical mode shapes at deck nodes, and modal bending moments at
//! stations. [`crate::modal::import::build_imported_basis`] builds the basis from it;
//! [`ImportedModes`] is the bridge model that runs on it (`vbi run`, studies), with the static
//! reference from the modal flexibility of its modes.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::mode_kind::ModeKind;
use super::station::Station;
use super::Damage;

/// One longitudinal line of deck nodes with its mode-shape values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImportedLine {
    /// Lateral position y of the line [m], from the deck centreline, positive to the left.
    pub lateral_position: f64,
    /// Longitudinal positions x of the nodes [m] from the first support, strictly ascending.
    pub node_positions: Vec<f64>,
    /// Vertical mass-normalised mode-shape values, node-major:
    /// `deflection[node * mode_count + k]` [m per unit modal coordinate, φᵀMφ = 1 with M in kg].
    pub deflection: Vec<f64>,
}

/// A station with its modal bending moments.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImportedStation {
    /// The station (its target girder indexes the lines sorted by ascending lateral position).
    pub station: Station,
    /// Sagging-positive modal bending moment of each mode [N·m per unit modal coordinate].
    pub moments: Vec<f64>,
}

/// One station's influence lines on one deck line, as another program gives them: the static
/// response to a unit downward load [N] at each node of the line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImportedInfluenceLine {
    /// The station's name (one of the imported stations).
    pub station: String,
    /// Lateral position y of the deck line [m] (one of the imported lines).
    pub lateral_position: f64,
    /// Deflection at the station [m per N, upwards positive] for a load at each node.
    pub deflection: Vec<f64>,
    /// Sagging bending moment at the station [N·m per N] for a load at each node.
    pub moment: Vec<f64>,
}

/// Everything an imported modal basis is made of.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModalImport {
    /// Natural frequencies [Hz], ascending, one per mode.
    pub frequencies_hz: Vec<f64>,
    /// Modal damping ratio of each mode [-]; `None` entries take `default_damping_ratio`.
    pub damping_ratios: Vec<Option<f64>>,
    /// Damping ratio of modes without their own [-] (the paper's 0.05 is the usual choice).
    pub default_damping_ratio: f64,
    /// Mode kinds, when the other program gives them; `None` entries are classified from the
    /// deck shapes (vertical bending or torsion).
    pub kinds: Vec<Option<ModeKind>>,
    /// Deck lines, in any order (sorted by lateral position here).
    pub lines: Vec<ImportedLine>,
    /// Deck length between end supports [m]; `None` takes the largest node position.
    pub deck_length: Option<f64>,
    /// Stations with modal moments (may be empty: then only deck shapes are available).
    pub stations: Vec<ImportedStation>,
    /// The stations' influence lines on every deck line, the exact static reference; empty:
    /// the static reference is the modes' flexibility, truncated.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub influence_lines: Vec<ImportedInfluenceLine>,
}

impl ModalImport {
    /// Deck length between the end supports [m]: as given, else the largest node position.
    pub fn deck_length(&self) -> f64 {
        self.deck_length.unwrap_or_else(|| {
            self.lines
                .iter()
                .filter_map(|l| l.node_positions.last().copied())
                .fold(0.0, f64::max)
        })
    }

    /// Why `spans` [m] do not fit the deck (their sum is not its length, to 1e-6), if they do not.
    pub fn span_mismatch(&self, spans: &[f64]) -> Option<String> {
        let length: f64 = spans.iter().sum();
        let deck = self.deck_length();
        ((length - deck).abs() > 1e-6 * deck.max(1.0))
            .then(|| format!("the spans add up to {length} m but the deck is {deck} m long"))
    }
}

/// A bridge known only by its modes: the imported data, and the spans that codes, stations and
/// lanes need.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ImportedModes {
    /// The frequencies, shapes and station moments as read.
    pub data: Arc<ModalImport>,
    /// Span lengths between consecutive supports [m]; they add up to the deck's length.
    pub span_lengths: Vec<f64>,
    /// Always intact (kept so that every bridge answers [`super::BridgeModel::damage`]).
    #[serde(default, skip_serializing_if = "Damage::is_intact")]
    pub damage: Damage,
    /// Where the data came from (the files), for messages and reports.
    pub source: String,
}

impl ImportedModes {
    /// Checks the spans against the deck and that the model is intact (the data themselves are
    /// checked when the basis is built).
    pub fn validate(&self) -> Result<(), super::ModelError> {
        super::require_spans(&self.span_lengths)?;
        let invalid = |message: String| Err(super::ModelError::ImportedMatrices { message });
        if !self.damage.is_intact() {
            return invalid(
                "stiffness losses and changed supports need an FE model; an imported modal \
                 basis has none"
                    .into(),
            );
        }
        if let Some(message) = self.data.span_mismatch(&self.span_lengths) {
            return invalid(message);
        }
        Ok(())
    }
}
