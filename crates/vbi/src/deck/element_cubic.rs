//! Fields within one girder element as cubics in ξ: the fast route to the values (and slopes)
//! of many fields at a point that moves along the deck, checked against the stencil route of
//! [`DeckGeometry::stencil`].

#[cfg(doc)]
use super::DeckStencil;
use super::{DeckGeometry, DeckWalk};

/// The values and slopes of `count` fields (stored node-major, `deflection[node · count + k]`)
/// at a point of fixed lateral position, as cubics of the girder element it stands in.
///
/// Within one element the stencil of a point at fixed lateral position is the same cubic in
/// ξ = (x − x_a)/h on every line it reads (the lines share the element when their nodes are at
/// the same x, as on every FE deck): f(x) = c₀ + c₁ξ + c₂ξ² + c₃ξ³ and f′(x) = (c₁ + 2c₂ξ + 3c₃ξ²)/h,
/// with, summed over the lines with their lever-rule weights λ (the Hermite shape functions of
/// [`super::hermite_shape_functions`], the paper's Eq. 26, expanded in powers of ξ; w, s the
/// node deflection and slope vectors):
/// c₀ = λw_a, c₁ = λh s_a, c₂ = λ(−3w_a − 2h s_a + 3w_b − h s_b), c₃ = λ(2w_a + h s_a − 2w_b + h s_b).
/// The coefficients are built once when the point enters an element (every ~20 steps at 80 km/h
/// and 0.5 m elements); each evaluation then costs 3 multiply–adds per field for a value (5 with
/// the slope) instead of 8 (16) for the stencil of two lines × two nodes. Same values as the
/// stencil route to round-off (only the order of the operations differs). The coupled solver's
/// mode shapes at the tyres and the analysis's (the mode-acceleration correction, the static
/// reference) take this route, so that they are the same numbers bit for bit. Hand-written: no
/// crate does this.
#[derive(Debug, Clone)]
pub struct ElementCubic {
    /// Element [x_a, x_b) [m] the coefficients belong to; empty (NaN) before the first build.
    start: f64,
    end: f64,
    /// Its length h [m].
    length: f64,
    /// Number of fields.
    count: usize,
    /// c₀, c₁, c₂, c₃ one after the other, `count` each.
    coefficients: Vec<f64>,
}

impl ElementCubic {
    /// The cubics of `count` fields, not yet built for any element.
    pub fn new(count: usize) -> ElementCubic {
        ElementCubic {
            start: f64::NAN,
            end: f64::NAN,
            length: f64::NAN,
            count,
            coefficients: vec![0.0; 4 * count],
        }
    }

    /// Forgets the element the cubics were built for (the next [`ElementCubic::reach`] builds
    /// them again).
    pub fn forget(&mut self) {
        (self.start, self.end, self.length) = (f64::NAN, f64::NAN, f64::NAN);
    }

    /// Whether x [m] lies in the element the cubics were built for.
    #[inline]
    pub fn holds(&self, x: f64) -> bool {
        x >= self.start && x < self.end
    }

    /// Makes the cubics those of the element containing x [m] (built again only when x has
    /// left the element), for a point on the deck (0 ≤ x ≤ L) with lateral `weights`
    /// ([`DeckGeometry::lateral_weights`]); false where the lines it reads do not share the
    /// element, or x is beyond a line's end (then the caller takes the stencil).
    #[inline]
    pub fn reach(
        &mut self,
        deck: &DeckGeometry,
        weights: &[(usize, f64); 2],
        (deflection, slope): (&[f64], &[f64]),
        x: f64,
    ) -> bool {
        self.holds(x) || self.build(deck, weights, (deflection, slope), x)
    }

    /// The fields' values at x [m] (in the element: [`ElementCubic::reach`] was true), written
    /// to `values[k]`: the same numbers, bit for bit, as the values of
    /// [`ElementCubic::values_and_slopes`].
    #[inline]
    pub fn values(&self, x: f64, values: &mut [f64]) {
        let n = self.count;
        let xi = self.local_coordinate(x);
        let (c0, c1, c2, c3) = self.coefficients();
        for ((((v, a), b), c), d) in values[..n].iter_mut().zip(c0).zip(c1).zip(c2).zip(c3) {
            *v = a + xi * (b + xi * (c + xi * d));
        }
    }

    /// The fields' values and slopes d/dx at x [m] (in the element: [`ElementCubic::reach`] was
    /// true), written to `values[k]` and `slopes[k]`.
    #[inline]
    pub fn values_and_slopes(&self, x: f64, values: &mut [f64], slopes: &mut [f64]) {
        let n = self.count;
        let xi = self.local_coordinate(x);
        let (c0, c1, c2, c3) = self.coefficients();
        let (two_xi, three_xi2, inv_h) = (2.0 * xi, 3.0 * xi * xi, 1.0 / self.length);
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
    }

    /// ξ = (x − x_a)/h, held to [0, 1].
    #[inline]
    fn local_coordinate(&self, x: f64) -> f64 {
        ((x - self.start) / self.length).clamp(0.0, 1.0)
    }

