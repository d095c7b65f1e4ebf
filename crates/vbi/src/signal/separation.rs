//! Whether a low-pass separates the static part of a crossing from its dynamic part, checked
//! against the frequency content of the influence line.
//!
//! A static response R_s(t) = Σ_a P_a·IL(v·(t − t₀) − d_a) holds the spectrum of the influence
//! line read at speed v. A deflection influence line is smooth: its content falls off fast above
//! the pass frequency v/L. A bending-moment influence line has a kink under the section: its
//! spectrum falls off only as 1/f², so a low-pass below the first bridge frequency rounds the
//! peak of the static moment and biases its DAF upwards. The check filters the predicted static
//! response with the very filter used on the record and reports the relative error of its
//! peak: the DAF's relative error from the separation alone.

use serde::{Deserialize, Serialize};

use super::filter::butterworth_lowpass;
use super::measured::{static_from_influence_line, MovingLoads, SampledInfluenceLine};
use super::SignalError;

/// Largest relative error of the static peak for which the low-pass separation counts as
/// separated: 0.5 % of the static maximum moves a DAF of about 1.1 by 0.0055, half of the
/// 0.01 to which a measured DAF is wanted.
pub const SEPARATION_PEAK_TOLERANCE: f64 = 0.005;

/// Samples per span of the shape influence lines (enough that linear interpolation between
/// them is exact to 1e-5 of the peak for the cubic deflection line).
const SHAPE_SAMPLES: usize = 401;

/// The shape of a station's influence line, by quantity, on the loaded span (simply supported:
/// the shape that sets the frequency content; continuity changes the ordinates little near
/// mid-span and adds small lobes in the other spans).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InfluenceShape {
    /// Deflection at `position` (fraction of the span) of a simply supported span: the cubic
    /// δ(x) = x·b·(L² − b² − x²)/(6L) for x ≤ a (b = L − a), mirrored beyond a. Smooth.
    Deflection {
        /// Section position as a fraction of the span, 0 to 1 exclusive.
        position: f64,
    },
    /// Bending moment at `position`: the triangle x·b/L for x ≤ a, a·(L − x)/L beyond, with its
    /// kink under the section.
    BendingMoment {
        /// Section position as a fraction of the span, 0 to 1 exclusive.
        position: f64,
    },
}

impl InfluenceShape {
    /// The influence line on a span of `span_length` [m] from x = 0 to L, scaled to a peak of
    /// one.
    pub fn influence_line(&self, span_length: f64) -> SampledInfluenceLine {
        let l = span_length;
        let (a, moment) = match *self {
            Self::Deflection { position } => (position * l, false),
            Self::BendingMoment { position } => (position * l, true),
        };
        let b = l - a;
        let ordinate = |x: f64| -> f64 {
            // Symmetric in (x, a) <-> (L − x, L − a): evaluate the left branch on the mirror.
            let (x, b) = if x <= a { (x, b) } else { (l - x, a) };
            if moment {
                x * b / l
            } else {
                x * b * (l * l - b * b - x * x) / (6.0 * l)
            }
        };
        let positions: Vec<f64> = (0..SHAPE_SAMPLES)
            .map(|i| l * i as f64 / (SHAPE_SAMPLES - 1) as f64)
            .collect();
        let mut values: Vec<f64> = positions.iter().map(|&x| ordinate(x)).collect();
        let peak = values.iter().cloned().fold(0.0, f64::max);
        values.iter_mut().for_each(|v| *v /= peak);
        SampledInfluenceLine { positions, values }
    }

    /// The shape's name in outputs.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Deflection { .. } => "deflection",
            Self::BendingMoment { .. } => "bending_moment",
        }
    }
}

/// The outcome of the separation check of one channel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeparationCheck {
    /// The influence-line shape checked (`deflection` or `bending_moment`).
    pub shape: String,
    /// Relative error of the predicted static peak after the low-pass, (max_filtered − max)/max
    /// [-]; positive when the filter raises it, negative when it rounds it off.
    pub peak_error: f64,
    /// |peak_error| ≤ [`SEPARATION_PEAK_TOLERANCE`].
    pub separated: bool,
    /// Why, in words.
    pub reason: String,
}

