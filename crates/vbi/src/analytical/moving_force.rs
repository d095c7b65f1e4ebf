//! Modal response to a constant force crossing the beam (the paper's Eqs. 7–13), evaluated
//! exactly.
//!
//! For a mass-normalised mode the modal equation is q̈ + 2ζωq̇ + ω²q = −P φ(v t) while
//! 0 ≤ v t ≤ N l, and free vibration afterwards. On span i the force term, in local time
//! u = t − i l/v and with σ = a v / l, is a sum of exponentials
//!
//! ```text
//! φ = c₀ sin σu + c₁ cos σu + c₂ e^(σu − a) + c₃ e^(−σu) = Re[(c₁ − i c₀) e^(iσu)] + …
//! ```
//!
//! and the Duhamel integral of each, with h(t) = (e^(λ₁t) − e^(λ₂t))/(λ₁ − λ₂),
//! λ₁,₂ = −ζω ± iω_D, ω_D = ω√(1 − ζ²), is exact:
//!
//! ```text
//! ∫₀ᵘ e^(λ(u−r)) e^(sr+κ) dr = (e^(su+κ) − e^(λu+κ)) / (s − λ) = e^(λu+κ) u φ₁((s − λ)u),
//! φ₁(z) = (eᶻ − 1)/z.
//! ```
//!
//! The φ₁ form (by its series when |z| is small) is the resonance limit β = 1, ζ = 0 (s = λ)
//! without any special case, and every exponent above is ≤ 0, so nothing overflows at any speed.
//! The state (q, q̇) is carried from span to span by the free response. This replaces the
//! quadrature of Eqs. 11 and 13; for sine modes it equals Eq. 8 (with the forced cos Ωt term
//! that the printed Eq. 8 omits: see [`super::fryba::sine_mode_response`]).
//!
//! Hand-written: no crate evaluates these piecewise Duhamel integrals.

use nalgebra::Complex;

use super::{AnalyticalError, BeamMode};

/// A constant force crossing the beam at constant speed, entering at x = 0 at t = 0.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MovingForce {
    /// Force P, positive downwards \[N\]. No default.
    pub force: f64,
    /// Speed v \[m/s\]. No default.
    pub speed: f64,
}

type C = Complex<f64>;

/// φ₁(z) = (eᶻ − 1)/z, by its Taylor series for |z| < 0.5 (18 terms: error < 1e-17).
fn phi1(z: C) -> C {
    let mut term = C::new(1.0, 0.0);
    let mut sum = term;
    for k in 2..20 {
        term = term * z / k as f64;
        sum += term;
    }
    sum
}

/// Below this |(s − λ)u| the convolution uses the φ₁ series (no cancellation).
const SERIES_LIMIT: f64 = 0.5;

/// ∫₀ᵘ e^(λ(u−r)) e^(sr+κ) dr from the already computed exponentials e^(su+κ) and e^(λu+κ),
/// and 1/(s − λ); stable for every argument with Re(su+κ) ≤ 0 and Re λ ≤ 0.
#[inline]
fn convolution(exp_s: C, exp_lambda: C, s_minus_lambda: C, inverse: C, u: f64) -> C {
    let z = s_minus_lambda * u;
    if z.norm_sqr() < SERIES_LIMIT * SERIES_LIMIT {
        exp_lambda * u * phi1(z)
    } else {
        (exp_s - exp_lambda) * inverse
    }
}

/// One mode's response to a unit downward force crossing at speed v: the state at every span
/// entry, and everything needed to evaluate q(t) exactly at any t ≥ 0.
#[derive(Debug, Clone)]
pub struct ModalMovingForce {
    mode: BeamMode,
    damping_ratio: f64,
    span_time: f64,
    omega: f64,
    damped_frequency: f64,
    /// σ = a v / l \[rad/s\].
    sigma: f64,
    /// e^(−a).
    exp_minus_a: f64,
    /// λ₁ = −ζω + iω_D.
    lambda: C,
    /// s − λ and 1/(s − λ) for (s, λ) = (iσ, λ₁), (iσ, λ₂), (σ, λ₁), (−σ, λ₁).
    differences: [C; 4],
    inverses: [C; 4],
    /// (q, q̇) at t = i l/v, i = 0 … N, for P = 1 N.
    entry_states: Vec<(f64, f64)>,
}

