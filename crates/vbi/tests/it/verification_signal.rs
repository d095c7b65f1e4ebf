//! Verification of the `signal` stage: filters against their closed-form responses, spectra
//! against known signals, DAF and model updating against synthetic data with known answers.

use std::f64::consts::PI;

use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use vbi::modal::ModeKind;
use vbi::signal::*;

/// Standard normal deviates by Box–Muller from a seeded ChaCha8 stream.
fn normal_noise(seed: u64, n: usize) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut uniform = || ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
    (0..n)
        .map(|_| {
            let (u1, u2) = (uniform(), uniform());
            (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
        })
        .collect()
}

#[test]
fn butterworth_order_two_matches_the_closed_form_bilinear_coefficients() {
    // Reference: bilinear transform of ω²/(s² + √2 ω s + ω²) with pre-warping, K = tan(πf_c/f_s):
    // b = K²/(1 + √2K + K²)·[1, 2, 1], a = [1, 2(K² − 1), 1 − √2K + K²]/(1 + √2K + K²)
    // (closed form; scipy.signal.butter(2, f_c, fs=f_s, output='sos') gives the same numbers).
    for (fc, fs) in [(10.0, 200.0), (2.0, 200.0), (40.0, 100.0)] {
        let k: f64 = (PI * fc / fs).tan();
        let norm = 1.0 + 2f64.sqrt() * k + k * k;
        let b0 = k * k / norm;
        let expected = [
            b0,
            2.0 * b0,
            b0,
            1.0,
            2.0 * (k * k - 1.0) / norm,
            (1.0 - 2f64.sqrt() * k + k * k) / norm,
        ];
        let f = butterworth_lowpass(2, fc, fs).unwrap();
        assert_eq!(f.len(), 1);
        for (a, b) in f.sections[0].iter().zip(expected) {
            // A dozen complex operations of round-off.
            assert!((a - b).abs() < 1e-13, "{:?} vs {expected:?}", f.sections[0]);
        }
    }
}

