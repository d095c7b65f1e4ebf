//! The station histories of a crossing as named columns (`histories.csv` of `vbi run`, and
//! `RunResult.histories` in Python): one table, built once, so that every front end shows the
//! same columns with the same numbers.

use crate::analysis::{
    corrected_station_responses, static_force_reference, static_reference, station_response,
    AnalysisError,
};
use crate::modal::Quantity;
use crate::solver::ResponseHistory;

use super::PreparedBridge;

/// One named column of the station histories, one value per recorded instant.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryColumn {
    /// Name with its unit (`span1_mid_g2_moment_n_m`, `span1_mid_g2_paper_moment_n_m`).
    pub name: String,
    /// Values [the unit in the name].
    pub values: Vec<f64>,
}

/// Time [s], the front axle's position [m], then for every station its deflection [m] (the
/// converged, static-corrected one `<station>_<quantity>`, the paper's plain modal sum
/// `<station>_paper_<quantity>`, the exact static one `<station>_static_<quantity>`), its
/// bending moment [N·m] (the same three), its shear force or, at a support, its support
/// reaction [N] (the same three, where the basis has them), and its acceleration [m/s²]. Where
/// the correction does not exist (a mode without a positive frequency) the first column is the
/// plain modal sum, as the report's headline is ([`crate::analysis::StationDaf::static_corrected`]).
pub fn station_history_columns(
    bridge: &PreparedBridge,
    history: &ResponseHistory,
) -> Result<Vec<HistoryColumn>, AnalysisError> {
    let (basis, influence) = (&bridge.basis, &bridge.influence);
    let reference = static_reference(influence, history)?;
    let all_stations: Vec<usize> = (0..basis.stations.len()).collect();
    let forces = static_force_reference(influence, history, &all_stations)?;
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
        for quantity in basis.station_quantities(s) {
            if !influence.has_quantity(s, quantity) {
                continue;
            }
            let statics = match quantity {
                Quantity::Deflection => column_of(&reference.deflection, stations, s, steps),
                Quantity::BendingMoment => column_of(&reference.bending_moment, stations, s, steps),
                Quantity::ShearForce | Quantity::SupportReaction => forces[s].clone(),
            };
            let (name, unit) = (&station.name, column_suffix(quantity));
            let paper = station_response(basis, history, s, quantity)?;
            let converged = corrected.as_ref().and_then(|c| {
                c[s].iter()
                    .find(|(q, _)| *q == quantity)
                    .map(|(_, values)| values.clone())
            });
            columns.push(column(
                format!("{name}_{unit}"),
                converged.unwrap_or_else(|| paper.clone()),
            ));
            columns.push(column(format!("{name}_paper_{unit}"), paper));
            columns.push(column(format!("{name}_static_{unit}"), statics));
        }
        columns.push(column(
            format!("{}_acceleration_m_s2", station.name),
            station_acceleration(bridge, history, s),
        ));
    }
    Ok(columns)
}

/// The quantity and unit part of a station history's column name.
pub fn column_suffix(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::Deflection => "deflection_m",
        Quantity::BendingMoment => "moment_n_m",
        Quantity::ShearForce => "shear_n",
        Quantity::SupportReaction => "reaction_n",
    }
}

/// Station `s`'s column of a step-major table with `stations` columns.
fn column_of(table: &[f64], stations: usize, s: usize, steps: usize) -> Vec<f64> {
    (0..steps).map(|i| table[i * stations + s]).collect()
}

/// The vertical acceleration at station `s` [m/s²], Σₖ φₖ(station) q̈ₖ(t_i): the plain modal sum,
/// which converges fast for acceleration (the high modes' accelerations are not negligible, but
/// the static correction concerns the quasi-static part only).
pub fn station_acceleration(
    bridge: &PreparedBridge,
    history: &ResponseHistory,
    s: usize,
) -> Vec<f64> {
    let n = history.mode_count;
    let shape = &bridge.basis.station_deflection[s * n..(s + 1) * n];
    history
        .modal_acceleration
        .chunks_exact(n)
        .take(history.step_count)
        .map(|qdd| shape.iter().zip(qdd).map(|(p, a)| p * a).sum())
        .collect()
}

