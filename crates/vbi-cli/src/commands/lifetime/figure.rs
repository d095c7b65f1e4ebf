//! The return-level plot of `vbi lifetime` (`DIR/return_levels.png` and `.svg`): per effect, the
//! block maxima at their empirical mean recurrence intervals (Gringorten's positions), the GEV,
//! Gumbel and generalised Pareto levels against the mean recurrence interval x (the value
//! exceeded on average once in x years: a block probability of exceedance (b/d)/x, or a GP
//! exceedance rate λ of λx), and the GEV's 95 % profile-likelihood intervals at the asked return
//! periods. Magnitudes in the effect's governing sense, its SI unit.

use std::path::Path;

use anyhow::Result;

use vbi::lifetime::{
    empirical_recurrence_intervals, loaded_share, BlockMaximaFit, BlockMaximaTally, StaticLifetime,
    SECONDS_PER_DAY,
};
use vbi::statistics::extreme_value::ExtremeValueModel;

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

/// An effect's chart: its block maxima `values` (signed, in the effect's `sense`), the laws'
/// curves and the GEV's intervals; None without a block-maxima fit.
fn effect_chart(
    effect: &lifetime_input::EffectSummary,
    values: &[f64],
    sense: f64,
    summary: &lifetime_input::LifetimeSummary,
) -> Option<Chart> {
    let fits = effect.fits.as_ref()?;
    let block_days = summary.block_seconds / SECONDS_PER_DAY;
    let block_years = block_days / summary.days_per_year;
    let points = empirical_recurrence_intervals(values, sense, block_days, summary.days_per_year);
    let shortest = points.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let longest = summary
        .return_periods_years
        .iter()
        .chain(points.iter().map(|p| &p.0))
        .fold(0.0_f64, |a, b| a.max(*b));
    let (from, to) = (shortest.max(1e-9), 2.0 * longest);
    let recurrence: Vec<f64> = (0..CURVE_POINTS)
        .map(|k| from * (to / from).powf(k as f64 / (CURVE_POINTS - 1) as f64))
        .collect();
    let unloaded = fits.unloaded_blocks as f64 / (fits.loaded_blocks + fits.unloaded_blocks) as f64;
    let mut series = vec![Series {
        label: format!("{} block maxima", fits.loaded_blocks),
        points,
        style: SeriesStyle::Points,
    }];
    for fit in &fits.fits {
        let curve = recurrence
            .iter()
            .filter_map(|&x| {
                // Exceeded once in x years: F_block = 1 − (b/d)/x.
                let p = loaded_share(1.0 - block_years / x, unloaded)?;
                Some((x, fit.law.quantile(p)))
            })
            .collect();
        series.push(Series::line(fit.model.name().to_uppercase(), curve));
    }
    if let Some(peaks) = &effect.peaks_over_threshold {
        let curve = recurrence
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
    let gev = fits.fits.iter().find(|f| f.model == ExtremeValueModel::Gev);
    series.extend(gev.and_then(|gev| gev_intervals(gev, sense)));
    Some(chart(effect, series))
}

/// The GEV's profile intervals at the asked periods, as magnitudes, cut at three times the
/// largest level (an interval of few blocks can reach far beyond it and would flatten every
/// curve); the legend says so, and return_levels.csv has the whole interval.
fn gev_intervals(gev: &BlockMaximaFit, sense: f64) -> Option<Series> {
    let ceiling = 3.0
        * gev
            .return_levels
            .iter()
            .map(|level| (sense * level.value).abs())
            .fold(0.0, f64::max);
    let mut cut = false;
    let points: Vec<(f64, f64)> = gev
        .return_levels
        .iter()
        .flat_map(|level| {
            let high = level.high.map_or(f64::INFINITY, |h| sense * h);
            cut |= high > ceiling;
            let t = level.period_years;
            [(t, sense * level.low), (t, high.min(ceiling))]
        })
        .collect();
    let label = if cut {
        "GEV 95 % profile interval (cut at 3 × the level)"
    } else {
        "GEV 95 % profile interval"
    };
    (!points.is_empty()).then(|| Series {
        label: label.into(),
        points,
        style: SeriesStyle::Segments,
    })
}

/// Writes `stem.png` and `stem.svg` with one chart per effect that has a block-maxima fit.
pub fn write_return_level_plot(
    stem: &Path,
    analysis: &StaticLifetime,
    tally: &BlockMaximaTally,
    summary: &lifetime_input::LifetimeSummary,
) -> Result<()> {
    let charts: Vec<Chart> = summary
        .effects
        .iter()
        .enumerate()
        .filter_map(|(e, effect)| {
            let sense = analysis.effects[e].sense;
            effect_chart(effect, &tally.values[e], sense, summary)
        })
        .collect();
    if charts.is_empty() {
        return Ok(());
    }
    let columns = charts.len().min(2);
    write_charts(&charts, columns, stem)?;
    Ok(())
}
