//! Dynamics on the events that can govern (issue 48, item 3): each such event of the traffic
//! becomes a crossing scenario ([`event_scenario`]: every truck a multibody vehicle built from
//! its axle record, [`crate::vehicle::multibody_from_axles`], on its lane at its recorded speed
//! and time, the road sampled per event), run by the crossing application
//! ([`crate::crossing::run_crossings`]), and its converged total effect read at every station
//! and quantity in the effect's own governing sense
//! ([`crate::analysis::AnalysisOptions::governing_directions`]).
//!
//! **Screening.** Integrating every event of decades of traffic is needless: a block's total
//! maximum comes from an event whose static effect is near the block's static maximum. The
//! rule: an event is integrated when, for some effect e, its static extreme S (a magnitude in
//! e's sense) reaches r × the static maximum of e in the event's block, r the
//! [`DynamicSettings::screening_ratio`]. Every block's static-maximum event is integrated
//! (r ≤ 1); an event left out could govern the block's total only if its own DAF exceeded
//! D₀ / r, D₀ the DAF of the block's static-maximum event. With r = 0 every event that loads
//! an effect is integrated: the validation run the screening's bias is measured against.
//!
//! The same rule (which they apply in two passes, [`super::total_block_maxima`]; vbi in one,
//! [`super::static_and_total_block_maxima`]) is the one of OBrien, Cantero, Enright & González
//! (2010), *Characteristic dynamic increment for extreme traffic loading events on short and
//! medium span highway bridges*, Engineering Structures 32(12), 3827–3835, who ran dynamics on
//! the events that give each block's largest static effects.

use super::{BlockMaximaTally, LifetimeEffect, LifetimeLane, StaticLifetime};
use crate::analysis::{Direction, GoverningDirection, StationDaf};
use crate::crossing::{PipelineError, PreparedBridge, RunResult, Scenario};
use crate::road::splitmix64_of as splitmix64;
use crate::solver::Recording;
use crate::traffic::{Entry, Motion, RecordedTruck, SpeedKnot, TrafficVehicle};
use crate::vehicle::{multibody_from_axles, VehicleError};

/// Screening ratio r by default: an event is integrated when its static effect reaches 70 %
/// of its block's static maximum for some effect; one left out could govern its block's total
/// only with a DAF above 1.43 D₀. Measured against VBI on every event over 100 days of Auxerre
/// traffic on a 30 m span (docs/lifetime.md, "The bias on the characteristic value"): 0.7 gave
/// every daily total exactly, 0.9 moved the midspan shear's 1000-year GEV level by 4 to 10 %.
pub const DEFAULT_SCREENING_RATIO: f64 = 0.7;

/// How the events that can govern are integrated.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicSettings {
    /// The crossing every event's scenario is made from: its bridge (the one the lifetime
    /// analysis tracks, with its modes), road (class, approach and exit lengths; its `seed` is
    /// the lifetime's road seed), solver and analysis options. Its vehicle and motion are
    /// replaced by the event's trucks.
    pub template: Scenario,
    /// Screening ratio r in [0, 1] (module docs): an event is integrated when its static effect
    /// reaches r × its block's static maximum for some effect; 0: every event that loads an
    /// effect.
    pub screening_ratio: f64,
    /// The road's roughness rising with the years: each change applies to the events that
    /// start at or after its instant, in increasing order (empty: the template's road
    /// throughout).
    pub road_changes: Vec<RoadChange>,
}

/// A change of the events' road roughness from an instant of the record on (the road
/// deteriorating with the years; issue 48, item 3). The road's band, approach and exit lengths
/// and seeds stay the template's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoadChange {
    /// From when [s, on the record's clock].
    pub from_time: f64,
    /// The roughness of the events that start from then on.
    pub roughness: crate::road::Roughness,
}

/// The roughness of an event that starts at `time` [s]: the last of `changes` at or before it,
/// or `initial` before the first.
pub fn roughness_at(
    changes: &[RoadChange],
    initial: crate::road::Roughness,
    time: f64,
) -> crate::road::Roughness {
    (changes.iter())
        .take_while(|change| change.from_time <= time)
        .last()
        .map_or(initial, |change| change.roughness)
}

