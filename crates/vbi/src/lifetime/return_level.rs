//! Return levels of an effect's block maxima (issue 48, item 4): the Gumbel and GEV fits of
//! [`crate::statistics::extreme_value`], each effect's levels for the asked return periods, and
//! their bootstrap intervals.
//!
//! Blocks no truck loads (maximum 0: a night hour of hourly blocks) are not a sample of the
//! law of a loaded block's maximum, so the fit takes the loaded blocks only, and the level
//! accounts for the others: with a fraction q₀ of unloaded blocks,
//! F_block(z) = q₀ + (1 − q₀) G(z) for z > 0 (G: the fitted law), so the level of block
//! probability p is G⁻¹((p − q₀)/(1 − q₀)).

use crate::statistics::extreme_value::{
    bootstrap_quantiles, exceedance_ratio, fit_generalised_pareto, non_exceedance_probability,
    pareto_profile_interval, profile_interval, ExtremeValueError, ExtremeValueModel,
    GeneralisedExtremeValue, GeneralisedPareto,
};

/// Days of traffic in a year by default: 250 working days, BTLS's year (10 months of 25 days;
/// the traffic files' dates) and the convention of the lifetime studies it serves (Caprani,
/// OBrien & McLachlan 2008, "Characteristic traffic load effects from a mixture of loading
/// events on short to medium span bridges", Struct. Saf. 30(5)).
pub const DEFAULT_DAYS_PER_YEAR: f64 = 250.0;

/// The return period of the characteristic value by default [years]: 1000, the period EN
/// 1991-2's road-traffic load models were calibrated to ([`crate::statistics::extreme_value`]).
pub const DEFAULT_RETURN_PERIOD_YEARS: f64 = 1000.0;

/// Bootstrap resamples by default. The Monte Carlo error of the 2.5 % and 97.5 % points of B
/// resamples is about √(0.025 · 0.975 / B)/f (f: the density there); B = 400 keeps it below a
/// tenth of the interval's width for the laws of tests.rs.
pub const DEFAULT_BOOTSTRAP_RESAMPLES: usize = 400;

/// Exceedances of the peaks-over-threshold fit by default: the 1000 largest events of each
/// effect over the record, the threshold the 1001st. Enough for the fit's two parameters to be
/// well determined, few enough that the threshold lies in the tail (for a year of Auxerre
/// traffic, about 1.6 million events, the top 0.06 %); a record with fewer events has no
/// peaks-over-threshold fit.
pub const DEFAULT_EXCEEDANCES: usize = 1000;

/// How return levels are computed.
#[derive(Debug, Clone, PartialEq)]
pub struct ReturnLevelSettings {
    /// Return periods [years].
    pub periods_years: Vec<f64>,
    /// Days of traffic in a year.
    pub days_per_year: f64,
    /// Bootstrap resamples (0: no intervals).
    pub resamples: usize,
    /// Seed of the resamples. Every effect draws the same resample indices into its loaded
    /// blocks, so effects loaded in the same blocks resample the same days together.
    pub seed: u64,
    /// Exceedances of the peaks-over-threshold fit (0: no such fit).
    pub exceedances: usize,
}

impl Default for ReturnLevelSettings {
    fn default() -> Self {
        ReturnLevelSettings {
            periods_years: vec![DEFAULT_RETURN_PERIOD_YEARS],
            days_per_year: DEFAULT_DAYS_PER_YEAR,
            resamples: DEFAULT_BOOTSTRAP_RESAMPLES,
            seed: 0,
            exceedances: DEFAULT_EXCEEDANCES,
        }
    }
}

/// One return level with its intervals, in the effect's sense (signed, its unit; "low" is the
/// end nearer zero).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ReturnLevel {
    /// Return period [years].
    pub period_years: f64,
    /// The level: the fitted law's quantile.
    pub value: f64,
    /// Lower end of its 95 % profile-likelihood interval (the interval shown first: its coverage
    /// is tested, docs/verification.md §32).
    pub low: f64,
    /// Upper end of that interval; None where the likelihood sets no upper bound.
    pub high: Option<f64>,
    /// Lower end of its 95 % percentile-bootstrap interval; None without resamples, when more
    /// than half the refits failed, and for the peaks-over-threshold fit, which has none.
    pub bootstrap_low: Option<f64>,
    /// Upper end of that interval.
    pub bootstrap_high: Option<f64>,
}

/// One law fitted to an effect's block maxima.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BlockMaximaFit {
    /// The law.
    pub model: ExtremeValueModel,
    /// Its parameters, fitted to the loaded blocks' maxima as magnitudes (in the effect's sense:
    /// a hogging moment's −2 MN·m is 2 MN·m here).
    pub law: GeneralisedExtremeValue,
    /// The maximised log-likelihood.
    pub log_likelihood: f64,
    /// The levels, one per asked period.
    pub return_levels: Vec<ReturnLevel>,
    /// Resamples whose refit failed.
    pub failed_resamples: usize,
}

