//! What one instant of a crossing depends on through the tyres' positions alone: the contact
//! shapes φ, φ′ ([`ContactShapes`]) and the deck coupling of the tyre system (W, G, G·W and the
//! coupled matrix's LU, [`DeckCoupling`]).
//!
//! None of it depends on the road or on the state of the bridge and the vehicle, so crossings
//! that differ only in their road (a study's roughness samples) compute it once per instant and
//! share it ([`super::batch`]). It is recomputed whenever the instant, a tyre's position or its
//! speed of travel differs, bit for bit, from those it was computed for: sharing it gives every
//! crossing exactly the numbers it computes alone.

use super::kinematics::ContactPoints;
use super::setup::Setup;
use super::shapes::ContactShapes;
use super::tyre_system::DeckCoupling;
use crate::modal::ModalBasis;

/// The position-dependent quantities of one instant, and the instant and contact positions they
/// belong to.
pub(super) struct StepGeometry {
    /// The instant i, contact positions x [m] and speeds of travel ẋ [m/s] the quantities were
    /// computed for; None before the first computation.
    computed_for: Option<(usize, Vec<f64>, Vec<f64>)>,
    /// φ and φ′ of every tyre on the deck.
    pub(super) shapes: ContactShapes,
    /// The deck coupling of the tyre system.
    pub(super) coupling: DeckCoupling,
}

impl StepGeometry {
    /// Buffers for the crossing of `setup` on `basis`.
    pub(super) fn new(basis: &ModalBasis, setup: &Setup) -> StepGeometry {
        let n = basis.mode_count();
        StepGeometry {
            computed_for: None,
            shapes: ContactShapes::new(setup.tyres.len(), n),
            coupling: DeckCoupling::new(&setup.vehicle, n),
        }
    }

    /// A placeholder without buffers (while an integrator lends out its own).
    pub(super) fn none() -> StepGeometry {
        StepGeometry {
            computed_for: None,
            shapes: ContactShapes::new(0, 0),
            coupling: DeckCoupling::empty(),
        }
    }

    /// Brings the quantities to instant `step` with the contacts at `points`: nothing to do when
    /// they were computed for the same instant, positions and speeds (bit for bit), else the
    /// shapes and, after the first instant with a tyre on the deck, the on-deck products.
    pub(super) fn update(
        &mut self,
        basis: &ModalBasis,
        setup: &Setup,
        step: usize,
        points: &ContactPoints,
    ) {
        if self.is_computed_for(step, points) {
            return;
        }
        self.shapes.evaluate(basis, &setup.tyres, points);
        self.coupling.uncouple_deck();
        if step > 0 && !setup.tyres.is_empty() && self.shapes.any_on_deck() {
            self.coupling.couple_deck(
                &setup.tyres,
                &self.shapes,
                points,
                &setup.vehicle,
                &setup.modal.d_inv,
                setup.newmark.beta_dt2,
            );
        }
        let (positions, speeds) = match self.computed_for.take() {
            Some((_, mut positions, mut speeds)) => {
                positions.clone_from(&points.position);
                speeds.clone_from(&points.travel_speed);
                (positions, speeds)
            }
            None => (points.position.clone(), points.travel_speed.clone()),
        };
        self.computed_for = Some((step, positions, speeds));
    }

    fn is_computed_for(&self, step: usize, points: &ContactPoints) -> bool {
        let same = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
        };
        matches!(&self.computed_for, Some((i, positions, speeds))
            if *i == step
                && same(positions, &points.position)
                && same(speeds, &points.travel_speed))
    }
}
