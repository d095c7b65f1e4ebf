//! The static references of a channel that the headline and the comparison of methods both
//! read: the crawl run's static part ([`crawl_static`], with its cut-off [`crawl_cutoff`]) and
//! the check that a low-pass separates the static part ([`separation_check`],
//! [`separation_check_at`]).

use super::MeasureError;
use crate::measure::measurement::{Channel, Measurement};
use crate::signal::{
    check_separation, static_component, InfluenceShape, MeasuredQuantity, MovingLoads,
    SeparationCheck, SignalError,
};

/// The static part from a crawl-speed run: the crawl channel of the same name, low-passed at
/// its own `cutoff_hz` or f₁/2, read at the time the crawling vehicle stood where this
/// record's vehicle stands: t_crawl = t₀,crawl + v·(t − t₀)/v_crawl, linear between samples,
/// zero outside the crawl record.
pub(super) fn crawl_static(
    m: &Measurement,
    crawl: &Measurement,
    c: &Channel,
    first_frequency: Option<f64>,
) -> Result<Vec<f64>, MeasureError> {
    let needs = |what: &str| {
        MeasureError::input(
            "crawl",
            format!("a crawl-run static reference needs {what}"),
        )
    };
    let crawl_channel = crawl
        .channels
        .iter()
        .find(|k| k.name == c.name)
        .ok_or_else(|| needs(&format!("a channel `{}` in the crawl run", c.name)))?;
    let (Some(speed), Some(entry)) = (m.speed, m.entry_time) else {
        return Err(needs("this record's speed and entry time"));
    };
    let (Some(crawl_speed), Some(crawl_entry)) = (crawl.speed, crawl.entry_time) else {
        return Err(needs("the crawl run's speed and entry time"));
    };
    let cutoff = crawl_cutoff(crawl, first_frequency).ok_or_else(|| {
        needs("the first bridge frequency (first_frequency_hz, or an acceleration channel)")
    })?;
    let in_channel = |source: SignalError| MeasureError::Channel {
        channel: c.name.clone(),
        source,
    };
    let smooth = static_component(
        &crawl_channel.samples,
        crawl.sampling_rate_hz,
        crawl.filter_order,
        cutoff,
    )
    .map_err(in_channel)?;
    let t0 = crawl.time[0];
    let dt = 1.0 / crawl.sampling_rate_hz;
    Ok(m.time
        .iter()
        .map(|&t| {
            let at = crawl_entry + speed * (t - entry) / crawl_speed;
            let u = (at - t0) / dt;
            if u < 0.0 || u > (smooth.len() - 1) as f64 {
                return 0.0;
            }
            let i = (u.floor() as usize).min(smooth.len() - 2);
            let f = u - i as f64;
            smooth[i] * (1.0 - f) + smooth[i + 1] * f
        })
        .collect())
}

/// The low-pass cut-off of a crawl run [Hz]: its own `cutoff_hz`, else f₁/2. At crawl speed the
/// quasi-static content lies far below f₁ and the dynamic content is the bridge's own modes
/// (f₁ and up): f₁/2 removes them and rounds the kink of a moment influence line least (a bias
/// of about 2/(π²·T_b·f_c), T_b = L/v_crawl: 0.5 % for 30 m at 5 km/h and 3.6 Hz).
pub(super) fn crawl_cutoff(crawl: &Measurement, first_frequency: Option<f64>) -> Option<f64> {
    crawl.cutoff_hz.or(first_frequency.map(|f| f / 2.0))
}

/// The low-pass at `cutoff_hz` checked on the static response of the channel's influence-line
/// shape on the loaded span under the vehicle's axles (one axle without a vehicle), when the
/// span and the speed are known.
pub(super) fn separation_check(
    m: &Measurement,
    c: &Channel,
    cutoff_hz: f64,
) -> Result<Option<SeparationCheck>, SignalError> {
    separation_check_at(m, c, m.speed, m.sampling_rate_hz, m.filter_order, cutoff_hz)
}

/// The separation check of a low-pass of `order` at `cutoff_hz` on a record sampled at
/// `sampling_rate_hz` of the vehicle at `speed` [m/s] (this record's, or its crawl run's).
pub(super) fn separation_check_at(
    m: &Measurement,
    c: &Channel,
    speed: Option<f64>,
    sampling_rate_hz: f64,
    order: usize,
    cutoff_hz: f64,
) -> Result<Option<SeparationCheck>, SignalError> {
    let (Some(span), Some(speed)) = (m.span_length, speed) else {
        return Ok(None);
    };
    let position = c.position_in_span;
    let shape = match c.kind {
        MeasuredQuantity::Deflection => InfluenceShape::Deflection { position },
        _ => InfluenceShape::BendingMoment { position },
    };
    let loads = match &m.vehicle {
        Some(v) => MovingLoads { speed, ..v.clone() },
        None => MovingLoads {
            axle_loads: vec![1.0],
            axle_offsets: vec![0.0],
            speed,
            entry_time: 0.0,
        },
    };
    check_separation(shape, span, &loads, sampling_rate_hz, order, cutoff_hz).map(Some)
}
