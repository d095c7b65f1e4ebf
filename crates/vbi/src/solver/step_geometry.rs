//! What one instant of a crossing depends on through the tyres' positions alone: the contact
//! shapes φ, φ′ ([`ContactShapes`]), the deck coupling of the tyre system (W, G, G·W and the
//! coupled matrix's LU, [`DeckCoupling`]) and the x-dependent part of the road's interpolant
//! under the tyres ([`RoadStencil`], for roads on the same sample grid).
//!
//! None of it depends on the state of the bridge and the vehicle, nor on the road's heights
//! (the road stencils depend on its sample grid alone, and are kept with it), so crossings that
//! differ only in their road (a study's roughness samples) compute it once per instant and
//! share it ([`super::batch`]). It is recomputed whenever the instant, a tyre's position or its
//! speed of travel differs, bit for bit, from those it was computed for (the road stencils also
//! when the road's sample grid differs): sharing it gives every crossing exactly the numbers it
//! computes alone.

use super::kinematics::{ContactKinematics, ContactPoints};
use super::setup::Setup;
use super::shapes::ContactShapes;
use super::tyre_system::DeckCoupling;
use crate::bits::same_bits;
use crate::modal::ModalBasis;
use crate::road::{RoadProfile, RoadStencil};

/// The position-dependent quantities of one instant, and the instant and contact positions they
/// belong to.
pub(super) struct StepGeometry<'a> {
    /// The instant i the quantities were computed for; None before the first computation.
    step: Option<usize>,
    /// The contact positions x [m] and speeds of travel ẋ [m/s] of that instant.
    positions: Vec<f64>,
    speeds: Vec<f64>,
    /// φ and φ′ of every tyre on the deck.
    pub(super) shapes: ContactShapes<'a>,
    /// The deck coupling of the tyre system.
    pub(super) coupling: DeckCoupling,
    /// The road's stencils under the tyres at the instant's positions, and the sample grid
    /// (start and spacing, as bits) of the road they were computed on; None: not computed at
    /// this instant.
    road_grid: Option<(u64, u64)>,
    road_stencils: Vec<Option<RoadStencil>>,
    /// How many times the quantities were computed (for the tests of sharing).
    #[cfg(test)]
    computations: usize,
}

impl<'a> StepGeometry<'a> {
    /// Buffers for the crossing of `setup` on `basis`; `shared`: several crossings share them
    /// (the shapes then also arranged mode by mode, [`ContactShapes::new`]).
    pub(super) fn new(basis: &'a ModalBasis, setup: &Setup, shared: bool) -> StepGeometry<'a> {
        let n = basis.mode_count();
        StepGeometry {
            step: None,
            positions: Vec::new(),
            speeds: Vec::new(),
            shapes: ContactShapes::new(basis, &setup.tyres, shared),
            coupling: DeckCoupling::new(&setup.vehicle, n),
            road_grid: None,
            road_stencils: Vec::with_capacity(setup.tyres.len()),
            #[cfg(test)]
            computations: 0,
        }
    }

    /// A placeholder without buffers (while an integrator lends out its own).
    pub(super) fn none() -> StepGeometry<'a> {
        StepGeometry {
            step: None,
            positions: Vec::new(),
            speeds: Vec::new(),
            shapes: ContactShapes::none(),
            coupling: DeckCoupling::empty(),
            road_grid: None,
            road_stencils: Vec::new(),
            #[cfg(test)]
            computations: 0,
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
        if self.step == Some(step)
            && same_bits(&self.positions, &points.position)
            && same_bits(&self.speeds, &points.travel_speed)
        {
            return;
        }
        self.shapes.evaluate(basis, &setup.tyres, points);
        self.road_grid = None;
        self.coupling.uncouple_deck();
        if step > 0 && !setup.tyres.is_empty() && self.shapes.any_on_deck() {
            self.coupling.couple_deck(
                &setup.tyres,
                &self.shapes,
                points,
                &setup.vehicle,
                &setup.modal,
                setup.newmark.gamma_dt,
            );
        }
        self.step = Some(step);
        self.positions.clone_from(&points.position);
        self.speeds.clone_from(&points.travel_speed);
        #[cfg(test)]
        {
            self.computations += 1;
        }
    }

    /// The road (r, r′) under each tyre of `points` (the positions of the last
    /// [`StepGeometry::update`]) on `road`: from the stencils of the instant when they were
    /// computed on a road with the same sample grid (another crossing of the group), else
    /// computed and kept. The same numbers either way, bit for bit.
    pub(super) fn road_under_tyres(
        &mut self,
        kinematics: &ContactKinematics,
        road: &RoadProfile,
        points: &mut ContactPoints,
    ) {
        let grid = (road.start.to_bits(), road.spacing.to_bits());
        if self.road_grid != Some(grid) {
            kinematics.road_stencils(road, points, &mut self.road_stencils);
            self.road_grid = Some(grid);
        }
        kinematics.road_under_tyres(road, &self.road_stencils, points);
    }

    /// How many times the quantities were computed (once per instant when shared as intended).
    #[cfg(test)]
    pub(super) fn computations(&self) -> usize {
        self.computations
    }
}