/// An effect's block maxima fitted ([`fit_block_maxima`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct EffectFits {
    /// Blocks fitted (those some truck loads).
    pub loaded_blocks: usize,
    /// Blocks no truck loads.
    pub unloaded_blocks: usize,
    /// The GEV fit first, then the Gumbel fit; a law whose fit or interval failed is left out
    /// and named in [`EffectFits::errors`].
    pub fits: Vec<BlockMaximaFit>,
    /// Why a law is missing from [`EffectFits::fits`] ("gev: …").
    pub errors: Vec<String>,
}

/// The non-exceedance probability under the loaded blocks' law G of the T-year level, with a
/// fraction `unloaded_fraction` of blocks no truck loads: [`loaded_share`] of
/// [`non_exceedance_probability`].
pub fn loaded_probability(
    period_years: f64,
    block_days: f64,
    days_per_year: f64,
    unloaded_fraction: f64,
) -> Option<f64> {
    let p = non_exceedance_probability(period_years, block_days, days_per_year);
    loaded_share(p, unloaded_fraction)
}

/// G(z) for a block non-exceedance probability F_block(z) = `block_probability` (module doc):
/// (F − q₀)/(1 − q₀), q₀ = `unloaded_fraction`; None where it is not in (0, 1) (the level is 0,
/// or beyond every value).
pub fn loaded_share(block_probability: f64, unloaded_fraction: f64) -> Option<f64> {
    let conditional = (block_probability - unloaded_fraction) / (1.0 - unloaded_fraction);
    (conditional > 0.0 && conditional < 1.0).then_some(conditional)
}

/// The block maxima as points of a return-level plot: each loaded block's maximum (magnitude in
/// the effect's `sense`) at its empirical mean recurrence interval [years], the i-th largest of
/// n blocks at Gringorten's plotting position of exceedance (i − 0.44)/(n + 0.12) (Gringorten
/// 1963, "A plotting rule for extreme probability paper", J. Geophys. Res. 68(3), the position
/// for Gumbel and GEV samples), so at (b/d)/((i − 0.44)/(n + 0.12)) years for blocks of b days
/// and d days of traffic a year. (The mean recurrence interval (b/d)/(1 − F_block) spreads the
/// blocks of a short record below one year, where the return period of
/// [`non_exceedance_probability`] is close to 1 for every one of them; above some tens of years
/// the two agree to 1/(2T).) Largest first.
pub fn empirical_recurrence_intervals(
    values: &[f64],
    sense: f64,
    block_days: f64,
    days_per_year: f64,
) -> Vec<(f64, f64)> {
    let mut magnitudes: Vec<f64> = values.iter().map(|v| sense * v).collect();
    magnitudes.sort_by(|a, b| b.total_cmp(a));
    let n = magnitudes.len() as f64;
    let block_years = block_days / days_per_year;
    magnitudes
        .iter()
        .enumerate()
        .filter(|(_, v)| **v > 0.0)
        .map(|(i, &v)| (block_years * (n + 0.12) / (i as f64 + 1.0 - 0.44), v))
        .collect()
}

/// Fits an effect's block maxima `values` (signed, in the effect's `sense`) of blocks of
/// `block_days` days, and computes the return levels `settings` asks for, by both laws.
pub fn fit_block_maxima(
    values: &[f64],
    sense: f64,
    block_days: f64,
    settings: &ReturnLevelSettings,
) -> Result<EffectFits, ExtremeValueError> {
    let loaded: Vec<f64> = values
        .iter()
        .map(|v| sense * v)
        .filter(|v| *v > 0.0)
        .collect();
    let unloaded = values.len() - loaded.len();
    let unloaded_fraction = unloaded as f64 / values.len().max(1) as f64;
    // The probability each level has under the loaded blocks' law (None: at or below the
    // probability of an unloaded block, so the level is 0).
    let probabilities: Vec<Option<f64>> = settings
        .periods_years
        .iter()
        .map(|&period| {
            loaded_probability(
                period,
                block_days,
                settings.days_per_year,
                unloaded_fraction,
            )
        })
        .collect();
    let asked: Vec<f64> = probabilities.iter().flatten().copied().collect();
    let mut fits = Vec::new();
    let mut errors = Vec::new();
    for model in ExtremeValueModel::ALL {
        match fit_one_law(&loaded, model, sense, &asked, &probabilities, settings) {
            Ok(fit) => fits.push(fit),
            // The sample itself cannot be fitted (too few, constant): no law can.
            Err(
                error @ (ExtremeValueError::TooFew { .. } | ExtremeValueError::Constant { .. }),
            ) => return Err(error),
            Err(error) => errors.push(format!("{}: {error}", model.name())),
        }
    }
    Ok(EffectFits {
        loaded_blocks: loaded.len(),
        unloaded_blocks: unloaded,
        fits,
        errors,
    })
}

