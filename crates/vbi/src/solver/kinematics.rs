//! Contact kinematics: where every contact is at an instant — its position x along the deck, its
//! speed of travel ẋ and, for a tyre, the road point (r, r′) under it.
//!
//! The motion law of today is one vehicle at constant speed v, each contact at a fixed offset
//! behind the front axle: x_c(t) = x₀ + v t + offset_c, ẋ_c = v. Everything downstream (contact
//! shapes, tyre forces, the coupled step) reads only [`ContactPoints`], so that another motion
//! law (several vehicles, each with its own x(t)) is a change of this file alone.

use super::validation::is_positive;
use super::{Crossing, SolverError};
use crate::road::{RoadProfile, Track};
use crate::vehicle::ContactKind;

/// The motion law of the contacts: the vehicle's start position and speed, and each contact's
/// longitudinal offset from the front axle and, for a tyre, the road track it runs on.
pub(super) struct ContactKinematics {
    /// Front-axle position x₀ at t = 0 [m].
    start_position: f64,
    /// Speed v [m/s].
    speed: f64,
    /// Longitudinal offset of each contact from the front axle [m], in the vehicle's order.
    offsets: Vec<f64>,
    /// Road track of each tyre; None for a moving force (which reads no road).
    tracks: Vec<Option<Track>>,
    /// min(0, offsets): the offset of the last contact to leave the deck [m].
    rearmost_offset: f64,
}

/// The contact points of one instant, indexed by contact (the vehicle's contact order).
pub(super) struct ContactPoints {
    /// Front-axle position x [m].
    pub(super) front_axle_position: f64,
    /// Position x of each contact along the deck [m].
    pub(super) position: Vec<f64>,
    /// Speed of travel ẋ of each contact [m/s].
    pub(super) travel_speed: Vec<f64>,
    /// Road elevation and slope (r, r′) under each tyre [m, -]; (0, 0) for a moving force.
    pub(super) road: Vec<(f64, f64)>,
}

impl ContactKinematics {
    /// The constant-speed law of `crossing`.
    pub(super) fn new(crossing: &Crossing) -> ContactKinematics {
        let contacts = &crossing.vehicle.contacts;
        ContactKinematics {
            start_position: crossing.start_position,
            speed: crossing.speed,
            offsets: contacts.iter().map(|c| c.longitudinal_offset).collect(),
            tracks: contacts
                .iter()
                .map(|c| {
                    matches!(c.kind, ContactKind::Tyre { .. })
                        .then(|| Track::of_lateral_offset(c.lateral_offset))
                })
                .collect(),
            rearmost_offset: contacts
                .iter()
                .map(|c| c.longitudinal_offset)
                .fold(0.0, f64::min),
        }
    }

    /// Time at which the last contact leaves the deck [s]: (L − offset_last − x₀) / v. Errs when
    /// the vehicle starts beyond the deck end.
    pub(super) fn exit_time(&self, deck_length: f64) -> Result<f64, SolverError> {
        let exit_distance = deck_length - self.rearmost_offset - self.start_position;
        if !is_positive(exit_distance) {
            return Err(SolverError::StartsBeyondDeck {
                start_position: self.start_position,
                deck_length,
            });
        }
        Ok(exit_distance / self.speed)
    }

    /// Buffers for the contact points of one instant.
    pub(super) fn points(&self) -> ContactPoints {
        let count = self.offsets.len();
        ContactPoints {
            front_axle_position: self.start_position,
            position: vec![0.0; count],
            travel_speed: vec![0.0; count],
            road: vec![(0.0, 0.0); count],
        }
    }

    /// The contact points at time t: x_c = (x₀ + v t) + offset_c, ẋ_c = v, and the road under
    /// each tyre.
    pub(super) fn locate(&self, time: f64, road: &RoadProfile, points: &mut ContactPoints) {
        let x_front = self.start_position + self.speed * time;
        points.front_axle_position = x_front;
        for (c, &offset) in self.offsets.iter().enumerate() {
            let x = x_front + offset;
            points.position[c] = x;
            points.travel_speed[c] = self.speed;
            if let Some(track) = self.tracks[c] {
                points.road[c] = road.elevation_and_slope(track, x);
            }
        }
    }

    /// The road point under tyre `contact` at its start position x₀ + offset (static
    /// equilibrium); (0, 0) for a moving force.
    pub(super) fn start_road_point(&self, contact: usize, road: &RoadProfile) -> (f64, f64) {
        match self.tracks[contact] {
            Some(track) => {
                road.elevation_and_slope(track, self.start_position + self.offsets[contact])
            }
            None => (0.0, 0.0),
        }
    }

    /// True once every contact of `points` is beyond the deck end (start of free vibration).
    pub(super) fn has_left_deck(&self, points: &ContactPoints, deck_length: f64) -> bool {
        points.front_axle_position + self.rearmost_offset > deck_length
    }
}
