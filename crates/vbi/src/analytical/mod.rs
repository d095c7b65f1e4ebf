//! Closed-form moving-load theory of continuous beams: the paper's §2 (Eqs. 1–18).
//!
//! A uniform Euler–Bernoulli beam of `spans` equal spans `l`, pinned at every support
//! (x = 0, l, 2l, … N·l), crossed at constant speed v by a constant downward force P:
//!
//! ```text
//! EI ∂⁴w/∂x⁴ + m̄ ∂²w/∂t² + c ∂w/∂t = −P δ(x − v t)          (Eqs. 1–2, w upwards)
//! w(x,t) = Σ φₙ(x) qₙ(t),   M(x,t) = EI Σ φₙ''(x) qₙ(t)        (Eqs. 3–4, M sagging positive)
//! q̈ₙ + 2ζₙωₙ q̇ₙ + ωₙ² qₙ = −P φₙ(v t)   (mass-normalised φₙ, 0 ≤ v t ≤ N l)
//! ```
//!
//! * [`modes`]: exact modes from the exact frequency equation (not the paper's approximation
//!   αₙ = 3.927 + (n/2 − 1)π), normalised to unit modal mass, with their second derivatives.
//! * [`moving_force`]: the Duhamel integral (Eqs. 7–13) evaluated exactly, span by span;
//!   [`section_history`] gives w(x, t) and M(x, t) at a section (the reference for numerical
//!   moving-load solvers).
//! * [`statics`]: exact statics λ₁, λ₂ (Eq. 14) by the three-moment equation.
//! * [`daf`]: DAF_u(K), DAF_M(K) and RDM(K) (Eqs. 15–17), from the paper's plain modal sums and
//!   from the static-corrected (mode-acceleration) sums that converge in a few modes.
//! * [`fryba`]: Frýba's closed form for the simply supported beam (the case N = 1).
//!
//! Conventions: SI units; x from the first support; deflection w positive upwards; bending
//! moment positive sagging; the force P is positive downwards. The speed parameter is
//! α = v / (2 f₁ l) with l the span length (docs/verification.md §0); for a single
//! span it equals Frýba's Ω/ω₁ = πv/(l ω₁).

pub mod daf;
pub mod fryba;
pub mod modes;
pub mod moving_force;
pub mod statics;

pub use daf::{daf_by_modes, DafOptions, DafTable, MaximumWindow, StaticReference};
pub use modes::{continuous_beam_modes, frequency_parameters, two_span_even_roots, BeamMode};
pub use moving_force::{section_history, ModalMovingForce, MovingForce, SectionHistory};
pub use statics::{static_load_factors, static_response, StaticResponse};

/// Largest number of spans accepted (the theory holds for any N; this bounds the work).
pub const MAX_SPANS: usize = 64;

/// Errors of the closed-form theory; each carries the offending numbers.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AnalyticalError {
    /// A physical parameter is not a finite positive number.
    #[error("{name} = {value} is not allowed; expected a finite positive number")]
    NotPositive {
        /// Parameter name.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The number of spans is outside 1..=MAX_SPANS.
    #[error("{spans} spans is not allowed; expected 1 to {max}")]
    SpanCount {
        /// Number of spans given.
        spans: usize,
        /// Largest allowed.
        max: usize,
    },
    /// The number of modes is zero or too large.
    #[error("{modes} modes is not allowed; expected 1 to {max}")]
    ModeCount {
        /// Number of modes asked for.
        modes: usize,
        /// Largest allowed.
        max: usize,
    },
    /// A modal damping ratio outside [0, 1).
    #[error("damping ratio {value} is not allowed; expected 0 ≤ ζ < 1")]
    DampingRatio {
        /// The value given.
        value: f64,
    },
    /// A position (section or load) outside the beam.
    #[error("{name} = {value} m lies outside the beam [0, {length}] m")]
    OutsideBeam {
        /// Which position.
        name: &'static str,
        /// The position given \[m\].
        value: f64,
        /// Total length of the beam \[m\].
        length: f64,
    },
    /// The static reference of a quantity is zero at the section (a support), so its DAF is
    /// undefined.
    #[error("the static {quantity} at x = {section} m is zero (a support?): its DAF is undefined")]
    ZeroStaticResponse {
        /// `deflection` or `bending moment`.
        quantity: &'static str,
        /// Section \[m\].
        section: f64,
    },
    /// Too few output times for a time history.
    #[error("{count} output times is not allowed; expected at least 3")]
    OutputTimes {
        /// Number given.
        count: usize,
    },
    /// A free-vibration window too long to sample at the crossing's spacing.
    #[error(
        "a free-vibration duration of {duration} s needs {samples} output instants at the \
         crossing's spacing of {spacing:e} s; at most {limit} are allowed: shorten the window \
         (the maximum of a damped response comes within a few periods of the first mode) or \
         use fewer output times"
    )]
    FreeVibrationTooLong {
        /// The window [s].
        duration: f64,
        /// Instants it would need.
        samples: f64,
        /// The spacing of the crossing's instants [s].
        spacing: f64,
        /// The most allowed.
        limit: usize,
    },
    /// A DAF came out non-finite (parameters beyond the floating-point range).
    #[error("the DAF with {modes} modes is not finite (deflection {deflection}, moment {moment})")]
    NonFinite {
        /// K.
        modes: usize,
        /// DAF_u(K).
        deflection: f64,
        /// DAF_M(K).
        moment: f64,
    },
    /// A frequency-equation root could not be bracketed (a bug: the theory guarantees it).
    #[error("no root of the frequency equation in band {band} at level {level}")]
    RootNotFound {
        /// Band index k (roots between kπ and the k-th clamped–clamped root).
        band: usize,
        /// The level cos(pπ/N) sought.
        level: f64,
    },
}

