//! Maxima over time of the partial modal sums R_K(t) = b(t) + Σ_{k≤K} cₖ yₖ(t), for every number
//! of modes K = 1…N at once: the kernel behind DAF(K) (paper Figs. 11–24).
//!
//! The cost is O(steps × N) per station and quantity, and it is the analysis's inner loop. The
//! running sum over k is a chain of dependent additions; summing it for one instant at a time
//! leaves the floating-point adder waiting on its own latency. Here the time axis is cut into
//! panels of [`LANES`] instants whose running sums advance together (independent chains, which
//! the compiler keeps in vector registers). A panel stores its N × [`LANES`] coordinates
//! contiguously, mode by mode (`panel[k · LANES + j]` = yₖ(t_{start + j})), so that it streams
//! through the cache in order. The panels are fed one at a time ([`MaximaOfPartialSums`]): a
//! run's coordinates are never held as a second whole table. Each instant's sum is still formed
//! in the order k = 1, 2, …, N, so the results equal those of the one-instant-at-a-time loop
//! bit for bit.

/// Instants summed together (one panel).
pub(crate) const LANES: usize = 8;

/// Writes the panel of instants `start..start + len` of a step-major table
/// (`step_major[i · modes + k]`) into `panel` (`panel[k · LANES + j]`, N × [`LANES`]); the
/// lanes from `len` on are zero. (The tests' panels; a run's panels are filled instant by
/// instant as they stream.)
#[cfg(test)]
fn fill_panel(step_major: &[f64], modes: usize, (start, len): (usize, usize), panel: &mut [f64]) {
    let panel = &mut panel[..modes * LANES];
    if len < LANES {
        panel.fill(0.0);
    }
    let rows = &step_major[start * modes..(start + len) * modes];
    for (j, row) in rows.chunks_exact(modes.max(1)).enumerate() {
        for (k, &y) in row.iter().enumerate() {
            panel[k * LANES + j] = y;
        }
    }
}

/// Maxima of the partial sums in one direction.
pub(crate) struct PartialSumMaxima {
    /// max_i σ·R_K(t_i) for K = 1…N (index K − 1).
    pub maxima: Vec<f64>,
    /// max_i σ·R_K(t_i) for the check modes taken on after the N modes, K = N + 1…N + C
    /// (index K − N − 1; empty without them).
    pub beyond: Vec<f64>,
    /// First instant at which σ·R_N is largest.
    pub step_of_full_maximum: usize,
    /// σ·R_N at the instants before, at and after `step_of_full_maximum` (NaN where the run
    /// has no such instant): what the extreme between the instants is refined from
    /// (`continuous_extreme::dynamic_extreme`).
    pub around_full_maximum: [f64; 3],
    /// max σ·R_N between the instants and its fractional instant, where it was refined
    /// (`continuous_extreme::dynamic_extreme`; the converged series' deflections and moments).
    pub continuous_full_maximum: Option<(f64, f64)>,
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

/// max over i of σ·(b_i + Σ_{k≤K} cₖ yₖ(t_i)) for every K, with σ = `sign` (±1), taken one panel
/// at a time, in the order of time. NaN values are skipped, as `f64::max` skips them. The
/// full sum R_N, whose extreme is located, is that of the first N = `headline` modes; the
/// check modes after them continue the sums (K > N) without moving it.
pub(crate) struct MaximaOfPartialSums {
    /// σ·cₖ (σ·cₖ·y = σ·(cₖ·y) exactly, since σ = ±1).
    signed: Vec<f64>,
    /// N: the modes of the full sum R_N (the others are check modes).
    headline: usize,
    sign: f64,
    /// The maxima so far of each K, per lane.
    lane_maxima: Vec<[f64; LANES]>,
    full_maximum: f64,
    step_of_full_maximum: usize,
    /// σ·R_N at the instant before the last one taken in (NaN before the first).
    last_full: f64,
    /// σ·R_N around the full maximum so far.
    around_full_maximum: [f64; 3],
    /// Whether the instant after the full maximum is still to come.
    awaiting_next: bool,
}

impl MaximaOfPartialSums {
    /// No instant yet, for the coefficients cₖ and the direction σ = `sign` (±1).
    #[cfg(test)]
    pub fn new(coefficients: &[f64], sign: f64) -> Self {
        Self::with_check_modes(coefficients, &[], sign)
    }