/// [`event_scenario`] on the road of the event's start ([`roughness_at`] its first truck's
/// arrival): the scenario of a lifetime's event, as `vbi lifetime` integrates it.
pub fn event_scenario_at(
    changes: &[RoadChange],
    template: &Scenario,
    lanes: &[LifetimeLane],
    trucks: &[RecordedTruck],
    number: u64,
) -> Result<Scenario, EventScenarioError> {
    let mut scenario = event_scenario(template, lanes, trucks, number)?;
    scenario.road.roughness =
        roughness_at(changes, template.road.roughness, trucks[0].arrival_time);
    Ok(scenario)
}

/// The seed of event n's road sample: the SplitMix64 finaliser (Steele, Lea & Flood 2014) of
/// the lifetime's road seed and the event's number, so that each event has its own road, the
/// same whichever events are integrated and on any thread count.
pub fn event_road_seed(road_seed: u64, event: u64) -> u64 {
    splitmix64(splitmix64(road_seed) ^ event)
}

/// Why an event's trucks cannot be made a scenario.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EventScenarioError {
    /// A truck's record does not make a vehicle.
    #[error("truck {truck} of the event: its axles make no vehicle")]
    Vehicle {
        /// Its number in the event, from 1.
        truck: usize,
        /// Why.
        #[source]
        source: VehicleError,
    },
    /// A truck drives in a lane the analysis does not have (the static pass refuses it first).
    #[error("truck {truck} of the event drives in a lane the analysis does not have")]
    Lane {
        /// Its number in the event, from 1.
        truck: usize,
    },
}

/// Event `number`'s trucks (in order of arrival) as a crossing scenario made from `template`:
/// the first truck is the scenario's vehicle, its front axle at the start of the approach at
/// t = 0; each later truck reaches its deck entry at t = a + (t_k − t₁), a = approach / v₁
/// the first truck's arrival, t_k the recorded arrivals. Each truck drives its lane's line at
/// its recorded constant speed; the road is sampled with [`event_road_seed`]. The scenario
/// replays with `vbi run` (its TOML form, [`crate::crossing`]'s keys).
pub fn event_scenario(
    template: &Scenario,
    lanes: &[LifetimeLane],
    trucks: &[RecordedTruck],
    number: u64,
) -> Result<Scenario, EventScenarioError> {
    let vehicle = |k: usize, truck: &RecordedTruck| {
        multibody_from_axles(&truck.axle_spacings, &truck.axle_loads).map_err(|source| {
            EventScenarioError::Vehicle {
                truck: k + 1,
                source,
            }
        })
    };
    let motion = |k: usize, truck: &RecordedTruck| {
        let lane =
            super::lane_index(lanes, truck).ok_or(EventScenarioError::Lane { truck: k + 1 })?;
        Ok(Motion {
            speed: truck.speed,
            lateral_position: lanes[lane].lateral_position,
            direction: truck.direction,
            acceleration: 0.0,
            speed_profile: Vec::new(),
        })
    };
    let first = &trucks[0];
    let arrival = template.road.approach_length / first.speed;
    let mut traffic = Vec::with_capacity(trucks.len() - 1);
    // Where each truck is at t = 0, with its lane and approach speed, for its followers.
    let mut placed = vec![Approach {
        lane: super::lane_index(lanes, first),
        direction: first.direction,
        start: -template.road.approach_length,
        length: first.axle_spacings.iter().sum(),
        speed: first.speed,
    }];
    for (k, truck) in trucks.iter().enumerate().skip(1) {
        let entry = arrival + (truck.arrival_time - first.arrival_time);
        let mut motion = motion(k, truck)?;
        let lane = super::lane_index(lanes, truck);
        let ahead =
            (placed.iter().rev()).find(|p| p.lane == lane && p.direction == truck.direction);
        if let Some(ahead) = ahead {
            motion.speed_profile = follower_profile(ahead, &motion, entry);
        }
        placed.push(Approach {
            lane,
            direction: truck.direction,
            start: crate::traffic::start_for_entry_time(&motion, entry).unwrap_or(f64::NAN),
            length: truck.axle_spacings.iter().sum(),
            speed: motion
                .speed_profile
                .first()
                .map_or(truck.speed, |k| k.speed),
        });
        traffic.push(TrafficVehicle {
            label: truck_label(k, truck),
            vehicle: vehicle(k, truck)?,
            motion,
            entry: Entry::Time(entry),
        });
    }
    let mut scenario = template.clone();
    scenario.name = format!("lifetime-event-{number}");
    scenario.vehicle = vehicle(0, first)?;
    scenario.motion = motion(0, first)?;
    scenario.traffic = traffic;
    scenario.traffic_stream = None;
    scenario.platoon_size = 1;
    scenario.lane_pattern = crate::traffic::LanePattern::Single;
    scenario.road.seed = event_road_seed(template.road.seed, number);
    Ok(scenario)
}

