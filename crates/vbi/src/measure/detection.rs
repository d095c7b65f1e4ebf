//! The time the vehicle enters the bridge, found from the record when no axle detector gave it:
//! the static response that the channel's influence-line shape predicts is slid along the
//! record, and the entry time is where it fits best, with a logger offset and a linear drift
//! fitted beside it.
//!
//! For every trial entry time τ, least squares of
//!
//! ```text
//! y(t) ≈ a + b·t + c·s(t − τ),   s(t) = Σ_a P_a·IL(v·t − d_a)
//! ```
//!
//! (IL the shape of the loaded span, [`InfluenceShape`]); τ minimises the residual. The search
//! runs on block means of the record at about [`SEARCH_RATE_HZ`] (the static response is smooth
//! on that scale, and block means average the noise and the vibration down), then on every
//! sample within one block of the coarse optimum. The loaded span is the bridge model's span
//! that holds the channel's gauge (its `position_m`), the entry then earlier by the spans before
//! it ([`sensor_span`]); without a model or a position, the first span the vehicle crosses
//! (gauges in span 1, as in most load tests).

use serde::Serialize;

use crate::measure::measurement::{Channel, Measurement};
use crate::signal::{static_from_influence_line, InfluenceShape, MeasuredQuantity, MovingLoads};

/// Rate of the coarse search [Hz]: block means of the record.
const SEARCH_RATE_HZ: f64 = 20.0;

/// Blocks of the coarse search at most.
const MAX_BLOCKS: usize = 2000;

/// A fit that explains less than this fraction of the record's variance (after offset and
/// drift) is refused as a detection: the record does not show the crossing.
pub const MINIMUM_EXPLAINED_VARIANCE: f64 = 0.5;

/// The entry time found in the record.
#[derive(Debug, Clone, Serialize)]
pub struct DetectedEntry {
    /// The channel it was found in.
    pub channel: String,
    /// Entry time of the first axle [s].
    pub entry_time_s: f64,
    /// Fraction of the record's variance (after offset and drift) that the fitted static
    /// response explains [-].
    pub explained_variance: f64,
}

/// Finds the entry time from the first deflection channel (else the first strain or moment
/// channel), given the speed and the loaded span ([`sensor_span`], else [`loaded_span`]);
/// `None` when they are unknown, when no channel
/// suits, or when the best fit explains less than [`MINIMUM_EXPLAINED_VARIANCE`].
pub fn detect_entry(m: &Measurement) -> Option<DetectedEntry> {
    let speed = m.speed?;
    let channel = detection_channel(m)?;
    // A gauge placed on a later span of the bridge model answers when the vehicle reaches
    // that span: its span's shape, and the entry earlier by the spans before it.
    let (before, span) = match sensor_span(m, channel) {
        Some(located) => located,
        None => (0.0, loaded_span(m)?),
    };
    let template = Template::new(m, channel, span, &loads_at(m, speed))?;
    let coarse = Blocks::of(&m.time, &channel.samples, m.sampling_rate_hz);
    let (best, _) = best_shift(
        &coarse.times,
        &coarse.values,
        &template,
        coarse.candidates(),
    )?;
    let step = 1.0 / m.sampling_rate_hz;
    let fine = (-(coarse.block as i64)..=coarse.block as i64).map(|k| best + k as f64 * step);
    let (entry, explained) = best_shift(&m.time, &channel.samples, &template, fine)?;
    (explained >= MINIMUM_EXPLAINED_VARIANCE).then(|| DetectedEntry {
        channel: channel.name.clone(),
        entry_time_s: entry - before / speed,
        explained_variance: explained,
    })
}

/// The start [m] and length [m] of the bridge model's span that holds channel `c`'s gauge
/// (its `position_m`); `None` without a model or a position.
fn sensor_span(m: &Measurement, c: &Channel) -> Option<(f64, f64)> {
    let position = c.location?.position;
    let spans = m.bridge.as_ref()?.model.span_lengths();
    let mut start = 0.0;
    for &length in spans {
        if position <= start + length {
            return Some((start, length));
        }
        start += length;
    }
    None
}

/// The loaded span [m]: `span_length_m`, else the bridge model's first span, else the bridge's
/// length (a bridge of one span): a two-span bridge's length taken for the span would fit
/// twice the speed, or an entry half a crossing off.
fn loaded_span(m: &Measurement) -> Option<f64> {
    match (m.span_length, m.bridge.as_ref()) {
        (Some(span), _) => Some(span),
        (None, Some(bridge)) => bridge.model.span_lengths().first().copied(),
        (None, None) => m.bridge_length,
    }
}

/// The channel the entry and the speed are read from: the first deflection channel, else the
/// first strain or moment channel.
fn detection_channel(m: &Measurement) -> Option<&Channel> {
    m.channels
        .iter()
        .find(|c| c.kind == MeasuredQuantity::Deflection)
        .or_else(|| m.channels.iter().find(|c| c.has_daf()))
}

