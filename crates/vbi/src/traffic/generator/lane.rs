//! One lane's traffic: its flow by hour block (BTLS's lane flow composition,
//! `cpp/src/LaneFlowComposition.cpp`; spec §2 and §4) and the step that draws its next truck
//! (`LaneGenTraffic.cpp:99-124`, `FlowGenerator.cpp:34-139`; spec §1).

use serde::{Deserialize, Serialize};

use super::grave::GraveParameters;
use super::headway::{minimum_gap, HeadwayModel};
use super::mixture::{bounded_draw, standard_normal};
use super::GeneratorError;
use crate::road::SampleRng;
use crate::traffic::{RecordedTruck, TravelDirection};

/// Length of an hour block by default [s].
pub const DEFAULT_BLOCK_SECONDS: f64 = 3600.0;

/// Number of blocks of a day by default (they repeat every day).
pub const DEFAULT_BLOCK_COUNT: usize = 24;

/// The slowest speed a truck is given [m/s]: BTLS draws speeds from an untruncated normal; vbi
/// redraws one below this ([`MAX_REDRAWS`](super::MAX_REDRAWS) times, then clamps), which at
/// BTLS's speeds (24.8 ± 1.0 m/s) never happens.
pub const MIN_SPEED: f64 = 1.0;

/// Tolerance on the sum of a block's class fractions.
pub const CLASS_FRACTION_TOLERANCE: f64 = 1e-6;

/// The first ChaCha20 stream of the lanes ([`lane_stream`]): "BTLS" in ASCII in the high
/// 32 bits, far from the road samples' streams (0, 1, …) and the traffic stream's (2⁶⁴ − 2).
pub const STREAM_BASE: u64 = 0x4254_4C53_0000_0000;

/// The ChaCha20 stream of the lane numbered `lane` (from 1) in `direction`:
/// [`STREAM_BASE`] + 2 (lane − 1) + d, d = 0 forward, 1 backward. A lane's stream depends on
/// its identity only, so that its trucks are the same whichever other lanes are generated.
pub fn lane_stream(direction: TravelDirection, lane: usize) -> u64 {
    let d = match direction {
        TravelDirection::Forward => 0,
        TravelDirection::Backward => 1,
    };
    STREAM_BASE + 2 * (lane.max(1) as u64 - 1) + d
}

/// A lane's traffic during one block of the day.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FlowBlock {
    /// Truck flow Q [veh/h]; positive. (BTLS's car percentage is not kept: vbi generates
    /// trucks only, so the flow is the trucks'.)
    pub truck_flow: f64,
    /// Mean speed of the trucks [m/s]; at least [`MIN_SPEED`].
    pub speed_mean: f64,
    /// Standard deviation of the speed [m/s]; zero or positive.
    pub speed_standard_deviation: f64,
    /// Fractions of trucks with 2, 3, 4 and 5 axles [-]; each zero or positive, summing to 1
    /// within [`CLASS_FRACTION_TOLERANCE`].
    pub class_fractions: [f64; 4],
}

/// The traffic of one lane: its direction, its number and its flow by block. Block i covers
/// [i T, (i + 1) T) of each period of n T (a day with BTLS's 24 blocks of 3600 s): the block of
/// time t is ⌊t/T⌋ mod n.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LaneFlow {
    /// Direction of travel: forward is BTLS's direction 1 (entering at x = 0), backward its
    /// direction 2.
    pub direction: TravelDirection,
    /// The lane's number from 1 within its direction, as [`RecordedTruck::lane`] gives it.
    pub lane: usize,
    /// Length T of a block [s] ([`DEFAULT_BLOCK_SECONDS`]); positive.
    pub block_seconds: f64,
    /// The blocks of a period, in order ([`DEFAULT_BLOCK_COUNT`] for a day of hours); at least
    /// one.
    pub blocks: Vec<FlowBlock>,
}

impl LaneFlow {
    /// A lane with the same block for every hour of the day (24 blocks of 3600 s).
    pub fn uniform(direction: TravelDirection, lane: usize, block: FlowBlock) -> LaneFlow {
        LaneFlow {
            direction,
            lane,
            block_seconds: DEFAULT_BLOCK_SECONDS,
            blocks: vec![block; DEFAULT_BLOCK_COUNT],
        }
    }

    /// The block of time t [s]: ⌊t/T⌋ mod n.
    pub fn block_at(&self, time: f64) -> &FlowBlock {
        let n = self.blocks.len().max(1);
        let index = (time / self.block_seconds).floor().max(0.0);
        let index = if index < 1e18 {
            (index as u64 % n as u64) as usize
        } else {
            0
        };
        &self.blocks[index.min(self.blocks.len() - 1)]
    }

