//! How sure a measured DAF is: the DAF by every static method the record allows (a low-pass, a
//! crawl run, an influence line), side by side, and a standard uncertainty of the headline DAF
//! from the record's noise and from the choice of static separation.
//!
//! The uncertainty follows the GUM's first-order propagation (JCGM 100:2008 §5.1) for
//! DAF = D/S, D the measured maximum and S the static maximum:
//!
//! ```text
//! u_noise = DAF · √((σ_D/D)² + (σ_S/S)²)
//! σ_D = σ                              (one sample of the record)
//! σ_S = σ·√g(f_c),  g = (2/f_s)∫₀^{f_s/2} |H(f)|⁴ df     (zero-phase low-pass: |H|² twice)
//! u_separation = max(|bias of the method|, max over the other valid methods |DAF_m − DAF|)
//! u = √(u_noise² + u_separation²)
//! ```
//!
//! σ is one sample's noise, from second differences (var Δ²n = 6σ² for white noise) of the
//! quiet window before the vehicle enters, or of the whole record when that window is unknown
//! (an upper bound: the response's own curvature adds to it). The maximum of a noisy signal
//! is also biased upwards by about one to two σ (the largest of the few samples near the
//! peak); the uncertainty covers it at its 95 % expansion (k = 2), which is what the outputs
//! give beside the standard value.

use serde::Serialize;

use super::influence_lines::ChannelLines;
use super::separation::comparison_cutoff;
use super::static_references::{crawl_cutoff, crawl_static, separation_check_at};
use super::MeasureError;
use crate::measure::measurement::{Channel, Measurement};
use crate::signal::{
    butterworth_lowpass, measured_daf, static_component, static_from_influence_line, SignalError,
};

/// Points of the quadrature of the low-pass noise gain over 0 to f_s/2.
const NOISE_GAIN_POINTS: usize = 4096;

/// One static method's DAF of a channel.
#[derive(Debug, Clone, Serialize)]
pub struct StaticMethodDaf {
    /// "low_pass", "crawl_run", "influence_line" (given), "influence_line_model" (the bridge
    /// model's at the sensor) or "influence_line_crawl" (calibrated from the crawl run).
    pub method: &'static str,
    /// The low-pass cut-off [Hz] (the crawl run's own for "crawl_run").
    pub cutoff_hz: Option<f64>,
    /// Static maximum, in the channel unit.
    pub static_max: f64,
    /// DAF by this method [-].
    pub daf: f64,
    /// The method's own systematic error of the DAF [-] where it can be estimated: the
    /// separation check of its low-pass on the channel's influence-line shape (0 for a given
    /// influence line).
    pub bias: Option<f64>,
    /// Whether the method counts in the spread of the static separation: a low-pass only when
    /// its cut-off rule finds the quasi-static content below half the first frequency and its
    /// separation check passes (the check alone sees the influence line, not the vehicle's own
    /// low-frequency forcing); a crawl run, a given influence line and the crawl run's line
    /// always; the bridge model's line when the model was fitted to the identified modes.
    pub valid: bool,
    /// The method is the one behind the channel's DAF.
    pub chosen: bool,
}

/// The standard uncertainty of a channel's DAF.
#[derive(Debug, Clone, Serialize)]
pub struct DafUncertainty {
    /// One sample's noise σ, in the channel unit.
    pub noise_std: f64,
    /// Where σ was estimated: "quiet_window_before_entry" or "whole_record" (an upper bound).
    pub noise_window: &'static str,
    /// Standard uncertainty of the DAF from the noise [-].
    pub from_noise: f64,
    /// Standard uncertainty of the DAF from the static separation [-].
    pub from_static_separation: f64,
    /// √(from_noise² + from_static_separation²) [-].
    pub combined: f64,
    /// 2 × combined: the 95 % interval's half-width [-].
    pub expanded_95: f64,
}

/// The method behind a channel's DAF and its static part [SI], computed once by the channel
/// stage and read here again instead of being recomputed.
pub(super) struct Chosen<'a> {
    /// The method's name.
    pub method: &'static str,
    /// Its static part [SI].
    pub part: &'a [f64],
}