/// The largest vertical acceleration at station `s` [m/s²], in absolute value:
/// max_i |Σₖ φₖ(station) q̈ₖ(t_i)| over the recorded instants ([`station_acceleration`]); 0
/// for a history without modal accelerations. What `vbi run`'s summary.json reports as
/// `station_accelerations` (the deck acceleration that a serviceability check reads).
pub fn station_peak_acceleration(
    bridge: &PreparedBridge,
    history: &ResponseHistory,
    s: usize,
) -> f64 {
    station_acceleration(bridge, history, s)
        .iter()
        .fold(0.0, |m: f64, a| m.max(a.abs()))
}

/// The vehicles' histories as named columns (`vehicles.csv` of `vbi run`), copied out of the
/// history: the columns of [`VehicleHistoryTable`], whose documentation names them.
pub fn vehicle_history_columns(history: &ResponseHistory) -> Vec<HistoryColumn> {
    let table = VehicleHistoryTable::of(history);
    (0..table.column_count())
        .map(|c| HistoryColumn {
            name: table.name(c).to_owned(),
            values: table.column(c).collect(),
        })
        .collect()
}

/// The vehicles' histories as named columns read in place from the history (a traffic stream's
/// are hundreds of columns over tens of thousands of instants: no copy): time [s]; every
/// vehicle DOF's displacement from static equilibrium and acceleration (`<dof>_displacement_m`,
/// `_rad` for a pitch or roll; `<dof>_acceleration_m_s2`, `_rad_s2`); every contact's deck
/// position x [m] and force [N] (compressive positive, static load included), named
/// `v<vehicle>_contact<c>_x_m` and `…_force_n` (vehicle and contact from 1).
pub struct VehicleHistoryTable<'a> {
    history: &'a ResponseHistory,
    /// Each column's name and where its values are.
    columns: Vec<(String, VehicleColumn)>,
}

/// Where a column of [`VehicleHistoryTable`] reads its values.
#[derive(Debug, Clone, Copy)]
enum VehicleColumn {
    Time,
    Displacement(usize),
    Acceleration(usize),
    ContactPosition(usize),
    ContactForce(usize),
}

impl<'a> VehicleHistoryTable<'a> {
    /// The columns of `history`.
    pub fn of(history: &'a ResponseHistory) -> Self {
        let mut columns = vec![("time_s".to_owned(), VehicleColumn::Time)];
        for (j, dof) in history.vehicle_dof_names.iter().enumerate() {
            let rotation = dof.ends_with("_pitch") || dof.ends_with("_roll");
            let (u, a) = match rotation {
                true => ("rad", "rad_s2"),
                false => ("m", "m_s2"),
            };
            let displacement = format!("{dof}_displacement_{u}");
            columns.push((displacement, VehicleColumn::Displacement(j)));
            let acceleration = format!("{dof}_acceleration_{a}");
            columns.push((acceleration, VehicleColumn::Acceleration(j)));
        }
        let vehicles = history.contacts.iter().map(|c| c.vehicle + 1).max();
        let mut numbers = vec![0_usize; vehicles.unwrap_or(0)];
        for (w, contact) in history.contacts.iter().enumerate() {
            numbers[contact.vehicle] += 1;
            let name = format!(
                "v{}_contact{}",
                contact.vehicle + 1,
                numbers[contact.vehicle]
            );
            columns.push((format!("{name}_x_m"), VehicleColumn::ContactPosition(w)));
            columns.push((format!("{name}_force_n"), VehicleColumn::ContactForce(w)));
        }
        VehicleHistoryTable { history, columns }
    }

    /// Number of columns.
    pub fn column_count(&self) -> usize {
        self.columns.len()
    }

    /// Name of column `c`, with its unit.
    pub fn name(&self, c: usize) -> &str {
        &self.columns[c].0
    }

    /// Column `c`'s value at instant i [the unit in its name].
    #[inline]
    pub fn value(&self, c: usize, i: usize) -> f64 {
        let history = self.history;
        let (d, contacts) = (history.vehicle_dof_count(), history.contacts.len());
        match self.columns[c].1 {
            VehicleColumn::Time => history.time(i),
            VehicleColumn::Displacement(j) => history.vehicle_displacement[i * d + j],
            VehicleColumn::Acceleration(j) => history.vehicle_acceleration[i * d + j],
            VehicleColumn::ContactPosition(w) => history.contact_position[i * contacts + w],
            VehicleColumn::ContactForce(w) => history.contact_force[i * contacts + w],
        }
    }

    /// Column `c`'s values at every instant, in order.
    pub fn column(&self, c: usize) -> impl Iterator<Item = f64> + '_ {
        (0..self.history.step_count).map(move |i| self.value(c, i))
    }
}
