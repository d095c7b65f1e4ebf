//! An upper bound of an event's static extreme that costs one multiplication a truck, so that
//! the continuous extreme ([`super::event::event_extreme`], O(A² K) for A axles and K knots)
//! is computed only for the events that can change something: a block maximum, a peak kept for
//! the peaks-over-threshold fit, or the screening of the dynamics. The outputs are those of
//! computing every event's extreme, bit for bit: an event left out could not have changed them.
//!
//! **The bound.** With η⁺ = max(0, maxₓ s η(x)) the largest ordinate of the truck's lane's line
//! in the effect's sense s, and every axle load w ≥ 0,
//!
//!   s E(t) = Σ_b w_b s η(x_b(t)) ≤ Σ_trucks W η⁺,   W the truck's gross weight,
//!
//! at every t. The extreme is evaluated in floating point as a sum of A products, whose
//! rounding error is at most about A u Σ_b w_b |η(x_b)| (u = 2⁻⁵³; Higham 2002, *Accuracy and
//! Stability of Numerical Algorithms*, §4.2); the bound adds 2 (A + 1) ε Σ W |η|max to cover
//! it, so that a computed extreme never exceeds its bound.
//!
//! **The coarse bound.** An event that passes the first test (a heavy truck, several on the
//! deck) gets a second, tight one: its extreme on each line simplified to within
//! [`COARSE_TOLERANCE`] of its largest ordinate ([`EffectLine::simplified`]: a tenth of the
//! knots or fewer, so a tenth of the cost), plus that tolerance times the event's weight.
//! With |η − η̃| ≤ δ everywhere, s E(t) ≤ s Ẽ(t) + δ Σ w_b, so that bound lies within about
//! 2 δ of the exact extreme, and only the events near a running maximum get the exact one.

use super::event::{event_extreme, PlacedTruck};
use super::{EffectLine, StaticLifetime};

/// The coarse lines' tolerance: 1 % of each line's largest ordinate. Smaller keeps more knots
/// (a smooth line's knots grow as 1/√δ); larger lets more events through to the exact extreme.
pub const COARSE_TOLERANCE: f64 = 0.01;

/// Each effect's largest ordinate in its sense and largest magnitude, per lane, and its
/// coarse lines.
#[derive(Debug, Clone, PartialEq)]
pub struct ExtremeBounds {
    /// Per effect and lane: (η⁺, max |η|) [effect unit per N].
    ordinates: Vec<Vec<(f64, f64)>>,
    /// Per effect: each lane's line simplified to within δ, and δ [effect unit per N].
    pub(super) coarse: Vec<(Vec<EffectLine>, Vec<f64>)>,
    /// The deck length L [m].
    deck_length: f64,
    /// Per effect: its sense.
    senses: Vec<f64>,
}

impl ExtremeBounds {
    /// The bounds of every effect of `analysis`.
    pub fn new(analysis: &StaticLifetime) -> ExtremeBounds {
        let ordinates = (analysis.effects.iter())
            .map(|effect| {
                (effect.lines.iter())
                    .map(|line| {
                        let (low, high) = line.ordinate_range();
                        let largest = (effect.sense * low).max(effect.sense * high).max(0.0);
                        (largest, (-low).max(high))
                    })
                    .collect()
            })
            .collect();
        let coarse = (analysis.effects.iter())
            .map(|effect| {
                let lines: Vec<EffectLine> = (effect.lines.iter())
                    .map(|line| line.simplified(COARSE_TOLERANCE))
                    .collect();
                let deviations = (effect.lines.iter())
                    .map(|line| COARSE_TOLERANCE * line.dominant_ordinate().abs())
                    .collect();
                (lines, deviations)
            })
            .collect();
        ExtremeBounds {
            ordinates,
            coarse,
            deck_length: analysis.deck_length,
            senses: analysis.effects.iter().map(|e| e.sense).collect(),
        }
    }

    /// Whether effect e's extreme under `trucks` (a magnitude in its sense) may reach `level`:
    /// both bounds positive and at least `level`, the cheap one first. When not, it cannot, and
    /// the extreme need not be computed.
    pub fn may_reach(&self, effect: usize, trucks: &[PlacedTruck], level: f64) -> bool {
        let reaches = |bound: f64| bound > 0.0 && bound >= level;
        let sums = self.sums(effect, trucks);
        reaches(sums.bound()) && reaches(self.coarse_with(effect, trucks, &sums))
    }

    /// An upper bound of s E(t) over all t for effect `effect` under `trucks` (module doc):
    /// at least the magnitude [`super::event::event_extreme`] computes, and 0 when no truck
    /// can load the effect in its sense.
    pub fn bound(&self, effect: usize, trucks: &[PlacedTruck]) -> f64 {
        self.sums(effect, trucks).bound()
    }

    /// The coarse bound of effect `effect` under `trucks` (module doc): the extreme on the
    /// coarse lines plus δ times the weight, with twice the rounding slack of [`Self::bound`]
    /// (the coarse extreme's rounding and the exact one's).
    pub fn coarse_bound(&self, effect: usize, trucks: &[PlacedTruck]) -> f64 {
        self.coarse_with(effect, trucks, &self.sums(effect, trucks))
    }

    /// [`Self::coarse_bound`] with the event's sums already taken.
    fn coarse_with(&self, effect: usize, trucks: &[PlacedTruck], sums: &Sums) -> f64 {
        let (lines, _) = &self.coarse[effect];
        let sense = self.senses[effect];
        let coarse = event_extreme(trucks, lines, self.deck_length, sense);
        sense * coarse.value + sums.deviation + 2.0 * sums.slack()
    }

    /// The weighted sums both bounds need, one pass over the trucks.
    fn sums(&self, effect: usize, trucks: &[PlacedTruck]) -> Sums {
        let lanes = &self.ordinates[effect];
        let deviations = &self.coarse[effect].1;
        let mut sums = Sums::default();
        for truck in trucks {
            let (largest, largest_magnitude) = lanes[truck.lane];
            sums.largest += truck.weight * largest;
            sums.magnitude += truck.weight * largest_magnitude;
            sums.deviation += truck.weight * deviations[truck.lane];
            sums.axles += truck.loads.len();
        }
        sums
    }
}

/// An event's weights summed against one effect's lines: Σ W η⁺, Σ W |η|max, Σ W δ [the
/// effect's unit], and its axles.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Sums {
    largest: f64,
    magnitude: f64,
    deviation: f64,
    axles: usize,
}

impl Sums {
    /// The rounding slack 2 (A + 1) ε Σ W |η|max (module doc).
    fn slack(&self) -> f64 {
        2.0 * (self.axles as f64 + 1.0) * f64::EPSILON * self.magnitude
    }

    /// The first bound: Σ W η⁺ and its slack, 0 when no truck can load the effect.
    fn bound(&self) -> f64 {
        match self.largest == 0.0 {
            true => 0.0,
            false => self.largest + self.slack(),
        }
    }
}
