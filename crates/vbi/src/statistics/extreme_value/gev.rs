//! The generalised extreme-value distribution and its maximum-likelihood fit.

use super::gumbel::fit_gumbel;
use super::nelder_mead::minimise;
use super::{checked, shape_growth, shape_log, ExtremeValueError};

/// The generalised extreme-value (GEV) distribution of a block maximum (Coles 2001, "An
/// Introduction to Statistical Modeling of Extreme Values", Theorem 3.1.1, eq. 3.2):
///
/// F(z) = exp(−[1 + ξ (z − μ)/σ]^(−1/ξ)),  defined where 1 + ξ (z − μ)/σ > 0,
///
/// the Gumbel law as ξ → 0, Fréchet (heavy upper tail) for ξ > 0 and reversed Weibull (an upper
/// end point μ − σ/ξ) for ξ < 0, the usual case of traffic load effects (a truck's weight is
/// bounded). scipy's `genextreme(c, loc=μ, scale=σ)` has the opposite sign: c = −ξ.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GeneralisedExtremeValue {
    /// Location μ [the data's unit].
    pub location: f64,
    /// Scale σ > 0 [the data's unit].
    pub scale: f64,
    /// Shape ξ [-] (Coles's sign: negative for a bounded upper tail).
    pub shape: f64,
}

impl GeneralisedExtremeValue {
    /// t(z) = ln(1 + ξ y)/ξ with y = (z − μ)/σ (t = y as ξ → 0), so that F(z) = exp(−e^(−t));
    /// None outside the support.
    fn reduced(&self, z: f64) -> Option<f64> {
        shape_log(self.shape, (z - self.location) / self.scale)
    }

    /// The probability F(z) that a block maximum does not exceed z (0 below the support's
    /// lower end, 1 above its upper end).
    pub fn cdf(&self, z: f64) -> f64 {
        match self.reduced(z) {
            Some(t) => (-(-t).exp()).exp(),
            None if self.shape > 0.0 => 0.0,
            None => 1.0,
        }
    }

    /// The quantile of non-exceedance probability p in (0, 1) (Coles eq. 3.4):
    /// z_p = μ + σ (y_p^(−ξ) − 1)/ξ with y_p = −ln p; z_p = μ − σ ln y_p as ξ → 0.
    pub fn quantile(&self, p: f64) -> f64 {
        self.location + self.scale * shape_growth(self.shape, -(-p.ln()).ln())
    }

    /// The log-likelihood of `values` (Coles eq. 3.7, with t_i as in [`Self::cdf`]):
    /// ℓ = −n ln σ − Σ [(1 + ξ) t_i + e^(−t_i)], −∞ if a value lies outside the support.
    pub fn log_likelihood(&self, values: &[f64]) -> f64 {
        let mut sum = 0.0;
        for &z in values {
            match self.reduced(z) {
                Some(t) => sum += (1.0 + self.shape) * t + (-t).exp(),
                None => return f64::NEG_INFINITY,
            }
        }
        -(values.len() as f64) * self.scale.ln() - sum
    }
}

/// The maximum-likelihood GEV fit of `values` (at least [`super::MINIMUM_FIT_VALUES`],
/// finite, not all equal).
///
/// The values are standardised (z − z̄)/s; the negative log-likelihood in (μ, ln σ, ξ) is
/// minimised by Nelder–Mead from three starts (the Gumbel fit with ξ = 0, −0.2 and +0.2), to a
/// relative change of 1e-13, and the best kept. ξ is held above −1: below it the likelihood is
/// unbounded as the upper end point approaches the largest value (Smith 1985, "Maximum
/// likelihood estimation in a class of nonregular cases", Biometrika 72; Coles §3.3.2), and no
/// maximum-likelihood estimate exists.
pub fn fit_gev(values: &[f64]) -> Result<GeneralisedExtremeValue, ExtremeValueError> {
    checked(values)?;
    let (mean, std, standard) = super::standardised(values);
    let gumbel = fit_gumbel(&standard)?;
    let cost = |theta: &[f64; 3]| {
        if theta[2] <= -1.0 {
            return f64::INFINITY;
        }
        let model = GeneralisedExtremeValue {
            location: theta[0],
            scale: theta[1].exp(),
            shape: theta[2],
        };
        -model.log_likelihood(&standard)
    };
    let mut best: Option<([f64; 3], f64)> = None;
    for shape in [0.0, -0.2, 0.2] {
        // A start whose support excludes a datum moves its location until it holds them all.
        let mut start = [gumbel.location, gumbel.scale.ln(), shape];
        while !cost(&start).is_finite() && start[0].abs() < 1e3 {
            start[0] -= shape.signum() * 0.5 * gumbel.scale;
        }
        let (theta, value, converged) = minimise(cost, start, 0.1, 1e-13, 20_000);
        if converged && best.is_none_or(|(_, b)| value < b) {
            best = Some((theta, value));
        }
    }
    let (theta, _) = best.ok_or(ExtremeValueError::NotConverged { model: "GEV" })?;
    Ok(GeneralisedExtremeValue {
        location: mean + std * theta[0],
        scale: std * theta[1].exp(),
        shape: theta[2],
    })
}
