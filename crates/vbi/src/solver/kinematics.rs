//! Contact kinematics: where every contact is at an instant — its position x along the deck, its
//! speed of travel ẋ and, for a tyre, the road point (r, r′) under it.
//!
//! Each vehicle follows its own travel law s(t) ([`crate::traffic::law`]), forward or backward, each
//! contact at a fixed offset behind its front axle. Everything downstream (contact shapes, tyre
//! forces, the coupled step) reads only [`ContactPoints`].

use super::stacked::Placement;
use super::validation::is_positive;
use super::{Crossing, SolverError};
use crate::road::{RoadProfile, RoadStencil, Track};
use crate::traffic::law::{TravelDirection, TravelLaw};

/// The motion law of the contacts: each vehicle's travel law and direction, and each
/// contact's vehicle, longitudinal offset from its front axle and road track.
pub(super) struct ContactKinematics {
    /// Deck length L [m] (where a backward vehicle enters).
    deck_length: f64,
    /// Each vehicle's travel law s(t).
    laws: Vec<TravelLaw>,
    /// Each vehicle's direction.
    directions: Vec<TravelDirection>,
    /// min(0, offsets) of each vehicle: the offset of its last contact to leave the deck [m].
    rearmost_offsets: Vec<f64>,
    /// The vehicle of each contact, in the stacked order.
    vehicle_of: Vec<usize>,
    /// Longitudinal offset of each contact from its front axle [m], ≤ 0 along the travel.
    offsets: Vec<f64>,
    /// Road track of each tyre; None for a moving force (which reads no road).
    tracks: Vec<Option<Track>>,
}

/// The contact points of one instant, indexed by contact (the stacked contact order).
pub(super) struct ContactPoints {
    /// Deck position x of the first vehicle's front axle [m].
    pub(super) front_axle_position: f64,
    /// Travel coordinate s of each vehicle's front axle [m].
    pub(super) travel: Vec<f64>,
    /// Longitudinal acceleration s̈ of each vehicle [m/s²] (exact, from its travel law).
    pub(super) acceleration: Vec<f64>,
    /// Each vehicle's front-axle deck position x_f [m], the sign of ẋ (+1 forward, −1
    /// backward) and its speed v [m/s].
    fronts: Vec<(f64, f64, f64)>,
    /// Position x of each contact along the deck [m].
    pub(super) position: Vec<f64>,
    /// Speed of travel ẋ of each contact [m/s] (negative for a vehicle travelling backward).
    pub(super) travel_speed: Vec<f64>,
    /// Road elevation and slope (r, dr/dx) under each tyre [m, -]; (0, 0) for a moving force.
    pub(super) road: Vec<(f64, f64)>,
}

impl ContactKinematics {
    /// The motion law of `crossing`'s vehicles on a deck of length L, with the contacts placed
    /// as in `placements` (the stacked order).
    pub(super) fn new(
        crossing: &Crossing,
        placements: &[Placement],
        deck_length: f64,
    ) -> ContactKinematics {
        let runs = &crossing.vehicles;
        ContactKinematics {
            deck_length,
            laws: runs
                .iter()
                .map(|r| TravelLaw::new(r.start_position, &r.speed))
                .collect(),
            directions: runs.iter().map(|r| r.direction).collect(),
            rearmost_offsets: runs
                .iter()
                .map(|r| {
                    r.vehicle
                        .contacts
                        .iter()
                        .map(|c| c.longitudinal_offset)
                        .fold(0.0, f64::min)
                })
                .collect(),
            vehicle_of: placements.iter().map(|p| p.vehicle).collect(),
            offsets: runs
                .iter()
                .flat_map(|r| r.vehicle.contacts.iter().map(|c| c.longitudinal_offset))
                .collect(),
            tracks: placements.iter().map(|p| p.track).collect(),
        }
    }

    /// Time at which the last contact of the last vehicle leaves the deck [s]: the largest over
    /// the vehicles of t(s = L − offset_last). Errs when a vehicle starts beyond the deck end.
    pub(super) fn exit_time(&self) -> Result<f64, SolverError> {
        let mut exit: f64 = 0.0;
        for (law, &rearmost) in self.laws.iter().zip(&self.rearmost_offsets) {
            let (start, _) = law.at(0.0);
            let exit_distance = self.deck_length - rearmost - start;
            if !is_positive(exit_distance) {
                return Err(SolverError::StartsBeyondDeck {
                    start_position: start,
                    deck_length: self.deck_length,
                });
            }
            exit = exit.max(law.time_at_travel(self.deck_length - rearmost));
        }
        Ok(exit)
    }

    /// Buffers for the contact points of one instant.
    pub(super) fn points(&self) -> ContactPoints {
        let count = self.offsets.len();
        ContactPoints {
            front_axle_position: 0.0,
            travel: vec![0.0; self.laws.len()],
            acceleration: vec![0.0; self.laws.len()],
            fronts: vec![(0.0, 1.0, 0.0); self.laws.len()],
            position: vec![0.0; count],
            travel_speed: vec![0.0; count],
            road: vec![(0.0, 0.0); count],
        }
    }

    /// The contact points at time t: each vehicle at s(t) with its acceleration s̈(t), its front
    /// axle at x_f = s forward or L − s backward, its contacts at x_c = x_f + offset_c forward or
    /// x_f − offset_c backward, with ẋ_c = ±v(t); and the road under each tyre.
    pub(super) fn locate(&self, time: f64, road: &RoadProfile, points: &mut ContactPoints) {
        self.locate_on_deck(time, points);
        let mut stencils = Vec::with_capacity(self.tracks.len());
        self.road_stencils(road, points, &mut stencils);
        self.road_under_tyres(road, &stencils, points);
    }

