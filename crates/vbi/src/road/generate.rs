//! Seeded generation of road profiles: random-phase harmonic superposition (paper Eq. 22),
//! evaluated directly or by an inverse real FFT, on two correlated wheel tracks.

use std::f64::consts::PI;
use std::sync::{LazyLock, Mutex};

use rand_chacha::ChaCha20Rng;
use rand_core::{Rng, SeedableRng};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use serde::{Deserialize, Serialize};

use super::events::{add_events, RoadEvent, UserProfile};
use super::psd::{DisplacementPsd, PsdReference, Roughness, RoughnessClass};
use super::{RoadError, RoadProfile, Track};
use crate::bits::same_bits;

/// Largest number of samples per track a generated profile may hold (2²⁴ ≈ 16.8 million).
pub const MAX_SAMPLE_COUNT: usize = 1 << 24;

/// Largest number of harmonics of the direct superposition.
pub const MAX_HARMONIC_COUNT: usize = 1 << 20;

/// Largest number of terms (harmonics × samples) of one track's direct superposition: 2³⁰,
/// about 5 s per track. 2²⁰ harmonics at 16 000 samples ran for minutes (issue 17, defect 4);
/// the inverse FFT gives the same Eq. 22 in milliseconds.
pub const MAX_DIRECT_TERMS: usize = 1 << 30;

/// How the harmonic sum of Eq. 22 is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GenerationMethod {
    /// Eq. 22 summed directly: `harmonic_count` harmonics at the mid-points
    /// n_i = n₁ + (i − ½)Δn, Δn = (n₂ − n₁)/N, each at every sample. Cost N × samples.
    HarmonicSuperposition,
    /// Eq. 22 on the frequency grid n_k = k/(N_fft Δx) of an inverse real FFT of length
    /// N_fft = the power of two ≥ max(samples, 1/(n₁Δx)), every grid line in [n₁, n₂] one
    /// harmonic (the paper's "inverse Fourier transform"). Cost N_fft log N_fft; the default.
    InverseFft,
}

/// How the right track relates to the left one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum TrackCorrelation {
    /// Right = left (a 2D road).
    Identical,
    /// The default: [`Coherent`](Self::Coherent) with the track spacing b of the vehicle that
    /// crosses (its wheels' lateral spread), which the pipeline fills in
    /// ([`resolved`](Self::resolved)); identical for a vehicle on one track (a 2D model) and for
    /// a road generated without a vehicle (`vbi road`). The paper's roads are "multi-path".
    VehicleTrack {
        /// Decay ρ [-] of the coherence (default 1.0, see [`coherence`]).
        coherence_decay: f64,
    },
    /// Independent random phases on each track (coherence 0).
    Independent,
    /// Partially correlated with the exponential coherence γ(n) = exp(−ρ n b) of [`coherence`].
    Coherent {
        /// Lateral distance b between the two wheel tracks [m] (for example 1.8 m).
        track_spacing: f64,
        /// Decay ρ [-] of the coherence (representative value 1.0, see [`coherence`]).
        coherence_decay: f64,
    },
}

impl TrackCorrelation {
    /// The correlation for a vehicle whose wheel tracks lie `track_spacing` [m] apart (0 for a
    /// vehicle on one track): [`VehicleTrack`](Self::VehicleTrack) becomes
    /// [`Coherent`](Self::Coherent) at that spacing, or [`Identical`](Self::Identical) without
    /// one; the other relations are kept.
    pub fn resolved(self, track_spacing: f64) -> TrackCorrelation {
        match self {
            TrackCorrelation::VehicleTrack { coherence_decay } => {
                if track_spacing.is_finite() && track_spacing > 0.0 {
                    TrackCorrelation::Coherent {
                        track_spacing,
                        coherence_decay,
                    }
                } else {
                    TrackCorrelation::Identical
                }
            }
            other => other,
        }
    }
}

/// Default decay ρ of the tracks' coherence [-] (a representative value, see [`coherence`]).
pub const DEFAULT_COHERENCE_DECAY: f64 = 1.0;