    /// What is wrong with the lane, named `field`: a lane number from 1, a positive block
    /// length, at least one block, and in each block a positive truck flow, a mean speed of at
    /// least [`MIN_SPEED`], a non-negative speed deviation, and class fractions that are zero or
    /// positive and sum to 1.
    pub fn check(&self, field: &str) -> Result<(), GeneratorError> {
        let fail = |sub: String, message: String| {
            Err(GeneratorError::new(format!("{field}{sub}"), message))
        };
        if self.lane == 0 {
            return fail(
                ".lane".into(),
                "lanes are numbered from 1 within their direction".into(),
            );
        }
        if !(self.block_seconds.is_finite() && self.block_seconds > 0.0) {
            return fail(
                ".block_seconds".into(),
                format!(
                    "a block must last a positive time, got {} s",
                    self.block_seconds
                ),
            );
        }
        if self.blocks.is_empty() {
            return fail(".blocks".into(), "a lane needs at least one block".into());
        }
        for (i, block) in self.blocks.iter().enumerate() {
            let at = |name: &str| format!(".blocks[{i}].{name}");
            let q = block.truck_flow;
            if !(q.is_finite() && q > 0.0) {
                return fail(
                    at("truck_flow"),
                    format!("the truck flow must be positive, got {q} veh/h"),
                );
            }
            if !(block.speed_mean.is_finite() && block.speed_mean >= MIN_SPEED) {
                return fail(
                    at("speed_mean"),
                    format!(
                        "the mean speed must be at least {MIN_SPEED} m/s, got {} m/s",
                        block.speed_mean
                    ),
                );
            }
            let sd = block.speed_standard_deviation;
            if !(sd.is_finite() && sd >= 0.0) {
                return fail(
                    at("speed_standard_deviation"),
                    format!("the speed's deviation must be zero or positive, got {sd} m/s"),
                );
            }
            let fractions = &block.class_fractions;
            let total: f64 = fractions.iter().sum();
            if fractions.iter().any(|f| !(f.is_finite() && *f >= 0.0))
                || (total - 1.0).abs() > CLASS_FRACTION_TOLERANCE
            {
                return fail(
                    at("class_fractions"),
                    format!(
                        "the fractions of 2, 3, 4 and 5 axles must be zero or positive and sum to 1, got {fractions:?} (sum {total})"
                    ),
                );
            }
        }
        Ok(())
    }
}

/// The state of one lane's generation: its random stream, the time it has reached (its last
/// arrival, 0 at the start) and the speed and wheelbase of its last truck.
#[derive(Debug, Clone)]
pub(crate) struct LaneState {
    rng: SampleRng,
    time: f64,
    ahead: Option<(f64, f64)>,
}

impl LaneState {
    /// The lane's state at time 0, its stream [`lane_stream`] of `seed`.
    pub(crate) fn new(seed: u64, lane: &LaneFlow) -> LaneState {
        LaneState {
            rng: SampleRng::new(seed, lane_stream(lane.direction, lane.lane)),
            time: 0.0,
            ahead: None,
        }
    }

    /// The lane's next truck. Everything is drawn with the block of the lane's last arrival
    /// (BTLS draws the class with the block before that, a quirk vbi drops): the truck
    /// ([`GraveParameters::draw_truck`]), its speed v ~ N(μ_v, σ_v) (above [`MIN_SPEED`]), the
    /// minimum gap behind the truck ahead ([`minimum_gap`]), and the gap
    /// ([`HeadwayModel::draw_gap`]); it arrives that gap after the last arrival.
    pub(crate) fn next_truck(
        &mut self,
        lane: &LaneFlow,
        parameters: &GraveParameters,
        headway: &HeadwayModel,
        no_overlap_length: f64,
    ) -> RecordedTruck {
        let block = lane.block_at(self.time);
        let rng = &mut self.rng;
        let truck = parameters.draw_truck(lane.direction, &block.class_fractions, rng);
        let (mean, sd) = (block.speed_mean, block.speed_standard_deviation);
        let speed = bounded_draw(rng, MIN_SPEED, f64::INFINITY, |rng| {
            mean + sd * standard_normal(rng)
        });
        let least = minimum_gap(self.ahead, speed, no_overlap_length);
        let gap = headway.draw_gap(block.truck_flow, least, rng);
        self.time += gap;
        let wheelbase: f64 = truck.axle_spacings.iter().sum();
        self.ahead = Some((speed, wheelbase));
        RecordedTruck {
            arrival_time: self.time,
            lane: lane.lane,
            direction: lane.direction,
            speed,
            axle_spacings: truck.axle_spacings,
            axle_loads: truck.axle_loads,
        }
    }
}
