//! The motion law of one vehicle: how far its front axle has travelled at time t, and how fast.
//!
//! A vehicle travels along a line parallel to the deck's axis, in one of two directions. Its
//! travel coordinate s is the distance of the front axle past the deck entry of its direction
//! (x = 0 for [`TravelDirection::Forward`], x = L for [`TravelDirection::Backward`]), negative on
//! the approach; the deck position of the front axle is x = s or x = L − s.
//!
//! The speed is a [`SpeedProfile`]: constant, or piecewise with constant acceleration between
//! knots (s_i, v_i), where v² is linear in s:
//! a_i = (v_{i+1}² − v_i²) / (2 (s_{i+1} − s_i)), s(τ) = s_i + v_i τ + ½ a_i τ², v(τ) = v_i + a_i τ,
//! the segment taking Δt_i = 2 (s_{i+1} − s_i) / (v_i + v_{i+1}). Before the first knot and after
//! the last the speed is constant. Positions follow this x(t) exactly at every instant (no
//! integration error).

use serde::{Deserialize, Serialize};

/// The direction a vehicle travels along the deck.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum TravelDirection {
    /// Towards increasing x: from the first support to the last.
    #[default]
    Forward,
    /// Towards decreasing x: from the last support to the first (the opposite lane). The
    /// vehicle's left is the deck's right (−y).
    Backward,
}

/// One knot of a piecewise speed profile.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SpeedKnot {
    /// Travel coordinate s of the front axle [m] (distance past the deck entry of the vehicle's
    /// direction; negative on the approach).
    pub travel: f64,
    /// Speed at that point [m/s]; positive.
    pub speed: f64,
}

/// How a vehicle's speed varies along its travel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SpeedProfile {
    /// Constant speed v [m/s]; positive.
    Constant(f64),
    /// Constant acceleration between consecutive knots (v² linear in s), constant speed before
    /// the first knot and after the last. The knots' travel coordinates increase strictly.
    Knots(Vec<SpeedKnot>),
}

impl SpeedProfile {
    /// A constant acceleration a [m/s²] through `[from, to]` (travel coordinates [m]) with the
    /// speed `speed_at_entry` [m/s] at the deck entry s = 0; constant speed outside. Errs with
    /// the travel coordinate where the speed would reach zero inside the interval.
    pub fn constant_acceleration(
        speed_at_entry: f64,
        acceleration: f64,
        from: f64,
        to: f64,
    ) -> Result<SpeedProfile, StopsAt> {
        if acceleration == 0.0 {
            return Ok(SpeedProfile::Constant(speed_at_entry));
        }
        let speed_at = |s: f64| {
            let squared = speed_at_entry * speed_at_entry + 2.0 * acceleration * s;
            (squared > 0.0).then(|| squared.sqrt())
        };
        let stop = -speed_at_entry * speed_at_entry / (2.0 * acceleration);
        match (speed_at(from), speed_at(to)) {
            (Some(first), Some(last)) => Ok(SpeedProfile::Knots(vec![
                SpeedKnot {
                    travel: from,
                    speed: first,
                },
                SpeedKnot {
                    travel: to,
                    speed: last,
                },
            ])),
            _ => Err(StopsAt { travel: stop }),
        }
    }

    /// The largest speed of the profile [m/s].
    pub fn highest_speed(&self) -> f64 {
        match self {
            SpeedProfile::Constant(v) => *v,
            SpeedProfile::Knots(knots) => knots.iter().map(|k| k.speed).fold(0.0, f64::max),
        }
    }

    /// The smallest speed of the profile [m/s].
    pub fn lowest_speed(&self) -> f64 {
        match self {
            SpeedProfile::Constant(v) => *v,
            SpeedProfile::Knots(knots) => {
                knots.iter().map(|k| k.speed).fold(f64::INFINITY, f64::min)
            }
        }
    }
}

/// A constant acceleration under which the vehicle would stop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopsAt {
    /// Travel coordinate where v² = v_e² + 2 a s reaches zero [m].
    pub travel: f64,
}

