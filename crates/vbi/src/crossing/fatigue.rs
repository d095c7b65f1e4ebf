//! The fatigue of a crossing's details (issue 51): each detail's stress history from its
//! station's converged (static-corrected) effect history and from the exact static one, the
//! same series as histories.csv's `<station>_<quantity>` and `<station>_static_<quantity>`
//! columns ([`station_history_columns`]), counted and summed by [`crate::fatigue`].

use crate::fatigue::{DetailFatigue, FatigueDetail};
use crate::model::station::{Quantity, Station};
use crate::solver::ResponseHistory;

use super::histories::{column_suffix, station_history_columns};
use super::{PipelineError, PreparedBridge};

/// A fatigue detail that the bridge cannot evaluate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FatigueDetailError {
    /// No station of that name.
    #[error("no station `{station}`; expected one of {known}")]
    UnknownStation { station: String, known: String },
    /// The station does not read the detail's effect.
    #[error(
        "station `{station}` reads no {quantity} (a support station reads the support reaction, \
         not the shear force); expected {allowed}"
    )]
    Quantity {
        station: String,
        quantity: &'static str,
        allowed: String,
    },
    /// An effect that stresses no detail.
    #[error("a detail is stressed by a bending moment or a shear force; {0} is neither")]
    NotAnEffect(&'static str),
}

/// Checks that every detail's station exists among `stations` and reads its effect. Errors: the
/// index of the first detail at fault and why.
pub fn check_fatigue_details(
    stations: &[Station],
    details: &[FatigueDetail],
) -> Result<(), (usize, FatigueDetailError)> {
    for (i, detail) in details.iter().enumerate() {
        if !matches!(
            detail.quantity,
            Quantity::BendingMoment | Quantity::ShearForce
        ) {
            return Err((i, FatigueDetailError::NotAnEffect(detail.quantity.name())));
        }
        let Some(station) = stations.iter().find(|s| s.name == detail.station) else {
            let known: Vec<&str> = stations.iter().map(|s| s.name.as_str()).collect();
            return Err((
                i,
                FatigueDetailError::UnknownStation {
                    station: detail.station.clone(),
                    known: known.join(", "),
                },
            ));
        };
        if !station.quantities().contains(&detail.quantity) {
            return Err((
                i,
                FatigueDetailError::Quantity {
                    station: station.name.clone(),
                    quantity: detail.quantity.name(),
                    allowed: "bending_moment".into(),
                },
            ));
        }
    }
    Ok(())
}

/// The fatigue of each detail under one crossing: rainflow and Miner on its stress from the
/// converged effect history (the headline, as the DAF's) and from the exact static one. Errors:
/// a detail whose station the bridge lacks or does not read the effect at
/// ([`PipelineError::FatigueDetail`]), and the analysis's.
pub fn crossing_fatigue(
    bridge: &PreparedBridge,
    history: &ResponseHistory,
    details: &[FatigueDetail],
) -> Result<Vec<DetailFatigue>, PipelineError> {
    if details.is_empty() {
        return Ok(Vec::new());
    }
    let at_fault = |(index, source)| PipelineError::FatigueDetail { index, source };
    check_fatigue_details(&bridge.basis.stations, details).map_err(at_fault)?;
    let columns = station_history_columns(bridge, history).map_err(PipelineError::Analysis)?;
    let column = |name: String| {
        columns
            .iter()
            .find(|c| c.name == name)
            .map(|c| c.values.as_slice())
    };
    let mut fatigue = Vec::with_capacity(details.len());
    for (index, detail) in details.iter().enumerate() {
        let suffix = column_suffix(detail.quantity);
        let (Some(dynamic), Some(static_history)) = (
            column(format!("{}_{suffix}", detail.station)),
            column(format!("{}_static_{suffix}", detail.station)),
        ) else {
            return Err(at_fault((
                index,
                FatigueDetailError::Quantity {
                    station: detail.station.clone(),
                    quantity: detail.quantity.name(),
                    allowed: "a quantity the bridge's modes read there (an imported basis reads \
                              only those of its files)"
                        .into(),
                },
            )));
        };
        fatigue.push(DetailFatigue::of(detail, dynamic, static_history));
    }
    Ok(fatigue)
}
