//! Vehicles may not overlap at t = 0: the footprint of each vehicle's contacts on the deck and
//! the check that no two share a part of it.

use super::{TravelDirection, VehicleRun};

/// Two vehicles occupy the same part of the deck or road at t = 0.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "vehicles {first} and {second} overlap at t = 0: their contacts span x from {} to {} m \
     and from {} to {} m in overlapping lanes; give the second a later entry or a larger gap",
    first_extent.0, first_extent.1, second_extent.0, second_extent.1
)]
pub struct VehiclesOverlap {
    /// First vehicle (from 1).
    pub first: usize,
    /// Second vehicle (from 1).
    pub second: usize,
    /// Deck x interval of the first vehicle's contacts [m].
    pub first_extent: (f64, f64),
    /// Deck x interval of the second's [m].
    pub second_extent: (f64, f64),
}

/// Vehicles may not overlap at t = 0: two vehicles whose contacts' deck x intervals overlap
/// (more than touching end to end: a gap of zero is allowed, a shared front or rear axle
/// position is not) and whose lateral intervals meet are refused.
pub fn check_vehicles_apart(
    vehicles: &[VehicleRun],
    deck_length: f64,
) -> Result<(), VehiclesOverlap> {
    let footprints: Vec<((f64, f64), (f64, f64))> = vehicles
        .iter()
        .map(|run| footprint(run, deck_length))
        .collect();
    for (i, (xi, yi)) in footprints.iter().enumerate() {
        for (j, (xj, yj)) in footprints.iter().enumerate().skip(i + 1) {
            let along = (xi.0 < xj.1 && xj.0 < xi.1) || xi.0 == xj.0 || xi.1 == xj.1;
            let across = yi.0 <= yj.1 && yj.0 <= yi.1;
            if along && across {
                return Err(VehiclesOverlap {
                    first: i + 1,
                    second: j + 1,
                    first_extent: *xi,
                    second_extent: *xj,
                });
            }
        }
    }
    Ok(())
}

/// The deck x and lateral y intervals [m] that a vehicle's contacts span at t = 0.
pub(super) fn footprint(run: &VehicleRun, deck_length: f64) -> ((f64, f64), (f64, f64)) {
    let (front, sign, lateral_sign) = match run.direction {
        TravelDirection::Forward => (run.start_position, 1.0, 1.0),
        TravelDirection::Backward => (deck_length - run.start_position, -1.0, -1.0),
    };
    let mut x = (f64::INFINITY, f64::NEG_INFINITY);
    let mut y = (f64::INFINITY, f64::NEG_INFINITY);
    for c in &run.vehicle.contacts {
        let (cx, cy) = (
            front + sign * c.longitudinal_offset,
            run.lateral_position + lateral_sign * c.lateral_offset,
        );
        x = (x.0.min(cx), x.1.max(cx));
        y = (y.0.min(cy), y.1.max(cy));
    }
    (x, y)
}