/// A phase of constant acceleration, from the instant `start_time`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Phase {
    /// Time the phase begins [s].
    start_time: f64,
    /// Travel coordinate at its start [m].
    start_travel: f64,
    /// Speed at its start [m/s].
    start_speed: f64,
    /// Acceleration [m/s²].
    acceleration: f64,
}

/// A profile laid out in time from a start point: the phases of constant acceleration.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TravelLaw {
    /// Travel coordinate s₀ at t = 0 [m].
    start: f64,
    /// Constant speed (one phase, evaluated as s₀ + v t), or the phases in time order.
    constant_speed: Option<f64>,
    phases: Vec<Phase>,
}

impl TravelLaw {
    /// The law of a vehicle whose front axle is at s₀ at t = 0. The knots must increase
    /// strictly with positive speeds (checked by validation before).
    pub(crate) fn new(start: f64, profile: &SpeedProfile) -> TravelLaw {
        let knots = match profile {
            SpeedProfile::Constant(v) => {
                return TravelLaw {
                    start,
                    constant_speed: Some(*v),
                    phases: Vec::new(),
                }
            }
            SpeedProfile::Knots(knots) => knots,
        };
        let mut phases = Vec::new();
        let (mut time, mut travel) = (0.0, start);
        let mut speed = speed_at_travel(knots, start);
        for (i, knot) in knots.iter().enumerate() {
            if knot.travel <= travel {
                continue;
            }
            let acceleration = if i == 0 {
                0.0
            } else {
                let previous = knots[i - 1];
                (knot.speed * knot.speed - previous.speed * previous.speed)
                    / (2.0 * (knot.travel - previous.travel))
            };
            phases.push(Phase {
                start_time: time,
                start_travel: travel,
                start_speed: speed,
                acceleration,
            });
            time += 2.0 * (knot.travel - travel) / (speed + knot.speed);
            travel = knot.travel;
            speed = knot.speed;
        }
        phases.push(Phase {
            start_time: time,
            start_travel: travel,
            start_speed: speed,
            acceleration: 0.0,
        });
        TravelLaw {
            start,
            constant_speed: None,
            phases,
        }
    }

    /// Travel coordinate s(t) [m] and speed v(t) [m/s] at time t ≥ 0.
    pub(crate) fn at(&self, time: f64) -> (f64, f64) {
        if let Some(v) = self.constant_speed {
            return (self.start + v * time, v);
        }
        let p = self.phases[self.phase_at(time)];
        let tau = time - p.start_time;
        (
            p.start_travel + p.start_speed * tau + 0.5 * p.acceleration * tau * tau,
            p.start_speed + p.acceleration * tau,
        )
    }

    /// Longitudinal acceleration s̈(t) [m/s²] at time t ≥ 0: that of the phase running at t (a
    /// phase starting exactly at t counts), 0 at constant speed.
    pub(crate) fn acceleration(&self, time: f64) -> f64 {
        if self.constant_speed.is_some() {
            return 0.0;
        }
        self.phases[self.phase_at(time)].acceleration
    }

    /// The times at which the acceleration may change [s]: the start of every phase (none at
    /// constant speed). Between consecutive ones s(t) is one quadratic.
    pub(crate) fn phase_start_times(&self) -> impl Iterator<Item = f64> + '_ {
        self.phases.iter().map(|p| p.start_time)
    }

    /// Index of the phase running at time t (the last one starting at or before t).
    fn phase_at(&self, time: f64) -> usize {
        self.phases.partition_point(|p| p.start_time <= time).max(1) - 1
    }

    /// The time at which the front axle reaches travel coordinate `travel` (≥ s₀) [s].
    pub(crate) fn time_at_travel(&self, travel: f64) -> f64 {
        if let Some(v) = self.constant_speed {
            return (travel - self.start) / v;
        }
        let index = self
            .phases
            .partition_point(|p| p.start_travel <= travel)
            .max(1)
            - 1;
        let p = self.phases[index];
        let distance = travel - p.start_travel;
        // s = v τ + ½ a τ² solved for the root τ ≥ 0 in its cancellation-free form.
        let root = (p.start_speed * p.start_speed + 2.0 * p.acceleration * distance)
            .max(0.0)
            .sqrt();
        p.start_time + 2.0 * distance / (p.start_speed + root)
    }
}

