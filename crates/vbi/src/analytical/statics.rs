//! Exact statics of N equal pinned spans under a point load (the paper's Eq. 14).
//!
//! The support moments M₀ … M_N (M₀ = M_N = 0, sagging positive) follow from Clapeyron's
//! three-moment equation, for equal spans l and a load P in the span left of support j at a
//! distance a from its far support (b = l − a), or in the span right of it at a from support j:
//!
//! ```text
//! M_{j−1} + 4 M_j + M_{j+1} = −P a b (l + a) / l²   (load in the left span)
//!                           = −P a b (l + b) / l²   (load in the right span)
//! ```
//!
//! In each span the moment is the simply supported moment plus the linear interpolation of the
//! end moments, and the deflection (downwards) is the simply supported one plus
//! (l²/6EI)[M_L(2ξ − 3ξ² + ξ³) + M_R(ξ − ξ³)]. Then (Eq. 14)
//!
//! ```text
//! y_s(x) = λ₁ P l³ / EI (downwards),   M_s(x) = λ₂ P l (sagging).
//! ```

use super::{AnalyticalError, ContinuousBeam};

/// Static response at a section to a point load.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StaticResponse {
    /// Deflection w, positive upwards \[m\] (negative under a downward load).
    pub deflection: f64,
    /// Bending moment M, positive sagging \[N·m\].
    pub bending_moment: f64,
}

/// Static load factors (λ₁, λ₂) of Eq. 14 at section `section_ratio` = x/l under a unit
/// downward load at `load_ratio` = x_P/l, both measured in span lengths from the first support
/// (0 … N): λ₁ = downward deflection · EI/(P l³), λ₂ = sagging moment /(P l).
///
/// Two spans, both at l/2: λ₁ = 23/1536, λ₂ = 13/64 (docs/verification.md §3).
pub fn static_load_factors(
    spans: usize,
    section_ratio: f64,
    load_ratio: f64,
) -> Result<(f64, f64), AnalyticalError> {
    let beam = ContinuousBeam::new(spans, 1.0, 1.0, 1.0)?;
    let r = static_response(&beam, section_ratio, load_ratio, 1.0)?;
    Ok((-r.deflection, r.bending_moment))
}

/// Exact static deflection and bending moment at `section` \[m\] under a downward point load
/// `force` \[N\] at `load_position` \[m\].
pub fn static_response(
    beam: &ContinuousBeam,
    section: f64,
    load_position: f64,
    force: f64,
) -> Result<StaticResponse, AnalyticalError> {
    beam.validate()?;
    beam.check_position("section", section)?;
    beam.check_position("load position", load_position)?;
    let n = beam.spans;
    let l = beam.span_length;
    let length = beam.total_length();
    let locate = |x: f64| {
        let s = (x / l).clamp(0.0, n as f64);
        let i = (s.floor() as usize).min(n - 1);
        (i, (s - i as f64) * l)
    };
    let (load_span, a) = locate(load_position.clamp(0.0, length));
    let b = l - a;
    // Support moments by the Thomas algorithm on the (N−1) interior supports.
    let mut support = vec![0.0; n + 1];
    if n > 1 {
        let m = n - 1;
        let mut rhs = vec![0.0; m];
        // Interior support j (1..n-1) is unknown j-1. The loaded span `load_span` lies right
        // of support load_span and left of support load_span + 1.
        let right_end = load_span + 1; // support whose left span is loaded
        if right_end < n {
            rhs[right_end - 1] += -force * a * b * (l + a) / (l * l);
        }
        if load_span >= 1 {
            rhs[load_span - 1] += -force * a * b * (l + b) / (l * l);
        }
        // Tridiagonal (1, 4, 1).
        let mut diag = vec![4.0; m];
        for j in 1..m {
            let w = 1.0 / diag[j - 1];
            diag[j] -= w;
            rhs[j] -= w * rhs[j - 1];
        }
        let mut x = vec![0.0; m];
        x[m - 1] = rhs[m - 1] / diag[m - 1];
        for j in (0..m - 1).rev() {
            x[j] = (rhs[j] - x[j + 1]) / diag[j];
        }
        support[1..n].copy_from_slice(&x);
    }
    let (span, s) = locate(section.clamp(0.0, length));
    let xi = s / l;
    let (ml, mr) = (support[span], support[span + 1]);
    let mut moment = ml * (1.0 - xi) + mr * xi;
    let ei = beam.flexural_rigidity;
    let mut down = l * l / (6.0 * ei)
        * (ml * (2.0 * xi - 3.0 * xi * xi + xi.powi(3)) + mr * (xi - xi.powi(3)));
    if span == load_span {
        if s <= a {
            moment += force * b * s / l;
            down += force * b * s * (l * l - b * b - s * s) / (6.0 * ei * l);
        } else {
            let r = l - s;
            moment += force * a * r / l;
            down += force * a * r * (l * l - a * a - r * r) / (6.0 * ei * l);
        }
    }
    Ok(StaticResponse {
        deflection: -down,
        bending_moment: moment,
    })
}

