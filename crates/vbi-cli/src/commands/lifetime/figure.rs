//! The return-level plot of `vbi lifetime` (`DIR/return_levels.png` and `.svg`): per effect, the
//! block maxima at their empirical mean recurrence intervals (Gringorten's positions), the GEV,
//! Gumbel and generalised Pareto levels against the mean recurrence interval x (the value
//! exceeded on average once in x years: a block probability of exceedance (b/d)/x, or a GP
//! exceedance rate λ of λx), and the GEV's 95 % profile-likelihood intervals at the asked return
//! periods. Magnitudes in the effect's governing sense, its SI unit.

use std::path::Path;

use anyhow::Result;

use vbi::lifetime::{
    empirical_recurrence_intervals, BlockMaximaTally, StaticLifetime, SECONDS_PER_DAY,
};

use crate::inputs::lifetime as lifetime_input;
use crate::plot::{write_charts, Chart, Series, SeriesStyle};

/// Points on each fitted curve.
const CURVE_POINTS: usize = 120;

/// An effect's chart of `series`.
fn chart(effect: &lifetime_input::EffectSummary, series: Vec<Series>) -> Chart {
    Chart {
        title: format!("{} {}", effect.station, effect.quantity),
        x_label: "mean recurrence interval [years]".into(),
        y_label: format!("{} [{}]", effect.quantity, effect.unit),
        series,
        log_x: true,
        ..Chart::default()
    }
}

/// Writes `stem.png` and `stem.svg` with one chart per effect that has a block-maxima fit.
pub fn write_return_level_plot(
    stem: &Path,
    analysis: &StaticLifetime,
    tally: &BlockMaximaTally,
    summary: &lifetime_input::LifetimeSummary,
) -> Result<()> {
    let block_days = summary.block_seconds / SECONDS_PER_DAY;
    let days_per_year = summary.days_per_year;
    let mut charts = Vec::new();
    for (e, effect) in summary.effects.iter().enumerate() {
        let Some(fits) = &effect.fits else { continue };
        let sense = analysis.effects[e].sense;
        let points =
            empirical_recurrence_intervals(&tally.values[e], sense, block_days, days_per_year);
        let block_years = block_days / days_per_year;
        let shortest = points.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
        let longest = summary
            .return_periods_years
            .iter()
            .chain(points.iter().map(|p| &p.0))
            .fold(0.0_f64, |a, b| a.max(*b));
        let (from, to) = (shortest.max(1e-9), 2.0 * longest);
        let periods: Vec<f64> = (0..CURVE_POINTS)
            .map(|k| from * (to / from).powf(k as f64 / (CURVE_POINTS - 1) as f64))
            .collect();
        let unloaded =
            fits.unloaded_blocks as f64 / (fits.loaded_blocks + fits.unloaded_blocks) as f64;
        let mut series = vec![Series {
            label: format!("{} block maxima", fits.loaded_blocks),
            points: points.clone(),
            style: SeriesStyle::Points,
        }];
        for fit in &fits.fits {
            let curve = periods
                .iter()
                .filter_map(|&x| {
                    // F_block = 1 − (b/d)/x; under the loaded blocks' law (F − q₀)/(1 − q₀).
                    let p = (1.0 - block_years / x - unloaded) / (1.0 - unloaded);
                    (p > 0.0 && p < 1.0).then(|| (x, fit.law.quantile(p)))
                })
                .collect();
            series.push(Series::line(fit.model.name().to_uppercase(), curve));
        }
        if let Some(peaks) = &effect.peaks_over_threshold {
            let curve = periods
                .iter()
                .filter_map(|&x| {
                    let r = peaks.rate_per_year * x;
                    (r > 1.0).then(|| (x, peaks.law.level(r)))
                })
                .collect();
            series.push(Series::line(
                format!("GP, {} peaks", peaks.exceedances),
                curve,
            ));
        }
        // The GEV's profile intervals, cut at three times the largest GEV level asked (an
        // interval of few blocks can reach far beyond it and would flatten every curve); the
        // legend says so, and return_levels.csv has the whole interval.
        let Some(gev) = fits
            .fits
            .iter()
            .find(|f| f.model == vbi::statistics::extreme_value::ExtremeValueModel::Gev)
        else {
            charts.push(chart(effect, series));
            continue;
        };
        let ceiling = 3.0
            * gev
                .return_levels
                .iter()
                .map(|level| (sense * level.value).abs())
                .fold(0.0, f64::max);
        let mut cut = false;
        let intervals: Vec<(f64, f64)> = gev
            .return_levels
            .iter()
            .flat_map(|level| {
                let high = level.high.map_or(f64::INFINITY, |h| sense * h);
                cut |= high > ceiling;
                let t = level.period_years;
                [(t, sense * level.low), (t, high.min(ceiling))]
            })
            .collect();
        if !intervals.is_empty() {
            series.push(Series {
                label: if cut {
                    "GEV 95 % profile interval (cut at 3 × the level)".into()
                } else {
                    "GEV 95 % profile interval".into()
                },
                points: intervals,
                style: SeriesStyle::Segments,
            });
        }
        charts.push(chart(effect, series));
    }
    if charts.is_empty() {
        return Ok(());
    }
    let columns = charts.len().min(2);
    write_charts(&charts, columns, stem)?;
    Ok(())
}
