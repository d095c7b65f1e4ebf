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

    /// The coarse bound of effect `effect` under `trucks` (module doc): the extreme on the
    /// coarse lines plus δ times the weight, with the rounding slack of [`Self::bound`].
    pub fn coarse_bound(&self, effect: usize, trucks: &[PlacedTruck]) -> f64 {
        let (lines, deviations) = &self.coarse[effect];
        let sense = self.senses[effect];
        let coarse = event_extreme(trucks, lines, self.deck_length, sense);
        let (mut deviation, mut magnitude, mut axles) = (0.0, 0.0, 0usize);
        for truck in trucks {
            let weight: f64 = truck.loads.iter().sum();
            deviation += weight * deviations[truck.lane];
            magnitude += weight * self.ordinates[effect][truck.lane].1;
            axles += truck.loads.len();
        }
        sense * coarse.value + deviation + 4.0 * (axles as f64 + 1.0) * f64::EPSILON * magnitude
    }

    /// An upper bound of s E(t) over all t for effect `effect` under `trucks` (module doc):
    /// at least the magnitude [`super::event::event_extreme`] computes, and 0 when no truck
    /// can load the effect in its sense.
    pub fn bound(&self, effect: usize, trucks: &[PlacedTruck]) -> f64 {
        let lanes = &self.ordinates[effect];
        let (mut bound, mut magnitude, mut axles) = (0.0, 0.0, 0usize);
        for truck in trucks {
            let weight: f64 = truck.loads.iter().sum();
            let (largest, largest_magnitude) = lanes[truck.lane];
            bound += weight * largest;
            magnitude += weight * largest_magnitude;
            axles += truck.loads.len();
        }
        if bound == 0.0 {
            return 0.0;
        }
        bound + 2.0 * (axles as f64 + 1.0) * f64::EPSILON * magnitude
    }
}