impl Chosen<'_> {
    /// The static part of method `name`: the chosen one's when it is that method, else
    /// `compute`d.
    fn part_of(
        &self,
        name: &str,
        compute: impl FnOnce() -> Option<Vec<f64>>,
    ) -> Option<std::borrow::Cow<'_, [f64]>> {
        if name == self.method {
            Some(std::borrow::Cow::Borrowed(self.part))
        } else {
            compute().map(std::borrow::Cow::Owned)
        }
    }
}

/// Every static method the record allows for channel `c`, and the uncertainty of the DAF of
/// the `chosen` method.
pub(super) fn assess(
    m: &Measurement,
    c: &Channel,
    chosen: &Chosen,
    first_frequency: Option<f64>,
    lines: &ChannelLines,
) -> Result<(Vec<StaticMethodDaf>, Option<DafUncertainty>), MeasureError> {
    // A comparison that cannot be computed (a record too short for a filter, a crawl that
    // misses the crossing) is left out: it must not fail the channel's own DAF.
    let (sigma, window) = noise_of(m, &c.samples);
    let candidates = [
        low_pass_method(m, c, chosen, first_frequency, sigma),
        crawl_method(m, c, chosen, first_frequency),
        given_line_method(m, c, chosen, lines),
        model_line_method(m, c, chosen, lines),
        crawl_line_method(m, c, chosen, lines),
    ];
    let (methods, static_noise): (Vec<_>, Vec<_>) = candidates.into_iter().flatten().unzip();
    let uncertainty = methods
        .iter()
        .position(|x| x.chosen)
        .and_then(|i| combine(&methods, i, sigma, static_noise[i], c.si_per_unit, window));
    Ok((methods, uncertainty))
}

/// The low-pass at the comparison cut-off, with the noise σ_S [SI] left in its static part.
fn low_pass_method(
    m: &Measurement,
    c: &Channel,
    chosen: &Chosen,
    first_frequency: Option<f64>,
    sigma: f64,
) -> Option<(StaticMethodDaf, f64)> {
    let (cutoff, apart) = comparison_cutoff(m, first_frequency)?;
    let part = static_component(&c.samples, m.sampling_rate_hz, m.filter_order, cutoff).ok()?;
    let check =
        separation_check_at(m, c, m.speed, m.sampling_rate_hz, m.filter_order, cutoff).ok()?;
    let gain = lowpass_noise_gain(m.filter_order, cutoff, m.sampling_rate_hz).ok()?;
    let valid = apart && check.as_ref().is_some_and(|k| k.separated);
    let peak_error = check.map(|k| k.peak_error);
    let daf = method(
        c,
        "low_pass",
        Some(cutoff),
        &part,
        peak_error,
        valid,
        chosen,
    )?;
    Some((daf, sigma * gain.sqrt()))
}

/// The crawl run's static part, with the noise σ_S [SI] of the crawl's low-passed channel.
fn crawl_method(
    m: &Measurement,
    c: &Channel,
    chosen: &Chosen,
    first_frequency: Option<f64>,
) -> Option<(StaticMethodDaf, f64)> {
    let crawl = m.crawl.as_deref()?;
    let part = chosen.part_of("crawl_run", || {
        crawl_static(m, crawl, c, first_frequency).ok()
    })?;
    let cutoff = crawl_cutoff(crawl, first_frequency)?;
    let (speed, rate, order) = (crawl.speed, crawl.sampling_rate_hz, crawl.filter_order);
    let check = separation_check_at(m, c, speed, rate, order, cutoff).ok()?;
    let crawl_channel = crawl.channels.iter().find(|k| k.name == c.name)?;
    let crawl_sigma = noise_of(crawl, &crawl_channel.samples).0;
    let gain = lowpass_noise_gain(order, cutoff, rate).ok()?;
    let peak_error = check.map(|k| k.peak_error);
    let daf = method(
        c,
        "crawl_run",
        Some(cutoff),
        &part,
        peak_error,
        true,
        chosen,
    )?;
    Some((daf, crawl_sigma * gain.sqrt()))
}