/// Exponential coherence of the two wheel tracks [-], a documented modelling choice:
/// γ(n) = exp(−ρ · n · b), with n the spatial frequency [cycles/m], b the track spacing [m] and
/// ρ a dimensionless decay. γ → 1 for long waves (both wheels ride the same swell) and → 0 for
/// short ones. It belongs to the "exponential" family of parallel-track coherence models surveyed
/// by Kropáč & Múčka (Int. J. Vehicle Design); their best fits (Ammon–Bormann) need more
/// parameters than an ISO 8608 class provides. ρ = 1 is a representative value, not a measured one.
/// Here γ is the real coherence Re G_lr / √(G_ll G_rr) (not squared).
pub fn coherence(spatial_frequency: f64, track_spacing: f64, coherence_decay: f64) -> f64 {
    (-coherence_decay * spatial_frequency * track_spacing).exp()
}

/// Longest tyre-patch length of the moving-average smoothing [m]: a truck tyre's contact patch
/// is 0.15–0.3 m long; beyond a few metres the "smoothing" would flatten the road itself (and a
/// window of 1e308 m overflowed the sample count).
pub const MAX_TYRE_PATCH_LENGTH: f64 = 2.0;

/// Everything that defines a random road. Every field has a default ([`RoadSpec::default`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoadSpec {
    /// Roughness class or custom G_d(n₀) (default: the paper's 'medium', 64 × 10⁻⁶ m³).
    pub roughness: Roughness,
    /// Where the roughness's G_d(n₀) is read (default None: the class's own reference, ISO
    /// 8608's 0.1 cycles/m for the paper's and ISO classes and custom values, 1/(2π) for the
    /// Dodds & Robson classes). `DoddsRobson` with the paper's classes is the second reading of
    /// the paper's roads (docs/paper-reproduction.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub psd_reference: Option<PsdReference>,
    /// Waviness w of Eq. 21 [-] (default 2).
    pub waviness: f64,
    /// Lower end n₁ of the spatial-frequency band [cycles/m] (default 0.01, wavelength 100 m).
    pub band_lower: f64,
    /// Upper end n₂ of the band [cycles/m] (default 3.0, wavelength 0.33 m; ISO 8608 classifies
    /// roads up to 2.83 cycles/m and shorter waves are filtered by the tyre patch).
    pub band_upper: f64,
    /// Number N of harmonics of [`GenerationMethod::HarmonicSuperposition`] (default 1000).
    pub harmonic_count: usize,
    /// Evaluation method (default [`GenerationMethod::InverseFft`]).
    pub method: GenerationMethod,
    /// Largest sample spacing Δx [m] (default 0.05); the spacing used divides the profile
    /// length into whole intervals. Must keep n₂ below the Nyquist frequency 1/(2Δx).
    pub sample_spacing: f64,
    /// Relation of the right track to the left one (default [`TrackCorrelation::VehicleTrack`]
    /// with ρ = 1: coherent at the crossing vehicle's track spacing).
    pub track_correlation: TrackCorrelation,
    /// Road before the bridge [m] (default 100), so the vehicle reaches a steady state.
    pub approach_length: f64,
    /// Road after the bridge [m] (default 30), for the rear axles.
    pub exit_length: f64,
    /// Tyre contact length of the moving-average smoothing [m] (default 0: none).
    pub tyre_patch_length: f64,
    /// Base seed of the ChaCha20 stream (default 1); sample i of a set uses stream i.
    pub seed: u64,
    /// Deterministic events superposed on the roughness (or on the user profile), positions
    /// in deck coordinates [m] (default none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub events: Vec<RoadEvent>,
    /// A user or measured profile that replaces the random roughness (default none: the
    /// random road of the fields above). It must cover the whole extent generated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<UserProfile>,
}

impl Default for RoadSpec {
    fn default() -> RoadSpec {
        RoadSpec {
            roughness: Roughness::Class(RoughnessClass::Medium),
            psd_reference: None,
            waviness: 2.0,
            band_lower: 0.01,
            band_upper: 3.0,
            harmonic_count: 1000,
            method: GenerationMethod::InverseFft,
            sample_spacing: 0.05,
            track_correlation: TrackCorrelation::VehicleTrack {
                coherence_decay: DEFAULT_COHERENCE_DECAY,
            },
            approach_length: 100.0,
            exit_length: 30.0,
            tyre_patch_length: 0.0,
            seed: 1,
            events: Vec::new(),
            profile: None,
        }
    }
}

