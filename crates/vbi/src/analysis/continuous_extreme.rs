//! The static extreme between time steps (issue 46, item 2): the static reference
//! S(t) = Σ_w S_w · IL(x_w(t), y_w) sampled at the instants of the run misses the extreme of the
//! influence line under the axle group wherever it falls between two instants. For a bending
//! moment the influence line has a kink at the station, so the sampled extreme lies below the
//! true one by up to |dIL/dx| · v Δt / 2 per wheel (0.38 % of PL/4 for a force at 460 km/h and
//! Δt = 1 ms; 0.3–0.5 % below 13/64·P·l on a two-span beam at the old default step).
//!
//! Between the instants i − 1 and i + 1 around the sampled extreme the wheels move along
//! straight lines in t (exact at constant speed, and to O(Δt²) otherwise), and each wheel reads
//! the influence field through the cubic of the element it stands in ([`DeckReader`]), so S(t)
//! is a cubic polynomial in t between the instants where a wheel crosses a deck node or the
//! station (the breakpoints). On each such piece the cubic is fixed by four values (Newton's
//! forward differences at the piece's thirds) and its extremes are the roots of its derivative;
//! the extreme of S over the two steps is the best of the breakpoints and those roots, each
//! evaluated directly. Written by hand: the piecewise-cubic structure is the deck's own, which no
//! optimisation crate knows.

use super::node_major::NodeMajorFields;
use crate::deck::{DeckField, DeckReader};
use crate::influence::InfluenceLines;
use crate::modal::Quantity;
use crate::solver::WheelPaths;

/// The extreme of one station's static deflection or bending moment over the instants
/// `step − 1 … step + 1` of `paths`, in the direction of `sampled` (its value at `step`, the
/// sampled extreme): (value, instant), the instant a fractional index (t = instant · Δt). Never
/// smaller in magnitude than `sampled`.
pub(super) fn continuous_extreme(
    influence: &InfluenceLines,
    paths: WheelPaths,
    target: (usize, Quantity),
    (step, sampled): (usize, f64),
) -> (f64, f64) {
    let sign = sampled.signum();
    match extreme_between_instants(influence, paths, target, (step, sign), None) {
        Some((value, instant)) if sign * value > sign * sampled => (value, instant),
        _ => (sampled, step as f64),
    }
}

/// The extreme of a dynamic response R(t) = S(t) + D(t) around its sampled extreme at `step`,
/// given R there and at the instants on either side (`around`: R(step − 1), R(step),
/// R(step + 1), NaN where the run has no such instant), in the direction `sign` (±1): the
/// static part S exact between the instants as in [`continuous_extreme`] (its kinks as wheels
/// pass the station and the nodes), the dynamic remainder D = R − S through its three values
/// (a parabola: D holds the modes' inertia and damping part and the wheel forces' departures
/// from their static loads times the influence line, whose kinks are those of S scaled by
/// (P_w − S_w)/S_w). (value, instant); None where it cannot be refined (a shear force or a
/// reaction, a run of one instant).
pub(super) fn dynamic_extreme(
    influence: &InfluenceLines,
    paths: WheelPaths,
    target: (usize, Quantity),
    (step, sign): (usize, f64),
    around: [f64; 3],
) -> Option<(f64, f64)> {
    extreme_between_instants(influence, paths, target, (step, sign), Some(around))
}

