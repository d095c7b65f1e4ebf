//! The measurement stage on records built in the test, whose static part and DAF are known in
//! closed form.

use super::*;
use crate::measure::measurement::{Channel, SpectrumSpec, SpectrumWindow, StaticReference};
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

/// A record of one mid-span deflection channel with a given triangle influence line, sampled at
/// 200 Hz, of one axle at 20 m/s over a 30 m span (shared with the sibling modules' tests).
pub(super) fn measurement(time: Vec<f64>, samples: Vec<f64>) -> Measurement {
    Measurement {
        description: None,
        sampling_rate_hz: RATE_HZ,
        resampled_from_hz: None,
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
            static_reference: Some(StaticReference::Given(mid_span_line())),
            position_in_span: 0.5,
            location: None,
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
            identification: crate::measure::measurement::Identification::WelchPeaks,
        },
        vehicle: Some(one_axle()),
        updating: None,
        bridge: None,
        entry_time: None,
        detect_entry: false,
        detect_entry_by_default: false,
        weighing: None,
        vehicle_frequencies_hz: Vec::new(),
        vehicle_track: Default::default(),
        bridge_length: None,
        baseline: crate::measure::measurement::Baseline::None,
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

/// A record of the three-axle truck of the paper's load tests crossing a 30 m span at 20 m/s,
/// entering at `entry` [s]: the static mid-span deflection of the simply supported shape, a
/// logger offset and drift, a 3.6 Hz vibration of 5 % of the peak while the truck is on, and
/// seeded noise of 0.2 % of the peak.
fn truck_record(entry: f64) -> (Measurement, MovingLoads) {
    let count = (12.0 * RATE_HZ) as usize;
    let time: Vec<f64> = (0..count).map(|i| i as f64 / RATE_HZ).collect();
    let loads = MovingLoads {
        axle_loads: vec![78.12e3, 139.20e3, 135.84e3],
        axle_offsets: vec![0.0, 3.8, 5.15],
        speed: SPEED,
        entry_time: entry,
    };
    let line = crate::signal::InfluenceShape::Deflection { position: 0.5 }.influence_line(SPAN);
    let statics = crate::signal::static_from_influence_line(&time, &line, &loads).unwrap();
    let peak = statics.iter().cloned().fold(0.0, f64::max);
    let mut rng = crate::road::SampleRng::new(20261204, 0);
    let samples = time
        .iter()
        .zip(&statics)
        .map(|(t, s)| {
            let (u1, u2) = (1.0 - rng.next_unit(), rng.next_unit());
            let z = (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos();
            let wave = if *s > 0.0 {
                0.05 * peak * (2.0 * std::f64::consts::PI * 3.6 * t).sin()
            } else {
                0.0
            };
            -(s + wave) * 1e-3 + 2e-4 + 1e-5 * t + 0.002 * peak * 1e-3 * z
        })
        .collect();
    let mut m = measurement(time, samples);
    m.speed = Some(SPEED);
    m.span_length = Some(SPAN);
    m.detect_entry = true;
    (m, loads)
}

#[test]
fn the_entry_time_found_in_a_record_with_drift_and_vibration_is_the_simulated_one() {
    // Reference: the record is built with the truck entering at 3.217 s. With its axle loads
    // and offsets known, the fit of the predicted static shape finds the entry within one
    // sample (5 ms); with one axle assumed, within the time its load centroid takes to pass
    // (the centroid lies 3.5 m behind the front axle: 0.17 s at 20 m/s).
    let entry = 3.217;
    let (mut m, loads) = truck_record(entry);
    m.vehicle = Some(MovingLoads {
        entry_time: 0.0,
        ..loads
    });
    let found = detect_entry(&m).expect("found");
    assert!(
        (found.entry_time_s - entry).abs() <= 1.0 / RATE_HZ,
        "{found:?}"
    );
    assert!(found.explained_variance > 0.9, "{found:?}");
    m.vehicle = None;
    let found = detect_entry(&m).expect("found");
    let centroid_delay = 3.5 / SPEED;
    assert!(
        found.entry_time_s > entry && found.entry_time_s < entry + 1.2 * centroid_delay,
        "{found:?}"
    );
}

#[test]
fn a_speed_in_m_s_given_as_km_h_is_warned_about_and_the_true_speed_is_not() {
    // Reference: the record is built at 20 m/s (72 km/h). Stated as 20 m/s, the fitted speed is
    // within 3 % with the truck's axles known and the check passes; stated as 20 km/h (the m/s
    // value typed into speed_kmh), the fit still finds about 20 m/s and measure warns, naming
    // the likely mistake. Tolerances: the fine grid is 0.6 % wide; noise, drift and the 5 %
    // vibration move the best fit by a few per cent.
    let (mut m, loads) = truck_record(3.217);
    m.vehicle = Some(MovingLoads {
        entry_time: 0.0,
        ..loads
    });
    m.detect_entry = false;
    m.entry_time = Some(3.217);
    let check = check_speed(&m).expect("checked");
    assert!(check.plausible, "{check:?}");
    assert!(
        (check.fitted_speed_m_s / SPEED - 1.0).abs() < 0.03,
        "{check:?}"
    );
    m.speed = Some(SPEED / 3.6);
    let check = check_speed(&m).expect("checked");
    assert!(!check.plausible, "{check:?}");
    assert!(
        (check.fitted_speed_m_s / SPEED - 1.0).abs() < 0.03,
        "{check:?}"
    );
    let result = measure(&m).expect("measured");
    let warning = (result.summary.warnings.iter())
        .find(|w| {
            matches!(
                w.kind,
                warnings::MeasureWarningKind::ImplausibleSpeed { .. }
            )
        })
        .expect("the speed is warned about");
    assert!(
        warning
            .message
            .contains("a speed in m/s given as speed_kmh?"),
        "{warning}"
    );
}

#[test]
fn a_record_without_a_crossing_gives_no_entry_time_and_measure_says_which_key_to_give() {
    // Reference: noise alone explains nothing; the stage refuses at `entry_time_s` rather than
    // guessing a window.
    let (mut m, _) = truck_record(3.0);
    let mut rng = crate::road::SampleRng::new(7, 0);
    m.channels[0].samples = (0..m.time.len()).map(|_| rng.next_unit() - 0.5).collect();
    assert!(detect_entry(&m).is_none());
    match measure(&m) {
        Err(MeasureError::Input { field, .. }) => assert_eq!(field, "entry_time_s"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_uncertainty_of_a_daf_with_an_exact_influence_line_is_the_noise_alone() {
    // Reference: GUM propagation for DAF = D/S with an exact (noise-free) static reference:
    // u = DAF·σ/D. The record's noise is σ = 0.2 % of the static peak; the quiet 2 s before
    // entry (400 samples, a relative standard error of the estimate of about 7 %) give σ back
    // within 20 %.
    let entry = 3.0;
    let (mut m, loads) = truck_record(entry);
    m.detect_entry = false;
    m.entry_time = Some(entry);
    m.bridge_length = Some(SPAN);
    m.baseline = crate::measure::measurement::Baseline::Linear;
    m.baseline_window = 2.0;
    let line = crate::signal::InfluenceShape::Deflection { position: 0.5 }.influence_line(SPAN);
    let statics = crate::signal::static_from_influence_line(&m.time, &line, &loads).unwrap();
    let static_peak = statics.iter().cloned().fold(0.0, f64::max) * 1e-3;
    m.vehicle = Some(loads);
    // The record is −(static + vibration)·1e-3 m per unit of the shape under loads in N.
    m.channels[0].static_reference = Some(StaticReference::Given(SampledInfluenceLine {
        positions: line.positions.clone(),
        values: line.values.iter().map(|v| -v * 1e-3).collect(),
    }));
    let result = measure(&m).unwrap();
    let channel = &result.summary.channels[0];
    assert_eq!(channel.static_method, "influence_line");
    assert!((channel.static_max.abs() / static_peak - 1.0).abs() < 1e-12);
    let u = channel.uncertainty.as_ref().expect("an uncertainty");
    assert_eq!(u.noise_window, "quiet_window_before_entry");
    let sigma = 0.002 * static_peak;
    assert!(
        (u.noise_std / sigma - 1.0).abs() < 0.2,
        "{u:?} against {sigma}"
    );
    let chosen: Vec<&StaticMethodDaf> =
        channel.static_methods.iter().filter(|x| x.chosen).collect();
    assert_eq!(chosen.len(), 1);
    assert_eq!(chosen[0].method, "influence_line");
    assert_eq!(chosen[0].daf, channel.daf);
    let expected = channel.daf * u.noise_std / channel.dynamic_max.abs();
    assert!((u.from_noise / expected - 1.0).abs() < 1e-12, "{u:?}");
    // No other method: without a first frequency no low-pass is chosen, so the separation
    // adds nothing.
    assert_eq!(
        u.from_static_separation, 0.0,
        "{:?}",
        channel.static_methods
    );
    assert!((u.combined - u.from_noise).abs() < 1e-15);
}

#[test]
fn a_vehicle_frequency_given_keeps_the_vehicles_bounce_out_of_the_bridge_modes() {
    // Reference: the new-user record, in closed form: an acceleration of the truck's
    // body bounce at 1.57 Hz (forced, strongest, while it crosses) and the bridge's first mode
    // at 3.83 Hz, with no free vibration recorded. Without the vehicle's frequency the Welch
    // peaks take 1.57 Hz as the first mode; with it (±5 %) the bounce is listed apart and the
    // first mode is 3.83 Hz within one bin.
    let count = (40.0 * RATE_HZ) as usize;
    let time: Vec<f64> = (0..count).map(|i| i as f64 / RATE_HZ).collect();
    let tau = 2.0 * std::f64::consts::PI;
    let samples: Vec<f64> = time
        .iter()
        .map(|t| 0.05 * (tau * 1.57 * t).sin() + 0.02 * (tau * 3.83 * t).sin())
        .collect();
    let mut m = measurement(time, samples);
    m.channels[0].kind = MeasuredQuantity::Acceleration;
    m.spectrum.modes = 1;
    m.spectrum.segment_length = 2048;
    m.spectrum.min_frequency_hz = 1.0;
    m.spectrum.max_frequency_hz = 10.0;
    m.spectrum.identification = crate::measure::measurement::Identification::WelchPeaks;
    let first = |m: &Measurement| {
        let result = measure(m).unwrap();
        assert!(
            !result.summary.identified_frequencies.is_empty(),
            "{:?}",
            result.summary.spectra
        );
        (
            result.summary.identified_frequencies[0].frequency_hz,
            result.summary.vehicle_modes.len(),
        )
    };
    let (f, excluded) = first(&m);
    assert!((f - 1.57).abs() < 0.05 && excluded == 0, "{f}");
    m.vehicle_frequencies_hz = vec![1.6];
    let (f, excluded) = first(&m);
    assert!((f - 3.83).abs() < 0.05 && excluded == 1, "{f}");
}

/// The new-user record with its crossing and what follows: the truck's body bounce at
/// 1.57 Hz (0.05 m/s²) and the bridge's first mode at 3.83 Hz (0.02 m/s²) while it crosses
/// (5 s to 25 s), then the bridge mode's free decay at 3 % damping, and white noise of
/// 0.0005 m/s² throughout (fixed-seed ChaCha).
fn record_with_a_forced_bounce() -> Measurement {
    use rand_core::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let mut noise =
        || 0.0005 * 3f64.sqrt() * (2.0 * (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 1.0);
    let (entry, exit) = (5.0, 25.0);
    let count = (40.0 * RATE_HZ) as usize;
    let time: Vec<f64> = (0..count).map(|i| i as f64 / RATE_HZ).collect();
    let tau = 2.0 * std::f64::consts::PI;
    let samples: Vec<f64> = time
        .iter()
        .map(|&t| {
            let bridge = 0.02 * (tau * 3.83 * t).sin();
            let signal = if t < entry {
                0.0
            } else if t < exit {
                0.05 * (tau * 1.57 * t).sin() + bridge
            } else {
                bridge * (-0.03 * tau * 3.83 * (t - exit)).exp()
            };
            signal + noise()
        })
        .collect();
    let mut m = measurement(time, samples);
    m.channels[0].kind = MeasuredQuantity::Acceleration;
    m.channels[0].static_reference = None;
    // One axle at 1.5 m/s over 30 m: in at 5 s, out at 25 s.
    m.speed = Some(1.5);
    m.vehicle = Some(MovingLoads {
        speed: 1.5,
        entry_time: entry,
        ..one_axle()
    });
    m.entry_time = Some(entry);
    m.bridge_length = Some(SPAN);
    m.spectrum.modes = 1;
    m.spectrum.segment_length = 2048;
    m.spectrum.min_frequency_hz = 1.0;
    m.spectrum.max_frequency_hz = 10.0;
    m.spectrum.identification = crate::measure::measurement::Identification::WelchPeaks;
    m.spectrum.window = Some(SpectrumWindow::Whole);
    m
}

#[test]
fn the_crossings_forced_bounce_is_recognised_without_the_vehicles_frequencies() {
    // Reference: the closed-form record above. The Welch peaks of the whole record hold the
    // bounce (strongest) and the bridge mode; the bounce stops when the truck leaves and the
    // mode rings on (its amplitude after one second is e^(−0.03·2π·3.83) = 49 % of its
    // amplitude while crossing, the bounce's the noise's, 1 %): the bounce is moved to
    // forced_modes and the first mode is 3.83 Hz within one bin (0.1 Hz).
    let result = measure(&record_with_a_forced_bounce()).unwrap();
    let s = &result.summary;
    assert_eq!(s.forced_content_check, ForcedContentCheck::Checked);
    assert_eq!(s.identified_frequencies.len(), 1, "{:?}", s.spectra);
    assert!((s.identified_frequencies[0].frequency_hz - 3.83).abs() < 0.1);
    assert_eq!(s.forced_modes.len(), 1, "{:?}", s.forced_modes);
    assert!((s.forced_modes[0].frequency_hz - 1.57).abs() < 0.1);
}

#[test]
fn forced_content_is_not_looked_for_in_the_free_vibration_and_cannot_be_without_the_exit() {
    // The free vibration alone (ERA from the exit, the automatic choice with 15 s of it) holds
    // no forced content; a record without its exit time cannot be checked, and says so.
    let mut m = record_with_a_forced_bounce();
    m.spectrum.window = None;
    m.spectrum.identification = crate::measure::measurement::Identification::Automatic;
    let result = measure(&m).unwrap();
    assert_eq!(
        result.summary.forced_content_check,
        ForcedContentCheck::NotNeeded
    );
    assert!((result.summary.identified_frequencies[0].frequency_hz - 3.83).abs() < 0.1);
    let mut m = record_with_a_forced_bounce();
    m.bridge_length = None;
    let result = measure(&m).unwrap();
    assert_eq!(
        result.summary.forced_content_check,
        ForcedContentCheck::NotPossible
    );
    assert!((result.summary.identified_frequencies[0].frequency_hz - 1.57).abs() < 0.1);
}

#[test]
fn the_automatic_baseline_is_a_line_through_both_quiet_windows_when_the_record_has_them() {
    // Reference: a drift of 1 % of the static peak per second added to the record, which goes
    // on 7 s past the exit (entry 3 s, 35.15 m at 20 m/s): the automatic baseline is the line
    // through the 1 s windows before entry and at the end, 9 s apart, and gives the drift back
    // within four standard errors of the slope, 4·√2·σ/(√200·9 s), σ = 0.2 % of the static
    // peak (truck_record's noise). Without the bridge length the exit, and so the end window,
    // is unknown: an offset.
    let entry = 3.0;
    let (mut m, loads) = truck_record(entry);
    let peak = m.channels[0]
        .samples
        .iter()
        .fold(0.0_f64, |a, &x| a.max((x - 2e-4).abs()));
    let drift = 0.01 * peak;
    for (x, t) in m.channels[0].samples.iter_mut().zip(&m.time) {
        *x += drift * t;
    }
    m.detect_entry = false;
    m.entry_time = Some(entry);
    m.vehicle = Some(loads);
    m.bridge_length = Some(SPAN);
    m.first_frequency_hz = Some(3.6);
    m.baseline = measurement::Baseline::Automatic;
    let result = measure(&m).unwrap();
    let preparation = &result.summary.preparation;
    assert_eq!(preparation.baseline, measurement::Baseline::Linear);
    let found = preparation.corrections[0].drift_per_s;
    let sigma = 0.002 * peak;
    let tolerance = 4.0 * 2f64.sqrt() * sigma / (200f64.sqrt() * 9.0);
    assert!(
        (found - drift).abs() < tolerance,
        "{found} against {drift} ± {tolerance}"
    );
    m.bridge_length = None;
    let result = measure(&m).unwrap();
    assert_eq!(
        result.summary.preparation.baseline,
        measurement::Baseline::Offset
    );
    assert_eq!(result.summary.preparation.corrections[0].drift_per_s, 0.0);
}