/// One law's fit of the loaded blocks' maxima (magnitudes) and its levels at the
/// `probabilities` of the asked periods (`asked`: those that are Some, in order).
fn fit_one_law(
    loaded: &[f64],
    model: ExtremeValueModel,
    sense: f64,
    asked: &[f64],
    probabilities: &[Option<f64>],
    settings: &ReturnLevelSettings,
) -> Result<BlockMaximaFit, ExtremeValueError> {
    let quantiles = bootstrap_quantiles(loaded, model, asked, settings.resamples, settings.seed)?;
    // A bootstrap interval is given only when at least half the refits succeeded.
    let bootstrapped = settings.resamples > 0 && 2 * quantiles.failed < settings.resamples;
    let mut next = 0;
    let return_levels = settings
        .periods_years
        .iter()
        .zip(probabilities)
        .map(|(&period_years, probability)| {
            let Some(p) = probability else {
                return Ok(ReturnLevel {
                    period_years,
                    value: 0.0,
                    low: 0.0,
                    high: Some(0.0),
                    bootstrap_low: None,
                    bootstrap_high: None,
                });
            };
            let k = next;
            next += 1;
            let (low, high) = profile_interval(loaded, model, &quantiles.fit, *p)?;
            Ok(ReturnLevel {
                period_years,
                value: sense * quantiles.estimate[k],
                low: sense * low,
                high: high.map(|h| sense * h),
                bootstrap_low: bootstrapped.then(|| sense * quantiles.low[k]),
                bootstrap_high: bootstrapped.then(|| sense * quantiles.high[k]),
            })
        })
        .collect::<Result<Vec<_>, ExtremeValueError>>()?;
    let law = quantiles.fit;
    Ok(BlockMaximaFit {
        model,
        law,
        log_likelihood: law.log_likelihood(loaded),
        return_levels,
        failed_resamples: quantiles.failed,
    })
}

/// The peaks-over-threshold fit of an effect ([`fit_peaks`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PeaksOverThresholdFit {
    /// The generalised Pareto law of the exceedances as magnitudes (its threshold: the
    /// smallest event kept).
    pub law: GeneralisedPareto,
    /// Exceedances fitted.
    pub exceedances: usize,
    /// Their rate [per year of traffic].
    pub rate_per_year: f64,
    /// The maximised log-likelihood.
    pub log_likelihood: f64,
    /// The levels, one per asked period, with their 95 % profile-likelihood intervals.
    pub return_levels: Vec<ReturnLevel>,
}

