//! DAF from measured signals (the paper's §6): the static component by zero-phase low-pass
//! filtering (or from an influence line), DAF per channel, RDM, strain to bending moment, and
//! low-pass filtering at the frequency of the cut-off mode K1 (Figs. 27–28).

use serde::{Deserialize, Serialize};

use super::filter::butterworth_lowpass;
use super::SignalError;

/// What a measured channel records.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MeasuredQuantity {
    /// Vertical deflection [m] (the sign as recorded; the DAF uses the extreme in the
    /// direction of the static response).
    Deflection,
    /// Longitudinal strain [-] at a fibre at distance y from the neutral axis.
    Strain,
    /// Bending moment [N·m], usually converted from strain.
    BendingMoment,
    /// Vertical acceleration [m/s²], used for frequencies, not for a DAF.
    Acceleration,
}

/// Factor of the quasi-static band: the static response of a crossing keeps its shape within
/// this many harmonics of the pass frequency v/L (used by [`automatic_cutoff`]).
pub const QUASI_STATIC_HARMONICS: f64 = 5.0;

/// Why a cut-off frequency was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CutoffRule {
    /// Given by the user.
    Given,
    /// Geometric mean of the quasi-static limit and the first bridge frequency (the two are
    /// well separated).
    GeometricMean,
    /// Capped at half the first bridge frequency (the quasi-static content reaches into the
    /// first mode: the static part is distorted; the DAF is less reliable).
    HalfFirstFrequency,
}

/// A low-pass cut-off frequency for the static component, with the numbers behind it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CutoffChoice {
    /// The cut-off frequency [Hz].
    pub cutoff_hz: f64,
    /// Pass frequency of the crossing f_p = v/L = 1/T_pass [Hz]; `None` when the cut-off was given.
    pub pass_frequency_hz: Option<f64>,
    /// Upper limit of the quasi-static content f_q = 5·f_p [Hz].
    pub quasi_static_limit_hz: Option<f64>,
    /// First bridge frequency f₁ [Hz].
    pub first_frequency_hz: Option<f64>,
    /// Which rule produced the cut-off.
    pub rule: CutoffRule,
    /// False when the quasi-static and the dynamic content overlap (f_q ≥ f₁/2).
    pub separated: bool,
}

/// Chooses the static low-pass cut-off between the quasi-static content of a crossing and the
/// first bridge frequency:
///
/// f_q = 5·f_p (f_p = v/L, or 1/T_pass), f_c = √(f_q·f₁) if that is ≤ f₁/2, else f_c = f₁/2.
///
/// The geometric mean puts the cut-off midway between the two on a log-frequency axis, where
/// a Butterworth filter of order N, applied forwards and backwards, passes f_q with
/// |H|² = 1/(1 + (f_q/f_c)^{2N}) ≈ 1 and removes the first mode to 1/(1 + (f₁/f_c)^{2N}). The
/// cap f₁/2 keeps the first mode attenuated (to 1/257 with N = 4) even for short, fast crossings,
/// whose quasi-static content then overlaps the first mode: `separated` reports it.
pub fn automatic_cutoff(
    pass_frequency_hz: f64,
    first_frequency_hz: f64,
) -> Result<CutoffChoice, SignalError> {
    if !(pass_frequency_hz.is_finite()
        && pass_frequency_hz > 0.0
        && first_frequency_hz.is_finite()
        && first_frequency_hz > 0.0)
    {
        return Err(SignalError::BadCutoffInputs {
            pass_frequency_hz,
            first_frequency_hz,
        });
    }
    let quasi_static = QUASI_STATIC_HARMONICS * pass_frequency_hz;
    let mean = (quasi_static * first_frequency_hz).sqrt();
    let cap = first_frequency_hz / 2.0;
    let (cutoff_hz, rule) = if mean <= cap {
        (mean, CutoffRule::GeometricMean)
    } else {
        (cap, CutoffRule::HalfFirstFrequency)
    };
    Ok(CutoffChoice {
        cutoff_hz,
        pass_frequency_hz: Some(pass_frequency_hz),
        quasi_static_limit_hz: Some(quasi_static),
        first_frequency_hz: Some(first_frequency_hz),
        rule,
        separated: quasi_static < cap,
    })
}

