//! Static influence lines: the exact static response at a station to a unit load anywhere on the
//! deck. They give the static reference of the DAF (the response to the vehicle's static wheel
//! loads at every position along its path).
//!
//! Each influence line is a [`DeckField`], so a load at (x, y) is evaluated with the same
//! [`DeckStencil`](crate::deck::DeckStencil) that couples a wheel to the modes. The bending moment
//! has two lines per station: read from the element left of the station (exact for loads right of
//! it) and from the element right of it (exact for loads left of it); so has the shear force.
//! The support reaction at a station over a support has one line, continuous in the load's
//! position, with the value 1 at the bearing.
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
    /// The station's force quantity ([`Station::quantities`]) [N per N]: the shear force read
    /// from the element left of the station (exact for loads right of it), or at a support the
    /// support reaction (the same field on both sides: a reaction is continuous in the load's
    /// position). Empty when the influence lines were made without forces.
    pub force_left: Vec<DeckField>,
    /// The shear force read from the element right of the station (exact for loads left of
    /// it), or the support reaction.
    pub force_right: Vec<DeckField>,
}

impl InfluenceLines {
    /// Whether station `s` has an influence line of `quantity`.
    pub fn has_quantity(&self, s: usize, quantity: Quantity) -> bool {
        match quantity {
            Quantity::Deflection | Quantity::BendingMoment => true,
            Quantity::ShearForce | Quantity::SupportReaction => {
                self.force_left.len() == self.stations.len()
                    && self.stations[s].quantities()[2] == quantity
            }
        }
    }

    /// Whether a load at longitudinal position `x` [m] reads station `s`'s moment and shear
    /// lines from the element left of the station (`moment_left`, `force_left`):
    /// [`Station::reads_left_element`].
    #[inline]
    pub fn reads_left_element(&self, s: usize, x: f64) -> bool {
        self.stations[s].reads_left_element(x)
    }

    /// The field that gives station `s`'s `quantity` exactly for a load at longitudinal
    /// position `x` [m]: for the moment and the shear, the element on the side of the station
    /// away from the load ([`InfluenceLines::reads_left_element`]). None where the station has
    /// no such quantity.
    pub fn field(&self, s: usize, quantity: Quantity, x: f64) -> Option<&DeckField> {
        self.field_of_element(s, quantity, self.reads_left_element(s, x))
    }

    /// Station `s`'s field of `quantity` read from the element left of the station
    /// (`left_element`, exact for loads right of it) or right of it: [`InfluenceLines::field`]
    /// for a side chosen by the caller (a one-sided limit at a knot). None where the station has
    /// no such quantity.
    pub fn field_of_element(
        &self,
        s: usize,
        quantity: Quantity,
        left_element: bool,
    ) -> Option<&DeckField> {
        match quantity {
            Quantity::Deflection => Some(&self.deflection[s]),
            Quantity::BendingMoment if left_element => Some(&self.moment_left[s]),
            Quantity::BendingMoment => Some(&self.moment_right[s]),
            _ if !self.has_quantity(s, quantity) => None,
            _ if left_element => Some(&self.force_left[s]),
            _ => Some(&self.force_right[s]),
        }
    }

    /// Response of station `s` to a unit downward load at (x, y) [m]; zero off the deck or
    /// where the station has no such quantity.
    pub fn unit_load_response(&self, s: usize, quantity: Quantity, x: f64, y: f64) -> f64 {
        let stencil = self.deck.stencil(x, y);
        self.field(s, quantity, x)
            .map_or(0.0, |field| stencil.evaluate(field).0)
    }
}
