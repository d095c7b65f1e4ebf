//! A seeded random traffic stream: vehicles drawn from a mix, entering one lane at random
//! headways with scattered speeds and payloads, as further vehicles of a crossing event.
//!
//! Draws (ChaCha20, [`SampleRng`] stream [`STREAM_INDEX`] of the stream's seed, in this order
//! for each vehicle i = 1…n): the vehicle type (a uniform u against the cumulative weights), the
//! time headway h_i = h_min + E_i with E_i exponential of mean h̄ − h_min (a shifted exponential,
//! the usual model of free-flowing traffic: h_i = h_min − (h̄ − h_min) ln(1 − u)), the speed
//! v_i = v̄ + σ_v z and the load scale λ_i = 1 + σ_λ z′ with z, z′ standard normal (Box–Muller
//! from two uniforms each), each truncated to ±3σ.
//!
//! Placement: the first vehicle's front axle reaches the deck at t₀ (`first_entry`); vehicle
//! i > 1 starts v_i h_i behind the last axle of vehicle i − 1 (its time headway at its own
//! speed). One lane has no overtaking, so a vehicle is never faster than the one ahead of it:
//! v_i = min(v_i drawn, v_{i−1}); gaps then only grow and no two stream vehicles meet. (The
//! speeds of a long stream drift down by this rule; the drawn values are the free speeds.) The
//! load scale multiplies the vehicle's body masses and inertias (its payload; unsprung masses
//! stay), or a moving force's axle loads.

use serde::{Deserialize, Serialize};

use super::{Entry, Motion, TrafficVehicle, TravelDirection};
use crate::road::SampleRng;
use crate::vehicle::{VehicleDescription, VehicleSpec};

/// The ChaCha20 stream of a traffic seed that the draws use (road samples use streams 0, 1, …).
pub const STREAM_INDEX: u64 = u64::MAX - 1;

/// One vehicle type of a stream's mix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MixEntry {
    /// How the input named it.
    pub label: String,
    /// The vehicle.
    pub vehicle: VehicleSpec,
    /// Relative frequency [-]; positive.
    pub weight: f64,
}

/// A random stream of vehicles in one lane.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrafficStream {
    /// Number of vehicles drawn.
    pub vehicle_count: usize,
    /// The vehicle types and their weights; at least one.
    pub mix: Vec<MixEntry>,
    /// Mean time headway h̄ between successive entries [s].
    pub mean_headway: f64,
    /// Smallest headway h_min [s]; below the mean.
    pub minimum_headway: f64,
    /// Time t₀ at which the first stream vehicle's front axle reaches the deck [s]. It must not
    /// catch up with a vehicle listed before the stream in the same lane: choose t₀ so.
    pub first_entry: f64,
    /// Mean speed v̄ [m/s].
    pub mean_speed: f64,
    /// Standard deviation of the speed σ_v [m/s].
    pub speed_deviation: f64,
    /// Standard deviation of the load scale σ_λ [-].
    pub load_scale_deviation: f64,
    /// Lateral position of the lane [m] (deck coordinates).
    pub lateral_position: f64,
    /// Direction of the lane.
    pub direction: TravelDirection,
    /// Seed of the draws; None: the road's seed (so that every case of a Monte Carlo study,
    /// which varies the road seed, draws its own traffic).
    pub seed: Option<u64>,
}

/// Why a stream cannot be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("traffic stream: {0}")]
pub struct StreamError(pub String);

