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
    /// Its gross weight, the sum of `loads` [N].
    pub weight: f64,
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
            weight: truck.axle_loads.iter().sum(),
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

    /// The instant axle b is at deck position x, counted from `origin` [s]: the arrival less
    /// the origin (both on the record's clock; an event's own first arrival loses no digits to
    /// a record decades long) plus the travel time.
    #[inline]
    fn time_after(&self, origin: f64, b: usize, x: f64, deck_length: f64) -> f64 {
        let travel = if self.forward { x } else { deck_length - x };
        (self.arrival - origin) + (travel + self.offsets[b]) / self.speed
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
/// t, exact for the piecewise-linear lines (module doc) to rounding. `deck_length` is L [m]. An
/// event that never loads the line gives zero, at its first arrival.
///
/// **Sweep.** The breakpoints are visited in time order, each axle's in the order it passes
/// its line's knots, so that E stays a sum of linear pieces: between breakpoints E(t) = E₀ +
/// S (t − t₀), S the sum of the axles' slopes; at an axle's breakpoint its piece changes (and
/// E jumps by w × the line's jump there). E is evaluated on both sides of each breakpoint,
/// E(t⁻) and E(t⁺) (several axles at one instant are taken together), and each axle's drifted
/// piece is replaced by its exact limit at its own breakpoints, so that rounding does not
/// accumulate past one piece. Cost O(B × a), B = Σ axles × knots the breakpoints and a the axles
/// on the deck at once, against O(B × A) for evaluating E afresh at each
/// ([`event_extreme_at_breakpoints`], the reference it is tested against).
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
    let mut sweep = Sweep::new(trucks, lines, deck_length);
    let mut best_scaled = 0.0;
    while let Some((time, left, right)) = sweep.next_breakpoint() {
        for value in [left, right] {
            if sense * value > best_scaled {
                best_scaled = sense * value;
                best = EventExtreme {
                    value,
                    time: sweep.origin + time,
                };
            }
        }
    }
    best
}

/// One axle's piece of E in the sweep of [`event_extreme`].
#[derive(Debug, Clone, Copy)]
struct AxlePiece {
    /// Its truck and axle.
    truck: usize,
    axle: usize,
    /// The next breakpoint, counted in time order (0 = the first knot it reaches).
    next: usize,
    /// Its next breakpoint's time [s].
    next_time: f64,
    /// Its contribution at `start` (right-in-time limit) and its slope [unit/s].
    value: f64,
    slope: f64,
    start: f64,
}

/// The state of the sweep: the axles not yet on the line (by arrival), those on it, and E.
/// Times are counted from the first truck's arrival (`origin`), so that a record decades long
/// loses no digits in the pieces' time differences.
struct Sweep<'a> {
    origin: f64,
    trucks: &'a [PlacedTruck],
    lines: &'a [EffectLine],
    deck_length: f64,
    /// Axles in order of their first breakpoint, and how many have started.
    waiting: Vec<AxlePiece>,
    started: usize,
    active: Vec<AxlePiece>,
    /// E at `time` (right limit) and the sum of the active axles' slopes.
    effect: f64,
    slope: f64,
    time: f64,
}

