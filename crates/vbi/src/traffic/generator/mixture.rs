//! Bounded mixtures of normal distributions, the building block of the Grave vehicle model
//! (Grave 2001; BTLS's "multi-modal normal", `cpp/src/Distribution.cpp:200-217`), and the one
//! normal sampler of the generator.

use serde::{Deserialize, Serialize};

use super::GeneratorError;
use crate::road::SampleRng;

/// The most draws of a bounded sample: BTLS redraws until the value falls inside its bounds,
/// without end; vbi stops after this many draws and clamps the last one into the bounds (a
/// distribution that almost never reaches its bounds then gives its nearest bound, instead of
/// hanging the run).
pub const MAX_REDRAWS: usize = 10_000;

/// Tolerance on the sum of a mixture's weights: parameter files give weights to 3 decimals, so
/// a sum of 0.999 or 1.001 is their rounding of 1.
pub const MIXTURE_WEIGHT_TOLERANCE: f64 = 0.01;

/// The most modes of a mixture (BTLS's files hold three).
pub const MAX_MODES: usize = 3;

/// A standard normal deviate z by the Box–Muller transform (Box & Muller 1958), from two
/// uniforms u₁, u₂ of the lane's stream: z = √(−2 ln(1 − u₁)) cos(2π u₂). Exactly two draws
/// each time (the sine partner is not kept), so that every vehicle consumes a fixed number of
/// draws per normal and the stream stays in step whatever the values.
pub fn standard_normal(rng: &mut SampleRng) -> f64 {
    let u1 = 1.0 - rng.next_unit();
    let u2 = rng.next_unit();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// A sample of `draw` inside [lower, upper]: redrawn until inside, at most [`MAX_REDRAWS`]
/// times, then the last draw clamped into the bounds.
pub(crate) fn bounded_draw(
    rng: &mut SampleRng,
    lower: f64,
    upper: f64,
    mut draw: impl FnMut(&mut SampleRng) -> f64,
) -> f64 {
    let mut value = f64::NAN;
    for _ in 0..MAX_REDRAWS {
        value = draw(rng);
        if value >= lower && value <= upper {
            return value;
        }
    }
    if value.is_nan() {
        lower
    } else {
        value.clamp(lower, upper)
    }
}

/// One normal mode of a mixture, in the unit of the quantity it describes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NormalMode {
    /// Probability w of the mode [-]; positive.
    pub weight: f64,
    /// Mean μ of the mode (the quantity's unit).
    pub mean: f64,
    /// Standard deviation σ of the mode (the quantity's unit); zero or positive.
    pub standard_deviation: f64,
}

/// A mixture of up to three normal modes with bounds: density
/// f(x) = Σ_k w_k φ((x − μ_k)/σ_k)/σ_k, restricted to [lower_bound, upper_bound] by redrawing.
///
/// A sample draws u uniform, picks the first mode k with u·W < w₁ + … + w_k (W the weights'
/// sum), then x = μ_k + σ_k z with z standard normal ([`standard_normal`]); the whole draw
/// (mode and value) is repeated until x lies inside the bounds, at most [`MAX_REDRAWS`] times,
/// then clamped into them. Three draws per attempt. (BTLS walks the raw weights and clamps to the
/// last mode when they sum to less than u, `Distribution.cpp:200-217`; vbi scales u by W, so that
/// weights rounded to 0.999 never pick a mode of weight 0.)
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NormalMixture {
    /// The modes, 1 to [`MAX_MODES`], each of positive weight; the weights sum to 1 within
    /// [`MIXTURE_WEIGHT_TOLERANCE`].
    pub modes: Vec<NormalMode>,
    /// Smallest value accepted (the quantity's unit).
    pub lower_bound: f64,
    /// Largest value accepted (the quantity's unit); above the lower bound.
    pub upper_bound: f64,
}

impl NormalMixture {
    /// A single normal N(μ, σ²) restricted to [lower, upper].
    pub fn single(mean: f64, standard_deviation: f64, lower: f64, upper: f64) -> NormalMixture {
        NormalMixture {
            modes: vec![NormalMode {
                weight: 1.0,
                mean,
                standard_deviation,
            }],
            lower_bound: lower,
            upper_bound: upper,
        }
    }

    /// What is wrong with the mixture, named `field`: 1 to 3 modes, positive finite weights
    /// summing to 1 within [`MIXTURE_WEIGHT_TOLERANCE`], finite means, finite non-negative
    /// standard deviations, finite bounds with lower < upper.
    pub fn check(&self, field: &str) -> Result<(), GeneratorError> {
        let fail =
            |sub: &str, message: String| Err(GeneratorError::new(format!("{field}{sub}"), message));
        if self.modes.is_empty() || self.modes.len() > MAX_MODES {
            return fail(
                ".modes",
                format!(
                    "a mixture needs 1 to {MAX_MODES} modes of positive weight, got {}",
                    self.modes.len()
                ),
            );
        }
        for (k, mode) in self.modes.iter().enumerate() {
            if !(mode.weight.is_finite() && mode.weight > 0.0) {
                return fail(
                    &format!(".modes[{k}].weight"),
                    format!("a mode's weight must be positive, got {}", mode.weight),
                );
            }
            if !mode.mean.is_finite() {
                return fail(
                    &format!(".modes[{k}].mean"),
                    format!("a mode's mean must be finite, got {}", mode.mean),
                );
            }
            let sd = mode.standard_deviation;
            if !(sd.is_finite() && sd >= 0.0) {
                return fail(
                    &format!(".modes[{k}].standard_deviation"),
                    format!("a standard deviation must be zero or positive, got {sd}"),
                );
            }
        }
        let total: f64 = self.modes.iter().map(|m| m.weight).sum();
        if (total - 1.0).abs() > MIXTURE_WEIGHT_TOLERANCE {
            return fail(
                ".modes",
                format!("the modes' weights must sum to 1 (within {MIXTURE_WEIGHT_TOLERANCE}), got {total}"),
            );
        }
        if !(self.lower_bound.is_finite()
            && self.upper_bound.is_finite()
            && self.lower_bound < self.upper_bound)
        {
            return fail(
                ".lower_bound",
                format!(
                    "the bounds must be finite with lower < upper, got [{}, {}]",
                    self.lower_bound, self.upper_bound
                ),
            );
        }
        Ok(())
    }

    /// One draw of the mixture without the bounds: the mode (one uniform), then its normal.
    fn draw_unbounded(&self, rng: &mut SampleRng) -> f64 {
        let total: f64 = self.modes.iter().map(|m| m.weight).sum();
        let pick = rng.next_unit() * total;
        let mut cumulative = 0.0;
        let mode = self
            .modes
            .iter()
            .find(|m| {
                cumulative += m.weight;
                pick < cumulative
            })
            .or(self.modes.last());
        let z = standard_normal(rng);
        mode.map_or(f64::NAN, |m| m.mean + m.standard_deviation * z)
    }

    /// A sample inside the bounds (see the type's description).
    pub fn sample(&self, rng: &mut SampleRng) -> f64 {
        bounded_draw(rng, self.lower_bound, self.upper_bound, |rng| {
            self.draw_unbounded(rng)
        })
    }
}
