//! Assessment statistics of a group of cases (issue 14.3): what an engineer needs to turn a
//! Monte Carlo set of DAFs into an assessment value.
//!
//! - [`assess`]: count, mean, sample standard deviation, the standard error of the mean, the
//!   95th percentile and the **characteristic value** with a bootstrap confidence interval.
//!   The characteristic value of a variable action is a fractile of its distribution (EN 1990
//!   §1.5.3.14 and §4.1.2(7)); for a dynamic amplification factor the 95 % fractile is the usual
//!   choice (the DAF of a load model is "not exceeded with 95 % probability"). It is estimated
//!   distribution-free by the sample's 95th percentile (Hyndman–Fan type 7,
//!   [`percentile_sorted`]); beside it, the normal-theory value mean + 1.645 σ. The interval is the
//!   percentile bootstrap (Efron & Tibshirani 1993, §13.3): B resamples of the n values with
//!   replacement, the 95th percentile of each, and the 2.5 % and 97.5 % points of those B values.
//! - [`running_mean`]: the Monte Carlo convergence of the mean with the number of samples, with
//!   the standard error s_n/√n at each n.
//! - [`histogram`] (Freedman–Diaconis bins) and [`empirical_cdf`].
//! - [`linear_fit`]: least squares of a DAF against the static response (heavier vehicles give
//!   lower DAFs), with Pearson's correlation.
//!
//! Resamples draw from [`SampleRng`] (ChaCha20) with a seed derived from the study's seed and the
//! group, so the interval is the same bit for bit on every run, thread count and shard layout.

use super::{percentile_sorted, statistics, StudyError};
use crate::road::SampleRng;

/// Number of bootstrap resamples of [`assess`]. With B = 2000 the Monte Carlo error of the 2.5 %
/// and 97.5 % points is small beside the interval's width (Efron & Tibshirani recommend
/// B ≥ 1000 for percentile intervals).
pub const BOOTSTRAP_RESAMPLES: usize = 2000;

/// Confidence level of the bootstrap interval [-].
pub const CONFIDENCE: f64 = 0.95;

/// The fractile of the characteristic value [-].
pub const CHARACTERISTIC_FRACTILE: f64 = 0.95;

/// The fewest values whose sample 95th percentile is called a characteristic value: 21. The
/// type-7 percentile of n values sits at rank h = 0.95 (n − 1) + 1; below 21 values h exceeds
/// n − 1, so it interpolates between the two largest values and the sample's maximum governs
/// it: the sample shows no value that it exceeds with 5 % probability, and its bootstrap
/// interval runs up to the maximum. Below this count the value is named for what it is, the
/// sample's 95th percentile (issue 46, item 9).
pub const MINIMUM_CHARACTERISTIC_SAMPLES: usize = 21;

/// The standard normal quantile of [`CHARACTERISTIC_FRACTILE`], Φ⁻¹(0.95) = 1.6449 (to 5
/// digits; tables of the normal distribution).
pub const NORMAL_QUANTILE_95: f64 = 1.644_853_626_951_472_2;

/// Assessment statistics of one group of values ([`assess`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Assessment {
    /// Number of values.
    pub count: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation (n − 1); 0 for one value.
    pub std: f64,
    /// Standard error of the mean, std/√n.
    pub standard_error: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// The characteristic value: the sample 95th percentile (Hyndman–Fan type 7).
    pub characteristic: f64,
    /// Lower end of its 95 % percentile-bootstrap confidence interval.
    pub characteristic_low: f64,
    /// Upper end of that interval.
    pub characteristic_high: f64,
    /// The normal-theory characteristic value, mean + 1.645 std.
    pub characteristic_normal: f64,
}

impl Assessment {
    /// Whether the sample supports a characteristic value (a 95 % fractile): at least
    /// [`MINIMUM_CHARACTERISTIC_SAMPLES`] values.
    pub fn supports_characteristic(&self) -> bool {
        self.count >= MINIMUM_CHARACTERISTIC_SAMPLES
    }

    /// The name of [`Assessment::characteristic`] for this sample, with its count: "the
    /// characteristic value (95 % fractile of 40 samples)", or below
    /// [`MINIMUM_CHARACTERISTIC_SAMPLES`] "the 95th percentile of 10 samples (too few for a
    /// characteristic value: at least 21)".
    pub fn fractile_name(&self) -> String {
        if self.supports_characteristic() {
            format!(
                "the characteristic value (95 % fractile of {} samples)",
                self.count
            )
        } else {
            format!(
                "the 95th percentile of {} samples (too few for a characteristic value: at \
                 least {MINIMUM_CHARACTERISTIC_SAMPLES})",
                self.count
            )
        }
    }
}

