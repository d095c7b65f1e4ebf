//! Frýba's closed form for a constant force crossing a simply supported beam (N = 1), and the
//! damped sine-mode response of the paper's Eq. 8.
//!
//! Undamped, 0 ≤ t ≤ L/v, Ω = πv/L, α = Ω/ω₁, v₀ = PL³/(48EI) (docs/verification.md §2):
//!
//! ```text
//! w(x,t) = v₀ (96/π⁴) Σⱼ 1/(j²(j² − α²)) [sin(jΩt) − (α/j) sin(ωⱼt)] sin(jπx/L)
//! ```
//!
//! (downwards). The resonant term j = α is replaced by its limit.

use std::f64::consts::PI;

/// Downward deflection \[m\] of a simply supported beam at `x` \[m\] and time `t` ∈ [0, L/v] \[s\]
/// under a downward force `force` \[N\] crossing at `speed` \[m/s\], from the first `terms` terms of
/// Frýba's undamped series (docs/verification.md §2).
pub fn simply_supported_deflection(
    span_length: f64,
    flexural_rigidity: f64,
    mass_per_length: f64,
    force: f64,
    speed: f64,
    x: f64,
    t: f64,
    terms: usize,
) -> f64 {
    let l = span_length;
    let omega1 = (PI / l).powi(2) * (flexural_rigidity / mass_per_length).sqrt();
    let big_omega = PI * speed / l;
    let alpha = big_omega / omega1;
    let v0 = force * l.powi(3) / (48.0 * flexural_rigidity);
    let mut sum = 0.0;
    for j in 1..=terms {
        let jf = j as f64;
        let omega_j = jf * jf * omega1;
        // Bracket / (j² − α²); at α → j it tends to d/dα of the numerator over −2α.
        let numerator = |al: f64| (jf * big_omega * t).sin() - (al / jf) * (omega_j * t).sin();
        let denom = jf * jf - alpha * alpha;
        let ratio = if denom.abs() > 1e-6 {
            // Away from resonance, evaluate directly with ω_j t fixed.
            numerator(alpha) / denom
        } else {
            // At resonance (α = j with Ω fixed ⇒ ω_j = jΩ): sin(jΩt) − sin(jΩt)·(α/j) with
            // ω₁ = Ω/α; the limit of [sin(jΩt) − (α/j) sin(j²Ωt/α)]/(j² − α²) as α → j.
            let phase = jf * big_omega * t;
            (phase.sin() - phase * phase.cos()) / (2.0 * jf * jf)
        };
        sum += ratio / (jf * jf) * (jf * PI * x / l).sin();
    }
    v0 * 96.0 / PI.powi(4) * sum
}

/// Damped response of a sine mode to a force crossing at Ω = kπv/L (the paper's Eq. 8, as
/// derived; the printed Eq. 8 omits the forced term −2ζβ cos Ωt):
///
/// ```text
/// q̈ + 2ζωq̇ + ω²q = f₀ sin Ωt,  q(0) = q̇(0) = 0,  β = Ω/ω, D = (1 − β²)² + (2ζβ)²:
/// q(t) = f₀/(ω² D) [ (1 − β²) sin Ωt − 2ζβ cos Ωt
///        + e^(−ζωt) ( 2ζβ cos ω_D t + (2ζ²βω − (1 − β²)Ω) / ω_D · sin ω_D t ) ]
/// ```
///
/// Returns q(t) / f₀ \[s²\]. Not defined at β = 1, ζ = 0 (use
/// [`super::ModalMovingForce`], which handles the limit).
pub fn sine_mode_response(omega: f64, damping_ratio: f64, big_omega: f64, t: f64) -> f64 {
    let z = damping_ratio;
    let beta = big_omega / omega;
    let wd = omega * (1.0 - z * z).sqrt();
    let d = (1.0 - beta * beta).powi(2) + (2.0 * z * beta).powi(2);
    let decay = (-z * omega * t).exp();
    ((1.0 - beta * beta) * (big_omega * t).sin() - 2.0 * z * beta * (big_omega * t).cos()
        + decay
            * (2.0 * z * beta * (wd * t).cos()
                + (2.0 * z * z * beta * omega - (1.0 - beta * beta) * big_omega) / wd
                    * (wd * t).sin()))
        / (omega * omega * d)
}
