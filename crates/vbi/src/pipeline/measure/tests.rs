//! The measurement stage on records built in the test, whose static part and DAF are known in
//! closed form.

use super::*;
use crate::pipeline::measurement::{Channel, SpectrumSpec};
use crate::signal::{MovingLoads, SampledInfluenceLine};

const RATE_HZ: f64 = 200.0;
const SPEED: f64 = 20.0;
const SPAN: f64 = 30.0;
const AXLE_LOAD: f64 = 100e3;
/// Static mid-span deflection per unit load at mid-span [m/N] (a triangle influence line).
const PEAK_PER_NEWTON: f64 = 1e-7;

/// A triangle influence line of mid-span deflection of a simple span [m/N].
fn mid_span_line() -> SampledInfluenceLine {
    SampledInfluenceLine::new(vec![0.0, SPAN / 2.0, SPAN], vec![0.0, PEAK_PER_NEWTON, 0.0]).unwrap()
}

fn one_axle() -> MovingLoads {
    MovingLoads {
        axle_loads: vec![AXLE_LOAD],
        axle_offsets: vec![0.0],
        speed: SPEED,
        entry_time: 0.5,
    }
}

/// A deflection record: the exact static response of one axle plus a free oscillation of
/// amplitude `amplitude` [m] at 4 Hz while the axle is on the span.
fn record(amplitude: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let count = (3.0 * RATE_HZ) as usize;
    let time: Vec<f64> = (0..count).map(|i| i as f64 / RATE_HZ).collect();
    let line = mid_span_line();
    let loads = one_axle();
    let statics: Vec<f64> = time
        .iter()
        .map(|t| AXLE_LOAD * line.evaluate(SPEED * (t - loads.entry_time)))
        .collect();
    let measured = time
        .iter()
        .zip(&statics)
        .map(|(t, s)| {
            let on_span = *s > 0.0;
            let wave = (2.0 * std::f64::consts::PI * 4.0 * t).sin();
            s + if on_span { amplitude * wave } else { 0.0 }
        })
        .collect();
    (time, statics, measured)
}

fn measurement(time: Vec<f64>, samples: Vec<f64>) -> Measurement {
    Measurement {
        description: None,
        sampling_rate_hz: RATE_HZ,
        time,
        channels: vec![Channel {
            name: "u_mid".into(),
            column: "u_mid".into(),
            kind: MeasuredQuantity::Deflection,
            unit: "m".into(),
            si_per_unit: 1.0,
            samples,
            section: None,
            k1: None,
            moment: None,
            static_reference: Some(mid_span_line()),
            position_in_span: 0.5,
        }],
        speed: Some(SPEED),
        pass_frequency_hz: Some(SPEED / SPAN),
        span_length: Some(SPAN),
        first_frequency_hz: None,
        filter_order: 4,
        cutoff_hz: None,
        spectrum: SpectrumSpec {
            channel: None,
            segment_length: 256,
            fft_length: None,
            modes: 3,
            min_frequency_hz: 0.5,
            max_frequency_hz: 50.0,
            min_prominence_db: 6.0,
            window: None,
            identification: crate::pipeline::measurement::Identification::WelchPeaks,
        },
        vehicle: Some(one_axle()),
        updating: None,
        bridge: None,
        entry_time: None,
        bridge_length: None,
        baseline: crate::pipeline::measurement::Baseline::None,
        baseline_window: 1.0,
        crawl: None,
    }
}

#[test]
fn influence_line_static_reference_gives_the_daf_of_the_record_it_was_built_from() {
    let (time, statics, measured) = record(2e-4);
    let result = measure(&measurement(time, measured.clone())).unwrap();
    let channel = &result.summary.channels[0];
    assert_eq!(channel.static_method, "influence_line");
    // The stage's static part is the record's static part: the same sums in the same order.
    assert_eq!(result.signals[0].static_part, statics);
    let static_max = statics.iter().cloned().fold(f64::MIN, f64::max);
    let dynamic_max = measured.iter().cloned().fold(f64::MIN, f64::max);
    assert_eq!(channel.static_max, static_max);
    assert_eq!(channel.dynamic_max, dynamic_max);
    assert_eq!(channel.daf, dynamic_max / static_max);
    // Sampled at 200 Hz the axle passes mid-span exactly at a sample: 10 mm.
    assert!((static_max - AXLE_LOAD * PEAK_PER_NEWTON).abs() < 1e-15);
}

#[test]
fn a_record_without_dynamic_part_has_a_daf_of_one() {
    // The static limit: a measured signal equal to its static part.
    let (time, _, measured) = record(0.0);
    let result = measure(&measurement(time, measured)).unwrap();
    assert_eq!(result.summary.channels[0].daf, 1.0);
}

#[test]
fn an_influence_line_without_axle_loads_is_refused_naming_the_vehicle() {
    let (time, _, measured) = record(0.0);
    let mut m = measurement(time, measured);
    m.vehicle = None;
    match measure(&m) {
        Err(MeasureError::Input { field, message }) => {
            assert_eq!(field, "vehicle");
            assert!(message.contains("u_mid"), "{message}");
        }
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn a_channel_of_another_length_than_the_time_axis_is_refused() {
    let (time, _, mut measured) = record(0.0);
    measured.pop();
    match measure(&measurement(time, measured)) {
        Err(MeasureError::Input { field, .. }) => assert_eq!(field, "channels"),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn a_low_pass_without_pass_or_given_cutoff_is_refused_naming_the_cutoff() {
    let (time, _, measured) = record(0.0);
    let mut m = measurement(time, measured);
    m.channels[0].static_reference = None;
    m.pass_frequency_hz = None;
    match measure(&m) {
        Err(MeasureError::Input { field, .. }) => assert_eq!(field, "filter.cutoff_hz"),
        other => panic!("expected an input error, got {other:?}"),
    }
}
