//! The deck as the vehicle sees it: girder lines, fields on them, and where a wheel stands.
//!
//! Every field that a wheel samples (a mode shape, an influence line) is stored at the deck
//! nodes as a vertical deflection `w` [m per unit] and its longitudinal slope `dw/dx`
//! [per unit]. Between nodes of one line it is interpolated by the cubic Hermite shape functions
//! of the Euler–Bernoulli beam element (the paper's ⟨N_i⟩ of Eq. 26), which is exact for a beam
//! element that carries no load inside it. Across the deck, a point between two girder lines takes
//! the two lines' values by linear (lever-rule) weights; beyond the outermost line the same
//! straight line is extrapolated (a rigid cantilever to the edge).
//!
//! Coordinates: `x` [m] runs along the bridge from the first support (0) to the last (`length`);
//! `y` [m] is lateral, measured from the deck centreline, positive to the left in the direction of
//! travel. Deflection is positive upwards.

use serde::{Deserialize, Serialize};

mod element_cubic;

pub use element_cubic::{DeckReader, ElementCubic};

/// One longitudinal line of deck nodes: a girder of a grillage, or the single line of a beam.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DeckLine {
    /// Lateral position y of the line [m], from the deck centreline, positive to the left.
    pub lateral_position: f64,
    /// Longitudinal positions x of the line's nodes [m], strictly ascending.
    pub node_positions: Vec<f64>,
    /// Index of this line's first node in the deck-wide node numbering; its nodes are
    /// `first_node .. first_node + node_positions.len()`.
    pub first_node: usize,
}

/// The deck: its lines sorted by lateral position, and its length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DeckGeometry {
    /// Lines sorted by ascending lateral position (right to left).
    pub lines: Vec<DeckLine>,
    /// Length of the deck between the end supports [m].
    pub length: f64,
}

/// A field on the deck nodes, for example one mode shape or one influence line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct DeckField {
    /// Vertical value at each deck node (deflection [m] per unit of the field's cause).
    pub deflection: Vec<f64>,
    /// Longitudinal slope d(deflection)/dx at each deck node [per metre of the above].
    pub slope: Vec<f64>,
}

impl DeckField {
    /// A field of zeros on `nodes` deck nodes.
    pub fn zeros(nodes: usize) -> Self {
        DeckField {
            deflection: vec![0.0; nodes],
            slope: vec![0.0; nodes],
        }
    }
}

/// One term of a [`DeckStencil`]: how one node's value and slope enter the point's value and slope.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StencilTerm {
    /// Deck node index.
    pub node: usize,
    /// Weight of the node's deflection in the point's deflection.
    pub value_from_deflection: f64,
    /// Weight of the node's slope in the point's deflection [m].
    pub value_from_slope: f64,
    /// Weight of the node's deflection in the point's slope [1/m].
    pub slope_from_deflection: f64,
    /// Weight of the node's slope in the point's slope.
    pub slope_from_slope: f64,
}

/// The interpolation of a deck field at one point: at most two lines × two nodes.
/// A point off the deck (x < 0 or x > length) has no terms: fields vanish there.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DeckStencil {
    terms: [StencilTerm; 4],
    len: usize,
}

impl DeckStencil {
    /// The stencil's terms.
    pub fn terms(&self) -> &[StencilTerm] {
        &self.terms[..self.len]
    }