    /// [`MaximaOfPartialSums::new`] with the coefficients of check modes after the N modes of
    /// `coefficients` (the panels then hold N + C modes).
    pub fn with_check_modes(coefficients: &[f64], check: &[f64], sign: f64) -> Self {
        let all = coefficients.iter().chain(check);
        MaximaOfPartialSums {
            signed: all.map(|c| sign * c).collect(),
            headline: coefficients.len(),
            sign,
            lane_maxima: vec![[f64::NEG_INFINITY; LANES]; coefficients.len() + check.len()],
            full_maximum: f64::NEG_INFINITY,
            step_of_full_maximum: 0,
            last_full: f64::NAN,
            around_full_maximum: [f64::NAN; 3],
            awaiting_next: false,
        }
    }

    /// Takes in the panel of instants `start..start + len` (`panel[k · LANES + j]` is mode k at
    /// instant start + j; the lanes from `len` on are zero), with b of
    /// those instants in `base` (zero when None).
    pub fn add_panel(
        &mut self,
        panel: &[f64],
        (start, len): (usize, usize),
        base: Option<&[f64; LANES]>,
    ) {
        let (n, headline) = (self.signed.len(), self.headline);
        if headline == 0 {
            return;
        }
        let mut running = [0.0f64; LANES];
        if let Some(b) = base {
            for j in 0..len {
                running[j] = self.sign * b[j];
            }
        }
        let panel = &panel[..n * LANES];
        let (signed, maxima) = (&self.signed, &mut self.lane_maxima);
        accumulate(
            (&signed[..headline], &mut maxima[..headline]),
            &panel[..headline * LANES],
            len,
            &mut running,
        );
        let full = running;
        accumulate(
            (&signed[headline..], &mut maxima[headline..]),
            &panel[headline * LANES..],
            len,
            &mut running,
        );
        for (j, &value) in full.iter().enumerate().take(len) {
            if self.awaiting_next {
                self.around_full_maximum[2] = value;
                self.awaiting_next = false;
            }
            if value > self.full_maximum {
                self.full_maximum = value;
                self.step_of_full_maximum = start + j;
                self.around_full_maximum = [self.last_full, value, f64::NAN];
                self.awaiting_next = true;
            }
            self.last_full = value;
        }
    }

    /// The maxima of every K over the instants taken in.
    pub fn finish(self) -> PartialSumMaxima {
        let mut maxima: Vec<f64> = self
            .lane_maxima
            .iter()
            .map(|lanes| lanes.iter().copied().fold(f64::NEG_INFINITY, f64::max))
            .collect();
        let beyond = maxima.split_off(self.headline);
        PartialSumMaxima {
            maxima,
            beyond,
            step_of_full_maximum: self.step_of_full_maximum,
            around_full_maximum: self.around_full_maximum,
            continuous_full_maximum: None,
        }
    }
}

/// Adds each mode's cₖ yₖ to the lanes' running sums, in mode order, and keeps each partial
/// sum's maxima over the first `len` lanes (the padded instants of a last panel do not count).
#[inline(always)]
fn accumulate(
    (signed, maxima): (&[f64], &mut [[f64; LANES]]),
    panel: &[f64],
    len: usize,
    running: &mut [f64; LANES],
) {
    for ((&c, best), y) in signed.iter().zip(maxima).zip(panel.chunks_exact(LANES)) {
        for j in 0..LANES {
            running[j] += c * y[j];
        }
        if len == LANES {
            for j in 0..LANES {
                best[j] = larger(running[j], best[j]);
            }
        } else {
            for j in 0..len {
                best[j] = larger(running[j], best[j]);
            }
        }
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
    fn maxima_fed_panel_by_panel_equal_the_one_instant_loop_bit_for_bit() {
        // Steps not a multiple of the block, both signs, with and without a base series.
        let (steps, n) = (37, 5);
        let y: Vec<f64> = (0..steps * n)
            .map(|i| ((i as f64) * 0.37).sin() * (1.0 + (i % 7) as f64))
            .collect();
        let c = [0.3, -1.2, 0.7, 2.0, -0.05];
        let base: Vec<f64> = (0..steps).map(|i| (i as f64 * 0.11).cos()).collect();
        let zero = vec![0.0; steps];
        for sign in [1.0, -1.0] {
            for with_base in [false, true] {
                let b = if with_base { &base } else { &zero };
                let mut maxima = MaximaOfPartialSums::new(&c, sign);
                let mut panel = vec![f64::NAN; n * LANES];
                for start in (0..steps).step_by(LANES) {
                    let len = LANES.min(steps - start);
                    fill_panel(&y, n, (start, len), &mut panel);
                    let mut lanes = [0.0; LANES];
                    lanes[..len].copy_from_slice(&b[start..start + len]);
                    maxima.add_panel(&panel, (start, len), with_base.then_some(&lanes));
                }
                let got = maxima.finish();
                let (want, at) = reference(&c, sign, &y, steps, b);
                assert_eq!(got.maxima, want);
                assert_eq!(got.step_of_full_maximum, at);
            }
        }
    }
}
