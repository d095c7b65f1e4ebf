//! The Nelder–Mead simplex minimiser of the maximum-likelihood fits (Nelder & Mead 1965, with
//! the standard coefficients and order of tests of Lagarias, Reeds, Wright & Wright 1998,
//! "Convergence properties of the Nelder–Mead simplex method in low dimensions", SIAM J.
//! Optim. 9(1), §2: reflection ρ = 1, expansion χ = 2, contraction γ = ½, shrink σ = ½).
//!
//! Written by hand (about 80 lines): argmin, the well-kept Rust optimisation crate, brings
//! through argmin-math 0.5 a second `rand` (0.9, not optional) and matrix bridges to older faer
//! and nalgebra than the workspace's, for a three-parameter problem. A cost of +∞ marks a point
//! outside the domain (a GEV whose support excludes a datum); it is never accepted as a better
//! point, so the simplex stays where the cost is finite once its first vertex is.

/// Minimises `cost` from `start`: a simplex of `start` and `start + step·e_i`, iterated until
/// the spread of its costs is within `tolerance` (relative to the best, plus `tolerance`
/// absolute) and its vertices lie within `tolerance` of the best in every coordinate, then
/// restarted at the best point until a restart improves the best cost by no more than
/// `tolerance` (a collapsed simplex can stall short of the minimum; Lagarias et al. §7).
/// Returns the best point, its cost, and whether it converged within `max_evaluations`.
pub(crate) fn minimise<const N: usize>(
    cost: impl Fn(&[f64; N]) -> f64,
    start: [f64; N],
    step: f64,
    tolerance: f64,
    max_evaluations: usize,
) -> ([f64; N], f64, bool) {
    let evaluations = std::cell::Cell::new(0);
    let mut counted = |x: &[f64; N]| {
        evaluations.set(evaluations.get() + 1);
        let value = cost(x);
        if value.is_nan() {
            f64::INFINITY
        } else {
            value
        }
    };
    let mut best = start;
    let mut best_cost = counted(&best);
    loop {
        let (point, value, converged) = one_descent(&mut counted, best, step, tolerance);
        let improvement = best_cost - value;
        if value <= best_cost {
            (best, best_cost) = (point, value);
        }
        if !converged || evaluations.get() >= max_evaluations {
            return (best, best_cost, false);
        }
        if improvement <= tolerance * (best_cost.abs() + tolerance) {
            return (best, best_cost, true);
        }
    }
}

/// One run of the simplex from `start` until it collapses (true) or 10 000 iterations pass.
fn one_descent<const N: usize>(
    cost: &mut impl FnMut(&[f64; N]) -> f64,
    start: [f64; N],
    step: f64,
    tolerance: f64,
) -> ([f64; N], f64, bool) {
    let mut simplex: Vec<([f64; N], f64)> = (0..=N)
        .map(|i| {
            let mut x = start;
            if i > 0 {
                x[i - 1] += step;
            }
            let value = cost(&x);
            (x, value)
        })
        .collect();
    for _ in 0..10_000 {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (best, worst) = (simplex[0].1, simplex[N].1);
        let spread = simplex[1..]
            .iter()
            .flat_map(|(x, _)| x.iter().zip(&simplex[0].0).map(|(a, b)| (a - b).abs()))
            .fold(0.0, f64::max);
        if worst - best <= tolerance * (best.abs() + tolerance) && spread <= tolerance {
            return (simplex[0].0, best, true);
        }
        let mut centroid = [0.0; N];
        for (x, _) in &simplex[..N] {
            for (c, xi) in centroid.iter_mut().zip(x) {
                *c += xi / N as f64;
            }
        }
        let along = |t: f64| -> [f64; N] {
            std::array::from_fn(|i| centroid[i] + t * (simplex[N].0[i] - centroid[i]))
        };
        let reflected = along(-1.0);
        let reflected_cost = cost(&reflected);
        if reflected_cost < best {
            let expanded = along(-2.0);
            let expanded_cost = cost(&expanded);
            simplex[N] = if expanded_cost < reflected_cost {
                (expanded, expanded_cost)
            } else {
                (reflected, reflected_cost)
            };
        } else if reflected_cost < simplex[N - 1].1 {
            simplex[N] = (reflected, reflected_cost);
        } else {
            // Outside contraction when the reflection beats the worst, inside otherwise.
            let outside = reflected_cost < worst;
            let contracted = along(if outside { -0.5 } else { 0.5 });
            let contracted_cost = cost(&contracted);
            let limit = if outside { reflected_cost } else { worst };
            if contracted_cost <= limit {
                simplex[N] = (contracted, contracted_cost);
            } else {
                let first = simplex[0].0;
                for (x, value) in simplex[1..].iter_mut() {
                    *x = std::array::from_fn(|i| first[i] + 0.5 * (x[i] - first[i]));
                    *value = cost(x);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    (simplex[0].0, simplex[0].1, false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_minimum_of_rosenbrocks_valley_and_of_a_quadratic_bowl() {
        // Rosenbrock's function (Lagarias et al. §5): minimum 0 at (1, 1).
        let rosenbrock = |x: &[f64; 2]| 100.0 * (x[1] - x[0] * x[0]).powi(2) + (1.0 - x[0]).powi(2);
        let (x, value, converged) = minimise(rosenbrock, [-1.2, 1.0], 0.1, 1e-12, 100_000);
        assert!(converged);
        assert!(value < 1e-18, "{value}");
        assert!(
            (x[0] - 1.0).abs() < 1e-8 && (x[1] - 1.0).abs() < 1e-8,
            "{x:?}"
        );
        let bowl =
            |x: &[f64; 3]| (x[0] - 3.0).powi(2) + 2.0 * (x[1] + 1.0).powi(2) + 5.0 * x[2] * x[2];
        let (x, _, converged) = minimise(bowl, [0.0; 3], 0.5, 1e-13, 100_000);
        assert!(converged);
        assert!((x[0] - 3.0).abs() < 1e-6 && (x[1] + 1.0).abs() < 1e-6 && x[2].abs() < 1e-6);
    }

    #[test]
    fn an_infinite_cost_bounds_the_search_to_its_domain() {
        // Minimum of (x − 2)² on x ≤ 1: at the edge, x = 1.
        let bounded = |x: &[f64; 1]| {
            if x[0] > 1.0 {
                f64::INFINITY
            } else {
                (x[0] - 2.0).powi(2)
            }
        };
        let (x, _, _) = minimise(bounded, [0.0], 0.1, 1e-12, 10_000);
        assert!((x[0] - 1.0).abs() < 1e-9, "{x:?}");
    }
}
