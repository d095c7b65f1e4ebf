//! A [`StaticLifetime`] from a bridge: its FE model's influence lines ([`crate::fe::statics`]),
//! tabulated along each lane ([`super::from_influence`]) for every station and quantity. No
//! modal analysis: the static analysis needs none.

use super::from_influence::{knot_positions, station_effect_line};
use super::{LifetimeEffect, LifetimeLane, StaticLifetime};
use crate::crossing::{BridgeSpec, PipelineError};
use crate::fe::statics::influence_lines;
use crate::fe::{discretise, Quantity};

/// Points per element at which the FE influence lines are tabulated by default: a beam's moment
/// and shear lines exactly, its deflection line within h²/128 × its curvature (h: the element's
/// length; [`super::from_influence`]).
pub const DEFAULT_POINTS_PER_ELEMENT: usize = 4;

/// The static lifetime analysis of `bridge` (its model and mesh, with its stations) under
/// traffic in `lanes`, block maxima over blocks of `block_seconds` [s], the influence lines
/// tabulated at `points_per_element` points per element. Every station's quantities among
/// `quantities` are tracked (of deflection, bending moment, and the shear force or support
/// reaction, which a station has).
pub fn prepare_static(
    bridge: &BridgeSpec,
    lanes: Vec<LifetimeLane>,
    block_seconds: f64,
    points_per_element: usize,
    quantities: &[Quantity],
) -> Result<StaticLifetime, PipelineError> {
    let fe = discretise(&bridge.model, &bridge.mesh).map_err(PipelineError::Discretise)?;
    let influence = influence_lines(&fe).map_err(PipelineError::Influence)?;
    let knots = knot_positions(&influence.deck, points_per_element);
    let mut effects = Vec::new();
    for (s, station) in influence.stations.iter().enumerate() {
        for quantity in station.quantities() {
            if !quantities.contains(&quantity) {
                continue;
            }
            let mut lines = Vec::with_capacity(lanes.len());
            for lane in &lanes {
                match station_effect_line(&influence, s, quantity, lane.lateral_position, &knots) {
                    Some(Ok(line)) => lines.push(line),
                    // The knots are finite and increasing by construction; a field that is not
                    // finite would be a failed static solve, which is reported before.
                    Some(Err(_)) | None => break,
                }
            }
            if lines.len() == lanes.len() {
                effects.push(LifetimeEffect::new(station.name.clone(), quantity, lines));
            }
        }
    }
    Ok(StaticLifetime {
        deck_length: influence.deck.length,
        lanes,
        effects,
        block_seconds,
        record_end: None,
        blocks: super::BlockRange::ALL,
    })
}
