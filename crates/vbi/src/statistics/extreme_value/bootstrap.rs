//! Percentile-bootstrap intervals of a fitted law's quantiles (return levels).

use rayon::prelude::*;

use super::{ExtremeValueError, ExtremeValueModel, GeneralisedExtremeValue};
use crate::road::SampleRng;
use crate::statistics::percentile_sorted;

/// Confidence level of the intervals [-].
pub const CONFIDENCE: f64 = 0.95;

/// The quantiles of a fit with their bootstrap intervals ([`bootstrap_quantiles`]).
#[derive(Debug, Clone, PartialEq)]
pub struct BootstrapQuantiles {
    /// The law fitted to the values.
    pub fit: GeneralisedExtremeValue,
    /// Per probability: the fitted law's quantile.
    pub estimate: Vec<f64>,
    /// Per probability: the lower end of its [`CONFIDENCE`] interval.
    pub low: Vec<f64>,
    /// Per probability: the upper end.
    pub high: Vec<f64>,
    /// Resamples drawn.
    pub resamples: usize,
    /// Resamples whose refit failed (too few distinct values, or no convergence); the interval
    /// is taken over the others.
    pub failed: usize,
}

/// The quantiles of non-exceedance probabilities `probabilities` of `model`'s fit of `values`,
/// each with its percentile-bootstrap interval (Efron & Tibshirani 1993, "An Introduction to
/// the Bootstrap", §13.3; for return levels, Coles 2001 §4.4 and Caprani & OBrien 2010,
/// "Estimating extreme highway bridge traffic load effects", ICOSSAR): `resamples` resamples
/// of the n values with replacement, each refitted, and the 2.5 % and 97.5 % points (type 7)
/// of the refitted quantiles.
///
/// Resample r draws its indices ⌊u n⌋ from [`SampleRng`]`(seed, r)`, so the intervals are the
/// same bit for bit whatever the thread count (the resamples run in parallel and are gathered in
/// order). With no resamples the interval is the estimate itself.
pub fn bootstrap_quantiles(
    values: &[f64],
    model: ExtremeValueModel,
    probabilities: &[f64],
    resamples: usize,
    seed: u64,
) -> Result<BootstrapQuantiles, ExtremeValueError> {
    let fit = model.fit(values)?;
    let estimate: Vec<f64> = probabilities.iter().map(|&p| fit.quantile(p)).collect();
    let n = values.len();
    let refits: Vec<Option<Vec<f64>>> = (0..resamples as u64)
        .into_par_iter()
        .map(|r| {
            let mut rng = SampleRng::new(seed, r);
            let resample: Vec<f64> = (0..n)
                .map(|_| values[((rng.next_unit() * n as f64) as usize).min(n - 1)])
                .collect();
            let refit = model.fit(&resample).ok()?;
            Some(probabilities.iter().map(|&p| refit.quantile(p)).collect())
        })
        .collect();
    let succeeded: Vec<&Vec<f64>> = refits.iter().flatten().collect();
    let tail = (1.0 - CONFIDENCE) / 2.0;
    let (mut low, mut high) = (estimate.clone(), estimate.clone());
    if !succeeded.is_empty() {
        for (k, _) in probabilities.iter().enumerate() {
            let mut column: Vec<f64> = succeeded.iter().map(|q| q[k]).collect();
            column.sort_by(f64::total_cmp);
            low[k] = percentile_sorted(&column, tail);
            high[k] = percentile_sorted(&column, 1.0 - tail);
        }
    }
    Ok(BootstrapQuantiles {
        fit,
        estimate,
        low,
        high,
        resamples,
        failed: resamples - succeeded.len(),
    })
}
