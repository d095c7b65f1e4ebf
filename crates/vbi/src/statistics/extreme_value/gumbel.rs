//! The Gumbel distribution (the extreme-value law of type I) and its maximum-likelihood fit.

use super::{checked, ExtremeValueError};

/// The Gumbel distribution of a block maximum (Coles 2001, "An Introduction to Statistical
/// Modeling of Extreme Values", eq. 3.2 with ξ → 0):
///
/// F(z) = exp(−exp(−(z − μ)/σ)).
///
/// scipy: `scipy.stats.gumbel_r(loc=μ, scale=σ)`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Gumbel {
    /// Location μ [the data's unit].
    pub location: f64,
    /// Scale σ > 0 [the data's unit].
    pub scale: f64,
}

impl Gumbel {
    /// The probability F(z) that a block maximum does not exceed z.
    pub fn cdf(&self, z: f64) -> f64 {
        (-(-(z - self.location) / self.scale).exp()).exp()
    }

    /// The quantile z_p = μ − σ ln(−ln p) of non-exceedance probability p in (0, 1).
    pub fn quantile(&self, p: f64) -> f64 {
        self.location - self.scale * (-p.ln()).ln()
    }

    /// The log-likelihood of `values` (Coles eq. 3.9):
    /// ℓ = −n ln σ − Σ y_i − Σ exp(−y_i), y_i = (z_i − μ)/σ.
    pub fn log_likelihood(&self, values: &[f64]) -> f64 {
        let n = values.len() as f64;
        -n * self.scale.ln()
            - values
                .iter()
                .map(|z| {
                    let y = (z - self.location) / self.scale;
                    y + (-y).exp()
                })
                .sum::<f64>()
    }
}

/// The maximum-likelihood Gumbel fit of `values` (at least [`super::MINIMUM_FIT_VALUES`],
/// finite, not all equal).
///
/// The likelihood equations (Coles §3.3.2; Johnson, Kotz & Balakrishnan 1995, "Continuous
/// Univariate Distributions" vol. 2, §22.7) reduce to one equation in σ,
///
/// g(σ) = σ − z̄ + Σ z_i e^(−z_i/σ) / Σ e^(−z_i/σ) = 0,  then μ = −σ ln((1/n) Σ e^(−z_i/σ)).
///
/// g increases (g′ = 1 + Var_w(z)/σ² with weights e^(−z_i/σ)), is negative as σ → 0 and
/// non-negative at σ = z̄ − min z, so its one root lies in that bracket: Newton's method from the
/// moment estimate σ = s√6/π, safeguarded by bisection, to round-off. The values are shifted by
/// their minimum so that no exponential overflows.
pub fn fit_gumbel(values: &[f64]) -> Result<Gumbel, ExtremeValueError> {
    checked(values)?;
    let n = values.len() as f64;
    let minimum = values.iter().copied().fold(f64::INFINITY, f64::min);
    let shifted: Vec<f64> = values.iter().map(|z| z - minimum).collect();
    let mean = shifted.iter().sum::<f64>() / n;
    let variance = shifted.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / (n - 1.0);
    // The weighted sums Σ w, Σ w z, Σ w z² with w = e^(−z/σ).
    let sums = |sigma: f64| {
        shifted.iter().fold((0.0, 0.0, 0.0), |(s0, s1, s2), &z| {
            let w = (-z / sigma).exp();
            (s0 + w, s1 + w * z, s2 + w * z * z)
        })
    };
    let (mut low, mut high) = (0.0, mean);
    let mut sigma = (variance.sqrt() * 6f64.sqrt() / std::f64::consts::PI).clamp(0.5 * mean, mean);
    for _ in 0..200 {
        let (s0, s1, s2) = sums(sigma);
        let weighted_mean = s1 / s0;
        let g = sigma - mean + weighted_mean;
        if g < 0.0 {
            low = sigma;
        } else {
            high = sigma;
        }
        let slope = 1.0 + (s2 / s0 - weighted_mean * weighted_mean) / (sigma * sigma);
        let newton = sigma - g / slope;
        let next = if newton > low && newton < high {
            newton
        } else {
            0.5 * (low + high)
        };
        let settled = (next - sigma).abs() <= 4.0 * f64::EPSILON * sigma
            || high - low <= 4.0 * f64::EPSILON * high;
        sigma = next;
        if settled {
            let (s0, _, _) = sums(sigma);
            let location = minimum - sigma * (s0 / n).ln();
            return Ok(Gumbel {
                location,
                scale: sigma,
            });
        }
    }
    Err(ExtremeValueError::NotConverged { model: "Gumbel" })
}
