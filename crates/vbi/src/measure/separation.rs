//! The static separation: one zero-phase low-pass cut-off for every channel without an
//! influence-line static reference, given or chosen from the pass and first bridge frequencies.

use super::{ChannelDaf, IdentifiedMode, MeasureError, StaticSeparation};
use crate::measure::measurement::Measurement;
use crate::signal::{automatic_cutoff, CutoffChoice, CutoffRule, QUASI_STATIC_HARMONICS};

/// The low-pass static separation, when a DAF channel has neither an influence-line nor a
/// crawl-run reference; `first` is the first bridge frequency ([`first_frequency`]).
pub(super) fn static_separation(
    m: &Measurement,
    first: Option<f64>,
) -> Result<Option<StaticSeparation>, MeasureError> {
    let needs_lowpass = m
        .channels
        .iter()
        .any(|c| c.has_daf() && c.static_reference.is_none() && m.crawl.is_none());
    if !needs_lowpass {
        return Ok(None);
    }
    let cutoff = match m.cutoff_hz {
        Some(f) => CutoffChoice {
            cutoff_hz: f,
            pass_frequency_hz: m.pass_frequency_hz,
            quasi_static_limit_hz: None,
            first_frequency_hz: first,
            rule: CutoffRule::Given,
            separated: true,
        },
        None => automatic(m, first)?,
    };
    Ok(Some(StaticSeparation {
        filter: "butterworth_zero_phase",
        filter_order: m.filter_order,
        explanation: explanation(&cutoff),
        reason: String::new(),
        cutoff,
    }))
}

/// The low-pass cut-off that the comparison of static methods uses for a channel whatever its
/// own method [Hz], and whether its rule finds the quasi-static and the dynamic content apart:
/// the given cut-off (taken as separated), else the automatic one when the pass and first
/// frequencies are known.
pub(super) fn comparison_cutoff(m: &Measurement, first: Option<f64>) -> Option<(f64, bool)> {
    match m.cutoff_hz {
        Some(f) => Some((f, true)),
        None => automatic(m, first).ok().map(|c| (c.cutoff_hz, c.separated)),
    }
}

/// The verdict of the static separation: separated only when the cut-off rule finds the
/// quasi-static and the dynamic content apart (or the cut-off was given) and every low-pass
/// channel passed its separation check; the reason names what failed or was not checked.
pub(super) fn conclude(separation: &mut StaticSeparation, channels: &[ChannelDaf]) {
    let mut reasons = Vec::new();
    let mut separated = separation.cutoff.separated;
    if !separated {
        reasons.push(
            "the quasi-static content of the crossing reaches half the first bridge frequency"
                .to_string(),
        );
    }
    for c in channels.iter().filter(|c| c.static_method == "low_pass") {
        match &c.separation_check {
            Some(check) => {
                separated &= check.separated;
                reasons.push(format!("{}: {}", c.name, check.reason));
            }
            None => {
                separated = false;
                reasons.push(format!(
                    "{}: not checked (give span_length_m and the speed)",
                    c.name
                ));
            }
        }
    }
    separation.cutoff.separated = separated;
    separation.reason = reasons.join("; ");
}

/// The first bridge frequency [Hz]: given, else the first identified one, else the model's
/// first vertical bending mode.
pub(super) fn first_frequency(
    m: &Measurement,
    identified: &[IdentifiedMode],
    model_first_bending_hz: Option<f64>,
) -> Option<f64> {
    m.first_frequency_hz
        .or(identified.first().map(|p| p.frequency_hz))
        .or(model_first_bending_hz)
}

/// The automatic cut-off from the pass frequency and the first bridge frequency.
fn automatic(m: &Measurement, first: Option<f64>) -> Result<CutoffChoice, MeasureError> {
    let pass = m.pass_frequency_hz.ok_or_else(|| {
        MeasureError::input(
            "filter.cutoff_hz",
            "the static cut-off cannot be chosen: give filter.cutoff_hz, or the crossing (speed_kmh and bridge_length_m, or pass_duration_s) and the first bridge frequency",
        )
    })?;
    let first = first.ok_or_else(|| {
        MeasureError::input(
            "first_frequency_hz",
            "the static cut-off needs the first bridge frequency: give first_frequency_hz, or an acceleration channel whose spectrum shows a peak, or a bridge model, or filter.cutoff_hz",
        )
    })?;
    let choice = automatic_cutoff(pass, first)
        .map_err(|e| MeasureError::input("first_frequency_hz", e.to_string()))?;
    if choice.cutoff_hz >= m.sampling_rate_hz / 2.0 {
        return Err(MeasureError::input(
            "filter.cutoff_hz",
            format!(
                "the automatic cut-off {} Hz is above the Nyquist frequency; give filter.cutoff_hz",
                choice.cutoff_hz
            ),
        ));
    }
    Ok(choice)
}

/// The rule that chose the cut-off, in words.
fn explanation(cutoff: &CutoffChoice) -> String {
    let quasi_static = cutoff.quasi_static_limit_hz.unwrap_or(f64::NAN);
    match cutoff.rule {
        CutoffRule::Given => format!("cut-off {} Hz given in the input", cutoff.cutoff_hz),
        CutoffRule::GeometricMean => format!(
            "f_c = sqrt(f_q * f_1) = sqrt({:.4} * {:.4}) = {:.4} Hz, with f_q = {} * v/L the quasi-static limit and f_1 the first bridge frequency",
            quasi_static,
            cutoff.first_frequency_hz.unwrap_or(f64::NAN),
            cutoff.cutoff_hz,
            QUASI_STATIC_HARMONICS
        ),
        CutoffRule::HalfFirstFrequency if cutoff.separated => format!(
            "f_c = f_1/2 = {:.4} Hz: the geometric mean sqrt(f_q * f_1) of the quasi-static limit f_q = {:.4} Hz and f_1 lies above f_1/2, and the cap keeps the first mode attenuated (f_q is still below f_1/2)",
            cutoff.cutoff_hz, quasi_static
        ),
        CutoffRule::HalfFirstFrequency => format!(
            "f_c = f_1/2 = {:.4} Hz because the quasi-static limit f_q = {:.4} Hz reaches f_1/2: quasi-static and dynamic content overlap, the static part is distorted",
            cutoff.cutoff_hz, quasi_static
        ),
    }
}
