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
    /// Force P, positive downwards [N]. No default.
    pub force: f64,
    /// Speed v [m/s]. No default.
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

/// ∫₀ᵘ e^(λ(u−r)) e^(sr+κ) dr, stable for every argument with Re(su+κ) ≤ 0 and Re λ ≤ 0.
fn exp_convolution(lambda: C, s: C, kappa: f64, u: f64) -> C {
    let z = (s - lambda) * u;
    if z.norm() < 0.5 {
        (lambda * u + kappa).exp() * u * phi1(z)
    } else {
        ((s * u + kappa).exp() - (lambda * u + kappa).exp()) / (s - lambda)
    }
}

/// One mode's response to a unit downward force crossing at speed v: the state at every span
/// entry, and everything needed to evaluate q(t) exactly at any t ≥ 0.
#[derive(Debug, Clone)]
pub struct ModalMovingForce {
    mode: BeamMode,
    damping_ratio: f64,
    speed: f64,
    span_time: f64,
    damped_frequency: f64,
    /// (q, q̇) at t = i l/v, i = 0 … N, for P = 1 N.
    entry_states: Vec<(f64, f64)>,
}

impl ModalMovingForce {
    /// Prepares the response of `mode` with modal damping ratio ζ ∈ [0, 1) to a force crossing
    /// at `speed` [m/s].
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
        let mut this = ModalMovingForce {
            mode: mode.clone(),
            damping_ratio,
            speed,
            span_time: mode.span_length / speed,
            damped_frequency: omega * (1.0 - damping_ratio * damping_ratio).sqrt(),
            entry_states: Vec::with_capacity(mode.spans() + 1),
        };
        let mut state = (0.0, 0.0);
        this.entry_states.push(state);
        for i in 0..mode.spans() {
            let free = this.free(state, this.span_time);
            let forced = this.forced(i, this.span_time);
            state = (free.0 + forced.0, free.1 + forced.1);
            this.entry_states.push(state);
        }
        Ok(this)
    }

    /// The mode.
    pub fn mode(&self) -> &BeamMode {
        &self.mode
    }

    /// Time the force spends on the beam, N l / v [s].
    pub fn crossing_time(&self) -> f64 {
        self.span_time * self.mode.spans() as f64
    }

    /// Free response after u [s] from state (q, q̇).
    fn free(&self, (q0, p0): (f64, f64), u: f64) -> (f64, f64) {
        let w = self.mode.angular_frequency;
        let z = self.damping_ratio;
        let wd = self.damped_frequency;
        let decay = (-z * w * u).exp();
        let (s, c) = (wd * u).sin_cos();
        (
            decay * (q0 * c + (p0 + z * w * q0) / wd * s),
            decay * (p0 * c - (w * w * q0 + z * w * p0) / wd * s),
        )
    }

    /// Zero-initial-state response (q, q̇) after u [s] on span i to the modal force −φ(x(t)).
    fn forced(&self, span: usize, u: f64) -> (f64, f64) {
        let c = &self.mode.span_coefficients[span];
        let a = self.mode.frequency_parameter;
        let sigma = a * self.speed / self.mode.span_length;
        let w = self.mode.angular_frequency;
        let z = self.damping_ratio;
        let wd = self.damped_frequency;
        let l1 = C::new(-z * w, wd);
        let l2 = l1.conj();
        // Oscillatory part: forcing Re[(c₁ − i c₀) e^(iσu)].
        let s = C::new(0.0, sigma);
        let e1 = exp_convolution(l1, s, 0.0, u);
        let e2 = exp_convolution(l2, s, 0.0, u);
        let amp = C::new(c[1], -c[0]);
        let denom = l1 - l2; // 2iω_D
        let q_osc = (amp * (e1 - e2) / denom).re;
        let p_osc = (amp * (l1 * e1 - l2 * e2) / denom).re;
        // Real exponentials: the kernel is real, so I = Im(E(λ₁))/ω_D and İ = Im(λ₁E(λ₁))/ω_D.
        let g = exp_convolution(l1, C::new(sigma, 0.0), -a, u);
        let h = exp_convolution(l1, C::new(-sigma, 0.0), 0.0, u);
        let q_exp = (c[2] * g.im + c[3] * h.im) / wd;
        let p_exp = (c[2] * (l1 * g).im + c[3] * (l1 * h).im) / wd;
        // The force is downward: modal force −φ.
        (-(q_osc + q_exp), -(p_osc + p_exp))
    }

    /// Modal coordinate q(t) and its rate q̇(t) for a unit downward force (multiply by P).
    pub fn state(&self, t: f64) -> (f64, f64) {
        if t <= 0.0 {
            return (0.0, 0.0);
        }
        let n = self.mode.spans();
        if t >= self.crossing_time() {
            return self.free(self.entry_states[n], t - self.crossing_time());
        }
        let i = ((t / self.span_time).floor() as usize).min(n - 1);
        let u = t - i as f64 * self.span_time;
        let free = self.free(self.entry_states[i], u);
        let forced = self.forced(i, u);
        (free.0 + forced.0, free.1 + forced.1)
    }

    /// Modal coordinate q(t) for a unit downward force [kg^(1/2)·m per N].
    pub fn displacement(&self, t: f64) -> f64 {
        self.state(t).0
    }
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
}
