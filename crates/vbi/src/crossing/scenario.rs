//! The typed scenario: one crossing of one vehicle over one bridge on one road, in SI units,
//! made of the library's own option types.

use serde::{Deserialize, Serialize};

use crate::analysis::AnalysisOptions;
use crate::fe::MeshOptions;
use crate::modal::{ModalOptions, ModeKind};
use crate::model::{paper_bridge, BridgeModel};
use crate::road::RoadSpec;
use crate::solver::SolverOptions;
use crate::traffic::{LanePattern, Motion, TrafficSpec, TrafficVehicle, DEFAULT_PLATOON_GAP};
use crate::units::KMH;
use crate::vehicle::{preset, VehicleSpec};

/// The vehicle of the built-in scenario: the paper's five-axle tractor–semitrailer (15 DOF).
pub const DEFAULT_VEHICLE: &str = "tractor-semitrailer-5axle";
/// Speed of the built-in scenario [m/s] (80 km/h).
pub const DEFAULT_SPEED: f64 = 80.0 * KMH;

fn one() -> usize {
    1
}

fn default_platoon_gap() -> f64 {
    DEFAULT_PLATOON_GAP
}

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
    /// Further vehicles of the event, each with its own motion and entry (default none).
    #[serde(default)]
    pub traffic: Vec<TrafficVehicle>,
    /// A seeded random stream of further vehicles, after `traffic` (default none).
    #[serde(default)]
    pub traffic_stream: Option<crate::traffic::stream::TrafficStream>,
    /// A platoon: the scenario's vehicle repeated this many times in its lane, each copy
    /// `platoon_gap` behind the one before (default 1: the vehicle alone).
    #[serde(default = "one")]
    pub platoon_size: usize,
    /// Clear gap between consecutive vehicles of the platoon [m] (rear contact to front axle;
    /// default 10).
    #[serde(default = "default_platoon_gap")]
    pub platoon_gap: f64,
    /// How the scenario's vehicle is arranged over the lanes (default: alone in its lane).
    #[serde(default, skip_serializing_if = "LanePattern::is_single")]
    pub lane_pattern: LanePattern,
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
    /// The fatigue details evaluated on the crossing's histories (default none; issue 51).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fatigue_details: Vec<crate::fatigue::FatigueDetail>,
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
            motion: Motion::constant(DEFAULT_SPEED, 0.0),
            traffic: Vec::new(),
            traffic_stream: None,
            platoon_size: 1,
            platoon_gap: DEFAULT_PLATOON_GAP,
            lane_pattern: LanePattern::Single,
            free_vibration_duration: None,
            solver: SolverOptions::default(),
            analysis: AnalysisOptions::default(),
            rerun_mode_counts: Vec::new(),
            fatigue_details: Vec::new(),
        }
    }
}

impl Scenario {
    /// Who is on the deck in this scenario's event, where and when: the fields that
    /// [`crate::traffic`] places (its own vehicle and motion, platoon, lane pattern, further
    /// vehicles, the seeded stream) with the deck and the road they need.
    pub fn traffic_spec(&self) -> TrafficSpec<'_> {
        TrafficSpec {
            bridge: &self.bridge.model,
            road: &self.road,
            vehicle: &self.vehicle,
            motion: &self.motion,
            platoon_size: self.platoon_size,
            platoon_gap: self.platoon_gap,
            lane_pattern: self.lane_pattern,
            traffic: &self.traffic,
            traffic_stream: self.traffic_stream.as_ref(),
        }
    }
}