/// The vehicle's axles (a single unit load where not given) at `speed` [m/s], entering at 0.
fn loads_at(m: &Measurement, speed: f64) -> MovingLoads {
    m.vehicle.clone().map_or_else(
        || MovingLoads {
            axle_loads: vec![1.0],
            axle_offsets: vec![0.0],
            speed,
            entry_time: 0.0,
        },
        |v| MovingLoads {
            speed,
            entry_time: 0.0,
            ..v
        },
    )
}

/// The stated speed against the one the record's own response shows (issue 52, item 3).
#[derive(Debug, Clone, Serialize)]
pub struct SpeedCheck {
    /// The channel it was read from.
    pub channel: String,
    /// The stated speed [m/s].
    pub stated_speed_m_s: f64,
    /// The speed whose static response fits the record best [m/s].
    pub fitted_speed_m_s: f64,
    /// Fraction of the record's variance (after offset and drift) that the best fit explains
    /// [-].
    pub explained_variance: f64,
    /// The largest relative difference accepted: [`SPEED_TOLERANCE_WITH_AXLES`] where the
    /// vehicle's axles are given, else [`SPEED_TOLERANCE_WITHOUT_AXLES`] [-].
    pub tolerance: f64,
    /// |fitted / stated − 1| ≤ tolerance.
    pub plausible: bool,
}

/// The relative difference between the stated and the fitted speed accepted when the vehicle's
/// axles are given: the fit then has the static response's shape and duration, (span + axle
/// group) / v, and the battery's records at their true speeds fit within a few per cent
/// (docs/verification.md §29a).
pub const SPEED_TOLERANCE_WITH_AXLES: f64 = 0.25;

/// The same without axles: a single load stands for the vehicle, whose length then lengthens
/// the response unseen (a 12 m axle group on a 30 m span fits a speed about 30 % low).
pub const SPEED_TOLERANCE_WITHOUT_AXLES: f64 = 0.5;

/// Speeds tried, as factors of the stated speed: 0.2 to 5 on a geometric grid of 48 steps
/// (6.9 % apart; the km/h–m/s mix-ups are 3.6 and 1/3.6), then 20 steps across the best one's
/// neighbours.
const SPEED_FACTORS: (f64, f64, usize) = (0.2, 5.0, 48);

/// The speed whose static response (the channel's influence-line shape under the vehicle's
/// axles, [`Template`]) fits the record best, entry time, offset and drift free, against the
/// stated one: a speed in m/s typed as km/h is 3.6 times off. None without a stated speed, a
/// loaded span's length (`span_length_m`, the bridge model's first span, or `bridge_length_m`
/// without a model), a channel to read in the first span, or a fit that explains at least
/// [`MINIMUM_EXPLAINED_VARIANCE`] of the record.
pub fn check_speed(m: &Measurement) -> Option<SpeedCheck> {
    let stated = m.speed?;
    let span = loaded_span(m)?;
    let channel = detection_channel(m)?;
    // The template is the loaded span's shape with the vehicle entering it: a sensor beyond
    // the first span also answers while the vehicle is on the spans before it.
    if channel.location.is_some_and(|l| l.position > span) {
        return None;
    }
    let coarse = Blocks::of(&m.time, &channel.samples, m.sampling_rate_hz);
    let fit = |factor: f64| -> Option<(f64, f64)> {
        let template = Template::new(m, channel, span, &loads_at(m, stated * factor))?;
        let (_, explained) = best_shift(
            &coarse.times,
            &coarse.values,
            &template,
            coarse.candidates(),
        )?;
        Some((factor, explained))
    };
    let (low, high, steps) = SPEED_FACTORS;
    let ratio = (high / low).powf(1.0 / steps as f64);
    let best_of = |factors: Vec<f64>| {
        factors.into_iter().filter_map(fit).fold(
            None,
            |best: Option<(f64, f64)>, (f, e)| match best {
                Some((_, b)) if b >= e => best,
                _ => Some((f, e)),
            },
        )
    };
    let (coarse_best, _) = best_of((0..=steps).map(|k| low * ratio.powi(k as i32)).collect())?;
    let fine = (-10..=10).map(|k| coarse_best * ratio.powf(k as f64 / 10.0));
    let (factor, explained) = best_of(fine.collect())?;
    if explained < MINIMUM_EXPLAINED_VARIANCE {
        return None;
    }
    let tolerance = if m.vehicle.is_some() {
        SPEED_TOLERANCE_WITH_AXLES
    } else {
        SPEED_TOLERANCE_WITHOUT_AXLES
    };
    Some(SpeedCheck {
        channel: channel.name.clone(),
        stated_speed_m_s: stated,
        fitted_speed_m_s: stated * factor,
        explained_variance: explained,
        tolerance,
        plausible: (factor - 1.0).abs() <= tolerance,
    })
}