impl RoadSpec {
    /// The spec of a named class with every other field at its default.
    pub fn of_class(class: RoughnessClass) -> RoadSpec {
        RoadSpec {
            roughness: Roughness::Class(class),
            ..RoadSpec::default()
        }
    }

    /// Whether the road generated depends on `seed`: false for a user profile and for a
    /// roughness of zero (the paper's 'smooth'), whose every sample is the same road (the
    /// events are deterministic).
    pub fn reads_seed(&self) -> bool {
        self.profile.is_none() && self.roughness.psd_at_reference() != 0.0
    }

    /// Where the roughness is read: `psd_reference`, or the roughness's own.
    pub fn reference(&self) -> PsdReference {
        self.psd_reference
            .unwrap_or_else(|| self.roughness.reference())
    }

    /// G_d at ISO 8608's n₀ = 0.1 cycles/m [m³]: the roughness converted from its reference
    /// ([`PsdReference::to_iso_reference`]).
    pub fn psd_at_iso_reference(&self) -> f64 {
        self.reference()
            .to_iso_reference(self.roughness.psd_at_reference(), self.waviness)
    }

    /// The target PSD (Eq. 21), referred to n₀ = 0.1 cycles/m.
    pub fn psd(&self) -> Result<DisplacementPsd, RoadError> {
        DisplacementPsd::new(self.psd_at_iso_reference(), self.waviness)
    }

    /// The profile extent for a bridge of total length L [m]: [−approach, L + exit].
    pub fn extent_for_bridge(&self, bridge_length: f64) -> (f64, f64) {
        (-self.approach_length, bridge_length + self.exit_length)
    }

    /// The profile extent [start, end] [m] for a crossing of a bridge of total length L by a
    /// vehicle whose last tyre trails its front axle by `trailing_length` ≥ 0 [m] (the front
    /// axle starts at −approach): the start of [`extent_for_bridge`](Self::extent_for_bridge)
    /// moved back by the trailing length, rounded up to whole `sample_spacing`s, so that every
    /// tyre's whole path lies on the profile from t = 0. The samples at the positions of the
    /// shorter extent keep their values when the spacing and the FFT length stay the same (the
    /// harmonics are evaluated at absolute x).
    pub fn extent_for_crossing(&self, bridge_length: f64, trailing_length: f64) -> (f64, f64) {
        let (start, end) = self.extent_for_bridge(bridge_length);
        let behind = if trailing_length.is_finite() && trailing_length > 0.0 {
            (trailing_length / self.sample_spacing).ceil() * self.sample_spacing
        } else {
            0.0
        };
        (start - behind, end)
    }

    /// Checks every field; the error carries the offending numbers.
    pub fn validate(&self) -> Result<(), RoadError> {
        self.psd()?;
        let (lower, upper) = (self.band_lower, self.band_upper);
        if !(lower.is_finite() && upper.is_finite() && lower > 0.0 && lower < upper) {
            return Err(RoadError::InvalidBand { lower, upper });
        }
        if self.harmonic_count == 0 || self.harmonic_count > MAX_HARMONIC_COUNT {
            return Err(RoadError::InvalidHarmonicCount {
                count: self.harmonic_count,
                limit: MAX_HARMONIC_COUNT,
            });
        }
        let spacing = self.sample_spacing;
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(RoadError::InvalidLength {
                quantity: "sample spacing",
                value: spacing,
                allowed: "a finite value > 0",
            });
        }
        let nyquist = 0.5 / spacing;
        if upper >= nyquist && self.profile.is_none() {
            return Err(RoadError::BandAboveNyquist {
                upper,
                nyquist,
                spacing,
            });
        }
        for (quantity, value) in [
            ("approach length", self.approach_length),
            ("exit length", self.exit_length),
            ("tyre-patch length", self.tyre_patch_length),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(RoadError::InvalidLength {
                    quantity,
                    value,
                    allowed: "a finite value >= 0",
                });
            }
        }
        if self.tyre_patch_length > MAX_TYRE_PATCH_LENGTH {
            return Err(RoadError::InvalidLength {
                quantity: "tyre-patch length",
                value: self.tyre_patch_length,
                allowed: "at most 2 m (a truck tyre's contact patch is 0.15-0.3 m long)",
            });
        }
        if let TrackCorrelation::VehicleTrack { coherence_decay } = self.track_correlation {
            if !(coherence_decay.is_finite() && coherence_decay >= 0.0) {
                return Err(RoadError::InvalidCoherenceDecay {
                    decay: coherence_decay,
                });
            }
        }
        if let TrackCorrelation::Coherent {
            track_spacing,
            coherence_decay,
        } = self.track_correlation
        {
            if !(track_spacing.is_finite() && track_spacing > 0.0) {
                return Err(RoadError::InvalidLength {
                    quantity: "track spacing",
                    value: track_spacing,
                    allowed: "a finite value > 0",
                });
            }
            if !(coherence_decay.is_finite() && coherence_decay >= 0.0) {
                return Err(RoadError::InvalidCoherenceDecay {
                    decay: coherence_decay,
                });
            }
        }
        for (index, event) in self.events.iter().enumerate() {
            event.shape.validate(index, spacing)?;
        }
        if let Some(profile) = &self.profile {
            profile.validate()?;
        }
        Ok(())
    }
}

