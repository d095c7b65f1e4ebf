//! What the wheels of a run read from the deck at an instant: the mode values φₖ(x_w, y_w) and
//! the influence lines' values IL(x_w, y_w) of the run's targets, which the mode-acceleration
//! correction ([`super::static_correction`]) needs at every contact and instant.
//!
//! Each contact keeps the cubics of the girder element it stands in ([`ElementCubic`]), built
//! again when it enters the next: the same route, and so the same numbers bit for bit, as the
//! coupled solver's mode values at its tyres (`solver::shapes`), at 3 multiply–adds per mode
//! instead of the stencil's 8. Where the lines a contact reads do not share the element (or it
//! is beyond a line's end) the stencil is taken, as the solver does.

use crate::deck::{DeckField, DeckGeometry, DeckReader};
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::ContactPath;

/// The deck fields at the contacts of runs that share their paths.
pub(super) struct WheelFields<'a> {
    basis: &'a ModalBasis,
    influence: &'a InfluenceLines,
    contacts: Vec<ContactFields<'a>>,
    /// The (station, quantity) targets read, each once ([`WheelFields::slots`]).
    targets: Vec<(usize, Quantity)>,
    /// φₖ at the contact last read [-, the modes' normalisation].
    shape: Vec<f64>,
    /// IL of each target at the contact last read (None: the station has no such line) [m, N·m
    /// or N per N of load].
    lines: Vec<Option<f64>>,
}

/// One contact's readers of the deck fields.
struct ContactFields<'a> {
    /// The mode shapes, on the modes' deck.
    modes: DeckReader<'a>,
    /// Each target's influence line, on the lines' deck.
    lines: Vec<LineReader<'a>>,
    /// The contact's lateral position [m].
    lateral_position: f64,
}

impl<'a> WheelFields<'a> {
    /// The fields at `contacts` (their lateral positions), no target read yet.
    pub(super) fn new(
        basis: &'a ModalBasis,
        influence: &'a InfluenceLines,
        contacts: &[ContactPath],
    ) -> Self {
        let n = basis.mode_count();
        let contact = |y: f64| ContactFields {
            modes: DeckReader::new(&basis.deck, y, n),
            lines: Vec::new(),
            lateral_position: y,
        };
        WheelFields {
            basis,
            influence,
            contacts: contacts
                .iter()
                .map(|c| contact(c.lateral_position))
                .collect(),
            targets: Vec::new(),
            shape: vec![0.0; n],
            lines: Vec::new(),
        }
    }

    /// Where each of `targets` is read in [`WheelFields::read`]'s lines (a target not read
    /// before is added).
    pub(super) fn slots(&mut self, targets: &[(usize, Quantity)]) -> Vec<usize> {
        let slot = |fields: &mut Self, target: &(usize, Quantity)| {
            if let Some(slot) = fields.targets.iter().position(|t| t == target) {
                return slot;
            }
            fields.targets.push(*target);
            fields.lines.push(None);
            let deck = &fields.influence.deck;
            for contact in &mut fields.contacts {
                contact
                    .lines
                    .push(LineReader::new(deck, contact.lateral_position));
            }
            fields.targets.len() - 1
        };
        targets.iter().map(|target| slot(self, target)).collect()
    }

    /// φₖ of every mode and IL of every target at contact `w` at x [m]; None where the contact
    /// is off the deck (beyond its ends, or where no girder line carries it).
    pub(super) fn read(&mut self, w: usize, x: f64) -> Option<(&[f64], &[Option<f64>])> {
        let (basis, influence) = (self.basis, self.influence);
        let contact = &mut self.contacts[w];
        let modes = (&basis.deck_deflection[..], &basis.deck_slope[..]);
        if !contact.modes.values(modes, x, &mut self.shape) {
            return None;
        }
        for ((value, &(s, quantity)), line) in (self.lines.iter_mut())
            .zip(&self.targets)
            .zip(&mut contact.lines)
        {
            let field = influence.field(s, quantity, x);
            *value = field.map(|field| line.value(field, x).unwrap_or(0.0));
        }
        Some((&self.shape, &self.lines))
    }
}

/// A reader of one station's influence line of one quantity at a contact: a moment or shear
/// line changes field where the contact passes the station, and its cubic is then built again.
struct LineReader<'a> {
    /// The field the reader's cubic was built for.
    field: Option<&'a DeckField>,
    /// Its reader of that one field.
    reader: DeckReader<'a>,
}

impl<'a> LineReader<'a> {
    /// A reader on `deck` at lateral position y [m].
    fn new(deck: &'a DeckGeometry, y: f64) -> Self {
        LineReader {
            field: None,
            reader: DeckReader::new(deck, y, 1),
        }
    }

    /// IL(x) of `field` at x [m] [the field's unit per N of load]; None off the lines' deck.
    fn value(&mut self, field: &'a DeckField, x: f64) -> Option<f64> {
        if !self.field.is_some_and(|built| std::ptr::eq(built, field)) {
            self.field = Some(field);
            self.reader.forget();
        }
        let mut value = [0.0];
        let on_deck = self
            .reader
            .values((&field.deflection, &field.slope), x, &mut value);
        on_deck.then_some(value[0])
    }
}