    /// True when the point is off the deck.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    fn push(&mut self, term: StencilTerm) {
        self.terms[self.len] = term;
        self.len += 1;
    }

    /// Value and slope of one field at the point.
    pub fn evaluate(&self, field: &DeckField) -> (f64, f64) {
        let mut value = 0.0;
        let mut slope = 0.0;
        for t in self.terms() {
            let w = field.deflection[t.node];
            let s = field.slope[t.node];
            value += t.value_from_deflection * w + t.value_from_slope * s;
            slope += t.slope_from_deflection * w + t.slope_from_slope * s;
        }
        (value, slope)
    }

    /// Values (no slopes) of many fields stored node-major (`deflection[node * count + k]`),
    /// written to `values[k]`, k = 0..count; each value is summed in the same order as
    /// [`DeckStencil::evaluate`], so the two agree bit for bit. Cost: terms × count.
    pub fn values_many(&self, deflection: &[f64], slope: &[f64], count: usize, values: &mut [f64]) {
        let values = &mut values[..count];
        values.fill(0.0);
        for t in self.terms() {
            let w = &deflection[t.node * count..(t.node + 1) * count];
            let s = &slope[t.node * count..(t.node + 1) * count];
            for ((v, &wk), &sk) in values.iter_mut().zip(w).zip(s) {
                *v += t.value_from_deflection * wk + t.value_from_slope * sk;
            }
        }
    }

    /// Values and slopes of many fields stored node-major (`deflection[node * count + k]`),
    /// written to `values[k]` and `slopes[k]`, k = 0..count. Cost: terms × count. The terms are
    /// taken in pairs (the two nodes of one girder element), so each output is read and written
    /// once per element, over zipped slices that the compiler vectorises without bounds checks:
    /// this is the coupled solver's mode-shape evaluation, in its time-step loop.
    pub fn evaluate_many(
        &self,
        deflection: &[f64],
        slope: &[f64],
        count: usize,
        values: &mut [f64],
        slopes: &mut [f64],
    ) {
        let (values, slopes) = (&mut values[..count], &mut slopes[..count]);
        let field = |t: &StencilTerm| {
            (
                &deflection[t.node * count..(t.node + 1) * count],
                &slope[t.node * count..(t.node + 1) * count],
            )
        };
        values.fill(0.0);
        slopes.fill(0.0);
        for pair in self.terms().chunks(2) {
            let t0 = &pair[0];
            let (w0, s0) = field(t0);
            if let [_, t1] = pair {
                let (w1, s1) = field(t1);
                let rows = w0.iter().zip(s0).zip(w1.iter().zip(s1));
                for ((v, sl), ((a0, b0), (a1, b1))) in
                    values.iter_mut().zip(slopes.iter_mut()).zip(rows)
                {
                    *v += t0.value_from_deflection * a0
                        + t0.value_from_slope * b0
                        + t1.value_from_deflection * a1
                        + t1.value_from_slope * b1;
                    *sl += t0.slope_from_deflection * a0
                        + t0.slope_from_slope * b0
                        + t1.slope_from_deflection * a1
                        + t1.slope_from_slope * b1;
                }
            } else {
                for (((v, sl), a0), b0) in values.iter_mut().zip(slopes.iter_mut()).zip(w0).zip(s0)
                {
                    *v += t0.value_from_deflection * a0 + t0.value_from_slope * b0;
                    *sl += t0.slope_from_deflection * a0 + t0.slope_from_slope * b0;
                }
            }
        }
    }
}

/// Cubic Hermite shape functions of a beam element of length `h` at ξ = (x − x₁)/h and their
/// x-derivatives: N₁ = 1 − 3ξ² + 2ξ³, N₂ = h(ξ − 2ξ² + ξ³), N₃ = 3ξ² − 2ξ³, N₄ = h(ξ³ − ξ²).
pub fn hermite_shape_functions(xi: f64, h: f64) -> ([f64; 4], [f64; 4]) {
    let xi2 = xi * xi;
    let xi3 = xi2 * xi;
    let n = [
        1.0 - 3.0 * xi2 + 2.0 * xi3,
        h * (xi - 2.0 * xi2 + xi3),
        3.0 * xi2 - 2.0 * xi3,
        h * (xi3 - xi2),
    ];
    let dn = [
        (-6.0 * xi + 6.0 * xi2) / h,
        1.0 - 4.0 * xi + 3.0 * xi2,
        (6.0 * xi - 6.0 * xi2) / h,
        3.0 * xi2 - 2.0 * xi,
    ];
    (n, dn)
}

