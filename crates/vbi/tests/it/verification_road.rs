//! Verification of the `road` stage: the discrete variance identity of Eq. 22, the spectrum of
//! generated profiles against ISO 8608 (Eq. 21), track coherence, determinism.
//!
//! Reference: docs/verification.md §8 (ISO 8608 classes, variance identity) and the
//! paper §3.2, Eqs. 21–22.

use std::f64::consts::PI;

use vbi::road::{
    coherence, generate, generate_sample, welch_cross_spectrum, welch_psd, DisplacementPsd,
    GenerationMethod, HarmonicSet, RoadSpec, RoughnessClass, SampleRng, Track, TrackCorrelation,
};

/// One full period of the long-profile tests: 2¹⁷ samples at 0.05 m (6553.6 m), so the
/// inverse FFT of length 2¹⁷ holds exactly this profile.
const LONG_COUNT: usize = 1 << 17;
const SPACING: f64 = 0.05;

fn long_spec(track_correlation: TrackCorrelation) -> RoadSpec {
    RoadSpec {
        track_correlation,
        ..RoadSpec::of_class(RoughnessClass::Medium)
    }
}

fn long_profile(track_correlation: TrackCorrelation) -> vbi::road::RoadProfile {
    let spec = long_spec(track_correlation);
    let length = (LONG_COUNT - 1) as f64 * SPACING;
    generate(&spec, 0.0, length, 2026).unwrap()
}

/// Quantile of χ²_ν / ν by the Wilson–Hilferty approximation (accurate to < 1 % for ν ≥ 30).
fn scaled_chi_square_quantile(dof: f64, z: f64) -> f64 {
    let c = 2.0 / (9.0 * dof);
    (1.0 - c + z * c.sqrt()).powi(3)
}

// Reference: docs/verification.md §8. With n_i = iΔn, Δn = 1/L_p, sampled at M > 2N
// points over one period, the discrete cosines are orthogonal, so the mean square is
// Σ a_i²/2 = Σ G_d(n_i) Δn whatever the phases.
#[test]
fn variance_identity_holds_to_round_off_over_one_period_for_any_phases() {
    let psd = DisplacementPsd::new(RoughnessClass::Poor.psd_at_reference(), 2.0).unwrap();
    let period = 256.0; // L_p [m]
    let step = 1.0 / period;
    let harmonics = 300; // n up to 1.17 cycles/m
    let samples = 1024; // > 2 × 300
    let frequencies: Vec<f64> = (1..=harmonics).map(|i| i as f64 * step).collect();
    let target: f64 = frequencies.iter().map(|&n| psd.value(n) * step).sum();
    let mut rng = SampleRng::new(99, 0);
    let phase_sets: Vec<Vec<f64>> = vec![
        vec![0.0; harmonics], // every crest aligned: the worst peak, same mean square
        (0..harmonics).map(|_| 2.0 * PI * rng.next_unit()).collect(),
        (0..harmonics).map(|_| 2.0 * PI * rng.next_unit()).collect(),
    ];
    for phases in phase_sets {
        let set = HarmonicSet::from_psd(&psd, frequencies.clone(), step, phases);
        let h = set.sample_direct(0.0, period / samples as f64, samples);
        let mean_square = h.iter().map(|v| v * v).sum::<f64>() / samples as f64;
        // Round-off of 1024 × 300 cosine terms in double precision: ~1e-13 relative; 1e-11
        // leaves margin while any leakage (a wrong Δn or sampling) would show at 1e-3.
        assert!(
            ((mean_square - target) / target).abs() < 1e-11,
            "{mean_square} vs {target}"
        );
        assert!(((set.mean_square() - target) / target).abs() < 1e-13);
    }
}

// The inverse-FFT path is Eq. 22 evaluated on its grid: it must agree with the direct sum.
#[test]
fn inverse_fft_sampling_equals_the_direct_harmonic_sum() {
    let psd = DisplacementPsd::new(64e-6, 2.0).unwrap();
    let (fft_length, spacing) = (512, 0.1);
    let step = 1.0 / (fft_length as f64 * spacing);
    let frequencies: Vec<f64> = (3..200).map(|k| k as f64 * step).collect();
    let mut rng = SampleRng::new(5, 0);
    let phases = frequencies
        .iter()
        .map(|_| 2.0 * PI * rng.next_unit())
        .collect();
    let set = HarmonicSet::from_psd(&psd, frequencies, step, phases);
    let start = -37.3; // a start off the grid checks the phase shift to the first sample
    let direct = set.sample_direct(start, spacing, 400);
    let fft = set.sample_fft(start, spacing, 400, fft_length).unwrap();
    let rms = set.mean_square().sqrt();
    for (a, b) in direct.iter().zip(&fft) {
        // Both are sums of 197 terms of size ≤ rms: round-off ~1e-13 rms.
        assert!((a - b).abs() < 1e-10 * rms, "{a} vs {b}");
    }
}