/// A uniform number in [0, 1) from the top 53 bits of a 64-bit word: (word >> 11) · 2⁻⁵³.
/// Written here (not rand's distributions) so the stream is portable and fixed forever.
pub fn uniform_unit(word: u64) -> f64 {
    (word >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// SplitMix64 step (Steele, Lea & Flood 2014): advances the state and returns one output.
fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    finalise_splitmix64(*state)
}

/// The SplitMix64 output of z + γ (Steele, Lea & Flood 2014): the one seed mixer of road
/// samples, study cases and lifetime events.
pub(crate) fn splitmix64_of(z: u64) -> u64 {
    finalise_splitmix64(z.wrapping_add(0x9E37_79B9_7F4A_7C15))
}

/// SplitMix64's finaliser (Steele, Lea & Flood 2014).
fn finalise_splitmix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The random stream of one road sample.
///
/// Derivation (fixed; changing it changes every profile): the 256-bit ChaCha20 key is four
/// successive SplitMix64 outputs of the base seed, stored little-endian; sample i selects
/// ChaCha20 stream (nonce) i of that key. Samples of one base seed are thus independent
/// streams of one key, and sample 0 is what [`generate`] uses.
#[derive(Debug, Clone)]
pub struct SampleRng {
    rng: ChaCha20Rng,
}

impl SampleRng {
    /// The stream of sample `sample_index` of base seed `base_seed`.
    pub fn new(base_seed: u64, sample_index: u64) -> SampleRng {
        let mut state = base_seed;
        let mut key = [0u8; 32];
        for chunk in key.chunks_exact_mut(8) {
            chunk.copy_from_slice(&splitmix64(&mut state).to_le_bytes());
        }
        let mut rng = ChaCha20Rng::from_seed(key);
        rng.set_stream(sample_index);
        SampleRng { rng }
    }

    /// The next raw 64-bit word.
    pub fn next_word(&mut self) -> u64 {
        self.rng.next_u64()
    }

    /// The next uniform number in [0, 1) ([`uniform_unit`]).
    pub fn next_unit(&mut self) -> f64 {
        uniform_unit(self.next_word())
    }
}

/// A finite set of harmonics, the right-hand side of Eq. 22:
/// h(x) = Σ_i a_i cos(2π n_i x + θ_i), with a_i = √(2 G_d(n_i) Δn).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HarmonicSet {
    /// Spatial frequencies n_i [cycles/m].
    pub frequencies: Vec<f64>,
    /// Amplitudes a_i [m].
    pub amplitudes: Vec<f64>,
    /// Phases θ_i [rad].
    pub phases: Vec<f64>,
}

impl HarmonicSet {
    /// Harmonics of Eq. 22 at the given frequencies [cycles/m], each representing a band
    /// Δn [cycles/m]: a_i = √(2 G_d(n_i) Δn).
    pub fn from_psd(
        psd: &DisplacementPsd,
        frequencies: Vec<f64>,
        frequency_step: f64,
        phases: Vec<f64>,
    ) -> HarmonicSet {
        let amplitudes = frequencies
            .iter()
            .map(|&n| (2.0 * psd.value(n) * frequency_step).sqrt())
            .collect();
        HarmonicSet {
            frequencies,
            amplitudes,
            phases,
        }
    }

