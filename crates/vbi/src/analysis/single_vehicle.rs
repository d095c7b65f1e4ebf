//! The static reference of the heaviest single vehicle (issue 46, item 6). A DAF divides the
//! dynamic extreme by a static one; with several vehicles on the deck the headline divides by
//! the event's own static envelope, S(t) = Σ_w S_w · IL(x_w(t), y_w) over every wheel of every
//! vehicle, which can be below what one truck alone gives (two trucks meeting over a pier, one
//! loading the span's hogging and the other its sagging part: 1,560 against 1,779 kNm). Beside
//! it every entry of a run with two or more vehicles gets the largest static extreme of any one
//! vehicle alone, Sᵥ(t) = Σ_{w of v} S_w · IL(x_w(t), y_w), in the event's direction and taken
//! between the time steps as the event's is (`continuous_extreme`), and the DAF against it
//! (tested against each vehicle run alone: `crossing::tests::a_two_vehicle_event_states_…`).
//! This file splits a run's wheel paths by vehicle; `static_reference` takes each vehicle's
//! extremes over them.

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

    /// Its paths as a run's.
    pub(super) fn paths(&self) -> WheelPaths<'_> {
        WheelPaths {
            contacts: &self.contacts,
            positions: &self.positions,
            step_count: self.step_count,
        }
    }
}