/// Decelerations [m/s²] a follower that closes up on its leader on the approach may brake at
/// ([`follower_profile`]): the gentlest that keeps it behind its leader, from a gentle service
/// braking of a truck (0.1 g) to a firm one (0.3 g).
pub const FOLLOWER_DECELERATIONS: [f64; 5] = [1.0, 1.5, 2.0, 2.5, 3.0];

/// Road [m] a follower drives at its recorded speed before the deck after braking to it
/// ([`follower_profile`]), so that its pitch from the braking has settled (a 2 Hz body with
/// 10 % damping: about two periods at 80 km/h).
pub const FOLLOWER_SETTLING_LENGTH: f64 = 20.0;

/// A truck of an event at t = 0: its lane (index), direction, front axle's travel coordinate
/// [m], axle-group length [m] and speed on the approach [m/s].
struct Approach {
    lane: Option<usize>,
    direction: crate::traffic::TravelDirection,
    start: f64,
    length: f64,
    speed: f64,
}

/// The speed profile of a truck that follows `ahead` in its lane and would overlap it at t = 0
/// if traced back from its deck entry (at `entry` [s]) at its recorded, slower speed: a truck
/// that fell back from its leader before the bridge. It drives at the leader's approach speed,
/// brakes at the gentlest of [`FOLLOWER_DECELERATIONS`] that keeps it behind its leader at
/// t = 0 to its recorded speed, and holds that for the last [`FOLLOWER_SETTLING_LENGTH`]
/// before the deck, reaching the deck entry at its recorded time and speed. Empty (the
/// constant speed) where the constant speed keeps it behind its leader, or where no such
/// braking does (a follower not slower than its leader, a gap too small, too little time
/// before its entry): the crossing's checks then refuse the event, as before.
fn follower_profile(ahead: &Approach, motion: &Motion, entry: f64) -> Vec<SpeedKnot> {
    let behind = |start: f64| start < ahead.start - ahead.length;
    if behind(-motion.speed * entry) || ahead.speed <= motion.speed || ahead.speed.is_nan() {
        return Vec::new();
    }
    let settled = -FOLLOWER_SETTLING_LENGTH;
    for deceleration in FOLLOWER_DECELERATIONS {
        let braking =
            (ahead.speed * ahead.speed - motion.speed * motion.speed) / (2.0 * deceleration);
        let profile = vec![
            SpeedKnot {
                travel: settled - braking,
                speed: ahead.speed,
            },
            SpeedKnot {
                travel: settled,
                speed: motion.speed,
            },
        ];
        let with = Motion {
            speed_profile: profile.clone(),
            ..motion.clone()
        };
        if crate::traffic::start_for_entry_time(&with, entry).is_ok_and(behind) {
            return profile;
        }
    }
    Vec::new()
}

/// How a truck of an event is named in its scenario: its number, lane and recorded time.
fn truck_label(k: usize, truck: &RecordedTruck) -> String {
    format!(
        "truck {} (direction {}, lane {}, t = {:.3} s)",
        k + 1,
        super::direction_number(truck.direction),
        truck.lane,
        truck.arrival_time
    )
}