/// The assessment statistics of finite values (non-finite values are an error, never dropped);
/// `seed` seeds the bootstrap.
pub fn assess(values: &[f64], seed: u64) -> Result<Assessment, StudyError> {
    let s = statistics(values)?;
    let (low, high) = bootstrap_interval(values, CHARACTERISTIC_FRACTILE, seed);
    Ok(Assessment {
        count: s.count,
        mean: s.mean,
        std: s.std,
        standard_error: s.std / (s.count as f64).sqrt(),
        min: s.min,
        max: s.max,
        characteristic: s.p95,
        characteristic_low: low,
        characteristic_high: high,
        characteristic_normal: s.mean + NORMAL_QUANTILE_95 * s.std,
    })
}

/// The percentile-bootstrap [`CONFIDENCE`] interval of the p-quantile of `values` (not empty):
/// [`BOOTSTRAP_RESAMPLES`] resamples with replacement, each index ⌊u·n⌋ from a uniform u of
/// the seeded stream; the 2.5 % and 97.5 % points (type 7) of the resampled quantiles.
pub fn bootstrap_interval(values: &[f64], p: f64, seed: u64) -> (f64, f64) {
    let n = values.len();
    let tail = (1.0 - CONFIDENCE) / 2.0;
    // Values all equal bit for bit (a smooth road's samples): every resample is the same
    // sample, so every resampled quantile is that sample's, and no draw is needed.
    if n > 0 && values.iter().all(|v| v.to_bits() == values[0].to_bits()) {
        let quantile = percentile_sorted(values, p);
        let quantiles = vec![quantile; BOOTSTRAP_RESAMPLES];
        return (
            percentile_sorted(&quantiles, tail),
            percentile_sorted(&quantiles, 1.0 - tail),
        );
    }
    let mut rng = SampleRng::new(seed, 0);
    let mut resample = vec![0.0; n];
    let mut quantiles: Vec<f64> = (0..BOOTSTRAP_RESAMPLES)
        .map(|_| {
            for slot in resample.iter_mut() {
                let index = ((rng.next_unit() * n as f64) as usize).min(n - 1);
                *slot = values[index];
            }
            resample.sort_by(f64::total_cmp);
            percentile_sorted(&resample, p)
        })
        .collect();
    quantiles.sort_by(f64::total_cmp);
    (
        percentile_sorted(&quantiles, tail),
        percentile_sorted(&quantiles, 1.0 - tail),
    )
}

/// One point of the Monte Carlo convergence of a mean.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunningMean {
    /// Number of samples n.
    pub samples: usize,
    /// Mean of the first n values.
    pub mean: f64,
    /// Its standard error s_n/√n (0 for n = 1).
    pub standard_error: f64,
}

/// The mean of the first n values and its standard error, n = 1…len, in the order given (a
/// study's sample order), by Welford's update (one pass, no cancellation).
pub fn running_mean(values: &[f64]) -> Vec<RunningMean> {
    let (mut mean, mut squares) = (0.0, 0.0);
    values
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            let n = (i + 1) as f64;
            let delta = x - mean;
            mean += delta / n;
            squares += delta * (x - mean);
            let std = if i > 0 {
                (squares / (n - 1.0)).sqrt()
            } else {
                0.0
            };
            RunningMean {
                samples: i + 1,
                mean,
                standard_error: std / n.sqrt(),
            }
        })
        .collect()
}

/// A histogram: `counts[i]` values in [edges[i], edges[i + 1]) (the last bin closed).
#[derive(Debug, Clone, PartialEq)]
pub struct Histogram {
    /// Bin edges, one more than the bins.
    pub edges: Vec<f64>,
    /// Values per bin.
    pub counts: Vec<usize>,
}