/// The speed of a knot profile at travel coordinate s [m/s] (v² linear between knots,
/// constant outside).
fn speed_at_travel(knots: &[SpeedKnot], travel: f64) -> f64 {
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    if travel <= first.travel {
        return first.speed;
    }
    if travel >= last.travel {
        return last.speed;
    }
    let i = knots.partition_point(|k| k.travel <= travel);
    let (a, b) = (knots[i - 1], knots[i]);
    let fraction = (travel - a.travel) / (b.travel - a.travel);
    (a.speed * a.speed + fraction * (b.speed * b.speed - a.speed * a.speed)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// s(t) of a constant acceleration from rest-free start, against s₀ + v₀t + ½at² (closed
    /// form of uniformly accelerated motion), and t(s) as its inverse.
    #[test]
    fn constant_acceleration_follows_the_closed_form_of_uniform_acceleration() {
        let profile = SpeedProfile::constant_acceleration(20.0, -2.0, -50.0, 80.0).unwrap();
        let law = TravelLaw::new(-50.0, &profile);
        let v0 = (400.0_f64 + 2.0 * 2.0 * 50.0).sqrt();
        for &t in &[0.0, 0.5, 1.0, 3.0, 5.0] {
            let (s, v) = law.at(t);
            let expected = -50.0 + v0 * t - 0.5 * 2.0 * t * t;
            assert!(
                (s - expected).abs() < 1e-12 * (1.0 + expected.abs()),
                "{s} {expected}"
            );
            assert!((v - (v0 - 2.0 * t)).abs() < 1e-12 * v0);
            assert!((law.time_at_travel(s) - t).abs() < 1e-12 * (1.0 + t));
        }
        // Past the last knot the speed stays at v(80) = sqrt(400 − 320).
        let t_end = law.time_at_travel(80.0);
        let (s, v) = law.at(t_end + 2.0);
        assert!((v - 80.0_f64.sqrt()).abs() < 1e-12 * 10.0);
        assert!((s - (80.0 + 2.0 * 80.0_f64.sqrt())).abs() < 1e-9);
    }

    /// A braking that would stop the vehicle before the end of the interval is refused at the
    /// stopping point s = −v²/(2a).
    #[test]
    fn a_braking_that_stops_the_vehicle_is_refused_where_it_stops() {
        let error = SpeedProfile::constant_acceleration(10.0, -1.0, -20.0, 90.0).unwrap_err();
        assert_eq!(error.travel, 50.0);
    }

    /// Knots: the speed is continuous at every knot and the travel time of a segment is
    /// 2Δs/(v_i + v_{i+1}) (mean speed of uniform acceleration).
    #[test]
    fn knot_profile_is_continuous_and_takes_the_uniform_acceleration_times() {
        let knots = vec![
            SpeedKnot {
                travel: 0.0,
                speed: 20.0,
            },
            SpeedKnot {
                travel: 30.0,
                speed: 10.0,
            },
            SpeedKnot {
                travel: 60.0,
                speed: 15.0,
            },
        ];
        let law = TravelLaw::new(-40.0, &SpeedProfile::Knots(knots));
        let t0 = 40.0 / 20.0;
        let t1 = t0 + 2.0 * 30.0 / 30.0;
        let t2 = t1 + 2.0 * 30.0 / 25.0;
        for (t, s, v) in [(t0, 0.0, 20.0), (t1, 30.0, 10.0), (t2, 60.0, 15.0)] {
            let (s_at, v_at) = law.at(t);
            assert!((s_at - s).abs() < 1e-12 * 100.0, "{t}: {s_at} vs {s}");
            assert!((v_at - v).abs() < 1e-12 * 20.0, "{t}: {v_at} vs {v}");
            assert!((law.time_at_travel(s) - t).abs() < 1e-12 * 10.0);
        }
    }
}
