//! A scenario's crossing event placed by [`crate::traffic`]: the scenario's traffic fields handed
//! over as a [`TrafficSpec`](crate::traffic::TrafficSpec), and a refusal of the traffic read as
//! the pipeline's error, with the variant it always had (which `vbi-input` locates at a key).

use super::{PipelineError, Scenario};
use crate::solver::{SolverError, VehicleRun};
use crate::traffic::{self, TrafficError};

impl From<TrafficError> for PipelineError {
    fn from(error: TrafficError) -> PipelineError {
        match error {
            TrafficError::Vehicle(source) => PipelineError::Vehicle(source),
            TrafficError::Stream(source) => PipelineError::Stream(source),
            TrafficError::Overlap(overlap) => {
                PipelineError::Crossing(SolverError::VehiclesOverlap(overlap))
            }
            TrafficError::Placement {
                vehicle,
                label,
                reason,
            } => PipelineError::Traffic {
                vehicle,
                label,
                reason,
            },
        }
    }
}

/// The vehicles of the scenario's event, placed for t = 0 ([`traffic::vehicle_runs`]).
pub fn vehicle_runs(scenario: &Scenario) -> Result<Vec<VehicleRun>, PipelineError> {
    Ok(traffic::vehicle_runs(&scenario.traffic_spec())?)
}

/// The road extent every tyre's path needs ([`traffic::road_extent`]).
pub fn road_extent(scenario: &Scenario, runs: &[VehicleRun]) -> (f64, f64) {
    traffic::road_extent(&scenario.traffic_spec(), runs)
}

/// The key of the input table that vehicle `index` (0-based) of the event comes from
/// ([`traffic::input_entry`]).
pub fn input_entry(scenario: &Scenario, index: usize) -> String {
    traffic::input_entry(&scenario.traffic_spec(), index)
}
