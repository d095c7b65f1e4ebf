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
use super::{Crossing, HistoryBuffers, Recording, ResponseHistory, SolverError, SolverOptions};
use crate::modal::ModalBasis;

/// The histories of `crossings` on `basis`, each exactly that of
/// [`simulate`](super::simulate)`(basis, crossing, options)` (less what `recording` leaves out), in
/// the same order; the crossings
/// that share their vehicles, motion and time grid are integrated together (see the module
/// documentation). Memory: every crossing's history at once.
pub fn simulate_batch(
    basis: &ModalBasis,
    crossings: &[Crossing],
    options: &SolverOptions,
    recording: Recording,
) -> Vec<Result<ResponseHistory, SolverError>> {
    let buffers = &mut HistoryBuffers::new();
    simulate_batch_into(basis, crossings, options, (recording, buffers))
}

/// [`simulate_batch`], the histories recorded into tables taken from `buffers` (the same
/// histories bit for bit).
pub fn simulate_batch_into(
    basis: &ModalBasis,
    crossings: &[Crossing],
    options: &SolverOptions,
    (recording, buffers): (Recording, &mut HistoryBuffers),
) -> Vec<Result<ResponseHistory, SolverError>> {
    let mut slots: Vec<Slot> = crossings
        .iter()
        .map(|crossing| {
            let recording = (recording, &mut *buffers);
            match Integrator::recording_into(basis, crossing, options, recording) {
                Ok(integrator) => Slot::Running(Box::new(integrator)),
                Err(error) => Slot::Failed(error),
            }
        })
        .collect();
    for group in sharing_groups(&slots) {
        run_in_lockstep(&mut slots, &group);
    }
    slots
        .into_iter()
        .map(|slot| match slot {
            Slot::Running(integrator) => integrator.finish(),
            Slot::Failed(error) => Err(error),
        })
        .collect()
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

/// Steps the crossings of `group` together to their end, one shared `StepGeometry` for all;
/// a crossing whose step fails leaves the group with its error.
fn run_in_lockstep(slots: &mut [Slot], group: &[usize]) {
    let Some(Slot::Running(first)) = group.first().map(|&i| &slots[i]) else {
        return;
    };
    let mut geometry = first.new_step_geometry();
    loop {
        let mut stepped = false;
        for &i in group {
            let Slot::Running(integrator) = &mut slots[i] else {
                continue;
            };
            if integrator.is_finished() {
                continue;
            }
            stepped = true;
            if let Err(error) = integrator.step_sharing(&mut geometry) {
                slots[i] = Slot::Failed(error);
            }
        }
        if !stepped {
            return;
        }
    }
}
