//! vbi's own simulated truck traffic, in the way of BTLS / PyBTLS 1.0.1 (Caprani's Bridge
//! Traffic Load Simulation; spec docs/design/btls-traffic-generator.md, read from its sources;
//! issue 48, item 1): the Grave vehicle model ([`grave`]), lane flows by hour block ([`lane`]),
//! free-flow (Poisson), HeDS and constant headways ([`headway`]), streamed lazily as
//! [`RecordedTruck`]s in order of arrival over all lanes, so that a lifetime analysis consumes
//! them as it consumes a traffic file, in memory flat in the number of days.
//!
//! The simulation (spec §1): each lane is independent, with its own random stream
//! ([`lane_stream`] of the seed: ChaCha20, [`SampleRng`](crate::road::SampleRng)) and its own
//! state. Its step draws, in this fixed order, the truck's class, gross weight, axle spacings
//! and axle loads (the Grave model), its speed, and the gap to its arrival (at least the
//! minimum gap that keeps it off the truck ahead over the no-overlap length L,
//! [`minimum_gap`]; [`HeadwayModel::draw_gap`]); everything with
//! the hour block of the lane's previous arrival. The lanes are merged by next arrival (ties by
//! the lanes' order) until days × 86 400 s. Multiple presence comes only from short gaps in a
//! lane and from the lanes overlapping in time: there is no correlation between lanes.
//!
//! Where vbi differs from BTLS 1.0.1 (each documented where it acts): trucks only (BTLS draws
//! cars too, below the 35 kN at which it lets a vehicle onto the bridge, and they shift the
//! trucks' gaps a little); a stream per lane instead of one shared Mersenne twister (BTLS's
//! results depend on the call order of all lanes, vbi's per lane on the seed only); gross
//! weights by the lane's direction (BTLS's assignment was lost); HeDS clamped to its last row
//! and with its tail at the truck flow; redraws capped at [`MAX_REDRAWS`]; speeds kept above
//! [`MIN_SPEED`]; a class draw with the block of the previous arrival.
//!
//! Sources: Grave, S.A.J. (2001), PhD thesis, Trinity College Dublin; O'Brien, E.J. & Caprani,
//! C.C. (2005), The Structural Engineer 83(16):33-36 (HeDS); Caprani, C.C. (2005), PhD thesis,
//! University College Dublin; the BTLS user manual (`Manual/BTLS - User Manual.docx` of
//! github.com/ccaprani/btls). BTLS is GPL v3: this is a re-implementation from the spec, and
//! the parameter files are read from outside the program (`vbi_input::grave_parameters`).

pub mod grave;
pub mod headway;
pub mod lane;
pub mod mixture;

#[cfg(test)]
mod tests;

pub use grave::{
    GraveParameters, GraveTruck, GvwBandLoadShares, TandemLoadShareTable, AXLE_COUNTS,
    AXLE_SHARE_BOUNDS, AXLE_SPACING_BOUNDS, GROSS_WEIGHT_BOUNDS, GVW_BAND_START, GVW_BAND_WIDTH,
};
pub use headway::{
    minimum_gap, HeadwayModel, HedsFlowRow, HedsTable, QuadraticCdf, MIN_GAP_SPACE, MIN_GAP_TIME,
};
pub use lane::{
    lane_stream, FlowBlock, LaneFlow, DEFAULT_BLOCK_COUNT, DEFAULT_BLOCK_SECONDS, MIN_SPEED,
    STREAM_BASE,
};
pub use mixture::{standard_normal, NormalMixture, NormalMode, MAX_REDRAWS};

use super::RecordedTruck;
use lane::LaneState;

/// Seconds in a day (the horizon is days × this; the lifetime module's day too).
const SECONDS_PER_DAY: f64 = 86_400.0;

/// Why traffic cannot be generated: the field at fault (a path into the parameters, lanes or
/// headway model) and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("traffic generator: `{field}`: {message}")]
pub struct GeneratorError {
    /// The field, for example `lanes[1].blocks[3].class_fractions`.
    pub field: String,
    /// What is wrong and what is allowed.
    pub message: String,
}

impl GeneratorError {
    /// An error about `field`.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> GeneratorError {
        GeneratorError {
            field: field.into(),
            message: message.into(),
        }
    }
}

