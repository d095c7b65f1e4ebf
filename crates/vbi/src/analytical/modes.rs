//! Exact modes of a continuous beam of N equal spans pinned at every support.
//!
//! On span i (0-based) with local coordinate ξ = x/l − i ∈ [0, 1], a mode of frequency parameter
//! a (a⁴ = ω² m̄ l⁴ / EI) is
//!
//! ```text
//! φ(ξ) = c₀ sin aξ + c₁ cos aξ + c₂ e^(−a(1−ξ)) + c₃ e^(−aξ)
//! ```
//!
//! (the exponentials replace sinh and cosh so that nothing overflows at large a). The spans are
//! joined by the slope-deflection (dynamic stiffness) equations in the support rotations θⱼ. A
//! span with zero end deflections has end moments (EI/l)(F θ_near + G θ_far) with
//!
//! ```text
//! F(a) = a (sinh a cos a − cosh a sin a) / (cosh a cos a − 1),
//! G(a) = a (sin a − sinh a) / (cosh a cos a − 1).
//! ```
//!
//! Moment balance at the supports gives G θⱼ₋₁ + 2F θⱼ + G θⱼ₊₁ = 0 inside and F θ₀ + G θ₁ = 0,
//! G θ_{N−1} + F θ_N = 0 at the ends. It is solved by θⱼ = cos(jμ) with cos μ = −F/G and
//! sin(Nμ) sin μ = 0, so the exact frequency equation is
//!
//! ```text
//! R(a) = (sinh a cos a − cosh a sin a) / (sinh a − sin a) = cos(pπ/N),   p = 1 … N−1,
//! ```
//!
//! plus a = kπ (every span vibrates as a simply supported span, R = ±1). R sweeps [−1, 1]
//! monotonically between kπ and the k-th clamped–clamped root (cos a cosh a = 1), so each band k
//! holds exactly N roots: kπ and one root per level cos(pπ/N). Each is found by bisection on its
//! own bracket, so clusters of close roots cannot be confused. For N = 2 the level is 0, i.e.
//! tan a = tanh a (Eq. 10's pinned–clamped spans).
//!
//! Hand-written: no crate solves this transcendental eigenproblem.

use std::f64::consts::PI;

use super::{gauss_legendre, AnalyticalError, ContinuousBeam};

/// Largest number of modes computed.
pub const MAX_MODES: usize = 2000;

/// One exact mode of a continuous beam, normalised to unit modal mass ∫ m̄ φ² dx = 1 kg.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BeamMode {
    /// Frequency parameter a = l (ω² m̄ / EI)^(1/4) \[-\].
    pub frequency_parameter: f64,
    /// Circular frequency ω = (a/l)² √(EI/m̄) \[rad/s\].
    pub angular_frequency: f64,
    /// Span length l \[m\].
    pub span_length: f64,
    /// Coefficients (c₀, c₁, c₂, c₃) of each span (module docs) \[kg^(−1/2)\].
    pub span_coefficients: Vec<[f64; 4]>,
}

impl BeamMode {
    /// Frequency f = ω / 2π \[Hz\].
    pub fn frequency_hz(&self) -> f64 {
        self.angular_frequency / (2.0 * PI)
    }

    /// Number of spans.
    pub fn spans(&self) -> usize {
        self.span_coefficients.len()
    }

    /// Span index and local coordinate ξ ∈ [0, 1] of a position x \[m\] (clamped to the beam).
    pub fn locate(&self, x: f64) -> (usize, f64) {
        let s = (x / self.span_length).clamp(0.0, self.spans() as f64);
        let i = (s.floor() as usize).min(self.spans() - 1);
        (i, s - i as f64)
    }

    /// Mode shape φ(x) \[kg^(−1/2)\] (Eqs. 5, 10, 12, exact).
    pub fn shape(&self, x: f64) -> f64 {
        let (i, xi) = self.locate(x);
        let c = &self.span_coefficients[i];
        let a = self.frequency_parameter;
        let (s, co) = (a * xi).sin_cos();
        c[0] * s + c[1] * co + c[2] * (-a * (1.0 - xi)).exp() + c[3] * (-a * xi).exp()
    }

    /// Slope dφ/dx \[kg^(−1/2)/m\].
    pub fn slope(&self, x: f64) -> f64 {
        let (i, xi) = self.locate(x);
        let c = &self.span_coefficients[i];
        let a = self.frequency_parameter;
        let (s, co) = (a * xi).sin_cos();
        a / self.span_length
            * (c[0] * co - c[1] * s + c[2] * (-a * (1.0 - xi)).exp() - c[3] * (-a * xi).exp())
    }