impl TrafficStream {
    /// Checks the numbers: a non-empty mix of positive weights, 0 ≤ h_min < h̄, t₀ ≥ 0, a mean
    /// speed whose −3σ truncation stays positive, σ_λ < 1/3 (a load scale above 0).
    pub fn validate(&self) -> Result<(), StreamError> {
        let fail = |m: &str| Err(StreamError(m.to_string()));
        if self.mix.is_empty()
            || self
                .mix
                .iter()
                .any(|m| !(m.weight > 0.0 && m.weight.is_finite()))
        {
            return fail("the mix needs at least one vehicle, each with a positive weight");
        }
        if !(self.minimum_headway >= 0.0
            && self.minimum_headway < self.mean_headway
            && self.mean_headway.is_finite())
        {
            return fail("the headways need 0 <= minimum_headway_s < mean_headway_s");
        }
        if !(self.first_entry >= 0.0 && self.first_entry.is_finite()) {
            return fail("first_entry_s must be a finite time >= 0");
        }
        if !(self.speed_deviation >= 0.0 && self.mean_speed - 3.0 * self.speed_deviation > 0.0) {
            return fail("the speed's mean minus three standard deviations must stay positive");
        }
        if !(self.load_scale_deviation >= 0.0 && self.load_scale_deviation < 1.0 / 3.0) {
            return fail("load_scale_sd must lie from 0 to below 1/3 (the scale stays above 0)");
        }
        Ok(())
    }

    /// The stream's vehicles, as further vehicles entering at their times, drawn with the
    /// stream's seed or else `road_seed`.
    pub fn draw(&self, road_seed: u64) -> Result<Vec<TrafficVehicle>, StreamError> {
        self.validate()?;
        let mut rng = SampleRng::new(self.seed.unwrap_or(road_seed), STREAM_INDEX);
        let total: f64 = self.mix.iter().map(|m| m.weight).sum();
        let mut vehicles = Vec::with_capacity(self.vehicle_count);
        let mut ahead_speed = f64::INFINITY;
        for i in 0..self.vehicle_count {
            let pick = rng.next_unit() * total;
            let mut cumulative = 0.0;
            let kind = self
                .mix
                .iter()
                .find(|m| {
                    cumulative += m.weight;
                    pick < cumulative
                })
                .unwrap_or(&self.mix[self.mix.len() - 1]);
            let spread = self.mean_headway - self.minimum_headway;
            let headway = self.minimum_headway - spread * (1.0 - rng.next_unit()).ln();
            let free_speed = self.mean_speed + self.speed_deviation * truncated_normal(&mut rng);
            let scale = 1.0 + self.load_scale_deviation * truncated_normal(&mut rng);
            let speed = free_speed.min(ahead_speed);
            ahead_speed = speed;
            let entry = match i {
                0 => Entry::Time(self.first_entry),
                _ => Entry::Gap(speed * headway),
            };
            vehicles.push(TrafficVehicle {
                label: format!("{} (stream vehicle {})", kind.label, i + 1),
                vehicle: scaled_payload(&kind.vehicle, scale),
                motion: Motion {
                    direction: self.direction,
                    ..Motion::constant(speed, self.lateral_position)
                },
                entry,
            });
        }
        Ok(vehicles)
    }
}

/// A standard normal deviate by Box–Muller, truncated to ±3.
fn truncated_normal(rng: &mut SampleRng) -> f64 {
    let (u1, u2) = (1.0 - rng.next_unit(), rng.next_unit());
    let z = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
    z.clamp(-3.0, 3.0)
}