impl<'a> Sweep<'a> {
    fn new(trucks: &'a [PlacedTruck], lines: &'a [EffectLine], deck_length: f64) -> Sweep<'a> {
        let origin = trucks.first().map_or(0.0, |t| t.arrival);
        let mut waiting = Vec::new();
        for (i, truck) in trucks.iter().enumerate() {
            let line = &lines[truck.lane];
            for (b, &load) in truck.loads.iter().enumerate() {
                if load == 0.0 {
                    continue;
                }
                let first = knot_in_time_order(truck, line, 0);
                waiting.push(AxlePiece {
                    truck: i,
                    axle: b,
                    next: 0,
                    next_time: truck.time_after(origin, b, line.knots()[first], deck_length),
                    value: 0.0,
                    slope: 0.0,
                    start: 0.0,
                });
            }
        }
        waiting.sort_by(|a, b| a.next_time.total_cmp(&b.next_time));
        Sweep {
            origin,
            trucks,
            lines,
            deck_length,
            waiting,
            started: 0,
            active: Vec::new(),
            effect: 0.0,
            slope: 0.0,
            time: f64::NEG_INFINITY,
        }
    }

    /// The next breakpoint's time and E just before and just after it; None after the last.
    fn next_breakpoint(&mut self) -> Option<(f64, f64, f64)> {
        let waiting_next = self.waiting.get(self.started).map(|a| a.next_time);
        let active_next = (self.active.iter()).map(|a| a.next_time).reduce(f64::min);
        let time = match (waiting_next, active_next) {
            (None, None) => return None,
            (Some(w), None) => w,
            (None, Some(a)) => a,
            (Some(w), Some(a)) => w.min(a),
        };
        while self
            .waiting
            .get(self.started)
            .is_some_and(|a| a.next_time == time)
        {
            self.active.push(self.waiting[self.started]);
            self.started += 1;
        }
        // (A zero slope adds nothing, and keeps the first breakpoint's −∞ start out.)
        let mut left = match self.slope == 0.0 {
            true => self.effect,
            false => self.effect + self.slope * (time - self.time),
        };
        // Every axle at a breakpoint now: its drifted piece replaced by its exact left limit,
        // then its jump and its next piece.
        let (mut jump, mut settle) = (0.0, 0.0);
        let mut k = 0;
        while k < self.active.len() {
            if self.active[k].next_time != time {
                k += 1;
                continue;
            }
            let piece = self.active[k];
            let truck = &self.trucks[piece.truck];
            let line = &self.lines[truck.lane];
            let load = truck.loads[piece.axle];
            let knot = knot_in_time_order(truck, line, piece.next);
            let (before, after) = line.limits(knot);
            let (from_left, to_right) = match truck.forward {
                true => (before, after),
                false => (after, before),
            };
            let drifted = piece.value + piece.slope * (time - piece.start);
            left += load * from_left - if piece.next == 0 { 0.0 } else { drifted };
            jump += load * (to_right - from_left);
            self.slope -= piece.slope;
            let next = piece.next + 1;
            if next == line.knots().len() {
                // Off the line after its last knot: its right limit there, then nothing.
                settle -= load * to_right;
                self.active.swap_remove(k);
                continue;
            }
            let next_knot = knot_in_time_order(truck, line, next);
            let x = line.knots()[next_knot];
            let next_time = truck.time_after(self.origin, piece.axle, x, self.deck_length);
            let (next_before, next_after) = line.limits(next_knot);
            let next_from_left = if truck.forward {
                next_before
            } else {
                next_after
            };
            let value = load * to_right;
            let slope = (load * next_from_left - value) / (next_time - time);
            self.slope += slope;
            self.active[k] = AxlePiece {
                next,
                next_time,
                value,
                slope,
                start: time,
                ..piece
            };
            k += 1;
        }
        let right = left + jump;
        self.effect = right + settle;
        if self.active.is_empty() {
            // No axle on the line: exactly zero, whatever rounding the pieces left.
            (self.effect, self.slope) = (0.0, 0.0);
        }
        self.time = time;
        Some((time, left, right))
    }
}

/// The knot an axle of `truck` reaches j-th: the j-th from the start of the line forward, from
/// its end backward.
#[inline]
fn knot_in_time_order(truck: &PlacedTruck, line: &EffectLine, j: usize) -> usize {
    match truck.forward {
        true => j,
        false => line.knots().len() - 1 - j,
    }
}

/// [`event_extreme`] by evaluating E afresh at every breakpoint (the axle at its knot taking
/// the better of the line's two limits, every other axle its ordinate there): O(B × A), the
/// reference the sweep is tested against.
#[cfg(test)]
pub fn event_extreme_at_breakpoints(
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
                let t = truck.time_after(0.0, b, x, deck_length);
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

/// The event's static effect history at its breakpoints, in time order, from zero and back to
/// zero: at each instant an axle passes a knot, E just before and just after it (the axle on
/// the one-sided limit of the side it comes from, then of the side it goes to; one value where
/// the line is continuous). E is linear between consecutive breakpoints (module doc), so every
/// peak and valley of the continuous history is among these values, and rainflow counting them
/// counts the continuous history (ASTM E1049 reads reversals only). Where two axles pass knots
/// at the same instant, the others read their right limits there. Cost: O(B × A) for B
/// breakpoints and A axles.
pub fn event_history_at_breakpoints(
    trucks: &[PlacedTruck],
    lines: &[EffectLine],
    deck_length: f64,
) -> Vec<f64> {
    let mut breakpoints: Vec<(f64, usize, usize, usize)> = Vec::new();
    for (i, truck) in trucks.iter().enumerate() {
        let line = &lines[truck.lane];
        for b in 0..truck.loads.len() {
            for k in 0..line.knots().len() {
                let t = truck.time_after(0.0, b, line.knots()[k], deck_length);
                breakpoints.push((t, i, b, k));
            }
        }
    }
    breakpoints.sort_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then((a.1, a.2, a.3).cmp(&(b.1, b.2, b.3)))
    });
    let mut history = Vec::with_capacity(2 * breakpoints.len() + 2);
    history.push(0.0);
    for (t, i, b, k) in breakpoints {
        let truck = &trucks[i];
        let (left, right) = lines[truck.lane].limits(k);
        let (from, to) = match truck.forward {
            true => (left, right),
            false => (right, left),
        };
        let others = effect_without(trucks, lines, deck_length, t, (i, b));
        let load = truck.loads[b];
        history.push(others + load * from);
        if to != from {
            history.push(others + load * to);
        }
    }
    history.push(0.0);
    history
}

/// The static effect E(t) of the trucks at time t [s] (every axle on the line's right limit at
/// a knot): for sampled histories and tests.
pub fn effect_at(trucks: &[PlacedTruck], lines: &[EffectLine], deck_length: f64, t: f64) -> f64 {
    effect_without(trucks, lines, deck_length, t, (usize::MAX, usize::MAX))
}

/// When the event's last truck leaves the deck [s].
pub fn last_departure(trucks: &[PlacedTruck]) -> f64 {
    trucks.iter().map(|t| t.leaves).fold(f64::MIN, f64::max)
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
