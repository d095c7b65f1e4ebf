//! The typed scenario: one crossing of one vehicle over one bridge on one road, in SI units,
//! made of the library's own option types.

use serde::{Deserialize, Serialize};

use crate::analysis::AnalysisOptions;
use crate::fe::MeshOptions;
use crate::modal::{ModalOptions, ModeKind};
use crate::model::{paper_bridge, BridgeModel};
use crate::road::RoadSpec;
use crate::solver::{SolverOptions, SpeedKnot, TravelDirection};
use crate::units::KMH;
use crate::vehicle::{preset, VehicleSpec};

/// The vehicle of the built-in scenario: the paper's five-axle tractor–semitrailer (15 DOF).
pub const DEFAULT_VEHICLE: &str = "tractor-semitrailer-5axle";
/// Speed of the built-in scenario [m/s] (80 km/h).
pub const DEFAULT_SPEED: f64 = 80.0 * KMH;

/// Clear gap between the vehicles of a platoon by default [m].
pub const DEFAULT_PLATOON_GAP: f64 = 10.0;

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

/// How a vehicle moves along a line parallel to the deck's axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Motion {
    /// Speed v [m/s] when the front axle reaches the deck (at every point, when the acceleration
    /// is zero and there is no speed profile); positive.
    pub speed: f64,
    /// Lateral position of the vehicle centreline from the deck centreline [m], left positive
    /// (deck coordinates, whatever the direction).
    pub lateral_position: f64,
    /// Direction of travel; default forward (increasing x).
    #[serde(default)]
    pub direction: TravelDirection,
    /// Constant acceleration a [m/s²] (negative: braking) from the start of the approach until
    /// the last axle leaves the deck, with `speed` at the deck entry: v² = v_e² + 2 a s. Default
    /// 0. Refused when the speed would reach zero before the vehicle leaves the deck.
    #[serde(default)]
    pub acceleration: f64,
    /// A piecewise speed profile (knots of travel coordinate s [m] past the deck entry and speed
    /// [m/s], constant acceleration between them); when given it replaces `speed` and
    /// `acceleration`. Default none.
    #[serde(default)]
    pub speed_profile: Vec<SpeedKnot>,
}

impl Motion {
    /// Constant speed v [m/s] forward on the lateral position y [m].
    pub fn constant(speed: f64, lateral_position: f64) -> Motion {
        Motion {
            speed,
            lateral_position,
            direction: TravelDirection::Forward,
            acceleration: 0.0,
            speed_profile: Vec::new(),
        }
    }
}

/// When a further vehicle of the event enters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Entry {
    /// The time its front axle reaches the deck entry of its direction [s].
    Time(f64),
    /// The clear distance [m] at t = 0 from the last contact of the vehicle before it in the list
    /// that travels the same way to this vehicle's front axle (a platoon or a queue).
    Gap(f64),
}

/// How the scenario's own vehicle is arranged over the deck's lanes (the `lane_pattern` key).
/// Lane 1 is the vehicle's own line (`lateral_position_m`, y); lane 2 is its mirror image about
/// the deck's centreline (−y). The copy of a two-vehicle pattern is the same vehicle with the
/// same speed law, starting at the start of the approach of its direction at t = 0, so that both
/// reach their deck entries at the same instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LanePattern {
    /// The event as given: the scenario's vehicle alone in lane 1 (default).
    #[default]
    Single,
    /// A copy abreast in lane 2, travelling the same way: two trucks side by side.
    SideBySide,
    /// A copy in lane 2 travelling the other way: two trucks meeting on the deck (at mid-length
    /// when the speed is constant).
    Meeting,
}

impl LanePattern {
    /// Every pattern's name, in order (the key's allowed words).
    pub const NAMES: [&'static str; 3] = ["single", "side_by_side", "meeting"];

    /// The pattern of a name.
    pub fn from_name(name: &str) -> Option<LanePattern> {
        match name {
            "single" => Some(LanePattern::Single),
            "side_by_side" => Some(LanePattern::SideBySide),
            "meeting" => Some(LanePattern::Meeting),
            _ => None,
        }
    }

    /// Whether this is the default, [`LanePattern::Single`] (not serialised then, so that a
    /// scenario without a pattern serialises as before).
    pub fn is_single(&self) -> bool {
        *self == LanePattern::Single
    }

    /// The copy's direction of travel, given the scenario vehicle's, if the pattern has a copy.
    pub fn copy_direction(self, own: TravelDirection) -> Option<TravelDirection> {
        match (self, own) {
            (LanePattern::Single, _) => None,
            (LanePattern::SideBySide, d) => Some(d),
            (LanePattern::Meeting, TravelDirection::Forward) => Some(TravelDirection::Backward),
            (LanePattern::Meeting, TravelDirection::Backward) => Some(TravelDirection::Forward),
        }
    }
}

/// A further vehicle of the crossing event, after the scenario's own.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrafficVehicle {
    /// How the input named it, for reports.
    pub label: String,
    /// The vehicle description.
    pub vehicle: VehicleSpec,
    /// Its motion.
    pub motion: Motion,
    /// When it enters.
    pub entry: Entry,
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
    pub traffic_stream: Option<super::stream::TrafficStream>,
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
        }
    }
}