#[test]
fn butterworth_magnitude_is_the_closed_form_and_half_power_at_the_cutoff() {
    // Reference: the bilinear Butterworth magnitude |H(f)|² = 1/(1 + (tan(πf/f_s)/tan(πf_c/f_s))^{2N})
    // (closed form), hence |H(f_c)| = 1/√2 for every order.
    let fs = 200.0;
    for order in 1..=8 {
        for fc in [0.7, 3.0, 16.5, 60.0] {
            let f = butterworth_lowpass(order, fc, fs).unwrap();
            assert_eq!(f.len(), order.div_ceil(2));
            let at_cutoff = f.frequency_response(fc, fs).norm();
            // Round-off of the cascade only.
            assert!(
                (at_cutoff - 0.5f64.sqrt()).abs() < 1e-12,
                "N={order} fc={fc}: {at_cutoff}"
            );
            for freq in [0.0, 0.3 * fc, 0.9 * fc, 1.7 * fc, 0.45 * fs] {
                let r = ((PI * freq / fs).tan() / (PI * fc / fs).tan()).powi(2 * order as i32);
                let expected = 1.0 / (1.0 + r).sqrt();
                let got = f.frequency_response(freq, fs).norm();
                // Relative round-off; the tail values reach 1e-12 in magnitude.
                assert!(
                    (got - expected).abs() < 1e-11 * expected.max(1e-3),
                    "N={order} f={freq}: {got} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn butterworth_poles_are_the_bilinear_images_of_the_analog_circle_worst_last() {
    // Reference: analog poles ω_a·(−exp(iπm/2N)) (closed form), mapped by z = (4 + s)/(4 − s)
    // with ω_a = 4 tan(πf_c/f_s); scipy's zpk2sos puts the pole nearest the unit circle last
    // and pads odd orders with b = [1, 1, 0]-type sections (b2 = 0, a2 = 0 counted in padlen).
    let (fs, fc, order) = (200.0, 5.0, 6usize);
    let f = butterworth_lowpass(order, fc, fs).unwrap();
    let w = 4.0 * (PI * fc / fs).tan();
    let mut expected: Vec<(f64, f64)> = (0..order / 2)
        .map(|j| {
            let m = -(order as f64) + 1.0 + 2.0 * j as f64;
            let s = (
                -w * (PI * m / (2.0 * order as f64)).cos(),
                -w * (PI * m / (2.0 * order as f64)).sin(),
            );
            // z = (4 + s)/(4 − s) for s = (re, im).
            let (nr, ni) = (4.0 + s.0, s.1);
            let (dr, di) = (4.0 - s.0, -s.1);
            let d = dr * dr + di * di;
            ((nr * dr + ni * di) / d, (ni * dr - nr * di) / d)
        })
        .collect();
    expected.sort_by(|a, b| {
        let ra = (1.0 - a.0.hypot(a.1)).abs();
        let rb = (1.0 - b.0.hypot(b.1)).abs();
        rb.total_cmp(&ra)
    });
    for (s, (re, im)) in f.sections.iter().zip(expected) {
        // Denominator 1 + a1 z⁻¹ + a2 z⁻² = (1 − p z⁻¹)(1 − p̄ z⁻¹): a1 = −2 Re p, a2 = |p|².
        assert!((s[4] + 2.0 * re).abs() < 1e-13, "{s:?}");
        assert!((s[5] - (re * re + im * im)).abs() < 1e-13, "{s:?}");
    }
    assert_eq!(f.default_pad_length(), 3 * (2 * 3 + 1));
    let odd = butterworth_lowpass(3, fc, fs).unwrap();
    assert_eq!(&odd.sections[1][..3], &[1.0, 1.0, 0.0]);
    assert_eq!(odd.sections[0][5], 0.0);
    assert_eq!(odd.default_pad_length(), 3 * (2 * 2 + 1 - 1));
}

#[test]
fn filtfilt_of_a_sinusoid_has_zero_phase_and_the_squared_magnitude() {
    // Reference: forward–backward filtering has response H·H̄ = |H|² (closed form, no phase).
    // Away from the ends (transients of the edge padding decay in a few time constants), a
    // sinusoid comes out in phase, scaled by |H(f)|².
    let fs = 200.0;
    let filter = butterworth_lowpass(4, 5.0, fs).unwrap();
    for freq in [2.0, 5.0, 7.0] {
        let x: Vec<f64> = (0..4000)
            .map(|i| (2.0 * PI * freq * i as f64 / fs + 0.3).sin())
            .collect();
        let y = filter.filtfilt(&x, None).unwrap();
        let gain = filter.frequency_response(freq, fs).norm_sqr();
        for i in 1000..3000 {
            // The padding transient decays as exp(−ζω_c t) over 5 s = 1000 samples: below 1e-9.
            assert!(
                (y[i] - gain * x[i]).abs() < 1e-8,
                "f={freq} i={i}: {} vs {}",
                y[i],
                gain * x[i]
            );
        }
    }
}

#[test]
fn filtfilt_passes_a_constant_and_refuses_a_signal_shorter_than_the_padding() {
    // Reference: scipy's sosfiltfilt — DC gain 1 with steady-state initial conditions, and
    // "the length of the input vector x must be greater than padlen".
    let filter = butterworth_lowpass(4, 2.0, 200.0).unwrap();
    let y = filter.filtfilt(&[3.5; 100], None).unwrap();
    assert!(y.iter().all(|v| (v - 3.5).abs() < 1e-12));
    let err = filter.filtfilt(&[1.0; 15], None).unwrap_err();
    assert_eq!(
        err,
        SignalError::SignalTooShort {
            samples: 15,
            required: 16
        }
    );
}

#[test]
fn welch_recovers_a_sinusoid_frequency_and_a_white_noise_level() {
    // Reference: white noise of variance σ² has the one-sided density 2σ²/f_s (Welch scaling,
    // closed form); a sinusoid puts its peak at its frequency.
    let fs = 200.0;
    let sigma = 0.3;
    let noise: Vec<f64> = normal_noise(7, 65_536)
        .into_iter()
        .map(|v| sigma * v)
        .collect();
    let psd = welch(
        &noise,
        fs,
        &WelchOptions {
            segment_length: 512,
            fft_length: None,
        },
    )
    .unwrap();
    assert_eq!(psd.segments, 255);
    let level = 2.0 * sigma * sigma / fs;
    let inner = &psd.density[5..250];
    let mean = inner.iter().sum::<f64>() / inner.len() as f64;
    // 255 segments × 245 bins averaged: relative standard error ≈ 1/√(255·245/2) ≈ 0.6 %; 3 %
    // is five standard errors.
    assert!((mean / level - 1.0).abs() < 0.03, "{mean} vs {level}");

    let f0 = 7.3;
    let x: Vec<f64> = (0..8192)
        .map(|i| (2.0 * PI * f0 * i as f64 / fs).sin() + 0.05 * noise[i])
        .collect();
    let psd = welch(
        &x,
        fs,
        &WelchOptions {
            segment_length: 2048,
            fft_length: None,
        },
    )
    .unwrap();
    let peaks = pick_peaks(
        &psd,
        &PeakOptions {
            count: 1,
            ..PeakOptions::default()
        },
    );
    assert_eq!(peaks.len(), 1);
    // Parabolic interpolation of a Hann peak in dB: error well under a tenth of a bin
    // (Δf = 0.098 Hz).
    assert!(
        (peaks[0].frequency_hz - f0).abs() < 0.01,
        "{}",
        peaks[0].frequency_hz
    );
}

/// Response of an SDOF oscillator (f_n, ζ) to white noise, by the exact impulse-invariant
/// recursion y_k = 2e^{−ζωΔt}cos(ω_dΔt)·y_{k−1} − e^{−2ζωΔt}·y_{k−2} + e_k.
fn sdof_noise_response(fn_hz: f64, zeta: f64, fs: f64, n: usize, seed: u64) -> Vec<f64> {
    let w = 2.0 * PI * fn_hz;
    let dt = 1.0 / fs;
    let r = (-zeta * w * dt).exp();
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let (a1, a2) = (2.0 * r * (wd * dt).cos(), -r * r);
    let e = normal_noise(seed, n);
    let mut y = vec![0.0; n];
    for k in 2..n {
        y[k] = a1 * y[k - 1] + a2 * y[k - 2] + e[k];
    }
    y
}

#[test]
fn peak_picking_and_half_power_damping_recover_an_sdof_oscillator() {
    // Reference: the half-power bandwidth of an SDOF is 2ζf_n to first order in ζ (closed form).
    // Synthetic SDOF, f_n = 3.2 Hz, ζ = 2 %, 2^20 samples at 200 Hz, segments of 8192 samples
    // (Δf = 0.0244 Hz; half-power bandwidth 0.128 Hz ≈ 5 bins; 255 averaged segments).
    let (fn_hz, zeta, fs) = (3.2, 0.02, 200.0);
    let y = sdof_noise_response(fn_hz, zeta, fs, 1 << 20, 11);
    let psd = welch(
        &y,
        fs,
        &WelchOptions {
            segment_length: 8192,
            fft_length: None,
        },
    )
    .unwrap();
    let peaks = pick_peaks(&psd, &PeakOptions::default());
    assert_eq!(peaks.len(), 1, "{peaks:?}");
    let p = &peaks[0];
    // Frequency within 0.3 %: a fraction of a bin after interpolation, plus estimation noise
    // of 255 averaged segments (the vertex of three bins moves by ~¼ bin = 0.2 %).
    assert!(
        (p.frequency_hz / fn_hz - 1.0).abs() < 0.003,
        "{}",
        p.frequency_hz
    );
    let z = p.damping_ratio.expect("resolved bandwidth");
    assert!(!p.resolution_limited, "5 bins of bandwidth are resolved");
    // Damping within 10 %: the Hann main lobe (−3 dB width 1.44 bins) widens a 5-bin
    // bandwidth by a few per cent, and the density of 255 averaged segments scatters by ±6 %
    // per bin, which moves the interpolated half-power points (seed 11 gives −2.7 %).
    assert!((z / zeta - 1.0).abs() < 0.10, "ζ = {z}");
}

#[test]
fn daf_of_a_synthetic_crossing_with_a_known_static_part_is_recovered() {
    // Synthetic crossing: static part s(t) = −A sin²(πt/T) for 0 ≤ t ≤ T (zero outside),
    // T = 6 s (120 m at 20 m/s), plus a 4 Hz vibration of amplitude 0.1·A under the same smooth
    // envelope (so it carries no low-frequency content of its own; a suddenly starting decaying
    // sine would have a mean ≈ A/(10ω) and shift the static part). The exact DAF is
    // max(−x)/max(−s), known from the samples.
    let fs = 200.0;
    let n = 2000;
    let t_pass = 6.0;
    let a = 0.01;
    let envelope = |i: usize| {
        let ti = i as f64 / fs - 1.0;
        if (0.0..=t_pass).contains(&ti) {
            (PI * ti / t_pass).sin().powi(2)
        } else {
            0.0
        }
    };
    let stat: Vec<f64> = (0..n).map(|i| -a * envelope(i)).collect();
    let x: Vec<f64> = (0..n)
        .map(|i| stat[i] - 0.1 * a * envelope(i) * (2.0 * PI * 4.0 * i as f64 / fs).sin())
        .collect();
    let exact = measured_daf(&x, &stat).unwrap();
    let choice = automatic_cutoff(1.0 / t_pass, 4.0).unwrap();
    assert_eq!(choice.rule, CutoffRule::GeometricMean);
    let estimated_static = static_component(&x, fs, 4, choice.cutoff_hz).unwrap();
    let d = measured_daf(&x, &estimated_static).unwrap();
    assert_eq!(d.direction, -1.0);
    // The low-pass leaves 1/(1 + (4/1.83)^8) = 0.2 % of the 4 Hz vibration (10 % of A) and
    // takes nothing measurable from the 1/6 Hz bump: the static maximum is right to 0.1 %.
    assert!(
        (d.static_max / exact.static_max - 1.0).abs() < 1e-3,
        "{} vs {}",
        d.static_max,
        exact.static_max
    );
    assert!(
        (d.daf - exact.daf).abs() < 2e-3,
        "{} vs {}",
        d.daf,
        exact.daf
    );
}

#[test]
fn cutoff_mode_filtering_removes_noise_without_changing_the_daf() {
    // The paper's §6: low-pass at the K1 mode frequency changed the DAF by at most 0.3 %. A
    // synthetic crossing with a 3.5 Hz mode plus white noise (σ = 1 % of the static maximum),
    // filtered at f_K1 = 9.8 Hz.
    let fs = 200.0;
    let n = 2400;
    let noise = normal_noise(3, n);
    let stat = static_pulse(n, fs);
    let clean: Vec<f64> = (0..n)
        .map(|i| stat[i] + 0.08 * (2.0 * PI * 3.5 * i as f64 / fs).sin())
        .collect();
    let noisy: Vec<f64> = clean
        .iter()
        .zip(&noise)
        .map(|(c, e)| c + 0.01 * e)
        .collect();
    let r = cutoff_mode_filtering(&noisy, &stat, fs, 4, 9.8).unwrap();
    let truth = measured_daf(&clean, &stat).unwrap();
    // Noise peaks add ~3σ = 3 % of the static maximum to the raw DAF; after filtering at
    // 9.8 Hz only the in-band 10 % of the noise power remains (σ' ≈ 0.3 %), so the filtered DAF
    // lies within 1 % of the noise-free value, and closer than the raw one.
    assert!(
        (r.after.daf - truth.daf).abs() < 0.01,
        "{} vs {}",
        r.after.daf,
        truth.daf
    );
    assert!((r.after.daf - truth.daf).abs() < (r.before.daf - truth.daf).abs());
}

#[test]
fn updating_recovers_a_known_stiffness_scale_in_closed_form() {
    // Synthetic: a model with frequencies f_i = √α·(3.1, 4.9, 12.4) Hz; measured frequencies
    // made with α = 1.18 (frequencies ∝ √(EI/m), closed form).
    let base = [3.1, 4.9, 12.4];
    let alpha = 1.18f64;
    let identified: Vec<IdentifiedFrequency> = base
        .iter()
        .map(|f| IdentifiedFrequency {
            frequency_hz: f * alpha.sqrt(),
            kind: None,
        })
        .collect();
    let model = |s: &[f64]| -> Result<Vec<f64>, String> {
        Ok(base.iter().map(|f| f * s[0].sqrt()).collect())
    };
    let u = update_model(model, None, &identified, &UpdatingOptions::default()).unwrap();
    assert_eq!(u.method, UpdatingMethod::ClosedForm);
    // Exact data: round-off only.
    assert!(
        (u.stiffness_scale - alpha).abs() < 1e-12,
        "{}",
        u.stiffness_scale
    );
    assert!(u.updated_rms_error_hz < 1e-12);
}

#[test]
fn updating_with_an_added_mass_scale_recovers_both_factors_and_refuses_a_uniform_mass_scale() {
    // Synthetic 3-mode model: ω_i² = α·k_i / (m_s,i + β·m_a,i), structural and added modal
    // masses differ per mode (added mass concentrated differently), so α and β are separable.
    let k = [1.0e6, 2.6e6, 1.5e7];
    let ms = [2.0e3, 2.2e3, 2.5e3];
    let ma = [1.2e3, 0.3e3, 0.9e3];
    let freqs = move |alpha: f64, beta: f64| -> Vec<f64> {
        (0..3)
            .map(|i| (alpha * k[i] / (ms[i] + beta * ma[i])).sqrt() / (2.0 * PI))
            .collect()
    };
    let (alpha, beta) = (0.9, 1.3);
    let identified: Vec<IdentifiedFrequency> = freqs(alpha, beta)
        .into_iter()
        .map(|f| IdentifiedFrequency {
            frequency_hz: f,
            kind: Some(ModeKind::VerticalBending),
        })
        .collect();
    let kinds = [ModeKind::VerticalBending; 3];
    let options = UpdatingOptions {
        fit_mass: true,
        ..UpdatingOptions::default()
    };
    let model = move |s: &[f64]| -> Result<Vec<f64>, String> { Ok(freqs(s[0], s[1])) };
    let u = update_model(model, Some(&kinds), &identified, &options).unwrap();
    assert_eq!(u.method, UpdatingMethod::LevenbergMarquardt);
    // Exact synthetic data; finite-difference Jacobian only slows convergence, the fixed point
    // is exact to the stopping tolerance (1e-10 in ln scale).
    assert!((u.stiffness_scale - alpha).abs() < 1e-7, "{u:?}");
    assert!((u.mass_scale.unwrap() - beta).abs() < 1e-7, "{u:?}");

    // Uniform mass scale: ω² = α/β·k/m, frequencies see only α/β.
    let uniform = move |s: &[f64]| -> Result<Vec<f64>, String> {
        Ok((0..3)
            .map(|i| (s[0] * k[i] / (s[1] * ms[i])).sqrt() / (2.0 * PI))
            .collect())
    };
    let err = update_model(uniform, Some(&kinds), &identified, &options).unwrap_err();
    assert!(matches!(err, SignalError::NotIdentifiable { .. }), "{err}");
}

#[test]
fn modes_pair_by_kind_and_order() {
    let identified = [
        IdentifiedFrequency {
            frequency_hz: 3.0,
            kind: Some(ModeKind::VerticalBending),
        },
        IdentifiedFrequency {
            frequency_hz: 4.0,
            kind: Some(ModeKind::Torsion),
        },
        IdentifiedFrequency {
            frequency_hz: 5.0,
            kind: Some(ModeKind::VerticalBending),
        },
    ];
    let kinds = [
        ModeKind::VerticalBending,
        ModeKind::Lateral,
        ModeKind::VerticalBending,
        ModeKind::Torsion,
    ];
    let pairs = pair_modes(&identified, Some(&kinds), 4).unwrap();
    assert_eq!(pairs, vec![(0, 0), (1, 3), (2, 2)]);
}

#[test]
fn influence_line_static_reference_sums_the_axles() {
    // Reference: R_s(t) = Σ P_a·IL(v(t − t₀) − d_a) (superposition, closed form). Triangular
    // influence line of a 20 m simply supported span at mid-span, IL(x) = x/4 for x ≤ 10 m
    // (moment per unit load, L/4 at the peak), two axles 100 kN and 50 kN, 4 m apart, 10 m/s.
    let line = SampledInfluenceLine::new(vec![0.0, 10.0, 20.0], vec![0.0, 2.5, 0.0]).unwrap();
    let loads = MovingLoads {
        axle_loads: vec![100e3, 50e3],
        axle_offsets: vec![0.0, 4.0],
        speed: 10.0,
        entry_time: 0.5,
    };
    // At t = 1.5 s the front axle is at 10 m (IL 2.5), the rear at 6 m (IL 1.5).
    let r = static_from_influence_line(&[0.0, 1.5, 3.0], &line, &loads).unwrap();
    assert_eq!(r[0], 0.0);
    // Linear interpolation is exact on a piecewise-linear line: round-off only.
    assert!((r[1] - (100e3 * 2.5 + 50e3 * 1.5)).abs() < 1e-6, "{}", r[1]);
    // At t = 3 s: front at 25 m (off), rear at 21 m (off).
    assert_eq!(r[2], 0.0);
    assert!(SampledInfluenceLine::new(vec![0.0, 0.0], vec![1.0, 1.0]).is_err());
}

#[test]
fn the_cutoff_mode_filter_passes_mode_k1_with_the_butterworth_gain() {
    // Closed form: the zero-phase Butterworth of order N has amplitude 1/(1 + (f/f_c)^{2N});
    // f_c = f_K1·99^{1/(2N)} gives 0.99 at f_K1. A static pulse plus 10 % of a sine at
    // f_K1 = 6 Hz keeps its DAF within 0.2 % (the sine loses 1 % of 10 % of the peak, 0.1 %),
    // where a filter at f_K1 itself halves the sine (amplitude ½) and lowers the DAF by ~5 %.
    let fs = 200.0;
    let k1 = 6.0;
    assert!((vbi::signal::cutoff_above_mode(k1, 4) - k1 * 99f64.powf(1.0 / 8.0)).abs() < 1e-12);
    let n = 2400;
    let stat = static_pulse(n, fs);
    let measured: Vec<f64> = (0..n)
        .map(|i| stat[i] + 0.1 * (2.0 * PI * k1 * i as f64 / fs).sin())
        .collect();
    let r = cutoff_mode_filtering(&measured, &stat, fs, 4, k1).unwrap();
    assert!((r.mode_gain - 0.99).abs() < 1e-12, "{}", r.mode_gain);
    assert!(r.relative_change.abs() < 0.002, "{}", r.relative_change);
    let at_k1 = butterworth_lowpass(4, k1, fs)
        .unwrap()
        .filtfilt(&measured, None)
        .unwrap();
    let halved = measured_daf(&at_k1, &stat).unwrap();
    assert!(
        halved.daf < r.after.daf - 0.03,
        "{} vs {}",
        halved.daf,
        r.after.daf
    );
}

/// A static crossing pulse sin²(πt/8) for 0 ≤ t ≤ 8 s after a 2 s lead, `n` samples at `fs`.
fn static_pulse(n: usize, fs: f64) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let t = i as f64 / fs - 2.0;
            if (0.0..=8.0).contains(&t) {
                (PI * t / 8.0).sin().powi(2)
            } else {
                0.0
            }
        })
        .collect()
}
