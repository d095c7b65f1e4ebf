//! The typed scenario: one crossing of one vehicle over one bridge on one road, in SI units,
//! made of the library's own option types.

use serde::{Deserialize, Serialize};

use crate::analysis::AnalysisOptions;
use crate::fe::MeshOptions;
use crate::modal::{ModalOptions, ModeKind};
use crate::model::{paper_bridge, BridgeModel};
use crate::road::RoadSpec;
use crate::solver::SolverOptions;
use crate::units::KMH;
use crate::vehicle::{preset, VehicleSpec};

/// The vehicle of the built-in scenario: the paper's five-axle tractor–semitrailer (15 DOF).
pub const DEFAULT_VEHICLE: &str = "tractor-semitrailer-5axle";
/// Speed of the built-in scenario [m/s] (80 km/h).
pub const DEFAULT_SPEED: f64 = 80.0 * KMH;

/// Everything that determines a [`PreparedBridge`](super::PreparedBridge): two scenarios with
/// equal bridge specs share one modal analysis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BridgeSpec {
    /// The bridge as the engineer describes it.
    pub model: BridgeModel,
    /// How it is meshed (element length [m], stations).
    pub mesh: MeshOptions,
    /// How many modes are solved for and which kinds are kept.
    pub modal: ModalOptions,
}

impl BridgeSpec {
    /// A bridge meshed with the default 1 m elements, with the modal options of a crossing:
    /// `mode_count` modes solved for, vertical and differential bending and torsion kept
    /// ([`ModeKind::VERTICAL`], the modes a truck excites).
    pub fn new(model: BridgeModel, mode_count: usize) -> BridgeSpec {
        BridgeSpec {
            model,
            mesh: MeshOptions::default(),
            modal: ModalOptions {
                mode_count,
                keep_kinds: ModeKind::VERTICAL.to_vec(),
                ..ModalOptions::default()
            },
        }
    }
}

/// How the vehicle moves: constant speed along a line parallel to the deck's axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Motion {
    /// Speed v [m/s]; positive.
    pub speed: f64,
    /// Lateral position of the vehicle centreline from the deck centreline [m], left positive.
    pub lateral_position: f64,
}

/// One crossing, in SI units: what [`run_crossing`](super::run_crossing) needs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scenario {
    /// Name for reports.
    pub name: String,
    /// How the bridge was named (a preset, a file, inline), for reports.
    pub bridge_label: String,
    /// The bridge, its mesh and its modal options.
    pub bridge: BridgeSpec,
    /// The vehicle description (assembled per crossing).
    pub vehicle: VehicleSpec,
    /// The road; its `seed` is the crossing's seed.
    pub road: RoadSpec,
    /// Speed and lateral position.
    pub motion: Motion,
    /// Free vibration recorded after the last contact leaves the deck [s]; None for the
    /// solver's default (two periods of the lowest mode).
    pub free_vibration_duration: Option<f64>,
    /// Time integration.
    pub solver: SolverOptions,
    /// DAF analysis.
    pub analysis: AnalysisOptions,
    /// Mode counts K for which the crossing is solved again with only the first K modes, to
    /// compare with the partial modal sums of the full run (default: none).
    pub rerun_mode_counts: Vec<usize>,
}

impl Default for Scenario {
    /// The built-in scenario: the paper's 3 × 30 m bridge, its five-axle truck on a 'medium'
    /// road at 80 km/h, seed 1, 50 modes.
    fn default() -> Scenario {
        Scenario {
            name: "paper-3x30-medium-80kmh".into(),
            bridge_label: "paper-3x30 (preset)".into(),
            bridge: BridgeSpec::new(paper_bridge(3, 30.0), 50),
            vehicle: preset(DEFAULT_VEHICLE).expect("the default vehicle is a preset"),
            road: RoadSpec::default(),
            motion: Motion {
                speed: DEFAULT_SPEED,
                lateral_position: 0.0,
            },
            free_vibration_duration: None,
            solver: SolverOptions::default(),
            analysis: AnalysisOptions::default(),
            rerun_mode_counts: Vec::new(),
        }
    }
}