/// The vehicle with its body masses and inertias (or its moving forces) times `scale`.
pub fn scaled_payload(vehicle: &VehicleSpec, scale: f64) -> VehicleSpec {
    let mut scaled = vehicle.clone();
    match &mut scaled.description {
        VehicleDescription::MovingForces(forces) => {
            for force in forces {
                force.axle_load *= scale;
            }
        }
        VehicleDescription::Multibody(model) => {
            for body in &mut model.bodies {
                body.mass *= scale;
                body.roll_inertia *= scale;
                if let Some(pitch) = &mut body.pitch_inertia {
                    *pitch *= scale;
                }
            }
        }
    }
    scaled
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vehicle::preset;

    fn stream(count: usize) -> TrafficStream {
        TrafficStream {
            vehicle_count: count,
            mix: vec![
                MixEntry {
                    label: "truck".into(),
                    vehicle: preset("tractor-semitrailer-5axle").unwrap(),
                    weight: 3.0,
                },
                MixEntry {
                    label: "car".into(),
                    vehicle: preset("quarter-car").unwrap(),
                    weight: 1.0,
                },
            ],
            mean_headway: 3.0,
            minimum_headway: 1.0,
            first_entry: 5.0,
            mean_speed: 22.0,
            speed_deviation: 2.0,
            load_scale_deviation: 0.1,
            lateral_position: 1.8,
            direction: TravelDirection::Forward,
            seed: Some(7),
        }
    }

    /// Over 20000 draws the sample statistics match the distributions' parameters (mean
    /// headway h̄, mix fraction 3/4, load-scale mean 1) within four standard errors; every
    /// headway is at least h_min; speeds never rise along the stream (no overtaking); the same
    /// seed draws the same stream bit for bit.
    #[test]
    fn the_stream_draws_the_distributions_it_names_and_is_reproducible() {
        let count = 20_000;
        let drawn = stream(count).draw(1).unwrap();
        assert_eq!(
            drawn,
            stream(count).draw(99).unwrap(),
            "its own seed, not the road's"
        );
        assert_eq!(drawn[0].entry, Entry::Time(5.0));
        let headways: Vec<f64> = drawn[1..]
            .iter()
            .map(|v| match v.entry {
                Entry::Gap(gap) => gap / v.motion.speed,
                Entry::Time(_) => unreachable!(),
            })
            .collect();
        assert!(headways.iter().all(|&h| h >= 1.0 - 1e-12));
        let n = headways.len() as f64;
        let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
        // Exponential part: standard deviation h̄ − h_min = 2 s.
        assert!((mean(&headways) - 3.0).abs() < 4.0 * 2.0 / n.sqrt());
        let trucks = drawn
            .iter()
            .filter(|v| v.label.starts_with("truck"))
            .count() as f64;
        let all = drawn.len() as f64;
        assert!((trucks / all - 0.75).abs() < 4.0 * (0.75_f64 * 0.25 / all).sqrt());
        assert!(drawn
            .windows(2)
            .all(|w| w[1].motion.speed <= w[0].motion.speed));
        let base = match &preset("quarter-car").unwrap().description {
            VehicleDescription::Multibody(m) => m.bodies[0].mass,
            VehicleDescription::MovingForces(_) => unreachable!(),
        };
        let scales: Vec<f64> = drawn
            .iter()
            .filter(|v| v.label.starts_with("car"))
            .map(|v| match &v.vehicle.description {
                VehicleDescription::Multibody(m) => m.bodies[0].mass / base,
                VehicleDescription::MovingForces(_) => unreachable!(),
            })
            .collect();
        let cars = scales.len() as f64;
        assert!((mean(&scales) - 1.0).abs() < 4.0 * 0.1 / cars.sqrt());
    }

    /// The free speeds drawn follow v̄ and σ_v: the first vehicle's speed is its free speed, so
    /// 4000 one-vehicle streams of different seeds sample the speed distribution.
    #[test]
    fn the_free_speeds_have_the_mean_and_deviation_asked_for() {
        let speeds: Vec<f64> = (0..4000)
            .map(|seed| {
                let mut s = stream(1);
                s.seed = Some(seed);
                s.draw(0).unwrap()[0].motion.speed
            })
            .collect();
        let n = speeds.len() as f64;
        let mean = speeds.iter().sum::<f64>() / n;
        let sd = (speeds.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        assert!((mean - 22.0).abs() < 4.0 * 2.0 / n.sqrt(), "{mean}");
        // Truncation at ±3σ lowers σ by 1.5 %; the sampling error of σ is σ/√(2n) = 1.1 %.
        assert!((sd - 2.0).abs() < 0.1, "{sd}");
    }

    /// Without its own seed the stream follows the road's seed.
    #[test]
    fn without_a_seed_the_stream_follows_the_road_seed() {
        let mut s = stream(5);
        s.seed = None;
        assert_ne!(s.draw(1).unwrap(), s.draw(2).unwrap());
        assert_eq!(s.draw(3).unwrap(), s.draw(3).unwrap());
    }
}