/// The histogram of finite values with Freedman–Diaconis bins (width 2·IQR·n^(−1/3)), their
/// number clamped to 1…50; one bin when the values are all equal.
pub fn histogram(values: &[f64]) -> Histogram {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (Some(&low), Some(&high)) = (sorted.first(), sorted.last()) else {
        return Histogram {
            edges: Vec::new(),
            counts: Vec::new(),
        };
    };
    let iqr = percentile_sorted(&sorted, 0.75) - percentile_sorted(&sorted, 0.25);
    let width = 2.0 * iqr / (sorted.len() as f64).cbrt();
    let bins = if high > low && width > 0.0 {
        (((high - low) / width).ceil() as usize).clamp(1, 50)
    } else if high > low {
        10
    } else {
        1
    };
    let step = (high - low) / bins as f64;
    let edges: Vec<f64> = (0..=bins)
        .map(|i| {
            if i == bins {
                high
            } else {
                low + step * i as f64
            }
        })
        .collect();
    let mut counts = vec![0; bins];
    for &v in &sorted {
        let bin = if step > 0.0 {
            (((v - low) / step) as usize).min(bins - 1)
        } else {
            0
        };
        counts[bin] += 1;
    }
    Histogram { edges, counts }
}

/// The empirical distribution function: the sorted values with F = i/n, i = 1…n.
pub fn empirical_cdf(values: &[f64]) -> Vec<(f64, f64)> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len() as f64;
    sorted
        .into_iter()
        .enumerate()
        .map(|(i, v)| (v, (i + 1) as f64 / n))
        .collect()
}

/// A least-squares line y = intercept + slope·x and Pearson's correlation r.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearFit {
    /// Number of points.
    pub count: usize,
    /// Slope dy/dx.
    pub slope: f64,
    /// Intercept (y at x = 0).
    pub intercept: f64,
    /// Pearson's r, in [−1, 1].
    pub correlation: f64,
}

