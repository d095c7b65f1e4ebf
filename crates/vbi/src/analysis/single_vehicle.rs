//! The static reference of the heaviest single vehicle (issue 46, item 6). A DAF divides the
//! dynamic extreme by a static one; with several vehicles on the deck the headline divides by
//! the event's own static envelope, S(t) = Σ_w S_w · IL(x_w(t), y_w) over every wheel of every
//! vehicle, which can be below what one truck alone gives (two trucks meeting over a pier, one
//! loading the span's hogging and the other its sagging part: 1,560 against 1,779 kNm). Beside
//! it every entry of a run with two or more vehicles gets the largest static extreme of any one
//! vehicle alone, Sᵥ(t) = Σ_{w of v} S_w · IL(x_w(t), y_w), in the event's direction and taken
//! between the time steps as the event's is ([`continuous_extreme`]), and the DAF against it
//! (tested against each vehicle run alone: `crossing::tests::a_two_vehicle_event_states_…`).

use super::continuous_extreme::continuous_extreme;
use crate::influence::InfluenceLines;
use crate::modal::Quantity;
use crate::solver::{ContactPath, WheelPaths};

/// One vehicle's wheel paths: its contacts and their positions, copied out of a run's.
pub(super) struct VehiclePaths {
    contacts: Vec<ContactPath>,
    positions: Vec<f64>,
    step_count: usize,
}

impl VehiclePaths {
    /// The paths of each vehicle of `paths` with a contact, in the order of the vehicles; empty
    /// for a run of one vehicle (its reference is the event's).
    pub(super) fn of_each(paths: WheelPaths) -> Vec<VehiclePaths> {
        let mut vehicles: Vec<usize> = paths.contacts.iter().map(|c| c.vehicle).collect();
        vehicles.sort_unstable();
        vehicles.dedup();
        if vehicles.len() < 2 {
            return Vec::new();
        }
        let all = paths.contacts.len();
        vehicles
            .into_iter()
            .map(|v| {
                let own: Vec<usize> = (0..all)
                    .filter(|&w| paths.contacts[w].vehicle == v)
                    .collect();
                let positions = (0..paths.step_count)
                    .flat_map(|i| own.iter().map(move |&w| paths.positions[i * all + w]))
                    .collect();
                VehiclePaths {
                    contacts: own.iter().map(|&w| paths.contacts[w].clone()).collect(),
                    positions,
                    step_count: paths.step_count,
                }
            })
            .collect()
    }

    fn paths(&self) -> WheelPaths<'_> {
        WheelPaths {
            contacts: &self.contacts,
            positions: &self.positions,
            step_count: self.step_count,
        }
    }
}

/// The largest static extreme of one vehicle alone at station `s`, quantity `quantity`
/// (deflection or bending moment), in the direction `sign` of the event's extreme, taken between
/// the steps: signed; None where no vehicle loads the station in that direction.
pub(super) fn single_vehicle_extreme(
    influence: &InfluenceLines,
    vehicles: &[VehiclePaths],
    (station, quantity): (usize, Quantity),
    sign: f64,
) -> Option<f64> {
    let mut best: Option<f64> = None;
    for vehicle in vehicles {
        let paths = vehicle.paths();
        let history = static_history(influence, paths, (station, quantity));
        let sampled = (history.iter().enumerate())
            .filter(|&(_, &v)| sign * v > 0.0)
            .max_by(|a, b| (sign * a.1).total_cmp(&(sign * b.1)));
        let Some((step, &value)) = sampled else {
            continue;
        };
        let (value, _) = continuous_extreme(influence, paths, (station, quantity), (step, value));
        if best.is_none_or(|b| sign * value > sign * b) {
            best = Some(value);
        }
    }
    best
}

/// S(t) of one station's deflection or moment under the wheels of `paths`, at the instants.
fn static_history(
    influence: &InfluenceLines,
    paths: WheelPaths,
    (station, quantity): (usize, Quantity),
) -> Vec<f64> {
    (0..paths.step_count)
        .map(|i| {
            let positions = &paths.positions[i * paths.contacts.len()..];
            (paths.contacts.iter().zip(positions))
                .map(|(contact, &x)| {
                    let unit = influence.unit_load_response(
                        station,
                        quantity,
                        x,
                        contact.lateral_position,
                    );
                    contact.static_load * unit
                })
                .sum()
        })
        .collect()
}