/// The static component of a measured signal: zero-phase Butterworth low-pass of `order` at
/// `cutoff_hz` (forward–backward with odd edge padding, see
/// [`SosFilter::filtfilt`](super::SosFilter::filtfilt)).
pub fn static_component(
    signal: &[f64],
    sampling_rate_hz: f64,
    order: usize,
    cutoff_hz: f64,
) -> Result<Vec<f64>, SignalError> {
    butterworth_lowpass(order, cutoff_hz, sampling_rate_hz)?.filtfilt(signal, None)
}

/// A DAF from a measured signal and its static component.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeasuredDaf {
    /// Direction of the response: +1 or −1, the sign of the static sample of largest magnitude.
    pub direction: f64,
    /// Static maximum in that direction (signed, signal unit).
    pub static_max: f64,
    /// Index of the static maximum.
    pub static_max_index: usize,
    /// Measured (dynamic) maximum in that direction (signed, signal unit).
    pub dynamic_max: f64,
    /// Index of the measured maximum.
    pub dynamic_max_index: usize,
    /// DAF = dynamic_max / static_max [-].
    pub daf: f64,
}

/// DAF = max_t R_measured(t) / max_t R_static(t), both maxima taken in the direction of the
/// static response (the sign of its largest-magnitude sample), so that a downward deflection
/// recorded as negative gives the same DAF as one recorded as positive.
pub fn measured_daf(measured: &[f64], static_part: &[f64]) -> Result<MeasuredDaf, SignalError> {
    if measured.len() != static_part.len() || measured.is_empty() {
        return Err(SignalError::LengthMismatch {
            measured: measured.len(),
            reference: static_part.len(),
        });
    }
    for s in [measured, static_part] {
        if let Some(i) = s.iter().position(|x| !x.is_finite()) {
            return Err(SignalError::NonFiniteSample {
                index: i,
                value: s[i],
            });
        }
    }
    let extreme = static_part
        .iter()
        .copied()
        .fold(0.0_f64, |m, v| if v.abs() > m.abs() { v } else { m });
    if extreme == 0.0 {
        return Err(SignalError::ZeroStaticResponse);
    }
    let direction = extreme.signum();
    let argmax = |s: &[f64]| {
        let mut best = 0;
        for (i, v) in s.iter().enumerate() {
            if direction * v > direction * s[best] {
                best = i;
            }
        }
        best
    };
    let static_max_index = argmax(static_part);
    let dynamic_max_index = argmax(measured);
    let static_max = static_part[static_max_index];
    let dynamic_max = measured[dynamic_max_index];
    Ok(MeasuredDaf {
        direction,
        static_max,
        static_max_index,
        dynamic_max,
        dynamic_max_index,
        daf: dynamic_max / static_max,
    })
}

/// RDM = DAF_deflection / DAF_moment at one section (the paper's ratio of the deflection DAF to
/// the bending-moment DAF).
pub fn rdm(daf_deflection: f64, daf_moment: f64) -> Result<f64, SignalError> {
    if !(daf_deflection.is_finite() && daf_moment.is_finite() && daf_moment > 0.0) {
        return Err(SignalError::BadDafPair {
            daf_deflection,
            daf_moment,
        });
    }
    Ok(daf_deflection / daf_moment)
}

/// How a strain converts to a bending moment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StrainToMoment {
    /// Elastic beam theory: M = E·I·ε / y.
    Section {
        /// Young's modulus E [Pa].
        elastic_modulus: f64,
        /// Second moment of area I [m⁴].
        second_moment_of_area: f64,
        /// Distance y from the neutral axis to the gauge [m], positive below it (tension
        /// under sagging).
        distance_to_neutral_axis: f64,
    },
    /// M = factor · ε, factor [N·m per unit strain].
    Factor {
        /// The factor [N·m].
        newton_metres_per_strain: f64,
    },
}

impl StrainToMoment {
    /// The factor M/ε [N·m]: E·I/y, or the given factor.
    pub fn factor(&self) -> Result<f64, SignalError> {
        let f = match *self {
            StrainToMoment::Section {
                elastic_modulus,
                second_moment_of_area,
                distance_to_neutral_axis,
            } => elastic_modulus * second_moment_of_area / distance_to_neutral_axis,
            StrainToMoment::Factor {
                newton_metres_per_strain,
            } => newton_metres_per_strain,
        };
        if f.is_finite() && f != 0.0 {
            Ok(f)
        } else {
            Err(SignalError::BadStrainFactor { factor: f })
        }
    }