// Reference: docs/verification.md §8 applied to the generator: a profile of exactly one
// FFT period holds every grid line n_k = k/(NΔx) in [n₁, n₂] once, so its mean square is
// Σ_k G_d(n_k) Δn exactly.
#[test]
fn generated_profile_over_one_fft_period_has_the_discrete_variance() {
    let profile = long_profile(TrackCorrelation::Identical);
    assert_eq!(profile.len(), LONG_COUNT);
    assert!((profile.spacing - SPACING).abs() < 1e-15);
    let spec = long_spec(TrackCorrelation::Identical);
    let psd = spec.psd().unwrap();
    let step = 1.0 / (LONG_COUNT as f64 * SPACING);
    let first = (spec.band_lower / step).ceil() as usize;
    let last = (spec.band_upper / step).floor() as usize;
    let target: f64 = (first..=last)
        .map(|k| psd.value(k as f64 * step) * step)
        .sum();
    let mean_square = profile.rms(Track::Left).powi(2);
    // FFT of length 2¹⁷: round-off ~ 17 ε per sample; 1e-10 relative is ample.
    assert!(
        ((mean_square - target) / target).abs() < 1e-10,
        "{mean_square} vs {target}"
    );
    // The discrete sum and the continuous integral differ by a few percent only
    // (docs/verification.md §8).
    let continuous = psd.band_variance(spec.band_lower, spec.band_upper);
    assert!(((target - continuous) / continuous).abs() < 0.05);
}

// Reference: paper Eq. 21 (ISO 8608), medium class. K = 32 independent Hann segments of 4096
// samples: each line of the averaged periodogram scatters as G_d(n) χ²₆₄/64 (2 degrees of
// freedom per segment), whose central 99.9 % interval is [0.52, 1.69] (Wilson–Hilferty).
#[test]
fn averaged_periodogram_of_a_long_profile_matches_the_iso_psd_within_chi_square_scatter() {
    let profile = long_profile(TrackCorrelation::Identical);
    let segment = 4096;
    let segments = LONG_COUNT / segment;
    let estimate = welch_psd(&profile.left, SPACING, segment, segment).unwrap();
    let psd = long_spec(TrackCorrelation::Identical).psd().unwrap();
    let dof = 2.0 * segments as f64;
    let (low, high) = (
        scaled_chi_square_quantile(dof, -3.2905),
        scaled_chi_square_quantile(dof, 3.2905),
    );
    // Lines 8 … 600: the Hann main lobe (±2 lines) biases the n⁻² slope by ≈ 1/j², under 2 %
    // from line 8 on; line 600 (2.93 cycles/m) stays 3 lines inside the band edge 3.0.
    let lines = &estimate[7..600];
    let ratios: Vec<f64> = lines
        .iter()
        .map(|p| p.psd / psd.value(p.spatial_frequency))
        .collect();
    let outside = ratios.iter().filter(|r| **r < low || **r > high).count();
    // Expected 0.1 % outside (0.6 of 593 lines); adjacent Hann lines are correlated, so allow
    // 1 % (6 lines), far below what a wrong level or slope would give.
    assert!(
        outside <= ratios.len() / 100,
        "{outside} of {} lines outside [{low:.3}, {high:.3}]",
        ratios.len()
    );
    // The mean ratio over 593 lines: σ ≈ √(1.5 / (64 · 593)) ≈ 0.006 (1.5 = Hann noise
    // bandwidth in lines); 4σ plus the 0.1 % main-lobe bias gives 0.025.
    let mean = ratios.iter().sum::<f64>() / ratios.len() as f64;
    assert!((mean - 1.0).abs() < 0.025, "mean ratio {mean}");
}

// Reference: the documented exponential coherence γ(n) = exp(−ρ n b) (vbi::road::coherence).
// Estimated from K = 32 independent segments; per line the real-coherence estimate scatters by
// ≈ (1 − γ²)/√(2K), and averaging m lines (m/1.5 independent) divides that by √(m/1.5).
#[test]
fn correlated_tracks_follow_the_coherence_model() {
    let (track_spacing, coherence_decay) = (1.8, 1.0);
    let profile = long_profile(TrackCorrelation::Coherent {
        track_spacing,
        coherence_decay,
    });
    // Each track keeps the exact Eq. 22 amplitudes: equal mean squares to round-off.
    let (l, r) = (profile.rms(Track::Left), profile.rms(Track::Right));
    assert!(((l - r) / l).abs() < 1e-10, "{l} vs {r}");
    let segment = 4096;
    let k = (LONG_COUNT / segment) as f64;
    let cross =
        welch_cross_spectrum(&profile.left, &profile.right, SPACING, segment, segment).unwrap();
    let band = 40;
    for chunk in cross[7..600].chunks(band) {
        let estimated = chunk.iter().map(|p| p.real_coherence()).sum::<f64>() / chunk.len() as f64;
        let expected = chunk
            .iter()
            .map(|p| coherence(p.spatial_frequency, track_spacing, coherence_decay))
            .sum::<f64>()
            / chunk.len() as f64;
        let sigma =
            (1.0 - expected * expected) / (2.0 * k).sqrt() / (chunk.len() as f64 / 1.5).sqrt();
        // 4σ, plus 0.01 for the window's smoothing of γ across ±2 lines.
        assert!(
            (estimated - expected).abs() < 4.0 * sigma + 0.01,
            "n ≈ {:.3}: {estimated:.4} vs {expected:.4} (σ = {sigma:.4})",
            chunk[0].spatial_frequency
        );
    }
}