/// Filters the static response that `shape` predicts on a span of `span_length` [m] under
/// `loads` (its axle loads and offsets at its speed) with the zero-phase Butterworth low-pass of
/// `order` at `cutoff_hz`, sampled at `sampling_rate_hz`, and compares the peaks.
pub fn check_separation(
    shape: InfluenceShape,
    span_length: f64,
    loads: &MovingLoads,
    sampling_rate_hz: f64,
    order: usize,
    cutoff_hz: f64,
) -> Result<SeparationCheck, SignalError> {
    let line = shape.influence_line(span_length);
    // The crossing with a quiet lead and tail of 20 % of the crossing time each side, enough
    // for the filter's edge transients to die out before the response starts.
    let length = span_length + loads.axle_offsets.iter().cloned().fold(0.0, f64::max);
    let crossing_time = length / loads.speed;
    let lead = 0.2 * crossing_time + 4.0 / cutoff_hz;
    let count = ((crossing_time + 2.0 * lead) * sampling_rate_hz).ceil() as usize + 1;
    let times: Vec<f64> = (0..count).map(|i| i as f64 / sampling_rate_hz).collect();
    let at_speed = MovingLoads {
        entry_time: lead,
        ..loads.clone()
    };
    let predicted = static_from_influence_line(&times, &line, &at_speed)?;
    let filtered =
        butterworth_lowpass(order, cutoff_hz, sampling_rate_hz)?.filtfilt(&predicted, None)?;
    let peak = predicted.iter().cloned().fold(f64::MIN, f64::max);
    let filtered_peak = filtered.iter().cloned().fold(f64::MIN, f64::max);
    let peak_error = (filtered_peak - peak) / peak;
    let separated = peak_error.abs() <= SEPARATION_PEAK_TOLERANCE;
    let percent = 100.0 * peak_error;
    let limit = 100.0 * SEPARATION_PEAK_TOLERANCE;
    // A static peak scaled by (1 + e) scales the DAF by 1/(1 + e).
    let daf_bias = 100.0 * (1.0 / (1.0 + peak_error) - 1.0);
    let reason = if separated {
        format!(
            "the low-pass at {cutoff_hz:.3} Hz changes the peak of the predicted static {} response by {percent:+.2} % (limit ±{limit} %)",
            shape.name()
        )
    } else {
        format!(
            "the low-pass at {cutoff_hz:.3} Hz changes the peak of the predicted static {} response by {percent:+.2} % (limit ±{limit} %): the static part is distorted and the DAF biased by about {daf_bias:+.1} %; use an influence-line static reference or a crawl run",
            shape.name()
        )
    };
    Ok(SeparationCheck {
        shape: shape.name().to_string(),
        peak_error,
        separated,
        reason,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one_axle(speed: f64) -> MovingLoads {
        MovingLoads {
            axle_loads: vec![1.0],
            axle_offsets: vec![0.0],
            speed,
            entry_time: 0.0,
        }
    }

    #[test]
    fn shape_lines_match_the_simple_beam_closed_forms() {
        // Mid-span deflection under a load at L/4: x·b·(L² − b² − x²)/(6L) with x = L/4,
        // b = L/2 over the peak L³/48: (L/4)(L/2)(L² − L²/4 − L²/16)/(6L) / (L³/48) = 11/16.
        let line = InfluenceShape::Deflection { position: 0.5 }.influence_line(30.0);
        assert!((line.evaluate(7.5) - 11.0 / 16.0).abs() < 1e-12);
        assert!((line.evaluate(22.5) - 11.0 / 16.0).abs() < 1e-12);
        // Mid-span moment: the triangle, 1/2 at L/4.
        let line = InfluenceShape::BendingMoment { position: 0.5 }.influence_line(30.0);
        assert!((line.evaluate(7.5) - 0.5).abs() < 1e-12);
        assert_eq!(line.evaluate(15.0), 1.0);
    }

    /// The check of `shape` on a 30 m span under one axle at `speed`, at 200 Hz, order 4,
    /// cut-off 1.81 Hz (f₁/2 of a 3.62 Hz bridge).
    fn check_at(shape: InfluenceShape, speed: f64) -> SeparationCheck {
        check_separation(shape, 30.0, &one_axle(speed), 200.0, 4, 1.81).unwrap()
    }

    #[test]
    fn a_slow_crossing_is_separated_and_a_fast_kinked_one_is_not() {
        // A crawl at 1 m/s has content far below the cut-off; the mid-span moment at 20 m/s
        // (f_p = 0.67 Hz) has its kink rounded off.
        let moment = InfluenceShape::BendingMoment { position: 0.5 };
        let crawl = check_at(moment, 1.0);
        assert!(crawl.separated, "{crawl:?}");
        let fast = check_at(moment, 20.0);
        assert!(!fast.separated, "{fast:?}");
        assert!(fast.peak_error < -0.01, "{fast:?}");
        // The smooth deflection line at the same speed loses far less of its peak.
        let deflection = check_at(InfluenceShape::Deflection { position: 0.5 }, 20.0);
        assert!(deflection.peak_error.abs() < fast.peak_error.abs() / 3.0);
    }
}