    /// The x-dependent part of the road's interpolant under each tyre at `points`' positions
    /// ([`RoadStencil`]; None for a moving force). The two wheels of an axle stand at the same
    /// x: the second takes the first's stencil (the same numbers as its own, bit for bit).
    pub(super) fn road_stencils(
        &self,
        road: &RoadProfile,
        points: &ContactPoints,
        stencils: &mut Vec<Option<RoadStencil>>,
    ) {
        stencils.clear();
        let mut last: Option<(f64, RoadStencil)> = None;
        for (track, &x) in self.tracks.iter().zip(&points.position) {
            if track.is_none() {
                stencils.push(None);
                continue;
            }
            let stencil = match last {
                Some((at, stencil)) if at.to_bits() == x.to_bits() => stencil,
                _ => road.stencil(x),
            };
            last = Some((x, stencil));
            stencils.push(Some(stencil));
        }
    }

    /// The road (r, r′) under each tyre from its stencil ([`ContactKinematics::road_stencils`]
    /// at these positions, on a road with the same sample grid).
    pub(super) fn road_under_tyres(
        &self,
        road: &RoadProfile,
        stencils: &[Option<RoadStencil>],
        points: &mut ContactPoints,
    ) {
        let tyres = self.tracks.iter().zip(stencils).zip(&mut points.road);
        for ((track, stencil), under) in tyres {
            if let (Some(track), Some(stencil)) = (track, stencil) {
                *under = stencil.evaluate(road.samples(*track));
            }
        }
    }

    /// [`ContactKinematics::locate`] but for the road: where the contacts are and how they
    /// move at time t, which the road does not change.
    pub(super) fn locate_on_deck(&self, time: f64, points: &mut ContactPoints) {
        for (v, law) in self.laws.iter().enumerate() {
            let (s, speed) = law.at(time);
            let (front, sign) = self.front_and_sign(v, s);
            points.travel[v] = s;
            points.acceleration[v] = law.acceleration(time);
            points.fronts[v] = (front, sign, speed);
        }
        points.front_axle_position = points.fronts[0].0;
        for (c, &offset) in self.offsets.iter().enumerate() {
            let (front, sign, speed) = points.fronts[self.vehicle_of[c]];
            let x = front + sign * offset;
            points.position[c] = x;
            points.travel_speed[c] = sign * speed;
        }
    }

    /// The deck position of vehicle `v`'s front axle at travel s, and the sign of ẋ.
    fn front_and_sign(&self, v: usize, s: f64) -> (f64, f64) {
        match self.directions[v] {
            TravelDirection::Forward => (s, 1.0),
            TravelDirection::Backward => (self.deck_length - s, -1.0),
        }
    }

    /// The speed of the first vehicle at t = 0 [m/s].
    pub(super) fn initial_speed(&self) -> f64 {
        self.laws[0].at(0.0).1
    }

    /// The contact points at t = 0 (the start positions of the static equilibrium).
    pub(super) fn start_points(&self, road: &RoadProfile) -> ContactPoints {
        let mut points = self.points();
        self.locate(0.0, road, &mut points);
        points
    }

    /// True once every vehicle's last contact is beyond the deck end of its direction (start
    /// of free vibration).
    pub(super) fn has_left_deck(&self, points: &ContactPoints) -> bool {
        points
            .travel
            .iter()
            .zip(&self.rearmost_offsets)
            .all(|(s, rearmost)| s + rearmost > self.deck_length)
    }
}

#[cfg(test)]
mod tests {
    use super::super::stacked::StackedVehicles;
    use super::*;
    use crate::vehicle::{assemble, preset};

    #[test]
    fn the_road_under_each_tyre_is_its_own_tracks_interpolant_bit_for_bit() {
        // A five-axle truck (both wheels of each axle at one x, on two tracks) on a road whose
        // tracks differ, at instants that put wheels before, on and beyond the profile.
        let truck = assemble(&preset("tractor-semitrailer-5axle").unwrap()).unwrap();
        let road = RoadProfile {
            highest_spatial_frequency: None,
            start: -20.0,
            spacing: 0.1,
            left: (0..700).map(|i| (0.37 * i as f64).sin() * 4.0e-3).collect(),
            right: (0..700).map(|i| (0.23 * i as f64).cos() * 3.0e-3).collect(),
        };
        let mut crossing = Crossing::new(truck, road, 22.0);
        crossing.vehicles[0].start_position = -10.0;
        let traffic = StackedVehicles::new(&crossing);
        let kinematics = ContactKinematics::new(&crossing, &traffic.placements, 30.0);
        let mut points = kinematics.points();
        let mut reused = 0;
        for step in 0..300 {
            let time = step as f64 * 7.0e-3;
            kinematics.locate(time, &crossing.road, &mut points);
            for (c, track) in kinematics.tracks.iter().enumerate() {
                let track = track.expect("a truck's contacts are tyres");
                let own = crossing.road.elevation_and_slope(track, points.position[c]);
                assert_eq!(
                    (points.road[c].0.to_bits(), points.road[c].1.to_bits()),
                    (own.0.to_bits(), own.1.to_bits()),
                    "contact {c} at t = {time}"
                );
                reused += usize::from(c > 0 && points.position[c] == points.position[c - 1]);
            }
        }
        assert!(reused > 0, "the wheels of an axle share their x");
    }
}
