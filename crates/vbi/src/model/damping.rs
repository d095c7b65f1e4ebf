//! Damping laws other than one modal damping ratio for every mode: a ratio per mode, or Rayleigh
//! damping fitted to two ratios at two frequencies.
//!
//! The modes are numbered as `vbi modes` lists them: the retained modes (after the modal
//! options' `keep_kinds` filter) in ascending frequency, the first being mode 1.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::{require_damping, ModelError};

/// A damping law that gives each retained mode its own ratio; a bridge without one gives every
/// mode its `damping_ratio`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "law")]
pub enum ModeDamping {
    /// ζ_k of the k-th retained mode [-], k from 1 in ascending frequency; modes beyond the list
    /// take its last value. At least one ratio, each in [0, 1).
    PerMode {
        /// The ratios, mode 1 first [-].
        ratios: Vec<f64>,
    },
    /// Rayleigh damping C = αM + βK: ζ(ω) = α/(2ω) + βω/2 ([`RayleighDamping`]).
    Rayleigh(RayleighDamping),
}

/// Rayleigh damping fitted to two damping ratios at two frequencies.
///
/// With ω_i = 2π f_i, the two equations ζ_i = α/(2ω_i) + βω_i/2 give
/// α = 2ω₁ω₂(ζ₁ω₂ − ζ₂ω₁)/(ω₂² − ω₁²) [1/s] and β = 2(ζ₂ω₂ − ζ₁ω₁)/(ω₂² − ω₁²) [s].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RayleighDamping {
    /// Damping ratio ζ₁ at the first frequency [-], in [0, 1).
    pub first_ratio: f64,
    /// The first frequency f₁ [Hz], positive.
    pub first_frequency: f64,
    /// Damping ratio ζ₂ at the second frequency [-], in [0, 1).
    pub second_ratio: f64,
    /// The second frequency f₂ [Hz], positive and not equal to f₁.
    pub second_frequency: f64,
}

/// The fitted Rayleigh coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayleighCoefficients {
    /// Mass-proportional coefficient α [1/s] (C = αM + βK).
    pub mass_coefficient: f64,
    /// Stiffness-proportional coefficient β [s].
    pub stiffness_coefficient: f64,
}

impl RayleighCoefficients {
    /// ζ(ω) = α/(2ω) + βω/2 at the circular frequency ω [rad/s] (ω > 0).
    pub fn damping_ratio(&self, circular_frequency: f64) -> f64 {
        self.mass_coefficient / (2.0 * circular_frequency)
            + self.stiffness_coefficient * circular_frequency / 2.0
    }
}

impl RayleighDamping {
    /// α and β through the two points (see [`RayleighDamping`]). Errors: a ratio outside
    /// [0, 1), a frequency that is not positive, equal frequencies, or a negative α or β (the
    /// two ratios then need negative damping between or beyond them: ζ₂/ζ₁ above ω₂/ω₁ or
    /// below ω₁/ω₂).
    pub fn coefficients(&self) -> Result<RayleighCoefficients, ModelError> {
        require_damping(self.first_ratio)?;
        require_damping(self.second_ratio)?;
        super::require_positive("Rayleigh first frequency", self.first_frequency)?;
        super::require_positive("Rayleigh second frequency", self.second_frequency)?;
        let (w1, w2) = (
            2.0 * PI * self.first_frequency,
            2.0 * PI * self.second_frequency,
        );
        let denominator = w2 * w2 - w1 * w1;
        if denominator.abs() <= 1e-12 * w2 * w2 {
            return Err(ModelError::RayleighEqualFrequencies {
                frequency: self.first_frequency,
            });
        }
        let (z1, z2) = (self.first_ratio, self.second_ratio);
        let coefficients = RayleighCoefficients {
            mass_coefficient: 2.0 * w1 * w2 * (z1 * w2 - z2 * w1) / denominator,
            stiffness_coefficient: 2.0 * (z2 * w2 - z1 * w1) / denominator,
        };
        for (coefficient, value) in [
            ("mass-proportional α", coefficients.mass_coefficient),
            (
                "stiffness-proportional β",
                coefficients.stiffness_coefficient,
            ),
        ] {
            if value < 0.0 {
                return Err(ModelError::RayleighNegative { coefficient, value });
            }
        }
        Ok(coefficients)
    }
}