impl ModalMovingForce {
    /// Prepares the response of `mode` with modal damping ratio ζ ∈ [0, 1) to a force crossing
    /// at `speed` \[m/s\].
    pub fn new(
        mode: &BeamMode,
        damping_ratio: f64,
        speed: f64,
    ) -> Result<ModalMovingForce, AnalyticalError> {
        if !(damping_ratio.is_finite() && (0.0..1.0).contains(&damping_ratio)) {
            return Err(AnalyticalError::DampingRatio {
                value: damping_ratio,
            });
        }
        super::positive("speed", speed)?;
        let omega = mode.angular_frequency;
        let damped_frequency = omega * (1.0 - damping_ratio * damping_ratio).sqrt();
        let a = mode.frequency_parameter;
        let sigma = a * speed / mode.span_length;
        let l1 = C::new(-damping_ratio * omega, damped_frequency);
        let l2 = l1.conj();
        let differences = [
            C::new(0.0, sigma) - l1,
            C::new(0.0, sigma) - l2,
            C::new(sigma, 0.0) - l1,
            C::new(-sigma, 0.0) - l1,
        ];
        let inverses = differences.map(|d| {
            if d.norm_sqr() > 0.0 {
                d.inv()
            } else {
                C::new(0.0, 0.0) // exact resonance: only the series branch is used
            }
        });
        let mut this = ModalMovingForce {
            mode: mode.clone(),
            damping_ratio,
            span_time: mode.span_length / speed,
            omega,
            damped_frequency,
            sigma,
            exp_minus_a: (-a).exp(),
            lambda: l1,
            differences,
            inverses,
            entry_states: Vec::with_capacity(mode.spans() + 1),
        };
        let mut state = (0.0, 0.0);
        this.entry_states.push(state);
        for i in 0..mode.spans() {
            state = this.on_span(i, state, this.span_time);
            this.entry_states.push(state);
        }
        Ok(this)
    }

    /// The mode.
    pub fn mode(&self) -> &BeamMode {
        &self.mode
    }

    /// Time the force spends on the beam, N l / v \[s\].
    pub fn crossing_time(&self) -> f64 {
        self.span_time * self.mode.spans() as f64
    }

    /// e^(λ₁u) = e^(−ζωu)(cos ω_D u + i sin ω_D u).
    #[inline]
    fn exp_lambda(&self, u: f64) -> C {
        let decay = (self.lambda.re * u).exp();
        let (s, c) = (self.damped_frequency * u).sin_cos();
        C::new(decay * c, decay * s)
    }

    /// Free response after u \[s\] from state (q, q̇), given e^(λ₁u).
    #[inline]
    fn free(&self, (q0, p0): (f64, f64), el: C) -> (f64, f64) {
        let w = self.omega;
        let z = self.damping_ratio;
        let wd = self.damped_frequency;
        (
            el.re * q0 + el.im * (p0 + z * w * q0) / wd,
            el.re * p0 - el.im * (w * w * q0 + z * w * p0) / wd,
        )
    }

    /// State (q, q̇) after u \[s\] on span i, from the state at its entry: free response plus the
    /// zero-initial-state response to the modal force −φ(x(t)).
    fn on_span(&self, span: usize, entry: (f64, f64), u: f64) -> (f64, f64) {
        let el = self.exp_lambda(u);
        let (q_free, p_free) = self.free(entry, el);
        let c = &self.mode.span_coefficients[span];
        let (d, inv) = (&self.differences, &self.inverses);
        let wd = self.damped_frequency;
        let (l1, l2) = (self.lambda, self.lambda.conj());
        // Oscillatory part: forcing Re[(c₁ − i c₀) e^(iσu)].
        let (ss, cs) = (self.sigma * u).sin_cos();
        let es = C::new(cs, ss);
        let e1 = convolution(es, el, d[0], inv[0], u);
        let e2 = convolution(es, el.conj(), d[1], inv[1], u);
        let amp = C::new(c[1], -c[0]);
        // (λ₁ − λ₂) = 2iω_D: divide by it as multiplication by −i/(2ω_D).
        let half = C::new(0.0, -0.5 / wd);
        let q_osc = (amp * (e1 - e2) * half).re;
        let p_osc = (amp * (l1 * e1 - l2 * e2) * half).re;
        // Real exponentials: the kernel is real, so I = Im(E(λ₁))/ω_D and İ = Im(λ₁E(λ₁))/ω_D.
        let mut q_exp = 0.0;
        let mut p_exp = 0.0;
        if c[2] != 0.0 {
            let g_s = C::new((self.sigma * u - self.mode.frequency_parameter).exp(), 0.0);
            let g = convolution(g_s, el * self.exp_minus_a, d[2], inv[2], u);
            q_exp += c[2] * g.im;
            p_exp += c[2] * (l1 * g).im;
        }
        if c[3] != 0.0 {
            let h_s = C::new((-self.sigma * u).exp(), 0.0);
            let h = convolution(h_s, el, d[3], inv[3], u);
            q_exp += c[3] * h.im;
            p_exp += c[3] * (l1 * h).im;
        }
        // The force is downward: modal force −φ.
        (q_free - (q_osc + q_exp / wd), p_free - (p_osc + p_exp / wd))
    }

    /// Modal coordinate q(t) and its rate q̇(t) for a unit downward force (multiply by P).
    pub fn state(&self, t: f64) -> (f64, f64) {
        if t <= 0.0 {
            return (0.0, 0.0);
        }
        let n = self.mode.spans();
        if t >= self.crossing_time() {
            let el = self.exp_lambda(t - self.crossing_time());
            return self.free(self.entry_states[n], el);
        }
        let i = ((t / self.span_time).floor() as usize).min(n - 1);
        let u = t - i as f64 * self.span_time;
        self.on_span(i, self.entry_states[i], u)
    }

    /// Modal coordinate q(t) for a unit downward force [kg^(1/2)·m per N].
    pub fn displacement(&self, t: f64) -> f64 {
        self.state(t).0
    }
}

