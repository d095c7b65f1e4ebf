//! Profile-likelihood intervals of a fitted law's quantiles (return levels).

use super::nelder_mead::minimise;
use super::{
    half_chi_square_95, shape_growth, ExtremeValueError, ExtremeValueModel, GeneralisedExtremeValue,
};

/// c(ξ) = (y^(−ξ) − 1)/ξ with y = −ln p, so that z_p = μ + σ c(ξ): [`shape_growth`] with
/// L = −ln y, increasing with ξ whatever the sign of L.
fn reduced_quantile(p: f64, shape: f64) -> f64 {
    shape_growth(shape, -(-p.ln()).ln())
}

/// The 95 % profile-likelihood interval of the quantile of non-exceedance probability `p`
/// of `model`'s maximum-likelihood fit `fit` of `values` (Coles 2001, §2.6.6 and §4.4.3: the
/// return levels z whose profile log-likelihood ℓ_p(z) = max over the other parameters of
/// ℓ(μ = z − σ c(ξ), σ, ξ) lies within χ²₁(0.95)/2 of the maximum). Coles recommends it over
/// symmetric (delta-method) intervals for return levels: the likelihood surface of a long
/// return period is strongly asymmetric, its upper side much longer.
///
/// Each end is bracketed by stepping out from the estimate (doubling the step, from the law's
/// scale) and then bisected to 10⁻¹⁰ of the scale; each ℓ_p is a Nelder–Mead maximisation over
/// (μ, ln σ), ξ following from z (over ln σ alone for Gumbel), warm-started from the nearest
/// point already profiled.
/// An upper end that is not reached within 2³⁹ scales (a likelihood that stays flat upward, as
/// for a heavy tail) is `None`: the data set no upper bound.
pub fn profile_interval(
    values: &[f64],
    model: ExtremeValueModel,
    fit: &GeneralisedExtremeValue,
    p: f64,
) -> Result<(f64, Option<f64>), ExtremeValueError> {
    // Standardised as the fits are: (z − z̄)/s.
    let (mean, std, standard) = super::standardised(values);
    let law = GeneralisedExtremeValue {
        location: (fit.location - mean) / std,
        scale: fit.scale / std,
        shape: fit.shape,
    };
    let best = law.log_likelihood(&standard);
    let estimate = law.quantile(p);
    let start = [law.location, law.scale.ln()];
    let profile = Profile {
        values: &standard,
        model,
        p,
    };
    let target = best - half_chi_square_95();
    let at = |z: f64, from: [f64; 2]| profile.at(z, from);
    let lower = interval_end(at, estimate, -law.scale, start, target);
    let upper = interval_end(at, estimate, law.scale, start, target);
    let back = |z: f64| mean + std * z;
    let lower = lower.ok_or(ExtremeValueError::NotConverged {
        model: "profile-likelihood",
    })?;
    Ok((back(lower), upper.map(back)))
}

/// The largest shape the profile considers: a GEV with ξ > 50 is no law of a load effect.
const LARGEST_SHAPE: f64 = 50.0;

