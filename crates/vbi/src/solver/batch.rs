//! Crossings integrated together, instant by instant, sharing what depends on the tyres'
//! positions alone.
//!
//! The road samples of a study's bridge × vehicle × speed differ only in their road: at every
//! instant their tyres stand at the same positions, so the contact shapes φ, φ′, the on-deck
//! products W, G, G·W and the LU of the coupled matrix (the `StepGeometry`) are the same for all
//! of them while their contact sets agree. [`simulate_batch`] steps such crossings in lockstep
//! and computes those once per instant (about a quarter of a crossing's cost at 50 modes and 10
//! tyres). Each crossing still computes its own road, loads, right-hand sides and corrector, in
//! the same order as alone: a crossing of a batch gives exactly the history of
//! [`simulate`](super::simulate), bit for bit. A crossing whose tyre leaves the road uses its own
//! LU for that contact set; crossings that cannot share (other vehicles, time step or length)
//! run in their own groups.

use super::integrator::Integrator;
use super::step_geometry::StepGeometry;
use super::{Crossing, Recording, ResponseHistory, SolverError, SolverOptions};
use crate::modal::ModalBasis;

/// The histories of `crossings` on `basis`, each exactly that of
/// [`simulate`](super::simulate)`(basis, crossing, options)` (less what `recording` leaves out), in
/// the same order; the crossings
/// that share their vehicles, motion and time grid are integrated together (see the module
/// documentation). Memory: every crossing's history at once ([`LockstepBatch`] lets a caller
/// read each instant instead).
pub fn simulate_batch(
    basis: &ModalBasis,
    crossings: &[Crossing],
    options: &SolverOptions,
    recording: Recording,
) -> Vec<Result<ResponseHistory, SolverError>> {
    let mut batch = LockstepBatch::new(basis, crossings, options, recording);
    while batch.step() {}
    batch.finish()
}

/// Crossings stepped together, one instant at a time (see the module documentation): set up,
/// [`LockstepBatch::step`], the state of each crossing read from its [`Integrator`] between
/// steps, and [`LockstepBatch::finish`] for the histories. Every crossing's numbers are those
/// of [`simulate`](super::simulate), bit for bit.
///
/// The crossings start together at t = 0 and advance together, one Δt per step, so that at any
/// time every running crossing is at the same instant; a crossing with fewer instants
/// finishes first, and one whose step fails leaves the batch with its error.
pub struct LockstepBatch<'a> {
    slots: Vec<Slot<'a>>,
    /// The running crossings that share their geometry, and their shared geometry.
    groups: Vec<(Vec<usize>, StepGeometry<'a>)>,
}

impl<'a> LockstepBatch<'a> {
    /// Sets up every crossing ([`Integrator::recording`]) and computes its first instant;
    /// a crossing whose set-up fails holds its error.
    pub fn new(
        basis: &'a ModalBasis,
        crossings: &'a [Crossing],
        options: &SolverOptions,
        recording: Recording,
    ) -> LockstepBatch<'a> {
        let slots: Vec<Slot> = crossings
            .iter()
            .map(
                |crossing| match Integrator::recording(basis, crossing, options, recording) {
                    Ok(integrator) => Slot::Running(Box::new(integrator)),
                    Err(error) => Slot::Failed(error),
                },
            )
            .collect();
        let groups = sharing_groups(&slots)
            .into_iter()
            .map(|group| {
                let geometry = match &slots[group[0]] {
                    Slot::Running(first) => first.new_step_geometry(group.len() > 1),
                    Slot::Failed(_) => unreachable!("a group holds running crossings"),
                };
                (group, geometry)
            })
            .collect();
        LockstepBatch { slots, groups }
    }

    /// Number of crossings.
    pub fn len(&self) -> usize {
        self.slots.len()
    }

    /// Whether the batch has no crossing.
    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// Advances every crossing that is neither finished nor failed by one time step; whether
    /// any did (false: the batch is at its end).
    pub fn step(&mut self) -> bool {
        let mut stepped = false;
        for (group, geometry) in &mut self.groups {
            for &i in group.iter() {
                let Slot::Running(integrator) = &mut self.slots[i] else {
                    continue;
                };
                if integrator.is_finished() {
                    continue;
                }
                stepped = true;
                if let Err(error) = integrator.step_sharing(geometry) {
                    self.slots[i] = Slot::Failed(error);
                }
            }
        }
        stepped
    }

    /// Crossing `i` at its current instant, unless it has failed.
    ///
    /// # Panics
    /// If `i` is not a crossing of the batch.
    pub fn integrator(&self, i: usize) -> Option<&Integrator<'a>> {
        match &self.slots[i] {
            Slot::Running(integrator) => Some(integrator),
            Slot::Failed(_) => None,
        }
    }

    /// The history of every crossing ([`Integrator::finish`]), or its error, in order.
    pub fn finish(self) -> Vec<Result<ResponseHistory, SolverError>> {
        self.slots
            .into_iter()
            .map(|slot| match slot {
                Slot::Running(integrator) => integrator.finish(),
                Slot::Failed(error) => Err(error),
            })
            .collect()
    }
}

/// One crossing of a batch: integrating, or failed.
enum Slot<'a> {
    Running(Box<Integrator<'a>>),
    Failed(SolverError),
}

/// The running crossings grouped by [`Integrator::can_share_geometry_with`] (each group in the
/// order of the batch).
fn sharing_groups(slots: &[Slot]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for (i, slot) in slots.iter().enumerate() {
        let Slot::Running(integrator) = slot else {
            continue;
        };
        let fits = |group: &Vec<usize>| match &slots[group[0]] {
            Slot::Running(first) => first.can_share_geometry_with(integrator),
            Slot::Failed(_) => false,
        };
        match groups.iter_mut().find(|group| fits(group)) {
            Some(group) => group.push(i),
            None => groups.push(vec![i]),
        }
    }
    groups
}