/// The extreme static value of a quantity at a section over all load positions, with the
/// load position that gives it: dense sampling (64 points per span plus the section itself and
/// the supports) refined by golden-section search on the neighbouring interval.
pub(crate) fn static_envelope(
    beam: &ContinuousBeam,
    section: f64,
    value: impl Fn(&StaticResponse) -> f64,
) -> Result<(f64, f64), AnalyticalError> {
    let length = beam.total_length();
    let per_span = 64;
    let count = per_span * beam.spans;
    let mut positions: Vec<f64> = (0..=count)
        .map(|i| length * i as f64 / count as f64)
        .collect();
    positions.push(section);
    positions.sort_by(f64::total_cmp);
    let mut values = Vec::with_capacity(positions.len());
    for &p in &positions {
        values.push(value(&static_response(beam, section, p, 1.0)?));
    }
    let best = (0..values.len())
        .max_by(|&i, &j| values[i].abs().total_cmp(&values[j].abs()))
        .unwrap_or(0);
    let sign = if values[best] < 0.0 { -1.0 } else { 1.0 };
    let f = |p: f64| -> f64 {
        static_response(beam, section, p, 1.0)
            .map(|r| sign * value(&r))
            .unwrap_or(f64::NEG_INFINITY)
    };
    let lo = positions[best.saturating_sub(1)];
    let hi = positions[(best + 1).min(positions.len() - 1)];
    let (p, v) = golden_maximum(&f, lo, hi, 80);
    if v > sign * values[best] {
        Ok((sign * v, p))
    } else {
        Ok((values[best], positions[best]))
    }
}

/// Golden-section search for the maximum of a unimodal `f` on [lo, hi]; returns (x, f(x)).
/// Hand-written (a dozen lines; no dependency does scalar optimisation).
pub(crate) fn golden_maximum(
    f: &impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
    iterations: usize,
) -> (f64, f64) {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (lo, hi);
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let mut fc = f(c);
    let mut fd = f(d);
    for _ in 0..iterations {
        if fc >= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
        if (b - a).abs() <= 1e-15 * (a.abs() + b.abs()) {
            break;
        }
    }
    if fc >= fd {
        (c, fc)
    } else {
        (d, fd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_span_midspan_load_factors_match_the_three_moment_closed_form() {
        // Reference: docs/verification.md §3, λ₁ = 23/1536, λ₂ = 13/64.
        let (l1, l2) = static_load_factors(2, 0.5, 0.5).unwrap();
        // Exact arithmetic up to a few roundings: 1e-15 relative.
        assert!((l1 - 23.0 / 1536.0).abs() < 1e-16, "{l1}");
        assert!((l2 - 13.0 / 64.0).abs() < 1e-15, "{l2}");
    }

    #[test]
    fn a_single_span_gives_pl_over_4_and_pl3_over_48ei() {
        // Reference: docs/verification.md §1.
        let (l1, l2) = static_load_factors(1, 0.5, 0.5).unwrap();
        assert!((l1 - 1.0 / 48.0).abs() < 1e-16);
        assert!((l2 - 0.25).abs() < 1e-16);
    }
}