/// The trucks of all lanes in order of arrival: an [`Iterator`] of [`RecordedTruck`]s (arrival
/// time t ≤ days × 86 400 s; lane from 1 within its direction; constant speed [m/s]; axle
/// spacings [m] and loads [N]). Each lane keeps its next truck ready; the earliest is handed
/// out and its lane draws the following one (ties: the lane listed first).
#[derive(Debug, Clone)]
pub struct TrafficGenerator {
    parameters: GraveParameters,
    lanes: Vec<LaneFlow>,
    headway: HeadwayModel,
    no_overlap_length: f64,
    end_time: f64,
    states: Vec<LaneState>,
    pending: Vec<Option<RecordedTruck>>,
    last_arrival: f64,
}

impl TrafficGenerator {
    /// The generator of `days` days of traffic on `lanes` (each a distinct direction and lane
    /// number), with vehicles of `parameters`, gaps of `headway`, the lanes' streams of `seed`,
    /// and the no-overlap length L [m] of the minimum gap (the bridge's length; BTLS's default
    /// 100 m). Checks every input first.
    pub fn new(
        parameters: GraveParameters,
        lanes: Vec<LaneFlow>,
        headway: HeadwayModel,
        seed: u64,
        days: u64,
        no_overlap_length: f64,
    ) -> Result<TrafficGenerator, GeneratorError> {
        parameters.check()?;
        headway.check()?;
        check_lanes(&lanes)?;
        if days == 0 {
            return Err(GeneratorError::new(
                "days",
                "at least one day of traffic is needed",
            ));
        }
        if !(no_overlap_length.is_finite() && no_overlap_length >= 0.0) {
            return Err(GeneratorError::new(
                "no_overlap_length",
                format!(
                    "the no-overlap length must be zero or positive, got {no_overlap_length} m"
                ),
            ));
        }
        let states = lanes
            .iter()
            .map(|lane| LaneState::new(seed, lane))
            .collect();
        let mut generator = TrafficGenerator {
            parameters,
            pending: vec![None; lanes.len()],
            lanes,
            headway,
            no_overlap_length,
            end_time: days as f64 * SECONDS_PER_DAY,
            states,
            last_arrival: 0.0,
        };
        for i in 0..generator.lanes.len() {
            generator.refill(i);
        }
        Ok(generator)
    }

    /// The end of the traffic [s]: days × 86 400.
    pub fn end_time(&self) -> f64 {
        self.end_time
    }

    /// The arrival time of the last truck handed out [s] (0 before the first): with
    /// [`Self::end_time`], how far the traffic has got.
    pub fn last_arrival(&self) -> f64 {
        self.last_arrival
    }

    /// The lanes, in the order that breaks ties.
    pub fn lanes(&self) -> &[LaneFlow] {
        &self.lanes
    }

    /// Draws lane i's next truck, or marks the lane finished when it arrives after the end.
    fn refill(&mut self, i: usize) {
        let truck = self.states[i].next_truck(
            &self.lanes[i],
            &self.parameters,
            &self.headway,
            self.no_overlap_length,
        );
        self.pending[i] = (truck.arrival_time <= self.end_time).then_some(truck);
    }
}

/// What is wrong with the lanes: each valid ([`LaneFlow::check`]), at least one, no two with the
/// same direction and number.
fn check_lanes(lanes: &[LaneFlow]) -> Result<(), GeneratorError> {
    if lanes.is_empty() {
        return Err(GeneratorError::new("lanes", "at least one lane is needed"));
    }
    for (i, lane) in lanes.iter().enumerate() {
        lane.check(&format!("lanes[{i}]"))?;
        if lanes[..i]
            .iter()
            .any(|l| l.direction == lane.direction && l.lane == lane.lane)
        {
            return Err(GeneratorError::new(
                format!("lanes[{i}].lane"),
                format!("lane {} of its direction is listed twice", lane.lane),
            ));
        }
    }
    Ok(())
}

impl Iterator for TrafficGenerator {
    type Item = RecordedTruck;

    fn next(&mut self) -> Option<RecordedTruck> {
        let mut earliest: Option<(usize, f64)> = None;
        for (i, truck) in self.pending.iter().enumerate() {
            if let Some(truck) = truck {
                if earliest.is_none_or(|(_, t)| truck.arrival_time < t) {
                    earliest = Some((i, truck.arrival_time));
                }
            }
        }
        let (i, _) = earliest?;
        let truck = self.pending[i].take()?;
        self.last_arrival = truck.arrival_time;
        self.refill(i);
        Some(truck)
    }
}
