//! The generalised Pareto law of exceedances over a threshold, its maximum-likelihood fit, and
//! its return levels with their profile-likelihood interval (peaks over threshold).

use super::nelder_mead::minimise;
use super::profile::interval_end;
use super::{half_chi_square_95, shape_growth, shape_log, ExtremeValueError};

/// The generalised Pareto (GP) law of an exceedance y = x − u of a threshold u (Coles 2001,
/// "An Introduction to Statistical Modeling of Extreme Values", Theorem 4.1, eq. 4.2):
///
/// H(y) = 1 − (1 + ξ y/σ)^(−1/ξ),  y > 0 and 1 + ξ y/σ > 0,
///
/// the exponential law as ξ → 0. Its ξ is the ξ of the GEV law of the block maxima of the same
/// events. scipy: `genpareto(c=ξ, loc=u, scale=σ)` (the same sign).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GeneralisedPareto {
    /// Threshold u [the data's unit].
    pub threshold: f64,
    /// Scale σ > 0 [the data's unit].
    pub scale: f64,
    /// Shape ξ [-].
    pub shape: f64,
}

impl GeneralisedPareto {
    /// t(y) = ln(1 + ξ y/σ)/ξ (y/σ as ξ → 0), so that 1 − H = e^(−t); None outside the support.
    fn reduced(&self, x: f64) -> Option<f64> {
        let y = (x - self.threshold) / self.scale;
        if y < 0.0 {
            return None;
        }
        shape_log(self.shape, y)
    }

    /// The probability that an exceedance of the threshold does not exceed x.
    pub fn cdf(&self, x: f64) -> f64 {
        match self.reduced(x) {
            Some(t) => -(-t).exp_m1(),
            None if x < self.threshold => 0.0,
            None => 1.0,
        }
    }

    /// The log-likelihood of exceedances `values` (all above the threshold; Coles eq. 4.10):
    /// ℓ = −k ln σ − (1 + ξ) Σ t_i; −∞ if one lies outside the support.
    pub fn log_likelihood(&self, values: &[f64]) -> f64 {
        let mut sum = 0.0;
        for &x in values {
            match self.reduced(x) {
                Some(t) => sum += t,
                None => return f64::NEG_INFINITY,
            }
        }
        -(values.len() as f64) * self.scale.ln() - (1.0 + self.shape) * sum
    }

    /// The value that an exceedance passes with probability 1/r (r > 1): the threshold plus
    /// σ c(ξ) with c(ξ) = (r^ξ − 1)/ξ (ln r as ξ → 0; Coles eq. 4.12).
    pub fn level(&self, r: f64) -> f64 {
        self.threshold + self.scale * growth(r, self.shape)
    }

    /// The T-year return level of exceedances that occur at `rate_per_year` (a Poisson
    /// process; Coles §4.3.3 and §7.4): the level z with exp(−λ (1 − H(z − u))) = 1 − 1/T, so
    /// that the year's largest event exceeds it with probability 1/T, as a block-maxima return
    /// level ([`super::non_exceedance_probability`]); z = u + σ c(ξ) with r = λ / (−ln(1 − 1/T)).
    pub fn return_level(&self, period_years: f64, rate_per_year: f64) -> f64 {
        self.level(exceedance_ratio(period_years, rate_per_year))
    }
}

/// r = λ / (−ln(1 − 1/T)): the ratio of the exceedance rate to the rate at which the level is
/// exceeded.
pub fn exceedance_ratio(period_years: f64, rate_per_year: f64) -> f64 {
    rate_per_year / -(-1.0 / period_years).ln_1p()
}

/// c(ξ) = (r^ξ − 1)/ξ (ln r as ξ → 0).
fn growth(r: f64, shape: f64) -> f64 {
    shape_growth(shape, r.ln())
}

/// The exceedances x − u divided by their mean, with the mean: the fit and its profile work in
/// units of the mean exceedance, well scaled for the simplex whatever the data's unit.
fn scaled_exceedances(values: &[f64], threshold: f64) -> (f64, Vec<f64>) {
    let mean = values.iter().map(|x| x - threshold).sum::<f64>() / values.len() as f64;
    (
        mean,
        values.iter().map(|x| (x - threshold) / mean).collect(),
    )
}

