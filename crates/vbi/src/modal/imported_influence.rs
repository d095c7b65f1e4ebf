//! The static reference of a bridge known by its modes, from the influence lines that another
//! program gives for its stations (the exact static reference, as vbi's own FE models have it).
//!
//! Each line is given at the nodes of every deck line (the nodes of the mode shapes) and becomes
//! a [`DeckField`]: the values at the nodes as given, the slopes dw/dx by 5-point Lagrange
//! differentiation ([`node_slopes`]). A moment's influence line has a kink at its station, so
//! its slopes are taken on each side separately: `moment_left` (read for loads right of the
//! station) from the nodes at and right of the station, `moment_right` from those at and left of
//! it. The field is then exact at the nodes and, between them, a Hermite cubic on those slopes.

use crate::deck::DeckField;
use crate::fe::influence::InfluenceLines;

use super::import::{node_slopes, ImportError, ModalImport};
use super::ModalBasis;

/// Node slopes of `values` on `xs`, each side of node `split` differentiated on its own side
/// (`right_side`: the split node's slope from the nodes at and right of it).
fn split_slopes(xs: &[f64], values: &[f64], split: Option<usize>, right_side: bool) -> Vec<f64> {
    let Some(i) = split.filter(|&i| i >= 1 && i + 2 <= xs.len()) else {
        return node_slopes(xs, values);
    };
    let left = node_slopes(&xs[..=i], &values[..=i]);
    let right = node_slopes(&xs[i..], &values[i..]);
    let mut slopes: Vec<f64> = left[..i].to_vec();
    slopes.push(if right_side { right[0] } else { left[i] });
    slopes.extend_from_slice(&right[1..]);
    slopes
}

/// The influence lines of `basis`'s stations from `data.influence_lines`, or None when the data
/// give none. Errors: a station or a deck line without its line, or a line of the wrong length.
pub fn imported_influence_lines(
    data: &ModalImport,
    basis: &ModalBasis,
) -> Result<Option<InfluenceLines>, ImportError> {
    if data.influence_lines.is_empty() {
        return Ok(None);
    }
    let misfit = |message: String| ImportError::InfluenceLines { message };
    let nodes = basis.deck.node_count();
    let mut influence = InfluenceLines {
        deck: basis.deck.clone(),
        stations: basis.stations.clone(),
        deflection: Vec::new(),
        moment_left: Vec::new(),
        moment_right: Vec::new(),
        force_left: Vec::new(),
        force_right: Vec::new(),
    };
    for station in &basis.stations {
        let mut deflection = DeckField::zeros(nodes);
        let mut left = DeckField::zeros(nodes);
        let mut right = DeckField::zeros(nodes);
        for line in &basis.deck.lines {
            let y = line.lateral_position;
            let given = data
                .influence_lines
                .iter()
                .find(|l| l.station == station.name && l.lateral_position == y)
                .ok_or_else(|| {
                    misfit(format!(
                        "station `{}` has no line at y = {y} m",
                        station.name
                    ))
                })?;
            let xs = &line.node_positions;
            if given.deflection.len() != xs.len() || given.moment.len() != xs.len() {
                return Err(misfit(format!(
                    "station `{}` at y = {y} m: {} and {} values for {} nodes",
                    station.name,
                    given.deflection.len(),
                    given.moment.len(),
                    xs.len()
                )));
            }
            // The kink of the moment's line is resolved where the station sits on a node.
            let split = xs
                .iter()
                .position(|&x| (x - station.position).abs() <= 1e-9 * basis.deck.length);
            let range = line.first_node..line.first_node + xs.len();
            deflection.deflection[range.clone()].copy_from_slice(&given.deflection);
            deflection.slope[range.clone()].copy_from_slice(&node_slopes(xs, &given.deflection));
            left.deflection[range.clone()].copy_from_slice(&given.moment);
            left.slope[range.clone()].copy_from_slice(&split_slopes(
                xs,
                &given.moment,
                split,
                true,
            ));
            right.deflection[range.clone()].copy_from_slice(&given.moment);
            right.slope[range].copy_from_slice(&split_slopes(xs, &given.moment, split, false));
        }
        influence.deflection.push(deflection);
        influence.moment_left.push(left);
        influence.moment_right.push(right);
    }
    Ok(Some(influence))
}
