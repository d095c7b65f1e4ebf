//! The design codes' dynamic allowances beside a measured DAF: what each code would have a
//! designer assume at the gauge's section, read with the measured frequencies (the codes that
//! take the fundamental frequency) and the bridge model's spans and section when one is named.

use super::IdentifiedMode;
use crate::codes::{factors_at, whole_section, CodeImpactFactor, CodeInputs, CodeLocation};
use crate::fe::Quantity;
use crate::measure::measurement::{Channel, Measurement};
use crate::signal::MeasuredQuantity;

/// The code factors of a DAF channel, or none when the loaded span is unknown. The gauge is
/// taken to lie in the first span at its `position_in_span` (the loaded span of a load test);
/// the spans are the bridge model's, else `bridge_length / span_length` equal spans when that
/// is a whole number, else the loaded span alone.
pub(super) fn channel_codes(
    m: &Measurement,
    c: &Channel,
    identified: &[IdentifiedMode],
) -> Vec<CodeImpactFactor> {
    let Some(inputs) = code_inputs(m, identified) else {
        return Vec::new();
    };
    let quantity = match c.kind {
        MeasuredQuantity::Deflection => Quantity::Deflection,
        _ => Quantity::BendingMoment,
    };
    let location = CodeLocation::in_span(&inputs, 0, c.position_in_span);
    factors_at(&inputs, location, quantity)
}

/// What the codes need, from the measurement.
fn code_inputs(m: &Measurement, identified: &[IdentifiedMode]) -> Option<CodeInputs> {
    let model = m.bridge.as_ref().map(|b| &b.model);
    let span_lengths = match (model, m.span_length, m.bridge_length) {
        (Some(model), _, _) => model.span_lengths().to_vec(),
        (None, Some(span), Some(length)) => {
            let count = (length / span).round();
            // Equal spans when the length is a whole number of them (at most 100 spans).
            if (1.0..=100.0).contains(&count) && (count * span - length).abs() <= 1e-6 * length {
                vec![span; count as usize]
            } else {
                vec![span]
            }
        }
        (None, Some(span), None) => vec![span],
        (None, None, _) => return None,
    };
    let mut bending_frequencies: Vec<f64> = identified.iter().map(|p| p.frequency_hz).collect();
    if bending_frequencies.is_empty() {
        bending_frequencies.extend(m.first_frequency_hz);
    }
    Some(CodeInputs {
        line_offsets: Vec::new(),
        section: model.and_then(|model| whole_section(model).ok()),
        span_lengths,
        bending_frequencies,
        measured_frequencies: true,
        axle_count: m.vehicle.as_ref().map_or(0, |v| v.axle_loads.len()),
        psd_at_reference: None,
    })
}
