//! Traffic events and the continuous extreme of their static load effect.
//!
//! An event is a maximal set of trucks whose stays on the deck overlap in time (a truck stays
//! from its front axle's arrival at its entry until its last axle leaves at the other end,
//! [`PlacedTruck::leaves`]): one truck alone, several following or meeting. Between events the
//! deck carries no truck and every static effect is zero.
//!
//! **Continuous extreme.** Axle b of a truck at constant speed v, arriving at t₀, is at travel
//! coordinate s(t) = v (t − t₀) − d_b (d_b: its distance behind the front axle), that is at deck
//! position x = s forward or x = L − s backward. Its contribution w_b η(x(t)) to the effect is
//! piecewise linear in t when the influence line η is piecewise linear in x
//! ([`super::EffectLine`]), with breakpoints at the instants the axle passes a knot. The event's
//! effect E(t) = Σ w_b η(x_b(t)) is a sum of such functions, linear between the union of their
//! breakpoints, so its supremum over all t is attained (as a value or a one-sided limit, at a
//! jump) at one of them: it is the largest of E at the breakpoints, where the axle at the knot
//! takes the better of the line's two one-sided limits there. This is exact for the tabulated
//! line, whatever the time step a sampled maximum would take (PyBTLS samples at a fixed step,
//! so that its maximum lies at or below this one).

use super::EffectLine;
use crate::traffic::{RecordedTruck, TravelDirection};

/// A truck of an event, with what the extreme needs precomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedTruck {
    /// When its front axle reaches its deck entry [s].
    pub arrival: f64,
    /// Speed [m/s].
    pub speed: f64,
    /// Whether it travels towards increasing x.
    pub forward: bool,
    /// Index of its lane in the analysis's lanes (not the record's lane number).
    pub lane: usize,
    /// Each axle's distance behind the front axle [m].
    pub offsets: Vec<f64>,
    /// Each axle's load [N].
    pub loads: Vec<f64>,
    /// When its last axle leaves the deck [s]: t₀ + (L + d_last) / v.
    pub leaves: f64,
}

impl PlacedTruck {
    /// Places a recorded truck in lane index `lane` on a deck of length `deck_length` [m].
    pub fn new(truck: &RecordedTruck, lane: usize, deck_length: f64) -> PlacedTruck {
        let offsets = truck.axle_offsets();
        let last = offsets.last().copied().unwrap_or(0.0);
        PlacedTruck {
            arrival: truck.arrival_time,
            speed: truck.speed,
            forward: truck.direction == TravelDirection::Forward,
            lane,
            offsets,
            loads: truck.axle_loads.clone(),
            leaves: truck.arrival_time + (deck_length + last) / truck.speed,
        }
    }

    /// The truck as a record again, in lane `number` of its direction: the axle spacings are
    /// the differences of the offsets (equal to the record's within a unit in the last place).
    pub fn record(&self, number: usize) -> RecordedTruck {
        RecordedTruck {
            arrival_time: self.arrival,
            lane: number,
            direction: match self.forward {
                true => TravelDirection::Forward,
                false => TravelDirection::Backward,
            },
            speed: self.speed,
            axle_spacings: self.offsets.windows(2).map(|w| w[1] - w[0]).collect(),
            axle_loads: self.loads.clone(),
        }
    }

    /// Deck position of axle b at time t [m].
    #[inline]
    fn axle_position(&self, b: usize, t: f64, deck_length: f64) -> f64 {
        let travel = self.speed * (t - self.arrival) - self.offsets[b];
        if self.forward {
            travel
        } else {
            deck_length - travel
        }
    }

    /// The instant axle b is at deck position x [s].
    #[inline]
    fn time_at(&self, b: usize, x: f64, deck_length: f64) -> f64 {
        let travel = if self.forward { x } else { deck_length - x };
        self.arrival + (travel + self.offsets[b]) / self.speed
    }
}

/// The extreme of one effect over one event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventExtreme {
    /// The effect's value at its extreme, signed (in the effect's unit: N, N·m or m).
    pub value: f64,
    /// When it occurs [s].
    pub time: f64,
}