/// The ξ in (−1, [`LARGEST_SHAPE`]] with c(ξ) = `reduced` ([`reduced_quantile`]); None
/// outside c's range there. c increases with ξ, with c′(ξ) = ∫₀^L t e^(ξt) dt =
/// (L e^(ξL) − c)/ξ (L²/2 at ξ = 0). Where c > 0 (L > 0, every return period of a year or
/// more) the root is sought on ln c, which is nearly linear for large ξ (ln c ≈ ξL − ln ξ):
/// Newton's method on c itself creeps down an exponential by 1/L a step. Each Newton step that
/// leaves the bracket or fails to halve the one before gives way to bisection (the rtsafe rule
/// of Press et al., "Numerical Recipes", §9.4), to round-off.
fn shape_of(p: f64, reduced: f64) -> Option<f64> {
    let (mut low, mut high) = (-1.0, LARGEST_SHAPE);
    if !(reduced > reduced_quantile(p, low) && reduced <= reduced_quantile(p, high)) {
        return None;
    }
    let log_span = -(-p.ln()).ln();
    let logarithmic = reduced > 0.0;
    // h(ξ) = ln c − ln r (or c − r) and its derivative.
    let residual = |shape: f64| {
        let c = reduced_quantile(p, shape);
        let slope = if shape.abs() < 1e-8 {
            0.5 * log_span * log_span
        } else {
            (log_span * (shape * log_span).exp() - c) / shape
        };
        if logarithmic {
            (c.ln() - reduced.ln(), slope / c)
        } else {
            (c - reduced, slope)
        }
    };
    let mut shape = 0.0_f64.clamp(low, high);
    let (mut step, mut step_before) = (high - low, high - low);
    for _ in 0..300 {
        let (h, slope) = residual(shape);
        if h == 0.0 {
            return Some(shape);
        }
        if h < 0.0 {
            low = shape;
        } else {
            high = shape;
        }
        let newton = shape - h / slope;
        let next =
            if newton > low && newton < high && (newton - shape).abs() < 0.5 * step_before.abs() {
                newton
            } else {
                0.5 * (low + high)
            };
        (step_before, step) = (step, next - shape);
        if step.abs() <= 1e-15 * (1.0 + shape.abs()) || high - low <= 1e-15 * (1.0 + shape.abs()) {
            return Some(next);
        }
        shape = next;
    }
    Some(0.5 * (low + high))
}

struct Profile<'a> {
    values: &'a [f64],
    model: ExtremeValueModel,
    p: f64,
}

impl Profile<'_> {
    /// ℓ_p(z) and the parameters (μ, ln σ) that give it (standardised), from `start`; None
    /// if no start near it is feasible. For the GEV, ξ follows from (μ, σ): z = μ + σ c(ξ)
    /// with c increasing in ξ ([`shape_of`]), so the search runs over the two parameters the
    /// bulk of the data fixes, and ξ takes up the tail. (A search over (ln σ, ξ) with μ
    /// following must walk a narrow curved ridge at long return periods and stalls on it.)
    fn at(&self, z: f64, start: [f64; 2]) -> Option<(f64, [f64; 2])> {
        let gumbel = self.model == ExtremeValueModel::Gumbel;
        let cost = |theta: &[f64; 2]| {
            let scale = theta[1].exp();
            let shape = if gumbel {
                0.0
            } else {
                match shape_of(self.p, (z - theta[0]) / scale) {
                    Some(shape) => shape,
                    None => return f64::INFINITY,
                }
            };
            let location = if gumbel {
                z - scale * reduced_quantile(self.p, 0.0)
            } else {
                theta[0]
            };
            -GeneralisedExtremeValue {
                location,
                scale,
                shape,
            }
            .log_likelihood(self.values)
        };
        if gumbel {
            let (t, v, _) = minimise(
                |x: &[f64; 1]| cost(&[0.0, x[0]]),
                [start[1]],
                0.05,
                1e-12,
                5000,
            );
            let location = z - t[0].exp() * reduced_quantile(self.p, 0.0);
            return v.is_finite().then_some((-v, [location, t[0]]));
        }
        // The warm start, or a nearby point whose support holds every datum.
        let from = [0.0, -0.5, -1.0, -2.0, -4.0, 0.5]
            .into_iter()
            .flat_map(|k| [[start[0] + k, start[1]], [start[0] + k, start[1] + 0.5]])
            .find(|from| cost(from).is_finite())?;
        let (t, v, _) = minimise(cost, from, 0.05, 1e-12, 10_000);
        v.is_finite().then_some((-v, t))
    }
}