    /// c₀, c₁, c₂, c₃.
    #[inline]
    fn coefficients(&self) -> (&[f64], &[f64], &[f64], &[f64]) {
        let n = self.count;
        let (c0, rest) = self.coefficients.split_at(n);
        let (c1, rest) = rest.split_at(n);
        let (c2, c3) = rest.split_at(n);
        (c0, c1, c2, c3)
    }

    /// Builds the coefficients of the element containing x; false if the lines disagree.
    fn build(
        &mut self,
        deck: &DeckGeometry,
        weights: &[(usize, f64); 2],
        (deflection, slope): (&[f64], &[f64]),
        x: f64,
    ) -> bool {
        let Some(ElementNodes {
            interval: (start, end),
            nodes,
            used,
        }) = element_nodes(deck, weights, x)
        else {
            return false;
        };
        let n = self.count;
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

/// The element that the lines with a non-zero lateral weight read at a point.
struct ElementNodes {
    /// [x_a, x_b) [m].
    interval: (f64, f64),
    /// Each line's first node of the element, with the line's weight (`used` of them).
    nodes: [(usize, f64); 2],
    used: usize,
}

/// The element containing x that every line with a non-zero weight reads; None if the lines
/// disagree or x is beyond a line's ends (where the stencil holds the end value: not a cubic
/// of an element).
fn element_nodes(deck: &DeckGeometry, weights: &[(usize, f64); 2], x: f64) -> Option<ElementNodes> {
    let mut interval: Option<(f64, f64)> = None;
    let mut nodes = [(0usize, 0.0f64); 2];
    let mut used = 0;
    for &(line_index, weight) in weights {
        if weight == 0.0 {
            continue;
        }
        let line = &deck.lines[line_index];
        let xs = &line.node_positions;
        if x < xs[0] || x > xs[xs.len() - 1] {
            return None;
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
            Some(other) if other != here => return None,
            Some(_) => {}
        }
        nodes[used] = (line.first_node + e, weight);
        used += 1;
    }
    Some(ElementNodes {
        interval: interval?,
        nodes,
        used,
    })
}

/// A point at a fixed lateral position moving along the deck that reads `count` fields stored
/// node-major at each of its positions: through the cubics of the element it stands in
/// ([`ElementCubic`], built again when it enters the next), or through the stencil (its walk,
/// [`DeckStencil::evaluate_many`]) where the lines it reads do not share the element. This is
/// the route of the coupled solver's mode values at its tyres, so a reader of the mode shapes
/// gives the solver's numbers bit for bit.
pub struct DeckReader<'a> {
    /// The deck the point moves along.
    deck: &'a DeckGeometry,
    /// The point's lateral weights ([`DeckGeometry::lateral_weights`]).
    weights: [(usize, f64); 2],
    /// Its walk, for the stencil where the cubic does not apply.
    walk: DeckWalk<'a>,
    /// The cubics of its element.
    cubic: ElementCubic,
    /// The stencil's slopes (not read).
    slopes: Vec<f64>,
}

impl<'a> DeckReader<'a> {
    /// A reader of `count` fields at lateral position y [m].
    pub fn new(deck: &'a DeckGeometry, y: f64, count: usize) -> Self {
        DeckReader {
            deck,
            weights: deck.lateral_weights(y),
            walk: DeckWalk::new(deck, y),
            cubic: ElementCubic::new(count),
            slopes: vec![0.0; count],
        }
    }

    /// The values of the fields `(deflection, slope)` (node-major, the reader's `count` of
    /// them: the same fields at every call until [`DeckReader::forget`]) at x [m], written to
    /// `values`; false, and nothing written, where the point is off the deck
    /// ([`DeckGeometry::carries`]).
    #[inline]
    pub fn values(&mut self, fields: (&[f64], &[f64]), x: f64, values: &mut [f64]) -> bool {
        if !self.deck.carries(&self.weights, x) {
            return false;
        }
        if self.cubic.reach(self.deck, &self.weights, fields, x) {
            self.cubic.values(x, values);
        } else {
            let count = self.slopes.len();
            let stencil = self.walk.stencil(x);
            stencil.evaluate_many(fields.0, fields.1, count, values, &mut self.slopes);
        }
        true
    }

    /// [`DeckReader::values`] with the fields' slopes d/dx at x [1/m × the fields' unit],
    /// written to `slopes`: the values the same numbers, bit for bit.
    #[inline]
    pub fn values_and_slopes(
        &mut self,
        fields: (&[f64], &[f64]),
        x: f64,
        values: &mut [f64],
        slopes: &mut [f64],
    ) -> bool {
        if !self.deck.carries(&self.weights, x) {
            return false;
        }
        if self.cubic.reach(self.deck, &self.weights, fields, x) {
            self.cubic.values_and_slopes(x, values, slopes);
        } else {
            let stencil = self.walk.stencil(x);
            stencil.evaluate_many(fields.0, fields.1, self.slopes.len(), values, slopes);
        }
        true
    }

    /// Forgets the element's cubics: the next fields read are others.
    pub fn forget(&mut self) {
        self.cubic.forget();
    }
}
