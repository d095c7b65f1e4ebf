//! A static load effect's influence line along one lane, piecewise linear in the load's
//! position, with jumps allowed at its knots (a shear force at its section, an end support's
//! reaction at its bearing): the form in which the continuous maximum of a traffic event's
//! static effect is exact ([`super::maximum`]).
//!
//! Between knots x_k < x_{k+1} the ordinate is linear from `after[k]` (the limit from the right
//! at x_k) to `before[k+1]` (the limit from the left at x_{k+1}); it is zero off the line
//! (x < x₀ or x > x_n), where the load is off the deck. At a knot the line takes the limit from
//! the right ([`EffectLine::ordinate`]); [`EffectLine::limits`] gives both.
//!
//! Looked up in O(1) on average: a uniform grid of buckets over [x₀, x_n] holds, for each
//! bucket, the first interval that reaches into it (hand-written: a sorted-interval lookup
//! with a bucket index is a few lines, and no crate does this one job).

/// A piecewise-linear influence line with jumps: ordinate per unit downward load at position x.
#[derive(Debug, Clone, PartialEq)]
pub struct EffectLine {
    /// Knot positions x_k [m], increasing strictly, deck coordinates.
    knots: Vec<f64>,
    /// Limit from the left at each knot (per newton, in the effect's unit per N); `before[0]`
    /// is the value just inside the line's start approached from off the deck, i.e. 0.
    before: Vec<f64>,
    /// Limit from the right at each knot; `after[n − 1]` is 0 (off the deck beyond the end).
    after: Vec<f64>,
    /// First interval index per bucket of [`BUCKETS_PER_KNOT`] × n equal buckets.
    bucket_first_interval: Vec<u32>,
    /// Bucket width [m].
    bucket_width: f64,
}

/// Buckets per knot of the lookup grid: enough that a lookup scans about one interval.
const BUCKETS_PER_KNOT: usize = 2;

/// The relative difference under which a line's most negative and most positive ordinates are
/// a tie (a midspan shear's −½ and +½, which the FE lines give to round-off, about 10⁻¹²).
pub const SENSE_TIE: f64 = 1e-9;

/// The ordinate of largest magnitude of a range (most negative, most positive), positive on a
/// tie within [`SENSE_TIE`].
pub fn dominant_of((low, high): (f64, f64)) -> f64 {
    if -low > high * (1.0 + SENSE_TIE) {
        low
    } else {
        high
    }
}

/// Why a tabulated line cannot be an [`EffectLine`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EffectLineError {
    /// Fewer than two knots.
    #[error("an influence line needs at least two points, got {0}")]
    TooFewKnots(usize),
    /// Positions not increasing (a repeated position is a jump: give it once with two values).
    #[error("the positions must increase strictly: x = {previous} m then {next} m")]
    NotIncreasing {
        /// The earlier position [m].
        previous: f64,
        /// The position that does not exceed it [m].
        next: f64,
    },
    /// A position or an ordinate is not finite.
    #[error("a position or an ordinate is not finite (point {0}, from 1)")]
    NotFinite(usize),
}

impl EffectLine {
    /// A continuous line through the points (x_k, y_k), zero off [x₀, x_n]. An ordinate at the
    /// ends that is not zero is a jump there (the load steps onto the deck).
    pub fn continuous(knots: Vec<f64>, ordinates: Vec<f64>) -> Result<EffectLine, EffectLineError> {
        let n = knots.len().min(ordinates.len());
        let mut before = ordinates.clone();
        let mut after = ordinates;
        if n > 0 {
            before[0] = 0.0;
            after[n - 1] = 0.0;
        }
        EffectLine::with_jumps(knots, before, after)
    }

    /// A line from both one-sided limits at each knot; `before[0]` and `after[n − 1]` are read
    /// as they are (give 0 for a line that vanishes off the deck, as loads off it act on the
    /// ground).
    pub fn with_jumps(
        knots: Vec<f64>,
        before: Vec<f64>,
        after: Vec<f64>,
    ) -> Result<EffectLine, EffectLineError> {
        let n = knots.len();
        if n < 2 || before.len() != n || after.len() != n {
            return Err(EffectLineError::TooFewKnots(
                n.min(before.len()).min(after.len()),
            ));
        }
        for k in 0..n {
            if !(knots[k].is_finite() && before[k].is_finite() && after[k].is_finite()) {
                return Err(EffectLineError::NotFinite(k + 1));
            }
            if k > 0 && knots[k] <= knots[k - 1] {
                return Err(EffectLineError::NotIncreasing {
                    previous: knots[k - 1],
                    next: knots[k],
                });
            }
        }
        let buckets = BUCKETS_PER_KNOT * n;
        let bucket_width = (knots[n - 1] - knots[0]) / buckets as f64;
        let mut bucket_first_interval = Vec::with_capacity(buckets);
        let mut interval = 0;
        for b in 0..buckets {
            let start = knots[0] + b as f64 * bucket_width;
            while interval + 2 < n && knots[interval + 1] <= start {
                interval += 1;
            }
            bucket_first_interval.push(interval as u32);
        }
        Ok(EffectLine {
            knots,
            before,
            after,
            bucket_first_interval,
            bucket_width,
        })
    }