/// A uniform continuous beam of equal spans, pinned at every support.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ContinuousBeam {
    /// Number of equal spans N (1 = simply supported). No default.
    pub spans: usize,
    /// Span length l \[m\]. No default.
    pub span_length: f64,
    /// Flexural rigidity EI \[N·m²\]. No default.
    pub flexural_rigidity: f64,
    /// Mass per unit length m̄ \[kg/m\]. No default.
    pub mass_per_length: f64,
}

impl ContinuousBeam {
    /// Checks the parameters: 1 ≤ spans ≤ [`MAX_SPANS`], the others finite and positive.
    pub fn new(
        spans: usize,
        span_length: f64,
        flexural_rigidity: f64,
        mass_per_length: f64,
    ) -> Result<ContinuousBeam, AnalyticalError> {
        let beam = ContinuousBeam {
            spans,
            span_length,
            flexural_rigidity,
            mass_per_length,
        };
        beam.validate()?;
        Ok(beam)
    }

    /// Checks the parameters (for a beam built as a struct literal).
    pub fn validate(&self) -> Result<(), AnalyticalError> {
        if self.spans == 0 || self.spans > MAX_SPANS {
            return Err(AnalyticalError::SpanCount {
                spans: self.spans,
                max: MAX_SPANS,
            });
        }
        positive("span_length", self.span_length)?;
        positive("flexural_rigidity", self.flexural_rigidity)?;
        positive("mass_per_length", self.mass_per_length)?;
        Ok(())
    }

    /// Total length N·l \[m\].
    pub fn total_length(&self) -> f64 {
        self.spans as f64 * self.span_length
    }

    /// ω = (a/l)² √(EI/m̄) \[rad/s\] for a frequency parameter a (the paper's ωₙ below Eq. 9).
    pub fn angular_frequency(&self, frequency_parameter: f64) -> f64 {
        (frequency_parameter / self.span_length).powi(2)
            * (self.flexural_rigidity / self.mass_per_length).sqrt()
    }

    /// Fundamental frequency f₁ = π/(2l²) √(EI/m̄) \[Hz\] (every span vibrates as simply supported).
    pub fn fundamental_frequency_hz(&self) -> f64 {
        self.angular_frequency(std::f64::consts::PI) / (2.0 * std::f64::consts::PI)
    }

    /// Speed parameter α = v / (2 f₁ l) of a speed v \[m/s\].
    pub fn speed_parameter(&self, speed: f64) -> f64 {
        speed / (2.0 * self.fundamental_frequency_hz() * self.span_length)
    }

    /// Speed v = 2 α f₁ l \[m/s\] of a speed parameter α.
    pub fn speed_from_parameter(&self, alpha: f64) -> f64 {
        2.0 * alpha * self.fundamental_frequency_hz() * self.span_length
    }

    pub(crate) fn check_position(&self, name: &'static str, x: f64) -> Result<(), AnalyticalError> {
        let length = self.total_length();
        // A relative slack of 1e-12 accepts an end position computed as N·l by rounding.
        if x.is_finite() && x >= -1e-12 * length && x <= length * (1.0 + 1e-12) {
            Ok(())
        } else {
            Err(AnalyticalError::OutsideBeam {
                name,
                value: x,
                length,
            })
        }
    }
}

pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, AnalyticalError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(AnalyticalError::NotPositive { name, value })
    }
}

/// Composite 8-point Gauss–Legendre quadrature of `f` on [lo, hi] with `pieces` sub-intervals.
/// Hand-written: exact for polynomials of degree 15 per piece; used for modal masses and the
/// quadrature cross-checks.
pub fn gauss_legendre(f: impl Fn(f64) -> f64, lo: f64, hi: f64, pieces: usize) -> f64 {
    const NODES: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const WEIGHTS: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let pieces = pieces.max(1);
    let h = (hi - lo) / pieces as f64;
    let mut sum = 0.0;
    for p in 0..pieces {
        let mid = lo + (p as f64 + 0.5) * h;
        let half = 0.5 * h;
        for (x, w) in NODES.iter().zip(WEIGHTS.iter()) {
            sum += w * half * (f(mid - half * x) + f(mid + half * x));
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_sin_squared_exactly() {
        // ∫₀^π sin² = π/2; 8 pieces of 8 points reach round-off.
        let v = gauss_legendre(|x| x.sin().powi(2), 0.0, std::f64::consts::PI, 8);
        assert!((v - std::f64::consts::FRAC_PI_2).abs() < 1e-14);
    }

    #[test]
    fn a_beam_with_no_span_or_negative_rigidity_is_rejected() {
        assert!(matches!(
            ContinuousBeam::new(0, 20.0, 1.0, 1.0),
            Err(AnalyticalError::SpanCount { spans: 0, .. })
        ));
        assert!(matches!(
            ContinuousBeam::new(2, 20.0, -1.0, 1.0),
            Err(AnalyticalError::NotPositive {
                name: "flexural_rigidity",
                ..
            })
        ));
    }
}