/// A given influence line under the axle loads (noise-free, no bias).
fn given_line_method(
    m: &Measurement,
    c: &Channel,
    chosen: &Chosen,
    lines: &ChannelLines,
) -> Option<(StaticMethodDaf, f64)> {
    let (name, line) = lines
        .chosen
        .as_ref()
        .filter(|(name, _)| *name == "influence_line")?;
    let loads = m.vehicle.as_ref()?;
    let part = chosen.part_of(name, || {
        static_from_influence_line(&m.time, line, loads).ok()
    })?;
    let daf = method(c, name, None, &part, Some(0.0), true, chosen)?;
    Some((daf, 0.0))
}

/// The bridge model's influence line under the axle loads (noise-free): valid only when the
/// model was updated or calibrated to the identified modes (an unfitted model's stiffness
/// error enters the static maximum one to one); its bias is not known.
fn model_line_method(
    m: &Measurement,
    c: &Channel,
    chosen: &Chosen,
    lines: &ChannelLines,
) -> Option<(StaticMethodDaf, f64)> {
    let (line, loads) = (lines.model.as_ref()?, m.vehicle.as_ref()?);
    let name = "influence_line_model";
    let part = chosen.part_of(name, || {
        static_from_influence_line(&m.time, line, loads).ok()
    })?;
    let daf = method(c, name, None, &part, None, lines.model_fitted, chosen)?;
    Some((daf, 0.0))
}

/// The crawl run's influence line under the axle loads, with the noise its fit leaves.
fn crawl_line_method(
    m: &Measurement,
    c: &Channel,
    chosen: &Chosen,
    lines: &ChannelLines,
) -> Option<(StaticMethodDaf, f64)> {
    let (crawl, loads) = (lines.crawl.as_ref()?, m.vehicle.as_ref()?);
    let name = "influence_line_crawl";
    let part = chosen.part_of(name, || {
        static_from_influence_line(&m.time, &crawl.line, loads).ok()
    })?;
    let daf = method(c, name, None, &part, None, true, chosen)?;
    Some((daf, crawl.static_part_std()))
}

/// One method's DAF from its static part [SI].
fn method(
    c: &Channel,
    name: &'static str,
    cutoff_hz: Option<f64>,
    static_part: &[f64],
    peak_error: Option<f64>,
    valid: bool,
    chosen: &Chosen,
) -> Option<StaticMethodDaf> {
    let d = measured_daf(&c.samples, static_part).ok()?;
    // A static peak scaled by (1 + e) scales the DAF by 1/(1 + e).
    let bias = peak_error.map(|e| d.daf * (1.0 / (1.0 + e) - 1.0));
    Some(StaticMethodDaf {
        method: name,
        cutoff_hz,
        static_max: d.static_max / c.si_per_unit,
        daf: d.daf,
        bias,
        valid,
        chosen: name == chosen.method,
    })
}

/// The uncertainty of method `i`'s DAF: σ [SI] of the record, σ_S [SI] of its static part.
fn combine(
    methods: &[StaticMethodDaf],
    i: usize,
    sigma: f64,
    static_sigma: f64,
    si_per_unit: f64,
    window: &'static str,
) -> Option<DafUncertainty> {
    let chosen = &methods[i];
    let static_max = chosen.static_max * si_per_unit;
    let dynamic_max = chosen.daf * static_max;
    // A measured maximum of 0 in the static direction has no relative noise.
    if dynamic_max == 0.0 || static_max == 0.0 {
        return None;
    }
    let from_noise =
        chosen.daf * ((sigma / dynamic_max).powi(2) + (static_sigma / static_max).powi(2)).sqrt();
    let spread = methods
        .iter()
        .filter(|x| x.valid && !x.chosen)
        .map(|x| (x.daf - chosen.daf).abs())
        .fold(0.0, f64::max);
    let from_static_separation = chosen.bias.map_or(0.0, f64::abs).max(spread);
    let combined = from_noise.hypot(from_static_separation);
    Some(DafUncertainty {
        noise_std: sigma / si_per_unit,
        noise_window: window,
        from_noise,
        from_static_separation,
        combined,
        expanded_95: 2.0 * combined,
    })
    .filter(|u| u.combined.is_finite())
}