/// [`continuous_extreme`] (`around` None) and [`dynamic_extreme`].
fn extreme_between_instants(
    influence: &InfluenceLines,
    paths: WheelPaths,
    (station, quantity): (usize, Quantity),
    (step, sign): (usize, f64),
    around: Option<[f64; 3]>,
) -> Option<(f64, f64)> {
    let steps = paths.step_count;
    if steps < 2 || sign == 0.0 || step >= steps {
        return None;
    }
    let fields: Vec<&DeckField> = match quantity {
        Quantity::Deflection => vec![&influence.deflection[station]],
        Quantity::BendingMoment => vec![
            &influence.moment_left[station],
            &influence.moment_right[station],
        ],
        Quantity::ShearForce | Quantity::SupportReaction => return None,
    };
    let mut line = StaticLine::new(influence, paths, station, &fields);
    let (mut first, mut last) = (step.saturating_sub(1), (step + 1).min(steps - 1));
    // The remainder D = R − S at the three instants, and the instants it reaches.
    let remainder = match around {
        None => [0.0; 3],
        Some(r) => {
            if !r[1].is_finite() {
                return None;
            }
            if !r[0].is_finite() || step == 0 {
                first = step;
            }
            if !r[2].is_finite() || step + 1 >= steps {
                last = step;
            }
            let mut at = |k: usize, i: usize| {
                if r[k].is_finite() {
                    r[k] - line.value(i as f64)
                } else {
                    f64::NAN
                }
            };
            [at(0, first), at(1, step), at(2, last)]
        }
    };
    let remainder_at = |instant: f64| -> f64 {
        let u = instant - step as f64;
        let [d0, d1, d2] = remainder;
        match (first < step, last > step) {
            (true, true) => d1 + u * (d2 - d0) / 2.0 + u * u * (d0 - 2.0 * d1 + d2) / 2.0,
            (true, false) => d1 + u * (d1 - d0),
            (false, true) => d1 + u * (d2 - d1),
            (false, false) => d1,
        }
    };
    let mut best: Option<(f64, f64)> = None;
    let mut consider = |line: &mut StaticLine, instant: f64| {
        let value = line.value(instant) + remainder_at(instant);
        if value.is_finite() && best.is_none_or(|(b, _)| sign * value > sign * b) {
            best = Some((value, instant));
        }
    };
    consider(&mut line, step as f64);
    let breakpoints = line.breakpoints(first, last);
    for piece in breakpoints.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        consider(&mut line, a);
        consider(&mut line, b);
        if b - a <= 0.0 {
            continue;
        }
        let h = (b - a) / 3.0;
        let f = [a, a + h, a + 2.0 * h, b].map(|t| line.value(t) + remainder_at(t));
        for s in cubic_stationary_points(f) {
            consider(&mut line, a + h * s);
        }
    }
    best
}

/// The stationary points s ∈ (0, 3) of the cubic through f(0), f(1), f(2), f(3) (Newton's
/// forward differences: p′(s) = Δ + (2s − 1)/2 Δ² + (3s² − 6s + 2)/6 Δ³).
fn cubic_stationary_points(f: [f64; 4]) -> Vec<f64> {
    let d1 = f[1] - f[0];
    let d2 = f[2] - 2.0 * f[1] + f[0];
    let d3 = f[3] - 3.0 * f[2] + 3.0 * f[1] - f[0];
    let (a, b, c) = (d3 / 2.0, d2 - d3, d1 - d2 / 2.0 + d3 / 3.0);
    let scale = f.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let roots = if a.abs() <= 1e-12 * scale {
        if b.abs() <= 1e-15 * scale {
            Vec::new()
        } else {
            vec![-c / b]
        }
    } else {
        let discriminant = b * b - 4.0 * a * c;
        if discriminant < 0.0 {
            Vec::new()
        } else {
            let root = discriminant.sqrt();
            // The root without cancellation, and the other from their product c/a.
            let q = -0.5 * (b + b.signum() * root);
            let mut roots = vec![q / a];
            if q != 0.0 {
                roots.push(c / q);
            }
            roots
        }
    };
    roots
        .into_iter()
        .filter(|s| s.is_finite() && *s > 0.0 && *s < 3.0)
        .collect()
}

/// One station's static line read at fractional instants: the wheels' positions interpolated
/// linearly between the recorded ones, each wheel's value through its element's cubic.
struct StaticLine<'a> {
    influence: &'a InfluenceLines,
    paths: WheelPaths<'a>,
    station: usize,
    table: NodeMajorFields,
    readers: Vec<DeckReader<'a>>,
    values: Vec<f64>,
}

impl<'a> StaticLine<'a> {
    fn new(
        influence: &'a InfluenceLines,
        paths: WheelPaths<'a>,
        station: usize,
        fields: &[&DeckField],
    ) -> Self {
        let table = NodeMajorFields::of(&influence.deck, fields);
        let readers = (paths.contacts.iter())
            .map(|c| DeckReader::new(&influence.deck, c.lateral_position, table.count))
            .collect();
        StaticLine {
            influence,
            paths,
            station,
            values: vec![0.0; table.count],
            table,
            readers,
        }
    }