/// The event's extreme of the effect whose lines (one per lane index) are `lines`, in the sense
/// `sense` (+1: the largest value; −1: the most negative): the supremum of sense × E(t) over all
/// t, exact for the piecewise-linear lines (module doc). `deck_length` is L [m]. An event that
/// never loads the line gives zero, at its first arrival.
pub fn event_extreme(
    trucks: &[PlacedTruck],
    lines: &[EffectLine],
    deck_length: f64,
    sense: f64,
) -> EventExtreme {
    let mut best = EventExtreme {
        value: 0.0,
        time: trucks.first().map_or(0.0, |t| t.arrival),
    };
    let mut best_scaled = 0.0;
    for (i, truck) in trucks.iter().enumerate() {
        let line = &lines[truck.lane];
        for (b, &load) in truck.loads.iter().enumerate() {
            for (k, &x) in line.knots().iter().enumerate() {
                let t = truck.time_at(b, x, deck_length);
                let (left, right) = line.limits(k);
                let at_knot = load
                    * if sense * left > sense * right {
                        left
                    } else {
                        right
                    };
                let value = at_knot + effect_without(trucks, lines, deck_length, t, (i, b));
                if sense * value > best_scaled {
                    best_scaled = sense * value;
                    best = EventExtreme { value, time: t };
                }
            }
        }
    }
    best
}

/// E(t) without the contribution of axle `skip` = (truck, axle).
#[inline]
fn effect_without(
    trucks: &[PlacedTruck],
    lines: &[EffectLine],
    deck_length: f64,
    t: f64,
    skip: (usize, usize),
) -> f64 {
    let mut sum = 0.0;
    for (j, truck) in trucks.iter().enumerate() {
        if t < truck.arrival || t > truck.leaves {
            continue;
        }
        let line = &lines[truck.lane];
        for (b, &load) in truck.loads.iter().enumerate() {
            if (j, b) != skip {
                sum += load * line.ordinate(truck.axle_position(b, t, deck_length));
            }
        }
    }
    sum
}

/// The static effect E(t) of the trucks at time t [s] (every axle on the line's right limit at
/// a knot): for sampled histories and tests.
pub fn effect_at(trucks: &[PlacedTruck], lines: &[EffectLine], deck_length: f64, t: f64) -> f64 {
    effect_without(trucks, lines, deck_length, t, (usize::MAX, usize::MAX))
}

/// Groups a time-ordered stream of placed trucks into events (module doc): calls `on_event`
/// with each event's trucks, in order. Returns the arrival of the first truck that arrives
/// before the one ahead of it, if any (the stream must be ordered by arrival).
pub fn for_each_event(
    trucks: impl IntoIterator<Item = PlacedTruck>,
    mut on_event: impl FnMut(&[PlacedTruck]),
) -> Result<(), OutOfOrder> {
    let mut event: Vec<PlacedTruck> = Vec::new();
    let mut event_ends = f64::NEG_INFINITY;
    let mut last_arrival = f64::NEG_INFINITY;
    for (index, truck) in trucks.into_iter().enumerate() {
        if truck.arrival < last_arrival {
            return Err(OutOfOrder {
                truck: index + 1,
                arrival: truck.arrival,
                previous: last_arrival,
            });
        }
        last_arrival = truck.arrival;
        if truck.arrival > event_ends && !event.is_empty() {
            on_event(&event);
            event.clear();
        }
        event_ends = event_ends.max(truck.leaves);
        event.push(truck);
    }
    if !event.is_empty() {
        on_event(&event);
    }
    Ok(())
}

/// A truck that arrives before the truck ahead of it in the stream.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("truck {truck} arrives at {arrival} s, before the truck ahead of it in the record ({previous} s): the record must be in order of time")]
pub struct OutOfOrder {
    /// The truck's number in the stream, from 1.
    pub truck: usize,
    /// Its arrival [s].
    pub arrival: f64,
    /// The arrival of the truck before it [s].
    pub previous: f64,
}
