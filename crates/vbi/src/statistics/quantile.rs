//! Sample quantiles.

/// The p-quantile (0 ≤ p ≤ 1) of sorted values by linear interpolation between order
/// statistics (Hyndman–Fan type 7): h = (n − 1)p, x⌊h⌋ + (h − ⌊h⌋)(x⌊h⌋₊₁ − x⌊h⌋).
pub fn percentile_sorted(sorted: &[f64], p: f64) -> f64 {
    let n = sorted.len();
    if n == 1 {
        return sorted[0];
    }
    let h = (n - 1) as f64 * p.clamp(0.0, 1.0);
    let lower = h.floor() as usize;
    if lower + 1 >= n {
        return sorted[n - 1];
    }
    sorted[lower] + (h - lower as f64) * (sorted[lower + 1] - sorted[lower])
}