/// The least-squares line through the points (x, y); None for fewer than two points or when
/// x or y does not vary.
pub fn linear_fit(points: &[(f64, f64)]) -> Option<LinearFit> {
    let n = points.len();
    if n < 2 {
        return None;
    }
    let mean = |f: fn(&(f64, f64)) -> f64| points.iter().map(f).sum::<f64>() / n as f64;
    let (mx, my) = (mean(|p| p.0), mean(|p| p.1));
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for &(x, y) in points {
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
        sxy += (x - mx) * (y - my);
    }
    if !(sxx > 0.0 && syy > 0.0) {
        return None;
    }
    let slope = sxy / sxx;
    Some(LinearFit {
        count: n,
        slope,
        intercept: my - slope * mx,
        correlation: (sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// n standard normal draws (Box–Muller on the seeded stream).
    fn normal_draws(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = SampleRng::new(seed, 7);
        (0..n)
            .map(|_| {
                let u1 = 1.0 - rng.next_unit();
                let u2 = rng.next_unit();
                (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
            })
            .collect()
    }

    #[test]
    fn assessment_matches_the_sample_formulas_and_is_deterministic() {
        let values = [1.05, 1.10, 1.02, 1.20, 1.08, 1.12, 1.04, 1.15, 1.09, 1.11];
        let a = assess(&values, 42).unwrap();
        let s = statistics(&values).unwrap();
        assert_eq!(
            (a.count, a.mean, a.std, a.characteristic),
            (10, s.mean, s.std, s.p95)
        );
        assert!((a.standard_error - s.std / 10f64.sqrt()).abs() < 1e-15);
        assert!((a.characteristic_normal - (s.mean + 1.6448536269514722 * s.std)).abs() < 1e-15);
        // The interval of a 95th percentile lies within the sample's range and holds the
        // estimate's neighbourhood.
        assert!(a.characteristic_low >= a.min && a.characteristic_high <= a.max);
        assert!(
            a.characteristic_low <= a.characteristic && a.characteristic <= a.characteristic_high
        );
        assert_eq!(assess(&values, 42).unwrap(), a, "same seed, same bits");
        assert!(assess(&[f64::NAN], 1).is_err());
        assert!(assess(&[], 1).is_err());
    }

    #[test]
    fn equal_values_give_the_interval_that_drawn_resamples_give_bit_for_bit() {
        // The drawn resamples of equal values, as the general path takes them.
        let drawn = |values: &[f64], p: f64| {
            let quantiles: Vec<f64> = (0..BOOTSTRAP_RESAMPLES)
                .map(|_| percentile_sorted(values, p))
                .collect();
            let tail = (1.0 - CONFIDENCE) / 2.0;
            let low = percentile_sorted(&quantiles, tail);
            (low, percentile_sorted(&quantiles, 1.0 - tail))
        };
        for value in [1.0090612092648408, -0.0, 0.0, 3.5e-3] {
            for n in [1, 2, 10, 37] {
                let values = vec![value; n];
                let (low, high) = bootstrap_interval(&values, 0.95, 7);
                let (want_low, want_high) = drawn(&values, 0.95);
                assert_eq!(
                    (low.to_bits(), high.to_bits()),
                    (want_low.to_bits(), want_high.to_bits())
                );
            }
        }
    }

    #[test]
    fn the_bootstrap_interval_of_the_95th_percentile_covers_the_true_normal_fractile() {
        // Coverage check against a known distribution: 100 sets of 200 standard normal values;
        // the true 95 % fractile is 1.6449. A 95 % interval should cover it in about 95 of 100
        // sets (the percentile bootstrap of an upper quantile runs a little below nominal at this
        // n: Efron & Tibshirani §13.3); 85 is 4.6 binomial standard deviations (2.2) below 95.
        let mut covered = 0;
        for set in 0..100 {
            let values = normal_draws(200, 1000 + set);
            let a = assess(&values, set).unwrap();
            if a.characteristic_low <= NORMAL_QUANTILE_95
                && NORMAL_QUANTILE_95 <= a.characteristic_high
            {
                covered += 1;
            }
        }
        assert!(covered >= 85, "covered {covered} of 100");
    }

    #[test]
    fn the_running_mean_ends_at_the_mean_and_its_standard_error_at_std_over_root_n() {
        let values = normal_draws(500, 3);
        let running = running_mean(&values);
        let s = statistics(&values).unwrap();
        let last = running.last().unwrap();
        assert_eq!(last.samples, 500);
        assert!((last.mean - s.mean).abs() < 1e-14);
        assert!((last.standard_error - s.std / 500f64.sqrt()).abs() < 1e-14);
        assert_eq!(running[0].standard_error, 0.0);
        // Standard normal: the standard error at n = 500 is about 1/√500 = 0.045.
        assert!((last.standard_error - 0.0447).abs() < 0.005);
    }

    #[test]
    fn histogram_counts_every_value_once_in_freedman_diaconis_bins() {
        let values = normal_draws(1000, 5);
        let h = histogram(&values);
        assert_eq!(h.counts.iter().sum::<usize>(), 1000);
        assert_eq!(h.edges.len(), h.counts.len() + 1);
        // IQR of a standard normal 1.349: width 2·1.349/10 = 0.27 over a range of about 6.5.
        let bins = h.counts.len();
        assert!((18..=32).contains(&bins), "{bins} bins");
        assert_eq!(histogram(&[2.0, 2.0]).counts, [2]);
        let cdf = empirical_cdf(&[3.0, 1.0, 2.0]);
        assert_eq!(cdf, [(1.0, 1.0 / 3.0), (2.0, 2.0 / 3.0), (3.0, 1.0)]);
    }

    #[test]
    fn a_linear_fit_recovers_an_exact_line_and_the_sign_of_a_trend() {
        let line: Vec<(f64, f64)> = (0..5).map(|i| (i as f64, 1.3 - 0.05 * i as f64)).collect();
        let fit = linear_fit(&line).unwrap();
        assert!((fit.slope + 0.05).abs() < 1e-14 && (fit.intercept - 1.3).abs() < 1e-14);
        assert!((fit.correlation + 1.0).abs() < 1e-14);
        assert!(linear_fit(&[(1.0, 2.0)]).is_none());
        assert!(linear_fit(&[(1.0, 2.0), (1.0, 3.0)]).is_none());
    }

    /// Issue 46, item 9: ten road samples' 95th percentile is not called characteristic (it lies
    /// between the two largest values); 21 are the fewest that make it an order statistic below
    /// the maximum (rank 0.95·20 + 1 = 20 of 21).
    #[test]
    fn a_characteristic_value_needs_21_samples_and_is_named_with_its_count() {
        let ten: Vec<f64> = (0..10).map(|i| 1.0 + 0.01 * i as f64).collect();
        let a = assess(&ten, 7).unwrap();
        assert!(!a.supports_characteristic());
        assert!(a.characteristic > ten[8] && a.characteristic < ten[9]);
        assert_eq!(
            a.fractile_name(),
            "the 95th percentile of 10 samples (too few for a characteristic value: at least 21)"
        );
        let twenty_one: Vec<f64> = (0..21).map(|i| 1.0 + 0.01 * i as f64).collect();
        let b = assess(&twenty_one, 7).unwrap();
        assert!(b.supports_characteristic());
        assert_eq!(b.characteristic, twenty_one[19]);
        assert!(b
            .fractile_name()
            .contains("characteristic value (95 % fractile of 21 samples)"));
    }
}
