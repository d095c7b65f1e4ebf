//! The [`EffectLine`]s of a bridge's stations along a lane, tabulated from its FE influence
//! lines ([`InfluenceLines`]).
//!
//! The FE lines are cubic (Hermite) between deck nodes. They are tabulated at every node of
//! the deck lines and at `points_per_element − 1` equally spaced points inside each element,
//! with both one-sided limits at each knot (a shear force jumps by the load at its section, an
//! end reaction at its bearing). A moment or shear line of a beam is linear between nodes, and
//! its tabulation is exact; a deflection line (cubic) is approximated within h²/8 × its
//! curvature, h the spacing of the knots (the interpolation error of a linear interpolant).
//! Knots on the chord of their neighbours are then dropped ([`EffectLine::simplified`]): a
//! moment line keeps its kinks only, and the extreme costs that many evaluations.

use super::{EffectLine, EffectLineError};
use crate::deck::DeckGeometry;
use crate::fe::Quantity;
use crate::influence::InfluenceLines;

/// Knot positions along the deck [m]: every node of every deck line (merged within 1 µm) and
/// `points_per_element − 1` points inside each interval between merged nodes.
pub fn knot_positions(deck: &DeckGeometry, points_per_element: usize) -> Vec<f64> {
    let mut nodes: Vec<f64> = deck
        .lines
        .iter()
        .flat_map(|line| line.node_positions.iter().copied())
        .filter(|x| (0.0..=deck.length).contains(x))
        .collect();
    nodes.push(0.0);
    nodes.push(deck.length);
    nodes.sort_by(f64::total_cmp);
    nodes.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    let per = points_per_element.max(1);
    let mut knots = Vec::with_capacity(nodes.len() * per);
    for pair in nodes.windows(2) {
        for i in 0..per {
            knots.push(pair[0] + (pair[1] - pair[0]) * i as f64 / per as f64);
        }
    }
    knots.push(deck.length);
    knots
}

/// Station `station`'s `quantity` along the lane at lateral position `y` [m], per newton of a
/// downward load, tabulated at `knots` ([`knot_positions`]). None where the station has no
/// such quantity.
pub fn station_effect_line(
    influence: &InfluenceLines,
    station: usize,
    quantity: Quantity,
    y: f64,
    knots: &[f64],
) -> Option<Result<EffectLine, EffectLineError>> {
    if !influence.has_quantity(station, quantity) {
        return None;
    }
    let position = influence.stations[station].position;
    let n = knots.len();
    let mut before = Vec::with_capacity(n);
    let mut after = Vec::with_capacity(n);
    for (k, &x) in knots.iter().enumerate() {
        let stencil = influence.deck.stencil(x, y);
        let value = |left_element: bool| {
            influence
                .field_of_element(station, quantity, left_element)
                .map_or(0.0, |field| stencil.evaluate(field).0)
        };
        // A load just below x reads the left element when it is right of the station.
        before.push(if k == 0 { 0.0 } else { value(x > position) });
        after.push(if k == n - 1 {
            0.0
        } else {
            value(x >= position)
        });
    }
    Some(
        EffectLine::with_jumps(knots.to_vec(), before, after)
            .map(|line| line.simplified(SIMPLIFY_TOLERANCE)),
    )
}

/// Relative tolerance under which a tabulated knot on the chord of its neighbours is dropped
/// ([`EffectLine::simplified`]): 10⁻¹⁰ of the line's largest ordinate, a hundred times the
/// static solve's round-off (the FE lines' ordinates agree with closed forms to about 10⁻¹²),
/// so that only true kinks and jumps stay.
pub const SIMPLIFY_TOLERANCE: f64 = 1e-10;
