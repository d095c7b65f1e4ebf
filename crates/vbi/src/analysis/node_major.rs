//! Influence fields copied node-major, so that one wheel's reader (the cubics of its element,
//! [`crate::deck::DeckReader`]) reads contiguous rows instead of gathering from many fields: the
//! table of the static reference (`static_reference`) and of the extremes between the time steps
//! (`continuous_extreme`).

use crate::deck::{DeckField, DeckGeometry};
use crate::influence::InfluenceLines;

/// Influence fields node-major: row j holds every field's value at node j (and the same for
/// the slopes).
pub(super) struct NodeMajorFields {
    pub(super) count: usize,
    pub(super) deflection: Vec<f64>,
    pub(super) slope: Vec<f64>,
}

impl NodeMajorFields {
    /// The deflection fields of all stations, then the left moment fields, then the right ones.
    pub(super) fn new(influence: &InfluenceLines) -> Self {
        let fields: Vec<_> = influence
            .deflection
            .iter()
            .chain(&influence.moment_left)
            .chain(&influence.moment_right)
            .collect();
        NodeMajorFields::of(&influence.deck, &fields)
    }

    /// `fields` on `deck`, in their order.
    pub(super) fn of(deck: &DeckGeometry, fields: &[&DeckField]) -> Self {
        let count = fields.len();
        let nodes = deck.node_count();
        let mut deflection = vec![0.0; nodes * count];
        let mut slope = vec![0.0; nodes * count];
        for (f, field) in fields.iter().enumerate() {
            for j in 0..nodes {
                deflection[j * count + f] = field.deflection[j];
                slope[j * count + f] = field.slope[j];
            }
        }
        NodeMajorFields {
            count,
            deflection,
            slope,
        }
    }
}