/// The predicted static response of the channel's shape, sampled finely from the front axle's
/// entry at t = 0 to the last axle's exit.
struct Template {
    times: Vec<f64>,
    values: Vec<f64>,
}

impl Template {
    fn new(m: &Measurement, c: &Channel, span: f64, loads: &MovingLoads) -> Option<Self> {
        let position = c.position_in_span;
        let shape = match c.kind {
            MeasuredQuantity::Deflection => InfluenceShape::Deflection { position },
            _ => InfluenceShape::BendingMoment { position },
        };
        let length = span + loads.axle_offsets.iter().cloned().fold(0.0, f64::max);
        let duration = length / loads.speed;
        let dt = 1.0 / m.sampling_rate_hz;
        // A crossing longer than the record cannot be found in it (and would ask for an
        // unbounded template).
        let record = m.time[m.time.len() - 1] - m.time[0];
        if !(duration.is_finite() && duration <= record) {
            return None;
        }
        let count = (duration / dt).ceil() as usize + 2;
        let times: Vec<f64> = (0..count).map(|i| i as f64 * dt).collect();
        let values = static_from_influence_line(&times, &shape.influence_line(span), loads).ok()?;
        Some(Template { times, values })
    }

    /// s(t) by linear interpolation, zero outside the crossing.
    fn at(&self, t: f64) -> f64 {
        let dt = self.times[1] - self.times[0];
        let u = t / dt;
        if u < 0.0 || u >= (self.times.len() - 1) as f64 {
            return 0.0;
        }
        let i = u as usize;
        let f = u - i as f64;
        self.values[i] * (1.0 - f) + self.values[i + 1] * f
    }
}

/// Block means of a record.
struct Blocks {
    times: Vec<f64>,
    values: Vec<f64>,
    block: usize,
}

impl Blocks {
    fn of(time: &[f64], samples: &[f64], sampling_rate_hz: f64) -> Self {
        // At most MAX_BLOCKS blocks: the coarse search costs blocks² (an hour at 20 Hz would
        // take minutes); longer records get longer blocks.
        let block = ((sampling_rate_hz / SEARCH_RATE_HZ).round() as usize)
            .max(time.len().div_ceil(MAX_BLOCKS))
            .max(1);
        let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
        Blocks {
            times: time.chunks(block).map(mean).collect(),
            values: samples.chunks(block).map(mean).collect(),
            block,
        }
    }

    /// Trial entry times: every block's mean time, from the first block to the last.
    fn candidates(&self) -> impl Iterator<Item = f64> + '_ {
        self.times.iter().copied()
    }
}

/// The shift τ of the best least-squares fit y ≈ a + b·t + c·s(t − τ) over `shifts`, and the
/// fraction of the variance (after a + b·t) that c·s explains.
fn best_shift(
    times: &[f64],
    values: &[f64],
    template: &Template,
    shifts: impl Iterator<Item = f64>,
) -> Option<(f64, f64)> {
    let n = times.len() as f64;
    let t_mean = times.iter().sum::<f64>() / n;
    let y_mean = values.iter().sum::<f64>() / n;
    // y and t with their means removed, and y with its straight line removed.
    let tc: Vec<f64> = times.iter().map(|t| t - t_mean).collect();
    let tt: f64 = tc.iter().map(|t| t * t).sum();
    let ty: f64 = tc.iter().zip(values).map(|(t, y)| t * (y - y_mean)).sum();
    let slope = if tt > 0.0 { ty / tt } else { 0.0 };
    let residual: Vec<f64> = tc
        .iter()
        .zip(values)
        .map(|(t, y)| y - y_mean - slope * t)
        .collect();
    let total: f64 = residual.iter().map(|r| r * r).sum();
    let mut best: Option<(f64, f64)> = None;
    for tau in shifts {
        // s with its own mean and line removed, then the explained sum of squares (r·s)²/(s·s).
        let s: Vec<f64> = times.iter().map(|t| template.at(t - tau)).collect();
        let s_mean = s.iter().sum::<f64>() / n;
        let ts: f64 = tc.iter().zip(&s).map(|(t, v)| t * (v - s_mean)).sum();
        let s_slope = if tt > 0.0 { ts / tt } else { 0.0 };
        let (mut ss, mut rs) = (0.0, 0.0);
        for ((v, t), r) in s.iter().zip(&tc).zip(&residual) {
            let sc = v - s_mean - s_slope * t;
            ss += sc * sc;
            rs += sc * r;
        }
        if ss <= 0.0 || total <= 0.0 {
            continue;
        }
        let explained = rs * rs / (ss * total);
        if best.is_none_or(|(_, e)| explained > e) {
            best = Some((tau, explained));
        }
    }
    best
}