/// The end of a profile-likelihood interval on the side of `step` (its sign) from `estimate`:
/// the z where the profile `at(z, start) = Some((ℓ_p(z), the maximiser))` crosses `target`.
/// Bracketed by doubling steps from the estimate, then bisected to 10⁻¹⁰ |step|, each profile
/// warm-started from the maximiser of the nearest point inside; a point where `at` is None
/// counts as outside. None if `target` is not crossed within 2³⁹ |step|. Ends in at most 40
/// + 200 profiles, whatever the likelihood.
pub(super) fn interval_end<S: Copy>(
    at: impl Fn(f64, S) -> Option<(f64, S)>,
    estimate: f64,
    step: f64,
    start: S,
    target: f64,
) -> Option<f64> {
    let (mut inside, mut inside_start) = (estimate, start);
    let mut width = step;
    let mut outside = None;
    for _ in 0..40 {
        let z = estimate + width;
        match at(z, inside_start) {
            Some((value, maximiser)) if value >= target => {
                (inside, inside_start) = (z, maximiser);
                width *= 2.0;
            }
            _ => {
                outside = Some(z);
                break;
            }
        }
    }
    let mut outside = outside?;
    // Far out (an end 2³⁰ steps away, say) the floats between the two are coarser than
    // 10⁻¹⁰ |step|: stop where no midpoint is left between them, and after as many halvings
    // as take 2⁴⁰ steps to 10⁻¹⁰ of one (73), with room to spare.
    for _ in 0..200 {
        let middle = 0.5 * (inside + outside);
        if (outside - inside).abs() <= 1e-10 * step.abs() || middle == inside || middle == outside {
            break;
        }
        match at(middle, inside_start) {
            Some((value, maximiser)) if value >= target => {
                (inside, inside_start) = (middle, maximiser)
            }
            _ => outside = middle,
        }
    }
    Some(0.5 * (inside + outside))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ten daily maxima of a midspan shear under simulated traffic (a GEV fit with ξ = 0.45,
    /// a heavy tail): the upper end of the 1000-year level's interval lies some 2³⁰ scales out,
    /// where the floats are coarser than the bisection's tolerance. The interval is found (the
    /// search once looped for ever there), its lower end below the estimate.
    #[test]
    fn a_heavy_tailed_sample_s_interval_ends_where_the_floats_run_out() {
        let values = [
            223332.31834919314,
            261675.78492906567,
            255492.3088605335,
            233102.59185664507,
            239788.04273139406,
            218892.65015630555,
            225094.6888772641,
            223448.80310811946,
            282208.63530919066,
            247765.09982870572,
        ];
        let law = super::super::fit_gev(&values).unwrap();
        assert!(law.shape > 0.3, "{law:?}");
        let p = super::super::non_exceedance_probability(1000.0, 1.0, 250.0);
        let (low, high) = profile_interval(&values, ExtremeValueModel::Gev, &law, p).unwrap();
        let estimate = law.quantile(p);
        assert!(low < estimate, "{low} {estimate}");
        assert!(high.is_none_or(|h| h > estimate), "{high:?} {estimate}");
    }

    #[test]
    fn the_shape_solves_its_reduced_quantile_to_round_off_over_the_whole_range() {
        // Block probabilities of an hourly block at 1000 years (L = 15.6), of a yearly block at
        // 2 years (L = 0.37), and p = 0.2 < 1/e (L < 0: c is negative).
        for p in [(1.0f64 - 1e-3).powf(1.0 / 6000.0), 0.5, 0.2] {
            let (bottom, top) = (
                reduced_quantile(p, -1.0),
                reduced_quantile(p, LARGEST_SHAPE),
            );
            for k in 1..40 {
                let reduced = if bottom > 0.0 {
                    bottom * (top.min(1e300) / bottom).powf(k as f64 / 40.0)
                } else {
                    bottom + (top - bottom) * k as f64 / 40.0
                };
                let shape = shape_of(p, reduced).unwrap();
                let c = reduced_quantile(p, shape);
                assert!(
                    (c - reduced).abs() <= 1e-12 * reduced.abs(),
                    "p {p}: c({shape}) = {c} for {reduced}"
                );
            }
            assert_eq!(shape_of(p, bottom), None);
        }
    }
}
