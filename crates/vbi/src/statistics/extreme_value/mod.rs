//! Extreme-value statistics of block maxima (issue 48, item 4): the Gumbel and generalised
//! extreme-value (GEV) laws, their maximum-likelihood fits, return levels, and percentile-
//! bootstrap intervals of those levels.
//!
//! Theory (Coles 2001, "An Introduction to Statistical Modeling of Extreme Values", ch. 3): the
//! maximum of a block of many independent (or weakly dependent) events tends to a GEV law; the
//! fit of the block maxima by maximum likelihood gives its parameters, and the **return level**
//! of a return period of T years is the value a block maximum exceeds with the probability
//! that gives, on average, one exceedance in T years. With blocks of b days and d days of
//! traffic in a year ([`non_exceedance_probability`]):
//!
//! F_block(z_T) = (1 − 1/T)^(b/d),
//!
//! so that the yearly maximum, the largest of d/b independent block maxima, has
//! F_year(z_T) = 1 − 1/T exactly. The road-traffic load models of EN 1991-2 were calibrated to
//! a return period of 1000 years (a 10 % probability of exceedance in 100 years: the JRC
//! background document to EN 1991-2, Sedlacek et al. 2008, report EUR 23375), which is why a
//! lifetime assessment's characteristic value is commonly its 1000-year return level.
//!
//! Written by hand: no well-kept Rust crate fits extreme-value laws (statrs has neither law;
//! gevlib, last released in 2022, has the laws and no fit). The fits are checked against
//! scipy's `gumbel_r.fit` and `genextreme.fit` in crates/vbi-py/tests.

mod bootstrap;
mod gev;
mod gumbel;
mod nelder_mead;
mod pareto;
mod profile;
#[cfg(test)]
mod tests;

pub use bootstrap::{bootstrap_quantiles, BootstrapQuantiles, CONFIDENCE};
pub use gev::{fit_gev, GeneralisedExtremeValue};
pub use gumbel::{fit_gumbel, Gumbel};
pub use pareto::{
    exceedance_ratio, fit_generalised_pareto, pareto_profile_interval, GeneralisedPareto,
};
pub use profile::profile_interval;

/// The fewest block maxima fitted: ten. A three-parameter fit of fewer has too little to say
/// about its tail (Coles §3.4 fits 65 annual maxima; Caprani's daily maxima are hundreds).
pub const MINIMUM_FIT_VALUES: usize = 10;

/// Half the 95 % point of the χ² law with one degree of freedom, χ²₁(0.95)/2 = 3.8415/2: the
/// drop of the profile log-likelihood at a 95 % interval's ends (Coles §2.6.6), computed from
/// statrs's χ² law so that it follows [`CONFIDENCE`].
fn half_chi_square_95() -> f64 {
    use statrs::distribution::{ChiSquared, ContinuousCDF};
    // One degree of freedom is a valid χ² law.
    ChiSquared::new(1.0).map_or(f64::NAN, |law| law.inverse_cdf(CONFIDENCE) / 2.0)
}

/// Below this |ξ| the ξ → 0 limits of [`shape_growth`] and [`shape_log`] are used (their
/// relative error is of order |ξ| × the argument, far below the fits' round-off).
const SHAPE_LIMIT: f64 = 1e-12;

/// (e^(ξL) − 1)/ξ = ∫₀^L e^(ξt) dt, L as ξ → 0: the growth of a GEV quantile (L = −ln(−ln p):
/// z_p = μ + σ × this) and of a GP level (L = ln r). It increases with ξ whatever the sign of
/// L.
fn shape_growth(shape: f64, log_argument: f64) -> f64 {
    if shape.abs() < SHAPE_LIMIT {
        log_argument
    } else {
        (shape * log_argument).exp_m1() / shape
    }
}

/// ln(1 + ξy)/ξ, y as ξ → 0: the inverse of [`shape_growth`], the reduced variate t of a GEV
/// (F = exp(−e^(−t))) and a GP law (1 − H = e^(−t)); None where 1 + ξy ≤ 0 (outside the
/// support).
fn shape_log(shape: f64, y: f64) -> Option<f64> {
    if shape.abs() < SHAPE_LIMIT {
        return Some(y);
    }
    let argument = shape * y;
    (argument > -1.0).then(|| argument.ln_1p() / shape)
}