/// The maximum-likelihood GP fit of the exceedances `values` (every one above `threshold`; at
/// least [`super::MINIMUM_FIT_VALUES`], finite, not all equal): Nelder–Mead over (ln σ, ξ) from the
/// exponential fit (σ = the mean exceedance, ξ = 0) and from ξ = ±0.2, on exceedances scaled by
/// their mean; ξ held above −1, where the likelihood is unbounded (Coles §4.3.2; Grimshaw 1993,
/// "Computing maximum likelihood estimates for the generalized Pareto distribution",
/// Technometrics 35).
pub fn fit_generalised_pareto(
    values: &[f64],
    threshold: f64,
) -> Result<GeneralisedPareto, ExtremeValueError> {
    super::checked(values)?;
    if let Some(index) = values.iter().position(|v| *v <= threshold) {
        return Err(ExtremeValueError::NotAbove { index, threshold });
    }
    let (mean, scaled) = scaled_exceedances(values, threshold);
    let cost = |theta: &[f64; 2]| {
        if theta[1] <= -1.0 {
            return f64::INFINITY;
        }
        -GeneralisedPareto {
            threshold: 0.0,
            scale: theta[0].exp(),
            shape: theta[1],
        }
        .log_likelihood(&scaled)
    };
    let mut best: Option<([f64; 2], f64)> = None;
    for shape in [0.0, -0.2, 0.2] {
        // A negative shape's upper end σ/|ξ| must lie above the largest exceedance.
        let largest = scaled.iter().copied().fold(0.0, f64::max);
        let scale = if shape < 0.0 {
            f64::max(1.0, 1.5 * largest * -shape)
        } else {
            1.0
        };
        let (theta, value, converged) = minimise(cost, [scale.ln(), shape], 0.1, 1e-13, 20_000);
        if converged && value.is_finite() && best.is_none_or(|(_, b)| value < b) {
            best = Some((theta, value));
        }
    }
    let (theta, _) = best.ok_or(ExtremeValueError::NotConverged {
        model: "generalised Pareto",
    })?;
    Ok(GeneralisedPareto {
        threshold,
        scale: mean * theta[0].exp(),
        shape: theta[1],
    })
}

/// The 95 % profile-likelihood interval of the level `fit.level(r)` (Coles §4.3.4): with the
/// level held at z, σ = (z − u)/c(ξ), and the profile is a one-parameter maximisation over ξ.
/// Ends bracketed by doubling steps from the estimate and bisected, as for the GEV
/// ([`super::profile_interval`]); an upper end not reached within 2³⁹ scales is None.
pub fn pareto_profile_interval(
    values: &[f64],
    fit: &GeneralisedPareto,
    r: f64,
) -> (f64, Option<f64>) {
    let (mean, scaled) = scaled_exceedances(values, fit.threshold);
    let law = GeneralisedPareto {
        threshold: 0.0,
        scale: fit.scale / mean,
        shape: fit.shape,
    };
    let target = law.log_likelihood(&scaled) - half_chi_square_95();
    let estimate = law.level(r);
    // ℓ_p(z) from a start ξ; None where no ξ near it is feasible.
    let profile = |z: f64, start: f64| -> Option<(f64, f64)> {
        let cost = |xi: &[f64; 1]| {
            let c = growth(r, xi[0]);
            if xi[0] <= -1.0 || c.is_nan() || c <= 0.0 {
                return f64::INFINITY;
            }
            -GeneralisedPareto {
                threshold: 0.0,
                scale: z / c,
                shape: xi[0],
            }
            .log_likelihood(&scaled)
        };
        let from = [start, 0.0, 0.5, 1.0, 2.0]
            .into_iter()
            .find(|s| cost(&[*s]).is_finite())?;
        let (xi, value, _) = minimise(cost, [from], 0.05, 1e-12, 5000);
        value.is_finite().then_some((-value, xi[0]))
    };
    // A level at or below the threshold has no profile: the lower end is reached before it.
    let at = |z: f64, from: f64| (z > 0.0).then(|| profile(z, from)).flatten();
    let low = interval_end(at, estimate, -law.scale, law.shape, target).unwrap_or(0.0);
    let high = interval_end(at, estimate, law.scale, law.shape, target);
    let back = |z: f64| fit.threshold + mean * z;
    (back(low), high.map(back))
}