/// Deflection and bending moment histories at one section.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SectionHistory {
    /// Times \[s\].
    pub times: Vec<f64>,
    /// Deflection w, positive upwards \[m\].
    pub deflection: Vec<f64>,
    /// Bending moment M, positive sagging \[N·m\].
    pub bending_moment: Vec<f64>,
}

/// Deflection and bending moment at `section` \[m\] at the given times \[s\] (t = 0 when the force
/// enters at x = 0), from the first `modes` exact modes with modal damping ratio ζ (Eqs. 3–4):
/// w = Σ φₙ(x) qₙ(t), M = EI Σ φₙ''(x) qₙ(t). The reference for numerical moving-load solvers.
pub fn section_history(
    beam: &super::ContinuousBeam,
    load: &MovingForce,
    damping_ratio: f64,
    modes: usize,
    section: f64,
    times: &[f64],
) -> Result<SectionHistory, AnalyticalError> {
    beam.validate()?;
    beam.check_position("section", section)?;
    if !load.force.is_finite() {
        return Err(AnalyticalError::NotPositive {
            name: "force",
            value: load.force,
        });
    }
    let basis = super::continuous_beam_modes(beam, modes)?;
    let mut deflection = vec![0.0; times.len()];
    let mut bending_moment = vec![0.0; times.len()];
    for mode in &basis {
        let response = ModalMovingForce::new(mode, damping_ratio, load.speed)?;
        let phi = mode.shape(section) * load.force;
        let moment = beam.flexural_rigidity * mode.curvature(section) * load.force;
        for (j, &t) in times.iter().enumerate() {
            let q = response.displacement(t);
            deflection[j] += phi * q;
            bending_moment[j] += moment * q;
        }
    }
    Ok(SectionHistory {
        times: times.to_vec(),
        deflection,
        bending_moment,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::{continuous_beam_modes, gauss_legendre, ContinuousBeam};

    /// Brute-force Duhamel quadrature of Eq. 11/13: q(t) = −∫₀ᵗ h(t − τ) φ(vτ) dτ.
    fn duhamel_quadrature(mode: &BeamMode, zeta: f64, v: f64, t: f64) -> f64 {
        let w = mode.angular_frequency;
        let wd = w * (1.0 - zeta * zeta).sqrt();
        let end = t.min(mode.span_length * mode.spans() as f64 / v);
        let f = |tau: f64| {
            -mode.shape(v * tau) * (-zeta * w * (t - tau)).exp() * (wd * (t - tau)).sin() / wd
        };
        // Integrate span by span (the force is smooth inside a span), 200 pieces each.
        let span_time = mode.span_length / v;
        let mut sum = 0.0;
        let mut lo = 0.0;
        while lo < end {
            let hi = (lo + span_time).min(end);
            sum += gauss_legendre(f, lo, hi, 200);
            lo = hi;
        }
        sum
    }

    #[test]
    fn exact_piecewise_duhamel_matches_quadrature_for_even_and_odd_modes() {
        let beam = ContinuousBeam::new(2, 20.0, 3.0e10, 2.0e4).unwrap();
        let modes = continuous_beam_modes(&beam, 6).unwrap();
        let v = 25.0;
        for mode in &modes {
            let r = ModalMovingForce::new(mode, 0.03, v).unwrap();
            let scale = (1..40)
                .map(|i| r.displacement(i as f64 * 0.05).abs())
                .fold(0.0, f64::max);
            for &t in &[0.13, 0.55, 0.8, 1.2, 1.6, 1.9] {
                let exact = r.displacement(t);
                let quad = duhamel_quadrature(mode, 0.03, v, t);
                // 200 × 8-point Gauss per span resolves every oscillation: agreement to 1e-10
                // of the response amplitude.
                assert!(
                    (exact - quad).abs() < 1e-10 * scale,
                    "a = {}, t = {t}: {exact} vs {quad}",
                    mode.frequency_parameter
                );
            }
        }
    }

    #[test]
    fn resonance_is_continuous_in_the_speed() {
        // β = 1, ζ = 0 (α = 1 on a single span) is handled by the φ₁ series; a speed 1e-9 away
        // takes the difference form. Both must agree to the O(1e-9) change of the physics
        // (plus the difference form's cancellation, ≈ 1e-16/1e-9).
        let beam = ContinuousBeam::new(1, 20.0, 3.0e10, 2.0e4).unwrap();
        let mode = &continuous_beam_modes(&beam, 1).unwrap()[0];
        let v = beam.speed_from_parameter(1.0);
        let exact = ModalMovingForce::new(mode, 0.0, v).unwrap();
        let near = ModalMovingForce::new(mode, 0.0, v * (1.0 + 1e-9)).unwrap();
        let t_end = exact.crossing_time();
        let scale = exact.displacement(t_end).abs();
        for i in 1..=10 {
            let t = t_end * i as f64 / 10.0;
            let d = (exact.displacement(t) - near.displacement(t)).abs();
            assert!(d < 1e-6 * scale, "t = {t}: {d}");
        }
    }
}