    /// The same line without its redundant knots: an interior knot with no jump whose ordinate
    /// the straight line between its neighbours (as kept) reproduces within `tolerance` ×
    /// the line's largest |ordinate|. A knot is a breakpoint of the continuous extreme
    /// ([`super::event`]), so a beam's moment line tabulated at every node keeps only its kinks
    /// (a simple span's midspan moment: 3 knots), and the extreme costs that many evaluations.
    /// The line moves by at most that tolerance anywhere.
    pub fn simplified(&self, tolerance: f64) -> EffectLine {
        let scale = self.dominant_ordinate().abs();
        let limit = tolerance * scale;
        let n = self.knots.len();
        let mut keep = vec![0usize];
        for k in 1..n - 1 {
            let last = *keep.last().expect("the first knot is kept");
            let next = k + 1;
            let continuous = self.before[k] == self.after[k];
            // Every dropped knot between `last` and `next` (and k itself) must lie on the chord
            // from `last` (its right limit) to `next` (its left limit).
            let on_chord = (last + 1..=k).all(|j| {
                let fraction =
                    (self.knots[j] - self.knots[last]) / (self.knots[next] - self.knots[last]);
                let chord = self.after[last] + fraction * (self.before[next] - self.after[last]);
                (chord - self.after[j]).abs() <= limit && (chord - self.before[j]).abs() <= limit
            });
            if !(continuous && on_chord) {
                keep.push(k);
            }
        }
        keep.push(n - 1);
        EffectLine::with_jumps(
            keep.iter().map(|&k| self.knots[k]).collect(),
            keep.iter().map(|&k| self.before[k]).collect(),
            keep.iter().map(|&k| self.after[k]).collect(),
        )
        .expect("a subset of a valid line's knots is valid")
    }