    /// h(x) [m] at x [m], Eq. 22 summed directly.
    pub fn evaluate(&self, x: f64) -> f64 {
        self.frequencies
            .iter()
            .zip(&self.amplitudes)
            .zip(&self.phases)
            .map(|((n, a), theta)| a * (2.0 * PI * n * x + theta).cos())
            .sum()
    }

    /// Mean square Σ a_i²/2 [m²] (= Σ G_d(n_i) Δn for a set built by [`HarmonicSet::from_psd`]).
    pub fn mean_square(&self) -> f64 {
        self.amplitudes.iter().map(|a| 0.5 * a * a).sum()
    }

    /// h at x_j = start + j·spacing, j < count, summed directly.
    pub fn sample_direct(&self, start: f64, spacing: f64, count: usize) -> Vec<f64> {
        (0..count)
            .map(|j| self.evaluate(start + j as f64 * spacing))
            .collect()
    }

    /// h at x_j = start + j·spacing, j < count, by one inverse real FFT of length `fft_length`
    /// ≥ count (hand-written on realfft: X_k = (a/2) e^{i(θ + 2π n start)} at k = n·N·Δx, then
    /// Σ_k 2 Re X_k e^{2πi kj/N}). Every frequency must be a grid line k/(N Δx) with
    /// 0 < k < N/2 (to 10⁻⁹ of a line).
    pub fn sample_fft(
        &self,
        start: f64,
        spacing: f64,
        count: usize,
        fft_length: usize,
    ) -> Result<Vec<f64>, RoadError> {
        // One planner for the process, which keeps its plans (their twiddle factors) for the
        // next road of the same length: a study's roughness samples share them. The lock is
        // held while planning only.
        static PLANNER: LazyLock<Mutex<RealFftPlanner<f64>>> =
            LazyLock::new(|| Mutex::new(RealFftPlanner::new()));
        let grid = 1.0 / (fft_length as f64 * spacing);
        let inverse = PLANNER
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .plan_fft_inverse(fft_length);
        let mut spectrum = inverse.make_input_vec();
        for (index, ((&n, &a), &theta)) in self
            .frequencies
            .iter()
            .zip(&self.amplitudes)
            .zip(&self.phases)
            .enumerate()
        {
            let line = n / grid;
            let k = line.round();
            if (line - k).abs() > 1e-9 * line.max(1.0) || k < 1.0 || k >= (fft_length / 2) as f64 {
                return Err(RoadError::NotOnFftGrid {
                    index,
                    frequency: n,
                    grid,
                });
            }
            // Shift the phase to the first sample: cos(2π n (start + jΔx) + θ).
            let phase = theta + 2.0 * PI * (n * start).rem_euclid(1.0);
            spectrum[k as usize] += Complex::from_polar(0.5 * a, phase);
        }
        let mut out = inverse.make_output_vec();
        inverse
            .process(&mut spectrum, &mut out)
            .map_err(|_| RoadError::NotOnFftGrid {
                index: 0,
                frequency: 0.0,
                grid,
            })?;
        out.truncate(count.min(fft_length));
        Ok(out)
    }
}

/// The phase spreads a_i = [`phase_spread_for_coherence`](γ(n_i)) of coherent tracks at the
/// frequencies n_i [cycles/m], for a track spacing [m] and coherence decay [-]. They depend on
/// nothing else, and a study's roughness samples share them: the last few sets computed are
/// kept (process-wide, [`KEPT_PHASE_SPREAD_SETS`]) and given again, the same bits, to a road
/// that asks for the same frequencies, spacing and decay (each spread costs 60 sines: about
/// 3 % of a crossing of the paper study). Not thread-local: a Python extension module has
/// little static thread-local storage to spare.
fn phase_spreads(frequencies: &[f64], track_spacing: f64, coherence_decay: f64) -> Vec<f64> {
    let same = |set: &PhaseSpreadSet| {
        set.track_spacing.to_bits() == track_spacing.to_bits()
            && set.coherence_decay.to_bits() == coherence_decay.to_bits()
            && same_bits(&set.frequencies, frequencies)
    };
    // The lock is held for look-ups only; a poisoned lock still holds valid sets.
    let kept = || PHASE_SPREAD_SETS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(set) = kept().iter().find(|set| same(set)) {
        return set.spreads.clone();
    }
    let spreads: Vec<f64> = frequencies
        .iter()
        .map(|&n| phase_spread_for_coherence(coherence(n, track_spacing, coherence_decay)))
        .collect();
    let mut sets = kept();
    if sets.len() >= KEPT_PHASE_SPREAD_SETS {
        sets.remove(0);
    }
    sets.push(PhaseSpreadSet {
        track_spacing,
        coherence_decay,
        frequencies: frequencies.to_vec(),
        spreads: spreads.clone(),
    });
    spreads
}

