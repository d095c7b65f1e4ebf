//! Rainflow counting of a stress history, ASTM E1049-85 (reapproved 2017), *Standard Practices
//! for Cycle Counting in Fatigue Analysis*, §5.4.4 (the three-point rainflow counting that keeps
//! the history's starting point), with the residue counted as half cycles as §5.4.4 prescribes.
//!
//! The history is first reduced to its reversals (§5.4.4: peaks and valleys; a sample equal to
//! the one before it is skipped; the first and the last samples are reversals). Then each
//! reversal is read in turn; with X the range of the two latest reversals and Y the range of the
//! two before them (ASTM E1049 §5.4.4.2):
//!
//! 1. while at least three reversals are on the stack and X ≥ Y:
//!    - if Y contains the starting point S, count Y as one half cycle and discard its first
//!      point (S moves on);
//!    - else count Y as one cycle and discard its peak and valley;
//! 2. at the end, count every range of the residue as one half cycle (§5.4.4.3).
//!
//! The counting is online: [`RainflowCounter`] takes the samples one at a time and holds only
//! the pending reversal and the residue (a stack whose ranges grow outwards, as short as the
//! history's distinct amplitude levels), so that a lifetime of traffic is counted as one history
//! across its events without keeping it.
//!
//! Written by hand: crates.io has no rainflow crate (checked December 2026). The counts are those
//! of the Python package `rainflow` 3.2 (same rule, same reversals), which the Python tests
//! compare on 1,000 random histories (crates/vbi-py/tests/test_rainflow.py).

/// One counted cycle or half cycle of a history, in the history's unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cycle {
    /// The range |peak − valley| [the history's unit; Pa for a stress].
    pub range: f64,
    /// The mean (peak + valley)/2 [the history's unit].
    pub mean: f64,
    /// 1 for a full cycle, 0.5 for a half cycle.
    pub count: f64,
}

impl Cycle {
    fn between(first: f64, second: f64, count: f64) -> Cycle {
        Cycle {
            range: (first - second).abs(),
            mean: 0.5 * (first + second),
            count,
        }
    }
}

/// Counts a history's cycles sample by sample (ASTM E1049-85 §5.4.4): [`RainflowCounter::push`]
/// each sample, then [`RainflowCounter::finish`] for the residue's half cycles. The cycles are
/// given to a closure as they close, so that nothing grows with the history's length.
#[derive(Debug, Clone, Default)]
pub struct RainflowCounter {
    /// The reversals not yet counted, the starting point first.
    stack: Vec<f64>,
    /// The last sample that differs from the one before it, not yet known to be a reversal.
    pending: Option<f64>,
    /// The sign of the slope into `pending` (0 while the history has been flat).
    slope: f64,
}

impl RainflowCounter {
    /// A counter for a new history.
    pub fn new() -> RainflowCounter {
        RainflowCounter::default()
    }

    /// Reads one sample; the cycles it closes go to `on_cycle`. A non-finite sample is skipped
    /// (a stress history has none; the callers check their inputs).
    pub fn push(&mut self, sample: f64, mut on_cycle: impl FnMut(Cycle)) {
        if !sample.is_finite() {
            return;
        }
        let Some(pending) = self.pending else {
            // The first sample is a reversal.
            self.pending = Some(sample);
            self.reversal(sample, &mut on_cycle);
            return;
        };
        if sample == pending {
            return;
        }
        let slope = (sample - pending).signum();
        if self.slope * slope < 0.0 {
            // The pending sample was a peak or a valley (and not the first sample, which the
            // stack already holds).
            self.reversal(pending, &mut on_cycle);
        }
        self.slope = slope;
        self.pending = Some(sample);
    }

    /// Reads a reversal: the three-point rule of ASTM E1049 §5.4.4.2.
    fn reversal(&mut self, point: f64, on_cycle: &mut impl FnMut(Cycle)) {
        self.stack.push(point);
        while self.stack.len() >= 3 {
            let n = self.stack.len();
            let (x1, x2, x3) = (self.stack[n - 3], self.stack[n - 2], self.stack[n - 1]);
            let x_range = (x3 - x2).abs();
            let y_range = (x2 - x1).abs();
            if x_range < y_range {
                break;
            }
            if n == 3 {
                // Y contains the starting point: one half cycle, and S moves on.
                on_cycle(Cycle::between(x1, x2, 0.5));
                self.stack.remove(0);
            } else {
                on_cycle(Cycle::between(x1, x2, 1.0));
                self.stack.truncate(n - 3);
                self.stack.push(x3);
            }
        }
    }

    /// Ends the history: its last sample is a reversal (unless the history never left its first
    /// value, which the stack holds already), and every range of the residue counts as one half
    /// cycle (§5.4.4.3), in the history's order.
    pub fn finish(mut self, mut on_cycle: impl FnMut(Cycle)) {
        if let (Some(last), true) = (self.pending, self.slope != 0.0) {
            self.reversal(last, &mut on_cycle);
        }
        for pair in self.stack.windows(2) {
            on_cycle(Cycle::between(pair[0], pair[1], 0.5));
        }
    }
}

/// The cycles of a whole history (ASTM E1049-85 §5.4.4), in the order they are counted: the
/// closed ones as they close, then the residue's half cycles.
pub fn rainflow(history: &[f64]) -> Vec<Cycle> {
    let mut cycles = Vec::new();
    let mut counter = RainflowCounter::new();
    for &sample in history {
        counter.push(sample, |c| cycles.push(c));
    }
    counter.finish(|c| cycles.push(c));
    cycles
}

/// The counts of a history's cycles by range, summed over equal ranges and sorted by range:
/// what the Python package `rainflow`'s `count_cycles(series)` returns.
pub fn count_by_range(cycles: &[Cycle]) -> Vec<(f64, f64)> {
    let mut sorted: Vec<(f64, f64)> = cycles.iter().map(|c| (c.range, c.count)).collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut counts: Vec<(f64, f64)> = Vec::new();
    for (range, count) in sorted {
        match counts.last_mut() {
            Some(last) if last.0 == range => last.1 += count,
            _ => counts.push((range, count)),
        }
    }
    counts
}
