//! Who is on the deck, where and when: the vehicles of a crossing event placed for t = 0
//! ([`vehicle_runs`]: the scenario's own vehicle, its platoon, its lane pattern, further
//! vehicles by entry time or gap, the seeded random stream of [`stream`]), each with its speed
//! law ([`law`]: x(t) exact), the checks that they stand apart and never drive through each
//! other ([`check_vehicles_apart`], [`first_catching_up`]), and the road extent their tyres
//! need ([`road_extent`]).
//!
//! Below the solver: it uses the vehicle, road and model modules only; the solver integrates
//! the [`VehicleRun`]s placed here, and the crossing application ([`crate::crossing`]) hands a
//! scenario's traffic fields over as a [`TrafficSpec`].

mod apart;
mod catching_up;
pub mod generator;
pub mod law;
mod placement;
pub mod record;
pub mod stream;

use serde::{Deserialize, Serialize};

pub use apart::{check_vehicles_apart, VehiclesOverlap};
pub use catching_up::{first_catching_up, CatchingUp};
pub use law::{SpeedKnot, SpeedProfile, StopsAt, TravelDirection};
pub(crate) use placement::start_for_entry_time;
pub use placement::{input_entry, road_extent, vehicle_runs};
pub use record::RecordedTruck;

use crate::model::BridgeModel;
use crate::road::RoadSpec;
use crate::vehicle::{VehicleError, VehicleModel, VehicleSpec};

/// Clear gap between the vehicles of a platoon by default [m].
pub const DEFAULT_PLATOON_GAP: f64 = 10.0;

/// The traffic of one event as a scenario gives it: the fields [`vehicle_runs`] places, with
/// the deck and the road they need (borrowed from a
/// [`Scenario`](crate::crossing::Scenario), [`Scenario::traffic_spec`](crate::crossing::Scenario::traffic_spec)).
#[derive(Debug, Clone, Copy)]
pub struct TrafficSpec<'a> {
    /// The bridge (its deck length and width, its girder lines).
    pub bridge: &'a BridgeModel,
    /// The road: the approach and exit lengths, the sample spacing, and the seed the stream
    /// draws from.
    pub road: &'a RoadSpec,
    /// The scenario's own vehicle.
    pub vehicle: &'a VehicleSpec,
    /// Its speed, lateral position and direction.
    pub motion: &'a Motion,
    /// Copies of the own vehicle in its lane (at least 1).
    pub platoon_size: usize,
    /// Clear gap between consecutive copies [m].
    pub platoon_gap: f64,
    /// The own vehicle's arrangement over the lanes.
    pub lane_pattern: LanePattern,
    /// Further vehicles, each with its motion and entry.
    pub traffic: &'a [TrafficVehicle],
    /// A seeded random stream of further vehicles, after `traffic`.
    pub traffic_stream: Option<&'a stream::TrafficStream>,
}

/// Why an event's vehicles cannot be placed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrafficError {
    /// A vehicle is not a valid model.
    #[error("assembling the vehicle")]
    Vehicle(#[source] VehicleError),
    /// The traffic stream cannot be drawn.
    #[error("drawing the traffic stream")]
    Stream(#[source] stream::StreamError),
    /// Two vehicles overlap at t = 0.
    #[error(transparent)]
    Overlap(VehiclesOverlap),
    /// A vehicle of the event cannot move as asked, or does not fit on the deck.
    #[error("vehicle {vehicle} ({label}): {reason}")]
    Placement {
        /// Vehicle number in the event (from 1: the scenario's own vehicle).
        vehicle: usize,
        /// How the input names it.
        label: String,
        /// What is wrong, and what is allowed.
        reason: String,
    },
}

/// One vehicle of a crossing and how it moves ([`law`] module: x(t) exact).
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleRun {
    /// The vehicle (contacts, DOFs, M, C, K).
    pub vehicle: VehicleModel,
    /// Direction of travel.
    pub direction: TravelDirection,
    /// Lateral position y of the vehicle centreline on the deck [m], from the deck centreline,
    /// positive to the left of the deck (deck coordinates, whatever the direction).
    pub lateral_position: f64,
    /// Travel coordinate s₀ of the front axle at t = 0 [m]: its distance past the deck entry of
    /// its direction (x = 0 forward, x = L backward), negative on the approach. The vehicle
    /// starts in static equilibrium on the road there, with the bridge at rest and undeflected.
    pub start_position: f64,
    /// Speed along the travel.
    pub speed: SpeedProfile,
}

impl VehicleRun {
    /// A vehicle travelling forward on the deck centreline at constant speed v [m/s], its front
    /// axle starting at the first support.
    pub fn forward(vehicle: VehicleModel, speed: f64) -> VehicleRun {
        VehicleRun {
            vehicle,
            direction: TravelDirection::Forward,
            lateral_position: 0.0,
            start_position: 0.0,
            speed: SpeedProfile::Constant(speed),
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

    /// The pattern's name (one of [`LanePattern::NAMES`]).
    pub fn name(self) -> &'static str {
        LanePattern::NAMES
            .into_iter()
            .find(|name| LanePattern::from_name(name) == Some(self))
            .unwrap_or("single")
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