/// One sample's noise σ [SI] of `samples` and the window it came from: the quiet window before
/// the vehicle enters when the record holds one (at least 10 samples), else the whole record.
pub(super) fn noise_of(m: &Measurement, samples: &[f64]) -> (f64, &'static str) {
    // Only an entry inside the record leaves a window before it that holds no response.
    if let Some(entry) = m.entry_time.filter(|&t| t <= m.time[m.time.len() - 1]) {
        let end = m.time.partition_point(|&t| t < entry);
        let start = m.time.partition_point(|&t| t < entry - m.baseline_window);
        if end >= start + 10 {
            return (
                second_difference_noise(&samples[start..end]),
                "quiet_window_before_entry",
            );
        }
    }
    (second_difference_noise(samples), "whole_record")
}

/// σ of white noise from second differences: Δ²x_i = x_{i+1} − 2x_i + x_{i−1} has variance
/// 6σ² for white noise, while a signal smooth on the scale of a sample contributes little;
/// σ = √(mean (Δ²x)² / 6). Zero for fewer than three samples.
pub fn second_difference_noise(samples: &[f64]) -> f64 {
    if samples.len() < 3 {
        return 0.0;
    }
    let sum: f64 = samples
        .windows(3)
        .map(|w| (w[2] - 2.0 * w[1] + w[0]).powi(2))
        .sum();
    (sum / (6.0 * (samples.len() - 2) as f64)).sqrt()
}

/// The fraction of white noise's variance that the zero-phase Butterworth low-pass passes:
/// g = (2/f_s)∫₀^{f_s/2} |H(f)|⁴ df (midpoint rule on [`NOISE_GAIN_POINTS`] points; about
/// 0.90·f_c/(f_s/2) for order 4, from ∫₀^∞ dx/(1 + x^{2N})² = (1 − 1/2N)(π/2N)/sin(π/2N)).
pub fn lowpass_noise_gain(
    order: usize,
    cutoff_hz: f64,
    sampling_rate_hz: f64,
) -> Result<f64, SignalError> {
    let filter = butterworth_lowpass(order, cutoff_hz, sampling_rate_hz)?;
    let nyquist = sampling_rate_hz / 2.0;
    let step = nyquist / NOISE_GAIN_POINTS as f64;
    let sum: f64 = (0..NOISE_GAIN_POINTS)
        .map(|k| {
            filter
                .frequency_response((k as f64 + 0.5) * step, sampling_rate_hz)
                .norm_sqr()
                .powi(2)
        })
        .sum();
    Ok(sum / NOISE_GAIN_POINTS as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::road::SampleRng;

    #[test]
    fn second_difference_noise_recovers_white_noise_under_a_slow_signal() {
        // Reference: var(n_{i+1} − 2n_i + n_{i−1}) = (1 + 4 + 1)σ² for independent n_i.
        let mut rng = SampleRng::new(18, 0);
        let samples: Vec<f64> = (0..20_000)
            .map(|i| {
                let t = i as f64 / 200.0;
                // Box–Muller on the seeded stream.
                let (u1, u2) = (1.0 - rng.next_unit(), rng.next_unit());
                let z = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
                (2.0 * std::f64::consts::PI * 0.3 * t).sin() + 0.01 * z
            })
            .collect();
        let sigma = second_difference_noise(&samples);
        // 20 000 samples: the estimate's relative standard error is about 1/√(2·20 000/3.5)
        // ≈ 1 %; 4 % is four of them.
        assert!((sigma / 0.01 - 1.0).abs() < 0.04, "{sigma}");
    }

    #[test]
    fn lowpass_noise_gain_matches_the_butterworth_integral() {
        // Reference: ∫₀^∞ dx/(1 + x^8)² = (7/8)(π/8)/sin(π/8) = 0.89786 for order 4; at
        // f_c ≪ f_s the bilinear warping is negligible (f_c = 2 Hz, f_s = 200 Hz: 0.03 %).
        let gain = lowpass_noise_gain(4, 2.0, 200.0).unwrap();
        let n = 8.0;
        let exact = (1.0 - 1.0 / n) * (std::f64::consts::PI / n) / (std::f64::consts::PI / n).sin()
            * 2.0
            / 100.0;
        assert!((gain / exact - 1.0).abs() < 2e-3, "{gain} against {exact}");
    }
}