impl DeckGeometry {
    /// Total number of deck nodes over all lines.
    pub fn node_count(&self) -> usize {
        self.lines.iter().map(|l| l.node_positions.len()).sum()
    }

    /// Whether a point at x [m] with lateral `weights` ([`DeckGeometry::lateral_weights`]) is
    /// on the deck: exactly where [`DeckGeometry::stencil`] has terms (0 ≤ x ≤ L, and a line
    /// with a non-zero weight).
    #[inline]
    pub fn carries(&self, weights: &[(usize, f64); 2], x: f64) -> bool {
        (0.0..=self.length).contains(&x) && weights.iter().any(|&(_, l)| l != 0.0)
    }

    /// Lateral weights of the lines around y: `(line index, weight)` pairs summing to 1.
    pub fn lateral_weights(&self, y: f64) -> [(usize, f64); 2] {
        let n = self.lines.len();
        if n == 1 {
            return [(0, 1.0), (0, 0.0)];
        }
        // The pair of lines bracketing y, or the outermost pair for extrapolation.
        let mut right = 0;
        while right + 2 < n && self.lines[right + 1].lateral_position <= y {
            right += 1;
        }
        let left = right + 1;
        let y0 = self.lines[right].lateral_position;
        let y1 = self.lines[left].lateral_position;
        let s = (y - y0) / (y1 - y0);
        [(right, 1.0 - s), (left, s)]
    }

    /// The stencil of the point (x, y): Hermite along each line, lever rule across lines.
    pub fn stencil(&self, x: f64, y: f64) -> DeckStencil {
        let mut stencil = DeckStencil::default();
        if !(0.0..=self.length).contains(&x) {
            return stencil;
        }
        for (line_index, lateral_weight) in self.lateral_weights(y) {
            if lateral_weight == 0.0 {
                continue;
            }
            let xs = &self.lines[line_index].node_positions;
            // Element e spans xs[e]..xs[e+1].
            let element = match xs.partition_point(|&p| p <= x) {
                0 => 0,
                i if i >= xs.len() => xs.len() - 2,
                i => i - 1,
            };
            self.push_line_terms(&mut stencil, line_index, lateral_weight, x, element);
        }
        stencil
    }

    /// The terms of line `line_index` at x, weighted by `lateral_weight`, on element `element`
    /// (the last node at or before x, at most the line's last element).
    fn push_line_terms(
        &self,
        stencil: &mut DeckStencil,
        line_index: usize,
        lateral_weight: f64,
        x: f64,
        element: usize,
    ) {
        let line = &self.lines[line_index];
        let xs = &line.node_positions;
        // Beyond a line's own ends (the corners of a skewed deck, where its neighbour's
        // support is offset), the line holds its end node's deflection, with no slope.
        let last = xs.len() - 1;
        if x < xs[0] || x > xs[last] {
            let end = if x < xs[0] { 0 } else { last };
            stencil.push(StencilTerm {
                node: line.first_node + end,
                value_from_deflection: lateral_weight,
                value_from_slope: 0.0,
                slope_from_deflection: 0.0,
                slope_from_slope: 0.0,
            });
            return;
        }
        let e = element;
        let h = xs[e + 1] - xs[e];
        let xi = ((x - xs[e]) / h).clamp(0.0, 1.0);
        let (n, dn) = hermite_shape_functions(xi, h);
        for (end, node) in [(0usize, line.first_node + e), (1, line.first_node + e + 1)] {
            stencil.push(StencilTerm {
                node,
                value_from_deflection: lateral_weight * n[2 * end],
                value_from_slope: lateral_weight * n[2 * end + 1],
                slope_from_deflection: lateral_weight * dn[2 * end],
                slope_from_slope: lateral_weight * dn[2 * end + 1],
            });
        }
    }
}

