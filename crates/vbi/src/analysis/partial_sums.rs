//! Maxima over time of the partial modal sums R_K(t) = b(t) + Σ_{k≤K} cₖ yₖ(t), for every number
//! of modes K = 1…N at once: the kernel behind DAF(K) (paper Figs. 11–24).
//!
//! The cost is O(steps × N) per station and quantity, and it is the analysis's inner loop. The
//! running sum over k is a chain of dependent additions; summing it for one instant at a time
//! leaves the floating-point adder waiting on its own latency. Here the time axis is cut into
//! panels of [`LANES`] instants whose running sums advance together (independent chains, which
//! the compiler keeps in vector registers). A panel stores its N × [`LANES`] coordinates
//! contiguously, mode by mode, so the whole table streams through the cache in order. Each
//! instant's sum is still formed in the order k = 1, 2, …, N, so the results equal those of the
//! one-instant-at-a-time loop bit for bit.

/// Instants summed together (one panel).
const LANES: usize = 8;

/// A table of per-mode time series yₖ(t_i) in panels of [`LANES`] instants: `values[(p · N + k)
/// · LANES + j]` = yₖ(t_{p·LANES + j}); the last panel is padded with zeros.
#[derive(Clone)]
pub(crate) struct Panels {
    /// Number of instants.
    pub steps: usize,
    /// Number of modes.
    pub modes: usize,
    values: Vec<f64>,
}

impl Panels {
    /// Copies a step-major table `step_major[i * modes + k]`.
    pub fn from_step_major(step_major: &[f64], steps: usize, modes: usize) -> Self {
        let panels = steps.div_ceil(LANES);
        let mut table = Panels {
            steps,
            modes,
            values: vec![0.0; panels * modes * LANES],
        };
        for (i, row) in step_major
            .chunks_exact(modes.max(1))
            .take(steps)
            .enumerate()
        {
            for (k, &y) in row.iter().enumerate() {
                let at = table.index(i, k);
                table.values[at] = y;
            }
        }
        table
    }

    /// Position of yₖ(t_i) in the table.
    pub fn index(&self, step: usize, mode: usize) -> usize {
        ((step / LANES) * self.modes + mode) * LANES + step % LANES
    }

    /// yₖ(t_i).
    pub fn value(&self, step: usize, mode: usize) -> f64 {
        self.values[self.index(step, mode)]
    }

    /// The entry of mode `mode` at instant `step`, to change.
    pub fn at_mut(&mut self, step: usize, mode: usize) -> &mut f64 {
        let at = self.index(step, mode);
        &mut self.values[at]
    }
}

/// Maxima of the partial sums in one direction.
pub(crate) struct PartialSumMaxima {
    /// max_i σ·R_K(t_i) for K = 1…N (index K − 1).
    pub maxima: Vec<f64>,
    /// First instant at which σ·R_N is largest.
    pub step_of_full_maximum: usize,
}

/// The larger of the two, keeping `best` when `value` is NaN (as `f64::max` does); written as a
/// comparison so that it compiles to one vector max instruction.
#[inline(always)]
fn larger(value: f64, best: f64) -> f64 {
    if value > best {
        value
    } else {
        best
    }
}

/// max over i of σ·(b_i + Σ_{k≤K} cₖ yₖ(t_i)) for every K, with σ = `sign` (±1) and b = `base`
/// (zero when None). NaN values are skipped, as `f64::max` skips them.
pub(crate) fn maxima_of_partial_sums(
    coefficients: &[f64],
    sign: f64,
    series: &Panels,
    base: Option<&[f64]>,
) -> PartialSumMaxima {
    let n = series.modes;
    let steps = series.steps;
    debug_assert_eq!(coefficients.len(), n);
    debug_assert!(base.is_none_or(|b| b.len() == steps));
    // σ·cₖ·y = σ·(cₖ·y) exactly, since σ = ±1.
    let signed: Vec<f64> = coefficients.iter().map(|c| sign * c).collect();
    let mut lane_maxima = vec![[f64::NEG_INFINITY; LANES]; n];
    let mut full_maximum = f64::NEG_INFINITY;
    let mut step_of_full_maximum = 0;
    if n == 0 {
        return PartialSumMaxima {
            maxima: Vec::new(),
            step_of_full_maximum,
        };
    }
    for (p, panel) in series.values.chunks_exact(n * LANES).enumerate() {
        let start = p * LANES;
        let len = LANES.min(steps - start);
        let mut running = [0.0f64; LANES];
        if let Some(b) = base {
            for j in 0..len {
                running[j] = sign * b[start + j];
            }
        }
        for ((&c, best), y) in signed
            .iter()
            .zip(lane_maxima.iter_mut())
            .zip(panel.chunks_exact(LANES))
        {
            for j in 0..LANES {
                running[j] += c * y[j];
            }
            if len == LANES {
                for j in 0..LANES {
                    best[j] = larger(running[j], best[j]);
                }
            } else {
                // The padded instants of the last panel do not count.
                for j in 0..len {
                    best[j] = larger(running[j], best[j]);
                }
            }
        }
        for (j, &value) in running.iter().enumerate().take(len) {
            if value > full_maximum {
                full_maximum = value;
                step_of_full_maximum = start + j;
            }
        }
    }
    let maxima = lane_maxima
        .iter()
        .map(|lanes| lanes.iter().copied().fold(f64::NEG_INFINITY, f64::max))
        .collect();
    PartialSumMaxima {
        maxima,
        step_of_full_maximum,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The straightforward loop: one instant at a time, the partial sums in mode order.
    fn reference(c: &[f64], sign: f64, y: &[f64], steps: usize, base: &[f64]) -> (Vec<f64>, usize) {
        let n = c.len();
        let mut best = vec![f64::NEG_INFINITY; n];
        let mut at = 0;
        for i in 0..steps {
            let mut running = sign * base[i];
            for k in 0..n {
                running += (sign * c[k]) * y[i * n + k];
                if k == n - 1 && running > best[k] {
                    at = i;
                }
                best[k] = best[k].max(running);
            }
        }
        (best, at)
    }

    #[test]
    fn blocked_maxima_equal_the_one_instant_loop_bit_for_bit() {
        // Steps not a multiple of the block, both signs, with and without a base series.
        let (steps, n) = (37, 5);
        let y: Vec<f64> = (0..steps * n)
            .map(|i| ((i as f64) * 0.37).sin() * (1.0 + (i % 7) as f64))
            .collect();
        let c = [0.3, -1.2, 0.7, 2.0, -0.05];
        let base: Vec<f64> = (0..steps).map(|i| (i as f64 * 0.11).cos()).collect();
        let zero = vec![0.0; steps];
        let table = Panels::from_step_major(&y, steps, n);
        for sign in [1.0, -1.0] {
            for with_base in [false, true] {
                let b = if with_base { &base } else { &zero };
                let got = maxima_of_partial_sums(&c, sign, &table, with_base.then_some(&base[..]));
                let (want, at) = reference(&c, sign, &y, steps, b);
                assert_eq!(got.maxima, want);
                assert_eq!(got.step_of_full_maximum, at);
            }
        }
    }
}
