//! The station histories of a crossing as named columns (`histories.csv` of `vbi run`, and
//! `RunResult.histories` in Python): one table, built once, so that every front end shows the
//! same columns with the same numbers.

use crate::analysis::{
    corrected_station_responses, static_reference, station_response, AnalysisError,
};
use crate::modal::Quantity;
use crate::solver::ResponseHistory;

use super::PreparedBridge;

/// One named column of the station histories, one value per recorded instant.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryColumn {
    /// Name with its unit (`span1_mid_g2_corrected_moment_n_m`).
    pub name: String,
    /// Values [the unit in the name].
    pub values: Vec<f64>,
}

/// Time [s], the front axle's position [m], then for every station its deflection [m] (the
/// paper's modal sum, the static-corrected converged one, the exact static one) and its bending
/// moment [N·m] (the same three). The corrected columns are left out when the correction does
/// not exist (a mode without a positive frequency).
pub fn station_history_columns(
    bridge: &PreparedBridge,
    history: &ResponseHistory,
) -> Result<Vec<HistoryColumn>, AnalysisError> {
    let (basis, influence) = (&bridge.basis, &bridge.influence);
    let reference = static_reference(influence, history)?;
    let corrected = corrected_station_responses(basis, influence, history)?;
    let stations = basis.stations.len();
    let steps = history.step_count;
    let column = |name: String, values: Vec<f64>| HistoryColumn { name, values };
    let mut columns = vec![
        column(
            "time_s".into(),
            (0..steps).map(|i| history.time(i)).collect(),
        ),
        column(
            "front_axle_x_m".into(),
            history.front_axle_position[..steps].to_vec(),
        ),
    ];
    for (s, station) in basis.stations.iter().enumerate() {
        let statics = [&reference.deflection, &reference.bending_moment].map(|r| {
            (0..steps)
                .map(|i| r[i * stations + s])
                .collect::<Vec<f64>>()
        });
        for (q, (quantity, unit)) in [
            (Quantity::Deflection, "deflection_m"),
            (Quantity::BendingMoment, "moment_n_m"),
        ]
        .into_iter()
        .enumerate()
        {
            let name = &station.name;
            columns.push(column(
                format!("{name}_{unit}"),
                station_response(basis, history, s, quantity)?,
            ));
            if let Some(c) = &corrected {
                columns.push(column(format!("{name}_corrected_{unit}"), c[s][q].clone()));
            }
            columns.push(column(format!("{name}_static_{unit}"), statics[q].clone()));
        }
    }
    Ok(columns)
}