/// A wheel's walk along the deck at a fixed lateral position: the lateral weights computed
/// once and, on each line, the element where the wheel stood last, from which the element of
/// the next position is found by a short scan (a run's positions move by a fraction of an
/// element per step) instead of a binary search. [`DeckWalk::stencil`] is
/// [`DeckGeometry::stencil`] bit for bit, for positions in any order.
#[derive(Debug, Clone)]
pub struct DeckWalk<'a> {
    deck: &'a DeckGeometry,
    weights: [(usize, f64); 2],
    elements: [usize; 2],
}

impl<'a> DeckWalk<'a> {
    /// A walk at lateral position y [m].
    pub fn new(deck: &'a DeckGeometry, y: f64) -> Self {
        DeckWalk {
            deck,
            weights: deck.lateral_weights(y),
            elements: [0, 0],
        }
    }

    /// The stencil at x [m] ([`DeckGeometry::stencil`] at (x, y)).
    pub fn stencil(&mut self, x: f64) -> DeckStencil {
        let deck = self.deck;
        let mut stencil = DeckStencil::default();
        if !(0.0..=deck.length).contains(&x) {
            return stencil;
        }
        for ((line_index, lateral_weight), element) in
            self.weights.into_iter().zip(self.elements.iter_mut())
        {
            if lateral_weight == 0.0 {
                continue;
            }
            let xs = &deck.lines[line_index].node_positions;
            // The last node at or before x, at most the last element's first node: the same
            // element as the binary search of DeckGeometry::stencil.
            let mut e = (*element).min(xs.len() - 2);
            while e + 2 < xs.len() && xs[e + 1] <= x {
                e += 1;
            }
            while e > 0 && xs[e] > x {
                e -= 1;
            }
            *element = e;
            deck.push_line_terms(&mut stencil, line_index, lateral_weight, x, e);
        }
        stencil
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_line_deck() -> DeckGeometry {
        DeckGeometry {
            lines: vec![
                DeckLine {
                    lateral_position: -1.0,
                    node_positions: vec![0.0, 2.0, 4.0],
                    first_node: 0,
                },
                DeckLine {
                    lateral_position: 1.0,
                    node_positions: vec![0.0, 2.0, 4.0],
                    first_node: 3,
                },
            ],
            length: 4.0,
        }
    }

    #[test]
    fn hermite_interpolation_reproduces_a_cubic_exactly() {
        // f(x) = x³ − 2x² + 1 is cubic, so Hermite interpolation on any element is exact.
        let f = |x: f64| x * x * x - 2.0 * x * x + 1.0;
        let df = |x: f64| 3.0 * x * x - 4.0 * x;
        let deck = two_line_deck();
        let xs = [0.0, 2.0, 4.0, 0.0, 2.0, 4.0];
        let field = DeckField {
            deflection: xs.iter().map(|&x| f(x)).collect(),
            slope: xs.iter().map(|&x| df(x)).collect(),
        };
        for x in [0.0, 0.3, 1.7, 2.0, 3.1, 4.0] {
            let (v, s) = deck.stencil(x, 0.4).evaluate(&field);
            assert!((v - f(x)).abs() < 1e-12, "value at {x}");
            assert!((s - df(x)).abs() < 1e-12, "slope at {x}");
        }
    }

    #[test]
    fn lever_rule_weights_sum_to_one_and_extrapolate_linearly() {
        let deck = two_line_deck();
        let [(a, wa), (b, wb)] = deck.lateral_weights(0.5);
        assert_eq!((a, b), (0, 1));
        assert!((wa - 0.25).abs() < 1e-15 && (wb - 0.75).abs() < 1e-15);
        let [(_, wa), (_, wb)] = deck.lateral_weights(2.0);
        assert!((wa + 0.5).abs() < 1e-15 && (wb - 1.5).abs() < 1e-15);
    }

    #[test]
    fn a_point_off_the_deck_has_an_empty_stencil() {
        let deck = two_line_deck();
        assert!(deck.stencil(-0.1, 0.0).is_empty());
        assert!(deck.stencil(4.1, 0.0).is_empty());
        assert!(!deck.stencil(4.0, 0.0).is_empty());
    }

    #[test]
    fn evaluate_many_matches_evaluate_per_field() {
        let deck = two_line_deck();
        let count = 2;
        let nodes = deck.node_count();
        let deflection: Vec<f64> = (0..nodes * count).map(|i| (i as f64).sin()).collect();
        let slope: Vec<f64> = (0..nodes * count).map(|i| (i as f64).cos()).collect();
        let stencil = deck.stencil(2.7, -0.3);
        let mut values = vec![0.0; count];
        let mut slopes = vec![0.0; count];
        stencil.evaluate_many(&deflection, &slope, count, &mut values, &mut slopes);
        for k in 0..count {
            let field = DeckField {
                deflection: (0..nodes).map(|n| deflection[n * count + k]).collect(),
                slope: (0..nodes).map(|n| slope[n * count + k]).collect(),
            };
            let (v, s) = stencil.evaluate(&field);
            assert!((v - values[k]).abs() < 1e-14 && (s - slopes[k]).abs() < 1e-14);
        }
    }

    #[test]
    fn values_many_equals_evaluate_per_field_bit_for_bit() {
        // Four terms (between the lines), two (on a line, or beyond a line's lever arm), and
        // fields with signed zeros, so that the sum's first addition to 0 matters.
        let deck = two_line_deck();
        let count = 7;
        let nodes = deck.node_count();
        let value = |i: usize| match i % 5 {
            0 => -0.0,
            _ => (1.7 * i as f64).sin() * 10f64.powi(i as i32 % 7 - 3),
        };
        let deflection: Vec<f64> = (0..nodes * count).map(value).collect();
        let slope: Vec<f64> = (0..nodes * count).map(|i| value(i + 2)).collect();
        let mut term_counts = Vec::new();
        for (x, y) in [(2.7, -0.3), (0.4, 0.9), (3.1, -1.0), (1.0, 1.0), (4.0, 0.0)] {
            let stencil = deck.stencil(x, y);
            term_counts.push(stencil.terms().len());
            let mut values = vec![f64::NAN; count];
            stencil.values_many(&deflection, &slope, count, &mut values);
            for (k, v) in values.iter().enumerate() {
                let field = DeckField {
                    deflection: (0..nodes).map(|n| deflection[n * count + k]).collect(),
                    slope: (0..nodes).map(|n| slope[n * count + k]).collect(),
                };
                let (expected, _) = stencil.evaluate(&field);
                let terms = stencil.terms().len();
                assert_eq!(
                    v.to_bits(),
                    expected.to_bits(),
                    "x {x}, y {y}, {terms} terms"
                );
            }
        }
        assert!(
            term_counts.contains(&4) && term_counts.contains(&2),
            "{term_counts:?}"
        );
    }

    #[test]
    fn a_walk_gives_the_binary_search_stencil_bit_for_bit_in_any_order() {
        // Uneven nodes, and lines of different extents (a skewed deck's corners), walked
        // forward in small steps, backward, and in jumps, at several lateral positions.
        let deck = skewed_deck();
        let forward = (0..=700).map(|i| -0.3 + 0.01 * i as f64);
        let backward = (0..=700).rev().map(|i| -0.3 + 0.01 * i as f64);
        let jumps = (0..200).map(|i| ((i * 37) % 61) as f64 * 0.1);
        let nodes = [0.0, 0.7, 2.0, 2.1, 3.5, 5.0, 5.4, 5.8];
        let positions: Vec<f64> = forward.chain(backward).chain(jumps).chain(nodes).collect();
        for y in [-2.0, -1.5, 0.0, 0.5, 1.2, 2.0, 3.0] {
            let mut walk = DeckWalk::new(&deck, y);
            for &x in &positions {
                assert_eq!(walk.stencil(x), deck.stencil(x, y), "x = {x}, y = {y}");
            }
        }
    }

    /// Uneven nodes, and lines of different extents (a skewed deck's corners).
    fn skewed_deck() -> DeckGeometry {
        DeckGeometry {
            lines: vec![
                DeckLine {
                    lateral_position: -1.5,
                    node_positions: vec![0.0, 0.7, 2.0, 2.1, 3.5, 5.0],
                    first_node: 0,
                },
                DeckLine {
                    lateral_position: 0.5,
                    node_positions: vec![0.4, 1.0, 2.5, 4.0, 5.4],
                    first_node: 6,
                },
                DeckLine {
                    lateral_position: 2.0,
                    node_positions: vec![0.8, 3.0, 5.8],
                    first_node: 11,
                },
            ],
            length: 5.8,
        }
    }

    #[test]
    fn a_reader_takes_the_element_cubic_or_the_stencil_as_the_solver_does_bit_for_bit() {
        // The route of the solver's tyres (`solver::shapes`, values and slopes) and of the
        // analysis (values): the element cubic where the lines share the element, else the
        // stencil's `evaluate_many`. On one line (y = -1.5) the cubic is taken within the
        // line's extent (the stencil beyond its end, 5.0 < x ≤ 5.8); between lines whose nodes
        // differ, the stencil. Both agree with the stencil's values to round-off (1e-15 on
        // fields of size 1); off the deck nothing. The values read with the slopes are those
        // read alone, bit for bit.
        let deck = skewed_deck();
        let count = 3;
        let nodes = deck.node_count();
        let deflection: Vec<f64> = (0..nodes * count)
            .map(|i| (0.37 * i as f64).sin())
            .collect();
        let slope: Vec<f64> = (0..nodes * count)
            .map(|i| (0.91 * i as f64).cos())
            .collect();
        let fields = (&deflection[..], &slope[..]);
        let mut routes = [0, 0];
        for y in [-2.0, -1.5, 0.0, 0.5, 1.2, 2.0] {
            let mut reader = DeckReader::new(&deck, y, count);
            let mut slope_reader = DeckReader::new(&deck, y, count);
            let mut cubic = ElementCubic::new(count);
            let weights = deck.lateral_weights(y);
            for i in 0..=640 {
                let x = -0.2 + 0.01 * i as f64;
                let mut read = [f64::NAN; 3];
                let on_deck = reader.values(fields, x, &mut read);
                let (mut read_with, mut read_slopes) = ([f64::NAN; 3], [f64::NAN; 3]);
                let on_deck_with =
                    slope_reader.values_and_slopes(fields, x, &mut read_with, &mut read_slopes);
                assert_eq!(on_deck_with, on_deck, "x {x} y {y}");
                let stencil = deck.stencil(x, y);
                assert_eq!(on_deck, !stencil.is_empty(), "x {x} y {y}");
                if !on_deck {
                    assert!(read.iter().chain(&read_with).all(|v| v.is_nan()));
                    continue;
                }
                let (mut expected, mut slopes) = ([0.0; 3], [0.0; 3]);
                if cubic.reach(&deck, &weights, fields, x) {
                    cubic.values_and_slopes(x, &mut expected, &mut slopes);
                    routes[0] += 1;
                } else {
                    stencil.evaluate_many(fields.0, fields.1, count, &mut expected, &mut slopes);
                    routes[1] += 1;
                }
                let mut plain = [0.0; 3];
                stencil.values_many(fields.0, fields.1, count, &mut plain);
                for k in 0..count {
                    assert_eq!(read[k].to_bits(), expected[k].to_bits(), "x {x} y {y}");
                    assert_eq!(read_with[k].to_bits(), expected[k].to_bits(), "x {x} y {y}");
                    assert_eq!(read_slopes[k].to_bits(), slopes[k].to_bits(), "x {x} y {y}");
                    assert!((read[k] - plain[k]).abs() <= 1e-15, "x {x} y {y} field {k}");
                }
            }
        }
        assert!(routes[0] > 100 && routes[1] > 100, "{routes:?}");
    }
}