/// How many sets of phase spreads [`phase_spreads`] keeps: a study's worker threads each
/// generate the roads of one bridge length at a time, so a few sets serve them all.
const KEPT_PHASE_SPREAD_SETS: usize = 8;

/// The phase spreads of one road's frequencies, track spacing and decay.
struct PhaseSpreadSet {
    track_spacing: f64,
    coherence_decay: f64,
    frequencies: Vec<f64>,
    spreads: Vec<f64>,
}

static PHASE_SPREAD_SETS: Mutex<Vec<PhaseSpreadSet>> = Mutex::new(Vec::new());

/// Half-width a of a uniform phase difference δ ∈ [−a, a] whose mean cosine sin(a)/a is γ
/// (bisection on [0, π], where sin(a)/a falls from 1 to 0; hand-written, 60 halvings reach
/// round-off).
fn phase_spread_for_coherence(gamma: f64) -> f64 {
    if gamma >= 1.0 {
        return 0.0;
    }
    if gamma <= 0.0 {
        return PI;
    }
    let (mut lo, mut hi) = (0.0_f64, PI);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let sinc = if mid == 0.0 { 1.0 } else { mid.sin() / mid };
        if sinc > gamma {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Generates sample 0 of the road `spec` over [start, end] [m] with base seed `seed`
/// (see [`generate_sample`]).
pub fn generate(
    spec: &RoadSpec,
    start: f64,
    end: f64,
    seed: u64,
) -> Result<RoadProfile, RoadError> {
    generate_sample(spec, start, end, seed, 0)
}

/// Generates sample `sample_index` of a set with base seed `base_seed` ([`SampleRng`]) over
/// [start, end] [m] (in bridge coordinates, e.g. [`RoadSpec::extent_for_bridge`]).
///
/// Each track is Eq. 22, h(x) = Σ √(2 G_d(n_i) Δn) cos(2π n_i x + θ_i), on the frequencies
/// of `spec.method`. Draw order from the stream (fixed): one uniform u per harmonic for the left
/// phases θ_i = 2πu; then, for independent tracks, one per harmonic for the right phases; for
/// coherent tracks, one per harmonic for a phase difference δ_i = a_i(2u − 1), uniform on
/// [−a_i, a_i] with sin(a_i)/a_i = γ(n_i), so the right phases θ_i + δ_i give the expected
/// cross-spectrum γ(n) G_d(n) while each track keeps exactly the amplitudes of Eq. 22.
/// The same inputs give the same profile bit for bit (single-threaded; on one platform's libm).
pub fn generate_sample(
    spec: &RoadSpec,
    start: f64,
    end: f64,
    base_seed: u64,
    sample_index: u64,
) -> Result<RoadProfile, RoadError> {
    spec.validate()?;
    let (spacing, count) = sample_grid(spec, start, end)?;
    let (mut left, mut right) = match &spec.profile {
        Some(profile) => {
            profile.covers(start, end, spacing)?;
            profile.resampled(start, spacing, count)
        }
        None => random_tracks(
            spec,
            (start, end),
            spacing,
            count,
            (base_seed, sample_index),
        )?,
    };
    add_events(&spec.events, Track::Left, start, spacing, &mut left);
    add_events(&spec.events, Track::Right, start, spacing, &mut right);
    let mut profile = RoadProfile::from_uniform_samples(start, spacing, left, right)?;
    if spec.profile.is_none() && spec.events.is_empty() {
        // Eq. 22's harmonics lie in [n₁, n₂]: no roughness above n₂.
        profile.highest_spatial_frequency = Some(spec.band_upper);
    }
    if spec.tyre_patch_length > 0.0 {
        profile.smoothed(spec.tyre_patch_length)
    } else {
        Ok(profile)
    }
}

/// The sample grid of [start, end] [m]: the spacing [m] (the largest ≤ `spec.sample_spacing`
/// that divides the length into whole intervals) and the number of samples.
fn sample_grid(spec: &RoadSpec, start: f64, end: f64) -> Result<(f64, usize), RoadError> {
    if !(start.is_finite() && end.is_finite() && start < end) {
        return Err(RoadError::InvalidRange { start, end });
    }
    let length = end - start;
    let intervals_real = (length / spec.sample_spacing * (1.0 - 1e-12))
        .ceil()
        .max(1.0);
    if intervals_real >= MAX_SAMPLE_COUNT as f64 {
        return Err(RoadError::TooManySamples {
            count: intervals_real as usize,
            length,
            spacing: spec.sample_spacing,
            limit: MAX_SAMPLE_COUNT,
        });
    }
    let intervals = intervals_real as usize;
    Ok((length / intervals as f64, intervals + 1))
}

/// The harmonics' frequencies [cycles/m] of `spec.method`, the band Δn [cycles/m] each
/// represents, and the inverse FFT's length (0 for the direct sum) for `count` samples at
/// `spacing` [m] over `length` [m].
fn harmonic_frequencies(
    spec: &RoadSpec,
    length: f64,
    spacing: f64,
    count: usize,
) -> Result<(Vec<f64>, f64, usize), RoadError> {
    Ok(match spec.method {
        GenerationMethod::HarmonicSuperposition => {
            let n = spec.harmonic_count;
            if n.saturating_mul(count) > MAX_DIRECT_TERMS {
                return Err(RoadError::TooManyDirectTerms {
                    harmonics: n,
                    samples: count,
                    limit: MAX_DIRECT_TERMS,
                });
            }
            let step = (spec.band_upper - spec.band_lower) / n as f64;
            let freqs = (0..n)
                .map(|i| spec.band_lower + (i as f64 + 0.5) * step)
                .collect::<Vec<_>>();
            (freqs, step, 0)
        }
        GenerationMethod::InverseFft => {
            let resolve = (1.0 / (spec.band_lower * spacing)).ceil();
            let needed = (count as f64).max(resolve);
            if needed > MAX_SAMPLE_COUNT as f64 {
                return Err(RoadError::TooManySamples {
                    count: needed as usize,
                    length,
                    spacing,
                    limit: MAX_SAMPLE_COUNT,
                });
            }
            let fft_length = (needed as usize).next_power_of_two();
            let step = 1.0 / (fft_length as f64 * spacing);
            let first = ((spec.band_lower / step).ceil() as usize).max(1);
            let last = ((spec.band_upper / step).floor() as usize).min(fft_length / 2 - 1);
            let freqs = (first..=last)
                .map(|k| k as f64 / (fft_length as f64 * spacing))
                .collect::<Vec<_>>();
            (freqs, step, fft_length)
        }
    })
}

/// The random roughness of both tracks (Eq. 22, see [`generate_sample`]) at the `count` samples
/// start + j·spacing of the extent (start, end) [m], from the stream (base seed, sample index).
fn random_tracks(
    spec: &RoadSpec,
    (start, end): (f64, f64),
    spacing: f64,
    count: usize,
    (base_seed, sample_index): (u64, u64),
) -> Result<(Vec<f64>, Vec<f64>), RoadError> {
    let length = end - start;
    let psd = spec.psd()?;
    if psd.psd_at_reference == 0.0 {
        return Ok((vec![0.0; count], vec![0.0; count]));
    }
    let (frequencies, frequency_step, fft_length) =
        harmonic_frequencies(spec, length, spacing, count)?;
    let mut rng = SampleRng::new(base_seed, sample_index);
    let left_phases: Vec<f64> = frequencies
        .iter()
        .map(|_| 2.0 * PI * rng.next_unit())
        .collect();
    let right_phases: Option<Vec<f64>> = match spec.track_correlation {
        TrackCorrelation::Identical | TrackCorrelation::VehicleTrack { .. } => None,
        TrackCorrelation::Independent => Some(
            frequencies
                .iter()
                .map(|_| 2.0 * PI * rng.next_unit())
                .collect(),
        ),
        TrackCorrelation::Coherent {
            track_spacing,
            coherence_decay,
        } => Some(
            phase_spreads(&frequencies, track_spacing, coherence_decay)
                .iter()
                .zip(&left_phases)
                .map(|(&spread, &theta)| theta + spread * (2.0 * rng.next_unit() - 1.0))
                .collect(),
        ),
    };
    let sample = |set: &HarmonicSet| -> Result<Vec<f64>, RoadError> {
        match spec.method {
            GenerationMethod::HarmonicSuperposition => Ok(set.sample_direct(start, spacing, count)),
            GenerationMethod::InverseFft => set.sample_fft(start, spacing, count, fft_length),
        }
    };
    let left_set = HarmonicSet::from_psd(&psd, frequencies.clone(), frequency_step, left_phases);
    let left = sample(&left_set)?;
    let right = match right_phases {
        None => left.clone(),
        Some(phases) => sample(&HarmonicSet::from_psd(
            &psd,
            frequencies,
            frequency_step,
            phases,
        ))?,
    };
    Ok((left, right))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_unit_maps_the_extremes_into_the_half_open_interval() {
        assert_eq!(uniform_unit(0), 0.0);
        assert!(uniform_unit(u64::MAX) < 1.0);
        assert_eq!(uniform_unit(1 << 63), 0.5);
    }

    #[test]
    fn phase_spread_inverts_the_mean_cosine() {
        for gamma in [0.05, 0.3, 0.5, 0.9, 0.999] {
            let a = phase_spread_for_coherence(gamma);
            // 60 bisection steps on [0, π]: interval 2.7e-18, so round-off only.
            assert!((a.sin() / a - gamma).abs() < 1e-12, "{gamma}");
        }
        assert_eq!(phase_spread_for_coherence(1.0), 0.0);
        assert_eq!(phase_spread_for_coherence(0.0), PI);
    }

    #[test]
    fn kept_phase_spreads_equal_the_spreads_computed_anew_bit_for_bit() {
        let direct = |frequencies: &[f64], spacing: f64, decay: f64| -> Vec<u64> {
            let spread = |&n: &f64| phase_spread_for_coherence(coherence(n, spacing, decay));
            frequencies.iter().map(spread).map(f64::to_bits).collect()
        };
        let kept = |frequencies: &[f64], spacing: f64, decay: f64| -> Vec<u64> {
            let spreads = phase_spreads(frequencies, spacing, decay);
            spreads.into_iter().map(f64::to_bits).collect()
        };
        let (a, b) = ([0.01, 0.2, 1.5], [0.01, 0.2, 1.6]);
        // Computed, kept, then other frequencies, another spacing, another decay, and back.
        for (frequencies, spacing, decay) in [
            (&a, 1.8, 1.0),
            (&a, 1.8, 1.0),
            (&b, 1.8, 1.0),
            (&b, 2.0, 1.0),
            (&b, 2.0, 0.5),
            (&a, 1.8, 1.0),
        ] {
            assert_eq!(
                kept(frequencies, spacing, decay),
                direct(frequencies, spacing, decay)
            );
        }
    }

    #[test]
    fn sample_streams_of_one_seed_differ_and_repeat() {
        let a: Vec<u64> = (0..4).map(|_| SampleRng::new(7, 0).next_word()).collect();
        assert!(a.windows(2).all(|w| w[0] == w[1]));
        let mut s0 = SampleRng::new(7, 0);
        let mut s1 = SampleRng::new(7, 1);
        assert_ne!(s0.next_word(), s1.next_word());
    }

    #[test]
    fn spec_validation_names_the_bad_numbers() {
        let bad_band = RoadSpec {
            band_lower: 2.0,
            band_upper: 1.0,
            ..RoadSpec::default()
        };
        assert_eq!(
            bad_band.validate(),
            Err(RoadError::InvalidBand {
                lower: 2.0,
                upper: 1.0
            })
        );
        let nyquist = RoadSpec {
            band_upper: 20.0,
            ..RoadSpec::default()
        };
        assert!(matches!(
            nyquist.validate(),
            Err(RoadError::BandAboveNyquist { .. })
        ));
        assert!(RoadSpec::default().validate().is_ok());
    }

    #[test]
    fn smooth_class_generates_zeros_over_the_whole_extent() {
        let spec = RoadSpec::of_class(RoughnessClass::Smooth);
        let p = generate(&spec, -10.0, 10.0, 3).unwrap();
        assert_eq!(p.len(), 401);
        assert!(p.left.iter().chain(&p.right).all(|v| *v == 0.0));
        assert!((p.end() - 10.0).abs() < 1e-12);
    }
}
