//! The fatigue of a crossing's details (issue 51): each detail's stress history from its
//! station's converged (static-corrected) effect history and from the exact static one, the
//! same series as histories.csv's `<station>_<quantity>` and `<station>_static_<quantity>`
//! columns ([`station_history_columns`]), counted and summed by [`crate::fatigue`].

use crate::analysis::{corrected_station_response_by_modes, usable_check_modes};
use crate::fatigue::{DetailFatigue, FatigueConvergence, FatigueDetail};
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
        let mut evaluated = DetailFatigue::of(detail, dynamic, static_history);
        evaluated.convergence = modal_convergence(bridge, history, &evaluated, static_history)?;
        fatigue.push(evaluated);
    }
    Ok(fatigue)
}

/// The fatigue DAFs' convergence indicator in the modes ([`FatigueConvergence`]): each DAF again
/// from the static-corrected history with the first K modes, K over the last ⌈N/2⌉ kept, and
/// with the check modes after the N (twice that change, where larger: as `daf_change`). None
/// with one mode and no check modes, or where the correction does not exist.
fn modal_convergence(
    bridge: &PreparedBridge,
    history: &ResponseHistory,
    fatigue: &DetailFatigue,
    static_history: &[f64],
) -> Result<Option<FatigueConvergence>, PipelineError> {
    let detail = &fatigue.detail;
    let basis = &bridge.basis;
    let n = basis.mode_count();
    let window = n.div_ceil(2);
    let check = usable_check_modes(basis).map_or(0, |c| c.mode_count());
    let Some(station) = (basis.stations.iter()).position(|s| s.name == detail.station) else {
        return Ok(None);
    };
    let beyond = (check > 0).then_some(n + check);
    let counts: Vec<usize> = (n.saturating_sub(window).max(1)..n).chain(beyond).collect();
    if counts.is_empty() {
        return Ok(None);
    }
    let station_quantity = (station, detail.quantity);
    let partial = corrected_station_response_by_modes(
        basis,
        &bridge.influence,
        history,
        station_quantity,
        &counts,
    )
    .map_err(PipelineError::Analysis)?;
    let Some(partial) = partial else {
        return Ok(None);
    };
    let headline = fatigue.amplification;
    let change = |of: fn(&crate::fatigue::FatigueAmplification) -> Option<f64>| {
        let full = of(&headline)?;
        (partial.iter())
            .map(|(k, values)| {
                let truncated = DetailFatigue::of(detail, values, static_history).amplification;
                let weight = if *k > n { 2.0 } else { 1.0 };
                of(&truncated).map(|daf| weight * (daf - full).abs())
            })
            .try_fold(0.0f64, |largest, change| Some(largest.max(change?)))
    };
    Ok(Some(FatigueConvergence {
        window,
        fatigue_daf_change: change(|a| a.fatigue_daf),
        straight_line_change: change(|a| a.fatigue_daf_straight_line),
    }))
}