    /// Second derivative d²φ/dx² \[kg^(−1/2)/m²\]; the bending moment is M = EI Σ φₙ'' qₙ (Eq. 4).
    pub fn curvature(&self, x: f64) -> f64 {
        let (i, xi) = self.locate(x);
        let c = &self.span_coefficients[i];
        let a = self.frequency_parameter;
        let (s, co) = (a * xi).sin_cos();
        (a / self.span_length).powi(2)
            * (-c[0] * s - c[1] * co + c[2] * (-a * (1.0 - xi)).exp() + c[3] * (-a * xi).exp())
    }
}

/// R(a) of the frequency equation (module docs), written with tanh and sech so that it is finite
/// for every a > 0.
pub fn frequency_function(a: f64) -> f64 {
    let t = a.tanh();
    let sech = 1.0 / a.cosh();
    let (s, c) = a.sin_cos();
    (t * c - s) / (t - s * sech)
}

/// Bisection to the last representable bit on a bracket [lo, hi] with f(lo), f(hi) of
/// opposite signs. Hand-written: robust and fast enough for these smooth scalar functions.
fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> Option<f64> {
    let mut flo = f(lo);
    let fhi = f(hi);
    if flo == 0.0 {
        return Some(lo);
    }
    if fhi == 0.0 {
        return Some(hi);
    }
    if flo.signum() == fhi.signum() || !flo.is_finite() || !fhi.is_finite() {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let fm = f(mid);
        if fm == 0.0 {
            return Some(mid);
        }
        if fm.signum() == flo.signum() {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
    Some(0.5 * (lo + hi))
}

/// The k-th clamped–clamped root (cos a cosh a = 1) in (kπ, (k+1)π), k ≥ 1: the upper edge of
/// band k.
fn clamped_clamped_root(k: usize) -> f64 {
    let lo = k as f64 * PI;
    let hi = (k + 1) as f64 * PI;
    // cos a − sech a changes sign exactly once on [kπ, (k+1)π] (cos is monotonic there).
    bisect(|a| a.cos() - 1.0 / a.cosh(), lo, hi).unwrap_or(lo + 0.5 * PI)
}

/// Band index k, level index p (0 for the simply supported root a = kπ) and value a of each root.
fn roots_with_labels(
    spans: usize,
    count: usize,
) -> Result<Vec<(usize, usize, f64)>, AnalyticalError> {
    let mut roots = Vec::with_capacity(count + spans);
    let mut band = 1;
    while roots.len() < count {
        let lo = band as f64 * PI;
        roots.push((band, 0, lo));
        if spans > 1 {
            let hi = clamped_clamped_root(band);
            for p in 1..spans {
                let level = (p as f64 * PI / spans as f64).cos();
                let root = bisect(|a| frequency_function(a) - level, lo, hi)
                    .ok_or(AnalyticalError::RootNotFound { band, level })?;
                roots.push((band, p, root));
            }
        }
        band += 1;
    }
    roots.sort_by(|x, y| x.2.total_cmp(&y.2));
    roots.truncate(count);
    Ok(roots)
}

/// The first `count` frequency parameters aₙ (ωₙ = (aₙ/l)² √(EI/m̄)) of N equal pinned spans, in
/// increasing order, from the exact frequency equation.
pub fn frequency_parameters(spans: usize, count: usize) -> Result<Vec<f64>, AnalyticalError> {
    check_counts(spans, count)?;
    Ok(roots_with_labels(spans, count)?
        .into_iter()
        .map(|r| r.2)
        .collect())
}

/// The first `count` positive roots of tan a = tanh a: the even modes of two equal spans
/// (each span pinned–clamped, Eq. 10), a = 3.926602, 7.068583, …
pub fn two_span_even_roots(count: usize) -> Vec<f64> {
    (1..=count)
        .map(|k| {
            // tan a − tanh a, written as sin a − tanh a cos a (no poles), has one root in
            // (kπ, kπ + π/2): it is −tanh(kπ)(−1)^k at kπ and (−1)^k at kπ + π/2.
            let lo = k as f64 * PI;
            bisect(|a| a.sin() - a.tanh() * a.cos(), lo, lo + 0.5 * PI).unwrap_or(lo + 0.25 * PI)
        })
        .collect()
}

fn check_counts(spans: usize, count: usize) -> Result<(), AnalyticalError> {
    if spans == 0 || spans > super::MAX_SPANS {
        return Err(AnalyticalError::SpanCount {
            spans,
            max: super::MAX_SPANS,
        });
    }
    if count == 0 || count > MAX_MODES {
        return Err(AnalyticalError::ModeCount {
            modes: count,
            max: MAX_MODES,
        });
    }
    Ok(())
}

/// Solves a 4×4 linear system by Gaussian elimination with partial pivoting (hand-written: too
/// small for a library call).
fn solve4(mut m: [[f64; 4]; 4], mut b: [f64; 4]) -> [f64; 4] {
    for col in 0..4 {
        let pivot = (col..4)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .unwrap_or(col);
        m.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..4 {
            let factor = m[row][col] / m[col][col];
            for k in col..4 {
                m[row][k] -= factor * m[col][k];
            }
            b[row] -= factor * b[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..4).rev() {
        let mut s = b[row];
        for k in row + 1..4 {
            s -= m[row][k] * x[k];
        }
        x[row] = s / m[row][row];
    }
    x
}

/// Coefficients of one span with zero end deflections and end slopes dφ/dξ = θL, θR.
fn span_coefficients(a: f64, theta_left: f64, theta_right: f64) -> [f64; 4] {
    let e = (-a).exp();
    let (s, c) = a.sin_cos();
    let m = [
        [0.0, 1.0, e, 1.0],         // φ(0) = 0
        [s, c, 1.0, e],             // φ(1) = 0
        [a, 0.0, a * e, -a],        // φ'(0) = θL
        [a * c, -a * s, a, -a * e], // φ'(1) = θR
    ];
    solve4(m, [0.0, 0.0, theta_left, theta_right])
}

/// The first `count` exact modes of the beam, in increasing frequency, each normalised to unit
/// modal mass and signed so that its slope at x = 0 is positive.
pub fn continuous_beam_modes(
    beam: &ContinuousBeam,
    count: usize,
) -> Result<Vec<BeamMode>, AnalyticalError> {
    beam.validate()?;
    check_counts(beam.spans, count)?;
    let n = beam.spans;
    let labelled = roots_with_labels(n, count)?;
    Ok(labelled
        .into_iter()
        .map(|(band, p, a)| {
            // Support rotations θⱼ = cos(jμ): μ = pπ/N, and for the simply supported root kπ
            // μ = π (k odd, neighbouring spans alternate) or 0 (k even).
            let mu = if p == 0 {
                if band % 2 == 1 {
                    PI
                } else {
                    0.0
                }
            } else {
                p as f64 * PI / n as f64
            };
            let theta: Vec<f64> = (0..=n).map(|j| (j as f64 * mu).cos()).collect();
            let mut coefficients: Vec<[f64; 4]> = (0..n)
                .map(|i| span_coefficients(a, theta[i], theta[i + 1]))
                .collect();
            // Modal mass m̄ l Σ ∫₀¹ φᵢ(ξ)² dξ; 8-point Gauss on ≥ 2 pieces per half-wave.
            let pieces = (a / PI).ceil() as usize * 2 + 2;
            let mut integral = 0.0;
            for c in &coefficients {
                integral += gauss_legendre(
                    |xi| {
                        let (s, co) = (a * xi).sin_cos();
                        let v = c[0] * s
                            + c[1] * co
                            + c[2] * (-a * (1.0 - xi)).exp()
                            + c[3] * (-a * xi).exp();
                        v * v
                    },
                    0.0,
                    1.0,
                    pieces,
                );
            }
            let scale = 1.0 / (beam.mass_per_length * beam.span_length * integral).sqrt();
            for c in &mut coefficients {
                for v in c.iter_mut() {
                    *v *= scale;
                }
            }
            BeamMode {
                frequency_parameter: a,
                angular_frequency: beam.angular_frequency(a),
                span_length: beam.span_length,
                span_coefficients: coefficients,
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_span_has_the_simply_supported_roots() {
        // Reference: docs/verification.md §1, ωₙ = (nπ/L)²√(EI/m̄).
        let a = frequency_parameters(1, 5).unwrap();
        for (n, v) in a.iter().enumerate() {
            assert!((v - (n + 1) as f64 * PI).abs() < 1e-14);
        }
    }

    #[test]
    fn modes_satisfy_support_and_continuity_conditions() {
        let beam = ContinuousBeam::new(3, 10.0, 2.0e9, 1.0e3).unwrap();
        for mode in continuous_beam_modes(&beam, 12).unwrap() {
            let scale = mode.curvature(5.0).abs().max(mode.curvature(15.0).abs()) + 1e-3;
            for j in 0..=3 {
                let x = j as f64 * 10.0;
                assert!(mode.shape(x).abs() < 1e-9, "deflection at support {j}");
                if j == 0 || j == 3 {
                    assert!(mode.curvature(x).abs() < 1e-8 * scale, "moment at end {j}");
                } else {
                    let dl = mode.curvature(x - 1e-12);
                    let dr = mode.curvature(x + 1e-12);
                    assert!((dl - dr).abs() < 1e-6 * scale, "moment jump at {j}");
                    let sl = mode.slope(x - 1e-12);
                    let sr = mode.slope(x + 1e-12);
                    assert!((sl - sr).abs() < 1e-6 * scale * 10.0, "slope jump at {j}");
                }
            }
        }
    }
}