/// Why a fit cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExtremeValueError {
    /// Too few values.
    #[error("{count} block maxima are too few to fit an extreme-value law (at least {MINIMUM_FIT_VALUES})")]
    TooFew {
        /// How many there are.
        count: usize,
    },
    /// A value is not finite.
    #[error("block maximum {index} is not finite")]
    NotFinite {
        /// Its index from 0.
        index: usize,
    },
    /// Every value is the same.
    #[error("every block maximum is {value}: no spread to fit")]
    Constant {
        /// The value.
        value: f64,
    },
    /// An exceedance is not above its threshold.
    #[error("exceedance {index} is not above the threshold {threshold}")]
    NotAbove {
        /// Its index from 0.
        index: usize,
        /// The threshold.
        threshold: f64,
    },
    /// Too few events for the asked exceedances.
    #[error("{events} events are too few for a peaks-over-threshold fit of {exceedances} exceedances (it needs one more event than exceedances)")]
    TooFewEvents {
        /// Events kept.
        events: usize,
        /// Exceedances asked.
        exceedances: usize,
    },
    /// A return period so short that its level lies below the threshold.
    #[error("the {period_years}-year level lies below the peaks-over-threshold fit's threshold (its exceedances come less often than once in {period_years} years); ask for fewer exceedances")]
    BelowThreshold {
        /// The period.
        period_years: f64,
    },
    /// The likelihood's maximum was not found.
    #[error("the maximum-likelihood {model} fit did not converge")]
    NotConverged {
        /// The law.
        model: &'static str,
    },
}

/// The values a fit accepts: at least [`MINIMUM_FIT_VALUES`], finite, not all equal.
fn checked(values: &[f64]) -> Result<(), ExtremeValueError> {
    if values.len() < MINIMUM_FIT_VALUES {
        return Err(ExtremeValueError::TooFew {
            count: values.len(),
        });
    }
    if let Some(index) = values.iter().position(|v| !v.is_finite()) {
        return Err(ExtremeValueError::NotFinite { index });
    }
    if values.iter().all(|v| *v == values[0]) {
        return Err(ExtremeValueError::Constant { value: values[0] });
    }
    Ok(())
}

/// The values standardised as the fits take them, (z − z̄)/s (s: the sample standard
/// deviation), with z̄ and s: a likelihood in units of the data's spread is well scaled for
/// the simplex whatever the data's unit.
fn standardised(values: &[f64]) -> (f64, f64, Vec<f64>) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let std = (values.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    (mean, std, values.iter().map(|z| (z - mean) / std).collect())
}

/// An extreme-value law fitted to block maxima.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ExtremeValueModel {
    /// [`Gumbel`].
    Gumbel,
    /// [`GeneralisedExtremeValue`].
    Gev,
}

impl ExtremeValueModel {
    /// Both, the general law first.
    pub const ALL: [ExtremeValueModel; 2] = [ExtremeValueModel::Gev, ExtremeValueModel::Gumbel];

    /// The name in tables: "gev" or "gumbel".
    pub fn name(self) -> &'static str {
        match self {
            ExtremeValueModel::Gumbel => "gumbel",
            ExtremeValueModel::Gev => "gev",
        }
    }

    /// The maximum-likelihood fit of `values` by this law, as a GEV (ξ = 0 for Gumbel).
    pub fn fit(self, values: &[f64]) -> Result<GeneralisedExtremeValue, ExtremeValueError> {
        match self {
            ExtremeValueModel::Gumbel => fit_gumbel(values).map(|g| GeneralisedExtremeValue {
                location: g.location,
                scale: g.scale,
                shape: 0.0,
            }),
            ExtremeValueModel::Gev => fit_gev(values),
        }
    }
}

/// The probability that a block maximum does not exceed the T-year return level:
/// (1 − 1/T)^(b/d), for blocks of b = `block_days` and d = `days_per_year` days of traffic in a
/// year, so that the largest of the d/b block maxima of a year exceeds it with probability 1/T.
/// Computed as exp((b/d) ln(1 − 1/T)) with ln_1p, exact to round-off for long periods.
pub fn non_exceedance_probability(period_years: f64, block_days: f64, days_per_year: f64) -> f64 {
    ((block_days / days_per_year) * (-1.0 / period_years).ln_1p()).exp()
}