#[test]
fn identical_tracks_are_equal_and_independent_tracks_are_incoherent() {
    let identical = long_profile(TrackCorrelation::Identical);
    assert_eq!(identical.left, identical.right);
    let independent = long_profile(TrackCorrelation::Independent);
    // Same left track whatever the correlation: the left phases are drawn first.
    assert_eq!(independent.left, identical.left);
    let cross =
        welch_cross_spectrum(&independent.left, &independent.right, SPACING, 4096, 4096).unwrap();
    let mean = cross[7..600]
        .iter()
        .map(|p| p.real_coherence())
        .sum::<f64>()
        / 593.0;
    // γ = 0: σ of the mean ≈ √(1.5/(64 · 593)) ≈ 0.006; 4σ = 0.025.
    assert!(mean.abs() < 0.025, "{mean}");
}

#[test]
fn same_seed_gives_identical_profiles_and_different_samples_differ() {
    for method in [
        GenerationMethod::InverseFft,
        GenerationMethod::HarmonicSuperposition,
    ] {
        let spec = RoadSpec {
            method,
            harmonic_count: 200,
            track_correlation: TrackCorrelation::Independent,
            ..RoadSpec::of_class(RoughnessClass::Good)
        };
        let a = generate_sample(&spec, -50.0, 80.0, 11, 3).unwrap();
        let b = generate_sample(&spec, -50.0, 80.0, 11, 3).unwrap();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.left), bits(&b.left));
        assert_eq!(bits(&a.right), bits(&b.right));
        let other_sample = generate_sample(&spec, -50.0, 80.0, 11, 4).unwrap();
        let other_seed = generate_sample(&spec, -50.0, 80.0, 12, 3).unwrap();
        assert_ne!(a.left, other_sample.left);
        assert_ne!(a.left, other_seed.left);
        assert_eq!(
            generate(&spec, -50.0, 80.0, 11).unwrap(),
            generate_sample(&spec, -50.0, 80.0, 11, 0).unwrap()
        );
    }
}

// Pins the documented seed derivation (SplitMix64 key, ChaCha20 stream = sample index, top 53
// bits): values produced by this implementation; any change to the derivation breaks them.
#[test]
fn seed_derivation_is_pinned() {
    let mut rng = SampleRng::new(1, 0);
    let words: Vec<u64> = (0..3).map(|_| rng.next_word()).collect();
    assert_eq!(words, PINNED_WORDS);
}

const PINNED_WORDS: [u64; 3] = [
    2920944695010215200,
    15533121707553204838,
    5925869431031305792,
];

#[test]
fn profile_spans_the_approach_the_bridge_and_the_exit() {
    let spec = RoadSpec::default();
    let (start, end) = spec.extent_for_bridge(90.0);
    let p = generate(&spec, start, end, spec.seed).unwrap();
    assert_eq!(p.start, -spec.approach_length);
    assert!((p.end() - (90.0 + spec.exit_length)).abs() < 1e-9);
    assert!(p.spacing <= spec.sample_spacing);
}

// Tyre-patch smoothing is a moving average: it removes short waves (it lowers the slope far
// more than the elevation), never adds to them.
#[test]
fn tyre_patch_smoothing_reduces_short_wave_content() {
    let raw = RoadSpec::of_class(RoughnessClass::Poor);
    let smoothed = RoadSpec {
        tyre_patch_length: 0.25,
        ..raw.clone()
    };
    let a = generate(&raw, 0.0, 200.0, 4).unwrap();
    let b = generate(&smoothed, 0.0, 200.0, 4).unwrap();
    let slope_rms = |p: &vbi::road::RoadProfile| {
        let s: Vec<f64> = p
            .left
            .windows(2)
            .map(|w| (w[1] - w[0]) / p.spacing)
            .collect();
        (s.iter().map(|v| v * v).sum::<f64>() / s.len() as f64).sqrt()
    };
    assert!(b.rms(Track::Left) < a.rms(Track::Left));
    assert!(b.rms(Track::Left) > 0.95 * a.rms(Track::Left));
    assert!(slope_rms(&b) < 0.8 * slope_rms(&a));
}