/// The peaks-over-threshold fit (Coles 2001, ch. 4; for bridge traffic, Crespo-Minguillón &
/// Casas 1997, "A comprehensive traffic load model for bridge safety checking", Struct. Saf.
/// 19(4)) of an effect's largest events `peaks` (magnitudes in its sense, as
/// [`super::EventPeaks`] keeps them: the `settings.exceedances` + 1 largest) over a record of
/// `record_days` days: the smallest is the threshold u, the others its exceedances, fitted by a
/// generalised Pareto law; they occur at λ = k/(record_days/days_per_year) a year, and the T-year
/// level is u + σ c(ξ) with r = λ/(−ln(1 − 1/T)) ([`GeneralisedPareto::return_level`]). An
/// event ends when the deck is empty, so events are taken as independent and no declustering
/// is done. That is an assumption, not a guarantee: platoons, congestion and the daily cycle of
/// flow correlate neighbouring events, and Caprani, OBrien & McLachlan 2008 separate events by
/// the number of trucks, which one law over all events does not. Levels carry the effect's
/// `sense`.
pub fn fit_peaks(
    peaks: &[f64],
    sense: f64,
    record_days: f64,
    settings: &ReturnLevelSettings,
) -> Result<PeaksOverThresholdFit, ExtremeValueError> {
    if peaks.len() < settings.exceedances + 1 || settings.exceedances == 0 {
        return Err(ExtremeValueError::TooFewEvents {
            events: peaks.len(),
            exceedances: settings.exceedances,
        });
    }
    let threshold = peaks.iter().copied().fold(f64::INFINITY, f64::min);
    let exceedances: Vec<f64> = peaks.iter().copied().filter(|v| *v > threshold).collect();
    let law = fit_generalised_pareto(&exceedances, threshold)?;
    let rate_per_year = exceedances.len() as f64 / (record_days / settings.days_per_year);
    let return_levels = settings
        .periods_years
        .iter()
        .map(|&period_years| {
            let r = exceedance_ratio(period_years, rate_per_year);
            if r.is_nan() || r <= 1.0 {
                return Err(ExtremeValueError::BelowThreshold { period_years });
            }
            let (low, high) = pareto_profile_interval(&exceedances, &law, r);
            Ok(ReturnLevel {
                period_years,
                value: sense * law.level(r),
                low: sense * low,
                high: high.map(|h| sense * h),
                bootstrap_low: None,
                bootstrap_high: None,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(PeaksOverThresholdFit {
        law,
        exceedances: exceedances.len(),
        rate_per_year,
        log_likelihood: law.log_likelihood(&exceedances),
        return_levels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::statistics::extreme_value::fit_gev;

    /// Deterministic block maxima: quantiles of a GEV at evenly spaced probabilities.
    fn maxima(n: usize) -> Vec<f64> {
        let law = GeneralisedExtremeValue {
            location: 2.0e6,
            scale: 2.0e5,
            shape: -0.15,
        };
        (0..n)
            .map(|i| law.quantile((i as f64 + 0.5) / n as f64))
            .collect()
    }

    #[test]
    fn unloaded_blocks_are_left_out_of_the_fit_and_counted_in_the_level_s_probability() {
        // 60 loaded blocks and 20 empty ones: q₀ = 1/4; the level of block probability p is the
        // loaded law's quantile of (p − q₀)/(1 − q₀) (return_level.rs's module doc).
        let loaded = maxima(60);
        let mut values = loaded.clone();
        values.extend([0.0; 20]);
        let settings = ReturnLevelSettings {
            periods_years: vec![50.0, 1000.0],
            days_per_year: 250.0,
            resamples: 0,
            seed: 0,
            exceedances: 0,
        };
        let fits = fit_block_maxima(&values, 1.0, 1.0, &settings).unwrap();
        assert_eq!((fits.loaded_blocks, fits.unloaded_blocks), (60, 20));
        let gev = &fits.fits[0];
        assert_eq!(gev.model, ExtremeValueModel::Gev);
        assert_eq!(gev.law, fit_gev(&loaded).unwrap());
        for level in &gev.return_levels {
            let p = non_exceedance_probability(level.period_years, 1.0, 250.0);
            let want = gev.law.quantile((p - 0.25) / 0.75);
            assert_eq!(level.value, want);
            // No resamples: no bootstrap interval.
            assert_eq!((level.bootstrap_low, level.bootstrap_high), (None, None));
            assert!(level.low < want && want < level.high.unwrap());
        }
        assert!(gev.return_levels[1].value > gev.return_levels[0].value);
    }

    #[test]
    fn a_negative_effect_is_fitted_as_magnitudes_and_its_levels_carry_its_sign() {
        let positive = maxima(40);
        let negative: Vec<f64> = positive.iter().map(|v| -v).collect();
        let settings = ReturnLevelSettings {
            resamples: 50,
            ..ReturnLevelSettings::default()
        };
        let up = fit_block_maxima(&positive, 1.0, 1.0, &settings).unwrap();
        let down = fit_block_maxima(&negative, -1.0, 1.0, &settings).unwrap();
        for (a, b) in up.fits.iter().zip(&down.fits) {
            assert_eq!(a.law, b.law);
            for (x, y) in a.return_levels.iter().zip(&b.return_levels) {
                assert_eq!(x.value, -y.value);
                assert_eq!((x.low, x.high), (-y.low, y.high.map(|h| -h)));
                let minus = |v: Option<f64>| v.map(|v| -v);
                assert_eq!(
                    (x.bootstrap_low, x.bootstrap_high),
                    (minus(y.bootstrap_low), minus(y.bootstrap_high))
                );
                assert!(x.low <= x.value && x.value <= x.high.unwrap());
                assert!(
                    x.bootstrap_low.unwrap() <= x.value && x.value <= x.bootstrap_high.unwrap()
                );
            }
        }
    }

    #[test]
    fn recurrence_intervals_are_gringorten_s_positions_in_years_and_skip_empty_blocks() {
        // Four daily blocks, one empty, 250 days a year: the i-th largest of n = 4 at
        // (1/250)(4.12)/(i − 0.44) years (Gringorten 1963).
        let values = [-3.0, 0.0, -5.0, -4.0];
        let points = empirical_recurrence_intervals(&values, -1.0, 1.0, 250.0);
        let want =
            [(1, 5.0), (2, 4.0), (3, 3.0)].map(|(i, v)| (4.12 / (i as f64 - 0.44) / 250.0, v));
        assert_eq!(points.len(), 3);
        for (got, want) in points.iter().zip(want) {
            assert!(
                (got.0 - want.0).abs() < 1e-15 && got.1 == want.1,
                "{got:?} {want:?}"
            );
        }
    }
}
