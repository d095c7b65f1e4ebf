//! Per-tyre cache of the mode values and slopes within one girder element (the contact shapes'
//! fast path), checked against the stencil route of [`DeckGeometry::stencil`].

use crate::deck::DeckGeometry;

/// The mode values and slopes of all n modes at a tyre, cached per girder element.
///
/// Within one element the stencil of a tyre at fixed lateral position is the same cubic in
/// ξ = (x − x_a)/h on every line it reads (the lines share the element when their nodes are at
/// the same x, as on every FE deck): φ(x) = c₀ + c₁ξ + c₂ξ² + c₃ξ³ and φ′(x) = (c₁ + 2c₂ξ + 3c₃ξ²)/h,
/// with, summed over the lines with their lever-rule weights λ (Hermite shape functions of
/// [`crate::deck::hermite_shape_functions`] expanded in powers of ξ; w, s the node deflection and
/// slope vectors):
/// c₀ = λw_a, c₁ = λh s_a, c₂ = λ(−3w_a − 2h s_a + 3w_b − h s_b), c₃ = λ(2w_a + h s_a − 2w_b + h s_b).
/// The coefficients are built once when the tyre enters an element (every ~20 steps at 80 km/h
/// and 0.5 m elements); each step then costs 5n multiply–adds instead of 16n for the stencil of
/// two lines × two nodes. Same values as the stencil route to round-off (only the order of the
/// operations differs). Hand-written: no crate does this.
pub(super) struct ElementCache {
    /// Element [x_a, x_b) the coefficients belong to; empty (NaN) before the first use.
    start: f64,
    end: f64,
    length: f64,
    /// c₀, c₁, c₂, c₃ one after the other, n each.
    coefficients: Vec<f64>,
}

impl ElementCache {
    pub(super) fn new(n: usize) -> ElementCache {
        ElementCache {
            start: f64::NAN,
            end: f64::NAN,
            length: f64::NAN,
            coefficients: vec![0.0; 4 * n],
        }
    }

    /// Fills `values` and `slopes` at x (on the deck); false when the lines the tyre reads do
    /// not share the element (then the caller uses the stencil).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    pub(super) fn evaluate(
        &mut self,
        deck: &DeckGeometry,
        weights: &[(usize, f64); 2],
        deflection: &[f64],
        slope: &[f64],
        n: usize,
        x: f64,
        values: &mut [f64],
        slopes: &mut [f64],
    ) -> bool {
        let inside = x >= self.start && x < self.end;
        if !(inside || self.rebuild(deck, weights, deflection, slope, n, x)) {
            return false;
        }
        let h = self.length;
        let xi = ((x - self.start) / h).clamp(0.0, 1.0);
        let (c0, rest) = self.coefficients.split_at(n);
        let (c1, rest) = rest.split_at(n);
        let (c2, c3) = rest.split_at(n);
        let (two_xi, three_xi2, inv_h) = (2.0 * xi, 3.0 * xi * xi, 1.0 / h);
        for (((((v, sl), a), b), c), d) in values[..n]
            .iter_mut()
            .zip(slopes[..n].iter_mut())
            .zip(c0)
            .zip(c1)
            .zip(c2)
            .zip(c3)
        {
            *v = a + xi * (b + xi * (c + xi * d));
            *sl = (b + two_xi * c + three_xi2 * d) * inv_h;
        }
        true
    }

    /// Builds the coefficients of the element containing x; false if the lines disagree.
    fn rebuild(
        &mut self,
        deck: &DeckGeometry,
        weights: &[(usize, f64); 2],
        deflection: &[f64],
        slope: &[f64],
        n: usize,
        x: f64,
    ) -> bool {
        let mut interval: Option<(f64, f64)> = None;
        let mut nodes = [(0usize, 0.0f64); 2];
        let mut used = 0;
        for &(line_index, weight) in weights {
            if weight == 0.0 {
                continue;
            }
            let line = &deck.lines[line_index];
            let xs = &line.node_positions;
            // Beyond a line's ends the stencil holds the end value: not a cubic of an element.
            if x < xs[0] || x > xs[xs.len() - 1] {
                return false;
            }
            // The element choice of `DeckGeometry::stencil`.
            let e = match xs.partition_point(|&p| p <= x) {
                0 => 0,
                i if i >= xs.len() => xs.len() - 2,
                i => i - 1,
            };
            let here = (xs[e], xs[e + 1]);
            match interval {
                None => interval = Some(here),
                Some(other) if other != here => return false,
                Some(_) => {}
            }
            nodes[used] = (line.first_node + e, weight);
            used += 1;
        }
        let Some((start, end)) = interval else {
            return false;
        };
        let h = end - start;
        self.coefficients.fill(0.0);
        let (c0, rest) = self.coefficients.split_at_mut(n);
        let (c1, rest) = rest.split_at_mut(n);
        let (c2, c3) = rest.split_at_mut(n);
        for &(a, weight) in &nodes[..used] {
            let b = a + 1;
            let (wa, sa) = (&deflection[a * n..(a + 1) * n], &slope[a * n..(a + 1) * n]);
            let (wb, sb) = (&deflection[b * n..(b + 1) * n], &slope[b * n..(b + 1) * n]);
            for k in 0..n {
                let (hsa, hsb) = (h * sa[k], h * sb[k]);
                c0[k] += weight * wa[k];
                c1[k] += weight * hsa;
                c2[k] += weight * (-3.0 * wa[k] - 2.0 * hsa + 3.0 * wb[k] - hsb);
                c3[k] += weight * (2.0 * wa[k] + hsa - 2.0 * wb[k] + hsb);
            }
        }
        self.start = start;
        // The last element also holds x = end (as in the stencil); others are half-open.
        self.end = if end >= deck.length {
            f64::INFINITY
        } else {
            end
        };
        self.length = h;
        true
    }
}