/// The analysis options of an event's crossing: every effect read in its own governing sense.
pub fn governing_directions(effects: &[LifetimeEffect]) -> Vec<GoverningDirection> {
    effects
        .iter()
        .map(|effect| GoverningDirection {
            station: effect.station.clone(),
            quantity: effect.quantity,
            direction: match effect.sense < 0.0 {
                true => Direction::Negative,
                false => Direction::Positive,
            },
        })
        .collect()
}

/// One effect's total of one integrated event.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EventTotal {
    /// The static extreme of the crossing in the effect's sense, signed [N, N·m or m].
    pub static_value: f64,
    /// The converged dynamic (total) extreme in the effect's sense, signed.
    pub total: f64,
    /// When it occurs [s], on the record's clock.
    pub time: f64,
}

/// The totals of every effect of one integrated event, in effect order (None where the event
/// does not load the effect in its sense).
#[derive(Debug, Clone, PartialEq)]
pub struct EventTotals {
    /// The event's number in the record (from 0).
    pub event: u64,
    /// Trucks in the event.
    pub trucks: usize,
    /// Per effect.
    pub totals: Vec<Option<EventTotal>>,
}

/// The totals of an event's crossing `result`, started at `start` on the record's clock.
pub fn event_totals(
    analysis: &StaticLifetime,
    result: &RunResult,
    (event, trucks, start): (u64, usize, f64),
) -> EventTotals {
    let totals = analysis
        .effects
        .iter()
        .map(|effect| {
            let entry = result
                .report
                .stations
                .iter()
                .find(|s| s.name == effect.station && s.quantity == effect.quantity)?;
            effect_total(effect, entry, start)
        })
        .collect();
    EventTotals {
        event,
        trucks,
        totals,
    }
}

/// An entry's total in the effect's sense, if the event loads it that way (a static extreme of
/// the effect's sign with a DAF).
fn effect_total(effect: &LifetimeEffect, entry: &StationDaf, start: f64) -> Option<EventTotal> {
    let loads = entry.converged.daf.is_some() && effect.sense * entry.static_max > 0.0;
    loads.then_some(EventTotal {
        static_value: entry.static_max,
        total: entry.converged.dynamic_max,
        time: start + entry.converged.dynamic_max_time,
    })
}

/// Whether an event whose static extremes are `extremes` (per effect, signed; the block of each
/// in `blocks`) is integrated: for some effect, its magnitude in the effect's sense is positive
/// and reaches r × the block's static maximum.
pub fn screened(
    analysis: &StaticLifetime,
    static_maxima: &BlockMaximaTally,
    extremes: &[(f64, u64)],
    ratio: f64,
) -> bool {
    analysis
        .effects
        .iter()
        .zip(extremes)
        .enumerate()
        .any(|(e, (effect, &(value, block)))| {
            let magnitude = effect.sense * value;
            let block_maximum = static_maxima
                .block_value(e, block)
                .map_or(0.0, |v| effect.sense * v);
            magnitude > 0.0 && magnitude >= ratio * block_maximum
        })
}

/// Runs the crossings of `scenarios` on `bridge` (in parallel, each as `vbi run` would, its
/// outcome only), in order.
pub fn run_events(
    bridge: &PreparedBridge,
    scenarios: &[Scenario],
) -> Vec<Result<RunResult, PipelineError>> {
    use rayon::prelude::*;
    scenarios
        .par_iter()
        .map(|scenario| {
            crate::crossing::run_crossings(bridge, &[scenario], Recording::OutcomeOnly)
                .pop()
                .expect("one result per scenario")
        })
        .collect()
}

/// The time on the record's clock at which event's crossing starts: the first truck's arrival
/// less its time on the approach.
pub fn event_start(template: &Scenario, first: &RecordedTruck) -> f64 {
    first.arrival_time - template.road.approach_length / first.speed
}