    /// The knot positions [m].
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The line's start and end [m].
    pub fn extent(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// The interval k with x_k ≤ x < x_{k+1}, for x inside [x₀, x_n).
    #[inline]
    fn interval(&self, x: f64) -> usize {
        let last = self.knots.len() - 2;
        let bucket = ((x - self.knots[0]) / self.bucket_width) as usize;
        let mut k =
            self.bucket_first_interval[bucket.min(self.bucket_first_interval.len() - 1)] as usize;
        while k < last && self.knots[k + 1] <= x {
            k += 1;
        }
        k
    }

    /// The ordinate at x [m]: the limit from the right at a knot, zero off the line.
    #[inline]
    pub fn ordinate(&self, x: f64) -> f64 {
        let n = self.knots.len();
        if x < self.knots[0] || x > self.knots[n - 1] {
            return 0.0;
        }
        if x == self.knots[n - 1] {
            return self.after[n - 1];
        }
        let k = self.interval(x);
        if x == self.knots[k] {
            return self.after[k];
        }
        let fraction = (x - self.knots[k]) / (self.knots[k + 1] - self.knots[k]);
        self.after[k] + fraction * (self.before[k + 1] - self.after[k])
    }

    /// Both one-sided limits at knot k: (from the left, from the right).
    #[inline]
    pub fn limits(&self, k: usize) -> (f64, f64) {
        (self.before[k], self.after[k])
    }

    /// The most negative and the most positive ordinates over the line (each 0 at least: the
    /// line is 0 off the deck).
    pub fn ordinate_range(&self) -> (f64, f64) {
        self.before
            .iter()
            .chain(&self.after)
            .fold((0.0, 0.0), |(low, high): (f64, f64), &y| {
                (low.min(y), high.max(y))
            })
    }

    /// The ordinate of largest magnitude over the line, with its sign (the positive one when the
    /// two agree within [`SENSE_TIE`] of their size): the sense in which the effect governs (a
    /// sagging moment positive, a hogging moment or a downward deflection negative, a midspan
    /// shear's ±½ positive).
    pub fn dominant_ordinate(&self) -> f64 {
        dominant_of(self.ordinate_range())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The midspan moment line of a simple span L = 30 m: L/4 at the middle, zero at the ends.
    fn midspan_moment() -> EffectLine {
        EffectLine::continuous(vec![0.0, 15.0, 30.0], vec![0.0, 7.5, 0.0]).unwrap()
    }

    #[test]
    fn ordinates_interpolate_linearly_and_vanish_off_the_deck() {
        let line = midspan_moment();
        for (x, expected) in [
            (-1.0, 0.0),
            (0.0, 0.0),
            (6.0, 3.0),
            (15.0, 7.5),
            (27.0, 1.5),
            (31.0, 0.0),
        ] {
            assert!((line.ordinate(x) - expected).abs() < 1e-14, "x = {x}");
        }
        assert_eq!(line.dominant_ordinate(), 7.5);
    }

    #[test]
    fn a_jump_takes_the_right_limit_at_its_knot_and_both_limits_are_given() {
        // Shear at the middle of a simple span: −x/L left of it, 1 − x/L right of it.
        let line = EffectLine::with_jumps(
            vec![0.0, 15.0, 30.0],
            vec![0.0, -0.5, 0.0],
            vec![0.0, 0.5, 0.0],
        )
        .unwrap();
        assert_eq!(line.ordinate(15.0), 0.5);
        assert_eq!(line.limits(1), (-0.5, 0.5));
        assert!((line.ordinate(7.5) + 0.25).abs() < 1e-14);
        assert!((line.ordinate(22.5) - 0.25).abs() < 1e-14);
    }

    #[test]
    fn the_bucket_lookup_agrees_with_a_linear_scan_on_uneven_knots() {
        let knots: Vec<f64> = (0..40).map(|k| (k as f64).powf(1.7)).collect();
        let values: Vec<f64> = knots.iter().map(|x| (x * 0.1).sin()).collect();
        let line = EffectLine::continuous(knots.clone(), values.clone()).unwrap();
        for i in 0..2000 {
            let x = knots[39] * i as f64 / 1999.0;
            let k = knots
                .windows(2)
                .position(|w| w[0] <= x && x < w[1])
                .unwrap_or(38);
            let fraction = (x - knots[k]) / (knots[k + 1] - knots[k]);
            let start = if k == 0 { values[0] } else { values[k] };
            let end = if k + 1 == 39 {
                values[39]
            } else {
                values[k + 1]
            };
            let expected = if x == knots[39] {
                0.0
            } else {
                start + fraction * (end - start)
            };
            assert!((line.ordinate(x) - expected).abs() < 1e-12, "x = {x}");
        }
    }

    #[test]
    fn simplifying_keeps_the_kinks_and_jumps_and_moves_no_ordinate_beyond_the_tolerance() {
        // The midspan moment tabulated every 0.25 m, with round-off of 1e-13 on its ordinates.
        let knots: Vec<f64> = (0..=120).map(|k| k as f64 * 0.25).collect();
        let values: Vec<f64> = knots
            .iter()
            .enumerate()
            .map(|(k, &x)| x.min(30.0 - x) / 2.0 * (1.0 + 1e-13 * ((k % 3) as f64 - 1.0)))
            .collect();
        let line = EffectLine::continuous(knots.clone(), values).unwrap();
        let simple = line.simplified(1e-10);
        assert_eq!(simple.knots(), &[0.0, 15.0, 30.0]);
        for i in 0..=3000 {
            let x = i as f64 * 0.01;
            assert!(
                (simple.ordinate(x) - line.ordinate(x)).abs() <= 1e-10 * 7.5,
                "x = {x}"
            );
        }
        // A jump is a knot to keep, even where the chord passes through both limits' mean.
        let shear = EffectLine::with_jumps(
            vec![0.0, 7.5, 15.0, 22.5, 30.0],
            vec![0.0, -0.25, -0.5, 0.25, 0.0],
            vec![0.0, -0.25, 0.5, 0.25, 0.0],
        )
        .unwrap()
        .simplified(1e-10);
        assert_eq!(shear.knots(), &[0.0, 15.0, 30.0]);
        assert_eq!(shear.limits(1), (-0.5, 0.5));
    }

    #[test]
    fn repeated_and_non_finite_positions_are_refused() {
        assert!(matches!(
            EffectLine::continuous(vec![0.0, 1.0, 1.0], vec![0.0; 3]),
            Err(EffectLineError::NotIncreasing { .. })
        ));
        assert_eq!(
            EffectLine::continuous(vec![0.0, f64::NAN], vec![0.0; 2]),
            Err(EffectLineError::NotFinite(2))
        );
        assert_eq!(
            EffectLine::continuous(vec![0.0], vec![0.0]),
            Err(EffectLineError::TooFewKnots(1))
        );
    }
}