    /// Wheel `w`'s position [m] at the fractional instant `instant`.
    fn position(&self, w: usize, instant: f64) -> f64 {
        let contacts = self.paths.contacts.len();
        let last = self.paths.step_count - 1;
        let i = (instant.floor().max(0.0) as usize).min(last.saturating_sub(1));
        let fraction = instant - i as f64;
        let (x0, x1) = (
            self.paths.positions[i * contacts + w],
            self.paths.positions[(i + 1).min(last) * contacts + w],
        );
        if fraction == 0.0 {
            x0
        } else if fraction == 1.0 {
            x1
        } else {
            x0 + fraction * (x1 - x0)
        }
    }

    /// S(t) of the station at the fractional instant.
    fn value(&mut self, instant: f64) -> f64 {
        let fields = (&self.table.deflection[..], &self.table.slope[..]);
        let mut sum = 0.0;
        for w in 0..self.paths.contacts.len() {
            let x = self.position(w, instant);
            if !self.readers[w].values(fields, x, &mut self.values) {
                continue;
            }
            // The moment field of the element on the side of the station away from the wheel.
            let value =
                if self.values.len() == 1 || self.influence.reads_left_element(self.station, x) {
                    self.values[0]
                } else {
                    self.values[1]
                };
            sum += self.paths.contacts[w].static_load * value;
        }
        sum
    }

    /// The instants in [first, last] where S(t) may change its cubic: the ends, the recorded
    /// instants between, and where a wheel crosses a deck node or the station; sorted. Each
    /// line's nodes are ascending already: a wheel's nodes in its step's range are found by
    /// bisection, line by line, without merging the deck's nodes.
    fn breakpoints(&self, first: usize, last: usize) -> Vec<f64> {
        let station = self.influence.stations[self.station].position;
        let lines = &self.influence.deck.lines;
        let mut instants: Vec<f64> = (first..=last).map(|i| i as f64).collect();
        for i in first..last {
            for w in 0..self.paths.contacts.len() {
                let (x0, x1) = (self.position(w, i as f64), self.position(w, (i + 1) as f64));
                if x0 == x1 {
                    continue;
                }
                let (low, high) = (x0.min(x1), x0.max(x1));
                let at = |x: f64| i as f64 + (x - x0) / (x1 - x0);
                for nodes in lines.iter().map(|line| &line.node_positions[..]) {
                    let from = nodes.partition_point(|&x| x <= low);
                    let to = nodes.partition_point(|&x| x < high);
                    instants.extend(nodes[from..to].iter().map(|&x| at(x)));
                }
                if low < station && station < high {
                    instants.push(at(station));
                }
            }
        }
        instants.sort_by(f64::total_cmp);
        instants.dedup();
        instants
    }
}

#[cfg(test)]
mod tests {
    use super::cubic_stationary_points;

    #[test]
    fn the_stationary_point_of_a_cubic_through_four_values_is_that_of_the_cubic() {
        // p(s) = (s − 1.2)² (a parabola: Δ³ = 0) has its minimum at s = 1.2.
        let p = |s: f64| (s - 1.2) * (s - 1.2);
        let roots = cubic_stationary_points([p(0.0), p(1.0), p(2.0), p(3.0)]);
        assert_eq!(roots.len(), 1);
        assert!((roots[0] - 1.2).abs() < 1e-12, "{roots:?}");
        // p(s) = s³ − 4.5 s² + 6 s: p′ = 3s² − 9s + 6 = 3(s − 1)(s − 2).
        let p = |s: f64| s * s * s - 4.5 * s * s + 6.0 * s;
        let mut roots = cubic_stationary_points([p(0.0), p(1.0), p(2.0), p(3.0)]);
        roots.sort_by(f64::total_cmp);
        assert_eq!(roots.len(), 2);
        assert!(
            (roots[0] - 1.0).abs() < 1e-12 && (roots[1] - 2.0).abs() < 1e-12,
            "{roots:?}"
        );
        // A straight line has none.
        assert!(cubic_stationary_points([0.0, 1.0, 2.0, 3.0]).is_empty());
    }
}