impl ModeDamping {
    /// Checks the law: a non-empty list of ratios in [0, 1), or a Rayleigh fit with
    /// non-negative coefficients.
    pub fn validate(&self) -> Result<(), ModelError> {
        match self {
            ModeDamping::PerMode { ratios } => {
                if ratios.is_empty() {
                    return Err(ModelError::NoDampingRatios);
                }
                ratios.iter().try_for_each(|&ratio| require_damping(ratio))
            }
            ModeDamping::Rayleigh(rayleigh) => rayleigh.coefficients().map(|_| ()),
        }
    }

    /// The damping ratio of each retained mode [-], from their circular frequencies ω [rad/s]
    /// in ascending order. Errors: an invalid law ([`ModeDamping::validate`]), or a Rayleigh
    /// ratio ζ(ω) ≥ 1 at a mode (an overdamped mode has no vibration to keep).
    pub fn ratios(&self, circular_frequencies: &[f64]) -> Result<Vec<f64>, ModelError> {
        self.validate()?;
        match self {
            ModeDamping::PerMode { ratios } => Ok((0..circular_frequencies.len())
                .map(|k| ratios[k.min(ratios.len() - 1)])
                .collect()),
            ModeDamping::Rayleigh(rayleigh) => {
                let coefficients = rayleigh.coefficients()?;
                circular_frequencies
                    .iter()
                    .enumerate()
                    .map(|(k, &omega)| {
                        let ratio = coefficients.damping_ratio(omega);
                        if ratio.is_finite() && ratio < 1.0 {
                            Ok(ratio)
                        } else {
                            Err(ModelError::RayleighOverdamped {
                                mode: k + 1,
                                frequency: omega / (2.0 * PI),
                                damping_ratio: ratio,
                            })
                        }
                    })
                    .collect()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_beyond_the_list_take_its_last_ratio() {
        let law = ModeDamping::PerMode {
            ratios: vec![0.01, 0.02],
        };
        assert_eq!(law.ratios(&[1.0, 2.0, 3.0]).unwrap(), [0.01, 0.02, 0.02]);
        assert_eq!(
            ModeDamping::PerMode { ratios: vec![] }.validate(),
            Err(ModelError::NoDampingRatios)
        );
    }

    #[test]
    fn rayleigh_fits_that_need_negative_coefficients_or_equal_frequencies_are_refused() {
        let fit = |z1, f1, z2, f2| RayleighDamping {
            first_ratio: z1,
            first_frequency: f1,
            second_ratio: z2,
            second_frequency: f2,
        };
        assert!(matches!(
            fit(0.02, 2.0, 0.03, 2.0).coefficients(),
            Err(ModelError::RayleighEqualFrequencies { .. })
        ));
        // ζ₂/ζ₁ = 10 > ω₂/ω₁ = 2: α < 0.
        assert!(matches!(
            fit(0.01, 2.0, 0.1, 4.0).coefficients(),
            Err(ModelError::RayleighNegative { .. })
        ));
        // ζ₂/ζ₁ = 0.1 < ω₁/ω₂ = 0.5: β < 0.
        assert!(matches!(
            fit(0.1, 2.0, 0.01, 4.0).coefficients(),
            Err(ModelError::RayleighNegative { .. })
        ));
        // Mode at 1000 Hz: ζ ≈ βω/2 ≫ 1.
        let law = ModeDamping::Rayleigh(fit(0.02, 2.0, 0.15, 20.0));
        assert!(matches!(
            law.ratios(&[2.0 * PI * 1000.0]),
            Err(ModelError::RayleighOverdamped { mode: 1, .. })
        ));
    }
}
