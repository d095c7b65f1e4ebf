//! Static influence lines: the exact static response at a station to a unit load anywhere on the
//! deck. They give the static reference of the DAF (the response to the vehicle's static wheel
//! loads at every position along its path).
//!
//! Each influence line is a [`DeckField`], so a load at (x, y) is evaluated with the same
//! [`DeckStencil`](crate::deck::DeckStencil) that couples a wheel to the modes. The bending moment
//! has two lines per station: read from the element left of the station (exact for loads right of
//! it) and from the element right of it (exact for loads left of it).
//!
//! Computed by [`super::statics`] from the full stiffness; the DAF analysis and the solver read
//! them (re-exported by the top-level `influence` module, their older path).

use crate::deck::{DeckField, DeckGeometry};

use super::{Quantity, Station};

/// Influence lines of every station, for a unit downward load [N].
#[derive(Debug, Clone, PartialEq)]
pub struct InfluenceLines {
    /// The deck the fields live on.
    pub deck: DeckGeometry,
    /// Stations, in the order of the fields below.
    pub stations: Vec<Station>,
    /// Deflection [m per N] (upwards positive, so mostly negative), one field per station.
    pub deflection: Vec<DeckField>,
    /// Sagging moment [N·m per N] read from the element left of the station.
    pub moment_left: Vec<DeckField>,
    /// Sagging moment [N·m per N] read from the element right of the station.
    pub moment_right: Vec<DeckField>,
}

impl InfluenceLines {
    /// Response of station `s` to a unit downward load at (x, y) [m]; zero off the deck.
    pub fn unit_load_response(&self, s: usize, quantity: Quantity, x: f64, y: f64) -> f64 {
        let stencil = self.deck.stencil(x, y);
        let field = match quantity {
            Quantity::Deflection => &self.deflection[s],
            Quantity::BendingMoment if x >= self.stations[s].position => &self.moment_left[s],
            Quantity::BendingMoment => &self.moment_right[s],
        };
        stencil.evaluate(field).0
    }
}