    /// Converts strains [-] to bending moments [N·m].
    pub fn apply(&self, strain: &[f64]) -> Result<Vec<f64>, SignalError> {
        let f = self.factor()?;
        Ok(strain.iter().map(|e| e * f).collect())
    }
}

/// An influence line given as samples: response per unit downward load [signal unit per N] at
/// load positions [m] (strictly increasing), linear between samples and zero outside.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SampledInfluenceLine {
    /// Load positions x [m], strictly increasing.
    pub positions: Vec<f64>,
    /// Response per unit load at each position [signal unit per N].
    pub values: Vec<f64>,
}

impl SampledInfluenceLine {
    /// Validates the samples (at least two, finite, strictly increasing positions).
    pub fn new(positions: Vec<f64>, values: Vec<f64>) -> Result<Self, SignalError> {
        if positions.len() != values.len() || positions.len() < 2 {
            return Err(SignalError::BadInfluenceLine {
                index: 0,
                reason: format!(
                    "{} positions and {} values; expected two or more of each, as many values as positions",
                    positions.len(),
                    values.len()
                ),
            });
        }
        for i in 0..positions.len() {
            if !(positions[i].is_finite() && values[i].is_finite()) {
                return Err(SignalError::BadInfluenceLine {
                    index: i,
                    reason: "not a finite number".into(),
                });
            }
            if i > 0 && positions[i] <= positions[i - 1] {
                return Err(SignalError::BadInfluenceLine {
                    index: i,
                    reason: format!(
                        "position {} m does not increase from {} m",
                        positions[i],
                        positions[i - 1]
                    ),
                });
            }
        }
        Ok(SampledInfluenceLine { positions, values })
    }

    /// Linear interpolation at x [m]; zero outside the sampled range.
    pub fn evaluate(&self, x: f64) -> f64 {
        let p = &self.positions;
        if x < p[0] || x > p[p.len() - 1] {
            return 0.0;
        }
        let i = p.partition_point(|&q| q <= x).clamp(1, p.len() - 1);
        let t = (x - p[i - 1]) / (p[i] - p[i - 1]);
        self.values[i - 1] + t * (self.values[i] - self.values[i - 1])
    }
}

/// A vehicle crossing at constant speed, as static loads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MovingLoads {
    /// Static axle loads [N], downward positive.
    pub axle_loads: Vec<f64>,
    /// Distance of each axle behind the first one [m] (the first is 0).
    pub axle_offsets: Vec<f64>,
    /// Speed v [m/s].
    pub speed: f64,
    /// Time at which the first axle is at x = 0 [s].
    pub entry_time: f64,
}

/// Static reference from an influence line: R_s(t) = Σ_a P_a·IL(v·(t − t₀) − d_a).
pub fn static_from_influence_line(
    times: &[f64],
    line: &SampledInfluenceLine,
    loads: &MovingLoads,
) -> Result<Vec<f64>, SignalError> {
    if loads.axle_loads.len() != loads.axle_offsets.len()
        || loads.axle_loads.is_empty()
        || !(loads.speed.is_finite() && loads.speed > 0.0)
        || !loads.entry_time.is_finite()
    {
        return Err(SignalError::BadMovingLoads {
            axles: loads.axle_loads.len(),
            offsets: loads.axle_offsets.len(),
            speed: loads.speed,
        });
    }
    Ok(times
        .iter()
        .map(|&t| {
            let front = loads.speed * (t - loads.entry_time);
            loads
                .axle_loads
                .iter()
                .zip(&loads.axle_offsets)
                .map(|(p, d)| p * line.evaluate(front - d))
                .sum()
        })
        .collect())
}

/// Gain of the zero-phase K1 filter at the frequency of mode K1: |H(f_K1)|² = 0.99 (the
/// forward–backward Butterworth's amplitude 1/(1 + (f/f_c)^{2N})), so that mode K1 itself passes
/// within 1 % and a DAF changes only by what lies above it.
pub const CUTOFF_MODE_GAIN: f64 = 0.99;

/// The cut-off [Hz] of the order-`order` zero-phase low-pass that passes mode K1 at
/// `k1_frequency_hz` with the gain [`CUTOFF_MODE_GAIN`]: f_c = f_K1·(1/g − 1)^{−1/(2N)}
/// (1.78·f_K1 for N = 4). Filtering exactly at f_K1 would halve mode K1's amplitude
/// (|H|² = ½ twice over), distorting the very response the filter should keep.
pub fn cutoff_above_mode(k1_frequency_hz: f64, order: usize) -> f64 {
    k1_frequency_hz * (1.0 / CUTOFF_MODE_GAIN - 1.0).powf(-1.0 / (2.0 * order as f64))
}

/// DAF before and after low-pass filtering above the frequency of the cut-off mode K1 (the
/// paper's Figs. 27–28: filtering at K1 removes noise above the modes that carry 95 % of the
/// response without distorting the DAF).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CutoffModeFiltering {
    /// Frequency of mode K1 [Hz].
    pub mode_frequency_hz: f64,
    /// The filter's cut-off [Hz]: [`cutoff_above_mode`], capped at 0.95 × Nyquist.
    pub cutoff_hz: f64,
    /// Amplitude gain of the zero-phase filter at f_K1 [-] (0.99 unless the cap lowered it).
    pub mode_gain: f64,
    /// The filtered signal (zero-phase, same length).
    pub filtered: Vec<f64>,
    /// DAF of the raw signal.
    pub before: MeasuredDaf,
    /// DAF of the filtered signal.
    pub after: MeasuredDaf,
    /// (DAF_after − DAF_before) / DAF_before [-].
    pub relative_change: f64,
}

/// Zero-phase Butterworth low-pass of `order` that passes mode K1 (at `k1_frequency_hz`) with
/// gain 0.99 ([`cutoff_above_mode`]), and the DAF before and after against the same static
/// component: the static content lies far below f_K1, where the filter passes it unchanged.
pub fn cutoff_mode_filtering(
    measured: &[f64],
    static_part: &[f64],
    sampling_rate_hz: f64,
    order: usize,
    k1_frequency_hz: f64,
) -> Result<CutoffModeFiltering, SignalError> {
    let cutoff_hz = cutoff_above_mode(k1_frequency_hz, order).min(0.95 * sampling_rate_hz / 2.0);
    let filtered =
        butterworth_lowpass(order, cutoff_hz, sampling_rate_hz)?.filtfilt(measured, None)?;
    let before = measured_daf(measured, static_part)?;
    let after = measured_daf(&filtered, static_part)?;
    let relative_change = (after.daf - before.daf) / before.daf;
    Ok(CutoffModeFiltering {
        mode_frequency_hz: k1_frequency_hz,
        cutoff_hz,
        mode_gain: 1.0 / (1.0 + (k1_frequency_hz / cutoff_hz).powi(2 * order as i32)),
        filtered,
        before,
        after,
        relative_change,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strain_converts_through_e_i_over_y() {
        // M = E I ε / y: 34.5 GPa · 0.5 m⁴ · 100 µε / 0.9 m = 1.916667 MN·m (closed form).
        let c = StrainToMoment::Section {
            elastic_modulus: 34.5e9,
            second_moment_of_area: 0.5,
            distance_to_neutral_axis: 0.9,
        };
        let m = c.apply(&[100e-6]).unwrap()[0];
        assert!((m - 34.5e9 * 0.5 * 100e-6 / 0.9).abs() < 1e-6);
    }

    #[test]
    fn a_downward_signal_gives_a_positive_daf() {
        let stat = [0.0, -1.0, -2.0, -1.0, 0.0];
        let meas = [0.0, -1.1, -2.2, -0.9, 0.1];
        let d = measured_daf(&meas, &stat).unwrap();
        assert_eq!(d.direction, -1.0);
        assert!((d.daf - 1.1).abs() < 1e-12);
    }

    #[test]
    fn automatic_cutoff_is_the_geometric_mean_when_separated() {
        // 4×30 m at 20 m/s: f_p = 1/6 Hz, f_q = 5/6 Hz, f₁ = 4 Hz → √(10/3) = 1.8257 Hz.
        let c = automatic_cutoff(20.0 / 120.0, 4.0).unwrap();
        assert_eq!(c.rule, CutoffRule::GeometricMean);
        assert!((c.cutoff_hz - (10.0f64 / 3.0).sqrt()).abs() < 1e-12);
        // 30 m at 25 m/s: f_q = 4.17 Hz > f₁/2 → capped at 2 Hz.
        let c = automatic_cutoff(25.0 / 30.0, 4.0).unwrap();
        assert_eq!(c.rule, CutoffRule::HalfFirstFrequency);
        assert!(!c.separated);
        assert_eq!(c.cutoff_hz, 2.0);
    }
}
